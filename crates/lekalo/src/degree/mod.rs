//! Changing the degree of Bezier curves and surfaces without changing their shape (document
//! 004), and of B-splines piece by piece.
//!
//! - `curve.rs`: exact elevation, exact reduction and the real degree of a Bezier curve
//!   (methods of [`BezierCurve`](crate::BezierCurve)).
//! - `matrices.rs`: the document's matrices in exact rational arithmetic ([`RationalMatrix`]).
//! - `elevation_plan.rs`: [`ElevationPlan`], precomputed elevation for many curves of one degree.
//! - `approx_reduction.rs`: least-squares degree reduction ([`ApproximateReduction`]).
//! - `bspline.rs`: degree change of B-spline curves and surfaces through Bezier pieces.
//! - `surface.rs`: degree change of tensor-product Bezier nets (`bezier_net_*`).

mod approx_reduction;
mod bspline;
pub(crate) mod curve;
mod elevation_plan;
mod matrices;
mod surface;

pub use approx_reduction::{ApproximateReduction, EndConditions, APPROX_SAMPLES};
pub use bspline::BSplineApproximateReduction;
pub use curve::{DEFAULT_DEGREE_TOLERANCE, MAX_MONOMIAL_DEGREE};
pub use elevation_plan::ElevationPlan;
pub use matrices::{
    bernstein_monomial_matrix, bernstein_monomial_matrix_inverse, elevation_block,
    elevation_matrix, order_change_matrix, reduction_block, truncation_matrix, RationalMatrix,
    MAX_EXACT_MATRIX_DEGREE,
};
pub use surface::{
    bezier_net_change_degree, bezier_net_elevate, bezier_net_from_monomial,
    bezier_net_real_degrees, bezier_net_real_degrees_monomial, bezier_net_to_monomial,
};
