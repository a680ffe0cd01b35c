//! `lekalo fit --periodic`: closed curves and periodic functions.

use std::path::PathBuf;

use anyhow::Result;
use lekalo::fit::{
    closed_parameters, constrained_least_squares, periodic_least_squares_with_progress,
    periodic_smoothing_condition_with_progress, periodic_smoothing_on_knots_with_progress, FitData,
};
use lekalo::{KnotVector, Points};
use lekalo_io::Object;
use serde_json::json;

use super::args::FitArgs;
use super::report::finish;
use super::shapes::shape_constraints;
use crate::cancel::with_progress;
use crate::context::Context;
use crate::exit::bad_input;
use crate::values::numbers;

// -- closed curves and periodic functions (`lekalo fit --periodic`): least squares with given
// knots or the smoothing condition (`lekalo::fit::periodic_least_squares`,
// `periodic_smoothing_condition`) --

/// Fits a closed curve: parametric points are parametrised closed (one parameter more, for the
/// chord back to the first point); with `--function` the period is `[x_first, x_last]` and the
/// last row, the repetition of the first, is left out (as SciPy's `splrep(per=1)` does).
pub(super) fn run_periodic(
    a: &FitArgs,
    pts: &Points,
    weights: Option<&[f64]>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    if a.smooth.is_some() || a.tol.is_some() || a.robust.is_some() {
        return bad_input(
            "--periodic fits by least squares (--lsq, --ctrl, --knots) or with --s; drop \
             --smooth, --tolerance and --robust",
        );
    }
    if a.clamp_ends || a.d0.is_some() || a.dn.is_some() {
        return bad_input("a closed curve has no ends: drop --clamp-ends, --d0 and --dn");
    }
    let (values, params, domain) = if a.function {
        if pts.dim() < 2 || pts.len() < 2 {
            return bad_input(
                "--function --periodic needs two columns (x, y) and two rows or more",
            );
        }
        let n = pts.len() - 1;
        let x: Vec<f64> = pts.iter().take(n).map(|p| p[0]).collect();
        let end = pts.point(n)[0];
        let y = Points::from_flat(
            pts.dim() - 1,
            pts.iter().take(n).flat_map(|p| p[1..].to_vec()).collect(),
        )?;
        (y, x.clone(), (x[0], end))
    } else {
        let u = closed_parameters(pts.as_view(), a.param())?;
        let n = pts.len();
        (pts.clone(), u[..n].to_vec(), (u[0], u[n]))
    };
    let mut data = FitData::new(values.as_view(), &params)?;
    let w;
    if let Some(all) = weights {
        w = if a.function && all.len() == pts.len() {
            all[..params.len()].to_vec()
        } else {
            all.to_vec()
        };
        data = data.with_weights(&w)?;
    }
    let mut report = json!({ "periodic": true, "period": [domain.0, domain.1] });
    let shape = shape_constraints(a)?;
    if !shape.is_empty() {
        if !a.function {
            return bad_input(
                "shape constraints (--increasing, --convex, --min, --through, …) are for functions y(x): add --function",
            );
        }
        if a.s.is_some() {
            return bad_input(
                "--periodic with shape constraints fits by least squares (--lsq, --ctrl, \
                 --knots); drop --s",
            );
        }
        report["constraints"] = json!((0..shape.len())
            .map(|i| shape.describe(i))
            .chain(std::iter::once("periodic".to_string()))
            .collect::<Vec<_>>());
    }
    // a bar on a terminal for large data; Ctrl-C stops the fit between two steps
    let large = data.len() > super::args::LARGE;
    let degree = a.degree()?;
    let fit = if let Some(s) = a.s {
        report["s"] = json!(s);
        match &a.knots {
            Some(k) => {
                let mut breaks = vec![domain.0];
                breaks.extend(numbers(k, "--knots")?);
                breaks.push(domain.1);
                with_progress(cx, "closed smoothing on the knots", large, |p| {
                    periodic_smoothing_on_knots_with_progress(&data, degree, &breaks, s, p)
                })?
            }
            None => with_progress(cx, "closed smoothing condition", large, |p| {
                periodic_smoothing_condition_with_progress(&data, degree, s, domain, p)
            })?,
        }
    } else {
        let (lo, hi) = domain;
        let mut breaks = vec![lo];
        if let Some(k) = &a.knots {
            if a.ctrl.is_some() {
                return bad_input("give --ctrl or --knots, not both");
            }
            breaks.extend(numbers(k, "--knots")?);
        } else {
            // --ctrl N: N free control points, N equal spans of the period
            let n = a.ctrl.unwrap_or((params.len() / 10).max(a.degree()? + 1));
            if n == 0 {
                return bad_input("--ctrl: a closed curve needs one control point or more");
            }
            breaks.extend((1..n).map(|j| lo + (hi - lo) * j as f64 / n as f64));
        }
        breaks.push(hi);
        if shape.is_empty() {
            with_progress(cx, "closed least squares", large, |p| {
                periodic_least_squares_with_progress(&data, degree, &breaks, p)
            })?
        } else {
            // the periodic splines on these breakpoints are the clamped ones whose derivatives
            // below the degree agree at the ends: the library's periodicity constraint
            let mut t = vec![lo; degree];
            t.extend(&breaks);
            t.extend(std::iter::repeat_n(hi, degree));
            let kv = KnotVector::new(t)?;
            constrained_least_squares(&data, degree, &kv, &shape.with_periodicity())?
        }
    };
    let shown = if a.function { pts } else { &values };
    finish(
        a,
        Object::BSpline(fit.curve.clone()),
        shown,
        &fit,
        report,
        inputs,
        cx,
    )
}
