//! `BezierCurve`, `BSplineCurve`, `NurbsCurve`: thin wrappers over the library's types.
//!
//! This file holds the helpers and the `curve_class!` macro of the methods the three classes
//! share, and `BSplineCurve`; `curves/bezier.rs` holds `BezierCurve`, `curves/nurbs.rs`
//! `NurbsCurve`.
//!
//! Evaluation takes parameters of any shape and returns `t.shape + (dim,)` (a scalar `t` gives
//! `(dim,)`); derivatives `t.shape + (order + 1, dim)`. Large batches run on the rayon pool
//! with results identical to the sequential ones (the library's `par_eval_batch`). The GIL is
//! released around every computation.

use lekalo_io::CurveJson;
use std::sync::OnceLock;

use lekalo::{
    BSplineCurve, BezierCurve, CurveEvaluator, EndConditions, NurbsCurve, NurbsEvaluator, Points,
};
use lekalo_io::{Object, Shape};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::{
    array, check_size, filled, floats, from_json_shape, out_array, out_shape, owned_points,
    points_array, points_into_array, reduce, vec1, vec_array, IntArg,
};
use crate::error::{bad, lib_err};

/// Batches at least this long are split over the rayon pool.
pub(crate) const PAR_MIN: usize = 1 << 14;

pub(crate) fn ends_arg(ends: &str) -> PyResult<EndConditions> {
    match ends {
        "free" => Ok(EndConditions::Free),
        "points" => Ok(EndConditions::Points),
        "tangents" => Ok(EndConditions::Tangents),
        _ => Err(bad(format!(
            "ends: unknown value {ends:?}; use 'free', 'points' or 'tangents'"
        ))),
    }
}

/// Evaluates `f(t, out)` point by point for a scalar-wise curve evaluation (Bezier).
fn eval_pointwise<F>(py: Python<'_>, t: &Bound<'_, PyAny>, dim: usize, f: F) -> PyResult<Py<PyAny>>
where
    F: Fn(f64, &mut [f64]) -> lekalo::Result<()> + Sync,
{
    let ta = floats(t, "t")?;
    let ts = ta.data();
    check_size("t", &[ts.len(), dim])?;
    let out = filled(py, &out_shape(&ta, &[dim]), |out| {
        ts.iter()
            .zip(out.chunks_exact_mut(dim))
            .try_for_each(|(&t, o)| f(t, o))
    })?;
    Ok(out.unbind())
}

/// Derivatives up to `order` at every parameter with a per-point function returning rows.
fn derivatives_pointwise<F>(
    py: Python<'_>,
    t: &Bound<'_, PyAny>,
    order: usize,
    dim: usize,
    f: F,
) -> PyResult<Py<PyAny>>
where
    F: Fn(f64, usize) -> lekalo::Result<Points> + Sync,
{
    let ta = floats(t, "t")?;
    let ts = ta.data();
    let row = check_size("order", &[order.saturating_add(1), dim])?;
    check_size("t", &[ts.len(), row])?;
    let out = filled(py, &out_shape(&ta, &[order + 1, dim]), |out| {
        ts.iter()
            .zip(out.chunks_exact_mut(row))
            .try_for_each(|(&t, o)| {
                let d = f(t, order)?;
                o.copy_from_slice(d.as_slice());
                Ok(())
            })
    })?;
    Ok(out.unbind())
}

/// Picks row `nu` out of a derivative result `t.shape + (order + 1, dim)`.
fn pick_order(py: Python<'_>, d: Py<PyAny>, nu: usize) -> PyResult<Py<PyAny>> {
    let d = d.into_bound(py);
    let idx = (
        pyo3::types::PyEllipsis::get(py),
        nu,
        pyo3::types::PySlice::full(py),
    );
    let row = d.get_item(idx)?;
    // a contiguous copy of the view
    Ok(py
        .import("numpy")?
        .call_method1("ascontiguousarray", (row,))?
        .unbind())
}

/// `f()` with the GIL released, the library's error raised as Python's.
fn detached<T: Send>(py: Python<'_>, f: impl Send + FnOnce() -> lekalo::Result<T>) -> PyResult<T> {
    py.detach(f).map_err(lib_err)
}

/// The Python object of a curve of any kind: the class of its kind.
pub(crate) fn curve_to_py(py: Python<'_>, c: lekalo::Curve) -> PyResult<Py<PyAny>> {
    Ok(match c {
        lekalo::Curve::Bezier(c) => Py::new(py, PyBezierCurve::wrap(c))?.into_any(),
        lekalo::Curve::BSpline(c) => Py::new(py, PyBSplineCurve::wrap(c))?.into_any(),
        lekalo::Curve::Nurbs(c) => Py::new(py, PyNurbsCurve::wrap(c))?.into_any(),
    })
}

/// One curve through `curves` in order, each over its own parameter interval after the
/// previous one's: all raised to the highest degree, each join a knot of multiplicity
/// degree, rational if any is (`lekalo::Curve::composite`, IGES 5.3 §4.4). A start that
/// misses the previous end by at most `tolerance` (default 1e-9 of the largest coordinate,
/// `Curve::composite_tolerance`) is moved onto it; a larger gap raises `lekalo.InputError`.
///
/// >>> import lekalo
/// >>> a = lekalo.BSplineCurve(1, [0.0, 0.0, 1.0, 1.0], [[0.0, 0.0], [1.0, 0.0]])
/// >>> b = lekalo.BSplineCurve(2, [0.0, 0.0, 0.0, 2.0, 2.0, 2.0], [[1.0, 0.0], [2.0, 0.0], [2.0, 1.0]])
/// >>> c = lekalo.composite_curve([a, b])
/// >>> c.degree, c.domain, c(3.0).tolist()
/// (2, (0.0, 3.0), [2.0, 1.0])
#[pyfunction]
#[pyo3(signature = (curves, tolerance = None))]
pub(crate) fn composite_curve(
    py: Python<'_>,
    curves: Vec<Bound<'_, PyAny>>,
    tolerance: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let members = curves
        .iter()
        .enumerate()
        .map(|(k, c)| curve_of(c, &format!("curves[{k}]")))
        .collect::<PyResult<Vec<_>>>()?;
    let tol = tolerance.unwrap_or_else(|| lekalo::Curve::composite_tolerance(&members));
    let c = detached(py, || lekalo::Curve::composite(&members, tol))?;
    curve_to_py(py, c)
}

/// The library's curve of an object of any of the three curve classes (`what` names the
/// argument in the error for any other object).
pub(crate) fn curve_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<lekalo::Curve> {
    if let Ok(c) = obj.cast::<PyBSplineCurve>() {
        return Ok(lekalo::Curve::BSpline(c.get().inner.clone()));
    }
    if let Ok(c) = obj.cast::<PyNurbsCurve>() {
        return Ok(lekalo::Curve::Nurbs(c.get().inner.clone()));
    }
    if let Ok(c) = obj.cast::<PyBezierCurve>() {
        return Ok(lekalo::Curve::Bezier(c.get().inner.clone()));
    }
    Err(bad(format!(
        "{what}: expected a BezierCurve, BSplineCurve or NurbsCurve, got {}",
        obj.get_type().name()?
    )))
}

/// The methods every curve class shares, written once (docs/theory/curves.md):
/// `curve_class!(Type, Variant, "json_type", { class-specific methods })` makes the class's one
/// `#[pymethods]` block from its own methods plus degree, dimension, splitting, JSON, pickling
/// and equality; the `knots` form adds the knot operations and the evaluator-backed `__call__`
/// of the B-spline and NURBS curves.
macro_rules! curve_class {
    ($ty:ident, $variant:ident, $name:literal, knots, { $($extra:tt)* }) => {
        impl $ty {
            /// Points at `ts` into `out` with the kept evaluator; batches of at least
            /// [`PAR_MIN`] parameters on the rayon pool (results identical to the sequential
            /// ones).
            fn evaluate_into(&self, ts: &[f64], out: &mut [f64]) -> lekalo::Result<()> {
                let ev = self.evaluator();
                if ts.len() >= PAR_MIN {
                    ev.par_eval_batch(ts, out)
                } else {
                    ev.eval_batch(ts, out)
                }
            }

            /// The `nu`-th derivative at `ts` into `out` (`dim` numbers a parameter), through
            /// `derivatives_into` on blocks of parameters, so that the lower orders are never
            /// stored for the whole batch. `nu` is at most `MAX_DERIVATIVE_ORDER`.
            fn nth_derivative_into(
                &self,
                ts: &[f64],
                nu: usize,
                out: &mut [f64],
            ) -> lekalo::Result<()> {
                const BLOCK: usize = 1024;
                let dim = self.inner.dim();
                let row = (nu + 1) * dim;
                let mut scratch = vec![0.0; BLOCK.min(ts.len()) * row];
                for (tb, ob) in ts.chunks(BLOCK).zip(out.chunks_mut(BLOCK * dim)) {
                    let s = &mut scratch[..tb.len() * row];
                    self.derivatives_into(tb, nu, s)?;
                    for (r, o) in s.chunks_exact(row).zip(ob.chunks_exact_mut(dim)) {
                        o.copy_from_slice(&r[nu * dim..]);
                    }
                }
                Ok(())
            }
        }

        curve_class!($ty, $variant, $name, {
            $($extra)*

            /// The knot vector, a 1-D array of `n + p + 2` numbers.
            #[getter]
            fn knots<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
                vec_array(py, self.inner.knots().as_slice())
            }

            /// The parameter domain `(t_p, t_{n+1})`.
            #[getter]
            fn domain(&self) -> (f64, f64) {
                self.inner.domain()
            }

            /// Points at `t` (any shape): `t.shape + (dim,)`; `nu > 0` gives the `nu`-th
            /// derivative. Parameters outside the domain raise `lekalo.Error` (no
            /// extrapolation). `out`, a float64 C-contiguous array of the result's shape, receives
            /// the points without a new allocation (NumPy's `out=`; for repeated evaluation)
            /// and is returned.
            #[pyo3(signature = (t, nu = IntArg::of(0), *, out = None))]
            fn __call__(
                &self,
                py: Python<'_>,
                t: &Bound<'_, PyAny>,
                nu: IntArg,
                out: Option<&Bound<'_, PyAny>>,
            ) -> PyResult<Py<PyAny>> {
                let nu = nu.count("nu")?;
                if nu > 0 && out.is_some() {
                    return Err(bad("out: only for points (nu = 0)".into()));
                }
                if nu > lekalo::MAX_DERIVATIVE_ORDER {
                    // the library's error for the order
                    return pick_order(py, self.derivatives(py, t, IntArg::of(nu))?, nu);
                }
                let dim = self.inner.dim();
                let ta = floats(t, "t")?;
                let ts = ta.data();
                if nu > 0 {
                    check_size("t", &[ts.len(), nu + 1, dim])?;
                    let d = filled(py, &out_shape(&ta, &[dim]), |buf| {
                        self.nth_derivative_into(ts, nu, buf)
                    })?;
                    return Ok(d.unbind());
                }
                if let Some(o) = out {
                    let mut rw = out_array(o, &out_shape(&ta, &[dim]))?;
                    let buf = rw
                        .as_slice_mut()
                        .map_err(|e| bad(format!("out: {e}")))?;
                    py.detach(|| self.evaluate_into(ts, buf)).map_err(lib_err)?;
                    return Ok(o.clone().unbind());
                }
                if ta.scalar {
                    let mut out = vec![0.0; dim];
                    py.detach(|| self.inner.eval_into(ts[0], &mut out))
                        .map_err(lib_err)?;
                    return Ok(array(py, out, &[dim])?.unbind());
                }
                check_size("t", &[ts.len(), dim])?;
                // allocated by NumPy in its final shape and written in place
                let out = filled(py, &out_shape(&ta, &[dim]), |buf| self.evaluate_into(ts, buf))?;
                Ok(out.unbind())
            }

            /// Inserts `t` `times` times (Boehm; P&T A5.1): the same curve, more control points.
            #[pyo3(signature = (t, times = IntArg::of(1)), text_signature = "($self, t, times=1)")]
            fn insert_knot(&self, py: Python<'_>, t: f64, times: IntArg) -> PyResult<Self> {
                let times = times.count("times")?;
                Ok(Self::wrap(
                    py.detach(|| self.inner.insert_knot(t, times))
                        .map_err(lib_err)?,
                ))
            }

            /// Inserts all knots of the sorted array `x` at once (P&T A5.4).
            fn refine_knots(&self, py: Python<'_>, x: &Bound<'_, PyAny>) -> PyResult<Self> {
                let x = vec1(x, "x")?;
                Ok(Self::wrap(
                    py.detach(|| self.inner.refine_knots(&x)).map_err(lib_err)?,
                ))
            }

            /// Removes knot `t` up to `times` times while the curve moves less than
            /// `tolerance` (default: relative to the control net's size; P&T A5.8). Returns
            /// `(curve, removed)`.
            #[pyo3(signature = (t, times = IntArg::of(1), tolerance = None), text_signature = "($self, t, times=1, tolerance=None)")]
            fn remove_knot(
                &self,
                py: Python<'_>,
                t: f64,
                times: IntArg,
                tolerance: Option<f64>,
            ) -> PyResult<(Self, usize)> {
                let times = times.count("times")?;
                let tol = tolerance.unwrap_or_else(|| self.inner.default_removal_tolerance());
                let (c, k) = py
                    .detach(|| self.inner.remove_knot(t, times, tol))
                    .map_err(lib_err)?;
                Ok((Self::wrap(c), k))
            }

            /// Removes every knot that can go within `tolerance`; returns `(curve, removed)`.
            #[pyo3(signature = (tolerance = None))]
            fn remove_all_removable_knots(
                &self,
                py: Python<'_>,
                tolerance: Option<f64>,
            ) -> PyResult<(Self, usize)> {
                let tol = tolerance.unwrap_or_else(|| self.inner.default_removal_tolerance());
                let (c, k) = py
                    .detach(|| self.inner.remove_all_removable_knots(tol))
                    .map_err(lib_err)?;
                Ok((Self::wrap(c), k))
            }

            /// The same curve traversed backwards on the same domain.
            fn reverse(&self, py: Python<'_>) -> PyResult<Self> {
                Ok(Self::wrap(
                    py.detach(|| self.inner.reverse()).map_err(lib_err)?,
                ))
            }

            /// The same curve on the domain `[a, b]` (an affine change of parameter).
            fn reparametrize(&self, py: Python<'_>, a: f64, b: f64) -> PyResult<Self> {
                Ok(Self::wrap(
                    py.detach(|| self.inner.reparametrize(a, b))
                        .map_err(lib_err)?,
                ))
            }
        });
    };
    ($ty:ident, $variant:ident, $name:literal, { $($extra:tt)* }) => {
        #[pymethods]
        impl $ty {
            $($extra)*

            /// The degree.
            #[getter]
            fn degree(&self) -> usize {
                self.inner.degree()
            }

            /// The dimension of the (Euclidean) points.
            #[getter]
            fn dim(&self) -> usize {
                self.inner.dim()
            }

            /// Splits at `t` into the curves before and after it (a Bezier curve's halves are
            /// reparametrised to `[0, 1]`, a B-spline's and NURBS's keep their parameters).
            fn split(&self, py: Python<'_>, t: f64) -> PyResult<(Self, Self)> {
                let (a, b) = py.detach(|| self.inner.split_at(t)).map_err(lib_err)?;
                Ok((Self::wrap(a), Self::wrap(b)))
            }

            /// JSON text in the command-line tool's format (`{"lekalo": 1, "type": …}`).
            fn to_json(&self) -> String {
                Object::$variant(self.inner.clone()).to_json_pretty()
            }

            /// Reads the curve from JSON text.
            #[staticmethod]
            fn from_json(text: &str) -> PyResult<Self> {
                match from_json_shape(text)? {
                    Shape::Curve(Object::$variant(c)) => Ok(Self::wrap(c)),
                    other => Err(bad(format!(
                        concat!("expected a ", $name, ", got {}"),
                        other.type_name()
                    ))),
                }
            }

            fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
                reduce(py, self.to_json())
            }

            fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
                other
                    .cast::<Self>()
                    .is_ok_and(|o| o.get().inner == self.inner)
            }
        }
    };
}

// declared after `curve_class!`, whose textual scope they need (`macro_rules!` macros are in
// scope only below their definition)
mod bezier;
mod nurbs;

pub(crate) use bezier::PyBezierCurve;
pub(crate) use nurbs::PyNurbsCurve;

// ---------------------------------------------------------------------------------------------

/// A B-spline curve `C(t) = Σ N_{i,p}(t) P_i` on the domain `[t_p, t_{n+1}]`
/// (docs/theory/curves.md#b-spline-curves).
///
/// Call: `c(t, nu=0, *, out=None)`: the points at `t` (any shape), `t.shape + (dim,)`; `nu > 0`
/// gives the `nu`-th derivative; `out`, a float64 C-contiguous array of that shape, receives
/// the points (NumPy's `out=`). Outside the domain `lekalo.Error` (no extrapolation).
///
/// >>> import lekalo
/// >>> c = lekalo.BSplineCurve(2, [0, 0, 1, 2, 3, 3], [[1, 1], [2, 3], [4, 3]])
/// >>> c.domain
/// (1.0, 2.0)
/// >>> c(1.5)
/// array([2.125, 2.75 ])
#[pyclass(module = "lekalo", name = "BSplineCurve", frozen)]
pub(crate) struct PyBSplineCurve {
    pub(crate) inner: BSplineCurve,
    evaluator: OnceLock<CurveEvaluator>,
    basis_evaluator: OnceLock<CurveEvaluator>,
}

impl PyBSplineCurve {
    pub(crate) fn wrap(inner: BSplineCurve) -> Self {
        PyBSplineCurve {
            inner,
            evaluator: OnceLock::new(),
            basis_evaluator: OnceLock::new(),
        }
    }

    /// The fast evaluator, built on first use and kept.
    pub(crate) fn evaluator(&self) -> &CurveEvaluator {
        self.evaluator.get_or_init(|| self.inner.evaluator())
    }

    /// The fast evaluator with the basis kernel (`EvalKernel::Basis`: the reference's
    /// arithmetic, so that a zero coefficient contributes an exact zero, as in SciPy), built on
    /// first use and kept.
    pub(crate) fn basis_evaluator(&self) -> &CurveEvaluator {
        self.basis_evaluator
            .get_or_init(|| basis_kernel(&self.inner))
    }

    /// Derivatives of orders `0..=order` at `ts` into `out`, `(order + 1) · dim` numbers a
    /// parameter.
    fn derivatives_into(&self, ts: &[f64], order: usize, out: &mut [f64]) -> lekalo::Result<()> {
        self.evaluator().eval_derivatives_batch(ts, order, out)
    }
}

curve_class!(PyBSplineCurve, BSpline, "bspline_curve", knots, {
    #[new]
    fn new(degree: IntArg, knots: &Bound<'_, PyAny>, control: &Bound<'_, PyAny>) -> PyResult<Self> {
        let degree = degree.get(
            "BSplineCurve: degree",
            "lekalo's call is BSplineCurve(degree, knots, control): SciPy's BSpline(t, c, k) is \
             lekalo.BSplineCurve(k, t, c)",
        )?;
        let k = vec1(knots, "knots")?;
        let p = owned_points(control, "control")?;
        Ok(Self::wrap(
            BSplineCurve::new(degree, k, p).map_err(lib_err)?,
        ))
    }

    /// A clamped B-spline with uniform interior knots on `[0, 1]` over the control points.
    #[staticmethod]
    fn clamped(degree: IntArg, control: &Bound<'_, PyAny>) -> PyResult<Self> {
        let degree = degree.count("degree")?;
        let p = owned_points(control, "control")?;
        let kv = lekalo::KnotVector::clamped_uniform(degree, p.len()).map_err(lib_err)?;
        Ok(Self::wrap(
            BSplineCurve::from_knot_vector(degree, kv, p).map_err(lib_err)?,
        ))
    }

    /// The control points, `(n + 1, dim)`.
    #[getter]
    fn control<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_array(py, self.inner.control_points())
    }

    /// Derivatives of orders `0..=order` at `t`: `t.shape + (order + 1, dim)` (right-hand at
    /// interior knots, left-hand at the right end).
    fn derivatives(
        &self,
        py: Python<'_>,
        t: &Bound<'_, PyAny>,
        order: IntArg,
    ) -> PyResult<Py<PyAny>> {
        let order = order.count("order")?;
        let dim = self.inner.dim();
        let ta = floats(t, "t")?;
        let ts = ta.data();
        let row = check_size("order", &[order.saturating_add(1), dim])?;
        check_size("t", &[ts.len(), row])?;
        if order > lekalo::MAX_DERIVATIVE_ORDER {
            // the library's own message for the limit
            return Err(lib_err(
                self.inner
                    .eval_derivatives(self.inner.domain().0, order)
                    .err()
                    .unwrap_or(lekalo::Error::InvalidArgument {
                        what: "order".into(),
                        reason: "too large".into(),
                    }),
            ));
        }
        let out = filled(py, &out_shape(&ta, &[order + 1, dim]), |out| {
            self.evaluator().eval_derivatives_batch(ts, order, out)
        })?;
        Ok(out.unbind())
    }

    /// The derivative curve `C'` (degree `p − 1`).
    fn derivative(&self, py: Python<'_>) -> PyResult<Self> {
        Ok(Self::wrap(
            py.detach(|| self.inner.derivative()).map_err(lib_err)?,
        ))
    }

    /// The graph `t ↦ (t, y(t))` of this 1-D curve (a function) as a plane curve of the same
    /// degree and knots, control points at the Greville abscissae (exact).
    fn graph(&self, py: Python<'_>) -> PyResult<Self> {
        Ok(Self::wrap(
            py.detach(|| self.inner.graph()).map_err(lib_err)?,
        ))
    }

    /// The Bezier pieces: a list of `(start, end, BezierCurve)`.
    fn to_bezier_segments(&self, py: Python<'_>) -> Vec<(f64, f64, PyBezierCurve)> {
        py.detach(|| self.inner.to_bezier_segments())
            .into_iter()
            .map(|s| (s.start, s.end, PyBezierCurve::wrap(s.curve)))
            .collect()
    }

    /// Degree elevation by `by`, piece by piece (document 004).
    #[pyo3(signature = (by = IntArg::of(1)), text_signature = "($self, by=1)")]
    fn elevate_degree(&self, py: Python<'_>, by: IntArg) -> PyResult<Self> {
        let by = by.count("by")?;
        Ok(Self::wrap(detached(py, || self.inner.elevate_degree(by))?))
    }

    /// Exact degree change to `target` (refused below the real degree of a piece).
    fn change_degree(&self, py: Python<'_>, target: IntArg) -> PyResult<Self> {
        let target = target.count("target")?;
        Ok(Self::wrap(detached(py, || {
            self.inner.change_degree(target)
        })?))
    }

    /// The axis-aligned bounding box of the control net, `(lo, hi)`.
    fn bounding_box<'py>(&self, py: Python<'py>) -> (Bound<'py, PyAny>, Bound<'py, PyAny>) {
        let (lo, hi) = self.inner.bounding_box();
        (vec_array(py, &lo), vec_array(py, &hi))
    }

    /// The same curve as a NURBS with unit weights.
    fn to_nurbs(&self) -> PyNurbsCurve {
        PyNurbsCurve::wrap(NurbsCurve::from_bspline(&self.inner))
    }

    fn __repr__(&self) -> String {
        let (a, b) = self.inner.domain();
        format!(
            "BSplineCurve(degree={}, n_control={}, dim={}, domain=({a}, {b}))",
            self.inner.degree(),
            self.inner.control_points().len(),
            self.inner.dim()
        )
    }
});

// ---------------------------------------------------------------------------------------------

/// `curve`'s fast evaluator with the basis kernel (which every curve has).
pub(crate) fn basis_kernel(curve: &BSplineCurve) -> CurveEvaluator {
    CurveEvaluator::with_kernel(curve, lekalo::EvalKernel::Basis)
        .unwrap_or_else(|_| curve.evaluator())
}
