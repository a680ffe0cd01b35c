//! Least squares over scattered data in `N` variables with given knots: the normal equations,
//! assembled point by point into a symmetric band and factored by the banded `UᵀDU` of the
//! curve and surface fits. `docs/theory/tensor.md#least-squares-on-scattered-data`.

use crate::error::{ControlSupport, Error, Result, MAX_SCALARS};
use crate::fit::banded::SymBand;
use crate::knots::KnotVector;
use crate::points::{Points, PointsRef};
use crate::tensor::scattered_qr::{
    observe, solve, to_natural, Layout, RankDeficiency, RowProducts,
};
use crate::tensor::spline::{check_len, check_n_vars, checked_size, TensorBSpline};
use crate::{Arg, What};

/// The result of [`tensor_scattered_least_squares`].
#[derive(Debug, Clone, PartialEq)]
pub struct TensorScatteredFit {
    /// The fitted spline (values of the data's dimension).
    pub spline: TensorBSpline,
    /// `|S(x_k) − y_k|` for every data point.
    pub residuals: Vec<f64>,
    /// `Σ_k w_k |S(x_k) − y_k|²`.
    pub weighted_rss: f64,
    /// The rank of the system solved: the number of control points unless
    /// [`RankDeficiency::MinimumNorm`] dropped some
    /// ([`tensor_scattered_least_squares_with`]).
    pub rank: usize,
}

/// The net sizes of a scattered fit's space, after checking the data against it: one degree
/// and one knot vector per variable, at least one point, one value row and (when given) one
/// finite non-negative weight per point, and knot vectors valid for their degrees.
fn check_data(
    x: PointsRef<'_>,
    values: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: &[usize],
    knots: &[KnotVector],
) -> Result<Vec<usize>> {
    let n_vars = x.dim();
    check_n_vars(n_vars)?;
    check_len("degrees (one per variable)", n_vars, degrees.len())?;
    check_len("knot vectors (one per variable)", n_vars, knots.len())?;
    let count = x.len();
    if count == 0 {
        return Err(Error::TooFew {
            what: "scattered data points".into(),
            min: 1,
            got: 0,
        });
    }
    check_len("values (one row per data point)", count, values.len())?;
    if let Some(w) = weights {
        check_weights(w, count)?;
    }
    let mut shape = Vec::with_capacity(n_vars);
    for (kv, &p) in knots.iter().zip(degrees) {
        let n = kv.len().saturating_sub(p + 1);
        kv.validate_for(p, n)?;
        shape.push(n);
    }
    Ok(shape)
}

/// The tensor-product B-spline with the given degrees and knots that minimises
/// `Σ_k w_k |S(x_k) − y_k|²` over scattered points `x_k` in `N` variables (SciPy's
/// `LSQBivariateSpline` for `N = 2`, here in any number of variables; Dierckx, *Curve and
/// Surface Fitting with Splines*, 1993, §5.1, for the bivariate normal equations).
///
/// Each point touches the `W = Π_a (p_a + 1)` control points of its window, so the normal
/// matrix `AᵀWA` is sparse with at most `W` non-zeros per row of `A`. In the net order (the
/// first direction slowest, strides `σ_a = Π_{b>a} n_b`) two control points that share a point
/// differ in index by at most `Σ_a p_a σ_a`: the matrix is banded with that half-bandwidth `b`.
/// It is assembled point by point (`W(W+1)/2` products a point, no matrix `A`), factored by the
/// banded `UᵀDU` of the curve and surface smoothing in `O(n b²)` (`n = Π_a n_a` unknowns) and
/// solved with the `dim` columns of the values as right-hand sides. Memory: `n (b + 1)` numbers,
/// refused above [`MAX_SCALARS`] before anything is allocated. A general sparse Cholesky with a
/// fill-reducing ordering would store less for large nets in three or more variables (the band
/// fills completely in this ordering); the band needs no symbolic analysis and no dependency,
/// and for nets of up to a few thousand control points its factorisation is below the
/// assembly. The values are shifted by the first point's before the solve (affine invariance).
///
/// Rank deficiency is named: a control point whose support (the box of knot spans where its
/// basis function is positive) holds no data point of positive weight, or whose pivot vanishes
/// because the data there are too few or too nearly aligned, is [`Error::EmptySupport`] with its
/// index per direction, its support and the number of points in it.
///
/// ```
/// use lekalo::{tensor_scattered_least_squares, KnotVector, PointsRef};
/// // 200 scattered points of f(x, y, z) = x·y − z² in [0, 1]³, fitted by a 4 × 4 × 4 net of
/// // degree 2: f lies in the spline space and is recovered
/// let mut x = Vec::new();
/// let mut y = Vec::new();
/// let mut state = 1u64;
/// let mut next = || { state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (state >> 11) as f64 / (1u64 << 53) as f64 };
/// for _ in 0..200 { let p = [next(), next(), next()]; y.push(p[0] * p[1] - p[2] * p[2]); x.extend(p); }
/// let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0])?;
/// let fit = tensor_scattered_least_squares(
///     PointsRef::from_flat(3, &x)?, PointsRef::from_flat(1, &y)?, None, &[2, 2, 2], vec![k.clone(), k.clone(), k],
/// )?;
/// assert_eq!(fit.spline.shape(), &[4, 4, 4]);
/// assert!(fit.weighted_rss < 1e-24);
/// assert!((fit.spline.eval(&[0.3, 0.7, 0.45])?[0] - (0.21 - 0.2025)).abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// - [`Error::TooFew`] for no data points;
/// - [`Error::LengthMismatch`] if `degrees` or `knots` do not have one entry per variable
///   (`x.dim()`), `values` not one row per point, or `weights` not one weight per point;
/// - [`Error::InvalidDataWeight`] for a weight that is NaN, infinite or negative, or all zero;
/// - [`Error::Degree`] and the knot errors of [`KnotVector::validate_for`] per direction;
/// - [`Error::ParameterOutOfDomain`] for a coordinate outside its direction's knot domain;
/// - [`Error::TooLarge`] if the net or the band (`n (b + 1)` numbers) exceeds [`MAX_SCALARS`];
/// - [`Error::EmptySupport`] as above.
pub fn tensor_scattered_least_squares(
    x: PointsRef<'_>,
    values: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: &[usize],
    knots: Vec<KnotVector>,
) -> Result<TensorScatteredFit> {
    tensor_scattered_penalized_least_squares(x, values, weights, degrees, knots, 0.0)
}

/// [`tensor_scattered_least_squares`] with a smoothing penalty that fills the cells without
/// data: minimises
/// `Σ_k w_k |S(x_k) − y_k|² + penalty · Σ_a Σ (second differences of the net along direction a)²`,
/// the discrete penalty of Eilers & Marx's P-splines (*Flexible smoothing with B-splines and
/// penalties*, Statistical Science 11, 1996) summed over the directions, which for `N = 2` is
/// [`surface_scattered_least_squares`](crate::fit::surface_scattered_least_squares)'s. A
/// control point without data then takes the value its neighbours' second differences leave
/// it, so data need not reach every cell; the penalty's null space (the nets linear in the
/// index along each direction) must still be determined by the data. The differences are of
/// the net, not of the function: on uneven knots or near clamped ends (where the Greville
/// abscissae are uneven) a linear function has a penalty too, as in P-splines. `penalty = 0` is
/// [`tensor_scattered_least_squares`]. The second differences of direction `a` couple control
/// points `2 σ_a` apart in the net order, so the band is `max(Σ_a p_a σ_a, 2 σ_a)`.
/// `docs/theory/tensor.md#least-squares-on-scattered-data`.
///
/// ```
/// use lekalo::{tensor_scattered_penalized_least_squares, KnotVector, PointsRef};
/// // points only in the part x < 0.4 of the cube: the control points at x = 0.6, 0.8, 1 have
/// // no data, and the penalty fills them from their neighbours
/// let mut x = Vec::new();
/// let mut y = Vec::new();
/// for i in 0..8 { for j in 0..8 { for k in 0..8 {
///     let p = [0.05 * i as f64, j as f64 / 7.0, k as f64 / 7.0];
///     y.push(1.0 + p[0] + 2.0 * p[1] - p[2]);
///     x.extend(p);
/// } } }
/// let k = KnotVector::clamped_uniform(1, 6)?;
/// let knots = vec![k.clone(), k.clone(), k];
/// let fit = tensor_scattered_penalized_least_squares(
///     PointsRef::from_flat(3, &x)?, PointsRef::from_flat(1, &y)?, None, &[1, 1, 1], knots, 1e-3,
/// )?;
/// // on even knots of degree 1 a linear function's net has no second differences: it is
/// // recovered, data or not
/// assert!((fit.spline.eval(&[0.9, 0.5, 0.5])?[0] - 2.4).abs() < 1e-9);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`tensor_scattered_least_squares`], and [`Error::NegativeSmoothing`] for a penalty that
/// is negative or not finite. With a positive penalty a control point without data is no
/// error; [`Error::EmptySupport`] names one the data and the penalty together leave
/// undetermined.
pub fn tensor_scattered_penalized_least_squares(
    x: PointsRef<'_>,
    values: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: &[usize],
    knots: Vec<KnotVector>,
    penalty: f64,
) -> Result<TensorScatteredFit> {
    if !(penalty >= 0.0 && penalty.is_finite()) {
        return Err(Error::NegativeSmoothing {
            what: What::of(Arg::Lambda, "penalty"),
            value: penalty,
        });
    }
    let shape = check_data(x, values, weights, degrees, &knots)?;
    let (n_vars, count) = (x.dim(), x.len());
    let n_ctrl = checked_size(
        "control net of the scattered fit (product of the net sizes)",
        &shape,
        1,
    )?;
    let mut stride = vec![1usize; n_vars];
    for a in (0..n_vars - 1).rev() {
        stride[a] = stride[a + 1] * shape[a + 1];
    }
    // two control points sharing a data point differ by at most Σ p_a σ_a in the net order
    let mut band = degrees
        .iter()
        .zip(&stride)
        .fold(0usize, |b, (&p, &s)| b.saturating_add(p.saturating_mul(s)));
    // the second differences of direction a couple control points 2 σ_a apart
    if penalty > 0.0 {
        for (&n, &s) in shape.iter().zip(&stride) {
            if n >= 3 {
                band = band.max(s.saturating_mul(2));
            }
        }
    }
    let size = n_ctrl.saturating_mul(band.saturating_add(1));
    if size > MAX_SCALARS {
        return Err(Error::TooLarge {
            what: "normal matrix of the scattered fit (control points × (half-bandwidth + 1))"
                .into(),
            size,
            max: MAX_SCALARS,
        });
    }
    let domains: Vec<(f64, f64)> = knots
        .iter()
        .zip(degrees)
        .map(|(kv, &p)| kv.domain(p))
        .collect();
    for row in x.iter() {
        for (&t, &(lo, hi)) in row.iter().zip(&domains) {
            if !(t >= lo && t <= hi) {
                return Err(Error::ParameterOutOfDomain {
                    t,
                    min: lo,
                    max: hi,
                });
            }
        }
    }
    let dim = values.dim();
    let center = values.point(0).to_vec();
    let mut normal = SymBand::zeros(n_ctrl, band);
    let mut rhs = vec![0.0; n_ctrl * dim];
    // data points of positive weight and positive basis value in each control point's support
    let mut support = vec![0usize; n_ctrl];
    let window: usize = degrees.iter().map(|p| p + 1).product();
    let mut row_products = RowProducts::new(degrees);
    for (k, (row, y)) in x.iter().zip(values.iter()).enumerate() {
        let w = weights.map_or(1.0, |w| w[k]);
        if w == 0.0 {
            continue;
        }
        // the window's indices and basis products, the first direction slowest (increasing)
        let (idx, val) = row_products.fill(&knots, degrees, &stride, row);
        for r in 0..window {
            if val[r] > 0.0 {
                support[idx[r]] += 1;
            }
            let wr = w * val[r];
            for c in r..window {
                normal.add(idx[r], idx[c], wr * val[c]);
            }
            let out = &mut rhs[idx[r] * dim..(idx[r] + 1) * dim];
            for ((o, &z), &c0) in out.iter_mut().zip(y).zip(&center) {
                *o += wr * (z - c0);
            }
        }
    }
    if penalty > 0.0 {
        add_second_differences(&mut normal, &shape, &stride, penalty);
    } else if let Some(i) = support.iter().position(|&c| c == 0) {
        return Err(empty_support(i, 0, &shape, degrees, &knots));
    }
    if let Err(i) = normal.factor() {
        return Err(empty_support(i, support[i], &shape, degrees, &knots));
    }
    normal.solve(&mut rhs, dim);
    for c in rhs.chunks_exact_mut(dim) {
        for (v, c0) in c.iter_mut().zip(&center) {
            *v += c0;
        }
    }
    let spline =
        TensorBSpline::from_knot_vectors(degrees.to_vec(), knots, Points::from_flat(dim, rhs)?)?;
    let mut fitted = vec![0.0; count * dim];
    spline.par_eval_batch(x.as_slice(), None, &mut fitted)?;
    let mut residuals = Vec::with_capacity(count);
    let mut weighted_rss = 0.0;
    for (k, (s, y)) in fitted.chunks_exact(dim).zip(values.iter()).enumerate() {
        let r2: f64 = s.iter().zip(y).map(|(a, b)| (a - b) * (a - b)).sum();
        weighted_rss += weights.map_or(1.0, |w| w[k]) * r2;
        residuals.push(r2.sqrt());
    }
    Ok(TensorScatteredFit {
        spline,
        residuals,
        weighted_rss,
        rank: n_ctrl,
    })
}

/// [`tensor_scattered_least_squares`] with a choice for a control point the data do not
/// determine: [`RankDeficiency::Refuse`] is [`tensor_scattered_least_squares`];
/// [`RankDeficiency::MinimumNorm`] is FITPACK's `surfit` with given knots (SciPy's
/// `LSQBivariateSpline`): the observation matrix reduced to a band triangle by Givens
/// rotations, the variables ordered for the least band, and the solution of least norm with
/// the pivots at most `√eps` times the largest taken as zero (FITPACK `fprank`; Dierckx, *Curve
/// and Surface Fitting with Splines*, 1993, §9.2.2). The result's `rank` says how many
/// pivots were kept. `docs/theory/tensor.md#rank-deficient-least-squares`.
///
/// ```
/// use lekalo::{tensor_scattered_least_squares_with, KnotVector, PointsRef, RankDeficiency};
/// // points on the diagonal of the square leave some bilinear control points undetermined
/// let x: Vec<f64> = (0..20).flat_map(|i| [i as f64 / 19.0, i as f64 / 19.0]).collect();
/// let y: Vec<f64> = (0..20).map(|i| 2.0 + i as f64 / 19.0).collect();
/// let k = KnotVector::new(vec![0.0, 0.0, 0.5, 1.0, 1.0])?;
/// let fit = tensor_scattered_least_squares_with(
///     PointsRef::from_flat(2, &x)?, PointsRef::from_flat(1, &y)?, None, &[1, 1],
///     vec![k.clone(), k], RankDeficiency::MinimumNorm { eps: 1e-16 },
/// )?;
/// assert!(fit.rank < 9);
/// assert!(fit.weighted_rss < 1e-20);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`tensor_scattered_least_squares`] (no [`Error::EmptySupport`] with
/// [`RankDeficiency::MinimumNorm`]), and [`Error::InvalidArgument`] for `eps` outside `(0, 1)`.
pub fn tensor_scattered_least_squares_with(
    x: PointsRef<'_>,
    values: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: &[usize],
    knots: Vec<KnotVector>,
    rank: RankDeficiency,
) -> Result<TensorScatteredFit> {
    rank.check()?;
    if rank == RankDeficiency::Refuse {
        return tensor_scattered_least_squares(x, values, weights, degrees, knots);
    }
    let shape = check_data(x, values, weights, degrees, &knots)?;
    let (n_vars, count) = (x.dim(), x.len());
    checked_size(
        "control net of the scattered fit (product of the net sizes)",
        &shape,
        1,
    )?;
    for row in x.iter() {
        for ((&t, kv), &p) in row.iter().zip(&knots).zip(degrees) {
            let (lo, hi) = kv.domain(p);
            if !(t >= lo && t <= hi) {
                return Err(Error::ParameterOutOfDomain {
                    t,
                    min: lo,
                    max: hi,
                });
            }
        }
    }
    let identity: Vec<usize> = (0..n_vars).collect();
    let layout = Layout::least_band(&identity, &shape, degrees);
    let obs = observe(x, values, weights, degrees, &knots, layout, false)?;
    let dim = values.dim();
    let (c, rank) = solve(obs.qr.clone(), obs.bw, rank).map_err(|i| {
        let natural = obs.layout.natural(i, &shape);
        empty_support(natural, obs.support[i], &shape, degrees, &knots)
    })?;
    let c = to_natural(&c, &obs.layout, &shape, dim);
    let spline =
        TensorBSpline::from_knot_vectors(degrees.to_vec(), knots, Points::from_flat(dim, c)?)?;
    let mut fitted = vec![0.0; count * dim];
    spline.par_eval_batch(x.as_slice(), None, &mut fitted)?;
    let mut residuals = Vec::with_capacity(count);
    let mut weighted_rss = 0.0;
    for (k, (s, y)) in fitted.chunks_exact(dim).zip(values.iter()).enumerate() {
        let r2: f64 = s.iter().zip(y).map(|(a, b)| (a - b) * (a - b)).sum();
        weighted_rss += weights.map_or(1.0, |w| w[k]) * r2;
        residuals.push(r2.sqrt());
    }
    Ok(TensorScatteredFit {
        spline,
        residuals,
        weighted_rss,
        rank,
    })
}

/// `penalty · Dᵀ D` added to the normal matrix for the second differences `D` of the net along
/// every direction with at least three control points (Eilers & Marx's P-spline penalty): the
/// directions in order, each line of the net along the direction in the net order, its
/// differences in order (the order of the surface fit's, so that `N = 2` adds the same numbers
/// in the same order).
fn add_second_differences(normal: &mut SymBand, shape: &[usize], stride: &[usize], penalty: f64) {
    const COEF: [f64; 3] = [1.0, -2.0, 1.0];
    let total: usize = shape.iter().product();
    for (&n, &s) in shape.iter().zip(stride) {
        if n < 3 {
            continue;
        }
        // the first control point of every line along the direction: its index there is 0
        for start in (0..total).filter(|&i| (i / s) % n == 0) {
            for j in 0..n - 2 {
                let base = start + j * s;
                let ids = [base, base + s, base + 2 * s];
                for r in 0..3 {
                    for c in r..3 {
                        normal.add(ids[r], ids[c], penalty * COEF[r] * COEF[c]);
                    }
                }
            }
        }
    }
}

/// Weights finite, non-negative, one per point, not all zero.
pub(super) fn check_weights(w: &[f64], count: usize) -> Result<()> {
    check_len(
        What::of(Arg::DataWeights, "weights (one per data point)"),
        count,
        w.len(),
    )?;
    if let Some((index, &weight)) = w
        .iter()
        .enumerate()
        .find(|(_, &x)| !(x.is_finite() && x >= 0.0))
    {
        return Err(Error::InvalidDataWeight { index, weight });
    }
    if w.iter().all(|&x| x == 0.0) {
        return Err(Error::InvalidDataWeight {
            index: 0,
            weight: 0.0,
        });
    }
    Ok(())
}

/// [`Error::EmptySupport`] for the control point of flat index `i`.
pub(super) fn empty_support(
    i: usize,
    points: usize,
    shape: &[usize],
    degrees: &[usize],
    knots: &[KnotVector],
) -> Error {
    let mut index = vec![0; shape.len()];
    let mut rest = i;
    for a in (0..shape.len()).rev() {
        index[a] = rest % shape[a];
        rest /= shape[a];
    }
    let lower = index
        .iter()
        .zip(knots)
        .map(|(&j, kv)| kv.as_slice()[j])
        .collect();
    let upper = index
        .iter()
        .zip(knots.iter().zip(degrees))
        .map(|(&j, (kv, &p))| kv.as_slice()[j + p + 1])
        .collect();
    Error::EmptySupport {
        support: Box::new(ControlSupport {
            index,
            lower,
            upper,
        }),
        points,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn unit_knots(p: usize, n: usize) -> KnotVector {
        KnotVector::clamped_uniform(p, n).unwrap()
    }

    /// Points of a deterministic low-discrepancy sequence in `[0, 1]^n` (Kronecker / golden
    /// ratio), so that every cell of a moderate net holds data.
    fn points(count: usize, n: usize, shift: f64) -> Vec<f64> {
        let alphas = [0.754_877_666, 0.569_840_291, 0.438_047_065, 0.618_033_989];
        let mut out = Vec::with_capacity(count * n);
        for k in 0..count {
            for alpha in alphas.iter().take(n) {
                out.push((shift + (k as f64 + 0.5) * alpha).fract());
            }
        }
        out
    }

    /// The basis function of control point `i` of `s`'s space at the points `xs`.
    fn basis_at(s: &TensorBSpline, i: usize, xs: &[f64]) -> Vec<f64> {
        let n: usize = s.shape().iter().product();
        let mut e = vec![0.0; n];
        e[i] = 1.0;
        let unit = TensorBSpline::from_knot_vectors(
            s.degrees().to_vec(),
            s.knots().to_vec(),
            Points::from_flat(1, e).unwrap(),
        )
        .unwrap();
        let mut out = vec![0.0; xs.len() / s.n_vars()];
        unit.eval_batch(xs, None, &mut out).unwrap();
        out
    }

    #[test]
    fn errors_name_the_argument() {
        let k = unit_knots(1, 3);
        let x = points(20, 2, 0.1);
        let y = vec![0.0; 20];
        let fit = |x: &[f64], y: &[f64], w: Option<&[f64]>, d: &[usize], ks: Vec<KnotVector>| {
            tensor_scattered_least_squares(
                PointsRef::from_flat(2, x).unwrap(),
                PointsRef::from_flat(1, y).unwrap(),
                w,
                d,
                ks,
            )
        };
        let two = || vec![k.clone(), k.clone()];
        assert!(matches!(
            fit(&x, &y, None, &[1], two()),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            fit(&x, &y[..19], None, &[1, 1], two()),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            fit(&x, &y, Some(&[1.0; 3]), &[1, 1], two()),
            Err(Error::LengthMismatch { .. })
        ));
        let mut w = vec![1.0; 20];
        w[4] = -1.0;
        assert!(matches!(
            fit(&x, &y, Some(&w), &[1, 1], two()),
            Err(Error::InvalidDataWeight { index: 4, .. })
        ));
        assert!(matches!(
            fit(&x, &y, Some(&[0.0; 20]), &[1, 1], two()),
            Err(Error::InvalidDataWeight { index: 0, .. })
        ));
        let mut out = x.clone();
        out[5] = 1.5;
        assert!(matches!(
            fit(&out, &y, None, &[1, 1], two()),
            Err(Error::ParameterOutOfDomain { t, .. }) if t == 1.5
        ));
        assert!(matches!(
            fit(&[], &[], None, &[1, 1], two()),
            Err(Error::TooFew { .. })
        ));
        assert!(matches!(
            fit(&x, &y, None, &[5, 1], two()),
            Err(Error::Degree { .. })
        ));
        // a net whose band would exceed the limit is refused before it is allocated
        let big = unit_knots(3, 3000);
        let e = fit(&x, &y, None, &[3, 3], vec![big.clone(), big]).unwrap_err();
        assert!(matches!(e, Error::TooLarge { .. }), "{e:?}");
    }

    #[test]
    fn points_on_two_lines_leave_a_control_point_undetermined() {
        // every support holds points, but x takes two values for three linear basis functions
        // in x: the normal matrix is singular and the failing pivot's control point is named
        let k = unit_knots(1, 3);
        let x: Vec<f64> = (0..40)
            .flat_map(|i| [0.25 + 0.5 * f64::from(i % 2), (f64::from(i) + 0.5) / 40.0])
            .collect();
        let y: Vec<f64> = (0..40).map(f64::from).collect();
        let e = tensor_scattered_least_squares(
            PointsRef::from_flat(2, &x).unwrap(),
            PointsRef::from_flat(1, &y).unwrap(),
            None,
            &[1, 1],
            vec![k.clone(), k],
        )
        .unwrap_err();
        match &e {
            Error::EmptySupport { points, .. } => assert!(*points > 0, "{e}"),
            other => panic!("expected EmptySupport, got {other:?}"),
        }
        assert!(e.to_string().contains("too nearly aligned"), "{e}");
    }

    #[test]
    fn two_variables_agree_with_the_surface_fit() {
        let (ku, kv) = (unit_knots(3, 6), unit_knots(2, 5));
        let x = points(300, 2, 0.3);
        let mut rows = Vec::new();
        let mut y = Vec::new();
        for p in x.chunks_exact(2) {
            let z = (3.0 * p[0]).sin() * (2.0 * p[1]).cos() + 4.0;
            rows.extend([p[0], p[1], z]);
            y.push(z);
        }
        let surf = crate::fit::surface_scattered_least_squares(
            PointsRef::from_flat(3, &rows).unwrap(),
            None,
            (3, 2),
            (&ku, &kv),
            0.0,
        )
        .unwrap();
        let t = tensor_scattered_least_squares(
            PointsRef::from_flat(2, &x).unwrap(),
            PointsRef::from_flat(1, &y).unwrap(),
            None,
            &[3, 2],
            vec![ku, kv],
        )
        .unwrap();
        let a = surf.surface.control_points().as_slice();
        let b = t.spline.control_points().as_slice();
        for (p, q) in a.iter().zip(b) {
            assert!((p - q).abs() < 1e-11, "{p} {q}");
        }
        assert!((surf.weighted_rss - t.weighted_rss).abs() < 1e-12 * (1.0 + t.weighted_rss));
    }

    #[test]
    fn two_variables_with_a_penalty_agree_with_the_surface_fit() {
        // degree 1 in v: the second differences along u (2 n_v apart) widen the band
        for (p, q) in [(3, 2), (1, 1)] {
            let (ku, kv) = (unit_knots(p, 7), unit_knots(q, 6));
            // no data in u > 0.6: the penalty fills those cells
            let x: Vec<f64> = points(300, 2, 0.3)
                .chunks_exact(2)
                .flat_map(|c| [0.6 * c[0], c[1]])
                .collect();
            let mut rows = Vec::new();
            let mut y = Vec::new();
            for c in x.chunks_exact(2) {
                let z = (3.0 * c[0]).sin() * (2.0 * c[1]).cos() + 1e3;
                rows.extend([c[0], c[1], z]);
                y.push(z);
            }
            let surf = crate::fit::surface_scattered_least_squares(
                PointsRef::from_flat(3, &rows).unwrap(),
                None,
                (p, q),
                (&ku, &kv),
                0.01,
            )
            .unwrap();
            let fit = |penalty| {
                tensor_scattered_penalized_least_squares(
                    PointsRef::from_flat(2, &x).unwrap(),
                    PointsRef::from_flat(1, &y).unwrap(),
                    None,
                    &[p, q],
                    vec![ku.clone(), kv.clone()],
                    penalty,
                )
            };
            let t = fit(0.01).unwrap();
            let a = surf.surface.control_points().as_slice();
            let b = t.spline.control_points().as_slice();
            for (u, v) in a.iter().zip(b) {
                assert!((u - v).abs() < 1e-11 * 1e3, "{u} {v}");
            }
            assert!(matches!(fit(0.0), Err(Error::EmptySupport { .. })));
        }
    }

    #[test]
    fn a_penalty_fills_cells_without_data_and_solves_its_normal_equations() {
        // three variables of mixed degrees, one of them linear (its second differences reach
        // beyond the data's band), the data in x0 < 0.5 only
        let degrees = [1usize, 2, 1];
        let knots: Vec<KnotVector> = [5, 4, 4]
            .iter()
            .zip(&degrees)
            .map(|(&n, &p)| unit_knots(p, n))
            .collect();
        let x: Vec<f64> = points(600, 3, 0.2)
            .chunks_exact(3)
            .flat_map(|c| [0.5 * c[0], c[1], c[2]])
            .collect();
        let y: Vec<f64> = x
            .chunks_exact(3)
            .map(|c| 100.0 + (4.0 * c[0]).cos() + c[1] * c[2] * c[2])
            .collect();
        let fit = |penalty: f64| {
            tensor_scattered_penalized_least_squares(
                PointsRef::from_flat(3, &x).unwrap(),
                PointsRef::from_flat(1, &y).unwrap(),
                None,
                &degrees,
                knots.clone(),
                penalty,
            )
        };
        match fit(0.0) {
            Err(Error::EmptySupport { support, points }) => {
                assert_eq!(points, 0);
                assert_eq!(support.index[0], 3, "{support:?}");
            }
            other => panic!("expected EmptySupport, got {other:?}"),
        }
        let penalty = 0.5;
        let f = fit(penalty).unwrap();
        let c = f.spline.control_points().as_slice();
        let shape = f.spline.shape().to_vec();
        let m = c.len();
        // the gradient of the objective: Aᵀ(Ac − y) + penalty · DᵀD c = 0
        let mut s = vec![0.0; y.len()];
        f.spline.eval_batch(&x, None, &mut s).unwrap();
        let mut grad = vec![0.0; m];
        let mut scale = vec![0.0; m];
        for (i, (g, sc)) in grad.iter_mut().zip(&mut scale).enumerate() {
            for (k, b) in basis_at(&f.spline, i, &x).iter().enumerate() {
                *g += b * (s[k] - y[k]);
                *sc += b * (s[k] - y[k]).abs();
            }
        }
        let stride = [shape[1] * shape[2], shape[2], 1];
        for a in 0..3 {
            for start in (0..m).filter(|&i| (i / stride[a]) % shape[a] == 0) {
                for j in 0..shape[a] - 2 {
                    let ids = [0, 1, 2].map(|d| start + (j + d) * stride[a]);
                    let d2 = c[ids[0]] - 2.0 * c[ids[1]] + c[ids[2]];
                    for (id, w) in ids.iter().zip([1.0, -2.0, 1.0]) {
                        grad[*id] += penalty * w * d2;
                        scale[*id] += penalty * (w * d2).abs();
                    }
                }
            }
        }
        for (i, (g, sc)) in grad.iter().zip(&scale).enumerate() {
            assert!(
                g.abs() <= 1e-6 * (1.0 + sc),
                "control point {i}: {g} of {sc}"
            );
        }
        // the filled values stay near the field (no data: only the penalty's continuation)
        let v = f.spline.eval(&[0.8, 0.5, 0.5]).unwrap()[0] - 100.0;
        assert!(v.is_finite() && v.abs() < 3.0, "{v}");
        assert!(matches!(
            fit(-1.0),
            Err(Error::NegativeSmoothing { value, .. }) if value == -1.0
        ));
        assert!(matches!(
            fit(f64::NAN),
            Err(Error::NegativeSmoothing { .. })
        ));
    }

    proptest! {
        #![proptest_config(crate::oracle::proptest_config(24))]

        /// Data sampled from a spline of the same space are fitted exactly, whatever the
        /// weights, and the residual of noisy data is orthogonal to every basis function
        /// (`Aᵀ W r = 0`).
        #[test]
        fn reproduces_its_space_and_leaves_orthogonal_residuals(
            degrees in proptest::collection::vec(1usize..=3, 1..=3),
            extra in proptest::collection::vec(0usize..=1, 3),
            coefficients in proptest::collection::vec(-5.0f64..5.0, 2 * 125),
            noise in proptest::collection::vec(-0.1f64..0.1, 400),
            shift in 0.0f64..1.0,
            weighted in any::<bool>(),
        ) {
            let n = degrees.len();
            let knots: Vec<KnotVector> = degrees
                .iter()
                .zip(&extra)
                .map(|(&p, &e)| unit_knots(p, p + 1 + e))
                .collect();
            let shape: Vec<usize> = degrees.iter().zip(&extra).map(|(&p, &e)| p + 1 + e).collect();
            let m: usize = shape.iter().product();
            let truth = TensorBSpline::from_knot_vectors(
                degrees.clone(),
                knots.clone(),
                Points::from_flat(2, coefficients[..2 * m].to_vec()).unwrap(),
            )
            .unwrap();
            let count = 20 * m.max(4);
            let x = points(count, n, shift);
            let mut y = vec![0.0; count * 2];
            truth.eval_batch(&x, None, &mut y).unwrap();
            let w: Vec<f64> = (0..count).map(|k| 0.5 + (k % 7) as f64 / 4.0).collect();
            let weights = weighted.then_some(w.as_slice());
            let fit = tensor_scattered_least_squares(
                PointsRef::from_flat(n, &x).unwrap(),
                PointsRef::from_flat(2, &y).unwrap(),
                weights,
                &degrees,
                knots.clone(),
            )
            .unwrap();
            let scale = coefficients.iter().fold(1.0f64, |s, c| s.max(c.abs()));
            for (p, q) in fit
                .spline
                .control_points()
                .as_slice()
                .iter()
                .zip(truth.control_points().as_slice())
            {
                prop_assert!((p - q).abs() < 1e-9 * scale, "{} vs {}", p, q);
            }
            // noisy data: Σ_k w_k B_i(x_k) r_k = 0 for every control point i
            for (k, v) in y.iter_mut().enumerate() {
                *v += noise[k % noise.len()];
            }
            let fit = tensor_scattered_least_squares(
                PointsRef::from_flat(n, &x).unwrap(),
                PointsRef::from_flat(2, &y).unwrap(),
                weights,
                &degrees,
                knots,
            )
            .unwrap();
            let mut s = vec![0.0; count * 2];
            fit.spline.eval_batch(&x, None, &mut s).unwrap();
            for i in 0..m {
                let basis = basis_at(&fit.spline, i, &x);
                let mut dot = [0.0f64; 2];
                let mut size = 0.0f64;
                for (k, &b) in basis.iter().enumerate() {
                    let wk = weights.map_or(1.0, |w| w[k]);
                    for c in 0..2 {
                        let r = y[2 * k + c] - s[2 * k + c];
                        dot[c] += wk * b * r;
                        size += wk * b * r.abs();
                    }
                }
                for d in dot {
                    prop_assert!(d.abs() <= 1e-9 * (1.0 + size), "{} of {}", d, size);
                }
            }
        }
    }
}
