//! Tensor-product Bezier surfaces `p(u, v) = Σ_i Σ_j b_{n,i}(u) b_{m,j}(v) P_{i,j}` on
//! `[0, 1]²` (document 004 eq. 11 and 13, `p(t, τ) = B_nᵀ(t) U_{n,m} B_m(τ)`; P&T §1.5).
//! Net layout and derivative tables as in [`crate::surface::bspline`].

use serde::{Deserialize, Serialize};

use crate::basis::bernstein_derivatives;
use crate::curve::bezier::BezierCurve;
use crate::error::{check_derivative_order, Error, Result, MAX_SURFACE_DERIVATIVE_ORDER};
use crate::knots::KnotVector;
use crate::points::Points;
use crate::surface::bspline::{
    check_net, check_normal_dim, check_out, check_unit, unit_normal, BSplineSurface,
};

/// A Bezier surface of degrees `(n, m) = (nu − 1, nv − 1)` with an `nu × nv` control net.
///
/// ```
/// use lekalo::{BezierSurface, Points};
/// // the bilinear patch S(u, v) = (u, v, u·v)
/// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
/// let s = BezierSurface::new(net, (2, 2))?;
/// assert_eq!(s.eval(0.5, 0.25)?, vec![0.5, 0.25, 0.125]);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BezierSurfaceRepr", into = "BezierSurfaceRepr")]
pub struct BezierSurface {
    control: Points,
    net_size: (usize, usize),
}

#[derive(Serialize, Deserialize)]
struct BezierSurfaceRepr {
    net_size: (usize, usize),
    control: Points,
}

impl TryFrom<BezierSurfaceRepr> for BezierSurface {
    type Error = Error;
    fn try_from(r: BezierSurfaceRepr) -> Result<Self> {
        BezierSurface::new(r.control, r.net_size)
    }
}

impl From<BezierSurface> for BezierSurfaceRepr {
    fn from(s: BezierSurface) -> Self {
        BezierSurfaceRepr {
            net_size: s.net_size,
            control: s.control,
        }
    }
}

impl BezierSurface {
    /// A Bezier surface from its control net (`net_size = (nu, nv)`, point `(i, j)` at index
    /// `i·nv + j`); degrees `nu − 1` and `nv − 1`.
    ///
    /// # Errors
    /// [`Error::TooFew`] for an empty direction; [`Error::LengthMismatch`] if
    /// `control.len() != nu·nv`; [`Error::TooLarge`].
    pub fn new(control: Points, net_size: (usize, usize)) -> Result<Self> {
        check_net(&control, net_size)?;
        Ok(BezierSurface { control, net_size })
    }

    /// Trusted constructor for nets built inside the crate (debug-checked).
    pub(crate) fn from_raw(control: Points, net_size: (usize, usize)) -> Self {
        debug_assert!(check_net(&control, net_size).is_ok(), "raw Bezier net");
        BezierSurface { control, net_size }
    }

    /// Degrees `(n, m) = (nu − 1, nv − 1)` in `u` and `v` (the pair of
    /// [`BezierCurve::degree`](crate::BezierCurve::degree)).
    #[must_use]
    pub fn degree(&self) -> (usize, usize) {
        (self.degree_u(), self.degree_v())
    }

    /// Degree `n = nu − 1` in `u`.
    #[must_use]
    pub fn degree_u(&self) -> usize {
        self.net_size.0 - 1
    }

    /// Degree `m = nv − 1` in `v`.
    #[must_use]
    pub fn degree_v(&self) -> usize {
        self.net_size.1 - 1
    }

    /// Net size `(nu, nv)`.
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        self.net_size
    }

    /// Dimension of the points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.control.dim()
    }

    /// The parameter domain, always `((0, 1), (0, 1))`.
    #[must_use]
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        ((0.0, 1.0), (0.0, 1.0))
    }

    /// The control net, flat point-major.
    #[must_use]
    pub fn control_points(&self) -> &Points {
        &self.control
    }

    /// Control point `P_{i,j}`, or `None` outside the net.
    #[must_use]
    pub fn control_point(&self, i: usize, j: usize) -> Option<&[f64]> {
        let (nu, nv) = self.net_size;
        (i < nu && j < nv).then(|| self.control.point(i * nv + j))
    }

    /// Point `p(u, v)`.
    ///
    /// # Errors
    /// As [`BezierSurface::eval_into`].
    pub fn eval(&self, u: f64, v: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(u, v, &mut out)?;
        Ok(out)
    }

    /// Point `p(u, v)` into `out` by de Casteljau's algorithm in both directions (P&T
    /// Algorithm A1.7): each row `i` is reduced in `v` to a point `Q_i`, then the curve `Q` is
    /// reduced in `u`. Stable, O(nu·nv²·dim + nu²·dim); one scratch of `(nu + nv)·dim` values.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `u, v ∈ [0, 1]`; [`Error::LengthMismatch`] if
    /// `out.len() != dim`.
    pub fn eval_into(&self, u: f64, v: f64, out: &mut [f64]) -> Result<()> {
        check_unit(u)?;
        check_unit(v)?;
        let dim = self.dim();
        check_out(out.len(), dim)?;
        let (nu, nv) = self.net_size;
        let mut rows = vec![0.0; nu * dim];
        let mut work = vec![0.0; nv * dim];
        let ctrl = self.control.as_slice();
        for (i, q) in rows.chunks_exact_mut(dim).enumerate() {
            work.copy_from_slice(&ctrl[i * nv * dim..(i + 1) * nv * dim]);
            de_casteljau(&mut work, dim, v);
            q.copy_from_slice(&work[..dim]);
        }
        de_casteljau(&mut rows, dim, u);
        out.copy_from_slice(&rows[..dim]);
        Ok(())
    }

    /// Partial derivatives `p_{u^k v^l}` for `0 ≤ k, l ≤ order`, as `(order + 1)²` points (point
    /// `k·(order + 1) + l`): `Σ_i Σ_j b_{n,i}^{(k)}(u) b_{m,j}^{(l)}(v) P_{i,j}` with the
    /// Bernstein derivatives of [`crate::basis::bernstein_derivatives`]. Orders above the degree
    /// in a direction are zero. O(order²·nu·nv·dim).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `u, v ∈ [0, 1]`; [`Error::TooLarge`] if `order > MAX_SURFACE_DERIVATIVE_ORDER`.
    pub fn eval_derivatives(&self, u: f64, v: f64, order: usize) -> Result<Points> {
        check_unit(u)?;
        check_unit(v)?;
        check_derivative_order(order, MAX_SURFACE_DERIVATIVE_ORDER)?;
        let (nu, nv) = self.net_size;
        let dim = self.dim();
        let side = order + 1;
        let bu = bernstein_derivatives(nu - 1, u, order.min(nu - 1))?;
        let bv = bernstein_derivatives(nv - 1, v, order.min(nv - 1))?;
        let ctrl = self.control.as_slice();
        let mut out = vec![0.0; side * side * dim];
        let mut tmp = vec![0.0; dim];
        for k in 0..=order.min(nu - 1) {
            for l in 0..=order.min(nv - 1) {
                let o = &mut out[(k * side + l) * dim..(k * side + l + 1) * dim];
                for i in 0..nu {
                    tmp.fill(0.0);
                    for j in 0..nv {
                        let b = bv[l * nv + j];
                        for (t, c) in tmp.iter_mut().zip(&ctrl[(i * nv + j) * dim..]) {
                            *t += b * c;
                        }
                    }
                    let a = bu[k * nu + i];
                    for (x, t) in o.iter_mut().zip(&tmp) {
                        *x += a * t;
                    }
                }
            }
        }
        Points::from_flat(dim, out)
    }

    /// Unit normal `(p_u × p_v) / |p_u × p_v|` of a surface in 3-D.
    ///
    /// # Errors
    /// As [`BSplineSurface::normal`] (with the domain `[0, 1]²`).
    pub fn normal(&self, u: f64, v: f64) -> Result<[f64; 3]> {
        check_normal_dim(self.dim())?;
        let d = self.eval_derivatives(u, v, 1)?;
        unit_normal(d.point(2), d.point(1), u, v)
    }

    /// The iso-parametric Bezier curve `C(u) = p(u, v)` at fixed `v`: control points
    /// `Q_i = Σ_j b_{m,j}(v) P_{i,j}`, evaluated by de Casteljau on each row.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `v ∈ [0, 1]`.
    pub fn iso_curve_u(&self, v: f64) -> Result<BezierCurve> {
        check_unit(v)?;
        let (nu, nv) = self.net_size;
        let dim = self.dim();
        let ctrl = self.control.as_slice();
        let mut out = vec![0.0; nu * dim];
        let mut work = vec![0.0; nv * dim];
        for (i, q) in out.chunks_exact_mut(dim).enumerate() {
            work.copy_from_slice(&ctrl[i * nv * dim..(i + 1) * nv * dim]);
            de_casteljau(&mut work, dim, v);
            q.copy_from_slice(&work[..dim]);
        }
        BezierCurve::new(Points::from_flat(dim, out)?)
    }

    /// The iso-parametric Bezier curve `C(v) = p(u, v)` at fixed `u`: control points
    /// `Q_j = Σ_i b_{n,i}(u) P_{i,j}`, evaluated by de Casteljau on each column.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `u ∈ [0, 1]`.
    pub fn iso_curve_v(&self, u: f64) -> Result<BezierCurve> {
        check_unit(u)?;
        let (nu, nv) = self.net_size;
        let dim = self.dim();
        let ctrl = self.control.as_slice();
        let mut out = vec![0.0; nv * dim];
        let mut work = vec![0.0; nu * dim];
        for (j, q) in out.chunks_exact_mut(dim).enumerate() {
            for (i, w) in work.chunks_exact_mut(dim).enumerate() {
                w.copy_from_slice(&ctrl[(i * nv + j) * dim..(i * nv + j + 1) * dim]);
            }
            de_casteljau(&mut work, dim, u);
            q.copy_from_slice(&work[..dim]);
        }
        BezierCurve::new(Points::from_flat(dim, out)?)
    }

    /// The same surface as a B-spline surface of degrees `(nu − 1, nv − 1)` on the clamped knot
    /// vectors `[0, …, 0, 1, …, 1]` (`degree + 1` copies each), whose basis functions are the
    /// Bernstein polynomials (P&T §2.2).
    ///
    /// ```
    /// use lekalo::{BezierSurface, Points};
    /// let net = Points::from_flat(1, (0..3 * 4).map(|k| (k as f64).sin()).collect())?;
    /// let bez = BezierSurface::new(net, (3, 4))?;
    /// let bs = bez.to_bspline();
    /// assert_eq!((bs.degree_u(), bs.degree_v()), (2, 3));
    /// assert!((bs.eval(0.3, 0.8)?[0] - bez.eval(0.3, 0.8)?[0]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn to_bspline(&self) -> BSplineSurface {
        let (nu, nv) = self.net_size;
        let bezier_knots = |n: usize| {
            let mut k = vec![0.0; n];
            k.extend(std::iter::repeat_n(1.0, n));
            KnotVector::from_raw(k)
        };
        BSplineSurface::from_raw(
            nu - 1,
            nv - 1,
            bezier_knots(nu),
            bezier_knots(nv),
            self.control.clone(),
        )
    }
}

impl From<&BezierSurface> for BSplineSurface {
    fn from(s: &BezierSurface) -> Self {
        s.to_bspline()
    }
}

/// De Casteljau's algorithm in place on `n` points of dimension `dim`; the result is left in the
/// first point (P&T A1.5).
fn de_casteljau(points: &mut [f64], dim: usize, t: f64) {
    let n = points.len() / dim;
    let s = 1.0 - t;
    for k in 1..n {
        for i in 0..n - k {
            for d in 0..dim {
                points[i * dim + d] = s * points[i * dim + d] + t * points[(i + 1) * dim + d];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn general() -> BezierSurface {
        let data: Vec<f64> = (0..48_u32)
            .map(|k| (0.83 * f64::from(k)).sin() + f64::from(k % 5))
            .collect();
        BezierSurface::new(Points::from_flat(4, data).unwrap(), (4, 3)).unwrap()
    }

    #[test]
    fn de_casteljau_equals_bspline_form_and_bernstein_sum() {
        let s = general();
        let b = s.to_bspline();
        assert_eq!(BSplineSurface::from(&s), b);
        assert_eq!((b.degree_u(), b.degree_v(), b.net_size()), (3, 2, (4, 3)));
        for a in 0..=8 {
            for c in 0..=8 {
                let (u, v) = (f64::from(a) / 8.0, f64::from(c) / 8.0);
                let p = s.eval(u, v).unwrap();
                let q = b.eval(u, v).unwrap();
                let d = s.eval_derivatives(u, v, 4).unwrap();
                let e = b.eval_derivatives(u, v, 4).unwrap();
                for k in 0..4 {
                    assert!((p[k] - q[k]).abs() < 1e-14, "({u},{v})");
                    // the Bernstein sum (row 0 of the derivatives) vs de Casteljau
                    assert!((d.point(0)[k] - p[k]).abs() < 1e-14, "sum vs de Casteljau");
                }
                let scale = e.max_abs();
                for (x, y) in d.as_slice().iter().zip(e.as_slice()) {
                    assert!((x - y).abs() < 1e-12 * scale, "derivatives at ({u},{v})");
                }
            }
        }
    }

    #[test]
    fn bilinear_golden_and_normal() {
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
        ])
        .unwrap();
        let s = BezierSurface::new(net, (2, 2)).unwrap();
        let (u, v) = (0.3, 0.8);
        let p = s.eval(u, v).unwrap();
        assert!(
            (p[0] - u).abs() < 1e-15 && (p[1] - v).abs() < 1e-15 && (p[2] - u * v).abs() < 1e-15,
            "{p:?}"
        );
        let n = s.normal(u, v).unwrap();
        let len = (1.0 + u * u + v * v).sqrt();
        assert!(
            (n[0] + v / len).abs() < 1e-15 && (n[1] + u / len).abs() < 1e-15,
            "{n:?}"
        );
        let flat = BezierSurface::new(Points::from_flat(2, vec![0.0; 8]).unwrap(), (2, 2)).unwrap();
        assert!(matches!(
            flat.normal(0.5, 0.5),
            Err(Error::Dimension { .. })
        ));
        let point =
            BezierSurface::new(Points::from_flat(3, vec![1.0; 12]).unwrap(), (2, 2)).unwrap();
        assert!(matches!(
            point.normal(0.5, 0.5),
            Err(Error::InvalidArgument { .. })
        ));
    }

    #[test]
    fn iso_curves_and_accessors() {
        let s = general();
        assert_eq!(
            (s.degree_u(), s.degree_v(), s.dim(), s.net_size()),
            (3, 2, 4, (4, 3))
        );
        assert_eq!(s.domain(), ((0.0, 1.0), (0.0, 1.0)));
        assert_eq!(s.control_point(1, 2), Some(s.control_points().point(5)));
        assert_eq!(s.control_point(4, 0), None);
        for &t in &[0.0, 0.4, 1.0] {
            let cu = s.iso_curve_u(t).unwrap();
            let cv = s.iso_curve_v(t).unwrap();
            assert_eq!((cu.degree(), cv.degree()), (3, 2));
            for &x in &[0.0, 0.7, 1.0] {
                let (a, b) = (cu.eval(x).unwrap(), s.eval(x, t).unwrap());
                let (c, d) = (cv.eval(x).unwrap(), s.eval(t, x).unwrap());
                for k in 0..4 {
                    assert!(
                        (a[k] - b[k]).abs() < 1e-14 && (c[k] - d[k]).abs() < 1e-14,
                        "iso at {t}, {x}"
                    );
                }
            }
        }
        assert!(matches!(
            s.iso_curve_u(1.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            s.iso_curve_v(-0.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            s.eval(f64::NAN, 0.0),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            s.eval_derivatives(0.0, 2.0, 1),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            s.eval_into(0.0, 0.0, &mut [0.0; 3]),
            Err(Error::LengthMismatch { .. })
        ));
    }

    #[test]
    fn constructor_and_serde_validate() {
        let net = Points::from_flat(1, vec![0.0; 6]).unwrap();
        assert!(matches!(
            BezierSurface::new(net.clone(), (2, 2)),
            Err(Error::LengthMismatch {
                expected: 4,
                got: 6,
                ..
            })
        ));
        assert!(matches!(
            BezierSurface::new(net.clone(), (6, 0)),
            Err(Error::TooFew { .. })
        ));
        let s = BezierSurface::new(net, (3, 2)).unwrap();
        let json = serde_json::to_string(&s).unwrap();
        assert_eq!(serde_json::from_str::<BezierSurface>(&json).unwrap(), s);
        let bad = json.replace("[3,2]", "[2,2]");
        assert_ne!(bad, json, "the replacement must hit");
        assert!(serde_json::from_str::<BezierSurface>(&bad).is_err());
    }
}
