//! Least squares and smoothing splines of functions `y(x)` that keep their shape, and the exact
//! check of a curve against shape constraints (`docs/theory/fitting.md#shape-constraints`).

use super::bernstein::{bernstein_rows, min_on_unit, pieces};
use super::constraints::ShapeConstraints;
use super::program::{failure_error, gram_of_triangle, triangle_transpose_times, ConeProgram};
use super::row::Row;
use crate::basis::{basis_ders_into, BasisScratch};
use crate::error::{Error, Result};
use crate::fit::banded::SymBand;
use crate::fit::data::{CurveFit, FitData, FitReport};
use crate::fit::knot_placement::check_schoenberg_whitney;
use crate::fit::lsq::{accumulate, solve_control, spline_space, Fixed};
use crate::fit::progress::Steps;
use crate::fit::smoothing::Smoother;
use crate::fit::{smoothing_spline, Lambda};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::Points;
use crate::BSplineCurve;
use crate::{Arg, What};

/// Violation, relative to the data's scale, below which a constraint counts as holding when the
/// unconstrained fit is tested (then it is returned unchanged) and when the constrained one is
/// checked. The scale of `y⁽ʳ⁾` is `Y / L^r`, `Y` the largest `|y_k − y_0|` and `L` the length
/// of the domain.
pub const SHAPE_RTOL: f64 = 5e-13;

/// The weighted least-squares spline of `degree` on `knots` (as [`least_squares`]) that keeps
/// `constraints`: the minimiser of `Σ_k w_k (y(x_k) − y_k)²` over the splines satisfying every
/// shape on its interval for **every** `x` (not only at samples) and every point equality.
///
/// Each shape `σ(y⁽ʳ⁾ − v) ≥ 0` becomes conditions on the Bernstein coefficients of `y⁽ʳ⁾` on
/// each piece of a knot span inside its interval (linear in the control points), exact where
/// the constrained derivative has degree `d = p − r ≤ 2`: `d ≤ 1` by the coefficients' signs, `d = 2`
/// by a rotated second-order cone `b₁ + √(b₀b₂) ≥ 0`. For `d ≥ 3` the coefficient signs are
/// sufficient only (the fit is feasible but may be the optimum of a slightly stricter problem).
/// The data are reduced by banded QR to the triangle `R` (one pass, as [`least_squares`]: the
/// same triangle gives the unconstrained fit); the cone program with the banded `RᵀR` is
/// solved by Clarabel (interior point), so the work after the pass over the data grows with
/// the number of coefficients only. Only the pieces near or past their bounds enter the
/// program: a working set grown until its optimum keeps every row, which makes it the whole
/// program's optimum (`docs/theory/fitting.md#shape-constraints`).
///
/// When the unconstrained fit already satisfies every constraint (to [`SHAPE_RTOL`]) it is
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
/// convex/concave (`d = 1`) exact, bounds (`d = 3`) sufficient only.
///
/// When the unconstrained spline already satisfies every constraint (to [`SHAPE_RTOL`]) it is
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
            return bisect_condition(lo, hi, s, &fit_at, &close);
        }
        near = (lam, f);
    }
    if below {
        // even the straightest fit tried stays below s
        return Ok(near.1);
    }
    let least = near.1.report.weighted_rss;
    Err(Error::InvalidArgument {
        what: What::of(Arg::S, "s (smoothing condition)"),
        reason: format!(
            "the shape constraints leave a residual sum of squares of at least about {least:e} \
             (at the smallest penalty tried), above s = {s:e}; give s ≥ {least:e}, or fewer \
             constraints"
        ),
    })
}

/// Relative distance of the residual from `s` at which [`constrained_smoothing_condition`]
/// stops (FITPACK's `|fp − s| ≤ 0.001·s`).
pub const CONDITION_RTOL: f64 = 1e-3;

/// Decades of λ searched either side of the cross-validation choice.
const CONDITION_DECADES: usize = 16;

/// Bisection steps in `log λ` (each halves the bracket's ratio).
const CONDITION_STEPS: usize = 80;

/// Bisection in `log λ` between a fit whose residual is below `s` and one above.
fn bisect_condition(
    mut lo: (f64, CurveFit),
    mut hi: (f64, CurveFit),
    s: f64,
    fit_at: &dyn Fn(f64) -> Result<CurveFit>,
    close: &dyn Fn(&CurveFit) -> bool,
) -> Result<CurveFit> {
    for _ in 0..CONDITION_STEPS {
        let lam = (lo.0 * hi.0).sqrt();
        if lam <= lo.0 || lam >= hi.0 {
            break;
        }
        let f = fit_at(lam)?;
        if close(&f) {
            return Ok(f);
        }
        if f.report.weighted_rss < s {
            lo = (lam, f);
        } else {
            hi = (lam, f);
        }
    }
    // the nearer of the two ends
    let d = |f: &CurveFit| (f.report.weighted_rss - s).abs();
    Ok(if d(&lo.1) <= d(&hi.1) { lo.1 } else { hi.1 })
}

/// For each constraint (shapes, then points), by how much `curve` violates it (0 when it holds):
/// `max(0, −min σ(y⁽ʳ⁾ − v))` over the interval for a shape, `|y⁽ʳ⁾(x) − value|` for a point.
/// The minimum on each piece of a knot span is exact for `d = p − r ≤ 3` (end values and the
/// roots of the derivative by the quadratic formula) and a lower bound for `d ≥ 4` (least
/// Bernstein coefficient on 64 sub-pieces), so a reported 0 always means the shape holds.
///
/// # Errors
/// [`Error::Dimension`] for a curve that is not 1-D; the constraint errors of
/// [`constrained_least_squares`].
pub fn shape_violations(curve: &BSplineCurve, constraints: &ShapeConstraints) -> Result<Vec<f64>> {
    if curve.dim() != 1 {
        return Err(Error::Dimension {
            what: "curve checked against shape constraints (a function y(x))".into(),
            expected: 1,
            got: curve.dim(),
        });
    }
    constraints.validate(curve.domain(), curve.degree())?;
    ShapeCheck::new(curve, constraints).violations(curve, constraints)
}

/// The Bernstein rows of every shape's pieces ([`bernstein_rows`]), computed once from the
/// degree and knots: the exact check of [`shape_violations`] for any control points on them.
struct ShapeCheck {
    shapes: Vec<ShapeRows>,
}

/// One shape's check: `σ(y⁽ʳ⁾ − v)` with `r` above the degree (`y⁽ʳ⁾ ≡ 0`, the violation
/// known), or the rows of each piece with the index of its first control point.
enum ShapeRows {
    Constant(f64),
    Pieces {
        sigma: f64,
        level: f64,
        rows: Vec<(usize, Vec<Vec<f64>>)>,
    },
}

impl ShapeCheck {
    fn new(curve: &BSplineCurve, constraints: &ShapeConstraints) -> Self {
        let p = curve.degree();
        let t = curve.knots().as_slice();
        let n_ctrl = curve.control_points().len();
        let domain = curve.domain();
        let mut scratch = BasisScratch::new(p);
        let shapes = constraints
            .shapes
            .iter()
            .map(|s| {
                let r = s.shape.derivative_order();
                let (sigma, level) = (s.shape.sign(), s.shape.level());
                if r > p {
                    return ShapeRows::Constant((sigma * level).max(0.0));
                }
                let (a, b) = s.interval.unwrap_or(domain);
                let rows = pieces(t, p, n_ctrl, a, b)
                    .into_iter()
                    .map(|(span, lo, hi)| {
                        (
                            span - p,
                            bernstein_rows(t, p, span, lo, hi, r, &mut scratch),
                        )
                    })
                    .collect();
                ShapeRows::Pieces { sigma, level, rows }
            })
            .collect();
        ShapeCheck { shapes }
    }

    /// [`shape_violations`] of `curve` (on the degree and knots this check was made for).
    fn violations(&self, curve: &BSplineCurve, constraints: &ShapeConstraints) -> Result<Vec<f64>> {
        let ctrl = curve.control_points().as_slice();
        let mut out = Vec::with_capacity(constraints.len());
        let mut bc = Vec::new();
        for s in &self.shapes {
            out.push(match s {
                ShapeRows::Constant(v) => *v,
                ShapeRows::Pieces { sigma, level, rows } => {
                    let mut worst = 0.0_f64;
                    for (first, m) in rows {
                        bc.clear();
                        bc.extend(m.iter().map(|row| {
                            let y: f64 = row.iter().zip(&ctrl[*first..]).map(|(a, c)| a * c).sum();
                            sigma * (y - level)
                        }));
                        worst = worst.max(-min_on_unit(&bc));
                    }
                    worst
                }
            });
        }
        for q in &constraints.points {
            let y = curve
                .eval_derivatives(q.x, q.derivative)?
                .point(q.derivative)[0];
            out.push((y - q.value).abs());
        }
        Ok(out)
    }
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

/// The scales of the problem: values in units of `y`, derivatives of order `r` in `y / L^r`.
struct Scale {
    y: f64,
    length: f64,
}

impl Scale {
    fn of(data: &FitData<'_>, (lo, hi): (f64, f64)) -> Self {
        let v = data.points().as_slice();
        let y = v.iter().fold(0.0_f64, |m, q| m.max((q - v[0]).abs()));
        Scale {
            y: if y > 0.0 { y } else { v[0].abs().max(1.0) },
            length: hi - lo,
        }
    }

    /// The scale of `y⁽ʳ⁾`.
    fn of_derivative(&self, r: usize) -> f64 {
        (0..r).fold(self.y, |s, _| s / self.length)
    }
}

/// Whether `curve` keeps every constraint to [`SHAPE_RTOL`] of the scale.
fn holds(curve: &BSplineCurve, constraints: &ShapeConstraints, scale: &Scale) -> Result<bool> {
    holds_by(
        &ShapeCheck::new(curve, constraints),
        curve,
        constraints,
        scale,
    )
}

/// [`holds`] with the rows of a check made once for the curve's degree and knots.
fn holds_by(
    check: &ShapeCheck,
    curve: &BSplineCurve,
    constraints: &ShapeConstraints,
    scale: &Scale,
) -> Result<bool> {
    let v = check.violations(curve, constraints)?;
    let orders = constraints
        .shapes
        .iter()
        .map(|s| s.shape.derivative_order())
        .chain(constraints.points.iter().map(|q| q.derivative));
    Ok(v.iter()
        .zip(orders)
        .all(|(v, r)| *v <= SHAPE_RTOL * scale.of_derivative(r)))
}

/// Which rows of the cone program are solved: a working set of pieces grown until the answer
/// keeps every row (what the fits use), or every row at once (crate-private, so that tests can
/// compare the two).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Rows {
    /// The working set (`docs/theory/fitting.md#shape-constraints`).
    WorkingSet,
    /// The whole program.
    All,
}

/// The rows of one shape on one piece of a knot span: the unit the working set adds.
struct Piece {
    /// The index of the user's constraint.
    owner: usize,
    /// `d + 1` inequalities (`d ≠ 2`) or the three Bernstein coefficients of a quadratic.
    rows: PieceRows,
}

/// The conditions of a [`Piece`] (`docs/theory/fitting.md#shape-constraints`, the table by `d`).
enum PieceRows {
    /// `b_j ≥ 0` for `d ≠ 2`.
    Linear(Vec<Row>),
    /// `(b₀, b₁, b₂)` of a quadratic `≥ 0` on `[0, 1]` (a cone in the program).
    Quadratic([Row; 3]),
}

impl Piece {
    /// The least value of the piece's conditions at the coefficients `c`, rows scaled to unit
    /// largest coefficient as the solver sees them: the least row for linear conditions, the
    /// exact minimum on `[0, 1]` of the quadratic (its three coefficients scaled together).
    fn slack(&self, c: &[f64], n: usize) -> f64 {
        let unit = |r: &Row, m: f64| r.eval(c, n) / if m > 0.0 { m } else { 1.0 };
        match &self.rows {
            PieceRows::Linear(rows) => rows
                .iter()
                .map(|r| unit(r, r.max_abs()))
                .fold(f64::INFINITY, f64::min),
            PieceRows::Quadratic(b) => {
                let m = b.iter().fold(0.0_f64, |m, r| m.max(r.max_abs()));
                min_on_unit(&b.clone().map(|r| unit(&r, m)))
            }
        }
    }
}

/// Slack (rows scaled to unit largest coefficient, coefficients in units of the data) below
/// which a piece joins the working set: above the polish's activity threshold, so that every
/// row the polish of the whole program would make an equality is in the working set.
const WORKING_MARGIN: f64 = 1e-6;

/// What the steps of the cone program of a shape-constrained fit are reported as.
const SHAPE_STEPS: &str = "shape-constrained fit";

/// Rounds of the working set before the whole program is solved instead.
const WORKING_ROUNDS: usize = 12;

/// Builds and solves the cone program of the constraints for the objective `½cᵀPc + qᵀc` in
/// scaled coefficients `c = (control − center)/Y`; returns the scaled coefficients. With
/// [`Rows::WorkingSet`], `start` (the unconstrained optimum, scaled) chooses the first pieces.
#[allow(clippy::too_many_arguments)] // objective (two), knots, degree, constraints, scales (two), start, strategy
fn solve_program(
    p: SymBand,
    q: Vec<f64>,
    knots: &[f64],
    degree: usize,
    constraints: &ShapeConstraints,
    scale: &Scale,
    center: f64,
    start: &[f64],
    strategy: Rows,
    steps: &Steps<'_, '_>,
) -> Result<Vec<f64>> {
    let n = p.n;
    let mut scratch = BasisScratch::new(degree);
    let domain = (knots[degree], knots[n]);
    let mut pieces_all: Vec<Piece> = Vec::new();
    for (owner, s) in constraints.shapes.iter().enumerate() {
        let r = s.shape.derivative_order();
        if r > degree {
            // y⁽ʳ⁾ ≡ 0 satisfies every derivative shape (levels are 0)
            continue;
        }
        let sigma = s.shape.sign();
        // σ(y⁽ʳ⁾ − v) in scaled units: y⁽ʳ⁾ = Y·c⁽ʳ⁾ + center·[r = 0]
        let level = (s.shape.level() - if r == 0 { center } else { 0.0 }) / scale.y;
        let (a, b) = s.interval.unwrap_or(domain);
        let d = degree - r;
        for (span, lo, hi) in pieces(knots, degree, n, a, b) {
            let m = bernstein_rows(knots, degree, span, lo, hi, r, &mut scratch);
            let first = span - degree;
            let row = |j: usize| Row {
                first,
                coef: m[j].iter().map(|v| sigma * v).collect(),
                aux: None,
                constant: -sigma * level,
            };
            let rows = if d == 2 {
                PieceRows::Quadratic([row(0), row(1), row(2)])
            } else {
                PieceRows::Linear((0..=d).map(row).collect())
            };
            pieces_all.push(Piece { owner, rows });
        }
    }
    let n_shapes = constraints.shapes.len();
    let kv = KnotVector::from_raw(knots.to_vec());
    let mut equalities = Vec::with_capacity(constraints.points.len());
    for (i, c) in constraints.points.iter().enumerate() {
        let span = kv.find_span(degree, c.x)?;
        let w = degree + 1;
        let mut ders = vec![0.0; w * w];
        basis_ders_into(knots, degree, span, c.x, degree, &mut scratch, &mut ders);
        let r = c.derivative;
        let value = (c.value - if r == 0 { center } else { 0.0 }) / scale.y;
        equalities.push((
            Row {
                first: span - degree,
                coef: ders[r * w..(r + 1) * w].to_vec(),
                aux: None,
                constant: -value,
            },
            n_shapes + i,
        ));
    }
    let program = |chosen: &[bool]| {
        let mut prog = ConeProgram::new(p.clone(), q.clone());
        prog.equalities.clone_from(&equalities);
        for (piece, _) in pieces_all.iter().zip(chosen).filter(|(_, c)| **c) {
            match &piece.rows {
                PieceRows::Linear(rows) => prog
                    .inequalities
                    .extend(rows.iter().map(|r| (r.clone(), piece.owner))),
                PieceRows::Quadratic(b) => prog.quadratics.push((b.clone(), piece.owner)),
            }
        }
        prog
    };
    let finish = |prog: &ConeProgram, interior: Vec<f64>| {
        finish_program(
            prog,
            interior,
            (degree, knots),
            constraints,
            (scale, center),
            steps,
        )
    };
    let fail = |f| failure_error(f, |i| constraints.describe(i));
    let all = vec![true; pieces_all.len()];
    if strategy == Rows::All || start.len() != n {
        let prog = program(&all);
        let interior = prog.solve(0.0).map_err(fail)?;
        return finish(&prog, interior);
    }
    // The working set: the pieces the unconstrained optimum violates or nearly violates, and
    // their neighbours of the same constraint; grown by the pieces each answer violates. An
    // answer of the relaxation that keeps every row of the whole program is its optimum.
    let mut chosen = vec![false; pieces_all.len()];
    let grow = |chosen: &mut [bool], c: &[f64]| {
        let mut added = false;
        for i in 0..pieces_all.len() {
            if chosen[i] || pieces_all[i].slack(c, n) >= WORKING_MARGIN {
                continue;
            }
            added = true;
            chosen[i] = true;
            let owner = pieces_all[i].owner;
            for j in [i.wrapping_sub(1), i + 1] {
                if pieces_all.get(j).is_some_and(|pj| pj.owner == owner) {
                    chosen[j] = true;
                }
            }
        }
        added
    };
    grow(&mut chosen, start);
    if equalities.is_empty() && !chosen.contains(&true) {
        // nothing near a bound (the unconstrained fit failed the exact check by rounding only):
        // the program needs a row, and the whole one is small enough then
        chosen.fill(true);
    }
    for _ in 0..WORKING_ROUNDS {
        steps.tick()?;
        let prog = program(&chosen);
        let interior = prog.solve(0.0).map_err(fail)?;
        if grow(&mut chosen, &interior) {
            continue;
        }
        let c = finish(&prog, interior)?;
        if !grow(&mut chosen, &c) {
            return Ok(c);
        }
    }
    let prog = program(&all);
    let interior = prog.solve(0.0).map_err(fail)?;
    finish(&prog, interior)
}

/// The exact answer from the interior-point answer `interior` of `prog`: its polish on the
/// active face, checked against every constraint exactly
/// (`docs/theory/fitting.md#shape-constraints`).
fn finish_program(
    prog: &ConeProgram,
    interior: Vec<f64>,
    (degree, knots): (usize, &[f64]),
    constraints: &ShapeConstraints,
    (scale, center): (&Scale, f64),
    steps: &Steps<'_, '_>,
) -> Result<Vec<f64>> {
    let n = prog.p.n;
    let rows = ShapeCheck::new(
        &curve_of(degree, knots.to_vec(), &interior[..n], scale, center),
        constraints,
    );
    let check = |c: &[f64]| {
        holds_by(
            &rows,
            &curve_of(degree, knots.to_vec(), c, scale, center),
            constraints,
            scale,
        )
    };
    // polish on the active face, kept only if it keeps every constraint exactly and does not
    // raise the objective; when the face's own rounding leaves it a few ulps outside a
    // constraint, polish the same face tightened by the margin
    let bound = prog.objective(&interior) + POLISH_RTOL * (1.0 + prog.objective(&interior).abs());
    let mut start = interior.clone();
    for margin in [0.0, ROUNDING_MARGIN, FEASIBILITY_MARGIN] {
        let (exact, last) = polish_exact(prog, &start, (margin, bound), &check, steps)?;
        if let Some(c) = exact {
            return Ok(c);
        }
        // the tightened face is polished from where the first polish ended
        start = last;
    }
    if check(&interior)? {
        return Ok(interior);
    }
    // the interior-point answer misses a constraint by its rounding and the polish found no
    // face: solve again with every inequality tightened by a margin above that rounding
    if let Ok(c) = prog.solve(FEASIBILITY_MARGIN) {
        if check(&c)? {
            return Ok(c);
        }
    }
    Ok(interior)
}

/// The polished answer from `start` (up to four rounds while a touching point of a quadratic
/// moves), if one keeps every constraint exactly (`check`) with an objective at most `bound`;
/// and the last answer polished (or `start`).
fn polish_exact(
    prog: &ConeProgram,
    start: &[f64],
    (margin, bound): (f64, f64),
    check: &dyn Fn(&[f64]) -> Result<bool>,
    steps: &Steps<'_, '_>,
) -> Result<(Option<Vec<f64>>, Vec<f64>)> {
    let mut best = None;
    let mut current = start.to_vec();
    for _ in 0..4 {
        steps.tick()?;
        let Some(c) = prog.polish(&current, margin, steps)? else {
            break;
        };
        let moved = c
            .iter()
            .zip(&current)
            .any(|(a, b)| (a - b).abs() > 1e-15 * (1.0 + a.abs()));
        if prog.objective(&c) <= bound && check(&c)? {
            best = Some(c.clone());
        }
        current = c;
        if !moved {
            break;
        }
    }
    Ok((best, current))
}

/// Margin (rows scaled to unit largest coefficient, coefficients in units of the data) by which
/// inequalities are tightened when neither the interior-point answer nor its polish keeps them
/// exactly; the answer moves by about this much.
const FEASIBILITY_MARGIN: f64 = 1e-10;

/// Margin (as [`FEASIBILITY_MARGIN`]) of the first tightened polish: above the rounding of a
/// face's solve (a few ulps of rows whose largest coefficient is up to `1/h^r` for spans `h`),
/// small enough that the objective rises by far less than [`POLISH_RTOL`].
const ROUNDING_MARGIN: f64 = 1e-13;

/// Relative rise of the objective above the interior-point answer's that a polished answer may
/// show (rounding) and still be taken.
const POLISH_RTOL: f64 = 1e-11;

/// The scaled coefficients `(control − center)/Y` of `curve` (the inverse of [`curve_of`]).
fn scaled(curve: &BSplineCurve, scale: &Scale, center: f64) -> Vec<f64> {
    curve
        .control_points()
        .as_slice()
        .iter()
        .map(|v| (v - center) / scale.y)
        .collect()
}

/// The curve of scaled coefficients `c`: control points `center + Y·c`.
fn curve_of(degree: usize, knots: Vec<f64>, c: &[f64], scale: &Scale, center: f64) -> BSplineCurve {
    let ctrl: Vec<f64> = c.iter().map(|v| center + scale.y * v).collect();
    BSplineCurve::from_raw(degree, knots, Points::from_raw(ctrl, 1))
}
