//! Validity of a face's trims in its surface's `(u, v)` (`docs/theory/topology.md`, "Faces
//! with bad trims"): the checks a mesher needs before it can trust the loops to bound one
//! region of the domain, after Open CASCADE's `BRepCheck_Face` and `BRepCheck_Wire`
//! (`BRepCheck_SelfIntersectingWire`, `BRepCheck_IntersectingWires`,
//! `BRepCheck_InvalidImbricationOfWires`, `BRepCheck_EmptyWire`, and the pcurve's range checked
//! against the surface's):
//!
//! * every pcurve lies in the surface's domain in each direction that does not close, within
//!   [`LOOP_CLOSURE_RTOL`] of the domain's width (a pcurve past it by less is clipped to it:
//!   the CAD system's rounding); in a closed direction a pcurve may leave the domain by whole
//!   periods (a loop unwrapped across the seam);
//! * an edge whose pcurve has no length (every sample within the tolerance of its start) is
//!   dropped; an inner loop of no length (a hole of one point) is dropped; an outer loop of no
//!   length bounds nothing and is refused;
//! * no loop crosses itself or another loop (segments of the loops' polygons crossing
//!   properly, found by a sweep over `u`; touching is allowed, and so is a crossing of two
//!   consecutive edges within the tolerance of their common vertex);
//! * every hole lies inside the outer loop, and no hole inside another hole (winding numbers,
//!   Hormann & Agathos 2001).
//!
//! Loops that do not close in `(u, v)` (a band or a cap going round a closed surface, cut along
//! its seam by the mesher) are checked for their domain and length only.

use super::face::{Edge, Face, Loop, LOOP_CLOSURE_RTOL};
use super::inside::{winding_number, TRIM_SAMPLES_PER_SPAN};
use super::pcurve::{SurfaceClosure, PCURVE_SAMPLING_RTOL};
use crate::error::readable;
use crate::{Error, Result};

/// Most points of the polygons through a face's trims that the checks sample.
const MAX_CHECK_POINTS: usize = 1 << 22;
/// Most pairs of trim segments tested for a crossing in one face (the sweep over `u` tests
/// the pairs whose `u` ranges overlap): a bound on the time of a hostile trim whose segments
/// all span the whole domain.
const MAX_CROSSING_TESTS: usize = 1 << 28;

/// What is wrong with a loop of a face ([`Error::InvalidTrim`]), each with what to do.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum TrimDefect {
    /// An edge's pcurve leaves the surface's domain by more than the tolerance.
    OutsideDomain {
        /// The edge, counted from 0 along the loop.
        edge: usize,
        /// A point of the pcurve outside the domain.
        at: [f64; 2],
        /// The parameter it is past: 0 for `u`, 1 for `v`.
        direction: usize,
        /// The side of the domain it is past (`u₀` or `u₁`, `v₀` or `v₁`).
        bound: f64,
    },
    /// The outer loop has no length in `(u, v)`: it bounds no region.
    ZeroLength,
    /// The loop crosses itself between two of its edges (the same edge twice for an edge that
    /// crosses itself).
    SelfCrossing {
        /// The two edges that cross, counted from 0 along the loop.
        edges: [usize; 2],
        /// About where, in `(u, v)`.
        at: [f64; 2],
    },
    /// The loop crosses another loop of the face.
    CrossesLoop {
        /// The other loop: 0 for the outer loop, `i` for the `i`-th inner loop.
        other: usize,
        /// About where, in `(u, v)`.
        at: [f64; 2],
    },
    /// A hole (inner loop) lying outside the outer loop.
    OutsideOuter,
    /// A hole lying inside another hole.
    InsideHole {
        /// The hole around it: `i` for the `i`-th inner loop.
        other: usize,
    },
}

/// A loop's name in messages: the outer loop is loop 0, the `i`-th inner loop loop `i`.
pub(crate) fn loop_name(i: usize) -> String {
    if i == 0 {
        "the outer loop".into()
    } else {
        format!("inner loop {i}")
    }
}

impl std::fmt::Display for TrimDefect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let pt = |p: &[f64; 2]| format!("({}, {})", readable(&p[0]), readable(&p[1]));
        match self {
            TrimDefect::OutsideDomain {
                edge,
                at,
                direction,
                bound,
            } => write!(
                f,
                "leaves the surface's domain: edge {edge}'s curve in (u, v) reaches {}, past its side {} = {}; its pcurve is not in this surface's parameters (export the face with pcurves on its surface, or leave the pcurves out and lekalo projects the edges onto the surface)",
                pt(at),
                if *direction == 0 { "u" } else { "v" },
                readable(bound)
            ),
            TrimDefect::ZeroLength => write!(
                f,
                "has no length in (u, v) (a loop of one point): it bounds no region; remove the face or give it its boundary"
            ),
            TrimDefect::SelfCrossing { edges, at } => {
                let which = if edges[0] == edges[1] {
                    format!("edge {} crosses itself", edges[0])
                } else {
                    format!("edges {} and {} cross", edges[0], edges[1])
                };
                write!(
                    f,
                    "crosses itself: {which} near (u, v) = {}; the trim does not bound one region (correct the loop in the CAD system)",
                    pt(at)
                )
            }
            TrimDefect::CrossesLoop { other, at } => write!(
                f,
                "crosses {} near (u, v) = {}; loops of a face must not cross (correct the loops in the CAD system)",
                loop_name(*other),
                pt(at)
            ),
            TrimDefect::OutsideOuter => write!(
                f,
                "is a hole outside the outer loop; a hole must lie inside it (make it a face of its own or remove it)"
            ),
            TrimDefect::InsideHole { other } => write!(
                f,
                "is a hole inside {}, which leaves the region between them ambiguous (remove one, or make the inner part a face of its own)",
                loop_name(*other)
            ),
        }
    }
}

/// A repair of a face's trims made by [`Face::checked_trims`], unambiguous and within the
/// tolerance.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum TrimRepair {
    /// Pcurves of a loop past the domain by at most the tolerance, clipped to it.
    Clipped {
        /// The loop: 0 for the outer loop, `i` for the `i`-th inner loop.
        lp: usize,
        /// The largest distance past the domain, in the parameter.
        by: f64,
    },
    /// An edge of no length in `(u, v)`, dropped from its loop.
    DroppedEdge {
        /// The loop: 0 for the outer loop, `i` for the `i`-th inner loop.
        lp: usize,
        /// The edge, counted from 0 along the loop as given.
        edge: usize,
    },
    /// A hole of no length in `(u, v)`, dropped.
    DroppedLoop {
        /// The `i`-th inner loop.
        lp: usize,
    },
}

impl std::fmt::Display for TrimRepair {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TrimRepair::Clipped { lp, by } => write!(
                f,
                "{} leaves the surface's domain by {} (within the tolerance): clipped to it",
                loop_name(*lp),
                readable(by)
            ),
            TrimRepair::DroppedEdge { lp, edge } => write!(
                f,
                "edge {edge} of {} has no length: dropped",
                loop_name(*lp)
            ),
            TrimRepair::DroppedLoop { lp } => {
                write!(
                    f,
                    "{} has no length (a hole of one point): dropped",
                    loop_name(*lp)
                )
            }
        }
    }
}

/// The parameter tolerance in each direction: [`LOOP_CLOSURE_RTOL`] of the domain's width.
fn uv_tolerance(face: &Face) -> [f64; 2] {
    let ((u0, u1), (v0, v1)) = face.surface().domain();
    [LOOP_CLOSURE_RTOL * (u1 - u0), LOOP_CLOSURE_RTOL * (v1 - v0)]
}

/// Points of an edge's pcurve along it: the control points of a degree-1 pcurve (its
/// polygon, exact), else [`TRIM_SAMPLES_PER_SPAN`] per knot span (at least 16).
fn pcurve_points(e: &Edge, budget: &mut usize) -> Result<Option<Vec<[f64; 2]>>> {
    let Some(p) = e.pcurve() else { return Ok(None) };
    let pts = if p.degree() == 1 && !p.is_rational() {
        let cp = p.control_points();
        charge(budget, cp.len())?;
        cp.as_slice()
            .chunks_exact(2)
            .map(|c| [c[0], c[1]])
            .collect()
    } else {
        let spans = p.knots().distinct().len().saturating_sub(1).max(1);
        let n = spans.saturating_mul(TRIM_SAMPLES_PER_SPAN).max(16);
        charge(budget, n)?;
        let s = p.sample(n)?;
        s.as_slice().chunks_exact(2).map(|c| [c[0], c[1]]).collect()
    };
    Ok(Some(pts))
}

fn charge(budget: &mut usize, n: usize) -> Result<()> {
    if n > *budget {
        return Err(Error::TooLarge {
            what: "points of a face's trims to check".into(),
            size: n,
            max: MAX_CHECK_POINTS,
        });
    }
    *budget -= n;
    Ok(())
}

/// True when every point is within `tol` of the first, in each direction.
fn no_length(pts: &[[f64; 2]], tol: [f64; 2]) -> bool {
    pts.iter()
        .all(|p| (0..2).all(|d| (p[d] - pts[0][d]).abs() <= tol[d]))
}

/// One loop's points, edge by edge, with which edges were kept.
struct LoopPoints {
    /// The original index of each edge kept, with its points.
    edges: Vec<(usize, Vec<[f64; 2]>)>,
    /// True when the loop closes in `(u, v)` within the tolerance.
    closed: bool,
}

impl Face {
    /// The face's trims checked in its surface's `(u, v)` and repaired where the repair is
    /// unambiguous (module docs of `topology/trims.rs`; `docs/theory/topology.md`, "Faces with
    /// bad trims"): the repaired face when an edge or a hole was dropped (`None` when the face
    /// is meshed as it is: clipping to the domain is the mesher's), with the repairs made. A
    /// face with an edge without pcurve is not checked (the mesher names the edge).
    ///
    /// ```
    /// use lekalo::topology::{Edge, Face, Loop, TrimDefect, LOOP_CLOSURE_RTOL};
    /// use lekalo::{BSplineCurve, BSplineSurface, Curve, Error, Points, Surface};
    /// let plane = Surface::from(BSplineSurface::new(1, 1, vec![0.0, 0.0, 1.0, 1.0],
    ///     vec![0.0, 0.0, 1.0, 1.0], Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0],
    ///     [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]])?, (2, 2))?);
    /// // a bow tie: the loop crosses itself at (0.5, 0.5)
    /// let c = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
    /// let edges = (0..4).map(|k| {
    ///     let (a, b) = (c[k], c[(k + 1) % 4]);
    ///     let d = [b[0] - a[0], b[1] - a[1]];
    ///     Edge::new(
    ///         Curve::from(BSplineCurve::line_segment(&[a[0], a[1], 0.0], &[d[0], d[1], 0.0], 0.0, 1.0)?),
    ///         Some(Curve::from(BSplineCurve::line_segment(&a, &d, 0.0, 1.0)?)),
    ///     )
    /// }).collect::<lekalo::Result<Vec<_>>>()?;
    /// let face = Face::new(plane, Loop::new(edges)?, vec![], true, LOOP_CLOSURE_RTOL)?;
    /// let e = face.checked_trims().unwrap_err();
    /// assert!(matches!(e, Error::InvalidTrim { lp: 0, defect: TrimDefect::SelfCrossing { edges: [0, 2], .. } }));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTrim`] naming the loop and the [`TrimDefect`]; [`Error::TooLarge`] for
    /// trims of more than 2^22 points to check or 2^28 pairs of segments to test.
    pub fn checked_trims(&self) -> Result<(Option<Face>, Vec<TrimRepair>)> {
        if !self.has_pcurves() {
            return Ok((None, Vec::new()));
        }
        let domain = self.surface().domain();
        let dom = [domain.0, domain.1];
        let tol = uv_tolerance(self);
        // closed as the mesher finds it at its coarsest (`plan_face`)
        let closure = SurfaceClosure::of(self.surface(), PCURVE_SAMPLING_RTOL * self.model_size())?;
        let mut budget = MAX_CHECK_POINTS;
        let mut repairs = Vec::new();
        let mut loops: Vec<(usize, LoopPoints)> = Vec::new();
        for (li, lp) in self.loops().enumerate() {
            let mut edges = Vec::new();
            let mut past = 0.0_f64;
            for (ei, e) in lp.edges().iter().enumerate() {
                let Some(pts) = pcurve_points(e, &mut budget)? else {
                    return Ok((None, Vec::new()));
                };
                for p in &pts {
                    for d in 0..2 {
                        if closure.period[d].is_some() {
                            continue;
                        }
                        let (a, b) = dom[d];
                        let by = (a - p[d]).max(p[d] - b);
                        // NaN cannot come from a validated curve; refused all the same
                        if by > tol[d] || by.is_nan() {
                            return Err(Error::InvalidTrim {
                                lp: li,
                                defect: TrimDefect::OutsideDomain {
                                    edge: ei,
                                    at: *p,
                                    direction: d,
                                    bound: if p[d] < a { a } else { b },
                                },
                            });
                        }
                        past = past.max(by);
                    }
                }
                edges.push((ei, pts));
            }
            if past > 0.0 {
                repairs.push(TrimRepair::Clipped { lp: li, by: past });
            }
            let all: Vec<[f64; 2]> = edges.iter().flat_map(|(_, p)| p.iter().copied()).collect();
            if no_length(&all, tol) {
                if li == 0 {
                    return Err(Error::InvalidTrim {
                        lp: 0,
                        defect: TrimDefect::ZeroLength,
                    });
                }
                repairs.push(TrimRepair::DroppedLoop { lp: li });
                continue;
            }
            let before = edges.len();
            edges.retain(|(ei, p)| {
                let keep = !no_length(p, tol);
                if !keep {
                    repairs.push(TrimRepair::DroppedEdge { lp: li, edge: *ei });
                }
                keep
            });
            debug_assert!(
                !edges.is_empty() && edges.len() <= before,
                "a loop with length keeps an edge"
            );
            let gap = lp.largest_gap(true)?.map_or(0.0, |(g, _)| g);
            let closed = gap <= tol[0].hypot(tol[1]).max(f64::MIN_POSITIVE);
            loops.push((li, LoopPoints { edges, closed }));
        }
        check_crossings(&loops, tol)?;
        check_nesting(&loops, &closure)?;
        if repairs
            .iter()
            .all(|r| matches!(r, TrimRepair::Clipped { .. }))
        {
            // clipping is the mesher's: it takes the surface at the nearest point of the domain
            // and clips the loops' points there
            return Ok((None, repairs));
        }
        let keep_loop = |li: usize, lp: &Loop| -> Option<Loop> {
            let (_, pts) = loops.iter().find(|(i, _)| *i == li)?;
            let edges = pts
                .edges
                .iter()
                .map(|(ei, _)| lp.edges()[*ei].clone())
                .collect();
            Loop::new(edges).ok()
        };
        let outer = keep_loop(0, self.outer()).unwrap_or_else(|| self.outer().clone());
        let inner = self
            .inner()
            .iter()
            .enumerate()
            .filter_map(|(k, lp)| keep_loop(k + 1, lp))
            .collect();
        Ok((
            Some(Face::from_parts(
                self.surface().clone(),
                outer,
                inner,
                self.same_sense(),
            )),
            repairs,
        ))
    }
}

/// A segment of a loop's polygon: its ends, its loop, its edge, and the edge's place among the
/// loop's edges kept.
#[derive(Clone, Copy)]
struct Segment {
    a: [f64; 2],
    b: [f64; 2],
    lp: usize,
    edge: usize,
    pos: usize,
}

/// `(b − a) × (c − a)`: positive when `c` is left of the line from `a` to `b`.
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Where two segments cross properly (each one's ends strictly on either side of the other's
/// line, by more than rounding), or `None` (apart, touching, or collinear).
fn proper_crossing(s: &Segment, t: &Segment) -> Option<[f64; 2]> {
    let (d1, d2) = (orient(s.a, s.b, t.a), orient(s.a, s.b, t.b));
    let (d3, d4) = (orient(t.a, t.b, s.a), orient(t.a, t.b, s.b));
    // rounding of the cross products: a few ulps of the largest term
    let size = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        let m = p
            .iter()
            .chain(&q)
            .chain(&r)
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        64.0 * f64::EPSILON * m * m
    };
    let e1 = size(s.a, s.b, t.a).max(size(s.a, s.b, t.b));
    let e2 = size(t.a, t.b, s.a).max(size(t.a, t.b, s.b));
    let strictly = |x: f64, y: f64, e: f64| (x > e && y < -e) || (x < -e && y > e);
    if strictly(d1, d2, e1) && strictly(d3, d4, e2) {
        let w = d1 / (d1 - d2);
        Some([
            t.a[0] + w * (t.b[0] - t.a[0]),
            t.a[1] + w * (t.b[1] - t.a[1]),
        ])
    } else {
        None
    }
}

/// True when `at` is within `tol` (in each direction) of `p`.
fn near(at: [f64; 2], p: [f64; 2], tol: [f64; 2]) -> bool {
    (0..2).all(|d| (at[d] - p[d]).abs() <= tol[d])
}

/// True when a crossing at `at` of the edges at places `p` and `q` of loop `lp` is their touch at
/// the vertex they share: the edges follow one another along the loop (the last and the first
/// of a closed loop too) and `at` is within `tol` of where the first ends or the next starts.
/// The ends of two edges at a vertex meet within the tolerance the loop closes within, not
/// exactly (a file's sewing gap, or the projection of each edge onto the surface), so their
/// last segments may poke across each other there by that much (as `BRepCheck_Wire` ignores
/// the intersections of consecutive edges within their common vertex's tolerance).
fn vertex_touch(lp: &LoopPoints, p: usize, q: usize, at: [f64; 2], tol: [f64; 2]) -> bool {
    let n = lp.edges.len();
    // edge k ends where edge k + 1 starts
    let joint = |k: usize| -> bool {
        lp.edges[k].1.last().is_some_and(|&e| near(at, e, tol))
            || lp.edges[(k + 1) % n]
                .1
                .first()
                .is_some_and(|&s| near(at, s, tol))
    };
    let follows = |a: usize, b: usize| (a + 1) % n == b && (lp.closed || b != 0);
    (follows(p, q) && joint(p)) || (follows(q, p) && joint(q))
}

/// Refuses loops that cross themselves or each other: the segments of the closed loops'
/// polygons (and of the others', without their closing segment) swept in `u`, each tested
/// against those whose `u` range overlaps it. Consecutive edges touching at their common
/// vertex within `tol` ([`vertex_touch`]) do not cross.
fn check_crossings(loops: &[(usize, LoopPoints)], tol: [f64; 2]) -> Result<()> {
    let mut segs = Vec::new();
    for (li, lp) in loops {
        let pts: Vec<([f64; 2], usize, usize)> = lp
            .edges
            .iter()
            .enumerate()
            .flat_map(|(pos, (ei, p))| p.iter().map(move |x| (*x, *ei, pos)))
            .collect();
        let n = pts.len();
        let closing = if lp.closed { n } else { n.saturating_sub(1) };
        for k in 0..closing {
            let (a, b) = (pts[k], pts[(k + 1) % n]);
            if a.0 != b.0 {
                segs.push(Segment {
                    a: a.0,
                    b: b.0,
                    lp: *li,
                    edge: a.1,
                    pos: a.2,
                });
            }
        }
    }
    let loop_of = |li: usize| loops.iter().find(|(i, _)| *i == li).map(|(_, l)| l);
    let lo = |s: &Segment| s.a[0].min(s.b[0]);
    let hi = |s: &Segment| s.a[0].max(s.b[0]);
    segs.sort_by(|s, t| lo(s).total_cmp(&lo(t)));
    let mut active: Vec<Segment> = Vec::new();
    let mut tests = 0usize;
    for s in &segs {
        active.retain(|t| hi(t) >= lo(s));
        let (slo, shi) = (s.a[1].min(s.b[1]), s.a[1].max(s.b[1]));
        for t in &active {
            if t.a[1].max(t.b[1]) < slo || t.a[1].min(t.b[1]) > shi {
                continue;
            }
            tests += 1;
            if tests > MAX_CROSSING_TESTS {
                return Err(Error::TooLarge {
                    what: "pairs of a face's trim segments to test for crossings".into(),
                    size: tests,
                    max: MAX_CROSSING_TESTS,
                });
            }
            if let Some(at) = proper_crossing(s, t) {
                if s.lp == t.lp
                    && loop_of(s.lp).is_some_and(|l| vertex_touch(l, s.pos, t.pos, at, tol))
                {
                    continue;
                }
                let (first, second) = if (t.lp, t.edge) <= (s.lp, s.edge) {
                    (t, s)
                } else {
                    (s, t)
                };
                let defect = if first.lp == second.lp {
                    TrimDefect::SelfCrossing {
                        edges: [first.edge, second.edge],
                        at,
                    }
                } else {
                    TrimDefect::CrossesLoop {
                        other: first.lp,
                        at,
                    }
                };
                return Err(Error::InvalidTrim {
                    lp: second.lp,
                    defect,
                });
            }
        }
        active.push(*s);
    }
    Ok(())
}

/// Refuses holes outside the outer loop and holes inside holes (loops that cross were refused
/// before, so one point of a loop tells on which side of another it lies); in a closed
/// direction a hole may be a whole period from the outer loop. Loops that do not close in
/// `(u, v)` are left to the cut along the seam.
fn check_nesting(loops: &[(usize, LoopPoints)], closure: &SurfaceClosure) -> Result<()> {
    let flat = |lp: &LoopPoints| -> Vec<f64> {
        lp.edges
            .iter()
            .flat_map(|(_, p)| p.iter().flat_map(|x| *x))
            .collect()
    };
    let shifts =
        |d: usize| -> Vec<f64> { closure.period[d].map_or(vec![0.0], |p| vec![0.0, -p, p]) };
    let winds = |poly: &[f64], p: [f64; 2]| {
        shifts(0).iter().any(|du| {
            shifts(1)
                .iter()
                .any(|dv| winding_number(poly, p[0] + du, p[1] + dv) != 0)
        })
    };
    let first = |lp: &LoopPoints| lp.edges[0].1[0];
    let Some((0, outer)) = loops.first() else {
        return Ok(());
    };
    let outer_poly = outer.closed.then(|| flat(outer));
    let holes: Vec<(usize, &LoopPoints, Vec<f64>)> = loops
        .iter()
        .skip(1)
        .filter(|(_, l)| l.closed)
        .map(|(i, l)| (*i, l, flat(l)))
        .collect();
    for (i, l, _) in &holes {
        if let Some(poly) = &outer_poly {
            if !winds(poly, first(l)) {
                return Err(Error::InvalidTrim {
                    lp: *i,
                    defect: TrimDefect::OutsideOuter,
                });
            }
        }
        for (j, _, poly) in &holes {
            if j != i && winds(poly, first(l)) {
                return Err(Error::InvalidTrim {
                    lp: *i,
                    defect: TrimDefect::InsideHole { other: *j },
                });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "trims_tests.rs"]
mod tests;
