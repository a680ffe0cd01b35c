//! Piecewise polynomials given on decreasing breakpoints (SciPy's `PPoly` with `x` decreasing):
//! the same function in lekalo's pp-form on increasing breakpoints, and back, by a Taylor shift
//! of each piece to its other end (docs/theory/pp.md#decreasing-breakpoints).

use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::pp::ppform::PiecewisePolynomial;
use crate::Arg;

/// Re-expands `order` coefficients (lowest power first) of `p(u)` as those of `p(s + δ)`, in
/// place, for each of `dim` interleaved columns: the repeated synthetic division of Horner's
/// Taylor shift, `O(order²)` (Knuth, TAOCP vol. 2, §4.6.4), carried in double-double
/// arithmetic (error-free `TwoSum` and `TwoProduct` by fused multiply-add; Ogita, Rump and
/// Oishi 2005) so that each result is the correctly rounded coefficient up to a few units in
/// the last place: an extrapolated piece amplifies coefficient errors, and the shifted form must
/// evaluate as accurately as the given one.
fn taylor_shift(c: &mut [f64], order: usize, dim: usize, delta: f64) {
    let mut lo = vec![0.0; c.len()];
    for i in 0..order.saturating_sub(1) {
        for j in (i..order - 1).rev() {
            for d in 0..dim {
                let (a, b) = (j * dim + d, (j + 1) * dim + d);
                // (c_a, lo_a) += δ · (c_b, lo_b)
                let p = delta * c[b];
                let p_err = delta.mul_add(c[b], -p) + delta * lo[b];
                let s = c[a] + p;
                let bb = s - c[a];
                let s_err = (c[a] - (s - bb)) + (p - bb) + lo[a] + p_err;
                let hi = s + s_err;
                lo[a] = s_err - (hi - s);
                c[a] = hi;
            }
        }
    }
}

impl PiecewisePolynomial {
    /// The piecewise polynomial given on strictly decreasing breakpoints `x_0 > … > x_l` with
    /// piece `i` on `[x_{i+1}, x_i]` written about `x_i`, its right end:
    /// `f(x) = Σ_r c_{i,r} (x − x_i)^r` (coefficients lowest power first, layout
    /// `c[(i·order + r)·dim + d]`, as [`PiecewisePolynomial::new`]). The result is the same
    /// function on the increasing breakpoints, each piece shifted to its left end by Horner's
    /// Taylor shift (docs/theory/pp.md#decreasing-breakpoints); SciPy's `PPoly` with
    /// decreasing `x`.
    ///
    /// ```
    /// use lekalo::PiecewisePolynomial;
    /// // x² on [0, 1] and 1 + 2 (x − 1) on [1, 3], given from the right
    /// let f = PiecewisePolynomial::from_decreasing(&[3.0, 1.0, 0.0], 3, 1, &[5.0, 2.0, 0.0, 1.0, 2.0, 1.0])?;
    /// assert_eq!(f.breakpoints(), &[0.0, 1.0, 3.0]);
    /// assert_eq!(f.eval(0.5)?, vec![0.25]);
    /// assert_eq!(f.eval(2.0)?, vec![3.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] unless the breakpoints strictly decrease; otherwise as
    /// [`PiecewisePolynomial::new`].
    pub fn from_decreasing(
        breakpoints: &[f64],
        order: usize,
        dim: usize,
        coefficients: &[f64],
    ) -> Result<Self> {
        check_finite(Arg::Breakpoints, breakpoints)?;
        if let Some(i) = breakpoints.windows(2).position(|w| w[0] <= w[1]) {
            return Err(Error::InvalidArgument {
                what: Arg::Breakpoints.into(),
                reason: format!(
                    "must be strictly decreasing, but breakpoint {i} = {} is not greater than breakpoint {} = {}",
                    readable(&breakpoints[i]),
                    i + 1,
                    readable(&breakpoints[i + 1])
                ),
            });
        }
        let increasing: Vec<f64> = breakpoints.iter().rev().copied().collect();
        // validates counts, order, dim and finiteness (on the pieces in their given order)
        let given = PiecewisePolynomial::new(increasing, order, dim, coefficients.to_vec())?;
        let block = order * dim;
        let pieces = breakpoints.len() - 1;
        let mut out = Vec::with_capacity(coefficients.len());
        for j in 0..pieces {
            // increasing piece j is given piece i = pieces − 1 − j, about x_i = ξ_{j+1}
            let i = pieces - 1 - j;
            let mut c = coefficients[i * block..(i + 1) * block].to_vec();
            taylor_shift(&mut c, order, dim, breakpoints[i + 1] - breakpoints[i]);
            out.extend(c);
        }
        check_finite("coefficients shifted to the left ends", &out)?;
        Ok(PiecewisePolynomial::from_raw(
            given.breakpoints().to_vec(),
            order,
            dim,
            out,
        ))
    }

    /// The inverse of [`PiecewisePolynomial::from_decreasing`]: the breakpoints in decreasing
    /// order and, piece by piece in that order, the coefficients about each piece's right end
    /// (its left limits there, `c_{i,r} = f^{(r)}(x_i^−)/r!`), by Horner's Taylor shift.
    ///
    /// ```
    /// use lekalo::PiecewisePolynomial;
    /// let f = PiecewisePolynomial::new(vec![0.0, 1.0], 3, 1, vec![0.0, 0.0, 1.0])?; // x²
    /// let (x, c) = f.to_decreasing();
    /// assert_eq!((x, c), (vec![1.0, 0.0], vec![1.0, 2.0, 1.0])); // 1 + 2(x − 1) + (x − 1)²
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn to_decreasing(&self) -> (Vec<f64>, Vec<f64>) {
        let (order, dim) = (self.order(), self.dim());
        let xi = self.breakpoints();
        let block = order * dim;
        let pieces = self.n_pieces();
        let mut out = Vec::with_capacity(self.coefficients().len());
        for i in 0..pieces {
            let j = pieces - 1 - i;
            let mut c = self.coefficients()[j * block..(j + 1) * block].to_vec();
            taylor_shift(&mut c, order, dim, xi[j + 1] - xi[j]);
            out.extend(c);
        }
        (xi.iter().rev().copied().collect(), out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random-looking cubic in 2-D given from the right agrees with its increasing form
    /// everywhere, and the round trip returns the coefficients.
    #[test]
    fn round_trip_and_values() {
        let x = [4.0, 2.5, 1.0, -0.5];
        let order = 4;
        let c: Vec<f64> = (0..3 * order * 2)
            .map(|i| ((i * 37 % 11) as f64 - 5.0) / 3.0)
            .collect();
        let f = PiecewisePolynomial::from_decreasing(&x, order, 2, &c).unwrap();
        for (i, w) in x.windows(2).enumerate() {
            for t in [0.1, 0.5, 0.9] {
                let at = w[1] + t * (w[0] - w[1]);
                let u = at - w[0];
                let got = f.eval(at).unwrap();
                for d in 0..2 {
                    let want: f64 = (0..order)
                        .map(|r| c[(i * order + r) * 2 + d] * u.powi(i32::try_from(r).unwrap()))
                        .sum();
                    assert!((got[d] - want).abs() < 1e-12, "piece {i} at {at}: {got:?}");
                }
            }
        }
        let (xb, cb) = f.to_decreasing();
        assert_eq!(xb, x.to_vec());
        for (a, b) in c.iter().zip(&cb) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }

    /// Order-12 coefficients shifted by 0.7 against the exact shift of the same binary numbers
    /// in rational arithmetic: each coefficient within two units in its last place (plain
    /// double-precision Horner is off by up to about a hundred here).
    #[test]
    fn shift_is_accurate_to_the_last_places() {
        use num_rational::BigRational;
        use num_traits::ToPrimitive;
        let n = 12;
        let c: Vec<f64> = (0..n).map(|i| ((i * 37 % 11) as f64 - 5.0) / 3.0).collect();
        let mut got = c.clone();
        taylor_shift(&mut got, n, 1, 0.7);
        let rat = |v: f64| BigRational::from_float(v).unwrap();
        let mut exact: Vec<BigRational> = c.iter().map(|&v| rat(v)).collect();
        let delta = rat(0.7);
        for i in 0..n - 1 {
            for j in (i..n - 1).rev() {
                let add = &delta * &exact[j + 1];
                exact[j] += add;
            }
        }
        for (g, w) in got.iter().zip(&exact) {
            let w = w.to_f64().unwrap();
            assert!((g - w).abs() <= 2.0 * f64::EPSILON * w.abs(), "{g} vs {w}");
        }
    }

    #[test]
    fn refuses_increasing_breakpoints() {
        let e = PiecewisePolynomial::from_decreasing(&[0.0, 1.0], 1, 1, &[1.0]).unwrap_err();
        assert!(
            matches!(
                e,
                Error::InvalidArgument { what, .. } if what.arg() == Some(Arg::Breakpoints)
            ),
            "{e}"
        );
    }
}
