//! The check of a surface against shape constraints: the least Bernstein coefficient of each
//! constrained function on every knot cell (`docs/theory/fitting.md#shape-constraints-of-surfaces`).

use super::cells::Space;
use super::constraints::SurfaceShapeConstraints;
use crate::error::{Error, Result};
use crate::BSplineSurface;

/// For each constraint, by how much `surface` breaks its Bernstein condition (0 when it holds):
/// `max(0, −min σ(b − v))` over the Bernstein coefficients `b` of `z` (bounds) or of `∂z/∂u`,
/// `∂z/∂v` (monotonicity) on every knot cell (every piece of a cell inside its box), in units of `z` (bounds) or of `z` per unit of the
/// parameter (monotonicity).
///
/// A 0 always means the shape holds on the whole domain (the convex-hull property of the
/// Bernstein basis). The converse holds where the constrained function has degree ≤ 1 in each
/// variable on a cell (a bilinear function takes its extremes at the corners, which are its
/// coefficients): bounds for degrees `(1, 1)`, monotonicity in `u` for `p ≤ 2, q ≤ 1` and in
/// `v` for `p ≤ 1, q ≤ 2`. Otherwise a positive number may come from a surface that keeps the
/// shape with coefficients of the wrong sign; it is then an upper bound of the true violation.
///
/// ```
/// use lekalo::fit::{surface_shape_violations, SurfaceShape, SurfaceShapeConstraints};
/// use lekalo::{BSplineSurface, Direction, KnotVector, Points};
/// // z = u on [0, 1]², bilinear: increasing in u, constant in v, between 0 and 1
/// let k = KnotVector::clamped_uniform(1, 2)?;
/// let net = Points::from_flat(1, vec![0.0, 0.0, 1.0, 1.0])?;
/// let s = BSplineSurface::from_knot_vectors(1, 1, k.clone(), k, net, (2, 2))?;
/// let c = SurfaceShapeConstraints::new()
///     .with(SurfaceShape::Increasing(Direction::U))
///     .with(SurfaceShape::Decreasing(Direction::U))
///     .with(SurfaceShape::AtMost(0.75));
/// assert_eq!(surface_shape_violations(&s, &c)?, vec![0.0, 1.0, 0.25]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Dimension`] for a surface whose control points are not numbers (dimension 1); the
/// constraint errors of
/// [`constrained_surface_grid_least_squares`](super::constrained_surface_grid_least_squares).
pub fn surface_shape_violations(
    surface: &BSplineSurface,
    constraints: &SurfaceShapeConstraints,
) -> Result<Vec<f64>> {
    if surface.dim() != 1 {
        return Err(Error::Dimension {
            what: "surface checked against shape constraints (a function z(u, v))".into(),
            expected: 1,
            got: surface.dim(),
        });
    }
    let (ku, kv) = surface.knots();
    let space = Space {
        degrees: surface.degree(),
        knots: (ku.as_slice(), kv.as_slice()),
        net: surface.net_size(),
    };
    constraints.validate(surface.degree(), space.domain())?;
    Ok(violations(
        &space,
        surface.control_points().as_slice(),
        constraints,
    ))
}

/// [`surface_shape_violations`] of the net `c` in `space`.
pub(super) fn violations(
    space: &Space<'_>,
    c: &[f64],
    constraints: &SurfaceShapeConstraints,
) -> Vec<f64> {
    constraints
        .shapes
        .iter()
        .map(|constraint| {
            let (sigma, level) = (constraint.shape.sign(), constraint.shape.level());
            space
                .cell_rows(constraint)
                .iter()
                .fold(0.0_f64, |w, r| w.max(-sigma * (r.eval(c) - level)))
        })
        .collect()
}
