//! Progress reports and cancellation for long computations: a small hook that a kernel calls
//! between units of work, never inside its arithmetic, so results are the same with or without it.

use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::{Error, Result};

/// How a long computation reports progress and learns that it should stop.
///
/// Kernels that can run for seconds (over millions of points) take a `&Progress` and call it
/// between units of work: `report(done, total)` with `done` non-decreasing and reaching `total`
/// when the work completes, and a check of the `cancel` flag, which stops the computation with
/// [`Error::Cancelled`]. The hook never changes a result. [`Progress::new`] does nothing.
///
/// ```
/// use std::sync::atomic::AtomicBool;
/// use std::sync::Mutex;
/// use lekalo::Progress;
/// let seen = Mutex::new(Vec::new());
/// let report = |done: u64, total: u64| seen.lock().unwrap().push((done, total));
/// let stop = AtomicBool::new(false);
/// let progress = Progress::new().with_report(&report).with_cancel(&stop);
/// assert!(progress.is_active());
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Clone, Copy, Default)]
pub struct Progress<'a> {
    report: Option<&'a (dyn Fn(u64, u64) + Sync)>,
    cancel: Option<&'a AtomicBool>,
}

impl std::fmt::Debug for Progress<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Progress")
            .field("report", &self.report.is_some())
            .field("cancel", &self.cancel.map(|c| c.load(Ordering::Relaxed)))
            .finish()
    }
}

impl<'a> Progress<'a> {
    /// Units of work between two reports in the kernels that take a [`Progress`]: a check costs
    /// an atomic load, so it is made every `STRIDE` items (a few milliseconds of work at most).
    pub const STRIDE: u64 = 1 << 12;

    /// No reports and no cancellation.
    #[must_use]
    pub fn new() -> Self {
        Progress::default()
    }

    /// Reports `(done, total)` to `report`.
    #[must_use]
    pub fn with_report(self, report: &'a (dyn Fn(u64, u64) + Sync)) -> Self {
        Progress {
            report: Some(report),
            ..self
        }
    }

    /// Stops with [`Error::Cancelled`] once `cancel` is set (e.g. by a signal handler).
    #[must_use]
    pub fn with_cancel(self, cancel: &'a AtomicBool) -> Self {
        Progress {
            cancel: Some(cancel),
            ..self
        }
    }

    /// True if a report or a cancel flag is attached.
    #[must_use]
    pub fn is_active(&self) -> bool {
        self.report.is_some() || self.cancel.is_some()
    }

    /// Called by a kernel after `done` of `total` units of `what`: reports, then checks the
    /// cancel flag.
    ///
    /// # Errors
    /// [`Error::Cancelled`] naming `what` if the cancel flag is set.
    pub fn step(&self, what: &'static str, done: u64, total: u64) -> Result<()> {
        if let Some(report) = self.report {
            report(done, total);
        }
        if self.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return Err(Error::Cancelled { what });
        }
        Ok(())
    }

    /// [`Progress::step`] every [`Progress::STRIDE`] units and at the last one (`done == total`).
    ///
    /// # Errors
    /// As [`Progress::step`].
    pub fn every(&self, what: &'static str, done: u64, total: u64) -> Result<()> {
        if done % Self::STRIDE == 0 || done == total {
            self.step(what, done, total)
        } else {
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn ticks_are_monotone_reach_the_total_and_cancel_stops() {
        let seen = Mutex::new(Vec::new());
        let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
        let p = Progress::new().with_report(&report);
        let total = 3 * Progress::STRIDE + 7;
        for done in 0..=total {
            p.every("work", done, total).unwrap();
        }
        let seen = seen.into_inner().unwrap();
        assert!(
            seen.windows(2).all(|w| w[0].0 < w[1].0),
            "monotone: {seen:?}"
        );
        assert_eq!(seen.last(), Some(&(total, total)), "reaches the total");
        assert!(seen.iter().all(|&(_, t)| t == total), "one total");
        let stop = AtomicBool::new(false);
        let p = Progress::new().with_cancel(&stop);
        assert!(p.step("work", 1, 2).is_ok(), "not cancelled yet");
        stop.store(true, Ordering::Relaxed);
        assert_eq!(
            p.step("work", 2, 2),
            Err(Error::Cancelled { what: "work" }),
            "cancelled"
        );
        assert!(!Progress::new().is_active(), "the default does nothing");
    }
}
