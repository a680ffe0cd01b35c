//! C^k blending of curves (document 001): jump-smoothing polynomials, deformation of one curve
//! into another, splines blended from local curves, corner smoothing.
//!
//! - `jump.rs`: [`JumpPolynomial`], the jump-smoothing polynomials `w_k`.
//! - `deformation.rs`: [`ParametricCurve`], [`Deformation`] and their exact Bezier/NURBS forms;
//!   the range of its continuity degree `k` ([`check_deformation_continuity`]).
//! - `spline.rs`: [`BlendSpline`], interpolating splines blended from local three-point curves.
//! - `pieces.rs`: [`BlendSplinePieces`], the exact NURBS form of a blend spline segment by
//!   segment, for splines through millions of points.
//! - `local_curves.rs`: the local curves: [`Parabolas`], [`CircularArcs`], [`FnLocalCurves`].
//! - `corner.rs`: [`CornerTransition`], corner smoothing by a deformation.
//! - `polyline.rs`: [`smooth_polyline_corners`], every corner of a polyline smoothed into one
//!   curve.
//! - `approximation.rs`: [`approximate_curve`], piecewise Hermite–Bezier approximation with
//!   measured error.
//! - `bernstein.rs`: Bernstein-form derivatives and products used by the above.

mod approximation;
pub(crate) mod bernstein;
mod corner;
pub(crate) mod deformation;
mod jump;
mod local_curves;
mod pieces;
mod polyline;
mod spline;

pub use approximation::{approximate_curve, Approximation};
pub use corner::CornerTransition;
pub use deformation::{
    check_deformation_continuity, deformation_bezier_degree, max_deformation_continuity,
    BezierForm, Deformation, FnCurve, ParametricCurve, ENDPOINT_TOLERANCE,
    MAX_DEFORMATION_CONTINUITY,
};
pub use jump::JumpPolynomial;
pub use local_curves::{
    ArcParametrization, CircularArcs, Continuity, FnLocalCurves, LocalCurves, Parabolas,
    SharedCurve,
};
pub use pieces::BlendSplinePieces;
pub use polyline::{
    smooth_polyline_corners, CornerWindow, SmoothedPolyline, MAX_POLYLINE_CONTINUITY,
};
pub use spline::{BlendSpline, BlendSplineOptions, SplineParameters};
