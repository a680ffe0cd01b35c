//! `lekalo fit --sphere`: bicubic splines on the sphere `s(θ, φ)`, one value at each pole and
//! periodic in the longitude, fitted to scattered rows `θ, φ, r` (least squares on the knots
//! `--knots-u`, `--knots-v`, or the smoothing condition `--s`) or to values on a grid of
//! colatitudes and longitudes with pole conditions. Parsing and presentation only; the fits are
//! the library's ([`lekalo::fit::sphere_least_squares`], [`lekalo::fit::sphere_smoothing`],
//! [`lekalo::fit::sphere_grid_smoothing`]; `docs/theory/sphere.md`).

use std::path::PathBuf;

use anyhow::Result;
use lekalo::fit::{
    sphere_grid_smoothing, sphere_least_squares, sphere_smoothing, PoleCondition, SphereData,
    SphereFit, SphereGrid,
};
use serde_json::json;

use super::args::{FitArgs, LARGE};
use super::tensor::finish_with;
use crate::cancel::with_progress;
use crate::cmd::tensor::{checked_grid_values, given_parameters, grid_factors};
use crate::context::Context;
use crate::exit::bad_input;
use crate::values::numbers;

/// FITPACK's rank threshold of the least-squares solutions (no option sets it: `Arg::Eps`).
const EPS: f64 = 1e-16;

/// The fit on the sphere asked by `a`, written with its report.
pub(super) fn run(a: &FitArgs, cx: &Context) -> Result<()> {
    refuse_other_options(a)?;
    match (a.scattered, &a.grid) {
        (true, None) => scattered(a, cx),
        (false, Some(g)) => grid(a, g, cx),
        _ => bad_input(
            "--sphere fits either scattered rows theta, phi, r (add --scattered) or values on a \
             grid of colatitudes and longitudes (add --grid NUxNV with --params-u and --params-v)",
        ),
    }
}

/// Scattered rows `θ, φ, r`: least squares on `--knots-u` (θ) and `--knots-v` (φ), or the
/// smoothing condition `--s`, weighted by `--weights`.
fn scattered(a: &FitArgs, cx: &Context) -> Result<()> {
    if a.pole_given() {
        return bad_input(
            "--pole-values, --pole-exact, --pole-continuity and --pole-flat are for --sphere \
             --grid; a scattered fit on the sphere has one value at each pole and a continuous \
             derivative across it (FITPACK's sphere): drop them",
        );
    }
    let (pts, _) = crate::items::read_points(cx, &a.points)?;
    if pts.dim() != 3 {
        return bad_input(format!(
            "--sphere --scattered reads rows theta, phi, r (three columns: colatitude in [0, pi], \
             longitude in [0, 2pi], value); {} has {}",
            a.points.display(),
            pts.dim()
        ));
    }
    let column = |c: usize| pts.iter().map(|r| r[c]).collect::<Vec<f64>>();
    let (theta, phi, r) = (column(0), column(1), column(2));
    let mut inputs = vec![a.points.clone()];
    let weights = match &a.weights {
        Some(p) => {
            let (t, name) = lekalo_io::read_input(p)?;
            inputs.push(p.clone());
            Some(lekalo_io::read_points(&t, &name)?.into_vec())
        }
        None => None,
    };
    let data = SphereData::new(&theta, &phi, &r, weights.as_deref())?;
    let knots = [(&a.knots_u, "--knots-u"), (&a.knots_v, "--knots-v")]
        .map(|(k, option)| k.as_deref().map(|t| numbers(t, option)).transpose());
    let [ku, kv] = knots;
    let (ku, kv) = (ku?, kv?);
    let fit = match (a.s, ku, kv) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
            return bad_input(
                "--s places the knots on the sphere itself (FITPACK's sphere): drop --knots-u and \
                 --knots-v, or drop --s for least squares on them",
            )
        }
        (Some(s), None, None) => {
            with_progress(cx, "smoothing on the sphere", r.len() > LARGE, |p| {
                sphere_smoothing(&data, s, EPS, p)
            })?
        }
        (None, Some(tt), Some(tp)) => sphere_least_squares(&data, &tt, &tp, EPS)?,
        (None, _, _) => return bad_input(
            "--sphere --scattered is least squares on the interior knots --knots-u (colatitudes \
                 in (0, pi)) and --knots-v (longitudes in (0, 2pi)), or the smoothing condition \
                 --s S: give both lists of knots, or --s",
        ),
    };
    let at: Vec<f64> = theta.iter().zip(&phi).flat_map(|(t, p)| [*t, *p]).collect();
    write(a, &fit, &at, &r, a.s, &inputs, cx)
}

/// Values on the grid `--params-u × --params-v` (colatitudes in `(0, π)`, longitudes from
/// `v₀ ∈ [−π, π)` over less than a period), one per node with `u` slowest: interpolation
/// (`--s 0`, the default) or the smoothing condition, with the pole conditions.
fn grid(a: &FitArgs, g: &str, cx: &Context) -> Result<()> {
    let refused: Vec<&str> = [
        (a.lsq, "--lsq"),
        (a.knots_u.is_some(), "--knots-u"),
        (a.knots_v.is_some(), "--knots-v"),
        (a.weights.is_some(), "--weights"),
    ]
    .iter()
    .filter(|(on, _)| *on)
    .map(|(_, name)| *name)
    .collect();
    if !refused.is_empty() {
        return bad_input(format!(
            "{}: a grid on the sphere is fitted by --s S (0, the default, interpolates), its knots \
             placed by FITPACK's spgrid and every node weighing alike; drop {}",
            refused.join(", "),
            if refused.len() == 1 { "it" } else { "them" }
        ));
    }
    let shape = grid_factors(g)?;
    if shape.len() != 2 {
        return bad_input(format!(
            "--grid {g}: a grid on the sphere has two directions, colatitudes and longitudes \
             (e.g. --grid 9x12)"
        ));
    }
    let values = checked_grid_values(g, &shape, &a.points, cx)?;
    if values.dim() != 1 {
        return bad_input(format!(
            "--sphere --grid reads one value per node (one column); {} has {}",
            a.points.display(),
            values.dim()
        ));
    }
    let given = given_parameters(a.grid_params(), &shape, g, cx)?;
    let (Some((_, u)), Some((_, v))) = (&given[0], &given[1]) else {
        return bad_input(
            "--sphere --grid needs the colatitudes of its rows, --params-u (in (0, pi)), and the \
             longitudes of its columns, --params-v (from v0 in [-pi, pi), less than 2pi apart)",
        );
    };
    let poles = poles(a)?;
    let r = values.into_vec();
    let grid = SphereGrid::new(u, v, &r)?;
    let s = a.s.unwrap_or(0.0);
    let fit = with_progress(
        cx,
        "smoothing on a grid of the sphere",
        r.len() > LARGE,
        |p| sphere_grid_smoothing(&grid, s, poles, p),
    )?;
    let at: Vec<f64> = u
        .iter()
        .flat_map(|t| v.iter().flat_map(|p| [*t, *p]))
        .collect();
    write(
        a,
        &fit,
        &at,
        &r,
        Some(s),
        std::slice::from_ref(&a.points),
        cx,
    )
}

/// The pole conditions at `θ = 0` and `θ = π` from `--pole-values`, `--pole-exact`,
/// `--pole-continuity`, `--pole-flat`.
fn poles(a: &FitArgs) -> Result<[PoleCondition; 2]> {
    let values = match &a.pole_values {
        None => [None, None],
        Some(text) => pair(text, "--pole-values", "--pole-values 1 or 1,none", |w| {
            if w.eq_ignore_ascii_case("none") {
                Some(None)
            } else {
                w.parse::<f64>().ok().map(Some)
            }
        })?,
    };
    let flag = |text: &Option<String>, option: &str| -> Result<[bool; 2]> {
        match text {
            None => Ok([false, false]),
            Some(t) => pair(
                t,
                option,
                &format!("{option} or {option}=true,false"),
                |w| match w.to_ascii_lowercase().as_str() {
                    "true" => Some(true),
                    "false" => Some(false),
                    _ => None,
                },
            ),
        }
    };
    let exact = flag(&a.pole_exact, "--pole-exact")?;
    let continuity = flag(&a.pole_continuity, "--pole-continuity")?;
    let flat = flag(&a.pole_flat, "--pole-flat")?;
    Ok([0, 1].map(|i| PoleCondition {
        value: values[i],
        exact: exact[i],
        continuity: continuity[i],
        flat: flat[i],
    }))
}

/// `X` (both poles) or `X0,X1` (`θ = 0`, `θ = π`) of `option`, each word read by `word`.
fn pair<T: Copy>(
    text: &str,
    option: &str,
    example: &str,
    word: impl Fn(&str) -> Option<T>,
) -> Result<[T; 2]> {
    let words: Vec<Option<T>> = text.split(',').map(|w| word(w.trim())).collect();
    match words[..] {
        [Some(x)] => Ok([x, x]),
        [Some(x), Some(y)] => Ok([x, y]),
        _ => bad_input(format!(
            "{option}: \"{text}\" is not one value for both poles or two (theta = 0, theta = pi), \
             e.g. {example}"
        )),
    }
}

/// Writes the fitted spline and its report: the residuals at the data `at` (θ, φ pairs) of
/// the values `r`, the library's weighted residual, `s`, `p`, the rank and the knot limit.
fn write(
    a: &FitArgs,
    fit: &SphereFit,
    at: &[f64],
    r: &[f64],
    s: Option<f64>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let mut fitted = vec![0.0; r.len()];
    fit.spline.par_eval_batch(at, None, &mut fitted)?;
    let residuals: Vec<f64> = fitted.iter().zip(r).map(|(f, v)| (f - v).abs()).collect();
    if let (Some(l), Some(s), false) = (fit.limit, s, cx.is_quiet()) {
        crate::output::report(&format!(
            "fit: no knot could be added ({l}); the least-squares spline on the knots found has \
             weighted RSS {} > --s {s}",
            lekalo_io::fmt_number(fit.fp)
        ));
    }
    let extra = json!({ "s": s, "p": fit.p, "rank": fit.rank, "unknowns": fit.unknowns,
        "knot_limit": fit.limit });
    let net = fit.spline.shape().to_vec();
    finish_with(
        a,
        &fit.spline,
        &net,
        &residuals,
        fit.fp,
        Some(extra),
        inputs,
        cx,
    )
}

/// The options of other fits, refused with `--sphere` (its splines are bicubic, periodic in
/// the longitude, with their own knots and domain).
fn refuse_other_options(a: &FitArgs) -> Result<()> {
    let others = [
        (a.ctrl_grid.is_some(), "--ctrl-grid"),
        (a.knots.is_some(), "--knots"),
        (!a.knots_in.is_empty(), "--knots-in"),
        (!a.params_in.is_empty(), "--params-in"),
        (a.bbox.is_some(), "--bbox"),
        (a.domain.is_some(), "--domain"),
        (a.param.is_some(), "--param"),
        (a.penalty != 0.0, "--penalty"),
        (a.knot_rounds.is_some(), "--knot-rounds"),
        (
            !matches!(a.degrees[..], [3] | [3, 3]),
            "--degree (other than 3)",
        ),
    ];
    let given: Vec<&str> = a
        .curve_options()
        .into_iter()
        .chain(others)
        .filter(|(on, _)| *on)
        .map(|(_, name)| name)
        .collect();
    if given.is_empty() {
        return Ok(());
    }
    bad_input(format!(
        "{} {} not for --sphere: a fit on the sphere is bicubic in (theta, phi), periodic in \
         phi with one value at each pole; it takes --knots-u, --knots-v, --s, --weights \
         (scattered) and the pole options (--grid)",
        given.join(", "),
        if given.len() == 1 { "is" } else { "are" }
    ))
}
