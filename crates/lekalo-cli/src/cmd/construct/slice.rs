//! `lekalo slice`: fix some parameters of a spline in N parameters (the spline in the others,
//! [`lekalo::Tensor::slice`]) or one parameter of a surface (its iso-curve,
//! [`lekalo::Surface::iso_curve`]); `docs/theory/tensor.md#operations-along-one-direction`.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo::Direction;
use lekalo_io::Shape;

use crate::cmd::cad::load_shape;
use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::output::emit;
use crate::values::numbers;

/// Arguments of `lekalo slice`.
#[derive(Args, Debug)]
#[command(after_help = "\
A spline in N parameters with K of them fixed is a spline in the other N − K, of the same
kind (B-spline or NURBS), written as JSON or, for an output .npz, SciPy's NdBSpline arrays.
A surface with one parameter fixed is its iso-parametric curve: `--fix v=0.5` gives
u ↦ S(u, 0.5).

Examples:
  lekalo slice tensor.json --fix 3=0.5 -o plane.json       # f(x, y, 0.5)
  lekalo slice tensor.json --fix 1=0.25 --fix 2=0.5 -o line.json
  lekalo slice surface.json --fix v=0.5 -o curve.json     # the iso-curve at v = 0.5")]
pub(crate) struct SliceArgs {
    /// A spline in N parameters or a surface (object JSON; `-` for standard input).
    input: PathBuf,
    /// A parameter to fix, `K=X`: direction `K` (from 1; `u` and `v` for a surface, or 1
    /// and 2) at the value `X`. Repeat for more.
    #[arg(long, value_name = "K=X", required = true, allow_hyphen_values = true)]
    fix: Vec<String>,
    /// Output file (JSON, or `.npz` for a spline in N parameters; default standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

/// `K=X` as the direction (from 0) and the value; `u` and `v` are directions 1 and 2.
fn fixed(text: &str) -> Result<(usize, f64)> {
    let Some((k, x)) = text.split_once('=') else {
        return bad_input(format!(
            "--fix {text}: give a direction and a value, K=X (for example --fix 2=0.5, or \
             v=0.5 for a surface)"
        ));
    };
    let axis = match k.trim() {
        "u" => 0,
        "v" => 1,
        k => match k.parse::<usize>() {
            Ok(k) if k >= 1 => k - 1,
            _ => {
                return bad_input(format!(
                    "--fix {text}: \"{k}\" is not a direction; directions count from 1 (or u \
                     and v for a surface)"
                ))
            }
        },
    };
    match numbers(x, "--fix")?.as_slice() {
        &[x] => Ok((axis, x)),
        other => bad_input(format!(
            "--fix {text}: {} values; give one value a direction",
            other.len()
        )),
    }
}

pub(crate) fn run(a: &SliceArgs, cx: &Context) -> Result<()> {
    let mut fixes = Vec::with_capacity(a.fix.len());
    for f in &a.fix {
        fixes.push(fixed(f)?);
    }
    let inputs = std::slice::from_ref(&a.input);
    match load_shape(&a.input, cx)? {
        Shape::Tensor(t) => {
            let n = t.n_vars();
            let mut at = vec![None; n];
            for (&(axis, x), text) in fixes.iter().zip(&a.fix) {
                if axis >= n {
                    return bad_input(format!(
                        "--fix {text}: the spline has {n} parameters; directions run from 1 to \
                         {n}"
                    ));
                }
                if at[axis].replace(x).is_some() {
                    return bad_input(format!(
                        "--fix {text}: direction {} is fixed twice; give each direction once",
                        axis + 1
                    ));
                }
            }
            if at.iter().all(Option::is_some) {
                return bad_input(format!(
                    "--fix: all {n} parameters fixed leaves a point, not a spline; use `lekalo \
                     eval {} --at …` for its value",
                    a.input.display()
                ));
            }
            let sliced = t.slice(&at).map_err(|e| BadInput(format!("--fix: {e}")))?;
            crate::output::objects::write_tensor(&sliced, (None, a.output.as_deref()), inputs, cx)
        }
        Shape::Surface(s) => {
            let &[(axis, x)] = fixes.as_slice() else {
                return bad_input(
                    "--fix: a surface takes one fixed parameter (u=X or v=X); fixing both gives \
                     a point: use `lekalo eval --uv`",
                );
            };
            // fixing v leaves u free: the iso-curve along u
            let free = match axis {
                0 => Direction::V,
                1 => Direction::U,
                _ => {
                    return bad_input(format!(
                        "--fix {}: a surface has the directions u and v (1 and 2)",
                        a.fix[0]
                    ))
                }
            };
            let curve = s
                .iso_curve(free, x)
                .map_err(|e| BadInput(format!("--fix {}: {e}", a.fix[0])))?;
            emit(
                a.output.as_deref(),
                Shape::Curve(curve).to_json_pretty().as_bytes(),
                inputs,
                cx,
            )
        }
        other => bad_input(format!(
            "{}: a {}; `lekalo slice` takes splines in N parameters and surfaces",
            a.input.display(),
            other.type_name()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::fixed;

    #[test]
    fn directions_count_from_one_and_u_v_name_the_first_two() {
        assert_eq!(fixed("3=0.5").unwrap(), (2, 0.5));
        assert_eq!(fixed("u=-1").unwrap(), (0, -1.0));
        assert_eq!(fixed("v=1/4").unwrap(), (1, 0.25));
        for bad in ["0=0.5", "x=1", "2", "2=1,2"] {
            let e = fixed(bad).unwrap_err().to_string();
            assert!(e.contains("--fix"), "{bad}: {e}");
        }
    }
}
