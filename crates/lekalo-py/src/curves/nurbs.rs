//! `NurbsCurve`: the Python class of a rational B-spline curve, a B-spline over homogeneous
//! points `(w·P, w)` (docs/theory/curves.md#nurbs-curves), with its exact conics (circle, arc
//! through three points).

// the class macro `curve_class!` expands here and names the parent's helpers and imports
use super::*;

/// A NURBS curve `C(t) = Σ N_{i,p}(t) w_i P_i / Σ N_{i,p}(t) w_i`
/// (docs/theory/curves.md#nurbs-curves).
///
/// Call: `c(t, nu=0, *, out=None)`: the points at `t` (any shape), `t.shape + (dim,)`; `nu > 0`
/// gives the `nu`-th derivative; `out`, a float64 C-contiguous array of that shape, receives
/// the points (NumPy's `out=`). Outside the domain `lekalo.Error` (no extrapolation).
///
/// >>> import lekalo
/// >>> c = lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], 2.0)
/// >>> bool(abs((c(0.3) ** 2).sum() - 4.0) < 1e-12)
/// True
#[pyclass(module = "lekalo", name = "NurbsCurve", frozen)]
pub(crate) struct PyNurbsCurve {
    pub(crate) inner: NurbsCurve,
    evaluator: OnceLock<NurbsEvaluator>,
}

impl PyNurbsCurve {
    pub(crate) fn wrap(inner: NurbsCurve) -> Self {
        PyNurbsCurve {
            inner,
            evaluator: OnceLock::new(),
        }
    }

    /// The fast evaluator, built on first use and kept.
    fn evaluator(&self) -> &NurbsEvaluator {
        self.evaluator.get_or_init(|| self.inner.evaluator())
    }

    /// Derivatives of orders `0..=order` at `ts` into `out`, `(order + 1) · dim` numbers a
    /// parameter.
    fn derivatives_into(&self, ts: &[f64], order: usize, out: &mut [f64]) -> lekalo::Result<()> {
        let row = (order + 1) * self.inner.dim();
        ts.iter()
            .zip(out.chunks_exact_mut(row))
            .try_for_each(|(&t, o)| {
                o.copy_from_slice(self.inner.eval_derivatives(t, order)?.as_slice());
                Ok(())
            })
    }
}

curve_class!(PyNurbsCurve, Nurbs, "nurbs_curve", knots, {
    #[new]
    fn new(
        degree: IntArg,
        knots: &Bound<'_, PyAny>,
        control: &Bound<'_, PyAny>,
        weights: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let degree = degree.count("degree")?;
        let k = vec1(knots, "knots")?;
        let p = owned_points(control, "control")?;
        let w = vec1(weights, "weights")?;
        Ok(Self::wrap(
            NurbsCurve::new(degree, k, p, w).map_err(lib_err)?,
        ))
    }

    /// A full circle of `radius` about `center` in the plane of the orthonormal axes
    /// `x_axis`, `y_axis` (exact: nine control points, degree 2).
    #[staticmethod]
    fn circle(
        center: &Bound<'_, PyAny>,
        x_axis: &Bound<'_, PyAny>,
        y_axis: &Bound<'_, PyAny>,
        radius: f64,
    ) -> PyResult<Self> {
        let (c, x, y) = (
            vec1(center, "center")?,
            vec1(x_axis, "x_axis")?,
            vec1(y_axis, "y_axis")?,
        );
        Ok(Self::wrap(
            NurbsCurve::circle(&c, &x, &y, radius).map_err(lib_err)?,
        ))
    }

    /// The circular arc through three points `a`, `b`, `c` (from `a` to `c`).
    #[staticmethod]
    fn arc_through_points(
        a: &Bound<'_, PyAny>,
        b: &Bound<'_, PyAny>,
        c: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let (a, b, c) = (vec1(a, "a")?, vec1(b, "b")?, vec1(c, "c")?);
        Ok(Self::wrap(
            NurbsCurve::arc_through_points(&a, &b, &c).map_err(lib_err)?,
        ))
    }

    /// The Euclidean control points, `(n + 1, dim)`.
    #[getter]
    fn control<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_into_array(py, self.inner.control_points())
    }

    /// The weights, `(n + 1,)`.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vec_array(py, &self.inner.weights())
    }

    /// The homogeneous B-spline `(w·P, w)`.
    fn homogeneous(&self) -> PyBSplineCurve {
        PyBSplineCurve::wrap(self.inner.homogeneous().clone())
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

    /// The rational Bezier pieces as NURBS curves.
    fn to_bezier_segments(&self, py: Python<'_>) -> Vec<Self> {
        py.detach(|| self.inner.to_bezier_segments())
            .into_iter()
            .map(Self::wrap)
            .collect()
    }

    fn __repr__(&self) -> String {
        format!(
            "NurbsCurve(degree={}, n_control={}, dim={})",
            self.inner.degree(),
            self.inner.weights().len(),
            self.inner.dim()
        )
    }
});
