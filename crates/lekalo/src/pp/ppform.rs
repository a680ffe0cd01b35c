//! Piecewise polynomials (pp-form) and the spaces `P_{k,ξ}` and `P_{k,ξ,ν}` (document 003,
//! docs/theory/pp.md#piecewise-polynomials).
//!
//! A [`PiecewisePolynomial`] of order `k` (degree `< k`) on strictly increasing breakpoints
//! `ξ_1 < … < ξ_{l+1}` stores, for each piece `j`, the local power coefficients about its left
//! breakpoint: `f(x) = Σ_{r<k} c_{j,r} (x − ξ_j)^r` on `[ξ_j, ξ_{j+1})` (the last piece closed).
//! So `c_{j,r} = f^{(r)}(ξ_j^+)/r!`. Values have any dimension `dim`; the coefficients are flat,
//! `c[(j·k + r)·dim + d]`.
//!
//! Evaluation is right-continuous (half-open pieces, the last closed), like the B-splines of
//! lekalo; [`PiecewisePolynomial::eval_derivatives_left`] gives left limits, which the de Boor–Fix
//! functionals need (see `quasi`). Conversions to and from B-splines are in `quasi`.

use serde::{Deserialize, Serialize};

use crate::curve::bspline::BSplineCurve;
use crate::error::{
    check_derivative_order, check_finite, Error, Result, MAX_DERIVATIVE_ORDER, MAX_SCALARS,
};
use crate::knots::check_breakpoints;
use crate::knots::KnotVector;
use crate::points::Points;

/// Relative tolerance of [`PpSpace::contains`] (and of the membership check of
/// [`PiecewisePolynomial::to_bspline`]): a jump of `D^j f` counts as zero if it is at most this
/// times the size of `D^j f` over the pieces (the largest of its bounds on each piece from the
/// piece's coefficients).
pub const DEFAULT_CONTINUITY_RTOL: f64 = 1e-9;

/// A piecewise polynomial in pp-form: breakpoints, order and local power coefficients
/// (module docs; document 003 §4 conventions).
///
/// ```
/// use lekalo::PiecewisePolynomial;
/// // |x| on [−1, 1]: two linear pieces (order 2), each about its left breakpoint:
/// // piece 0 is 1 − (x + 1), piece 1 is 0 + 1·(x − 0)
/// let f = PiecewisePolynomial::new(vec![-1.0, 0.0, 1.0], 2, 1, vec![1.0, -1.0, 0.0, 1.0])?;
/// assert_eq!(f.eval(-0.5)?, vec![0.5]);
/// assert_eq!(f.eval(1.0)?, vec![1.0]);
/// assert_eq!(f.jump(1, 1)?, vec![2.0]); // f' jumps from −1 to 1
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "PpRepr", into = "PpRepr")]
pub struct PiecewisePolynomial {
    breakpoints: Vec<f64>,
    order: usize,
    dim: usize,
    coefficients: Vec<f64>,
}

#[derive(Serialize, Deserialize)]
struct PpRepr {
    breakpoints: Vec<f64>,
    order: usize,
    dim: usize,
    coefficients: Vec<f64>,
}

impl TryFrom<PpRepr> for PiecewisePolynomial {
    type Error = Error;
    fn try_from(r: PpRepr) -> Result<Self> {
        PiecewisePolynomial::new(r.breakpoints, r.order, r.dim, r.coefficients)
    }
}

impl From<PiecewisePolynomial> for PpRepr {
    fn from(p: PiecewisePolynomial) -> Self {
        PpRepr {
            breakpoints: p.breakpoints,
            order: p.order,
            dim: p.dim,
            coefficients: p.coefficients,
        }
    }
}

impl PiecewisePolynomial {
    /// A piecewise polynomial from `l + 1` breakpoints, the order `k ≥ 1`, the dimension and
    /// `l·k·dim` local power coefficients (layout in the module docs).
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than two breakpoints; [`Error::InvalidArgument`] if they are
    /// not strictly increasing or their width overflows; [`Error::Degree`] if `order == 0`; [`Error::Dimension`] if
    /// `dim == 0`; [`Error::LengthMismatch`] for a wrong number of coefficients;
    /// [`Error::NonFinite`]; [`Error::TooLarge`].
    pub fn new(
        breakpoints: Vec<f64>,
        order: usize,
        dim: usize,
        coefficients: Vec<f64>,
    ) -> Result<Self> {
        check_breakpoints(&breakpoints)?;
        if order == 0 {
            return Err(Error::Degree {
                degree: 0,
                reason: "the order k = degree + 1 of a piecewise polynomial must be at least 1"
                    .into(),
            });
        }
        if dim == 0 {
            return Err(Error::Dimension {
                what: "piecewise polynomial values".into(),
                expected: 1,
                got: 0,
            });
        }
        let expected = (breakpoints.len() - 1)
            .checked_mul(order)
            .and_then(|v| v.checked_mul(dim))
            .filter(|&v| v <= MAX_SCALARS)
            .ok_or(Error::TooLarge {
                what: "piecewise polynomial coefficients".into(),
                size: usize::MAX,
                max: MAX_SCALARS,
            })?;
        if coefficients.len() != expected {
            return Err(Error::LengthMismatch {
                what: "coefficients (pieces × order × dim)".into(),
                expected,
                got: coefficients.len(),
            });
        }
        check_finite("coefficients", &coefficients)?;
        Ok(PiecewisePolynomial {
            breakpoints,
            order,
            dim,
            coefficients,
        })
    }

    /// Trusted constructor for results built in the crate (debug-checked).
    pub(crate) fn from_raw(
        breakpoints: Vec<f64>,
        order: usize,
        dim: usize,
        coefficients: Vec<f64>,
    ) -> Self {
        debug_assert_eq!(
            coefficients.len(),
            (breakpoints.len() - 1) * order * dim,
            "raw pp coefficient count"
        );
        PiecewisePolynomial {
            breakpoints,
            order,
            dim,
            coefficients,
        }
    }

    /// The coefficients for in-crate constructions that change them in place.
    pub(crate) fn coefficients_mut(&mut self) -> &mut [f64] {
        &mut self.coefficients
    }

    /// The breakpoints `ξ_1 < … < ξ_{l+1}`.
    #[must_use]
    pub fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }

    /// The order `k` (degree `< k`).
    #[must_use]
    pub fn order(&self) -> usize {
        self.order
    }

    /// Dimension of the values.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of pieces `l`.
    #[must_use]
    pub fn n_pieces(&self) -> usize {
        self.breakpoints.len() - 1
    }

    /// All coefficients, flat (module docs).
    #[must_use]
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// The domain `[ξ_1, ξ_{l+1}]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (
            self.breakpoints[0],
            self.breakpoints[self.breakpoints.len() - 1],
        )
    }

    /// Index `j` of the piece `[ξ_j, ξ_{j+1})` containing `x` (the last piece is closed).
    /// Binary search, O(log l).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] outside the domain or for NaN.
    pub fn piece_index(&self, x: f64) -> Result<usize> {
        let (min, max) = self.domain();
        if !(x >= min && x <= max) {
            return Err(Error::ParameterOutOfDomain { t: x, min, max });
        }
        let first_greater = self.breakpoints.partition_point(|&b| b <= x);
        Ok((first_greater - 1).min(self.n_pieces() - 1))
    }

    /// Index of the piece `(ξ_j, ξ_{j+1}]` whose closure contains `x` from the left (the first
    /// piece at `x = ξ_1`).
    pub(crate) fn piece_index_left(&self, x: f64) -> Result<usize> {
        let (min, max) = self.domain();
        if !(x >= min && x <= max) {
            return Err(Error::ParameterOutOfDomain { t: x, min, max });
        }
        let first_ge = self.breakpoints.partition_point(|&b| b < x);
        Ok(first_ge.saturating_sub(1).min(self.n_pieces() - 1))
    }

    /// The value at `x` (right-continuous; the last piece closed). Horner's rule, O(k·dim).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`].
    pub fn eval(&self, x: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim];
        self.eval_into(x, &mut out)?;
        Ok(out)
    }

    /// As [`PiecewisePolynomial::eval`], into a caller's buffer of length `dim`; no allocation.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::LengthMismatch`] for a wrong buffer length;
    /// [`Error::NonFinite`] if the value overflows (huge coefficients: rescale them).
    pub fn eval_into(&self, x: f64, out: &mut [f64]) -> Result<()> {
        if out.len() != self.dim {
            return Err(Error::LengthMismatch {
                what: "output point (dimension)".into(),
                expected: self.dim,
                got: out.len(),
            });
        }
        let j = self.piece_index(x)?;
        self.piece_derivative_into(j, x, 0, out);
        check_finite(
            "piecewise polynomial value (overflow: rescale the coefficients)",
            out,
        )?;
        Ok(())
    }

    /// Derivatives of orders `0..=m` at `x`, right-hand at interior breakpoints (left-hand at
    /// the right end): row `r` is `D^r f(x)`. Orders `≥ k` are zero.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::TooLarge`] if `m > MAX_DERIVATIVE_ORDER`; [`Error::NonFinite`] if a derivative overflows.
    pub fn eval_derivatives(&self, x: f64, m: usize) -> Result<Points> {
        let j = self.piece_index(x)?;
        check_derivative_order(m, MAX_DERIVATIVE_ORDER)?;
        let out = self.piece_derivatives(j, x, m);
        check_finite(
            "derivatives (overflow: rescale the coefficients)",
            out.as_slice(),
        )?;
        Ok(out)
    }

    /// As [`PiecewisePolynomial::eval_derivatives`] but with left-hand limits at interior
    /// breakpoints (right-hand at the left end `ξ_1`).
    ///
    /// # Errors
    /// As [`PiecewisePolynomial::eval_derivatives`].
    pub fn eval_derivatives_left(&self, x: f64, m: usize) -> Result<Points> {
        let j = self.piece_index_left(x)?;
        check_derivative_order(m, MAX_DERIVATIVE_ORDER)?;
        let out = self.piece_derivatives(j, x, m);
        check_finite(
            "derivatives (overflow: rescale the coefficients)",
            out.as_slice(),
        )?;
        Ok(out)
    }

    fn piece_derivatives(&self, j: usize, x: f64, m: usize) -> Points {
        let mut out = vec![0.0; (m + 1) * self.dim];
        for (r, row) in out.chunks_exact_mut(self.dim).enumerate() {
            self.piece_derivative_into(j, x, r, row);
        }
        Points::from_raw(out, self.dim)
    }

    /// `D^r` of piece `j`'s polynomial at `x` (any `x`: the polynomial is extended).
    /// `D^r Σ_s c_s u^s = Σ_{s≥r} c_s s!/(s−r)! u^{s−r}`, by Horner in `u = x − ξ_j`.
    pub(crate) fn piece_derivative_into(&self, j: usize, x: f64, r: usize, out: &mut [f64]) {
        let (k, dim) = (self.order, self.dim);
        out.fill(0.0);
        if r >= k {
            return;
        }
        let u = x - self.breakpoints[j];
        let c = &self.coefficients[j * k * dim..(j + 1) * k * dim];
        for s in (r..k).rev() {
            let falling: f64 = (s - r + 1..=s).map(|v| v as f64).product();
            for (o, &cs) in out.iter_mut().zip(&c[s * dim..(s + 1) * dim]) {
                *o = *o * u + falling * cs;
            }
        }
    }

    /// The derivative `D^j f` as a piecewise polynomial of order `max(k − j, 1)` on the same
    /// breakpoints (document 003, Definition 4.2). For `j ≥ k` it is the zero function of order 1.
    #[must_use]
    pub fn derivative(&self, j: usize) -> PiecewisePolynomial {
        let (k, dim, l) = (self.order, self.dim, self.n_pieces());
        let new_order = k.saturating_sub(j).max(1);
        let mut c = vec![0.0; l * new_order * dim];
        if j < k {
            for p in 0..l {
                for r in 0..new_order {
                    // c'_r = c_{r+j} (r+j)!/r!
                    let falling: f64 = (r + 1..=r + j).map(|v| v as f64).product();
                    let src = (p * k + r + j) * dim;
                    let dst = (p * new_order + r) * dim;
                    for d in 0..dim {
                        c[dst + d] = falling * self.coefficients[src + d];
                    }
                }
            }
        }
        PiecewisePolynomial::from_raw(self.breakpoints.clone(), new_order, dim, c)
    }

    /// The jump `jump_{ξ_i} D^j f = D^j f(ξ_i^+) − D^j f(ξ_i^−)` at the interior breakpoint
    /// `ξ_i`, `i = 1 … l − 1` (0-based), document 003 eq. (9).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if `i` is not an interior breakpoint index.
    pub fn jump(&self, i: usize, j: usize) -> Result<Vec<f64>> {
        if i == 0 || i >= self.n_pieces() {
            return Err(Error::InvalidArgument {
                what: "breakpoint index".into(),
                reason: format!(
                    "jumps exist at interior breakpoints 1..={}, got {i}",
                    self.n_pieces().saturating_sub(1)
                ),
            });
        }
        let x = self.breakpoints[i];
        let mut right = vec![0.0; self.dim];
        let mut left = vec![0.0; self.dim];
        self.piece_derivative_into(i, x, j, &mut right);
        self.piece_derivative_into(i - 1, x, j, &mut left);
        Ok(right.iter().zip(&left).map(|(r, l)| r - l).collect())
    }

    /// The continuity `ν_2 … ν_l` of `self` at its interior breakpoints
    /// (docs/theory/pp.md#continuity-conditions): `ν_i` is the number of derivatives
    /// `D^0 … D^{ν_i − 1}` that do not jump at `ξ_i` (document 003 eq. (9)), so `self` is
    /// `C^{ν_i − 1}` there (`ν_i = k`: no break at all). A jump counts as zero by the test of
    /// [`PpSpace::contains`] with the same `rtol`, so `self` always belongs to
    /// `PpSpace::new(breakpoints, &continuity, order)`: the smallest space of its breakpoints and
    /// order that holds it. O(l·k²·dim).
    ///
    /// ```
    /// use lekalo::{PiecewisePolynomial, PpSpace, DEFAULT_CONTINUITY_RTOL};
    /// // |x| on [−1, 1]: continuous, with a kink at 0
    /// let f = PiecewisePolynomial::new(vec![-1.0, 0.0, 1.0], 2, 1, vec![1.0, -1.0, 0.0, 1.0])?;
    /// let nu = f.continuity(DEFAULT_CONTINUITY_RTOL);
    /// assert_eq!(nu, vec![1]);
    /// assert!(PpSpace::new(f.breakpoints(), &nu, 2)?.contains(&f, DEFAULT_CONTINUITY_RTOL));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn continuity(&self, rtol: f64) -> Vec<usize> {
        let dim = self.dim;
        let interior = self.n_pieces().saturating_sub(1);
        // ν_i grows while the derivatives keep agreeing; `open[m]` is false once one jumped
        let mut nu = vec![0; interior];
        let mut open = vec![true; interior];
        let mut left = vec![0.0; dim];
        let mut right = vec![0.0; dim];
        for j in 0..self.order {
            let scale = self.derivative_scale(j);
            for m in 0..interior {
                if !open[m] {
                    continue;
                }
                let i = m + 1;
                let x = self.breakpoints[i];
                self.piece_derivative_into(i, x, j, &mut right);
                self.piece_derivative_into(i - 1, x, j, &mut left);
                if (0..dim).any(|d| (right[d] - left[d]).abs() > rtol * scale[d]) {
                    open[m] = false;
                } else {
                    nu[m] = j + 1;
                }
            }
        }
        nu
    }

    /// The size of `D^j f` over the pieces and the coordinates: the largest of the bounds
    /// `Σ_{s ≥ j} s!/(s − j)! |c_{p,s,d}| h_p^{s−j} ≥ max |D^j f_d|` on piece `p` of length `h_p`
    /// (`f_d = Σ_s c_{p,s,d} (x − ξ_p)^s` there), the same for every coordinate `d` (a curve's
    /// coordinates share their unit). It is the scale of the continuity test of
    /// [`PpSpace::contains`] and [`PiecewisePolynomial::continuity`]: a jump of `D^j f` counts
    /// as zero when it is below `rtol` times this size. The values at the breakpoints alone
    /// would not do: where every join is `C^j` with `D^j f = 0` there (a polyline's corners
    /// rounded with `C^k`, `k ≥ j`), they are rounding, and rounding would count as a jump;
    /// nor would a scale per coordinate, for a coordinate whose `D^j f_d` vanishes (`x` along
    /// a zigzag whose segments all have the same `x` direction).
    fn derivative_scale(&self, j: usize) -> Vec<f64> {
        let (k, dim) = (self.order, self.dim);
        let mut scale = vec![0.0f64; dim];
        if j >= k {
            return scale;
        }
        for p in 0..self.n_pieces() {
            let h = self.breakpoints[p + 1] - self.breakpoints[p];
            let c = &self.coefficients[p * k * dim..(p + 1) * k * dim];
            for (d, out) in scale.iter_mut().enumerate() {
                // Horner in h of the falling-factorial-weighted |c_s|, as piece_derivative_into
                let mut bound = 0.0;
                for s in (j..k).rev() {
                    let falling: f64 = (s - j + 1..=s).map(|v| v as f64).product();
                    bound = bound * h + falling * c[s * dim + d].abs();
                }
                *out = out.max(bound);
            }
        }
        let size = scale.iter().copied().fold(0.0, f64::max);
        scale.fill(size);
        scale
    }

    /// The pp-form of a B-spline curve (docs/theory/pp.md#from-b-spline-to-pp-form): the
    /// breakpoints are the distinct knots of the domain `[x_k, x_{n+1}]`, the order `k = p + 1`,
    /// and the coefficients of piece `j` are the right-hand derivatives at its left breakpoint,
    /// `c_{j,r} = C^{(r)}(ξ_j^+)/r!` ([`BSplineCurve::eval_derivatives`], P&T A2.3).
    /// O(l·(p² + p·dim)).
    ///
    /// A breakpoint where the curve is `C^∞` only because it is not a knot does not appear: a pp
    /// with `ν_i = k` somewhere round-trips to fewer pieces.
    ///
    /// # Errors
    /// None in practice (the curve is valid); errors of [`BSplineCurve::eval_derivatives`] are
    /// passed on.
    pub fn from_bspline(curve: &BSplineCurve) -> Result<Self> {
        let p = curve.degree();
        let (a, b) = curve.domain();
        let mut breakpoints: Vec<f64> = curve
            .knots()
            .as_slice()
            .iter()
            .copied()
            .filter(|&t| t >= a && t <= b)
            .collect();
        breakpoints.dedup();
        let (k, dim) = (p + 1, curve.dim());
        let l = breakpoints.len() - 1;
        let mut c = Vec::with_capacity(l * k * dim);
        for &xi in &breakpoints[..l] {
            let d = curve.eval_derivatives(xi, p)?;
            let mut factorial = 1.0;
            for r in 0..k {
                if r > 0 {
                    factorial *= r as f64;
                }
                c.extend(d.point(r).iter().map(|v| v / factorial));
            }
        }
        Ok(PiecewisePolynomial::from_raw(breakpoints, k, dim, c))
    }
}

/// The space `P_{k,ξ,ν}` of piecewise polynomials of order `k` on breakpoints `ξ` with `ν_i`
/// continuity conditions `jump_{ξ_i} D^{j−1} f = 0`, `j = 1 … ν_i`, at each interior breakpoint
/// (document 003 eq. 9; `ν = 0` everywhere gives `P_{k,ξ}`), with its Curry–Schoenberg knots.
///
/// ```
/// use lekalo::PpSpace;
/// // the thesis's practical task: C¹ quadratics on 7 breakpoints, dimension 3 + 5 = 8
/// let s = PpSpace::new(&[0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0], &[2; 5], 3)?;
/// assert_eq!(s.dimension(), 8);
/// assert_eq!(s.knots().len(), 11);
/// assert_eq!(PpSpace::unconstrained(&[0.0, 1.0, 2.0], 4)?.dimension(), 8); // k·l
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "PpSpaceRepr", into = "PpSpaceRepr")]
pub struct PpSpace {
    breakpoints: Vec<f64>,
    continuity: Vec<usize>,
    order: usize,
    knots: KnotVector,
}

#[derive(Serialize, Deserialize)]
struct PpSpaceRepr {
    breakpoints: Vec<f64>,
    continuity: Vec<usize>,
    order: usize,
}

impl TryFrom<PpSpaceRepr> for PpSpace {
    type Error = Error;
    fn try_from(r: PpSpaceRepr) -> Result<Self> {
        PpSpace::new(&r.breakpoints, &r.continuity, r.order)
    }
}

impl From<PpSpace> for PpSpaceRepr {
    fn from(s: PpSpace) -> Self {
        PpSpaceRepr {
            breakpoints: s.breakpoints,
            continuity: s.continuity,
            order: s.order,
        }
    }
}

impl PpSpace {
    /// The space `P_{k,ξ,ν}` for breakpoints `ξ_1 < … < ξ_{l+1}`, `ν_2 … ν_l` (one per interior
    /// breakpoint, `0 ≤ ν_i ≤ k`) and order `k`. Its knots are those of
    /// [`KnotVector::from_breakpoints`] (Curry–Schoenberg, Theorem 4.5): `k` copies of `ξ_1`,
    /// `ξ_i` repeated `k − ν_i` times, `k` copies of `ξ_{l+1}`. The end knots are clamped, as in
    /// the thesis's practical task; the theorem allows any `x_1 ≤ … ≤ x_k ≤ ξ_1` and
    /// `ξ_{l+1} ≤ x_{n+1} ≤ …`, but clamped ends keep the B-spline coefficients local to the
    /// domain and let the curve evaluate at both ends.
    ///
    /// # Errors
    /// As [`KnotVector::from_breakpoints`].
    pub fn new(breakpoints: &[f64], continuity: &[usize], order: usize) -> Result<Self> {
        let knots = KnotVector::from_breakpoints(breakpoints, continuity, order)?;
        Ok(PpSpace {
            breakpoints: breakpoints.to_vec(),
            continuity: continuity.to_vec(),
            order,
            knots,
        })
    }

    /// `P_{k,ξ}`: no continuity conditions (`ν_i = 0`).
    ///
    /// # Errors
    /// As [`PpSpace::new`].
    pub fn unconstrained(breakpoints: &[f64], order: usize) -> Result<Self> {
        let nu = vec![0; breakpoints.len().saturating_sub(2)];
        Self::new(breakpoints, &nu, order)
    }

    /// The breakpoints.
    #[must_use]
    pub fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }

    /// The continuity conditions `ν_2 … ν_l`.
    #[must_use]
    pub fn continuity(&self) -> &[usize] {
        &self.continuity
    }

    /// The order `k`.
    #[must_use]
    pub fn order(&self) -> usize {
        self.order
    }

    /// `dim P_{k,ξ,ν} = k + Σ_{i=2}^{l} (k − ν_i)` (Theorem 4.3; `k·l` for `P_{k,ξ}`).
    #[must_use]
    pub fn dimension(&self) -> usize {
        self.order
            + self
                .continuity
                .iter()
                .map(|nu| self.order - nu)
                .sum::<usize>()
    }

    /// The Curry–Schoenberg knots `x_1 … x_{n+k}` (see [`PpSpace::new`]).
    #[must_use]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The truncated-power basis of the space (Theorem 4.3, eq. 10): `(x − ξ_1)^i/i!` for
    /// `i = 0 … k − 1`, then for each interior breakpoint `ξ_j` the functions
    /// `(x − ξ_j)_+^i/i!`, `i = ν_j … k − 1`. There are [`PpSpace::dimension`] of them, each as
    /// a scalar piecewise polynomial. Its condition number grows quickly with `l` and `k`; use
    /// the B-spline basis ([`PpSpace::knots`]) for computation.
    #[must_use]
    pub fn truncated_power_basis(&self) -> Vec<PiecewisePolynomial> {
        let k = self.order;
        let xi = &self.breakpoints;
        let l = xi.len() - 1;
        let mut basis = Vec::with_capacity(self.dimension());
        let starts = std::iter::once((0usize, 0usize)).chain(
            self.continuity
                .iter()
                .enumerate()
                .map(|(m, &nu)| (m + 1, nu)),
        );
        for (j, nu) in starts {
            for i in nu..k {
                // (x − ξ_j)^i/i! about ξ_p (p ≥ j): Σ_r C(i,r) (ξ_p − ξ_j)^{i−r} u^r / i!
                let mut c = vec![0.0; l * k];
                let i_fact: f64 = (1..=i).map(|v| v as f64).product();
                for p in j..l {
                    let h = xi[p] - xi[j];
                    let mut binom = 1.0;
                    for r in 0..=i {
                        c[p * k + r] = binom * h.powi(i32::try_from(i - r).unwrap_or(0)) / i_fact;
                        binom = binom * (i - r) as f64 / (r + 1) as f64;
                    }
                }
                basis.push(PiecewisePolynomial::from_raw(xi.clone(), k, 1, c));
            }
        }
        basis
    }

    /// True if `f` belongs to the space: same breakpoints (exactly), order `≤ k`, and every jump
    /// `jump_{ξ_i} D^{j} f`, `j < ν_i`, is at most `rtol` times the size of `D^j f` over the
    /// pieces and coordinates (a bound of its largest value on each piece from the piece's
    /// coefficients), see [`DEFAULT_CONTINUITY_RTOL`].
    #[must_use]
    pub fn contains(&self, f: &PiecewisePolynomial, rtol: f64) -> bool {
        if f.breakpoints != self.breakpoints || f.order > self.order {
            return false;
        }
        let dim = f.dim;
        let max_nu = self.continuity.iter().copied().max().unwrap_or(0);
        let mut left = vec![0.0; dim];
        let mut right = vec![0.0; dim];
        for j in 0..max_nu.min(f.order) {
            let scale = f.derivative_scale(j);
            for (m, &nu) in self.continuity.iter().enumerate() {
                if j >= nu {
                    continue;
                }
                let i = m + 1;
                let x = f.breakpoints[i];
                f.piece_derivative_into(i, x, j, &mut right);
                f.piece_derivative_into(i - 1, x, j, &mut left);
                for d in 0..dim {
                    if (right[d] - left[d]).abs() > rtol * scale[d] {
                        return false;
                    }
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pp_abs() -> PiecewisePolynomial {
        PiecewisePolynomial::new(vec![-1.0, 0.0, 1.0], 2, 1, vec![1.0, -1.0, 0.0, 1.0]).unwrap()
    }

    #[test]
    fn eval_sides_and_derivatives() {
        let f = pp_abs();
        assert_eq!(f.eval(0.0).unwrap(), vec![0.0]);
        assert_eq!(f.eval_derivatives(0.0, 1).unwrap().point(1), &[1.0]);
        assert_eq!(f.eval_derivatives_left(0.0, 1).unwrap().point(1), &[-1.0]);
        assert_eq!(f.eval_derivatives_left(-1.0, 1).unwrap().point(0), &[1.0]);
        assert_eq!(f.eval_derivatives(1.0, 2).unwrap().point(2), &[0.0]);
        let d = f.derivative(1);
        assert_eq!(d.order(), 1);
        assert_eq!(d.eval(-0.5).unwrap(), vec![-1.0]);
        assert_eq!(f.derivative(5).eval(0.3).unwrap(), vec![0.0]);
    }

    // A cubic pp: derivative pp agrees with derivatives evaluated directly.
    #[test]
    fn derivative_matches_direct() {
        let c: Vec<f64> = (0..8).map(|v| (v as f64 * 0.7).sin()).collect();
        let f = PiecewisePolynomial::new(vec![0.0, 1.0, 2.5], 4, 1, c).unwrap();
        let d2 = f.derivative(2);
        for k in 0..=10 {
            let x = 0.25 * k as f64;
            let direct = f.eval_derivatives(x, 2).unwrap();
            assert!(
                (d2.eval(x).unwrap()[0] - direct.point(2)[0]).abs() < 1e-13,
                "x = {x}"
            );
        }
    }

    #[test]
    fn errors() {
        let e = PiecewisePolynomial::new(vec![0.0], 1, 1, vec![]).unwrap_err();
        assert!(matches!(e, Error::TooFew { .. }));
        let e = PiecewisePolynomial::new(vec![0.0, 0.0], 1, 1, vec![0.0]).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }));
        let e = PiecewisePolynomial::new(vec![0.0, 1.0], 0, 1, vec![]).unwrap_err();
        assert!(matches!(e, Error::Degree { .. }));
        let e = PiecewisePolynomial::new(vec![0.0, 1.0], 1, 0, vec![]).unwrap_err();
        assert!(matches!(e, Error::Dimension { .. }));
        let e = PiecewisePolynomial::new(vec![0.0, 1.0], 2, 1, vec![0.0]).unwrap_err();
        assert!(matches!(e, Error::LengthMismatch { .. }));
        let e = PiecewisePolynomial::new(vec![0.0, 1.0], 1, 1, vec![f64::NAN]).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }));
        let e = PiecewisePolynomial::new(vec![0.0, f64::INFINITY], 1, 1, vec![0.0]).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }));
        let e = PiecewisePolynomial::new(vec![0.0, 1.0], usize::MAX, 2, vec![]).unwrap_err();
        assert!(matches!(e, Error::TooLarge { .. }));
        let f = pp_abs();
        assert!(matches!(
            f.eval(1.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            f.eval(f64::NAN),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(f.jump(0, 0), Err(Error::InvalidArgument { .. })));
        assert!(matches!(f.jump(2, 0), Err(Error::InvalidArgument { .. })));
        let mut out = [0.0; 2];
        assert!(matches!(
            f.eval_into(0.0, &mut out),
            Err(Error::LengthMismatch { .. })
        ));
    }

    // Theorem 4.3: the truncated-power functions have the right count and satisfy exactly the
    // continuity conditions of the space; each is (x − ξ_j)_+^i / i!.
    #[test]
    fn truncated_power_basis() {
        let s = PpSpace::new(&[0.0, 1.0, 1.5, 3.0], &[1, 3], 3).unwrap();
        assert_eq!(s.dimension(), 3 + 2);
        let basis = s.truncated_power_basis();
        assert_eq!(basis.len(), s.dimension());
        for b in &basis {
            assert!(s.contains(b, DEFAULT_CONTINUITY_RTOL), "{b:?}");
        }
        // the fourth function is (x − 1)_+^1 / 1!
        for k in 0..=12 {
            let x = 0.25 * k as f64;
            let want = if x > 1.0 { x - 1.0 } else { 0.0 };
            assert!(
                (basis[3].eval(x).unwrap()[0] - want).abs() < 1e-15,
                "x = {x}"
            );
        }
        // (x − 1)_+^0 is not C⁰: it is in P_{3,ξ} but not in a space with ν_2 ≥ 1
        let full = PpSpace::unconstrained(&[0.0, 1.0, 1.5, 3.0], 3).unwrap();
        assert_eq!(full.dimension(), 9);
        let fb = full.truncated_power_basis();
        assert_eq!(fb.len(), 9);
        assert!(
            !s.contains(&fb[3], DEFAULT_CONTINUITY_RTOL),
            "step in C⁰ space"
        );
    }

    #[test]
    fn serde_validates() {
        let f = pp_abs();
        let s = serde_json::to_string(&f).unwrap();
        let g: PiecewisePolynomial = serde_json::from_str(&s).unwrap();
        assert_eq!(f, g);
        let bad = r#"{"breakpoints":[1.0,0.0],"order":1,"dim":1,"coefficients":[0.0]}"#;
        assert!(serde_json::from_str::<PiecewisePolynomial>(bad).is_err());
        let space = PpSpace::new(&[0.0, 1.0, 3.0], &[2], 3).unwrap();
        let s = serde_json::to_string(&space).unwrap();
        assert_eq!(serde_json::from_str::<PpSpace>(&s).unwrap(), space);
        let bad = r#"{"breakpoints":[0.0,1.0,3.0],"continuity":[4],"order":3}"#;
        assert!(serde_json::from_str::<PpSpace>(bad).is_err());
    }
}
