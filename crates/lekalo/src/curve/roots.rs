//! Zeros of a scalar spline given as arrays (SciPy's `(t, c, k)`), span by span on the B-spline
//! itself (`docs/theory/curves.md#zeros-of-a-spline`).

use crate::basis::{basis_ders_into, BasisScratch};
use crate::error::readable;
use crate::error::{Error, Result};
use crate::pp::{PiecewisePolynomial, Solution};

/// The zeros of the scalar spline `S = Σ_j c_j B_{j,k}` on the knots `t`, in its base interval
/// `[t_k, t_n]`, increasing (FITPACK's `sproot`, for any degree):
///
/// - a span `[t_s, t_{s+1}]` whose `k + 1` coefficients `c_{s−k} … c_s` are all positive or all
///   negative is skipped: there `S` is a convex combination of them (the B-splines are
///   non-negative and sum to one), so it has their sign — the convex-hull form of the
///   variation-diminishing property (de Boor, *A Practical Guide to Splines*, ch. XI; Lane &
///   Riesenfeld 1981 use it the same way to isolate roots). For a spline with few zeros almost
///   every span is skipped after `k + 1` comparisons;
/// - on the other spans the local power form `Σ_r S^{(r)}(t_s)/r! (x − t_s)^r` (the basis
///   derivatives at `t_s`, P&T A2.3) is solved as one piece of a
///   [`PiecewisePolynomial`] ([`PiecewisePolynomial::solve`]: roots isolated between the
///   roots of the derivatives, bisected to adjacent doubles, one Newton step);
/// - the first span's polynomial is also searched to the left of the domain and the last
///   span's to the right (a zero at an end may round to either side; the caller decides how
///   far outside to keep), a span on which `S` vanishes identically gives no zero, and a zero
///   on a knot found in both neighbouring spans is reported once.
///
/// O(n·k) for the sign tests plus O(k²) a span with a sign change.
///
/// ```
/// use lekalo::curve::bspline_zeros;
/// // the linear spline through (0, −1), (1, 1), (2, −1): zeros at 0.5 and 1.5
/// let z = bspline_zeros(&[0.0, 0.0, 1.0, 2.0, 2.0], 1, &[-1.0, 1.0, -1.0])?;
/// assert_eq!(z, vec![0.5, 1.5]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] for fewer than `2k + 2` knots, fewer than `n = len(t) − k − 1`
/// coefficients, knots that decrease or are not finite, or an empty base interval.
#[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN knots must be refused
pub fn bspline_zeros(t: &[f64], k: usize, c: &[f64]) -> Result<Vec<f64>> {
    let invalid = |reason: String| Error::InvalidArgument {
        what: "spline (knots, degree, coefficients)".into(),
        reason,
    };
    if t.len() < 2 * k + 2 {
        return Err(invalid(format!(
            "{} knots for degree {k}: at least 2k + 2 are needed",
            t.len()
        )));
    }
    let n = t.len() - k - 1;
    if c.len() < n {
        return Err(invalid(format!(
            "{} coefficients for {} knots of degree {k}: at least {n} are needed",
            c.len(),
            t.len()
        )));
    }
    // one branch-free pass (vectorised; NaN fails `≤`), the offending pair searched on failure
    let sorted = t.iter().zip(&t[1..]).fold(true, |ok, (a, b)| ok & (a <= b));
    if let Some(i) = (!sorted)
        .then(|| t.windows(2).position(|w| !(w[0] <= w[1])))
        .flatten()
    {
        return Err(invalid(format!(
            "knots {i} and {} ({} and {}) are not finite and non-decreasing",
            i + 1,
            readable(&t[i]),
            readable(&t[i + 1])
        )));
    }
    if !(t[k] < t[n]) || !t[0].is_finite() || !t[t.len() - 1].is_finite() {
        return Err(invalid(format!(
            "the base interval [t_k, t_n] = [{}, {}] is empty or not finite",
            t[k], t[n]
        )));
    }
    // the non-empty spans, walked without collecting them (a list of a million spans is fresh
    // memory whose page faults cost more than the walk); t_k < t_n, so there is one
    let nonempty = |s: &usize| t[*s] < t[*s + 1];
    let (Some(first), Some(last)) = ((k..n).find(nonempty), (k..n).rev().find(nonempty)) else {
        return Ok(Vec::new());
    };
    let mut work = SpanWork {
        scratch: BasisScratch::new(k),
        ders: vec![0.0; (k + 1) * (k + 1)],
        power: vec![0.0; k + 1],
    };
    let mut out: Vec<f64> = Vec::new();
    let mut s = first;
    while s <= last {
        // a block of spans whose coefficients all share one strict sign is skipped after one
        // branch-free pass over them (NaN shares no sign)
        let end = (s + SIGN_BLOCK).min(last + 1);
        if one_strict_sign(&c[s - k..end]) {
            s = end;
            continue;
        }
        for s in (s..end).filter(nonempty) {
            solve_span(t, k, c, s, s == first, s == last, &mut work, &mut out)?;
        }
        s = end;
    }
    Ok(out)
}

/// Spans a block of [`bspline_zeros`]'s sign test: long enough that the test's pass
/// vectorises, short enough that a block with a zero costs little more than its spans.
const SIGN_BLOCK: usize = 64;

/// Whether the numbers are all positive or all negative (NaN is neither).
fn one_strict_sign(v: &[f64]) -> bool {
    let (pos, neg) = v
        .iter()
        .fold((true, true), |(p, n), &x| (p & (x > 0.0), n & (x < 0.0)));
    pos || neg
}

/// The scratch of [`solve_span`]: the basis derivatives and the power coefficients.
struct SpanWork {
    scratch: BasisScratch,
    ders: Vec<f64>,
    power: Vec<f64>,
}

/// The zeros of `S` on the span `s` (beyond the domain too on the `first` and `last` spans)
/// appended to `out`, unless its `k + 1` coefficients share one strict sign.
#[allow(clippy::too_many_arguments)]
fn solve_span(
    t: &[f64],
    k: usize,
    c: &[f64],
    s: usize,
    first: bool,
    last: bool,
    work: &mut SpanWork,
    out: &mut Vec<f64>,
) -> Result<()> {
    let SpanWork {
        scratch,
        ders,
        power,
    } = work;
    let window = &c[s - k..=s];
    if window.iter().all(|&v| v > 0.0) || window.iter().all(|&v| v < 0.0) {
        return Ok(());
    }
    basis_ders_into(t, k, s, t[s], k, scratch, ders);
    let mut factorial = 1.0;
    for (r, a) in power.iter_mut().enumerate() {
        if r > 0 {
            factorial *= r as f64;
        }
        let row = &ders[r * (k + 1)..(r + 1) * (k + 1)];
        *a = row.iter().zip(window).map(|(b, v)| b * v).sum::<f64>() / factorial;
    }
    let (lo, hi) = (t[s], t[s + 1]);
    let piece = PiecewisePolynomial::new(vec![lo, hi], k + 1, 1, power.clone())?;
    let extend = first || last;
    for z in piece.solve(0.0, false, extend).swap_remove(0) {
        let Solution::At(x) = z else { continue };
        let keep = (x >= lo || first) && (x <= hi || last);
        if keep && out.last() != Some(&x) {
            out.push(x);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSplineCurve, Points};

    /// A cubic through samples of `f` on [0, 10] (clamped knots at the samples).
    fn cubic(samples: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let m = samples.len();
        let mut t = vec![0.0; 4];
        for i in 1..m - 3 {
            t.push(10.0 * i as f64 / (m - 3) as f64);
        }
        t.extend([10.0; 4]);
        (t, samples.to_vec())
    }

    #[test]
    fn every_sign_change_of_a_wavy_cubic_is_a_zero_and_nothing_else() {
        let c: Vec<f64> = (0..400)
            .map(|i| (0.05 * f64::from(i) + 0.1).sin())
            .collect();
        let (t, c) = cubic(&c);
        let z = bspline_zeros(&t, 3, &c).unwrap();
        let curve =
            BSplineCurve::new(3, t.clone(), Points::from_flat(1, c.clone()).unwrap()).unwrap();
        // a fine grid's sign changes, each bracketing exactly one reported zero
        let grid: Vec<f64> = (0..=20000).map(|i| f64::from(i) * 10.0 / 20000.0).collect();
        let v: Vec<f64> = grid.iter().map(|&x| curve.eval(x).unwrap()[0]).collect();
        let changes = v
            .windows(2)
            .filter(|w| w[0].signum() != w[1].signum())
            .count();
        assert_eq!(z.len(), changes);
        for &x in &z {
            assert!(
                curve.eval(x).unwrap()[0].abs() < 1e-12,
                "S({x}) is not zero"
            );
        }
        assert!(z.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn vanishing_spans_give_none_and_zeros_on_knots_and_ends_come_once() {
        // linear: zero identically on [0, 3] (no zero reported there), then rising from the knot 3
        let t = [0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0];
        let c = [0.0, 0.0, 0.0, 0.0, 1.0];
        let z = bspline_zeros(&t, 1, &c).unwrap();
        assert_eq!(z, vec![3.0]);
        let c = [-1.0, 1.0, -1.0, 1.0, 0.0];
        let z = bspline_zeros(&t, 1, &c).unwrap();
        assert_eq!(z, vec![0.5, 1.5, 2.5, 4.0]);
    }

    #[test]
    fn refusals_name_the_problem() {
        assert!(bspline_zeros(&[0.0, 1.0], 1, &[0.0]).is_err());
        assert!(bspline_zeros(&[0.0, 0.0, 1.0, 1.0], 1, &[0.0]).is_err());
        assert!(bspline_zeros(&[0.0, 0.0, f64::NAN, 1.0, 1.0], 1, &[0.0, 1.0, 0.0]).is_err());
        assert!(bspline_zeros(&[1.0, 1.0, 1.0, 1.0], 1, &[0.0, 1.0]).is_err());
    }

    /// Skipping blocks of spans with one sign loses no zero: the result is that of solving
    /// every span, with sign changes at and around the blocks' edges and a span emptied by a
    /// repeated knot; a NaN coefficient, in a block no sign skips, is refused, not a panic.
    #[test]
    fn skipped_blocks_lose_no_zero() {
        let m = 700;
        let mut samples: Vec<f64> = (0..m)
            .map(|i| 1.0 + 0.1 * (f64::from(i) * 0.3).sin())
            .collect();
        for &i in &[5usize, 63, 64, 65, 66, 127, 128, 200, 333, 512, 690] {
            samples[i] = -2.0;
        }
        let (mut t, mut c) = cubic(&samples);
        // a double interior knot: one empty span
        t[300] = t[301];
        let k = 3;
        let z = bspline_zeros(&t, k, &c).unwrap();
        let n = t.len() - k - 1;
        let nonempty = |s: &usize| t[*s] < t[*s + 1];
        let first = (k..n).find(nonempty).unwrap();
        let last = (k..n).rev().find(nonempty).unwrap();
        let mut work = SpanWork {
            scratch: BasisScratch::new(k),
            ders: vec![0.0; (k + 1) * (k + 1)],
            power: vec![0.0; k + 1],
        };
        let mut want = Vec::new();
        for s in (first..=last).filter(nonempty) {
            solve_span(&t, k, &c, s, s == first, s == last, &mut work, &mut want).unwrap();
        }
        assert!(z.len() >= 12, "{} zeros", z.len());
        assert_eq!(z, want);
        c[400] = f64::NAN;
        assert!(bspline_zeros(&t, k, &c).is_err());
    }
}
