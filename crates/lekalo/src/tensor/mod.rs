//! Tensor-product splines in any number of parameters: B-splines and NURBS in `N ≥ 1`
//! directions, their evaluation at points and on grids, operations along one direction, and
//! interpolation of grids by sweeps of banded solves. The formulas, costs and memory are in
//! `docs/theory/tensor.md`. For `N = 1` and `N = 2` they are the curves and surfaces of
//! [`curve`](crate::curve) and [`surface`](crate::surface), with which they convert bit for bit.
//!
//! - `spline.rs`: [`TensorBSpline`], the type and its validation (net layout: first direction
//!   slowest), and its evaluation at a point, partial derivatives and batches (by the kernels
//!   of `eval.rs` and `contract.rs`).
//! - `view.rs`: [`TensorBSplineRef`], a spline whose arrays are borrowed, its validation, sizes
//!   and domain.
//! - `contract.rs`: the point kernel: scratch sized once for a spline, the basis vectors of
//!   every direction, the window contraction (sum factorisation) and the fixed-size bivariate
//!   and trivariate kernels.
//! - `eval.rs`: evaluation at points: single points, partial derivatives, sequential, parallel
//!   and cell-ordered batches.
//! - `cell_order.rs`: the cell order of a large batch (a counting sort of the points by the
//!   cell of a coarse grid over the domain), its gather and the values put back.
//! - `fixed.rs`: the batch kernels of scalar splines in two or three directions of one degree
//!   (the bases of all directions at once, fixed-size contractions).
//! - `locate.rs`: the span search of batches, a bucket table per direction (O(1) a point), and
//!   what a batch does at a point beyond the domain ([`Beyond`]).
//! - `point_value.rs`: [`tensor_value_by`], the value at one point of a scalar spline whose
//!   arrays are read through accessors (SciPy's scalar calls on arrays in place).
//! - `grid_eval.rs`: evaluation on the outer product of per-direction parameter lists
//!   ([`TensorBSpline::eval_grid`]) by sum factorisation, the same bits as point by point.
//! - `slice.rs`: knot insertion per direction, slicing (fixing parameters), conversion to and
//!   from [`BSplineCurve`](crate::BSplineCurve) and [`BSplineSurface`](crate::BSplineSurface).
//! - `nurbs.rs`: [`TensorNurbs`], the B-spline of homogeneous points, and its quotient rule.
//! - `interpolate.rs`: [`TensorInterpolation`], grid interpolation by one factorisation and one
//!   sweep of solves per direction.
//! - `any.rs`: [`Tensor`], one value for either kind.
//! - `fit.rs`: [`tensor_grid_least_squares`], least squares on a grid with given knots by one
//!   sweep of curve fits per direction.
//! - `grid_smoothing.rs`: [`tensor_grid_smoothing`], the fewest knots whose residual on a grid
//!   is at most `s` (FITPACK `regrid` in `N` directions), one banded sweep per direction a
//!   solve.
//! - `grid_penalized.rs`: [`tensor_grid_smoothing_spline`], the smoothing spline on a grid
//!   with a penalty weight per direction, given or chosen by GCV ([`tensor_grid_gcv_score`]):
//!   the separable (sandwich) smoother, one sweep of the curve's banded smoothing solves per
//!   direction.
//! - `test_grids.rs` (tests only): the grids both grid fits' tests sample.
//! - `integral.rs`: [`TensorBSpline::integral`], the integral over a box.
//! - `scattered.rs`: [`tensor_scattered_least_squares`], least squares on scattered points in
//!   `N` variables by banded normal equations, and [`tensor_scattered_least_squares_with`], the
//!   same with FITPACK's minimal-norm answer to a rank-deficient system, and
//!   [`tensor_scattered_penalized_least_squares`], with a second-difference penalty that fills
//!   the cells without data.
//! - `design_matrix.rs`: [`tensor_design_matrix`], the basis products at points (rows the
//!   Kronecker products of the one-direction basis rows).
//! - `scattered_qr.rs`: the observation matrix of scattered data as a band triangle (Givens
//!   rotations), the rows of the derivative jumps, and the minimal-norm solve
//!   ([`RankDeficiency`], FITPACK `fprank`).
//! - `scattered_smoothing.rs`: [`tensor_scattered_smoothing`], the spline whose residual on
//!   scattered data is at most `s`, with the knots of FITPACK `surfit`.

mod any;
mod cell_order;
mod contract;
mod design_matrix;
mod eval;
mod fit;
mod fixed;
mod grid_eval;
mod grid_penalized;
mod grid_smoothing;
mod integral;
mod interpolate;
mod locate;
mod nurbs;
mod point_value;
mod scattered;
mod scattered_qr;
mod scattered_smoothing;
mod slice;
mod spline;
mod view;

pub use any::Tensor;
pub use design_matrix::{tensor_design_matrix, TensorDesignMatrix};
pub use fit::tensor_grid_least_squares;
pub use grid_penalized::{
    tensor_grid_gcv_score, tensor_grid_smoothing_spline,
    tensor_grid_smoothing_spline_with_progress, TensorGridSmoothingSpline, GCV_CYCLE_TOL,
    GCV_MAX_CYCLES,
};
pub use grid_smoothing::{
    tensor_grid_smoothing, tensor_grid_smoothing_with_progress, TensorGridSmoothing,
};
pub use interpolate::TensorInterpolation;
pub use locate::Beyond;
pub(crate) use locate::SpanTable;
pub use nurbs::{TensorNurbs, MAX_TENSOR_DERIVATIVE_TABLE};
pub use point_value::{tensor_value_by, MAX_POINT_VALUE_VARS};
pub use scattered::{
    tensor_scattered_least_squares, tensor_scattered_least_squares_with,
    tensor_scattered_penalized_least_squares, TensorScatteredFit,
};
pub use scattered_qr::RankDeficiency;
// the band triangle's rotation with fill-in and its minimal-norm solve, shared by the fits on
// the sphere
pub(crate) use scattered_qr::{rotate_full, solve as solve_triangle};
pub use scattered_smoothing::{
    tensor_scattered_smoothing, tensor_scattered_smoothing_with_progress, KnotLimit,
    ScatteredSmoothingOptions, TensorScatteredSmoothing,
};
pub use spline::TensorBSpline;
pub use view::TensorBSplineRef;

#[cfg(test)]
mod eval_tests;
#[cfg(test)]
mod test_grids;
#[cfg(test)]
mod tests;
