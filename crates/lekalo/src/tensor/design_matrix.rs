//! The design (collocation) matrix of a tensor-product B-spline space at scattered points: each
//! row the Kronecker product of the one-direction basis rows
//! (`docs/theory/tensor.md#design-matrix`).

use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{check_finite, Error, Result};
use crate::knots::KnotVector;
use crate::tensor::spline::{check_len, check_n_vars, checked_size};

/// The design matrix of [`tensor_design_matrix`] in compressed rows, every row of the same
/// length: row `j` has the entries `values[j·row_len..(j+1)·row_len]` in the columns
/// `columns[j·row_len..(j+1)·row_len]` (increasing), the other `columns − row_len` entries zero.
/// As a CSR matrix its row pointers are `0, row_len, 2·row_len, …`.
#[derive(Debug, Clone, PartialEq)]
pub struct TensorDesignMatrix {
    /// Number of rows, one per point.
    pub rows: usize,
    /// Number of columns, `Π_a n_a`, one per control point of the net (first direction
    /// slowest, as [`TensorBSpline`](crate::TensorBSpline)'s control points).
    pub columns: usize,
    /// Entries per row, `Π_a (p_a + 1)`.
    pub row_len: usize,
    /// The column of each entry, row by row.
    pub indices: Vec<usize>,
    /// The value of each entry, row by row.
    pub values: Vec<f64>,
}

/// The matrix `B_{j,i} = Π_a N_{i_a,p_a}(x_{j,a})` of the tensor-product B-spline space with
/// `degrees` and `knots` at the points `x_j` (`points` holds `N` coordinates a point, point
/// after point), the column `i = Σ_a i_a·σ_a` of the control point `(i_0, …, i_{N−1})` with
/// strides `σ_a = Π_{b>a} n_b` (SciPy's `NdBSpline.design_matrix`): the tensor spline with the
/// net `c` is `B·c` at the points. Row `j` is the Kronecker product of the one-direction rows
/// `[N_{s_a−p_a,p_a}(x_{j,a}), …, N_{s_a,p_a}(x_{j,a})]` at the knot spans `s_a` (P&T Algorithm
/// A2.2 per direction, as [`basis_functions_many`](crate::basis::basis_functions_many)), the last
/// direction fastest, so its `Π_a (p_a + 1)` columns increase. Outside the domain, `extrapolate`
/// continues the polynomials of the end spans (the span of the nearest domain end, as
/// [`TensorBSpline::par_eval_batch_extrapolated`](crate::TensorBSpline::par_eval_batch_extrapolated));
/// without it such a point is an error. Cost `O(m·(Σ_a p_a² + Π_a (p_a + 1)))` for `m` points.
///
/// ```
/// use lekalo::tensor::tensor_design_matrix;
/// use lekalo::KnotVector;
/// // bilinear on [0, 1]², one span per direction: the four products (1−x)(1−y), (1−x)y, x(1−y), xy
/// let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0])?;
/// let m = tensor_design_matrix(&[1, 1], &[kv.clone(), kv], &[0.25, 0.5], false)?;
/// assert_eq!((m.rows, m.columns, m.row_len), (1, 4, 4));
/// assert_eq!(m.indices, [0, 1, 2, 3]);
/// assert_eq!(m.values, [0.375, 0.375, 0.125, 0.125]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// - [`Error::TooFew`] for zero directions;
/// - [`Error::LengthMismatch`] if `knots` does not have one vector per degree, or `points` is
///   not a whole number of points of `N` coordinates;
/// - [`Error::Degree`] if a knot vector is too short for its degree;
/// - [`Error::NonFinite`] for a coordinate that is not finite;
/// - [`Error::ParameterOutOfDomain`] for a coordinate outside its direction's domain when not
///   `extrapolate`;
/// - [`Error::TooLarge`] if the number of columns or of entries exceeds
///   [`MAX_SCALARS`](crate::MAX_SCALARS).
pub fn tensor_design_matrix(
    degrees: &[usize],
    knots: &[KnotVector],
    points: &[f64],
    extrapolate: bool,
) -> Result<TensorDesignMatrix> {
    let n = degrees.len();
    check_n_vars(n)?;
    check_len("knot vectors (one per degree)", n, knots.len())?;
    let mut shape = Vec::with_capacity(n);
    let mut widths = Vec::with_capacity(n);
    for (kv, &p) in knots.iter().zip(degrees) {
        kv.check_degree(p)?;
        // check_degree: len ≥ 2p + 2, so the subtraction cannot wrap
        let count = kv.len() - p - 1;
        kv.validate_for(p, count)?;
        shape.push(count);
        widths.push(p + 1);
    }
    if points.len() % n != 0 {
        return Err(Error::LengthMismatch {
            what: "point coordinates (a whole number of points, one coordinate per direction)"
                .into(),
            expected: points.len() / n * n + n,
            got: points.len(),
        });
    }
    check_finite("points", points)?;
    let m = points.len() / n;
    let columns = checked_size("design matrix columns (control points)", &shape, 1)?;
    let row_len = checked_size("design matrix row (Π (degree + 1))", &widths, 1)?;
    let total = checked_size("design matrix entries", &[m, row_len], 1)?;
    let strides: Vec<usize> = (0..n).map(|a| shape[a + 1..].iter().product()).collect();
    let domains: Vec<(f64, f64)> = knots
        .iter()
        .zip(degrees)
        .map(|(kv, &p)| kv.domain(p))
        .collect();
    let mut cursors: Vec<_> = knots
        .iter()
        .zip(degrees)
        .map(|(kv, &p)| kv.span_cursor(p))
        .collect();
    let mut scratch: Vec<BasisScratch> = degrees.iter().map(|&p| BasisScratch::new(p)).collect();
    let mut basis: Vec<Vec<f64>> = widths.iter().map(|&w| vec![0.0; w]).collect();
    let mut first = vec![0usize; n];
    let mut indices = vec![0usize; total];
    let mut values = vec![0.0; total];
    for ((x, cols), vals) in points
        .chunks_exact(n)
        .zip(indices.chunks_exact_mut(row_len))
        .zip(values.chunks_exact_mut(row_len))
    {
        for a in 0..n {
            let span = if extrapolate {
                let (lo, hi) = domains[a];
                cursors[a].find_unchecked(x[a].clamp(lo, hi))
            } else {
                cursors[a].find(x[a])?
            };
            let p = degrees[a];
            basis_funs_into(
                knots[a].as_slice(),
                p,
                span,
                x[a],
                &mut scratch[a],
                &mut basis[a],
            );
            first[a] = span - p;
        }
        // the Kronecker product, one direction at a time: after direction a the first
        // Π_{b≤a} (p_b + 1) entries hold the products of the rows of directions 0..=a
        let mut len = 1;
        cols[0] = 0;
        vals[0] = 1.0;
        for a in 0..n {
            let w = widths[a];
            for e in (0..len).rev() {
                let (c, v) = (cols[e], vals[e]);
                for (j, b) in basis[a].iter().enumerate() {
                    cols[e * w + j] = c + (first[a] + j) * strides[a];
                    vals[e * w + j] = v * b;
                }
            }
            len *= w;
        }
    }
    Ok(TensorDesignMatrix {
        rows: m,
        columns,
        row_len,
        indices,
        values,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::Points;
    use crate::TensorBSpline;

    fn knots(p: usize, inner: &[f64], lo: f64, hi: f64) -> KnotVector {
        let mut t = vec![lo; p + 1];
        t.extend_from_slice(inner);
        t.extend(std::iter::repeat_n(hi, p + 1));
        KnotVector::new(t).unwrap()
    }

    /// `B·c` is the tensor spline with the net `c`, inside the domain and (extrapolated) beyond
    /// it, in three variables of degrees 1, 2 and 3; each row sums to 1 inside (partition of
    /// unity).
    #[test]
    fn rows_times_the_net_are_the_spline() {
        let degrees = [1, 2, 3];
        let kvs = vec![
            knots(1, &[0.3, 0.5], 0.0, 1.0),
            knots(2, &[1.0], -1.0, 2.0),
            knots(3, &[0.2, 0.7, 1.3], 0.0, 2.0),
        ];
        let shape: Vec<usize> = kvs
            .iter()
            .zip(degrees)
            .map(|(k, p)| k.len() - p - 1)
            .collect();
        let size: usize = shape.iter().product();
        let net: Vec<f64> = (0..size)
            .map(|i| ((i * 37 % 11) as f64 - 5.0) / 3.0)
            .collect();
        let s = TensorBSpline::from_knot_vectors(
            degrees.to_vec(),
            kvs.clone(),
            Points::from_flat(1, net.clone()).unwrap(),
        )
        .unwrap();
        let inside = [0.1, -0.5, 0.0, 0.5, 1.0, 1.9, 1.0, 2.0, 2.0, 0.31, 0.0, 1.3];
        let beyond = [-0.2, 2.5, 1.0, 1.2, -1.5, 2.3];
        for (pts, extrapolate) in [
            (&inside[..], false),
            (&inside[..], true),
            (&beyond[..], true),
        ] {
            let m = tensor_design_matrix(&degrees, &kvs, pts, extrapolate).unwrap();
            assert_eq!((m.columns, m.row_len), (size, 2 * 3 * 4), "sizes");
            let mut want = vec![0.0; m.rows];
            s.par_eval_batch_extrapolated(pts, None, &mut want).unwrap();
            for (j, x) in pts.chunks_exact(3).enumerate() {
                let row = j * m.row_len..(j + 1) * m.row_len;
                let cols = &m.indices[row.clone()];
                assert!(cols.windows(2).all(|w| w[0] < w[1]), "columns increase");
                let got: f64 = cols
                    .iter()
                    .zip(&m.values[row.clone()])
                    .map(|(&c, v)| v * net[c])
                    .sum();
                assert!((got - want[j]).abs() < 1e-12, "{x:?}: {got} vs {}", want[j]);
                if !extrapolate {
                    let sum: f64 = m.values[row].iter().sum();
                    assert!((sum - 1.0).abs() < 1e-14, "partition of unity {sum}");
                }
            }
        }
    }

    #[test]
    fn bad_points_are_named() {
        let kv = knots(2, &[0.5], 0.0, 1.0);
        let kvs = [kv.clone(), kv];
        assert!(matches!(
            tensor_design_matrix(&[2, 2], &kvs, &[0.5, 0.5, 0.5], false),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            tensor_design_matrix(&[2, 2], &kvs, &[0.5, 1.5], false),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            tensor_design_matrix(&[2, 2], &kvs, &[0.5, f64::NAN], true),
            Err(Error::NonFinite { .. })
        ));
        assert!(matches!(
            tensor_design_matrix(&[2], &kvs, &[0.5, 0.5], false),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            tensor_design_matrix(&[], &[], &[], false),
            Err(Error::TooFew { .. })
        ));
    }
}
