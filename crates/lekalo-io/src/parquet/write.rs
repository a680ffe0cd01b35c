//! The writer of curves, point sets and samples: one row group per call, or row groups of a
//! given size (see [`ParquetBatchWriter::with_row_group_bytes`]).
//!
//! Every column is built from flat vectors filled a slice at a time (no builder call per
//! number), against a schema stated here rather than guessed from the batch, so that every row
//! group of a file has the same schema. Pages are uncompressed and without dictionaries, and
//! only the key column has statistics: see [`properties`].

use std::io::Write;
use std::sync::Arc;

use arrow_array::builder::{Float64Builder, StringBuilder};
use arrow_array::{
    ArrayRef, Float64Array, Int32Array, Int64Array, ListArray, RecordBatch, StringArray,
};
use arrow_buffer::OffsetBuffer;
use arrow_schema::{DataType, Field, Schema};
use parquet::arrow::{add_encoded_arrow_schema_to_metadata, ArrowSchemaConverter, ArrowWriter};
use parquet::basic::{Compression, Encoding};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::properties::{EnabledStatistics, WriterProperties};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::ColumnPath;

use super::GroupKey;
use crate::object::Object;

fn other(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

/// The writer's settings for a file whose key column is `schema`'s first field.
///
/// - No compression: writing is then a copy of the doubles, which are mostly the mantissa
///   noise of curves and samples (a general codec finds little to remove).
/// - No dictionaries: hashing every double costs more than it saves. An integer key (repeated
///   on every sample of a curve) is delta-encoded instead, which stores a run of equal keys in
///   a few bits without hashing them; a string key keeps its dictionary.
/// - Statistics (min/max per page) on the key only, so that a reader can skip to a group;
///   on the doubles they would cost a comparison per number and serve no query.
fn properties(schema: &Schema) -> WriterProperties {
    let key = schema.field(0);
    let path = ColumnPath::from(key.name().as_str());
    let b = WriterProperties::builder()
        .set_compression(Compression::UNCOMPRESSED)
        .set_dictionary_enabled(false)
        .set_statistics_enabled(EnabledStatistics::None)
        .set_column_statistics_enabled(path.clone(), EnabledStatistics::Page);
    match key.data_type() {
        DataType::Int64 => b.set_column_encoding(path, Encoding::DELTA_BINARY_PACKED),
        _ => b.set_column_dictionary_enabled(path, true),
    }
    .build()
}

/// The key column of a batch: each key repeated `n` times, integers if `int` (a string key is
/// then an error), strings otherwise (an integer key written as its decimal text).
fn key_column<'k>(
    int: bool,
    keys: impl Iterator<Item = (&'k GroupKey, usize)>,
) -> std::io::Result<ArrayRef> {
    if int {
        let mut out = Vec::new();
        for (k, n) in keys {
            match k {
                GroupKey::Int(i) => out.extend(std::iter::repeat_n(*i, n)),
                GroupKey::Str(s) => {
                    return Err(other(format!(
                        "group {s:?}: a string key among integer keys"
                    )))
                }
            }
        }
        Ok(Arc::new(Int64Array::from(out)))
    } else {
        let mut b = StringBuilder::new();
        for (k, n) in keys {
            let text = match k {
                GroupKey::Int(i) => i.to_string(),
                GroupKey::Str(s) => s.clone(),
            };
            for _ in 0..n {
                b.append_value(&text);
            }
        }
        Ok(Arc::new(b.finish()))
    }
}

fn key_field(name: &str, int: bool) -> Field {
    Field::new(
        name,
        if int { DataType::Int64 } else { DataType::Utf8 },
        false,
    )
}

/// The item field of the list columns of curves: a double that is never null.
fn float_item() -> Arc<Field> {
    Arc::new(Field::new_list_field(DataType::Float64, false))
}

/// The type of the list columns of curves: a list that is never null of doubles that are
/// never null.
fn float_list() -> DataType {
    DataType::List(float_item())
}

/// The type of `control`: a list of points, each a list of doubles (none of them null).
fn point_list() -> DataType {
    DataType::List(Arc::new(Field::new_list_field(float_list(), false)))
}

/// An `i32` offset of a list column, or an error if a row group holds too many values.
fn offset(n: usize) -> std::io::Result<i32> {
    i32::try_from(n).map_err(|_| {
        other(format!(
            "{n} values in one row group; a Parquet list column holds at most 2^31 - 1"
        ))
    })
}

/// A list column being filled one row (one slice) at a time: the values end to end and the
/// offsets of the rows, turned into an Arrow array without a copy.
struct FloatLists {
    values: Vec<f64>,
    offsets: Vec<i32>,
}

impl FloatLists {
    fn with_capacity(rows: usize, values: usize) -> Self {
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        FloatLists {
            values: Vec::with_capacity(values),
            offsets,
        }
    }

    fn push(&mut self, row: &[f64]) -> std::io::Result<()> {
        self.values.extend_from_slice(row);
        self.offsets.push(offset(self.values.len())?);
        Ok(())
    }

    fn array(values: Vec<f64>, offsets: Vec<i32>) -> std::io::Result<ListArray> {
        ListArray::try_new(
            float_item(),
            OffsetBuffer::new(offsets.into()),
            Arc::new(Float64Array::from(values)),
            None,
        )
        .map_err(other)
    }

    fn finish(self) -> std::io::Result<ArrayRef> {
        Ok(Arc::new(Self::array(self.values, self.offsets)?))
    }
}

/// The `control` column being filled: per row a list of points, each a list of `dim`
/// doubles; the coordinates end to end (as the curves hold them), with the offsets of the
/// points and of the rows.
struct PointLists {
    points: FloatLists,
    rows: Vec<i32>,
}

impl PointLists {
    fn with_capacity(rows: usize, points: usize, values: usize) -> Self {
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        PointLists {
            points: FloatLists::with_capacity(points, values),
            rows: offsets,
        }
    }

    /// Appends a row of point-major coordinates, `dim` a point (`coords` holds whole points).
    fn push(&mut self, coords: &[f64], dim: usize) -> std::io::Result<()> {
        let d = offset(dim.max(1))?;
        let mut o = offset(self.points.values.len())?;
        offset(self.points.values.len() + coords.len())?;
        self.points.values.extend_from_slice(coords);
        let n = coords.len() / dim.max(1);
        self.points
            .offsets
            .extend(std::iter::repeat_n((), n).map(|()| {
                o += d;
                o
            }));
        self.rows.push(offset(self.points.offsets.len() - 1)?);
        Ok(())
    }

    fn finish(self) -> std::io::Result<ArrayRef> {
        let points = FloatLists::array(self.points.values, self.points.offsets)?;
        let list = ListArray::try_new(
            Arc::new(Field::new_list_field(float_list(), false)),
            OffsetBuffer::new(self.rows.into()),
            Arc::new(points),
            None,
        )
        .map_err(other)?;
        Ok(Arc::new(list))
    }
}

/// The parts of a curve that its row holds.
struct CurveRow<'a> {
    degree: usize,
    dim: usize,
    knots: &'a [f64],
    control: std::borrow::Cow<'a, [f64]>,
    weights: Option<Vec<f64>>,
}

impl<'a> CurveRow<'a> {
    fn of(obj: &'a Object) -> Self {
        CurveRow {
            degree: obj.degree(),
            dim: obj.dim(),
            knots: obj
                .explicit_knots()
                .map_or(&[], lekalo::KnotVector::as_slice),
            control: match obj.control_points() {
                std::borrow::Cow::Borrowed(p) => p.as_slice().into(),
                std::borrow::Cow::Owned(p) => p.into_vec().into(),
            },
            weights: obj.weights(),
        }
    }
}

/// A Parquet writer of batches: one row group per call of a `write_` method, or, with
/// [`ParquetBatchWriter::with_row_group_bytes`], row groups of about a given size.
pub struct ParquetBatchWriter<W: Write + Send> {
    writer: Option<Inner<W>>,
    out: Option<W>,
    /// In [`ParquetBatchWriter::close`]: a batch without rows is then written, for the layout.
    closing: bool,
    /// The encoded size at which a row group is written; `None`: at every call.
    row_group_bytes: Option<usize>,
}

impl<W: Write + Send> ParquetBatchWriter<W> {
    /// A writer into `out` (uncompressed pages, see the module's documentation).
    pub fn new(out: W) -> Self {
        ParquetBatchWriter {
            writer: None,
            out: Some(out),
            closing: false,
            row_group_bytes: None,
        }
    }

    /// The same writer, but the calls add their rows to a row group that is written when its
    /// encoded pages reach `bytes` (and at [`ParquetBatchWriter::close`]): the file's row
    /// groups are then of that size whatever the size of the calls, and memory is bounded by
    /// it (the row groups of docs/formats.md#parquet-batches).
    #[must_use]
    pub fn with_row_group_bytes(mut self, bytes: usize) -> Self {
        self.row_group_bytes = Some(bytes);
        self
    }

    /// Writes `columns` under `fields` as one row group, or adds them to the open one (the
    /// first call sets the file's schema and settings).
    fn push(&mut self, fields: Vec<Field>, columns: Vec<ArrayRef>) -> std::io::Result<()> {
        let schema = Arc::new(Schema::new(fields));
        let batch = RecordBatch::try_new(schema.clone(), columns).map_err(other)?;
        if batch.num_rows() == 0 && !self.closing {
            // nothing to write, and the schema (the key's type) is left to the first rows
            return Ok(());
        }
        if self.writer.is_none() {
            let out = self.take_out()?;
            let props = properties(&schema);
            let w = ArrowWriter::try_new(out, schema, Some(props)).map_err(other)?;
            self.writer = Some(Inner::Arrow(w));
        }
        if let Some(w) = self.writer.as_mut() {
            let Inner::Arrow(w) = w else {
                return Err(other(MIXED));
            };
            w.write(&batch).map_err(other)?;
            if self
                .row_group_bytes
                .is_none_or(|b| w.in_progress_size() >= b)
            {
                w.flush().map_err(other)?;
            }
        }
        Ok(())
    }

    /// Writes curves (or the errors of the groups that gave none) as one row group; `key`
    /// names the key column. The control points are a list of points per curve, each a list
    /// of `dim` doubles, as docs/formats.md#parquet-batches says.
    ///
    /// # Errors
    /// The writer's; a string key among integer keys.
    pub fn write_curves(
        &mut self,
        key: &str,
        rows: &[(GroupKey, Result<Object, String>)],
    ) -> std::io::Result<()> {
        let int = rows
            .first()
            .is_some_and(|(k, _)| matches!(k, GroupKey::Int(_)));
        let n = rows.len();
        let parts: Vec<Option<CurveRow<'_>>> = rows
            .iter()
            .map(|(_, r)| r.as_ref().ok().map(CurveRow::of))
            .collect();
        let sum = |f: fn(&CurveRow<'_>) -> usize| parts.iter().flatten().map(f).sum::<usize>();
        let mut kind: Vec<Option<&str>> = Vec::with_capacity(n);
        let mut degree: Vec<Option<i32>> = Vec::with_capacity(n);
        let mut dim: Vec<Option<i32>> = Vec::with_capacity(n);
        let mut error: Vec<Option<&str>> = Vec::with_capacity(n);
        let mut knots = FloatLists::with_capacity(n, sum(|c| c.knots.len()));
        let mut control = PointLists::with_capacity(
            n,
            sum(|c| c.control.len() / c.dim.max(1)),
            sum(|c| c.control.len()),
        );
        let mut weights =
            FloatLists::with_capacity(n, sum(|c| c.weights.as_ref().map_or(0, Vec::len)));
        let small = |what: &str, v: usize| {
            i32::try_from(v).map_err(|_| other(format!("{what} {v} does not fit a Parquet int32")))
        };
        for ((_, r), c) in rows.iter().zip(&parts) {
            match (r, c) {
                (Ok(obj), Some(c)) => {
                    kind.push(Some(obj.type_name()));
                    degree.push(Some(small("degree", c.degree)?));
                    dim.push(Some(small("dimension", c.dim)?));
                    knots.push(c.knots)?;
                    control.push(&c.control, c.dim)?;
                    weights.push(c.weights.as_deref().unwrap_or(&[]))?;
                    error.push(None);
                }
                (r, _) => {
                    kind.push(None);
                    degree.push(None);
                    dim.push(None);
                    knots.push(&[])?;
                    control.push(&[], 1)?;
                    weights.push(&[])?;
                    error.push(r.as_ref().err().map(String::as_str));
                }
            }
        }
        let fields = vec![
            key_field(key, int),
            Field::new("type", DataType::Utf8, true),
            Field::new("degree", DataType::Int32, true),
            Field::new("dim", DataType::Int32, true),
            Field::new("knots", float_list(), false),
            Field::new("control", point_list(), false),
            Field::new("weights", float_list(), false),
            Field::new("error", DataType::Utf8, true),
        ];
        let columns: Vec<ArrayRef> = vec![
            key_column(int, rows.iter().map(|(k, _)| (k, 1)))?,
            Arc::new(StringArray::from(kind)),
            Arc::new(Int32Array::from(degree)),
            Arc::new(Int32Array::from(dim)),
            knots.finish()?,
            control.finish()?,
            weights.finish()?,
            Arc::new(StringArray::from(error)),
        ];
        self.push(fields, columns)
    }

    /// Writes point sets in the long layout as one row group: the key `key` on each point's
    /// row, then one double column per coordinate, named `names` (the layout
    /// [`super::read_point_groups`] reads).
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
        if let Some((k, pts)) = groups.iter().find(|(_, p)| p.dim() != names.len()) {
            return Err(other(format!(
                "group {k} has points of dimension {}, the columns are {}",
                pts.dim(),
                names.join(",")
            )));
        }
        let n: usize = groups.iter().map(|(_, p)| p.len()).sum();
        let mut cols: Vec<Vec<f64>> = names.iter().map(|_| Vec::with_capacity(n)).collect();
        for (_, pts) in groups {
            split_columns(pts.as_slice(), &mut cols);
        }
        let mut fields = vec![key_field(key, int)];
        let mut columns = vec![key_column(int, groups.iter().map(|(k, p)| (k, p.len())))?];
        for (name, col) in names.iter().zip(cols) {
            fields.push(Field::new(*name, DataType::Float64, false));
            columns.push(Arc::new(Float64Array::from(col)));
        }
        self.push(fields, columns)
    }

    /// Writes points sampled from curves as one row group: per group, its key on each of its
    /// rows, `t`, and the coordinates `x, y, z` (`x1 … xd` above 3-D) of `points` (point-major,
    /// `dim` values a parameter), the columns of [`ParquetBatchWriter::write_samples`] without
    /// derivatives.
    ///
    /// # Errors
    /// The writer's; a string key among integer keys.
    pub fn write_point_samples(
        &mut self,
        key: &str,
        dim: usize,
        rows: &[(GroupKey, Vec<f64>, Vec<f64>)],
    ) -> std::io::Result<()> {
        let int = rows
            .first()
            .is_none_or(|(k, _, _)| matches!(k, GroupKey::Int(_)));
        if rows.iter().all(|(_, ts, _)| ts.is_empty()) && !self.closing {
            // nothing to write, and the schema (the key's type) is left to the first rows
            return Ok(());
        }
        if self.writer.is_none() {
            let out = self.take_out()?;
            let w = PointSamples::new(out, key, dim, int, self.row_group_bytes)?;
            self.writer = Some(Inner::Points(w));
        }
        let Some(Inner::Points(w)) = self.writer.as_mut() else {
            return Err(other(MIXED));
        };
        let n: usize = rows.iter().map(|(_, ts, _)| ts.len()).sum();
        if w.rows() > 0 && w.rows() + n > w.limit {
            // a row group stays within its size (and the vectors within their capacity)
            w.write_row_group()?;
        }
        w.append(key, dim, rows)?;
        if w.rows() >= w.limit {
            w.write_row_group()?;
        }
        Ok(())
    }

    /// The output, for the first write; an error once the writer is closed.
    fn take_out(&mut self) -> std::io::Result<W> {
        self.out
            .take()
            .ok_or_else(|| other("the Parquet writer was closed"))
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
        let int = matches!(first_key, GroupKey::Int(_));
        let n: usize = rows.iter().map(|(_, t)| t.rows.len()).sum();
        let mut cols: Vec<Float64Builder> = first
            .header
            .iter()
            .map(|_| Float64Builder::with_capacity(n))
            .collect();
        for (k, table) in rows {
            if table.header != first.header {
                return Err(other(format!(
                    "group {k} has the columns {}, group {first_key} has {}; a samples file holds curves of one dimension",
                    table.header.join(","),
                    first.header.join(",")
                )));
            }
            for row in &table.rows {
                for (c, v) in cols.iter_mut().zip(row) {
                    c.append_option(*v);
                }
            }
        }
        let mut fields = vec![key_field(key, int)];
        let mut columns = vec![key_column(
            int,
            rows.iter().map(|(k, t)| (k, t.rows.len())),
        )?];
        for (name, mut c) in first.header.iter().zip(cols) {
            fields.push(Field::new(name, DataType::Float64, true));
            columns.push(Arc::new(c.finish()));
        }
        self.push(fields, columns)
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
            self.closing = true;
            empty(&mut self)?;
        }
        match self.writer.take() {
            Some(Inner::Arrow(w)) => w.close().map(|_| ()).map_err(other),
            Some(Inner::Points(w)) => w.close(),
            None => Ok(()),
        }
    }
}

/// Appends the coordinates of point-major `points` to one vector per coordinate.
fn split_columns(points: &[f64], cols: &mut [Vec<f64>]) {
    match cols {
        [x, y, z] => {
            for p in points.chunks_exact(3) {
                x.push(p[0]);
                y.push(p[1]);
                z.push(p[2]);
            }
        }
        _ => {
            for p in points.chunks_exact(cols.len().max(1)) {
                for (c, v) in cols.iter_mut().zip(p) {
                    c.push(*v);
                }
            }
        }
    }
}

/// The message of a write whose layout is not the file's.
const MIXED: &str = "point samples and other layouts in one Parquet file";

/// The writer of a file: Arrow's for curves, point sets and sample tables, or Parquet's column
/// writers for point samples ([`PointSamples`]).
enum Inner<W: Write + Send> {
    Arrow(ArrowWriter<W>),
    Points(PointSamples<W>),
}

/// The key column of the row group being gathered, as runs (a key and its rows): an integer
/// key repeated on every row would take as much memory as a column of doubles.
enum KeyValues {
    Int(Vec<(i64, usize)>),
    Str(Vec<(ByteArray, usize)>),
}

/// The rows of the key column given to the column writer at once.
const KEY_CHUNK: usize = 1 << 13;

/// Writes a key column given as runs, `KEY_CHUNK` rows at a time from one vector.
fn write_runs<T: parquet::data_type::DataType>(
    col: &mut parquet::column::writer::ColumnWriterImpl<'_, T>,
    runs: &[(T::T, usize)],
) -> parquet::errors::Result<()> {
    let mut chunk: Vec<T::T> = Vec::with_capacity(KEY_CHUNK);
    for (key, n) in runs {
        let mut left = *n;
        while left > 0 {
            let take = left.min(KEY_CHUNK - chunk.len());
            chunk.extend(std::iter::repeat_n(key.clone(), take));
            left -= take;
            if chunk.len() == KEY_CHUNK {
                col.write_batch(&chunk, None, None)?;
                chunk.clear();
            }
        }
    }
    if !chunk.is_empty() {
        col.write_batch(&chunk, None, None)?;
    }
    Ok(())
}

/// The writer of point samples (`t` and the coordinates, never null): the rows of the open row
/// group gathered into one vector per column, reused from row group to row group, and written
/// by Parquet's column writers, whose pages go straight to the output. No column is nullable
/// or nested, so there are no levels to compute, and no copy of the row group is held in
/// pages (Arrow's writer keeps the encoded pages of the open row group in memory).
struct PointSamples<W: Write + Send> {
    file: SerializedFileWriter<W>,
    /// The key column's name, and whether it is an integer one.
    key: (String, bool),
    keys: KeyValues,
    t: Vec<f64>,
    /// One vector per coordinate.
    coords: Vec<Vec<f64>>,
    /// The rows of a row group: those of the size asked for (at most the writer's most rows),
    /// 0 for a row group per call.
    limit: usize,
}

impl<W: Write + Send> PointSamples<W> {
    /// The schema and settings of [`ParquetBatchWriter::write_point_samples`] (and the Arrow
    /// schema in the file's metadata, as Arrow's writer stores it).
    fn new(
        out: W,
        key: &str,
        dim: usize,
        int: bool,
        row_group_bytes: Option<usize>,
    ) -> std::io::Result<Self> {
        let mut fields = vec![
            key_field(key, int),
            Field::new("t", DataType::Float64, false),
        ];
        for name in crate::samples::coord_names(dim) {
            fields.push(Field::new(name, DataType::Float64, false));
        }
        let schema = Schema::new(fields);
        let parquet_schema = ArrowSchemaConverter::new()
            .convert(&schema)
            .map_err(other)?;
        let mut props = properties(&schema);
        add_encoded_arrow_schema_to_metadata(&schema, &mut props);
        // the size of a row as written (an integer key takes a few bits)
        let row = 8 * (dim + 1) + if int { 0 } else { 8 };
        let most = props.max_row_group_row_count().unwrap_or(usize::MAX);
        let limit = row_group_bytes.map_or(0, |b| (b / row).clamp(1, most));
        let file =
            SerializedFileWriter::new(out, parquet_schema.root_schema_ptr(), Arc::new(props))
                .map_err(other)?;
        Ok(PointSamples {
            file,
            key: (key.to_string(), int),
            keys: if int {
                KeyValues::Int(Vec::new())
            } else {
                KeyValues::Str(Vec::new())
            },
            t: Vec::with_capacity(limit),
            coords: (0..dim).map(|_| Vec::with_capacity(limit)).collect(),
            limit,
        })
    }

    /// The rows gathered.
    fn rows(&self) -> usize {
        self.t.len()
    }

    /// Adds the rows of `rows` (as [`ParquetBatchWriter::write_point_samples`]).
    fn append(
        &mut self,
        key: &str,
        dim: usize,
        rows: &[(GroupKey, Vec<f64>, Vec<f64>)],
    ) -> std::io::Result<()> {
        if key != self.key.0 || dim != self.coords.len() {
            return Err(other(format!(
                "samples of {dim}-D curves keyed by `{key}` after samples of {}-D curves keyed by `{}`; a samples file holds one layout",
                self.coords.len(),
                self.key.0
            )));
        }
        let n: usize = rows.iter().map(|(_, ts, _)| ts.len()).sum();
        self.t.reserve(n);
        for c in &mut self.coords {
            c.reserve(n);
        }
        for (k, ts, pts) in rows {
            if pts.len() != ts.len() * dim {
                return Err(other(format!(
                    "group {k}: {} coordinates for {} parameters of a {dim}-D curve",
                    pts.len(),
                    ts.len()
                )));
            }
            match (&mut self.keys, k) {
                (KeyValues::Int(v), GroupKey::Int(i)) => v.push((*i, ts.len())),
                (KeyValues::Int(_), GroupKey::Str(s)) => {
                    return Err(other(format!(
                        "group {s:?}: a string key among integer keys"
                    )))
                }
                (KeyValues::Str(v), k) => {
                    let text = match k {
                        GroupKey::Int(i) => i.to_string(),
                        GroupKey::Str(s) => s.clone(),
                    };
                    v.push((ByteArray::from(text.into_bytes()), ts.len()));
                }
            }
            self.t.extend_from_slice(ts);
            split_columns(pts, &mut self.coords);
        }
        Ok(())
    }

    /// Writes the gathered rows as one row group (nothing if there are none), column by column,
    /// and empties the vectors (keeping their memory for the next row group).
    fn write_row_group(&mut self) -> std::io::Result<()> {
        if self.t.is_empty() {
            return Ok(());
        }
        let mut rg = self.file.next_row_group().map_err(other)?;
        let missing = || other("fewer columns than the schema");
        let mut col = rg.next_column().map_err(other)?.ok_or_else(missing)?;
        match &self.keys {
            KeyValues::Int(k) => write_runs(col.typed::<Int64Type>(), k),
            KeyValues::Str(k) => write_runs(col.typed::<ByteArrayType>(), k),
        }
        .map_err(other)?;
        col.close().map_err(other)?;
        for values in std::iter::once(&self.t).chain(&self.coords) {
            let mut col = rg.next_column().map_err(other)?.ok_or_else(missing)?;
            col.typed::<DoubleType>()
                .write_batch(values, None, None)
                .map_err(other)?;
            col.close().map_err(other)?;
        }
        rg.close().map_err(other)?;
        match &mut self.keys {
            KeyValues::Int(k) => k.clear(),
            KeyValues::Str(k) => k.clear(),
        }
        self.t.clear();
        for c in &mut self.coords {
            c.clear();
        }
        Ok(())
    }

    /// Writes the last row group and the footer.
    fn close(mut self) -> std::io::Result<()> {
        self.write_row_group()?;
        self.file.close().map(|_| ()).map_err(other)
    }
}
