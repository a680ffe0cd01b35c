//! The least-squares fit on given knots and parameters and the smoothing spline with a given
//! `λ` as XLA FFI handlers, with their JVP and VJP with respect to the data values, and the
//! least-squares fit's with respect to its knots too
//! (`lekalo::derivatives::{LeastSquaresFit, SmoothingFit}`, `docs/theory/derivatives.md`,
//! "Fits" and "Knots of the fits"):
//!
//! | target | arguments | attributes | results |
//! |---|---|---|---|
//! | `lekalo_fit_least_squares_eval` | params `(m,)`, w `(m,)`, knots `(n + p + 1,)`, points `(m, dim)` | `degree`, `weighted` | `P` `(n, dim)` |
//! | `lekalo_fit_least_squares_factor` | as `…_eval` | as `…_eval` | `P`, F `((p + 3) m + (p + 1) n,)` |
//! | `lekalo_fit_smoothing_eval` | x `(m,)`, w `(m,)`, λ `()`, y `(m, dim)` | `weighted` | `P` `(m + 2, dim)` |
//! | `lekalo_fit_smoothing_factor` | as `…_eval` | as `…_eval` | `P`, F `(11 m + 14,)` |
//! | `lekalo_fit_least_squares_jvp` | params, w, F, knots, points, [`τ̇` as knots], [`Q̇` `(m, dim)`] | the same, `with_knots`, `with_data` | `Ṗ` as `P` |
//! | `lekalo_fit_least_squares_vjp` | params, w, F, knots, points, `P̄` as `P` | the same, `with_knots`, `with_data` | [`τ̄` as knots], [`Q̄` `(m, dim)`] |
//! | `lekalo_fit_smoothing_jvp` | x, w, λ, F, y, [`Q̇`] | the same, `with_data` | `Ṗ` as `P` |
//! | `lekalo_fit_smoothing_vjp` | x, w, λ, F, y, `P̄` | the same, `with_data` | [`Q̄`] |
//!
//! The bracketed buffers are present when the attribute `with_<kind>` of their kind is true; `w` is read only when `weighted`
//! is true (unweighted is the fit without weights, not weights of 1); every buffer may have the
//! same leading batch axes. The control points are bit for bit `lekalo.fit_least_squares`'s and
//! `lekalo.fit_smoothing`'s. A fit's forward pass under differentiation is its `…_factor`
//! target: the values and F, the map of the same factorisation as numbers
//! ([`LeastSquaresMap::to_flat`]: the rows of `B` and the triangle of their banded QR;
//! [`SmoothingMap::to_flat`]: the rows and the `UᵀDU` of `BᵀWB + λΩ`), which its JVP and VJP
//! apply without factoring again (the same bits as factoring again). The least-squares fit's
//! knots come after its factors, among the differentiable operands; their derivatives
//! ([`LeastSquaresFit::knot_jvp`], [`LeastSquaresFit::knot_vjp`]: the tangent of the `p + 1`
//! first and last knots ignored, their cotangent zero) factor the fit again.

use lekalo::derivatives::{LeastSquaresFit, LeastSquaresMap, SmoothingFit, SmoothingMap};

use super::abi::{self, Call, In};
use super::operands::{
    batch_sizes, cotangents, count_attr, count_error, element, element_mut, flags, last_axis,
    single, tangents, Batch,
};
use super::Handler;

/// The handlers of both fits, by target name.
pub(super) const HANDLERS: [&[(&str, Handler)]; 2] = [least_squares::HANDLERS, smoothing::HANDLERS];

/// The handlers of `lekalo.jax.fit_least_squares`.
pub(super) mod least_squares {
    ffi_targets! {
        stem: "fit_least_squares",
        function: "fit_least_squares",
        eval: eval_body,
        factor: factor_body,
        jvp: jvp_body,
        vjp: vjp_body,
    }

    use super::{run_eval, run_factor, Factors, Fit};
    use crate::xla_ffi::abi::Call;

    /// Params, weights, knots and points, with their core axes.
    const RESIDUALS: [(&str, usize); 4] = [("params", 1), ("w", 1), ("t", 1), ("points", 2)];

    /// The derivatives' residuals: params, weights, the factors of the forward pass, knots and
    /// the points (the knots and the points the differentiable kinds).
    const FACTORED: [(&str, usize); 5] = [
        ("params", 1),
        ("w", 1),
        ("factors", 1),
        ("t", 1),
        ("points", 2),
    ];

    /// `degree`, `weighted`.
    fn fit(call: &Call<'_>) -> Result<Fit, String> {
        Ok(Fit::LeastSquares {
            degree: super::count_attr(call, "degree")?,
            weighted: call.attr("weighted")? != 0,
        })
    }

    /// The derivatives' map, of degree `degree`.
    fn factored(call: &Call<'_>) -> Result<Fit, String> {
        let degree = super::count_attr(call, "degree")?;
        Ok(Fit::Factored(Factors::LeastSquares { degree }))
    }

    /// The fit of batch element `b` from the derivatives' residuals (for the knots).
    fn refit<'r>(
        fit: Fit,
        res: &'r [super::In<'_>],
        sizes: &[usize],
        dim: usize,
        b: usize,
    ) -> Result<super::LeastSquaresFit<'r>, String> {
        let Fit::LeastSquares { degree, weighted } = fit else {
            return Err("not a least-squares fit".into());
        };
        let operand = |i: usize| super::element(res[i].data, sizes[i], b);
        let w = weighted.then(|| operand(1));
        super::LeastSquaresFit::new(degree, operand(3), operand(0), operand(4), dim, w)
            .map_err(|e| e.to_string())
    }

    fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
        run_eval(fit(call)?, &RESIDUALS, call)
    }

    fn factor_body(call: &mut Call<'_>) -> Result<(), String> {
        run_factor(fit(call)?, &RESIDUALS, call)
    }

    fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
        let (map, plain) = (factored(call)?, fit(call)?);
        let present = super::flags(call, ["with_knots", "with_data"]);
        let Call { args, rets, .. } = call;
        let (res, [dt, dq]) = super::tangents(args, FACTORED.len(), present)?;
        let (batch, sizes, dim) = super::layout(res, &FACTORED)?;
        let (st, sq) = (sizes[3], sizes[4]);
        let tangent = super::single(rets)?;
        let size = batch.size("control-point tangent", tangent.dims, 2)?;
        if let Some(a) = dt {
            batch.expect("knot tangent", a.dims, 1, st)?;
        }
        if let Some(a) = dq {
            batch.expect("data tangent", a.dims, 2, sq)?;
        }
        for b in 0..batch.count {
            let mut out = match dq {
                Some(a) => {
                    let op = super::Op::Jvp(super::element(a.data, sq, b));
                    super::apply(map, res, &sizes, dim, b, op)?
                }
                None => vec![0.0; size],
            };
            if let Some(a) = dt {
                let (_, moved) = refit(plain, res, &sizes, dim, b)?
                    .knot_jvp(super::element(a.data, st, b))
                    .map_err(|e| e.to_string())?;
                if moved.len() != out.len() {
                    return Err(format!(
                        "the knot tangent has {} numbers, the result {}",
                        moved.len(),
                        out.len()
                    ));
                }
                for (o, d) in out.iter_mut().zip(&moved) {
                    *o += d;
                }
            }
            super::store(map, super::element_mut(tangent.data, size, b), &out)?;
        }
        Ok(())
    }

    fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
        let (map, plain) = (factored(call)?, fit(call)?);
        let present = super::flags(call, ["with_knots", "with_data"]);
        let Call { args, rets, .. } = call;
        let (res, [g]) = super::tangents(args, FACTORED.len(), [true])?;
        let g = g.ok_or("no cotangent")?;
        let (batch, sizes, dim) = super::layout(res, &FACTORED)?;
        let (st, sq) = (sizes[3], sizes[4]);
        let size = batch.size("control-point cotangent", g.dims, 2)?;
        let [mut gt, mut gq] = super::cotangents(rets, present)?;
        if let Some(a) = &gt {
            batch.expect("knot cotangent", a.dims, 1, st)?;
        }
        if let Some(a) = &gq {
            batch.expect("data cotangent", a.dims, 2, sq)?;
        }
        for b in 0..batch.count {
            let gb = super::element(g.data, size, b);
            if let Some(a) = gq.as_mut() {
                let got = super::apply(map, res, &sizes, dim, b, super::Op::Vjp(gb))?;
                super::store(map, super::element_mut(a.data, sq, b), &got)?;
            }
            if let Some(a) = gt.as_mut() {
                let got = refit(plain, res, &sizes, dim, b)?
                    .knot_vjp(gb)
                    .map_err(|e| e.to_string())?;
                super::store(map, super::element_mut(a.data, st, b), &got)?;
            }
        }
        Ok(())
    }
}

/// The handlers of `lekalo.jax.fit_smoothing`.
pub(super) mod smoothing {
    ffi_targets! {
        stem: "fit_smoothing",
        function: "fit_smoothing",
        eval: eval_body,
        factor: factor_body,
        jvp: jvp_body,
        vjp: vjp_body,
    }

    use super::{run_eval, run_factor, run_jvp, run_vjp, Factors, Fit};
    use crate::xla_ffi::abi::Call;

    /// x, weights, λ and y, with their core axes.
    const RESIDUALS: [(&str, usize); 4] = [("x", 1), ("w", 1), ("lam", 0), ("y", 2)];

    /// The derivatives' residuals: x, weights, λ, the factors of the forward pass and y.
    const FACTORED: [(&str, usize); 5] = [("x", 1), ("w", 1), ("lam", 0), ("factors", 1), ("y", 2)];

    /// `weighted`.
    fn fit(call: &Call<'_>) -> Result<Fit, String> {
        Ok(Fit::Smoothing {
            weighted: call.attr("weighted")? != 0,
        })
    }

    fn eval_body(call: &mut Call<'_>) -> Result<(), String> {
        run_eval(fit(call)?, &RESIDUALS, call)
    }

    fn factor_body(call: &mut Call<'_>) -> Result<(), String> {
        run_factor(fit(call)?, &RESIDUALS, call)
    }

    fn jvp_body(call: &mut Call<'_>) -> Result<(), String> {
        run_jvp(Fit::Factored(Factors::Smoothing), &FACTORED, call)
    }

    fn vjp_body(call: &mut Call<'_>) -> Result<(), String> {
        run_vjp(Fit::Factored(Factors::Smoothing), &FACTORED, call)
    }
}

/// Which fit a target computes, with its attributes.
#[derive(Clone, Copy)]
enum Fit {
    LeastSquares {
        degree: usize,
        weighted: bool,
    },
    Smoothing {
        weighted: bool,
    },
    /// A fit's derivatives by the map its forward pass kept (the residual before the data).
    Factored(Factors),
}

/// Whose map a forward pass kept.
#[derive(Clone, Copy)]
enum Factors {
    /// [`LeastSquaresMap::to_flat`] of degree `degree`.
    LeastSquares { degree: usize },
    /// [`SmoothingMap::to_flat`].
    Smoothing,
}

/// What a target computes for one batch element.
#[derive(Clone, Copy)]
enum Op<'a> {
    /// The control points of the data (the last residual).
    Values,
    /// `Ṗ` for the data tangent.
    Jvp(&'a [f64]),
    /// `Q̄` for the control-point cotangent.
    Vjp(&'a [f64]),
}

/// The residuals of a fit target (`names`: each one's name and core axes; the data last, as
/// `(m, dim)`): the batch, their element sizes and the dimension.
fn layout<'a>(
    res: &[In<'a>],
    names: &[(&str, usize)],
) -> Result<(Batch<'a>, Vec<usize>, usize), String> {
    let (batch, sizes) = batch_sizes(res, names)?;
    let data = &res[res.len() - 1];
    Ok((
        batch,
        sizes,
        last_axis(names[names.len() - 1].0, data.dims)?,
    ))
}

/// `op` for batch element `b` of the residuals `res` (element sizes `sizes`).
fn apply(
    fit: Fit,
    res: &[In<'_>],
    sizes: &[usize],
    dim: usize,
    b: usize,
    op: Op<'_>,
) -> Result<Vec<f64>, String> {
    let operand = |i: usize| element(res[i].data, sizes[i], b);
    let data = operand(res.len() - 1);
    match fit {
        Fit::LeastSquares { degree, weighted } => {
            let w = weighted.then(|| operand(1));
            let fit = LeastSquaresFit::new(degree, operand(2), operand(0), data, dim, w)
                .map_err(|e| e.to_string())?;
            match op {
                Op::Values => fit.control_points(),
                Op::Jvp(t) => fit.jvp(t),
                Op::Vjp(g) => fit.vjp(g),
            }
        }
        Fit::Smoothing { weighted } => {
            let lam = operand(2).first().copied().ok_or("lam is empty")?;
            let w = weighted.then(|| operand(1));
            let fit =
                SmoothingFit::new(operand(0), data, dim, lam, w).map_err(|e| e.to_string())?;
            match op {
                Op::Values => fit.control_points(),
                Op::Jvp(t) => fit.jvp(t),
                Op::Vjp(g) => fit.vjp(g),
            }
        }
        Fit::Factored(factors) => {
            // the factors follow the constant residuals: before the knots and the points of the
            // least-squares fit, before the values `y` of the smoothing spline
            let at = match factors {
                Factors::LeastSquares { .. } => 2,
                Factors::Smoothing => 3,
            };
            let (flat, m) = (operand(at), data.len() / dim.max(1));
            match (factors, op) {
                (_, Op::Values) => {
                    return Err("the values come from the fit, not its factors".into());
                }
                (Factors::LeastSquares { degree }, Op::Jvp(t)) => {
                    LeastSquaresMap::from_flat(flat, m, degree).and_then(|map| map.jvp(t, dim))
                }
                (Factors::LeastSquares { degree }, Op::Vjp(g)) => {
                    LeastSquaresMap::from_flat(flat, m, degree).and_then(|map| map.vjp(g, dim))
                }
                (Factors::Smoothing, Op::Jvp(t)) => {
                    SmoothingMap::from_flat(flat, m).and_then(|map| map.jvp(t, dim))
                }
                (Factors::Smoothing, Op::Vjp(g)) => {
                    SmoothingMap::from_flat(flat, m).and_then(|map| map.vjp(g, dim))
                }
            }
        }
    }
    .map_err(|e| e.to_string())
}

/// A fit's values and the map of their one factorisation as numbers
/// ([`LeastSquaresFit::control_points_and_map`], [`SmoothingFit::control_points_and_map`] and
/// the maps' `to_flat`) for batch element `b` of the residuals `res` (element sizes `sizes`).
fn values_and_factors(
    fit: Fit,
    res: &[In<'_>],
    sizes: &[usize],
    dim: usize,
    b: usize,
) -> Result<(Vec<f64>, Vec<f64>), String> {
    let operand = |i: usize| element(res[i].data, sizes[i], b);
    let s = |e: lekalo::Error| e.to_string();
    match fit {
        Fit::LeastSquares { degree, weighted } => {
            let w = weighted.then(|| operand(1));
            let fit = LeastSquaresFit::new(degree, operand(2), operand(0), operand(3), dim, w)
                .map_err(s)?;
            let (values, map) = fit.control_points_and_map().map_err(s)?;
            Ok((values, map.to_flat()))
        }
        Fit::Smoothing { weighted } => {
            let lam = operand(2).first().copied().ok_or("lam is empty")?;
            let w = weighted.then(|| operand(1));
            let fit = SmoothingFit::new(operand(0), operand(3), dim, lam, w).map_err(s)?;
            let (values, map) = fit.control_points_and_map().map_err(s)?;
            Ok((values, map.to_flat()))
        }
        Fit::Factored(_) => Err("a fit's factors come from its data, not from factors".into()),
    }
}

/// Copies a batch element's result into its slot of `size` numbers, after checking its length:
/// the smoothing spline of data with a repeated `x` has fewer control points than the shape
/// `lekalo.jax` gave the result.
fn store(fit: Fit, out: &mut [f64], got: &[f64]) -> Result<(), String> {
    if got.len() != out.len() {
        return Err(match fit {
            Fit::Smoothing { .. } => format!(
                "x has repeated values: the smoothing spline has one control point for each \
                 distinct x plus 2 ({} numbers), not len(x) + 2 ({}); give strictly increasing x",
                got.len(),
                out.len()
            ),
            Fit::LeastSquares { .. } | Fit::Factored(_) => format!(
                "the fit has {} numbers, the result {} (lekalo.jax and its native module \
                 disagree)",
                got.len(),
                out.len()
            ),
        });
    }
    out.copy_from_slice(got);
    Ok(())
}

fn run_eval(fit: Fit, names: &[(&str, usize)], call: &mut Call<'_>) -> Result<(), String> {
    let Call { args, rets, .. } = call;
    let (batch, sizes, dim) = layout(args, names)?;
    let control = single(rets)?;
    let size = batch.size("control points", control.dims, 2)?;
    for b in 0..batch.count {
        let got = apply(fit, args, &sizes, dim, b, Op::Values)?;
        store(fit, element_mut(control.data, size, b), &got)?;
    }
    Ok(())
}

/// The values and the factors of the forward pass ([`values_and_factors`]) into the two
/// results, the factors' length checked as [`store`] checks the values'.
fn run_factor(fit: Fit, names: &[(&str, usize)], call: &mut Call<'_>) -> Result<(), String> {
    let Call { args, rets, .. } = call;
    let (batch, sizes, dim) = layout(args, names)?;
    let [control, factors] = &mut rets[..] else {
        return Err(count_error("results", 2, rets.len()));
    };
    let size = batch.size("control points", control.dims, 2)?;
    let flat = batch.size("factors", factors.dims, 1)?;
    for b in 0..batch.count {
        let (values, f) = values_and_factors(fit, args, &sizes, dim, b)?;
        store(fit, element_mut(control.data, size, b), &values)?;
        store(fit, element_mut(factors.data, flat, b), &f)?;
    }
    Ok(())
}

fn run_jvp(fit: Fit, names: &[(&str, usize)], call: &mut Call<'_>) -> Result<(), String> {
    let present = flags(call, ["with_data"]);
    let Call { args, rets, .. } = call;
    let (res, [dq]) = tangents(args, names.len(), present)?;
    let (batch, sizes, dim) = layout(res, names)?;
    let sq = sizes[names.len() - 1];
    let tangent = single(rets)?;
    let size = batch.size("control-point tangent", tangent.dims, 2)?;
    let Some(dq) = dq else {
        tangent.data.fill(0.0);
        return Ok(());
    };
    batch.expect("data tangent", dq.dims, 2, sq)?;
    for b in 0..batch.count {
        let got = apply(fit, res, &sizes, dim, b, Op::Jvp(element(dq.data, sq, b)))?;
        store(fit, element_mut(tangent.data, size, b), &got)?;
    }
    Ok(())
}

fn run_vjp(fit: Fit, names: &[(&str, usize)], call: &mut Call<'_>) -> Result<(), String> {
    let present = flags(call, ["with_data"]);
    let Call { args, rets, .. } = call;
    let (res, [g]) = tangents(args, names.len(), [true])?;
    let g = g.ok_or("no cotangent")?;
    let (batch, sizes, dim) = layout(res, names)?;
    let sq = sizes[names.len() - 1];
    let size = batch.size("control-point cotangent", g.dims, 2)?;
    let [gq] = cotangents(rets, present)?;
    let Some(gq) = gq else {
        return Ok(());
    };
    batch.expect("data cotangent", gq.dims, 2, sq)?;
    for b in 0..batch.count {
        let got = apply(fit, res, &sizes, dim, b, Op::Vjp(element(g.data, size, b)))?;
        store(fit, element_mut(gq.data, sq, b), &got)?;
    }
    Ok(())
}
