//! Interpolation of curves through points (document 000 §1–4;
//! docs/theory/interpolation.md#global-interpolation) and closed curves
//! (docs/theory/interpolation.md#closed-curves).
//!
//! One configurable construction, [`CurveInterpolation`], combines three independent choices:
//!
//! - **parametrisation** ([`Parametrization`]): uniform, chord length, centripetal or the general
//!   exponent form (docs/theory/interpolation.md#parametrisation; P&T eq. 9.4–9.6);
//! - **knot placement** ([`KnotPlacement`]): averaging (eq. 3, eq. 4), uniform (eq. 2) or at the
//!   parameters (eq. 8);
//! - **end conditions** ([`EndCondition`]): none (§1), first derivatives (§2 for any degree
//!   `p ≥ 2`, §3 for the C² cubic), second derivatives and the natural cubic (§4), or a
//!   closed periodic curve.
//!
//! Every result is a [`BSplineCurve`], so evaluation, derivatives, export and plotting apply.
//!
//! ## Numerics
//! - The collocation matrix is built row by row straight from the Cox–de Boor kernel into a band
//!   buffer and eliminated without pivoting ([`crate::numeric::linalg`]); all coordinates are solved
//!   together. Time O(n·p²), memory O(n·p); no dense matrix.
//! - The common case — a free-end cubic with chord-length parameters and averaged knots in 1–3
//!   dimensions — takes a fused path (`chord_cubic`, [`crate::interpolate::cubic_sweep`]'s `solve_free_cubic`):
//!   parameters, knots, rows and elimination in three sweeps with no buffer but the result and
//!   the `U` factor (peak memory about twice the input's size besides the input). Its rows
//!   share the reciprocals of the knot differences, so it agrees with the general path to
//!   rounding amplified by the condition number (1e-15 on smooth data); anything it does not
//!   handle, and every error, goes to the general path.
//! - Control points whose values follow from the end conditions (`P_0 = q_0`, `P_n = q_n` of a
//!   clamped curve, `P_1` and `P_{n+1}` from first derivatives, eq. 6–7 and 9–10) are set
//!   directly and moved to the right-hand side, so the remaining system is a submatrix of a
//!   totally positive collocation matrix.
//! - The data are solved relative to the first point `q_0` (the basis functions sum to 1, so the
//!   curve moves with its data): data offset by 1e8 are interpolated as accurately as data at the
//!   origin, and `q_0` is reproduced exactly.
//! - Parameters are computed from point differences only, hence offset-invariant and
//!   scale-invariant (distances are rescaled before squaring when they would underflow).
//! - On request ([`CurveInterpolation::max_condition`], [`CurveInterpolation::condition`]) the
//!   1-norm condition number of the collocation system is estimated (Hager–Higham, as LAPACK
//!   `dgbcon`) from the banded factors, and a system above the limit is refused with
//!   [`Error::IllConditioned`]. Off by default: the default path does not pay for it.

use crate::curve::bspline::BSplineCurve;
use crate::error::{check_finite, Error, Result};
use crate::interpolate::collocation::{check_condition_limit, condition_exceeded};
use crate::interpolate::end_conditions::{
    first_derivative_ends, free_end, second_derivative_ends, EndCondition,
};
use crate::interpolate::fast::{chord_cubic, free_end_cubic, InterpolationWorkspace};
use crate::interpolate::parametrization::{
    check_strictly_increasing, parametrize_impl, Parametrization,
};
use crate::interpolate::periodic::periodic;
use crate::knots::KnotVector;
use crate::points::{Points, PointsRef};
use crate::{Arg, What};

/// Where the knots go.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KnotPlacement {
    /// The natural choice for the end condition: [`KnotPlacement::Averaged`] for
    /// [`EndCondition::Free`] and for first derivatives with degree ≠ 3;
    /// [`KnotPlacement::AtParameters`] for cubics with first or second derivatives; the
    /// periodic rule for [`EndCondition::Periodic`].
    #[default]
    Auto,
    /// Averages of `p` consecutive parameters: document 000 eq. (3), or eq. (4) with end
    /// derivatives. Always gives a non-singular, totally positive system.
    Averaged,
    /// Uniform interior knots, eq. (2). The source warns that with chord-length or centripetal
    /// parameters this "can lead to a system with a singular matrix"; lekalo then reports
    /// [`Error::SingularSystem`]. Only with [`EndCondition::Free`].
    Uniform,
    /// Knots at the parameters, eq. (8): the C² cubic of §3–4. Degree 3 with first or
    /// second end derivatives only.
    AtParameters,
}

/// Global interpolation of points by a B-spline curve: parametrisation × knot placement × end
/// conditions (document 000 §1–4, plus closed curves;
/// docs/theory/interpolation.md#global-interpolation).
///
/// ```
/// use lekalo::{CurveInterpolation, EndCondition, Parametrization, Points};
/// // P&T Example 9.1, cubic, chord length, averaged knots
/// let q = Points::from_2d(&[[0.0, 0.0], [3.0, 4.0], [-1.0, 4.0], [-4.0, 0.0], [-4.0, -3.0]])?;
/// let c = CurveInterpolation::new(3).interpolate(q.as_view())?;
/// let p1 = c.control_points().point(1);
/// assert!((p1[0] - 7.316964).abs() < 1e-6 && (p1[1] - 3.686778).abs() < 1e-6);
/// // the curve passes through the data at the chord-length parameters
/// let r = c.eval(9.0 / 17.0)?;
/// assert!((r[0] + 1.0).abs() < 1e-14 && (r[1] - 4.0).abs() < 1e-14);
///
/// // the natural cubic spline (§4 with zero second derivatives)
/// let natural = CurveInterpolation::new(3)
///     .end_condition(EndCondition::Natural)
///     .parametrization(Parametrization::ChordLength)
///     .interpolate(q.as_view())?;
/// let d2 = natural.eval_derivatives(0.0, 2)?;
/// assert!(d2.point(2).iter().all(|v| v.abs() < 1e-12));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CurveInterpolation {
    degree: usize,
    parametrization: Parametrization,
    knots: KnotPlacement,
    end: EndCondition,
    drop_duplicates: bool,
    max_condition: Option<f64>,
}

impl CurveInterpolation {
    /// Interpolation of `degree` with chord-length parameters, [`KnotPlacement::Auto`],
    /// [`EndCondition::Free`], and coincident consecutive points refused.
    #[must_use]
    pub fn new(degree: usize) -> Self {
        CurveInterpolation {
            degree,
            parametrization: Parametrization::ChordLength,
            knots: KnotPlacement::Auto,
            end: EndCondition::Free,
            drop_duplicates: false,
            max_condition: None,
        }
    }

    /// Sets the parametrisation.
    #[must_use]
    pub fn parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }

    /// Sets the knot placement.
    #[must_use]
    pub fn knot_placement(mut self, knots: KnotPlacement) -> Self {
        self.knots = knots;
        self
    }

    /// Sets the end conditions.
    #[must_use]
    pub fn end_condition(mut self, end: EndCondition) -> Self {
        self.end = end;
        self
    }

    /// When `true`, exact consecutive duplicates among the points are dropped (the curve passes
    /// through each remaining point once) instead of reported as [`Error::CoincidentPoints`].
    #[must_use]
    pub fn drop_duplicates(mut self, drop: bool) -> Self {
        self.drop_duplicates = drop;
        self
    }

    /// Refuses, with [`Error::IllConditioned`], a collocation system whose 1-norm condition
    /// number `κ_1` is estimated above `limit` (`limit ≥ 1`; e.g. `1e8` keeps about 8 of the 16
    /// digits of `f64`). Off by default, and then free.
    ///
    /// When set, every interpolation also estimates `κ_1 = ‖A‖_1·‖A⁻¹‖_1` of the system it solves
    /// (Hager–Higham estimator, LAPACK `dgbcon`; see [`CurveInterpolation::condition`]), which
    /// costs a few extra banded solves, and the fused cubic fast path is not taken. Large `κ_1`
    /// comes from parameters that crowd together (nearly coincident points with chord-length
    /// parameters) or knots too unevenly spaced for the degree. Not available for
    /// [`EndCondition::Periodic`] (reported as [`Error::InvalidArgument`]).
    ///
    /// ```
    /// use lekalo::{CurveInterpolation, Error, Points};
    /// // two points 1e-9 apart among unit-spaced ones
    /// let q = Points::from_2d(&[[0.0, 0.0], [1.0, 0.5], [2.0, 0.0], [2.0, 1e-9], [3.0, 0.5], [4.0, 0.0]])?;
    /// let strict = CurveInterpolation::new(3).max_condition(1e6);
    /// assert!(matches!(strict.interpolate(q.as_view()), Err(Error::IllConditioned { .. })));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn max_condition(mut self, limit: f64) -> Self {
        self.max_condition = Some(limit);
        self
    }

    /// Estimate of the 1-norm condition number `κ_1 = ‖A‖_1·‖A⁻¹‖_1` of the collocation system
    /// that [`CurveInterpolation::interpolate`] solves for `points` (the unknown control points
    /// only: those fixed by the end conditions are on the right-hand side). The relative error
    /// of the control points is bounded by about `κ_1·ε` times the data's size.
    ///
    /// The estimate is Higham's refinement of Hager's method (N. J. Higham, ACM TOMS 14 (1988),
    /// Algorithm 4.1; LAPACK `dlacn2`/`dgbcon`) with the banded factors: O(n·p) beyond the
    /// factorisation, no dense matrix. It is a lower bound of `κ_1`, usually equal to it and
    /// rarely low by more than a factor of 3. A system with no unknowns (two points, free ends)
    /// has `κ_1 = 1`.
    ///
    /// ```
    /// use lekalo::{CurveInterpolation, Parametrization, Points};
    /// let q = Points::from_flat(1, (0..50).map(|k| f64::from(k).sin()).collect())?;
    /// let kappa = CurveInterpolation::new(3)
    ///     .parametrization(Parametrization::Uniform)
    ///     .condition(q.as_view())?;
    /// assert!(kappa >= 1.0 && kappa < 10.0);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`CurveInterpolation::interpolate`] (but never the limit of
    /// [`CurveInterpolation::max_condition`]); [`Error::InvalidArgument`] for
    /// [`EndCondition::Periodic`], whose cyclic system has no estimate yet.
    pub fn condition(&self, points: PointsRef<'_>) -> Result<f64> {
        let owned = self.prepare_points(points);
        let points = owned.as_ref().map_or(points, Points::as_view);
        let periodic = self.end == EndCondition::Periodic;
        let params = parametrize_impl(points, self.parametrization, periodic)?;
        let mut kappa = 1.0;
        self.solve_system(points, &params, Some(&mut kappa))?;
        Ok(kappa)
    }

    /// The curve through `points` with parameters from the configured [`Parametrization`] on
    /// `[0, 1]`.
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than 2 points (after dropping duplicates);
    /// [`Error::CoincidentPoints`] for equal consecutive points with a non-uniform
    /// parametrisation (unless [`CurveInterpolation::drop_duplicates`]); [`Error::Degree`] if the
    /// degree does not fit the number of points or the end condition; [`Error::Dimension`] for
    /// end derivatives of the wrong dimension; [`Error::NonFinite`]; [`Error::InvalidArgument`]
    /// for an unsupported combination of knot placement and end condition or a bad exponent;
    /// [`Error::SingularSystem`] / [`Error::IllConditioned`] from the solve, or
    /// [`Error::IllConditioned`] for a condition estimate above
    /// [`CurveInterpolation::max_condition`] ([`Error::InvalidArgument`] if that limit is not a
    /// number ≥ 1, or with [`EndCondition::Periodic`]).
    ///
    /// The result is always in new memory. The scratch of the fused cubic path (the `U`
    /// factor, 16 bytes a point) is kept per thread for the next call, up to 32 MiB; an
    /// [`InterpolationWorkspace`] keeps the result buffers as well.
    pub fn interpolate(&self, points: PointsRef<'_>) -> Result<BSplineCurve> {
        let mut ws = InterpolationWorkspace::from_thread();
        let curve = self.interpolate_with(points, &mut ws);
        ws.return_to_thread();
        curve
    }

    /// [`CurveInterpolation::interpolate`] with buffers from (and the `U` factor kept in) a
    /// reusable [`InterpolationWorkspace`]: the same curve, bit for bit. Give finished curves
    /// back with [`InterpolationWorkspace::recycle`] and repeated interpolation of large data
    /// sets touches no fresh memory. Only the fused path (free-end cubic, chord length,
    /// averaged knots, 1–3 dimensions, the default configuration) uses the workspace; the
    /// others allocate as `interpolate` does.
    ///
    /// # Errors
    /// As [`CurveInterpolation::interpolate`].
    pub fn interpolate_with(
        &self,
        points: PointsRef<'_>,
        ws: &mut InterpolationWorkspace,
    ) -> Result<BSplineCurve> {
        let owned = self.prepare_points(points);
        let points = owned.as_ref().map_or(points, Points::as_view);
        if self.degree == 3
            && self.max_condition.is_none()
            && self.end == EndCondition::Free
            && self.parametrization == Parametrization::ChordLength
            && matches!(self.knots, KnotPlacement::Auto | KnotPlacement::Averaged)
        {
            if let Some(curve) = chord_cubic(points, ws) {
                return Ok(curve);
            }
        }
        let periodic = self.end == EndCondition::Periodic;
        let params = parametrize_impl(points, self.parametrization, periodic)?;
        self.interpolate_checked(points, &params)
    }

    /// The curve through `points` at the given parameters, strictly increasing. For
    /// [`EndCondition::Periodic`] give one parameter more than points: the last one belongs to
    /// the return to the first point (the period is its distance to the first parameter).
    ///
    /// Useful for functions `y(x)`: pass the ordinates as 1-D (or m-D) points and the abscissae
    /// as parameters (see [`natural_cubic_spline`]).
    ///
    /// # Errors
    /// As [`CurveInterpolation::interpolate`]; [`Error::LengthMismatch`] if the parameter count
    /// is wrong; [`Error::NotIncreasing`] / [`Error::Repeated`] for decreasing / equal
    /// parameters. Duplicates are not dropped here (they would shift the parameters).
    pub fn interpolate_at(
        &self,
        points: PointsRef<'_>,
        parameters: &[f64],
    ) -> Result<BSplineCurve> {
        let periodic = self.end == EndCondition::Periodic;
        let expected = points.len() + usize::from(periodic);
        if parameters.len() != expected {
            return Err(Error::LengthMismatch {
                what: if periodic {
                    What::of(
                        Arg::Parameters,
                        "parameters (points + 1 for the closing parameter)",
                    )
                } else {
                    What::of(Arg::Parameters, "parameters (one per point)")
                },
                expected,
                got: parameters.len(),
            });
        }
        check_strictly_increasing(parameters)?;
        self.interpolate_checked(points, parameters)
    }

    /// Drops exact consecutive duplicates (if asked) and, for closed curves, a final copy of the
    /// first point; `None` when the points are used as given.
    fn prepare_points(&self, points: PointsRef<'_>) -> Option<Points> {
        let dim = points.dim();
        let mut owned: Option<Points> = None;
        if self.drop_duplicates
            && points
                .iter()
                .zip(points.iter().skip(1))
                .any(|(a, b)| a == b)
        {
            let mut data = Vec::with_capacity(points.as_slice().len());
            let mut last: Option<&[f64]> = None;
            for q in points.iter() {
                if last != Some(q) {
                    data.extend_from_slice(q);
                }
                last = Some(q);
            }
            owned = Some(Points::from_raw(data, dim));
        }
        if self.end == EndCondition::Periodic {
            let view = owned.as_ref().map_or(points, Points::as_view);
            let n = view.len();
            if n >= 2 && view.point(0) == view.point(n - 1) {
                let data = view.as_slice()[..(n - 1) * dim].to_vec();
                owned = Some(Points::from_raw(data, dim));
            }
        }
        owned
    }

    /// Dispatch after the parameters are known to be strictly increasing, with the limit of
    /// [`CurveInterpolation::max_condition`] applied.
    fn interpolate_checked(&self, points: PointsRef<'_>, params: &[f64]) -> Result<BSplineCurve> {
        let Some(limit) = self.max_condition else {
            return self.solve_system(points, params, None);
        };
        check_condition_limit(limit)?;
        let mut kappa = 1.0;
        let curve = self.solve_system(points, params, Some(&mut kappa))?;
        // an infinite estimate (overflowing solves) exceeds every limit
        if kappa > limit {
            return Err(condition_exceeded(kappa, limit));
        }
        Ok(curve)
    }

    /// Builds and solves the system; with `kappa`, the largest condition estimate of the
    /// systems solved goes there (the fused cubic path, which keeps no factors, is not taken).
    fn solve_system(
        &self,
        points: PointsRef<'_>,
        params: &[f64],
        kappa: Option<&mut f64>,
    ) -> Result<BSplineCurve> {
        let p = self.degree;
        if p == 0 {
            return Err(Error::Degree {
                degree: 0,
                reason: "interpolation needs degree ≥ 1".into(),
            });
        }
        if points.len() < 2 {
            return Err(Error::TooFew {
                what: "points to interpolate".into(),
                min: 2,
                got: points.len(),
            });
        }
        let dim = points.dim();
        let curve = match (&self.end, self.knots) {
            (EndCondition::Free, KnotPlacement::Auto | KnotPlacement::Averaged) => {
                let kv = KnotVector::averaged(params, p)?;
                if p == 3 && kappa.is_none() {
                    if let Some(control) = free_end_cubic(points, params, kv.as_slice()) {
                        return Ok(BSplineCurve::from_raw(3, kv.into_vec(), control));
                    }
                }
                free_end(points, params, p, kv.into_vec(), kappa)
            }
            (EndCondition::Free, KnotPlacement::Uniform) => {
                let n_ctrl = points.len();
                let kv = KnotVector::clamped_uniform(p, n_ctrl)?;
                let (a, b) = (params[0], params[n_ctrl - 1]);
                let knots = kv.as_slice().iter().map(|u| a + (b - a) * u).collect();
                free_end(points, params, p, knots, kappa)
            }
            (EndCondition::FirstDerivatives { start, end }, placement) => {
                check_vector(Arg::StartDerivative, start, dim)?;
                check_vector(Arg::EndDerivative, end, dim)?;
                let at_params = match placement {
                    KnotPlacement::Auto => p == 3,
                    KnotPlacement::AtParameters => true,
                    KnotPlacement::Averaged => false,
                    KnotPlacement::Uniform => {
                        return Err(unsupported("uniform", "first derivatives"))
                    }
                };
                if at_params && p != 3 {
                    return Err(Error::Degree {
                        degree: p,
                        reason: "knots at the parameters with end derivatives need a cubic (document 000 §3)"
                            .into(),
                    });
                }
                if p < 2 {
                    return Err(Error::Degree {
                        degree: p,
                        reason: "prescribed end derivatives need degree ≥ 2 (document 000 §2)"
                            .into(),
                    });
                }
                let n = params.len() - 1;
                let kv = if at_params {
                    KnotVector::from_parameters(params, 3)?
                } else if p == n + 2 {
                    // eq. (4) with an empty range of interior knots: a single Bezier piece
                    // (KnotVector::averaged_with_end_derivatives does not handle this case)
                    let mut knots = vec![params[0]; p + 1];
                    knots.resize(2 * p + 2, params[n]);
                    KnotVector::from_raw(knots)
                } else {
                    KnotVector::averaged_with_end_derivatives(params, p)?
                };
                first_derivative_ends(points, params, p, kv.into_vec(), [start, end], kappa)
            }
            (EndCondition::SecondDerivatives { .. } | EndCondition::Natural, placement) => {
                if !matches!(placement, KnotPlacement::Auto | KnotPlacement::AtParameters) {
                    return Err(unsupported("averaged or uniform", "second derivatives"));
                }
                if p != 3 {
                    return Err(Error::Degree {
                        degree: p,
                        reason:
                            "second-derivative and natural end conditions are for cubics (document 000 §4)"
                                .into(),
                    });
                }
                let zero = vec![0.0; dim];
                let (start, end) = match &self.end {
                    EndCondition::SecondDerivatives { start, end } => {
                        check_vector(
                            What::of(Arg::StartDerivative, "start second derivative"),
                            start,
                            dim,
                        )?;
                        check_vector(
                            What::of(Arg::EndDerivative, "end second derivative"),
                            end,
                            dim,
                        )?;
                        (start.as_slice(), end.as_slice())
                    }
                    _ => (zero.as_slice(), zero.as_slice()),
                };
                second_derivative_ends(points, params, start, end, kappa)
            }
            (EndCondition::Periodic, KnotPlacement::Auto) if kappa.is_some() => {
                Err(Error::InvalidArgument {
                    what: "condition estimate (max_condition / condition)".into(),
                    reason: "not available for periodic curves yet: their cyclic system is \
                             solved by block elimination; drop max_condition for closed curves"
                        .into(),
                })
            }
            (EndCondition::Periodic, KnotPlacement::Auto) => periodic(points, params, p),
            (EndCondition::Periodic, _) => Err(unsupported("explicit", "periodic")),
            (EndCondition::Free, KnotPlacement::AtParameters) => Err(unsupported(
                "at-the-parameters",
                "free (use first or second derivatives, or averaged knots)",
            )),
        }?;
        // the fused cubic (averaged knots, returned above) needs no check: its rows satisfy the
        // Schoenberg–Whitney condition with margin and its growth is bounded
        check_residual(&curve, points, params)?;
        Ok(curve)
    }
}

/// Largest accepted distance of an interpolant from its data, relative to the data's extent
/// (`max_k ‖q_k − q_0‖_∞`), on top of the rounding of evaluating in absolute coordinates
/// (`64 (p+1) ε max|q|`). Control points far larger than the data (from an ill-conditioned
/// system, or from end derivatives far larger than the data's scale) cancel in every
/// evaluation and can break this bound: such results are refused too. A backward-stable banded solve of a well-posed collocation system
/// stays near `1e-15`; a curve that misses its data by more than this is refused as
/// [`Error::IllConditioned`] rather than returned.
pub const INTERPOLATION_RESIDUAL_RTOL: f64 = 1e-9;

/// The a-posteriori check of the general path: evaluates `curve` at the data parameters
/// (the fast evaluator, O(n·p²·dim) to build, a few ns a point) and refuses a result that misses
/// a data point by more than [`INTERPOLATION_RESIDUAL_RTOL`] times the data's extent. Catches
/// what the pivot checks cannot: elimination without pivoting on a system whose
/// Schoenberg–Whitney condition holds only barely (e.g. uniform knots under clustered
/// chord-length parameters) can lose every digit with pivots and growth that look harmless.
fn check_residual(curve: &BSplineCurve, points: PointsRef<'_>, params: &[f64]) -> Result<()> {
    let dim = points.dim();
    let n = points.len();
    let q0 = points.point(0);
    let extent = (0..n)
        .flat_map(|k| points.point(k).iter().zip(q0).map(|(a, b)| (a - b).abs()))
        .fold(0.0_f64, f64::max);
    if !extent.is_finite() {
        return Err(Error::InvalidArgument {
            what: "points".into(),
            reason: format!(
                "coordinates differ from the first point by more than the largest f64 \
                 ({extent:e}); the interpolant is computed from such differences: rescale the \
                 data so that their span stays well below {:e}",
                f64::MAX
            ),
        });
    }
    if let Some(i) = curve
        .control_points()
        .as_slice()
        .iter()
        .position(|v| !v.is_finite())
    {
        return Err(Error::IllConditioned {
            reason: format!(
                "control point coordinate {i} overflowed to {:e}: the data are too close to \
                 the largest f64 for this interpolant; rescale them",
                curve.control_points().as_slice()[i]
            ),
        });
    }
    let magnitude = points
        .as_slice()
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut at = vec![0.0; n * dim];
    curve.evaluator().eval_batch(&params[..n], &mut at)?;
    // plus the rounding of an evaluation in absolute coordinates (data offset far from 0)
    let rounding = 64.0 * (curve.degree() + 1) as f64 * f64::EPSILON * magnitude;
    let tolerance = INTERPOLATION_RESIDUAL_RTOL * extent + rounding;
    for (k, c) in at.chunks_exact(dim).enumerate() {
        // a NaN coordinate counts as an infinite miss (f64::max would skip it)
        let miss = c
            .iter()
            .zip(points.point(k))
            .map(|(a, b)| {
                if a.is_nan() {
                    f64::INFINITY
                } else {
                    (a - b).abs()
                }
            })
            .fold(0.0_f64, f64::max);
        if miss > tolerance {
            return Err(Error::IllConditioned {
                reason: format!(
                    "the computed curve misses data point {k} by {miss:e} ({:e} of the data's \
                     extent {extent:e}; at most {INTERPOLATION_RESIDUAL_RTOL:e} is accepted); \
                     its control points reach {:e}, and evaluations cancel them: the \
                     collocation system is too ill-conditioned, or the end derivatives are far \
                     larger than the data's scale; use averaged knots \
                     (KnotPlacement::Averaged), centripetal or uniform parameters, fewer points \
                     or smaller end derivatives",
                    miss / extent,
                    curve.control_points().max_abs()
                ),
            });
        }
    }
    Ok(())
}

fn unsupported(knots: &str, end: &str) -> Error {
    Error::InvalidArgument {
        what: Arg::Knots.into(),
        reason: format!(
            "{knots} knots do not go with {end} end conditions; use the knot placement \"auto\""
        ),
    }
}

fn check_vector(what: impl Into<What>, v: &[f64], dim: usize) -> Result<()> {
    let what: What = what.into();
    if v.len() != dim {
        return Err(Error::Dimension {
            what,
            expected: dim,
            got: v.len(),
        });
    }
    check_finite(what, v)
}

/// The natural cubic spline `y(x)` through `(x_k, y_k)` for strictly increasing `x`: document
/// 000 §4 with zero end second derivatives, the parameters being the abscissae themselves, so
/// that `curve.eval(x)` is `y(x)` (each component of `y` is one function). The result equals
/// SciPy's `CubicSpline(x, y, bc_type="natural")`.
///
/// ```
/// use lekalo::{natural_cubic_spline, Points};
/// let x = [0.0, 1.0, 2.5, 4.0];
/// let y = Points::from_flat(1, vec![1.0, 3.0, 2.0, 5.0])?;
/// let s = natural_cubic_spline(&x, y.as_view())?;
/// assert!((s.eval(2.5)?[0] - 2.0).abs() < 1e-14);
/// assert!(s.eval_derivatives(4.0, 2)?.point(2)[0].abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`CurveInterpolation::interpolate_at`].
pub fn natural_cubic_spline(x: &[f64], y: PointsRef<'_>) -> Result<BSplineCurve> {
    CurveInterpolation::new(3)
        .end_condition(EndCondition::Natural)
        .interpolate_at(y, x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpolate::fast::{chord_cubic, InterpolationWorkspace};
    use crate::interpolate::parametrization::{distance, parametrize};

    fn example() -> Points {
        Points::from_2d(&[
            [0.0, 0.0],
            [3.0, 4.0],
            [-1.0, 4.0],
            [-4.0, 0.0],
            [-4.0, -3.0],
        ])
        .unwrap()
    }

    fn assert_points(got: &Points, expect: &[[f64; 2]], tol: f64) {
        assert_eq!(got.len(), expect.len(), "number of control points");
        for (i, e) in expect.iter().enumerate() {
            let g = got.point(i);
            assert!(
                (g[0] - e[0]).abs() < tol && (g[1] - e[1]).abs() < tol,
                "control point {i}: {g:?} vs {e:?}"
            );
        }
    }

    #[test]
    fn example_9_1_uniform_exact() {
        let c = CurveInterpolation::new(3)
            .parametrization(Parametrization::Uniform)
            .interpolate(example().as_view())
            .unwrap();
        assert_points(
            c.control_points(),
            &[
                [0.0, 0.0],
                [58.0 / 9.0, 67.0 / 18.0],
                [-8.0 / 3.0, 7.5],
                [-46.0 / 9.0, -49.0 / 18.0],
                [-4.0, -3.0],
            ],
            1e-14,
        );
    }

    /// The general path (parametrisation, averaged knots, [`solve_collocation`]) for comparison
    /// with the fused cubic.
    fn general_cubic(q: PointsRef<'_>, params: &[f64]) -> BSplineCurve {
        let kv = KnotVector::averaged(params, 3).unwrap();
        free_end(q, params, 3, kv.into_vec(), None).unwrap()
    }

    /// Wobbly, unevenly spaced points around `offset`, scaled by `scale`.
    fn wobbly(n: usize, dim: usize, offset: f64, scale: f64) -> Points {
        let mut data = Vec::new();
        for i in 0..n {
            let s = i as f64 * 0.37 + 0.2 * (i as f64 * 1.3).sin();
            for k in 0..dim {
                data.push(offset + scale * (s * (k as f64 + 1.0)).sin() * (1.0 + s));
            }
        }
        Points::from_flat(dim, data).unwrap()
    }

    #[test]
    fn distance_survives_tiny_and_huge_scales() {
        assert!((distance(&[0.0, 0.0], &[3e-200, 4e-200]) - 5e-200).abs() < 1e-214);
        assert!((distance(&[0.0, 0.0], &[3e200, 4e200]) - 5e200).abs() < 1e186);
        assert_eq!(distance(&[1.0], &[1.0]), 0.0);
    }

    #[test]
    fn chord_length_survives_an_overflowing_total() {
        // 19 points 1e307 apart: the total length 1.8e308 exceeds f64::MAX
        let data: Vec<f64> = (-9..=9).map(|k| f64::from(k) * 1e307).collect();
        let q = Points::from_flat(1, data).unwrap();
        let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
        for (k, tk) in t.iter().enumerate() {
            assert!((tk - k as f64 / 18.0).abs() < 1e-14, "t[{k}] = {tk}");
        }
    }

    #[test]
    fn periodic_with_two_points_degree_one() {
        let q = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0]]).unwrap();
        let c = CurveInterpolation::new(1)
            .end_condition(EndCondition::Periodic)
            .interpolate(q.as_view())
            .unwrap();
        assert_eq!(c.eval(0.5).unwrap(), vec![1.0, 0.0]);
        assert_eq!(c.eval(1.0).unwrap(), vec![0.0, 0.0]);
    }

    #[test]
    fn fused_cubic_agrees_with_the_general_path() {
        // one workspace throughout, sizes up and down: recycled buffers hold stale numbers of
        // other curves, which must not leak into the result
        let mut ws = InterpolationWorkspace::new();
        for dim in 1..=3 {
            for n in [200, 600, 5, 258, 12, 6, 257, 7] {
                // (squared steps subnormal at 1e-160 and overflowing at 1e155: the scaled lengths)
                for (offset, scale) in [
                    (0.0, 1.0),
                    (1e8, 1.0),
                    (0.0, 1e-8),
                    (-3.0, 1e5),
                    (0.0, 1e-160),
                    (0.0, 1e155),
                ] {
                    let q = wobbly(n, dim, offset, scale);
                    let params = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
                    let fused = chord_cubic(q.as_view(), &mut ws).unwrap();
                    let general = general_cubic(q.as_view(), &params);
                    assert_eq!(
                        fused.knots().as_slice(),
                        general.knots().as_slice(),
                        "knots"
                    );
                    // the fused rows share the reciprocals of the knot differences, the general
                    // rows divide by A2.2's sums: the two solves differ by rounding, amplified
                    // at most by the condition number (measured: at most 0.34·κ·ε of the data)
                    let a = fused.control_points().as_slice();
                    let b = general.control_points().as_slice();
                    let worst = a
                        .iter()
                        .zip(b)
                        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
                    let kappa = CurveInterpolation::new(3).condition(q.as_view()).unwrap();
                    let data = q.as_slice();
                    let extent = data.iter().fold(0.0_f64, |m, v| m.max((v - data[0]).abs()));
                    assert!(
                        worst <= kappa * f64::EPSILON * extent,
                        "dim {dim}, n {n}, offset {offset}, scale {scale}: {worst:e} (κ {kappa:.1})"
                    );
                    // the interpolate_at route through free_end_cubic gives the same curve
                    let at = CurveInterpolation::new(3)
                        .interpolate_at(q.as_view(), &params)
                        .unwrap();
                    assert_eq!(at.control_points().as_slice(), a, "interpolate_at");
                    ws.recycle(fused);
                }
            }
        }
    }

    #[test]
    fn fused_cubic_agrees_to_1e_14_on_smooth_data() {
        // a helix (the benchmark's curve) and a plane curve with uneven spacing
        let mut ws = InterpolationWorkspace::new();
        let helix: Vec<f64> = (0..2000)
            .flat_map(|i| {
                let s = f64::from(i) * 0.05;
                [s.cos(), s.sin(), 0.1 * s]
            })
            .collect();
        let uneven: Vec<f64> = (0..500)
            .flat_map(|i| {
                let s = f64::from(i) * 0.02 + 0.01 * (f64::from(i) * 2.1).sin();
                [s, (3.0 * s).sin()]
            })
            .collect();
        for (data, dim) in [(helix, 3), (uneven, 2)] {
            let q = Points::from_flat(dim, data).unwrap();
            let params = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
            let fused = chord_cubic(q.as_view(), &mut ws).unwrap();
            let general = general_cubic(q.as_view(), &params);
            let b = general.control_points().as_slice();
            let size = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let worst = fused
                .control_points()
                .as_slice()
                .iter()
                .zip(b)
                .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(
                worst <= 1e-14 * size,
                "{dim}-D: {:e} of the net",
                worst / size
            );
        }
    }

    #[test]
    fn fused_cubic_declines_what_it_does_not_handle() {
        // four points (too few for the band), four dimensions, coincident points
        let mut ws = InterpolationWorkspace::new();
        assert!(chord_cubic(wobbly(4, 2, 0.0, 1.0).as_view(), &mut ws).is_none());
        assert!(chord_cubic(wobbly(9, 4, 0.0, 1.0).as_view(), &mut ws).is_none());
        let mut q = wobbly(9, 2, 0.0, 1.0).as_slice().to_vec();
        q.copy_within(6..8, 8);
        assert!(chord_cubic(Points::from_flat(2, q).unwrap().as_view(), &mut ws).is_none());
        // the declined attempt keeps the buffers it had grown for the next call
        assert!(ws.capacity_bytes() >= 9 * 2 * 8);
    }
}
