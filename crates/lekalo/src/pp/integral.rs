//! Antiderivatives and integrals of a piecewise polynomial in its own pp-form
//! (docs/theory/pp.md#antiderivatives-in-pp-form): each piece integrated term by term, the
//! constants chosen for continuity from the left, as SciPy's `PPoly.antiderivative` and
//! `PPoly.integrate` do.

use crate::error::{check_finite, Error, Result, MAX_SCALARS};
use crate::pp::ppform::PiecewisePolynomial;

impl PiecewisePolynomial {
    /// The `n`-th antiderivative, of order `k + n`, continuous, whose derivatives of orders
    /// `0 … n − 1` vanish at `anchor` (any finite point; outside the breakpoints the end pieces
    /// are continued). Each integration maps `c_r` to `c_{r+1}/(r+1)` in every piece and sets
    /// the constant of piece `j` to the value of piece `j − 1`'s integral at `ξ_j` (zero in the
    /// first piece), then subtracts the value at `anchor`
    /// (docs/theory/pp.md#antiderivatives-in-pp-form).
    ///
    /// ```
    /// use lekalo::PiecewisePolynomial;
    /// // 1 on [0, 1), 2 on [1, 3]: the antiderivative from 3 is x − 5 then 2x − 6
    /// let f = PiecewisePolynomial::new(vec![0.0, 1.0, 3.0], 1, 1, vec![1.0, 2.0])?;
    /// let g = f.antiderivative(1, 3.0)?;
    /// assert_eq!(g.coefficients(), &[-5.0, 1.0, -4.0, 2.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `anchor` or an overflowing coefficient;
    /// [`Error::TooLarge`] if the order `k + n` would exceed the size limit.
    pub fn antiderivative(&self, n: usize, anchor: f64) -> Result<PiecewisePolynomial> {
        check_finite("anchor", &[anchor])?;
        let (dim, l) = (self.dim(), self.n_pieces());
        let order = self
            .order()
            .checked_add(n)
            .filter(|&o| o.checked_mul(l * dim).is_some_and(|s| s <= MAX_SCALARS))
            .ok_or(Error::TooLarge {
                what: "antiderivative coefficients".into(),
                size: usize::MAX,
                max: MAX_SCALARS,
            })?;
        let mut f = self.clone();
        let mut value = vec![0.0; dim];
        for _ in 0..n {
            let k = f.order();
            let xi = f.breakpoints().to_vec();
            let mut c = vec![0.0; l * (k + 1) * dim];
            for j in 0..l {
                for r in 0..k {
                    for d in 0..dim {
                        c[(j * (k + 1) + r + 1) * dim + d] =
                            f.coefficients()[(j * k + r) * dim + d] / (r + 1) as f64;
                    }
                }
            }
            let mut g = PiecewisePolynomial::from_raw(xi.clone(), k + 1, dim, c);
            // constants for continuity: the previous piece's value at the breakpoint
            for j in 1..l {
                g.piece_derivative_into(j - 1, xi[j], 0, &mut value);
                let block = j * (k + 1) * dim;
                let coefficients = g.coefficients_mut();
                coefficients[block..block + dim].copy_from_slice(&value);
            }
            g.eval_extrapolated_into(anchor, 0, &mut value)?;
            let k1 = k + 1;
            let coefficients = g.coefficients_mut();
            for j in 0..l {
                for (d, v) in value.iter().enumerate() {
                    coefficients[j * k1 * dim + d] -= v;
                }
            }
            f = g;
        }
        debug_assert_eq!(f.order(), order, "antiderivative order");
        check_finite("antiderivative coefficients", f.coefficients())?;
        Ok(f)
    }

    /// `∫_a^b f(x) dx` for any finite `a`, `b` (`a > b` gives the negative), the end pieces
    /// continued beyond the breakpoints: the difference of the antiderivative's values
    /// ([`PiecewisePolynomial::antiderivative`] from the first breakpoint), SciPy's
    /// `PPoly.integrate` with `extrapolate=True`.
    ///
    /// ```
    /// use lekalo::PiecewisePolynomial;
    /// let f = PiecewisePolynomial::new(vec![0.0, 1.0, 3.0], 1, 1, vec![1.0, 2.0])?;
    /// assert_eq!(f.integral_extrapolated(-1.0, 4.0)?, vec![2.0 + 2.0 * 3.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite limit or an overflowing value.
    pub fn integral_extrapolated(&self, a: f64, b: f64) -> Result<Vec<f64>> {
        check_finite("integration limits", &[a, b])?;
        let g = self.antiderivative(1, self.breakpoints()[0])?;
        let mut fa = vec![0.0; self.dim()];
        let mut fb = vec![0.0; self.dim()];
        g.eval_extrapolated_into(a, 0, &mut fa)?;
        g.eval_extrapolated_into(b, 0, &mut fb)?;
        let out: Vec<f64> = fb.iter().zip(&fa).map(|(y, x)| y - x).collect();
        check_finite("integral", &out)?;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x³ − x on [−1, 0), 2 + x on [0, 1]: the antiderivative is continuous, its derivative is
    /// the function, it vanishes with its first derivative at the anchor (twice integrated),
    /// and the integral matches the closed form also beyond the breakpoints.
    #[test]
    fn antiderivative_and_integral() {
        let f = PiecewisePolynomial::new(
            vec![-1.0, 0.0, 1.0],
            4,
            1,
            vec![0.0, 2.0, -3.0, 1.0, 2.0, 1.0, 0.0, 0.0],
        )
        .unwrap();
        let g = f.antiderivative(1, -1.0).unwrap();
        assert_eq!(g.order(), 5);
        for x in [-0.75, 0.0, 0.5] {
            let (d, v) = (g.derivative(1).eval(x).unwrap(), f.eval(x).unwrap());
            assert!((d[0] - v[0]).abs() < 1e-14, "G' = f at {x}");
        }
        let mut left = [0.0];
        let mut right = [0.0];
        g.eval_extrapolated_into(0.0, 0, &mut right).unwrap();
        g.piece_derivative_into(0, 0.0, 0, &mut left);
        assert!((left[0] - right[0]).abs() < 1e-15, "continuous at 0");
        // ∫_{-1}^{0} x³ − x = −1/4 + 1/2; ∫_0^{1} 2 + x = 5/2
        let whole = f.integral_extrapolated(-1.0, 1.0).unwrap()[0];
        assert!((whole - (0.25 + 2.5)).abs() < 1e-14, "{whole}");
        // beyond: ∫_1^2 (2 + x) = 3.5; ∫_{-2}^{-1} (x³ − x) = (1/4 − 1/2) − (4 − 2) = −2.25
        let out = f.integral_extrapolated(-2.0, 2.0).unwrap()[0];
        assert!((out - (0.25 + 2.5 + 3.5 - 2.25)).abs() < 1e-13, "{out}");
        let back = f.integral_extrapolated(2.0, -2.0).unwrap()[0];
        assert_eq!(back, -out, "reversed limits");
        let h = f.antiderivative(2, 0.5).unwrap();
        let d = h.eval_derivatives(0.5, 1).unwrap();
        assert!(
            d.point(0)[0].abs() < 1e-15 && d.point(1)[0].abs() < 1e-15,
            "{d:?}"
        );
        let e = f.antiderivative(1, f64::NAN).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{e}");
    }
}
