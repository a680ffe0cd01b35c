//! Weighted least squares with given knots, with end points and end derivatives imposed exactly
//! (`docs/theory/fitting.md#least-squares`, `#constraints`).

use crate::Arg;
use std::cell::Cell;

use super::banded::{BandedQr, QrRows};
use super::data::{check_in_domain, CurveFit, FitData, FitReport};
use super::progress::checked_rows;
use super::rows::for_each_row;
use crate::error::{check_degree_bound, check_finite, Error, Result};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::Points;
use crate::BSplineCurve;

/// End conditions imposed exactly on a least-squares fit (Piegl & Tiller §9.4.1, A9.6/A9.7):
/// the curve starts at the first data point and/or ends at the last, optionally with given
/// first derivatives there. Each condition fixes a control point of the clamped curve,
/// `P_0 = Q_0`, `P_1 = Q_0 + D_0 (t_{p+1} − t_1)/p`, `P_n = Q_m`,
/// `P_{n−1} = Q_m − D_m (t_{n+p} − t_n)/p`, which is then eliminated from the problem.
///
/// ```
/// use lekalo::fit::EndConstraints;
/// let ends = EndConstraints::points().with_start_derivative(vec![1.0, 0.0]);
/// assert!(ends.start_point && ends.end_point);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EndConstraints {
    /// `C(a) = Q_0`, the first data point.
    pub start_point: bool,
    /// `C(b) = Q_m`, the last data point.
    pub end_point: bool,
    /// `C'(a) = D_0` (needs `start_point`).
    pub start_derivative: Option<Vec<f64>>,
    /// `C'(b) = D_m` (needs `end_point`).
    pub end_derivative: Option<Vec<f64>>,
}

impl EndConstraints {
    /// No constraint: the plain least-squares problem.
    #[must_use]
    pub fn none() -> Self {
        Self::default()
    }

    /// Both end points interpolated (P&T A9.6).
    #[must_use]
    pub fn points() -> Self {
        EndConstraints {
            start_point: true,
            end_point: true,
            ..Self::default()
        }
    }

    /// Adds `C'(a) = d` (and the start point).
    #[must_use]
    pub fn with_start_derivative(mut self, d: Vec<f64>) -> Self {
        self.start_point = true;
        self.start_derivative = Some(d);
        self
    }

    /// Adds `C'(b) = d` (and the end point).
    #[must_use]
    pub fn with_end_derivative(mut self, d: Vec<f64>) -> Self {
        self.end_point = true;
        self.end_derivative = Some(d);
        self
    }
}

/// The number of control points of the splines of `degree` on `knots`, after the checks every
/// fit on given knots makes: the degree's bound, enough valid knots, and the data parameters in
/// the domain.
pub(super) fn spline_space(data: &FitData<'_>, degree: usize, knots: &KnotVector) -> Result<usize> {
    check_degree_bound(degree)?;
    let n_ctrl = knots
        .len()
        .checked_sub(degree + 1)
        .ok_or_else(|| Error::Degree {
            degree,
            reason: format!("{} knots carry no spline of this degree", knots.len()),
        })?;
    knots.validate_for(degree, n_ctrl)?;
    check_in_domain(data.params(), knots.domain(degree))?;
    Ok(n_ctrl)
}

/// The weighted least-squares B-spline of `degree` on `knots`: minimises
/// `Σ_k w_k |C(ū_k) − Q_k|²` over the control points (SciPy's `make_lsq_spline`; P&T §9.4.1),
/// subject to `ends`, which are imposed exactly by eliminating the control points they fix.
///
/// Solved by banded QR as the rows arrive, Householder reflections of blocks of rows with the
/// same non-zero columns (`docs/theory/fitting.md#banded-qr`; FITPACK rotates each row in by
/// Givens rotations, `fpgivs`/`fprota`): no normal equations, no dense matrix; O(N·p·(p + dim))
/// time and O(n·(p + dim)) memory for `N` points and `n` control points. The data are shifted by
/// their first point before the solve (exact by partition of unity), so data far from the origin
/// keep their digits.
///
/// ```
/// use lekalo::fit::{least_squares, EndConstraints, FitData};
/// use lekalo::{KnotVector, PointsRef};
/// // samples of a cubic polynomial are reproduced exactly by any cubic spline space
/// let x: Vec<f64> = (0..20).map(|k| k as f64 / 19.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| 1.0 - 2.0 * t + t * t * t).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0])?;
/// let fit = least_squares(&data, 3, &kv, &EndConstraints::none())?;
/// assert!(fit.report.max_residual < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`] and the knot errors of [`KnotVector::validate_for`];
/// [`Error::ParameterOutOfDomain`] for a data parameter outside the knots' domain;
/// [`Error::SchoenbergWhitney`] when the data leave a basis function without support (a knot
/// span without data, or more control points than distinct parameters);
/// [`Error::Dimension`] / [`Error::NonFinite`] for a bad end derivative;
/// [`Error::InvalidArgument`] for an end condition on an end that is not clamped, or a derivative
/// without its end point; [`Error::TooFew`] when the end conditions fix more control points than
/// there are.
pub fn least_squares(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    ends: &EndConstraints,
) -> Result<CurveFit> {
    least_squares_with_progress(data, degree, knots, ends, &Progress::new())
}

/// [`least_squares`] reporting to `progress` as the data rows are rotated in (`done` rows of
/// `total` data points, a report every few thousand rows, then `(total, total)` once solved),
/// and stopping with [`Error::Cancelled`] between two blocks of rows when its cancel flag is
/// set. The result is the same with or without the hook.
///
/// # Errors
/// As [`least_squares`], and [`Error::Cancelled`].
pub fn least_squares_with_progress(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    ends: &EndConstraints,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    let curve = fit_curve(data, degree, knots, ends, progress)?;
    let report = FitReport::new(&curve, data, None);
    let n = data.len() as u64;
    // the fit is complete: a flag set this late does not discard it
    let _ = progress.step(LSQ_WORK, n, n);
    Ok(CurveFit { curve, report })
}

/// The curve of [`least_squares`] without its [`FitReport`]: the same solve, the same bits,
/// without the report's second pass over the data (a basis evaluation and a residual a point,
/// and an array of the residuals), for callers that measure the fit their own way (SciPy's
/// `make_lsq_spline` and `LSQUnivariateSpline`).
///
/// ```
/// use lekalo::fit::{least_squares, least_squares_curve, EndConstraints, FitData};
/// use lekalo::{KnotVector, PointsRef};
/// let x: Vec<f64> = (0..20).map(|k| k as f64 / 19.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| (3.0 * t).sin()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0])?;
/// let ends = EndConstraints::none();
/// let curve = least_squares_curve(&data, 3, &kv, &ends)?;
/// assert_eq!(curve, least_squares(&data, 3, &kv, &ends)?.curve);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`least_squares`].
pub fn least_squares_curve(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    ends: &EndConstraints,
) -> Result<BSplineCurve> {
    fit_curve(data, degree, knots, ends, &Progress::new())
}

/// [`least_squares_curve`] with the weighted residual sum of squares of the fit,
/// `fp = Σ_k w_k |C(ū_k) − Q_k|²`, as FITPACK's `curfit` reports it (Dierckx, *Curve and
/// Surface Fitting with Splines*, 1993, §4.1.2): the squares of the right-hand sides reflected
/// out of the banded triangle as the rows arrive. With `A = QR`, `‖Ax − y‖² = ‖Rx − z‖² +
/// ‖(Qᵀy)_{n..}‖²` and the least-squares `x` makes the first term zero, so `fp` is the second:
/// no evaluation pass over the data after the solve. Orthogonal transformations keep the
/// reflected-out vector within a small multiple of `ε·‖√w y‖` of its exact value (Golub & Van
/// Loan §5.3.3), the same order as the rounding of evaluating the `N` residuals one by one (each
/// within about `ε·|y_k|`), so the two agree to rounding relative to the data (tested); SciPy's
/// `LSQUnivariateSpline.get_residual()` returns FITPACK's rotated-out sum.
///
/// ```
/// use lekalo::fit::{least_squares, least_squares_curve_rss, EndConstraints, FitData};
/// use lekalo::{KnotVector, PointsRef};
/// let x: Vec<f64> = (0..40).map(|k| k as f64 / 39.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| (7.0 * t).sin()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0])?;
/// let (curve, fp) = least_squares_curve_rss(&data, 3, &kv, &EndConstraints::none())?;
/// let fit = least_squares(&data, 3, &kv, &EndConstraints::none())?;
/// assert_eq!(curve.control_points().as_slice(), fit.curve.control_points().as_slice());
/// assert!((fp - fit.report.weighted_rss).abs() <= 1e-13 * fp.max(1e-300));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`least_squares`].
pub fn least_squares_curve_rss(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    ends: &EndConstraints,
) -> Result<(BSplineCurve, f64)> {
    fit_curve_rss(data, degree, knots, ends, &Progress::new())
}

/// The checks of [`least_squares`] without end constraints and the banded QR of its weighted
/// data rows, `QR = √W B` for the weights divided by the largest (right-hand sides: the data
/// minus their first point); returns the number of control points and the QR. Its triangle `R`
/// (`RᵀR = BᵀWB`, the weights so divided) depends on the parameters, knots and weights, not on
/// the data values: the derivatives of the fit apply it
/// ([`crate::derivatives::LeastSquaresMap`], `docs/theory/derivatives.md#fits`).
///
/// # Errors
/// As [`least_squares`] with [`EndConstraints::none`], before the solve.
pub(crate) fn least_squares_qr(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
) -> Result<(usize, BandedQr)> {
    let n_ctrl = spline_space(data, degree, knots)?;
    super::knot_placement::check_schoenberg_whitney(data.params(), degree, knots)?;
    let fixed = Fixed::free(data);
    let qr = accumulate(
        data,
        degree,
        knots,
        n_ctrl,
        &fixed,
        degree + 1,
        &Progress::new(),
    )?;
    Ok((n_ctrl, qr))
}

/// The control points of [`least_squares`] with [`EndConstraints::none`] (flat, `n × dim`, the
/// same bits: the same checks, rows and solve) and the QR they were solved with
/// ([`least_squares_qr`]), for a caller that differentiates the fit after its values and would
/// otherwise factor the same rows again.
///
/// # Errors
/// As [`least_squares`] with [`EndConstraints::none`].
pub(crate) fn least_squares_values_and_qr(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
) -> Result<(Vec<f64>, BandedQr)> {
    let (n_ctrl, qr) = least_squares_qr(data, degree, knots)?;
    let control = solve_control(&qr, data, degree, knots, n_ctrl, &Fixed::free(data))?;
    Ok((control.into_vec(), qr))
}

/// The solve of [`least_squares_with_progress`], up to the curve.
fn fit_curve(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    ends: &EndConstraints,
    progress: &Progress<'_>,
) -> Result<BSplineCurve> {
    fit_curve_rss(data, degree, knots, ends, progress).map(|(curve, _)| curve)
}

/// [`fit_curve`] and the sum of the squares rotated out (see [`least_squares_curve_rss`]).
fn fit_curve_rss(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    ends: &EndConstraints,
    progress: &Progress<'_>,
) -> Result<(BSplineCurve, f64)> {
    let n_ctrl = spline_space(data, degree, knots)?;
    let fixed = Fixed::new(data, degree, knots, n_ctrl, ends)?;
    if fixed.count() == 0 {
        super::knot_placement::check_schoenberg_whitney(data.params(), degree, knots)?;
    }
    let qr = accumulate(data, degree, knots, n_ctrl, &fixed, degree + 1, progress)?;
    let control = solve_control(&qr, data, degree, knots, n_ctrl, &fixed)?;
    let curve = BSplineCurve::from_raw(degree, knots.as_slice().to_vec(), control);
    Ok((curve, qr.rss))
}

/// What a least-squares pass reports to a [`Progress`] hook.
const LSQ_WORK: &str = "least-squares fit (data rows)";

/// Control points fixed by end conditions, relative to the reference point `center`.
#[derive(Debug, Clone, Default)]
pub(crate) struct Fixed {
    /// The data's reference point (the first data point).
    pub(crate) center: Vec<f64>,
    /// `P_0, P_1, …` fixed at the start, flat, minus `center`.
    pub(crate) start: Vec<f64>,
    /// `…, P_{n−1}, P_n` fixed at the end, flat, minus `center`.
    pub(crate) end: Vec<f64>,
}

impl Fixed {
    /// No fixed control point; the reference point is the first data point.
    pub(crate) fn free(data: &FitData<'_>) -> Self {
        Fixed {
            center: data.points().point(0).to_vec(),
            ..Fixed::default()
        }
    }

    fn new(
        data: &FitData<'_>,
        degree: usize,
        knots: &KnotVector,
        n_ctrl: usize,
        ends: &EndConstraints,
    ) -> Result<Self> {
        let mut f = Fixed::free(data);
        let pts = data.points();
        let dim = pts.dim();
        let t = knots.as_slice();
        let p = degree;
        let check_derivative = |d: &Option<Vec<f64>>, has_point: bool, end: &str| -> Result<()> {
            if let Some(d) = d {
                if d.len() != dim {
                    return Err(Error::Dimension {
                        what: "end derivative of a least-squares fit".into(),
                        expected: dim,
                        got: d.len(),
                    });
                }
                check_finite(Arg::EndDerivative, d)?;
                if !has_point {
                    return Err(Error::InvalidArgument {
                        what: "end constraints".into(),
                        reason: format!(
                            "a derivative at the {end} needs the {end} point interpolated too \
                             (set the point constraint)"
                        ),
                    });
                }
            }
            Ok(())
        };
        check_derivative(&ends.start_derivative, ends.start_point, "start")?;
        check_derivative(&ends.end_derivative, ends.end_point, "end")?;
        let clamped_start = t[..=p].iter().all(|&v| v == t[0]);
        let clamped_end = t[n_ctrl..].iter().all(|&v| v == t[t.len() - 1]);
        let unclamped = |end: &str| Error::InvalidArgument {
            what: "end constraints".into(),
            reason: format!(
                "the knots are not clamped at the {end} (degree + 1 equal end knots), so the \
                 {end} point is not a control point; use clamped knots"
            ),
        };
        if ends.start_point {
            if !clamped_start {
                return Err(unclamped("start"));
            }
            let q0 = pts.point(0);
            f.start.extend(q0.iter().zip(&f.center).map(|(q, c)| q - c));
            if let Some(d) = &ends.start_derivative {
                let h = (t[p + 1] - t[1]) / p.max(1) as f64;
                let p1: Vec<f64> = (0..dim).map(|c| f.start[c] + d[c] * h).collect();
                f.start.extend(p1);
            }
        }
        if ends.end_point {
            if !clamped_end {
                return Err(unclamped("end"));
            }
            let qm = pts.point(pts.len() - 1);
            let pn: Vec<f64> = qm.iter().zip(&f.center).map(|(q, c)| q - c).collect();
            if let Some(d) = &ends.end_derivative {
                let h = (t[n_ctrl + p - 1] - t[n_ctrl - 1]) / p.max(1) as f64;
                f.end.extend((0..dim).map(|c| pn[c] - d[c] * h));
            }
            f.end.extend(pn);
        }
        if p == 0 && (ends.start_derivative.is_some() || ends.end_derivative.is_some()) {
            return Err(Error::InvalidArgument {
                what: "end constraints".into(),
                reason: "a piecewise constant curve has no end derivative; use degree ≥ 1".into(),
            });
        }
        if f.count() > n_ctrl {
            return Err(Error::TooFew {
                what: "control points for the end conditions (each fixes one or two)".into(),
                min: f.count(),
                got: n_ctrl,
            });
        }
        Ok(f)
    }

    /// Number of fixed control points.
    pub(crate) fn count(&self) -> usize {
        let dim = self.center.len().max(1);
        (self.start.len() + self.end.len()) / dim
    }
}

/// Rotates every data row into a banded QR of the free control points (band `bw ≥ p + 1`).
/// Rows with zero weight are skipped; weights are divided by the largest one (the minimiser is
/// unchanged) so that no square overflows. The result's `rss` is the sum of the squares rotated
/// out of the right-hand sides in the data's own weights (multiplied back by the largest): the
/// weighted residual sum of squares of the least-squares solution (see
/// [`least_squares_curve_rss`]). `progress` is told of the rows done and may stop
/// the pass between two blocks of rows.
///
/// # Errors
/// [`Error::Cancelled`] when `progress`'s cancel flag is set.
pub(crate) fn accumulate(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    n_ctrl: usize,
    fixed: &Fixed,
    bw: usize,
    progress: &Progress<'_>,
) -> Result<BandedQr> {
    let pts = data.points();
    let dim = pts.dim();
    let ks = fixed.start.len() / dim;
    let ke = fixed.end.len() / dim;
    let n_free = n_ctrl - ks - ke;
    let mut qr = QrRows::new(n_free, bw, dim);
    let wmax = data
        .weights()
        .map_or(1.0, |w| w.iter().fold(0.0_f64, |m, &v| m.max(v)));
    let mut y = vec![0.0; dim];
    let mut h = vec![0.0; degree + 1];
    // √(w_k / w_max), without a square root for unweighted data (each row reads it twice: the
    // basis row and the right-hand side are scaled by it)
    let weights = data.weights();
    let scale = |k: usize| weights.map_or(1.0, |w| (w[k] / wmax).sqrt());
    let mut on_row = |k: usize, span: usize, nb: &[f64]| {
        let sw = scale(k);
        if sw == 0.0 {
            return;
        }
        let first = span - degree;
        for (yc, (q, o)) in y.iter_mut().zip(pts.point(k).iter().zip(&fixed.center)) {
            *yc = sw * (q - o);
        }
        // nb = √w·N: the fixed control points' share of the row (first and last spans only)
        let touches_fixed = first < ks || first + degree + 1 > n_ctrl - ke;
        if !touches_fixed {
            // the usual row: its p + 1 columns all unknowns, taken as they are
            qr.push(first - ks, nb, &y);
            return;
        }
        for (a, &b) in nb.iter().enumerate() {
            let col = first + a;
            let fixed_point = if col < ks {
                Some(&fixed.start[col * dim..(col + 1) * dim])
            } else if col >= n_ctrl - ke {
                let e = col - (n_ctrl - ke);
                Some(&fixed.end[e * dim..(e + 1) * dim])
            } else {
                None
            };
            if let Some(pf) = fixed_point {
                for (yc, pc) in y.iter_mut().zip(pf) {
                    *yc -= b * pc;
                }
            }
        }
        let lo = first.max(ks);
        let hi = (first + degree + 1).min(n_ctrl - ke);
        if lo < hi {
            let len = hi - lo;
            h[..len].copy_from_slice(&nb[lo - first..hi - first]);
            qr.push(lo - ks, &h[..len], &y);
        } else {
            qr.add_residual(&y);
        }
    };
    let params = data.params();
    let stopped = Cell::new(None);
    let cost = ((degree + 1) * (bw + dim)) as u64;
    let n = data.len();
    match data.order() {
        None => {
            let rows = checked_rows(progress, LSQ_WORK, n, cost, 0..n, &stopped);
            for_each_row(knots, degree, params, rows, scale, &mut on_row);
        }
        Some(order) => {
            let rows = checked_rows(progress, LSQ_WORK, n, cost, order.into_iter(), &stopped);
            for_each_row(knots, degree, params, rows, scale, &mut on_row);
        }
    }
    match stopped.take() {
        Some(e) => Err(e),
        None => {
            let mut qr = qr.finish();
            // the squares rotated out, of rows scaled by 1/√w_max: back to the data's weights
            qr.rss *= wmax;
            Ok(qr)
        }
    }
}

/// Back-substitutes the free control points and assembles all of them (plus the reference
/// point).
///
/// # Errors
/// [`Error::SchoenbergWhitney`] naming the basis function whose column is rank-deficient.
pub(crate) fn solve_control(
    qr: &BandedQr,
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    n_ctrl: usize,
    fixed: &Fixed,
) -> Result<Points> {
    let dim = data.points().dim();
    let ks = fixed.start.len() / dim;
    let mut x = vec![0.0; qr.n() * dim];
    if let Err(col) = qr.solve(&mut x) {
        let t = knots.as_slice();
        let j = col + ks;
        return Err(Error::SchoenbergWhitney {
            basis: j,
            start: t[j],
            end: t[j + degree + 1],
        });
    }
    Ok(assemble(&x, fixed, n_ctrl, dim))
}

/// `[fixed start, free, fixed end] + center` as control points.
pub(crate) fn assemble(free: &[f64], fixed: &Fixed, n_ctrl: usize, dim: usize) -> Points {
    let mut all = Vec::with_capacity(n_ctrl * dim);
    all.extend_from_slice(&fixed.start);
    all.extend_from_slice(free);
    all.extend_from_slice(&fixed.end);
    for p in all.chunks_exact_mut(dim) {
        for (v, c) in p.iter_mut().zip(&fixed.center) {
            *v += c;
        }
    }
    Points::from_raw(all, dim)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::PointsRef;

    fn sample(curve: &BSplineCurve, u: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; u.len() * curve.dim()];
        curve.eval_batch(u, &mut out).unwrap();
        out
    }

    #[test]
    fn end_constraints_hold_exactly() {
        let u: Vec<f64> = (0..50).map(|k| k as f64 / 49.0).collect();
        let q: Vec<f64> = u
            .iter()
            .flat_map(|&t| [(3.0 * t).sin() + 0.01 * (40.0 * t).cos(), t * t])
            .collect();
        let data = FitData::new(PointsRef::from_flat(2, &q).unwrap(), &u).unwrap();
        let kv = KnotVector::clamped_uniform(3, 8).unwrap();
        let ends = EndConstraints::points()
            .with_start_derivative(vec![3.0, 0.0])
            .with_end_derivative(vec![-2.0, 2.0]);
        let fit = least_squares(&data, 3, &kv, &ends).unwrap();
        let c = &fit.curve;
        let d0 = c.eval_derivatives(0.0, 1).unwrap();
        let d1 = c.eval_derivatives(1.0, 1).unwrap();
        for k in 0..2 {
            assert!((d0.point(0)[k] - q[k]).abs() < 1e-14, "start point");
            assert!((d1.point(0)[k] - q[98 + k]).abs() < 1e-14, "end point");
        }
        assert!(
            (d0.point(1)[0] - 3.0).abs() < 1e-12 && d0.point(1)[1].abs() < 1e-12,
            "start derivative {:?}",
            d0.point(1)
        );
        assert!(
            (d1.point(1)[0] + 2.0).abs() < 1e-12 && (d1.point(1)[1] - 2.0).abs() < 1e-12,
            "end derivative {:?}",
            d1.point(1)
        );
        // the constrained fit is no better than the free one
        let free = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
        assert!(
            free.report.weighted_rss <= fit.report.weighted_rss,
            "free fit is optimal"
        );
    }

    /// FITPACK's `fp` read off the QR is the weighted residual sum of squares evaluated at the
    /// data, to rounding relative to the data: weighted or not, in 1-D and 2-D, with end
    /// constraints (rows fixed out), for data far from the origin, and zero-weight rows skipped.
    #[test]
    fn rotated_out_squares_are_the_weighted_residual() {
        let u: Vec<f64> = (0..300).map(|k| (k as f64 / 299.0).powf(1.3)).collect();
        for (dim, offset) in [(1, 0.0), (2, 0.0), (1, 1e6)] {
            let q: Vec<f64> = u
                .iter()
                .enumerate()
                .flat_map(|(k, &t)| {
                    let noise = 0.01 * ((k * 7919 % 101) as f64 / 50.0 - 1.0);
                    [offset + (9.0 * t).sin() + noise, t * t - noise][..dim].to_vec()
                })
                .collect();
            let w: Vec<f64> = (0..300)
                .map(|k| {
                    if k % 37 == 0 {
                        0.0
                    } else {
                        0.5 + (k % 5) as f64
                    }
                })
                .collect();
            let kv = KnotVector::clamped_uniform(3, 20).unwrap();
            for weighted in [false, true] {
                let mut data = FitData::new(PointsRef::from_flat(dim, &q).unwrap(), &u).unwrap();
                if weighted {
                    data = data.with_weights(&w).unwrap();
                }
                for ends in [EndConstraints::none(), EndConstraints::points()] {
                    let (curve, fp) = least_squares_curve_rss(&data, 3, &kv, &ends).unwrap();
                    let fit = least_squares(&data, 3, &kv, &ends).unwrap();
                    assert_eq!(
                        curve.control_points().as_slice(),
                        fit.curve.control_points().as_slice(),
                        "the same solve"
                    );
                    let want = fit.report.weighted_rss;
                    // rounding of the residuals relative to the data's size
                    let scale = q.iter().map(|v| v * v).sum::<f64>().sqrt();
                    assert!(
                        (fp - want).abs() <= 1e-12 * want + 1e-20 * scale * scale,
                        "dim {dim}, offset {offset}, weighted {weighted}, {ends:?}: {fp} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn unsorted_parameters_give_the_same_fit() {
        let u: Vec<f64> = (0..40).map(|k| ((k * 17) % 40) as f64 / 39.0).collect();
        let q: Vec<f64> = u.iter().map(|&t| (5.0 * t).sin()).collect();
        let data = FitData::new(PointsRef::from_flat(1, &q).unwrap(), &u).unwrap();
        let kv = KnotVector::clamped_uniform(3, 9).unwrap();
        let a = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
        let mut pairs: Vec<(f64, f64)> = u.iter().copied().zip(q.iter().copied()).collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (us, qs): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
        let data = FitData::new(PointsRef::from_flat(1, &qs).unwrap(), &us).unwrap();
        let b = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
        let (ea, eb) = (sample(&a.curve, &us), sample(&b.curve, &us));
        for (x, y) in ea.iter().zip(&eb) {
            assert!((x - y).abs() < 1e-13, "{x} vs {y}");
        }
    }

    #[test]
    fn constraint_errors_are_named() {
        let u = [0.0, 0.25, 0.5, 0.75, 1.0];
        let q = [0.0, 1.0, 0.0, 1.0, 0.0];
        let data = FitData::new(PointsRef::from_flat(1, &q).unwrap(), &u).unwrap();
        let kv = KnotVector::clamped_uniform(2, 4).unwrap();
        let bad_dim = EndConstraints::points().with_start_derivative(vec![1.0, 2.0]);
        assert!(
            matches!(
                least_squares(&data, 2, &kv, &bad_dim),
                Err(Error::Dimension { .. })
            ),
            "dimension"
        );
        let no_point = EndConstraints {
            start_derivative: Some(vec![1.0]),
            ..EndConstraints::none()
        };
        assert!(
            matches!(
                least_squares(&data, 2, &kv, &no_point),
                Err(Error::InvalidArgument { .. })
            ),
            "derivative without point"
        );
        let uniform = KnotVector::new(vec![-0.5, -0.25, 0.0, 0.5, 1.0, 1.25, 1.5]).unwrap();
        let e = least_squares(&data, 2, &uniform, &EndConstraints::points()).unwrap_err();
        assert!(
            matches!(e, Error::InvalidArgument { .. }),
            "unclamped: {e:?}"
        );
        let kv1 = KnotVector::clamped_uniform(1, 2).unwrap();
        let all = EndConstraints::points().with_start_derivative(vec![1.0]);
        let e = least_squares(&data, 1, &kv1, &all).unwrap_err();
        assert!(matches!(e, Error::TooFew { .. }), "over-constrained: {e:?}");
        let e = least_squares(
            &data,
            2,
            &KnotVector::clamped_uniform(2, 6).unwrap(),
            &EndConstraints::none(),
        )
        .unwrap_err();
        assert!(
            matches!(e, Error::SchoenbergWhitney { .. }),
            "too many control points: {e:?}"
        );
    }
}
