//! Calculus on a spline given as arrays, SciPy's `(t, c, k)`, for `lekalo.scipy`: derivative and
//! antiderivative coefficients, definite integrals (`lekalo::curve::tck`), knot insertion
//! (`lekalo::insert_knot_into`) and zeros (`lekalo::curve::bspline_zeros`). The knots and
//! coefficients are read in place (C-contiguous float64 arrays are borrowed, never copied) and
//! each result is one NumPy array, allocated once and written with the GIL released; no curve
//! is built, so nothing is validated or copied beyond what the computation reads.

use lekalo::curve::{
    antiderivative_coefficients_into, antiderivative_knots_into, basis_integrals_into,
    bspline_zeros, derivative_coefficients_into, integral_into,
};
use lekalo::insert_knot_into;
use numpy::PyArray1;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::IntArg;
use crate::convert::{check_size, filled, filled_pair, floats, FloatArray};
use crate::error::{bad, lib_err};

/// The knots: a 1-D array (not checked finite here: the library refuses what it cannot use).
fn knots<'a>(t: &'a FloatArray<'_>) -> PyResult<&'a [f64]> {
    if t.shape().len() != 1 {
        return Err(bad(format!(
            "t: expected a 1-D array of knots, got shape {:?}",
            t.shape()
        )));
    }
    Ok(t.data())
}

/// The coefficients' columns: `(rows, dim)`, or `(rows,)` as one column.
fn columns(c: &FloatArray<'_>) -> PyResult<usize> {
    match c.shape() {
        [_] => Ok(1),
        [_, d] => Ok(*d),
        s => Err(bad(format!(
            "c: expected a 1-D or 2-D array of coefficients (rows, columns), got shape {s:?}"
        ))),
    }
}

/// The coefficients of the `nu`-th derivative of the spline `(t, c, k)`, `(len(t) − 2nu, dim)`
/// in SciPy's layout (the rows past `n − nu` zero; its knots are `t[nu:-nu]`), without a curve
/// built (`lekalo::curve::derivative_coefficients_into`).
///
/// >>> import numpy as np, lekalo
/// >>> t = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
/// >>> lekalo._lekalo.tck_derivative(t, np.array([[0.0], [0.0], [1.0]]), 2)[:, 0].tolist()
/// [0.0, 2.0, 0.0, 0.0]
#[pyfunction]
#[pyo3(signature = (t, c, k, nu = IntArg::of(1)), text_signature = "(t, c, k, nu=1)")]
pub(crate) fn tck_derivative<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: IntArg,
    nu: IntArg,
) -> PyResult<Bound<'py, PyAny>> {
    let k = k.count("k")?;
    let nu = nu.count("nu")?;
    let ta = floats(t, "t")?;
    let ca = floats(c, "c")?;
    let (ts, dim) = (knots(&ta)?, columns(&ca)?);
    let rows = ts.len().checked_sub(2 * nu).ok_or_else(|| {
        bad(format!(
            "derivative order {nu} needs at least {} knots, got {}",
            2 * nu,
            ts.len()
        ))
    })?;
    let cs = ca.data();
    filled(py, &[rows, dim], |out| {
        derivative_coefficients_into(ts, k, cs, dim, nu, out)
    })
}

/// The `nu`-th antiderivative of the spline `(t, c, k)` in SciPy's layout (`splantider`):
/// `(knots, coefficients)`, the knots `t` with each end knot repeated `nu` times more
/// (`lekalo::curve::antiderivative_knots_into`), the coefficients `(len(t) + 2nu, dim)` (the
/// rows past `n + nu` copies of the last; `lekalo::curve::antiderivative_coefficients_into`),
/// each array allocated once, without a curve built.
///
/// >>> import numpy as np, lekalo
/// >>> t, c = lekalo._lekalo.tck_antiderivative(np.array([0.0, 1.0]), np.array([[1.0]]), 0)
/// >>> t.tolist(), c[:, 0].tolist()
/// ([0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 1.0, 1.0])
#[pyfunction]
#[pyo3(signature = (t, c, k, nu = IntArg::of(1)), text_signature = "(t, c, k, nu=1)")]
pub(crate) fn tck_antiderivative<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: IntArg,
    nu: IntArg,
) -> PyResult<Bound<'py, PyTuple>> {
    let k = k.count("k")?;
    let nu = nu.count("nu")?;
    let ta = floats(t, "t")?;
    let ca = floats(c, "c")?;
    let (ts, dim) = (knots(&ta)?, columns(&ca)?);
    let rows = nu
        .checked_mul(2)
        .and_then(|v| v.checked_add(ts.len()))
        .ok_or_else(|| bad(format!("antiderivative order {nu} is too large")))?;
    check_size("antiderivative coefficients", &[rows, dim])?;
    let cs = ca.data();
    let (new_t, new_c) = filled_pair(py, [&[rows], &[rows, dim]], |out_t, out_c| {
        antiderivative_coefficients_into(ts, k, cs, dim, nu, out_c)?;
        antiderivative_knots_into(ts, nu, out_t)
    })?;
    PyTuple::new(py, [new_t, new_c])
}

/// `∫_a^b` of the spline `(t, c, k)`, `(dim,)`, the end polynomials continued beyond the
/// domain (clip the limits first for the integral over the domain only), reading only the
/// coefficients between the limits (`lekalo::curve::integral_into`).
///
/// >>> import numpy as np, lekalo
/// >>> t = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
/// >>> float(lekalo._lekalo.tck_integral(t, np.array([[0.0], [0.0], [3.0]]), 2, 0.0, 1.0)[0])
/// 1.0
#[pyfunction]
pub(crate) fn tck_integral<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: IntArg,
    a: f64,
    b: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let k = k.count("k")?;
    let ta = floats(t, "t")?;
    let ca = floats(c, "c")?;
    let (ts, dim) = (knots(&ta)?, columns(&ca)?);
    let mut out = vec![0.0; dim];
    let cs = ca.data();
    py.detach(|| integral_into(ts, k, cs, dim, a, b, &mut out))
        .map_err(lib_err)?;
    Ok(PyArray1::from_vec(py, out))
}

/// `∫_a^b N_{i,k}` for each of the `len(t) − k − 1` B-splines on the knots `t`, limits in the
/// domain `[t_k, t_n]` (FITPACK's `fpintb`, `lekalo::curve::basis_integrals_into`).
///
/// >>> import numpy as np, lekalo
/// >>> lekalo._lekalo.tck_basis_integrals(np.array([0.0, 0.0, 1.0, 2.0, 2.0]), 1, 0.0, 1.0).tolist()
/// [0.5, 0.5, 0.0]
#[pyfunction]
pub(crate) fn tck_basis_integrals<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    k: IntArg,
    a: f64,
    b: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let k = k.count("k")?;
    let ta = floats(t, "t")?;
    let ts = knots(&ta)?;
    let n = ts.len().saturating_sub(k).saturating_sub(1);
    let mut out = vec![0.0; n];
    py.detach(|| basis_integrals_into(ts, k, a, b, &mut out))
        .map_err(lib_err)?;
    Ok(PyArray1::from_vec(py, out))
}

/// The spline `(t, c, k)` with `x` inserted `m` times (Boehm's insertion at any multiplicity, as
/// FITPACK's `fpinst`; with `periodic`, the periodic extension kept): `(knots, coefficients)`,
/// the coefficients `(len(knots), dim)` in SciPy's layout (zero rows after the
/// `len(knots) − k − 1` coefficients), each array allocated once (`lekalo::insert_knot_into`:
/// the knots and coefficients the insertion reads are checked, the others copied as they are,
/// as FITPACK copies them). `c` has exactly `len(t) − k − 1` rows.
///
/// >>> import numpy as np, lekalo
/// >>> t, c = lekalo._lekalo.tck_insert(np.array([0.0, 0.0, 1.0, 1.0]), np.array([[0.0], [1.0]]), 1, 0.5)
/// >>> t.tolist(), c[:, 0].tolist()
/// ([0.0, 0.0, 0.5, 1.0, 1.0], [0.0, 0.5, 1.0, 0.0, 0.0])
#[pyfunction]
#[pyo3(signature = (t, c, k, x, m = IntArg::of(1), periodic = false), text_signature = "(t, c, k, x, m=1, periodic=False)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn tck_insert<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: IntArg,
    x: f64,
    m: IntArg,
    periodic: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let k = k.count("k")?;
    let m = m.count("m")?;
    let ta = floats(t, "t")?;
    let ca = floats(c, "c")?;
    let (ts, dim) = (knots(&ta)?, columns(&ca)?);
    let cs = ca.data();
    let len = ts
        .len()
        .checked_add(m)
        .ok_or_else(|| bad(format!("m = {m} insertions are too many")))?;
    check_size("coefficients after insertion", &[len, dim])?;
    let (new_t, new_c) = filled_pair(py, [&[len], &[len, dim]], |out_t, out_c| {
        insert_knot_into(k, ts, cs, dim, x, m, periodic, out_t, out_c)
    })?;
    PyTuple::new(py, [new_t, new_c])
}

/// The zeros of the scalar spline `(t, c, k)` in its base interval, increasing, the first and
/// last spans' polynomials also searched beyond it (`lekalo::curve::bspline_zeros`: spans whose
/// coefficients share one strict sign skipped, the others solved in power form). `c` is 1-D.
/// With `fitpack_knots`, FITPACK's condition on the knots of `sproot`,
/// `t_1 ≤ … ≤ t_4 < t_5 < … < t_{n−3} ≤ … ≤ t_n` (sorted, and `t[k] … t[n]` increasing
/// strictly; NaN fails), is checked in one pass and refused as FITPACK's `TypeError`.
///
/// >>> import numpy as np, lekalo
/// >>> lekalo._lekalo.tck_zeros(np.array([0.0, 0.0, 1.0, 2.0, 2.0]), np.array([-1.0, 1.0, -1.0]), 1).tolist()
/// [0.5, 1.5]
#[pyfunction]
#[pyo3(signature = (t, c, k, fitpack_knots = false))]
pub(crate) fn tck_zeros<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: IntArg,
    fitpack_knots: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let k = k.count("k")?;
    let ta = floats(t, "t")?;
    let ca = floats(c, "c")?;
    let ts = knots(&ta)?;
    if ca.shape().len() != 1 {
        return Err(bad(format!(
            "c: expected a 1-D array of coefficients (one spline), got shape {:?}",
            ca.shape()
        )));
    }
    if fitpack_knots && !fitpack_zero_knots(ts, k) {
        return Err(PyTypeError::new_err(format!(
            "Invalid input data. t1<=..<=t4<t5<..<tn-3<=..<=tn must hold: the knots must be \
             sorted, and t[{k}] … t[len(t) − {}] distinct (no NaN)",
            k + 1
        )));
    }
    let cs = ca.data();
    let z = py.detach(|| bspline_zeros(ts, k, cs)).map_err(lib_err)?;
    Ok(PyArray1::from_vec(py, z))
}

/// FITPACK's condition on the knots of `sproot` (`fpchec`'s order conditions): `t` sorted and
/// `t[k] < … < t[n]`, `n = len(t) − k − 1`, in one branch-free pass (NaN fails every
/// comparison). Fewer than `k + 2` knots pass here; the library refuses them.
fn fitpack_zero_knots(t: &[f64], k: usize) -> bool {
    let Some(n) = t.len().checked_sub(k + 1).filter(|&n| n > k) else {
        return true;
    };
    // three runs of neighbours, one pass in all: sorted up to t[k], increasing strictly from
    // t[k] to t[n], sorted after
    let pairs = |u: &[f64], strict: bool| {
        u.iter()
            .zip(&u[1..])
            .fold(true, |ok, (a, b)| ok & if strict { a < b } else { a <= b })
    };
    pairs(&t[..=k], false) & pairs(&t[k..=n], true) & pairs(&t[n..], false)
}

/// Registers the functions of this module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(tck_derivative, m)?)?;
    m.add_function(wrap_pyfunction!(tck_antiderivative, m)?)?;
    m.add_function(wrap_pyfunction!(tck_integral, m)?)?;
    m.add_function(wrap_pyfunction!(tck_basis_integrals, m)?)?;
    m.add_function(wrap_pyfunction!(tck_insert, m)?)?;
    m.add_function(wrap_pyfunction!(tck_zeros, m)?)?;
    Ok(())
}
