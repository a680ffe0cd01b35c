//! Reading B-spline and NURBS curves and surfaces from STEP files (ISO 10303-21 exchange
//! structures of AP203, AP214 and AP242).
//!
//! Read: `B_SPLINE_CURVE_WITH_KNOTS` and `B_SPLINE_SURFACE_WITH_KNOTS`, plain or as the complex
//! instances that Open CASCADE and FreeCAD write for rational geometry
//! (`(BOUNDED_CURVE() B_SPLINE_CURVE(…) B_SPLINE_CURVE_WITH_KNOTS(…) … RATIONAL_B_SPLINE_CURVE(…)
//! …)`, and the surface analogue), and `TRIMMED_CURVE` over a B-spline basis trimmed by
//! `PARAMETER_VALUE`s (ISO 10303-42 §4.4.7, §4.4.13–15, §4.4.29, §4.4.35–37). The length unit
//! comes from the unit context: 3-D coordinates are converted to millimetres, the unit
//! [`crate::StepWriter`] declares, so that a file read and written again describes the same
//! geometry. A conversion factor of 1 (files in millimetres) leaves every coordinate bit for bit
//! as written. Curves of dimension 2 (parameter-space curves of faces) are not scaled.
//!
//! Everything else that is geometry (lines, conics, elementary and swept surfaces, implicit-knot
//! B-splines such as `BEZIER_CURVE`, trims by points) is listed in [`StepRead::skipped`] with the
//! reason, so a caller can tell the user what was left out.
//!
//! The exchange structure is tokenized here rather than with `ruststep`'s parser: that parser
//! panics on integers and exponents beyond the range of `i64` (`1.0E99999999999999999999`),
//! which a reader of user files must report as an error, and its errors carry no line numbers.
//! The grammar needed (ISO 10303-21 §6–7: keywords, the six token kinds, lists, typed
//! parameters, simple and complex instances) is small.
//!
//! | file | subject |
//! |---|---|
//! | `parse.rs` | the exchange structure's lexer and parser: instances by id and the header's schema |
//! | `entities.rs` | decoding of the B-spline curve and surface entities, trimmed curves and the trims' splitting; the geometry that is skipped |
//! | `units.rs` | the file's length unit and its factor to millimetres |
//! | `driver.rs` | [`read_step`]: parse, unit, then each geometric entity read or listed as skipped |
//! | `tests.rs` | tests |

mod analytic;
#[cfg(test)]
mod analytic_tests;
mod bounds;
mod driver;
mod entities;
mod parse;
#[cfg(test)]
mod tests;
mod units;

pub use driver::read_step;

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

/// What [`read_step`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRead {
    /// The curves and surfaces read, with the id of their entity instance, in id order.
    pub shapes: Vec<(u64, Shape)>,
    /// Geometric entities that were not read, in id order.
    pub skipped: Vec<StepSkipped>,
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

#[derive(Debug, Clone)]
struct Instance {
    records: Vec<Record>,
    line: usize,
}

impl Instance {
    fn get(&self, name: &str) -> Option<&[P]> {
        self.records
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_slice())
    }

    fn has(&self, name: &str) -> bool {
        self.records.iter().any(|(n, _)| n == name)
    }

    /// The type name for reports: the record's name, or the most specific of a complex one.
    fn type_name(&self) -> String {
        if self.records.len() == 1 {
            return self.records[0].0.clone();
        }
        let names: Vec<&str> = self.records.iter().map(|(n, _)| n.as_str()).collect();
        format!("({})", names.join(" "))
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
