//! Changing the degree of Bezier curves without changing their shape (document 004, Nikulin
//! 2011, "A new method of changing the orders of Bezier curves and surfaces";
//! docs/theory/degree.md).
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
//!   elevated by 20 at least (test `stable_path_degree_40`, proptests in
//!   `tests/all/degree_change.rs`).
//! - The real degree depends on the tolerance: a smooth control polygon of high degree is often
//!   within `1e-10 × scale` of a lower degree, and then that lower degree is its real degree.

use crate::degree::elevation::{binomials, check_size, elevate};
use crate::degree::monomial::{
    check_monomial_degree, from_monomial_vec, real_degree_monomial_slice, to_monomial_vec,
};
use crate::degree::reduction::{
    absolute_tolerance, real_degree_and_net, try_reduce_exact, DEFAULT_DEGREE_TOLERANCE,
};
use crate::error::{check_finite, Error, Result};
use crate::points::Points;
use crate::BezierCurve;
use crate::What;

pub(crate) fn finite_result(what: impl Into<What>, data: Vec<f64>, dim: usize) -> Result<Points> {
    let what: What = what.into();
    if check_finite(what, &data).is_err() {
        return Err(Error::IllConditioned {
            reason: format!("{what} overflowed f64"),
        });
    }
    Ok(Points::from_raw(data, dim))
}

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
    /// closed-form inverse of docs/theory/degree.md#three-forms-of-a-bezier-curve). O(n²·dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // p(t) = 1 + 2t + 0t², a quadratic of real degree 1 (document 004's example, eq. (6)–(8))
    /// let c = BezierCurve::from_monomial(Points::from_flat(1, vec![1.0, 2.0, 0.0])?)?;
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
                what: "monomial coefficients".into(),
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
    /// let c = BezierCurve::new(Points::from_flat(1, vec![0.0, 3.0, 6.0])?)?.elevate_degree_once();
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
    /// `u'_j = Σ_i C(n,i) C(r,j−i) / C(n+r,j) u_i`, `r = by`
    /// (docs/theory/degree.md#elevation-by-several-degrees; Farin, *Curves and Surfaces for CAGD*,
    /// §5.1). Each new point is a convex combination of old ones, so the result is accurate to a
    /// few ulps of the net's scale at any degree. Equal to `by` applications of
    /// [`BezierCurve::elevate_degree_once`]. O((n+1)(r+1)·dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // document 004, Example 1, task 3: u'_2 = (u_0 + 6u_1 + 3u_2)/10
    /// let c = BezierCurve::new(Points::from_flat(1, vec![10.0, 0.0, 0.0, 0.0])?)?.elevate_degree(2)?;
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

    /// Degree defect `d = n − n'` (document 004, eq. (9)–(10)) with the default tolerance.
    #[must_use]
    pub fn degree_defect(&self) -> usize {
        self.degree() - self.real_degree()
    }

    /// Real degree `n'` of the polynomial (document 004, eq. (9)–(10)): the smallest `k` such that
    /// the exact reduction to degree `k` (stable Bernstein-domain recurrences, see the module
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

    /// Real degree by the paper's literal rule (document 004, eq. (9)–(10)): the number of trailing
    /// zero columns of `S_n = U_n H_n`. Coefficient `s_j` counts as zero when every coordinate is
    /// at most `tolerance × max|coordinate| × C(n,j) × 2^j`, the scale of its rounding error.
    /// Reliable for low degrees (about 15); use [`BezierCurve::real_degree_with_tolerance`]
    /// otherwise.
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
    ///   the terms `t^(target+1) … t^n`, docs/theory/degree.md#reduction-without-a-defect). For an
    ///   approximation use [`BezierCurve::reduce_degree_approx`].
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
    use super::*;
    use crate::degree::elevation::elevation_weights_into;
    use crate::degree::monomial::MAX_MONOMIAL_DEGREE;
    use crate::degree::reduction::max_abs_diff;

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
        Points::from_flat(dim, data).unwrap()
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
            BezierCurve::from_monomial(Points::from_flat(2, vec![]).unwrap()),
            Err(Error::TooFew { .. })
        ));
        let big =
            BezierCurve::new(Points::from_flat(1, vec![0.0; MAX_MONOMIAL_DEGREE + 2]).unwrap())
                .unwrap();
        assert!(matches!(big.to_monomial(), Err(Error::Degree { .. })));
        let huge =
            BezierCurve::new(Points::from_flat(1, vec![1.5e308, -1.5e308, 1.5e308]).unwrap())
                .unwrap();
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
        let p = BezierCurve::new(Points::from_flat(1, vec![2.0, 2.0, 2.0, 2.0]).unwrap()).unwrap();
        assert_eq!(p.real_degree(), 0, "constant");
        assert_eq!(p.reduce_degree_exact().control_points().as_slice(), &[2.0]);
        let z = BezierCurve::new(Points::from_flat(2, vec![0.0; 6]).unwrap()).unwrap();
        assert_eq!(z.real_degree(), 0, "zero net");
        let l = BezierCurve::new(Points::from_flat(1, vec![1.0, 2.0, 3.0, 4.0]).unwrap()).unwrap();
        assert_eq!(l.real_degree(), 1, "line");
        let single = BezierCurve::new(Points::from_flat(1, vec![5.0]).unwrap()).unwrap();
        assert_eq!(single.change_degree(0).unwrap(), single, "degree 0 stays");
    }
}
