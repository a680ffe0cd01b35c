//! B-spline curve evaluation `C(t_i) = Σ_j N_{j,p}(t_i) P_j` as XLA FFI handlers, with its JVP
//! and VJP with respect to the control points `P` and the parameters `t`
//! (`docs/theory/derivatives.md`, "Curves"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_bspline_eval` | knots `(nk,)`, control `(n, dim)`, t `(m,)` | `degree` | `C(t)` `(m, dim)` |
//! | `lekalo_bspline_jvp` | knots, control, t, [`Ṗ` `(n, dim)`], [`ṫ` `(m,)`] | `degree`, `with_control`, `with_parameter` | `Ċ` `(m, dim)` |
//! | `lekalo_bspline_vjp` | knots, control, t, `ḡ` `(m, dim)` | `degree`, `with_control`, `with_parameter` | [`P̄` `(n, dim)`], [`t̄` `(m,)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true. Each buffer
//! may have leading batch axes (the same for all). The values are
//! [`BSplineCurve::eval_batch`]'s (P&T A2.2), or for large batches ([`FAST_PER_PIECE`]) those of
//! the fast [`lekalo::CurveEvaluator`]; the JVP
//! [`BSplineCurve::eval_batch_jvp`]'s, the VJP [`BSplineCurve::eval_batch_vjp`]'s.

use lekalo::{BSplineCurve, Points};

use super::abi::{handle, Call, CallFrame, XlaError};
use super::batch_layout;

/// Parameters a polynomial piece from which the values come from the curve's fast evaluator
/// ([`lekalo::CurveEvaluator`], per-piece power form: a few ns a point, the same points as
/// `lekalo.BSplineCurve.__call__`) rather than the reference de Boor evaluation: building the
/// evaluator costs about as much as evaluating 10 to 15 parameters a piece by the reference
/// (measured for a cubic on 1000 pieces), so smaller batches, a single parameter above all,
/// keep the reference. Both agree to `1e-14` relative to the control net's scale.
const FAST_PER_PIECE: usize = 16;

/// An `XLA_FFI_Handler`.
pub(super) type Handler = extern "C" fn(*mut CallFrame) -> *mut XlaError;

/// The handlers of this module, by target name.
pub(super) const HANDLERS: &[(&str, Handler)] = &[
    ("lekalo_bspline_eval", bspline_eval),
    ("lekalo_bspline_jvp", bspline_jvp),
    ("lekalo_bspline_vjp", bspline_vjp),
];

extern "C" fn bspline_eval(frame: *mut CallFrame) -> *mut XlaError {
    handle(frame, "lekalo.jax.bspline_eval", eval_body)
}

extern "C" fn bspline_jvp(frame: *mut CallFrame) -> *mut XlaError {
    handle(
        frame,
        "lekalo.jax.bspline_eval (forward derivative)",
        jvp_body,
    )
}

extern "C" fn bspline_vjp(frame: *mut CallFrame) -> *mut XlaError {
    handle(
        frame,
        "lekalo.jax.bspline_eval (reverse derivative)",
        vjp_body,
    )
}

/// The `degree` attribute and the two optional-buffer flags (false when absent).
fn attributes(call: &Call<'_>) -> Result<(usize, bool, bool), String> {
    let degree = call.attr("degree")?;
    let degree =
        usize::try_from(degree).map_err(|_| format!("degree must be >= 0, got {degree}"))?;
    let flag = |name| call.attr(name).map(|v| v != 0).unwrap_or(false);
    Ok((degree, flag("with_control"), flag("with_parameter")))
}

/// Element `b` of a batch of elements of `size` numbers.
fn element(data: &[f64], size: usize, b: usize) -> &[f64] {
    &data[b * size..(b + 1) * size]
}

fn element_mut(data: &mut [f64], size: usize, b: usize) -> &mut [f64] {
    &mut data[b * size..(b + 1) * size]
}

/// The dimension of the control points: the last axis of `(..., n, dim)`.
fn dim_of(dims: &[i64]) -> Result<usize, String> {
    dims.last()
        .and_then(|&d| usize::try_from(d).ok())
        .ok_or_else(|| format!("control points of shape {dims:?}: expected (n, dim)"))
}

/// The curve of batch element `b` (the knots and control points being the first two operands
/// of every target, their element sizes `size[0]` and `size[1]`), built (and validated) by
/// [`BSplineCurve::new`].
fn curve(
    degree: usize,
    knots: &[f64],
    control: &[f64],
    size: &[usize],
    b: usize,
    dim: usize,
) -> Result<BSplineCurve, String> {
    let (knots, control) = (element(knots, size[0], b), element(control, size[1], b));
    let points = Points::from_flat(dim, control.to_vec()).map_err(|e| e.to_string())?;
    BSplineCurve::new(degree, knots.to_vec(), points).map_err(|e| e.to_string())
}

fn count_error(what: &str, want: usize, got: usize) -> String {
    format!("expected {want} {what}, got {got} (lekalo.jax and its native module disagree)")
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let (degree, _, _) = attributes(call)?;
    let Call { args, rets, .. } = call;
    let [knots, ctrl, t] = &args[..] else {
        return Err(count_error("arguments", 3, args.len()));
    };
    let [values] = &mut rets[..] else {
        return Err(count_error("results", 1, rets.len()));
    };
    let dim = dim_of(ctrl.dims)?;
    let (batch, size) = batch_layout(&[
        ("knots", knots.dims, 1),
        ("control points", ctrl.dims, 2),
        ("u", t.dims, 1),
        ("values", values.dims, 2),
    ])?;
    for b in 0..batch {
        let c = curve(degree, knots.data, ctrl.data, &size, b, dim)?;
        let (ts, out) = (
            element(t.data, size[2], b),
            element_mut(values.data, size[3], b),
        );
        let pieces = c.control_points().len() - degree;
        let done = if ts.len() >= FAST_PER_PIECE * pieces {
            c.evaluator().eval_batch(ts, out)
        } else {
            c.eval_batch(ts, out)
        };
        done.map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
    let (degree, with_control, with_parameter) = attributes(call)?;
    let Call { args, rets, .. } = call;
    let want = 3 + usize::from(with_control) + usize::from(with_parameter);
    if args.len() != want {
        return Err(count_error("arguments", want, args.len()));
    }
    let [tangent] = &mut rets[..] else {
        return Err(count_error("results", 1, rets.len()));
    };
    let (knots, ctrl, t) = (&args[0], &args[1], &args[2]);
    let dc = with_control.then(|| &args[3]);
    let dt = with_parameter.then(|| &args[args.len() - 1]);
    let dim = dim_of(ctrl.dims)?;
    let mut layout = vec![
        ("knots", knots.dims, 1),
        ("control points", ctrl.dims, 2),
        ("u", t.dims, 1),
        ("tangent", tangent.dims, 2),
    ];
    layout.extend(dc.map(|a| ("control-point tangent", a.dims, 2)));
    layout.extend(dt.map(|a| ("parameter tangent", a.dims, 1)));
    let (batch, size) = batch_layout(&layout)?;
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation)
    let mut values = vec![0.0; size[3]];
    for b in 0..batch {
        let c = curve(degree, knots.data, ctrl.data, &size, b, dim)?;
        let dc_b = dc.map(|a| element(a.data, size[1], b));
        let dt_b = dt.map(|a| element(a.data, size[2], b));
        let ts = element(t.data, size[2], b);
        c.eval_batch_jvp(
            ts,
            dc_b,
            dt_b,
            &mut values,
            element_mut(tangent.data, size[3], b),
        )
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
    let (degree, with_control, with_parameter) = attributes(call)?;
    let Call { args, rets, .. } = call;
    let [knots, ctrl, t, g] = &args[..] else {
        return Err(count_error("arguments", 4, args.len()));
    };
    let want = usize::from(with_control) + usize::from(with_parameter);
    if rets.len() != want {
        return Err(count_error("results", want, rets.len()));
    }
    let dim = dim_of(ctrl.dims)?;
    let mut layout = vec![
        ("knots", knots.dims, 1),
        ("control points", ctrl.dims, 2),
        ("u", t.dims, 1),
        ("cotangent", g.dims, 2),
    ];
    let (gc, gt) = match &mut rets[..] {
        [] => (None, None),
        [one] if with_control => (Some(one), None),
        [one] => (None, Some(one)),
        [gc, gt] => (Some(gc), Some(gt)),
        _ => return Err(count_error("results", want, rets.len())),
    };
    layout.extend(gc.as_ref().map(|a| ("control-point cotangent", a.dims, 2)));
    layout.extend(gt.as_ref().map(|a| ("parameter cotangent", a.dims, 1)));
    let (batch, size) = batch_layout(&layout)?;
    let (mut gc, mut gt) = (gc, gt);
    for b in 0..batch {
        let c = curve(degree, knots.data, ctrl.data, &size, b, dim)?;
        let gc_b = gc.as_mut().map(|a| element_mut(a.data, size[1], b));
        let gt_b = gt.as_mut().map(|a| element_mut(a.data, size[2], b));
        let (ts, gb) = (element(t.data, size[2], b), element(g.data, size[3], b));
        c.eval_batch_vjp(ts, gb, gc_b, gt_b)
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}
