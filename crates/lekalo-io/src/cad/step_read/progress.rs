//! The progress of a STEP read ([`Meter`]): the bytes parsed, then the instances converted in
//! each [`Pass`], reported through the library's progress hook, which may cancel the read.

use crate::error::{IoError, IoResult};
use lekalo::Progress;

/// The passes over the entity instances after parsing, in order.
#[derive(Debug, Clone, Copy)]
pub(super) enum Pass {
    /// Trimmed curves.
    Trims = 0,
    /// B-spline curves and surfaces, analytic curves.
    Curves = 1,
    /// Analytic surfaces.
    Surfaces = 2,
    /// Faces.
    Faces = 3,
}

/// The progress of one read on a bar of `2 · len` units for a text of `len` bytes: the bytes
/// parsed, then the instances converted, the four [`Pass`]es sharing the second half.
pub(super) struct Meter<'a> {
    pub(super) progress: &'a Progress<'a>,
    pub(super) source: &'a str,
    pub(super) len: u64,
}

/// What a STEP read reports itself as.
const READING: &str = "reading STEP";

/// Instances converted between two consultations of the hook.
const REPORT_INSTANCES: usize = 1 << 10;

impl Meter<'_> {
    fn step(&self, done: u64) -> IoResult<()> {
        if !self.progress.is_active() {
            return Ok(());
        }
        self.progress
            .step(READING, done, 2 * self.len)
            .map_err(|e| IoError::cancelled(self.source, &e))
    }

    /// `bytes` of the text parsed.
    pub(super) fn parsed(&self, bytes: usize) -> IoResult<()> {
        self.step((bytes as u64).min(self.len))
    }

    /// Instance `k` of `n` reached in `pass`: reported every [`REPORT_INSTANCES`].
    pub(super) fn converted(&self, pass: Pass, k: usize, n: usize) -> IoResult<()> {
        if k % REPORT_INSTANCES != 0 {
            return Ok(());
        }
        let whole = 4 * n.max(1) as u128;
        let at = (pass as u128) * n as u128 + k as u128;
        // at ≤ whole, so the quotient is at most len
        #[allow(clippy::cast_possible_truncation)]
        let done = (u128::from(self.len) * at / whole) as u64;
        self.step(self.len + done)
    }

    /// The read is complete: `(total, total)`, whatever the flag says now.
    pub(super) fn finish(&self) {
        if self.progress.is_active() {
            let _ = self.progress.step(READING, 2 * self.len, 2 * self.len);
        }
    }
}
