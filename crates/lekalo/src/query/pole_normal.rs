//! The limit normal of a surface at a point of a collapsed edge (a pole), where
//! `S_u × S_v` vanishes and the normal is defined only as a limit.
//!
//! On an edge `v = v*` that collapses to a point, `S_u(u, v*) = 0` for every `u`, so
//! `S_u(u, v* + h) = h S_uv(u, v*) + O(h²)` (Taylor in `v`) and
//!
//! `S_u × S_v (u, v* + h) = h (S_uv × S_v)(u, v*) + O(h²)`:
//!
//! the unit normal tends to `sign(h) · S_uv × S_v / |S_uv × S_v|` as the point approaches the
//! pole along `u = const` from inside the domain (`h` pointing into it). Likewise on an edge
//! `u = u*` that collapses, `S_u × S_v → sign(h) · S_u × S_uv`. The derivation, and the
//! bound below which a normal counts as undefined, are in `docs/theory/queries.md`
//! ("Vertex normals"); derivatives by P&T A3.6, A4.4. At a sphere's pole the limit is the
//! axis whatever `u`; at a cone's apex it is the normal along the generator at `u`, the limit
//! along that generator.

/// The relative size of `|S_u × S_v|`, against the largest `|S_u| · |S_v|` of a mesh, below
/// which [`Mesh::surface_normals`](super::Mesh::surface_normals) takes a vertex's normal as the limit at a pole: rounding
/// leaves derivatives of about `1e-15` of their size at a pole, whose direction is then
/// noise; a normal accepted above a bound `t` is off by up to about `ε / t` radians
/// (`ε` ≈ `1e-16`, the rounding of the cross product), and the limit taken below it by up
/// to about `t` (the vertex's distance from the pole, relatively, in the first-order
/// expansion): `t = 1e-8` ≈ `√ε` balances the two, both about `1e-8` radians.
pub const MESH_NORMAL_RTOL: f64 = 1e-8;

/// The direction `S_u × S_v` tends to (a vector of that direction, not unit) at
/// `(u, v)` of `surface`, a point of a collapsed edge, approached from inside the domain
/// `((u0, u1), (v0, v1))`: `±S_uv × S_v` when `|S_u| ≤ |S_v|` (the edge `v = const`
/// collapses), `±S_u × S_uv` otherwise; the sign is that of the step into the domain (towards
/// the farther end). `None` when the surface is not 3-D, cannot be differentiated twice
/// there, or the limit is itself degenerate (`|result|` at most [`MESH_NORMAL_RTOL`] times
/// the product of the two vectors' lengths: a collapse of higher order, or a point where
/// both directions collapse), in which case the caller falls back to neighbouring samples.
pub(crate) fn limit_normal(
    surface: &crate::Surface,
    u: f64,
    v: f64,
    ((u0, u1), (v0, v1)): ((f64, f64), (f64, f64)),
) -> Option<[f64; 3]> {
    if surface.dim() != 3 {
        return None;
    }
    // table layout of BSplineSurface::eval_derivatives at order 2: index k·3 + l for S_{u^k v^l}
    let d = surface.eval_derivatives(u, v, 2).ok()?;
    let get = |i: usize| -> [f64; 3] {
        let p = d.point(i);
        [p[0], p[1], p[2]]
    };
    let (sv, su, suv) = (get(1), get(3), get(4));
    let len = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let (n, scale) = if len(su) <= len(sv) {
        // the edge v = const collapses: S_u × S_v / h → S_uv × S_v
        let h = if v - v0 <= v1 - v { 1.0 } else { -1.0 };
        (cross(suv, sv).map(|x| h * x), len(suv) * len(sv))
    } else {
        // the edge u = const collapses: S_u × S_v / h → S_u × S_uv
        let h = if u - u0 <= u1 - u { 1.0 } else { -1.0 };
        (cross(su, suv).map(|x| h * x), len(su) * len(suv))
    };
    let m = len(n);
    (m.is_finite() && m > MESH_NORMAL_RTOL * scale && m > 0.0).then_some(n)
}

/// `a × b`.
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::Placement;
    use crate::{BSplineSurface, NurbsSurface, Points, Surface};
    use std::f64::consts::FRAC_PI_2;

    fn unit(n: [f64; 3]) -> [f64; 3] {
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        n.map(|x| x / l)
    }

    /// At the north pole of a NURBS sphere (an edge of the net collapsed to a point) the
    /// limit normal is the axis, outward as `S_u × S_v` points off the pole, whatever `u`
    /// and whichever parameter collapses (the surface transposed).
    #[test]
    fn limit_normal_at_a_sphere_s_pole_is_the_axis() {
        let frame = Placement::new([0.0; 3], None, None).unwrap();
        let s = NurbsSurface::sphere(&frame, 2.0, (0.0, FRAC_PI_2), (0.0, FRAC_PI_2)).unwrap();
        for surface in [Surface::Nurbs(s.clone()), Surface::Nurbs(s.transpose())] {
            let dom = surface.domain();
            let ((u0, u1), (v0, v1)) = dom;
            // the side S_u × S_v points to off the pole: outward or inward
            let (mu, mv) = ((u0 + u1) / 2.0, (v0 + v1) / 2.0);
            let d = surface.eval_derivatives(mu, mv, 1).unwrap();
            let (sv, su) = (d.point(1), d.point(2));
            let c = cross([su[0], su[1], su[2]], [sv[0], sv[1], sv[2]]);
            let p = surface.eval(mu, mv).unwrap();
            let side = (c[0] * p[0] + c[1] * p[1] + c[2] * p[2]).signum();
            // every (u, v) of the domain's boundary whose point is the pole
            let mut at_pole = 0;
            for k in 0..=16 {
                let t = f64::from(k) / 16.0;
                let (a, b) = (u0 + t * (u1 - u0), v0 + t * (v1 - v0));
                for (u, v) in [(a, v0), (a, v1), (u0, b), (u1, b)] {
                    if surface.eval(u, v).unwrap()[2] < 2.0 - 1e-12 {
                        continue;
                    }
                    at_pole += 1;
                    let n = unit(limit_normal(&surface, u, v, dom).expect("a limit normal"));
                    assert!((n[2] * side - 1.0).abs() < 1e-12, "{n:?} at ({u}, {v})");
                }
            }
            assert!(at_pole >= 17, "a whole edge at the pole: {at_pole}");
        }
    }

    /// A surface with no collapse gives no limit where the expansion's vector is itself zero:
    /// a flat bilinear patch (`S_uv = 0`).
    #[test]
    fn a_flat_patch_has_no_limit_normal() {
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
        ])
        .unwrap();
        let k = vec![0.0, 0.0, 1.0, 1.0];
        let s = Surface::BSpline(BSplineSurface::new(1, 1, k.clone(), k, net, (2, 2)).unwrap());
        let dom = s.domain();
        assert_eq!(limit_normal(&s, 0.0, 0.0, dom), None);
    }
}
