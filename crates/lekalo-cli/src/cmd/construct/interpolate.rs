//! `lekalo interpolate`: curves and surfaces through points (document 000; document 002, four-point
//! cubic and Hermite segment).

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};
use lekalo::vocabulary::{self, EndKind};
use lekalo::{
    natural_cubic_spline, CubicHermite, CurveInterpolation, KnotPlacement, Parametrization, Points,
    SurfaceInterpolation, TangentEstimate,
};
use lekalo_io::Object;

use crate::context::Context;
use crate::exit::bad_input;
use crate::output::objects::{write_curve, write_surface, OutArgs};
use crate::values::{net_size, numbers};
use crate::words::Words;

/// The parametrisation of `--param`, or the exponent of `--exponent` when given (document 000
/// §1; P&T eq. 9.4–9.6).
pub(crate) fn parametrization(param: Parametrization, exponent: Option<f64>) -> Parametrization {
    exponent.map_or(param, Parametrization::Exponent)
}

/// Tangent estimates for Hermite interpolation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Tangents {
    /// Mean of the neighbouring secant slopes.
    FiniteDifference,
    /// Catmull–Rom.
    CatmullRom,
    /// Cardinal with --tension.
    Cardinal,
    /// Fritsch–Carlson monotone (functions y(x)).
    Monotone,
}

/// Arguments of `lekalo interpolate`.
#[derive(Args, Debug)]
#[command(after_help = "\
Curves (document 000): global B-spline interpolation, any degree, every parametrisation,
knot placement and end condition. Surfaces (§5): --grid ROWSxCOLS reads the points row by row.
Grids in 3 or more directions (--grid AxBxC): one row of values per node, the first direction
slowest (or a .npy array of shape (A, B, C[, d])), a spline in as many parameters; --degree
takes one degree or one per direction; their parameters are equally spaced unless --param
says otherwise. --knots and --end (free, natural, periodic: the first line not repeated) apply
to every direction of every grid, surfaces included. A grid's parameters in a direction (the axis of a lookup table): --params-u,
--params-v (directions 1, 2) or --params-in K=LIST|FILE (direction K); the other directions'
from --param, averaged over the grid's lines. A grid's knots in a direction: its interior
knots (values − degree − 1, inside the parameters' range) by --knots-u, --knots-v or
--knots-in K=LIST; the other directions' by averaging.
Functions y(x) (--function): the first column is x; natural cubic spline, or Hermite with
--hermite. Hermite curves (document 002, Hermite segment): --hermite TANGENTS.

Examples:
  lekalo interpolate pts.csv --degree 3 --param chord -o curve.json
  lekalo interpolate pts.csv --param centripetal --knots averaged -o curve.svg
  lekalo interpolate pts.csv --end derivatives --start-derivative 1,2 --end-derivative -3,-1 --degree 2
  lekalo interpolate pts.csv --end derivatives --start-derivative 1,2 --end-derivative -3,-1 --knots at-params
  lekalo interpolate pts.csv --end second --start-derivative 2,-1 --end-derivative 0.5,4
  lekalo interpolate pts.csv --end natural -o natural.step
  lekalo interpolate pts.csv --end periodic --degree 3
  lekalo interpolate grid.csv --grid 4x3 --degree 3 --degree-v 2 -o surface.obj
  lekalo interpolate grid.csv --grid 4x3 --degree 2 --knots uniform -o uniform.json
  lekalo interpolate values.csv --grid 6x5x4 --degree 3,3,1 --param uniform -o tensor.json
  lekalo interpolate values.csv --grid 6x5x4 --degree 3,3,2 --param uniform --knots-u 0.4,0.6 --knots-in 3=0.5
  lekalo interpolate values.csv --grid 6x5x4 --params-u 0,1,2,4,8,16 --params-in 3=-1,0,1,3 -o table.json
  lekalo interpolate xy.csv --function -o spline.svg             # natural y(x)
  lekalo interpolate xy.csv --function --hermite monotone
  lekalo interpolate pts.csv --hermite cardinal --tension 0.5 -o hermite.json
  lekalo interpolate pts.csv --params 0,0.25,0.5,1 --degree 2 -o at-params.json
  lekalo interpolate pts.csv --tangents tangents.csv --params 0,1,2,3 -o hermite.json")]
pub(crate) struct InterpolateArgs {
    /// Points file (CSV, whitespace text or JSON; `-` for standard input).
    points: PathBuf,
    /// Degree (curves and the u direction of surfaces); for a grid, one degree per direction
    /// may be listed (`3,3,1`).
    #[arg(long, short = 'p', value_delimiter = ',', default_value = "3")]
    degree: Vec<usize>,
    /// Degree in v of a surface (default: --degree, at most columns − 1).
    #[arg(long)]
    degree_v: Option<usize>,
    /// Parametrisation (default: chord; uniform for a grid of values in 3 or more directions,
    /// whose values are not points in space).
    #[arg(long, value_parser = Words(&vocabulary::PARAMETRIZATION))]
    param: Option<Parametrization>,
    /// General parametrisation exponent e ≥ 0 (overrides --param; 0.5 is centripetal).
    #[arg(long)]
    exponent: Option<f64>,
    /// Knot placement.
    #[arg(long, value_parser = Words(&vocabulary::KNOT_PLACEMENT), default_value = "auto")]
    knots: KnotPlacement,
    /// End condition.
    #[arg(long, value_parser = Words(&vocabulary::END_CONDITION), default_value = "free")]
    end: EndKind,
    /// Derivative at the start: the first (`--end derivatives`) or second (`--end second`),
    /// comma-separated (`--d0`, the older spelling, still works with a warning).
    #[arg(long = "start-derivative", alias = "d0", allow_hyphen_values = true)]
    d0: Option<String>,
    /// Derivative at the end, as --start-derivative (`--dn`, the older spelling, still works
    /// with a warning).
    #[arg(long = "end-derivative", alias = "dn", allow_hyphen_values = true)]
    dn: Option<String>,
    /// Interpolate a grid of points (rows x columns, e.g. 4x3) by a surface; with three or
    /// more sizes (e.g. 5x4x3), a grid of values by a tensor-product spline in as many
    /// parameters (rows: the first direction slowest); --end and --knots apply to every
    /// direction of either.
    #[arg(
        long,
        value_name = "ROWSxCOLS[x…]",
        conflicts_with_all = ["d0", "dn", "function", "hermite"]
    )]
    grid: Option<String>,
    /// Interior knots of a grid's first direction (u, the rows of a surface grid), inside its
    /// parameters' range, as `fit --knots-u`: values − degree − 1 of them; the ends are clamped.
    #[arg(
        long,
        value_name = "LIST",
        requires = "grid",
        allow_hyphen_values = true
    )]
    knots_u: Option<String>,
    /// Interior knots of a grid's second direction (v), as --knots-u.
    #[arg(
        long,
        value_name = "LIST",
        requires = "grid",
        allow_hyphen_values = true
    )]
    knots_v: Option<String>,
    /// Interior knots of direction K of a grid (K from 1, as the columns x1 … xN of `eval`),
    /// as --knots-u; repeat for several directions (e.g. --knots-in 3=0.5).
    #[arg(
        long,
        value_name = "K=LIST",
        requires = "grid",
        allow_hyphen_values = true
    )]
    knots_in: Vec<String>,
    /// Parameters of a grid's first direction (the rows of a surface grid): one strictly
    /// increasing value per row, a list or a file of one value a line, e.g. the axis of a
    /// lookup table (default: from --param, averaged over the grid's lines).
    #[arg(
        long,
        value_name = "LIST|FILE",
        requires = "grid",
        allow_hyphen_values = true
    )]
    params_u: Option<String>,
    /// Parameters of a grid's second direction (v), as --params-u.
    #[arg(
        long,
        value_name = "LIST|FILE",
        requires = "grid",
        allow_hyphen_values = true
    )]
    params_v: Option<String>,
    /// Parameters of direction K of a grid (K from 1), as --params-u; repeat for several
    /// directions (e.g. --params-in 3=0,0.5,2,4).
    #[arg(
        long,
        value_name = "K=LIST|FILE",
        requires = "grid",
        allow_hyphen_values = true
    )]
    params_in: Vec<String>,
    /// The points are (x, y...) samples of a function y(x): natural cubic spline (or Hermite).
    /// The first column is x, the parameter: --params and --tangents are refused, not ignored.
    #[arg(
        long,
        conflicts_with_all = [
            "end", "knots", "d0", "dn", "param", "exponent", "degree", "degree_v", "params",
            "tangents"
        ]
    )]
    function: bool,
    /// Cubic Hermite interpolation with estimated tangents.
    #[arg(
        long,
        value_enum,
        conflicts_with_all = ["end", "knots", "d0", "dn", "degree", "degree_v"]
    )]
    hermite: Option<Tangents>,
    /// Tension of cardinal tangents, in [0, 1] (with --hermite cardinal; default 0).
    #[arg(long, requires = "hermite")]
    tension: Option<f64>,
    /// Refuse (exit code 2) a curve or grid whose collocation system has an estimated 1-norm
    /// condition number above LIMIT (e.g. 1e8 keeps about 8 significant digits in the control
    /// points); off by default.
    #[arg(long, value_name = "LIMIT")]
    max_condition: Option<f64>,
    /// Explicit parameters of the points (strictly increasing): a list `0,0.3,1` or a file
    /// with one value per line. Replaces --param.
    #[arg(long, value_name = "LIST|FILE", allow_hyphen_values = true)]
    params: Option<String>,
    /// Cubic Hermite interpolation with the given tangents: a points file with one tangent
    /// per data point (same dimension). Parameters from --params or --param.
    #[arg(long, value_name = "FILE", conflicts_with = "hermite")]
    tangents: Option<PathBuf>,
    /// Parquet batches: write each group's curve sampled at N evenly spaced parameters over
    /// its domain, in one pass (the samples layout of `lekalo eval curves.parquet --samples
    /// N`), instead of the curves.
    #[arg(long, short = 'n', value_name = "N")]
    samples: Option<usize>,
    #[command(flatten)]
    out: OutArgs,
}

pub(crate) fn run(a: &InterpolateArgs, cx: &Context) -> Result<()> {
    interpolate(a, cx).map_err(|e| crate::items::at_point_lines(cx, &a.points, e))
}

fn interpolate(a: &InterpolateArgs, cx: &Context) -> Result<()> {
    let param = parametrization(a.param.unwrap_or(Parametrization::ChordLength), a.exponent);
    if a.grid.is_some() && a.params.is_some() {
        return bad_input(
            "--params gives a curve's parameters; a grid's are --params-u, --params-v and \
             --params-in K=LIST, one list per direction",
        );
    }
    // a Parquet file with --grid is one table, the grid's values (read below as points)
    if crate::items::is_parquet(&a.points) && a.grid.is_none() {
        if a.function || a.hermite.is_some() || a.tangents.is_some() || a.params.is_some() {
            return bad_input("a Parquet batch is interpolated by B-spline curves: --function, --hermite, --tangents and --params are for one points file (with --grid, a Parquet file is a grid's values)");
        }
        let interp = curve_interpolation(a, param)?;
        // the work on one group of points
        let curve = |p: &Points| -> Result<Object> {
            Ok(Object::BSpline(interp.interpolate(p.as_view())?))
        };
        let out = a.out.output.as_deref();
        return match a.samples {
            Some(n) => {
                let n = cx.in_range(n, 1, usize::MAX, "--samples")?;
                crate::batch::parquet::samples_of_groups(cx, &a.points, out, n, &curve)
            }
            None => crate::batch::parquet::curves_of_groups(cx, &a.points, out, &curve),
        };
    }
    if a.samples.is_some() {
        return bad_input(
            "--samples samples the curves of a Parquet batch; for one points file, write the curve and sample it with `lekalo eval curve.json --samples N`",
        );
    }
    // three sizes or more: a tensor spline; one or two keep the surface's path and messages
    if let Some(g) = a
        .grid
        .as_deref()
        .filter(|g| g.split(['x', 'X', '×']).count() >= 3)
    {
        if a.degree_v.is_some() {
            return bad_input("--degree-v is for surfaces; a grid in 3 or more directions takes its degrees from --degree (one, or one per direction: --degree 3,3,1)");
        }
        let g = crate::cmd::tensor::GridInterpolation {
            grid: g,
            factors: crate::cmd::tensor::grid_factors(g)?,
            degree: &a.degree,
            // the values of a grid in 3 or more directions are not points in space: equally
            // spaced parameters unless another parametrisation is asked for
            param: parametrization(a.param.unwrap_or(Parametrization::Uniform), a.exponent),
            placement: a.knots,
            end: a.end,
            max_condition: a.max_condition,
            knots: grid_knots(a),
            params: grid_params(a),
            output: a.out.output.as_deref(),
            to: a.out.to.as_deref(),
        };
        return crate::cmd::tensor::interpolate(&g, &a.points, cx);
    }
    let (pts, name) = crate::items::read_points(cx, &a.points)?;
    let inputs = vec![a.points.clone()];
    if a.tension.is_some() && a.hermite != Some(Tangents::Cardinal) {
        return bad_input(
            "--tension is used only with --hermite cardinal; give --hermite cardinal or drop --tension",
        );
    }
    if a.degree_v.is_some() && a.grid.is_none() {
        return bad_input("--degree-v is the v degree of a surface; it needs --grid ROWSxCOLS");
    }
    if a.max_condition.is_some() && (a.function || a.hermite.is_some()) {
        return bad_input(
            "--max-condition applies to B-spline curves and grids; --function and --hermite \
             solve no collocation system to estimate (drop --max-condition)",
        );
    }
    if let Some(g) = &a.grid {
        let (nu, nv) = net_size(g, "--grid")?;
        let (degree, listed_v) = match a.degree.as_slice() {
            [p, q] if a.degree_v.is_none() => (*p, Some(*q)),
            _ => (single_degree(a)?, a.degree_v),
        };
        let degree_v = listed_v.unwrap_or(degree.min(nv.saturating_sub(1)).max(1));
        if a.end != EndKind::Free
            || a.knots != KnotPlacement::Auto
            || grid_knots(a).any()
            || grid_params(a).any()
        {
            // end conditions, knot placements, given knots or parameters: the tensor
            // interpolation of two directions (the surface's own is its free, averaged case)
            let degrees = [degree, degree_v];
            let spec = crate::cmd::tensor::GridInterpolation {
                grid: g,
                factors: vec![nu, nv],
                degree: &degrees,
                param,
                placement: a.knots,
                end: a.end,
                max_condition: a.max_condition,
                knots: grid_knots(a),
                params: grid_params(a),
                output: a.out.output.as_deref(),
                to: a.out.to.as_deref(),
            };
            let interp = crate::cmd::tensor::grid_interpolation(&degrees, &spec)?;
            let s = crate::cmd::tensor::interpolate_given(
                interp,
                &degrees,
                &pts,
                (g.as_str(), &[nu, nv]),
                (grid_knots(a), grid_params(a)),
                cx,
            )?;
            let mut inputs = inputs;
            inputs.extend(grid_params(a).files());
            return write_surface(&s.to_surface()?, &a.out, &inputs, cx);
        }
        let mut fit = SurfaceInterpolation::new(degree, degree_v).parametrization(param);
        if let Some(limit) = a.max_condition {
            fit = fit.max_condition(limit);
        }
        let s = fit.interpolate(pts.as_view(), nu, nv)?;
        return write_surface(&s, &a.out, &inputs, cx);
    }
    if a.function {
        if pts.dim() < 2 {
            return bad_input(format!(
                "{name}: --function needs at least two columns, x and y (got {})",
                pts.dim()
            ));
        }
        let x: Vec<f64> = pts.iter().map(|p| p[0]).collect();
        if let Some(k) = x.windows(2).position(|w| w[1] <= w[0]) {
            return bad_input(format!(
                "{name}: --function: x must be strictly increasing: row {} has x = {} after {} (sort the rows by x and merge repeated x)",
                k + 2,
                x[k + 1],
                x[k]
            ));
        }
        let ys: Vec<f64> = pts.iter().flat_map(|p| p[1..].to_vec()).collect();
        let y = Points::from_flat(pts.dim() - 1, ys)?;
        let curve = match a.hermite {
            Some(t) => {
                CubicHermite::function(&x, y.as_view(), tangents(t, a.tension.unwrap_or(0.0)))?
                    .to_bspline()
            }
            None => natural_cubic_spline(&x, y.as_view())?,
        };
        return write_curve(&Object::BSpline(curve), Some(&pts), &a.out, &inputs, cx);
    }
    if let Some(file) = &a.tangents {
        let (tan, _) = crate::items::read_points(cx, file)?;
        let ts = match &a.params {
            Some(p) => crate::cmd::explicit::parameters(cx, p, "--params")?,
            None => lekalo::parametrize(pts.as_view(), param)?,
        };
        let h = CubicHermite::new(ts, pts.clone(), tan)?;
        let mut inputs = inputs;
        inputs.push(file.clone());
        return write_curve(
            &Object::BSpline(h.to_bspline()),
            Some(&pts),
            &a.out,
            &inputs,
            cx,
        );
    }
    if let (Some(t), Some(p)) = (a.hermite, &a.params) {
        let ts = crate::cmd::explicit::parameters(cx, p, "--params")?;
        let h = CubicHermite::with_estimated_tangents(
            ts,
            pts.as_view(),
            tangents(t, a.tension.unwrap_or(0.0)),
        )?;
        return write_curve(
            &Object::BSpline(h.to_bspline()),
            Some(&pts),
            &a.out,
            &inputs,
            cx,
        );
    }
    if let Some(t) = a.hermite {
        let h =
            CubicHermite::from_points(pts.as_view(), param, tangents(t, a.tension.unwrap_or(0.0)))?;
        let obj = Object::BSpline(h.to_bspline());
        return write_curve(&obj, Some(&pts), &a.out, &inputs, cx);
    }
    let interp = curve_interpolation(a, param)?;
    let bar = crate::output::spinner(
        cx,
        format!("interpolating {} points", pts.len()),
        pts.len() > 100_000,
    );
    let curve = match &a.params {
        Some(p) => interp.interpolate_at(
            pts.as_view(),
            &crate::cmd::explicit::parameters(cx, p, "--params")?,
        ),
        None => interp.interpolate(pts.as_view()),
    };
    bar.finish_and_clear();
    let curve = curve?;
    write_curve(&Object::BSpline(curve), Some(&pts), &a.out, &inputs, cx)
}

/// The interior knots given per direction of a grid.
fn grid_knots(a: &InterpolateArgs) -> crate::cmd::tensor::GridLists<'_> {
    crate::cmd::tensor::GridLists {
        u: a.knots_u.as_deref(),
        v: a.knots_v.as_deref(),
        per_direction: &a.knots_in,
    }
}

/// The parameters given per direction of a grid.
fn grid_params(a: &InterpolateArgs) -> crate::cmd::tensor::GridLists<'_> {
    crate::cmd::tensor::GridLists {
        u: a.params_u.as_deref(),
        v: a.params_v.as_deref(),
        per_direction: &a.params_in,
    }
}

/// The B-spline interpolation of the options (end conditions, knots, condition limit).
fn curve_interpolation(a: &InterpolateArgs, param: Parametrization) -> Result<CurveInterpolation> {
    let start =
        a.d0.as_deref()
            .map(|s| numbers(s, "--start-derivative"))
            .transpose()?;
    let end =
        a.dn.as_deref()
            .map(|s| numbers(s, "--end-derivative"))
            .transpose()?;
    let end = a.end.condition(start, end)?;
    let knots = a.knots;
    let mut interp = CurveInterpolation::new(single_degree(a)?)
        .parametrization(param)
        .knot_placement(knots)
        .end_condition(end);
    if let Some(limit) = a.max_condition {
        interp = interp.max_condition(limit);
    }
    Ok(interp)
}

/// The one degree of a curve (a list of degrees is for grids).
fn single_degree(a: &InterpolateArgs) -> Result<usize> {
    match a.degree.as_slice() {
        [p] => Ok(*p),
        list => bad_input(format!(
            "--degree: {} degrees given; a list of degrees is for grids (--grid), one per direction, and a curve takes one",
            list.len()
        )),
    }
}

fn tangents(t: Tangents, tension: f64) -> TangentEstimate {
    match t {
        Tangents::FiniteDifference => TangentEstimate::FiniteDifference,
        Tangents::CatmullRom => TangentEstimate::CatmullRom,
        Tangents::Cardinal => TangentEstimate::Cardinal { tension },
        Tangents::Monotone => TangentEstimate::Monotone,
    }
}
