//! B-spline curve evaluation `C(t_i) = Σ_j N_{j,p}(t_i) P_j` as XLA FFI handlers, with its JVP
//! and VJP with respect to the knots `τ`, the control points `P` and the parameters `t`
//! (`docs/theory/derivatives.md`, "Curves" and "Knots"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_bspline_eval` | knots `(nk,)`, control `(n, dim)`, t `(m,)` | `degree` | `C(t)` `(m, dim)` |
//! | `lekalo_bspline_jvp` | knots, control, t, [`τ̇` `(nk,)`], [`Ṗ` `(n, dim)`], [`ṫ` `(m,)`] | `degree`, `with_knots`, `with_control`, `with_parameter` | `Ċ` `(m, dim)` |
//! | `lekalo_bspline_vjp` | knots, control, t, `ḡ` `(m, dim)` | `degree`, `with_knots`, `with_control`, `with_parameter` | [`τ̄` `(nk,)`], [`P̄` `(n, dim)`], [`t̄` `(m,)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true. Each buffer
//! may have leading batch axes (the same for all). The values are
//! [`BSplineCurve::eval_batch`]'s (P&T A2.2), or for large batches ([`FAST_PER_PIECE`]) those of
//! the fast [`lekalo::CurveEvaluator`]; the JVP
//! [`BSplineCurve::eval_batch_jvp`]'s plus [`BSplineCurve::eval_batch_knot_jvp`]'s, the VJP
//! [`BSplineCurve::eval_batch_vjp`]'s and [`BSplineCurve::eval_batch_knot_vjp`]'s. For a batch
//! element with few parameters against its pieces ([`in_place`]), and no knot derivative, the
//! three are
//! [`BorrowedCurve`]'s on the operand buffers themselves (the same numbers): no copy, and only
//! the knots and control points the parameters' spans read are checked.

use lekalo::derivatives::BorrowedCurve;
use lekalo::{BSplineCurve, Points};

use super::abi::{Call, In};
use super::operands::{
    cotangents, count_attr, count_error, element, element_mut, flags, last_axis, single, tangents,
    Batch,
};

/// Parameters a polynomial piece from which the values come from the curve's fast evaluator
/// ([`lekalo::CurveEvaluator`], per-piece power form: a few ns a point, the same points as
/// `lekalo.BSplineCurve.__call__`) rather than the reference de Boor evaluation: building the
/// evaluator costs about as much as evaluating 10 to 15 parameters a piece by the reference
/// (measured for a cubic on 1000 pieces), so smaller batches, a single parameter above all,
/// keep the reference. Both agree to `1e-14` relative to the control net's scale.
pub(super) const FAST_PER_PIECE: usize = 16;

ffi_targets! {
    stem: "bspline",
    function: "bspline_eval",
    eval: eval_body,
    jvp: jvp_body,
    vjp: vjp_body,
}

/// The attributes naming the tangents (JVP) and cotangents (VJP) present, in operand order.
const KINDS: [&str; 3] = ["with_knots", "with_control", "with_parameter"];

/// Whether `m` parameters on `n` control points of `degree` are evaluated in place
/// ([`BorrowedCurve`]) rather than on a built curve: when they read fewer knots and control
/// points than building it copies and validates, `m · (degree + 1) ≤ n` (each parameter reads
/// and checks `2p + 2` knots and `p + 1` points, building checks all `n + p + 1` and `n`).
pub(super) fn in_place(m: usize, n: usize, degree: usize) -> bool {
    m.saturating_mul(degree + 1) <= n
}

/// The borrowed curve of batch element `b` (as [`curve`]).
fn borrowed<'a>(
    degree: usize,
    (knots, sk): (&In<'a>, usize),
    (control, sc): (&In<'a>, usize),
    dim: usize,
    b: usize,
) -> Result<BorrowedCurve<'a>, String> {
    let (knots, control) = (element(knots.data, sk, b), element(control.data, sc, b));
    BorrowedCurve::new(degree, knots, control, dim).map_err(|e| e.to_string())
}

/// The curve of batch element `b` (the knots and control points being the first two operands
/// of every target, their element sizes `sk` and `sc`), built (and validated) by
/// [`BSplineCurve::new`].
fn curve(
    degree: usize,
    (knots, sk): (&In<'_>, usize),
    (control, sc): (&In<'_>, usize),
    dim: usize,
    b: usize,
) -> Result<BSplineCurve, String> {
    let control = element(control.data, sc, b);
    let points = Points::from_flat(dim, control.to_vec()).map_err(|e| e.to_string())?;
    BSplineCurve::new(degree, element(knots.data, sk, b).to_vec(), points)
        .map_err(|e| e.to_string())
}

/// The knots, control points and parameters, the residuals of every target: the batch, their
/// element sizes and the dimension.
fn layout<'a>(res: &[In<'a>]) -> Result<(Batch<'a>, [usize; 3], usize), String> {
    let [knots, ctrl, t] = res else {
        return Err(count_error("arguments", 3, res.len()));
    };
    let batch = Batch::of("knots", knots.dims, 1)?;
    let sizes = [
        batch.size("knots", knots.dims, 1)?,
        batch.size("control points", ctrl.dims, 2)?,
        batch.size("u", t.dims, 1)?,
    ];
    Ok((batch, sizes, last_axis("control points", ctrl.dims)?))
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degree = count_attr(call, "degree")?;
    let Call { args, rets, .. } = call;
    let (batch, [sk, sc, st], dim) = layout(args)?;
    let values = single(rets)?;
    let sv = batch.size("values", values.dims, 2)?;
    let small = in_place(st, sc / dim.max(1), degree);
    for b in 0..batch.count {
        let (ts, out) = (
            element(args[2].data, st, b),
            element_mut(values.data, sv, b),
        );
        if small {
            let c = borrowed(degree, (&args[0], sk), (&args[1], sc), dim, b)?;
            c.eval_batch(ts, out).map_err(|e| e.to_string())?;
            continue;
        }
        let c = curve(degree, (&args[0], sk), (&args[1], sc), dim, b)?;
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
    let degree = count_attr(call, "degree")?;
    let present = flags(call, KINDS);
    let Call { args, rets, .. } = call;
    let (res, [dk, dc, dt]) = tangents(args, 3, present)?;
    let (batch, [sk, sc, st], dim) = layout(res)?;
    let tangent = single(rets)?;
    let sv = batch.size("tangent", tangent.dims, 2)?;
    if let Some(a) = dk {
        batch.expect("knot tangent", a.dims, 1, sk)?;
    }
    if let Some(a) = dc {
        batch.expect("control-point tangent", a.dims, 2, sc)?;
    }
    if let Some(a) = dt {
        batch.expect("parameter tangent", a.dims, 1, st)?;
    }
    // the knot derivative needs the built curve
    let small = dk.is_none() && in_place(st, sc / dim.max(1), degree);
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation)
    let mut values = vec![0.0; if small { 0 } else { sv }];
    let mut knot_part = vec![0.0; if dk.is_some() { sv } else { 0 }];
    for b in 0..batch.count {
        if small {
            let c = borrowed(degree, (&res[0], sk), (&res[1], sc), dim, b)?;
            c.eval_batch_jvp(
                element(res[2].data, st, b),
                dc.map(|a| element(a.data, sc, b)),
                dt.map(|a| element(a.data, st, b)),
                element_mut(tangent.data, sv, b),
            )
            .map_err(|e| e.to_string())?;
            continue;
        }
        let c = curve(degree, (&res[0], sk), (&res[1], sc), dim, b)?;
        let (ts, out) = (
            element(res[2].data, st, b),
            element_mut(tangent.data, sv, b),
        );
        c.eval_batch_jvp(
            ts,
            dc.map(|a| element(a.data, sc, b)),
            dt.map(|a| element(a.data, st, b)),
            &mut values,
            out,
        )
        .map_err(|e| e.to_string())?;
        if let Some(a) = dk {
            c.eval_batch_knot_jvp(ts, element(a.data, sk, b), &mut values, &mut knot_part)
                .map_err(|e| e.to_string())?;
            for (o, k) in out.iter_mut().zip(&knot_part) {
                *o += k;
            }
        }
    }
    Ok(())
}

fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degree = count_attr(call, "degree")?;
    let present = flags(call, KINDS);
    let Call { args, rets, .. } = call;
    let (res, [g]) = tangents(args, 3, [true])?;
    let g = g.ok_or("no cotangent")?;
    let (batch, [sk, sc, st], dim) = layout(res)?;
    let sg = batch.size("cotangent", g.dims, 2)?;
    let [mut gk, mut gc, mut gt] = cotangents(rets, present)?;
    if let Some(a) = &gk {
        batch.expect("knot cotangent", a.dims, 1, sk)?;
    }
    if let Some(a) = &gc {
        batch.expect("control-point cotangent", a.dims, 2, sc)?;
    }
    if let Some(a) = &gt {
        batch.expect("parameter cotangent", a.dims, 1, st)?;
    }
    // the knot derivative needs the built curve
    let small = gk.is_none() && in_place(st, sc / dim.max(1), degree);
    for b in 0..batch.count {
        let (ts, gb) = (element(res[2].data, st, b), element(g.data, sg, b));
        if small {
            let c = borrowed(degree, (&res[0], sk), (&res[1], sc), dim, b)?;
            c.eval_batch_vjp(
                ts,
                gb,
                gc.as_mut().map(|a| element_mut(a.data, sc, b)),
                gt.as_mut().map(|a| element_mut(a.data, st, b)),
            )
            .map_err(|e| e.to_string())?;
            continue;
        }
        let c = curve(degree, (&res[0], sk), (&res[1], sc), dim, b)?;
        if let Some(a) = gk.as_mut() {
            c.eval_batch_knot_vjp(ts, gb, element_mut(a.data, sk, b))
                .map_err(|e| e.to_string())?;
        }
        if gc.is_some() || gt.is_some() {
            c.eval_batch_vjp(
                ts,
                gb,
                gc.as_mut().map(|a| element_mut(a.data, sc, b)),
                gt.as_mut().map(|a| element_mut(a.data, st, b)),
            )
            .map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}
