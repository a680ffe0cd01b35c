//! How the fits report to a [`Progress`] hook (crate-private plumbing, no arithmetic): the
//! iterations whose number is not known ahead (knot rounds, smoothing weights, GCV scores) count
//! [`Steps`]; a single pass over the data checks the hook every few thousand rows
//! ([`checked_rows`]). The hook is consulted between units of work only, so a fit gives the same
//! bits with or without it.

use std::cell::Cell;

use crate::error::{Error, Result};
use crate::numeric::progress::Progress;

/// A counter of the steps of an iteration of unknown length: step `d` reports `(d, d + 1)`, or
/// `(d, e)` while fewer than `e` steps are expected ([`Steps::expect`]), so `done` never goes
/// back and `total` stays ahead until [`Steps::finish`] reports `(done, done)`.
pub(crate) struct Steps<'a, 'p> {
    progress: &'a Progress<'p>,
    what: &'static str,
    done: Cell<u64>,
    expected: Cell<u64>,
}

impl<'a, 'p> Steps<'a, 'p> {
    /// No step done yet.
    pub(crate) fn new(progress: &'a Progress<'p>, what: &'static str) -> Self {
        Steps {
            progress,
            what,
            done: Cell::new(0),
            expected: Cell::new(0),
        }
    }

    /// At least `more` steps follow (e.g. the points of a scan): the total reported is that of
    /// the steps done and expected, for a bar that fills rather than stays at its end.
    pub(super) fn expect(&self, more: u64) {
        self.expected.set(self.done.get() + more);
    }

    /// One more step: reports it, then checks the cancel flag.
    ///
    /// # Errors
    /// [`Error::Cancelled`] once the cancel flag is set.
    pub(crate) fn tick(&self) -> Result<()> {
        let d = self.done.get() + 1;
        self.done.set(d);
        self.progress
            .step(self.what, d, (d + 1).max(self.expected.get()))
    }

    /// The work is complete: reports `(done, done)`. A cancel flag set now is not an error (the
    /// result is there).
    pub(crate) fn finish(&self) {
        let d = self.done.get();
        // the result is complete: a flag set this late does not discard it
        let _ = self.progress.step(self.what, d, d);
    }
}

/// `indices` (a pass over `total` data rows, each of about `cost` operations) with a report and
/// a check of the cancel flag every [`Progress::items_per_step`]`(cost)` rows; once cancelled it
/// stops yielding and leaves the error in `stopped`, which the caller returns after the pass.
pub(super) fn checked_rows<'s>(
    progress: &'s Progress<'_>,
    what: &'static str,
    total: usize,
    cost: u64,
    indices: impl Iterator<Item = usize> + 's,
    stopped: &'s Cell<Option<Error>>,
) -> impl Iterator<Item = usize> + 's {
    let every = Progress::items_per_step(cost);
    let total = total as u64;
    indices.enumerate().map_while(move |(i, k)| {
        if i % every == 0 {
            if let Err(e) = progress.step(what, i as u64, total) {
                stopped.set(Some(e));
                return None;
            }
        }
        Some(k)
    })
}

#[cfg(test)]
pub(super) mod tests {
    //! What every fit's progress test checks, shared by the tests of the fit modules.
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Mutex;

    use crate::error::{Error, Result};
    use crate::numeric::progress::Progress;

    /// Runs `fit` with no hook, with a report and an unset cancel flag, and with a set flag:
    /// the hooked result equals the plain one (`same` compares them bit for bit), the reports are
    /// monotone in `done`, never exceed `total` and end at `done == total`, and the set flag
    /// gives [`Error::Cancelled`].
    pub(in crate::fit) fn check_hook<T: std::fmt::Debug>(
        name: &str,
        fit: impl Fn(&Progress<'_>) -> Result<T>,
        same: impl Fn(&T, &T) -> bool,
    ) {
        let plain = fit(&Progress::new()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let seen = Mutex::new(Vec::new());
        let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
        let stop = AtomicBool::new(false);
        let hooked = fit(&Progress::new().with_report(&report).with_cancel(&stop))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(same(&plain, &hooked), "{name}: the hook changed the fit");
        let seen = seen.into_inner().unwrap();
        assert!(seen.len() >= 2, "{name}: reports {seen:?}");
        assert!(
            seen.windows(2).all(|w| w[0].0 <= w[1].0),
            "{name}: reports go back {seen:?}"
        );
        assert!(seen.iter().all(|&(d, t)| d <= t), "{name}: done > total");
        let last = seen[seen.len() - 1];
        assert_eq!(last.0, last.1, "{name}: the last report is the total");
        stop.store(true, Ordering::Relaxed);
        let e = fit(&Progress::new().with_cancel(&stop));
        assert!(
            matches!(e, Err(Error::Cancelled { .. })),
            "{name}: a set flag gave {e:?}"
        );
    }

    /// Bit equality of two float slices.
    pub(in crate::fit) fn same_bits(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// Bit equality of two curve fits: knots, control points and the report's residuals.
    fn same_fit(a: &crate::fit::CurveFit, b: &crate::fit::CurveFit) -> bool {
        same_bits(a.curve.knots().as_slice(), b.curve.knots().as_slice())
            && same_bits(
                a.curve.control_points().as_slice(),
                b.curve.control_points().as_slice(),
            )
            && same_bits(&a.report.residuals, &b.report.residuals)
            && a.report.lambda.map(f64::to_bits) == b.report.lambda.map(f64::to_bits)
    }

    /// Noisy samples of a wave at `m` parameters spread over `[0, span)`.
    fn wave(m: usize, span: f64) -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..m).map(|k| span * k as f64 / m as f64).collect();
        let y = x
            .iter()
            .enumerate()
            .map(|(k, t)| t.sin() + 0.3 * (3.0 * t).cos() + 0.01 * ((k * 7919 % 13) as f64 - 6.0))
            .collect();
        (x, y)
    }

    /// Every fit with a `*_with_progress` variant: the same bits with the hook, monotone
    /// reports ending at the total, and a set flag stops it. Enough points that the row passes
    /// report in several blocks.
    #[test]
    fn every_fit_with_a_hook_is_unchanged_reports_forward_and_stops_when_cancelled() {
        use crate::fit::*;
        use crate::{KnotVector, PointsRef};
        use std::f64::consts::TAU;
        let (x, y) = wave(3000, TAU);
        let pts = PointsRef::from_flat(1, &y).unwrap();
        let data = FitData::new(pts, &x).unwrap();
        let kv = KnotVector::clamped_uniform(3, 40).unwrap();
        let kv =
            KnotVector::new(kv.as_slice().iter().map(|t| t * x[x.len() - 1]).collect()).unwrap();
        let ends = EndConstraints::points();
        check_hook(
            "least squares",
            |p| least_squares_with_progress(&data, 3, &kv, &ends, p),
            same_fit,
        );
        for lambda in [Lambda::Gcv, Lambda::Given(1e-3)] {
            check_hook(
                "smoothing spline",
                |p| smoothing_spline_with_progress(&data, lambda, p),
                same_fit,
            );
        }
        check_hook(
            "smoothing condition",
            |p| smoothing_condition_with_progress(&data, 3, 0.2, p),
            same_fit,
        );
        check_hook(
            "smoothing on knots",
            |p| smoothing_on_knots_with_progress(&data, 3, &kv, 0.3, p),
            same_fit,
        );
        let breaks: Vec<f64> = (0..=24).map(|j| TAU * j as f64 / 24.0).collect();
        check_hook(
            "closed least squares",
            |p| periodic_least_squares_with_progress(&data, 3, &breaks, p),
            same_fit,
        );
        check_hook(
            "closed smoothing condition",
            |p| periodic_smoothing_condition_with_progress(&data, 3, 0.2, (0.0, TAU), p),
            same_fit,
        );
        check_hook(
            "closed smoothing on knots",
            |p| periodic_smoothing_on_knots_with_progress(&data, 3, &breaks, 0.3, p),
            same_fit,
        );
        // scattered (u, v, z) over a 50 × 50 grid, 12 × 12 control points
        let side = 50;
        let mut uvz = Vec::with_capacity(side * side * 3);
        for i in 0..side {
            for j in 0..side {
                let (u, v) = (i as f64 / (side - 1) as f64, j as f64 / (side - 1) as f64);
                uvz.extend([
                    u,
                    v,
                    (3.0 * u).sin() * (2.0 * v).cos() + 0.001 * ((i * j) % 7) as f64,
                ]);
            }
        }
        let uvz = PointsRef::from_flat(3, &uvz).unwrap();
        let ku = KnotVector::clamped_uniform(3, 12).unwrap();
        for penalty in [0.0, 1e-4] {
            check_hook(
                "scattered surface",
                |p| {
                    surface_scattered_least_squares_with_progress(
                        uvz,
                        None,
                        (3, 3),
                        (&ku, &ku),
                        penalty,
                        p,
                    )
                },
                |a, b| {
                    same_bits(
                        a.surface.control_points().as_slice(),
                        b.surface.control_points().as_slice(),
                    ) && same_bits(&a.residuals, &b.residuals)
                },
            );
        }
    }
}
