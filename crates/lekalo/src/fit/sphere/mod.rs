//! Bicubic splines on the sphere: `s(θ, φ)` with the colatitude `θ ∈ [0, π]` clamped, the
//! longitude `φ` periodic with period `2π`, one value at each pole and, where asked, continuous
//! first derivatives across the poles; fitted to scattered data or to data on a grid (Dierckx,
//! *Curve and Surface Fitting with Splines*, 1993, ch. 11; FITPACK `sphere` and `spgrid`, the
//! methods behind SciPy's `LSQSphereBivariateSpline`, `SmoothSphereBivariateSpline` and
//! `RectSphereBivariateSpline`). The theory is in `docs/theory/sphere.md`.
//!
//! | file | what it does | theory |
//! |---|---|---|
//! | `space.rs` | [`PoleCondition`]; the spline space: knots, the pole rows as affine functions of the pole parameters, the periodic splines of `cos φ` and `sin φ` (crate-private) | [#space] |
//! | `scattered.rs` | [`SphereData`], [`sphere_least_squares`] (given knots), [`sphere_smoothing`] (the smoothing condition, FITPACK's knots) | [#scattered] |
//! | `grid.rs` | [`SphereGrid`], [`sphere_grid_smoothing`]: interpolation and the smoothing condition on a grid, with pole values, exactness, flatness and continuity | [#grid] |
//!
//! [#space]: ../../../docs/theory/sphere.md#space
//! [#scattered]: ../../../docs/theory/sphere.md#scattered
//! [#grid]: ../../../docs/theory/sphere.md#grid
//!
//! Every fit returns a [`SphereFit`] whose spline is a [`TensorBSpline`] of degrees `(3, 3)` in
//! `(θ, φ)` (the φ knots extended by three periodic knots at each end, the coefficients of the
//! last three columns repeating the first three), so evaluation, partial derivatives and grids
//! are the tensor kernels'.

mod grid;
mod scattered;
mod space;
#[cfg(test)]
mod tests;

pub use grid::{sphere_grid_smoothing, SphereGrid};
pub use scattered::{sphere_least_squares, sphere_max_knots, sphere_smoothing, SphereData};
pub use space::PoleCondition;

use crate::tensor::TensorBSpline;

/// The result of a fit on the sphere.
#[derive(Debug, Clone)]
pub struct SphereFit {
    /// The spline, degrees `(3, 3)` in `(θ, φ)`, one coefficient per tensor B-spline.
    pub spline: TensorBSpline,
    /// The (weighted) residual sum of squares at the data (FITPACK's `fp`).
    pub fp: f64,
    /// The rank of the last least-squares system solved.
    pub rank: usize,
    /// The number of its unknowns.
    pub unknowns: usize,
    /// The weight `p` of the jumps of the third derivatives; `None` for a least-squares
    /// result.
    pub p: Option<f64>,
    /// Why the knot rounds of [`sphere_smoothing`] stopped with the residual above `s`:
    /// `"max-knots"`, `"too-many-unknowns"` or `"no-span"`; `None` otherwise.
    pub limit: Option<&'static str>,
}
