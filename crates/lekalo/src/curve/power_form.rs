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
