//! `lekalo info`: what an object is: for a curve its type, degree, knots with multiplicities,
//! domain and boxes; surfaces and pp-forms as in [`crate::cmd::shapes`].

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo_io::{Object, Shape};
use serde_json::{json, Value};

use crate::cmd::shapes;
use crate::context::Context;
use crate::exit::bad_input;
use crate::items::{not_a_curve, open, Items};

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
  lekalo info many.jsonl            # one JSON line per object, in parallel
  lekalo info part.step --faces     # faces: surface, loops and their edges, pcurves
  lekalo info part.step --faces --all-skipped   # every skipped face, not the first 20

A JSON Lines file of faces (convert --faces) is listed as --faces lists a STEP file's faces.")]
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
    /// Describe the faces of a STEP file, or the trimmed surfaces of an IGES file (surface,
    /// loops, edges, pcurves) instead of its curves and surfaces.
    #[arg(long)]
    faces: bool,
    /// With --faces: list every face that was not read, each with its reason. By default the
    /// first 20 are listed (by id) and the others counted by reason.
    #[arg(long, requires = "faces")]
    all_skipped: bool,
}

/// Faces not read that `info --faces` lists one by one without `--all-skipped`.
const SKIPPED_FACES_LISTED: usize = 20;

/// Most entries of a knot list shown by `info`; a longer list shows its first and last
/// `LIST_MAX / 2` entries (the `*_total` fields give the full count), so that the report of a
/// curve with millions of knots stays small.
const LIST_MAX: usize = 10_000;

/// Indices of the entries of a list of `n` that `info` shows.
fn shown(n: usize) -> impl Iterator<Item = usize> {
    let half = LIST_MAX / 2;
    if n <= LIST_MAX {
        (0..n).chain(0..0)
    } else {
        (0..half).chain(n - half..n)
    }
}

/// The facts about one object, as JSON.
pub(crate) fn info_json(obj: &Object, samples: usize) -> lekalo::Result<Value> {
    let kv = obj.knots();
    let ctrl = obj.control_points();
    let (a, b) = obj.domain();
    let sampled = obj.sample(samples)?;
    let all_distinct = kv.distinct();
    let distinct: Vec<Value> = shown(all_distinct.len())
        .map(|i| json!({"knot": all_distinct[i].0, "multiplicity": all_distinct[i].1}))
        .collect();
    let knots: Vec<f64> = shown(kv.len()).map(|i| kv.as_slice()[i]).collect();
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
        "knots": knots,
        "knots_total": kv.len(),
        "distinct_knots": distinct,
        "distinct_knots_total": all_distinct.len(),
        "clamped": kv.is_clamped(obj.degree()),
        "domain": [a, b],
        "start": obj.eval(a)?,
        "end": obj.eval(b)?,
        "control_box": bbox(&ctrl),
        "sampled_box": bbox(&sampled),
    }))
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
        let _ = writeln!(s, "weights         {}", shapes::fmt(&j["weights"]));
    }
    let more = |list: &str, total: &str| {
        let (n, total) = (j[list].as_array().map_or(0, Vec::len), &j[total]);
        if total.as_u64().is_some_and(|t| t > n as u64) {
            format!(" (the first and last {} of {total})", n / 2)
        } else {
            String::new()
        }
    };
    let _ = writeln!(
        s,
        "knots           {}{}",
        shapes::fmt(&j["knots"]),
        more("knots", "knots_total")
    );
    let mults: Vec<String> = j["distinct_knots"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|d| format!("{}×{}", shapes::fmt(&d["knot"]), d["multiplicity"]))
                .collect()
        })
        .unwrap_or_default();
    let _ = writeln!(
        s,
        "multiplicities  {}{}",
        mults.join("  "),
        more("distinct_knots", "distinct_knots_total")
    );
    let clamped = if j["clamped"] == Value::Bool(true) {
        "clamped: the curve starts and ends at its end control points"
    } else {
        "not clamped"
    };
    let _ = writeln!(
        s,
        "domain          {} ({clamped})",
        shapes::fmt(&j["domain"])
    );
    let _ = writeln!(
        s,
        "start, end      {}, {}",
        shapes::fmt(&j["start"]),
        shapes::fmt(&j["end"])
    );
    let bx = |b: &Value| format!("{} .. {}", shapes::fmt(&b["min"]), shapes::fmt(&b["max"]));
    let _ = writeln!(s, "control box     {}", bx(&j["control_box"]));
    let _ = writeln!(s, "sampled box     {}", bx(&j["sampled_box"]));
    s
}

/// `e`, an object file's read error, with a hint when the file holds points instead (a
/// reader's first `lekalo info pts.txt`): which commands make an object of them.
fn points_file_hint(path: &std::path::Path, e: anyhow::Error) -> anyhow::Error {
    let points = lekalo_io::read_input(path)
        .ok()
        .and_then(|(text, name)| lekalo_io::read_points(&text, &name).ok());
    match points {
        Some(p) => {
            let f = path.display();
            e.context(format!(
                "{f} holds points ({} of dimension {}), not a curve or surface object: `lekalo \
                 interpolate {f} -o curve.json` or `lekalo make bspline --control {f} --degree 2 \
                 -o curve.json` makes one",
                p.len(),
                p.dim()
            ))
        }
        None => e,
    }
}

pub(crate) fn run(a: &InfoArgs, cx: &Context) -> Result<()> {
    let inputs = vec![a.input.clone()];
    // standard input is read once here: faces, or the text for the readers below
    let (face_lines, stdin) = crate::cmd::files::cad::face_input(&a.input)?;
    if a.faces || face_lines.is_some() {
        let iges = crate::items::is_iges(&a.input)
            || stdin
                .as_ref()
                .is_some_and(|(text, _)| crate::items::is_iges_text(text));
        let r = match face_lines {
            Some(faces) => lekalo_io::StepRead {
                shapes: Vec::new(),
                skipped: lekalo_io::Skips::default(),
                faces,
                triangulations: Vec::new(),
                skipped_faces: lekalo_io::Skips::default(),
                schema: None,
                length_unit: "millimetre".into(),
                scale_to_mm: 1.0,
            },
            None => crate::cmd::files::cad::read_faces_of(&a.input, stdin, a.all_skipped, cx)?,
        };
        return crate::report::print_report(
            a.json,
            &faces_json(&r, a.all_skipped),
            |j| faces_text(j, if iges { "D" } else { "#" }),
            a.output.as_deref(),
            &inputs,
            cx,
        );
    }
    let samples = cx.in_range(a.samples, 2, 1_000_000, "--samples")?;
    let cad_text = stdin
        .as_ref()
        .filter(|(text, _)| crate::items::is_step_text(text) || crate::items::is_iges_text(text));
    let loaded = if crate::items::is_step(&a.input)
        || crate::items::is_iges(&a.input)
        || cad_text.is_some()
    {
        // a CAD file: one shape is described as any object; several (curves and surfaces
        // mixed) as JSON Lines, one per shape in the file's order
        let mut shapes = match cad_text {
            Some((text, name)) => crate::cmd::files::cad::shapes_of_text(cx, &a.input, text, name)?,
            None => crate::cmd::files::cad::load_shapes(&a.input, cx)?,
        };
        match shapes.len() {
            0 => {
                return bad_input(format!(
                    "{}: no curve or surface lekalo reads",
                    a.input.display()
                ))
            }
            1 => match shapes.remove(0) {
                Shape::Curve(o) => Items::One(o),
                other => Items::Other(other),
            },
            _ => return cad_info(a, cx, &shapes, samples, &inputs),
        }
    } else if let Some((text, name)) = stdin {
        let now = std::time::Instant::now();
        crate::items::open_text(cx, &a.input, a.jsonl, &text, &name, now)?
    } else {
        open(cx, &a.input, a.jsonl).map_err(|e| points_file_hint(&a.input, e))?
    };
    match loaded {
        Items::Other(Shape::Tensor(t)) => crate::report::print_report(
            a.json,
            &crate::cmd::tensor::info_json(&t),
            crate::cmd::tensor::info_text,
            a.output.as_deref(),
            &inputs,
            cx,
        ),
        Items::Other(shape) => {
            let j = match &shape {
                Shape::Surface(s) => shapes::surface_info_json(s, samples)?,
                Shape::Pp(p) => shapes::pp_info_json(p, samples)?,
                other => return not_a_curve(&a.input, other),
            };
            crate::report::print_report(
                a.json,
                &j,
                shapes::info_text,
                a.output.as_deref(),
                &inputs,
                cx,
            )
        }
        Items::One(obj) => {
            cx.check_bezier_degree(&obj, "sampling")?;
            let j = info_json(&obj, samples)?;
            crate::report::print_report(a.json, &j, info_text, a.output.as_deref(), &inputs, cx)
        }
        Items::Lines(items) => {
            crate::batch::lines::run(cx, items, a.output.as_deref(), &inputs, |line, o| {
                cx.check_bezier_degree(&o, "sampling")
                    .map_err(|e| format!("{}:{line}: {e}", a.input.display()))?;
                let mut j = info_json(&o, samples).map_err(|e| e.to_string())?;
                j["line"] = json!(line);
                Ok(j)
            })
        }
        Items::Parquet(input) => crate::items::not_a_batch_command(&input),
    }
}

/// `info` of a CAD file of several shapes: one JSON line each (`"line"`: its place among the
/// shapes read), curves as [`info_json`], surfaces as the surface summary; a shape that cannot
/// be described is a line with its error (exit code 2 after the others are written).
fn cad_info(
    a: &InfoArgs,
    cx: &Context,
    shapes: &[Shape],
    samples: usize,
    inputs: &[PathBuf],
) -> Result<()> {
    let lines = shapes
        .iter()
        .enumerate()
        .map(|(i, shape)| {
            let j: Result<Value> = match shape {
                Shape::Curve(o) => cx
                    .check_bezier_degree(o, "sampling")
                    .and_then(|()| Ok(info_json(o, samples)?)),
                Shape::Surface(s) => shapes::surface_info_json(s, samples).map_err(Into::into),
                other => Err(anyhow::anyhow!(
                    "\"{}\" is not read from CAD files",
                    other.type_name()
                )),
            };
            match j {
                Ok(mut j) => {
                    j["line"] = json!(i + 1);
                    (true, j.to_string())
                }
                Err(e) => (
                    false,
                    json!({"line": i + 1, "error": e.to_string()}).to_string(),
                ),
            }
        })
        .collect();
    crate::batch::lines::finish(cx, lines, a.output.as_deref(), inputs)
}

/// `info --faces`: the number of faces read and skipped, and each face's id, name, surface,
/// loops (edge counts and `EDGE_CURVE` ids, outer first) and whether its edges have pcurves;
/// each face of triangles (AP242 tessellated faces) with its entity, name, linked surface and
/// counts of points, triangles and normals;
/// the faces not read, the first [`SKIPPED_FACES_LISTED`] by id (every one the read kept with
/// `all`), and their count by type and reason (`skipped_kinds`).
fn faces_json(r: &lekalo_io::StepRead, all: bool) -> Value {
    let faces: Vec<Value> = r
        .faces
        .iter()
        .map(|f| {
            let loops: Vec<Value> = f
                .face
                .loops()
                .zip(&f.edge_ids)
                .enumerate()
                .map(|(i, (lp, ids))| {
                    json!({"outer": i == 0, "edges": lp.edges().len(), "edge_ids": ids})
                })
                .collect();
            json!({
                "id": f.id,
                "name": f.name,
                "surface": f.face.surface().type_name(),
                "surface_id": f.surface_id,
                "same_sense": f.face.same_sense(),
                "loops": loops,
                "pcurves": f.pcurves.as_ref().map_or(json!(true), |why| json!(why)),
            })
        })
        .collect();
    let tessellated: Vec<Value> = r
        .triangulations
        .iter()
        .map(|t| {
            json!({
                "id": t.id,
                "entity": t.entity,
                "name": t.name,
                "link": t.link,
                "vertices": t.vertices.len(),
                "triangles": t.triangles.len(),
                "normals": t.normals.len(),
            })
        })
        .collect();
    let listed = if all {
        usize::MAX
    } else {
        SKIPPED_FACES_LISTED
    };
    let skipped: Vec<Value> = r
        .skipped_faces
        .iter()
        .take(listed)
        .map(|s| json!({"id": s.id, "entity": s.entity, "reason": s.reason}))
        .collect();
    let kinds: Vec<Value> = r
        .skipped_faces
        .kinds()
        .iter()
        .map(|k| json!({"entity": k.entity, "reason": k.reason, "count": k.count, "first_id": k.first_id}))
        .collect();
    json!({
        "faces_total": r.faces.len(),
        "with_pcurves": r.faces.iter().filter(|f| f.pcurves.is_none()).count(),
        "tessellated_total": r.triangulations.len(),
        "tessellated_triangles": r.triangulations.iter().map(|t| t.triangles.len()).sum::<usize>(),
        "skipped_total": r.skipped_faces.len(),
        "faces": faces,
        "tessellated": tessellated,
        "skipped": skipped,
        "skipped_kinds": kinds,
    })
}

/// The text of [`faces_json`]: a summary line, then one line per face and per skipped face
/// listed, and when not every skipped face is listed their count by reason; ids after `prefix`
/// (`#` for STEP instances, `D` for IGES directory entries).
fn faces_text(j: &Value, prefix: &str) -> String {
    let mut s = String::new();
    // faces of triangles (AP242) are named only when the file has some
    let tessellated = match j["tessellated_total"].as_u64() {
        Some(n) if n > 0 => format!(
            ", {n} tessellated ({} triangles)",
            j["tessellated_triangles"]
        ),
        _ => String::new(),
    };
    let _ = writeln!(
        s,
        "faces           {} ({} with pcurves){tessellated}, {} skipped",
        j["faces_total"], j["with_pcurves"], j["skipped_total"]
    );
    for f in j["faces"].as_array().into_iter().flatten() {
        let loops: Vec<String> = f["loops"]
            .as_array()
            .into_iter()
            .flatten()
            .map(|l| {
                let kind = if l["outer"] == Value::Bool(true) {
                    "outer"
                } else {
                    "inner"
                };
                format!("{kind} {}", l["edges"])
            })
            .collect();
        let pcurves = match &f["pcurves"] {
            Value::Bool(true) => "pcurves".to_string(),
            other => format!("no pcurves: {}", other.as_str().unwrap_or_default()),
        };
        let _ = writeln!(
            s,
            "{prefix}{} {}  {} {prefix}{}  edges: {}  {pcurves}",
            f["id"],
            f["name"],
            f["surface"].as_str().unwrap_or_default(),
            f["surface_id"],
            loops.join(", "),
        );
    }
    for t in j["tessellated"].as_array().into_iter().flatten() {
        let link = t["link"]
            .as_u64()
            .map(|l| format!("  on {prefix}{l}"))
            .unwrap_or_default();
        let _ = writeln!(
            s,
            "{prefix}{} {}  {}  {} points, {} triangles, {} normals{link}",
            t["id"],
            t["name"],
            t["entity"].as_str().unwrap_or_default(),
            t["vertices"],
            t["triangles"],
            t["normals"],
        );
    }
    for k in j["skipped"].as_array().into_iter().flatten() {
        let _ = writeln!(
            s,
            "skipped {prefix}{} {}: {}",
            k["id"],
            k["entity"].as_str().unwrap_or_default(),
            k["reason"].as_str().unwrap_or_default()
        );
    }
    let listed = j["skipped"].as_array().map_or(0, Vec::len);
    let total = j["skipped_total"].as_u64().unwrap_or(0);
    if (listed as u64) < total {
        let _ = writeln!(
            s,
            "skipped faces by reason ({} listed of {total}; --all-skipped lists every one):",
            listed
        );
        for k in j["skipped_kinds"].as_array().into_iter().flatten() {
            let _ = writeln!(
                s,
                "  {:>6} {}: {} (first {prefix}{})",
                k["count"].as_u64().unwrap_or(0),
                k["entity"].as_str().unwrap_or_default(),
                k["reason"].as_str().unwrap_or_default(),
                k["first_id"]
            );
        }
    }
    s
}
