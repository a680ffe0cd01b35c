//! The one error answer of the API: HTTP 400 (or 413/408 from the limit layers, 503/504 from
//! the pool) with the library's message and the request field that caused it, so that the
//! editor can show the message next to the control that set the field.
//!
//! The field of a library error comes from its typed parts, never from its message: the
//! variant, and the argument key of the variants that carry one (`what`), looked up exactly in
//! [`KEY_FIELDS`], the one table from the library's keys to the request's fields (as the CLI's
//! table from the keys to its options).

use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use lekalo_io::IoError;
use serde_json::json;

/// An error answer: `{"error": message, "field": "curve.knots"}` (field `null` when unknown).
#[derive(Debug, Clone, PartialEq)]
pub struct ApiError {
    /// HTTP status (400 for bad input).
    pub status: StatusCode,
    /// The message, worded as the CLI words it.
    pub message: String,
    /// The request field, as a dotted path (`curve.knots`, `degree`, `points[3]`).
    pub field: Option<String>,
}

/// Result of a handler.
pub type ApiResult<T> = Result<T, ApiError>;

impl ApiError {
    /// A 400 answer about `field`.
    pub fn bad(field: impl Into<String>, message: impl Into<String>) -> Self {
        ApiError {
            status: StatusCode::BAD_REQUEST,
            message: message.into(),
            field: Some(field.into()),
        }
    }

    /// A 400 answer from a library error about `field` (504 for [`lekalo::Error::Cancelled`]:
    /// the deadline passed).
    pub fn lib(field: &str, e: &lekalo::Error) -> Self {
        let mut a = ApiError::bad(field, e.to_string());
        if matches!(e, lekalo::Error::Cancelled { .. }) {
            a.status = StatusCode::GATEWAY_TIMEOUT;
            a.field = None;
        }
        a
    }

    /// A 400 answer from a library error: the field its argument key names ([`field_of`]),
    /// `default` for an error without a key of the table.
    pub fn lib_or(default: &str, e: &lekalo::Error) -> Self {
        ApiError::lib(field_of(e).unwrap_or(default), e)
    }

    /// A 400 answer from the formats crate's error for the object in `field`: the field the
    /// reader names (`knots`) is appended (`curve.knots`).
    pub fn io(field: &str, e: &IoError) -> Self {
        let inner = match e {
            IoError::Syntax { at, .. } | IoError::Invalid { at, .. } => at.field.clone(),
            _ => None,
        };
        let status = if e.is_bad_input() {
            StatusCode::BAD_REQUEST
        } else {
            StatusCode::INTERNAL_SERVER_ERROR
        };
        ApiError {
            status,
            message: e.to_string(),
            field: Some(match inner {
                Some(f) => format!("{field}.{f}"),
                None => field.to_string(),
            }),
        }
    }
}

/// The library's argument keys (the `what` of its errors) that name a request field, and the
/// field. A key not in the table leaves the choice to the handler, which knows which of its
/// fields the library read.
pub const KEY_FIELDS: [(&str, &str); 31] = [
    ("knots", "knots"),
    ("knots (control points + degree + 1)", "knots"),
    ("weights", "weights"),
    ("weights (one per control point)", "weights"),
    ("control points", "control"),
    ("Bezier control points", "control"),
    ("parametrization", "parametrization"),
    ("parametrisation exponent", "exponent"),
    ("end", "end"),
    ("start derivative", "start_derivative"),
    ("end derivative", "end_derivative"),
    ("start second derivative", "start_derivative"),
    ("end second derivative", "end_derivative"),
    ("rule", "rule"),
    ("expression", "expression"),
    ("derivative order of an expression", "expression"),
    ("x of the expression", "expression"),
    ("derivative of the expression (index = order)", "expression"),
    ("value of the expression (division by zero)", "expression"),
    ("ln of a non-positive value in the expression", "expression"),
    ("breakpoints", "breakpoints"),
    ("continuity conditions", "continuity"),
    (
        "continuity conditions (one per interior breakpoint)",
        "continuity",
    ),
    ("continuity degree k", "continuity"),
    ("λ", "lambda"),
    ("s", "s"),
    ("arc-length tolerance", "tolerance"),
    ("knot insertion count", "times"),
    ("knot removal count", "times"),
    ("knot to remove", "t"),
    ("tolerance", "tolerance"),
];

/// The argument key of a library error, for the variants that carry one.
#[must_use]
pub fn key_of(e: &lekalo::Error) -> Option<&'static str> {
    use lekalo::Error as E;
    match e {
        E::NonFinite { what, .. }
        | E::TooFew { what, .. }
        | E::LengthMismatch { what, .. }
        | E::Dimension { what, .. }
        | E::InvalidArgument { what, .. }
        | E::TooLarge { what, .. }
        | E::NegativeSmoothing { what, .. } => Some(what),
        _ => None,
    }
}

/// The request field of a library error, by its key in [`KEY_FIELDS`] (exact match).
#[must_use]
pub fn field_of(e: &lekalo::Error) -> Option<&'static str> {
    let key = key_of(e)?;
    KEY_FIELDS
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, field)| *field)
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = json!({ "error": self.message, "field": self.field });
        (self.status, Json(body)).into_response()
    }
}
