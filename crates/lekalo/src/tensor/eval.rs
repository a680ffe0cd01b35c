//! Evaluation kernels of tensor-product B-splines at points: [`TensorBSplineRef`] (the spline's
//! degrees, knots and net borrowed, from a [`TensorBSpline`] or from caller's arrays), its
//! scratch, the window contraction (sum factorisation), the fixed-size kernel of trivariate
//! scalar splines, and batches (sequential, parallel, in cell order, and with the points beyond
//! the domain continued, clamped or `NaN`). Formulas: `docs/theory/tensor.md#tensor-product-splines`.

use rayon::prelude::*;

use crate::error::{check_finite, Error, Result};
use crate::knots::span_in;
use crate::tensor::cell_order::{bins_per_direction, CellOrder};
use crate::tensor::contract::TensorScratch;
use crate::tensor::fixed::Fixed;
use crate::tensor::locate::Beyond;
use crate::tensor::locate::{locate, Mode, SpanTable};
use crate::tensor::spline::{check_len, checked_size, TensorBSpline};
use crate::tensor::view::TensorBSplineRef;

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
}

impl TensorBSplineRef<'_> {
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
        let tables = self.span_tables();
        self.batch_slice(xs, orders, Mode::Refuse, &tables, &mut scratch, out)
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
    /// the point: a coordinate that is NaN gives `NaN` values, and so does an infinite one
    /// except under [`Beyond::Clamp`] (taken at the domain's end); a finite point outside the
    /// domain is treated by `beyond` ([`Beyond`]); inside the domain the bits of
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
    /// // an infinite coordinate: NaN, or taken at the domain's end when clamped (FITPACK)
    /// let ys = [f64::INFINITY, 0.5, f64::NEG_INFINITY, 0.25];
    /// s.view().par_eval_batch_beyond(&ys, None, Beyond::Clamp, &mut out)?;
    /// assert_eq!(out, [1.5, 0.25]);
    /// s.view().par_eval_batch_beyond(&ys, None, Beyond::Continue, &mut out)?;
    /// assert!(out[0].is_nan() && out[1].is_nan());
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
        let tables = self.span_tables();
        let n = self.n_vars();
        let points = xs.len() / n;
        if points < PAR_MIN_POINTS {
            return self.batch_slice(xs, orders, mode, &tables, &mut scratch, out);
        }
        if points >= SORT_MIN_POINTS
            && self.net.len() >= SORT_MIN_NET
            && n <= SORT_MAX_VARS
            && (mode != Mode::Refuse || self.all_inside(xs))
        {
            return self.par_batch_sorted(xs, orders, mode, &tables, out);
        }
        self.par_chunked(xs, orders, mode, &tables, out)
    }

    /// The points of `xs` in parallel chunks (four a thread, at least [`PAR_CHUNK`] points),
    /// each by [`TensorBSplineRef::batch_slice`] with its own scratch; the first error in the
    /// order of the points.
    fn par_chunked(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        mode: Mode,
        tables: &[SpanTable],
        out: &mut [f64],
    ) -> Result<()> {
        let (n, dim) = (self.n_vars(), self.dim);
        let chunk = (xs.len() / n)
            .div_ceil(4 * rayon::current_num_threads().max(1))
            .max(PAR_CHUNK);
        let results: Vec<Result<()>> = xs
            .par_chunks(chunk * n)
            .zip(out.par_chunks_mut(chunk * dim))
            .map(|(x, o)| {
                let mut scratch = TensorScratch::new(self, orders)?;
                self.batch_slice(x, orders, mode, tables, &mut scratch, o)
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
    /// evaluable: the points are visited in the cell order of [`CellOrder`] (a counting sort
    /// by the cell of a coarse grid over the domain, the first direction slowest, as the net),
    /// so that consecutive points read neighbouring control points from the cache and the
    /// span searches start next to their answer. Each point is evaluated by the same kernel on
    /// the same numbers, so the values are the bits of the unsorted batch; only the order of
    /// the work changes. Memory: the permutation and its inverse, and a sorted copy of the
    /// points and values (`points·(1 + N + dim)` numbers).
    fn par_batch_sorted(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        mode: Mode,
        tables: &[SpanTable],
        out: &mut [f64],
    ) -> Result<()> {
        let (n, dim) = (self.n_vars(), self.dim);
        let points = xs.len() / n;
        checked_size("sorted copy of the points", &[points], 1 + n + dim)?;
        let order = CellOrder::new(xs, n, &self.domain(), bins_per_direction(points, n));
        let mut sorted_xs = vec![0.0; xs.len()];
        order.gather(xs, n, &mut sorted_xs);
        let mut sorted_out = vec![0.0; out.len()];
        self.par_chunked(&sorted_xs, orders, mode, tables, &mut sorted_out)?;
        order.scatter_back(&sorted_out, dim, out);
        Ok(())
    }

    pub(crate) fn check_batch(&self, xs: &[f64], out: &[f64]) -> Result<()> {
        let n = self.n_vars();
        if xs.len() % n != 0 {
            return Err(Error::LengthMismatch {
                what: "point coordinates (a multiple of the number of directions)".into(),
                expected: xs.len() / n * n,
                got: xs.len(),
            });
        }
        check_len("output (points × dim)", xs.len() / n * self.dim, out.len())
    }

    /// The span table of every direction ([`SpanTable`]), built once a batch.
    fn span_tables(&self) -> Vec<SpanTable> {
        self.knots
            .iter()
            .zip(self.degrees)
            .map(|(k, &p)| SpanTable::new(k, p))
            .collect()
    }

    /// The points of `xs` in order, each by [`locate`] then the kernel: the fixed-size kernels
    /// of [`Fixed`] for scalar values in two or three directions of one degree `p ≤ 5`, the
    /// general kernel ([`TensorScratch`], [`contract_prepared`](Self::contract_prepared))
    /// otherwise.
    fn batch_slice(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        mode: Mode,
        tables: &[SpanTable],
        scratch: &mut TensorScratch,
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.n_vars();
        let domains = self.domain();
        let d = self.degrees;
        if orders.is_none() && (n == 2 || n == 3) && self.dim == 1 && d.iter().all(|&p| p == d[0]) {
            let run = Fixed {
                s: self,
                xs,
                mode,
                domains: &domains,
                tables,
            };
            macro_rules! fixed {
                ($w:literal) => {
                    if n == 2 {
                        run.values2::<$w>(out)
                    } else {
                        run.values3::<$w>(out)
                    }
                };
            }
            match d[0] {
                1 => return fixed!(2),
                2 => return fixed!(3),
                3 => return fixed!(4),
                4 => return fixed!(5),
                5 => return fixed!(6),
                _ => {}
            }
        }
        let mut point = vec![0.0; n];
        for (x, o) in xs.chunks_exact(n).zip(out.chunks_exact_mut(self.dim)) {
            if !locate(mode, x, &domains, tables, &mut scratch.spans, &mut point)? {
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
}

/// Batches below this many points run on the calling thread (the thread pool's hand-over costs
/// more than it saves).
const PAR_MIN_POINTS: usize = 2048;
/// Batches of at least this many points on nets of at least [`SORT_MIN_NET`] numbers are
/// evaluated in the order of a coarse grid of cells ([`TensorBSplineRef::par_batch_sorted`]).
const SORT_MIN_POINTS: usize = 1 << 14;
/// Nets below this many numbers (256 KiB) stay in the cache whatever the order of the points.
const SORT_MIN_NET: usize = 1 << 15;
/// Most directions of a batch in cell order (two cells a direction at least, at most
/// [`MAX_CELLS`](crate::tensor::cell_order::MAX_CELLS) cells).
const SORT_MAX_VARS: usize = 15;

/// Points per parallel chunk at least (scratch set-up and scheduling amortised).
const PAR_CHUNK: usize = 256;
