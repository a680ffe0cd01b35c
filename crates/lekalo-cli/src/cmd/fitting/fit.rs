//! `lekalo fit`: least squares, smoothing and fitting to a tolerance (curves and surfaces).
//! Parses arguments, calls `lekalo::fit`, writes the result and its report.

use lekalo_io::CurveJson;
use std::path::PathBuf;

use anyhow::Result;
use clap::{ArgAction, Args, ValueEnum};
use lekalo::fit::{
    closed_parameters, constrained_least_squares, constrained_smoothing_spline,
    fit_tolerance_with_progress, least_squares, periodic_least_squares,
    periodic_smoothing_condition, periodic_smoothing_on_knots, place_knots, robust_least_squares,
    smoothing_condition, smoothing_on_knots, smoothing_spline, surface_grid_least_squares_at,
    surface_grid_parameters, surface_scattered_least_squares, CurveFit, Deviation, EndConstraints,
    FitData, Lambda, RobustLoss, Shape, ShapeConstraints, ToleranceOptions,
};
use lekalo::{parametrize, KnotVector, Points};
use lekalo_io::Object;
use serde_json::{json, Value};

use crate::context::Context;
use crate::exit::bad_input;
use crate::output::emit;
use crate::output::objects::{write_curve, write_surface, OutArgs};
use crate::values::net_size;
use crate::values::numbers;
use crate::words::Words;

/// Robust loss for `--robust`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Robust {
    /// Huber weights (c = 1.345 robust standard deviations).
    Huber,
    /// Tukey's biweight (c = 4.685): outliers get weight 0.
    Tukey,
}

/// Arguments of `lekalo fit`.
#[derive(Args, Debug)]
#[command(after_help = "\
Modes (one of them; least squares by default):
  --lsq              least squares with --ctrl N control points or --knots (interior knots);
                     --domain A:B sets the end knots (a curve reaching beyond the data)
  --smooth LAMBDA    cubic smoothing spline, λ given, or `--smooth gcv` (cross-validation)
  --s S              fewest knots with weighted residual sum of squares <= S (like splrep);
                     with --knots, the least k-th derivative jumps on those knots with RSS = S
  --tol TOL          within TOL of every point (distance), few control points
  --robust huber|tukey   least squares that resists outliers (final weights in the report)
  --periodic         a closed curve (or periodic function), with --lsq/--ctrl/--knots or --s
Surfaces: --grid ROWSxCOLS or --scattered (rows u,v,z), with --ctrl-grid NUxNV or the interior
knots of each direction (--knots-u, --knots-v); --degree P,Q per direction; --bbox U0:U1,V0:V1
the domain (end knots); a grid's parameters --params-u, --params-v (default: from --param).

Shape constraints (--function fits by --lsq or --smooth; each holds for every x, not only at
the data; repeat an option for several intervals):
  --increasing[=A:B] --decreasing[=A:B] --convex[=A:B] --concave[=A:B]
  --min V[@A:B] --max V[@A:B]   bounds on y;  --through X=V  y(X) = V;  --slope-at X=V  y'(X) = V

The report (residual max and RMS, λ or s, control points) goes to standard error, or with
--json the output is {\"object\": …, \"report\": …}; --per-point adds every residual.

Examples:
  lekalo fit scan.csv --ctrl 20 -o fit.json
  lekalo fit scan.csv --lsq --knots 0.25,0.5,0.75 --clamp-ends --start-derivative 1,0 --end-derivative 0,-1
  lekalo fit xy.csv --function --smooth gcv --json
  lekalo fit xy.csv --function --s 0.05 --weights w.txt
  lekalo fit xy.csv --function --s 0.5 --knots 10,20
  lekalo fit track.csv --tol 0.01 -o track.svg
  lekalo fit xy.csv --function --ctrl 12 --robust tukey --json
  lekalo fit xy.csv --function --ctrl 10 --increasing --convex=0:15 --min 0
  lekalo fit xy.csv --function --smooth 1 --max 0.9 --concave=5:20 --through 0=0
  lekalo fit loop.csv --periodic --s 0.01 -o loop.json
  lekalo fit grid.csv --grid 30x20 --ctrl-grid 8x6 -o surface.json
  lekalo fit uvz.csv --scattered --ctrl-grid 10x10 --penalty 1e-3
  lekalo fit xy.csv --function --ctrl 8 --domain -5:35 -o wide.json
  lekalo fit grid.csv --grid 30x20 --degree 3,2 --knots-u 0.25,0.5,0.75 --knots-v 0.5 -o surface.json
  lekalo fit uvz.csv --scattered --knots-u 0.3,0.6 --knots-v 0.5 --bbox 0:1,0:1 --degree 3,2")]
pub(crate) struct FitArgs {
    /// Points file (CSV, whitespace text or JSON; `-` for standard input).
    points: PathBuf,
    /// Least squares with given control-point count or knots (the default mode).
    #[arg(long)]
    lsq: bool,
    /// Penalised smoothing: λ ≥ 0, or `gcv`.
    #[arg(long, value_name = "LAMBDA|gcv", allow_hyphen_values = true)]
    pub(crate) smooth: Option<String>,
    /// Smoothing condition: the weighted residual sum of squares target.
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub(crate) s: Option<f64>,
    /// Fit within this distance of every point.
    #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
    pub(crate) tol: Option<f64>,
    /// With --tol: measure the deviation at the data parameters instead of the distance.
    #[arg(long)]
    parameter_deviation: bool,
    /// Iteratively reweighted least squares with this loss.
    #[arg(long, value_enum)]
    pub(crate) robust: Option<Robust>,
    /// The points are (x, y...) samples of a function y(x): x is the parameter.
    #[arg(long)]
    pub(crate) function: bool,
    /// Degree of curves; a surface takes one for both directions or one per direction (`3,2`:
    /// 3 in u, 2 in v).
    #[arg(
        long = "degree",
        short = 'p',
        value_name = "P[,Q]",
        value_delimiter = ',',
        default_value = "3"
    )]
    pub(crate) degrees: Vec<usize>,
    /// Number of control points (least squares, robust; default: a tenth of the points, at
    /// least degree + 1).
    #[arg(long)]
    pub(crate) ctrl: Option<usize>,
    /// Interior knots (comma-separated, inside the parameter range) instead of --ctrl.
    #[arg(long, value_name = "LIST")]
    pub(crate) knots: Option<String>,
    /// The parameter domain A:B of the curve, its end knots: wider than the data's parameters
    /// (x with --function) for a curve that reaches beyond them (least squares and --robust;
    /// default: from the first to the last parameter, as splrep's xb, xe).
    #[arg(long, value_name = "A:B", allow_hyphen_values = true)]
    domain: Option<String>,
    /// Weights file: one number per point.
    #[arg(long, value_name = "FILE")]
    weights: Option<PathBuf>,
    /// Interpolate the first and last points exactly.
    #[arg(long)]
    pub(crate) clamp_ends: bool,
    /// First derivative at the start (with --clamp-ends), comma-separated. Formerly `--d0`.
    #[arg(long = "start-derivative", alias = "d0", allow_hyphen_values = true)]
    pub(crate) d0: Option<String>,
    /// First derivative at the end (with --clamp-ends), comma-separated. Formerly `--dn`.
    #[arg(long = "end-derivative", alias = "dn", allow_hyphen_values = true)]
    pub(crate) dn: Option<String>,
    /// Parametrisation of parametric curves.
    #[arg(long, value_parser = Words(&lekalo::vocabulary::PARAMETRIZATION), default_value = "chord")]
    pub(crate) param: lekalo::Parametrization,
    /// A closed curve (periodic spline; with --function, a periodic function whose last row
    /// repeats the first).
    #[arg(long)]
    pub(crate) periodic: bool,
    /// A grid of points (rows x columns) fitted by a surface.
    #[arg(long, value_name = "ROWSxCOLS")]
    grid: Option<String>,
    /// Scattered rows (u, v, z…) fitted by a surface z(u, v).
    #[arg(long)]
    scattered: bool,
    /// Surface control net size (e.g. 8x6).
    #[arg(long, value_name = "NUxNV")]
    ctrl_grid: Option<String>,
    /// Interior knots of a surface in u (comma-separated, inside the u range) instead of the
    /// u count of --ctrl-grid.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    knots_u: Option<String>,
    /// Interior knots of a surface in v, as --knots-u.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    knots_v: Option<String>,
    /// The surface's domain U0:U1,V0:V1, its end knots, as the `bbox` of SciPy's
    /// `LSQBivariateSpline`
    /// (default: the range of the data's u and v, or of the grid's parameters).
    #[arg(long, value_name = "U0:U1,V0:V1", allow_hyphen_values = true)]
    bbox: Option<String>,
    /// Parameters of the grid's rows (--grid): one number per row, a list or a file with one
    /// value per line (default: --param averaged over the grid's columns).
    #[arg(long, value_name = "LIST|FILE", allow_hyphen_values = true)]
    params_u: Option<String>,
    /// Parameters of the grid's columns (--grid), as --params-u.
    #[arg(long, value_name = "LIST|FILE", allow_hyphen_values = true)]
    params_v: Option<String>,
    /// Smoothing penalty of scattered surfaces (second differences of the net).
    #[arg(long, default_value_t = 0.0)]
    penalty: f64,
    /// Keep y(x) increasing (y' ≥ 0) everywhere, or with `=A:B` on [A, B].
    #[arg(long, value_name = "A:B", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    increasing: Vec<String>,
    /// Keep y(x) decreasing (y' ≤ 0) everywhere, or with `=A:B` on [A, B].
    #[arg(long, value_name = "A:B", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    decreasing: Vec<String>,
    /// Keep y(x) convex (y'' ≥ 0) everywhere, or with `=A:B` on [A, B].
    #[arg(long, value_name = "A:B", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    convex: Vec<String>,
    /// Keep y(x) concave (y'' ≤ 0) everywhere, or with `=A:B` on [A, B].
    #[arg(long, value_name = "A:B", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    concave: Vec<String>,
    /// Lower bound y ≥ V everywhere, or `V@A:B` on [A, B].
    #[arg(long, value_name = "V[@A:B]", allow_hyphen_values = true, action = ArgAction::Append)]
    min: Vec<String>,
    /// Upper bound y ≤ V everywhere, or `V@A:B` on [A, B].
    #[arg(long, value_name = "V[@A:B]", allow_hyphen_values = true, action = ArgAction::Append)]
    max: Vec<String>,
    /// A point the fit passes through: `X=V` for y(X) = V.
    #[arg(long, value_name = "X=V", allow_hyphen_values = true, action = ArgAction::Append)]
    through: Vec<String>,
    /// The slope at a point: `X=V` for y'(X) = V.
    #[arg(long, value_name = "X=V", allow_hyphen_values = true, action = ArgAction::Append)]
    slope_at: Vec<String>,
    /// Write {"object", "report"} as JSON instead of the object alone.
    #[arg(long)]
    json: bool,
    /// Add every point's residual to the report.
    #[arg(long)]
    per_point: bool,
    #[command(flatten)]
    out: OutArgs,
}

impl FitArgs {
    /// The degree of a curve: `--degree` with one value.
    fn degree(&self) -> Result<usize> {
        match self.degrees[..] {
            [p] => Ok(p),
            _ => bad_input(format!(
                "--degree: {} degrees given; a curve takes one (one per direction is for surfaces, \
                 --grid or --scattered)",
                self.degrees.len()
            )),
        }
    }

    /// The degrees (u, v) of a surface: `--degree P` for both directions or `--degree P,Q`.
    fn surface_degrees(&self) -> Result<(usize, usize)> {
        match self.degrees[..] {
            [p] => Ok((p, p)),
            [p, q] => Ok((p, q)),
            _ => bad_input(format!(
                "--degree: {} degrees given; a surface takes one, or one per direction (e.g. \
                 --degree 3,2: 3 in u, 2 in v)",
                self.degrees.len()
            )),
        }
    }

    /// Refuses the options that the chosen kind of fit does not use, naming them and the fit
    /// they belong to.
    fn check_options_used(&self) -> Result<()> {
        let surface = self.grid.is_some() || self.scattered;
        if !surface {
            let given: Vec<&str> = [
                (self.knots_u.is_some(), "--knots-u"),
                (self.knots_v.is_some(), "--knots-v"),
                (self.bbox.is_some(), "--bbox"),
                (self.params_u.is_some(), "--params-u"),
                (self.params_v.is_some(), "--params-v"),
            ]
            .iter()
            .filter(|(on, _)| *on)
            .map(|(_, name)| *name)
            .collect();
            if !given.is_empty() {
                return bad_input(format!(
                    "{} {} for surfaces: add --grid ROWSxCOLS or --scattered",
                    given.join(", "),
                    if given.len() == 1 { "is" } else { "are" }
                ));
            }
        }
        if self.domain.is_some() {
            if surface {
                return bad_input(
                    "--domain is the interval of a curve; a surface's domain is --bbox U0:U1,V0:V1",
                );
            }
            if self.periodic {
                return bad_input(
                    "--domain: a closed fit's period is its data's (--function: from the first x \
                     to the last); drop --domain",
                );
            }
            if self.smooth.is_some() || self.s.is_some() || self.tol.is_some() {
                return bad_input(
                    "--domain sets the end knots of least squares (--lsq, --ctrl, --knots, \
                     --robust); --smooth, --s and --tol place their own knots: drop --domain",
                );
            }
            if self.clamp_ends {
                return bad_input(
                    "--clamp-ends puts the curve's ends on the first and last points, at the ends \
                     of the domain; with --domain the domain reaches beyond the data: drop one",
                );
            }
        }
        if surface && self.knots.is_some() {
            return bad_input(
                "--knots is the interior knots of a curve; give a surface's as --knots-u and \
                 --knots-v",
            );
        }
        if self.scattered && (self.params_u.is_some() || self.params_v.is_some()) {
            return bad_input(
                "--params-u/--params-v are the parameters of a grid's rows and columns (--grid); \
                 --scattered reads u and v from the first two columns",
            );
        }
        Ok(())
    }
}

pub(crate) fn run(a: &FitArgs, cx: &Context) -> Result<()> {
    let modes = [
        a.lsq,
        a.smooth.is_some(),
        a.s.is_some(),
        a.tol.is_some(),
        a.robust.is_some(),
    ];
    if modes.iter().filter(|&&m| m).count() > 1 {
        return bad_input("choose one mode: --lsq, --smooth, --s, --tol or --robust");
    }
    a.check_options_used()?;
    if crate::items::is_parquet(&a.points) {
        if a.grid.is_some()
            || a.scattered
            || a.periodic
            || a.weights.is_some()
            || a.json
            || a.per_point
        {
            return bad_input("a Parquet batch is fitted by open curves, one per group: --grid, --scattered, --periodic, --weights, --json and --per-point are for one points file");
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
        let u = parametrize(pts.as_view(), a.param)?;
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
        if a.s.is_some() || a.tol.is_some() || a.robust.is_some() {
            return bad_input(
                "shape constraints go with least squares (--lsq, the default) or --smooth; drop --s, --tol and --robust",
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
        let lambda = if sm.eq_ignore_ascii_case("gcv") {
            Lambda::Gcv
        } else {
            match sm.parse::<f64>() {
                Ok(l) => Lambda::Given(l),
                Err(_) => {
                    return bad_input(format!("--smooth: \"{sm}\" is neither a number nor gcv"))
                }
            }
        };
        if shape.is_empty() {
            smoothing_spline(&data, lambda)?
        } else {
            constrained_smoothing_spline(&data, lambda, &shape)?
        }
    } else if let Some(s) = a.s {
        report["s"] = json!(s);
        if a.knots.is_some() {
            smoothing_on_knots(&data, a.degree()?, &curve_knots(a, &params)?, s)?
        } else {
            smoothing_condition(&data, a.degree()?, s)?
        }
    } else if let Some(tol) = a.tol {
        if a.function {
            return bad_input(
                "--tol fits parametric curves (distance to the curve); drop --function",
            );
        }
        let mut opts = ToleranceOptions::new(a.degree()?, tol);
        opts.parametrization = a.param;
        if a.parameter_deviation {
            opts.deviation = Deviation::Parameter;
        }
        // a bar on a terminal for large data; Ctrl-C stops the fit between two steps
        let large = pts.len() > 100_000;
        let t = crate::cancel::with_progress(cx, "fitting to the tolerance", large, |p| {
            fit_tolerance_with_progress(pts.as_view(), &opts, p)
        })?;
        report["tol"] = json!(tol);
        report["max_deviation"] = json!(t.max_deviation);
        report["worst_index"] = json!(t.worst_index);
        report["worst_param"] = json!(t.worst_param);
        if a.per_point {
            report["deviations"] = json!(t.deviations);
        }
        let d = FitData::new(pts.as_view(), &t.params)?;
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
            None => least_squares(&data, a.degree()?, &knots, &ends)?,
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

pub(super) fn finish(
    a: &FitArgs,
    obj: Object,
    shown: &Points,
    fit: &CurveFit,
    mut report: Value,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let r = &fit.report;
    report["max_residual"] = json!(r.max_residual);
    report["max_index"] = json!(r.max_index);
    report["rms"] = json!(r.rms);
    report["weighted_rss"] = json!(r.weighted_rss);
    report["control_points"] = json!(r.n_ctrl);
    report["knots"] = json!(fit.curve.knots().len());
    if let Some(l) = r.lambda {
        report["lambda"] = json!(l);
    }
    if a.per_point {
        report["residuals"] = json!(r.residuals);
    }
    if a.json {
        let object: Value = serde_json::from_str(&obj.to_json_pretty())?;
        let text = serde_json::to_string_pretty(&json!({ "object": object, "report": report }))?;
        return emit(a.out.output.as_deref(), text.as_bytes(), inputs, cx);
    }
    if !cx.is_quiet() {
        crate::output::report(&report_line(&report));
    }
    write_curve(&obj, Some(shown), &a.out, inputs, cx)
}

fn report_line(r: &Value) -> String {
    let mut s = format!(
        "fit: {} control points, residual max {} (point {}), RMS {}, weighted RSS {}",
        r["control_points"], r["max_residual"], r["max_index"], r["rms"], r["weighted_rss"]
    );
    for key in ["lambda", "s", "tol", "max_deviation"] {
        if !r[key].is_null() {
            s.push_str(&format!(", {key} {}", r[key]));
        }
    }
    s
}

fn curve_knots(a: &FitArgs, params: &[f64]) -> Result<KnotVector> {
    let p = a.degree()?;
    let data = params
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &u| {
            (l.min(u), h.max(u))
        });
    let domain = match &a.domain {
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
    };
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

/// `A:B` with `A < B` (the value of `option`; `example` shows the spelling in the message).
fn span(text: &str, option: &str, example: &str) -> Result<(f64, f64)> {
    let ab = text
        .split_once(':')
        .map(|(a, b)| (numbers(a, option), numbers(b, option)));
    match ab {
        Some((Ok(a), Ok(b))) if a.len() == 1 && b.len() == 1 && a[0] < b[0] => Ok((a[0], b[0])),
        _ => bad_input(format!(
            "{option}: \"{text}\" is not an interval A:B with A < B (e.g. {example})"
        )),
    }
}

/// The clamped knot vector of degree `p` on `[lo, hi]` with the interior knots `inner` (of
/// `option`, which must lie inside the interval, set by `within`): `p + 1` copies of each end
/// around them, as the end knots of P&T eq. 9.68.
fn clamped(
    p: usize,
    (lo, hi): (f64, f64),
    inner: &[f64],
    option: &str,
    within: &str,
) -> Result<KnotVector> {
    if let Some(t) = inner.iter().find(|&&t| t <= lo || t >= hi) {
        return bad_input(format!(
            "{option}: the knot {t} is not inside the domain ({lo}, {hi}) ({within}); give \
             interior knots strictly between the ends"
        ));
    }
    let mut all = vec![lo; p + 1];
    all.extend_from_slice(inner);
    all.extend(vec![hi; p + 1]);
    Ok(KnotVector::new(all)?)
}

/// The clamped knots `k` of degree `p` with their `p + 1` end knots moved to `lo` and `hi` (a
/// domain wider than the data the interior knots were placed over).
fn with_ends(k: &KnotVector, p: usize, (lo, hi): (f64, f64)) -> Result<KnotVector> {
    let mut t = k.as_slice().to_vec();
    let n = t.len();
    t[..=p].fill(lo);
    t[n - p - 1..].fill(hi);
    Ok(KnotVector::new(t)?)
}

/// The shape constraints of the options, in the order of the options' kinds.
fn shape_constraints(a: &FitArgs) -> Result<ShapeConstraints> {
    let mut c = ShapeConstraints::new();
    let interval = |text: &str, option: &str| -> Result<Option<(f64, f64)>> {
        if text.is_empty() {
            return Ok(None);
        }
        let ab = numbers(&text.replacen(':', ",", 1), option)?;
        match ab[..] {
            [a, b] => Ok(Some((a, b))),
            _ => bad_input(format!("{option}: \"{text}\" is not an interval A:B")),
        }
    };
    let kinds: [(&[String], Shape, &str); 4] = [
        (&a.increasing, Shape::Increasing, "--increasing"),
        (&a.decreasing, Shape::Decreasing, "--decreasing"),
        (&a.convex, Shape::Convex, "--convex"),
        (&a.concave, Shape::Concave, "--concave"),
    ];
    for (list, shape, option) in kinds {
        for text in list {
            c = match interval(text, option)? {
                None => c.with(shape),
                Some((lo, hi)) => c.with_on(shape, lo, hi),
            };
        }
    }
    for (list, option) in [(&a.min, "--min"), (&a.max, "--max")] {
        for text in list {
            let (v, on) = text.split_once('@').unwrap_or((text, ""));
            let v = match numbers(v, option)?[..] {
                [v] => v,
                _ => return bad_input(format!("{option}: \"{text}\" is not V or V@A:B")),
            };
            let shape = if option == "--min" {
                Shape::AtLeast(v)
            } else {
                Shape::AtMost(v)
            };
            c = match interval(on, option)? {
                None => c.with(shape),
                Some((lo, hi)) => c.with_on(shape, lo, hi),
            };
        }
    }
    for (list, order, option) in [(&a.through, 0, "--through"), (&a.slope_at, 1, "--slope-at")] {
        for text in list {
            let parsed = text
                .split_once('=')
                .map(|(x, v)| (numbers(x, option), numbers(v, option)));
            match parsed {
                Some((Ok(x), Ok(v))) if x.len() == 1 && v.len() == 1 => {
                    c = c.with_point(x[0], order, v[0]);
                }
                _ => return bad_input(format!("{option}: \"{text}\" is not X=V")),
            }
        }
    }
    Ok(c)
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

fn run_surface(
    a: &FitArgs,
    pts: &Points,
    weights: Option<&[f64]>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let (p, q) = a.surface_degrees()?;
    let counts = match &a.ctrl_grid {
        Some(cg) => {
            let (ncu, ncv) = net_size(cg, "--ctrl-grid")?;
            (Some(ncu), Some(ncv))
        }
        None => (None, None),
    };
    let bbox = a.bbox.as_deref().map(bounding_box).transpose()?;
    let dirs = [
        Direction {
            name: "u",
            degree: p,
            inner: a
                .knots_u
                .as_deref()
                .map(|t| numbers(t, "--knots-u"))
                .transpose()?,
            knots_option: "--knots-u",
            count: counts.0,
            range: bbox.map(|b| b.0),
        },
        Direction {
            name: "v",
            degree: q,
            inner: a
                .knots_v
                .as_deref()
                .map(|t| numbers(t, "--knots-v"))
                .transpose()?,
            knots_option: "--knots-v",
            count: counts.1,
            range: bbox.map(|b| b.1),
        },
    ];
    for d in &dirs {
        d.check_count(counts)?;
    }
    if let Some(g) = &a.grid {
        let (nu, nv) = net_size(g, "--grid")?;
        let given = [
            (&a.params_u, "--params-u", nu, "rows"),
            (&a.params_v, "--params-v", nv, "columns"),
        ]
        .map(|(text, option, n, lines)| -> Result<Option<Vec<f64>>> {
            let Some(text) = text else { return Ok(None) };
            let t = crate::cmd::explicit::parameters(cx, text, option)?;
            if t.len() != n {
                return bad_input(format!(
                    "{option}: {} values for the {n} {lines} of --grid {g}; give one parameter \
                     per grid line",
                    t.len()
                ));
            }
            Ok(Some(t))
        });
        let [gu, gv] = given;
        let (gu, gv) = (gu?, gv?);
        // the parameters not given: --param averaged over the grid lines (P&T §9.2.5)
        let (uu, vv) = match (gu, gv) {
            (Some(u), Some(v)) => (u, v),
            (gu, gv) => {
                let (cu, cv) = surface_grid_parameters(pts.as_view(), (nu, nv), a.param)?;
                (gu.unwrap_or(cu), gv.unwrap_or(cv))
            }
        };
        let place = |d: &Direction, params: &[f64], n: usize, range: (f64, f64)| {
            let mut sorted = params.to_vec();
            sorted.sort_by(f64::total_cmp);
            let k = place_knots(&sorted, d.degree, n)?;
            with_ends(&k, d.degree, range)
        };
        let ku = dirs[0].knots(&uu, "u parameters of the grid's rows", &place)?;
        let kv = dirs[1].knots(&vv, "v parameters of the grid's columns", &place)?;
        let s =
            surface_grid_least_squares_at(pts.as_view(), (nu, nv), (p, q), (&uu, &vv), (&ku, &kv))?;
        return write_surface(&s, &a.out, inputs, cx);
    }
    if pts.dim() < 3 {
        return bad_input("--scattered needs rows u, v, z (three columns or more)");
    }
    let column = |c: usize| pts.iter().map(|r| r[c]).collect::<Vec<f64>>();
    let uniform = |d: &Direction, _: &[f64], n: usize, (lo, hi): (f64, f64)| {
        let k = KnotVector::clamped_uniform(d.degree, n)?;
        Ok(KnotVector::new(
            k.as_slice().iter().map(|t| lo + (hi - lo) * t).collect(),
        )?)
    };
    let (ncu, ncv) = (dirs[0].net_count(), dirs[1].net_count());
    // The system solved is banded: NU·NV rows of about p·NV + q + 1 numbers (twice NV with a
    // penalty). Its size is refused here, before the library allocates it.
    let band = p
        .saturating_mul(ncv)
        .saturating_add(q)
        .max(ncv.saturating_mul(2));
    let entries = ncu
        .saturating_mul(ncv)
        .saturating_mul(band.saturating_add(1));
    let limit = cx.max_size;
    if entries > limit {
        let net = match &a.ctrl_grid {
            Some(cg) if a.knots_u.is_none() && a.knots_v.is_none() => format!("--ctrl-grid {cg}"),
            _ => format!("a {ncu}x{ncv} control net (--ctrl-grid, --knots-u, --knots-v)"),
        };
        return bad_input(format!(
            "{net}: the scattered fit's least-squares system holds {entries} numbers ({} bytes), above the size limit {limit}; use a smaller control net, or raise the limit with --max-size {entries} if the machine has the memory",
            lekalo_io::fmt_number(entries as f64 * 8.0)
        ));
    }
    let ku = dirs[0].knots(
        &column(0),
        "u values of the data (the first column)",
        &uniform,
    )?;
    let kv = dirs[1].knots(
        &column(1),
        "v values of the data (the second column)",
        &uniform,
    )?;
    let f = surface_scattered_least_squares(pts.as_view(), weights, (p, q), (&ku, &kv), a.penalty)?;
    let max = f.residuals.iter().fold(0.0_f64, |m, &r| m.max(r));
    let rms = (f.residuals.iter().map(|r| r * r).sum::<f64>() / f.residuals.len() as f64).sqrt();
    let mut report = json!({ "max_residual": max, "rms": rms, "weighted_rss": f.weighted_rss,
        "control_points": ncu * ncv, "penalty": a.penalty });
    if a.per_point {
        report["residuals"] = json!(f.residuals);
    }
    if a.json {
        let object: Value = serde_json::from_str(&lekalo_io::bspline_surface_to_json(&f.surface))?;
        let text = serde_json::to_string_pretty(&json!({ "object": object, "report": report }))?;
        return emit(a.out.output.as_deref(), text.as_bytes(), inputs, cx);
    }
    if !cx.is_quiet() {
        crate::output::report(&format!(
            "fit: {ncu}x{ncv} control points, residual max {max}, RMS {rms}"
        ));
    }
    write_surface(&f.surface, &a.out, inputs, cx)
}

/// How a direction without given knots places `count` of them over its data's parameters,
/// clamped at the ends of its range: `place(direction, params, count, range)`.
type PlaceKnots = dyn Fn(&Direction, &[f64], usize, (f64, f64)) -> Result<KnotVector>;

/// One direction of a surface fit: its degree, and its knots given (`inner`, interior) or its
/// control-point count (`count`, from `--ctrl-grid`), with the domain `range` of `--bbox`.
struct Direction {
    name: &'static str,
    degree: usize,
    inner: Option<Vec<f64>>,
    knots_option: &'static str,
    count: Option<usize>,
    range: Option<(f64, f64)>,
}

impl Direction {
    /// The number of control points in this direction: set by its knots, or its count.
    fn net_count(&self) -> usize {
        match &self.inner {
            Some(k) => k.len() + self.degree + 1,
            None => self.count.unwrap_or(0),
        }
    }

    /// A direction needs interior knots or a count; given both, they must agree.
    fn check_count(&self, (ncu, ncv): (Option<usize>, Option<usize>)) -> Result<()> {
        let (name, option, p) = (self.name, self.knots_option, self.degree);
        match (&self.inner, self.count) {
            (None, None) => bad_input(format!(
                "surfaces need the control net's size --ctrl-grid NUxNV, or the interior knots of \
                 each direction (--knots-u, --knots-v); {name} has neither"
            )),
            (Some(k), Some(n)) if k.len() + p + 1 != n => {
                let implied = k.len() + p + 1;
                let (u, v) = if name == "u" {
                    (implied, ncv.unwrap_or(0))
                } else {
                    (ncu.unwrap_or(0), implied)
                };
                bad_input(format!(
                    "--ctrl-grid and {option} disagree: {} interior knots of degree {p} make \
                     {implied} control points in {name}, not {n}; drop --ctrl-grid or write \
                     --ctrl-grid {u}x{v}",
                    k.len()
                ))
            }
            _ => Ok(()),
        }
    }

    /// The knots of this direction over the data's parameters `params` (named `what` in
    /// messages): the interior knots given, or `place(self, params, count, range)`, clamped at
    /// the ends of `--bbox` (which must hold the data) or of the data.
    fn knots(&self, params: &[f64], what: &str, place: &PlaceKnots) -> Result<KnotVector> {
        let data = params
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &u| {
                (l.min(u), h.max(u))
            });
        let range = match self.range {
            Some((lo, hi)) => {
                if lo > data.0 || hi < data.1 {
                    return bad_input(format!(
                        "--bbox: the {what} run from {} to {}, outside {lo}:{hi}, the bbox's \
                         {name} interval; give one around them, e.g. {}:{}",
                        data.0,
                        data.1,
                        lo.min(data.0),
                        hi.max(data.1),
                        name = self.name
                    ));
                }
                (lo, hi)
            }
            None => data,
        };
        match (&self.inner, self.count) {
            (Some(inner), _) => {
                let within = if self.range.is_some() {
                    "--bbox"
                } else {
                    "the range of the data's parameters, or --bbox"
                };
                clamped(self.degree, range, inner, self.knots_option, within)
            }
            (None, Some(n)) => place(self, params, n, range),
            (None, None) => bad_input("surfaces need --ctrl-grid NUxNV (the control net size)"),
        }
    }
}

/// `U0:U1,V0:V1` of `--bbox`.
fn bounding_box(text: &str) -> Result<((f64, f64), (f64, f64))> {
    match text.split_once(',') {
        Some((u, v)) => Ok((
            span(u, "--bbox", "--bbox 0:1,-1:2")?,
            span(v, "--bbox", "--bbox 0:1,-1:2")?,
        )),
        None => bad_input(format!(
            "--bbox: \"{text}\" is not U0:U1,V0:V1 (e.g. --bbox 0:1,-1:2)"
        )),
    }
}

// -- closed curves and periodic functions (`lekalo fit --periodic`): least squares with given
// knots or the smoothing condition (`lekalo::fit::periodic_least_squares`,
// `periodic_smoothing_condition`) --

/// Fits a closed curve: parametric points are parametrised closed (one parameter more, for the
/// chord back to the first point); with `--function` the period is `[x_first, x_last]` and the
/// last row, the repetition of the first, is left out (as SciPy's `splrep(per=1)` does).
fn run_periodic(
    a: &FitArgs,
    pts: &Points,
    weights: Option<&[f64]>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    if a.smooth.is_some() || a.tol.is_some() || a.robust.is_some() {
        return bad_input(
            "--periodic fits by least squares (--lsq, --ctrl, --knots) or with --s; drop \
             --smooth, --tol and --robust",
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
        let u = closed_parameters(pts.as_view(), a.param)?;
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
    let fit = if let Some(s) = a.s {
        report["s"] = json!(s);
        match &a.knots {
            Some(k) => {
                let mut breaks = vec![domain.0];
                breaks.extend(numbers(k, "--knots")?);
                breaks.push(domain.1);
                periodic_smoothing_on_knots(&data, a.degree()?, &breaks, s)?
            }
            None => periodic_smoothing_condition(&data, a.degree()?, s, domain)?,
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
        periodic_least_squares(&data, a.degree()?, &breaks)?
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
