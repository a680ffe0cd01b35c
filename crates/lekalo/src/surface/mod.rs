//! Tensor-product surfaces: Bezier, B-spline and NURBS, and their knot operations.
//!
//! - `any.rs`: [`Surface`], a surface of any of the three kinds with their shared
//!   capabilities delegated once, and [`Direction`] (`u` or `v`).
//! - `bspline.rs`: [`BSplineSurface`] and the conventions shared by all surfaces (net layout,
//!   derivative tables).
//! - `bspline/derivatives.rs`: its partial derivatives (P&T A3.6) and unit normals, with the
//!   normal's degeneracy test shared by all three kinds.
//! - `bezier.rs`: [`BezierSurface`] on `[0, 1]²`.
//! - `nurbs.rs`: [`NurbsSurface`], a B-spline surface over homogeneous points.
//! - `knot_ops.rs`: knot insertion, refinement, splitting, Bezier patches ([`BezierPatch`],
//!   [`RationalBezierPatch`]), transposition and reversal.
//! - `analytic.rs`: [`Placement`] and the elementary surfaces of CAD exchange (plane,
//!   cylinder, cone, sphere, torus) as exact NURBS patches.
//! - `revolution.rs`: surfaces of revolution and of linear extrusion of a NURBS curve, exact.
//! - `ruled.rs`: the ruled surface between two NURBS curves, exact.
//! - `power_patches.rs`: grids of polynomial patches in power form (IGES 114) as exact
//!   B-splines.
//! - `curvature.rs`: Gaussian, mean and principal curvatures ([`surface_curvature`]).

mod analytic;
mod any;
pub(crate) mod bezier;
pub(crate) mod bspline;
mod curvature;
mod knot_ops;
pub(crate) mod nurbs;
mod power_patches;
mod revolution;
mod ruled;

pub use analytic::{Placement, FULL_TURN};
pub use any::{Direction, Surface};
pub use bezier::BezierSurface;
pub use bspline::BSplineSurface;
pub use curvature::{surface_curvature, SurfaceCurvature};
pub use knot_ops::{BezierPatch, RationalBezierPatch};
pub use nurbs::NurbsSurface;
