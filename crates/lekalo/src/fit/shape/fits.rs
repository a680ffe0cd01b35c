//! Least squares and smoothing splines of functions `y(x)` that keep their shape
//! (`docs/theory/fitting.md#shape-constraints`): the unconstrained fit first, the cone program of
//! `working_set.rs` when it breaks a constraint.

use super::check::{holds, Scale};
use super::constraints::ShapeConstraints;
use super::program::{gram_of_triangle, triangle_transpose_times};
use super::working_set::{curve_of, scaled, solve_program, Rows};
use crate::error::{Error, Result};
use crate::fit::data::{CurveFit, FitData, FitReport};
use crate::fit::knot_placement::check_schoenberg_whitney;
use crate::fit::lsq::{accumulate, solve_control, spline_space, Fixed};
use crate::fit::progress::Steps;
use crate::fit::smoothing::Smoother;
use crate::fit::{smoothing_spline, Lambda};
use crate::knots::KnotVector;
use crate::message::readable;
use crate::numeric::progress::Progress;
use crate::BSplineCurve;
use crate::{Arg, What};

/// What the steps of the cone program of a shape-constrained fit are reported as.
const SHAPE_STEPS: &str = "shape-constrained fit";

/// The weighted least-squares spline of `degree` on `knots` (as [`least_squares`]) that keeps
/// `constraints`: the minimiser of `Σ_k w_k (y(x_k) − y_k)²` over the splines satisfying every
/// shape on its interval for **every** `x` (not only at samples) and every point equality.
///
/// Each shape `σ(y⁽ʳ⁾ − v) ≥ 0` becomes conditions on the Bernstein coefficients of `y⁽ʳ⁾` on
/// each piece of a knot span inside its interval (linear in the control points), exact where
/// the constrained derivative has degree `d = p − r ≤ 3`: `d ≤ 1` by the coefficients' signs, `d = 2`
/// by a rotated second-order cone `b₁ + √(b₀b₂) ≥ 0`, `d = 3` by two such cones (the cubic as
/// `τ·q₁ + (1 − τ)·q₂` with quadratics non-negative on the line, Markov–Lukács). For `d ≥ 4` the
/// coefficient signs are sufficient only (the fit is feasible but may be the optimum of a
/// slightly stricter problem).
/// The data are reduced by banded QR to the triangle `R` (one pass, as [`least_squares`]: the
/// same triangle gives the unconstrained fit); the cone program with the banded `RᵀR` is
/// solved by Clarabel (interior point), so the work after the pass over the data grows with
/// the number of coefficients only. Only the pieces near or past their bounds enter the
/// program: a working set grown until its optimum keeps every row, which makes it the whole
/// program's optimum (`docs/theory/fitting.md#shape-constraints`).
///
/// When the unconstrained fit already satisfies every constraint (to [`SHAPE_RTOL`](super::SHAPE_RTOL)) it is
/// returned unchanged. Functions only: the data are 1-D (`y` over parameters `x`).
///
/// ```
/// use lekalo::fit::{constrained_least_squares, FitData, Shape, ShapeConstraints};
/// use lekalo::{KnotVector, PointsRef};
/// let x: Vec<f64> = (0..40).map(|k| k as f64 / 39.0).collect();
/// // a rising signal with a dip
/// let y: Vec<f64> = x.iter().map(|t| t + 0.1 * (12.0 * t).sin()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let kv = KnotVector::clamped_uniform(3, 10)?;
/// let c = ShapeConstraints::new().with(Shape::Increasing);
/// let fit = constrained_least_squares(&data, 3, &kv, &c)?;
/// let v = lekalo::fit::shape_violations(&fit.curve, &c)?;
/// assert!(v[0] <= 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// The errors of [`least_squares`]; [`Error::Dimension`] for data that are not 1-D;
/// [`Error::InvalidArgument`] / [`Error::NonFinite`] for a constraint outside the domain or with
/// a bad number; [`Error::InfeasibleConstraints`] naming the constraints that contradict each
/// other; [`Error::IllConditioned`] if the solver stops without an answer.
///
/// [`least_squares`]: crate::fit::least_squares
pub fn constrained_least_squares(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    constraints: &ShapeConstraints,
) -> Result<CurveFit> {
    constrained_least_squares_by(data, degree, knots, constraints, Rows::WorkingSet)
}

/// [`constrained_least_squares`] with the rows of the cone program chosen by `strategy`.
pub(crate) fn constrained_least_squares_by(
    data: &FitData<'_>,
    degree: usize,
    knots: &KnotVector,
    constraints: &ShapeConstraints,
    strategy: Rows,
) -> Result<CurveFit> {
    check_function_data(data)?;
    let n_ctrl = spline_space(data, degree, knots)?;
    let domain = knots.domain(degree);
    constraints.validate(domain, degree)?;
    check_schoenberg_whitney(data.params(), degree, knots)?;
    // one pass over the data: the triangle gives the unconstrained fit (as `least_squares`,
    // the same operations) and the objective of the constrained one
    let fixed = Fixed::free(data);
    let bw = degree + 1;
    let qr = accumulate(data, degree, knots, n_ctrl, &fixed, bw, &Progress::new())?;
    let scale = Scale::of(data, domain);
    let free = BSplineCurve::from_raw(
        degree,
        knots.as_slice().to_vec(),
        solve_control(&qr, data, degree, knots, n_ctrl, &fixed)?,
    );
    if holds(&free, constraints, &scale)? {
        let report = FitReport::new(&free, data, None);
        return Ok(CurveFit {
            curve: free,
            report,
        });
    }
    // ½‖Rc − z‖² with c and z in units of the data scale
    let p = gram_of_triangle(&qr.r, n_ctrl, bw);
    let z: Vec<f64> = qr.z.iter().map(|v| v / scale.y).collect();
    let q: Vec<f64> = triangle_transpose_times(&qr.r, &z, n_ctrl, bw)
        .into_iter()
        .map(|v| -v)
        .collect();
    let start = scaled(&free, &scale, fixed.center[0]);
    let coef = solve_program(
        p,
        q,
        knots.as_slice(),
        degree,
        constraints,
        &scale,
        fixed.center[0],
        &start,
        strategy,
        &Steps::new(&Progress::new(), SHAPE_STEPS),
    )?;
    let curve = curve_of(
        degree,
        knots.as_slice().to_vec(),
        &coef,
        &scale,
        fixed.center[0],
    );
    let report = FitReport::new(&curve, data, None);
    Ok(CurveFit { curve, report })
}

/// The cubic smoothing spline of [`smoothing_spline`] that keeps `constraints`: the minimiser of
/// `Σ_k w_k (y(x_k) − y_k)² + λ ∫ y''²` over the cubic splines with knots at the data
/// (the space of the unconstrained minimiser) satisfying every shape for every `x` of its
/// interval and every point equality. With [`Lambda::Gcv`], λ is the one generalised
/// cross-validation chooses for the unconstrained spline. Exactness per shape as in
/// [`constrained_least_squares`] with `p = 3`: increasing/decreasing (`d = 2`, cone) and
/// convex/concave (`d = 1`) and bounds (`d = 3`, two cones) all exact.
///
/// When the unconstrained spline already satisfies every constraint (to [`SHAPE_RTOL`](super::SHAPE_RTOL)) it is
/// returned unchanged. The objective is the banded `BᵀWB + λΩ` of [`smoothing_spline`].
///
/// ```
/// use lekalo::fit::{constrained_smoothing_spline, FitData, Lambda, Shape, ShapeConstraints};
/// use lekalo::PointsRef;
/// let x: Vec<f64> = (0..30).map(|k| k as f64 / 29.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| (t - 0.5).abs() + 0.05 * (20.0 * t).cos()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let c = ShapeConstraints::new().with(Shape::Convex);
/// let fit = constrained_smoothing_spline(&data, Lambda::Given(1e-4), &c)?;
/// assert!(lekalo::fit::shape_violations(&fit.curve, &c)?[0] <= 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// The errors of [`smoothing_spline`] and of [`constrained_least_squares`]'s constraints;
/// [`Error::NegativeSmoothing`] for `λ ≤ 0` given (the constrained problem needs the penalty).
pub fn constrained_smoothing_spline(
    data: &FitData<'_>,
    lambda: Lambda,
    constraints: &ShapeConstraints,
) -> Result<CurveFit> {
    constrained_smoothing_spline_with_progress(data, lambda, constraints, &Progress::new())
}

/// [`constrained_smoothing_spline`] reporting to `progress` and stopping when it is cancelled:
/// the GCV scores (with [`Lambda::Gcv`]), then the rounds of the working set and of the polish
/// of the cone program, each reported as one step of unknown total (`(done, done + 1)`, then
/// `(done, done)` at the end). The hook never changes the result.
///
/// # Errors
/// Those of [`constrained_smoothing_spline`]; [`Error::Cancelled`] once `progress` is cancelled.
pub fn constrained_smoothing_spline_with_progress(
    data: &FitData<'_>,
    lambda: Lambda,
    constraints: &ShapeConstraints,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    // one count for the GCV scores and the cone program's rounds, so that `done` never goes back
    let steps = Steps::new(progress, SHAPE_STEPS);
    let fit = spline_in_steps(data, lambda, constraints, &steps)?;
    steps.finish();
    Ok(fit)
}

/// [`constrained_smoothing_spline_with_progress`] counting its GCV scores and rounds on `steps`
/// (left unfinished, for a caller that fits several λ on one count).
fn spline_in_steps(
    data: &FitData<'_>,
    lambda: Lambda,
    constraints: &ShapeConstraints,
    steps: &Steps<'_, '_>,
) -> Result<CurveFit> {
    check_function_data(data)?;
    if let Lambda::Given(l) = lambda {
        if !(l > 0.0 && l.is_finite()) {
            return Err(Error::NegativeSmoothing {
                what: What::of(
                    Arg::Lambda,
                    "λ (a shape-constrained smoothing spline needs λ > 0)",
                ),
                value: l,
            });
        }
    }
    let s = Smoother::new(data)?;
    let lam = match lambda {
        Lambda::Given(l) => l,
        Lambda::Gcv => s.minimise_gcv(steps)?,
    };
    let n = s.knots.len() - 4;
    let domain = (s.knots[0], s.knots[s.knots.len() - 1]);
    constraints.validate(domain, 3)?;
    let free = smoothing_spline(data, Lambda::Given(lam))?;
    let scale = Scale::of(data, domain);
    if holds(&free.curve, constraints, &scale)? {
        return Ok(free);
    }
    let mut p = s.gram.clone();
    for (a, o) in p.a.iter_mut().zip(&s.omega.a) {
        *a += lam * o;
    }
    debug_assert_eq!(p.n, n, "one coefficient per B-spline");
    let q: Vec<f64> = s.rhs.iter().map(|v| -v / scale.y).collect();
    let center = s.center[0];
    let start = scaled(&free.curve, &scale, center);
    let coef = solve_program(
        p,
        q,
        &s.knots,
        3,
        constraints,
        &scale,
        center,
        &start,
        Rows::WorkingSet,
        steps,
    )?;
    let curve = curve_of(3, s.knots.clone(), &coef, &scale, center);
    let report = FitReport::new(&curve, data, Some(lam));
    Ok(CurveFit { curve, report })
}

/// The shape-constrained cubic smoothing spline of [`constrained_smoothing_spline`] whose
/// weighted residual sum of squares `Σ_k w_k (y(x_k) − y_k)²` is `s` (Reinsch's smoothing
/// condition, 1967, on the space of the smoothing spline: knots at the data, the penalty weight λ
/// found instead of knots; `docs/theory/fitting.md#shape-constraints`). The residual of the
/// constrained optimum never decreases as λ grows (a penalised least-squares problem over a
/// convex set), so λ is bracketed by factors of ten from the generalised cross-validation choice
/// and then found by bisection in `log λ` until the residual is within [`CONDITION_RTOL`] of
/// `s`. Where even the straight line (λ → ∞) leaves less than `s`, the fit at the largest λ
/// tried is returned; its residual is then below `s`.
///
/// ```
/// use lekalo::fit::{constrained_smoothing_condition, FitData, Shape, ShapeConstraints};
/// use lekalo::PointsRef;
/// let x: Vec<f64> = (0..40).map(|k| k as f64 / 39.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| t * t + 0.02 * (40.0 * t).sin()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let c = ShapeConstraints::new().with(Shape::Increasing);
/// let fit = constrained_smoothing_condition(&data, 2e-3, &c)?;
/// assert!((fit.report.weighted_rss - 2e-3).abs() <= 1e-3 * 2e-3);
/// assert!(lekalo::fit::shape_violations(&fit.curve, &c)?[0] <= 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// The errors of [`constrained_smoothing_spline`]; [`Error::NegativeSmoothing`] for `s < 0` or
/// not finite; [`Error::InvalidArgument`] when the constraints leave a residual above `s` at every
/// λ (the message gives the least residual they allow).
pub fn constrained_smoothing_condition(
    data: &FitData<'_>,
    s: f64,
    constraints: &ShapeConstraints,
) -> Result<CurveFit> {
    constrained_smoothing_condition_with_progress(data, s, constraints, &Progress::new())
}

/// [`constrained_smoothing_condition`] reporting to `progress` and stopping when it is
/// cancelled: the steps of every constrained smoothing spline it fits (GCV scores, rounds of
/// the cone program) on one count of unknown total, as
/// [`constrained_smoothing_spline_with_progress`] reports them. The hook never changes the
/// result.
///
/// # Errors
/// Those of [`constrained_smoothing_condition`]; [`Error::Cancelled`] once `progress` is
/// cancelled.
pub fn constrained_smoothing_condition_with_progress(
    data: &FitData<'_>,
    s: f64,
    constraints: &ShapeConstraints,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    let steps = Steps::new(progress, SHAPE_STEPS);
    let fit = condition_in_steps(data, s, constraints, &steps)?;
    steps.finish();
    Ok(fit)
}

/// [`constrained_smoothing_condition`] counting on `steps`.
fn condition_in_steps(
    data: &FitData<'_>,
    s: f64,
    constraints: &ShapeConstraints,
    steps: &Steps<'_, '_>,
) -> Result<CurveFit> {
    if !(s >= 0.0 && s.is_finite()) {
        return Err(Error::NegativeSmoothing {
            what: Arg::S.into(),
            value: s,
        });
    }
    let start = spline_in_steps(data, Lambda::Gcv, constraints, steps)?;
    let Some(lam0) = start.report.lambda.filter(|l| *l > 0.0) else {
        return Ok(start);
    };
    let fit_at = |lam: f64| spline_in_steps(data, Lambda::Given(lam), constraints, steps);
    let close = |f: &CurveFit| (f.report.weighted_rss - s).abs() <= CONDITION_RTOL * s;
    if close(&start) {
        return Ok(start);
    }
    // bracket: (λ, fit) with the residual below s and above it
    let below = start.report.weighted_rss < s;
    let mut near = (lam0, start);
    for _ in 0..CONDITION_DECADES {
        let lam = if below { near.0 * 10.0 } else { near.0 / 10.0 };
        let f = match fit_at(lam) {
            Ok(f) => f,
            // a penalty so small (or so large) that the system loses its pivots: the search
            // ends at the last λ that could be solved
            Err(Error::SingularSystem { .. } | Error::IllConditioned { .. }) => break,
            Err(e) => return Err(e),
        };
        if close(&f) {
            return Ok(f);
        }
        if (f.report.weighted_rss < s) != below {
            let far = (lam, f);
            let (lo, hi) = if below { (near, far) } else { (far, near) };
            return bisect_condition((lo, hi), s, &fit_at, &close, |f| f.report.weighted_rss);
        }
        near = (lam, f);
    }
    if below {
        // even the straightest fit tried stays below s
        return Ok(near.1);
    }
    Err(least_residual_error(near.1.report.weighted_rss, s))
}

/// The refusal of a smoothing condition `s` below the least residual the shape constraints
/// leave (`residual`, at the smallest penalty tried), curves and surfaces alike: the bound a
/// user types back, four digits rounded up so that it is enough.
pub(super) fn least_residual_error(residual: f64, s: f64) -> Error {
    let least = digits_up(residual);
    Error::InvalidArgument {
        what: What::of(Arg::S, "s (smoothing condition)"),
        reason: format!(
            "the shape constraints leave a residual sum of squares of at least about {least} \
             (at the smallest penalty tried), above s = {s}; give s ≥ {least}, or fewer \
             constraints",
            least = readable(&least),
            s = readable(&s)
        ),
    }
}

/// `x > 0` rounded up to four significant digits (`53.522558…` → `53.53`), as a message
/// suggests a bound; other values unchanged.
pub(super) fn digits_up(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    // the decimal exponent of a finite positive double lies within ±324: the cast is exact
    #[allow(clippy::cast_possible_truncation)]
    let e = x.log10().floor() as i32;
    let scale = 10f64.powi(3 - e);
    let up = (x * scale).ceil() / scale;
    if up >= x && up.is_finite() {
        up
    } else {
        x
    }
}

/// `x` rounded down to four significant digits (the bound to quote where a value must not be
/// exceeded), as [`digits_up`] rounds up.
pub(super) fn digits_down(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    // the decimal exponent of a finite positive double lies within ±324: the cast is exact
    #[allow(clippy::cast_possible_truncation)]
    let e = x.log10().floor() as i32;
    let scale = 10f64.powi(3 - e);
    let down = (x * scale).floor() / scale;
    if down <= x && down.is_finite() {
        down
    } else {
        x
    }
}

/// Relative distance of the residual from `s` at which [`constrained_smoothing_condition`]
/// stops (FITPACK's `|fp − s| ≤ 0.001·s`).
pub const CONDITION_RTOL: f64 = 1e-3;

/// Decades of λ searched either side of the cross-validation choice.
pub(super) const CONDITION_DECADES: usize = 16;

/// Bisection steps in `log λ` (each halves the bracket's ratio).
pub(super) const CONDITION_STEPS: usize = 80;

/// Bisection in `log λ` between a fit whose residual is below `s` and one above, until a fit
/// is `close` to `s` or the bracket can no longer be split; the nearer end then. Shared by the
/// curves' and the surfaces' smoothing conditions (`residual` reads a fit's).
pub(super) fn bisect_condition<F>(
    (mut lo, mut hi): ((f64, F), (f64, F)),
    s: f64,
    fit_at: &dyn Fn(f64) -> Result<F>,
    close: &dyn Fn(&F) -> bool,
    residual: fn(&F) -> f64,
) -> Result<F> {
    for _ in 0..CONDITION_STEPS {
        let lam = (lo.0 * hi.0).sqrt();
        if lam <= lo.0 || lam >= hi.0 {
            break;
        }
        let f = fit_at(lam)?;
        if close(&f) {
            return Ok(f);
        }
        if residual(&f) < s {
            lo = (lam, f);
        } else {
            hi = (lam, f);
        }
    }
    // the nearer of the two ends
    let d = |f: &F| (residual(f) - s).abs();
    Ok(if d(&lo.1) <= d(&hi.1) { lo.1 } else { hi.1 })
}

/// Refuses data that are not a function `y(x)`.
fn check_function_data(data: &FitData<'_>) -> Result<()> {
    if data.points().dim() != 1 {
        return Err(Error::Dimension {
            what: "data of a shape-constrained fit (values y over x)".into(),
            expected: 1,
            got: data.points().dim(),
        });
    }
    Ok(())
}
