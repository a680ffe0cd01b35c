//! The control-point cotangent of a curve's batch evaluation, `P̄_j = Σ_i N_{j,p}(t_i) ḡ_i`,
//! for batches with at least as many parameters as control points (a gradient with respect to
//! the control points): what its two kernels share, and the kernel for degrees above
//! [`POWER_FORM_MAX_DEGREE`].
//!
//! Shared by the two kernels: the parameters located in their spans and the monomorphised
//! common orders and dimensions (`located.rs`), and the cotangent's finiteness read from the
//! sums instead of a pass of its own (a non-finite `ḡ_i` reaches every sum it enters: its
//! weight in the zeroth power sum is exactly 1, and in the basis kernel `N·∞` is infinite or
//! NaN).
//!
//! Kernels: per-piece power sums for degree ≤ [`POWER_FORM_MAX_DEGREE`] (`power_sums.rs`, the
//! transpose of the power-form evaluation), P&T Algorithm A2.2 with the reciprocals of the
//! knot differences computed once a span above it (here): a parameter costs no division.

use crate::curve::fast_eval::{
    basis_by_reciprocals, basis_by_reciprocals_dyn, push_span_reciprocals,
};
use crate::curve::{BSplineCurve, POWER_FORM_MAX_DEGREE};
use crate::error::{check_finite, Result};

use super::checks::check_scalars;
use super::located::{common_orders, Located};
use super::power_sums::control_cotangent_by_power_sums;

/// `gp = Bᵀ ḡ` (`gp` zeroed by the caller, as the control points; `cotangent` `m × dim` of the
/// right length, not yet checked finite), for `m ≥ n`: per-piece power sums for degree ≤
/// [`POWER_FORM_MAX_DEGREE`], A2.2 by reciprocals above; the same sums as the general path to
/// rounding.
///
/// # Errors
/// [`crate::Error::NonFinite`] for a non-finite cotangent (before any parameter error, as the general
/// path); [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain;
/// [`crate::Error::TooLarge`] if the per-span tables would exceed [`crate::MAX_SCALARS`].
pub(super) fn control_cotangent_large(
    curve: &BSplineCurve,
    ts: &[f64],
    cotangent: &[f64],
    gp: &mut [f64],
) -> Result<()> {
    let located = Located::new(curve, ts, cotangent);
    let finite = if curve.degree() <= POWER_FORM_MAX_DEGREE {
        control_cotangent_by_power_sums(curve, &located, gp)?
    } else {
        control_cotangent_by_reciprocals(curve, &located, gp)?;
        gp.iter().all(|v| v.is_finite())
    };
    if !finite {
        // a non-finite cotangent, or finite numbers whose sums overflow (not an error)
        check_finite("cotangent", cotangent)?;
    }
    Ok(())
}

/// `P̄_j = Σ_i N_{j,p}(t_i) ḡ_i` into `gp` (zeroed): the basis functions by P&T Algorithm A2.2
/// with the reciprocals `1 / (t_{s+r+1} − t_{s+r+1−l})` of every span `s` computed once
/// ([`span_reciprocals`]), so that a parameter costs no division and no derivative, and the
/// common orders and dimensions monomorphised. The same numbers as the general path to
/// rounding (a product by a reciprocal for a quotient). O(n·p² + m·(p² + p·dim)).
fn control_cotangent_by_reciprocals(
    curve: &BSplineCurve,
    located: &Located<'_>,
    gp: &mut [f64],
) -> Result<()> {
    let (p, dim) = (curve.degree(), curve.dim());
    let knots = curve.knots().as_slice();
    let recip = span_reciprocals(knots, p, curve.control_points().len())?;
    macro_rules! fixed {
        ($w:literal, $d:literal) => {
            located.walk($d, |span, t, g| {
                let n = basis_by_reciprocals::<$w>(knots, span_triangle(&recip, p, span), span, t);
                let net = &mut gp[(span - p) * $d..(span + 1) * $d];
                for (nk, c) in n.iter().zip(net.chunks_exact_mut($d)) {
                    for d in 0..$d {
                        c[d] += nk * g[d];
                    }
                }
            })
        };
    }
    common_orders!(p, dim, fixed, {
        let mut n = vec![0.0; 3 * (p + 1)];
        located.walk(dim, |span, t, g| {
            let rc = span_triangle(&recip, p, span);
            basis_by_reciprocals_dyn(knots, rc, p, span, t, &mut n);
            let net = &mut gp[(span - p) * dim..(span + 1) * dim];
            for (nk, c) in n[..=p].iter().zip(net.chunks_exact_mut(dim)) {
                for (x, gi) in c.iter_mut().zip(g) {
                    *x += nk * gi;
                }
            }
        })
    })
}

/// Span `span`'s triangle of the table of [`span_reciprocals`].
fn span_triangle(recip: &[f64], p: usize, span: usize) -> &[f64] {
    let tri = p * (p + 1) / 2;
    &recip[(span - p) * tri..(span - p + 1) * tri]
}

/// The reciprocal tables of every span `s` in `p..n`, span `s`'s triangle at
/// `[(s − p)·p(p+1)/2 ..]` ([`push_span_reciprocals`]: the denominators of P&T Algorithm A2.2).
/// Empty spans (never located) get infinities, unused.
fn span_reciprocals(knots: &[f64], p: usize, n: usize) -> Result<Vec<f64>> {
    let tri = p * (p + 1) / 2;
    let size = check_scalars("reciprocal table (spans × p(p + 1)/2)", n - p, tri)?;
    let mut recip = Vec::with_capacity(size);
    for s in p..n {
        push_span_reciprocals(knots, p, s, &mut recip);
    }
    Ok(recip)
}
