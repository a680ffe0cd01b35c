//! Jump-smoothing polynomials `w_k` (document 001 §1;
//! docs/theory/blending.md#jump-smoothing-polynomials); the mathematics is documented on
//! [`JumpPolynomial`].

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::blend::bernstein as bernstein_ops;
use crate::error::{Error, Result};

/// The jump-smoothing polynomial `w_k(u) = Σ_{i=k+1}^{2k+1} b_{2k+1,i}(u)` of document 001 §1
/// (docs/theory/blending.md#jump-smoothing-polynomials).
///
/// # Definition
/// The unit step `σ(u)` on `[0, 1]` (0 before `1/2`, 1 after) is approximated by the Bezier
/// function whose `2k + 2` ordinates are `k + 1` zeros followed by `k + 1` ones:
///
/// ```text
/// w_k(u) = Σ_{i=k+1}^{2k+1} b_{2k+1,i}(u),    b_{n,i}(u) = C(n,i) (1−u)^{n−i} u^i,   u ∈ [0, 1].
/// ```
///
/// `w_k` has degree `2k + 1`; `w_0(u) = u`, `w_1(u) = 3u² − 2u³`, `w_2(u) = 10u³ − 15u⁴ + 6u⁵`.
///
/// # Properties (all tested in this module, exactly for k ≤ 10, in floating point beyond)
/// - **Boundary conditions:** `w_k(0) = 0`, `w_k(1) = 1`, `w_k^{(l)}(0) = w_k^{(l)}(1) = 0` for
///   `l = 1 … k`. The `(k+1)`-th derivative does *not* vanish:
///   `w_k^{(k+1)}(0) = (2k+1) C(2k,k) k! = (2k+1)!/k!` and `w_k^{(k+1)}(1) = (−1)^k` times that.
///   This is why the conditions stop at `l = k`.
/// - **Derivative:** `w_k'(u) = (2k+1) C(2k,k) u^k (1−u)^k`, hence the closed monomial form
///   `w_k(u) = (2k+1) C(2k,k) Σ_{j=0}^{k} (−1)^j C(k,j) u^{k+j+1} / (k+j+1)` (the regularised
///   incomplete beta function `I_u(k+1, k+1)`). Its coefficients are integers.
/// - **Property 1 / 2 (point symmetry):** `w_k(u) + w_k(1 − u) = 1`.
/// - **Property 3:** `∫_0^{1/2} w_k = C(2k+1, k) / 2^{2k+3} ~ 1/(4√(πk)) → 0`, so `w_k → σ`.
/// - **Property 4 (energy minimality):** among all `f` with the boundary conditions above, `w_k`
///   is the unique minimiser of `J_{k+1}(f) = ∫_0^1 (f^{(k+1)})²`. Integrating by parts `k + 1`
///   times (document 001's proof) gives `J_{k+1}(w_k) = (−1)^k w_k^{(2k+1)} = (2k+1)! C(2k,k)`:
///   1, 12, 720, 100800, … and `J(w_k + h) = J(w_k) + J(h)` for every admissible perturbation `h`.
///
/// # Why `w_{k−1}` gives continuity degree `k`
/// Blending two curves that share their end points, `p = (1 − w) p_1 + w p_2`, has
/// `p^{(l)}(0) − p_1^{(l)}(0) = Σ_{i=1}^{l} C(l,i) w^{(i)}(0) (p_2 − p_1)^{(l−i)}(0)`. With
/// `w = w_{k−1}` the terms `i < k` vanish by the boundary conditions and the term `i = l = k`
/// multiplies `p_2(0) − p_1(0) = 0`. So the cheaper `w_{k−1}` (degree `2k − 1`) already gives
/// contact of order `k`; see [`Deformation`](crate::Deformation).
///
/// ```
/// use lekalo::JumpPolynomial;
/// let w = JumpPolynomial::new(1)?; // 3u² − 2u³
/// assert_eq!(w.degree(), 3);
/// assert!((w.eval(0.25)? - (3.0 / 16.0 - 2.0 / 64.0)).abs() < 1e-15);
/// // exact coefficients and the exact energy J_2(w_1) = 12
/// assert_eq!(w.monomial_coefficients(), [0, 0, 3, -2].map(num_bigint::BigInt::from).to_vec());
/// assert_eq!(w.energy(), num_bigint::BigInt::from(12));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JumpPolynomial {
    k: usize,
}

impl JumpPolynomial {
    /// Largest `k` accepted (evaluation costs O(k²)). Values stay in `[0, 1]` for every `k`, but
    /// high derivatives overflow `f64` long before: `w_k^{(k+1)}(0) = (2k+1)!/k!` exceeds
    /// `f64::MAX` for `k` above about 130; such derivatives come back as infinities, never as
    /// panics.
    pub const MAX_K: usize = 1024;

    /// `w_k`.
    ///
    /// # Errors
    /// [`Error::Degree`] if `k > JumpPolynomial::MAX_K`.
    pub fn new(k: usize) -> Result<Self> {
        if k > Self::MAX_K {
            return Err(Error::Degree {
                degree: k,
                reason: format!(
                    "jump-smoothing polynomial index k must be at most {} (degree 2k + 1)",
                    Self::MAX_K
                ),
            });
        }
        Ok(JumpPolynomial { k })
    }

    /// The index `k`.
    #[must_use]
    pub fn k(&self) -> usize {
        self.k
    }

    /// Degree `2k + 1`.
    #[must_use]
    pub fn degree(&self) -> usize {
        2 * self.k + 1
    }

    /// Bernstein (Bezier) ordinates of degree `2k + 1`: `k + 1` zeros, then `k + 1` ones
    /// (document 001, definition of `w_k`).
    #[must_use]
    pub fn bernstein_coefficients(&self) -> Vec<BigInt> {
        (0..=self.degree())
            .map(|i| BigInt::from(u8::from(i > self.k)))
            .collect()
    }

    /// The same ordinates as `f64` (exact).
    #[must_use]
    pub fn bernstein_coefficients_f64(&self) -> Vec<f64> {
        (0..=self.degree())
            .map(|i| if i > self.k { 1.0 } else { 0.0 })
            .collect()
    }

    /// Exact monomial coefficients `a_0 … a_{2k+1}` of `w_k(u) = Σ a_j u^j` (integers; the first
    /// `k + 1` are zero), expanded from the Bernstein definition:
    /// `a_m = Σ_{i=k+1}^{m} C(n,i) C(n−i, m−i) (−1)^{m−i}`, `n = 2k + 1`.
    /// Equal to the closed form `(2k+1) C(2k,k) (−1)^j C(k,j) / (k+j+1)` for `m = k + 1 + j`
    /// (tested). O(k²) big-integer operations.
    #[must_use]
    pub fn monomial_coefficients(&self) -> Vec<BigInt> {
        let n = self.degree();
        (0..=n)
            .map(|m| {
                let mut a = BigInt::zero();
                for i in (self.k + 1)..=m {
                    let term = big_binomial(n, i) * big_binomial(n - i, m - i);
                    if (m - i) % 2 == 0 {
                        a += term;
                    } else {
                        a -= term;
                    }
                }
                a
            })
            .collect()
    }

    /// `w_k(u)`. Up to `k = 65` (`2k + 1 ≤ 131`, the binomial table: exact integers up to
    /// `k = 27`, correctly rounded above) by the binomial tail in Horner form: for `u ≤ 1/2`, with `s = 1 − u` and `ρ = u/s ≤ 1`,
    /// `w_k(u) = u^{k+1} s^k Σ_{j=0}^{k} C(2k+1, k+1+j) ρ^j`, a sum of positive terms (relative
    /// error a few `k` ulps, no cancellation), and `w_k(u) = 1 − w_k(1 − u)` above `1/2`
    /// (Property 2; `1 − u` is exact there). O(k), no allocation. Above `k = 65` by de
    /// Casteljau's algorithm on the 0/1 ordinates (P&T Algorithm A1.5): every step is a convex
    /// combination, so the result lies in `[0, 1]` and is accurate to a few ulps. O(k²).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ u ≤ 1`.
    pub fn eval(&self, u: f64) -> Result<f64> {
        crate::curve::bezier::check_unit(u)?;
        Ok(self.value(u))
    }

    /// [`JumpPolynomial::eval`] for a `u` already checked to lie in `[0, 1]`.
    fn value(&self, u: f64) -> f64 {
        binomial_tail(self.k, u).unwrap_or_else(|| {
            let ctrl = self.bernstein_coefficients_f64();
            let mut out = [0.0];
            bernstein_ops::derivatives_at(&ctrl, 1, u, 0, &mut out, &mut Vec::new());
            out[0]
        })
    }

    /// `w_k^{(l)}(u)` for `l = 0 … out.len() − 1` into `out`, by de Casteljau's algorithm plus
    /// forward differences of the Bernstein ordinates (Farin, *Curves and Surfaces for CAGD*,
    /// §5.4): `w^{(l)}(u) = n!/(n−l)! Δ^l r^{(n−l)}`. Orders above `2k + 1` are zero.
    /// O(k² + l³). Accuracy: the value to a few ulps; the `l`-th difference costs about `l` bits,
    /// so order `l` is accurate to roughly `2^l ε` relative to its size (1e-9 for `l = 21`,
    /// measured in the tests).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ u ≤ 1`; [`Error::TooFew`] if `out` is empty.
    pub fn eval_derivatives(&self, u: f64, out: &mut [f64]) -> Result<()> {
        crate::curve::bezier::check_unit(u)?;
        if out.is_empty() {
            return Err(Error::TooFew {
                what: "output buffer for w_k derivatives".into(),
                min: 1,
                got: 0,
            });
        }
        if out.len() > 1 {
            let ctrl = self.bernstein_coefficients_f64();
            let mut scratch = Vec::with_capacity(ctrl.len());
            bernstein_ops::derivatives_at(&ctrl, 1, u, out.len() - 1, out, &mut scratch);
        }
        // the value as JumpPolynomial::eval computes it, whatever the number of derivatives
        out[0] = self.value(u);
        Ok(())
    }

    /// Exact `∫_0^{1/2} w_k(u) du` (Property 3), from the exact monomial coefficients.
    /// Equals `C(2k+1, k) / 2^{2k+3}` (tested).
    #[must_use]
    pub fn integral_to_half(&self) -> BigRational {
        let coeffs: Vec<BigRational> = self
            .monomial_coefficients()
            .into_iter()
            .map(BigRational::from_integer)
            .collect();
        let half = BigRational::new(BigInt::one(), BigInt::from(2));
        poly_integral(&coeffs, &half)
    }

    /// `∫_0^{1/2} w_k` in floating point, for any `k`: subdivide the Bezier function at `1/2` by
    /// de Casteljau and use `∫_0^1 Σ c_i b_{n,i} = Σ c_i / (n + 1)`. Stable (sums of positive
    /// numbers). O(k²).
    #[must_use]
    pub fn integral_to_half_f64(&self) -> f64 {
        let mut c = self.bernstein_coefficients_f64();
        let n = c.len() - 1;
        // left half of the subdivision at 1/2: the first point of each de Casteljau level
        let mut left = Vec::with_capacity(n + 1);
        left.push(c[0]);
        for level in 1..=n {
            for i in 0..=(n - level) {
                c[i] = 0.5 * (c[i] + c[i + 1]);
            }
            left.push(c[0]);
        }
        0.5 * left.iter().sum::<f64>() / (n + 1) as f64
    }

    /// Exact energy `J_{k+1}(w_k) = ∫_0^1 (w_k^{(k+1)}(u))² du` (Property 4), computed by exact
    /// polynomial arithmetic from the monomial coefficients. Equals `(2k+1)! C(2k,k)` (tested).
    #[must_use]
    pub fn energy(&self) -> BigInt {
        let coeffs: Vec<BigRational> = self
            .monomial_coefficients()
            .into_iter()
            .map(BigRational::from_integer)
            .collect();
        let j = energy_exact(&coeffs, self.k + 1);
        debug_assert!(j.is_integer(), "J_(k+1)(w_k) is an integer");
        j.to_integer()
    }
}

/// `C(n, k)` as a big integer.
pub(crate) fn big_binomial(n: usize, k: usize) -> BigInt {
    if k > n {
        return BigInt::zero();
    }
    let k = k.min(n - k);
    let mut c = BigInt::one();
    for j in 1..=k {
        c = c * BigInt::from(n - k + j) / BigInt::from(j);
    }
    c
}

/// `∫_0^x Σ a_j u^j du` exactly.
fn poly_integral(a: &[BigRational], x: &BigRational) -> BigRational {
    let mut sum = BigRational::zero();
    let mut power = x.clone(); // x^{j+1}
    for (j, aj) in a.iter().enumerate() {
        sum += aj * &power / BigRational::from_integer(BigInt::from(j + 1));
        power = &power * x;
    }
    sum
}

/// Derivative of order `r` of a monomial polynomial.
fn poly_derivative(a: &[BigRational], r: usize) -> Vec<BigRational> {
    let mut d = a.to_vec();
    for _ in 0..r {
        if d.len() <= 1 {
            return vec![BigRational::zero()];
        }
        d = d
            .iter()
            .enumerate()
            .skip(1)
            .map(|(j, c)| c * BigRational::from_integer(BigInt::from(j)))
            .collect();
    }
    d
}

/// Product of two monomial polynomials.
fn poly_mul(a: &[BigRational], b: &[BigRational]) -> Vec<BigRational> {
    let mut out = vec![BigRational::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// `J_r(f) = ∫_0^1 (f^{(r)})²` exactly for a monomial polynomial `f`.
fn energy_exact(f: &[BigRational], r: usize) -> BigRational {
    let d = poly_derivative(f, r);
    poly_integral(&poly_mul(&d, &d), &BigRational::one())
}

/// `w_k(u)` as the upper tail `P(X ≥ k + 1)` of the binomial distribution `X ~ B(2k+1, u)` in
/// Horner form (see [`JumpPolynomial::eval`]), or `None` when `2k + 1` is beyond the binomial
/// table. `u` is in `[0, 1]`.
fn binomial_tail(k: usize, u: f64) -> Option<f64> {
    let n = 2 * k + 1;
    let row = crate::degree::elevation::binomial_row(n)?;
    if u > 0.5 {
        // 1 − u is exact for u in [1/2, 1] (Sterbenz)
        return binomial_tail(k, 1.0 - u).map(|w| 1.0 - w);
    }
    let s = 1.0 - u;
    let rho = u / s;
    let sum = row[k + 1..=n]
        .iter()
        .rev()
        .fold(0.0_f64, |acc, &c| acc * rho + c);
    // powi with an exponent ≤ 66: a handful of multiplications
    let e = i32::try_from(k).ok()?;
    Some(sum * u.powi(e + 1) * s.powi(e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn int(x: i64) -> BigInt {
        BigInt::from(x)
    }

    fn rat(x: &BigInt) -> BigRational {
        BigRational::from_integer(x.clone())
    }

    /// `w_k(u)` exactly, from the exact monomial coefficients at the exact rational `u`.
    fn exact_value(k: usize, u: f64) -> f64 {
        use num_traits::ToPrimitive;
        let x = BigRational::from_float(u).unwrap();
        let value = w(k)
            .monomial_coefficients()
            .iter()
            .rev()
            .fold(BigRational::zero(), |acc, c| acc * &x + rat(c));
        value.to_f64().unwrap()
    }

    #[test]
    fn horner_tail_is_relatively_accurate_and_matches_de_casteljau() {
        let us = [
            0.0,
            1e-300,
            1e-9,
            0.001,
            0.1,
            0.3,
            0.49,
            0.5,
            0.51,
            0.7,
            0.999,
            1.0 - 1e-12,
            1.0,
        ];
        for k in (0..=30).chain([64, 65, 66, 80]) {
            let ctrl = w(k).bernstein_coefficients_f64();
            for &u in &us {
                let fast = w(k).eval(u).unwrap();
                let mut dc = [0.0];
                bernstein_ops::derivatives_at(&ctrl, 1, u, 0, &mut dc, &mut Vec::new());
                // both are accurate to a few ulps relative to max(w, 1 − w)'s scale
                assert!(
                    (fast - dc[0]).abs() <= 64.0 * f64::EPSILON * dc[0].max(1e-300)
                        || (fast - dc[0]).abs() <= 4.0 * f64::EPSILON,
                    "k {k}, u {u}: {fast} vs de Casteljau {}",
                    dc[0]
                );
                assert!((0.0..=1.0).contains(&fast));
                if k <= 12 && u > 0.0 && u <= 0.5 {
                    // below 1/2 the tail is accurate relative to its own (small) size
                    let exact = exact_value(k, u);
                    assert!(
                        (fast - exact).abs() <= 16.0 * (k + 2) as f64 * f64::EPSILON * exact,
                        "k {k}, u {u}: {fast} vs exact {exact}"
                    );
                }
            }
        }
    }

    fn w(k: usize) -> JumpPolynomial {
        JumpPolynomial::new(k).unwrap()
    }

    fn factorial(n: usize) -> BigInt {
        (1..=n).fold(BigInt::one(), |f, j| f * BigInt::from(j))
    }

    // Evaluate a monomial polynomial at a rational point.
    fn poly_eval(a: &[BigRational], x: &BigRational) -> BigRational {
        a.iter()
            .rev()
            .fold(BigRational::zero(), |acc, c| acc * x + c)
    }

    // The table of w_k, k = 0 … 5 (docs/theory/blending.md#jump-smoothing-polynomials).
    #[test]
    fn table_of_w_0_to_w_5() {
        let table: [&[i64]; 6] = [
            &[0, 1],
            &[0, 0, 3, -2],
            &[0, 0, 0, 10, -15, 6],
            &[0, 0, 0, 0, 35, -84, 70, -20],
            &[0, 0, 0, 0, 0, 126, -420, 540, -315, 70],
            &[0, 0, 0, 0, 0, 0, 462, -1980, 3465, -3080, 1386, -252],
        ];
        let ends: [(i64, i64); 6] = [
            (1, 1),
            (6, -6),
            (60, 60),
            (840, -840),
            (15120, 15120),
            (332_640, -332_640),
        ];
        for (k, row) in table.iter().enumerate() {
            let got = w(k).monomial_coefficients();
            let expect: Vec<BigInt> = row.iter().map(|&x| int(x)).collect();
            assert_eq!(got, expect, "w_{k}");
            // (k+1)-th derivative at the ends, exactly
            let a: Vec<BigRational> = got.iter().map(rat).collect();
            let d = poly_derivative(&a, k + 1);
            let zero = BigRational::zero();
            let one = BigRational::one();
            assert_eq!(poly_eval(&d, &zero), rat(&int(ends[k].0)), "w_{k}^(k+1)(0)");
            assert_eq!(poly_eval(&d, &one), rat(&int(ends[k].1)), "w_{k}^(k+1)(1)");
        }
    }

    // Bernstein definition = closed monomial form, exactly, k ≤ 10.
    #[test]
    fn bernstein_equals_closed_form() {
        for k in 0..=10 {
            let got = w(k).monomial_coefficients();
            let lead = BigInt::from(2 * k + 1) * big_binomial(2 * k, k);
            for (m, a) in got.iter().enumerate() {
                if m <= k {
                    assert!(a.is_zero(), "a_{m} of w_{k}");
                    continue;
                }
                let j = m - k - 1;
                let num = &lead * big_binomial(k, j);
                let num = if j % 2 == 0 { num } else { -num };
                let closed = BigRational::new(num, BigInt::from(k + j + 1));
                assert_eq!(rat(a), closed, "a_{m} of w_{k}");
            }
        }
    }

    // Boundary conditions, Property 1 and the derivative formula, exactly for k ≤ 10.
    #[test]
    fn boundary_conditions_and_symmetry_exact() {
        let zero = BigRational::zero();
        let one = BigRational::one();
        for k in 0..=10 {
            let a: Vec<BigRational> = w(k).monomial_coefficients().iter().map(rat).collect();
            assert_eq!(poly_eval(&a, &zero), zero, "w_{k}(0)");
            assert_eq!(poly_eval(&a, &one), one, "w_{k}(1)");
            for l in 1..=k {
                let d = poly_derivative(&a, l);
                assert!(poly_eval(&d, &zero).is_zero(), "w_{k}^({l})(0)");
                assert!(poly_eval(&d, &one).is_zero(), "w_{k}^({l})(1)");
            }
            let d = poly_derivative(&a, k + 1);
            let at0 = poly_eval(&d, &zero);
            let expect = rat(&(BigInt::from(2 * k + 1) * big_binomial(2 * k, k) * factorial(k)));
            assert_eq!(at0, expect, "w_{k}^(k+1)(0)");
            // w(u) + w(1 − u) = 1 at 17 rational points (a polynomial identity of degree 2k+1,
            // so checking more than 2k+2 points proves it for k ≤ 7; the rest by the f64 test)
            for step in 0..=(2 * k + 2) {
                let u = BigRational::new(BigInt::from(step), BigInt::from(2 * k + 2));
                let s = poly_eval(&a, &u) + poly_eval(&a, &(&one - &u));
                assert_eq!(s, one, "w_{k}(u) + w_{k}(1-u) at {u}");
            }
            // w' = (2k+1) C(2k,k) u^k (1−u)^k, compared coefficient by coefficient
            let d1 = poly_derivative(&a, 1);
            let lead = BigInt::from(2 * k + 1) * big_binomial(2 * k, k);
            for (m, c) in d1.iter().enumerate() {
                let expect = if m >= k {
                    let j = m - k;
                    let v = &lead * big_binomial(k, j);
                    if j % 2 == 0 {
                        v
                    } else {
                        -v
                    }
                } else {
                    BigInt::zero()
                };
                assert_eq!(c, &rat(&expect), "w_{k}' coefficient {m}");
            }
        }
    }

    // Property 3: ∫_0^{1/2} w_k = C(2k+1, k) / 2^{2k+3}, exactly for k ≤ 10.
    #[test]
    fn integral_to_half_exact() {
        let first = [(1, 8), (3, 32), (5, 64), (35, 512), (63, 1024), (231, 4096)];
        for k in 0..=10 {
            let got = w(k).integral_to_half();
            let expect = BigRational::new(big_binomial(2 * k + 1, k), BigInt::one() << (2 * k + 3));
            assert_eq!(got, expect, "k = {k}");
            if let Some(&(p, q)) = first.get(k) {
                assert_eq!(
                    got,
                    BigRational::new(int(p), int(q)),
                    "tabulated value k = {k}"
                );
            }
        }
    }

    // Property 3 numerically for large k, and the decimals for k = 10, 20
    // (docs/theory/blending.md#properties-of-the-jump-polynomials).
    #[test]
    fn integral_to_half_f64() {
        assert!(
            (w(10).integral_to_half_f64() - 0.042_047).abs() < 5e-7,
            "k = 10"
        );
        assert!(
            (w(20).integral_to_half_f64() - 0.030_596).abs() < 5e-7,
            "k = 20"
        );
        for k in [11, 30, 60, 200, 500] {
            // C(2k+1,k)/2^{2k+3} via logs of the exact ratio C(2k+1,k) = Π (k+1+j)/j
            let mut ratio = 1.0_f64 / 8.0;
            for j in 1..=k {
                ratio *= (k + 1 + j) as f64 / (4.0 * j as f64);
            }
            let got = w(k).integral_to_half_f64();
            assert!(
                (got - ratio).abs() < 1e-13 * ratio.max(1.0),
                "k = {k}: {got} vs {ratio}"
            );
        }
        // decreasing to 0 like 1/(4√(πk))
        let big = w(1000).integral_to_half_f64();
        let asymptotic = 1.0 / (4.0 * (std::f64::consts::PI * 1000.0).sqrt());
        assert!((big / asymptotic - 1.0).abs() < 1e-3, "k = 1000: {big}");
    }

    // Property 4: J_{k+1}(w_k) = 1, 12, 720, 100800, … = (2k+1)! C(2k,k), exactly for k ≤ 10.
    #[test]
    fn energy_values() {
        let tabulated = [1, 12, 720, 100_800];
        for k in 0..=10 {
            let j = w(k).energy();
            assert_eq!(j, factorial(2 * k + 1) * big_binomial(2 * k, k), "k = {k}");
            if let Some(&v) = tabulated.get(k) {
                assert_eq!(j, int(v), "tabulated value k = {k}");
            }
        }
    }

    // Property 4: w_k + c·u^{k+1}(1−u)^{k+1}·q(u) keeps the boundary conditions and has
    // J = J(w_k) + J(perturbation) > J(w_k), exactly (the cross term integrates to zero).
    // Reference values: 12 + 4c²/5 (k = 1), 720 + 36c²/7 (k = 2)
    // (docs/theory/blending.md#energy-minimality).
    #[test]
    fn energy_minimal_against_perturbations() {
        let r = |p: i64, q: i64| BigRational::new(int(p), int(q));
        for k in 0..=10 {
            let a: Vec<BigRational> = w(k).monomial_coefficients().iter().map(rat).collect();
            let jw = rat(&w(k).energy());
            // bubble u^{k+1}(1−u)^{k+1}
            let mut bubble = vec![BigRational::one()];
            for _ in 0..=k {
                bubble = poly_mul(&bubble, &[BigRational::zero(), BigRational::one()]);
                bubble = poly_mul(&bubble, &[BigRational::one(), -BigRational::one()]);
            }
            let qs: [Vec<BigRational>; 3] = [
                vec![r(1, 1)],
                vec![r(-3, 2), r(5, 1)],
                vec![r(2, 7), r(0, 1), r(-11, 3)],
            ];
            for q in &qs {
                let h = poly_mul(&bubble, q);
                let mut f = a.clone();
                f.resize(h.len().max(f.len()), BigRational::zero());
                for (fi, hi) in f.iter_mut().zip(&h) {
                    *fi += hi;
                }
                let jf = energy_exact(&f, k + 1);
                let jh = energy_exact(&h, k + 1);
                assert!(jh > BigRational::zero(), "perturbation energy k = {k}");
                assert_eq!(jf, &jw + &jh, "orthogonality k = {k}");
                assert!(jf > jw, "w_{k} not beaten");
            }
            if k == 1 || k == 2 {
                let c = r(3, 1);
                let h: Vec<BigRational> = bubble.iter().map(|b| b * &c).collect();
                let mut f = a.clone();
                f.resize(h.len(), BigRational::zero());
                for (fi, hi) in f.iter_mut().zip(&h) {
                    *fi += hi;
                }
                let expect = if k == 1 {
                    r(12, 1) + r(4, 5) * &c * &c
                } else {
                    r(720, 1) + r(36, 7) * &c * &c
                };
                assert_eq!(energy_exact(&f, k + 1), expect, "closed form k = {k}");
            }
        }
    }

    // Floating point: the f64 evaluator against the exact coefficients (k ≤ 10), and the
    // properties for large k where the monomial form would be useless.
    #[test]
    fn f64_evaluation() {
        for k in 0..=10 {
            let a: Vec<f64> = w(k)
                .monomial_coefficients()
                .iter()
                .map(|c| c.to_string().parse::<f64>().unwrap())
                .collect();
            let mut out = vec![0.0; 2 * k + 4];
            for step in 0..=16 {
                let u = f64::from(step) / 16.0;
                w(k).eval_derivatives(u, &mut out).unwrap();
                for (l, &got) in out.iter().enumerate() {
                    // l-th derivative of the monomial form
                    let mut expect = 0.0;
                    for (j, &c) in a.iter().enumerate().skip(l) {
                        let falling: f64 = (j - l + 1..=j).map(|x| x as f64).product();
                        expect += c * falling * u.powi(i32::try_from(j - l).unwrap());
                    }
                    let scale = a.iter().map(|c| c.abs()).sum::<f64>()
                        * (1..=l)
                            .map(|x| (2 * k + 1) as f64 * x as f64)
                            .product::<f64>();
                    assert!(
                        (got - expect).abs() <= 1e-12 * scale.max(1.0),
                        "w_{k}^({l})({u}) = {got}, expected {expect}"
                    );
                }
            }
        }
        for k in [15, 40, 100, 400] {
            let wk = w(k);
            let mut out = vec![0.0; k + 2];
            wk.eval_derivatives(0.0, &mut out).unwrap();
            assert_eq!(out[0], 0.0, "k = {k}");
            assert!(
                out[1..=k].iter().all(|&d| d == 0.0),
                "k = {k}: derivatives at 0"
            );
            assert!(out[k + 1] != 0.0, "k = {k}: (k+1)-th derivative");
            wk.eval_derivatives(1.0, &mut out).unwrap();
            assert_eq!(out[0], 1.0, "k = {k}");
            assert!(
                out[1..=k].iter().all(|&d| d == 0.0),
                "k = {k}: derivatives at 1"
            );
            for step in 0..=20 {
                let u = f64::from(step) / 20.0;
                let s = wk.eval(u).unwrap() + wk.eval(1.0 - u).unwrap();
                assert!((s - 1.0).abs() < 1e-14, "k = {k}, u = {u}");
                // w' = (2k+1) C(2k,k) u^k (1−u)^k, computed in logs to avoid overflow
                wk.eval_derivatives(u, &mut out[..2]).unwrap();
                let expect = if u == 0.0 || u == 1.0 {
                    0.0
                } else {
                    let mut log = ((2 * k + 1) as f64).ln();
                    for j in 1..=k {
                        log += ((k + j) as f64 / j as f64).ln();
                    }
                    (log + k as f64 * (u * (1.0 - u)).ln()).exp()
                };
                assert!(
                    (out[1] - expect).abs() <= 1e-12 * expect.max(1.0),
                    "w_{k}'({u}) = {} vs {expect}",
                    out[1]
                );
            }
            assert!((wk.eval(0.5).unwrap() - 0.5).abs() < 1e-15, "k = {k}");
        }
    }

    // Gauss–Legendre nodes and weights on [0, 1] (Newton on the three-term recurrence; exact for
    // polynomials of degree 2n − 1).
    fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
        (1..=n)
            .map(|i| {
                let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
                let mut dp = 1.0;
                for _ in 0..100 {
                    let (mut p0, mut p1) = (1.0, x);
                    for j in 2..=n {
                        let p2 = ((2 * j - 1) as f64 * x * p1 - (j - 1) as f64 * p0) / j as f64;
                        p0 = p1;
                        p1 = p2;
                    }
                    dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                    let step = p1 / dp;
                    x -= step;
                    if step.abs() < 1e-16 {
                        break;
                    }
                }
                (0.5 * (1.0 - x), 1.0 / ((1.0 - x * x) * dp * dp))
            })
            .collect()
    }

    // Property 4 numerically for large k: J_{k+1}(w_k) = (2k+1)! C(2k,k) by Gauss–Legendre
    // quadrature of the library's own f64 derivatives, and the perturbation by the bubble
    // u^{k+1}(1−u)^{k+1} is J-orthogonal, so it can only increase J.
    #[test]
    fn energy_numerically_for_large_k() {
        // (order-l derivatives carry a relative error of about 2^l ε, see eval_derivatives)
        for k in [12, 16, 20] {
            let n = 2 * k + 1;
            let mut bubble = vec![0.0; n + 2];
            bubble[k + 1] = 1.0 / bernstein_ops::binomial(n + 1, k + 1);
            let (mut j, mut jh, mut cross) = (0.0, 0.0, 0.0);
            let mut dw = vec![0.0; k + 2];
            let mut dh = vec![0.0; k + 2];
            let mut scratch = Vec::new();
            for (u, weight) in gauss_legendre(k + 2) {
                w(k).eval_derivatives(u, &mut dw).unwrap();
                bernstein_ops::derivatives_at(&bubble, 1, u, k + 1, &mut dh, &mut scratch);
                j += weight * dw[k + 1] * dw[k + 1];
                jh += weight * dh[k + 1] * dh[k + 1];
                cross += weight * dw[k + 1] * dh[k + 1];
            }
            let closed: f64 = (1..=n).map(|x| x as f64).product::<f64>()
                * (1..=k).map(|j| (k + j) as f64 / j as f64).product::<f64>();
            assert!((j / closed - 1.0).abs() < 1e-8, "k = {k}: {j} vs {closed}");
            assert!(jh > 0.0, "k = {k}");
            assert!(
                cross.abs() < 1e-8 * (j * jh).sqrt(),
                "k = {k}: cross term {cross}"
            );
            // J(w + c h) − J(w) = 2c·cross + c²·J(h) > 0, c scaled so J(c h) = t² J(w_k)
            for t in [-2.0, 0.1, 3.0] {
                let c = t * (j / jh).sqrt();
                let increase = 2.0 * c * cross + c * c * jh;
                assert!(increase > 0.5 * t * t * j, "k = {k}, t = {t}");
            }
        }
    }

    #[test]
    fn errors() {
        assert!(matches!(
            JumpPolynomial::new(JumpPolynomial::MAX_K + 1),
            Err(Error::Degree { .. })
        ));
        assert!(matches!(
            w(2).eval(1.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            w(2).eval(f64::NAN),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            w(2).eval_derivatives(0.5, &mut []),
            Err(Error::TooFew { .. })
        ));
        assert_eq!(
            w(3).bernstein_coefficients(),
            [0, 0, 0, 0, 1, 1, 1, 1].map(int).to_vec()
        );
    }
}
