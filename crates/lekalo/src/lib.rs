//! # lekalo — spline curves and surfaces
//!
//! ("Лекало" is the draftsman's curve template: the first spline.)
//!
//! A spline kernel in pure Rust: Bezier, B-spline and NURBS curves and surfaces; interpolation
//! of points and grids; Bezier degree change; C^k blending of curves; piecewise polynomials and
//! their B-spline bases. It implements five Russian documents on curves and splines (see
//! `docs/theory.md`) and what users of SciPy, Open CASCADE, geomdl or tinyspline expect.
//!
//! ## What is here
//!
//! | area (module) | main items | source |
//! |---|---|---|
//! | points, knots, bases ([`basis`]) | [`Points`], [`KnotVector`], [`basis`] | doc 000 eq. 2–4, 8; document 002, B-splines; doc 003 Thm 4.5 |
//! | curves ([`curve`]) | [`BezierCurve`], [`BSplineCurve`], [`NurbsCurve`] (exact circles and arcs) | document 002, Bezier curves and B-splines; P&T ch. 2–5, 7 |
//! | surfaces ([`surface`]) | [`BezierSurface`], [`BSplineSurface`], [`NurbsSurface`] | P&T ch. 3–4 |
//! | tensor products in N parameters ([`tensor`]) | [`TensorBSpline`], [`TensorNurbs`], [`Tensor`] (either kind), [`TensorInterpolation`], [`tensor_grid_least_squares`], [`tensor_grid_smoothing`], [`tensor_grid_smoothing_spline`], [`tensor_scattered_least_squares`], [`tensor_scattered_smoothing`] | P&T §3.4, §4.4; `docs/theory/tensor.md` |
//! | interpolation ([`interpolate`]) | [`CurveInterpolation`], [`SurfaceInterpolation`], [`natural_cubic_spline`], [`CubicHermite`] | doc 000; document 002, four-point cubic and Hermite segment |
//! | Bezier degree change ([`degree`]) | [`BezierCurve::elevate_degree`], [`BezierCurve::change_degree`], [`BezierCurve::real_degree`], [`ElevationPlan`] | doc 004 |
//! | blending ([`blend`]) | [`JumpPolynomial`], [`Deformation`], [`BlendSpline`], [`CornerTransition`], [`smooth_polyline_corners`] | doc 001 |
//! | piecewise polynomials ([`pp`]) | [`PiecewisePolynomial`], [`PpSpace`], [`divided_difference`], [`quasi_interpolate`], [`piecewise_hermite_bernstein`] | doc 003 |
//! | derivatives for automatic differentiation ([`derivatives`]) | [`BSplineCurve::eval_batch_jvp`], [`BSplineCurve::eval_batch_vjp`], [`BSplineCurve::eval_batch_linearize`], the same for [`BSplineSurface`] | P&T A2.3; `docs/theory.md` |
//! | faces of CAD models ([`topology`]) | [`Face`], [`Loop`], [`Edge`], [`TrimRegion`] (point in face) | ISO 10303-42 §5; Hormann & Agathos 2001 |
//! | fitting | [`least_squares`], [`smoothing_spline`], [`smoothing_condition`], [`fit_tolerance`], [`fit`] | P&T §9.4; Dierckx; `docs/theory/fitting.md` |
//!
//! ## Conventions
//! - Scalars are `f64`. Points of any dimension are stored flat and point-major ([`Points`],
//!   built by [`Points::from_flat`]).
//! - Degree `p`, order `p + 1`. Knot domains are `[t_p, t_{n+1}]`; spans are half-open and the
//!   right end of the domain belongs to the last span ([`KnotVector`]).
//! - NURBS are B-splines over homogeneous points `(w·x, …, w)`.
//! - Every function that takes user data validates it and returns [`Result`]; nothing panics on
//!   user input. Errors are one enum, [`Error`].
//! - No `unsafe` code but two kinds of call, each with its safety argument beside it:
//!   - on Linux, large result buffers (4 MiB and more, e.g. the control points of an
//!     interpolation through 10^6 points) are marked for transparent huge pages with `madvise`,
//!     as NumPy marks its arrays, because first-touch page faults otherwise cost as much as the
//!     arithmetic (`numeric/large_buffer.rs`);
//!   - a few throughput-bound kernels have a second copy compiled with AVX2, called after the
//!     processor's AVX2 is detected (`numeric/isa.rs`); without FMA, so both copies return the
//!     same bits.
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
mod arg;
pub mod basis;
mod error;
mod knots;
mod message;
mod points;

pub use arg::{Arg, What};
pub use error::{
    ControlSupport, Error, Result, MAX_DEGREE, MAX_DERIVATIVE_ORDER, MAX_SCALARS,
    MAX_SURFACE_DERIVATIVE_ORDER,
};
pub use knots::{breakpoints_sorted, check_parameters, uniform_parameters, KnotVector, SpanCursor};
pub use points::{Points, PointsRef};

// -- curves: Bezier, B-spline, NURBS, knot operations, fast evaluation --
pub mod curve;

pub use curve::{
    bspline_value, bspline_value_by, curvature, insert_knot_into, insert_knot_periodic,
    insert_knot_raw, principal_normal, torsion, BSplineCurve, Beyond, BezierCurve, BezierSegment,
    Curve, CurveEvaluator, EvalKernel, NurbsCurve, NurbsEvaluator, COMPOSITE_GAP_RTOL,
    DEFAULT_REMOVAL_RTOL, POWER_FORM_MAX_DEGREE,
};

// -- surfaces: tensor-product Bezier, B-spline, NURBS --
pub mod surface;

pub use surface::{
    surface_curvature, BSplineSurface, BezierPatch, BezierSurface, Direction, NurbsSurface,
    RationalBezierPatch, Surface, SurfaceCurvature,
};

// -- interpolation: curves and surfaces through points, natural and Hermite splines --
pub mod interpolate;

pub use interpolate::{
    akima_slopes, akima_slopes_into, cubic_through_four_points, four_point_cubic_coefficients,
    hermite_segment_coefficients, interpolate_with_end_derivatives, natural_cubic_spline,
    parametrize, pchip_slopes, pchip_slopes_into, CubicHermite, CurveInterpolation, EndCondition,
    EndDerivative, InterpolationWorkspace, KnotPlacement, Parametrization, SurfaceInterpolation,
    SurfaceInterpolationReport, TangentEstimate, HERMITE_MATRIX, INTERPOLATION_RESIDUAL_RTOL,
};
// the grid interpolation functions before `SurfaceInterpolation`, kept for existing code
#[allow(deprecated)]
pub use interpolate::{
    interpolate_surface, interpolate_surface_condition, interpolate_surface_max_condition,
    SurfaceInterpolant,
};

// -- tensor products in N parameters: B-splines, NURBS, grid interpolation --
pub mod tensor;

pub use tensor::{
    tensor_grid_gcv_score, tensor_grid_least_squares, tensor_grid_smoothing,
    tensor_grid_smoothing_spline, tensor_grid_smoothing_spline_with_progress,
    tensor_grid_smoothing_with_progress, tensor_scattered_least_squares,
    tensor_scattered_least_squares_with, tensor_scattered_penalized_least_squares,
    tensor_scattered_smoothing, tensor_scattered_smoothing_with_progress, KnotLimit,
    RankDeficiency, ScatteredSmoothingOptions, Tensor, TensorBSpline, TensorBSplineRef,
    TensorGridSmoothing, TensorGridSmoothingSpline, TensorInterpolation, TensorNurbs,
    TensorScatteredFit, TensorScatteredSmoothing, MAX_TENSOR_DERIVATIVE_TABLE,
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
    BlendSplineOptions, BlendSplinePieces, CircularArcs, Continuity, CornerTransition, Deformation,
    FnCurve, FnLocalCurves, JumpPolynomial, LocalCurves, Parabolas, ParametricCurve, SharedCurve,
    SplineParameters, ENDPOINT_TOLERANCE,
};
pub use blend::{smooth_polyline_corners, CornerWindow, SmoothedPolyline, MAX_POLYLINE_CONTINUITY};

// -- piecewise polynomials: divided differences, pp-form, quasi-interpolation --
pub mod pp;

pub use pp::{
    bspline_divided_difference, divided_difference, divided_difference_explicit, hermite_bernstein,
    piecewise_hermite_bernstein, quasi_interpolate, quasi_interpolate_expression,
    sample_quasi_interpolant, sample_quasi_interpolant_expression, truncated_power, Expression,
    NewtonForm, PiecewisePolynomial, PpSpace, QuasiSamples, Tau, TauRule, DEFAULT_CONTINUITY_RTOL,
    MAX_EXPRESSION_LEN, MAX_EXPRESSION_ORDER, MAX_HERMITE_DEGREE,
};

// -- fitting: least squares, smoothing, fitting to a tolerance --
pub mod fit;

pub use fit::{
    fit_tolerance, least_squares, place_knots, smoothing_condition, smoothing_spline, CurveFit,
    EndConstraints, FitData, FitReport, Lambda, ToleranceOptions,
};

// -- numerical building blocks (crate-private) and the test oracle --
mod numeric;

/// Progress reports and cancellation of long computations.
pub use numeric::progress::Progress;
#[cfg(test)]
mod oracle;

// -- geometric queries: length, closest points, intersections, offsets, tessellation, curvature --
pub mod query;

pub use query::{
    ArcLength, CurveProjection, QueryCurve, QuerySurface, SurfaceProjection,
    CURVATURE_EXTREMUM_RTOL, MAX_QUERY_DEGREE, SURFACE_BOX_RTOL,
};

// -- topology: faces of CAD models, surfaces trimmed by loops of edges --
pub mod topology;

pub use topology::{Edge, Face, Loop, TrimRegion};

// -- derivatives of evaluation for differentiable programs: JVP, VJP, linearisation --
pub mod derivatives;

pub use derivatives::{CurveLinearization, NurbsLinearization, SurfaceLinearization};

// -- the words of the options every front end shares, one canonical spelling each --
pub mod vocabulary;
