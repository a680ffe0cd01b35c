//! [`TensorNurbs`]: a tensor-product NURBS in `N` parameters, the [`TensorBSpline`] of its
//! homogeneous points `(w·P, w)` (P&T §4.2, §4.4). `docs/theory/tensor.md#nurbs`.

use serde::{Deserialize, Serialize};

use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::points::{check_homogeneous, homogenize, with_unit_weights, Points};
use crate::surface::nurbs::NurbsSurface;
use crate::tensor::spline::{check_len, TensorBSpline};

/// Largest number of partial derivatives `Π_a (k_a + 1)` that
/// [`TensorNurbs::eval_partial`] tabulates (its quotient rule costs the square of it).
pub const MAX_TENSOR_DERIVATIVE_TABLE: usize = 1 << 12;

/// A tensor-product NURBS in `N ≥ 1` parameters:
///
/// `R(x) = Σ_i N_{i_0}(x_0)⋯N_{i_{N−1}}(x_{N−1}) w_i P_i / Σ_i N_{i_0}(x_0)⋯N_{i_{N−1}}(x_{N−1}) w_i`
///
/// stored as the [`TensorBSpline`] `A(x)` of the homogeneous points `(w_i·P_i, w_i)`
/// (dimension `dim + 1`, weight last), so that every B-spline operation (grid and batch
/// evaluation, knot insertion, slicing) applies unchanged, and `R = A_{0..dim} / A_dim`.
/// Deserialisation goes through [`TensorNurbs::new`].
///
/// ```
/// use lekalo::{Points, TensorNurbs};
/// // a quarter circle swept along a straight line: a cylinder patch, N = 2
/// let s = std::f64::consts::FRAC_1_SQRT_2;
/// let arc = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let mut net = Vec::new();
/// for h in [0.0, 1.0] { for p in arc { net.extend([p[0], p[1], h]); } }
/// let weights = [1.0, s, 1.0, 1.0, s, 1.0];
/// let k = |p: usize| -> Vec<f64> { [vec![0.0; p + 1], vec![1.0; p + 1]].concat() };
/// let cyl = TensorNurbs::new(vec![1, 2], vec![k(1), k(2)], Points::from_flat(3, net)?, &weights)?;
/// let q = cyl.eval(&[0.3, 0.6])?;
/// assert!((q[0].hypot(q[1]) - 1.0).abs() < 1e-15 && (q[2] - 0.3).abs() < 1e-15);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "TensorNurbsRepr", into = "TensorNurbsRepr")]
pub struct TensorNurbs {
    homogeneous: TensorBSpline,
}

#[derive(Serialize, Deserialize)]
struct TensorNurbsRepr {
    degrees: Vec<usize>,
    knots: Vec<Vec<f64>>,
    control: Points,
    weights: Vec<f64>,
}

impl TryFrom<TensorNurbsRepr> for TensorNurbs {
    type Error = Error;
    fn try_from(r: TensorNurbsRepr) -> Result<Self> {
        TensorNurbs::new(r.degrees, r.knots, r.control, &r.weights)
    }
}

impl From<TensorNurbs> for TensorNurbsRepr {
    fn from(s: TensorNurbs) -> Self {
        let weights = s.weights();
        let control = s.control_points();
        let (degrees, knots, _) = s.homogeneous.into_parts();
        TensorNurbsRepr {
            degrees,
            knots: knots.into_iter().map(KnotVector::into_vec).collect(),
            control,
            weights,
        }
    }
}

impl TensorNurbs {
    /// A NURBS from degrees, knots, Euclidean control points and one weight per point.
    ///
    /// # Errors
    /// As [`TensorBSpline::new`]; [`Error::LengthMismatch`] if there is not one weight per
    /// point; [`Error::NonFinite`] / [`Error::NonPositiveWeight`] for a bad weight.
    pub fn new(
        degrees: Vec<usize>,
        knots: Vec<Vec<f64>>,
        control: Points,
        weights: &[f64],
    ) -> Result<Self> {
        let h = homogenize(&control, weights)?;
        Ok(TensorNurbs {
            homogeneous: TensorBSpline::new(degrees, knots, h)?,
        })
    }

    /// The NURBS whose homogeneous B-spline is `homogeneous` (weight last).
    ///
    /// # Errors
    /// [`Error::Dimension`] for homogeneous points of dimension below 2;
    /// [`Error::NonPositiveWeight`].
    pub fn from_homogeneous(homogeneous: TensorBSpline) -> Result<Self> {
        check_homogeneous(homogeneous.control_points())?;
        Ok(TensorNurbs { homogeneous })
    }

    /// The B-spline as a NURBS with unit weights.
    #[must_use]
    pub fn from_bspline(s: &TensorBSpline) -> Self {
        TensorNurbs {
            homogeneous: TensorBSpline::from_raw(
                s.degrees().to_vec(),
                s.knots().to_vec(),
                with_unit_weights(s.control_points()),
            ),
        }
    }

    /// The NURBS curve as a NURBS in one parameter: the same homogeneous B-spline, bit for bit.
    #[must_use]
    pub fn from_nurbs_curve(curve: &NurbsCurve) -> Self {
        TensorNurbs {
            homogeneous: TensorBSpline::from_curve(curve.homogeneous()),
        }
    }

    /// The NURBS surface as a NURBS in two parameters `(u, v)`: the same homogeneous
    /// B-spline, bit for bit.
    #[must_use]
    pub fn from_nurbs_surface(surface: &NurbsSurface) -> Self {
        TensorNurbs {
            homogeneous: TensorBSpline::from_surface(surface.homogeneous()),
        }
    }

    /// The NURBS in one parameter as a [`NurbsCurve`], bit for bit.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `N ≠ 1`.
    pub fn to_nurbs_curve(&self) -> Result<NurbsCurve> {
        NurbsCurve::from_homogeneous(self.homogeneous.to_curve()?)
    }

    /// The NURBS in two parameters as a [`NurbsSurface`], bit for bit.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `N ≠ 2`.
    pub fn to_nurbs_surface(&self) -> Result<NurbsSurface> {
        NurbsSurface::from_homogeneous(self.homogeneous.to_surface()?)
    }

    /// The homogeneous B-spline `A`.
    #[must_use]
    pub fn homogeneous(&self) -> &TensorBSpline {
        &self.homogeneous
    }

    /// Number of parameter directions `N`.
    #[must_use]
    pub fn n_vars(&self) -> usize {
        self.homogeneous.n_vars()
    }

    /// Euclidean dimension of the values.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.homogeneous.dim() - 1
    }

    /// Degrees, one per direction.
    #[must_use]
    pub fn degrees(&self) -> &[usize] {
        self.homogeneous.degrees()
    }

    /// Knot vectors, one per direction.
    #[must_use]
    pub fn knots(&self) -> &[KnotVector] {
        self.homogeneous.knots()
    }

    /// Net size in each direction.
    #[must_use]
    pub fn shape(&self) -> &[usize] {
        self.homogeneous.shape()
    }

    /// The weights, in net order.
    #[must_use]
    pub fn weights(&self) -> Vec<f64> {
        crate::points::weights_of(self.homogeneous.control_points())
    }

    /// The Euclidean control points `P_i = (w·P_i) / w_i`.
    #[must_use]
    pub fn control_points(&self) -> Points {
        crate::points::dehomogenize(self.homogeneous.control_points())
    }

    /// `R(x)`: the homogeneous value divided by its weight. O(`Π_a (p_a + 1)·(dim + 1)`).
    ///
    /// # Errors
    /// As [`TensorBSpline::eval`].
    pub fn eval(&self, x: &[f64]) -> Result<Vec<f64>> {
        let mut h = self.homogeneous.eval(x)?;
        Ok(project(&mut h).to_vec())
    }

    /// `R` on the grid `axes[0] × ⋯ × axes[N−1]` into `out` (`dim` numbers a point, layout of
    /// [`TensorBSpline::eval_grid`]): the homogeneous grid, then one division a value. Each
    /// value is the same bits as [`TensorNurbs::eval`] at its point.
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_grid`] (with `dim` the Euclidean dimension).
    pub fn eval_grid(&self, axes: &[&[f64]], out: &mut [f64]) -> Result<()> {
        let hd = self.homogeneous.dim();
        let points = out.len() / self.dim().max(1);
        check_len(
            "grid output (product of the list lengths × dim)",
            points * self.dim(),
            out.len(),
        )?;
        let mut h = vec![0.0; points.saturating_mul(hd)];
        self.homogeneous.eval_grid(axes, None, &mut h)?;
        write_projected(&mut h, hd, out);
        Ok(())
    }

    /// `R` at every point of `xs` (`N` coordinates a point) into `out` (`dim` a point): the
    /// homogeneous batch ([`TensorBSpline::eval_batch`]), then one division a value. The same
    /// bits as [`TensorNurbs::eval`] at each point.
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_batch`].
    pub fn eval_batch(&self, xs: &[f64], out: &mut [f64]) -> Result<()> {
        self.batch(xs, out, Batch::Serial)
    }

    /// [`TensorNurbs::eval_batch`] on the rayon pool ([`TensorBSpline::par_eval_batch`]); the
    /// same bits.
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_batch`].
    pub fn par_eval_batch(&self, xs: &[f64], out: &mut [f64]) -> Result<()> {
        self.batch(xs, out, Batch::Parallel)
    }

    /// [`TensorNurbs::par_eval_batch`] with points outside the domain evaluated by the end
    /// spans' polynomials continued ([`TensorBSpline::par_eval_batch_extrapolated`] of the
    /// homogeneous spline, then one division a value; SciPy's `extrapolate=True`). Inside the
    /// domain the same bits as [`TensorNurbs::par_eval_batch`]. Outside it the continued weight
    /// function may reach 0, where the value is not finite.
    ///
    /// # Errors
    /// As [`TensorBSpline::par_eval_batch_extrapolated`].
    pub fn par_eval_batch_extrapolated(&self, xs: &[f64], out: &mut [f64]) -> Result<()> {
        self.batch(xs, out, Batch::Extrapolated)
    }

    fn batch(&self, xs: &[f64], out: &mut [f64], how: Batch) -> Result<()> {
        let hd = self.homogeneous.dim();
        let n = self.n_vars();
        let points = xs.len() / n;
        check_len("output (points × dim)", points * self.dim(), out.len())?;
        let mut h = vec![0.0; points * hd];
        match how {
            Batch::Serial => self.homogeneous.eval_batch(xs, None, &mut h)?,
            Batch::Parallel => self.homogeneous.par_eval_batch(xs, None, &mut h)?,
            Batch::Extrapolated => self
                .homogeneous
                .par_eval_batch_extrapolated(xs, None, &mut h)?,
        }
        write_projected(&mut h, hd, out);
        Ok(())
    }

    /// The partial derivative `∂^{|k|} R / ∂x_0^{k_0} ⋯ ∂x_{N−1}^{k_{N−1}}` at `x`, by the
    /// quotient rule in `N` variables (P&T eq. 4.20 for surfaces, here with multi-indices):
    /// `R^{(α)} = (A^{(α)} − Σ_{0 ≠ β ≤ α} C(α, β)·w^{(β)}·R^{(α−β)}) / w` with
    /// `C(α, β) = Π_a C(α_a, β_a)`, over every `α ≤ k` in lexicographic order (each `α − β`
    /// comes before `α`). `A^{(β)}` are [`TensorBSpline::eval_partial`] of the homogeneous
    /// spline. O(`T·Π_a (p_a + 1)·(dim + 1) + T²·dim`), `T = Π_a (k_a + 1)`.
    ///
    /// # Errors
    /// As [`TensorBSpline::eval_partial`]; [`Error::TooLarge`] if `T` exceeds
    /// [`MAX_TENSOR_DERIVATIVE_TABLE`].
    pub fn eval_partial(&self, x: &[f64], orders: &[usize]) -> Result<Vec<f64>> {
        self.partial_by(orders, |alpha| self.homogeneous.eval_partial(x, alpha))
    }

    /// [`TensorNurbs::eval_partial`] with a point outside the domain evaluated by the end
    /// spans' polynomials continued: the same quotient rule on the homogeneous partials of
    /// [`TensorBSpline::par_eval_batch_extrapolated`].
    ///
    /// # Errors
    /// As [`TensorNurbs::eval_partial`], except that a finite point outside the domain is
    /// evaluated; [`Error::NonFinite`] for a coordinate that is NaN or infinite.
    pub fn eval_partial_extrapolated(&self, x: &[f64], orders: &[usize]) -> Result<Vec<f64>> {
        check_len(
            "point coordinates (one per direction)",
            self.n_vars(),
            x.len(),
        )?;
        let hd = self.homogeneous.dim();
        self.partial_by(orders, |alpha| {
            let mut a = vec![0.0; hd];
            self.homogeneous
                .par_eval_batch_extrapolated(x, Some(alpha), &mut a)?;
            Ok(a)
        })
    }

    /// The quotient rule of [`TensorNurbs::eval_partial`], the homogeneous partial of each
    /// multi-index `α` from `partial(α)`.
    fn partial_by(
        &self,
        orders: &[usize],
        partial: impl Fn(&[usize]) -> Result<Vec<f64>>,
    ) -> Result<Vec<f64>> {
        let n = self.n_vars();
        check_len("derivative orders (one per direction)", n, orders.len())?;
        let table = orders
            .iter()
            .try_fold(1usize, |t, &k| t.checked_mul(k.checked_add(1)?))
            .filter(|&t| t <= MAX_TENSOR_DERIVATIVE_TABLE)
            .ok_or(Error::TooLarge {
                what: "partial derivative table (product of orders + 1)".into(),
                size: orders
                    .iter()
                    .fold(1usize, |t, &k| t.saturating_mul(k.saturating_add(1))),
                max: MAX_TENSOR_DERIVATIVE_TABLE,
            })?;
        let hd = self.homogeneous.dim();
        let dim = hd - 1;
        // multi-indices α ≤ k in lexicographic order (last direction fastest)
        let alphas = multi_indices(orders);
        let mut a_vals = Vec::with_capacity(table);
        for alpha in &alphas {
            a_vals.push(partial(alpha)?);
        }
        let mut r = vec![0.0; table * dim];
        let w = a_vals[0][dim];
        for (ai, alpha) in alphas.iter().enumerate() {
            let mut v: Vec<f64> = a_vals[ai][..dim].to_vec();
            for (bi, beta) in alphas.iter().enumerate().take(ai + 1).skip(1) {
                if beta.iter().zip(alpha).any(|(b, a)| b > a) {
                    continue;
                }
                let c: f64 = alpha
                    .iter()
                    .zip(beta)
                    .map(|(&a, &b)| binomial(a, b))
                    .product::<f64>()
                    * a_vals[bi][dim];
                let diff: Vec<usize> = alpha.iter().zip(beta).map(|(a, b)| a - b).collect();
                let di = index_of(&diff, orders);
                for (vk, rk) in v.iter_mut().zip(&r[di * dim..(di + 1) * dim]) {
                    *vk -= c * rk;
                }
            }
            for (o, vk) in r[ai * dim..(ai + 1) * dim].iter_mut().zip(&v) {
                *o = vk / w;
            }
        }
        Ok(r[(table - 1) * dim..].to_vec())
    }

    /// [`TensorBSpline::insert_knot`] of the homogeneous spline: the same NURBS.
    ///
    /// # Errors
    /// As [`TensorBSpline::insert_knot`].
    pub fn insert_knot(&self, axis: usize, t: f64, times: usize) -> Result<TensorNurbs> {
        Ok(TensorNurbs {
            homogeneous: self.homogeneous.insert_knot(axis, t, times)?,
        })
    }

    /// [`TensorBSpline::slice`] of the homogeneous spline: the NURBS in the free parameters
    /// (a slice of a rational spline is rational with the sliced weights).
    ///
    /// # Errors
    /// As [`TensorBSpline::slice`].
    pub fn slice(&self, fixed: &[Option<f64>]) -> Result<TensorNurbs> {
        Ok(TensorNurbs {
            homogeneous: self.homogeneous.slice(fixed)?,
        })
    }
}

/// How [`TensorNurbs::batch`] evaluates the homogeneous spline.
#[derive(Clone, Copy)]
enum Batch {
    Serial,
    Parallel,
    Extrapolated,
}

/// `h[..dim] / h[dim]` in place; returns the projected part.
fn project(h: &mut [f64]) -> &[f64] {
    let d = h.len() - 1;
    let w = h[d];
    for x in &mut h[..d] {
        *x /= w;
    }
    &h[..d]
}

/// Projects homogeneous values (`hd` numbers a point) into `out` (`hd − 1` a point).
fn write_projected(h: &mut [f64], hd: usize, out: &mut [f64]) {
    for (p, o) in h.chunks_exact_mut(hd).zip(out.chunks_exact_mut(hd - 1)) {
        o.copy_from_slice(project(p));
    }
}

/// Every multi-index `α ≤ k`, lexicographic, the last direction fastest.
fn multi_indices(k: &[usize]) -> Vec<Vec<usize>> {
    let mut all = Vec::new();
    let mut alpha = vec![0usize; k.len()];
    loop {
        all.push(alpha.clone());
        let mut a = k.len();
        loop {
            if a == 0 {
                return all;
            }
            a -= 1;
            alpha[a] += 1;
            if alpha[a] <= k[a] {
                break;
            }
            alpha[a] = 0;
        }
    }
}

/// Position of `alpha` in [`multi_indices`]`(k)`.
fn index_of(alpha: &[usize], k: &[usize]) -> usize {
    alpha.iter().zip(k).fold(0, |i, (&a, &ka)| i * (ka + 1) + a)
}

/// `C(n, k)` in floating point (exact for the small orders of a derivative table).
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}
