//! Evaluation kernels of tensor-product B-splines at points: [`TensorBSplineRef`] (the spline's
//! degrees, knots and net borrowed, from a [`TensorBSpline`] or from caller's arrays), its
//! scratch, the window contraction (sum factorisation), the fixed-size kernel of trivariate
//! scalar splines, and batches (sequential, parallel, in cell order, and with the points beyond
//! the domain continued, clamped or `NaN`). Formulas: `docs/theory/tensor.md#tensor-product-splines`.

use rayon::prelude::*;

use crate::basis::{basis_ders_into, basis_funs_fixed, basis_funs_into, BasisScratch};
use crate::error::{check_derivative_order, check_finite, Error, Result, MAX_DERIVATIVE_ORDER};
use crate::knots::{check_width, span_in, KnotVector, SpanCursor};
use crate::tensor::spline::{check_len, check_n_vars, checked_size, TensorBSpline};

/// What a batch does at a point outside the domain (or with a coordinate that is not finite):
/// [`TensorBSplineRef::par_eval_batch_beyond`]. A point with a NaN or infinite coordinate gets
/// `NaN` values in every mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// The polynomials of the end spans continued (SciPy's `NdBSpline(..., extrapolate=True)`).
    Continue,
    /// Each coordinate taken at the nearest end of its domain (FITPACK's `fpbisp`, SciPy's
    /// `bisplev` and `RectBivariateSpline.ev`).
    Clamp,
    /// `NaN` values (SciPy's `extrapolate=False`).
    Nan,
}

/// How a batch treats the points: refuse those outside the domain, continue the end spans
/// (points checked finite before), or one of the [`Beyond`] rules.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Refuse,
    Extrapolate,
    Beyond(Beyond),
}

/// A tensor-product B-spline whose degrees, knot vectors and control net are borrowed: the
/// evaluation kernels of [`TensorBSpline`] on data held elsewhere (a [`TensorBSpline`] through
/// [`TensorBSpline::view`], or arrays of a caller, validated by [`TensorBSplineRef::new`] in
/// `O(Σ_a |T_a|)` without copying the net). Same layout and same formulas as
/// [`TensorBSpline`], so the same values bit for bit.
#[derive(Debug, Clone)]
pub struct TensorBSplineRef<'a> {
    pub(super) degrees: &'a [usize],
    pub(super) knots: Vec<&'a [f64]>,
    pub(super) shape: Vec<usize>,
    pub(super) net: &'a [f64],
    pub(super) dim: usize,
}

impl TensorBSpline {
    /// `S(x)` into `out` (`dim` numbers). One allocation (the scratch); for many points use
    /// [`TensorBSpline::eval_batch`].
    ///
    /// # Errors
    /// As [`TensorBSpline::eval`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_into(&self, x: &[f64], out: &mut [f64]) -> Result<()> {
        check_len("output (dim)", self.dim(), out.len())?;
        let view = self.view();
        let mut scratch = TensorScratch::new(&view, None)?;
        view.eval_with(x, None, &mut scratch, out)
    }

    /// The partial derivative `∂^{|k|} S / ∂x_0^{k_0} ⋯ ∂x_{N−1}^{k_{N−1}}` at `x`: the same
    /// contraction as [`TensorBSpline::eval`] with the basis vector of direction `a` replaced by
    /// the `k_a`-th derivatives of its basis functions (P&T Algorithm A2.3; a tensor product
    /// differentiates direction by direction, P&T §3.4). Orders above `p_a` give zero. At an
    /// interior knot the derivatives are right-hand ones (left-hand at the right end), as for
    /// curves. O(`Π_a (p_a + 1)·dim + Σ_a (k_a + 1)·p_a²`).
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y) = x² + y on [0, 1]²: degree 2 in x, 1 in y
    /// let net = Points::from_flat(1, vec![0.0, 1.0, 0.0, 1.0, 1.0, 2.0])?;
    /// let s = TensorBSpline::new(
    ///     vec![2, 1],
    ///     vec![vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
    ///     net,
    /// )?;
    /// let (x, y) = (0.3, 0.7);
    /// assert!((s.eval(&[x, y])?[0] - (x * x + y)).abs() < 1e-15);
    /// assert!((s.eval_partial(&[x, y], &[1, 0])?[0] - 2.0 * x).abs() < 1e-15);
    /// assert!((s.eval_partial(&[x, y], &[2, 0])?[0] - 2.0).abs() < 1e-14);
    /// assert_eq!(s.eval_partial(&[x, y], &[0, 2])?, vec![0.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`TensorBSpline::eval`]; [`Error::LengthMismatch`] if `orders.len() != N`;
    /// [`Error::TooLarge`] for an order above [`MAX_DERIVATIVE_ORDER`].
    pub fn eval_partial(&self, x: &[f64], orders: &[usize]) -> Result<Vec<f64>> {
        let view = self.view();
        let mut out = vec![0.0; self.dim()];
        let mut scratch = TensorScratch::new(&view, Some(orders))?;
        view.eval_with(x, Some(orders), &mut scratch, &mut out)?;
        Ok(out)
    }

    /// The spline borrowed as a [`TensorBSplineRef`] (no copy, no check).
    #[must_use]
    pub fn view(&self) -> TensorBSplineRef<'_> {
        TensorBSplineRef {
            degrees: &self.degrees,
            knots: self.knots.iter().map(KnotVector::as_slice).collect(),
            shape: self.shape.clone(),
            net: self.control.as_slice(),
            dim: self.control.dim(),
        }
    }
}

impl<'a> TensorBSplineRef<'a> {
    /// A borrowed spline of `degrees`, knot vectors `knots` and the flat net `net` (`dim`
    /// numbers a control point, first direction slowest), with the checks of
    /// [`TensorBSpline::new`] and [`KnotVector::new`] on the knots (`O(Σ_a |T_a|)`; the net is
    /// only measured).
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline, TensorBSplineRef};
    /// let k = [0.0, 0.0, 1.0, 1.0];
    /// let net = [0.0, 1.0, 2.0, 3.0];
    /// let view = TensorBSplineRef::new(&[1, 1], vec![&k, &k], &net, 1)?;
    /// let owned = TensorBSpline::new(vec![1, 1], vec![k.to_vec(), k.to_vec()], Points::from_flat(1, net.to_vec())?)?;
    /// assert_eq!(view.eval(&[0.25, 0.5])?, owned.eval(&[0.25, 0.5])?);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`TensorBSpline::new`]; [`Error::InvalidArgument`] for `dim = 0`.
    pub fn new(
        degrees: &'a [usize],
        knots: Vec<&'a [f64]>,
        net: &'a [f64],
        dim: usize,
    ) -> Result<Self> {
        check_n_vars(degrees.len())?;
        if knots.len() != degrees.len() {
            return Err(Error::LengthMismatch {
                what: "knot vectors (one per degree)",
                expected: degrees.len(),
                got: knots.len(),
            });
        }
        if dim == 0 {
            return Err(Error::InvalidArgument {
                what: "dim",
                reason: "a control point needs at least one number".into(),
            });
        }
        let mut shape = Vec::with_capacity(degrees.len());
        for (&t, &p) in knots.iter().zip(degrees) {
            let n = check_knots(t, p)?;
            shape.push(n);
        }
        let size = checked_size("control net (product of the net sizes)", &shape, dim)?;
        if net.len() != size {
            return Err(Error::LengthMismatch {
                what: "control net numbers (product of the net sizes knots[a].len() − degrees[a] − 1, times dim)",
                expected: size,
                got: net.len(),
            });
        }
        Ok(TensorBSplineRef {
            degrees,
            knots,
            shape,
            net,
            dim,
        })
    }

    /// Number of parameter directions `N`.
    #[must_use]
    pub fn n_vars(&self) -> usize {
        self.degrees.len()
    }

    /// Dimension of the values.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Degrees `p_a`, one per direction.
    #[must_use]
    pub fn degrees(&self) -> &[usize] {
        self.degrees
    }

    /// Net size `n_a` in each direction.
    #[must_use]
    pub fn shape(&self) -> &[usize] {
        &self.shape
    }

    /// Domain `[t_{p_a}, t_{n_a}]` of each direction.
    #[must_use]
    pub fn domain(&self) -> Vec<(f64, f64)> {
        self.knots
            .iter()
            .zip(self.degrees)
            .map(|(k, &p)| (k[p], k[k.len() - p - 1]))
            .collect()
    }

    /// Offset between consecutive indices of direction `a` in the flat net, in numbers.
    pub(crate) fn stride(&self, a: usize) -> usize {
        self.shape[a + 1..].iter().product::<usize>() * self.dim
    }

    /// `S(x)`, as [`TensorBSpline::eval`].
    ///
    /// # Errors
    /// As [`TensorBSpline::eval`].
    pub fn eval(&self, x: &[f64]) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim];
        let mut scratch = TensorScratch::new(self, None)?;
        self.eval_with(x, None, &mut scratch, &mut out)?;
        Ok(out)
    }

    /// As [`TensorBSpline::eval_batch`].
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_batch`].
    pub fn eval_batch(&self, xs: &[f64], orders: Option<&[usize]>, out: &mut [f64]) -> Result<()> {
        self.check_batch(xs, out)?;
        let mut scratch = TensorScratch::new(self, orders)?;
        self.batch_slice(xs, orders, Mode::Refuse, &mut scratch, out)
    }

    /// As [`TensorBSpline::par_eval_batch`].
    ///
    /// # Errors
    /// As [`TensorBSpline::par_eval_batch`].
    pub fn par_eval_batch(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        out: &mut [f64],
    ) -> Result<()> {
        self.par_batch(xs, orders, Mode::Refuse, out)
    }

    /// As [`TensorBSpline::par_eval_batch_extrapolated`].
    ///
    /// # Errors
    /// As [`TensorBSpline::par_eval_batch_extrapolated`].
    pub fn par_eval_batch_extrapolated(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        out: &mut [f64],
    ) -> Result<()> {
        check_finite("point coordinates", xs)?;
        self.par_batch(xs, orders, Mode::Extrapolate, out)
    }

    /// The values (or the partial derivative of `orders`) at every point of `xs`, whatever
    /// the point: a coordinate that is NaN or infinite gives `NaN` values; a finite point
    /// outside the domain is treated by `beyond` ([`Beyond`]); inside the domain the bits of
    /// [`TensorBSpline::eval`] (or `eval_partial`). Parallel above a few thousand points, as
    /// [`TensorBSpline::par_eval_batch`].
    ///
    /// ```
    /// use lekalo::tensor::Beyond;
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y) = x + y on [0, 1]²
    /// let k = vec![0.0, 0.0, 1.0, 1.0];
    /// let s = TensorBSpline::new(vec![1, 1], vec![k.clone(), k], Points::from_flat(1, vec![0.0, 1.0, 1.0, 2.0])?)?;
    /// let xs = [2.0, 0.5, f64::NAN, 0.0];
    /// let mut out = [0.0; 2];
    /// s.view().par_eval_batch_beyond(&xs, None, Beyond::Continue, &mut out)?;
    /// assert_eq!(out[0], 2.5);
    /// assert!(out[1].is_nan());
    /// s.view().par_eval_batch_beyond(&xs, None, Beyond::Clamp, &mut out)?;
    /// assert_eq!(out[0], 1.5);
    /// s.view().par_eval_batch_beyond(&xs, None, Beyond::Nan, &mut out)?;
    /// assert!(out[0].is_nan());
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `xs.len()` is not a multiple of `N`, if `out` does not hold
    /// `dim` numbers a point or `orders.len() != N`; [`Error::TooLarge`] for an order above
    /// [`MAX_DERIVATIVE_ORDER`].
    pub fn par_eval_batch_beyond(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        beyond: Beyond,
        out: &mut [f64],
    ) -> Result<()> {
        self.par_batch(xs, orders, Mode::Beyond(beyond), out)
    }

    fn par_batch(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        mode: Mode,
        out: &mut [f64],
    ) -> Result<()> {
        self.check_batch(xs, out)?;
        // validates the orders once, before the threads start
        let mut scratch = TensorScratch::new(self, orders)?;
        let (n, dim) = (self.n_vars(), self.dim);
        let points = xs.len() / n;
        if points < PAR_MIN_POINTS {
            return self.batch_slice(xs, orders, mode, &mut scratch, out);
        }
        if points >= SORT_MIN_POINTS
            && self.net.len() >= SORT_MIN_NET
            && n <= SORT_MAX_VARS
            && (mode != Mode::Refuse || self.all_inside(xs))
        {
            return self.par_batch_sorted(xs, orders, mode, out);
        }
        let chunk = points
            .div_ceil(4 * rayon::current_num_threads().max(1))
            .max(PAR_CHUNK);
        let results: Vec<Result<()>> = xs
            .par_chunks(chunk * n)
            .zip(out.par_chunks_mut(chunk * dim))
            .map(|(x, o)| {
                let mut scratch = TensorScratch::new(self, orders)?;
                self.batch_slice(x, orders, mode, &mut scratch, o)
            })
            .collect();
        results.into_iter().collect()
    }

    /// Whether every point of `xs` lies in the domain (then no point of the batch fails).
    fn all_inside(&self, xs: &[f64]) -> bool {
        let domains = self.domain();
        xs.chunks_exact(self.n_vars()).all(|x| {
            x.iter()
                .zip(&domains)
                .all(|(&t, &(lo, hi))| t >= lo && t <= hi)
        })
    }

    /// [`TensorBSplineRef::par_batch`] for a large batch on a large net, every point
    /// evaluable: the points are visited in the order of a coarse grid of cells over the domain
    /// ([`SORT_BINS`] per direction, the first direction slowest, as the net), so that
    /// consecutive points read neighbouring control points from the cache and the span
    /// searches start next to their answer. Each point is evaluated by the same kernel on the
    /// same numbers, so the values are the bits of the unsorted batch; only the order of the
    /// work changes. Memory: the permutation and a sorted copy of the points and values
    /// (`points·(2 + N + dim)` numbers).
    fn par_batch_sorted(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        mode: Mode,
        out: &mut [f64],
    ) -> Result<()> {
        let (n, dim) = (self.n_vars(), self.dim);
        let points = xs.len() / n;
        checked_size("sorted copy of the points", &[points], 2 + n + dim)?;
        let domains = self.domain();
        let bins = SORT_BINS as f64;
        let mut order: Vec<(u64, usize)> = xs
            .par_chunks_exact(n)
            .enumerate()
            .map(|(k, x)| {
                let mut key = 0u64;
                for (&t, &(lo, hi)) in x.iter().zip(&domains) {
                    let width = hi - lo;
                    let cell = if width > 0.0 {
                        ((t - lo) / width * bins).clamp(0.0, bins - 1.0)
                    } else {
                        0.0
                    };
                    // truncation of a number in [0, SORT_BINS − 1]; a NaN coordinate (a point
                    // whose values are NaN) saturates to cell 0
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    let cell = cell as u64;
                    key = key * SORT_BINS + cell;
                }
                (key, k)
            })
            .collect();
        order.par_sort_unstable_by_key(|&(key, _)| key);
        let mut sorted_xs = Vec::with_capacity(xs.len());
        for &(_, k) in &order {
            sorted_xs.extend_from_slice(&xs[k * n..(k + 1) * n]);
        }
        let mut sorted_out = vec![0.0; out.len()];
        let chunk = points
            .div_ceil(4 * rayon::current_num_threads().max(1))
            .max(PAR_CHUNK);
        let results: Vec<Result<()>> = sorted_xs
            .par_chunks(chunk * n)
            .zip(sorted_out.par_chunks_mut(chunk * dim))
            .map(|(x, o)| {
                let mut scratch = TensorScratch::new(self, orders)?;
                self.batch_slice(x, orders, mode, &mut scratch, o)
            })
            .collect();
        results.into_iter().collect::<Result<()>>()?;
        for (&(_, k), v) in order.iter().zip(sorted_out.chunks_exact(dim)) {
            out[k * dim..(k + 1) * dim].copy_from_slice(v);
        }
        Ok(())
    }

    pub(crate) fn check_batch(&self, xs: &[f64], out: &[f64]) -> Result<()> {
        let n = self.n_vars();
        if xs.len() % n != 0 {
            return Err(Error::LengthMismatch {
                what: "point coordinates (a multiple of the number of directions)",
                expected: xs.len() / n * n,
                got: xs.len(),
            });
        }
        check_len("output (points × dim)", xs.len() / n * self.dim, out.len())
    }

    /// The points of `xs` in order, each by [`locate`] then the kernel.
    fn batch_slice(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        mode: Mode,
        scratch: &mut TensorScratch,
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.n_vars();
        let mut cursors: Vec<_> = self
            .knots
            .iter()
            .zip(self.degrees)
            .map(|(k, &p)| SpanCursor::over(k, p))
            .collect();
        let domains = self.domain();
        if orders.is_none() && n == 3 && self.dim == 1 {
            let d = self.degrees;
            if d[1] == d[0] && d[2] == d[0] {
                let run = Batch3 {
                    s: self,
                    xs,
                    mode,
                    domains: &domains,
                };
                match d[0] {
                    1 => return run.values::<2>(&mut cursors, out),
                    2 => return run.values::<3>(&mut cursors, out),
                    3 => return run.values::<4>(&mut cursors, out),
                    4 => return run.values::<5>(&mut cursors, out),
                    5 => return run.values::<6>(&mut cursors, out),
                    _ => {}
                }
            }
        }
        let mut point = vec![0.0; n];
        for (x, o) in xs.chunks_exact(n).zip(out.chunks_exact_mut(self.dim)) {
            if !locate(
                mode,
                x,
                &domains,
                &mut cursors,
                &mut scratch.spans,
                &mut point,
            )? {
                o.fill(f64::NAN);
                continue;
            }
            scratch.fill_bases(self, &point, orders);
            self.contract_prepared(scratch, o);
        }
        Ok(())
    }

    /// The point kernel with the spans searched here.
    pub(crate) fn eval_with(
        &self,
        x: &[f64],
        orders: Option<&[usize]>,
        scratch: &mut TensorScratch,
        out: &mut [f64],
    ) -> Result<()> {
        check_len(
            "point coordinates (one per direction)",
            self.n_vars(),
            x.len(),
        )?;
        for (a, (k, &p)) in self.knots.iter().zip(self.degrees).enumerate() {
            let (min, max) = (k[p], k[k.len() - p - 1]);
            let t = x[a];
            if !(t >= min && t <= max) {
                return Err(Error::ParameterOutOfDomain { t, min, max });
            }
            scratch.spans[a] = span_in(k, p, t);
        }
        scratch.fill_bases(self, x, orders);
        self.contract_prepared(scratch, out);
        Ok(())
    }

    /// The contraction of the window ([`contract_window`]) with the spans and basis vectors
    /// already in `scratch`.
    pub(crate) fn contract_prepared(&self, scratch: &mut TensorScratch, out: &mut [f64]) {
        let TensorScratch {
            spans,
            values,
            offsets,
            stages,
            odometer,
            strides,
            ..
        } = scratch;
        let window = Window {
            spans,
            values,
            offsets,
            strides,
        };
        contract_window(self, &window, stages, odometer, out);
    }
}

/// The checks of [`KnotVector::new`] and [`KnotVector::validate_for`] on a borrowed knot vector
/// of a direction of degree `p`; its number of control points `n = |T| − p − 1`.
fn check_knots(t: &[f64], p: usize) -> Result<usize> {
    if t.len() < 2 {
        return Err(Error::TooFew {
            what: "knots",
            min: 2,
            got: t.len(),
        });
    }
    check_finite("knots", t)?;
    for i in 1..t.len() {
        if t[i] < t[i - 1] {
            return Err(Error::KnotsNotSorted {
                index: i,
                value: t[i],
                previous: t[i - 1],
            });
        }
    }
    let (first, last) = (t[0], t[t.len() - 1]);
    if first >= last {
        return Err(Error::EmptyDomain {
            min: first,
            max: last,
        });
    }
    check_width("knots", first, last)?;
    if t.len() / 2 <= p {
        return Err(Error::Degree {
            degree: p,
            reason: format!(
                "{} knots carry a degree of at most {}",
                t.len(),
                (t.len() / 2).saturating_sub(1)
            ),
        });
    }
    let max = p + 1;
    let mut run = 1;
    for i in 1..t.len() {
        run = if t[i] == t[i - 1] { run + 1 } else { 1 };
        if run > max {
            return Err(Error::KnotMultiplicity {
                knot: t[i],
                multiplicity: t[i..].iter().take_while(|&&v| v == t[i]).count() + run - 1,
                max,
            });
        }
    }
    let (min, max) = (t[p], t[t.len() - p - 1]);
    if min >= max {
        return Err(Error::EmptyDomain { min, max });
    }
    Ok(t.len() - p - 1)
}

/// The spans of the point `x` into `spans` and the coordinates at which the basis functions are
/// evaluated into `point`: `false` when the point's values are `NaN` ([`Beyond`] rules).
/// Inside the domain every mode finds the span of [`SpanCursor::find`] and evaluates at `x`.
///
/// # Errors
/// [`Error::ParameterOutOfDomain`] outside the domain in the refusing mode.
#[inline]
fn locate(
    mode: Mode,
    x: &[f64],
    domains: &[(f64, f64)],
    cursors: &mut [SpanCursor<'_>],
    spans: &mut [usize],
    point: &mut [f64],
) -> Result<bool> {
    if let Mode::Beyond(b) = mode {
        for (&t, &(lo, hi)) in x.iter().zip(domains) {
            if !t.is_finite() || (b == Beyond::Nan && !(t >= lo && t <= hi)) {
                return Ok(false);
            }
        }
    }
    for (a, c) in cursors.iter_mut().enumerate() {
        let (lo, hi) = domains[a];
        let t = x[a];
        spans[a] = match mode {
            Mode::Refuse => c.find(t)?,
            // finite, checked: the span of the nearest domain end
            _ => c.find_unchecked(t.clamp(lo, hi)),
        };
        point[a] = if mode == Mode::Beyond(Beyond::Clamp) {
            t.clamp(lo, hi)
        } else {
            t
        };
    }
    Ok(true)
}

/// A batch of values of a trivariate scalar spline of one degree `p ≤ 5` in every direction:
/// per point the three spans (searched from the previous point's), the basis vectors by the
/// fixed-order A2.2 ([`basis_funs_fixed`], the same operations in the same order as
/// [`basis_funs_into`]) and the fixed-size contraction [`contract3`], with no scratch and no
/// odometer. The same bits as the general kernel (tested); it is the whole cost of the
/// evaluation of a trivariate lookup table at scattered points.
struct Batch3<'a, 'b> {
    s: &'a TensorBSplineRef<'b>,
    xs: &'a [f64],
    mode: Mode,
    domains: &'a [(f64, f64)],
}

impl Batch3<'_, '_> {
    fn values<const W: usize>(
        &self,
        cursors: &mut [SpanCursor<'_>],
        out: &mut [f64],
    ) -> Result<()> {
        let s = self.s;
        let strides = [s.stride(0), s.stride(1)];
        let (k0, k1, k2) = (s.knots[0], s.knots[1], s.knots[2]);
        let p = W - 1;
        let mut spans = [0usize; 3];
        let mut x = [0.0; 3];
        for (xp, o) in self.xs.chunks_exact(3).zip(out.iter_mut()) {
            if !locate(self.mode, xp, self.domains, cursors, &mut spans, &mut x)? {
                *o = f64::NAN;
                continue;
            }
            let b0: [f64; W] = basis_funs_fixed(k0, spans[0], x[0]);
            let b1: [f64; W] = basis_funs_fixed(k1, spans[1], x[1]);
            let b2: [f64; W] = basis_funs_fixed(k2, spans[2], x[2]);
            let first = [spans[0] - p, spans[1] - p, spans[2] - p];
            *o = contract3::<W>(s.net, first, strides, &b0, &b1, &b2);
        }
        Ok(())
    }
}

/// Batches below this many points run on the calling thread (the thread pool's hand-over costs
/// more than it saves).
const PAR_MIN_POINTS: usize = 2048;
/// Batches of at least this many points on nets of at least [`SORT_MIN_NET`] numbers are
/// evaluated in the order of a coarse grid of cells ([`TensorBSplineRef::par_batch_sorted`]).
const SORT_MIN_POINTS: usize = 1 << 14;
/// Nets below this many numbers (256 KiB) stay in the cache whatever the order of the points.
const SORT_MIN_NET: usize = 1 << 15;
/// Cells per direction of the ordering grid.
const SORT_BINS: u64 = 64;
/// Directions whose cell indices fit one 64-bit key (6 bits each).
const SORT_MAX_VARS: usize = 10;

/// Points per parallel chunk at least (scratch set-up and scheduling amortised).
const PAR_CHUNK: usize = 256;

/// Scratch for point evaluation, sized once for a spline (and derivative orders): basis
/// scratch, the basis vectors of each direction, the contraction stages.
#[derive(Debug, Clone)]
pub(crate) struct TensorScratch {
    basis: Vec<BasisScratch>,
    /// Derivative table of one direction (`(k_a + 1) × (p_a + 1)`), for `eval_partial`.
    ders: Vec<f64>,
    pub(crate) spans: Vec<usize>,
    /// The basis vector (or its `k_a`-th derivative) of direction `a` at `offsets[a]..`.
    pub(crate) values: Vec<f64>,
    pub(crate) offsets: Vec<usize>,
    /// Stage `a` of the contraction: `Π_{b > a}(p_b + 1)·dim` numbers.
    stages: Vec<Vec<f64>>,
    odometer: Vec<usize>,
    /// [`TensorBSplineRef::stride`] of every direction.
    strides: Vec<usize>,
}

impl TensorScratch {
    /// # Errors
    /// [`Error::LengthMismatch`] if `orders` does not have one order per direction;
    /// [`Error::TooLarge`] for an order above [`MAX_DERIVATIVE_ORDER`].
    pub(crate) fn new(s: &TensorBSplineRef<'_>, orders: Option<&[usize]>) -> Result<Self> {
        let n = s.n_vars();
        let mut ders_len = 0;
        if let Some(k) = orders {
            check_len("derivative orders (one per direction)", n, k.len())?;
            for (&k, &p) in k.iter().zip(s.degrees) {
                check_derivative_order(k, MAX_DERIVATIVE_ORDER)?;
                ders_len = ders_len.max((k.min(p) + 1) * (p + 1));
            }
        }
        let mut offsets = Vec::with_capacity(n);
        let mut total = 0;
        for &p in s.degrees {
            offsets.push(total);
            total += p + 1;
        }
        let dim = s.dim;
        let stages = (1..n)
            .map(|a| vec![0.0; s.degrees[a..].iter().map(|p| p + 1).product::<usize>() * dim])
            .collect();
        Ok(TensorScratch {
            basis: s.degrees.iter().map(|&p| BasisScratch::new(p)).collect(),
            ders: vec![0.0; ders_len],
            spans: vec![0; n],
            values: vec![0.0; total],
            offsets,
            stages,
            odometer: vec![0; n],
            strides: (0..n).map(|a| s.stride(a)).collect(),
        })
    }

    /// The basis vectors of every direction at `x` (spans already in `self.spans`).
    pub(crate) fn fill_bases(
        &mut self,
        s: &TensorBSplineRef<'_>,
        x: &[f64],
        orders: Option<&[usize]>,
    ) {
        for a in 0..s.n_vars() {
            let p = s.degrees[a];
            let out = &mut self.values[self.offsets[a]..self.offsets[a] + p + 1];
            let k = orders.map_or(0, |k| k[a]);
            basis_vector(
                s.knots[a],
                p,
                self.spans[a],
                x[a],
                k,
                &mut self.basis[a],
                &mut self.ders,
                out,
            );
        }
    }
}

/// The `k`-th derivatives of the `p + 1` non-zero basis functions at `t` into `out`: A2.2 for
/// `k = 0`, row `k` of A2.3 for `0 < k ≤ p`, zeros above `p`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn basis_vector(
    knots: &[f64],
    p: usize,
    span: usize,
    t: f64,
    k: usize,
    scratch: &mut BasisScratch,
    ders: &mut [f64],
    out: &mut [f64],
) {
    if k == 0 {
        basis_funs_into(knots, p, span, t, scratch, out);
    } else if k > p {
        out.fill(0.0);
    } else {
        let table = &mut ders[..(k + 1) * (p + 1)];
        basis_ders_into(knots, p, span, t, k, scratch, table);
        out.copy_from_slice(&table[k * (p + 1)..]);
    }
}

/// `acc ← n·x` (first term) or `acc ← acc + n·x`, element by element: the one accumulation
/// step of every contraction in this module, so that the point, grid and slice paths perform
/// the same operations on each number.
#[inline(always)]
pub(crate) fn accumulate(acc: &mut [f64], n: f64, x: &[f64], first: bool) {
    if first {
        for (a, v) in acc.iter_mut().zip(x) {
            *a = n * v;
        }
    } else {
        for (a, v) in acc.iter_mut().zip(x) {
            *a += n * v;
        }
    }
}

/// The point's window: spans, basis vectors (direction `a` at `offsets[a]..`) and the net's
/// strides.
#[derive(Clone, Copy)]
struct Window<'a> {
    spans: &'a [usize],
    values: &'a [f64],
    offsets: &'a [usize],
    strides: &'a [usize],
}

/// Sum factorisation over the window of the spans: stage 1 contracts direction 0 straight
/// from the net, `B_1[r] = Σ_j N_0[j]·P[(s_0 − p_0 + j), r]` for `r` in the window of
/// directions `1…N−1` (walked by an odometer, the last direction contiguous); stage `a + 1`
/// contracts direction `a` of the dense stage `a`. The grid path performs the same operations
/// on each number (`grid_eval.rs`).
fn contract_window(
    s: &TensorBSplineRef<'_>,
    w: &Window<'_>,
    stages: &mut [Vec<f64>],
    odometer: &mut [usize],
    out: &mut [f64],
) {
    let Window {
        spans,
        values,
        offsets,
        strides,
    } = *w;
    let n = s.n_vars();
    let dim = s.dim;
    let net = s.net;
    let p0 = s.degrees[0];
    let n0 = &values[offsets[0]..offsets[0] + p0 + 1];
    let first0 = spans[0] - p0;
    let stride0 = strides[0];
    if n == 3 && dim == 1 {
        if let Some(v) = contract3_scalar(s, w) {
            out[0] = v;
            return;
        }
    }
    if n == 1 {
        for (j, &v) in n0.iter().enumerate() {
            let at = (first0 + j) * dim;
            accumulate(out, v, &net[at..at + dim], j == 0);
        }
        return;
    }
    // stage 1: odometer over the window of directions 1..n−1 except the last, runs of
    // (p_last + 1)·dim contiguous numbers
    let last = n - 1;
    let run = (s.degrees[last] + 1) * dim;
    let run_start = (spans[last] - s.degrees[last]) * dim;
    let stage1 = &mut stages[0];
    odometer.fill(0);
    let mut pos = 0;
    loop {
        let mut base = run_start;
        for b in 1..last {
            base += (spans[b] - s.degrees[b] + odometer[b]) * strides[b];
        }
        let acc = &mut stage1[pos..pos + run];
        for (j, &v) in n0.iter().enumerate() {
            let at = (first0 + j) * stride0 + base;
            accumulate(acc, v, &net[at..at + run], j == 0);
        }
        pos += run;
        // advance directions last−1 … 1
        let mut b = last;
        loop {
            b -= 1;
            if b == 0 {
                break;
            }
            odometer[b] += 1;
            if odometer[b] <= s.degrees[b] {
                break;
            }
            odometer[b] = 0;
        }
        if b == 0 {
            break;
        }
    }
    // stages 2..n: dense contractions of the leading direction of stage a into stage a + 1,
    // the last into `out`
    let contract = |a: usize, src: &[f64], dst: &mut [f64]| {
        let p = s.degrees[a];
        let na = &values[offsets[a]..offsets[a] + p + 1];
        let len = src.len() / (p + 1);
        for (j, &v) in na.iter().enumerate() {
            accumulate(dst, v, &src[j * len..(j + 1) * len], j == 0);
        }
    };
    for a in 1..last {
        let (done, next) = stages.split_at_mut(a);
        contract(a, &done[a - 1], &mut next[0]);
    }
    contract(last, &stages[last - 1], out);
}

/// [`contract_window`] for three directions, scalar values and one degree `p ≤ 5` in every
/// direction, with the window's sizes known at compile time: the same operations on each
/// number in the same order (so the same bits), without the odometer and the run-length loops.
/// Written out by hand because this contraction is the whole cost of a point of a trivariate
/// lookup table; `None` for the other cases.
fn contract3_scalar(s: &TensorBSplineRef<'_>, w: &Window<'_>) -> Option<f64> {
    let d = s.degrees;
    if d[1] != d[0] || d[2] != d[0] {
        return None;
    }
    let first = [w.spans[0] - d[0], w.spans[1] - d[1], w.spans[2] - d[2]];
    let basis = |a: usize| &w.values[w.offsets[a]..w.offsets[a] + d[a] + 1];
    let (b0, b1, b2) = (basis(0), basis(1), basis(2));
    let strides = [w.strides[0], w.strides[1]];
    Some(match d[0] {
        1 => contract3::<2>(s.net, first, strides, b0, b1, b2),
        2 => contract3::<3>(s.net, first, strides, b0, b1, b2),
        3 => contract3::<4>(s.net, first, strides, b0, b1, b2),
        4 => contract3::<5>(s.net, first, strides, b0, b1, b2),
        5 => contract3::<6>(s.net, first, strides, b0, b1, b2),
        _ => return None,
    })
}

/// The three stages of [`contract_window`] for `Q = p + 1` basis functions per direction and
/// `dim = 1`: `B_1[i_1][i_2] = Σ_j N_0[j]·P[f_0 + j][f_1 + i_1][f_2 + i_2]`, then
/// `B_2[i_2] = Σ_j N_1[j]·B_1[j][i_2]`, then `Σ_j N_2[j]·B_2[j]`, each sum from `j = 0` up
/// ([`accumulate`]'s order).
#[inline(always)]
fn contract3<const Q: usize>(
    net: &[f64],
    first: [usize; 3],
    strides: [usize; 2],
    n0: &[f64],
    n1: &[f64],
    n2: &[f64],
) -> f64 {
    let (n0, n1, n2): (&[f64; Q], &[f64; Q], &[f64; Q]) = (
        n0.try_into().expect("Q basis functions"),
        n1.try_into().expect("Q basis functions"),
        n2.try_into().expect("Q basis functions"),
    );
    let mut b1 = [[0.0; Q]; Q];
    for (i1, row) in b1.iter_mut().enumerate() {
        let base = first[2] + (first[1] + i1) * strides[1];
        for (j, &v) in n0.iter().enumerate() {
            let at = (first[0] + j) * strides[0] + base;
            let p: &[f64; Q] = net[at..at + Q].try_into().expect("a run of Q numbers");
            if j == 0 {
                for (r, x) in row.iter_mut().zip(p) {
                    *r = v * x;
                }
            } else {
                for (r, x) in row.iter_mut().zip(p) {
                    *r += v * x;
                }
            }
        }
    }
    let mut b2 = [0.0; Q];
    for (j, (&v, row)) in n1.iter().zip(&b1).enumerate() {
        if j == 0 {
            for (r, x) in b2.iter_mut().zip(row) {
                *r = v * x;
            }
        } else {
            for (r, x) in b2.iter_mut().zip(row) {
                *r += v * x;
            }
        }
    }
    let mut r = n2[0] * b2[0];
    for j in 1..Q {
        r += n2[j] * b2[j];
    }
    r
}
