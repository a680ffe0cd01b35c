//! Offsets of planar curves: `C(t) + d·N(t)` approximated by a cubic B-spline within a
//! tolerance, with the cusps where `d·κ = 1` found and the loops between them trimmed
//! (`docs/theory/queries.md#offsets`).

use super::intersect::CurveIntersection;
use super::pieces::{check_tolerance, dist, QueryCurve};
use crate::error::{check_finite, Error, Result};
use crate::{BSplineCurve, CurveInterpolation, Points};

/// Most interpolation points per piece of the base curve.
const MAX_SAMPLES_PER_PIECE: usize = 1 << 12;

/// The offset of a planar curve.
#[derive(Debug, Clone)]
pub struct Offset {
    /// The whole offset as one cubic B-spline on the base curve's parameters (loops included):
    /// `curve(t) ≈ C(t) + d·N(t)`.
    pub curve: BSplineCurve,
    /// The offset with its loops cut out: the parts between the trimmed intervals.
    pub trimmed: Vec<BSplineCurve>,
    /// Parameters of the cusps (`d·κ(t) = 1`).
    pub cusps: Vec<f64>,
    /// The parameter intervals removed as loops: each from the self-intersection on the
    /// part before a pair of cusps to the one after it.
    pub loops: Vec<(f64, f64)>,
    /// Largest deviation `|curve(t) − (C(t) + d·N(t))|` found at the check points (7 between
    /// every two interpolation points).
    pub deviation: f64,
}

impl QueryCurve {
    /// The exact offset point `C(t) + d·N(t)` and the factor `1 − d·κ(t)` (signed curvature,
    /// left normal `N = (−y', x')/|C'|`); `None` where `C' = 0`.
    fn offset_point(&self, t: f64, d: f64, scratch: &mut Vec<f64>) -> Option<([f64; 2], f64)> {
        let v = self.eval_global(t, 2, scratch);
        let (x1, y1, x2, y2) = (v[2], v[3], v[4], v[5]);
        let speed = x1.hypot(y1);
        if !(speed > 0.0) {
            return None;
        }
        let kappa = (x1 * y2 - y1 * x2) / (speed * speed * speed);
        Some((
            [v[0] - d * y1 / speed, v[1] + d * x1 / speed],
            1.0 - d * kappa,
        ))
    }

    /// The offset of a planar curve at signed distance `d` (positive to the left of the
    /// direction of travel) as a cubic B-spline within `tolerance` of `C(t) + d·N(t)`: each
    /// piece of the curve is interpolated at the offset points (at its own parameters), the
    /// number of points doubled from 8 until the deviation at 7 check points between every two
    /// is within the tolerance (a sampled check). Cusps (`d·κ = 1`) are found by bisection
    /// between the curvature extrema and inflections, where the signed curvature is monotone;
    /// between two cusps where `1 − d·κ < 0` the offset runs backwards and forms a loop, cut
    /// out at the self-intersection of the parts before and after.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, QueryCurve};
    /// // a circle of radius 2 offset inwards by 0.5 is the circle of radius 1.5
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0)?;
    /// let off = QueryCurve::from_nurbs(&c)?.offset(0.5, 1e-6)?;
    /// assert!(off.deviation <= 1e-6 && off.cusps.is_empty());
    /// let p = off.curve.eval(0.3)?;
    /// assert!((p[0].hypot(p[1]) - 1.5).abs() < 1e-6);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless planar; [`Error::NonFinite`] / [`Error::InvalidArgument`] for
    /// a bad distance or tolerance, or a curve with a stationary point (`C' = 0`, no normal);
    /// [`Error::TooLarge`] if a piece needs more than 4096 points.
    pub fn offset(&self, d: f64, tolerance: f64) -> Result<Offset> {
        if self.dim != 2 {
            return Err(Error::Dimension {
                what: "curve to offset",
                expected: 2,
                got: self.dim,
            });
        }
        check_finite("offset distance", &[d])?;
        check_tolerance("offset tolerance", tolerance)?;
        let mut scratch = Vec::new();
        let no_normal = |t: f64| Error::InvalidArgument {
            what: "curve to offset",
            reason: format!("C'(t) = 0 at t = {t}: the normal, hence the offset, is undefined"),
        };
        let mut segments = Vec::new();
        let mut worst = 0.0_f64;
        for k in 0..self.piece_count() {
            let (a, b) = self.spans[k];
            let mut m = 8_usize;
            loop {
                let ts: Vec<f64> = (0..=m).map(|i| a + (b - a) * i as f64 / m as f64).collect();
                let mut pts = Vec::with_capacity(2 * (m + 1));
                for &t in &ts {
                    let (p, _) = self
                        .offset_point(t, d, &mut scratch)
                        .ok_or_else(|| no_normal(t))?;
                    pts.extend(p);
                }
                let spline = CurveInterpolation::new(3)
                    .interpolate_at(Points::from_flat(2, pts)?.as_view(), &ts)?;
                let mut dev = 0.0_f64;
                for i in 0..m {
                    for j in 1..8 {
                        let t = ts[i] + (ts[i + 1] - ts[i]) * f64::from(j) / 8.0;
                        let (p, _) = self
                            .offset_point(t, d, &mut scratch)
                            .ok_or_else(|| no_normal(t))?;
                        dev = dev.max(dist(&spline.eval(t)?, &p));
                    }
                }
                if dev <= tolerance {
                    worst = worst.max(dev);
                    segments.extend(spline.to_bezier_segments());
                    break;
                }
                if m >= MAX_SAMPLES_PER_PIECE {
                    return Err(Error::TooLarge {
                        what: "offset interpolation points per piece (tolerance not reached)",
                        size: 2 * m,
                        max: MAX_SAMPLES_PER_PIECE,
                    });
                }
                m *= 2;
            }
        }
        let curve = BSplineCurve::from_bezier_segments(&segments)?;
        // cusps: 1 − dκ is monotone between the curvature extrema and inflections
        let mut breaks: Vec<f64> = self.spans.iter().map(|s| s.0).collect();
        breaks.push(self.domain().1);
        breaks.extend(self.curvature_extrema()?.iter().map(|e| e.t));
        breaks.extend(self.inflections()?);
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let h =
            |t: f64, scratch: &mut Vec<f64>| self.offset_point(t, d, scratch).map_or(0.0, |x| x.1);
        let mut cusps = Vec::new();
        for w in breaks.windows(2) {
            let (mut lo, mut hi) = (w[0], w[1]);
            let (flo, fhi) = (h(lo, &mut scratch), h(hi, &mut scratch));
            if !(flo * fhi < 0.0) {
                continue;
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if (h(mid, &mut scratch) < 0.0) == (flo < 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            cusps.push(0.5 * (lo + hi));
        }
        // loops: between consecutive cusps where the offset runs backwards
        let (lo, hi) = self.domain();
        let mut loops = Vec::new();
        let mut bounds = vec![lo];
        bounds.extend(&cusps);
        bounds.push(hi);
        for i in 1..bounds.len().saturating_sub(2) {
            let (c1, c2) = (bounds[i], bounds[i + 1]);
            if h(0.5 * (c1 + c2), &mut scratch) >= 0.0 {
                continue;
            }
            let before = sub_curve(&curve, bounds[i - 1], c1)?;
            let after = sub_curve(&curve, c2, bounds[i + 2])?;
            let hits = QueryCurve::from_bspline(&before)?
                .intersect(&QueryCurve::from_bspline(&after)?, tolerance)?;
            let best = hits
                .iter()
                .filter_map(|x| match x {
                    CurveIntersection::Point { t_a, t_b, .. } => Some((*t_a, *t_b)),
                    CurveIntersection::Overlap { .. } => None,
                })
                .min_by(|x, y| ((c1 - x.0) + (x.1 - c2)).total_cmp(&((c1 - y.0) + (y.1 - c2))));
            if let Some(cut) = best {
                loops.push(cut);
            }
        }
        let mut trimmed = Vec::new();
        let mut start = lo;
        for &(a, b) in &loops {
            if a > start {
                trimmed.push(sub_curve(&curve, start, a)?);
            }
            start = b;
        }
        if hi > start {
            trimmed.push(sub_curve(&curve, start, hi)?);
        }
        Ok(Offset {
            curve,
            trimmed,
            cusps,
            loops,
            deviation: worst,
        })
    }
}

/// The part of `c` on `[a, b]` (inside its domain, `a < b`).
fn sub_curve(c: &BSplineCurve, a: f64, b: f64) -> Result<BSplineCurve> {
    let (lo, hi) = c.domain();
    let right = if a > lo { c.split_at(a)?.1 } else { c.clone() };
    Ok(if b < hi { right.split_at(b)?.0 } else { right })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{NurbsCurve, Points};

    #[test]
    fn offset_is_within_tolerance_and_at_distance() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, -1.0], [4.0, 1.0], [5.0, 0.0]])
                .unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let off = q.offset(0.1, 1e-6).unwrap();
        assert!(off.deviation <= 1e-6, "{}", off.deviation);
        // every offset point is at distance |d| from the curve (where no loop is trimmed)
        for i in 0..=50 {
            let t = f64::from(i) / 50.0;
            let p = off.curve.eval(t).unwrap();
            let pr = q.project(&p).unwrap();
            assert!((pr.distance - 0.1).abs() <= 2e-6, "t {t}: {}", pr.distance);
        }
    }

    #[test]
    fn inner_offset_of_an_ellipse_has_cusps_and_loops() {
        // a stretched circle: radius of curvature b²/a = 0.25 at the ends of the long axis
        let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap();
        let h = c.homogeneous();
        let mut data = h.control_points().as_slice().to_vec();
        for p in data.chunks_exact_mut(3) {
            p[0] *= 2.0; // x scaled: the ellipse x²/4 + y² = 1
        }
        let e = NurbsCurve::from_homogeneous(
            BSplineCurve::new(
                2,
                h.knots().as_slice().to_vec(),
                Points::from_flat(3, data).unwrap(),
            )
            .unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_nurbs(&e).unwrap();
        // inward (left of the counter-clockwise ellipse) by 0.6 > 0.25: swallowtails at both ends
        let off = q.offset(0.6, 1e-6).unwrap();
        assert_eq!(off.cusps.len(), 4, "{:?}", off.cusps);
        assert!(!off.loops.is_empty(), "loops {:?}", off.loops);
    }
}
