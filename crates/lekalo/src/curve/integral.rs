//! Antiderivatives, definite integrals and extrapolation of B-spline curves
//! (`docs/theory/curves.md#antiderivatives-integrals-and-extrapolation`).
//!
//! - [`BSplineCurve::antiderivative`]: the spline of degree `p + 1` whose derivative is the
//!   curve (de Boor, *A Practical Guide to Splines*, ch. X, eq. (31); the same coefficients as
//!   SciPy's `splantider`).
//! - [`BSplineCurve::integral`] and [`BSplineCurve::integral_extrapolated`]: `∫_a^b C(t) dt`
//!   as the difference of the antiderivative at the two limits.
//! - [`BSplineCurve::eval_extrapolated`] and [`BSplineCurve::eval_batch_extrapolated`]: the
//!   polynomials of the first and last non-empty spans continued beyond the domain (SciPy's
//!   `BSpline(..., extrapolate=True)`); inside the domain the same bits as
//!   [`BSplineCurve::eval`]; [`bspline_value`], the same at one parameter on borrowed knots and
//!   coefficients (no curve built).

use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::{BSplineCurve, Beyond};
use crate::error::readable;
use crate::error::{check_degree_bound, check_finite, Error, Result};
use crate::points::Points;

impl BSplineCurve {
    /// The `order`-th antiderivative: a B-spline of degree `p + order` with the same domain,
    /// whose `order`-th derivative is the curve. One step takes the knots
    /// `t̃ = (t_0, t_0, t_1, …, t_m, t_m)` (each end knot once more) and the control points
    ///
    /// `P̃_0 = 0`, `P̃_{i+1} = Σ_{j≤i} P_j (t_{j+p+1} − t_j)/(p + 1)`, `i = 0 … n`,
    ///
    /// from `d/dt N_{i,p+1} = (p+1)(N_{i,p}/(t_{i+p+1} − t_i) − N_{i+1,p}/(t_{i+p+2} − t_{i+1}))`
    /// (de Boor, *A Practical Guide to Splines*, ch. X, eq. (31); SciPy's `splantider`, whose
    /// knots and coefficients these are). The antiderivative vanishes at `t_0` (to the left of
    /// the domain unless the knots are clamped there); definite integrals are differences of its
    /// values. `order = 0` gives the curve back. O(order · n · dim).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// // C(t) = t on [0, 1] (degree 1): ∫_0^t C = t²/2
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_flat(1, vec![0.0, 1.0])?)?;
    /// let a = c.antiderivative(1)?;
    /// assert_eq!(a.degree(), 2);
    /// assert_eq!(a.eval(0.5)?, vec![0.125]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Degree`] if `p + order` exceeds [`crate::MAX_DEGREE`];
    /// [`Error::NonFinite`] if a coefficient overflows.
    pub fn antiderivative(&self, order: usize) -> Result<BSplineCurve> {
        check_degree_bound(self.degree.saturating_add(order))?;
        let mut c = self.clone();
        for _ in 0..order {
            c = c.antiderivative_once()?;
        }
        Ok(c)
    }

    /// One step of [`BSplineCurve::antiderivative`].
    fn antiderivative_once(&self) -> Result<BSplineCurve> {
        let p = self.degree;
        let dim = self.dim();
        let u = self.knots.as_slice();
        let (first, last) = (u[0], u[u.len() - 1]);
        let mut knots = Vec::with_capacity(u.len() + 2);
        knots.push(first);
        knots.extend_from_slice(u);
        knots.push(last);
        let scale = 1.0 / (p as f64 + 1.0);
        let mut ctrl = Vec::with_capacity((self.control.len() + 1) * dim);
        let mut acc = vec![0.0; dim];
        ctrl.extend_from_slice(&acc);
        for (j, pj) in self.control.as_slice().chunks_exact(dim).enumerate() {
            let w = (u[j + p + 1] - u[j]) * scale;
            for (a, x) in acc.iter_mut().zip(pj) {
                *a += x * w;
            }
            ctrl.extend_from_slice(&acc);
        }
        check_finite(
            "antiderivative control points (overflow: rescale the control points)",
            &ctrl,
        )?;
        let curve = BSplineCurve::from_raw(p + 1, knots, Points::from_raw(ctrl, dim));
        debug_assert!(
            curve.knots.validate_for(p + 1, curve.control.len()).is_ok(),
            "antiderivative curve must be valid"
        );
        Ok(curve)
    }

    /// The definite integral `∫_a^b C(t) dt` (one number per coordinate) for `a`, `b` in the
    /// domain: `A(b) − A(a)` with `A` the [`BSplineCurve::antiderivative`] (de Boor, ch. X;
    /// SciPy's `BSpline.integrate(a, b, extrapolate=False)` for limits inside the base
    /// interval). `a > b` gives the negative of `∫_b^a`, `a = b` zero. Exact for the spline up
    /// to rounding; O(n · dim).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_flat(1, vec![0.0, 1.0])?)?;
    /// assert_eq!(c.integral(0.0, 1.0)?, vec![0.5]);
    /// assert_eq!(c.integral(1.0, 0.0)?, vec![-0.5]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if a limit is outside the domain or NaN (use
    /// [`BSplineCurve::integral_extrapolated`] to integrate the end polynomials beyond it);
    /// [`Error::NonFinite`] on overflow.
    pub fn integral(&self, a: f64, b: f64) -> Result<Vec<f64>> {
        let (lo, hi) = self.domain();
        for t in [a, b] {
            if !(t >= lo && t <= hi) {
                return Err(Error::ParameterOutOfDomain {
                    t,
                    min: lo,
                    max: hi,
                });
            }
        }
        let anti = self.antiderivative_once()?;
        let (fa, fb) = (anti.eval(a)?, anti.eval(b)?);
        difference(fb, &fa, (a, b), (lo, hi))
    }

    /// The definite integral `∫_a^b C(t) dt` for any finite `a`, `b`, the curve continued
    /// beyond its domain by its end polynomials ([`BSplineCurve::eval_extrapolated`]):
    /// `Ã(b) − Ã(a)` with `Ã` the antiderivative continued the same way (its first and last
    /// pieces are antiderivatives of the curve's, so the continuation commutes with
    /// integration). SciPy's `BSpline.integrate(a, b, extrapolate=True)`. Inside the domain
    /// the same numbers as [`BSplineCurve::integral`].
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// // C(t) = t on [0, 1], continued as t: ∫_{-1}^{2} t dt = 3/2
    /// let c = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_flat(1, vec![0.0, 1.0])?)?;
    /// assert_eq!(c.integral_extrapolated(-1.0, 2.0)?, vec![1.5]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] if a limit is NaN or infinite, or the result overflows inside the
    /// domain; [`Error::InvalidArgument`] naming the limits if the continued end polynomials'
    /// integral passes the largest double.
    pub fn integral_extrapolated(&self, a: f64, b: f64) -> Result<Vec<f64>> {
        check_finite("integration limits [a, b]", &[a, b])?;
        let anti = self.antiderivative_once()?;
        let (fa, fb) = (anti.eval_extrapolated(a)?, anti.eval_extrapolated(b)?);
        difference(fb, &fa, (a, b), self.domain())
    }

    /// Point `C(t)` for any finite `t`: inside the domain `[t_p, t_{n+1}]` the curve; before it
    /// the polynomial of the first non-empty span `[t_p, t_{p+1})`, after it that of the last,
    /// continued. The Cox–de Boor triangle (P&T Algorithm A2.2) computes the `p + 1` basis
    /// polynomials of a span for any `t`, not only inside it, so the continuation is the
    /// evaluation at the end span (de Boor, ch. IX; SciPy's `BSpline` with `extrapolate=True`
    /// and FITPACK's `splev(..., ext=0)` do the same).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// // the lecture's curve is (t²/2 + 1, −t² + 4t − 1) on [1, 2); at t = 0 that polynomial gives (1, −1)
    /// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?;
    /// assert_eq!(c.eval_extrapolated(0.0)?, vec![1.0, -1.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] if `t` is NaN or infinite.
    pub fn eval_extrapolated(&self, t: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_batch_extrapolated(&[t], &mut out)?;
        Ok(out)
    }

    /// [`BSplineCurve::eval_extrapolated`] at every parameter of `ts` into `out`
    /// (`ts.len() × dim`, point-major), with one scratch buffer and the previous span as the
    /// search hint.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`; [`Error::NonFinite`] at the
    /// first parameter that is NaN or infinite (nothing is guaranteed about `out` then).
    pub fn eval_batch_extrapolated(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        let dim = self.dim();
        if out.len() != ts.len() * dim {
            return Err(Error::LengthMismatch {
                what: "output buffer (parameters × dimension)".into(),
                expected: ts.len() * dim,
                got: out.len(),
            });
        }
        check_finite("parameters", ts)?;
        let p = self.degree;
        let (lo, hi) = self.domain();
        let mut cursor = self.knots.span_cursor(p);
        let mut scratch = BasisScratch::new(p);
        let mut n = vec![0.0; p + 1];
        for (&t, o) in ts.iter().zip(out.chunks_exact_mut(dim)) {
            let span = if t < lo {
                cursor.find_unchecked(lo)
            } else if t > hi {
                cursor.find_unchecked(hi)
            } else {
                cursor.find_unchecked(t)
            };
            self.eval_span(span, t, &mut scratch, &mut n, o);
        }
        Ok(())
    }
}

/// The value at `t` of the scalar spline `S(t) = Σ_j c_j B_{j,k}(t)` on borrowed knots and
/// coefficients, without building a curve: one span search (the last non-empty span
/// `t_i <= t < t_{i+1}` of the domain `[t_k, t_n]`, the last span at `t = t_n`), the `k + 1`
/// basis functions by Cox–de Boor (P&T Algorithm A2.2) and their combination (A3.1). Outside the
/// domain the end spans' polynomials are continued or NaN is given, as `beyond` says (the same
/// function as [`BSplineCurve::eval_extrapolated`]); a NaN or infinite `t` gives NaN. Knots with
/// more than `k + 1` copies are accepted (their B-splines vanish and are never used), and
/// coefficients beyond the `n = len(knots) − k − 1` that the knots use are ignored, as SciPy's
/// `BSpline` does. O(log n + k²); one small allocation.
///
/// ```
/// use lekalo::{bspline_value, BSplineCurve, Beyond, Points};
/// let t = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
/// let c = [1.0, 2.0, 4.0, 3.0, 0.5];
/// let curve = BSplineCurve::new(2, t.to_vec(), Points::from_flat(1, c.to_vec())?)?;
/// for x in [-1.0, 0.0, 0.7, 2.0, 3.0, 4.5] {
///     let v = bspline_value(&t, 2, &c, x, Beyond::Continue)?;
///     assert!((v - curve.eval_extrapolated(x)?[0]).abs() < 1e-14);
/// }
/// assert!(bspline_value(&t, 2, &c, 4.5, Beyond::Nan)?.is_nan());
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] if there are fewer than `2k + 2` knots, fewer coefficients than
/// `n`, or the domain is empty (`t_k = t_n`).
pub fn bspline_value(
    knots: &[f64],
    k: usize,
    coefficients: &[f64],
    t: f64,
    beyond: Beyond,
) -> Result<f64> {
    bspline_value_by(
        knots.len(),
        |i| knots[i],
        k,
        coefficients.len(),
        |i| coefficients[i],
        t,
        beyond,
    )
}

/// [`bspline_value`] reading the knots and coefficients through `knot(i)`, `i < n_knots`, and
/// `coefficient(j)`, `j < n_coefficients` (for arrays that are not Rust slices, such as a NumPy
/// array read in place): about `log2(n) + 3k + 2` reads, the same arithmetic.
///
/// # Errors
/// As [`bspline_value`].
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN knots must read as an empty domain or span
pub fn bspline_value_by(
    n_knots: usize,
    knot: impl Fn(usize) -> f64,
    k: usize,
    n_coefficients: usize,
    coefficient: impl Fn(usize) -> f64,
    t: f64,
    beyond: Beyond,
) -> Result<f64> {
    let invalid = |reason: String| Error::InvalidArgument {
        what: "spline (knots, degree, coefficients)".into(),
        reason,
    };
    if n_knots < 2 * k + 2 {
        return Err(invalid(format!(
            "{n_knots} knots for degree {k}: at least {} are needed",
            2 * k + 2
        )));
    }
    let n = n_knots - k - 1;
    if n_coefficients < n {
        return Err(invalid(format!(
            "{n_coefficients} coefficients for {n_knots} knots of degree {k}: at least {n} are needed"
        )));
    }
    let (lo, hi) = (knot(k), knot(n));
    if !(lo < hi) {
        return Err(invalid(format!(
            "the domain [t_k, t_n] = [{lo}, {hi}] is empty",
            lo = readable(&lo),
            hi = readable(&hi)
        )));
    }
    if !t.is_finite() || (beyond == Beyond::Nan && !(lo <= t && t <= hi)) {
        return Ok(f64::NAN);
    }
    // the last span i in k..n with t_i <= t (the first for t < t_k), non-empty
    let i = crate::knots::span_by(&knot, k, n, t);
    // the knots t_{i-k+1} ..= t_{i+k} that the triangle reads, after one unused slot: t_i is
    // at index k of the window, which is the span the triangle is given
    let window: Vec<f64> = std::iter::once(f64::NAN)
        .chain((i + 1 - k..=i + k).map(&knot))
        .collect();
    let mut scratch = BasisScratch::new(k);
    let mut basis = vec![0.0; k + 1];
    basis_funs_into(&window, k, k, t, &mut scratch, &mut basis);
    Ok(basis
        .iter()
        .enumerate()
        .map(|(r, b)| b * coefficient(i - k + r))
        .sum())
}

/// `b − a` coordinate by coordinate, the integral from `ta` to `tb` over the domain `[lo, hi]`,
/// checked for overflow ([`check_integral`]).
fn difference(
    mut b: Vec<f64>,
    a: &[f64],
    (ta, tb): (f64, f64),
    (lo, hi): (f64, f64),
) -> Result<Vec<f64>> {
    for (x, y) in b.iter_mut().zip(a) {
        *x -= y;
    }
    check_integral(
        &b,
        ta,
        tb,
        lo,
        hi,
        "integral (overflow: rescale the control points)",
    )?;
    Ok(b)
}

/// An error if `values`, the integral from `a` to `b` of a spline on the domain `[lo, hi]`, are
/// not all finite. A limit outside the domain (the end polynomials continued,
/// `docs/theory/curves.md#antiderivatives-integrals-and-extrapolation`) whose integral passes
/// the largest double is named with the limits and the fix, an [`Error::InvalidArgument`] of
/// the limits: `∫_{−1e308}^{1e308}` of a line is `+∞ − ∞`, which was reported as a NaN to
/// rescale the coefficients. Inside the domain the coefficients are what overflows:
/// [`Error::NonFinite`] of `inside`.
pub(crate) fn check_integral(
    values: &[f64],
    a: f64,
    b: f64,
    lo: f64,
    hi: f64,
    inside: &'static str,
) -> Result<()> {
    let beyond = a.min(b) < lo || a.max(b) > hi;
    if beyond && values.iter().any(|v| !v.is_finite()) {
        return Err(Error::InvalidArgument {
            what: "integration limits [a, b]".into(),
            reason: format!(
                "the integral from {} to {} is computed from the antiderivative of the spline's \
                 end polynomials, continued that far beyond its domain [{}, {}], which passes \
                 the largest double (1.8e308) there; integrate over a shorter interval, or \
                 without extrapolation",
                readable(&a),
                readable(&b),
                readable(&lo),
                readable(&hi)
            ),
        });
    }
    check_finite(inside, values)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An integral continued so far that it passes the largest double is refused naming the
    /// limits (it was a NaN, `+∞ − ∞`, reported as coefficients to rescale), by the curve and by
    /// the arrays' kernel; a large one that fits is still computed.
    #[test]
    fn integrals_past_the_largest_double_name_the_limits() {
        let line = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_flat(1, vec![0.0, 1.0]).unwrap(),
        )
        .unwrap();
        let e = line.integral_extrapolated(-1e308, 1e308).unwrap_err();
        assert!(
            matches!(&e, Error::InvalidArgument { what, .. } if what.words() == "integration limits [a, b]"),
            "{e:?}"
        );
        let m = e.to_string();
        assert!(
            m.contains("the integral from -1e308 to 1e308 is computed from the antiderivative"),
            "{m}"
        );
        assert!(m.contains("integrate over a shorter interval"), "{m}");
        let mut out = [0.0];
        let e = crate::curve::integral_into(
            &[0.0, 0.0, 1.0, 1.0],
            1,
            &[0.0, 1.0],
            1,
            1e308,
            -1e308,
            &mut out,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("the integral from 1e308 to -1e308 is computed"),
            "{e}"
        );
        // ∫ t dt from -1e10 to 2e10 = 1.5e20, far outside the domain: finite, computed
        let v = line.integral_extrapolated(-1e10, 2e10).unwrap();
        assert!((v[0] / 1.5e20 - 1.0).abs() < 1e-12, "{v:?}");
    }

    /// `bspline_value` is `eval_extrapolated` on the curve (knots of any multiplicity, the
    /// ends, beyond them), NaN where asked for, and refuses inconsistent sizes.
    #[test]
    fn bspline_value_matches_the_curve() {
        // a repeated interior knot, end knots of multiplicity k + 2 (a vanishing B-spline)
        let t = vec![
            0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 5.0, 5.0, 5.0, 5.0,
        ];
        let k = 3;
        let n = t.len() - k - 1;
        let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.9).sin() + 2.0).collect();
        // the curve without the vanishing B-spline (its coefficient is never used)
        let curve = BSplineCurve::new(
            k,
            t[1..].to_vec(),
            Points::from_flat(1, c[1..].to_vec()).unwrap(),
        )
        .unwrap();
        for x in [-2.0, 0.0, 0.3, 1.0, 1.999, 2.0, 2.5, 4.9, 5.0, 7.0] {
            let v = bspline_value(&t, k, &c, x, Beyond::Continue).unwrap();
            let want = curve.eval_extrapolated(x).unwrap()[0];
            assert!(
                (v - want).abs() <= 1e-13 * (1.0 + x.abs().powi(3)),
                "x = {x}: {v} {want}"
            );
            let inside = (0.0..=5.0).contains(&x);
            assert_eq!(
                bspline_value(&t, k, &c, x, Beyond::Nan).unwrap().is_nan(),
                !inside
            );
        }
        // more coefficients than the knots use: the extra ones are ignored
        let mut longer = c.clone();
        longer.extend([1e9, 1e9]);
        assert_eq!(
            bspline_value(&t, k, &longer, 2.5, Beyond::Continue).unwrap(),
            bspline_value(&t, k, &c, 2.5, Beyond::Continue).unwrap()
        );
        for x in [f64::NAN, f64::INFINITY] {
            assert!(bspline_value(&t, k, &c, x, Beyond::Continue)
                .unwrap()
                .is_nan());
        }
        assert!(bspline_value(&t[..7], k, &c, 0.5, Beyond::Continue).is_err());
        assert!(bspline_value(&t, k, &c[..n - 1], 0.5, Beyond::Continue).is_err());
        assert!(bspline_value(&[1.0; 8], k, &c, 1.0, Beyond::Continue).is_err());
    }

    /// Gauss–Legendre nodes and weights of 5 points on [−1, 1]: exact for degree ≤ 9.
    const GL5: [(f64, f64); 5] = [
        (0.0, 0.568_888_888_888_888_9),
        (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
        (0.906_179_845_938_664, 0.236_926_885_056_189_08),
    ];

    /// `∫_a^b C` by 5-point Gauss–Legendre on each span piece inside `[a, b]`, the curve
    /// continued by its end polynomials outside the domain.
    fn quadrature(c: &BSplineCurve, a: f64, b: f64) -> Vec<f64> {
        if a > b {
            return quadrature(c, b, a).iter().map(|x| -x).collect();
        }
        let (lo, hi) = c.domain();
        let mut cuts = vec![a, b];
        cuts.extend(
            c.knots()
                .as_slice()
                .iter()
                .filter(|&&k| k > a && k < b && k >= lo && k <= hi),
        );
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let mut sum = vec![0.0; c.dim()];
        for w in cuts.windows(2) {
            let (m, h) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
            for &(x, wt) in &GL5 {
                let v = c.eval_extrapolated(m + h * x).unwrap();
                for (s, y) in sum.iter_mut().zip(v) {
                    *s += wt * h * y;
                }
            }
        }
        sum
    }

    fn lecture() -> BSplineCurve {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
        BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap()
    }

    #[test]
    fn lecture_integral_and_extrapolation_follow_the_power_form() {
        // on [1, 2]: (t²/2 + 1, −t² + 4t − 1); ∫_1^2 = (7/6 + 1, −7/3 + 6 − 1)
        let c = lecture();
        let i = c.integral(1.0, 2.0).unwrap();
        assert!((i[0] - (7.0 / 6.0 + 1.0)).abs() < 1e-14, "x: {i:?}");
        assert!((i[1] - (-7.0 / 3.0 + 5.0)).abs() < 1e-14, "y: {i:?}");
        let r = c.integral(2.0, 1.0).unwrap();
        assert_eq!(r, vec![-i[0], -i[1]]);
        assert_eq!(c.integral(1.5, 1.5).unwrap(), vec![0.0, 0.0]);
        for t in [-3.0, 0.0, 0.5, 2.5, 7.0] {
            let p = c.eval_extrapolated(t).unwrap();
            assert!((p[0] - (0.5 * t * t + 1.0)).abs() < 1e-12, "x at {t}");
            assert!((p[1] - (-t * t + 4.0 * t - 1.0)).abs() < 1e-12, "y at {t}");
        }
        // ∫_0^3 of the power form: (9/2 + 3, −9 + 18 − 3)
        let e = c.integral_extrapolated(0.0, 3.0).unwrap();
        assert!(
            (e[0] - 7.5).abs() < 1e-13 && (e[1] - 6.0).abs() < 1e-13,
            "{e:?}"
        );
    }

    #[test]
    fn errors_are_reported_not_panicked() {
        let c = lecture();
        assert!(matches!(
            c.integral(0.5, 1.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            c.integral(f64::NAN, 1.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            c.integral_extrapolated(f64::INFINITY, 1.5),
            Err(Error::NonFinite { .. })
        ));
        assert!(matches!(
            c.eval_extrapolated(f64::NAN),
            Err(Error::NonFinite { .. })
        ));
        assert!(matches!(
            c.antiderivative(usize::MAX),
            Err(Error::Degree { .. })
        ));
        let mut out = [0.0; 3];
        assert!(matches!(
            c.eval_batch_extrapolated(&[1.0, 2.0], &mut out),
            Err(Error::LengthMismatch { .. })
        ));
        assert_eq!(c.antiderivative(0).unwrap(), c);
    }

    #[test]
    fn antiderivative_of_a_jump_is_continuous() {
        // degree 0 with an interior knot of multiplicity 1 = p + 1: a step from 1 to 3 at t = 1
        let c = BSplineCurve::new(
            0,
            vec![0.0, 1.0, 2.0],
            Points::from_flat(1, vec![1.0, 3.0]).unwrap(),
        )
        .unwrap();
        let a = c.antiderivative(1).unwrap();
        assert_eq!(a.degree(), 1);
        assert_eq!(a.eval(1.0).unwrap(), vec![1.0]);
        assert_eq!(a.eval(2.0).unwrap(), vec![4.0]);
        assert_eq!(c.integral(0.5, 1.5).unwrap(), vec![2.0]);
    }

    #[test]
    fn curves_of_any_kind_delegate_and_rational_ones_refuse() {
        use crate::{BezierCurve, Curve, NurbsCurve};
        // the Bezier curve t ↦ t² on [0, 1] (control 0, 0, 1): ∫_0^1 = 1/3
        let b = Curve::from(
            BezierCurve::new(Points::from_flat(1, vec![0.0, 0.0, 1.0]).unwrap()).unwrap(),
        );
        let i = b.integral(0.0, 1.0).unwrap();
        assert!((i[0] - 1.0 / 3.0).abs() < 1e-15, "{i:?}");
        let a = b.antiderivative(1).unwrap();
        assert_eq!(a.degree(), 3);
        assert!((a.eval(1.0).unwrap()[0] - 1.0 / 3.0).abs() < 1e-15);
        let n = Curve::from(
            NurbsCurve::new(
                1,
                vec![0.0, 0.0, 1.0, 1.0],
                Points::from_flat(1, vec![0.0, 1.0]).unwrap(),
                vec![1.0, 2.0],
            )
            .unwrap(),
        );
        assert!(matches!(
            n.integral(0.0, 1.0),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            n.antiderivative(1),
            Err(Error::InvalidArgument { .. })
        ));
    }

    proptest::proptest! {
        /// On random (possibly unclamped, with repeated knots) splines of degree 0..=5 and
        /// dimension 1..=3: the derivative of the antiderivative is the curve, the integral
        /// equals Gauss–Legendre quadrature per span (also beyond the domain), and
        /// extrapolation inside the domain is plain evaluation.
        #[test]
        fn antiderivative_integral_and_extrapolation(
            degree in 0usize..=5,
            dim in 1usize..=3,
            gaps in proptest::collection::vec(0u8..=4, 12..20),
            coords in proptest::collection::vec(-10.0f64..10.0, 60),
            limits in proptest::collection::vec(0.0f64..1.0, 2),
        ) {
            let mut knots = vec![0.0];
            for g in &gaps {
                let last = knots[knots.len() - 1];
                knots.push(last + f64::from(*g) * 0.25);
            }
            let n = knots.len().saturating_sub(degree + 1);
            if n < degree + 1 {
                return Ok(());
            }
            let ctrl = Points::from_flat(dim, coords[..n * dim].to_vec()).unwrap();
            let Ok(c) = BSplineCurve::new(degree, knots, ctrl) else {
                return Ok(()); // a knot of multiplicity above degree + 1, or an empty domain
            };
            let (lo, hi) = c.domain();
            let anti = c.antiderivative(1).unwrap();
            proptest::prop_assert_eq!(anti.domain(), (lo, hi));
            let back = anti.derivative().unwrap();
            let scale = coords.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for k in 0..=20 {
                let t = lo + (hi - lo) * f64::from(k) / 20.0;
                let (x, y) = (c.eval(t).unwrap(), back.eval(t).unwrap());
                for (u, v) in x.iter().zip(&y) {
                    proptest::prop_assert!((u - v).abs() <= 1e-12 * scale, "C({}) {:?} vs (∫C)' {:?}", t, x, y);
                }
                proptest::prop_assert_eq!(c.eval_extrapolated(t).unwrap(), c.eval(t).unwrap());
            }
            let (a, b) = (lo + (hi - lo) * limits[0], lo + (hi - lo) * limits[1]);
            let width = (hi - lo).max(1.0);
            for (got, want) in [
                (c.integral(a, b).unwrap(), quadrature(&c, a, b)),
                (c.integral_extrapolated(lo - 0.5, hi + 0.75).unwrap(), quadrature(&c, lo - 0.5, hi + 0.75)),
            ] {
                for (u, v) in got.iter().zip(&want) {
                    proptest::prop_assert!(
                        (u - v).abs() <= 1e-10 * scale * width.powi(i32::try_from(degree).unwrap() + 1),
                        "integral {:?} vs quadrature {:?}", got, want
                    );
                }
            }
        }
    }
}
