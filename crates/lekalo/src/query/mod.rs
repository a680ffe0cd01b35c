//! Geometric queries on curves and surfaces: how long, where is the closest point, where do two
//! objects meet, what lies at a distance, which polyline or mesh is within a tolerance, how
//! curved, how big (`docs/theory/queries.md`).
//!
//! Every query works on the object's Bezier pieces (rational for NURBS), because on a piece the
//! convex-hull property bounds the geometry and the Bernstein coefficients count roots, so no
//! answer depends on sampling luck. A curve is prepared once as a [`QueryCurve`] (pieces
//! normalised to the unit box, a tree of their boxes), a surface as a [`QuerySurface`].
//!
//! | file | subject |
//! |---|---|
//! | `pieces.rs` | [`QueryCurve`]: the pieces, their tree, evaluation; scalar Bernstein polynomials and their roots |
//! | `surface.rs` | [`QuerySurface`]: the patches, their evaluation and subdivision |
//! | `length.rs` | arc length by adaptive Gauss–Legendre, its inverse, equal arc-length steps, the arc-length spline ([`ArcLength`]) |
//! | `project.rs` | closest points on curves and surfaces, all minima on request, parallel batches, point inversion |
//! | `intersect/` | curve–curve (planar: sweep, Bezier clipping, Newton), self-intersection, curve–plane, curve–surface and surface–surface intersections, plane sections |
//! | `offset.rs` | offsets of planar curves, with cusps and loops detected and trimmed |
//! | `tessellate.rs` | polylines within a proved deviation; the mesh type, its facet normals and its vertices' normals (the surface's, or its triangles' averaged) |
//! | `mesh/` | adaptive, crack-free triangle meshes of surfaces within a proved deviation |
//! | `curvature.rs` | curvature and torsion, inflections and curvature extrema; surface curvatures |
//! | `bbox.rs` | exact bounding boxes from the pieces' extrema |
//!
//! Every iteration in here has a bound (stated where it is), and every query validates its
//! input: NaN queries, bad tolerances and degrees beyond [`MAX_QUERY_DEGREE`] are named errors.

// Every negated comparison in here (`!(x > 0.0)`) is deliberate: NaN must fail the test it
// guards, which the un-negated opposite (`x <= 0.0`) would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod bbox;
mod curvature;
mod intersect;
mod length;
mod mesh;
mod offset;
mod pieces;
mod pole_normal;
mod project;
mod surface;
mod tessellate;

pub use bbox::SURFACE_BOX_RTOL;
pub use curvature::{CurvatureExtremum, SurfaceCurvature, CURVATURE_EXTREMUM_RTOL};
pub use intersect::{
    Contact, CurveIntersection, IntersectionBranch, PlaneIntersection, SurfaceIntersection,
    TOUCH_RTOL,
};
pub use length::{ArcLength, DEFAULT_LENGTH_RTOL};
pub(crate) use mesh::triangle_bound;
pub use offset::Offset;
pub use pieces::{QueryCurve, MAX_QUERY_DEGREE};
pub use pole_normal::MESH_NORMAL_RTOL;
pub use project::{CurveProjection, SurfaceProjection, MAX_QUERY_RANGE};
pub use surface::QuerySurface;
pub(crate) use tessellate::{check_deviation, check_tol, TESSELLATION_TOLERANCE};
pub use tessellate::{
    Mesh, Polyline, MAX_MESH_TRIANGLES, MAX_MESH_VERTICES, MAX_POLYLINE_POINTS,
    MIN_RELATIVE_TOLERANCE,
};
