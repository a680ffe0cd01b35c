//! Curves from Parquet, as written by the writer.
//!
//! A row group's rows are turned into curves in parallel (the checks of the curves'
//! constructors are most of the reading once the columns are decoded); their order is kept.

use std::path::Path;

use arrow_array::cast::AsArray;
use arrow_array::{Array, ListArray, RecordBatch};
use rayon::prelude::*;

use super::columns::{Keys, Numbers, RowGroups};
use super::{GroupKey, DEFAULT_KEY};
use crate::error::{IoError, IoResult, Location};
use crate::object::Object;

/// Reads the curves of a Parquet file written by
/// [`ParquetBatchWriter::write_curves`](super::ParquetBatchWriter::write_curves) a batch of
/// rows at a time (a few MiB, within a row group); `each` gets the batch's `(key, curve)` pairs, a row with an `error` or an invalid curve as an
/// error naming its key. The control points of a row are read as one slice of the inner
/// lists' values (no array or vector per point).
///
/// # Errors
/// As [`read_point_groups`](super::read_point_groups), and for a file without the curve
/// columns.
pub fn read_curve_groups(
    path: &Path,
    key: Option<&str>,
    mut each: impl FnMut(Vec<(GroupKey, IoResult<Object>)>) -> IoResult<()>,
) -> IoResult<()> {
    let key = key.unwrap_or(DEFAULT_KEY);
    let rg = RowGroups::open(path)?;
    let source = rg.source.clone();
    let schema = rg.schema().clone();
    let col = |name: &str| {
        schema.index_of(name).map_err(|_| {
            IoError::syntax(
                Location::new(&source),
                format!("no column `{name}`; a curves file has the columns {key}, type, degree, dim, knots, control and weights (docs/formats.md)"),
            )
        })
    };
    let cols = CurveColumns {
        key: col(key)?,
        kind: col("type")?,
        degree: col("degree")?,
        knots: col("knots")?,
        control: col("control")?,
        weights: col("weights")?,
        error: schema.index_of("error").ok(),
    };
    for g in 0..rg.count() {
        for batch in rg.read(g)? {
            let out = cols.curves(&batch?, key, &source)?;
            if !out.is_empty() {
                each(out)?;
            }
        }
    }
    Ok(())
}

/// The indices of the columns of a curves file.
struct CurveColumns {
    key: usize,
    kind: usize,
    degree: usize,
    knots: usize,
    control: usize,
    weights: usize,
    error: Option<usize>,
}

/// The columns of one batch of curves, typed.
struct Batch<'a> {
    kinds: &'a arrow_array::StringArray,
    degrees: Keys<'a>,
    knots: &'a ListArray,
    control: &'a ListArray,
    /// The inner lists of `control`, one per point.
    points: &'a ListArray,
    weights: &'a ListArray,
}

impl CurveColumns {
    /// The curves of `batch`, in its order.
    fn curves(
        &self,
        batch: &RecordBatch,
        key: &str,
        source: &str,
    ) -> IoResult<Vec<(GroupKey, IoResult<Object>)>> {
        let bad = |what: &str| {
            IoError::syntax(
                Location::new(source).at_field(what),
                "the column does not have the type of docs/formats.md#parquet-batches",
            )
        };
        let list = |c: usize, what: &str| {
            batch
                .column(c)
                .as_list_opt::<i32>()
                .ok_or_else(|| bad(what))
        };
        let keys = Keys::of(batch.column(self.key).as_ref()).ok_or_else(|| bad(key))?;
        let control = list(self.control, "control")?;
        let points = control
            .values()
            .as_list_opt::<i32>()
            .ok_or_else(|| bad("control"))?;
        let b = Batch {
            kinds: batch
                .column(self.kind)
                .as_string_opt::<i32>()
                .ok_or_else(|| bad("type"))?,
            degrees: Keys::of(batch.column(self.degree).as_ref())
                .and_then(integer)
                .ok_or_else(|| bad("degree"))?,
            knots: list(self.knots, "knots")?,
            control,
            points,
            weights: list(self.weights, "weights")?,
        };
        let errors = self
            .error
            .and_then(|c| batch.column(c).as_string_opt::<i32>());
        let null_key = |r: usize| {
            IoError::syntax(
                Location::new(source).at_field(key),
                format!("row {}: a null key", r + 1),
            )
        };
        (0..batch.num_rows())
            .into_par_iter()
            .map(|r| {
                let k = keys.get(r).ok_or_else(|| null_key(r))?;
                let at = Location::new(format!("{source}: group {k}"));
                let obj = match errors.filter(|e| e.is_valid(r)) {
                    Some(e) => Err(IoError::syntax(at, format!("no curve: {}", e.value(r)))),
                    None => b.curve(r, &at),
                };
                Ok((k, obj))
            })
            .collect()
    }
}

/// The numbers of row `r` of the list column `l`, named `what` in errors.
fn list_row(l: &ListArray, r: usize, at: &Location, what: &str) -> IoResult<Vec<f64>> {
    let bad = |m: String| IoError::syntax(at.clone().at_field(what), m);
    if l.is_null(r) {
        return Err(bad("null".into()));
    }
    let values =
        Numbers::of(l.values().as_ref()).ok_or_else(|| bad("not a list of numbers".into()))?;
    let range = span(l.value_offsets(), r, r + 1);
    let a = range.start;
    let mut out = Vec::with_capacity(range.len());
    values
        .extend_range(range, &mut out)
        .map_err(|i| bad(format!("value {} is null", i - a)))?;
    Ok(out)
}

/// The range of the values of the lists `from..to` given the lists' offsets.
fn span(offsets: &[i32], from: usize, to: usize) -> std::ops::Range<usize> {
    let index = |o: i32| usize::try_from(o).unwrap_or(0);
    index(offsets[from])..index(offsets[to])
}

/// `k` if it is an integer column.
fn integer(k: Keys<'_>) -> Option<Keys<'_>> {
    matches!(k, Keys::I32(_) | Keys::I64(_)).then_some(k)
}

impl Batch<'_> {
    /// The control points of row `r`: their dimension and their coordinates.
    fn control_row(&self, r: usize, at: &Location) -> IoResult<(usize, Vec<f64>)> {
        let bad = |m: String| IoError::syntax(at.clone().at_field("control"), m);
        // the inner lists of one row lie end to end in the inner values, so the coordinates
        // are one slice of them, copied at once
        if self.control.is_null(r) {
            return Err(bad("null".into()));
        }
        let inner = self.points;
        let points = span(self.control.value_offsets(), r, r + 1);
        let (p0, p1) = (points.start, points.end);
        let offsets = inner.value_offsets();
        let mut dim = None;
        for i in p0..p1 {
            if inner.is_null(i) {
                return Err(bad(format!("point {} is null", i - p0)));
            }
            let len = span(offsets, i, i + 1).len();
            if let Some(d) = dim.filter(|&d| d != len) {
                return Err(bad(format!(
                    "point {} has {len} coordinates, point 0 has {d}",
                    i - p0
                )));
            }
            dim = Some(len);
        }
        let d = dim.unwrap_or(0);
        let values = Numbers::of(inner.values().as_ref())
            .ok_or_else(|| bad("not a list of lists of numbers".into()))?;
        let range = span(offsets, p0, p1);
        let a = range.start;
        let mut ctrl = Vec::with_capacity(range.len());
        values.extend_range(range, &mut ctrl).map_err(|j| {
            let k = j - a;
            bad(format!(
                "point {} value {} is null",
                k / d.max(1),
                k % d.max(1)
            ))
        })?;
        Ok((d, ctrl))
    }

    /// The curve of row `r` (a row without an error).
    fn curve(&self, r: usize, at: &Location) -> IoResult<Object> {
        let kind = if self.kinds.is_valid(r) {
            self.kinds.value(r)
        } else {
            ""
        };
        let (dim, ctrl) = self.control_row(r, at)?;
        let invalid = |field: &str, error| IoError::Invalid {
            at: at.clone().at_field(field),
            error,
        };
        let ctrl = lekalo::Points::from_flat(dim, ctrl).map_err(|e| invalid("control", e))?;
        let degree = || {
            match self.degrees.get(r) {
                Some(GroupKey::Int(d)) => usize::try_from(d).ok(),
                _ => None,
            }
            .ok_or_else(|| IoError::syntax(at.clone().at_field("degree"), "not a degree"))
        };
        match kind {
            "bezier_curve" => lekalo::BezierCurve::new(ctrl)
                .map(Object::Bezier)
                .map_err(|e| invalid("control", e)),
            "bspline_curve" => {
                lekalo::BSplineCurve::new(degree()?, list_row(self.knots, r, at, "knots")?, ctrl)
                    .map(Object::BSpline)
                    .map_err(|e| invalid("knots", e))
            }
            "nurbs_curve" => lekalo::NurbsCurve::new(
                degree()?,
                list_row(self.knots, r, at, "knots")?,
                ctrl,
                list_row(self.weights, r, at, "weights")?,
            )
            .map(Object::Nurbs)
            .map_err(|e| invalid("weights", e)),
            other => Err(IoError::syntax(
                at.clone().at_field("type"),
                format!("\"{other}\" is not a curve type; expected bezier_curve, bspline_curve or nurbs_curve"),
            )),
        }
    }
}
