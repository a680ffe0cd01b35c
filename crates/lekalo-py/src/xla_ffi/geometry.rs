//! A B-spline curve's arc length and the parameters of its closest points to given points as
//! XLA FFI handlers, with their JVP and VJP (`lekalo::derivatives::{ArcLengthGradient,
//! ClosestParameters}`, `docs/theory/derivatives.md`, "Arc length and closest points"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_arc_length_eval` | knots `(nk,)`, control `(n, dim)` | `degree` | `L` `()` |
//! | `lekalo_arc_length_jvp` | knots, control, [`τ̇` `(nk,)`], [`Ṗ` `(n, dim)`] | `degree`, `with_knots`, `with_control` | `L̇` `()` |
//! | `lekalo_arc_length_vjp` | knots, control, `L̄` `()` | `degree`, `with_knots`, `with_control` | [`τ̄` `(nk,)`], [`P̄` `(n, dim)`] |
//! | `lekalo_closest_parameter_eval` | knots, control, x `(m, dim)` | `degree` | `t` `(m,)` |
//! | `lekalo_closest_parameter_jvp` | knots, control, x, [`τ̇`], [`Ṗ`], [`ẋ` `(m, dim)`] | `degree`, `with_knots`, `with_control`, `with_point` | `ṫ` `(m,)` |
//! | `lekalo_closest_parameter_vjp` | knots, control, x, `t̄` `(m,)` | `degree`, `with_knots`, `with_control`, `with_point` | [`τ̄`], [`P̄`], [`x̄`] |
//!
//! The bracketed buffers are present when the attribute of the same name is true; every buffer
//! may have the same leading batch axes. Each batch element builds its curve
//! ([`BSplineCurve::new`], validated) and runs the core's kernel once (built with the knot
//! derivatives, `with_knots`, only when the knots' tangent or cotangent is asked for).

use lekalo::derivatives::{ArcLengthGradient, ClosestParameters};
use lekalo::{BSplineCurve, Points};

use super::abi::{self, In};
use super::operands::{
    batch_sizes, cotangents, count_attr, element, element_mut, flags, last_axis, single, tangents,
    Batch,
};
use super::Handler;

/// The handlers of both queries, by target name.
pub(super) const HANDLERS: [&[(&str, Handler)]; 2] =
    [arc_length::HANDLERS, closest_parameter::HANDLERS];

/// The residuals' batch, element sizes (`names`: each one's name and core axes) and the
/// dimension (the control points' last axis).
fn layout<'a>(
    res: &[In<'a>],
    names: &[(&str, usize)],
) -> Result<(Batch<'a>, Vec<usize>, usize), String> {
    let (batch, sizes) = batch_sizes(res, names)?;
    Ok((batch, sizes, last_axis(names[1].0, res[1].dims)?))
}

/// The curve of batch element `b` from the first two residuals (knots, control points).
fn curve(
    degree: usize,
    res: &[In<'_>],
    sizes: &[usize],
    dim: usize,
    b: usize,
) -> Result<BSplineCurve, String> {
    let control = element(res[1].data, sizes[1], b);
    let points = Points::from_flat(dim, control.to_vec()).map_err(|e| e.to_string())?;
    BSplineCurve::new(degree, element(res[0].data, sizes[0], b).to_vec(), points)
        .map_err(|e| e.to_string())
}

/// The handlers of `lekalo.jax.arc_length`.
pub(super) mod arc_length {
    ffi_targets! {
        stem: "arc_length",
        function: "arc_length",
        eval: eval_body,
        jvp: jvp_body,
        vjp: vjp_body,
    }

    use super::{
        cotangents, count_attr, curve, element, element_mut, flags, layout, single, tangents,
        ArcLengthGradient,
    };
    use crate::xla_ffi::abi::{Call, In};

    /// Knots and control points, with their core axes.
    const RESIDUALS: [(&str, usize); 2] = [("knots", 1), ("control points", 2)];

    /// The gradient of batch element `b`, in the knots too when `knots`.
    fn gradient(
        degree: usize,
        res: &[In<'_>],
        sizes: &[usize],
        dim: usize,
        b: usize,
        knots: bool,
    ) -> Result<ArcLengthGradient, String> {
        let c = curve(degree, res, sizes, dim, b)?;
        if knots {
            ArcLengthGradient::with_knots(&c)
        } else {
            ArcLengthGradient::new(&c)
        }
        .map_err(|e| e.to_string())
    }

    fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
        let degree = count_attr(call, "degree")?;
        let Call { args, rets, .. } = call;
        let (batch, sizes, dim) = layout(args, &RESIDUALS)?;
        let out = single(rets)?;
        batch.expect("length", out.dims, 0, 1)?;
        for b in 0..batch.count {
            let c = curve(degree, args, &sizes, dim, b)?;
            let q = lekalo::QueryCurve::from_bspline(&c).map_err(|e| e.to_string())?;
            out.data[b] = q.length().map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
        let degree = count_attr(call, "degree")?;
        let present = flags(call, ["with_knots", "with_control"]);
        let Call { args, rets, .. } = call;
        let (res, [dk, dc]) = tangents(args, 2, present)?;
        let (batch, sizes, dim) = layout(res, &RESIDUALS)?;
        let out = single(rets)?;
        batch.expect("length tangent", out.dims, 0, 1)?;
        if dk.is_none() && dc.is_none() {
            out.data.fill(0.0);
            return Ok(());
        }
        if let Some(a) = dk {
            batch.expect("knot tangent", a.dims, 1, sizes[0])?;
        }
        if let Some(a) = dc {
            batch.expect("control-point tangent", a.dims, 2, sizes[1])?;
        }
        for b in 0..batch.count {
            let grad = gradient(degree, res, &sizes, dim, b, dk.is_some())?;
            let mut sum = 0.0;
            if let Some(a) = dc {
                sum += grad
                    .jvp(element(a.data, sizes[1], b))
                    .map_err(|e| e.to_string())?;
            }
            if let Some(a) = dk {
                sum += grad
                    .knot_jvp(element(a.data, sizes[0], b))
                    .map_err(|e| e.to_string())?;
            }
            out.data[b] = sum;
        }
        Ok(())
    }

    fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
        let degree = count_attr(call, "degree")?;
        let present = flags(call, ["with_knots", "with_control"]);
        let Call { args, rets, .. } = call;
        let (res, [g]) = tangents(args, 2, [true])?;
        let g = g.ok_or("no cotangent")?;
        let (batch, sizes, dim) = layout(res, &RESIDUALS)?;
        batch.expect("length cotangent", g.dims, 0, 1)?;
        let [mut gk, mut gc] = cotangents(rets, present)?;
        if let Some(a) = &gk {
            batch.expect("knot cotangent", a.dims, 1, sizes[0])?;
        }
        if let Some(a) = &gc {
            batch.expect("control-point cotangent", a.dims, 2, sizes[1])?;
        }
        if gk.is_none() && gc.is_none() {
            return Ok(());
        }
        for b in 0..batch.count {
            let grad = gradient(degree, res, &sizes, dim, b, gk.is_some())?;
            if let Some(a) = gc.as_mut() {
                let v = grad.vjp(g.data[b]).map_err(|e| e.to_string())?;
                element_mut(a.data, sizes[1], b).copy_from_slice(&v);
            }
            if let Some(a) = gk.as_mut() {
                let v = grad.knot_vjp(g.data[b]).map_err(|e| e.to_string())?;
                element_mut(a.data, sizes[0], b).copy_from_slice(&v);
            }
        }
        Ok(())
    }
}

/// The handlers of `lekalo.jax.closest_parameter`.
pub(super) mod closest_parameter {
    ffi_targets! {
        stem: "closest_parameter",
        function: "closest_parameter",
        eval: eval_body,
        jvp: jvp_body,
        vjp: vjp_body,
    }

    use super::{
        cotangents, count_attr, curve, element, element_mut, flags, layout, single, tangents,
        ClosestParameters,
    };
    use crate::xla_ffi::abi::{Call, In};

    /// Knots, control points and the points, with their core axes.
    const RESIDUALS: [(&str, usize); 3] = [("knots", 1), ("control points", 2), ("x", 2)];

    /// The closest parameters of batch element `b`, with their knot derivatives when `knots`.
    fn closest(
        degree: usize,
        res: &[In<'_>],
        sizes: &[usize],
        dim: usize,
        b: usize,
        knots: bool,
    ) -> Result<ClosestParameters, String> {
        let c = curve(degree, res, sizes, dim, b)?;
        let x = element(res[2].data, sizes[2], b);
        if knots {
            ClosestParameters::with_knots(&c, x)
        } else {
            ClosestParameters::new(&c, x)
        }
        .map_err(|e| e.to_string())
    }

    fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
        let degree = count_attr(call, "degree")?;
        let Call { args, rets, .. } = call;
        let (batch, sizes, dim) = layout(args, &RESIDUALS)?;
        let out = single(rets)?;
        let m = sizes[2] / dim.max(1);
        batch.expect("parameters", out.dims, 1, m)?;
        for b in 0..batch.count {
            let c = curve(degree, args, &sizes, dim, b)?;
            let points = lekalo::PointsRef::from_flat(dim, element(args[2].data, sizes[2], b))
                .map_err(|e| e.to_string())?;
            let q = lekalo::QueryCurve::from_bspline(&c).map_err(|e| e.to_string())?;
            let found = q.project_batch(points).map_err(|e| e.to_string())?;
            for (o, f) in element_mut(out.data, m, b).iter_mut().zip(&found) {
                *o = f.t;
            }
        }
        Ok(())
    }

    fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
        let degree = count_attr(call, "degree")?;
        let present = flags(call, ["with_knots", "with_control", "with_point"]);
        let Call { args, rets, .. } = call;
        let (res, [dk, dc, dx]) = tangents(args, 3, present)?;
        let (batch, sizes, dim) = layout(res, &RESIDUALS)?;
        let m = sizes[2] / dim.max(1);
        if let Some(a) = dk {
            batch.expect("knot tangent", a.dims, 1, sizes[0])?;
        }
        if let Some(a) = dc {
            batch.expect("control-point tangent", a.dims, 2, sizes[1])?;
        }
        if let Some(a) = dx {
            batch.expect("point tangent", a.dims, 2, sizes[2])?;
        }
        let out = single(rets)?;
        batch.expect("parameter tangent", out.dims, 1, m)?;
        for b in 0..batch.count {
            let cp = closest(degree, res, &sizes, dim, b, dk.is_some())?;
            let mut got = cp
                .jvp(
                    dc.map(|a| element(a.data, sizes[1], b)),
                    dx.map(|a| element(a.data, sizes[2], b)),
                )
                .map_err(|e| e.to_string())?;
            if let Some(a) = dk {
                let k = cp
                    .knot_jvp(element(a.data, sizes[0], b))
                    .map_err(|e| e.to_string())?;
                for (o, v) in got.iter_mut().zip(&k) {
                    *o += v;
                }
            }
            element_mut(out.data, m, b).copy_from_slice(&got);
        }
        Ok(())
    }

    fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
        let degree = count_attr(call, "degree")?;
        let present = flags(call, ["with_knots", "with_control", "with_point"]);
        let Call { args, rets, .. } = call;
        let (res, [g]) = tangents(args, 3, [true])?;
        let g = g.ok_or("no cotangent")?;
        let (batch, sizes, dim) = layout(res, &RESIDUALS)?;
        let m = sizes[2] / dim.max(1);
        batch.expect("parameter cotangent", g.dims, 1, m)?;
        let [mut gk, mut gc, mut gx] = cotangents(rets, present)?;
        if let Some(a) = &gk {
            batch.expect("knot cotangent", a.dims, 1, sizes[0])?;
        }
        if let Some(a) = &gc {
            batch.expect("control-point cotangent", a.dims, 2, sizes[1])?;
        }
        if let Some(a) = &gx {
            batch.expect("point cotangent", a.dims, 2, sizes[2])?;
        }
        for b in 0..batch.count {
            let cp = closest(degree, res, &sizes, dim, b, gk.is_some())?;
            if let Some(a) = gk.as_mut() {
                let v = cp
                    .knot_vjp(element(g.data, m, b))
                    .map_err(|e| e.to_string())?;
                element_mut(a.data, sizes[0], b).copy_from_slice(&v);
            }
            let (c, x) = cp
                .vjp(element(g.data, m, b), gc.is_some(), gx.is_some())
                .map_err(|e| e.to_string())?;
            if let (Some(a), Some(v)) = (gc.as_mut(), c) {
                element_mut(a.data, sizes[1], b).copy_from_slice(&v);
            }
            if let (Some(a), Some(v)) = (gx.as_mut(), x) {
                element_mut(a.data, sizes[2], b).copy_from_slice(&v);
            }
        }
        Ok(())
    }
}
