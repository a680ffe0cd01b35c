//! Blending (document 001, docs/theory/blending.md): the jump polynomials `w_k`, the
//! deformation of one curve into another, blend splines through points, corner transitions.
//! Curves taken as arguments may be any lekalo curve (Bezier, B-spline, NURBS), or another
//! blend.

use std::sync::Arc;

use lekalo::{
    smooth_polyline_corners as smooth_polyline_corners_lib, ArcParametrization, BlendSpline,
    BlendSplineOptions, CircularArcs, CornerTransition, CornerWindow, Deformation, JumpPolynomial,
    LocalCurves, Parabolas, ParametricCurve, SharedCurve, SplineParameters,
};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::out_shape;
use crate::convert::IntArg;
use crate::convert::{array, check_size, filled, floats};
use crate::curves::{PyBSplineCurve, PyBezierCurve, PyNurbsCurve};
use crate::error::{bad, lib_err};

/// Adds the blending classes to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyJumpPolynomial>()?;
    m.add_class::<PyDeformation>()?;
    m.add_class::<PyBlendSpline>()?;
    m.add_class::<PyCornerTransition>()?;
    m.add_function(wrap_pyfunction!(smooth_polyline_corners, m)?)?;
    Ok(())
}

/// Any curve-like Python argument as a shared curve.
fn shared_curve(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<SharedCurve> {
    if let Ok(c) = obj.cast::<PyBezierCurve>() {
        return Ok(Arc::new(c.get().inner.clone()));
    }
    if let Ok(c) = obj.cast::<PyBSplineCurve>() {
        return Ok(Arc::new(c.get().inner.clone()));
    }
    if let Ok(c) = obj.cast::<PyNurbsCurve>() {
        return Ok(Arc::new(c.get().inner.clone()));
    }
    if let Ok(c) = obj.cast::<PyDeformation>() {
        return Ok(Arc::clone(&c.get().shared));
    }
    if let Ok(c) = obj.cast::<PyBlendSpline>() {
        return Ok(Arc::clone(&c.get().shared));
    }
    if let Ok(c) = obj.cast::<PyCornerTransition>() {
        return Ok(Arc::clone(&c.get().shared));
    }
    Err(bad(format!(
        "{what}: expected a lekalo curve (BezierCurve, BSplineCurve, NurbsCurve or a blend), got {}",
        obj.get_type().name()?
    )))
}

/// Points (`nu = 0`) or the `nu`-th derivative of a parametric curve at `t` of any shape.
fn eval_curve(
    py: Python<'_>,
    c: &(dyn ParametricCurve + Send + Sync),
    t: &Bound<'_, PyAny>,
    nu: usize,
) -> PyResult<Py<PyAny>> {
    let ta = floats(t, "t")?;
    let ts = ta.data();
    let dim = c.dim();
    let row = check_size("nu", &[nu.saturating_add(1), dim])?;
    check_size("t", &[ts.len(), dim])?;
    let out = filled(py, &out_shape(&ta, &[dim]), |out| {
        let mut scratch = vec![0.0; row];
        ts.iter()
            .zip(out.chunks_exact_mut(dim))
            .try_for_each(|(&t, o)| {
                c.eval_derivatives_into(t, nu, &mut scratch)?;
                o.copy_from_slice(&scratch[nu * dim..]);
                Ok(())
            })
    })?;
    Ok(out.unbind())
}

/// Derivatives `0..=order` at `t`: `t.shape + (order + 1, dim)`.
fn derivatives_curve(
    py: Python<'_>,
    c: &(dyn ParametricCurve + Send + Sync),
    t: &Bound<'_, PyAny>,
    order: usize,
) -> PyResult<Py<PyAny>> {
    let ta = floats(t, "t")?;
    let ts = ta.data();
    let dim = c.dim();
    let row = check_size("order", &[order.saturating_add(1), dim])?;
    check_size("t", &[ts.len(), row])?;
    let out = filled(py, &out_shape(&ta, &[order + 1, dim]), |out| {
        ts.iter()
            .zip(out.chunks_exact_mut(row))
            .try_for_each(|(&t, o)| c.eval_derivatives_into(t, order, o))
    })?;
    Ok(out.unbind())
}

/// The jump polynomial `w_k` of document 001: `w_k(0) = 0`, `w_k(1) = 1`, derivatives
/// `1 … k` zero at both ends; degree `2k + 1`.
///
/// >>> import lekalo
/// >>> w = lekalo.JumpPolynomial(2)
/// >>> float(w(0.5)[()])
/// 0.5
#[pyclass(module = "lekalo", name = "JumpPolynomial", frozen)]
pub(crate) struct PyJumpPolynomial {
    inner: JumpPolynomial,
}

#[pymethods]
impl PyJumpPolynomial {
    #[new]
    fn new(k: IntArg) -> PyResult<Self> {
        let k = k.count("k")?;
        Ok(Self {
            inner: JumpPolynomial::new(k).map_err(lib_err)?,
        })
    }

    /// `k`.
    #[getter]
    fn k(&self) -> usize {
        self.inner.k()
    }

    /// The degree `2k + 1`.
    #[getter]
    fn degree(&self) -> usize {
        self.inner.degree()
    }

    /// `w_k(u)` for `u` of any shape in `[0, 1]` (same shape out).
    fn __call__(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let ua = floats(u, "u")?;
        let us = ua.data();
        let mut out = vec![0.0; us.len()];
        py.detach(|| {
            us.iter().zip(out.iter_mut()).try_for_each(|(&u, o)| {
                *o = self.inner.eval(u)?;
                Ok(())
            })
        })
        .map_err(lib_err)?;
        Ok(array(py, out, ua.shape())?.unbind())
    }

    /// The Bernstein coefficients (rounded to float64).
    fn bernstein_coefficients(&self) -> Vec<f64> {
        self.inner.bernstein_coefficients_f64()
    }

    /// `∫_0^{1/2} w_k` (rounded to float64).
    fn integral_to_half(&self) -> f64 {
        self.inner.integral_to_half_f64()
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (usize,))> {
        Ok((py.get_type::<Self>().into_any(), (self.inner.k(),)))
    }
}

/// The methods the blended-curve classes share, written once: pickling by their constructor's
/// arguments, the domain, evaluation and derivatives through the shared `ParametricCurve`.
/// `$t` names the parameter in Python (`u`, or `s` for a blend spline).
macro_rules! blend_class {
    ($ty:ident, $t:ident, { $($extra:tt)* }) => {
        #[pymethods]
        impl $ty {
            $($extra)*

            fn __reduce__<'py>(
                &self,
                py: Python<'py>,
            ) -> (Bound<'py, PyAny>, Bound<'py, PyTuple>) {
                (py.get_type::<Self>().into_any(), self.args.bind(py).clone())
            }

            /// The parameter domain.
            #[getter]
            fn domain(&self) -> (f64, f64) {
                self.inner.domain()
            }

            /// Points at the parameters (any shape): `shape + (dim,)`; `nu > 0` gives the
            /// `nu`-th derivative.
            #[pyo3(signature = ($t, nu = IntArg::of(0)))]
            fn __call__(
                &self,
                py: Python<'_>,
                $t: &Bound<'_, PyAny>,
                nu: IntArg,
            ) -> PyResult<Py<PyAny>> {
                let nu = nu.count("nu")?;
                eval_curve(py, &*self.shared, $t, nu)
            }

            /// Derivatives `0..=order`: `shape + (order + 1, dim)`.
            fn derivatives(
                &self,
                py: Python<'_>,
                $t: &Bound<'_, PyAny>,
                order: IntArg,
            ) -> PyResult<Py<PyAny>> {
                let order = order.count("order")?;
                derivatives_curve(py, &*self.shared, $t, order)
            }
        }
    };
}

/// The deformation of `first` into `second` with continuity degree `k`:
/// `c(u) = (1 − w_{k−1}(u))·first(u) + w_{k−1}(u)·second(u)`, each curve mapped to `[0, 1]`
/// (document 001 §B.1).
#[pyclass(module = "lekalo", name = "Deformation", frozen)]
pub(crate) struct PyDeformation {
    /// The constructor's arguments, for pickling.
    args: Py<PyTuple>,
    inner: Arc<Deformation<SharedCurve, SharedCurve>>,
    shared: SharedCurve,
}

blend_class!(PyDeformation, u, {
    #[new]
    #[pyo3(signature = (first, second, continuity = IntArg::of(2)), text_signature = "(first, second, continuity=2)")]
    fn new(
        first: &Bound<'_, PyAny>,
        second: &Bound<'_, PyAny>,
        continuity: IntArg,
    ) -> PyResult<Self> {
        let continuity = continuity.count("continuity")?;
        let d = Deformation::new(
            shared_curve(first, "first")?,
            shared_curve(second, "second")?,
            continuity,
        )
        .map_err(lib_err)?;
        let inner = Arc::new(d);
        Ok(Self {
            args: PyTuple::new(
                first.py(),
                [
                    first.clone(),
                    second.clone(),
                    continuity.into_pyobject(first.py())?.into_any(),
                ],
            )?
            .unbind(),
            shared: Arc::clone(&inner) as SharedCurve,
            inner,
        })
    }

    /// The exact Bezier form when both curves are single polynomial pieces.
    fn to_bezier(&self) -> PyResult<PyBezierCurve> {
        Ok(PyBezierCurve::wrap(
            self.inner.to_bezier().map_err(lib_err)?,
        ))
    }

    /// The exact NURBS form when both curves are single (rational) Bezier pieces.
    fn to_nurbs(&self) -> PyResult<PyNurbsCurve> {
        Ok(PyNurbsCurve::wrap(self.inner.to_nurbs().map_err(lib_err)?))
    }
});

fn spline_parameters(s: &str) -> PyResult<SplineParameters> {
    match s {
        "uniform" => Ok(SplineParameters::Uniform),
        "chord" | "chord_length" => Ok(SplineParameters::ChordLength),
        "centripetal" => Ok(SplineParameters::Centripetal),
        _ => Err(bad(format!(
            "parameters: unknown value {s:?}; use 'uniform', 'chord' or 'centripetal'"
        ))),
    }
}

/// A `C^k` (or `G^k`) spline through points blending local curves through each three
/// consecutive points (document 001 §B.3): `local` is `'parabolas'` or `'arcs'` (circular
/// arcs, `arcs` = `'uniform_angle'`, `'rational_quadratic'` or `'global_angle'`).
///
/// >>> import numpy as np, lekalo
/// >>> s = lekalo.BlendSpline([[0, 0], [1, 1], [2, 0], [3, 1]], local="arcs", continuity=2)
/// >>> np.allclose(s(s.domain[0]), [0, 0], rtol=0, atol=1e-12)  # the first point, to rounding
/// True
#[pyclass(module = "lekalo", name = "BlendSpline", frozen)]
pub(crate) struct PyBlendSpline {
    /// The constructor's arguments, for pickling.
    args: Py<PyTuple>,
    inner: Arc<BlendSpline>,
    shared: SharedCurve,
}

blend_class!(PyBlendSpline, s, {
    #[new]
    #[pyo3(signature = (points, local = "parabolas", continuity = IntArg::of(2), closed = false,
                        parameters = "uniform", arcs = "uniform_angle"), text_signature = "(points, local=\"parabolas\", continuity=2, closed=False, parameters=\"uniform\", arcs=\"uniform_angle\")")]
    fn new(
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        local: &str,
        continuity: IntArg,
        closed: bool,
        parameters: &str,
        arcs: &str,
    ) -> PyResult<Self> {
        let continuity = continuity.count("continuity")?;
        let arc_kind = match arcs {
            "uniform_angle" => ArcParametrization::UniformAngle,
            "rational_quadratic" => ArcParametrization::RationalQuadratic,
            "global_angle" => ArcParametrization::GlobalAngle,
            _ => {
                return Err(bad(format!(
                    "arcs: unknown value {arcs:?}; use 'uniform_angle', 'rational_quadratic' or 'global_angle'"
                )))
            }
        };
        let circular = CircularArcs::new(arc_kind);
        let local_name = local;
        let local: &(dyn LocalCurves + Sync) = match local {
            "parabolas" => &Parabolas,
            "arcs" => &circular,
            _ => {
                return Err(bad(format!(
                    "local: unknown value {local:?}; use 'parabolas' or 'arcs'"
                )))
            }
        };
        let options = BlendSplineOptions {
            continuity,
            closed,
            parameters: spline_parameters(parameters)?,
        };
        let pa = floats(points, "points")?;
        let pts = pa.points("points")?;
        let s = py
            .detach(|| BlendSpline::new(pts, local, options))
            .map_err(lib_err)?;
        let inner = Arc::new(s);
        let args = (points, local_name, continuity, closed, parameters, arcs).into_pyobject(py)?;
        Ok(Self {
            args: args.unbind(),
            shared: Arc::clone(&inner) as SharedCurve,
            inner,
        })
    }

    /// The parameters of the points.
    #[getter]
    fn parameters(&self) -> Vec<f64> {
        self.inner.parameters().to_vec()
    }

    /// The number of segments.
    #[getter]
    fn segment_count(&self) -> usize {
        self.inner.segment_count()
    }

    /// The exact NURBS form (parabolas, or arcs with `arcs='rational_quadratic'`).
    fn to_nurbs(&self, py: Python<'_>) -> PyResult<PyNurbsCurve> {
        Ok(PyNurbsCurve::wrap(
            py.detach(|| self.inner.to_nurbs()).map_err(lib_err)?,
        ))
    }
});

/// A `C^k` transition replacing the corner where `before` (from `t_start`) meets `after` (up
/// to `t_end`): the deformation of one into the other over the window (document 001 §B.2).
#[pyclass(module = "lekalo", name = "CornerTransition", frozen)]
pub(crate) struct PyCornerTransition {
    /// The constructor's arguments, for pickling.
    args: Py<PyTuple>,
    inner: Arc<CornerTransition<SharedCurve, SharedCurve>>,
    shared: SharedCurve,
}

blend_class!(PyCornerTransition, u, {
    #[new]
    #[pyo3(signature = (before, t_start, after, t_end, continuity = IntArg::of(2)), text_signature = "(before, t_start, after, t_end, continuity=2)")]
    fn new(
        before: &Bound<'_, PyAny>,
        t_start: f64,
        after: &Bound<'_, PyAny>,
        t_end: f64,
        continuity: IntArg,
    ) -> PyResult<Self> {
        let continuity = continuity.count("continuity")?;
        let c = CornerTransition::new(
            shared_curve(before, "before")?,
            t_start,
            shared_curve(after, "after")?,
            t_end,
            continuity,
        )
        .map_err(lib_err)?;
        let inner = Arc::new(c);
        let py = before.py();
        let args = (before, t_start, after, t_end, continuity).into_pyobject(py)?;
        Ok(Self {
            args: args.unbind(),
            shared: Arc::clone(&inner) as SharedCurve,
            inner,
        })
    }

    /// The window `(t_start, t_end)`.
    #[getter]
    fn window(&self) -> (f64, f64) {
        self.inner.window()
    }
});

/// Every corner of a polyline smoothed with continuity `C^k` into one fair B-spline of degree
/// `2k + 1`, no inflection inside a corner
/// (docs/theory/blending.md#polyline-corners): give the window as `fraction` (of the shorter
/// segment at each corner, in (0, 0.5]; 0.25 when neither is given) or as `length`.
#[pyfunction]
#[pyo3(signature = (points, *, fraction = None, length = None, continuity = IntArg::of(2)), text_signature = "(points, *, fraction=None, length=None, continuity=2)")]
fn smooth_polyline_corners(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    fraction: Option<f64>,
    length: Option<f64>,
    continuity: IntArg,
) -> PyResult<PyBSplineCurve> {
    let continuity = continuity.count("continuity")?;
    let window = match (fraction, length) {
        (Some(_), Some(_)) => {
            return Err(bad(
                "give the window as fraction or as length, not both".into()
            ))
        }
        (_, Some(r)) => CornerWindow::Length(r),
        (f, None) => CornerWindow::Fraction(f.unwrap_or(0.25)),
    };
    let pa = floats(points, "points")?;
    let pts = pa.points("points")?;
    let s = py
        .detach(|| smooth_polyline_corners_lib(pts, window, continuity))
        .map_err(lib_err)?;
    Ok(PyBSplineCurve::wrap(s.into_curve()))
}
