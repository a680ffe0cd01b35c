//! Length and finiteness checks of the derivative kernels' buffers.

use crate::error::{check_finite, Error, Result, MAX_SCALARS};

/// `got == expected`, else [`Error::LengthMismatch`] naming `what`.
pub(super) fn check_len(what: &'static str, expected: usize, got: usize) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(Error::LengthMismatch {
            what,
            expected,
            got,
        })
    }
}

/// An optional input buffer: its length, then its numbers finite.
pub(super) fn check_input(what: &'static str, expected: usize, got: Option<&[f64]>) -> Result<()> {
    match got {
        Some(v) => {
            check_len(what, expected, v.len())?;
            check_finite(what, v)
        }
        None => Ok(()),
    }
}

/// `count · width` numbers fit in [`MAX_SCALARS`], else [`Error::TooLarge`]; returns the product.
pub(super) fn check_scalars(what: &'static str, count: usize, width: usize) -> Result<usize> {
    match count.checked_mul(width) {
        Some(n) if n <= MAX_SCALARS => Ok(n),
        _ => Err(Error::TooLarge {
            what,
            size: count.saturating_mul(width),
            max: MAX_SCALARS,
        }),
    }
}
