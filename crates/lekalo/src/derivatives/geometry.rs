//! Derivatives of two queries of a B-spline curve where they are smooth
//! (`docs/theory/derivatives.md#arc-length-and-closest-points`):
//!
//! - the arc length over the domain, `L = ∫ |C'(t)| dt`, with respect to the control points:
//!   `∂L/∂P_j = ∫ N'_{j,p}(t) T(t) dt` with `T = C'/|C'|`, on the nodes and weights of the
//!   adaptive Gauss–Legendre table that computes `L` ([`crate::QueryCurve::arc_length`]), so that
//!   the gradient is that of the number returned;
//! - the parameter `t*` of the closest point of the curve to a point `x`, a root of
//!   `g(t) = (C(t) − x)·C'(t)`, with respect to the control points and `x`, by the implicit
//!   function theorem: `ṫ = −(∂g/∂P · Ṗ + ∂g/∂x · ẋ) / g'(t*)` with `∂g/∂P_j = N_j C' +
//!   N'_j (C − x)`, `∂g/∂x = −C'` and `g' = |C'|² + (C − x)·C''`. At an end of the domain the
//!   closest point stays at the end under a small change (the distance grows into the domain):
//!   the derivative is zero there, and likewise at a corner of the curve (a knot where `C'`
//!   jumps), where the distance has a kink.
//! - both with respect to the knots ([`ArcLengthGradient::with_knots`],
//!   [`ClosestParameters::with_knots`]): `geometry_knots.rs`, the domain's ends by the queries'
//!   behaviour under an affine map of the knots, the interior knots by the knot derivatives of
//!   `C` and of its derivative curve `C'`; `geometry_knots_tests.rs` its tests.

use super::checks::{check_input, check_len};
use super::curve::{combine, PointBasis};
use crate::curve::BSplineCurve;
use crate::error::{check_finite, Error, Result};
use crate::points::PointsRef;
use crate::query::{QueryCurve, DEFAULT_LENGTH_RTOL};

/// The length of a B-spline curve over its domain and its gradient with respect to the
/// control points (`docs/theory/derivatives.md#arc-length-and-closest-points`).
///
/// ```
/// use lekalo::derivatives::ArcLengthGradient;
/// use lekalo::{BSplineCurve, Points};
/// // a straight segment of length 5: moving its end point along the segment lengthens it at
/// // rate 1, across it not at all
/// let c = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_2d(&[[0.0, 0.0], [3.0, 4.0]])?)?;
/// let g = ArcLengthGradient::new(&c)?;
/// assert!((g.length() - 5.0).abs() < 1e-14);
/// assert!((g.jvp(&[0.0, 0.0, 0.6, 0.8])? - 1.0).abs() < 1e-14);
/// assert!(g.jvp(&[0.0, 0.0, -0.8, 0.6])?.abs() < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct ArcLengthGradient {
    length: f64,
    gradient: Vec<f64>,
    /// `∂L/∂τ`, when built by [`ArcLengthGradient::with_knots`].
    knot_gradient: Option<Vec<f64>>,
}

impl ArcLengthGradient {
    /// The length ([`crate::QueryCurve::length`], the same number) and `∂L/∂P` (as the control
    /// points): `Σ_nodes weight · N'_j(t) T(t)` on the table's nodes. Where the curve stands
    /// still (`C' = 0`, a cusp) the node adds nothing: the length is not differentiable
    /// there, and this is the derivative of the smooth rest.
    ///
    /// # Errors
    /// As [`QueryCurve::from_bspline`] and [`crate::QueryCurve::arc_length`].
    pub fn new(curve: &BSplineCurve) -> Result<Self> {
        Ok(Self::build(curve, false)?.0)
    }

    /// [`ArcLengthGradient::new`]; with `nodes`, also the quadrature's nodes `t` and the
    /// cotangents `weight · T(t)` of `C'(t)` there (`nodes × dim`), for the knot gradient.
    fn build(curve: &BSplineCurve, nodes: bool) -> Result<(Self, Vec<f64>, Vec<f64>)> {
        let q = QueryCurve::from_bspline(curve)?;
        let table = q.arc_length(DEFAULT_LENGTH_RTOL)?;
        let (p, dim) = (curve.degree(), curve.dim());
        let (knots, ctrl) = (curve.knots().as_slice(), curve.control_points().as_slice());
        let mut gradient = vec![0.0; ctrl.len()];
        let mut cursor = curve.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut d = vec![0.0; dim];
        let mut failed = None;
        let (mut ts, mut cot) = (Vec::new(), Vec::new());
        table.for_each_node(|t, weight| {
            let span = match cursor.find(t) {
                Ok(s) => s,
                Err(e) => {
                    if failed.is_none() {
                        failed = Some(e);
                    }
                    return;
                }
            };
            let first = basis.at(knots, p, span, t);
            combine(ctrl, dim, first, basis.slopes(), &mut d);
            let speed = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            if nodes {
                ts.push(t);
                let s = if speed > 0.0 { weight / speed } else { 0.0 };
                cot.extend(d.iter().map(|x| s * x));
            }
            if speed > 0.0 {
                let s = weight / speed;
                for (k, &nk) in basis.slopes().iter().enumerate() {
                    let g = &mut gradient[(first + k) * dim..(first + k + 1) * dim];
                    for (gc, dc) in g.iter_mut().zip(&d) {
                        *gc += s * nk * dc;
                    }
                }
            }
        });
        if let Some(e) = failed {
            return Err(e);
        }
        let g = ArcLengthGradient {
            length: table.total(),
            gradient,
            knot_gradient: None,
        };
        Ok((g, ts, cot))
    }

    /// The length.
    #[must_use]
    pub fn length(&self) -> f64 {
        self.length
    }

    /// `∂L/∂P`, as the control points (`n × dim`, point-major).
    #[must_use]
    pub fn gradient(&self) -> &[f64] {
        &self.gradient
    }

    /// Forward-mode derivative: `L̇ = Σ_j ∂L/∂P_j · Ṗ_j` for a control-point tangent `Ṗ`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `control_tangent` is shaped as the control points;
    /// [`Error::NonFinite`].
    pub fn jvp(&self, control_tangent: &[f64]) -> Result<f64> {
        check_len(
            "control-point tangent (as the control points)",
            self.gradient.len(),
            control_tangent.len(),
        )?;
        check_finite("control-point tangent", control_tangent)?;
        Ok(self
            .gradient
            .iter()
            .zip(control_tangent)
            .map(|(g, t)| g * t)
            .sum())
    }

    /// Reverse-mode derivative: `P̄ = L̄ ∂L/∂P` for a cotangent `L̄` of the length.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a cotangent that is not finite.
    pub fn vjp(&self, cotangent: f64) -> Result<Vec<f64>> {
        check_finite("length cotangent", &[cotangent])?;
        Ok(self.gradient.iter().map(|g| cotangent * g).collect())
    }
}

/// The control-point and point cotangents of [`ClosestParameters::vjp`], each when asked for.
pub type Cotangents = (Option<Vec<f64>>, Option<Vec<f64>>);

/// The parameters of the closest points of a B-spline curve to points `x_i`
/// ([`crate::QueryCurve::project`]) and their derivatives with respect to the control points and
/// the points (`docs/theory/derivatives.md#arc-length-and-closest-points`): per point, the basis
/// functions and their derivatives at `t*`, `C'(t*)`, `C(t*) − x` and `1/g'(t*)` (0 at an end of
/// the domain), so that the JVP and the VJP are sparse products, `p + 1` control points a point.
///
/// ```
/// use lekalo::derivatives::ClosestParameters;
/// use lekalo::{BSplineCurve, Points};
/// // the segment from (0, 0) to (2, 0) on [0, 1]: the closest point to (x, y) is at t = x / 2
/// let c = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_2d(&[[0.0, 0.0], [2.0, 0.0]])?)?;
/// let cp = ClosestParameters::new(&c, &[0.5, 1.0])?;
/// assert!((cp.params()[0] - 0.25).abs() < 1e-15);
/// let dt = cp.jvp(None, Some(&[1.0, 0.0]))?;           // moving x by 1 moves t by 1/2
/// assert!((dt[0] - 0.5).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct ClosestParameters {
    dim: usize,
    width: usize,
    n_ctrl_scalars: usize,
    params: Vec<f64>,
    first: Vec<usize>,
    /// `N_{first+k}(t*)`, `m × (p + 1)`.
    basis: Vec<f64>,
    /// `N'_{first+k}(t*)`, `m × (p + 1)`.
    slopes: Vec<f64>,
    /// `C'(t*)`, `m × dim`.
    tangent: Vec<f64>,
    /// `C(t*) − x`, `m × dim`.
    offset: Vec<f64>,
    /// `1/g'(t*)`, 0 at an end of the domain and at a corner.
    inverse: Vec<f64>,
    /// The first and last index of the knot at a corner `t*` lies on.
    corners: Vec<Option<(usize, usize)>>,
    /// The curve and its derivative curve, when built by [`ClosestParameters::with_knots`].
    knots: Option<Box<knots::ClosestKnots>>,
}

impl ClosestParameters {
    /// The closest points of `curve` to `points` (`m × dim`, point-major) and what their
    /// derivatives need.
    ///
    /// # Errors
    /// As [`QueryCurve::from_bspline`] and [`crate::QueryCurve::project_batch`];
    /// [`Error::InvalidArgument`] where the distance has no isolated minimum at the closest
    /// point (`g'(t*) ≤ 0`: the point at the centre of curvature of the curve there), where
    /// the parameter is not differentiable.
    pub fn new(curve: &BSplineCurve, points: &[f64]) -> Result<Self> {
        let (p, dim) = (curve.degree(), curve.dim());
        let pts = PointsRef::from_flat(dim, points)?;
        let found = QueryCurve::from_bspline(curve)?.project_batch(pts)?;
        let m = found.len();
        let width = p + 1;
        let (knots, ctrl) = (curve.knots().as_slice(), curve.control_points().as_slice());
        let (lo, hi) = curve.domain();
        let mut cp = ClosestParameters {
            dim,
            width,
            n_ctrl_scalars: ctrl.len(),
            params: Vec::with_capacity(m),
            first: Vec::with_capacity(m),
            basis: Vec::with_capacity(m * width),
            slopes: Vec::with_capacity(m * width),
            tangent: vec![0.0; m * dim],
            offset: vec![0.0; m * dim],
            inverse: Vec::with_capacity(m),
            knots: None,
            corners: Vec::with_capacity(m),
        };
        let mut cursor = curve.knots().span_cursor(p);
        let mut basis = PointBasis::new(p);
        let mut at = vec![0.0; dim];
        let mut corner_basis = (PointBasis::new(p), vec![0.0; dim], vec![0.0; dim]);
        for (i, proj) in found.iter().enumerate() {
            let t = proj.t;
            let first = basis.at(knots, p, cursor.find(t)?, t);
            let d = &mut cp.tangent[i * dim..(i + 1) * dim];
            combine(ctrl, dim, first, basis.slopes(), d);
            combine(ctrl, dim, first, basis.values(), &mut at);
            let r = &mut cp.offset[i * dim..(i + 1) * dim];
            for ((rc, a), x) in r.iter_mut().zip(&at).zip(pts.point(i)) {
                *rc = a - x;
            }
            let corner = corner_at(curve, &mut corner_basis, t);
            let inverse = if t <= lo || t >= hi || corner.is_some() {
                0.0
            } else {
                let second = curve.eval_derivatives(t, 2)?;
                let dd: f64 = d.iter().map(|v| v * v).sum();
                let rc: f64 = r.iter().zip(second.point(2)).map(|(a, b)| a * b).sum();
                let gt = dd + rc;
                if gt.is_nan() || gt <= 0.0 {
                    return Err(Error::InvalidArgument {
                        what: "point for the closest-point parameter".into(),
                        reason: format!(
                            "point {i} has no isolated closest point at t = {t} (it lies at the \
                             curve's centre of curvature there, where the distance is flat): \
                             the parameter is not differentiable; move the point"
                        ),
                    });
                }
                1.0 / gt
            };
            cp.params.push(t);
            cp.first.push(first);
            cp.basis.extend_from_slice(basis.values());
            cp.slopes.extend_from_slice(basis.slopes());
            cp.inverse.push(inverse);
            cp.corners.push(corner);
        }
        Ok(cp)
    }

    /// The closest points' parameters, one a point.
    #[must_use]
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// Forward-mode derivative: `ṫ_i = (C'·ẋ_i − Σ_k (N_k C' + N'_k (C − x_i))·Ṗ_{first+k}) /
    /// g'(t*_i)` for a control-point tangent `Ṗ` (as the control points) and a point tangent
    /// `ẋ` (as the points), each optional (`None` is zero).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] for a tangent of another shape; [`Error::NonFinite`].
    pub fn jvp(
        &self,
        control_tangent: Option<&[f64]>,
        point_tangent: Option<&[f64]>,
    ) -> Result<Vec<f64>> {
        let dim = self.dim;
        check_input(
            "control-point tangent (as the control points)",
            self.n_ctrl_scalars,
            control_tangent,
        )?;
        check_input(
            "point tangent (as the points)",
            self.params.len() * dim,
            point_tangent,
        )?;
        let mut out = vec![0.0; self.params.len()];
        for (i, o) in out.iter_mut().enumerate() {
            if self.inverse[i] == 0.0 {
                continue;
            }
            let (d, r) = (self.row(&self.tangent, i), self.row(&self.offset, i));
            let mut s = 0.0;
            if let Some(xt) = point_tangent {
                s += dot(d, &xt[i * dim..(i + 1) * dim]);
            }
            if let Some(pt) = control_tangent {
                let (n, ns) = self.basis_row(i);
                let block = &pt[self.first[i] * dim..(self.first[i] + self.width) * dim];
                for ((nk, sk), pj) in n.iter().zip(ns).zip(block.chunks_exact(dim)) {
                    s -= nk * dot(d, pj) + sk * dot(r, pj);
                }
            }
            *o = s * self.inverse[i];
        }
        Ok(out)
    }

    /// Reverse-mode derivative, the transpose of [`ClosestParameters::jvp`]: for a cotangent `t̄`
    /// (one a point), the control-point cotangent (as the control points) when `control` and
    /// the point cotangent (as the points) when `points`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `cotangent` has one number a point; [`Error::NonFinite`].
    pub fn vjp(&self, cotangent: &[f64], control: bool, points: bool) -> Result<Cotangents> {
        let (dim, w, m) = (self.dim, self.width, self.params.len());
        check_len("parameter cotangent (one a point)", m, cotangent.len())?;
        check_finite("parameter cotangent", cotangent)?;
        let mut gc = control.then(|| vec![0.0; self.n_ctrl_scalars]);
        let mut gx = points.then(|| vec![0.0; m * dim]);
        for (i, &g) in cotangent.iter().enumerate() {
            let s = g * self.inverse[i];
            if s == 0.0 {
                continue;
            }
            let (d, r) = (self.row(&self.tangent, i), self.row(&self.offset, i));
            if let Some(gx) = gx.as_mut() {
                for (o, dc) in gx[i * dim..(i + 1) * dim].iter_mut().zip(d) {
                    *o += s * dc;
                }
            }
            if let Some(gc) = gc.as_mut() {
                let (n, ns) = self.basis_row(i);
                let block = &mut gc[self.first[i] * dim..(self.first[i] + w) * dim];
                for ((nk, sk), pj) in n.iter().zip(ns).zip(block.chunks_exact_mut(dim)) {
                    for ((o, dc), rc) in pj.iter_mut().zip(d).zip(r) {
                        *o -= s * (nk * dc + sk * rc);
                    }
                }
            }
        }
        Ok((gc, gx))
    }

    /// The basis functions and their derivatives at point `i`'s parameter.
    fn basis_row(&self, i: usize) -> (&[f64], &[f64]) {
        let w = self.width;
        (
            &self.basis[i * w..(i + 1) * w],
            &self.slopes[i * w..(i + 1) * w],
        )
    }

    fn row<'a>(&self, v: &'a [f64], i: usize) -> &'a [f64] {
        &v[i * self.dim..(i + 1) * self.dim]
    }
}

/// Where `t` is an interior knot of multiplicity `μ ≥ p` at which `C'` jumps (a corner of the
/// curve), the first and last index of its copies: a closest point there stays on the corner
/// under small changes (the distance has a kink, not a smooth minimum, in `t`).
fn corner_at(
    curve: &BSplineCurve,
    (basis, left, right): &mut (PointBasis, Vec<f64>, Vec<f64>),
    t: f64,
) -> Option<(usize, usize)> {
    let (p, dim, n) = (curve.degree(), curve.dim(), curve.control_points().len());
    let (knots, ctrl) = (curve.knots().as_slice(), curve.control_points().as_slice());
    let first = knots[p + 1..n].partition_point(|&k| k < t) + p + 1;
    let last = knots[p + 1..n].partition_point(|&k| k <= t) + p;
    if first > last || last + 1 - first < p {
        return None;
    }
    let f = basis.at(knots, p, first - 1, t);
    combine(ctrl, dim, f, basis.slopes(), left);
    let f = basis.at(knots, p, last, t);
    combine(ctrl, dim, f, basis.slopes(), right);
    let size = dot(left, left).max(dot(right, right)).sqrt();
    let gap: f64 = left
        .iter()
        .zip(right.iter())
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt();
    (gap > 1e-9 * size).then_some((first, last))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[path = "geometry_knots.rs"]
mod knots;

#[cfg(test)]
#[path = "geometry_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "geometry_knots_tests.rs"]
mod knots_tests;
