//! Fitting (`docs/theory/fitting.md`): least squares on given knots, smoothing splines (λ given
//! or by GCV), the fewest knots within a residual `s` (FITPACK's `splrep`/`splprep` smoothing
//! condition), fitting to a distance tolerance, robust (IRLS) least squares, and surfaces.
//!
//! The SciPy-named functions (`make_lsq_spline`, `make_smoothing_spline`, `make_splrep`,
//! `make_splprep`) take SciPy's arguments and return the curve; the `fit_*` functions return
//! `(curve, report)` where the report is a dict of the library's `FitReport`. Every computation
//! runs with the GIL released.

use lekalo::fit::{
    closed_parameters, constrained_least_squares, constrained_smoothing_condition,
    constrained_smoothing_spline, gcv_score as lk_gcv, least_squares, periodic_least_squares,
    periodic_smoothing_condition, periodic_smoothing_knot_sequence, periodic_smoothing_on_knots,
    place_knots as lk_place_knots, robust_least_squares, smoothing_condition,
    smoothing_condition_in, smoothing_knot_sequence, smoothing_on_knots, smoothing_spline,
    surface_grid_least_squares_at, surface_grid_parameters, surface_scattered_least_squares,
    CurveFit, Deviation, EndConstraints, FitData, FitReport, Lambda, RobustLoss, ToleranceOptions,
};
use lekalo::{KnotVector, PointsRef};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{floats, grid_points, vec1, vec_array, FloatArray};
use crate::curves::PyBSplineCurve;
use crate::error::{bad, lib_err, named};
use crate::interp::{parametrization_arg, parametrization_or_chord};
use crate::shape::ShapeArgs;
use crate::surfaces::PyBSplineSurface;

/// How a weight argument enters the sum of squares.
#[derive(Clone, Copy)]
enum WeightsAre {
    /// The library's `Σ w_k |r_k|²` (and SciPy's `make_smoothing_spline`).
    Squared,
    /// SciPy's `make_lsq_spline` / `splrep` convention, `Σ (w_k |r_k|)²`: squared here.
    Linear,
}

/// Values `y` (`(n,)` or `(n, dim)`), parameters `x` (`(n,)`) and optional weights, read once.
struct Data<'py> {
    y: FloatArray<'py>,
    x: FloatArray<'py>,
    w: Option<Vec<f64>>,
}

impl<'py> Data<'py> {
    fn read(
        x: &Bound<'py, PyAny>,
        y: &Bound<'py, PyAny>,
        w: Option<&Bound<'py, PyAny>>,
        xname: &str,
        weights: WeightsAre,
    ) -> PyResult<Self> {
        Ok(Data {
            x: floats(x, xname)?,
            y: floats(y, "y")?,
            w: w.map(|w| weight_vec(w, weights)).transpose()?,
        })
    }

    /// The library's validated data (lengths, finiteness, weights ≥ 0).
    fn fit_data(&self, xname: &str) -> PyResult<FitData<'_>> {
        let d = FitData::new(self.y.points("y")?, self.x.vector(xname)?).map_err(lib_err)?;
        match &self.w {
            Some(w) => d.with_weights(w).map_err(lib_err),
            None => Ok(d),
        }
    }
}

/// The weights as the library takes them. Negative weights are passed on unsquared, so that the
/// library refuses them by name.
fn weight_vec(w: &Bound<'_, PyAny>, weights: WeightsAre) -> PyResult<Vec<f64>> {
    let mut v = vec1(w, "w")?;
    if let WeightsAre::Linear = weights {
        for x in v.iter_mut().filter(|x| **x >= 0.0) {
            *x *= *x;
        }
    }
    Ok(v)
}

/// The report of a fit as a dict: `residuals`, `max_residual`, `max_index`, `rms`,
/// `weighted_rss`, `lam` (the smoothing weight, `None` without one), `n_ctrl`.
fn report_dict<'py>(py: Python<'py>, r: &FitReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("residuals", vec_array(py, &r.residuals))?;
    d.set_item("max_residual", r.max_residual)?;
    d.set_item("max_index", r.max_index)?;
    d.set_item("rms", r.rms)?;
    d.set_item("weighted_rss", r.weighted_rss)?;
    d.set_item("lam", r.lambda)?;
    d.set_item("n_ctrl", r.n_ctrl)?;
    Ok(d)
}

/// `(curve, report)` of a curve fit.
fn with_report(py: Python<'_>, f: CurveFit) -> PyResult<(PyBSplineCurve, Bound<'_, PyDict>)> {
    let r = report_dict(py, &f.report)?;
    Ok((PyBSplineCurve::wrap(f.curve), r))
}

fn knot_vector(t: &Bound<'_, PyAny>) -> PyResult<KnotVector> {
    KnotVector::new(vec1(t, "t")?).map_err(lib_err)
}

fn ends_constraints(
    clamp_ends: bool,
    d_start: Option<&Bound<'_, PyAny>>,
    d_end: Option<&Bound<'_, PyAny>>,
) -> PyResult<EndConstraints> {
    let mut e = if clamp_ends {
        EndConstraints::points()
    } else {
        EndConstraints::none()
    };
    if let Some(d) = d_start {
        e = e.with_start_derivative(vec1(d, "d_start")?);
    }
    if let Some(d) = d_end {
        e = e.with_end_derivative(vec1(d, "d_end")?);
    }
    Ok(e)
}

/// The weighted least-squares spline of degree `k` on the knots `t` through the data
/// `(x_k, y_k)`: minimises `Σ (w_k |f(x_k) − y_k|)²`, SciPy's weights (SciPy's
/// `make_lsq_spline`; P&T §9.4.1, `docs/theory/fitting.md#least-squares`). `y` is `(n,)` or
/// `(n, dim)`.
///
/// >>> import numpy as np, lekalo
/// >>> x = np.linspace(0, 1, 20); y = 1 - 2 * x + x ** 3
/// >>> c = lekalo.make_lsq_spline(x, y, [0, 0, 0, 0, 0.5, 1, 1, 1, 1], k=3)
/// >>> bool(np.abs(c(x)[:, 0] - y).max() < 1e-12)
/// True
///
/// Shape constraints (keyword arguments; `y` 1-D) make it the best fit that keeps its shape for
/// every `x`, not only at the data (`docs/theory/fitting.md#shape-constraints`): `increasing`,
/// `decreasing`, `convex`, `concave` are `True`, an interval `(a, b)` or a list of intervals;
/// `min`, `max` are a number, `(v, a, b)` or a list of those; `through` and `slope_at` are
/// `(x, v)` or a list of pairs (`y(x) = v`, `y'(x) = v`).
///
/// >>> c = lekalo.make_lsq_spline(x, np.sin(6 * x), [0, 0, 0, 0, 0.5, 1, 1, 1, 1], increasing=True)
/// >>> bool((np.diff(c(np.linspace(0, 1, 200))[:, 0]) >= -1e-12).all())
/// True
#[pyfunction]
#[pyo3(signature = (x, y, t, k = 3, w = None, *, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn make_lsq_spline<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: usize,
    w: Option<&Bound<'py, PyAny>>,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    convex: Option<&Bound<'py, PyAny>>,
    concave: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
    through: Option<&Bound<'py, PyAny>>,
    slope_at: Option<&Bound<'py, PyAny>>,
) -> PyResult<PyBSplineCurve> {
    let shape = ShapeArgs {
        increasing,
        decreasing,
        convex,
        concave,
        min,
        max,
        through,
        slope_at,
    }
    .constraints()?;
    let data = Data::read(x, y, w, "x", WeightsAre::Linear)?;
    let fd = data.fit_data("x")?;
    let kv = knot_vector(t)?;
    let f = py
        .detach(|| {
            if shape.is_empty() {
                least_squares(&fd, k, &kv, &EndConstraints::none())
            } else {
                constrained_least_squares(&fd, k, &kv, &shape)
            }
        })
        .map_err(lib_err)?;
    Ok(PyBSplineCurve::wrap(f.curve))
}

/// Least squares on given knots with optional end constraints, returning `(curve, report)`:
/// `clamp_ends` makes the curve start at the first point and end at the last; `d_start` /
/// `d_end` also fix the end derivatives (P&T A9.6/A9.7, `docs/theory/fitting.md#constraints`).
/// `params` are the data parameters (1-D, inside the knots' domain); `t` is the full knot
/// vector, so its end knots set the domain, which may reach beyond the data; the weights are the
/// library's, `Σ w_k |C(ū_k) − Q_k|²`. The shape constraints are those of `make_lsq_spline`
/// (for 1-D `points`, without `clamp_ends`: give end values as `through`).
#[pyfunction]
#[pyo3(signature = (points, params, t, k = 3, *, w = None, clamp_ends = false, d_start = None, d_end = None, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_least_squares<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: usize,
    w: Option<&Bound<'py, PyAny>>,
    clamp_ends: bool,
    d_start: Option<&Bound<'py, PyAny>>,
    d_end: Option<&Bound<'py, PyAny>>,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    convex: Option<&Bound<'py, PyAny>>,
    concave: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
    through: Option<&Bound<'py, PyAny>>,
    slope_at: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let shape = ShapeArgs {
        increasing,
        decreasing,
        convex,
        concave,
        min,
        max,
        through,
        slope_at,
    }
    .constraints()?;
    let data = Data::read(params, points, w, "params", WeightsAre::Squared)?;
    let fd = data.fit_data("params")?;
    let kv = knot_vector(t)?;
    let ends = ends_constraints(clamp_ends, d_start, d_end)?;
    if !shape.is_empty() && ends != EndConstraints::none() {
        return Err(bad(
            "clamp_ends/d_start/d_end: with shape constraints give end values and slopes as \
             through=(x, v) and slope_at=(x, v)"
                .into(),
        ));
    }
    let f = py
        .detach(|| {
            if shape.is_empty() {
                least_squares(&fd, k, &kv, &ends)
            } else {
                constrained_least_squares(&fd, k, &kv, &shape)
            }
        })
        .map_err(lib_err)?;
    with_report(py, f)
}

fn lambda_arg(lam: Option<f64>) -> Lambda {
    lam.map_or(Lambda::Gcv, Lambda::Given)
}

/// The cubic smoothing spline minimising `Σ w_k |y_k − f(x_k)|² + lam ∫ |f''|²` (SciPy's
/// `make_smoothing_spline`; Reinsch, `docs/theory/fitting.md#penalised`). `lam=None` chooses λ
/// by generalised cross-validation (`#gcv`). `x` strictly increasing; `y` `(n,)` or `(n, dim)`.
///
/// >>> import numpy as np, lekalo
/// >>> x = np.linspace(0, 1, 50); y = np.sin(4 * x) + 0.01 * np.cos(37 * x)
/// >>> c = lekalo.make_smoothing_spline(x, y)
/// >>> bool(np.abs(c(x)[:, 0] - y).max() < 0.05)
/// True
///
/// The shape constraints of `make_lsq_spline` (keyword arguments) keep the spline's shape over
/// the cubic splines with knots at the data; with `lam=None`, λ is the unconstrained spline's
/// GCV choice.
#[pyfunction]
#[pyo3(signature = (x, y, w = None, lam = None, *, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn make_smoothing_spline<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    lam: Option<f64>,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    convex: Option<&Bound<'py, PyAny>>,
    concave: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
    through: Option<&Bound<'py, PyAny>>,
    slope_at: Option<&Bound<'py, PyAny>>,
) -> PyResult<PyBSplineCurve> {
    Ok(fit_smoothing(
        py, x, y, w, lam, increasing, decreasing, convex, concave, min, max, through, slope_at,
    )?
    .0)
}

/// As `make_smoothing_spline`, returning `(curve, report)`; `report["lam"]` is the λ used.
#[pyfunction]
#[pyo3(signature = (x, y, w = None, lam = None, *, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_smoothing<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    lam: Option<f64>,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    convex: Option<&Bound<'py, PyAny>>,
    concave: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
    through: Option<&Bound<'py, PyAny>>,
    slope_at: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let shape = ShapeArgs {
        increasing,
        decreasing,
        convex,
        concave,
        min,
        max,
        through,
        slope_at,
    }
    .constraints()?;
    let data = Data::read(x, y, w, "x", WeightsAre::Squared)?;
    let fd = data.fit_data("x")?;
    let f = py
        .detach(|| {
            if shape.is_empty() {
                smoothing_spline(&fd, lambda_arg(lam))
            } else {
                constrained_smoothing_spline(&fd, lambda_arg(lam), &shape)
            }
        })
        .map_err(lib_err)?;
    with_report(py, f)
}

/// The generalised cross-validation score of the smoothing spline with weight `lam`
/// (`docs/theory/fitting.md#gcv`).
#[pyfunction]
#[pyo3(signature = (x, y, lam, w = None))]
pub(crate) fn gcv_score(
    py: Python<'_>,
    x: &Bound<'_, PyAny>,
    y: &Bound<'_, PyAny>,
    lam: f64,
    w: Option<&Bound<'_, PyAny>>,
) -> PyResult<f64> {
    let data = Data::read(x, y, w, "x", WeightsAre::Squared)?;
    let fd = data.fit_data("x")?;
    py.detach(|| lk_gcv(&fd, lam)).map_err(lib_err)
}

/// The spline of degree `k` with the fewest knots whose weighted residual `Σ w_k |y_k −
/// f(x_k)|²` is at most `s` (the smoothing condition of SciPy's `splrep`/`make_splrep`,
/// FITPACK `curfit`; `docs/theory/fitting.md#smoothing-condition`). `s = 0` interpolates.
/// With a knot vector `t` (SciPy's full vector), the spline on those knots whose `k`-th
/// derivative jumps least with the residual `s` (`docs/theory/fitting.md#smoothing-on-given-knots`).
/// Weights as SciPy's: the condition is `Σ (w_k (y_k − f(x_k)))² ≤ s`. `domain=(a, b)`, holding
/// the data, puts the end knots at `a` and `b` (SciPy's `xb`, `xe`; without `t`).
/// Returns the curve; `fit_smoothing_condition` also returns the report.
///
/// >>> import numpy as np, lekalo
/// >>> x = np.linspace(0, 1, 200); y = np.sin(6 * x)
/// >>> c = lekalo.make_splrep(x, y, s=1e-4)
/// >>> bool(((c(x)[:, 0] - y) ** 2).sum() <= 1e-4)
/// True
/// >>> t = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
/// >>> c = lekalo.make_splrep(x, y, s=0.5, t=t)
/// >>> bool(abs(((c(x)[:, 0] - y) ** 2).sum() - 0.5) <= 1e-3 * 0.5)
/// True
#[pyfunction]
#[pyo3(signature = (x, y, *, w = None, k = 3, s = 0.0, t = None, domain = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn make_splrep(
    py: Python<'_>,
    x: &Bound<'_, PyAny>,
    y: &Bound<'_, PyAny>,
    w: Option<&Bound<'_, PyAny>>,
    k: usize,
    s: f64,
    t: Option<&Bound<'_, PyAny>>,
    domain: Option<(f64, f64)>,
) -> PyResult<PyBSplineCurve> {
    let data = Data::read(x, y, w, "x", WeightsAre::Linear)?;
    Ok(PyBSplineCurve::wrap(
        condition_fit(py, &data, k, s, t, domain)?.curve,
    ))
}

/// The smoothing condition on FITPACK's knots (end knots at `domain` when given) or, with `t`,
/// the smoothing on those knots.
fn condition_fit(
    py: Python<'_>,
    data: &Data<'_>,
    k: usize,
    s: f64,
    t: Option<&Bound<'_, PyAny>>,
    domain: Option<(f64, f64)>,
) -> PyResult<CurveFit> {
    let fd = data.fit_data("x")?;
    let kv = t.map(knot_vector).transpose()?;
    if kv.is_some() && domain.is_some() {
        return Err(bad(
            "domain: the knots t set the domain (their end knots); drop domain or t".into(),
        ));
    }
    py.detach(|| match (&kv, domain) {
        (Some(kv), _) => smoothing_on_knots(&fd, k, kv, s),
        (None, Some(domain)) => smoothing_condition_in(&fd, k, s, domain),
        (None, None) => smoothing_condition(&fd, k, s),
    })
    .map_err(|e| match e {
        lekalo::Error::ParameterOutOfDomain { .. } | lekalo::Error::EmptyDomain { .. }
            if domain.is_some() =>
        {
            named("domain", &e)
        }
        other => lib_err(other),
    })
}

/// As `make_splrep`, returning `(curve, report)`, with the library's weights: the condition is
/// `Σ w_k |y_k − f(x_k)|² ≤ s` (`make_splrep` squares SciPy's `w` into these). With shape
/// constraints (keywords as `fit_smoothing`), the constrained cubic smoothing spline whose
/// residual is `s` (its λ, found by bisection, in `report["lam"]`; no `t`, `k = 3`).
/// `domain=(a, b)` as in `make_splrep`: the end knots, reaching beyond the data.
#[pyfunction]
#[pyo3(signature = (x, y, *, w = None, k = 3, s = 0.0, t = None, domain = None, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_smoothing_condition<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: usize,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
    domain: Option<(f64, f64)>,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    convex: Option<&Bound<'py, PyAny>>,
    concave: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
    through: Option<&Bound<'py, PyAny>>,
    slope_at: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let shape = ShapeArgs {
        increasing,
        decreasing,
        convex,
        concave,
        min,
        max,
        through,
        slope_at,
    }
    .constraints()?;
    let data = Data::read(x, y, w, "x", WeightsAre::Squared)?;
    if shape.is_empty() {
        let f = condition_fit(py, &data, k, s, t, domain)?;
        return with_report(py, f);
    }
    if domain.is_some() {
        return Err(bad(
            "domain: with shape constraints the smoothing condition fits the cubic smoothing spline (knots at the data); drop domain"
                .into(),
        ));
    }
    if t.is_some() || k != 3 {
        return Err(bad(
            "with shape constraints the smoothing condition fits the cubic smoothing spline (knots at the data): drop t and k"
                .into(),
        ));
    }
    let fd = data.fit_data("x")?;
    let f = py
        .detach(|| constrained_smoothing_condition(&fd, s, &shape))
        .map_err(lib_err)?;
    with_report(py, f)
}

/// The successive knot vectors of the smoothing condition's rounds (SciPy's `generate_knots`,
/// FITPACK's knot placement; `docs/theory/fitting.md#smoothing-condition`): a list of knot
/// arrays, each with more knots than the one before; the last is the knot vector
/// `make_splrep(x, y, s=s)` smooths on. `nest` stops the rounds once a vector has that many
/// knots. Weights as SciPy's (`Σ (w_k (y_k − f(x_k)))² ≤ s`). With `periodic=True` the rounds
/// of `fit_periodic` (the last row of `x`, `y` repeats the first, on the period
/// `[x[0], x[-1]]`).
///
/// >>> import numpy as np, lekalo
/// >>> x = np.arange(8.0); y = np.sin(x * np.pi / 8)
/// >>> [len(t) for t in lekalo.generate_knots(x, y, s=1e-7)]
/// [8, 9, 10, 11, 12]
#[pyfunction]
#[pyo3(signature = (x, y, *, w = None, k = 3, s = 0.0, nest = None, periodic = false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn generate_knots<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: usize,
    s: f64,
    nest: Option<usize>,
    periodic: bool,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let data = Data::read(x, y, w, "x", WeightsAre::Linear)?;
    let seq = if periodic {
        let xs = data.x.vector("x")?;
        let ys = data.y.points("y")?;
        let n = periodic_rows(xs.len(), ys.len())?;
        let rows =
            PointsRef::from_flat(ys.dim(), &ys.as_slice()[..n * ys.dim()]).map_err(lib_err)?;
        let mut fd = FitData::new(rows, &xs[..n]).map_err(lib_err)?;
        if let Some(w) = data.w.as_deref() {
            fd = fd.with_weights(&w[..n.min(w.len())]).map_err(lib_err)?;
        }
        let domain = (xs[0], xs[n]);
        py.detach(|| periodic_smoothing_knot_sequence(&fd, k, s, domain, nest))
    } else {
        let fd = data.fit_data("x")?;
        py.detach(|| smoothing_knot_sequence(&fd, k, s, nest))
    }
    .map_err(lib_err)?;
    Ok(seq.iter().map(|t| vec_array(py, t)).collect())
}

/// A parametric curve through points `(n, dim)` with the fewest knots within the residual `s`
/// (SciPy's `make_splprep`, points as rows instead of SciPy's list of coordinate arrays).
/// Parameters `u` default to chord length on `[0, 1]` (`parametrization` chooses another);
/// weights as SciPy's (`Σ (w_k |r_k|)² ≤ s`).
/// Returns `(curve, u)`.
#[pyfunction]
#[pyo3(signature = (points, *, w = None, u = None, k = 3, s = 0.0, t = None, parametrization = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn make_splprep<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    u: Option<&Bound<'py, PyAny>>,
    k: usize,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
    parametrization: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyAny>)> {
    let pa = floats(points, "points")?;
    let pts = pa.points("points")?;
    let params = match u {
        Some(u) => vec1(u, "u")?,
        None => {
            let m = parametrization_or_chord(parametrization)?;
            py.detach(|| lekalo::parametrize(pts, m)).map_err(lib_err)?
        }
    };
    let wv = w.map(|w| weight_vec(w, WeightsAre::Linear)).transpose()?;
    let mut fd = FitData::new(pts, &params).map_err(lib_err)?;
    if let Some(wv) = &wv {
        fd = fd.with_weights(wv).map_err(lib_err)?;
    }
    let kv = t.map(knot_vector).transpose()?;
    let f = py
        .detach(|| match &kv {
            Some(kv) => smoothing_on_knots(&fd, k, kv, s),
            None => smoothing_condition(&fd, k, s),
        })
        .map_err(lib_err)?;
    Ok((PyBSplineCurve::wrap(f.curve), vec_array(py, &params)))
}

/// A B-spline of degree `k` within `tol` (a distance in the data's units) of every point,
/// with few control points (`docs/theory/fitting.md#tolerance`). `deviation` is `"distance"`
/// (to the curve, by projection) or `"parameter"` (at the data parameter). Returns
/// `(curve, report)` with `params`, `deviations`, `max_deviation`, `worst_index`,
/// `worst_param`.
#[pyfunction]
#[pyo3(signature = (points, tol, k = 3, *, deviation = "distance", parametrization = None))]
pub(crate) fn fit_tolerance<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    tol: f64,
    k: usize,
    deviation: &str,
    parametrization: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let mut opts = ToleranceOptions::new(k, tol);
    opts.deviation = match deviation {
        "distance" => Deviation::Distance,
        "parameter" => Deviation::Parameter,
        _ => {
            return Err(bad(format!(
                "deviation: unknown value {deviation:?}; use 'distance' or 'parameter'"
            )))
        }
    };
    if let Some(p) = parametrization {
        opts.parametrization = parametrization_arg(p)?;
    }
    let pa = floats(points, "points")?;
    let pts = pa.points("points")?;
    let f = py
        .detach(|| lekalo::fit::fit_tolerance(pts, &opts))
        .map_err(lib_err)?;
    let d = PyDict::new(py);
    d.set_item("params", vec_array(py, &f.params))?;
    d.set_item("deviations", vec_array(py, &f.deviations))?;
    d.set_item("max_deviation", f.max_deviation)?;
    d.set_item("worst_index", f.worst_index)?;
    d.set_item("worst_param", f.worst_param)?;
    Ok((PyBSplineCurve::wrap(f.curve), d))
}

/// Least squares on the knots `t` that resists outliers: iteratively reweighted with the
/// `"huber"` or `"tukey"` loss and tuning constant `c` (default 1.345 for Huber, 4.685 for
/// Tukey; `docs/theory/fitting.md#robust`). Returns `(curve, report)`; the report adds the final
/// `robust_weights`, the noise `scale` σ and the number of `iterations`.
#[pyfunction]
#[pyo3(signature = (x, y, t, k = 3, *, w = None, loss = "huber", c = None, max_iter = 50))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_robust<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: usize,
    w: Option<&Bound<'py, PyAny>>,
    loss: &str,
    c: Option<f64>,
    max_iter: usize,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let loss = match loss {
        "huber" => RobustLoss::Huber(c.unwrap_or(1.345)),
        "tukey" => RobustLoss::Tukey(c.unwrap_or(4.685)),
        _ => {
            return Err(bad(format!(
                "loss: unknown value {loss:?}; use 'huber' or 'tukey'"
            )))
        }
    };
    let data = Data::read(x, y, w, "x", WeightsAre::Squared)?;
    let fd = data.fit_data("x")?;
    let kv = knot_vector(t)?;
    let r = py
        .detach(|| robust_least_squares(&fd, k, &kv, loss, max_iter))
        .map_err(lib_err)?;
    let d = report_dict(py, &r.fit.report)?;
    d.set_item("robust_weights", vec_array(py, &r.weights))?;
    d.set_item("scale", r.scale)?;
    d.set_item("iterations", r.iterations)?;
    Ok((PyBSplineCurve::wrap(r.fit.curve), d))
}

/// Knots for a least-squares fit with `n_ctrl` control points of degree `k` over the data
/// parameters `params` (P&T eq. 9.68–9.69, `docs/theory/fitting.md#knot-placement`): every
/// knot span holds data.
#[pyfunction]
#[pyo3(signature = (params, n_ctrl, k = 3))]
pub(crate) fn place_knots<'py>(
    py: Python<'py>,
    params: &Bound<'py, PyAny>,
    n_ctrl: usize,
    k: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let pa = floats(params, "params")?;
    let p = pa.vector("params")?;
    let kv = py
        .detach(|| lk_place_knots(p, k, n_ctrl))
        .map_err(lib_err)?;
    Ok(vec_array(py, kv.as_slice()))
}

/// Least-squares surface over a grid of points `(nu, nv, dim)` with a net of `n_ctrl =
/// (ncu, ncv)` control points of degrees `degree = (p, q)` (P&T §9.4.3,
/// `docs/theory/fitting.md#surfaces`). The parameters of the grid rows and columns are those of
/// `parametrization` averaged over the grid lines, or given (`u`: `nu` numbers, `v`: `nv`); the
/// knots are placed over them for `n_ctrl`, or given (`tu`, `tv`, which then set the net's size).
#[pyfunction]
#[pyo3(signature = (grid, n_ctrl = None, degree = (3, 3), *, parametrization = None, u = None, v = None, tu = None, tv = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_surface_grid(
    py: Python<'_>,
    grid: &Bound<'_, PyAny>,
    n_ctrl: Option<(usize, usize)>,
    degree: (usize, usize),
    parametrization: Option<&Bound<'_, PyAny>>,
    u: Option<&Bound<'_, PyAny>>,
    v: Option<&Bound<'_, PyAny>>,
    tu: Option<&Bound<'_, PyAny>>,
    tv: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyBSplineSurface> {
    let m = parametrization_or_chord(parametrization)?;
    let ga = floats(grid, "grid")?;
    let (pts, (nu, nv)) = grid_points(&ga, "grid")?;
    let given_params = (
        u.map(|x| vec1(x, "u")).transpose()?,
        v.map(|x| vec1(x, "v")).transpose()?,
    );
    let given_knots = (
        tu.map(|t| KnotVector::new(vec1(t, "tu")?).map_err(|e| named("tu", &e)))
            .transpose()?,
        tv.map(|t| KnotVector::new(vec1(t, "tv")?).map_err(|e| named("tv", &e)))
            .transpose()?,
    );
    let need_count = |given: &Option<KnotVector>, name: &str| -> PyResult<()> {
        if given.is_none() && n_ctrl.is_none() {
            return Err(bad(format!(
                "n_ctrl: give the net's size (ncu, ncv), or the knots {name} of that direction"
            )));
        }
        Ok(())
    };
    need_count(&given_knots.0, "tu")?;
    need_count(&given_knots.1, "tv")?;
    let inner = py
        .detach(|| {
            let computed = match &given_params {
                (Some(_), Some(_)) => None,
                _ => Some(surface_grid_parameters(pts, (nu, nv), m)?),
            };
            let uu = given_params
                .0
                .as_deref()
                .unwrap_or_else(|| &computed.as_ref().expect("computed when not given").0);
            let vv = given_params
                .1
                .as_deref()
                .unwrap_or_else(|| &computed.as_ref().expect("computed when not given").1);
            let (ncu, ncv) = n_ctrl.unwrap_or((0, 0));
            let ku = match &given_knots.0 {
                Some(k) => k.clone(),
                None => lk_place_knots(uu, degree.0, ncu)?,
            };
            let kv = match &given_knots.1 {
                Some(k) => k.clone(),
                None => lk_place_knots(vv, degree.1, ncv)?,
            };
            surface_grid_least_squares_at(pts, (nu, nv), degree, (uu, vv), (&ku, &kv))
        })
        .map_err(lib_err)?;
    Ok(PyBSplineSurface { inner })
}

/// Least squares over scattered data: rows `(u, v, z...)` of `data` (`(n, 2 + values)`, at
/// least one value) on the full knot vectors `tu`, `tv` with degrees `degree = (p, q)`, optional
/// weights and a second-difference `penalty` (SciPy's `LSQBivariateSpline(x, y, z, tx, ty,
/// bbox, kx=p, ky=q)` for `penalty = 0` is `tu` = `p + 1` copies of `bbox[0]`, `tx`, `p + 1`
/// copies of `bbox[1]`, and `tv` likewise;
/// `docs/theory/fitting.md#surfaces`). Returns `(surface, residuals, weighted_rss)`.
#[pyfunction]
#[pyo3(signature = (data, tu, tv, degree = (3, 3), *, w = None, penalty = 0.0))]
pub(crate) fn fit_surface_scattered<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    tu: &Bound<'py, PyAny>,
    tv: &Bound<'py, PyAny>,
    degree: (usize, usize),
    w: Option<&Bound<'py, PyAny>>,
    penalty: f64,
) -> PyResult<(PyBSplineSurface, Bound<'py, PyAny>, f64)> {
    let da = floats(data, "data")?;
    let pts = da.points("data")?;
    let wa = w.map(|w| floats(w, "w")).transpose()?;
    let wv = wa.as_ref().map(|w| w.vector("w")).transpose()?;
    let (ku, kv) = (knot_vector(tu)?, knot_vector(tv)?);
    let f = py
        .detach(|| surface_scattered_least_squares(pts, wv, degree, (&ku, &kv), penalty))
        .map_err(lib_err)?;
    Ok((
        PyBSplineSurface { inner: f.surface },
        vec_array(py, &f.residuals),
        f.weighted_rss,
    ))
}

/// Registers the fitting functions.
/// The closed fit of points with parameters `params` (the period `[params[0], params[n]]`, one
/// parameter more than points): with interior breakpoints `t`, least squares (`s = 0`) or the
/// least jumps with the residual `s`; without, the fewest knots within the residual `s`
/// (`docs/theory/fitting.md#periodic`).
fn closed_fit(
    py: Python<'_>,
    pts: PointsRef<'_>,
    params: &[f64],
    w: Option<&[f64]>,
    k: usize,
    s: f64,
    t: Option<Vec<f64>>,
) -> PyResult<CurveFit> {
    let n = pts.len();
    let domain = (params[0], params[n]);
    let mut fd = FitData::new(pts, &params[..n]).map_err(lib_err)?;
    if let Some(w) = w {
        fd = fd.with_weights(w).map_err(lib_err)?;
    }
    py.detach(|| match t {
        Some(t) => {
            let mut breaks = Vec::with_capacity(t.len() + 2);
            breaks.push(domain.0);
            breaks.extend(t);
            breaks.push(domain.1);
            if s > 0.0 {
                periodic_smoothing_on_knots(&fd, k, &breaks, s)
            } else {
                periodic_least_squares(&fd, k, &breaks)
            }
        }
        None => periodic_smoothing_condition(&fd, k, s, domain),
    })
    .map_err(lib_err)
}

/// A periodic spline of degree `k` through `(x_k, y_k)` on the period `[x[0], x[-1]]`: the last
/// row repeats the first and is left out, as SciPy's `splrep(x, y, per=1)` does. With `t` (the
/// interior breakpoints) it is the weighted least-squares spline on those knots for `s = 0`, and
/// for `s > 0` the spline on them whose `k`-th derivative jumps least with the residual `s`
/// (SciPy's `make_splrep(…, t=…, bc_type="periodic")`); otherwise the
/// fewest knots with `Σ w_k |y_k − f(x_k)|² ≤ s` (FITPACK's periodic smoothing condition,
/// `docs/theory/fitting.md#periodic`). `y` is `(n,)` or `(n, dim)`; weights are the library's
/// (squared into the sum). Returns `(curve, report)`.
///
/// >>> import numpy as np, lekalo
/// >>> x = np.linspace(0, 2 * np.pi, 41); y = np.cos(x)
/// >>> c, r = lekalo.fit_periodic(x, y, s=1e-4)
/// >>> bool(r["weighted_rss"] <= 1e-4)
/// True
#[pyfunction]
#[pyo3(signature = (x, y, *, w = None, k = 3, s = 0.0, t = None))]
pub(crate) fn fit_periodic<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: usize,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let data = Data::read(x, y, w, "x", WeightsAre::Squared)?;
    let xs = data.x.vector("x")?;
    let ys = data.y.points("y")?;
    let n = periodic_rows(xs.len(), ys.len())?;
    let rows = PointsRef::from_flat(ys.dim(), &ys.as_slice()[..n * ys.dim()]).map_err(lib_err)?;
    let w = data.w.as_deref().map(|w| &w[..n.min(w.len())]);
    let t = t.map(|t| vec1(t, "t")).transpose()?;
    let f = closed_fit(py, rows, xs, w, k, s, t)?;
    with_report(py, f)
}

/// The number of rows of periodic data without the last, which repeats the first.
fn periodic_rows(nx: usize, ny: usize) -> PyResult<usize> {
    if nx < 2 || ny != nx {
        return Err(bad(format!(
            "periodic data: x and y need the same number of rows, two or more (got {nx} and \
             {ny}); the last row repeats the first"
        )));
    }
    Ok(nx - 1)
}

/// A closed curve through the points `(n, dim)` of a closed polygon (the first point is not
/// repeated): parameters by `parametrization` (chord length by default) with one more for the
/// chord back to the first point, then the fit of `fit_periodic` on that period. Returns
/// `(curve, u)` with the `n + 1` parameters.
///
/// >>> import numpy as np, lekalo
/// >>> a = np.linspace(0, 2 * np.pi, 60, endpoint=False)
/// >>> c, u = lekalo.fit_closed(np.c_[np.cos(a), np.sin(a)], s=1e-6)
/// >>> bool(np.allclose(c(u[0]), c(u[-1])))
/// True
#[pyfunction]
#[pyo3(signature = (points, *, w = None, k = 3, s = 0.0, t = None, parametrization = None))]
pub(crate) fn fit_closed<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: usize,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
    parametrization: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyAny>)> {
    let pa = floats(points, "points")?;
    let pts = pa.points("points")?;
    let m = parametrization_or_chord(parametrization)?;
    let params = py.detach(|| closed_parameters(pts, m)).map_err(lib_err)?;
    let wv = w.map(|w| weight_vec(w, WeightsAre::Squared)).transpose()?;
    let t = t.map(|t| vec1(t, "t")).transpose()?;
    let f = closed_fit(py, pts, &params, wv.as_deref(), k, s, t)?;
    Ok((PyBSplineCurve::wrap(f.curve), vec_array(py, &params)))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(make_lsq_spline, m)?)?;
    m.add_function(wrap_pyfunction!(make_smoothing_spline, m)?)?;
    m.add_function(wrap_pyfunction!(make_splrep, m)?)?;
    m.add_function(wrap_pyfunction!(make_splprep, m)?)?;
    m.add_function(wrap_pyfunction!(fit_least_squares, m)?)?;
    m.add_function(wrap_pyfunction!(fit_smoothing, m)?)?;
    m.add_function(wrap_pyfunction!(fit_smoothing_condition, m)?)?;
    m.add_function(wrap_pyfunction!(generate_knots, m)?)?;
    m.add_function(wrap_pyfunction!(fit_tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(fit_robust, m)?)?;
    m.add_function(wrap_pyfunction!(fit_periodic, m)?)?;
    m.add_function(wrap_pyfunction!(fit_closed, m)?)?;
    m.add_function(wrap_pyfunction!(gcv_score, m)?)?;
    m.add_function(wrap_pyfunction!(place_knots, m)?)?;
    m.add_function(wrap_pyfunction!(fit_surface_grid, m)?)?;
    m.add_function(wrap_pyfunction!(fit_surface_scattered, m)?)?;
    Ok(())
}
