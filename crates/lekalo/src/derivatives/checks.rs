//! Length and finiteness checks of the derivative kernels' buffers.

use crate::error::{check_finite, Error, Result, MAX_SCALARS};
use crate::What;

/// `got == expected`, else [`Error::LengthMismatch`] naming `what`.
pub(super) fn check_len(what: impl Into<What>, expected: usize, got: usize) -> Result<()> {
    let what: What = what.into();
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
pub(super) fn check_input(
    what: impl Into<What>,
    expected: usize,
    got: Option<&[f64]>,
) -> Result<()> {
    let what: What = what.into();
    match got {
        Some(v) => {
            check_len(what, expected, v.len())?;
            check_finite(what, v)
        }
        None => Ok(()),
    }
}

/// `count · width` numbers fit in [`MAX_SCALARS`], else [`Error::TooLarge`]; returns the product.
pub(super) fn check_scalars(what: impl Into<What>, count: usize, width: usize) -> Result<usize> {
    let what: What = what.into();
    match count.checked_mul(width) {
        Some(n) if n <= MAX_SCALARS => Ok(n),
        _ => Err(Error::TooLarge {
            what,
            size: count.saturating_mul(width),
            max: MAX_SCALARS,
        }),
    }
}

/// The cotangent of a batch VJP: `count · dim` numbers (`what` names them), all finite.
pub(super) fn check_cotangent(
    what: impl Into<What>,
    count: usize,
    dim: usize,
    cotangent: &[f64],
) -> Result<()> {
    let what: What = what.into();
    check_len(what, count.saturating_mul(dim), cotangent.len())?;
    check_finite("cotangent", cotangent)
}

/// An optional output buffer a VJP sums into: its length, then zeroed.
pub(super) fn zeroed_output(
    what: impl Into<What>,
    expected: usize,
    buf: Option<&mut [f64]>,
) -> Result<()> {
    let what: What = what.into();
    if let Some(g) = buf {
        check_len(what, expected, g.len())?;
        g.fill(0.0);
    }
    Ok(())
}

/// An optional output buffer a VJP overwrites: its length.
pub(super) fn check_output<T>(
    what: impl Into<What>,
    expected: usize,
    buf: Option<&[T]>,
) -> Result<()> {
    let what: What = what.into();
    match buf {
        Some(g) => check_len(what, expected, g.len()),
        None => Ok(()),
    }
}
