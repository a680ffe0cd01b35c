//! `TensorBSpline`: tensor-product B-splines in `N` variables with SciPy's `NdBSpline`
//! conventions: knots `t` (one 1-D array per variable), coefficients `c` of shape
//! `(n_1, …, n_N, *trailing)` in C order (the library's net, first variable slowest, with
//! `dim = prod(trailing)`), degrees `k`. Evaluation at `(..., N)` arrays gives
//! `(..., *trailing)`.

use lekalo::{
    Arg, EndCondition, KnotVector, Points, PointsRef, TensorBSpline, TensorInterpolation,
};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

use crate::convert::{array, check_size, counts, filled, floats, vec1, FloatArray, IntArg};
use crate::error::{bad, lib_err, named};
use crate::interp::end_arg;

/// The argument of `TensorBSpline(t, c, k)` a constructor error is about.
fn constructor_arg(e: &lekalo::Error) -> &'static str {
    match e {
        lekalo::Error::LengthMismatch { .. } | lekalo::Error::TooLarge { .. } => "c",
        lekalo::Error::Degree { .. } => "k",
        _ => "t",
    }
}

/// A tensor-product B-spline in `N` variables (SciPy's `NdBSpline`, with the library's
/// validation and evaluation).
#[pyclass(name = "TensorBSpline", module = "lekalo", frozen)]
pub(crate) struct PyTensorBSpline {
    pub(crate) inner: TensorBSpline,
    /// The coefficients' axes after the `N` net axes (`()` for scalar values).
    pub(crate) trailing: Vec<usize>,
}

impl PyTensorBSpline {
    /// The Python object of a spline of scalar values (no trailing axes).
    pub(crate) fn scalar(inner: TensorBSpline) -> Self {
        PyTensorBSpline {
            inner,
            trailing: Vec::new(),
        }
    }
}

/// The knot vectors as a tuple of 1-D arrays, one per variable.
pub(crate) fn knot_tuple<'py>(
    py: Python<'py>,
    knots: &[KnotVector],
) -> PyResult<Bound<'py, PyTuple>> {
    let arrays: Vec<Bound<'py, PyAny>> = knots
        .iter()
        .map(|k| crate::convert::vec_array(py, k.as_slice()))
        .collect();
    PyTuple::new(py, arrays)
}

/// The points `x` of a spline in `n` variables: an array whose last axis holds a point's `n`
/// coordinates.
pub(crate) fn points_arg<'py>(x: &Bound<'py, PyAny>, n: usize) -> PyResult<FloatArray<'py>> {
    let xa = floats(x, "x")?;
    let shape = xa.shape();
    if shape.last() != Some(&n) {
        return Err(bad(format!(
            "x: shape {shape:?}; the last axis must hold the {n} coordinates of a point"
        )));
    }
    Ok(xa)
}

/// Degrees from `k`: one integer for every variable, or one per variable.
pub(crate) fn degrees_arg(k: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<usize>> {
    // a tuple or list is not tried as one integer first (the failed extraction builds an
    // exception, a good part of a scalar call)
    if !(k.is_instance_of::<PyTuple>() || k.is_instance_of::<PyList>()) {
        if let Ok(p) = k.extract::<usize>() {
            return Ok(vec![p; n]);
        }
    }
    let list: Vec<usize> = k.extract().map_err(|_| {
        bad("k: expected a non-negative integer or one per variable (a tuple of ints)".into())
    })?;
    if list.len() != n {
        return Err(bad(format!(
            "k: {} degrees for {n} variables; give one integer, or one per variable",
            list.len()
        )));
    }
    Ok(list)
}

/// Degrees from `k` as [`degrees_arg`], cubic in every variable without `k`.
pub(crate) fn degrees_or_cubic(k: Option<&Bound<'_, PyAny>>, n: usize) -> PyResult<Vec<usize>> {
    match k {
        Some(k) => degrees_arg(k, n),
        None => Ok(vec![3; n]),
    }
}

/// Values on the grid of the coordinate `lists` (`va` of shape `(m_1, …, m_N, *trailing)`) as
/// rows of the trailing size, and the trailing axes.
pub(crate) fn grid_values<'a>(
    va: &'a FloatArray<'_>,
    lists: &[Vec<f64>],
) -> PyResult<(PointsRef<'a>, Vec<usize>)> {
    grid_values_of(va, lists, &vec![false; lists.len()])
}

/// [`grid_values`] where the axes of the `periodic` directions hold one coordinate more than
/// the values, the return to the first line.
fn grid_values_of<'a>(
    va: &'a FloatArray<'_>,
    lists: &[Vec<f64>],
    periodic: &[bool],
) -> PyResult<(PointsRef<'a>, Vec<usize>)> {
    let n = lists.len();
    let shape = va.shape();
    let sizes: Vec<usize> = lists
        .iter()
        .zip(periodic)
        .map(|(x, &p)| x.len().saturating_sub(usize::from(p)))
        .collect();
    if shape.len() < n || shape[..n] != sizes[..] {
        let periodic_note = if periodic.iter().any(|&p| p) {
            " (a periodic axis holds one coordinate more than the values, the return to the \
             first line, whose values are not repeated)"
        } else {
            ""
        };
        return Err(bad(format!(
            "values: shape {shape:?} does not start with the axes' lengths {sizes:?}{periodic_note}"
        )));
    }
    let trailing = shape[n..].to_vec();
    let dim: usize = trailing.iter().product();
    let pts = PointsRef::from_flat(dim.max(1), va.data()).map_err(|e| named("values", &e))?;
    Ok((pts, trailing))
}

/// `end` of `interpolate_grid`: one word of the end-condition vocabulary for every variable, or
/// a sequence of one per variable.
fn ends_arg(obj: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<EndCondition>> {
    if let Ok(word) = obj.extract::<String>() {
        return Ok(vec![end_arg(&word, None, None)?; n]);
    }
    let words: Vec<String> = obj.extract().map_err(|_| {
        bad(format!(
            "end: expected a word (\"free\", \"natural\", \"periodic\") or a sequence of {n}, \
             one per variable"
        ))
    })?;
    if words.len() != n {
        return Err(bad(format!(
            "end: {} end conditions for {n} variables; give one per variable or one word for all",
            words.len()
        )));
    }
    words.iter().map(|w| end_arg(w, None, None)).collect()
}

/// One 1-D float array per variable.
pub(crate) fn axes_arg(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Vec<f64>>> {
    let items: Vec<Bound<'_, PyAny>> = obj
        .try_iter()
        .map_err(|_| {
            bad(format!(
                "{what}: expected a sequence of 1-D arrays, one per variable"
            ))
        })?
        .collect::<PyResult<_>>()?;
    items
        .iter()
        .enumerate()
        .map(|(a, x)| vec1(x, &format!("{what}[{a}]")))
        .collect()
}

/// `knots`: one entry per variable, `None` or a 1-D array of knots.
fn knots_arg(obj: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<Option<KnotVector>>> {
    let items: Vec<Bound<'_, PyAny>> = obj
        .try_iter()
        .map_err(|_| {
            bad("knots: expected a sequence with one knot array (or None) per variable".into())
        })?
        .collect::<PyResult<_>>()?;
    if items.len() != n {
        return Err(bad(format!(
            "knots: {} entries for {n} variables; give one knot array (or None) per variable",
            items.len()
        )));
    }
    items
        .iter()
        .enumerate()
        .map(|(a, x)| {
            if x.is_none() {
                return Ok(None);
            }
            let what = format!("knots[{a}]");
            let t = vec1(x, &what)?;
            KnotVector::new(t).map(Some).map_err(|e| named(&what, &e))
        })
        .collect()
}

impl PyTensorBSpline {
    fn out_shape(&self, lead: &[usize]) -> Vec<usize> {
        [lead, &self.trailing].concat()
    }

    fn orders(&self, nu: Option<Vec<IntArg>>) -> PyResult<Option<Vec<usize>>> {
        match nu.map(|v| counts(&v, "nu")).transpose()? {
            Some(v) if v.len() != self.inner.n_vars() => Err(bad(format!(
                "nu: {} orders for {} variables; give one derivative order per variable",
                v.len(),
                self.inner.n_vars()
            ))),
            Some(v) if v.iter().all(|&o| o == 0) => Ok(None),
            other => Ok(other),
        }
    }
}

#[pymethods]
impl PyTensorBSpline {
    /// `TensorBSpline(t, c, k)`: knots `t` (one 1-D array per variable), coefficients `c` of
    /// shape `(n_1, …, n_N, *trailing)` with `n_a = len(t[a]) - k[a] - 1`, degrees `k` (one
    /// integer, or one per variable) — SciPy's `NdBSpline(t, c, k)`.
    #[new]
    fn new(t: &Bound<'_, PyAny>, c: &Bound<'_, PyAny>, k: &Bound<'_, PyAny>) -> PyResult<Self> {
        let knots = axes_arg(t, "t")?;
        let n = knots.len();
        let degrees = degrees_arg(k, n)?;
        let ca = floats(c, "c")?;
        let shape = ca.shape();
        if shape.len() < n {
            return Err(bad(format!(
                "c: shape {shape:?} has fewer axes than the {n} variables; c has shape (n_1, …, n_N, *trailing)"
            )));
        }
        let trailing = shape[n..].to_vec();
        let dim: usize = trailing.iter().product();
        if dim == 0 {
            return Err(bad(format!(
                "c: a trailing axis of shape {shape:?} is empty"
            )));
        }
        for (a, (kv, &p)) in knots.iter().zip(&degrees).enumerate() {
            let want = kv.len().saturating_sub(p + 1);
            if shape[a] != want {
                return Err(bad(format!(
                    "c: axis {a} has {} coefficients, but t[{a}] ({} knots) and k[{a}] = {p} give {want}",
                    shape[a],
                    kv.len()
                )));
            }
        }
        let control = Points::from_flat(dim, ca.data().to_vec()).map_err(|e| named("c", &e))?;
        let inner = TensorBSpline::new(degrees, knots, control)
            .map_err(|e| named(constructor_arg(&e), &e))?;
        Ok(Self { inner, trailing })
    }

    /// The knot vectors, one 1-D array per variable.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        knot_tuple(py, self.inner.knots())
    }

    /// The coefficients, shape `(n_1, …, n_N, *trailing)`.
    #[getter]
    fn c<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let shape = [self.inner.shape(), &self.trailing].concat();
        array(py, self.inner.control_points().as_slice().to_vec(), &shape)
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
        self.inner.domain()
    }

    /// The spline (or, with `nu`, the partial derivative of orders `nu`, one per variable) at
    /// the points `x` of shape `(..., N)`: shape `(..., *trailing)`. A point outside the
    /// domain is refused, or with `extrapolate=True` evaluated by the end spans' polynomials
    /// continued (`TensorBSpline::par_eval_batch_extrapolated`).
    #[pyo3(signature = (x, nu = None, extrapolate = false))]
    fn __call__(
        &self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        nu: Option<Vec<IntArg>>,
        extrapolate: bool,
    ) -> PyResult<Py<PyAny>> {
        let xa = points_arg(x, self.inner.n_vars())?;
        let shape = xa.shape();
        let orders = self.orders(nu)?;
        let lead = &shape[..shape.len() - 1];
        let out_shape = self.out_shape(lead);
        check_size("x", &[lead.iter().product(), self.inner.dim()])?;
        let xs = xa.data();
        let out = filled(py, &out_shape, |out| {
            if extrapolate {
                self.inner
                    .par_eval_batch_extrapolated(xs, orders.as_deref(), out)
            } else {
                self.inner.par_eval_batch(xs, orders.as_deref(), out)
            }
        })?;
        Ok(out.unbind())
    }

    /// The spline (or the partial derivative of orders `nu`) on the grid `axes[0] × … ×
    /// axes[N-1]`: shape `(len(axes[0]), …, len(axes[N-1]), *trailing)`.
    #[pyo3(signature = (*axes, nu = None))]
    fn grid(
        &self,
        py: Python<'_>,
        axes: &Bound<'_, PyTuple>,
        nu: Option<Vec<IntArg>>,
    ) -> PyResult<Py<PyAny>> {
        let lists = axes_arg(axes.as_any(), "axes")?;
        let n = self.inner.n_vars();
        if lists.len() != n {
            return Err(bad(format!(
                "axes: {} parameter lists for {n} variables; pass one 1-D array per variable",
                lists.len()
            )));
        }
        let orders = self.orders(nu)?;
        let lead: Vec<usize> = lists.iter().map(Vec::len).collect();
        check_size("axes", &[&lead[..], &[self.inner.dim()]].concat())?;
        let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
        let out = filled(py, &self.out_shape(&lead), |out| {
            self.inner.eval_grid(&refs, orders.as_deref(), out)
        })?;
        Ok(out.unbind())
    }

    /// The integral over the box `bounds` (one `(a, b)` per variable, inside the domain):
    /// shape `trailing` (`TensorBSpline::integral`, `docs/theory/tensor.md#integrals-over-boxes`).
    fn integral<'py>(
        &self,
        py: Python<'py>,
        bounds: Vec<(f64, f64)>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let v = self
            .inner
            .integral(&bounds)
            .map_err(|e| named("bounds", &e))?;
        array(py, v, &self.trailing)
    }

    /// The interpolating spline of the grid `values` (shape `(m_1, …, m_N, *trailing)`) at the
    /// coordinates `axes` (one strictly increasing 1-D array per variable), of the given degrees
    /// (one integer or one per variable; free ends) and knots (`knots`: one entry per
    /// variable, a knot vector of `m_a + k_a + 1` knots or `None` for averaged knots):
    /// SciPy's `make_ndbspl` with its not-a-knot knots given (`TensorInterpolation::knot_vectors`,
    /// `docs/theory/tensor.md#interpolation-on-grids`). `end`: one end condition for every
    /// variable or one per variable, `"free"` (default), `"natural"` (cubic) or `"periodic"`
    /// (`TensorInterpolation::end_conditions`); a periodic axis holds one coordinate more than
    /// its values, the return to the first line (SciPy's `make_interp_spline(x, y,
    /// bc_type="periodic")` along that axis with the repeated last line of `y` dropped).
    #[staticmethod]
    #[pyo3(signature = (axes, values, degrees = None, knots = None, end = None))]
    fn interpolate_grid(
        py: Python<'_>,
        axes: &Bound<'_, PyAny>,
        values: &Bound<'_, PyAny>,
        degrees: Option<&Bound<'_, PyAny>>,
        knots: Option<&Bound<'_, PyAny>>,
        end: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let (inner, trailing) = interpolated(py, axes, values, degrees, knots, end)?;
        Ok(Self { inner, trailing })
    }

    /// The coefficients of [`interpolate_grid`](Self::interpolate_grid) with the same
    /// arguments, shape `(n_1, …, n_N, *trailing)`, without the spline object: the solves'
    /// array handed to NumPy as it is, not copied (all SciPy's `make_ndbspl` keeps; its peak
    /// is then one array of the grid's size above the input).
    #[staticmethod]
    #[pyo3(signature = (axes, values, degrees = None, knots = None, end = None))]
    fn interpolate_grid_c<'py>(
        py: Python<'py>,
        axes: &Bound<'_, PyAny>,
        values: &Bound<'_, PyAny>,
        degrees: Option<&Bound<'_, PyAny>>,
        knots: Option<&Bound<'_, PyAny>>,
        end: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (inner, trailing) = interpolated(py, axes, values, degrees, knots, end)?;
        let shape = [inner.shape(), &trailing].concat();
        let (_, _, control) = inner.into_parts();
        array(py, control.into_vec(), &shape)
    }

    /// The same spline from a `scipy.interpolate.NdBSpline` (its `t`, `c`, `k`, bit for bit).
    #[staticmethod]
    fn from_scipy(spline: &Bound<'_, PyAny>) -> PyResult<Self> {
        let c = spline.getattr("c")?;
        let c = spline
            .py()
            .import("numpy")?
            .call_method1("ascontiguousarray", (c, "float64"))?;
        Self::new(&spline.getattr("t")?, &c, &spline.getattr("k")?)
    }

    /// The partial-derivative spline of orders `nu` (one per variable): degrees lowered by
    /// the orders (`TensorBSpline::derivative`, P&T §3.3 direction by direction).
    fn derivative(&self, nu: Vec<IntArg>) -> PyResult<Self> {
        let nu = counts(&nu, "nu")?;
        let inner = self.inner.derivative(&nu).map_err(|e| named("nu", &e))?;
        Ok(Self {
            inner,
            trailing: self.trailing.clone(),
        })
    }

    /// The same spline with the knot `x` inserted `times` times in variable `axis` (from 0):
    /// one more coefficient a copy along that axis (`TensorBSpline::insert_knot`, Boehm along
    /// each line of the net, `docs/theory/tensor.md#operations-along-one-direction`).
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

    /// The spline in the variables left free, the others fixed: `fixed` holds one entry per
    /// variable, a value or `None` (free), so `s.slice([None, 0.5, None])(x)` is
    /// `s([x[0], 0.5, x[1]])` (`TensorBSpline::slice`,
    /// `docs/theory/tensor.md#operations-along-one-direction`).
    fn slice(&self, py: Python<'_>, fixed: Vec<Option<f64>>) -> PyResult<Self> {
        let inner = py
            .detach(|| self.inner.slice(&fixed))
            .map_err(|e| named("fixed", &e))?;
        Ok(Self {
            inner,
            trailing: self.trailing.clone(),
        })
    }

    /// The same spline as a `scipy.interpolate.NdBSpline` (bit for bit; no extrapolation).
    fn to_scipy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let nd = py.import("scipy.interpolate")?.getattr("NdBSpline")?;
        let kw = pyo3::types::PyDict::new(py);
        kw.set_item("extrapolate", false)?;
        nd.call(
            (self.t(py)?, self.c(py)?, PyTuple::new(py, self.k())?),
            Some(&kw),
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "TensorBSpline(k={:?}, shape={:?}, trailing={:?})",
            self.inner.degrees(),
            self.inner.shape(),
            self.trailing
        )
    }
}

/// The spline of `TensorBSpline.interpolate_grid(axes, values, degrees, knots, end)` and its
/// values' trailing axes, computed without the GIL (`TensorInterpolation::interpolate_at`,
/// `docs/theory/tensor.md#interpolation-on-grids`).
fn interpolated(
    py: Python<'_>,
    axes: &Bound<'_, PyAny>,
    values: &Bound<'_, PyAny>,
    degrees: Option<&Bound<'_, PyAny>>,
    knots: Option<&Bound<'_, PyAny>>,
    end: Option<&Bound<'_, PyAny>>,
) -> PyResult<(TensorBSpline, Vec<usize>)> {
    let lists = axes_arg(axes, "axes")?;
    let n = lists.len();
    let given = knots.map(|k| knots_arg(k, n)).transpose()?;
    let degrees = degrees_or_cubic(degrees, n)?;
    let ends = end.map(|e| ends_arg(e, n)).transpose()?;
    let periodic: Vec<bool> = match &ends {
        Some(e) => e.iter().map(|c| *c == EndCondition::Periodic).collect(),
        None => vec![false; n],
    };
    let va = floats(values, "values")?;
    let (pts, trailing) = grid_values_of(&va, &lists, &periodic)?;
    let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let mut interpolation = TensorInterpolation::new(degrees);
    if let Some(given) = given {
        interpolation = interpolation.knot_vectors(given);
    }
    if let Some(ends) = ends {
        interpolation = interpolation.end_conditions(ends);
    }
    let inner = py
        .detach(|| interpolation.interpolate_at(&refs, pts))
        .map_err(|e| match e {
            lekalo::Error::Degree { .. } => named("degrees", &e),
            lekalo::Error::InvalidArgument { .. } if e.arg() == Some(Arg::Knots) => {
                named("knots", &e)
            }
            lekalo::Error::SingularSystem { .. } => named("knots", &e),
            lekalo::Error::KnotsNotSorted { .. }
            | lekalo::Error::NotIncreasing { .. }
            | lekalo::Error::Repeated { .. }
            | lekalo::Error::InvalidArgument { .. }
            | lekalo::Error::NonFinite { .. } => named("axes", &e),
            other => lib_err(other),
        })?;
    Ok((inner, trailing))
}

/// The spline of `TensorBSpline(t, c, k)`, validated as the class validates it, and the
/// coefficients' trailing axes (for the derivative kernels of `derivatives.rs`).
pub(crate) fn tensor_arg(
    t: &Bound<'_, PyAny>,
    c: &Bound<'_, PyAny>,
    k: &Bound<'_, PyAny>,
) -> PyResult<(TensorBSpline, Vec<usize>)> {
    let s = PyTensorBSpline::new(t, c, k)?;
    Ok((s.inner, s.trailing))
}
