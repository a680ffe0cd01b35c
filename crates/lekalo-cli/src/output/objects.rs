//! Writing one object in the format the output asks for (`-o FILE` by its extension, or
//! `--to`): curves and surfaces as JSON, SVG/PNG figures, STEP, CSV samples, OBJ, NumPy
//! archives; the output options (`-o`, `--to`) of the commands that make objects.

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use lekalo::{BSplineSurface, Points};
use lekalo_io::{
    curve_figure, sample_table, CurveJson, CurvePlot, Figure, Grid, Object, SampleSpec, Series,
    Style, SurfaceNet, PALETTE,
};

use super::{emit, encode, format_of};
use crate::context::Context;
use crate::exit::bad_input;

/// Output options shared by the construction subcommands.
#[derive(Args, Debug, Clone)]
pub(crate) struct OutArgs {
    /// Output file (default: standard output); the format follows the extension.
    #[arg(short, long, value_name = "FILE")]
    pub(crate) output: Option<PathBuf>,
    /// Output format: json, svg, png, step, csv (samples) or obj (surfaces: tessellation).
    #[arg(long, value_name = "FORMAT")]
    pub(crate) to: Option<String>,
}

/// Fixed STEP timestamp, so that the same input gives the same file.
const STEP_TIMESTAMP: &str = "2000-01-01T00:00:00";
/// Samples along a curve in plots, CSV and OBJ output.
const CURVE_SAMPLES: usize = 200;
/// Samples per direction of a surface in plots and OBJ output.
const SURFACE_SAMPLES: usize = 25;

/// Writes a spline in N parameters: as a NumPy archive for an output `.npz` (SciPy's
/// `NdBSpline` arrays, [`lekalo_io::write_npz_tensor`], streamed into the file), as its JSON
/// otherwise.
pub(crate) fn write_tensor(
    t: &lekalo::Tensor,
    (to, out): (Option<&str>, Option<&Path>),
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    if tensor_format(t.n_vars(), to, out)? == "npz" {
        return super::emit_seek(out, inputs, cx, |w| lekalo_io::write_npz_tensor(t, w));
    }
    emit(out, lekalo_io::tensor_to_json(t).as_bytes(), inputs, cx)
}

/// The format a spline in `n` parameters is written in, `json` or `npz`, from `--to` or the
/// output's extension (JSON by default); another is refused naming both, before the spline
/// is computed.
pub(crate) fn tensor_format(
    n: usize,
    to: Option<&str>,
    out: Option<&Path>,
) -> Result<&'static str> {
    match format_of(to, out, "json").as_str() {
        "json" => Ok("json"),
        "npz" => Ok("npz"),
        other => bad_input(format!(
            "a spline in {n} parameters is written as json or npz, not \"{other}\""
        )),
    }
}

/// Writes a curve object in the chosen format; `data` are points to show in plots.
pub(crate) fn write_curve(
    obj: &Object,
    data: Option<&Points>,
    out: &OutArgs,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let format = format_of(out.to.as_deref(), out.output.as_deref(), "json");
    let bytes = match format.as_str() {
        // streamed: a curve of millions of control points is never held as text
        "json" => {
            return super::emit_stream(out.output.as_deref(), inputs, cx, |w| {
                obj.write_json(w, true)
            })
        }
        "svg" | "png" => encode(&curve_plot(obj, data, None)?, &format, 2.0)?,
        "csv" => sample_table(
            obj,
            &obj.uniform_parameters(CURVE_SAMPLES),
            SampleSpec::default(),
        )?
        .to_csv()
        .into_bytes(),
        "step" => {
            let mut w = lekalo_io::StepWriter::new(stem(out.output.as_deref()));
            w.add_object(obj)?;
            w.finish(STEP_TIMESTAMP).into_bytes()
        }
        "obj" => lekalo_io::polyline_to_obj(&obj.sample(CURVE_SAMPLES)?).into_bytes(),
        // streamed: the arrays go into the archive's members without a copy in memory
        "npz" => {
            return super::emit_seek(out.output.as_deref(), inputs, cx, |w| {
                lekalo_io::write_npz_curve(obj, w)
            })
        }
        other => {
            return bad_input(format!(
                "unknown output format \"{other}\": use json, svg, png, step, csv, obj or npz"
            ))
        }
    };
    emit(out.output.as_deref(), &bytes, inputs, cx)
}

/// A plot of a curve: plane curves with control polygon and data; 1-D curves (functions) as a
/// graph `(t, y(t))` with the data as `(x_k, y_k)`.
pub(crate) fn curve_plot(
    obj: &Object,
    data: Option<&Points>,
    title: Option<&str>,
) -> Result<Figure> {
    if obj.dim() != 1 {
        return Ok(curve_figure(
            obj,
            &CurvePlot {
                title: title.map(str::to_string),
                data_points: data,
                ..CurvePlot::default()
            },
        )?);
    }
    let t = obj.uniform_parameters(CURVE_SAMPLES);
    let y = obj.sample(CURVE_SAMPLES)?;
    let graph = t.iter().zip(y.iter()).map(|(t, y)| [*t, y[0]]).collect();
    let mut fig = Figure::new(
        title.unwrap_or(&format!(
            "{} y(x) of degree {}",
            obj.display_name(),
            obj.degree()
        )),
        false,
    );
    fig.series
        .push(Series::new(Some("y(x)"), graph, Style::Line, PALETTE[0]));
    // (x, y) data of a function; 1-D data are values without their parameters: not drawn
    if let Some(d) = data.filter(|d| d.dim() >= 2) {
        let pts = d.iter().map(|p| [p[0], p[1]]).collect();
        fig.series.push(Series::new(
            Some("data points"),
            pts,
            Style::Markers,
            PALETTE[2],
        ));
    }
    fig.axis_labels = ("x".into(), "y".into());
    Ok(fig)
}

fn stem(out: Option<&Path>) -> &str {
    out.and_then(|p| p.file_stem())
        .and_then(|s| s.to_str())
        .unwrap_or("lekalo")
}

/// A surface sampled on a `SURFACE_SAMPLES²` grid, shaded, with its control net.
pub(crate) fn surface_figure(s: &BSplineSurface, title: &str) -> Result<Figure> {
    let ((u0, u1), (v0, v1)) = s.domain();
    let us = lekalo_io::uniform(u0, u1, lekalo_io::SURFACE_SAMPLES);
    let vs = lekalo_io::uniform(v0, v1, lekalo_io::SURFACE_SAMPLES);
    let mut data = vec![0.0; us.len() * vs.len() * s.dim()];
    s.eval_grid(&us, &vs, &mut data)?;
    let grid = Grid::new(us.len(), vs.len(), s.dim(), &data)?;
    let (nu, nv) = s.net_size();
    let net = Grid::new(nu, nv, s.dim(), s.control_points().as_slice())?;
    Ok(lekalo_io::surface_plot(
        &grid,
        Some(&net),
        &lekalo_io::SurfacePlot::new(title),
    ))
}

/// Writes a B-spline surface: json, svg/png (wireframe), step, obj (tessellation).
pub(crate) fn write_surface(
    s: &BSplineSurface,
    out: &OutArgs,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let format = format_of(out.to.as_deref(), out.output.as_deref(), "json");
    let title = format!(
        "B-spline surface of degrees ({}, {})",
        s.degree_u(),
        s.degree_v()
    );
    let bytes = match format.as_str() {
        "json" => lekalo_io::bspline_surface_to_json(s).into_bytes(),
        "svg" | "png" => encode(&surface_figure(s, &title)?, &format, 2.0)?,
        "step" => {
            let (nu, nv) = s.net_size();
            let mut w = lekalo_io::StepWriter::new(stem(out.output.as_deref()));
            w.add_surface(&SurfaceNet {
                degrees: (s.degree_u(), s.degree_v()),
                knots: (s.knots_u().as_slice(), s.knots_v().as_slice()),
                net: Grid::new(nu, nv, s.dim(), s.control_points().as_slice())?,
                weights: None,
            })?;
            w.finish(STEP_TIMESTAMP).into_bytes()
        }
        "obj" => {
            let ((u0, u1), (v0, v1)) = s.domain();
            let us = lekalo_io::uniform(u0, u1, SURFACE_SAMPLES);
            let vs = lekalo_io::uniform(v0, v1, SURFACE_SAMPLES);
            let mut data = vec![0.0; us.len() * vs.len() * s.dim()];
            s.eval_grid(&us, &vs, &mut data)?;
            lekalo_io::grid_to_obj(&Grid::new(us.len(), vs.len(), s.dim(), &data)?, None)?
                .into_bytes()
        }
        other => {
            return bad_input(format!(
                "unknown surface output format \"{other}\": use json, svg, png, step or obj"
            ))
        }
    };
    emit(out.output.as_deref(), &bytes, inputs, cx)
}

/// Writes a Bezier surface: its own JSON (`bezier_surface`), other formats as
/// [`write_surface`] of its B-spline form.
pub(crate) fn write_bezier_surface(
    s: &lekalo::BezierSurface,
    out: &OutArgs,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    if format_of(out.to.as_deref(), out.output.as_deref(), "json") == "json" {
        let text = lekalo_io::bezier_surface_to_json(s);
        return emit(out.output.as_deref(), text.as_bytes(), inputs, cx);
    }
    write_surface(&s.to_bspline(), out, inputs, cx)
}
