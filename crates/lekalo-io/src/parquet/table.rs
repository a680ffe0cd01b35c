//! One table of numbers in Parquet, without a key column: one row per point (the values of a
//! grid's nodes, the points where a spline is evaluated) in, one row per sample out
//! (docs/formats.md#parquet-tables).

use std::path::Path;
use std::sync::Arc;

use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::basic::Compression;
use parquet::file::properties::{EnabledStatistics, WriterProperties};

use super::columns::{Numbers, RowGroups};
use crate::error::{IoError, IoResult, Location};

/// The points of a Parquet table: one row per point, every column a coordinate (double, float
/// or integer), in the file's order; also the columns' names. At most `max_points` rows are
/// read, checked against the file's metadata before anything is reserved.
///
/// # Errors
/// [`IoError::Read`] if the file cannot be opened; [`IoError::Syntax`] for a file that is not
/// Parquet, a column that is not numeric (naming it), no rows, or a null or non-finite number
/// (naming its row, from 1, and column); [`IoError::OverLimit`] (with [`crate::Limit::Size`])
/// above `max_points` rows or where the memory cannot be reserved.
pub fn read_parquet_points(
    path: &Path,
    max_points: usize,
) -> IoResult<(lekalo::Points, Vec<String>, String)> {
    let rg = RowGroups::open(path)?;
    let source = rg.source.clone();
    let at = Location::new(&source);
    let names: Vec<String> = rg
        .schema()
        .fields()
        .iter()
        .map(|f| f.name().clone())
        .collect();
    for f in rg.schema().fields() {
        if !matches!(
            f.data_type(),
            DataType::Float64 | DataType::Float32 | DataType::Int64 | DataType::Int32
        ) {
            return Err(IoError::syntax(
                at.clone().at_field(f.name()),
                format!(
                    "the column is {}, not numbers; a table of points has one numeric column \
                     per coordinate (double, float or integer), one row per point",
                    f.data_type()
                ),
            ));
        }
    }
    let dim = names.len();
    let rows: usize = (0..rg.count())
        .map(|i| rg.row_count(i))
        .fold(0usize, usize::saturating_add);
    if dim == 0 || rows == 0 {
        return Err(IoError::syntax(
            at,
            "no points: the table has no rows or no columns",
        ));
    }
    let too_many = |what: String| IoError::OverLimit {
        what,
        limit: crate::Limit::Size,
        raise_to: u64::try_from(rows).ok(),
    };
    if rows > max_points {
        return Err(too_many(format!(
            "{source}: {rows} rows, above the limit of {max_points} points"
        )));
    }
    let mut data: Vec<f64> = Vec::new();
    data.try_reserve_exact(rows.saturating_mul(dim))
        .map_err(|_| {
            too_many(format!(
                "{source}: {rows} rows of {dim} columns: no memory for them"
            ))
        })?;
    let mut row0 = 0usize;
    for i in 0..rg.count() {
        for batch in rg.read(i)? {
            let batch = batch?;
            append_rows(&batch, &names, row0, &mut data, &at)?;
            row0 += batch.num_rows();
        }
    }
    let points = lekalo::Points::from_flat(dim, data).map_err(|error| IoError::Invalid {
        at: Location::new(&source),
        error,
    })?;
    Ok((points, names, source))
}

/// Appends the rows of `batch` (rows `row0 + 1 …` of the file) point by point to `data`.
fn append_rows(
    batch: &RecordBatch,
    names: &[String],
    row0: usize,
    data: &mut Vec<f64>,
    at: &Location,
) -> IoResult<()> {
    let columns: Vec<Numbers<'_>> = batch
        .columns()
        .iter()
        .zip(names)
        .map(|(c, name)| {
            Numbers::of(c.as_ref()).ok_or_else(|| {
                IoError::syntax(at.clone().at_field(name), "the column is not numbers")
            })
        })
        .collect::<IoResult<_>>()?;
    for r in 0..batch.num_rows() {
        for (n, name) in columns.iter().zip(names) {
            match n.get(r) {
                Some(v) if v.is_finite() => data.push(v),
                v => {
                    return Err(IoError::syntax(
                        at.clone().at_field(name),
                        format!(
                            "row {}: {}; every coordinate must be a finite number",
                            row0 + r + 1,
                            v.map_or("null".to_string(), |v| v.to_string())
                        ),
                    ))
                }
            }
        }
    }
    Ok(())
}

/// A Parquet file of one table of doubles: `columns` named, `flat` row by row (its length a
/// multiple of the number of columns), never null, in one row group; uncompressed, without
/// dictionaries or statistics (as the batches' doubles: see `write.rs`).
///
/// # Errors
/// [`IoError::Render`] if `flat` does not fill whole rows, or the encoder fails.
pub fn table_to_parquet(columns: &[String], flat: &[f64]) -> IoResult<Vec<u8>> {
    let width = columns.len();
    if width == 0 || flat.len() % width != 0 {
        return Err(IoError::Render(format!(
            "{} values do not fill rows of {width} columns",
            flat.len()
        )));
    }
    let rows = flat.len() / width;
    let schema = Arc::new(Schema::new(
        columns
            .iter()
            .map(|c| Field::new(c, DataType::Float64, false))
            .collect::<Vec<_>>(),
    ));
    let arrays: Vec<ArrayRef> = (0..width)
        .map(|j| {
            let column: Vec<f64> = (0..rows).map(|i| flat[i * width + j]).collect();
            Arc::new(Float64Array::from(column)) as ArrayRef
        })
        .collect();
    let render = |e: &dyn std::fmt::Display| IoError::Render(format!("Parquet: {e}"));
    let batch = RecordBatch::try_new(schema.clone(), arrays).map_err(|e| render(&e))?;
    let props = WriterProperties::builder()
        .set_compression(Compression::UNCOMPRESSED)
        .set_dictionary_enabled(false)
        .set_statistics_enabled(EnabledStatistics::None)
        .build();
    let mut out = Vec::new();
    let mut w = ArrowWriter::try_new(&mut out, schema, Some(props)).map_err(|e| render(&e))?;
    w.write(&batch).map_err(|e| render(&e))?;
    w.close().map_err(|e| render(&e))?;
    Ok(out)
}
