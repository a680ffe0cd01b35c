//! Partial derivatives and unit normals of a B-spline surface: `S_{u^k v^l}` by P&T Algorithm
//! A3.6 over the full square `0 ≤ k, l ≤ d` (basis derivatives by A2.3), and the normal
//! `(S_u × S_v) / |S_u × S_v|` (P&T §3.4), refused where it is not defined; the normal
//! helpers are shared with the Bezier and NURBS surfaces.

use super::BSplineSurface;
use crate::basis::{basis_ders_into, BasisScratch};
use crate::error::{
    check_derivative_order, readable, Error, Result, MAX_SCALARS, MAX_SURFACE_DERIVATIVE_ORDER,
};
use crate::points::Points;

/// A unit normal is refused where `|S_u × S_v| ≤ NORMAL_DEGENERACY_TOL · |S_u| · |S_v|`, i.e.
/// where the sine of the angle between the partial derivatives is below `1e-12` (or one of them
/// vanishes): at poles, collapsed edges and cusps the normal is not defined by the derivatives.
pub(crate) const NORMAL_DEGENERACY_TOL: f64 = 1e-12;

impl BSplineSurface {
    /// Partial derivatives `S_{u^k v^l}(u, v)` for `0 ≤ k, l ≤ order`, as `(order + 1)²` points:
    /// point `k·(order + 1) + l` is `∂^{k+l} S / ∂u^k ∂v^l` (P&T Algorithm A3.6, over the full
    /// square instead of the triangle `k + l ≤ d`). Basis derivatives by P&T A2.3; derivatives
    /// of order above the degree in a direction are zero. O((order + 1)·(p² + q²) +
    /// (order + 1)²·p·q·dim).
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points};
    /// // S(u, v) = (u, v, u·v): S_uv = (0, 0, 1)
    /// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let s = BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0], net, (2, 2))?;
    /// let d = s.eval_derivatives(0.3, 0.6, 1)?;
    /// assert_eq!(d.point(1), &[0.0, 1.0, 0.3]);  // S_v
    /// assert_eq!(d.point(2), &[1.0, 0.0, 0.6]);  // S_u
    /// assert_eq!(d.point(3), &[0.0, 0.0, 1.0]);  // S_uv
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::TooLarge`] if `order > MAX_SURFACE_DERIVATIVE_ORDER`.
    pub fn eval_derivatives(&self, u: f64, v: f64, order: usize) -> Result<Points> {
        let (p, q) = (self.degree_u, self.degree_v);
        let dim = self.dim();
        let su = self.knots_u.find_span(p, u)?;
        let sv = self.knots_v.find_span(q, v)?;
        check_derivative_order(order, MAX_SURFACE_DERIVATIVE_ORDER)?;
        let side = order
            .checked_add(1)
            .filter(|&s| s.saturating_mul(s).saturating_mul(dim) <= MAX_SCALARS);
        let side = side.ok_or(Error::TooLarge {
            what: "derivative table ((order + 1)² points)".into(),
            size: order,
            max: 1 << 15,
        })?;
        let (wu, wv) = (p + 1, q + 1);
        let (du, dv) = (order.min(p), order.min(q));
        let mut nu = vec![0.0; (du + 1) * wu];
        let mut nv = vec![0.0; (dv + 1) * wv];
        basis_ders_into(
            self.knots_u.as_slice(),
            p,
            su,
            u,
            du,
            &mut BasisScratch::new(p),
            &mut nu,
        );
        basis_ders_into(
            self.knots_v.as_slice(),
            q,
            sv,
            v,
            dv,
            &mut BasisScratch::new(q),
            &mut nv,
        );
        let mut out = vec![0.0; side * side * dim];
        let mut tmp = vec![0.0; dim];
        for k in 0..=du {
            for l in 0..=dv {
                let o = &mut out[(k * side + l) * dim..(k * side + l + 1) * dim];
                self.combine(
                    su,
                    sv,
                    &nu[k * wu..(k + 1) * wu],
                    &nv[l * wv..(l + 1) * wv],
                    &mut tmp,
                    o,
                );
            }
        }
        Points::from_flat(dim, out)
    }

    /// Unit normal `(S_u × S_v) / |S_u × S_v|` of a surface in 3-D.
    ///
    /// ```
    /// use lekalo::{BSplineSurface, Points};
    /// let net = Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let s = BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0], net, (2, 2))?;
    /// assert_eq!(s.normal(0.0, 0.0)?, [0.0, 0.0, 1.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless `dim == 3`; [`Error::ParameterOutOfDomain`];
    /// [`Error::InvalidArgument`] where the normal is undefined:
    /// `|S_u × S_v| ≤ 1e-12 · |S_u| · |S_v|` (a pole, a collapsed edge, parallel or vanishing
    /// partial derivatives).
    pub fn normal(&self, u: f64, v: f64) -> Result<[f64; 3]> {
        check_normal_dim(self.dim())?;
        let d = self.eval_derivatives(u, v, 1)?;
        unit_normal(d.point(2), d.point(1), u, v)
    }
}

pub(crate) fn check_normal_dim(dim: usize) -> Result<()> {
    if dim != 3 {
        return Err(Error::Dimension {
            what: "surface points (a normal S_u × S_v needs 3-D points)".into(),
            expected: 3,
            got: dim,
        });
    }
    Ok(())
}

/// `(su × sv) / |su × sv|`, refused where `|su × sv| ≤ NORMAL_DEGENERACY_TOL · |su| · |sv|`.
pub(crate) fn unit_normal(su: &[f64], sv: &[f64], u: f64, v: f64) -> Result<[f64; 3]> {
    debug_assert!(su.len() == 3 && sv.len() == 3, "normals are 3-D");
    let n = [
        su[1] * sv[2] - su[2] * sv[1],
        su[2] * sv[0] - su[0] * sv[2],
        su[0] * sv[1] - su[1] * sv[0],
    ];
    let len = |a: &[f64]| a.iter().map(|x| x * x).sum::<f64>().sqrt();
    let (ln, lu, lv) = (len(&n), len(su), len(sv));
    if !ln.is_finite() || ln <= NORMAL_DEGENERACY_TOL * lu * lv {
        return Err(Error::InvalidArgument {
            what: "surface point for a normal".into(),
            reason: format!(
                "the normal is undefined at (u, v) = ({u}, {v}): |S_u × S_v| = {ln:e} is at most \
                 {NORMAL_DEGENERACY_TOL:e} · |S_u| · |S_v| (|S_u| = {lu:e}, |S_v| = {lv:e}); \
                 this is a degenerate point (pole, collapsed edge or cusp) — evaluate nearby",
                u = readable(&u),
                v = readable(&v)
            ),
        });
    }
    Ok([n[0] / ln, n[1] / ln, n[2] / ln])
}

#[cfg(test)]
mod tests {
    use super::super::tests::bilinear;
    use super::*;

    #[test]
    fn normals_need_3d_and_a_regular_point() {
        // a 2-D surface has no normal
        let net = Points::from_2d(&[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]]).unwrap();
        let k = vec![0.0, 0.0, 1.0, 1.0];
        let s2 = BSplineSurface::new(1, 1, k.clone(), k.clone(), net, (2, 2)).unwrap();
        assert!(matches!(
            s2.normal(0.5, 0.5),
            Err(Error::Dimension {
                expected: 3,
                got: 2,
                ..
            })
        ));
        // a triangle: the edge u = 1 collapsed to a point, S_v = 0 there
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.5, 0.0],
            [1.0, 0.5, 0.0],
        ])
        .unwrap();
        let tri = BSplineSurface::new(1, 1, k.clone(), k, net, (2, 2)).unwrap();
        assert!(tri.normal(0.5, 0.5).is_ok());
        let e = tri.normal(1.0, 0.5).unwrap_err();
        assert!(
            matches!(&e, Error::InvalidArgument { reason, .. } if reason.contains("undefined")),
            "{e}"
        );
        assert!(matches!(
            tri.normal(1.5, 0.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    #[test]
    fn absurd_derivative_orders_are_refused() {
        let s = bilinear();
        assert_eq!(s.eval_derivatives(0.5, 0.5, 64).unwrap().len(), 65 * 65);
        assert!(matches!(
            s.eval_derivatives(0.5, 0.5, 65),
            Err(Error::TooLarge {
                size: 65,
                max: 64,
                ..
            })
        ));
        assert!(matches!(
            s.eval_derivatives(0.5, 0.5, usize::MAX),
            Err(Error::TooLarge { .. })
        ));
    }
}
