//! `lekalo serve`: a local HTTP server with a JSON API over the lekalo library and a
//! single-page spline editor (`docs/serve.md`).
//!
//! The server is thin: each API handler reads a request (curves in the CLI's object format,
//! validated by the same reader as `lekalo`), calls the library and answers the result with
//! its drawing. The editor's HTML, CSS and JavaScript are embedded in the binary; nothing else
//! of the file system is served and nothing is fetched from the network.
//!
//! Limits (all in [`Limits`], `docs/serve.md`): request body size and time, a budget per
//! request (degree, samples, points and total work, checked for every curve a request sends or
//! asks for before anything is computed: [`budget`]), and a bounded pool for the computations
//! ([`pool`]): they run on blocking threads, never on the runtime's workers, so that
//! `/api/health` and the editor's files are answered while the pool is full; a request that
//! finds the pool and its queue full gets 503, and one whose computation passes the deadline
//! gets 504, the computation being stopped through the library's [`lekalo::Progress`] hook.
//! Answers carry no CORS headers, so pages of other origins cannot read them. Connections are
//! bounded in number and in the time to send a request's head ([`listen`]).

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use axum::http::{header, Method, StatusCode};
use axum::response::IntoResponse;
use axum::routing::{get, MethodRouter};
use axum::Router;

mod answer;
pub mod api;
pub mod blend;
pub mod budget;
pub mod error;
pub mod expr;
mod fields;
pub mod fit;
pub mod jobs;
pub mod listen;
pub mod pool;
pub mod query;
pub mod transport;
pub mod view;
mod words;

pub use error::{ApiError, ApiResult};
pub use pool::{Job, Pool};

/// Limits of the server and of one request, with the defaults of `lekalo serve`
/// (`docs/serve.md`, section "Security and limits"). Every field has an option of
/// `lekalo serve` (`--max-body`, `--timeout`, `--deadline`, `--workers`, `--queue`,
/// `--max-connections`, `--max-degree`, `--max-samples`, `--max-points`, `--max-work`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Largest request body in bytes, as sent and once decompressed (413 above it;
    /// [`transport`]). Default 2 MiB.
    pub body_bytes: usize,
    /// Longest time to read a request and answer it (408 after it), which also bounds a
    /// client that sends its body slowly. Default 10 s.
    pub timeout: Duration,
    /// Longest time a computation may wait for the pool and run (504 after it, and the
    /// computation is cancelled). Default 5 s; keep it below `timeout`.
    pub deadline: Duration,
    /// Computations that run at once, each on a blocking thread. Default: the machine's
    /// available parallelism.
    pub workers: usize,
    /// Computations that may wait for a worker; one more is refused with 503 and
    /// `Retry-After`. Default 64.
    pub queue: usize,
    /// Connections served at once; beyond them a connection gets only the pages and the light
    /// routes, computing routes answering 503 ([`listen`]). Default 4096.
    pub connections: usize,
    /// Highest degree of any curve a request sends or asks for (a Bezier curve of `n + 1`
    /// control points has degree `n`), and the order − 1 of a quasi-interpolant. Default
    /// [`api::MAX_API_DEGREE`] (64).
    pub max_degree: usize,
    /// Most samples of a curve, of the basis panel or of a quasi-interpolant's error. Default
    /// [`api::MAX_SAMPLES`] (10,000).
    pub max_samples: usize,
    /// Most points a request sends (data points, control points of a curve, breakpoints,
    /// lengths) or asks for (control points of a constructed curve). Default
    /// [`api::MAX_POINTS`] (10,000).
    pub max_points: usize,
    /// Most work of one request, in evaluations times `(degree + 1)²` (the cost of one point
    /// by de Casteljau or Cox–de Boor): a drawing of `s` samples (twice with the comb), `b`
    /// basis samples and `k` knots of a degree-`p` curve costs `(s + b + k)·(p + 1)²`.
    /// Default [`budget::MAX_WORK`] (2^27, about 0.1 s): every request inside the other
    /// defaults fits; it bounds requests once those are raised.
    pub max_work: u64,
}

impl Default for Limits {
    /// An editor request is a few kilobytes and a few milliseconds: the values in the field
    /// docs.
    fn default() -> Self {
        Limits {
            body_bytes: 2 << 20,
            timeout: Duration::from_secs(10),
            deadline: Duration::from_secs(5),
            workers: std::thread::available_parallelism().map_or(1, std::num::NonZero::get),
            queue: 64,
            connections: 4096,
            max_degree: api::MAX_API_DEGREE,
            max_samples: api::MAX_SAMPLES,
            max_points: api::MAX_POINTS,
            max_work: budget::MAX_WORK,
        }
    }
}

const INDEX_HTML: &str = include_str!("../assets/index.html");
const APP_CSS: &str = include_str!("../assets/app.css");

/// The editor's script: ES modules by job (`assets/js/main.js` says which file does what),
/// loaded by the page as modules from these paths. No bundler: the browser follows the
/// imports.
pub const EDITOR_SCRIPTS: &[(&str, &str)] = &[
    ("/js/api.js", include_str!("../assets/js/api.js")),
    ("/js/draw.js", include_str!("../assets/js/draw.js")),
    ("/js/errors.js", include_str!("../assets/js/errors.js")),
    ("/js/files.js", include_str!("../assets/js/files.js")),
    ("/js/idle.js", include_str!("../assets/js/idle.js")),
    ("/js/keyboard.js", include_str!("../assets/js/keyboard.js")),
    ("/js/main.js", include_str!("../assets/js/main.js")),
    (
        "/js/modes/bezier.js",
        include_str!("../assets/js/modes/bezier.js"),
    ),
    (
        "/js/modes/blend.js",
        include_str!("../assets/js/modes/blend.js"),
    ),
    (
        "/js/modes/bspline.js",
        include_str!("../assets/js/modes/bspline.js"),
    ),
    (
        "/js/modes/common.js",
        include_str!("../assets/js/modes/common.js"),
    ),
    (
        "/js/modes/fit.js",
        include_str!("../assets/js/modes/fit.js"),
    ),
    (
        "/js/modes/index.js",
        include_str!("../assets/js/modes/index.js"),
    ),
    (
        "/js/modes/interpolate.js",
        include_str!("../assets/js/modes/interpolate.js"),
    ),
    (
        "/js/modes/quasi.js",
        include_str!("../assets/js/modes/quasi.js"),
    ),
    ("/js/panels.js", include_str!("../assets/js/panels.js")),
    ("/js/pointer.js", include_str!("../assets/js/pointer.js")),
    ("/js/queries.js", include_str!("../assets/js/queries.js")),
    ("/js/schedule.js", include_str!("../assets/js/schedule.js")),
    ("/js/screen.js", include_str!("../assets/js/screen.js")),
    ("/js/state.js", include_str!("../assets/js/state.js")),
];

/// The `OpenAPI` 3.1 description of the routes (`docs/openapi.json`), served at
/// `/api/openapi.json`.
pub const OPENAPI: &str = include_str!("../../../docs/openapi.json");

/// Every route of the application: path, method and handler (the editor's scripts are
/// [`EDITOR_SCRIPTS`]). The router is built from this table, and a test checks it against
/// [`OPENAPI`] both ways. The pages, `/api/health` and
/// `/api/openapi.json` and `/api/progress` are answered on the runtime's workers; every other
/// route computes in the [`Pool`].
pub fn routes() -> Vec<(&'static str, Method, MethodRouter<Arc<Pool>>)> {
    let page =
        |body: &'static str, mime: &'static str| get(move || async move { asset(body, mime) });
    let mut routes = vec![
        (
            "/",
            Method::GET,
            page(INDEX_HTML, "text/html; charset=utf-8"),
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
        ("/api/progress", Method::GET, get(jobs::progress)),
        ("/api/evaluate", Method::POST, pool::post(api::evaluate)),
        (
            "/api/interpolate",
            Method::POST,
            pool::post(api::interpolate),
        ),
        ("/api/bspline", Method::POST, pool::post(api::bspline)),
        ("/api/bezier", Method::POST, pool::post(api::bezier)),
        (
            "/api/bezier/build",
            Method::POST,
            pool::post(api::bezier_build),
        ),
        ("/api/blend/deform", Method::POST, pool::post(blend::deform)),
        (
            "/api/blend/corners",
            Method::POST,
            pool::post(blend::corners),
        ),
        ("/api/blend/spline", Method::POST, pool::post(blend::spline)),
        ("/api/quasi", Method::POST, pool::post(expr::quasi)),
        ("/api/fit", Method::POST, pool::post(fit::fit)),
        ("/api/project", Method::POST, pool::post(query::project)),
        ("/api/measure", Method::POST, pool::post(query::measure)),
        ("/api/intersect", Method::POST, pool::post(query::intersect)),
        (
            "/api/knot/insert",
            Method::POST,
            pool::post(api::knot_insert),
        ),
        (
            "/api/knot/remove",
            Method::POST,
            pool::post(api::knot_remove),
        ),
        ("/api/import", Method::POST, pool::post(api::import)),
        (
            "/api/export/json",
            Method::POST,
            pool::post(api::export_json),
        ),
        (
            "/api/export/step",
            Method::POST,
            pool::post(api::export_step),
        ),
    ];
    routes.extend(EDITOR_SCRIPTS.iter().map(|&(path, body)| {
        (
            path,
            Method::GET,
            page(body, "text/javascript; charset=utf-8"),
        )
    }));
    routes
}

/// The application: editor assets and the API under `/api/` ([`routes`]), with the body and
/// time limits and a [`Pool`] sized by `limits`.
pub fn router(limits: Limits) -> Router {
    app(Arc::new(Pool::new(limits)), routes())
}

/// The router of `routes` on `pool`, with the 404 fallback and the transport layers (body
/// size, decoding and time: [`transport`]).
fn app(pool: Arc<Pool>, routes: Vec<(&'static str, Method, MethodRouter<Arc<Pool>>)>) -> Router {
    let limits = *pool.limits();
    let router = routes
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
        .with_state(pool);
    transport::layered(router, limits)
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
        listen::serve(listener, limits, async {
            let _ = tokio::signal::ctrl_c().await;
        })
        .await
    })
}
