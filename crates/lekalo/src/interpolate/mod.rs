//! Interpolation: curves and surfaces through given points (document 000) and the natural
//! cubic and Hermite splines of document 002.
//!
//! - `curve.rs`: [`CurveInterpolation`]: parametrisation, knot placement, end conditions, the
//!   collocation system; [`natural_cubic_spline`].
//! - `fast.rs`: the fused fast path of free-end cubic interpolation
//!   ([`InterpolationWorkspace`]).
//! - `cubic_sweep.rs`: the fused collocation sweep of that fast path.
//! - `periodic.rs`: closed (periodic) curves, the cyclic banded system.
//! - `surface.rs`: tensor-product surface interpolation of a grid ([`interpolate_surface`]).
//! - `hermite.rs`: cubic Hermite splines ([`CubicHermite`]) and the cubic through four points.

mod cubic_sweep;
pub(crate) mod curve;
mod fast;
pub(crate) mod hermite;
mod periodic;
mod surface;

pub use curve::{
    natural_cubic_spline, parametrize, CurveInterpolation, EndCondition, KnotPlacement,
    Parametrization, INTERPOLATION_RESIDUAL_RTOL,
};
pub use fast::InterpolationWorkspace;
pub use hermite::{
    cubic_through_four_points, four_point_cubic_coefficients, hermite_segment_coefficients,
    CubicHermite, TangentEstimate, HERMITE_MATRIX,
};
pub use surface::{
    interpolate_surface, interpolate_surface_condition, interpolate_surface_max_condition,
    SurfaceInterpolant,
};
