//! The local power basis of SciPy's `PPoly` ([`PowerBasis`]) and its arrays read in place
//! ([`PowerFormRef`]): coefficients `c` of shape `(k, pieces, dim)`, the highest power first,
//! evaluated by Horner's rule in each piece without a copy into a [`PiecewisePolynomial`] (the
//! same operations, so the same bits). The arrays, the piece search and the batch drivers are
//! the generic view's (`piecewise_ref.rs`). `docs/theory/pp.md#piecewise-polynomials`.

use crate::pp::piecewise_ref::{Piece, PieceBasis, PiecewiseRef};
#[cfg(doc)]
use crate::pp::ppform::PiecewisePolynomial;

/// The local power basis of SciPy's `PPoly`: on piece `j`, `t = u = x − x_j` and
/// `f(x) = Σ_m c[m, j]·u^{k−1−m}` (row `m` holds the power `k − 1 − m`, the highest first).
/// `D^r Σ_s c_s u^s = Σ_{s≥r} c_s·s!/(s−r)!·u^{s−r}` by Horner's rule (Knuth, TAOCP vol. 2,
/// §4.6.4), the operations and their order of [`PiecewisePolynomial::eval_extrapolated_into`],
/// so the same bits. O(k·dim) a point, no scratch.
#[derive(Debug, Clone, Copy)]
pub struct PowerBasis;

impl super::piecewise_ref::sealed::Sealed for PowerBasis {}

impl PieceBasis for PowerBasis {
    #[inline(always)]
    fn local(piece: &Piece<'_>, x: f64) -> f64 {
        x - piece.start()
    }

    /// Horner's rule with the order `K` known at compile time: the operations of
    /// [`PieceBasis::derivative`] with `nu = 0` (its factor `1` is exact).
    #[inline(always)]
    fn value<const K: usize>(c: &[f64; K], u: f64) -> f64 {
        let mut acc = 0.0;
        // row m holds the power K − 1 − m: the highest first, as Horner reads them
        for &cm in c {
            acc = acc * u + cm;
        }
        acc
    }

    #[inline(always)]
    fn derivative(piece: &Piece<'_>, u: f64, r: usize, _: &mut [f64], o: &mut [f64]) {
        let k = piece.order();
        o.fill(0.0);
        for s in (r..k).rev() {
            let falling: f64 = (s - r + 1..=s).map(|v| v as f64).product();
            // power s is row k − 1 − s of SciPy's array
            for (d, v) in o.iter_mut().enumerate() {
                *v = *v * u + falling * piece.coefficient(k - 1 - s, d);
            }
        }
    }

    fn scratch_len(_: usize) -> usize {
        0
    }

    /// SciPy's `evaluate_poly1`: `Σ_{p ≥ nu} c_{k−1−p}·u^{p−nu}·p!/(p−nu)!` summed from the
    /// constant term up, the powers of `u = x − x_j` by repeated multiplication, each term
    /// `(c·u^m)·p!/(p − nu)!`.
    fn scipy_derivative(piece: &Piece<'_>, x: f64, nu: usize, _: &mut [f64], o: &mut [f64]) {
        let k = piece.order();
        let u = x - piece.start();
        for (d, v) in o.iter_mut().enumerate() {
            let (mut res, mut z) = (0.0, 1.0);
            for p in nu..k {
                let prefactor = (p + 1 - nu..=p).rev().fold(1.0, |f, m| f * m as f64);
                res += piece.coefficient(k - 1 - p, d) * z * prefactor;
                if p + 1 < k {
                    z *= u;
                }
            }
            *v = res;
        }
    }
}

/// Borrowed coefficients of SciPy's `PPoly`: `f(x) = Σ_m c[m, i]·(x − x_i)^{k−1−m}` on
/// `x_i ≤ x < x_{i+1}` (`x_i ≥ x > x_{i+1}` on decreasing breakpoints), `c[m, i, d]` at
/// `(m·pieces + i)·dim + d`, evaluated by Horner's rule ([`PowerBasis`]). Repeated
/// breakpoints (empty pieces) are allowed and never evaluated. The constructor and the
/// evaluations are [`PiecewiseRef`]'s.
///
/// ```
/// use lekalo::pp::PowerFormRef;
/// // x² on [0, 1), then 1 + 2(x − 1) on [1, 2]: c[0] the highest power
/// let c = [1.0, 0.0, 0.0, 2.0, 0.0, 1.0];
/// let f = PowerFormRef::new(&c, 3, &[0.0, 1.0, 2.0], 1)?;
/// let mut out = [0.0; 3];
/// f.par_eval_extrapolated(&[0.5, 1.5, 3.0], 0, &mut out)?;
/// assert_eq!(out, [0.25, 2.0, 5.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
pub type PowerFormRef<'a> = PiecewiseRef<'a, PowerBasis>;

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::error::Error;
    use crate::oracle::proptest_config;
    use crate::pp::ppform::PiecewisePolynomial;

    proptest! {
        #![proptest_config(proptest_config(64))]

        /// The borrowed power form has the bits of the pp-form without its empty pieces
        /// (`eval_extrapolated_into`), inside and beyond the breakpoints, derivatives included.
        #[test]
        fn borrowed_power_form_has_the_pp_form_bits(
            order in 1usize..=5,
            dim in 1usize..=2,
            gaps in prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 0.1f64..2.0], 1..=8),
            seed in prop::collection::vec(-5.0f64..5.0, 200),
            xs in prop::collection::vec(-0.3f64..1.3, 1..=40),
            nu in 0usize..=5,
        ) {
            let mut b = vec![-1.0];
            for g in &gaps {
                b.push(b[b.len() - 1] + g);
            }
            prop_assume!(b[b.len() - 1] > b[0]);
            let pieces = b.len() - 1;
            let c: Vec<f64> = (0..order * pieces * dim).map(|i| seed[i % seed.len()]).collect();
            let f = PowerFormRef::new(&c, order, &b, dim).unwrap();
            // the pp-form of the non-empty pieces, lowest power first
            let mut kept_b = vec![b[0]];
            let mut local = Vec::new();
            for j in 0..pieces {
                if b[j + 1] > b[j] {
                    kept_b.push(b[j + 1]);
                    for s in 0..order {
                        let at = ((order - 1 - s) * pieces + j) * dim;
                        local.extend_from_slice(&c[at..at + dim]);
                    }
                }
            }
            let pp = PiecewisePolynomial::new(kept_b, order, dim, local).unwrap();
            let (lo, hi) = (b[0], b[pieces]);
            let xs: Vec<f64> = xs.iter().map(|u| lo + (hi - lo) * u).chain(b.iter().copied()).collect();
            let mut out = vec![0.0; xs.len() * dim];
            f.par_eval_extrapolated(&xs, nu, &mut out).unwrap();
            let mut want = vec![0.0; dim];
            for (&x, o) in xs.iter().zip(out.chunks_exact(dim)) {
                pp.eval_extrapolated_into(x, nu, &mut want).unwrap();
                let bits = |v: &[f64]| v.iter().map(|t| t.to_bits()).collect::<Vec<_>>();
                prop_assert_eq!(bits(o), bits(&want), "x = {}", x);
            }
        }
    }

    /// A large batch on the thread pool has the bits of the sequential one; bad arguments are
    /// refused by name.
    #[test]
    fn parallel_batches_and_errors() {
        let b: Vec<f64> = (0..=100).map(f64::from).collect();
        let c: Vec<f64> = (0..400).map(|i| f64::from(i % 17) - 8.0).collect();
        let f = PowerFormRef::new(&c, 4, &b, 1).unwrap();
        let xs: Vec<f64> = (0..10_000).map(|i| f64::from(i) * 0.0107 - 3.0).collect();
        let mut par = vec![0.0; xs.len()];
        f.par_eval_extrapolated(&xs, 1, &mut par).unwrap();
        for (&x, &v) in xs.iter().zip(&par) {
            let mut one = [0.0];
            f.par_eval_extrapolated(&[x], 1, &mut one).unwrap();
            assert_eq!(one[0].to_bits(), v.to_bits(), "x = {x}");
        }
        let mut one = [0.0];
        let e = f
            .par_eval_extrapolated(&[f64::NAN], 0, &mut one)
            .unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e}");
        let e = PowerFormRef::new(&c[..399], 4, &b, 1).unwrap_err();
        assert!(
            matches!(e, Error::LengthMismatch { expected: 400, .. }),
            "{e}"
        );
        let e = PowerFormRef::new(&c[..4], 4, &[1.0, 1.0], 1).unwrap_err();
        assert!(matches!(e, Error::EmptyDomain { .. }), "{e}");
        let huge = [f64::MAX, f64::MAX];
        let g = PowerFormRef::new(&huge, 2, &[0.0, 1.0], 1).unwrap();
        let e = g.par_eval_extrapolated(&[1.0], 0, &mut one).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    }
}
