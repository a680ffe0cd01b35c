//! Intersections: curve–curve (planar and in space, with tangential contact and overlaps),
//! self-intersections of a planar curve, curve–plane and curve–surface, every answer naming its
//! kind of contact ([`Contact`]; `docs/theory/queries.md#intersections`).
//!
//! | file | subject |
//! |---|---|
//! | `planar.rs` | the search over pairs of planar sub-curves: sort and sweep of the pieces' boxes, Bezier clipping, halving, Newton's method |
//! | `space.rs` | the search over pairs of sub-curves outside the plane: halving, Levenberg–Marquardt |
//! | `curves.rs` | [`QueryCurve::intersect`] and [`QueryCurve::self_intersections`]: the search's solutions grouped into crossings, contacts and overlaps |
//! | `refine.rs` | a contact refined on the tangency system and named: touch, near miss or two crossings, order of contact |
//! | `surface.rs` | [`QueryCurve::intersect_plane`] and [`QueryCurve::intersect_surface`], with their overlaps |
//! | `surface_surface/` | [`QuerySurface::intersect_surface`] and [`QuerySurface::intersect_plane`]: branches of the intersection of two surfaces, plane sections |

mod curves;
mod planar;
mod refine;
mod space;
mod surface;
mod surface_surface;

pub use surface_surface::IntersectionBranch;

#[cfg(doc)]
use super::{pieces::QueryCurve, surface::QuerySurface};

/// Most sub-curve pairs one intersection visits (a bound on its work; reaching it is
/// [`crate::Error::TooLarge`]).
const MAX_PAIRS: usize = 1 << 20;
/// Deepest halving (or clipping) of a sub-curve.
const MAX_DEPTH: u32 = 48;

/// What kind of contact an intersection answer is (`docs/theory/queries.md#kinds-of-contact`).
/// Every intersection query of the library states it, and the front ends present it by
/// [`Contact::name`] without deciding it themselves.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Contact {
    /// A transversal crossing: the tangents (for a plane or a surface, the curve's tangent and
    /// the normal) are not orthogonal to what is crossed, and the gap changes sign through the
    /// point.
    Crossing,
    /// A tangential contact where the objects meet: the gap grows like `|Δt|^(order + 1)` away
    /// from the point (`order` 1 for a line touching a circle, 2 for `y = x³` against its
    /// tangent, which crosses; an odd `order` touches, an even one crosses).
    Tangent {
        /// Order of contact: how many derivatives of the gap vanish at the point, less one.
        order: u32,
    },
    /// A contact at an end point of either curve (within the tolerance of it), transversal or
    /// not.
    End,
    /// The objects come within the tolerance but do not meet: the least gap is larger than
    /// [`TOUCH_RTOL`] times their scale; the point is where the gap is least.
    NearMiss {
        /// The least gap (in the objects' units).
        gap: f64,
    },
    /// The objects coincide over an interval (within rounding).
    Overlap,
}

impl Contact {
    /// The canonical word of the kind, as every front end writes it: `crossing`, `tangent`,
    /// `end`, `near-miss` or `overlap`.
    pub fn name(&self) -> &'static str {
        match self {
            Contact::Crossing => "crossing",
            Contact::Tangent { .. } => "tangent",
            Contact::End => "end",
            Contact::NearMiss { .. } => "near-miss",
            Contact::Overlap => "overlap",
        }
    }

    /// The order of a tangential contact, `None` for the other kinds.
    pub fn order(&self) -> Option<u32> {
        match self {
            Contact::Tangent { order } => Some(*order),
            _ => None,
        }
    }

    /// The least gap of a near miss, `0` for the other kinds.
    pub fn gap(&self) -> f64 {
        match self {
            Contact::NearMiss { gap } => *gap,
            _ => 0.0,
        }
    }
}

impl std::fmt::Display for Contact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Largest gap, relative to the scale of the objects (the larger half-diagonal of their boxes),
/// at which a tangential contact counts as touching ([`Contact::Tangent`]) rather than as a
/// near miss ([`Contact::NearMiss`]) or two crossings: `2⁻⁴⁴ = 256·ε ≈ 5.7e-14`, the rounding of
/// a point evaluated from normalised control points (a unit in `2⁻⁵²` per de Casteljau level and
/// per change of frame) with a margin (`docs/theory/queries.md#kinds-of-contact`).
pub const TOUCH_RTOL: f64 = 256.0 * f64::EPSILON;

/// One intersection of two curves.
#[derive(Debug, Clone, PartialEq)]
pub enum CurveIntersection {
    /// The curves meet (or come within the tolerance) at a point: parameters on both, the point
    /// (the first curve's point) and the kind of contact (never [`Contact::Overlap`]).
    Point {
        /// Parameter on the first curve.
        t_a: f64,
        /// Parameter on the second curve.
        t_b: f64,
        /// The common point.
        point: Vec<f64>,
        /// Crossing, tangent, end or near miss.
        contact: Contact,
    },
    /// The curves coincide (within rounding) over an interval of each.
    Overlap {
        /// Parameter interval on the first curve.
        a: (f64, f64),
        /// The corresponding interval on the second (its ends in the order matching `a`).
        b: (f64, f64),
    },
}

impl CurveIntersection {
    /// The kind of contact ([`Contact::Overlap`] for an overlap).
    pub fn contact(&self) -> Contact {
        match self {
            CurveIntersection::Point { contact, .. } => *contact,
            CurveIntersection::Overlap { .. } => Contact::Overlap,
        }
    }
}

/// One intersection of a curve with a plane (a hyperplane: a line in 2-D).
#[derive(Debug, Clone, PartialEq)]
pub enum PlaneIntersection {
    /// The curve meets the plane at a point.
    Point {
        /// Parameter on the curve.
        t: f64,
        /// The point.
        point: Vec<f64>,
        /// Crossing, tangent or end (never an overlap or a near miss: the roots are exact).
        contact: Contact,
    },
    /// The curve lies in the plane over an interval of its parameter.
    Overlap {
        /// The parameter interval.
        t: (f64, f64),
    },
}

impl PlaneIntersection {
    /// The kind of contact ([`Contact::Overlap`] for an overlap).
    pub fn contact(&self) -> Contact {
        match self {
            PlaneIntersection::Point { contact, .. } => *contact,
            PlaneIntersection::Overlap { .. } => Contact::Overlap,
        }
    }
}

/// One intersection of a curve with a surface.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceIntersection {
    /// The curve meets the surface (or comes within the tolerance) at a point.
    Point {
        /// Parameter on the curve.
        t: f64,
        /// Parameters `(u, v)` on the surface.
        uv: (f64, f64),
        /// The point (the curve's point).
        point: Vec<f64>,
        /// Crossing, tangent, end or near miss.
        contact: Contact,
    },
    /// The curve lies on the surface over an interval of its parameter.
    Overlap {
        /// The parameter interval on the curve.
        t: (f64, f64),
        /// The surface parameters `(u, v)` at its two ends.
        uv: ((f64, f64), (f64, f64)),
    },
}

impl SurfaceIntersection {
    /// The kind of contact ([`Contact::Overlap`] for an overlap).
    pub fn contact(&self) -> Contact {
        match self {
            SurfaceIntersection::Point { contact, .. } => *contact,
            SurfaceIntersection::Overlap { .. } => Contact::Overlap,
        }
    }
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
