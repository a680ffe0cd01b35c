//! The derivatives of B-spline and NURBS curve and surface and tensor-spline evaluation
//! with respect to the knots (`lekalo::BSplineCurve::eval_batch_knot_jvp` and its twins,
//! `docs/theory/derivatives.md`, "Knots"), NumPy in and out, with the arguments of the
//! coefficient derivatives beside them.

use pyo3::prelude::*;
use pyo3::types::PyTuple;

use super::{
    cotangent_arg, curve, curve_at, data_of, nurbs, pairs, points_of, same_shape, tensor_points,
    values_and_tangent,
};
use crate::convert::{array, check_size, floats, out_shape, IntArg};
use crate::error::{bad, lib_err};
use crate::surfaces::{bspline_surface_arg, nurbs_surface_arg};

/// Registers the functions of this module.
pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(bspline_curve_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_curve_knot_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_surface_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(bspline_surface_knot_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_curve_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_curve_knot_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_surface_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(nurbs_surface_knot_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_bspline_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_bspline_knot_vjp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_nurbs_knot_jvp, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_nurbs_knot_vjp, m)?)?;
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

/// A surface whose batch evaluation has knot derivatives: the B-spline and the NURBS surface
/// (`lekalo::BSplineSurface::eval_batch_knot_jvp`, `lekalo::NurbsSurface::eval_batch_knot_jvp`
/// and their VJPs), so that one binding parses and presents for both.
trait KnotSurface: Sync {
    fn dim(&self) -> usize;
    fn knot_lens(&self) -> (usize, usize);
    fn knot_jvp(
        &self,
        uv: &[[f64; 2]],
        du: Option<&[f64]>,
        dv: Option<&[f64]>,
        out: &mut [f64],
        tan: &mut [f64],
    ) -> lekalo::Result<()>;
    fn knot_vjp(
        &self,
        uv: &[[f64; 2]],
        g: &[f64],
        gu: &mut [f64],
        gv: &mut [f64],
    ) -> lekalo::Result<()>;
}

macro_rules! knot_surface {
    ($t:ty) => {
        impl KnotSurface for $t {
            fn dim(&self) -> usize {
                <$t>::dim(self)
            }
            fn knot_lens(&self) -> (usize, usize) {
                (self.knots_u().len(), self.knots_v().len())
            }
            fn knot_jvp(
                &self,
                uv: &[[f64; 2]],
                du: Option<&[f64]>,
                dv: Option<&[f64]>,
                out: &mut [f64],
                tan: &mut [f64],
            ) -> lekalo::Result<()> {
                self.eval_batch_knot_jvp(uv, du, dv, out, tan)
            }
            fn knot_vjp(
                &self,
                uv: &[[f64; 2]],
                g: &[f64],
                gu: &mut [f64],
                gv: &mut [f64],
            ) -> lekalo::Result<()> {
                self.eval_batch_knot_vjp(uv, g, Some(gu), Some(gv))
            }
        }
    };
}
knot_surface!(lekalo::BSplineSurface);
knot_surface!(lekalo::NurbsSurface);

/// The knot JVP of a surface at `(u, v)`: the tangents checked against the knots' shapes,
/// `(values, tangent)` of shape `u.shape + (dim,)`.
fn surface_knot_jvp<'py>(
    py: Python<'py>,
    s: &impl KnotSurface,
    (knots_u, knots_v): (&Bound<'py, PyAny>, &Bound<'py, PyAny>),
    (u, v): (&Bound<'py, PyAny>, &Bound<'py, PyAny>),
    (du, dv): (Option<&Bound<'py, PyAny>>, Option<&Bound<'py, PyAny>>),
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (uv, shape) = pairs(u, v)?;
    let dim = s.dim();
    let n = check_size("u", &[uv.len(), dim])?;
    let (su, sv) = (
        knots_shape(knots_u, "knots_u")?,
        knots_shape(knots_v, "knots_v")?,
    );
    let du = same_shape(du, "knots_u_tangent", &su, "knots_u")?;
    let dv = same_shape(dv, "knots_v_tangent", &sv, "knots_v")?;
    let (du, dv) = (data_of(&du), data_of(&dv));
    values_and_tangent(py, n, &[shape.as_slice(), &[dim]].concat(), |out, tan| {
        s.knot_jvp(&uv, du, dv, out, tan)
    })
}

/// The knot VJP of a surface: `(knots_u_cotangent, knots_v_cotangent)`, shaped as the knots.
fn surface_knot_vjp<'py>(
    py: Python<'py>,
    s: &impl KnotSurface,
    (knots_u, knots_v): (&Bound<'py, PyAny>, &Bound<'py, PyAny>),
    (u, v): (&Bound<'py, PyAny>, &Bound<'py, PyAny>),
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (uv, shape) = pairs(u, v)?;
    let ga = cotangent_arg(cotangent, &[shape.as_slice(), &[s.dim()]].concat())?;
    let g = data_of(&ga).unwrap_or(&[]);
    let (lu, lv) = s.knot_lens();
    let (mut gu, mut gv) = (vec![0.0; lu], vec![0.0; lv]);
    py.detach(|| s.knot_vjp(&uv, g, &mut gu, &mut gv))
        .map_err(lib_err)?;
    Ok((
        array(py, gu, &knots_shape(knots_u, "knots_u")?)?,
        array(py, gv, &knots_shape(knots_v, "knots_v")?)?,
    ))
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
    let degrees = (degree_u.count("degree_u")?, degree_v.count("degree_v")?);
    let s = bspline_surface_arg(degrees, knots_u, knots_v, control)?;
    let tangents = (knots_u_tangent, knots_v_tangent);
    surface_knot_jvp(py, &s, (knots_u, knots_v), (u, v), tangents)
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
    let degrees = (degree_u.count("degree_u")?, degree_v.count("degree_v")?);
    let s = bspline_surface_arg(degrees, knots_u, knots_v, control)?;
    surface_knot_vjp(py, &s, (knots_u, knots_v), (u, v), cotangent)
}

/// Forward-mode derivative of NURBS curve evaluation with respect to the knots: returns
/// `(values, tangent)`, `tangent = Σ_k knots_tangent[k] ∂C(t)/∂τ_k` (the interior knots only;
/// the `degree + 1` first and last are held fixed), through the homogeneous curve and the
/// quotient rule.
#[pyfunction]
#[pyo3(signature = (degree, knots, control, weights, t, knots_tangent))]
pub(crate) fn nurbs_curve_knot_jvp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    knots_tangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.count("degree")?;
    let (_, c, ta) = curve_at(control, t, |ca| nurbs(degree, knots, ca, weights))?;
    let n = check_size("t", &[ta.data().len(), c.dim()])?;
    let shape = knots_shape(knots, "knots")?;
    let dk = same_shape(Some(knots_tangent), "knots_tangent", &shape, "knots")?;
    let (ts, dk) = (ta.data(), data_of(&dk).unwrap_or(&[]));
    values_and_tangent(py, n, &out_shape(&ta, &[c.dim()]), |out, tan| {
        c.eval_batch_knot_jvp(ts, dk, out, tan)
    })
}

/// Reverse-mode derivative of NURBS curve evaluation with respect to the knots: for
/// `cotangent` of shape `t.shape + (dim,)`, returns the knots' cotangent
/// `Σ_i cotangent[i] · ∂C(t_i)/∂τ_k` (zero for the `degree + 1` first and last knots).
#[pyfunction]
#[pyo3(signature = (degree, knots, control, weights, t, cotangent))]
pub(crate) fn nurbs_curve_knot_vjp<'py>(
    py: Python<'py>,
    degree: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let degree = degree.count("degree")?;
    let (_, c, ta) = curve_at(control, t, |ca| nurbs(degree, knots, ca, weights))?;
    let ga = cotangent_arg(cotangent, &out_shape(&ta, &[c.dim()]))?;
    let g = data_of(&ga).unwrap_or(&[]);
    let mut gk = vec![0.0; c.knots().len()];
    let ts = ta.data();
    py.detach(|| c.eval_batch_knot_vjp(ts, g, &mut gk))
        .map_err(lib_err)?;
    array(py, gk, &knots_shape(knots, "knots")?)
}

/// Forward-mode derivative of NURBS surface evaluation at `(u, v)` with respect to the knots of
/// each direction: returns `(values, tangent)` as `bspline_surface_knot_jvp` does, through the
/// homogeneous net `(w P, w)` and the quotient rule (`weights` of shape `(nu, nv)`).
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, weights, u, v,
                    knots_u_tangent = None, knots_v_tangent = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn nurbs_surface_knot_jvp<'py>(
    py: Python<'py>,
    degree_u: IntArg,
    degree_v: IntArg,
    knots_u: &Bound<'py, PyAny>,
    knots_v: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    weights: &Bound<'py, PyAny>,
    u: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    knots_u_tangent: Option<&Bound<'py, PyAny>>,
    knots_v_tangent: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degrees = (degree_u.count("degree_u")?, degree_v.count("degree_v")?);
    let s = nurbs_surface_arg(degrees, knots_u, knots_v, control, weights)?;
    let tangents = (knots_u_tangent, knots_v_tangent);
    surface_knot_jvp(py, &s, (knots_u, knots_v), (u, v), tangents)
}

/// Reverse-mode derivative of NURBS surface evaluation with respect to the knots: for
/// `cotangent` of shape `u.shape + (dim,)`, returns `(knots_u_cotangent, knots_v_cotangent)`.
#[pyfunction]
#[pyo3(signature = (degree_u, degree_v, knots_u, knots_v, control, weights, u, v, cotangent))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn nurbs_surface_knot_vjp<'py>(
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
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degrees = (degree_u.count("degree_u")?, degree_v.count("degree_v")?);
    let s = nurbs_surface_arg(degrees, knots_u, knots_v, control, weights)?;
    surface_knot_vjp(py, &s, (knots_u, knots_v), (u, v), cotangent)
}

/// The entries of a sequence with one entry a variable (`what` names it).
fn per_variable<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    n: usize,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let items: Vec<Bound<'py, PyAny>> = obj
        .try_iter()
        .map_err(|_| {
            bad(format!(
                "{what}: expected a sequence with one entry per variable"
            ))
        })?
        .collect::<PyResult<_>>()?;
    if items.len() != n {
        return Err(bad(format!(
            "{what}: {} entries for {n} variables; give one per variable",
            items.len()
        )));
    }
    Ok(items)
}

/// Forward-mode derivative of tensor-spline evaluation `TensorBSpline(t, c, k)(x)` with respect
/// to the knots of each variable: returns `(values, tangent)`, each `x.shape[:-1] + trailing`,
/// `tangent = Σ_a Σ_k t_tangent[a][k] ∂S/∂t[a][k]`; `t_tangent` has one entry a variable, an
/// array shaped as `t[a]` or `None` (that variable's knots held fixed). Each variable's
/// `k[a] + 1` first and last knots are held fixed.
#[pyfunction]
#[pyo3(signature = (t, c, k, x, t_tangent))]
pub(crate) fn tensor_bspline_knot_jvp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    t_tangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (s, trailing, xa, lead) = tensor_points(t, c, k, x)?;
    let tangents = knot_tangents(t_tangent, s.knots())?;
    let tangents: Vec<Option<&[f64]>> = tangents.iter().map(data_of).collect();
    let len = lead.iter().product::<usize>() * s.dim();
    let xs = xa.data();
    values_and_tangent(
        py,
        len,
        &[lead.as_slice(), &trailing].concat(),
        |out, tan| s.eval_batch_knot_jvp(xs, &tangents, out, tan),
    )
}

/// Reverse-mode derivative of tensor-spline evaluation with respect to the knots: for
/// `cotangent` of shape `x.shape[:-1] + trailing`, returns a tuple of the `N` knot
/// cotangents, shaped as `t[a]` (zero for each variable's `k[a] + 1` first and last knots).
#[pyfunction]
#[pyo3(signature = (t, c, k, x, cotangent))]
pub(crate) fn tensor_bspline_knot_vjp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyTuple>> {
    let (s, trailing, xa, lead) = tensor_points(t, c, k, x)?;
    let want = [lead.as_slice(), &trailing].concat();
    let ga = same_shape(Some(cotangent), "cotangent", &want, "the values")?;
    let g = data_of(&ga).unwrap_or(&[]);
    let mut gk: Vec<Vec<f64>> = s.knots().iter().map(|kv| vec![0.0; kv.len()]).collect();
    let mut bufs: Vec<Option<&mut [f64]>> = gk.iter_mut().map(|b| Some(b.as_mut_slice())).collect();
    let xs = xa.data();
    py.detach(|| s.eval_batch_knot_vjp(xs, g, &mut bufs))
        .map_err(lib_err)?;
    knot_arrays(py, gk)
}

/// The knot tangents of `t_tangent`: one entry a variable, an array shaped as that variable's
/// knots or `None`.
fn knot_tangents<'py>(
    t_tangent: &Bound<'py, PyAny>,
    knots: &[lekalo::KnotVector],
) -> PyResult<Vec<Option<crate::convert::FloatArray<'py>>>> {
    let items = per_variable(t_tangent, "t_tangent", knots.len())?;
    items
        .iter()
        .zip(knots)
        .enumerate()
        .map(|(a, (item, kv))| {
            let what = format!("t_tangent[{a}]");
            same_shape(Some(item), &what, &[kv.len()], &format!("t[{a}]"))
        })
        .collect()
}

/// The knot cotangents as a tuple of `N` arrays.
fn knot_arrays<'py>(py: Python<'py>, gk: Vec<Vec<f64>>) -> PyResult<Bound<'py, PyTuple>> {
    let arrays = gk
        .into_iter()
        .map(|b| {
            let len = b.len();
            array(py, b, &[len])
        })
        .collect::<PyResult<Vec<_>>>()?;
    PyTuple::new(py, arrays)
}

/// Forward-mode derivative of `TensorNurbs(t, c, k, w)(x)` with respect to the knots of each
/// variable: returns `(values, tangent)` as `tensor_bspline_knot_jvp` does, through the
/// homogeneous spline `(w c, w)` and the quotient rule.
#[pyfunction]
#[pyo3(signature = (t, c, k, w, x, t_tangent))]
pub(crate) fn tensor_nurbs_knot_jvp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    w: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    t_tangent: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (s, trailing) = crate::tensor_nurbs::tensor_nurbs_arg(t, c, k, w)?;
    let (xa, lead) = points_of(x, s.n_vars(), s.dim())?;
    let tangents = knot_tangents(t_tangent, s.knots())?;
    let tangents: Vec<Option<&[f64]>> = tangents.iter().map(data_of).collect();
    let len = lead.iter().product::<usize>() * s.dim();
    let xs = xa.data();
    values_and_tangent(
        py,
        len,
        &[lead.as_slice(), &trailing].concat(),
        |out, tan| s.eval_batch_knot_jvp(xs, &tangents, out, tan),
    )
}

/// Reverse-mode derivative of `TensorNurbs(t, c, k, w)(x)` with respect to the knots: for
/// `cotangent` of shape `x.shape[:-1] + trailing`, returns a tuple of the `N` knot
/// cotangents, shaped as `t[a]` (zero for each variable's `k[a] + 1` first and last knots).
#[pyfunction]
#[pyo3(signature = (t, c, k, w, x, cotangent))]
pub(crate) fn tensor_nurbs_knot_vjp<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    w: &Bound<'py, PyAny>,
    x: &Bound<'py, PyAny>,
    cotangent: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyTuple>> {
    let (s, trailing) = crate::tensor_nurbs::tensor_nurbs_arg(t, c, k, w)?;
    let (xa, lead) = points_of(x, s.n_vars(), s.dim())?;
    let want = [lead.as_slice(), &trailing].concat();
    let ga = same_shape(Some(cotangent), "cotangent", &want, "the values")?;
    let g = data_of(&ga).unwrap_or(&[]);
    let mut gk: Vec<Vec<f64>> = s.knots().iter().map(|kv| vec![0.0; kv.len()]).collect();
    let mut bufs: Vec<Option<&mut [f64]>> = gk.iter_mut().map(|b| Some(b.as_mut_slice())).collect();
    let xs = xa.data();
    py.detach(|| s.eval_batch_knot_vjp(xs, g, &mut bufs))
        .map_err(lib_err)?;
    knot_arrays(py, gk)
}
