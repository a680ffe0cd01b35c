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
use axum::http::{header, Method, StatusCode};
use axum::response::IntoResponse;
use axum::routing::{get, post, MethodRouter};
use axum::Router;
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;

mod answer;
pub mod api;
pub mod error;
pub mod expr;
pub mod fit;
pub mod query;
pub mod view;
mod words;

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

/// The `OpenAPI` 3.1 description of the routes (`docs/openapi.json`), served at
/// `/api/openapi.json`.
pub const OPENAPI: &str = include_str!("../../../docs/openapi.json");

/// Every route of the application: path, method and handler. The router is built from this
/// table, and a test checks it against [`OPENAPI`] both ways.
pub fn routes() -> Vec<(&'static str, Method, MethodRouter)> {
    let page =
        |body: &'static str, mime: &'static str| get(move || async move { asset(body, mime) });
    vec![
        (
            "/",
            Method::GET,
            page(INDEX_HTML, "text/html; charset=utf-8"),
        ),
        (
            "/app.js",
            Method::GET,
            page(APP_JS, "text/javascript; charset=utf-8"),
        ),
        (
            "/app.css",
            Method::GET,
            page(APP_CSS, "text/css; charset=utf-8"),
        ),
        ("/api/health", Method::GET, get(|| async { "ok" })),
        (
            "/api/openapi.json",
            Method::GET,
            get(|| async { ([(header::CONTENT_TYPE, "application/json")], OPENAPI) }),
        ),
        ("/api/evaluate", Method::POST, post(api::evaluate)),
        ("/api/interpolate", Method::POST, post(api::interpolate)),
        ("/api/bspline", Method::POST, post(api::bspline)),
        ("/api/bezier", Method::POST, post(api::bezier)),
        ("/api/bezier/build", Method::POST, post(api::bezier_build)),
        ("/api/blend/deform", Method::POST, post(api::blend_deform)),
        ("/api/blend/corners", Method::POST, post(api::blend_corners)),
        ("/api/blend/spline", Method::POST, post(api::blend_spline)),
        ("/api/quasi", Method::POST, post(expr::quasi)),
        ("/api/fit", Method::POST, post(fit::fit)),
        ("/api/project", Method::POST, post(query::project)),
        ("/api/measure", Method::POST, post(query::measure)),
        ("/api/knot/insert", Method::POST, post(api::knot_insert)),
        ("/api/knot/remove", Method::POST, post(api::knot_remove)),
        ("/api/import", Method::POST, post(api::import)),
        ("/api/export/json", Method::POST, post(api::export_json)),
        ("/api/export/step", Method::POST, post(api::export_step)),
    ]
}

/// The application: editor assets and the API under `/api/` ([`routes`]), with the body and
/// time limits.
pub fn router(limits: Limits) -> Router {
    routes()
        .into_iter()
        .fold(Router::new(), |r, (path, _, handler)| {
            r.route(path, handler)
        })
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
