//! The one error answer of the API: HTTP 400 (or 413/408 from the limit layers) with the
//! library's message and the request field that caused it, so that the editor can show the
//! message next to the control that set the field.

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

    /// A 400 answer from a library error about `field`.
    pub fn lib(field: &str, e: &lekalo::Error) -> Self {
        ApiError::bad(field, e.to_string())
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

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = json!({ "error": self.message, "field": self.field });
        (self.status, Json(body)).into_response()
    }
}
