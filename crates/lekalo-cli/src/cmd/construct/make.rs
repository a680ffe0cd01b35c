//! `lekalo make`: a curve object from control points, knots and weights.

use lekalo_io::CurveJson;
use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};
use lekalo::{BSplineCurve, BezierCurve, KnotVector, NurbsCurve};
use lekalo_io::Object;

use crate::context::Context;
use crate::exit::bad_input;
use crate::output::emit;
use crate::values::numbers;

/// The kind of curve to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Kind {
    /// Bezier curve: degree = number of control points − 1.
    Bezier,
    /// B-spline curve (default knots: clamped uniform).
    Bspline,
    /// NURBS curve: needs --weights.
    Nurbs,
    /// Bezier surface from an NU × NV net (--net): degrees NU − 1 and NV − 1.
    BezierSurface,
    /// B-spline surface (--net, --degree, optional --degree-v, --knots-u, --knots-v).
    BsplineSurface,
    /// NURBS surface: as bspline-surface plus --weights, row by row.
    NurbsSurface,
    /// B-spline in N parameters (--net, --degree: one or one per direction, optional
    /// --knots-in); a net of two sizes is written as a surface.
    BsplineTensor,
    /// NURBS in N parameters: as bspline-tensor plus --weights, in the order of the points.
    NurbsTensor,
}

/// Arguments of `lekalo make`.
#[derive(Args, Debug)]
#[command(after_help = "\
Control points are read as CSV, whitespace-separated columns or JSON ([[x, y], …]); `-` is
standard input. Without --knots, B-spline and NURBS curves get clamped uniform knots
(document 000 eq. 2). --weights is a list or a file of one weight a line.

Examples:
  lekalo make bezier --control pts.csv -o bezier.json
  lekalo make bspline --control pts.csv --degree 2 --knots 0,0,1,2,3,3 -o lecture.json
  printf '1 0\\n1 1\\n0 1\\n' | lekalo make nurbs --control - --degree 2 --weights 1,0.7071067811865476,1
  lekalo make bezier-surface --control net.csv --net 3x3 -o patch.json
  lekalo make bspline-surface --control net.csv --net 3x3 --degree 2 -o surface.json
  lekalo make nurbs-surface --control net.csv --net 3x3 --degree 2 --weights 1,1,1,1,2,1,1,1,1 -o nurbs.json
  lekalo make bspline-tensor --control values.csv --net 6x5x4 --degree 3,3,1 -o tensor.json
  lekalo make bspline-tensor --control values.csv --net 6x5x4 --degree 2 --knots-in 3=0,0,0,0.5,1,1,1
  lekalo make nurbs-tensor --control values.csv --net 6x5x4 --degree 1 --weights weights.txt -o nurbs-tensor.json

Surfaces: the control points are the rows of the net, u outer: point (i, j) is line i·NV + j.

Splines in N parameters (bspline-tensor, nurbs-tensor): --net AxBxC… is the net's size in each
direction and --control holds one row per point, the first direction slowest (as `interpolate
--grid` reads its values), or a .npy array of shape (A, B, C, …[, dim]); --degree is one degree
or one per direction; each direction's knots are clamped uniform unless --knots-in K=LIST gives
direction K's full vector (control points + degree + 1 knots; --knots-u and --knots-v are
directions 1 and 2). A net of two sizes (--net AxB) is a surface and is written as one, the
surface of bspline-surface or nurbs-surface, as `interpolate --grid AxB` writes one.")]
pub(crate) struct MakeArgs {
    /// Kind of curve, surface or spline in N parameters.
    #[arg(value_enum)]
    kind: Kind,
    /// Control points file (CSV, text or JSON; `-` for standard input).
    #[arg(long, value_name = "FILE")]
    control: PathBuf,
    /// Degree (B-spline and NURBS); splines in N parameters take one degree or one per
    /// direction (`3,3,1`), surfaces `P,Q` as --degree P --degree-v Q.
    #[arg(long, short = 'p', value_name = "P|P1,P2,…", value_delimiter = ',')]
    degree: Vec<usize>,
    /// Full knot vector, comma-separated (fractions like 1/3 allowed).
    #[arg(long, allow_hyphen_values = true)]
    knots: Option<String>,
    /// Weights, one per control point (NURBS): a list, or a file of one value a line.
    #[arg(long, value_name = "LIST|FILE")]
    weights: Option<String>,
    /// Surfaces: size of the control net, `NUxNV` (e.g. `4x5`); splines in N parameters:
    /// `AxBxC…`, one size per direction.
    #[arg(long, value_name = "NUxNV|AxBxC…")]
    net: Option<String>,
    /// Surfaces: degree in v (default: --degree).
    #[arg(long, value_name = "Q")]
    degree_v: Option<usize>,
    /// Surfaces: knot vector in u (default: clamped uniform); splines in N parameters: of
    /// direction 1.
    #[arg(long, allow_hyphen_values = true)]
    knots_u: Option<String>,
    /// Surfaces: knot vector in v (default: clamped uniform); splines in N parameters: of
    /// direction 2.
    #[arg(long, allow_hyphen_values = true)]
    knots_v: Option<String>,
    /// Splines in N parameters: the full knot vector of direction K (from 1, as the columns
    /// x1 … xN of `eval`; control points + degree + 1 knots; default: clamped uniform); repeat
    /// for several directions (e.g. --knots-in 3=0,0,0.5,1,1).
    #[arg(long, value_name = "K=LIST", allow_hyphen_values = true)]
    knots_in: Vec<String>,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn run(a: &MakeArgs, cx: &Context) -> Result<()> {
    use crate::cmd::make_surface::{SurfaceKind, SurfaceMake};
    if matches!(a.kind, Kind::BsplineTensor | Kind::NurbsTensor) {
        return make_tensor(a, cx);
    }
    if !a.knots_in.is_empty() {
        return bad_input(
            "--knots-in K=LIST is a knot vector of a spline in N parameters (bspline-tensor, \
             nurbs-tensor); a surface's are --knots-u and --knots-v, a curve's --knots",
        );
    }
    let surface = match a.kind {
        Kind::BezierSurface => Some(SurfaceKind::Bezier),
        Kind::BsplineSurface => Some(SurfaceKind::BSpline),
        Kind::NurbsSurface => Some(SurfaceKind::Nurbs),
        _ => None,
    };
    if let Some(kind) = surface {
        let (degree, degree_v) = match a.degree[..] {
            [] => (None, a.degree_v),
            [p] => (Some(p), a.degree_v),
            [p, q] if a.degree_v.is_none() => (Some(p), Some(q)),
            _ => {
                return bad_input(format!(
                    "--degree: {} degrees for a surface; give one degree for u and v, or two \
                     (u,v), or --degree P --degree-v Q",
                    a.degree.len()
                ))
            }
        };
        return crate::cmd::make_surface::run(
            &SurfaceMake {
                kind,
                control: &a.control,
                net: a.net.as_deref(),
                degree,
                degree_v,
                knots_u: a.knots_u.as_deref(),
                knots_v: a.knots_v.as_deref(),
                weights: a.weights.as_deref(),
                output: a.output.as_deref(),
            },
            cx,
        );
    }
    if a.net.is_some() || a.degree_v.is_some() || a.knots_u.is_some() || a.knots_v.is_some() {
        return bad_input(
            "--net, --degree-v, --knots-u and --knots-v are for surfaces and splines in N parameters: use bezier-surface, bspline-surface, nurbs-surface, bspline-tensor or nurbs-tensor",
        );
    }
    let (ctrl, _) = crate::items::read_points(cx, &a.control)?;
    let degree = || -> Result<usize> {
        match a.degree[..] {
            [d] => Ok(d),
            [] => bad_input("--degree is required for B-spline and NURBS curves"),
            _ => bad_input(format!(
                "--degree: {} degrees for a curve, which takes one; a list of degrees is for \
                 surfaces (u,v) and splines in N parameters (one per direction)",
                a.degree.len()
            )),
        }
    };
    let knots = |degree: usize, n: usize| -> Result<KnotVector> {
        Ok(match &a.knots {
            Some(k) => KnotVector::new(numbers(k, "--knots")?)?,
            None => KnotVector::clamped_uniform(degree, n)?,
        })
    };
    let obj = match a.kind {
        Kind::Bezier => {
            if a.knots.is_some() || a.weights.is_some() || !a.degree.is_empty() {
                return bad_input(
                    "a Bezier curve takes only --control (its degree is the number of points − 1)",
                );
            }
            Object::Bezier(BezierCurve::new(ctrl)?)
        }
        Kind::Bspline => {
            if a.weights.is_some() {
                return bad_input("--weights make a rational curve: use `lekalo make nurbs`");
            }
            let p = degree()?;
            Object::BSpline(BSplineCurve::from_knot_vector(
                p,
                knots(p, ctrl.len())?,
                ctrl,
            )?)
        }
        Kind::Nurbs => {
            let p = degree()?;
            let Some(w) = &a.weights else {
                return bad_input("a NURBS curve needs --weights, one per control point");
            };
            let w = crate::cmd::explicit::parameters(cx, w, "--weights")?;
            let kv = knots(p, ctrl.len())?;
            Object::Nurbs(NurbsCurve::new(p, kv.into_vec(), ctrl, w)?)
        }
        Kind::BezierSurface
        | Kind::BsplineSurface
        | Kind::NurbsSurface
        | Kind::BsplineTensor
        | Kind::NurbsTensor => {
            return bad_input("internal: surface and tensor kinds are handled above")
        }
    };
    let mut inputs = vec![a.control.clone()];
    inputs.extend(a.weights.iter().map(PathBuf::from).filter(|p| p.is_file()));
    emit(
        a.output.as_deref(),
        obj.to_json_pretty().as_bytes(),
        &inputs,
        cx,
    )
}

/// `make bspline-tensor|nurbs-tensor`: the options of splines in N parameters, the curve's and
/// the surface's own refused by name.
fn make_tensor(a: &MakeArgs, cx: &Context) -> Result<()> {
    if a.knots.is_some() {
        return bad_input(
            "--knots is a curve's knot vector; a spline in N parameters takes one per \
             direction: --knots-in K=LIST (or --knots-u, --knots-v for directions 1 and 2)",
        );
    }
    if a.degree_v.is_some() {
        return bad_input(
            "--degree-v is for surfaces; a spline in N parameters takes its degrees from \
             --degree (one, or one per direction: --degree 3,3,1)",
        );
    }
    crate::cmd::make_tensor::run(
        &crate::cmd::make_tensor::TensorMake {
            rational: a.kind == Kind::NurbsTensor,
            control: &a.control,
            net: a.net.as_deref(),
            degree: &a.degree,
            knots: crate::cmd::tensor::GridLists {
                u: a.knots_u.as_deref(),
                v: a.knots_v.as_deref(),
                per_direction: &a.knots_in,
            },
            weights: a.weights.as_deref(),
            output: a.output.as_deref(),
        },
        cx,
    )
}
