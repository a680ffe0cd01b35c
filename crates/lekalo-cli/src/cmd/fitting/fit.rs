//! `lekalo fit` on curves: the modes (least squares, smoothing, the smoothing condition, fitting
//! to a tolerance, robust fits, shape constraints) and their knots and end constraints; surfaces
//! and closed curves go to `surface.rs` and `periodic.rs`.

use anyhow::Result;
use lekalo::fit::{
    constrained_least_squares, constrained_smoothing_condition, constrained_smoothing_spline,
    fit_tolerance_with_progress, least_squares_with_progress, place_knots, robust_least_squares,
    smoothing_condition_with_rounds, smoothing_on_knots_with_progress,
    smoothing_spline_with_progress, CurveFit, Deviation, EndConstraints, FitData, RobustLoss,
    ToleranceOptions,
};
use lekalo::{parametrize, KnotVector, Points};
use lekalo_io::Object;
use serde_json::{json, Value};

use super::args::{clamped, span, with_ends, FitArgs, Robust, LARGE};
use super::report::finish;
use super::shapes::shape_constraints;
use super::{periodic::run_periodic, surface::run_surface};
use crate::cancel::with_progress;
use crate::context::Context;
use crate::exit::bad_input;
use crate::values::numbers;

pub(crate) fn run(a: &FitArgs, cx: &Context) -> Result<()> {
    fit(a, cx).map_err(|e| crate::items::at_point_lines(cx, &a.points, e))
}

fn fit(a: &FitArgs, cx: &Context) -> Result<()> {
    let modes = [
        a.lsq,
        a.smooth.is_some(),
        a.s.is_some(),
        a.tol.is_some(),
        a.robust.is_some(),
    ];
    if modes.iter().filter(|&&m| m).count() > 1 {
        return bad_input("choose one mode: --lsq, --smooth, --s, --tolerance or --robust");
    }
    a.check_options_used()?;
    if a.sphere {
        return super::sphere::run(a, cx);
    }
    // a Parquet file with --grid or --scattered is one table (read below as points)
    if crate::items::is_parquet(&a.points) && a.grid.is_none() && !a.scattered {
        if a.periodic || a.weights.is_some() || a.json || a.per_point {
            return bad_input("a Parquet batch is fitted by open curves, one per group: --periodic, --weights, --json and --per-point are for one points file (with --grid or --scattered, a Parquet file is one table of data)");
        }
        // the work on one group of points
        let quiet = cx.quiet();
        let curve = |pts: &Points| -> Result<Object> {
            let (fit, _, _) = fit_curve(a, pts, None, "the group", &quiet)?;
            Ok(Object::BSpline(fit.curve))
        };
        return crate::batch::parquet::curves_of_groups(
            cx,
            &a.points,
            a.out.output.as_deref(),
            &curve,
        );
    }
    if let Some(n) = super::tensor::variables(a)? {
        return super::tensor::run(a, n, cx);
    }
    let (pts, name) = crate::items::read_points(cx, &a.points)?;
    let mut inputs = vec![a.points.clone()];
    let weights = match &a.weights {
        Some(p) => {
            let (t, n) = lekalo_io::read_input(p)?;
            inputs.push(p.clone());
            Some(lekalo_io::read_points(&t, &n)?.into_vec())
        }
        None => None,
    };
    if a.grid.is_some() || a.scattered {
        return run_surface(a, &pts, weights.as_deref(), &inputs, cx);
    }
    if a.periodic {
        return run_periodic(a, &pts, weights.as_deref(), &inputs, cx);
    }
    let (fit, report, shown) = fit_curve(a, &pts, weights.as_deref(), &name, cx)?;
    finish(
        a,
        Object::BSpline(fit.curve.clone()),
        &shown,
        &fit,
        report,
        &inputs,
        cx,
    )
}

/// The curve fitted to `pts` (named `name` in messages) in the mode of `a`, its report's
/// mode-specific entries and the points to show in plots.
fn fit_curve(
    a: &FitArgs,
    pts: &Points,
    weights: Option<&[f64]>,
    name: &str,
    cx: &Context,
) -> Result<(CurveFit, Value, Points)> {
    // data: function samples (x, y…) or parametric points
    let (values, params) = if a.function {
        if pts.dim() < 2 {
            return bad_input(format!(
                "{name}: --function needs two columns or more, x and y"
            ));
        }
        let x: Vec<f64> = pts.iter().map(|p| p[0]).collect();
        let y = Points::from_flat(
            pts.dim() - 1,
            pts.iter().flat_map(|p| p[1..].to_vec()).collect(),
        )?;
        (y, x)
    } else {
        let u = parametrize(pts.as_view(), a.param())?;
        (pts.clone(), u)
    };
    let mut data = FitData::new(values.as_view(), &params)?;
    if let Some(w) = weights {
        data = data.with_weights(w)?;
    }
    let mut report = json!({});
    let shape = shape_constraints(a)?;
    if !shape.is_empty() {
        if !a.function {
            return bad_input(
                "shape constraints (--increasing, --convex, --min, --through, …) are for functions y(x): add --function",
            );
        }
        if a.tol.is_some() || a.robust.is_some() || (a.s.is_some() && a.knots.is_some()) {
            return bad_input(
                "shape constraints go with least squares (--lsq, the default), --smooth, or --s without --knots (the smoothing spline whose residual is S); drop --tolerance, --robust, or --knots with --s",
            );
        }
        if a.clamp_ends || a.d0.is_some() || a.dn.is_some() {
            return bad_input(
                "with shape constraints, give end values and slopes as --through X=V and --slope-at X=V instead of --clamp-ends/--start-derivative/--end-derivative",
            );
        }
        report["constraints"] = json!((0..shape.len())
            .map(|i| shape.describe(i))
            .collect::<Vec<_>>());
    }
    let fit: CurveFit = if let Some(sm) = &a.smooth {
        let lambda = match super::args::smoothing_weights(sm)?[..] {
            [l] => l,
            _ => {
                return bad_input(format!(
                    "--smooth: \"{sm}\" gives several weights; a curve takes one λ ≥ 0 or gcv \
                     (one per direction is for grids, --grid AxB…)"
                ))
            }
        };
        if shape.is_empty() {
            let large = data.len() > LARGE;
            with_progress(cx, "smoothing", large, |p| {
                smoothing_spline_with_progress(&data, lambda, p)
            })?
        } else {
            constrained_smoothing_spline(&data, lambda, &shape)?
        }
    } else if let Some(s) = a.s {
        report["s"] = json!(s);
        let large = data.len() > LARGE;
        let degree = a.degree()?;
        if !shape.is_empty() {
            if a.domain.is_some() {
                return bad_input(
                    "--domain: with shape constraints --s fits the cubic smoothing spline with \
                     knots at the data; drop --domain",
                );
            }
            constrained_smoothing_condition(&data, s, &shape)?
        } else if a.knots.is_some() {
            let knots = curve_knots(a, &params)?;
            with_progress(cx, "smoothing on the knots", large, |p| {
                smoothing_on_knots_with_progress(&data, degree, &knots, s, p)
            })?
        } else {
            let domain = domain_arg(a, &params)?;
            let rounds = a.knot_rounds.unwrap_or_default();
            with_progress(cx, "smoothing condition", large, |p| {
                smoothing_condition_with_rounds(&data, degree, s, domain, rounds, p)
            })?
        }
    } else if let Some(tol) = a.tol {
        if a.function {
            return bad_input(
                "--tolerance fits parametric curves (distance to the curve); drop --function",
            );
        }
        let mut opts = ToleranceOptions::new(a.degree()?, tol);
        opts.parametrization = a.param();
        if a.parameter_deviation {
            opts.deviation = Deviation::Parameter;
        }
        // a bar on a terminal for large data; Ctrl-C stops the fit between two steps
        let large = pts.len() > LARGE;
        let t = with_progress(cx, "fitting to the tolerance", large, |p| {
            fit_tolerance_with_progress(pts.as_view(), &opts, p)
        })?;
        report["tolerance"] = json!(tol);
        report["max_deviation"] = json!(t.max_deviation);
        report["worst_index"] = json!(t.worst_index);
        report["worst_param"] = json!(t.worst_param);
        if a.per_point {
            report["deviations"] = json!(t.deviations);
        }
        // the residuals at the parameters the deviations were measured at (each point's
        // closest point on the curve): they are the deviations, within the tolerance
        let d = FitData::new(pts.as_view(), &t.closest_params)?;
        let fit = least_squares_report(&t.curve, &d)?;
        return Ok((fit, report, pts.clone()));
    } else {
        let knots = curve_knots(a, &params)?;
        let ends = constraints(a)?;
        match a.robust {
            Some(r) => {
                if ends != EndConstraints::none() || !shape.is_empty() {
                    return bad_input(
                        "--robust fits without end or shape constraints; drop --clamp-ends/--start-derivative/--end-derivative",
                    );
                }
                let loss = match r {
                    Robust::Huber => RobustLoss::Huber(1.345),
                    Robust::Tukey => RobustLoss::Tukey(4.685),
                };
                let r = robust_least_squares(&data, a.degree()?, &knots, loss, 50)?;
                report["robust_weights"] = json!(r.weights);
                report["robust_scale"] = json!(r.scale);
                report["iterations"] = json!(r.iterations);
                r.fit
            }
            None if !shape.is_empty() => {
                constrained_least_squares(&data, a.degree()?, &knots, &shape)?
            }
            None => {
                let (degree, large) = (a.degree()?, data.len() > LARGE);
                with_progress(cx, "least squares", large, |p| {
                    least_squares_with_progress(&data, degree, &knots, &ends, p)
                })?
            }
        }
    };
    let shown = if a.function { pts.clone() } else { values };
    Ok((fit, report, shown))
}

/// The report of a curve that is already fitted (tolerance mode).
fn least_squares_report(curve: &lekalo::BSplineCurve, d: &FitData<'_>) -> Result<CurveFit> {
    Ok(CurveFit {
        curve: curve.clone(),
        report: lekalo::fit::FitReport::of(curve, d)?,
    })
}

/// `--domain A:B`, checked to hold the data's parameters `params`.
fn domain_arg(a: &FitArgs, params: &[f64]) -> Result<Option<(f64, f64)>> {
    let data = params
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &u| {
            (l.min(u), h.max(u))
        });
    Ok(match &a.domain {
        Some(text) => {
            let (lo, hi) = span(text, "--domain", "--domain -1:2")?;
            if lo > data.0 || hi < data.1 {
                let of = if a.function { "x" } else { "parameters" };
                return bad_input(format!(
                    "--domain {text} does not hold the data: their {of} run from {} to {}; give \
                     a domain around them, e.g. --domain {}:{}",
                    data.0,
                    data.1,
                    lo.min(data.0),
                    hi.max(data.1)
                ));
            }
            Some((lo, hi))
        }
        None => None,
    })
}

fn curve_knots(a: &FitArgs, params: &[f64]) -> Result<KnotVector> {
    let p = a.degree()?;
    let data = params
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &u| {
            (l.min(u), h.max(u))
        });
    let domain = domain_arg(a, params)?;
    if let Some(k) = &a.knots {
        if a.ctrl.is_some() {
            return bad_input("give --ctrl or --knots, not both");
        }
        let inner = numbers(k, "--knots")?;
        let within = if domain.is_some() {
            "--domain"
        } else {
            "the data's parameters, or --domain"
        };
        return clamped(p, domain.unwrap_or(data), &inner, "--knots", within);
    }
    let n = a.ctrl.unwrap_or((params.len() / 10).max(p + 1));
    if a.ctrl.is_none() && params.len() < n {
        // no count was asked for: say what the default asks and how to fit these points
        let fix = if params.len() >= 2 {
            format!(
                "give --degree {} or lower, or more points",
                params.len() - 1
            )
        } else {
            "give at least two points".to_string()
        };
        return bad_input(format!(
            "{} data points are too few for a fit of degree {p}: it needs degree + 1 = {n} \
             control points and at least as many points; {fix}",
            params.len(),
        ));
    }
    let mut sorted = params.to_vec();
    sorted.sort_by(f64::total_cmp);
    let placed = place_knots(&sorted, p, n)?;
    match domain {
        Some(ends) => with_ends(&placed, p, ends),
        None => Ok(placed),
    }
}

fn constraints(a: &FitArgs) -> Result<EndConstraints> {
    let mut e = if a.clamp_ends {
        EndConstraints::points()
    } else {
        EndConstraints::none()
    };
    if (a.d0.is_some() || a.dn.is_some()) && !a.clamp_ends {
        return bad_input("--start-derivative/--end-derivative need --clamp-ends (the end points are interpolated too)");
    }
    if let Some(d) = &a.d0 {
        e = e.with_start_derivative(numbers(d, "--start-derivative")?);
    }
    if let Some(d) = &a.dn {
        e = e.with_end_derivative(numbers(d, "--end-derivative")?);
    }
    Ok(e)
}
