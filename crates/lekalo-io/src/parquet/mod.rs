//! Parquet batches (docs/formats.md#parquet-batches): many point sets in, many curves out, and
//! curves in, samples out, streamed a batch of a few MiB at a time (a row group or a part of
//! one) so that memory is bounded by the batch, not the file.
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
//!
//! Files: `columns.rs` reads a file's row groups and its numeric and key columns whatever their
//! Arrow types; `read_points.rs` gathers point sets; `read_curves.rs` reads curves back;
//! `write.rs` holds the writer of curves, points and samples; `text_groups.rs` reads point
//! sets in the long layout from a text table (CSV with a key column), to be written as a batch;
//! `table.rs` reads and writes one table without a key (one point set: a grid's values, the
//! points where a spline is evaluated, its samples).

mod columns;
mod read_curves;
mod read_points;
mod table;
mod text_groups;
mod write;

pub use read_curves::read_curve_groups;
pub use read_points::read_point_groups;
pub use table::{read_parquet_points, table_to_parquet};
pub use text_groups::{read_text_point_groups, TextPointGroups};
pub use write::ParquetBatchWriter;

use crate::error::IoResult;

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

#[cfg(test)]
mod tests;
