//! SciPy's piecewise cubics from values and slopes, for `lekalo.scipy`: the knots and
//! coefficients of the B-spline with double knots written straight into two NumPy arrays
//! (`lekalo::pp::cubic_hermite_bspline_into`), the data read in place (C-contiguous float64
//! arrays are borrowed, never copied), no curve built.

use lekalo::pp::{cubic_hermite_bspline_into, cubic_hermite_bspline_len};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::{filled, floats};
use crate::error::bad;

/// `(t, c)`: the cubic B-spline (knots `(2n + 4,)`, coefficients `(2n, m)`) of the cubic
/// Hermite spline with values `y` and slopes `dydx` (both `(n, m)`, or `(n,)` as one column) at
/// the strictly increasing `x` (`(n,)`): `x_0` and `x_{n−1}` four times, the other breakpoints
/// twice, the coefficients `y_0`, the inner Bézier points of every piece, `y_{n−1}`.
///
/// >>> import numpy as np, lekalo
/// >>> t, c = lekalo._lekalo.hermite_tck(np.array([0.0, 3.0]), np.array([1.0, 2.0]), np.array([0.0, 1.0]))
/// >>> t.tolist(), c[:, 0].tolist()
/// ([0.0, 0.0, 0.0, 0.0, 3.0, 3.0, 3.0, 3.0], [1.0, 1.0, 1.0, 2.0])
#[pyfunction]
pub(crate) fn hermite_tck<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    dydx: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyTuple>> {
    let xa = floats(x, "x")?;
    let ya = floats(y, "y")?;
    let da = floats(dydx, "dydx")?;
    if xa.shape().len() != 1 {
        return Err(bad(format!(
            "x: expected a 1-D array of breakpoints, got shape {:?}",
            xa.shape()
        )));
    }
    let n = xa.shape()[0];
    let dim = match ya.shape() {
        [_] => 1,
        [_, d] => *d,
        s => {
            return Err(bad(format!(
                "y: expected a 1-D or 2-D array (breakpoints, columns), got shape {s:?}"
            )))
        }
    };
    if da.shape() != ya.shape() {
        return Err(bad(format!(
            "dydx: expected the shape of y {:?}, got {:?}",
            ya.shape(),
            da.shape()
        )));
    }
    let (n_knots, n_ctrl) = cubic_hermite_bspline_len(n);
    let (xs, ys, ds) = (xa.data(), ya.data(), da.data());
    let t = PyArray1::<f64>::zeros(py, n_knots, false);
    let c = {
        let mut rw = t.readwrite();
        let knots = rw.as_slice_mut().map_err(|e| bad(format!("knots: {e}")))?;
        filled(py, &[n_ctrl, dim], |out| {
            cubic_hermite_bspline_into(xs, ys, ds, dim, knots, out)
        })?
    };
    PyTuple::new(py, [t.into_any(), c])
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(hermite_tck, m)?)?;
    Ok(())
}
