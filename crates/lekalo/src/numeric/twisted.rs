//! The twisted elimination of a tridiagonal system ("burn at both ends": H. A. van der Vorst,
//! *Large tridiagonal and block tridiagonal linear systems on vector and parallel computers*,
//! Parallel Computing 5, 1987, 45–54): rows `0 … k` are eliminated downwards and rows
//! `n − 1 … k + 1` upwards at the same time, the two meet at row `k`, and the unknowns are
//! substituted back from `k` in both directions at once.
//!
//! Each elimination is a chain of dependent operations, one row after the other; two chains of
//! half the length, interleaved, keep the core's arithmetic units busy with one while the other
//! waits for its latest result, so the time of a solve is about half that of one chain. The
//! pivots of each half are those of Gaussian elimination without row swaps of the matrix and of
//! its reversal; for a matrix whose rows are diagonally dominant (the interior of SciPy's
//! `CubicSpline` system) both are backward stable (Higham, *Accuracy and Stability of Numerical
//! Algorithms*, 2nd ed., ch. 9), the same solution as LAPACK `dgtsv`'s to rounding.
//!
//! The numerical kernel is hand-written because it is the product: no linear-algebra crate
//! eliminates a tridiagonal system from both ends, or reads its entries where they are formed.

use super::tridiagonal::{next_minor, Bands};

/// One elimination's state at its latest row: the last two minors of the eliminated part (the
/// determinants of its leading rows and columns, or trailing for the upward one), the
/// reciprocal of the latest pivot (`pivot = minor / prev`) and the latest reduced right-hand
/// side.
#[derive(Clone, Copy)]
struct Sweep {
    prev: f64,
    minor: f64,
    recip: f64,
    value: f64,
}

impl Sweep {
    /// The first row of a sweep: diagonal `d`, right-hand side `rhs`.
    #[inline(always)]
    fn start(d: f64, rhs: f64) -> Self {
        Sweep {
            prev: 1.0,
            minor: d,
            recip: 1.0 / d,
            value: rhs,
        }
    }

    /// One row further: the row's diagonal `d`, the product `c` of the two entries that couple
    /// it to the previous row, its entry `a` in the previous row's column and its right-hand
    /// side `rhs`; the minors by [`next_minor`], the reduced right-hand side
    /// `rhs − (a/p)·value`.
    #[inline(always)]
    fn step(&mut self, d: f64, c: f64, a: f64, rhs: f64) {
        let (next, minor) = next_minor(d, c, self.minor, self.prev);
        self.value = rhs - (a * self.recip) * self.value;
        let recip = minor / next;
        self.prev = minor;
        self.minor = next;
        self.recip = recip;
    }
}

/// Whether the reciprocal `r` of a pivot is in (0, ∞) (not NaN), with no branch.
#[inline(always)]
fn positive(r: f64) -> bool {
    (r > 0.0) & (r < f64::INFINITY)
}

/// Solves `A·x = b` in place (one column, `n ≥ 2` rows) by the twisted elimination (module
/// docs) when every pivot of both halves is positive and finite, and returns `true`; returns
/// `false` otherwise, with `b` overwritten by partial work (the caller forms it again and
/// eliminates with row swaps). `recip` is `n` numbers of scratch (the pivots' reciprocals).
/// O(n).
pub(crate) fn solve_twisted(m: &impl Bands, b: &mut [f64], recip: &mut [f64]) -> bool {
    let n = m.len();
    debug_assert!(n >= 2 && b.len() == n && recip.len() == n, "lengths");
    // rows 0 … k downwards, n − 1 … k + 1 upwards: k downward steps, n − 2 − k upward ones
    let k = (n - 1) / 2;
    let (first, last) = (m.row(0), m.row(n - 1));
    let mut down = Sweep::start(first[1], b[0]);
    let mut up = Sweep::start(last[1], b[n - 1]);
    recip[0] = down.recip;
    recip[n - 1] = up.recip;
    // the entry of the row above that couples it to the next one down (`du`), and of the row
    // below to the next one up (`dl`), carried from row to row
    let (mut u, mut l) = (first[2], last[0]);
    let both = (n - 2 - k).min(k);
    for s in 0..both {
        let (i, j) = (s + 1, n - 2 - s);
        let [li, di, ui] = m.row(i);
        down.step(di, li * u, li, b[i]);
        let [lj, dj, uj] = m.row(j);
        up.step(dj, l * uj, uj, b[j]);
        (u, l) = (ui, lj);
        (b[i], recip[i]) = (down.value, down.recip);
        (b[j], recip[j]) = (up.value, up.recip);
    }
    for i in both + 1..=k {
        let [li, di, ui] = m.row(i);
        down.step(di, li * u, li, b[i]);
        u = ui;
        (b[i], recip[i]) = (down.value, down.recip);
    }
    for j in (k + 1..n - 1 - both).rev() {
        let [lj, dj, uj] = m.row(j);
        up.step(dj, l * uj, uj, b[j]);
        l = lj;
        (b[j], recip[j]) = (up.value, up.recip);
    }
    // row k, its left neighbour eliminated from above and its right one from below:
    // (p_k − u_k l_k / s_{k+1})·x_k = y_k − (u_k / s_{k+1})·z_{k+1}
    let pivot = 1.0 / down.recip - (u * l) * up.recip;
    // every pivot in (0, ∞): its reciprocal in (0, ∞), NaN failing both (checked in one
    // vectorised pass after the chains, not on them: a count, without the early exit of
    // `all`, whose branch a number kept the pass from being vectorised)
    if !positive(pivot) || recip.iter().filter(|&&r| !positive(r)).count() != 0 {
        return false;
    }
    let mut above = (down.value - (u * up.recip) * up.value) / pivot;
    b[k] = above;
    let mut below = above;
    // back from row k: x_i = y_i/p_i − (u_i/p_i)·x_{i+1} upwards and
    // x_j = z_j/s_j − (l_{j−1}/s_j)·x_{j−1} downwards, one multiplication and one subtraction
    // a row on each chain
    let rows_up = k;
    let rows_down = n - 1 - k;
    for s in 0..rows_up.min(rows_down) {
        let (i, j) = (k - 1 - s, k + 1 + s);
        above = b[i] * recip[i] - (m.row(i)[2] * recip[i]) * above;
        below = b[j] * recip[j] - (m.row(j)[0] * recip[j]) * below;
        b[i] = above;
        b[j] = below;
    }
    for i in (0..k.saturating_sub(rows_down)).rev() {
        above = b[i] * recip[i] - (m.row(i)[2] * recip[i]) * above;
        b[i] = above;
    }
    for j in k + 1 + rows_up..n {
        below = b[j] * recip[j] - (m.row(j)[0] * recip[j]) * below;
        b[j] = below;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::tridiagonal::tests::{pivoted, spline_rows};
    use crate::numeric::tridiagonal::StoredBands;

    /// `dgtsv`'s solution of the same system.
    #[test]
    fn the_solution_of_row_swaps_to_rounding_at_every_meeting_row() {
        // every n from 2 (each half's leftover rows, odd and even n) and a long system
        for n in (2..=12).chain([300, 1001]) {
            let (dl, d, du) = spline_rows(n);
            let rhs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() + 0.5).collect();
            let (mut x, mut recip) = (rhs.clone(), vec![0.0; n]);
            let m = StoredBands {
                dl: &dl,
                d: &d,
                du: &du,
            };
            assert!(solve_twisted(&m, &mut x, &mut recip), "n = {n}");
            let want = pivoted(&dl, &d, &du, &rhs);
            let scale = want.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            for (i, (a, b)) in x.iter().zip(&want).enumerate() {
                assert!(
                    (a - b).abs() <= 1e-14 * scale,
                    "n = {n}, row {i}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn minors_far_beyond_the_exponent_range_are_rescaled() {
        // pivots of 3e60: the minors pass 2^1024 within six rows unless rescaled
        let n = 40;
        let d = vec![3e60; n];
        let (dl, du) = (vec![1e60; n - 1], vec![1e60; n - 1]);
        let rhs: Vec<f64> = (0..n).map(|i| 1e60 * (1.0 + i as f64)).collect();
        let (mut x, mut recip) = (rhs.clone(), vec![0.0; n]);
        let m = StoredBands {
            dl: &dl,
            d: &d,
            du: &du,
        };
        assert!(solve_twisted(&m, &mut x, &mut recip));
        let want = pivoted(&dl, &d, &du, &rhs);
        for (a, b) in x.iter().zip(&want) {
            assert!((a - b).abs() <= 1e-14 * b.abs(), "{a} vs {b}");
        }
    }

    #[test]
    fn a_pivot_that_is_not_positive_is_refused() {
        let cases: [(&[f64], &[f64], &[f64]); 4] = [
            // zero first pivot
            (&[1.0], &[0.0, 1.0], &[1.0]),
            // negative pivot at the meeting row
            (&[2.0], &[1.0, 1.0], &[1.0]),
            // a negative pivot in the upward half
            (&[1.0, 1.0, 5.0], &[4.0, 4.0, 4.0, 1.0], &[1.0, 1.0, 5.0]),
            // NaN on the diagonal
            (&[1.0, 1.0], &[4.0, f64::NAN, 4.0], &[1.0, 1.0]),
        ];
        for (dl, d, du) in cases {
            let mut b = vec![1.0; d.len()];
            let m = StoredBands { dl, d, du };
            assert!(!solve_twisted(&m, &mut b, &mut vec![0.0; d.len()]), "{d:?}");
        }
    }
}
