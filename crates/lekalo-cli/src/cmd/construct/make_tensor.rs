//! `lekalo make bspline-tensor|nurbs-tensor`: a spline in N parameters from its control net,
//! degrees, knot vectors and weights ([`lekalo::TensorBSpline::from_knot_vectors`],
//! [`lekalo::TensorNurbs::new`]); a net of two directions is written as the surface it is, as
//! `interpolate --grid AxB` writes one.

use std::path::{Path, PathBuf};

use anyhow::Result;
use lekalo::{Arg, KnotVector, Tensor, TensorBSpline, TensorNurbs};
use lekalo_io::{Surface, SurfaceJson};

use crate::cmd::tensor::{
    checked_nodes, checked_values, degrees_for, per_direction, size_factors, GridLists,
};
use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::output::emit;
use crate::values::numbers;

/// What `make` was given for a spline in N parameters.
pub(crate) struct TensorMake<'a> {
    /// `nurbs-tensor` (with `--weights`) rather than `bspline-tensor`.
    pub(crate) rational: bool,
    pub(crate) control: &'a Path,
    /// `--net AxBxC…`.
    pub(crate) net: Option<&'a str>,
    /// `--degree`: one for every direction, or one per direction.
    pub(crate) degree: &'a [usize],
    /// Full knot vectors per direction: `--knots-u`, `--knots-v`, `--knots-in K=LIST`.
    pub(crate) knots: GridLists<'a>,
    /// `--weights LIST|FILE`.
    pub(crate) weights: Option<&'a str>,
    pub(crate) output: Option<&'a Path>,
}

/// Builds the spline of `m` (every size checked before anything of that size is read or
/// allocated) and writes it as a `bspline_tensor` / `nurbs_tensor`, or as a surface for a net
/// of two directions.
pub(crate) fn run(m: &TensorMake<'_>, cx: &Context) -> Result<()> {
    let kind = if m.rational {
        "nurbs-tensor"
    } else {
        "bspline-tensor"
    };
    let Some(net) = m.net else {
        return bad_input(format!(
            "{kind} needs --net AxBxC…, the size of the control net in each direction (the \
             rows of --control are its points, the first direction slowest)"
        ));
    };
    let shape = size_factors(net, "--net")?;
    let n = shape.len();
    if n < 2 {
        let curve = if m.rational { "nurbs" } else { "bspline" };
        return bad_input(format!(
            "--net {net}: a net of one direction is a curve; use `lekalo make {curve}`, or give \
             the size in each direction, e.g. --net 4x3x2"
        ));
    }
    let count = checked_nodes(("--net", net), "control points", &shape, cx)?;
    if m.degree.is_empty() {
        return bad_input(format!(
            "{kind} needs --degree: one degree for every direction, or one per direction (e.g. \
             --degree {})",
            vec!["2"; n].join(",")
        ));
    }
    let degrees = degrees_for(m.degree, n)?;
    let knots = knot_vectors(net, &shape, &degrees, m.knots)?;
    if m.rational != m.weights.is_some() {
        return bad_input(if m.rational {
            "a NURBS in N parameters needs --weights, one per control point in the order of \
             --control (a list or a file of one value a line)"
                .to_string()
        } else {
            "--weights make a rational spline: use `lekalo make nurbs-tensor`".to_string()
        });
    }
    let control = checked_values(("--net", net), "control points", &shape, m.control, cx)?;
    let mut inputs: Vec<PathBuf> = vec![m.control.to_path_buf()];
    let tensor = match m.weights {
        None => {
            let s = TensorBSpline::from_knot_vectors(degrees, knots, control)?;
            if n == 2 {
                let text = Surface::BSpline(s.to_surface()?).to_json_pretty();
                return emit(m.output, text.as_bytes(), &inputs, cx);
            }
            Tensor::BSpline(s)
        }
        Some(w) => {
            let weights = crate::cmd::explicit::parameters(cx, w, "--weights")?;
            if weights.len() != count {
                return bad_input(format!(
                    "--weights: {} weights for the {count} control points of --net {net}; give \
                     one weight per control point, in the order of --control",
                    weights.len()
                ));
            }
            if Path::new(w).is_file() {
                inputs.push(PathBuf::from(w));
            }
            let knots = knots.into_iter().map(KnotVector::into_vec).collect();
            let s = TensorNurbs::new(degrees, knots, control, &weights).map_err(|e| {
                if e.arg() == Some(Arg::Weights) {
                    BadInput(format!("--weights: {e}; give positive finite weights")).into()
                } else {
                    anyhow::Error::from(e)
                }
            })?;
            if n == 2 {
                let text = Surface::Nurbs(s.to_nurbs_surface()?).to_json_pretty();
                return emit(m.output, text.as_bytes(), &inputs, cx);
            }
            Tensor::Nurbs(s)
        }
    };
    crate::output::objects::write_tensor(&tensor, (None, m.output), &inputs, cx)
}

/// The knot vector of each direction of the net `shape` (`--net net`) at `degrees`: the one
/// given (`--knots-u`, `--knots-v`, `--knots-in K=LIST`, a full vector of control points +
/// degree + 1 knots, checked by [`KnotVector::validate_for`]), or clamped uniform knots
/// ([`KnotVector::clamped_uniform`], document 000 eq. 2); a degree not below its direction's
/// size and a wrong knot vector name their option and direction.
fn knot_vectors(
    net: &str,
    shape: &[usize],
    degrees: &[usize],
    lists: GridLists<'_>,
) -> Result<Vec<KnotVector>> {
    let options = ("--knots-u", "--knots-v", "--knots-in");
    let given = per_direction(shape.len(), lists, options, "knots", numbers)?;
    let mut out = Vec::with_capacity(shape.len());
    for (a, entry) in given.into_iter().enumerate() {
        let (size, p, k) = (shape[a], degrees[a], a + 1);
        if p >= size {
            return bad_input(format!(
                "--degree: direction {k} has {size} control points (--net {net}) and takes a \
                 degree of at most {}; lower its degree or give it more control points",
                size - 1
            ));
        }
        let kv = match entry {
            None => KnotVector::clamped_uniform(p, size)
                .map_err(|e| BadInput(format!("--degree (direction {k}): {e}")))?,
            Some((option, list)) => {
                let want = size + p + 1;
                if list.len() != want {
                    return bad_input(format!(
                        "{option}: {} knots for direction {k} ({size} control points, degree \
                         {p}); its knot vector holds control points + degree + 1 = {want} knots",
                        list.len()
                    ));
                }
                KnotVector::new(list)
                    .and_then(|kv| kv.validate_for(p, size).map(|()| kv))
                    .map_err(|e| BadInput(format!("{option} (direction {k}): {e}")))?
            }
        };
        out.push(kv);
    }
    Ok(out)
}
