//! The one error answer of the API: HTTP 400 (or 413/408 from the limit layers, 503/504 from
//! the pool) with the library's message and the request field that caused it, so that the
//! editor can show the message next to the control that set the field.
//!
//! The field of a library error comes from its typed parts, never from its message: its
//! argument key ([`lekalo::Error::arg`]), mapped by [`field`], the one table from the
//! library's keys to the request's fields, or else the handler's choice among its own fields.

use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use lekalo::Arg;
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
    /// the deadline passed). `field` is what the handler chose after asking the error's key
    /// ([`field_of`]); a handler with one default field calls [`ApiError::lib_or`].
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

/// The request field of each argument key of the library's errors ([`lekalo::Error::arg`]): the
/// one table from the library's keys to the request's fields (as the CLI's table from the keys
/// to its options), `None` for an argument that no request field sets alone, whose field the
/// handler chooses (it knows which of its fields the library read). Exhaustive, so that a new
/// key does not compile until it is named here.
#[must_use]
pub const fn field(arg: Arg) -> Option<&'static str> {
    Some(match arg {
        Arg::Knots => "knots",
        Arg::Weights => "weights",
        Arg::ControlPoints => "control",
        Arg::Parametrization => "parametrization",
        Arg::Exponent => "exponent",
        Arg::End => "end",
        Arg::StartDerivative => "start_derivative",
        Arg::EndDerivative => "end_derivative",
        Arg::Rule => "rule",
        Arg::Expression => "expression",
        Arg::Breakpoints => "breakpoints",
        Arg::ContinuityConditions | Arg::Continuity => "continuity",
        Arg::CornerFraction => "fraction",
        Arg::CornerLength => "length",
        Arg::Lambda => "lambda",
        Arg::S => "s",
        Arg::KnotRounds => "knot_rounds",
        Arg::Tolerance => "tolerance",
        // the measure request's `rtol`: the arc length's relative tolerance
        Arg::RelativeTolerance => "rtol",
        Arg::Times => "times",
        Arg::Knot => "t",
        Arg::EndDerivatives
        | Arg::Parameters
        | Arg::Tangents
        | Arg::DataWeights
        | Arg::Direction
        | Arg::CornerWindow
        | Arg::Eps
        | Arg::MaxKnots
        | Arg::Bbox
        | Arg::ColatitudeKnots
        | Arg::LongitudeKnots
        | Arg::Colatitudes
        | Arg::Longitudes
        | Arg::PoleValues
        | Arg::PoleFlat => return None,
    })
}

/// The request field of a library error: the field of its argument key ([`field`]).
#[must_use]
pub fn field_of(e: &lekalo::Error) -> Option<&'static str> {
    e.arg().and_then(field)
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = json!({ "error": self.message, "field": self.field });
        (self.status, Json(body)).into_response()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The keys without a field ([`field`] is `None`), each with the reason.
    const WITHOUT_FIELD: &[(Arg, &str)] = &[
        (
            Arg::EndDerivatives,
            "both derivatives: the interpolation handler names the one at fault",
        ),
        (
            Arg::Parameters,
            "no request gives the points' parameters: they come from `parametrization`",
        ),
        (Arg::Tangents, "no request gives Hermite tangents"),
        (Arg::DataWeights, "no request gives a fit's data weights"),
        (Arg::Direction, "no request takes a surface direction"),
        (
            Arg::CornerWindow,
            "the window is `fraction` or `length`: the corners handler names the one given",
        ),
        (Arg::Eps, "no request fits scattered data"),
        (Arg::MaxKnots, "no request fits scattered data"),
        (Arg::Bbox, "no request fits scattered data"),
        (Arg::ColatitudeKnots, "no request fits data on the sphere"),
        (Arg::LongitudeKnots, "no request fits data on the sphere"),
        (Arg::Colatitudes, "no request fits data on the sphere"),
        (Arg::Longitudes, "no request fits data on the sphere"),
        (Arg::PoleValues, "no request fits data on the sphere"),
        (Arg::PoleFlat, "no request fits data on the sphere"),
    ];

    /// Every key has a field, or is listed in `WITHOUT_FIELD` with the reason: a new key, or a
    /// key whose field is forgotten, fails here.
    #[test]
    fn every_key_has_a_field_or_a_reason() {
        for &arg in Arg::ALL {
            let listed = WITHOUT_FIELD.iter().any(|(a, _)| *a == arg);
            match field(arg) {
                Some(f) => assert!(!listed, "{arg:?} has the field {f} and a reason for none"),
                None => assert!(listed, "{arg:?} has no request field and no reason"),
            }
        }
    }

    /// Each key: a library error about it answers with the key's field (or the handler's
    /// default for a key without one), and with the library's message unchanged.
    #[test]
    fn errors_about_a_key_answer_with_its_field() {
        for &arg in Arg::ALL {
            let e = lekalo::Error::InvalidArgument {
                what: arg.into(),
                reason: "why".into(),
            };
            assert_eq!(field_of(&e), field(arg), "{arg:?}");
            let a = ApiError::lib_or("points", &e);
            assert_eq!(a.field.as_deref(), Some(field(arg).unwrap_or("points")));
            assert_eq!(a.message, format!("invalid {arg}: why"));
        }
        let nan = lekalo::KnotVector::new(vec![0.0, f64::NAN]).unwrap_err();
        assert_eq!(
            ApiError::lib_or("curve", &nan).field.as_deref(),
            Some("knots")
        );
        let buffer = lekalo::Error::LengthMismatch {
            what: "output buffer".into(),
            expected: 2,
            got: 1,
        };
        assert_eq!(
            field_of(&buffer),
            None,
            "an error without a key has no field"
        );
    }
}
