//! Arc length: adaptive Gauss–Legendre quadrature of the speed `|C'|` on each Bezier piece, its
//! inverse (the parameter at a given length), points at equal arc-length steps and an
//! approximately arc-length-parametrised B-spline (`docs/theory/queries.md#arc-length`).

use crate::error::readable;
use crate::{Arg, What};
use std::sync::OnceLock;

use rayon::prelude::*;

use super::pieces::{check_tolerance, QueryCurve};
use crate::error::{Error, Result};
use crate::{BSplineCurve, CurveInterpolation, Points};

/// Gauss–Legendre order used on every interval.
const GL_ORDER: usize = 12;
/// Deepest bisection of a piece by the adaptive quadrature (2^-40 of a piece).
const MAX_DEPTH: u32 = 40;
/// Default relative tolerance of [`QueryCurve::length`].
pub const DEFAULT_LENGTH_RTOL: f64 = 1e-13;

/// Nodes on `[0, 1]` and weights (summing to 1) of the `GL_ORDER`-point Gauss–Legendre rule:
/// roots of the Legendre polynomial by Newton from Chebyshev guesses (Press et al., *Numerical
/// Recipes* §4.6), computed once.
fn gauss_legendre() -> &'static ([f64; GL_ORDER], [f64; GL_ORDER]) {
    static RULE: OnceLock<([f64; GL_ORDER], [f64; GL_ORDER])> = OnceLock::new();
    RULE.get_or_init(|| {
        let n = GL_ORDER;
        let mut x = [0.0; GL_ORDER];
        let mut w = [0.0; GL_ORDER];
        for i in 0..n {
            let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, 0.0);
                for j in 0..n {
                    let p2 = p1;
                    p1 = p0;
                    p0 = ((2 * j + 1) as f64 * z * p1 - j as f64 * p2) / (j + 1) as f64;
                }
                dp = n as f64 * (z * p0 - p1) / (z * z - 1.0);
                let dz = p0 / dp;
                z -= dz;
                if dz.abs() < 1e-16 {
                    break;
                }
            }
            x[i] = 0.5 * (1.0 - z);
            w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
        }
        (x, w)
    })
}

/// Pieces handed to one task of the parallel arc-length table.
const PIECES_PER_TASK: usize = 64;

/// Gauss–Legendre integral over `[a, b]` of the speed of the polynomial Bezier piece `piece`
/// of degree `P` in `D` dimensions (`(P + 1)·D` scalars): the hodograph's `P` points
/// `P·(P_{i+1} − P_i)` once, then de Casteljau on them, one coordinate at a time for all the
/// nodes together (so that the node loops vectorise).
fn hodograph_gl<const P: usize, const D: usize>(piece: &[f64], a: f64, b: f64) -> f64 {
    let (x, w) = gauss_legendre();
    let h = b - a;
    let mut s = [0.0; GL_ORDER];
    for i in 0..GL_ORDER {
        s[i] = a + h * x[i];
    }
    let pf = P as f64;
    let mut square = [0.0; GL_ORDER];
    for d in 0..D {
        let mut c = [[0.0; GL_ORDER]; P];
        for (j, cj) in c.iter_mut().enumerate() {
            *cj = [pf * (piece[(j + 1) * D + d] - piece[j * D + d]); GL_ORDER];
        }
        for level in 1..P {
            for j in 0..P - level {
                let next = c[j + 1];
                for i in 0..GL_ORDER {
                    c[j][i] += s[i] * (next[i] - c[j][i]);
                }
            }
        }
        for i in 0..GL_ORDER {
            square[i] += c[0][i] * c[0][i];
        }
    }
    let mut sum = 0.0;
    for i in 0..GL_ORDER {
        sum += w[i] * square[i].sqrt();
    }
    sum * h
}

/// The adaptive intervals `(piece, a, b, length)` of a run of pieces and their summed error
/// estimate.
type Intervals = (Vec<(usize, f64, f64, f64)>, f64);

impl QueryCurve {
    /// `|C'(s)|` of piece `k` in normalised units per unit of the local parameter.
    pub(crate) fn speed(&self, k: usize, s: f64, scratch: &mut Vec<f64>, buf: &mut [f64]) -> f64 {
        self.eval_local(k, s, 1, scratch, buf);
        let d = &buf[self.dim..2 * self.dim];
        d.iter().map(|x| x * x).sum::<f64>().sqrt()
    }

    /// Gauss–Legendre integral of the speed of piece `k` over local `[a, b]`. A polynomial
    /// piece of degree 1 to 5 in 1 to 3 dimensions has the speed `|C'(s)|` of its hodograph
    /// `C'(s) = Σ_i b_{p−1,i}(s)·p·(P_{i+1} − P_i)` (P&T eq. 1.9 / Farin §5.3), formed once per
    /// call and evaluated by de Casteljau at the nodes ([`hodograph_gl`], sizes fixed at
    /// compile time); other pieces go through [`QueryCurve::speed`].
    pub(crate) fn gl(&self, k: usize, a: f64, b: f64, scratch: &mut Vec<f64>) -> f64 {
        if !self.rational {
            let piece = self.piece(k);
            let fast = match (self.degree, self.dim) {
                (1, 1) => Some(hodograph_gl::<1, 1>(piece, a, b)),
                (1, 2) => Some(hodograph_gl::<1, 2>(piece, a, b)),
                (1, 3) => Some(hodograph_gl::<1, 3>(piece, a, b)),
                (2, 1) => Some(hodograph_gl::<2, 1>(piece, a, b)),
                (2, 2) => Some(hodograph_gl::<2, 2>(piece, a, b)),
                (2, 3) => Some(hodograph_gl::<2, 3>(piece, a, b)),
                (3, 1) => Some(hodograph_gl::<3, 1>(piece, a, b)),
                (3, 2) => Some(hodograph_gl::<3, 2>(piece, a, b)),
                (3, 3) => Some(hodograph_gl::<3, 3>(piece, a, b)),
                (4, 2) => Some(hodograph_gl::<4, 2>(piece, a, b)),
                (4, 3) => Some(hodograph_gl::<4, 3>(piece, a, b)),
                (5, 2) => Some(hodograph_gl::<5, 2>(piece, a, b)),
                (5, 3) => Some(hodograph_gl::<5, 3>(piece, a, b)),
                _ => None,
            };
            if let Some(v) = fast {
                return v;
            }
        }
        self.gl_by_eval(k, a, b, scratch)
    }

    /// [`QueryCurve::gl`] through the general evaluation [`QueryCurve::speed`].
    fn gl_by_eval(&self, k: usize, a: f64, b: f64, scratch: &mut Vec<f64>) -> f64 {
        let (x, w) = gauss_legendre();
        let h = b - a;
        let mut buf = vec![0.0; 3 * self.dim];
        let mut sum = 0.0;
        for i in 0..GL_ORDER {
            sum += w[i] * self.speed(k, a + h * x[i], scratch, &mut buf);
        }
        sum * h
    }

    /// The arc-length table to the relative tolerance `rtol` (at least `1e-15`): each piece is
    /// bisected until the Gauss–Legendre value of an interval and the sum over its halves agree
    /// within `rtol` times the piece's length share of the interval; the halves' sum is kept and
    /// the differences are summed into [`ArcLength::error_estimate`]
    /// (`docs/theory/queries.md#arc-length`). Runs of pieces are worked in parallel; the
    /// result does not depend on the number of threads.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, QueryCurve};
    /// let arc = NurbsCurve::circular_arc(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0, 0.0, 2.0)?;
    /// let q = QueryCurve::from_nurbs(&arc)?;
    /// let table = q.arc_length(1e-14)?;
    /// assert!((table.total() - 4.0).abs() < 4e-14);
    /// let t = table.param_at(2.0)?;                       // half way along
    /// assert!((table.length_at(t)? - 2.0).abs() < 1e-13);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a tolerance that is not positive and finite, or for a
    /// curve whose length is beyond the range of a double (a curve near ±1e308), which would
    /// otherwise be reported as infinite.
    pub fn arc_length(&self, rtol: f64) -> Result<ArcLength<'_>> {
        check_tolerance(
            What::of(Arg::RelativeTolerance, "arc-length relative tolerance"),
            rtol,
        )?;
        let rtol = rtol.max(1e-15);
        let n = self.piece_count();
        let runs: Vec<Intervals> = (0..n.div_ceil(PIECES_PER_TASK))
            .into_par_iter()
            .map(|r| {
                let mut out = (Vec::new(), 0.0);
                let mut scratch = Vec::new();
                let mut stack = Vec::new();
                for k in r * PIECES_PER_TASK..((r + 1) * PIECES_PER_TASK).min(n) {
                    self.adapt_piece(k, rtol, &mut scratch, &mut stack, &mut out);
                }
                out
            })
            .collect();
        let mut intervals = Vec::with_capacity(runs.iter().map(|r| r.0.len()).sum());
        let mut cum = Vec::with_capacity(intervals.capacity() + 1);
        cum.push(0.0);
        let mut error = 0.0;
        for (ivs, err) in runs {
            error += err;
            for (k, a, b, len) in ivs {
                intervals.push((k, a, b));
                let last = cum[cum.len() - 1];
                cum.push(last + len);
            }
        }
        let total = cum[cum.len() - 1] * self.scale;
        if !total.is_finite() {
            return Err(Error::InvalidArgument {
                what: "curve for its arc length".into(),
                reason: format!(
                    "the length is {total}, beyond the largest double (about 1.8e308); \
                     scale the curve down (its size is {:e}) and scale the length back",
                    self.scale,
                    total = readable(&total)
                ),
            });
        }
        Ok(ArcLength {
            curve: self,
            intervals,
            cum,
            error,
        })
    }

    /// Appends the adaptive intervals `(k, a, b, length)` of piece `k` to `out.0` and their
    /// error estimate to `out.1` (`stack`: reused work list).
    fn adapt_piece(
        &self,
        k: usize,
        rtol: f64,
        scratch: &mut Vec<f64>,
        stack: &mut Vec<(f64, f64, f64, u32)>,
        out: &mut Intervals,
    ) {
        let whole = self.gl(k, 0.0, 1.0, scratch);
        // the floor keeps a piece of zero length (all control points equal) from bisecting
        let target = rtol * whole.max(1e-300);
        stack.clear();
        stack.push((0.0_f64, 1.0_f64, whole, 0_u32));
        while let Some((a, b, q, depth)) = stack.pop() {
            let m = 0.5 * (a + b);
            let (l, r) = (self.gl(k, a, m, scratch), self.gl(k, m, b, scratch));
            let diff = (l + r - q).abs();
            if diff <= target * (b - a) || depth >= MAX_DEPTH {
                out.0.push((k, a, m, l));
                out.0.push((k, m, b, r));
                out.1 += diff;
            } else {
                stack.push((m, b, r, depth + 1));
                stack.push((a, m, l, depth + 1));
            }
        }
    }

    /// Length of the whole curve to the relative tolerance [`DEFAULT_LENGTH_RTOL`].
    ///
    /// # Errors
    /// None in practice (the tolerance is valid); kept fallible like the other queries.
    pub fn length(&self) -> Result<f64> {
        Ok(self.arc_length(DEFAULT_LENGTH_RTOL)?.total())
    }

    /// Length of the curve between the parameters `a ≤ b` (either order; the sign follows).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] for parameters outside the domain or NaN.
    pub fn length_between(&self, a: f64, b: f64) -> Result<f64> {
        let table = self.arc_length(DEFAULT_LENGTH_RTOL)?;
        Ok(table.length_at(b)? - table.length_at(a)?)
    }
}

/// The arc length of a [`QueryCurve`] as a table of adaptive intervals with their cumulative
/// lengths: the total, the length at any parameter and its inverse.
#[derive(Debug, Clone)]
pub struct ArcLength<'a> {
    curve: &'a QueryCurve,
    /// `(piece, local a, local b)` in parameter order.
    intervals: Vec<(usize, f64, f64)>,
    /// Cumulative normalised length at the start of each interval (one more entry: the total).
    cum: Vec<f64>,
    error: f64,
}

impl ArcLength<'_> {
    /// Total length.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.cum[self.cum.len() - 1] * self.curve.scale
    }

    /// Estimated absolute error of [`ArcLength::total`]: the sum over the intervals of the
    /// difference between one Gauss–Legendre rule on the interval and the rule on its halves.
    /// The kept value (the halves) is far more accurate than the single rule for the analytic
    /// speed of a regular piece, so the estimate bounds the error in practice; near a cusp the
    /// speed is not analytic and the estimate is only an estimate.
    #[must_use]
    pub fn error_estimate(&self) -> f64 {
        self.error * self.curve.scale
    }

    /// Calls `f(t, weight)` for every Gauss–Legendre node of every adaptive interval, `t` the
    /// node's parameter and `weight` its weight in the parameter (the rule's weight times the
    /// interval's length in `t`): [`ArcLength::total`] is `Σ weight·|C'(t)|` to rounding, and
    /// its derivatives with respect to the control points are those of this sum on the same
    /// nodes (`crate::derivatives::ArcLengthGradient`).
    pub(crate) fn for_each_node(&self, mut f: impl FnMut(f64, f64)) {
        let (x, w) = gauss_legendre();
        let c = self.curve;
        for &(k, a, b) in &self.intervals {
            let (t0, t1) = c.spans[k];
            let h = (b - a) * (t1 - t0);
            for (xi, wi) in x.iter().zip(w) {
                f(c.global(k, a + (b - a) * xi), wi * h);
            }
        }
    }

    /// Number of adaptive intervals.
    #[must_use]
    pub fn interval_count(&self) -> usize {
        self.intervals.len()
    }

    fn interval_of_t(&self, t: f64) -> (usize, f64) {
        let c = self.curve;
        let k = c.piece_of(t);
        let s = c.local(k, t);
        let i = self
            .intervals
            .partition_point(|&(p, _, b)| p < k || (p == k && b < s));
        (i.min(self.intervals.len() - 1), s)
    }

    /// Length from the start of the domain to `t`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] outside the domain or for NaN.
    pub fn length_at(&self, t: f64) -> Result<f64> {
        self.curve.check_t(t)?;
        let (i, s) = self.interval_of_t(t);
        let (k, a, _) = self.intervals[i];
        let part = self.curve.gl(k, a, s.max(a), &mut Vec::new());
        Ok((self.cum[i] + part) * self.curve.scale)
    }

    /// The parameter at which the length from the start reaches `length` (`0 ≤ length ≤
    /// total`): the interval by binary search in the table, then Newton's method on
    /// `s(t) − length` with `s' = |C'|`, kept inside the interval by bisection; at most 60
    /// steps. Where the curve stands still (a zero-length stretch) the first such parameter.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a length that is NaN, negative or beyond the total (by
    /// more than the error estimate).
    pub fn param_at(&self, length: f64) -> Result<f64> {
        self.param_at_with(length, &mut Vec::new())
    }

    fn param_at_with(&self, length: f64, scratch: &mut Vec<f64>) -> Result<f64> {
        let c = self.curve;
        let total = self.total();
        let slack = 4.0 * self.error_estimate() + 8.0 * f64::EPSILON * total;
        if !(length >= -slack && length <= total + slack) {
            return Err(Error::InvalidArgument {
                what: "arc length".into(),
                reason: format!(
                    "{length} is not within [0, {total}] (the curve's length)",
                    length = readable(&length),
                    total = readable(&total)
                ),
            });
        }
        let target = (length / c.scale).clamp(0.0, self.cum[self.cum.len() - 1]);
        let i = self.cum.partition_point(|&x| x < target).saturating_sub(1);
        let i = i.min(self.intervals.len() - 1);
        let (k, a, b) = self.intervals[i];
        let want = target - self.cum[i];
        let have = self.cum[i + 1] - self.cum[i];
        if have <= 0.0 {
            return Ok(c.global(k, a));
        }
        let (mut lo, mut hi) = (a, b);
        let mut s = a + (b - a) * (want / have).clamp(0.0, 1.0);
        let mut buf = vec![0.0; 3 * c.dim];
        for _ in 0..60 {
            let f = c.gl(k, a, s, scratch) - want;
            if f < 0.0 {
                lo = s;
            } else {
                hi = s;
            }
            let v = c.speed(k, s, scratch, &mut buf);
            let mut next = if v > 0.0 { s - f / v } else { f64::NAN };
            if !(next >= lo && next <= hi) {
                next = 0.5 * (lo + hi);
            }
            let done = (next - s).abs() <= 1e-16 * (1.0 + s.abs()) || hi - lo <= 1e-16;
            s = next;
            if done || f.abs() <= 1e-17 * have {
                break;
            }
        }
        Ok(c.global(k, s))
    }

    /// [`ArcLength::param_at`] for many lengths, in parallel (the same results on any number
    /// of threads: each length is solved on its own).
    ///
    /// # Errors
    /// As [`ArcLength::param_at`], for the first bad length.
    pub fn param_at_batch(&self, lengths: &[f64]) -> Result<Vec<f64>> {
        lengths
            .par_iter()
            .map_init(Vec::new, |scratch, &l| self.param_at_with(l, scratch))
            .collect()
    }

    /// Parameters of `n + 1 ≥ 2` points at equal arc-length steps from start to end (the first
    /// and last are the domain's ends).
    ///
    /// # Errors
    /// [`Error::TooFew`] for `n = 0`.
    pub fn equal_steps(&self, n: usize) -> Result<Vec<f64>> {
        if n == 0 {
            return Err(Error::TooFew {
                what: "arc-length steps".into(),
                min: 1,
                got: 0,
            });
        }
        let total = self.total();
        let lengths: Vec<f64> = (0..=n).map(|i| total * i as f64 / n as f64).collect();
        let mut t = self.param_at_batch(&lengths)?;
        let (a, b) = self.curve.domain();
        t[0] = a;
        t[n] = b;
        Ok(t)
    }

    /// A cubic B-spline `A(s)` on `[0, total]` with `A(s) ≈ C(t(s))`: it interpolates the curve
    /// at `m + 1` points at equal arc-length steps (at their lengths as parameters), with `m`
    /// doubled from 4 until the largest deviation `|A(s) − C(t(s))|`, checked at 7 lengths
    /// inside every step, is at most `tolerance` (absolute, in the curve's units). Returns the
    /// spline and that largest checked deviation. The check is by sampling, so the deviation is
    /// stated at those lengths; for a smooth curve the interpolation error between them is of
    /// the same size (`docs/theory/queries.md#arc-length`).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a bad tolerance or a curve of zero length;
    /// [`Error::TooLarge`] if `2^16` steps do not reach the tolerance (a cusp or a tolerance
    /// near rounding).
    pub fn parametrized_spline(&self, tolerance: f64) -> Result<(BSplineCurve, f64)> {
        check_tolerance(
            What::of(Arg::Tolerance, "arc-length spline tolerance"),
            tolerance,
        )?;
        let total = self.total();
        if total <= 0.0 {
            return Err(Error::InvalidArgument {
                what: "curve".into(),
                reason: "it has zero length; no arc-length parametrisation exists".into(),
            });
        }
        let c = self.curve;
        let mut m = 4_usize;
        let mut scratch = Vec::new();
        loop {
            let ts = self.equal_steps(m)?;
            let mut pts = Vec::with_capacity((m + 1) * c.dim);
            for &t in &ts {
                pts.extend(c.eval_global(t, 0, &mut scratch));
            }
            let params: Vec<f64> = (0..=m).map(|i| total * i as f64 / m as f64).collect();
            let spline = CurveInterpolation::new(3.min(m))
                .interpolate_at(Points::from_flat(c.dim, pts)?.as_view(), &params)?;
            let mut worst = 0.0_f64;
            for i in 0..m {
                for j in 1..8 {
                    let s = total * (i as f64 + j as f64 / 8.0) / m as f64;
                    let t = self.param_at_with(s, &mut scratch)?;
                    let p = c.eval_global(t, 0, &mut scratch);
                    let q = spline.eval(s.min(total))?;
                    worst = worst.max(super::pieces::dist(&p, &q));
                }
            }
            if worst <= tolerance {
                return Ok((spline, worst));
            }
            if m >= 1 << 16 {
                return Err(Error::TooLarge {
                    what: "arc-length spline steps (tolerance not reached)".into(),
                    size: m * 2,
                    max: 1 << 16,
                });
            }
            m *= 2;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, NurbsCurve, Points};

    #[test]
    fn hodograph_quadrature_agrees_with_evaluation() {
        // every degree and dimension of the fast path, on wiggly pieces, over whole and part
        // intervals: the same rule through the general evaluation agrees to rounding
        for degree in 1..=5 {
            for dim in 1..=3 {
                let n = degree + 3;
                let pts: Vec<f64> = (0..n * dim)
                    .map(|i| (0.7 * i as f64).sin() + 0.1 * i as f64)
                    .collect();
                let c = BSplineCurve::from_knot_vector(
                    degree,
                    crate::KnotVector::clamped_uniform(degree, n).unwrap(),
                    Points::from_flat(dim, pts).unwrap(),
                )
                .unwrap();
                let q = QueryCurve::from_bspline(&c).unwrap();
                let mut scratch = Vec::new();
                for k in 0..q.piece_count() {
                    for (a, b) in [(0.0, 1.0), (0.25, 0.6)] {
                        let fast = q.gl(k, a, b, &mut scratch);
                        let slow = q.gl_by_eval(k, a, b, &mut scratch);
                        assert!(
                            (fast - slow).abs() <= 1e-14 * slow.abs(),
                            "degree {degree} dim {dim} piece {k} [{a}, {b}]: {fast} vs {slow}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn polyline_length_is_the_sum() {
        let pts = [[0.0, 0.0], [3.0, 4.0], [3.0, 0.0], [-1.0, 0.5], [2.0, 2.0]];
        let c = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 2.0, 2.5, 4.0, 4.0],
            Points::from_2d(&pts).unwrap(),
        )
        .unwrap();
        let sum: f64 = pts
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum();
        let l = QueryCurve::from_bspline(&c).unwrap().length().unwrap();
        assert!((l - sum).abs() <= 4.0 * f64::EPSILON * sum, "{l} vs {sum}");
    }

    #[test]
    fn a_length_beyond_the_doubles_is_an_error_not_infinity() {
        // a segment from -1e308 to 1e308 is 2e308 long: reported as `null` (infinity in JSON)
        let c = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[[-1e308, 0.0], [1e308, 0.0]]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let e = q.length().unwrap_err().to_string();
        assert!(
            e.contains("the length is inf") && e.contains("scale the curve down"),
            "{e}"
        );
        // half of it still has a length
        let half = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1e308, 0.0]]).unwrap(),
        )
        .unwrap();
        let l = QueryCurve::from_bspline(&half).unwrap().length().unwrap();
        assert!((l - 1e308).abs() <= 1e295, "{l}");
    }

    #[test]
    fn circular_arc_is_r_theta() {
        for (r, theta) in [(1.0, 0.3), (2.5, 2.0), (1e-3, 6.0), (1e7, 4.5)] {
            let arc =
                NurbsCurve::circular_arc(&[1.0, -2.0], &[1.0, 0.0], &[0.0, 1.0], r, 0.0, theta)
                    .unwrap();
            let l = QueryCurve::from_nurbs(&arc).unwrap().length().unwrap();
            let e = r * theta;
            assert!((l - e).abs() <= 1e-14 * e, "r {r} θ {theta}: {l} vs {e}");
        }
    }

    #[test]
    fn inverse_round_trips_and_degenerate_is_zero() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, -1.0], [4.0, 1.0], [5.0, 0.0]])
                .unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let table = q.arc_length(1e-14).unwrap();
        for f in [0.0, 0.1, 0.5, 0.77, 1.0] {
            let s = f * table.total();
            let t = table.param_at(s).unwrap();
            let back = table.length_at(t).unwrap();
            assert!(
                (back - s).abs() < 1e-12 * table.total(),
                "{f}: {back} vs {s}"
            );
        }
        assert!(table.param_at(f64::NAN).is_err(), "NaN length");
        assert!(table.param_at(2.0 * table.total()).is_err(), "too long");
        let point = BSplineCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[1.0, 1.0]; 3]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&point).unwrap();
        assert_eq!(q.length().unwrap(), 0.0);
        assert_eq!(q.arc_length(1e-12).unwrap().param_at(0.0).unwrap(), 0.0);
    }

    #[test]
    fn arc_length_spline_is_within_its_deviation() {
        let arc =
            NurbsCurve::circular_arc(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0, 0.0, 1.5).unwrap();
        let q = QueryCurve::from_nurbs(&arc).unwrap();
        let table = q.arc_length(1e-13).unwrap();
        let (spline, dev) = table.parametrized_spline(1e-6).unwrap();
        assert!(dev <= 1e-6, "{dev}");
        // on a circle, arc length is the angle: A(s) = (cos s, sin s)
        let p = spline.eval(0.9).unwrap();
        assert!((p[0] - 0.9_f64.cos()).abs() < 2e-6, "{p:?}");
    }
}
