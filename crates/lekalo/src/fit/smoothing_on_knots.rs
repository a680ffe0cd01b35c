//! Smoothing on given knots: the spline on a fixed knot vector whose `k`-th derivative jumps
//! least, subject to a residual of `s` (FITPACK `curfit` step 3 on the caller's knots, SciPy's
//! `make_splrep(x, y, t=…, s=…)`; `docs/theory/fitting.md#smoothing-on-given-knots`).

use super::data::{CurveFit, FitData};
use super::knot_placement::check_schoenberg_whitney;
use super::lsq::spline_space;
use super::progress::Steps;
use super::smoothing_condition::{
    back_substitute, check_condition_args, finish, smooth_on, LsqPass, Observations,
};
use crate::error::Result;
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;

/// The B-spline of `degree` on `knots` that minimises `Σ_j (jump of C^{(k)} at t_j)²` over the
/// interior knots subject to `Σ_k w_k |C(ū_k) − Q_k|² = s` (Dierckx, "Curve and Surface Fitting
/// with Splines", 1993, ch. 5: the smoothing criterion on a fixed knot set).
///
/// With the Lagrange multiplier written as `p`, the minimiser is the least-squares solution of
/// the data rows stacked on the jump rows divided by `p` (FITPACK's `fpdisc`); its residual
/// `fp(p)` decreases from the least-squares polynomial on `[t_k, t_{n}]` (`p = 0`) to the
/// least-squares spline on `knots` (`p = ∞`), and `p` with `fp(p) = s` is found by FITPACK's
/// rational interpolation from `p = n / trace R`, each step a banded QR of the data's triangle
/// `R` and the `p`-scaled jump rows (O(n·k²), no pass over the data). The result has
/// `(1 − SMOOTHING_RTOL)·s ≤ fp ≤ s` whenever `s` lies between the two ends. Outside, no `p`
/// satisfies the condition: when the least-squares spline's residual is above `s` the result is
/// that spline (the smallest residual on these knots, which the report shows); when the
/// polynomial's is below `s`, the result tends to the polynomial. A knot vector without interior
/// knots gives the least-squares polynomial. The same computation as SciPy's
/// `make_splrep(x, y, t=t, s=s)` and FITPACK's `curfit(iopt=1)` step 3, so the coefficients are
/// SciPy's to rounding.
///
/// ```
/// use lekalo::fit::{smoothing_on_knots, FitData};
/// use lekalo::{KnotVector, PointsRef};
/// let x: Vec<f64> = (0..100).map(|k| k as f64 / 99.0).collect();
/// let y: Vec<f64> = x.iter().enumerate().map(|(k, t)| (6.0 * t).sin() + 0.01 * ((k * 7919 % 13) as f64 - 6.0)).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.0, 1.0, 1.0])?;
/// let fit = smoothing_on_knots(&data, 3, &kv, 0.3)?;
/// assert!(fit.report.weighted_rss <= 0.3 && fit.report.weighted_rss >= 0.3 * (1.0 - 1e-3));
/// assert_eq!(fit.curve.knots().as_slice(), kv.as_slice());
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::NegativeSmoothing`](crate::Error::NegativeSmoothing) for `s < 0` or NaN;
/// [`Error::Degree`](crate::Error::Degree) for degree 0 and the errors of
/// [`least_squares`](super::least_squares) on given knots: knots that do not suit the degree,
/// data outside their domain, [`Error::SchoenbergWhitney`](crate::Error::SchoenbergWhitney)
/// when a basis function has no data.
pub fn smoothing_on_knots(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    s: f64,
) -> Result<CurveFit> {
    smoothing_on_knots_with_progress(data, degree, knots, s, &Progress::new())
}

/// [`smoothing_on_knots`] reporting to `progress` after the least-squares passes and each
/// smoothing weight tried (`done` the steps so far, `total` one more; `(done, done)` at the end),
/// and stopping with [`Error::Cancelled`](crate::Error::Cancelled) between two steps when its
/// cancel flag is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`smoothing_on_knots`], and [`Error::Cancelled`](crate::Error::Cancelled).
pub fn smoothing_on_knots_with_progress(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    s: f64,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    check_condition_args(degree, s)?;
    let steps = Steps::new(progress, "smoothing on given knots (weights)");
    let n_ctrl = spline_space(data, degree, knots)?;
    check_schoenberg_whitney(data.params(), degree, knots)?;
    let k = degree;
    let t = knots.as_slice();
    let obs = Observations::new(data);
    let mut pass = LsqPass::new(&obs, k);
    steps.tick()?;
    let qr = pass.run(&obs, t);
    if n_ctrl == k + 1 {
        // no interior knot: nothing to smooth
        let c = back_substitute(&qr)?;
        steps.finish();
        return Ok(finish(data, &obs, k, t.to_vec(), &c, None));
    }
    let (a, b) = (t[k], t[n_ctrl]);
    let mut poly = Vec::with_capacity(2 * k + 2);
    poly.extend(std::iter::repeat_n(a, k + 1));
    poly.extend(std::iter::repeat_n(b, k + 1));
    steps.tick()?;
    let fp0 = pass.run(&obs, &poly).rss;
    let (c, lambda) = smooth_on(&obs, k, t, &qr, s, fp0, qr.rss, &steps)?;
    let fit = finish(data, &obs, k, t.to_vec(), &c, lambda);
    steps.finish();
    Ok(fit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::{least_squares, smoothing_condition, EndConstraints, SMOOTHING_RTOL};
    use crate::PointsRef;
    use proptest::prelude::*;

    fn noisy(m: usize) -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..m).map(|i| i as f64 / (m - 1) as f64).collect();
        let y = x
            .iter()
            .enumerate()
            .map(|(i, t)| (5.0 * t).sin() + 0.05 * (((i * 7919) % 17) as f64 - 8.0) / 8.0)
            .collect();
        (x, y)
    }

    #[test]
    fn on_the_knots_of_the_smoothing_condition_it_is_the_smoothing_condition() {
        let (x, y) = noisy(80);
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let auto = smoothing_condition(&data, 3, 0.05).unwrap();
        assert!(
            auto.report.lambda.is_some(),
            "the reference fit is smoothed"
        );
        let kv = KnotVector::new(auto.curve.knots().as_slice().to_vec()).unwrap();
        let fixed = smoothing_on_knots(&data, 3, &kv, 0.05).unwrap();
        assert_eq!(
            fixed.curve.control_points().as_slice(),
            auto.curve.control_points().as_slice()
        );
    }

    #[test]
    fn no_interior_knot_is_the_least_squares_polynomial() {
        let (x, y) = noisy(30);
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).unwrap();
        let fit = smoothing_on_knots(&data, 2, &kv, 1e-3).unwrap();
        let lsq = least_squares(&data, 2, &kv, &EndConstraints::none()).unwrap();
        let (a, b) = (
            fit.curve.control_points().as_slice(),
            lsq.curve.control_points().as_slice(),
        );
        for (u, v) in a.iter().zip(b) {
            assert!((u - v).abs() < 1e-12, "{u} vs {v}");
        }
    }

    #[test]
    fn s_below_the_least_squares_spline_gives_that_spline() {
        let (x, y) = noisy(50);
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0]).unwrap();
        let lsq = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
        let fit = smoothing_on_knots(&data, 3, &kv, 0.5 * lsq.report.weighted_rss).unwrap();
        assert!(fit.report.lambda.is_none(), "not smoothed");
        let rel = (fit.report.weighted_rss - lsq.report.weighted_rss) / lsq.report.weighted_rss;
        assert!(rel.abs() < 1e-12, "residual {rel}");
    }

    #[test]
    fn refuses_a_basis_function_without_data() {
        let x = [0.0, 0.1, 0.2, 0.9, 1.0];
        let y = [0.0, 1.0, 0.0, 1.0, 0.0];
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let kv = KnotVector::new(vec![0.0, 0.0, 0.4, 0.5, 0.6, 1.0, 1.0]).unwrap();
        let e = smoothing_on_knots(&data, 1, &kv, 0.1).unwrap_err();
        assert!(matches!(e, crate::Error::SchoenbergWhitney { .. }), "{e:?}");
    }

    /// The case a property run found: the range of the residual (polynomial to least-squares
    /// spline) is narrower than the accuracy asked of s, and the continued iteration used to
    /// aim below the spline's residual and drive p to a singular system.
    #[test]
    fn a_residual_range_narrower_than_the_accuracy() {
        let (m, k, interior, frac) = (31, 5, 1, 0.05);
        let (x, y) = noisy(m);
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let mut t = vec![0.0; k + 1];
        t.extend((1..=interior).map(|j| j as f64 / (interior + 1) as f64));
        t.extend(std::iter::repeat_n(1.0, k + 1));
        let kv = KnotVector::new(t).unwrap();
        let mut p = vec![0.0; k + 1];
        p.extend(std::iter::repeat_n(1.0, k + 1));
        let poly = KnotVector::new(p).unwrap();
        let none = EndConstraints::none();
        let fp_inf = least_squares(&data, k, &kv, &none)
            .unwrap()
            .report
            .weighted_rss;
        let fp0 = least_squares(&data, k, &poly, &none)
            .unwrap()
            .report
            .weighted_rss;
        let s = fp_inf + frac * (fp0 - fp_inf);
        let fp = smoothing_on_knots(&data, k, &kv, s)
            .unwrap()
            .report
            .weighted_rss;
        assert!(
            fp <= s && fp >= s * (1.0 - SMOOTHING_RTOL),
            "fp {fp}, s {s}"
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// Between the polynomial's residual and the least-squares spline's, the residual at
        /// convergence is s within the documented relative accuracy, never above.
        #[test]
        fn residual_is_s_at_convergence(
            m in 20usize..120,
            k in 1usize..6,
            interior in 1usize..8,
            frac in 0.05f64..0.95,
        ) {
            let (x, y) = noisy(m);
            let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
            let mut t = vec![0.0; k + 1];
            t.extend((1..=interior).map(|j| j as f64 / (interior + 1) as f64));
            t.extend(std::iter::repeat_n(1.0, k + 1));
            let kv = KnotVector::new(t).unwrap();
            let poly = {
                let mut p = vec![0.0; k + 1];
                p.extend(std::iter::repeat_n(1.0, k + 1));
                KnotVector::new(p).unwrap()
            };
            let fp_inf = least_squares(&data, k, &kv, &EndConstraints::none()).unwrap().report.weighted_rss;
            let fp0 = least_squares(&data, k, &poly, &EndConstraints::none()).unwrap().report.weighted_rss;
            prop_assume!(fp0 - fp_inf > 1e-6 * fp0);
            let s = fp_inf + frac * (fp0 - fp_inf);
            let fit = smoothing_on_knots(&data, k, &kv, s).unwrap();
            let fp = fit.report.weighted_rss;
            prop_assert!(fp <= s * (1.0 + 1e-12), "fp {} above s {}", fp, s);
            prop_assert!(fp >= s * (1.0 - SMOOTHING_RTOL), "fp {} below s {} by more than the tolerance", fp, s);
            prop_assert_eq!(fit.curve.knots().as_slice(), kv.as_slice());
        }
    }
}
