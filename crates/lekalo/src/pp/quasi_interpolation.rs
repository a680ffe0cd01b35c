//! The de Boor–Fix dual functionals: pp-form → B-spline conversion and quasi-interpolation
//! (document 003 §5; docs/theory/pp.md#de-boor-fix-functionals).
//!
//! For the knots `x_1 ≤ … ≤ x_{n+k}` of order `k` and a point `τ_i ∈ [x_i, x_{i+k}]`,
//! `λ_i f = Σ_{r=0}^{k−1} (−1)^{k−1−r} ψ_i^{(k−1−r)}(τ_i) f^{(r)}(τ_i)`,
//! `ψ_i(z) = (x_{i+1} − z)⋯(x_{i+k−1} − z)/(k − 1)!`, and `λ_i b_j = δ_{ij}` (de Boor–Fix). So the
//! B-spline coefficients of a spline are `c_i = λ_i f`, and for a smooth `f` the same functionals
//! give a quasi-interpolant whose coefficients depend on the choice of `τ` ([`TauRule`]).
//!
//! **One-sided derivatives.** When `τ_i` lies on a knot, the derivatives of a spline are taken
//! from the side inside the support: the left side when `τ_i = x_{i+k}` (the thesis's rule does
//! this for the last B-spline), the right side otherwise (also at `τ_i = x_i`). With the other side
//! `λ_i b_j = δ_{ij}` fails (docs/theory/pp.md#one-sided-derivatives).

use crate::curve::bspline::BSplineCurve;
use crate::error::readable;
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::points::Points;
use crate::pp::expression::Expression;
use crate::pp::ppform::{PiecewisePolynomial, PpSpace, DEFAULT_CONTINUITY_RTOL};
use crate::Arg;

/// How the point `τ_i ∈ [x_i, x_{i+k}]` of the dual functional `λ_i` is chosen.
///
/// On the thesis's practical task (f = x·cos x on [0, 3], k = 3, breakpoints
/// {0, 0.5, 0.9, 1.4, 2.1, 2.7, 3}, 61-point grid of step 0.05), the maximum errors are
/// (`tests/all/ppform.rs`):
///
/// | rule | max error |
/// |---|---|
/// | [`TauRule::FirstKnotAfter`] (stated in the thesis) | 0.0548489 (at x = 0) |
/// | [`TauRule::LeftEndOfSupport`] | **0.2048312** (at x = 2.75), the thesis's printed 0.204831 |
/// | [`TauRule::Midpoint`] | 0.0266450 |
/// | [`TauRule::Greville`] | 0.0126331 |
/// | [`TauRule::FirstIntervalMidpoint`] | 0.0317437 |
///
/// The printed figure is reproduced by `τ_i = x_i`, i.e. the thesis's rule read with `≥`
/// (`min{x_j : x_j ≥ x_i}`), or equivalently (the same figure to 1e-15) by the thesis's rule
/// with its index shifted by one, `τ_i = min{x_j : x_j > x_{i−1}}` (a 0-/1-based off-by-one). No
/// other choice searched reproduces it. Searched (all combinations): τ rules first knot after,
/// `x_i`, midpoint, Greville, `x_{i+1}`, `x_{i+k−1}`, `x_{i+k}`, middle of the inner knots and
/// the shifted-index variants; `ψ` without its index (`ψ_1` for all `i`) or with its index
/// shifted by ±1; the sign `(−1)^{k−1−r}` or the `1/(k−1)!` dropped; the step-3 typo
/// `(x_{i+k} − x_k)` scaling the B-splines; left-continuous B-splines or an open right end;
/// exact, accumulated (`z += 0.05`) or 60-point grids; non-clamped end knots
/// (`−1, −0.5, 0 … 3, 3.5, 4` and others, 0.2088 at best); the explicit sum (4) with zero factors
/// skipped at repeated knots (errors > 300). The side of the derivatives does not matter for the
/// smooth `x cos x`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TauRule {
    /// `τ_i = min{x_j : x_j > x_i}`, the rule stated in the thesis (document 003 §5.1, step 5).
    #[default]
    FirstKnotAfter,
    /// `τ_i = x_i`, the left end of the support; reproduces the thesis's printed error.
    LeftEndOfSupport,
    /// `τ_i = (x_i + x_{i+k})/2`, the middle of the support.
    Midpoint,
    /// `τ_i = (x_{i+1} + … + x_{i+k−1})/(k − 1)`, the Greville abscissa (`x_i` for `k = 1`).
    Greville,
    /// `τ_i = (x_j + x_{j+1})/2` for the first `j ≥ i` with `x_j < x_{j+1}`: the middle of the
    /// first non-empty knot interval of the support, so `τ_i` is never a knot and both sides of
    /// a spline agree there (docs/theory/pp.md#the-two-tau-rules).
    FirstIntervalMidpoint,
}

/// Where the points `τ_i` of the de Boor–Fix functionals come from: a [`TauRule`], or one value
/// per B-spline given by the caller (each in its support `[x_i, x_{i+k}]`;
/// docs/theory/pp.md#explicit-tau-values).
///
/// A [`TauRule`] converts into it, so every function taking `impl Into<Tau>` accepts a rule:
///
/// ```
/// use lekalo::{quasi_interpolate, PpSpace, Tau, TauRule};
/// let space = PpSpace::new(&[0.0, 1.0, 2.0], &[2], 3)?; // knots 0 0 0 1 2 2 2
/// let f = |x: f64, r: usize| [x.exp(), x.exp(), x.exp()][r];
/// let by_rule = quasi_interpolate(&space, TauRule::Greville, f)?;
/// let taus = TauRule::Greville.points(space.knots(), 3)?;
/// let by_values = quasi_interpolate(&space, Tau::Values(&taus), f)?;
/// assert_eq!(by_rule, by_values);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tau<'a> {
    /// `τ_i` by a rule.
    Rule(TauRule),
    /// `τ_1 … τ_n`, one per B-spline, `τ_i ∈ [x_i, x_{i+k}]`.
    Values(&'a [f64]),
}

impl From<TauRule> for Tau<'_> {
    fn from(rule: TauRule) -> Self {
        Tau::Rule(rule)
    }
}

impl<'a> From<&'a [f64]> for Tau<'a> {
    fn from(values: &'a [f64]) -> Self {
        Tau::Values(values)
    }
}

impl Tau<'_> {
    /// The points `τ_1 … τ_n` for the `n` B-splines of order `k` on `knots`: the rule's, or the
    /// given values after checking them.
    ///
    /// # Errors
    /// As [`TauRule::points`]; for [`Tau::Values`] also [`Error::LengthMismatch`] if there is not
    /// one value per B-spline, [`Error::NonFinite`] for NaN or infinity and
    /// [`Error::InvalidArgument`] for a value outside its support `[x_i, x_{i+k}]`.
    pub fn points(self, knots: &KnotVector, order: usize) -> Result<Vec<f64>> {
        let values = match self {
            Tau::Rule(rule) => return rule.points(knots, order),
            Tau::Values(v) => v,
        };
        let n = check_knots(knots, order)?;
        if values.len() != n {
            return Err(Error::LengthMismatch {
                what: "τ values (one per B-spline)".into(),
                expected: n,
                got: values.len(),
            });
        }
        let x = knots.as_slice();
        for (i, &t) in values.iter().enumerate() {
            if !t.is_finite() {
                return Err(Error::NonFinite {
                    what: "τ value (index = position in the list)".into(),
                    index: i,
                    value: t,
                });
            }
            if !(x[i]..=x[i + order]).contains(&t) {
                return Err(Error::InvalidArgument {
                    what: "τ value".into(),
                    reason: format!(
                        "τ number {} is {t}, outside the support [{}, {}] of its B-spline; each \
                         τ_i must lie in [x_i, x_(i+k)]",
                        i + 1,
                        readable(&x[i]),
                        readable(&x[i + order]),
                        t = readable(&t)
                    ),
                });
            }
        }
        Ok(values.to_vec())
    }
}

impl TauRule {
    /// `τ_i` for B-spline `i` (0-based) of order `k` on `knots`; always in `[x_i, x_{i+k}]`
    /// (clamped there against rounding, e.g. a Greville mean of equal knots).
    fn tau(self, x: &[f64], i: usize, order: usize) -> f64 {
        let tau = match self {
            TauRule::FirstKnotAfter => {
                let after = x.partition_point(|&v| v <= x[i]);
                // x_{i+k} > x_i in a valid knot vector, so the first greater knot is ≤ x_{i+k}
                x[after.min(i + order)]
            }
            TauRule::LeftEndOfSupport => x[i],
            TauRule::Midpoint => 0.5 * (x[i] + x[i + order]),
            TauRule::Greville => {
                if order == 1 {
                    x[i]
                } else {
                    x[i + 1..i + order].iter().sum::<f64>() / (order - 1) as f64
                }
            }
            TauRule::FirstIntervalMidpoint => {
                // x_i < x_{i+k} in a valid knot vector, so some interval of the support is
                // non-empty
                let j = (i..i + order)
                    .find(|&j| x[j] < x[j + 1])
                    .unwrap_or(i + order - 1);
                0.5 * (x[j] + x[j + 1])
            }
        };
        tau.clamp(x[i], x[i + order])
    }

    /// The points `τ_1 … τ_n` for the B-splines of order `k` on `knots`.
    ///
    /// ```
    /// use lekalo::{PpSpace, TauRule};
    /// let s = PpSpace::new(&[0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0], &[2; 5], 3)?;
    /// let tau = TauRule::FirstKnotAfter.points(s.knots(), 3)?;
    /// assert_eq!(tau, vec![0.5, 0.5, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0]); // the practical task
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`KnotVector::validate_for`] for degree `k − 1` and `len − k` B-splines
    /// ([`Error::Degree`] if `order == 0`).
    pub fn points(self, knots: &KnotVector, order: usize) -> Result<Vec<f64>> {
        let n = check_knots(knots, order)?;
        Ok((0..n)
            .map(|i| self.tau(knots.as_slice(), i, order))
            .collect())
    }
}

/// Validates knots for order `k`, returning the number of B-splines.
fn check_knots(knots: &KnotVector, order: usize) -> Result<usize> {
    let degree = order.checked_sub(1).ok_or(Error::Degree {
        degree: 0,
        reason: "the order k = degree + 1 must be at least 1".into(),
    })?;
    let n = knots.len().saturating_sub(order);
    knots.validate_for(degree, n)?;
    Ok(n)
}

/// The weights `w_r = (−1)^{k−1−r} ψ_i^{(k−1−r)}(τ)`, `r = 0 … k−1`, so that
/// `λ_i f = Σ_r w_r f^{(r)}(τ)`. `ψ_i` is expanded in powers of `u = z − τ`:
/// `Π_{j=1}^{k−1} ((x_{i+j} − τ) − u) = Σ_m e_m u^m`, and `ψ^{(m)}(τ) = m! e_m/(k−1)!`. O(k²).
fn dual_weights(x: &[f64], i: usize, order: usize, tau: f64, w: &mut [f64]) {
    debug_assert_eq!(w.len(), order, "weight buffer");
    let k = order;
    // e holds the product's coefficients, degree grows to k − 1
    let mut e = vec![0.0; k];
    e[0] = 1.0;
    for j in 1..k {
        let a = x[i + j] - tau;
        for m in (0..=j).rev() {
            let lower = if m > 0 { e[m - 1] } else { 0.0 };
            e[m] = a * e[m] - lower;
        }
    }
    let fact_k1: f64 = (1..k).map(|v| v as f64).product();
    for r in 0..k {
        let m = k - 1 - r;
        let m_fact: f64 = (1..=m).map(|v| v as f64).product();
        let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
        w[r] = sign * m_fact * e[m] / fact_k1;
    }
}

/// B-spline coefficients `c_i = λ_i f` on `knots` of order `k`, with `derivs(τ, from_left, out)`
/// filling `out` (`k × dim`, row `r` = `f^{(r)}(τ)`) from the given side.
fn de_boor_fix<D>(
    knots: &KnotVector,
    order: usize,
    dim: usize,
    tau: Tau<'_>,
    mut derivs: D,
) -> Result<Points>
where
    D: FnMut(f64, bool, &mut [f64]) -> Result<()>,
{
    let taus = tau.points(knots, order)?;
    let n = taus.len();
    let x = knots.as_slice();
    let mut w = vec![0.0; order];
    let mut d = vec![0.0; order * dim];
    let mut coef = vec![0.0; n * dim];
    for (i, c) in coef.chunks_exact_mut(dim).enumerate() {
        let tau = taus[i];
        dual_weights(x, i, order, tau, &mut w);
        let from_left = tau == x[i + order] && x[i] < tau;
        derivs(tau, from_left, &mut d)?;
        for (wr, row) in w.iter().zip(d.chunks_exact(dim)) {
            for (ci, v) in c.iter_mut().zip(row) {
                *ci += wr * v;
            }
        }
    }
    Ok(Points::from_raw(coef, dim))
}

impl PiecewisePolynomial {
    /// The B-spline form of `self ∈ P_{k,ξ,ν}` on the Curry–Schoenberg knots of `space`
    /// (document 003 §5.1; docs/theory/pp.md#de-boor-fix-functionals): `c_i = λ_i f` with the de
    /// Boor–Fix functionals at the points `tau` (a [`TauRule`] or explicit [`Tau::Values`]),
    /// one-sided derivatives as in the module docs. Exact for every choice (to rounding) because
    /// `f` is in the space. O(n·k·(k + dim)).
    ///
    /// ```
    /// use lekalo::{PiecewisePolynomial, PpSpace, TauRule};
    /// // x² on [0, 2] with a breakpoint at 1, as a C¹ quadratic: coefficients x_{i+1}·x_{i+2}
    /// let f = PiecewisePolynomial::new(vec![0.0, 1.0, 2.0], 3, 1, vec![0.0, 0.0, 1.0, 1.0, 2.0, 1.0])?;
    /// let space = PpSpace::new(&[0.0, 1.0, 2.0], &[2], 3)?; // knots 0 0 0 1 2 2 2
    /// let c = f.to_bspline(&space, TauRule::Midpoint)?;
    /// let want = [0.0, 0.0, 2.0, 4.0];
    /// for (got, w) in c.control_points().as_slice().iter().zip(want) {
    ///     assert!((got - w).abs() < 1e-14);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if `self` is not in the space (other breakpoints, higher
    /// order, or a continuity condition violated beyond [`DEFAULT_CONTINUITY_RTOL`]); use
    /// [`quasi_interpolate`] to approximate a function outside the space; errors of
    /// [`Tau::points`].
    pub fn to_bspline<'a>(&self, space: &PpSpace, tau: impl Into<Tau<'a>>) -> Result<BSplineCurve> {
        if !space.contains(self, DEFAULT_CONTINUITY_RTOL) {
            return Err(Error::InvalidArgument {
                what: "piecewise polynomial".into(),
                reason: format!(
                    "not in the space P_{{k,ξ,ν}} with k = {}, {} breakpoints and ν = {:?}: it \
                     needs the same breakpoints, order at most k and the continuity \
                     conditions; approximate it by quasi-interpolation instead",
                    space.order(),
                    space.breakpoints().len(),
                    space.continuity()
                ),
            });
        }
        let (k, dim) = (space.order(), self.dim());
        let coef = de_boor_fix(space.knots(), k, dim, tau.into(), |tau, from_left, out| {
            let piece = if from_left {
                self.piece_index_left(tau)?
            } else {
                self.piece_index(tau)?
            };
            for (r, row) in out.chunks_exact_mut(dim).enumerate() {
                self.piece_derivative_into(piece, tau, r, row);
            }
            Ok(())
        })?;
        BSplineCurve::from_knot_vector(k - 1, space.knots().clone(), coef)
    }
}

/// The de Boor–Fix quasi-interpolant `Σ_i (λ_i f) b_{i,k}` of a smooth scalar function on the
/// Curry–Schoenberg knots of `space` (document 003 §5.1–5.3). `f(x, r)` returns `f^{(r)}(x)` for
/// `r = 0 … k − 1`. It reproduces every `f ∈ P_{k,ξ,ν}`; for other `f` the result depends on
/// `tau`, a [`TauRule`] (see its table for the thesis's practical task) or explicit
/// [`Tau::Values`]. O(n·k²) plus `n·k` calls of `f`.
///
/// ```
/// use lekalo::{quasi_interpolate, PpSpace, TauRule};
/// // the thesis's practical task
/// let space = PpSpace::new(&[0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0], &[2; 5], 3)?;
/// let f = |x: f64, r: usize| match r {
///     0 => x * x.cos(),
///     1 => x.cos() - x * x.sin(),
///     _ => -2.0 * x.sin() - x * x.cos(),
/// };
/// let q = quasi_interpolate(&space, TauRule::FirstKnotAfter, f)?;
/// assert_eq!(q.control_points().len(), 8);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] about [`Arg::Expression`] if `f` returns NaN or infinity, naming
/// the point and the fix; errors of [`Tau::points`].
pub fn quasi_interpolate<'a, F: FnMut(f64, usize) -> f64>(
    space: &PpSpace,
    tau: impl Into<Tau<'a>>,
    mut f: F,
) -> Result<BSplineCurve> {
    let k = space.order();
    let coef = de_boor_fix(space.knots(), k, 1, tau.into(), |tau, _left, out| {
        for (r, o) in out.iter_mut().enumerate() {
            let v = f(tau, r);
            if !v.is_finite() {
                let which = if r == 0 {
                    "its value".to_string()
                } else {
                    format!("its derivative of order {r}")
                };
                return Err(needed_on(
                    space,
                    Error::InvalidArgument {
                        what: Arg::Expression.into(),
                        reason: format!(
                            "undefined at x = {}: the function returned {v} for {which}",
                            readable(&tau)
                        ),
                    },
                ));
            }
            *o = v;
        }
        Ok(())
    })?;
    BSplineCurve::from_knot_vector(k - 1, space.knots().clone(), coef)
}

/// A function and its quasi-interpolant sampled on a uniform grid (for plots such as the
/// thesis's Figure 1).
#[derive(Debug, Clone, PartialEq)]
pub struct QuasiSamples {
    /// The grid `t_j = a + j (b − a)/N`, `j = 0 … N`.
    pub t: Vec<f64>,
    /// `f(t_j)`.
    pub exact: Vec<f64>,
    /// The quasi-interpolant at `t_j`.
    pub approx: Vec<f64>,
}

impl QuasiSamples {
    /// `max_j |f(t_j) − q(t_j)|`.
    #[must_use]
    pub fn max_error(&self) -> f64 {
        self.exact
            .iter()
            .zip(&self.approx)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }
}

/// Builds the quasi-interpolant of [`quasi_interpolate`] and samples `f` and it on the uniform
/// grid of `n_intervals + 1` points over the space's domain (the thesis's task: 60 intervals
/// of 0.05 on [0, 3]). Each grid point is computed as `a + j (b − a)/N`, not by accumulation.
///
/// # Errors
/// [`Error::TooFew`] if `n_intervals == 0`; errors of [`quasi_interpolate`].
pub fn sample_quasi_interpolant<'a, F: FnMut(f64, usize) -> f64>(
    space: &PpSpace,
    tau: impl Into<Tau<'a>>,
    mut f: F,
    n_intervals: usize,
) -> Result<QuasiSamples> {
    if n_intervals == 0 {
        return Err(Error::TooFew {
            what: "grid intervals".into(),
            min: 1,
            got: 0,
        });
    }
    let q = quasi_interpolate(space, tau, &mut f)?;
    let (a, b) = q.domain();
    let t: Vec<f64> = (0..=n_intervals)
        .map(|j| {
            if j == n_intervals {
                b
            } else {
                a + (b - a) * j as f64 / n_intervals as f64
            }
        })
        .collect();
    let exact = t.iter().map(|&x| f(x, 0)).collect();
    let mut approx = vec![0.0; t.len()];
    q.eval_batch(&t, &mut approx)?;
    Ok(QuasiSamples { t, exact, approx })
}

/// A typed function's derivatives as the callback of [`quasi_interpolate`]: `f^(r)(x)` from one
/// Taylor expansion per point ([`Expression::derivatives`] up to `order − 1`, kept while `x`
/// stays the same), the first error kept for the caller and NaN returned in its place (which
/// stops the construction).
struct ExpressionDerivatives<'e> {
    f: &'e Expression,
    order: usize,
    at: f64,
    values: Vec<f64>,
    failure: Option<Error>,
}

impl ExpressionDerivatives<'_> {
    fn value(&mut self, x: f64, r: usize) -> f64 {
        if self.at.to_bits() != x.to_bits() || self.values.len() <= r {
            match self.f.derivatives(x, self.order.max(r + 1) - 1) {
                Ok(v) => {
                    self.at = x;
                    self.values = v;
                }
                Err(e) => {
                    self.failure.get_or_insert(e);
                    return f64::NAN;
                }
            }
        }
        self.values[r]
    }
}

/// [`quasi_interpolate`] of a typed function ([`Expression`], e.g. `x*cos(x)`), its derivatives
/// by Taylor arithmetic (`docs/theory/pp.md`).
///
/// ```
/// use lekalo::{quasi_interpolate_expression, Expression, PpSpace, TauRule};
/// let space = PpSpace::new(&[0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0], &[2; 5], 3)?;
/// let f = Expression::parse("x*cos(x)")?;
/// let q = quasi_interpolate_expression(&space, TauRule::FirstKnotAfter, &f)?;
/// assert_eq!(q.control_points().len(), 8);
/// let undefined = Expression::parse("ln(x - 5)")?; // no logarithm of a negative number
/// assert!(quasi_interpolate_expression(&space, TauRule::FirstKnotAfter, &undefined).is_err());
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// The expression's first error where it is undefined (a pole, a logarithm of a non-positive
/// number); errors of [`quasi_interpolate`].
pub fn quasi_interpolate_expression<'a>(
    space: &PpSpace,
    tau: impl Into<Tau<'a>>,
    f: &Expression,
) -> Result<BSplineCurve> {
    let mut d = ExpressionDerivatives {
        f,
        order: space.order(),
        at: f64::NAN,
        values: Vec::new(),
        failure: None,
    };
    let q = quasi_interpolate(space, tau, |x, r| d.value(x, r));
    match d.failure {
        Some(e) => Err(needed_on(space, e)),
        None => q,
    }
}

/// [`sample_quasi_interpolant`] of a typed function ([`Expression`]).
///
/// # Errors
/// As [`quasi_interpolate_expression`]; [`Error::TooFew`] if `n_intervals == 0`.
pub fn sample_quasi_interpolant_expression<'a>(
    space: &PpSpace,
    tau: impl Into<Tau<'a>>,
    f: &Expression,
    n_intervals: usize,
) -> Result<QuasiSamples> {
    let mut d = ExpressionDerivatives {
        f,
        order: space.order(),
        at: f64::NAN,
        values: Vec::new(),
        failure: None,
    };
    let s = sample_quasi_interpolant(space, tau, |x, r| d.value(x, r), n_intervals);
    match d.failure {
        Some(e) => Err(needed_on(space, e)),
        None => s,
    }
}

/// The expression's refusal at a point (`undefined at x = 0: ln of 0 …`) with what
/// quasi-interpolation needs of `f`, and the fix: `f` and its first `k − 1` derivatives on the
/// whole breakpoint range, where the `τ_i` and the sampling grid lie.
fn needed_on(space: &PpSpace, e: Error) -> Error {
    match e {
        Error::InvalidArgument { what, reason } if what.arg() == Some(Arg::Expression) => {
            let (a, b) = match space.breakpoints() {
                [first, .., last] => (*first, *last),
                _ => (f64::NAN, f64::NAN),
            };
            let k = space.order();
            let at_tau = if k > 1 {
                format!(
                    "f and its derivatives up to order {} at the points τ",
                    k - 1
                )
            } else {
                "f at the points τ".to_string()
            };
            Error::InvalidArgument {
                what,
                reason: format!(
                    "{reason}; quasi-interpolation evaluates f on the whole range of the \
                     breakpoints, [{a}, {b}] ({at_tau}, f where the error is measured): choose \
                     breakpoints where f is defined, or another f",
                    a = readable(&a),
                    b = readable(&b),
                ),
            }
        }
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xcosx(x: f64, r: usize) -> f64 {
        let (s, c) = x.sin_cos();
        match r {
            0 => x * c,
            1 => c - x * s,
            2 => -2.0 * s - x * c,
            _ => -3.0 * c + x * s,
        }
    }

    fn thesis_space() -> PpSpace {
        PpSpace::new(&[0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0], &[2; 5], 3).unwrap()
    }

    // ln x with a breakpoint at 0: the refusal names x = 0, why, the range f is needed on and
    // the fix, about the expression; the default rule's τ avoid 0, the error's grid does not
    #[test]
    fn a_function_undefined_on_the_breakpoints_names_where_and_the_fix() {
        let f = Expression::parse("log(x)").unwrap();
        let space = thesis_space();
        assert!(quasi_interpolate_expression(&space, TauRule::FirstKnotAfter, &f).is_ok());
        for e in [
            quasi_interpolate_expression(&space, TauRule::LeftEndOfSupport, &f).unwrap_err(),
            sample_quasi_interpolant_expression(&space, TauRule::FirstKnotAfter, &f, 60)
                .unwrap_err(),
        ] {
            assert_eq!(e.arg(), Some(Arg::Expression));
            assert_eq!(
                e.to_string(),
                "invalid expression: undefined at x = 0: ln of 0 (a logarithm needs a positive \
                 argument); quasi-interpolation evaluates f on the whole range of the \
                 breakpoints, [0, 3] (f and its derivatives up to order 2 at the points τ, f \
                 where the error is measured): choose breakpoints where f is defined, or \
                 another f"
            );
        }
        let inside = PpSpace::new(&[0.5, 1.0, 2.0, 3.0], &[2; 2], 3).unwrap();
        assert!(quasi_interpolate_expression(&inside, TauRule::FirstKnotAfter, &f).is_ok());
    }

    // For k = 3, λ_i(x²) = x_{i+1} x_{i+2} for every τ (docs/theory/pp.md#de-boor-fix-functionals).
    #[test]
    fn dual_weights_quadratic() {
        let x = [0.0, 0.2, 0.7, 1.5, 2.0];
        let mut w = [0.0; 3];
        for tau in [0.0, 0.3, 1.0, 1.5] {
            dual_weights(&x, 0, 3, tau, &mut w);
            let lam = w[0] * tau * tau + w[1] * 2.0 * tau + w[2] * 2.0;
            assert!((lam - 0.2 * 0.7).abs() < 1e-15, "τ = {tau}");
            // k = 3: w = (1, (x1 + x2)/2 − τ, (x1 − τ)(x2 − τ)/2)
            assert!((w[1] - (0.45 - tau)).abs() < 1e-15, "w1");
            assert!((w[2] - (0.2 - tau) * (0.7 - tau) / 2.0).abs() < 1e-15, "w2");
        }
    }

    // The thesis's printed 0.204831 is also reproduced by the stated rule with its index shifted
    // by one (τ_i = min{x_j : x_j > x_{i−1}}, τ_1 = x_1): the same figure as τ_i = x_i.
    #[test]
    fn printed_error_by_shifted_index() {
        let space = thesis_space();
        let x = space.knots().as_slice();
        let taus: Vec<f64> = (0..8)
            .map(|i| {
                if i == 0 {
                    x[0]
                } else {
                    x[x.partition_point(|&v| v <= x[i - 1])]
                }
            })
            .collect();
        assert_eq!(taus, [0.0, 0.5, 0.5, 0.5, 0.9, 1.4, 2.1, 2.7]);
        let mut coef = vec![0.0; 8];
        let mut w = [0.0; 3];
        for (i, c) in coef.iter_mut().enumerate() {
            dual_weights(x, i, 3, taus[i], &mut w);
            *c = (0..3).map(|r| w[r] * xcosx(taus[i], r)).sum();
        }
        let q = BSplineCurve::from_knot_vector(
            2,
            space.knots().clone(),
            Points::from_flat(1, coef).unwrap(),
        )
        .unwrap();
        let err = (0..=60)
            .map(|j| {
                let t = 3.0 * j as f64 / 60.0;
                (q.eval(t).unwrap()[0] - xcosx(t, 0)).abs()
            })
            .fold(0.0, f64::max);
        assert!((err - 0.204_831_219_164_730_4).abs() < 1e-12, "{err}");
    }

    // λ_i(b_j) = δ_ij for the practical task's knots with every rule
    // (docs/theory/pp.md#one-sided-derivatives). With the thesis's rule τ_1 = 0.5 = x_4 is the
    // right end of b_1's support: there the left-hand derivatives are needed; the right-hand ones
    // would give λ_1(b_1) = 0.
    #[test]
    fn duality_and_side() {
        let space = thesis_space();
        for rule in [
            TauRule::FirstKnotAfter,
            TauRule::LeftEndOfSupport,
            TauRule::Midpoint,
            TauRule::Greville,
            TauRule::FirstIntervalMidpoint,
        ] {
            for j in 0..8 {
                let mut unit = vec![0.0; 8];
                unit[j] = 1.0;
                let b = BSplineCurve::from_knot_vector(
                    2,
                    space.knots().clone(),
                    Points::from_flat(1, unit.clone()).unwrap(),
                )
                .unwrap();
                let pp = PiecewisePolynomial::from_bspline(&b).unwrap();
                let c = pp.to_bspline(&space, rule).unwrap();
                for (got, want) in c.control_points().as_slice().iter().zip(&unit) {
                    assert!((got - want).abs() < 1e-13, "{rule:?} j = {j}");
                }
            }
        }
        // wrong side at τ_1 = 0.5 (= x_4, the right end of b_1's support): right-hand derivatives
        // of b_1 there are all zero, so λ_1(b_1) would be 0 instead of 1
        let x = space.knots().as_slice();
        let mut w = [0.0; 3];
        dual_weights(x, 0, 3, 0.5, &mut w);
        let b1 = BSplineCurve::from_knot_vector(
            2,
            space.knots().clone(),
            Points::from_flat(1, vec![1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap(),
        )
        .unwrap();
        let pp = PiecewisePolynomial::from_bspline(&b1).unwrap();
        let right = pp.eval_derivatives(0.5, 2).unwrap();
        let left = pp.eval_derivatives_left(0.5, 2).unwrap();
        let lam = |d: &Points| (0..3).map(|r| w[r] * d.point(r)[0]).sum::<f64>();
        assert!((lam(&left) - 1.0).abs() < 1e-14, "left side gives 1");
        assert!(lam(&right).abs() < 1e-14, "right side gives 0");
    }

    #[test]
    fn errors() {
        let space = thesis_space();
        assert!(matches!(
            sample_quasi_interpolant(&space, TauRule::Midpoint, xcosx, 0),
            Err(Error::TooFew { .. })
        ));
        // a function that is not finite at a τ: where, and the fix, about the function
        let e = quasi_interpolate(&space, TauRule::LeftEndOfSupport, |x: f64, r| {
            if r == 0 {
                x.ln()
            } else {
                1.0 / x
            }
        })
        .unwrap_err();
        assert_eq!(e.arg(), Some(Arg::Expression));
        assert!(
            e.to_string().starts_with(
                "invalid expression: undefined at x = 0: the function returned -inf for its \
                 value; quasi-interpolation evaluates f on the whole range of the breakpoints, \
                 [0, 3]"
            ),
            "{e}"
        );
        // a pp with a kink is not in the C¹ space
        let kink = PiecewisePolynomial::new(
            vec![0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0],
            2,
            1,
            vec![0.0, 1.0, 0.5, 1.0, 0.9, 1.0, 1.4, 1.0, 2.1, -1.0, 1.5, 1.0],
        )
        .unwrap();
        assert!(matches!(
            kink.to_bspline(&space, TauRule::Midpoint),
            Err(Error::InvalidArgument { .. })
        ));
        let kv = KnotVector::new(vec![0.0, 1.0]).unwrap();
        assert!(matches!(
            TauRule::Midpoint.points(&kv, 0),
            Err(Error::Degree { .. })
        ));
        // explicit τ: one per B-spline, finite, inside its support
        let f = |x: f64, _r: usize| x;
        let seven = [0.5; 7];
        assert!(matches!(
            quasi_interpolate(&space, Tau::Values(&seven), f),
            Err(Error::LengthMismatch {
                expected: 8,
                got: 7,
                ..
            })
        ));
        let mut taus = TauRule::Greville.points(space.knots(), 3).unwrap();
        taus[3] = f64::NAN;
        assert!(matches!(
            quasi_interpolate(&space, Tau::Values(&taus), f),
            Err(Error::NonFinite { index: 3, .. })
        ));
        // b_4's support is [x_3, x_6] = [0.5, 2.1]
        taus[3] = 2.2;
        let e = quasi_interpolate(&space, Tau::Values(&taus), f).unwrap_err();
        assert!(e.to_string().contains("τ number 4 is 2.2"), "{e}");
        taus[3] = 2.1; // the end of the support is allowed
        assert!(
            quasi_interpolate(&space, Tau::Values(&taus), f).is_ok(),
            "τ on x_(i+k)"
        );
    }

    // The middle of the first non-empty interval: for the practical task's clamped knots the
    // first three B-splines share the first interval (0, 0.5), and τ is never a knot.
    #[test]
    fn first_interval_midpoint_points() {
        let space = thesis_space();
        let tau = TauRule::FirstIntervalMidpoint
            .points(space.knots(), 3)
            .unwrap();
        // first non-empty intervals: (0, 0.5) three times, then (x_i, x_{i+1})
        let mid = |a: f64, b: f64| 0.5 * (a + b);
        let want = [
            mid(0.0, 0.5),
            mid(0.0, 0.5),
            mid(0.0, 0.5),
            mid(0.5, 0.9),
            mid(0.9, 1.4),
            mid(1.4, 2.1),
            mid(2.1, 2.7),
            mid(2.7, 3.0),
        ];
        assert_eq!(tau, want);
        let x = space.knots().as_slice();
        assert!(tau.iter().all(|t| !x.contains(t)), "no τ on a knot");
    }

    // Explicit values equal to a rule's points give that rule's coefficients bit for bit, for
    // the exact conversion and for quasi-interpolation.
    #[test]
    fn explicit_values_match_rule() {
        let space = thesis_space();
        for rule in [TauRule::FirstKnotAfter, TauRule::Midpoint] {
            let taus = rule.points(space.knots(), 3).unwrap();
            let a = quasi_interpolate(&space, rule, xcosx).unwrap();
            let b = quasi_interpolate(&space, taus.as_slice(), xcosx).unwrap();
            assert_eq!(a, b, "{rule:?}");
        }
    }
}
