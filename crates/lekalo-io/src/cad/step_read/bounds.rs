//! What the topology tells about unbounded geometry: the parameter range of each line that
//! bounds edges (from the edges' vertices), and the points that bound the faces on each plane,
//! cylinder, cone and extrusion (vertices of the faces' edges and the control points of the
//! edges' curves, which contain the curves: P&T §2.3 and §4.2, convex hull property; or the
//! vertices of the triangulated faces that AP242 links to the surface).

use std::collections::{HashMap, HashSet};

use super::analytic::{Basis, FaceBounds};
use super::entities::Reader;
use super::{list, Instance, P};
use crate::object::Object;

/// The curve under an edge's geometry: `SURFACE_CURVE`, `SEAM_CURVE` and
/// `INTERSECTION_CURVE` stand for their 3-D curve (followed at most four deep).
fn curve_3d(rd: &Reader<'_>, mut id: u64) -> u64 {
    for _ in 0..4 {
        let Some(inst) = rd.p.instances.get(&id) else {
            return id;
        };
        let next = ["SURFACE_CURVE", "SEAM_CURVE", "INTERSECTION_CURVE"]
            .iter()
            .find_map(
                |n| match inst.get(n).and_then(|r| super::unnamed(r).first()) {
                    Some(P::Ref(c)) => Some(*c),
                    _ => None,
                },
            );
        match next {
            Some(c) => id = c,
            None => return id,
        }
    }
    id
}

fn reference(p: Option<&P>) -> Option<u64> {
    match p {
        Some(P::Ref(id)) => Some(*id),
        _ => None,
    }
}

/// `EDGE_CURVE(name, start, end, geometry, same_sense)`: its vertices' points and geometry.
fn edge(rd: &Reader<'_>, inst: &Instance<'_>) -> Option<(Vec<Vec<f64>>, u64)> {
    let r = inst.get("EDGE_CURVE")?;
    let mut points = Vec::with_capacity(2);
    for k in [1, 2] {
        let v = rd.p.instances.get(&reference(r.get(k))?)?;
        if let Some(q) = v.get("VERTEX_POINT").and_then(|r| r.get(1)) {
            if let Ok(p) = rd.location(q) {
                points.push(p);
            }
        }
    }
    Some((points, curve_3d(rd, reference(r.get(3))?)))
}

/// The parameter range over which each `LINE` carries edges: the parameters of the edges'
/// vertices on it.
pub(super) fn line_ranges(rd: &Reader<'_>) -> HashMap<u64, (f64, f64)> {
    let mut out: HashMap<u64, (f64, f64)> = HashMap::new();
    let mut lines: HashMap<u64, Option<Basis>> = HashMap::new();
    for inst in rd.p.instances.values() {
        let Some((points, geom)) = edge(rd, &inst) else {
            continue;
        };
        if !rd.p.instances.get(&geom).is_some_and(|g| g.has("LINE")) {
            continue;
        }
        let basis = lines.entry(geom).or_insert_with(|| rd.basis(geom).ok());
        let Some(basis) = basis else { continue };
        for p in points {
            if let Some(t) = basis.parameter_of(&p) {
                let r = out.entry(geom).or_insert((t, t));
                *r = (r.0.min(t), r.1.max(t));
            }
        }
    }
    out
}

/// The vertices of a `TRIANGULATED_FACE` or `COMPLEX_TRIANGULATED_FACE` (AP242, ISO 10303-42
/// §5: `name, coordinates, pnmax, normals, geometric_link, pnindex, …`) whose geometric link is
/// a surface of `wanted`: the points of its `COORDINATES_LIST` that `pnindex` names (all of them
/// when `pnindex` is empty), in millimetres. They lie on the surface and span the face.
/// `lists` keeps the coordinate lists parsed, by id: one list serves many faces.
fn triangulated<'a>(
    rd: &Reader<'a>,
    inst: &Instance<'_>,
    wanted: &HashSet<u64>,
    lists: &mut HashMap<u64, Option<Instance<'a>>>,
) -> Option<(u64, Vec<[f64; 3]>)> {
    let r = inst
        .get("TRIANGULATED_FACE")
        .or_else(|| inst.get("COMPLEX_TRIANGULATED_FACE"))?;
    let surface = reference(r.get(4)).filter(|s| wanted.contains(s))?;
    let lid = reference(r.get(1))?;
    let list_inst = lists
        .entry(lid)
        .or_insert_with(|| rd.p.instances.get(&lid))
        .as_ref()?;
    let coords = list_inst.get("COORDINATES_LIST")?.get(2).and_then(list)?;
    let point = |k: usize| -> Option<[f64; 3]> {
        let c = list(coords.get(k)?)?;
        let mut p = [0.0; 3];
        for (x, q) in p.iter_mut().zip(c) {
            *x = super::num(q)? * rd.scale;
        }
        (c.len() == 3).then_some(p)
    };
    let index = r.get(5).and_then(list).unwrap_or(&[]);
    let pts: Vec<[f64; 3]> = if index.is_empty() {
        (0..coords.len()).filter_map(point).collect()
    } else {
        index
            .iter()
            .filter_map(|i| super::int(i)?.checked_sub(1).and_then(point))
            .collect()
    };
    Some((surface, pts))
}

/// The points bounding the faces (`ADVANCED_FACE`, `FACE_SURFACE`) on each surface of
/// `wanted`. Each edge's points are gathered once; the control points copied in all are capped
/// at eight per instance of the file, beyond which only vertices are taken, so that the work
/// stays linear in the file's size even when many faces share long edges.
pub(super) fn face_bounds(
    rd: &Reader<'_>,
    wanted: &HashSet<u64>,
    curves: &HashMap<u64, Object>,
) -> FaceBounds {
    let mut bounds = FaceBounds::default();
    if wanted.is_empty() {
        return bounds;
    }
    let mut budget = rd.p.instances.len().saturating_mul(8);
    let mut lists = HashMap::new();
    for &id in rd.p.instances.ids() {
        let inst = rd.p.instances.known(&id);
        if let Some((surface, pts)) = triangulated(rd, &inst, wanted, &mut lists) {
            bounds.points.entry(surface).or_default().extend(pts);
            continue;
        }
        let Some(face) = inst
            .get("ADVANCED_FACE")
            .or_else(|| inst.get("FACE_SURFACE"))
        else {
            continue;
        };
        let Some(surface) = reference(face.get(2)) else {
            continue;
        };
        if !wanted.contains(&surface) {
            continue;
        }
        let mut pts: Vec<[f64; 3]> = Vec::new();
        let mut push = |p: &[f64]| {
            if let Ok(a) = <[f64; 3]>::try_from(p) {
                pts.push(a);
            }
        };
        for b in face.get(1).and_then(list).unwrap_or(&[]) {
            let Some(bound) = reference(Some(b)).and_then(|b| rd.p.instances.get(&b)) else {
                continue;
            };
            let Some(lp) = bound
                .get("FACE_OUTER_BOUND")
                .or_else(|| bound.get("FACE_BOUND"))
                .and_then(|r| reference(r.get(1)))
                .and_then(|l| rd.p.instances.get(&l))
            else {
                continue;
            };
            if let Some(v) = lp.get("VERTEX_LOOP").and_then(|r| reference(r.get(1))) {
                if let Some(v) = rd.p.instances.get(&v) {
                    if let Some(q) = v.get("VERTEX_POINT").and_then(|r| r.get(1)) {
                        if let Ok(p) = rd.location(q) {
                            push(&p);
                        }
                    }
                }
            }
            if let Some(poly) = lp.get("POLY_LOOP").and_then(|r| r.get(1)).and_then(list) {
                for q in poly {
                    if let Ok(p) = rd.location(q) {
                        push(&p);
                    }
                }
            }
            let edges = lp.get("EDGE_LOOP").and_then(|r| r.get(1)).and_then(list);
            for oe in edges.unwrap_or(&[]) {
                let Some(e) = reference(Some(oe))
                    .and_then(|o| rd.p.instances.get(&o))
                    .and_then(|o| reference(o.get("ORIENTED_EDGE")?.get(3)))
                    .and_then(|e| rd.p.instances.get(&e))
                else {
                    continue;
                };
                let Some((vertices, geom)) = edge(rd, &e) else {
                    continue;
                };
                vertices.iter().for_each(|p| push(p));
                if let Some(c) = curves.get(&geom) {
                    let cp = c.control_points();
                    if cp.dim() == 3 && cp.len() <= budget {
                        budget -= cp.len();
                        cp.as_slice().chunks_exact(3).for_each(&mut push);
                    }
                }
            }
        }
        bounds.points.entry(surface).or_default().extend(pts);
    }
    bounds
}
