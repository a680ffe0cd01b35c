//! Evaluation of a tensor-product B-spline in `N` variables,
//! `S(x) = Σ_k Π_a N_{k_a,p_a}(x_a) P_k`, as XLA FFI handlers, with its JVP and VJP with
//! respect to the knots of each direction, the control net `P` and the points `x`
//! (`docs/theory/derivatives.md#tensor-product-splines` and "Knots"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_tensor_eval` | `knots_0` … `knots_{N−1}` (1-D each), net `(n_0, …, n_{N−1}, dim)`, x `(m, N)` | `n_vars`, `degree_0` … `degree_{N−1}` | `S` `(m, dim)` |
//! | `lekalo_tensor_jvp` | the same, [`τ̇⁰`] … [`τ̇ᴺ⁻¹`] (as the knots), [`Ṗ` as the net], [`ẋ` `(m, N)`] | the same, `with_knots_0` … `with_knots_{N−1}`, `with_control`, `with_point` | `Ṡ` `(m, dim)` |
//! | `lekalo_tensor_vjp` | the same, `ḡ` `(m, dim)` | the same, `with_knots_0` … `with_knots_{N−1}`, `with_control`, `with_point` | [`τ̄⁰`] … [`τ̄ᴺ⁻¹`], [`P̄` as the net], [`x̄` `(m, N)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have leading batch axes (the same for all). The values are
//! [`TensorBSpline::eval_batch`]'s (P&T A2.2 a direction), the JVP
//! [`TensorBSpline::eval_batch_jvp`]'s plus [`TensorBSpline::eval_batch_knot_jvp`]'s, the VJP
//! [`TensorBSpline::eval_batch_vjp`]'s and [`TensorBSpline::eval_batch_knot_vjp`]'s. For a
//! batch element with few points against its net ([`in_place`]), and no knot derivative, the
//! three are [`BorrowedTensor`]'s on the operand buffers themselves (the same numbers): no copy
//! of the net, and only the knots and net points the points' cells read are checked.

use lekalo::derivatives::BorrowedTensor;
use lekalo::{Points, TensorBSpline};

use super::abi::{Call, In};
use super::operands::{
    cotangents_of, count_attr, count_error, element, element_mut, flag, last_axis, single,
    tangents, tangents_of, Batch,
};

ffi_targets! {
    stem: "tensor",
    function: "tensor_bspline_eval",
    eval: eval_body,
    jvp: jvp_body,
    vjp: vjp_body,
}

/// Which tangents (JVP) and cotangents (VJP) are present, in operand order: the attributes
/// `with_knots_0` … `with_knots_{N−1}`, then those of `rest` (`with_control` and `with_point`
/// here; the rational targets add `with_weight` between them).
pub(super) fn present(call: &Call<'_>, n: usize, rest: &[&str]) -> Vec<bool> {
    let knots = (0..n).map(|a| flag(call, &format!("with_knots_{a}")));
    knots.chain(rest.iter().map(|r| flag(call, r))).collect()
}

/// The degrees, one a variable (attributes `n_vars`, `degree_0`, …), of a tensor-product
/// `what` ("spline", "NURBS").
pub(super) fn degrees(call: &Call<'_>, what: &str) -> Result<Vec<usize>, String> {
    let n = count_attr(call, "n_vars")?;
    if n == 0 {
        return Err(format!(
            "a tensor-product {what} needs at least one variable"
        ));
    }
    (0..n)
        .map(|a| count_attr(call, &format!("degree_{a}")))
        .collect()
}

/// The residuals of every target (`N` knot vectors, the net, the points): the batch, the
/// element size of each (knots first, then the net and the points) and the dimension.
struct Layout<'a> {
    batch: Batch<'a>,
    sizes: Vec<usize>,
    dim: usize,
}

impl<'a> Layout<'a> {
    fn of(res: &[In<'a>], degrees: &[usize]) -> Result<Self, String> {
        let n = degrees.len();
        if res.len() != n + 2 {
            return Err(count_error("arguments", n + 2, res.len()));
        }
        let (knots, net, x) = (&res[..n], &res[n], &res[n + 1]);
        let batch = Batch::of("knots[0]", knots[0].dims, 1)?;
        let mut sizes = Vec::with_capacity(n + 2);
        for (a, k) in knots.iter().enumerate() {
            sizes.push(batch.size(&format!("knots[{a}]"), k.dims, 1)?);
        }
        sizes.push(batch.size("control net", net.dims, n + 1)?);
        sizes.push(batch.size("points", x.dims, 2)?);
        if x.dims.last().and_then(|&d| usize::try_from(d).ok()) != Some(n) {
            return Err(format!(
                "points of shape {:?}: the last axis must hold the {n} coordinates",
                x.dims
            ));
        }
        // the net's axes must be those the knots and degrees imply (their product alone is
        // what the constructor can check)
        let axes = &net.dims[net.dims.len() - n - 1..net.dims.len() - 1];
        for (a, ((&size, &p), &axis)) in sizes.iter().zip(degrees).zip(axes).enumerate() {
            if usize::try_from(axis).ok() != size.checked_sub(p + 1) {
                return Err(format!(
                    "control net of shape {:?}: axis {a} has {axis} points, knots[{a}] \
                     ({size} knots) of degree {p} need {}",
                    net.dims,
                    size.saturating_sub(p + 1)
                ));
            }
        }
        let dim = last_axis("control net", net.dims)?;
        Ok(Layout { batch, sizes, dim })
    }

    /// The spline of batch element `b`, built (and validated) by [`TensorBSpline::new`].
    fn spline(&self, degrees: &[usize], res: &[In<'_>], b: usize) -> Result<TensorBSpline, String> {
        let n = degrees.len();
        let knots = (0..n)
            .map(|a| element(res[a].data, self.sizes[a], b).to_vec())
            .collect();
        let net = element(res[n].data, self.sizes[n], b).to_vec();
        let points = Points::from_flat(self.dim, net).map_err(|e| e.to_string())?;
        TensorBSpline::new(degrees.to_vec(), knots, points).map_err(|e| e.to_string())
    }

    /// The spline of batch element `b` on the operand buffers (as [`Layout::spline`]).
    fn borrowed<'r>(
        &self,
        degrees: &'r [usize],
        res: &[In<'r>],
        b: usize,
    ) -> Result<BorrowedTensor<'r>, String> {
        let n = degrees.len();
        let knots = (0..n)
            .map(|a| element(res[a].data, self.sizes[a], b))
            .collect();
        let net = element(res[n].data, self.sizes[n], b);
        BorrowedTensor::new(degrees, knots, net, self.dim).map_err(|e| e.to_string())
    }

    /// Whether `m` points on this net are evaluated in place ([`BorrowedTensor`]) rather than
    /// on a built spline: when they read fewer net points than building it copies and
    /// validates, `m · Π_a (p_a + 1) ≤ Π_a n_a` (each point reads and checks a
    /// `Π_a (p_a + 1)` block and `2p_a + 2` knots a direction).
    fn in_place(&self, degrees: &[usize]) -> bool {
        let n = degrees.len();
        let m = self.sizes[n + 1] / n.max(1);
        let block = degrees
            .iter()
            .fold(1usize, |acc, p| acc.saturating_mul(p + 1));
        m.saturating_mul(block) <= self.sizes[n] / self.dim.max(1)
    }

    /// The element sizes of the net and of the points.
    fn net_and_points(&self) -> (usize, usize) {
        let n = self.sizes.len() - 2;
        (self.sizes[n], self.sizes[n + 1])
    }
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call, "spline")?;
    let Call { args, rets, .. } = call;
    let layout = Layout::of(args, &degrees)?;
    let (_, sx) = layout.net_and_points();
    let values = single(rets)?;
    let sv = layout.batch.size("values", values.dims, 2)?;
    let x = &args[degrees.len() + 1];
    let small = layout.in_place(&degrees);
    for b in 0..layout.batch.count {
        let (xs, out) = (element(x.data, sx, b), element_mut(values.data, sv, b));
        let done = if small {
            layout.borrowed(&degrees, args, b)?.eval_batch(xs, out)
        } else {
            layout.spline(&degrees, args, b)?.eval_batch(xs, None, out)
        };
        done.map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call, "spline")?;
    let n = degrees.len();
    let present = present(call, n, &["with_control", "with_point"]);
    let Call { args, rets, .. } = call;
    let (res, tangents) = tangents_of(args, n + 2, &present)?;
    let (dk, [dc, dx]) = (&tangents[..n], [tangents[n], tangents[n + 1]]);
    let layout = Layout::of(res, &degrees)?;
    let (batch, (sn, sx)) = (&layout.batch, layout.net_and_points());
    let tangent = single(rets)?;
    let sv = batch.size("tangent", tangent.dims, 2)?;
    for (a, d) in dk.iter().enumerate() {
        if let Some(d) = d {
            batch.expect(&format!("knot tangent {a}"), d.dims, 1, layout.sizes[a])?;
        }
    }
    if let Some(a) = dc {
        batch.expect("control-net tangent", a.dims, n + 1, sn)?;
    }
    if let Some(a) = dx {
        batch.expect("point tangent", a.dims, 2, sx)?;
    }
    // the knot derivatives need the built spline
    let knots = dk.iter().any(Option::is_some);
    let small = !knots && layout.in_place(&degrees);
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation)
    let mut values = vec![0.0; if small { 0 } else { sv }];
    let mut knot_part = vec![0.0; if knots { sv } else { 0 }];
    for b in 0..batch.count {
        let xs = element(res[n + 1].data, sx, b);
        let dc = dc.map(|a| element(a.data, sn, b));
        let dx = dx.map(|a| element(a.data, sx, b));
        let out = element_mut(tangent.data, sv, b);
        if small {
            let s = layout.borrowed(&degrees, res, b)?;
            s.eval_batch_jvp(xs, dc, dx, out)
                .map_err(|e| e.to_string())?;
            continue;
        }
        let s = layout.spline(&degrees, res, b)?;
        s.eval_batch_jvp(xs, dc, dx, &mut values, out)
            .map_err(|e| e.to_string())?;
        if knots {
            let dk: Vec<Option<&[f64]>> = (dk.iter().enumerate())
                .map(|(a, d)| d.map(|d| element(d.data, layout.sizes[a], b)))
                .collect();
            s.eval_batch_knot_jvp(xs, &dk, &mut values, &mut knot_part)
                .map_err(|e| e.to_string())?;
            for (o, k) in out.iter_mut().zip(&knot_part) {
                *o += k;
            }
        }
    }
    Ok(())
}

fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call, "spline")?;
    let n = degrees.len();
    let present = present(call, n, &["with_control", "with_point"]);
    let Call { args, rets, .. } = call;
    let (res, [g]) = tangents(args, n + 2, [true])?;
    let g = g.ok_or("no cotangent")?;
    let layout = Layout::of(res, &degrees)?;
    let (batch, (sn, sx)) = (&layout.batch, layout.net_and_points());
    let sg = batch.size("cotangent", g.dims, 2)?;
    let mut gk = cotangents_of(rets, &present)?;
    let (mut gx, mut gc) = (gk.pop().flatten(), gk.pop().flatten());
    for (a, c) in gk.iter().enumerate() {
        if let Some(c) = c {
            batch.expect(&format!("knot cotangent {a}"), c.dims, 1, layout.sizes[a])?;
        }
    }
    if let Some(a) = &gc {
        batch.expect("control-net cotangent", a.dims, n + 1, sn)?;
    }
    if let Some(a) = &gx {
        batch.expect("point cotangent", a.dims, 2, sx)?;
    }
    // the knot derivatives need the built spline
    let knots = gk.iter().any(Option::is_some);
    let small = !knots && layout.in_place(&degrees);
    for b in 0..batch.count {
        let (xs, g) = (element(res[n + 1].data, sx, b), element(g.data, sg, b));
        let gc = gc.as_mut().map(|a| element_mut(a.data, sn, b));
        let gx = gx.as_mut().map(|a| element_mut(a.data, sx, b));
        if small {
            layout
                .borrowed(&degrees, res, b)?
                .eval_batch_vjp(xs, g, gc, gx)
                .map_err(|e| e.to_string())?;
            continue;
        }
        let s = layout.spline(&degrees, res, b)?;
        if knots {
            let mut bufs: Vec<Option<&mut [f64]>> = (gk.iter_mut().enumerate())
                .map(|(a, c)| c.as_mut().map(|c| element_mut(c.data, layout.sizes[a], b)))
                .collect();
            s.eval_batch_knot_vjp(xs, g, &mut bufs)
                .map_err(|e| e.to_string())?;
        }
        if gc.is_some() || gx.is_some() {
            s.eval_batch_vjp(xs, g, gc, gx).map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}
