//! Knot vectors: validation, construction rules, multiplicities and span search.
//!
//! Conventions, stated once:
//! - A knot vector `t_0 ≤ t_1 ≤ … ≤ t_m` is stored as given; lekalo never sorts or alters it.
//! - For degree `p` and `n + 1` control points, `m = n + p + 1` and the **domain** is
//!   `[t_p, t_{n+1}]`.
//! - Spans are half-open, `[t_i, t_{i+1})`, except that the right end of the domain belongs to the
//!   last non-empty span, so that curves evaluate at their end point.
//! - A knot may be repeated at most `p + 1` times.
//!
//! Construction rules follow document 000 (docs/theory/interpolation.md#averaged-knots): clamped
//! uniform (eq. 2), averaging (eq. 3), averaging with two extra knots for end derivatives (eq. 4),
//! knots at the parameters (eq. 8); and the Curry–Schoenberg rule of document 003 (Theorem 4.5,
//! docs/theory/pp.md#curry-schoenberg-knots).
//!
//! | file | computes |
//! |---|---|
//! | `knots.rs` (this file) | [`KnotVector`]: validation, construction rules, multiplicities |
//! | `knots/span.rs` | span search, P&T Algorithm A2.1, and the batch [`SpanCursor`] |
//! | `knots/breakpoints.rs` | pp-form breakpoints (document 003 §4): validation, SciPy's sortedness test |

mod breakpoints;
mod span;

pub use breakpoints::breakpoints_sorted;
pub(crate) use breakpoints::check_breakpoints;
pub use span::SpanCursor;
pub(crate) use span::{span_by, span_in};

use crate::error::readable;
use crate::{Arg, What};
use serde::{Deserialize, Serialize};

use crate::error::{check_degree_bound, check_finite, Error, Result, MAX_SCALARS};

/// A validated, non-decreasing sequence of finite knots with a non-empty range.
///
/// ```
/// use lekalo::KnotVector;
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
/// assert_eq!(kv.multiplicity(0.0), 3);
/// assert_eq!(kv.find_span(2, 0.75).unwrap(), 3);
/// assert_eq!(kv.find_span(2, 1.0).unwrap(), 3); // the right end belongs to the last span
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<f64>", into = "Vec<f64>")]
pub struct KnotVector {
    knots: Vec<f64>,
}

impl TryFrom<Vec<f64>> for KnotVector {
    type Error = Error;
    fn try_from(v: Vec<f64>) -> Result<Self> {
        KnotVector::new(v)
    }
}

impl From<KnotVector> for Vec<f64> {
    fn from(k: KnotVector) -> Self {
        k.knots
    }
}

impl KnotVector {
    /// A knot vector from values given in non-decreasing order.
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than 2 knots; [`Error::NonFinite`];
    /// [`Error::KnotsNotSorted`] at the first decrease; [`Error::EmptyDomain`] if all knots are
    /// equal; [`Error::InvalidArgument`] if `t_last − t_0` overflows; [`Error::TooLarge`].
    pub fn new(knots: Vec<f64>) -> Result<Self> {
        Self::check_values(&knots)?;
        Ok(KnotVector { knots })
    }

    /// The checks of [`KnotVector::new`] on knots read in place (nothing copied).
    ///
    /// # Errors
    /// As [`KnotVector::new`].
    pub(crate) fn check_values(knots: &[f64]) -> Result<()> {
        if knots.len() < 2 {
            return Err(Error::TooFew {
                what: Arg::Knots.into(),
                min: 2,
                got: knots.len(),
            });
        }
        if knots.len() > MAX_SCALARS {
            return Err(Error::TooLarge {
                what: Arg::Knots.into(),
                size: knots.len(),
                max: MAX_SCALARS,
            });
        }
        check_finite(Arg::Knots, knots)?;
        // one branch-free pass (vectorised): every gap is 0 or at least the smallest normal
        // number (which implies sorted); the first offending knot searched only on failure
        let gaps_ok = knots.iter().zip(&knots[1..]).fold(true, |ok, (a, b)| {
            let gap = b - a;
            ok & ((gap == 0.0) | (gap >= f64::MIN_POSITIVE))
        });
        if !gaps_ok {
            for i in 1..knots.len() {
                if knots[i] < knots[i - 1] {
                    return Err(Error::KnotsNotSorted {
                        index: i,
                        value: knots[i],
                        previous: knots[i - 1],
                    });
                }
                check_gap(Arg::Knots, knots[i - 1], knots[i])?;
            }
        }
        let (min, max) = (knots[0], knots[knots.len() - 1]);
        if min >= max {
            return Err(Error::EmptyDomain { min, max });
        }
        check_width(Arg::Knots, min, max)?;
        Ok(())
    }

    /// Trusted constructor for knots built by this crate (debug-checked).
    pub(crate) fn from_raw(knots: Vec<f64>) -> Self {
        debug_assert!(
            knots.len() >= 2 && knots.windows(2).all(|w| w[0] <= w[1]),
            "raw knots must be sorted"
        );
        KnotVector { knots }
    }

    /// Checks that this knot vector suits a spline of `degree` with `n_ctrl` control points:
    /// `len == n_ctrl + degree + 1`, `n_ctrl ≥ degree + 1`, multiplicities ≤ `degree + 1`, and a
    /// non-empty domain `[t_p, t_{n+1}]`.
    ///
    /// # Errors
    /// [`Error::Degree`], [`Error::LengthMismatch`], [`Error::KnotMultiplicity`],
    /// [`Error::EmptyDomain`].
    pub fn validate_for(&self, degree: usize, n_ctrl: usize) -> Result<()> {
        if n_ctrl <= degree {
            return Err(too_few_for_degree(n_ctrl, degree));
        }
        // n_ctrl > degree, so only the sum can overflow (and then cannot match any length)
        let expected = n_ctrl.saturating_add(degree).saturating_add(1);
        if self.knots.len() != expected {
            return Err(Error::LengthMismatch {
                what: What::of(Arg::Knots, "knots (control points + degree + 1)"),
                expected,
                got: self.knots.len(),
            });
        }
        let max = degree + 1;
        // the runs of equal knots, without allocating (this runs at every construction)
        for run in self.knots.chunk_by(|a, b| a == b) {
            if run.len() > max {
                return Err(Error::KnotMultiplicity {
                    knot: run[0],
                    multiplicity: run.len(),
                    max,
                });
            }
        }
        let (min, max) = self.domain(degree);
        if min >= max {
            return Err(Error::EmptyDomain { min, max });
        }
        Ok(())
    }

    /// Clamped knots with uniformly spaced interior knots on `[0, 1]`, document 000 eq. (2)
    /// (P&T eq. 9.7): `t_0 = … = t_p = 0`, `t_{j+p} = j / (n − p + 1)`, `t_{n+1} = … = 1`.
    ///
    /// ```
    /// use lekalo::KnotVector;
    /// let kv = KnotVector::clamped_uniform(2, 5).unwrap();
    /// assert_eq!(kv.as_slice(), &[0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]);
    /// ```
    ///
    /// # Errors
    /// [`Error::Degree`] if `n_ctrl < degree + 1`; [`Error::TooLarge`].
    pub fn clamped_uniform(degree: usize, n_ctrl: usize) -> Result<Self> {
        if n_ctrl <= degree {
            return Err(too_few_for_degree(n_ctrl, degree));
        }
        check_degree_bound(degree)?;
        check_size(n_ctrl.saturating_add(degree + 1))?;
        let n = n_ctrl - 1;
        let pieces = n - degree + 1;
        let mut knots = Vec::with_capacity(n_ctrl + degree + 1);
        knots.extend(std::iter::repeat_n(0.0, degree + 1));
        knots.extend((1..pieces).map(|j| j as f64 / pieces as f64));
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        Ok(KnotVector::from_raw(knots))
    }

    /// The clamped knots `[0]·(p+1) ++ [1]·(p+1)` of a single Bezier segment of degree `p`
    /// (document 002: the Bernstein polynomials of degree `p` are the B-splines on these knots).
    ///
    /// ```
    /// use lekalo::KnotVector;
    /// assert_eq!(KnotVector::clamped_bezier(2).as_slice(), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    /// ```
    #[must_use]
    pub fn clamped_bezier(degree: usize) -> Self {
        let mut knots = vec![0.0; degree + 1];
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        KnotVector::from_raw(knots)
    }

    /// Knots by averaging the parameters, document 000 eq. (3) (P&T eq. 9.8): for parameters
    /// `t̄_0 … t̄_n` and degree `p`, `p + 1` copies of `t̄_0`, then
    /// `t_{j+p} = (1/p) Σ_{i=j}^{j+p−1} t̄_i` for `j = 1 … n − p`, then `p + 1` copies of `t̄_n`.
    /// With these knots the interpolation matrix is banded and totally positive.
    ///
    /// ```
    /// use lekalo::KnotVector;
    /// // chord-length parameters of P&T Example 9.1
    /// let t = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
    /// let kv = KnotVector::averaged(&t, 3).unwrap();
    /// assert!((kv.as_slice()[4] - 28.0 / 51.0).abs() < 1e-15);
    /// ```
    ///
    /// # Errors
    /// [`Error::Degree`] if `degree == 0` or there are fewer than `degree + 1` parameters;
    /// parameter errors as [`check_parameters`].
    pub fn averaged(params: &[f64], degree: usize) -> Result<Self> {
        check_parameters(params)?;
        check_interpolation_degree(degree, params.len(), params.len())?;
        let n = params.len() - 1;
        let mut knots = Vec::with_capacity(n + degree + 2);
        knots.extend(std::iter::repeat_n(params[0], degree + 1));
        for j in 1..=n - degree {
            knots.push(average(&params[j..j + degree]));
        }
        knots.extend(std::iter::repeat_n(params[n], degree + 1));
        Ok(KnotVector::from_raw(knots))
    }

    /// Knots for interpolation with prescribed end derivatives, document 000 eq. (4)
    /// (P&T eq. 9.22): `p + 1` copies of `t̄_0`, then `t_{j+p+1} = (1/p) Σ_{i=j}^{j+p−1} t̄_i` for
    /// `j = 0 … n − p + 1`, then `p + 1` copies of `t̄_n`; `n + p + 4` knots for `n + 3` control
    /// points.
    ///
    /// # Errors
    /// [`Error::Degree`] if `degree == 0` or there are fewer than `degree` parameters;
    /// parameter errors as [`check_parameters`].
    pub fn averaged_with_end_derivatives(params: &[f64], degree: usize) -> Result<Self> {
        check_parameters(params)?;
        check_interpolation_degree(degree, params.len() + 1, params.len() + 2)?;
        let n = params.len() - 1;
        let mut knots = Vec::with_capacity(n + degree + 4);
        knots.extend(std::iter::repeat_n(params[0], degree + 1));
        // n − p + 2 interior knots; none when n + 2 = p (checked above: n + 2 ≥ p)
        for j in 0..(n + 2 - degree) {
            knots.push(average(&params[j..j + degree]));
        }
        knots.extend(std::iter::repeat_n(params[n], degree + 1));
        Ok(KnotVector::from_raw(knots))
    }

    /// Knots equal to the parameters, document 000 eq. (8) (P&T eq. 9.17) generalised to any
    /// degree: `p + 1` copies of `t̄_0`, the interior parameters `t̄_1 … t̄_{n−1}`, `p + 1` copies
    /// of `t̄_n`. For `p = 3` this gives the `n + 7` knots and `n + 3` control points of the C²
    /// cubic with end conditions (§3–4).
    ///
    /// # Errors
    /// [`Error::Degree`] if `degree == 0`; parameter errors as [`check_parameters`].
    pub fn from_parameters(params: &[f64], degree: usize) -> Result<Self> {
        check_parameters(params)?;
        if degree == 0 {
            return Err(Error::Degree {
                degree,
                reason: "knots at the parameters need degree ≥ 1".into(),
            });
        }
        check_degree_bound(degree)?;
        let n = params.len() - 1;
        let mut knots = Vec::with_capacity(n + 2 * degree + 1);
        knots.extend(std::iter::repeat_n(params[0], degree + 1));
        knots.extend_from_slice(&params[1..n]);
        knots.extend(std::iter::repeat_n(params[n], degree + 1));
        Ok(KnotVector::from_raw(knots))
    }

    /// Knots by the Curry–Schoenberg rule (document 003, Theorem 4.5;
    /// docs/theory/pp.md#curry-schoenberg-knots): for strictly increasing breakpoints `ξ_1 < … <
    /// ξ_{l+1}`, continuity conditions `ν_2 … ν_l` (the number of derivatives, counting the value,
    /// that are continuous at each interior breakpoint; `0 ≤ ν_i ≤ k`) and order `k` (degree `k −
    /// 1`), the knots are `k` copies of `ξ_1`, then `ξ_i` repeated `k − ν_i` times, then `k` copies
    /// of `ξ_{l+1}`. The B-splines of order `k` on these knots are a basis of `P_{k,ξ,ν}` on `[ξ_1,
    /// ξ_{l+1}]`, of dimension `n = k + Σ (k − ν_i)`.
    ///
    /// The end knots are chosen clamped (`x_1 = … = x_k = ξ_1`, `x_{n+1} = … = x_{n+k} = ξ_{l+1}`),
    /// as in the thesis's practical task; any choice outside the interval would also do.
    ///
    /// ```
    /// use lekalo::KnotVector;
    /// // the thesis's practical task: k = 3, C¹ quadratics (ν = 2) on 7 breakpoints
    /// let xi = [0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0];
    /// let kv = KnotVector::from_breakpoints(&xi, &[2; 5], 3).unwrap();
    /// assert_eq!(kv.as_slice(), &[0.0, 0.0, 0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0, 3.0, 3.0]);
    /// ```
    ///
    /// # Errors
    /// [`Error::Degree`] if `order == 0`; [`Error::TooFew`] for fewer than two breakpoints;
    /// [`Error::LengthMismatch`] if `continuity.len() != breakpoints.len() − 2`;
    /// [`Error::InvalidArgument`] if some `ν_i > k` or breakpoints are not strictly increasing;
    /// [`Error::NonFinite`].
    pub fn from_breakpoints(
        breakpoints: &[f64],
        continuity: &[usize],
        order: usize,
    ) -> Result<Self> {
        if order == 0 {
            return Err(Error::Degree {
                degree: 0,
                reason: "the order k = degree + 1 must be at least 1".into(),
            });
        }
        check_degree_bound(order - 1)?;
        check_breakpoints(breakpoints)?;
        let interior = breakpoints.len() - 2;
        if continuity.len() != interior {
            return Err(Error::LengthMismatch {
                what: What::of(
                    Arg::ContinuityConditions,
                    "continuity conditions (one per interior breakpoint)",
                ),
                expected: interior,
                got: continuity.len(),
            });
        }
        if let Some(i) = continuity.iter().position(|&nu| nu > order) {
            return Err(Error::InvalidArgument {
                what: Arg::ContinuityConditions.into(),
                reason: format!(
                    "ν at breakpoint {} is {}, more than the order {order}",
                    i + 1,
                    continuity[i]
                ),
            });
        }
        let total: usize = 2 * order + continuity.iter().map(|nu| order - nu).sum::<usize>();
        check_size(total)?;
        let mut knots = Vec::with_capacity(total);
        knots.extend(std::iter::repeat_n(breakpoints[0], order));
        for (xi, nu) in breakpoints[1..=interior].iter().zip(continuity) {
            knots.extend(std::iter::repeat_n(*xi, order - nu));
        }
        knots.extend(std::iter::repeat_n(breakpoints[interior + 1], order));
        Ok(KnotVector::from_raw(knots))
    }

    /// The knots.
    #[must_use]
    pub fn as_slice(&self) -> &[f64] {
        &self.knots
    }

    /// Number of knots.
    #[must_use]
    pub fn len(&self) -> usize {
        self.knots.len()
    }

    /// Always false: a knot vector has at least two knots.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.knots.is_empty()
    }

    /// The knots as an owned vector.
    #[must_use]
    pub fn into_vec(self) -> Vec<f64> {
        self.knots
    }

    /// Domain `[t_p, t_{n+1}]` of a spline of `degree` on these knots.
    ///
    /// The caller guarantees `len ≥ 2·degree + 2` (true after [`KnotVector::validate_for`]).
    #[must_use]
    pub fn domain(&self, degree: usize) -> (f64, f64) {
        (
            self.knots[degree],
            self.knots[self.knots.len() - degree - 1],
        )
    }

    /// How many times `t` occurs (exact comparison).
    #[must_use]
    pub fn multiplicity(&self, t: f64) -> usize {
        let lo = self.knots.partition_point(|&k| k < t);
        let hi = self.knots.partition_point(|&k| k <= t);
        hi - lo
    }

    /// Distinct knots with their multiplicities, in increasing order.
    #[must_use]
    pub fn distinct(&self) -> Vec<(f64, usize)> {
        let mut out: Vec<(f64, usize)> = Vec::new();
        for &k in &self.knots {
            match out.last_mut() {
                Some((v, m)) if *v == k => *m += 1,
                _ => out.push((k, 1)),
            }
        }
        out
    }

    /// True if the first and last `degree + 1` knots are equal (the curve interpolates its end
    /// control points).
    #[must_use]
    pub fn is_clamped(&self, degree: usize) -> bool {
        let m = self.knots.len();
        m / 2 > degree // m ≥ 2·degree + 2, without overflow
            && self.knots[..=degree].iter().all(|&k| k == self.knots[0])
            && self.knots[m - degree - 1..]
                .iter()
                .all(|&k| k == self.knots[m - 1])
    }
}

/// `n` values evenly spaced from `a` to `b`, both ends exact (`n = 1` gives `[a]`, `n = 0`
/// nothing): `a + (b − a)·k/(n − 1)` for `k < n − 1`, and `b` itself last, so that sampling a
/// curve's domain never steps outside it by rounding.
///
/// ```
/// assert_eq!(lekalo::uniform_parameters(1.0, 2.0, 3), vec![1.0, 1.5, 2.0]);
/// ```
#[must_use]
pub fn uniform_parameters(a: f64, b: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![a],
        _ => (0..n)
            .map(|k| {
                if k == n - 1 {
                    b
                } else {
                    a + (b - a) * (k as f64 / (n - 1) as f64)
                }
            })
            .collect(),
    }
}

/// Checks parameters for the knot constructors: at least two, finite, non-decreasing, with
/// `t̄_0 < t̄_n`.
///
/// # Errors
/// [`Error::TooFew`], [`Error::NonFinite`], [`Error::NotIncreasing`] (naming the parameter
/// index), [`Error::EmptyDomain`]; [`Error::InvalidArgument`] if `t̄_n − t̄_0` overflows.
pub fn check_parameters(params: &[f64]) -> Result<()> {
    if params.len() < 2 {
        return Err(Error::TooFew {
            what: "parameters".into(),
            min: 2,
            got: params.len(),
        });
    }
    check_size(params.len())?;
    check_finite("parameters", params)?;
    for i in 1..params.len() {
        if params[i] < params[i - 1] {
            return Err(Error::NotIncreasing {
                what: "parameters".into(),
                index: i,
                value: params[i],
                previous: params[i - 1],
            });
        }
    }
    let (min, max) = (params[0], params[params.len() - 1]);
    if min >= max {
        return Err(Error::EmptyDomain { min, max });
    }
    check_width("parameters", min, max)
}

/// Every basis function divides by knot differences: the width `max − min` must be finite.
///
/// # Errors
/// [`Error::InvalidArgument`] naming `what` if `max − min` overflows.
/// Refuses two distinct knots `a < b` closer than the smallest normal number
/// (`f64::MIN_POSITIVE`, about 2.2e-308): in a span that narrow Cox–de Boor's ratios
/// `N / (t_{i+j} − t_i)` (P&T Algorithm A2.2) overflow, and the basis would be `∞ · 0 = NaN`.
/// Equal knots (a multiple knot) and every normal gap pass.
///
/// # Errors
/// [`Error::InvalidArgument`] naming the two knots and the fix.
pub(crate) fn check_gap(what: impl Into<What>, a: f64, b: f64) -> Result<()> {
    let gap = b - a;
    if gap != 0.0 && gap.abs() < f64::MIN_POSITIVE {
        return Err(Error::InvalidArgument {
            what: what.into(),
            reason: format!(
                "knots {a} and {b} differ by {gap:e}, less than the smallest normal number \
                 {min:e}, so the span between them cannot be evaluated; make them equal or \
                 move them at least {min:e} apart",
                a = readable(&a),
                b = readable(&b),
                min = f64::MIN_POSITIVE
            ),
        });
    }
    Ok(())
}

/// [`check_gap`] for a knot `t` about to be inserted into the sorted `knots`: against its
/// neighbours on both sides.
///
/// # Errors
/// As [`check_gap`], with [`Arg::Knot`].
pub(crate) fn check_inserted_gap(knots: &[f64], t: f64) -> Result<()> {
    let i = knots.partition_point(|&x| x < t);
    if i > 0 {
        check_gap(Arg::Knot, knots[i - 1], t)?;
    }
    if let Some(&b) = knots.get(i) {
        check_gap(Arg::Knot, t, b)?;
    }
    Ok(())
}

pub(crate) fn check_width(what: impl Into<What>, min: f64, max: f64) -> Result<()> {
    let what: What = what.into();
    if !(max - min).is_finite() {
        return Err(Error::InvalidArgument {
            what,
            reason: format!(
                "the width of [{min}, {max}] overflows; rescale them",
                min = readable(&min),
                max = readable(&max)
            ),
        });
    }
    Ok(())
}

fn check_interpolation_degree(
    degree: usize,
    n_points: usize,
    min_points_plus: usize,
) -> Result<()> {
    if degree == 0 {
        return Err(Error::Degree {
            degree,
            reason: "interpolation knots need degree ≥ 1".into(),
        });
    }
    // n_points + (min_points_plus − n_points) extra conditions must carry degree + 1 unknowns
    if min_points_plus <= degree {
        return Err(Error::Degree {
            degree,
            reason: format!(
                "{n_points} parameters determine a spline of degree at most {}",
                min_points_plus.saturating_sub(1)
            ),
        });
    }
    Ok(())
}

/// [`Error::Degree`] for `n_ctrl ≤ degree` control points: a B-spline of degree `p` needs at
/// least `p + 1` of them (one polynomial piece, P&T §2.2).
pub(crate) fn too_few_for_degree(n_ctrl: usize, degree: usize) -> Error {
    let (noun, verb) = if n_ctrl == 1 {
        ("control point", "carries")
    } else {
        ("control points", "carry")
    };
    Error::Degree {
        degree,
        reason: format!(
            "{n_ctrl} {noun} {verb} a degree of at most {}; give at least {} control points or \
             lower the degree",
            n_ctrl.saturating_sub(1),
            degree.saturating_add(1)
        ),
    }
}

fn check_size(n: usize) -> Result<()> {
    if n > MAX_SCALARS {
        return Err(Error::TooLarge {
            what: Arg::Knots.into(),
            size: n,
            max: MAX_SCALARS,
        });
    }
    Ok(())
}

/// Mean of a non-empty slice. If the plain sum overflows (values near `f64::MAX`), the terms
/// are scaled first, so that the mean of finite values is always finite.
fn average(values: &[f64]) -> f64 {
    let n = values.len() as f64;
    let sum = values.iter().sum::<f64>();
    if sum.is_finite() {
        sum / n
    } else {
        values.iter().map(|v| v / n).sum()
    }
}

#[cfg(test)]
mod tests;
