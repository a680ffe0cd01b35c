//! `POST /api/quasi`: quasi-interpolation of a typed function (document 003, de Boor–Fix
//! functionals; `lekalo pp quasi`). The text is parsed by [`lekalo::Expression`] (a parser
//! and Taylor-arithmetic derivatives; nothing is executed) and the interpolant and its error
//! come from [`lekalo::sample_quasi_interpolant`].

use axum::body::Bytes;
use axum::response::Response;
use lekalo::{sample_quasi_interpolant_expression, Expression, PpSpace, Tau, TauRule};
use lekalo_io::Object;
use serde::{Deserialize, Serialize};

use crate::answer::{answer, NUMBER_BYTES, SMALL};
use crate::api::{view_in, CurveView, ViewOptions};
use crate::error::{field_of, ApiError, ApiResult};
use crate::pool::Job;

fn default_intervals() -> usize {
    200
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct QuasiRequest {
    expression: String,
    #[serde(deserialize_with = "crate::fields::numbers")]
    breakpoints: Vec<f64>,
    #[serde(deserialize_with = "crate::fields::count")]
    order: usize,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_counts")]
    continuity: Option<Vec<usize>>,
    /// A word of [`lekalo::vocabulary::TAU_RULE`].
    #[serde(default)]
    rule: Option<String>,
    /// Explicit `τ_i`, one per B-spline (instead of `rule`).
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_numbers")]
    tau: Option<Vec<f64>>,
    #[serde(default = "default_intervals")]
    #[serde(deserialize_with = "crate::fields::count")]
    intervals: usize,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_count")]
    basis_samples: Option<usize>,
}

/// The interpolant's view, and `f`, `q` and `f − q` at the sample parameters `t`.
#[derive(Debug, Serialize)]
struct QuasiAnswer {
    view: CurveView,
    t: Vec<f64>,
    exact: Vec<f64>,
    approx: Vec<f64>,
    error: Vec<f64>,
    max_error: f64,
}

pub(crate) fn quasi(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let limits = job.limits;
    let r: QuasiRequest = crate::api::parse(body)?;
    limits.check_points(r.breakpoints.len(), "breakpoints")?;
    if !(1..limits.max_samples).contains(&r.intervals) {
        return Err(ApiError::bad(
            "intervals",
            format!(
                "intervals = {}: give 1 to {} (lekalo serve --max-samples)",
                r.intervals,
                limits.max_samples - 1
            ),
        ));
    }
    // the interpolant's degree is order − 1
    limits.check_degree(r.order.saturating_sub(1), "order")?;
    let f = Expression::parse(&r.expression).map_err(|e| ApiError::lib_or("expression", &e))?;
    // as `lekalo pp quasi`: ν = k − 1 continuous derivatives (C^(k−2)) at every interior
    // breakpoint unless `continuity` says otherwise
    let interior = r.breakpoints.len().saturating_sub(2);
    let nu = match &r.continuity {
        Some(nu) if nu.len() != interior => {
            return Err(ApiError::bad(
                "continuity",
                format!(
                    "{} values given; the {} breakpoints have {interior} interior ones",
                    nu.len(),
                    r.breakpoints.len()
                ),
            ))
        }
        Some(nu) => nu.clone(),
        None => vec![r.order.saturating_sub(1); interior],
    };
    let space = PpSpace::new(&r.breakpoints, &nu, r.order).map_err(|e| {
        let field = if matches!(e, lekalo::Error::Degree { .. }) {
            "order"
        } else {
            field_of(&e).unwrap_or("breakpoints")
        };
        ApiError::lib(field, &e)
    })?;
    // one de Boor–Fix functional per B-spline, each O(order²): the size and the work of the
    // interpolant, before it is computed
    limits.check_points(space.dimension(), "breakpoints")?;
    limits.check_work(space.dimension(), r.order.saturating_sub(1), "breakpoints")?;
    let rule = crate::words::word(
        &lekalo::vocabulary::TAU_RULE,
        "rule",
        r.rule.as_deref(),
        TauRule::FirstKnotAfter,
    )?;
    if let Some(t) = &r.tau {
        limits.check_points(t.len(), "tau")?;
    }
    // explicit values win over the rule (as `lekalo pp quasi --tau`)
    let tau = || match &r.tau {
        Some(v) => Tau::Values(v),
        None => Tau::Rule(rule),
    };
    let tau_field = if r.tau.is_some() {
        "tau"
    } else {
        "breakpoints"
    };
    // the expression's own errors name it in their key (`what`)
    let s = sample_quasi_interpolant_expression(&space, tau(), &f, r.intervals)
        .map_err(|e| ApiError::lib_or(tau_field, &e))?;
    let q = lekalo::quasi_interpolate_expression(&space, tau(), &f)
        .map_err(|e| ApiError::lib_or("expression", &e))?;
    let opts = ViewOptions {
        samples: r.intervals + 1,
        basis_samples: r.basis_samples,
        ..ViewOptions::default()
    };
    let error: Vec<f64> = s.exact.iter().zip(&s.approx).map(|(a, b)| a - b).collect();
    let view = view_in(job, &Object::BSpline(q), &opts, "breakpoints")?;
    let size = view.size_hint() + 4 * error.len() * NUMBER_BYTES + SMALL;
    let a = QuasiAnswer {
        view,
        max_error: s.max_error(),
        t: s.t,
        exact: s.exact,
        approx: s.approx,
        error,
    };
    Ok(answer(&a, size))
}
