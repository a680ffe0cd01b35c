//! `lekalo knot`: knot operations on curves and surfaces — insert, refine, remove, split,
//! reverse, reparametrise, decompose into Bezier pieces and join them back — and knot
//! insertion in splines in N parameters. Every operation is
//! the library's own (`BSplineCurve::insert_knot`, `NurbsSurface::split_at_u`, …); this module
//! only chooses the method by the object's kind and the direction.

use lekalo_io::CurveJson;
use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::{Args, Subcommand, ValueEnum};
use lekalo::Direction;
use lekalo_io::{fmt_number, Object, Shape};

use crate::cmd::cad::{load_shape, load_shapes};
use crate::context::Context;
use crate::exit::bad_input;
use crate::output::emit;
use crate::values::numbers;

/// Arguments of `lekalo knot`.
#[derive(Args, Debug)]
#[command(after_help = "\
Curves (Bezier, B-spline, NURBS) and surfaces (in u or v with --dir); `insert` also takes
splines in N parameters (in direction K with --axis K). A Bezier curve or surface is first
written as a B-spline on clamped knots. Results that are several objects
(split, decompose) are JSON Lines, one object per line; `join` reads them back.

Examples:
  lekalo knot insert curve.json --at 0.5 --times 2 -o inserted.json
  lekalo knot refine curve.json --knots 0.25,0.5,0.75 -o refined.json
  lekalo knot remove inserted.json --at 0.5 --times 2 -o back.json
  lekalo knot remove curve.json --all --tolerance 1e-6 -o simpler.json
  lekalo knot split curve.json --at 0.5 -o halves.jsonl
  lekalo knot reverse curve.json -o reversed.json
  lekalo knot reparam curve.json --interval 0,10 -o scaled.json
  lekalo knot decompose curve.json -o pieces.jsonl
  lekalo knot join pieces.jsonl -o joined.json
  lekalo knot insert surface.json --dir v --at 0.5 -o surface2.json
  lekalo knot insert tensor.json --axis 3 --at 0.5 -o tensor2.json")]
pub(crate) struct KnotArgs {
    #[command(subcommand)]
    op: KnotOp,
}

/// Parameter direction of a surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Dir {
    /// The first parameter.
    U,
    /// The second parameter.
    V,
}

/// Input, output and direction shared by every operation.
#[derive(Args, Debug)]
pub(crate) struct Common {
    /// Object file (JSON; `-` for standard input).
    input: PathBuf,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Surfaces: the parameter direction (default u).
    #[arg(long, value_enum)]
    dir: Option<Dir>,
    /// Splines in N parameters: the direction `K` (from 1; default 1). `--dir u|v` names
    /// directions 1 and 2 too.
    #[arg(long, value_name = "K", conflicts_with = "dir")]
    axis: Option<usize>,
}

impl Common {
    /// The surface direction of `--dir`, or of `--axis 1|2`.
    fn surface_dir(&self) -> Result<Direction> {
        match (self.dir, self.axis) {
            (Some(Dir::V), _) | (None, Some(2)) => Ok(Direction::V),
            (Some(Dir::U), _) | (None, None | Some(1)) => Ok(Direction::U),
            (None, Some(k)) => bad_input(format!(
                "--axis {k}: a surface has the directions 1 and 2 (u and v)"
            )),
        }
    }

    /// The direction (from 0) of a spline in `n` parameters: `--axis K`, `--dir u|v`, or
    /// the first.
    fn tensor_axis(&self, n: usize) -> Result<usize> {
        let k = match (self.dir, self.axis) {
            (Some(Dir::U), _) => 1,
            (Some(Dir::V), _) => 2,
            (None, k) => k.unwrap_or(1),
        };
        if k == 0 || k > n {
            return bad_input(format!(
                "--axis {k}: the spline has {n} parameters; directions run from 1 to {n}"
            ));
        }
        Ok(k - 1)
    }
}

#[derive(Subcommand, Debug)]
enum KnotOp {
    /// Insert a knot `--times` times (Boehm; P&T Algorithm A5.1).
    #[command(after_help = "\
The curve or surface keeps its shape; each copy adds one control point. A knot may reach
multiplicity degree at most (degree + 1 at the ends of the domain).

Examples:
  lekalo knot insert curve.json --at 0.5 --times 2 -o inserted.json
  lekalo knot insert surface.json --dir v --at 0.5 -o surface2.json
  lekalo knot insert tensor.json --axis 3 --at 0.5 -o tensor2.json   # a spline in N parameters")]
    Insert {
        #[command(flatten)]
        c: Common,
        /// The knot value.
        #[arg(long, allow_hyphen_values = true)]
        at: String,
        /// How many copies to insert.
        #[arg(long, short = 'r', default_value_t = 1)]
        times: usize,
    },
    /// Insert many knots at once (Oslo refinement; P&T Algorithm A5.4).
    #[command(after_help = "\
Examples:
  lekalo knot refine curve.json --knots 0.25,0.5,0.75 -o refined.json
  lekalo knot refine surface.json --dir u --knots 1/3,2/3 -o finer.json")]
    Refine {
        #[command(flatten)]
        c: Common,
        /// The knots to insert, sorted, comma-separated.
        #[arg(long, allow_hyphen_values = true)]
        knots: String,
    },
    /// Remove a knot (or every removable knot) within a tolerance (P&T Algorithm A5.8);
    /// reports on stderr what was removed. Curves only.
    #[command(after_help = "\
Examples:
  lekalo knot insert curve.json --at 0.5 --times 2 -o inserted.json
  lekalo knot remove inserted.json --at 0.5 --times 2 -o back.json   # the copies inserted come out again
  lekalo knot remove curve.json --all --tolerance 1e-6 --json        # every knot that can go, and a report")]
    Remove {
        #[command(flatten)]
        c: Common,
        /// The knot to remove.
        #[arg(
            long,
            allow_hyphen_values = true,
            conflicts_with = "all",
            required_unless_present = "all"
        )]
        at: Option<String>,
        /// How many copies to try to remove (default: all copies).
        #[arg(long, short = 'r')]
        times: Option<usize>,
        /// Remove every interior knot copy that the tolerance allows.
        #[arg(long)]
        all: bool,
        /// Largest distance the curve may move (default: the library's, relative to the size
        /// of the control polygon).
        #[arg(long)]
        tolerance: Option<f64>,
        /// Write `{"removed", "tolerance", "knots_removed", "curve"}` instead of the curve alone.
        #[command(flatten)]
        json: crate::report::JsonFlag,
    },
    /// Split at a parameter into two objects (JSON Lines).
    #[command(after_help = "\
Examples:
  lekalo knot split curve.json --at 0.5 -o halves.jsonl   # two curves that meet at t = 0.5
  lekalo knot split surface.json --dir v --at 0.5 -o halves.jsonl")]
    Split {
        #[command(flatten)]
        c: Common,
        /// The parameter to split at (inside the domain).
        #[arg(long, allow_hyphen_values = true)]
        at: String,
    },
    /// Reverse the direction of the parameter.
    #[command(after_help = "\
Examples:
  lekalo knot reverse curve.json -o reversed.json
  lekalo knot reverse surface.json --dir v -o flipped.json")]
    Reverse {
        #[command(flatten)]
        c: Common,
    },
    /// Map the domain affinely onto `[a, b]` (curves).
    #[command(after_help = "\
Examples:
  lekalo knot reparam curve.json --interval 0,1 -o unit.json   # the same curve on the domain [0, 1]")]
    Reparam {
        #[command(flatten)]
        c: Common,
        /// The new domain `a,b` with `a < b`.
        #[arg(long, allow_hyphen_values = true, value_name = "A,B")]
        interval: String,
    },
    /// Decompose into Bezier pieces (JSON Lines), each on its own interval of the domain.
    #[command(after_help = "\
Examples:
  lekalo knot decompose curve.json -o pieces.jsonl     # one Bezier curve a line
  lekalo knot decompose surface.json -o patches.jsonl  # one Bezier patch a line")]
    Decompose {
        #[command(flatten)]
        c: Common,
    },
    /// Join curves end to end (JSON Lines, in order; the Bezier pieces `decompose` writes, or
    /// any curves) into one B-spline or NURBS curve (`lekalo::Curve::composite`).
    #[command(after_help = "\
Each curve follows on over its own parameter interval, shifted to start where the previous
one ends; all are raised to the highest degree, each join is a knot of multiplicity degree
(C0), and the result is rational if any piece is.

Examples:
  lekalo knot decompose curve.json -o pieces.jsonl
  lekalo knot join pieces.jsonl -o joined.json   # the curve again, its interior knots at multiplicity degree")]
    Join {
        /// JSON Lines of the curves, in order.
        input: PathBuf,
        /// Largest gap between one curve's end and the next one's start that is closed (the
        /// start moved onto the end; default 1e-9 of the largest coordinate).
        #[arg(long)]
        tolerance: Option<f64>,
        /// Output file (default: standard output).
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
    },
}

fn one(text: &str, what: &str) -> Result<f64> {
    let v = numbers(text, what)?;
    if v.len() != 1 {
        return bad_input(format!("{what}: give one value, not {}", v.len()));
    }
    Ok(v[0])
}

fn write_one(c: &Common, s: &Shape, cx: &Context) -> Result<()> {
    emit(
        c.output.as_deref(),
        s.to_json_pretty().as_bytes(),
        std::slice::from_ref(&c.input),
        cx,
    )
}

fn write_many(out: Option<&Path>, input: &Path, shapes: &[Shape], cx: &Context) -> Result<()> {
    let text: String = shapes.iter().map(|s| s.to_json_line() + "\n").collect();
    emit(out, text.as_bytes(), &[input.to_path_buf()], cx)
}

fn surface_only_u_v<T>(op: &str) -> Result<T> {
    bad_input(format!(
        "`lekalo knot {op}` works on curves; for a surface use insert, refine, split, reverse or decompose (with --dir u or v)"
    ))
}

pub(crate) fn run(a: &KnotArgs, cx: &Context) -> Result<()> {
    match &a.op {
        KnotOp::Insert { c, at, times } => {
            let t = one(at, "--at")?;
            let out = match load_shape(&c.input, cx)? {
                Shape::Curve(o) => Shape::Curve(o.insert_knot(t, *times)?),
                Shape::Surface(s) => Shape::Surface(s.insert_knot(c.surface_dir()?, t, *times)?),
                Shape::Tensor(s) => {
                    let axis = c.tensor_axis(s.n_vars())?;
                    let out = s.insert_knot(axis, t, *times)?;
                    let inputs = std::slice::from_ref(&c.input);
                    let out_file = c.output.as_deref();
                    return crate::output::objects::write_tensor(
                        &out,
                        (None, out_file),
                        inputs,
                        cx,
                    );
                }
                other => return not_spline(&c.input, &other),
            };
            write_one(c, &out, cx)
        }
        KnotOp::Refine { c, knots } => {
            let x = numbers(knots, "--knots")?;
            let out = match load_shape(&c.input, cx)? {
                Shape::Curve(o) => Shape::Curve(o.refine_knots(&x)?),
                Shape::Surface(s) => Shape::Surface(s.refine_knots(c.surface_dir()?, &x)?),
                other => return not_spline(&c.input, &other),
            };
            write_one(c, &out, cx)
        }
        KnotOp::Remove {
            c,
            at,
            times,
            all,
            tolerance,
            json,
        } => {
            let curve = match load_shape(&c.input, cx)? {
                Shape::Curve(o) => o.to_spline(),
                Shape::Surface(_) => return surface_only_u_v("remove"),
                other => return not_spline(&c.input, &other),
            };
            let tol = tolerance.unwrap_or_else(|| curve.default_removal_tolerance());
            let before = curve.knots().into_owned().into_vec();
            let (after, removed) = match at {
                Some(at) if !*all => {
                    let t = one(at, "--at")?;
                    let r = times.unwrap_or_else(|| curve.knots().multiplicity(t));
                    curve.remove_knot(t, r, tol)?
                }
                _ => curve.remove_all_removable_knots(tol)?,
            };
            let gone = removed_knots(&before, after.knots().as_slice());
            if json.json {
                let report = serde_json::json!({
                    "removed": removed,
                    "tolerance": tol,
                    "knots_removed": gone
                        .iter()
                        .map(|(t, m)| serde_json::json!({"knot": t, "copies": m}))
                        .collect::<Vec<_>>(),
                    "curve": after.to_json_value(),
                });
                let inputs = std::slice::from_ref(&c.input);
                let out = c.output.as_deref();
                return crate::report::print_report(
                    true,
                    &report,
                    crate::report::text_of,
                    out,
                    inputs,
                    cx,
                );
            }
            if !cx.is_quiet() {
                crate::output::report(&removal_report(&gone, removed, tol));
            }
            write_one(c, &Shape::Curve(after), cx)
        }
        KnotOp::Split { c, at } => {
            let t = one(at, "--at")?;
            let pieces = match load_shape(&c.input, cx)? {
                Shape::Curve(o) => {
                    let (l, r) = o.split_at(t)?;
                    vec![Shape::Curve(l), Shape::Curve(r)]
                }
                Shape::Surface(s) => {
                    let (l, r) = s.split_at(c.surface_dir()?, t)?;
                    vec![Shape::Surface(l), Shape::Surface(r)]
                }
                other => return not_spline(&c.input, &other),
            };
            write_many(c.output.as_deref(), &c.input, &pieces, cx)
        }
        KnotOp::Reverse { c } => {
            let out = match load_shape(&c.input, cx)? {
                Shape::Curve(o) => Shape::Curve(o.reverse()?),
                Shape::Surface(s) => Shape::Surface(s.reverse(c.surface_dir()?)?),
                other => return not_spline(&c.input, &other),
            };
            write_one(c, &out, cx)
        }
        KnotOp::Reparam { c, interval } => {
            let ab = numbers(interval, "--interval")?;
            let [lo, hi] = ab[..] else {
                return bad_input(format!(
                    "--interval: give two values a,b with a < b, not {}",
                    ab.len()
                ));
            };
            if !(lo < hi && (hi - lo).is_finite()) {
                // ±1e308 used to reach the library as an infinite width ("knots[0] is NaN")
                return bad_input(format!(
                    "--interval {},{}: give a < b whose difference b − a is a finite number",
                    lekalo_io::fmt_number(lo),
                    lekalo_io::fmt_number(hi)
                ));
            }
            let out = match load_shape(&c.input, cx)? {
                Shape::Curve(o) => Shape::Curve(o.reparametrize(lo, hi)?),
                Shape::Surface(_) => {
                    return bad_input(
                        "`lekalo knot reparam` works on curves; surfaces keep their domain",
                    )
                }
                other => return not_spline(&c.input, &other),
            };
            write_one(c, &out, cx)
        }
        KnotOp::Decompose { c } => {
            let pieces: Vec<Shape> = match load_shape(&c.input, cx)? {
                Shape::Curve(o) => o
                    .to_bezier_pieces()?
                    .into_iter()
                    .map(Shape::Curve)
                    .collect(),
                Shape::Surface(s) => s
                    .to_bezier_pieces()?
                    .into_iter()
                    .map(Shape::Surface)
                    .collect(),
                other => return not_spline(&c.input, &other),
            };
            write_many(c.output.as_deref(), &c.input, &pieces, cx)
        }
        KnotOp::Join {
            input,
            output,
            tolerance,
        } => {
            let shapes = load_shapes(input, cx)?;
            let joined = join(&shapes, input, *tolerance)?;
            emit(
                output.as_deref(),
                joined.to_json_pretty().as_bytes(),
                std::slice::from_ref(input),
                cx,
            )
        }
    }
}

fn not_spline<T>(path: &Path, s: &Shape) -> Result<T> {
    if let Shape::Tensor(_) = s {
        return bad_input(format!(
            "{}: a spline in N parameters takes `lekalo knot insert --axis K` (and `lekalo \
             slice`); the other knot operations take curves and surfaces",
            path.display()
        ));
    }
    bad_input(format!(
        "{}: field `type`: \"{}\" has no knots to operate on (knot operations take curves and surfaces)",
        path.display(),
        s.type_name()
    ))
}

/// The knots that were in `before` and are not in `after`, with how many copies went.
fn removed_knots(before: &[f64], after: &[f64]) -> Vec<(f64, usize)> {
    let mut gone: Vec<(f64, usize)> = Vec::new();
    let (mut i, mut j) = (0, 0);
    while i < before.len() {
        if j < after.len() && after[j] == before[i] {
            i += 1;
            j += 1;
        } else {
            match gone.last_mut() {
                Some((x, m)) if *x == before[i] => *m += 1,
                _ => gone.push((before[i], 1)),
            }
            i += 1;
        }
    }
    gone
}

/// "removed 2 knot copies (tolerance 1e-9): 0.5×2".
fn removal_report(gone: &[(f64, usize)], removed: usize, tol: f64) -> String {
    let list: Vec<String> = gone
        .iter()
        .map(|(x, m)| format!("{}×{m}", fmt_number(*x)))
        .collect();
    if removed == 0 {
        format!(
            "removed no knot (tolerance {}): no removal keeps the curve that close",
            fmt_number(tol)
        )
    } else {
        format!(
            "removed {removed} knot cop{} (tolerance {}): {}",
            if removed == 1 { "y" } else { "ies" },
            fmt_number(tol),
            list.join("  ")
        )
    }
}

/// One curve from single-segment pieces in order ([`lekalo::Curve::join`]).
fn join(shapes: &[Shape], input: &Path, tolerance: Option<f64>) -> Result<Shape> {
    let mut curves = Vec::with_capacity(shapes.len());
    for (k, s) in shapes.iter().enumerate() {
        let Shape::Curve(o) = s else {
            return bad_input(format!(
                "{}: piece {} is a {}, not a curve",
                input.display(),
                k + 1,
                s.type_name()
            ));
        };
        curves.push(o.clone());
    }
    let tol = tolerance.unwrap_or_else(|| Object::composite_tolerance(&curves));
    match Object::composite(&curves, tol) {
        Ok(c) => Ok(Shape::Curve(c)),
        Err(e) => bad_input(format!("{}: {e}", input.display())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removal_report_lists_what_went() {
        let gone = removed_knots(&[0.0, 0.0, 0.5, 0.5, 1.0, 1.0], &[0.0, 0.0, 1.0, 1.0]);
        assert_eq!(gone, [(0.5, 2)]);
        let r = removal_report(&gone, 2, 1e-9);
        assert_eq!(r, "removed 2 knot copies (tolerance 1e-9): 0.5×2");
        let r = removal_report(&removed_knots(&[0.0, 1.0], &[0.0, 1.0]), 0, 0.5);
        assert!(r.starts_with("removed no knot"), "{r}");
    }
}
