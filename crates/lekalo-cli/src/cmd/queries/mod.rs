//! Geometric queries: length, closest points, intersections, offsets, meshes.
//!
//! - `measure.rs`: `lekalo measure`;
//! - `project.rs`: `lekalo project`;
//! - `intersect.rs`: `lekalo intersect`;
//! - `offset.rs`: `lekalo offset`;
//! - `mesh.rs`: `lekalo mesh`.

pub(crate) mod intersect;
pub(crate) mod measure;
pub(crate) mod mesh;
pub(crate) mod offset;
pub(crate) mod project;
