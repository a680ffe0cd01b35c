//! `BezierCurve`: the Python class of a Bezier curve `C(t) = Σ B_{i,n}(t) P_i` on `[0, 1]`
//! (docs/theory/curves.md#bezier-curves), with its degree operations (document 004: elevation,
//! exact change, least-squares reduction, real degree) and its monomial form.

// the class macro `curve_class!` expands here and names the parent's helpers and imports
use super::*;

/// A Bezier curve `C(t) = Σ B_{i,n}(t) P_i`, `t ∈ [0, 1]` (docs/theory/curves.md#bezier-curves).
///
/// Call: `c(t, nu=0)`: the points at `t` (any shape), `t.shape + (dim,)`; `nu > 0` gives the
/// `nu`-th derivative.
///
/// >>> import numpy as np, lekalo
/// >>> c = lekalo.BezierCurve([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])
/// >>> c(0.5)
/// array([1., 1.])
#[pyclass(module = "lekalo", name = "BezierCurve", frozen)]
pub(crate) struct PyBezierCurve {
    pub(crate) inner: BezierCurve,
}

impl PyBezierCurve {
    pub(crate) fn wrap(inner: BezierCurve) -> Self {
        PyBezierCurve { inner }
    }
}

curve_class!(PyBezierCurve, Bezier, "bezier_curve", {
    #[new]
    fn new(control: &Bound<'_, PyAny>) -> PyResult<Self> {
        let p = owned_points(control, "control")?;
        Ok(Self::wrap(BezierCurve::new(p).map_err(lib_err)?))
    }

    /// The control points, `(n + 1, dim)`.
    #[getter]
    fn control<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_array(py, self.inner.control_points())
    }

    /// The parameter domain, always `(0.0, 1.0)`.
    #[getter]
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }

    /// Points at `t` (any shape): `t.shape + (dim,)`; `nu > 0` gives the `nu`-th derivative.
    #[pyo3(signature = (t, nu = IntArg::of(0)))]
    fn __call__(&self, py: Python<'_>, t: &Bound<'_, PyAny>, nu: IntArg) -> PyResult<Py<PyAny>> {
        let nu = nu.count("nu")?;
        if nu > 0 {
            return pick_order(py, self.derivatives(py, t, IntArg::of(nu))?, nu);
        }
        let c = &self.inner;
        eval_pointwise(py, t, c.dim(), |t, o| c.eval_into(t, o))
    }

    /// Derivatives of orders `0..=order` at `t`: `t.shape + (order + 1, dim)`.
    fn derivatives(
        &self,
        py: Python<'_>,
        t: &Bound<'_, PyAny>,
        order: IntArg,
    ) -> PyResult<Py<PyAny>> {
        let order = order.count("order")?;
        let c = &self.inner;
        derivatives_pointwise(py, t, order, c.dim(), |t, k| c.eval_derivatives(t, k))
    }

    /// The hodograph `C'` as a Bezier curve of degree `n − 1`.
    fn derivative(&self, py: Python<'_>) -> Self {
        Self::wrap(py.detach(|| self.inner.derivative()))
    }

    /// Degree elevation by `by` (document 004): the same curve with more control points.
    #[pyo3(signature = (by = IntArg::of(1)), text_signature = "($self, by=1)")]
    fn elevate_degree(&self, py: Python<'_>, by: IntArg) -> PyResult<Self> {
        let by = by.count("by")?;
        Ok(Self::wrap(detached(py, || self.inner.elevate_degree(by))?))
    }

    /// Exact degree change to `target` (document 004): elevation, or reduction that is refused
    /// below the real degree.
    fn change_degree(&self, py: Python<'_>, target: IntArg) -> PyResult<Self> {
        let target = target.count("target")?;
        Ok(Self::wrap(detached(py, || {
            self.inner.change_degree(target)
        })?))
    }

    /// Least-squares degree reduction to `target` keeping `ends` ('free', 'points',
    /// 'tangents'); returns `(curve, max_deviation_bound)`.
    #[pyo3(signature = (target, ends = "points"))]
    fn reduce_degree_approx(
        &self,
        py: Python<'_>,
        target: IntArg,
        ends: &str,
    ) -> PyResult<(Self, f64)> {
        let target = target.count("target")?;
        let ends = ends_arg(ends)?;
        let r = py
            .detach(|| self.inner.reduce_degree_approx(target, ends))
            .map_err(lib_err)?;
        Ok((Self::wrap(r.curve.clone()), r.max_deviation_bound))
    }

    /// The real degree: the least degree that represents the same curve (document 004).
    fn real_degree(&self) -> usize {
        self.inner.real_degree()
    }

    /// The monomial coefficients `a_k` with `C(t) = Σ a_k t^k`, `(n + 1, dim)`.
    fn to_monomial<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_into_array(py, self.inner.to_monomial().map_err(lib_err)?)
    }

    /// The Bezier curve with the given monomial coefficients `(n + 1, dim)`.
    #[staticmethod]
    fn from_monomial(coefficients: &Bound<'_, PyAny>) -> PyResult<Self> {
        let p = owned_points(coefficients, "coefficients")?;
        Ok(Self::wrap(BezierCurve::from_monomial(p).map_err(lib_err)?))
    }

    /// The same curve as a clamped B-spline on `[0, 1]`.
    fn to_bspline(&self) -> PyBSplineCurve {
        PyBSplineCurve::wrap(self.inner.to_bspline())
    }

    fn __repr__(&self) -> String {
        format!(
            "BezierCurve(degree={}, dim={})",
            self.inner.degree(),
            self.inner.dim()
        )
    }
});
