//! Curves given in piecewise power form (the parametric splines of IGES entity 112, CAD
//! systems' "pp-form") converted exactly to B-splines on the knots of their own smoothness.

use crate::curve::bspline::BSplineCurve;
use crate::error::Result;
use crate::pp::ppform::{PiecewisePolynomial, PpSpace};
use crate::pp::TauRule;

/// Relative tolerance on the jumps of a piecewise polynomial's derivatives below which
/// [`BSplineCurve::from_piecewise_polynomial`] joins two pieces with that derivative continuous:
/// a jump of `D^j f` at most `POWER_FORM_CONTINUITY_RTOL` times the largest `|D^j f|` at the
/// breakpoints is rounding in the file, not a corner. Jumps above it keep the knot's full
/// multiplicity, so the B-spline reproduces every piece as given.
pub const POWER_FORM_CONTINUITY_RTOL: f64 = 1e-13;

impl BSplineCurve {
    /// The B-spline form of a piecewise polynomial, on the same parameter: the knots are the
    /// Curry–Schoenberg knots of the smallest space `P_{k,ξ,ν}` holding it (each breakpoint
    /// repeated `k − ν_i` times, `ν_i` found by [`PiecewisePolynomial::continuity`] with
    /// [`POWER_FORM_CONTINUITY_RTOL`]), the coefficients the de Boor–Fix functionals of the
    /// pieces (document 003 §5.1; docs/theory/pp.md#de-boor-fix-functionals). Exact to
    /// rounding: a polynomial of the space is reproduced by its dual functionals (P&T §2.2, de
    /// Boor "A Practical Guide to Splines" IX (39)). Pieces that meet with a gap (a
    /// discontinuous piecewise polynomial) give a knot of multiplicity `k`: the B-spline is then
    /// discontinuous there as well, right-continuous like the pp-form.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, PiecewisePolynomial};
    /// // x ↦ (x, x²) on [0, 1] ∪ [1, 2], written as two cubic pieces about their left ends
    /// let f = PiecewisePolynomial::new(vec![0.0, 1.0, 2.0], 4, 2, vec![
    ///     0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, // piece 0: (t, t²)
    ///     1.0, 1.0, 1.0, 2.0, 0.0, 1.0, 0.0, 0.0, // piece 1: (1 + s, 1 + 2s + s²)
    /// ])?;
    /// let c = BSplineCurve::from_piecewise_polynomial(&f)?;
    /// assert_eq!(c.degree(), 3);
    /// assert_eq!(c.control_points().len(), 4); // C^∞ at 1: no interior knot
    /// let p = c.eval(1.5)?;
    /// assert!((p[0] - 1.5).abs() < 1e-14 && (p[1] - 2.25).abs() < 1e-14);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// Errors of [`PpSpace::new`] and [`PiecewisePolynomial::to_bspline`] (none for a valid
    /// piecewise polynomial).
    pub fn from_piecewise_polynomial(pp: &PiecewisePolynomial) -> Result<Self> {
        let nu = pp.continuity(POWER_FORM_CONTINUITY_RTOL);
        let space = PpSpace::new(pp.breakpoints(), &nu, pp.order())?;
        pp.to_bspline(&space, TauRule::FirstIntervalMidpoint)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three cubic pieces in 2-D: C² at the first breakpoint, a corner (C⁰) at the second, and
    /// a gap of 1e-3 at the third, which must all be reproduced.
    #[test]
    fn pieces_of_any_smoothness_are_reproduced() {
        let breaks = vec![0.0, 0.5, 1.5, 2.0, 3.0];
        // piece 0: (t³, 1 + t); piece 1 continues it with C² and a new cubic term
        let p0 = [[0.0, 0.0, 0.0, 1.0], [1.0, 1.0, 0.0, 0.0]];
        let at = |c: [f64; 4], s: f64, j: usize| -> f64 {
            // j-th derivative / j! of the cubic at s
            match j {
                0 => c[0] + s * (c[1] + s * (c[2] + s * c[3])),
                1 => c[1] + s * (2.0 * c[2] + 3.0 * s * c[3]),
                2 => c[2] + 3.0 * s * c[3],
                _ => c[3],
            }
        };
        let p1: Vec<[f64; 4]> = p0
            .iter()
            .map(|&c| [at(c, 0.5, 0), at(c, 0.5, 1), at(c, 0.5, 2), -2.0])
            .collect();
        let p2: Vec<[f64; 4]> = p1
            .iter()
            .map(|&c| [at(c, 1.0, 0), 0.25, 1.0, 0.5])
            .collect();
        let p3: Vec<[f64; 4]> = p2
            .iter()
            .map(|&c| [at(c, 0.5, 0) + 1e-3, -1.0, 0.0, 0.0])
            .collect();
        let pieces = [p0.to_vec(), p1, p2, p3];
        let mut coef = Vec::new();
        for piece in &pieces {
            for r in 0..4 {
                for c in piece {
                    coef.push(c[r]);
                }
            }
        }
        let pp = PiecewisePolynomial::new(breaks.clone(), 4, 2, coef).unwrap();
        let b = BSplineCurve::from_piecewise_polynomial(&pp).unwrap();
        let k = b.knots();
        assert_eq!(
            [0.5, 1.5, 2.0].map(|x| k.multiplicity(x)),
            [1, 3, 4],
            "{k:?}"
        );
        for i in 0..=300 {
            let x = 3.0 * f64::from(i) / 300.0;
            let (got, want) = (b.eval(x).unwrap(), pp.eval(x).unwrap());
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() <= 1e-14 * 16.0, "at {x}: {got:?} vs {want:?}");
            }
        }
    }
}
