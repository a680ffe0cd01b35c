//! Divided differences and the B-spline as a divided difference of truncated powers
//! (document 003, chapters 2–3; docs/theory/pp.md#divided-differences).
//!
//! Notation of the thesis: `f(x_1; …; x_n)` is de Boor's `[x_1, …, x_n] f`, the divided difference
//! of order `n − 1`. Points may repeat: at a point that occurs `m` times the divided difference
//! uses the derivatives `f', …, f^{(m−1)}` there (Lemmas 2.8–2.9), so the function is given as a
//! closure `f(x, r) = f^{(r)}(x)`.
//!
//! Conventions for the truncated power `(x − z)_+^{k−1}` and the B-spline `b_{i,k}` (eq. 4) are
//! chosen so that `b_{i,k}` agrees with the rest of lekalo: right-continuous, non-zero on
//! `[x_i, x_{i+k})`, with the last non-empty interval closed at the last knot (see
//! [`bspline_divided_difference`]).

use crate::error::{check_finite, Error, Result};
use crate::knots::KnotVector;

/// Divided difference `f(x_1; …; x_n)` of order `n − 1` at any points, repeated ones included
/// (document 003, eq. 1 and Lemmas 2.8–2.9).
///
/// `f(x, r)` must return the `r`-th derivative `f^{(r)}(x)`; it is called with `r > 0` only at a
/// point that occurs more than `r` times. The points are sorted first (the divided difference is
/// symmetric, Lemma 2.3), then the triangular table of eq. (1) is built, with
/// `f(x; …; x) = f^{(m)}(x)/m!` for `m + 1` equal points (Lemma 2.8). Equality is exact. O(n²)
/// time, O(n) memory.
///
/// **Conditioning.** Each level divides differences of nearly equal numbers by point gaps, so the
/// absolute error is about `ε · max|f| · (1/h)^{n−1}` for the smallest non-zero gap `h`. This is
/// inherent to divided differences of high order, not to this algorithm.
///
/// ```
/// use lekalo::divided_difference;
/// // f = x³: f(0; 1; 1; 2) is the leading coefficient 1 (Lemma 2.5), f(2; 2; 2) = f''(2)/2 = 6
/// let cube = |x: f64, r: usize| [x * x * x, 3.0 * x * x, 6.0 * x, 6.0][r.min(3)];
/// assert!((divided_difference(&[0.0, 1.0, 2.0, 1.0], cube).unwrap() - 1.0).abs() < 1e-14);
/// assert!((divided_difference(&[2.0, 2.0, 2.0], cube).unwrap() - 6.0).abs() < 1e-14);
/// ```
///
/// # Errors
/// [`Error::TooFew`] for no points; [`Error::NonFinite`] for a NaN or infinite point.
pub fn divided_difference<F: FnMut(f64, usize) -> f64>(points: &[f64], f: F) -> Result<f64> {
    let x = sorted_points(points)?;
    let mut table = vec![0.0; x.len()];
    Ok(divided_difference_sorted(&x, f, &mut table, None))
}

/// Divided differences by the explicit formula of Lemma 2.1 (document 003, eq. 2), for
/// **distinct** points with given values:
/// `f(x_1; …; x_n) = Σ_j f(x_j) / Π_{i≠j} (x_j − x_i)`.
/// O(n²). Less stable than the table of [`divided_difference`] (no cancellation control), kept as
/// the thesis's formula and as a test oracle.
///
/// ```
/// use lekalo::{divided_difference, divided_difference_explicit};
/// let x = [0.0, 0.5, 2.0];
/// let v: Vec<f64> = x.iter().map(|t| t * t).collect();
/// assert!((divided_difference_explicit(&x, &v).unwrap() - 1.0).abs() < 1e-15);
/// ```
///
/// # Errors
/// [`Error::TooFew`] for no points; [`Error::LengthMismatch`] if `values` and `points` differ in
/// length; [`Error::NonFinite`]; [`Error::InvalidArgument`] if two points are equal (use
/// [`divided_difference`] with derivatives instead).
pub fn divided_difference_explicit(points: &[f64], values: &[f64]) -> Result<f64> {
    let x = sorted_points(points)?;
    if values.len() != points.len() {
        return Err(Error::LengthMismatch {
            what: "values (one per point)".into(),
            expected: points.len(),
            got: values.len(),
        });
    }
    check_finite("values", values)?;
    if let Some(w) = x.windows(2).find(|w| w[0] == w[1]) {
        return Err(Error::InvalidArgument {
            what: "points".into(),
            reason: format!(
                "the explicit formula (Lemma 2.1) needs distinct points, but {} repeats; use \
                 divided_difference with derivatives for repeated points",
                w[0]
            ),
        });
    }
    let mut sum = 0.0;
    for (j, (&xj, &fj)) in points.iter().zip(values).enumerate() {
        let denom: f64 = points
            .iter()
            .enumerate()
            .filter(|&(i, _)| i != j)
            .map(|(_, &xi)| xj - xi)
            .product();
        sum += fj / denom;
    }
    Ok(sum)
}

/// The Newton form of the polynomial `p_n` of order `n` (degree `< n`) that agrees with `g` on
/// `x_1, …, x_n` (repeated points meaning osculation), document 003 Theorem 4.1, eq. (8):
/// `p_n(z) = Σ_i (z − x_1)⋯(z − x_{i−1}) g(x_1; …; x_i)`.
/// The error is `g(z) − p_n(z) = (z − x_1)⋯(z − x_n) g(x_1; …; x_n; z)` (eq. 7).
///
/// ```
/// use lekalo::NewtonForm;
/// // osculating g = exp at 0 (twice) and 1: value and slope at 0, value at 1
/// let g = |x: f64, _r: usize| x.exp();
/// let p = NewtonForm::new(&[0.0, 0.0, 1.0], g).unwrap();
/// assert!((p.eval(1.0) - 1f64.exp()).abs() < 1e-15);
/// assert!((p.eval(0.0) - 1.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonForm {
    nodes: Vec<f64>,
    coefficients: Vec<f64>,
}

impl NewtonForm {
    /// The Newton form on `points` (sorted internally; the polynomial does not depend on their
    /// order). `g(x, r)` returns `g^{(r)}(x)` as for [`divided_difference`]. O(n²).
    ///
    /// # Errors
    /// As [`divided_difference`].
    pub fn new<F: FnMut(f64, usize) -> f64>(points: &[f64], g: F) -> Result<Self> {
        let nodes = sorted_points(points)?;
        let mut table = vec![0.0; nodes.len()];
        let mut coefficients = Vec::with_capacity(nodes.len());
        divided_difference_sorted(&nodes, g, &mut table, Some(&mut coefficients));
        Ok(NewtonForm {
            nodes,
            coefficients,
        })
    }

    /// The nodes `x_1 ≤ … ≤ x_n`.
    #[must_use]
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The coefficients `g(x_1; …; x_i)`, `i = 1 … n`.
    #[must_use]
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// `p_n(z)` by nested multiplication (Horner for the Newton basis). O(n).
    #[must_use]
    pub fn eval(&self, z: f64) -> f64 {
        let n = self.coefficients.len();
        let mut p = self.coefficients[n - 1];
        for i in (0..n - 1).rev() {
            p = p * (z - self.nodes[i]) + self.coefficients[i];
        }
        p
    }
}

/// The truncated power `(x − z)_+^{k−1}` of order `k` (document 003, Definition 3.1): the
/// variable is `x`, `z` a parameter. For `k = 1` the step is taken as `1` for `x > z` and `0` for
/// `x ≤ z` (the source leaves `x = z` open): with this choice the B-splines of eq. (4) are
/// right-continuous, non-zero on `[x_i, x_{i+k})`, like the Cox–de Boor basis of lekalo.
///
/// ```
/// use lekalo::truncated_power;
/// assert_eq!(truncated_power(3.0, 1.0, 3), 4.0);
/// assert_eq!(truncated_power(0.5, 1.0, 3), 0.0);
/// assert_eq!(truncated_power(1.0, 1.0, 1), 0.0);
/// ```
#[must_use]
pub fn truncated_power(x: f64, z: f64, order: usize) -> f64 {
    truncated_power_derivative(x, z, order, 0, false)
}

/// `d^r/dx^r (x − z)_+^{k−1} = (k−1)!/(k−1−r)! (x − z)_+^{k−1−r}`, zero for `r ≥ k`; the step
/// (exponent 0) is `x > z`, or `x ≥ z` when `closed` (the left limit in `z`).
fn truncated_power_derivative(x: f64, z: f64, order: usize, r: usize, closed: bool) -> f64 {
    if order == 0 || r >= order {
        return 0.0;
    }
    let e = order - 1 - r;
    let d = x - z;
    let on = if e == 0 {
        d > 0.0 || (closed && d == 0.0)
    } else {
        d > 0.0
    };
    if !on {
        return 0.0;
    }
    let falling: f64 = (e + 1..order).map(|v| v as f64).product();
    falling * d.powi(i32::try_from(e).unwrap_or(i32::MAX))
}

/// The normalised B-spline of degree `p` (order `k = p + 1`) on the knots `x_i … x_{i+k}` as a
/// divided difference of truncated powers, document 003 eq. (4):
/// `b_{i,k}(t) = (x_{i+k} − x_i) · φ_t(x_i; …; x_{i+k})`, `φ_t(x) = (x − t)_+^{k−1}`,
/// the divided difference taken in `x`. Repeated knots use confluent divided differences
/// (Lemmas 2.8–2.9) through the derivatives of `φ_t`; the explicit sum (4) would divide by zero.
///
/// Conventions, identical to [`crate::basis::basis_function_recursive`]: the value is `0` outside
/// `[x_i, x_{i+k})` (Lemma 3.1; returned exactly without computing), right-continuous at the
/// knots, and at the last knot `t = x_m` the left limit is taken (the last non-empty interval is
/// closed). Defined on the whole knot range `[x_0, x_m]`.
///
/// **Conditioning.** The divided difference of order `k` cancels values of size `Δ^{k−1}`
/// (`Δ = x_{i+k} − x_i`) and divides by knot gaps. The loss is worst when `m + 1` distinct knots
/// with gaps `g` cluster where `φ_t` does not vanish (right of `t`): the error is then about
/// `ε · (Δ/g)^m`, at most `ε · (Δ/g)^{k−1}`. Measured against the recurrence (support `[0, 1]`,
/// `k` knots clustered within `h` at the right end): `k = 3, Δ/h = 256`: 1.5e-11;
/// `k = 4, Δ/h = 16`: 1.0e-11; `k = 4, Δ/h = 256`: 3.4e-8; `k = 6, Δ/h = 16`: 8.6e-8. With all
/// gaps `≥ Δ/8` (knots on a coarse grid) and `k ≤ 5` it agrees to 1e-12 (property test), and a
/// single small gap costs nothing. It is meant as an oracle, not a kernel: use
/// [`crate::basis::basis_functions`] to evaluate splines. O(k²) per call.
///
/// ```
/// use lekalo::{basis::basis_function_recursive, bspline_divided_difference, KnotVector};
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0, 3.0, 3.0]).unwrap();
/// for i in 0..8 {
///     for &t in &[0.0, 0.3, 0.9, 2.2, 3.0] {
///         let a = bspline_divided_difference(&kv, i, 2, t).unwrap();
///         let b = basis_function_recursive(&kv, i, 2, t).unwrap();
///         assert!((a - b).abs() < 1e-13);
///     }
/// }
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] if `i + p + 1` exceeds the last knot index;
/// [`Error::ParameterOutOfDomain`] if `t` is outside `[x_0, x_m]` or NaN.
pub fn bspline_divided_difference(
    knots: &KnotVector,
    i: usize,
    degree: usize,
    t: f64,
) -> Result<f64> {
    let all = knots.as_slice();
    let order = degree.saturating_add(1); // saturated: then the check below fails
    if i.checked_add(order).is_none_or(|end| end >= all.len()) {
        return Err(Error::InvalidArgument {
            what: "basis function index".into(),
            reason: format!(
                "b_{{{i},{order}}} needs knots up to index {}, but the last knot index is {}",
                i.saturating_add(order),
                all.len() - 1
            ),
        });
    }
    let (min, last) = (all[0], all[all.len() - 1]);
    if !(t >= min && t <= last) {
        return Err(Error::ParameterOutOfDomain { t, min, max: last });
    }
    let x = &all[i..=i + order];
    let (lo, hi) = (x[0], x[order]);
    // the left limit at the last knot closes the last non-empty interval
    let closed = t == last;
    if lo == hi || t < lo || t > hi || (t == hi && !closed) {
        return Ok(0.0);
    }
    let mut table = vec![0.0; order + 1];
    let dd = divided_difference_sorted(
        x,
        |xv, r| truncated_power_derivative(xv, t, order, r, closed),
        &mut table,
        None,
    );
    Ok((hi - lo) * dd)
}

/// Validated, sorted copy of the points.
fn sorted_points(points: &[f64]) -> Result<Vec<f64>> {
    if points.is_empty() {
        return Err(Error::TooFew {
            what: "points of a divided difference".into(),
            min: 1,
            got: 0,
        });
    }
    check_finite("points", points)?;
    let mut x = points.to_vec();
    x.sort_by(f64::total_cmp);
    Ok(x)
}

/// The divided-difference table (eq. 1, Lemma 2.8) on sorted points `x`, in place in `table`
/// (`len == x.len()`); pushes the Newton coefficients `f(x_0; …; x_j)` if asked.
fn divided_difference_sorted<F: FnMut(f64, usize) -> f64>(
    x: &[f64],
    mut f: F,
    table: &mut [f64],
    mut newton: Option<&mut Vec<f64>>,
) -> f64 {
    debug_assert_eq!(x.len(), table.len(), "table length");
    debug_assert!(x.windows(2).all(|w| w[0] <= w[1]), "points sorted");
    for (d, &xi) in table.iter_mut().zip(x) {
        *d = f(xi, 0);
    }
    if let Some(c) = newton.as_deref_mut() {
        c.push(table[0]);
    }
    let mut factorial = 1.0;
    for j in 1..x.len() {
        factorial *= j as f64;
        for i in 0..x.len() - j {
            table[i] = if x[i + j] == x[i] {
                f(x[i], j) / factorial
            } else {
                (table[i + 1] - table[i]) / (x[i + j] - x[i])
            };
        }
        if let Some(c) = newton.as_deref_mut() {
            c.push(table[0]);
        }
    }
    table[0]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    // sin with its derivatives.
    fn sin_d(x: f64, r: usize) -> f64 {
        match r % 4 {
            0 => x.sin(),
            1 => x.cos(),
            2 => -x.sin(),
            _ => -x.cos(),
        }
    }

    fn factorial(n: usize) -> f64 {
        (1..=n).map(|v| v as f64).product()
    }

    // Lemma 2.1: the explicit formula equals the recursive table at distinct points.
    #[test]
    fn explicit_formula_equals_recursion() {
        let x = [0.3, -1.0, 0.9, 2.0, 1.4];
        let v: Vec<f64> = x.iter().map(|&t| sin_d(t, 0)).collect();
        for n in 1..=x.len() {
            let a = divided_difference_explicit(&x[..n], &v[..n]).unwrap();
            let b = divided_difference(&x[..n], sin_d).unwrap();
            assert!((a - b).abs() < 1e-14, "n = {n}: {a} vs {b}");
        }
    }

    // Lemma 2.4 and 2.5: a polynomial of degree n has constant order-n divided differences
    // (its leading coefficient) and zero ones of order n + 1, also with repeated points.
    // Lemma 2.3: symmetric in the points (the explicit formula sums in the given order).
    #[test]
    fn symmetry() {
        let x = [0.3, -1.0, 0.9, 2.0];
        let perm = [2.0, 0.3, 0.9, -1.0];
        let v = |p: &[f64]| p.iter().map(|&t| sin_d(t, 0)).collect::<Vec<_>>();
        let a = divided_difference_explicit(&x, &v(&x)).unwrap();
        let b = divided_difference_explicit(&perm, &v(&perm)).unwrap();
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
        let c = divided_difference(&[1.0, 0.0, 1.0, 0.5, 0.0], sin_d).unwrap();
        let d = divided_difference(&[0.0, 0.0, 0.5, 1.0, 1.0], sin_d).unwrap();
        assert_eq!(c, d, "repeated points in any order");
    }

    #[test]
    fn polynomial_leading_coefficient() {
        // p(x) = 2x³ − x + 5
        let p = |x: f64, r: usize| match r {
            0 => 2.0 * x * x * x - x + 5.0,
            1 => 6.0 * x * x - 1.0,
            2 => 12.0 * x,
            3 => 12.0,
            _ => 0.0,
        };
        let lead = divided_difference(&[0.0, 1.0, 1.0, 3.0], p).unwrap();
        assert!((lead - 2.0).abs() < 1e-13, "leading coefficient {lead}");
        let zero = divided_difference(&[0.0, 1.0, 1.0, 1.0, 3.0], p).unwrap();
        assert!(zero.abs() < 1e-13, "order 4 of a cubic: {zero}");
    }

    // Lemma 2.8: p + 1 equal points give f^{(p)}(x)/p!; and the confluent value is the limit
    // of coalescing distinct points.
    #[test]
    fn repeated_point_is_derivative() {
        for p in 0..6 {
            let x = vec![0.7; p + 1];
            let d = divided_difference(&x, sin_d).unwrap();
            assert!((d - sin_d(0.7, p) / factorial(p)).abs() < 1e-15, "p = {p}");
        }
        let h = 1e-4;
        let near = divided_difference(&[0.7, 0.7 + h, 1.2], sin_d).unwrap();
        let conf = divided_difference(&[0.7, 0.7, 1.2], sin_d).unwrap();
        assert!((near - conf).abs() < 1e-4, "{near} vs {conf}");
    }

    // Lemma 2.9: the confluent divided difference is linear in f and its derivatives at the
    // points, with coefficients independent of f: check linearity (Lemma 2.2) with repeats.
    #[test]
    fn confluent_linearity() {
        let x = [0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
        let a = divided_difference(&x, sin_d).unwrap();
        let b = divided_difference(&x, |t, _r| t.exp()).unwrap();
        let c = divided_difference(&x, |t, r| 2.0 * sin_d(t, r) - 3.0 * t.exp()).unwrap();
        assert!((c - (2.0 * a - 3.0 * b)).abs() < 1e-12, "{c}");
    }

    // Lemmas 2.9–2.10: f(x_0^{m_0}; …; x_s^{m_s}) = Σ_i Σ_{j<m_i} α_{ij} f^{(j)}(x_i) with α
    // independent of f. The α are read off by feeding the unit data (one derivative at one point
    // equal to 1, the rest 0), then applied to two different functions.
    #[test]
    fn confluent_weights_do_not_depend_on_f() {
        let x = [0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
        let slots = [(0.0, 0), (0.0, 1), (0.5, 0), (1.0, 0), (1.0, 1), (1.0, 2)];
        let alpha: Vec<f64> = slots
            .iter()
            .map(|&(p, j)| {
                divided_difference(&x, |t, r| if t == p && r == j { 1.0 } else { 0.0 }).unwrap()
            })
            .collect();
        let exp_d = |t: f64, _r: usize| t.exp();
        for f in [&sin_d as &dyn Fn(f64, usize) -> f64, &exp_d] {
            let direct = divided_difference(&x, f).unwrap();
            let via: f64 = slots
                .iter()
                .zip(&alpha)
                .map(|(&(p, j), a)| a * f(p, j))
                .sum();
            assert!((direct - via).abs() < 1e-13, "{direct} vs {via}");
        }
    }

    // Lemma 2.7 (Leibniz): (gh)(x_0; …; x_n) = Σ_k g(x_0; …; x_k) h(x_k; …; x_n), including
    // repeated points (derivatives of the product by the Leibniz rule for derivatives).
    #[test]
    fn leibniz_rule() {
        let g = |x: f64, r: usize| sin_d(x, r);
        let h = |x: f64, _r: usize| x.exp();
        let gh = |x: f64, r: usize| {
            let mut s = 0.0;
            let mut binom = 1.0;
            for j in 0..=r {
                s += binom * g(x, j) * h(x, r - j);
                binom = binom * (r - j) as f64 / (j + 1) as f64;
            }
            s
        };
        for x in [
            vec![0.1, 0.4, 0.8, 1.3],
            vec![0.1, 0.1, 0.8, 1.3, 1.3],
            vec![0.5, 0.5, 0.5],
        ] {
            let lhs = divided_difference(&x, gh).unwrap();
            let mut rhs = 0.0;
            for k in 0..x.len() {
                rhs += divided_difference(&x[..=k], g).unwrap()
                    * divided_difference(&x[k..], h).unwrap();
            }
            assert!((lhs - rhs).abs() < 1e-12, "{x:?}: {lhs} vs {rhs}");
        }
    }

    // Theorem 4.1: g(z) = p_n(z) + (z − x_1)⋯(z − x_n) g(x_1; …; x_n; z), and p_n agrees with g
    // on x (osculation at repeated points).
    #[test]
    fn newton_form_with_remainder() {
        let x = [0.0, 0.0, 0.6, 1.1, 1.1, 1.1];
        let p = NewtonForm::new(&x, sin_d).unwrap();
        assert_eq!(p.nodes(), &x);
        assert_eq!(p.coefficients().len(), x.len());
        for k in 0..=20 {
            let z = -0.5 + 0.1 * k as f64;
            let mut pts = x.to_vec();
            pts.push(z);
            let rem: f64 = x.iter().map(|&xi| z - xi).product::<f64>()
                * divided_difference(&pts, sin_d).unwrap();
            assert!((sin_d(z, 0) - (p.eval(z) + rem)).abs() < 1e-12, "z = {z}");
        }
        // agreement: value and slope at 0, value, slope, curvature at 1.1
        let h = 1e-6;
        assert!((p.eval(0.0) - 0.0).abs() < 1e-15, "value at 0");
        assert!(
            ((p.eval(h) - p.eval(-h)) / (2.0 * h) - 1.0).abs() < 1e-8,
            "slope at 0"
        );
        assert!((p.eval(1.1) - 1.1f64.sin()).abs() < 1e-14, "value at 1.1");
        assert!((p.eval(0.6) - 0.6f64.sin()).abs() < 1e-14, "value at 0.6");
    }

    #[test]
    fn errors() {
        assert!(matches!(
            divided_difference(&[], sin_d),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            divided_difference(&[0.0, f64::NAN], sin_d),
            Err(Error::NonFinite { index: 1, .. })
        ));
        assert!(matches!(
            divided_difference_explicit(&[0.0, 1.0, 0.0], &[0.0; 3]),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            divided_difference_explicit(&[0.0, 1.0], &[0.0; 3]),
            Err(Error::LengthMismatch { .. })
        ));
        let kv = KnotVector::new(vec![0.0, 1.0, 2.0]).unwrap();
        assert!(matches!(
            bspline_divided_difference(&kv, 0, 2, 0.5),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            bspline_divided_difference(&kv, 0, 1, 2.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    #[test]
    fn truncated_power_conventions() {
        assert_eq!(truncated_power(2.0, 1.0, 4), 1.0);
        assert_eq!(truncated_power(1.0, 1.0, 2), 0.0);
        assert_eq!(truncated_power(1.5, 1.0, 1), 1.0);
        assert_eq!(truncated_power_derivative(1.0, 1.0, 1, 0, true), 1.0);
        assert_eq!(truncated_power_derivative(3.0, 1.0, 4, 2, false), 12.0);
        assert_eq!(truncated_power_derivative(3.0, 1.0, 4, 4, false), 0.0);
    }

    // Knot vectors on a coarse grid (multiples of 0.5 in [0, 4]) so that the divided difference
    // is well conditioned (Δ/h ≤ 8); multiplicities up to degree + 1.
    fn knots_strategy() -> impl Strategy<Value = (usize, Vec<f64>)> {
        (0usize..=4)
            .prop_flat_map(|p| {
                let steps = prop::collection::vec(0usize..=2, 2 * p + 1..2 * p + 8);
                (Just(p), steps)
            })
            .prop_map(|(p, steps)| {
                let mut k = vec![0.0];
                for s in steps {
                    let last = k[k.len() - 1];
                    k.push(last + 0.5 * s as f64);
                }
                (p, k)
            })
    }

    proptest! {
        #![proptest_config(crate::oracle::proptest_config(96))]

        // Foundation item 6: Cox–de Boor (fast), the lecture recursion and the divided
        // difference of truncated powers (eq. 4) agree to 1e-12, multiple knots included.
        #[test]
        fn three_bspline_evaluations_agree((p, k) in knots_strategy()) {
            let m = k.len() - 1;
            prop_assume!(k[0] < k[m]);
            let mult_ok = k.windows(p + 2).all(|w| w[0] < w[p + 1]);
            let kv = KnotVector::new(k.clone()).unwrap();
            let n_basis = m - p; // b_0 … b_{m−p−1}
            let mut ts: Vec<f64> = (0..=80).map(|j| k[0] + (k[m] - k[0]) * j as f64 / 80.0).collect();
            ts.extend_from_slice(&k);
            for &t in &ts {
                for i in 0..n_basis {
                    let dd = bspline_divided_difference(&kv, i, p, t).unwrap();
                    let rec = basis_function_recursive_oracle(&kv, i, p, t);
                    prop_assert!((dd - rec).abs() < 1e-12, "i={} p={} t={} dd={} rec={}", i, p, t, dd, rec);
                }
                // the fast kernel on the spline's domain [x_p, x_{m−p}] (right end only where it
                // is the last knot, since the fast kernel closes the domain's last span)
                let (lo, hi) = (k[p], k[m - p]);
                let in_domain = mult_ok && lo < hi && t >= lo && t <= hi && (t < hi || hi == k[m]);
                if in_domain {
                    let (span, vals) = crate::basis::basis_functions(&kv, p, t).unwrap();
                    for i in 0..n_basis {
                        let fast = if i + p >= span && i <= span { vals[i + p - span] } else { 0.0 };
                        let dd = bspline_divided_difference(&kv, i, p, t).unwrap();
                        prop_assert!((dd - fast).abs() < 1e-12, "fast: i={} p={} t={}", i, p, t);
                    }
                }
            }
        }
    }

    fn basis_function_recursive_oracle(kv: &KnotVector, i: usize, p: usize, t: f64) -> f64 {
        crate::basis::basis_function_recursive(kv, i, p, t).unwrap()
    }
}
