//! Interpolation: curves and surfaces through given points (document 000) and the natural
//! cubic and Hermite splines of document 002.
//!
//! - `curve.rs`: [`CurveInterpolation`], the builder that combines a parametrisation, a knot
//!   placement ([`KnotPlacement`]) and end conditions, and checks the result's residual;
//!   [`natural_cubic_spline`] for functions `y(x)`.
//! - `parametrization.rs`: [`Parametrization`] and [`parametrize`]: uniform, chord length,
//!   centripetal parameters.
//! - `end_conditions.rs`: [`EndCondition`]: free ends, first and second end derivatives, the
//!   natural cubic.
//! - `end_derivatives.rs`: [`interpolate_with_end_derivatives`], interpolation on given knots
//!   with derivative conditions of any orders chosen per end ([`EndDerivative`]).
//! - `collocation.rs`: the banded collocation system and its condition estimate.
//! - `fast.rs`: the fused fast path of free-end cubic interpolation
//!   ([`InterpolationWorkspace`]).
//! - `cubic_sweep.rs`: the fused collocation sweep of that fast path.
//! - `periodic.rs`: closed (periodic) curves, the cyclic banded system.
//! - `surface.rs`: tensor-product surface interpolation of a grid ([`SurfaceInterpolation`]).
//! - `cubic_spline.rs`: SciPy's C² cubic spline by its slopes, one tridiagonal system with
//!   SciPy's end rows ([`cubic_spline_slopes_into`], [`cubic_spline_power_into`]).
//! - `hermite.rs`: cubic Hermite splines ([`CubicHermite`]) and the cubic through four points.
//! - `akima.rs`: [`akima_slopes`], Akima's and the modified Akima (makima) slopes (dimension 1
//!   in vectorised passes: [`akima_slopes_into`]).
//! - `pchip.rs`: [`pchip_slopes`], shape-preserving slopes for Hermite interpolation (PCHIP)
//!   (dimension 1 in one vectorised pass: [`pchip_slopes_into`]).

mod akima;
pub(crate) mod collocation;
mod cubic_spline;
mod cubic_sweep;
pub(crate) mod curve;
mod end_conditions;
mod end_derivatives;
mod fast;
pub(crate) mod hermite;
pub(crate) mod parametrization;
mod pchip;
mod periodic;
mod surface;

pub use akima::{akima_slopes, akima_slopes_into};
pub use cubic_spline::{cubic_spline_power_into, cubic_spline_slopes_into, CubicSplineEnd};
pub use curve::{
    natural_cubic_spline, CurveInterpolation, KnotPlacement, INTERPOLATION_RESIDUAL_RTOL,
};
pub use end_conditions::EndCondition;
pub use end_derivatives::{interpolate_with_end_derivatives, EndDerivative};
pub use fast::InterpolationWorkspace;
pub use hermite::{
    cubic_through_four_points, four_point_cubic_coefficients, hermite_segment_coefficients,
    CubicHermite, TangentEstimate, HERMITE_MATRIX,
};
pub use parametrization::{parametrize, Parametrization};
pub use pchip::{pchip_slopes, pchip_slopes_into};
#[allow(deprecated)]
pub use surface::{
    interpolate_surface, interpolate_surface_condition, interpolate_surface_max_condition,
    SurfaceInterpolant,
};
pub use surface::{SurfaceInterpolation, SurfaceInterpolationReport};
