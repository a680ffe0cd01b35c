//! `lekalo sweep`: exact swept surfaces from curves, the surface of revolution, the extrusion
//! and the ruled surface (`lekalo::NurbsSurface::revolve`, `extrude`, `ruled`).

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::{Args, Subcommand};
use lekalo::NurbsSurface;
use lekalo_io::{Surface, SurfaceJson};

use crate::context::Context;
use crate::exit::bad_input;
use crate::items::load_one;
use crate::output::emit;
use crate::values::numbers;

/// `lekalo sweep` operations.
#[derive(Subcommand, Debug)]
pub(crate) enum SweepOp {
    /// Turn a 3-D curve about an axis: the surface of revolution, exact (P&T A8.1).
    #[command(after_help = "\
u runs along the arcs (from --angles' start to its end, counterclockwise seen from the axis's
tip), v along the curve.

Examples:
  lekalo sweep revolve curve3d.json --axis-point 0,0,0 --axis-direction 0,0,1 -o vase.json
  lekalo sweep revolve curve3d.json --axis-point 0,0,0 --axis-direction 0,0,1 --angles 0,3.14159 -o half.json")]
    Revolve {
        /// The curve (object JSON).
        curve: PathBuf,
        /// A point of the axis, `x,y,z`.
        #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
        axis_point: String,
        /// The axis's direction, `x,y,z` (any length but zero).
        #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
        axis_direction: String,
        /// Start and end angle in radians (default a full turn, 0,2π).
        #[arg(long, value_name = "A,B", allow_hyphen_values = true)]
        angles: Option<String>,
        /// Output file (JSON; default standard output).
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
    },
    /// Move a 3-D curve along a vector: S(u, v) = C(u) + v·D, exact.
    #[command(after_help = "\
Examples:
  lekalo sweep extrude curve3d.json --direction 0,0,4 -o wall.json
  lekalo sweep extrude curve3d.json --direction 0,0,1 --range -2,2 -o slab.json")]
    Extrude {
        /// The curve (object JSON).
        curve: PathBuf,
        /// The vector D, `x,y,z` (its length counts).
        #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
        direction: String,
        /// The range of v (default 0,1).
        #[arg(long, value_name = "V0,V1", allow_hyphen_values = true)]
        range: Option<String>,
        /// Output file (JSON; default standard output).
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
    },
    /// Join two curves by straight lines between their points of equal relative parameter:
    /// (1 − v)·A(u) + v·B(u), exact.
    #[command(after_help = "\
Examples:
  lekalo sweep ruled curve3d.json upper.json -o band.json")]
    Ruled {
        /// The first curve (object JSON), the edge v = 0.
        first: PathBuf,
        /// The second curve, the edge v = 1.
        second: PathBuf,
        /// Output file (JSON; default standard output).
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
    },
}

#[derive(Args, Debug)]
#[command(after_help = "\
The surfaces are exact NURBS, written as JSON (`lekalo convert surface.json -o surface.step`
for STEP, IGES or OBJ; `lekalo plot surface.json -o surface.png` to look at it).")]
pub(crate) struct SweepArgs {
    #[command(subcommand)]
    op: SweepOp,
}

/// `x,y,z` as three numbers.
fn triple(text: &str, what: &str) -> Result<[f64; 3]> {
    match numbers(text, what)?.as_slice() {
        &[x, y, z] => Ok([x, y, z]),
        other => bad_input(format!(
            "{what}: {} numbers in \"{text}\"; give three, x,y,z",
            other.len()
        )),
    }
}

/// `a,b` as two numbers, or `default`.
fn pair(text: Option<&str>, what: &str, default: (f64, f64)) -> Result<(f64, f64)> {
    let Some(text) = text else {
        return Ok(default);
    };
    match numbers(text, what)?.as_slice() {
        &[a, b] => Ok((a, b)),
        other => bad_input(format!(
            "{what}: {} numbers in \"{text}\"; give two, a,b",
            other.len()
        )),
    }
}

/// The curve of an object file as a NURBS curve.
fn nurbs(cx: &Context, path: &Path) -> Result<lekalo::NurbsCurve> {
    Ok(load_one(cx, path)?.to_nurbs())
}

/// Writes the surface as JSON; any other extension is refused, naming the command that
/// converts.
fn write(s: NurbsSurface, output: Option<&Path>, inputs: &[PathBuf], cx: &Context) -> Result<()> {
    if let Some(ext) = output.and_then(Path::extension).and_then(|e| e.to_str()) {
        if !ext.eq_ignore_ascii_case("json") {
            return bad_input(format!(
                "-o: `lekalo sweep` writes JSON (.json), not .{ext}; write surface.json, then \
                 `lekalo convert surface.json -o surface.{ext}`"
            ));
        }
    }
    emit(
        output,
        Surface::Nurbs(s).to_json_pretty().as_bytes(),
        inputs,
        cx,
    )
}

pub(crate) fn run(a: &SweepArgs, cx: &Context) -> Result<()> {
    match &a.op {
        SweepOp::Revolve {
            curve,
            axis_point,
            axis_direction,
            angles,
            output,
        } => {
            let point = triple(axis_point, "--axis-point")?;
            let dir = triple(axis_direction, "--axis-direction")?;
            let (a0, a1) = pair(angles.as_deref(), "--angles", (0.0, std::f64::consts::TAU))?;
            let s = NurbsSurface::revolve(&nurbs(cx, curve)?, point, dir, a0, a1)?;
            write(s, output.as_deref(), std::slice::from_ref(curve), cx)
        }
        SweepOp::Extrude {
            curve,
            direction,
            range,
            output,
        } => {
            let d = triple(direction, "--direction")?;
            let (v0, v1) = pair(range.as_deref(), "--range", (0.0, 1.0))?;
            let s = NurbsSurface::extrude(&nurbs(cx, curve)?, d, v0, v1)?;
            write(s, output.as_deref(), std::slice::from_ref(curve), cx)
        }
        SweepOp::Ruled {
            first,
            second,
            output,
        } => {
            let s = NurbsSurface::ruled(&nurbs(cx, first)?, &nurbs(cx, second)?)?;
            write(s, output.as_deref(), &[first.clone(), second.clone()], cx)
        }
    }
}
