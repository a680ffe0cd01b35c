//! `lekalo plot`: SVG or PNG plots of a curve, its basis functions or its knots; wireframes of
//! surfaces and graphs of piecewise polynomials.

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use lekalo_io::{
    basis_figure, curve_figure, ColorField, CurvePlot, Figure, Object, Projection, Shape,
    SurfacePlot, SURFACE_SAMPLES,
};

use crate::cmd::shapes;
use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::items::{load_one, not_a_curve, open, Items};
use crate::output::{emit, format_of};

/// Arguments of `lekalo plot`.
#[derive(Args, Debug)]
#[command(after_help = "\
The format follows the output's extension (.svg or .png) or --to. Curves in 3-D are drawn in
an orthographic view (--azimuth, --elevation).

Examples:
  lekalo plot curve.json -o curve.svg
  lekalo plot curve.json -o curve.png --points data.csv --title 'Interpolated'
  lekalo plot curve.json -o residuals.svg --points data.csv --residuals   # deviations from the curve
  lekalo plot curve.json -o basis.svg --basis
  lekalo plot curve3d.json -o view.svg --azimuth 30 --elevation 20
  lekalo plot surface.json -o surface.svg                  # shaded, 33 × 33 points, axes
  lekalo plot surface.json -o surface.png --net --iso 4     # with its control net
  lekalo plot surface.json -o surface.svg --wireframe --samples 20   # 20 × 20 hidden-line mesh
  lekalo plot surface.json -o gauss.svg --curvature gaussian   # a curvature map
  lekalo plot spline.pp.json -o spline.png")]
pub(crate) struct PlotArgs {
    /// Object file (JSON; `-` for standard input).
    input: PathBuf,
    /// Output file (.svg or .png; default: SVG on standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Output format: svg or png.
    #[arg(long)]
    to: Option<String>,
    /// Plot the B-spline basis functions of the curve's knots instead of the curve.
    #[arg(long)]
    basis: bool,
    /// Data points to show (CSV, text or JSON).
    #[arg(long, value_name = "FILE")]
    points: Option<PathBuf>,
    /// With `--points`: draw each point's deviation from the curve, a segment to its closest
    /// point on the curve, with the largest and the RMS distance in the legend (for a fit:
    /// the data, the fit and its deviations).
    #[arg(long, requires = "points")]
    residuals: bool,
    /// Leave out the control polygon.
    #[arg(long)]
    no_control: bool,
    /// Leave out the marks at the knots.
    #[arg(long)]
    no_knots: bool,
    /// Evaluation points along the curve (default 400), or per direction of a surface
    /// (default 33).
    #[arg(long)]
    samples: Option<usize>,
    /// Curves: draw the curvature comb (teeth of length proportional to the curvature, away
    /// from the centre of curvature) at `--comb-teeth` points.
    #[arg(long)]
    comb: bool,
    /// Teeth of the curvature comb.
    #[arg(long, default_value_t = 120, value_name = "N")]
    comb_teeth: usize,
    /// Surfaces: draw a hidden-line wireframe of every sampled grid line instead of the
    /// shaded surface.
    #[arg(long)]
    wireframe: bool,
    /// Surfaces: draw the control net.
    #[arg(long)]
    net: bool,
    /// Surfaces: colour the shaded surface by a curvature (3-D surfaces) instead of the height:
    /// a curvature map with its colour bar.
    #[arg(long, value_enum, value_name = "KIND")]
    curvature: Option<CurvatureMap>,
    /// Surfaces: isoparametric lines drawn on the shaded surface, per direction (0: none).
    #[arg(long, default_value_t = 8, value_name = "N")]
    iso: usize,
    /// Title of the figure.
    #[arg(long)]
    title: Option<String>,
    /// View azimuth in degrees (3-D curves).
    #[arg(long, default_value_t = -60.0, allow_hyphen_values = true)]
    azimuth: f64,
    /// View elevation in degrees (3-D curves).
    #[arg(long, default_value_t = 30.0, allow_hyphen_values = true)]
    elevation: f64,
    /// PNG scale factor (1 = 640 × 420 pixels).
    #[arg(long, default_value_t = 2.0)]
    scale: f32,
}

/// The curvature a surface plot is coloured by (`--curvature`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum CurvatureMap {
    /// Gaussian curvature K = κ₁κ₂.
    Gaussian,
    /// Mean curvature H = (κ₁ + κ₂)/2.
    Mean,
    /// The larger principal curvature κ₁.
    K1,
    /// The smaller principal curvature κ₂.
    K2,
}

impl CurvatureMap {
    /// The column of `eval --curvature` and the colour bar's label.
    fn column_and_label(self) -> (&'static str, &'static str) {
        match self {
            CurvatureMap::Gaussian => ("gaussian", "Gaussian curvature"),
            CurvatureMap::Mean => ("mean", "mean curvature"),
            CurvatureMap::K1 => ("k1", "principal curvature k1"),
            CurvatureMap::K2 => ("k2", "principal curvature k2"),
        }
    }
}

/// Evaluation points along a curve, a basis function or a pp-form by default.
const CURVE_SAMPLES: usize = 400;

/// The figure `plot` draws for one object.
pub(crate) fn figure(
    cx: &Context,
    obj: &Object,
    a: &PlotArgs,
    data: Option<&lekalo::Points>,
) -> Result<Figure> {
    if a.basis {
        let mut fig = basis_figure(
            &obj.knots(),
            obj.degree(),
            cx.in_range(
                a.samples.unwrap_or(CURVE_SAMPLES),
                2,
                PLOT_SAMPLES,
                "--samples",
            )?,
        )?;
        if let Some(t) = &a.title {
            fig.title.clone_from(t);
        }
        return Ok(fig);
    }
    Ok(curve_figure(
        obj,
        &CurvePlot {
            title: a.title.clone(),
            samples: cx.in_range(
                a.samples.unwrap_or(CURVE_SAMPLES),
                2,
                PLOT_SAMPLES,
                "--samples",
            )?,
            control_polygon: !a.no_control,
            knot_marks: !a.no_knots,
            data_points: data,
            projection: Projection {
                azimuth: a.azimuth,
                elevation: a.elevation,
            },
        },
    )?)
}

/// Most samples along a plotted curve (far more than a picture can show).
const PLOT_SAMPLES: usize = 1_000_000;

/// The curvature `kind` at the plot's `side × side` grid points: the `eval --curvature` column
/// of the library's curvatures (`lekalo::surface_curvature`), undefined where the normal is.
fn curvature_field(
    s: &lekalo_io::Surface,
    side: usize,
    kind: CurvatureMap,
    a: &PlotArgs,
) -> Result<ColorField> {
    if a.wireframe {
        return bad_input("--curvature colours the shaded surface; it cannot go with --wireframe");
    }
    if s.dim() != 3 {
        return bad_input(format!(
            "--curvature needs a surface in 3-D; {} is a {}-D {}",
            a.input.display(),
            s.dim(),
            s.display_name()
        ));
    }
    let spec = lekalo_io::SurfaceSampleSpec {
        derivatives: 0,
        normals: false,
        curvature: true,
    };
    let table = lekalo_io::surface_sample_table(s, &s.grid_parameters(side, side), spec)
        .map_err(|e| BadInput(format!("{}: {e}", a.input.display())))?;
    let (column, label) = kind.column_and_label();
    let at = table
        .header
        .iter()
        .position(|h| h == column)
        .ok_or_else(|| BadInput(format!("no {column} column in the curvature table")))?;
    Ok(ColorField {
        label: label.to_string(),
        values: table.rows.iter().map(|r| r[at]).collect(),
    })
}

/// `Err(BadInput)` unless the view angles are finite numbers.
fn check_view(a: &PlotArgs) -> Result<()> {
    for (name, v) in [("--azimuth", a.azimuth), ("--elevation", a.elevation)] {
        if !v.is_finite() {
            return bad_input(format!(
                "{name} {v}: the view angle must be a finite number of degrees"
            ));
        }
    }
    Ok(())
}

pub(crate) fn run(a: &PlotArgs, cx: &Context) -> Result<()> {
    check_view(a)?;
    let format = format_of(a.to.as_deref(), a.output.as_deref(), "svg");
    let obj = match open(cx, &a.input, false)? {
        Items::One(o) => o,
        Items::Other(shape) => {
            let fig = match &shape {
                _ if a.basis || a.points.is_some() || a.comb => {
                    return bad_input(format!(
                        "--basis, --points, --residuals and --comb are for curves; {} is a {}",
                        a.input.display(),
                        shape.type_name()
                    ))
                }
                Shape::Surface(s) => {
                    let side = cx.in_range(
                        a.samples.unwrap_or(SURFACE_SAMPLES),
                        2,
                        1000,
                        "--samples (per direction of a surface)",
                    )?;
                    let colors = match a.curvature {
                        Some(kind) => Some(curvature_field(s, side, kind, a)?),
                        None => None,
                    };
                    shapes::surface_figure(
                        s,
                        side,
                        a.net,
                        &SurfacePlot {
                            title: a.title.as_deref().unwrap_or(s.display_name()).to_string(),
                            projection: Projection {
                                azimuth: a.azimuth,
                                elevation: a.elevation,
                            },
                            shaded: !a.wireframe,
                            iso_lines: a.iso,
                            axes: true,
                            colors,
                        },
                    )?
                }
                _ if a.curvature.is_some() => {
                    return bad_input(format!(
                        "--curvature colours a surface; {} is a {} (a curve's curvature: --comb)",
                        a.input.display(),
                        shape.type_name()
                    ))
                }
                Shape::Pp(p) => shapes::pp_figure(
                    p,
                    cx.in_range(
                        a.samples.unwrap_or(CURVE_SAMPLES),
                        2,
                        PLOT_SAMPLES,
                        "--samples",
                    )?,
                    a.title.as_deref(),
                )?,
                other => return not_a_curve(&a.input, other),
            };
            let bytes = crate::output::encode(&fig, &format, a.scale)?;
            return emit(
                a.output.as_deref().filter(|p| *p != Path::new("-")),
                &bytes,
                std::slice::from_ref(&a.input),
                cx,
            );
        }
        Items::Lines(_) | Items::Parquet(_) => return load_one(cx, &a.input).map(|_| ()),
    };
    if a.curvature.is_some() {
        return bad_input(format!(
            "--curvature colours a surface; {} is a curve (its curvature: --comb)",
            a.input.display()
        ));
    }
    let mut inputs = vec![a.input.clone()];
    let data = match &a.points {
        Some(p) => {
            inputs.push(p.clone());
            Some(crate::items::read_points(cx, p)?.0)
        }
        None => None,
    };
    if !a.basis {
        cx.check_bezier_degree(&obj, "plotting")?;
    }
    let mut fig = figure(cx, &obj, a, data.as_ref())?;
    if a.comb && !a.basis {
        let teeth = cx.in_range(a.comb_teeth, 2, 100_000, "--comb-teeth")?;
        fig.series
            .extend(crate::cmd::comb::comb_series(&obj, &a.input, teeth)?);
    }
    if let (true, Some(data), Some(path)) = (a.residuals, &data, &a.points) {
        if a.basis {
            return bad_input("--residuals draws a curve's deviations; it cannot go with --basis");
        }
        let feet = crate::cmd::project::closest_points(&obj, &a.input, data, path)?;
        let projection = Projection {
            azimuth: a.azimuth,
            elevation: a.elevation,
        };
        fig.series
            .push(lekalo_io::residual_series(data, &feet, &projection)?);
    }
    let bytes = crate::output::encode(&fig, &format, a.scale)?;
    emit(
        a.output.as_deref().filter(|p| *p != Path::new("-")),
        &bytes,
        &inputs,
        cx,
    )
}
