//! Subcommands that build objects: control points, interpolation, explicit and tensor
//! splines, Bezier degree change, blending, piecewise polynomials, knot vectors and knot
//! operations, slices, swept surfaces.
//!
//! - `make.rs`: `lekalo make`: curves from control points;
//! - `make_surface.rs`: `lekalo make` of surfaces;
//! - `make_tensor.rs`: `lekalo make` of splines in N parameters;
//! - `interpolate.rs`: `lekalo interpolate`: curves, surfaces and grids through points;
//! - `explicit.rs`: explicit parameters and tangents read from files;
//! - `tensor.rs`: splines in N parameters for interpolate, eval and info;
//! - `bezier.rs`: `lekalo bezier`: degree elevation and reduction, real degree;
//! - `blend.rs`: `lekalo blend`: C^k blending of curves, corners;
//! - `jump.rs`: `lekalo blend jump`: the jump polynomials;
//! - `pp.rs`: `lekalo pp`: piecewise polynomials and quasi-interpolation;
//! - `knots.rs`: `lekalo knots`: knot vectors;
//! - `knot.rs`: `lekalo knot`: knot operations on curves, surfaces and splines in N parameters;
//! - `slice.rs`: `lekalo slice`: splines in N parameters with some fixed, surfaces' iso-curves;
//! - `sweep.rs`: `lekalo sweep`: surfaces of revolution, extrusions and ruled surfaces.

pub(crate) mod bezier;
pub(crate) mod blend;
pub(crate) mod explicit;
pub(crate) mod interpolate;
pub(crate) mod jump;
pub(crate) mod knot;
pub(crate) mod knots;
pub(crate) mod make;
pub(crate) mod make_surface;
pub(crate) mod make_tensor;
pub(crate) mod pp;
pub(crate) mod slice;
pub(crate) mod sweep;
pub(crate) mod tensor;
