//! Interpolation: curves (every parametrisation, knot placement and end condition), surfaces,
//! the natural cubic spline and cubic Hermite splines. Options are strings, parsed here into
//! the library's enums (the parsers are shared with the batch API).

use lekalo::{
    interpolate_with_end_derivatives as lk_end_derivatives, natural_cubic_spline as lk_natural,
    CubicHermite, CurveInterpolation, EndCondition, EndDerivative, KnotPlacement, Parametrization,
    TangentEstimate,
};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyInt, PyTuple};

use crate::convert::out_shape;
use crate::convert::{
    check_size, filled, floats, grid_points, owned_points, points_array, vec1, vec_array, IntArg,
};
use crate::curves::{PyBSplineCurve, PyBezierCurve};
use crate::error::{bad, function_err, lib_err};
use crate::surfaces::PyBSplineSurface;
use crate::words::word;
use lekalo::vocabulary;

/// `"uniform"`, `"chord"` (`"chord_length"`), `"centripetal"`, or a number: the exponent `e`
/// of `|Δq|^e`.
pub(crate) fn parametrization_arg(obj: &Bound<'_, PyAny>) -> PyResult<Parametrization> {
    if obj.is_instance_of::<PyFloat>() || obj.is_instance_of::<PyInt>() {
        return Ok(Parametrization::Exponent(obj.extract()?));
    }
    let s: String = obj.extract().map_err(|_| {
        bad(format!(
            "parametrization: expected one of {} or an exponent",
            vocabulary::PARAMETRIZATION.one_of()
        ))
    })?;
    word(&vocabulary::PARAMETRIZATION, "parametrization", &s)
}

/// `parametrization_arg` of the argument when given, chord length otherwise.
pub(crate) fn parametrization_or_chord(
    obj: Option<&Bound<'_, PyAny>>,
) -> PyResult<Parametrization> {
    obj.map_or(Ok(Parametrization::ChordLength), parametrization_arg)
}

/// A knot placement of the vocabulary (`"auto"`, `"averaged"`, `"uniform"`, `"at-params"`).
pub(crate) fn knots_arg(s: &str) -> PyResult<KnotPlacement> {
    word(&vocabulary::KNOT_PLACEMENT, "knots", s)
}

/// An end condition of the vocabulary (`"free"`, `"derivatives"`, `"second"`, `"natural"`,
/// `"periodic"`) with its derivatives `d_start`, `d_end` where it takes them
/// ([`lekalo::vocabulary::EndKind::condition`]).
pub(crate) fn end_arg(
    s: &str,
    d_start: Option<Vec<f64>>,
    d_end: Option<Vec<f64>>,
) -> PyResult<EndCondition> {
    word(&vocabulary::END_CONDITION, "end", s)?
        .condition(d_start, d_end)
        .map_err(lib_err)
}

/// Global B-spline interpolation through `points` (`(n, dim)`, or `(n,)` values): document
/// 000 and docs/theory/interpolation.md.
///
/// - `degree`: 3 by default, at most one less than the number of points;
/// - `parametrization`: 'uniform', 'chord' (default), 'centripetal' or an exponent;
/// - `knots`: `'auto'` (default), `'averaged'`, `'uniform'`, `'at-params'`;
/// - `end`: 'free' (default), 'natural', 'periodic', 'derivatives' / 'second' with `d_start`,
///   `d_end`;
/// - `params`: explicit parameters (strictly increasing; one more than the points for
///   'periodic'), replacing `parametrization`;
/// - `max_condition`: refuse systems whose condition estimate exceeds it;
/// - `drop_duplicates`: drop exact consecutive repeats of a point instead of refusing them.
///
/// >>> import numpy as np, lekalo
/// >>> q = np.array([[0, 0], [3, 4], [-1, 4], [-4, 0], [-4, -3]], dtype=float)
/// >>> c = lekalo.interpolate(q, degree=3)
/// >>> np.allclose(c(9 / 17), [-1, 4])
/// True
#[pyfunction]
#[pyo3(signature = (points, degree = IntArg::of(3), *, parametrization = None, knots = "auto", end = "free",
                    d_start = None, d_end = None, params = None, max_condition = None,
                    drop_duplicates = false), text_signature = "(points, degree=3, *, parametrization=None, knots=\"auto\", end=\"free\", d_start=None, d_end=None, params=None, max_condition=None, drop_duplicates=False)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn interpolate(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    degree: IntArg,
    parametrization: Option<&Bound<'_, PyAny>>,
    knots: &str,
    end: &str,
    d_start: Option<&Bound<'_, PyAny>>,
    d_end: Option<&Bound<'_, PyAny>>,
    params: Option<&Bound<'_, PyAny>>,
    max_condition: Option<f64>,
    drop_duplicates: bool,
) -> PyResult<PyBSplineCurve> {
    let degree = degree.get(
        "interpolate: degree",
        "lekalo's call is interpolate(points, degree, params=x): SciPy's \
         make_interp_spline(x, y, k) is lekalo.interpolate(y, k, params=x)",
    )?;
    let mut ci = CurveInterpolation::new(degree)
        .knot_placement(knots_arg(knots)?)
        .end_condition(end_arg(
            end,
            d_start.map(|d| vec1(d, "d_start")).transpose()?,
            d_end.map(|d| vec1(d, "d_end")).transpose()?,
        )?)
        .drop_duplicates(drop_duplicates);
    if let Some(p) = parametrization {
        ci = ci.parametrization(parametrization_arg(p)?);
    }
    if let Some(m) = max_condition {
        ci = ci.max_condition(m);
    }
    let pa = floats(points, "points")?;
    let pts = pa.curve_points("points", degree + 1)?;
    let curve = match params {
        Some(t) => {
            let ta = floats(t, "params")?;
            let t = ta.vector("params")?;
            py.detach(|| ci.interpolate_at(pts, t))
        }
        None => py.detach(|| ci.interpolate(pts)),
    }
    .map_err(lib_err)?;
    Ok(PyBSplineCurve::wrap(curve))
}

/// The parameters `t̄_k` on `[0, 1]` that `interpolate` would use for `points`.
#[pyfunction]
#[pyo3(signature = (points, parametrization = None))]
pub(crate) fn parametrize<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    parametrization: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let m = parametrization_or_chord(parametrization)?;
    let pa = floats(points, "points")?;
    let pts = pa.points("points")?;
    let t = py.detach(|| lekalo::parametrize(pts, m)).map_err(lib_err)?;
    Ok(vec_array(py, &t))
}

/// The non-zero B-spline basis functions of `degree` over the knots `t` at each parameter of
/// `x`: `(spans, values)`, `spans[j]` the knot span of `x[j]` and `values[j]` the `degree + 1`
/// values `N_{spans[j]−degree..=spans[j]}(x[j])` (`lekalo::basis::basis_functions_many`, P&T
/// A2.2): the banded design matrix. Parameters outside the domain are an error.
#[pyfunction]
pub(crate) fn basis_functions<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    degree: IntArg,
    x: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let degree = degree.get(
        "basis_functions: degree",
        "lekalo's call is basis_functions(t, degree, x): SciPy's \
         BSpline.design_matrix(x, t, k) is lekalo.design_matrix(x, t, k)",
    )?;
    let knots = lekalo::KnotVector::new(vec1(t, "t")?).map_err(lib_err)?;
    let xa = floats(x, "x")?;
    let xs = xa.vector("x")?;
    let (spans, values) = py
        .detach(|| lekalo::basis::basis_functions_many(&knots, degree, xs))
        .map_err(lib_err)?;
    let m = spans.len();
    let spans = numpy::PyArray1::from_vec(py, spans.into_iter().map(|s| s as i64).collect());
    Ok((
        spans.into_any(),
        crate::convert::array(py, values, &[m, degree + 1])?,
    ))
}

/// SciPy's `BSpline.design_matrix(x, t, k, extrapolate)` as the three arrays of its CSR matrix,
/// `(data, indices, indptr)`, each written once (`lekalo::basis::design_matrix_into`, P&T
/// A2.2): row `j` holds `N_{s−k..=s,k}(x_j)` in the columns `s − k..=s`, `s` the span of
/// `x_j`; the index arrays are int32 when the `len(x)·(k + 1)` entries allow it, as SciPy's,
/// else int64. With `extrapolate` the end spans' polynomials continue beyond `[t_k, t_n]`;
/// without, a point outside is an error.
///
/// >>> import numpy as np, lekalo
/// >>> data, indices, indptr = lekalo._lekalo.design_matrix_csr(np.array([0.0, 0.0, 1.0, 2.0, 2.0]), 1, np.array([0.5, 2.0]))
/// >>> data.tolist(), indices.tolist(), indptr.tolist()
/// ([0.5, 0.5, 0.0, 1.0], [0, 1, 1, 2], [0, 2, 4])
#[pyfunction]
#[pyo3(signature = (t, k, x, extrapolate = false))]
pub(crate) fn design_matrix_csr<'py>(
    py: Python<'py>,
    t: &Bound<'py, PyAny>,
    k: IntArg,
    x: &Bound<'py, PyAny>,
    extrapolate: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let k = k.count("k")?;
    let knots = lekalo::KnotVector::new(vec1(t, "t")?).map_err(lib_err)?;
    let xa = floats(x, "x")?;
    let xs = xa.vector("x")?;
    let w = k
        .checked_add(1)
        .ok_or_else(|| bad(format!("k: {k} is not a degree")))?;
    let nnz = check_size("design matrix", &[xs.len(), w])?;
    if i32::try_from(nnz).is_ok_and(|v| v < i32::MAX) {
        csr_arrays::<i32>(py, &knots, k, xs, extrapolate)
    } else {
        csr_arrays::<i64>(py, &knots, k, xs, extrapolate)
    }
}

/// [`design_matrix_csr`] with index arrays of type `I` (wide enough for `len(xs)·(k + 1)`).
fn csr_arrays<'py, I>(
    py: Python<'py>,
    knots: &lekalo::KnotVector,
    k: usize,
    xs: &[f64],
    extrapolate: bool,
) -> PyResult<Bound<'py, PyTuple>>
where
    I: numpy::Element + Copy + Default + Send + TryFrom<usize>,
{
    let w = k + 1;
    let nnz = xs.len() * w;
    let data = PyArray1::<f64>::zeros(py, nnz, false);
    let indices = PyArray1::<I>::zeros(py, nnz, false);
    let indptr = PyArray1::<I>::zeros(py, xs.len() + 1, false);
    {
        let (mut d, mut ix, mut ip) = (data.readwrite(), indices.readwrite(), indptr.readwrite());
        let not_contiguous = |e: numpy::AsSliceError| bad(format!("design matrix: {e}"));
        let d = d.as_slice_mut().map_err(not_contiguous)?;
        let ix = ix.as_slice_mut().map_err(not_contiguous)?;
        let ip = ip.as_slice_mut().map_err(not_contiguous)?;
        // every index is below nnz, which fits I (the caller's choice): the default never shows
        let index = |v: usize| I::try_from(v).unwrap_or_default();
        py.detach(|| {
            for (j, p) in ip.iter_mut().enumerate() {
                *p = index(j * w);
            }
            lekalo::basis::design_matrix_into(knots, k, xs, extrapolate, d, |j, first| {
                for (i, slot) in ix[j * w..(j + 1) * w].iter_mut().enumerate() {
                    *slot = index(first + i);
                }
            })
        })
        .map_err(lib_err)?;
    }
    PyTuple::new(py, [data.into_any(), indices.into_any(), indptr.into_any()])
}

/// The natural cubic spline `y(x)` through `(x_k, y_k)` (zero second derivatives at the ends;
/// document 002 §C.2), as a B-spline with knots at the `x_k`.
#[pyfunction]
pub(crate) fn natural_cubic_spline(
    py: Python<'_>,
    x: &Bound<'_, PyAny>,
    y: &Bound<'_, PyAny>,
) -> PyResult<PyBSplineCurve> {
    let xa = floats(x, "x")?;
    let xs = xa.vector("x")?;
    let ya = floats(y, "y")?;
    let ys = ya.points("y")?;
    let c = py.detach(|| lk_natural(xs, ys)).map_err(function_err)?;
    Ok(PyBSplineCurve::wrap(c))
}

/// Reads `[(order, value), ...]`: derivative conditions at one end, each value with `dim`
/// components (a number for `dim = 1`).
fn end_derivatives_arg(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Vec<EndDerivative>> {
    let Some(obj) = obj else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for item in obj.try_iter()? {
        let item = item?;
        let (order, value): (usize, Bound<'_, PyAny>) = item.extract().map_err(|_| {
            bad(format!(
                "{what}: expected a list of (order, value) pairs, order a non-negative integer"
            ))
        })?;
        let value = floats(&value, what)?.data().to_vec();
        out.push(EndDerivative::new(order, value));
    }
    Ok(out)
}

/// The B-spline of degree `k` on the knots `t` through `(x_j, y_j)` with derivative conditions
/// chosen per end: `start` and `end` are lists of `(order, value)`, `C^(order)(x_0) = value` and
/// `C^(order)(x_last) = value` (`docs/theory/interpolation.md#derivative-conditions-per-end`).
/// The points and conditions must number the control points, `len(t) - k - 1`.
///
/// >>> import numpy as np, lekalo
/// >>> x = np.array([0.0, 1.0, 2.0, 3.0]); t = [0, 0, 0, 0, 1, 2, 3, 3, 3, 3]
/// >>> c = lekalo.interpolate_with_end_derivatives(x, x ** 3, t, 3, start=[(1, 0.0)], end=[(2, 18.0)])
/// >>> bool(np.allclose(c(np.linspace(0, 3, 7))[:, 0], np.linspace(0, 3, 7) ** 3))
/// True
#[pyfunction]
#[pyo3(signature = (x, y, t, k = IntArg::of(3), *, start = None, end = None), text_signature = "(x, y, t, k=3, *, start=None, end=None)")]
pub(crate) fn interpolate_with_end_derivatives(
    py: Python<'_>,
    x: &Bound<'_, PyAny>,
    y: &Bound<'_, PyAny>,
    t: &Bound<'_, PyAny>,
    k: IntArg,
    start: Option<&Bound<'_, PyAny>>,
    end: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyBSplineCurve> {
    let k = k.count("k")?;
    let xa = floats(x, "x")?;
    // interpolate_with_end_derivatives checks every parameter (finite, increasing)
    let xs = xa.vector_for_checking_call("x")?;
    let ya = floats(y, "y")?;
    let ys = ya.points("y")?;
    let knots = lekalo::KnotVector::new(vec1(t, "t")?).map_err(lib_err)?;
    let start = end_derivatives_arg(start, "start")?;
    let end = end_derivatives_arg(end, "end")?;
    let c = py
        .detach(|| lk_end_derivatives(ys, xs, &knots, k, &start, &end))
        .map_err(function_err)?;
    Ok(PyBSplineCurve::wrap(c))
}

/// Tensor-product interpolation of a grid `(nu, nv, dim)` of points (document 000 applied in
/// both directions): the B-spline surface through every grid point.
#[pyfunction]
#[pyo3(signature = (grid, degree_u = IntArg::of(3), degree_v = IntArg::of(3), *, parametrization = None, max_condition = None), text_signature = "(grid, degree_u=3, degree_v=3, *, parametrization=None, max_condition=None)")]
pub(crate) fn interpolate_surface(
    py: Python<'_>,
    grid: &Bound<'_, PyAny>,
    degree_u: IntArg,
    degree_v: IntArg,
    parametrization: Option<&Bound<'_, PyAny>>,
    max_condition: Option<f64>,
) -> PyResult<PyBSplineSurface> {
    let degree_u = degree_u.count("degree_u")?;
    let degree_v = degree_v.count("degree_v")?;
    let m = parametrization_or_chord(parametrization)?;
    let ga = floats(grid, "grid")?;
    let (pts, (nu, nv)) = grid_points(&ga, "grid")?;
    let mut interp = lekalo::SurfaceInterpolation::new(degree_u, degree_v).parametrization(m);
    if let Some(mc) = max_condition {
        interp = interp.max_condition(mc);
    }
    let inner = py
        .detach(|| interp.interpolate(pts, nu, nv))
        .map_err(lib_err)?;
    Ok(PyBSplineSurface { inner })
}

/// The cubic Bezier curve through four points at parameters 0, 1/3, 2/3, 1.
#[pyfunction]
pub(crate) fn cubic_through_four_points(points: &Bound<'_, PyAny>) -> PyResult<PyBezierCurve> {
    let pa = floats(points, "points")?;
    let c = lekalo::cubic_through_four_points(pa.points("points")?).map_err(lib_err)?;
    Ok(PyBezierCurve::wrap(c))
}

fn estimate_arg(s: &str, tension: f64) -> PyResult<TangentEstimate> {
    match s {
        "finite_difference" => Ok(TangentEstimate::FiniteDifference),
        "catmull_rom" => Ok(TangentEstimate::CatmullRom),
        "cardinal" => Ok(TangentEstimate::Cardinal { tension }),
        "monotone" => Ok(TangentEstimate::Monotone),
        _ => Err(bad(format!(
            "tangents: unknown value {s:?}; use 'finite_difference', 'catmull_rom', 'cardinal' or 'monotone'"
        ))),
    }
}

/// A C¹ piecewise cubic Hermite curve (document 002 §C.3): points and tangents at increasing
/// parameters. Build it with tangents given, or estimated (`from_points`, `function`).
///
/// >>> import numpy as np, lekalo
/// >>> h = lekalo.CubicHermite.function([0, 1, 2, 3], [0, 1, 1, 2], tangents="monotone")
/// >>> h(1.5)
/// array([1.])
#[pyclass(module = "lekalo", name = "CubicHermite", frozen, eq)]
#[derive(PartialEq)]
pub(crate) struct PyCubicHermite {
    inner: CubicHermite,
}

#[pymethods]
impl PyCubicHermite {
    #[new]
    fn new(
        params: &Bound<'_, PyAny>,
        points: &Bound<'_, PyAny>,
        tangents: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let t = vec1(params, "params")?;
        let p = owned_points(points, "points")?;
        let d = owned_points(tangents, "tangents")?;
        Ok(Self {
            inner: CubicHermite::new(t, p, d).map_err(lib_err)?,
        })
    }

    /// A parametric Hermite curve through `points` with parameters on `[0, 1]` and tangents
    /// estimated by `tangents` (`'finite_difference'`, `'catmull_rom'`, `'cardinal'` with `tension`,
    /// 'monotone').
    #[staticmethod]
    #[pyo3(signature = (points, parametrization = None, tangents = "catmull_rom", tension = 0.0))]
    fn from_points(
        points: &Bound<'_, PyAny>,
        parametrization: Option<&Bound<'_, PyAny>>,
        tangents: &str,
        tension: f64,
    ) -> PyResult<Self> {
        let m = match parametrization {
            Some(p) => parametrization_arg(p)?,
            None => Parametrization::ChordLength,
        };
        let pa = floats(points, "points")?;
        let h =
            CubicHermite::from_points(pa.points("points")?, m, estimate_arg(tangents, tension)?)
                .map_err(lib_err)?;
        Ok(Self { inner: h })
    }

    /// The function `y(x)` through `(x_k, y_k)` (`x` strictly increasing); 'monotone' keeps
    /// monotone data monotone (Fritsch–Carlson, like SciPy's `PchipInterpolator` in spirit).
    #[staticmethod]
    #[pyo3(signature = (x, y, tangents = "monotone", tension = 0.0))]
    fn function(
        x: &Bound<'_, PyAny>,
        y: &Bound<'_, PyAny>,
        tangents: &str,
        tension: f64,
    ) -> PyResult<Self> {
        let xa = floats(x, "x")?;
        let ya = floats(y, "y")?;
        let h = CubicHermite::function(
            xa.vector("x")?,
            ya.points("y")?,
            estimate_arg(tangents, tension)?,
        )
        .map_err(function_err)?;
        Ok(Self { inner: h })
    }

    /// The parameters.
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vec_array(py, self.inner.params())
    }

    /// The points `(n, dim)`.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_array(py, self.inner.points())
    }

    /// The tangents `(n, dim)`.
    #[getter]
    fn tangents<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        points_array(py, self.inner.tangents())
    }

    /// The parameter domain.
    #[getter]
    fn domain(&self) -> (f64, f64) {
        self.inner.domain()
    }

    /// Points at `t` (any shape): `t.shape + (dim,)`.
    fn __call__(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let ta = floats(t, "t")?;
        let ts = ta.data();
        let dim = self.inner.points().dim();
        check_size("t", &[ts.len(), dim])?;
        let out = filled(py, &out_shape(&ta, &[dim]), |out| {
            ts.iter()
                .zip(out.chunks_exact_mut(dim))
                .try_for_each(|(&t, o)| {
                    o.copy_from_slice(&self.inner.eval(t)?);
                    Ok(())
                })
        })?;
        Ok(out.unbind())
    }

    /// The same curve as a B-spline (knots of multiplicity 2 at the parameters).
    fn to_bspline(&self) -> PyBSplineCurve {
        PyBSplineCurve::wrap(self.inner.to_bspline())
    }

    /// The cubic Bezier pieces.
    fn to_bezier_segments(&self) -> Vec<PyBezierCurve> {
        self.inner
            .to_bezier_segments()
            .into_iter()
            .map(PyBezierCurve::wrap)
            .collect()
    }

    /// Pickled as its parameters, points and tangents (bit for bit).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let cls = py.get_type::<Self>();
        let args = PyTuple::new(py, [self.params(py), self.points(py)?, self.tangents(py)?])?;
        PyTuple::new(py, [cls.into_any(), args.into_any()])
    }

    fn __repr__(&self) -> String {
        format!(
            "CubicHermite(n_points={}, dim={})",
            self.inner.params().len(),
            self.inner.points().dim()
        )
    }
}
