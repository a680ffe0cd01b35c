//! `lekalo info`: what an object is: for a curve its type, degree, knots with multiplicities,
//! domain and boxes; surfaces and pp-forms as in [`crate::cmd::shapes`].

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo_io::{Object, Shape};
use rayon::prelude::*;
use serde_json::{json, Value};

use crate::cmd::eval::finish_batch;
use crate::cmd::shapes;
use crate::io::{emit, load, not_a_curve, progress, Loaded};
use crate::Verbosity;

/// Arguments of `lekalo info`.
#[derive(Args, Debug)]
#[command(after_help = "\
The control-point box encloses the curve (convex hull property); the sampled box is the box
of --samples points on the curve, a close inner estimate.

Examples:
  lekalo info curve.json
  lekalo info curve.json --json
  lekalo info surface.json          # degrees, knots u and v, net, domain, boxes
  lekalo info spline.pp.json        # order, breakpoints, continuity at each breakpoint
  lekalo info many.jsonl            # one JSON line per object, in parallel")]
pub(crate) struct InfoArgs {
    /// Object file (JSON; JSON Lines for batches; `-` for standard input).
    input: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Number of samples for the sampled bounding box.
    #[arg(long, default_value_t = 1000)]
    samples: usize,
    /// Treat the input as JSON Lines.
    #[arg(long)]
    jsonl: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

/// The facts about one object, as JSON.
pub(crate) fn info_json(obj: &Object, samples: usize) -> lekalo::Result<Value> {
    let kv = obj.knots();
    let ctrl = obj.control_points();
    let (a, b) = obj.domain();
    let sampled = obj.sample(samples)?;
    let distinct: Vec<Value> = kv
        .distinct()
        .iter()
        .map(|(t, m)| json!({"knot": t, "multiplicity": m}))
        .collect();
    let bbox = |p: &lekalo::Points| {
        p.bounding_box()
            .map_or(Value::Null, |(lo, hi)| json!({"min": lo, "max": hi}))
    };
    Ok(json!({
        "type": obj.type_name(),
        "name": obj.display_name(),
        "dim": obj.dim(),
        "degree": obj.degree(),
        "order": obj.degree() + 1,
        "control_points": ctrl.len(),
        "rational": obj.weights().is_some(),
        "weights": obj.weights(),
        "knots": kv.as_slice(),
        "distinct_knots": distinct,
        "clamped": kv.is_clamped(obj.degree()),
        "domain": [a, b],
        "start": obj.eval(a)?,
        "end": obj.eval(b)?,
        "control_box": bbox(&ctrl),
        "sampled_box": bbox(&sampled),
    }))
}

fn fmt_list(v: &Value) -> String {
    match v {
        Value::Array(a) => {
            let s: Vec<String> = a.iter().map(fmt_list).collect();
            format!("[{}]", s.join(", "))
        }
        Value::Number(n) => n.as_f64().map_or_else(|| n.to_string(), |x| format!("{x}")),
        other => other.to_string(),
    }
}

/// Human-readable text of [`info_json`].
fn info_text(j: &Value) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "type            {} ({})",
        j["name"].as_str().unwrap_or("?"),
        j["type"].as_str().unwrap_or("?")
    );
    let _ = writeln!(s, "dimension       {}", j["dim"]);
    let _ = writeln!(s, "degree          {} (order {})", j["degree"], j["order"]);
    let _ = writeln!(s, "control points  {}", j["control_points"]);
    if j["rational"] == Value::Bool(true) {
        let _ = writeln!(s, "weights         {}", fmt_list(&j["weights"]));
    }
    let _ = writeln!(s, "knots           {}", fmt_list(&j["knots"]));
    let mults: Vec<String> = j["distinct_knots"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|d| format!("{}×{}", fmt_list(&d["knot"]), d["multiplicity"]))
                .collect()
        })
        .unwrap_or_default();
    let _ = writeln!(s, "multiplicities  {}", mults.join("  "));
    let clamped = if j["clamped"] == Value::Bool(true) {
        "clamped: the curve starts and ends at its end control points"
    } else {
        "not clamped"
    };
    let _ = writeln!(s, "domain          {} ({clamped})", fmt_list(&j["domain"]));
    let _ = writeln!(
        s,
        "start, end      {}, {}",
        fmt_list(&j["start"]),
        fmt_list(&j["end"])
    );
    let bx = |b: &Value| format!("{} .. {}", fmt_list(&b["min"]), fmt_list(&b["max"]));
    let _ = writeln!(s, "control box     {}", bx(&j["control_box"]));
    let _ = writeln!(s, "sampled box     {}", bx(&j["sampled_box"]));
    s
}

pub(crate) fn run(a: &InfoArgs, v: Verbosity) -> Result<()> {
    let inputs = vec![a.input.clone()];
    let samples = crate::io::in_range(a.samples, 2, 1_000_000, "--samples")?;
    match load(&a.input, a.jsonl, v)? {
        Loaded::Other(shape) => {
            let j = match &shape {
                Shape::Surface(s) => shapes::surface_info_json(s, samples)?,
                Shape::Pp(p) => shapes::pp_info_json(p, samples)?,
                other => return not_a_curve(&a.input, other),
            };
            let text = if a.json {
                format!("{j:#}\n")
            } else {
                shapes::info_text(&j)
            };
            emit(a.output.as_deref(), text.as_bytes(), &inputs, v)
        }
        Loaded::One(obj) => {
            let j = info_json(&obj, samples)?;
            let text = if a.json {
                format!("{j:#}\n")
            } else {
                info_text(&j)
            };
            emit(a.output.as_deref(), text.as_bytes(), &inputs, v)
        }
        Loaded::Many(items) => {
            let bar = progress(items.len(), v);
            let lines: Vec<(bool, String)> = items
                .into_par_iter()
                .map(|(line, obj)| {
                    let r = obj
                        .map_err(|e| e.to_string())
                        .and_then(|o| info_json(&o, samples).map_err(|e| e.to_string()));
                    bar.inc(1);
                    match r {
                        Ok(mut j) => {
                            j["line"] = json!(line);
                            (true, j.to_string())
                        }
                        Err(e) => (false, json!({"line": line, "error": e}).to_string()),
                    }
                })
                .collect();
            bar.finish_and_clear();
            finish_batch(lines, a.output.as_deref(), &inputs, v)
        }
    }
}
