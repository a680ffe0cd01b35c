//! `TensorBSpline`: tensor-product B-splines in `N` variables with SciPy's `NdBSpline`
//! conventions: knots `t` (one 1-D array per variable), coefficients `c` of shape
//! `(n_1, …, n_N, *trailing)` in C order (the library's net, first variable slowest, with
//! `dim = prod(trailing)`), degrees `k`. Evaluation at `(..., N)` arrays gives
//! `(..., *trailing)`.

use lekalo::tensor::tensor_design_matrix as lk_design_matrix;
use lekalo::{
    tensor_grid_least_squares, tensor_grid_smoothing, tensor_scattered_least_squares_with,
    tensor_scattered_smoothing, Arg, KnotLimit, KnotVector, Points, PointsRef, RankDeficiency,
    ScatteredSmoothingOptions, TensorBSpline, TensorInterpolation,
};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

use crate::convert::{
    array, check_size, counts, filled, floats, vec1, vec_array, FloatArray, IntArg,
};
use crate::error::{argument, bad, lib_err, named};

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
    inner: TensorBSpline,
    /// The coefficients' axes after the `N` net axes (`()` for scalar values).
    trailing: Vec<usize>,
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
fn degrees_or_cubic(k: Option<&Bound<'_, PyAny>>, n: usize) -> PyResult<Vec<usize>> {
    match k {
        Some(k) => degrees_arg(k, n),
        None => Ok(vec![3; n]),
    }
}

/// Values on the grid of the coordinate `lists` (`va` of shape `(m_1, …, m_N, *trailing)`) as
/// rows of the trailing size, and the trailing axes.
fn grid_values<'a>(
    va: &'a FloatArray<'_>,
    lists: &[Vec<f64>],
) -> PyResult<(PointsRef<'a>, Vec<usize>)> {
    let n = lists.len();
    let shape = va.shape();
    let sizes: Vec<usize> = lists.iter().map(Vec::len).collect();
    if shape.len() < n || shape[..n] != sizes[..] {
        return Err(bad(format!(
            "values: shape {shape:?} does not start with the axes' lengths {sizes:?}"
        )));
    }
    let trailing = shape[n..].to_vec();
    let dim: usize = trailing.iter().product();
    let pts = PointsRef::from_flat(dim.max(1), va.data()).map_err(|e| named("values", &e))?;
    Ok((pts, trailing))
}

/// One 1-D float array per variable.
fn axes_arg(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Vec<f64>>> {
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
        let arrays: Vec<Bound<'py, PyAny>> = self
            .inner
            .knots()
            .iter()
            .map(|k| crate::convert::vec_array(py, k.as_slice()))
            .collect();
        PyTuple::new(py, arrays)
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
        let n = self.inner.n_vars();
        let xa = floats(x, "x")?;
        let shape = xa.shape();
        if shape.last() != Some(&n) {
            return Err(bad(format!(
                "x: shape {shape:?}; the last axis must hold the {n} coordinates of a point"
            )));
        }
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
    /// `docs/theory/tensor.md#interpolation-on-grids`).
    #[staticmethod]
    #[pyo3(signature = (axes, values, degrees = None, knots = None))]
    fn interpolate_grid(
        py: Python<'_>,
        axes: &Bound<'_, PyAny>,
        values: &Bound<'_, PyAny>,
        degrees: Option<&Bound<'_, PyAny>>,
        knots: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let lists = axes_arg(axes, "axes")?;
        let n = lists.len();
        let given = knots.map(|k| knots_arg(k, n)).transpose()?;
        let degrees = degrees_or_cubic(degrees, n)?;
        let va = floats(values, "values")?;
        let (pts, trailing) = grid_values(&va, &lists)?;
        let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
        let mut interpolation = TensorInterpolation::new(degrees);
        if let Some(given) = given {
            interpolation = interpolation.knot_vectors(given);
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
        Ok(Self { inner, trailing })
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

/// Knot vectors `t` (one 1-D array per variable) for the fits: validated, `t[a]` named in the
/// errors.
fn knot_vectors_arg(t: &Bound<'_, PyAny>) -> PyResult<Vec<KnotVector>> {
    axes_arg(t, "t")?
        .into_iter()
        .enumerate()
        .map(|(a, k)| KnotVector::new(k).map_err(|e| named(&format!("t[{a}]"), &e)))
        .collect()
}

/// The argument of a fit an error is about (`x` or `axes` for the coordinates).
fn fit_err(e: lekalo::Error, coordinates: &str) -> PyErr {
    match e {
        lekalo::Error::Degree { .. } => named("k", &e),
        lekalo::Error::ParameterOutOfDomain { .. }
        | lekalo::Error::KnotsNotSorted { .. }
        | lekalo::Error::NotIncreasing { .. }
        | lekalo::Error::Repeated { .. }
        | lekalo::Error::NonFinite { .. } => named(coordinates, &e),
        lekalo::Error::InvalidDataWeight { .. } => named("w", &e),
        other => lib_err(other),
    }
}

/// The least-squares tensor-product spline on a grid with given knots
/// (`tensor_grid_least_squares`, `docs/theory/tensor.md#least-squares-on-grids`): `values` of
/// shape `(m_1, …, m_N, *trailing)` at the coordinates `axes` (one strictly increasing 1-D
/// array per variable), knots `t` (one 1-D array per variable, at most `m_a + k_a + 1` knots),
/// degrees `k` (one integer or one per variable). SciPy's `make_lsq_spline` in each direction;
/// for `N = 2`, `RectBivariateSpline`'s least squares on given knots.
#[pyfunction]
#[pyo3(signature = (axes, values, t, k = None))]
pub(crate) fn fit_tensor_grid(
    py: Python<'_>,
    axes: &Bound<'_, PyAny>,
    values: &Bound<'_, PyAny>,
    t: &Bound<'_, PyAny>,
    k: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyTensorBSpline> {
    let lists = axes_arg(axes, "axes")?;
    let n = lists.len();
    let (knots, degrees) = knots_and_degrees(t, k, n, &format!("{n} axes"))?;
    let va = floats(values, "values")?;
    let (pts, trailing) = grid_values(&va, &lists)?;
    let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let inner = py
        .detach(|| tensor_grid_least_squares(&refs, pts, &degrees, knots))
        .map_err(|e| fit_err(e, "axes"))?;
    Ok(PyTensorBSpline { inner, trailing })
}

/// The smoothing spline on a grid (`tensor_grid_smoothing`,
/// `docs/theory/tensor.md#smoothing-on-grids`): the tensor-product spline with the fewest knots
/// found whose residual sum of squares over the grid is at most `s` (`s = 0`: interpolation on
/// FITPACK's knots). `values` of shape `(m_1, …, m_N, *trailing)` at the coordinates `axes`
/// (one strictly increasing 1-D array per variable), degrees `k` (one integer or one per
/// variable, default 3), `bbox` one `(a, b)` per variable around its coordinates (default:
/// their range). Returns `(spline, residual, p)`, `p` the smoothing weight (`None` for a
/// least-squares result). SciPy's `RectBivariateSpline(x, y, z, s=…)` for `N = 2`.
#[pyfunction]
#[pyo3(signature = (axes, values, s, k = None, *, bbox = None))]
pub(crate) fn fit_tensor_grid_smoothing(
    py: Python<'_>,
    axes: &Bound<'_, PyAny>,
    values: &Bound<'_, PyAny>,
    s: f64,
    k: Option<&Bound<'_, PyAny>>,
    bbox: Option<Vec<(f64, f64)>>,
) -> PyResult<(PyTensorBSpline, f64, Option<f64>)> {
    let lists = axes_arg(axes, "axes")?;
    let n = lists.len();
    let degrees = degrees_or_cubic(k, n)?;
    if let Some(b) = &bbox {
        if b.len() != n {
            return Err(bad(format!(
                "bbox: {} intervals for {n} axes; give one (a, b) per variable",
                b.len()
            )));
        }
    }
    let va = floats(values, "values")?;
    let (pts, trailing) = grid_values(&va, &lists)?;
    let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let f = py
        .detach(|| tensor_grid_smoothing(&refs, pts, &degrees, s, bbox.as_deref()))
        .map_err(|e| match e {
            lekalo::Error::NegativeSmoothing { .. } => named("s", &e),
            lekalo::Error::ParameterOutOfDomain { .. } | lekalo::Error::EmptyDomain { .. } => {
                named("bbox", &e)
            }
            other => fit_err(other, "axes"),
        })?;
    Ok((
        PyTensorBSpline {
            inner: f.spline,
            trailing,
        },
        f.residual,
        f.p,
    ))
}

/// The rank choice of the scattered fits: `eps = None` refuses a control point the data do not
/// determine, a number is FITPACK's minimal-norm solution with that rank threshold.
fn rank_arg(eps: Option<f64>) -> RankDeficiency {
    eps.map_or(RankDeficiency::Refuse, |eps| RankDeficiency::MinimumNorm {
        eps,
    })
}

/// Points `x` of shape `(npts, N)` of a scattered fit: the array, `npts` and `N`.
fn points_arg<'py>(x: &Bound<'py, PyAny>) -> PyResult<(FloatArray<'py>, usize, usize)> {
    let xa = floats(x, "x")?;
    let xshape = xa.shape();
    let [npts, n] = xshape[..] else {
        return Err(bad(format!(
            "x: shape {xshape:?}; give the points as an array of shape (npts, N)"
        )));
    };
    Ok((xa, npts, n))
}

/// The knot vectors `t` (one per variable) and degrees `k` (default 3 in each) of a space in
/// `n` variables; `of` says what the `n` variables are, for the message.
fn knots_and_degrees(
    t: &Bound<'_, PyAny>,
    k: Option<&Bound<'_, PyAny>>,
    n: usize,
    of: &str,
) -> PyResult<(Vec<KnotVector>, Vec<usize>)> {
    let knots = knot_vectors_arg(t)?;
    if knots.len() != n {
        return Err(bad(format!(
            "t: {} knot vectors for {of}; give one per variable",
            knots.len()
        )));
    }
    let degrees = degrees_or_cubic(k, n)?;
    Ok((knots, degrees))
}

/// Values `y` of shape `(npts, *trailing)` of a scattered fit: the array and `trailing`.
fn values_arg<'py>(y: &Bound<'py, PyAny>, npts: usize) -> PyResult<(FloatArray<'py>, Vec<usize>)> {
    let ya = floats(y, "y")?;
    let yshape = ya.shape();
    if yshape.first() != Some(&npts) {
        return Err(bad(format!(
            "y: shape {yshape:?}; give one value (row) per point of x, {npts} in all"
        )));
    }
    let trailing = yshape[1..].to_vec();
    Ok((ya, trailing))
}

/// The least-squares tensor-product spline through scattered points with given knots
/// (`tensor_scattered_least_squares_with`,
/// `docs/theory/tensor.md#least-squares-on-scattered-data`): points `x` of shape `(npts, N)`,
/// values `y` of shape `(npts, *trailing)`, knots `t` (one 1-D array per variable), degrees `k`,
/// weights `w` (one per point). `eps = None` refuses a control point the data do not determine
/// (`InputError` naming it); a number in `(0, 1)` gives FITPACK's minimal-norm solution, the
/// pivots at most `sqrt(eps)` times the largest taken as zero
/// (`docs/theory/tensor.md#rank-deficient-least-squares`). Returns
/// `(spline, residuals, weighted_rss)`, and `(spline, residuals, weighted_rss, rank)` with
/// `full_output=True` (SciPy's convention for extra results); SciPy's `LSQBivariateSpline` for
/// `N = 2`.
#[pyfunction]
#[pyo3(signature = (x, y, t, k = None, *, w = None, eps = None, full_output = false))]
#[allow(clippy::too_many_arguments)] // one parameter per Python argument
pub(crate) fn fit_tensor_scattered<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: Option<&Bound<'py, PyAny>>,
    w: Option<&Bound<'py, PyAny>>,
    eps: Option<f64>,
    full_output: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let (xa, npts, n) = points_arg(x)?;
    let (knots, degrees) = knots_and_degrees(t, k, n, &format!("points in {n} variables"))?;
    let (ya, trailing) = values_arg(y, npts)?;
    let dim: usize = trailing.iter().product();
    let xs = PointsRef::from_flat(n.max(1), xa.data()).map_err(|e| named("x", &e))?;
    let ys = PointsRef::from_flat(dim.max(1), ya.data()).map_err(|e| named("y", &e))?;
    let wa = w.map(|w| floats(w, "w")).transpose()?;
    let wv = wa.as_ref().map(|w| w.vector("w")).transpose()?;
    let f = py
        .detach(|| tensor_scattered_least_squares_with(xs, ys, wv, &degrees, knots, rank_arg(eps)))
        .map_err(|e| match e {
            lekalo::Error::InvalidArgument { .. } if e.arg() == Some(Arg::Eps) => named("eps", &e),
            other => fit_err(other, "x"),
        })?;
    let spline = PyTensorBSpline {
        inner: f.spline,
        trailing,
    }
    .into_pyobject(py)?
    .into_any();
    let residuals = vec_array(py, &f.residuals);
    let rss = f.weighted_rss.into_pyobject(py)?.into_any();
    if full_output {
        PyTuple::new(
            py,
            [spline, residuals, rss, f.rank.into_pyobject(py)?.into_any()],
        )
    } else {
        PyTuple::new(py, [spline, residuals, rss])
    }
}

/// `(spline, residual, p, rank, limit)` of `fit_tensor_scattered_smoothing`.
type ScatteredSmoothing = (
    PyTensorBSpline,
    f64,
    Option<f64>,
    usize,
    Option<&'static str>,
);

/// The smoothing spline of scattered data (`tensor_scattered_smoothing`,
/// `docs/theory/tensor.md#smoothing-scattered-data`): the tensor-product spline with FITPACK
/// `surfit`'s knots whose weighted residual sum of squares is `s` (within 0.1 %, never above).
/// Points `x` of shape `(npts, N)`, values `y` of shape `(npts, *trailing)`, degrees `k` (one
/// integer or one per variable, default 3), weights `w` (one per point, multiplying the squared
/// residual), `bbox` one `(a, b)` per variable (default: the range of the points), `max_knots`
/// the largest knot count per variable (end knots included, FITPACK's `nxest`), `eps` the rank
/// choice of `fit_tensor_scattered`. Returns `(spline, residual, p, rank, limit)`: `p` the
/// smoothing weight (`None` for a least-squares result), `rank` that of the last system, and
/// `limit` why the knot rounds stopped above `s` (`None`, `"max-knots"`,
/// `"coefficients-exceed-data"` or `"knots-coincide"`). SciPy's `SmoothBivariateSpline` for
/// `N = 2`.
#[pyfunction]
#[pyo3(signature = (x, y, s, k = None, *, w = None, bbox = None, max_knots = None, eps = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_tensor_scattered_smoothing<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    s: f64,
    k: Option<&Bound<'py, PyAny>>,
    w: Option<&Bound<'py, PyAny>>,
    bbox: Option<Vec<(f64, f64)>>,
    max_knots: Option<Vec<usize>>,
    eps: Option<f64>,
) -> PyResult<ScatteredSmoothing> {
    let (xa, npts, n) = points_arg(x)?;
    let (ya, trailing) = values_arg(y, npts)?;
    let wa = w.map(|w| floats(w, "w")).transpose()?;
    let degrees = degrees_or_cubic(k, n)?;
    let dim: usize = trailing.iter().product();
    let xs = PointsRef::from_flat(n.max(1), xa.data()).map_err(|e| named("x", &e))?;
    let ys = PointsRef::from_flat(dim.max(1), ya.data()).map_err(|e| named("y", &e))?;
    let wv = wa.as_ref().map(|w| w.vector("w")).transpose()?;
    let options = ScatteredSmoothingOptions {
        bbox,
        max_knots,
        rank: rank_arg(eps),
    };
    let f = py
        .detach(|| tensor_scattered_smoothing(xs, ys, wv, &degrees, s, &options))
        .map_err(|e| match e {
            lekalo::Error::NegativeSmoothing { .. } => named("s", &e),
            lekalo::Error::EmptyDomain { .. } => named("bbox", &e),
            lekalo::Error::InvalidArgument { .. } | lekalo::Error::LengthMismatch { .. }
                if matches!(e.arg(), Some(Arg::Eps | Arg::MaxKnots | Arg::Bbox)) =>
            {
                named(e.arg().and_then(argument).unwrap_or("x"), &e)
            }
            other => fit_err(other, "x"),
        })?;
    let limit = f.limit.map(|l| match l {
        KnotLimit::MaxKnots => "max-knots",
        KnotLimit::CoefficientsExceedData => "coefficients-exceed-data",
        KnotLimit::KnotsCoincide => "knots-coincide",
    });
    Ok((
        PyTensorBSpline {
            inner: f.spline,
            trailing,
        },
        f.residual,
        f.p,
        f.rank,
        limit,
    ))
}

/// A CSR matrix for Python: `(data, indices, indptr, shape)`.
type Csr<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    (usize, usize),
);

/// The design matrix of the tensor-product B-spline space with knots `t` (one 1-D array per
/// variable) and degrees `k` at the points `x` of shape `(npts, N)`
/// (`lekalo::tensor::tensor_design_matrix`, `docs/theory/tensor.md#design-matrix`; SciPy's
/// `NdBSpline.design_matrix`): `(data, indices, indptr, shape)` of a CSR matrix with one row per
/// point and one column per control point (the net in C order), each row the Kronecker product
/// of the per-variable basis rows. `extrapolate` continues the end spans' polynomials beyond the
/// domain; without it a point outside is an error.
#[pyfunction]
#[pyo3(signature = (x, t, k = None, *, extrapolate = true))]
pub(crate) fn tensor_design_matrix<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: Option<&Bound<'py, PyAny>>,
    extrapolate: bool,
) -> PyResult<Csr<'py>> {
    let xa = floats(x, "x")?;
    let xshape = xa.shape();
    let [_, n] = xshape[..] else {
        return Err(bad(format!(
            "x: shape {xshape:?}; give the points as an array of shape (npts, N)"
        )));
    };
    let (knots, degrees) = knots_and_degrees(t, k, n, &format!("points in {n} variables"))?;
    let xs = xa.data();
    let m = py
        .detach(|| lk_design_matrix(&degrees, &knots, xs, extrapolate))
        .map_err(|e| fit_err(e, "x"))?;
    let to_i64 = |v: Vec<usize>| -> Vec<i64> {
        v.into_iter()
            .map(|i| i64::try_from(i).unwrap_or(i64::MAX))
            .collect()
    };
    let indptr: Vec<usize> = (0..=m.rows).map(|j| j * m.row_len).collect();
    Ok((
        vec_array(py, &m.values),
        numpy::PyArray1::from_vec(py, to_i64(m.indices)).into_any(),
        numpy::PyArray1::from_vec(py, to_i64(indptr)).into_any(),
        (m.rows, m.columns),
    ))
}

/// Registers the fits of tensor-product splines.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(tensor_design_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_grid, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_grid_smoothing, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_scattered, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_scattered_smoothing, m)?)?;
    Ok(())
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
