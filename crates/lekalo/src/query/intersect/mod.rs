//! Intersections: planar curve–curve (with tangential contact and overlaps), self-intersections
//! of a planar curve, curve–plane and curve–surface (`docs/theory/queries.md#intersections`).
//!
//! | file | subject |
//! |---|---|
//! | `planar.rs` | the search over pairs of planar sub-curves: sort and sweep of the pieces' boxes, Bezier clipping, halving, Newton's method |
//! | `curves.rs` | [`QueryCurve::intersect`] and [`QueryCurve::self_intersections`]: the search's solutions grouped into crossings, contacts and overlaps |
//! | `surface.rs` | [`QueryCurve::intersect_plane`] and [`QueryCurve::intersect_surface`] |

mod curves;
mod planar;
mod surface;

#[cfg(doc)]
use super::pieces::QueryCurve;

/// Most sub-curve pairs one intersection visits (a bound on its work; reaching it is
/// [`crate::Error::TooLarge`]).
const MAX_PAIRS: usize = 1 << 20;
/// Deepest halving (or clipping) of a sub-curve.
const MAX_DEPTH: u32 = 48;

/// A curve–surface intersection: the curve's parameter, the surface's `(u, v)` and the point.
pub type SurfaceHit = (f64, (f64, f64), Vec<f64>);

/// One intersection of two curves.
#[derive(Debug, Clone, PartialEq)]
pub enum CurveIntersection {
    /// The curves meet at a point (crossing or touching): parameters on both and the point
    /// (the first curve's point).
    Point {
        /// Parameter on the first curve.
        t_a: f64,
        /// Parameter on the second curve.
        t_b: f64,
        /// The common point.
        point: Vec<f64>,
    },
    /// The curves coincide (within rounding) over an interval of each.
    Overlap {
        /// Parameter interval on the first curve.
        a: (f64, f64),
        /// The corresponding interval on the second (its ends in the order matching `a`).
        b: (f64, f64),
    },
}

/// Distance from `x` to the segment `[a, b]`.
pub(crate) fn segment_distance(x: &[f64], a: &[f64], b: &[f64]) -> f64 {
    let ab: Vec<f64> = a.iter().zip(b).map(|(p, q)| q - p).collect();
    let ax: Vec<f64> = a.iter().zip(x).map(|(p, q)| q - p).collect();
    let l2: f64 = ab.iter().map(|v| v * v).sum();
    let t = if l2 > 0.0 {
        (ax.iter().zip(&ab).map(|(p, q)| p * q).sum::<f64>() / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ax.iter()
        .zip(&ab)
        .map(|(p, q)| (p - t * q) * (p - t * q))
        .sum::<f64>()
        .sqrt()
}

/// Whether two boxes (minima then maxima, `dim` each) overlap within `slack`.
fn boxes_overlap(a: &[f64], b: &[f64], dim: usize, slack: f64) -> bool {
    (0..dim).all(|d| a[d] <= b[dim + d] + slack && b[d] <= a[dim + d] + slack)
}
