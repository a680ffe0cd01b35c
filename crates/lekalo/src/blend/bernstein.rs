//! Bernstein-domain operations used by blending (crate-internal).
//!
//! A polynomial of degree `n` on `[0, 1]` is kept as its Bernstein (Bezier) coefficients
//! `c_0 … c_n`, each a point of dimension `dim` stored flat (`c_i = ctrl[i*dim..(i+1)*dim]`):
//! `f(u) = Σ_i c_i b_{n,i}(u)`, `b_{n,i}(u) = C(n,i) (1−u)^{n−i} u^i`.
//!
//! - [`derivatives_at`]: `f^{(l)}(u)` for `l = 0..=order` by de Casteljau's algorithm and forward
//!   differences, `f^{(l)}(u) = n!/(n−l)! · Δ^l r^{(n−l)}_0` where `r^{(n−l)}` are the `l + 1`
//!   points left after `n − l` de Casteljau steps (Farin, *Curves and Surfaces for CAGD*, 5th ed.,
//!   §5.4, "derivatives via de Casteljau"). Every step is a convex combination or a difference of
//!   neighbours, so no monomial conversion (and its cancellation) happens.
//! - [`product`]: the Bernstein coefficients of a product, `(Σ a_i b_{m,i})(Σ c_j b_{d,j}) =
//!   Σ_l [Σ_{i+j=l} C(m,i) C(d,j) / C(m+d,l) · a_i c_j] b_{m+d,l}` (Farouki & Rajan,
//!   *Algorithms for polynomials in Bernstein form*, CAGD 5 (1988), §3).
//!   The weights `C(m,i) C(d,j) / C(m+d,l)` are positive and sum to 1 over `i + j = l`, so the
//!   result is a convex combination: stable, and positive inputs give positive outputs (this is
//!   why blended NURBS keep positive weights).

/// Binomial coefficient `C(n, k)` as `f64` (0 for `k > n`), by the multiplicative formula
/// `Π_{j=1}^{k} (n − k + j) / j`; every partial product is the integer `C(n − k + j, j)`, so the
/// result is exact while it stays below 2^53.
pub(crate) fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut c = 1.0_f64;
    for j in 1..=k {
        c = c * (n - k + j) as f64 / j as f64;
    }
    c
}

/// Derivatives `f^{(l)}(u)`, `l = 0..=order`, of the Bernstein polynomial with coefficients
/// `ctrl` (degree `n = ctrl.len()/dim − 1`), into `out` (`(order + 1) * dim`, row `l` the l-th
/// derivative). Orders above `n` are zero. `scratch` is resized to `2 · ctrl.len()` (reuse it
/// across calls to avoid allocation; [`derivatives_at_in`] takes any slice that long).
/// O(n² · dim + order³ · dim).
///
/// Method: see the module docs (de Casteljau + forward differences).
pub(crate) fn derivatives_at(
    ctrl: &[f64],
    dim: usize,
    u: f64,
    order: usize,
    out: &mut [f64],
    scratch: &mut Vec<f64>,
) {
    scratch.resize(2 * ctrl.len(), 0.0);
    derivatives_at_in(ctrl, dim, u, order, out, scratch);
}

/// Stack room for [`with_work`]: enough for [`derivatives_at_in`] on a 3-D curve of degree 9.
const SMALL_WORK: usize = 64;

/// Calls `f` with a zeroed work slice of `len` numbers: on the stack up to [`SMALL_WORK`],
/// allocated above, so that evaluations of small curves allocate nothing.
pub(crate) fn with_work<R>(len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    if len <= SMALL_WORK {
        let mut stack = [0.0; SMALL_WORK];
        f(&mut stack[..len])
    } else {
        f(&mut vec![0.0; len])
    }
}

/// [`derivatives_at`] with the work space given as a slice of at least `2 · ctrl.len()`
/// numbers (the de Casteljau points, then their differences).
pub(crate) fn derivatives_at_in(
    ctrl: &[f64],
    dim: usize,
    u: f64,
    order: usize,
    out: &mut [f64],
    work: &mut [f64],
) {
    debug_assert!(dim > 0 && ctrl.len() % dim == 0 && !ctrl.is_empty(), "ctrl");
    debug_assert_eq!(out.len(), (order + 1) * dim, "derivative output length");
    debug_assert!(work.len() >= 2 * ctrl.len(), "work space");
    let (scratch, diff) = work.split_at_mut(ctrl.len());
    let n = ctrl.len() / dim - 1;
    out.fill(0.0);
    scratch.copy_from_slice(ctrl);
    // after `m` de Casteljau steps, points 0..=n−m remain; they give derivative l = n − m
    for m in 0..=n {
        let l = n - m;
        if l <= order {
            // Δ^l of the l + 1 remaining points, times n!/(n−l)!
            let diff = &mut diff[..(l + 1) * dim];
            diff.copy_from_slice(&scratch[..(l + 1) * dim]);
            for level in 1..=l {
                for i in 0..=(l - level) {
                    for d in 0..dim {
                        diff[i * dim + d] = diff[(i + 1) * dim + d] - diff[i * dim + d];
                    }
                }
            }
            let falling: f64 = (m + 1..=n).map(|x| x as f64).product();
            for d in 0..dim {
                // an exact zero stays zero even when n!/(n−l)! overflows (no inf·0 = NaN)
                out[l * dim + d] = if diff[d] == 0.0 {
                    0.0
                } else {
                    falling * diff[d]
                };
            }
        }
        if m < n {
            let t1 = 1.0 - u;
            for i in 0..(n - m) {
                for d in 0..dim {
                    scratch[i * dim + d] =
                        t1 * scratch[i * dim + d] + u * scratch[(i + 1) * dim + d];
                }
            }
        }
    }
}

/// Bernstein coefficients (degree `m + d`) of the product of the scalar Bernstein polynomial
/// `a` (degree `m = a.len() − 1`) and the point-valued one `ctrl` (degree `d`, dimension `dim`).
/// Formula in the module docs (Farouki & Rajan 1988). O(m · d · dim).
pub(crate) fn product(a: &[f64], ctrl: &[f64], dim: usize) -> Vec<f64> {
    debug_assert!(
        !a.is_empty() && dim > 0 && ctrl.len() % dim == 0 && !ctrl.is_empty(),
        "args"
    );
    let m = a.len() - 1;
    let d = ctrl.len() / dim - 1;
    let mut out = vec![0.0; (m + d + 1) * dim];
    for (i, &ai) in a.iter().enumerate() {
        if ai == 0.0 {
            continue;
        }
        let ci = binomial(m, i);
        for j in 0..=d {
            let l = i + j;
            let weight = ci * binomial(d, j) / binomial(m + d, l);
            for k in 0..dim {
                out[l * dim + k] += weight * ai * ctrl[j * dim + k];
            }
        }
    }
    out
}

/// Bernstein coefficients of the restriction `f(t_0 + u (t_1 − t_0))`, `u ∈ [0, 1]`, of the
/// polynomial with coefficients `ctrl`, by two de Casteljau subdivisions (Farin, *Curves and Surfaces
/// for CAGD*, §4.6, subdivision): split at `t_1` and keep the left part,
/// then split that at `t_0 / t_1` and keep the right part. Stable (convex combinations only for
/// `0 ≤ t_0 < t_1 ≤ 1`). O(n² · dim).
pub(crate) fn restrict(ctrl: &[f64], dim: usize, t0: f64, t1: f64) -> Vec<f64> {
    debug_assert!(
        (0.0..1.0).contains(&t0) && t0 < t1 && t1 <= 1.0,
        "0 <= t0 < t1 <= 1"
    );
    let n = ctrl.len() / dim - 1;
    let left = if t1 < 1.0 {
        subdivide(ctrl, dim, t1).0
    } else {
        ctrl.to_vec()
    };
    if t0 > 0.0 {
        subdivide(&left, dim, t0 / t1).1
    } else {
        debug_assert_eq!(left.len(), (n + 1) * dim, "restrict length");
        left
    }
}

/// De Casteljau subdivision at `t`: the control points of the left and right parts.
fn subdivide(ctrl: &[f64], dim: usize, t: f64) -> (Vec<f64>, Vec<f64>) {
    let n = ctrl.len() / dim - 1;
    let mut work = ctrl.to_vec();
    let mut left = Vec::with_capacity(ctrl.len());
    let mut right = vec![0.0; ctrl.len()];
    left.extend_from_slice(&work[..dim]);
    right[n * dim..].copy_from_slice(&work[n * dim..]);
    for level in 1..=n {
        for i in 0..=(n - level) {
            for d in 0..dim {
                work[i * dim + d] = (1.0 - t) * work[i * dim + d] + t * work[(i + 1) * dim + d];
            }
        }
        left.extend_from_slice(&work[..dim]);
        let last = n - level;
        right[last * dim..(last + 1) * dim].copy_from_slice(&work[last * dim..(last + 1) * dim]);
    }
    (left, right)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::bernstein;

    fn eval_sum(ctrl: &[f64], u: f64) -> f64 {
        let n = ctrl.len() - 1;
        ctrl.iter()
            .enumerate()
            .map(|(i, c)| c * bernstein(n, i, u))
            .sum()
    }

    #[test]
    fn restriction_reparametrises() {
        let c = [0.5, -1.0, 2.0, 3.0, 0.25];
        for (t0, t1) in [(0.0, 0.4), (0.3, 1.0), (0.2, 0.7), (0.0, 1.0)] {
            let r = restrict(&c, 1, t0, t1);
            assert_eq!(r.len(), c.len());
            for step in 0..=10 {
                let u = f64::from(step) / 10.0;
                let expect = eval_sum(&c, t0 + u * (t1 - t0));
                assert!(
                    (eval_sum(&r, u) - expect).abs() < 1e-14,
                    "[{t0}, {t1}] at {u}"
                );
            }
        }
    }

    #[test]
    fn binomials() {
        assert_eq!(binomial(5, 2), 10.0);
        assert_eq!(binomial(40, 20), 137_846_528_820.0);
        assert_eq!(binomial(3, 4), 0.0);
        assert_eq!(binomial(0, 0), 1.0);
    }

    /// f(u) = 1 − 2u + 3u² + u³ written in Bernstein form of degree 3, derivatives against the
    /// monomial form.
    #[test]
    fn derivatives_match_monomial() {
        // monomial -> Bernstein: c_i = Σ_{j≤i} C(i,j)/C(n,j) a_j
        let a = [1.0, -2.0, 3.0, 1.0];
        let n = 3;
        let ctrl: Vec<f64> = (0..=n)
            .map(|i| {
                (0..=i)
                    .map(|j| binomial(i, j) / binomial(n, j) * a[j])
                    .sum()
            })
            .collect();
        let mut out = vec![0.0; 6];
        let mut scratch = Vec::new();
        for step in 0..=8 {
            let u = f64::from(step) / 8.0;
            derivatives_at(&ctrl, 1, u, 5, &mut out, &mut scratch);
            let f = 1.0 - 2.0 * u + 3.0 * u * u + u * u * u;
            let f1 = -2.0 + 6.0 * u + 3.0 * u * u;
            let f2 = 6.0 + 6.0 * u;
            let expect = [f, f1, f2, 6.0, 0.0, 0.0];
            for l in 0..6 {
                assert!((out[l] - expect[l]).abs() < 1e-13, "order {l} at {u}");
            }
        }
    }

    #[test]
    fn product_evaluates_to_product() {
        let a = [0.3, -1.0, 2.0];
        let c = [1.0, 4.0, -0.5, 2.0, 0.0, 1.0, 3.0, 3.0]; // 4 points in 2D
        let p = product(&a, &c, 2);
        assert_eq!(p.len(), 6 * 2, "degree 2 + 3");
        let cx: Vec<f64> = c.iter().step_by(2).copied().collect();
        let cy: Vec<f64> = c.iter().skip(1).step_by(2).copied().collect();
        let px: Vec<f64> = p.iter().step_by(2).copied().collect();
        let py: Vec<f64> = p.iter().skip(1).step_by(2).copied().collect();
        for step in 0..=10 {
            let u = f64::from(step) / 10.0;
            let fa = eval_sum(&a, u);
            assert!(
                (eval_sum(&px, u) - fa * eval_sum(&cx, u)).abs() < 1e-14,
                "x at {u}"
            );
            assert!(
                (eval_sum(&py, u) - fa * eval_sum(&cy, u)).abs() < 1e-14,
                "y at {u}"
            );
        }
    }
}
