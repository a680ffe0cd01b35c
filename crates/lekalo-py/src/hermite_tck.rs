//! SciPy's piecewise cubics from values and slopes as B-splines: the knots and coefficients of
//! the B-spline with double knots written straight into two NumPy arrays
//! (`lekalo::pp::cubic_hermite_bspline_into`), the data read in place (C-contiguous float64
//! arrays are borrowed, never copied), no curve built. (`lekalo.scipy`'s classes take SciPy's
//! power coefficients instead, `hermite_pp.rs`.)

use lekalo::pp::{cubic_hermite_bspline_into, cubic_hermite_bspline_len};
use lekalo::{akima_slopes_into, pchip_slopes_into};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::{filled_pair, floats, FloatArray};
use crate::error::bad;
use crate::slopes::akima_modified;

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
    let (t, c) = filled_pair(py, [&[n_knots], &[n_ctrl, dim]], |knots, out| {
        cubic_hermite_bspline_into(xs, ys, ds, dim, knots, out)
    })?;
    PyTuple::new(py, [t, c])
}

/// `(t, c)`: [`hermite_tck`] with the slopes of SciPy's `PchipInterpolator` at the values `y`
/// of dimension 1 (`(n,)` or `(n, 1)`; coefficients `(2n, 1)`): `lekalo::pchip_slopes_into`,
/// then `cubic_hermite_bspline_into`, both one vectorised pass with the checks of the data
/// folded in; the slopes in one scratch array.
///
/// >>> import numpy as np, lekalo
/// >>> t, c = lekalo._lekalo.pchip_tck(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 1.0]))
/// >>> c[:, 0].tolist()
/// [0.0, 0.5, 1.0, 1.0, 1.0, 1.0]
#[pyfunction]
pub(crate) fn pchip_tck<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyTuple>> {
    scalar_tck(py, x, y, pchip_slopes_into)
}

/// `(t, c)`: [`hermite_tck`] with the slopes of SciPy's `Akima1DInterpolator` (`method`
/// `"akima"` or `"makima"`) at the values `y` of dimension 1 (`(n,)` or `(n, 1)`; coefficients
/// `(2n, 1)`): `lekalo::akima_slopes_into`, then `cubic_hermite_bspline_into`, the checks of
/// the data folded into their passes; the slopes in one scratch array.
///
/// >>> import numpy as np, lekalo
/// >>> t, c = lekalo._lekalo.akima_tck(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 2.0]), "akima")
/// >>> c[:, 0].tolist()
/// [0.0, 0.3333333333333333, 0.6666666666666667, 1.3333333333333333, 1.6666666666666667, 2.0]
#[pyfunction]
#[pyo3(signature = (x, y, method = "akima"))]
pub(crate) fn akima_tck<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    method: &str,
) -> PyResult<Bound<'py, PyTuple>> {
    let modified = akima_modified(method)?;
    scalar_tck(py, x, y, |xs, ys, slopes| {
        akima_slopes_into(xs, ys, modified, slopes)
    })
}

/// `(t, c)` of the cubic Hermite spline through the values `y` of dimension 1 (`(n,)` or
/// `(n, 1)`) at `x` with the slopes `slopes_into` writes: the slopes in one scratch array, then
/// `cubic_hermite_bspline_into` into the two NumPy arrays, the data read in place.
fn scalar_tck<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    slopes_into: impl FnOnce(&[f64], &[f64], &mut [f64]) -> lekalo::Result<()> + Send,
) -> PyResult<Bound<'py, PyTuple>> {
    let xa = floats(x, "x")?;
    let ya = floats(y, "y")?;
    let xs = one_d(&xa, "x")?;
    let n = xs.len();
    if !matches!(ya.shape(), [m] | [m, 1] if *m == n) {
        return Err(bad(format!(
            "y: expected one value per breakpoint, shape ({n},) or ({n}, 1), got {:?}",
            ya.shape()
        )));
    }
    let ys = ya.data();
    let (n_knots, n_ctrl) = cubic_hermite_bspline_len(n);
    let (t, c) = filled_pair(py, [&[n_knots], &[n_ctrl, 1]], |knots, out| {
        let mut slopes = vec![0.0; n];
        slopes_into(xs, ys, &mut slopes)?;
        cubic_hermite_bspline_into(xs, ys, &slopes, 1, knots, out)
    })?;
    PyTuple::new(py, [t, c])
}

/// The numbers of a 1-D array, unchecked: the kernels check them in their passes (the
/// conversion's own finiteness check would be one more pass).
fn one_d<'a>(a: &'a FloatArray<'_>, what: &str) -> PyResult<&'a [f64]> {
    match a.shape() {
        [_] => Ok(a.data()),
        s => Err(bad(format!(
            "{what}: expected a 1-D array, got shape {s:?}"
        ))),
    }
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(hermite_tck, m)?)?;
    m.add_function(wrap_pyfunction!(pchip_tck, m)?)?;
    m.add_function(wrap_pyfunction!(akima_tck, m)?)?;
    Ok(())
}
