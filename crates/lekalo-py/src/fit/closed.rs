//! Closed (periodic) fits from Python (`docs/theory/fitting.md#periodic`): of a function
//! `y(x)` on a period and of a closed polygon of points.

use lekalo::fit::{
    closed_parameters, periodic_least_squares, periodic_smoothing_condition,
    periodic_smoothing_on_knots, CurveFit, FitData,
};
use lekalo::PointsRef;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{weight_vec, with_report, Data, WeightsAre};
use crate::convert::IntArg;
use crate::convert::{floats, vec1, vec_array};
use crate::curves::PyBSplineCurve;
use crate::error::lib_err;
use crate::interp::parametrization_or_chord;

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
#[pyo3(signature = (x, y, *, w = None, k = IntArg::of(3), s = 0.0, t = None), text_signature = "(x, y, *, w=None, k=3, s=0.0, t=None)")]
pub(crate) fn fit_periodic<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: IntArg,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let k = k.count("k")?;
    let data = Data::read(x, y, w, "x", WeightsAre::Squared)?;
    let (rows, xs, w) = data.periodic()?;
    let t = t.map(|t| vec1(t, "t")).transpose()?;
    let f = closed_fit(py, rows, xs, w, k, s, t)?;
    with_report(py, f)
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
#[pyo3(signature = (points, *, w = None, k = IntArg::of(3), s = 0.0, t = None, parametrization = None), text_signature = "(points, *, w=None, k=3, s=0.0, t=None, parametrization=None)")]
pub(crate) fn fit_closed<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: IntArg,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
    parametrization: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyAny>)> {
    let k = k.count("k")?;
    let pa = floats(points, "points")?;
    let pts = pa.points("points")?;
    let m = parametrization_or_chord(parametrization)?;
    let params = py.detach(|| closed_parameters(pts, m)).map_err(lib_err)?;
    let wv = w.map(|w| weight_vec(w, WeightsAre::Squared)).transpose()?;
    let t = t.map(|t| vec1(t, "t")).transpose()?;
    let f = closed_fit(py, pts, &params, wv.as_deref(), k, s, t)?;
    Ok((PyBSplineCurve::wrap(f.curve), vec_array(py, &params)))
}
