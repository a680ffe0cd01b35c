//! `lekalo intersect`: planar curve–curve intersections, self-intersections, curve–plane.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo::query::CurveIntersection;
use serde_json::json;

use crate::cmd::measure::query_curve;
use crate::io::{bad_input, emit, load_one, numbers, BadInput};
use crate::Verbosity;

/// Arguments of `lekalo intersect`.
#[derive(Args, Debug)]
#[command(after_help = "\
Two planar curves: every crossing and touching point (parameters on both curves and the point)
and every overlap (an interval on each). One curve with --self: its self-intersections. One curve
with --plane: where it meets the plane through a point with a normal (any dimension).

Output CSV rows: point,t_a,t_b,x,y  or  overlap,a0,a1,b0,b1.

Examples:
  lekalo intersect a.json b.json
  lekalo intersect a.json b.json --tolerance 1e-9 --json
  lekalo intersect loop.json --self
  lekalo intersect space.json --plane 0,0,1,0,0,1")]
pub(crate) struct IntersectArgs {
    /// First curve.
    first: PathBuf,
    /// Second curve (omit with --self or --plane).
    second: Option<PathBuf>,
    /// Self-intersections of the first curve.
    #[arg(long = "self")]
    self_: bool,
    /// Plane as origin then normal, comma-separated (2·dim numbers).
    #[arg(long, allow_hyphen_values = true)]
    plane: Option<String>,
    /// Distance under which points count as common (in the curves' units).
    #[arg(long, default_value_t = 1e-9)]
    tolerance: f64,
    /// Output JSON instead of CSV.
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn run(a: &IntersectArgs, v: Verbosity) -> Result<()> {
    let qa = query_curve(&load_one(&a.first, v)?, &a.first)?;
    let bad = |e: lekalo::Error| BadInput(format!("{}: {e}", a.first.display()));
    let mut inputs = vec![a.first.clone()];
    let hits: Vec<CurveIntersection> = if let Some(plane) = &a.plane {
        let nums = numbers(plane, "--plane")?;
        let d = qa.dim();
        if nums.len() != 2 * d {
            return bad_input(format!(
                "--plane: give {} numbers (origin, normal), got {}",
                2 * d,
                nums.len()
            ));
        }
        qa.intersect_plane(&nums[..d], &nums[d..])
            .map_err(bad)?
            .into_iter()
            .map(|(t, point)| CurveIntersection::Point {
                t_a: t,
                t_b: f64::NAN,
                point,
            })
            .collect()
    } else if a.self_ {
        qa.self_intersections(a.tolerance).map_err(bad)?
    } else {
        let Some(second) = &a.second else {
            return bad_input("give a second curve, --self or --plane");
        };
        inputs.push(second.clone());
        let qb = query_curve(&load_one(second, v)?, second)?;
        qa.intersect(&qb, a.tolerance).map_err(bad)?
    };
    let text = if a.json {
        let j: Vec<_> = hits
            .iter()
            .map(|h| match h {
                CurveIntersection::Point { t_a, t_b, point } => {
                    if t_b.is_nan() {
                        json!({"kind": "point", "t": t_a, "point": point})
                    } else {
                        json!({"kind": "point", "t_a": t_a, "t_b": t_b, "point": point})
                    }
                }
                CurveIntersection::Overlap { a, b } => {
                    json!({"kind": "overlap", "a": [a.0, a.1], "b": [b.0, b.1]})
                }
            })
            .collect();
        format!("{:#}\n", json!(j))
    } else {
        let mut s = String::new();
        for h in &hits {
            match h {
                CurveIntersection::Point { t_a, t_b, point } => {
                    let p: Vec<String> = point.iter().map(f64::to_string).collect();
                    let tb = if t_b.is_nan() {
                        String::new()
                    } else {
                        t_b.to_string()
                    };
                    s.push_str(&format!("point,{t_a},{tb},{}\n", p.join(",")));
                }
                CurveIntersection::Overlap { a, b } => {
                    s.push_str(&format!("overlap,{},{},{},{}\n", a.0, a.1, b.0, b.1));
                }
            }
        }
        s
    };
    emit(a.output.as_deref(), text.as_bytes(), &inputs, v)
}
