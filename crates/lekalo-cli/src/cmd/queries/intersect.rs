//! `lekalo intersect`: curve–curve intersections (planar and in space), self-intersections,
//! curve–plane; every answer with the kind of contact the library names.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo::query::{Contact, CurveIntersection, PlaneIntersection};
use serde_json::{json, Map, Value};

use crate::cmd::measure::query_curve;
use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::items::load_one;
use crate::output::emit;
use crate::values::numbers;

/// Arguments of `lekalo intersect`.
#[derive(Args, Debug)]
#[command(after_help = "\
Two curves (planar, or both in space): every crossing, tangent contact, contact at an end point
and near miss within the tolerance (parameters on both curves and the point), and every overlap
(an interval on each). One planar curve with --self: its self-intersections. One curve with
--plane: where it meets the plane through a point with a normal (any dimension), overlaps where
it lies in the plane. Each answer names its kind: crossing, tangent (with its order of
contact), end, near-miss (with its gap) or overlap.

Output CSV rows: KIND,t_a,t_b,x,y  or  overlap,a0,a1,b0,b1  (--plane: KIND,t,,x,y,z  or
overlap,t0,t1). --json adds order (tangent) and gap (near-miss).

Examples:
  lekalo intersect a.json b.json
  lekalo intersect a.json b.json --tolerance 1e-9 --json
  lekalo intersect loop.json --self
  lekalo intersect space.json --plane 0,0,1,0,0,1")]
pub(crate) struct IntersectArgs {
    /// First curve.
    first: PathBuf,
    /// Second curve, of the first one's dimension (omit with --self or --plane).
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

pub(crate) fn run(a: &IntersectArgs, cx: &Context) -> Result<()> {
    let qa = query_curve(&load_one(cx, &a.first)?, &a.first)?;
    let bad = |e: lekalo::Error| BadInput(format!("{}: {e}", a.first.display()));
    let mut inputs = vec![a.first.clone()];
    let hits: Vec<Value> = if let Some(plane) = &a.plane {
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
            .iter()
            .map(plane_json)
            .collect()
    } else if a.self_ {
        qa.self_intersections(a.tolerance)
            .map_err(bad)?
            .iter()
            .map(curves_json)
            .collect()
    } else {
        let Some(second) = &a.second else {
            return bad_input("give a second curve, --self or --plane");
        };
        inputs.push(second.clone());
        let qb = query_curve(&load_one(cx, second)?, second)?;
        qa.intersect(&qb, a.tolerance)
            .map_err(bad)?
            .iter()
            .map(curves_json)
            .collect()
    };
    let text = if a.json {
        format!("{:#}\n", json!(hits))
    } else {
        hits.iter().map(csv_row).collect()
    };
    emit(a.output.as_deref(), text.as_bytes(), &inputs, cx)
}

/// The JSON object of a point answer: its kind, the given parameter fields and the point, then
/// the order of a tangent contact or the gap of a near miss.
fn point_json(contact: Contact, params: &[(&str, f64)], point: &[f64]) -> Value {
    let mut m = Map::new();
    m.insert("kind".into(), json!(contact.name()));
    for (k, t) in params {
        m.insert((*k).into(), json!(t));
    }
    m.insert("point".into(), json!(point));
    if let Some(order) = contact.order() {
        m.insert("order".into(), json!(order));
    }
    if let Contact::NearMiss { gap } = contact {
        m.insert("gap".into(), json!(gap));
    }
    Value::Object(m)
}

fn curves_json(h: &CurveIntersection) -> Value {
    match h {
        CurveIntersection::Point {
            t_a,
            t_b,
            point,
            contact,
        } => point_json(*contact, &[("t_a", *t_a), ("t_b", *t_b)], point),
        CurveIntersection::Overlap { a, b } => {
            json!({"kind": h.contact().name(), "a": [a.0, a.1], "b": [b.0, b.1]})
        }
    }
}

fn plane_json(h: &PlaneIntersection) -> Value {
    match h {
        PlaneIntersection::Point { t, point, contact } => point_json(*contact, &[("t", *t)], point),
        PlaneIntersection::Overlap { t } => json!({"kind": h.contact().name(), "t": [t.0, t.1]}),
    }
}

/// The CSV row of an answer's JSON object: the kind, then `t_a,t_b` (a plane: `t,`) and the
/// point, or an overlap's interval ends.
fn csv_row(h: &Value) -> String {
    let num = |v: &Value| v.as_f64().map(|x| x.to_string()).unwrap_or_default();
    let mut cells = vec![h["kind"].as_str().unwrap_or_default().to_string()];
    if let Some(point) = h["point"].as_array() {
        if h.get("t").is_some() {
            cells.extend([num(&h["t"]), String::new()]);
        } else {
            cells.extend([num(&h["t_a"]), num(&h["t_b"])]);
        }
        cells.extend(point.iter().map(num));
    } else {
        for key in ["a", "b", "t"] {
            if let Some(ends) = h[key].as_array() {
                cells.extend(ends.iter().map(num));
            }
        }
    }
    cells.join(",") + "\n"
}
