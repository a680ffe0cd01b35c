//! `lekalo blend`: deformation of curves, splines by blending local curves, corner smoothing
//! (document 001).

use lekalo_io::CurveJson;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Result;
use clap::{Args, Subcommand, ValueEnum};
use lekalo::{
    smooth_polyline_corners, ArcParametrization, BezierForm, BlendSpline, BlendSplineOptions,
    BlendSplinePieces, CircularArcs, CornerTransition, CornerWindow, Deformation, LocalCurves,
    Parabolas, ParametricCurve, SharedCurve, SplineParameters,
};
use lekalo_io::Object;

use crate::cancel::with_progress;
use crate::context::Context;
use crate::exit::bad_input;
use crate::items::load_one;
use crate::output::format_of;
use crate::output::objects::{write_curve, OutArgs};
use crate::values::numbers;

/// Local curves of a blended spline.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Local {
    /// Circular arcs with the angle linear (document 001's example; approximated for output).
    Arcs,
    /// Circular arcs as rational quadratics (exact NURBS output; arcs under 180°).
    RationalArcs,
    /// Arcs with the angle quadratic in the global parameter (C^k with --param chord).
    GlobalArcs,
    /// Parabolas through three points (C^k; exact B-spline output).
    Parabolas,
}

/// Parameters of the spline's points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum SplineParams {
    /// Δ = 1.
    Uniform,
    /// Δ = chord length.
    Chord,
    /// Δ = square root of the chord length.
    Centripetal,
}

/// `lekalo blend` operations.
#[derive(Subcommand, Debug)]
pub(crate) enum BlendOp {
    /// Deform curve A into curve B (same end points; document 001 §2):
    /// p = (1 − w_{k−1}) A + w_{k−1} B.
    #[command(after_help = "\
The result is exact: a Bezier curve of degree (2k − 1) + max(d1, d2), or a rational Bezier
(NURBS) when a curve is rational (e.g. circular arcs made with `lekalo make nurbs`).

Examples:
  lekalo blend deform up.json down.json --continuity 2 -o blend.json
  lekalo blend deform arc1.json arc2.json --continuity 3 -o blend.svg")]
    Deform {
        /// The first curve (object JSON).
        first: PathBuf,
        /// The second curve, with the same end points.
        second: PathBuf,
        /// Continuity degree k ≥ 1 (contact of order k with each curve at its end).
        #[arg(long = "continuity", short_alias = 'k', default_value_t = 2)]
        k: usize,
        #[command(flatten)]
        out: OutArgs,
    },
    /// A spline through points by blending local three-point curves (document 001 §3).
    #[command(after_help = "\
Output: exact NURBS for --local parabolas and rational-arcs; for arcs and global-arcs a
B-spline approximation of degree 2k + 1 with the same joins, within --tolerance (printed).

Examples:
  lekalo blend spline pts.csv --continuity 2 --local parabolas -o spline.json
  lekalo blend spline pts.csv --continuity 3 --local arcs --closed -o closed.svg
  lekalo blend spline pts.csv --local rational-arcs --param chord -o spline.step")]
    Spline {
        /// Points file (CSV, text or JSON; `-` for standard input).
        points: PathBuf,
        /// Continuity degree k ≥ 1.
        #[arg(long = "continuity", short_alias = 'k', default_value_t = 2)]
        k: usize,
        /// Local curves.
        #[arg(long, value_enum, default_value_t = Local::Arcs)]
        local: Local,
        /// Closed curve through the points.
        #[arg(long)]
        closed: bool,
        /// Parameters of the points.
        #[arg(long = "param", alias = "params", value_enum, default_value_t = SplineParams::Uniform)]
        params: SplineParams,
        /// Tolerance of the approximation for arcs.
        #[arg(long, default_value_t = 1e-8)]
        tolerance: f64,
        /// Write `{"max_error", "degree", "curve"}` (the approximation's measured error for
        /// arcs; 0 for exact output) instead of the curve alone.
        #[command(flatten)]
        json: crate::report::JsonFlag,
        #[command(flatten)]
        out: OutArgs,
    },
    /// Smooth the corner where curve A ends and curve B starts, with continuity degree k.
    #[command(after_help = "\
The window: A is replaced from parameter --from to its end, B from its start to --until. The
output is the transition curve, exact (Bezier or rational Bezier) when A and B are single
Bezier pieces.

Examples:
  lekalo blend corner before.json after.json --from 0.5 --until 0.5 --continuity 2 -o corner.json")]
    Corner {
        /// The curve before the corner.
        before: PathBuf,
        /// The curve after the corner (starts where `before` ends).
        after: PathBuf,
        /// Parameter of `before` where the transition starts.
        #[arg(long, allow_hyphen_values = true)]
        from: String,
        /// Parameter of `after` where the transition ends.
        #[arg(long, allow_hyphen_values = true)]
        until: String,
        /// Continuity degree k ≥ 1.
        #[arg(long = "continuity", short_alias = 'k', default_value_t = 2)]
        k: usize,
        #[command(flatten)]
        out: OutArgs,
    },
    /// Smooth every corner of a polyline with continuity degree k; the result is one curve.
    #[command(after_help = "\
Each corner is replaced by one Bezier curve over a window cut on both sides; outside the windows
the segments are kept exactly. The result is one B-spline of degree 2k + 1, C^k everywhere,
parametrised by arc length along the straight parts, and fair: inside each corner window the
curvature keeps the sign of the corner's turn (docs/theory/blending.md#polyline-corners).

--window takes a length (the same at every corner; each segment must hold the windows of its two
corners) or a percentage of the shorter segment at each corner, at most 50%.

Examples:
  lekalo blend corners polyline.csv --window 25% --continuity 2 -o smooth.json
  lekalo blend corners polyline.csv --window 0.4 --continuity 3 -o smooth.svg")]
    Corners {
        /// The polyline: points file (CSV, text or JSON; `-` for standard input), at least three
        /// points.
        polyline: PathBuf,
        /// Window at each corner: a length (`0.4`) or a percentage of the shorter adjacent
        /// segment (`25%`, at most 50%).
        #[arg(long, default_value = "25%", allow_hyphen_values = true)]
        window: String,
        /// Continuity degree k ≥ 1 (the curve has degree 2k + 1).
        #[arg(long = "continuity", short_alias = 'k', default_value_t = 2)]
        k: usize,
        #[command(flatten)]
        out: OutArgs,
    },
    /// The jump-smoothing polynomial `w_k` (document 001): exact monomial and Bernstein
    /// coefficients and samples.
    #[command(after_help = "\
Examples:
  lekalo blend jump --k 1             # 3u^2 - 2u^3: monomial 0 0 3 -2, Bernstein 0 0 1 1
  lekalo blend jump --k 3 --samples 5 --json")]
    Jump(crate::cmd::jump::JumpArgs),
}

/// Arguments of `lekalo blend`.
#[derive(Args, Debug)]
#[command(after_help = "\
Examples:
  lekalo blend deform a.json b.json --continuity 2
  lekalo blend spline pts.csv --continuity 2 --local parabolas
  lekalo blend corner before.json after.json --from 0.8 --until 0.2
  lekalo blend corners polyline.csv --window 25% --continuity 2")]
pub(crate) struct BlendArgs {
    #[command(subcommand)]
    op: BlendOp,
}

/// A curve object as a library curve.
fn curve(path: &Path, cx: &Context) -> Result<SharedCurve> {
    Ok(Arc::new(load_one(cx, path)?))
}

fn form_object(f: BezierForm) -> Object {
    Object::from(f)
}

/// A blend spline with an exact NURBS form, made segment by segment: JSON is streamed from the
/// points (memory a few numbers a point, whatever the output's size), other formats get the
/// whole NURBS (returned, as with `--json`). Both with a progress bar and Ctrl-C.
fn exact_spline(
    pts: &lekalo::Points,
    local: &(dyn LocalCurves + Sync),
    options: BlendSplineOptions,
    out: &OutArgs,
    input: &Path,
    json: bool,
    cx: &Context,
) -> Result<Option<lekalo::NurbsCurve>> {
    let large = pts.len() > 100_000;
    let what = format!("blending through {} points", pts.len());
    let pieces = with_progress(cx, &what, large, |p| {
        BlendSplinePieces::new(pts.as_view(), local, options, p)
    })?;
    let inputs = [input.to_path_buf()];
    if !json && format_of(out.to.as_deref(), out.output.as_deref(), "json") == "json" {
        with_progress(cx, "writing", large, |p| {
            crate::output::emit_stream(out.output.as_deref(), &inputs, cx, |w| {
                lekalo_io::write_blend_nurbs_json(&pieces, w, true, p)
            })
        })?;
        return Ok(None);
    }
    Ok(Some(with_progress(cx, &what, large, |p| {
        pieces.to_nurbs(p)
    })?))
}

/// `--window`: a length, or a percentage of the shorter segment at each corner.
fn corner_window(text: &str) -> Result<CornerWindow> {
    let (number, percent) = match text.trim().strip_suffix('%') {
        Some(p) => (p, true),
        None => (text, false),
    };
    let x = one_number(number, "--window")?;
    Ok(if percent {
        CornerWindow::Fraction(x / 100.0)
    } else {
        CornerWindow::Length(x)
    })
}

fn one_number(text: &str, what: &str) -> Result<f64> {
    match numbers(text, what)?.as_slice() {
        [x] => Ok(*x),
        _ => bad_input(format!("{what}: give one parameter value, got \"{text}\"")),
    }
}

pub(crate) fn run(a: &BlendArgs, cx: &Context) -> Result<()> {
    match &a.op {
        BlendOp::Jump(j) => crate::cmd::jump::run(j, cx),
        BlendOp::Deform {
            first,
            second,
            k,
            out,
        } => {
            let d = Deformation::new(curve(first, cx)?, curve(second, cx)?, *k)?;
            let Some(form) = d.bezier_form() else {
                return bad_input(
                    "the deformation has an exact form only for single Bezier pieces (Bezier \
                     curves, or B-spline/NURBS curves without interior knots)",
                );
            };
            write_curve(
                &form_object(form),
                None,
                out,
                &[first.clone(), second.clone()],
                cx,
            )
        }
        BlendOp::Spline {
            points,
            k,
            local,
            closed,
            params,
            tolerance,
            json,
            out,
        } => {
            let (pts, _) = crate::items::read_points(cx, points)?;
            let options = BlendSplineOptions {
                continuity: *k,
                closed: *closed,
                parameters: match params {
                    SplineParams::Uniform => SplineParameters::Uniform,
                    SplineParams::Chord => SplineParameters::ChordLength,
                    SplineParams::Centripetal => SplineParameters::Centripetal,
                },
            };
            let large = pts.len() > 100_000;
            let what = format!("blending through {} points", pts.len());
            let (obj, max_error) = match local {
                Local::Parabolas | Local::RationalArcs => {
                    let arcs = CircularArcs::new(ArcParametrization::RationalQuadratic);
                    let family: &(dyn LocalCurves + Sync) = if *local == Local::Parabolas {
                        &Parabolas
                    } else {
                        &arcs
                    };
                    match exact_spline(&pts, family, options, out, points, json.json, cx)? {
                        Some(nurbs) => (Object::Nurbs(nurbs), 0.0),
                        None => return Ok(()),
                    }
                }
                Local::Arcs | Local::GlobalArcs => {
                    let family = CircularArcs::new(if *local == Local::Arcs {
                        ArcParametrization::UniformAngle
                    } else {
                        ArcParametrization::GlobalAngle
                    });
                    let bar = crate::output::spinner(cx, what, large);
                    let s = BlendSpline::new(pts.as_view(), &family, options);
                    let approx = s.and_then(|s| s.approximate(*tolerance));
                    bar.finish_and_clear();
                    let approx = approx?;
                    if !cx.is_quiet() && !json.json {
                        crate::output::report(&format!(
                            "note: arcs have no exact polynomial form; B-spline approximation of \
                             degree {} with max error {}",
                            approx.curve().degree(),
                            crate::report::number(approx.max_error())
                        ));
                    }
                    (Object::BSpline(approx.curve().clone()), approx.max_error())
                }
            };
            if json.json {
                let report = serde_json::json!({
                    "max_error": max_error,
                    "degree": obj.degree(),
                    "curve": obj.to_json_value(),
                });
                return crate::report::print_report(
                    true,
                    &report,
                    crate::report::text_of,
                    out.output.as_deref(),
                    std::slice::from_ref(points),
                    cx,
                );
            }
            write_curve(&obj, Some(&pts), out, std::slice::from_ref(points), cx)
        }
        BlendOp::Corners {
            polyline,
            window,
            k,
            out,
        } => {
            let window = corner_window(window)?;
            let (pts, _) = crate::items::read_points(cx, polyline)?;
            let s = smooth_polyline_corners(pts.as_view(), window, *k)?;
            let obj = Object::BSpline(s.into_curve());
            let inputs = std::slice::from_ref(polyline);
            let format = crate::output::format_of(out.to.as_deref(), out.output.as_deref(), "json");
            if format == "svg" || format == "png" {
                // the control polygon runs along the straight parts, under the curve: the figure
                // shows the curve over its polyline instead (dashed, drawn first, mostly under
                // the curve's straight parts), and marks the polyline's corners, which the curve
                // rounds off and leaves in view
                let mut fig = lekalo_io::curve_figure(
                    &obj,
                    &lekalo_io::CurvePlot {
                        control_polygon: false,
                        ..lekalo_io::CurvePlot::default()
                    },
                )?;
                let view = lekalo_io::Projection::default();
                let polyline: Vec<[f64; 2]> = pts.iter().map(|p| view.to_plane(p)).collect();
                let corners = polyline[1..polyline.len().saturating_sub(1).max(1)].to_vec();
                fig.series.insert(
                    0,
                    lekalo_io::Series::new(
                        Some("corners of the polyline"),
                        corners,
                        lekalo_io::Style::Markers,
                        "#777777",
                    ),
                );
                fig.series.insert(
                    0,
                    lekalo_io::Series::new(None, polyline, lekalo_io::Style::Dashed, "#777777"),
                );
                let bytes = crate::output::encode(&fig, &format, 2.0)?;
                return crate::output::emit(out.output.as_deref(), &bytes, inputs, cx);
            }
            write_curve(&obj, Some(&pts), out, inputs, cx)
        }
        BlendOp::Corner {
            before,
            after,
            from,
            until,
            k,
            out,
        } => {
            let t1 = one_number(from, "--from")?;
            let t2 = one_number(until, "--until")?;
            let c = CornerTransition::new(curve(before, cx)?, t1, curve(after, cx)?, t2, *k)?;
            let Some(form) = c.bezier_form() else {
                return bad_input(
                    "the transition has an exact form only when both curves are single Bezier \
                     pieces",
                );
            };
            write_curve(
                &form_object(form),
                None,
                out,
                &[before.clone(), after.clone()],
                cx,
            )
        }
    }
}
