//! C^k deformation (blending) of curves with jump-smoothing polynomials (document 001 §2;
//! docs/theory/blending.md#deformation-of-curves): [`ParametricCurve`], [`Deformation`] (the
//! mathematics is documented there), exact Bezier/NURBS forms; corners are in `corner.rs`.

use crate::{Arg, What};
use std::sync::Arc;

use crate::blend::bernstein as bernstein_ops;
use crate::blend::jump::JumpPolynomial;
use crate::curve::bezier::check_unit;
use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::points::Points;
use crate::BezierCurve;

/// The largest continuity degree `k` a [`Deformation`] accepts: it uses `w_{k−1}`, so
/// [`JumpPolynomial::MAX_K`] + 1.
pub const MAX_DEFORMATION_CONTINUITY: usize = JumpPolynomial::MAX_K + 1;

/// `continuity` if it lies in `1..=max` (`max` capped at [`MAX_DEFORMATION_CONTINUITY`]): the
/// check of [`Deformation::new`], open to a caller with a tighter bound (a server's degree limit),
/// so that the refusal names the bound that applies where the caller is.
///
/// ```
/// use lekalo::blend::check_deformation_continuity;
/// assert_eq!(check_deformation_continuity(2, 64)?, 2);
/// let e = check_deformation_continuity(0, 64).unwrap_err();
/// assert!(e.to_string().contains("must be in 1..=64"), "{e}");
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] about [`Arg::Continuity`] for `continuity` outside `1..=max`.
pub fn check_deformation_continuity(continuity: usize, max: usize) -> Result<usize> {
    let max = max.min(MAX_DEFORMATION_CONTINUITY);
    if continuity == 0 || continuity > max {
        return Err(Error::InvalidArgument {
            what: Arg::Continuity.into(),
            reason: format!(
                "got {continuity}; k must be in 1..={max} (k = 1 is the linear blend; the \
                 deformation uses w_(k-1))"
            ),
        });
    }
    Ok(continuity)
}

/// The degree `(2k − 1) + max(d_1, d_2)` of [`Deformation::to_bezier`] of two polynomial pieces
/// of degrees `d_1`, `d_2` with continuity degree `k ≥ 1` (saturating, for any `k`).
///
/// ```
/// use lekalo::blend::deformation_bezier_degree;
/// assert_eq!(deformation_bezier_degree(2, 2, 2), 5); // two parabolas, C²
/// ```
#[must_use]
pub fn deformation_bezier_degree(d1: usize, d2: usize, continuity: usize) -> usize {
    (continuity.max(1).saturating_mul(2) - 1).saturating_add(d1.max(d2))
}

/// The largest continuity degree `k` whose [`Deformation::to_bezier`] of pieces of degrees `d_1`,
/// `d_2` has degree at most `max_degree` ([`deformation_bezier_degree`]), at most
/// [`MAX_DEFORMATION_CONTINUITY`]; 0 when even `k = 1` passes `max_degree`.
///
/// ```
/// use lekalo::blend::max_deformation_continuity;
/// assert_eq!(max_deformation_continuity(3, 3, 64), 31); // degree 61 + 3 = 64
/// assert_eq!(max_deformation_continuity(64, 1, 64), 0);
/// ```
#[must_use]
pub fn max_deformation_continuity(d1: usize, d2: usize, max_degree: usize) -> usize {
    ((max_degree + 1).saturating_sub(d1.max(d2)) / 2).min(MAX_DEFORMATION_CONTINUITY)
}

/// A parametric curve `c : [a, b] → R^dim` that can report its derivatives: the input of
/// [`Deformation`], [`CornerTransition`](crate::CornerTransition) and the local curves of splines.
///
/// Implemented for [`BezierCurve`], [`BSplineCurve`], [`NurbsCurve`], [`FnCurve`] (closures),
/// [`Deformation`], [`CornerTransition`](crate::CornerTransition), [`BlendSpline`](crate::BlendSpline), and references,
/// boxes and `Arc`s of those.
pub trait ParametricCurve {
    /// Dimension of the points.
    fn dim(&self) -> usize;

    /// Parameter domain `(a, b)`, `a < b`.
    fn domain(&self) -> (f64, f64);

    /// Derivatives `c^{(l)}(t)`, `l = 0 … order`, into `out` (length `(order + 1) · dim`, row
    /// `l` the l-th derivative; row 0 the point).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] for `t` outside the domain; [`Error::LengthMismatch`] for
    /// a wrong `out` length; anything a user-supplied curve returns.
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()>;

    /// The curve as a single Bezier or rational Bezier piece in the parameter
    /// `u = (t − a)/(b − a)`, if it is one; `None` otherwise (the default).
    fn bezier_form(&self) -> Option<BezierForm> {
        None
    }

    /// The point `c(t)`.
    ///
    /// # Errors
    /// As [`ParametricCurve::eval_derivatives_into`].
    fn eval(&self, t: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_derivatives_into(t, 0, &mut out)?;
        Ok(out)
    }
}

/// A curve piece in exact Bezier form over `u ∈ [0, 1]`, as returned by
/// [`ParametricCurve::bezier_form`].
#[derive(Debug, Clone, PartialEq)]
pub enum BezierForm {
    /// A polynomial piece.
    Polynomial(BezierCurve),
    /// A rational piece: a single-segment NURBS with knots `0, …, 0, 1, …, 1`.
    Rational(NurbsCurve),
}

impl BezierForm {
    /// Degree of the piece.
    #[must_use]
    pub fn degree(&self) -> usize {
        match self {
            BezierForm::Polynomial(b) => b.degree(),
            BezierForm::Rational(n) => n.degree(),
        }
    }

    /// Homogeneous control points `(w·P, w)` (weights 1 for a polynomial piece), flat, and the
    /// Euclidean dimension.
    pub(crate) fn homogeneous(&self) -> (Vec<f64>, usize) {
        match self {
            BezierForm::Polynomial(b) => {
                let dim = b.dim();
                let mut h = Vec::with_capacity(b.control_points().len() * (dim + 1));
                for p in b.control_points().iter() {
                    h.extend_from_slice(p);
                    h.push(1.0);
                }
                (h, dim)
            }
            BezierForm::Rational(n) => (
                n.homogeneous().control_points().as_slice().to_vec(),
                n.dim(),
            ),
        }
    }

    /// As a NURBS (unit weights for a polynomial piece).
    #[must_use]
    pub fn to_nurbs(&self) -> NurbsCurve {
        match self {
            BezierForm::Polynomial(b) => NurbsCurve::from_bspline(&bezier_as_bspline(b)),
            BezierForm::Rational(n) => n.clone(),
        }
    }
}

/// A Bezier curve as a single-segment B-spline on `[0, 1]`.
pub(crate) fn bezier_as_bspline(b: &BezierCurve) -> BSplineCurve {
    let p = b.degree();
    let mut knots = vec![0.0; p + 1];
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    BSplineCurve::from_raw(p, knots, b.control_points().clone())
}

/// Refuses derivative orders above [`MAX_DERIVATIVE_ORDER`](crate::MAX_DERIVATIVE_ORDER)
/// before any `(order + 1) · dim` allocation can overflow.
pub(crate) fn check_order(order: usize) -> Result<()> {
    crate::error::check_derivative_order(order, crate::MAX_DERIVATIVE_ORDER)
}

pub(crate) fn check_out_len(out: &[f64], order: usize, dim: usize) -> Result<()> {
    check_order(order)?;
    let expected = (order + 1) * dim;
    if out.len() != expected {
        return Err(Error::LengthMismatch {
            what: "derivative output ((order + 1) · dim)".into(),
            expected,
            got: out.len(),
        });
    }
    Ok(())
}

/// A curve of any kind is a [`ParametricCurve`] through its kind's implementation.
impl ParametricCurve for crate::Curve {
    fn dim(&self) -> usize {
        crate::Curve::dim(self)
    }
    fn domain(&self) -> (f64, f64) {
        crate::Curve::domain(self)
    }
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
        match self {
            crate::Curve::Bezier(c) => c.eval_derivatives_into(t, order, out),
            crate::Curve::BSpline(c) => c.eval_derivatives_into(t, order, out),
            crate::Curve::Nurbs(c) => c.eval_derivatives_into(t, order, out),
        }
    }
    fn bezier_form(&self) -> Option<BezierForm> {
        match self {
            crate::Curve::Bezier(c) => c.bezier_form(),
            crate::Curve::BSpline(c) => c.bezier_form(),
            crate::Curve::Nurbs(c) => c.bezier_form(),
        }
    }
}

/// An exact Bezier form as a curve: a Bezier curve, or a single-segment NURBS.
impl From<BezierForm> for crate::Curve {
    fn from(f: BezierForm) -> Self {
        match f {
            BezierForm::Polynomial(b) => crate::Curve::Bezier(b),
            BezierForm::Rational(n) => crate::Curve::Nurbs(n),
        }
    }
}

impl ParametricCurve for BezierCurve {
    fn dim(&self) -> usize {
        BezierCurve::dim(self)
    }
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    /// De Casteljau plus forward differences (Farin, *Curves and Surfaces for CAGD*, §5.4).
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
        check_unit(t)?;
        check_out_len(out, order, BezierCurve::dim(self))?;
        let ctrl = self.control_points().as_slice();
        bernstein_ops::with_work(2 * ctrl.len(), |work| {
            bernstein_ops::derivatives_at_in(ctrl, BezierCurve::dim(self), t, order, out, work);
        });
        Ok(())
    }
    fn bezier_form(&self) -> Option<BezierForm> {
        Some(BezierForm::Polynomial(self.clone()))
    }
}

impl ParametricCurve for BSplineCurve {
    fn dim(&self) -> usize {
        BSplineCurve::dim(self)
    }
    fn domain(&self) -> (f64, f64) {
        BSplineCurve::domain(self)
    }
    /// P&T Algorithm A3.2 via [`BSplineCurve::eval_derivatives`].
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
        check_out_len(out, order, BSplineCurve::dim(self))?;
        let d = self.eval_derivatives(t, order)?;
        out.copy_from_slice(d.as_slice());
        Ok(())
    }
    /// `Some` when the knot vector is a single clamped Bezier segment.
    fn bezier_form(&self) -> Option<BezierForm> {
        let p = self.degree();
        (self.control_points().len() == p + 1 && self.knots().is_clamped(p))
            .then(|| BezierForm::Polynomial(BezierCurve::from_raw(self.control_points().clone())))
    }
}

impl ParametricCurve for NurbsCurve {
    fn dim(&self) -> usize {
        NurbsCurve::dim(self)
    }
    fn domain(&self) -> (f64, f64) {
        NurbsCurve::domain(self)
    }
    /// [`NurbsCurve::eval_derivatives`] (quotient rule, P&T Algorithm A4.2).
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
        check_out_len(out, order, NurbsCurve::dim(self))?;
        let d = self.eval_derivatives(t, order)?;
        out.copy_from_slice(d.as_slice());
        Ok(())
    }
    /// `Some` when the knot vector is a single clamped Bezier segment.
    fn bezier_form(&self) -> Option<BezierForm> {
        let hom = self.homogeneous();
        let p = hom.degree();
        if hom.control_points().len() != p + 1 || !hom.knots().is_clamped(p) {
            return None;
        }
        let unit = bezier_as_bspline(&BezierCurve::from_raw(hom.control_points().clone()));
        NurbsCurve::from_homogeneous(unit)
            .ok()
            .map(BezierForm::Rational)
    }
}

/// Smart pointers and references to curves are curves: every method forwards to the pointee.
macro_rules! forward_parametric_curve {
    ($($ptr:ty),*) => {$(
        impl<C: ParametricCurve + ?Sized> ParametricCurve for $ptr {
            fn dim(&self) -> usize {
                (**self).dim()
            }
            fn domain(&self) -> (f64, f64) {
                (**self).domain()
            }
            fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
                (**self).eval_derivatives_into(t, order, out)
            }
            fn bezier_form(&self) -> Option<BezierForm> {
                (**self).bezier_form()
            }
        }
    )*};
}

forward_parametric_curve!(&C, Box<C>, Arc<C>);

/// A user-supplied curve: a closure `f(t, order, out)` that writes `c^{(l)}(t)`,
/// `l = 0 … order`, into `out` (row-major, `(order + 1) · dim`), on a domain `[a, b]`.
///
/// ```
/// use lekalo::{FnCurve, ParametricCurve};
/// // the parabola t ↦ (t, t²) on [0, 1]
/// let c = FnCurve::new(2, (0.0, 1.0), |t: f64, order: usize, out: &mut [f64]| {
///     out.fill(0.0);
///     out[..2].copy_from_slice(&[t, t * t]);
///     if order >= 1 { out[2..4].copy_from_slice(&[1.0, 2.0 * t]); }
///     if order >= 2 { out[5] = 2.0; }
///     Ok(())
/// })?;
/// assert_eq!(c.eval(0.5)?, vec![0.5, 0.25]);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Clone)]
pub struct FnCurve<F> {
    dim: usize,
    domain: (f64, f64),
    f: F,
}

impl<F> std::fmt::Debug for FnCurve<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FnCurve")
            .field("dim", &self.dim)
            .field("domain", &self.domain)
            .finish_non_exhaustive()
    }
}

impl<F: Fn(f64, usize, &mut [f64]) -> Result<()>> FnCurve<F> {
    /// A curve from a derivative-reporting closure.
    ///
    /// # Errors
    /// [`Error::Dimension`] if `dim == 0`; [`Error::NonFinite`] or [`Error::EmptyDomain`] unless
    /// the domain is finite with `a < b`.
    pub fn new(dim: usize, domain: (f64, f64), f: F) -> Result<Self> {
        if dim == 0 {
            return Err(Error::Dimension {
                what: "user curve".into(),
                expected: 1,
                got: 0,
            });
        }
        check_domain(domain)?;
        Ok(FnCurve { dim, domain, f })
    }
}

/// `a < b`, both finite.
pub(crate) fn check_domain((min, max): (f64, f64)) -> Result<()> {
    crate::error::check_finite("curve domain", &[min, max])?;
    if min >= max {
        return Err(Error::EmptyDomain { min, max });
    }
    Ok(())
}

fn check_in_domain(t: f64, (min, max): (f64, f64)) -> Result<()> {
    if !(t >= min && t <= max) {
        return Err(Error::ParameterOutOfDomain { t, min, max });
    }
    Ok(())
}

impl<F: Fn(f64, usize, &mut [f64]) -> Result<()>> ParametricCurve for FnCurve<F> {
    fn dim(&self) -> usize {
        self.dim
    }
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
        check_in_domain(t, self.domain)?;
        check_out_len(out, order, self.dim)?;
        (self.f)(t, order, out)?;
        crate::error::check_finite("user curve derivatives", out)
    }
}

/// `c(a + u (b − a))` and its derivatives in `u` (scaled by `(b − a)^l`), for `u ∈ [0, 1]`.
/// `u = 1` maps exactly to `b` (no rounding past the domain).
fn unit_derivatives<C: ParametricCurve + ?Sized>(
    c: &C,
    u: f64,
    order: usize,
    out: &mut [f64],
) -> Result<()> {
    let (a, b) = c.domain();
    let t = (a * (1.0 - u) + b * u).clamp(a, b);
    c.eval_derivatives_into(t, order, out)?;
    let dim = c.dim();
    let h = b - a;
    let mut scale = 1.0;
    for l in 1..=order {
        scale *= h;
        for x in &mut out[l * dim..(l + 1) * dim] {
            *x *= scale;
        }
    }
    Ok(())
}

/// Relative tolerance for "common end points": two end points are common when their distance is
/// at most this times the scale of the data, the largest of the absolute coordinates of the end
/// points involved and the chord between the first curve's ends.
pub const ENDPOINT_TOLERANCE: f64 = 1e-9;

/// Checks `|x − y| ≤ ENDPOINT_TOLERANCE · scale` (`scale` as documented there, `extra` the chord).
pub(crate) fn check_common(end: &'static str, x: &[f64], y: &[f64], extra: f64) -> Result<()> {
    let scale = x.iter().chain(y).fold(extra, |m, v| m.max(v.abs()));
    let distance = dist(x, y);
    let tolerance = ENDPOINT_TOLERANCE * scale;
    if distance > tolerance || distance.is_nan() {
        return Err(Error::EndPointMismatch {
            end,
            distance,
            tolerance,
        });
    }
    Ok(())
}

pub(crate) fn dist(x: &[f64], y: &[f64]) -> f64 {
    x.iter()
        .zip(y)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt()
}

/// The deformation of `p_1` into `p_2` with continuity degree `k` (document 001 §2;
/// docs/theory/blending.md#deformation-of-curves): `p(u) = (1 − w_{k−1}(u)) p_1(u) + w_{k−1}(u)
/// p_2(u)`, `u ∈ [0, 1]`; see the sections below for why `w_{k−1}` suffices.
///
/// # The construction (document 001 §2)
/// Two parametric curves `p_1, p_2 : [0, 1] → R^d` with **common end points**
/// (`p_1(0) = p_2(0)`, `p_1(1) = p_2(1)`) are blended into
///
/// ```text
/// p(u) = (1 − w_{k−1}(u)) p_1(u) + w_{k−1}(u) p_2(u),      u ∈ [0, 1],
/// ```
///
/// where `w_{k−1}` is the jump-smoothing polynomial of degree `2k − 1` ([`JumpPolynomial`]). The
/// result starts as `p_1` and ends as `p_2` with **continuity degree k**:
/// `p^{(l)}(0) = p_1^{(l)}(0)` and `p^{(l)}(1) = p_2^{(l)}(1)` for `l = 0 … k`.
///
/// # The index: `w_{k−1}`, not `w_k`
/// By Leibniz, `p^{(l)} = p_1^{(l)} + Σ_{i=0}^{l} C(l,i) w^{(i)} (p_2 − p_1)^{(l−i)}`. At `u = 0`
/// the term `i = 0` vanishes because `w(0) = 0`; the terms `1 ≤ i ≤ k − 1` vanish because
/// `w_{k−1}^{(i)}(0) = 0`; the term `i = l = k` is `w^{(k)}(0) (p_2 − p_1)(0)`, which vanishes
/// **because the end points are common**. So `w_{k−1}` already gives contact of order `k`, one
/// more than its own boundary conditions. Without common end points it gives only `k − 1`; with
/// `w_k` one would get `k + 1`. Derivative `k + 1` generally jumps (tested). `k = 1` is the
/// linear blend `(1 − u) p_1 + u p_2` with `w_0(u) = u`.
///
/// # Curves of any kind
/// Anything implementing [`ParametricCurve`] can be blended: [`BezierCurve`],
/// [`BSplineCurve`], [`NurbsCurve`], closures ([`FnCurve`]), other deformations, and the local
/// curves of [`BlendSpline`](crate::BlendSpline). A curve on `[a, b]` is used as
/// `u ↦ c(a + u (b − a))`, so its `l`-th derivative is scaled by `(b − a)^l`.
///
/// # Exact form
/// If `p_1, p_2` are polynomial of degrees `d_1, d_2`, `p` is a polynomial of degree
/// `(2k − 1) + max(d_1, d_2)` and [`Deformation::to_bezier`] returns its Bezier control points,
/// computed by Bernstein products (no monomial conversion). If they are rational
/// `p_i = A_i / ω_i` (for example circular arcs as rational quadratics), then
/// `p = [(1 − w) ω_2 A_1 + w ω_1 A_2] / (ω_1 ω_2)`, a rational Bezier of degree
/// `(2k − 1) + d_1 + d_2`: [`Deformation::to_nurbs`]. Its weights are positive when those of
/// `p_1, p_2` are (products and sums of positive Bernstein coefficients), so it exports to CAD.
///
/// # Corners
/// [`CornerTransition`](crate::CornerTransition) replaces a window around the corner where two curves meet by a
/// deformation with continuity degree `k` (the "smoothing of corners" named in document 001's
/// conclusion; the construction is ours and documented there).
///
/// ```
/// use lekalo::{BezierCurve, Deformation, ParametricCurve, Points};
/// // two parabolas from (0,0) to (2,0), one above and one below
/// let up = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?)?;
/// let down = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, -2.0], [2.0, 0.0]])?)?;
/// let p = Deformation::new(&up, &down, 2)?; // C² contact: w_1(u) = 3u² − 2u³
/// let d0 = p.eval_derivatives(0.0, 2)?;
/// let mut e0 = vec![0.0; 6];
/// up.eval_derivatives_into(0.0, 2, &mut e0)?;
/// assert_eq!(d0.as_slice(), &e0[..]); // starts as `up` up to the second derivative
/// let b = p.to_bezier()?; // exact: degree (2k − 1) + 2 = 5
/// assert_eq!(b.degree(), 5);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Deformation<C1, C2> {
    first: C1,
    second: C2,
    continuity: usize,
    jump: JumpPolynomial,
}

impl<C1: ParametricCurve, C2: ParametricCurve> Deformation<C1, C2> {
    /// The deformation of `first` into `second` with continuity degree `continuity = k ≥ 1`,
    /// using `w_{k−1}`. Each curve is used over its whole domain, mapped to `u ∈ [0, 1]`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if `continuity == 0` (use `k ≥ 1`; `k = 1` is the linear blend)
    /// or above [`MAX_DEFORMATION_CONTINUITY`]; [`Error::Dimension`] if the dimensions differ;
    /// [`Error::EndPointMismatch`] if the curves do not share both end points (relative tolerance
    /// [`ENDPOINT_TOLERANCE`]); evaluation errors of the curves.
    pub fn new(first: C1, second: C2, continuity: usize) -> Result<Self> {
        check_deformation_continuity(continuity, MAX_DEFORMATION_CONTINUITY)?;
        if first.dim() != second.dim() {
            return Err(Error::Dimension {
                what: "second curve (must match the first)".into(),
                expected: first.dim(),
                got: second.dim(),
            });
        }
        check_domain(first.domain())?;
        check_domain(second.domain())?;
        let dim = first.dim();
        let mut ends = vec![0.0; 4 * dim];
        for (i, u) in [0.0, 1.0].into_iter().enumerate() {
            unit_derivatives(&first, u, 0, &mut ends[2 * i * dim..(2 * i + 1) * dim])?;
            unit_derivatives(
                &second,
                u,
                0,
                &mut ends[(2 * i + 1) * dim..(2 * i + 2) * dim],
            )?;
        }
        let (a0, rest) = ends.split_at(dim);
        let (b0, rest) = rest.split_at(dim);
        let (a1, b1) = rest.split_at(dim);
        let chord = dist(a0, a1);
        check_common("start (u = 0)", a0, b0, chord)?;
        check_common("end (u = 1)", a1, b1, chord)?;
        let jump = JumpPolynomial::new(continuity - 1)?;
        Ok(Deformation {
            first,
            second,
            continuity,
            jump,
        })
    }

    /// The continuity degree `k`.
    #[must_use]
    pub fn continuity(&self) -> usize {
        self.continuity
    }

    /// The blending polynomial `w_{k−1}`.
    #[must_use]
    pub fn jump(&self) -> JumpPolynomial {
        self.jump
    }

    /// The curve deformed from (`p_1`).
    #[must_use]
    pub fn first(&self) -> &C1 {
        &self.first
    }

    /// The curve deformed into (`p_2`).
    #[must_use]
    pub fn second(&self) -> &C2 {
        &self.second
    }

    /// `p^{(l)}(u)`, `l = 0 … order`, as rows of [`Points`], by the Leibniz rule
    /// `p^{(l)} = p_1^{(l)} + Σ_{i=0}^{l} C(l,i) w^{(i)} (p_2 − p_1)^{(l−i)}` (document 001 §2).
    /// O(order² · dim) plus the curves' own cost.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ u ≤ 1`; [`Error::TooLarge`] for an order above
    /// [`MAX_DERIVATIVE_ORDER`](crate::MAX_DERIVATIVE_ORDER); errors of the curves.
    pub fn eval_derivatives(&self, u: f64, order: usize) -> Result<Points> {
        check_order(order)?;
        let dim = self.first.dim();
        let mut out = vec![0.0; (order + 1) * dim];
        self.eval_derivatives_into(u, order, &mut out)?;
        Ok(Points::from_raw(out, dim))
    }

    /// The exact Bezier form when both curves are polynomial pieces: degree
    /// `(2k − 1) + max(d_1, d_2)`, control points
    /// `(1 − w) ⊗ p_1 + w ⊗ p_2` by Bernstein products (Farouki & Rajan 1988), with the
    /// lower-degree term degree-elevated (a product with the constant 1).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if a curve has no polynomial Bezier form (use
    /// [`Deformation::to_nurbs`] for rational pieces).
    pub fn to_bezier(&self) -> Result<BezierCurve> {
        let (Some(f1 @ BezierForm::Polynomial(_)), Some(f2 @ BezierForm::Polynomial(_))) =
            (self.first.bezier_form(), self.second.bezier_form())
        else {
            return Err(Error::InvalidArgument {
                what: "curves of the deformation".into(),
                reason: "both must be polynomial Bezier pieces for an exact Bezier form; \
                         use to_nurbs for rational pieces"
                    .into(),
            });
        };
        match blend_forms(&f1, &f2, &self.jump)? {
            BezierForm::Polynomial(b) => Ok(b),
            BezierForm::Rational(_) => unreachable_form(),
        }
    }

    /// The exact rational Bezier form (a single-segment NURBS on `[0, 1]`) when both curves are
    /// polynomial or rational pieces: homogeneous control points
    /// `(1 − w) ω_2 (A_1, ω_1) + w ω_1 (A_2, ω_2)`, degree `(2k − 1) + d_1 + d_2` when a curve is
    /// rational (`(2k − 1) + max(d_1, d_2)` with unit weights when both are polynomial).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if a curve has no Bezier form (see
    /// [`ParametricCurve::bezier_form`]); [`Error::NonPositiveWeight`] cannot occur for positive
    /// input weights.
    pub fn to_nurbs(&self) -> Result<NurbsCurve> {
        let (Some(f1), Some(f2)) = (self.first.bezier_form(), self.second.bezier_form()) else {
            return Err(Error::InvalidArgument {
                what: "curves of the deformation".into(),
                reason: "both must be Bezier or rational Bezier pieces for an exact form".into(),
            });
        };
        Ok(blend_forms(&f1, &f2, &self.jump)?.to_nurbs())
    }
}

/// Never returned for two polynomial pieces; kept as an error rather than a panic.
fn unreachable_form() -> Result<BezierCurve> {
    debug_assert!(false, "blend of polynomial pieces must be polynomial");
    Err(Error::InvalidArgument {
        what: "curves of the deformation".into(),
        reason: "internal: expected a polynomial blend".into(),
    })
}

/// `(1 − w) p_1 + w p_2` in exact (rational) Bezier form, `w` the jump polynomial: the formulas
/// of [`Deformation::to_bezier`] (both polynomial) and [`Deformation::to_nurbs`] (otherwise).
pub(crate) fn blend_forms(
    f1: &BezierForm,
    f2: &BezierForm,
    jump: &JumpPolynomial,
) -> Result<BezierForm> {
    let w = jump.bernstein_coefficients_f64();
    let one_minus: Vec<f64> = w.iter().map(|x| 1.0 - x).collect();
    if let (BezierForm::Polynomial(b1), BezierForm::Polynomial(b2)) = (f1, f2) {
        let dim = b1.dim();
        let (d1, d2) = (b1.degree(), b2.degree());
        let d = d1.max(d2);
        let t1 = bernstein_ops::product(
            &one_minus,
            &elevate(b1.control_points().as_slice(), dim, d - d1),
            dim,
        );
        let t2 = bernstein_ops::product(
            &w,
            &elevate(b2.control_points().as_slice(), dim, d - d2),
            dim,
        );
        let ctrl: Vec<f64> = t1.iter().zip(&t2).map(|(a, b)| a + b).collect();
        return Ok(BezierForm::Polynomial(BezierCurve::from_raw(
            Points::from_flat(dim, ctrl)?,
        )));
    }
    let (h1, dim) = f1.homogeneous();
    let (h2, _) = f2.homogeneous();
    let hd = dim + 1;
    let (omega1, omega2) = (weights_of(&h1, dim), weights_of(&h2, dim));
    // (1 − w) ω_2 H_1 and w ω_1 H_2, then elevate to the common degree
    let t1 = bernstein_ops::product(&bernstein_ops::product(&one_minus, &omega2, 1), &h1, hd);
    let t2 = bernstein_ops::product(&bernstein_ops::product(&w, &omega1, 1), &h2, hd);
    let (n1, n2) = (t1.len() / hd - 1, t2.len() / hd - 1);
    let n = n1.max(n2);
    let t1 = elevate(&t1, hd, n - n1);
    let t2 = elevate(&t2, hd, n - n2);
    let h: Vec<f64> = t1.iter().zip(&t2).map(|(a, b)| a + b).collect();
    let bez = BezierCurve::from_raw(Points::from_flat(hd, h)?);
    Ok(BezierForm::Rational(NurbsCurve::from_homogeneous(
        bezier_as_bspline(&bez),
    )?))
}

/// The derivatives `l = 0 … order` of `p = p_1 + w·(p_2 − p_1)` by Leibniz's rule,
/// `p^(l) = p_1^(l) + Σ_i C(l,i) w^(i) (p_2 − p_1)^(l−i)` (document 001, the deformation): `out`
/// holds the derivatives of `p_1` on entry and of `p` on return, `second` those of `p_2` (it is
/// overwritten by `p_2 − p_1`), `w` those of the blending function; rows of `dim` numbers. Terms
/// with a zero coefficient are skipped (so that `0·∞` does not turn into NaN). An overflow, for
/// curves near `f64::MAX` (found by the `blending` fuzz target), is [`Error::NonFinite`] naming
/// `what`, never NaN inside an `Ok`.
pub(crate) fn blend_derivatives(
    out: &mut [f64],
    second: &mut [f64],
    w: &[f64],
    dim: usize,
    what: impl Into<What>,
) -> Result<()> {
    let what: What = what.into();
    for (s, f) in second.iter_mut().zip(out.iter()) {
        *s -= f;
    }
    for l in 0..w.len() {
        let mut binom = 1.0;
        for i in 0..=l {
            if i > 0 {
                binom = binom * (l + 1 - i) as f64 / i as f64;
            }
            let c = binom * w[i];
            if c == 0.0 {
                continue;
            }
            for d in 0..dim {
                out[l * dim + d] += c * second[(l - i) * dim + d];
            }
        }
    }
    crate::error::check_finite(what, out)
}

/// The weights (last coordinates) of flat homogeneous points.
pub(crate) fn weights_of(h: &[f64], dim: usize) -> Vec<f64> {
    h.iter().skip(dim).step_by(dim + 1).copied().collect()
}

/// Degree elevation by `r` (document 004 eq. 8, [`crate::degree::elevation`]'s closed form).
pub(crate) fn elevate(ctrl: &[f64], dim: usize, r: usize) -> Vec<f64> {
    crate::degree::elevation::elevate(ctrl, dim, r)
}

impl<C1: ParametricCurve, C2: ParametricCurve> ParametricCurve for Deformation<C1, C2> {
    fn dim(&self) -> usize {
        self.first.dim()
    }
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval_derivatives_into(&self, u: f64, order: usize, out: &mut [f64]) -> Result<()> {
        check_unit(u)?;
        let dim = self.first.dim();
        check_out_len(out, order, dim)?;
        // the second curve's derivatives, then the jump polynomial's, in one work slice
        bernstein_ops::with_work(out.len() + order + 1, |work| {
            let (second, w) = work.split_at_mut(out.len());
            unit_derivatives(&self.first, u, order, out)?;
            unit_derivatives(&self.second, u, order, second)?;
            self.jump.eval_derivatives(u, w)?;
            blend_derivatives(
                out,
                second,
                w,
                dim,
                "deformation derivatives (overflow: rescale the curves)",
            )
        })
    }
    fn bezier_form(&self) -> Option<BezierForm> {
        match (self.first.bezier_form()?, self.second.bezier_form()?) {
            (BezierForm::Polynomial(_), BezierForm::Polynomial(_)) => {
                self.to_bezier().ok().map(BezierForm::Polynomial)
            }
            _ => self.to_nurbs().ok().map(BezierForm::Rational),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic(rows: [[f64; 2]; 4]) -> BezierCurve {
        BezierCurve::new(Points::from_2d(&rows).unwrap()).unwrap()
    }

    fn max_diff(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    /// Contact order at u = 0 of `d` with `p1` (largest l with matching derivatives 0..=l).
    fn contact(d: &Points, p1: &BezierCurve, max: usize) -> usize {
        let mut e = vec![0.0; 2 * (max + 1)];
        p1.eval_derivatives_into(0.0, max, &mut e).unwrap();
        (0..=max)
            .take_while(|&l| max_diff(d.point(l), &e[2 * l..2 * l + 2]) < 1e-10)
            .last()
            .unwrap_or(0)
    }

    // The index subtlety of document 001 §2 (docs/theory/blending.md#why-the-index-is-k-1), checked
    // on the formula itself: with common end points w_{k−1} gives contact of order exactly k and
    // w_k order k + 1; without common end points w_{k−1} gives only k − 1.
    #[test]
    fn index_of_the_jump_polynomial() {
        let p1 = cubic([[0.0, 0.0], [1.0, 2.0], [2.0, 2.5], [3.0, 0.0]]);
        let p2 = cubic([[0.0, 0.0], [1.5, 1.0], [2.5, -1.0], [3.0, 0.0]]);
        let shifted = cubic([[0.0, 0.5], [1.5, 1.0], [2.5, -1.0], [3.0, 0.0]]);
        for k in 1..=4 {
            let with = |second: &BezierCurve, index: usize| Deformation {
                first: p1.clone(),
                second: second.clone(),
                continuity: k,
                jump: JumpPolynomial::new(index).unwrap(),
            };
            let d = with(&p2, k - 1).eval_derivatives(0.0, k + 2).unwrap();
            assert_eq!(contact(&d, &p1, k + 2), k, "w_(k-1), k = {k}");
            let d = with(&p2, k).eval_derivatives(0.0, k + 2).unwrap();
            assert_eq!(contact(&d, &p1, k + 2), k + 1, "w_k, k = {k}");
            // bypassing the end-point check on purpose: order k − 1 only (and for k = 1 not
            // even the point, which is why `new` refuses such curves)
            let d = with(&shifted, k - 1).eval_derivatives(0.0, k + 2).unwrap();
            let c = contact(&d, &p1, k + 2);
            if k == 1 {
                assert!(
                    max_diff(d.point(1), &[3.0, 6.0]) > 0.1,
                    "k = 1 without common ends"
                );
            } else {
                assert_eq!(c, k - 1, "w_(k-1) without common ends, k = {k}");
            }
        }
    }

    #[test]
    fn bezier_forms_of_library_curves() {
        let b = cubic([[0.0, 0.0], [1.0, 2.0], [2.0, 2.5], [3.0, 0.0]]);
        let single = bezier_as_bspline(&b);
        assert_eq!(
            single.bezier_form(),
            Some(BezierForm::Polynomial(b.clone()))
        );
        let two = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 0.5, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]).unwrap(),
        )
        .unwrap();
        assert_eq!(two.bezier_form(), None);
        assert_eq!(NurbsCurve::from_bspline(&two).bezier_form(), None);
        let f = BezierForm::Polynomial(b.clone());
        assert_eq!(f.degree(), 3);
        assert_eq!(f.to_nurbs().weights(), vec![1.0; 4]);
        // BSpline derivatives through the trait equal the inherent ones
        let mut out = vec![0.0; 6];
        single.eval_derivatives_into(0.3, 2, &mut out).unwrap();
        assert_eq!(out, single.eval_derivatives(0.3, 2).unwrap().into_vec());
        assert!(matches!(
            single.eval_derivatives_into(0.3, 2, &mut [0.0; 5]),
            Err(Error::LengthMismatch { .. })
        ));
    }
}
