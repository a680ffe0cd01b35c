//! `lekalo measure`: length, parameters at lengths, exact bounding box, curvature extrema and
//! (planar curves) inflections of a curve (the library's `QueryCurve`); the exact bounding box of
//! a surface (`QuerySurface`).

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use lekalo::QueryCurve;
use lekalo_io::Object;
use serde_json::json;

use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::items::load_one;
use crate::output::emit;
use crate::values::numbers;
use crate::words::in_file;

/// Arguments of `lekalo measure`.
#[derive(Args, Debug)]
#[command(after_help = "\
Prints the length (with its error estimate), the exact bounding box of the curve (not of its
control points), its curvature extrema, for a planar curve its inflections (where the signed
curvature changes sign; none is missed), and, for --at-length or --lengths, the parameter at
each length from the start. For a surface: its domain and exact bounding box (of the surface,
each side within 1e-12 of its size of the true extreme).

Examples:
  lekalo measure curve.json
  lekalo measure curve.json --at-length 1,2.5 --json
  lekalo measure curve.json --lengths lengths.txt -o params.csv
  lekalo measure surface.json --json")]
pub(crate) struct MeasureArgs {
    /// Curve or surface file (JSON; `-` for standard input).
    input: PathBuf,
    /// Lengths from the start whose parameters are wanted, comma-separated.
    #[arg(long, allow_hyphen_values = true)]
    at_length: Option<String>,
    /// File of lengths (numbers separated by commas, spaces or newlines): a batch.
    #[arg(long, value_name = "FILE")]
    lengths: Option<PathBuf>,
    /// Relative tolerance of the arc length (a ratio to the length; `--tolerance` is the old
    /// spelling, hidden and deprecated: elsewhere it is an absolute distance).
    #[arg(long, alias = "tolerance", default_value_t = 1e-12)]
    rtol: f64,
    /// Output JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

/// The curve of an object, prepared for queries ([`lekalo::Curve::to_query`]).
pub(crate) fn query_curve(obj: &Object, path: &Path) -> Result<QueryCurve> {
    obj.to_query()
        .map_err(|e| BadInput(format!("{}: {e}", path.display())).into())
}

/// The surface of a shape file, prepared for queries ([`lekalo::Surface::to_query`]).
pub(crate) fn query_surface(s: &lekalo_io::Surface, path: &Path) -> Result<lekalo::QuerySurface> {
    s.to_query()
        .map_err(|e| BadInput(format!("{}: {e}", path.display())).into())
}

/// Reads a file of numbers (commas, spaces, newlines).
pub(crate) fn number_file(path: &Path) -> Result<Vec<f64>> {
    let (text, name) = lekalo_io::read_input(path)?;
    Ok(lekalo_io::parse_number_list(&text, &name)?)
}

pub(crate) fn run(a: &MeasureArgs, cx: &Context) -> Result<()> {
    let (text, name) = lekalo_io::read_input(&a.input)?;
    if let Ok(lekalo_io::Shape::Surface(s)) = lekalo_io::Shape::from_json_str(&text, &name) {
        return run_surface(a, &s, cx);
    }
    let obj = load_one(cx, &a.input)?;
    let q = query_curve(&obj, &a.input)?;
    // kept in the chain: an error about the tolerance names --rtol
    let bad = |e: lekalo::Error| in_file(&a.input, e);
    let table = q.arc_length(a.rtol).map_err(bad)?;
    let mut lengths = Vec::new();
    if let Some(s) = &a.at_length {
        lengths.extend(numbers(s, "--at-length")?);
    }
    if let Some(f) = &a.lengths {
        lengths.extend(number_file(f)?);
    }
    let params = table.param_at_batch(&lengths).map_err(bad)?;
    let (lo, hi) = q.bounding_box();
    let ext = q.curvature_extrema().map_err(bad)?;
    // inflections: planar curves only (where the signed curvature C' × C'' changes sign)
    let inflections = if q.dim() == 2 {
        Some(q.inflections().map_err(bad)?)
    } else {
        None
    };
    let text = if a.json {
        let mut j = json!({
            "length": table.total(),
            "error_estimate": table.error_estimate(),
            "domain": [q.domain().0, q.domain().1],
            "bounding_box": {"min": lo, "max": hi},
            "curvature_extrema": ext.iter().map(|e| json!({
                "t": e.t, "curvature": e.curvature,
                "kind": if e.maximum { "max" } else { "min" }})).collect::<Vec<_>>(),
            "at_length": lengths.iter().zip(&params)
                .map(|(l, t)| json!({"length": l, "t": t})).collect::<Vec<_>>(),
        });
        if let Some(t) = &inflections {
            j["inflections"] = json!(t);
        }
        format!("{j:#}\n")
    } else {
        let mut s = format!(
            "length {} (error estimate {:.1e})\ndomain [{}, {}]\nbounding box min {:?} max {:?}\n",
            table.total(),
            table.error_estimate(),
            q.domain().0,
            q.domain().1,
            lo,
            hi
        );
        for e in &ext {
            s.push_str(&format!(
                "curvature {} {} at t = {}\n",
                if e.maximum { "max" } else { "min" },
                e.curvature,
                e.t
            ));
        }
        if let Some(t) = &inflections {
            let list: Vec<String> = t.iter().map(|x| lekalo_io::fmt_number(*x)).collect();
            s.push_str(&if list.is_empty() {
                "inflections none\n".to_string()
            } else {
                format!("inflections at t = {}\n", list.join(", "))
            });
        }
        if !lengths.is_empty() {
            s.push_str("length,t\n");
            for (l, t) in lengths.iter().zip(&params) {
                s.push_str(&format!("{l},{t}\n"));
            }
        }
        s
    };
    if lengths.is_empty() && a.lengths.is_some() {
        return bad_input("--lengths: the file holds no numbers");
    }
    emit(
        a.output.as_deref(),
        text.as_bytes(),
        std::slice::from_ref(&a.input),
        cx,
    )
}

/// `measure` of a surface: its domain and exact bounding box.
fn run_surface(a: &MeasureArgs, s: &lekalo_io::Surface, cx: &Context) -> Result<()> {
    if a.at_length.is_some() || a.lengths.is_some() {
        return bad_input("--at-length and --lengths measure curves; the input is a surface");
    }
    let q = query_surface(s, &a.input)?;
    let (lo, hi) = q.bounding_box();
    let (u, w) = q.domain();
    let text = if a.json {
        let j = json!({
            "domain": {"u": [u.0, u.1], "v": [w.0, w.1]},
            "bounding_box": {"min": lo, "max": hi, "tolerance": lekalo::SURFACE_BOX_RTOL * q.scale()},
        });
        format!("{j:#}\n")
    } else {
        format!(
            "domain u [{}, {}] v [{}, {}]\nbounding box min {lo:?} max {hi:?}\n",
            u.0, u.1, w.0, w.1
        )
    };
    emit(
        a.output.as_deref(),
        text.as_bytes(),
        std::slice::from_ref(&a.input),
        cx,
    )
}
