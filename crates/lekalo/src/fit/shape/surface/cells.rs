//! The Bernstein coefficients of a surface's value or partial derivative on each knot cell, as
//! linear functions of the control net (`docs/theory/fitting.md#shape-constraints-of-surfaces`;
//! crate-private).

use super::super::bernstein::{bernstein_rows, pieces};
use super::constraints::SurfaceShapeConstraint;
use crate::basis::BasisScratch;
use crate::Direction;

/// The spline space of a surface `z(u, v)`: degrees, full knot vectors and the net's size
/// (control point `(i, j)` at `i·n_v + j`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Space<'a> {
    pub(crate) degrees: (usize, usize),
    pub(crate) knots: (&'a [f64], &'a [f64]),
    pub(crate) net: (usize, usize),
}

/// One Bernstein coefficient of a cell as a sparse row: `b = Σ w·c[first + offset]`.
#[derive(Debug, Clone)]
pub(crate) struct CellRow {
    pub(crate) first: usize,
    pub(crate) terms: Vec<(usize, f64)>,
}

impl CellRow {
    /// `b` for the net `c` (one value per control point).
    pub(crate) fn eval(&self, c: &[f64]) -> f64 {
        self.terms.iter().map(|&(o, w)| w * c[self.first + o]).sum()
    }
}

impl Space<'_> {
    /// The domain `[u_p, u_{n_u}] × [v_q, v_{n_v}]`.
    pub(crate) fn domain(&self) -> [(f64, f64); 2] {
        let ((p, q), (tu, tv), (nu, nv)) = (self.degrees, self.knots, self.net);
        [(tu[p], tu[nu]), (tv[q], tv[nv])]
    }

    /// For `constraint`, the Bernstein coefficients of the function its shape constrains (`z`
    /// for bounds, `∂z/∂u` or `∂z/∂v` for monotonicity) on every piece of a knot cell inside its
    /// region: on `[α, β] × [γ, δ]` inside the cell `[u_s, u_{s+1}] × [v_t, v_{t+1}]` that
    /// function is a tensor polynomial of degree `(p − r_u, q − r_v)`, and its coefficients
    /// are `M_u ⊗ M_v` applied to the cell's `(p + 1) × (q + 1)` control points, with `M` the
    /// one-direction rows of [`bernstein_rows`] on the piece (P&T A2.3 and Farouki & Rajan 1988
    /// in each direction). On the whole domain the pieces are the cells; a region's edge
    /// inside a cell cuts it, and a region of zero width in a direction (a line) takes the
    /// values on that line.
    pub(crate) fn cell_rows(&self, constraint: &SurfaceShapeConstraint) -> Vec<CellRow> {
        let (p, q) = self.degrees;
        let (tu, tv) = self.knots;
        let (nu, nv) = self.net;
        let shape = constraint.shape;
        let (ru, rv) = match shape.direction() {
            Some(Direction::U) => (1, 0),
            Some(Direction::V) => (0, 1),
            None => (0, 0),
        };
        let [(u0, u1), (v0, v1)] = constraint.region_or(self.domain());
        let (mut su, mut sv) = (BasisScratch::new(p), BasisScratch::new(q));
        let mu: Vec<(usize, Vec<Vec<f64>>)> = pieces(tu, p, nu, u0, u1)
            .into_iter()
            .map(|(s, a, b)| (s, bernstein_rows(tu, p, s, a, b, ru, &mut su)))
            .collect();
        let mv: Vec<(usize, Vec<Vec<f64>>)> = pieces(tv, q, nv, v0, v1)
            .into_iter()
            .map(|(t, a, b)| (t, bernstein_rows(tv, q, t, a, b, rv, &mut sv)))
            .collect();
        let mut out = Vec::new();
        for (s, a) in &mu {
            for (t, b) in &mv {
                let first = (s - p) * nv + (t - q);
                for ra in a {
                    for rb in b {
                        let mut terms = Vec::with_capacity((p + 1) * (q + 1));
                        for (i, &x) in ra.iter().enumerate() {
                            for (j, &y) in rb.iter().enumerate() {
                                let w = x * y;
                                if w != 0.0 {
                                    terms.push((i * nv + j, w));
                                }
                            }
                        }
                        out.push(CellRow { first, terms });
                    }
                }
            }
        }
        out
    }
}
