//! The rows of an active face that the polish keeps (crate-private;
//! `docs/theory/fitting.md#shape-constraints`): duplicates dropped, then, on a degenerate face,
//! only the rows independent of those kept before them.
//!
//! Every row of a shape constraint touches at most `p + 1` consecutive coefficients, so both
//! steps work along the band: a duplicate can only be a kept row whose columns cover the new
//! row's largest entry, and independence is decided by rotating the row into the banded
//! triangle of the rows kept so far (row-wise Givens QR, George & Heath, *Solution of sparse
//! linear least squares problems using Givens rotations*, Linear Algebra Appl. 34, 1980; rank
//! by the vanishing of the rotated row, Heath, SIAM J. Sci. Stat. Comput. 3, 1982). A row costs
//! O(w) per column it travels before it is placed or vanishes, `w` its width, instead of
//! O(rows kept · n) for Gram–Schmidt on dense vectors. Hand-written: the triangle must take rows
//! in the face's order (earlier rows take precedence) and report each row's fate as it
//! arrives, which a sparse QR of a whole matrix (`faer`) does not.

use super::row::Row;
use crate::error::Result;
use crate::fit::progress::Steps;

/// Entry difference (rows scaled to unit largest coefficient) below which two rows count as the
/// same function.
const SAME_ATOL: f64 = 1e-10;

/// Largest entry (rows scaled to unit largest coefficient) below which a row is compared with
/// every kept row for duplicates instead of those covering its largest entry.
const SMALL_ROW: f64 = 1e-9;

/// Share of a row's length below which what remains of it, once rotated against the rows kept
/// before it, counts as zero (the row depends on them); an entry below it that meets an empty
/// column of the triangle is a rounding remnant and is dropped.
const DEPENDENT_RTOL: f64 = 1e-9;

/// Whether two rows (scaled to unit largest coefficient) are the same function to rounding,
/// whatever their first columns.
pub(super) fn same_row(a: &Row, b: &Row) -> bool {
    let lo = a.first.min(b.first);
    let hi = (a.first + a.coef.len()).max(b.first + b.coef.len());
    let at = |r: &Row, j: usize| {
        j.checked_sub(r.first)
            .and_then(|i| r.coef.get(i))
            .copied()
            .unwrap_or(0.0)
    };
    (lo..hi).all(|j| (at(a, j) - at(b, j)).abs() <= SAME_ATOL)
        && (a.constant - b.constant).abs() <= SAME_ATOL
}

/// The rows, in order, that are not the same (as [`same_row`]) as a row kept before them, for
/// `n` coefficients. A row whose largest entry `|a_j|` exceeds [`SMALL_ROW`] can only equal a
/// row with a non-zero entry in column `j`, so it is compared with the kept rows starting at
/// most `w − 1` columns before `j` (`w` the widest row of at most `band` columns): O(rows · w²)
/// on a band, with the same answer as comparing every pair. Rows wider than `band` (an
/// integral, periodicity: few, from the user's equalities) are compared with every kept row.
pub(super) fn distinct<T>(rows: Vec<(Row, bool, T)>, n: usize, band: usize) -> Vec<(Row, bool, T)> {
    let w = rows
        .iter()
        .map(|(r, _, _)| r.coef.len())
        .filter(|&l| l <= band)
        .max()
        .unwrap_or(0);
    let mut kept: Vec<(Row, bool, T)> = Vec::with_capacity(rows.len());
    // kept rows by first column (indices into `kept`)
    let mut by_first: Vec<Vec<usize>> = vec![Vec::new(); n + 1];
    // kept rows wider than the band (indices into `kept`)
    let mut wide: Vec<usize> = Vec::new();
    for item in rows {
        let r = &item.0;
        let largest = r.coef.iter().enumerate().fold((0, 0.0_f64), |m, (i, v)| {
            if v.abs() > m.1 {
                (i, v.abs())
            } else {
                m
            }
        });
        let seen = if largest.1 > SMALL_ROW && r.aux.is_none() && r.coef.len() <= band {
            let j = r.first + largest.0;
            (j.saturating_sub(w.saturating_sub(1))..=j.min(n))
                .flat_map(|f| &by_first[f])
                .any(|&k| same_row(&kept[k].0, r))
                || wide.iter().any(|&k| same_row(&kept[k].0, r))
        } else {
            kept.iter().any(|(k, _, _)| same_row(k, r))
        };
        if !seen {
            if r.coef.len() > band {
                wide.push(kept.len());
            }
            by_first[r.first.min(n)].push(kept.len());
            kept.push(item);
        }
    }
    kept
}

/// The banded upper triangle `R` of the rows kept so far (row-wise Givens QR): its rows span
/// the same space as theirs; row `i`, when filled, has its first non-zero in column `i` and at
/// most `w` non-zeros.
struct RowTriangle {
    n: usize,
    w: usize,
    /// `r[i·w + k] = R[i][i + k]`.
    r: Vec<f64>,
    filled: Vec<bool>,
    /// The row being rotated in: `x[k]` is its entry in column `column + k`.
    x: Vec<f64>,
}

impl RowTriangle {
    fn new(n: usize, w: usize) -> Self {
        RowTriangle {
            n,
            w,
            r: vec![0.0; n * w],
            filled: vec![false; n],
            x: vec![0.0; w],
        }
    }

    /// Rotates `coef` (columns `first ..`, at most `w` of them) into the triangle; whether it
    /// was independent of the rows before it (then it fills an empty row of the triangle).
    /// Each Givens rotation with the row of the triangle at the current leading column zeroes
    /// that entry and moves the window one column on; the rotations are orthogonal, so the rows
    /// of the triangle and the remainder span the rows given, and the row depends on the rows
    /// before it when the remainder vanishes (below [`DEPENDENT_RTOL`] of its length).
    fn insert(&mut self, first: usize, coef: &[f64]) -> bool {
        let (n, w) = (self.n, self.w);
        let norm = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>().sqrt();
        let length = norm(coef);
        let floor = DEPENDENT_RTOL * length;
        if length == 0.0 || !length.is_finite() {
            return false;
        }
        let x = &mut self.x;
        x.fill(0.0);
        x[..coef.len()].copy_from_slice(coef);
        for column in first..n {
            let a = x[0];
            if a != 0.0 {
                let row = &mut self.r[column * w..(column + 1) * w];
                if self.filled[column] {
                    // FITPACK fpgivs/fprota: d = √(r² + a²), cos = r/d, sin = a/d
                    let d = (row[0] * row[0] + a * a).sqrt();
                    let (c, s) = (row[0] / d, a / d);
                    row[0] = d;
                    for (rk, xk) in row[1..].iter_mut().zip(x[1..].iter_mut()) {
                        let (rb, xa) = (*rk, *xk);
                        *rk = c * rb + s * xa;
                        *xk = c * xa - s * rb;
                    }
                } else if a.abs() > floor {
                    row.copy_from_slice(x);
                    self.filled[column] = true;
                    return true;
                }
                x[0] = 0.0;
                if norm(x) <= floor {
                    return false;
                }
            }
            x.rotate_left(1);
            x[w - 1] = 0.0;
        }
        false
    }
}

/// The rows, in order, that do not depend linearly on the rows kept before them, for `n`
/// coefficients: each is rotated into the banded triangle of those kept ([`RowTriangle`]), a
/// remainder below [`DEPENDENT_RTOL`] of its length counting as zero. On a consistent face
/// (every row zero at a point) the dropped rows are zero wherever the kept ones are, so the
/// face is the same and its equality-constrained optimum too. At most `n` rows remain; rows
/// with an auxiliary variable, and rows wider than `band` (an integral, periodicity: the user's
/// equalities, which a triangle of their width would make dense), are kept as they are. O(w)
/// per column a row travels; `steps`
/// ticks before each row, so that a cancelled hook stops a face of thousands of rows
/// ([`crate::Error::Cancelled`]).
pub(super) fn independent<T>(
    rows: Vec<(Row, bool, T)>,
    n: usize,
    band: usize,
    steps: &Steps<'_, '_>,
) -> Result<Vec<(Row, bool, T)>> {
    let w = rows
        .iter()
        .filter(|(r, _, _)| r.aux.is_none())
        .map(|(r, _, _)| r.coef.len())
        .filter(|&l| l <= band)
        .max()
        .unwrap_or(0);
    let mut triangle = RowTriangle::new(n, w.max(1));
    let mut rank = 0;
    let mut out = Vec::with_capacity(n.min(rows.len()));
    for item in rows {
        steps.tick()?;
        let r = &item.0;
        if r.aux.is_some() || r.coef.len() > band {
            out.push(item);
            continue;
        }
        if rank >= n {
            continue;
        }
        if triangle.insert(r.first, &r.coef) {
            rank += 1;
            out.push(item);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::progress::Progress;

    fn row(first: usize, coef: &[f64]) -> (Row, bool, ()) {
        (
            Row {
                first,
                coef: coef.to_vec(),
                aux: None,
                constant: 0.0,
            },
            true,
            (),
        )
    }

    /// Modified Gram–Schmidt on dense vectors (Golub & Van Loan §5.2.8): the reference the
    /// banded triangle must agree with.
    fn independent_by_gram_schmidt(rows: &[(Row, bool, ())], n: usize) -> Vec<usize> {
        let mut basis: Vec<Vec<f64>> = Vec::new();
        let mut out = Vec::new();
        for (i, (r, _, _)) in rows.iter().enumerate() {
            let mut v = vec![0.0; n];
            v[r.first..r.first + r.coef.len()].copy_from_slice(&r.coef);
            let length = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            for b in &basis {
                let d: f64 = b.iter().zip(&v).map(|(x, y)| x * y).sum();
                v.iter_mut().zip(b).for_each(|(y, x)| *y -= d * x);
            }
            let rest = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if rest > DEPENDENT_RTOL * length {
                v.iter_mut().for_each(|x| *x /= rest);
                basis.push(v);
                out.push(i);
            }
        }
        out
    }

    fn kept(rows: Vec<(Row, bool, ())>, n: usize) -> Vec<usize> {
        let tagged: Vec<(Row, bool, usize)> = rows
            .into_iter()
            .enumerate()
            .map(|(i, (r, b, ()))| (r, b, i))
            .collect();
        let progress = Progress::new();
        independent(tagged, n, usize::MAX, &Steps::new(&progress, "test"))
            .unwrap()
            .into_iter()
            .map(|(_, _, i)| i)
            .collect()
    }

    #[test]
    fn a_flat_stretch_keeps_as_many_rows_as_coefficients() {
        // value, slope and curvature rows of the pieces of a flat stretch of 12 coefficients
        // (a constant cubic): each piece's rows are combinations of differences of its four
        // coefficients, so the face has 11 independent rows among 27 (the constant is free)
        let n = 12;
        let mut rows = Vec::new();
        for f in 0..n - 3 {
            rows.push(row(f, &[-1.0, 1.0, 0.0, 0.0]));
            rows.push(row(f, &[1.0, -2.0, 1.0, 0.0]));
            rows.push(row(f, &[0.0, 0.0, -1.0, 1.0]));
        }
        let by_triangle = kept(rows.clone(), n);
        assert_eq!(
            by_triangle,
            independent_by_gram_schmidt(&rows, n),
            "same rows kept"
        );
        assert_eq!(by_triangle.len(), n - 1, "rank of the differences");
    }

    #[test]
    fn rows_out_of_column_order_agree_with_gram_schmidt() {
        // rows arriving right to left and then left to right, with a late row that travels
        // along a filled stretch before it finds an empty column
        let n = 30;
        let mut rows = Vec::new();
        for f in (0..n - 3).rev().step_by(2) {
            rows.push(row(f, &[1.0, -3.0, 3.0, -1.0]));
        }
        for f in 0..n - 3 {
            rows.push(row(f, &[0.5, 1.0, -0.25, 2.0]));
            rows.push(row(f, &[1.0, -3.0, 3.0, -1.0]));
        }
        rows.push(row(0, &[1.0, 1.0, 1.0, 1.0]));
        let by_triangle = kept(rows.clone(), n);
        assert_eq!(
            by_triangle,
            independent_by_gram_schmidt(&rows, n),
            "same rows kept"
        );
        assert_eq!(by_triangle.len(), n, "full rank");
    }

    #[test]
    fn a_row_dependent_to_rounding_is_dropped() {
        let n = 6;
        let a = [0.3, -1.0, 0.7, 0.1];
        let b = [1.0, 0.2, -0.4, 0.9];
        // a + b shifted by one column is independent; 0.1·a + 0.3·b (with a rounding remnant
        // below the resolution) is not
        let mix: Vec<f64> = a
            .iter()
            .zip(&b)
            .map(|(x, y)| 0.1 * x + 0.3 * y + 1e-13)
            .collect();
        let rows = vec![
            row(1, &a),
            row(1, &b),
            row(2, &[1.0, 1.0, 0.5, 0.25]),
            row(1, &mix),
        ];
        assert_eq!(kept(rows.clone(), n), vec![0, 1, 2], "the mixture depends");
        assert_eq!(
            independent_by_gram_schmidt(&rows, n),
            vec![0, 1, 2],
            "reference"
        );
    }

    #[test]
    fn duplicates_are_found_near_their_largest_entry() {
        let n = 10;
        let rows = vec![
            row(2, &[0.0, 1.0, -0.5, 0.0]),
            // the same function, starting two columns earlier
            row(1, &[0.0, 0.0, 1.0, -0.5]),
            row(3, &[1.0, -0.5, 0.0, 0.0]),
            // a different constant
            (
                Row {
                    first: 3,
                    coef: vec![1.0, -0.5],
                    aux: None,
                    constant: 1.0,
                },
                true,
                (),
            ),
            row(5, &[1.0, -0.5, 0.0, 0.0]),
        ];
        let firsts: Vec<usize> = distinct(rows, n, usize::MAX)
            .iter()
            .map(|(r, _, _)| r.first)
            .collect();
        assert_eq!(
            firsts,
            vec![2, 3, 5],
            "two duplicates of the first row dropped"
        );
    }
}
