//! End conditions of global curve interpolation (document 000 §1–4): free ends, prescribed
//! first derivatives (any degree `p ≥ 2`, and the C² cubic with knots at the parameters),
//! prescribed second derivatives and the natural cubic spline.

use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::Result;
use crate::interpolate::collocation::{
    clamped_result, fill_centered, record_condition, solve_collocation, sw_failure, Factors,
};
use crate::knots::KnotVector;
use crate::numeric::linalg::BandedCrout;
use crate::points::PointsRef;

/// Conditions at the ends of the curve. Derivatives are with respect to the curve parameter
/// (which runs over `[0, 1]` for [`CurveInterpolation::interpolate`], or over the given
/// parameters for [`CurveInterpolation::interpolate_at`]); each vector has the points'
/// dimension.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum EndCondition {
    /// No extra condition (document 000 §1): `n + 1` control points, any degree `1 ≤ p ≤ n`.
    #[default]
    Free,
    /// Prescribed first derivatives `C'(t̄_0) = start`, `C'(t̄_n) = end`: §2 (eq. 4–7) for any
    /// degree `p ≥ 2` with averaged knots, or §3 (eq. 8–12, C² cubic, Thomas algorithm) with
    /// knots at the parameters.
    FirstDerivatives {
        /// `d_0`, the derivative at the start.
        start: Vec<f64>,
        /// `d_n`, the derivative at the end.
        end: Vec<f64>,
    },
    /// Prescribed second derivatives of a C² cubic with knots at the parameters: §4
    /// (eq. 13–15).
    SecondDerivatives {
        /// `d''_0`, the second derivative at the start.
        start: Vec<f64>,
        /// `d''_n`, the second derivative at the end.
        end: Vec<f64>,
    },
    /// Zero second derivatives at both ends: the natural cubic spline (§4 with
    /// `d''_0 = d''_n = 0`; the minimum-`∫|C''|²` interpolant).
    Natural,
    /// A closed curve, `C^{p−1}` everywhere including the seam. The points are the distinct
    /// corners `q_0 … q_{N−1}` (a final copy of `q_0` is dropped); the parametrisation includes
    /// the closing chord `q_{N−1} → q_0`. Odd degrees put the knots at the parameters (the
    /// periodic version of eq. 8), even degrees halfway between them (so that the collocation
    /// matrix stays non-singular); the domain has length 1 and starts at `t̄_0 = 0` for odd and
    /// at `−(1 − t̄_{N−1})/2` for even degrees. Needs `N ≥ 2` points for every degree (with
    /// `N ≤ p` the basis functions wrap around the period more than once; three points of a
    /// cubic function, the last repeating the first, give SciPy's periodic `CubicSpline`).
    Periodic,
}

/// §1 (eq. 1): `n + 1` control points, `P_0 = q_0`, `P_n = q_n` (clamped ends), the interior
/// ones from the collocation rows `t̄_1 … t̄_{n−1}`.
pub(crate) fn free_end(
    points: PointsRef<'_>,
    params: &[f64],
    p: usize,
    knots: Vec<f64>,
    kappa: Option<&mut f64>,
) -> Result<BSplineCurve> {
    let dim = points.dim();
    let n = points.len() - 1;
    let reference = points.point(0);
    let mut control = vec![0.0; (n + 1) * dim];
    fill_centered(&mut control, 0, points.as_slice(), reference);
    let kv = KnotVector::from_raw(knots);
    let factors = Factors::for_condition(kappa.as_deref());
    let lu = solve_collocation(&kv, p, &params[1..n], 1, &mut control, dim, factors)?;
    record_condition(&lu, kappa);
    Ok(clamped_result(p, kv, control, points))
}

/// §2 (eq. 4–7) and §3 (eq. 8–12): `n + 3` control points. The first two and last two
/// follow directly from eq. (6)–(7) / (9)–(10): `P_0 = q_0`,
/// `P_1 = q_0 + (t_{p+1} − t̄_0)/p · d_0`, `P_{n+1} = q_n − (t̄_n − t_{n+2})/p · d_n`,
/// `P_{n+2} = q_n`; `P_2 … P_n` solve the collocation rows `t̄_1 … t̄_{n−1}` (for the cubic with
/// knots at the parameters these rows are the tridiagonal eq. (11)–(12), solved by the Thomas
/// sweep).
pub(crate) fn first_derivative_ends(
    points: PointsRef<'_>,
    params: &[f64],
    p: usize,
    knots: Vec<f64>,
    [d0, dn]: [&[f64]; 2],
    kappa: Option<&mut f64>,
) -> Result<BSplineCurve> {
    let dim = points.dim();
    let n = points.len() - 1;
    let reference = points.point(0);
    let n_ctrl = n + 3;
    debug_assert_eq!(knots.len(), n_ctrl + p + 1, "knots of eq. 4 / eq. 8");
    let mut control = vec![0.0; n_ctrl * dim];
    // rows 1..n of the data go to control rows 2..=n (the unknowns' right-hand sides)
    fill_centered(&mut control, 1, points.as_slice(), reference);
    let (a, b) = (params[0], params[n]);
    let s0 = (knots[p + 1] - a) / p as f64;
    let sn = (b - knots[n + 2]) / p as f64;
    let qn = points.point(n);
    for k in 0..dim {
        control[k] = 0.0;
        control[dim + k] = s0 * d0[k];
        let last = qn[k] - reference[k];
        control[(n + 2) * dim + k] = last;
        control[(n + 1) * dim + k] = last - sn * dn[k];
    }
    let kv = KnotVector::from_raw(knots);
    let factors = Factors::for_condition(kappa.as_deref());
    let lu = solve_collocation(&kv, p, &params[1..n], 2, &mut control, dim, factors)?;
    record_condition(&lu, kappa);
    Ok(clamped_result(p, kv, control, points))
}

/// §4 (eq. 13–15): the C² cubic with knots at the parameters and prescribed second
/// derivatives. `P_0 = q_0`, `P_{n+2} = q_n`; `P_1 … P_{n+1}` solve the tridiagonal system whose
/// first and last rows are eq. (13) and (14) multiplied by `h_4 = t_4 − t̄_0` and
/// `g = t̄_n − t_{n+2}` respectively (so that every entry is O(1)):
/// `P_0 − (1 + h_4/h_5) P_1 + (h_4/h_5) P_2 = h_4²/6 · d''_0` with `h_5 = t_5 − t̄_0`, and
/// `(g/g') P_n − (1 + g/g') P_{n+1} + P_{n+2} = g²/6 · d''_n` with `g' = t̄_n − t_{n+1}`; the rows
/// in between are eq. (11). Solved by the Thomas sweep, O(n).
pub(crate) fn second_derivative_ends(
    points: PointsRef<'_>,
    params: &[f64],
    d0: &[f64],
    dn: &[f64],
    kappa: Option<&mut f64>,
) -> Result<BSplineCurve> {
    const P: usize = 3;
    let dim = points.dim();
    let n = points.len() - 1;
    let knots = KnotVector::from_parameters(params, P)?.into_vec();
    let reference = points.point(0);
    let n_ctrl = n + 3;
    let mut control = vec![0.0; n_ctrl * dim];
    fill_centered(&mut control, 1, points.as_slice(), reference);
    let (a, b) = (params[0], params[n]);
    let (h4, h5) = (knots[4] - a, knots[5] - a);
    let (g, g1) = (b - knots[n + 2], b - knots[n + 1]);
    let qn = points.point(n);
    // unknown rows: 0 ↔ P_1 (eq. 13), r ↔ P_{r+1}, n ↔ P_{n+1} (eq. 14); rhs in control[1..=n+1]
    for k in 0..dim {
        control[k] = 0.0; // P_0 − q_0
        control[dim + k] = h4 * h4 / 6.0 * d0[k]; // − 1·(P_0 − q_0) = 0
        let last = qn[k] - reference[k];
        control[(n + 2) * dim + k] = last;
        control[(n + 1) * dim + k] = g * g / 6.0 * dn[k] - last;
    }
    let mut lu = if kappa.is_some() {
        BandedCrout::new_estimating(n + 1, 1, 1)
    } else {
        BandedCrout::new(n + 1, 1, 1, false)
    };
    let mut row = [0.0; 3];
    let mut scratch = BasisScratch::new(P);
    let mut basis = [0.0; P + 1];
    let rhs = &mut control[dim..(n + 2) * dim];
    row.copy_from_slice(&[0.0, -(1.0 + h4 / h5), h4 / h5]);
    lu.push_row(&mut row, rhs, dim, 0.0)?;
    let kv = KnotVector::from_raw(knots);
    let mut cursor = kv.span_cursor(P);
    for r in 1..n {
        let t = params[r];
        let span = cursor.find_unchecked(t);
        basis_funs_into(kv.as_slice(), P, span, t, &mut scratch, &mut basis);
        // unknown column of basis i is i − 1; the diagonal is column r
        row.fill(0.0);
        for (j, &v) in basis.iter().enumerate() {
            let i = span - P + j;
            if v == 0.0 {
                continue;
            }
            match (i + 1).checked_sub(r + 1) {
                Some(off) if off <= 2 && i >= 1 => row[off] = v,
                _ => return Err(sw_failure(r, t)),
            }
        }
        lu.push_row(&mut row, rhs, dim, 1.0)?;
    }
    row.copy_from_slice(&[g / g1, -(1.0 + g / g1), 0.0]);
    lu.push_row(&mut row, rhs, dim, 0.0)?;
    lu.back_substitute(rhs, dim);
    record_condition(&lu, kappa);
    Ok(clamped_result(P, kv, control, points))
}
