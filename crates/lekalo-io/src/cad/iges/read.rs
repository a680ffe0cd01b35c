//! Reading IGES: the sections of the file, the size limits, and the rational B-spline entities
//! (126, 128; 110, 112, 114 through `splines.rs`; the arcs 100 and 104 through `conics.rs`) as
//! shapes (IGES 5.3 §2, §4.3, §4.5, §4.23, §4.24).

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points, Progress};

use super::composite::{self, SUBORDINATE_COMPOSITE};
use super::faces::{self, Raw};
use super::fields::{count, fields, real, real_at, unit};
use super::{analytic, conics, matrix, splines, swept, IgesRead};
use crate::error::{IoError, IoResult, Location};
use crate::object::Object;
use crate::shape::{Shape, Surface};
use crate::step_read::{Skips, StepSkipped, SKIPPED_LISTED};

/// Parameter `k` of an entity's fields as a real; the error names it and quotes what is
/// written (a number beyond a double, `1.D+400`, or a word, `NaN`).
/// Why an entity of the faces' topology is not read by [`read_iges`].
const NOT_READ: &str = "not read (lekalo reads entities 100, 102, 104, 106, 108, 110, 112, 114, 118, 120, 122, 126, 128 and 190 to 198; trimmed and bounded surfaces with their boundaries as faces, `--faces`)";

/// Why an offset curve (entity 130) is not read.
const OFFSET_CURVE: &str = "an offset curve (entity 130) is not read: the offset C(t) + d N(t) of a free-form curve moves along its unit normal, whose length is a square root, so it is no NURBS; the offsets that are (of a line, of a circle) are not recognised either";

/// Why an offset surface (entity 140) is not read.
const OFFSET_SURFACE: &str = "an offset surface (entity 140) is not read: the offset S(u, v) + d N(u, v) of a free-form surface moves along its unit normal, whose length is a square root, so it is no NURBS; the offsets that are (of a plane, a cylinder, a sphere) are not recognised either";

/// The model-space curves of a boundary (entity 141: `TYPE, PREF, SPTR, N`, then per curve
/// `CRVPT, SENSE, K, PSCPT(1..K)`; IGES 5.3 §4.26), as far as the fields go.
fn boundary_curves(f: &[String]) -> Vec<usize> {
    let at = |k: usize| f.get(k).and_then(|s| count(s));
    let mut out = Vec::new();
    let (mut k, n) = (5, at(4).unwrap_or(0));
    for _ in 0..n {
        let (Some(c), Some(m)) = (at(k), at(k + 2)) else {
            break;
        };
        out.push(c);
        out.extend((k + 3..k + 3 + m).filter_map(at));
        k = k.saturating_add(3).saturating_add(m);
    }
    out
}

/// Why a swept surface (118, 120, 122) is not read when faces are.
const SWEPT_IN_FACES: &str = "a swept surface (ruled surface, surface of revolution or tabulated cylinder) is read as a surface, not as the surface of a face: its NURBS parametrisation is not IGES's, so the curves of a boundary in its parameters would land elsewhere";

/// What [`read_entities`] gives: the read, the raw entities by sequence number, the
/// independent surfaces, the reasons of the skipped entities (with `topology`), and the
/// analytic surfaces read (108, 190–198), whose NURBS parameters are not IGES's.
pub(super) type Entities = (
    IgesRead,
    std::collections::HashMap<u64, Raw>,
    Vec<u64>,
    std::collections::HashMap<u64, String>,
    std::collections::HashSet<u64>,
);

/// Reads the rational B-spline curves (126) and surfaces (128) of an IGES file.
///
/// ```
/// use lekalo_io::{read_iges, IgesWriter, Object, Shape};
/// let c = lekalo::NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 2.0)?;
/// let mut w = IgesWriter::new();
/// w.add_object(&Object::Nurbs(c.clone()))?;
/// let r = read_iges(&w.finish("circle", "20000101.000000"), "circle.igs")?;
/// assert_eq!(r.shapes[0].1, Shape::Curve(Object::Nurbs(c)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`IoError::Syntax`] with the line for records that are not IGES, pointers outside the file
/// and entities whose numbers do not fit their counts or that the library rejects.
pub fn read_iges(text: &str, source: &str) -> IoResult<IgesRead> {
    read_iges_limited(text, source, usize::MAX)
}

/// [`read_iges`] of a file that may hold at most `max_size` entities (directory entries), and
/// whose B-splines (entities 126 and 128) may hold at most `max_size` control points and knots
/// together: the counts each entity declares are checked before its points and knots are
/// allocated, so a file past the limit is refused with the count instead of filling the memory.
/// The CLI passes its `--max-size`.
///
/// ```
/// use lekalo_io::{read_iges_limited, IgesWriter, IoError, Object};
/// let c = lekalo::BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0],
///     lekalo::Points::from_rows(&[vec![0.0, 0.0, 0.0], vec![1.0, 0.0, 0.0]])?)?;
/// let mut w = IgesWriter::new();
/// w.add_object(&Object::BSpline(c))?;
/// let text = w.finish("line.igs", "2000-01-01T00:00:00");
/// assert!(read_iges_limited(&text, "line.igs", 1000).is_ok());
/// // 2 control points and 4 knots are above a limit of 5
/// let e = read_iges_limited(&text, "line.igs", 5).unwrap_err();
/// assert!(matches!(e, IoError::OverLimit { .. }) && e.to_string().contains("--max-size"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`read_iges`]; [`IoError::OverLimit`] naming the count and `--max-size` for a file above
/// the limit.
pub fn read_iges_limited(text: &str, source: &str, max_size: usize) -> IoResult<IgesRead> {
    read_entities(
        text,
        source,
        max_size,
        false,
        SKIPPED_LISTED,
        &Progress::new(),
    )
    .map(|(r, ..)| r)
}

/// What an IGES read reports itself as.
const READING: &str = "reading IGES";

/// Directory entries read between two consultations of the progress hook.
const REPORT_ENTITIES: usize = 1 << 10;

/// [`read_iges_limited`] (or [`read_iges_faces`] with `faces`) that reports to `progress` and
/// stops when its cancel flag is set: `(entities read, entities)` of the directory section,
/// every 1024 entities and never inside one (the result is the same with or without the hook),
/// `(total, total)` last. `listed` bounds the skipped entities and faces listed one by one
/// (the others are counted by kind), as in [`crate::read_step_with_progress`].
///
/// ```
/// use std::sync::atomic::AtomicBool;
/// use lekalo::Progress;
/// use lekalo_io::{read_iges_with_progress, IgesWriter, IoError, Object};
/// let c = lekalo::BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0],
///     lekalo::Points::from_rows(&[vec![0.0, 0.0, 0.0], vec![1.0, 0.0, 0.0]])?)?;
/// let mut w = IgesWriter::new();
/// w.add_object(&Object::BSpline(c))?;
/// let text = w.finish("line.igs", "2000-01-01T00:00:00");
/// let stop = AtomicBool::new(true);
/// let e = read_iges_with_progress(&text, "line.igs", 1000, false, lekalo_io::SKIPPED_LISTED,
///     &Progress::new().with_cancel(&stop)).unwrap_err();
/// assert_eq!(e.to_string(), "line.igs: reading IGES: cancelled");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`read_iges_limited`]; [`IoError::Cancelled`] once the cancel flag is set.
pub fn read_iges_with_progress(
    text: &str,
    source: &str,
    max_size: usize,
    faces: bool,
    listed: usize,
    progress: &Progress<'_>,
) -> IoResult<IgesRead> {
    if faces {
        faces::read_faces_with_progress(text, source, max_size, listed, progress)
    } else {
        read_entities(text, source, max_size, false, listed, progress).map(|(r, ..)| r)
    }
}

/// The entities of a file as [`read_iges_limited`] reads them and, with `topology`, the
/// parameters of the composite curves, curves on surfaces, boundaries, bounded and trimmed
/// surfaces (entities 102, 141, 142, 143, 144) by sequence number, which the faces are built
/// from, and the sequence numbers of the surfaces (114, 128) whose directory entry says they are
/// independent (subordinate entity switch `00`, IGES 5.3 §2.2.4.4.9: no other entity needs
/// them), which stand alone as untrimmed faces, and why each skipped entity was skipped, by
/// sequence number, for the faces that name one (a directory entry takes two lines of 80
/// columns, so these reasons are smaller than the file). `progress` is told the directory
/// entries read; at most `listed` skips are listed in [`IgesRead::skipped`].
pub(super) fn read_entities(
    text: &str,
    source: &str,
    max_size: usize,
    topology: bool,
    listed: usize,
    progress: &Progress<'_>,
) -> IoResult<Entities> {
    let mut raw = std::collections::HashMap::new();
    let mut independent = Vec::new();
    let mut g = String::new();
    let mut d: Vec<(usize, &str)> = Vec::new();
    let mut p: Vec<(usize, &str)> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let l = raw.trim_end_matches('\r');
        if l.trim().is_empty() {
            continue;
        }
        let section = l.get(72..73).ok_or_else(|| {
            IoError::syntax(
                Location::new(source).at_line(i + 1),
                "an IGES record has 80 columns with the section letter in column 73; this line is shorter",
            )
        })?;
        match section {
            "G" => g.push_str(&l[..72]),
            "D" => d.push((i + 1, l)),
            "P" => p.push((i + 1, l)),
            "S" | "T" => {}
            other => {
                return Err(IoError::syntax(
                    Location::new(source).at_line(i + 1),
                    format!("section letter \"{other}\" in column 73: expected S, G, D, P or T"),
                ))
            }
        }
    }
    let (delim, record) = {
        // `1H,` and `1H;` name the delimiters; the character after `1H` may take several bytes
        let hollerith = |t: &str, default: char| -> (char, usize) {
            t.strip_prefix("1H")
                .and_then(|r| r.chars().next())
                .map_or((default, 0), |c| (c, 2 + c.len_utf8()))
        };
        let t = g.trim_start();
        let (pd, used) = hollerith(t, ',');
        let rest = t[used..].trim_start_matches(pd).trim_start();
        let (rd, _) = hollerith(rest, ';');
        (pd, rd)
    };
    let gf = fields(&g, delim, record);
    let flag = gf.get(13).and_then(|s| count(s)).unwrap_or(2);
    let name = gf.get(14).cloned().unwrap_or_default();
    let scale_field = gf
        .get(12)
        .and_then(|s| real(s))
        .filter(|s| *s > 0.0)
        .unwrap_or(1.0);
    let (length_unit, unit_mm) =
        unit(flag, &name).unwrap_or_else(|| (format!("{name} (assumed MM)"), 1.0));
    // the minimum user-intended resolution (field 19), in millimetres: patches of entity 114
    // that meet within it are joined
    let resolution_mm = gf
        .get(18)
        .and_then(|s| real(s))
        .filter(|r| *r > 0.0)
        .map_or(0.0, |r| r * unit_mm);
    // model space scale: model units per drawing unit; coordinates are in model units
    let _ = scale_field;
    let matrices = matrix::matrices(&d, &p, delim, record, unit_mm);
    let place = |s: Shape, m: Option<&crate::cad::motion::Motion>| match m {
        Some(m) => matrix::moved(s, m),
        None => Ok(s),
    };
    let mut shapes = Vec::new();
    let mut skipped = Vec::new();
    // swept surfaces (118, 120, 122), built from their curves after the loop
    let mut sweeps = Vec::new();
    // independent composite curves (102): (sequence number, member pointers, placement),
    // and the curves that boundaries (141, 142) point at
    let mut composites = Vec::new();
    let mut pointed_at = std::collections::HashSet::new();
    // analytic surfaces (108, 190–198), built after the loop from the points (116),
    // directions (123) and curves they point at
    let mut refs = analytic::Refs::default();
    let mut pending = Vec::new();
    let entities = d.len() / 2;
    if entities > max_size {
        return Err(IoError::OverLimit {
            what: format!(
                "{source}: {entities} entities in the directory section, above the size limit {max_size}"
            ),
            limit: crate::Limit::Size,
            raise_to: Some(entities as u64),
        });
    }
    // control points and knots of the B-splines read so far, against the size limit
    let mut used = 0usize;
    let mut charge = |seq: u64, n: usize| -> IoResult<()> {
        used = used.saturating_add(n);
        if used > max_size {
            return Err(IoError::OverLimit {
                what: format!(
                    "{source}: entity D{seq}: {used} control points and knots with this entity's {n}, above the size limit {max_size}"
                ),
                limit: crate::Limit::Size,
                raise_to: Some(used as u64),
            });
        }
        Ok(())
    };
    // parameter lines read so far: each entity owns its own lines, so more than the section
    // holds means entities share lines, which a file could use to make the reading quadratic
    let mut lines_read = 0usize;
    let step = |k: usize| -> IoResult<()> {
        if progress.is_active() {
            progress
                .step(READING, k as u64, entities as u64)
                .map_err(|e| IoError::cancelled(source, &e))?;
        }
        Ok(())
    };
    for (k, pair) in d.chunks(2).enumerate() {
        if k % REPORT_ENTITIES == 0 {
            step(k)?;
        }
        let [(line, a), (_, b)] = pair else {
            return Err(IoError::syntax(
                Location::new(source).at_line(pair[0].0),
                "the directory section has an odd number of records",
            ));
        };
        let field = |s: &str, k: usize| s.get(8 * k..8 * k + 8).unwrap_or("").trim().to_string();
        let ty = field(a, 0);
        let seq: u64 = a
            .get(73..80)
            .and_then(|s| s.trim().parse().ok())
            .unwrap_or(0);
        let keep = topology && matches!(ty.as_str(), "102" | "141" | "142" | "143" | "144");
        if !keep
            && !matches!(
                ty.as_str(),
                "100"
                    | "102"
                    | "104"
                    | "106"
                    | "108"
                    | "116"
                    | "123"
                    | "190"
                    | "192"
                    | "194"
                    | "196"
                    | "198"
                    | "141"
                    | "142"
                    | "110"
                    | "112"
                    | "114"
                    | "118"
                    | "120"
                    | "122"
                    | "126"
                    | "128"
            )
        {
            let reason = match ty.as_str() {
                "143" | "144" => NOT_READ,
                "130" => OFFSET_CURVE,
                "140" => OFFSET_SURFACE,
                _ => "",
            };
            if !reason.is_empty() {
                skipped.push(StepSkipped {
                    id: seq,
                    entity: format!("IGES entity {ty}"),
                    reason: reason.into(),
                });
            }
            continue;
        }
        let at = Location::new(source).at_line(*line);
        // the status number (columns 65-72, digits in fixed columns, blanks read as 0): its
        // digits 3-4 are the subordinate entity switch, `00` for an independent entity
        let alone = a
            .get(66..68)
            .unwrap_or("")
            .trim_matches(|c| c == ' ' || c == '0')
            .is_empty();
        if ty == "110" && !matches!(field(b, 4).as_str(), "" | "0") {
            skipped.push(StepSkipped {
                id: seq,
                entity: format!("IGES entity 110 form {}", field(b, 4)),
                reason: "a ray or an unbounded line (forms 1 and 2), which no NURBS holds".into(),
            });
            continue;
        }
        // the curve or surface is defined in the coordinates of its transformation matrix
        let motion = match field(a, 6).as_str() {
            "" | "0" => None,
            _ if keep => None,
            at => match count(at).map_or_else(
                || {
                    Err(format!(
                        "its transformation matrix pointer \"{at}\" is not a directory entry"
                    ))
                },
                |at| matrix::chain(&matrices, at as u64),
            ) {
                Ok(m) => Some(m),
                Err(reason) => {
                    skipped.push(StepSkipped {
                        id: seq,
                        entity: format!("IGES entity {ty}"),
                        reason,
                    });
                    continue;
                }
            },
        };
        let start = count(&field(a, 1)).unwrap_or(0);
        let n = count(&field(b, 3)).unwrap_or(0);
        if start == 0 || n == 0 || start.checked_add(n - 1).is_none_or(|last| last > p.len()) {
            return Err(IoError::syntax(at, format!("entity {ty}: parameter data pointer {start} (+{n} lines) is outside the P section")));
        }
        lines_read = lines_read.saturating_add(n);
        if lines_read > p.len() {
            return Err(IoError::syntax(
                at,
                format!("entity {ty}: its parameter data (lines {start} to {}) are also another entity's; each entity has its own lines of the P section", start + n - 1),
            ));
        }
        let body: String = p[start - 1..start - 1 + n]
            .iter()
            .map(|(_, l)| l.get(..64).unwrap_or(l))
            .collect();
        let f = fields(&body, delim, record);
        let bad = |why: String| {
            IoError::syntax(
                Location::new(source).at_line(p[start - 1].0),
                format!("entity {ty} (D{seq}): {why}"),
            )
        };
        let r = |k: usize| real_at(&f, k).map_err(bad);
        let c = |k: usize| {
            f.get(k)
                .and_then(|s| count(s))
                .ok_or_else(|| bad(format!("parameter {k} is missing or not a count")))
        };
        let lib = |e: lekalo::Error| bad(e.to_string());
        if keep {
            raw.insert(
                seq,
                Raw {
                    ty: ty.clone(),
                    fields: f,
                    matrix: !matches!(field(a, 6).as_str(), "" | "0"),
                },
            );
            continue;
        }
        // The counts are checked against the parameters the entity holds before anything is
        // allocated: a declared size the file cannot back (a 23170 × 23170 net in a few lines)
        // is refused, and so is one whose arithmetic would overflow.
        let needs = |what: String, sizes: &[Option<usize>]| -> IoResult<()> {
            let total = sizes.iter().try_fold(0usize, |sum, &x| sum.checked_add(x?));
            match total {
                Some(t) if t <= f.len() => Ok(()),
                Some(t) => Err(bad(format!(
                    "{what} need {t} parameters, the entity has {}; the counts or the parameter data are wrong",
                    f.len()
                ))),
                None => Err(bad(format!(
                    "{what} need more parameters than any file holds; the counts are wrong"
                ))),
            }
        };
        if ty == "116" || ty == "123" {
            // the points and directions of analytic surfaces, which point at them
            refs.add(&ty, seq, &f, unit_mm, motion.as_ref());
            continue;
        }
        if ty == "106" {
            match analytic::copious(&field(b, 4), &f, unit_mm) {
                Ok(shape) => {
                    charge(seq, shape_size(&shape))?;
                    shapes.push((seq, place(shape, motion.as_ref()).map_err(lib)?));
                }
                Err(reason) => skipped.push(StepSkipped {
                    id: seq,
                    entity: format!("IGES entity 106 form {}", field(b, 4)),
                    reason,
                }),
            }
            continue;
        }
        if matches!(ty.as_str(), "108" | "190" | "192" | "194" | "196" | "198") {
            // built once every point, direction and curve is read
            match analytic::Analytic::from_parameters(&ty, &field(b, 4), &f, unit_mm) {
                Ok(s) => pending.push((seq, s, motion, alone)),
                Err(reason) => skipped.push(StepSkipped {
                    id: seq,
                    entity: format!("IGES entity {ty}"),
                    reason,
                }),
            }
            continue;
        }
        if ty == "141" || ty == "142" {
            // not read without the faces; the curves they point at are boundaries, so a
            // composite among them is not built as a curve of its own
            let pointers: Vec<usize> = if ty == "142" {
                [3, 4]
                    .iter()
                    .filter_map(|&k| f.get(k).and_then(|s| count(s)))
                    .collect()
            } else {
                boundary_curves(&f)
            };
            pointed_at.extend(pointers.into_iter().map(|x| x as u64));
            skipped.push(StepSkipped {
                id: seq,
                entity: format!("IGES entity {ty}"),
                reason: NOT_READ.into(),
            });
            continue;
        }
        if ty == "102" {
            // built once every curve is read: the members are anywhere in the file
            if !alone {
                skipped.push(StepSkipped {
                    id: seq,
                    entity: "IGES entity 102".into(),
                    reason: SUBORDINATE_COMPOSITE.into(),
                });
                continue;
            }
            let n = c(1)?;
            needs(format!("N = {n} (constituent curves)"), &[Some(2), Some(n)])?;
            let members = (2..n + 2).map(c).collect::<IoResult<Vec<usize>>>()?;
            composites.push((seq, members, motion));
            continue;
        }
        if ty == "118" || ty == "120" || ty == "122" {
            // built once every curve is read: they point at curves anywhere in the file
            let v = (1..=4).map(r).collect::<IoResult<Vec<f64>>>()?;
            let sweep = if topology {
                Err(SWEPT_IN_FACES.to_string())
            } else {
                swept::Sweep::from_parameters(&ty, &v, unit_mm)
            };
            match sweep {
                Ok(sweep) => sweeps.push((seq, sweep, motion)),
                Err(reason) => skipped.push(StepSkipped {
                    id: seq,
                    entity: format!("IGES entity {ty}"),
                    reason,
                }),
            }
            continue;
        }
        if ty == "100" || ty == "104" {
            // the numbers are syntax (a missing one fails the file, as for every entity); an
            // arc they do not describe is skipped with the reason, the rest of the file read
            let v = (1..=if ty == "100" { 7 } else { 11 })
                .map(r)
                .collect::<IoResult<Vec<f64>>>()?;
            let arc = if ty == "100" {
                conics::circular_arc(&v, unit_mm)
            } else {
                conics::conic_arc(&v, unit_mm)
            };
            match arc {
                Ok(shape) => shapes.push((seq, place(shape, motion.as_ref()).map_err(lib)?)),
                Err(reason) => skipped.push(StepSkipped {
                    id: seq,
                    entity: format!("IGES entity {ty}"),
                    reason,
                }),
            }
            continue;
        }
        if matches!(ty.as_str(), "110" | "112" | "114") {
            let num = |k: usize| real_at(&f, k);
            let shape = if ty == "110" {
                splines::line(&num, unit_mm)
            } else if ty == "112" {
                splines::spline_curve(&num, f.len(), unit_mm)
            } else {
                splines::spline_surface(&num, f.len(), unit_mm, resolution_mm)
            };
            let shape = shape.map_err(bad)?;
            if ty == "114" && topology && alone {
                independent.push(seq);
            }
            shapes.push((seq, place(shape, motion.as_ref()).map_err(lib)?));
            continue;
        }
        if ty == "126" {
            let (k, m, poly) = (c(1)?, c(2)?, c(5)? == 1);
            let n = k.checked_add(1);
            let nk = k.checked_add(m).and_then(|x| x.checked_add(2));
            needs(
                format!("K = {k}, M = {m} (upper index and degree)"),
                &[Some(7), nk, n, n.and_then(|n| n.checked_mul(3)), Some(2)],
            )?;
            let (Some(nk), Some(n)) = (nk, n) else {
                return Err(bad("the counts overflow".into()));
            };
            charge(seq, nk.saturating_add(n))?;
            let base = 7;
            let knots = (0..nk).map(|i| r(base + i)).collect::<IoResult<Vec<_>>>()?;
            let w = (0..=k)
                .map(|i| r(base + nk + i))
                .collect::<IoResult<Vec<_>>>()?;
            let pb = base + nk + k + 1;
            let mut data = Vec::with_capacity(3 * (k + 1));
            for i in 0..3 * (k + 1) {
                data.push(r(pb + i)? * unit_mm);
            }
            let ctrl = Points::from_flat(3, data).map_err(lib)?;
            let obj = if poly {
                Object::BSpline(BSplineCurve::new(m, knots, ctrl).map_err(lib)?)
            } else {
                Object::Nurbs(NurbsCurve::new(m, knots, ctrl, w).map_err(lib)?)
            };
            shapes.push((seq, place(Shape::Curve(obj), motion.as_ref()).map_err(lib)?));
        } else {
            let (k1, k2, m1, m2, poly) = (c(1)?, c(2)?, c(3)?, c(4)?, c(7)? == 1);
            let plus = |a: usize, b: usize| a.checked_add(b);
            let net = plus(k1, 1)
                .zip(plus(k2, 1))
                .and_then(|(a, b)| a.checked_mul(b));
            let n1 = plus(k1, m1).and_then(|x| plus(x, 2));
            let n2 = plus(k2, m2).and_then(|x| plus(x, 2));
            needs(
                format!("K1 = {k1}, K2 = {k2}, M1 = {m1}, M2 = {m2} (upper indices and degrees)"),
                &[
                    Some(10),
                    n1,
                    n2,
                    net.and_then(|x| x.checked_mul(4)),
                    Some(4),
                ],
            )?;
            let (Some(n1), Some(n2)) = (n1, n2) else {
                return Err(bad("the counts overflow".into()));
            };
            charge(
                seq,
                n1.saturating_add(n2)
                    .saturating_add(net.unwrap_or(usize::MAX)),
            )?;
            // both below the parameter count (checked above), so k + 1 does not overflow
            let (nu, nv) = (k1 + 1, k2 + 1);
            let base = 10;
            let ku = (0..n1).map(|i| r(base + i)).collect::<IoResult<Vec<_>>>()?;
            let kv = (0..n2)
                .map(|i| r(base + n1 + i))
                .collect::<IoResult<Vec<_>>>()?;
            let wb = base + n1 + n2;
            let pb = wb + nu * nv;
            let mut w = vec![0.0; nu * nv];
            let mut data = vec![0.0; 3 * nu * nv];
            for j in 0..nv {
                for i in 0..nu {
                    let src = j * nu + i;
                    w[i * nv + j] = r(wb + src)?;
                    for x in 0..3 {
                        data[3 * (i * nv + j) + x] = r(pb + 3 * src + x)? * unit_mm;
                    }
                }
            }
            let ctrl = Points::from_flat(3, data).map_err(lib)?;
            let s = if poly {
                Surface::BSpline(BSplineSurface::new(m1, m2, ku, kv, ctrl, (nu, nv)).map_err(lib)?)
            } else {
                Surface::Nurbs(NurbsSurface::new(m1, m2, ku, kv, ctrl, w, (nu, nv)).map_err(lib)?)
            };
            if topology && alone {
                independent.push(seq);
            }
            shapes.push((seq, place(Shape::Surface(s), motion.as_ref()).map_err(lib)?));
        }
    }
    composite::build(
        composites,
        &pointed_at,
        &mut shapes,
        &mut skipped,
        (resolution_mm, max_size),
        |s, m| place(s, m).map_err(|e| e.to_string()),
    );
    if !sweeps.is_empty() {
        let curves: std::collections::HashMap<u64, usize> = shapes
            .iter()
            .enumerate()
            .filter(|(_, (_, s))| matches!(s, Shape::Curve(_)))
            .map(|(k, (id, _))| (*id, k))
            .collect();
        for (seq, sweep, motion) in sweeps {
            let built = sweep
                .build(&shapes, &curves)
                .and_then(|s| place(Shape::Surface(s), motion.as_ref()).map_err(|e| e.to_string()));
            match built {
                Ok(shape) => shapes.push((seq, shape)),
                Err(reason) => skipped.push(StepSkipped {
                    id: seq,
                    entity: sweep.entity().into(),
                    reason,
                }),
            }
        }
    }
    let mut foreign = std::collections::HashSet::new();
    if !pending.is_empty() {
        let curves: std::collections::HashMap<u64, usize> = shapes
            .iter()
            .enumerate()
            .filter(|(_, (_, s))| matches!(s, Shape::Curve(_)))
            .map(|(k, (id, _))| (*id, k))
            .collect();
        let faces = if topology {
            analytic::face_curves(&raw)
        } else {
            std::collections::HashMap::new()
        };
        let mut built = Vec::new();
        for (seq, s, motion, alone) in pending {
            let curve = |id: u64| match curves.get(&id).map(|&k| &shapes[k].1) {
                Some(Shape::Curve(c)) => Some(c.clone()),
                _ => None,
            };
            let bounds: Option<Vec<[f64; 3]>> =
                faces.get(&seq).filter(|_| s.unbounded()).map(|ids| {
                    let mut pts = Vec::new();
                    for id in ids {
                        if let Some(Shape::Curve(c)) = curves.get(id).map(|&k| &shapes[k].1) {
                            let cp = c.control_points();
                            if cp.dim() == 3 {
                                pts.extend(
                                    cp.as_slice().chunks_exact(3).map(|p| [p[0], p[1], p[2]]),
                                );
                            }
                        }
                    }
                    pts
                });
            match s.build(&refs, &curve, bounds.as_deref(), motion.as_ref()) {
                Ok(shape) => {
                    charge(seq, shape_size(&shape))?;
                    if topology && alone && !s.unbounded() {
                        independent.push(seq);
                    }
                    foreign.insert(seq);
                    built.push((seq, shape));
                }
                Err(reason) => skipped.push(StepSkipped {
                    id: seq,
                    entity: s.entity().into(),
                    reason,
                }),
            }
        }
        shapes.extend(built);
    }
    if progress.is_active() {
        // complete: a flag set this late does not discard the result
        let _ = progress.step(READING, entities as u64, entities as u64);
    }
    let reasons = if topology {
        skipped.iter().map(|s| (s.id, s.reason.clone())).collect()
    } else {
        std::collections::HashMap::new()
    };
    let mut listing = Skips::new(listed);
    for s in skipped {
        listing.push(s);
    }
    listing.finish();
    Ok((
        IgesRead {
            shapes,
            skipped: listing,
            length_unit,
            scale_to_mm: unit_mm,
            faces: Vec::new(),
            skipped_faces: Skips::default(),
        },
        raw,
        independent,
        reasons,
        foreign,
    ))
}

/// The control points and knots of a curve or surface, as counted against the size limit.
fn shape_size(s: &Shape) -> usize {
    match s {
        Shape::Curve(c) => c.control_points().len() + c.knots().as_slice().len(),
        Shape::Surface(s) => s.control_points().len(),
        _ => 0,
    }
}
