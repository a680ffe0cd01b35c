//! `lekalo intersect`: curve–curve intersections (planar and in space), self-intersections,
//! curve–plane, curve–surface; surface–surface intersections and plane sections of surfaces (branches written
//! as JSON Lines or STEP); every answer with the kind of contact the library names.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo::query::IntersectionBranch;
use lekalo_io::{Shape, StepWriter};
use serde_json::{json, Map, Value};

use crate::cmd::measure::{query_curve, query_surface};
use crate::context::Context;
use crate::exit::bad_input;
use crate::items::{load_one, open, Items};
use crate::output::{emit, format_of, report};
use crate::values::numbers;
use crate::words::in_file;

/// Arguments of `lekalo intersect`.
#[derive(Args, Debug)]
#[command(after_help = "\
Two curves (planar, or both in space): every crossing, tangent contact, contact at an end point
and near miss within the tolerance (parameters on both curves and the point), and every overlap
(an interval on each). One planar curve with --self: its self-intersections. One curve with
--plane: where it meets the plane through a point with a normal (any dimension), overlaps where
it lies in the plane. A curve and a 3-D surface (the curve first): where the curve meets the
surface, overlaps where it lies on it. Each answer names its kind: crossing, tangent (with its
order of contact), end, near-miss (with its gap) or overlap.

Output CSV rows: KIND,t_a,t_b,x,y  or  overlap,a0,a1,b0,b1  (--plane: KIND,t,,x,y,z  or
overlap,t0,t1; a surface: KIND,t,u,v,x,y,z  or  overlap,t0,t1). --json adds order (tangent)
and gap (near-miss), and for a surface uv (overlap: uv at both ends).

Two surfaces (3-D B-spline, Bezier or NURBS), or one surface with --plane: the branches of the
intersection, traced by marching from starting points found by subdivision (none is missed,
small closed loops included), each a crossing (a curve), a tangent contact (a point or a line
where the normals are parallel) or an overlap (where the surfaces coincide). Every point is
within the tolerance (default 1e-6 for surfaces) of both surfaces. Standard output gets a
summary (one line a branch: index, kind, closed or open, point count, length; --json for the
same as JSON); -o writes the branches: FILE.jsonl and FILE.step the fitted curves in space (one
curve a line, read by every command), FILE.json every branch in full (points, (u, v) on each
surface, the fitted curve in space and in each parameter plane).

Examples:
  lekalo intersect a.json b.json
  lekalo intersect a.json b.json --tolerance 1e-9 --json
  lekalo intersect loop.json --self
  lekalo intersect space.json --plane 0,0,1,0,0,1
  lekalo intersect space.json surface.json
  lekalo intersect surface.json level.json -o branches.jsonl
  lekalo intersect surface.json level.json -o branches.json
  lekalo intersect surface.json --plane 0,0,0.1,0,0,1 --json -o section.step")]
pub(crate) struct IntersectArgs {
    /// First curve.
    first: PathBuf,
    /// Second curve, of the first one's dimension, or a surface (omit with --self or --plane).
    second: Option<PathBuf>,
    /// Self-intersections of the first curve.
    #[arg(long = "self")]
    self_: bool,
    /// Plane as origin then normal, comma-separated (2·dim numbers).
    #[arg(long, allow_hyphen_values = true)]
    plane: Option<String>,
    /// Distance under which points count as common (in the objects' units; default 1e-9 for
    /// curves, 1e-6 for surfaces).
    #[arg(long)]
    tolerance: Option<f64>,
    /// Output JSON instead of CSV.
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn run(a: &IntersectArgs, cx: &Context) -> Result<()> {
    let first = match open(cx, &a.first, false)? {
        Items::Other(Shape::Surface(s)) => return run_surfaces(a, &s, cx),
        Items::One(o) => o,
        // the refusals (several objects, not a curve) are load_one's
        _ => load_one(cx, &a.first)?,
    };
    let tolerance = a.tolerance.unwrap_or(1e-9);
    let qa = query_curve(&first, &a.first)?;
    // kept in the chain: an error about the tolerance names --tolerance
    let bad = |e: lekalo::Error| in_file(&a.first, e);
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
            .map(lekalo_io::plane_intersection_json)
            .collect()
    } else if a.self_ {
        qa.self_intersections(tolerance)
            .map_err(bad)?
            .iter()
            .map(lekalo_io::curve_intersection_json)
            .collect()
    } else {
        let Some(second) = &a.second else {
            return bad_input("give a second curve, --self or --plane");
        };
        inputs.push(second.clone());
        match open(cx, second, false)? {
            Items::Other(Shape::Surface(s)) => {
                let qs = query_surface(&s, second)?;
                qa.intersect_surface(&qs, tolerance)
                    .map_err(|e| {
                        anyhow::Error::from(e).context(format!(
                            "{} and {}",
                            a.first.display(),
                            second.display()
                        ))
                    })?
                    .iter()
                    .map(lekalo_io::surface_intersection_json)
                    .collect()
            }
            other => {
                let b = match other {
                    Items::One(o) => o,
                    // the refusals (several objects, not a curve) are load_one's
                    _ => load_one(cx, second)?,
                };
                let qb = query_curve(&b, second)?;
                qa.intersect(&qb, tolerance)
                    .map_err(bad)?
                    .iter()
                    .map(lekalo_io::curve_intersection_json)
                    .collect()
            }
        }
    };
    let text = if a.json {
        format!("{:#}\n", json!(hits))
    } else {
        if hits.is_empty() && !cx.is_quiet() {
            report("note: no intersection within the tolerance");
        }
        hits.iter().map(csv_row).collect()
    };
    emit(a.output.as_deref(), text.as_bytes(), &inputs, cx)
}

/// The CSV row of an answer's JSON object: the kind, then `t_a,t_b` (a plane: `t,`; a surface:
/// `t,u,v`) and the point, or an overlap's interval ends.
fn csv_row(h: &Value) -> String {
    let num = |v: &Value| v.as_f64().map(lekalo_io::fmt_number).unwrap_or_default();
    let mut cells = vec![h["kind"].as_str().unwrap_or_default().to_string()];
    if let Some(point) = h["point"].as_array() {
        if let Some(uv) = h["uv"].as_array() {
            cells.push(num(&h["t"]));
            cells.extend(uv.iter().map(num));
        } else if h.get("t").is_some() {
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

/// `lekalo intersect` of a surface with a second surface or with `--plane`.
fn run_surfaces(a: &IntersectArgs, s: &lekalo_io::Surface, cx: &Context) -> Result<()> {
    let tolerance = a.tolerance.unwrap_or(1e-6);
    let qa = query_surface(s, &a.first)?;
    let mut inputs = vec![a.first.clone()];
    let branches = if let Some(plane) = &a.plane {
        let nums = numbers(plane, "--plane")?;
        if nums.len() != 6 {
            return bad_input(format!(
                "--plane: give 6 numbers (origin x,y,z then normal x,y,z), got {}",
                nums.len()
            ));
        }
        qa.intersect_plane(&nums[..3], &nums[3..], tolerance)
            .map_err(|e| in_file(&a.first, e))?
    } else if a.self_ {
        return bad_input("--self takes a planar curve; give a second surface or --plane");
    } else {
        let Some(second) = &a.second else {
            return bad_input("give a second surface or --plane");
        };
        inputs.push(second.clone());
        let Items::Other(Shape::Surface(t)) = open(cx, second, false)? else {
            return bad_input(format!(
                "{}: a surface intersects a surface (or a plane with --plane); this is not a surface (a curve and a surface: give the curve first)",
                second.display()
            ));
        };
        let qb = query_surface(&t, second)?;
        qa.intersect_surface(&qb, tolerance).map_err(|e| {
            anyhow::Error::from(e).context(format!(
                "{} and {}",
                a.first.display(),
                second.display()
            ))
        })?
    };
    let summary: Vec<Value> = branches.iter().map(branch_summary).collect();
    let text = if a.json {
        format!("{:#}\n", json!(summary))
    } else {
        summary_text(&summary)
    };
    if let Some(out) = a.output.as_deref() {
        let body = match format_of(None, Some(out), "jsonl").as_str() {
            "jsonl" => branches
                .iter()
                .filter_map(|b| b.curve.clone())
                .map(|c| Shape::Curve(lekalo::Curve::BSpline(c)).to_json_line() + "\n")
                .collect(),
            "json" => {
                let all: Vec<Value> = branches.iter().map(branch_json).collect();
                format!("{:#}\n", json!(all))
            }
            "step" => {
                let name = out
                    .file_stem()
                    .map_or("intersection".into(), |n| n.to_string_lossy());
                let mut w = StepWriter::new(&name);
                for c in branches.iter().filter_map(|b| b.curve.clone()) {
                    w.add_object(&lekalo::Curve::BSpline(c))?;
                }
                w.finish("20000101.000000")
            }
            other => {
                return bad_input(format!(
                "-o {}: intersection branches are written as jsonl, json or step, not \"{other}\"",
                out.display()
            ))
            }
        };
        emit(Some(out), body.as_bytes(), &inputs, cx)?;
    }
    emit(None, text.as_bytes(), &inputs, cx)
}

/// The summary of a branch: kind (and order of a tangent contact), closed, points, length.
fn branch_summary(b: &IntersectionBranch) -> Value {
    let mut m = Map::new();
    m.insert("kind".into(), json!(b.kind.name()));
    if let Some(order) = b.kind.order() {
        m.insert("order".into(), json!(order));
    }
    m.insert("closed".into(), json!(b.closed));
    m.insert("point_count".into(), json!(b.points.len()));
    m.insert("length".into(), json!(b.length()));
    Value::Object(m)
}

/// One summary line a branch: `index kind closed|open N points length L`.
fn summary_text(summary: &[Value]) -> String {
    if summary.is_empty() {
        return "no intersection\n".into();
    }
    summary
        .iter()
        .enumerate()
        .map(|(i, b)| {
            format!(
                "{i} {} {} {} points length {}\n",
                b["kind"].as_str().unwrap_or_default(),
                if b["closed"].as_bool() == Some(true) {
                    "closed"
                } else {
                    "open"
                },
                b["point_count"],
                lekalo_io::fmt_number(b["length"].as_f64().unwrap_or_default())
            )
        })
        .collect()
}

/// The full record of a branch: its summary, tolerance, points, parameters on both
/// surfaces and fitted curves (lekalo curve objects).
fn branch_json(b: &IntersectionBranch) -> Value {
    let mut v = branch_summary(b);
    let curve = |c: &Option<lekalo::BSplineCurve>| {
        c.as_ref().map_or(Value::Null, |c| {
            let line = Shape::Curve(lekalo::Curve::BSpline(c.clone())).to_json_line();
            serde_json::from_str(&line).unwrap_or(Value::Null)
        })
    };
    if let Value::Object(m) = &mut v {
        m.insert("tolerance".into(), json!(b.tolerance));
        m.insert("points".into(), json!(b.points));
        m.insert("uv_a".into(), json!(b.uv_a));
        m.insert("uv_b".into(), json!(b.uv_b));
        m.insert("curve".into(), curve(&b.curve));
        m.insert("curve_uv_a".into(), curve(&b.curve_uv_a));
        m.insert("curve_uv_b".into(), curve(&b.curve_uv_b));
    }
    v
}
