//! Smoothing of scattered data in `N` variables: the tensor-product spline whose weighted
//! residual sum of squares is at most `s`, its knots found by FITPACK's `surfit` (behind SciPy's
//! `SmoothBivariateSpline` and `bisplrep`), here in any number of variables.
//! `docs/theory/tensor.md#smoothing-scattered-data`.

use crate::error::{Error, NthDirection, Result};
use crate::fit::{check_condition_args, smooth_weight, Steps, SMOOTHING_RTOL};
use crate::knots::KnotVector;
use crate::numeric::progress::Progress;
use crate::points::{Points, PointsRef};
use crate::tensor::scattered::{check_weights, empty_support};
use crate::tensor::scattered_qr::{observe, solve, to_natural, with_jumps, Layout, Observation};
use crate::tensor::spline::{check_len, check_n_vars, TensorBSpline};
use crate::RankDeficiency;
use crate::{Arg, What};

/// The options of [`tensor_scattered_smoothing`] beyond the data, the degrees and `s`.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatteredSmoothingOptions {
    /// The box `(a, b)` per variable the spline is clamped on (default: the range of the data).
    pub bbox: Option<Vec<(f64, f64)>>,
    /// The largest number of knots (end knots included) per variable, FITPACK's `nxest`,
    /// `nyest` (default: no bound but the number of coefficients, at most the number of data
    /// points).
    pub max_knots: Option<Vec<usize>>,
    /// A least-squares spline of the knot rounds the data do not determine: refused, or
    /// FITPACK's minimal-norm solution (default: refused).
    pub rank: RankDeficiency,
}

impl Default for ScatteredSmoothingOptions {
    fn default() -> Self {
        ScatteredSmoothingOptions {
            bbox: None,
            max_knots: None,
            rank: RankDeficiency::Refuse,
        }
    }
}

/// Why the knot rounds of [`tensor_scattered_smoothing`] stopped with a least-squares spline
/// whose residual is still above `s` (FITPACK's `ier` 1, 4 and 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KnotLimit {
    /// Every variable holds [`ScatteredSmoothingOptions::max_knots`] knots (FITPACK `ier = 1`).
    MaxKnots,
    /// The coefficients outnumber the data points (FITPACK `ier = 4`).
    CoefficientsExceedData,
    /// Every knot interval with residual is too narrow for a new knot: it would (nearly)
    /// coincide with an old one (FITPACK `ier = 5`).
    KnotsCoincide,
}

/// The result of [`tensor_scattered_smoothing`].
#[derive(Debug, Clone, PartialEq)]
pub struct TensorScatteredSmoothing {
    /// The fitted spline (values of the data's dimension), clamped on the box.
    pub spline: TensorBSpline,
    /// `Σ_k w_k |S(x_k) − y_k|²` (FITPACK's `fp` with its weights squared).
    pub residual: f64,
    /// The smoothing weight `p` of the result: `None` for a least-squares spline (the
    /// polynomial, knots whose least squares lie within `s`, or a [`KnotLimit`]).
    pub p: Option<f64>,
    /// The rank of the last system solved (the number of coefficients at full rank).
    pub rank: usize,
    /// Set when the knot rounds stopped above `s`.
    pub limit: Option<KnotLimit>,
}

/// The tensor-product spline of the given degrees whose weighted residual sum of squares
/// `fp = Σ_k w_k |S(x_k) − y_k|²` over scattered points `x_k` in `N` variables is `s` within
/// [`SMOOTHING_RTOL`] (and never above), with the knots of FITPACK's `surfit` (Dierckx, *Curve
/// and Surface Fitting with Splines*, 1993, ch. 9; SciPy's `SmoothBivariateSpline` and
/// `bisplrep` for `N = 2`). `docs/theory/tensor.md#smoothing-scattered-data`.
///
/// - Knot rounds, from the polynomial (no interior knot): while the least-squares spline leaves
///   `fp > s` (by more than `SMOOTHING_RTOL·s`), add one knot. Each knot interval of each
///   variable sums the squared weighted residuals `r_k` of the points whose coordinate lies in
///   it; the interval of largest sum (among the variables below their knot bound) gets a knot
///   at the `r`-weighted mean of those coordinates, unless that splits it in parts of ratio
///   above 10, when the next largest is tried (FITPACK `fpsurf`). The rounds stop early, with
///   the least-squares spline and a [`KnotLimit`], when no knot can be added.
/// - Smoothing weight: on the final knots, minimise `fp + p⁻²·Σ_a ‖(I ⊗ B_a ⊗ I) c‖²`, `B_a`
///   the jumps of the `k_a`-th derivative at the interior knots of variable `a` (FITPACK
///   `fpdisc`: `p → 0` is the polynomial, `p → ∞` least squares), with `p` by FITPACK's
///   rational interpolation from `p = n/Σ_i R_ii` (`R` the data triangle), as the curve
///   smoothing does.
///
/// Each system is the observation matrix reduced to a band triangle by Givens rotations, the
/// points taken in the order of their first coefficient, the variables ordered for the least
/// band (FITPACK interchanges `x` and `y`); the rows of the jumps are rotated into a copy for
/// each `p`. Cost per least-squares solve `O(m·W·b + n·b)`, per `p` `O(N·n²·b)` at worst
/// (`m` points, `W = Π(k_a+1)`, `n` coefficients, `b` the band); memory `n·b`, refused above
/// [`MAX_SCALARS`](crate::MAX_SCALARS). A system the data do not determine follows
/// [`ScatteredSmoothingOptions::rank`].
///
/// ```
/// use lekalo::{tensor_scattered_smoothing, PointsRef, ScatteredSmoothingOptions};
/// // 400 scattered points of a smooth surface plus a small pattern of noise
/// let mut x = Vec::new();
/// let mut z = Vec::new();
/// for k in 0..400 {
///     let (u, v) = ((k as f64 * 0.754_877_666).fract(), (k as f64 * 0.569_840_291).fract());
///     x.extend([u, v]);
///     z.push((3.0 * u).sin() * (2.0 * v).cos() + 0.01 * ((k % 5) as f64 - 2.0));
/// }
/// let opts = ScatteredSmoothingOptions::default();
/// let fit = tensor_scattered_smoothing(
///     PointsRef::from_flat(2, &x)?, PointsRef::from_flat(1, &z)?, None, &[3, 3], 0.05, &opts,
/// )?;
/// assert!(fit.residual <= 0.05);
/// assert!(fit.spline.shape().iter().product::<usize>() < 100);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// - [`Error::TooFew`] for fewer points than `Π_a (k_a + 1)`;
/// - [`Error::LengthMismatch`] if `degrees`, `bbox` or `max_knots` have not one entry per
///   variable, `values` not one row per point, or `weights` not one weight per point;
/// - [`Error::NegativeSmoothing`] for `s < 0` or not finite; [`Error::Degree`] for degree 0 or
///   above [`MAX_DEGREE`](crate::MAX_DEGREE);
/// - [`Error::InvalidDataWeight`] for a weight that is NaN, infinite or negative, or all zero;
/// - [`Error::InvalidArgument`] for a knot bound below `2(k_a + 1)` or `eps` outside `(0, 1)`;
/// - [`Error::NonFinite`] for a coordinate that is not finite, [`Error::EmptyDomain`] for an
///   empty box, [`Error::ParameterOutOfDomain`] for a point outside it;
/// - [`Error::TooLarge`] if a triangle exceeds [`MAX_SCALARS`](crate::MAX_SCALARS);
/// - [`Error::EmptySupport`] with [`RankDeficiency::Refuse`] for a control point the data do
///   not determine.
pub fn tensor_scattered_smoothing(
    x: PointsRef<'_>,
    values: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: &[usize],
    s: f64,
    options: &ScatteredSmoothingOptions,
) -> Result<TensorScatteredSmoothing> {
    tensor_scattered_smoothing_with_progress(
        x,
        values,
        weights,
        degrees,
        s,
        options,
        &Progress::new(),
    )
}

/// [`tensor_scattered_smoothing`] reporting to `progress` after each knot round and each
/// smoothing weight `p` tried, and stopping with [`Error::Cancelled`] between two of them when
/// its cancel flag is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`tensor_scattered_smoothing`], and [`Error::Cancelled`].
pub fn tensor_scattered_smoothing_with_progress(
    x: PointsRef<'_>,
    values: PointsRef<'_>,
    weights: Option<&[f64]>,
    degrees: &[usize],
    s: f64,
    options: &ScatteredSmoothingOptions,
    progress: &Progress<'_>,
) -> Result<TensorScatteredSmoothing> {
    let n_vars = x.dim();
    check_n_vars(n_vars)?;
    check_len("degrees (one per variable)", n_vars, degrees.len())?;
    for &k in degrees {
        check_condition_args(k, s)?;
    }
    options.rank.check()?;
    let count = x.len();
    let window: usize = degrees.iter().map(|k| k + 1).product();
    if count < window {
        return Err(Error::TooFew {
            what: "scattered data points (at least Π (k_a + 1))".into(),
            min: window,
            got: count,
        });
    }
    check_len("values (one row per data point)", count, values.len())?;
    if let Some(w) = weights {
        check_weights(w, count)?;
    }
    if let Some((index, &value)) = x
        .as_slice()
        .iter()
        .enumerate()
        .find(|(_, v)| !v.is_finite())
    {
        return Err(Error::NonFinite {
            what: "scattered data coordinates".into(),
            index,
            value,
        });
    }
    let mut dirs = Vec::with_capacity(n_vars);
    for a in 0..n_vars {
        let coord = x.iter().map(|r| r[a]);
        let (lo, hi) = match &options.bbox {
            Some(b) => {
                check_len(
                    What::of(Arg::Bbox, "bbox intervals (one per variable)"),
                    n_vars,
                    b.len(),
                )?;
                b[a]
            }
            None => coord
                .clone()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                }),
        };
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return Err(Error::EmptyDomain { min: lo, max: hi });
        }
        if let Some(t) = coord.clone().find(|&t| t < lo || t > hi) {
            return Err(Error::ParameterOutOfDomain {
                t,
                min: lo,
                max: hi,
            });
        }
        let k = degrees[a];
        let max = match &options.max_knots {
            Some(m) => {
                check_len(
                    What::of(Arg::MaxKnots, "max_knots (one per variable)"),
                    n_vars,
                    m.len(),
                )?;
                if m[a] < 2 * k + 2 {
                    return Err(Error::InvalidArgument {
                        what: Arg::MaxKnots.into(),
                        reason: format!(
                            "{} knots in the {} cannot hold a spline of degree {k}; give at \
                             least 2(k + 1) = {}",
                            m[a],
                            NthDirection(a),
                            2 * k + 2
                        ),
                    });
                }
                m[a]
            }
            None => usize::MAX,
        };
        dirs.push(Direction {
            k,
            lo,
            hi,
            interior: Vec::new(),
            max,
        });
    }
    let data = Data {
        x,
        values,
        weights,
        degrees,
        rank: options.rank,
    };
    let steps = Steps::new(
        progress,
        "smoothing of scattered data (knot rounds, weights)",
    );
    let out = rounds(&data, &mut dirs, s, &steps)?;
    steps.finish();
    Ok(out)
}

/// The data of a fit and its rank choice.
struct Data<'a> {
    x: PointsRef<'a>,
    values: PointsRef<'a>,
    weights: Option<&'a [f64]>,
    degrees: &'a [usize],
    rank: RankDeficiency,
}

/// One variable's box, interior knots and knot bound.
struct Direction {
    k: usize,
    lo: f64,
    hi: f64,
    interior: Vec<f64>,
    max: usize,
}

impl Direction {
    fn knots(&self) -> Vec<f64> {
        let mut t = vec![self.lo; self.k + 1];
        t.extend_from_slice(&self.interior);
        t.extend(std::iter::repeat_n(self.hi, self.k + 1));
        t
    }

    fn full(&self) -> bool {
        self.interior.len() + 2 * self.k + 2 >= self.max
    }
}

/// A least-squares (or smoothed) spline on given knots: natural coefficients, the spline, the
/// weighted squared residual of every point, their sum and the rank.
struct Fit {
    spline: TensorBSpline,
    point_residuals: Vec<f64>,
    fp: f64,
    rank: usize,
}

/// The knot rounds and the smoothing weight (FITPACK `fpsurf`).
fn rounds(
    data: &Data<'_>,
    dirs: &mut [Direction],
    s: f64,
    steps: &Steps<'_, '_>,
) -> Result<TensorScatteredSmoothing> {
    let acc = SMOOTHING_RTOL * s;
    let n_vars = dirs.len();
    let mut order: Vec<usize> = (0..n_vars).collect();
    let mut fp0 = 0.0;
    let done = |fit: Fit, limit: Option<KnotLimit>| TensorScatteredSmoothing {
        spline: fit.spline,
        residual: fit.fp,
        p: None,
        rank: fit.rank,
        limit,
    };
    let (obs, knots, lsq) = loop {
        steps.tick()?;
        let knots: Vec<KnotVector> = dirs
            .iter()
            .map(|d| KnotVector::new(d.knots()))
            .collect::<Result<_>>()?;
        let shape: Vec<usize> = dirs.iter().map(|d| d.interior.len() + d.k + 1).collect();
        let layout = Layout::least_band(&order, &shape, data.degrees);
        order.clone_from(&layout.order);
        let obs = observe(
            data.x,
            data.values,
            data.weights,
            data.degrees,
            &knots,
            layout,
            true,
        )?;
        let lsq = finish(data, &obs, obs.qr.clone(), &knots, &shape, true)?;
        let polynomial = dirs.iter().all(|d| d.interior.is_empty());
        if polynomial {
            fp0 = lsq.fp;
        }
        let fpms = lsq.fp - s;
        if fpms.abs() <= acc {
            return Ok(done(lsq, None));
        }
        if fpms < 0.0 {
            if polynomial {
                return Ok(done(lsq, None));
            }
            break (obs, knots, lsq);
        }
        let n_coef: usize = shape.iter().product();
        if n_coef > data.x.len() {
            return Ok(done(lsq, Some(KnotLimit::CoefficientsExceedData)));
        }
        if dirs.iter().all(Direction::full) {
            return Ok(done(lsq, Some(KnotLimit::MaxKnots)));
        }
        if !add_knot(data, dirs, &order, &lsq.point_residuals) {
            return Ok(done(lsq, Some(KnotLimit::KnotsCoincide)));
        }
    };
    let shape: Vec<usize> = dirs.iter().map(|d| d.interior.len() + d.k + 1).collect();
    let n_coef: usize = shape.iter().product();
    let bw = obs.bw;
    let trace: f64 = (0..n_coef).map(|i| obs.qr.r[i * bw]).sum();
    let p0 = if trace > 0.0 {
        n_coef as f64 / trace
    } else {
        1.0
    };
    let last_rank = std::cell::Cell::new(lsq.rank);
    let solve_p = |p: f64| -> Result<(Vec<f64>, f64)> {
        let qr = with_jumps(&obs, data.degrees, &knots, p);
        let fit = finish(data, &obs, qr, &knots, &shape, false)?;
        last_rank.set(fit.rank);
        Ok((fit.spline.control_points().as_slice().to_vec(), fit.fp))
    };
    match smooth_weight(&solve_p, p0, s, fp0, lsq.fp, steps)? {
        Some((p, fp, c)) => {
            let dim = data.values.dim();
            let spline = TensorBSpline::from_knot_vectors(
                data.degrees.to_vec(),
                knots,
                Points::from_flat(dim, c)?,
            )?;
            Ok(TensorScatteredSmoothing {
                spline,
                residual: fp,
                p: Some(p),
                rank: last_rank.get(),
                limit: None,
            })
        }
        None => Ok(done(lsq, None)),
    }
}

/// Solves the triangle `qr` of `obs`'s layout and evaluates the residuals. For least squares
/// (`lsq`) the residual sum is FITPACK's: the squares rotated out of the data rows, plus
/// `‖R c − z‖²` when pivots were dropped (exactly 0 for an interpolating square system).
fn finish(
    data: &Data<'_>,
    obs: &Observation,
    qr: crate::fit::banded::BandedQr,
    knots: &[KnotVector],
    shape: &[usize],
    lsq: bool,
) -> Result<Fit> {
    let dim = data.values.dim();
    let (c, rank) = solve(qr, obs.bw, data.rank).map_err(|i| {
        let natural = obs.layout.natural(i, shape);
        empty_support(natural, obs.support[i], shape, data.degrees, knots)
    })?;
    let n_coef = c.len() / dim;
    let rotated = if rank == n_coef {
        obs.qr.rss
    } else {
        obs.qr.rss + obs.qr.residual_of(&c)
    };
    let c = to_natural(&c, &obs.layout, shape, dim);
    let spline = TensorBSpline::from_knot_vectors(
        data.degrees.to_vec(),
        knots.to_vec(),
        Points::from_flat(dim, c)?,
    )?;
    let count = data.x.len();
    let mut fitted = vec![0.0; count * dim];
    spline.par_eval_batch(data.x.as_slice(), None, &mut fitted)?;
    let mut point_residuals = Vec::with_capacity(count);
    let mut fp = 0.0;
    for (k, (f, y)) in fitted.chunks_exact(dim).zip(data.values.iter()).enumerate() {
        let r2: f64 = f.iter().zip(y).map(|(a, b)| (a - b) * (a - b)).sum();
        let r = data.weights.map_or(1.0, |w| w[k]) * r2;
        fp += r;
        point_residuals.push(r);
    }
    if lsq {
        fp = rotated;
    }
    Ok(Fit {
        spline,
        point_residuals,
        fp,
        rank,
    })
}

/// Adds one knot (FITPACK `fpsurf`): in the knot interval of largest residual sum among the
/// variables below their bound (taken in the layout `order`, the first largest kept), at the
/// residual-weighted mean coordinate, unless it would split the interval in parts of ratio
/// above 10 (then that interval is passed over). `false` if no interval takes a knot.
fn add_knot(data: &Data<'_>, dirs: &mut [Direction], order: &[usize], r: &[f64]) -> bool {
    let mut fpint: Vec<Vec<f64>> = dirs
        .iter()
        .map(|d| vec![0.0; d.interior.len() + 1])
        .collect();
    let mut coord = fpint.clone();
    for (row, &rk) in data.x.iter().zip(r) {
        for (a, d) in dirs.iter().enumerate() {
            let l = d.interior.partition_point(|&t| t <= row[a]);
            fpint[a][l] += rk;
            coord[a][l] += rk * row[a];
        }
    }
    loop {
        let mut best: Option<(usize, usize)> = None;
        let mut fpmax = 0.0;
        for &a in order {
            if dirs[a].full() {
                continue;
            }
            for (l, &f) in fpint[a].iter().enumerate() {
                if f > fpmax {
                    fpmax = f;
                    best = Some((a, l));
                }
            }
        }
        let Some((a, l)) = best else {
            return false;
        };
        let arg = coord[a][l] / fpint[a][l];
        fpint[a][l] = 0.0;
        let d = &mut dirs[a];
        let left = if l == 0 { d.lo } else { d.interior[l - 1] };
        let right = d.interior.get(l).copied().unwrap_or(d.hi);
        let (fac1, fac2) = (right - arg, arg - left);
        if fac1 > 10.0 * fac2 || fac2 > 10.0 * fac1 {
            continue;
        }
        d.interior.insert(l, arg);
        return true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tensor::{tensor_scattered_least_squares, tensor_scattered_least_squares_with};
    use proptest::prelude::*;

    /// `count` points of a Kronecker sequence in `[0, 1]^n`.
    fn points(count: usize, n: usize, shift: f64) -> Vec<f64> {
        let alphas = [0.754_877_666, 0.569_840_291, 0.438_047_065];
        (0..count)
            .flat_map(|k| {
                alphas
                    .iter()
                    .take(n)
                    .map(move |a| (shift + (k as f64 + 0.5) * a).fract())
            })
            .collect()
    }

    fn surface(x: &[f64], n: usize, noise: &[f64]) -> Vec<f64> {
        x.chunks_exact(n)
            .enumerate()
            .map(|(k, p)| {
                (3.0 * p[0]).sin() * (2.0 * p[n - 1]).cos()
                    + p.iter().sum::<f64>()
                    + noise[k % noise.len()]
            })
            .collect()
    }

    fn fit(
        x: &[f64],
        n: usize,
        z: &[f64],
        k: &[usize],
        s: f64,
        opts: &ScatteredSmoothingOptions,
    ) -> Result<TensorScatteredSmoothing> {
        tensor_scattered_smoothing(
            PointsRef::from_flat(n, x).unwrap(),
            PointsRef::from_flat(1, z).unwrap(),
            None,
            k,
            s,
            opts,
        )
    }

    /// A large `s` gives the least-squares polynomial; the refusals name their argument.
    #[test]
    fn large_s_gives_the_polynomial_and_bad_input_is_refused() {
        let x = points(60, 2, 0.2);
        let z = surface(&x, 2, &[0.0]);
        let opts = ScatteredSmoothingOptions::default();
        let poly = fit(&x, 2, &z, &[3, 2], 1e9, &opts).unwrap();
        assert_eq!(poly.spline.shape(), &[4, 3]);
        assert_eq!((poly.p, poly.limit), (None, None));
        assert!(matches!(
            fit(&x, 2, &z, &[3, 2], -1.0, &opts),
            Err(Error::NegativeSmoothing { .. })
        ));
        assert!(matches!(
            fit(&x, 2, &z, &[3, 0], 1.0, &opts),
            Err(Error::Degree { .. })
        ));
        assert!(matches!(
            fit(&x[..10], 2, &z[..5], &[3, 3], 1.0, &opts),
            Err(Error::TooFew { .. })
        ));
        let boxed = ScatteredSmoothingOptions {
            bbox: Some(vec![(0.0, 1.0), (0.5, 1.0)]),
            ..ScatteredSmoothingOptions::default()
        };
        assert!(matches!(
            fit(&x, 2, &z, &[3, 2], 1.0, &boxed),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        let few = ScatteredSmoothingOptions {
            max_knots: Some(vec![8, 5]),
            ..ScatteredSmoothingOptions::default()
        };
        assert!(matches!(
            fit(&x, 2, &z, &[3, 2], 1.0, &few),
            Err(Error::InvalidArgument { what, .. }) if what.arg() == Some(Arg::MaxKnots)
        ));
        let bad_eps = ScatteredSmoothingOptions {
            rank: RankDeficiency::MinimumNorm { eps: 1.0 },
            ..ScatteredSmoothingOptions::default()
        };
        assert!(matches!(
            fit(&x, 2, &z, &[3, 2], 1.0, &bad_eps),
            Err(Error::InvalidArgument { what, .. }) if what.arg() == Some(Arg::Eps)
        ));
    }

    /// With a knot bound the rounds stop at it with the least-squares spline and say so.
    #[test]
    fn the_knot_bound_stops_the_rounds() {
        let x = points(300, 2, 0.4);
        let z = surface(&x, 2, &[0.03, -0.02, 0.05, -0.04, 0.01]);
        let opts = ScatteredSmoothingOptions {
            max_knots: Some(vec![9, 9]),
            ..ScatteredSmoothingOptions::default()
        };
        let f = fit(&x, 2, &z, &[3, 3], 1e-6, &opts).unwrap();
        assert_eq!(f.limit, Some(KnotLimit::MaxKnots));
        assert_eq!(f.spline.shape(), &[5, 5]);
        assert!(f.residual > 1e-6);
    }

    /// A coefficient without data: refused by default, zero in the minimal-norm solution
    /// (the null space of the system is its unit vector), the rest the least squares of the
    /// others.
    #[test]
    fn a_coefficient_without_data_is_refused_or_zero() {
        // linear in both variables, knots at 0.5: the points avoid the corner square
        // [0.5, 1] × [0.5, 1], so the control point (2, 2) has no data
        let k = KnotVector::new(vec![0.0, 0.0, 0.5, 1.0, 1.0]).unwrap();
        let x: Vec<f64> = points(200, 2, 0.1)
            .chunks_exact(2)
            .filter(|p| p[0] < 0.5 || p[1] < 0.5)
            .flatten()
            .copied()
            .collect();
        let z = surface(&x, 2, &[0.01, -0.02]);
        let args = |r| {
            tensor_scattered_least_squares_with(
                PointsRef::from_flat(2, &x).unwrap(),
                PointsRef::from_flat(1, &z).unwrap(),
                None,
                &[1, 1],
                vec![k.clone(), k.clone()],
                r,
            )
        };
        assert!(matches!(
            args(RankDeficiency::Refuse),
            Err(Error::EmptySupport { ref support, points: 0 }) if support.index == [2, 2]
        ));
        let f = args(RankDeficiency::MinimumNorm { eps: 1e-16 }).unwrap();
        assert_eq!(f.rank, 8);
        let c = f.spline.control_points().as_slice();
        assert!(c[8].abs() < 1e-12, "{}", c[8]);
        // Aᵀ(Ac − z) = 0 for the eight determined basis functions
        let mut fitted = vec![0.0; z.len()];
        f.spline.eval_batch(&x, None, &mut fitted).unwrap();
        for i in 0..8 {
            let mut e = vec![0.0; 9];
            e[i] = 1.0;
            let unit = TensorBSpline::from_knot_vectors(
                vec![1, 1],
                vec![k.clone(), k.clone()],
                Points::from_flat(1, e).unwrap(),
            )
            .unwrap();
            let mut b = vec![0.0; z.len()];
            unit.eval_batch(&x, None, &mut b).unwrap();
            let dot: f64 = b
                .iter()
                .zip(fitted.iter().zip(&z))
                .map(|(b, (f, z))| b * (f - z))
                .sum();
            assert!(dot.abs() < 1e-10, "{i}: {dot}");
        }
    }

    proptest! {
        #![proptest_config(crate::oracle::proptest_config(16))]

        /// In two and three variables: the residual is at most `s`, and within
        /// SMOOTHING_RTOL of it when smoothed (`p` given); a least-squares result (`p` None,
        /// e.g. `s = 0`) is the least-squares spline of its own knots.
        #[test]
        fn residual_meets_s_and_least_squares_is_the_limit(
            three in any::<bool>(),
            degrees in proptest::collection::vec(1usize..=3, 3),
            noise in proptest::collection::vec(-0.1f64..0.1, 37),
            fraction in 0.0f64..0.9,
            shift in 0.0f64..1.0,
        ) {
            let n = if three { 3 } else { 2 };
            let count = if three { 400 } else { 250 };
            let x = points(count, n, shift);
            let z = surface(&x, n, &noise);
            let deg = &degrees[..n];
            let opts = ScatteredSmoothingOptions {
                rank: RankDeficiency::MinimumNorm { eps: 1e-16 },
                max_knots: Some(deg.iter().map(|k| 2 * k + 2 + 5).collect()),
                ..ScatteredSmoothingOptions::default()
            };
            let poly = fit(&x, n, &z, deg, 1e12, &opts).unwrap();
            let s = fraction * poly.residual;
            let f = fit(&x, n, &z, deg, s, &opts).unwrap();
            let mut back = vec![0.0; count];
            f.spline.eval_batch(&x, None, &mut back).unwrap();
            let rss: f64 = back.iter().zip(&z).map(|(a, b)| (a - b) * (a - b)).sum();
            prop_assert!((rss - f.residual).abs() <= 1e-9 * (1.0 + rss));
            if f.limit.is_none() {
                prop_assert!(f.residual <= s * (1.0 + SMOOTHING_RTOL), "{} > {}", f.residual, s);
            }
            if f.p.is_some() {
                prop_assert!(f.residual >= (1.0 - SMOOTHING_RTOL) * s && f.residual <= s);
            } else if f.rank == f.spline.shape().iter().product::<usize>() {
                let l = tensor_scattered_least_squares(
                    PointsRef::from_flat(n, &x).unwrap(),
                    PointsRef::from_flat(1, &z).unwrap(),
                    None,
                    deg,
                    f.spline.knots().to_vec(),
                ).unwrap();
                for (a, b) in l.spline.control_points().as_slice().iter()
                    .zip(f.spline.control_points().as_slice()) {
                    prop_assert!((a - b).abs() <= 1e-7 * (1.0 + a.abs()), "{} {}", a, b);
                }
            }
        }
    }
}
