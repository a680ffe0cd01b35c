//! IGES trimmed surfaces (entity 144, IGES 5.3 §4.34) read as [`lekalo::topology::Face`]s:
//! the surface, an outer boundary and inner boundaries, each a curve on a parametric surface
//! (entity 142, §4.32) holding the curve in the surface's parameters (`BPTR`) and the curve in
//! model space (`CPTR`); a composite curve (entity 102, §4.4) splits into one edge per
//! constituent, in its order. Each edge is directed as the boundary runs.
//!
//! Entity 144: `PTS, N1, N2, PTO, PTI(1)…PTI(N2)`; `N1 = 0` (or `PTO = 0`) says the outer
//! boundary is the boundary of the surface's domain, read as the four iso-parametric edges
//! `v = v0`, `u = u1`, `v = v1`, `u = u0` counter-clockwise in `(u, v)`. Entity 142:
//! `CRTN, SPTR, BPTR, CPTR, PREF`. Parameter-space curves are stored as 3-D curves with
//! `z = 0` in the units of the surface's parameters: they are read without the length unit and
//! kept as 2-D pcurves. The surfaces lekalo reads from IGES (128, and 114 converted exactly on
//! its own breakpoints) keep the file's parameters, so the pcurves apply as written.
//!
//! A bounded surface (entity 143, §4.33: `TYPE, SPTR, N, BDPT(1)…BDPT(N)`) is read the same
//! way, its first boundary the outer loop; each boundary (entity 141, §4.31: `TYPE, PREF, SPTR,
//! N`, then per curve `CRVPT, SENSE, K, PSCPT(1)…PSCPT(K)`) lists model-space curves, each with
//! its parameter-space curves, reversed where `SENSE = 2`.
//!
//! A surface (128 or 114) whose directory entry says it is independent (subordinate entity
//! switch `00`) and that no trimmed or bounded surface or boundary refers to is a face of its own,
//! untrimmed: its outer loop is the boundary of its domain, as for `N1 = 0`. Open CASCADE's
//! IGES reader makes the same face of it.
//!
//! A face whose surface, boundary or model-space curves are not read is listed as skipped with
//! the reason; edges whose parameter-space curves are missing or do not match the model-space
//! pieces are kept without pcurves, with the reason in [`StepFace::pcurves`].

use std::cell::Cell;
use std::collections::HashMap;

use lekalo::topology::{Edge, Face, Loop};
use lekalo::{BSplineCurve, Curve, Direction, NurbsCurve, Points};

use super::{read_entities, IgesRead};
use crate::error::{IoError, IoResult};
use crate::shape::{Shape, Surface};
use crate::step_read::{StepFace, StepSkipped, STEP_LOOP_RTOL};

/// The parameter data of an entity the faces are built from (102, 141, 142, 143, 144).
pub(super) struct Raw {
    /// The entity type, e.g. `144`.
    pub(super) ty: String,
    /// The parameters, the entity type first.
    pub(super) fields: Vec<String>,
    /// True when the directory entry points at a transformation matrix.
    pub(super) matrix: bool,
}

/// Composite curves nested deeper than this are refused; real files nest one or two (a cycle
/// is refused as such before this depth is reached).
const MAX_NESTING: usize = 8;

/// Reads an IGES file as [`super::read_iges_limited`] does and, in [`IgesRead::faces`], its
/// trimmed surfaces (entity 144), bounded surfaces (entity 143) and independent surfaces that
/// nothing bounds (untrimmed, see the module docs) as faces, in the order of the file; the ones
/// that cannot be read are in [`IgesRead::skipped_faces`] with the reason. In each
/// [`StepFace`], `id` is the sequence number of the 144's (or 143's, or the untrimmed
/// surface's) directory entry, `surface_id` the surface's, `edge_ids` the model-space
/// curves' (0 for the edges of an untrimmed outer boundary) and `name` is empty. Loops must
/// close within [`STEP_LOOP_RTOL`] of the model size. The control points copied into faces
/// count against `max_size` as well.
///
/// # Errors
/// As [`super::read_iges_limited`]; [`IoError::OverLimit`] when the faces' surfaces and edges
/// hold more than `max_size` control points together, or the composite curves of their
/// boundaries copy more than that out of the curves they list.
pub fn read_iges_faces(text: &str, source: &str, max_size: usize) -> IoResult<IgesRead> {
    read_faces_with_progress(
        text,
        source,
        max_size,
        crate::step_read::SKIPPED_LISTED,
        &lekalo::Progress::new(),
    )
}

/// [`read_iges_faces`] reporting the directory entries read to `progress`
/// ([`super::read_iges_with_progress`]).
pub(super) fn read_faces_with_progress(
    text: &str,
    source: &str,
    max_size: usize,
    listed: usize,
    progress: &lekalo::Progress<'_>,
) -> IoResult<IgesRead> {
    let (mut r, raw, independent, reasons, foreign) =
        read_entities(text, source, max_size, true, listed, progress)?;
    let mut cx = Faces {
        curves: HashMap::new(),
        surfaces: HashMap::new(),
        skips: reasons
            .iter()
            .map(|(id, why)| (*id, why.as_str()))
            .collect(),
        raw: &raw,
        foreign: &foreign,
        unit: r.scale_to_mm,
        max_size,
        spent: Cell::new(0),
        over: Cell::new(None),
    };
    for (id, s) in &r.shapes {
        match s {
            Shape::Curve(c) => {
                cx.curves.insert(*id, c);
            }
            Shape::Surface(s) => {
                cx.surfaces.insert(*id, s);
            }
            _ => {}
        }
    }
    // an independent surface (114, 128) that no trimmed or bounded surface, nor a boundary,
    // refers to is a face of its own, bounded by its domain, as Open CASCADE reads it
    let bounded: std::collections::HashSet<u64> = raw
        .iter()
        .filter_map(|(id, e)| {
            let k = match e.ty.as_str() {
                "144" => 1,
                "142" | "143" => 2,
                "141" => 3,
                _ => return None,
            };
            Faces::pointer(e, *id, k, "the surface").ok()
        })
        .collect();
    let mut ids: Vec<(u64, bool)> = raw
        .iter()
        .filter(|(_, e)| e.ty == "144" || e.ty == "143")
        .map(|(id, _)| (*id, true))
        .chain(
            independent
                .into_iter()
                .filter(|id| cx.surfaces.contains_key(id) && !bounded.contains(id))
                .map(|id| (id, false)),
        )
        .collect();
    ids.sort_unstable();
    let mut faces = Vec::new();
    let mut skipped = crate::step_read::Skips::new(listed);
    let mut used = 0usize;
    for (id, trimmed) in ids {
        let read = if trimmed {
            cx.face(id)
        } else {
            cx.untrimmed(id)
        };
        match read {
            Ok(f) => {
                let points = f.face.surface().control_points().len()
                    + f.face
                        .loops()
                        .flat_map(Loop::edges)
                        .map(|e| e.curve().control_points().len())
                        .sum::<usize>();
                used = used.saturating_add(points);
                if used > max_size {
                    return Err(IoError::OverLimit {
                        what: format!(
                            "{source}: face D{id}: {used} control points in the faces read so far, above the size limit {max_size}"
                        ),
                        limit: crate::Limit::Size,
                        raise_to: Some(used as u64),
                    });
                }
                faces.push(f);
            }
            Err(reason) if cx.over.get().is_some() => {
                return Err(IoError::OverLimit {
                    what: format!(
                        "{source}: face D{id}: {reason}; composite curves that list the same curves many times expand to that many copies"
                    ),
                    limit: crate::Limit::Size,
                    raise_to: Some(cx.spent.get() as u64),
                });
            }
            Err(reason) => skipped.push(StepSkipped {
                id,
                entity: if trimmed {
                    format!("IGES entity {}", raw[&id].ty)
                } else {
                    "IGES independent surface".into()
                },
                reason,
            }),
        }
    }
    r.faces = faces;
    skipped.finish();
    r.skipped_faces = skipped;
    Ok(r)
}

/// What the faces are built from.
struct Faces<'a> {
    curves: HashMap<u64, &'a Curve>,
    surfaces: HashMap<u64, &'a Surface>,
    skips: HashMap<u64, &'a str>,
    raw: &'a HashMap<u64, Raw>,
    /// The analytic surfaces (108, 190–198): their NURBS parameters are not IGES's, so the
    /// parameter-space curves of their boundaries are not used.
    foreign: &'a std::collections::HashSet<u64>,
    unit: f64,
    /// The read's size limit (`--max-size`), in control points.
    max_size: usize,
    /// Control points copied out of curves into boundaries so far, by every face.
    spent: Cell<usize>,
    /// The curve at which `spent` passed `max_size`, once it has.
    over: Cell<Option<u64>>,
}

/// A loop read: its edges, the sequence numbers of their model-space curves, and why the edges
/// have no pcurves when they have none.
type ReadLoop = (Loop, Vec<u64>, Option<String>);

impl Faces<'_> {
    /// Pointer `k` of entity `id` (a directory-entry sequence number), 0 when blank.
    fn pointer(e: &Raw, id: u64, k: usize, what: &str) -> Result<u64, String> {
        let t = e.fields.get(k).map_or("", |s| s.trim());
        if t.is_empty() {
            return Ok(0);
        }
        t.parse::<u64>().map_err(|_| {
            format!("entity {} D{id}: {what} (parameter {k}) is \"{t}\", not a pointer to a directory entry", e.ty)
        })
    }

    /// Why entity `id` is not a curve or surface read.
    fn why_not(&self, id: u64, what: &str) -> String {
        if let Some(why) = self.skips.get(&id) {
            format!("its {what} D{id} was not read: {why}")
        } else if let Some(e) = self.raw.get(&id) {
            format!("its {what} D{id} is an entity {}, not a {what}", e.ty)
        } else if self.curves.contains_key(&id) {
            format!("its {what} D{id} is a curve, not a {what}")
        } else if self.surfaces.contains_key(&id) {
            format!("its {what} D{id} is a surface, not a {what}")
        } else {
            format!("its {what} D{id} is not an entity lekalo reads (100, 102, 104, 106, 108, 110, 112, 114, 126, 128, 190 to 198; swept surfaces 118, 120, 122 only outside faces), or not in the file")
        }
    }

    /// The curves of entity `id`: itself, or the constituents of a composite curve in order,
    /// with their sequence numbers. `path` holds the composite curves being expanded, outermost
    /// first: a composite curve that lists one of them (itself among them) is a cycle, refused
    /// naming its entities (`D7 → D9 → D7`), and nesting is at most [`MAX_NESTING`] deep. The
    /// control points copied count against the read's size limit ([`Faces::spend`]), so a
    /// curve listed many times over by composite curves that list each other many times (a
    /// chain of `n` composites each listing the next `k` times expands to `k^n` curves) is
    /// refused after `--max-size` control points, not expanded.
    fn pieces(
        &self,
        id: u64,
        path: &mut Vec<u64>,
        out: &mut Vec<(u64, Curve)>,
    ) -> Result<(), String> {
        if let Some(c) = self.curves.get(&id) {
            self.spend(id, c.control_points().len())?;
            out.push((id, (*c).clone()));
            return Ok(());
        }
        let Some(e) = self.raw.get(&id).filter(|e| e.ty == "102") else {
            return Err(self.why_not(id, "curve"));
        };
        if e.matrix {
            return Err(format!(
                "its composite curve D{id} has a transformation matrix (entity 124), which is not applied"
            ));
        }
        let named = |ids: &[u64]| {
            ids.iter()
                .map(|d| format!("D{d}"))
                .chain(std::iter::once(format!("D{id}")))
                .collect::<Vec<_>>()
                .join(" → ")
        };
        if let Some(k) = path.iter().position(|&d| d == id) {
            return Err(format!(
                "composite curve D{id} contains itself: {}; a composite curve lists the curves it \
                 is made of, never one that contains it",
                named(&path[k..])
            ));
        }
        if path.len() >= MAX_NESTING {
            return Err(format!(
                "composite curves nested more than {MAX_NESTING} deep (D{} → D{} → … → D{id})",
                path[0], path[1]
            ));
        }
        let n = Self::pointer(e, id, 1, "the number of curves N")?;
        if n == 0 {
            return Err(format!("composite curve D{id} has no curves (N = 0)"));
        }
        path.push(id);
        for k in 0..n {
            let k = usize::try_from(k).unwrap_or(usize::MAX).saturating_add(2);
            if k >= e.fields.len() {
                return Err(format!(
                    "composite curve D{id} declares N = {n} curves and lists {}",
                    e.fields.len().saturating_sub(2)
                ));
            }
            let c = Self::pointer(e, id, k, "a constituent curve")?;
            self.pieces(c, path, out)?;
        }
        path.pop();
        Ok(())
    }

    /// Counts `points` control points copied out of curve `id` against the read's size limit;
    /// past it, marks the read as over the limit ([`read_faces_with_progress`] then fails with
    /// [`IoError::OverLimit`]) and answers why.
    fn spend(&self, id: u64, points: usize) -> Result<(), String> {
        let spent = self.spent.get().saturating_add(points);
        self.spent.set(spent);
        if spent > self.max_size {
            self.over.set(Some(id));
            return Err(format!(
                "the boundaries copy {spent} control points at curve D{id}, above the size limit {}",
                self.max_size
            ));
        }
        Ok(())
    }

    /// A parameter-space curve (`z = 0`, not in the length unit) as a 2-D curve.
    fn plane_curve(&self, c: &Curve) -> Result<Curve, String> {
        let ctrl = c.control_points();
        let mut data = Vec::with_capacity(2 * ctrl.len());
        for p in ctrl.iter() {
            data.extend([
                p[0] / self.unit,
                p.get(1).copied().unwrap_or(0.0) / self.unit,
            ]);
        }
        let pts = Points::from_flat(2, data).map_err(|e| e.to_string())?;
        let knots = c.knots().as_slice().to_vec();
        let out = match c.weights() {
            Some(w) => NurbsCurve::new(c.degree(), knots, pts, w).map(Curve::Nurbs),
            None => BSplineCurve::new(c.degree(), knots, pts).map(Curve::BSpline),
        };
        out.map_err(|e| e.to_string())
    }

    /// The loop of boundary `id` (an entity 142).
    fn boundary(&self, id: u64, (sid, surface): (u64, &Surface)) -> Result<ReadLoop, String> {
        let Some(e) = self.raw.get(&id).filter(|e| e.ty == "142") else {
            return Err(self.why_not(id, "boundary (curve on a parametric surface, entity 142)"));
        };
        if e.matrix {
            return Err(format!(
                "its boundary D{id} has a transformation matrix (entity 124), which is not applied"
            ));
        }
        let b = Self::pointer(e, id, 3, "the parameter-space curve BPTR")?;
        let c = Self::pointer(e, id, 4, "the model-space curve CPTR")?;
        if c == 0 {
            return Err(format!(
                "its boundary D{id} has no model-space curve (CPTR = 0); lekalo does not build the 3-D edges from the parameter-space curves"
            ));
        }
        let mut model = Vec::new();
        self.pieces(c, &mut Vec::new(), &mut model)
            .map_err(|why| format!("boundary D{id}: {why}"))?;
        let mut plane = Vec::new();
        let plane = if b == 0 {
            Err(format!(
                "boundary D{id} has no parameter-space curve (BPTR = 0)"
            ))
        } else {
            self.pieces(b, &mut Vec::new(), &mut plane)
                .map(|()| plane)
                .map_err(|why| format!("boundary D{id}: {why}"))
        };
        self.assemble(id, (sid, surface), model, plane)
    }

    /// The loop of boundary `id` (an entity 141, §4.31): its curves in order, each reversed
    /// where `SENSE = 2`, with their parameter-space curves.
    fn boundary_141(&self, id: u64, (sid, surface): (u64, &Surface)) -> Result<ReadLoop, String> {
        let Some(e) = self.raw.get(&id).filter(|e| e.ty == "141") else {
            return Err(self.why_not(id, "boundary (entity 141)"));
        };
        if e.matrix {
            return Err(format!(
                "its boundary D{id} has a transformation matrix (entity 124), which is not applied"
            ));
        }
        let n = Self::pointer(e, id, 4, "the number of curves N")?;
        let mut model = Vec::new();
        let mut plane: Result<Vec<(u64, Curve)>, String> = Ok(Vec::new());
        let mut k = 5usize;
        for j in 0..n {
            if k.saturating_add(2) >= e.fields.len() {
                return Err(format!(
                    "boundary D{id} declares N = {n} curves and lists {j}"
                ));
            }
            let crv = Self::pointer(e, id, k, "a model-space curve CRVPT")?;
            let reversed = Self::pointer(e, id, k + 1, "SENSE")? == 2;
            let kk = Self::pointer(e, id, k + 2, "the number of parameter-space curves K")?;
            let oriented = |mut v: Vec<(u64, Curve)>| -> Result<Vec<(u64, Curve)>, String> {
                if reversed {
                    v.reverse();
                    for (_, c) in &mut v {
                        *c = c.reverse().map_err(|e| e.to_string())?;
                    }
                }
                Ok(v)
            };
            let mut m = Vec::new();
            self.pieces(crv, &mut Vec::new(), &mut m)
                .map_err(|why| format!("boundary D{id}: {why}"))?;
            model.extend(oriented(m)?);
            let mut pk = Vec::new();
            let found = if kk == 0 {
                Err(format!(
                    "boundary D{id}: curve {j} has no parameter-space curve (K = 0)"
                ))
            } else {
                (0..kk).try_for_each(|i| {
                    let at = usize::try_from(i).map_or(usize::MAX, |i| k.saturating_add(3 + i));
                    let p = Self::pointer(e, id, at, "a parameter-space curve")?;
                    self.pieces(p, &mut Vec::new(), &mut pk)
                        .map_err(|why| format!("boundary D{id}: {why}"))
                })
            };
            plane = match (plane, found) {
                (Ok(mut all), Ok(())) => oriented(pk).map(|p| {
                    all.extend(p);
                    all
                }),
                (Err(w), _) | (_, Err(w)) => Err(w),
            };
            k = usize::try_from(kk)
                .ok()
                .and_then(|kk| k.checked_add(3 + kk))
                .ok_or_else(|| format!("boundary D{id}: K = {kk} is not a count"))?;
        }
        self.assemble(id, (sid, surface), model, plane)
    }

    /// The loop of boundary `id` from its model-space pieces and, when read, its
    /// parameter-space pieces (or why not), paired in order; on an analytic surface `sid`
    /// (108, 190–198) without the parameter-space pieces, which are in IGES's parameters.
    fn assemble(
        &self,
        id: u64,
        (sid, surface): (u64, &Surface),
        mut model: Vec<(u64, Curve)>,
        plane: Result<Vec<(u64, Curve)>, String>,
    ) -> Result<ReadLoop, String> {
        let plane = if self.foreign.contains(&sid) {
            Err(format!("its surface D{sid} is an analytic surface (entity 108 or 190 to 198) read as a NURBS whose parameters are not IGES's: the parameter-space curves are not used"))
        } else {
            plane
        };
        let pcurves: Result<Vec<Curve>, String> = plane
                .and_then(|plane| {
                    plane
                        .iter()
                        .map(|(_, p)| self.plane_curve(p))
                        .collect::<Result<Vec<_>, _>>()
                        .map_err(|why| format!("boundary D{id}: {why}"))
                })
                .and_then(|pcs| {
                    if pcs.len() == model.len() || poles(surface, &pcs, &mut model) {
                        Ok(pcs)
                    } else {
                        Err(format!(
                            "boundary D{id}: the parameter-space curve has {} pieces, the model-space curve {}",
                            pcs.len(),
                            model.len()
                        ))
                    }
                });
        let (mut pcs, why) = match pcurves {
            Ok(p) => (p.into_iter().map(Some).collect::<Vec<_>>(), None),
            Err(why) => (vec![None; model.len()], Some(why)),
        };
        let mut edges = Vec::with_capacity(model.len());
        let mut ids = Vec::with_capacity(model.len());
        for ((cid, curve), pc) in model.into_iter().zip(pcs.drain(..)) {
            edges.push(Edge::new(curve, pc).map_err(|e| format!("boundary D{id}: {e}"))?);
            ids.push(cid);
        }
        let lp = Loop::new(edges).map_err(|e| format!("boundary D{id}: {e}"))?;
        Ok((lp, ids, why))
    }

    /// The boundary of the surface's domain: the iso-parametric edges `v = v0`, `u = u1`,
    /// `v = v1`, `u = u0`, counter-clockwise in `(u, v)`, with their pcurves.
    fn domain_loop(s: &Surface) -> Result<ReadLoop, String> {
        let ((u0, u1), (v0, v1)) = s.domain();
        let lib = |e: lekalo::Error| format!("the boundary of the surface's domain: {e}");
        let line = |p: [f64; 2], d: [f64; 2], a: f64, b: f64| {
            BSplineCurve::line_segment(&p, &d, a, b).map(Curve::BSpline)
        };
        let edges = vec![
            (
                s.iso_curve(Direction::U, v0),
                line([0.0, v0], [1.0, 0.0], u0, u1),
            ),
            (
                s.iso_curve(Direction::V, u1),
                line([u1, 0.0], [0.0, 1.0], v0, v1),
            ),
            (
                s.iso_curve(Direction::U, v1).and_then(|c| c.reverse()),
                line([u0 + u1, v1], [-1.0, 0.0], u0, u1),
            ),
            (
                s.iso_curve(Direction::V, u0).and_then(|c| c.reverse()),
                line([u0, v0 + v1], [0.0, -1.0], v0, v1),
            ),
        ]
        .into_iter()
        .map(|(c, p)| Edge::new(c?, Some(p?)))
        .collect::<lekalo::Result<Vec<_>>>()
        .map_err(lib)?;
        Ok((Loop::new(edges).map_err(lib)?, vec![0; 4], None))
    }

    /// The face of bounded surface `id` (entity 143, §4.33: `TYPE, SPTR, N, BDPT(1)…BDPT(N)`),
    /// its first boundary (entity 141) taken as the outer loop.
    fn bounded(&self, id: u64, e: &Raw) -> Result<StepFace, String> {
        let sptr = Self::pointer(e, id, 2, "the surface SPTR")?;
        let Some(surface) = self.surfaces.get(&sptr) else {
            return Err(self.why_not(sptr, "surface"));
        };
        let n = Self::pointer(e, id, 3, "the number of boundaries N")?;
        if n == 0 {
            return Err("has no boundary (N = 0)".into());
        }
        let mut loops = Vec::new();
        let mut ids = Vec::new();
        let mut why = None;
        for k in 0..n {
            let at = usize::try_from(k).map_or(usize::MAX, |k| k.saturating_add(4));
            if at >= e.fields.len() {
                return Err(format!("declares N = {n} boundaries and lists {k}"));
            }
            let b = Self::pointer(e, id, at, "a boundary BDPT")?;
            let (lp, lids, w) = self.boundary_141(b, (sptr, surface))?;
            why = why.or(w);
            loops.push(lp);
            ids.push(lids);
        }
        let outer = loops.remove(0);
        let face = Face::new((*surface).clone(), outer, loops, true, STEP_LOOP_RTOL)
            .map_err(|e| e.to_string())?;
        Ok(StepFace {
            id,
            name: String::new(),
            surface_id: sptr,
            face,
            edge_ids: ids,
            pcurves: why,
        })
    }

    /// The untrimmed face of the independent surface `id`: its domain's boundary
    /// ([`Self::domain_loop`]) the outer loop, no inner loops.
    fn untrimmed(&self, id: u64) -> Result<StepFace, String> {
        let Some(surface) = self.surfaces.get(&id) else {
            return Err(self.why_not(id, "surface"));
        };
        let (outer, ids, why) = Self::domain_loop(surface)?;
        let face = Face::new((*surface).clone(), outer, Vec::new(), true, STEP_LOOP_RTOL)
            .map_err(|e| format!("as an untrimmed face: {e}"))?;
        Ok(StepFace {
            id,
            name: String::new(),
            surface_id: id,
            face,
            edge_ids: vec![ids],
            pcurves: why,
        })
    }

    /// The face of trimmed surface `id` (an entity 144).
    fn face(&self, id: u64) -> Result<StepFace, String> {
        let e = &self.raw[&id];
        if e.matrix {
            return Err(
                "has a transformation matrix (entity 124), which is not applied".to_string(),
            );
        }
        if e.ty == "143" {
            return self.bounded(id, e);
        }
        let pts = Self::pointer(e, id, 1, "the surface PTS")?;
        let Some(surface) = self.surfaces.get(&pts) else {
            return Err(self.why_not(pts, "surface"));
        };
        let n1 = Self::pointer(e, id, 2, "N1")?;
        let n2 = Self::pointer(e, id, 3, "the number of inner boundaries N2")?;
        let pto = Self::pointer(e, id, 4, "the outer boundary PTO")?;
        let outer = if n1 == 0 || pto == 0 {
            Self::domain_loop(surface)?
        } else {
            self.boundary(pto, (pts, surface))?
        };
        let mut why = outer.2;
        let mut ids = vec![outer.1];
        let mut inner = Vec::new();
        for k in 0..n2 {
            let k = usize::try_from(k).unwrap_or(usize::MAX).saturating_add(5);
            if k >= e.fields.len() {
                return Err(format!(
                    "declares N2 = {n2} inner boundaries and lists {}",
                    e.fields.len().saturating_sub(5)
                ));
            }
            let b = Self::pointer(e, id, k, "an inner boundary PTI")?;
            let (lp, lids, w) = self.boundary(b, (pts, surface))?;
            why = why.or(w);
            inner.push(lp);
            ids.push(lids);
        }
        let face = Face::new((*surface).clone(), outer.0, inner, true, STEP_LOOP_RTOL)
            .map_err(|e| e.to_string())?;
        Ok(StepFace {
            id,
            name: String::new(),
            surface_id: pts,
            face,
            edge_ids: ids,
            pcurves: why,
        })
    }
}

/// Where the parameter-space curve of a boundary has more pieces than its model-space curve
/// because the exporter left out the edges that collapse to a point in space (a pole of the
/// surface, where a whole side of the domain maps to one point), inserts those points into
/// `model` as degenerate edges (degree 1, both control points at the pole; sequence number 0)
/// and returns true. A piece is taken as collapsed when its images at its ends and middle lie
/// within [`STEP_LOOP_RTOL`] of the surface's size of each other; nothing is changed unless
/// exactly the missing number of pieces collapse.
fn poles(surface: &Surface, pcs: &[Curve], model: &mut Vec<(u64, Curve)>) -> bool {
    let Some(extra) = pcs.len().checked_sub(model.len()) else {
        return false;
    };
    let size = surface
        .control_points()
        .bounding_box()
        .map_or(0.0, |(lo, hi)| {
            lo.iter()
                .zip(&hi)
                .map(|(a, b)| (b - a) * (b - a))
                .sum::<f64>()
                .sqrt()
        });
    let tol = STEP_LOOP_RTOL * size;
    let ((u0, u1), (v0, v1)) = surface.domain();
    let at = |p: &Curve, t: f64| -> Option<Vec<f64>> {
        let uv = p.eval(t).ok()?;
        // parameter-space curves stray from the domain by rounding (1e-16 to 1e-9)
        surface.eval(uv[0].clamp(u0, u1), uv[1].clamp(v0, v1)).ok()
    };
    let collapsed: Vec<Option<Vec<f64>>> = pcs
        .iter()
        .map(|p| {
            let (a, b) = p.domain();
            let pts = [at(p, a)?, at(p, 0.5 * (a + b))?, at(p, b)?];
            let far = pts[1..].iter().any(|q| {
                q.iter()
                    .zip(&pts[0])
                    .map(|(x, y)| (x - y) * (x - y))
                    .sum::<f64>()
                    .sqrt()
                    > tol
            });
            (!far).then(|| pts[0].clone())
        })
        .collect();
    if collapsed.iter().filter(|c| c.is_some()).count() != extra {
        return false;
    }
    let mut out = Vec::with_capacity(pcs.len());
    let mut rest = model.iter();
    for (p, c) in pcs.iter().zip(collapsed) {
        match c {
            Some(pole) => {
                let (a, b) = p.domain();
                let pts = Points::from_rows(&[pole.clone(), pole]);
                let edge = pts.and_then(|pts| BSplineCurve::new(1, vec![a, a, b, b], pts));
                match edge {
                    Ok(e) => out.push((0, Curve::BSpline(e))),
                    Err(_) => return false,
                }
            }
            None => match rest.next() {
                Some(m) => out.push(m.clone()),
                None => return false,
            },
        }
    }
    *model = out;
    true
}
