//! Evaluation of a piecewise polynomial beyond its breakpoints: the end pieces continued
//! (SciPy's `PPoly(..., extrapolate=True)`), by Horner's rule on the pp-form itself
//! (docs/theory/pp.md#piecewise-polynomials).

use crate::error::{check_finite, Error, Result};
use crate::pp::ppform::PiecewisePolynomial;

impl PiecewisePolynomial {
    /// `D^nu f(x)` for any finite `x`, into `out` (length `dim`): inside the breakpoints as
    /// [`PiecewisePolynomial::eval_into`] (right-continuous, the last piece closed), below the
    /// first breakpoint the first piece's polynomial and beyond the last the last piece's,
    /// continued. Horner's rule in the local variable of the piece, so the rounding error grows
    /// only like the polynomial's own condition at `x` (not through a change of basis). Orders
    /// `nu ≥ k` give zeros. No allocation.
    ///
    /// ```
    /// use lekalo::PiecewisePolynomial;
    /// let f = PiecewisePolynomial::new(vec![0.0, 1.0, 2.0], 2, 1, vec![0.0, 1.0, 1.0, -1.0])?; // hat
    /// let mut v = [0.0];
    /// f.eval_extrapolated_into(3.0, 0, &mut v)?;
    /// assert_eq!(v, [-1.0]);
    /// f.eval_extrapolated_into(-1.0, 1, &mut v)?;
    /// assert_eq!(v, [1.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `x` or an overflowing value;
    /// [`Error::LengthMismatch`] for a wrong buffer length.
    pub fn eval_extrapolated_into(&self, x: f64, nu: usize, out: &mut [f64]) -> Result<()> {
        if out.len() != self.dim() {
            return Err(Error::LengthMismatch {
                what: "output point (dimension)".into(),
                expected: self.dim(),
                got: out.len(),
            });
        }
        check_finite("x", &[x])?;
        let xi = self.breakpoints();
        let j = xi
            .partition_point(|&b| b <= x)
            .saturating_sub(1)
            .min(self.n_pieces() - 1);
        self.piece_derivative_into(j, x, nu, out);
        check_finite(
            "piecewise polynomial value (overflow: rescale the coefficients)",
            out,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inside, the same numbers as `eval_derivatives`; outside, the end polynomials.
    #[test]
    fn agrees_inside_and_continues_outside() {
        // x³ − x on [−1, 0), then 2 + x on [0, 1]
        let f = PiecewisePolynomial::new(
            vec![-1.0, 0.0, 1.0],
            4,
            1,
            vec![0.0, 2.0, -3.0, 1.0, 2.0, 1.0, 0.0, 0.0],
        )
        .unwrap();
        let mut v = [0.0];
        for x in [-1.0, -0.5, 0.0, 0.25, 1.0] {
            let d = f.eval_derivatives(x, 3).unwrap();
            for nu in 0..4 {
                f.eval_extrapolated_into(x, nu, &mut v).unwrap();
                assert_eq!(v[0], d.point(nu)[0], "x = {x}, nu = {nu}");
            }
        }
        f.eval_extrapolated_into(-2.0, 0, &mut v).unwrap();
        assert!((v[0] - (-8.0 + 2.0)).abs() < 1e-12, "left: {}", v[0]);
        f.eval_extrapolated_into(5.0, 1, &mut v).unwrap();
        assert_eq!(v, [1.0], "right slope");
        f.eval_extrapolated_into(5.0, 4, &mut v).unwrap();
        assert_eq!(v, [0.0], "order above the degree");
        let e = f.eval_extrapolated_into(f64::NAN, 0, &mut v).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    }
}
