//! The monomial (power-basis) form of a Bezier curve, `p(t) = Σ_j s_j t^j` with
//! `s_j = C(n,j) Δ^j u_0` (document 004 eq. 1–5, the columns of `U_n H_n`), and the paper's own
//! real-degree rule on it (trailing monomial coefficients that vanish).

use crate::degree::elevation::binomials;
use crate::error::{Error, Result};

/// Largest degree for the monomial (power-basis) conversions in `f64`: above it the binomial
/// coefficients `C(n, j)` overflow.
pub const MAX_MONOMIAL_DEGREE: usize = 1000;

/// Monomial coefficients `s_j = C(n,j) Δ^j u_0` (the columns of `U_n H_n`, document 004 eq. 5).
pub(crate) fn to_monomial_vec(src: &[f64], dim: usize) -> Vec<f64> {
    let n = src.len() / dim - 1;
    let c = binomials(n);
    let mut diff = src.to_vec();
    let mut out = vec![0.0; src.len()];
    out[..dim].copy_from_slice(&src[..dim]);
    for j in 1..=n {
        for i in 0..=(n - j) {
            for k in 0..dim {
                diff[i * dim + k] = diff[(i + 1) * dim + k] - diff[i * dim + k];
            }
        }
        for k in 0..dim {
            out[j * dim + k] = c[j] * diff[k];
        }
    }
    out
}

/// Control points `u_j = Σ_{i≤j} C(j,i)/C(n,i) s_i` from monomial coefficients (`S_n H_n^{-1}`).
pub(crate) fn from_monomial_vec(coeffs: &[f64], dim: usize) -> Vec<f64> {
    let n = coeffs.len() / dim - 1;
    let mut out = vec![0.0; coeffs.len()];
    for j in 0..=n {
        let mut ratio = 1.0_f64; // C(j,i)/C(n,i) at i = 0
        for i in 0..=j {
            for k in 0..dim {
                out[j * dim + k] += ratio * coeffs[i * dim + k];
            }
            if i < j {
                ratio *= (j - i) as f64 / (n - i) as f64;
            }
        }
    }
    out
}

/// Real degree by the paper's rule (document 004, eq. (9)–(10)): the number of trailing monomial
/// coefficients that vanish. `s_j` counts as zero when `|s_j| ≤ tol_abs · C(n,j) · 2^j`, the size
/// of its rounding error when computed from a net of scale 1.
pub(crate) fn real_degree_monomial_slice(coeffs: &[f64], dim: usize, tol_abs: f64) -> usize {
    let n = coeffs.len() / dim - 1;
    let c = binomials(n);
    let mut degree = n;
    while degree > 0 {
        let bound = tol_abs * c[degree] * 2.0_f64.powi(i32::try_from(degree).unwrap_or(i32::MAX));
        let s = &coeffs[degree * dim..(degree + 1) * dim];
        if s.iter().all(|x| x.abs() <= bound) {
            degree -= 1;
        } else {
            break;
        }
    }
    degree
}

pub(crate) fn check_monomial_degree(degree: usize) -> Result<()> {
    if degree > MAX_MONOMIAL_DEGREE {
        return Err(Error::Degree {
            degree,
            reason: format!(
                "monomial (power-basis) conversion is limited to degree {MAX_MONOMIAL_DEGREE}, \
                 above which the binomial coefficients overflow f64"
            ),
        });
    }
    Ok(())
}
