//! A piecewise polynomial in the local power basis read in place from SciPy's `PPoly` arrays
//! ([`PowerFormRef`]): coefficients `c` of shape `(k, pieces, dim)`, the highest power first,
//! on monotonic breakpoints (either order, as SciPy allows), evaluated by Horner's rule in each
//! piece with the end pieces continued (or NaN), without a copy into a [`PiecewisePolynomial`] (the same operations, so
//! the same bits). The piece of a point is found as the B-spline evaluator finds it (a bucket
//! table for large batches, `piece_search.rs`), and the common orders have kernels with the
//! order fixed at compile time. `docs/theory/pp.md#piecewise-polynomials`.

use crate::curve::Beyond;
#[cfg(doc)]
use crate::error::Error;
use crate::error::{check_finite, Result};
use crate::pp::piece_search::{check_arrays, PieceSearch};
#[cfg(doc)]
use crate::pp::ppform::PiecewisePolynomial;

/// Borrowed coefficients of SciPy's `PPoly`: `f(x) = Σ_m c[m, i]·(x − x_i)^{k−1−m}` on
/// `x_i ≤ x < x_{i+1}` (`x_i ≥ x > x_{i+1}` on decreasing breakpoints), `c[m, i, d]` at
/// `(m·pieces + i)·dim + d`. Repeated breakpoints (empty pieces) are allowed and never
/// evaluated.
#[derive(Debug, Clone, Copy)]
pub struct PowerFormRef<'a> {
    c: &'a [f64],
    order: usize,
    breakpoints: &'a [f64],
    dim: usize,
}

impl<'a> PowerFormRef<'a> {
    /// The piecewise polynomial of order `order` (`k` coefficients a piece) on `breakpoints`
    /// (`pieces + 1` of them, monotonic, the ends different) with the coefficients
    /// `c` (`k·pieces·dim` numbers, SciPy's layout). The order of the breakpoints is the
    /// caller's to guarantee (SciPy's constructor checks it): only their ends are checked here,
    /// so that a call costs no pass over the arrays.
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
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than two breakpoints or an order of 0;
    /// [`Error::LengthMismatch`] if `c` does not hold `k·pieces·dim` numbers;
    /// [`Error::NonFinite`] for an end breakpoint that is not finite; [`Error::EmptyDomain`]
    /// if the first and the last breakpoint are equal.
    pub fn new(c: &'a [f64], order: usize, breakpoints: &'a [f64], dim: usize) -> Result<Self> {
        check_arrays(c, order, breakpoints, dim)?;
        Ok(PowerFormRef {
            c,
            order,
            breakpoints,
            dim,
        })
    }

    /// `D^nu f` at every `x` of `xs` into `out` (`dim` numbers a point), the end pieces
    /// continued; every `x` must be finite. As [`PowerFormRef::par_eval_beyond`] with
    /// [`Beyond::Continue`], which see.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out` does not hold `dim` numbers a point;
    /// [`Error::NonFinite`] for a NaN or infinite `x`, or a value that overflows.
    pub fn par_eval_extrapolated(&self, xs: &[f64], nu: usize, out: &mut [f64]) -> Result<()> {
        check_finite("x", xs)?;
        self.par_eval_beyond(xs, nu, Beyond::Continue, out)
    }

    /// `D^nu f` at every `x` of `xs` into `out` (`dim` numbers a point):
    /// `D^r Σ_s c_s u^s = Σ_{s≥r} c_s·s!/(s−r)!·u^{s−r}` by Horner's rule in `u = x − x_j` on the
    /// piece `j` with `x_j ≤ x < x_{j+1}`, as [`PiecewisePolynomial::eval_extrapolated_into`]
    /// (the same operations in the same order, so the same bits), on the piece `j` with
    /// `x_j ≤ x < x_{j+1}` (`x_j ≥ x > x_{j+1}` when decreasing, as SciPy). Outside the
    /// breakpoints the end pieces are continued or NaN is written, as `beyond` says (SciPy's `extrapolate`); NaN at
    /// a NaN or infinite `x`. Orders `nu ≥ k` give zeros. The piece by the bucket table of the
    /// B-spline evaluator when there are at least as many points as pieces (O(1) a point for
    /// spread-out breakpoints), else by binary search; on the rayon pool from 16384 points.
    /// O(points·k·dim), plus O(pieces) for the table.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out` does not hold `dim` numbers a point;
    /// [`Error::NonFinite`] for a value that overflows.
    pub fn par_eval_beyond(
        &self,
        xs: &[f64],
        nu: usize,
        beyond: Beyond,
        out: &mut [f64],
    ) -> Result<()> {
        let search = PieceSearch::new(self.breakpoints, xs.len());
        let (k, dim) = (self.order, self.dim);
        let b = self.breakpoints;
        macro_rules! fixed {
            ($k:literal) => {
                search.for_each_point(
                    xs,
                    dim,
                    beyond,
                    out,
                    || (),
                    |(), j, x, o| {
                        self.values_fixed::<$k>(j, x - b[j], o);
                    },
                )
            };
        }
        match (nu, k) {
            (0, 2) => fixed!(2),
            (0, 3) => fixed!(3),
            (0, 4) => fixed!(4),
            (0, 5) => fixed!(5),
            (0, 6) => fixed!(6),
            _ => search.for_each_point(
                xs,
                dim,
                beyond,
                out,
                || (),
                |(), j, x, o| {
                    self.derivative_at(j, x - b[j], nu, o);
                },
            ),
        }
    }

    /// Values on piece `j` at `u = x − x_j` with the order `K` known at compile time: the
    /// operations of [`PowerFormRef::derivative_at`] with `nu = 0` (its factor `1` is exact).
    #[inline(always)]
    fn values_fixed<const K: usize>(&self, j: usize, u: f64, o: &mut [f64]) {
        let (dim, pieces) = (self.dim, self.breakpoints.len() - 1);
        for (d, v) in o.iter_mut().enumerate() {
            let mut acc = 0.0;
            for m in 0..K {
                // row m holds the power K − 1 − m: the highest first, as Horner reads them
                acc = acc * u + self.c[(m * pieces + j) * dim + d];
            }
            *v = acc;
        }
    }

    /// `D^r` on piece `j` at `u = x − x_j`, any order.
    #[inline(always)]
    fn derivative_at(&self, j: usize, u: f64, r: usize, o: &mut [f64]) {
        let (k, dim) = (self.order, self.dim);
        let pieces = self.breakpoints.len() - 1;
        o.fill(0.0);
        if r >= k {
            return;
        }
        for s in (r..k).rev() {
            let falling: f64 = (s - r + 1..=s).map(|v| v as f64).product();
            // power s is row k − 1 − s of SciPy's array
            let at = ((k - 1 - s) * pieces + j) * dim;
            for (v, &cs) in o.iter_mut().zip(&self.c[at..at + dim]) {
                *v = *v * u + falling * cs;
            }
        }
    }
}

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
