//! Adaptive triangle meshes of surfaces within a proved deviation
//! (`docs/theory/queries.md#tessellation`): each patch is cut into parts, halved in `u` or in
//! `v` or near the end cut into a few equal parts, until the bound of every part is within the
//! tolerance; the parts' sides are then matched across parts and patches, so the mesh has no
//! cracks, and a part with extra points on its sides is a strip (polynomial, its triangles'
//! own bounds checked, the part split again where none of its triangulations is within the
//! tolerance) or a fan (rational) through them; the polynomial mesh is then thinned by removing
//! vertices where the fan of the polygon around one stays within the tolerance.
//!
//! | file | subject |
//! |---|---|
//! | `bounds.rs` | deviation bounds: the second-derivative nets of a part ([`SecondNets`](bounds::SecondNets)), the bound of one triangle ([`triangle_bound`](bounds::triangle_bound)), `(A + 2B + C)/8` of a net, degree elevation |
//! | `parts.rs` | the parts of a polynomial patch: halved, or cut into a few equal parts, until within the tolerance |
//! | `rational.rs` | the parts of a rational patch, halved until within the tolerance |
//! | `strips.rs` | the parts' corners on the global lattice, each part's boundary, and strips of triangles between two chains of it |
//! | `plan.rs` | the patches' places on the lattice, and how each polynomial part is triangulated (two triangles, a strip, a fan, or split again) |
//! | `driver.rs` | [`QuerySurface::mesh`]: the size check, the rounds of matching and splitting, the mesh's vertices and triangles |
//! | `decimate.rs` | thinning of the polynomial mesh by vertex removal |
//! | `tests.rs` | tests |

mod bounds;
mod decimate;
mod driver;
mod parts;
mod plan;
mod rational;
mod strips;
#[cfg(test)]
mod tests;

pub(crate) use bounds::triangle_bound;

#[cfg(doc)]
use super::surface::QuerySurface;

/// Most halvings of a patch in one direction. A part's corners are integers in
/// `[0, 2^(MAX_LEVELS + 1)]` along each direction of its patch, so every part is at least two
/// units wide and its centre is an integer too.
const MAX_LEVELS: u32 = 40;
/// Integer width of a patch along each direction.
const PATCH_WIDTH: u64 = 1 << (MAX_LEVELS + 1);
/// Most parts a part is cut into at once ([`QuerySurface::poly_leaves`]).
const MAX_DIRECT_PARTS: usize = 9;
/// Most rounds of matching the parts' sides and splitting the parts none of whose
/// triangulations is within the tolerance, before every part is refined to the bound that
/// holds for any triangle inside it ([`QuerySurface::mesh_polynomial`]).
const MAX_ROUNDS: usize = 12;

/// A part's integer ranges on the global lattice: `((u0, u1), (v0, v1))`.
type Rect = ((u64, u64), (u64, u64));

/// A part of a patch that is meshed as a whole: its patch, its integer ranges inside the patch,
/// its deviation bound as two triangles, the diagonal of those (`anti`: from `(u1, v0)` to
/// `(u0, v1)`, otherwise from `(u0, v0)` to `(u1, v1)`), and its four corners (`(u0, v0)`,
/// `(u1, v0)`, `(u1, v1)`, `(u0, v1)`, normalised Cartesian points).
struct Leaf {
    patch: usize,
    u: (u64, u64),
    v: (u64, u64),
    bound: f64,
    anti: bool,
    corners: Vec<f64>,
}

/// Which bound a polynomial part must meet to be accepted.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Rule {
    /// Its two triangles' edge bound ([`triangle_bound`](bounds::triangle_bound)), along the
    /// better diagonal.
    Edges,
    /// `(A + 2B + C)/8` ([`QuerySurface::net_bounds`]), which holds for every triangle inside
    /// the part.
    Any,
}
