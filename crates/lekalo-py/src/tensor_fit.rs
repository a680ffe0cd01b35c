//! The fits of tensor-product splines in `N` variables: least squares on grids and on
//! scattered points with given knots (with a penalty for cells without data), smoothing with
//! FITPACK's knots or with a penalty weight per direction, and the design matrix (`docs/theory/tensor.md`). Parsing and conversion
//! only; the fits are the library's.

use lekalo::fit::{
    constrained_surface_grid_smoothing_condition, constrained_surface_grid_smoothing_spline, Lambda,
};
use lekalo::tensor::tensor_design_matrix as lk_design_matrix;
use lekalo::{
    tensor_grid_gcv_score as lk_tensor_grid_gcv_score, tensor_grid_least_squares,
    tensor_grid_smoothing, tensor_grid_smoothing_spline, tensor_scattered_least_squares_with,
    tensor_scattered_penalized_least_squares, tensor_scattered_smoothing, Arg, KnotLimit,
    KnotVector, PointsRef, RankDeficiency, ScatteredSmoothingOptions, TensorBSpline,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::convert::{floats, vec_array, FloatArray};
use crate::error::{argument, bad, lib_err, named};
use crate::shape::SurfaceShapeArgs;
use crate::tensor::{axes_arg, degrees_or_cubic, grid_values, PyTensorBSpline};

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
/// `N = 2`. `penalty > 0` adds `penalty` times the squared second differences of the net along
/// every direction, which fills the cells without data from their neighbours
/// (`tensor_scattered_penalized_least_squares`; `fit_surface_scattered`'s penalty for `N = 2`);
/// it takes no `eps`.
#[pyfunction]
#[pyo3(signature = (x, y, t, k = None, *, w = None, eps = None, full_output = false, penalty = 0.0))]
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
    penalty: f64,
) -> PyResult<Bound<'py, PyTuple>> {
    if penalty != 0.0 && eps.is_some() {
        return Err(bad(
            "penalty: it fills the cells without data, eps answers them by the minimal-norm \
             solution; give one of them"
                .into(),
        ));
    }
    let (xa, npts, n) = points_arg(x)?;
    let (knots, degrees) = knots_and_degrees(t, k, n, &format!("points in {n} variables"))?;
    let (ya, trailing) = values_arg(y, npts)?;
    let dim: usize = trailing.iter().product();
    let xs = PointsRef::from_flat(n.max(1), xa.data()).map_err(|e| named("x", &e))?;
    let ys = PointsRef::from_flat(dim.max(1), ya.data()).map_err(|e| named("y", &e))?;
    let wa = w.map(|w| floats(w, "w")).transpose()?;
    let wv = wa.as_ref().map(|w| w.vector("w")).transpose()?;
    let f = py
        .detach(|| {
            if penalty != 0.0 {
                tensor_scattered_penalized_least_squares(xs, ys, wv, &degrees, knots, penalty)
            } else {
                tensor_scattered_least_squares_with(xs, ys, wv, &degrees, knots, rank_arg(eps))
            }
        })
        .map_err(|e| match e {
            lekalo::Error::InvalidArgument { .. } if e.arg() == Some(Arg::Eps) => named("eps", &e),
            _ if e.arg() == Some(Arg::Lambda) => named("penalty", &e),
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

/// The penalty weights `lam` of the smoothing spline on a grid with `n` axes: `None` (GCV in
/// every direction), one number for all, or one number or `None` (GCV) per axis.
fn lambdas_arg(lam: Option<&Bound<'_, PyAny>>, n: usize) -> PyResult<Vec<Lambda>> {
    let Some(lam) = lam.filter(|l| !l.is_none()) else {
        return Ok(vec![Lambda::Gcv; n]);
    };
    if let Ok(v) = lam.extract::<f64>() {
        return Ok(vec![Lambda::Given(v); n]);
    }
    let items: Vec<Option<f64>> = lam.extract().map_err(|_| {
        bad(format!(
            "lam: give None (GCV), a number λ ≥ 0, or one number or None per axis, not {}",
            lam.get_type()
                .name()
                .map_or_else(|_| "this".into(), |t| t.to_string())
        ))
    })?;
    if items.len() != n {
        return Err(bad(format!(
            "lam: {} weights for {n} axes; give one number or None (GCV) per axis, or one for all",
            items.len()
        )));
    }
    Ok(items
        .into_iter()
        .map(|l| l.map_or(Lambda::Gcv, Lambda::Given))
        .collect())
}

/// The smoothing spline on a grid with a penalty weight per direction
/// (`tensor_grid_smoothing_spline`, `docs/theory/tensor.md#penalised-smoothing-on-grids`):
/// `make_smoothing_spline` applied along each axis in turn (the separable "sandwich"
/// smoother), cubic with a knot at every coordinate. `values` of shape `(m_1, …, m_N,
/// *trailing)` at the coordinates `axes` (one strictly increasing 1-D array per variable, at
/// least 3 each); `lam` `None` (every weight by generalised cross-validation over the grid), a
/// number `λ ≥ 0` for every axis, or one number or `None` (GCV) per axis. Returns `(spline,
/// report)`: `report["lam"]` the weights used, `"gcv"` the GCV score, `"residual"` the residual
/// sum of squares, `"trace"` the smoother's trace. One axis gives `fit_smoothing`'s spline.
///
/// A table `z(u, v)` (two axes, one value a node) may keep shapes, on the whole domain or on
/// boxes of it, with the keywords of `fit_surface_grid` (`increasing`, `decreasing`, `min`,
/// `max`; `docs/theory/fitting.md#shape-constrained-smoothing-of-surfaces`): the spline then
/// minimises the same penalised objective over the surfaces that keep them
/// (`constrained_surface_grid_smoothing_spline`; a weight of GCV is the unconstrained
/// spline's, and `λ = 0` is refused). With shapes, `s` asks for the residual `s` instead of
/// weights (`constrained_surface_grid_smoothing_condition`: GCV's weights scaled together);
/// `lam` must then be `None`. A constrained fit's report has `"gcv"` and `"trace"` `None` (they
/// are the unconstrained smoother's).
///
/// >>> import numpy as np, lekalo
/// >>> x, y = np.linspace(0, 1, 12), np.linspace(0, 2, 9)
/// >>> z = np.add.outer(x, 3 * y) + 0.5
/// >>> s, r = lekalo.fit_tensor_grid_smoothing_spline([x, y], z, lam=[1e-3, None])
/// >>> bool(np.allclose(s([[0.3, 1.1]]), 0.3 + 3.3 + 0.5))
/// True
#[pyfunction]
#[pyo3(signature = (axes, values, lam = None, *, s = None, increasing = None, decreasing = None, min = None, max = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_tensor_grid_smoothing_spline<'py>(
    py: Python<'py>,
    axes: &Bound<'py, PyAny>,
    values: &Bound<'py, PyAny>,
    lam: Option<&Bound<'py, PyAny>>,
    s: Option<f64>,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyTensorBSpline, Bound<'py, PyDict>)> {
    let shapes = SurfaceShapeArgs {
        increasing,
        decreasing,
        min,
        max,
    }
    .constraints()?;
    let lists = axes_arg(axes, "axes")?;
    let lambdas = lambdas_arg(lam, lists.len())?;
    let va = floats(values, "values")?;
    let (pts, trailing) = grid_values(&va, &lists)?;
    let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    let smoothing_err = |e: lekalo::Error| match e.arg() {
        Some(Arg::Lambda) => named("lam", &e),
        Some(Arg::S) => named("s", &e),
        _ => fit_err(e, "axes"),
    };
    let report = PyDict::new(py);
    if shapes.is_empty() {
        if s.is_some() {
            return Err(bad(
                "s: the residual target on this space is for shapes (increasing, decreasing, \
                 min, max); without them give lam, or use fit_tensor_grid_smoothing(axes, \
                 values, s) for the fewest knots whose residual is s"
                    .into(),
            ));
        }
        let f = py
            .detach(|| tensor_grid_smoothing_spline(&refs, pts, &lambdas))
            .map_err(smoothing_err)?;
        report.set_item("lam", f.lambdas)?;
        report.set_item("gcv", f.gcv)?;
        report.set_item("residual", f.residual)?;
        report.set_item("trace", f.trace)?;
        return Ok((
            PyTensorBSpline {
                inner: f.spline,
                trailing,
            },
            report,
        ));
    }
    if refs.len() != 2 {
        return Err(bad(format!(
            "increasing, decreasing, min, max: shapes are kept by a table z(u, v) of two axes, \
             not {}; drop them",
            refs.len()
        )));
    }
    if s.is_some() && lam.is_some() {
        return Err(bad(
            "lam, s: give one: the weights, or the residual s they are scaled to".into(),
        ));
    }
    let (uu, vv) = (refs[0], refs[1]);
    let f = py
        .detach(|| match s {
            Some(s) => constrained_surface_grid_smoothing_condition(pts, (uu, vv), s, &shapes),
            None => constrained_surface_grid_smoothing_spline(
                pts,
                (uu, vv),
                [lambdas[0], lambdas[1]],
                &shapes,
            ),
        })
        .map_err(smoothing_err)?;
    report.set_item("lam", f.lambdas.to_vec())?;
    report.set_item("gcv", py.None())?;
    report.set_item("residual", f.residual)?;
    report.set_item("trace", py.None())?;
    Ok((
        PyTensorBSpline {
            inner: TensorBSpline::from_surface(&f.surface),
            trailing,
        },
        report,
    ))
}

/// The GCV score of the smoothing spline on a grid with the weights `lam` (one `λ ≥ 0` per
/// axis, or one for all): what `fit_tensor_grid_smoothing_spline` minimises over the weights
/// it chooses (`docs/theory/tensor.md#penalised-smoothing-on-grids`). One axis gives
/// `gcv_score`.
#[pyfunction]
#[pyo3(signature = (axes, values, lam))]
pub(crate) fn tensor_grid_gcv_score(
    py: Python<'_>,
    axes: &Bound<'_, PyAny>,
    values: &Bound<'_, PyAny>,
    lam: &Bound<'_, PyAny>,
) -> PyResult<f64> {
    let lists = axes_arg(axes, "axes")?;
    let lambdas: Vec<f64> = lambdas_arg(Some(lam), lists.len())?
        .into_iter()
        .map(|l| match l {
            Lambda::Given(v) => Ok(v),
            Lambda::Gcv => Err(bad(
                "lam: the score is of given weights; give a number λ ≥ 0 per axis".into(),
            )),
        })
        .collect::<PyResult<_>>()?;
    let va = floats(values, "values")?;
    let (pts, _) = grid_values(&va, &lists)?;
    let refs: Vec<&[f64]> = lists.iter().map(Vec::as_slice).collect();
    py.detach(|| lk_tensor_grid_gcv_score(&refs, pts, &lambdas))
        .map_err(|e| match e {
            lekalo::Error::NegativeSmoothing { .. } => named("lam", &e),
            other => fit_err(other, "axes"),
        })
}

/// Registers the fits of tensor-product splines.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(tensor_design_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_grid, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_grid_smoothing, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_grid_smoothing_spline, m)?)?;
    m.add_function(wrap_pyfunction!(tensor_grid_gcv_score, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_scattered, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tensor_scattered_smoothing, m)?)?;
    Ok(())
}
