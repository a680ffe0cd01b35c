//! `lekalo bezier`: order change of Bezier curves and surfaces (document 004).

use lekalo_io::CurveJson;
use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, Subcommand, ValueEnum};
use lekalo::{BSplineCurve, BezierCurve, BezierSurface, EndConditions};
use lekalo_io::Object;

use crate::context::Context;
use crate::exit::bad_input;
use crate::items::load_one;
use crate::output::objects::{write_bezier_surface, write_curve, write_surface, OutArgs};
use crate::values::integers;
use crate::values::net_size;

/// The input of a `bezier` operation: a curve object, or a surface net.
#[derive(Args, Debug)]
pub(crate) struct BezierInput {
    /// A Bezier curve or Bezier surface object (JSON; `-` for standard input), a B-spline curve
    /// or surface (elevate, change, and reduce --approx of curves: piece by piece), or the
    /// control points of a Bezier curve as a points file (CSV, text, JSON list, .npy; degree =
    /// number of points − 1), or nothing with --surface.
    input: Option<PathBuf>,
    /// A Bezier surface: its control net as a points file, read row by row (with --net).
    #[arg(long, value_name = "FILE", requires = "net")]
    surface: Option<PathBuf>,
    /// Net size of --surface, rows x columns = (n + 1) x (m + 1), e.g. 5x4.
    #[arg(long, value_name = "ROWSxCOLS")]
    net: Option<String>,
}

/// End conditions of the approximate reduction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Ends {
    /// Nothing (plain L2 best approximation).
    Free,
    /// The end points.
    Points,
    /// The end points and end tangents (degree ≥ 3).
    Tangents,
}

/// `lekalo bezier` operations.
#[derive(Subcommand, Debug)]
pub(crate) enum BezierOp {
    /// Raise the degree without changing the shape (document 004 eq. 7–8); B-spline curves too
    /// (each Bezier piece elevated; interior knots get multiplicity m + r, as P&T A5.9).
    #[command(after_help = "\
Examples:
  lekalo bezier elevate quad.json --by 1          # Example 1, task 1: 2 legs -> 3 legs
  lekalo bezier elevate cubic.json --by 2 -o quintic.svg
  lekalo bezier elevate --surface net.csv --net 3x4 --by 1,2 -o s.json
  lekalo bezier elevate s.json --by 1,0 -o s.step    # s.json: a bezier_surface object")]
    Elevate {
        #[command(flatten)]
        input: BezierInput,
        /// How much to raise: one number for a curve, `du,dv` for a surface.
        #[arg(long, default_value = "1")]
        by: String,
        #[command(flatten)]
        out: OutArgs,
    },
    /// Reduce exactly to the real degree: the minimal control polygon (document 004 eq. 9);
    /// or, with --approx, the best L2 approximation of a lower degree (curves).
    #[command(after_help = "\
Examples:
  lekalo bezier reduce quintic.json               # Example 2: the cubic (10,0),(30,10),(0,20),(20,0)
  lekalo bezier reduce --surface net.csv --net 5x4 -o minimal.json
  lekalo bezier reduce quartic.json --approx 3 --ends tangents   # prints the deviation
  lekalo bezier reduce quartic.json --approx 3 --json            # deviation and curve")]
    Reduce {
        #[command(flatten)]
        input: BezierInput,
        /// Approximate reduction to this degree (changes the shape; the deviation is printed).
        #[arg(long, value_name = "DEGREE")]
        approx: Option<usize>,
        /// What the approximate reduction keeps at the ends.
        #[arg(long, value_enum, default_value_t = Ends::Points)]
        ends: Ends,
        /// Write `{"max_deviation_sampled", "max_deviation_bound", "curve"}` (0 for exact
        /// reduction) instead of the curve alone.
        #[command(flatten)]
        json: crate::report::JsonFlag,
        #[command(flatten)]
        out: OutArgs,
    },
    /// Print the formal degree, the real degree and the defect (document 004, eq. (9)–(10)).
    #[command(after_help = "\
Examples:
  lekalo bezier real-degree quintic.json          # degree 5, real degree 3, defect 2
  lekalo bezier real-degree quintic.json --json   # {\"degree\": 5, \"real_degree\": 3, \"defect\": 2}
  lekalo bezier real-degree --surface net.csv --net 5x4")]
    RealDegree {
        #[command(flatten)]
        input: BezierInput,
        /// Print a JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Change to any degree by the unified formula (eq. 10; eq. 14 for surfaces). Lowering
    /// below the real degree is refused with the real degree in the message.
    #[command(after_help = "\
Examples:
  lekalo bezier change quintic.json --degree 3
  lekalo bezier change quintic.json --degree 2    # refused: the real degree is 3
  lekalo bezier change --surface net.csv --net 5x4 --degree 3,6")]
    Change {
        #[command(flatten)]
        input: BezierInput,
        /// Target degree: one number for a curve, `n,m` for a surface.
        #[arg(long)]
        degree: String,
        #[command(flatten)]
        out: OutArgs,
    },
}

/// Arguments of `lekalo bezier`.
#[derive(Args, Debug)]
#[command(after_help = "\
Curves are read as Bezier curve objects, or directly as a points file of their control points
(CSV, text, JSON list or .npy; the degree is the number of points minus one); surfaces as a
surface object, or a points file of the control net, row by row, with --net ROWSxCOLS.

Examples:
  lekalo bezier real-degree quintic.json
  lekalo bezier real-degree control.csv           # the control points of a Bezier curve
  lekalo bezier reduce quintic.json -o cubic.json
  lekalo bezier elevate cubic.json --by 2
  lekalo bezier change --surface net.csv --net 5x4 --degree 3,6 -o s.step")]
pub(crate) struct BezierArgs {
    #[command(subcommand)]
    op: BezierOp,
}

enum Loaded {
    Curve(BezierCurve, PathBuf),
    BSpline(BSplineCurve, PathBuf),
    Surface(BezierSurface, PathBuf),
    BSplineSurface(lekalo::BSplineSurface, PathBuf),
}

fn load(i: &BezierInput, cx: &Context) -> Result<Loaded> {
    match (&i.input, &i.surface, &i.net) {
        (Some(p), None, None) => {
            if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("npy")) {
                let (pts, _) = crate::items::read_points(cx, p)?;
                return Ok(Loaded::Curve(BezierCurve::new(pts)?, p.clone()));
            }
            let (text, name) = lekalo_io::read_input(p)?;
            match lekalo_io::envelope_type(&text).as_deref() {
                Some("bezier_surface") => {
                    let s = lekalo_io::read_bezier_surface(&text, &name)?;
                    Ok(Loaded::Surface(s, p.clone()))
                }
                Some("bspline_surface") => {
                    let s = lekalo_io::read_bspline_surface(&text, &name)?;
                    Ok(Loaded::BSplineSurface(s, p.clone()))
                }
                // not an object: a points file of the control points
                None if !lekalo_io::strip_bom_str(&text)
                    .trim_start()
                    .starts_with('{') =>
                {
                    let pts = crate::items::points_from_text(cx, &text, &name)?;
                    Ok(Loaded::Curve(BezierCurve::new(pts)?, p.clone()))
                }
                _ => load_curve(p, cx),
            }
        }
        (None, Some(p), Some(net)) => {
            let (rows, cols) = net_size(net, "--net")?;
            let (pts, _) = crate::items::read_points(cx, p)?;
            Ok(Loaded::Surface(
                BezierSurface::new(pts, (rows, cols))?,
                p.clone(),
            ))
        }
        (Some(_), Some(_), _) => {
            bad_input("give either a curve file or --surface FILE --net ROWSxCOLS, not both")
        }
        _ => bad_input("no input: give a Bezier curve file, or --surface FILE --net ROWSxCOLS"),
    }
}

fn load_curve(p: &std::path::Path, cx: &Context) -> Result<Loaded> {
    match load_one(cx, p)? {
        Object::Bezier(c) => Ok(Loaded::Curve(c, p.to_path_buf())),
        Object::BSpline(c) => Ok(Loaded::BSpline(c, p.to_path_buf())),
        other => bad_input(format!(
            "{}: is a {}; `lekalo bezier` takes a Bezier curve or surface, a points file of control points, or --surface with --net",
            p.display(),
            other.display_name()
        )),
    }
}

/// Refuses degrees above `--max-degree` for the operations whose cost grows as the degree
/// `bezier reduce --json`: the deviation `(sampled, bound)` and the curve.
fn reduction_report(
    obj: &Object,
    (sampled, bound): (f64, f64),
    out: &OutArgs,
    input: PathBuf,
    cx: &Context,
) -> Result<()> {
    let report = serde_json::json!({
        "max_deviation_sampled": sampled,
        "max_deviation_bound": bound,
        "curve": obj.to_json_value(),
    });
    let to = out.output.as_deref();
    crate::report::print_report(true, &report, crate::report::text_of, to, &[input], cx)
}

/// squared (real degree, exact reduction, change) or cubed (approximate reduction).
fn guard(cx: &Context, l: Loaded, what: &str) -> Result<Loaded> {
    let limit = cx.max_degree;
    let degree = match &l {
        Loaded::Curve(c, _) => c.degree(),
        Loaded::Surface(s, _) => s.degree_u().max(s.degree_v()),
        Loaded::BSpline(c, _) => c.degree(),
        Loaded::BSplineSurface(s, _) => s.degree_u().max(s.degree_v()),
    };
    if degree > limit {
        return bad_input(format!(
            "{what} of degree {degree} is above the degree limit {limit} (its cost grows as the degree squared or faster); raise it with --max-degree {degree}"
        ));
    }
    Ok(l)
}

/// The refusal of the real degree, or of the exact reduction, of a B-spline curve or surface.
fn not_bezier() -> Result<()> {
    bad_input(
        "the real degree is defined for one Bezier piece; a B-spline curve or surface is \
         elevated or changed to a degree (`lekalo bezier change --degree N` refuses a degree \
         below that of its pieces and names it), a B-spline curve reduced with --approx; split \
         it into Bezier pieces with `lekalo knot decompose` for the real degree of each",
    )
}

/// The library's end conditions of `--ends`.
fn end_conditions(ends: Ends) -> EndConditions {
    match ends {
        Ends::Free => EndConditions::Free,
        Ends::Points => EndConditions::Points,
        Ends::Tangents => EndConditions::Tangents,
    }
}

/// One number for curves, two for surfaces.
fn amounts(text: &str, what: &str, surface: bool) -> Result<(usize, usize)> {
    let n = integers(text, what)?;
    match (surface, n.as_slice()) {
        (false, [a]) => Ok((*a, 0)),
        (true, [a, b]) => Ok((*a, *b)),
        (true, [a]) => Ok((*a, *a)),
        _ => bad_input(format!(
            "{what}: give one number for a curve, or two (u,v) for a surface; got \"{text}\""
        )),
    }
}

pub(crate) fn run(a: &BezierArgs, cx: &Context) -> Result<()> {
    match &a.op {
        BezierOp::Elevate { input, by, out } => match load(input, cx)? {
            Loaded::Curve(c, p) => {
                let (k, _) = amounts(by, "--by", false)?;
                cx.check_size(c.degree().saturating_add(k), "degree after --by")?;
                let r = c.elevate_degree(k)?;
                write_curve(&Object::Bezier(r), None, out, &[p], cx)
            }
            Loaded::BSpline(c, p) => {
                let (k, _) = amounts(by, "--by", false)?;
                write_curve(&Object::BSpline(c.elevate_degree(k)?), None, out, &[p], cx)
            }
            Loaded::Surface(s, p) => {
                let (du, dv) = amounts(by, "--by", true)?;
                write_bezier_surface(&s.elevate_degree(du, dv)?, out, &[p], cx)
            }
            Loaded::BSplineSurface(s, p) => {
                let (du, dv) = amounts(by, "--by", true)?;
                write_surface(&s.elevate_degree(du, dv)?, out, &[p], cx)
            }
        },
        BezierOp::Reduce {
            input,
            approx,
            ends,
            json,
            out,
        } => match guard(cx, load(input, cx)?, "reduction")? {
            Loaded::Curve(c, p) => match approx {
                None => {
                    let obj = Object::Bezier(c.reduce_degree_exact());
                    if json.json {
                        return reduction_report(&obj, (0.0, 0.0), out, p, cx);
                    }
                    write_curve(&obj, None, out, &[p], cx)
                }
                Some(target) => {
                    let limit = cx.max_degree / 4;
                    if c.degree() > limit {
                        return bad_input(format!(
                            "approximate reduction of degree {} is above its limit {limit} (a quarter of --max-degree: its cost grows as the degree cubed); raise it with --max-degree {}",
                            c.degree(),
                            c.degree().saturating_mul(4)
                        ));
                    }
                    let ends = end_conditions(*ends);
                    let bar = crate::output::spinner(
                        cx,
                        format!("reducing degree {} to {target}", c.degree()),
                        c.degree() > 200,
                    );
                    let r = c.reduce_degree_approx(*target, ends);
                    bar.finish_and_clear();
                    let r = r?;
                    let obj = Object::Bezier(r.curve);
                    if json.json {
                        let d = (r.max_deviation_sampled, r.max_deviation_bound);
                        return reduction_report(&obj, d, out, p, cx);
                    }
                    if !cx.is_quiet() {
                        crate::output::report(&format!(
                            "max deviation {} (sampled), bound {}",
                            crate::report::number(r.max_deviation_sampled),
                            crate::report::number(r.max_deviation_bound)
                        ));
                    }
                    write_curve(&obj, None, out, &[p], cx)
                }
            },
            Loaded::BSpline(c, p) => {
                let Some(target) = approx else {
                    return not_bezier();
                };
                let r = c.reduce_degree_approx(*target, end_conditions(*ends))?;
                let obj = Object::BSpline(r.curve);
                let d = (r.max_deviation_sampled, r.max_deviation_bound);
                if json.json {
                    return reduction_report(&obj, d, out, p, cx);
                }
                if !cx.is_quiet() {
                    crate::output::report(&format!(
                        "max deviation {} (sampled), bound {}",
                        crate::report::number(d.0),
                        crate::report::number(d.1)
                    ));
                }
                write_curve(&obj, None, out, &[p], cx)
            }
            Loaded::BSplineSurface(..) => not_bezier(),
            Loaded::Surface(_, _) if approx.is_some() => bad_input(
                "--approx reduces curves; surfaces are reduced exactly to their real degrees",
            ),
            Loaded::Surface(s, p) => {
                let (n, m) = s.real_degrees();
                write_bezier_surface(&s.change_degree(n, m)?, out, &[p], cx)
            }
        },
        BezierOp::RealDegree { input, json } => {
            let report = match guard(cx, load(input, cx)?, "the real degree")? {
                Loaded::Curve(c, _) => serde_json::json!({
                    "degree": c.degree(),
                    "real_degree": c.real_degree(),
                    "defect": c.degree_defect(),
                }),
                Loaded::BSpline(..) | Loaded::BSplineSurface(..) => return not_bezier(),
                Loaded::Surface(s, _) => {
                    let (n, m) = s.real_degrees();
                    serde_json::json!({
                        "degree": [s.degree_u(), s.degree_v()],
                        "real_degree": [n, m],
                        "defect": [s.degree_u() - n, s.degree_v() - m],
                    })
                }
            };
            // text: "degree 5" / "degrees 5 4", one line per figure
            let text = |r: &serde_json::Value| {
                let plural = if r["degree"].is_array() { "s" } else { "" };
                ["degree", "real_degree", "defect"]
                    .iter()
                    .map(|k| {
                        format!(
                            "{}{plural} {}\n",
                            k.replace('_', " "),
                            crate::report::value_text(&r[*k])
                        )
                    })
                    .collect()
            };
            crate::report::print_report(*json, &report, text, None, &[], cx)
        }
        BezierOp::Change { input, degree, out } => {
            match guard(cx, load(input, cx)?, "degree change")? {
                Loaded::Curve(c, p) => {
                    let (n, _) = amounts(degree, "--degree", false)?;
                    write_curve(&Object::Bezier(c.change_degree(n)?), None, out, &[p], cx)
                }
                Loaded::BSpline(c, p) => {
                    let (n, _) = amounts(degree, "--degree", false)?;
                    write_curve(&Object::BSpline(c.change_degree(n)?), None, out, &[p], cx)
                }
                Loaded::Surface(s, p) => {
                    let (n, m) = amounts(degree, "--degree", true)?;
                    write_bezier_surface(&s.change_degree(n, m)?, out, &[p], cx)
                }
                Loaded::BSplineSurface(s, p) => {
                    let (n, m) = amounts(degree, "--degree", true)?;
                    write_surface(&s.change_degree(n, m)?, out, &[p], cx)
                }
            }
        }
    }
}
