//! The derivatives of B-spline curve and surface evaluation with respect to the knots
//! (`lekalo::BSplineCurve::eval_batch_knot_jvp` and its twins, `docs/theory/derivatives.md`,
//! "Knots"), NumPy in and out, with the arguments of the coefficient derivatives beside them.

use pyo3::prelude::*;

use super::{cotangent_arg, curve, curve_at, data_of, pairs, same_shape, values_and_tangent};
use crate::convert::{array, check_size, floats, out_shape, IntArg};
use crate::error::lib_err;
use crate::surfaces::bspline_surface_arg;

/// Registers the functions of this module.
pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(bspline_curve_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_curve_knot_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_surface_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_surface_knot_vjp, m)?)?;
    Ok(())
}

/// The knots as a float array (for its shape; the curve or surface reads them itself).
fn knots_shape(knots: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<usize>> {
    Ok(floats(knots, what)?.shape().to_vec())
}

/// Forward-mode derivative of B-spline curve evaluation with respect to the knots: returns
/// `(values, tangent)`, `tangent = Σ_k knots_tangent[k] ∂C(t)/∂τ_k` (the interior knots only;
/// the `degree + 1` first and last are held fixed).
#[pyfunction]
#[pyo3(signature = (degree, knots, control, t, knots_tangent))]
pub(crate) fn bspline_curve_knot_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    knots_tangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let (_, c, ta) = curve_at(control, t, |ca| curve(degree, knots, ca))?;
    let n = check_size("t", &[ta.data().len(), c.dim()])?;
    let shape = knots_shape(knots, "knots")?;
    let dk = same_shape(Some(knots_tangent), "knots_tangent", &shape, "knots")?;
    let (ts, dk) = (ta.data(), data_of(&dk).unwrap_or(&[]));
    values_and_tangent(py, n, &out_shape(&ta, &[c.dim()]), |out, tan| {
        c.eval_batch_knot_jvp(ts, dk, out, tan)
    })
}

/// Reverse-mode derivative of B-spline curve evaluation with respect to the knots: for
/// `cotangent` of shape `t.shape + (dim,)`, returns the knots' cotangent
/// `Σ_i cotangent[i] · ∂C(t_i)/∂τ_k` (zero for the `degree + 1` first and last knots).
#[pyfunction]
#[pyo3(signature = (degree, knots, control, t, cotangent))]
pub(crate) fn bspline_curve_knot_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let degree = degree.count("degree")?;
    let (_, c, ta) = curve_at(control, t, |ca| curve(degree, knots, ca))?;
    let ga = cotangent_arg(cotangent, &out_shape(&ta, &[c.dim()]))?;
    let g = data_of(&ga).unwrap_or(&[]);
    let mut gk = vec![0.0; c.knots().len()];
    let ts = ta.data();
    py.detach(|| c.eval_batch_knot_vjp(ts, g, &mut gk))
        .map_err(lib_err)?;
    array(py, gk, &knots_shape(knots, "knots")?)
}

/// Forward-mode derivative of B-spline surface evaluation at `(u, v)` with respect to the knots
/// of each direction: returns `(values, tangent)`, `tangent = Σ_k knots_u_tangent[k] ∂S/∂τᵘ_k +
/// Σ_l knots_v_tangent[l] ∂S/∂τᵛ_l` (either tangent may be `None`; each direction's
/// `degree + 1` first and last knots are held fixed).
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, u, v, knots_u_tangent = None,
                    knots_v_tangent = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn bspline_surface_knot_jvp<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    knots_u_tangent: Option<&Bound<'py, PyAny>>,
    knots_v_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree_u = degree_u.count("degree_u")?;
    let degree_v = degree_v.count("degree_v")?;
    let s = bspline_surface_arg((degree_u, degree_v), knots_u, knots_v, control)?;
    let (uv, shape) = pairs(u, v)?;
    let dim = s.dim();
    let n = check_size("u", &[uv.len(), dim])?;
    let (su, sv) = (
        knots_shape(knots_u, "knots_u")?,
        knots_shape(knots_v, "knots_v")?,
    );
    let du = same_shape(knots_u_tangent, "knots_u_tangent", &su, "knots_u")?;
    let dv = same_shape(knots_v_tangent, "knots_v_tangent", &sv, "knots_v")?;
    let (du, dv) = (data_of(&du), data_of(&dv));
    values_and_tangent(py, n, &[shape.as_slice(), &[dim]].concat(), |out, tan| {
        s.eval_batch_knot_jvp(&uv, du, dv, out, tan)
    })
}

/// Reverse-mode derivative of B-spline surface evaluation with respect to the knots: for
/// `cotangent` of shape `u.shape + (dim,)`, returns `(knots_u_cotangent, knots_v_cotangent)`.
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, u, v, cotangent))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn bspline_surface_knot_vjp<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree_u = degree_u.count("degree_u")?;
    let degree_v = degree_v.count("degree_v")?;
    let s = bspline_surface_arg((degree_u, degree_v), knots_u, knots_v, control)?;
    let (uv, shape) = pairs(u, v)?;
    let ga = cotangent_arg(cotangent, &[shape.as_slice(), &[s.dim()]].concat())?;
    let g = data_of(&ga).unwrap_or(&[]);
    let (mut gu, mut gv) = (vec![0.0; s.knots_u().len()], vec![0.0; s.knots_v().len()]);
    py.detach(|| s.eval_batch_knot_vjp(&uv, g, Some(&mut gu), Some(&mut gv)))
        .map_err(lib_err)?;
    Ok((
        array(py, gu, &knots_shape(knots_u, "knots_u")?)?,
        array(py, gv, &knots_shape(knots_v, "knots_v")?)?,
    ))
}
