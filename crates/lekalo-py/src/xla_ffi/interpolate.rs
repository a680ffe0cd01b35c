//! Interpolation at given parameters on given knots, `A(x) P = Q` with
//! `A[r][i] = N_{i,p}(x_r)`, as XLA FFI handlers, with its JVP and VJP with respect to the data
//! `Q`, the parameters `x` and the knots `τ` (`lekalo::derivatives::Interpolant`,
//! `docs/theory/derivatives.md`, "Interpolation" and "Knots of the fits"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_interpolate_eval` | knots `(m + p + 1,)`, points `(m, dim)`, params `(m,)` | `degree` | `P` `(m, dim)` |
//! | `lekalo_interpolate_jvp` | knots, points, params, [`τ̇` `(m + p + 1,)`], [`Q̇` `(m, dim)`], [`ẋ` `(m,)`] | `degree`, `with_knots`, `with_data`, `with_parameter` | `Ṗ` `(m, dim)` |
//! | `lekalo_interpolate_vjp` | knots, points, params, `P̄` `(m, dim)` | `degree`, `with_knots`, `with_data`, `with_parameter` | [`τ̄` `(m + p + 1,)`], [`Q̄` `(m, dim)`], [`x̄` `(m,)`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have the same leading batch axes. The tangent of the `p + 1` first and last knots is
//! ignored and their cotangent is zero ([`Interpolant::knot_jvp`]). Each batch element factors its collocation matrix once
//! ([`Interpolant::new`]); the control points are bit for bit `lekalo.interpolation_jvp`'s.

use lekalo::derivatives::Interpolant;

use super::abi::{Call, In};
use super::operands::{
    cotangents, count_attr, count_error, element, element_mut, flags, last_axis, single, tangents,
    Batch,
};

ffi_targets! {
    stem: "interpolate",
    function: "interpolate",
    eval: eval_body,
    jvp: jvp_body,
    vjp: vjp_body,
}

/// The knots, points and parameters, the residuals of every target: the batch, their element
/// sizes and the dimension.
fn layout<'a>(res: &[In<'a>]) -> Result<(Batch<'a>, [usize; 3], usize), String> {
    let [knots, points, params] = res else {
        return Err(count_error("arguments", 3, res.len()));
    };
    let batch = Batch::of("t", knots.dims, 1)?;
    let sizes = [
        batch.size("t", knots.dims, 1)?,
        batch.size("points", points.dims, 2)?,
        batch.size("params", params.dims, 1)?,
    ];
    Ok((batch, sizes, last_axis("points", points.dims)?))
}

/// The interpolant of batch element `b`.
fn interpolant(
    degree: usize,
    res: &[In<'_>],
    [sk, sq, sx]: [usize; 3],
    dim: usize,
    b: usize,
) -> Result<Interpolant, String> {
    Interpolant::new(
        degree,
        element(res[0].data, sk, b),
        element(res[2].data, sx, b),
        element(res[1].data, sq, b),
        dim,
    )
    .map_err(|e| e.to_string())
}

fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
    let degree = count_attr(call, "degree")?;
    let Call { args, rets, .. } = call;
    let (batch, sizes, dim) = layout(args)?;
    let control = single(rets)?;
    batch.expect("control points", control.dims, 2, sizes[1])?;
    for b in 0..batch.count {
        let it = interpolant(degree, args, sizes, dim, b)?;
        element_mut(control.data, sizes[1], b).copy_from_slice(it.control_points());
    }
    Ok(())
}

fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degree = count_attr(call, "degree")?;
    let present = flags(call, ["with_knots", "with_data", "with_parameter"]);
    let Call { args, rets, .. } = call;
    let (res, [dt, dq, dx]) = tangents(args, 3, present)?;
    let (batch, sizes, dim) = layout(res)?;
    let [sk, sq, sx] = sizes;
    let tangent = single(rets)?;
    batch.expect("control-point tangent", tangent.dims, 2, sq)?;
    if let Some(a) = dt {
        batch.expect("knot tangent", a.dims, 1, sk)?;
    }
    if let Some(a) = dq {
        batch.expect("data tangent", a.dims, 2, sq)?;
    }
    if let Some(a) = dx {
        batch.expect("parameter tangent", a.dims, 1, sx)?;
    }
    for b in 0..batch.count {
        let it = interpolant(degree, res, sizes, dim, b)?;
        let mut out = if dq.is_some() || dx.is_some() || dt.is_none() {
            it.jvp(
                dq.map(|a| element(a.data, sq, b)),
                dx.map(|a| element(a.data, sx, b)),
            )
            .map_err(|e| e.to_string())?
        } else {
            vec![0.0; sq]
        };
        if let Some(a) = dt {
            let moved = it
                .knot_jvp(element(a.data, sk, b))
                .map_err(|e| e.to_string())?;
            for (o, d) in out.iter_mut().zip(&moved) {
                *o += d;
            }
        }
        element_mut(tangent.data, sq, b).copy_from_slice(&out);
    }
    Ok(())
}

fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
    let degree = count_attr(call, "degree")?;
    let present = flags(call, ["with_knots", "with_data", "with_parameter"]);
    let Call { args, rets, .. } = call;
    let (res, [g]) = tangents(args, 3, [true])?;
    let g = g.ok_or("no cotangent")?;
    let (batch, sizes, dim) = layout(res)?;
    let [sk, sq, sx] = sizes;
    batch.expect("control-point cotangent", g.dims, 2, sq)?;
    let [mut gt, mut gq, mut gx] = cotangents(rets, present)?;
    if let Some(a) = &gt {
        batch.expect("knot cotangent", a.dims, 1, sk)?;
    }
    if let Some(a) = &gq {
        batch.expect("data cotangent", a.dims, 2, sq)?;
    }
    if let Some(a) = &gx {
        batch.expect("parameter cotangent", a.dims, 1, sx)?;
    }
    for b in 0..batch.count {
        let it = interpolant(degree, res, sizes, dim, b)?;
        if let Some(a) = gt.as_mut() {
            let knots = it
                .knot_vjp(element(g.data, sq, b))
                .map_err(|e| e.to_string())?;
            element_mut(a.data, sk, b).copy_from_slice(&knots);
        }
        if gq.is_none() && gx.is_none() {
            continue;
        }
        let (data, params) = it
            .vjp(element(g.data, sq, b), gx.is_some())
            .map_err(|e| e.to_string())?;
        if let Some(a) = gq.as_mut() {
            element_mut(a.data, sq, b).copy_from_slice(&data);
        }
        if let (Some(a), Some(p)) = (gx.as_mut(), params) {
            element_mut(a.data, sx, b).copy_from_slice(&p);
        }
    }
    Ok(())
}
