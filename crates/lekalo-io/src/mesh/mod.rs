//! Meshes and polylines as files: OBJ, STL, PLY.
//!
//! - `mesh_files.rs`: meshes of surfaces within a deviation, polylines of curves;
//! - `obj.rs`: sampled grids with normals and polylines as OBJ;
//! - `cad_mesh.rs`: a CAD model's meshed faces and faces of triangles joined as one mesh with
//!   its vertices' normals ([`crate::join_cad_mesh`]), for `lekalo mesh` and Python alike.

pub(crate) mod cad_mesh;
pub(crate) mod mesh_files;
pub(crate) mod obj;
