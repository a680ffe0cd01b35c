//! The smoothing spline on a grid in `N` directions with a penalty weight `λ_a` per direction,
//! given or chosen by generalised cross-validation: the separable ("sandwich") smoother, one
//! cubic smoothing spline per direction applied mode by mode.
//! `docs/theory/tensor.md#penalised-smoothing-on-grids`.

use std::cell::Cell;

use crate::error::{Error, NthDirection, Result};
use crate::fit::banded::SymBand;
use crate::fit::{brent_min, FitData, Lambda, Smoother, Steps, GCV_ROUNDING_SHARE};
use crate::interpolate::parametrization::check_strictly_increasing;
use crate::natural_cubic_spline;
use crate::numeric::progress::Progress;
use crate::points::{Points, PointsRef};
use crate::tensor::spline::{check_len, check_n_vars, checked_size, TensorBSpline};
use crate::Arg;

/// The result of [`tensor_grid_smoothing_spline`].
#[derive(Debug, Clone, PartialEq)]
pub struct TensorGridSmoothingSpline {
    /// The fitted spline: cubic in every direction, with a knot at every grid coordinate
    /// (`m_a + 2` coefficients in direction `a`).
    pub spline: TensorBSpline,
    /// The penalty weight `λ_a` of each direction (given, or chosen by GCV).
    pub lambdas: Vec<f64>,
    /// `RSS = Σ_k |S(x̄_k) − q_k|²` over the nodes of the grid and the value coordinates.
    pub residual: f64,
    /// `tr S = Π_a tr S_a`, the effective number of parameters of the smoother, as
    /// `M·(1 − share)` from the score's denominator share `1 − tr S/M`.
    pub trace: f64,
    /// The GCV score `V = (RSS/(M·dim)) / (1 − tr S / M)²` at [`Self::lambdas`], `M = Π_a m_a`
    /// the number of nodes (`+∞` where it is within rounding of `0/0`, near interpolation).
    pub gcv: f64,
}

/// The smoothing spline on the grid `params[0] × ⋯ × params[N−1]` with the penalty weight
/// `λ_a` of direction `a`: the separable penalised least squares of Eilers, Currie & Durbán
/// (2006, "Fast and compact smoothing on large multidimensional grids") and Xiao, Li & Ruppert
/// (2013, "Fast bivariate P-splines: the sandwich smoother", JRSS-B 75(3)), with the cubic
/// smoothing spline of [`smoothing_spline`](crate::fit::smoothing_spline) as the smoother of
/// each direction. `docs/theory/tensor.md#penalised-smoothing-on-grids`.
///
/// In direction `a`, with `B_a` the clamped cubic B-splines with a knot at every coordinate
/// (`m_a × (m_a + 2)`) and `Ω_a = ∫ B_a'' B_a''ᵀ`, the coefficients are
/// `C = Y ×_0 H_0 ×_1 ⋯ ×_{N−1} H_{N−1}` with `H_a = (B_aᵀB_a + λ_a Ω_a)⁻¹ B_aᵀ`: one sweep of
/// banded solves (`UᵀDU`, half-bandwidth 3) per direction, never an `N`-dimensional system. It
/// minimises `‖(⊗_a B_a) c − y‖² + cᵀ (⊗_a (B_aᵀB_a + λ_a Ω_a) − ⊗_a B_aᵀB_a) c`, whose penalty
/// holds the `λ_a Ω_a` of each direction and their products. `N = 1` is the smoothing spline of
/// a curve, with the same bits. `λ_a = 0` interpolates along direction `a` by the natural
/// cubic spline (the limit of `λ_a → 0`, as for curves).
///
/// With [`Lambda::Gcv`] in some directions, their `λ_a` minimise the GCV score
/// `V = (RSS/(M·dim)) / (1 − tr S/M)²` of the whole grid (`M` nodes): the smoother is the
/// Kronecker product `S = ⊗_a S_a`, `S_a = B_a H_a`, so `tr S = Π_a tr S_a` and
/// `1 − tr S/M = 1 − Π_a (1 − s_a)`, summed without cancellation from each direction's residual
/// share `s_a = 1 − tr S_a/m_a`, computed as the curve's from the band of an inverse (Hutchinson
/// & de Hoog 1985). The minimisation is a
/// coordinate search over `log λ_a`, starting from `tr(B_aᵀB_a)/tr(Ω_a)` (the penalty weighing
/// like the data over one knot interval): for each such direction in turn, the data smoothed
/// along every other direction once, then the scan and Brent's minimisation of
/// [`smoothing_spline`](crate::fit::smoothing_spline)'s GCV (one sweep along that direction a
/// score), cycles repeated until no `log₁₀ λ_a` moves by more than [`GCV_CYCLE_TOL`] (at most
/// [`GCV_MAX_CYCLES`]). The values are shifted by the first node's before the solves (the
/// smoother reproduces constants, so the fit shifts with them).
///
/// Cost: a fit is `O(Σ_a (Π_{b<a} (m_b + 2)) · m_a · Π_{b>a} m_b · dim)` (one banded solve per
/// line); a GCV score one sweep of that size. Memory: two grids of coefficients.
///
/// ```
/// use lekalo::fit::Lambda;
/// use lekalo::{tensor_grid_smoothing_spline, PointsRef};
/// let xs: Vec<f64> = (0..30).map(|i| i as f64 / 29.0).collect();
/// let ys: Vec<f64> = (0..20).map(|j| j as f64 / 19.0).collect();
/// let mut z = Vec::new();
/// for (i, x) in xs.iter().enumerate() {
///     for (j, y) in ys.iter().enumerate() {
///         z.push((3.0 * x).sin() * y + 0.05 * (((i * 7 + j * 13) % 5) as f64 - 2.0));
///     }
/// }
/// let v = PointsRef::from_flat(1, &z)?;
/// let fit = tensor_grid_smoothing_spline(&[&xs, &ys], v, &[Lambda::Gcv, Lambda::Gcv])?;
/// assert!(fit.lambdas.iter().all(|&l| l > 0.0));
/// assert!(fit.trace < 600.0 && fit.residual > 0.0);
/// let given = tensor_grid_smoothing_spline(&[&xs, &ys], v, &[Lambda::Given(1e-3), Lambda::Given(0.0)])?;
/// assert_eq!(given.spline.shape(), &[32, 22]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// - [`Error::TooFew`] for zero directions, or a direction with fewer than 3 coordinates;
/// - [`Error::LengthMismatch`] if `lambdas` has not one entry per direction or `values` does
///   not hold `Π_a m_a` values;
/// - [`Error::NegativeSmoothing`] for a given `λ_a` negative or not finite;
/// - [`Error::NonFinite`], [`Error::KnotsNotSorted`] or [`Error::InvalidArgument`] for
///   coordinates that are not finite and strictly increasing (the values are finite by
///   [`PointsRef`]'s construction);
/// - [`Error::TooLarge`] if the coefficients exceed [`MAX_SCALARS`](crate::MAX_SCALARS);
/// - [`Error::SingularSystem`] if no weight of a GCV direction gives a finite score.
pub fn tensor_grid_smoothing_spline(
    params: &[&[f64]],
    values: PointsRef<'_>,
    lambdas: &[Lambda],
) -> Result<TensorGridSmoothingSpline> {
    tensor_grid_smoothing_spline_with_progress(params, values, lambdas, &Progress::new())
}

/// Largest change of any `log₁₀ λ_a` in a cycle of the coordinate search of
/// [`tensor_grid_smoothing_spline`] at which the search stops: a thousandth of a decade, far
/// below the width of the score's minima (decades).
pub const GCV_CYCLE_TOL: f64 = 1e-3;

/// Most cycles of the coordinate search of [`tensor_grid_smoothing_spline`] over the GCV
/// directions.
pub const GCV_MAX_CYCLES: usize = 8;

/// [`tensor_grid_smoothing_spline`] reporting to `progress` after each GCV score, and stopping
/// with [`Error::Cancelled`] between two of them when its cancel flag is set. The result is the
/// same with or without the hook.
///
/// # Errors
/// As [`tensor_grid_smoothing_spline`], and [`Error::Cancelled`].
pub fn tensor_grid_smoothing_spline_with_progress(
    params: &[&[f64]],
    values: PointsRef<'_>,
    lambdas: &[Lambda],
    progress: &Progress<'_>,
) -> Result<TensorGridSmoothingSpline> {
    let grid = PenalizedGrid::new(params, values, lambdas)?;
    let steps = Steps::new(progress, "smoothing spline on a grid (GCV scores)");
    let mut lam: Vec<f64> = grid
        .axes
        .iter()
        .zip(lambdas)
        .map(|(ax, l)| match l {
            Lambda::Given(v) => *v,
            Lambda::Gcv => 10f64.powf(ax.scan.0 + 12.0),
        })
        .collect();
    let searched: Vec<usize> = (0..lambdas.len())
        .filter(|&a| lambdas[a] == Lambda::Gcv)
        .collect();
    if !searched.is_empty() {
        grid.search(&mut lam, &searched, &steps)?;
    }
    steps.tick()?;
    let maps: Vec<AxisMap> = grid
        .axes
        .iter()
        .zip(&lam)
        .map(|(ax, &l)| ax.map(l))
        .collect();
    let (gcv, trace) = grid.score_of(&maps)?;
    let mut c = grid.q.clone();
    let mut shape = grid.sizes.clone();
    for (a, (ax, map)) in grid.axes.iter().zip(&maps).enumerate() {
        c = ax.coefficients(map, &c, &shape, a, grid.dim)?;
        shape[a] += 2;
    }
    for p in c.chunks_exact_mut(grid.dim) {
        p.iter_mut().zip(&grid.center).for_each(|(v, o)| *v += o);
    }
    let knots = grid
        .axes
        .iter()
        .map(|ax| ax.smoother.knots.clone())
        .collect();
    let spline = TensorBSpline::new(
        vec![3; grid.axes.len()],
        knots,
        Points::from_flat(grid.dim, c)?,
    )?;
    let mut fitted = vec![0.0; values.as_slice().len()];
    spline.eval_grid(params, None, &mut fitted)?;
    let residual = fitted
        .iter()
        .zip(values.as_slice())
        .map(|(f, q)| (f - q) * (f - q))
        .sum();
    steps.finish();
    Ok(TensorGridSmoothingSpline {
        spline,
        lambdas: lam,
        residual,
        trace,
        gcv,
    })
}

/// The GCV score `V = (RSS/(M·dim)) / (1 − tr S/M)²` of [`tensor_grid_smoothing_spline`] with
/// the weights `lambdas` (one `λ_a ≥ 0` per direction), the criterion its GCV minimises: `+∞`
/// where `M − tr S < √ε·M` or `RSS < ε·TSS` (both within rounding of 0, near interpolation).
/// `N = 1` is [`gcv_score`](crate::fit::gcv_score). O(one fit).
///
/// # Errors
/// As [`tensor_grid_smoothing_spline`].
pub fn tensor_grid_gcv_score(
    params: &[&[f64]],
    values: PointsRef<'_>,
    lambdas: &[f64],
) -> Result<f64> {
    let given: Vec<Lambda> = lambdas.iter().map(|&l| Lambda::Given(l)).collect();
    let grid = PenalizedGrid::new(params, values, &given)?;
    let maps: Vec<AxisMap> = grid
        .axes
        .iter()
        .zip(lambdas)
        .map(|(ax, &l)| ax.map(l))
        .collect();
    Ok(grid.score_of(&maps)?.0)
}

/// The validated data of a smoothing on a grid: each direction's smoother, the values minus
/// the first node's (first direction slowest), their spread about their mean.
struct PenalizedGrid {
    axes: Vec<AxisSmoother>,
    sizes: Vec<usize>,
    dim: usize,
    center: Vec<f64>,
    q: Vec<f64>,
    /// `TSS = Σ_k |q_k − q̄|²`: the scale of the GCV score's rounding floor.
    spread: f64,
}

impl PenalizedGrid {
    fn new(params: &[&[f64]], values: PointsRef<'_>, lambdas: &[Lambda]) -> Result<Self> {
        let n = params.len();
        check_n_vars(n)?;
        check_len(
            "smoothing weights λ (one per grid direction)",
            n,
            lambdas.len(),
        )?;
        for l in lambdas {
            if let Lambda::Given(v) = *l {
                if !(v >= 0.0 && v.is_finite()) {
                    return Err(Error::NegativeSmoothing {
                        what: Arg::Lambda.into(),
                        value: v,
                    });
                }
            }
        }
        let sizes: Vec<usize> = params.iter().map(|p| p.len()).collect();
        let count = checked_size("grid values (product of the coordinate counts)", &sizes, 1)?;
        check_len(
            "grid values (product of the coordinate counts)",
            count,
            values.len(),
        )?;
        let dim = values.dim();
        let net: Vec<usize> = sizes.iter().map(|m| m.saturating_add(2)).collect();
        checked_size("coefficients of the smoothing spline", &net, dim)?;
        let mut axes = Vec::with_capacity(n);
        for &x in params {
            check_strictly_increasing(x)?;
            if x.len() < 3 {
                return Err(Error::TooFew {
                    what: "grid coordinates in a direction of a smoothing spline".into(),
                    min: 3,
                    got: x.len(),
                });
            }
            axes.push(AxisSmoother::new(x)?);
        }
        let center = values.as_slice()[..dim].to_vec();
        let q: Vec<f64> = values
            .as_slice()
            .chunks_exact(dim)
            .flat_map(|v| v.iter().zip(&center).map(|(a, b)| a - b))
            .collect();
        let spread = (0..dim)
            .map(|c| {
                let mean = q.iter().skip(c).step_by(dim).sum::<f64>() / count as f64;
                q.iter()
                    .skip(c)
                    .step_by(dim)
                    .map(|v| (v - mean) * (v - mean))
                    .sum::<f64>()
            })
            .sum();
        Ok(PenalizedGrid {
            axes,
            sizes,
            dim,
            center,
            q,
            spread,
        })
    }

    /// The values smoothed along every direction except `skip`.
    fn smoothed_except(&self, maps: &[AxisMap], skip: Option<usize>) -> Result<Vec<f64>> {
        let mut z = self.q.clone();
        for (a, (ax, map)) in self.axes.iter().zip(maps).enumerate() {
            if Some(a) != skip {
                z = ax.smooth(map, &z, &self.sizes, a, self.dim)?;
            }
        }
        Ok(z)
    }

    /// The GCV score of the fitted values `fitted` with `1 − tr S/M = share`, as
    /// [`tensor_grid_gcv_score`] floors it.
    fn score(&self, fitted: &[f64], share: f64) -> f64 {
        let rss: f64 = self
            .q
            .iter()
            .zip(fitted)
            .map(|(y, f)| (y - f) * (y - f))
            .sum();
        let m = self.q.len() as f64 / self.dim as f64;
        if share < GCV_ROUNDING_SHARE || rss < GCV_ROUNDING_SHARE * GCV_ROUNDING_SHARE * self.spread
        {
            return f64::INFINITY;
        }
        (rss / (m * self.dim as f64)) / (share * share)
    }

    /// The GCV score and `tr S = M·(1 − share)` of the maps `maps`.
    fn score_of(&self, maps: &[AxisMap]) -> Result<(f64, f64)> {
        let share = grid_share(maps.iter().map(AxisMap::share));
        let fitted = self.smoothed_except(maps, None)?;
        let m = self.q.len() as f64 / self.dim as f64;
        Ok((self.score(&fitted, share), m * (1.0 - share)))
    }

    /// The coordinate search of the GCV weights of the directions `searched`
    /// ([`tensor_grid_smoothing_spline`]), starting from `lam`.
    fn search(&self, lam: &mut [f64], searched: &[usize], steps: &Steps<'_, '_>) -> Result<()> {
        let stopped = Cell::new(None);
        let cancelled = |stopped: &Cell<Option<Error>>| stopped.take().map_or(Ok(()), Err);
        let cycles = if searched.len() == 1 {
            1
        } else {
            GCV_MAX_CYCLES
        };
        for _ in 0..cycles {
            let mut moved: f64 = 0.0;
            for &d in searched {
                let maps: Vec<AxisMap> = self
                    .axes
                    .iter()
                    .zip(lam.iter())
                    .map(|(ax, &l)| ax.map(l))
                    .collect();
                let z = self.smoothed_except(&maps, Some(d))?;
                let shares: Vec<f64> = maps.iter().map(AxisMap::share).collect();
                let ax = &self.axes[d];
                let f = |e: f64| {
                    if let Err(err) = steps.tick() {
                        stopped.set(Some(err));
                        return f64::INFINITY;
                    }
                    // a system that cannot be factored scores +∞, as for curves
                    let Ok(map) = ax.penalized(10f64.powf(e)) else {
                        return f64::INFINITY;
                    };
                    let share = grid_share((shares.iter().enumerate()).map(|(a, &s)| {
                        if a == d {
                            map.share()
                        } else {
                            s
                        }
                    }));
                    match ax.smooth(&map, &z, &self.sizes, d, self.dim) {
                        Ok(fitted) => self.score(&fitted, share),
                        Err(_) => f64::INFINITY,
                    }
                };
                let (lo, hi, n_grid) = ax.scan;
                let grid: Vec<f64> = (0..=n_grid)
                    .map(|i| lo + (hi - lo) * i as f64 / n_grid as f64)
                    .collect();
                let vals: Vec<f64> = grid.iter().map(|&e| f(e)).collect();
                cancelled(&stopped)?;
                let mut best = (f64::INFINITY, 0);
                for (i, &v) in vals.iter().enumerate() {
                    if v < best.0 {
                        best = (v, i);
                    }
                }
                if !best.0.is_finite() {
                    return Err(Error::SingularSystem {
                        reason: format!(
                            "no smoothing weight λ of the grid's {} gives a finite GCV score; \
                             give λ for it",
                            NthDirection(d)
                        ),
                    });
                }
                let i = best.1;
                let (a, b) = (grid[i.saturating_sub(1)], grid[(i + 1).min(n_grid)]);
                let e = brent_min(f, a, b, grid[i], best.0, 1e-7);
                cancelled(&stopped)?;
                moved = moved.max((e - lam[d].log10()).abs());
                lam[d] = 10f64.powf(e);
            }
            if moved <= GCV_CYCLE_TOL {
                break;
            }
        }
        Ok(())
    }
}

/// The smoother of one direction: the cubic smoothing spline's banded pieces for its
/// coordinates (knots at every coordinate, unit weights) and its GCV scan in `log₁₀ λ`.
struct AxisSmoother {
    smoother: Smoother,
    x: Vec<f64>,
    scan: (f64, f64, usize),
}

/// The linear map of one direction for one `λ`: the factored `BᵀB + λΩ` with the residual
/// share `s_a = 1 − tr S_a/m_a`, or natural cubic interpolation (`λ = 0`, or `λ` below the
/// rounding of `BᵀB`), `s_a = 0`.
enum AxisMap {
    Penalized { matrix: SymBand, share: f64 },
    Interpolate,
}

impl AxisMap {
    fn share(&self) -> f64 {
        match self {
            AxisMap::Penalized { share, .. } => *share,
            AxisMap::Interpolate => 0.0,
        }
    }
}

/// `1 − tr S/M = 1 − Π_a (1 − s_a)` from the directions' shares `s_a = 1 − tr S_a/m_a`,
/// accumulated as `s_a + (1 − s_a)·(share of the directions before)`: a sum of non-negative
/// terms, without the cancellation of `1 − Π_a tr S_a/m_a` near interpolation; `s_0` itself for
/// one direction (`docs/theory/tensor.md#penalised-smoothing-on-grids`).
fn grid_share(shares: impl IntoIterator<Item = f64>) -> f64 {
    shares.into_iter().fold(0.0, |acc, s| s + (1.0 - s) * acc)
}

impl AxisSmoother {
    fn new(x: &[f64]) -> Result<Self> {
        let zeros = vec![0.0; x.len()];
        let smoother = Smoother::new(&FitData::new(PointsRef::from_flat(1, &zeros)?, x)?)?;
        let scan = smoother.gcv_scan();
        Ok(AxisSmoother {
            smoother,
            x: x.to_vec(),
            scan,
        })
    }

    fn map(&self, lam: f64) -> AxisMap {
        if lam == 0.0 {
            return AxisMap::Interpolate;
        }
        // λΩ below the rounding of BᵀB (unit weights): the λ → 0 limit, as for curves
        self.penalized(lam).unwrap_or(AxisMap::Interpolate)
    }

    /// The factored map of `λ > 0`, or the factorisation's error.
    fn penalized(&self, lam: f64) -> Result<AxisMap> {
        let matrix = self.smoother.factored(lam)?;
        let share = self.smoother.residual_dof(lam, &matrix) / self.x.len() as f64;
        Ok(AxisMap::Penalized { matrix, share })
    }

    /// The coefficients along direction `a` of the tensor `cur` (shape `shape`, `dim` values a
    /// node): `H_a` applied to every line, `m_a` values becoming `m_a + 2` coefficients.
    fn coefficients(
        &self,
        map: &AxisMap,
        cur: &[f64],
        shape: &[usize],
        a: usize,
        dim: usize,
    ) -> Result<Vec<f64>> {
        let m = shape[a];
        let nc = m + 2;
        let outer: usize = shape[..a].iter().product();
        let inner = shape[a + 1..].iter().product::<usize>() * dim;
        let mut out = Vec::with_capacity(outer * nc * inner);
        for block in cur.chunks_exact(m * inner).take(outer) {
            match map {
                AxisMap::Penalized { matrix, .. } => {
                    // Bᵀy in the order of the curve's assembly (`Smoother::new`), so that one
                    // direction gives the curve's bits
                    let mut rhs = vec![0.0; nc * inner];
                    for (k, (nb, &first)) in self
                        .smoother
                        .basis
                        .iter()
                        .zip(&self.smoother.first)
                        .enumerate()
                    {
                        for c in 0..inner {
                            let v = block[k * inner + c];
                            for (i, b) in nb.iter().enumerate() {
                                rhs[(first + i) * inner + c] += 1.0 * b * v;
                            }
                        }
                    }
                    matrix.solve(&mut rhs, inner);
                    out.extend_from_slice(&rhs);
                }
                AxisMap::Interpolate => {
                    let curve = natural_cubic_spline(&self.x, PointsRef::from_flat(inner, block)?)?;
                    out.extend_from_slice(curve.control_points().as_slice());
                }
            }
        }
        Ok(out)
    }

    /// The smoothed values along direction `a`: `S_a = B_a H_a` applied to every line (the
    /// values themselves for interpolation).
    fn smooth(
        &self,
        map: &AxisMap,
        cur: &[f64],
        shape: &[usize],
        a: usize,
        dim: usize,
    ) -> Result<Vec<f64>> {
        if let AxisMap::Interpolate = map {
            return Ok(cur.to_vec());
        }
        let c = self.coefficients(map, cur, shape, a, dim)?;
        let m = shape[a];
        let nc = m + 2;
        let inner = shape[a + 1..].iter().product::<usize>() * dim;
        let mut out = vec![0.0; cur.len()];
        for (block, coef) in out
            .chunks_exact_mut(m * inner)
            .zip(c.chunks_exact(nc * inner))
        {
            for (k, (nb, &first)) in self
                .smoother
                .basis
                .iter()
                .zip(&self.smoother.first)
                .enumerate()
            {
                for col in 0..inner {
                    block[k * inner + col] = (0..4)
                        .map(|i| nb[i] * coef[(first + i) * inner + col])
                        .sum();
                }
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::{gcv_score, smoothing_spline};
    use crate::tensor::test_grids::{axis, sample};
    use proptest::prelude::*;

    /// A deterministic pattern of noise in `[-1, 1]` (splitmix64 of `k`).
    fn noise(k: usize) -> f64 {
        let mut z = (k as u64)
            .wrapping_add(1)
            .wrapping_mul(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        2.0 * ((z ^ (z >> 31)) as f64 / 2f64.powi(64)) - 1.0
    }

    /// One direction is the smoothing spline of a curve: the same coefficients bit for bit for
    /// a given λ, the same λ chosen by GCV and the same score; λ = 0 interpolates as the
    /// curve's natural spline does.
    #[test]
    fn one_direction_is_the_curve_smoothing_spline() {
        let x = axis(40, 0.4);
        let y: Vec<f64> = x
            .iter()
            .enumerate()
            .flat_map(|(k, t)| [(5.0 * t).sin() + 0.1 * noise(k), 1e3 + t * t])
            .collect();
        let pts = PointsRef::from_flat(2, &y).unwrap();
        let data = FitData::new(pts, &x).unwrap();
        for lam in [1e-6, 3e-3, 0.4, 25.0] {
            let grid = tensor_grid_smoothing_spline(&[&x], pts, &[Lambda::Given(lam)]).unwrap();
            let curve = smoothing_spline(&data, Lambda::Given(lam)).unwrap().curve;
            assert_eq!(
                grid.spline.control_points().as_slice(),
                curve.control_points().as_slice(),
                "λ = {lam}"
            );
            assert_eq!(grid.spline.knots()[0].as_slice(), curve.knots().as_slice());
            assert_eq!(
                tensor_grid_gcv_score(&[&x], pts, &[lam]).unwrap(),
                gcv_score(&data, lam).unwrap()
            );
        }
        let grid = tensor_grid_smoothing_spline(&[&x], pts, &[Lambda::Gcv]).unwrap();
        let curve = smoothing_spline(&data, Lambda::Gcv).unwrap();
        assert_eq!(Some(grid.lambdas[0]), curve.report.lambda);
        assert_eq!(
            grid.spline.control_points().as_slice(),
            curve.curve.control_points().as_slice()
        );
        let zero = tensor_grid_smoothing_spline(&[&x], pts, &[Lambda::Given(0.0)]).unwrap();
        let natural = smoothing_spline(&data, Lambda::Given(0.0)).unwrap().curve;
        for (a, b) in zero
            .spline
            .control_points()
            .as_slice()
            .iter()
            .zip(natural.control_points().as_slice())
        {
            assert!((a - b).abs() <= 1e-12 * 1e3, "{a} vs {b}");
        }
        assert!(zero.residual <= 1e-20 * 1e6 * 40.0, "{}", zero.residual);
    }

    /// Dense `n × n` solve by Gaussian elimination with partial pivoting (tests only).
    fn dense_solve(mut a: Vec<f64>, mut b: Vec<f64>, n: usize) -> Vec<f64> {
        for col in 0..n {
            let piv = (col..n)
                .max_by(|&i, &j| a[i * n + col].abs().total_cmp(&a[j * n + col].abs()))
                .unwrap();
            for k in 0..n {
                a.swap(col * n + k, piv * n + k);
            }
            b.swap(col, piv);
            for r in col + 1..n {
                let f = a[r * n + col] / a[col * n + col];
                for k in col..n {
                    a[r * n + k] -= f * a[col * n + k];
                }
                b[r] -= f * b[col];
            }
        }
        for r in (0..n).rev() {
            let s: f64 = (r + 1..n).map(|k| a[r * n + k] * b[k]).sum();
            b[r] = (b[r] - s) / a[r * n + r];
        }
        b
    }

    /// The dense matrix of a symmetric band (`a[i·(b+1) + k]` the entry `(i, i + k)`).
    fn dense(s: &SymBand) -> Vec<f64> {
        let (n, w) = (s.n, s.b + 1);
        let mut d = vec![0.0; n * n];
        for i in 0..n {
            for k in 0..w.min(n - i) {
                d[i * n + i + k] = s.a[i * w + k];
                d[(i + k) * n + i] = s.a[i * w + k];
            }
        }
        d
    }

    /// `m − tr S` of the cubic smoothing spline at `x` with unit weights and weight `lam`, by
    /// Reinsch's form `I − S = λ Q (R + λ QᵀQ)⁻¹ Qᵀ` (Green & Silverman 1994, §2.3), dense.
    fn reinsch_residual(x: &[f64], lam: f64) -> f64 {
        let m = x.len();
        let k = m - 2;
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let mut q = vec![0.0; m * k];
        let mut r = vec![0.0; k * k];
        for j in 0..k {
            q[j * k + j] = 1.0 / h[j];
            q[(j + 1) * k + j] = -1.0 / h[j] - 1.0 / h[j + 1];
            q[(j + 2) * k + j] = 1.0 / h[j + 1];
            r[j * k + j] = (h[j] + h[j + 1]) / 3.0;
            if j + 1 < k {
                r[j * k + j + 1] = h[j + 1] / 6.0;
                r[(j + 1) * k + j] = h[j + 1] / 6.0;
            }
        }
        let qtq: Vec<f64> = (0..k * k)
            .map(|e| (0..m).map(|i| q[i * k + e / k] * q[i * k + e % k]).sum())
            .collect();
        let a: Vec<f64> = r.iter().zip(&qtq).map(|(r, g)| r + lam * g).collect();
        (0..k)
            .map(|j| {
                let col: Vec<f64> = (0..k).map(|i| lam * qtq[i * k + j]).collect();
                dense_solve(a.clone(), col, k)[j]
            })
            .sum()
    }

    /// Every direction all but interpolating (`λ_a` from 1e-5 to 1e-13 times
    /// `tr(B_aᵀB_a)/tr(Ω_a)`), in two and three directions: the residual share `1 − tr S/M`
    /// agrees with Reinsch's form combined as `−expm1(Σ_a ln_1p(−r_a/m_a))` to rounding, the
    /// reported trace to its last place, and the score with `RSS/(M·(share)²)` of the
    /// reference share; below the floor `√ε` the score is `+∞`. Computed as `1 − Π_a tr S_a/m_a`
    /// with `tr S_a` from the band of the inverse, the share is 8e-6 off (relative) at 1e-6 and
    /// 2e-3 at 1e-7.
    #[test]
    fn gcv_share_near_interpolation_in_every_direction_is_accurate() {
        let f = |p: &[f64]| (2.0 * p[0]).sin() * (1.0 + p[1]) + p.get(2).map_or(0.0, |z| z * z);
        for xs in [
            vec![axis(9, 0.3), axis(8, -0.4)],
            vec![axis(7, 0.3), axis(6, -0.2), axis(5, 0.1)],
        ] {
            let refs: Vec<&[f64]> = xs.iter().map(Vec::as_slice).collect();
            let z: Vec<f64> = sample(&refs, f)
                .iter()
                .enumerate()
                .map(|(k, v)| v + 0.3 * noise(k))
                .collect();
            let v = PointsRef::from_flat(1, &z).unwrap();
            let m = z.len() as f64;
            let axes: Vec<AxisSmoother> =
                refs.iter().map(|x| AxisSmoother::new(x).unwrap()).collect();
            for e in [-5.0, -6.0, -7.0, -8.0, -9.0, -10.0, -11.0, -12.0] {
                // λ_a = 10^(e − a/2) times the direction's scale tr(BᵀB)/tr(Ω)
                let lams: Vec<f64> = axes
                    .iter()
                    .enumerate()
                    .map(|(a, ax)| 10f64.powf(ax.scan.0 + 12.0 + e - 0.5 * a as f64))
                    .collect();
                let reference = -refs
                    .iter()
                    .zip(&lams)
                    .map(|(x, &l)| (-reinsch_residual(x, l) / x.len() as f64).ln_1p())
                    .sum::<f64>()
                    .exp_m1();
                let share = grid_share(axes.iter().zip(&lams).map(|(ax, &l)| ax.map(l).share()));
                assert!(
                    (share - reference).abs() <= 1e-10 * reference,
                    "1e{e}: share {share:e} vs {reference:e}"
                );
                let given: Vec<Lambda> = lams.iter().map(|&l| Lambda::Given(l)).collect();
                let fit = tensor_grid_smoothing_spline(&refs, v, &given).unwrap();
                let reported = 1.0 - fit.trace / m;
                assert!(
                    (reported - reference).abs() <= 1e-9 * reference + 4.0 * f64::EPSILON,
                    "1e{e}: 1 − tr S/M = {reported:e} vs {reference:e}"
                );
                if reference >= 2.0 * GCV_ROUNDING_SHARE {
                    let expected = fit.residual / m / (reference * reference);
                    assert!(
                        (fit.gcv - expected).abs() <= 1e-7 * expected,
                        "1e{e}: score {} vs {expected}",
                        fit.gcv
                    );
                } else if reference <= 0.5 * GCV_ROUNDING_SHARE {
                    assert_eq!(fit.gcv, f64::INFINITY, "1e{e}");
                }
            }
        }
    }

    /// In two directions the sweeps solve `(M_0 ⊗ M_1) c = (B_0 ⊗ B_1)ᵀ y`, `M_a = B_aᵀB_a +
    /// λ_a Ω_a`: the same coefficients as a dense solve of the Kronecker system.
    #[test]
    fn two_directions_solve_the_kronecker_system() {
        let (x0, x1) = (axis(7, 0.3), axis(6, -0.5));
        let z: Vec<f64> = sample(&[&x0, &x1], |p| (3.0 * p[0]).cos() * p[1].exp())
            .iter()
            .enumerate()
            .map(|(k, v)| v + 0.05 * noise(k))
            .collect();
        let lam = [0.01, 0.5];
        let fit = tensor_grid_smoothing_spline(
            &[&x0, &x1],
            PointsRef::from_flat(1, &z).unwrap(),
            &[Lambda::Given(lam[0]), Lambda::Given(lam[1])],
        )
        .unwrap();
        // the dense pieces of each direction: B (m × (m + 2)) and M
        let pieces: Vec<(Vec<f64>, Vec<f64>, usize, usize)> = [&x0, &x1]
            .iter()
            .zip(lam)
            .map(|(x, l)| {
                let ax = AxisSmoother::new(x).unwrap();
                let (m, nc) = (x.len(), x.len() + 2);
                let mut b = vec![0.0; m * nc];
                for (k, (nb, &first)) in
                    ax.smoother.basis.iter().zip(&ax.smoother.first).enumerate()
                {
                    for (i, v) in nb.iter().enumerate() {
                        b[k * nc + first + i] = *v;
                    }
                }
                let g = dense(&ax.smoother.gram);
                let o = dense(&ax.smoother.omega);
                let mm: Vec<f64> = g.iter().zip(&o).map(|(g, o)| g + l * o).collect();
                (b, mm, m, nc)
            })
            .collect();
        let (b0, m0, r0, n0) = &pieces[0];
        let (b1, m1, r1, n1) = &pieces[1];
        let n = n0 * n1;
        let mut k = vec![0.0; n * n];
        let mut rhs = vec![0.0; n];
        for i0 in 0..*n0 {
            for i1 in 0..*n1 {
                let row = i0 * n1 + i1;
                for j0 in 0..*n0 {
                    for j1 in 0..*n1 {
                        k[row * n + j0 * n1 + j1] = m0[i0 * n0 + j0] * m1[i1 * n1 + j1];
                    }
                }
                for a in 0..*r0 {
                    for b in 0..*r1 {
                        rhs[row] += b0[a * n0 + i0] * b1[b * n1 + i1] * z[a * r1 + b];
                    }
                }
            }
        }
        // the sweeps' coefficients solve the Kronecker system to rounding: a backward error of
        // a few ε (‖K c − r‖ against ‖K‖‖c‖ + ‖r‖, maximum norms)
        let got = fit.spline.control_points().as_slice();
        let norm = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let k_norm = (0..n)
            .map(|i| k[i * n..(i + 1) * n].iter().map(|v| v.abs()).sum::<f64>())
            .fold(0.0_f64, f64::max);
        let residual: Vec<f64> = (0..n)
            .map(|i| {
                k[i * n..(i + 1) * n]
                    .iter()
                    .zip(got)
                    .map(|(a, b)| a * b)
                    .sum::<f64>()
                    - rhs[i]
            })
            .collect();
        let backward = norm(&residual) / (k_norm * norm(got) + norm(&rhs));
        assert!(backward < 1e-14, "backward error {backward:e}");
        // and agree with a dense elimination of it to the accuracy its condition allows
        // (cond(M_0 ⊗ M_1) = cond(M_0)·cond(M_1), about 1e5 here: 1e-10 relative)
        let c = dense_solve(k.clone(), rhs.clone(), n);
        let scale = norm(&c);
        for (a, b) in got.iter().zip(&c) {
            assert!((a - b).abs() <= 1e-10 * scale, "{a} vs {b}");
        }
    }

    /// GCV's weights score no worse than any pair of a brute-force grid over both weights'
    /// ranges (half a decade apart), and the score reported is the score of the weights.
    #[test]
    fn gcv_beats_a_brute_force_grid_of_weights() {
        let (x0, x1) = (axis(14, 0.2), axis(12, 0.0));
        let z: Vec<f64> = sample(&[&x0, &x1], |p| (4.0 * p[0]).sin() + p[1] * p[1])
            .iter()
            .enumerate()
            .map(|(k, v)| v + 0.2 * noise(k))
            .collect();
        let v = PointsRef::from_flat(1, &z).unwrap();
        let fit =
            tensor_grid_smoothing_spline(&[&x0, &x1], v, &[Lambda::Gcv, Lambda::Gcv]).unwrap();
        assert!(fit.gcv.is_finite());
        assert_eq!(
            tensor_grid_gcv_score(&[&x0, &x1], v, &fit.lambdas).unwrap(),
            fit.gcv
        );
        let (s0, s1) = (
            AxisSmoother::new(&x0).unwrap().scan,
            AxisSmoother::new(&x1).unwrap().scan,
        );
        // the whole grid, the corner where both directions all but interpolate included
        let mut best = (f64::INFINITY, 0.0, 0.0);
        let mut e0 = s0.0;
        while e0 <= s0.1 {
            let mut e1 = s1.0;
            while e1 <= s1.1 {
                let (l0, l1) = (10f64.powf(e0), 10f64.powf(e1));
                let g = tensor_grid_gcv_score(&[&x0, &x1], v, &[l0, l1]).unwrap();
                if g < best.0 {
                    best = (g, l0, l1);
                }
                e1 += 0.5;
            }
            e0 += 0.5;
        }
        assert!(
            fit.gcv <= best.0 * (1.0 + 1e-9),
            "GCV chose {:?} (score {}); the grid finds ({}, {}) with {}",
            fit.lambdas,
            fit.gcv,
            best.1,
            best.2,
            best.0
        );
        // one direction searched, the other given
        let half =
            tensor_grid_smoothing_spline(&[&x0, &x1], v, &[Lambda::Given(1e-3), Lambda::Gcv])
                .unwrap();
        assert_eq!(half.lambdas[0], 1e-3);
        for e in [-6.0, -4.0, -2.0, 0.0, 2.0] {
            let g = tensor_grid_gcv_score(&[&x0, &x1], v, &[1e-3, 10f64.powf(e)]).unwrap();
            assert!(half.gcv <= g * (1.0 + 1e-9), "{} > {g} at 1e{e}", half.gcv);
        }
    }

    #[test]
    fn bad_input_is_refused_by_name() {
        let (x0, x1) = (axis(5, 0.0), axis(4, 0.0));
        let z = sample(&[&x0, &x1], |p| p[0] + p[1]);
        let v = PointsRef::from_flat(1, &z).unwrap();
        let g = Lambda::Given(1.0);
        assert!(matches!(
            tensor_grid_smoothing_spline(&[&x0, &x1], v, &[g, Lambda::Given(-1.0)]),
            Err(Error::NegativeSmoothing { .. })
        ));
        assert!(matches!(
            tensor_grid_smoothing_spline(&[&x0, &x1], v, &[g, Lambda::Given(f64::NAN)]),
            Err(Error::NegativeSmoothing { .. })
        ));
        assert!(matches!(
            tensor_grid_smoothing_spline(&[&x0, &x1], v, &[g]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            tensor_grid_smoothing_spline(&[&x0, &x1[..3]], v, &[g, g]),
            Err(Error::LengthMismatch { .. })
        ));
        let short = sample(&[&x0, &x1[..2]], |p| p[0]);
        assert!(matches!(
            tensor_grid_smoothing_spline(
                &[&x0, &x1[..2]],
                PointsRef::from_flat(1, &short).unwrap(),
                &[g, g]
            ),
            Err(Error::TooFew { min: 3, got: 2, .. })
        ));
        let nan = [0.0, f64::NAN, 1.0, 2.0];
        assert!(matches!(
            tensor_grid_smoothing_spline(&[&x0, &nan], v, &[g, g]),
            Err(Error::NonFinite { .. })
        ));
        let unsorted = [0.0, 0.5, 0.4, 1.0];
        assert!(tensor_grid_smoothing_spline(&[&x0, &unsorted], v, &[g, g]).is_err());
        assert!(matches!(
            tensor_grid_smoothing_spline(&[], v, &[]),
            Err(Error::TooFew { .. })
        ));
    }

    proptest! {
        #![proptest_config(crate::oracle::proptest_config(32))]

        /// The penalty vanishes on functions linear in each variable (the null space of
        /// `∫ f''²` in every direction): data sampled from a multilinear polynomial, offset far
        /// from 0, are reproduced for every λ, in one to three directions.
        #[test]
        fn multilinear_data_are_reproduced(
            n in 1usize..=3,
            sizes in proptest::collection::vec(3usize..=8, 3),
            warps in proptest::collection::vec(-0.6f64..0.6, 3),
            exps in proptest::collection::vec(-6.0f64..4.0, 3),
            coef in proptest::collection::vec(-3.0f64..3.0, 8),
            offset in -1e6f64..1e6,
        ) {
            let axes: Vec<Vec<f64>> = (0..n).map(|a| axis(sizes[a], warps[a])).collect();
            let refs: Vec<&[f64]> = axes.iter().map(Vec::as_slice).collect();
            // Σ over the subsets J of the directions of coef_J Π_{a∈J} x_a
            let f = |p: &[f64]| -> f64 {
                offset + (0..1usize << n)
                    .map(|mask| {
                        coef[mask] * (0..n).filter(|a| mask >> a & 1 == 1).map(|a| p[a]).product::<f64>()
                    })
                    .sum::<f64>()
            };
            let z = sample(&refs, f);
            let lambdas: Vec<Lambda> = exps[..n].iter().map(|e| Lambda::Given(10f64.powf(*e))).collect();
            let fit = tensor_grid_smoothing_spline(&refs, PointsRef::from_flat(1, &z).unwrap(), &lambdas).unwrap();
            let scale = 1.0 + offset.abs() + coef.iter().map(|c| c.abs()).sum::<f64>();
            for k in 0..7 {
                let p: Vec<f64> = (0..n).map(|a| (0.13 + 0.17 * (k + a) as f64) % 1.0).collect();
                let got = fit.spline.eval(&p).unwrap()[0];
                prop_assert!((got - f(&p)).abs() <= 1e-11 * scale, "{got} vs {} at {p:?}", f(&p));
            }
            prop_assert!(fit.residual <= (1e-11 * scale).powi(2) * z.len() as f64);
        }
    }
}
