//! Fits of functions `y(x)` that keep their shape: increasing or decreasing, convex or concave,
//! above or below bounds, on the whole domain, on intervals or at points, with equalities of
//! values and derivatives at points, of integrals, and periodicity
//! (`docs/theory/fitting.md#shape-constraints`).
//!
//! Every shape is a sign condition `σ(y⁽ʳ⁾ − v) ≥ 0` for every `x` of an interval. On each piece
//! of a knot span it is a condition on the Bernstein coefficients of `y⁽ʳ⁾` there, which are
//! linear in the control points; the condition is exact (necessary and sufficient) where the
//! constrained derivative has degree `d = p − r ≤ 3` and sufficient only for `d ≥ 4`. The fit is
//! the solution of a convex quadratic program with second-order cones, solved by Clarabel on a
//! working set of pieces grown until its answer keeps every row (then the whole program's
//! optimum).
//!
//! | file | what it does |
//! |---|---|
//! | `constraints.rs` | [`Shape`], [`ShapeConstraint`], [`PointCondition`], [`IntegralCondition`], [`ShapeConstraints`]: what is kept, validated against the domain |
//! | `bernstein.rs` | the Bernstein coefficients of `y⁽ʳ⁾` on a piece of a span as rows over the control points; the exact minimum of a polynomial of degree ≤ 3 on `[0, 1]` and where it is taken (crate-private) |
//! | `row.rs` | `Row`: a linear function of the coefficients local to a span, the unit of every program (crate-private) |
//! | `program.rs` | the cone program (banded objective, linear and second-order-cone rows), its solution by Clarabel, the polish on the active face, infeasibility certificates mapped back to constraints (crate-private) |
//! | `face_rows.rs` | the rows of a polished face: duplicates dropped, and on a degenerate face the independent ones, by Givens rotations along the band (crate-private) |
//! | `check.rs` | [`shape_violations`], [`SHAPE_RTOL`]: the exact check of a curve against the constraints, and the scales it is measured in (crate-private otherwise) |
//! | `working_set.rs` | the cone program on a working set of pieces grown until its optimum keeps every row, the polish and the exact check of its answer (crate-private) |
//! | `fits.rs` | [`constrained_least_squares`], [`constrained_smoothing_spline`], [`constrained_smoothing_condition`]: the unconstrained fit first, the working set when it breaks a constraint |
//! | `surface/` | [`constrained_surface_grid_least_squares`], [`constrained_surface_scattered_least_squares`], [`constrained_surface_grid_smoothing_spline`], [`constrained_surface_grid_smoothing_condition`], [`surface_shape_violations`]: surfaces `z(u, v)` monotone per direction and bounded, by least squares or the grid's smoothing spline, by linear Bernstein conditions on each knot cell and the same solver (`program.rs`'s sparse entry) |

mod bernstein;
mod check;
mod constraints;
mod face_rows;
mod fits;
mod program;
mod row;
mod surface;
mod working_set;

pub use check::{shape_violations, SHAPE_RTOL};
pub use constraints::{
    IntegralCondition, PointCondition, Shape, ShapeConstraint, ShapeConstraints,
};
pub use fits::{
    constrained_least_squares, constrained_smoothing_condition,
    constrained_smoothing_condition_with_progress, constrained_smoothing_spline,
    constrained_smoothing_spline_with_progress, CONDITION_RTOL,
};
pub use surface::{
    constrained_surface_grid_least_squares, constrained_surface_grid_smoothing_condition,
    constrained_surface_grid_smoothing_spline, constrained_surface_scattered_least_squares,
    surface_shape_violations, SurfaceGridSmoothing, SurfaceShape, SurfaceShapeConstraint,
    SurfaceShapeConstraints,
};

#[cfg(test)]
mod tests;
