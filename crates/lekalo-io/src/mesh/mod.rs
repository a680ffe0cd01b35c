//! Meshes and polylines as files: OBJ, STL, PLY.
//!
//! - `mesh_files.rs`: meshes of surfaces within a deviation, polylines of curves;
//! - `obj.rs`: sampled grids with normals and polylines as OBJ.

pub(crate) mod mesh_files;
pub(crate) mod obj;
