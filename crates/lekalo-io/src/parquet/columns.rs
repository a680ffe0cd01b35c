//! Reading a Parquet file's row groups, and its numeric and key columns whatever their Arrow
//! types.

use std::fs::File;
use std::path::{Path, PathBuf};

use arrow_array::cast::AsArray;
use arrow_array::types::{Float32Type, Float64Type, Int32Type, Int64Type};
use arrow_array::{Array, RecordBatch};
use parquet::arrow::arrow_reader::{
    ArrowReaderMetadata, ArrowReaderOptions, ParquetRecordBatchReaderBuilder,
};

use super::GroupKey;
use crate::error::{IoError, IoResult, Location};

pub(super) fn parquet_err(source: &str, e: impl std::fmt::Display) -> IoError {
    IoError::syntax(
        Location::new(source),
        format!("not a readable Parquet file: {e}"),
    )
}

/// A file's row groups, read one at a time.
pub(super) struct RowGroups {
    path: PathBuf,
    file: File,
    meta: ArrowReaderMetadata,
    pub(super) source: String,
}

impl RowGroups {
    pub(super) fn open(path: &Path) -> IoResult<Self> {
        let source = path.display().to_string();
        let file = File::open(path).map_err(|error| IoError::Read {
            path: path.to_path_buf(),
            error,
        })?;
        crate::atomic::note_read(path);
        let meta = ArrowReaderMetadata::load(&file, ArrowReaderOptions::new())
            .map_err(|e| parquet_err(&source, e))?;
        Ok(RowGroups {
            path: path.to_path_buf(),
            file,
            meta,
            source,
        })
    }

    /// The Parquet schema (the leaf columns, their levels and physical types).
    pub(super) fn parquet_schema(&self) -> &parquet::schema::types::SchemaDescriptor {
        self.meta.parquet_schema()
    }

    /// Parquet's own reader of the doubles of leaf column `leaf` in row group `i` (values and
    /// levels, no Arrow arrays), from the metadata already read, with its own handle of the file.
    pub(super) fn double_column(
        &self,
        i: usize,
        leaf: usize,
    ) -> IoResult<parquet::column::reader::ColumnReaderImpl<parquet::data_type::DoubleType>> {
        use parquet::column::reader::{get_column_reader, ColumnReader};
        let file = File::open(&self.path).map_err(|error| IoError::Read {
            path: self.path.clone(),
            error,
        })?;
        let group = self.meta.metadata().row_group(i);
        let rows = usize::try_from(group.num_rows()).unwrap_or(0);
        let pages = parquet::file::serialized_reader::SerializedPageReader::new(
            std::sync::Arc::new(file),
            group.column(leaf),
            rows,
            None,
        )
        .map_err(|e| parquet_err(&self.source, e))?;
        let descr = self.parquet_schema().column(leaf);
        match get_column_reader(descr, Box::new(pages)) {
            ColumnReader::DoubleColumnReader(r) => Ok(r),
            _ => Err(parquet_err(&self.source, "the column is not of doubles")),
        }
    }

    pub(super) fn count(&self) -> usize {
        self.meta.metadata().num_row_groups()
    }

    /// The rows of row group `i`, from the metadata.
    pub(super) fn row_count(&self, i: usize) -> usize {
        usize::try_from(self.meta.metadata().row_group(i).num_rows()).unwrap_or(usize::MAX)
    }

    pub(super) fn schema(&self) -> &arrow_schema::Schema {
        self.meta.schema()
    }

    /// The batches of row group `i`, decoded as they are iterated, each of about
    /// [`BATCH_BYTES`] (by the row group's uncompressed size per row) and at most
    /// [`BATCH_ROWS`] rows: memory follows the batch, not the row group, and a batch's columns
    /// stay in the caches from decoding to writing.
    pub(super) fn read(
        &self,
        i: usize,
    ) -> IoResult<impl Iterator<Item = IoResult<RecordBatch>> + '_> {
        self.read_without(i, None)
    }

    /// [`RowGroups::read`] without the root column `skip` (if any): the batches hold the other
    /// columns, in order.
    pub(super) fn read_without(
        &self,
        i: usize,
        skip: Option<usize>,
    ) -> IoResult<impl Iterator<Item = IoResult<RecordBatch>> + '_> {
        let meta = self.meta.metadata().row_group(i);
        let rows = usize::try_from(meta.num_rows()).unwrap_or(0);
        let bytes = usize::try_from(meta.total_byte_size()).unwrap_or(0);
        let file = self.file.try_clone().map_err(|error| IoError::Read {
            path: self.path.clone(),
            error,
        })?;
        let mut builder =
            ParquetRecordBatchReaderBuilder::new_with_metadata(file, self.meta.clone())
                .with_row_groups(vec![i])
                .with_batch_size(batch_rows(rows, bytes));
        if let Some(skip) = skip {
            let roots = (0..self.schema().fields().len()).filter(|&c| c != skip);
            let mask = parquet::arrow::ProjectionMask::roots(self.meta.parquet_schema(), roots);
            builder = builder.with_projection(mask);
        }
        Ok(builder
            .build()
            .map_err(|e| parquet_err(&self.source, e))?
            .map(|b| b.map_err(|e| parquet_err(&self.source, e))))
    }
}

/// The uncompressed size aimed at for one batch of rows: small enough that a batch's decoded
/// columns stay in the caches until its groups are gathered and worked on (4 MiB measured 13%
/// slower for `eval` of a curves file, and no faster for points).
pub(super) const BATCH_BYTES: usize = 1 << 20;

/// The most rows of one batch.
pub(super) const BATCH_ROWS: usize = 1 << 16;

/// The rows of a batch of a row group of `rows` rows and `bytes` uncompressed bytes.
fn batch_rows(rows: usize, bytes: usize) -> usize {
    let per_row = bytes.div_ceil(rows.max(1)).max(1);
    (BATCH_BYTES / per_row).clamp(1, BATCH_ROWS)
}

/// A numeric column (or the values of a list column) as `f64`s.
pub(super) enum Numbers<'a> {
    F64(&'a arrow_array::Float64Array),
    F32(&'a arrow_array::Float32Array),
    I64(&'a arrow_array::Int64Array),
    I32(&'a arrow_array::Int32Array),
}

impl<'a> Numbers<'a> {
    pub(super) fn of(a: &'a dyn Array) -> Option<Self> {
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

    /// Appends values `range` to `out`; `Err(i)` at the first null, value `i`. Doubles without
    /// nulls are copied as one slice.
    pub(super) fn extend_range(
        &self,
        range: std::ops::Range<usize>,
        out: &mut Vec<f64>,
    ) -> Result<(), usize> {
        if let Numbers::F64(a) = self {
            if a.null_count() == 0 {
                out.extend_from_slice(&a.values()[range]);
                return Ok(());
            }
        }
        for i in range {
            out.push(self.get(i).ok_or(i)?);
        }
        Ok(())
    }

    /// The values as a slice if they are doubles without nulls.
    pub(super) fn as_f64s(&self) -> Option<&'a [f64]> {
        match self {
            Numbers::F64(a) if a.null_count() == 0 => Some(a.values()),
            _ => None,
        }
    }

    /// Value `i`, `None` if null.
    #[allow(clippy::cast_precision_loss)] // integers are read as the nearest f64
    pub(super) fn get(&self, i: usize) -> Option<f64> {
        match self {
            Numbers::F64(a) => a.is_valid(i).then(|| a.value(i)),
            Numbers::F32(a) => a.is_valid(i).then(|| f64::from(a.value(i))),
            Numbers::I64(a) => a.is_valid(i).then(|| a.value(i) as f64),
            Numbers::I32(a) => a.is_valid(i).then(|| f64::from(a.value(i))),
        }
    }
}

/// The key column.
pub(super) enum Keys<'a> {
    I64(&'a arrow_array::Int64Array),
    I32(&'a arrow_array::Int32Array),
    Str(&'a arrow_array::StringArray),
    LargeStr(&'a arrow_array::LargeStringArray),
}

impl<'a> Keys<'a> {
    pub(super) fn of(a: &'a dyn Array) -> Option<Self> {
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

    /// The first null key's row, if any.
    pub(super) fn first_null(&self) -> Option<usize> {
        let nulls = match self {
            Keys::I64(a) => a.nulls(),
            Keys::I32(a) => a.nulls(),
            Keys::Str(a) => a.nulls(),
            Keys::LargeStr(a) => a.nulls(),
        };
        nulls.and_then(|n| (0..n.len()).find(|&i| n.is_null(i)))
    }

    /// The end of the run of equal keys that starts at row `r` (the first row after it with
    /// another key, or the length). Nulls are not compared: see [`Keys::first_null`].
    pub(super) fn run_end(&self, r: usize) -> usize {
        fn end<T: PartialEq>(r: usize, len: usize, at: impl Fn(usize) -> T) -> usize {
            let k = at(r);
            (r + 1..len).find(|&i| at(i) != k).unwrap_or(len)
        }
        match self {
            Keys::I64(a) => {
                let v = a.values();
                end(r, v.len(), |i| v[i])
            }
            Keys::I32(a) => {
                let v = a.values();
                end(r, v.len(), |i| v[i])
            }
            Keys::Str(a) => end(r, a.len(), |i| a.value(i)),
            Keys::LargeStr(a) => end(r, a.len(), |i| a.value(i)),
        }
    }

    pub(super) fn get(&self, i: usize) -> Option<GroupKey> {
        match self {
            Keys::I64(a) => a.is_valid(i).then(|| GroupKey::Int(a.value(i))),
            Keys::I32(a) => a.is_valid(i).then(|| GroupKey::Int(i64::from(a.value(i)))),
            Keys::Str(a) => a.is_valid(i).then(|| GroupKey::Str(a.value(i).to_string())),
            Keys::LargeStr(a) => a.is_valid(i).then(|| GroupKey::Str(a.value(i).to_string())),
        }
    }
}
