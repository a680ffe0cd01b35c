//! Slopes for Hermite interpolation of functions `y(x)` that SciPy's interpolators use:
//! `pchip_slopes` (the library's `interpolate/pchip.rs`).

use pyo3::prelude::*;

use crate::convert::{floats, points_into_array};
use crate::error::lib_err;

/// PCHIP slopes at `x` for values `y` (`(n,)` or `(n, d)`, each coordinate on its own):
/// Fritsch–Butland harmonic means inside, Moler's one-sided shape-preserving ends
/// (`lekalo::pchip_slopes`; the slopes of SciPy's `PchipInterpolator`). Returns `(n, d)`.
#[pyfunction]
pub(crate) fn pchip_slopes<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let xa = floats(x, "x")?;
    let xs = xa.vector("x")?;
    let ya = floats(y, "y")?;
    let ys = ya.points("y")?;
    let d = py
        .detach(|| lekalo::pchip_slopes(xs, ys))
        .map_err(lib_err)?;
    points_into_array(py, d)
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pchip_slopes, m)?)?;
    Ok(())
}
