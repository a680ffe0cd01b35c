//! # lekalo — spline curves and surfaces
//!
//! ("Лекало" is the draftsman's curve template: the first spline.)
//!
//! A spline kernel in pure Rust: Bezier, B-spline and NURBS curves and surfaces; interpolation
//! of points and grids; Bezier degree change; C^k blending of curves; piecewise polynomials and
//! their B-spline bases. It implements five Russian documents on curves and splines (see
//! `docs/` and the digest) and what users of SciPy, Open CASCADE, geomdl or tinyspline expect.
//!
//! ## Conventions
//! - Scalars are `f64`. Points of any dimension are stored flat and point-major ([`Points`]).
//! - Degree `p`, order `p + 1`. Knot domains are `[t_p, t_{n+1}]`; spans are half-open and the
//!   right end of the domain belongs to the last span ([`KnotVector`]).
//! - NURBS are B-splines over homogeneous points `(w·x, …, w)`.
//! - Every function that takes user data validates it and returns [`Result`]; nothing panics on
//!   user input. Errors are one enum, [`Error`].
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
mod error;
mod knots;
mod nurbs;
mod nurbs_surface;
#[cfg(test)]
mod oracle;
mod points;
mod surface;

pub use bezier::{BezierCurve, BezierSegment};
pub use bezier_surface::BezierSurface;
pub use bspline::BSplineCurve;
pub use error::{Error, Result, MAX_SCALARS};
pub use knots::{check_parameters, KnotVector, SpanCursor};
pub use nurbs::NurbsCurve;
pub use nurbs_surface::NurbsSurface;
pub use points::{Points, PointsRef};
pub use surface::BSplineSurface;

// -- interpolation (issue 3) --
mod hermite;
mod interpolate;
mod linalg;

// -- Bezier order change (issue 4) --
mod bezier_degree;

// -- blending (issue 5) --
mod blend;

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

// -- formats (issue 7) --
mod format;

// -- robustness (issue 9) --
pub use error::{MAX_DEGREE, MAX_DERIVATIVE_ORDER, MAX_SURFACE_DERIVATIVE_ORDER};
