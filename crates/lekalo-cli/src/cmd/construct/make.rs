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
}

/// Arguments of `lekalo make`.
#[derive(Args, Debug)]
#[command(after_help = "\
Control points are read as CSV, whitespace-separated columns or JSON ([[x, y], …]); `-` is
standard input. Without --knots, B-spline and NURBS curves get clamped uniform knots
(document 000 eq. 2).

Examples:
  lekalo make bezier --control pts.csv -o bezier.json
  lekalo make bspline --control pts.csv --degree 2 --knots 0,0,1,2,3,3 -o lecture.json
  printf '1 0\\n1 1\\n0 1\\n' | lekalo make nurbs --control - --degree 2 --weights 1,0.7071067811865476,1
  lekalo make bezier-surface --control net.csv --net 3x3 -o patch.json
  lekalo make bspline-surface --control net.csv --net 3x3 --degree 2 -o surface.json
  lekalo make nurbs-surface --control net.csv --net 3x3 --degree 2 --weights 1,1,1,1,2,1,1,1,1 -o nurbs.json

Surfaces: the control points are the rows of the net, u outer: point (i, j) is line i·NV + j.")]
pub(crate) struct MakeArgs {
    /// Kind of curve.
    #[arg(value_enum)]
    kind: Kind,
    /// Control points file (CSV, text or JSON; `-` for standard input).
    #[arg(long, value_name = "FILE")]
    control: PathBuf,
    /// Degree (B-spline and NURBS).
    #[arg(long, short = 'p')]
    degree: Option<usize>,
    /// Full knot vector, comma-separated (fractions like 1/3 allowed).
    #[arg(long, allow_hyphen_values = true)]
    knots: Option<String>,
    /// Weights, one per control point (NURBS).
    #[arg(long)]
    weights: Option<String>,
    /// Surfaces: size of the control net, `NUxNV` (e.g. `4x5`).
    #[arg(long, value_name = "NUxNV")]
    net: Option<String>,
    /// Surfaces: degree in v (default: --degree).
    #[arg(long, value_name = "Q")]
    degree_v: Option<usize>,
    /// Surfaces: knot vector in u (default: clamped uniform).
    #[arg(long, allow_hyphen_values = true)]
    knots_u: Option<String>,
    /// Surfaces: knot vector in v (default: clamped uniform).
    #[arg(long, allow_hyphen_values = true)]
    knots_v: Option<String>,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn run(a: &MakeArgs, cx: &Context) -> Result<()> {
    use crate::cmd::make_surface::{SurfaceKind, SurfaceMake};
    let surface = match a.kind {
        Kind::BezierSurface => Some(SurfaceKind::Bezier),
        Kind::BsplineSurface => Some(SurfaceKind::BSpline),
        Kind::NurbsSurface => Some(SurfaceKind::Nurbs),
        _ => None,
    };
    if let Some(kind) = surface {
        return crate::cmd::make_surface::run(
            &SurfaceMake {
                kind,
                control: &a.control,
                net: a.net.as_deref(),
                degree: a.degree,
                degree_v: a.degree_v,
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
            "--net, --degree-v, --knots-u and --knots-v are for surfaces: use bezier-surface, bspline-surface or nurbs-surface",
        );
    }
    let (ctrl, _) = crate::items::read_points(cx, &a.control)?;
    let degree = || -> Result<usize> {
        match a.degree {
            Some(d) => Ok(d),
            None => bad_input("--degree is required for B-spline and NURBS curves"),
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
            if a.knots.is_some() || a.weights.is_some() || a.degree.is_some() {
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
            let w = numbers(w, "--weights")?;
            let kv = knots(p, ctrl.len())?;
            Object::Nurbs(NurbsCurve::new(p, kv.into_vec(), ctrl, w)?)
        }
        Kind::BezierSurface | Kind::BsplineSurface | Kind::NurbsSurface => {
            return bad_input("internal: surface kinds are handled above")
        }
    };
    let inputs = vec![a.control.clone()];
    emit(
        a.output.as_deref(),
        obj.to_json_pretty().as_bytes(),
        &inputs,
        cx,
    )
}
