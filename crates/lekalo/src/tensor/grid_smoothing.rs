//! Smoothing on grids in `N` directions: the tensor-product spline with the fewest knots found
//! whose residual sum of squares on the grid is at most `s`, or within `0.001·s` above it
//! (FITPACK `regrid`, behind SciPy's
//! `RectBivariateSpline`, here in any number of directions).
//! `docs/theory/tensor.md#smoothing-on-grids`.

use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, NthDirection, Result};
use crate::fit::banded::BandedQr;
use crate::fit::{
    accepts_least_squares, check_condition_args, jump_rows, next_nplus, smooth_weight, Steps,
    SMOOTHING_RTOL,
};
use crate::interpolate::parametrization::check_strictly_increasing;
use crate::numeric::progress::Progress;
use crate::points::{Points, PointsRef};
use crate::tensor::spline::{check_len, check_n_vars, checked_size, TensorBSpline};
use crate::tensor::TensorInterpolation;
use crate::KnotVector;
use crate::{Arg, What};

/// The result of [`tensor_grid_smoothing`].
#[derive(Debug, Clone, PartialEq)]
pub struct TensorGridSmoothing {
    /// The fitted spline (values of the data's dimension), clamped on the box of the grid (or
    /// the box given).
    pub spline: TensorBSpline,
    /// `Σ_k |S(x̄_k) − q_k|²` over the nodes of the grid (FITPACK's `fp`).
    pub residual: f64,
    /// FITPACK's smoothing weight `p` of the result (the weight of the data against the
    /// derivative jumps): `None` for a least-squares spline (the polynomial, interpolation, or
    /// knots whose least squares already lie within `s`).
    pub p: Option<f64>,
}

/// The tensor-product spline of the given degrees on the grid `params[0] × ⋯ × params[N−1]`
/// whose residual sum of squares `fp = Σ_k |S(x̄_k) − q_k|²` over the nodes is at most `s`, with
/// the fewest knots found (a least-squares spline of a round with `|fp − s| < 0.001·s` is the
/// answer, above `s` too, as FITPACK `fpregr` accepts it) (Dierckx, *Curve and Surface Fitting with Splines*, 1993, ch. 10;
/// FITPACK `regrid` as in SciPy's `RectBivariateSpline(x, y, z, s=…)`, in `N` directions).
/// `docs/theory/tensor.md#smoothing-on-grids`.
///
/// - `s = 0`: interpolation on FITPACK's knots (the interior knots at the nodes for odd
///   degrees, at their midpoints for even degrees, dropping `⌊k/2⌋ + 1` at each end), solved
///   as [`TensorInterpolation`] solves a grid (banded elimination, one sweep a direction); the
///   residual is `0`, as FITPACK reports it.
/// - `s > 0`: start from the polynomial (no interior knot). While the least-squares spline
///   leaves `fp ≥ s + 0.001·s`, add knots in one direction (a direction that reaches the knot count of
///   interpolation takes the knots of interpolation, as SciPy's `regrid` does): the direction whose estimated number of new
///   knots (`min(2·nplus, max(nplus·(fp − s)/reduction, nplus/2, 1))`, `reduction` the residual
///   decrease its last addition brought) is smallest, ties going to the next direction after
///   the last one used; each knot splits the knot span whose nodes carry the largest residual
///   (summed over the other directions, a node that opens a span counting half to each side)
///   at its middle node (FITPACK `fpknot`). Then, on the final knots, find the weight `p` of
///   `min ‖(A_0 ⊗ ⋯ ⊗ A_{N−1}) c − q‖² + ‖Σ of the cross terms with (B_a/p)‖²` (the augmented
///   observation matrices `[A_a; B_a/p]`, `B_a` the jumps of the `k_a`-th derivative at the
///   interior knots, FITPACK `fpdisc`) with `fp(p) = s` within [`SMOOTHING_RTOL`] and never
///   above, by FITPACK's rational interpolation, starting from `p = 1`.
///
/// The augmented system keeps the Kronecker form, so each solve is `N` sweeps: along direction
/// `a` every line of the grid is one right-hand side of the banded QR (Givens rotations) of
/// `[A_a; B_a/p]` (FITPACK `fpgrre`). A solve costs
/// `O(Σ_a (Π_{b<a} n_b)·(m_a + n_a)·(k_a + 2)·Π_{b>a} m_b·dim)` and the residual one evaluation
/// on the grid; memory two grids. The values are shifted by the first node's before the solve
/// (the jumps of a constant vanish, so the fit shifts with it).
///
/// ```
/// use lekalo::{tensor_grid_smoothing, PointsRef};
/// // a 40 × 30 grid of a smooth surface plus a small pattern of noise
/// let xs: Vec<f64> = (0..40).map(|i| i as f64 / 39.0).collect();
/// let ys: Vec<f64> = (0..30).map(|j| j as f64 / 29.0).collect();
/// let mut z = Vec::new();
/// for (i, x) in xs.iter().enumerate() {
///     for (j, y) in ys.iter().enumerate() {
///         z.push((3.0 * x).sin() * (2.0 * y).cos() + 0.01 * (((i * 7 + j * 13) % 5) as f64 - 2.0));
///     }
/// }
/// let fit = tensor_grid_smoothing(&[&xs, &ys], PointsRef::from_flat(1, &z)?, &[3, 3], 0.3, None)?;
/// assert!(fit.residual <= 0.3);
/// assert!(fit.spline.shape().iter().product::<usize>() < 200);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// - [`Error::TooFew`] for zero directions, or a direction with at most `k_a` coordinates;
/// - [`Error::LengthMismatch`] if `degrees` (or `bbox`) has not one entry per direction or
///   `values` does not hold `Π_a m_a` values;
/// - [`Error::NegativeSmoothing`] for `s < 0` or not finite; [`Error::Degree`] for degree 0
///   or above [`MAX_DEGREE`](crate::MAX_DEGREE);
/// - [`Error::NonFinite`], [`Error::KnotsNotSorted`] or [`Error::InvalidArgument`] for
///   coordinates that are not finite and strictly increasing;
/// - [`Error::ParameterOutOfDomain`] for a coordinate outside its `bbox` interval,
///   [`Error::EmptyDomain`] for an interval that is empty;
/// - [`Error::TooLarge`] if the grid exceeds [`MAX_SCALARS`](crate::MAX_SCALARS);
/// - [`Error::SingularSystem`] if a coefficient has no node under its basis function.
pub fn tensor_grid_smoothing(
    params: &[&[f64]],
    values: PointsRef<'_>,
    degrees: &[usize],
    s: f64,
    bbox: Option<&[(f64, f64)]>,
) -> Result<TensorGridSmoothing> {
    tensor_grid_smoothing_with_progress(params, values, degrees, s, bbox, &Progress::new())
}

/// [`tensor_grid_smoothing`] reporting to `progress` after each round of knot addition and each
/// smoothing weight `p` tried, and stopping with [`Error::Cancelled`] between two of them when
/// its cancel flag is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`tensor_grid_smoothing`], and [`Error::Cancelled`].
pub fn tensor_grid_smoothing_with_progress(
    params: &[&[f64]],
    values: PointsRef<'_>,
    degrees: &[usize],
    s: f64,
    bbox: Option<&[(f64, f64)]>,
    progress: &Progress<'_>,
) -> Result<TensorGridSmoothing> {
    let n = params.len();
    check_n_vars(n)?;
    check_len("degrees (one per grid direction)", n, degrees.len())?;
    if let Some(b) = bbox {
        check_len(
            What::of(Arg::Bbox, "bbox intervals (one per grid direction)"),
            n,
            b.len(),
        )?;
    }
    for &k in degrees {
        check_condition_args(k, s)?;
        if k == 0 {
            return Err(Error::Degree {
                degree: 0,
                reason: "smoothing on a grid needs degree 1 or more in every direction".into(),
            });
        }
    }
    let sizes: Vec<usize> = params.iter().map(|p| p.len()).collect();
    let count = checked_size("grid values (product of the coordinate counts)", &sizes, 1)?;
    check_len(
        "grid values (product of the coordinate counts)",
        count,
        values.len(),
    )?;
    let mut axes = Vec::with_capacity(n);
    for (a, (&x, &k)) in params.iter().zip(degrees).enumerate() {
        check_strictly_increasing(x)?;
        if x.len() <= k {
            return Err(Error::TooFew {
                what: "grid coordinates in a direction (more than its degree)".into(),
                min: k + 1,
                got: x.len(),
            });
        }
        let (lo, hi) = bbox.map_or((x[0], x[x.len() - 1]), |b| b[a]);
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return Err(Error::EmptyDomain { min: lo, max: hi });
        }
        if let Some(&t) = x.iter().find(|&&t| t < lo || t > hi) {
            return Err(Error::ParameterOutOfDomain {
                t,
                min: lo,
                max: hi,
            });
        }
        axes.push(Axis::new(x, k, lo, hi));
    }
    let steps = Steps::new(progress, "smoothing on a grid (knot rounds, weights)");
    if s == 0.0 {
        steps.tick()?;
        let fit = interpolation(params, values, degrees, &mut axes)?;
        steps.finish();
        return Ok(fit);
    }
    let dim = values.dim();
    let center = values.as_slice()[..dim].to_vec();
    let q: Vec<f64> = values
        .as_slice()
        .chunks_exact(dim)
        .flat_map(|v| v.iter().zip(&center).map(|(a, b)| a - b))
        .collect();
    let grid = Grid {
        params,
        q: &q,
        dim,
        count,
    };
    let fit = rounds(&grid, &mut axes, s, &steps)?;
    steps.finish();
    let knots: Vec<KnotVector> = axes
        .iter()
        .map(|ax| KnotVector::new(ax.knots()))
        .collect::<Result<_>>()?;
    let mut c = fit.c;
    for p in c.chunks_exact_mut(dim) {
        p.iter_mut().zip(&center).for_each(|(v, o)| *v += o);
    }
    let spline =
        TensorBSpline::from_knot_vectors(degrees.to_vec(), knots, Points::from_flat(dim, c)?)?;
    Ok(TensorGridSmoothing {
        spline,
        residual: fit.fp,
        p: fit.p,
    })
}

/// `s = 0`: the interpolating spline on FITPACK's knots (`fpregr`). The system is square (one
/// coefficient a node in each direction) and its solution the same as the least squares of
/// [`solve`], so it is solved as [`TensorInterpolation`] solves it: each direction's
/// collocation matrix factored once by banded elimination without pivoting (totally positive,
/// de Boor 1976), one sweep of solves a direction, instead of Givens rotations on every line.
/// The residual is reported as FITPACK reports it for interpolation, `0` (what remains is
/// rounding).
fn interpolation(
    params: &[&[f64]],
    values: PointsRef<'_>,
    degrees: &[usize],
    axes: &mut [Axis<'_>],
) -> Result<TensorGridSmoothing> {
    let knots = axes
        .iter_mut()
        .map(|ax| {
            ax.interpolation();
            KnotVector::new(ax.knots()).map(Some)
        })
        .collect::<Result<_>>()?;
    let spline = TensorInterpolation::new(degrees.to_vec())
        .knot_vectors(knots)
        .interpolate_at(params, values)?;
    Ok(TensorGridSmoothing {
        spline,
        residual: 0.0,
        p: None,
    })
}

/// The data of a smoothing on a grid: the coordinates, the centred values (first direction
/// slowest), their dimension and the number of nodes.
struct Grid<'a> {
    params: &'a [&'a [f64]],
    q: &'a [f64],
    dim: usize,
    count: usize,
}

/// One direction of the grid and its knots, as FITPACK keeps them: the interior knots, the
/// number of coordinates strictly inside each knot span (the first and last coordinates and
/// those on knots excluded) and the residual summed over each span.
struct Axis<'a> {
    x: &'a [f64],
    k: usize,
    lo: f64,
    hi: f64,
    interior: Vec<f64>,
    inside: Vec<usize>,
    span_residual: Vec<f64>,
    /// Knots added at the last addition in this direction, and the residual decrease it gave.
    nplus: usize,
    reduction: f64,
    /// No span holds a coordinate where a knot could go.
    stuck: bool,
}

impl<'a> Axis<'a> {
    fn new(x: &'a [f64], k: usize, lo: f64, hi: f64) -> Self {
        Axis {
            x,
            k,
            lo,
            hi,
            interior: Vec::new(),
            inside: vec![x.len() - 2],
            span_residual: vec![0.0],
            nplus: 0,
            reduction: 0.0,
            stuck: false,
        }
    }

    /// The clamped knot vector: `k + 1` copies of each end around the interior knots.
    fn knots(&self) -> Vec<f64> {
        let mut t = vec![self.lo; self.k + 1];
        t.extend_from_slice(&self.interior);
        t.extend(std::iter::repeat_n(self.hi, self.k + 1));
        t
    }

    /// Interior knots of interpolation: `m − k − 1`.
    fn max_interior(&self) -> usize {
        self.x.len() - self.k - 1
    }

    fn full(&self) -> bool {
        self.stuck || self.interior.len() >= self.max_interior()
    }

    /// FITPACK's knots of interpolation (`fpregr` with `s = 0`): the coordinates
    /// `x_{⌊k/2⌋+1} … x_{m−⌊k/2⌋−2}` for odd `k`, the midpoints of consecutive ones for even `k`.
    fn interpolation(&mut self) {
        let (x, h) = (self.x, self.k / 2);
        self.interior = (0..self.max_interior())
            .map(|l| {
                let j = h + 1 + l;
                if self.k % 2 == 1 {
                    x[j]
                } else {
                    (x[j] + x[j - 1]) * 0.5
                }
            })
            .collect();
    }

    /// The span of each coordinate (the number of interior knots at or below it) and the
    /// residual per span from the residual per coordinate `r`: a coordinate that opens a span
    /// gives half of its residual to the span before (FITPACK `fpgrre`).
    fn span_sums(&mut self, r: &[f64]) {
        let mut sums = vec![0.0; self.interior.len() + 1];
        let mut old = 0;
        for (&x, &v) in self.x.iter().zip(r) {
            let span = self.interior.partition_point(|&t| t <= x);
            sums[span] += v;
            if span != old {
                sums[span] -= 0.5 * v;
                sums[span - 1] += 0.5 * v;
            }
            old = span;
        }
        self.span_residual = sums;
    }

    /// Adds one knot (FITPACK `fpknot`): in the span of largest residual among those holding a
    /// coordinate strictly inside, at its middle such coordinate, the span's residual and
    /// coordinates shared between the two halves. `false` if no span holds a coordinate.
    fn add_knot(&mut self) -> bool {
        let mut best: Option<(usize, usize)> = None;
        let mut fpmax = 0.0;
        let mut begin = 1;
        for (j, (&count, &f)) in self.inside.iter().zip(&self.span_residual).enumerate() {
            if count > 0 && f > fpmax {
                fpmax = f;
                best = Some((j, begin));
            }
            begin += count + 1;
        }
        let Some((j, begin)) = best else {
            self.stuck = true;
            return false;
        };
        let total = self.inside[j];
        let half = total / 2 + 1;
        self.interior.insert(j, self.x[begin + half - 1]);
        self.inside[j] = half - 1;
        self.inside.insert(j + 1, total - half);
        let share = |c: usize| fpmax * c as f64 / total as f64;
        self.span_residual[j] = share(half - 1);
        self.span_residual.insert(j + 1, share(total - half));
        true
    }
}

/// A solve on given knots: the coefficients (centred), the residual, the weight `p` (`None` for
/// least squares) and the residual summed per coordinate of each direction.
struct Solved {
    c: Vec<f64>,
    fp: f64,
    p: Option<f64>,
    marginals: Vec<Vec<f64>>,
}

/// The knot rounds and the smoothing weight (FITPACK `fpregr`).
fn rounds(grid: &Grid<'_>, axes: &mut [Axis<'_>], s: f64, steps: &Steps<'_, '_>) -> Result<Solved> {
    let acc = SMOOTHING_RTOL * s;
    let bound: usize = grid.params.iter().map(|p| p.len()).sum();
    let (mut fp0, mut fpold) = (0.0, 0.0);
    let mut last: Option<usize> = None;
    let mut lsq;
    let mut iterations = 0;
    loop {
        steps.tick()?;
        iterations += 1;
        lsq = solve(grid, axes, f64::INFINITY)?;
        let fp = lsq.fp;
        let polynomial = axes.iter().all(|ax| ax.interior.is_empty());
        if polynomial {
            fp0 = fp;
        }
        let fpms = fp - s;
        if accepts_least_squares(fpms, acc) {
            return Ok(lsq);
        }
        if fpms < 0.0 {
            if polynomial {
                return Ok(lsq);
            }
            break;
        }
        if axes.iter().all(Axis::full) || iterations > bound {
            // interpolation, or no span left to split: the least-squares spline
            return Ok(lsq);
        }
        if let Some(d) = last {
            axes[d].reduction = fpold - fp;
        }
        fpold = fp;
        for (ax, r) in axes.iter_mut().zip(&lsq.marginals) {
            ax.span_sums(r);
        }
        let planned: Vec<usize> = axes
            .iter()
            .map(|ax| {
                if ax.interior.is_empty() {
                    1
                } else {
                    next_nplus(ax.nplus, fpms, ax.reduction, acc)
                }
            })
            .collect();
        // the direction needing the fewest knots, ties to the next one after the last used
        let n = axes.len();
        let start = last.map_or(0, |d| (d + 1) % n);
        let d = (0..n)
            .map(|i| (start + i) % n)
            .filter(|&a| !axes[a].full())
            .min_by_key(|&a| planned[a])
            .unwrap_or(start);
        let ax = &mut axes[d];
        ax.nplus = planned[d];
        for _ in 0..planned[d] {
            if !ax.add_knot() {
                break;
            }
            if ax.interior.len() >= ax.max_interior() {
                // as many knots as interpolation has: its knots (SciPy's regrid does the same)
                ax.interpolation();
                break;
            }
        }
        last = Some(d);
    }
    let fp_inf = lsq.fp;
    let solve_p = |p: f64| -> Result<(Vec<f64>, f64)> {
        let r = solve(grid, axes, p)?;
        Ok((r.c, r.fp))
    };
    match smooth_weight(&solve_p, 1.0, s, fp0, fp_inf, steps)? {
        Some((p, fp, c)) => Ok(Solved {
            c,
            fp,
            p: Some(p),
            marginals: Vec::new(),
        }),
        None => Ok(lsq),
    }
}

/// The coefficients minimising `‖(R_0 ⊗ ⋯ ⊗ R_{N−1}) c − [q; 0]‖²` with `R_a = [A_a; B_a/p]`
/// (`p = ∞`: least squares), by one sweep of banded QR per direction, and the residual of the
/// data on the grid (FITPACK `fpgrre`).
fn solve(grid: &Grid<'_>, axes: &[Axis<'_>], p: f64) -> Result<Solved> {
    let dim = grid.dim;
    let mut shape: Vec<usize> = grid.params.iter().map(|x| x.len()).collect();
    let knots: Vec<Vec<f64>> = axes.iter().map(Axis::knots).collect();
    let mut cur = grid.q.to_vec();
    for (a, (ax, t)) in axes.iter().zip(&knots).enumerate() {
        let (k, m) = (ax.k, shape[a]);
        let nc = t.len() - k - 1;
        let outer: usize = shape[..a].iter().product();
        let inner = shape[a + 1..].iter().product::<usize>() * dim;
        // the rows of A_a: first column and k + 1 values per coordinate
        let mut scratch = BasisScratch::new(k);
        let mut rows = vec![0.0; m * (k + 1)];
        let mut firsts = Vec::with_capacity(m);
        for (i, &x) in ax.x.iter().enumerate() {
            let span = (k + ax.interior.partition_point(|&v| v <= x)).min(nc - 1);
            basis_funs_into(
                t,
                k,
                span,
                x,
                &mut scratch,
                &mut rows[i * (k + 1)..(i + 1) * (k + 1)],
            );
            firsts.push(span - k);
        }
        let penalty = (p.is_finite() && !ax.interior.is_empty()).then(|| jump_rows(t, k).rows);
        let bw = if penalty.is_some() { k + 2 } else { k + 1 };
        let mut next = Vec::with_capacity(outer * nc * inner);
        let mut h = vec![0.0; k + 2];
        let mut y = vec![0.0; inner];
        let mut c = vec![0.0; nc * inner];
        for block in cur.chunks_exact(m * inner).take(outer) {
            let mut qr = BandedQr::new(nc, bw, inner);
            // in column order, as FITPACK: the jump row of knot j before the data rows of
            // span j + 1, so that no rotation fills in beyond a row's band
            let mut jumps = 0;
            for (i, &first) in firsts.iter().enumerate() {
                if let Some(b) = &penalty {
                    while jumps < first {
                        for (hv, v) in h.iter_mut().zip(&b[jumps * (k + 2)..(jumps + 1) * (k + 2)])
                        {
                            *hv = v / p;
                        }
                        y.fill(0.0);
                        qr.add_row(jumps, &mut h, &mut y);
                        jumps += 1;
                    }
                }
                h[..=k].copy_from_slice(&rows[i * (k + 1)..(i + 1) * (k + 1)]);
                y.copy_from_slice(&block[i * inner..(i + 1) * inner]);
                qr.add_row(first, &mut h[..=k], &mut y);
            }
            if let Some(b) = &penalty {
                // the jump rows of the knots after the last coordinate (a wider bbox)
                for (j, row) in b.chunks_exact(k + 2).enumerate().skip(jumps) {
                    for (hv, v) in h.iter_mut().zip(row) {
                        *hv = v / p;
                    }
                    y.fill(0.0);
                    qr.add_row(j, &mut h, &mut y);
                }
            }
            qr.solve(&mut c).map_err(|col| Error::SingularSystem {
                reason: format!(
                    "coefficient {col} of the grid's {} has no grid coordinate under its basis \
                     function; give fewer knots or more coordinates there",
                    NthDirection(a)
                ),
            })?;
            next.extend_from_slice(&c);
        }
        shape[a] = nc;
        cur = next;
    }
    // the residual of every node, summed over the grid and over each direction's lines
    let spline = TensorBSpline::new(
        axes.iter().map(|ax| ax.k).collect(),
        knots,
        Points::from_flat(dim, cur.clone())?,
    )?;
    let mut fitted = vec![0.0; grid.count * dim];
    spline.eval_grid(grid.params, None, &mut fitted)?;
    let sizes: Vec<usize> = grid.params.iter().map(|x| x.len()).collect();
    let mut marginals: Vec<Vec<f64>> = sizes.iter().map(|&m| vec![0.0; m]).collect();
    let mut fp = 0.0;
    let mut index = vec![0usize; sizes.len()];
    for (f, q) in fitted.chunks_exact(dim).zip(grid.q.chunks_exact(dim)) {
        let r: f64 = f.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum();
        fp += r;
        for (marginal, &i) in marginals.iter_mut().zip(&index) {
            marginal[i] += r;
        }
        // the next node, the last direction fastest
        for a in (0..sizes.len()).rev() {
            index[a] += 1;
            if index[a] < sizes[a] {
                break;
            }
            index[a] = 0;
        }
    }
    Ok(Solved {
        c: cur,
        fp,
        p: p.is_finite().then_some(p),
        marginals,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tensor::test_grids::{axis, sample};
    use proptest::prelude::*;

    /// `s = 0` interpolates on FITPACK's knots: the nodes for odd degrees, their midpoints for
    /// even degrees.
    #[test]
    fn zero_s_interpolates_on_fitpack_knots() {
        let (x, y) = (axis(7, 0.3), axis(6, -0.2));
        let z = sample(&[&x, &y], |p| (3.0 * p[0]).sin() + p[1] * p[1] * p[0]);
        let fit = tensor_grid_smoothing(
            &[&x, &y],
            PointsRef::from_flat(1, &z).unwrap(),
            &[3, 2],
            0.0,
            None,
        )
        .unwrap();
        let tx = fit.spline.knots()[0].as_slice();
        assert_eq!(&tx[4..7], &x[2..5]);
        let ty = fit.spline.knots()[1].as_slice();
        let mid: Vec<f64> = (2..5).map(|j| (y[j] + y[j - 1]) * 0.5).collect();
        assert_eq!(&ty[3..6], &mid[..]);
        assert!(fit.residual < 1e-24);
        let mut back = vec![0.0; z.len()];
        fit.spline.eval_grid(&[&x, &y], None, &mut back).unwrap();
        for (a, b) in back.iter().zip(&z) {
            assert!((a - b).abs() < 1e-13);
        }
    }

    /// An `s` above the residual of the polynomial gives the polynomial; the refusals name
    /// their argument.
    #[test]
    fn large_s_gives_the_polynomial_and_bad_input_is_refused() {
        let (x, y) = (axis(9, 0.0), axis(8, 0.1));
        let z = sample(&[&x, &y], |p| (4.0 * p[0]).cos() * p[1]);
        let v = PointsRef::from_flat(1, &z).unwrap();
        let fit = tensor_grid_smoothing(&[&x, &y], v, &[3, 1], 1e6, None).unwrap();
        assert_eq!(fit.spline.shape(), &[4, 2]);
        assert_eq!(fit.p, None);
        assert!(matches!(
            tensor_grid_smoothing(&[&x, &y], v, &[3, 1], -1.0, None),
            Err(Error::NegativeSmoothing { .. })
        ));
        assert!(matches!(
            tensor_grid_smoothing(&[&x, &y], v, &[3, 0], 1.0, None),
            Err(Error::Degree { .. })
        ));
        assert!(matches!(
            tensor_grid_smoothing(&[&x, &y], v, &[3, 1], 1.0, Some(&[(0.0, 1.0), (0.2, 1.0)])),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            tensor_grid_smoothing(&[&x, &y[..7]], v, &[3, 1], 1.0, None),
            Err(Error::LengthMismatch { .. })
        ));
        let wide =
            tensor_grid_smoothing(&[&x, &y], v, &[3, 1], 0.0, Some(&[(-1.0, 2.0), (0.0, 1.0)]))
                .unwrap();
        assert_eq!(wide.spline.domain()[0], (-1.0, 2.0));
    }

    /// A round whose least squares lies above `s` by less than `0.001·s` is the answer (FITPACK
    /// `fpregr`: `abs(fpms).lt.acc`), not a reason to add knots: with `s` just below the
    /// polynomial's residual, the result is that polynomial.
    #[test]
    fn least_squares_within_the_tolerance_above_s_is_kept() {
        let (x, y) = (axis(9, 0.0), axis(13, 0.1));
        let z = sample(&[&x, &y], |p| {
            (3.0 * (p[0] + p[1])).sin() + 0.1 * (37.0 * p[0] * p[1]).sin()
        });
        let v = PointsRef::from_flat(1, &z).unwrap();
        let poly = tensor_grid_smoothing(&[&x, &y], v, &[3, 3], 1e6, None).unwrap();
        let s = poly.residual / (1.0 + 0.5 * SMOOTHING_RTOL);
        let fit = tensor_grid_smoothing(&[&x, &y], v, &[3, 3], s, None).unwrap();
        assert_eq!(fit.spline.shape(), &[4, 4]);
        assert_eq!(fit.p, None);
        assert!(fit.residual > s);
        assert_eq!(fit.residual.to_bits(), poly.residual.to_bits());
        // below the tolerance, knots are added
        let s = poly.residual / (1.0 + 2.0 * SMOOTHING_RTOL);
        let fit = tensor_grid_smoothing(&[&x, &y], v, &[3, 3], s, None).unwrap();
        assert_ne!(fit.spline.shape(), &[4, 4]);
        assert!(fit.residual < (1.0 + SMOOTHING_RTOL) * s);
    }

    proptest! {
        #![proptest_config(crate::oracle::proptest_config(24))]

        /// In two and three directions, the residual is below `s + SMOOTHING_RTOL·s` (above
        /// `s` only for a round's least squares, `p` none), and within SMOOTHING_RTOL of `s`
        /// below it when the result is smoothed (`p` given); adding a constant to
        /// the values adds it to the fit.
        #[test]
        fn residual_meets_s(
            three in any::<bool>(),
            sizes in proptest::collection::vec(6usize..=14, 3),
            degrees in proptest::collection::vec(1usize..=3, 3),
            noise in proptest::collection::vec(-0.2f64..0.2, 53),
            fraction in 0.05f64..0.9,
            offset in -1e3f64..1e3,
        ) {
            let n = if three { 3 } else { 2 };
            let axes: Vec<Vec<f64>> = sizes[..n].iter().map(|&m| axis(m, 0.2)).collect();
            let refs: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
            let mut z = sample(&refs, |p| (2.0 * p[0]).sin() + p[1] * p.iter().sum::<f64>());
            for (i, v) in z.iter_mut().enumerate() {
                *v += noise[i % noise.len()];
            }
            let deg = &degrees[..n];
            // the residual of the polynomial bounds s from above
            let poly = tensor_grid_smoothing(&refs, PointsRef::from_flat(1, &z).unwrap(), deg, 1e12, None).unwrap();
            let s = fraction * poly.residual;
            let fit = tensor_grid_smoothing(&refs, PointsRef::from_flat(1, &z).unwrap(), deg, s, None).unwrap();
            if fit.p.is_some() {
                prop_assert!(fit.residual <= s, "{} > {}", fit.residual, s);
                prop_assert!(fit.residual >= (1.0 - SMOOTHING_RTOL) * s);
            } else {
                prop_assert!(fit.residual < (1.0 + SMOOTHING_RTOL) * s, "{} > {}", fit.residual, s);
            }
            let total: usize = z.len();
            let mut back = vec![0.0; total];
            fit.spline.eval_grid(&refs, None, &mut back).unwrap();
            let rss: f64 = back.iter().zip(&z).map(|(a, b)| (a - b) * (a - b)).sum();
            prop_assert!((rss - fit.residual).abs() <= 1e-9 * (1.0 + rss));
            let shifted: Vec<f64> = z.iter().map(|v| v + offset).collect();
            let moved = tensor_grid_smoothing(&refs, PointsRef::from_flat(1, &shifted).unwrap(), deg, s, None).unwrap();
            prop_assert_eq!(moved.spline.shape(), fit.spline.shape());
            let mut there = vec![0.0; total];
            moved.spline.eval_grid(&refs, None, &mut there).unwrap();
            for (a, b) in there.iter().zip(&back) {
                prop_assert!((a - offset - b).abs() <= 1e-8 * (1.0 + offset.abs()));
            }
        }
    }
}
