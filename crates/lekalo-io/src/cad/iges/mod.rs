//! IGES 5.3 (Initial Graphics Exchange Specification): rational B-spline curves (entity 126)
//! and surfaces (entity 128), written and read; lines (entity 110), parametric spline curves
//! (entity 112) and surfaces (entity 114) read as exact B-splines (`splines.rs`).
//!
//! A file is 80-column records in five sections: Start (`S`), Global (`G`: delimiters, units,
//! precision), Directory Entry (`D`: two records per entity), Parameter Data (`P`: the entity's
//! numbers, comma-separated, `;` at the end) and Terminate (`T`: the section counts). Entity 126
//! carries `K, M, PROP1–4`, the `K + M + 2` knots, `K + 1` weights, the control points, the
//! parameter range and a normal; entity 128 the same per direction with the net stored `u`
//! fastest (IGES 5.3 §4.23, §4.24). Polynomial objects are written with `PROP3 = 1` and unit
//! weights and read back as B-splines.
//!
//! Reals are written in the shortest form that reads back to the same `f64` and read correctly
//! rounded (`D` exponents accepted), so a round trip is exact. The units of the Global section
//! (flag 1–11) convert coordinates to millimetres. Entities of other types, and 126/128 entities
//! with a transformation matrix, are listed as skipped.
//!
//! | file | subject |
//! |---|---|
//! | `splines.rs` | entities 110, 112 and 114 as exact B-splines |
//! | `faces_write.rs` | faces written as trimmed surfaces (144 over 128, boundaries 142 with composite curves 102 of 126) |
//! | `faces.rs` | trimmed (144) and bounded (143) surfaces with their boundaries (142, 141) and composite curves (102) as faces ([`read_iges_faces`]) |

use std::fmt::Write as _;

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points, Progress};

mod faces;
mod faces_write;
mod splines;

pub use faces::read_iges_faces;
use faces::Raw;

use crate::error::{IoError, IoResult, Location};
use crate::object::Object;
use crate::shape::{Shape, Surface};
use crate::step::step_real;
use crate::step_read::{StepFace, StepSkipped};

/// What [`read_iges`] found: the shapes with their directory-entry sequence numbers, what was
/// skipped, the unit.
#[derive(Debug, Clone, PartialEq)]
pub struct IgesRead {
    /// Curves and surfaces, with the sequence number of their directory entry.
    pub shapes: Vec<(u64, Shape)>,
    /// Entities not read (`id` is the directory entry's sequence number, `entity` its type).
    pub skipped: Vec<StepSkipped>,
    /// The unit named by the Global section, e.g. `MM`, `IN`.
    pub length_unit: String,
    /// The factor that converted coordinates to millimetres.
    pub scale_to_mm: f64,
    /// The trimmed surfaces (entities 144 and 143) read as faces, with the sequence number of
    /// their directory entry in `id` ([`read_iges_faces`]; empty from [`read_iges`]).
    pub faces: Vec<StepFace>,
    /// The trimmed and bounded surfaces not read as faces, with the reason
    /// ([`read_iges_faces`]).
    pub skipped_faces: Vec<StepSkipped>,
}

/// Builds one IGES file from curves and surfaces.
#[derive(Debug, Clone, Default)]
pub struct IgesWriter {
    /// `(entity type, form, parameter text, status number)` per entity.
    entities: Vec<(u32, u32, Vec<String>, &'static str)>,
}

/// The status number of an independent entity (IGES 5.3 §2.2.4.4.9: visible, independent,
/// geometry use, top-down).
const INDEPENDENT: &str = "00000000";

fn pad3(p: &[f64]) -> [f64; 3] {
    let mut c = [0.0; 3];
    c[..p.len()].copy_from_slice(p);
    c
}

fn check_dim(dim: usize) -> IoResult<()> {
    if dim == 0 || dim > 3 {
        return Err(IoError::Unsupported {
            what: format!(
                "IGES holds points in 1 to 3 dimensions, these have {dim}; project the data first"
            ),
        });
    }
    Ok(())
}

impl IgesWriter {
    /// An empty file.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a curve as entity 126.
    ///
    /// # Errors
    /// [`IoError::Unsupported`] for points of dimension above 3.
    pub fn add_object(&mut self, obj: &Object) -> IoResult<()> {
        let t = Self::curve_params(obj)?;
        self.push(126, t, INDEPENDENT);
        Ok(())
    }

    /// Appends an entity of form 0; returns its directory entry's sequence number.
    pub(crate) fn push(&mut self, ty: u32, params: Vec<String>, status: &'static str) -> usize {
        self.entities.push((ty, 0, params, status));
        2 * self.entities.len() - 1
    }

    /// The parameters of entity 126 for `obj`.
    pub(crate) fn curve_params(obj: &Object) -> IoResult<Vec<String>> {
        check_dim(obj.dim())?;
        let p = obj.degree();
        let knots = obj.knots();
        let ctrl = obj.control_points();
        let n = ctrl.len();
        let weights = obj.weights();
        let (a, b) = obj.domain();
        let mut t: Vec<String> = vec!["126".into(), (n - 1).to_string(), p.to_string()];
        let planar = ctrl.dim() < 3 || ctrl.iter().all(|q| q[2] == 0.0);
        t.extend(
            [usize::from(planar), 0, usize::from(weights.is_none()), 0].map(|x| x.to_string()),
        );
        t.extend(knots.as_slice().iter().map(|&x| step_real(x)));
        match &weights {
            Some(w) => t.extend(w.iter().map(|&x| step_real(x))),
            None => t.extend(std::iter::repeat_n("1.".to_string(), n)),
        }
        for q in ctrl.iter() {
            t.extend(pad3(q).iter().map(|&x| step_real(x)));
        }
        t.extend([step_real(a), step_real(b)]);
        t.extend(["0.", "0.", if planar { "1." } else { "0." }].map(String::from));
        Ok(t)
    }

    /// Adds a surface as entity 128.
    ///
    /// # Errors
    /// [`IoError::Unsupported`] for points of dimension above 3.
    pub fn add_surface(&mut self, s: &Surface) -> IoResult<()> {
        let t = Self::surface_params(s)?;
        self.push(128, t, INDEPENDENT);
        Ok(())
    }

    /// The parameters of entity 128 for `s`.
    pub(crate) fn surface_params(s: &Surface) -> IoResult<Vec<String>> {
        check_dim(s.dim())?;
        let (pu, pv) = s.degrees();
        let (nu, nv) = s.net_size();
        let (ku, kv) = s.knots();
        let ctrl = s.control_points();
        let weights = s.weights();
        let ((u0, u1), (v0, v1)) = s.domain();
        let mut t: Vec<String> = vec!["128".into()];
        t.extend(
            [
                nu - 1,
                nv - 1,
                pu,
                pv,
                0,
                0,
                usize::from(weights.is_none()),
                0,
                0,
            ]
            .map(|x| x.to_string()),
        );
        t.extend(
            ku.as_slice()
                .iter()
                .chain(kv.as_slice())
                .map(|&x| step_real(x)),
        );
        // u varies fastest
        for j in 0..nv {
            for i in 0..nu {
                t.push(
                    weights
                        .as_ref()
                        .map_or_else(|| "1.".to_string(), |w| step_real(w[i * nv + j])),
                );
            }
        }
        for j in 0..nv {
            for i in 0..nu {
                t.extend(pad3(ctrl.point(i * nv + j)).iter().map(|&x| step_real(x)));
            }
        }
        t.extend([u0, u1, v0, v1].map(step_real));
        Ok(t)
    }

    /// The complete file; `name` is the file name in the Global section, `timestamp` its date
    /// (`YYYYMMDD.HHNNSS`; pass a fixed value for reproducible files).
    #[must_use]
    pub fn finish(&self, name: &str, timestamp: &str) -> String {
        let mut out = String::new();
        let line = |out: &mut String, text: &str, section: char, seq: usize| {
            let _ = writeln!(out, "{text:<72}{section}{seq:>7}");
        };
        line(&mut out, "lekalo spline export", 'S', 1);
        let h = |s: &str| format!("{}H{s}", s.len());
        let max_coord = self
            .entities
            .iter()
            .flat_map(|(_, _, t, _)| t.iter().filter_map(|x| x.parse::<f64>().ok()))
            .fold(0.0_f64, |m, x| m.max(x.abs()));
        let global = [
            h(","),
            h(";"),
            h(name),
            h(name),
            h("lekalo"),
            h(env!("CARGO_PKG_VERSION")),
            "32".into(),
            "308".into(),
            "15".into(),
            "308".into(),
            "15".into(),
            h(name),
            "1.".into(),
            "2".into(),
            h("MM"),
            "1".into(),
            "1.".into(),
            h(timestamp),
            "1.E-10".into(),
            step_real(max_coord),
            h("lekalo"),
            h(""),
            "11".into(),
            "0".into(),
            h(timestamp),
        ];
        let glines = pack(&global, 72);
        for (k, g) in glines.iter().enumerate() {
            line(&mut out, g, 'G', k + 1);
        }
        // parameter lines first (to know the pointers), then the directory
        let mut dir = String::new();
        let mut par = String::new();
        let mut pseq = 1;
        for (k, (ty, form, t, status)) in self.entities.iter().enumerate() {
            let de = 2 * k + 1;
            let lines = pack(t, 64);
            let start = pseq;
            for l in &lines {
                let _ = writeln!(par, "{l:<64}{de:>8}P{pseq:>7}");
                pseq += 1;
            }
            let _ = writeln!(
                dir,
                "{ty:>8}{start:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{status:>8}D{de:>7}",
                0, 0, 0, 0, 0, 0
            );
            let _ = writeln!(
                dir,
                "{ty:>8}{:>8}{:>8}{:>8}{form:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}",
                0,
                0,
                lines.len(),
                "",
                "",
                "",
                0,
                de + 1
            );
        }
        out.push_str(&dir);
        out.push_str(&par);
        let t = format!(
            "S{:>7}G{:>7}D{:>7}P{:>7}",
            1,
            glines.len(),
            2 * self.entities.len(),
            pseq - 1
        );
        line(&mut out, &t, 'T', 1);
        out
    }
}

/// Tokens joined by `,` (the last followed by `;`), packed into lines of at most `width`
/// characters without splitting a token.
fn pack(tokens: &[String], width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for (k, t) in tokens.iter().enumerate() {
        let piece = format!("{t}{}", if k + 1 == tokens.len() { ';' } else { ',' });
        if !cur.is_empty() && cur.len() + piece.len() > width {
            lines.push(std::mem::take(&mut cur));
        }
        cur.push_str(&piece);
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// Splits a parameter text at `delim` outside Hollerith strings, up to the record delimiter.
/// A Hollerith count beyond the text (up to 2^64 − 1, or more digits than that) takes the rest
/// of the text.
fn fields(text: &str, delim: char, record: char) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut cur = String::new();
    // whether `cur` holds only blanks so far: a Hollerith count can start only there. Kept as
    // a flag so that a long field is not scanned again for every character (that was
    // quadratic in the field's length).
    let mut blank = true;
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_ascii_digit() && blank {
            // a Hollerith string nHxxx: digits then H then n characters
            let mut j = i;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
            if j < chars.len() && chars[j] == 'H' {
                let n: usize = chars[i..j]
                    .iter()
                    .collect::<String>()
                    .parse()
                    .unwrap_or(usize::MAX);
                let end = (j + 1).saturating_add(n).min(chars.len());
                cur = chars[j + 1..end].iter().collect();
                blank = cur.trim().is_empty();
                i = end;
                continue;
            }
        }
        if c == delim {
            out.push(std::mem::take(&mut cur));
            blank = true;
        } else if c == record {
            out.push(std::mem::take(&mut cur));
            return out;
        } else {
            cur.push(c);
            blank &= c.is_whitespace();
        }
        i += 1;
    }
    out.push(cur);
    out
}

fn real(s: &str) -> Option<f64> {
    let t = s.trim().replace(['D', 'd'], "E");
    if t.is_empty() {
        return Some(0.0);
    }
    t.parse::<f64>().ok().filter(|x| x.is_finite())
}

fn count(s: &str) -> Option<usize> {
    let t = s.trim();
    if t.is_empty() {
        return Some(0);
    }
    t.parse::<usize>().ok()
}

/// The unit of flag `f` (IGES 5.3 §2.2.4.3, field 14) in millimetres, and its name.
fn unit(flag: usize, name: &str) -> Option<(String, f64)> {
    let mm = match flag {
        1 => 25.4,
        2 => 1.0,
        4 => 304.8,
        5 => 1_609_344.0,
        6 => 1000.0,
        7 => 1e6,
        8 => 0.0254,
        9 => 1e-3,
        10 => 10.0,
        11 => 2.54e-5,
        3 => match name.trim().to_ascii_uppercase().as_str() {
            "MM" => 1.0,
            "IN" | "INCH" => 25.4,
            "M" => 1000.0,
            "CM" => 10.0,
            _ => return None,
        },
        _ => return None,
    };
    Some((name.trim().to_string(), mm))
}

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
/// assert!(matches!(e, IoError::TooLarge { .. }) && e.to_string().contains("--max-size"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`read_iges`]; [`IoError::TooLarge`] naming the count and `--max-size` for a file above
/// the limit.
pub fn read_iges_limited(text: &str, source: &str, max_size: usize) -> IoResult<IgesRead> {
    read_entities(text, source, max_size, false, &Progress::new()).map(|(r, _)| r)
}

/// What an IGES read reports itself as.
const READING: &str = "reading IGES";

/// Directory entries read between two consultations of the progress hook.
const REPORT_ENTITIES: usize = 1 << 10;

/// [`read_iges_limited`] (or [`read_iges_faces`] with `faces`) that reports to `progress` and
/// stops when its cancel flag is set: `(entities read, entities)` of the directory section,
/// every 1024 entities and never inside one (the result is the same with or without the hook),
/// `(total, total)` last.
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
/// let e = read_iges_with_progress(&text, "line.igs", 1000, false,
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
    progress: &Progress<'_>,
) -> IoResult<IgesRead> {
    if faces {
        faces::read_faces_with_progress(text, source, max_size, progress)
    } else {
        read_entities(text, source, max_size, false, progress).map(|(r, _)| r)
    }
}

/// The entities of a file as [`read_iges_limited`] reads them and, with `topology`, the
/// parameters of the composite curves, curves on surfaces, boundaries, bounded and trimmed
/// surfaces (entities 102, 141, 142, 143, 144) by sequence number, which the faces are built
/// from. `progress` is told the directory entries read.
fn read_entities(
    text: &str,
    source: &str,
    max_size: usize,
    topology: bool,
    progress: &Progress<'_>,
) -> IoResult<(IgesRead, std::collections::HashMap<u64, Raw>)> {
    let mut raw = std::collections::HashMap::new();
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
    // model space scale: model units per drawing unit; coordinates are in model units
    let _ = scale_field;
    let mut shapes = Vec::new();
    let mut skipped = Vec::new();
    let entities = d.len() / 2;
    if entities > max_size {
        return Err(IoError::TooLarge {
            what: format!(
                "{source}: {entities} entities in the directory section, above the size limit {max_size}; raise the limit with --max-size {entities} if the machine has the memory"
            ),
        });
    }
    // control points and knots of the B-splines read so far, against the size limit
    let mut used = 0usize;
    let mut charge = |seq: u64, n: usize| -> IoResult<()> {
        used = used.saturating_add(n);
        if used > max_size {
            return Err(IoError::TooLarge {
                what: format!(
                    "{source}: entity D{seq}: {used} control points and knots with this entity's {n}, above the size limit {max_size}; raise the limit with --max-size {used} if the machine has the memory"
                ),
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
        if !keep && !matches!(ty.as_str(), "110" | "112" | "114" | "126" | "128") {
            if matches!(
                ty.as_str(),
                "100"
                    | "102"
                    | "104"
                    | "106"
                    | "108"
                    | "118"
                    | "120"
                    | "122"
                    | "130"
                    | "140"
                    | "141"
                    | "142"
                    | "143"
                    | "144"
                    | "190"
                    | "192"
                    | "194"
                    | "196"
                    | "198"
            ) {
                skipped.push(StepSkipped {
                    id: seq,
                    entity: format!("IGES entity {ty}"),
                    reason: "not read (lekalo reads entities 110, 112, 114, 126 and 128)".into(),
                });
            }
            continue;
        }
        let at = Location::new(source).at_line(*line);
        if ty == "110" && !matches!(field(b, 4).as_str(), "" | "0") {
            skipped.push(StepSkipped {
                id: seq,
                entity: format!("IGES entity 110 form {}", field(b, 4)),
                reason: "a ray or an unbounded line (forms 1 and 2), which no NURBS holds".into(),
            });
            continue;
        }
        if !keep && !matches!(field(a, 6).as_str(), "" | "0") {
            skipped.push(StepSkipped {
                id: seq,
                entity: format!("IGES entity {ty}"),
                reason: "has a transformation matrix (entity 124), which is not applied".into(),
            });
            continue;
        }
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
        let r = |k: usize| {
            f.get(k)
                .and_then(|s| real(s))
                .ok_or_else(|| bad(format!("parameter {k} is missing or not a number")))
        };
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
        if ty == "110" || ty == "112" || ty == "114" {
            let num = |k: usize| {
                f.get(k)
                    .and_then(|s| real(s))
                    .ok_or_else(|| format!("parameter {k} is missing or not a number"))
            };
            let shape = if ty == "110" {
                splines::line(&num, unit_mm)
            } else if ty == "112" {
                splines::spline_curve(&num, f.len(), unit_mm)
            } else {
                splines::spline_surface(&num, f.len(), unit_mm)
            };
            shapes.push((seq, shape.map_err(bad)?));
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
            shapes.push((seq, Shape::Curve(obj)));
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
            shapes.push((seq, Shape::Surface(s)));
        }
    }
    if progress.is_active() {
        // complete: a flag set this late does not discard the result
        let _ = progress.step(READING, entities as u64, entities as u64);
    }
    Ok((
        IgesRead {
            shapes,
            skipped,
            length_unit,
            scale_to_mm: unit_mm,
            faces: Vec::new(),
            skipped_faces: Vec::new(),
        },
        raw,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_every_kind_bit_for_bit() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let ctrl =
            Points::from_3d(&[[1.0, 0.0, 0.1], [1.0, 1.0, 1.0 / 3.0], [0.0, 1.0, 1e-300]]).unwrap();
        let nurbs = Object::Nurbs(
            NurbsCurve::new(
                2,
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                ctrl.clone(),
                vec![1.0, w, 1.0],
            )
            .unwrap(),
        );
        let bs = Object::BSpline(
            BSplineCurve::new(2, vec![0.5, 0.5, 0.5, 2.0, 2.0, 2.0], ctrl).unwrap(),
        );
        let net = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.7],
            [0.0, 2.0, 0.1],
            [1.0, 0.0, -0.3],
            [1.0, 1.0, 1.0 / 7.0],
            [1.0, 2.0, 0.0],
        ])
        .unwrap();
        let s = Surface::BSpline(
            BSplineSurface::new(
                1,
                2,
                vec![0.0, 0.0, 2.0, 2.0],
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                net.clone(),
                (2, 3),
            )
            .unwrap(),
        );
        let n = Surface::Nurbs(
            NurbsSurface::new(
                1,
                2,
                vec![0.0, 0.0, 2.0, 2.0],
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                net,
                vec![1.0, 0.5, 2.0, 1.5, 1.0, 0.25],
                (2, 3),
            )
            .unwrap(),
        );
        let mut wr = IgesWriter::new();
        wr.add_object(&nurbs).unwrap();
        wr.add_object(&bs).unwrap();
        wr.add_surface(&s).unwrap();
        wr.add_surface(&n).unwrap();
        let text = wr.finish("t", "20000101.000000");
        for l in text.lines() {
            assert_eq!(l.len(), 80, "{l}");
        }
        let r = read_iges(&text, "t.igs").unwrap();
        let got: Vec<Shape> = r.shapes.into_iter().map(|(_, s)| s).collect();
        assert_eq!(got[0], Shape::Curve(nurbs));
        assert_eq!(got[1], Shape::Curve(bs));
        assert_eq!(got[2], Shape::Surface(s));
        let (Shape::Surface(Surface::Nurbs(a)), Surface::Nurbs(b)) = (&got[3], &n) else {
            panic!("a NURBS surface")
        };
        assert_eq!(a.weights(), b.weights());
        assert_eq!(a.control_points(), b.control_points());
        assert_eq!(r.scale_to_mm, 1.0);
    }

    #[test]
    fn errors_name_the_line() {
        let e = read_iges("short line\n", "x.igs").unwrap_err().to_string();
        assert!(e.starts_with("x.igs:1:"), "{e}");
        let mut wr = IgesWriter::new();
        let c = Object::BSpline(
            BSplineCurve::new(
                1,
                vec![0.0, 0.0, 1.0, 1.0],
                Points::from_2d(&[[0.0, 0.0], [1.0, 1.0]]).unwrap(),
            )
            .unwrap(),
        );
        wr.add_object(&c).unwrap();
        let text = wr.finish("t", "20000101.000000").replace(
            "126,1,1,1,0,1,0,0.,0.,1.,1.,",
            "126,1,1,1,0,1,0,0.,2.,1.,1.,",
        );
        assert!(text.contains("0.,2.,1.,1."), "{text}");
        let e = read_iges(&text, "x.igs").unwrap_err().to_string();
        assert!(e.contains("entity 126"), "{e}");
    }

    /// An IGES file with the Global section `global` and one entity of type `ty` whose parameter
    /// data is `params`, laid out in 80-column records as a writer would.
    pub(super) fn one_entity(global: &str, ty: u32, params: &str) -> String {
        let mut out = format!("{:<72}S{:>7}\n", "hostile", 1);
        // padded by bytes: the reader finds the section letter at byte 72
        let pad = 72usize.saturating_sub(global.len());
        out += &format!("{global}{}G{:>7}\n", " ".repeat(pad), 1);
        let lines: Vec<&str> = params
            .as_bytes()
            .chunks(64)
            .map(|c| std::str::from_utf8(c).unwrap())
            .collect();
        let d = |fields: [String; 9], seq: usize| {
            let mut l: String = fields.iter().map(|f| format!("{f:>8}")).collect();
            l += &format!("D{seq:>7}\n");
            l
        };
        let s = |x: usize| x.to_string();
        out += &d(
            [
                ty.to_string(),
                s(1),
                s(0),
                s(0),
                s(0),
                s(0),
                s(0),
                s(0),
                "00000000".into(),
            ],
            1,
        );
        out += &d(
            [
                ty.to_string(),
                s(0),
                s(0),
                s(lines.len()),
                s(0),
                String::new(),
                String::new(),
                String::new(),
                s(0),
            ],
            2,
        );
        for (i, l) in lines.iter().enumerate() {
            out += &format!("{l:<64}{:>8}P{:>7}\n", 1, i + 1);
        }
        out += &format!("{:<72}T{:>7}\n", "S      1G      1D      2P      1", 1);
        out
    }

    const SEGMENT: &str = "126,1,1,0,0,1,0,0.,0.,1.,1.,1.,1.,0.,0.,0.,1.,1.,0.,0.,1.,0.,0.,1.;";

    #[test]
    fn hostile_global_sections_are_read_without_panics() {
        let r = read_iges(&one_entity("1H,,1H;;", 126, SEGMENT), "ok.igs").unwrap();
        assert_eq!(r.shapes.len(), 1, "the file of the tests below reads");
        // a Hollerith count of 2^64 - 1 overflowed the end index; one with more digits than
        // that parsed as 0; a multi-byte delimiter after 1H was sliced inside its bytes
        for global in [
            "18446744073709551615Habc;",
            "1H,,1H;,99999999999999999999999Habc;",
            "1H,,1Hé,3Habc;",
            "é,1H;;",
        ] {
            let r = read_iges(&one_entity(global, 126, SEGMENT), "g.igs");
            assert!(r.is_ok(), "{global}: {r:?}");
        }
        // é as the parameter delimiter: read as such (here the data use ',', so entity 126
        // has no readable counts, a named error)
        let e = read_iges(&one_entity("1Hé,1H;;", 126, SEGMENT), "g.igs").unwrap_err();
        assert!(e.to_string().starts_with("g.igs:5: entity 126"), "{e}");
        // in the parameter data too
        let text = one_entity("1H,,1H;;", 126, "126,18446744073709551615H1,1;");
        let e = read_iges(&text, "p.igs").unwrap_err().to_string();
        assert!(e.starts_with("p.igs:5: entity 126"), "{e}");
    }

    #[test]
    fn reading_is_linear_in_long_fields_and_shared_parameter_lines() {
        // a field of 200,000 digits was scanned again for every digit (quadratic)
        let long = format!(
            "126,{}1,1,0,0,1,0;",
            " ".repeat(100_000) + &"7".repeat(200_000)
        );
        let start = std::time::Instant::now();
        let e = read_iges(&one_entity("1H,,1H;;", 126, &long), "long.igs").unwrap_err();
        assert!(start.elapsed().as_secs() < 5, "{:?}", start.elapsed());
        assert!(e.to_string().contains("parameter 1"), "{e}");
        // many directory entries pointing at the same parameter lines would read them once
        // per entry: refused
        let one = one_entity("1H,,1H;;", 126, SEGMENT);
        let d: Vec<&str> = one.lines().filter(|l| l.get(72..73) == Some("D")).collect();
        let again: String = d
            .iter()
            .enumerate()
            .map(|(k, l)| format!("{}{:>7}\n", &l[..73], k + 3))
            .collect();
        let shared = one.replacen(&format!("{}\n", d[1]), &format!("{}\n{again}", d[1]), 1);
        let e = read_iges(&shared, "shared.igs").unwrap_err().to_string();
        assert!(e.contains("also another entity's"), "{e}");
    }

    #[test]
    fn declared_sizes_the_file_cannot_hold_are_refused_before_allocation() {
        let refused = |ty: u32, params: &str| {
            read_iges(&one_entity("1H,,1H;;", ty, params), "h.igs")
                .unwrap_err()
                .to_string()
        };
        // a 23170 x 23170 net (2^31 points) in a few bytes aborted on allocation
        let e = refused(128, "128,23169,23169,1,1,0,0,1,0,0,0.,0.,1.,1.;");
        assert!(
            e.starts_with("h.igs:5: entity 128")
                && e.contains("need 2147441958 parameters, the entity has 14"),
            "{e}"
        );
        // counts whose sums or products overflow
        for (ty, params) in [
            (128, "128,18446744073709551615,1,1,1,0,0,1,0,0;"),
            (128, "128,4294967296,4294967296,1,1,0,0,1,0,0;"),
            (126, "126,18446744073709551615,1,0,0,1,0;"),
            (126, "126,1,18446744073709551614,0,0,1,0;"),
        ] {
            let e = refused(ty, params);
            assert!(
                e.contains("more parameters than any file holds"),
                "{params}: {e}"
            );
        }
        // a curve whose counts promise more numbers than it has
        let e = refused(126, "126,3,1,0,0,1,0,0.,0.,1.,1.;");
        assert!(
            e.contains("K = 3, M = 1") && e.contains("need 31 parameters"),
            "{e}"
        );
    }
    #[test]
    fn progress_reports_the_entities_and_cancels() {
        use std::sync::atomic::{AtomicBool, Ordering};
        use std::sync::Mutex;

        let mut w = IgesWriter::new();
        for k in 0..3000 {
            let x = f64::from(k);
            let c = BSplineCurve::new(
                1,
                vec![0.0, 0.0, 1.0, 1.0],
                Points::from_rows(&[vec![x, 0.0, 0.0], vec![x, 1.0, 0.0]]).unwrap(),
            )
            .unwrap();
            w.add_object(&Object::BSpline(c)).unwrap();
        }
        let text = w.finish("lines.igs", "20000101.000000");
        let plain = read_iges(&text, "l.igs").unwrap();
        let seen = Mutex::new(Vec::new());
        let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
        let hooked = read_iges_with_progress(
            &text,
            "l.igs",
            usize::MAX,
            false,
            &Progress::new().with_report(&report),
        )
        .unwrap();
        assert_eq!(hooked, plain, "the hook changed the result");
        let seen = seen.into_inner().unwrap();
        assert_eq!(
            seen,
            vec![(0, 3000), (1024, 3000), (2048, 3000), (3000, 3000)]
        );
        let stop = AtomicBool::new(false);
        let report = |d: u64, _: u64| stop.store(d >= 1024, Ordering::Relaxed);
        for faces in [false, true] {
            let e = read_iges_with_progress(
                &text,
                "l.igs",
                usize::MAX,
                faces,
                &Progress::new().with_report(&report).with_cancel(&stop),
            )
            .unwrap_err();
            assert!(matches!(e, IoError::Cancelled { .. }), "{e:?}");
            assert_eq!(e.to_string(), "l.igs: reading IGES: cancelled");
        }
    }
}

#[cfg(test)]
mod faces_tests;
