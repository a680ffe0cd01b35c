//! Surface–surface intersection and plane sections of surfaces
//! (`docs/theory/queries.md#surface-surface-intersection`): starting points from a subdivision
//! with loop detection, branches traced by marching, each branch returned as a polyline with
//! the parameters of both surfaces at every point and fitted as a B-spline in space and in each
//! parameter plane.
//!
//! | file | subject |
//! |---|---|
//! | `system.rs` | the equations (two surfaces, or a surface and a plane), their tangent and Newton's method |
//! | `seeds.rs` | the subdivision: boxes, normal cones, starting points on the sides of sub-patches |
//! | `march.rs` | marching along a branch: predictor, corrector, step control, stops |
//! | `contacts.rs` | tangent contacts: single points and lines of contact, grouped and ordered |
//! | `fit.rs` | the fitted curves of a branch: a cubic Hermite spline through its points and tangents |
//! | `mod.rs` | [`QuerySurface::intersect_surface`], [`QuerySurface::intersect_plane`], the branches' kinds and fitted curves |

mod contacts;
mod fit;
mod march;
mod seeds;
mod system;

use super::super::pieces::{check_tolerance, dist};
use super::super::project::check_query;
use super::super::surface::QuerySurface;
use super::refine::order_from_growth;
use super::Contact;
use crate::error::readable;
use crate::error::{Error, Result};
use crate::Arg;
use crate::BSplineCurve;
use march::{March, Stop, Traced, SIN_STOP};
use rayon::prelude::*;
use seeds::Found;
use system::{newton, norm, surface_jet, PlaneSection, TwoSurfaces, K};

/// Tangent points closer than this fraction of the scale are one contact (and chained into a
/// line of contact when they spread further).
const TANGENT_MERGE: f64 = 1.0 / 64.0;
/// The points of a line of contact are kept at least this fraction of the scale apart (the
/// subdivision's finest sub-patches are `1/512` of it across).
const LINE_SPACING: f64 = 1.0 / 512.0;

/// One branch of the intersection of two surfaces (or of a plane section).
#[derive(Debug, Clone, PartialEq)]
pub struct IntersectionBranch {
    /// [`Contact::Crossing`] for a branch along which the surfaces cross,
    /// [`Contact::Tangent`] for a point (or line) where they touch, with normals parallel,
    /// [`Contact::Overlap`] for a region where they coincide.
    pub kind: Contact,
    /// Whether the branch is a closed curve in space (its ends within the tolerance; the
    /// parameter curves may still jump across a seam of a closed surface).
    pub closed: bool,
    /// The points, in order along the branch (for an overlap: the middles of the coinciding
    /// cells of the subdivision, in no order).
    pub points: Vec<[f64; 3]>,
    /// `(u, v)` on the first surface at every point.
    pub uv_a: Vec<[f64; 2]>,
    /// `(u, v)` on the second surface at every point (empty for a plane section).
    pub uv_b: Vec<[f64; 2]>,
    /// The branch fitted in space (a crossing branch of at least two points): within
    /// [`IntersectionBranch::tolerance`] of every point, at the same parameters as the
    /// parameter curves.
    pub curve: Option<BSplineCurve>,
    /// The branch in the first surface's parameter plane (same knots as `curve`): `S₁` of it is
    /// within the tolerance of every point, to first order.
    pub curve_uv_a: Option<BSplineCurve>,
    /// The branch in the second surface's parameter plane (none for a plane section).
    pub curve_uv_b: Option<BSplineCurve>,
    /// The tolerance of the answer: every point is within a tenth of it of both surfaces (the
    /// marched points are corrected to a millionth of it, the points filled between them lie on
    /// cubics through corrected points whose measured error is below a tenth), consecutive
    /// points are joined by chords within it of the branch, and the fitted curves are within it
    /// of the points.
    pub tolerance: f64,
}

impl IntersectionBranch {
    /// Length of the polyline of the points (0 for a point or an overlap).
    #[must_use]
    pub fn length(&self) -> f64 {
        if self.kind == Contact::Overlap {
            return 0.0;
        }
        self.points.windows(2).map(|w| dist(&w[0], &w[1])).sum()
    }
}

impl QuerySurface {
    /// The intersection of two 3-D surfaces within `tolerance` (an absolute distance): every
    /// branch where they cross, every point (or line) where they touch and every region where
    /// they coincide (`docs/theory/queries.md#surface-surface-intersection`).
    ///
    /// 1. **Starting points**: pairs of sub-patches are subdivided (de Casteljau, the larger
    ///    one) while their boxes overlap within the tolerance, until their normal cones are
    ///    disjoint (no closed loop inside: Sederberg and Meyers, *CAGD* 5, 1988) and both are
    ///    at most 1/8 of the scale across, or until they are 1/512 of it; then Newton's method
    ///    finds the points where the intersection crosses the sides of either sub-patch (one
    ///    unknown held) and, in a pair whose cones are not disjoint, one from the middles;
    ///    each solve kept near its pair.
    /// 2. **Marching** from each starting point not already on a branch, both ways along
    ///    `n₁ × n₂`: a predictor step, a Newton corrector on `S₁ = S₂` and the plane
    ///    orthogonal to the step, the step set by the error of the cubic Hermite interpolant of
    ///    its ends (measured at its corrected middle and its halves' middles), the points in
    ///    between filled from the cubics of the corrected points so that every chord deviates at
    ///    most `tolerance` from the branch (turning of the tangent θ over a chord c: `cθ/8`),
    ///    stopping at a side of either parameter domain, where the branch closes, or where the
    ///    normals become parallel (Barnhill and Kersey, *CAGD* 7, 1990; Patrikalakis and
    ///    Maekawa, *Shape Interrogation*, §5.8).
    /// 3. Points where the normals are parallel (sine below `10⁻⁴`) are **tangent** answers
    ///    (those within 1/64 of the scale merged, chained into a line of contact when they
    ///    spread); sub-patches that coincide within the tolerance are an **overlap**.
    /// 4. Each crossing branch is fitted as a C¹ cubic Hermite spline through a subset of its
    ///    points with the marching's tangents, in the seven coordinates
    ///    `(x, y, z, k₁u₁, k₁v₁, k₂u₂, k₂v₂)` (`kᵢ` the largest `|S_u| + |S_v|` on the branch),
    ///    the subset chosen so that the spline is within the tolerance of every point at its
    ///    arc-length parameter, and split into the curve in space and the two parameter curves.
    ///
    /// ```
    /// use lekalo::query::Contact;
    /// use lekalo::{surface::Placement, BSplineSurface, NurbsSurface};
    /// use std::f64::consts::{FRAC_PI_2, TAU};
    /// // the unit sphere and the plane z = 0.5 (as a surface): a circle of radius √0.75
    /// let f = Placement::new([0.0; 3], None, None)?;
    /// let sphere = NurbsSurface::sphere(&f, 1.0, (0.0, TAU), (-FRAC_PI_2, FRAC_PI_2))?;
    /// let g = Placement::new([0.0, 0.0, 0.5], None, None)?;
    /// let plane = BSplineSurface::plane_patch(&g, (-2.0, 2.0), (-2.0, 2.0))?;
    /// let (a, b) = (lekalo::QuerySurface::from_nurbs(&sphere)?, lekalo::QuerySurface::from_bspline(&plane)?);
    /// let branches = a.intersect_surface(&b, 1e-6)?;
    /// assert_eq!(branches.len(), 1);
    /// assert_eq!(branches[0].kind, Contact::Crossing);
    /// assert!(branches[0].closed);
    /// for p in &branches[0].points {
    ///     assert!((p[0].hypot(p[1]) - 0.75_f64.sqrt()).abs() < 1e-9 && (p[2] - 0.5).abs() < 1e-9);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless both surfaces are 3-D; [`Error::InvalidArgument`] for a
    /// tolerance that is not positive and finite, below `10⁻¹²` of the scale or above `10⁻²` of
    /// it;
    /// [`Error::TooLarge`] past `2²⁰` sub-patch pairs or points of a branch; errors of the fit.
    pub fn intersect_surface(
        &self,
        other: &QuerySurface,
        tolerance: f64,
    ) -> Result<Vec<IntersectionBranch>> {
        for s in [self, other] {
            if s.dim != 3 {
                return Err(Error::Dimension {
                    what: "surfaces to intersect".into(),
                    expected: 3,
                    got: s.dim,
                });
            }
        }
        let scale = self.scale.max(other.scale);
        check_section_tolerance(tolerance, scale)?;
        let sys = TwoSurfaces::new(self, other);
        let march = March {
            sys: &sys,
            tol: tolerance,
            scale,
        };
        let found = seeds::surface_seeds(self, other, &sys, tolerance, scale, march.eps())?;
        let probe = |x: &[f64; K], p: &[f64; 3]| seeds::distance_to(other, p, x[2], x[3]).0;
        assemble(&march, found, &probe, |x| [x[2], x[3]], true)
    }

    /// The section of a 3-D surface by the plane through `origin` with normal `normal`, within
    /// `tolerance`: the contour `f(u, v) = n·(S(u, v) − o) = 0`, found as
    /// [`QuerySurface::intersect_surface`] describes with the plane's exact tests: a patch cell
    /// whose coefficients of `f` (those of the control points, `n·(P^w − w o)`) have one sign is
    /// dropped; one whose `u` or `v` differences have one sign holds no closed contour, and the
    /// roots of `f` on its sides ([`crate::query`]'s Bernstein root finder) start the marching;
    /// a cell whose coefficients vanish lies in the plane (an overlap). Branches carry `(u, v)`
    /// only.
    ///
    /// ```
    /// use lekalo::{surface::Placement, NurbsSurface};
    /// use std::f64::consts::TAU;
    /// // a cylinder of radius 1 about z cut by the plane z = x: an ellipse
    /// let f = Placement::new([0.0; 3], None, None)?;
    /// let cyl = lekalo::QuerySurface::from_nurbs(&NurbsSurface::cylinder(&f, 1.0, (0.0, TAU), (-2.0, 2.0))?)?;
    /// let b = cyl.intersect_plane(&[0.0; 3], &[1.0, 0.0, -1.0], 1e-6)?;
    /// assert_eq!(b.len(), 1);
    /// assert!(b[0].closed);
    /// for p in &b[0].points {
    ///     assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-9 && (p[2] - p[0]).abs() < 1e-9);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`QuerySurface::intersect_surface`]; [`Error::Dimension`] / [`Error::NonFinite`] for
    /// bad plane data; [`Error::InvalidArgument`] for a zero normal.
    pub fn intersect_plane(
        &self,
        origin: &[f64],
        normal: &[f64],
        tolerance: f64,
    ) -> Result<Vec<IntersectionBranch>> {
        if self.dim != 3 {
            return Err(Error::Dimension {
                what: "surface of a plane section".into(),
                expected: 3,
                got: self.dim,
            });
        }
        check_query("plane origin", origin, 3)?;
        check_query("plane normal", normal, 3)?;
        let nn = norm(normal);
        if !(nn > 0.0) {
            return Err(Error::InvalidArgument {
                what: "plane normal".into(),
                reason: "it is the zero vector".into(),
            });
        }
        check_section_tolerance(tolerance, self.scale)?;
        let n = [normal[0] / nn, normal[1] / nn, normal[2] / nn];
        let o = [origin[0], origin[1], origin[2]];
        let sys = PlaneSection::new(self, o, n);
        let march = March {
            sys: &sys,
            tol: tolerance,
            scale: self.scale,
        };
        let found = seeds::plane_seeds(self, &sys, &o, &n, march.eps(), tolerance)?;
        let probe =
            |_: &[f64; K], p: &[f64; 3]| (0..3).map(|c| n[c] * (p[c] - o[c])).sum::<f64>().abs();
        assemble(&march, found, &probe, |_| [0.0; 2], false)
    }
}

fn check_section_tolerance(tolerance: f64, scale: f64) -> Result<()> {
    check_tolerance(Arg::Tolerance, tolerance)?;
    if tolerance < 1e-12 * scale {
        return Err(Error::InvalidArgument {
            what: Arg::Tolerance.into(),
            reason: format!(
                "{tolerance} is below 1e-12 of the surfaces' size {scale}: rounding, not the \
                 geometry, would decide it; give a larger tolerance",
                tolerance = readable(&tolerance),
                scale = readable(&scale)
            ),
        });
    }
    if tolerance > MAX_TOLERANCE_OF_SCALE * scale {
        return Err(Error::InvalidArgument {
            what: Arg::Tolerance.into(),
            reason: format!(
                "{tolerance} is above 1/100 of the surfaces' size {scale}: points that far off \
                 the surfaces cannot tell one branch from another (an open crossing could close \
                 into a loop); give at most {:e}",
                MAX_TOLERANCE_OF_SCALE * scale,
                tolerance = readable(&tolerance),
                scale = readable(&scale)
            ),
        });
    }
    Ok(())
}

/// The largest tolerance of a section, as a fraction of the surfaces' size: a tolerance
/// comparable to the distances at which branches are told apart (tangent points within 1/64 of
/// the size are one contact) would let the marching and the chaining join what is separate.
const MAX_TOLERANCE_OF_SCALE: f64 = 1e-2;

/// Most segments of a branch listed as one run in [`SegmentGrid`].
const RUN: usize = 64;

/// The segments of the traced branches in a uniform grid of cubes, listed by runs: consecutive
/// segments of a branch whose box spans at most a cube (and at most [`RUN`] of them), each run
/// listed in every cube its box widened by `cover` meets, so that whether a point lies within
/// `cover` of a branch is decided by the runs of its own cube (the search of [`assemble`] for
/// starting points not yet on a branch, in time independent of the branches' length; listing
/// runs rather than single segments keeps the grid's cost a few entries per cube crossed).
struct SegmentGrid {
    cover: f64,
    cell: f64,
    /// Branch, first and one past the last segment, box (minima then maxima) of each run.
    runs: Vec<(usize, usize, usize, [f64; 6])>,
    cells: std::collections::HashMap<[i64; 3], Vec<usize>>,
}

impl SegmentGrid {
    /// A grid of cubes of side `cell` (at least `4 cover`; the longest step of the marching
    /// keeps a segment within a few cubes).
    fn new(cover: f64, cell: f64) -> Self {
        SegmentGrid {
            cover,
            cell: cell.max(4.0 * cover),
            runs: Vec::new(),
            cells: std::collections::HashMap::new(),
        }
    }

    // `as` saturates: a coordinate beyond 2^63 cells (not met: coordinates are finite and the
    // cell a fraction of the scale) shares the last cell, which only costs comparisons
    #[allow(clippy::cast_possible_truncation)]
    fn key(&self, x: f64) -> i64 {
        (x / self.cell).floor() as i64
    }

    /// Lists the segments (or the single point) of branch `b`, by runs.
    fn insert(&mut self, b: usize, ps: &[[f64; 3]]) {
        let segs = ps.len().saturating_sub(1).max(1);
        let mut s0 = 0;
        while s0 < segs {
            // the run: segments s0.. while their box spans at most a cube
            let (mut lo, mut hi) = (ps[s0], ps[s0]);
            let mut s1 = s0;
            while s1 < segs && s1 - s0 < RUN {
                let q = &ps[(s1 + 1).min(ps.len() - 1)];
                let (l, h) = (
                    [lo[0].min(q[0]), lo[1].min(q[1]), lo[2].min(q[2])],
                    [hi[0].max(q[0]), hi[1].max(q[1]), hi[2].max(q[2])],
                );
                if s1 > s0
                    && (h[0] - l[0] > self.cell
                        || h[1] - l[1] > self.cell
                        || h[2] - l[2] > self.cell)
                {
                    break;
                }
                (lo, hi) = (l, h);
                s1 += 1;
            }
            let bx = [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]];
            let run = self.runs.len();
            self.runs.push((b, s0, s1, bx));
            let lo: [i64; 3] = std::array::from_fn(|c| self.key(bx[c] - self.cover));
            let hi: [i64; 3] = std::array::from_fn(|c| self.key(bx[3 + c] + self.cover));
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    for k in lo[2]..=hi[2] {
                        self.cells.entry([i, j, k]).or_default().push(run);
                    }
                }
            }
            s0 = s1;
        }
    }

    /// Whether `p` lies within `cover` of a listed segment of `traced`.
    fn covers(&self, p: &[f64; 3], traced: &[Traced]) -> bool {
        let key = [self.key(p[0]), self.key(p[1]), self.key(p[2])];
        self.cells.get(&key).is_some_and(|list| {
            list.iter().any(|&r| {
                let (b, s0, s1, bx) = &self.runs[r];
                if (0..3).any(|c| p[c] < bx[c] - self.cover || p[c] > bx[3 + c] + self.cover) {
                    return false;
                }
                let ps = &traced[*b].ps;
                let n = ps.len();
                (*s0..*s1)
                    .any(|s| segment_distance3(p, &ps[s], &ps[(s + 1).min(n - 1)]) <= self.cover)
            })
        })
    }
}

/// Distance from `x` to the segment `[a, b]` in space.
pub(super) fn segment_distance3(x: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ax = [x[0] - a[0], x[1] - a[1], x[2] - a[2]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if l2 > 0.0 {
        ((ax[0] * ab[0] + ax[1] * ab[1] + ax[2] * ab[2]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [ax[0] - t * ab[0], ax[1] - t * ab[1], ax[2] - t * ab[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// Traces the branches from the starting points and builds the answers: crossing branches
/// (fitted), tangent points and lines, the overlap. `probe(x, p)` is the distance of a point
/// `p` of the first surface (near the section point `x`) to the second object; `uv_b` the
/// second surface's parameters of `x`; `two` whether there is a second surface.
fn assemble(
    march: &March<'_>,
    found: Found,
    probe: &dyn Fn(&[f64; K], &[f64; 3]) -> f64,
    uv_b: impl Fn(&[f64; K]) -> [f64; 2] + Sync,
    two: bool,
) -> Result<Vec<IntersectionBranch>> {
    let sys = march.sys;
    let (tol, scale) = (march.tol, march.scale);
    let cover = 4.0 * tol + 1e-9 * scale;
    let mut traced: Vec<Traced> = Vec::new();
    // tangent candidates: (x, p, sine)
    let mut touch: Vec<contacts::Touch> = Vec::new();
    let mut grid = SegmentGrid::new(cover, march::MAX_STEP * scale);
    let k = sys.k();
    for x in &found.seeds {
        let Some(jet) = sys.jet(x) else { continue };
        if jet.sin >= SIN_STOP && grid.covers(&jet.p, &traced) {
            continue;
        }
        // a starting point solved to a looser residual is corrected to the marching's
        let (x, jet) = if jet.gap(k) > march.eps() {
            match newton(sys, *x, None, None, march.eps()) {
                Some(r) => r,
                None => continue,
            }
        } else {
            (*x, jet)
        };
        if jet.sin < SIN_STOP {
            touch.push((x, jet.p, jet.sin));
            continue;
        }
        if grid.covers(&jet.p, &traced) {
            continue;
        }
        let t = march.branch(x, &jet)?;
        grid.insert(traced.len(), &t.ps);
        for (end, stop) in [(0, t.stops[0]), (t.xs.len() - 1, t.stops[1])] {
            if stop == Stop::Tangent {
                let s = sys.jet(&t.xs[end]).map_or(0.0, |j| j.sin);
                touch.push((t.xs[end], t.ps[end], s));
            }
        }
        traced.push(t);
    }
    // the branches' fits are independent: in parallel
    let fitted: Vec<Result<Option<IntersectionBranch>>> = traced
        .into_par_iter()
        .map(|t| {
            let n = t.ps.len();
            if n < 2 {
                return Ok(None);
            }
            let closed = t.stops[0] == Stop::Closed || dist(&t.ps[0], &t.ps[n - 1]) <= tol;
            let uv_a: Vec<[f64; 2]> = t.xs.iter().map(|x| [x[0], x[1]]).collect();
            let uvb: Vec<[f64; 2]> = if two {
                t.xs.iter().map(&uv_b).collect()
            } else {
                Vec::new()
            };
            let fitted = fit::fit_branch(&t, tol, two)?;
            let (curve, ca, cb) = match fitted {
                Some((c, a, b)) => (Some(c), Some(a), b),
                None => (None, None, None),
            };
            Ok(Some(IntersectionBranch {
                kind: Contact::Crossing,
                closed,
                points: t.ps,
                uv_a,
                uv_b: uvb,
                curve,
                curve_uv_a: ca,
                curve_uv_b: cb,
                tolerance: tol,
            }))
        })
        .collect();
    let mut out = Vec::new();
    for b in fitted {
        out.extend(b?);
    }
    // tangent points: thinned, grouped into contacts and lines of contact
    for g in contacts::group(touch, TANGENT_MERGE * scale, LINE_SPACING * scale) {
        let chosen = &g.members;
        let order = chosen
            .first()
            .map_or(1, |m| contact_order(march, probe, &m.0));
        out.push(IntersectionBranch {
            kind: Contact::Tangent { order },
            closed: g.closed,
            points: chosen.iter().map(|m| m.1).collect(),
            uv_a: chosen.iter().map(|m| [m.0[0], m.0[1]]).collect(),
            uv_b: if two {
                chosen.iter().map(|m| uv_b(&m.0)).collect()
            } else {
                Vec::new()
            },
            curve: None,
            curve_uv_a: None,
            curve_uv_b: None,
            tolerance: tol,
        });
    }
    if !found.overlaps.is_empty() {
        let mut points = Vec::new();
        let mut uv_a = Vec::new();
        let mut uvb = Vec::new();
        for x in &found.overlaps {
            if let Some([p, _, _]) = surface_jet(sys.first(), x[0], x[1]) {
                points.push(p);
                uv_a.push([x[0], x[1]]);
                if two {
                    uvb.push(uv_b(x));
                }
            }
        }
        out.push(IntersectionBranch {
            kind: Contact::Overlap,
            closed: false,
            points,
            uv_a,
            uv_b: uvb,
            curve: None,
            curve_uv_a: None,
            curve_uv_b: None,
            tolerance: tol,
        });
    }
    Ok(out)
}

/// The order of a tangential contact at `x`: the growth of the distance from the first
/// surface's point to the second object at parameter offsets `h` and `2h` (`h` a thousandth of
/// the first surface's domain, along `u` and along `v`, on the side with room),
/// `gap(2h)/gap(h) ≈ 2^(order + 1)`; the lower of the two directions.
fn contact_order(
    march: &March<'_>,
    probe: &dyn Fn(&[f64; K], &[f64; 3]) -> f64,
    x: &[f64; K],
) -> u32 {
    let b = march.sys.bounds();
    let s = march.sys.first();
    (0..2)
        .map(|i| {
            let h = 1e-3 * (b[i].1 - b[i].0);
            let sign = if x[i] + 2.0 * h <= b[i].1 { 1.0 } else { -1.0 };
            let gap = |m: f64| {
                let mut y = *x;
                y[i] += m * sign * h;
                surface_jet(s, y[0], y[1]).map_or(f64::INFINITY, |[p, _, _]| probe(&y, &p))
            };
            order_from_growth(gap(1.0), gap(2.0))
        })
        .min()
        .unwrap_or(1)
}

#[cfg(test)]
mod known_answers;
#[cfg(test)]
mod tests;
