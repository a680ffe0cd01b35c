//! Gaussian elimination without row swaps of a tridiagonal system in [`LANES`] partitions
//! eliminated at the same time, each started from a guess a few rows before its own and
//! accepted only where it has met its neighbour's exact state bit for bit.
//!
//! Elimination is a chain of dependent operations, one row after the other, with a division on
//! the chain: one chain keeps the core waiting on each division. For a diagonally dominant
//! matrix the influence of the first rows on the pivots `p_i = d_i − dl_{i−1} du_{i−1} / p_{i−1}`
//! and on the reduced right-hand side dies out geometrically (the decay that the truncated SPIKE
//! algorithm rests on: E. Polizzi and A. H. Sameh, *A parallel hybrid banded system solver: the
//! SPIKE algorithm*, Parallel Computing 32, 2006, 177–194). So partition `j` starts [`WARM`]
//! rows before its block from the guess `p = d`, right-hand side 0, and by its block's first row
//! its state is the exact one: the state of the previous partition at the same row, which that
//! partition computed from the true first row. Where the two states are equal bit for bit, every
//! later operation of partition `j` is the one the single chain would make, so the answer is the
//! single chain's to the last bit; where they are not (a matrix whose eliminations remember
//! their start, or rounding that has not settled), the solve says so and the caller solves
//! another way. The back substitution `x_i = y_i/p_i − (du_i/p_i) x_{i+1}` is partitioned the
//! same way from the other end.
//!
//! Eight chains interleaved keep the divider busy (measured on the `CubicSpline` system of 10^5
//! rows: 310 µs against 483 µs for [`super::twisted`]'s two chains and 835 µs for one).
//! The kernel is hand-written because it is the product: no linear-algebra crate eliminates a
//! tridiagonal system in checked partitions, or reads its entries where they are formed.

use super::tridiagonal::Bands;

/// The number of partitions eliminated at the same time.
const LANES: usize = 8;

/// The rows a partition runs from its guess before its state must equal its neighbour's.
const WARM: usize = 40;

/// The fewest rows solved in partitions: each partition at least twice [`WARM`] long, so that
/// the rows a partition reads are read before its neighbour writes them.
pub(crate) const MIN_ROWS: usize = LANES * 2 * WARM + WARM;

/// One forward elimination's state after a row: the reciprocal of its pivot, its reduced
/// right-hand side and its entry right of the diagonal (what the next row reads).
#[derive(Clone, Copy, Default)]
struct Down {
    recip: f64,
    value: f64,
    upper: f64,
}

impl Down {
    /// Row `i` eliminated with the previous row's state: `m = dl_{i−1}/p_{i−1}`,
    /// `p_i = d_i − m du_{i−1}`, `y_i = b_i − m y_{i−1}`.
    #[inline(always)]
    fn step(&mut self, m: &impl Bands, b: &[f64], i: usize) {
        let [lower, diag, upper] = m.row(i);
        let mult = lower * self.recip;
        self.recip = 1.0 / (diag - mult * self.upper);
        self.value = b[i] - mult * self.value;
        self.upper = upper;
    }

    /// Bit for bit the same state: every later step gives the same numbers.
    fn same(&self, recip: f64, value: f64) -> bool {
        self.recip.to_bits() == recip.to_bits() && self.value.to_bits() == value.to_bits()
    }
}

/// Row `i` of the back substitution: `x_i = y_i r_i − (du_i r_i) x_{i+1}` with `r_i = 1/p_i`.
#[inline(always)]
fn back(m: &impl Bands, b: &[f64], recip: &[f64], i: usize, x: f64) -> f64 {
    b[i] * recip[i] - (m.row(i)[2] * recip[i]) * x
}

#[inline(always)]
fn positive(r: f64) -> bool {
    (r > 0.0) & (r < f64::INFINITY)
}

/// Solves `A·x = b` in place (`b`: `n ≥` [`MIN_ROWS`] rows, one column) by Gaussian elimination
/// without row swaps, the reciprocals of the pivots left in `recip` (`n` numbers), and returns
/// `true` when every pivot is positive and finite and every partition met its neighbour's state
/// (the module's documentation): then `b` holds bit for bit what one chain of elimination gives.
/// `false` otherwise, `b` and `recip` partly overwritten: the caller forms `b` again and solves
/// another way. O(n); nothing allocated.
pub(crate) fn solve_partitioned(m: &impl Bands, b: &mut [f64], recip: &mut [f64]) -> bool {
    let n = m.len();
    debug_assert!(b.len() == n && recip.len() == n, "lengths");
    if n < MIN_ROWS {
        return false;
    }
    // partition j eliminates rows j·len + 1 … j·len + len + WARM − 1, the first WARM − 1 of them
    // (j > 0) from its guess and unwritten; the last partition then the rows left over
    let len = (n - WARM) / LANES;
    let rest = n - WARM - LANES * len;
    let mut down = [Down::default(); LANES];
    for (j, lane) in down.iter_mut().enumerate() {
        let [_, diag, upper] = m.row(j * len);
        *lane = Down {
            recip: 1.0 / diag,
            value: 0.0,
            upper,
        };
    }
    down[0].value = b[0];
    recip[0] = down[0].recip;
    let mut bad = !positive(recip[0]);
    for k in 1..WARM {
        down[0].step(m, b, k);
        (b[k], recip[k]) = (down[0].value, down[0].recip);
        bad |= !positive(recip[k]);
        for (j, lane) in down.iter_mut().enumerate().skip(1) {
            lane.step(m, b, j * len + k);
        }
    }
    let guessed = down;
    for k in WARM..len + WARM {
        for (j, lane) in down.iter_mut().enumerate() {
            let i = j * len + k;
            lane.step(m, b, i);
            (b[i], recip[i]) = (lane.value, lane.recip);
            bad |= !positive(lane.recip);
        }
    }
    let last = &mut down[LANES - 1];
    for i in n - rest..n {
        last.step(m, b, i);
        (b[i], recip[i]) = (last.value, last.recip);
        bad |= !positive(last.recip);
    }
    let met = (1..LANES).all(|j| {
        let i = j * len + WARM - 1;
        guessed[j].same(recip[i], b[i])
    });
    if bad || !met {
        return false;
    }
    // back substitution: partition j from row top(j), the last one from the true last row
    let top = |j: usize| n - 1 - (LANES - 1 - j) * len;
    let mut x = [0.0; LANES];
    x[LANES - 1] = b[n - 1] * recip[n - 1];
    b[n - 1] = x[LANES - 1];
    for k in 1..WARM {
        for (j, v) in x.iter_mut().enumerate().take(LANES - 1) {
            *v = back(m, b, recip, top(j) - k, *v);
        }
        let i = top(LANES - 1) - k;
        x[LANES - 1] = back(m, b, recip, i, x[LANES - 1]);
        b[i] = x[LANES - 1];
    }
    let guessed = x;
    for k in WARM..len + WARM {
        for (j, v) in x.iter_mut().enumerate() {
            let i = top(j) - k;
            *v = back(m, b, recip, i, *v);
            b[i] = *v;
        }
    }
    for i in (0..rest).rev() {
        x[0] = back(m, b, recip, i, x[0]);
        b[i] = x[0];
    }
    (0..LANES - 1).all(|j| guessed[j].to_bits() == b[top(j) - (WARM - 1)].to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::tridiagonal::tests::{pivoted, spline_rows};
    use crate::numeric::tridiagonal::StoredBands;
    use proptest::prelude::*;

    /// One chain of elimination, the operations of [`Down::step`] and [`back`] in row order.
    fn one_chain(m: &StoredBands<'_>, rhs: &[f64]) -> Vec<f64> {
        let n = m.len();
        let (mut b, mut recip) = (rhs.to_vec(), vec![0.0; n]);
        let [_, diag, upper] = m.row(0);
        let mut s = Down {
            recip: 1.0 / diag,
            value: b[0],
            upper,
        };
        recip[0] = s.recip;
        for i in 1..n {
            s.step(m, &b, i);
            (b[i], recip[i]) = (s.value, s.recip);
        }
        let mut x = b[n - 1] * recip[n - 1];
        b[n - 1] = x;
        for i in (0..n - 1).rev() {
            x = back(m, &b, &recip, i, x);
            b[i] = x;
        }
        b
    }

    /// The rows of SciPy's `CubicSpline` system (not-a-knot ends) on the steps `h`.
    fn rows_of_steps(h: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let n = h.len() + 1;
        let mut d = vec![0.0; n];
        let (mut dl, mut du) = (vec![0.0; n - 1], vec![0.0; n - 1]);
        for i in 1..n - 1 {
            d[i] = 2.0 * (h[i - 1] + h[i]);
            du[i] = h[i - 1];
            dl[i - 1] = h[i];
        }
        (d[0], du[0]) = (h[1], h[0] + h[1]);
        (d[n - 1], dl[n - 2]) = (h[n - 3], h[n - 3] + h[n - 2]);
        (dl, d, du)
    }

    #[test]
    fn one_chain_bit_for_bit_and_the_pivoted_solution_to_rounding() {
        for n in [MIN_ROWS, MIN_ROWS + 1, MIN_ROWS + 7, 1001, 4099, 20000] {
            let (dl, d, du) = spline_rows(n);
            let rhs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() + 0.5).collect();
            let m = StoredBands {
                dl: &dl,
                d: &d,
                du: &du,
            };
            let (mut x, mut recip) = (rhs.clone(), vec![0.0; n]);
            assert!(solve_partitioned(&m, &mut x, &mut recip), "n = {n}");
            let chain = one_chain(&m, &rhs);
            for (i, (a, b)) in x.iter().zip(&chain).enumerate() {
                assert_eq!(a.to_bits(), b.to_bits(), "n = {n}, row {i}: {a} vs {b}");
            }
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
    fn fewer_rows_than_the_partitions_need_are_left_to_the_caller() {
        let n = MIN_ROWS - 1;
        let (dl, d, du) = spline_rows(n);
        let m = StoredBands {
            dl: &dl,
            d: &d,
            du: &du,
        };
        let mut b = vec![1.0; n];
        assert!(!solve_partitioned(&m, &mut b, &mut vec![0.0; n]));
        assert!(b.iter().all(|&v| v == 1.0), "nothing written");
    }

    #[test]
    fn an_elimination_that_remembers_its_start_is_left_to_the_caller() {
        // the second difference (2, −1): pivots (i + 2)/(i + 1), whose start is forgotten only
        // as 1/i, so no partition meets its neighbour's state after WARM rows
        let n = 2 * MIN_ROWS;
        let (dl, d, du) = (vec![-1.0; n - 1], vec![2.0; n], vec![-1.0; n - 1]);
        let m = StoredBands {
            dl: &dl,
            d: &d,
            du: &du,
        };
        let mut b = vec![1.0; n];
        assert!(!solve_partitioned(&m, &mut b, &mut vec![0.0; n]));
    }

    #[test]
    fn a_pivot_that_is_not_positive_is_refused() {
        let n = MIN_ROWS + 3;
        let (dl, mut d, du) = spline_rows(n);
        for bad in [0.0, -1.0, f64::NAN] {
            d[n / 2] = bad;
            let m = StoredBands {
                dl: &dl,
                d: &d,
                du: &du,
            };
            let mut b = vec![1.0; n];
            assert!(!solve_partitioned(&m, &mut b, &mut vec![0.0; n]), "{bad}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Whenever the partitions are accepted, the answer is one chain's to the last bit; on
        /// steps within a factor 100 of each other they are accepted.
        #[test]
        fn accepted_means_one_chains_bits(
            steps in prop::collection::vec(1e-2_f64..1.0, MIN_ROWS..MIN_ROWS + 3000),
            wild in prop::collection::vec(1e-9_f64..1e9, 8),
            seed in 0.0_f64..10.0,
        ) {
            let mut h = steps.clone();
            // a few steps of any size, where the partitions may or may not meet
            let jumpy = seed > 5.0;
            if jumpy {
                for (k, w) in wild.iter().enumerate() {
                    let i = (k * 997 + 13) % h.len();
                    h[i] = *w;
                }
            }
            let (dl, d, du) = rows_of_steps(&h);
            let n = d.len();
            let rhs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.61 + seed).cos()).collect();
            let m = StoredBands { dl: &dl, d: &d, du: &du };
            let (mut x, mut recip) = (rhs.clone(), vec![0.0; n]);
            let accepted = solve_partitioned(&m, &mut x, &mut recip);
            prop_assert!(accepted || jumpy, "steps within a factor 100 refused");
            if accepted {
                let chain = one_chain(&m, &rhs);
                for (a, b) in x.iter().zip(&chain) {
                    prop_assert_eq!(a.to_bits(), b.to_bits());
                }
            }
        }
    }
}
