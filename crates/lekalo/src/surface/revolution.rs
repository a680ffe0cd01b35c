//! Swept surfaces as exact NURBS: the surface of revolution of a NURBS curve (P&T §8.5,
//! Algorithm A8.1) and the extrusion of a NURBS curve along a vector (the general cylinder of
//! P&T §8.3).

use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{check_finite, Error, Result};
use crate::points::Points;
use crate::surface::bspline::BSplineSurface;
use crate::surface::nurbs::NurbsSurface;
use crate::What;

/// `v / |v|`, or an error naming `what` for a zero or non-finite vector.
pub(crate) fn unit3(v: [f64; 3], what: &'static str) -> Result<[f64; 3]> {
    check_finite(what, &v)?;
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(n > 0.0 && n.is_finite()) {
        return Err(Error::InvalidArgument {
            what: what.into(),
            reason: "the vector is zero or overflows; give a direction".into(),
        });
    }
    Ok([v[0] / n, v[1] / n, v[2] / n])
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn check_3d(curve: &NurbsCurve, what: impl Into<What>) -> Result<()> {
    let what: What = what.into();
    if curve.dim() != 3 {
        return Err(Error::Dimension {
            what,
            expected: 3,
            got: curve.dim(),
        });
    }
    Ok(())
}

impl NurbsSurface {
    /// The surface swept by `generatrix` turning about the axis through `axis_point` along
    /// `axis_direction`, from `start_angle` to `end_angle` (radians, counter-clockwise seen from
    /// the tip of the axis; ISO 10303-42 `surface_of_revolution`, §4.5.3): the point of
    /// parameter `v` turned by `θ` is `O + cos θ r + sin θ (ẑ × r)`, `O` its foot on the axis,
    /// `r` its offset from it.
    ///
    /// Exact, by P&T §8.5 (Algorithm A8.1): `u` runs along the circular arcs (the rational
    /// quadratic of [`NurbsCurve::circular_arc`] on `[0, 1]`, so `u` is not the angle), `v` is
    /// the generatrix's own parameter. Control point `(i, j)` is the generatrix's control point
    /// `P_j` carried by the `i`-th control point `(x_i, y_i)` of the unit arc,
    /// `O_j + x_i r_j + y_i (ẑ × r_j)`, with weight `w_j · ω_i`. A control point on the axis
    /// stays there (a pole of a sphere).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, NurbsCurve, NurbsSurface};
    /// // a segment parallel to z at distance 2, turned a full turn: a cylinder of radius 2
    /// let seg = BSplineCurve::line_segment(&[2.0, 0.0, 0.0], &[0.0, 0.0, 1.0], 0.0, 3.0)?;
    /// let s = NurbsSurface::revolve(&NurbsCurve::from_bspline(&seg), [0.0; 3], [0.0, 0.0, 1.0],
    ///     0.0, std::f64::consts::TAU)?;
    /// let p = s.eval(0.3, 1.5)?;
    /// assert!((p[0].hypot(p[1]) - 2.0).abs() < 1e-14 && (p[2] - 1.5).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless the generatrix is 3-D; [`Error::InvalidArgument`] for a zero
    /// axis or a sweep of zero or more than a full turn; [`Error::NonFinite`].
    pub fn revolve(
        generatrix: &NurbsCurve,
        axis_point: [f64; 3],
        axis_direction: [f64; 3],
        start_angle: f64,
        end_angle: f64,
    ) -> Result<Self> {
        check_3d(generatrix, "generatrix")?;
        check_finite("axis point", &axis_point)?;
        let z = unit3(axis_direction, "axis direction")?;
        let arc = NurbsCurve::circular_arc(
            &[0.0, 0.0],
            &[1.0, 0.0],
            &[0.0, 1.0],
            1.0,
            start_angle,
            end_angle,
        )?;
        let arc_h = arc.homogeneous();
        let gen_h = generatrix.homogeneous();
        let (nu, nv) = (arc_h.control_points().len(), gen_h.control_points().len());
        let mut data = Vec::with_capacity(nu * nv * 4);
        for a in arc_h.control_points().as_slice().chunks_exact(3) {
            let (ax, ay, aw) = (a[0], a[1], a[2]);
            for g in gen_h.control_points().as_slice().chunks_exact(4) {
                let w = g[3];
                let p = [g[0] / w, g[1] / w, g[2] / w];
                let d = [
                    p[0] - axis_point[0],
                    p[1] - axis_point[1],
                    p[2] - axis_point[2],
                ];
                let h = dot3(d, z);
                let o = [
                    axis_point[0] + h * z[0],
                    axis_point[1] + h * z[1],
                    axis_point[2] + h * z[2],
                ];
                let r = [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
                let s = cross(z, r);
                for k in 0..3 {
                    data.push(w * (aw * o[k] + ax * r[k] + ay * s[k]));
                }
                data.push(w * aw);
            }
        }
        let homogeneous = BSplineSurface::new(
            arc.degree(),
            generatrix.degree(),
            arc.knots().as_slice().to_vec(),
            generatrix.knots().as_slice().to_vec(),
            Points::from_flat(4, data)?,
            (nu, nv),
        )?;
        NurbsSurface::from_homogeneous(homogeneous)
    }

    /// The surface swept by `curve` moved along `direction`: `S(u, v) = C(u) + v D`,
    /// `v ∈ [v0, v1]` (ISO 10303-42 `surface_of_linear_extrusion`, §4.5.2, with `D` the
    /// extrusion vector, its length included). Exact, as the general cylinder of P&T §8.3:
    /// degree 1 in `v`, the curve's control points at `v0` and `v1` with its weights.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, NurbsSurface};
    /// let c = NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0)?;
    /// let s = NurbsSurface::extrude(&c, [0.0, 0.0, 2.0], 0.0, 1.0)?;
    /// let p = s.eval(0.4, 1.0)?;
    /// assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-14 && (p[2] - 2.0).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless the curve is 3-D; [`Error::InvalidArgument`] for a zero
    /// direction; knot errors unless `v0 < v1`; [`Error::NonFinite`].
    pub fn extrude(curve: &NurbsCurve, direction: [f64; 3], v0: f64, v1: f64) -> Result<Self> {
        check_3d(curve, "extruded curve")?;
        unit3(direction, "extrusion direction")?;
        check_finite("extrusion range", &[v0, v1])?;
        let h = curve.homogeneous();
        let n = h.control_points().len();
        let mut data = Vec::with_capacity(n * 8);
        for g in h.control_points().as_slice().chunks_exact(4) {
            for v in [v0, v1] {
                for k in 0..3 {
                    data.push(g[k] + g[3] * v * direction[k]);
                }
                data.push(g[3]);
            }
        }
        let homogeneous = BSplineSurface::new(
            curve.degree(),
            1,
            curve.knots().as_slice().to_vec(),
            vec![v0, v0, v1, v1],
            Points::from_flat(4, data)?,
            (n, 2),
        )?;
        NurbsSurface::from_homogeneous(homogeneous)
    }
}

/// The segment `a + t d`, `t ∈ [t0, t1]`, as a NURBS generatrix.
pub(crate) fn segment(a: [f64; 3], d: [f64; 3], t0: f64, t1: f64) -> Result<NurbsCurve> {
    Ok(NurbsCurve::from_bspline(&BSplineCurve::line_segment(
        &a, &d, t0, t1,
    )?))
}
