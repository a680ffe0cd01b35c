//! Curves: Bezier, B-spline and NURBS curves, their knot operations and fast evaluation.
//!
//! - `any.rs`: [`Curve`], a curve of any of the three kinds with their shared capabilities
//!   delegated once (what every front end holds).
//! - `bezier.rs`: [`BezierCurve`] (de Casteljau, Bernstein form) and [`BezierSegment`].
//! - `bspline.rs`: [`BSplineCurve`]: evaluation, derivatives, the derivative curve, reversal,
//!   reparametrisation.
//! - `integral.rs`: antiderivatives, definite integrals and extrapolation by the end
//!   polynomials of [`BSplineCurve`].
//! - `knot_insertion.rs`: knot insertion and refinement, splitting, Bezier decomposition and
//!   its inverse.
//! - `periodic_insertion.rs`: [`insert_knot_periodic`], knot insertion keeping a periodic
//!   spline's extension, and [`insert_knot_raw`], insertion at any multiplicity (FITPACK's
//!   `fpinst`); [`insert_knot_into`], either into the caller's buffers.
//! - `roots.rs`: [`bspline_zeros`], the zeros of a scalar spline span by span, spans without a
//!   sign change among their coefficients skipped.
//! - `tck.rs`: [`derivative_coefficients_into`], [`antiderivative_coefficients_into`] (with
//!   [`antiderivative_knots_into`]) and [`integral_into`]: calculus on a spline given as arrays (SciPy's `(t, c, k)`), read in
//!   place and written into the caller's buffers.
//! - `nurbs.rs`: [`NurbsCurve`], a B-spline over homogeneous points.
//! - `composite.rs`: [`Curve::composite`], curves joined end to end into one (IGES 102).
//! - `conics.rs`: exact circles, circular and elliptic arcs as rational quadratics; straight
//!   segments.
//! - `nurbs_ops.rs`: knot operations on NURBS curves through their homogeneous B-spline.
//! - `power_form.rs`: piecewise polynomials in power form (IGES 112) as exact B-splines.
//! - `knot_removal.rs`: knot removal with a tolerance and curve simplification.
//! - `curvature.rs`: [`curvature`] and [`principal_normal`] from the first two derivatives,
//!   [`torsion`] from three.
//! - `fast_eval.rs`: [`CurveEvaluator`], batch evaluation by polynomial pieces; in
//!   `fast_eval/`: `locate.rs` (piece location, shared with `pp::piece_search`), `kernels.rs` (fixed-size kernels), `nurbs.rs`
//!   ([`NurbsEvaluator`]), `tests.rs`.

mod any;
pub(crate) mod bezier;
pub(crate) mod bspline;
mod composite;
mod conics;
mod curvature;
pub(crate) mod fast_eval;
mod integral;
mod knot_insertion;
pub(crate) mod knot_removal;
pub(crate) mod nurbs;
mod nurbs_ops;
mod periodic_insertion;
mod power_form;
mod roots;
mod tck;

pub use any::Curve;
pub use bezier::{BezierCurve, BezierSegment};
pub use bspline::BSplineCurve;
pub use composite::COMPOSITE_GAP_RTOL;
pub use curvature::{curvature, principal_normal, torsion};
pub(crate) use fast_eval::PieceLocator;
pub use fast_eval::{Beyond, CurveEvaluator, EvalKernel, NurbsEvaluator, POWER_FORM_MAX_DEGREE};
pub use integral::{bspline_value, bspline_value_by};
pub use knot_removal::DEFAULT_REMOVAL_RTOL;
pub use nurbs::NurbsCurve;
pub use periodic_insertion::{insert_knot_into, insert_knot_periodic, insert_knot_raw};
pub use power_form::POWER_FORM_CONTINUITY_RTOL;
pub use roots::bspline_zeros;
pub use tck::{
    antiderivative_coefficients_into, antiderivative_knots_into, basis_integrals_into,
    derivative_coefficients_into, integral_into,
};
