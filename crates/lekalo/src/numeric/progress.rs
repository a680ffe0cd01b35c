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

    /// Items to process between two checks when one item costs `cost` units of work (an
    /// estimate of its arithmetic, e.g. `(p + 1)²` for a point of a degree-`p` curve):
    /// `STRIDE / cost`, at least one, so that a check comes about every [`Progress::STRIDE`]
    /// units whatever the size of an item.
    ///
    /// ```
    /// use lekalo::Progress;
    /// assert_eq!(Progress::items_per_step(1), Progress::STRIDE as usize);
    /// assert_eq!(Progress::items_per_step(16), (Progress::STRIDE / 16) as usize);
    /// assert_eq!(Progress::items_per_step(u64::MAX), 1);
    /// ```
    #[must_use]
    pub fn items_per_step(cost: u64) -> usize {
        usize::try_from(Self::STRIDE / cost.max(1))
            .unwrap_or(1)
            .max(1)
    }

    /// Runs `f` on consecutive chunks of `items`, [`Progress::items_per_step`]`(cost)` items
    /// at a time, and calls [`Progress::step`] before the first chunk and after each one with
    /// the number of items done. `f` keeps its state (span cursors, scratch, the iterator over
    /// the output) across chunks, so the results are those of one pass over all items: the
    /// hook only decides whether the next chunk runs.
    ///
    /// # Errors
    /// `f`'s errors; [`Error::Cancelled`] naming `what` when the cancel flag is set.
    pub(crate) fn chunks<T>(
        &self,
        what: &'static str,
        items: &[T],
        cost: u64,
        mut f: impl FnMut(&[T]) -> Result<()>,
    ) -> Result<()> {
        let total = items.len() as u64;
        self.step(what, 0, total)?;
        let mut done = 0_u64;
        for chunk in items.chunks(Self::items_per_step(cost)) {
            f(chunk)?;
            done += chunk.len() as u64;
            self.step(what, done, total)?;
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

    /// The batch evaluations that take a [`Progress`] give the bits of those that do not, with
    /// a report and an unset cancel flag attached; their reports are monotone and reach the
    /// number of points; a set flag stops them with [`Error::Cancelled`].
    #[test]
    fn batch_evaluation_is_unchanged_by_the_hook_and_stops_when_cancelled() {
        use crate::{BSplineCurve, BSplineSurface, BezierCurve, Curve, NurbsCurve, NurbsSurface};
        use crate::{KnotVector, Points};
        let wave = |n: usize, dim: usize| {
            let data = (0..n * dim)
                .map(|i| (i as f64 * 0.37).sin() + i as f64 * 0.01)
                .collect();
            Points::from_flat(dim, data).unwrap()
        };
        let knots = |p: usize, n: usize| KnotVector::clamped_uniform(p, n).unwrap().into_vec();
        let mut curves = vec![Curve::Bezier(BezierCurve::new(wave(40, 2)).unwrap())];
        for (p, dim) in [(1, 2), (2, 3), (3, 2), (3, 4), (5, 3)] {
            curves.push(Curve::BSpline(
                BSplineCurve::new(p, knots(p, 30), wave(30, dim)).unwrap(),
            ));
        }
        let weights: Vec<f64> = (0..30)
            .map(|i| 1.0 + 0.5 * (i as f64).cos().abs())
            .collect();
        curves.push(Curve::Nurbs(
            NurbsCurve::new(3, knots(3, 30), wave(30, 2), weights.clone()).unwrap(),
        ));
        // more points than one chunk for every kind
        let n = 3 * Progress::items_per_step(1) + 5;
        let stop = AtomicBool::new(false);
        for c in &curves {
            let ts = c.uniform_parameters(n);
            let mut plain = vec![0.0; n * c.dim()];
            c.eval_batch(&ts, &mut plain).unwrap();
            let seen = Mutex::new(Vec::new());
            let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
            let hooked = Progress::new().with_report(&report).with_cancel(&stop);
            let mut out = vec![0.0; n * c.dim()];
            c.eval_batch_with_progress(&ts, &mut out, &hooked).unwrap();
            let same = plain
                .iter()
                .zip(&out)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{}: the hook changed a point", c.type_name());
            let seen = seen.into_inner().unwrap();
            assert!(seen.len() > 2, "{}: reported in chunks", c.type_name());
            assert!(seen.windows(2).all(|w| w[0].0 <= w[1].0), "monotone");
            assert_eq!(
                seen.last(),
                Some(&(n as u64, n as u64)),
                "reaches the total"
            );
            let sampled = c
                .sample_with_progress(n, &Progress::new().with_cancel(&stop))
                .unwrap();
            assert_eq!(sampled, c.sample(n).unwrap(), "{}: sampling", c.type_name());
        }
        let net = wave(6 * 5, 3);
        let s = BSplineSurface::new(3, 2, knots(3, 6), knots(2, 5), net.clone(), (6, 5)).unwrap();
        let w: Vec<f64> = weights[..30].to_vec();
        let r = NurbsSurface::new(3, 2, knots(3, 6), knots(2, 5), net, w, (6, 5)).unwrap();
        let uv: Vec<[f64; 2]> = (0..n)
            .map(|i| [i as f64 / n as f64, (i * 7 % n) as f64 / n as f64])
            .collect();
        type Eval<'e> = &'e dyn Fn(&Progress<'_>, &mut [f64]) -> Result<()>;
        let surfaces: [Eval<'_>; 2] = [
            &|p, out| s.eval_batch_with_progress(&uv, out, p),
            &|p, out| r.eval_batch_with_progress(&uv, out, p),
        ];
        let mut plain = vec![0.0; n * 3];
        s.eval_batch(&uv, &mut plain).unwrap();
        let mut rational = vec![0.0; n * 3];
        r.eval_batch(&uv, &mut rational).unwrap();
        for (eval, plain) in surfaces.iter().zip([&plain, &rational]) {
            let mut out = vec![0.0; n * 3];
            eval(&Progress::new().with_cancel(&stop), &mut out).unwrap();
            let same = plain
                .iter()
                .zip(&out)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "a surface point changed with the hook");
        }
        stop.store(true, Ordering::Relaxed);
        let cancelled = Progress::new().with_cancel(&stop);
        for c in &curves {
            let ts = c.uniform_parameters(n);
            let mut out = vec![0.0; n * c.dim()];
            let e = c.eval_batch_with_progress(&ts, &mut out, &cancelled);
            assert!(
                matches!(e, Err(Error::Cancelled { .. })),
                "{}: {e:?}",
                c.type_name()
            );
            let e = c.sample_with_progress(n, &cancelled);
            assert!(matches!(e, Err(Error::Cancelled { .. })), "{e:?}");
        }
        for eval in surfaces {
            let mut out = vec![0.0; n * 3];
            let e = eval(&cancelled, &mut out);
            assert!(matches!(e, Err(Error::Cancelled { .. })), "{e:?}");
        }
    }
}
