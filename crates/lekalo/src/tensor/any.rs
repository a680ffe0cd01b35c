//! [`Tensor`]: one value for a tensor-product spline in `N` parameters of either kind
//! (B-spline or NURBS), with the capabilities the front ends share delegated once.

use crate::tensor::{TensorBSpline, TensorNurbs};
use crate::{KnotVector, Points, Result};

/// A tensor-product spline in `N ≥ 1` parameters, polynomial or rational.
///
/// ```
/// use lekalo::{Points, Tensor, TensorBSpline};
/// let k = vec![0.0, 0.0, 1.0, 1.0];
/// let net = Points::from_flat(1, (0..8).map(f64::from).collect())?;
/// let t = Tensor::from(TensorBSpline::new(vec![1, 1, 1], vec![k.clone(), k.clone(), k], net)?);
/// assert_eq!((t.n_vars(), t.dim(), t.weights()), (3, 1, None));
/// let mut out = [0.0; 1];
/// t.eval_batch(&[1.0, 1.0, 1.0], &mut out)?;
/// assert_eq!(out, [7.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub enum Tensor {
    /// A tensor-product B-spline.
    BSpline(TensorBSpline),
    /// A tensor-product NURBS.
    Nurbs(TensorNurbs),
}

impl From<TensorBSpline> for Tensor {
    fn from(s: TensorBSpline) -> Self {
        Tensor::BSpline(s)
    }
}

impl From<TensorNurbs> for Tensor {
    fn from(s: TensorNurbs) -> Self {
        Tensor::Nurbs(s)
    }
}

impl Tensor {
    /// Number of parameter directions `N`.
    #[must_use]
    pub fn n_vars(&self) -> usize {
        match self {
            Tensor::BSpline(s) => s.n_vars(),
            Tensor::Nurbs(s) => s.n_vars(),
        }
    }

    /// Dimension of the values (Euclidean for a NURBS).
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            Tensor::BSpline(s) => s.dim(),
            Tensor::Nurbs(s) => s.dim(),
        }
    }

    /// Degree of each direction.
    #[must_use]
    pub fn degrees(&self) -> &[usize] {
        match self {
            Tensor::BSpline(s) => s.degrees(),
            Tensor::Nurbs(s) => s.degrees(),
        }
    }

    /// Knot vector of each direction.
    #[must_use]
    pub fn knots(&self) -> &[KnotVector] {
        match self {
            Tensor::BSpline(s) => s.knots(),
            Tensor::Nurbs(s) => s.knots(),
        }
    }

    /// Net size of each direction.
    #[must_use]
    pub fn shape(&self) -> &[usize] {
        match self {
            Tensor::BSpline(s) => s.shape(),
            Tensor::Nurbs(s) => s.shape(),
        }
    }

    /// Parameter domain `[min, max]` of each direction.
    #[must_use]
    pub fn domain(&self) -> Vec<(f64, f64)> {
        match self {
            Tensor::BSpline(s) => s.domain(),
            Tensor::Nurbs(s) => s.homogeneous().domain(),
        }
    }

    /// Euclidean control points, the first direction slowest.
    #[must_use]
    pub fn control_points(&self) -> Points {
        match self {
            Tensor::BSpline(s) => s.control_points().clone(),
            Tensor::Nurbs(s) => s.control_points(),
        }
    }

    /// One weight per control point for a NURBS, `None` for a B-spline.
    #[must_use]
    pub fn weights(&self) -> Option<Vec<f64>> {
        match self {
            Tensor::BSpline(_) => None,
            Tensor::Nurbs(s) => Some(s.weights()),
        }
    }

    /// The spline at every point of `xs` (`N` coordinates a point, flat) into `out` (`dim`
    /// numbers a point), in parallel: [`TensorBSpline::par_eval_batch`] or
    /// [`TensorNurbs::par_eval_batch`].
    ///
    /// # Errors
    /// As those methods ([`crate::Error::LengthMismatch`],
    /// [`crate::Error::ParameterOutOfDomain`]).
    pub fn eval_batch(&self, xs: &[f64], out: &mut [f64]) -> Result<()> {
        match self {
            Tensor::BSpline(s) => s.par_eval_batch(xs, None, out),
            Tensor::Nurbs(s) => s.par_eval_batch(xs, out),
        }
    }

    /// The spline on the grid `axes[0] × ⋯ × axes[N−1]` into `out` (`dim` numbers a point, the
    /// first direction slowest), without forming the grid's points:
    /// [`TensorBSpline::eval_grid`] or [`TensorNurbs::eval_grid`]
    /// (`docs/theory/tensor.md#evaluation-on-grids`). Each value is the same bits as the
    /// evaluation at its point.
    ///
    /// # Errors
    /// As those methods ([`crate::Error::LengthMismatch`], [`crate::Error::TooLarge`],
    /// [`crate::Error::ParameterOutOfDomain`]).
    pub fn eval_grid(&self, axes: &[&[f64]], out: &mut [f64]) -> Result<()> {
        match self {
            Tensor::BSpline(s) => s.eval_grid(axes, None, out),
            Tensor::Nurbs(s) => s.eval_grid(axes, out),
        }
    }

    /// The same spline with the knot `t` inserted `times` times in direction `axis` (from 0):
    /// [`TensorBSpline::insert_knot`] or [`TensorNurbs::insert_knot`] (Boehm along each line
    /// of the net; P&T A5.3 in `N` directions).
    ///
    /// # Errors
    /// As those methods.
    pub fn insert_knot(&self, axis: usize, t: f64, times: usize) -> Result<Tensor> {
        Ok(match self {
            Tensor::BSpline(s) => Tensor::BSpline(s.insert_knot(axis, t, times)?),
            Tensor::Nurbs(s) => Tensor::Nurbs(s.insert_knot(axis, t, times)?),
        })
    }

    /// The spline in the free parameters with the others fixed (`fixed[a] = Some(x_a)`), of
    /// the same kind: [`TensorBSpline::slice`] or [`TensorNurbs::slice`]
    /// (`docs/theory/tensor.md#operations-along-one-direction`).
    ///
    /// # Errors
    /// As those methods.
    pub fn slice(&self, fixed: &[Option<f64>]) -> Result<Tensor> {
        Ok(match self {
            Tensor::BSpline(s) => Tensor::BSpline(s.slice(fixed)?),
            Tensor::Nurbs(s) => Tensor::Nurbs(s.slice(fixed)?),
        })
    }
}
