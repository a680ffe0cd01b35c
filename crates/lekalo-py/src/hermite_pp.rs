//! SciPy's piecewise cubics as `PPoly` coefficients, for `lekalo.scipy`: the slopes (the C²
//! spline's tridiagonal system, PCHIP's, Akima's, or given) and the power coefficients of the
//! pieces (`lekalo::pp::cubic_hermite_power_into`) written straight into one NumPy array of
//! shape `(4, n − 1, m)` (or `(4, n − 1)` for values of shape `(n,)`), the data read in place.

use lekalo::interpolate::{cubic_spline_power_into, CubicSplineEnd};
use lekalo::pp::cubic_hermite_power_into;
use lekalo::{akima_slopes_into, pchip_slopes_into};
use pyo3::prelude::*;

use crate::convert::{filled, floats, FloatArray};
use crate::error::bad;
use crate::slopes::akima_modified;

/// The breakpoints (a 1-D array) and the number of columns of `y` (`(n,)`: 1, `(n, m)`: `m`)
/// with the shape of the result, `(4, n − 1)` or `(4, n − 1, m)`.
fn layout(xa: &FloatArray<'_>, ya: &FloatArray<'_>) -> PyResult<(usize, Vec<usize>)> {
    let n = match xa.shape() {
        [n] => *n,
        s => {
            return Err(bad(format!(
                "x: expected a 1-D array of breakpoints, got shape {s:?}"
            )))
        }
    };
    let pieces = n.saturating_sub(1);
    match ya.shape() {
        [m] if *m == n => Ok((1, vec![4, pieces])),
        [m, d] if *m == n => Ok((*d, vec![4, pieces, *d])),
        s => Err(bad(format!(
            "y: expected one row of values per breakpoint, shape ({n},) or ({n}, m), got {s:?}"
        ))),
    }
}

/// `c` (`(4, n − 1)` or `(4, n − 1, m)`): SciPy's `CubicHermiteSpline` coefficients of the
/// values `y` and slopes `dydx` (the same shape, `(n,)` or `(n, m)`) at the strictly increasing
/// `x`, `lekalo::pp::cubic_hermite_power_into` (SciPy's operations, its numbers).
///
/// >>> import numpy as np, lekalo
/// >>> lekalo._lekalo.hermite_pp(np.array([0.0, 1.0]), np.array([0.0, 1.0]), np.array([0.0, 3.0])).tolist()
/// [[1.0], [0.0], [0.0], [0.0]]
#[pyfunction]
pub(crate) fn hermite_pp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    dydx: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let (xa, ya, da) = (floats(x, "x")?, floats(y, "y")?, floats(dydx, "dydx")?);
    let (dim, shape) = layout(&xa, &ya)?;
    if da.shape() != ya.shape() {
        return Err(bad(format!(
            "dydx: expected the shape of y {:?}, got {:?}",
            ya.shape(),
            da.shape()
        )));
    }
    let (xs, ys, ds) = (xa.data(), ya.data(), da.data());
    filled(py, &shape, |c| cubic_hermite_power_into(xs, ys, ds, dim, c))
}

/// `c` (`(4, n − 1)`): [`hermite_pp`] with the slopes of SciPy's `PchipInterpolator` at the
/// values `y` of dimension 1 (`(n,)`): `lekalo::pchip_slopes_into`, then
/// `cubic_hermite_power_into`, one vectorised pass each with the checks of the data folded in.
///
/// >>> import numpy as np, lekalo
/// >>> lekalo._lekalo.pchip_pp(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 1.0]))[:, 0].tolist()
/// [-0.5, 0.0, 1.5, 0.0]
#[pyfunction]
pub(crate) fn pchip_pp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    scalar_pp(py, x, y, pchip_slopes_into)
}

/// `c` (`(4, n − 1)`): [`hermite_pp`] with the slopes of SciPy's `Akima1DInterpolator`
/// (`method` `"akima"` or `"makima"`) at the values `y` of dimension 1 (`(n,)`):
/// `lekalo::akima_slopes_into`, then `cubic_hermite_power_into`.
///
/// >>> import numpy as np, lekalo
/// >>> lekalo._lekalo.akima_pp(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 2.0]), "akima").tolist()
/// [[0.0, 0.0], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
#[pyfunction]
#[pyo3(signature = (x, y, method = "akima"))]
pub(crate) fn akima_pp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    method: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let modified = akima_modified(method)?;
    scalar_pp(py, x, y, |xs, ys, slopes| {
        akima_slopes_into(xs, ys, modified, slopes)
    })
}

/// The power coefficients of the cubic Hermite spline through the values `y` of dimension 1
/// with the slopes `slopes_into` writes (one scratch array).
fn scalar_pp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    slopes_into: impl FnOnce(&[f64], &[f64], &mut [f64]) -> lekalo::Result<()> + Send,
) -> PyResult<Bound<'py, PyAny>> {
    let (xa, ya) = (floats(x, "x")?, floats(y, "y")?);
    let (dim, shape) = layout(&xa, &ya)?;
    if dim != 1 || ya.shape().len() != 1 {
        return Err(bad(format!(
            "y: expected one value per breakpoint, shape ({},), got {:?}",
            xa.shape()[0],
            ya.shape()
        )));
    }
    let (xs, ys) = (xa.data(), ya.data());
    filled(py, &shape, |c| {
        let mut slopes = vec![0.0; xs.len()];
        slopes_into(xs, ys, &mut slopes)?;
        cubic_hermite_power_into(xs, ys, &slopes, 1, c)
    })
}

/// One end condition of [`cubic_spline_pp`] as given: a word or `(order, values)`.
enum EndArg<'py> {
    NotAKnot,
    Periodic,
    Derivative(u8, FloatArray<'py>),
}

impl<'py> EndArg<'py> {
    fn read(obj: &Bound<'py, PyAny>, which: &str) -> PyResult<Self> {
        if let Ok(word) = obj.extract::<String>() {
            return match word.as_str() {
                "not-a-knot" => Ok(EndArg::NotAKnot),
                "periodic" => Ok(EndArg::Periodic),
                _ => Err(bad(format!(
                    "{which}: unknown end condition {word:?}; use \"not-a-knot\", \"periodic\" or (order, values)"
                ))),
            };
        }
        let (order, values): (u8, Bound<'py, PyAny>) = obj.extract().map_err(|_| {
            bad(format!(
                "{which}: expected \"not-a-knot\", \"periodic\" or (order, values) with order 1 or 2"
            ))
        })?;
        if !matches!(order, 1 | 2) {
            return Err(bad(format!(
                "{which}: the derivative order is {order}; use 1 or 2"
            )));
        }
        Ok(EndArg::Derivative(order, floats(&values, which)?))
    }

    fn condition(&self) -> CubicSplineEnd<'_> {
        match self {
            EndArg::NotAKnot => CubicSplineEnd::NotAKnot,
            EndArg::Periodic => CubicSplineEnd::Periodic,
            EndArg::Derivative(1, v) => CubicSplineEnd::FirstDerivative(v.data()),
            EndArg::Derivative(_, v) => CubicSplineEnd::SecondDerivative(v.data()),
        }
    }
}

/// `c` (`(4, n − 1)` or `(4, n − 1, m)`): SciPy's `CubicSpline` coefficients of the values `y`
/// (`(n,)` or `(n, m)`) at the strictly increasing `x`, each end `"not-a-knot"`, `"periodic"`
/// (both) or `(order, values)` (a first or second derivative, one value a column):
/// `lekalo::interpolate::cubic_spline_power_into` (SciPy's tridiagonal system solved for every
/// column at once, then the pieces in power form; SciPy's coefficients to rounding).
///
/// >>> import numpy as np, lekalo
/// >>> x = np.array([0.0, 1.0, 2.0])
/// >>> lekalo._lekalo.cubic_spline_pp(x, x**3, (1, np.array([0.0])), (1, np.array([12.0]))).tolist()
/// [[1.0, 1.0], [0.0, 3.0], [0.0, 3.0], [0.0, 1.0]]
#[pyfunction]
pub(crate) fn cubic_spline_pp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    start: &Bound<'py, PyAny>,
    end: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let (xa, ya) = (floats(x, "x")?, floats(y, "y")?);
    let (dim, shape) = layout(&xa, &ya)?;
    let (start, end) = (EndArg::read(start, "start")?, EndArg::read(end, "end")?);
    let (xs, ys) = (xa.data(), ya.data());
    let (s, e) = (start.condition(), end.condition());
    filled(py, &shape, |c| {
        cubic_spline_power_into(xs, ys, dim, s, e, c)
    })
}

/// Registers the functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(hermite_pp, m)?)?;
    m.add_function(wrap_pyfunction!(pchip_pp, m)?)?;
    m.add_function(wrap_pyfunction!(akima_pp, m)?)?;
    m.add_function(wrap_pyfunction!(cubic_spline_pp, m)?)?;
    Ok(())
}
