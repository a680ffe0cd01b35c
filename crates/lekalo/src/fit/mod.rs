//! Fitting: least squares, smoothing and fitting to a tolerance, for curves and surfaces.
//!
//! Interpolation passes through every point; fitting approximates many noisy points with fewer
//! control points, a smooth curve or a known error. The theory of every method, with the
//! anchors cited below, is in `docs/theory/fitting.md`.
//!
//! | file | what it does | theory |
//! |---|---|---|
//! | `banded.rs` | banded QR by Givens rotations or Householder blocks; banded `UᵀDU` and the band of its inverse (crate-private kernels) | [#banded-qr], [#gcv] |
//! | `data.rs` | [`FitData`] (points, parameters, weights, validated once) and the [`FitReport`] of every fit | [#residuals] |
//! | `knot_placement.rs` | [`place_knots`] (P&T eq. 9.68–9.69), [`check_schoenberg_whitney`] | [#knot-placement] |
//! | `lsq.rs` | [`least_squares`] (the curve alone: [`least_squares_curve`]; with FITPACK's `fp`: [`least_squares_curve_rss`]): weighted least squares with given knots, end points and end derivatives eliminated exactly (P&T A9.6/A9.7) | [#least-squares], [#constraints] |
//! | `smoothing.rs` | [`smoothing_spline`]: `Σ w (y − f)² + λ ∫ f''²`, λ given or by GCV | [#penalised], [#gcv] |
//! | `smoothing_condition/` | [`smoothing_condition`]: fewest knots with weighted RSS ≤ s (FITPACK `curfit`/`parcur` style), [`smoothing_condition_in`] on a domain wider than the data; [`smoothing_knot_sequence`]: its knot vectors round by round; [`KnotRounds`]: FITPACK's rounds or SciPy's `generate_knots`; [`smoothing_condition_from`]: the rounds continued from an earlier call's [`RoundsState`] (FITPACK's `iopt = 1`) | [#smoothing-condition] |
//! | `smoothing_on_knots.rs` | [`smoothing_on_knots`]: least jumps of the `k`-th derivative on given knots with weighted RSS = s | [#smoothing-on-given-knots] |
//! | `tolerance/` | [`fit_tolerance`]: within `tol` of every point with few control points (knot insertion and removal, deviations by projection) | [#tolerance] |
//! | `periodic.rs` | [`periodic_least_squares`], [`periodic_smoothing_condition`], [`periodic_smoothing_knot_sequence`], [`periodic_smoothing_on_knots`]: closed fits (FITPACK `fpperi`) | [#periodic] |
//! | `cyclic.rs` | the banded QR whose band wraps around the corner, for closed fits (crate-private kernel) | [#periodic] |
//! | `progress.rs` | how the fits report to a [`Progress`](crate::Progress) hook and stop when cancelled: steps of iterations of unknown length, checked passes over the data rows (crate-private plumbing, no arithmetic) | — |
//! | `rows.rs` | the rows of the observation matrix: the weighted non-zero B-splines at each data parameter (crate-private kernel) | [#banded-qr] |
//! | `shape/` | [`constrained_least_squares`], [`constrained_smoothing_spline`], [`constrained_smoothing_condition`]: fits of `y(x)` kept increasing, convex, bounded, … for every `x`, by a cone program (Clarabel); [`constrained_surface_grid_least_squares`], [`constrained_surface_scattered_least_squares`], [`constrained_surface_grid_smoothing_spline`], [`constrained_surface_grid_smoothing_condition`]: surfaces `z(u, v)` monotone per direction and bounded | [#shape-constraints] |
//! | `robust.rs` | [`robust_least_squares`]: IRLS with Huber or Tukey weights | [#robust] |
//! | `sphere/` | [`sphere_least_squares`], [`sphere_smoothing`] (scattered data), [`sphere_grid_smoothing`] (a grid): bicubic splines on the sphere, periodic in the longitude, with pole conditions (FITPACK `sphere`/`spgrid`) | `docs/theory/sphere.md` |
//! | `surface.rs` | [`surface_grid_least_squares`] (P&T §9.4.3; [`surface_grid_least_squares_at`] at given parameters and knots, [`surface_grid_parameters`]), [`surface_scattered_least_squares`] | [#surfaces] |
//!
//! [#banded-qr]: ../../docs/theory/fitting.md#banded-qr
//! [#gcv]: ../../docs/theory/fitting.md#gcv
//! [#residuals]: ../../docs/theory/fitting.md#residuals
//! [#knot-placement]: ../../docs/theory/fitting.md#knot-placement
//! [#least-squares]: ../../docs/theory/fitting.md#least-squares
//! [#constraints]: ../../docs/theory/fitting.md#constraints
//! [#penalised]: ../../docs/theory/fitting.md#penalised
//! [#smoothing-condition]: ../../docs/theory/fitting.md#smoothing-condition
//! [#smoothing-on-given-knots]: ../../docs/theory/fitting.md#smoothing-on-given-knots
//! [#tolerance]: ../../docs/theory/fitting.md#tolerance
//! [#periodic]: ../../docs/theory/fitting.md#periodic
//! [#robust]: ../../docs/theory/fitting.md#robust
//! [#surfaces]: ../../docs/theory/fitting.md#surfaces
//! [#shape-constraints]: ../../docs/theory/fitting.md#shape-constraints
//!
//! ## Conventions
//! - Data are points `Q_k` (any dimension, [`PointsRef`](crate::PointsRef)) with parameters
//!   `ū_k` and optional weights `w_k ≥ 0` ([`FitData`]). Functions `y(x)` are 1-D points with
//!   `ū_k = x_k`.
//! - Every solver works on the data minus a reference point (the first data point) and adds it
//!   back to the control points: by partition of unity the fit is the same, and data far from
//!   the origin (a 1e8 offset) lose no digits in the solve.
//! - The fits that can run long have a `*_with_progress` variant taking a
//!   [`Progress`](crate::Progress): it reports between units of work (data rows, knot rounds,
//!   smoothing weights, GCV scores), stops with [`Error::Cancelled`](crate::Error::Cancelled)
//!   once the cancel flag is set, and otherwise gives the bits of the plain function.
//! - No dense matrix is formed: curves use banded QR or banded `UᵀDU`, O(N·p²) for `N` points.

pub(crate) mod banded;
mod cyclic;
mod data;
mod knot_placement;
mod lsq;
mod periodic;
mod progress;
mod robust;
mod rows;
mod shape;
mod smoothing;
mod smoothing_condition;
mod smoothing_on_knots;
mod sphere;
mod surface;
mod tolerance;

pub use data::{CurveFit, FitData, FitReport};
pub use knot_placement::{check_schoenberg_whitney, place_knots};
pub use lsq::{
    least_squares, least_squares_curve, least_squares_curve_rss, least_squares_with_progress,
    EndConstraints,
};
pub(crate) use lsq::{least_squares_qr, least_squares_values_and_qr};
pub use periodic::{
    closed_parameters, periodic_least_squares, periodic_least_squares_with_progress,
    periodic_smoothing_condition, periodic_smoothing_condition_with_progress,
    periodic_smoothing_knot_sequence, periodic_smoothing_on_knots,
    periodic_smoothing_on_knots_with_progress,
};
pub use robust::{robust_least_squares, RobustFit, RobustLoss, ROBUST_SCALE_RTOL};
pub(crate) use rows::for_each_row;
pub use shape::{
    constrained_least_squares, constrained_smoothing_condition,
    constrained_smoothing_condition_with_progress, constrained_smoothing_spline,
    constrained_smoothing_spline_with_progress, shape_violations, IntegralCondition,
    PointCondition, Shape, ShapeConstraint, ShapeConstraints, CONDITION_RTOL, SHAPE_RTOL,
};
pub use shape::{
    constrained_surface_grid_least_squares, constrained_surface_grid_smoothing_condition,
    constrained_surface_grid_smoothing_spline, constrained_surface_scattered_least_squares,
    surface_shape_violations, SurfaceGridSmoothing, SurfaceShape, SurfaceShapeConstraint,
    SurfaceShapeConstraints,
};
pub(crate) use smoothing::{
    brent_min, smoothing_system, smoothing_values_and_system, Smoother, SmoothingSystem,
    GCV_ROUNDING_SHARE,
};
pub use smoothing::{gcv_score, smoothing_spline, smoothing_spline_with_progress, Lambda};
pub use smoothing_condition::{
    smoothing_condition, smoothing_condition_from, smoothing_condition_in,
    smoothing_condition_in_with_progress, smoothing_condition_with_limit,
    smoothing_condition_with_progress, smoothing_condition_with_rounds, smoothing_knot_sequence,
    KnotLimit, KnotRounds, RoundsStart, RoundsState, SMOOTHING_RTOL,
};
pub use smoothing_on_knots::{smoothing_on_knots, smoothing_on_knots_with_progress};
// the pieces of FITPACK's smoothing condition that the smoothing on tensor grids shares
pub(crate) use progress::Steps;
pub(crate) use smoothing_condition::{
    accepts_least_squares, check_condition_args, jump_rows, next_nplus, smooth_weight,
};
pub use sphere::{
    sphere_grid_smoothing, sphere_least_squares, sphere_max_knots, sphere_smoothing, PoleCondition,
    SphereData, SphereFit, SphereGrid,
};
pub use surface::{
    surface_grid_least_squares, surface_grid_least_squares_at, surface_grid_parameters,
    surface_scattered_least_squares, surface_scattered_least_squares_with_progress,
    ScatteredSurfaceFit,
};
pub use tolerance::{
    fit_tolerance, fit_tolerance_with_progress, Deviation, ToleranceFit, ToleranceOptions,
};
