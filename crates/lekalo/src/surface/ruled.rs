//! The ruled surface between two NURBS curves, exact (P&T §8.2): both curves brought to the
//! domain `[0, 1]`, to the same degree (degree elevation, P&T A5.9) and to the same knots
//! (knot refinement, P&T A5.4), in homogeneous coordinates; then the net of degree 1 in `v`
//! whose rows are the two curves' control points.

use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::points::Points;
use crate::surface::bspline::BSplineSurface;
use crate::surface::nurbs::NurbsSurface;

impl NurbsSurface {
    /// The ruled surface `S(u, v) = (1 − v) C₀(u) + v C₁(u)` between two NURBS curves of one
    /// dimension, each taken on `[0, 1]` by the affine change of its parameter (IGES 5.3
    /// §4.17 form 1: points of equal relative parameter joined by lines), `v ∈ [0, 1]`.
    ///
    /// Exact (P&T §8.2): in homogeneous coordinates the curves are brought to one degree
    /// (the lower one elevated, P&T A5.9) and one knot vector (each knot at the larger of its
    /// two multiplicities, by refinement, P&T A5.4), and the surface of degree `(p, 1)` has the
    /// two homogeneous control polygons as its rows. For rational curves the lines join the
    /// points of equal parameter in homogeneous space, which projects to the straight lines
    /// between `C₀(u)` and `C₁(u)` (each at its own rational parameter along them).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, NurbsCurve, NurbsSurface};
    /// // a unit circle arc and a line below it: every v-line a straight segment
    /// let arc = NurbsCurve::circular_arc(&[0.0, 0.0, 1.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0],
    ///     1.0, 0.0, std::f64::consts::FRAC_PI_2)?;
    /// let seg = BSplineCurve::line_segment(&[1.0, 0.0, 0.0], &[-1.0, 1.0, 0.0], 0.0, 1.0)?;
    /// let s = NurbsSurface::ruled(&arc, &NurbsCurve::from_bspline(&seg))?;
    /// assert_eq!(s.degree(), (2, 1));
    /// let (on_arc, on_segment) = (s.eval(0.3, 0.0)?, s.eval(0.3, 1.0)?);
    /// assert!((on_arc[0].hypot(on_arc[1]) - 1.0).abs() < 1e-14 && (on_arc[2] - 1.0).abs() < 1e-15);
    /// assert!((on_segment[0] + on_segment[1] - 1.0).abs() < 1e-14 && on_segment[2].abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] for curves of different dimensions; [`Error::TooLarge`] if the
    /// common knots would not fit in memory; the errors of refinement for knots that cannot
    /// be inserted.
    pub fn ruled(first: &NurbsCurve, second: &NurbsCurve) -> Result<NurbsSurface> {
        if first.dim() != second.dim() {
            return Err(Error::Dimension {
                what: "the second curve of a ruled surface".into(),
                expected: first.dim(),
                got: second.dim(),
            });
        }
        let on_unit = |c: &NurbsCurve| -> Result<BSplineCurve> {
            Ok(c.reparametrize(0.0, 1.0)?.homogeneous().clone())
        };
        let (mut a, mut b) = (on_unit(first)?, on_unit(second)?);
        let p = a.degree().max(b.degree());
        if a.degree() < p {
            a = a.elevate_degree(p - a.degree())?;
        }
        if b.degree() < p {
            b = b.elevate_degree(p - b.degree())?;
        }
        let (a, b) = (merged(&a, &b)?, merged(&b, &a)?);
        let hd = a.dim();
        let n = a.control_points().len();
        let mut net = Vec::with_capacity(2 * n * hd);
        for (x, y) in a.control_points().iter().zip(b.control_points().iter()) {
            net.extend_from_slice(x);
            net.extend_from_slice(y);
        }
        let homogeneous = BSplineSurface::new(
            p,
            1,
            a.knots().as_slice().to_vec(),
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_flat(hd, net)?,
            (n, 2),
        )?;
        NurbsSurface::from_homogeneous(homogeneous)
    }
}

/// `c` refined with every knot of `other` (both on `[0, 1]`, one degree) that it has fewer
/// times: each interior knot value at the larger of its two multiplicities.
fn merged(c: &BSplineCurve, other: &BSplineCurve) -> Result<BSplineCurve> {
    let mine = c.knots().distinct();
    let mut missing = Vec::new();
    for (x, m) in other.knots().distinct() {
        if x <= 0.0 || x >= 1.0 {
            continue;
        }
        let have = mine.iter().find(|(y, _)| *y == x).map_or(0, |&(_, k)| k);
        missing.extend(std::iter::repeat_n(x, m.saturating_sub(have)));
    }
    if missing.is_empty() {
        Ok(c.clone())
    } else {
        c.refine_knots(&missing)
    }
}

#[cfg(test)]
mod tests {
    use crate::curve::bspline::BSplineCurve;
    use crate::curve::nurbs::NurbsCurve;
    use crate::error::Error;
    use crate::points::Points;
    use crate::surface::nurbs::NurbsSurface;

    /// A cubic on [2, 5] with an interior knot and a rational quadratic on [−1, 0]: every
    /// point of the surface on the segment between the curves' points of equal relative
    /// parameter, at the fraction `v` of the way in homogeneous terms, and its edges the
    /// curves.
    #[test]
    fn edges_are_the_curves_and_v_lines_are_segments() {
        let c0 = BSplineCurve::new(
            3,
            vec![2.0, 2.0, 2.0, 2.0, 3.5, 5.0, 5.0, 5.0, 5.0],
            Points::from_3d(&[
                [0.0, 0.0, 0.0],
                [1.0, 2.0, 0.5],
                [2.0, -1.0, 1.0],
                [3.0, 1.0, 0.0],
                [4.0, 0.0, 2.0],
            ])
            .unwrap(),
        )
        .unwrap();
        let c0 = NurbsCurve::from_bspline(&c0);
        let c1 = NurbsCurve::new(
            2,
            vec![-1.0, -1.0, -1.0, -0.3, 0.0, 0.0, 0.0],
            Points::from_3d(&[
                [0.0, 3.0, 0.0],
                [1.0, 5.0, 1.0],
                [3.0, 4.0, 0.0],
                [4.0, 3.0, 1.0],
            ])
            .unwrap(),
            vec![1.0, 2.0, 0.5, 1.0],
        )
        .unwrap();
        let s = NurbsSurface::ruled(&c0, &c1).unwrap();
        assert_eq!(s.degree(), (3, 1));
        for k in 0..=20 {
            let u = f64::from(k) / 20.0;
            let (p0, p1) = (c0.eval(2.0 + 3.0 * u).unwrap(), c1.eval(-1.0 + u).unwrap());
            let (e0, e1) = (s.eval(u, 0.0).unwrap(), s.eval(u, 1.0).unwrap());
            for d in 0..3 {
                assert!((e0[d] - p0[d]).abs() < 1e-13, "{u}: {e0:?} {p0:?}");
                assert!((e1[d] - p1[d]).abs() < 1e-13, "{u}: {e1:?} {p1:?}");
            }
            // an interior point lies on the segment p0 p1
            let m = s.eval(u, 0.4).unwrap();
            let (d, e): (Vec<f64>, Vec<f64>) =
                (0..3).map(|i| (p1[i] - p0[i], m[i] - p0[i])).unzip();
            let t = (d[0] * e[0] + d[1] * e[1] + d[2] * e[2])
                / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            assert!((0.0..=1.0).contains(&t), "{t}");
            for i in 0..3 {
                assert!((e[i] - t * d[i]).abs() < 1e-13, "{u}: off the segment");
            }
        }
    }

    #[test]
    fn curves_of_different_dimensions_are_refused() {
        let a = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap();
        let b =
            NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0).unwrap();
        assert!(matches!(
            NurbsSurface::ruled(&a, &b),
            Err(Error::Dimension {
                expected: 2,
                got: 3,
                ..
            })
        ));
    }
}
