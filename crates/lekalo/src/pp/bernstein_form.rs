//! The Bernstein basis of each piece of SciPy's `BPoly` ([`BernsteinBasis`]) and its arrays
//! read in place ([`BernsteinFormRef`]): coefficients `c` of shape `(k + 1, pieces, dim)`,
//! evaluated in each piece without a copy or a change of basis. The arrays, the piece search
//! and the batch drivers are the generic view's (`piecewise_ref.rs`).
//! `docs/theory/pp.md#extrapolation-in-pp-form`.

use crate::pp::piecewise_ref::{Piece, PieceBasis, PiecewiseRef};

/// The Bernstein basis of each piece of SciPy's `BPoly`: on piece `j`,
/// `t = s = (x − x_j)/h_j`, `h_j = x_{j+1} − x_j`, and `f(x) = Σ_{a=0}^{k} c[a, j]·b_{a,k}(s)`,
/// `b_{a,k}(s) = C(k, a)·s^a·(1 − s)^{k−a}`. Degree `k ≤ 3`: the Bernstein sum written out, in
/// the operations and order of SciPy's `evaluate_bpoly1` (so the same bits); higher degrees:
/// de Casteljau's algorithm (Farin, *Curves and Surfaces for CAGD*, 5th ed., §4.1),
/// `k(k + 1)/2` convex combinations, stable for `s` in `[0, 1]`. Derivatives:
/// `D^nu f = k!/(k − nu)!·h^{−nu}·Σ_a Δ^nu c_a·b_{a,k−nu}(s)` with the forward differences
/// `Δ^nu c_a` (Farin §5.3). Beyond the ends the same polynomials at `s < 0` or `s > 1`.
/// O(k²·dim) a point above degree 3, O(k·dim) up to it; a scratch of `k + 1` numbers for
/// derivatives.
#[derive(Debug, Clone, Copy)]
pub struct BernsteinBasis;

impl super::piecewise_ref::sealed::Sealed for BernsteinBasis {}

impl PieceBasis for BernsteinBasis {
    #[inline(always)]
    fn local(piece: &Piece<'_>, x: f64) -> f64 {
        (x - piece.start()) / piece.width()
    }

    /// The written-out sum up to degree 3, de Casteljau's algorithm on the stack above.
    #[inline(always)]
    fn value<const K: usize>(c: &[f64; K], s: f64) -> f64 {
        if K <= 4 {
            bernstein_sum(K - 1, s, |a| c[a])
        } else {
            let mut w = *c;
            de_casteljau(s, &mut w)
        }
    }

    #[inline(always)]
    fn derivative(piece: &Piece<'_>, s: f64, nu: usize, w: &mut [f64], o: &mut [f64]) {
        let k = piece.order() - 1;
        // Δ^nu c, scaled by k!/(k − nu)!, then the sum of degree k − nu
        let falling: f64 = (k - nu + 1..=k).map(|v| v as f64).product();
        let h = piece.width();
        let h_nu = (0..nu).fold(1.0, |p, _| p * h);
        for (d, v) in o.iter_mut().enumerate() {
            for (a, wa) in w.iter_mut().enumerate() {
                *wa = piece.coefficient(a, d);
            }
            for r in 1..=nu {
                for a in 0..=k - r {
                    w[a] = w[a + 1] - w[a];
                }
            }
            let w = &mut w[..=k - nu];
            for wa in w.iter_mut() {
                *wa *= falling;
            }
            *v = match k - nu {
                degree @ 0..=3 => bernstein_sum(degree, s, |a| w[a]),
                _ => de_casteljau(s, w),
            } / h_nu;
        }
    }

    fn scratch_len(order: usize) -> usize {
        order
    }

    /// SciPy's `evaluate_bpoly1` at `s = (x − x_j)/h_j` (the written-out sums up to degree 3,
    /// above it `Σ_a C(k, a)·s^a·(1 − s)^{k−a}·c_a` with the powers by `pow`), and for `nu > 0`
    /// its `evaluate_bpoly1_deriv`: the coefficients `(k!/(k − nu)!)·Σ_j (−1)^{j+nu} C(nu, j)
    /// c_{a+j}` summed by the same, divided by `h_j^nu` (`pow`).
    fn scipy_derivative(piece: &Piece<'_>, x: f64, nu: usize, w: &mut [f64], o: &mut [f64]) {
        let k = piece.order() - 1;
        let h = piece.width();
        let s = (x - piece.start()) / h;
        let poch = (0..nu).fold(1.0, |p, a| p * (k - a) as f64);
        for (d, v) in o.iter_mut().enumerate() {
            if nu == 0 {
                *v = scipy_bernstein_sum(k, s, |a| piece.coefficient(a, d));
                continue;
            }
            for (a, wa) in w.iter_mut().enumerate().take(k - nu + 1) {
                let (mut term, mut comb) = (0.0, 1.0);
                for j in 0..=nu {
                    let sign = if (j + nu) % 2 == 0 { 1.0 } else { -1.0 };
                    term += piece.coefficient(j + a, d) * sign * comb;
                    comb *= (nu - j) as f64 / (j + 1) as f64;
                }
                *wa = term * poch;
            }
            *v = scipy_bernstein_sum(k - nu, s, |a| w[a]) / h.powf(nu as f64);
        }
    }
}

/// SciPy's `evaluate_bpoly1`: [`bernstein_sum`] up to degree 3, above it the sum of
/// `comb·s^a·(1 − s)^{k−a}·c_a` with `pow` for the powers and `comb` updated by
/// `(k − a)/(a + 1)`, in its order.
fn scipy_bernstein_sum(k: usize, s: f64, c: impl Fn(usize) -> f64) -> f64 {
    if k <= 3 {
        return bernstein_sum(k, s, c);
    }
    let s1 = 1.0 - s;
    let (mut res, mut comb) = (0.0, 1.0);
    for j in 0..=k {
        res += comb * s.powf(j as f64) * s1.powf((k - j) as f64) * c(j);
        comb *= (k - j) as f64 / (j as f64 + 1.0);
    }
    res
}

/// Borrowed coefficients of SciPy's `BPoly`: on `x_i ≤ x < x_{i+1}` (`x_i ≥ x > x_{i+1}` on
/// decreasing breakpoints), with `s = (x − x_i)/(x_{i+1} − x_i)`,
/// `f(x) = Σ_{a=0}^{k} c[a, i]·b_{a,k}(s)`, `c[a, i, d]` at `(a·pieces + i)·dim + d`
/// ([`BernsteinBasis`]; order `k + 1`). Repeated breakpoints (empty pieces) are allowed and
/// never evaluated. The constructor and the evaluations are [`PiecewiseRef`]'s.
///
/// ```
/// use lekalo::pp::BernsteinFormRef;
/// use lekalo::Beyond;
/// // s² on [0, 1] (Bernstein coefficients 0, 0, 1), then 1 + 2(x − 1) on [1, 3]
/// let c = [0.0, 1.0, 0.0, 3.0, 1.0, 5.0];
/// let f = BernsteinFormRef::new(&c, 3, &[0.0, 1.0, 3.0], 1)?;
/// let mut out = [0.0; 3];
/// f.par_eval_beyond(&[0.5, 2.0, 4.0], 0, Beyond::Continue, &mut out)?;
/// assert_eq!(out, [0.25, 3.0, 7.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
pub type BernsteinFormRef<'a> = PiecewiseRef<'a, BernsteinBasis>;

/// `Σ_{a=0}^{k} c(a)·b_{a,k}(s)` for `k ≤ 3`, written out as SciPy's `evaluate_bpoly1` writes
/// it (each product left to right, the terms summed left to right), so that the values have
/// its bits.
#[inline(always)]
fn bernstein_sum(k: usize, s: f64, c: impl Fn(usize) -> f64) -> f64 {
    debug_assert!(k <= 3, "the written-out sum stops at degree 3");
    let s1 = 1.0 - s;
    match k {
        0 => c(0),
        1 => c(0) * s1 + c(1) * s,
        2 => c(0) * s1 * s1 + c(1) * 2.0 * s1 * s + c(2) * s * s,
        _ => {
            c(0) * s1 * s1 * s1
                + c(1) * 3.0 * s1 * s1 * s
                + c(2) * 3.0 * s1 * s * s
                + c(3) * s * s * s
        }
    }
}

/// `Σ_a w_a·b_{a,k}(s)` by de Casteljau's algorithm (`k = w.len() − 1`), overwriting `w`.
#[inline(always)]
fn de_casteljau(s: f64, w: &mut [f64]) -> f64 {
    let s1 = 1.0 - s;
    for r in 1..w.len() {
        for a in 0..w.len() - r {
            w[a] = s1 * w[a] + s * w[a + 1];
        }
    }
    w[0]
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::curve::Beyond;
    use crate::error::Error;
    use crate::oracle::proptest_config;

    /// `C(k, a)` as a float.
    fn binomial(k: usize, a: usize) -> f64 {
        (0..a).fold(1.0, |p, i| p * (k - i) as f64 / (i + 1) as f64)
    }

    /// The oracle: `D^nu` of the Bernstein sum on the piece of `x` (the last non-empty one
    /// with `x_j ≤ x`, the end pieces outside), each basis polynomial expanded in powers of
    /// `s` and differentiated term by term; per coordinate the value and the scale of its
    /// rounding, the larger of the sum of the terms' magnitudes and the bound
    /// `k!/(k − nu)!·(2(|s| + |1 − s|))^nu·(|s| + |1 − s|)^{k−nu}·max|c| / h^nu` on what the
    /// Bernstein evaluation adds up.
    fn oracle(
        c: &[f64],
        order: usize,
        b: &[f64],
        dim: usize,
        x: f64,
        nu: usize,
    ) -> Vec<(f64, f64)> {
        let pieces = b.len() - 1;
        let non_empty: Vec<usize> = (0..pieces).filter(|&j| b[j] < b[j + 1]).collect();
        let j = if x < b[0] {
            non_empty[0]
        } else if x >= b[pieces] {
            non_empty[non_empty.len() - 1]
        } else {
            (0..pieces).rev().find(|&j| b[j] <= x).unwrap_or(0)
        };
        let k = order - 1;
        if nu > k {
            return vec![(0.0, 0.0); dim];
        }
        let h = b[j + 1] - b[j];
        let s = (x - b[j]) / h;
        let pow = |v: f64, e: usize| v.powi(i32::try_from(e).unwrap());
        let reach = s.abs() + (1.0 - s).abs();
        // b_{a,k}(s) = Σ_m C(k,a) C(k−a, m) (−1)^m s^{a+m}
        (0..dim)
            .map(|d| {
                let (mut v, mut magnitude, mut largest) = (0.0, 0.0, 0.0f64);
                for a in 0..=k {
                    let ca = c[(a * pieces + j) * dim + d];
                    largest = largest.max(ca.abs());
                    for m in 0..=k - a {
                        let p = a + m;
                        if p < nu {
                            continue;
                        }
                        let falling: f64 = (p - nu + 1..=p).map(|q| q as f64).product();
                        let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
                        let term = ca
                            * binomial(k, a)
                            * binomial(k - a, m)
                            * sign
                            * falling
                            * pow(s, p - nu);
                        v += term;
                        magnitude += term.abs();
                    }
                }
                let falling: f64 = (k - nu + 1..=k).map(|q| q as f64).product();
                let bound = falling * pow(2.0 * reach, nu) * pow(reach, k - nu) * largest;
                (v / pow(h, nu), magnitude.max(bound) / pow(h, nu))
            })
            .collect()
    }

    proptest! {
        #![proptest_config(proptest_config(64))]

        /// Every degree and derivative order agrees with the expanded oracle inside and beyond
        /// the breakpoints, with empty pieces.
        #[test]
        fn values_and_derivatives_agree_with_the_expansion(
            order in 1usize..=7,
            dim in 1usize..=2,
            gaps in prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 0.2f64..2.0], 1..=6),
            seed in prop::collection::vec(-3.0f64..3.0, 100),
            us in prop::collection::vec(-0.2f64..1.2, 1..=20),
            nu in 0usize..=7,
        ) {
            let mut b = vec![-1.0];
            for g in &gaps {
                b.push(b[b.len() - 1] + g);
            }
            prop_assume!(b[b.len() - 1] > b[0]);
            let pieces = b.len() - 1;
            let c: Vec<f64> = (0..order * pieces * dim).map(|i| seed[i % seed.len()]).collect();
            let f = BernsteinFormRef::new(&c, order, &b, dim).unwrap();
            let (lo, hi) = (b[0], b[pieces]);
            let xs: Vec<f64> = us.iter().map(|u| lo + (hi - lo) * u).chain(b.iter().copied()).collect();
            let mut out = vec![0.0; xs.len() * dim];
            f.par_eval_beyond(&xs, nu, Beyond::Continue, &mut out).unwrap();
            for (&x, o) in xs.iter().zip(out.chunks_exact(dim)) {
                let want = oracle(&c, order, &b, dim, x, nu);
                for (g, (w, scale)) in o.iter().zip(&want) {
                    // a few roundings of each of at most 2^7 terms, relative to their scale
                    prop_assert!((g - w).abs() <= 1e-13 * (scale + 1e-300), "x = {}, nu = {}: {} against {}", x, nu, g, w);
                }
            }
        }
    }

    /// A cubic's values have the bits of SciPy's written-out sum; a parallel batch has the
    /// bits of a sequential one; outside without extrapolation, NaN; errors by name.
    #[test]
    fn scipy_bits_batches_and_errors() {
        let b: Vec<f64> = (0..=100).map(|i| f64::from(i) * 0.37).collect();
        let c: Vec<f64> = (0..400).map(|i| f64::from(i % 13) * 0.3 - 2.0).collect();
        let f = BernsteinFormRef::new(&c, 4, &b, 1).unwrap();
        let xs: Vec<f64> = (0..40_000).map(|i| f64::from(i) * 0.001 - 1.0).collect();
        let mut par = vec![0.0; xs.len()];
        f.par_eval_beyond(&xs, 0, Beyond::Continue, &mut par)
            .unwrap();
        for (&x, &v) in xs.iter().zip(&par).step_by(97) {
            let j = if x < b[0] {
                0
            } else {
                (b.partition_point(|&t| t <= x) - 1).min(99)
            };
            let s = (x - b[j]) / (b[j + 1] - b[j]);
            let s1 = 1.0 - s;
            let cc = |a: usize| c[a * 100 + j];
            let scipy = cc(0) * s1 * s1 * s1
                + cc(1) * 3.0 * s1 * s1 * s
                + cc(2) * 3.0 * s1 * s * s
                + cc(3) * s * s * s;
            assert_eq!(v.to_bits(), scipy.to_bits(), "x = {x}");
            let mut one = [0.0];
            f.par_eval_beyond(&[x], 0, Beyond::Continue, &mut one)
                .unwrap();
            assert_eq!(one[0].to_bits(), v.to_bits(), "x = {x}: batch and single");
        }
        // the same function on the breakpoints reversed: the pieces reversed and each one's
        // coefficients reversed (b_{a,k}(1 − s) = b_{k−a,k}(s)), as in SciPy's BPoly tests
        let rb: Vec<f64> = b.iter().rev().copied().collect();
        let rc: Vec<f64> = (0..400)
            .map(|i| c[(3 - i / 100) * 100 + 99 - i % 100])
            .collect();
        let g = BernsteinFormRef::new(&rc, 4, &rb, 1).unwrap();
        for nu in 0..=2 {
            let (mut up, mut down) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
            f.par_eval_beyond(&xs, nu, Beyond::Continue, &mut up)
                .unwrap();
            g.par_eval_beyond(&xs, nu, Beyond::Continue, &mut down)
                .unwrap();
            for ((&x, u), d) in xs.iter().zip(&up).zip(&down) {
                if b.iter().any(|&t| (t - x).abs() < 1e-9) {
                    continue; // the jumps: the right limit going up, the left one going down
                }
                assert!(
                    (u - d).abs() <= 1e-12 * (1.0 + u.abs()),
                    "x = {x}, nu = {nu}: {u} {d}"
                );
            }
        }
        let mut two = [0.0; 2];
        f.par_eval_beyond(&[-0.5, 37.5], 1, Beyond::Nan, &mut two)
            .unwrap();
        assert!(two.iter().all(|v| v.is_nan()), "outside: {two:?}");
        f.par_eval_beyond(&[1.0, 2.0], 4, Beyond::Nan, &mut two)
            .unwrap();
        assert_eq!(two, [0.0, 0.0], "orders above the degree");
        let e = BernsteinFormRef::new(&c[..399], 4, &b, 1).unwrap_err();
        assert!(
            matches!(e, Error::LengthMismatch { expected: 400, .. }),
            "{e}"
        );
        let e = BernsteinFormRef::new(&c[..4], 4, &[1.0, 1.0], 1).unwrap_err();
        assert!(matches!(e, Error::EmptyDomain { .. }), "{e}");
        let e = BernsteinFormRef::new(&c[..4], 0, &[0.0, 1.0], 1).unwrap_err();
        assert!(matches!(e, Error::TooFew { .. }), "{e}");
        let huge = [f64::MAX, f64::MAX];
        let g = BernsteinFormRef::new(&huge, 2, &[0.0, 1.0], 1).unwrap();
        let e = g
            .par_eval_beyond(&[3.0], 0, Beyond::Continue, &mut two[..1])
            .unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    }
}
