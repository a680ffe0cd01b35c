//! Evaluation of a tensor-product NURBS in `N` variables,
//! `S(x) = Σ_k B_k(x) w_k P_k / Σ_k B_k(x) w_k`, `B_k = Π_a N_{k_a,p_a}(x_a)`, as XLA FFI
//! handlers, with its JVP and VJP with respect to the knots of each direction, the Euclidean
//! control net `P`, the weights `w` and the points `x` (`docs/theory/derivatives.md`, "NURBS
//! surfaces and N-variate NURBS" and "Knots"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_tensor_nurbs_eval` | `knots_0` … `knots_{N−1}` (1-D each), net `(n_0, …, n_{N−1}, dim)`, weights `(n_0, …, n_{N−1})`, x `(m, N)` | `n_vars`, `degree_0` … `degree_{N−1}` | `S` `(m, dim)` |
//! | `lekalo_tensor_nurbs_jvp` | the same, [`τ̇⁰`] … [`τ̇ᴺ⁻¹`], [`Ṗ` as the net], [`ẇ` as the weights], [`ẋ` `(m, N)`] | the same, `with_knots_0` … `with_knots_{N−1}`, `with_control`, `with_weight`, `with_point` | `Ṡ` `(m, dim)` |
//! | `lekalo_tensor_nurbs_vjp` | the same, `ḡ` `(m, dim)` | as the JVP's | [`τ̄⁰`] … [`τ̄ᴺ⁻¹`], [`P̄`], [`w̄`], [`x̄`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have leading batch axes (the same for all). The values are [`TensorNurbs::eval_batch`]'s,
//! the JVP [`TensorNurbs::eval_batch_jvp`]'s plus [`TensorNurbs::eval_batch_knot_jvp`]'s, the
//! VJP [`TensorNurbs::eval_batch_vjp`]'s and [`TensorNurbs::eval_batch_knot_vjp`]'s, on the
//! spline built (and validated) for each batch element.

use lekalo::{Points, TensorNurbs};

use super::abi::{Call, In};
use super::operands::{
    cotangents_of, count_error, element, element_mut, last_axis, single, tangents, tangents_of,
    Batch,
};
use super::tensor::{degrees, present};

ffi_targets! {
    stem: "tensor_nurbs",
    function: "tensor_nurbs_eval",
    eval: eval_body,
    jvp: jvp_body,
    vjp: vjp_body,
}

/// The residuals of every target (`N` knot vectors, the net, the weights, the points): the
/// batch, the element size of each (knots first, then the net, the weights and the points) and
/// the dimension.
struct Layout<'a> {
    batch: Batch<'a>,
    sizes: Vec<usize>,
    dim: usize,
}

impl<'a> Layout<'a> {
    fn of(res: &[In<'a>], degrees: &[usize]) -> Result<Self, String> {
        let n = degrees.len();
        if res.len() != n + 3 {
            return Err(count_error("arguments", n + 3, res.len()));
        }
        let (knots, net, w, x) = (&res[..n], &res[n], &res[n + 1], &res[n + 2]);
        let batch = Batch::of("knots[0]", knots[0].dims, 1)?;
        let mut sizes = Vec::with_capacity(n + 3);
        for (a, k) in knots.iter().enumerate() {
            sizes.push(batch.size(&format!("knots[{a}]"), k.dims, 1)?);
        }
        sizes.push(batch.size("control net", net.dims, n + 1)?);
        sizes.push(batch.size("weights", w.dims, n)?);
        sizes.push(batch.size("points", x.dims, 2)?);
        if x.dims.last().and_then(|&d| usize::try_from(d).ok()) != Some(n) {
            return Err(format!(
                "points of shape {:?}: the last axis must hold the {n} coordinates",
                x.dims
            ));
        }
        // the net's axes must be those the knots and degrees imply, the weights' the net's
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
        if w.dims[w.dims.len() - n..] != *axes {
            return Err(format!(
                "weights of shape {:?}: one a net point, the net's shape {axes:?}",
                w.dims
            ));
        }
        let dim = last_axis("control net", net.dims)?;
        Ok(Layout { batch, sizes, dim })
    }

    /// The spline of batch element `b`, built (and validated: sorted knots, one positive weight
    /// a net point) by [`TensorNurbs::new`].
    fn spline(&self, degrees: &[usize], res: &[In<'_>], b: usize) -> Result<TensorNurbs, String> {
        let n = degrees.len();
        let knots = (0..n)
            .map(|a| element(res[a].data, self.sizes[a], b).to_vec())
            .collect();
        let net = element(res[n].data, self.sizes[n], b).to_vec();
        let points = Points::from_flat(self.dim, net).map_err(|e| e.to_string())?;
        let w = element(res[n + 1].data, self.sizes[n + 1], b);
        TensorNurbs::new(degrees.to_vec(), knots, points, w).map_err(|e| e.to_string())
    }

    /// The element sizes of the net, the weights and the points.
    fn net_weights_points(&self) -> (usize, usize, usize) {
        let n = self.sizes.len() - 3;
        (self.sizes[n], self.sizes[n + 1], self.sizes[n + 2])
    }
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call, "NURBS")?;
    let Call { args, rets, .. } = call;
    let layout = Layout::of(args, &degrees)?;
    let (_, _, sx) = layout.net_weights_points();
    let values = single(rets)?;
    let sv = layout.batch.size("values", values.dims, 2)?;
    let x = &args[degrees.len() + 2];
    for b in 0..layout.batch.count {
        let (xs, out) = (element(x.data, sx, b), element_mut(values.data, sv, b));
        let s = layout.spline(&degrees, args, b)?;
        s.eval_batch(xs, out).map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call, "NURBS")?;
    let n = degrees.len();
    let present = present(call, n, &["with_control", "with_weight", "with_point"]);
    let Call { args, rets, .. } = call;
    let (res, tangents) = tangents_of(args, n + 3, &present)?;
    let (dk, [dc, dw, dx]) = (
        &tangents[..n],
        [tangents[n], tangents[n + 1], tangents[n + 2]],
    );
    let layout = Layout::of(res, &degrees)?;
    let (batch, (sn, sw, sx)) = (&layout.batch, layout.net_weights_points());
    let tangent = single(rets)?;
    let sv = batch.size("tangent", tangent.dims, 2)?;
    for (a, d) in dk.iter().enumerate() {
        if let Some(d) = d {
            batch.expect(&format!("knot tangent {a}"), d.dims, 1, layout.sizes[a])?;
        }
    }
    for (a, what, core, size) in [
        (dc, "control-net tangent", n + 1, sn),
        (dw, "weight tangent", n, sw),
        (dx, "point tangent", 2, sx),
    ] {
        if let Some(a) = a {
            batch.expect(what, a.dims, core, size)?;
        }
    }
    let knots = dk.iter().any(Option::is_some);
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation)
    let mut values = vec![0.0; sv];
    let mut knot_part = vec![0.0; if knots { sv } else { 0 }];
    for b in 0..batch.count {
        let xs = element(res[n + 2].data, sx, b);
        let dc = dc.map(|a| element(a.data, sn, b));
        let dw = dw.map(|a| element(a.data, sw, b));
        let dx = dx.map(|a| element(a.data, sx, b));
        let out = element_mut(tangent.data, sv, b);
        let s = layout.spline(&degrees, res, b)?;
        s.eval_batch_jvp(xs, dc, dw, dx, &mut values, out)
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
    let degrees = degrees(call, "NURBS")?;
    let n = degrees.len();
    let present = present(call, n, &["with_control", "with_weight", "with_point"]);
    let Call { args, rets, .. } = call;
    let (res, [g]) = tangents(args, n + 3, [true])?;
    let g = g.ok_or("no cotangent")?;
    let layout = Layout::of(res, &degrees)?;
    let (batch, (sn, sw, sx)) = (&layout.batch, layout.net_weights_points());
    let sg = batch.size("cotangent", g.dims, 2)?;
    let mut gk = cotangents_of(rets, &present)?;
    let (mut gx, mut gw, mut gc) = (gk.pop().flatten(), gk.pop().flatten(), gk.pop().flatten());
    for (a, c) in gk.iter().enumerate() {
        if let Some(c) = c {
            batch.expect(&format!("knot cotangent {a}"), c.dims, 1, layout.sizes[a])?;
        }
    }
    for (a, what, core, size) in [
        (&gc, "control-net cotangent", n + 1, sn),
        (&gw, "weight cotangent", n, sw),
        (&gx, "point cotangent", 2, sx),
    ] {
        if let Some(a) = a {
            batch.expect(what, a.dims, core, size)?;
        }
    }
    let knots = gk.iter().any(Option::is_some);
    for b in 0..batch.count {
        let (xs, g) = (element(res[n + 2].data, sx, b), element(g.data, sg, b));
        let gc = gc.as_mut().map(|a| element_mut(a.data, sn, b));
        let gw = gw.as_mut().map(|a| element_mut(a.data, sw, b));
        let gx = gx.as_mut().map(|a| element_mut(a.data, sx, b));
        let s = layout.spline(&degrees, res, b)?;
        if knots {
            let mut bufs: Vec<Option<&mut [f64]>> = (gk.iter_mut().enumerate())
                .map(|(a, c)| c.as_mut().map(|c| element_mut(c.data, layout.sizes[a], b)))
                .collect();
            s.eval_batch_knot_vjp(xs, g, &mut bufs)
                .map_err(|e| e.to_string())?;
        }
        if gc.is_some() || gw.is_some() || gx.is_some() {
            s.eval_batch_vjp(xs, g, gc, gw, gx)
                .map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}
