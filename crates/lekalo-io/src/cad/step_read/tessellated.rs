//! Faces of triangles (AP242 tessellated geometry, ISO 10303-42 ed. 4, geometric model schema:
//! `tessellated_face` and `tessellated_surface_set` with their subtypes): `TRIANGULATED_FACE`,
//! `COMPLEX_TRIANGULATED_FACE`, `TRIANGULATED_SURFACE_SET` and
//! `COMPLEX_TRIANGULATED_SURFACE_SET`, read as triangle meshes ([`StepTriangulation`]) with
//! their triangles as given: nothing is re-meshed.
//!
//! Attributes after the name: `coordinates` (a `COORDINATES_LIST(name, npoints, ((x, y, z), …))`),
//! `pnmax` (the number of points the face uses), `normals` (none, one for a planar face, or one
//! per point), for a face an optional `geometric_link` (the surface or face the triangles
//! approximate), `pnindex` (empty, or `pnmax` 1-based indices into the coordinates), then the
//! triangles: a list of index triples, or for the complex forms `triangle_strips` and
//! `triangle_fans`. The triangles' indices run from 1 to `pnmax` and name the points through
//! `pnindex` when it is given (point `k` is `coordinates[pnindex[k]]`), directly otherwise.
//!
//! Strips and fans are decoded as in ISO 10303-42 (the convention of OpenGL's strips and fans):
//! a strip `(p1, p2, p3, p4, …)` gives `(p1, p2, p3)`, `(p3, p2, p4)`, `(p3, p4, p5)`, …: the
//! orientation alternates so that every triangle turns the way the first does; a fan
//! `(p1, p2, p3, p4, …)` gives `(p1, p2, p3)`, `(p1, p3, p4)`, …. A triangle two of whose
//! indices are equal (strips repeat an index to turn or to join) has no area and is dropped
//! (counted in [`StepTriangulation::dropped`]). On the AP242 file of the NIST test case FTC 08
//! every one of the 3370 triangles so decoded turns about the normals the file gives at its
//! points.
//!
//! Coordinates are converted to millimetres like every STEP point; normals are directions and
//! are not scaled. Both follow the placement of their part in an assembly. Sizes are charged
//! against the read's size limit before anything is allocated; an index of 0 or past `pnmax`,
//! a list of the wrong length, a strip or fan of fewer than 3 indices, a non-finite coordinate
//! or normal refuse the face with the reason.

use std::collections::HashMap;
use std::rc::Rc;

use lekalo::query::Mesh;
use lekalo::Points;

use super::entities::Reader;
use super::{int, list, num, Instance, Why, P};

/// The entities read as triangle meshes.
pub(super) const TRIANGULATED: &[&str] = &[
    "TRIANGULATED_FACE",
    "COMPLEX_TRIANGULATED_FACE",
    "TRIANGULATED_SURFACE_SET",
    "COMPLEX_TRIANGULATED_SURFACE_SET",
];

/// A face of triangles read from a STEP file: its points (in millimetres), its triangles as
/// the file gives them (strips and fans decoded), and its normals.
#[derive(Debug, Clone, PartialEq)]
pub struct StepTriangulation {
    /// The instance id (`#id`).
    pub id: u64,
    /// The entity, e.g. `COMPLEX_TRIANGULATED_FACE`.
    pub entity: String,
    /// Its name as written (often empty).
    pub name: String,
    /// The surface or face the triangles approximate (`geometric_link`), when given.
    pub link: Option<u64>,
    /// The points of the face, `pnmax` of them, point `k` the face's index `k + 1`: 3-D, in
    /// millimetres.
    pub vertices: Points,
    /// The triangles, as 0-based indices into [`StepTriangulation::vertices`], each turning
    /// counter-clockwise about the face's side the file's normals point to.
    pub triangles: Vec<[u32; 3]>,
    /// The normals as given: none, one for the whole face (a planar face), or one per vertex.
    pub normals: Vec<[f64; 3]>,
    /// Triangles of no area dropped (two equal indices, as strips write to turn or join).
    pub dropped: usize,
}

impl StepTriangulation {
    /// The triangles as a [`Mesh`] of the library, to be written or joined with meshed faces:
    /// the same vertices and triangles, `uv` all `(0, 0)` (a triangulation has no surface
    /// parameters), and `deviation` 0: the triangles are the file's geometry, not an
    /// approximation lekalo made.
    #[must_use]
    pub fn to_mesh(&self) -> Mesh {
        Mesh {
            vertices: self.vertices.clone(),
            uv: vec![[0.0, 0.0]; self.vertices.len()],
            triangles: self.triangles.clone(),
            deviation: 0.0,
        }
    }

    /// The unit normals of the vertices from the file's, for a mesh file's `vn` lines
    /// ([`crate::mesh_text_with_normals`]): one per vertex, the file's normal of the vertex (or
    /// of the whole face, for a planar face that gives one) scaled to unit length; a zero
    /// normal takes the area-weighted average of the normals of its triangles
    /// ([`lekalo::query::Mesh::vertex_normals`]). Empty when the file gives no normals: the
    /// triangles' own are the facets'.
    #[must_use]
    pub fn vertex_normals(&self) -> Vec<Option<[f64; 3]>> {
        let given: Vec<Option<[f64; 3]>> = match self.normals.len() {
            0 => return Vec::new(),
            1 => vec![Some(self.normals[0]); self.vertices.len()],
            _ => self.normals.iter().copied().map(Some).collect(),
        };
        self.to_mesh().vertex_normals(&given)
    }
}

/// The coordinate lists converted to millimetres, by id: one list serves many faces.
pub(super) type CoordinateCache = HashMap<u64, Rc<Vec<[f64; 3]>>>;

/// A list of 1-based indices `p` in `1..=max` (`bound` names `max` in messages), as `what`
/// names the list.
fn indices(p: &P, max: usize, bound: &str, what: &dyn Fn() -> String) -> Result<Vec<u32>, Why> {
    let l = list(p).ok_or_else(|| format!("{} is not a list of indices", what()))?;
    l.iter()
        .enumerate()
        .map(|(k, q)| match int(q) {
            Some(0) => Err(format!(
                "{} has index 0 at position {}: indices start at 1",
                what(),
                k + 1
            )),
            Some(i) if i <= max => {
                u32::try_from(i - 1).map_err(|_| format!("{}: index {i} too large", what()))
            }
            Some(i) => Err(format!(
                "{} has index {i} at position {}, past {bound}",
                what(),
                k + 1
            )),
            None => Err(format!(
                "{} has a value at position {} that is not a positive integer",
                what(),
                k + 1
            )),
        })
        .collect()
}

/// Three finite numbers.
fn triple(p: &P, what: &dyn Fn() -> String) -> Result<[f64; 3], Why> {
    let l = list(p).ok_or_else(|| format!("{} is not a list of 3 numbers", what()))?;
    if l.len() != 3 {
        return Err(format!("{} has {} numbers, not 3", what(), l.len()));
    }
    let mut out = [0.0; 3];
    for (x, q) in out.iter_mut().zip(l) {
        *x = num(q).ok_or_else(|| format!("{} is not a list of 3 numbers", what()))?;
        if !x.is_finite() {
            return Err(format!("{} is not finite", what()));
        }
    }
    Ok(out)
}

/// Pushes the triangle `t` unless two of its indices are equal (then counts it as dropped).
fn push(out: &mut Vec<[u32; 3]>, dropped: &mut usize, t: [u32; 3]) {
    if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
        *dropped += 1;
    } else {
        out.push(t);
    }
}

/// The triangles of a strip (ISO 10303-42; see the module docs): triangle `k` is
/// `(s[k], s[k+1], s[k+2])` for even `k` and `(s[k+1], s[k], s[k+2])` for odd `k`.
pub(super) fn strip_triangles(s: &[u32], out: &mut Vec<[u32; 3]>, dropped: &mut usize) {
    for (k, w) in s.windows(3).enumerate() {
        let t = if k % 2 == 0 {
            [w[0], w[1], w[2]]
        } else {
            [w[1], w[0], w[2]]
        };
        push(out, dropped, t);
    }
}

/// The triangles of a fan: `(f[0], f[k], f[k+1])` for `k ≥ 1`.
pub(super) fn fan_triangles(f: &[u32], out: &mut Vec<[u32; 3]>, dropped: &mut usize) {
    for w in f.get(1..).unwrap_or(&[]).windows(2) {
        push(out, dropped, [f[0], w[0], w[1]]);
    }
}

impl Reader<'_> {
    /// The points of `COORDINATES_LIST` `#lid`, in millimetres, converted once per read.
    fn coordinates(&self, lid: u64, cache: &mut CoordinateCache) -> Result<Rc<Vec<[f64; 3]>>, Why> {
        if let Some(c) = cache.get(&lid) {
            return Ok(Rc::clone(c));
        }
        let inst = self
            .p
            .instances
            .get(&lid)
            .ok_or_else(|| format!("its coordinates #{lid} are not defined"))?;
        let r = inst.get("COORDINATES_LIST").ok_or_else(|| {
            format!(
                "its coordinates #{lid} are a {}, not a COORDINATES_LIST",
                inst.type_name()
            )
        })?;
        let npoints = r
            .get(1)
            .and_then(int)
            .ok_or_else(|| format!("COORDINATES_LIST #{lid}: npoints is not an integer"))?;
        let pts = r
            .get(2)
            .and_then(list)
            .ok_or_else(|| format!("COORDINATES_LIST #{lid}: position_coords is not a list"))?;
        if pts.len() != npoints || npoints == 0 {
            return Err(format!(
                "COORDINATES_LIST #{lid} declares {npoints} points and lists {}",
                pts.len()
            ));
        }
        self.charge(npoints, "mesh coordinates")?;
        let mut out = Vec::with_capacity(npoints);
        for (k, q) in pts.iter().enumerate() {
            let mut p = triple(q, &|| format!("point {} of COORDINATES_LIST #{lid}", k + 1))?;
            for x in &mut p {
                *x *= self.scale;
                if !x.is_finite() {
                    return Err(format!(
                        "point {} of COORDINATES_LIST #{lid} is not finite in millimetres",
                        k + 1
                    ));
                }
            }
            out.push(p);
        }
        let out = Rc::new(out);
        cache.insert(lid, Rc::clone(&out));
        Ok(out)
    }

    /// The triangle mesh of `inst` (`#id`, one of [`TRIANGULATED`], named `entity`), or why it
    /// cannot be read.
    pub(super) fn triangulation(
        &self,
        id: u64,
        entity: &str,
        inst: &Instance<'_>,
        cache: &mut CoordinateCache,
    ) -> Result<StepTriangulation, Why> {
        let r = inst.get(entity).ok_or("no record of its entity")?;
        let face = entity.ends_with("FACE");
        let complex = entity.starts_with("COMPLEX");
        // name, coordinates, pnmax, normals, [geometric_link], pnindex, triangles | strips, fans
        let first = if face { 5 } else { 4 };
        let expected = first + if complex { 3 } else { 2 };
        if r.len() != expected {
            return Err(format!("{} attributes, a {entity} has {expected}", r.len()));
        }
        let name = match &r[0] {
            P::Str(s) => s.clone(),
            _ => String::new(),
        };
        let lid = match &r[1] {
            P::Ref(l) => *l,
            _ => return Err("coordinates is not a reference to a COORDINATES_LIST".into()),
        };
        let pnmax = int(&r[2]).ok_or("pnmax is not a non-negative integer")?;
        let link = match (face, &r[4]) {
            (true, P::Ref(s)) => Some(*s),
            _ => None,
        };
        let coords = self.coordinates(lid, cache)?;
        let pnindex = indices(
            &r[first],
            coords.len(),
            &format!("the {} points of COORDINATES_LIST #{lid}", coords.len()),
            &|| "pnindex".into(),
        )?;
        if pnindex.is_empty() && pnmax != coords.len() {
            return Err(format!(
                "pnmax {pnmax} without pnindex, but COORDINATES_LIST #{lid} has {} points",
                coords.len()
            ));
        }
        if !pnindex.is_empty() && pnindex.len() != pnmax {
            return Err(format!(
                "pnmax {pnmax}, but pnindex lists {} points",
                pnindex.len()
            ));
        }
        if pnmax == 0 {
            return Err("pnmax 0: a face of no points".into());
        }
        let normals_in = list(&r[3]).ok_or("normals is not a list")?;
        if !matches!(normals_in.len(), 0 | 1) && normals_in.len() != pnmax {
            return Err(format!(
                "{} normals for pnmax {pnmax} points; there are 0, 1 or pnmax",
                normals_in.len()
            ));
        }
        // sizes from the lists as written, charged before the points and triangles are made
        let lists = |k: usize| list(&r[k]).ok_or_else(|| format!("attribute {k} is not a list"));
        let count = if complex {
            let mut n = 0usize;
            for k in [first + 1, first + 2] {
                for s in lists(k)? {
                    n = n.saturating_add(list(s).map_or(0, |s| s.len().saturating_sub(2)));
                }
            }
            n
        } else {
            lists(first + 1)?.len()
        };
        self.charge(pnmax.saturating_add(count), "mesh points and triangles")?;
        let motion = self.motion.get();
        let mut flat = Vec::with_capacity(pnmax * 3);
        for k in 0..pnmax {
            let at = pnindex.get(k).map_or(k, |&i| i as usize);
            let mut p = coords[at];
            if let Some(m) = motion {
                m.point(&mut p);
            }
            flat.extend_from_slice(&p);
        }
        let vertices = Points::from_flat(3, flat).map_err(|e| e.to_string())?;
        let mut normals = Vec::with_capacity(normals_in.len());
        for (k, q) in normals_in.iter().enumerate() {
            let mut n = triple(q, &|| format!("normal {}", k + 1))?;
            if let Some(m) = motion {
                m.direction(&mut n);
            }
            normals.push(n);
        }
        let mut triangles = Vec::with_capacity(count);
        let mut dropped = 0;
        if complex {
            for (k, kind) in [(first + 1, "triangle strip"), (first + 2, "triangle fan")] {
                for (j, s) in lists(k)?.iter().enumerate() {
                    let what = || format!("{kind} {}", j + 1);
                    let s = indices(s, pnmax, &format!("pnmax {pnmax}"), &what)?;
                    if s.len() < 3 {
                        return Err(format!("{} has {} indices, fewer than 3", what(), s.len()));
                    }
                    if k == first + 1 {
                        strip_triangles(&s, &mut triangles, &mut dropped);
                    } else {
                        fan_triangles(&s, &mut triangles, &mut dropped);
                    }
                }
            }
        } else {
            for (j, t) in lists(first + 1)?.iter().enumerate() {
                let what = || format!("triangle {}", j + 1);
                let t = indices(t, pnmax, &format!("pnmax {pnmax}"), &what)?;
                let [a, b, c] = t[..] else {
                    return Err(format!("{} has {} indices, not 3", what(), t.len()));
                };
                push(&mut triangles, &mut dropped, [a, b, c]);
            }
        }
        if triangles.is_empty() {
            return Err(format!(
                "no triangle of any area ({dropped} with two equal indices)"
            ));
        }
        Ok(StepTriangulation {
            id,
            entity: entity.to_string(),
            name,
            link,
            vertices,
            triangles,
            normals,
            dropped,
        })
    }
}
