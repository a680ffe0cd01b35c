//! The collocation system of global interpolation: rows `Σ_i N_{i,p}(t̄_r) P_i = q_r` built
//! straight from the Cox–de Boor kernel into a band and eliminated without pivoting
//! ([`BandedCrout`]), with the known control points moved to the right-hand side; the data
//! centred on the first point; the optional condition estimate.

use crate::basis::{basis_funs_into, BasisScratch};
use crate::curve::bspline::BSplineCurve;
use crate::error::readable;
use crate::error::{Error, Result};
use crate::knots::KnotVector;
use crate::numeric::linalg::BandedCrout;
use crate::points::{Points, PointsRef};

/// Smallest meaningful [`CurveInterpolation::max_condition`]: `κ_1 ≥ 1` for every matrix.
const MIN_CONDITION_LIMIT: f64 = 1.0;

/// A condition limit must be a number ≥ 1 (`κ_1 ≥ 1` for every matrix).
///
/// # Errors
/// [`Error::InvalidArgument`] for NaN or a limit below 1.
pub(crate) fn check_condition_limit(limit: f64) -> Result<()> {
    if limit.is_nan() || limit < MIN_CONDITION_LIMIT {
        return Err(Error::InvalidArgument {
            what: "condition limit (max_condition)".into(),
            reason: format!(
                "{limit} is not a number ≥ {MIN_CONDITION_LIMIT} (every matrix has κ_1 ≥ 1); \
                 pass e.g. 1e8 to keep about 8 significant digits",
                limit = readable(&limit)
            ),
        });
    }
    Ok(())
}

#[cold]
pub(crate) fn condition_exceeded(kappa: f64, limit: f64) -> Error {
    Error::IllConditioned {
        reason: format!(
            "the collocation matrix has an estimated condition number κ_1 ≈ {kappa:.3e}, above \
             the limit {limit:e} set by max_condition: the parameters crowd together (nearly \
             coincident points) or the knot spacing is too uneven for this degree; use \
             centripetal or uniform parameters, drop near-duplicate points, use fewer points or \
             a lower degree"
        ),
    }
}

/// Folds the condition estimate of `lu` (made by [`Factors::Estimate`]) into `kappa`: the
/// largest over the systems of one problem.
pub(crate) fn record_condition(lu: &BandedCrout, kappa: Option<&mut f64>) {
    if let (Some(k), Some(e)) = (kappa, lu.condition_estimate()) {
        *k = k.max(e);
    }
}

/// Which factors a banded solve keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Factors {
    /// Only `U` (dropped with the solver).
    Discard,
    /// `L` and `U`, for further right-hand sides ([`BandedCrout::solve`]).
    Keep,
    /// `L`, `U` and `‖A‖_1`, for [`BandedCrout::condition_estimate`] as well.
    Estimate,
}

impl Factors {
    pub(crate) fn for_condition(kappa: Option<&f64>) -> Self {
        if kappa.is_some() {
            Factors::Estimate
        } else {
            Factors::Discard
        }
    }
}

/// Solves `Σ_i N_{i,p}(ts[r]) P_i = rhs_r` for the unknown control points `P_first … P_{first+m−1}`
/// (`m = ts.len()`, row `r` has its diagonal at `P_{first+r}`), with the other control points
/// known. On entry `control` (all control points, `dim` per point) holds the known points and,
/// in rows `first..first+m`, the right-hand sides; on return those rows hold the solution.
///
/// Two passes over sorted parameters with a span cursor: the first finds the band widths
/// (and checks the Schoenberg–Whitney condition `N_{first+r}(ts[r]) > 0`), the second evaluates
/// each row by Cox–de Boor (P&T A2.2) into the band buffer and eliminates it at once
/// ([`BandedCrout`]). O(m·p²) time, O(m·p) memory besides `control`.
///
/// With [`Factors::Keep`] the factorisation is returned for further right-hand sides, with
/// [`Factors::Estimate`] also for [`BandedCrout::condition_estimate`].
pub(crate) fn solve_collocation(
    kv: &KnotVector,
    p: usize,
    ts: &[f64],
    first: usize,
    control: &mut [f64],
    dim: usize,
    factors: Factors,
) -> Result<BandedCrout> {
    let m = ts.len();
    let knots = kv.as_slice();
    let (kl, ku) = band_widths(kv, p, ts, first)?;
    let mut lu = match factors {
        Factors::Discard => BandedCrout::new(m, kl, ku, false),
        Factors::Keep => BandedCrout::new(m, kl, ku, true),
        Factors::Estimate => BandedCrout::new_estimating(m, kl, ku),
    };
    if m == 0 {
        return Ok(lu);
    }
    let mut row = vec![0.0; lu.width()];
    let mut basis = vec![0.0; p + 1];
    let mut scratch = BasisScratch::new(p);
    let mut cursor = kv.span_cursor(p);
    let (known_lo, rest) = control.split_at_mut(first * dim);
    let (block, known_hi) = rest.split_at_mut(m * dim);
    for (r, &t) in ts.iter().enumerate() {
        let span = cursor.find_unchecked(t);
        basis_funs_into(knots, p, span, t, &mut scratch, &mut basis);
        row.fill(0.0);
        let rhs = &mut block[r * dim..(r + 1) * dim];
        for (j, &v) in basis.iter().enumerate() {
            if v == 0.0 {
                continue;
            }
            let i = span - p + j;
            let known = if i < first {
                Some(&known_lo[i * dim..(i + 1) * dim])
            } else if i >= first + m {
                let o = i - first - m;
                Some(&known_hi[o * dim..(o + 1) * dim])
            } else {
                None
            };
            match known {
                Some(x) => {
                    for (y, xi) in rhs.iter_mut().zip(x) {
                        *y -= v * xi;
                    }
                }
                // band_widths placed every value the exact basis can make non-zero; a value
                // outside comes from knots too close to resolve (subnormal spacing)
                None => match (kl + (i - first))
                    .checked_sub(r)
                    .and_then(|c| row.get_mut(c))
                {
                    Some(x) => *x = v,
                    None => return Err(unresolved_parameters(r, t)),
                },
            }
        }
        lu.push_row(&mut row, block, dim, 1.0)?;
    }
    lu.back_substitute(block, dim);
    Ok(lu)
}

/// The banded factors of the collocation matrix `A[r][i] = N_{i,p}(ts[r])` alone (no
/// right-hand side), kept for [`BandedCrout::solve`]: [`solve_collocation`] with every control
/// point unknown and no columns. `factors` is [`Factors::Keep`] or [`Factors::Estimate`].
pub(crate) fn factor_collocation(
    kv: &KnotVector,
    p: usize,
    ts: &[f64],
    factors: Factors,
) -> Result<BandedCrout> {
    debug_assert!(factors != Factors::Discard, "the factors are the result");
    solve_collocation(kv, p, ts, 0, &mut [], 0, factors)
}

/// Band widths `(kl, ku)` of the collocation rows (see [`solve_collocation`]), counting only
/// unknown columns and entries that can be non-zero (`N_{span}` vanishes at `t = t_span`).
fn band_widths(kv: &KnotVector, p: usize, ts: &[f64], first: usize) -> Result<(usize, usize)> {
    let knots = kv.as_slice();
    let m = ts.len();
    let mut cursor = kv.span_cursor(p);
    let (mut kl, mut ku) = (0usize, 0usize);
    for (r, &t) in ts.iter().enumerate() {
        let span = cursor.find_unchecked(t);
        // non-zero basis functions: N_{span−p..=span}, except that N_span vanishes at t = t_span
        // and only N_span is left at a clamped right end
        let clamped_end = t == knots[span + 1] && knots[span + 1] == knots[span + p + 1];
        let lo = if clamped_end { span } else { span - p };
        let hi = if t == knots[span] { span - 1 } else { span };
        let diag = first + r;
        if diag < lo || diag > hi {
            return Err(sw_failure(r, t));
        }
        let lo_u = lo.max(first);
        let hi_u = hi.min(first + m - 1);
        kl = kl.max(diag - lo_u);
        ku = ku.max(hi_u - diag);
    }
    Ok((kl, ku))
}

#[cold]
fn unresolved_parameters(row: usize, t: f64) -> Error {
    Error::SingularSystem {
        reason: format!(
            "parameter {t:e} of row {row} lies too close to its knots to resolve in floating \
             point (spacing near the smallest normal f64); rescale the data or drop points that \
             are negligibly close to their neighbours"
        ),
    }
}

pub(crate) fn sw_failure(row: usize, t: f64) -> Error {
    Error::SingularSystem {
        reason: format!(
            "Schoenberg–Whitney condition fails: the basis function of unknown {row} vanishes at \
             its parameter {t}; place the knots by averaging or use other parameters",
            t = readable(&t)
        ),
    }
}

/// Copies `points` minus `reference` into rows `first..first + n` of `control`.
pub(crate) fn fill_centered(control: &mut [f64], first: usize, points: &[f64], reference: &[f64]) {
    let dim = reference.len();
    for (c, q) in control[first * dim..]
        .chunks_exact_mut(dim)
        .zip(points.chunks_exact(dim))
    {
        for ((ci, qi), ri) in c.iter_mut().zip(q).zip(reference) {
            *ci = qi - ri;
        }
    }
}

fn add_reference(control: &mut [f64], reference: &[f64]) {
    /// The loop for a dimension known at compile time (the reference in registers).
    fn fixed<const D: usize>(control: &mut [f64], reference: &[f64]) {
        let mut r = [0.0; D];
        r.copy_from_slice(reference);
        for c in control.chunks_exact_mut(D) {
            for k in 0..D {
                c[k] += r[k];
            }
        }
    }
    match reference.len() {
        2 => fixed::<2>(control, reference),
        3 => fixed::<3>(control, reference),
        _ => {
            for c in control.chunks_exact_mut(reference.len()) {
                for (ci, ri) in c.iter_mut().zip(reference) {
                    *ci += ri;
                }
            }
        }
    }
}

/// The clamped interpolant from the centred solution `control` (relative to `q_0`): the
/// reference added back, the ends set exactly ([`set_clamped_ends`]).
pub(crate) fn clamped_result(
    p: usize,
    kv: KnotVector,
    mut control: Vec<f64>,
    points: PointsRef<'_>,
) -> BSplineCurve {
    add_reference(&mut control, points.point(0));
    set_clamped_ends(&mut control, points);
    BSplineCurve::from_raw(p, kv.into_vec(), Points::from_raw(control, points.dim()))
}

/// A clamped interpolant has `P_0 = q_0` and `P_last = q_n`: store them exactly (the centred
/// solve would round `(q_n − q_0) + q_0`).
fn set_clamped_ends(control: &mut [f64], points: PointsRef<'_>) {
    let dim = points.dim();
    let len = control.len();
    control[..dim].copy_from_slice(points.point(0));
    control[len - dim..].copy_from_slice(points.point(points.len() - 1));
}
