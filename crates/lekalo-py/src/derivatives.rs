//! Derivatives of evaluation for automatic differentiation (JAX, PyTorch): the JVP, VJP and
//! linearisation kernels of `lekalo::derivatives`, NumPy in and out. The pure-Python
//! `lekalo.jax` builds its differentiable functions on these.
//!
//! Curves take `(degree, knots, control, t)` as `BSplineCurve(degree, knots, control)(t)`
//! (NURBS `(degree, knots, control, weights, t)`);
//! surfaces `(degree_u, degree_v, knots_u, knots_v, control, u, v)` as `BSplineSurface`. Values
//! and tangents have the shape `t.shape + (dim,)`; cotangents of the control points the shape
//! of `control`, of the parameters the shape of `t`.
//!
//! This file holds the derivatives of evaluation (curves, NURBS, surfaces, tensor products);
//! `derivatives/fits.rs` those of the fits (interpolation, least squares, smoothing) with
//! respect to their data, `derivatives/fit_knots.rs` those of interpolation and least squares
//! with respect to the knots, and `derivatives/knots.rs` those of curve and surface evaluation with
//! respect to the knots; `derivatives/rational_nets.rs` those of NURBS surface and tensor-NURBS
//! evaluation with respect to the net, the weights and the parameters.

mod fit_knots;
mod fits;
mod knots;
mod rational_nets;

use lekalo::derivatives::CurveLinearization;
use lekalo::{BSplineCurve, NurbsCurve};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::IntArg;
use crate::convert::{array, check_size, floats, out_shape, vec1, FloatArray};
use crate::error::{bad, lib_err};
use crate::surfaces::bspline_surface_arg;

/// Registers the functions of this module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    fits::register(m)?;
    fit_knots::register(m)?;
    knots::register(m)?;
    rational_nets::register(m)?;
    m.add_function(wrap_pyfunction!(bspline_curve_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_curve_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_curve_linearize, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_curve_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_curve_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_curve_linearize, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_bspline_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_bspline_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_bspline_linearize, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_surface_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_surface_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_surface_linearize, m)?)?;
    Ok(())
}

fn curve(
    degree: usize,
    knots: &Bound<'_, PyAny>,
    control: &FloatArray<'_>,
) -> PyResult<BSplineCurve> {
    let k = vec1(knots, "knots")?;
    let p = control.points("control")?.to_owned();
    BSplineCurve::new(degree, k, p).map_err(lib_err)
}

/// An optional argument of the same shape as `like` (`like_name`).
fn same_shape<'py>(
    arg: Option<&Bound<'py, PyAny>>,
    what: &str,
    like: &[usize],
    like_name: &str,
) -> PyResult<Option<FloatArray<'py>>> {
    let Some(a) = arg.filter(|a| !a.is_none()) else {
        return Ok(None);
    };
    let a = floats(a, what)?;
    if a.shape() != like {
        return Err(bad(format!(
            "{what}: shape {:?} differs from {like_name}'s {like:?}; a tangent or cotangent has the shape of what it belongs to",
            a.shape()
        )));
    }
    Ok(Some(a))
}

/// Indices as an int64 array of the given shape.
fn index_array<'py>(
    py: Python<'py>,
    v: Vec<usize>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let v: Vec<i64> = v
        .into_iter()
        .map(|i| i64::try_from(i).unwrap_or(i64::MAX))
        .collect();
    Ok(PyArray1::from_vec(py, v)
        .reshape(shape.to_vec())?
        .into_any())
}

/// The data of an optional array.
fn data_of<'a>(a: &'a Option<FloatArray<'_>>) -> Option<&'a [f64]> {
    a.as_ref().map(FloatArray::data)
}

/// `control` and `t` as arrays, and the curve `make` builds from `control`.
fn curve_at<'py, C>(
    control: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    make: impl FnOnce(&FloatArray<'py>) -> PyResult<C>,
) -> PyResult<(FloatArray<'py>, C, FloatArray<'py>)> {
    let ca = floats(control, "control")?;
    let c = make(&ca)?;
    Ok((ca, c, floats(t, "t")?))
}

/// The values and tangent of a forward-mode derivative: two buffers of `n` numbers that `f`
/// fills with the GIL released, as arrays of `shape`.
fn values_and_tangent<'py, F>(
    py: Python<'py>,
    n: usize,
    shape: &[usize],
    f: F,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)>
where
    F: Send + FnOnce(&mut [f64], &mut [f64]) -> lekalo::Result<()>,
{
    let (mut out, mut tan) = (vec![0.0; n], vec![0.0; n]);
    py.detach(|| f(&mut out, &mut tan)).map_err(lib_err)?;
    Ok((array(py, out, shape)?, array(py, tan, shape)?))
}

/// The `cotangent` of a reverse-mode derivative, checked to have the values' `shape`; absent
/// for Python's `None` (the callers then pass no numbers, which the library refuses by their
/// length).
fn cotangent_arg<'py>(
    cotangent: &Bound<'py, PyAny>,
    shape: &[usize],
) -> PyResult<Option<FloatArray<'py>>> {
    same_shape(Some(cotangent), "cotangent", shape, "the values")
}

/// Forward-mode derivative of B-spline curve evaluation: returns `(values, tangent)` with
/// `values = C(t)` (bit-for-bit `BSplineCurve.evaluate_batch`'s de Boor evaluation) and
/// `tangent = B(t) @ control_tangent + C'(t) * t_tangent` (either tangent may be `None`).
#[pyfunction]
#[pyo3(signature = (degree, knots, control, t, control_tangent = None, t_tangent = None))]
pub(crate) fn bspline_curve_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    control_tangent: Option<&Bound<'py, PyAny>>,
    t_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let (ca, c, ta) = curve_at(control, t, |ca| curve(degree, knots, ca))?;
    let n = check_size("t", &[ta.data().len(), c.dim()])?;
    let dc = same_shape(control_tangent, "control_tangent", ca.shape(), "control")?;
    let dt = same_shape(t_tangent, "t_tangent", ta.shape(), "t")?;
    let (ts, dc, dt) = (ta.data(), data_of(&dc), data_of(&dt));
    values_and_tangent(py, n, &out_shape(&ta, &[c.dim()]), |out, tan| {
        c.eval_batch_jvp(ts, dc, dt, out, tan)
    })
}

/// Reverse-mode derivative of B-spline curve evaluation: for `cotangent` of shape
/// `t.shape + (dim,)`, returns `(control_cotangent, t_cotangent)` =
/// `(B(t).T @ cotangent, sum(cotangent * C'(t), axis=-1))`.
#[pyfunction]
#[pyo3(signature = (degree, knots, control, t, cotangent))]
pub(crate) fn bspline_curve_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let (ca, c, ta) = curve_at(control, t, |ca| curve(degree, knots, ca))?;
    let ga = cotangent_arg(cotangent, &out_shape(&ta, &[c.dim()]))?;
    let g = data_of(&ga).unwrap_or(&[]);
    let (mut gc, mut gt) = (vec![0.0; ca.data().len()], vec![0.0; ta.data().len()]);
    let ts = ta.data();
    py.detach(|| c.eval_batch_vjp(ts, g, Some(&mut gc), Some(&mut gt)))
        .map_err(lib_err)?;
    Ok((array(py, gc, ca.shape())?, array(py, gt, ta.shape())?))
}

/// The linearisation of B-spline curve evaluation at `t`: a dict with `values` and
/// `derivatives` (`C(t)`, `C'(t)`, shape `t.shape + (dim,)`), `first` (int64, `t.shape`: the
/// first control point with a non-zero basis function) and `basis` (`t.shape + (degree + 1,)`:
/// those basis functions), so that `C(t) = sum(basis[..., k, None] * control[first + k])`.
#[pyfunction]
#[pyo3(signature = (degree, knots, control, t))]
pub(crate) fn bspline_curve_linearize<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let degree = degree.count("degree")?;
    let (_, c, ta) = curve_at(control, t, |ca| curve(degree, knots, ca))?;
    let ts = ta.data();
    let lin = py.detach(|| c.eval_batch_linearize(ts)).map_err(lib_err)?;
    linearization_dict(py, lin, &ta, c.dim(), degree)
}

/// A curve's linearisation (B-spline or NURBS) as the dict of NumPy arrays the Python side
/// reads: `values`, `derivatives` (`t.shape + (dim,)`), `first` (`t.shape`), `basis`
/// (`t.shape + (degree + 1,)`).
fn linearization_dict<'py>(
    py: Python<'py>,
    lin: CurveLinearization,
    ta: &FloatArray<'_>,
    dim: usize,
    degree: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let pts = out_shape(ta, &[dim]);
    d.set_item("values", array(py, lin.values, &pts)?)?;
    d.set_item("derivatives", array(py, lin.derivatives, &pts)?)?;
    d.set_item("first", index_array(py, lin.first, ta.shape())?)?;
    d.set_item(
        "basis",
        array(py, lin.basis, &out_shape(ta, &[degree + 1]))?,
    )?;
    Ok(d)
}

fn nurbs(
    degree: usize,
    knots: &Bound<'_, PyAny>,
    control: &FloatArray<'_>,
    weights: &Bound<'_, PyAny>,
) -> PyResult<NurbsCurve> {
    let k = vec1(knots, "knots")?;
    let p = control.points("control")?.to_owned();
    let w = vec1(weights, "weights")?;
    NurbsCurve::new(degree, k, p, w).map_err(lib_err)
}

/// Forward-mode derivative of NURBS curve evaluation: returns `(values, tangent)` with
/// `tangent = R(t) @ control_tangent + ∂C/∂w @ weights_tangent + C'(t) * t_tangent` (any
/// tangent may be `None`; `R` is the rational basis).
#[pyfunction]
#[pyo3(signature = (degree, knots, control, weights, t, control_tangent = None,
                    weights_tangent = None, t_tangent = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn nurbs_curve_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    control_tangent: Option<&Bound<'py, PyAny>>,
    weights_tangent: Option<&Bound<'py, PyAny>>,
    t_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let (ca, c, ta) = curve_at(control, t, |ca| nurbs(degree, knots, ca, weights))?;
    let n = check_size("t", &[ta.data().len(), c.dim()])?;
    let w_shape = [c.weights().len()];
    let dc = same_shape(control_tangent, "control_tangent", ca.shape(), "control")?;
    let dw = same_shape(weights_tangent, "weights_tangent", &w_shape, "weights")?;
    let dt = same_shape(t_tangent, "t_tangent", ta.shape(), "t")?;
    let (ts, dc, dw, dt) = (ta.data(), data_of(&dc), data_of(&dw), data_of(&dt));
    values_and_tangent(py, n, &out_shape(&ta, &[c.dim()]), |out, tan| {
        c.eval_batch_jvp(ts, dc, dw, dt, out, tan)
    })
}

/// Reverse-mode derivative of NURBS curve evaluation: for `cotangent` of shape
/// `t.shape + (dim,)`, returns `(control_cotangent, weights_cotangent, t_cotangent)`.
#[pyfunction]
#[pyo3(signature = (degree, knots, control, weights, t, cotangent))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn nurbs_curve_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let (ca, c, ta) = curve_at(control, t, |ca| nurbs(degree, knots, ca, weights))?;
    let ga = cotangent_arg(cotangent, &out_shape(&ta, &[c.dim()]))?;
    let g = data_of(&ga).unwrap_or(&[]);
    let n_ctrl = c.weights().len();
    let (mut gc, mut gw) = (vec![0.0; ca.data().len()], vec![0.0; n_ctrl]);
    let mut gt = vec![0.0; ta.data().len()];
    let ts = ta.data();
    py.detach(|| c.eval_batch_vjp(ts, g, Some(&mut gc), Some(&mut gw), Some(&mut gt)))
        .map_err(lib_err)?;
    Ok((
        array(py, gc, ca.shape())?,
        array(py, gw, &[n_ctrl])?,
        array(py, gt, ta.shape())?,
    ))
}

/// The linearisation of NURBS curve evaluation at `t`: a dict with `values`, `derivatives`,
/// `first` (int64) and `basis` (the rational basis `R_j = N_j w_j / W`,
/// `t.shape + (degree + 1,)`); `∂C/∂w_j = R_j (P_j − C) / w_j`.
#[pyfunction]
#[pyo3(signature = (degree, knots, control, weights, t))]
pub(crate) fn nurbs_curve_linearize<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let degree = degree.count("degree")?;
    let (_, c, ta) = curve_at(control, t, |ca| nurbs(degree, knots, ca, weights))?;
    let ts = ta.data();
    let lin = py.detach(|| c.eval_batch_linearize(ts)).map_err(lib_err)?;
    linearization_dict(py, lin, &ta, c.dim(), degree)
}

/// `(u, v)` of one shape as pairs, and that shape.
fn pairs(u: &Bound<'_, PyAny>, v: &Bound<'_, PyAny>) -> PyResult<(Vec<[f64; 2]>, Vec<usize>)> {
    let (ua, pairs) = crate::convert::uv_args(u, v)?;
    Ok((pairs, ua.shape().to_vec()))
}

/// Forward-mode derivative of B-spline surface evaluation at `(u, v)` (arrays of one shape):
/// returns `(values, tangent)`, `tangent = Σ N_k(u) N_l(v) control_tangent[k, l] + S_u(u, v)
/// u_tangent + S_v(u, v) v_tangent` (any tangent may be `None`).
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, u, v, control_tangent = None,
                    u_tangent = None, v_tangent = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn bspline_surface_jvp<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    control_tangent: Option<&Bound<'py, PyAny>>,
    u_tangent: Option<&Bound<'py, PyAny>>,
    v_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree_u = degree_u.count("degree_u")?;
    let degree_v = degree_v.count("degree_v")?;
    let s = bspline_surface_arg((degree_u, degree_v), knots_u, knots_v, control)?;
    let (uv, shape) = pairs(u, v)?;
    let dim = s.dim();
    let n = check_size("u", &[uv.len(), dim])?;
    let net_shape = floats(control, "control")?.shape().to_vec();
    let dc = same_shape(control_tangent, "control_tangent", &net_shape, "control")?;
    let du = same_shape(u_tangent, "u_tangent", &shape, "u")?;
    let dv = same_shape(v_tangent, "v_tangent", &shape, "v")?;
    let duv: Option<Vec<[f64; 2]>> = if du.is_some() || dv.is_some() {
        let get = |a: &Option<FloatArray<'_>>, i: usize| a.as_ref().map_or(0.0, |a| a.data()[i]);
        Some((0..uv.len()).map(|i| [get(&du, i), get(&dv, i)]).collect())
    } else {
        None
    };
    let (dc, duv) = (data_of(&dc), duv.as_deref());
    values_and_tangent(py, n, &[shape.as_slice(), &[dim]].concat(), |out, tan| {
        s.eval_batch_jvp(&uv, dc, duv, out, tan)
    })
}

/// Reverse-mode derivative of B-spline surface evaluation: for `cotangent` of shape
/// `u.shape + (dim,)`, returns `(control_cotangent, u_cotangent, v_cotangent)`.
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, u, v, cotangent))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn bspline_surface_vjp<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree_u = degree_u.count("degree_u")?;
    let degree_v = degree_v.count("degree_v")?;
    let s = bspline_surface_arg((degree_u, degree_v), knots_u, knots_v, control)?;
    let (uv, shape) = pairs(u, v)?;
    let ga = cotangent_arg(cotangent, &[shape.as_slice(), &[s.dim()]].concat())?;
    let g = data_of(&ga).unwrap_or(&[]);
    let mut gc = vec![0.0; s.control_points().as_slice().len()];
    let mut guv = vec![[0.0; 2]; uv.len()];
    py.detach(|| s.eval_batch_vjp(&uv, g, Some(&mut gc), Some(&mut guv)))
        .map_err(lib_err)?;
    let (gu, gv): (Vec<f64>, Vec<f64>) = guv.into_iter().map(|[a, b]| (a, b)).unzip();
    let (nu, nv) = s.net_size();
    Ok((
        array(py, gc, &[nu, nv, s.dim()])?,
        array(py, gu, &shape)?,
        array(py, gv, &shape)?,
    ))
}

/// The linearisation of B-spline surface evaluation at `(u, v)`: a dict with `values`,
/// `derivatives_u`, `derivatives_v` (`u.shape + (dim,)`), `first_u`, `first_v` (int64,
/// `u.shape`) and `basis_u`, `basis_v` (`u.shape + (degree + 1,)`), so that
/// `S = Σ_k Σ_l basis_u[..., k] basis_v[..., l] control[first_u + k, first_v + l]`.
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, u, v))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn bspline_surface_linearize<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let degree_u = degree_u.count("degree_u")?;
    let degree_v = degree_v.count("degree_v")?;
    let s = bspline_surface_arg((degree_u, degree_v), knots_u, knots_v, control)?;
    let (uv, shape) = pairs(u, v)?;
    let lin = py.detach(|| s.eval_batch_linearize(&uv)).map_err(lib_err)?;
    let tail = |k: usize| {
        let mut s = shape.clone();
        s.push(k);
        s
    };
    let d = PyDict::new(py);
    let pts = tail(s.dim());
    d.set_item("values", array(py, lin.values, &pts)?)?;
    d.set_item("derivatives_u", array(py, lin.derivatives_u, &pts)?)?;
    d.set_item("derivatives_v", array(py, lin.derivatives_v, &pts)?)?;
    d.set_item("first_u", index_array(py, lin.first_u, &shape)?)?;
    d.set_item("first_v", index_array(py, lin.first_v, &shape)?)?;
    d.set_item("basis_u", array(py, lin.basis_u, &tail(degree_u + 1))?)?;
    d.set_item("basis_v", array(py, lin.basis_v, &tail(degree_v + 1))?)?;
    Ok(d)
}

/// A tensor spline `TensorBSpline(t, c, k)`, its trailing axes, the points `x` (`(..., N)`)
/// and their leading shape.
fn tensor_points<'py>(
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
) -> PyResult<(
    lekalo::TensorBSpline,
    Vec<usize>,
    FloatArray<'py>,
    Vec<usize>,
)> {
    let (s, trailing) = crate::tensor::tensor_arg(t, c, k)?;
    let (xa, lead) = points_of(x, s.n_vars(), s.dim())?;
    Ok((s, trailing, xa, lead))
}

/// The points `x` (`(..., N)`) of a spline in `N` variables with values of `dim` numbers, and
/// their leading shape (the values' count checked against the size limit).
fn points_of<'py>(
    x: &Bound<'py, PyAny>,
    n: usize,
    dim: usize,
) -> PyResult<(FloatArray<'py>, Vec<usize>)> {
    let xa = crate::tensor::points_arg(x, n)?;
    let shape = xa.shape();
    let lead = shape[..shape.len() - 1].to_vec();
    check_size("x", &[lead.iter().product(), dim])?;
    Ok((xa, lead))
}

/// Forward-mode derivative of tensor-spline evaluation `TensorBSpline(t, c, k)(x)` at the
/// points `x` (`(..., N)`): returns `(values, tangent)`, each `x.shape[:-1] + trailing`, with
/// `tangent = Σ_k Π_a N_{k_a}(x_a) c_tangent[k] + Σ_a ∂S/∂x_a x_tangent[..., a]` (either
/// tangent may be `None`); the values are bit-for-bit the evaluation's.
#[pyfunction]
#[pyo3(signature = (t, c, k, x, c_tangent = None, x_tangent = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn tensor_bspline_jvp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    c_tangent: Option<&Bound<'py, PyAny>>,
    x_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (s, trailing, xa, lead) = tensor_points(t, c, k, x)?;
    let c_shape = floats(c, "c")?.shape().to_vec();
    let dc = same_shape(c_tangent, "c_tangent", &c_shape, "c")?;
    let dx = same_shape(x_tangent, "x_tangent", xa.shape(), "x")?;
    let len = lead.iter().product::<usize>() * s.dim();
    let (xs, dc, dx) = (xa.data(), data_of(&dc), data_of(&dx));
    values_and_tangent(
        py,
        len,
        &[lead.as_slice(), &trailing].concat(),
        |out, tan| s.eval_batch_jvp(xs, dc, dx, out, tan),
    )
}

/// Reverse-mode derivative of tensor-spline evaluation: for `cotangent` of shape
/// `x.shape[:-1] + trailing`, returns `(c_cotangent, x_cotangent)`, shaped as `c` and `x`.
#[pyfunction]
#[pyo3(signature = (t, c, k, x, cotangent))]
pub(crate) fn tensor_bspline_vjp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (s, trailing, xa, lead) = tensor_points(t, c, k, x)?;
    let c_shape = floats(c, "c")?.shape().to_vec();
    let want = [lead.as_slice(), &trailing].concat();
    let g = floats(cotangent, "cotangent")?;
    if g.shape() != want.as_slice() {
        return Err(bad(format!(
            "cotangent: shape {:?} differs from the values' {want:?} (x.shape[:-1] + the \
             coefficients' trailing axes)",
            g.shape()
        )));
    }
    let (mut gc, mut gx) = (
        vec![0.0; s.control_points().as_slice().len()],
        vec![0.0; xa.data().len()],
    );
    let (xs, gs) = (xa.data(), g.data());
    py.detach(|| s.eval_batch_vjp(xs, gs, Some(&mut gc), Some(&mut gx)))
        .map_err(lib_err)?;
    Ok((array(py, gc, &c_shape)?, array(py, gx, xa.shape())?))
}

/// The linearisation of tensor-spline evaluation at `x`: a dict with `values`
/// (`x.shape[:-1] + trailing`), `partials` (`x.shape[:-1] + (N,) + trailing`, `∂S/∂x_a`),
/// `first` (int64, `x.shape`: the first net index of every direction) and `basis`
/// (`x.shape[:-1] + (Σ_a (k_a + 1),)`: the basis vectors of the directions one after the other).
#[pyfunction]
#[pyo3(signature = (t, c, k, x))]
pub(crate) fn tensor_bspline_linearize<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let (s, trailing, xa, lead) = tensor_points(t, c, k, x)?;
    let xs = xa.data();
    let lin = py.detach(|| s.eval_batch_linearize(xs)).map_err(lib_err)?;
    let n = s.n_vars();
    let width: usize = s.degrees().iter().map(|p| p + 1).sum();
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
            &[lead.as_slice(), &[n], &trailing].concat(),
        )?,
    )?;
    d.set_item("first", index_array(py, lin.first, xa.shape())?)?;
    d.set_item(
        "basis",
        array(py, lin.basis, &[lead.as_slice(), &[width]].concat())?,
    )?;
    Ok(d)
}
