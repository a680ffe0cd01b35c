//! `lekalo serve`: a local HTTP server with a JSON API over the lekalo library and a
//! single-page spline editor (`docs/serve.md`).
//!
//! The server is thin: each API handler reads a request (curves in the CLI's object format,
//! validated by the same reader as `lekalo`), calls the library and answers the result with
//! its drawing. The editor's HTML, CSS and JavaScript are embedded in the binary; nothing else
//! of the file system is served and nothing is fetched from the network.
//!
//! Limits (all in [`Limits`]): request body size, time per request, and the explicit size
//! limits of [`api`] (samples, points, degree). Answers carry no CORS headers, so pages of
//! other origins cannot read them.

use std::net::SocketAddr;
use std::time::Duration;

use axum::extract::DefaultBodyLimit;
use axum::http::{header, StatusCode};
use axum::response::IntoResponse;
use axum::routing::{get, post};
use axum::Router;
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;

pub mod api;
pub mod error;
pub mod expr;
pub mod fit;
pub mod query;

pub use error::{ApiError, ApiResult};

/// Limits of one request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Largest request body in bytes (413 above it).
    pub body_bytes: usize,
    /// Longest time to read a request and compute its answer (408 after it), which also
    /// bounds a client that sends its body slowly.
    pub timeout: Duration,
}

impl Default for Limits {
    /// 2 MiB and 10 s: an editor request is a few kilobytes and a few milliseconds.
    fn default() -> Self {
        Limits {
            body_bytes: 2 << 20,
            timeout: Duration::from_secs(10),
        }
    }
}

const INDEX_HTML: &str = include_str!("../assets/index.html");
const APP_JS: &str = include_str!("../assets/app.js");
const APP_CSS: &str = include_str!("../assets/app.css");

/// The application: editor assets and the API under `/api/`, with the body and time limits.
pub fn router(limits: Limits) -> Router {
    Router::new()
        .route(
            "/",
            get(|| async { asset(INDEX_HTML, "text/html; charset=utf-8") }),
        )
        .route(
            "/app.js",
            get(|| async { asset(APP_JS, "text/javascript; charset=utf-8") }),
        )
        .route(
            "/app.css",
            get(|| async { asset(APP_CSS, "text/css; charset=utf-8") }),
        )
        .route("/api/health", get(|| async { "ok" }))
        .route("/api/evaluate", post(api::evaluate))
        .route("/api/interpolate", post(api::interpolate))
        .route("/api/bspline", post(api::bspline))
        .route("/api/bezier", post(api::bezier))
        .route("/api/bezier/build", post(api::bezier_build))
        .route("/api/blend/deform", post(api::blend_deform))
        .route("/api/blend/corners", post(api::blend_corners))
        .route("/api/quasi", post(expr::quasi))
        .route("/api/fit", post(fit::fit))
        .route("/api/project", post(query::project))
        .route("/api/measure", post(query::measure))
        .route("/api/knot/insert", post(api::knot_insert))
        .route("/api/knot/remove", post(api::knot_remove))
        .route("/api/import", post(api::import))
        .route("/api/export/json", post(api::export_json))
        .route("/api/export/step", post(api::export_step))
        .fallback(|| async {
            (
                StatusCode::NOT_FOUND,
                axum::Json(
                    serde_json::json!({"error": "no such page or API route", "field": null}),
                ),
            )
        })
        .layer(DefaultBodyLimit::disable())
        .layer(RequestBodyLimitLayer::new(limits.body_bytes))
        .layer(TimeoutLayer::with_status_code(
            StatusCode::REQUEST_TIMEOUT,
            limits.timeout,
        ))
}

fn asset(body: &'static str, mime: &'static str) -> impl IntoResponse {
    (
        [
            (header::CONTENT_TYPE, mime),
            // the page talks only to its own origin
            (
                header::CONTENT_SECURITY_POLICY,
                "default-src 'self'; img-src 'self' data: blob:; style-src 'self'",
            ),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        body,
    )
}

/// Binds `addr`, calls `ready` with the bound address (port 0 picks a free port), and serves
/// until Ctrl-C.
///
/// # Errors
/// The operating system's error when the address cannot be bound.
pub fn run(
    addr: SocketAddr,
    limits: Limits,
    ready: impl FnOnce(SocketAddr),
) -> std::io::Result<()> {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()?;
    rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind(addr).await?;
        ready(listener.local_addr()?);
        axum::serve(listener, router(limits))
            .with_graceful_shutdown(async {
                let _ = tokio::signal::ctrl_c().await;
            })
            .await
    })
}
