//! Tensor-product B-spline surface evaluation `S(u, v) = Σ_k Σ_l N_{k,p}(u) N_{l,q}(v) P_{kl}`
//! as XLA FFI handlers, with its JVP and VJP with respect to the knots of each direction, the
//! control net `P` and the parameter pairs `(u, v)` (`docs/theory/derivatives.md`, "Surfaces"
//! and "Knots"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_surface_eval` | `knots_u` `(nku,)`, `knots_v` `(nkv,)`, net `(nu, nv, dim)`, uv `(m, 2)` | `degree_u`, `degree_v` | `S` `(m, dim)` |
//! | `lekalo_surface_jvp` | `knots_u`, `knots_v`, net, uv, [`τ̇ᵘ` `(nku,)`], [`τ̇ᵛ` `(nkv,)`], [`Ṗ` `(nu, nv, dim)`], [`(u̇, v̇)` `(m, 2)`] | `degree_u`, `degree_v`, `with_knots_u`, `with_knots_v`, `with_control`, `with_parameter` | `Ṡ` `(m, dim)` |
//! | `lekalo_surface_vjp` | `knots_u`, `knots_v`, net, uv, `ḡ` `(m, dim)` | `degree_u`, `degree_v`, `with_knots_u`, `with_knots_v`, `with_control`, `with_parameter` | [`τ̄ᵘ` `(nku,)`], [`τ̄ᵛ` `(nkv,)`], [`P̄` `(nu, nv, dim)`], [`(ū, v̄)` `(m, 2)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have leading batch axes (the same for all). The values are
//! [`BSplineSurface::eval_batch`]'s (P&T A3.5), the JVP [`BSplineSurface::eval_batch_jvp`]'s
//! plus [`BSplineSurface::eval_batch_knot_jvp`]'s, the VJP [`BSplineSurface::eval_batch_vjp`]'s
//! and [`BSplineSurface::eval_batch_knot_vjp`]'s. For a batch element with few pairs against
//! its net ([`in_place`]), and no knot derivative, the three are [`BorrowedSurface`]'s on the operand buffers themselves
//! (the same numbers): no copy of the net, and only the knots and net points the pairs' cells
//! read are checked.

use lekalo::derivatives::BorrowedSurface;
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
const KINDS: [&str; 4] = [
    "with_knots_u",
    "with_knots_v",
    "with_control",
    "with_parameter",
];

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

    /// The surface of batch element `b` on the operand buffers (as [`Layout::surface`]).
    fn borrowed<'r>(
        &self,
        degrees: (usize, usize),
        res: &[In<'r>],
        b: usize,
    ) -> Result<BorrowedSurface<'r>, String> {
        let [sku, skv, sn, _] = self.sizes;
        let knots = (element(res[0].data, sku, b), element(res[1].data, skv, b));
        let net = element(res[2].data, sn, b);
        BorrowedSurface::new(degrees, knots, net, self.net, self.dim).map_err(|e| e.to_string())
    }

    /// Whether the batch's elements are evaluated in place ([`in_place`]).
    fn in_place(&self, (p, q): (usize, usize)) -> bool {
        in_place(self.sizes[3] / 2, self.net, (p, q))
    }

    /// The parameter pairs of batch element `b`.
    fn uv(&self, res: &[In<'_>], b: usize) -> Vec<[f64; 2]> {
        pairs(element(res[3].data, self.sizes[3], b))
    }
}

/// `(u, v)` pairs from their flat `(m, 2)` layout (the element sizes are even, the last axis
/// being checked to be 2), copied: the kernels take `&[[f64; 2]]`, and the slice-to-array
/// view (`as_chunks`) is newer than the crate's minimum Rust.
pub(super) fn pairs(flat: &[f64]) -> Vec<[f64; 2]> {
    flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect()
}

/// Whether `m` pairs on a net of `nu × nv` points of degrees `(p, q)` are evaluated in place
/// ([`BorrowedSurface`]) rather than on a built surface: when they read fewer net points than
/// building it copies and validates, `m · (p + 1)(q + 1) ≤ nu · nv` (each pair reads and
/// checks a `(p + 1) × (q + 1)` block and `2p + 2 + 2q + 2` knots).
fn in_place(m: usize, (nu, nv): (usize, usize), (p, q): (usize, usize)) -> bool {
    m.saturating_mul((p + 1).saturating_mul(q + 1)) <= nu.saturating_mul(nv)
}

/// The degrees `(p, q)` of a surface target (attributes `degree_u`, `degree_v`).
pub(super) fn degrees(call: &Call<'_>) -> Result<(usize, usize), String> {
    Ok((count_attr(call, "degree_u")?, count_attr(call, "degree_v")?))
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let Call { args, rets, .. } = call;
    let layout = Layout::of(args)?;
    let values = single(rets)?;
    let sv = layout.batch.size("values", values.dims, 2)?;
    let small = layout.in_place(degrees);
    for b in 0..layout.batch.count {
        let (uv, out) = (layout.uv(args, b), element_mut(values.data, sv, b));
        let done = if small {
            layout.borrowed(degrees, args, b)?.eval_batch(&uv, out)
        } else {
            layout.surface(degrees, args, b)?.eval_batch(&uv, out)
        };
        done.map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degrees = degrees(call)?;
    let present = flags(call, KINDS);
    let Call { args, rets, .. } = call;
    let (res, [dku, dkv, dc, duv]) = tangents(args, 4, present)?;
    let layout = Layout::of(res)?;
    let (batch, [sku, skv, sn, sp]) = (&layout.batch, layout.sizes);
    let tangent = single(rets)?;
    let sv = batch.size("tangent", tangent.dims, 2)?;
    if let Some(a) = dku {
        batch.expect("u knot tangent", a.dims, 1, sku)?;
    }
    if let Some(a) = dkv {
        batch.expect("v knot tangent", a.dims, 1, skv)?;
    }
    if let Some(a) = dc {
        batch.expect("control-net tangent", a.dims, 3, sn)?;
    }
    if let Some(a) = duv {
        batch.expect("parameter tangent", a.dims, 2, sp)?;
    }
    let knots = dku.is_some() || dkv.is_some();
    // the values the JVP kernel also computes, not returned (XLA has them from the evaluation);
    // the knot derivatives need the built surface
    let small = !knots && layout.in_place(degrees);
    let mut values = vec![0.0; if small { 0 } else { sv }];
    let mut knot_part = vec![0.0; if knots { sv } else { 0 }];
    for b in 0..batch.count {
        let duv = duv.map(|a| pairs(element(a.data, sp, b)));
        let (uv, dc) = (layout.uv(res, b), dc.map(|a| element(a.data, sn, b)));
        let out = element_mut(tangent.data, sv, b);
        if small {
            let s = layout.borrowed(degrees, res, b)?;
            s.eval_batch_jvp(&uv, dc, duv.as_deref(), out)
                .map_err(|e| e.to_string())?;
            continue;
        }
        let s = layout.surface(degrees, res, b)?;
        s.eval_batch_jvp(&uv, dc, duv.as_deref(), &mut values, out)
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
    let (res, [g]) = tangents(args, 4, [true])?;
    let g = g.ok_or("no cotangent")?;
    let layout = Layout::of(res)?;
    let (batch, [sku, skv, sn, sp]) = (&layout.batch, layout.sizes);
    let sg = batch.size("cotangent", g.dims, 2)?;
    let [mut gku, mut gkv, mut gc, mut guv] = cotangents(rets, present)?;
    if let Some(a) = &gku {
        batch.expect("u knot cotangent", a.dims, 1, sku)?;
    }
    if let Some(a) = &gkv {
        batch.expect("v knot cotangent", a.dims, 1, skv)?;
    }
    if let Some(a) = &gc {
        batch.expect("control-net cotangent", a.dims, 3, sn)?;
    }
    if let Some(a) = &guv {
        batch.expect("parameter cotangent", a.dims, 2, sp)?;
    }
    let knots = gku.is_some() || gkv.is_some();
    // the parameter cotangent as pairs, copied into the result after each element
    let mut pairs_out = vec![[0.0; 2]; if guv.is_some() { sp / 2 } else { 0 }];
    let small = !knots && layout.in_place(degrees);
    for b in 0..batch.count {
        let (uv, g) = (layout.uv(res, b), element(g.data, sg, b));
        let gc = gc.as_mut().map(|a| element_mut(a.data, sn, b));
        let wants_rest = gc.is_some() || guv.is_some();
        let guv_b = guv.is_some().then_some(&mut pairs_out[..]);
        if small {
            layout
                .borrowed(degrees, res, b)?
                .eval_batch_vjp(&uv, g, gc, guv_b)
                .map_err(|e| e.to_string())?;
        } else {
            let s = layout.surface(degrees, res, b)?;
            if knots {
                let gu = gku.as_mut().map(|a| element_mut(a.data, sku, b));
                let gv = gkv.as_mut().map(|a| element_mut(a.data, skv, b));
                s.eval_batch_knot_vjp(&uv, g, gu, gv)
                    .map_err(|e| e.to_string())?;
            }
            if wants_rest {
                s.eval_batch_vjp(&uv, g, gc, guv_b)
                    .map_err(|e| e.to_string())?;
            }
        }
        if let Some(a) = guv.as_mut() {
            element_mut(a.data, sp, b).copy_from_slice(pairs_out.as_flattened());
        }
    }
    Ok(())
}
