//! Least squares on a grid with given knots: the tensor product of the one-direction
//! least-squares projectors, applied by one sweep per direction.
//! `docs/theory/tensor.md#least-squares-on-grids`.

use crate::error::Result;
use crate::fit::{least_squares, EndConstraints, FitData};
use crate::interpolate::parametrization::check_strictly_increasing;
use crate::knots::KnotVector;
use crate::points::{Points, PointsRef};
use crate::tensor::spline::{check_len, check_n_vars, checked_size, TensorBSpline};

/// The tensor-product B-spline with the given degrees and knots that minimises
/// `Σ_k |S(x̄_{0,k_0}, …, x̄_{N−1,k_{N−1}}) − q_k|²` over a grid of values (P&T §9.4.3 for
/// `N = 2`; SciPy's `make_lsq_spline` in each direction).
///
/// The grid holds `Π_a m_a` values (`m_a = params[a].len()`), the first direction slowest as in
/// [`TensorInterpolation`](crate::TensorInterpolation). The observation matrix is
/// `A_0 ⊗ ⋯ ⊗ A_{N−1}` and its pseudo-inverse is `A_0⁺ ⊗ ⋯ ⊗ A_{N−1}⁺` (each `A_a` has full
/// column rank by the Schoenberg–Whitney conditions), so the fit is `N` sweeps: along direction
/// `a` (the last first), every block of the grid is fitted as one curve whose points are the
/// `Π_{b>a}` columns of the block, by [`least_squares`] (banded QR, the columns as
/// right-hand sides). The direction's size shrinks from `m_a` to `n_a` in its sweep. Cost
/// `O(Σ_a (Π_{b<a} m_b)·m_a·(Π_{b>a} n_b)·dim·(p_a + 1))`, at most
/// `O(Π_a m_a·dim·Σ_a (p_a + 1))` (plus each fit's residual report); memory: two grids of
/// intermediate values.
///
/// ```
/// use lekalo::{tensor_grid_least_squares, KnotVector, PointsRef};
/// // a 3-variate quadratic sampled on 12 × 10 × 8 nodes, fitted by a 5 × 4 × 4 net of degree 2:
/// // the quadratic lies in the spline space and is recovered
/// let axis = |m: usize| -> Vec<f64> { (0..m).map(|k| k as f64 / (m - 1) as f64).collect() };
/// let (xs, ys, zs) = (axis(12), axis(10), axis(8));
/// let mut q = Vec::new();
/// for &x in &xs { for &y in &ys { for &z in &zs { q.push(x * x - y * z + 0.5 * z); } } }
/// let knots = vec![
///     KnotVector::clamped_uniform(2, 5)?, KnotVector::clamped_uniform(2, 4)?, KnotVector::clamped_uniform(2, 4)?,
/// ];
/// let s = tensor_grid_least_squares(&[&xs, &ys, &zs], PointsRef::from_flat(1, &q)?, &[2, 2, 2], knots)?;
/// assert_eq!(s.shape(), &[5, 4, 4]);
/// let v = s.eval(&[0.3, 0.7, 0.45])?[0];
/// assert!((v - (0.09 - 0.7 * 0.45 + 0.225)).abs() < 1e-13);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// - [`Error::TooFew`](crate::Error::TooFew) for zero directions;
/// - [`Error::LengthMismatch`](crate::Error::LengthMismatch) if `degrees` or `knots` do not
///   have one entry per direction or `values` does not hold `Π_a m_a` values;
/// - [`Error::TooLarge`](crate::Error::TooLarge) if the grid's size overflows or exceeds
///   [`MAX_SCALARS`](crate::MAX_SCALARS);
/// - [`Error::NonFinite`](crate::Error::NonFinite),
///   [`Error::KnotsNotSorted`](crate::Error::KnotsNotSorted) or
///   [`Error::InvalidArgument`](crate::Error::InvalidArgument) for coordinates that are not
///   finite and strictly increasing;
/// - the errors of [`least_squares`] per direction: [`Error::Degree`](crate::Error::Degree),
///   [`Error::ParameterOutOfDomain`](crate::Error::ParameterOutOfDomain),
///   [`Error::SchoenbergWhitney`](crate::Error::SchoenbergWhitney) (more control points than
///   coordinates, or a knot span without coordinates).
pub fn tensor_grid_least_squares(
    params: &[&[f64]],
    values: PointsRef<'_>,
    degrees: &[usize],
    knots: Vec<KnotVector>,
) -> Result<TensorBSpline> {
    let n = params.len();
    check_n_vars(n)?;
    check_len("degrees (one per grid direction)", n, degrees.len())?;
    check_len("knot vectors (one per grid direction)", n, knots.len())?;
    let mut shape: Vec<usize> = params.iter().map(|p| p.len()).collect();
    let count = checked_size("grid values (product of the coordinate counts)", &shape, 1)?;
    check_len(
        "grid values (product of the coordinate counts)",
        count,
        values.len(),
    )?;
    for p in params {
        check_strictly_increasing(p)?;
    }
    let dim = values.dim();
    let mut grid = values.as_slice().to_vec();
    for a in (0..n).rev() {
        let outer: usize = shape[..a].iter().product();
        let inner = shape[a + 1..].iter().product::<usize>() * dim;
        let m = shape[a];
        let mut next = Vec::new();
        for block in grid.chunks_exact(m * inner).take(outer) {
            let data = FitData::new(PointsRef::from_flat(inner, block)?, params[a])?;
            let fit = least_squares(&data, degrees[a], &knots[a], &EndConstraints::none())?;
            next.extend_from_slice(fit.curve.control_points().as_slice());
        }
        shape[a] = knots[a].len() - degrees[a] - 1;
        grid = next;
    }
    TensorBSpline::from_knot_vectors(degrees.to_vec(), knots, Points::from_flat(dim, grid)?)
}
