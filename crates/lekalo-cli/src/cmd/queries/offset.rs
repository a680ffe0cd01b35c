//! `lekalo offset`: the offset of a planar curve at a distance, within a tolerance, with its
//! cusps and loops reported and the loops trimmed (the library's `QueryCurve::offset`).

use lekalo_io::CurveJson;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo::query::Offset;
use lekalo_io::{Object, Shape};
use serde_json::json;

use crate::cmd::measure::query_curve;
use crate::context::Context;
use crate::items::load_one;
use crate::output::{emit, report};
use crate::words::in_file;

/// Arguments of `lekalo offset`.
#[derive(Args, Debug)]
#[command(after_help = "\
The offset of a planar curve C at signed distance d: a cubic B-spline within the tolerance of
C(t) + d·N(t), N the left normal (positive d lies to the left of the direction of travel). Where
d exceeds the radius of curvature on the same side the exact offset has cusps and a loop between
them; the cusps and the cut-out parameter intervals are reported, and --trim writes the parts
left after cutting out the loops (JSON Lines, one curve a line) instead of the whole offset.

--json writes a report instead: distance, tolerance, the deviation reached, the cusps, the loops
and the curves themselves (\"curve\": the whole offset; \"trimmed\": the parts).

Examples:
  lekalo offset curve.json --distance 0.5 -o outside.json
  lekalo offset curve.json --distance -0.5 --tolerance 1e-8 --trim -o inside.jsonl
  lekalo offset ellipse.json --distance 0.6 --json")]
pub(crate) struct OffsetArgs {
    /// Planar curve file (JSON; `-` for standard input).
    input: PathBuf,
    /// Signed distance: positive to the left of the direction of travel, negative to the right.
    #[arg(long, allow_hyphen_values = true)]
    distance: f64,
    /// Largest deviation from the exact offset (in the curve's units).
    #[arg(long, short = 't', default_value_t = 1e-6)]
    tolerance: f64,
    /// Write the parts left after cutting out the loops (JSON Lines) instead of the whole
    /// offset.
    #[arg(long)]
    trim: bool,
    /// Write a JSON report (cusps, loops, deviation and the curves) instead of the curve.
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

/// The JSON report of an offset.
fn report_json(a: &OffsetArgs, off: &Offset) -> String {
    let curve = |c: &lekalo::BSplineCurve| Object::BSpline(c.clone()).to_json_value();
    let j = json!({
        "distance": a.distance,
        "tolerance": a.tolerance,
        "deviation": off.deviation,
        "cusps": off.cusps,
        "loops": off.loops.iter().map(|l| [l.0, l.1]).collect::<Vec<_>>(),
        "curve": curve(&off.curve),
        "trimmed": off.trimmed.iter().map(curve).collect::<Vec<_>>(),
    });
    format!("{j:#}\n")
}

pub(crate) fn run(a: &OffsetArgs, cx: &Context) -> Result<()> {
    let q = query_curve(&load_one(cx, &a.input)?, &a.input)?;
    let off = q
        .offset(a.distance, a.tolerance)
        // kept in the chain: an error about the tolerance names --tolerance
        .map_err(|e| in_file(&a.input, e))?;
    let text = if a.json {
        report_json(a, &off)
    } else {
        if !cx.is_quiet() && !off.cusps.is_empty() {
            report(&format!(
                "note: {} cusp(s) where |d| exceeds the radius of curvature, {} loop(s) cut out \
                 (--json lists them){}",
                off.cusps.len(),
                off.loops.len(),
                if a.trim {
                    ""
                } else {
                    "; --trim writes the offset without its loops"
                }
            ));
        }
        if a.trim {
            off.trimmed
                .iter()
                .map(|c| Object::BSpline(c.clone()).to_json_line() + "\n")
                .collect()
        } else {
            Shape::Curve(Object::BSpline(off.curve)).to_json_pretty()
        }
    };
    emit(
        a.output.as_deref(),
        text.as_bytes(),
        std::slice::from_ref(&a.input),
        cx,
    )
}
