//! Fast batch evaluation of B-spline and NURBS curves, for many parameters at once.
//!
//! The reference path, [`BSplineCurve::eval_batch`], does for every parameter what
//! P&T *The NURBS Book* Algorithm A3.1 says: a span search, the `p + 1` basis functions by the
//! Cox–de Boor triangular scheme (Algorithm A2.2, `p(p + 1)/2` divisions) and their combination
//! with `p + 1` control points. A [`CurveEvaluator`] does the parameter-independent part of that
//! work once per curve:
//!
//! - **Piece location.** The distinct knots of the domain `x_0 < … < x_m` split it into `m`
//!   polynomial pieces, piece `j` on `[x_j, x_{j+1})` (the last also holds `x_m`): the same
//!   half-open convention as [`crate::KnotVector::find_span`]. A bucket table over the domain
//!   gives, for any parameter, the few pieces it can fall in, so that the search costs O(1) for
//!   reasonably spread knots and O(log m) at worst, in any order. Consecutive parameters in the
//!   same piece (sorted batches) skip the search after a one-comparison test against a ball
//!   strictly inside the piece.
//! - **Kernel [`EvalKernel::PowerForm`]** (default for degree ≤ [`POWER_FORM_MAX_DEGREE`]): each
//!   piece as a polynomial in the *local* parameter `u = (t − x_j) / (x_{j+1} − x_j) ∈ [0, 1]`,
//!   `C(t) = Σ_{k=0}^{p} c_k u^k` with `c_k = h_j^k C^{(k)}(x_j⁺) / k!` (Taylor's formula about the
//!   piece's left end, `h_j = x_{j+1} − x_j`; the derivatives by P&T Algorithm A2.3 once per
//!   piece), evaluated by Horner's scheme: `p·dim` multiply–adds per point. Expanding about the
//!   left knot and scaling by the piece's length keeps `|u| ≤ 1` and the coefficients bounded by
//!   `3^p` times the control net's scale however wide the span or large the knot values, which
//!   is what keeps this form accurate (see `docs/performance/kernels.md` for the measured error).
//! - **Kernel [`EvalKernel::Basis`]** (default for higher degrees, where the power form's
//!   rounding grows like `3^p`): Algorithm A2.2 with the reciprocals of the knot differences
//!   `1 / (t_{i+r+1} − t_{i+r+1−j})` precomputed per piece, so that a point costs no division.
//!
//! The default kernels agree with the reference to a few `1e-15` relative to the control net's scale
//! (the largest absolute control coordinate); the tests check `1e-14`. The opt-in parallel paths
//! (`par_*`, rayon) split the parameters into fixed chunks and run the sequential kernel on each,
//! so their results are bit-identical to the sequential fast path's.
//!
//! Monomorphised kernels (degree and dimension known at compile time) serve the common cases:
//! degree 1–3 in dimensions 2 and 3, cubics also in dimensions 1 and 4 (the basis kernel in
//! dimension 1 at degrees 1–3 too: SciPy's scalar splines), and NURBS of degree 2–3
//! in 2-D and 3-D (homogeneous dimension 3 and 4); everything else takes the generic kernel, which performs the same arithmetic.

use rayon::prelude::*;

use crate::basis::{basis_ders_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::{Error, Result};

mod kernels;
pub(crate) mod locate;
mod nurbs;

pub(crate) use kernels::{basis_by_reciprocals, basis_by_reciprocals_dyn, push_span_reciprocals};
use kernels::{basis_fixed, power_ders, power_dyn, power_fixed};
use locate::inner_ball;
pub(crate) use locate::PieceLocator;
pub use nurbs::NurbsEvaluator;

/// Highest degree for which [`EvalKernel::Auto`] chooses the power form. The power form's
/// rounding error grows like `3^p` times the control net's scale in the worst case; measured
/// against the reference (random, alternating ±1, offset by 10^6 and geometrically graded
/// knots, `docs/performance/kernels.md`) it stays below `3e-15` relative up to degree 3 but reaches
/// `6.7e-15` at degree 5 and `9e-13` at degree 9, so above degree 3 the basis kernel (below
/// `1.1e-15` at every degree) is the default.
pub const POWER_FORM_MAX_DEGREE: usize = 3;

/// Smallest number of parameters per task of the parallel paths. The task size may depend on
/// the thread count ([`par_chunk_len`]) because no result does: each point's arithmetic depends
/// only on its parameter and its piece (tested bit for bit against the sequential path).
const PAR_CHUNK: usize = 1 << 13;

/// Which per-piece representation a [`CurveEvaluator`] uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EvalKernel {
    /// Power form for degree ≤ [`POWER_FORM_MAX_DEGREE`] (and finite coefficients), basis
    /// functions otherwise.
    Auto,
    /// Per-piece power (Taylor) form in the local parameter, Horner's scheme.
    PowerForm,
    /// Cox–de Boor basis functions with precomputed reciprocals of knot differences.
    Basis,
}

/// What the `*_beyond` evaluations of a [`CurveEvaluator`] give at a parameter outside the
/// domain `[t_p, t_{n+1}]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// The polynomial of the first (last) piece continued to the left (right): the same
    /// function as [`BSplineCurve::eval_extrapolated`] (SciPy's `BSpline(extrapolate=True)`,
    /// FITPACK's `splev(ext=0)`).
    Continue,
    /// NaN in every coordinate (SciPy's `BSpline(extrapolate=False)`).
    Nan,
}

/// Per-piece data of the kernels.
#[derive(Debug, Clone)]
enum KernelData {
    /// Per piece `j` a block of `2 + (p+1)·dim` values, kept together so that a random
    /// parameter touches one place: `x_j`, `1 / h_j`, then at `2 + k·dim + d` the coefficient
    /// of `u^{p−k}`, coordinate `d` (highest power first, as Horner's scheme reads them).
    Power { coef: Vec<f64> },
    /// Knots and control points of the curve, and `recip[j·p(p+1)/2 + l(l−1)/2 + r]`:
    /// `1 / (t_{i+r+1} − t_{i+r+1−l})` for piece `j` with knot span `i`, level `l = 1..=p`,
    /// `r = 0..l` (the denominators of Algorithm A2.2).
    Basis {
        knots: Vec<f64>,
        control: Vec<f64>,
        recip: Vec<f64>,
    },
}

/// A B-spline curve prepared for fast evaluation at many parameters (piece location by a bucket
/// table, then a per-piece power form or basis functions with precomputed reciprocals; see
/// `docs/performance.md`): build it once with [`BSplineCurve::evaluator`], then
/// call [`CurveEvaluator::eval_batch`], [`CurveEvaluator::par_eval_batch`] or
/// [`CurveEvaluator::eval_derivatives_batch`] as often as needed.
///
/// ```
/// use lekalo::{BSplineCurve, KnotVector, Points};
/// let ctrl = Points::from_3d(&[[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [3.0, 2.0, 1.0], [4.0, 0.0, 2.0], [5.0, 1.0, 0.0]])?;
/// let curve = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 5)?, ctrl)?;
/// let fast = curve.evaluator();
/// let ts: Vec<f64> = (0..=100).map(|k| f64::from(k) / 100.0).collect();
/// let (mut a, mut b) = (vec![0.0; 303], vec![0.0; 303]);
/// fast.eval_batch(&ts, &mut a)?;
/// curve.eval_batch(&ts, &mut b)?; // the reference
/// let scale = curve.control_points().max_abs();
/// assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-14 * scale));
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct CurveEvaluator {
    degree: usize,
    dim: usize,
    /// Distinct knots of the domain, `x_0 < … < x_m`.
    breaks: Vec<f64>,
    /// `1 / (x_{j+1} − x_j)` per piece.
    inv_len: Vec<f64>,
    /// Knot span index `i` (`t_i = x_j < t_{i+1}`) per piece.
    spans: Vec<usize>,
    /// Per piece `(m_j, r_j)`: if `|t − m_j| < r_j` then certainly `x_j < t < x_{j+1}`
    /// (see [`inner_ball`]).
    balls: Vec<(f64, f64)>,
    locator: PieceLocator,
    kernel: KernelData,
}

impl BSplineCurve {
    /// A [`CurveEvaluator`] for this curve with the default kernel ([`EvalKernel::Auto`]).
    /// O(n·p²·dim) once.
    #[must_use]
    pub fn evaluator(&self) -> CurveEvaluator {
        CurveEvaluator::build(self, EvalKernel::Auto)
    }
}

impl CurveEvaluator {
    /// A [`CurveEvaluator`] with the given kernel.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if [`EvalKernel::PowerForm`] is asked for and a power-form
    /// coefficient overflows (control coordinates near `f64::MAX`); [`EvalKernel::Auto`] then
    /// falls back to the basis kernel.
    pub fn with_kernel(curve: &BSplineCurve, kernel: EvalKernel) -> Result<Self> {
        let ev = Self::build(curve, kernel);
        if kernel == EvalKernel::PowerForm && ev.kernel() != EvalKernel::PowerForm {
            return Err(Error::InvalidArgument {
                what: "evaluation kernel".into(),
                reason: "the power form's coefficients overflow for these control points; \
                         use EvalKernel::Basis or EvalKernel::Auto"
                    .into(),
            });
        }
        Ok(ev)
    }

    fn build(curve: &BSplineCurve, kernel: EvalKernel) -> Self {
        let p = curve.degree();
        let dim = curve.dim();
        let knots = curve.knots().as_slice();
        let n_ctrl = curve.control_points().len();
        let mut breaks = Vec::new();
        let mut spans = Vec::new();
        for i in p..n_ctrl {
            if knots[i] < knots[i + 1] {
                breaks.push(knots[i]);
                spans.push(i);
            }
        }
        debug_assert!(
            !spans.is_empty(),
            "validated curves have a non-empty domain"
        );
        breaks.push(knots[n_ctrl]);
        let inv_len: Vec<f64> = breaks.windows(2).map(|w| 1.0 / (w[1] - w[0])).collect();
        let locator = PieceLocator::new(&breaks);
        let balls = breaks.windows(2).map(|w| inner_ball(w[0], w[1])).collect();
        let mut ev = CurveEvaluator {
            degree: p,
            dim,
            breaks,
            inv_len,
            spans,
            balls,
            locator,
            kernel: KernelData::Power { coef: Vec::new() },
        };
        let want_power = match kernel {
            EvalKernel::Auto => p <= POWER_FORM_MAX_DEGREE,
            EvalKernel::PowerForm => true,
            EvalKernel::Basis => false,
        };
        ev.kernel = match want_power.then(|| ev.power_coefficients(curve)).flatten() {
            Some(coef) => KernelData::Power { coef },
            None => ev.basis_data(curve),
        };
        ev
    }

    /// Taylor coefficients `c_k = h^k C^{(k)}(x_j⁺) / k!` per piece (None on overflow).
    fn power_coefficients(&self, curve: &BSplineCurve) -> Option<Vec<f64>> {
        let p = self.degree;
        let dim = self.dim;
        let w = p + 1;
        let knots = curve.knots().as_slice();
        let ctrl = curve.control_points().as_slice();
        let stride = 2 + w * dim;
        let mut coef = vec![0.0; self.spans.len() * stride];
        let mut scratch = BasisScratch::new(p);
        let mut ders = vec![0.0; w * w];
        for (j, &span) in self.spans.iter().enumerate() {
            let x = self.breaks[j];
            let h = self.breaks[j + 1] - x;
            basis_ders_into(knots, p, span, x, p, &mut scratch, &mut ders);
            let block = &mut coef[j * stride..(j + 1) * stride];
            block[0] = x;
            block[1] = self.inv_len[j];
            let block = &mut block[2..];
            let mut factor = 1.0; // h^k / k!
            for k in 0..=p {
                let row = &mut block[(p - k) * dim..(p - k + 1) * dim];
                for r in 0..w {
                    let c = ders[k * w + r] * factor;
                    let base = (span - p + r) * dim;
                    for (o, &q) in row.iter_mut().zip(&ctrl[base..base + dim]) {
                        *o += c * q;
                    }
                }
                factor *= h / (k + 1) as f64;
            }
        }
        coef.iter().all(|c| c.is_finite()).then_some(coef)
    }

    fn basis_data(&self, curve: &BSplineCurve) -> KernelData {
        let p = self.degree;
        let knots = curve.knots().as_slice();
        let tri = p * (p + 1) / 2;
        let mut recip = Vec::with_capacity(self.spans.len() * tri);
        for &i in &self.spans {
            push_span_reciprocals(knots, p, i, &mut recip);
        }
        KernelData::Basis {
            knots: knots.to_vec(),
            control: curve.control_points().as_slice().to_vec(),
            recip,
        }
    }

    /// The kernel in use ([`EvalKernel::PowerForm`] or [`EvalKernel::Basis`], never `Auto`).
    #[must_use]
    pub fn kernel(&self) -> EvalKernel {
        match self.kernel {
            KernelData::Power { .. } => EvalKernel::PowerForm,
            KernelData::Basis { .. } => EvalKernel::Basis,
        }
    }

    /// Degree of the curve.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Dimension of the curve's points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Parameter domain `[t_p, t_{n+1}]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (self.breaks[0], self.breaks[self.breaks.len() - 1])
    }

    /// Number of polynomial pieces (non-empty knot spans in the domain).
    #[must_use]
    pub fn pieces(&self) -> usize {
        self.spans.len()
    }

    /// Knot span index of `t`, the same as [`crate::KnotVector::find_span`] but found through
    /// the bucket table: O(1) for spread-out knots, O(log n) at worst.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is outside the domain or NaN.
    pub fn find_span(&self, t: f64) -> Result<usize> {
        self.check_domain(t)?;
        Ok(self.spans[self.locator.find(&self.breaks, t)])
    }

    #[inline(always)]
    fn check_domain(&self, t: f64) -> Result<()> {
        let (min, max) = self.domain();
        if t >= min && t <= max {
            Ok(())
        } else {
            Err(Error::ParameterOutOfDomain { t, min, max })
        }
    }

    /// Points `C(t)` for every `t` in `ts` into `out` (`ts.len() × dim`, point-major), in any
    /// parameter order; the fast twin of [`BSplineCurve::eval_batch`] (same results to
    /// `1e-14` relative to the control net's scale). No allocation.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`;
    /// [`Error::ParameterOutOfDomain`] at the first parameter outside the domain (the points
    /// before it are written, nothing is guaranteed about the rest).
    pub fn eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        check_batch(ts.len(), self.dim, out.len())?;
        self.eval_slice(ts, out, None)
    }

    /// As [`CurveEvaluator::eval_batch`] for parameters anywhere on the real line: outside the
    /// domain the end pieces' polynomials are continued or NaN is written, as `beyond` says
    /// (the power form and the basis kernel are polynomials in `t`, so the kernels are the
    /// same; `docs/theory/curves.md#antiderivatives-integrals-and-extrapolation`). A NaN or
    /// infinite parameter gives a NaN point. No allocation.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Beyond, Points};
    /// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?;
    /// let fast = c.evaluator();
    /// let mut out = [0.0; 6];
    /// fast.eval_batch_beyond(&[-0.5, 1.5, f64::NAN], Beyond::Continue, &mut out)?;
    /// let want = c.eval_extrapolated(-0.5)?;
    /// assert!((out[0] - want[0]).abs() < 1e-14 && (out[1] - want[1]).abs() < 1e-14);
    /// assert!(out[4].is_nan() && out[5].is_nan());
    /// fast.eval_batch_beyond(&[-0.5, 1.5, 3.5], Beyond::Nan, &mut out)?;
    /// assert!(out[0].is_nan() && !out[2].is_nan() && out[5].is_nan());
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · dim`.
    pub fn eval_batch_beyond(&self, ts: &[f64], beyond: Beyond, out: &mut [f64]) -> Result<()> {
        check_batch(ts.len(), self.dim, out.len())?;
        self.eval_slice(ts, out, Some(beyond))
    }

    /// [`CurveEvaluator::eval_batch_beyond`] split over the current rayon thread pool as
    /// [`CurveEvaluator::par_eval_batch`] splits; the results are bit-identical to the
    /// sequential ones.
    ///
    /// # Errors
    /// As [`CurveEvaluator::eval_batch_beyond`].
    pub fn par_eval_batch_beyond(&self, ts: &[f64], beyond: Beyond, out: &mut [f64]) -> Result<()> {
        check_batch(ts.len(), self.dim, out.len())?;
        par_chunks(ts, out, self.dim, |t, o| {
            self.eval_slice(t, o, Some(beyond))
        })
    }

    /// As [`CurveEvaluator::eval_batch`], split over the current rayon thread pool in chunks of
    /// a fixed number of parameters; the results are bit-identical to the sequential ones. Run
    /// inside `rayon::ThreadPool::install` to choose the number of threads.
    ///
    /// On machines with few processors, pin the pool's workers to distinct processors
    /// (`ThreadPoolBuilder::start_handler`, e.g. with the `core_affinity` crate): Linux
    /// sometimes queues two freshly woken workers on one processor and leaves them there for
    /// milliseconds, which costs up to the whole speed-up (`docs/performance/kernels.md`,
    /// "Parallel evaluation and thread placement").
    ///
    /// # Errors
    /// As [`CurveEvaluator::eval_batch`] (the error of the first failing chunk).
    pub fn par_eval_batch(&self, ts: &[f64], out: &mut [f64]) -> Result<()> {
        check_batch(ts.len(), self.dim, out.len())?;
        par_chunks(ts, out, self.dim, |t, o| self.eval_slice(t, o, None))
    }

    /// Derivatives `C^{(k)}(t)`, `k = 0..=order`, for every `t` in `ts`, into `out` laid out
    /// `ts.len() × (order + 1) × dim` (for each parameter the rows of
    /// [`BSplineCurve::eval_derivatives`]). Orders above the degree are zero; at an interior
    /// knot the derivatives are right-hand ones (left-hand at the right end).
    ///
    /// Power form: Horner's scheme repeated as synthetic division (Knuth, TAOCP vol. 2,
    /// §4.6.4) gives the Taylor coefficients `a_k` at `u`, and `C^{(k)}(t) = k!·a_k / h^k`.
    /// Basis kernel: P&T Algorithm A2.3 per point. One allocation per call (scratch).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `out.len() != ts.len() · (order + 1) · dim`;
    /// [`Error::ParameterOutOfDomain`] at the first parameter outside the domain.
    pub fn eval_derivatives_batch(&self, ts: &[f64], order: usize, out: &mut [f64]) -> Result<()> {
        let row = (order + 1) * self.dim;
        check_batch(ts.len(), row, out.len())?;
        let p = self.degree;
        let dim = self.dim;
        match &self.kernel {
            KernelData::Power { coef } => {
                let kmax = order.min(p);
                macro_rules! fixed {
                    ($w:literal, $d:literal) => {
                        self.drive(ts, out, row, None, |j, t, o| {
                            let mut a = [0.0; $w];
                            power_ders(&mut a, $d, coef, j, t, kmax, o);
                        })
                    };
                }
                // the usual requests with the order a constant too (`power_ders` is inlined,
                // so every loop unrolls and the Taylor coefficients stay in registers). With a
                // run-time order they went through the stack: a 3-D cubic's point and 1st
                // derivative took 10.2 ns a parameter, now 3.5; with the 2nd, 13.2 → 4.9
                // (docs/performance.md)
                macro_rules! fixed_order {
                    ($w:literal, $d:literal, $k:literal) => {
                        self.drive(ts, out, row, None, |j, t, o| {
                            let mut a = [0.0; $w];
                            power_ders(&mut a, $d, coef, j, t, $k, o);
                        })
                    };
                }
                match (p, dim, order) {
                    (2, 2, 1) => fixed_order!(3, 2, 1),
                    (2, 3, 1) => fixed_order!(3, 3, 1),
                    (2, 2, 2) => fixed_order!(3, 2, 2),
                    (2, 3, 2) => fixed_order!(3, 3, 2),
                    (3, 2, 1) => fixed_order!(4, 2, 1),
                    (3, 3, 1) => fixed_order!(4, 3, 1),
                    (3, 2, 2) => fixed_order!(4, 2, 2),
                    (3, 3, 2) => fixed_order!(4, 3, 2),
                    (2, 2, _) => fixed!(3, 2),
                    (2, 3, _) => fixed!(3, 3),
                    (3, 2, _) => fixed!(4, 2),
                    (3, 3, _) => fixed!(4, 3),
                    _ => {
                        let mut a = vec![0.0; p + 1];
                        self.drive(ts, out, row, None, |j, t, o| {
                            power_ders(&mut a, dim, coef, j, t, kmax, o);
                        })
                    }
                }
            }
            KernelData::Basis { knots, control, .. } => {
                let w = p + 1;
                let mut scratch = BasisScratch::new(p);
                let mut d = vec![0.0; (order + 1) * w];
                self.drive(ts, out, row, None, |j, t, o| {
                    let span = self.spans[j];
                    basis_ders_into(knots, p, span, t, order, &mut scratch, &mut d);
                    o.fill(0.0);
                    for k in 0..=order.min(p) {
                        let orow = &mut o[k * dim..(k + 1) * dim];
                        for r in 0..w {
                            let c = d[k * w + r];
                            let base = (span - p + r) * dim;
                            for (x, &q) in orow.iter_mut().zip(&control[base..base + dim]) {
                                *x += c * q;
                            }
                        }
                    }
                })
            }
        }
    }

    /// The batch loop shared by all kernels: piece location (reusing the previous piece when
    /// the next parameter is in it), domain check, then `f(piece, t, out_row)`.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN must fail the ball test
    fn drive<F: FnMut(usize, f64, &mut [f64])>(
        &self,
        ts: &[f64],
        out: &mut [f64],
        row: usize,
        beyond: Option<Beyond>,
        mut f: F,
    ) -> Result<()> {
        let (mut j, (mut mid, mut radius)) = (0, self.balls[0]);
        for (&t, o) in ts.iter().zip(out.chunks_exact_mut(row)) {
            // One comparison, so one branch: `x_j <= t && t < x_{j+1}` compiles to two, and
            // for random parameters the first is a coin toss that the branch predictor loses
            // (cachegrind: 0.6 mispredictions per point). Parameters the ball misses (NaN,
            // outside the domain, another piece, within rounding of an end) take the exact
            // path.
            if !((t - mid).abs() < radius) {
                match self.piece_beyond(t, beyond)? {
                    Some(piece) => j = piece,
                    None => {
                        o.fill(f64::NAN);
                        continue;
                    }
                }
                (mid, radius) = self.balls[j];
            }
            f(j, t, o);
        }
        Ok(())
    }

    /// The piece that evaluates `t`: its own inside the domain; outside, the error (`beyond`
    /// None), the end piece (`Continue`, finite `t`) or none (NaN to be written).
    #[inline(always)]
    fn piece_beyond(&self, t: f64, beyond: Option<Beyond>) -> Result<Option<usize>> {
        let (min, max) = self.domain();
        if t >= min && t <= max {
            return Ok(Some(self.locator.find(&self.breaks, t)));
        }
        match beyond {
            None => self.check_domain(t).map(|()| None),
            Some(Beyond::Continue) if t.is_finite() => {
                Ok(Some(if t < min { 0 } else { self.spans.len() - 1 }))
            }
            Some(_) => Ok(None),
        }
    }

    /// Points into `out`, choosing a monomorphised kernel where there is one.
    fn eval_slice(&self, ts: &[f64], out: &mut [f64], beyond: Option<Beyond>) -> Result<()> {
        match &self.kernel {
            KernelData::Power { coef } => {
                macro_rules! fixed {
                    ($p:literal, $d:literal) => {
                        self.drive(ts, out, $d, beyond, |j, t, o| {
                            power_fixed::<$p, $d>(coef, j, t, o);
                        })
                    };
                }
                match (self.degree, self.dim) {
                    (1, 2) => fixed!(1, 2),
                    (1, 3) => fixed!(1, 3),
                    (2, 2) => fixed!(2, 2),
                    (2, 3) => fixed!(2, 3),
                    (3, 1) => fixed!(3, 1),
                    (3, 2) => fixed!(3, 2),
                    (3, 3) => fixed!(3, 3),
                    (3, 4) => fixed!(3, 4),
                    _ => self.drive(ts, out, self.dim, beyond, |j, t, o| {
                        power_dyn(self.degree, coef, j, t, o);
                    }),
                }
            }
            KernelData::Basis {
                knots,
                control,
                recip,
            } => {
                macro_rules! fixed {
                    ($w:literal, $d:literal) => {
                        self.drive(ts, out, $d, beyond, |j, t, o| {
                            basis_fixed::<$w, $d>(knots, control, recip, self.spans[j], j, t, o);
                        })
                    };
                }
                match (self.degree, self.dim) {
                    (1, 1) => fixed!(2, 1),
                    (2, 1) => fixed!(3, 1),
                    (3, 1) => fixed!(4, 1),
                    (3, 2) => fixed!(4, 2),
                    (3, 3) => fixed!(4, 3),
                    (4, 2) => fixed!(5, 2),
                    (4, 3) => fixed!(5, 3),
                    (5, 2) => fixed!(6, 2),
                    (5, 3) => fixed!(6, 3),
                    (6, 3) => fixed!(7, 3),
                    (7, 3) => fixed!(8, 3),
                    _ => {
                        let mut n = vec![0.0; 3 * (self.degree + 1)];
                        self.drive(ts, out, self.dim, beyond, |j, t, o| {
                            self.basis_point(knots, control, recip, j, t, &mut n, o);
                        })
                    }
                }
            }
        }
    }

    /// One point by Algorithm A2.2 with precomputed reciprocals, then A3.1's combination.
    /// `n` is scratch of length `3(p + 1)`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn basis_point(
        &self,
        knots: &[f64],
        control: &[f64],
        recip: &[f64],
        j: usize,
        t: f64,
        n: &mut [f64],
        o: &mut [f64],
    ) {
        let p = self.degree;
        let dim = self.dim;
        let i = self.spans[j];
        let tri = p * (p + 1) / 2;
        basis_by_reciprocals_dyn(knots, &recip[j * tri..(j + 1) * tri], p, i, t, n);
        let nv = &n[..=p];
        o.fill(0.0);
        for (r, &nr) in nv.iter().enumerate() {
            let base = (i - p + r) * dim;
            for (x, &q) in o.iter_mut().zip(&control[base..base + dim]) {
                *x += nr * q;
            }
        }
    }
}

fn check_batch(n: usize, row: usize, got: usize) -> Result<()> {
    let expected = n * row;
    if got != expected {
        return Err(Error::LengthMismatch {
            what: "output buffer (parameters × values per parameter)".into(),
            expected,
            got,
        });
    }
    Ok(())
}

/// Runs `f` on fixed-size chunks of `(ts, out)` in parallel; the first failing chunk's error.
/// Parameters per parallel task: about four tasks per thread (enough for work stealing to even
/// out a slow core) but never fewer than [`PAR_CHUNK`], so that the per-task cost (a piece
/// search, a wake-up) stays negligible. The split does not change any result: every point is
/// computed by the same sequential kernel from its own parameter.
fn par_chunk_len(len: usize, threads: usize) -> usize {
    len.div_ceil(4 * threads.max(1)).max(PAR_CHUNK)
}

fn par_chunks<F>(ts: &[f64], out: &mut [f64], row: usize, f: F) -> Result<()>
where
    F: Fn(&[f64], &mut [f64]) -> Result<()> + Sync,
{
    let chunk = par_chunk_len(ts.len(), rayon::current_num_threads());
    let results: Vec<Result<()>> = ts
        .par_chunks(chunk)
        .zip(out.par_chunks_mut(chunk * row))
        .map(|(t, o)| f(t, o))
        .collect();
    results.into_iter().collect()
}

#[cfg(test)]
mod tests;
