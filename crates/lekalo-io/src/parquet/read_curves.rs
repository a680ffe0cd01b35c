//! Curves from Parquet, as written by the writer.
//!
//! A row group's rows are turned into curves in parallel (the checks of the curves'
//! constructors are most of the reading once the columns are decoded); their order is kept.
//! The control points, a list of lists, are decoded from their values and levels by Parquet's
//! column reader when they have the writer's layout (`control_leaf`, `ControlRows`), and
//! through Arrow's nested list arrays otherwise; both give the same curves and errors (the
//! round-trip property test and the test of other writers' lists read their files both ways).

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
/// rows at a time (about a MiB, within a row group); `each` gets the batch's `(key, curve)`
/// pairs, a row with an `error` or an invalid curve as an error naming its key. The control
/// points of a row are one slice of the column's values (no array or vector per point).
///
/// # Errors
/// As [`read_point_groups`](super::read_point_groups), and for a file without the curve
/// columns.
pub fn read_curve_groups(
    path: &Path,
    key: Option<&str>,
    each: impl FnMut(Vec<(GroupKey, IoResult<Object>)>) -> IoResult<()>,
) -> IoResult<()> {
    read_curves(path, key, true, each)
}

/// [`read_curve_groups`], with the control points decoded from their levels where the layout
/// allows it if `levels` (else always through Arrow: the tests compare the two).
pub(super) fn read_curves(
    path: &Path,
    key: Option<&str>,
    levels: bool,
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
    let levels = control_leaf(&rg, cols.control).filter(|_| levels);
    for g in 0..rg.count() {
        match levels {
            // the control points by Parquet's column reader, the other columns by Arrow's
            Some(leaf) => {
                let mut control = rg.double_column(g, leaf)?;
                let mut decoded = ControlRows::default();
                let others = cols.without_control();
                for batch in rg.read_without(g, Some(cols.control))? {
                    let batch = batch?;
                    decoded
                        .read(&mut control, batch.num_rows())
                        .map_err(|e| super::columns::parquet_err(&source, e))?;
                    let out = others.curves(&batch, Control::Levels(&decoded), key, &source)?;
                    if !out.is_empty() {
                        each(out)?;
                    }
                }
            }
            None => {
                for batch in rg.read(g)? {
                    let batch = batch?;
                    let control = Control::Arrow(batch.column(cols.control).as_ref());
                    let out = cols.curves(&batch, control, key, &source)?;
                    if !out.is_empty() {
                        each(out)?;
                    }
                }
            }
        }
    }
    Ok(())
}

/// The leaf column of `control` (root column `root`) if it is the writer's layout: a list
/// that is never null of lists that are never null of doubles that are never null (maximum
/// definition and repetition levels 2). Its levels then say all there is to know, and
/// [`ControlRows`] reads them directly, without Arrow's nested list arrays (whose levels were
/// most of the decoding of a curves file). Other writers' layouts (nullable lists) go through
/// Arrow.
pub(super) fn control_leaf(rg: &RowGroups, root: usize) -> Option<usize> {
    let schema = rg.parquet_schema();
    let mut leaves = (0..schema.num_columns()).filter(|&i| schema.get_column_root_idx(i) == root);
    let leaf = leaves.next()?;
    let c = schema.column(leaf);
    let plain = leaves.next().is_none()
        && c.max_def_level() == 2
        && c.max_rep_level() == 2
        && c.physical_type() == parquet::basic::Type::DOUBLE
        && rg.schema().field(root).data_type()
            == &arrow_schema::DataType::List(std::sync::Arc::new(
                arrow_schema::Field::new_list_field(
                    arrow_schema::DataType::List(std::sync::Arc::new(
                        arrow_schema::Field::new_list_field(arrow_schema::DataType::Float64, false),
                    )),
                    false,
                ),
            ));
    plain.then_some(leaf)
}

/// The control points of a batch of rows decoded from their levels (see [`control_leaf`]):
/// the coordinates end to end, and per row its dimension and the range of its coordinates, or
/// why its points are unusable.
#[derive(Default)]
struct ControlRows {
    values: Vec<f64>,
    rows: Vec<Result<(usize, std::ops::Range<usize>), String>>,
    def: Vec<i16>,
    rep: Vec<i16>,
}

impl ControlRows {
    /// Reads the next `n` rows of `column` (whose levels are those of [`control_leaf`]),
    /// replacing the previous batch's. A row starts at repetition level 0; a point at level
    /// 0 or 1 with a definition level of at least 1 (0: a row without points); a coordinate
    /// wherever the definition level is 2 (1: a point without coordinates).
    fn read(
        &mut self,
        column: &mut parquet::column::reader::ColumnReaderImpl<parquet::data_type::DoubleType>,
        n: usize,
    ) -> Result<(), String> {
        self.values.clear();
        self.rows.clear();
        self.def.clear();
        self.rep.clear();
        let mut read = 0;
        while read < n {
            let (records, _, _) = column
                .read_records(
                    n - read,
                    Some(&mut self.def),
                    Some(&mut self.rep),
                    &mut self.values,
                )
                .map_err(|e| e.to_string())?;
            if records == 0 {
                return Err(format!("the control column ends after {read} of {n} rows"));
            }
            read += records;
        }
        let mut row: Option<RowLevels> = None;
        let mut value = 0usize;
        for (&d, &r) in self.def.iter().zip(&self.rep) {
            if r == 0 {
                if let Some(done) = row.take() {
                    self.rows.push(done.finish(value));
                }
                row = Some(RowLevels::starting_at(value));
            }
            let Some(at) = row.as_mut() else {
                return Err("the control column starts inside a row".into());
            };
            if d >= 1 && r <= 1 {
                at.next_point();
            }
            if d == 2 {
                at.len += 1;
                value += 1;
            }
        }
        if let Some(done) = row.take() {
            self.rows.push(done.finish(value));
        }
        if self.rows.len() != n || value != self.values.len() {
            return Err(format!(
                "the control column's levels give {} rows and {value} values for {n} rows and {} values",
                self.rows.len(),
                self.values.len()
            ));
        }
        Ok(())
    }
}

/// A row of control points being gathered from the levels.
struct RowLevels {
    /// Its first coordinate among the batch's values.
    start: usize,
    /// The coordinates of its first point, once that point is complete.
    dim: Option<usize>,
    /// The coordinates of the current point so far.
    len: usize,
    /// The points begun.
    points: usize,
    /// The first point whose length is not the first point's.
    problem: Option<String>,
}

impl RowLevels {
    fn starting_at(start: usize) -> Self {
        RowLevels {
            start,
            dim: None,
            len: 0,
            points: 0,
            problem: None,
        }
    }

    /// The current point (if any) is complete: it sets the dimension, or is checked against it.
    fn close_point(&mut self) {
        if self.points == 0 || self.problem.is_some() {
            return;
        }
        match self.dim {
            None => self.dim = Some(self.len),
            Some(d) if d != self.len => {
                self.problem = Some(format!(
                    "point {} has {} coordinates, point 0 has {d}",
                    self.points - 1,
                    self.len
                ));
            }
            Some(_) => {}
        }
    }

    /// A point begins.
    fn next_point(&mut self) {
        self.close_point();
        self.points += 1;
        self.len = 0;
    }

    /// The row's dimension and coordinates (it ends before value `end`), or its problem.
    fn finish(mut self, end: usize) -> Result<(usize, std::ops::Range<usize>), String> {
        self.close_point();
        match self.problem {
            Some(p) => Err(p),
            None => Ok((self.dim.unwrap_or(0), self.start..end)),
        }
    }
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
    control: Points<'a>,
    weights: &'a ListArray,
}

/// The control points of a batch.
enum Points<'a> {
    /// `control` as Arrow's lists, and its inner lists (one per point).
    Lists(&'a ListArray, &'a ListArray),
    /// Decoded from the column's levels.
    Levels(&'a ControlRows),
}

/// Where the control points of a batch come from.
enum Control<'a> {
    /// Arrow's `control` column, a list of lists.
    Arrow(&'a dyn Array),
    /// The levels and values of the column, decoded by [`ControlRows`].
    Levels(&'a ControlRows),
}

impl CurveColumns {
    /// The indices of the other columns in a batch read without `control`.
    fn without_control(&self) -> CurveColumns {
        let shift = |c: usize| if c > self.control { c - 1 } else { c };
        CurveColumns {
            key: shift(self.key),
            kind: shift(self.kind),
            degree: shift(self.degree),
            knots: shift(self.knots),
            control: self.control,
            weights: shift(self.weights),
            error: self.error.map(shift),
        }
    }

    /// The curves of `batch`, in its order, their control points from `control`.
    fn curves(
        &self,
        batch: &RecordBatch,
        control: Control<'_>,
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
        let control = match control {
            Control::Arrow(c) => {
                let lists = c.as_list_opt::<i32>().ok_or_else(|| bad("control"))?;
                let points = lists
                    .values()
                    .as_list_opt::<i32>()
                    .ok_or_else(|| bad("control"))?;
                Points::Lists(lists, points)
            }
            Control::Levels(rows) => Points::Levels(rows),
        };
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
        let (control, inner) = match self.control {
            Points::Lists(control, inner) => (control, inner),
            Points::Levels(rows) => {
                return match &rows.rows[r] {
                    Ok((dim, range)) => Ok((*dim, rows.values[range.clone()].to_vec())),
                    Err(problem) => Err(bad(problem.clone())),
                }
            }
        };
        // the inner lists of one row lie end to end in the inner values, so the coordinates
        // are one slice of them, copied at once
        if control.is_null(r) {
            return Err(bad("null".into()));
        }
        let points = span(control.value_offsets(), r, r + 1);
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
