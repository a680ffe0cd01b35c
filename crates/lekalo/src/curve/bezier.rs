//! Bezier curves `P(t) = Σ_{i=0}^{n} b_{n,i}(t) P_i`, `t ∈ [0, 1]` (document 002, Bezier curves,
//! document 004 eq. 1), of any degree and dimension.

use crate::error::readable;
use crate::{Arg, What};
use serde::{Deserialize, Serialize};

use crate::basis::bernstein_all_unchecked;
use crate::curve::bspline::BSplineCurve;
use crate::error::{check_derivative_order, check_finite, Error, Result, MAX_DERIVATIVE_ORDER};
use crate::numeric::progress::Progress;
use crate::points::Points;

/// A Bezier curve of degree `n` with control points `P_0 … P_n` on the domain `[0, 1]`.
///
/// ```
/// use lekalo::{BezierCurve, Points};
/// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]).unwrap()).unwrap();
/// assert_eq!(c.degree(), 2);
/// assert_eq!(c.eval(0.5).unwrap(), vec![1.0, 1.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BezierCurveRepr", into = "BezierCurveRepr")]
pub struct BezierCurve {
    control: Points,
}

#[derive(Serialize, Deserialize)]
struct BezierCurveRepr {
    control: Points,
}

impl TryFrom<BezierCurveRepr> for BezierCurve {
    type Error = Error;
    fn try_from(r: BezierCurveRepr) -> Result<Self> {
        BezierCurve::new(r.control)
    }
}

impl From<BezierCurve> for BezierCurveRepr {
    fn from(c: BezierCurve) -> Self {
        BezierCurveRepr { control: c.control }
    }
}

impl BezierCurve {
    /// A Bezier curve from its control points (degree = number of points − 1).
    ///
    /// # Errors
    /// [`Error::TooFew`] if there are no control points.
    pub fn new(control: Points) -> Result<Self> {
        if control.is_empty() {
            return Err(Error::TooFew {
                what: What::of(Arg::ControlPoints, "Bezier control points"),
                min: 1,
                got: 0,
            });
        }
        Ok(BezierCurve { control })
    }

    /// Trusted constructor for internal results.
    pub(crate) fn from_raw(control: Points) -> Self {
        debug_assert!(!control.is_empty(), "raw Bezier needs control points");
        BezierCurve { control }
    }

    /// Degree `n` (number of control points − 1).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.control.len() - 1
    }

    /// Dimension of the points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.control.dim()
    }

    /// The parameter domain, always `(0, 1)`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }

    /// The control points.
    #[must_use]
    pub fn control_points(&self) -> &Points {
        &self.control
    }

    /// The control points, owned.
    #[must_use]
    pub fn into_control_points(self) -> Points {
        self.control
    }

    /// Point `P(t)` by de Casteljau's algorithm (P&T Algorithm A1.5): repeated linear
    /// interpolation of the control polygon, O(n²·dim), stable.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ t ≤ 1`.
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(t, &mut out)?;
        Ok(out)
    }

    /// Point `P(t)` by de Casteljau's algorithm (P&T Algorithm A1.5), into `out` (length `dim`).
    /// Allocates one scratch copy of the control polygon; use [`BezierCurve::eval_batch`] for
    /// many parameters.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ t ≤ 1`; [`Error::LengthMismatch`] if
    /// `out.len() != dim`.
    pub fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<()> {
        check_unit(t)?;
        check_out(out.len(), self.dim())?;
        let mut scratch = self.control.as_slice().to_vec();
        de_casteljau_into(self.control.as_slice(), self.dim(), t, &mut scratch, out);
        Ok(())
    }

    /// Evaluates at every parameter of `ts` into `out` (`ts.len() × dim`, point-major) by de
    /// Casteljau's algorithm, reusing one scratch buffer: the results are bit-for-bit those of
    /// [`BezierCurve::eval`].
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?)?;
    /// let mut out = vec![0.0; 6];
    /// c.eval_batch(&[0.0, 0.5, 1.0], &mut out)?;
    /// assert_eq!(out, vec![0.0, 0.0, 1.0, 1.0, 2.0, 0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`;
    /// [`Error::ParameterOutOfDomain`] at the first parameter outside `[0, 1]` (nothing is
    /// guaranteed about `out` then).
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        self.eval_batch_with_progress(ts, out, &Progress::new())
    }

    /// [`BezierCurve::eval_batch`] reporting to `progress` (`done` of `ts.len()` parameters)
    /// and stopping when it is cancelled. De Casteljau costs `(n + 1)²·dim / 2` operations per
    /// point, so the hook is called about every [`Progress::STRIDE`] of them: after every point
    /// for high degrees. The points are bit-for-bit those of [`BezierCurve::eval_batch`].
    ///
    /// ```
    /// use std::sync::atomic::AtomicBool;
    /// use lekalo::{BezierCurve, Error, Points, Progress};
    /// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?)?;
    /// let stop = AtomicBool::new(true);
    /// let mut out = vec![0.0; 6];
    /// let e = c.eval_batch_with_progress(&[0.0, 0.5, 1.0], &mut out, &Progress::new().with_cancel(&stop));
    /// assert!(matches!(e, Err(Error::Cancelled { .. })));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BezierCurve::eval_batch`]; [`Error::Cancelled`] when `progress` is cancelled.
    pub fn eval_batch_with_progress(
        &self,
        ts: &[f64],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        let dim = self.dim();
        let expected = ts.len().saturating_mul(dim);
        if out.len() != expected {
            return Err(Error::LengthMismatch {
                what: "output buffer (parameters × dimension)".into(),
                expected,
                got: out.len(),
            });
        }
        let control = self.control.as_slice();
        let mut scratch = vec![0.0; control.len()];
        let mut outs = out.chunks_exact_mut(dim);
        let cost = (control.len() as u64).saturating_mul(self.control.len() as u64) / 2;
        progress.chunks("Bezier curve evaluation", ts, cost, |ts| {
            for (&t, o) in ts.iter().zip(&mut outs) {
                check_unit(t)?;
                de_casteljau_into(control, dim, t, &mut scratch, o);
            }
            Ok(())
        })
    }

    /// Point `P(t)` by the Bernstein sum `Σ b_{n,i}(t) P_i` (document 002, Bezier curves), into
    /// `out`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_bernstein_into(&self, t: f64, out: &mut [f64]) -> Result<()> {
        check_unit(t)?;
        let dim = self.dim();
        check_out(out.len(), dim)?;
        let n = self.degree();
        let mut b = vec![0.0; n + 1];
        bernstein_all_unchecked(n, t, &mut b);
        out.fill(0.0);
        for (bi, p) in b.iter().zip(self.control.iter()) {
            for (o, x) in out.iter_mut().zip(p) {
                *o += bi * x;
            }
        }
        Ok(())
    }

    /// Derivatives `P^{(k)}(t)` for `k = 0..=order`: returns `order + 1` points, row `k` the k-th
    /// derivative; orders above the degree are zero. Each derivative is evaluated by de Casteljau
    /// on the k-th hodograph, whose control points are `n!/(n−k)! Δ^k P_i` (the hodograph formula
    /// applied k times; see [`BezierCurve::derivative`]). O((order + 1)·n²·dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// // P(t) = t² in Bernstein form (0, 0, 1): P' = 2t, P'' = 2
    /// let c = BezierCurve::new(Points::from_flat(1, vec![0.0, 0.0, 1.0])?)?;
    /// let d = c.eval_derivatives(0.25, 3)?;
    /// assert_eq!(d.as_slice(), &[0.0625, 0.5, 2.0, 0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ t ≤ 1`; [`Error::TooLarge`] if `order > MAX_DERIVATIVE_ORDER`; [`Error::NonFinite`] if a derivative overflows.
    pub fn eval_derivatives(&self, t: f64, order: usize) -> Result<Points> {
        check_unit(t)?;
        check_derivative_order(order, MAX_DERIVATIVE_ORDER)?;
        let n = self.degree();
        let dim = self.dim();
        let mut out = Points::zeros(order + 1, dim);
        // `hodograph` holds the control points of the k-th derivative (n − k + 1 of them)
        let mut hodograph = self.control.as_slice().to_vec();
        let mut scratch = vec![0.0; hodograph.len()];
        for k in 0..=order.min(n) {
            let len = (n - k + 1) * dim;
            de_casteljau_into(
                &hodograph[..len],
                dim,
                t,
                &mut scratch[..len],
                out.point_mut(k),
            );
            if k < n {
                let factor = (n - k) as f64;
                for i in 0..len - dim {
                    hodograph[i] = factor * (hodograph[i + dim] - hodograph[i]);
                }
            }
        }
        check_finite(
            "derivatives (overflow: rescale the control points)",
            out.as_slice(),
        )?;
        Ok(out)
    }

    /// The derivative curve (hodograph) `P'(t) = Σ_{i=0}^{n−1} b_{n−1,i}(t) · n (P_{i+1} − P_i)`,
    /// a Bezier curve of degree `n − 1` (the hodograph; P&T §1.3, derivative of a Bezier
    /// curve). The derivative of a degree-0 (constant)
    /// curve is the constant zero curve of degree 0.
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0]])?)?;
    /// let d = c.derivative();
    /// assert_eq!(d.control_points().as_slice(), &[2.0, 4.0, 4.0, 0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn derivative(&self) -> BezierCurve {
        let n = self.degree();
        let dim = self.dim();
        if n == 0 {
            return BezierCurve::from_raw(Points::zeros(1, dim));
        }
        let c = self.control.as_slice();
        let factor = n as f64;
        let data = (0..n * dim).map(|i| factor * (c[i + dim] - c[i])).collect();
        BezierCurve::from_raw(Points::from_raw(data, dim))
    }

    /// Subdivision at `t` by de Casteljau's algorithm (P&T §1.3 and §5.2; Farin, *Curves and
    /// Surfaces for CAGD*, "subdivision"): the left curve holds the first points `P_0^{(k)}` of
    /// each de Casteljau level, the right curve the last points `P_{n−k}^{(k)}`. The left curve
    /// reparametrised to `[0, 1]` is `P` on `[0, t]`, the right one is `P` on `[t, 1]`; both
    /// have the degree of `P`. O(n²·dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?)?;
    /// let (left, right) = c.split_at(0.5)?;
    /// assert_eq!(left.control_points().as_slice(), &[0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
    /// assert_eq!(right.control_points().as_slice(), &[1.0, 1.0, 1.5, 1.0, 2.0, 0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `0 ≤ t ≤ 1`; [`Error::InvalidArgument`] for
    /// `t = 0` or `t = 1` (one piece would be a single point).
    pub fn split_at(&self, t: f64) -> Result<(BezierCurve, BezierCurve)> {
        check_unit(t)?;
        if t == 0.0 || t == 1.0 {
            return Err(Error::InvalidArgument {
                what: "split parameter".into(),
                reason: format!(
                    "t = {t} is an end of [0, 1]; split strictly inside (0, 1)",
                    t = readable(&t)
                ),
            });
        }
        let n = self.degree();
        let dim = self.dim();
        let mut q = self.control.as_slice().to_vec();
        let mut left = vec![0.0; q.len()];
        let mut right = vec![0.0; q.len()];
        left[..dim].copy_from_slice(&q[..dim]);
        right[n * dim..].copy_from_slice(&q[n * dim..]);
        for k in 1..=n {
            for i in 0..=(n - k) {
                for d in 0..dim {
                    q[i * dim + d] = (1.0 - t) * q[i * dim + d] + t * q[(i + 1) * dim + d];
                }
            }
            left[k * dim..(k + 1) * dim].copy_from_slice(&q[..dim]);
            right[(n - k) * dim..(n - k + 1) * dim]
                .copy_from_slice(&q[(n - k) * dim..(n - k + 1) * dim]);
        }
        Ok((
            BezierCurve::from_raw(Points::from_raw(left, dim)),
            BezierCurve::from_raw(Points::from_raw(right, dim)),
        ))
    }

    /// The same curve as a clamped B-spline of degree `n` on the knots
    /// `[0, …, 0, 1, …, 1]` (`n + 1` copies each), whose basis functions are the Bernstein
    /// polynomials (P&T §2.2, property P2.1).
    ///
    /// ```
    /// use lekalo::{BezierCurve, Points};
    /// let c = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])?)?;
    /// let b = c.to_bspline();
    /// assert_eq!(b.knots().as_slice(), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    /// assert_eq!(b.eval(0.5)?, c.eval(0.5)?);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn to_bspline(&self) -> BSplineCurve {
        let n = self.degree();
        let mut knots = vec![0.0; n + 1];
        knots.resize(2 * n + 2, 1.0);
        BSplineCurve::from_raw(n, knots, self.control.clone())
    }
}

/// One polynomial piece of a B-spline curve: the Bezier curve `curve` reparametrised from
/// `[start, end]` to `[0, 1]`, i.e. the spline at `t ∈ [start, end]` equals
/// `curve` at `(t − start) / (end − start)`. Produced by
/// [`BSplineCurve::to_bezier_segments`] and consumed by
/// [`BSplineCurve::from_bezier_segments`] (which validates the fields).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BezierSegment {
    /// Start of the segment's parameter interval (a breakpoint of the spline).
    pub start: f64,
    /// End of the segment's parameter interval (`> start`).
    pub end: f64,
    /// The piece as a Bezier curve on `[0, 1]`.
    pub curve: BezierCurve,
}

impl BezierSegment {
    /// Point at the spline parameter `t ∈ [start, end]`: the curve at
    /// `(t − start) / (end − start)` (clamped to `[0, 1]` against rounding).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is outside `[start, end]` or NaN.
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        if !(t >= self.start && t <= self.end) {
            return Err(Error::ParameterOutOfDomain {
                t,
                min: self.start,
                max: self.end,
            });
        }
        let local = ((t - self.start) / (self.end - self.start)).clamp(0.0, 1.0);
        self.curve.eval(local)
    }
}

/// De Casteljau's algorithm (P&T A1.5) on `ctrl` (flat, `dim` per point) at `t`, using
/// `scratch` (same length as `ctrl`); writes `P(t)` into `out` (length `dim`). No allocation.
fn de_casteljau_into(ctrl: &[f64], dim: usize, t: f64, scratch: &mut [f64], out: &mut [f64]) {
    debug_assert!(
        scratch.len() == ctrl.len() && out.len() == dim && !ctrl.is_empty(),
        "de Casteljau buffer sizes"
    );
    scratch.copy_from_slice(ctrl);
    let n = ctrl.len() / dim - 1;
    for k in 1..=n {
        for i in 0..=(n - k) {
            for d in 0..dim {
                scratch[i * dim + d] =
                    (1.0 - t) * scratch[i * dim + d] + t * scratch[(i + 1) * dim + d];
            }
        }
    }
    out.copy_from_slice(&scratch[..dim]);
}

fn check_out(got: usize, dim: usize) -> Result<()> {
    if got != dim {
        return Err(Error::LengthMismatch {
            what: "output point (dimension)".into(),
            expected: dim,
            got,
        });
    }
    Ok(())
}

/// Checks `t ∈ [0, 1]` (NaN fails).
pub(crate) fn check_unit(t: f64) -> Result<()> {
    if !(0.0..=1.0).contains(&t) {
        return Err(Error::ParameterOutOfDomain {
            t,
            min: 0.0,
            max: 1.0,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn de_casteljau_equals_bernstein_sum() {
        let ctrl =
            Points::from_flat(3, (0..18).map(|i| (f64::from(i) * 0.7).cos()).collect()).unwrap();
        let c = BezierCurve::new(ctrl).unwrap();
        let mut out = vec![0.0; 3];
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            let a = c.eval(t).unwrap();
            c.eval_bernstein_into(t, &mut out).unwrap();
            for d in 0..3 {
                assert!((a[d] - out[d]).abs() < 1e-14, "t={t}");
            }
        }
        assert!(c.eval(-0.1).is_err() && c.eval(f64::NAN).is_err());
        assert!(matches!(
            BezierCurve::new(Points::from_flat(2, vec![]).unwrap()),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            c.eval_bernstein_into(0.5, &mut [0.0; 2]),
            Err(Error::LengthMismatch { .. })
        ));
    }

    /// Document 002, Bezier curves: the cubic written out.
    #[test]
    fn cubic_formula() {
        let c = BezierCurve::new(Points::from_flat(1, vec![1.0, 5.0, -2.0, 3.0]).unwrap()).unwrap();
        let t: f64 = 0.3;
        let s = 1.0 - t;
        let expect = s.powi(3) + 3.0 * 5.0 * t * s * s + 3.0 * -2.0 * t * t * s + 3.0 * t.powi(3);
        assert!((c.eval(t).unwrap()[0] - expect).abs() < 1e-14, "cubic");
    }
}
