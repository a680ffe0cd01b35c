//! The arguments of `lekalo fit` and what they say: domains, bounding boxes and clamped knot
//! vectors read from the options.

use std::path::PathBuf;

use anyhow::Result;
use clap::{ArgAction, Args, ValueEnum};
use lekalo::KnotVector;

use crate::exit::bad_input;
use crate::output::objects::OutArgs;
use crate::values::numbers;
use crate::words::Words;

/// Data points from which a fit draws a progress bar on a terminal (fewer fit in a blink).
/// Ctrl-C stops every fit between two steps of its work, bar or no bar.
pub(super) const LARGE: usize = 100_000;

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
  --smooth LAMBDA    cubic smoothing spline, λ given, or `--smooth gcv` (cross-validation);
                     on a grid (--grid AxB…) one per direction, e.g. --smooth 0.1,gcv
  --s S              fewest knots with weighted residual sum of squares <= S (like splrep);
                     with --knots, the least k-th derivative jumps on those knots with RSS = S;
                     --domain A:B sets the end knots
  --tolerance TOL    within TOL of every point (distance), few control points
  --robust huber|tukey   least squares that resists outliers (final weights in the report)
  --periodic         a closed curve (or periodic function), with --lsq/--ctrl/--knots or --s
Surfaces: --grid ROWSxCOLS or --scattered (rows u,v,z), with --ctrl-grid NUxNV or the interior
knots of each direction (--knots-u, --knots-v); --degree P,Q per direction; --bbox U0:U1,V0:V1
the domain (end knots); a grid's parameters --params-u, --params-v (default: from --param).
In 3 or more variables: --grid AxBxC (one row of values per node, the first direction slowest,
or a .npy array) or --scattered (rows x1 … xN then the values; N from --ctrl-grid AxBxC, or the
last direction whose knots are given); direction K's interior knots --knots-in K=LIST (1 and 2
also --knots-u, --knots-v), a grid's parameters --params-in K=LIST|FILE, --bbox one A:B per
direction; the spline is written as JSON, as `interpolate --grid AxBxC` writes it. --s S on
such a grid places the knots itself: the fewest found with residual sum of squares <= S
(FITPACK's regrid, SciPy's RectBivariateSpline). --scattered --s S does the same for scattered
rows in any number of variables (FITPACK's surfit, SciPy's SmoothBivariateSpline; the number
from --degree P,Q,R…, else --bbox, else 2), weighted RSS within 0.1 % of S and never above.

On the sphere (--sphere; FITPACK's sphere and spgrid, SciPy's *SphereBivariateSpline): a bicubic
spline in (theta, phi), periodic in phi, one value at each pole, written as JSON. --scattered
reads rows theta, phi, r: least squares on the interior knots --knots-u (theta) and --knots-v
(phi), or --s S with FITPACK's knots; --weights weighs the rows. --grid NUxNV reads one value per
node (theta slowest) at the colatitudes --params-u and longitudes --params-v: --s S (0, the
default, interpolates) with the pole conditions --pole-values V|V0,V1 (none: fitted),
--pole-exact, --pole-continuity, --pole-flat (each =B0,B1 for the poles theta = 0 and pi).

Shape constraints (--function fits by --lsq, --smooth, or --s without --knots; each holds for
every x, not only at the data; repeat an option for several intervals; =X or @X: at a point):
  --increasing[=A:B] --decreasing[=A:B] --convex[=A:B] --concave[=A:B]
  --min V[@A:B] --max V[@A:B]   bounds on y;  --through X=V  y(X) = V;  --slope-at X=V  y'(X) = V
  --integral A:B=V  the integral of y over [A, B];  with --periodic (--lsq): a periodic y(x)
A surface z(u, v) (--grid NUxNV of rows u,v,z or of one value per node at --params-u/-v, or
--scattered rows u,v,z; least squares, with --penalty for scattered rows; on a grid also the
smoothing spline, --smooth LU,LV or gcv, or --s S for its residual) keeps, on its whole domain
or with @U0:U1,V0:V1 on a box: --increasing[=u|v|u,v] --decreasing[=u|v|u,v] (bare: both
directions) --min V --max V

The report (residual max and RMS, λ or s, control points; with --tolerance the residuals are
the deviations the tolerance bounds, at each point's closest point, all within it)
goes to standard error, or with --json the output is {\"object\": …, \"report\": …};
--per-point adds every residual.

Examples:
  lekalo fit scan.csv --ctrl 20 -o fit.json
  lekalo fit scan.csv --lsq --knots 0.25,0.5,0.75 --clamp-ends --start-derivative 1,0 --end-derivative 0,-1
  lekalo fit xy.csv --function --smooth gcv --json
  lekalo fit xy.csv --function --s 0.05 --weights w.txt
  lekalo fit xy.csv --function --s 0.5 --knots 10,20
  lekalo fit track.csv --tolerance 0.01 -o track.svg
  lekalo fit xy.csv --function --ctrl 12 --robust tukey --json
  lekalo fit xy.csv --function --ctrl 10 --increasing --convex=0:15 --min 0
  lekalo fit xy.csv --function --smooth 1 --max 0.9 --concave=5:20 --through 0=0
  lekalo fit loop.csv --periodic --s 0.01 -o loop.json
  lekalo fit grid.csv --grid 30x20 --ctrl-grid 8x6 -o surface.json
  lekalo fit uvz.csv --scattered --ctrl-grid 10x10 --penalty 1e-3
  lekalo fit uvz.csv --scattered --s 5 --json
  lekalo fit xy.csv --function --ctrl 8 --domain -5:35 -o wide.json
  lekalo fit xy.csv --function --s 0.5 --domain -5:35 -o wide.json
  lekalo fit grid.csv --grid 30x20 --degree 3,2 --knots-u 0.25,0.5,0.75 --knots-v 0.5 -o surface.json
  lekalo fit uvz.csv --scattered --knots-u 0.3,0.6 --knots-v 0.5 --bbox 0:1,0:1 --degree 3,2
  lekalo fit values.csv --grid 6x5x4 --degree 2 --param uniform --ctrl-grid 4x4x3 -o fitted.json
  lekalo fit values.csv --grid 6x5x4 --degree 2,2,1 --param uniform --knots-in 3=0.5 --ctrl-grid 4x4x3
  lekalo fit xyzw.csv --scattered --ctrl-grid 4x4x4 --degree 2 --bbox 0:1,0:1,0:1 --json
  lekalo fit values.csv --grid 6x5x4 --param uniform --smooth gcv --json
  lekalo fit grid.csv --grid 30x20 --smooth 1e-3,gcv -o smooth.json
  lekalo fit tpr.csv --sphere --scattered --s 0.5 -o sphere.json
  lekalo fit tpr.csv --sphere --scattered --knots-u 1,2 --knots-v 1.5,3,4.5 --json
  lekalo fit r.csv --sphere --grid 7x10 --params-u 0.4,0.8,1.2,1.6,2,2.4,2.8 \
      --params-v 0,0.6,1.2,1.8,2.4,3,3.6,4.2,4.8,5.4 --pole-continuity -o sphere-grid.json")]
pub(crate) struct FitArgs {
    /// Points file (CSV, whitespace text or JSON; `-` for standard input).
    pub(super) points: PathBuf,
    /// Least squares with given control-point count or knots (the default mode).
    #[arg(long)]
    pub(super) lsq: bool,
    /// Penalised smoothing: λ ≥ 0, or `gcv`; on a grid one for all directions or one per
    /// direction (`0.1,gcv`).
    #[arg(long, value_name = "LAMBDA|gcv[,...]", allow_hyphen_values = true)]
    pub(crate) smooth: Option<String>,
    /// Smoothing condition: the weighted residual sum of squares target.
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub(crate) s: Option<f64>,
    /// With --s: how each round of knot addition places its knots (shared: FITPACK's `curfit`, as
    /// SciPy's `splrep`, the default; refit: a fit after every knot, as SciPy's `make_splrep`).
    #[arg(long, requires = "s", value_parser = Words(&lekalo::vocabulary::KNOT_ROUNDS))]
    pub(crate) knot_rounds: Option<lekalo::fit::KnotRounds>,
    /// Fit within this distance of every point. Formerly `--tol`.
    #[arg(
        long = "tolerance",
        alias = "tol",
        value_name = "TOL",
        allow_hyphen_values = true
    )]
    pub(crate) tol: Option<f64>,
    /// With --tolerance: measure the deviation at the data parameters instead of the distance.
    #[arg(long)]
    pub(super) parameter_deviation: bool,
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
    /// (x with --function) for a curve that reaches beyond them (least squares, --robust and
    /// --s; default: from the first to the last parameter, as splrep's xb, xe).
    #[arg(long, value_name = "A:B", allow_hyphen_values = true)]
    pub(super) domain: Option<String>,
    /// Weights file: one number per point.
    #[arg(long, value_name = "FILE")]
    pub(super) weights: Option<PathBuf>,
    /// Interpolate the first and last points exactly.
    #[arg(long)]
    pub(crate) clamp_ends: bool,
    /// First derivative at the start (with --clamp-ends), comma-separated (`--d0`, the older
    /// spelling, still works with a warning).
    #[arg(long = "start-derivative", alias = "d0", allow_hyphen_values = true)]
    pub(crate) d0: Option<String>,
    /// First derivative at the end (with --clamp-ends), comma-separated (`--dn`, the older
    /// spelling, still works with a warning).
    #[arg(long = "end-derivative", alias = "dn", allow_hyphen_values = true)]
    pub(crate) dn: Option<String>,
    /// Parametrisation of parametric curves and grids (default: chord; uniform for a grid of
    /// values in 3 or more directions, whose values are not points in space).
    #[arg(long, value_parser = Words(&lekalo::vocabulary::PARAMETRIZATION))]
    pub(crate) param: Option<lekalo::Parametrization>,
    /// A closed curve (periodic spline; with --function, a periodic function whose last row
    /// repeats the first).
    #[arg(long)]
    pub(crate) periodic: bool,
    /// A grid of points (rows x columns) fitted by a surface.
    #[arg(long, value_name = "ROWSxCOLS")]
    pub(super) grid: Option<String>,
    /// Scattered rows (u, v, z…) fitted by a surface z(u, v).
    #[arg(long)]
    pub(super) scattered: bool,
    /// Surface control net size (e.g. 8x6).
    #[arg(long, value_name = "NUxNV")]
    pub(super) ctrl_grid: Option<String>,
    /// Interior knots of a surface in u (comma-separated, inside the u range) instead of the
    /// u count of --ctrl-grid.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub(super) knots_u: Option<String>,
    /// Interior knots of a surface in v, as --knots-u.
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub(super) knots_v: Option<String>,
    /// Interior knots of direction K of a fit in 3 or more variables (K from 1, the column xK
    /// of scattered rows), as --knots-u; repeat for several directions (e.g. --knots-in 3=0.5).
    #[arg(long, value_name = "K=LIST", allow_hyphen_values = true)]
    pub(super) knots_in: Vec<String>,
    /// The surface's domain U0:U1,V0:V1, its end knots, as the `bbox` of SciPy's
    /// `LSQBivariateSpline`
    /// (default: the range of the data's u and v, or of the grid's parameters).
    #[arg(long, value_name = "U0:U1,V0:V1", allow_hyphen_values = true)]
    pub(super) bbox: Option<String>,
    /// Parameters of the grid's rows (--grid): one number per row, a list or a file with one
    /// value per line (default: --param averaged over the grid's columns).
    #[arg(long, value_name = "LIST|FILE", allow_hyphen_values = true)]
    pub(super) params_u: Option<String>,
    /// Parameters of the grid's columns (--grid), as --params-u.
    #[arg(long, value_name = "LIST|FILE", allow_hyphen_values = true)]
    pub(super) params_v: Option<String>,
    /// Parameters of direction K of a grid in 3 or more directions (`--grid AxBxC`), one per
    /// grid line along it, as --params-u; repeat for several directions.
    #[arg(long, value_name = "K=LIST|FILE", allow_hyphen_values = true)]
    pub(super) params_in: Vec<String>,
    /// Data on the sphere: with --scattered rows theta, phi, r (colatitude in [0, pi],
    /// longitude in [0, 2pi], value); with --grid `NUxNV` one value per node, the colatitudes
    /// --params-u and the longitudes --params-v. A bicubic spline in (theta, phi), periodic in
    /// phi, one value at each pole.
    #[arg(long)]
    pub(super) sphere: bool,
    /// --sphere --grid: the values at the poles theta = 0 and theta = pi, one for both or two,
    /// `none` for a pole whose value is fitted (SciPy's `pole_values`; default: both fitted).
    #[arg(long, value_name = "V|V0,V1", allow_hyphen_values = true)]
    pub(super) pole_values: Option<String>,
    /// --sphere --grid: impose the --pole-values exactly (without, each counts as one more
    /// datum); `=true,false` for each pole (SciPy's `pole_exact`).
    #[arg(long, value_name = "B|B0,B1", num_args = 0..=1, require_equals = true, default_missing_value = "true")]
    pub(super) pole_exact: Option<String>,
    /// --sphere --grid: a continuous first derivative across the poles; `=true,false` for
    /// each pole (SciPy's `pole_continuity`).
    #[arg(long, value_name = "B|B0,B1", num_args = 0..=1, require_equals = true, default_missing_value = "true")]
    pub(super) pole_continuity: Option<String>,
    /// --sphere --grid: a zero derivative at the poles (with --pole-continuity); `=true,false`
    /// for each pole (SciPy's `pole_flat`).
    #[arg(long, value_name = "B|B0,B1", num_args = 0..=1, require_equals = true, default_missing_value = "true")]
    pub(super) pole_flat: Option<String>,
    /// Smoothing penalty of scattered least squares, surfaces and N variables (second
    /// differences of the net along every direction).
    #[arg(long, default_value_t = 0.0)]
    pub(super) penalty: f64,
    /// Keep y(x) increasing (y' ≥ 0) everywhere, with `=A:B` on [A, B], or with `=X` at the point X;
    /// a surface in `=u`, `=v` or both (bare), `=u@U0:U1,V0:V1` on a box.
    #[arg(long, value_name = "A:B|u|v", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    pub(super) increasing: Vec<String>,
    /// Keep y(x) decreasing (y' ≤ 0) everywhere, with `=A:B` on [A, B], or with `=X` at the point X;
    /// a surface in `=u`, `=v` or both (bare), `=u@U0:U1,V0:V1` on a box.
    #[arg(long, value_name = "A:B|u|v", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    pub(super) decreasing: Vec<String>,
    /// Keep y(x) convex (y'' ≥ 0) everywhere, with `=A:B` on [A, B], or with `=X` at the point X.
    #[arg(long, value_name = "A:B", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    pub(super) convex: Vec<String>,
    /// Keep y(x) concave (y'' ≤ 0) everywhere, with `=A:B` on [A, B], or with `=X` at the point X.
    #[arg(long, value_name = "A:B", num_args = 0..=1, require_equals = true, default_missing_value = "", action = ArgAction::Append)]
    pub(super) concave: Vec<String>,
    /// Lower bound y ≥ V everywhere, `V@A:B` on [A, B], or `V@X` at the point X (a surface: V, or V@U0:U1,V0:V1 on a box).
    #[arg(long, value_name = "V[@A:B|@X]", allow_hyphen_values = true, action = ArgAction::Append)]
    pub(super) min: Vec<String>,
    /// Upper bound y ≤ V everywhere, `V@A:B` on [A, B], or `V@X` at the point X (a surface: V, or V@U0:U1,V0:V1 on a box).
    #[arg(long, value_name = "V[@A:B|@X]", allow_hyphen_values = true, action = ArgAction::Append)]
    pub(super) max: Vec<String>,
    /// A point the fit passes through: `X=V` for y(X) = V.
    #[arg(long, value_name = "X=V", allow_hyphen_values = true, action = ArgAction::Append)]
    pub(super) through: Vec<String>,
    /// The slope at a point: `X=V` for y'(X) = V.
    #[arg(long, value_name = "X=V", allow_hyphen_values = true, action = ArgAction::Append)]
    pub(super) slope_at: Vec<String>,
    /// An integral: `A:B=V` for ∫_A^B y dx = V.
    #[arg(long, value_name = "A:B=V", allow_hyphen_values = true, action = ArgAction::Append)]
    pub(super) integral: Vec<String>,
    /// Write {"object", "report"} as JSON instead of the object alone.
    #[arg(long)]
    pub(super) json: bool,
    /// Add every point's residual to the report.
    #[arg(long)]
    pub(super) per_point: bool,
    #[command(flatten)]
    pub(super) out: OutArgs,
}

impl FitArgs {
    /// Whether any shape constraint (`--increasing` … `--integral`) is given.
    pub(super) fn shape_given(&self) -> bool {
        !(self.increasing.is_empty()
            && self.decreasing.is_empty()
            && self.convex.is_empty()
            && self.concave.is_empty()
            && self.min.is_empty()
            && self.max.is_empty()
            && self.through.is_empty()
            && self.slope_at.is_empty()
            && self.integral.is_empty())
    }

    /// The options of curve fits, each with whether it is given, for the fits that refuse them
    /// (in 3 or more variables, on the sphere).
    pub(super) fn curve_options(&self) -> [(bool, &'static str); 9] {
        [
            (self.smooth.is_some(), "--smooth"),
            (self.tol.is_some(), "--tolerance"),
            (self.robust.is_some(), "--robust"),
            (self.periodic, "--periodic"),
            (self.function, "--function"),
            (self.clamp_ends, "--clamp-ends"),
            (
                self.d0.is_some() || self.dn.is_some(),
                "--start-derivative/--end-derivative",
            ),
            (self.ctrl.is_some(), "--ctrl"),
            (self.shape_given(), "shape constraints"),
        ]
    }

    /// Whether any pole option of `--sphere --grid` is given.
    pub(super) fn pole_given(&self) -> bool {
        self.pole_values.is_some()
            || self.pole_exact.is_some()
            || self.pole_continuity.is_some()
            || self.pole_flat.is_some()
    }

    /// The parametrisation of curves and surfaces: `--param`, chord length by default.
    pub(super) fn param(&self) -> lekalo::Parametrization {
        self.param.unwrap_or(lekalo::Parametrization::ChordLength)
    }

    /// The parametrisation of a grid of values in 3 or more directions: `--param`, equally
    /// spaced by default (the values are not points in space).
    pub(super) fn grid_param(&self) -> lekalo::Parametrization {
        self.param.unwrap_or(lekalo::Parametrization::Uniform)
    }

    /// The interior knots given per direction (`--knots-u`, `--knots-v`, `--knots-in`).
    pub(super) fn grid_knots(&self) -> crate::cmd::tensor::GridLists<'_> {
        crate::cmd::tensor::GridLists {
            u: self.knots_u.as_deref(),
            v: self.knots_v.as_deref(),
            per_direction: &self.knots_in,
        }
    }

    /// The grid parameters given per direction (`--params-u`, `--params-v`, `--params-in`).
    pub(super) fn grid_params(&self) -> crate::cmd::tensor::GridLists<'_> {
        crate::cmd::tensor::GridLists {
            u: self.params_u.as_deref(),
            v: self.params_v.as_deref(),
            per_direction: &self.params_in,
        }
    }

    /// The degree of a curve: `--degree` with one value.
    pub(super) fn degree(&self) -> Result<usize> {
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
    pub(super) fn surface_degrees(&self) -> Result<(usize, usize)> {
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
    pub(super) fn check_options_used(&self) -> Result<()> {
        let surface = self.grid.is_some() || self.scattered;
        if self.pole_given() && !self.sphere {
            return bad_input(
                "--pole-values, --pole-exact, --pole-continuity and --pole-flat are the pole \
                 conditions of a grid on the sphere: add --sphere --grid NUxNV",
            );
        }
        if !surface {
            let given: Vec<&str> = [
                (self.knots_u.is_some(), "--knots-u"),
                (self.knots_v.is_some(), "--knots-v"),
                (self.bbox.is_some(), "--bbox"),
                (self.params_u.is_some(), "--params-u"),
                (self.params_v.is_some(), "--params-v"),
                (!self.knots_in.is_empty(), "--knots-in"),
                (!self.params_in.is_empty(), "--params-in"),
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
            if self.smooth.is_some() || self.tol.is_some() {
                return bad_input(
                    "--domain sets the end knots of least squares (--lsq, --ctrl, --knots, \
                     --robust) and of --s; --smooth and --tolerance place their own knots: drop \
                     --domain",
                );
            }
            if self.clamp_ends {
                return bad_input(
                    "--clamp-ends puts the curve's ends on the first and last points, at the ends \
                     of the domain; with --domain the domain reaches beyond the data: drop one",
                );
            }
        }
        if self.knot_rounds.is_some()
            && (surface || self.periodic || self.knots.is_some() || self.shape_given())
        {
            return bad_input(
                "--knot-rounds chooses how --s places the knots of an open curve; with --knots, \
                 --periodic, a surface or shape constraints it has no rounds: drop --knot-rounds",
            );
        }
        if surface && self.knots.is_some() {
            return bad_input(
                "--knots is the interior knots of a curve; give a surface's as --knots-u and \
                 --knots-v",
            );
        }
        if self.scattered
            && (self.params_u.is_some() || self.params_v.is_some() || !self.params_in.is_empty())
        {
            return bad_input(
                "--params-u/--params-v/--params-in are the parameters of a grid's rows and columns (--grid); \
                 --scattered reads u and v from the first two columns (x1 … xN from the first N in N \
                 variables)",
            );
        }
        Ok(())
    }
}

/// The penalty weights of `--smooth`: `λ ≥ 0` or `gcv` (generalised cross-validation), one
/// for a curve, or one per direction of a grid, comma separated (one value for all of them).
pub(super) fn smoothing_weights(text: &str) -> Result<Vec<lekalo::fit::Lambda>> {
    text.split(',')
        .map(|w| {
            let w = w.trim();
            if w.eq_ignore_ascii_case("gcv") {
                Ok(lekalo::fit::Lambda::Gcv)
            } else {
                match w.parse::<f64>() {
                    Ok(l) => Ok(lekalo::fit::Lambda::Given(l)),
                    Err(_) => bad_input(format!(
                        "--smooth: \"{w}\" is neither a number nor gcv (give λ ≥ 0 or gcv; on a \
                         grid one per direction, e.g. --smooth 0.1,gcv)"
                    )),
                }
            }
        })
        .collect()
}

/// `A:B` with `A < B` (the value of `option`; `example` shows the spelling in the message).
pub(super) fn span(text: &str, option: &str, example: &str) -> Result<(f64, f64)> {
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
pub(crate) fn clamped(
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
pub(super) fn with_ends(k: &KnotVector, p: usize, (lo, hi): (f64, f64)) -> Result<KnotVector> {
    let mut t = k.as_slice().to_vec();
    let n = t.len();
    t[..=p].fill(lo);
    t[n - p - 1..].fill(hi);
    Ok(KnotVector::new(t)?)
}

/// `U0:U1,V0:V1` of `--bbox`.
pub(super) fn bounding_box(text: &str) -> Result<((f64, f64), (f64, f64))> {
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
