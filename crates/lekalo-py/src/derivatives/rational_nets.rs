//! The derivatives of NURBS surface and tensor-NURBS evaluation with respect to the control
//! net, the weights and the parameters (`lekalo::NurbsSurface::eval_batch_jvp`,
//! `lekalo::TensorNurbs::eval_batch_jvp` and their VJPs, `docs/theory/derivatives.md`, "NURBS
//! surfaces and N-variate NURBS"), NumPy in and out, with the arguments of the B-spline
//! kernels and of the knot derivatives beside them: surfaces
//! `(degree_u, degree_v, knots_u, knots_v, control, weights, u, v)`, tensor splines
//! `(t, c, k, w, x)` as `TensorNurbs(t, c, k, w)(x)`.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{
    cotangent_arg, data_of, index_array, pairs, points_of, same_shape, values_and_tangent,
};
use crate::convert::{array, check_size, floats, IntArg};
use crate::error::lib_err;
use crate::surfaces::nurbs_surface_arg;

/// Registers the functions of this module.
pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(nurbs_surface_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_surface_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_surface_linearize, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_nurbs_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_nurbs_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_nurbs_linearize, m)?)?;
    Ok(())
}

/// Forward-mode derivative of NURBS surface evaluation at `(u, v)` (arrays of one shape):
/// returns `(values, tangent)`, `tangent = Σ R_kl(u, v) control_tangent[k, l] + Σ N_k M_l
/// (P_kl − S) / W weights_tangent[k, l] + S_u u_tangent + S_v v_tangent` (any tangent may be
/// `None`; `R` is the rational basis); the values are bit-for-bit `NurbsSurface`'s.
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, weights, u, v,
                    control_tangent = None, weights_tangent = None, u_tangent = None,
                    v_tangent = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn nurbs_surface_jvp<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    control_tangent: Option<&Bound<'py, PyAny>>,
    weights_tangent: Option<&Bound<'py, PyAny>>,
    u_tangent: Option<&Bound<'py, PyAny>>,
    v_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degrees = (degree_u.count("degree_u")?, degree_v.count("degree_v")?);
    let s = nurbs_surface_arg(degrees, knots_u, knots_v, control, weights)?;
    let (uv, shape) = pairs(u, v)?;
    let dim = s.dim();
    let n = check_size("u", &[uv.len(), dim])?;
    let net_shape = floats(control, "control")?.shape().to_vec();
    let w_shape = floats(weights, "weights")?.shape().to_vec();
    let dc = same_shape(control_tangent, "control_tangent", &net_shape, "control")?;
    let dw = same_shape(weights_tangent, "weights_tangent", &w_shape, "weights")?;
    let du = same_shape(u_tangent, "u_tangent", &shape, "u")?;
    let dv = same_shape(v_tangent, "v_tangent", &shape, "v")?;
    let duv: Option<Vec<[f64; 2]>> = if du.is_some() || dv.is_some() {
        let get = |a: &Option<_>, i: usize| data_of(a).map_or(0.0, |a| a[i]);
        Some((0..uv.len()).map(|i| [get(&du, i), get(&dv, i)]).collect())
    } else {
        None
    };
    let (dc, dw, duv) = (data_of(&dc), data_of(&dw), duv.as_deref());
    values_and_tangent(py, n, &[shape.as_slice(), &[dim]].concat(), |out, tan| {
        s.eval_batch_jvp(&uv, dc, dw, duv, out, tan)
    })
}

/// Reverse-mode derivative of NURBS surface evaluation: for `cotangent` of shape
/// `u.shape + (dim,)`, returns `(control_cotangent, weights_cotangent, u_cotangent,
/// v_cotangent)`, shaped as `control` (`(nu, nv, dim)`), `weights`, `u` and `v`.
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, weights, u, v, cotangent))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub(crate) fn nurbs_surface_vjp<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
)> {
    let degrees = (degree_u.count("degree_u")?, degree_v.count("degree_v")?);
    let s = nurbs_surface_arg(degrees, knots_u, knots_v, control, weights)?;
    let (uv, shape) = pairs(u, v)?;
    let ga = cotangent_arg(cotangent, &[shape.as_slice(), &[s.dim()]].concat())?;
    let g = data_of(&ga).unwrap_or(&[]);
    let (nu, nv) = s.net_size();
    let mut gc = vec![0.0; nu * nv * s.dim()];
    let mut gw = vec![0.0; nu * nv];
    let mut guv = vec![[0.0; 2]; uv.len()];
    py.detach(|| s.eval_batch_vjp(&uv, g, Some(&mut gc), Some(&mut gw), Some(&mut guv)))
        .map_err(lib_err)?;
    let (gu, gv): (Vec<f64>, Vec<f64>) = guv.into_iter().map(|[a, b]| (a, b)).unzip();
    let w_shape = floats(weights, "weights")?.shape().to_vec();
    Ok((
        array(py, gc, &[nu, nv, s.dim()])?,
        array(py, gw, &w_shape)?,
        array(py, gu, &shape)?,
        array(py, gv, &shape)?,
    ))
}

/// Forward-mode derivative of `TensorNurbs(t, c, k, w)(x)` at the points `x` (`(..., N)`):
/// returns `(values, tangent)`, each `x.shape[:-1] + trailing`, with `tangent = Σ_k R_k(x)
/// c_tangent[k] + Σ_k B_k(x) (c_k − S) / W w_tangent[k] + Σ_a ∂S/∂x_a x_tangent[..., a]` (any
/// tangent may be `None`; `R_k = B_k w_k / W` the rational basis); the values are bit-for-bit
/// the evaluation's.
#[pyfunction]
#[pyo3(signature = (t, c, k, w, x, c_tangent = None, w_tangent = None, x_tangent = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn tensor_nurbs_jvp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    w: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    c_tangent: Option<&Bound<'py, PyAny>>,
    w_tangent: Option<&Bound<'py, PyAny>>,
    x_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (s, trailing) = crate::tensor_nurbs::tensor_nurbs_arg(t, c, k, w)?;
    let (xa, lead) = points_of(x, s.n_vars(), s.dim())?;
    let c_shape = floats(c, "c")?.shape().to_vec();
    let dc = same_shape(c_tangent, "c_tangent", &c_shape, "c")?;
    let dw = same_shape(w_tangent, "w_tangent", s.shape(), "w")?;
    let dx = same_shape(x_tangent, "x_tangent", xa.shape(), "x")?;
    let len = lead.iter().product::<usize>() * s.dim();
    let (xs, dc, dw, dx) = (xa.data(), data_of(&dc), data_of(&dw), data_of(&dx));
    values_and_tangent(
        py,
        len,
        &[lead.as_slice(), &trailing].concat(),
        |out, tan| s.eval_batch_jvp(xs, dc, dw, dx, out, tan),
    )
}

/// Reverse-mode derivative of `TensorNurbs(t, c, k, w)(x)`: for `cotangent` of shape
/// `x.shape[:-1] + trailing`, returns `(c_cotangent, w_cotangent, x_cotangent)`, shaped as
/// `c`, `w` and `x`.
#[pyfunction]
#[pyo3(signature = (t, c, k, w, x, cotangent))]
pub(crate) fn tensor_nurbs_vjp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    w: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (s, trailing) = crate::tensor_nurbs::tensor_nurbs_arg(t, c, k, w)?;
    let (xa, lead) = points_of(x, s.n_vars(), s.dim())?;
    let want = [lead.as_slice(), &trailing].concat();
    let ga = same_shape(Some(cotangent), "cotangent", &want, "the values")?;
    let g = data_of(&ga).unwrap_or(&[]);
    let c_shape = floats(c, "c")?.shape().to_vec();
    let n_net = s.weights().len();
    let (mut gc, mut gw) = (vec![0.0; n_net * s.dim()], vec![0.0; n_net]);
    let mut gx = vec![0.0; xa.data().len()];
    let xs = xa.data();
    py.detach(|| s.eval_batch_vjp(xs, g, Some(&mut gc), Some(&mut gw), Some(&mut gx)))
        .map_err(lib_err)?;
    Ok((
        array(py, gc, &c_shape)?,
        array(py, gw, s.shape())?,
        array(py, gx, xa.shape())?,
    ))
}

/// The linearisation of NURBS surface evaluation at `(u, v)`
/// (`lekalo::NurbsSurface::eval_batch_linearize`): a dict with `values`, `derivatives_u`,
/// `derivatives_v` (`u.shape + (dim,)`, the values bit-for-bit the evaluation's), `first_u`,
/// `first_v` (int64, `u.shape`) and `basis` (`u.shape + (degree_u + 1, degree_v + 1)`, the
/// rational basis `R_kl = N_k M_l w_kl / W`), so that `S = Σ_kl basis[..., k, l]
/// control[first_u + k, first_v + l]` and `∂S/∂w_kl = R_kl (P_kl − S) / w_kl`.
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, weights, u, v))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn nurbs_surface_linearize<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let degrees = (degree_u.count("degree_u")?, degree_v.count("degree_v")?);
    let s = nurbs_surface_arg(degrees, knots_u, knots_v, control, weights)?;
    let (uv, shape) = pairs(u, v)?;
    let lin = py.detach(|| s.eval_batch_linearize(&uv)).map_err(lib_err)?;
    let pts = [shape.as_slice(), &[s.dim()]].concat();
    let d = PyDict::new(py);
    d.set_item("values", array(py, lin.values, &pts)?)?;
    d.set_item("derivatives_u", array(py, lin.derivatives_u, &pts)?)?;
    d.set_item("derivatives_v", array(py, lin.derivatives_v, &pts)?)?;
    d.set_item("first_u", index_array(py, lin.first_u, &shape)?)?;
    d.set_item("first_v", index_array(py, lin.first_v, &shape)?)?;
    let block = [shape.as_slice(), &[degrees.0 + 1, degrees.1 + 1]].concat();
    d.set_item("basis", array(py, lin.basis, &block)?)?;
    Ok(d)
}

/// The linearisation of `TensorNurbs(t, c, k, w)(x)` (`lekalo::TensorNurbs::
/// eval_batch_linearize`): a dict with `values` (`x.shape[:-1] + trailing`, bit-for-bit the
/// evaluation's), `partials` (`x.shape[:-1] + (N,) + trailing`, `∂S/∂x_a`), `first` (int64,
/// `x.shape`: the first net index of every direction) and `basis` (`x.shape[:-1] + (k_1 + 1,
/// …, k_N + 1)`: the rational basis `R = B w / W` of each point's block of the net).
#[pyfunction]
#[pyo3(signature = (t, c, k, w, x))]
pub(crate) fn tensor_nurbs_linearize<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    w: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let (s, trailing) = crate::tensor_nurbs::tensor_nurbs_arg(t, c, k, w)?;
    let (xa, lead) = points_of(x, s.n_vars(), s.dim())?;
    let xs = xa.data();
    let lin = py.detach(|| s.eval_batch_linearize(xs)).map_err(lib_err)?;
    let block: Vec<usize> = s.degrees().iter().map(|p| p + 1).collect();
    let d = PyDict::new(py);
    d.set_item(
        "values",
        array(py, lin.values, &[lead.as_slice(), &trailing].concat())?,
    )?;
    d.set_item(
        "partials",
        array(
            py,
            lin.partials,
            &[lead.as_slice(), &[s.n_vars()], &trailing].concat(),
        )?,
    )?;
    d.set_item("first", index_array(py, lin.first, xa.shape())?)?;
    d.set_item(
        "basis",
        array(py, lin.basis, &[lead.as_slice(), &block].concat())?,
    )?;
    Ok(d)
}
