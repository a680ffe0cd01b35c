//! Meshes of a set of faces (`docs/theory/topology.md`, "Meshing a trimmed face", "Faces that
//! cannot be meshed"): every edge of the faces' [`Shell`] sampled once for the faces that share
//! it, every face meshed once from its edges' samples (in parallel: each face depends only on
//! its own edges), and a face that fails left out with its error while the others are meshed
//! as they would be without it.

use crate::error::readable;
use std::collections::HashMap;
use std::sync::Arc;

use rayon::prelude::*;

use super::face::{Edge, Face};
use super::mesh::{
    check_grid, mesh_face, plan_face, sample_shared_edge, EdgeSamples, FacePlan, UseSamples,
    MAX_REFINE_ROUNDS,
};
use super::shell::{EdgeUse, Shell};
use super::trims::TrimRepair;
use crate::query::{check_deviation, Mesh, MAX_MESH_VERTICES, TESSELLATION_TOLERANCE};
use crate::{Arg, Error, Points, Result, What};

/// The meshes of a set of faces that could be meshed, and the errors of those that could not
/// ([`mesh_faces_each`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct FaceMeshes {
    /// The index of each face meshed in the set, with its mesh, in the order of the set.
    pub meshes: Vec<(usize, Mesh)>,
    /// The index of each face not meshed, with the reason, in the order of the set.
    pub failures: Vec<(usize, Error)>,
    /// The index of each face meshed (in [`FaceMeshes::meshes`]) whose proved deviation bound
    /// is above the tolerance, refinement having stopped at its limit, with
    /// [`Error::ToleranceNotMet`] naming the bound, in the order of the set.
    pub above_tolerance: Vec<(usize, Error)>,
    /// The index of each face whose trims were repaired before meshing ([`Face::checked_trims`]:
    /// pcurves clipped to the domain within the tolerance, edges or holes of no length
    /// dropped), with the repair, in the order of the set.
    pub repairs: Vec<(usize, TrimRepair)>,
}

impl FaceMeshes {
    /// The meshes of the faces meshed as one ([`join_meshes`]).
    ///
    /// # Errors
    /// As [`join_meshes`].
    pub fn join(&self) -> Result<Mesh> {
        join(self.meshes.iter().map(|(_, m)| m))
    }

    /// The unit normals of the vertices of [`FaceMeshes::join`], in its order: for each face
    /// meshed, [`Mesh::surface_normals`] of its mesh on its face's surface, turned by the face's
    /// sense ([`Face::same_sense`]): the exact `S_u × S_v / |S_u × S_v|` at each vertex's
    /// `(u, v)`, the pole fallback where that is undefined. `faces` is the set that was meshed
    /// (the slice given to [`mesh_faces_each`]); a face index past it (a different set) gives
    /// `None` for its vertices.
    #[must_use]
    pub fn surface_normals(&self, faces: &[&Face]) -> Vec<Option<[f64; 3]>> {
        let mut normals = Vec::with_capacity(self.meshes.iter().map(|(_, m)| m.uv.len()).sum());
        for (i, m) in &self.meshes {
            match faces.get(*i) {
                Some(f) => normals.extend(m.surface_normals(f.surface(), f.same_sense())),
                None => normals.extend(std::iter::repeat_n(None, m.vertices.len())),
            }
        }
        normals
    }
}

/// Uses of one edge, by the index of their face in the whole set, their loop and their place
/// in it, and whether they run the edge as its first use does: what an edge's samples depend
/// on, so the key under which they are kept while faces drop out of the set.
type EdgeKey = Vec<(usize, usize, usize, bool)>;

/// One use of an edge while it is sampled: its face's plan, the edge, and whether it runs the
/// edge as the first use does.
type Use<'a> = (&'a FacePlan<'a>, &'a Edge, bool);

/// The samples of a face's edges, loop by loop, each with whether the face runs the edge as
/// its samples do: what a face's mesh depends on besides the face.
/// Each use's samples, direction and vertex points (see [`UseSamples`]), owned.
type FaceSamples = Vec<Option<(Arc<EdgeSamples>, bool, [Vec<f64>; 2])>>;

/// Meshes of `faces`, one per face, each within `tolerance` of its surface over its trimmed
/// region, the faces' meshes meeting without cracks along their shared edges
/// (`docs/theory/topology.md`, "Meshing a trimmed face"):
///
/// * every edge of the [`Shell`] of the faces is sampled once, at fractions of its first
///   use's curve, halved where on any of its faces the surface at the pcurve's midpoint
///   departs from the chord by more than `tolerance / 2`, where the parameter step `e` has
///   `M(e) > 4·tolerance`, or where it is longer than the face's grid spacing; each use takes
///   the same points of the 3-D curve, its `(u, v)` from its pcurve at the same fraction (run
///   backwards by a use that runs the edge the other way), so the faces' boundary vertices
///   coincide;
/// * the interior points are the points of a uniform `(u, v)` grid whose triangles are within
///   the tolerance by the bound of the untrimmed mesher (`M(e) = A e_u² + 2B |e_u e_v| +
///   C e_v²`, `A, B, C` bounds on `|S_uu|, |S_uv|, |S_vv|` from the Bezier nets, and the
///   triangle bound `½ max Σ λ_i λ_j M_ij`; `docs/theory/queries.md#tessellation`) that lie
///   inside the trims (winding numbers of the sampled loops) farther than
///   [`TRIM_CLEARANCE`](super::TRIM_CLEARANCE) of the spacing from every trim segment;
/// * a constrained Delaunay triangulation of these points with the loops' segments as
///   constraints (Chew 1989; de Berg et al. 2008, ch. 9; the `spade` crate) keeps the
///   triangles inside the trims: those joined across edges that are not constraints form one
///   region, outside when it reaches the convex hull, else inside when the centroid of its
///   largest triangle is (so a sliver of three nearly collinear trim points, whose own
///   centroid is within rounding of the trim, takes its region's side); a triangle whose bound is above the
///   tolerance gets its centroid inserted, and the triangulation is made again, at most
///   24 times.
///
/// Vertices on the edges are the edges' 3-D points, the others the surface's. Triangles run
/// counter-clockwise in `(u, v)` where the face's normal is the surface's and the other way
/// where it is not, so their normals are the face's. The reported deviation is the largest
/// triangle bound (for a rational surface the bounds of its nets, an estimate; the edges'
/// chords are checked at their midpoints).
///
/// # Errors
/// [`Error::InvalidArgument`] for a tolerance that is not finite or below
/// [`MIN_RELATIVE_TOLERANCE`](crate::query::MIN_RELATIVE_TOLERANCE) of a surface's size, for
/// an edge without pcurve, or a tolerance whose grid would exceed
/// [`MAX_MESH_VERTICES`](crate::query::MAX_MESH_VERTICES) points (naming the tolerance and the
/// number of points); [`Error::InvalidTrim`] for loops that do not bound one region of the
/// domain ([`Face::checked_trims`]); [`Error::TooLarge`] when the edges' points or the refined meshes exceed
/// that many vertices; the error of the first face that cannot be meshed
/// ([`mesh_faces_each`] keeps the others).
pub fn mesh_faces(faces: &[&Face], tolerance: f64) -> Result<Vec<Mesh>> {
    let r = mesh_faces_each(faces, tolerance)?;
    if let Some((_, e)) = r.failures.into_iter().chain(r.above_tolerance).next() {
        return Err(e);
    }
    Ok(r.meshes.into_iter().map(|(_, m)| m).collect())
}

/// The meshes of the faces of `faces` that can be meshed within `tolerance`, as
/// [`mesh_faces`] meshes them when the others are left out of the set, and for each face that
/// cannot, its index and its error; each face is meshed once (`docs/theory/topology.md`,
/// "Faces that cannot be meshed"):
///
/// 0. every face's trims are checked ([`Face::checked_trims`]): a face whose loops do not bound
///    one region of its domain fails with [`Error::InvalidTrim`]; edges and holes of no length
///    are dropped and pcurves past the domain within the tolerance clipped, each repair listed
///    in [`FaceMeshes::repairs`];
/// 1. every face is planned (its surface's bounds and grid; a surface that cannot be meshed at
///    this tolerance fails there);
/// 2. the edges of the [`Shell`] of the faces not failed are sampled once each, in parallel;
///    a face whose use of an edge cannot be sampled (no pcurve, a pcurve that cannot be
///    evaluated) fails, found by sampling the edge's uses one by one;
/// 3. the faces not failed are meshed from their edges' samples, in parallel; a face whose
///    loops cannot be cut along a seam or triangulated fails.
///
/// When faces fail at step 2 or 3, the shell of the others is made again: an edge that was
/// shared with a failed face is sampled again for its other faces alone, and only the faces
/// whose edges' samples then differ are meshed again; every other edge and face keeps its
/// samples and mesh. So the meshes are those of [`mesh_faces`] of the faces that succeed
/// (watertight along their shared edges), a failed face changes nothing but its neighbours'
/// edges, and the work is one pass plus the neighbours, along the edges whose samples the
/// failed face refined, of the faces that fail at step 3.
///
/// # Errors
/// Of the whole set: [`Error::InvalidArgument`] for a tolerance that is not positive and
/// finite, or whose grids together exceed
/// [`MAX_MESH_VERTICES`](crate::query::MAX_MESH_VERTICES) points; [`Error::TooLarge`] when
/// the meshes together exceed that many vertices. A face's own errors are in
/// [`FaceMeshes::failures`].
pub fn mesh_faces_each(faces: &[&Face], tolerance: f64) -> Result<FaceMeshes> {
    Ok(mesh_counted(faces, tolerance, MAX_REFINE_ROUNDS)?.0)
}

/// [`mesh_faces_each`] with the number of faces meshed (each face meshed once, its
/// neighbours again when it fails at step 3), at most `rounds` rounds of refinement.
pub(super) fn mesh_counted(
    faces: &[&Face],
    tolerance: f64,
    rounds: usize,
) -> Result<(FaceMeshes, usize)> {
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(Error::InvalidArgument {
            what: TESSELLATION_TOLERANCE,
            reason: format!(
                "{tolerance} is not a positive finite tolerance",
                tolerance = readable(&tolerance)
            ),
        });
    }
    let n = faces.len();
    let mut failed: Vec<Option<Error>> = vec![None; n];
    // step 0: the trims checked, repaired where the repair is unambiguous
    let checked: Vec<Result<(Option<Face>, Vec<TrimRepair>)>> =
        faces.par_iter().map(|f| f.checked_trims()).collect();
    let mut repaired: Vec<Option<Face>> = Vec::with_capacity(n);
    let mut repairs = Vec::new();
    for (i, c) in checked.into_iter().enumerate() {
        match c {
            Ok((g, r)) => {
                repaired.push(g);
                repairs.extend(r.into_iter().map(|x| (i, x)));
            }
            Err(e) => {
                failed[i] = Some(e);
                repaired.push(None);
            }
        }
    }
    let faces: Vec<&Face> = faces
        .iter()
        .zip(&repaired)
        .map(|(f, g)| g.as_ref().unwrap_or(f))
        .collect();
    let faces = faces.as_slice();
    let mut plans: Vec<Option<FacePlan<'_>>> = Vec::with_capacity(n);
    let mut grid_total = 0.0_f64;
    let planned: Vec<Option<Result<(FacePlan<'_>, f64)>>> = faces
        .par_iter()
        .zip(&failed)
        .map(|(f, bad)| bad.is_none().then(|| plan_face(f, tolerance, rounds)))
        .collect();
    for (i, p) in planned.into_iter().enumerate() {
        let Some(p) = p else {
            plans.push(None);
            continue;
        };
        match p {
            Ok((plan, cells)) => {
                grid_total += cells;
                plans.push(Some(plan));
            }
            Err(e) => {
                failed[i] = Some(e);
                plans.push(None);
            }
        }
    }
    check_grid(tolerance, grid_total)?;
    let edge_of = |fi: usize, lp: usize, ei: usize| -> Option<&Edge> {
        faces.get(fi)?.loops().nth(lp)?.edges().get(ei)
    };
    let uses_of = |key: &EdgeKey| -> Vec<Use<'_>> {
        key.iter()
            .filter_map(|&(fi, lp, ei, same)| {
                Some((plans[fi].as_ref()?, edge_of(fi, lp, ei)?, same))
            })
            .collect()
    };
    let mut sampled: HashMap<EdgeKey, Arc<EdgeSamples>> = HashMap::new();
    // each face's mesh with the samples of its edges it was made from
    let mut meshed: Vec<Option<(FaceSamples, Mesh)>> = vec![None; n];
    let mut count = 0;
    loop {
        let live: Vec<usize> = (0..n).filter(|&i| failed[i].is_none()).collect();
        let live_faces: Vec<&Face> = live.iter().map(|&i| faces[i]).collect();
        let shell = Shell::new(&live_faces)?;
        let keys: Vec<EdgeKey> = shell
            .edges()
            .iter()
            .map(|se| {
                se.uses
                    .iter()
                    .map(|&(u, same)| (live[u.face], u.lp, u.edge, same))
                    .collect()
            })
            .collect();
        // step 2: the edges not sampled yet for these uses
        let todo: Vec<&EdgeKey> = keys.iter().filter(|k| !sampled.contains_key(*k)).collect();
        let done: Vec<(EdgeKey, Result<EdgeSamples>)> = todo
            .par_iter()
            .map(|&k| (k.clone(), sample_shared_edge(&uses_of(k), tolerance)))
            .collect();
        let mut more = false;
        for (k, r) in done {
            match r {
                Ok(s) => {
                    sampled.insert(k, Arc::new(s));
                }
                Err(e) => {
                    more = true;
                    blame(&k, e, &uses_of, tolerance, &mut failed);
                }
            }
        }
        if more {
            continue;
        }
        // step 3: the faces whose edges' samples changed (all of them the first time)
        let face_samples = |li: usize| -> FaceSamples {
            let mut out = Vec::new();
            for (lp, l) in live_faces[li].loops().enumerate() {
                for edge in 0..l.edges().len() {
                    let u = EdgeUse { face: li, lp, edge };
                    out.push(shell.edge_of(u).and_then(|(g, same)| {
                        let [a, b] = corners(&shell, g, same);
                        Some((
                            sampled.get(&keys[g])?.clone(),
                            same,
                            [a.to_vec(), b.to_vec()],
                        ))
                    }));
                }
            }
            out
        };
        let todo: Vec<(usize, FaceSamples)> = (0..live.len())
            .map(|li| (li, face_samples(li)))
            .filter(|(li, fk)| meshed[live[*li]].as_ref().is_none_or(|(k, _)| k != fk))
            .collect();
        count += todo.len();
        let done: Vec<(usize, FaceSamples, Result<Mesh>)> = todo
            .into_par_iter()
            .filter_map(|(li, fk)| {
                let fi = live[li];
                let samples = |u: EdgeUse| -> Option<UseSamples<'_>> {
                    let (g, same) = shell.edge_of(u)?;
                    Some((
                        sampled.get(&keys[g])?.as_ref(),
                        same,
                        corners(&shell, g, same),
                    ))
                };
                let plan = plans[fi].as_ref()?;
                Some((fi, fk, mesh_face(plan, li, &samples, tolerance)))
            })
            .collect();
        let mut more = false;
        for (fi, fk, r) in done {
            match r {
                Ok(m) => meshed[fi] = Some((fk, m)),
                Err(e) => {
                    more = true;
                    meshed[fi] = None;
                    failed[fi] = Some(e);
                }
            }
        }
        if !more {
            break;
        }
    }
    let mut out = FaceMeshes {
        meshes: Vec::new(),
        failures: Vec::new(),
        above_tolerance: Vec::new(),
        repairs: Vec::new(),
    };
    out.repairs = repairs
        .into_iter()
        .filter(|(i, _)| failed[*i].is_none())
        .collect();
    let mut vertices = 0_usize;
    for (i, (f, m)) in failed.into_iter().zip(meshed).enumerate() {
        match (f, m) {
            (Some(e), _) => out.failures.push((i, e)),
            (None, Some((_, m))) => {
                vertices = vertices.saturating_add(m.vertices.len());
                if let Err(e) = check_deviation("the face's mesh", m.deviation, tolerance) {
                    out.above_tolerance.push((i, e));
                }
                out.meshes.push((i, m));
            }
            (None, None) => {}
        }
    }
    if vertices > MAX_MESH_VERTICES {
        return Err(Error::TooLarge {
            what: What::of(
                Arg::Tolerance,
                "vertices of the faces' meshes (make the tolerance larger)",
            ),
            size: vertices,
            max: MAX_MESH_VERTICES,
        });
    }
    Ok((out, count))
}

/// The points of the vertices at the start and end of a use of edge `g` of `shell` that runs
/// it the way its first use does (`same`) or backwards.
fn corners(shell: &Shell, g: usize, same: bool) -> [&[f64]; 2] {
    let e = &shell.edges()[g];
    let at = |v: usize| shell.vertices()[v].as_slice();
    let [a, b] = e.vertices.map(at);
    if same {
        [a, b]
    } else {
        [b, a]
    }
}

/// The faces to blame for an edge that could not be sampled for all its uses: those whose use
/// cannot be sampled alone, each with its own error; every face of the edge, with `e`, when
/// each use can be sampled alone.
fn blame<'a>(
    key: &EdgeKey,
    e: Error,
    uses_of: &dyn Fn(&EdgeKey) -> Vec<Use<'a>>,
    tolerance: f64,
    failed: &mut [Option<Error>],
) {
    let mut found = false;
    for &u in key {
        // a use alone runs the edge its own way
        let one = vec![(u.0, u.1, u.2, true)];
        if let Err(e1) = sample_shared_edge(&uses_of(&one), tolerance) {
            failed[u.0] = Some(e1);
            found = true;
        }
    }
    if !found {
        for &u in key {
            failed[u.0] = Some(e.clone());
        }
    }
}

impl Face {
    /// A triangle mesh of the face's trimmed region within `tolerance` ([`mesh_faces`] of the
    /// face alone).
    ///
    /// # Errors
    /// As [`mesh_faces`].
    pub fn mesh(&self, tolerance: f64) -> Result<Mesh> {
        let mut m = mesh_faces(&[self], tolerance)?;
        Ok(m.remove(0))
    }
}

/// The meshes as one: vertices and triangles in order, each vertex with its own face's
/// `(u, v)`, the deviation the largest.
///
/// # Errors
/// [`Error::Dimension`] when the meshes' points differ in dimension.
pub fn join_meshes<'a>(meshes: impl IntoIterator<Item = &'a Mesh>) -> Result<Mesh> {
    join(meshes.into_iter())
}

#[allow(clippy::cast_possible_truncation)] // vertex counts below MAX_MESH_VERTICES
fn join<'a>(meshes: impl Iterator<Item = &'a Mesh>) -> Result<Mesh> {
    let meshes = meshes.collect::<Vec<_>>();
    let dim = meshes.first().map_or(3, |m| m.vertices.dim());
    let mut flat = Vec::new();
    let mut uv = Vec::new();
    let mut triangles = Vec::new();
    let mut deviation = 0.0_f64;
    for m in &meshes {
        let base = uv.len() as u32;
        flat.extend_from_slice(m.vertices.as_slice());
        uv.extend_from_slice(&m.uv);
        triangles.extend(m.triangles.iter().map(|t| t.map(|k| k + base)));
        deviation = deviation.max(m.deviation);
    }
    for m in &meshes {
        if m.vertices.dim() != dim {
            return Err(Error::Dimension {
                what: "mesh vertices".into(),
                expected: dim,
                got: m.vertices.dim(),
            });
        }
    }
    Ok(Mesh {
        vertices: Points::from_flat(dim, flat)?,
        uv,
        triangles,
        deviation,
    })
}
