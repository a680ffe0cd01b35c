//! IGES 5.3 (Initial Graphics Exchange Specification): rational B-spline curves (entity 126)
//! and surfaces (entity 128), written and read; lines (entity 110), parametric spline curves
//! (entity 112) and surfaces (entity 114) read as exact B-splines (`splines.rs`), circular and
//! conic arcs (entities 100, 104) and swept surfaces (entities 118, 120, 122) as exact NURBS
//! (`conics.rs`, `swept.rs`), the analytic surfaces (entities 190–198, and the bounded plane
//! 108) as exact NURBS and the linear paths of copious data (106) as polylines (`analytic.rs`).
//!
//! A file is 80-column records in five sections: Start (`S`), Global (`G`: delimiters, units,
//! precision), Directory Entry (`D`: two records per entity), Parameter Data (`P`: the entity's
//! numbers, comma-separated, `;` at the end) and Terminate (`T`: the section counts). Entity 126
//! carries `K, M, PROP1–4`, the `K + M + 2` knots, `K + 1` weights, the control points, the
//! parameter range and a normal; entity 128 the same per direction with the net stored `u`
//! fastest (IGES 5.3 §4.23, §4.24). Polynomial objects are written with `PROP3 = 1` and unit
//! weights and read back as B-splines.
//!
//! Reals are written in the shortest form that reads back to the same `f64` and read correctly
//! rounded (`D` exponents accepted), so a round trip is exact. The units of the Global section
//! (flag 1–11) convert coordinates to millimetres. A curve or surface whose directory entry
//! points at a transformation matrix (entity 124, chained to the matrices it points at) is read
//! in the file's coordinates, its control points mapped. Offset curves and surfaces (130, 140),
//! and trimmed and bounded surfaces when faces are not read, are listed as skipped with the
//! reason; other entities (annotations, properties, points) are passed over.
//!
//! | file | subject |
//! |---|---|
//! | `splines.rs` | entities 110, 112 and 114 as exact B-splines |
//! | `analytic.rs` | entities 190–198 (plane, cylinder, cone, sphere, torus surfaces, over points 116 and directions 123), the bounded plane 108 and the linear paths of copious data 106 as exact NURBS; planes, cylinders and cones bounded by the faces on them |
//! | `analytic_tests.rs` | those entities read, placed, bounded by faces, and refused with the reason |
//! | `composite.rs` | independent composite curves (102) as one curve through their members, and their tests |
//! | `conics.rs` | entities 100 (circular arc) and 104 (conic arc) as exact NURBS, and their tests |
//! | `swept.rs` | entities 118 (ruled surface), 120 (surface of revolution) and 122 (tabulated cylinder) as exact NURBS from the curves they point at, and their tests |
//! | `faces_write.rs` | faces written as trimmed surfaces (144 over 128, boundaries 142 with composite curves 102 of 126) |
//! | `faces.rs` | trimmed (144) and bounded (143) surfaces with their boundaries (142, 141) and composite curves (102), and untrimmed independent surfaces, as faces ([`read_iges_faces`]) |
//! | `matrix.rs` | transformation matrices (entity 124) and their chains, applied to the control points |
//! | `matrix_tests.rs` | matrices applied, chained, in the file's unit, and refused |
//! | `fields.rs` | the lexical layer: parameter fields split at the delimiters (Hollerith strings kept whole), reals, counts, the units of the Global section |
//! | `read.rs` | [`read_iges`] and its limited and progress-reporting forms: the sections, the size limits, the entities 126 and 128 (and, through `splines.rs` and `conics.rs`, 110, 112, 114, 100, 104) as shapes |
//! | `write.rs` | [`IgesWriter`]: entities 126 and 128 as Directory Entry and Parameter Data records |
//! | `tests.rs` | round trips, hostile files, size limits and progress of the reader |

mod analytic;
#[cfg(test)]
mod analytic_tests;
mod composite;
mod conics;
mod faces;
#[cfg(test)]
mod faces_tests;
mod faces_write;
mod fields;
mod matrix;
#[cfg(test)]
mod matrix_tests;
mod read;
mod splines;
mod swept;
#[cfg(test)]
mod tests;
mod write;

pub use faces::read_iges_faces;
use read::read_entities;
pub use read::{read_iges, read_iges_limited, read_iges_with_progress};
pub use write::IgesWriter;
use write::INDEPENDENT;

use crate::shape::Shape;
use crate::step_read::{Skips, StepFace};

/// What [`read_iges`] found: the shapes with their directory-entry sequence numbers, what was
/// skipped, the unit.
#[derive(Debug, Clone, PartialEq)]
pub struct IgesRead {
    /// Curves and surfaces, with the sequence number of their directory entry.
    pub shapes: Vec<(u64, Shape)>,
    /// Entities not read (`id` is the directory entry's sequence number, `entity` its type):
    /// counted by kind, the first listed.
    pub skipped: Skips,
    /// The unit named by the Global section, e.g. `MM`, `IN`.
    pub length_unit: String,
    /// The factor that converted coordinates to millimetres.
    pub scale_to_mm: f64,
    /// The trimmed surfaces (entities 144 and 143), and the independent surfaces nothing trims,
    /// read as faces, with the sequence number of
    /// their directory entry in `id` ([`read_iges_faces`]; empty from [`read_iges`]).
    pub faces: Vec<StepFace>,
    /// The trimmed and bounded surfaces not read as faces, with the reason
    /// ([`read_iges_faces`]): counted by kind, the first listed.
    pub skipped_faces: Skips,
}
