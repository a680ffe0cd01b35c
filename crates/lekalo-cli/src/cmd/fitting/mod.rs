//! `lekalo fit`: least squares, smoothing, tolerance, robust, surfaces, closed curves.
//!
//! - `args.rs`: the command's arguments, and the domains and knot vectors they give.
//! - `fit.rs`: the command, dispatching to the curve modes (here), surfaces and closed curves.
//! - `surface.rs`: grid and scattered surfaces.
//! - `tensor.rs`: grid and scattered fits in three or more variables.
//! - `sphere.rs`: scattered and grid fits on the sphere.
//! - `periodic.rs`: closed curves and periodic functions.
//! - `shapes.rs`: the shape constraints the options give (curves and periodic functions).
//! - `report.rs`: a fitted curve written out with its report.

pub(crate) mod args;
pub(crate) mod fit;
mod periodic;
mod report;
mod shapes;
mod sphere;
mod surface;
mod tensor;
