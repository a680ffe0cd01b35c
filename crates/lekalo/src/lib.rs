//! # lekalo — spline curves and surfaces
//!
//! ("Лекало" is the draftsman's curve template: the first spline.)
//!
//! A spline kernel in pure Rust: Bezier, B-spline and NURBS curves and surfaces; interpolation
//! of points and grids; Bezier degree change; C^k blending of curves; piecewise polynomials and
//! their B-spline bases. It implements five Russian documents on curves and splines (see
//! `docs/` and the digest) and what users of SciPy, Open CASCADE, geomdl or tinyspline expect.
//!
//! ## What is here
//!
//! | area | main items | source |
//! |---|---|---|
//! | points, knots, bases | [`Points`], [`KnotVector`], [`basis`] | doc 000 eq. 2–4, 8; doc 002 §C.5; doc 003 Thm 4.5 |
//! | curves | [`BezierCurve`], [`BSplineCurve`], [`NurbsCurve`] (exact circles and arcs) | doc 002 §C.4–C.5; P&T ch. 2–5, 7 |
//! | surfaces | [`BezierSurface`], [`BSplineSurface`], [`NurbsSurface`] | P&T ch. 3–4 |
//! | interpolation | [`CurveInterpolation`], [`interpolate_surface`], [`natural_cubic_spline`], [`CubicHermite`] | doc 000; doc 002 §C.2–C.3 |
//! | Bezier degree change | [`BezierCurve::elevate_degree`], [`BezierCurve::change_degree`], [`BezierCurve::real_degree`], [`ElevationPlan`] | doc 004 |
//! | blending | [`JumpPolynomial`], [`Deformation`], [`BlendSpline`], [`CornerTransition`] | doc 001 |
//! | piecewise polynomials | [`PiecewisePolynomial`], [`PpSpace`], [`divided_difference`], [`quasi_interpolate`] | doc 003 |
//!
//! ## Conventions
//! - Scalars are `f64`. Points of any dimension are stored flat and point-major ([`Points`]).
//! - Degree `p`, order `p + 1`. Knot domains are `[t_p, t_{n+1}]`; spans are half-open and the
//!   right end of the domain belongs to the last span ([`KnotVector`]).
//! - NURBS are B-splines over homogeneous points `(w·x, …, w)`.
//! - Every function that takes user data validates it and returns [`Result`]; nothing panics on
//!   user input. Errors are one enum, [`Error`].
//! - No `unsafe` code but two kinds of call, each with its safety argument beside it:
//!   - on Linux, large result buffers (4 MiB and more, e.g. the control points of an
//!     interpolation through 10^6 points) are marked for transparent huge pages with `madvise`,
//!     as NumPy marks its arrays, because first-touch page faults otherwise cost as much as the
//!     arithmetic (`large_buffer`);
//!   - a few throughput-bound kernels have a second copy compiled with AVX2, called after the
//!     processor's AVX2 is detected (`isa`); without FMA, so both copies return the same bits.
//!
//!   See `docs/performance.md`.
//!
//! ## Example
//! ```
//! use lekalo::{BSplineCurve, KnotVector, Points};
//! let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
//! let curve = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4)?, ctrl)?;
//! let mid = curve.eval(0.5)?;
//! assert!((mid[0] - 2.0).abs() < 1e-15 && (mid[1] - 1.5).abs() < 1e-15);
//! # Ok::<(), lekalo::Error>(())
//! ```

// -- foundation (issue 2) --
pub mod basis;
mod bezier;
mod bezier_surface;
mod bspline;
mod differential;
mod error;
mod fast_eval;
mod isa;
mod knot_removal;
mod knots;
mod large_buffer;
mod nurbs;
mod nurbs_ops;
mod nurbs_surface;
#[cfg(test)]
mod oracle;
mod points;
mod surface;
mod surface_ops;

pub use bezier::{BezierCurve, BezierSegment};
pub use bezier_surface::BezierSurface;
pub use bspline::BSplineCurve;
pub use differential::curvature;
pub use error::{Error, Result, MAX_SCALARS};
pub use fast_eval::{CurveEvaluator, EvalKernel, NurbsEvaluator, POWER_FORM_MAX_DEGREE};
pub use knot_removal::DEFAULT_REMOVAL_RTOL;
pub use knots::{check_parameters, KnotVector, SpanCursor};
pub use nurbs::NurbsCurve;
pub use nurbs_surface::NurbsSurface;
pub use points::{Points, PointsRef};
pub use surface::BSplineSurface;
pub use surface_ops::{BezierPatch, RationalBezierPatch};

// -- interpolation (issue 3) --
mod cubic_sweep;
mod hermite;
mod interpolate;
mod interpolate_fast;
mod interpolate_periodic;
mod interpolate_surface;
mod linalg;

pub use hermite::{
    cubic_through_four_points, four_point_cubic_coefficients, hermite_segment_coefficients,
    CubicHermite, TangentEstimate, HERMITE_MATRIX,
};
pub use interpolate::{
    natural_cubic_spline, parametrize, CurveInterpolation, EndCondition, KnotPlacement,
    Parametrization, INTERPOLATION_RESIDUAL_RTOL,
};
pub use interpolate_fast::InterpolationWorkspace;
pub use interpolate_surface::{interpolate_surface, SurfaceInterpolant};

// -- Bezier order change (issue 4) --
mod bezier_degree;
mod bezier_degree_approx;
mod bezier_degree_bspline;
mod bezier_degree_matrix;
mod bezier_degree_plan;
mod bezier_degree_surface;

pub use bezier_degree::{DEFAULT_DEGREE_TOLERANCE, MAX_MONOMIAL_DEGREE};
pub use bezier_degree_approx::{ApproximateReduction, EndConditions, APPROX_SAMPLES};
pub use bezier_degree_bspline::BSplineApproximateReduction;
pub use bezier_degree_matrix::{
    bernstein_monomial_matrix, bernstein_monomial_matrix_inverse, elevation_block,
    elevation_matrix, order_change_matrix, reduction_block, truncation_matrix, RationalMatrix,
    MAX_EXACT_MATRIX_DEGREE,
};
pub use bezier_degree_plan::ElevationPlan;
pub use bezier_degree_surface::{
    bezier_net_change_degree, bezier_net_elevate, bezier_net_from_monomial,
    bezier_net_real_degrees, bezier_net_real_degrees_monomial, bezier_net_to_monomial,
};

// -- blending (issue 5) --
mod bernstein_ops;
mod blend;
mod blend_approx;
mod blend_spline;
mod corner;
mod jump;

pub use blend::{BezierForm, Deformation, FnCurve, ParametricCurve, ENDPOINT_TOLERANCE};
pub use blend_approx::{approximate_curve, Approximation};
pub use blend_spline::{
    ArcParametrization, BlendSpline, BlendSplineOptions, CircularArcs, Continuity, FnLocalCurves,
    LocalCurves, Parabolas, SharedCurve, SplineParameters,
};
pub use corner::CornerTransition;
pub use jump::JumpPolynomial;

// -- piecewise polynomials (issue 6) --
mod divdiff;
mod ppform;
mod quasi;

pub use divdiff::{
    bspline_divided_difference, divided_difference, divided_difference_explicit, truncated_power,
    NewtonForm,
};
pub use ppform::{PiecewisePolynomial, PpSpace, DEFAULT_CONTINUITY_RTOL};
pub use quasi::{quasi_interpolate, sample_quasi_interpolant, QuasiSamples, TauRule};

// -- robustness (issue 9) --
pub use error::{MAX_DEGREE, MAX_DERIVATIVE_ORDER, MAX_SURFACE_DERIVATIVE_ORDER};
pub use interpolate_surface::{interpolate_surface_condition, interpolate_surface_max_condition};

// -- geometric queries --
pub mod query;

pub use query::{
    ArcLength, CurveProjection, QueryCurve, QuerySurface, SurfaceProjection, MAX_QUERY_DEGREE,
};
