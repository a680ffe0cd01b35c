//! The Bernstein coefficients of a surface's value or partial derivative on each knot cell, as
//! linear functions of the control net (`docs/theory/fitting.md#shape-constraints-of-surfaces`;
//! crate-private).

use super::super::bernstein::bernstein_rows;
use super::constraints::SurfaceShape;
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
    /// The non-empty spans of one direction's knots (`p ≤ s < n`).
    fn spans(knots: &[f64], p: usize, n: usize) -> Vec<usize> {
        (p..n).filter(|&s| knots[s] < knots[s + 1]).collect()
    }

    /// For `shape`, the Bernstein coefficients on every knot cell of the function it constrains
    /// (`z` for bounds, `∂z/∂u` or `∂z/∂v` for monotonicity): on the cell
    /// `[u_s, u_{s+1}] × [v_t, v_{t+1}]` that function is a tensor polynomial of degree
    /// `(p − r_u, q − r_v)`, and its coefficients are `M_u ⊗ M_v` applied to the cell's
    /// `(p + 1) × (q + 1)` control points, with `M` the one-direction rows of
    /// [`bernstein_rows`] (P&T A2.3 and Farouki & Rajan 1988 in each direction).
    pub(crate) fn cell_rows(&self, shape: SurfaceShape) -> Vec<CellRow> {
        let (p, q) = self.degrees;
        let (tu, tv) = self.knots;
        let (nu, nv) = self.net;
        let (ru, rv) = match shape.direction() {
            Some(Direction::U) => (1, 0),
            Some(Direction::V) => (0, 1),
            None => (0, 0),
        };
        let (mut su, mut sv) = (BasisScratch::new(p), BasisScratch::new(q));
        let mu: Vec<(usize, Vec<Vec<f64>>)> = Self::spans(tu, p, nu)
            .into_iter()
            .map(|s| (s, bernstein_rows(tu, p, s, tu[s], tu[s + 1], ru, &mut su)))
            .collect();
        let mv: Vec<(usize, Vec<Vec<f64>>)> = Self::spans(tv, q, nv)
            .into_iter()
            .map(|t| (t, bernstein_rows(tv, q, t, tv[t], tv[t + 1], rv, &mut sv)))
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
