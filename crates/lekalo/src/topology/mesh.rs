//! Triangle meshes of trimmed faces (`docs/theory/topology.md`, "Meshing a trimmed face"):
//! each loop sampled through its edges' pcurves, points of a `(u, v)` grid inside the trims,
//! a constrained Delaunay triangulation of both with the loops' segments as constraints
//! (Chew, "Constrained Delaunay triangulations", Algorithmica 4 (1989) 97–108; de Berg et al.,
//! "Computational Geometry", 3rd ed., 2008, ch. 9), refined where a triangle's deviation bound
//! is above the tolerance. Faces of a set are meshed with each shared edge sampled once, so the
//! faces' meshes meet at the same points along it. This file meshes one face from its edges'
//! samples, which `mesh/edge_sampling.rs` takes; `mesh_set.rs` drives a set of faces (each
//! edge sampled once, each face meshed once, the failures by face).

mod edge_sampling;

use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation as _};

use super::curvature::Curvature;
use super::face::Face;
use super::inside::winding_number;
use super::pcurve::{SurfaceClosure, PCURVE_SAMPLING_RTOL};
use super::seam::{cut_along_seam, SeamPlan};
use super::shell::EdgeUse;
use crate::query::{check_tol, Mesh, MAX_MESH_VERTICES, TESSELLATION_TOLERANCE};
use crate::{Arg, Error, Points, Result, What};
use edge_sampling::pcurve_at;
pub(super) use edge_sampling::{sample_shared_edge, EdgeSamples};

/// Points on a pole side of the domain within this fraction of the domain's width of it, and
/// apart along it by more, are a loop's run along the pole.
const POLE_RTOL: f64 = 1e-9;
/// Most points inserted along one run of a loop along a pole.
const MAX_POLE_STEPS: f64 = 1e6;
/// Most rounds of refinement of the triangles above the tolerance.
pub(super) const MAX_REFINE_ROUNDS: usize = 24;
/// Grid points closer to a trim than this fraction of the grid spacing are left out, so no
/// sliver triangle joins a grid point to a nearby trim segment.
pub const TRIM_CLEARANCE: f64 = 0.3;

/// What one face needs while its edges are sampled: its surface's bounds and grid spacing,
/// patch by patch.
pub(super) struct FacePlan<'a> {
    face: &'a Face,
    curv: Curvature,
    /// The least grid spacing in `u` and in `v` (the steps along seam and pole lines).
    h: [f64; 2],
    /// The surface's seams: a pcurve projected across one leaves the domain by whole periods.
    closure: SurfaceClosure,
    /// Most rounds of refinement ([`MAX_REFINE_ROUNDS`]; fewer in tests of the report of a
    /// mesh above its tolerance).
    rounds: usize,
}

impl FacePlan<'_> {
    /// The surface at a point of a pcurve: a pcurve written by a CAD system may leave the
    /// surface's domain by its own rounding or tolerance, and the surface is taken at the
    /// nearest point of its domain there; one unwrapped across a seam is brought back by whole
    /// periods ([`SurfaceClosure::wrap`]).
    fn surface_at(&self, uv: [f64; 2]) -> Result<Vec<f64>> {
        let s = self.face.surface();
        let w = self.closure.wrap(s.domain(), uv);
        s.eval(w[0], w[1])
    }
}

impl FacePlan<'_> {
    /// `uv` clipped to the surface's domain in each direction in which it does not close: a
    /// pcurve past the domain by its CAD system's rounding or tolerance (at most
    /// [`LOOP_CLOSURE_RTOL`](super::LOOP_CLOSURE_RTOL) of the width, [`Face::checked_trims`])
    /// bounds the region up to the domain's side, not past it.
    fn clip(&self, uv: [f64; 2]) -> [f64; 2] {
        let ((u0, u1), (v0, v1)) = self.face.surface().domain();
        let dom = [(u0, u1), (v0, v1)];
        let mut out = uv;
        for d in 0..2 {
            if self.closure.period[d].is_none() {
                out[d] = out[d].clamp(dom[d].0, dom[d].1);
            }
        }
        out
    }

    /// The free parameter (0 = `u`) when `a` and `b` are two points of one pole of the surface
    /// (a side that is one point, [`SurfaceClosure`]) apart along it by more than rounding.
    fn along_pole(&self, a: [f64; 2], b: [f64; 2]) -> Option<usize> {
        let dom = self.face.surface().domain();
        let (wa, wb) = (self.closure.wrap(dom, a), self.closure.wrap(dom, b));
        let sides = [dom.0 .0, dom.0 .1, dom.1 .0, dom.1 .1];
        let widths = [dom.0 .1 - dom.0 .0, dom.1 .1 - dom.1 .0];
        (0..4).find_map(|k| {
            let (fixed, free) = (k / 2, 1 - k / 2);
            let on = |w: [f64; 2]| (w[fixed] - sides[k]).abs() <= POLE_RTOL * widths[fixed];
            (self.closure.pole[k]
                && on(wa)
                && on(wb)
                && (a[free] - b[free]).abs() > POLE_RTOL * widths[free])
                .then_some(free)
        })
    }

    /// The polygon with points inserted along each segment that runs along a pole, at most
    /// the grid spacing apart, each the segment's first point in space (the pole's): the
    /// triangles there are then within the tolerance as elsewhere, and those with two
    /// vertices at the pole are left out as having no area.
    fn fill_poles(&self, poly: Vec<([f64; 2], Vec<f64>)>) -> Vec<([f64; 2], Vec<f64>)> {
        let n = poly.len();
        let mut out = Vec::with_capacity(n);
        for k in 0..n {
            let (a, b) = (&poly[k], &poly[(k + 1) % n]);
            out.push(a.clone());
            if let Some(free) = self.along_pole(a.0, b.0) {
                let len = (b.0[free] - a.0[free]).abs();
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // clamped
                let steps = (len / self.h[free]).ceil().clamp(1.0, MAX_POLE_STEPS) as usize;
                for i in 1..steps {
                    let t = i as f64 / steps as f64;
                    let uv = [
                        a.0[0] + (b.0[0] - a.0[0]) * t,
                        a.0[1] + (b.0[1] - a.0[1]) * t,
                    ];
                    out.push((uv, a.1.clone()));
                }
            }
        }
        out
    }
}

/// The plan of one face's mesh: its surface's second-derivative bounds patch by patch and the
/// grid spacing of each knot span whose triangles are within `tolerance` by the bound of the
/// untrimmed mesher (each of the three edge terms `M(e) = A e_u² + 2B |e_u e_v| + C e_v²` at
/// most `6·tolerance`, split evenly; [`Curvature::of`]; `docs/theory/queries.md#tessellation`),
/// its seams; with the number of grid cells over its domain.
///
/// # Errors
/// [`Error::InvalidArgument`] for a tolerance below
/// [`MIN_RELATIVE_TOLERANCE`](crate::query::MIN_RELATIVE_TOLERANCE) of the surface's size, a
/// rational surface with a weight that is not positive, or a grid of more than
/// [`MAX_MESH_VERTICES`] points (naming the tolerance that would do).
pub(super) fn plan_face(f: &Face, tolerance: f64, rounds: usize) -> Result<(FacePlan<'_>, f64)> {
    // closed within the tolerance of the pcurves' projection: a surface smaller than a coarse
    // tolerance is not closed (nor every side of it a pole) for being small
    let closure = SurfaceClosure::of(
        f.surface(),
        tolerance.min(PCURVE_SAMPLING_RTOL * f.model_size()),
    )?;
    let (curv, scale) = Curvature::of(f.surface(), &closure, tolerance)?;
    check_tol(tolerance, scale)?;
    let ((u0, u1), (v0, v1)) = f.surface().domain();
    let cells = curv.cells();
    check_grid(tolerance, cells)?;
    let h = [
        curv.spacing_over(0, u0, u1).min(u1 - u0),
        curv.spacing_over(1, v0, v1).min(v1 - v0),
    ];
    let plan = FacePlan {
        face: f,
        curv,
        h: h.map(|x| x.max(f64::MIN_POSITIVE)),
        closure,
        rounds,
    };
    Ok((plan, cells))
}

/// Refuses a grid of `cells` points at `tolerance` above [`MAX_MESH_VERTICES`], naming the
/// tolerance that would do.
pub(super) fn check_grid(tolerance: f64, cells: f64) -> Result<()> {
    #[allow(clippy::cast_precision_loss)] // 2^26 is exact
    let max = MAX_MESH_VERTICES as f64;
    if cells > max {
        return Err(Error::InvalidArgument {
            what: TESSELLATION_TOLERANCE,
            reason: format!(
                "{tolerance:e} needs a grid of about {cells:.1e} points inside the faces, more than the {MAX_MESH_VERTICES} a mesh may have; use a tolerance of at least {:.1e}",
                tolerance * cells / max
            ),
        });
    }
    Ok(())
}

/// The samples of one use of an edge: the edge's samples, whether the use runs the edge the way
/// they do, and the points of the vertices at the use's start and end.
pub(super) type UseSamples<'s> = (&'s EdgeSamples, bool, [&'s [f64]; 2]);

/// The mesh of face `fi` of a set from the samples of its edges (`samples` of a use, see
/// [`UseSamples`]): the loops as polygons in `(u, v)` through the samples, each corner at its
/// vertex's point in space (one point for every face meeting there, where the edges' ends
/// differ within the file's tolerance), cut along a seam where they go round a closed surface,
/// triangulated and refined ([`mesh_faces`](super::mesh_faces)).
///
/// # Errors
/// As [`mesh_faces`](super::mesh_faces) for one face.
pub(super) fn mesh_face<'s>(
    plan: &FacePlan<'_>,
    fi: usize,
    samples: &dyn Fn(EdgeUse) -> Option<UseSamples<'s>>,
    tolerance: f64,
) -> Result<Mesh> {
    // the loops as polygons in (u, v), with their 3-D points
    let mut loops: Vec<Vec<([f64; 2], Vec<f64>)>> = Vec::new();
    for (li, lp) in plan.face.loops().enumerate() {
        // each edge's points, all of them
        let mut edges: Vec<Vec<([f64; 2], Vec<f64>)>> = Vec::new();
        for (ei, e) in lp.edges().iter().enumerate() {
            let u = EdgeUse {
                face: fi,
                lp: li,
                edge: ei,
            };
            let Some((es, same, corners)) = samples(u) else {
                continue;
            };
            let (s, pts) = (&es.s, &es.pts);
            let n = s.len();
            if n < 2 {
                continue;
            }
            let mut pe = Vec::with_capacity(n);
            for k in 0..n {
                let j = if same { k } else { n - 1 - k };
                let su = if same { s[j] } else { 1.0 - s[j] };
                let x = match k {
                    0 => corners[0].to_vec(),
                    _ if k == n - 1 => corners[1].to_vec(),
                    _ => pts[j].clone(),
                };
                pe.push((plan.clip(pcurve_at(e, su)?), x));
            }
            edges.push(pe);
        }
        // the last point of an edge is the next edge's first, unless the loop runs along a
        // pole between them (the pole's free parameter changes at one point in space)
        let mut poly = Vec::new();
        for (k, pe) in edges.iter().enumerate() {
            let next = &edges[(k + 1) % edges.len()][0];
            let last = &pe[pe.len() - 1];
            poly.extend_from_slice(&pe[..pe.len() - 1]);
            if plan.along_pole(last.0, next.0).is_some() {
                poly.push(last.clone());
            }
        }
        loops.push(plan.fill_poles(poly));
    }
    // loops going round a closed surface (a band, a cap): the face cut along a seam
    let eval = |uv: [f64; 2]| plan.surface_at(uv);
    let seam = SeamPlan {
        closure: &plan.closure,
        domain: plan.face.surface().domain(),
        same_sense: plan.face.same_sense(),
        h: plan.h,
        eval: &eval,
    };
    let loops = cut_along_seam(&seam, loops)?;
    mesh_one(plan, &loops, tolerance, MAX_MESH_VERTICES)
}

/// True when `(u, v)` is inside the polygons (the outer's winding number not zero, every
/// inner's zero).
fn inside(polys: &[Vec<f64>], u: f64, v: f64) -> bool {
    let mut it = polys.iter();
    let Some(outer) = it.next() else { return false };
    winding_number(outer, u, v) != 0 && it.all(|p| winding_number(p, u, v) == 0)
}

/// The distance from `p` to the segment `ab`, in coordinates scaled by `1 / h`.
fn seg_dist(p: [f64; 2], a: [f64; 2], b: [f64; 2], h: [f64; 2]) -> f64 {
    let (px, py) = ((p[0] - a[0]) / h[0], (p[1] - a[1]) / h[1]);
    let (dx, dy) = ((b[0] - a[0]) / h[0], (b[1] - a[1]) / h[1]);
    let l = dx * dx + dy * dy;
    let t = if l > 0.0 {
        ((px * dx + py * dy) / l).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((px - t * dx).powi(2) + (py - t * dy).powi(2)).sqrt()
}

#[allow(clippy::cast_possible_truncation)] // cells and counts checked against MAX_MESH_VERTICES
fn mesh_one(
    plan: &FacePlan<'_>,
    loops: &[Vec<([f64; 2], Vec<f64>)>],
    tol: f64,
    budget: usize,
) -> Result<Mesh> {
    let polys: Vec<Vec<f64>> = loops
        .iter()
        .map(|l| l.iter().flat_map(|(uv, _)| *uv).collect())
        .collect();
    let surface = plan.face.surface();
    let mut uv: Vec<[f64; 2]> = Vec::new();
    let mut xyz: Vec<Vec<f64>> = Vec::new();
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    // vertex of the triangulation -> our vertex
    let mut ours: Vec<usize> = Vec::new();
    let insert_err = |e: spade::InsertionError| {
        Error::InvalidArgument {
        what: "face loop".into(),
        reason: format!("a point of a trim cannot be triangulated ({e:?}); its (u, v) is not finite or too large"),
    }
    };
    // the Delaunay triangulation is of the points with v scaled by h_u / h_v (the least
    // spacings): a refinement at centroids then makes triangles of the cells' shape rather
    // than slivers across them where the spacing differs much between u and v
    let aspect = (plan.h[0] / plan.h[1]).clamp(1e-6, 1e6);
    let add = |cdt: &mut Cdt,
               ours: &mut Vec<usize>,
               uv: &mut Vec<[f64; 2]>,
               xyz: &mut Vec<Vec<f64>>,
               p: [f64; 2],
               x: Vec<f64>|
     -> Result<spade::handles::FixedVertexHandle> {
        // a parameter within 2⁻¹⁴² of 0 (a foot on a seam at 0, by rounding) is 0: the
        // triangulation refuses smaller coordinates other than 0
        let p = p.map(|x| {
            if x.abs() < spade::MIN_ALLOWED_VALUE {
                0.0
            } else {
                x
            }
        });
        // triangulated with v scaled to the grid's aspect, so cells are about square there
        let q = p[1] * aspect;
        let q = if q.abs() < spade::MIN_ALLOWED_VALUE {
            0.0
        } else {
            q
        };
        let vh = cdt.insert(Point2::new(p[0], q)).map_err(insert_err)?;
        if vh.index() >= ours.len() {
            ours.push(uv.len());
            uv.push(p);
            xyz.push(x);
        }
        Ok(vh)
    };
    // the grid lines over the loops' box: each knot span at its own spacing
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in loops.iter().flatten() {
        for d in 0..2 {
            lo[d] = lo[d].min(p.0[d]);
            hi[d] = hi[d].max(p.0[d]);
        }
    }
    let lines = if lo[0].is_finite() {
        [
            plan.curv.lines(0, lo[0], hi[0], budget)?,
            plan.curv.lines(1, lo[1], hi[1], budget)?,
        ]
    } else {
        [Vec::new(), Vec::new()]
    };
    let grid = Grid { lines };
    // the segments of the loops, bucketed by grid cell for the clearance test
    let mut buckets = Buckets::default();
    for l in loops {
        let n = l.len();
        if n == 0 {
            continue;
        }
        let mut handles = Vec::with_capacity(n);
        for (p, x) in l {
            handles.push(add(&mut cdt, &mut ours, &mut uv, &mut xyz, *p, x.clone())?);
        }
        for k in 0..n {
            let (a, b) = (l[k].0, l[(k + 1) % n].0);
            buckets.insert(&grid, a, b);
            if handles[k] != handles[(k + 1) % n] {
                cdt.try_add_constraint(handles[k], handles[(k + 1) % n]);
            }
        }
    }
    // grid points inside the trims, clear of them by a fraction of their cells' spacing
    let [lu, lv] = &grid.lines;
    for i in 1..lu.len().saturating_sub(1) {
        for j in 1..lv.len().saturating_sub(1) {
            let p = [lu[i], lv[j]];
            if !inside(&polys, p[0], p[1]) {
                continue;
            }
            let h = [
                (lu[i] - lu[i - 1]).min(lu[i + 1] - lu[i]),
                (lv[j] - lv[j - 1]).min(lv[j + 1] - lv[j]),
            ];
            if buckets.near(&grid, p, h) {
                continue;
            }
            let x = plan.surface_at(p)?;
            add(&mut cdt, &mut ours, &mut uv, &mut xyz, p, x)?;
            if uv.len() > budget {
                return Err(Error::TooLarge {
                    what: What::of(
                        Arg::Tolerance,
                        "vertices of the faces' mesh (make the tolerance larger)",
                    ),
                    size: uv.len(),
                    max: budget,
                });
            }
        }
    }
    // triangles inside, refined at the centroids of those above the tolerance
    let mut round = 0;
    let (tris, deviation) = loop {
        let keep = inside_triangles(&cdt, &polys, &uv, &ours);
        let mut tris = Vec::new();
        let mut worst = 0.0_f64;
        let mut refine = Vec::new();
        for f in cdt.inner_faces() {
            let vs = f.vertices().map(|v| ours[v.fix().index()]);
            let p = vs.map(|k| uv[k]);
            let c = [
                (p[0][0] + p[1][0] + p[2][0]) / 3.0,
                (p[0][1] + p[1][1] + p[2][1]) / 3.0,
            ];
            if !keep[f.fix().index()] {
                continue;
            }
            // two vertices at one point (along a pole): refined as the others, but without
            // area in space
            if !(0..3).any(|i| xyz[vs[i]] == xyz[vs[(i + 1) % 3]]) {
                tris.push(vs);
            }
            let b = plan.curv.triangle(p);
            if b > tol {
                refine.push(c);
            }
            worst = worst.max(b);
        }
        if refine.is_empty() || round >= plan.rounds {
            break (tris, worst);
        }
        round += 1;
        for c in refine {
            let x = plan.surface_at(c)?;
            add(&mut cdt, &mut ours, &mut uv, &mut xyz, c, x)?;
            if uv.len() > budget {
                return Err(Error::TooLarge {
                    what: What::of(
                        Arg::Tolerance,
                        "vertices of the faces' mesh (make the tolerance larger)",
                    ),
                    size: uv.len(),
                    max: budget,
                });
            }
        }
    };
    let dim = surface.dim();
    let mut flat = Vec::with_capacity(dim * xyz.len());
    for x in &xyz {
        flat.extend_from_slice(&x[..dim]);
    }
    let triangles = tris
        .into_iter()
        .map(|t| {
            let t = t.map(|k| k as u32);
            if plan.face.same_sense() {
                t
            } else {
                [t[0], t[2], t[1]]
            }
        })
        .collect();
    Ok(Mesh {
        vertices: Points::from_flat(dim, flat)?,
        uv,
        triangles,
        deviation,
    })
}

/// The grid lines of a face's mesh in `u` and `v` ([`Curvature::lines`]).
struct Grid {
    lines: [Vec<f64>; 2],
}

impl Grid {
    /// The cell index along `d` holding `x` (clamped to the grid).
    fn cell(&self, d: usize, x: f64) -> usize {
        let l = &self.lines[d];
        l.partition_point(|&t| t <= x)
            .saturating_sub(1)
            .min(l.len().saturating_sub(2))
    }
}

/// Most grid cells a trim segment is filed under; a longer one is tested against every grid
/// point (seam and pole lines are sampled at the least spacing, and the edges at their spans'
/// spacing, so a segment meets a few cells).
const MAX_SEGMENT_CELLS: usize = 256;

/// Trim segments by grid cell, and those meeting too many cells to file.
#[derive(Default)]
struct Buckets {
    cells: std::collections::HashMap<(usize, usize), Vec<Segment>>,
    long: Vec<Segment>,
}

/// A trim segment's ends in `(u, v)`.
type Segment = ([f64; 2], [f64; 2]);

impl Buckets {
    fn insert(&mut self, g: &Grid, a: [f64; 2], b: [f64; 2]) {
        if g.lines[0].len() < 2 || g.lines[1].len() < 2 {
            return;
        }
        let (i0, i1) = (g.cell(0, a[0].min(b[0])), g.cell(0, a[0].max(b[0])));
        let (j0, j1) = (g.cell(1, a[1].min(b[1])), g.cell(1, a[1].max(b[1])));
        if (i1 - i0 + 1).saturating_mul(j1 - j0 + 1) > MAX_SEGMENT_CELLS {
            self.long.push((a, b));
            return;
        }
        for i in i0..=i1 {
            for j in j0..=j1 {
                self.cells.entry((i, j)).or_default().push((a, b));
            }
        }
    }

    /// True when a trim segment is closer to `p` than [`TRIM_CLEARANCE`] of the spacing `h`.
    fn near(&self, g: &Grid, p: [f64; 2], h: [f64; 2]) -> bool {
        let close = |&(s, t): &([f64; 2], [f64; 2])| seg_dist(p, s, t, h) < TRIM_CLEARANCE;
        let r = [TRIM_CLEARANCE * h[0], TRIM_CLEARANCE * h[1]];
        let (i0, i1) = (g.cell(0, p[0] - r[0]), g.cell(0, p[0] + r[0]));
        let (j0, j1) = (g.cell(1, p[1] - r[1]), g.cell(1, p[1] + r[1]));
        self.long.iter().any(close)
            || (i0..=i1).any(|i| {
                (j0..=j1).any(|j| self.cells.get(&(i, j)).is_some_and(|v| v.iter().any(close)))
            })
    }
}

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// Which faces of the triangulation (by index) are inside the trims: the faces joined across
/// edges that are not constraints are one region, on one side of every loop, so a region is
/// outside when it reaches the convex hull across an edge that is not a constraint, and
/// otherwise inside when the centroid of its largest triangle is (winding numbers of the
/// loops' polygons). A triangle of three nearly collinear points of a loop, whose own centroid is
/// within rounding of the trim, takes the side of its region.
fn inside_triangles(cdt: &Cdt, polys: &[Vec<f64>], uv: &[[f64; 2]], ours: &[usize]) -> Vec<bool> {
    let n = cdt.num_all_faces();
    let mut region = vec![usize::MAX; n];
    let mut keep = vec![false; n];
    let mut members = Vec::new();
    let mut stack = Vec::new();
    let area_centroid = |f: spade::handles::FaceHandle<
        '_,
        spade::handles::InnerTag,
        Point2<f64>,
        (),
        spade::CdtEdge<()>,
        (),
    >| {
        let p = f.vertices().map(|v| uv[ours[v.fix().index()]]);
        let a = ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
            - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))
            .abs();
        (
            a,
            [
                (p[0][0] + p[1][0] + p[2][0]) / 3.0,
                (p[0][1] + p[1][1] + p[2][1]) / 3.0,
            ],
        )
    };
    for f in cdt.inner_faces() {
        let start = f.fix().index();
        if region[start] != usize::MAX {
            continue;
        }
        region[start] = start;
        members.clear();
        stack.push(f);
        let mut best = (-1.0, [0.0, 0.0]);
        let mut outer = false;
        while let Some(g) = stack.pop() {
            members.push(g.fix().index());
            let (a, c) = area_centroid(g);
            if a > best.0 {
                best = (a, c);
            }
            for e in g.adjacent_edges() {
                if cdt.is_constraint_edge(e.fix().as_undirected()) {
                    continue;
                }
                match e.rev().face().as_inner() {
                    Some(h) => {
                        let k = h.fix().index();
                        if region[k] == usize::MAX {
                            region[k] = start;
                            stack.push(h);
                        }
                    }
                    None => outer = true,
                }
            }
        }
        let is_in = !outer && inside(polys, best.1[0], best.1[1]);
        for &k in &members {
            keep[k] = is_in;
        }
    }
    keep
}

#[cfg(test)]
#[path = "mesh_tests.rs"]
mod tests;
