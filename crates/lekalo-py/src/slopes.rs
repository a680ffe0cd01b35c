//! Slopes for Hermite interpolation of functions `y(x)` that SciPy's interpolators use:
//! `pchip_slopes` and `akima_slopes` (the library's `interpolate/pchip.rs`, `interpolate/akima.rs`).

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

/// Akima slopes at `x` for values `y` (`(n,)` or `(n, d)`): `method="akima"` (Akima 1970) or
/// `"makima"` (Moler's modified weights), `lekalo::akima_slopes`, the slopes of SciPy's
/// `Akima1DInterpolator`. Returns `(n, d)`.
#[pyfunction]
#[pyo3(signature = (x, y, method = "akima"))]
pub(crate) fn akima_slopes<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    method: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let modified = akima_modified(method)?;
    let xa = floats(x, "x")?;
    let xs = xa.vector("x")?;
    let ya = floats(y, "y")?;
    let ys = ya.points("y")?;
    let d = py
        .detach(|| lekalo::akima_slopes(xs, ys, modified))
        .map_err(lib_err)?;
    points_into_array(py, d)
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pchip_slopes, m)?)?;
    m.add_function(wrap_pyfunction!(akima_slopes, m)?)?;
    Ok(())
}

/// Whether `method` asks for Moler's modified Akima weights: `"makima"` yes, `"akima"` no, any
/// other spelling refused with the two SciPy accepts.
pub(crate) fn akima_modified(method: &str) -> PyResult<bool> {
    match method {
        "akima" => Ok(false),
        "makima" => Ok(true),
        other => Err(crate::error::bad(format!(
            "method: expected 'akima' or 'makima', got {other:?}"
        ))),
    }
}
