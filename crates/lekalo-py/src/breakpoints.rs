//! SciPy's test of the breakpoints of a piecewise polynomial, for `lekalo.scipy`'s `PPoly` and
//! `BPoly`: `lekalo::breakpoints_sorted` on the array in place.

use pyo3::prelude::*;

use crate::convert::floats;
use crate::error::bad;

/// `breakpoints_sorted(x)`: whether the 1-D float64 array `x` is sorted one way, every
/// difference `x[i+1] - x[i] >= 0` or every one `<= 0` (NaN makes it false): SciPy's
/// `np.all(dx >= 0) or np.all(dx <= 0)` on `dx = np.diff(x)` in one pass, nothing allocated
/// (`lekalo::breakpoints_sorted`).
///
/// >>> import numpy as np, lekalo
/// >>> lekalo._lekalo.breakpoints_sorted(np.array([0.0, 1.0, 1.0])), lekalo._lekalo.breakpoints_sorted(np.array([0.0, 2.0, 1.0]))
/// (True, False)
#[pyfunction]
pub(crate) fn breakpoints_sorted(py: Python<'_>, x: &Bound<'_, PyAny>) -> PyResult<bool> {
    let xa = floats(x, "x")?;
    if xa.shape().len() != 1 {
        return Err(bad(format!(
            "x: expected a 1-D array of breakpoints, got shape {:?}",
            xa.shape()
        )));
    }
    let xs = xa.data();
    Ok(py.detach(|| lekalo::breakpoints_sorted(xs)))
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(breakpoints_sorted, m)?)?;
    Ok(())
}
