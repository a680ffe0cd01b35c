//! Faces (ISO 10303-42 §5.4): `ADVANCED_FACE` and `FACE_SURFACE` with their bounds
//! (`FACE_OUTER_BOUND`, `FACE_BOUND`), `EDGE_LOOP`s of `ORIENTED_EDGE`s over `EDGE_CURVE`s
//! between `VERTEX_POINT`s, and the edges' curves in the surface's parameters (`PCURVE`s of a
//! `SURFACE_CURVE` or `SEAM_CURVE`, through their `DEFINITIONAL_REPRESENTATION`), read into
//! [`lekalo::Face`]s. A face whose surface or edges are not read is listed as skipped with the
//! reason.
//!
//! Pcurves are kept where their parameters are those of the surface lekalo holds: on B-spline
//! surfaces they are read as written; on planes, whose patch is parametrised by lengths along
//! the placement's axes, they are the 3-D edges in those coordinates (exact, whether or not the
//! file gives pcurves). Cylinders, cones,
//! spheres, tori and swept surfaces become NURBS whose parameters are not the angles of the
//! file, so their faces keep the 3-D edges only ([`StepFace::pcurves`] says why).

use std::collections::HashMap;

use lekalo::surface::Placement;
use lekalo::topology::{Edge, Face, Loop};
use lekalo::{BSplineCurve, Curve, NurbsCurve, Points};

use super::analytic::Basis;
use super::entities::{is_bspline_surface, Reader};
use super::progress::{Meter, Pass};
use super::skips::Skips;
use super::tessellated::{CoordinateCache, StepTriangulation, TRIANGULATED};
use super::{list, unnamed, StepSkipped, Why, P};
use crate::error::IoResult;
use crate::shape::Surface;

/// The tolerance on the gaps of a face's loops, relative to the model size (see
/// [`lekalo::topology::LOOP_CLOSURE_RTOL`]): `1e-3`, as exporters sew at tolerances up to 0.1 mm
/// on parts of 100 mm.
pub const STEP_LOOP_RTOL: f64 = 1e-3;

/// The tolerance on the gaps of a loop whose edges share their `VERTEX_POINT`s in the file (each
/// edge ends at the vertex where the next starts), relative to the model size: `1e-2`. Such a
/// loop is closed by the file's topology, and its gaps are those of curves that miss their
/// vertices by the exporter's precision (Open CASCADE widens the vertices' tolerances to cover
/// them); only a loop that the vertices do not close is held to [`STEP_LOOP_RTOL`].
pub const STEP_SHARED_VERTEX_RTOL: f64 = 1e-2;

/// A face read from a STEP file.
#[derive(Debug, Clone, PartialEq)]
pub struct StepFace {
    /// The face's instance id (`#id`).
    pub id: u64,
    /// The face's name as written (often empty).
    pub name: String,
    /// The id of its surface's instance.
    pub surface_id: u64,
    /// The face: surface, outer and inner loops, edges with their pcurves.
    pub face: Face,
    /// The `EDGE_CURVE` ids of each loop's edges, outer loop first (a seam edge appears twice).
    pub edge_ids: Vec<Vec<u64>>,
    /// Why the edges have no pcurves, when they have none (e.g. a cylinder's parameters).
    pub pcurves: Option<String>,
}

fn reference(p: Option<&P>) -> Option<u64> {
    match p {
        Some(P::Ref(id)) => Some(*id),
        _ => None,
    }
}

fn boolean(p: Option<&P>) -> Option<bool> {
    match p {
        Some(P::Enum(e)) if e == "T" => Some(true),
        Some(P::Enum(e)) if e == "F" => Some(false),
        _ => None,
    }
}

/// How the file's pcurves relate to the surface lekalo built for a face.
enum Pcurves {
    /// Read as written (a B-spline surface of the file).
    AsWritten,
    /// A plane: the pcurves are the 3-D edges in the placement's coordinates.
    Plane(Placement),
    /// Not kept: an analytic surface other than a plane, by its entity name.
    Dropped(String),
}

/// One use of an edge in a loop: its 3-D curve and candidate pcurves, directed along the loop.
struct Use {
    edge: u64,
    /// The ids of the vertices it starts and ends at, along the loop.
    vertices: [u64; 2],
    curve: Curve,
    pcurves: Vec<Curve>,
    /// Whether the file gives the edge pcurves (on any surface).
    written: bool,
}

/// The 3-D curve of an `EDGE_CURVE` from its start vertex to its end vertex, its vertices, the
/// pcurve ids of its geometry and `same_sense`.
struct EdgeGeom {
    curve: Curve,
    /// The parameters a spline was cut at, and its whole domain.
    cut_at: Option<(f64, f64)>,
    domain: Option<(f64, f64)>,
    /// The parameters of the start and end vertices on the 3-D curve as the file writes it.
    range: (f64, f64),
    /// The start and end vertices.
    ends: [Vec<f64>; 2],
    /// The ids of the start and end `VERTEX_POINT`s.
    vertices: [u64; 2],
    pcurves: Vec<u64>,
    same_sense: bool,
}

/// The faces a pass reads: those bounded by curves on a surface, the faces of triangles, and
/// those skipped with the reason.
pub(super) struct ReadFaces {
    pub(super) faces: Vec<StepFace>,
    pub(super) triangulations: Vec<StepTriangulation>,
    pub(super) skipped: Skips,
}

/// Reads every `ADVANCED_FACE` and `FACE_SURFACE` of the file, and every face or surface set
/// of triangles ([`TRIANGULATED`], read as meshes by `tessellated.rs`): the faces read, and those
/// skipped with the reason, counted by kind with at most `listed` of them kept. `surfaces` are
/// the surfaces read by id, `surface_skip` why another was not; `meter` is told the instances
/// looked at and can cancel the read; `enter` says whether a face is read in this pass and sets
/// the placement of its part.
pub(super) fn read_faces(
    rd: &Reader<'_>,
    ids: &[u64],
    surfaces: &HashMap<u64, &Surface>,
    surface_skip: &dyn Fn(u64) -> Option<Why>,
    listed: usize,
    meter: &Meter<'_>,
    enter: &dyn Fn(u64) -> bool,
) -> IoResult<ReadFaces> {
    let mut faces = Vec::new();
    let mut triangulations = Vec::new();
    let mut skipped = Skips::new(listed);
    let mut edges: HashMap<u64, Result<std::rc::Rc<EdgeGeom>, Why>> = HashMap::new();
    let mut coordinates = CoordinateCache::new();
    for (k, &id) in ids.iter().enumerate() {
        meter.converted(Pass::Faces, k, ids.len())?;
        if !enter(id) {
            continue;
        }
        let inst = rd.p.instances.known(&id);
        let Some((entity, r)) = ["ADVANCED_FACE", "FACE_SURFACE"]
            .iter()
            .find_map(|n| Some((*n, inst.get(n)?)))
        else {
            // a face of triangles (AP242 tessellated geometry): a mesh as given
            if let Some(entity) = TRIANGULATED.iter().find(|n| inst.has(n)) {
                match rd.triangulation(id, entity, &inst, &mut coordinates) {
                    Ok(t) => triangulations.push(t),
                    Err(reason) => skipped.push(StepSkipped {
                        id,
                        entity: (*entity).to_string(),
                        reason,
                    }),
                }
            }
            continue;
        };
        match read_face(rd, id, r, surfaces, surface_skip, &mut edges) {
            Ok(f) => faces.push(f),
            Err(reason) => skipped.push(StepSkipped {
                id,
                entity: entity.to_string(),
                reason,
            }),
        }
    }
    skipped.finish();
    Ok(ReadFaces {
        faces,
        triangulations,
        skipped,
    })
}

fn read_face(
    rd: &Reader<'_>,
    id: u64,
    r: &[P],
    surfaces: &HashMap<u64, &Surface>,
    surface_skip: &dyn Fn(u64) -> Option<Why>,
    edges: &mut HashMap<u64, Result<std::rc::Rc<EdgeGeom>, Why>>,
) -> Result<StepFace, Why> {
    let name = match r.first() {
        Some(P::Str(s)) => s.clone(),
        _ => String::new(),
    };
    let sid = reference(r.get(2)).ok_or("face_geometry is not a reference to a surface")?;
    let Some(surface) = surfaces.get(&sid) else {
        return Err(match surface_skip(sid) {
            Some(why) => format!("its surface #{sid} was not read: {why}"),
            None => match rd.p.instances.get(&sid) {
                Some(s) => format!(
                    "its surface #{sid} is a {}, not a surface lekalo reads",
                    s.type_name()
                ),
                None => format!("its surface #{sid} is not defined"),
            },
        });
    };
    let same_sense = boolean(r.get(3)).unwrap_or(true);
    let sinst = rd.p.instances.known(&sid);
    let policy = if is_bspline_surface(&sinst) {
        Pcurves::AsWritten
    } else if let Some(f) = rd.plane_placement(&sinst) {
        Pcurves::Plane(f)
    } else {
        Pcurves::Dropped(sinst.type_name().to_string())
    };
    // whether any edge of the face comes with pcurves in the file
    let mut written = false;
    let bounds = r
        .get(1)
        .and_then(list)
        .ok_or("bounds is not a list of face bounds")?;
    let mut outer: Option<(Loop, Vec<u64>)> = None;
    let mut inner: Vec<(Loop, Vec<u64>)> = Vec::new();
    let mut missing = 0usize;
    let mut pcurve_error: Option<String> = None;
    // whether every loop is closed by its shared vertices
    let mut closed_by_vertices = true;
    for b in bounds {
        let bid = reference(Some(b)).ok_or("a bound is not a reference")?;
        let binst =
            rd.p.instances
                .get(&bid)
                .ok_or_else(|| format!("bound #{bid} is not defined"))?;
        let (is_outer, br) = if let Some(br) = binst.get("FACE_OUTER_BOUND") {
            (true, br)
        } else if let Some(br) = binst.get("FACE_BOUND") {
            (false, br)
        } else {
            return Err(format!(
                "bound #{bid} is a {}, not a FACE_BOUND",
                binst.type_name()
            ));
        };
        let orientation = boolean(br.get(2)).unwrap_or(true);
        let lid = reference(br.get(1)).ok_or_else(|| format!("bound #{bid} has no loop"))?;
        let linst =
            rd.p.instances
                .get(&lid)
                .ok_or_else(|| format!("loop #{lid} is not defined"))?;
        if linst.has("VERTEX_LOOP") {
            // a loop of one vertex (the apex of a cone, the pole of a sphere) bounds nothing
            continue;
        }
        let lr = linst.get("EDGE_LOOP").ok_or_else(|| {
            format!(
                "loop #{lid} is a {}; lekalo reads EDGE_LOOPs",
                linst.type_name()
            )
        })?;
        let oes = lr
            .get(1)
            .and_then(list)
            .ok_or_else(|| format!("EDGE_LOOP #{lid} has no list of edges"))?;
        let mut uses = Vec::with_capacity(oes.len());
        for oe in oes {
            uses.push(edge_use(
                rd,
                oe,
                (sid, surface),
                &policy,
                edges,
                &mut pcurve_error,
            )?);
        }
        if !orientation {
            uses.reverse();
            for u in &mut uses {
                u.vertices.reverse();
                u.curve = u.curve.reverse().map_err(|e| e.to_string())?;
                for p in &mut u.pcurves {
                    *p = p.reverse().map_err(|e| e.to_string())?;
                }
            }
        }
        written |= uses.iter().any(|u| u.written);
        closed_by_vertices &= uses
            .iter()
            .zip(uses.iter().cycle().skip(1))
            .all(|(a, b)| a.vertices[1] == b.vertices[0]);
        let (edge_list, ids, no_pcurve) = choose_pcurves(uses)?;
        missing += no_pcurve;
        let lp = Loop::new(edge_list).map_err(|e| format!("EDGE_LOOP #{lid}: {e}"))?;
        if is_outer && outer.is_none() {
            outer = Some((lp, ids));
        } else {
            inner.push((lp, ids));
        }
    }
    // a face without a FACE_OUTER_BOUND: its first bound is taken as the outer one
    let (outer, outer_ids) = match outer {
        Some(o) => o,
        None if !inner.is_empty() => inner.remove(0),
        None => return Err("no EDGE_LOOP bounds the face".into()),
    };
    let mut edge_ids = vec![outer_ids];
    let mut inner_loops = Vec::with_capacity(inner.len());
    for (lp, ids) in inner {
        inner_loops.push(lp);
        edge_ids.push(ids);
    }
    let face = Face::new(
        (*surface).clone(),
        outer,
        inner_loops,
        same_sense,
        if closed_by_vertices {
            STEP_SHARED_VERTEX_RTOL
        } else {
            STEP_LOOP_RTOL
        },
    )
    .map_err(|e| e.to_string())?;
    let pcurves = match policy {
        Pcurves::Dropped(kind) if written => Some(format!(
            "the file's pcurves are in the parameters of its {kind}, not in those of the NURBS \
             surface lekalo builds for it"
        )),
        Pcurves::Dropped(kind) => Some(format!(
            "the file gives none, and lekalo computes pcurves from the 3-D edges only on planes, \
             not on its {kind}"
        )),
        _ if missing > 0 => Some(match pcurve_error {
            Some(why) => format!("{missing} edge(s) without a pcurve read: {why}"),
            None => format!("{missing} edge(s) have no pcurve on this face's surface"),
        }),
        _ => None,
    };
    Ok(StepFace {
        id,
        name,
        surface_id: sid,
        face,
        edge_ids,
        pcurves,
    })
}

/// Seam edges carry two pcurves on the same surface: each use takes the one that starts where
/// the previous edge's pcurve ends (the first use, with nothing before it, the one that ends
/// where the next starts, else the first). Returns the edges, their ids and the number without
/// a pcurve (in which case no edge of the loop keeps one).
fn choose_pcurves(uses: Vec<Use>) -> Result<(Vec<Edge>, Vec<u64>, usize), Why> {
    let end = |c: &Curve| c.eval(c.domain().1).ok();
    let start = |c: &Curve| c.eval(c.domain().0).ok();
    let dist = |a: Option<Vec<f64>>, b: Option<Vec<f64>>| match (a, b) {
        (Some(a), Some(b)) => a.iter().zip(&b).map(|(x, y)| (x - y) * (x - y)).sum(),
        _ => f64::INFINITY,
    };
    let n = uses.len();
    let mut chosen: Vec<Option<Curve>> = uses.iter().map(|u| u.pcurves.first().cloned()).collect();
    for k in 0..n {
        if uses[k].pcurves.len() < 2 {
            continue;
        }
        let prev = if k > 0 {
            chosen[k - 1].as_ref().and_then(end)
        } else {
            None
        };
        let best = if let Some(p) = prev {
            uses[k].pcurves.iter().min_by(|a, b| {
                dist(Some(p.clone()), start(a)).total_cmp(&dist(Some(p.clone()), start(b)))
            })
        } else {
            let next = chosen
                .get((k + 1) % n)
                .and_then(|c| c.as_ref())
                .and_then(start);
            uses[k]
                .pcurves
                .iter()
                .min_by(|a, b| dist(end(a), next.clone()).total_cmp(&dist(end(b), next.clone())))
        };
        chosen[k] = best.cloned();
    }
    let missing = chosen.iter().filter(|c| c.is_none()).count();
    let mut out = Vec::with_capacity(n);
    let mut ids = Vec::with_capacity(n);
    for (u, p) in uses.into_iter().zip(chosen) {
        ids.push(u.edge);
        let p = if missing > 0 { None } else { p };
        out.push(Edge::new(u.curve, p).map_err(|e| format!("edge #{}: {e}", u.edge))?);
    }
    Ok((out, ids, missing))
}

/// An `ORIENTED_EDGE(name, *, *, edge_element, orientation)` of the face on surface `sid`.
fn edge_use(
    rd: &Reader<'_>,
    oe: &P,
    (sid, surface): (u64, &Surface),
    policy: &Pcurves,
    edges: &mut HashMap<u64, Result<std::rc::Rc<EdgeGeom>, Why>>,
    pcurve_error: &mut Option<String>,
) -> Result<Use, Why> {
    let oid = reference(Some(oe)).ok_or("an edge of a loop is not a reference")?;
    let oinst =
        rd.p.instances
            .get(&oid)
            .ok_or_else(|| format!("edge #{oid} of a loop is not defined"))?;
    let or = oinst
        .get("ORIENTED_EDGE")
        .ok_or_else(|| format!("edge #{oid} of a loop is not an ORIENTED_EDGE"))?;
    let eid = reference(or.get(3)).ok_or_else(|| format!("ORIENTED_EDGE #{oid} has no edge"))?;
    let forward = boolean(or.get(4)).unwrap_or(true);
    let geom = edges
        .entry(eid)
        .or_insert_with(|| edge_geom(rd, eid).map(std::rc::Rc::new))
        .clone()?;
    let mut curve = geom.curve.clone();
    let mut vertices = geom.vertices;
    let mut pcurves = Vec::new();
    if let Pcurves::Plane(f) = policy {
        pcurves.push(on_plane(&curve, f)?);
    } else if matches!(policy, Pcurves::AsWritten) {
        for &pid in &geom.pcurves {
            match pcurve(rd, pid, sid, surface, &geom) {
                Ok(Some(p)) => pcurves.push(p),
                Ok(None) => {}
                Err(why) => {
                    pcurve_error.get_or_insert(why);
                }
            }
        }
    }
    if !forward {
        vertices.reverse();
        curve = curve.reverse().map_err(|e| e.to_string())?;
        for p in &mut pcurves {
            *p = p.reverse().map_err(|e| e.to_string())?;
        }
    }
    Ok(Use {
        edge: eid,
        vertices,
        curve,
        pcurves,
        written: !geom.pcurves.is_empty(),
    })
}

/// `EDGE_CURVE(name, edge_start, edge_end, edge_geometry, same_sense)`: the geometry's 3-D
/// curve cut at the vertices and directed from start to end.
fn edge_geom(rd: &Reader<'_>, eid: u64) -> Result<EdgeGeom, Why> {
    let inst =
        rd.p.instances
            .get(&eid)
            .ok_or_else(|| format!("edge #{eid} is not defined"))?;
    let r = inst
        .get("EDGE_CURVE")
        .ok_or_else(|| format!("edge #{eid} is a {}, not an EDGE_CURVE", inst.type_name()))?;
    let mut ends: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    let mut vertices = [0u64; 2];
    for (k, end) in ends.iter_mut().enumerate() {
        let vid =
            reference(r.get(k + 1)).ok_or_else(|| format!("EDGE_CURVE #{eid} has no vertex"))?;
        vertices[k] = vid;
        let vinst = rd.p.instances.get(&vid);
        let v = vinst
            .as_ref()
            .and_then(|v| v.get("VERTEX_POINT"))
            .ok_or_else(|| format!("vertex #{vid} of edge #{eid} is not a VERTEX_POINT"))?;
        *end = rd.location(v.get(1).ok_or("VERTEX_POINT without a point")?)?;
    }
    let gid = reference(r.get(3)).ok_or_else(|| format!("EDGE_CURVE #{eid} has no geometry"))?;
    let same_sense = boolean(r.get(4)).unwrap_or(true);
    // the geometry: a surface curve (its 3-D curve and pcurves) or a curve
    let mut pcurves = Vec::new();
    let mut cid = gid;
    if let Some(g) = rd.p.instances.get(&gid) {
        if g.has("PCURVE") {
            return Err(format!(
                "the geometry of edge #{eid} is the PCURVE #{gid}, without a 3-D curve"
            ));
        }
        if let Some(sr) = ["SURFACE_CURVE", "SEAM_CURVE", "INTERSECTION_CURVE"]
            .iter()
            .find_map(|n| g.get(n))
        {
            let sr = unnamed(sr);
            cid = reference(sr.first())
                .ok_or_else(|| format!("surface curve #{gid} has no 3-D curve"))?;
            for a in sr.get(1).and_then(list).unwrap_or(&[]) {
                if let Some(p) = reference(Some(a)) {
                    pcurves.push(p);
                }
            }
        }
    }
    let basis = rd.basis(cid).map_err(|why| format!("edge #{eid}: {why}"))?;
    let domain = match &basis {
        Basis::Spline(o) => Some(o.domain()),
        _ => None,
    };
    let (curve, cut_at) =
        cut(&basis, &ends, same_sense).map_err(|why| format!("edge #{eid}: {why}"))?;
    let range = match (&basis, cut_at) {
        (_, Some(r)) => r,
        (Basis::Spline(o), None) => {
            let (a, b) = o.domain();
            if same_sense {
                (a, b)
            } else {
                (b, a)
            }
        }
        _ => (
            basis.parameter_of(&ends[0]).unwrap_or(0.0),
            basis.parameter_of(&ends[1]).unwrap_or(0.0),
        ),
    };
    Ok(EdgeGeom {
        curve,
        cut_at,
        domain,
        range,
        ends,
        vertices,
        pcurves,
        same_sense,
    })
}

/// The piece of `basis` from the vertex `ends[0]` to `ends[1]`, along the curve when
/// `same_sense` (a whole closed conic when the vertices coincide), and the parameters it was
/// cut at on a spline. A spline is cut at the parameters of its points nearest the vertices
/// (P&T §6.1, point projection), and kept whole when they are its ends or coincide (a closed
/// edge).
fn cut(
    basis: &Basis,
    ends: &[Vec<f64>; 2],
    same_sense: bool,
) -> Result<(Curve, Option<(f64, f64)>), Why> {
    let lib = |e: lekalo::Error| e.to_string();
    match basis {
        Basis::Spline(o) => {
            let (a, b) = o.domain();
            // vertices written as the curve's own end points (the common case) are its ends:
            // no projection needed
            let (pa, pb) = (o.eval(a).map_err(lib)?, o.eval(b).map_err(lib)?);
            if (ends[0] == pa && ends[1] == pb) || (ends[0] == pb && ends[1] == pa) {
                let c = if same_sense {
                    o.clone()
                } else {
                    o.reverse().map_err(lib)?
                };
                return Ok((c, None));
            }
            let q = o.to_query().map_err(lib)?;
            let t0 = q.project(&ends[0]).map_err(lib)?.t;
            let t1 = q.project(&ends[1]).map_err(lib)?.t;
            let whole = (t0 - t1).abs() <= 1e-9 * (b - a)
                || ((t0.min(t1) - a).abs() <= 1e-9 * (b - a)
                    && (t0.max(t1) - b).abs() <= 1e-9 * (b - a));
            if whole {
                let c = if same_sense {
                    o.clone()
                } else {
                    o.reverse().map_err(lib)?
                };
                Ok((c, None))
            } else {
                Ok((basis.piece(t0, t1, same_sense)?, Some((t0, t1))))
            }
        }
        _ => {
            let t0 = basis
                .parameter_of(&ends[0])
                .ok_or("the start vertex has no parameter on the curve")?;
            let t1 = basis
                .parameter_of(&ends[1])
                .ok_or("the end vertex has no parameter on the curve")?;
            if matches!(basis, Basis::Line { .. }) {
                // a line's edge runs from the start vertex to the end one
                let seg = basis.piece(t0.min(t1), t0.max(t1), true)?;
                let seg = if t0 > t1 {
                    seg.reverse().map_err(lib)?
                } else {
                    seg
                };
                return Ok((seg, None));
            }
            Ok((basis.piece(t0, t1, same_sense)?, None))
        }
    }
}

/// The 3-D edge `c` in the coordinates of the plane `f`: the affine map taken by the control
/// points, exact for B-splines and NURBS (P&T §4.2, affine invariance).
fn on_plane(c: &Curve, f: &Placement) -> Result<Curve, Why> {
    let pts = c.control_points();
    let mut data = Vec::with_capacity(pts.len() * 2);
    for p in pts.iter() {
        let q = <[f64; 3]>::try_from(p).map_err(|_| "an edge is not 3-D".to_string())?;
        let uv = f.coordinates(q);
        data.extend([uv[0], uv[1]]);
    }
    let pts = Points::from_flat(2, data).map_err(|e| e.to_string())?;
    let knots = c.knots().as_slice().to_vec();
    Ok(match c.weights() {
        None => Curve::from(BSplineCurve::new(c.degree(), knots, pts).map_err(|e| e.to_string())?),
        Some(w) => {
            Curve::from(NurbsCurve::new(c.degree(), knots, pts, w).map_err(|e| e.to_string())?)
        }
    })
}

/// The pcurve `pid` if it lies on the surface `sid`: `PCURVE(name, basis_surface,
/// reference_to_curve)` whose `DEFINITIONAL_REPRESENTATION` holds a 2-D B-spline; directed
/// from the edge's start to its end, and cut where the 3-D curve was when both share their
/// parameters. `Ok(None)` for a pcurve on another surface.
fn pcurve(
    rd: &Reader<'_>,
    pid: u64,
    sid: u64,
    surface: &Surface,
    edge: &EdgeGeom,
) -> Result<Option<Curve>, Why> {
    let pinst = rd.p.instances.get(&pid);
    let Some(pr) = pinst.as_ref().and_then(|p| p.get("PCURVE")) else {
        return Ok(None);
    };
    let pr = unnamed(pr);
    if reference(pr.first()) != Some(sid) {
        return Ok(None);
    }
    let did = reference(pr.get(1)).ok_or_else(|| format!("PCURVE #{pid} has no representation"))?;
    let dinst = rd.p.instances.get(&did);
    let item = dinst
        .as_ref()
        .and_then(|d| d.get("DEFINITIONAL_REPRESENTATION"))
        .and_then(|d| unnamed(d).first())
        .and_then(list)
        .and_then(|items| reference(items.first()))
        .ok_or_else(|| {
            format!("PCURVE #{pid}: #{did} is not a DEFINITIONAL_REPRESENTATION of a curve")
        })?;
    let basis = rd
        .basis(item)
        .map_err(|why| format!("PCURVE #{pid}: {why}"))?;
    let lib = |e: lekalo::Error| e.to_string();
    let (t0, t1) = edge.range;
    let curve = match &basis {
        Basis::Spline(o) => match edge.cut_at {
            Some((t0, t1)) if Some(o.domain()) == edge.domain => {
                basis.piece(t0, t1, edge.same_sense)?
            }
            _ if edge.same_sense => o.clone(),
            _ => o.reverse().map_err(lib)?,
        },
        // a line or conic in (u, v) on the parameters of the 3-D curve (the same parameter
        // range, as exporters write them), checked at the vertices below
        Basis::Line { .. } => {
            let seg = basis.piece(t0.min(t1), t0.max(t1), true)?;
            if t0 > t1 {
                seg.reverse().map_err(lib)?
            } else {
                seg
            }
        }
        Basis::Ellipse { .. } => basis.piece(t0, t1, edge.same_sense)?,
    };
    if curve.dim() != 2 {
        return Err(format!(
            "PCURVE #{pid}: its curve #{item} has {} coordinates, not the 2 of a surface's (u, v)",
            curve.dim()
        ));
    }
    // S(p(t)) must meet the edge's vertices: the same check as the loops' closure
    let tol = STEP_LOOP_RTOL * size_of(surface);
    let (a, b) = curve.domain();
    for (t, v) in [(a, &edge.ends[0]), (b, &edge.ends[1])] {
        let uv = curve.eval(t).map_err(lib)?;
        let on = surface.eval(uv[0], uv[1]).map_err(lib)?;
        let d = on
            .iter()
            .zip(v)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt();
        if d.is_nan() || d > tol {
            return Err(format!(
                "PCURVE #{pid} does not run between its edge's vertices on the surface ({d:.3e} from a vertex, tolerance {tol:.3e})"
            ));
        }
    }
    Ok(Some(curve))
}

/// The diagonal of the box of a surface's control points (which contain it).
fn size_of(s: &Surface) -> f64 {
    s.control_points().bounding_box().map_or(0.0, |(lo, hi)| {
        lo.iter()
            .zip(&hi)
            .map(|(a, b)| (b - a) * (b - a))
            .sum::<f64>()
            .sqrt()
    })
}
