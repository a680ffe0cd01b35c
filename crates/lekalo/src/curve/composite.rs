//! [`Curve::composite`]: curves joined end to end into one B-spline or NURBS curve (IGES
//! entity 102, ISO 10303-42 `composite_curve`).

use crate::curve::any::Curve;
use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::points::{with_unit_weights, Points};

/// The default gap [`Curve::composite`] closes, relative to the members' size: see
/// [`Curve::composite_tolerance`].
pub const COMPOSITE_GAP_RTOL: f64 = 1e-9;

impl Curve {
    /// The default tolerance of [`Curve::composite`]: [`COMPOSITE_GAP_RTOL`] times the
    /// largest magnitude of the members' control point coordinates (rounding of end points
    /// computed separately, far below any modelling gap).
    #[must_use]
    pub fn composite_tolerance(members: &[Curve]) -> f64 {
        let size = members
            .iter()
            .flat_map(|c| c.control_points().as_slice().to_vec())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        COMPOSITE_GAP_RTOL * size
    }

    /// One curve running through `members` in order, each over its own parameter interval
    /// placed after the previous one's (member `k`'s domain shifted to start where member
    /// `k − 1`'s ends, IGES 5.3 §4.4: the composite's parameter is the members' in turn).
    ///
    /// In homogeneous coordinates (P&T §4.2) every member is raised to the highest degree `p`
    /// (P&T A5.9), clamped if it is not (its Bezier pieces joined), and the knot vectors are
    /// concatenated with each join a knot of multiplicity `p`: the curve is C⁰ there and each
    /// member's shape is kept exactly. The curve is rational if any member is; the weights of
    /// each member are scaled by one factor so that they agree at the joins, which leaves its
    /// points unchanged (P&T eq. 4.2 is homogeneous of degree 0 in the weights). A member's
    /// start that misses the previous member's end by at most `tolerance` is moved onto it
    /// (its first control point only).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Curve, NurbsCurve};
    /// let line = BSplineCurve::line_segment(&[1.0, -1.0], &[0.0, 1.0], 0.0, 1.0)?;
    /// let arc = NurbsCurve::circular_arc(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0, 0.0, 1.5)?;
    /// let c = Curve::composite(&[Curve::BSpline(line), Curve::Nurbs(arc)], 1e-12)?;
    /// assert!(c.is_rational() && c.degree() == 2);
    /// assert_eq!(c.domain(), (0.0, 2.0));
    /// let p = c.eval(1.5)?;
    /// assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a tolerance that is negative or not finite;
    /// [`Error::TooFew`] for no member; [`Error::Dimension`] for members of different
    /// dimensions; [`Error::InvalidArgument`] (`what` = `"composite members"`) for a member
    /// that starts farther than `tolerance` from where the previous one ends, naming both and
    /// the gap; the errors of degree elevation.
    pub fn composite(members: &[Curve], tolerance: f64) -> Result<Curve> {
        if !(tolerance >= 0.0 && tolerance.is_finite()) {
            return Err(Error::InvalidArgument {
                what: "composite tolerance".into(),
                reason: format!("{tolerance} is not a distance; give a finite number ≥ 0"),
            });
        }
        let Some(first) = members.first() else {
            return Err(Error::TooFew {
                what: "composite members".into(),
                min: 1,
                got: 0,
            });
        };
        let dim = first.dim();
        if let Some(m) = members.iter().find(|m| m.dim() != dim) {
            return Err(Error::Dimension {
                what: "composite members (each the first's dimension)".into(),
                expected: dim,
                got: m.dim(),
            });
        }
        let rational = members.iter().any(Curve::is_rational);
        let p = members.iter().map(Curve::degree).max().unwrap_or(1);
        let mut knots: Vec<f64> = Vec::new();
        let mut control: Vec<f64> = Vec::new();
        let hd = if rational { dim + 1 } else { dim };
        for (k, member) in members.iter().enumerate() {
            let clamped = if member.knots().is_clamped(member.degree()) {
                member.to_spline()
            } else {
                Curve::join(&member.to_bezier_pieces()?)?
            };
            let mut h = homogeneous(&clamped, rational)?;
            if h.degree() < p {
                h = h.elevate_degree(p - h.degree())?;
            }
            let a = h.domain().0;
            let (_, kv, pts) = h.into_parts();
            let mut pts = pts.into_vec();
            if k == 0 {
                knots.extend_from_slice(kv.as_slice());
                control = pts;
                continue;
            }
            // the previous end: the last knot and control point written
            let end = *knots.last().unwrap_or(&a);
            let prev = control[control.len() - hd..].to_vec();
            if rational {
                // one factor for the whole member: its weight at the join becomes the previous
                let f = prev[dim] / pts[dim];
                for x in &mut pts {
                    *x *= f;
                }
            }
            let w = |q: &[f64]| if rational { q[dim] } else { 1.0 };
            let gap = (0..dim)
                .map(|i| prev[i] / w(&prev) - pts[i] / w(&pts))
                .map(|d| d * d)
                .sum::<f64>()
                .sqrt();
            if gap > tolerance || gap.is_nan() {
                return Err(Error::InvalidArgument {
                    what: "composite members".into(),
                    reason: format!(
                        "member {} starts {gap:e} from the end of member {k}, more than the \
                         tolerance {tolerance:e}; the members must follow each other end to start",
                        k + 1
                    ),
                });
            }
            // the knots shifted to follow on, the join once less (multiplicity p), the first
            // control point the previous end
            knots.pop();
            knots.extend(kv.as_slice()[p + 1..].iter().map(|t| t - a + end));
            control.extend_from_slice(&pts[hd..]);
        }
        let spline = BSplineCurve::new(p, knots, Points::from_flat(hd, control)?)?;
        if rational {
            NurbsCurve::from_homogeneous(spline).map(Curve::Nurbs)
        } else {
            Ok(Curve::BSpline(spline))
        }
    }
}

/// The clamped spline `c` as a B-spline, in homogeneous coordinates when `rational` (unit
/// weights for a polynomial curve).
fn homogeneous(c: &Curve, rational: bool) -> Result<BSplineCurve> {
    match c {
        Curve::Nurbs(n) => Ok(n.homogeneous().clone()),
        Curve::BSpline(b) if rational => BSplineCurve::new(
            b.degree(),
            b.knots().as_slice().to_vec(),
            with_unit_weights(b.control_points()),
        ),
        Curve::BSpline(b) => Ok(b.clone()),
        Curve::Bezier(z) => homogeneous(&Curve::BSpline(z.to_bspline()), rational),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::bezier::BezierCurve;

    fn arc(a: f64, b: f64) -> Curve {
        Curve::Nurbs(
            NurbsCurve::circular_arc(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0, a, b).unwrap(),
        )
    }

    #[test]
    fn members_keep_their_shape_over_consecutive_intervals() {
        // a cubic Bezier from (1, 0) back up, a half circle, a line closing the loop
        let bez = Curve::Bezier(
            BezierCurve::new(
                Points::from_flat(2, vec![-1.0, 0.0, -1.0, -1.0, 1.0, -1.0, 1.0, 0.0]).unwrap(),
            )
            .unwrap(),
        );
        let half = arc(0.0, std::f64::consts::PI);
        let c = Curve::composite(&[half.clone(), bez.clone()], 1e-12).unwrap();
        assert_eq!((c.degree(), c.domain()), (3, (0.0, 2.0)));
        assert!(c.is_rational());
        for i in 0..=20 {
            let t = f64::from(i) / 20.0;
            let (x, y) = (c.eval(t).unwrap(), half.eval(t).unwrap());
            assert!(
                (x[0] - y[0]).abs() < 1e-14 && (x[1] - y[1]).abs() < 1e-14,
                "{t}"
            );
            let (x, y) = (c.eval(1.0 + t).unwrap(), bez.eval(t).unwrap());
            assert!(
                (x[0] - y[0]).abs() < 1e-14 && (x[1] - y[1]).abs() < 1e-14,
                "{t}"
            );
        }
        // the join is a knot of multiplicity p: C⁰, no more knots than the members'
        assert_eq!(c.knots().multiplicity(1.0), 3);
    }

    #[test]
    fn weights_agree_at_joins_and_gaps_are_closed_or_refused() {
        // two arcs whose weights are scaled differently: one curve, the second arc unchanged
        let a = arc(0.0, 1.0);
        let Curve::Nurbs(b) = arc(1.0, 2.0) else {
            unreachable!()
        };
        let scaled = NurbsCurve::from_homogeneous(
            BSplineCurve::new(
                2,
                b.knots().as_slice().to_vec(),
                Points::from_flat(
                    3,
                    b.homogeneous()
                        .control_points()
                        .as_slice()
                        .iter()
                        .map(|x| 3.0 * x)
                        .collect(),
                )
                .unwrap(),
            )
            .unwrap(),
        )
        .unwrap();
        let c = Curve::composite(&[a, Curve::Nurbs(scaled)], 1e-12).unwrap();
        let p = c.eval(1.5).unwrap();
        assert!((p[0] - 1.5f64.cos()).abs() < 1e-15 && (p[1] - 1.5f64.sin()).abs() < 1e-15);
        assert_eq!(
            c.knots().multiplicity(1.0),
            2,
            "one join, C⁰ in homogeneous space"
        );
        // a line starting 1e-9 off the arc's end: moved onto it within 1e-8, refused at 1e-10
        let end = [1.0f64.cos(), 1.0f64.sin()];
        let line = Curve::BSpline(
            BSplineCurve::line_segment(&[end[0] + 1e-9, end[1]], &[0.0, 1.0], 0.0, 1.0).unwrap(),
        );
        let c = Curve::composite(&[arc(0.0, 1.0), line.clone()], 1e-8).unwrap();
        assert_eq!(c.eval(1.0).unwrap(), arc(0.0, 1.0).eval(1.0).unwrap());
        let e = Curve::composite(&[arc(0.0, 1.0), line], 1e-10).unwrap_err();
        assert!(e.to_string().contains("member 2 starts 9.99"), "{e}");
        assert!(Curve::composite(&[], 1.0).is_err());
    }
}
