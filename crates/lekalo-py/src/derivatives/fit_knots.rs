//! Derivatives of interpolation and of the least-squares fit with respect to the knots, NumPy
//! in and out: `Interpolant::knot_jvp` / `::knot_vjp` and `LeastSquaresFit::knot_jvp` /
//! `::knot_vjp` of `lekalo::derivatives` (the normal equations differentiated,
//! `docs/theory/derivatives.md`, "Knots of the fits"). The data, parameters and weights are
//! constants.

use lekalo::derivatives::{Interpolant, LeastSquaresFit};
use pyo3::prelude::*;

use super::fits::{dim_of, weights_arg, with_len};
use crate::convert::{array, floats, vec1, IntArg};
use crate::error::lib_err;

/// Registers the functions of this module.
pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(interpolation_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(interpolation_knot_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(least_squares_knot_vjp, m)?)?;
    Ok(())
}

/// The interpolant of `points` (`(m, dim)`, or `(m,)`) at `params` on `knots`, and the shape of
/// the points.
fn interpolant(
    degree: IntArg,
    knots: &Bound<'_, PyAny>,
    params: &Bound<'_, PyAny>,
    points: &Bound<'_, PyAny>,
) -> PyResult<(Interpolant, Vec<usize>)> {
    let degree = degree.count("degree")?;
    let (kv, ts) = (vec1(knots, "knots")?, vec1(params, "params")?);
    let q = floats(points, "points")?;
    let dim = dim_of(&q, "points")?;
    let it = Interpolant::new(degree, &kv, &ts, q.data(), dim).map_err(lib_err)?;
    Ok((it, q.shape().to_vec()))
}

/// Forward-mode derivative of interpolation with respect to the knots: returns
/// `(control, control_tangent)`, the interpolant's control points (shape of `points`) and
/// `−A⁻¹ (Ȧ P)` for `knots_tangent` (one a knot; the `degree + 1` first and last are held
/// fixed).
#[pyfunction]
#[pyo3(signature = (degree, knots, params, points, knots_tangent))]
pub(crate) fn interpolation_knot_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
    knots_tangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (it, shape) = interpolant(degree, knots, params, points)?;
    let dk = vec1(knots_tangent, "knots_tangent")?;
    let tangent = py.detach(|| it.knot_jvp(&dk)).map_err(lib_err)?;
    Ok((
        array(py, it.control_points().to_vec(), &shape)?,
        array(py, tangent, &shape)?,
    ))
}

/// Reverse-mode derivative of interpolation with respect to the knots: the knots' cotangent
/// `−J_Pᵀ (A⁻ᵀ control_cotangent)` (zero for the `degree + 1` first and last knots) for
/// `control_cotangent` of the shape of `points`.
#[pyfunction]
#[pyo3(signature = (degree, knots, params, points, control_cotangent))]
pub(crate) fn interpolation_knot_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
    control_cotangent: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let (it, _) = interpolant(degree, knots, params, points)?;
    let g = floats(control_cotangent, "control_cotangent")?;
    let g = g.data();
    let out = py.detach(|| it.knot_vjp(g)).map_err(lib_err)?;
    let len = out.len();
    array(py, out, &[len])
}

/// Forward-mode derivative of the least-squares fit (`fit_least_squares` without end or shape
/// constraints) with respect to the knots: returns `(control, control_tangent)`, the fit's
/// control points (`(n_ctrl, dim)`, or 1-D) and `−G⁻¹ (BᵀW Ḃ P + Ḃᵀ W r)` for `knots_tangent`
/// (one a knot; the `degree + 1` first and last are held fixed), `r` the residual.
#[pyfunction]
#[pyo3(signature = (degree, knots, params, points, knots_tangent, w = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn least_squares_knot_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
    knots_tangent: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let (kv, ts, w) = (
        vec1(knots, "knots")?,
        vec1(params, "params")?,
        weights_arg(w)?,
    );
    let q = floats(points, "points")?;
    let dim = dim_of(&q, "points")?;
    let dk = vec1(knots_tangent, "knots_tangent")?;
    let fit =
        LeastSquaresFit::new(degree, &kv, &ts, q.data(), dim, w.as_deref()).map_err(lib_err)?;
    let (control, tangent) = py.detach(|| fit.knot_jvp(&dk)).map_err(lib_err)?;
    let shape = with_len(q.shape(), fit.n_ctrl());
    Ok((array(py, control, &shape)?, array(py, tangent, &shape)?))
}

/// Reverse-mode derivative of the least-squares fit with respect to the knots: the knots'
/// cotangent `−J_Pᵀ (W B z) − J_zᵀ (W r)`, `z = G⁻¹ control_cotangent` (zero for the
/// `degree + 1` first and last knots), for `control_cotangent` of shape `(n_ctrl, dim)` (or 1-D).
#[pyfunction]
#[pyo3(signature = (degree, knots, params, points, control_cotangent, w = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn least_squares_knot_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
    control_cotangent: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let degree = degree.count("degree")?;
    let (kv, ts, w) = (
        vec1(knots, "knots")?,
        vec1(params, "params")?,
        weights_arg(w)?,
    );
    let q = floats(points, "points")?;
    let dim = dim_of(&q, "points")?;
    let g = floats(control_cotangent, "control_cotangent")?;
    let g = g.data();
    let fit =
        LeastSquaresFit::new(degree, &kv, &ts, q.data(), dim, w.as_deref()).map_err(lib_err)?;
    let out = py.detach(|| fit.knot_vjp(g)).map_err(lib_err)?;
    let len = out.len();
    array(py, out, &[len])
}
