//! The fused fast path of global cubic interpolation (document 000 §A.1 with chord-length
//! parameters and averaged knots, eq. 3), for 1–3 dimensions: parameters, knots, banded
//! elimination and back substitution in three sweeps, with the same numbers as the general path
//! of [`crate::interpolate`] (tested there), which it falls back to whenever it does not apply.

use crate::interpolate::distance;
use crate::linalg::solve_free_cubic;
use crate::{BSplineCurve, Points, PointsRef};

/// The fast path of [`free_end`](crate::interpolate) for cubics with averaged knots in 1–3 dimensions
/// ([`solve_free_cubic`](crate::linalg::solve_free_cubic)): the control points, or `None` when it does not apply or a check
/// fails, so that the general path reports the error.
pub(crate) fn free_end_cubic(
    points: PointsRef<'_>,
    params: &[f64],
    knots: &[f64],
) -> Option<Points> {
    let dim = points.dim();
    let mut control = vec![0.0; points.as_slice().len()];
    for (c, t) in control.chunks_exact_mut(dim).zip(params) {
        c[0] = *t;
    }
    solve_free_cubic_dyn(points.as_slice(), knots, &mut control, dim)
        .then(|| Points::from_raw(control, dim))
}

/// [`solve_free_cubic`](crate::linalg::solve_free_cubic) for a runtime dimension 1–3 (`false` for others).
fn solve_free_cubic_dyn(q: &[f64], knots: &[f64], control: &mut [f64], dim: usize) -> bool {
    match dim {
        1 => solve_free_cubic::<1>(q, knots, control),
        2 => solve_free_cubic::<2>(q, knots, control),
        3 => solve_free_cubic::<3>(q, knots, control),
        _ => false,
    }
}

/// The whole free-end chord-length cubic in three sweeps over the data and no buffers besides
/// the result and `U`: chord lengths (P&T eq. 9.5, as [`parametrize_into`](crate::interpolate::parametrize_into), the same numbers)
/// go straight into the first slot of each control point's row, the averaged knots (document
/// 000 eq. 3, as [`KnotVector::averaged`](crate::KnotVector::averaged), the same numbers) are formed as the lengths are
/// normalised, then [`solve_free_cubic`](crate::linalg::solve_free_cubic). `None` (take the general path, which reports the
/// problem) for coincident or overflowing points, a dimension above 3, fewer than 5 points or
/// a failed check of the solve.
pub(crate) fn chord_cubic(points: PointsRef<'_>) -> Option<BSplineCurve> {
    let dim = points.dim();
    let q = points.as_slice();
    let n = points.len().checked_sub(1)?;
    if n < 4 {
        return None;
    }
    let mut control = vec![0.0; q.len()];
    let mut knots = vec![0.0; n + 5];
    let done = match dim {
        1 => chord_cubic_fill::<1>(q, &mut control, &mut knots),
        2 => chord_cubic_fill::<2>(q, &mut control, &mut knots),
        3 => chord_cubic_fill::<3>(q, &mut control, &mut knots),
        _ => false,
    };
    done.then(|| BSplineCurve::from_raw(3, knots, Points::from_raw(control, dim)))
}

/// The body of [`chord_cubic`] for `D` coordinates: `control` and `knots` are zeroed buffers of
/// the result's sizes.
fn chord_cubic_fill<const D: usize>(q: &[f64], control: &mut [f64], knots: &mut [f64]) -> bool {
    let n = q.len() / D - 1;
    let mut sum = 0.0;
    let mut prev: &[f64] = &q[..D];
    for (next, c) in q[D..].chunks_exact(D).zip(control[D..].chunks_exact_mut(D)) {
        let d = distance(prev, next);
        if d == 0.0 || !d.is_finite() {
            return false;
        }
        sum += d;
        c[0] = sum;
        prev = next;
    }
    if !sum.is_finite() {
        return false;
    }
    let inv = 1.0 / sum;
    control[n * D] = 1.0;
    knots[n + 1..].fill(1.0);
    // t̄_{r−2}, t̄_{r−1}
    let (mut t2, mut t1) = (0.0, 0.0);
    for r in 1..=n {
        let t = if r < n { control[r * D] * inv } else { 1.0 };
        if t <= t1 {
            return false;
        }
        control[r * D] = t;
        // u_{j+3} = (t̄_j + t̄_{j+1} + t̄_{j+2}) / 3 for j = 1 … n − 3, complete once t̄_{j+2} is
        if (3..n).contains(&r) {
            let sum3: f64 = [t2, t1, t].iter().sum();
            knots[r + 1] = sum3 / 3.0;
        }
        (t2, t1) = (t1, t);
    }
    solve_free_cubic::<D>(q, knots, control)
}
