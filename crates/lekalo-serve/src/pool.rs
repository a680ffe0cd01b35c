//! The computations of the API, off the runtime's workers: a bounded pool of blocking threads
//! with a bounded queue, a deadline per computation and cancellation through the library's
//! progress hook ([`lekalo::Progress`]).
//!
//! - At most [`Limits::workers`] computations run at once, each on a thread of
//!   `tokio::task::spawn_blocking`; the runtime's two workers only read requests and write
//!   answers, so `/api/health` and the editor's files are answered while every computation
//!   thread is busy.
//! - At most [`Limits::queue`] more wait for a thread; a request beyond that is answered at once
//!   with 503, a `Retry-After` header and the JSON error, before its body is read. A body is
//!   read only once its request is admitted, so the bodies held in memory are at most
//!   `(workers + queue) · --max-body` bytes, however many clients send at once.
//! - A computation that has not finished [`Limits::deadline`] after its request was read
//!   (waiting included) is answered with 504; its cancel flag is set, and the library's kernels,
//!   which check the flag between chunks of work, stop with [`lekalo::Error::Cancelled`]. The
//!   flag is also set when the request is dropped: the client went away or the request timeout
//!   (408) passed. A thread keeps its place in the pool until its kernel has stopped, so the pool
//!   bounds the threads that compute, not only the requests that wait.
//! - A request with a job id ([`crate::jobs::JOB_HEADER`]) has its computation's progress
//!   reports kept under that id while it runs, for `GET /api/progress` ([`crate::jobs`]).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use axum::body::{Body, Bytes};
use axum::extract::State;
use axum::http::{header, HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::MethodRouter;
use axum::Json;
use lekalo::Progress;
use serde_json::json;
use tokio::sync::Semaphore;

use crate::error::ApiResult;
use crate::jobs::{bad_id, job_id, BadJobId, Jobs};
use crate::Limits;

/// Seconds a client is asked to wait after a 503 (`Retry-After`).
pub const RETRY_AFTER_SECONDS: u64 = 1;

/// The computing pool shared by the API's routes: the limits, the threads that may compute
/// and the requests that may wait.
#[derive(Debug)]
pub struct Pool {
    limits: Limits,
    /// One permit per computing thread ([`Limits::workers`]).
    running: Arc<Semaphore>,
    /// One permit per admitted request, running or waiting ([`Limits::workers`] +
    /// [`Limits::queue`]).
    admitted: Arc<Semaphore>,
    /// The progress of the admitted computations that carry a job id.
    jobs: Arc<Jobs>,
}

impl Pool {
    /// A pool sized by `limits` (at least one worker).
    #[must_use]
    pub fn new(limits: Limits) -> Self {
        let workers = limits.workers.clamp(1, Semaphore::MAX_PERMITS / 2);
        let queue = limits.queue.min(Semaphore::MAX_PERMITS / 2);
        Pool {
            limits,
            running: Arc::new(Semaphore::new(workers)),
            admitted: Arc::new(Semaphore::new(workers + queue)),
            jobs: Arc::default(),
        }
    }

    /// The limits the pool and its requests obey.
    #[must_use]
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// The progress of the running computations that carry a job id.
    pub(crate) fn jobs(&self) -> &Jobs {
        &self.jobs
    }
}

/// What a computing handler receives besides its body: the limits of the request and the
/// progress hook that stops it at the deadline.
#[derive(Debug, Clone, Copy)]
pub struct Job<'a> {
    /// The server's limits (budget of the request).
    pub limits: &'a Limits,
    /// Cancelled at the deadline or when the request is dropped; pass it to the library's
    /// `*_with_progress` kernels.
    pub progress: Progress<'a>,
}

impl Job<'_> {
    /// A job with `limits` and no cancellation (tests, benchmarks).
    #[must_use]
    pub fn unbounded(limits: &Limits) -> Job<'_> {
        Job {
            limits,
            progress: Progress::new(),
        }
    }
}

/// A computing handler: parses the body, calls the library, answers.
pub type Compute = fn(&Job<'_>, &Bytes) -> ApiResult<Response>;

/// The `POST` route of a computing handler: its requests run in the [`Pool`].
pub fn post(f: Compute) -> MethodRouter<Arc<Pool>> {
    axum::routing::post(
        move |State(pool): State<Arc<Pool>>, headers: HeaderMap, body: Body| {
            run(pool, headers, body, f)
        },
    )
}

/// Sets the flag when dropped: the request's future was dropped before the computation ended
/// (client gone, request timeout) or the deadline passed.
struct CancelOnDrop(Arc<AtomicBool>);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Runs `f` on `body` in the pool, within the deadline (module docs).
async fn run(pool: Arc<Pool>, headers: HeaderMap, body: Body, f: Compute) -> Response {
    let id = match job_id(&headers) {
        Ok(id) => id,
        Err(BadJobId) => return bad_id(),
    };
    let Ok(admission) = Arc::clone(&pool.admitted).try_acquire_owned() else {
        return busy(pool.limits());
    };
    // read under the admission: the time is the request's (`--timeout`, 408)
    let body = match axum::body::to_bytes(body, pool.limits.body_bytes).await {
        Ok(body) => body,
        Err(e) => return unreadable(&e, pool.limits()),
    };
    // reports are kept from admission until the request ends, whatever the outcome
    let registered = id.map(|id| pool.jobs.register(id));
    let tracker = registered.as_ref().map(|r| Arc::clone(&r.tracker));
    let cancel = Arc::new(AtomicBool::new(false));
    let _cancel_on_drop = CancelOnDrop(Arc::clone(&cancel));
    let limits = pool.limits;
    let flag = Arc::clone(&cancel);
    let work = async move {
        let Ok(permit) = Arc::clone(&pool.running).acquire_owned().await else {
            // the semaphore is never closed
            return Err(internal("the computing pool is closed"));
        };
        tokio::task::spawn_blocking(move || {
            let _held = (permit, admission);
            let report = |done: u64, total: u64| {
                if let Some(t) = &tracker {
                    t.report(done, total);
                }
            };
            let progress = Progress::new().with_cancel(&flag);
            let job = Job {
                limits: &limits,
                progress: if tracker.is_some() {
                    progress.with_report(&report)
                } else {
                    progress
                },
            };
            f(&job, &body)
        })
        .await
        .map_err(|e| internal(&format!("the computation failed: {e}")))
    };
    match tokio::time::timeout(limits.deadline, work).await {
        Ok(Ok(Ok(answer))) => answer,
        Ok(Ok(Err(e))) => e.into_response(),
        Ok(Err(answer)) => answer,
        Err(_) => {
            cancel.store(true, Ordering::Relaxed);
            past_deadline(limits.deadline)
        }
    }
}

fn internal(message: &str) -> Response {
    (
        StatusCode::INTERNAL_SERVER_ERROR,
        Json(json!({"error": message, "field": null})),
    )
        .into_response()
}

/// 503 with `Retry-After`: every worker computes and the queue is full.
fn busy(limits: &Limits) -> Response {
    (
        StatusCode::SERVICE_UNAVAILABLE,
        [(header::RETRY_AFTER, RETRY_AFTER_SECONDS.to_string())],
        Json(json!({
            "error": format!(
                "the server is busy: {} computations run and {} wait (lekalo serve --workers, \
                 --queue); try again in {RETRY_AFTER_SECONDS} s",
                limits.workers, limits.queue
            ),
            "field": null,
        })),
    )
        .into_response()
}

/// 413 for a body above `--max-body` sent without a length (one with a larger
/// `Content-Length` is refused by the limit layer before the handler); 400 for a body that
/// could not be read (a broken chunked encoding; a client gone reads nothing).
fn unreadable(e: &axum::Error, limits: &Limits) -> Response {
    let mut source: Option<&(dyn std::error::Error + 'static)> = Some(e);
    while let Some(s) = source {
        if s.is::<http_body_util::LengthLimitError>() {
            return (
                StatusCode::PAYLOAD_TOO_LARGE,
                Json(json!({"error": crate::transport::too_large(limits), "field": null})),
            )
                .into_response();
        }
        source = s.source();
    }
    (
        StatusCode::BAD_REQUEST,
        Json(json!({"error": format!("the request body could not be read: {e}"), "field": null})),
    )
        .into_response()
}

/// 504: the computation passed the deadline and was cancelled.
pub(crate) fn past_deadline(deadline: Duration) -> Response {
    (
        StatusCode::GATEWAY_TIMEOUT,
        Json(json!({
            "error": format!(
                "the computation did not finish within the server's deadline of {d} s and was \
                 stopped: ask for less (fewer points, samples or shape constraints, a lower \
                 degree), or give the server more time by starting it again with \
                 `lekalo serve --deadline {more}`",
                d = deadline.as_secs_f64(),
                // a suggestion that is more than the deadline met, in whole seconds
                more = (deadline.as_secs_f64() * 6.0).ceil().max(30.0)
            ),
            "field": null,
        })),
    )
        .into_response()
}
