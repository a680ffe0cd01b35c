//! The writer of curves, point sets and samples, one row group per call.

use std::io::Write;
use std::sync::Arc;

use arrow_array::builder::{
    Float64Builder, Int32Builder, Int64Builder, ListBuilder, StringBuilder,
};
use arrow_array::{ArrayRef, RecordBatch};
use parquet::arrow::ArrowWriter;
use parquet::basic::Compression;
use parquet::file::properties::WriterProperties;
use parquet::schema::types::ColumnPath;

use super::GroupKey;
use crate::object::Object;

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
