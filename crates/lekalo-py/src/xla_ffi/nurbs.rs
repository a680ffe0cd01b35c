//! NURBS curve evaluation `C(t) = Σ_j N_{j,p}(t) w_j P_j / Σ_j N_{j,p}(t) w_j` as XLA FFI
//! handlers, with its JVP and VJP with respect to the knots `τ`, the Euclidean control points
//! `P`, the weights `w` and the parameters `t` (`docs/theory/derivatives.md`, "NURBS curves"
//! and "Knots"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_nurbs_eval` | knots `(nk,)`, control `(n, dim)`, weights `(n,)`, t `(m,)` | `degree` | `C(t)` `(m, dim)` |
//! | `lekalo_nurbs_jvp` | knots, control, weights, t, [`τ̇` `(nk,)`], [`Ṗ` `(n, dim)`], [`ẇ` `(n,)`], [`ṫ` `(m,)`] | `degree`, `with_knots`, `with_control`, `with_weight`, `with_parameter` | `Ċ` `(m, dim)` |
//! | `lekalo_nurbs_vjp` | knots, control, weights, t, `ḡ` `(m, dim)` | `degree`, `with_knots`, `with_control`, `with_weight`, `with_parameter` | [`τ̄` `(nk,)`], [`P̄` `(n, dim)`], [`w̄` `(n,)`], [`t̄` `(m,)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have leading batch axes (the same for all). The values are [`NurbsCurve::eval_batch`]'s
//! (P&T A4.1), or for large batches ([`FAST_PER_PIECE`] parameters a piece) those of the fast
//! [`lekalo::NurbsEvaluator`]; the JVP [`NurbsCurve::eval_batch_jvp`]'s plus
//! [`NurbsCurve::eval_batch_knot_jvp`]'s, the VJP [`NurbsCurve::eval_batch_vjp`]'s and
//! [`NurbsCurve::eval_batch_knot_vjp`]'s. For a batch element with few parameters against its
//! control points (`curve.rs`'s [`in_place`]), and no knot derivative, the three are
//! [`BorrowedNurbs`]'s on the operand buffers themselves (the same numbers): no copy, and only
//! the knots, control points and weights the parameters' spans read are checked.

use lekalo::derivatives::BorrowedNurbs;
use lekalo::{NurbsCurve, Points};

use super::abi::{Call, In};
use super::curve::{in_place, FAST_PER_PIECE};
use super::operands::{
    cotangents, count_attr, count_error, element, element_mut, flags, last_axis, single, tangents,
    Batch,
};

ffi_targets! {
    stem: "nurbs",
    function: "nurbs_eval",
    eval: eval_body,
    jvp: jvp_body,
    vjp: vjp_body,
}

/// The attributes naming the tangents (JVP) and cotangents (VJP) present, in operand order.
const KINDS: [&str; 4] = [
    "with_knots",
    "with_control",
    "with_weight",
    "with_parameter",
];

/// The residuals of every target (knots, control points, weights, parameters): the batch, the
/// element size of each, and the dimension.
struct Layout<'a> {
    batch: Batch<'a>,
    /// Element sizes of the knots, the control points, the weights and the parameters.
    sizes: [usize; 4],
    dim: usize,
}

impl<'a> Layout<'a> {
    fn of(res: &[In<'a>]) -> Result<Self, String> {
        let [knots, ctrl, w, t] = res else {
            return Err(count_error("arguments", 4, res.len()));
        };
        let batch = Batch::of("knots", knots.dims, 1)?;
        let sizes = [
            batch.size("knots", knots.dims, 1)?,
            batch.size("control points", ctrl.dims, 2)?,
            batch.size("weights", w.dims, 1)?,
            batch.size("u", t.dims, 1)?,
        ];
        let dim = last_axis("control points", ctrl.dims)?;
        Ok(Layout { batch, sizes, dim })
    }

    /// The curve of batch element `b`, built (and validated: sorted knots, one positive weight
    /// a control point) by [`NurbsCurve::new`].
    fn curve(&self, degree: usize, res: &[In<'_>], b: usize) -> Result<NurbsCurve, String> {
        let [sk, sc, sw, _] = self.sizes;
        let control = element(res[1].data, sc, b).to_vec();
        let points = Points::from_flat(self.dim, control).map_err(|e| e.to_string())?;
        let (knots, weights) = (element(res[0].data, sk, b), element(res[2].data, sw, b));
        NurbsCurve::new(degree, knots.to_vec(), points, weights.to_vec()).map_err(|e| e.to_string())
    }

    /// The curve of batch element `b` on the operand buffers, checked only where read.
    fn borrowed<'d>(
        &self,
        degree: usize,
        res: &'d [In<'_>],
        b: usize,
    ) -> Result<BorrowedNurbs<'d>, String> {
        let [sk, sc, sw, _] = self.sizes;
        let (knots, control) = (element(res[0].data, sk, b), element(res[1].data, sc, b));
        BorrowedNurbs::new(
            degree,
            knots,
            control,
            element(res[2].data, sw, b),
            self.dim,
        )
        .map_err(|e| e.to_string())
    }

    /// Whether the batch elements are evaluated in place ([`in_place`]).
    fn small(&self, degree: usize) -> bool {
        let n = self.sizes[1] / self.dim.max(1);
        in_place(self.sizes[3], n, degree)
    }

    /// The parameters of batch element `b`.
    fn ts<'d>(&self, res: &'d [In<'_>], b: usize) -> &'d [f64] {
        element(res[3].data, self.sizes[3], b)
    }
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degree = count_attr(call, "degree")?;
    let Call { args, rets, .. } = call;
    let layout = Layout::of(args)?;
    let values = single(rets)?;
    let sv = layout.batch.size("values", values.dims, 2)?;
    let small = layout.small(degree);
    for b in 0..layout.batch.count {
        let (ts, out) = (layout.ts(args, b), element_mut(values.data, sv, b));
        if small {
            let c = layout.borrowed(degree, args, b)?;
            c.eval_batch(ts, out).map_err(|e| e.to_string())?;
            continue;
        }
        let c = layout.curve(degree, args, b)?;
        let pieces = c.homogeneous().control_points().len() - degree;
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
    let (res, [dk, dc, dw, dt]) = tangents(args, 4, present)?;
    let layout = Layout::of(res)?;
    let (batch, [sk, sc, sw, st]) = (&layout.batch, layout.sizes);
    let tangent = single(rets)?;
    let sv = batch.size("tangent", tangent.dims, 2)?;
    for (a, what, core, size) in [
        (dk, "knot tangent", 1, sk),
        (dc, "control-point tangent", 2, sc),
        (dw, "weight tangent", 1, sw),
        (dt, "parameter tangent", 1, st),
    ] {
        if let Some(a) = a {
            batch.expect(what, a.dims, core, size)?;
        }
    }
    // the knot derivative needs the built curve
    let small = dk.is_none() && layout.small(degree);
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation)
    let mut values = vec![0.0; if small { 0 } else { sv }];
    let mut knot_part = vec![0.0; if dk.is_some() { sv } else { 0 }];
    for b in 0..batch.count {
        let out = element_mut(tangent.data, sv, b);
        if small {
            let c = layout.borrowed(degree, res, b)?;
            c.eval_batch_jvp(
                layout.ts(res, b),
                dc.map(|a| element(a.data, sc, b)),
                dw.map(|a| element(a.data, sw, b)),
                dt.map(|a| element(a.data, st, b)),
                out,
            )
            .map_err(|e| e.to_string())?;
            continue;
        }
        let c = layout.curve(degree, res, b)?;
        let ts = layout.ts(res, b);
        c.eval_batch_jvp(
            ts,
            dc.map(|a| element(a.data, sc, b)),
            dw.map(|a| element(a.data, sw, b)),
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
    let (res, [g]) = tangents(args, 4, [true])?;
    let g = g.ok_or("no cotangent")?;
    let layout = Layout::of(res)?;
    let (batch, [sk, sc, sw, st]) = (&layout.batch, layout.sizes);
    let sg = batch.size("cotangent", g.dims, 2)?;
    let [mut gk, mut gc, mut gw, mut gt] = cotangents(rets, present)?;
    for (a, what, core, size) in [
        (&gk, "knot cotangent", 1, sk),
        (&gc, "control-point cotangent", 2, sc),
        (&gw, "weight cotangent", 1, sw),
        (&gt, "parameter cotangent", 1, st),
    ] {
        if let Some(a) = a {
            batch.expect(what, a.dims, core, size)?;
        }
    }
    // the knot derivative needs the built curve
    let small = gk.is_none() && layout.small(degree);
    let wants_rest = gc.is_some() || gw.is_some() || gt.is_some();
    for b in 0..batch.count {
        let (ts, gb) = (layout.ts(res, b), element(g.data, sg, b));
        if small {
            let c = layout.borrowed(degree, res, b)?;
            c.eval_batch_vjp(
                ts,
                gb,
                gc.as_mut().map(|a| element_mut(a.data, sc, b)),
                gw.as_mut().map(|a| element_mut(a.data, sw, b)),
                gt.as_mut().map(|a| element_mut(a.data, st, b)),
            )
            .map_err(|e| e.to_string())?;
            continue;
        }
        let c = layout.curve(degree, res, b)?;
        if let Some(a) = gk.as_mut() {
            c.eval_batch_knot_vjp(ts, gb, element_mut(a.data, sk, b))
                .map_err(|e| e.to_string())?;
        }
        if wants_rest {
            c.eval_batch_vjp(
                ts,
                gb,
                gc.as_mut().map(|a| element_mut(a.data, sc, b)),
                gw.as_mut().map(|a| element_mut(a.data, sw, b)),
                gt.as_mut().map(|a| element_mut(a.data, st, b)),
            )
            .map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}
