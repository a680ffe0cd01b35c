//! Derivatives of the fits with respect to their data, for automatic differentiation:
//! interpolation at fixed parameters and knots, the least-squares fit on given knots and the
//! smoothing spline with a given `λ`, each linear in the data, `P = G⁻¹ BᵀW Q`: the JVP
//! `G⁻¹ BᵀW Q̇`, the VJP `W B G⁻¹ P̄` and the map's pieces, by the factored maps of
//! `lekalo::derivatives` (`docs/theory/derivatives.md#fits`), NumPy in and out.

use lekalo::derivatives::{
    FitLinearization, InterpolationMap, LeastSquaresFit, LeastSquaresMap, SmoothingFit,
    SmoothingMap,
};
use lekalo::KnotVector;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::index_array;
use crate::convert::{array, floats, vec1, FloatArray, IntArg};
use crate::error::lib_err;

/// Registers the functions of this module.
pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(interpolation_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(interpolation_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares_linearize, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_linearize, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_map_flat_len, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares_map_flat_len, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares_values_and_factors, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_values_and_factors, m)?)?;
    Ok(())
}

/// A tangent or cotangent of points `arg` (`(n, dim)`, or `(n,)` for dimension 1) through the
/// linear map `f(data, dim)` with the GIL released, shaped as `arg` with its first axis `len`
/// (unchanged for `None`).
fn map_points<'py, F>(
    py: Python<'py>,
    arg: &Bound<'py, PyAny>,
    what: &'static str,
    len: Option<usize>,
    f: F,
) -> PyResult<Bound<'py, PyAny>>
where
    F: Send + FnOnce(&[f64], usize) -> lekalo::Result<Vec<f64>>,
{
    let a = floats(arg, what)?;
    let dim = dim_of(&a, what)?;
    let v = a.data();
    let out = py.detach(|| f(v, dim)).map_err(lib_err)?;
    match len {
        Some(len) => array(py, out, &with_len(a.shape(), len)),
        None => array(py, out, a.shape()),
    }
}

/// An optional weights argument `w` (`None` as absent).
pub(super) fn weights_arg(w: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Vec<f64>>> {
    w.filter(|w| !w.is_none()).map(|w| vec1(w, "w")).transpose()
}

/// The factored collocation map of interpolation, and the data's dimension from `values`
/// (`(n, dim)`, or `(n,)` for dimension 1).
fn interpolation_map(
    degree: usize,
    knots: &Bound<'_, PyAny>,
    params: &Bound<'_, PyAny>,
) -> PyResult<InterpolationMap> {
    let kv = KnotVector::new(vec1(knots, "knots")?).map_err(lib_err)?;
    let ts = vec1(params, "params")?;
    InterpolationMap::new(degree, &kv, &ts).map_err(lib_err)
}

pub(super) fn dim_of(a: &FloatArray<'_>, what: &'static str) -> PyResult<usize> {
    Ok(a.points(what)?.dim())
}

/// Forward-mode derivative of interpolation at fixed `params` and `knots` with respect to the
/// data: the control-point tangent `A⁻¹ @ data_tangent` (shape of `data_tangent`).
#[pyfunction]
#[pyo3(signature = (degree, knots, params, data_tangent))]
pub(crate) fn interpolation_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    data_tangent: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let degree = degree.count("degree")?;
    let map = interpolation_map(degree, knots, params)?;
    map_points(py, data_tangent, "data_tangent", None, |v, dim| {
        map.jvp(v, dim)
    })
}

/// Reverse-mode derivative of interpolation at fixed `params` and `knots` with respect to the
/// data: the data cotangent `A⁻ᵀ @ control_cotangent` (an adjoint solve with the banded
/// factors; shape of `control_cotangent`).
#[pyfunction]
#[pyo3(signature = (degree, knots, params, control_cotangent))]
pub(crate) fn interpolation_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    control_cotangent: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let degree = degree.count("degree")?;
    let map = interpolation_map(degree, knots, params)?;
    map_points(
        py,
        control_cotangent,
        "control_cotangent",
        None,
        |v, dim| map.vjp(v, dim),
    )
}

/// `shape` with its first axis replaced by `len` (a tangent or cotangent of points mapped to
/// another number of points).
pub(super) fn with_len(shape: &[usize], len: usize) -> Vec<usize> {
    let mut s = shape.to_vec();
    if let Some(first) = s.first_mut() {
        *first = len;
    }
    s
}

/// An optional `factors` argument (`None` as absent): a fit's map as
/// `least_squares_values_and_factors` or `smoothing_values_and_factors` returned it.
fn factors_arg(factors: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Vec<f64>>> {
    factors
        .filter(|f| !f.is_none())
        .map(|f| vec1(f, "factors"))
        .transpose()
}

/// The factored least-squares map of `degree` on `knots` at `params` with weights `w` (the
/// library's `Σ w_k |r_k|²`, as `fit_least_squares`), or the map `factors` of the same fit
/// already factored (`least_squares_values_and_factors`).
fn least_squares_map(
    degree: usize,
    knots: &Bound<'_, PyAny>,
    params: &Bound<'_, PyAny>,
    w: Option<&Bound<'_, PyAny>>,
    factors: Option<&Bound<'_, PyAny>>,
) -> PyResult<LeastSquaresMap> {
    let kv = KnotVector::new(vec1(knots, "knots")?).map_err(lib_err)?;
    let ts = vec1(params, "params")?;
    let w = weights_arg(w)?;
    match factors_arg(factors)? {
        Some(f) => LeastSquaresMap::from_flat(&f, ts.len(), degree),
        None => LeastSquaresMap::new(degree, &kv, &ts, w.as_deref()),
    }
    .map_err(lib_err)
}

/// Forward-mode derivative of the least-squares fit (`fit_least_squares` without end or shape
/// constraints) at fixed `params` and `knots` with respect to the data: the control-point
/// tangent `(BᵀWB)⁻¹ BᵀW @ data_tangent` (`(n_ctrl, dim)`, or `(n_ctrl,)` for a 1-D tangent),
/// by the banded QR's triangle.
#[pyfunction]
#[pyo3(signature = (degree, knots, params, data_tangent, w = None, *, factors = None))]
pub(crate) fn least_squares_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    data_tangent: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    factors: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let degree = degree.count("degree")?;
    let map = least_squares_map(degree, knots, params, w, factors)?;
    let len = Some(map.n_ctrl());
    map_points(py, data_tangent, "data_tangent", len, |v, d| map.jvp(v, d))
}

/// Reverse-mode derivative of the least-squares fit with respect to the data: the data
/// cotangent `W B (BᵀWB)⁻¹ @ control_cotangent` (`(len(params), dim)`, or 1-D).
#[pyfunction]
#[pyo3(signature = (degree, knots, params, control_cotangent, w = None, *, factors = None))]
pub(crate) fn least_squares_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    control_cotangent: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    factors: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let degree = degree.count("degree")?;
    let map = least_squares_map(degree, knots, params, w, factors)?;
    let len = Some(map.n_data());
    map_points(py, control_cotangent, "control_cotangent", len, |v, d| {
        map.vjp(v, d)
    })
}

/// The factored smoothing map of the parameters `x` with weights `w` for `lam > 0`, or the map
/// `factors` of the same fit already factored (`smoothing_values_and_factors`).
fn smoothing_map(
    x: &Bound<'_, PyAny>,
    lam: f64,
    w: Option<&Bound<'_, PyAny>>,
    factors: Option<&Bound<'_, PyAny>>,
) -> PyResult<SmoothingMap> {
    let xs = vec1(x, "x")?;
    let w = weights_arg(w)?;
    match factors_arg(factors)? {
        Some(f) => SmoothingMap::from_flat(&f, xs.len()),
        None => SmoothingMap::new(&xs, lam, w.as_deref()),
    }
    .map_err(lib_err)
}

/// Forward-mode derivative of the smoothing spline with a given `lam > 0` (`fit_smoothing(x, y,
/// w, lam)`) with respect to the data `y`: the control-point tangent
/// `(BᵀWB + lam Ω)⁻¹ BᵀW @ data_tangent` (`(len(x) + 2, dim)`, or 1-D), with the fit's banded
/// factorisation.
#[pyfunction]
#[pyo3(signature = (x, lam, data_tangent, w = None, *, factors = None))]
pub(crate) fn smoothing_jvp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    lam: f64,
    data_tangent: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    factors: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let map = smoothing_map(x, lam, w, factors)?;
    let len = Some(map.n_ctrl());
    map_points(py, data_tangent, "data_tangent", len, |v, d| map.jvp(v, d))
}

/// Reverse-mode derivative of the smoothing spline with respect to the data: the data
/// cotangent `W B (BᵀWB + lam Ω)⁻¹ @ control_cotangent` (`(len(x), dim)`, or 1-D).
#[pyfunction]
#[pyo3(signature = (x, lam, control_cotangent, w = None, *, factors = None))]
pub(crate) fn smoothing_vjp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    lam: f64,
    control_cotangent: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    factors: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let map = smoothing_map(x, lam, w, factors)?;
    let len = Some(map.n_data());
    map_points(py, control_cotangent, "control_cotangent", len, |v, d| {
        map.vjp(v, d)
    })
}

/// A fit's map as a dict: `first` (int64, `(m,)`), `basis` (`(m, width)`), `weights`
/// (`(m,)`) and `triangle` (`(n_ctrl, bandwidth)`, row `i` holding `R[i, i:i + bandwidth]`).
fn fit_linearization_dict(py: Python<'_>, lin: FitLinearization) -> PyResult<Bound<'_, PyDict>> {
    let m = lin.first.len();
    let d = PyDict::new(py);
    d.set_item("first", index_array(py, lin.first, &[m])?)?;
    d.set_item("basis", array(py, lin.basis, &[m, lin.width])?)?;
    d.set_item("weights", array(py, lin.weights, &[m])?)?;
    d.set_item(
        "triangle",
        array(py, lin.triangle, &[lin.n_ctrl, lin.bandwidth])?,
    )?;
    Ok(d)
}

/// The least-squares fit's map from data to control points, `(RᵀR)⁻¹ BᵀW`, as a dict of its
/// pieces: `first`, `basis` (the sparse rows of `B`), `weights` (`W`, divided by the largest)
/// and `triangle` (the banded QR's `R`, `RᵀR = BᵀWB`).
#[pyfunction]
#[pyo3(signature = (degree, knots, params, w = None))]
pub(crate) fn least_squares_linearize<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let degree = degree.count("degree")?;
    let map = least_squares_map(degree, knots, params, w, None)?;
    fit_linearization_dict(py, map.linearize())
}

/// The smoothing spline's map from data to control points, `(RᵀR)⁻¹ BᵀW` with
/// `RᵀR = BᵀWB + lam Ω`, as [`least_squares_linearize`]'s dict.
#[pyfunction]
#[pyo3(signature = (x, lam, w = None))]
pub(crate) fn smoothing_linearize<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    lam: f64,
    w: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let map = smoothing_map(x, lam, w, None)?;
    fit_linearization_dict(py, map.linearize())
}

/// The number of numbers of a smoothing spline's map of `n_data` data points of distinct
/// parameters as `lekalo.jax` keeps it between the values and their derivatives
/// (`lekalo::derivatives::SmoothingMap::flat_len`).
#[pyfunction]
pub(crate) fn smoothing_map_flat_len(n_data: IntArg) -> PyResult<usize> {
    let n = n_data.count("n_data")?;
    SmoothingMap::flat_len(n)
        .ok_or_else(|| crate::error::bad(format!("n_data: {n} data points are too many")))
}

/// The number of numbers of a least-squares fit's map of `n_data` data points and `n_ctrl`
/// control points of degree `degree` as `lekalo.jax` keeps it between the values and their
/// derivatives (`lekalo::derivatives::LeastSquaresMap::flat_len`).
#[pyfunction]
pub(crate) fn least_squares_map_flat_len(
    n_data: IntArg,
    n_ctrl: IntArg,
    degree: IntArg,
) -> PyResult<usize> {
    let (m, n) = (n_data.count("n_data")?, n_ctrl.count("n_ctrl")?);
    let degree = degree.count("degree")?;
    LeastSquaresMap::flat_len(m, n, degree).ok_or_else(|| {
        crate::error::bad(format!(
            "n_data, n_ctrl: {m} data points and {n} control points of degree {degree} are too \
             many"
        ))
    })
}

/// A fit's control points, shaped as the data `a` with its first axis the number of control
/// points, and its map as flat numbers (1-D).
fn values_and_factors_arrays<'py>(
    py: Python<'py>,
    a: &FloatArray<'py>,
    dim: usize,
    (values, flat): (Vec<f64>, Vec<f64>),
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (n, len) = (values.len() / dim.max(1), flat.len());
    Ok((
        array(py, values, &with_len(a.shape(), n))?,
        array(py, flat, &[len])?,
    ))
}

/// The control points of the least-squares fit of `points` (`(m, dim)`, or `(m,)`) at
/// `params` on `knots` with weights `w` (`fit_least_squares(points, params, knots, degree,
/// w=w)[0].control`, bit for bit; `(n_ctrl, dim)` or 1-D) and the fit's map as flat numbers
/// (`lekalo::derivatives::LeastSquaresMap::to_flat`: the rows of `B` and the triangle of the
/// same banded QR), for `least_squares_jvp` and `least_squares_vjp` with `factors=`: the
/// values and their derivatives from one factorisation.
#[pyfunction]
#[pyo3(signature = (degree, knots, params, points, w = None))]
pub(crate) fn least_squares_values_and_factors<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let t = vec1(knots, "knots")?;
    let ts = vec1(params, "params")?;
    let w = weights_arg(w)?;
    let a = floats(points, "points")?;
    let dim = dim_of(&a, "points")?;
    let q = a.data();
    let out = py
        .detach(|| {
            let fit = LeastSquaresFit::new(degree, &t, &ts, q, dim, w.as_deref())?;
            let (values, map) = fit.control_points_and_map()?;
            Ok::<_, lekalo::Error>((values, map.to_flat()))
        })
        .map_err(lib_err)?;
    values_and_factors_arrays(py, &a, dim, out)
}

/// The control points of the smoothing spline of `y` (`(m, dim)`, or `(m,)`) at `x` with
/// weights `w` for `lam > 0` (`fit_smoothing(x, y, w, lam)[0].control`, bit for bit) and the
/// fit's map as flat numbers (`lekalo::derivatives::SmoothingMap::to_flat`: the rows of `B` and
/// the same `UᵀDU` factorisation), for `smoothing_jvp` and `smoothing_vjp` with `factors=`.
#[pyfunction]
#[pyo3(signature = (x, y, lam, w = None))]
pub(crate) fn smoothing_values_and_factors<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    lam: f64,
    w: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let xs = vec1(x, "x")?;
    let w = weights_arg(w)?;
    let a = floats(y, "y")?;
    let dim = dim_of(&a, "y")?;
    let q = a.data();
    let out = py
        .detach(|| {
            let fit = SmoothingFit::new(&xs, q, dim, lam, w.as_deref())?;
            let (values, map) = fit.control_points_and_map()?;
            Ok::<_, lekalo::Error>((values, map.to_flat()))
        })
        .map_err(lib_err)?;
    values_and_factors_arrays(py, &a, dim, out)
}
