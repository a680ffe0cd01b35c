//! `lekalo convert`: between the formats.

use lekalo_io::CurveJson;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo_io::{curve_figure, sample_table, CurvePlot, Object, SampleSpec, Shape, StepWriter};

use crate::cmd::shapes;
use crate::context::Context;
use crate::exit::bad_input;
use crate::items::{open, Items};
use crate::output::encode;
use crate::output::{emit, format_of};

/// Arguments of `lekalo convert`.
#[derive(Args, Debug)]
#[command(after_help = "\
Formats (chosen by --to or the output's extension):
  json   the versioned lekalo JSON (docs/formats.md)     jsonl  one object per line
  csv    samples t, x, y, … (--samples)                  svg, png  a plot of the curve
  step   ISO 10303-21 AP214 (B_SPLINE_CURVE_WITH_KNOTS, rational form for NURBS); every object
         of a JSON Lines input goes into one file
  obj    Wavefront OBJ polyline of the sampled curve
  npz    NumPy archive: degree, knots, control_points (, weights); np.load reads it
Surfaces (bezier_surface, bspline_surface, nurbs_surface) convert to json, step
(B_SPLINE_SURFACE_WITH_KNOTS, rational for NURBS), obj (a √samples × √samples tessellation
with the surface's normals) and svg/png (wireframe); piecewise polynomials to json, csv
(x, f samples) and svg/png (graph with the breakpoints). Splines in N parameters
(bspline_tensor, nurbs_tensor) convert to json and npz: degrees (N,), knots_0 … knots_{N-1},
control_points (n_1, …, n_N) or (n_1, …, n_N, dim) (, weights (n_1, …, n_N)), the arrays
of SciPy's NdBSpline; a .npz with a degrees member is read as such a spline.

Examples:
  lekalo convert curve.json -o curve.step
  lekalo convert curve.json -o curve.npz
  lekalo convert curve.npz -o from-npz.json
  lekalo convert tensor.json -o tensor.npz
  lekalo convert tensor.npz -o from-npz.json
  lekalo convert many.jsonl -o all.step
  lekalo convert curve.json -o curve.csv --samples 200
  lekalo convert curve.json --to jsonl
  lekalo convert surface.json -o surface.step
  lekalo convert surface.json -o surface.obj --samples 900
  lekalo convert spline.pp.json -o spline.csv --samples 100
  lekalo convert surface.json -o grid.csv --samples 400
  lekalo convert part.step -o curves.jsonl
  lekalo convert part.step -o faces.jsonl --faces
  lekalo convert faces.jsonl -o faces.step
  lekalo convert faces.jsonl -o faces.igs
  lekalo convert curves.jsonl -o again.step
  lekalo convert curves.jsonl -o again.igs
  lekalo convert again.igs -o from-iges.jsonl

Surfaces also convert to csv: u, v, x, y, z on a √samples × √samples grid.
Parquet batches (docs/formats.md#6c-parquet-batches-read-and-write): curves convert between
.parquet and .jsonl; a CSV of point sets whose header names the key column (group,x,y, or
--group-column NAME) converts to .parquet point sets, the input of interpolate and fit.
CAD input: a STEP file (.step, .stp; AP203, AP214, AP242) gives its B-spline and NURBS
curves and surfaces (B_SPLINE_CURVE_WITH_KNOTS, B_SPLINE_SURFACE_WITH_KNOTS, the rational
complex entities, TRIMMED_CURVE by parameter values), in millimetres, as jsonl (default),
json (one object) or step; what was skipped is listed on stderr. JSON Lines holding surfaces
convert to step and jsonl. With --faces, a STEP file's faces (ADVANCED_FACE: the surface,
its outer and inner loops, each edge's 3-D curve and pcurve) are written as JSON Lines, one
\"face\" object a line; faces that cannot be read are listed on stderr with the reason. IGES (.igs, .iges): entities 126 (rational B-spline curve) and 128
(rational B-spline surface) are written and read; with --faces, its trimmed and bounded surfaces
(144 and 143, boundaries 142 and 141 with their parameter-space curves, composite curves 102
split into edges) are written as faces. A JSON Lines file of faces (or --faces of a STEP or IGES
file) converts to step (ADVANCED_FACEs with shared EDGE_CURVEs and VERTEX_POINTs, pcurves in
SURFACE_CURVEs, a CLOSED_SHELL of a MANIFOLD_SOLID_BREP when the faces close a volume, else an
OPEN_SHELL of a SHELL_BASED_SURFACE_MODEL) and iges (trimmed surfaces 144 over 128 with
boundaries 142).")]
pub(crate) struct ConvertArgs {
    /// Object file (JSON; JSON Lines for batches; `-` for standard input).
    input: PathBuf,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Output format (default: from the output's extension).
    #[arg(long)]
    to: Option<String>,
    /// Samples for csv, svg, png and obj output.
    #[arg(long, default_value_t = 200)]
    samples: usize,
    /// Treat the input as JSON Lines.
    #[arg(long)]
    jsonl: bool,
    /// Write the faces of a STEP file, or the trimmed surfaces of an IGES file (surface, loops
    /// of edges with their pcurves) instead of its curves and surfaces: as JSON Lines (one face
    /// a line), STEP or IGES.
    #[arg(long)]
    faces: bool,
}

/// Timestamp written into STEP headers: fixed, so that the same input gives the same file.
const STEP_TIMESTAMP: &str = "2000-01-01T00:00:00";

/// The STEP product name: the output's file stem, or "lekalo".
fn step_name(a: &ConvertArgs) -> String {
    a.output
        .as_ref()
        .and_then(|p| p.file_stem())
        .and_then(|s| s.to_str())
        .unwrap_or("lekalo")
        .to_string()
}

pub(crate) fn run(a: &ConvertArgs, cx: &Context) -> Result<()> {
    // standard input is read once here: faces, or the text for the readers below
    let (face_lines, stdin) = crate::cmd::cad::face_input(&a.input)?;
    if a.faces || face_lines.is_some() {
        return crate::cmd::cad::convert_faces(
            &a.input,
            face_lines,
            stdin,
            a.output.as_deref(),
            a.to.as_deref(),
            (&step_name(a), STEP_TIMESTAMP),
            cx,
        );
    }
    let parquet = crate::items::is_parquet;
    if parquet(&a.input) || a.output.as_deref().is_some_and(parquet) {
        return crate::batch::parquet::convert_curves(cx, &a.input, stdin, a.output.as_deref());
    }
    // the input's items: of the text read from standard input, or opened by the file's kind
    let open_read = |cx: &Context, jsonl: bool| match &stdin {
        Some((text, name)) => {
            crate::items::open_text(cx, &a.input, jsonl, text, name, std::time::Instant::now())
        }
        None => open(cx, &a.input, jsonl),
    };
    if shapes::surface_csv_wanted(a.to.as_deref(), a.output.as_deref()) {
        if let Ok(Items::Other(Shape::Surface(s))) = open_read(&cx.quiet(), false) {
            let side = a.samples.clamp(2, 10_000_000).isqrt().max(2);
            let table = lekalo_io::surface_sample_table(
                &s,
                &s.grid_parameters(side, side),
                lekalo_io::SurfaceSampleSpec::default(),
            )?;
            return emit(
                a.output.as_deref(),
                table.to_csv().as_bytes(),
                std::slice::from_ref(&a.input),
                cx,
            );
        }
    }
    if crate::cmd::cad::wants_shapes(
        &a.input,
        a.jsonl,
        &format_of(a.to.as_deref(), a.output.as_deref(), "json"),
        stdin.as_ref().map(|(text, _)| text.as_str()),
    ) {
        return crate::cmd::cad::convert_shapes(
            &a.input,
            a.output.as_deref(),
            a.to.as_deref(),
            &step_name(a),
            STEP_TIMESTAMP,
            stdin.as_ref(),
            cx,
        );
    }
    // bad lines of JSON Lines: reported after the good ones are written (exit code 2)
    let mut failed: Vec<String> = Vec::new();
    let mut total = 0;
    let objects: Vec<Object> = match open_read(cx, a.jsonl)? {
        Items::Parquet(input) => {
            return crate::batch::parquet::convert_curves(cx, &input, None, a.output.as_deref())
        }
        Items::One(o) => vec![o],
        Items::Other(shape) => {
            let format = format_of(a.to.as_deref(), a.output.as_deref(), "json");
            let bytes = shapes::convert(
                &shape,
                &format,
                cx.in_range(a.samples, 2, usize::MAX, "--samples")?,
                &step_name(a),
                STEP_TIMESTAMP,
            )?;
            return emit(
                a.output.as_deref(),
                &bytes,
                std::slice::from_ref(&a.input),
                cx,
            );
        }
        Items::Lines(items) => {
            total = items.len();
            let mut good = Vec::with_capacity(items.len());
            for (_, o) in items {
                match o {
                    Ok(o) => good.push(o),
                    Err(e) => failed.push(e.to_string()),
                }
            }
            good
        }
    };
    if objects.is_empty() && !failed.is_empty() {
        for e in &failed {
            crate::output::report(&format!("  {e}"));
        }
        return bad_input(format!(
            "{}: all {total} objects failed (listed above); nothing written",
            a.input.display()
        ));
    }
    let Some(first) = objects.first() else {
        return bad_input(format!("{}: no objects", a.input.display()));
    };
    let format = format_of(a.to.as_deref(), a.output.as_deref(), "json");
    let single = || -> Result<&Object> {
        if objects.len() == 1 {
            Ok(first)
        } else {
            bad_input(format!(
                "{} objects: {format} output takes one object (use step or jsonl for many)",
                objects.len()
            ))
        }
    };
    let samples = cx.in_range(a.samples, 2, usize::MAX, "--samples")?;
    if matches!(format.as_str(), "csv" | "svg" | "png" | "obj") {
        cx.check_bezier_degree(first, "sampling")?;
    }
    let bytes: Vec<u8> = match format.as_str() {
        "json" => single()?.to_json_pretty().into_bytes(),
        "jsonl" => objects
            .iter()
            .map(|o| o.to_json_line() + "\n")
            .collect::<String>()
            .into_bytes(),
        "csv" => {
            let o = single()?;
            sample_table(o, &o.uniform_parameters(samples), SampleSpec::default())?
                .to_csv()
                .into_bytes()
        }
        "svg" | "png" => {
            let fig = curve_figure(
                single()?,
                &CurvePlot {
                    samples,
                    ..CurvePlot::default()
                },
            )?;
            encode(&fig, &format, 2.0)?
        }
        "step" => {
            let mut w = StepWriter::new(&step_name(a));
            for o in &objects {
                w.add_object(o)?;
            }
            w.finish(STEP_TIMESTAMP).into_bytes()
        }
        "obj" => lekalo_io::polyline_to_obj(&single()?.sample(samples)?).into_bytes(),
        "npz" => lekalo_io::curve_to_npz(single()?)?,
        other => {
            return bad_input(format!(
            "unknown output format \"{other}\": use json, jsonl, csv, svg, png, step, obj or npz"
        ))
        }
    };
    emit(
        a.output.as_deref(),
        &bytes,
        std::slice::from_ref(&a.input),
        cx,
    )?;
    crate::batch::failures(
        &failed,
        format!(
            "{} of {total} objects failed (listed above); the other {} were written",
            failed.len(),
            total - failed.len()
        ),
        cx,
    )
}
