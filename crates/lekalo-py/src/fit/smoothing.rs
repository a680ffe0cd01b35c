//! Smoothing from Python (`docs/theory/fitting.md#penalised`, `#smoothing-condition`): smoothing
//! splines (λ given or by GCV), the fewest knots within a residual `s` (SciPy's `make_splrep`,
//! `make_splprep`, `generate_knots`) and the least jumps on given knots.

use lekalo::fit::{
    constrained_smoothing_condition, constrained_smoothing_spline, gcv_score as lk_gcv,
    periodic_smoothing_knot_sequence, smoothing_condition_from, smoothing_condition_with_rounds,
    smoothing_knot_sequence, smoothing_on_knots, smoothing_spline, CurveFit, FitData, KnotLimit,
    KnotRounds, Lambda, RoundsStart, RoundsState, ShapeConstraints,
};
use lekalo::Progress;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{knot_vector, shape_constraints, weight_vec, with_report, Data, WeightsAre};
use crate::convert::IntArg;
use crate::convert::{floats, vec1, vec_array};
use crate::curves::PyBSplineCurve;
use crate::error::{bad, lib_err, named};
use crate::interp::parametrization_or_chord;
use crate::words::word;

/// `knot_rounds=`: a word of [`lekalo::vocabulary::KNOT_ROUNDS`], `"shared"` when absent.
fn knot_rounds(text: Option<&str>) -> PyResult<KnotRounds> {
    text.map_or(Ok(KnotRounds::Shared), |t| {
        word(&lekalo::vocabulary::KNOT_ROUNDS, "knot_rounds", t)
    })
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
#[pyo3(signature = (x, y, w = None, lam = None, *, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None, integral = None, periodic = None))]
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
    integral: Option<&Bound<'py, PyAny>>,
    periodic: Option<&Bound<'py, PyAny>>,
) -> PyResult<PyBSplineCurve> {
    Ok(fit_smoothing(
        py, x, y, w, lam, increasing, decreasing, convex, concave, min, max, through, slope_at,
        integral, periodic,
    )?
    .0)
}

/// As `make_smoothing_spline`, returning `(curve, report)`; `report["lam"]` is the λ used.
#[pyfunction]
#[pyo3(signature = (x, y, w = None, lam = None, *, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None, integral = None, periodic = None))]
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
    integral: Option<&Bound<'py, PyAny>>,
    periodic: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyDict>)> {
    let shape = shape_constraints([
        increasing, decreasing, convex, concave, min, max, through, slope_at, integral, periodic,
    ])?;
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
/// f(x_k)|²` is at most `s`, or a least-squares spline above it by less than `0.001·s` as
/// FITPACK accepts it (the smoothing condition of SciPy's `splrep`/`make_splrep`,
/// FITPACK `curfit`; `docs/theory/fitting.md#smoothing-condition`). `s = 0` interpolates.
/// With a knot vector `t` (SciPy's full vector), the spline on those knots whose `k`-th
/// derivative jumps least with the residual `s` (`docs/theory/fitting.md#smoothing-on-given-knots`).
/// Weights as SciPy's: the condition is `Σ (w_k (y_k − f(x_k)))² ≤ s`. `domain=(a, b)`, holding
/// the data, puts the end knots at `a` and `b` (SciPy's `xb`, `xe`; without `t`).
/// `knot_rounds` chooses how each round of knot addition places its knots: `"shared"` (the
/// default) as FITPACK's `curfit` and SciPy's `splrep`, `"refit"` as SciPy's `make_splrep` (a
/// fit after every knot; `docs/theory/fitting.md#smoothing-condition`). `nest` bounds the knots
/// the rounds place (SciPy's `nest`, end knots counted): they stop there with the least-squares
/// spline, or with `resume=True` go on from the knots reached without the bound, as SciPy's
/// `UnivariateSpline` (FITPACK `curfit` again with `iopt=1`).
/// Shape constraints (keyword arguments as `make_smoothing_spline`'s) make it the constrained
/// cubic smoothing spline whose residual is `s` (knots at the data, its λ found by bisection;
/// no `t`, `domain` or `knot_rounds`, `k = 3`; `docs/theory/fitting.md#shape-constraints`).
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
/// >>> len(lekalo.make_splrep(x, y, s=1e-4, knot_rounds="refit").knots) >= 8
/// True
/// >>> c = lekalo.make_splrep(x, y, s=2.0, increasing=True)
/// >>> bool((np.diff(c(np.linspace(0, 1, 500))[:, 0]) >= -1e-12).all())
/// True
#[pyfunction]
#[pyo3(signature = (x, y, *, w = None, k = IntArg::of(3), s = 0.0, t = None, domain = None, knot_rounds = None, nest = None, resume = false, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None, integral = None, periodic = None), text_signature = "(x, y, *, w=None, k=3, s=0.0, t=None, domain=None, knot_rounds=None, nest=None, resume=False, increasing=None, decreasing=None, convex=None, concave=None, min=None, max=None, through=None, slope_at=None, integral=None, periodic=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn make_splrep<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: IntArg,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
    domain: Option<(f64, f64)>,
    knot_rounds: Option<&str>,
    nest: Option<IntArg>,
    resume: bool,
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
    let start = RoundsStart::Fresh(knot_limit(nest, resume)?);
    let (f, _) = shaped_condition_fit(py, &data, (k, s, t, domain, knot_rounds, start), &shape)?;
    Ok(PyBSplineCurve::wrap(f.curve))
}

/// The smoothing condition's own arguments: `k`, `s`, `t`, `domain`, `knot_rounds` and where
/// the rounds start (fresh under the limit of `nest` and `resume`, or from `start`).
type ConditionArgs<'a, 'py, 's> = (
    usize,
    f64,
    Option<&'a Bound<'py, PyAny>>,
    Option<(f64, f64)>,
    Option<&'a str>,
    RoundsStart<'s>,
);

/// A fit of the smoothing condition, with the state of its knot rounds when they ran (not with
/// knots `t` or shape constraints).
type ConditionFit = (CurveFit, Option<RoundsState>);

/// `nest=`, `resume=`: the knots the rounds may place (FITPACK's `nest`) and whether they go on
/// from there ([`KnotLimit`]); `resume` without `nest` is refused.
fn knot_limit(nest: Option<IntArg>, resume: bool) -> PyResult<KnotLimit> {
    match (nest.map(|n| n.count("nest")).transpose()?, resume) {
        (None, false) => Ok(KnotLimit::Unlimited),
        (None, true) => Err(bad(
            "resume: the rounds resume after stopping at nest knots; give nest or drop resume"
                .into(),
        )),
        (Some(n), false) => Ok(KnotLimit::Stop(n)),
        (Some(n), true) => Ok(KnotLimit::Resume(n)),
    }
}

/// The smoothing condition with or without shape constraints: [`condition_fit`] when there are
/// none, else the constrained cubic smoothing spline whose residual is `s` (knots at the data:
/// `t`, `domain`, `knot_rounds` and `k ≠ 3` refused by name).
fn shaped_condition_fit(
    py: Python<'_>,
    data: &Data<'_>,
    (k, s, t, domain, knot_rounds, start): ConditionArgs<'_, '_, '_>,
    shape: &ShapeConstraints,
) -> PyResult<ConditionFit> {
    let rounds = self::knot_rounds(knot_rounds)?;
    if shape.is_empty() {
        return condition_fit(py, data, (k, s, t, domain, rounds, start));
    }
    match start {
        RoundsStart::Fresh(KnotLimit::Unlimited) => {}
        RoundsStart::Fresh(_) => {
            return Err(bad(
                "nest: with shape constraints the smoothing condition fits the cubic smoothing spline (knots at the data); drop nest"
                    .into(),
            ))
        }
        RoundsStart::Continue(_) => {
            return Err(bad(
                "start: with shape constraints the smoothing condition fits the cubic smoothing spline (knots at the data, no knot rounds); drop start"
                    .into(),
            ))
        }
    }
    if knot_rounds.is_some() {
        return Err(bad(
            "knot_rounds: with shape constraints the smoothing condition fits the cubic smoothing spline (knots at the data); drop knot_rounds"
                .into(),
        ));
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
        .detach(|| constrained_smoothing_condition(&fd, s, shape))
        .map_err(lib_err)?;
    Ok((f, None))
}

/// The smoothing condition on FITPACK's knots placed in `rounds` (end knots at `domain` when
/// given), started as `start` says, or, with `t`, the smoothing on those knots.
#[allow(clippy::type_complexity)]
fn condition_fit(
    py: Python<'_>,
    data: &Data<'_>,
    (k, s, t, domain, rounds, start): (
        usize,
        f64,
        Option<&Bound<'_, PyAny>>,
        Option<(f64, f64)>,
        KnotRounds,
        RoundsStart<'_>,
    ),
) -> PyResult<ConditionFit> {
    let fd = data.fit_data("x")?;
    let kv = t.map(knot_vector).transpose()?;
    if kv.is_some() && domain.is_some() {
        return Err(bad(
            "domain: the knots t set the domain (their end knots); drop domain or t".into(),
        ));
    }
    match (&kv, start) {
        (Some(_), RoundsStart::Fresh(KnotLimit::Unlimited)) | (None, _) => {}
        (Some(_), RoundsStart::Fresh(_)) => {
            return Err(bad(
                "nest: the knots t are given, no rounds place them; drop nest or t".into(),
            ))
        }
        (Some(_), RoundsStart::Continue(_)) => {
            return Err(bad(
                "start: the knots t are given, no rounds place them; drop start or t".into(),
            ))
        }
    }
    py.detach(|| match &kv {
        Some(kv) => smoothing_on_knots(&fd, k, kv, s).map(|f| (f, None)),
        None => {
            let quiet = Progress::new();
            smoothing_condition_from(&fd, k, s, domain, rounds, start, &quiet)
                .map(|(f, st)| (f, Some(st)))
        }
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

/// The state of the knot rounds as the report's `"rounds"` dict: `knots` (the interior knots
/// of the last pass), `fp0`, `fp_before`, `nplus`, `restart`, and the limit a continuation runs
/// under, `nest` (`None` for none) and `resume` ([`RoundsState`]).
fn rounds_dict<'py>(py: Python<'py>, st: &RoundsState) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("knots", vec_array(py, &st.interior))?;
    d.set_item("fp0", st.fp0)?;
    d.set_item("fp_before", st.fp_before)?;
    d.set_item("nplus", st.nplus)?;
    d.set_item("restart", st.restart)?;
    let (nest, resume) = match st.limit {
        KnotLimit::Unlimited => (None, false),
        KnotLimit::Stop(n) => (Some(n), false),
        KnotLimit::Resume(n) => (Some(n), true),
    };
    d.set_item("nest", nest)?;
    d.set_item("resume", resume)?;
    Ok(d)
}

/// `start=`: a report's `"rounds"` dict ([`rounds_dict`]) read back, every key required.
fn rounds_state(d: &Bound<'_, PyAny>) -> PyResult<RoundsState> {
    let get = |key: &str| -> PyResult<Bound<'_, PyAny>> {
        d.get_item(key).map_err(|_| {
            bad(format!(
                "start: no {key:?}; give the report[\"rounds\"] of an earlier \
                 fit_smoothing_condition on the same data"
            ))
        })
    };
    let nest: Option<IntArg> = get("nest")?.extract()?;
    let resume: bool = get("resume")?.extract()?;
    Ok(RoundsState {
        interior: vec1(&get("knots")?, "start[\"knots\"]")?,
        fp0: get("fp0")?.extract()?,
        fp_before: get("fp_before")?.extract()?,
        nplus: get("nplus")?
            .extract::<IntArg>()?
            .count("start[\"nplus\"]")?,
        restart: get("restart")?.extract()?,
        limit: knot_limit(nest, resume)?,
    })
}

/// As `make_splrep`, returning `(curve, report)`, with the library's weights: the condition is
/// `Σ w_k |y_k − f(x_k)|² ≤ s` (`make_splrep` squares SciPy's `w` into these). With shape
/// constraints (keywords as `fit_smoothing`), the constrained cubic smoothing spline whose
/// residual is `s` (its λ, found by bisection, in `report["lam"]`; no `t`, `k = 3`).
/// `domain=(a, b)` as in `make_splrep`: the end knots, reaching beyond the data.
/// When FITPACK's knot rounds ran (no `t`, no shape constraints), `report["rounds"]` is where
/// they ended (`knots`, `fp0`, `fp_before`, `nplus`, `restart`, `nest`, `resume`); `start=` that
/// dict goes on from there with another `s` on the same data, as FITPACK's `curfit` with
/// `iopt=1` (SciPy's `UnivariateSpline.set_smoothing_factor`): the rounds resume from its
/// knots under its limit (no `nest` then), or start over when `s` is at least the residual of
/// the least-squares polynomial (`docs/theory/fitting.md#smoothing-condition`).
///
/// >>> import numpy as np, lekalo
/// >>> x = np.linspace(0, 10, 60); y = np.sin(x) + 0.1 * np.cos(37 * x)
/// >>> c, r = lekalo.fit_smoothing_condition(x, y, s=1.0)
/// >>> c2, r2 = lekalo.fit_smoothing_condition(x, y, s=0.2, start=r["rounds"])
/// >>> bool(r2["weighted_rss"] <= 0.2 * 1.001 and len(c2.knots) > len(c.knots))
/// True
#[pyfunction]
#[pyo3(signature = (x, y, *, w = None, k = IntArg::of(3), s = 0.0, t = None, domain = None, knot_rounds = None, nest = None, resume = false, start = None, increasing = None, decreasing = None, convex = None, concave = None, min = None, max = None, through = None, slope_at = None, integral = None, periodic = None), text_signature = "(x, y, *, w=None, k=3, s=0.0, t=None, domain=None, knot_rounds=None, nest=None, resume=False, start=None, increasing=None, decreasing=None, convex=None, concave=None, min=None, max=None, through=None, slope_at=None, integral=None, periodic=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_smoothing_condition<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: IntArg,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
    domain: Option<(f64, f64)>,
    knot_rounds: Option<&str>,
    nest: Option<IntArg>,
    resume: bool,
    start: Option<&Bound<'py, PyAny>>,
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
    let data = Data::read(x, y, w, "x", WeightsAre::Squared)?;
    let limit = knot_limit(nest, resume)?;
    let state = start.map(rounds_state).transpose()?;
    let start = match &state {
        None => RoundsStart::Fresh(limit),
        Some(_) if limit != KnotLimit::Unlimited => {
            return Err(bad(
                "nest: the rounds continued from start run under the limit it carries; drop nest and resume"
                    .into(),
            ))
        }
        Some(st) => RoundsStart::Continue(st),
    };
    let (f, rounds) =
        shaped_condition_fit(py, &data, (k, s, t, domain, knot_rounds, start), &shape)?;
    let (curve, report) = with_report(py, f)?;
    if let Some(st) = rounds {
        report.set_item("rounds", rounds_dict(py, &st)?)?;
    }
    Ok((curve, report))
}

/// The successive knot vectors of the smoothing condition's rounds (SciPy's `generate_knots`,
/// FITPACK's knot placement; `docs/theory/fitting.md#smoothing-condition`): a list of knot
/// arrays, each with more knots than the one before; the last is the knot vector
/// `make_splrep(x, y, s=s)` smooths on. `nest` stops the rounds once a vector has that many
/// knots. Weights as SciPy's (`Σ (w_k (y_k − f(x_k)))² ≤ s`). With `periodic=True` the rounds
/// of `fit_periodic` (the last row of `x`, `y` repeats the first, on the period
/// `[x[0], x[-1]]`). `knot_rounds` as in `make_splrep`: `"refit"` gives SciPy's
/// `generate_knots`, `"shared"` (the default) the rounds of FITPACK's `curfit`.
///
/// >>> import numpy as np, lekalo
/// >>> x = np.arange(8.0); y = np.sin(x * np.pi / 8)
/// >>> [len(t) for t in lekalo.generate_knots(x, y, s=1e-7)]
/// [8, 9, 10, 11, 12]
#[pyfunction]
#[pyo3(signature = (x, y, *, w = None, k = IntArg::of(3), s = 0.0, nest = None, periodic = false, knot_rounds = None), text_signature = "(x, y, *, w=None, k=3, s=0.0, nest=None, periodic=False, knot_rounds=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn generate_knots<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    y: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    k: IntArg,
    s: f64,
    nest: Option<IntArg>,
    periodic: bool,
    knot_rounds: Option<&str>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let k = k.count("k")?;
    let rounds = self::knot_rounds(knot_rounds)?;
    if periodic && rounds != KnotRounds::Shared {
        return Err(bad(
            "knot_rounds: the periodic rounds share each round's residual (FITPACK's fpperi); drop knot_rounds or periodic".into(),
        ));
    }
    let nest = nest.map(|n| n.count("nest")).transpose()?;
    let data = Data::read(x, y, w, "x", WeightsAre::Linear)?;
    let seq = if periodic {
        let (rows, xs, w) = data.periodic()?;
        let n = rows.len();
        let mut fd = FitData::new(rows, &xs[..n]).map_err(lib_err)?;
        if let Some(w) = w {
            fd = fd.with_weights(w).map_err(lib_err)?;
        }
        let domain = (xs[0], xs[n]);
        py.detach(|| periodic_smoothing_knot_sequence(&fd, k, s, domain, nest))
    } else {
        let fd = data.fit_data("x")?;
        py.detach(|| smoothing_knot_sequence(&fd, k, s, nest, rounds))
    }
    .map_err(lib_err)?;
    Ok(seq.iter().map(|t| vec_array(py, t)).collect())
}

/// A parametric curve through points `(n, dim)` with the fewest knots within the residual `s`
/// (SciPy's `make_splprep`, points as rows instead of SciPy's list of coordinate arrays).
/// Parameters `u` default to chord length on `[0, 1]` (`parametrization` chooses another);
/// weights as SciPy's (`Σ (w_k |r_k|)² ≤ s`); `knot_rounds` as in `make_splrep`.
/// `domain=(a, b)`, holding the parameters, puts the end knots at `a` and `b` (FITPACK
/// `parcur`'s `ub`, `ue`; without `t`), as `make_splrep`'s `domain`. Returns `(curve, u)`.
#[pyfunction]
#[pyo3(signature = (points, *, w = None, u = None, k = IntArg::of(3), s = 0.0, t = None, parametrization = None, knot_rounds = None, domain = None), text_signature = "(points, *, w=None, u=None, k=3, s=0.0, t=None, parametrization=None, knot_rounds=None, domain=None)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn make_splprep<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    w: Option<&Bound<'py, PyAny>>,
    u: Option<&Bound<'py, PyAny>>,
    k: IntArg,
    s: f64,
    t: Option<&Bound<'py, PyAny>>,
    parametrization: Option<&Bound<'py, PyAny>>,
    knot_rounds: Option<&str>,
    domain: Option<(f64, f64)>,
) -> PyResult<(PyBSplineCurve, Bound<'py, PyAny>)> {
    let k = k.count("k")?;
    let rounds = self::knot_rounds(knot_rounds)?;
    let pa = floats(points, "points")?;
    let pts = pa.curve_points("points", k + 1)?;
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
    if kv.is_some() && domain.is_some() {
        return Err(bad(
            "domain: the knots t set the domain (their end knots); drop domain or t".into(),
        ));
    }
    let f = py
        .detach(|| match &kv {
            Some(kv) => smoothing_on_knots(&fd, k, kv, s),
            None => smoothing_condition_with_rounds(&fd, k, s, domain, rounds, &Progress::new()),
        })
        .map_err(|e| match e {
            lekalo::Error::ParameterOutOfDomain { .. } | lekalo::Error::EmptyDomain { .. }
                if domain.is_some() =>
            {
                named("domain", &e)
            }
            other => lib_err(other),
        })?;
    Ok((PyBSplineCurve::wrap(f.curve), vec_array(py, &params)))
}
