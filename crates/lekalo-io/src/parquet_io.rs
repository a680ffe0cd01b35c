//! Parquet batches (docs/formats.md#parquet-batches): many point sets in, many curves out, and
//! curves in, samples out, streamed one row group at a time so that memory is bounded by the
//! row-group size whatever the file size.
//!
//! - **Point sets** come in one of two layouts:
//!   - *long*: a key column (`group` unless named otherwise) and one numeric column per
//!     coordinate (every other column, in the file's order), one row per point; the rows of a
//!     group are consecutive (sorted by the key, or written group by group);
//!   - *lists*: the key column and one column per coordinate holding a list of numbers, one
//!     row per group.
//! - **Curves** are one row per curve: the key (same name and type as in the input), `type`,
//!   `degree`, `dim`, `knots` (list of double), `control` (list of lists of double, one inner
//!   list per control point), `weights` (list of double, empty unless rational) and `error`
//!   (null, or why the group gave no curve; `type`, `degree` and `dim` are then null and the
//!   lists empty). Lists are never null: see [`ParquetBatchWriter::write_curves`].
//! - **Samples** are one row per sample: the key, then the columns of `lekalo eval` (`t`, the
//!   coordinates `x, y, z` or `x1 … xd` above 3-D, derivatives, curvature).
//!
//! A group that cannot be read (a null coordinate, lists of different lengths, a key seen
//! before) is returned as an error with its key, and the others go on.

use std::fs::File;
use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use arrow_array::builder::{
    Float64Builder, Int32Builder, Int64Builder, ListBuilder, StringBuilder,
};
use arrow_array::cast::AsArray;
use arrow_array::types::{Float32Type, Float64Type, Int32Type, Int64Type};
use arrow_array::{Array, ArrayRef, RecordBatch};
use arrow_schema::DataType;
use parquet::arrow::arrow_reader::{
    ArrowReaderMetadata, ArrowReaderOptions, ParquetRecordBatchReaderBuilder,
};
use parquet::arrow::ArrowWriter;
use parquet::basic::Compression;
use parquet::file::properties::WriterProperties;
use parquet::schema::types::ColumnPath;

use crate::error::{IoError, IoResult, Location};
use crate::object::Object;

/// The key of a group: an integer or a string column.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum GroupKey {
    /// From an integer column.
    Int(i64),
    /// From a string column.
    Str(String),
}

impl std::fmt::Display for GroupKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GroupKey::Int(k) => write!(f, "{k}"),
            GroupKey::Str(s) => write!(f, "{s:?}"),
        }
    }
}

/// One group of a Parquet batch: its key and its points, or why they could not be read.
pub type PointGroup = (GroupKey, IoResult<lekalo::Points>);

/// The key column's name when none is given.
pub const DEFAULT_KEY: &str = "group";

fn parquet_err(source: &str, e: impl std::fmt::Display) -> IoError {
    IoError::syntax(
        Location::new(source),
        format!("not a readable Parquet file: {e}"),
    )
}

/// A file's row groups, read one at a time.
struct RowGroups {
    file: File,
    meta: ArrowReaderMetadata,
    source: String,
}

impl RowGroups {
    fn open(path: &Path) -> IoResult<Self> {
        let source = path.display().to_string();
        let file = File::open(path).map_err(|error| IoError::Read {
            path: path.to_path_buf(),
            error,
        })?;
        let meta = ArrowReaderMetadata::load(&file, ArrowReaderOptions::new())
            .map_err(|e| parquet_err(&source, e))?;
        Ok(RowGroups { file, meta, source })
    }

    fn count(&self) -> usize {
        self.meta.metadata().num_row_groups()
    }

    fn schema(&self) -> &arrow_schema::Schema {
        self.meta.schema()
    }

    /// The batches of row group `i` (one, unless the group is very large).
    fn read(&self, i: usize) -> IoResult<Vec<RecordBatch>> {
        let rows = self.meta.metadata().row_group(i).num_rows();
        let file = self.file.try_clone().map_err(|error| IoError::Read {
            path: self.source.clone().into(),
            error,
        })?;
        ParquetRecordBatchReaderBuilder::new_with_metadata(file, self.meta.clone())
            .with_row_groups(vec![i])
            .with_batch_size(usize::try_from(rows).unwrap_or(1).clamp(1, 1 << 20))
            .build()
            .map_err(|e| parquet_err(&self.source, e))?
            .map(|b| b.map_err(|e| parquet_err(&self.source, e)))
            .collect()
    }
}

/// A numeric column (or the values of a list column) as `f64`s.
enum Numbers<'a> {
    F64(&'a arrow_array::Float64Array),
    F32(&'a arrow_array::Float32Array),
    I64(&'a arrow_array::Int64Array),
    I32(&'a arrow_array::Int32Array),
}

impl<'a> Numbers<'a> {
    fn of(a: &'a dyn Array) -> Option<Self> {
        if let Some(x) = a.as_primitive_opt::<Float64Type>() {
            Some(Numbers::F64(x))
        } else if let Some(x) = a.as_primitive_opt::<Float32Type>() {
            Some(Numbers::F32(x))
        } else if let Some(x) = a.as_primitive_opt::<Int64Type>() {
            Some(Numbers::I64(x))
        } else {
            a.as_primitive_opt::<Int32Type>().map(Numbers::I32)
        }
    }

    /// Value `i`, `None` if null.
    #[allow(clippy::cast_precision_loss)] // integers are read as the nearest f64
    fn get(&self, i: usize) -> Option<f64> {
        match self {
            Numbers::F64(a) => a.is_valid(i).then(|| a.value(i)),
            Numbers::F32(a) => a.is_valid(i).then(|| f64::from(a.value(i))),
            Numbers::I64(a) => a.is_valid(i).then(|| a.value(i) as f64),
            Numbers::I32(a) => a.is_valid(i).then(|| f64::from(a.value(i))),
        }
    }
}

/// The key column.
enum Keys<'a> {
    I64(&'a arrow_array::Int64Array),
    I32(&'a arrow_array::Int32Array),
    Str(&'a arrow_array::StringArray),
    LargeStr(&'a arrow_array::LargeStringArray),
}

impl<'a> Keys<'a> {
    fn of(a: &'a dyn Array) -> Option<Self> {
        if let Some(x) = a.as_primitive_opt::<Int64Type>() {
            Some(Keys::I64(x))
        } else if let Some(x) = a.as_primitive_opt::<Int32Type>() {
            Some(Keys::I32(x))
        } else if let Some(x) = a.as_string_opt::<i32>() {
            Some(Keys::Str(x))
        } else {
            a.as_string_opt::<i64>().map(Keys::LargeStr)
        }
    }

    fn get(&self, i: usize) -> Option<GroupKey> {
        match self {
            Keys::I64(a) => a.is_valid(i).then(|| GroupKey::Int(a.value(i))),
            Keys::I32(a) => a.is_valid(i).then(|| GroupKey::Int(i64::from(a.value(i)))),
            Keys::Str(a) => a.is_valid(i).then(|| GroupKey::Str(a.value(i).to_string())),
            Keys::LargeStr(a) => a.is_valid(i).then(|| GroupKey::Str(a.value(i).to_string())),
        }
    }
}

/// The layout of a point-set file, found from its schema.
struct Layout {
    key: usize,
    coords: Vec<(usize, String)>,
    lists: bool,
}

fn layout(schema: &arrow_schema::Schema, key: &str, source: &str) -> IoResult<Layout> {
    let at = Location::new(source);
    let names: Vec<&str> = schema.fields().iter().map(|f| f.name().as_str()).collect();
    let k = names.iter().position(|n| *n == key).ok_or_else(|| {
        IoError::syntax(
            at.clone(),
            format!(
                "no key column `{key}` (columns: {}); name the column that groups the points with --group-column",
                names.join(", ")
            ),
        )
    })?;
    if !matches!(
        schema.field(k).data_type(),
        DataType::Int64 | DataType::Int32 | DataType::Utf8 | DataType::LargeUtf8
    ) {
        return Err(IoError::syntax(
            at.at_field(key),
            format!(
                "the key column is {}; it must be an integer or a string",
                schema.field(k).data_type()
            ),
        ));
    }
    let numeric = |t: &DataType| {
        matches!(
            t,
            DataType::Float64 | DataType::Float32 | DataType::Int64 | DataType::Int32
        )
    };
    let mut coords = Vec::new();
    let mut lists = None;
    for (i, f) in schema.fields().iter().enumerate() {
        if i == k {
            continue;
        }
        let is_list = match f.data_type() {
            t if numeric(t) => false,
            DataType::List(inner) | DataType::LargeList(inner) if numeric(inner.data_type()) => {
                true
            }
            other => {
                return Err(IoError::syntax(
                    at.clone().at_field(f.name()),
                    format!("the column is {other}, not numbers; every column other than the key `{key}` is a coordinate (double, float or integer, or a list of them)"),
                ))
            }
        };
        if lists.is_some_and(|l| l != is_list) {
            return Err(IoError::syntax(
                at.clone().at_field(f.name()),
                "the coordinate columns mix numbers and lists; use one row per point (numbers) or one row per group (lists)",
            ));
        }
        lists = Some(is_list);
        coords.push((i, f.name().clone()));
    }
    if coords.is_empty() {
        return Err(IoError::syntax(
            at,
            format!("no coordinate columns besides the key `{key}`"),
        ));
    }
    Ok(Layout {
        key: k,
        coords,
        lists: lists.unwrap_or(false),
    })
}

/// A group being gathered in the long layout (it may go on in the next row group).
struct Open {
    key: GroupKey,
    data: Vec<f64>,
    error: Option<IoError>,
}

impl Open {
    fn finish(self, dim: usize) -> PointGroup {
        let points = match self.error {
            Some(e) => Err(e),
            None => lekalo::Points::from_flat(dim, self.data).map_err(|error| IoError::Invalid {
                at: Location::new(format!("group {}", self.key)),
                error,
            }),
        };
        (self.key, points)
    }
}

/// Reads the point sets of a Parquet file one row group at a time, calling `each` with the
/// groups completed by each row group (a group running on into the next row group is passed
/// with that one). `key` names the key column ([`DEFAULT_KEY`] if `None`).
///
/// # Errors
/// [`IoError::Read`] if the file cannot be opened; [`IoError::Syntax`] for a file that is not
/// Parquet, a missing key column, a column that is not numeric, or a null key; errors of
/// `each`. A group's own problems are in its [`PointGroup`].
pub fn read_point_groups(
    path: &Path,
    key: Option<&str>,
    mut each: impl FnMut(Vec<PointGroup>) -> IoResult<()>,
) -> IoResult<()> {
    let key = key.unwrap_or(DEFAULT_KEY);
    let rg = RowGroups::open(path)?;
    let source = rg.source.clone();
    let lay = layout(rg.schema(), key, &source)?;
    let dim = lay.coords.len();
    let mut seen = std::collections::HashSet::new();
    let mut open: Option<Open> = None;
    let mut row0 = 0usize; // rows before the current batch
    for g in 0..rg.count() {
        let mut done = Vec::new();
        for batch in rg.read(g)? {
            let keys = Keys::of(batch.column(lay.key).as_ref()).ok_or_else(|| {
                IoError::syntax(
                    Location::new(&source).at_field(key),
                    "unreadable key column",
                )
            })?;
            let numbers: Vec<Option<Numbers<'_>>> = lay
                .coords
                .iter()
                .map(|(c, _)| Numbers::of(batch.column(*c).as_ref()))
                .collect();
            for r in 0..batch.num_rows() {
                let row = row0 + r + 1;
                let k = keys.get(r).ok_or_else(|| {
                    IoError::syntax(
                        Location::new(&source).at_field(key),
                        format!("row {row}: the key is null; every row needs a key"),
                    )
                })?;
                if lay.lists {
                    let mut o = Open {
                        key: k,
                        data: Vec::new(),
                        error: None,
                    };
                    o.error = read_list_row(&batch, &lay, r, &mut o.data, &source, &o.key).err();
                    done.push(o.finish(dim));
                    continue;
                }
                if open.as_ref().is_none_or(|o| o.key != k) {
                    if let Some(o) = open.take() {
                        done.push(o.finish(dim));
                    }
                    let mut o = Open {
                        key: k.clone(),
                        data: Vec::new(),
                        error: None,
                    };
                    if !seen.insert(k) {
                        o.error = Some(IoError::syntax(
                            Location::new(format!("{source}: group {}", o.key)),
                            format!("appears again at row {row}; the rows of a group must be consecutive (sort the file by `{key}`)"),
                        ));
                    }
                    open = Some(o);
                }
                if let Some(o) = open.as_mut().filter(|o| o.error.is_none()) {
                    for ((_, name), n) in lay.coords.iter().zip(&numbers) {
                        let v = n.as_ref().and_then(|n| n.get(r));
                        match v {
                            Some(v) if v.is_finite() => o.data.push(v),
                            _ => {
                                o.error = Some(IoError::syntax(
                                    Location::new(format!("{source}: group {}", o.key))
                                        .at_field(name.clone()),
                                    format!(
                                        "row {row}: {}; every coordinate must be a finite number",
                                        v.map_or("null".to_string(), |v| v.to_string())
                                    ),
                                ));
                                break;
                            }
                        }
                    }
                }
            }
            row0 += batch.num_rows();
        }
        if g + 1 == rg.count() {
            if let Some(o) = open.take() {
                done.push(o.finish(dim));
            }
        }
        if !done.is_empty() {
            each(done)?;
        }
    }
    Ok(())
}

/// The points of row `r` in the lists layout, appended to `data`.
fn read_list_row(
    batch: &RecordBatch,
    lay: &Layout,
    r: usize,
    data: &mut Vec<f64>,
    source: &str,
    key: &GroupKey,
) -> IoResult<()> {
    let at = || Location::new(format!("{source}: group {key}"));
    let mut cols = Vec::with_capacity(lay.coords.len());
    let mut len = None;
    for (c, name) in &lay.coords {
        let col = batch.column(*c);
        let list: ArrayRef = if let Some(l) = col.as_list_opt::<i32>() {
            if l.is_null(r) {
                return Err(IoError::syntax(
                    at().at_field(name.clone()),
                    "the list is null",
                ));
            }
            l.value(r)
        } else if let Some(l) = col.as_list_opt::<i64>() {
            if l.is_null(r) {
                return Err(IoError::syntax(
                    at().at_field(name.clone()),
                    "the list is null",
                ));
            }
            l.value(r)
        } else {
            return Err(IoError::syntax(at().at_field(name.clone()), "not a list"));
        };
        match len {
            Some((n, ref first)) if n != list.len() => {
                return Err(IoError::syntax(
                    at().at_field(name.clone()),
                    format!(
                        "{} values, but `{first}` has {n}; every coordinate list of a group needs the same length",
                        list.len()
                    ),
                ))
            }
            None => len = Some((list.len(), name.clone())),
            Some(_) => {}
        }
        cols.push((list, name));
    }
    let n = len.map_or(0, |(n, _)| n);
    data.reserve(n * cols.len());
    let nums: Vec<(Numbers<'_>, &String)> = cols
        .iter()
        .map(|(l, name)| {
            Numbers::of(l.as_ref())
                .map(|x| (x, *name))
                .ok_or_else(|| IoError::syntax(at().at_field((*name).clone()), "not numbers"))
        })
        .collect::<IoResult<_>>()?;
    for i in 0..n {
        for (x, name) in &nums {
            match x.get(i) {
                Some(v) if v.is_finite() => data.push(v),
                v => {
                    return Err(IoError::syntax(
                        at().at_field((*name).clone()),
                        format!(
                            "value {i} is {}; every coordinate must be a finite number",
                            v.map_or("null".to_string(), |v| v.to_string())
                        ),
                    ))
                }
            }
        }
    }
    Ok(())
}

/// Builders of a key column of the input's type.
enum KeyBuilder {
    Int(Int64Builder),
    Str(StringBuilder),
}

impl KeyBuilder {
    fn new(int: bool) -> Self {
        if int {
            KeyBuilder::Int(Int64Builder::new())
        } else {
            KeyBuilder::Str(StringBuilder::new())
        }
    }

    fn append(&mut self, k: &GroupKey) {
        match (self, k) {
            (KeyBuilder::Int(b), GroupKey::Int(k)) => b.append_value(*k),
            (KeyBuilder::Str(b), GroupKey::Str(k)) => b.append_value(k),
            (KeyBuilder::Int(b), GroupKey::Str(_)) => b.append_null(),
            (KeyBuilder::Str(b), GroupKey::Int(k)) => b.append_value(k.to_string()),
        }
    }

    fn finish(&mut self) -> ArrayRef {
        match self {
            KeyBuilder::Int(b) => Arc::new(b.finish()),
            KeyBuilder::Str(b) => Arc::new(b.finish()),
        }
    }
}

/// A Parquet writer of batches: one row group per call of `write`.
pub struct ParquetBatchWriter<W: Write + Send> {
    writer: Option<ArrowWriter<W>>,
    out: Option<W>,
}

impl<W: Write + Send> ParquetBatchWriter<W> {
    /// A writer into `out` (uncompressed pages).
    pub fn new(out: W) -> Self {
        ParquetBatchWriter {
            writer: None,
            out: Some(out),
        }
    }

    fn push(&mut self, batch: &RecordBatch) -> std::io::Result<()> {
        let to_io = |e: parquet::errors::ParquetError| std::io::Error::other(e.to_string());
        if self.writer.is_none() {
            // no dictionaries: hashing every double costs more than it saves on samples and
            // control points; the key column (repeated on every sample) keeps its dictionary.
            // No compression: writing is then a copy of the doubles, which are mostly the
            // mantissa noise of curves and samples (a general codec finds little to remove)
            let key = batch.schema().field(0).name().clone();
            let props = WriterProperties::builder()
                .set_compression(Compression::UNCOMPRESSED)
                .set_dictionary_enabled(false)
                .set_column_dictionary_enabled(ColumnPath::from(key), true)
                .build();
            let out = self
                .out
                .take()
                .ok_or_else(|| std::io::Error::other("the Parquet writer was closed"))?;
            self.writer =
                Some(ArrowWriter::try_new(out, batch.schema(), Some(props)).map_err(to_io)?);
        }
        if let Some(w) = self.writer.as_mut() {
            w.write(batch).map_err(to_io)?;
            w.flush().map_err(to_io)?;
        }
        Ok(())
    }

    /// Writes curves (or the errors of the groups that gave none) as one row group; `key`
    /// names the key column.
    ///
    /// # Errors
    /// The writer's.
    pub fn write_curves(
        &mut self,
        key: &str,
        rows: &[(GroupKey, Result<Object, String>)],
    ) -> std::io::Result<()> {
        let int = rows
            .first()
            .is_some_and(|(k, _)| matches!(k, GroupKey::Int(_)));
        let mut keys = KeyBuilder::new(int);
        let mut kind = StringBuilder::new();
        let mut degree = Int32Builder::new();
        let mut dim = Int32Builder::new();
        let mut knots = ListBuilder::new(Float64Builder::new());
        let mut control = ListBuilder::new(ListBuilder::new(Float64Builder::new()));
        let mut weights = ListBuilder::new(Float64Builder::new());
        let mut error = StringBuilder::new();
        let small = |n: usize| i32::try_from(n).unwrap_or(i32::MAX);
        for (k, r) in rows {
            keys.append(k);
            match r {
                Ok(obj) => {
                    kind.append_value(obj.type_name());
                    let (d, kn, w) = match obj {
                        Object::Bezier(c) => (c.degree(), None, None),
                        Object::BSpline(c) => (c.degree(), Some(c.knots().as_slice()), None),
                        Object::Nurbs(c) => {
                            (c.degree(), Some(c.knots().as_slice()), Some(c.weights()))
                        }
                    };
                    degree.append_value(small(d));
                    dim.append_value(small(obj.dim()));
                    match kn {
                        Some(kn) => {
                            knots.values().append_slice(kn);
                            knots.append(true);
                        }
                        None => knots.append(true),
                    }
                    let cp = obj.control_points();
                    for p in cp.iter() {
                        control.values().values().append_slice(p);
                        control.values().append(true);
                    }
                    control.append(true);
                    match w {
                        Some(w) => {
                            weights.values().append_slice(&w);
                            weights.append(true);
                        }
                        None => weights.append(true),
                    }
                    error.append_null();
                }
                Err(e) => {
                    kind.append_null();
                    degree.append_null();
                    dim.append_null();
                    // empty lists, never nulls, in the list columns: parquet 57's writer
                    // computes negative levels for a list column that is null in every row of
                    // a row group after one where it was not (and panics)
                    knots.append(true);
                    control.append(true);
                    weights.append(true);
                    error.append_value(e);
                }
            }
        }
        let batch = RecordBatch::try_from_iter([
            (key, keys.finish()),
            ("type", Arc::new(kind.finish()) as ArrayRef),
            ("degree", Arc::new(degree.finish())),
            ("dim", Arc::new(dim.finish())),
            ("knots", Arc::new(knots.finish())),
            ("control", Arc::new(control.finish())),
            ("weights", Arc::new(weights.finish())),
            ("error", Arc::new(error.finish())),
        ])
        .map_err(|e| std::io::Error::other(e.to_string()))?;
        self.push(&batch)
    }

    /// Writes point sets in the long layout as one row group: the key `key` on each point's
    /// row, then one double column per coordinate, named `names` (the layout
    /// [`read_point_groups`] reads).
    ///
    /// # Errors
    /// The writer's; a point set whose dimension is not `names.len()`.
    pub fn write_points(
        &mut self,
        key: &str,
        names: &[&str],
        groups: &[(GroupKey, lekalo::Points)],
    ) -> std::io::Result<()> {
        let int = groups
            .first()
            .is_none_or(|(k, _)| matches!(k, GroupKey::Int(_)));
        let mut keys = KeyBuilder::new(int);
        let mut cols: Vec<Float64Builder> = names.iter().map(|_| Float64Builder::new()).collect();
        for (k, pts) in groups {
            if pts.dim() != names.len() {
                return Err(std::io::Error::other(format!(
                    "group {k} has points of dimension {}, the columns are {}",
                    pts.dim(),
                    names.join(",")
                )));
            }
            for p in pts.iter() {
                keys.append(k);
                for (c, v) in cols.iter_mut().zip(p) {
                    c.append_value(*v);
                }
            }
        }
        let mut columns: Vec<(&str, ArrayRef)> = vec![(key, keys.finish())];
        for (n, c) in names.iter().zip(cols.iter_mut()) {
            columns.push((n, Arc::new(c.finish())));
        }
        let batch = RecordBatch::try_from_iter(columns)
            .map_err(|e| std::io::Error::other(e.to_string()))?;
        self.push(&batch)
    }

    /// Writes points sampled from curves as one row group: per group, its key on each of its
    /// rows, `t`, and the coordinates `x, y, z` (`x1 … xd` above 3-D) of `points` (point-major,
    /// `dim` values a parameter), the columns of [`ParquetBatchWriter::write_samples`] without
    /// derivatives.
    ///
    /// # Errors
    /// The writer's.
    pub fn write_point_samples(
        &mut self,
        key: &str,
        dim: usize,
        rows: &[(GroupKey, Vec<f64>, Vec<f64>)],
    ) -> std::io::Result<()> {
        let int = rows
            .first()
            .is_none_or(|(k, _, _)| matches!(k, GroupKey::Int(_)));
        let n: usize = rows.iter().map(|(_, ts, _)| ts.len()).sum();
        let mut keys = KeyBuilder::new(int);
        let mut t = Vec::with_capacity(n);
        let mut cols: Vec<Vec<f64>> = (0..dim).map(|_| Vec::with_capacity(n)).collect();
        for (k, ts, pts) in rows {
            for _ in 0..ts.len() {
                keys.append(k);
            }
            t.extend_from_slice(ts);
            for (c, col) in cols.iter_mut().enumerate() {
                col.extend(pts.iter().skip(c).step_by(dim.max(1)));
            }
        }
        let names = crate::samples::coord_names(dim);
        let mut columns: Vec<(&str, ArrayRef)> = vec![
            (key, keys.finish()),
            ("t", Arc::new(arrow_array::Float64Array::from(t))),
        ];
        for (name, col) in names.iter().zip(cols) {
            columns.push((
                name.as_str(),
                Arc::new(arrow_array::Float64Array::from(col)),
            ));
        }
        let batch = RecordBatch::try_from_iter(columns)
            .map_err(|e| std::io::Error::other(e.to_string()))?;
        self.push(&batch)
    }

    /// Writes sample tables ([`crate::sample_table`]) as one row group: per group, its key on
    /// each of its rows, then the table's columns (`t`, the point, derivatives, curvature; null
    /// where undefined). Every table has the columns of the first.
    ///
    /// # Errors
    /// The writer's; a table with other columns than the first.
    pub fn write_samples(
        &mut self,
        key: &str,
        rows: &[(GroupKey, crate::SampleTable)],
    ) -> std::io::Result<()> {
        let Some((first_key, first)) = rows.first() else {
            return Ok(());
        };
        let mut keys = KeyBuilder::new(matches!(first_key, GroupKey::Int(_)));
        let mut cols: Vec<Float64Builder> =
            first.header.iter().map(|_| Float64Builder::new()).collect();
        for (k, table) in rows {
            if table.header != first.header {
                return Err(std::io::Error::other(format!(
                    "group {k} has the columns {}, group {first_key} has {}; a samples file holds curves of one dimension",
                    table.header.join(","),
                    first.header.join(",")
                )));
            }
            for row in &table.rows {
                keys.append(k);
                for (c, v) in cols.iter_mut().zip(row) {
                    c.append_option(*v);
                }
            }
        }
        let mut columns: Vec<(&str, ArrayRef)> = vec![(key, keys.finish())];
        for (n, c) in first.header.iter().zip(cols.iter_mut()) {
            columns.push((n.as_str(), Arc::new(c.finish())));
        }
        let batch = RecordBatch::try_from_iter(columns)
            .map_err(|e| std::io::Error::other(e.to_string()))?;
        self.push(&batch)
    }

    /// Writes the footer (an empty file of the layout if nothing was written: `empty` gives
    /// its one batch).
    ///
    /// # Errors
    /// The writer's.
    pub fn close(
        mut self,
        empty: impl FnOnce(&mut Self) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        if self.writer.is_none() {
            empty(&mut self)?;
        }
        match self.writer.take() {
            Some(w) => w
                .close()
                .map(|_| ())
                .map_err(|e| std::io::Error::other(e.to_string())),
            None => Ok(()),
        }
    }
}

/// Reads the curves of a Parquet file written by [`ParquetBatchWriter::write_curves`] one row
/// group at a time; `each` gets `(key, curve)` pairs, a row with an `error` or an invalid curve
/// as an error naming its key.
///
/// # Errors
/// As [`read_point_groups`], and for a file without the curve columns.
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
                format!("no column `{name}`; a curves file has the columns {key}, type, degree, knots, control and weights (docs/formats.md)"),
            )
        })
    };
    let (ck, ct, cd, ckn, cc, cw) = (
        col(key)?,
        col("type")?,
        col("degree")?,
        col("knots")?,
        col("control")?,
        col("weights")?,
    );
    let ce = schema.index_of("error").ok();
    for g in 0..rg.count() {
        let mut out = Vec::new();
        for batch in rg.read(g)? {
            let bad = |what: &str| {
                IoError::syntax(
                    Location::new(&source).at_field(what),
                    "the column does not have the type of docs/formats.md#parquet-batches",
                )
            };
            let keys = Keys::of(batch.column(ck).as_ref()).ok_or_else(|| bad(key))?;
            let kinds = batch
                .column(ct)
                .as_string_opt::<i32>()
                .ok_or_else(|| bad("type"))?;
            let degrees = Keys::of(batch.column(cd).as_ref())
                .filter(|k| matches!(k, Keys::I32(_) | Keys::I64(_)))
                .ok_or_else(|| bad("degree"))?;
            let knots = batch
                .column(ckn)
                .as_list_opt::<i32>()
                .ok_or_else(|| bad("knots"))?;
            let control = batch
                .column(cc)
                .as_list_opt::<i32>()
                .ok_or_else(|| bad("control"))?;
            let weights = batch
                .column(cw)
                .as_list_opt::<i32>()
                .ok_or_else(|| bad("weights"))?;
            let errors = ce.and_then(|c| batch.column(c).as_string_opt::<i32>());
            for r in 0..batch.num_rows() {
                let k = keys.get(r).ok_or_else(|| {
                    IoError::syntax(Location::new(&source).at_field(key), "a null key")
                })?;
                let at = Location::new(format!("{source}: group {k}"));
                if let Some(e) = errors.filter(|e| e.is_valid(r)) {
                    out.push((
                        k,
                        Err(IoError::syntax(at, format!("no curve: {}", e.value(r)))),
                    ));
                    continue;
                }
                let obj = curve_row(r, kinds, &degrees, knots, control, weights, &at);
                out.push((k, obj));
            }
        }
        if !out.is_empty() {
            each(out)?;
        }
    }
    Ok(())
}

fn floats(a: &dyn Array, at: &Location, what: &str) -> IoResult<Vec<f64>> {
    let n = Numbers::of(a)
        .ok_or_else(|| IoError::syntax(at.clone().at_field(what), "not a list of numbers"))?;
    (0..a.len())
        .map(|i| {
            n.get(i).ok_or_else(|| {
                IoError::syntax(at.clone().at_field(what), format!("value {i} is null"))
            })
        })
        .collect()
}

/// The control points of row `r` of `control` (a list of lists of numbers): their dimension
/// and their coordinates. The inner lists of one row lie end to end in the inner values, so the
/// coordinates are one slice of them, copied at once (no array or vector per point).
fn control_row(
    control: &arrow_array::ListArray,
    r: usize,
    at: &Location,
) -> IoResult<(usize, Vec<f64>)> {
    let bad = |m: String| IoError::syntax(at.clone().at_field("control"), m);
    let inner = control
        .values()
        .as_list_opt::<i32>()
        .ok_or_else(|| bad("not a list of lists of numbers".into()))?;
    let index = |o: i32| usize::try_from(o).unwrap_or(0);
    let outer = control.value_offsets();
    let (p0, p1) = (index(outer[r]), index(outer[r + 1]));
    let offsets = inner.value_offsets();
    let mut dim = None;
    for i in p0..p1 {
        if inner.is_null(i) {
            return Err(bad(format!("point {} is null", i - p0)));
        }
        let len = index(offsets[i + 1]) - index(offsets[i]);
        if let Some(d) = dim.filter(|&d| d != len) {
            return Err(bad(format!(
                "point {} has {len} coordinates, point 0 has {d}",
                i - p0
            )));
        }
        dim = Some(len);
    }
    let (a, b) = (index(offsets[p0]), index(offsets[p1]));
    let values = inner.values();
    let n =
        Numbers::of(values.as_ref()).ok_or_else(|| bad("not a list of lists of numbers".into()))?;
    let d = dim.unwrap_or(0);
    let ctrl = match &n {
        Numbers::F64(x) if x.null_count() == 0 => x.values()[a..b].to_vec(),
        _ => (a..b)
            .map(|j| {
                n.get(j).ok_or_else(|| {
                    let k = j - a;
                    bad(format!(
                        "point {} value {} is null",
                        k / d.max(1),
                        k % d.max(1)
                    ))
                })
            })
            .collect::<IoResult<_>>()?,
    };
    Ok((d, ctrl))
}

fn curve_row(
    r: usize,
    kinds: &arrow_array::StringArray,
    degrees: &Keys<'_>,
    knots: &arrow_array::ListArray,
    control: &arrow_array::ListArray,
    weights: &arrow_array::ListArray,
    at: &Location,
) -> IoResult<Object> {
    let kind = if kinds.is_valid(r) {
        kinds.value(r)
    } else {
        ""
    };
    let (dim, ctrl) = control_row(control, r, at)?;
    let invalid = |field: &str, error| IoError::Invalid {
        at: at.clone().at_field(field),
        error,
    };
    let ctrl = lekalo::Points::from_flat(dim, ctrl).map_err(|e| invalid("control", e))?;
    let degree = || {
        match degrees.get(r) {
            Some(GroupKey::Int(d)) => usize::try_from(d).ok(),
            _ => None,
        }
        .ok_or_else(|| IoError::syntax(at.clone().at_field("degree"), "not a degree"))
    };
    let list = |l: &arrow_array::ListArray, what: &str| {
        if l.is_null(r) {
            Err(IoError::syntax(at.clone().at_field(what), "null"))
        } else {
            floats(l.value(r).as_ref(), at, what)
        }
    };
    match kind {
        "bezier_curve" => lekalo::BezierCurve::new(ctrl)
            .map(Object::Bezier)
            .map_err(|e| invalid("control", e)),
        "bspline_curve" => lekalo::BSplineCurve::new(degree()?, list(knots, "knots")?, ctrl)
            .map(Object::BSpline)
            .map_err(|e| invalid("knots", e)),
        "nurbs_curve" => lekalo::NurbsCurve::new(
            degree()?,
            list(knots, "knots")?,
            ctrl,
            list(weights, "weights")?,
        )
        .map(Object::Nurbs)
        .map_err(|e| invalid("weights", e)),
        other => Err(IoError::syntax(
            at.clone().at_field("type"),
            format!("\"{other}\" is not a curve type; expected bezier_curve, bspline_curve or nurbs_curve"),
        )),
    }
}

#[cfg(test)]
#[path = "parquet_tests.rs"]
mod tests;
