//! Exact degree reduction of Bezier curves (document 004 eq. 9) as the least-squares inverse of
//! elevation (a banded Householder QR of the elevation matrix), and the real degree: the
//! smallest degree that reproduces the control net within a tolerance (kernels on flat
//! point-major slices; callers validate).

use crate::degree::elevation::{elevate, elevation_weights_into};
use crate::error::readable;
use crate::error::{Error, Result};

/// Default relative tolerance of the degree-defect test: a reduction is accepted as exact when it
/// changes no control-point coordinate by more than `1e-10 ×` the largest absolute coordinate.
/// Elevated nets computed in `f64` reduce back with residuals near `1e-15`, so this leaves five
/// orders of magnitude for data that went through other software or a text file.
pub const DEFAULT_DEGREE_TOLERANCE: f64 = 1e-10;

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
/// 100 → 48: 4.5 ms scanned, see `docs/performance.md`).
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
            what: "degree tolerance".into(),
            reason: format!(
                "{tolerance} is not a finite non-negative number (relative to the largest \
                 absolute control-point coordinate; the default is {DEFAULT_DEGREE_TOLERANCE})",
                tolerance = readable(&tolerance)
            ),
        });
    }
    Ok(tolerance * net.iter().fold(0.0_f64, |m, v| m.max(v.abs())))
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
}
