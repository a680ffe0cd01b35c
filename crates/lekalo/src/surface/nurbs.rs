//! NURBS surfaces: a [`BSplineSurface`] over homogeneous control points `(w·P, w)` in dimension
//! `dim + 1`; the rational surface is the projection `S(u, v) = A(u, v) / w(u, v)` (P&T §4.4).
//! Net layout and derivative tables as in [`crate::surface::bspline`].

use serde::{Deserialize, Serialize};

use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::{
    check_homogeneous, dehomogenize, homogenize, weights_of, with_unit_weights, Points,
};
use crate::surface::bspline::{
    check_buffer, check_net, check_normal_dim, check_out, unit_normal, BSplineSurface,
};

/// A rational tensor-product B-spline surface.
///
/// ```
/// use lekalo::{NurbsSurface, Points};
/// use std::f64::consts::FRAC_1_SQRT_2 as H;
/// // a quarter of a cylinder of radius 1 around the z axis, height 2
/// let net = Points::from_3d(&[
///     [1.0, 0.0, 0.0], [1.0, 0.0, 2.0],
///     [1.0, 1.0, 0.0], [1.0, 1.0, 2.0],
///     [0.0, 1.0, 0.0], [0.0, 1.0, 2.0],
/// ])?;
/// let weights = vec![1.0, 1.0, H, H, 1.0, 1.0];
/// let s = NurbsSurface::new(2, 1, vec![0., 0., 0., 1., 1., 1.], vec![0., 0., 1., 1.], net, weights, (3, 2))?;
/// let p = s.eval(0.3, 0.5)?;
/// assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-15 && (p[2] - 1.0).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "NurbsSurfaceRepr", into = "NurbsSurfaceRepr")]
pub struct NurbsSurface {
    /// The B-spline surface in homogeneous coordinates (dimension `dim + 1`, weight last).
    homogeneous: BSplineSurface,
}

#[derive(Serialize, Deserialize)]
struct NurbsSurfaceRepr {
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    net_size: (usize, usize),
    control: Points,
    weights: Vec<f64>,
}

impl TryFrom<NurbsSurfaceRepr> for NurbsSurface {
    type Error = Error;
    fn try_from(r: NurbsSurfaceRepr) -> Result<Self> {
        NurbsSurface::new(
            r.degree_u, r.degree_v, r.knots_u, r.knots_v, r.control, r.weights, r.net_size,
        )
    }
}

impl From<NurbsSurface> for NurbsSurfaceRepr {
    fn from(s: NurbsSurface) -> Self {
        let control = s.control_points();
        let weights = s.weights();
        let net_size = s.net_size();
        NurbsSurfaceRepr {
            degree_u: s.degree_u(),
            degree_v: s.degree_v(),
            knots_u: s.knots_u().as_slice().to_vec(),
            knots_v: s.knots_v().as_slice().to_vec(),
            net_size,
            control,
            weights,
        }
    }
}

impl NurbsSurface {
    /// A NURBS surface from degrees, knot vectors, the Euclidean control net (`net_size =
    /// (nu, nv)`, point `(i, j)` at index `i·nv + j`) and one positive weight per control point
    /// (same layout).
    ///
    /// # Errors
    /// As [`BSplineSurface::new`], and [`Error::LengthMismatch`] if there is not one weight per
    /// control point, [`Error::NonFinite`] for a non-finite weight (or an overflowing `w·P`),
    /// [`Error::NonPositiveWeight`] for a weight `≤ 0` (the index is the flat index `i·nv + j`).
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: impl Into<Vec<f64>>,
        knots_v: impl Into<Vec<f64>>,
        control: Points,
        weights: Vec<f64>,
        net_size: (usize, usize),
    ) -> Result<Self> {
        check_net(&control, net_size)?;
        let homogeneous = BSplineSurface::new(
            degree_u,
            degree_v,
            knots_u,
            knots_v,
            homogenize(&control, &weights)?,
            net_size,
        )?;
        Ok(NurbsSurface { homogeneous })
    }

    /// A NURBS surface from a B-spline surface in homogeneous coordinates (last coordinate the
    /// weight).
    ///
    /// # Errors
    /// [`Error::Dimension`] if the dimension is below 2; [`Error::NonPositiveWeight`].
    pub fn from_homogeneous(homogeneous: BSplineSurface) -> Result<Self> {
        check_homogeneous(homogeneous.control_points())?;
        Ok(NurbsSurface { homogeneous })
    }

    /// Trusted constructor for homogeneous surfaces built inside the crate, whose weights are
    /// positive by construction (debug-checked).
    pub(crate) fn from_homogeneous_unchecked(homogeneous: BSplineSurface) -> Self {
        debug_assert!(
            Self::from_homogeneous(homogeneous.clone()).is_ok(),
            "raw homogeneous NURBS surface"
        );
        NurbsSurface { homogeneous }
    }

    /// The same surface with unit weights.
    #[must_use]
    pub fn from_bspline(surface: &BSplineSurface) -> Self {
        let homogeneous = BSplineSurface::from_raw(
            surface.degree_u(),
            surface.degree_v(),
            surface.knots_u().clone(),
            surface.knots_v().clone(),
            with_unit_weights(surface.control_points()),
        );
        NurbsSurface { homogeneous }
    }

    /// The homogeneous B-spline surface `(w·P, w)`.
    #[must_use]
    pub fn homogeneous(&self) -> &BSplineSurface {
        &self.homogeneous
    }

    /// Degrees `(p, q)` in `u` and `v` (the pair of [`NurbsCurve::degree`](crate::NurbsCurve::degree)).
    #[must_use]
    pub fn degree(&self) -> (usize, usize) {
        self.homogeneous.degree()
    }

    /// Knot vectors in `u` and `v` (the pair of [`NurbsCurve::knots`](crate::NurbsCurve::knots)).
    #[must_use]
    pub fn knots(&self) -> (&KnotVector, &KnotVector) {
        self.homogeneous.knots()
    }

    /// Degree in `u`.
    #[must_use]
    pub fn degree_u(&self) -> usize {
        self.homogeneous.degree_u()
    }

    /// Degree in `v`.
    #[must_use]
    pub fn degree_v(&self) -> usize {
        self.homogeneous.degree_v()
    }

    /// Knot vector in `u`.
    #[must_use]
    pub fn knots_u(&self) -> &KnotVector {
        self.homogeneous.knots_u()
    }

    /// Knot vector in `v`.
    #[must_use]
    pub fn knots_v(&self) -> &KnotVector {
        self.homogeneous.knots_v()
    }

    /// Net size `(nu, nv)`.
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        self.homogeneous.net_size()
    }

    /// Euclidean dimension.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.homogeneous.dim() - 1
    }

    /// Parameter domain `((u_min, u_max), (v_min, v_max))`.
    #[must_use]
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        self.homogeneous.domain()
    }

    /// Weights, in net order.
    #[must_use]
    pub fn weights(&self) -> Vec<f64> {
        weights_of(self.homogeneous.control_points())
    }

    /// Weight of control point `(i, j)`, or `None` outside the net.
    #[must_use]
    pub fn weight(&self, i: usize, j: usize) -> Option<f64> {
        self.homogeneous.control_point(i, j).map(|p| p[p.len() - 1])
    }

    /// Euclidean control net `P_{i,j} = (w·P_{i,j}) / w_{i,j}`.
    #[must_use]
    pub fn control_points(&self) -> Points {
        dehomogenize(self.homogeneous.control_points())
    }

    /// Euclidean control point `P_{i,j}`, or `None` outside the net.
    #[must_use]
    pub fn control_point(&self, i: usize, j: usize) -> Option<Vec<f64>> {
        self.homogeneous.control_point(i, j).map(|p| {
            let w = p[p.len() - 1];
            p[..p.len() - 1].iter().map(|x| x / w).collect()
        })
    }

    /// Point `S(u, v) = A(u, v) / w(u, v)` (P&T Algorithm A4.3).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn eval(&self, u: f64, v: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(u, v, &mut out)?;
        Ok(out)
    }

    /// Point `S(u, v)` into `out` (length `dim`), P&T Algorithm A4.3.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) -> Result<()> {
        check_out(out.len(), self.dim())?;
        let h = self.homogeneous.eval(u, v)?;
        project(&h, out);
        Ok(())
    }

    /// Evaluates on the grid `us × vs` into `out`, point `(i, j)` at index `i·vs.len() + j`, as
    /// [`BSplineSurface::eval_grid`] followed by the projection.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`]; [`Error::ParameterOutOfDomain`].
    pub fn eval_grid(&self, us: &[f64], vs: &[f64], out: &mut [f64]) -> Result<()> {
        let dim = self.dim();
        check_buffer(
            out.len(),
            us.len().saturating_mul(vs.len()).saturating_mul(dim),
        )?;
        let mut chunks = out.chunks_exact_mut(dim);
        self.homogeneous.grid_with(us, vs, |h| {
            if let Some(o) = chunks.next() {
                project(h, o);
            }
        })
    }

    /// Evaluates at a list of parameter pairs into `out` (`uv.len() · dim`), as
    /// [`BSplineSurface::eval_batch`] followed by the projection.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`]; [`Error::ParameterOutOfDomain`].
    pub fn eval_batch(&self, uv: &[[f64; 2]], out: &mut [f64]) -> Result<()> {
        self.eval_batch_with_progress(uv, out, &Progress::new())
    }

    /// [`NurbsSurface::eval_batch`] reporting to `progress` and stopping when it is cancelled
    /// ([`BSplineSurface::eval_batch_with_progress`] of the homogeneous surface, then the
    /// projection); the points are bit-for-bit those of [`NurbsSurface::eval_batch`].
    ///
    /// # Errors
    /// As [`NurbsSurface::eval_batch`]; [`Error::Cancelled`] when `progress` is cancelled.
    pub fn eval_batch_with_progress(
        &self,
        uv: &[[f64; 2]],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        let dim = self.dim();
        check_buffer(out.len(), uv.len().saturating_mul(dim))?;
        let mut chunks = out.chunks_exact_mut(dim);
        self.homogeneous.batch_with(uv, progress, |h| {
            if let Some(o) = chunks.next() {
                project(h, o);
            }
        })
    }

    /// Partial derivatives `S_{u^k v^l}` for `0 ≤ k, l ≤ order`, as `(order + 1)²` points (point
    /// `k·(order + 1) + l`), from the homogeneous derivatives `A_{k,l}`, `w_{k,l}` of
    /// [`BSplineSurface::eval_derivatives`] by P&T eq. (4.20), Algorithm A4.4:
    /// `S_{k,l} = (A_{k,l} − Σ_{j=1}^{l} C(l,j) w_{0,j} S_{k,l−j} − Σ_{i=1}^{k} C(k,i) w_{i,0}
    /// S_{k−i,l} − Σ_{i=1}^{k} C(k,i) Σ_{j=1}^{l} C(l,j) w_{i,j} S_{k−i,l−j}) / w`.
    /// O(order⁴·dim) on top of the polynomial derivatives.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::TooLarge`] if `order > MAX_SURFACE_DERIVATIVE_ORDER`; [`Error::NonFinite`] if a derivative overflows.
    pub fn eval_derivatives(&self, u: f64, v: f64, order: usize) -> Result<Points> {
        let hom = self.homogeneous.eval_derivatives(u, v, order)?;
        let dim = self.dim();
        let hd = dim + 1;
        let side = order + 1;
        let h = hom.as_slice();
        let w = |i: usize, j: usize| h[(i * side + j) * hd + dim];
        // Pascal's triangle C(n, k) for n < side
        let mut binom = vec![0.0; side * side];
        for n in 0..side {
            binom[n * side] = 1.0;
            for k in 1..=n {
                binom[n * side + k] = binom[(n - 1) * side + k - 1]
                    + if k < n {
                        binom[(n - 1) * side + k]
                    } else {
                        0.0
                    };
            }
        }
        let w0 = w(0, 0);
        let mut out = vec![0.0; side * side * dim];
        let mut acc = vec![0.0; dim];
        for k in 0..side {
            for l in 0..side {
                let at = (k * side + l) * hd;
                acc.copy_from_slice(&h[at..at + dim]);
                for i in 0..=k {
                    for j in 0..=l {
                        if i == 0 && j == 0 {
                            continue;
                        }
                        let c = binom[k * side + i] * binom[l * side + j] * w(i, j);
                        let prev = ((k - i) * side + (l - j)) * dim;
                        for (a, s) in acc.iter_mut().zip(&out[prev..prev + dim]) {
                            *a -= c * s;
                        }
                    }
                }
                let o = (k * side + l) * dim;
                for (x, a) in out[o..o + dim].iter_mut().zip(&acc) {
                    *x = a / w0;
                }
            }
        }
        Points::from_flat(dim, out)
    }

    /// Unit normal `(S_u × S_v) / |S_u × S_v|` of a surface in 3-D, from the rational first
    /// derivatives (P&T A4.4).
    ///
    /// # Errors
    /// As [`BSplineSurface::normal`].
    pub fn normal(&self, u: f64, v: f64) -> Result<[f64; 3]> {
        check_normal_dim(self.dim())?;
        let d = self.eval_derivatives(u, v, 1)?;
        unit_normal(d.point(2), d.point(1), u, v)
    }

    /// The iso-parametric NURBS curve `C(u) = S(u, v)` at fixed `v` (the homogeneous iso-curve
    /// of [`BSplineSurface::iso_curve_u`], projected).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn iso_curve_u(&self, v: f64) -> Result<NurbsCurve> {
        NurbsCurve::from_homogeneous(self.homogeneous.iso_curve_u(v)?)
    }

    /// The iso-parametric NURBS curve `C(v) = S(u, v)` at fixed `u`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn iso_curve_v(&self, u: f64) -> Result<NurbsCurve> {
        NurbsCurve::from_homogeneous(self.homogeneous.iso_curve_v(u)?)
    }
}

/// `out = h[..dim] / h[dim]`.
fn project(h: &[f64], out: &mut [f64]) {
    let w = h[h.len() - 1];
    debug_assert!(w > 0.0, "positive weights give w(u, v) > 0");
    for (o, x) in out.iter_mut().zip(h) {
        *o = x / w;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Arg;
    use std::f64::consts::PI;

    /// The cylinder piece `x² + y² = r²` (axis through `centre` along z), `z ∈ [z0, z0 + h]`:
    /// the extrusion of an exact arc, degree (2, 1), weights of the arc repeated along v.
    fn cylinder(centre: [f64; 3], r: f64, sweep: f64, h: f64) -> NurbsSurface {
        let arc = NurbsCurve::circular_arc(
            &centre,
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            r,
            0.3,
            0.3 + sweep,
        )
        .unwrap();
        let ctrl = arc.control_points();
        let w = arc.weights();
        let mut net = Vec::new();
        let mut weights = Vec::new();
        for (p, &wi) in ctrl.iter().zip(&w) {
            for dz in [0.0, h] {
                net.extend_from_slice(&[p[0], p[1], p[2] + dz]);
                weights.push(wi);
            }
        }
        NurbsSurface::new(
            2,
            1,
            arc.knots().as_slice().to_vec(),
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_flat(3, net).unwrap(),
            weights,
            (ctrl.len(), 2),
        )
        .unwrap()
    }

    /// A rational bicubic-by-quadratic surface with varied weights.
    fn general() -> NurbsSurface {
        let data: Vec<f64> = (0..60_u32)
            .map(|k| (0.61 * f64::from(k)).cos() * 2.0)
            .collect();
        let weights: Vec<f64> = (0..20_u32)
            .map(|k| 0.5 + (f64::from(k) * 0.9).sin().abs())
            .collect();
        NurbsSurface::new(
            3,
            2,
            vec![0.0, 0.0, 0.0, 0.0, 0.6, 1.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
            Points::from_flat(3, data).unwrap(),
            weights,
            (5, 4),
        )
        .unwrap()
    }

    #[test]
    fn cylinder_points_lie_at_radius_and_normals_are_radial() {
        for &(centre, r) in &[
            ([0.0, 0.0, 0.0], 1.0),
            ([0.25, -0.5, 3.0], 2.5),
            ([1e3, -1e3, 5.0], 1e3),
            ([1e3, 2e3, 0.0], 1.0),
        ] {
            for sweep in [0.5 * PI, 1.3 * PI, 2.0 * PI] {
                let s = cylinder(centre, r, sweep, 4.0);
                let offset = (centre[0] * centre[0] + centre[1] * centre[1]).sqrt();
                // 1e-14·r, plus the unavoidable rounding ε·|centre| of the coordinates
                let tol = 1e-14 * r + 4.0 * f64::EPSILON * offset;
                let steps = 60;
                for a in 0..=steps {
                    for b in 0..=4 {
                        let (u, v) = (f64::from(a) / f64::from(steps), f64::from(b) / 4.0);
                        let p = s.eval(u, v).unwrap();
                        let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
                        let err = (dx.hypot(dy) - r).abs();
                        assert!(err <= tol, "({u},{v}), r={r}: {err:e} > {tol:e}");
                        assert!(
                            (p[2] - centre[2] - 4.0 * v).abs() <= 1e-14 * (1.0 + centre[2]),
                            "height"
                        );
                        let n = s.normal(u, v).unwrap();
                        // S_u is tangent to the circle (counter-clockwise), S_v = +z: the normal
                        // S_u × S_v points outwards
                        let (ex, ey) = (dx / r, dy / r);
                        let ntol = 1e-13 + 8.0 * f64::EPSILON * offset / r;
                        assert!(
                            (n[0] - ex).abs() <= ntol
                                && (n[1] - ey).abs() <= ntol
                                && n[2].abs() <= ntol,
                            "normal {n:?} vs ({ex}, {ey}, 0)"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn rational_partials_match_finite_differences() {
        let s = general();
        let h = 1e-5;
        for &(u, v) in &[(0.2, 0.3), (0.7, 0.8), (0.55, 0.05)] {
            let order = 2;
            let side = order + 2;
            let d = s.eval_derivatives(u, v, order + 1).unwrap();
            assert_eq!(d.point(0), s.eval(u, v).unwrap().as_slice(), "S_00");
            let lo_u = s.eval_derivatives(u - h, v, order).unwrap();
            let hi_u = s.eval_derivatives(u + h, v, order).unwrap();
            let lo_v = s.eval_derivatives(u, v - h, order).unwrap();
            let hi_v = s.eval_derivatives(u, v + h, order).unwrap();
            for k in 0..=order {
                for l in 0..=order {
                    let idx = k * (order + 1) + l;
                    for c in 0..3 {
                        let fd_u = (hi_u.point(idx)[c] - lo_u.point(idx)[c]) / (2.0 * h);
                        let fd_v = (hi_v.point(idx)[c] - lo_v.point(idx)[c]) / (2.0 * h);
                        let ex_u = d.point((k + 1) * side + l)[c];
                        let ex_v = d.point(k * side + l + 1)[c];
                        let tol =
                            1e-5 * (1.0 + ex_u.abs().max(ex_v.abs())) * 10f64.powf((k + l) as f64);
                        assert!(
                            (fd_u - ex_u).abs() < tol,
                            "({u},{v}) u k={k} l={l}: {fd_u} vs {ex_u}"
                        );
                        assert!(
                            (fd_v - ex_v).abs() < tol,
                            "({u},{v}) v k={k} l={l}: {fd_v} vs {ex_v}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn unit_weights_reproduce_the_bspline() {
        let g = general();
        let b = BSplineSurface::new(
            3,
            2,
            g.knots_u().as_slice().to_vec(),
            g.knots_v().as_slice().to_vec(),
            g.control_points(),
            (5, 4),
        )
        .unwrap();
        let n = NurbsSurface::from_bspline(&b);
        assert_eq!(n.weights(), vec![1.0; 20]);
        for &(u, v) in &[(0.0, 0.0), (0.3, 0.9), (1.0, 0.5), (0.6, 0.5)] {
            let (db, dn) = (
                b.eval_derivatives(u, v, 3).unwrap(),
                n.eval_derivatives(u, v, 3).unwrap(),
            );
            let scale = db.max_abs();
            for (x, y) in db.as_slice().iter().zip(dn.as_slice()) {
                assert!((x - y).abs() < 1e-12 * scale, "({u},{v}): {x} vs {y}");
            }
        }
    }

    #[test]
    fn grid_batch_iso_and_single_agree() {
        let s = general();
        let us = [0.0, 0.25, 0.6, 1.0];
        let vs = [1.0, 0.5, 0.1];
        let mut grid = vec![0.0; 12 * 3];
        s.eval_grid(&us, &vs, &mut grid).unwrap();
        let pairs: Vec<[f64; 2]> = us
            .iter()
            .flat_map(|&u| vs.iter().map(move |&v| [u, v]))
            .collect();
        let mut list = vec![0.0; 12 * 3];
        s.eval_batch(&pairs, &mut list).unwrap();
        for (k, &[u, v]) in pairs.iter().enumerate() {
            let p = s.eval(u, v).unwrap();
            let cu = s.iso_curve_u(v).unwrap().eval(u).unwrap();
            let cv = s.iso_curve_v(u).unwrap().eval(v).unwrap();
            for c in 0..3 {
                let tol = 1e-14 * (1.0 + p[c].abs());
                assert!((grid[3 * k + c] - p[c]).abs() <= tol, "grid ({u},{v})");
                assert!((list[3 * k + c] - p[c]).abs() <= tol, "list ({u},{v})");
                assert!((cu[c] - p[c]).abs() <= tol, "iso u ({u},{v})");
                assert!((cv[c] - p[c]).abs() <= tol, "iso v ({u},{v})");
            }
        }
        assert!(matches!(
            s.eval_grid(&us, &vs, &mut grid[2..]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            s.eval_batch(&pairs, &mut list[2..]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            s.eval_into(0.5, 0.5, &mut [0.0; 4]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            s.eval(0.5, 1.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            s.iso_curve_u(-1.0),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            s.iso_curve_v(2.0),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    #[test]
    fn accessors_and_weights() {
        let s = general();
        assert_eq!(
            (s.degree_u(), s.degree_v(), s.dim(), s.net_size()),
            (3, 2, 3, (5, 4))
        );
        assert_eq!(s.domain(), ((0.0, 1.0), (0.0, 1.0)));
        assert_eq!(s.weight(1, 2), Some(s.weights()[6]));
        assert_eq!(s.weight(5, 0), None);
        let p = s.control_point(2, 3).unwrap();
        let q = s.control_points().point(11).to_vec();
        assert_eq!(p, q);
        assert_eq!(s.control_point(0, 4), None);
        assert_eq!(s.homogeneous().dim(), 4);
        assert_eq!(
            NurbsSurface::from_homogeneous(s.homogeneous().clone()).unwrap(),
            s
        );
    }

    #[test]
    fn constructor_errors() {
        let net = Points::from_flat(2, vec![0.0; 8]).unwrap();
        let k = vec![0.0, 0.0, 1.0, 1.0];
        let make =
            |w: Vec<f64>| NurbsSurface::new(1, 1, k.clone(), k.clone(), net.clone(), w, (2, 2));
        assert!(make(vec![1.0; 4]).is_ok());
        assert!(matches!(
            make(vec![1.0; 3]),
            Err(Error::LengthMismatch {
                expected: 4,
                got: 3,
                ..
            })
        ));
        assert!(matches!(
            make(vec![1.0, 1.0, 0.0, 1.0]),
            Err(Error::NonPositiveWeight { index: 2, .. })
        ));
        assert!(matches!(
            make(vec![1.0, f64::NAN, 1.0, 1.0]),
            Err(Error::NonFinite { what, .. }) if what.arg() == Some(Arg::Weights)
        ));
        assert!(matches!(
            NurbsSurface::new(
                1,
                1,
                k.clone(),
                k.clone(),
                net.clone(),
                vec![1.0; 4],
                (2, 3)
            ),
            Err(Error::LengthMismatch { .. })
        ));
        let big = Points::from_flat(2, vec![1e300; 8]).unwrap();
        assert!(matches!(
            NurbsSurface::new(1, 1, k.clone(), k.clone(), big, vec![1e10; 4], (2, 2)),
            Err(Error::NonFinite { .. })
        ));
        // from_homogeneous: weights must be positive, dimension at least 2
        let h = BSplineSurface::new(
            1,
            1,
            k.clone(),
            k.clone(),
            Points::from_flat(2, vec![1.0, -1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]).unwrap(),
            (2, 2),
        )
        .unwrap();
        assert!(matches!(
            NurbsSurface::from_homogeneous(h),
            Err(Error::NonPositiveWeight { index: 0, .. })
        ));
        let h1 = BSplineSurface::new(
            1,
            1,
            k.clone(),
            k,
            Points::from_flat(1, vec![1.0; 4]).unwrap(),
            (2, 2),
        )
        .unwrap();
        assert!(matches!(
            NurbsSurface::from_homogeneous(h1),
            Err(Error::Dimension { .. })
        ));
    }

    #[test]
    fn normal_errors() {
        let net = Points::from_flat(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0]).unwrap();
        let k = vec![0.0, 0.0, 1.0, 1.0];
        let s = NurbsSurface::new(
            1,
            1,
            k.clone(),
            k.clone(),
            net,
            vec![1.0, 2.0, 1.0, 1.0],
            (2, 2),
        )
        .unwrap();
        assert!(matches!(
            s.normal(0.5, 0.5),
            Err(Error::Dimension {
                expected: 3,
                got: 2,
                ..
            })
        ));
        // collapsed edge u = 0 (a rational triangle): S_v = 0 there
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
        ])
        .unwrap();
        let t =
            NurbsSurface::new(1, 1, k.clone(), k, net, vec![1.0, 2.0, 1.0, 3.0], (2, 2)).unwrap();
        let n = t.normal(0.5, 0.5).unwrap();
        assert!((n[2] - 1.0).abs() < 1e-15, "planar triangle normal {n:?}");
        assert!(matches!(
            t.normal(0.0, 0.5),
            Err(Error::InvalidArgument { .. })
        ));
    }

    #[test]
    fn serde_goes_through_validation() {
        let s = cylinder([0.0, 0.0, 0.0], 2.0, PI, 1.0);
        let json = serde_json::to_string(&s).unwrap();
        let back: NurbsSurface = serde_json::from_str(&json).unwrap();
        for &(u, v) in &[(0.1, 0.2), (0.9, 0.7)] {
            let (a, b) = (s.eval(u, v).unwrap(), back.eval(u, v).unwrap());
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 1e-15, "round trip");
            }
        }
        let bad = json.replace("\"weights\":[1.0", "\"weights\":[-1.0");
        assert_ne!(bad, json, "the replacement must hit");
        let e = serde_json::from_str::<NurbsSurface>(&bad).unwrap_err();
        assert!(e.to_string().contains("weight"), "{e}");
    }
}
