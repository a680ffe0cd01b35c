//! Changing the degree of Bezier curves without changing their shape (document 004, Nikulin
//! 2011, "A new method of changing the orders of Bezier curves and surfaces", digest §E).
//!
//! The paper calls the degree `n` the "order" (the number of legs of the control polygon). It
//! works with the monomial form `p(t) = U_n H_n T_n(t)` (eq. 1–5): elevation is
//! `U' = U_n H_n K_{n,n'}` (eq. 7–8), exact reduction `U' = U_n G_{n,n'} H_{n'}^{-1}` (eq. 9) and
//! both together the unified `U' = U_n H_n E_{n+1,n'+1} H_{n'}^{-1}` (eq. 10). Those matrices are
//! built exactly by [`order_change_matrix`](crate::order_change_matrix) and its relatives and the literal floating-point formula is
//! [`BezierCurve::change_degree_by_matrix`].
//!
//! ## Stable path (the default)
//! The monomial basis is ill-conditioned: `H_n` has entries up to about `3^n`, so the paper's
//! formula in `f64` loses about `n·log10(3)` digits. Measured relative error of the literal
//! eq. 10 for an elevation by 3 of rough nets (worst of 5): 2e-15 at degree 5, 3e-13 at 10,
//! 4e-10 at 15, 1e-7 at 20, 1e-5 at 25, 4e-3 at 30 (test `matrix_path_accuracy_degrades`). So
//! the matrix formula meets 1e-10 only up to degree 14. The default operations therefore never
//! leave the Bernstein basis:
//! - **elevation** by `r` in one step with the closed form of eq. 8,
//!   `u'_j = Σ_i C(n,i) C(r,j−i) / C(n+r,j) u_i` (Farin, *Curves and Surfaces for CAGD*, §5.1):
//!   a convex combination, accurate to a few ulps of the net's scale at any degree;
//! - **exact reduction** from `n` to `k` in one step as the least-squares inverse of that
//!   elevation (a banded Householder QR of the `(n+1)×(k+1)` elevation matrix; the residual is
//!   zero when the degree defect is at least `n − k`, document 004 eq. 9). Reducing one degree at
//!   a time by the recurrences inverting eq. 6 (Forrest 1972) is not used: each step amplifies
//!   the previous step's rounding errors by up to `n/2`, and the amplifications multiply;
//! - **real degree**: the smallest `k` such that reducing to `k` and elevating back to `n`
//!   reproduces the control net within `tolerance × scale`, where `scale` is the largest absolute
//!   control-point coordinate ([`Points::max_abs`]). Because the curve lies in the convex hull of
//!   its control net, a control-net difference of `δ` moves the curve by at most `δ` (per
//!   coordinate), so the test says "reducing to `k` moves the curve by at most
//!   `tolerance × scale`". The default is [`DEFAULT_DEGREE_TOLERANCE`].
//!
//! ## Limits
//! - Elevation keeps the curve to 1e-13 relative at every degree tested (up to 60, proptests).
//! - Exact reduction from `n` to `k` returns a net accurate to about `cond(E)·ε` relative, where
//!   `cond(E)` is the condition number of the elevation matrix from `k` to `n` (computed with
//!   mpmath: 3.2e2 for 20→30, 2.0e5 for 40→60, 1.2e7 for 40→80). Measured (elevate a rough net,
//!   reduce back, worst of 5): 4e-15 for 20→10, 2e-14 for 30→20, 2e-13 for 40→20, 2e-12 for
//!   50→30, 2e-11 for 60→40, 2e-10 for 80→60, 6e-10 for 80→40. So 1e-10 holds up to degree 40
//!   elevated by 20 at least (test `stable_path_degree_40`, proptests in `tests/degree_change.rs`).
//! - The real degree depends on the tolerance: a smooth control polygon of high degree is often
//!   within `1e-10 × scale` of a lower degree, and then that lower degree is its real degree.

use crate::degree::elevation_plan::{apply_band, band_stride, elevation_band};
use crate::error::{check_finite, Error, Result, MAX_SCALARS};
use crate::points::Points;
use crate::BezierCurve;
use std::cell::RefCell;

/// Default relative tolerance of the degree-defect test: a reduction is accepted as exact when it
/// changes no control-point coordinate by more than `1e-10 ×` the largest absolute coordinate.
/// Elevated nets computed in `f64` reduce back with residuals near `1e-15`, so this leaves five
/// orders of magnitude for data that went through other software or a text file.
pub const DEFAULT_DEGREE_TOLERANCE: f64 = 1e-10;

/// Largest degree for the monomial (power-basis) conversions in `f64`: above it the binomial
/// coefficients `C(n, j)` overflow.
pub const MAX_MONOMIAL_DEGREE: usize = 1000;

// ---------------------------------------------------------------------------------------------
// Kernels on flat point-major slices (pub(crate); callers validate).
// ---------------------------------------------------------------------------------------------

/// Largest `n` for which every binomial coefficient `C(n, k)` is an integer below `2^53`, so exact
/// in `f64` (`C(56, 28) ≈ 7.65·10^15 < 2^53 ≈ 9.01·10^15 < C(57, 28)`).
const EXACT_BINOMIAL_MAX: usize = 56;

/// Largest `n` of the binomial table: every `C(n, k)` up to `C(131, 65) ≈ 1.9·10^38` is an exact
/// `u128` at compile time, stored correctly rounded to `f64` (exact up to
/// [`EXACT_BINOMIAL_MAX`]).
pub(crate) const BINOMIAL_TABLE_MAX: usize = 131;

/// Entries of the triangle `0 ≤ k ≤ n ≤ BINOMIAL_TABLE_MAX`.
const BINOMIAL_ENTRIES: usize = (BINOMIAL_TABLE_MAX + 1) * (BINOMIAL_TABLE_MAX + 2) / 2;

/// Pascal's triangle row after row: `C(n, k)` at `n(n+1)/2 + k`.
static BINOMIAL: [f64; BINOMIAL_ENTRIES] = pascal();

/// Pascal's triangle by `C(n, k) = C(n−1, k−1) + C(n−1, k)` in `u128` (exact), at compile time,
/// each entry then rounded to the nearest `f64`.
const fn pascal() -> [f64; BINOMIAL_ENTRIES] {
    let mut exact = [0_u128; BINOMIAL_ENTRIES];
    let mut rounded = [0.0_f64; BINOMIAL_ENTRIES];
    let mut n = 0;
    while n <= BINOMIAL_TABLE_MAX {
        let row = n * (n + 1) / 2;
        let mut k = 0;
        while k <= n {
            exact[row + k] = if k == 0 || k == n {
                1
            } else {
                let prev = (n - 1) * n / 2;
                exact[prev + k - 1] + exact[prev + k]
            };
            rounded[row + k] = exact[row + k] as f64;
            k += 1;
        }
        n += 1;
    }
    rounded
}

/// The row `C(n, 0 ..= n)` of the binomial table (correctly rounded, exact up to `n = 56`), or
/// `None` above [`BINOMIAL_TABLE_MAX`].
pub(crate) fn binomial_row(n: usize) -> Option<&'static [f64]> {
    (n <= BINOMIAL_TABLE_MAX).then(|| &BINOMIAL[n * (n + 1) / 2..=n * (n + 1) / 2 + n])
}

/// Weights `w_i = C(n,i) C(r,j−i) / C(n+r,j)` of point `u_i` in the elevated point `u'_j`, for
/// `i = lo..=hi` with `lo = max(0, j−r)`, `hi = min(j, n)`, written to `out[..=hi−lo]`. Returns
/// `lo`.
///
/// Up to `n + r = 56` ([`EXACT_BINOMIAL_MAX`]) the binomials come from a table and are exact,
/// and so is the numerator (`C(n,i) C(r,j−i) ≤ C(n+r,j) < 2^53` by Vandermonde's identity): each
/// weight is the correctly rounded quotient of two exact integers, one division. Above, the
/// weights are hypergeometric probabilities built from their ratios starting at the mode (so
/// nothing overflows at any degree) and normalised by their sum, which is exactly 1
/// (Vandermonde's identity); each weight is then accurate to a few ulps.
pub(crate) fn elevation_weights_into(n: usize, r: usize, j: usize, out: &mut [f64]) -> usize {
    let lo = j.saturating_sub(r);
    let hi = j.min(n);
    debug_assert!(lo <= hi && out.len() > hi - lo, "weights buffer too short");
    if let (true, Some(row_n), Some(row_r), Some(row_nr)) = (
        n + r <= EXACT_BINOMIAL_MAX,
        binomial_row(n),
        binomial_row(r),
        binomial_row(n + r),
    ) {
        let total = row_nr[j];
        for (w, i) in out.iter_mut().zip(lo..=hi) {
            // the product is an exact integer below 2^53
            *w = row_n[i] * row_r[j - i] / total;
        }
        return lo;
    }
    ratio_weights_into(n, r, j, out)
}

/// The weights of [`elevation_weights_into`] from their ratios, for any degree.
fn ratio_weights_into(n: usize, r: usize, j: usize, out: &mut [f64]) -> usize {
    let lo = j.saturating_sub(r);
    let hi = j.min(n);
    // mode of the hypergeometric distribution (population n + r, n successes, j draws)
    let mode = ((j + 1) * (n + 1) / (n + r + 2)).clamp(lo, hi);
    out[mode - lo] = 1.0;
    for i in mode..hi {
        // w(i+1)/w(i) = (n−i)(j−i) / ((i+1)(r−j+i+1))
        let ratio = ((n - i) * (j - i)) as f64 / ((i + 1) * (r + i + 1 - j)) as f64;
        out[i + 1 - lo] = out[i - lo] * ratio;
    }
    for i in (lo + 1..=mode).rev() {
        // w(i−1)/w(i) = i(r−j+i) / ((n−i+1)(j−i+1))
        let ratio = (i * (r + i - j)) as f64 / ((n - i + 1) * (j - i + 1)) as f64;
        out[i - 1 - lo] = out[i - lo] * ratio;
    }
    let sum: f64 = out[..=hi - lo].iter().sum();
    for w in &mut out[..=hi - lo] {
        *w /= sum;
    }
    lo
}

/// Largest band (in numbers) [`elevate`] keeps between calls: 64 Ki numbers, 512 KiB.
const KEPT_BAND_MAX: usize = 1 << 16;

thread_local! {
    /// `(n, r, band)` of this thread's last one-step elevation ([`elevate`]).
    static LAST_BAND: RefCell<(usize, usize, Vec<f64>)> =
        const { RefCell::new((usize::MAX, 0, Vec::new())) };
}

/// One-step elevation by `r` into a new vector (document 004 eq. 8 in closed form): the band of
/// weights ([`elevation_band`]) applied to `src` (`n + 1` points of `dim` coordinates).
/// O((n+1)(r+1)·dim), the same arithmetic as an [`ElevationPlan`](crate::ElevationPlan).
///
/// The band depends on `(n, r)` only, and forming it (`n + r + 1` divisions, `(n+1)(r+1)`
/// products) costs more than applying it to a 3-D curve: 0.38 µs a call against the plan's
/// 0.10 µs for 10 → 20. So the last band of each thread (up to [`KEPT_BAND_MAX`] numbers) is kept,
/// and a run of elevations between the same degrees forms it once. The numbers are the same
/// either way (tested).
pub(crate) fn elevate(src: &[f64], dim: usize, r: usize) -> Vec<f64> {
    let n_pts = src.len() / dim;
    let mut out = vec![0.0; (n_pts + r) * dim];
    if n_pts == 0 {
        return out;
    }
    let n = n_pts - 1;
    let kept = (n + 1).saturating_mul(band_stride(r)) <= KEPT_BAND_MAX
        && LAST_BAND
            .try_with(|slot| {
                // (a slot in use or a thread being torn down: form the band afresh)
                let Ok(mut slot) = slot.try_borrow_mut() else {
                    return false;
                };
                if (slot.0, slot.1) != (n, r) {
                    *slot = (n, r, elevation_band(n, r));
                }
                apply_band(&slot.2, r, src, dim, &mut out);
                true
            })
            .unwrap_or(false);
    if !kept {
        apply_band(&elevation_band(n, r), r, src, dim, &mut out);
    }
    out
}

/// Least-squares inverse of elevation: the degree-`k` net `Q` minimising `‖E Q − P‖₂` for each
/// coordinate, where `E` is the `(n+1)×(k+1)` elevation matrix `C(k,i) C(r,j−i) / C(n,j)`,
/// `r = n − k` (the transpose of `H_k K_{k,n}`, document 004 eq. 8). When `P` is an elevated net
/// (a degree defect of at least `r`, eq. 9) the residual is zero and `Q` is the exact reduction.
///
/// Householder QR that exploits the band (column `i` of `E` is non-zero in rows `i..=i+r` only,
/// and so is row `i` of `R` in columns `i..=i+r`): O((k+1)(r+1)(r+1+dim)) flops, backward stable.
/// The error in `Q` is bounded by `cond(E)·ε·scale`; measured `cond(E)`: 4.6 for 40→41, 3.2e2
/// for 20→30, 2.0e5 for 40→60, 1.2e7 for 40→80. This is far better than reducing one degree
/// at a time, whose error amplifications multiply.
pub(crate) fn reduce_least_squares(src: &[f64], dim: usize, k: usize) -> Vec<f64> {
    let rows = src.len() / dim;
    let n = rows - 1;
    debug_assert!(k <= n, "reduction target above the degree");
    let r = n - k;
    // E column-major: a[i * rows + j] = weight of q_i in p_j
    let mut a = vec![0.0; rows * (k + 1)];
    let mut w = vec![0.0; k + 1];
    for j in 0..=n {
        let lo = elevation_weights_into(k, r, j, &mut w);
        for i in lo..=j.min(k) {
            a[i * rows + j] = w[i - lo];
        }
    }
    let mut b = src.to_vec(); // right-hand sides, row-major (rows × dim)
    let mut diag = vec![0.0; k + 1];
    let mut v = vec![0.0; r + 1];
    let mut dots = vec![0.0; dim];
    for i in 0..=k {
        let last = (i + r).min(n);
        let len = last - i + 1;
        let col = &a[i * rows + i..=i * rows + last];
        let norm = crate::numeric::linalg::norm2(col);
        let alpha = if col[0] > 0.0 { -norm } else { norm };
        v[..len].copy_from_slice(col);
        v[0] -= alpha;
        let vv = dot4(&v[..len], &v[..len]);
        diag[i] = alpha;
        if vv == 0.0 {
            continue;
        }
        let tau = 2.0 / vv;
        for j in i + 1..=(i + r).min(k) {
            let cj = &mut a[j * rows + i..=j * rows + last];
            let dot = dot4(cj, &v[..len]);
            for (x, y) in cj.iter_mut().zip(&v[..len]) {
                *x -= tau * dot * y;
            }
        }
        // all coordinates at once: one pass over the rows, `dim` independent sums
        let rhs = &mut b[i * dim..(last + 1) * dim];
        dots.fill(0.0);
        for (row, &vl) in rhs.chunks_exact(dim).zip(&v[..len]) {
            for (s, &x) in dots.iter_mut().zip(row) {
                *s += x * vl;
            }
        }
        for (row, &vl) in rhs.chunks_exact_mut(dim).zip(&v[..len]) {
            for (x, &s) in row.iter_mut().zip(&dots) {
                *x -= tau * s * vl;
            }
        }
    }
    // back substitution with R (diagonal in `diag`, R[i][j] = a[j * rows + i] for j > i)
    let mut q = vec![0.0; (k + 1) * dim];
    for i in (0..=k).rev() {
        for d in 0..dim {
            let mut s = b[i * dim + d];
            for j in i + 1..=(i + r).min(k) {
                s -= a[j * rows + i] * q[j * dim + d];
            }
            q[i * dim + d] = s / diag[i];
        }
    }
    q
}

/// `Σ a_l b_l` in four interleaved partial sums (combined pairwise at the end), so that the
/// Householder updates of [`reduce_least_squares`] are not bound by the latency of one chain of
/// additions; as accurate as the sequential sum (the error bound of pairwise summation).
fn dot4(a: &[f64], b: &[f64]) -> f64 {
    let mut s = [0.0_f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for l in 0..4 {
            s[l] += x[l] * y[l];
        }
    }
    for (l, (x, y)) in ra.iter().zip(rb).enumerate() {
        s[l] += x * y;
    }
    (s[0] + s[1]) + (s[2] + s[3])
}

/// Whether the net reduces exactly to degree `k`: the least-squares reduction, elevated back,
/// reproduces `src` within `tol_abs` per coordinate. Returns the reduced net if so.
pub(crate) fn try_reduce_exact(
    src: &[f64],
    dim: usize,
    k: usize,
    tol_abs: f64,
) -> Option<Vec<f64>> {
    let n = src.len() / dim - 1;
    let mut q = reduce_least_squares(src, dim, k);
    if k >= 1 {
        // an exact reduction keeps the end points (eq. 6 read backwards): use them exactly, so
        // that joins of Bezier pieces stay bit-identical
        q[..dim].copy_from_slice(&src[..dim]);
        q[k * dim..].copy_from_slice(&src[n * dim..]);
    }
    let back = elevate(&q, dim, n - k);
    (max_abs_diff(&back, src) <= tol_abs).then_some(q)
}

/// Largest coordinate difference; infinite if any difference is NaN or infinite.
pub(crate) fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    let mut m = 0.0_f64;
    for (x, y) in a.iter().zip(b) {
        let d = (x - y).abs();
        if !d.is_finite() {
            return f64::INFINITY;
        }
        m = m.max(d);
    }
    m
}

/// Real degree of the net `src` and the net reduced to it: the smallest `k ≥ floor` to which
/// [`try_reduce_exact`] reduces it, found by galloping down from the top (degrees `n − 1`,
/// `n − 2`, `n − 4`, … until one fails) and bisecting between the last success and that
/// failure.
///
/// Reducibility is monotone in `k` (a degree-`k` net elevated by one is a degree-`k + 1`
/// reduction), which both this search and a scan down from `n − 1` to the first failure rely
/// on; they return the same degree (tested). A net without defect costs one O(n·dim) reduction,
/// as before; a defect `d` costs about `2 log₂ d` reductions instead of `d + 1` (3-D,
/// 100 → 48: 4.5 ms scanned, see `docs/performance.md`, session 6).
pub(crate) fn real_degree_and_net(
    src: &[f64],
    dim: usize,
    tol_abs: f64,
    floor: usize,
) -> (usize, Vec<f64>) {
    let n = src.len() / dim - 1;
    // the lowest degree known to reduce, with its net, and a degree below it known not to
    let mut good = (n, src.to_vec());
    let mut bad = None;
    let mut step = 1;
    while bad.is_none() && good.0 > floor {
        let k = n.saturating_sub(step).max(floor);
        match try_reduce_exact(src, dim, k, tol_abs) {
            Some(q) => good = (k, q),
            None => bad = Some(k),
        }
        step = step.saturating_mul(2);
    }
    if let Some(mut bad) = bad {
        while good.0 - bad > 1 {
            let mid = bad + (good.0 - bad) / 2;
            match try_reduce_exact(src, dim, mid, tol_abs) {
                Some(q) => good = (mid, q),
                None => bad = mid,
            }
        }
    }
    good
}

/// Checks a relative tolerance and turns it into an absolute one for a net.
pub(crate) fn absolute_tolerance(tolerance: f64, net: &[f64]) -> Result<f64> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(Error::InvalidArgument {
            what: "degree tolerance",
            reason: format!(
                "{tolerance} is not a finite non-negative number (relative to the largest \
                 absolute control-point coordinate; the default is {DEFAULT_DEGREE_TOLERANCE})"
            ),
        });
    }
    Ok(tolerance * net.iter().fold(0.0_f64, |m, v| m.max(v.abs())))
}

/// Binomial coefficients `C(n, 0..=n)` in `f64` (exact up to `n = 56`, a few ulps beyond).
pub(crate) fn binomials(n: usize) -> Vec<f64> {
    let mut c = Vec::with_capacity(n + 1);
    let mut v = 1.0_f64;
    c.push(v);
    for j in 1..=n {
        v = v * (n + 1 - j) as f64 / j as f64;
        c.push(v);
    }
    for j in 0..=n / 2 {
        c[n - j] = c[j];
    }
    c
}

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

/// Real degree by the paper's rule (§E.3): the number of trailing monomial coefficients that
/// vanish. `s_j` counts as zero when `|s_j| ≤ tol_abs · C(n,j) · 2^j`, the size of its rounding
/// error when computed from a net of scale 1.
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

fn check_monomial_degree(degree: usize) -> Result<()> {
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

/// Checks that `points × dim` scalars can be allocated.
pub(crate) fn check_size(what: &'static str, points: usize, dim: usize) -> Result<()> {
    match points.checked_mul(dim) {
        Some(size) if size <= MAX_SCALARS => Ok(()),
        other => Err(Error::TooLarge {
            what,
            size: other.unwrap_or(usize::MAX),
            max: MAX_SCALARS,
        }),
    }
}

pub(crate) fn finite_result(what: &'static str, data: Vec<f64>, dim: usize) -> Result<Points> {
    if check_finite(what, &data).is_err() {
        return Err(Error::IllConditioned {
            reason: format!("{what} overflowed f64"),
        });
    }
    Ok(Points::from_raw(data, dim))
}

// ---------------------------------------------------------------------------------------------
// Bezier curves
// ---------------------------------------------------------------------------------------------

impl BezierCurve {
    /// Monomial coefficients `s_0 … s_n` with `p(t) = Σ s_j t^j`: the columns of `S_n = U_n H_n`
    /// (document 004 eq. 2 and 5), computed as `s_j = C(n,j) Δ^j u_0` from forward differences of
    /// the control points (the same numbers, O(n²·dim) instead of a matrix product).
    ///
    /// The power basis is ill-conditioned: the coefficients of a curve of scale 1 carry rounding
    /// errors up to about `C(n,j)·2^j·ε` (ε = 2.2e-16), so use it for low degrees or inspection.
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // document 004, Example 2: S_5 = [[10, 60, −150, 100, 0, 0], [0, 30, 0, −30, 0, 0]]
    /// let u = Points::from_2d(&[[10., 0.], [22., 6.], [19., 12.], [11., 15.], [8., 12.], [20., 0.]])?;
    /// let s = BezierCurve::new(u)?.to_monomial()?;
    /// assert_eq!(s.as_slice(), &[10., 0., 60., 30., -150., 0., 100., -30., 0., 0., 0., 0.]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Degree`] above [`MAX_MONOMIAL_DEGREE`]; [`Error::IllConditioned`] if a
    /// coefficient overflows.
    pub fn to_monomial(&self) -> Result<Points> {
        check_monomial_degree(self.degree())?;
        let p = self.control_points();
        finite_result(
            "monomial coefficients",
            to_monomial_vec(p.as_slice(), p.dim()),
            p.dim(),
        )
    }

    /// The Bezier curve of degree `n` (= number of coefficients − 1) with `p(t) = Σ s_j t^j`:
    /// `U_n = S_n H_n^{-1}`, `u_j = Σ_{i≤j} C(j,i)/C(n,i) s_i` (document 004 eq. 5 with the
    /// closed-form inverse of digest §E.1). O(n²·dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // p(t) = 1 + 2t + 0t², a quadratic whose real degree is 1 (the paper's example, §E.2)
    /// let c = BezierCurve::from_monomial(Points::new(vec![1.0, 2.0, 0.0], 1)?)?;
    /// assert_eq!(c.control_points().as_slice(), &[1.0, 2.0, 3.0]);
    /// assert_eq!(c.real_degree(), 1);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::TooFew`] for no coefficients; [`Error::Degree`] above [`MAX_MONOMIAL_DEGREE`];
    /// [`Error::IllConditioned`] if a control point overflows.
    pub fn from_monomial(coefficients: Points) -> Result<BezierCurve> {
        if coefficients.is_empty() {
            return Err(Error::TooFew {
                what: "monomial coefficients",
                min: 1,
                got: 0,
            });
        }
        check_monomial_degree(coefficients.len() - 1)?;
        let dim = coefficients.dim();
        let u = from_monomial_vec(coefficients.as_slice(), dim);
        Ok(BezierCurve::from_raw(finite_result(
            "control points from monomial coefficients",
            u,
            dim,
        )?))
    }

    /// Elevation by one, the classical recurrence of document 004 eq. 6:
    /// `u'_0 = u_0`, `u'_i = i/(n+1) u_{i−1} + (1 − i/(n+1)) u_i`, `u'_{n+1} = u_n`.
    /// O(n·dim); the shape is unchanged.
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // document 004, Example 1, task 1: u'_1 = u_0/3 + 2u_1/3
    /// let c = BezierCurve::new(Points::new(vec![0.0, 3.0, 6.0], 1)?)?.elevate_degree_once();
    /// assert_eq!(c.control_points().as_slice(), &[0.0, 2.0, 4.0, 6.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn elevate_degree_once(&self) -> BezierCurve {
        let p = self.control_points();
        let (dim, n) = (p.dim(), self.degree());
        let src = p.as_slice();
        let mut out = vec![0.0; (n + 2) * dim];
        out[..dim].copy_from_slice(&src[..dim]);
        let n1 = (n + 1) as f64;
        for i in 1..=n {
            let a = i as f64 / n1;
            for k in 0..dim {
                out[i * dim + k] = a * src[(i - 1) * dim + k] + (1.0 - a) * src[i * dim + k];
            }
        }
        out[(n + 1) * dim..].copy_from_slice(&src[n * dim..]);
        BezierCurve::from_raw(Points::from_raw(out, dim))
    }

    /// Elevation by `by` in one step (document 004 eq. 7–8) in the closed form
    /// `u'_j = Σ_i C(n,i) C(r,j−i) / C(n+r,j) u_i`, `r = by` (digest §E.2; Farin, *Curves and
    /// Surfaces for CAGD*, §5.1). Each new point is a convex combination of old ones, so the
    /// result is accurate to a few ulps of the net's scale at any degree. Equal to `by`
    /// applications of [`BezierCurve::elevate_degree_once`]. O((n+1)(r+1)·dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // document 004, Example 1, task 3: u'_2 = (u_0 + 6u_1 + 3u_2)/10
    /// let c = BezierCurve::new(Points::new(vec![10.0, 0.0, 0.0, 0.0], 1)?)?.elevate_degree(2)?;
    /// assert!((c.control_points().as_slice()[2] - 1.0).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::TooLarge`] if the new net would exceed [`MAX_SCALARS`](crate::MAX_SCALARS);
    /// [`Error::IllConditioned`] if a coordinate within an ulp of `f64::MAX` overflows.
    pub fn elevate_degree(&self, by: usize) -> Result<BezierCurve> {
        let p = self.control_points();
        let pts = p.len().saturating_add(by);
        check_size("elevated control points", pts, p.dim())?;
        let out = elevate(p.as_slice(), p.dim(), by);
        Ok(BezierCurve::from_raw(finite_result(
            "elevated control points",
            out,
            p.dim(),
        )?))
    }

    /// Real degree with the default tolerance [`DEFAULT_DEGREE_TOLERANCE`]; see
    /// [`BezierCurve::real_degree_with_tolerance`].
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // document 004, Example 2: the quintic is a cubic
    /// let u = Points::from_2d(&[[10., 0.], [22., 6.], [19., 12.], [11., 15.], [8., 12.], [20., 0.]])?;
    /// let c = BezierCurve::new(u)?;
    /// assert_eq!((c.real_degree(), c.degree_defect()), (3, 2));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn real_degree(&self) -> usize {
        let p = self.control_points();
        let tol = DEFAULT_DEGREE_TOLERANCE * p.max_abs();
        real_degree_and_net(p.as_slice(), p.dim(), tol, 0).0
    }

    /// Degree defect `d = n − n'` (document 004 §E.3) with the default tolerance.
    #[must_use]
    pub fn degree_defect(&self) -> usize {
        self.degree() - self.real_degree()
    }

    /// Real degree `n'` of the polynomial (document 004 §E.3): the smallest `k` such that the
    /// exact reduction to degree `k` (stable Bernstein-domain recurrences, see the module
    /// documentation), elevated back to degree `n`, reproduces every control-point coordinate to
    /// within `tolerance × max|coordinate|`. By the convex-hull property the curve then moves by
    /// at most that much per coordinate. Equivalent in exact arithmetic to the paper's count of
    /// zero trailing monomial coefficients ([`BezierCurve::real_degree_monomial`]), but stable at
    /// high degree. O(n·d²·(d + dim)) for a defect `d` (O(n·dim) without defect).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if `tolerance` is negative or not finite.
    pub fn real_degree_with_tolerance(&self, tolerance: f64) -> Result<usize> {
        let p = self.control_points();
        let tol = absolute_tolerance(tolerance, p.as_slice())?;
        Ok(real_degree_and_net(p.as_slice(), p.dim(), tol, 0).0)
    }

    /// Real degree by the paper's literal rule (document 004 §E.3): the number of trailing zero
    /// columns of `S_n = U_n H_n`. Coefficient `s_j` counts as zero when every coordinate is at
    /// most `tolerance × max|coordinate| × C(n,j) × 2^j`, the scale of its rounding error. Reliable
    /// for low degrees (about 15); use [`BezierCurve::real_degree_with_tolerance`] otherwise.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a bad tolerance; as [`BezierCurve::to_monomial`].
    pub fn real_degree_monomial(&self, tolerance: f64) -> Result<usize> {
        let p = self.control_points();
        let tol = absolute_tolerance(tolerance, p.as_slice())?;
        let s = self.to_monomial()?;
        Ok(real_degree_monomial_slice(s.as_slice(), p.dim(), tol))
    }

    /// The minimal control polygon: exact reduction to the real degree (document 004 eq. 9,
    /// computed by the stable recurrences of the module documentation), default tolerance.
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // document 004, Example 2
    /// let u = Points::from_2d(&[[10., 0.], [22., 6.], [19., 12.], [11., 15.], [8., 12.], [20., 0.]])?;
    /// let cubic = BezierCurve::new(u)?.reduce_degree_exact();
    /// let expect = [10., 0., 30., 10., 0., 20., 20., 0.];
    /// for (a, b) in cubic.control_points().as_slice().iter().zip(expect) {
    ///     assert!((a - b).abs() < 1e-12);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn reduce_degree_exact(&self) -> BezierCurve {
        let p = self.control_points();
        let tol = DEFAULT_DEGREE_TOLERANCE * p.max_abs();
        let (_, net) = real_degree_and_net(p.as_slice(), p.dim(), tol, 0);
        BezierCurve::from_raw(Points::from_raw(net, p.dim()))
    }

    /// Changes the degree to `target` without changing the shape (document 004 eq. 10), with the
    /// default tolerance; see [`BezierCurve::change_degree_with_tolerance`].
    ///
    /// ```
    /// use lekalo::{BezierCurve, Error, Points};
    /// let c = BezierCurve::new(Points::from_2d(&[[0., 0.], [1., 2.], [3., 2.], [4., 0.]])?)?;
    /// let up = c.change_degree(7)?;
    /// assert_eq!(up.change_degree(3)?.degree(), 3);
    /// let e = up.change_degree(2).unwrap_err();
    /// assert!(matches!(e, Error::DegreeReductionRefused { requested: 2, real_degree: 3, .. }));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BezierCurve::change_degree_with_tolerance`].
    pub fn change_degree(&self, target: usize) -> Result<BezierCurve> {
        self.change_degree_with_tolerance(target, DEFAULT_DEGREE_TOLERANCE)
    }

    /// Changes the degree from `n` to `target` without changing the shape: the unified order
    /// change of document 004 eq. 10, `U' = U_n H_n E_{n+1,n'+1} H_{n'}^{-1}`, computed in the
    /// Bernstein basis.
    /// - `target ≥ n`: elevation by `target − n` ([`BezierCurve::elevate_degree`]); always possible.
    /// - `target < n`: exact reduction, possible only if the real degree
    ///   ([`BezierCurve::real_degree_with_tolerance`]) is at most `target`. Otherwise the request
    ///   is refused instead of silently changing the shape (which eq. 10 would do by dropping
    ///   the terms `t^(target+1) … t^n`, digest §E.3). For an approximation use
    ///   [`BezierCurve::reduce_degree_approx`].
    ///
    /// # Errors
    /// [`Error::DegreeReductionRefused`] with the real degree; [`Error::InvalidArgument`] for a
    /// bad tolerance; [`Error::TooLarge`] for an elevation too large to allocate.
    pub fn change_degree_with_tolerance(
        &self,
        target: usize,
        tolerance: f64,
    ) -> Result<BezierCurve> {
        let p = self.control_points();
        let (n, dim) = (self.degree(), p.dim());
        let tol = absolute_tolerance(tolerance, p.as_slice())?;
        if target >= n {
            return self.elevate_degree(target - n);
        }
        if let Some(q) = try_reduce_exact(p.as_slice(), dim, target, tol) {
            return Ok(BezierCurve::from_raw(Points::from_raw(q, dim)));
        }
        let (real, _) = real_degree_and_net(p.as_slice(), dim, tol, target + 1);
        Err(Error::DegreeReductionRefused {
            requested: target,
            real_degree: real,
            direction: "curve",
        })
    }

    /// The paper's unified formula (document 004 eq. 10) evaluated literally in `f64`:
    /// `S = U_n H_n` (dense), the real degree from the trailing zero columns of `S`
    /// ([`BezierCurve::real_degree_monomial`]), then `U' = [S | 0] H_{n'}^{-1}` or
    /// `U' = S E H_{n'}^{-1}`. Kept as the reference the stable path is checked against.
    ///
    /// Accuracy: relative errors grow like `3^n ε` (measured 3e-13 at degree 10, 4e-10 at 15,
    /// 1e-7 at 20, 4e-3 at 30; see the module documentation). Prefer
    /// [`BezierCurve::change_degree`].
    ///
    /// # Errors
    /// [`Error::DegreeReductionRefused`]; [`Error::InvalidArgument`] for a bad tolerance;
    /// [`Error::Degree`] above [`MAX_MONOMIAL_DEGREE`]; [`Error::IllConditioned`] on overflow.
    pub fn change_degree_by_matrix(&self, target: usize, tolerance: f64) -> Result<BezierCurve> {
        let p = self.control_points();
        let (n, dim) = (self.degree(), p.dim());
        check_monomial_degree(n.max(target))?;
        let tol = absolute_tolerance(tolerance, p.as_slice())?;
        // S = U H_n, literally: s_j = Σ_i u_i h_ij, h_ij = (−1)^(j−i) C(n,j) C(j,i)
        let cn = binomials(n);
        let mut s = vec![0.0; (target + 1) * dim];
        let mut s_full = vec![0.0; (n + 1) * dim];
        for j in 0..=n {
            let cj = binomials(j);
            for i in 0..=j {
                let sign = if (j - i) % 2 == 0 { 1.0 } else { -1.0 };
                let h = sign * cn[j] * cj[i];
                for k in 0..dim {
                    s_full[j * dim + k] += h * p.as_slice()[i * dim + k];
                }
            }
        }
        let real = real_degree_monomial_slice(&s_full, dim, tol);
        if target < real {
            return Err(Error::DegreeReductionRefused {
                requested: target,
                real_degree: real,
                direction: "curve",
            });
        }
        let keep = (n.min(target) + 1) * dim;
        s[..keep].copy_from_slice(&s_full[..keep]);
        // U' = S' H_{n'}^{-1}: u'_j = Σ_{i≤j} C(j,i)/C(n',i) s'_i
        let c_target = binomials(target);
        let mut u = vec![0.0; (target + 1) * dim];
        for j in 0..=target {
            let cj = binomials(j);
            for i in 0..=j {
                let h = cj[i] / c_target[i];
                for k in 0..dim {
                    u[j * dim + k] += h * s[i * dim + k];
                }
            }
        }
        Ok(BezierCurve::from_raw(finite_result(
            "control points (matrix path)",
            u,
            dim,
        )?))
    }
}

#[cfg(test)]
mod tests {
    /// The galloping search of `real_degree_and_net` returns the degree and net of the scan
    /// from `n − 1` down to the first failure, for nets elevated from random ones (defects 0 to
    /// 40, degrees up to 60, 1–3 dimensions), with and without a floor.
    #[test]
    fn galloping_real_degree_matches_scan() {
        use super::{elevate, real_degree_and_net, try_reduce_exact, DEFAULT_DEGREE_TOLERANCE};
        let scan = |src: &[f64], dim: usize, tol: f64, floor: usize| {
            let n = src.len() / dim - 1;
            let mut best = (n, src.to_vec());
            for k in (floor..n).rev() {
                match try_reduce_exact(src, dim, k, tol) {
                    Some(q) => best = (k, q),
                    None => break,
                }
            }
            best
        };
        let mut seed = 7_u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for dim in 1..=3 {
            for (m, d) in [
                (0, 3),
                (1, 0),
                (2, 5),
                (3, 1),
                (5, 7),
                (8, 8),
                (12, 20),
                (20, 40),
            ] {
                let base: Vec<f64> = (0..(m + 1) * dim).map(|_| next()).collect();
                let src = if d == 0 { base } else { elevate(&base, dim, d) };
                let tol =
                    DEFAULT_DEGREE_TOLERANCE * src.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
                for floor in [0, m / 2, m + d / 2] {
                    let got = real_degree_and_net(&src, dim, tol, floor);
                    let want = scan(&src, dim, tol, floor);
                    assert_eq!(got.0, want.0, "dim {dim}, {m} + {d}, floor {floor}");
                    assert_eq!(got.1, want.1, "dim {dim}, {m} + {d}, floor {floor}");
                }
            }
        }
    }

    /// The kept band gives the numbers a freshly formed band gives, whichever elevation came
    /// before, and a band over the limit is formed every time.
    #[test]
    fn kept_elevation_band_changes_nothing() {
        use super::{apply_band, elevate, elevation_band, KEPT_BAND_MAX};
        let fresh = |src: &[f64], dim: usize, r: usize| {
            let mut out = vec![0.0; (src.len() / dim + r) * dim];
            apply_band(
                &elevation_band(src.len() / dim - 1, r),
                r,
                src,
                dim,
                &mut out,
            );
            out
        };
        let net = |pts: usize, dim: usize| -> Vec<f64> {
            (0..pts * dim)
                .map(|i| (i as f64 * 0.7).sin() * 3.0 + 1.0)
                .collect()
        };
        // alternate degrees and elevations so that the slot both hits and misses
        for (pts, dim, r) in [
            (11, 3, 10),
            (11, 3, 10),
            (5, 2, 3),
            (11, 3, 10),
            (11, 2, 4),
            (5, 2, 3),
        ] {
            let src = net(pts, dim);
            assert_eq!(
                elevate(&src, dim, r),
                fresh(&src, dim, r),
                "{pts} points by {r}"
            );
        }
        // too large to keep: (n + 1) rows of r + 1 + 2·BAND_PAD numbers above the limit
        let (pts, r) = (300, KEPT_BAND_MAX / 300);
        let src = net(pts, 1);
        assert_eq!(elevate(&src, 1, r), fresh(&src, 1, r), "large band");
        // and the kept slot still serves the small one afterwards
        let src = net(11, 3);
        assert_eq!(
            elevate(&src, 3, 10),
            fresh(&src, 3, 10),
            "after the large band"
        );
    }

    #[test]
    fn exact_binomial_weights_agree_with_the_ratio_weights() {
        use super::{binomial_row, elevation_weights_into, ratio_weights_into, EXACT_BINOMIAL_MAX};
        // the table is Pascal's triangle, exact up to C(56, 28) (below 2^53), rounded beyond
        let row = |n| binomial_row(n).unwrap();
        assert_eq!(row(56)[28], 7_648_690_600_760_440.0);
        assert!(row(56)[28] < 2.0_f64.powi(53));
        assert_eq!(row(10)[3], 120.0);
        assert_eq!(row(10).len(), 11);
        // C(131, 65) = 188694833082770476622296176145946360850 (exact, rounded once)
        assert_eq!(
            row(131)[65],
            188_694_833_082_770_476_622_296_176_145_946_360_850_u128 as f64
        );
        assert!(binomial_row(132).is_none());
        let (mut a, mut b) = ([0.0; 64], [0.0; 64]);
        for n in 0..=EXACT_BINOMIAL_MAX {
            for r in 0..=EXACT_BINOMIAL_MAX - n {
                for j in 0..=n + r {
                    let lo = elevation_weights_into(n, r, j, &mut a);
                    assert_eq!(lo, ratio_weights_into(n, r, j, &mut b));
                    let count = j.min(n) - lo + 1;
                    let sum: f64 = a[..count].iter().sum();
                    assert!((sum - 1.0).abs() <= 64.0 * f64::EPSILON, "sum {sum}");
                    for (x, y) in a[..count].iter().zip(&b[..count]) {
                        assert!(
                            (x - y).abs() <= 8.0 * f64::EPSILON * x.max(*y),
                            "n {n}, r {r}, j {j}: {x} vs {y}"
                        );
                    }
                }
            }
        }
    }

    use super::*;

    /// A rough, deterministic net in [−4, 4] (a fixed hash, not randomness). Smooth nets would
    /// not do: their high-degree components are so small that their real degree at a tolerance
    /// of 1e-10 is lower than their formal degree.
    fn net(n: usize, dim: usize, seed: f64) -> Points {
        let data = (0..(n + 1) * dim)
            .map(|i| {
                let x = ((i as f64) * 12.9898 + seed * 78.233).sin() * 43758.5453;
                8.0 * (x - x.floor()) - 4.0
            })
            .collect();
        Points::new(data, dim).unwrap()
    }

    fn curve_dev(a: &BezierCurve, b: &BezierCurve) -> f64 {
        (0..=200)
            .map(|k| {
                let t = f64::from(k) / 200.0;
                max_abs_diff(&a.eval(t).unwrap(), &b.eval(t).unwrap())
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn weights_match_closed_form() {
        for n in 0..=9 {
            for r in 0..=6 {
                let exact = crate::elevation_matrix(n, n + r).unwrap().to_f64();
                let mut w = vec![0.0; n + 1];
                for j in 0..=n + r {
                    let lo = elevation_weights_into(n, r, j, &mut w);
                    for i in 0..=n {
                        let got = if i >= lo && i <= j.min(n) {
                            w[i - lo]
                        } else {
                            0.0
                        };
                        let e = exact[i * (n + r + 1) + j];
                        assert!((got - e).abs() <= 4.0 * f64::EPSILON * e, "{n} {r} {j} {i}");
                    }
                }
            }
        }
    }

    #[test]
    fn weights_do_not_overflow_at_high_degree() {
        let (n, r) = (3000, 2500);
        let mut w = vec![0.0; n + 1];
        let j = 2700;
        let lo = elevation_weights_into(n, r, j, &mut w);
        let s: f64 = w[..=j.min(n) - lo].iter().sum();
        assert!(w.iter().all(|x| x.is_finite() && *x >= 0.0), "finite");
        assert!((s - 1.0).abs() < 1e-13, "sum {s}");
    }

    #[test]
    fn one_step_equals_repeated_eq6() {
        let c = BezierCurve::new(net(6, 3, 0.3)).unwrap();
        let mut rep = c.clone();
        for _ in 0..5 {
            rep = rep.elevate_degree_once();
        }
        let one = c.elevate_degree(5).unwrap();
        let scale = c.control_points().max_abs();
        assert!(
            max_abs_diff(
                one.control_points().as_slice(),
                rep.control_points().as_slice()
            ) <= 1e-14 * scale,
            "one step vs eq. 6"
        );
        assert_eq!(c.elevate_degree(0).unwrap(), c, "r = 0 is the identity");
    }

    #[test]
    fn stable_path_degree_40() {
        for dim in [1, 3] {
            let c = BezierCurve::new(net(40, dim, 1.1)).unwrap();
            let scale = c.control_points().max_abs();
            let up = c.elevate_degree(20).unwrap();
            assert!(
                curve_dev(&c, &up) <= 1e-13 * scale,
                "elevation keeps the curve"
            );
            assert_eq!(up.real_degree(), 40, "real degree");
            let down = up.change_degree(40).unwrap();
            let err = max_abs_diff(
                down.control_points().as_slice(),
                c.control_points().as_slice(),
            );
            // measured 4e-12 relative; the promise is 1e-10 (cond of the 40→60 elevation is 2e5)
            assert!(err <= 1e-10 * scale, "reduction inverts elevation: {err:e}");
            assert!(matches!(
                up.change_degree(39),
                Err(Error::DegreeReductionRefused {
                    requested: 39,
                    real_degree: 40,
                    ..
                })
            ));
        }
    }

    #[test]
    fn matrix_path_agrees_at_low_degree() {
        let c = BezierCurve::new(net(5, 2, 0.4)).unwrap();
        let up = c.elevate_degree(4).unwrap();
        let scale = c.control_points().max_abs();
        for target in 5..=12 {
            let a = up.change_degree(target).unwrap();
            let b = up
                .change_degree_by_matrix(target, DEFAULT_DEGREE_TOLERANCE)
                .unwrap();
            let d = max_abs_diff(a.control_points().as_slice(), b.control_points().as_slice());
            assert!(d <= 1e-11 * scale, "target {target}: {d:e}");
        }
        assert!(matches!(
            up.change_degree_by_matrix(4, DEFAULT_DEGREE_TOLERANCE),
            Err(Error::DegreeReductionRefused { real_degree: 5, .. })
        ));
        assert_eq!(up.real_degree_monomial(1e-10).unwrap(), 5, "paper's rule");
    }

    #[test]
    fn matrix_path_accuracy_degrades() {
        // The literal eq. 10 loses digits like 3^n; the stable path does not.
        let c = BezierCurve::new(net(20, 1, 0.2)).unwrap();
        let scale = c.control_points().max_abs();
        let stable = c.elevate_degree(5).unwrap();
        let literal = c
            .change_degree_by_matrix(25, DEFAULT_DEGREE_TOLERANCE)
            .unwrap();
        let d = max_abs_diff(
            stable.control_points().as_slice(),
            literal.control_points().as_slice(),
        );
        assert!(
            d > 1e-12 * scale,
            "the matrix path is visibly less accurate: {d:e}"
        );
        assert!(d < 1e-3 * scale, "but still roughly right: {d:e}");
    }

    #[test]
    fn monomial_round_trip_and_errors() {
        let c = BezierCurve::new(net(7, 2, 0.9)).unwrap();
        let back = BezierCurve::from_monomial(c.to_monomial().unwrap()).unwrap();
        let scale = c.control_points().max_abs();
        assert!(
            max_abs_diff(
                back.control_points().as_slice(),
                c.control_points().as_slice()
            ) <= 1e-12 * scale,
            "round trip"
        );
        assert!(matches!(
            BezierCurve::from_monomial(Points::new(vec![], 2).unwrap()),
            Err(Error::TooFew { .. })
        ));
        let big =
            BezierCurve::new(Points::new(vec![0.0; MAX_MONOMIAL_DEGREE + 2], 1).unwrap()).unwrap();
        assert!(matches!(big.to_monomial(), Err(Error::Degree { .. })));
        let huge =
            BezierCurve::new(Points::new(vec![1.5e308, -1.5e308, 1.5e308], 1).unwrap()).unwrap();
        assert!(matches!(
            huge.to_monomial(),
            Err(Error::IllConditioned { .. })
        ));
        assert!(matches!(
            c.real_degree_with_tolerance(-1.0),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            c.change_degree_with_tolerance(3, f64::NAN),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            c.elevate_degree(usize::MAX),
            Err(Error::TooLarge { .. })
        ));
    }

    #[test]
    fn constant_and_linear_nets() {
        let p = BezierCurve::new(Points::new(vec![2.0, 2.0, 2.0, 2.0], 1).unwrap()).unwrap();
        assert_eq!(p.real_degree(), 0, "constant");
        assert_eq!(p.reduce_degree_exact().control_points().as_slice(), &[2.0]);
        let z = BezierCurve::new(Points::new(vec![0.0; 6], 2).unwrap()).unwrap();
        assert_eq!(z.real_degree(), 0, "zero net");
        let l = BezierCurve::new(Points::new(vec![1.0, 2.0, 3.0, 4.0], 1).unwrap()).unwrap();
        assert_eq!(l.real_degree(), 1, "line");
        let single = BezierCurve::new(Points::new(vec![5.0], 1).unwrap()).unwrap();
        assert_eq!(single.change_degree(0).unwrap(), single, "degree 0 stays");
    }
}
