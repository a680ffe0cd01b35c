//! The versioned JSON envelope of every object (docs/formats.md): curves, surfaces, piecewise
//! polynomials and tensor splines, read through the library's validating constructors and written
//! field by field.
//!
//! - `object.rs`: curves: the envelope, `CurveJson`, JSON Lines;
//! - `object_ext.rs`: surfaces and piecewise polynomials;
//! - `shape.rs`: any object by its `type` (`Shape`), NURBS surfaces, `SurfaceJson`;
//! - `face_json.rs`: faces (a surface trimmed by loops of edges) read from CAD files;
//! - `tensor_json.rs`: tensor splines in N parameters;
//! - `json_write.rs`: streaming writer of large curves;
//! - `flat.rs`: control points as rows or flat `{dim, data}`;
//! - `intersections.rs`: the answers of intersections, each with its kind of contact;
//! - `analysis.rs`: names older callers used for the library's curve analysis.

pub(crate) mod analysis;
pub(crate) mod face_json;
pub(crate) mod flat;
pub(crate) mod intersections;
pub(crate) mod json_write;
pub(crate) mod object;
pub(crate) mod object_ext;
pub(crate) mod shape;
pub(crate) mod tensor_json;
