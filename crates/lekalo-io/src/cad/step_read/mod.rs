//! Reading curves and surfaces from STEP files (ISO 10303-21 exchange structures of AP203,
//! AP214 and AP242).
//!
//! Read: B-spline curves and surfaces with their knots given (`B_SPLINE_*_WITH_KNOTS`) or
//! implied by their form (`UNIFORM_*`, `QUASI_UNIFORM_*`, `BEZIER_*`), plain or as the complex
//! instances that rational geometry takes (`(BOUNDED_CURVE() B_SPLINE_CURVE(…) … RATIONAL_B_SPLINE_CURVE(…)
//! …)`, and the surface analogue); lines, circles, ellipses and polylines, and `TRIMMED_CURVE`s
//! over any of these, trimmed by parameter values or points; planes, cylinders, cones, spheres,
//! tori and surfaces of revolution and linear extrusion (ISO 10303-42 §4.3–4.5). Analytic
//! geometry becomes exact NURBS built by the library; unbounded surfaces take the extent of the
//! faces on them. The length unit comes from the unit context: 3-D coordinates are converted to
//! millimetres, the unit [`crate::StepWriter`] declares, so that a file read and written again
//! describes the same geometry. A conversion factor of 1 (files in millimetres) leaves every
//! coordinate bit for bit as written. Curves of dimension 2 (parameter-space curves of faces)
//! are not scaled.
//!
//! With the faces ([`read_step_faces`]), the faces of triangles of AP242 are read as meshes
//! ([`StepRead::triangulations`]).
//!
//! Everything else that is geometry (parabolas, hyperbolas, offsets, composite curves, unbounded
//! lines and surfaces that nothing bounds, tessellated geometry) is listed in [`StepRead::skipped`]
//! with the reason, so a caller can tell the user what was left out ([`skipped_by_kind`] groups
//! them).
//!
//! The exchange structure is tokenized here rather than with `ruststep`'s parser: that parser
//! panics on integers and exponents beyond the range of `i64` (`1.0E99999999999999999999`),
//! which a reader of user files must report as an error, and its errors carry no line numbers.
//! The grammar needed (ISO 10303-21 §6–7: keywords, the six token kinds, lists, typed
//! parameters, simple and complex instances) is small.
//!
//! Memory: the text is parsed once to check it and to index its instances (20 bytes each:
//! offset, type and id); an instance's parameters are parsed from the text when the conversion
//! asks for them and dropped after, so a read holds the text, that index and what it converts,
//! about 2.6 times the file's size for a file of B-spline faces (see
//! `docs/performance/data.md`).
//!
//! | file | subject |
//! |---|---|
//! | `parse.rs` | the exchange structure's lexer and parser: the whole text checked, each instance kept as its id, offset and type (its parameters parsed when asked for), and the header's schema |
//! | `entities.rs` | decoding of the B-spline curve and surface entities (given or implied knots); the geometry that is skipped |
//! | `assembly.rs` | the placements of parts in assemblies (occurrences and their item-defined transformations), and which instances are each placed part's geometry |
//! | `analytic.rs` | placements, lines, conics, polylines and the analytic surfaces, converted by the library; trimmed curves over any of them |
//! | `bounds.rs` | the ranges of lines from their edges, and of unbounded surfaces from their faces |
//! | `units.rs` | the file's length unit and its factor to millimetres; its plane angle unit |
//! | `faces.rs` | faces: `ADVANCED_FACE`, bounds, edge loops, oriented edges, edge curves cut at their vertices, pcurves in the surface's parameters ([`StepFace`]) |
//! | `tessellated.rs` | faces of triangles (`TRIANGULATED_FACE`, `COMPLEX_TRIANGULATED_FACE`, the triangulated surface sets) read as meshes: strips and fans decoded, `pnindex` followed, checked ([`StepTriangulation`]) |
//! | `skips.rs` | the report of what was not read: counts by kind and the first entities listed ([`Skips`]), bounded by the kinds, not the entities |
//! | `progress.rs` | the progress of a read through the library's hook: bytes parsed, instances converted per pass |
//! | `driver.rs` | [`read_step`]: parse, unit, then each geometric entity read or listed as skipped; [`read_step_limited`] within a size limit |
//! | `tests.rs`, `analytic_tests.rs`, `faces_tests.rs`, `pole_tests.rs`, `tessellated_tests.rs` | tests |

mod analytic;
#[cfg(test)]
mod analytic_tests;
mod assembly;
mod bounds;
mod driver;
mod entities;
mod faces;
#[cfg(test)]
pub(crate) mod faces_tests;
mod parse;
#[cfg(test)]
mod pole_tests;
mod progress;
mod skips;
mod tessellated;
#[cfg(test)]
mod tessellated_tests;
#[cfg(test)]
mod tests;
mod units;

pub use driver::{read_step, read_step_faces, read_step_limited, read_step_with_progress};
pub use faces::{StepFace, STEP_LOOP_RTOL, STEP_SHARED_VERTEX_RTOL};
pub use skips::{Skips, OTHER_KINDS, SKIPPED_KINDS, SKIPPED_LISTED};
pub use tessellated::StepTriangulation;

use crate::shape::Shape;

/// A geometric entity of the file that was not read.
#[derive(Debug, Clone, PartialEq)]
pub struct StepSkipped {
    /// Entity instance id (`#id`).
    pub id: u64,
    /// Entity type, e.g. `CIRCLE`.
    pub entity: String,
    /// Why it was skipped.
    pub reason: String,
}

/// Entities skipped for one reason: their type, the reason, how many and the first id.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SkippedKind {
    /// Entity type, e.g. `CIRCLE` or `IGES entity 144`.
    pub entity: String,
    /// Why they were skipped: the reason of the first of them (the entity `first_id`), whose
    /// references to other entities may differ from the others' ([`skipped_by_kind`]).
    pub reason: String,
    /// How many entities of the file share the type and the reason.
    pub count: usize,
    /// The smallest id among them (`#id` in STEP, the directory entry's sequence number in IGES).
    pub first_id: u64,
}

/// The skipped entities of [`StepRead::skipped`] or [`crate::IgesRead::skipped`] grouped by
/// type and reason, the entities a reason names masked (`curve #12 is …` and `curve #13 is …`
/// are one kind): the report of what a file holds that was not read, most frequent first
/// (then by type). Each kind keeps the reason of its first entity. Linear in the number of
/// entries.
///
/// ```
/// use lekalo_io::{skipped_by_kind, StepSkipped};
/// let s = |id, e: &str, r: &str| StepSkipped { id, entity: e.into(), reason: r.into() };
/// let k = skipped_by_kind(&[
///     s(4, "B", "r"),
///     s(2, "A", "r"),
///     s(7, "B", "r"),
///     s(9, "T", "curve #8 is too deep"),
///     s(8, "T", "curve #7 is too deep"),
/// ]);
/// assert_eq!((k[0].entity.as_str(), k[0].count, k[0].first_id), ("B", 2, 4));
/// assert_eq!((k[1].entity.as_str(), k[1].count, k[1].first_id), ("T", 2, 8));
/// assert_eq!(k[1].reason, "curve #7 is too deep");
/// assert_eq!((k[2].entity.as_str(), k[2].count), ("A", 1));
/// ```
#[must_use]
pub fn skipped_by_kind(skipped: &[StepSkipped]) -> Vec<SkippedKind> {
    let mut s = Skips::new(0);
    for x in skipped {
        s.push(x.clone());
    }
    s.finish();
    s.kinds().to_vec()
}

/// What [`read_step`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRead {
    /// The curves and surfaces read, with the id of their entity instance, in id order.
    pub shapes: Vec<(u64, Shape)>,
    /// Geometric entities that were not read: counted by kind, the first listed in id order.
    pub skipped: Skips,
    /// The faces, in id order ([`read_step_faces`]; empty from [`read_step`]).
    pub faces: Vec<StepFace>,
    /// The faces of triangles ([`read_step_faces`]; empty from [`read_step`]):
    /// `TRIANGULATED_FACE`, `COMPLEX_TRIANGULATED_FACE` and the triangulated surface sets of
    /// AP242, each a mesh as the file gives it, in id order.
    pub triangulations: Vec<StepTriangulation>,
    /// The faces that were not read, with the reason ([`read_step_faces`]): counted by kind,
    /// the first listed in id order.
    pub skipped_faces: Skips,
    /// The schema named in the header's `FILE_SCHEMA`, e.g. `AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }`.
    pub schema: Option<String>,
    /// The length unit of the unit context, e.g. `millimetre`, `metre`, `INCH (25.4 mm)`;
    /// `millimetre (assumed)` when the file declares none.
    pub length_unit: String,
    /// The factor that converted 3-D coordinates to millimetres (1 for files in millimetres).
    pub scale_to_mm: f64,
}

/// A parameter of an entity instance (ISO 10303-21 §6.3, §7.3).
#[derive(Debug, Clone, PartialEq)]
enum P {
    Num(f64),
    Str(String),
    Enum(String),
    Ref(u64),
    Unset,
    Derived,
    List(Vec<P>),
    Typed(String, Vec<P>),
}

/// One record `NAME(params)`.
type Record = (String, Vec<P>);

/// An entity instance of the file: its type (the names of its records, known from the parse)
/// and its records, parsed from the text the first time they are asked for and dropped with
/// it (see [`parse::Instances`]).
struct Instance<'a> {
    text: &'a str,
    /// The offset of the instance's `#` in `text`.
    at: usize,
    names: &'a [String],
    records: std::cell::OnceCell<Vec<Record>>,
}

impl<'a> Instance<'a> {
    fn new(text: &'a str, at: usize, names: &'a [String]) -> Self {
        Instance {
            text,
            at,
            names,
            records: std::cell::OnceCell::new(),
        }
    }

    /// The records, parsed on the first call.
    fn records(&self) -> &[Record] {
        self.records
            .get_or_init(|| parse::records_at(self.text, self.at))
    }

    /// The parameters of the record `name`; the text is parsed only when the instance has one.
    fn get(&self, name: &str) -> Option<&[P]> {
        if !self.has(name) {
            return None;
        }
        self.records()
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_slice())
    }

    /// The numbers of a simple instance `NAME('name', (x, y, …))` (a point, a direction)
    /// read straight from the text, without building its records; `None` for any other
    /// instance, or one whose records are already parsed: the caller then reads the records.
    fn numbers(&self) -> Option<Vec<f64>> {
        if self.names.len() != 1 || self.records.get().is_some() {
            return None;
        }
        parse::numbers_at(self.text, self.at)
    }

    fn has(&self, name: &str) -> bool {
        self.names.iter().any(|n| n == name)
    }

    /// The names of the records, in the order written.
    fn names(&self) -> &'a [String] {
        self.names
    }

    /// The line of the file where the instance starts.
    fn line(&self) -> usize {
        parse::line_of(self.text, self.at)
    }

    /// The type name for reports: the record's name, or the most specific of a complex one.
    fn type_name(&self) -> String {
        if self.names.len() == 1 {
            return self.names[0].clone();
        }
        format!("({})", self.names.join(" "))
    }
}

type Why = String;

fn num(p: &P) -> Option<f64> {
    match p {
        P::Num(x) => Some(*x),
        P::Typed(_, inner) if inner.len() == 1 => num(&inner[0]),
        _ => None,
    }
}

fn int(p: &P) -> Option<usize> {
    let x = num(p)?;
    // a count: integral and far below any size the library accepts
    if x >= 0.0 && x.fract() == 0.0 && x < 1e15 {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Some(x as usize)
    } else {
        None
    }
}

/// The attributes of a record after its name: a simple instance's record starts with the
/// inherited `name` (a string), a complex instance's record holds its own attributes only
/// (the name is in its `REPRESENTATION_ITEM` record).
fn unnamed(r: &[P]) -> &[P] {
    match r.first() {
        Some(P::Str(_)) => &r[1..],
        _ => r,
    }
}

fn list(p: &P) -> Option<&[P]> {
    match p {
        P::List(l) => Some(l),
        _ => None,
    }
}

fn numbers(p: &P, what: &str) -> Result<Vec<f64>, Why> {
    list(p)
        .and_then(|l| l.iter().map(num).collect::<Option<Vec<f64>>>())
        .ok_or_else(|| format!("{what} is not a list of numbers"))
}
