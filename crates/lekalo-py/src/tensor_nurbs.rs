//! `TensorNurbs`: rational tensor-product splines in `N` variables, `TensorBSpline(t, c, k)`'s
//! conventions with weights `w` of the net's shape `(n_1, …, n_N)`:
//! `R(x) = Σ_i N_i(x) w_i c_i / Σ_i N_i(x) w_i` (`lekalo::TensorNurbs`, the homogeneous
//! B-spline projected; P&T eq. 4.15 in `N` variables). Evaluation at `(..., N)` arrays gives
//! `(..., *trailing)`.

use lekalo::{TensorBSpline, TensorNurbs};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::{array, check_size, counts, filled, floats, IntArg};
use crate::error::{bad, lib_err, named};
use crate::tensor::{axes_arg, knot_tuple, points_arg, tensor_arg, PyTensorBSpline};

/// A rational tensor-product spline in `N` variables.
#[pyclass(name = "TensorNurbs", module = "lekalo", frozen)]
pub(crate) struct PyTensorNurbs {
    pub(crate) inner: TensorNurbs,
    /// The coefficients' axes after the `N` net axes (`()` for scalar values).
    pub(crate) trailing: Vec<usize>,
}

/// The spline of `TensorNurbs(t, c, k, w)`: `TensorBSpline(t, c, k)`'s validation, then the
/// weights, one positive finite number a coefficient of the net (shape `c.shape[:N]`).
pub(crate) fn tensor_nurbs_arg(
    t: &Bound<'_, PyAny>,
    c: &Bound<'_, PyAny>,
    k: &Bound<'_, PyAny>,
    w: &Bound<'_, PyAny>,
) -> PyResult<(TensorNurbs, Vec<usize>)> {
    let (b, trailing) = tensor_arg(t, c, k)?;
    let wa = floats(w, "w")?;
    if wa.shape() != b.shape() {
        return Err(bad(format!(
            "w: shape {:?}; the weights have the net's shape {:?} (c's first {} axes)",
            wa.shape(),
            b.shape(),
            b.n_vars()
        )));
    }
    let knots = b.knots().iter().map(|kv| kv.as_slice().to_vec()).collect();
    let inner = TensorNurbs::new(
        b.degrees().to_vec(),
        knots,
        b.control_points().clone(),
        wa.data(),
    )
    .map_err(|e| named("w", &e))?;
    Ok((inner, trailing))
}

impl PyTensorNurbs {
    fn out_shape(&self, lead: &[usize]) -> Vec<usize> {
        [lead, &self.trailing].concat()
    }
}

#[pymethods]
impl PyTensorNurbs {
    /// `TensorNurbs(t, c, k, w)`: `TensorBSpline(t, c, k)` with the weights `w`, shape
    /// `(n_1, …, n_N)`, all positive.
    #[new]
    fn new(
        t: &Bound<'_, PyAny>,
        c: &Bound<'_, PyAny>,
        k: &Bound<'_, PyAny>,
        w: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let (inner, trailing) = tensor_nurbs_arg(t, c, k, w)?;
        Ok(Self { inner, trailing })
    }

    /// The B-spline as the rational spline of unit weights (`TensorNurbs::from_bspline`).
    #[staticmethod]
    fn from_bspline(spline: PyRef<'_, PyTensorBSpline>) -> Self {
        Self {
            inner: TensorNurbs::from_bspline(&spline.inner),
            trailing: spline.trailing.clone(),
        }
    }

    /// The knot vectors, one 1-D array per variable.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        knot_tuple(py, self.inner.knots())
    }

    /// The Euclidean coefficients, shape `(n_1, …, n_N, *trailing)`.
    #[getter]
    fn c<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let shape = [self.inner.shape(), &self.trailing].concat();
        array(py, self.inner.control_points().as_slice().to_vec(), &shape)
    }

    /// The weights, shape `(n_1, …, n_N)`.
    #[getter]
    fn w<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, self.inner.weights(), self.inner.shape())
    }

    /// The degrees, one per variable.
    #[getter]
    fn k(&self) -> Vec<usize> {
        self.inner.degrees().to_vec()
    }

    /// The number of variables `N`.
    #[getter]
    fn ndim(&self) -> usize {
        self.inner.n_vars()
    }

    /// The domain `((a_1, b_1), …, (a_N, b_N))`.
    #[getter]
    fn domain(&self) -> Vec<(f64, f64)> {
        self.inner.homogeneous().domain()
    }

    /// The spline (or, with `nu`, the partial derivative of orders `nu`, one per variable, by
    /// the quotient rule in `N` variables, `TensorNurbs::eval_partial`) at the points `x` of
    /// shape `(..., N)`: shape `(..., *trailing)`. A point outside the domain is refused, or
    /// with `extrapolate=True` evaluated by the end spans' polynomials continued, numerator and
    /// weight alike (`TensorNurbs::par_eval_batch_extrapolated`); where the continued weight
    /// reaches 0 the value is not finite.
    #[pyo3(signature = (x, nu = None, extrapolate = false))]
    fn __call__(
        &self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        nu: Option<Vec<IntArg>>,
        extrapolate: bool,
    ) -> PyResult<Py<PyAny>> {
        let n = self.inner.n_vars();
        let xa = points_arg(x, n)?;
        let shape = xa.shape();
        let orders = match nu.map(|v| counts(&v, "nu")).transpose()? {
            Some(v) if v.len() != n => {
                return Err(bad(format!(
                    "nu: {} orders for {n} variables; give one derivative order per variable",
                    v.len()
                )))
            }
            Some(v) if v.iter().any(|&o| o > 0) => Some(v),
            _ => None,
        };
        let lead = &shape[..shape.len() - 1];
        let dim = self.inner.dim();
        check_size("x", &[lead.iter().product(), dim])?;
        let xs = xa.data();
        let out = filled(py, &self.out_shape(lead), |out| match &orders {
            None if extrapolate => self.inner.par_eval_batch_extrapolated(xs, out),
            None => self.inner.par_eval_batch(xs, out),
            Some(orders) => {
                for (p, o) in xs.chunks_exact(n).zip(out.chunks_exact_mut(dim)) {
                    let v = if extrapolate {
                        self.inner.eval_partial_extrapolated(p, orders)?
                    } else {
                        self.inner.eval_partial(p, orders)?
                    };
                    o.copy_from_slice(&v);
                }
                Ok(())
            }
        })?;
        Ok(out.unbind())
    }

    /// The spline on the grid `axes[0] × … × axes[N-1]` (`TensorNurbs::eval_grid`): shape
    /// `(len(axes[0]), …, len(axes[N-1]), *trailing)`.
    #[pyo3(signature = (*axes))]
    fn grid(&self, py: Python<'_>, axes: &Bound<'_, PyTuple>) -> PyResult<Py<PyAny>> {
        let lists = axes_arg(axes.as_any(), "axes")?;
        let n = self.inner.n_vars();
        if lists.len() != n {
            return Err(bad(format!(
                "axes: {} parameter lists for {n} variables; pass one 1-D array per variable",
                lists.len()
            )));
        }
        let lead: Vec<usize> = lists.iter().map(Vec::len).collect();
        check_size("axes", &[&lead[..], &[self.inner.dim()]].concat())?;
        let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
        let out = filled(py, &self.out_shape(&lead), |out| {
            self.inner.eval_grid(&refs, out)
        })?;
        Ok(out.unbind())
    }

    /// The same spline with the knot `x` inserted `times` times in variable `axis` (from 0):
    /// the homogeneous spline's insertion (`TensorNurbs::insert_knot`, P&T §5.2).
    #[pyo3(signature = (x, axis, times = IntArg::of(1)), text_signature = "($self, x, axis, times=1)")]
    fn insert_knot(&self, py: Python<'_>, x: f64, axis: IntArg, times: IntArg) -> PyResult<Self> {
        let (axis, times) = (axis.count("axis")?, times.count("times")?);
        let inner = py
            .detach(|| self.inner.insert_knot(axis, x, times))
            .map_err(lib_err)?;
        Ok(Self {
            inner,
            trailing: self.trailing.clone(),
        })
    }

    /// The rational spline in the variables left free, the others fixed: `fixed` holds one
    /// entry per variable, a value or `None` (`TensorNurbs::slice`, the homogeneous spline
    /// sliced).
    fn slice(&self, py: Python<'_>, fixed: Vec<Option<f64>>) -> PyResult<Self> {
        let inner = py
            .detach(|| self.inner.slice(&fixed))
            .map_err(|e| named("fixed", &e))?;
        Ok(Self {
            inner,
            trailing: self.trailing.clone(),
        })
    }

    /// The homogeneous B-spline `(w c, w)`: a `TensorBSpline` whose values have one more
    /// number, the weight function last (trailing shape `(prod(trailing) + 1,)`).
    fn homogeneous(&self) -> PyTensorBSpline {
        let h: &TensorBSpline = self.inner.homogeneous();
        PyTensorBSpline {
            inner: h.clone(),
            trailing: vec![h.dim()],
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "TensorNurbs(k={:?}, shape={:?}, trailing={:?})",
            self.inner.degrees(),
            self.inner.shape(),
            self.trailing
        )
    }
}
