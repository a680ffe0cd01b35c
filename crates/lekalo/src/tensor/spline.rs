//! [`TensorBSpline`]: the type, its validation, and evaluation at points (values, partial
//! derivatives, batches). Formulas: `docs/theory/tensor.md#tensor-product-splines`.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::basis::{basis_ders_into, basis_funs_fixed, basis_funs_into, BasisScratch};
use crate::error::{
    check_derivative_order, check_finite, Error, Result, MAX_DERIVATIVE_ORDER, MAX_SCALARS,
};
use crate::knots::KnotVector;
use crate::points::Points;

/// A tensor-product B-spline in `N ≥ 1` parameters `x = (x_0, …, x_{N−1})` with values of any
/// dimension:
///
/// `S(x) = Σ_{i_0} … Σ_{i_{N−1}} N_{i_0,p_0}(x_0) ⋯ N_{i_{N−1},p_{N−1}}(x_{N−1}) · P_{i_0…i_{N−1}}`
///
/// (P&T §3.4 for `N = 2`, here in any number of directions; `docs/theory/tensor.md`). Direction
/// `a` has its own degree `p_a`, knot vector `T_a` (`n_a + p_a + 1` knots, any valid vector:
/// clamped or not) and `n_a` control points. The net `P` is stored flat and point-major with the
/// first index slowest, as the surface net: `P_{i_0…i_{N−1}}` starts at
/// `((…(i_0·n_1 + i_1)·n_2 + …)·n_{N−1} + i_{N−1})·dim`. For `N = 2` this is exactly the
/// layout of [`BSplineSurface`](crate::BSplineSurface) (`(i·nv + j)·dim`), for `N = 1` that of
/// [`BSplineCurve`](crate::BSplineCurve). A NURBS is this type over homogeneous points
/// ([`TensorNurbs`](crate::TensorNurbs)).
///
/// Evaluation contracts the `(p_0 + 1)⋯(p_{N−1} + 1)` control points of the point's window
/// with the `N` basis vectors one direction at a time, the first direction first (sum
/// factorisation): `O(Π_a (p_a + 1)·dim)` per point, plus `O(Σ_a p_a²)` for the bases.
///
/// Deserialisation goes through [`TensorBSpline::new`].
///
/// ```
/// use lekalo::{Points, TensorBSpline};
/// // the trilinear function f(x, y, z) = x·y·z on [0, 1]³: corners 0 except P_111 = 1
/// let mut net = vec![0.0; 8];
/// net[7] = 1.0;
/// let k = vec![0.0, 0.0, 1.0, 1.0];
/// let s = TensorBSpline::new(vec![1, 1, 1], vec![k.clone(), k.clone(), k], Points::from_flat(1, net)?)?;
/// assert_eq!(s.shape(), &[2, 2, 2]);
/// assert_eq!(s.eval(&[0.5, 0.5, 0.5])?, vec![0.125]);
/// // ∂³f/∂x∂y∂z = 1
/// assert_eq!(s.eval_partial(&[0.3, 0.6, 0.2], &[1, 1, 1])?, vec![1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "TensorBSplineRepr", into = "TensorBSplineRepr")]
pub struct TensorBSpline {
    pub(super) degrees: Vec<usize>,
    pub(super) knots: Vec<KnotVector>,
    /// `n_a = |T_a| − p_a − 1` (derived, kept for the index arithmetic).
    pub(super) shape: Vec<usize>,
    pub(super) control: Points,
}

#[derive(Serialize, Deserialize)]
struct TensorBSplineRepr {
    degrees: Vec<usize>,
    knots: Vec<Vec<f64>>,
    control: Points,
}

impl TryFrom<TensorBSplineRepr> for TensorBSpline {
    type Error = Error;
    fn try_from(r: TensorBSplineRepr) -> Result<Self> {
        TensorBSpline::new(r.degrees, r.knots, r.control)
    }
}

impl From<TensorBSpline> for TensorBSplineRepr {
    fn from(s: TensorBSpline) -> Self {
        TensorBSplineRepr {
            degrees: s.degrees,
            knots: s.knots.into_iter().map(KnotVector::into_vec).collect(),
            control: s.control,
        }
    }
}

/// Number of entries of a net of `shape` with `dim` numbers a point, refused above
/// [`MAX_SCALARS`] (checked multiplication: nothing is allocated for a size that overflows).
///
/// # Errors
/// [`Error::TooLarge`] naming `what` and the size (saturated at `usize::MAX` on overflow).
pub(crate) fn checked_size(what: &'static str, shape: &[usize], dim: usize) -> Result<usize> {
    let size = shape
        .iter()
        .try_fold(dim, |acc, &n| acc.checked_mul(n))
        .filter(|&s| s <= MAX_SCALARS);
    size.ok_or_else(|| Error::TooLarge {
        what,
        size: shape.iter().fold(dim, |acc, &n| acc.saturating_mul(n)),
        max: MAX_SCALARS,
    })
}

/// Refuses zero parameter directions.
///
/// # Errors
/// [`Error::TooFew`].
pub(crate) fn check_n_vars(n: usize) -> Result<()> {
    if n == 0 {
        return Err(Error::TooFew {
            what: "parameter directions",
            min: 1,
            got: 0,
        });
    }
    Ok(())
}

impl TensorBSpline {
    /// A tensor-product B-spline from its degrees, knot vectors and control net (one degree and
    /// one knot vector per direction; the net size `n_a = knots[a].len() − degrees[a] − 1` is
    /// derived, the first direction slowest in `control`).
    ///
    /// ```
    /// use lekalo::{Error, Points, TensorBSpline};
    /// let net = Points::from_flat(1, vec![0.0; 6])?;
    /// let k2 = vec![0.0, 0.0, 1.0, 1.0];
    /// let k3 = vec![0.0, 0.0, 0.5, 1.0, 1.0];
    /// assert!(TensorBSpline::new(vec![1, 1], vec![k2.clone(), k3.clone()], net.clone()).is_ok());
    /// // a net of 2 × 3 points cannot carry these knots with a third direction
    /// let e = TensorBSpline::new(vec![1, 1, 1], vec![k2.clone(), k3, k2], net).unwrap_err();
    /// assert!(matches!(e, Error::LengthMismatch { expected: 12, got: 6, .. }));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// - [`Error::TooFew`] for zero directions;
    /// - [`Error::LengthMismatch`] if `degrees` and `knots` differ in length, or if `control`
    ///   does not hold `Π_a n_a` points;
    /// - [`Error::Degree`] if a knot vector is too short for its degree (fewer than
    ///   `2·p_a + 2` knots);
    /// - [`Error::TooLarge`] if `Π_a n_a · dim` overflows or exceeds [`MAX_SCALARS`];
    /// - knot errors of [`KnotVector::new`] ([`Error::NonFinite`], [`Error::KnotsNotSorted`],
    ///   [`Error::KnotMultiplicity`], [`Error::EmptyDomain`]).
    pub fn new(degrees: Vec<usize>, knots: Vec<Vec<f64>>, control: Points) -> Result<Self> {
        let knots = knots
            .into_iter()
            .map(KnotVector::new)
            .collect::<Result<Vec<_>>>()?;
        Self::from_knot_vectors(degrees, knots, control)
    }

    /// As [`TensorBSpline::new`] with already validated knot vectors.
    ///
    /// # Errors
    /// As [`TensorBSpline::new`].
    pub fn from_knot_vectors(
        degrees: Vec<usize>,
        knots: Vec<KnotVector>,
        control: Points,
    ) -> Result<Self> {
        check_n_vars(degrees.len())?;
        if knots.len() != degrees.len() {
            return Err(Error::LengthMismatch {
                what: "knot vectors (one per degree)",
                expected: degrees.len(),
                got: knots.len(),
            });
        }
        let mut shape = Vec::with_capacity(degrees.len());
        for (kv, &p) in knots.iter().zip(&degrees) {
            kv.check_degree(p)?;
            // check_degree: len ≥ 2p + 2, so the subtraction cannot wrap
            let n = kv.len() - p - 1;
            kv.validate_for(p, n)?;
            shape.push(n);
        }
        let size = checked_size("control net (product of the net sizes)", &shape, 1)?;
        if control.len() != size {
            return Err(Error::LengthMismatch {
                what: "control points (product of the net sizes knots[a].len() − degrees[a] − 1)",
                expected: size,
                got: control.len(),
            });
        }
        Ok(TensorBSpline {
            degrees,
            knots,
            shape,
            control,
        })
    }

    /// Trusted constructor for results built inside the crate (debug-checked).
    pub(crate) fn from_raw(degrees: Vec<usize>, knots: Vec<KnotVector>, control: Points) -> Self {
        let shape: Vec<usize> = knots
            .iter()
            .zip(&degrees)
            .map(|(k, p)| k.len() - p - 1)
            .collect();
        debug_assert_eq!(
            control.len(),
            shape.iter().product::<usize>(),
            "raw tensor net size"
        );
        TensorBSpline {
            degrees,
            knots,
            shape,
            control,
        }
    }

    /// Number of parameter directions `N`.
    #[must_use]
    pub fn n_vars(&self) -> usize {
        self.degrees.len()
    }

    /// Degrees `p_a`, one per direction.
    #[must_use]
    pub fn degrees(&self) -> &[usize] {
        &self.degrees
    }

    /// Knot vectors `T_a`, one per direction.
    #[must_use]
    pub fn knots(&self) -> &[KnotVector] {
        &self.knots
    }

    /// Net size `n_a` in each direction.
    #[must_use]
    pub fn shape(&self) -> &[usize] {
        &self.shape
    }

    /// The control net, flat, first direction slowest.
    #[must_use]
    pub fn control_points(&self) -> &Points {
        &self.control
    }

    /// Dimension of the values.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.control.dim()
    }

    /// Domain `[t_{p_a}, t_{n_a}]` of each direction.
    #[must_use]
    pub fn domain(&self) -> Vec<(f64, f64)> {
        self.knots
            .iter()
            .zip(&self.degrees)
            .map(|(k, &p)| k.domain(p))
            .collect()
    }

    /// The parts: degrees, knot vectors, control net.
    #[must_use]
    pub fn into_parts(self) -> (Vec<usize>, Vec<KnotVector>, Points) {
        (self.degrees, self.knots, self.control)
    }

    /// Offset between consecutive indices of direction `a` in the flat net, in numbers
    /// (`Π_{b > a} n_b · dim`).
    pub(crate) fn stride(&self, a: usize) -> usize {
        self.shape[a + 1..].iter().product::<usize>() * self.dim()
    }

    /// `S(x)`: see the type's documentation. O(`Π_a (p_a + 1)·dim + Σ_a p_a²`).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `x.len() != N`; [`Error::ParameterOutOfDomain`] for a
    /// coordinate outside its direction's domain (or NaN).
    pub fn eval(&self, x: &[f64]) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.dim()];
        let mut scratch = TensorScratch::new(self, None)?;
        self.eval_with(x, None, &mut scratch, &mut out)?;
        Ok(out)
    }

    /// `S(x)` into `out` (`dim` numbers). One allocation (the scratch); for many points use
    /// [`TensorBSpline::eval_batch`].
    ///
    /// # Errors
    /// As [`TensorBSpline::eval`]; [`Error::LengthMismatch`] if `out.len() != dim`.
    pub fn eval_into(&self, x: &[f64], out: &mut [f64]) -> Result<()> {
        check_len("output (dim)", self.dim(), out.len())?;
        let mut scratch = TensorScratch::new(self, None)?;
        self.eval_with(x, None, &mut scratch, out)
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
        let mut out = vec![0.0; self.dim()];
        let mut scratch = TensorScratch::new(self, Some(orders))?;
        self.eval_with(x, Some(orders), &mut scratch, &mut out)?;
        Ok(out)
    }

    /// `S(x_r)` (or the partial derivative of `orders`, see [`TensorBSpline::eval_partial`]) for
    /// every point `x_r` of `xs` (`N` coordinates a point, flat) into `out` (`dim` numbers a
    /// point). One scratch for the batch, span searches that start from the previous point's
    /// spans ([`KnotVector::span_cursor`]); each point gets the same bits as
    /// [`TensorBSpline::eval`] (or `eval_partial`).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `xs.len()` is not a multiple of `N`, if `out` does not hold
    /// `dim` numbers a point or `orders.len() != N`; [`Error::ParameterOutOfDomain`] at the first
    /// point outside the domain (the points before it are written).
    pub fn eval_batch(&self, xs: &[f64], orders: Option<&[usize]>, out: &mut [f64]) -> Result<()> {
        self.check_batch(xs, out)?;
        let mut scratch = TensorScratch::new(self, orders)?;
        self.batch_slice(xs, orders, false, &mut scratch, out)
    }

    /// [`TensorBSpline::eval_batch`] split over the current rayon thread pool in chunks of a
    /// fixed number of points, each with its own scratch; every point gets the same bits as in
    /// the sequential batch (the same kernel on the same numbers). A large batch on a large net
    /// whose points are all in the domain is worked through in the order of a grid of cells,
    /// for the cache, and its values put back in order
    /// (`docs/theory/tensor.md#tensor-product-splines`, "Large batches in cell order").
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_batch`] (the error of the first failing chunk).
    pub fn par_eval_batch(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        out: &mut [f64],
    ) -> Result<()> {
        self.par_batch(xs, orders, false, out)
    }

    /// [`TensorBSpline::par_eval_batch`] at any finite point: outside the domain of direction
    /// `a` the spline is continued by the polynomial of its first or last non-empty span in
    /// that direction (the span of the nearest domain end, with the basis polynomials of
    /// P&T Algorithm A2.2 evaluated at the coordinate itself, as
    /// [`BSplineCurve::eval_extrapolated`](crate::BSplineCurve::eval_extrapolated) does for
    /// curves; SciPy's `NdBSpline(..., extrapolate=True)`). Inside the domain the same bits
    /// as [`TensorBSpline::par_eval_batch`].
    ///
    /// ```
    /// use lekalo::{Points, TensorBSpline};
    /// // f(x, y) = x² + y on [0, 1]², continued: f(2, -1) = 3
    /// let net = Points::from_flat(1, vec![0.0, 1.0, 0.0, 1.0, 1.0, 2.0])?;
    /// let s = TensorBSpline::new(
    ///     vec![2, 1],
    ///     vec![vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
    ///     net,
    /// )?;
    /// let mut out = [0.0];
    /// s.par_eval_batch_extrapolated(&[2.0, -1.0], None, &mut out)?;
    /// assert!((out[0] - 3.0).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`TensorBSpline::par_eval_batch`], except that a finite point outside the domain is
    /// evaluated; [`Error::NonFinite`] for a coordinate that is NaN or infinite.
    pub fn par_eval_batch_extrapolated(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        out: &mut [f64],
    ) -> Result<()> {
        self.par_batch(xs, orders, true, out)
    }

    fn par_batch(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        extrapolate: bool,
        out: &mut [f64],
    ) -> Result<()> {
        self.check_batch(xs, out)?;
        if extrapolate {
            check_finite("point coordinates", xs)?;
        }
        // validates the orders once, before the threads start
        TensorScratch::new(self, orders)?;
        let (n, dim) = (self.n_vars(), self.dim());
        let points = xs.len() / n;
        if points >= SORT_MIN_POINTS
            && self.control.as_slice().len() >= SORT_MIN_NET
            && n <= SORT_MAX_VARS
            && (extrapolate || self.all_inside(xs))
        {
            return self.par_batch_sorted(xs, orders, extrapolate, out);
        }
        let chunk = points
            .div_ceil(4 * rayon::current_num_threads().max(1))
            .max(PAR_CHUNK);
        let results: Vec<Result<()>> = xs
            .par_chunks(chunk * n)
            .zip(out.par_chunks_mut(chunk * dim))
            .map(|(x, o)| {
                let mut scratch = TensorScratch::new(self, orders)?;
                self.batch_slice(x, orders, extrapolate, &mut scratch, o)
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

    /// [`TensorBSpline::par_batch`] for a large batch on a large net, every point evaluable:
    /// the points are visited in the order of a coarse grid of cells over the domain
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
        extrapolate: bool,
        out: &mut [f64],
    ) -> Result<()> {
        let (n, dim) = (self.n_vars(), self.dim());
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
                    // truncation of a number in [0, SORT_BINS − 1] (NaN-free: finite points)
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
                self.batch_slice(x, orders, extrapolate, &mut scratch, o)
            })
            .collect();
        results.into_iter().collect::<Result<()>>()?;
        for (&(_, k), v) in order.iter().zip(sorted_out.chunks_exact(dim)) {
            out[k * dim..(k + 1) * dim].copy_from_slice(v);
        }
        Ok(())
    }

    fn check_batch(&self, xs: &[f64], out: &[f64]) -> Result<()> {
        let n = self.n_vars();
        if xs.len() % n != 0 {
            return Err(Error::LengthMismatch {
                what: "point coordinates (a multiple of the number of directions)",
                expected: xs.len() / n * n,
                got: xs.len(),
            });
        }
        check_len(
            "output (points × dim)",
            xs.len() / n * self.dim(),
            out.len(),
        )
    }

    /// The points of `xs` in order; outside the domain an error or, with `extrapolate`, the
    /// polynomial of the nearest end span in each direction.
    fn batch_slice(
        &self,
        xs: &[f64],
        orders: Option<&[usize]>,
        extrapolate: bool,
        scratch: &mut TensorScratch,
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.n_vars();
        let mut cursors: Vec<_> = self
            .knots
            .iter()
            .zip(&self.degrees)
            .map(|(k, &p)| k.span_cursor(p))
            .collect();
        let domains = self.domain();
        if orders.is_none() && n == 3 && self.dim() == 1 {
            let d = &self.degrees;
            if d[1] == d[0] && d[2] == d[0] {
                let run = Batch3 {
                    s: self,
                    xs,
                    extrapolate,
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
        for (x, o) in xs.chunks_exact(n).zip(out.chunks_exact_mut(self.dim())) {
            for (a, c) in cursors.iter_mut().enumerate() {
                scratch.spans[a] = if extrapolate {
                    // finite (checked by the caller): the span of the nearest domain end
                    let (lo, hi) = domains[a];
                    c.find_unchecked(x[a].clamp(lo, hi))
                } else {
                    c.find(x[a])?
                };
            }
            self.eval_spans(x, orders, scratch, o);
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
        for (a, (k, &p)) in self.knots.iter().zip(&self.degrees).enumerate() {
            scratch.spans[a] = k.find_span(p, x[a])?;
        }
        self.eval_spans(x, orders, scratch, out);
        Ok(())
    }

    /// The point kernel, spans in `scratch.spans`: basis vectors per direction, then the
    /// contraction of the window ([`contract_window`]). No allocation.
    fn eval_spans(
        &self,
        x: &[f64],
        orders: Option<&[usize]>,
        scratch: &mut TensorScratch,
        out: &mut [f64],
    ) {
        scratch.fill_bases(self, x, orders);
        self.contract_prepared(scratch, out);
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

/// A batch of values of a trivariate scalar spline of one degree `p ≤ 5` in every direction:
/// per point the three spans (searched from the previous point's), the basis vectors by the
/// fixed-order A2.2 ([`basis_funs_fixed`], the same operations in the same order as
/// [`basis_funs_into`]) and the fixed-size contraction [`contract3`], with no scratch and no
/// odometer. The same bits as the general kernel (tested); it is the whole cost of the
/// evaluation of a trivariate lookup table at scattered points.
struct Batch3<'a> {
    s: &'a TensorBSpline,
    xs: &'a [f64],
    extrapolate: bool,
    domains: &'a [(f64, f64)],
}

impl Batch3<'_> {
    fn values<const W: usize>(
        &self,
        cursors: &mut [crate::knots::SpanCursor<'_>],
        out: &mut [f64],
    ) -> Result<()> {
        let s = self.s;
        let net = s.control.as_slice();
        let strides = [s.stride(0), s.stride(1)];
        let (k0, k1, k2) = (
            s.knots[0].as_slice(),
            s.knots[1].as_slice(),
            s.knots[2].as_slice(),
        );
        let p = W - 1;
        for (x, o) in self.xs.chunks_exact(3).zip(out.iter_mut()) {
            let mut spans = [0usize; 3];
            for (a, c) in cursors.iter_mut().enumerate() {
                spans[a] = if self.extrapolate {
                    let (lo, hi) = self.domains[a];
                    c.find_unchecked(x[a].clamp(lo, hi))
                } else {
                    c.find(x[a])?
                };
            }
            let b0: [f64; W] = basis_funs_fixed(k0, spans[0], x[0]);
            let b1: [f64; W] = basis_funs_fixed(k1, spans[1], x[1]);
            let b2: [f64; W] = basis_funs_fixed(k2, spans[2], x[2]);
            let first = [spans[0] - p, spans[1] - p, spans[2] - p];
            *o = contract3::<W>(net, first, strides, &b0, &b1, &b2);
        }
        Ok(())
    }
}

/// Batches of at least this many points on nets of at least [`SORT_MIN_NET`] numbers are
/// evaluated in the order of a coarse grid of cells ([`TensorBSpline::par_batch_sorted`]).
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
    /// [`TensorBSpline::stride`] of every direction.
    strides: Vec<usize>,
}

impl TensorScratch {
    /// # Errors
    /// [`Error::LengthMismatch`] if `orders` does not have one order per direction;
    /// [`Error::TooLarge`] for an order above [`MAX_DERIVATIVE_ORDER`].
    pub(crate) fn new(s: &TensorBSpline, orders: Option<&[usize]>) -> Result<Self> {
        let n = s.n_vars();
        let mut ders_len = 0;
        if let Some(k) = orders {
            check_len("derivative orders (one per direction)", n, k.len())?;
            for (&k, &p) in k.iter().zip(&s.degrees) {
                check_derivative_order(k, MAX_DERIVATIVE_ORDER)?;
                ders_len = ders_len.max((k.min(p) + 1) * (p + 1));
            }
        }
        let mut offsets = Vec::with_capacity(n);
        let mut total = 0;
        for &p in &s.degrees {
            offsets.push(total);
            total += p + 1;
        }
        let dim = s.dim();
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
    pub(crate) fn fill_bases(&mut self, s: &TensorBSpline, x: &[f64], orders: Option<&[usize]>) {
        for a in 0..s.n_vars() {
            let p = s.degrees[a];
            let knots = s.knots[a].as_slice();
            let out = &mut self.values[self.offsets[a]..self.offsets[a] + p + 1];
            let k = orders.map_or(0, |k| k[a]);
            basis_vector(
                knots,
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
    s: &TensorBSpline,
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
    let dim = s.dim();
    let net = s.control.as_slice();
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
fn contract3_scalar(s: &TensorBSpline, w: &Window<'_>) -> Option<f64> {
    let d = &s.degrees;
    if d[1] != d[0] || d[2] != d[0] {
        return None;
    }
    let first = [w.spans[0] - d[0], w.spans[1] - d[1], w.spans[2] - d[2]];
    let basis = |a: usize| &w.values[w.offsets[a]..w.offsets[a] + d[a] + 1];
    let (b0, b1, b2) = (basis(0), basis(1), basis(2));
    let net = s.control.as_slice();
    let strides = [w.strides[0], w.strides[1]];
    Some(match d[0] {
        1 => contract3::<2>(net, first, strides, b0, b1, b2),
        2 => contract3::<3>(net, first, strides, b0, b1, b2),
        3 => contract3::<4>(net, first, strides, b0, b1, b2),
        4 => contract3::<5>(net, first, strides, b0, b1, b2),
        5 => contract3::<6>(net, first, strides, b0, b1, b2),
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

/// # Errors
/// [`Error::LengthMismatch`].
pub(crate) fn check_len(what: &'static str, expected: usize, got: usize) -> Result<()> {
    if expected != got {
        return Err(Error::LengthMismatch {
            what,
            expected,
            got,
        });
    }
    Ok(())
}
