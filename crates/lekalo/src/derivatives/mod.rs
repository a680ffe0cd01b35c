//! Derivatives of evaluation for differentiable programs: the Jacobian-vector products (JVP,
//! forward mode) and vector-Jacobian products (VJP, reverse mode) of batch evaluation, with
//! respect to the control points, the parameters and the knots (`docs/theory/derivatives.md`).
//!
//! A spline is linear in its control points: the Jacobian of `C(t_i)` with respect to `P_j` is
//! the basis matrix `N_{j,p}(t_i)` times the identity, whose row `i` has `p + 1` non-zero
//! entries (P&T Algorithm A2.2, A2.3). Its Jacobian with respect to `t_i` is the curve's
//! derivative `C'(t_i)`. Every kernel here walks the parameters once, computes the basis
//! functions and their first derivatives at each, and applies them sparsely; none forms a
//! dense matrix. The primal values they return are bit-for-bit those of the plain batch
//! evaluation (`eval_batch`): the same basis scheme and the same order of sums.
//!
//! - `curve.rs`: [`crate::BSplineCurve::eval_batch_jvp`], [`crate::BSplineCurve::eval_batch_vjp`],
//!   [`crate::BSplineCurve::eval_batch_linearize`] (values, `C'(t)` and the sparse rows of the
//!   basis matrix, what an automatic-differentiation framework needs to build its own linear
//!   map).
//! - `borrowed/`: [`BorrowedCurve`], [`BorrowedNurbs`], [`BorrowedSurface`] and
//!   [`BorrowedTensor`], the values, JVP and VJP of `curve.rs`, `nurbs.rs`, `surface.rs` and
//!   `tensor.rs` for a few parameters on borrowed knots, control points (nets) and weights,
//!   reading and checking only the spans used (no O(n) copy or validation a call).
//! - `knots/`: the derivatives with respect to the knots, by differentiating knot insertion:
//!   [`crate::BSplineCurve::eval_batch_knot_jvp`], [`crate::BSplineCurve::eval_batch_knot_vjp`]
//!   and the same for [`crate::NurbsCurve`] (through its homogeneous curve and the quotient
//!   rule), [`crate::BSplineSurface`] and [`crate::TensorBSpline`] (each direction's knots, one
//!   kernel for both nets).
//! - `nurbs.rs`: the same three for [`crate::NurbsCurve`], with respect to the control points,
//!   the weights and the parameters.
//! - `surface.rs`: the same three for [`crate::BSplineSurface`] at pairs `(u, v)`.
//! - `nurbs_surface.rs`: the same three for [`crate::NurbsSurface`] at pairs `(u, v)`, with
//!   respect to the net, the weights and the pairs (the quotient rule on `surface.rs`'s
//!   homogeneous sums, `nurbs.rs`'s terms a control point); `nurbs_surface_tests.rs` its tests.
//! - `interpolation.rs`: [`InterpolationMap`], the derivatives of interpolation at fixed
//!   parameters and knots with respect to the data (a solve and an adjoint solve with one banded
//!   factorisation).
//! - `interpolant.rs`: [`Interpolant`], interpolation as a function of the data and of the
//!   parameters, with the JVP and VJP of both (`interpolation.rs`'s solves and the
//!   interpolant's derivative at the parameters).
//! - `fitting.rs`: [`LeastSquaresMap`] and [`SmoothingMap`], the derivatives of the
//!   least-squares fit on given knots and parameters and of the smoothing spline with a given
//!   `λ` with respect to the data (a sparse product and a solve with the fit's banded
//!   factorisation, forward or transposed).
//! - `fits.rs`: [`LeastSquaresFit`] and [`SmoothingFit`], the two fits as functions of their
//!   data on flat buffers: the fits' control points bit for bit, and `fitting.rs`'s JVP and VJP.
//! - `fit_knots.rs`: [`Interpolant::knot_jvp`], [`Interpolant::knot_vjp`],
//!   [`LeastSquaresFit::knot_jvp`] and [`LeastSquaresFit::knot_vjp`], the derivatives of the two
//!   fits with respect to the knots (the normal equations differentiated, solved with the fits'
//!   factorisations); `fit_knots_tests.rs` their tests.
//! - `geometry.rs`: [`ArcLengthGradient`] and [`ClosestParameters`], the derivatives of a
//!   B-spline curve's arc length (with respect to the control points) and of the parameters of
//!   its closest points to given points (with respect to the control points and the points);
//!   `geometry_knots.rs` (a child module of it) the same two with respect to the knots.
//! - `tensor.rs`: the same three for [`crate::TensorBSpline`] in `N` directions, at points of
//!   `N` coordinates.
//! - `tensor_nurbs.rs`: the same three for [`crate::TensorNurbs`], with respect to the net, the
//!   weights and the points (the quotient rule on `tensor.rs`'s homogeneous values and
//!   partials); `tensor_nurbs_tests.rs` its tests.
//! - `control_cotangent.rs`: the control-point cotangent of a curve for batches of at least as
//!   many parameters as control points (a gradient in the control points): the choice of its
//!   two kernels, the cotangent check, and the A2.2 kernel with reciprocals precomputed a span,
//!   for degrees above the power form's;
//! - `located.rs`: what the two kernels share: the parameters located in their spans by the
//!   bucket table, and the monomorphised dispatch over common orders and dimensions;
//! - `power_sums.rs`: the other kernel, by per-piece power sums (the transpose of the
//!   power-form evaluation), for degree ≤ 3.
//! - `slopes.rs`: the basis functions and their first derivatives in one Cox–de Boor pass.
//! - `checks.rs`: the length and finiteness checks the kernels share.

mod borrowed;
mod checks;
mod control_cotangent;
mod curve;
mod fit_knots;
#[cfg(test)]
mod fit_knots_tests;
mod fits;
mod fitting;
mod geometry;
mod interpolant;
mod interpolation;
mod knots;
mod located;
mod nurbs;
mod nurbs_surface;
mod power_sums;
mod slopes;
mod surface;
mod tensor;
mod tensor_nurbs;
#[cfg(test)]
mod tests;

pub use borrowed::{BorrowedCurve, BorrowedNurbs, BorrowedSurface, BorrowedTensor};
pub use curve::CurveLinearization;
pub use fits::{LeastSquaresFit, SmoothingFit};
pub use fitting::{FitLinearization, LeastSquaresMap, SmoothingMap};
pub use geometry::{ArcLengthGradient, ClosestParameters, Cotangents};
pub use interpolant::Interpolant;
pub use interpolation::InterpolationMap;
pub use nurbs::NurbsLinearization;
pub use nurbs_surface::NurbsSurfaceLinearization;
pub use surface::SurfaceLinearization;
pub use tensor::TensorLinearization;
pub use tensor_nurbs::TensorNurbsLinearization;
