//! `lekalo eval`: points, derivatives, curvature and torsion at parameters or on a uniform
//! sampling.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo_io::{sample_table, Object, SampleSpec};
use serde_json::json;

use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::items::{not_a_curve, open, Items};
use crate::output::{emit, emit_stream, format_of, progress};
use crate::values::numbers;

/// Arguments of `lekalo eval`.
#[derive(Args, Debug)]
#[command(after_help = "\
Without --at, the curve is sampled at --samples parameters spread evenly over its domain.
Output columns: t, the point (x, y, z or x1 … xd), derivatives d1x, d1y, … up to
--derivatives, curvature and, for a 3-D curve, torsion. A JSON Lines input (.jsonl, or --jsonl) is evaluated in
parallel and gives one JSON line per object with the fields line, columns and rows (a bad
line gives line and error instead, is reported on stderr, and the exit code is 2).

Examples:
  lekalo eval curve.json --at 1,1.5,2
  lekalo eval curve.json --samples 5 --derivatives 2 --curvature -o samples.csv
  lekalo eval helix.json --samples 50 --curvature --torsion
  lekalo eval curve.json --at 0.5 --format json
  lekalo eval curve.json --samples 3 --json
  lekalo eval curve.json --samples 1000 -o samples.npy   # NumPy: np.load('samples.npy')
  lekalo eval many.jsonl --samples 100 -o samples.jsonl
  lekalo eval surface.json --uv 0.3,0.7 --derivatives 2 --normals --curvature
  lekalo eval surface.json --grid 5x7 -o grid.csv
  lekalo eval tensor.json --at 0.5,0.25,1 --at-file points.csv
  lekalo eval tensor.json --grid 20x20x10 -o field.parquet

Surfaces: evaluated at --uv U,V pairs (repeat the option, or list several pairs), at the rows
of --uv-file, or on an evenly spaced --grid NUxNV (--samples N: N × N; default 5 × 5). Columns:
u, v, the point, the partial derivatives du{a}v{b}x … of every total order up to
--derivatives (du1v0x is ∂x/∂u), with --normals the unit normal nx, ny, nz, with --curvature
the principal curvatures k1 ≥ k2, gaussian and mean (sign: positive where the surface bends
towards the normal (S_u × S_v)/|S_u × S_v|).

Splines in N ≥ 3 parameters (bspline_tensor, nurbs_tensor): evaluated at --at x1,…,xN (several
points in a row), the rows of --at-file (N columns: CSV, .npy or a Parquet table) and on an
evenly spaced --grid AxBxC… (the first direction slowest). Columns: x1 … xN, then y (y1 … yd);
written as CSV, JSON, .npy or Parquet (by --format or the output's extension).")]
pub(crate) struct EvalArgs {
    /// Object file (JSON; JSON Lines for batches; `-` for standard input).
    input: PathBuf,
    /// Parameters, comma-separated (fractions like 5/17 allowed).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "samples")]
    at: Option<String>,
    /// Number of uniformly spaced parameters over the domain (default 11).
    #[arg(long, short = 'n')]
    samples: Option<usize>,
    /// Highest derivative order to output.
    #[arg(long, short = 'd', default_value_t = 0)]
    derivatives: usize,
    /// Output the curvature |C' × C''| / |C'|³.
    #[arg(long)]
    curvature: bool,
    /// Output the torsion (C' × C'')·C''' / |C' × C''|² of a 3-D curve (empty where the
    /// curvature is zero).
    #[arg(long)]
    torsion: bool,
    /// Output format: csv, json or npy (a NumPy float64 array, one row per sample, the CSV's
    /// columns); for splines in N parameters also parquet (one column per CSV column) (default:
    /// from the output's extension, else csv).
    #[arg(long)]
    format: Option<String>,
    /// The same as `--format json`: `{"columns", "rows"}` with full-precision numbers.
    #[arg(long, conflicts_with = "format")]
    json: bool,
    /// Treat the input as JSON Lines.
    #[arg(long)]
    jsonl: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Surfaces: parameter pairs U,V (repeatable; `0.3,0.7,0.5,0.5` is two pairs).
    #[arg(long, value_name = "U,V", allow_hyphen_values = true)]
    uv: Vec<String>,
    /// Surfaces: a file of (u, v) rows, two columns.
    #[arg(long, value_name = "FILE")]
    uv_file: Option<PathBuf>,
    /// Surfaces: an evenly spaced `NUxNV` parameter grid over the domain (e.g. `5x7`); splines
    /// in N parameters: `AxBxC…`, one size a direction.
    #[arg(long, value_name = "NUxNV", conflicts_with_all = ["uv", "uv_file"])]
    grid: Option<String>,
    /// Splines in N ≥ 3 parameters: a file of points, N columns (with or instead of --at
    /// x1,…,xN): CSV, whitespace text, JSON, `.npy` or a Parquet table (one row a point).
    #[arg(long, value_name = "FILE")]
    at_file: Option<PathBuf>,
    /// Surfaces: output the unit normal nx, ny, nz.
    #[arg(long)]
    normals: bool,
}

const DEFAULT_SAMPLES: usize = 11;
/// Highest `--derivatives` (every derivative above the degree is zero).
const MAX_DERIVATIVES: usize = 1000;

/// The parameters of one curve: `--at`, or `--samples` spread evenly over its domain.
fn parameters(cx: &Context, a: &EvalArgs, obj: &Object) -> Result<Vec<f64>> {
    match (&a.at, a.samples) {
        (Some(at), _) => numbers(at, "--at"),
        (None, n) => {
            let n = cx.in_range(n.unwrap_or(DEFAULT_SAMPLES), 1, usize::MAX, "--samples")?;
            check_table(cx, a, obj, n)?;
            Ok(obj.uniform_parameters(n))
        }
    }
}

/// Refuses, before it is made, a table of samples held whole in memory (JSON, NumPy, JSON
/// Lines, Parquet) whose samples × columns are above `--max-size`: 3·10^6 samples with
/// curvature in a Parquet batch ran out of memory. One curve's CSV is written chunk by chunk
/// and only `--samples` itself is limited.
fn check_table(cx: &Context, a: &EvalArgs, obj: &Object, n: usize) -> Result<()> {
    let streamed = !crate::items::is_parquet(&a.input)
        && !crate::items::is_json_lines(&a.input, a.jsonl)
        && !a.json
        && format_of(a.format.as_deref(), a.output.as_deref(), "csv") == "csv";
    if streamed {
        return Ok(());
    }
    let columns = obj
        .dim()
        .saturating_mul(a.derivatives.saturating_add(1))
        .saturating_add(1 + usize::from(a.curvature) + usize::from(a.torsion));
    let values = n.saturating_mul(columns);
    let limit = cx.max_size;
    if values > limit {
        return bad_input(format!(
            "--samples {n}: {n} samples of {columns} columns are {values} values, above the size limit {limit}; take fewer samples or columns, write one curve's samples as CSV (streamed), or raise the limit with --max-size {values} if the machine has the memory"
        ));
    }
    Ok(())
}

/// Refuses a derivative order whose column names alone would not fit in memory.
fn check_derivatives(a: &EvalArgs) -> Result<()> {
    if a.derivatives > MAX_DERIVATIVES {
        return bad_input(format!(
            "--derivatives {} is above {MAX_DERIVATIVES}, the highest order eval writes (every derivative above the curve's degree is zero)",
            a.derivatives
        ));
    }
    Ok(())
}

pub(crate) fn run(a: &EvalArgs, cx: &Context) -> Result<()> {
    let spec = SampleSpec {
        derivatives: a.derivatives,
        curvature: a.curvature,
        torsion: a.torsion,
    };
    let inputs = vec![a.input.clone()];
    check_derivatives(a)?;
    match open(cx, &a.input, a.jsonl)? {
        Items::Parquet(input) => crate::batch::parquet::samples_of_curves(
            cx,
            &input,
            a.output.as_deref(),
            spec,
            &|o: &Object| parameters(cx, a, o),
        ),
        Items::Other(lekalo_io::Shape::Surface(_)) if a.torsion => bad_input(
            "--torsion is for 3-D curves; a surface's principal, Gaussian and mean curvatures come with --curvature",
        ),
        Items::Other(lekalo_io::Shape::Surface(_)) if a.at_file.is_some() => bad_input(
            "--at-file is for splines in 3 or more parameters; a surface takes --uv-file",
        ),
        Items::Other(lekalo_io::Shape::Surface(s)) => crate::cmd::surface_eval::run(
            &crate::cmd::surface_eval::SurfaceEval {
                input: &a.input,
                uv: &a.uv,
                uv_file: a.uv_file.as_deref(),
                grid: a.grid.as_deref(),
                samples: a.samples,
                derivatives: a.derivatives,
                normals: a.normals,
                curvature: a.curvature,
                format: if a.json { Some("json") } else { a.format.as_deref() },
                output: a.output.as_deref(),
            },
            &s,
            cx,
        ),
        Items::Other(lekalo_io::Shape::Tensor(_))
            if a.samples.is_some()
                || a.derivatives > 0
                || a.curvature
                || a.torsion
                || a.normals
                || !a.uv.is_empty()
                || a.uv_file.is_some() =>
        {
            bad_input("a spline in N parameters is evaluated at --at x1,…,xN, --at-file FILE or on --grid AxBxC…; --samples, --derivatives, --curvature, --torsion, --normals, --uv and --uv-file are for curves and surfaces (partial derivatives: the Python TensorBSpline's nu=)")
        }
        Items::Other(lekalo_io::Shape::Tensor(t)) => crate::cmd::tensor::eval(
            &crate::cmd::tensor::TensorEval {
                input: &a.input,
                at: a.at.as_deref(),
                at_file: a.at_file.as_deref(),
                grid: a.grid.as_deref(),
                format: if a.json { Some("json") } else { a.format.as_deref() },
                output: a.output.as_deref(),
            },
            &t,
            cx,
        ),
        Items::Other(s) => not_a_curve(&a.input, &s),
        Items::One(_) | Items::Lines(_)
            if !a.uv.is_empty()
                || a.uv_file.is_some()
                || a.grid.is_some()
                || a.normals
                || a.at_file.is_some() =>
        {
            bad_input("--uv, --uv-file, --grid and --normals are for surfaces, --at-file for splines in 3 or more parameters; a curve takes --at or --samples")
        }
        Items::One(obj) if a.torsion && obj.dim() != 3 => bad_input(format!(
            "{}: --torsion needs a 3-D curve and this one is {}-D (a planar curve's torsion is zero everywhere); drop --torsion",
            a.input.display(),
            obj.dim()
        )),
        Items::One(obj) => {
            let ts = parameters(cx, a, &obj)?;
            let fmt = if a.json {
                "json".to_string()
            } else {
                format_of(a.format.as_deref(), a.output.as_deref(), "csv")
            };
            if fmt == "csv" && ts.len() > CHUNK {
                return eval_csv_streamed(a, &obj, &ts, spec, &inputs, cx);
            }
            let table = sample_table(&obj, &ts, spec)
                .map_err(|e| BadInput(format!("{}: {e}", a.input.display())))?;
            let bytes = match fmt.as_str() {
                "csv" => table.to_csv().into_bytes(),
                "json" => format!("{:#}\n", table.to_json()).into_bytes(),
                "npy" => table.to_npy()?,
                other => return bad_input(format!("--format {other}: use csv, json or npy")),
            };
            emit(a.output.as_deref(), &bytes, &inputs, cx)
        }
        Items::Lines(items) => {
            crate::batch::lines::run(cx, items, a.output.as_deref(), &inputs, |line, o| {
                let ts = parameters(cx, a, &o).map_err(|e| e.to_string())?;
                let t = sample_table(&o, &ts, spec)
                    .map_err(|e| format!("{}:{line}: {e}", a.input.display()))?;
                Ok(json!({"line": line, "columns": t.header, "rows": t.rows}))
            })
        }
    }
}

/// Parameters evaluated at a time by a streamed evaluation.
const CHUNK: usize = 65_536;

/// A long sampling as CSV, evaluated and written chunk by chunk (memory O(chunk), a progress
/// bar on a terminal). Every parameter is checked against the domain first, so that an error
/// never comes after part of the output was written.
fn eval_csv_streamed(
    a: &EvalArgs,
    obj: &Object,
    ts: &[f64],
    spec: SampleSpec,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let (lo, hi) = obj.domain();
    if let Some(t) = ts.iter().find(|t| !(lo..=hi).contains(*t)) {
        // the library's message for it
        sample_table(obj, &[*t], spec)
            .map_err(|e| BadInput(format!("{}: {e}", a.input.display())))?;
    }
    let bar = progress(cx, ts.len());
    let mut failure: Option<lekalo::Error> = None;
    let r = emit_stream(a.output.as_deref(), inputs, cx, |w| {
        for (k, chunk) in ts.chunks(CHUNK).enumerate() {
            let table = match sample_table(obj, chunk, spec) {
                Ok(t) => t,
                Err(e) => {
                    failure = Some(e);
                    return Err(std::io::Error::other("evaluation failed"));
                }
            };
            table.write_csv(w, k == 0)?;
            bar.inc(chunk.len() as u64);
        }
        Ok(())
    });
    bar.finish_and_clear();
    if let Some(e) = failure {
        return Err(BadInput(format!("{}: {e}", a.input.display())).into());
    }
    r
}
