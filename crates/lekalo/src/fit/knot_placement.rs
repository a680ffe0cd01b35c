//! Knots for least squares: placement so that every span holds data, and the
//! Schoenberg–Whitney check (`docs/theory/fitting.md#knot-placement`).

use crate::error::{check_degree_bound, Error, Result};
use crate::knots::{check_parameters, too_few_for_degree, KnotVector};

/// Clamped knots for a least-squares fit with `n_ctrl` control points of `degree` to data with
/// the sorted parameters `ū_0 ≤ … ≤ ū_m`, by Piegl & Tiller eq. 9.68–9.69: with
/// `d = (m + 1)/(n − p + 1)` (`n = n_ctrl − 1`), the interior knots are
/// `u_{p+j} = (1 − α) ū_{i−1} + α ū_i`, `i = ⌊j d⌋`, `α = j d − i`, `j = 1 … n − p`; the ends
/// are `p + 1` copies of `ū_0` and of `ū_m`. Every knot span then holds at least one parameter,
/// so the least-squares matrix has full rank (the Schoenberg–Whitney conditions hold). O(n).
///
/// ```
/// use lekalo::fit::place_knots;
/// let u: Vec<f64> = (0..10).map(|k| k as f64 / 9.0).collect();
/// let kv = place_knots(&u, 3, 6)?;
/// assert_eq!(kv.len(), 10);
/// lekalo::fit::check_schoenberg_whitney(&u, 3, &kv)?;
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// Parameter errors as [`check_parameters`] (sorted, finite, non-empty range);
/// [`Error::Degree`] for degree 0 or `n_ctrl ≤ degree`; [`Error::TooFew`] if there are fewer
/// parameters than control points; [`Error::KnotMultiplicity`] if repeated parameters make a
/// knot too multiple.
pub fn place_knots(params: &[f64], degree: usize, n_ctrl: usize) -> Result<KnotVector> {
    check_parameters(params)?;
    check_degree_bound(degree)?;
    if degree == 0 {
        return Err(Error::Degree {
            degree,
            reason: "least-squares knots need degree ≥ 1".into(),
        });
    }
    if n_ctrl <= degree {
        return Err(too_few_for_degree(n_ctrl, degree));
    }
    if params.len() < n_ctrl {
        return Err(Error::TooFew {
            what: "data points, one at least per control point asked for (Schoenberg–Whitney: ask for fewer control points or give more points)".into(),
            min: n_ctrl,
            got: params.len(),
        });
    }
    let (m1, n) = (params.len(), n_ctrl - 1);
    let d = m1 as f64 / (n - degree + 1) as f64;
    let mut knots = Vec::with_capacity(n_ctrl + degree + 1);
    knots.extend(std::iter::repeat_n(params[0], degree + 1));
    for j in 1..=n - degree {
        let jd = j as f64 * d;
        // 1 ≤ ⌊j d⌋ ≤ m because d ≥ 1 and j ≤ n − p
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let i = (jd.floor() as usize).clamp(1, m1 - 1);
        let alpha = jd - i as f64;
        knots.push((1.0 - alpha) * params[i - 1] + alpha * params[i]);
    }
    knots.extend(std::iter::repeat_n(params[m1 - 1], degree + 1));
    let kv = KnotVector::new(knots)?;
    kv.validate_for(degree, n_ctrl)?;
    Ok(kv)
}

/// Checks the Schoenberg–Whitney conditions for least squares with `knots` of `degree` at the
/// data parameters `params` (any order): distinct parameters `x_{i_0} < x_{i_1} < …` can be
/// chosen, one per basis function `B_j`, with `t_j < x_{i_j} < t_{j+p+1}` (a closed end where
/// the support meets an end of the domain). Then the least-squares matrix has full column rank
/// (de Boor, *A Practical Guide to Splines*, XIII; FITPACK `fpchec`). Greedy matching in order,
/// O(N + n) for sorted parameters.
///
/// ```
/// use lekalo::fit::check_schoenberg_whitney;
/// use lekalo::{Error, KnotVector};
/// let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.2, 0.4, 0.6, 1.0, 1.0, 1.0])?;
/// // no data between 0.2 and 0.6: basis function 4 is left without a parameter
/// let e = check_schoenberg_whitney(&[0.0, 0.05, 0.1, 0.15, 0.8, 1.0], 2, &kv).unwrap_err();
/// assert!(matches!(e, Error::SchoenbergWhitney { basis: 4, start: 0.4, end: 0.6 }));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::SchoenbergWhitney`] naming the first basis function left without a parameter and
/// the last knot span before the end of its support that holds no data (or the support itself
/// when every span there holds data but too few distinct parameters); [`Error::Degree`] and the other errors of
/// [`KnotVector::validate_for`] for knots that do not suit `degree`.
pub fn check_schoenberg_whitney(params: &[f64], degree: usize, knots: &KnotVector) -> Result<()> {
    let t = knots.as_slice();
    let n_ctrl = t
        .len()
        .checked_sub(degree + 1)
        .ok_or_else(|| Error::Degree {
            degree,
            reason: format!("{} knots carry no spline of this degree", t.len()),
        })?;
    knots.validate_for(degree, n_ctrl)?;
    let sorted_copy;
    let x: &[f64] = if params.windows(2).all(|w| w[0] <= w[1]) {
        params
    } else {
        let mut v = params.to_vec();
        v.sort_by(f64::total_cmp);
        sorted_copy = v;
        &sorted_copy
    };
    let (a, b) = knots.domain(degree);
    let mut i = 0;
    for j in 0..n_ctrl {
        let (lo, hi) = (t[j], t[j + degree + 1]);
        while i < x.len() && !(x[i] > lo || (j == 0 && x[i] >= a)) {
            i += 1;
        }
        if i == x.len() || !(x[i] < hi || (j + 1 == n_ctrl && x[i] <= b)) {
            let (start, end) = empty_span(x, t, degree, hi).unwrap_or((lo, hi));
            return Err(Error::SchoenbergWhitney {
                basis: j,
                start,
                end,
            });
        }
        let v = x[i];
        while i < x.len() && x[i] == v {
            i += 1;
        }
    }
    Ok(())
}

/// The last non-empty knot span of the domain ending at or before `hi` that holds no parameter.
fn empty_span(x: &[f64], t: &[f64], degree: usize, hi: f64) -> Option<(f64, f64)> {
    let n_ctrl = t.len() - degree - 1;
    (degree..n_ctrl)
        .rev()
        .map(|l| (t[l], t[l + 1]))
        .filter(|&(s, e)| s < e && e <= hi)
        .find(|&(s, e)| {
            let k = x.partition_point(|&v| v < s);
            // the last span is closed on the right
            !(k < x.len() && (x[k] < e || (e >= t[n_ctrl] && x[k] <= e)))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placed_knots_leave_no_empty_span() {
        for m in [4usize, 5, 7, 20, 101] {
            let u: Vec<f64> = (0..m)
                .map(|k| (k as f64 / (m - 1) as f64).powi(2))
                .collect();
            for p in 1..=3 {
                for n_ctrl in p + 1..=m {
                    let kv = place_knots(&u, p, n_ctrl).unwrap();
                    assert_eq!(kv.len(), n_ctrl + p + 1, "m {m} p {p} n {n_ctrl}");
                    check_schoenberg_whitney(&u, p, &kv).unwrap();
                }
            }
        }
    }

    #[test]
    fn too_many_control_points_is_refused() {
        let u = [0.0, 0.5, 1.0];
        let e = place_knots(&u, 2, 4).unwrap_err();
        assert!(matches!(e, Error::TooFew { min: 4, got: 3, .. }), "{e:?}");
        assert!(
            e.to_string().contains("ask for fewer control points"),
            "the message names the fix: {e}"
        );
        // duplicates do not count twice
        let kv = KnotVector::clamped_uniform(1, 3).unwrap();
        let e = check_schoenberg_whitney(&[0.0, 0.0, 1.0, 1.0], 1, &kv).unwrap_err();
        assert!(
            matches!(e, Error::SchoenbergWhitney { basis: 1, .. }),
            "{e:?}"
        );
    }
}
