//! The matrices of document 004 (Nikulin 2011; docs/theory/degree.md#order-change-matrices) in
//! exact rational arithmetic.
//!
//! The paper writes a Bezier curve of degree `n` as `p(t) = U_n B_n(t) = S_n T_n(t) =
//! U_n H_n T_n(t)` (eq. 1–5): `U_n` holds the control points as *columns*, `B_n(t)` the Bernstein
//! polynomials, `T_n(t) = [1 t … t^n]ᵀ` the powers and `S_n` the monomial coefficients. Every
//! matrix here is indexed like the paper, row `i`, column `j`, both from 0:
//!
//! | function | matrix | size | entries |
//! |---|---|---|---|
//! | [`bernstein_monomial_matrix`] | `H_n` | `(n+1)×(n+1)` | `(−1)^(j−i) C(n,j) C(j,i)`, `i ≤ j` (eq. 4) |
//! | [`bernstein_monomial_matrix_inverse`] | `H_n^{-1}` | `(n+1)×(n+1)` | `C(j,i) / C(n,i)`, `i ≤ j` |
//! | [`truncation_matrix`] | `E_{M,N}` | `M×N` | ones on the main diagonal |
//! | [`elevation_block`] | `K_{n,n'} = E_{n+1,n'+1} H_{n'}^{-1}` | `(n+1)×(n'+1)` | eq. 7–8 |
//! | [`reduction_block`] | `G_{n,n'} = H_n E_{n+1,n'+1}` | `(n+1)×(n'+1)` | eq. 9 |
//! | [`order_change_matrix`] | `H_n E_{n+1,n'+1} H_{n'}^{-1}` | `(n+1)×(n'+1)` | eq. 10 |
//!
//! The new control points are `U' = U M` for `M = order_change_matrix(n, n')`, that is
//! `u'_j = Σ_i m_ij u_i`. The entries are exact rationals ([`BigRational`]), so the matrices of
//! the paper's Examples 1 and 2 are reproduced digit for digit. The cost is O(n³) rational
//! operations, so degrees are limited to [`MAX_EXACT_MATRIX_DEGREE`]; the floating-point
//! operations on curves use the stable Bernstein-domain kernels of `bezier_degree` instead.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

use crate::error::{Error, Result};

/// Largest degree for which the exact rational matrices are built (their cost is O(n³)
/// rational operations on integers of O(n) digits).
pub const MAX_EXACT_MATRIX_DEGREE: usize = 128;

/// A dense matrix of exact rationals, stored row by row.
///
/// ```
/// use lekalo::bernstein_monomial_matrix;
/// let h2 = bernstein_monomial_matrix(2)?;
/// assert_eq!((h2.rows(), h2.cols()), (3, 3));
/// // document 004, Example 1: H_2 = [[1, −2, 1], [0, 2, −2], [0, 0, 1]]
/// assert_eq!(h2.to_f64(), vec![1.0, -2.0, 1.0, 0.0, 2.0, -2.0, 0.0, 0.0, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RationalMatrix {
    rows: usize,
    cols: usize,
    entries: Vec<BigRational>,
}

impl RationalMatrix {
    /// The `rows × cols` zero matrix.
    ///
    /// # Errors
    /// [`Error::TooLarge`] if `rows · cols` overflows or exceeds `MAX_EXACT_MATRIX_DEGREE + 1`
    /// squared times 4 entries.
    pub fn zeros(rows: usize, cols: usize) -> Result<Self> {
        let max = 4 * (MAX_EXACT_MATRIX_DEGREE + 1) * (MAX_EXACT_MATRIX_DEGREE + 1);
        let size = rows.saturating_mul(cols);
        if size > max {
            return Err(Error::TooLarge {
                what: "exact rational matrix (entries)".into(),
                size,
                max,
            });
        }
        Ok(Self::zeros_unchecked(rows, cols))
    }

    fn zeros_unchecked(rows: usize, cols: usize) -> Self {
        RationalMatrix {
            rows,
            cols,
            entries: vec![BigRational::zero(); rows * cols],
        }
    }

    /// A matrix of integers given row by row.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `values.len() != rows · cols`; [`Error::TooLarge`] as
    /// [`RationalMatrix::zeros`].
    pub fn from_integers(rows: usize, cols: usize, values: &[i64]) -> Result<Self> {
        let mut m = Self::zeros(rows, cols)?;
        if values.len() != rows * cols {
            return Err(Error::LengthMismatch {
                what: "matrix entries (rows × cols)".into(),
                expected: rows * cols,
                got: values.len(),
            });
        }
        for (e, &v) in m.entries.iter_mut().zip(values) {
            *e = BigRational::from_integer(BigInt::from(v));
        }
        Ok(m)
    }

    /// Number of rows.
    #[must_use]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns.
    #[must_use]
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Entry `(i, j)`, or `None` outside the matrix.
    #[must_use]
    pub fn get(&self, i: usize, j: usize) -> Option<&BigRational> {
        (i < self.rows && j < self.cols).then(|| &self.entries[i * self.cols + j])
    }

    fn at(&self, i: usize, j: usize) -> &BigRational {
        &self.entries[i * self.cols + j]
    }

    fn set(&mut self, i: usize, j: usize, v: BigRational) {
        self.entries[i * self.cols + j] = v;
    }

    /// The entries rounded to the nearest `f64`, row by row.
    #[must_use]
    pub fn to_f64(&self) -> Vec<f64> {
        self.entries
            .iter()
            .map(|e| e.to_f64().unwrap_or(f64::NAN))
            .collect()
    }

    /// The transpose.
    #[must_use]
    pub fn transpose(&self) -> Self {
        let mut t = Self::zeros_unchecked(self.cols, self.rows);
        for i in 0..self.rows {
            for j in 0..self.cols {
                t.set(j, i, self.at(i, j).clone());
            }
        }
        t
    }

    /// The exact product `self · rhs` (zero entries are skipped, so triangular factors cost
    /// about a sixth of the dense O(r·k·c)).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `self.cols() != rhs.rows()`.
    pub fn mul(&self, rhs: &RationalMatrix) -> Result<Self> {
        if self.cols != rhs.rows {
            return Err(Error::LengthMismatch {
                what: "matrix product (rows of the right factor = columns of the left)".into(),
                expected: self.cols,
                got: rhs.rows,
            });
        }
        let mut out = Self::zeros(self.rows, rhs.cols)?;
        for i in 0..self.rows {
            for k in 0..self.cols {
                let a = self.at(i, k);
                if a.is_zero() {
                    continue;
                }
                for j in 0..rhs.cols {
                    let b = rhs.at(k, j);
                    if !b.is_zero() {
                        let idx = i * out.cols + j;
                        out.entries[idx] += a * b;
                    }
                }
            }
        }
        Ok(out)
    }

    /// `U · M` for points `U` given as the columns of the paper (flat point-major `points` of
    /// dimension `dim`, one point per row of `self`), in exact arithmetic. Returns the new points,
    /// one per column of `self`, flat and point-major.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] if `points.len() != self.rows() · dim`; [`Error::Dimension`] if
    /// `dim == 0`.
    pub fn apply_to_points(&self, points: &[BigRational], dim: usize) -> Result<Vec<BigRational>> {
        if dim == 0 {
            return Err(Error::Dimension {
                what: "points".into(),
                expected: 1,
                got: 0,
            });
        }
        if points.len() != self.rows * dim {
            return Err(Error::LengthMismatch {
                what: "point coordinates (matrix rows × dimension)".into(),
                expected: self.rows * dim,
                got: points.len(),
            });
        }
        let mut out = vec![BigRational::zero(); self.cols * dim];
        for i in 0..self.rows {
            for j in 0..self.cols {
                let m = self.at(i, j);
                if m.is_zero() {
                    continue;
                }
                for k in 0..dim {
                    out[j * dim + k] += m * &points[i * dim + k];
                }
            }
        }
        Ok(out)
    }
}

fn check_exact_degree(degree: usize) -> Result<()> {
    if degree > MAX_EXACT_MATRIX_DEGREE {
        return Err(Error::Degree {
            degree,
            reason: format!(
                "exact rational matrices are built up to degree {MAX_EXACT_MATRIX_DEGREE}; use \
                 BezierCurve::change_degree (stable floating-point kernels) for higher degrees"
            ),
        });
    }
    Ok(())
}

/// Pascal's triangle rows `0..=n` as exact integers: `table[a][b] = C(a, b)`.
fn pascal(n: usize) -> Vec<Vec<BigInt>> {
    let mut table: Vec<Vec<BigInt>> = Vec::with_capacity(n + 1);
    for a in 0..=n {
        let mut row = vec![BigInt::from(1); a + 1];
        for b in 1..a {
            row[b] = &table[a - 1][b - 1] + &table[a - 1][b];
        }
        table.push(row);
    }
    table
}

/// `H_n`, the matrix with `B_n(t) = H_n T_n(t)` and `S_n = U_n H_n` (document 004 eq. 4–5):
/// upper triangular, `h_ij = (−1)^(j−i) C(n,j) C(j,i)` for `i ≤ j`. Column `j` of `U_n H_n` is
/// `C(n,j) Δ^j u_0`, the j-th forward difference of the control points.
///
/// ```
/// use lekalo::bernstein_monomial_matrix;
/// // document 004, Example 1: H_3
/// let h3 = bernstein_monomial_matrix(3)?;
/// let expect = [1., -3., 3., -1., 0., 3., -6., 3., 0., 0., 3., -3., 0., 0., 0., 1.];
/// assert_eq!(h3.to_f64(), expect.to_vec());
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`] above [`MAX_EXACT_MATRIX_DEGREE`].
pub fn bernstein_monomial_matrix(n: usize) -> Result<RationalMatrix> {
    check_exact_degree(n)?;
    let c = pascal(n);
    let mut h = RationalMatrix::zeros_unchecked(n + 1, n + 1);
    for j in 0..=n {
        for i in 0..=j {
            let mut v = &c[n][j] * &c[j][i];
            if (j - i) % 2 == 1 {
                v = -v;
            }
            h.set(i, j, BigRational::from_integer(v));
        }
    }
    Ok(h)
}

/// `H_n^{-1}` in closed form, `(H_n^{-1})_ij = C(j,i) / C(n,i)` for `i ≤ j` and 0 otherwise
/// (docs/theory/degree.md#three-forms-of-a-bezier-curve; it is the standard monomial-to-Bernstein
/// matrix, Farin, *Curves and Surfaces for CAGD*, §5.4). Row 0 and the last column are all ones.
///
/// ```
/// use lekalo::{bernstein_monomial_matrix, bernstein_monomial_matrix_inverse};
/// let h = bernstein_monomial_matrix(5)?;
/// let hi = bernstein_monomial_matrix_inverse(5)?;
/// let id = h.mul(&hi)?;
/// for i in 0..6 {
///     for j in 0..6 {
///         assert_eq!(id.to_f64()[i * 6 + j], if i == j { 1.0 } else { 0.0 });
///     }
/// }
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`] above [`MAX_EXACT_MATRIX_DEGREE`].
pub fn bernstein_monomial_matrix_inverse(n: usize) -> Result<RationalMatrix> {
    check_exact_degree(n)?;
    let c = pascal(n);
    let mut h = RationalMatrix::zeros_unchecked(n + 1, n + 1);
    for i in 0..=n {
        for j in i..=n {
            h.set(i, j, BigRational::new(c[j][i].clone(), c[n][i].clone()));
        }
    }
    Ok(h)
}

/// `E_{M,N}`: the `M×N` zero matrix with `min(M, N)` ones on the main diagonal (document 004,
/// notation of eq. 7). Multiplying by it keeps the leading rows or columns and pads with zeros.
///
/// # Errors
/// [`Error::TooLarge`] for more than `4 (MAX_EXACT_MATRIX_DEGREE + 1)²` entries.
pub fn truncation_matrix(rows: usize, cols: usize) -> Result<RationalMatrix> {
    let mut e = RationalMatrix::zeros(rows, cols)?;
    for i in 0..rows.min(cols) {
        e.set(i, i, BigRational::from_integer(BigInt::from(1)));
    }
    Ok(e)
}

/// `K_{n,n'} = E_{n+1,n'+1} H_{n'}^{-1}`, the first `n + 1` rows of `H_{n'}^{-1}` (document 004
/// eq. 7–8). Elevation is `U' = U_n H_n K_{n,n'}`.
///
/// # Errors
/// [`Error::Degree`] if `n` or `n_new` exceeds [`MAX_EXACT_MATRIX_DEGREE`].
pub fn elevation_block(n: usize, n_new: usize) -> Result<RationalMatrix> {
    check_exact_degree(n)?;
    truncation_matrix(n + 1, n_new + 1)?.mul(&bernstein_monomial_matrix_inverse(n_new)?)
}

/// `G_{n,n'} = H_n E_{n+1,n'+1}`, the first `n' + 1` columns of `H_n` (document 004 eq. 9).
/// Exact reduction of a curve with degree defect `n − n'` is `U' = U_n G_{n,n'} H_{n'}^{-1}`.
///
/// # Errors
/// [`Error::Degree`] if `n` or `n_new` exceeds [`MAX_EXACT_MATRIX_DEGREE`].
pub fn reduction_block(n: usize, n_new: usize) -> Result<RationalMatrix> {
    check_exact_degree(n_new)?;
    bernstein_monomial_matrix(n)?.mul(&truncation_matrix(n + 1, n_new + 1)?)
}

/// The unified order-change matrix `H_n E_{n+1,n'+1} H_{n'}^{-1}` of document 004 eq. 10:
/// `U'_{n'} = U_n · order_change_matrix(n, n')`.
///
/// - For `n' ≥ n` it equals the elevation matrix with the closed form
///   `C(n,i) C(n'−n, j−i) / C(n',j)` (non-negative, columns summing to 1).
/// - For `n' < n` it is exact only when the curve has a degree defect of at least `n − n'`:
///   otherwise it silently drops the monomial terms `t^(n'+1) … t^n`
///   (docs/theory/degree.md#reduction-without-a-defect). This function builds the matrix and
///   does not see the curve; the checked operation is
///   [`BezierCurve::change_degree`](crate::BezierCurve::change_degree).
///
/// ```
/// use lekalo::order_change_matrix;
/// // document 004, Example 1, task 3: H_3 K_{3,5}
/// let m = order_change_matrix(3, 5)?.to_f64();
/// assert_eq!(&m[..6], &[1.0, 0.4, 0.1, 0.0, 0.0, 0.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`] if `n` or `n_new` exceeds [`MAX_EXACT_MATRIX_DEGREE`].
pub fn order_change_matrix(n: usize, n_new: usize) -> Result<RationalMatrix> {
    reduction_block(n, n_new)?.mul(&bernstein_monomial_matrix_inverse(n_new)?)
}

/// The closed-form elevation matrix `(H_n K_{n,n'})_ij = C(n,i) C(n'−n, j−i) / C(n',j)`
/// (docs/theory/degree.md#elevation-by-several-degrees; Farin, *Curves and Surfaces for CAGD*,
/// §5.1), built without any inverse.
///
/// # Errors
/// [`Error::Degree`] if `n_new < n` or either exceeds [`MAX_EXACT_MATRIX_DEGREE`].
pub fn elevation_matrix(n: usize, n_new: usize) -> Result<RationalMatrix> {
    check_exact_degree(n_new)?;
    let r = n_new.checked_sub(n).ok_or_else(|| Error::Degree {
        degree: n_new,
        reason: format!("elevation needs a degree of at least the current {n}"),
    })?;
    let c = pascal(n_new);
    let mut m = RationalMatrix::zeros_unchecked(n + 1, n_new + 1);
    for i in 0..=n {
        for j in i..=i + r {
            let num = &c[n][i] * &c[r][j - i];
            m.set(i, j, BigRational::new(num, c[n_new][j].clone()));
        }
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ints(m: &RationalMatrix) -> Vec<f64> {
        m.to_f64()
    }

    #[test]
    fn h_times_inverse_is_identity() {
        for n in 0..=12 {
            let id = bernstein_monomial_matrix(n)
                .unwrap()
                .mul(&bernstein_monomial_matrix_inverse(n).unwrap())
                .unwrap();
            assert_eq!(id, truncation_matrix(n + 1, n + 1).unwrap(), "n = {n}");
        }
    }

    #[test]
    fn order_change_equals_closed_form_for_elevation() {
        for n in 0..=7 {
            for n_new in n..=n + 5 {
                assert_eq!(
                    order_change_matrix(n, n_new).unwrap(),
                    elevation_matrix(n, n_new).unwrap(),
                    "n = {n}, n' = {n_new}"
                );
            }
        }
    }

    #[test]
    fn blocks_are_the_leading_rows_and_columns() {
        let k = elevation_block(3, 5).unwrap();
        let hi = bernstein_monomial_matrix_inverse(5).unwrap();
        assert_eq!((k.rows(), k.cols()), (4, 6), "K_{{3,5}} size");
        for i in 0..4 {
            for j in 0..6 {
                assert_eq!(k.get(i, j), hi.get(i, j), "K_{{3,5}}[{i}][{j}]");
            }
        }
        let g = reduction_block(5, 3).unwrap();
        let h = bernstein_monomial_matrix(5).unwrap();
        assert_eq!((g.rows(), g.cols()), (6, 4), "G_{{5,3}} size");
        for i in 0..6 {
            for j in 0..4 {
                assert_eq!(g.get(i, j), h.get(i, j), "G_{{5,3}}[{i}][{j}]");
            }
        }
        assert_eq!(g.get(6, 0), None, "outside");
    }

    #[test]
    fn errors() {
        assert!(matches!(
            bernstein_monomial_matrix(MAX_EXACT_MATRIX_DEGREE + 1),
            Err(Error::Degree { .. })
        ));
        assert!(matches!(
            elevation_matrix(4, 3),
            Err(Error::Degree { degree: 3, .. })
        ));
        let a = truncation_matrix(2, 3).unwrap();
        assert!(matches!(a.mul(&a), Err(Error::LengthMismatch { .. })));
        assert!(matches!(
            RationalMatrix::from_integers(2, 2, &[1, 2, 3]),
            Err(Error::LengthMismatch { expected: 4, .. })
        ));
        assert!(matches!(
            RationalMatrix::zeros(usize::MAX, 2),
            Err(Error::TooLarge { .. })
        ));
        assert!(matches!(
            a.apply_to_points(&[], 0),
            Err(Error::Dimension { .. })
        ));
        assert!(matches!(
            a.apply_to_points(&[], 1),
            Err(Error::LengthMismatch { expected: 2, .. })
        ));
    }

    #[test]
    fn transpose_and_integers() {
        let m = RationalMatrix::from_integers(2, 3, &[1, 2, 3, 4, 5, 6]).unwrap();
        assert_eq!(ints(&m.transpose()), vec![1.0, 4.0, 2.0, 5.0, 3.0, 6.0]);
        assert_eq!(m.transpose().transpose(), m);
    }
}
