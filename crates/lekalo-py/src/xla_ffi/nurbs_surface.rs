//! NURBS surface evaluation `S(u, v) = Σ N_k(u) M_l(v) w_kl P_kl / Σ N_k(u) M_l(v) w_kl` as XLA
//! FFI handlers, with its JVP and VJP with respect to the knots of each direction, the
//! Euclidean control net `P`, the weights `w` and the parameter pairs `(u, v)`
//! (`docs/theory/derivatives.md`, "NURBS surfaces and N-variate NURBS" and "Knots"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_nurbs_surface_eval` | `knots_u` `(nku,)`, `knots_v` `(nkv,)`, net `(nu, nv, dim)`, weights `(nu, nv)`, uv `(m, 2)` | `degree_u`, `degree_v` | `S` `(m, dim)` |
//! | `lekalo_nurbs_surface_jvp` | the same, [`τ̇ᵘ`], [`τ̇ᵛ`], [`Ṗ` as the net], [`ẇ` as the weights], [`(u̇, v̇)` `(m, 2)`] | the same, `with_knots_u`, `with_knots_v`, `with_control`, `with_weight`, `with_parameter` | `Ṡ` `(m, dim)` |
//! | `lekalo_nurbs_surface_vjp` | the same, `ḡ` `(m, dim)` | as the JVP's | [`τ̄ᵘ`], [`τ̄ᵛ`], [`P̄`], [`w̄`], [`(ū, v̄)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have leading batch axes (the same for all). The values are
//! [`NurbsSurface::eval_batch`]'s (P&T A4.3), the JVP [`NurbsSurface::eval_batch_jvp`]'s plus
//! [`NurbsSurface::eval_batch_knot_jvp`]'s, the VJP [`NurbsSurface::eval_batch_vjp`]'s and
//! [`NurbsSurface::eval_batch_knot_vjp`]'s, on the surface built (and validated) for each batch
//! element.

use lekalo::{NurbsSurface, Points};

use super::abi::{Call, In};
use super::operands::{
    cotangents, count_error, element, element_mut, flags, last_axis, single, tangents, Batch,
};
use super::surface::{degrees, pairs};

ffi_targets! {
    stem: "nurbs_surface",
    function: "nurbs_surface_eval",
    eval: eval_body,
    jvp: jvp_body,
    vjp: vjp_body,
}

/// The attributes naming the tangents (JVP) and cotangents (VJP) present, in operand order.
const KINDS: [&str; 5] = [
    "with_knots_u",
    "with_knots_v",
    "with_control",
    "with_weight",
    "with_parameter",
];

/// The residuals of every target (two knot vectors, the net, the weights, the pairs): the
/// batch, the element size of each, the net's size and the dimension.
struct Layout<'a> {
    batch: Batch<'a>,
    /// Element sizes of `knots_u`, `knots_v`, the net, the weights and the pairs.
    sizes: [usize; 5],
    net: (usize, usize),
    dim: usize,
}

impl<'a> Layout<'a> {
    fn of(res: &[In<'a>]) -> Result<Self, String> {
        let [ku, kv, net, w, uv] = res else {
            return Err(count_error("arguments", 5, res.len()));
        };
        let batch = Batch::of("knots_u", ku.dims, 1)?;
        let sizes = [
            batch.size("knots_u", ku.dims, 1)?,
            batch.size("knots_v", kv.dims, 1)?,
            batch.size("control net", net.dims, 3)?,
            batch.size("weights", w.dims, 2)?,
            batch.size("(u, v) pairs", uv.dims, 2)?,
        ];
        if uv.dims.last() != Some(&2) {
            return Err(format!(
                "(u, v) pairs of shape {:?}: the last axis must hold u and v",
                uv.dims
            ));
        }
        let axis = |k: usize| usize::try_from(net.dims[net.dims.len() - k]).unwrap_or(0);
        let dim = last_axis("control net", net.dims)?;
        let grid = (axis(3), axis(2));
        if w.dims[w.dims.len() - 2..] != net.dims[net.dims.len() - 3..net.dims.len() - 1] {
            return Err(format!(
                "weights of shape {:?}: one a net point, the net's shape {grid:?}",
                w.dims
            ));
        }
        Ok(Layout {
            batch,
            sizes,
            net: grid,
            dim,
        })
    }

    /// The surface of batch element `b`, built (and validated: sorted knots, one positive
    /// weight a net point) by [`NurbsSurface::new`].
    fn surface(
        &self,
        degrees: (usize, usize),
        res: &[In<'_>],
        b: usize,
    ) -> Result<NurbsSurface, String> {
        let [sku, skv, sn, sw, _] = self.sizes;
        let net = element(res[2].data, sn, b).to_vec();
        let points = Points::from_flat(self.dim, net).map_err(|e| e.to_string())?;
        let (ku, kv) = (element(res[0].data, sku, b), element(res[1].data, skv, b));
        let w = element(res[3].data, sw, b).to_vec();
        NurbsSurface::new(
            degrees.0,
            degrees.1,
            ku.to_vec(),
            kv.to_vec(),
            points,
            w,
            self.net,
        )
        .map_err(|e| e.to_string())
    }

    /// The parameter pairs of batch element `b`.
    fn uv(&self, res: &[In<'_>], b: usize) -> Vec<[f64; 2]> {
        pairs(element(res[4].data, self.sizes[4], b))
    }
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let Call { args, rets, .. } = call;
    let layout = Layout::of(args)?;
    let values = single(rets)?;
    let sv = layout.batch.size("values", values.dims, 2)?;
    for b in 0..layout.batch.count {
        let (uv, out) = (layout.uv(args, b), element_mut(values.data, sv, b));
        let s = layout.surface(degrees, args, b)?;
        s.eval_batch(&uv, out).map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let present = flags(call, KINDS);
    let Call { args, rets, .. } = call;
    let (res, [dku, dkv, dc, dw, duv]) = tangents(args, 5, present)?;
    let layout = Layout::of(res)?;
    let (batch, [sku, skv, sn, sw, sp]) = (&layout.batch, layout.sizes);
    let tangent = single(rets)?;
    let sv = batch.size("tangent", tangent.dims, 2)?;
    for (a, what, core, size) in [
        (dku, "u knot tangent", 1, sku),
        (dkv, "v knot tangent", 1, skv),
        (dc, "control-net tangent", 3, sn),
        (dw, "weight tangent", 2, sw),
        (duv, "parameter tangent", 2, sp),
    ] {
        if let Some(a) = a {
            batch.expect(what, a.dims, core, size)?;
        }
    }
    let knots = dku.is_some() || dkv.is_some();
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation)
    let mut values = vec![0.0; sv];
    let mut knot_part = vec![0.0; if knots { sv } else { 0 }];
    for b in 0..batch.count {
        let duv = duv.map(|a| pairs(element(a.data, sp, b)));
        let uv = layout.uv(res, b);
        let (dc, dw) = (
            dc.map(|a| element(a.data, sn, b)),
            dw.map(|a| element(a.data, sw, b)),
        );
        let out = element_mut(tangent.data, sv, b);
        let s = layout.surface(degrees, res, b)?;
        s.eval_batch_jvp(&uv, dc, dw, duv.as_deref(), &mut values, out)
            .map_err(|e| e.to_string())?;
        if knots {
            let du = dku.map(|a| element(a.data, sku, b));
            let dv = dkv.map(|a| element(a.data, skv, b));
            s.eval_batch_knot_jvp(&uv, du, dv, &mut values, &mut knot_part)
                .map_err(|e| e.to_string())?;
            for (o, k) in out.iter_mut().zip(&knot_part) {
                *o += k;
            }
        }
    }
    Ok(())
}

fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let present = flags(call, KINDS);
    let Call { args, rets, .. } = call;
    let (res, [g]) = tangents(args, 5, [true])?;
    let g = g.ok_or("no cotangent")?;
    let layout = Layout::of(res)?;
    let (batch, [sku, skv, sn, sw, sp]) = (&layout.batch, layout.sizes);
    let sg = batch.size("cotangent", g.dims, 2)?;
    let [mut gku, mut gkv, mut gc, mut gw, mut guv] = cotangents(rets, present)?;
    for (a, what, core, size) in [
        (&gku, "u knot cotangent", 1, sku),
        (&gkv, "v knot cotangent", 1, skv),
        (&gc, "control-net cotangent", 3, sn),
        (&gw, "weight cotangent", 2, sw),
        (&guv, "parameter cotangent", 2, sp),
    ] {
        if let Some(a) = a {
            batch.expect(what, a.dims, core, size)?;
        }
    }
    let knots = gku.is_some() || gkv.is_some();
    // the parameter cotangent as pairs, copied into the result after each element
    let mut pairs_out = vec![[0.0; 2]; if guv.is_some() { sp / 2 } else { 0 }];
    for b in 0..batch.count {
        let (uv, g) = (layout.uv(res, b), element(g.data, sg, b));
        let gc = gc.as_mut().map(|a| element_mut(a.data, sn, b));
        let gw = gw.as_mut().map(|a| element_mut(a.data, sw, b));
        let wants_rest = gc.is_some() || gw.is_some() || guv.is_some();
        let guv_b = guv.is_some().then_some(&mut pairs_out[..]);
        let s = layout.surface(degrees, res, b)?;
        if knots {
            let gu = gku.as_mut().map(|a| element_mut(a.data, sku, b));
            let gv = gkv.as_mut().map(|a| element_mut(a.data, skv, b));
            s.eval_batch_knot_vjp(&uv, g, gu, gv)
                .map_err(|e| e.to_string())?;
        }
        if wants_rest {
            s.eval_batch_vjp(&uv, g, gc, gw, guv_b)
                .map_err(|e| e.to_string())?;
        }
        if let Some(a) = guv.as_mut() {
            element_mut(a.data, sp, b).copy_from_slice(pairs_out.as_flattened());
        }
    }
    Ok(())
}
