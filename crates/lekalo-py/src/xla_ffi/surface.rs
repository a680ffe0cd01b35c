//! Tensor-product B-spline surface evaluation `S(u, v) = Σ_k Σ_l N_{k,p}(u) N_{l,q}(v) P_{kl}`
//! as XLA FFI handlers, with its JVP and VJP with respect to the control net `P` and the
//! parameter pairs `(u, v)` (`docs/theory/derivatives.md`):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_surface_eval` | `knots_u` `(nku,)`, `knots_v` `(nkv,)`, net `(nu, nv, dim)`, uv `(m, 2)` | `degree_u`, `degree_v` | `S` `(m, dim)` |
//! | `lekalo_surface_jvp` | `knots_u`, `knots_v`, net, uv, [`Ṗ` `(nu, nv, dim)`], [`(u̇, v̇)` `(m, 2)`] | `degree_u`, `degree_v`, `with_control`, `with_parameter` | `Ṡ` `(m, dim)` |
//! | `lekalo_surface_vjp` | `knots_u`, `knots_v`, net, uv, `ḡ` `(m, dim)` | `degree_u`, `degree_v`, `with_control`, `with_parameter` | [`P̄` `(nu, nv, dim)`], [`(ū, v̄)` `(m, 2)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have leading batch axes (the same for all). The values are
//! [`BSplineSurface::eval_batch`]'s (P&T A3.5), the JVP [`BSplineSurface::eval_batch_jvp`]'s,
//! the VJP [`BSplineSurface::eval_batch_vjp`]'s.

use lekalo::{BSplineSurface, Points};

use super::abi::{Call, In};
use super::operands::{
    cotangents, count_attr, count_error, element, element_mut, flags, last_axis, single, tangents,
    Batch,
};

ffi_targets! {
    stem: "surface",
    function: "bspline_surface_eval",
    eval: eval_body,
    jvp: jvp_body,
    vjp: vjp_body,
}

/// The attributes naming the tangents (JVP) and cotangents (VJP) present, in operand order.
const KINDS: [&str; 2] = ["with_control", "with_parameter"];

/// The residuals of every target (two knot vectors, the net, the pairs): the batch, the
/// element size of each, the net's size and the dimension.
struct Layout<'a> {
    batch: Batch<'a>,
    /// Element sizes of `knots_u`, `knots_v`, the net and the pairs.
    sizes: [usize; 4],
    net: (usize, usize),
    dim: usize,
}

impl<'a> Layout<'a> {
    fn of(res: &[In<'a>]) -> Result<Self, String> {
        let [ku, kv, net, uv] = res else {
            return Err(count_error("arguments", 4, res.len()));
        };
        let batch = Batch::of("knots_u", ku.dims, 1)?;
        let sizes = [
            batch.size("knots_u", ku.dims, 1)?,
            batch.size("knots_v", kv.dims, 1)?,
            batch.size("control net", net.dims, 3)?,
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
        Ok(Layout {
            batch,
            sizes,
            net: (axis(3), axis(2)),
            dim,
        })
    }

    /// The surface of batch element `b`, built (and validated) by [`BSplineSurface::new`].
    fn surface(
        &self,
        degrees: (usize, usize),
        res: &[In<'_>],
        b: usize,
    ) -> Result<BSplineSurface, String> {
        let [sku, skv, sn, _] = self.sizes;
        let net = element(res[2].data, sn, b).to_vec();
        let points = Points::from_flat(self.dim, net).map_err(|e| e.to_string())?;
        let (ku, kv) = (element(res[0].data, sku, b), element(res[1].data, skv, b));
        BSplineSurface::new(
            degrees.0,
            degrees.1,
            ku.to_vec(),
            kv.to_vec(),
            points,
            self.net,
        )
        .map_err(|e| e.to_string())
    }

    /// The parameter pairs of batch element `b`.
    fn uv(&self, res: &[In<'_>], b: usize) -> Vec<[f64; 2]> {
        pairs(element(res[3].data, self.sizes[3], b))
    }
}

/// `(u, v)` pairs from their flat `(m, 2)` layout (the element sizes are even, the last axis
/// being checked to be 2), copied: the kernels take `&[[f64; 2]]`, and the slice-to-array
/// view (`as_chunks`) is newer than the crate's minimum Rust.
fn pairs(flat: &[f64]) -> Vec<[f64; 2]> {
    flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect()
}

fn degrees(call: &Call<'_>) -> Result<(usize, usize), String> {
    Ok((count_attr(call, "degree_u")?, count_attr(call, "degree_v")?))
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let Call { args, rets, .. } = call;
    let layout = Layout::of(args)?;
    let values = single(rets)?;
    let sv = layout.batch.size("values", values.dims, 2)?;
    for b in 0..layout.batch.count {
        let s = layout.surface(degrees, args, b)?;
        s.eval_batch(&layout.uv(args, b), element_mut(values.data, sv, b))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let present = flags(call, KINDS);
    let Call { args, rets, .. } = call;
    let (res, [dc, duv]) = tangents(args, 4, present)?;
    let layout = Layout::of(res)?;
    let (batch, [_, _, sn, sp]) = (&layout.batch, layout.sizes);
    let tangent = single(rets)?;
    let sv = batch.size("tangent", tangent.dims, 2)?;
    if let Some(a) = dc {
        batch.expect("control-net tangent", a.dims, 3, sn)?;
    }
    if let Some(a) = duv {
        batch.expect("parameter tangent", a.dims, 2, sp)?;
    }
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation)
    let mut values = vec![0.0; sv];
    for b in 0..batch.count {
        let s = layout.surface(degrees, res, b)?;
        let duv = duv.map(|a| pairs(element(a.data, sp, b)));
        s.eval_batch_jvp(
            &layout.uv(res, b),
            dc.map(|a| element(a.data, sn, b)),
            duv.as_deref(),
            &mut values,
            element_mut(tangent.data, sv, b),
        )
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let present = flags(call, KINDS);
    let Call { args, rets, .. } = call;
    let (res, [g]) = tangents(args, 4, [true])?;
    let g = g.ok_or("no cotangent")?;
    let layout = Layout::of(res)?;
    let (batch, [_, _, sn, sp]) = (&layout.batch, layout.sizes);
    let sg = batch.size("cotangent", g.dims, 2)?;
    let [mut gc, mut guv] = cotangents(rets, present)?;
    if let Some(a) = &gc {
        batch.expect("control-net cotangent", a.dims, 3, sn)?;
    }
    if let Some(a) = &guv {
        batch.expect("parameter cotangent", a.dims, 2, sp)?;
    }
    // the parameter cotangent as pairs, copied into the result after each element
    let mut pairs_out = vec![[0.0; 2]; if guv.is_some() { sp / 2 } else { 0 }];
    for b in 0..batch.count {
        let s = layout.surface(degrees, res, b)?;
        s.eval_batch_vjp(
            &layout.uv(res, b),
            element(g.data, sg, b),
            gc.as_mut().map(|a| element_mut(a.data, sn, b)),
            guv.is_some().then_some(&mut pairs_out[..]),
        )
        .map_err(|e| e.to_string())?;
        if let Some(a) = guv.as_mut() {
            element_mut(a.data, sp, b).copy_from_slice(pairs_out.as_flattened());
        }
    }
    Ok(())
}
