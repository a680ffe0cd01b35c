//! The batch runner: a command's work on one item (one curve, one group of points), given as a
//! closure, applied to every item of a batch in parallel; reading the batch, progress, writing
//! and the failures are handled here once. A bad item is written with its error and reported;
//! it does not stop the others, and the exit code is then 2.
//!
//! - `lines.rs`: JSON Lines (and the curves of a CAD file): one output line per item;
//! - `parquet.rs`: Parquet batches (docs/formats.md#parquet-batches): read, computed and
//!   written a few MiB at a time, and the conversion of curves between Parquet and JSON Lines.

pub(crate) mod lines;
pub(crate) mod parquet;

use anyhow::Result;

use crate::context::Context;
use crate::exit::bad_input;
use crate::output::report;

/// After a batch is written: each failure on its own line (unless quiet), then the batch's
/// error with `summary` (exit code 2); nothing when every object went through.
pub(crate) fn failures(failed: &[String], summary: String, cx: &Context) -> Result<()> {
    if failed.is_empty() {
        return Ok(());
    }
    if !cx.is_quiet() {
        for e in failed {
            report(&format!("  {e}"));
        }
    }
    bad_input(summary)
}
