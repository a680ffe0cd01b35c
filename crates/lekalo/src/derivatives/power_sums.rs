//! The control-point cotangent of a curve's batch evaluation, `P̄_j = Σ_i N_{j,p}(t_i) ḡ_i`, by
//! per-piece power sums: the transpose of the power-form evaluation of
//! [`crate::CurveEvaluator`].
//!
//! On the piece of span `s` (`x = t_s`, `h = t_{s+1} − t_s`) each basis function is a
//! polynomial in the local parameter `u = (t − x) / h ∈ [0, 1]`,
//! `N_{s−p+r,p}(t) = Σ_k a_{rk} u^k` with `a_{rk} = h^k N^{(k)}_{s−p+r,p}(x⁺) / k!` (Taylor's
//! formula; the derivatives by P&T Algorithm A2.3, once a piece). So
//!
//! `P̄_{s−p+r} += Σ_k a_{rk} S_{s,k}`, `S_{s,k} = Σ_{t_i in piece s} u_i^k ḡ_i`:
//!
//! a parameter costs its `p + 1` powers of `u` and `(p + 1)·dim` multiply–adds into its piece's
//! sums, with no division and no basis triangle; the `a_{rk}` cost O(p³) a piece. Used for degree
//! ≤ [`crate::POWER_FORM_MAX_DEGREE`] only, where the power form's coefficients stay within
//! `3^p` of the basis functions' scale (see `crate::curve::fast_eval`).

use crate::basis::{basis_ders_into, BasisScratch};
use crate::curve::BSplineCurve;
use crate::error::Result;

use super::checks::check_scalars;

/// `gp += Bᵀ ḡ` (`gp` zeroed by the caller, as the control points; `cotangent` `m × dim`) by
/// per-piece power sums, for `p ≤ 3`.
///
/// # Errors
/// [`crate::Error::ParameterOutOfDomain`] at the first parameter outside the domain;
/// [`crate::Error::TooLarge`] if the sums would exceed [`crate::MAX_SCALARS`].
pub(super) fn control_cotangent_by_power_sums(
    curve: &BSplineCurve,
    ts: &[f64],
    cotangent: &[f64],
    gp: &mut [f64],
) -> Result<()> {
    let (p, dim) = (curve.degree(), curve.dim());
    let w = p + 1;
    let knots = curve.knots().as_slice();
    let n = curve.control_points().len();
    let spans = n - p;
    let len = check_scalars(
        "power sums (spans × (degree + 1) × dimension)",
        spans,
        w * dim,
    )?;
    let mut sums = vec![0.0; len];
    // x_s and 1 / h_s a span (infinite for an empty span, which no parameter is located in)
    let origin: Vec<(f64, f64)> = (p..n)
        .map(|s| (knots[s], 1.0 / (knots[s + 1] - knots[s])))
        .collect();
    let mut cursor = curve.knots().span_cursor(p);
    macro_rules! fixed {
        ($w:literal, $d:literal) => {{
            for (&t, g) in ts.iter().zip(cotangent.chunks_exact($d)) {
                let j = cursor.find(t)? - p;
                let (x, inv) = origin[j];
                let u = (t - x) * inv;
                let row = &mut sums[j * $w * $d..(j + 1) * $w * $d];
                let mut uk = 1.0;
                for k in 0..$w {
                    for d in 0..$d {
                        row[k * $d + d] += uk * g[d];
                    }
                    uk *= u;
                }
            }
        }};
    }
    match (p, dim) {
        (1, 1) => fixed!(2, 1),
        (1, 2) => fixed!(2, 2),
        (1, 3) => fixed!(2, 3),
        (2, 1) => fixed!(3, 1),
        (2, 2) => fixed!(3, 2),
        (2, 3) => fixed!(3, 3),
        (3, 1) => fixed!(4, 1),
        (3, 2) => fixed!(4, 2),
        (3, 3) => fixed!(4, 3),
        _ => {
            for (&t, g) in ts.iter().zip(cotangent.chunks_exact(dim)) {
                let j = cursor.find(t)? - p;
                let (x, inv) = origin[j];
                let u = (t - x) * inv;
                let row = &mut sums[j * w * dim..(j + 1) * w * dim];
                let mut uk = 1.0;
                for k in 0..w {
                    for (s, gd) in row[k * dim..(k + 1) * dim].iter_mut().zip(g) {
                        *s += uk * gd;
                    }
                    uk *= u;
                }
            }
        }
    }
    // P̄_{s−p+r} += Σ_k a_{rk} S_{s,k}, a_{rk} = h^k N^{(k)}(x⁺) / k!
    let mut scratch = BasisScratch::new(p);
    let mut ders = vec![0.0; w * w];
    for (j, s) in (p..n).enumerate() {
        let row = &sums[j * w * dim..(j + 1) * w * dim];
        if knots[s] >= knots[s + 1] || row.iter().all(|&v| v == 0.0) {
            continue;
        }
        let h = knots[s + 1] - knots[s];
        basis_ders_into(knots, p, s, knots[s], p, &mut scratch, &mut ders);
        let mut factor = 1.0; // h^k / k!
        for k in 0..w {
            let sk = &row[k * dim..(k + 1) * dim];
            for r in 0..w {
                let a = ders[k * w + r] * factor;
                let out = &mut gp[(j + r) * dim..(j + r + 1) * dim];
                for (o, &v) in out.iter_mut().zip(sk) {
                    *o += a * v;
                }
            }
            #[allow(clippy::cast_precision_loss)] // a degree
            let next = (k + 1) as f64;
            factor *= h / next;
        }
    }
    Ok(())
}
