//! Surfaces `z(u, v)` that keep their shape: increasing or decreasing in `u` and/or `v`, above
//! or below constant bounds, on the whole domain or on boxes of it, fitted by least squares on a grid or on
//! scattered data (`docs/theory/fitting.md#shape-constraints-of-surfaces`).
//!
//! Every shape is a sign condition on a tensor polynomial on each knot cell (`z` itself, or
//! `∂z/∂u` of degree `(p − 1, q)`, or `∂z/∂v`); the fit asks its Bernstein coefficients to have
//! that sign, linear inequalities on the control net, sufficient everywhere and necessary where
//! the polynomial has degree ≤ 1 in each variable. The program is a convex quadratic program
//! solved by Clarabel through the curve's solver (`program.rs`, with a sparse objective).
//!
//! | file | what it does |
//! |---|---|
//! | `constraints.rs` | [`SurfaceShape`], [`SurfaceShapeConstraint`], [`SurfaceShapeConstraints`]: what is kept and where, validated against the degrees and the domain |
//! | `cells.rs` | the Bernstein coefficients on every knot cell (or piece of one inside a box) of `z`, `∂z/∂u` or `∂z/∂v` as sparse rows over the net (crate-private) |
//! | `check.rs` | [`surface_shape_violations`]: the Bernstein condition of a surface per constraint |
//! | `fits.rs` | [`constrained_surface_grid_least_squares`], [`constrained_surface_scattered_least_squares`]: the unconstrained fit first, the program when it breaks a constraint |
//! | `smoothing.rs` | [`constrained_surface_grid_smoothing_spline`], [`constrained_surface_grid_smoothing_condition`], [`SurfaceGridSmoothing`]: the grid's smoothing spline (penalty weights given, by GCV, or for a residual `s`) kept in shape, its penalised objective the program's |
//! | `whitened.rs` | the smoothing program in whitened variables: each direction's penalised Gram matrix factored, the correction to the unconstrained minimum solved with the identity for its Hessian (crate-private) |

mod cells;
mod check;
mod constraints;
mod fits;
mod smoothing;
mod whitened;

pub use check::surface_shape_violations;
pub use constraints::{SurfaceShape, SurfaceShapeConstraint, SurfaceShapeConstraints};
pub use fits::{
    constrained_surface_grid_least_squares, constrained_surface_scattered_least_squares,
};
pub use smoothing::{
    constrained_surface_grid_smoothing_condition, constrained_surface_grid_smoothing_spline,
    SurfaceGridSmoothing,
};

#[cfg(test)]
mod tests;
