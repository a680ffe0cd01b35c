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
    if let Some(i) = t.windows(2).position(|w| !(w[0] <= w[1])) {
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
    let mut scratch = BasisScratch::new(k);
    let mut ders = vec![0.0; (k + 1) * (k + 1)];
    let mut power = vec![0.0; k + 1];
    let mut out: Vec<f64> = Vec::new();
    for s in (first..=last).filter(nonempty) {
        let window = &c[s - k..=s];
        if window.iter().all(|&v| v > 0.0) || window.iter().all(|&v| v < 0.0) {
            continue;
        }
        basis_ders_into(t, k, s, t[s], k, &mut scratch, &mut ders);
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
        let extend = s == first || s == last;
        for z in piece.solve(0.0, false, extend).swap_remove(0) {
            let Solution::At(x) = z else { continue };
            let keep = (x >= lo || s == first) && (x <= hi || s == last);
            if keep && out.last() != Some(&x) {
                out.push(x);
            }
        }
    }
    Ok(out)
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
}
