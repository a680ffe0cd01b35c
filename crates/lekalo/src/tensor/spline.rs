//! [`TensorBSpline`]: the type, its validation, and evaluation at points (values, partial
//! derivatives, batches). Formulas: `docs/theory/tensor.md#tensor-product-splines`.

use crate::What;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result, MAX_SCALARS};
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
pub(crate) fn checked_size(what: impl Into<What>, shape: &[usize], dim: usize) -> Result<usize> {
    let what: What = what.into();
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

/// The number of directions `n_degrees` (as [`check_n_vars`]) and one knot vector per degree.
///
/// # Errors
/// As [`check_n_vars`]; [`Error::LengthMismatch`] for `n_knots != n_degrees`.
pub(crate) fn check_knot_count(n_degrees: usize, n_knots: usize) -> Result<()> {
    check_n_vars(n_degrees)?;
    if n_knots != n_degrees {
        return Err(Error::LengthMismatch {
            what: "knot vectors (one per degree)".into(),
            expected: n_degrees,
            got: n_knots,
        });
    }
    Ok(())
}

/// Refuses zero parameter directions.
///
/// # Errors
/// [`Error::TooFew`].
pub(crate) fn check_n_vars(n: usize) -> Result<()> {
    if n == 0 {
        return Err(Error::TooFew {
            what: "parameter directions".into(),
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
        check_knot_count(degrees.len(), knots.len())?;
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
                what: "control points (product of the net sizes knots[a].len() − degrees[a] − 1)"
                    .into(),
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
        self.view().eval(x)
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
        self.view().eval_batch(xs, orders, out)
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
        self.view().par_eval_batch(xs, orders, out)
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
        self.view().par_eval_batch_extrapolated(xs, orders, out)
    }
}

/// # Errors
/// [`Error::LengthMismatch`].
pub(crate) fn check_len(what: impl Into<What>, expected: usize, got: usize) -> Result<()> {
    let what: What = what.into();
    if expected != got {
        return Err(Error::LengthMismatch {
            what,
            expected,
            got,
        });
    }
    Ok(())
}
