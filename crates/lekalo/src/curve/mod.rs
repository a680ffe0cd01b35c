//! Curves: Bezier, B-spline and NURBS curves, their knot operations and fast evaluation.
//!
//! - `bezier.rs`: [`BezierCurve`] (de Casteljau, Bernstein form) and [`BezierSegment`].
//! - `bspline.rs`: [`BSplineCurve`]: evaluation, derivatives, knot insertion and refinement,
//!   splitting, Bezier decomposition, reversal.
//! - `nurbs.rs`: [`NurbsCurve`], a B-spline over homogeneous points; exact circles and arcs.
//! - `nurbs_ops.rs`: knot operations on NURBS curves through their homogeneous B-spline.
//! - `knot_removal.rs`: knot removal with a tolerance and curve simplification.
//! - `curvature.rs`: [`curvature`] from the first two derivatives.
//! - `fast_eval.rs`: [`CurveEvaluator`] and [`NurbsEvaluator`], batch evaluation by polynomial
//!   pieces.

pub(crate) mod bezier;
pub(crate) mod bspline;
mod curvature;
mod fast_eval;
pub(crate) mod knot_removal;
pub(crate) mod nurbs;
mod nurbs_ops;

pub use bezier::{BezierCurve, BezierSegment};
pub use bspline::BSplineCurve;
pub use curvature::curvature;
pub use fast_eval::{CurveEvaluator, EvalKernel, NurbsEvaluator, POWER_FORM_MAX_DEGREE};
pub use knot_removal::DEFAULT_REMOVAL_RTOL;
pub use nurbs::NurbsCurve;
