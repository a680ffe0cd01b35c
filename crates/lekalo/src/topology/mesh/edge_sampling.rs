//! Sampling of a face set's edges for the mesher (`docs/theory/topology.md`, "Meshing a
//! trimmed face"): each edge sampled once at fractions of its first use, bisected until its
//! curve is within half the tolerance of each chord (convex-hull bound, P&T §2.3, §4.2), and,
//! on every face that uses it, the surface at each pcurve midpoint within half the tolerance of
//! the chord's midpoint, the step within the face's grid spacing and its triangle bound
//! (`docs/theory/queries.md#tessellation`), and less than half a period across a seam.

use super::FacePlan;
use crate::query::MAX_MESH_VERTICES;
use crate::topology::face::Edge;
use crate::{Arg, Curve, Error, Result, What};

/// Segments per knot span of an edge's curve and pcurves before bisection.
const START_SAMPLES_PER_SPAN: usize = 1;
/// Longest step of an edge's samples in a closed direction, as a fraction of the period: a
/// loop's turns round the surface are read from its points, each step taken as less than half
/// a period.
const MAX_PERIOD_STEP: f64 = 0.4;
/// Fewest segments of a loop before bisection, shared evenly by its edges (a closed edge alone
/// gets three, a triangle in `(u, v)` with an inside): a coarser loop encloses no region.
const MIN_LOOP_SEGMENTS: usize = 3;
/// Most bisections of one segment of an edge.
const MAX_EDGE_DEPTH: u32 = 30;
/// The samples of one edge of a shell: fractions `s` along its first use and the 3-D points of
/// its curve there.
#[derive(Debug, PartialEq)]
pub(in crate::topology) struct EdgeSamples {
    pub(super) s: Vec<f64>,
    pub(super) pts: Vec<Vec<f64>>,
}

/// One edge of a shell sampled for all its uses (`(plan, edge, same direction)`, the first
/// use defining the direction): the fractions of [`sample_edge`] and the first use's curve
/// there.
///
/// # Errors
/// As [`Curve::eval`](crate::Curve::eval) and the pcurves' evaluation, an edge without pcurve
/// ([`Error::InvalidArgument`]), or more than [`MAX_MESH_VERTICES`] points
/// ([`Error::TooLarge`]).
pub(in crate::topology) fn sample_shared_edge(
    uses: &[(&FacePlan<'_>, &Edge, bool)],
    tolerance: f64,
) -> Result<EdgeSamples> {
    let Some(first) = uses.first() else {
        return Ok(EdgeSamples {
            s: Vec::new(),
            pts: Vec::new(),
        });
    };
    let s = sample_edge(uses, tolerance)?;
    let pts = s
        .iter()
        .map(|&x| curve_at(first.1, x))
        .collect::<Result<Vec<_>>>()?;
    Ok(EdgeSamples { s, pts })
}

/// One use of an edge: its face, and its pcurve's parameter at a fraction of the edge.
pub(super) fn pcurve_at(e: &Edge, s: f64) -> Result<[f64; 2]> {
    let p = e.pcurve().ok_or(Error::InvalidArgument {
        what: "face loop".into(),
        reason:
            "an edge has no curve in the surface's (u, v); meshing a face needs every edge's pcurve"
                .into(),
    })?;
    let x = p.eval(at_fraction(p.domain(), s))?;
    Ok([x[0], x[1]])
}

fn curve_at(e: &Edge, s: f64) -> Result<Vec<f64>> {
    e.curve().eval(at_fraction(e.curve().domain(), s))
}

/// The parameter at fraction `s` of `[a, b]`, kept in `[a, b]` (`a + (b − a)·1` may round
/// past `b`).
fn at_fraction((a, b): (f64, f64), s: f64) -> f64 {
    (a + (b - a) * s.clamp(0.0, 1.0)).clamp(a, b)
}

/// The largest distance of the Euclidean control points of `c` restricted to the fractions
/// `[s0, s1]` of its domain (knot insertion, [`Curve::split_at`]) from the chord joining its
/// ends: the curve there lies in their convex hull (weights positive), so within that distance
/// of the chord (P&T §2.3, §4.2), as in the curves' tessellation
/// (`docs/theory/queries.md#tessellation`).
fn chord_gap(c: &Curve, s0: f64, s1: f64) -> Result<f64> {
    let (a, b) = c.domain();
    let (t0, t1) = (at_fraction((a, b), s0), at_fraction((a, b), s1));
    let mut piece = c.clone();
    if t0 > a && t0 < b {
        piece = piece.split_at(t0)?.1;
    }
    if t1 > piece.domain().0 && t1 < piece.domain().1 {
        piece = piece.split_at(t1)?.0;
    }
    let cp = piece.control_points();
    let dim = cp.dim();
    let pts = cp.as_slice();
    let n = pts.len() / dim.max(1);
    if n < 3 {
        return Ok(0.0);
    }
    let (p0, p1) = (&pts[..dim], &pts[(n - 1) * dim..n * dim]);
    let d: Vec<f64> = p0.iter().zip(p1).map(|(x, y)| y - x).collect();
    let dd: f64 = d.iter().map(|x| x * x).sum();
    let mut gap = 0.0_f64;
    for x in pts.chunks_exact(dim).skip(1).take(n - 2) {
        let r: Vec<f64> = x.iter().zip(p0).map(|(x, y)| x - y).collect();
        let t = if dd > 0.0 {
            (r.iter().zip(&d).map(|(x, y)| x * y).sum::<f64>() / dd).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let e: f64 = r
            .iter()
            .zip(&d)
            .map(|(x, y)| (x - t * y).powi(2))
            .sum::<f64>();
        gap = gap.max(e.sqrt());
    }
    Ok(gap)
}

pub(super) fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The fractions `0 = s_0 < … < s_n = 1` at which an edge is sampled, as its first use runs
/// it, for all its uses (`(plan, edge, same direction)`): start at
/// [`START_SAMPLES_PER_SPAN`] per knot span of its curve and of its pcurves of degree above 1
/// (a projected pcurve of degree 1 has many short spans, which the tests below sample as
/// finely as they need), and at least `⌈MIN_LOOP_SEGMENTS / k⌉` on a loop of `k` edges
/// ([`MIN_LOOP_SEGMENTS`]), then halve a segment while the edge's curve there is farther than
/// `tol / 2` from its chord ([`chord_gap`], a convex-hull bound) or, on any use's face,
/// the surface at the pcurve's midpoint is farther than `tol / 2` from the chord's midpoint,
/// the segment's parameter step has `M(e) > 4 tol` (its part of the triangles' bound), the
/// step is longer than the face's grid spacing, or longer than [`MAX_PERIOD_STEP`] of a
/// period in a closed direction.
fn sample_edge(uses: &[(&FacePlan<'_>, &Edge, bool)], tol: f64) -> Result<Vec<f64>> {
    let budget = MAX_MESH_VERTICES;
    let spans = uses
        .iter()
        .flat_map(|(_, e, _)| {
            [
                e.curve().knots().distinct().len(),
                e.pcurve()
                    .filter(|p| p.degree() > 1)
                    .map_or(2, |p| p.knots().distinct().len()),
            ]
        })
        .max()
        .unwrap_or(2)
        .saturating_sub(1)
        .max(1);
    // a loop of k edges: each edge at least ⌈MIN_LOOP_SEGMENTS / k⌉ segments
    let least = uses
        .iter()
        .filter_map(|(plan, e, _)| {
            plan.face
                .loops()
                .find(|l| l.edges().iter().any(|x| std::ptr::eq(x, *e)))
                .map(|l| MIN_LOOP_SEGMENTS.div_ceil(l.edges().len().max(1)))
        })
        .max()
        .unwrap_or(MIN_LOOP_SEGMENTS);
    let n0 = spans.saturating_mul(START_SAMPLES_PER_SPAN).max(least);
    let first_curve = uses.first().map(|u| u.1.curve());
    let point = |u: &(&FacePlan<'_>, &Edge, bool), s: f64| -> Result<([f64; 2], Vec<f64>)> {
        let su = if u.2 { s } else { 1.0 - s };
        let uv = pcurve_at(u.1, su)?;
        Ok((uv, u.0.surface_at(uv)?))
    };
    let split = |s0: f64, s1: f64| -> Result<bool> {
        let sm = 0.5 * (s0 + s1);
        for u in uses {
            let (a, pa) = point(u, s0)?;
            let (b, pb) = point(u, s1)?;
            let (_, pm) = point(u, sm)?;
            let mid: Vec<f64> = pa.iter().zip(&pb).map(|(x, y)| 0.5 * (x + y)).collect();
            let c = &u.0.curv;
            if dist(&pm, &mid) > 0.5 * tol
                || c.segment(a, b) > 4.0 * tol
                || (b[0] - a[0]).abs() > c.spacing_over(0, a[0], b[0])
                || (b[1] - a[1]).abs() > c.spacing_over(1, a[1], b[1])
                || (0..2).any(|d| {
                    u.0.closure.period[d].is_some_and(|p| (b[d] - a[d]).abs() > MAX_PERIOD_STEP * p)
                })
            {
                return Ok(true);
            }
        }
        Ok(false)
    };
    // the edge's 3-D curve within tol / 2 of its chord (its control points between s0 and s1,
    // a convex hull bound), tested once for all uses (they share the first use's points)
    let split = |s0: f64, s1: f64| -> Result<bool> {
        if let Some(c) = first_curve {
            if chord_gap(c, s0, s1)? > 0.5 * tol {
                return Ok(true);
            }
        }
        split(s0, s1)
    };
    let mut out = vec![0.0];
    for k in 0..n0 {
        let (s0, s1) = (k as f64 / n0 as f64, (k + 1) as f64 / n0 as f64);
        let mut stack = vec![(s1, 0u32)];
        let mut at = s0;
        while let Some(&(s, depth)) = stack.last() {
            if depth < MAX_EDGE_DEPTH && split(at, s)? {
                stack.push((0.5 * (at + s), depth + 1));
                continue;
            }
            stack.pop();
            out.push(s);
            at = s;
            if out.len() > budget {
                return Err(Error::TooLarge {
                    what: What::of(
                        Arg::Tolerance,
                        "points on an edge of the faces to mesh (make the tolerance larger)",
                    ),
                    size: out.len(),
                    max: budget,
                });
            }
        }
    }
    Ok(out)
}
