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

// -- foundations: points, knots, B-spline bases, errors --
pub mod basis;
mod error;
mod knots;
mod points;

pub use error::{
    Error, Result, MAX_DEGREE, MAX_DERIVATIVE_ORDER, MAX_SCALARS, MAX_SURFACE_DERIVATIVE_ORDER,
};
pub use knots::{check_parameters, KnotVector, SpanCursor};
pub use points::{Points, PointsRef};

// -- curves: Bezier, B-spline, NURBS, knot operations, fast evaluation --
pub mod curve;

pub use curve::{
    curvature, BSplineCurve, BezierCurve, BezierSegment, CurveEvaluator, EvalKernel, NurbsCurve,
    NurbsEvaluator, DEFAULT_REMOVAL_RTOL, POWER_FORM_MAX_DEGREE,
};

// -- surfaces: tensor-product Bezier, B-spline, NURBS --
pub mod surface;

pub use surface::{BSplineSurface, BezierPatch, BezierSurface, NurbsSurface, RationalBezierPatch};

// -- interpolation: curves and surfaces through points, natural and Hermite splines --
pub mod interpolate;

pub use interpolate::{
    cubic_through_four_points, four_point_cubic_coefficients, hermite_segment_coefficients,
    interpolate_surface, interpolate_surface_condition, interpolate_surface_max_condition,
    natural_cubic_spline, parametrize, CubicHermite, CurveInterpolation, EndCondition,
    InterpolationWorkspace, KnotPlacement, Parametrization, SurfaceInterpolant, TangentEstimate,
    HERMITE_MATRIX, INTERPOLATION_RESIDUAL_RTOL,
};

// -- degree change of Bezier curves and surfaces --
pub mod degree;

pub use degree::{
    bernstein_monomial_matrix, bernstein_monomial_matrix_inverse, bezier_net_change_degree,
    bezier_net_elevate, bezier_net_from_monomial, bezier_net_real_degrees,
    bezier_net_real_degrees_monomial, bezier_net_to_monomial, elevation_block, elevation_matrix,
    order_change_matrix, reduction_block, truncation_matrix, ApproximateReduction,
    BSplineApproximateReduction, ElevationPlan, EndConditions, RationalMatrix, APPROX_SAMPLES,
    DEFAULT_DEGREE_TOLERANCE, MAX_EXACT_MATRIX_DEGREE, MAX_MONOMIAL_DEGREE,
};

// -- blending: jump polynomials, deformation, blended splines, corners --
pub mod blend;

pub use blend::{
    approximate_curve, Approximation, ArcParametrization, BezierForm, BlendSpline,
    BlendSplineOptions, CircularArcs, Continuity, CornerTransition, Deformation, FnCurve,
    FnLocalCurves, JumpPolynomial, LocalCurves, Parabolas, ParametricCurve, SharedCurve,
    SplineParameters, ENDPOINT_TOLERANCE,
};

// -- piecewise polynomials: divided differences, pp-form, quasi-interpolation --
pub mod pp;

pub use pp::{
    bspline_divided_difference, divided_difference, divided_difference_explicit, quasi_interpolate,
    sample_quasi_interpolant, truncated_power, NewtonForm, PiecewisePolynomial, PpSpace,
    QuasiSamples, TauRule, DEFAULT_CONTINUITY_RTOL,
};

// -- numerical building blocks (crate-private) and the test oracle --
mod numeric;
#[cfg(test)]
mod oracle;

// -- geometric queries: length, closest points, intersections, offsets, tessellation, curvature --
pub mod query;

pub use query::{
    ArcLength, CurveProjection, QueryCurve, QuerySurface, SurfaceProjection, MAX_QUERY_DEGREE,
};
