//! Topology of CAD models: faces, the surfaces of a model trimmed by loops of edges
//! (ISO 10303-42 §5, `advanced_face`, `face_bound`, `edge_loop`, `oriented_edge`,
//! `surface_curve`/`pcurve`), and which parameters of a face's surface lie inside its trims.
//!
//! | file | subject |
//! |---|---|
//! | `face.rs` | [`Face`], [`Loop`] and [`Edge`]: a surface, its outer and inner loops, each edge a 3-D curve with its curve in the surface's `(u, v)`; validation (dimensions, loops closed within a tolerance relative to the model size) |
//! | `shell.rs` | [`Shell`]: which edges of a set of faces are one edge (shared by two faces, or a seam), and which edge ends are one vertex |
//! | `curvature.rs` | second-derivative bounds of a face's surface patch by patch, and the grid spacing of each knot span they give |
//! | `mesh.rs` | one trimmed face's triangle mesh within a tolerance from its edges' samples: edge sampling, grid, constrained Delaunay triangulation, refinement |
//! | `mesh/edge_sampling.rs` | the fractions at which an edge shared by faces is sampled once for all of them: bisection until its curve is near its chords and, on each face, the surface near the chord's midpoints and the step within the face's grid spacing |
//! | `mesh_set.rs` | [`mesh_faces`], [`mesh_faces_each`] and [`Face::mesh`]: a set of faces meshed with each shared edge sampled once and each face meshed once, in parallel; the faces that fail listed by index with their errors ([`FaceMeshes`]) |
//! | `pcurve.rs` | [`Face::with_projected_pcurves`] and [`SurfaceClosure`]: the pcurves a file leaves out, by projecting each edge onto the surface, unwrapped across seams and continuous through poles |
//! | `seam.rs` | faces whose loops go round a closed surface without a seam edge (bands, caps round a pole), cut along a seam into one region of `(u, v)` for the mesher |
//! | `trims.rs` | [`Face::checked_trims`], [`TrimDefect`], [`TrimRepair`]: the loops checked to bound one region of the domain (pcurves in the domain, no loop of no length, no crossings, holes inside the outer loop), clipped or dropped where the repair is unambiguous |
//! | `vertex.rs` | the point of a vertex whose edges' ends do not coincide: past every end along its curve, so that each edge keeps its whole curve |
//! | `inside.rs` | [`TrimRegion`]: the loops in `(u, v)` as polygons and the point-in-face test by winding numbers |
//!
//! See `docs/theory/topology.md`.

mod curvature;
mod face;
mod inside;
mod mesh;
mod mesh_set;
mod pcurve;
mod seam;
mod shell;
mod trims;
mod vertex;

pub use face::{Edge, Face, Loop, LOOP_CLOSURE_RTOL};
pub use inside::{winding_number, TrimRegion, TRIM_SAMPLES_PER_SPAN};
pub use mesh::TRIM_CLEARANCE;
pub use mesh_set::{join_meshes, mesh_faces, mesh_faces_each, FaceMeshes};
pub use pcurve::{SurfaceClosure, MAX_PCURVE_POINTS, PCURVE_SAMPLING_RTOL};
pub use shell::{EdgeUse, SharedEdge, Shell};
pub(crate) use trims::loop_name;
pub use trims::{TrimDefect, TrimRepair};
#[cfg(test)]
mod tests;
