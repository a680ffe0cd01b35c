//! Topology of CAD models: faces, the surfaces of a model trimmed by loops of edges
//! (ISO 10303-42 §5, `advanced_face`, `face_bound`, `edge_loop`, `oriented_edge`,
//! `surface_curve`/`pcurve`), and which parameters of a face's surface lie inside its trims.
//!
//! | file | subject |
//! |---|---|
//! | `face.rs` | [`Face`], [`Loop`] and [`Edge`]: a surface, its outer and inner loops, each edge a 3-D curve with its curve in the surface's `(u, v)`; validation (dimensions, loops closed within a tolerance relative to the model size) |
//! | `inside.rs` | [`TrimRegion`]: the loops in `(u, v)` as polygons and the point-in-face test by winding numbers |
//!
//! See `docs/theory/topology.md`.

mod face;
mod inside;

pub use face::{Edge, Face, Loop, LOOP_CLOSURE_RTOL};
pub use inside::{winding_number, TrimRegion, TRIM_SAMPLES_PER_SPAN};
#[cfg(test)]
mod tests;
