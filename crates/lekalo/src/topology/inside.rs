//! [`TrimRegion`]: the loops of a face in the surface's `(u, v)`, sampled into polygons, and
//! the point-in-face test by winding numbers (Hormann and Agathos, "The point in polygon
//! problem for arbitrary polygons", Comput. Geom. 20 (2001) 131–144, algorithm 6, with the
//! crossing rule of Sunday).

use super::face::Face;
use crate::{Error, Points, Result};

/// Samples per knot span of a pcurve when a [`TrimRegion`] makes its polygons (at least 16
/// per edge): a chord of a span's sixteenth departs from a curve of curvature `κ` by about
/// `κ h² / 8` for a chord of length `h`, so a point closer to a trim than that may be classed
/// on the wrong side.
pub const TRIM_SAMPLES_PER_SPAN: usize = 16;

/// Most points a [`TrimRegion`] holds over all its polygons.
const MAX_TRIM_POINTS: usize = 1 << 24;

/// The trims of a face in its surface's `(u, v)`: each loop as a closed polygon through points
/// of its edges' pcurves, in loop order. A point is inside the face when the outer polygon
/// winds around it (non-zero winding number) and no inner polygon does; the rule does not
/// depend on the direction in which the loops run.
#[derive(Debug, Clone, PartialEq)]
pub struct TrimRegion {
    polygons: Vec<Points>,
}

impl Face {
    /// The trims in `(u, v)` ([`TrimRegion`]): each pcurve sampled at
    /// [`TRIM_SAMPLES_PER_SPAN`] points per knot span (at least 16).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] (`what` "face loop") naming the loop and the edge when an
    /// edge has no pcurve (a face read from a file whose pcurves are not in the parameters of
    /// the surface lekalo built); [`Error::TooLarge`] past 2^24 points.
    pub fn trim_region(&self) -> Result<TrimRegion> {
        let mut polygons = Vec::with_capacity(1 + self.inner().len());
        let mut total = 0usize;
        for (i, lp) in self.loops().enumerate() {
            let mut data = Vec::new();
            for (k, e) in lp.edges().iter().enumerate() {
                let Some(p) = e.pcurve() else {
                    return Err(Error::InvalidArgument {
                        what: "face loop".into(),
                        reason: format!(
                            "edge {k} of loop {i} has no curve in the surface's (u, v); the point-in-face test needs every edge's pcurve"
                        ),
                    });
                };
                let spans = p.knots().distinct().len().saturating_sub(1).max(1);
                let n = spans.saturating_mul(TRIM_SAMPLES_PER_SPAN).max(16);
                total = total.saturating_add(n);
                if total > MAX_TRIM_POINTS {
                    return Err(Error::TooLarge {
                        what: "points of a face's trim polygons".into(),
                        size: total,
                        max: MAX_TRIM_POINTS,
                    });
                }
                let pts = p.sample(n)?;
                // the last point is the next edge's first
                data.extend_from_slice(&pts.as_slice()[..2 * (n - 1)]);
            }
            polygons.push(Points::from_flat(2, data)?);
        }
        Ok(TrimRegion { polygons })
    }
}

impl TrimRegion {
    /// The polygons, outer first, each as its vertices in order (the last joined to the
    /// first).
    #[must_use]
    pub fn polygons(&self) -> &[Points] {
        &self.polygons
    }

    /// True when `(u, v)` is inside the face: the outer polygon's winding number about it is not
    /// zero and every inner polygon's is.
    #[must_use]
    pub fn contains(&self, u: f64, v: f64) -> bool {
        let mut it = self.polygons.iter();
        let Some(outer) = it.next() else { return false };
        winding_number(outer.as_slice(), u, v) != 0
            && it.all(|p| winding_number(p.as_slice(), u, v) == 0)
    }
}

/// The winding number of the closed polygon `xy` (flat `x0 y0 x1 y1 …`, the last vertex joined
/// to the first) about `(x, y)`: the signed count of its crossings of the ray from the point in
/// the `+x` direction, upward crossings with the point on their left counted `+1` and downward
/// ones with the point on their right `−1` (Sunday's rule; Hormann and Agathos 2001, algorithm
/// 6). Counterclockwise polygons wind `+1` round their inside; a point on an edge may count
/// either way.
///
/// ```
/// let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
/// assert_eq!(lekalo::topology::winding_number(&square, 0.5, 0.5), 1);
/// assert_eq!(lekalo::topology::winding_number(&square, 1.5, 0.5), 0);
/// ```
#[must_use]
pub fn winding_number(xy: &[f64], x: f64, y: f64) -> i64 {
    let n = xy.len() / 2;
    let mut w = 0i64;
    for i in 0..n {
        let j = (i + 1) % n;
        let (x0, y0, x1, y1) = (xy[2 * i], xy[2 * i + 1], xy[2 * j], xy[2 * j + 1]);
        // > 0 when (x, y) is left of the edge from (x0, y0) to (x1, y1)
        let left = (x1 - x0) * (y - y0) - (x - x0) * (y1 - y0);
        if y0 <= y {
            if y1 > y && left > 0.0 {
                w += 1;
            }
        } else if y1 <= y && left < 0.0 {
            w -= 1;
        }
    }
    w
}
