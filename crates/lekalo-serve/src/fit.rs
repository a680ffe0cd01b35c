//! `POST /api/fit`: smoothing of noisy points (`lekalo fit --smooth` and `--s`), a thin call of
//! [`lekalo::fit`] (`docs/theory/fitting.md`): the cubic smoothing spline with λ given or chosen
//! by generalised cross-validation, or the fewest knots whose weighted residual sum of squares
//! is at most `s` (FITPACK's smoothing condition); with shape constraints (increasing,
//! convex, bounds…) the constrained smoothing spline of a function y(x), its λ given, by GCV,
//! or found so that the residual is `s` (`lekalo fit --increasing --s S`).
//!
//! The smoothing spline and the smoothing condition run with the job's progress hook
//! ([`lekalo::fit::smoothing_spline_with_progress`],
//! [`lekalo::fit::smoothing_condition_with_rounds`]): at the deadline they stop between two
//! GCV scores, knot rounds or smoothing weights, and the request is answered with 504 while its
//! pool thread is freed. The constrained fits
//! ([`lekalo::fit::constrained_smoothing_spline_with_progress`],
//! [`lekalo::fit::constrained_smoothing_condition_with_progress`]) stop likewise between two GCV
//! scores or two rounds of their cone programs' working sets and polish.

use axum::body::Bytes;
use axum::response::Response;
use lekalo::fit::{
    constrained_smoothing_condition_with_progress, constrained_smoothing_spline_with_progress,
    smoothing_condition_with_rounds, smoothing_spline_with_progress, CurveFit, FitData, KnotRounds,
    Lambda, Shape, ShapeConstraints,
};
use lekalo::{parametrize, Points};
use lekalo_io::Object;
use serde::{Deserialize, Serialize};

use crate::answer::{answer, SMALL};
use crate::api::{parametrization, parse, points, view_in, CurveView, ViewOptionsFlat};
use crate::error::{field_of, ApiError, ApiResult};
use crate::pool::Job;

/// How the amount of smoothing is given.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
enum Smoothing {
    /// The penalty weight λ of `∫|f''|²` (`lekalo fit --smooth λ`).
    #[default]
    Lambda,
    /// λ by generalised cross-validation (`lekalo fit --smooth gcv`).
    Gcv,
    /// Fewest knots with weighted residual sum of squares `≤ s` (`lekalo fit --s S`).
    S,
}

impl crate::fields::Choice for Smoothing {
    const WORDS: &'static [(&'static str, Self)] =
        &[("lambda", Self::Lambda), ("gcv", Self::Gcv), ("s", Self::S)];
}

fn default_degree() -> usize {
    3
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FitRequest {
    #[serde(deserialize_with = "crate::fields::rows")]
    points: Vec<Vec<f64>>,
    #[serde(default, deserialize_with = "crate::fields::choice")]
    smoothing: Smoothing,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    lambda: Option<f64>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    s: Option<f64>,
    /// How the smoothing condition places its knots: a word of
    /// [`lekalo::vocabulary::KNOT_ROUNDS`] (`lekalo fit --knot-rounds`).
    #[serde(default)]
    knot_rounds: Option<String>,
    /// Degree of the smoothing condition (the smoothing spline is cubic).
    #[serde(default = "default_degree")]
    #[serde(deserialize_with = "crate::fields::count")]
    degree: usize,
    /// The points are samples `(x, y)` of a function: `x` is the parameter.
    #[serde(default)]
    function: bool,
    /// A word of [`lekalo::vocabulary::PARAMETRIZATION`].
    #[serde(default)]
    parametrization: Option<String>,
    /// Shape constraints of a function fit (`lekalo fit --increasing …`): the points are then
    /// samples `(x, y)` of a function, smoothed with λ given or by GCV.
    #[serde(default)]
    increasing: bool,
    #[serde(default)]
    decreasing: bool,
    #[serde(default)]
    convex: bool,
    #[serde(default)]
    concave: bool,
    /// Lower bound of the function (`--min`).
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    min: Option<f64>,
    /// Upper bound of the function (`--max`).
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    max: Option<f64>,
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// The fit's figures, named as in `lekalo fit --json`.
#[derive(Debug, Serialize)]
struct FitAnswer {
    view: CurveView,
    report: Report,
}

#[derive(Debug, Serialize)]
struct Report {
    max_residual: f64,
    max_index: usize,
    rms: f64,
    weighted_rss: f64,
    control_points: usize,
    /// Length of the knot vector (as `lekalo fit`).
    knots: usize,
    /// Distinct knots inside the domain.
    interior_knots: usize,
    lambda: Option<f64>,
    s: Option<f64>,
}

/// `POST /api/fit`: the smoothed curve, its drawing and its residuals.
pub(crate) fn fit(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: FitRequest = parse(body)?;
    let pts = points(job, &r.points, "points")?;
    let mut rules = ShapeConstraints::new();
    for (on, shape) in [
        (r.increasing, Shape::Increasing),
        (r.decreasing, Shape::Decreasing),
        (r.convex, Shape::Convex),
        (r.concave, Shape::Concave),
    ] {
        if on {
            rules = rules.with(shape);
        }
    }
    if let Some(v) = r.min {
        rules = rules.with(Shape::AtLeast(v));
    }
    if let Some(v) = r.max {
        rules = rules.with(Shape::AtMost(v));
    }
    let constrained = !rules.shapes.is_empty();
    if constrained && r.smoothing == Smoothing::S && r.knot_rounds.is_some() {
        return Err(ApiError::bad(
            "knot_rounds",
            "with a shape the residual target s is met by the cubic smoothing spline (knots at the data), which has no knot rounds: leave knot_rounds out",
        ));
    }
    let function = r.function || constrained;
    let (values, params) = if function {
        let x: Vec<f64> = pts.iter().map(|p| p[0]).collect();
        let y = Points::from_flat(1, pts.iter().map(|p| p[1]).collect())
            .map_err(|e| ApiError::lib_or("points", &e))?;
        (y, x)
    } else {
        let u = parametrize(
            pts.as_view(),
            parametrization(r.parametrization.as_deref(), None)?,
        )
        .map_err(|e| ApiError::lib_or("points", &e))?;
        (pts, u)
    };
    let data =
        FitData::new(values.as_view(), &params).map_err(|e| ApiError::lib_or("points", &e))?;
    let given = |v: Option<f64>, name: &str| {
        v.ok_or_else(|| ApiError::bad(name, format!("smoothing = {name} needs the value {name}")))
    };
    let fit: CurveFit = match r.smoothing {
        Smoothing::Lambda | Smoothing::Gcv if constrained => {
            let lambda = match r.smoothing {
                Smoothing::Lambda => Lambda::Given(given(r.lambda, "lambda")?),
                _ => Lambda::Gcv,
            };
            constrained_smoothing_spline_with_progress(&data, lambda, &rules, &job.progress)
                .map_err(|e| ApiError::lib(fit_field(&e, "lambda"), &e))?
        }
        Smoothing::Lambda => {
            let lambda = Lambda::Given(given(r.lambda, "lambda")?);
            smoothing_spline_with_progress(&data, lambda, &job.progress)
                .map_err(|e| ApiError::lib(fit_field(&e, "lambda"), &e))?
        }
        Smoothing::Gcv => smoothing_spline_with_progress(&data, Lambda::Gcv, &job.progress)
            .map_err(|e| ApiError::lib(fit_field(&e, "lambda"), &e))?,
        Smoothing::S if constrained => {
            let s = given(r.s, "s")?;
            constrained_smoothing_condition_with_progress(&data, s, &rules, &job.progress)
                .map_err(|e| ApiError::lib(fit_field(&e, "s"), &e))?
        }
        Smoothing::S => {
            let degree = job.limits.check_degree(r.degree, "degree")?;
            let rounds = crate::words::word(
                &lekalo::vocabulary::KNOT_ROUNDS,
                "knot_rounds",
                r.knot_rounds.as_deref(),
                KnotRounds::Shared,
            )?;
            let s = given(r.s, "s")?;
            smoothing_condition_with_rounds(&data, degree, s, None, rounds, &job.progress)
                .map_err(|e| ApiError::lib(fit_field(&e, "s"), &e))?
        }
    };
    let rep = &fit.report;
    let knots = fit.curve.knots();
    let (a, b) = fit.curve.domain();
    let report = Report {
        max_residual: rep.max_residual,
        max_index: rep.max_index,
        rms: rep.rms,
        weighted_rss: rep.weighted_rss,
        control_points: rep.n_ctrl,
        knots: knots.len(),
        interior_knots: knots
            .distinct()
            .iter()
            .filter(|&&(k, _)| k > a && k < b)
            .count(),
        lambda: rep.lambda,
        s: (r.smoothing == Smoothing::S).then_some(r.s).flatten(),
    };
    // a function is drawn as its graph (x, y(x))
    let curve = if function {
        fit.curve
            .graph()
            .map_err(|e| ApiError::lib_or("points", &e))?
    } else {
        fit.curve
    };
    let view = view_in(job, &Object::BSpline(curve), &r.view.options(), "points")?;
    let size = view.size_hint() + SMALL;
    Ok(answer(&FitAnswer { view, report }, size))
}

/// The request field a fitting error is about: the smoothing value, the degree or the points.
fn fit_field(e: &lekalo::Error, value: &'static str) -> &'static str {
    match e {
        lekalo::Error::NegativeSmoothing { .. } => value,
        lekalo::Error::Degree { .. } => "degree",
        _ => field_of(e).unwrap_or("points"),
    }
}
