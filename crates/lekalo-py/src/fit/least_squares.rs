//! Least squares on given knots from Python (`docs/theory/fitting.md#least-squares`): SciPy's
//! `make_lsq_spline`, `fit_least_squares` with end constraints and shape conditions, robust
//! (IRLS) least squares, the fit to a distance tolerance, and the placement of knots.

use lekalo::fit::{
    constrained_least_squares, least_squares, least_squares_curve, least_squares_curve_rss,
    place_knots as lk_place_knots, robust_least_squares, Deviation, EndConstraints, RobustLoss,
    ToleranceOptions,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{knot_vector, report_dict, shape_constraints, with_report, Data, WeightsAre};
use crate::convert::IntArg;
use crate::convert::{floats, vec1, vec_array};
use crate::curves::PyBSplineCurve;
use crate::error::{bad, lib_err};
use crate::interp::parametrization_arg;

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
/// `decreasing`, `convex`, `concave` are `True`, an interval `(a, b)` or a list of intervals
/// (`(x, x)`: at the point `x` alone); `min`, `max` are a number, `(v, a, b)` on `[a, b]`,
/// `(v, x)` at the point `x`, or a list of those; `through` and `slope_at` are `(x, v)` or a
/// list of pairs (`y(x) = v`, `y'(x) = v`).
///
/// >>> c = lekalo.make_lsq_spline(x, np.sin(6 * x), [0, 0, 0, 0, 0.5, 1, 1, 1, 1], increasing=True)
/// >>> bool((np.diff(c(np.linspace(0, 1, 200))[:, 0]) >= -1e-12).all())
/// True
#[pyfunction]
#[pyo3(signature = (x, y, t, k = IntArg::of(3), w = None, *, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None, integral = None, periodic = None), text_signature = "(x, y, t, k=3, w=None, *, increasing=None, decreasing=None, convex=None, concave=None, min=None, max=None, through=None, slope_at=None, integral=None, periodic=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn make_lsq_spline<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: IntArg,
    w: Option<&Bound<'py, PyAny>>,
    increasing: Option<&Bound<'py, PyAny>>,
    decreasing: Option<&Bound<'py, PyAny>>,
    convex: Option<&Bound<'py, PyAny>>,
    concave: Option<&Bound<'py, PyAny>>,
    min: Option<&Bound<'py, PyAny>>,
    max: Option<&Bound<'py, PyAny>>,
    through: Option<&Bound<'py, PyAny>>,
    slope_at: Option<&Bound<'py, PyAny>>,
    integral: Option<&Bound<'py, PyAny>>,
    periodic: Option<&Bound<'py, PyAny>>,
) -> PyResult<PyBSplineCurve> {
    let k = k.count("k")?;
    let shape = shape_constraints([
        increasing, decreasing, convex, concave, min, max, through, slope_at, integral, periodic,
    ])?;
    let data = Data::read(x, y, w, "x", WeightsAre::Linear)?;
    let fd = data.fit_data("x")?;
    let kv = knot_vector(t)?;
    // the curve alone: the fit's report (a second pass over the data) is not returned here
    let curve = py
        .detach(|| {
            if shape.is_empty() {
                least_squares_curve(&fd, k, &kv, &EndConstraints::none())
            } else {
                constrained_least_squares(&fd, k, &kv, &shape).map(|f| f.curve)
            }
        })
        .map_err(lib_err)?;
    Ok(PyBSplineCurve::wrap(curve))
}

/// SciPy's `LSQUnivariateSpline` (FITPACK's `curfit` on given knots): the weighted
/// least-squares spline of degree `k` on the full knot vector `t`, minimising
/// `Σ (w_k (f(x_k) − y_k))²` (`w` linear, SciPy's), and that minimum, FITPACK's `fp`, as the
/// squares reflected out of the banded QR (`lekalo.fit.least_squares_curve_rss`: no evaluation
/// pass after the solve). Returns `(curve, fp)`; `y` is `(n,)`.
///
/// >>> import numpy as np, lekalo
/// >>> x = np.linspace(0, 1, 20); y = 1 - 2 * x + x ** 3
/// >>> c, fp = lekalo._lekalo.make_lsq_spline_fp(x, y, [0, 0, 0, 0, 0.5, 1, 1, 1, 1], 3)
/// >>> bool(fp < 1e-25)
/// True
#[pyfunction]
#[pyo3(signature = (x, y, t, k = IntArg::of(3), w = None), text_signature = "(x, y, t, k=3, w=None)")]
pub(crate) fn make_lsq_spline_fp<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: IntArg,
    w: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, f64)> {
    let k = k.count("k")?;
    let data = Data::read(x, y, w, "x", WeightsAre::Linear)?;
    let fd = data.fit_data("x")?;
    let kv = knot_vector(t)?;
    let (curve, fp) = py
        .detach(|| least_squares_curve_rss(&fd, k, &kv, &EndConstraints::none()))
        .map_err(lib_err)?;
    Ok((PyBSplineCurve::wrap(curve), fp))
}

/// Least squares on given knots with optional end constraints, returning `(curve, report)`:
/// `clamp_ends` makes the curve start at the first point and end at the last; `d_start` /
/// `d_end` also fix the end derivatives (P&T A9.6/A9.7, `docs/theory/fitting.md#constraints`).
/// `params` are the data parameters (1-D, inside the knots' domain); `t` is the full knot
/// vector, so its end knots set the domain, which may reach beyond the data; the weights are the
/// library's, `Σ w_k |C(ū_k) − Q_k|²`. The shape constraints are those of `make_lsq_spline`
/// (for 1-D `points`, without `clamp_ends`: give end values as `through`).
#[pyfunction]
#[pyo3(signature = (points, params, t, k = IntArg::of(3), *, w = None, clamp_ends = false, d_start = None, d_end = None, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None, integral = None, periodic = None), text_signature = "(points, params, t, k=3, *, w=None, clamp_ends=False, d_start=None, d_end=None, increasing=None, decreasing=None, convex=None, concave=None, min=None, max=None, through=None, slope_at=None, integral=None, periodic=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_least_squares<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    params: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: IntArg,
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
    integral: Option<&Bound<'py, PyAny>>,
    periodic: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let k = k.count("k")?;
    let shape = shape_constraints([
        increasing, decreasing, convex, concave, min, max, through, slope_at, integral, periodic,
    ])?;
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

/// A B-spline of degree `k` within `tolerance` (a distance in the data's units) of every point,
/// with few control points (`docs/theory/fitting.md#tolerance`). `deviation` is `"distance"`
/// (to the curve, by projection) or `"parameter"` (at the data parameter). Returns
/// `(curve, report)` with `params`, `closest_params` (each point's closest point's parameter,
/// where its deviation is measured: `curve(closest_params)` is within `tolerance` of the points),
/// `deviations`, `max_deviation`, `worst_index`, `worst_param`.
#[pyfunction]
#[pyo3(signature = (points, tolerance, k = IntArg::of(3), *, deviation = "distance", parametrization = None), text_signature = "(points, tolerance, k=3, *, deviation=\"distance\", parametrization=None)")]
pub(crate) fn fit_tolerance<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    tolerance: f64,
    k: IntArg,
    deviation: &str,
    parametrization: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let k = k.count("k")?;
    let mut opts = ToleranceOptions::new(k, tolerance);
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
    let pts = pa.curve_points("points", k + 1)?;
    let f = py
        .detach(|| lekalo::fit::fit_tolerance(pts, &opts))
        .map_err(lib_err)?;
    let d = PyDict::new(py);
    d.set_item("params", vec_array(py, &f.params))?;
    d.set_item("closest_params", vec_array(py, &f.closest_params))?;
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
#[pyo3(signature = (x, y, t, k = IntArg::of(3), *, w = None, loss = "huber", c = None, max_iter = IntArg::of(50)), text_signature = "(x, y, t, k=3, *, w=None, loss=\"huber\", c=None, max_iter=50)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_robust<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    t: &Bound<'py, PyAny>,
    k: IntArg,
    w: Option<&Bound<'py, PyAny>>,
    loss: &str,
    c: Option<f64>,
    max_iter: IntArg,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let k = k.count("k")?;
    let max_iter = max_iter.count("max_iter")?;
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
#[pyo3(signature = (params, n_ctrl, k = IntArg::of(3)), text_signature = "(params, n_ctrl, k=3)")]
pub(crate) fn place_knots<'py>(
    py: Python<'py>,
    params: &Bound<'py, PyAny>,
    n_ctrl: IntArg,
    k: IntArg,
) -> PyResult<Bound<'py, PyAny>> {
    let n_ctrl = n_ctrl.count("n_ctrl")?;
    let k = k.count("k")?;
    let pa = floats(params, "params")?;
    let p = pa.vector("params")?;
    let kv = py
        .detach(|| lk_place_knots(p, k, n_ctrl))
        .map_err(lib_err)?;
    Ok(vec_array(py, kv.as_slice()))
}
