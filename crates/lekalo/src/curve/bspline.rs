//! Non-rational B-spline curves `C(t) = Σ_i N_{i,p}(t) P_i` of any degree and dimension:
//! evaluation (P&T A3.1, A3.2), the derivative curve (A3.3), reversal and affine
//! reparametrisation. Knot insertion (A5.1) and refinement (A5.4), splitting and Bezier
//! decomposition (the pieces of A5.6) are in `knot_insertion.rs`, knot removal in
//! `knot_removal.rs`.
//!
//! Knot conventions are those of [`crate::knots`]: domain `[t_p, t_{n+1}]`, half-open spans,
//! the right end evaluated by the last non-empty span. Every operation works for unclamped knot
//! vectors (such as the lecture's `[0, 0, 1, 2, 3, 3]`, document 002, B-splines) and acts on the
//! curve over its domain; knots of multiplicity `p + 1` (jumps) are allowed throughout.

use crate::Arg;
use serde::{Deserialize, Serialize};

use crate::basis::{basis_ders_into, basis_funs_fixed, basis_funs_into, BasisScratch};
use crate::error::{check_derivative_order, check_finite, Error, Result, MAX_DERIVATIVE_ORDER};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::Points;

/// What the progress reports and cancellation of a batch evaluation name.
const WHAT: &str = "B-spline curve evaluation";

/// A B-spline curve of degree `p` with control points `P_0 … P_n` on a knot vector of
/// `n + p + 2` knots. The degree is stored explicitly only to allow serialisation; it always
/// equals `knots.len() − control.len() − 1`.
///
/// ```
/// use lekalo::{BSplineCurve, Points};
/// // the lecture's example (document 002, B-splines): P(1.5) = (17/8, 11/4)
/// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
/// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap();
/// assert_eq!(c.domain(), (1.0, 2.0));
/// let p = c.eval(1.5).unwrap();
/// assert!((p[0] - 17.0 / 8.0).abs() < 1e-15 && (p[1] - 11.0 / 4.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BSplineCurveRepr", into = "BSplineCurveRepr")]
pub struct BSplineCurve {
    pub(super) degree: usize,
    pub(super) knots: KnotVector,
    pub(super) control: Points,
}

#[derive(Serialize, Deserialize)]
struct BSplineCurveRepr {
    degree: usize,
    knots: Vec<f64>,
    control: Points,
}

impl TryFrom<BSplineCurveRepr> for BSplineCurve {
    type Error = Error;
    fn try_from(r: BSplineCurveRepr) -> Result<Self> {
        BSplineCurve::new(r.degree, r.knots, r.control)
    }
}

impl From<BSplineCurve> for BSplineCurveRepr {
    fn from(c: BSplineCurve) -> Self {
        BSplineCurveRepr {
            degree: c.degree,
            knots: c.knots.into_vec(),
            control: c.control,
        }
    }
}

impl BSplineCurve {
    /// A B-spline curve from its degree, knots and control points.
    ///
    /// # Errors
    /// Knot errors of [`KnotVector::new`] and [`KnotVector::validate_for`]
    /// ([`Error::LengthMismatch`] if `knots.len() != n_ctrl + degree + 1`,
    /// [`Error::KnotMultiplicity`], [`Error::EmptyDomain`], [`Error::Degree`] if there are fewer
    /// than `degree + 1` control points).
    pub fn new(degree: usize, knots: impl Into<Vec<f64>>, control: Points) -> Result<Self> {
        let knots = KnotVector::new(knots.into())?;
        Self::from_knot_vector(degree, knots, control)
    }

    /// As [`BSplineCurve::new`] with an already validated [`KnotVector`].
    ///
    /// # Errors
    /// As [`KnotVector::validate_for`].
    pub fn from_knot_vector(degree: usize, knots: KnotVector, control: Points) -> Result<Self> {
        if control.is_empty() {
            return Err(Error::TooFew {
                what: Arg::ControlPoints.into(),
                min: degree.saturating_add(1),
                got: 0,
            });
        }
        knots.validate_for(degree, control.len())?;
        Ok(BSplineCurve {
            degree,
            knots,
            control,
        })
    }

    /// Trusted constructor for results built inside the crate (debug-checked).
    pub(crate) fn from_raw(degree: usize, knots: Vec<f64>, control: Points) -> Self {
        debug_assert_eq!(
            knots.len(),
            control.len() + degree + 1,
            "raw B-spline counts"
        );
        BSplineCurve {
            degree,
            knots: KnotVector::from_raw(knots),
            control,
        }
    }

    /// Degree `p` (order `p + 1`).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector.
    #[must_use]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points.
    #[must_use]
    pub fn control_points(&self) -> &Points {
        &self.control
    }

    /// Dimension of the curve's points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.control.dim()
    }

    /// The graph `t ↦ (t, y(t))` of a function `y` (this curve, 1-D) as a plane B-spline of the
    /// same degree and knots: its control points are `(ξ_i, c_i)` with the Greville abscissae
    /// `ξ_i = (t_{i+1} + … + t_{i+p}) / p`, exact because B-splines reproduce the linear
    /// function `t = Σ ξ_i N_{i,p}(t)` (de Boor, *A Practical Guide to Splines*, IX (36);
    /// for `p = 0`, `ξ_i` is the midpoint of the span and the graph is exact at those points only).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// let y = BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0],
    ///     Points::from_flat(1, vec![1.0, 3.0, 0.0, 2.0])?)?;
    /// let g = y.graph()?;
    /// let p = g.eval(1.5)?;
    /// assert!((p[0] - 1.5).abs() < 1e-15 && (p[1] - y.eval(1.5)?[0]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless the curve is 1-D.
    pub fn graph(&self) -> Result<BSplineCurve> {
        if self.dim() != 1 {
            return Err(Error::Dimension {
                what: "function for its graph".into(),
                expected: 1,
                got: self.dim(),
            });
        }
        let (p, t) = (self.degree, self.knots.as_slice());
        let mut ctrl = Vec::with_capacity(2 * self.control.len());
        for (i, c) in self.control.as_slice().iter().enumerate() {
            #[allow(clippy::cast_precision_loss)] // a degree
            let xi = if p == 0 {
                0.5 * (t[i] + t[i + 1])
            } else {
                t[i + 1..=i + p].iter().sum::<f64>() / p as f64
            };
            ctrl.extend([xi, *c]);
        }
        Ok(BSplineCurve::from_raw(
            p,
            t.to_vec(),
            Points::from_flat(2, ctrl)?,
        ))
    }

    /// Parameter domain `[t_p, t_{n+1}]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain(self.degree)
    }

    /// Decomposes into `(degree, knots, control points)`.
    #[must_use]
    pub fn into_parts(self) -> (usize, KnotVector, Points) {
        (self.degree, self.knots, self.control)
    }

    /// Point `C(t)`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is outside [`BSplineCurve::domain`] or NaN.
    pub fn eval(&self, t: f64) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(t, &mut out)?;
        Ok(out)
    }

    /// Point `C(t)` into `out` (length `dim`): span search, basis functions by the Cox–de Boor
    /// triangular scheme, and the combination of `p + 1` control points (P&T Algorithm A3.1).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_into(&self, t: f64, out: &mut [f64]) -> Result<()> {
        check_out(out.len(), self.dim())?;
        let span = self.knots.find_span(self.degree, t)?;
        let mut scratch = BasisScratch::new(self.degree);
        let mut n = vec![0.0; self.degree + 1];
        self.eval_span(span, t, &mut scratch, &mut n, out);
        Ok(())
    }

    /// Evaluates at a known span with caller-provided scratch (no allocation).
    pub(crate) fn eval_span(
        &self,
        span: usize,
        t: f64,
        scratch: &mut BasisScratch,
        n: &mut [f64],
        out: &mut [f64],
    ) {
        let p = self.degree;
        let dim = self.dim();
        basis_funs_into(self.knots.as_slice(), p, span, t, scratch, n);
        out.fill(0.0);
        let ctrl = self.control.as_slice();
        for (j, &nj) in n.iter().enumerate() {
            let base = (span - p + j) * dim;
            for (o, c) in out.iter_mut().zip(&ctrl[base..base + dim]) {
                *o += nj * c;
            }
        }
    }

    /// Evaluates at every parameter of `ts` into `out` (`ts.len() × dim`, point-major), without
    /// allocating per point. Sorted parameters take the amortised O(1) span search; any order is
    /// accepted.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
    /// let c = BSplineCurve::from_knot_vector(2, KnotVector::clamped_uniform(2, 4).unwrap(), ctrl).unwrap();
    /// let ts: Vec<f64> = (0..=10).map(|k| k as f64 / 10.0).collect();
    /// let mut out = vec![0.0; ts.len() * 2];
    /// c.eval_batch(&ts, &mut out).unwrap();
    /// assert_eq!(&out[20..22], &[4.0, 0.0]);
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`;
    /// [`Error::ParameterOutOfDomain`] at the first parameter outside the domain (nothing is
    /// guaranteed about `out` then).
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        self.eval_batch_with_progress(ts, out, &Progress::new())
    }

    /// [`BSplineCurve::eval_batch`] reporting to `progress` (`done` of `ts.len()` parameters)
    /// and stopping when it is cancelled. A point costs about `(p + 1)² + (p + 1)·dim`
    /// operations (P&T A2.2 and the sum), so the hook is called about every
    /// [`Progress::STRIDE`] of them. The points are bit-for-bit those of
    /// [`BSplineCurve::eval_batch`].
    ///
    /// # Errors
    /// As [`BSplineCurve::eval_batch`]; [`Error::Cancelled`] when `progress` is cancelled.
    pub fn eval_batch_with_progress(
        &self,
        ts: &[f64],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        let dim = self.dim();
        if out.len() != ts.len() * dim {
            return Err(Error::LengthMismatch {
                what: "output buffer (parameters × dimension)".into(),
                expected: ts.len() * dim,
                got: out.len(),
            });
        }
        match (self.degree, dim) {
            (1, 2) => self.eval_batch_fixed::<2, 2>(ts, out, progress),
            (1, 3) => self.eval_batch_fixed::<2, 3>(ts, out, progress),
            (2, 2) => self.eval_batch_fixed::<3, 2>(ts, out, progress),
            (2, 3) => self.eval_batch_fixed::<3, 3>(ts, out, progress),
            (3, 1) => self.eval_batch_fixed::<4, 1>(ts, out, progress),
            (3, 2) => self.eval_batch_fixed::<4, 2>(ts, out, progress),
            (3, 3) => self.eval_batch_fixed::<4, 3>(ts, out, progress),
            (3, 4) => self.eval_batch_fixed::<4, 4>(ts, out, progress),
            _ => self.eval_batch_generic(ts, out, progress),
        }
    }

    /// Operations per point of a batch evaluation, `(p + 1)² + (p + 1)·dim`, for
    /// [`Progress::items_per_step`].
    pub(crate) fn point_cost(&self) -> u64 {
        let w = self.degree as u64 + 1;
        w.saturating_mul(w.saturating_add(self.dim() as u64))
    }

    /// [`BSplineCurve::eval_batch`] for any degree and dimension.
    fn eval_batch_generic(
        &self,
        ts: &[f64],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        let mut cursor = self.knots.span_cursor(self.degree);
        let mut scratch = BasisScratch::new(self.degree);
        let mut n = vec![0.0; self.degree + 1];
        let mut outs = out.chunks_exact_mut(self.dim());
        progress.chunks(WHAT, ts, self.point_cost(), |ts| {
            for (&t, o) in ts.iter().zip(&mut outs) {
                let span = cursor.find(t)?;
                self.eval_span(span, t, &mut scratch, &mut n, o);
            }
            Ok(())
        })
    }

    /// [`BSplineCurve::eval_batch`] for order `W` (degree `W − 1`) and dimension `D` known at
    /// compile time: the generic path's operations in its order ([`basis_funs_fixed`], then
    /// the sum from zero over the control points), so the same bits, without the loops'
    /// bounds. Many small curves sampled a few times each (a Parquet batch) spend most of their
    /// evaluation here rather than in a per-curve set-up such as [`crate::CurveEvaluator`]'s.
    fn eval_batch_fixed<const W: usize, const D: usize>(
        &self,
        ts: &[f64],
        out: &mut [f64],
        progress: &Progress<'_>,
    ) -> Result<()> {
        let mut cursor = self.knots.span_cursor(W - 1);
        let knots = self.knots.as_slice();
        let ctrl = self.control.as_slice();
        let mut outs = out.chunks_exact_mut(D);
        progress.chunks(WHAT, ts, self.point_cost(), |ts| {
            for (&t, o) in ts.iter().zip(&mut outs) {
                let span = cursor.find(t)?;
                let n = basis_funs_fixed::<W>(knots, span, t);
                let net = &ctrl[(span + 1 - W) * D..(span + 1) * D];
                let mut p = [0.0; D];
                for (nj, c) in n.iter().zip(net.chunks_exact(D)) {
                    for (x, y) in p.iter_mut().zip(c) {
                        *x += nj * y;
                    }
                }
                o.copy_from_slice(&p);
            }
            Ok(())
        })
    }

    /// Derivatives `C^{(k)}(t)` for `k = 0..=order` (P&T Algorithm A3.2): returns
    /// `order + 1` points, row `k` the k-th derivative. Orders above the degree are zero. At an
    /// interior knot the derivatives are right-hand ones (left-hand at the right end).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`]; [`Error::TooLarge`] if `order > MAX_DERIVATIVE_ORDER`; [`Error::NonFinite`] if a derivative overflows.
    pub fn eval_derivatives(&self, t: f64, order: usize) -> Result<Points> {
        check_derivative_order(order, MAX_DERIVATIVE_ORDER)?;
        let p = self.degree;
        let dim = self.dim();
        let span = self.knots.find_span(p, t)?;
        let w = p + 1;
        let mut d = vec![0.0; (order + 1) * w];
        basis_ders_into(
            self.knots.as_slice(),
            p,
            span,
            t,
            order,
            &mut BasisScratch::new(p),
            &mut d,
        );
        let mut out = Points::zeros(order + 1, dim);
        let ctrl = self.control.as_slice();
        for k in 0..=order.min(p) {
            let row = out.point_mut(k);
            for j in 0..w {
                let base = (span - p + j) * dim;
                let c = d[k * w + j];
                for (o, x) in row.iter_mut().zip(&ctrl[base..base + dim]) {
                    *o += c * x;
                }
            }
        }
        check_finite(
            "derivatives (overflow: rescale the control points)",
            out.as_slice(),
        )?;
        Ok(out)
    }

    /// True if the first and last `p + 1` knots are equal, so that the curve starts at its first
    /// control point and ends at its last one.
    #[must_use]
    pub fn is_clamped(&self) -> bool {
        self.knots.is_clamped(self.degree)
    }

    /// Axis-aligned bounding box `(min, max)` of the control points. By the convex-hull property
    /// (P&T §3.2, strong convex hull property) it contains the curve on its domain.
    #[must_use]
    pub fn bounding_box(&self) -> (Vec<f64>, Vec<f64>) {
        debug_assert!(!self.control.is_empty(), "a curve has control points");
        self.control
            .bounding_box()
            .unwrap_or_else(|| (vec![0.0; self.dim()], vec![0.0; self.dim()]))
    }

    /// The derivative curve `C'(t) = Σ_{i=0}^{n−1} N_{i+1,p−1}(t) Q_i` with
    /// `Q_i = p (P_{i+1} − P_i) / (t_{i+p+1} − t_{i+1})` on the knots `t_1 … t_{m−1}`, of degree
    /// `p − 1` (P&T §3.3 and Algorithm A3.3). Where `t_{i+p+1} = t_{i+1}` (a knot of
    /// multiplicity `p + 1`, where the curve jumps) the basis function `N_{i+1,p−1}` vanishes
    /// identically; its control point and one copy of the knot are dropped, so the result is a
    /// valid spline (multiplicities ≤ `p`). The derivative curve has the same domain; at a knot it
    /// gives the right-hand derivative, as [`BSplineCurve::eval_derivatives`]. O(n·dim).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// // the lecture's example: on [1, 2], C(t) = (t²/2 + 1, −t² + 4t − 1), C'(t) = (t, 4 − 2t)
    /// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?;
    /// let d = c.derivative()?;
    /// assert_eq!(d.degree(), 1);
    /// assert_eq!(d.eval(1.5)?, vec![1.5, 1.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Degree`] for a degree-0 (piecewise constant) curve: its derivative is zero
    /// between the knots and undefined at its jumps, and degree −1 does not exist. (Use
    /// [`BSplineCurve::eval_derivatives`], which returns zero rows for orders above the degree.)
    /// [`Error::NonFinite`] if a control point of the derivative overflows.
    pub fn derivative(&self) -> Result<BSplineCurve> {
        let p = self.degree;
        if p == 0 {
            return Err(Error::Degree {
                degree: 0,
                reason: "a piecewise constant curve has no derivative curve (degree −1); \
                         eval_derivatives gives its zero derivative between the knots"
                    .into(),
            });
        }
        let dim = self.dim();
        let u = self.knots.as_slice();
        let c = self.control.as_slice();
        let n = self.control.len() - 1;
        let factor = p as f64;
        let mut ctrl = Vec::with_capacity(n * dim);
        let mut knots = Vec::with_capacity(u.len() - 2);
        let mut dropped: Vec<f64> = Vec::new();
        for i in 0..n {
            let denom = u[i + p + 1] - u[i + 1];
            if denom > 0.0 {
                let s = factor / denom;
                ctrl.extend((0..dim).map(|d| s * (c[(i + 1) * dim + d] - c[i * dim + d])));
            } else {
                dropped.push(u[i + 1]);
            }
        }
        // knots t_1 … t_{m−1}, minus one copy of each knot whose basis function vanished
        let mut drop_iter = dropped.iter().peekable();
        for &k in &u[1..u.len() - 1] {
            if drop_iter.peek().is_some_and(|&&x| x == k) {
                drop_iter.next();
            } else {
                knots.push(k);
            }
        }
        check_finite(
            "derivative control points (overflow: rescale the control points)",
            &ctrl,
        )?;
        let curve = BSplineCurve::from_raw(p - 1, knots, Points::from_raw(ctrl, dim));
        debug_assert!(
            curve.knots.validate_for(p - 1, curve.control.len()).is_ok(),
            "derivative curve must be valid"
        );
        Ok(curve)
    }

    /// The reversed curve `C̃(t) = C(a + b − t)` on the same domain `[a, b]`: control points in
    /// reverse order, knots `t̃_i = a + b − t_{m−i}` (standard; Open CASCADE
    /// `Geom_BSplineCurve::Reverse`). The ends of the domain map exactly onto each other; the
    /// other knots are rounded once.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?;
    /// let r = c.reverse()?;
    /// assert_eq!(r.domain(), (1.0, 2.0));
    /// assert_eq!(r.eval(1.0)?, c.eval(2.0)?);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// Only for knots at the limits of `f64`: [`Error::KnotMultiplicity`] if rounding merges
    /// distinct knots (knots closer than the rounding unit of the domain's scale);
    /// [`Error::NonFinite`] if a mapped knot outside the domain overflows.
    pub fn reverse(&self) -> Result<BSplineCurve> {
        let (a, b) = self.domain();
        // piecewise so that a ↔ b exactly and the map stays monotone under rounding
        let map = |t: f64| {
            if t <= a {
                b + (a - t)
            } else if t >= b {
                a - (t - b)
            } else {
                (b - (t - a)).clamp(a, b)
            }
        };
        let knots: Vec<f64> = self
            .knots
            .as_slice()
            .iter()
            .rev()
            .map(|&t| map(t))
            .collect();
        let dim = self.dim();
        let mut ctrl = Vec::with_capacity(self.control.as_slice().len());
        for pt in self.control.iter().rev() {
            ctrl.extend_from_slice(pt);
        }
        BSplineCurve::new(self.degree, knots, Points::from_raw(ctrl, dim))
    }

    /// The same curve on the domain `[a, b]`: the affine change of parameter
    /// `t̃ = a + (t − t_min)·(b − a)/(t_max − t_min)` applied to every knot (linear
    /// reparametrisation, P&T ch. 6), so `C̃(t̃) = C(t)`; control points are unchanged and
    /// derivatives scale by `(t_max − t_min)/(b − a)` per order. The ends of the domain map
    /// exactly to `a` and `b`.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?;
    /// let r = c.reparametrize(0.0, 10.0)?;
    /// assert_eq!(r.knots().as_slice(), &[-10.0, -10.0, 0.0, 10.0, 20.0, 20.0]);
    /// assert_eq!(r.eval(5.0)?, c.eval(1.5)?);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] if `a` or `b` (or a mapped knot) is not finite;
    /// [`Error::EmptyDomain`] if `a ≥ b`; [`Error::KnotMultiplicity`] if rounding merges
    /// distinct knots.
    pub fn reparametrize(&self, a: f64, b: f64) -> Result<BSplineCurve> {
        check_finite("new domain [a, b]", &[a, b])?;
        if a >= b {
            return Err(Error::EmptyDomain { min: a, max: b });
        }
        let (lo, hi) = self.domain();
        let scale = (b - a) / (hi - lo);
        let map = |t: f64| {
            if t <= lo {
                a - (lo - t) * scale
            } else if t >= hi {
                b + (t - hi) * scale
            } else {
                (a + (t - lo) * scale).clamp(a, b)
            }
        };
        let knots: Vec<f64> = self.knots.as_slice().iter().map(|&t| map(t)).collect();
        check_finite("reparametrised knots", &knots)?;
        BSplineCurve::new(self.degree, knots, self.control.clone())
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::basis_function_recursive;

    fn lecture() -> BSplineCurve {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
        BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap()
    }

    /// Document 002, B-splines: on [1,2) the curve is (t²/2 + 1, −t² + 4t − 1).
    #[test]
    fn lecture_curve_piece_on_domain() {
        let c = lecture();
        for k in 0..=20 {
            let t = 1.0 + k as f64 / 20.0;
            let p = c.eval(t).unwrap();
            assert!((p[0] - (0.5 * t * t + 1.0)).abs() < 1e-14, "x at {t}");
            assert!((p[1] - (-t * t + 4.0 * t - 1.0)).abs() < 1e-14, "y at {t}");
            let d = c.eval_derivatives(t, 3).unwrap();
            assert!((d.point(1)[0] - t).abs() < 1e-13, "x' at {t}");
            assert!(
                (d.point(1)[1] - (-2.0 * t + 4.0)).abs() < 1e-13,
                "y' at {t}"
            );
            assert!((d.point(2)[1] + 2.0).abs() < 1e-12, "y'' at {t}");
            assert_eq!(d.point(3), &[0.0, 0.0]);
        }
        // end points: midpoints of the control legs
        assert_eq!(c.eval(1.0).unwrap(), vec![1.5, 2.0]);
        assert_eq!(c.eval(2.0).unwrap(), vec![3.0, 3.0]);
        assert!(matches!(
            c.eval(0.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    proptest::proptest! {
        /// The monomorphised batch kernels give the generic kernel's bits for every degree and
        /// dimension they serve (and the generic cases stay generic), on random knots with
        /// repeated interior knots, at random parameters, the knots themselves and both ends.
        #[test]
        fn fixed_batch_kernels_give_the_generic_bits(
            degree in 1usize..=4,
            dim in 1usize..=4,
            grid in proptest::collection::vec(0u8..=8, 0..8),
            coords in proptest::collection::vec(-100.0f64..100.0, 64),
            random_ts in proptest::collection::vec(-1.0f64..2.0, 50),
        ) {
            // interior knots on a grid of eighths, so that some repeat
            let mut interior: Vec<f64> = grid.iter().map(|&g| f64::from(g) / 8.0 * 3.0 - 1.0).collect();
            interior.retain(|&k| k > -1.0 && k < 2.0);
            interior.sort_by(f64::total_cmp);
            let mut knots = vec![-1.0; degree + 1];
            knots.extend(&interior);
            knots.extend(std::iter::repeat_n(2.0, degree + 1));
            let n = knots.len() - degree - 1;
            let ctrl = coords[..n * dim].to_vec();
            let Ok(c) = BSplineCurve::new(degree, knots.clone(), Points::from_flat(dim, ctrl).unwrap()) else {
                return Ok(()); // an interior knot of multiplicity above the degree + 1
            };
            let mut ts = random_ts;
            ts.extend(&knots);
            ts.sort_by(f64::total_cmp);
            let (mut fast, mut generic) = (vec![0.0; ts.len() * dim], vec![0.0; ts.len() * dim]);
            c.eval_batch(&ts, &mut fast).unwrap();
            c.eval_batch_generic(&ts, &mut generic, &Progress::new()).unwrap();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            proptest::prop_assert_eq!(bits(&fast), bits(&generic));
            let before = ts.iter().copied().fold(f64::INFINITY, f64::min) - 1.0;
            let outside = c.eval_batch(&[0.5, before], &mut fast[..2 * dim]);
            proptest::prop_assert!(
                matches!(outside, Err(Error::ParameterOutOfDomain { .. })),
                "a parameter before the domain: {:?}",
                outside
            );
        }
    }

    #[test]
    fn absurd_derivative_orders_are_refused_before_allocating() {
        let c = lecture();
        assert!(matches!(
            c.eval_derivatives(1.5, usize::MAX),
            Err(Error::TooLarge { .. })
        ));
        let b = crate::BezierCurve::new(c.control_points().clone()).unwrap();
        assert!(matches!(
            b.eval_derivatives(0.5, usize::MAX),
            Err(Error::TooLarge { .. })
        ));
        assert_eq!(c.eval_derivatives(1.5, 1024).unwrap().len(), 1025);
    }

    #[test]
    fn constructor_errors() {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0]]).unwrap();
        assert!(matches!(
            BSplineCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0], ctrl.clone()),
            Err(Error::Degree { .. })
        ));
        assert!(matches!(
            BSplineCurve::new(1, vec![0.0, 0.0, 1.0], ctrl.clone()),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            BSplineCurve::new(1, vec![0.0, 1.0, 0.5, 1.0], ctrl),
            Err(Error::KnotsNotSorted { .. })
        ));
        let empty = Points::from_flat(2, vec![]).unwrap();
        assert!(matches!(
            BSplineCurve::new(1, vec![0.0, 1.0], empty),
            Err(Error::TooFew { .. })
        ));
    }

    #[test]
    fn batch_matches_single_and_oracle() {
        let ctrl = Points::from_flat(3, (0..21).map(|i| f64::from(i).sin()).collect()).unwrap();
        let kv =
            KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.2, 0.5, 1.0, 1.0, 1.0, 1.0]).unwrap();
        let c = BSplineCurve::from_knot_vector(3, kv.clone(), ctrl.clone()).unwrap();
        let ts: Vec<f64> = (0..=50).map(|k| f64::from(k) / 50.0).collect();
        let mut out = vec![0.0; ts.len() * 3];
        c.eval_batch(&ts, &mut out).unwrap();
        for (k, &t) in ts.iter().enumerate() {
            let single = c.eval(t).unwrap();
            assert_eq!(&out[3 * k..3 * k + 3], single.as_slice(), "t = {t}");
            for d in 0..3 {
                let oracle: f64 = (0..7)
                    .map(|i| basis_function_recursive(&kv, i, 3, t).unwrap() * ctrl.point(i)[d])
                    .sum();
                assert!((single[d] - oracle).abs() < 1e-13, "t = {t}");
            }
        }
        assert!(matches!(
            c.eval_batch(&ts, &mut out[1..]),
            Err(Error::LengthMismatch { .. })
        ));
        let mut o = vec![0.0; 3];
        assert!(matches!(
            c.eval_batch(&[f64::NAN], &mut o),
            Err(Error::ParameterOutOfDomain { .. })
        ));
    }

    #[test]
    fn serde_goes_through_validation() {
        let c = lecture();
        let s = serde_json::to_string(&c).unwrap();
        let back: BSplineCurve = serde_json::from_str(&s).unwrap();
        assert_eq!(back, c);
        let bad = s.replace("[0.0,0.0,1.0,2.0,3.0,3.0]", "[0.0,0.0,1.0,2.0,3.0]");
        assert!(serde_json::from_str::<BSplineCurve>(&bad).is_err());
    }

    proptest::proptest! {
        #[test]
        fn the_graph_of_a_function_is_t_and_its_value(
            degree in 1usize..5,
            inner in proptest::collection::vec(0.0..1.0_f64, 0..6),
            seed in 0u64..1000,
        ) {
            let mut t = vec![0.0; degree + 1];
            let mut inner = inner;
            inner.sort_by(f64::total_cmp);
            t.extend(inner);
            t.extend(vec![1.0; degree + 1]);
            let n = t.len() - degree - 1;
            #[allow(clippy::cast_precision_loss)]
            let c: Vec<f64> = (0..n).map(|i| ((i as u64 * 7919 + seed) % 97) as f64 / 10.0).collect();
            let Ok(y) = BSplineCurve::new(degree, t, Points::from_flat(1, c).unwrap()) else {
                return Ok(());
            };
            let g = y.graph().unwrap();
            for k in 0..=20 {
                let u = f64::from(k) / 20.0;
                let (p, v) = (g.eval(u).unwrap(), y.eval(u).unwrap()[0]);
                proptest::prop_assert!((p[0] - u).abs() < 1e-14, "x {} at {}", p[0], u);
                proptest::prop_assert!((p[1] - v).abs() < 1e-13, "y {} vs {}", p[1], v);
            }
        }
    }
}
