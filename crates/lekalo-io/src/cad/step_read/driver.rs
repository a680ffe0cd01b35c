//! [`read_step`]: the exchange structure parsed, its units found, then each geometric entity
//! read or listed as skipped.

use std::cell::{Cell, RefCell};
use std::collections::{HashMap, HashSet};

use super::analytic::{ANALYTIC_CURVES, ANALYTIC_SURFACES};
use super::assembly::{assembly, Assembly};
use super::bounds::{face_bounds, line_ranges};
use super::entities::{is_bspline_curve, is_bspline_surface, Reader, OTHER_GEOMETRY, TESSELLATED};
use super::faces::read_faces;
use super::parse::parse;
use super::progress::{Meter, Pass};
use super::skips::{Skips, SKIPPED_LISTED};
use super::units::{length_unit, plane_angle_unit};
use super::{StepRead, StepSkipped, Why, P};
use crate::cad::step::PLANE_DRAWING;
use lekalo::Progress;

use crate::error::{IoError, IoResult};
use crate::shape::Shape;

/// Reads the curves and surfaces of a STEP file. `source` names the file in errors.
///
/// B-splines and NURBS are read as written (knots given or implied by their form); lines,
/// circles, ellipses, polylines, planes, cylinders, cones, spheres, tori and swept surfaces are
/// converted to exact NURBS by the library (see the module documentation for the bounds of
/// unbounded ones). What is not read is listed in [`StepRead::skipped`] with the reason.
///
/// ```
/// use lekalo_io::{read_step, Object, Shape, StepWriter};
/// let c = lekalo::NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0)?;
/// let mut w = StepWriter::new("circle");
/// w.add_object(&Object::Nurbs(c.clone()))?;
/// let r = read_step(&w.finish("2000-01-01T00:00:00"), "circle.step")?;
/// assert_eq!(r.shapes.len(), 1);
/// assert_eq!(r.shapes[0].1, Shape::Curve(Object::Nurbs(c)));   // bit for bit
/// assert_eq!(r.length_unit, "millimetre");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`IoError::Syntax`] (with the line) when the text is not an exchange structure;
/// [`IoError::Syntax`] naming the entity when a B-spline entity is malformed or rejected by the
/// library's constructor (unsorted knots, wrong counts, non-positive weights).
pub fn read_step(text: &str, source: &str) -> IoResult<StepRead> {
    read_step_limited(text, source, usize::MAX)
}

/// [`read_step`] of a file that may hold at most `max_size` entity instances, and whose
/// B-splines may hold at most `max_size` control points and knots together (counted as they are
/// read, a curve each time it is read: as itself and as the basis of a trim): the count is
/// checked before the instances, points or knots past the limit are allocated, so a file that
/// declares more (knot multiplicities in the millions, a net of millions of points) is refused
/// with the count instead of filling the memory. The CLI passes its `--max-size`.
///
/// ```
/// use lekalo_io::{read_step_limited, IoError, Object, StepWriter};
/// let c = lekalo::BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0],
///     lekalo::Points::from_rows(&[vec![0.0, 0.0, 0.0], vec![1.0, 0.0, 0.0]])?)?;
/// let mut w = StepWriter::new("line");
/// w.add_object(&Object::BSpline(c))?;
/// let text = w.finish("2000-01-01T00:00:00");
/// assert!(read_step_limited(&text, "line.step", 1000).is_ok());
/// // 2 control points and 4 knots are above a limit of 5
/// let e = read_step_limited(&text, "line.step", 5).unwrap_err();
/// assert!(matches!(e, IoError::OverLimit { .. }) && e.to_string().contains("--max-size"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`read_step`]; [`IoError::OverLimit`] naming the count and `--max-size` for a file above
/// the limit.
pub fn read_step_limited(text: &str, source: &str, max_size: usize) -> IoResult<StepRead> {
    read(
        text,
        source,
        max_size,
        false,
        SKIPPED_LISTED,
        &Progress::new(),
    )
}

/// [`read_step_limited`] that reads the faces too ([`StepRead::faces`]): each `ADVANCED_FACE`
/// or `FACE_SURFACE` as a [`lekalo::Face`], its surface trimmed by loops of edges with their
/// pcurves; faces that cannot be read are listed in [`StepRead::skipped_faces`] with the
/// reason. The edges' curves count toward the size limit each time a face reads them.
///
/// # Errors
/// As [`read_step_limited`].
pub fn read_step_faces(text: &str, source: &str, max_size: usize) -> IoResult<StepRead> {
    read(
        text,
        source,
        max_size,
        true,
        SKIPPED_LISTED,
        &Progress::new(),
    )
}

/// [`read_step_limited`] (or [`read_step_faces`] with `faces`) that reports to `progress` and
/// stops when its cancel flag is set. The bar has twice the file's length in bytes: the first
/// half counts the bytes parsed, the second the entity instances converted, pass after pass
/// (trimmed curves, curves and B-spline surfaces, analytic surfaces, faces); `done` never goes
/// back and the last report is `(total, total)`. The hook is consulted every 64 KiB of text and
/// every 1024 instances, never inside an entity, so the result is the same with or without it.
/// `listed` bounds the skipped entities and faces listed one by one ([`Skips::listed`]; the
/// others are counted by kind): [`SKIPPED_LISTED`] is what the other readers keep, `usize::MAX`
/// lists every one (memory then grows with them).
///
/// ```
/// use std::sync::atomic::AtomicBool;
/// use lekalo::Progress;
/// use lekalo_io::{read_step_with_progress, IoError, Object, StepWriter};
/// let c = lekalo::BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0],
///     lekalo::Points::from_rows(&[vec![0.0, 0.0, 0.0], vec![1.0, 0.0, 0.0]])?)?;
/// let mut w = StepWriter::new("line");
/// w.add_object(&Object::BSpline(c))?;
/// let text = w.finish("2000-01-01T00:00:00");
/// let stop = AtomicBool::new(true);
/// let e = read_step_with_progress(&text, "line.step", 1000, false, lekalo_io::SKIPPED_LISTED,
///     &Progress::new().with_cancel(&stop)).unwrap_err();
/// assert!(matches!(e, IoError::Cancelled { .. }), "{e}");
/// assert_eq!(e.to_string(), "line.step: reading STEP: cancelled");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`read_step_limited`]; [`IoError::Cancelled`] once the cancel flag is set.
pub fn read_step_with_progress(
    text: &str,
    source: &str,
    max_size: usize,
    faces: bool,
    listed: usize,
    progress: &Progress<'_>,
) -> IoResult<StepRead> {
    read(text, source, max_size, faces, listed, progress)
}

fn read(
    text: &str,
    source: &str,
    max_size: usize,
    with_faces: bool,
    listed: usize,
    progress: &Progress<'_>,
) -> IoResult<StepRead> {
    let meter = Meter {
        progress,
        source,
        len: text.len() as u64,
    };
    let parsed = parse(text, source, max_size, &meter)?;
    let (length_unit, scale) = length_unit(&parsed, source)?;
    let rd = Reader {
        p: &parsed,
        source,
        scale,
        angle: plane_angle_unit(&parsed),
        max_size,
        used: Cell::new(0),
        over: RefCell::new(None),
        basis_sizes: RefCell::new(HashMap::new()),
        motion: Cell::new(None),
    };
    // the parts an assembly places are read at each of their occurrences, one pass each
    let placed = assembly(&rd);
    let mut read = convert(&rd, placed.as_ref(), 0, with_faces, listed, &meter)?;
    let quiet = Progress::new();
    let quiet = Meter {
        progress: &quiet,
        source,
        len: text.len() as u64,
    };
    for pass in 1..placed.as_ref().map_or(1, Assembly::passes) {
        let more = convert(&rd, placed.as_ref(), pass, with_faces, 0, &quiet)?;
        read.shapes.extend(more.shapes);
        read.faces.extend(more.faces);
        read.triangulations.extend(more.triangulations);
    }
    // stable: the occurrences of an instance in the order of the passes
    read.shapes.sort_by_key(|(id, _)| *id);
    read.faces.sort_by_key(|f| f.id);
    read.triangulations.sort_by_key(|t| t.id);
    let shapes = plane_drawing(
        &rd,
        read.shapes,
        read.faces.is_empty() && read.triangulations.is_empty(),
    )?;
    meter.finish();
    Ok(StepRead {
        shapes,
        skipped: read.skipped,
        faces: read.faces,
        triangulations: read.triangulations,
        skipped_faces: read.skipped_faces,
        schema: parsed.schema,
        length_unit,
        scale_to_mm: scale,
    })
}

/// A drawing in the plane read back as one. STEP has no place for a 2-D curve that CAD systems
/// read (Open CASCADE transfers neither 2-D points in a 2-D context nor a `PCURVE` on a plane
/// from a curve set), so lekalo writes 2-D curves padded with `z = 0` and names its context a
/// [`PLANE_DRAWING`] (`docs/formats.md`). A file with that context that holds curves only, every
/// control point at `z = 0` exactly, gives its curves back with their `(x, y)` coordinates;
/// any other file, and one edited to put a curve out of the plane, keeps every curve 3-D.
fn plane_drawing(
    rd: &Reader<'_>,
    shapes: Vec<(u64, Shape)>,
    no_faces: bool,
) -> IoResult<Vec<(u64, Shape)>> {
    let in_plane = |s: &Shape| match s {
        Shape::Curve(c) => {
            let p = c.control_points();
            p.dim() == 3 && p.iter().all(|x| x[2] == 0.0)
        }
        _ => false,
    };
    let marked = rd.p.instances.ids().iter().any(|id| {
        let i = rd.p.instances.known(id);
        i.get("REPRESENTATION_CONTEXT")
            .is_some_and(|ps| matches!(ps.get(1), Some(P::Str(t)) if t == PLANE_DRAWING))
    });
    if !marked || !no_faces || shapes.is_empty() || !shapes.iter().all(|(_, s)| in_plane(s)) {
        return Ok(shapes);
    }
    shapes
        .into_iter()
        .map(|(id, s)| match s {
            Shape::Curve(c) => {
                let xy: Vec<f64> = c
                    .control_points()
                    .iter()
                    .flat_map(|x| [x[0], x[1]])
                    .collect();
                let flat = lekalo::Points::from_flat(2, xy).and_then(|p| c.with_control_points(p));
                // the same knots and weights on finite points: the kind's checks hold again
                flat.map(|c| (id, Shape::Curve(c))).map_err(|e| {
                    IoError::syntax(rd.at(id), format!("entity #{id} in the plane z = 0: {e}"))
                })
            }
            other => Ok((id, other)),
        })
        .collect()
}

/// What one pass over the instances reads.
struct Converted {
    shapes: Vec<(u64, Shape)>,
    skipped: Skips,
    faces: Vec<super::StepFace>,
    triangulations: Vec<super::StepTriangulation>,
    skipped_faces: Skips,
}

/// Reads the geometry (and with `with_faces` the faces) of the instances that pass `pass` of
/// the assembly `placed` reads, each at its placement (every instance, as written, when the file
/// places no part). The skips are counted by kind, at most `listed` of them kept.
fn convert(
    rd: &Reader<'_>,
    placed: Option<&Assembly>,
    pass: usize,
    with_faces: bool,
    listed: usize,
    meter: &Meter<'_>,
) -> IoResult<Converted> {
    let source = rd.source;
    let parsed = rd.p;
    // whether the instance `id` is read in this pass, with the motion of its part set
    let enter = |id: u64| -> bool {
        let how = match placed {
            Some(a) => a.motion(id, pass),
            None => Some(None),
        };
        rd.motion.set(how.flatten());
        how.is_some()
    };
    // a refusal by the size limit, wherever it happened (a skipped entity included)
    let too_large = |rd: &Reader<'_>| {
        rd.over
            .borrow()
            .as_ref()
            .map(|(why, total)| IoError::OverLimit {
                what: format!("{source}: {why}"),
                limit: crate::Limit::Size,
                raise_to: Some(*total),
            })
    };
    let ids = parsed.instances.ids();
    let mut shapes = Vec::new();
    let mut skipped = Skips::new(listed);
    let skip = |skipped: &mut Skips, id: u64, entity: &str, reason: Why| {
        skipped.push(StepSkipped {
            id,
            entity: entity.to_string(),
            reason,
        });
    };
    // every curve read, by id (trimmed bases included), for swept surfaces and face bounds:
    // copies, kept only when the file has analytic surfaces to read
    let mut curves = HashMap::new();
    let keep_curves = parsed.instances.any_of(ANALYTIC_SURFACES);
    let mut trimmed_bases = HashSet::new();
    // the basis control points all trims may read: four times the instances of the file (each
    // control point is an instance), so that reading stays linear in the file's size
    let mut budget = parsed.instances.len().saturating_mul(4);
    for (k, &id) in ids.iter().enumerate() {
        meter.converted(Pass::Trims, k, ids.len())?;
        if !enter(id) {
            continue;
        }
        let inst = parsed.instances.known(&id);
        if let Some(r) = inst.get("TRIMMED_CURVE") {
            match rd.trimmed(r, &mut budget) {
                Ok((basis, piece)) => {
                    trimmed_bases.insert(basis);
                    if keep_curves {
                        curves.insert(id, piece.clone());
                    }
                    shapes.push((id, Shape::Curve(piece)));
                }
                Err(reason) => skip(&mut skipped, id, "TRIMMED_CURVE", reason),
            }
        }
    }
    if let Some(e) = too_large(rd) {
        return Err(e);
    }
    // the ranges of lines and unbounded surfaces are parameters, the same at any placement:
    // found as written
    rd.motion.set(None);
    let lines = line_ranges(rd);
    let mut unbounded = HashSet::new();
    for (k, &id) in ids.iter().enumerate() {
        meter.converted(Pass::Curves, k, ids.len())?;
        if !enter(id) {
            continue;
        }
        let inst = parsed.instances.known(&id);
        let bad = |why: Why| {
            too_large(rd).unwrap_or_else(|| {
                IoError::syntax(
                    rd.at(id),
                    format!("entity #{id} {}: {why}", inst.type_name()),
                )
            })
        };
        if is_bspline_curve(&inst) {
            let c = rd.curve(&inst).map_err(bad)?;
            if keep_curves {
                curves.insert(id, c.clone());
            }
            if !trimmed_bases.contains(&id) {
                shapes.push((id, Shape::Curve(c)));
            }
        } else if let Some(name) = first_of(&inst, ANALYTIC_CURVES) {
            let read = rd.basis(id).and_then(|b| match lines.get(&id) {
                Some(&(t0, t1)) if name == "LINE" => b.piece(t0, t1, true),
                _ => b.whole(),
            });
            match read {
                Ok(c) => {
                    if keep_curves {
                        curves.insert(id, c.clone());
                    }
                    if !trimmed_bases.contains(&id) {
                        shapes.push((id, Shape::Curve(c)));
                    }
                }
                // a line that a trim reads is not skipped
                Err(_) if trimmed_bases.contains(&id) => {}
                Err(reason) => skip(&mut skipped, id, name, reason),
            }
        } else if is_bspline_surface(&inst) {
            shapes.push((id, Shape::Surface(rd.surface(&inst).map_err(bad)?)));
        } else if let Some(name) = first_of(&inst, ANALYTIC_SURFACES) {
            if matches!(
                name,
                "PLANE" | "CYLINDRICAL_SURFACE" | "CONICAL_SURFACE" | "SURFACE_OF_LINEAR_EXTRUSION"
            ) {
                unbounded.insert(id);
            }
        } else if let Some(name) = first_of(&inst, TESSELLATED) {
            skip(&mut skipped, id, name, TESSELLATED_REASON.into());
        } else if let Some(name) = first_of(&inst, OTHER_GEOMETRY) {
            skip(&mut skipped, id, name, OTHER_REASON.into());
        }
    }
    if let Some(e) = too_large(rd) {
        return Err(e);
    }
    rd.motion.set(None);
    let bounds = face_bounds(rd, &unbounded, &curves);
    for (k, &id) in ids.iter().enumerate() {
        meter.converted(Pass::Surfaces, k, ids.len())?;
        if !enter(id) {
            continue;
        }
        let inst = parsed.instances.known(&id);
        let Some(name) = first_of(&inst, ANALYTIC_SURFACES) else {
            continue;
        };
        match rd.analytic_surface(id, &inst, &bounds, &curves) {
            Ok(s) => shapes.push((id, Shape::Surface(s))),
            Err(reason) => skip(&mut skipped, id, name, reason),
        }
    }
    if let Some(e) = too_large(rd) {
        return Err(e);
    }
    skipped.finish();
    let (faces, triangulations, skipped_faces) = if with_faces {
        let surfaces: HashMap<u64, &lekalo::Surface> = shapes
            .iter()
            .filter_map(|(id, s)| match s {
                Shape::Surface(s) => Some((*id, s)),
                _ => None,
            })
            .collect();
        // why a surface a face names was skipped: found again when a face asks, rather than
        // kept for every skipped entity (a few recent answers are kept for faces sharing one)
        let recent: RefCell<HashMap<u64, Option<Why>>> = RefCell::new(HashMap::new());
        let surface_skip = |sid: u64| -> Option<Why> {
            if let Some(why) = recent.borrow().get(&sid) {
                return why.clone();
            }
            let inst = parsed.instances.get(&sid)?;
            let why = if first_of(&inst, TESSELLATED).is_some() {
                Some(TESSELLATED_REASON.into())
            } else if first_of(&inst, OTHER_GEOMETRY).is_some() {
                Some(OTHER_REASON.into())
            } else if first_of(&inst, ANALYTIC_SURFACES).is_some() {
                // read again for its reason only: the size limit is not charged twice
                let (used, over) = (rd.used.get(), rd.over.borrow().clone());
                let why = rd.analytic_surface(sid, &inst, &bounds, &curves).err();
                rd.used.set(used);
                *rd.over.borrow_mut() = over;
                why
            } else {
                None
            };
            let mut recent = recent.borrow_mut();
            if recent.len() >= RECENT_SURFACE_SKIPS {
                recent.clear();
            }
            recent.insert(sid, why.clone());
            why
        };
        let r = read_faces(rd, ids, &surfaces, &surface_skip, listed, meter, &enter)?;
        if let Some(e) = too_large(rd) {
            return Err(e);
        }
        (r.faces, r.triangulations, r.skipped)
    } else {
        (Vec::new(), Vec::new(), Skips::default())
    };
    rd.motion.set(None);
    Ok(Converted {
        shapes,
        skipped,
        faces,
        triangulations,
        skipped_faces,
    })
}

/// Why tessellated geometry is skipped.
const TESSELLATED_REASON: &str =
    "tessellated geometry (a mesh of triangles or polylines), not a curve or surface; faces of triangles are read with --faces (`lekalo mesh` writes them)";

/// Why the other geometry ([`OTHER_GEOMETRY`]) is skipped.
const OTHER_REASON: &str =
    "not read (lekalo reads B-splines, NURBS, lines, conics, elementary and swept surfaces)";

/// How many surfaces' reasons for being skipped the face pass keeps at once.
const RECENT_SURFACE_SKIPS: usize = 1024;

/// The first record of `inst` named in `names`.
fn first_of<'a>(inst: &super::Instance<'_>, names: &[&'a str]) -> Option<&'a str> {
    inst.names()
        .iter()
        .find_map(|n| names.iter().find(|m| **m == n.as_str()).copied())
}
