//! The progress of running computations, for the editor's progress bar: a request that carries
//! a job id in the header [`JOB_HEADER`] has its computation's reports (the library's
//! [`lekalo::Progress`] hook, `(done, total)` of the current stage) kept under that id while
//! it runs, and `GET /api/progress?job=ID` answers them with the time elapsed and an estimate
//! of the time left.
//!
//! The table holds only admitted computations (at most [`crate::Limits::workers`] +
//! [`crate::Limits::queue`] entries), each removed when its request ends, whatever the
//! outcome; an id is at most [`MAX_JOB_ID`] characters of `A-Z a-z 0-9 - _`.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use axum::extract::{Query, State};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use serde_json::json;

use crate::Pool;

/// The request header that names a computation's job id.
pub const JOB_HEADER: &str = "x-lekalo-job";

/// Longest job id, in characters.
pub const MAX_JOB_ID: usize = 64;

/// The reports of one running computation.
#[derive(Debug)]
pub(crate) struct Tracker {
    done: AtomicU64,
    total: AtomicU64,
    started: Instant,
}

impl Tracker {
    /// Keeps the latest report of the library's progress hook.
    pub(crate) fn report(&self, done: u64, total: u64) {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(done, Ordering::Relaxed);
    }
}

/// The running computations that carry a job id.
#[derive(Debug, Default)]
pub(crate) struct Jobs(Mutex<HashMap<String, Arc<Tracker>>>);

impl Jobs {
    /// Registers `id`; the entry lives as long as the returned guard. A second request with an
    /// id still running takes the id over (the first's reports are no longer shown).
    pub(crate) fn register(self: &Arc<Self>, id: String) -> Registered {
        let tracker = Arc::new(Tracker {
            done: AtomicU64::new(0),
            total: AtomicU64::new(0),
            started: Instant::now(),
        });
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .insert(id.clone(), Arc::clone(&tracker));
        Registered {
            jobs: Arc::clone(self),
            id,
            tracker,
        }
    }

    fn get(&self, id: &str) -> Option<Arc<Tracker>> {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .get(id)
            .cloned()
    }
}

/// A registered job: removed from the table when dropped (the request ended).
#[derive(Debug)]
pub(crate) struct Registered {
    jobs: Arc<Jobs>,
    id: String,
    /// The tracker the computation reports to.
    pub(crate) tracker: Arc<Tracker>,
}

impl Drop for Registered {
    fn drop(&mut self) {
        let mut table = self.jobs.0.lock().unwrap_or_else(PoisonError::into_inner);
        if table
            .get(&self.id)
            .is_some_and(|t| Arc::ptr_eq(t, &self.tracker))
        {
            table.remove(&self.id);
        }
    }
}

/// A job id that is not 1 to [`MAX_JOB_ID`] characters of `A-Z a-z 0-9 - _`; answered by
/// [`bad_id`].
#[derive(Debug)]
pub(crate) struct BadJobId;

/// The job id of a request: `None` without the header.
pub(crate) fn job_id(headers: &HeaderMap) -> Result<Option<String>, BadJobId> {
    let Some(value) = headers.get(JOB_HEADER) else {
        return Ok(None);
    };
    match value.to_str() {
        Ok(id) if valid(id) => Ok(Some(id.to_string())),
        _ => Err(BadJobId),
    }
}

fn valid(id: &str) -> bool {
    !id.is_empty()
        && id.len() <= MAX_JOB_ID
        && id
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_')
}

/// 400: the job id cannot be kept.
pub(crate) fn bad_id() -> Response {
    (
        StatusCode::BAD_REQUEST,
        Json(json!({
            "error": format!(
                "the job id must be 1 to {MAX_JOB_ID} characters of A-Z, a-z, 0-9, - and _"
            ),
            "field": "job",
        })),
    )
        .into_response()
}

/// The query of `GET /api/progress`.
#[derive(Debug, Deserialize)]
pub struct ProgressQuery {
    /// The job id the computation's request carried in [`JOB_HEADER`].
    job: Option<String>,
}

/// `GET /api/progress?job=ID`: `running` (false once the request has ended, or before it
/// reached the pool), `done` and `total` of the current stage as the library's kernels report
/// them (both 0 before the first report), `elapsed_s` since the request was admitted, and
/// `remaining_s`, the time left at the stage's rate so far
/// (`elapsed · (total − done) / done`), or null before anything is done.
pub async fn progress(State(pool): State<Arc<Pool>>, query: Query<ProgressQuery>) -> Response {
    let Some(id) = query.0.job.filter(|id| valid(id)) else {
        return bad_id();
    };
    let answer = match pool.jobs().get(&id) {
        None => json!({"job": id, "running": false, "done": 0, "total": 0,
                       "elapsed_s": null, "remaining_s": null}),
        Some(t) => {
            let total = t.total.load(Ordering::Relaxed);
            let done = t.done.load(Ordering::Relaxed).min(total);
            let elapsed = t.started.elapsed().as_secs_f64();
            let remaining = (done > 0).then(|| elapsed * (total - done) as f64 / done as f64);
            json!({"job": id, "running": true, "done": done, "total": total,
                   "elapsed_s": elapsed, "remaining_s": remaining})
        }
    };
    Json(answer).into_response()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_short_and_plain() {
        assert!(valid("m3k-12_a"));
        assert!(!valid(""));
        assert!(!valid(&"a".repeat(MAX_JOB_ID + 1)));
        assert!(!valid("a b"));
        assert!(!valid("ä"));
    }

    #[test]
    fn an_entry_lives_as_long_as_its_guard_and_a_takeover_survives_the_first() {
        let jobs = Arc::new(Jobs::default());
        let first = jobs.register("a".into());
        first.tracker.report(3, 10);
        assert_eq!(
            jobs.get("a").map(|t| t.done.load(Ordering::Relaxed)),
            Some(3)
        );
        let second = jobs.register("a".into());
        drop(first);
        assert!(jobs.get("a").is_some(), "the second request keeps the id");
        drop(second);
        assert!(jobs.get("a").is_none());
    }
}
