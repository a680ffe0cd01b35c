//! Tridiagonal systems by Gaussian elimination with partial pivoting, LAPACK's `dgtsv`
//! (Anderson et al., *LAPACK Users' Guide*, 3rd ed., 1999; the reference implementation's
//! operations in their order, so that a caller that builds SciPy's matrix gets the numbers of
//! SciPy's `solve_banded((1, 1), …)`, which calls `?gtsv`).
//!
//! [`solve_unpivoted`] is the elimination without row swaps for systems whose pivots are
//! positive (SciPy's `CubicSpline` system; its interior rows are diagonally dominant), with its
//! dependent chains cut short: the same solution to rounding, several times faster.
//!
//! Row `i` of the matrix is `dl[i−1]·s[i−1] + d[i]·s[i] + du[i]·s[i+1]`; the right-hand side is
//! `n` rows of `ncols` numbers, row-major, one factorisation for every column. The elimination
//! swaps rows `i` and `i + 1` when `|d[i]| < |dl[i]|`, which fills a second superdiagonal
//! (`du2`). O(n·ncols) time, no allocation beyond the caller's scratch.

use crate::error::{Error, Result};

/// The scratch of [`solve_tridiagonal`]: the second superdiagonal made by row swaps.
pub(crate) struct Tridiagonal<'a> {
    /// Subdiagonal, `n − 1` numbers (overwritten by the second superdiagonal's fill).
    pub(crate) dl: &'a mut [f64],
    /// Diagonal, `n` numbers (overwritten by `U`'s diagonal).
    pub(crate) d: &'a mut [f64],
    /// Superdiagonal, `n − 1` numbers (overwritten by `U`'s first superdiagonal).
    pub(crate) du: &'a mut [f64],
}

/// A tridiagonal matrix read entry by entry, for [`solve_unpivoted`]: stored bands
/// ([`StoredBands`]) or rows formed where they are read (SciPy's `CubicSpline` system from its
/// breakpoints, so that its three bands are never written out).
pub(crate) trait Bands {
    /// The order `n ≥ 1`.
    fn len(&self) -> usize;
    /// `d[i]`, `i < n`.
    fn diag(&self, i: usize) -> f64;
    /// `dl[i]`, the entry of row `i + 1` left of the diagonal, `i < n − 1`.
    fn lower(&self, i: usize) -> f64;
    /// `du[i]`, the entry of row `i` right of the diagonal, `i < n − 1`.
    fn upper(&self, i: usize) -> f64;
    /// Row `i` whole: `[dl[i − 1], d[i], du[i]]`, 0 for an entry beyond the matrix; a matrix
    /// whose rows are formed where they are read forms the three at once here.
    #[inline]
    fn row(&self, i: usize) -> [f64; 3] {
        let n = self.len();
        [
            if i > 0 { self.lower(i - 1) } else { 0.0 },
            self.diag(i),
            if i + 1 < n { self.upper(i) } else { 0.0 },
        ]
    }
}

/// Three stored bands (`dl`, `du` of `n − 1`, `d` of `n`) as [`Bands`].
pub(crate) struct StoredBands<'a> {
    /// Subdiagonal.
    pub(crate) dl: &'a [f64],
    /// Diagonal.
    pub(crate) d: &'a [f64],
    /// Superdiagonal.
    pub(crate) du: &'a [f64],
}

impl Bands for StoredBands<'_> {
    fn len(&self) -> usize {
        self.d.len()
    }
    #[inline]
    fn diag(&self, i: usize) -> f64 {
        self.d[i]
    }
    #[inline]
    fn lower(&self, i: usize) -> f64 {
        self.dl[i]
    }
    #[inline]
    fn upper(&self, i: usize) -> f64 {
        self.du[i]
    }
}

/// Solves `A·X = B` in place (`b`: `n` rows of `ncols`, overwritten by `X`) for the
/// tridiagonal `A` of `m`, destroying `m`: LAPACK `dgtsv`'s elimination with partial pivoting
/// and its back substitution, operation for operation (`n ≥ 1`; `dl`, `du` of `n − 1`).
///
/// # Errors
/// [`Error::SingularSystem`] when a pivot is exactly zero (LAPACK's `INFO > 0`, SciPy's
/// `LinAlgError("singular matrix")`).
pub(crate) fn solve_tridiagonal(m: Tridiagonal<'_>, b: &mut [f64], ncols: usize) -> Result<()> {
    let Tridiagonal { dl, d, du } = m;
    let n = d.len();
    debug_assert!(dl.len() + 1 == n && du.len() + 1 == n, "band lengths");
    debug_assert!(b.len() == n * ncols, "right-hand side length");
    let singular = |row: usize| Error::SingularSystem {
        reason: format!("pivot {row} of the tridiagonal system is zero"),
    };
    for i in 0..n.saturating_sub(1) {
        let last = i + 2 == n;
        if d[i].abs() >= dl[i].abs() {
            // no row interchange
            if d[i] == 0.0 {
                return Err(singular(i));
            }
            let fact = dl[i] / d[i];
            d[i + 1] -= fact * du[i];
            let (top, bottom) = b[i * ncols..(i + 2) * ncols].split_at_mut(ncols);
            for (lo, hi) in bottom.iter_mut().zip(top.iter()) {
                *lo -= fact * hi;
            }
            if !last {
                dl[i] = 0.0;
            }
        } else {
            // interchange rows i and i + 1
            let fact = d[i] / dl[i];
            d[i] = dl[i];
            let temp = d[i + 1];
            d[i + 1] = du[i] - fact * temp;
            if !last {
                dl[i] = du[i + 1];
                du[i + 1] = -fact * dl[i];
            }
            du[i] = temp;
            let (top, bottom) = b[i * ncols..(i + 2) * ncols].split_at_mut(ncols);
            for (hi, lo) in top.iter_mut().zip(bottom.iter_mut()) {
                let temp = *hi;
                *hi = *lo;
                *lo = temp - fact * *lo;
            }
        }
    }
    if d[n - 1] == 0.0 {
        return Err(singular(n - 1));
    }
    // back substitution with U (diagonal d, superdiagonals du and dl's fill)
    for j in 0..ncols {
        b[(n - 1) * ncols + j] /= d[n - 1];
    }
    if n > 1 {
        let i = n - 2;
        for j in 0..ncols {
            b[i * ncols + j] = (b[i * ncols + j] - du[i] * b[(i + 1) * ncols + j]) / d[i];
        }
    }
    for i in (0..n.saturating_sub(2)).rev() {
        let (row, below) = b[i * ncols..(i + 3) * ncols].split_at_mut(ncols);
        let (next, after) = below.split_at(ncols);
        for j in 0..ncols {
            row[j] = (row[j] - du[i] * next[j] - dl[i] * after[j]) / d[i];
        }
    }
    Ok(())
}

/// 2^500: the size of a minor beyond which it is brought back by this exact power of two.
const BIG: f64 = f64::from_bits((1023 + 500) << 52);

/// 2^−500, the reciprocal of [`BIG`].
const SMALL: f64 = f64::from_bits((1023 - 500) << 52);

/// The next minor of an elimination, `μ' = d·μ − c·μ₋` (the determinant of one more row and
/// column, expanded along the new row: its diagonal `d`, the product `c` of the two entries
/// that couple it to the previous row), and `μ`, both rescaled together by 2^∓500 (exact) when
/// `μ'` leaves [2^−500, 2^500]: their ratio, the new pivot, is unchanged, and one that still
/// overflows gives an infinite pivot, which the callers refuse. A multiplication and a
/// subtraction on the chain from row to row, where the pivot recurrence `p' = d − c/p` takes
/// a division.
#[inline(always)]
pub(crate) fn next_minor(d: f64, c: f64, minor: f64, prev: f64) -> (f64, f64) {
    let (mut next, mut minor) = (d * minor - c * prev, minor);
    let size = next.abs();
    if size > BIG {
        next *= SMALL;
        minor *= SMALL;
    } else if size < SMALL && size != 0.0 {
        next *= BIG;
        minor *= BIG;
    }
    (next, minor)
}

/// Solves `A·X = B` in place (`b`: `n` rows of `ncols`) by Gaussian elimination without row
/// swaps, when every pivot `p_i` is positive and finite; returns `false`, `b` untouched, when
/// one is not (the caller then pivots: [`solve_tridiagonal`]). The pivots are the ratios
/// `p_i = q_i / q_{i−1}` of the leading principal minors, `q_{i+1} = d_{i+1} q_i − dl_i du_i q_{i−1}`
/// (`q_{−1} = 1`; the determinant of the leading `i + 2` rows and columns expanded along its
/// last row), rescaled by powers of two as they grow (exact), so that the chain from one row to
/// the next is one multiplication and one subtraction instead of a division; the reciprocals
/// `1/p_i` are then formed in a vectorised pass, and the forward and back substitutions multiply
/// by them. For a matrix whose rows are diagonally dominant (as the interior of SciPy's
/// `CubicSpline` system, `2(h_{i−1} + h_i) > h_{i−1} + h_i`) elimination without pivoting is
/// backward stable (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., ch. 9,
/// tridiagonal matrices):
/// the solution of [`solve_tridiagonal`] to rounding. O(n·ncols); `recip` is `n` numbers of
/// scratch.
pub(crate) fn solve_unpivoted(
    m: &impl Bands,
    b: &mut [f64],
    ncols: usize,
    recip: &mut [f64],
) -> bool {
    let n = m.len();
    debug_assert!(
        b.len() == n * ncols && recip.len() == n,
        "right-hand side length"
    );
    let (dl, d, du) = (|i| m.lower(i), |i| m.diag(i), |i| m.upper(i));
    // the pivots, into recip
    let (mut q_prev, mut q) = (1.0_f64, d(0));
    recip[0] = q;
    for i in 0..n - 1 {
        let next;
        (next, q) = next_minor(d(i + 1), dl(i) * du(i), q, q_prev);
        recip[i + 1] = next / q;
        q_prev = q;
        q = next;
    }
    // every pivot positive and finite (false for NaN)
    if !recip.iter().all(|&p| p > 0.0 && p < f64::INFINITY) {
        return false;
    }
    for r in recip.iter_mut() {
        *r = 1.0 / *r;
    }
    if ncols == 1 {
        for i in 0..n - 1 {
            b[i + 1] -= (dl(i) * recip[i]) * b[i];
        }
        // x_i = b_i/p_i − (u_i/p_i)·x_{i+1}: one multiplication and one subtraction a row on
        // the chain from x_{i+1} to x_i
        b[n - 1] *= recip[n - 1];
        for i in (0..n - 1).rev() {
            b[i] = b[i] * recip[i] - (du(i) * recip[i]) * b[i + 1];
        }
        return true;
    }
    for i in 0..n - 1 {
        let f = dl(i) * recip[i];
        let (top, bottom) = b[i * ncols..(i + 2) * ncols].split_at_mut(ncols);
        for (lo, hi) in bottom.iter_mut().zip(top.iter()) {
            *lo -= f * hi;
        }
    }
    for v in &mut b[(n - 1) * ncols..] {
        *v *= recip[n - 1];
    }
    for i in (0..n - 1).rev() {
        let (row, next) = b[i * ncols..(i + 2) * ncols].split_at_mut(ncols);
        let g = du(i) * recip[i];
        for (v, w) in row.iter_mut().zip(next.iter()) {
            *v = *v * recip[i] - g * w;
        }
    }
    true
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The solution of one column by LAPACK `dgtsv`'s elimination with row swaps.
    pub(crate) fn pivoted(dl: &[f64], d: &[f64], du: &[f64], rhs: &[f64]) -> Vec<f64> {
        let (mut l, mut m, mut u, mut x) = (dl.to_vec(), d.to_vec(), du.to_vec(), rhs.to_vec());
        let t = Tridiagonal {
            dl: &mut l,
            d: &mut m,
            du: &mut u,
        };
        solve_tridiagonal(t, &mut x, 1).unwrap();
        x
    }

    /// SciPy's `CubicSpline` rows `(dl, d, du)` on `n` uneven steps, some 100× the others (where
    /// `dgtsv` swaps rows): not-a-knot ends from four points, natural ends below (the
    /// not-a-knot rows of three points are singular: SciPy solves that case as the parabola
    /// through them).
    pub(crate) fn spline_rows(n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let h: Vec<f64> = (0..n - 1)
            .map(|i| {
                if i % 17 == 3 {
                    40.0
                } else {
                    0.1 + (i % 5) as f64 * 0.3
                }
            })
            .collect();
        let mut d = vec![1.0; n];
        let (mut dl, mut du) = (vec![0.0; n - 1], vec![0.0; n - 1]);
        for i in 1..n - 1 {
            d[i] = 2.0 * (h[i - 1] + h[i]);
            du[i] = h[i - 1];
            dl[i - 1] = h[i];
        }
        if n >= 4 {
            (d[0], du[0]) = (h[1], h[0] + h[1]);
            (d[n - 1], dl[n - 2]) = (h[n - 3], h[n - 3] + h[n - 2]);
        } else {
            (d[0], du[0]) = (2.0 * h[0], h[0]);
            (d[n - 1], dl[n - 2]) = (2.0 * h[n - 2], h[n - 2]);
        }
        (dl, d, du)
    }

    /// `A·x` for the tridiagonal `A` (one column).
    fn apply(dl: &[f64], d: &[f64], du: &[f64], x: &[f64]) -> Vec<f64> {
        (0..d.len())
            .map(|i| {
                let mut s = d[i] * x[i];
                if i > 0 {
                    s += dl[i - 1] * x[i - 1];
                }
                if i + 1 < d.len() {
                    s += du[i] * x[i + 1];
                }
                s
            })
            .collect()
    }

    #[test]
    fn solves_with_and_without_row_swaps() {
        // small diagonal entries force interchanges; residual at rounding
        let dl = [5.0, 0.1, 7.0, 2.0];
        let d = [1.0, 0.5, 3.0, 0.25, 4.0];
        let du = [2.0, 6.0, 0.3, 1.0];
        let x = [1.0, -2.0, 0.5, 3.0, -1.5];
        let rhs = apply(&dl, &d, &du, &x);
        let (mut l, mut m, mut u) = (dl, d, du);
        let mut b = rhs.clone();
        solve_tridiagonal(
            Tridiagonal {
                dl: &mut l,
                d: &mut m,
                du: &mut u,
            },
            &mut b,
            1,
        )
        .unwrap();
        for (got, want) in b.iter().zip(&x) {
            assert!((got - want).abs() < 1e-13, "{got} vs {want}");
        }
    }

    #[test]
    fn columns_are_solved_as_one_column_each() {
        let dl = [1.0, 4.0, 1.0];
        let d = [0.5, 2.0, 1.0, 3.0];
        let du = [1.0, 1.0, 0.2];
        let cols = [[1.0, 2.0, 3.0, 4.0], [-1.0, 0.5, 0.25, 8.0]];
        let mut both: Vec<f64> = (0..4).flat_map(|i| [cols[0][i], cols[1][i]]).collect();
        let (mut l, mut m, mut u) = (dl, d, du);
        let m2 = Tridiagonal {
            dl: &mut l,
            d: &mut m,
            du: &mut u,
        };
        solve_tridiagonal(m2, &mut both, 2).unwrap();
        for (c, col) in cols.iter().enumerate() {
            let (mut l, mut m, mut u) = (dl, d, du);
            let mut one = col.to_vec();
            let m1 = Tridiagonal {
                dl: &mut l,
                d: &mut m,
                du: &mut u,
            };
            solve_tridiagonal(m1, &mut one, 1).unwrap();
            for i in 0..4 {
                assert_eq!(
                    both[2 * i + c].to_bits(),
                    one[i].to_bits(),
                    "row {i} column {c}"
                );
            }
        }
    }

    #[test]
    fn without_pivoting_the_same_solution_to_rounding() {
        // SciPy's CubicSpline rows on uneven steps: the pivots positive, gtsv swapping rows
        let n = 300;
        let (dl, d, du) = spline_rows(n);
        for ncols in [1, 3] {
            let rhs: Vec<f64> = (0..n * ncols).map(|i| (i as f64 * 0.37).sin()).collect();
            let (mut fast, mut recip) = (rhs.clone(), vec![0.0; n]);
            assert!(
                solve_unpivoted(
                    &StoredBands {
                        dl: &dl,
                        d: &d,
                        du: &du
                    },
                    &mut fast,
                    ncols,
                    &mut recip
                ),
                "positive pivots"
            );
            let (mut l, mut m, mut u, mut slow) = (dl.clone(), d.clone(), du.clone(), rhs.clone());
            let t = Tridiagonal {
                dl: &mut l,
                d: &mut m,
                du: &mut u,
            };
            solve_tridiagonal(t, &mut slow, ncols).unwrap();
            let scale = slow.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            for (a, b) in fast.iter().zip(&slow) {
                assert!((a - b).abs() <= 1e-14 * scale, "{a} vs {b}");
            }
        }
        // a zero or negative pivot: refused, the right-hand side untouched
        let mut b = [1.0, 2.0];
        assert!(
            !solve_unpivoted(
                &StoredBands {
                    dl: &[1.0],
                    d: &[0.0, 1.0],
                    du: &[1.0]
                },
                &mut b,
                1,
                &mut [0.0; 2]
            ),
            "zero"
        );
        assert!(
            !solve_unpivoted(
                &StoredBands {
                    dl: &[2.0],
                    d: &[1.0, 1.0],
                    du: &[1.0]
                },
                &mut b,
                1,
                &mut [0.0; 2]
            ),
            "negative"
        );
        assert_eq!(b, [1.0, 2.0], "untouched");
    }

    #[test]
    fn a_zero_pivot_is_a_singular_system() {
        let (mut l, mut m, mut u) = ([0.0], [0.0, 1.0], [1.0]);
        let mut b = [1.0, 1.0];
        let e = solve_tridiagonal(
            Tridiagonal {
                dl: &mut l,
                d: &mut m,
                du: &mut u,
            },
            &mut b,
            1,
        )
        .unwrap_err();
        assert!(matches!(e, Error::SingularSystem { .. }), "{e}");
    }
}
