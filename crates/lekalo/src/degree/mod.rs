//! Changing the degree of Bezier curves and surfaces without changing their shape (document
//! 004), and of B-splines piece by piece.
//!
//! - `curve.rs`: the methods of [`BezierCurve`](crate::BezierCurve): elevation, exact
//!   reduction, real degree, the unified order change; why the Bernstein path is the default.
//! - `elevation.rs`: the elevation kernel (eq. 8 in closed form) and the binomial table.
//! - `reduction.rs`: exact reduction (eq. 9) as least-squares inverse of elevation; the real
//!   degree.
//! - `monomial.rs`: the monomial (power) form and the paper's trailing-coefficient rule.
//! - `matrices.rs`: the document's matrices in exact rational arithmetic ([`RationalMatrix`]).
//! - `elevation_plan.rs`: [`ElevationPlan`], precomputed elevation for many curves of one degree.
//! - `approx_reduction.rs`: least-squares degree reduction ([`ApproximateReduction`]).
//! - `bspline.rs`: degree change of B-spline curves and surfaces through Bezier pieces.
//! - `surface.rs`: degree change of tensor-product Bezier nets (`bezier_net_*`).

mod approx_reduction;
mod bspline;
mod curve;
pub(crate) mod elevation;
mod elevation_plan;
mod matrices;
pub(crate) mod monomial;
pub(crate) mod reduction;
mod surface;

pub use approx_reduction::{ApproximateReduction, EndConditions, APPROX_SAMPLES};
pub use bspline::BSplineApproximateReduction;
pub use elevation_plan::ElevationPlan;
pub use matrices::{
    bernstein_monomial_matrix, bernstein_monomial_matrix_inverse, elevation_block,
    elevation_matrix, order_change_matrix, reduction_block, truncation_matrix, RationalMatrix,
    MAX_EXACT_MATRIX_DEGREE,
};
pub use monomial::MAX_MONOMIAL_DEGREE;
pub use reduction::DEFAULT_DEGREE_TOLERANCE;
pub use surface::{
    bezier_net_change_degree, bezier_net_elevate, bezier_net_from_monomial,
    bezier_net_real_degrees, bezier_net_real_degrees_monomial, bezier_net_to_monomial,
};
