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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(crate::oracle::proptest_config(32))]

        /// A grid sampled from a spline of the same space is fitted exactly, and the residual
        /// of a perturbed grid is orthogonal to every basis function of the space: each
        /// `(B_i(x̄_{0,k_0})⋯B_{i'}(x̄_{N−1,k_{N−1}}))` summed against the residuals vanishes.
        #[test]
        fn reproduces_its_space_and_leaves_orthogonal_residuals(
            degrees in proptest::collection::vec(1usize..=3, 1..=3),
            extra in proptest::collection::vec(0usize..=2, 3),
            more in proptest::collection::vec(0usize..=4, 3),
            coefficients in proptest::collection::vec(-5.0f64..5.0, 216),
            noise in proptest::collection::vec(-0.1f64..0.1, 97),
        ) {
            let n = degrees.len();
            let shape: Vec<usize> = degrees.iter().zip(&extra).map(|(&p, &e)| p + 1 + e).collect();
            let knots: Vec<KnotVector> = degrees
                .iter()
                .zip(&shape)
                .map(|(&p, &c)| KnotVector::clamped_uniform(p, c).unwrap())
                .collect();
            let m: usize = shape.iter().product();
            let truth = TensorBSpline::from_knot_vectors(
                degrees.clone(),
                knots.clone(),
                Points::from_flat(1, coefficients[..m].to_vec()).unwrap(),
            )
            .unwrap();
            // uneven grid coordinates, more than control points in every direction
            let axes: Vec<Vec<f64>> = shape
                .iter()
                .zip(&more)
                .map(|(&c, &k)| {
                    let count = c + 1 + k;
                    (0..count)
                        .map(|i| {
                            let t = i as f64 / (count - 1) as f64;
                            t * t * (3.0 - 2.0 * t) * 0.5 + t * 0.5
                        })
                        .collect()
                })
                .collect();
            let refs: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
            let sizes: Vec<usize> = axes.iter().map(Vec::len).collect();
            let total: usize = sizes.iter().product();
            let mut grid = vec![0.0; total];
            truth.eval_grid(&refs, None, &mut grid).unwrap();
            let fit = tensor_grid_least_squares(
                &refs,
                PointsRef::from_flat(1, &grid).unwrap(),
                &degrees,
                knots.clone(),
            )
            .unwrap();
            for (p, q) in fit
                .control_points()
                .as_slice()
                .iter()
                .zip(truth.control_points().as_slice())
            {
                prop_assert!((p - q).abs() < 1e-9, "{} vs {}", p, q);
            }
            for (k, v) in grid.iter_mut().enumerate() {
                *v += noise[k % noise.len()];
            }
            let fit = tensor_grid_least_squares(
                &refs,
                PointsRef::from_flat(1, &grid).unwrap(),
                &degrees,
                knots.clone(),
            )
            .unwrap();
            let mut s = vec![0.0; total];
            fit.eval_grid(&refs, None, &mut s).unwrap();
            let residual: Vec<f64> = grid.iter().zip(&s).map(|(g, f)| g - f).collect();
            for i in 0..m {
                let mut e = vec![0.0; m];
                e[i] = 1.0;
                let unit = TensorBSpline::from_knot_vectors(
                    degrees.clone(),
                    knots.clone(),
                    Points::from_flat(1, e).unwrap(),
                )
                .unwrap();
                let mut b = vec![0.0; total];
                unit.eval_grid(&refs, None, &mut b).unwrap();
                let dot: f64 = b.iter().zip(&residual).map(|(x, r)| x * r).sum();
                let size: f64 = b.iter().zip(&residual).map(|(x, r)| (x * r).abs()).sum();
                prop_assert!(dot.abs() <= 1e-10 * (1.0 + size), "{} of {} (n = {})", dot, size, n);
            }
        }
    }
}
