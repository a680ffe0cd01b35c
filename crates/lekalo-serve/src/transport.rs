//! The transport layers around every route (`docs/serve.md`, "Security and limits"): what a
//! request's body may be before a handler sees it, and the JSON answer of each refusal. All of
//! them are tower-http's layers; this module only orders them and words their refusals.
//!
//! From the outside in:
//!
//! 1. [`transport_errors`]: the refusals of the layers below carry no JSON (408 and 415 an
//!    empty body, 413 a line of text); each gets the API's error object
//!    `{"error": …, "field": null}` naming the limit and the option that sets it.
//! 2. [`content_type`]: a body whose `Content-Type` is not JSON or plain text (a form, a
//!    multipart upload, an image) or whose charset is not UTF-8 is refused with 415 before a
//!    byte of it is read, naming the header and what to send.
//! 3. `TimeoutLayer`: the whole request, its body included, within [`Limits::timeout`] (408),
//!    so a body that never ends, or trickles in a byte a second, is cut off there.
//! 4. `RequestBodyLimitLayer` on the bytes as sent: at most [`Limits::body_bytes`] (413).
//! 5. `RequestDecompressionLayer`: a body with `Content-Encoding: gzip`, `deflate` or `br` is
//!    decompressed as it is read; any other encoding (`zstd`, `compress`, a list of
//!    encodings) is refused with 415 and `Accept-Encoding` naming the ones read.
//! 6. `RequestBodyLimitLayer` on the decompressed bytes: at most [`Limits::body_bytes`] too,
//!    so a kilobyte that inflates to gigabytes is refused (413) after `--max-body` bytes of
//!    output, never held in memory.

use axum::body::Body;
use axum::extract::{DefaultBodyLimit, Request, State};
use axum::http::{header, HeaderValue, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use axum::{Json, Router};
use serde_json::json;
use tower_http::decompression::RequestDecompressionLayer;
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;

use crate::Limits;

/// The content encodings of a request body the server decompresses (HTTP `Content-Encoding`).
pub const BODY_ENCODINGS: &[&str] = &["gzip", "deflate", "br"];

/// `router` with the transport layers of the module docs, sized by `limits`.
pub(crate) fn layered(router: Router, limits: Limits) -> Router {
    router
        .layer(DefaultBodyLimit::disable())
        // the body as the handler reads it: decompressed
        .layer(RequestBodyLimitLayer::new(limits.body_bytes))
        .layer(
            RequestDecompressionLayer::new()
                .gzip(true)
                .deflate(true)
                .br(true),
        )
        // the body as sent
        .layer(RequestBodyLimitLayer::new(limits.body_bytes))
        .layer(TimeoutLayer::with_status_code(
            StatusCode::REQUEST_TIMEOUT,
            limits.timeout,
        ))
        .layer(axum::middleware::from_fn(content_type))
        .layer(axum::middleware::from_fn_with_state(
            limits,
            transport_errors,
        ))
}

/// The media types of a request body the server reads (HTTP `Content-Type`, parameters aside):
/// every body is JSON, and a browser's `fetch` of a string sends it as `text/plain`. A body
/// without the header is read as JSON too.
pub const BODY_TYPES: &[&str] = &["application/json", "text/plain"];

/// Refuses (415, the API's JSON error) a request whose body is declared as anything but
/// [`BODY_TYPES`] (or a `+json` type such as `application/merge-patch+json`), or in a charset
/// other than UTF-8 (`us-ascii` is a subset): a form (`application/x-www-form-urlencoded`, what
/// `curl -d` sends unless told otherwise), a `multipart/form-data` upload, XML, an image. The
/// body is not read. Requests without a `Content-Type` pass, and so does any `GET`.
async fn content_type(req: Request, next: Next) -> Response {
    if matches!(req.method(), &Method::GET | &Method::HEAD) {
        return next.run(req).await;
    }
    let Some(value) = req.headers().get(header::CONTENT_TYPE) else {
        return next.run(req).await;
    };
    let shown = String::from_utf8_lossy(value.as_bytes()).into_owned();
    let mut parts = shown.split(';');
    let media = parts.next().unwrap_or("").trim().to_ascii_lowercase();
    let json_like = media.starts_with("application/") && media.ends_with("+json");
    let why = if !BODY_TYPES.contains(&media.as_str()) && !json_like {
        Some(format!(
            "the request body's Content-Type \"{shown}\" is not one the server reads; send \
             the body as JSON with Content-Type: application/json (text/plain is read as JSON \
             too; with curl, -H 'Content-Type: application/json')"
        ))
    } else {
        parts
            .filter_map(|p| p.split_once('='))
            .find(|(k, _)| k.trim().eq_ignore_ascii_case("charset"))
            .map(|(_, v)| v.trim().trim_matches('"').to_ascii_lowercase())
            .filter(|c| !matches!(c.as_str(), "utf-8" | "utf8" | "us-ascii"))
            .map(|c| {
                format!(
                    "the request body's Content-Type \"{shown}\" declares the charset {c}; the \
                     server reads UTF-8: send the body in UTF-8 (charset=utf-8, or no charset)"
                )
            })
    };
    match why {
        None => next.run(req).await,
        Some(message) => (
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            Json(json!({"error": message, "field": null})),
        )
            .into_response(),
    }
}

/// The message of a body above `--max-body`, sent or decompressed.
pub(crate) fn too_large(limits: &Limits) -> String {
    format!(
        "the request body is larger than {} bytes, as sent or decompressed (lekalo serve \
         --max-body)",
        limits.body_bytes
    )
}

/// Gives the refusals of the transport layers the API's JSON error object (module docs); every
/// other answer passes unchanged.
async fn transport_errors(State(limits): State<Limits>, req: Request, next: Next) -> Response {
    let encoding = req
        .headers()
        .get(header::CONTENT_ENCODING)
        .map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned());
    let answer = next.run(req).await;
    let is_json = answer
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(b"application/json"));
    if is_json {
        return answer;
    }
    let message = match answer.status() {
        StatusCode::REQUEST_TIMEOUT => format!(
            "the request was not received and answered within {} s (lekalo serve --timeout); \
             send the whole body at once",
            limits.timeout.as_secs_f64()
        ),
        StatusCode::PAYLOAD_TOO_LARGE => too_large(&limits),
        StatusCode::UNSUPPORTED_MEDIA_TYPE => format!(
            "the request body's Content-Encoding \"{}\" is not one the server reads; send the \
             body uncompressed or in one of {}",
            encoding.unwrap_or_default(),
            BODY_ENCODINGS.join(", ")
        ),
        _ => return answer,
    };
    let (mut parts, _) = answer.into_parts();
    parts.headers.remove(header::CONTENT_LENGTH);
    parts.headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("application/json"),
    );
    let body = Json(json!({"error": message, "field": null})).into_response();
    Response::from_parts(parts, Body::new(body.into_body()))
}
