//! Penalised smoothing splines, `Σ w_k |Q_k − f(ū_k)|² + λ ∫ |f''|²`, with λ given or chosen by
//! generalised cross-validation (`docs/theory/fitting.md#penalised`, `#gcv`).

use crate::error::readable;
use crate::Arg;
use std::cell::Cell;

use super::banded::SymBand;
use super::data::{CurveFit, FitData, FitReport};
use super::progress::Steps;
use crate::basis::{basis_ders_into, basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::natural_cubic_spline;
use crate::numeric::progress::Progress;
use crate::points::Points;
use crate::BSplineCurve;

/// How the smoothing weight λ is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lambda {
    /// A given `λ ≥ 0` (`0` interpolates with the natural cubic spline).
    Given(f64),
    /// The λ that minimises the generalised cross-validation score ([`gcv_score`]).
    Gcv,
}

/// The cubic smoothing spline: the minimiser over all `C²` functions of
/// `Σ_k w_k |Q_k − f(ū_k)|² + λ ∫ |f''(u)|² du` (Reinsch 1967; SciPy's
/// `make_smoothing_spline`), for functions `y(x)` (1-D points, `ū_k = x_k`) and for parametric
/// curves (each coordinate over the same parameters).
///
/// The minimiser is a natural cubic spline with knots at the data parameters. It is computed in
/// the B-spline basis of the clamped cubic spline with those knots (`M + 2` coefficients for
/// `M` distinct parameters):
/// `(BᵀWB + λ Ω) c = BᵀW Q` with `Ω_ij = ∫ B_i'' B_j''` (exact by Simpson's rule, `B''` is
/// linear on each span), a symmetric positive definite matrix of half-bandwidth 3, factored as
/// `UᵀDU`. The natural end conditions come out of the minimisation. O(N) time and memory.
///
/// A repeated parameter is allowed: the points at it share one row of `B`, so the minimiser is
/// the one of a single point at their weighted mean whose weight is the sum of theirs
/// (`Σ w_k |Q_k − f|² = (Σ w_k) |Q̄ − f|² + const`); the report and the GCV score count every
/// point. With `λ = 0` the result interpolates those means.
///
/// With [`Lambda::Gcv`], λ minimises [`gcv_score`], whose trace term uses the band of the
/// inverse (Hutchinson & de Hoog 1985): a coarse scan in `log λ` from all but interpolation
/// (twelve decades below `tr(BᵀWB)/tr(Ω)`) to all but the least-squares line (two decades above
/// `Σw·L³`), followed by Brent's minimisation (`docs/theory/fitting.md#gcv`).
///
/// ```
/// use lekalo::fit::{smoothing_spline, FitData, Lambda};
/// use lekalo::PointsRef;
/// let x: Vec<f64> = (0..50).map(|k| k as f64 / 49.0).collect();
/// let y: Vec<f64> = x.iter().enumerate().map(|(k, t)| t * t + 0.01 * ((k * 7 % 5) as f64 - 2.0)).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let fit = smoothing_spline(&data, Lambda::Gcv)?;
/// assert!(fit.report.lambda.unwrap() > 0.0 && fit.report.rms < 0.02);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::NegativeSmoothing`] for `λ < 0` or NaN; [`Error::TooFew`] for fewer than 3
/// points or 3 distinct parameters; [`Error::NotIncreasing`] for parameters that decrease;
/// [`Error::SingularSystem`] if the weighted data cannot fix a line (points of positive weight
/// at fewer than two distinct parameters), or if λ is too small for a stretch of points of
/// weight 0 (the message names them and says to raise λ).
pub fn smoothing_spline(data: &FitData<'_>, lambda: Lambda) -> Result<CurveFit> {
    smoothing_spline_with_progress(data, lambda, &Progress::new())
}

/// [`smoothing_spline`] reporting to `progress` after the assembly and after each GCV score
/// evaluated (`done` the steps so far, `total` one more: the number of scores is not known
/// ahead; `(done, done)` at the end), and stopping with [`Error::Cancelled`] between two steps
/// when its cancel flag is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`smoothing_spline`], and [`Error::Cancelled`].
pub fn smoothing_spline_with_progress(
    data: &FitData<'_>,
    lambda: Lambda,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    let steps = Steps::new(progress, "smoothing spline (GCV scores)");
    if let Lambda::Given(l) = lambda {
        if !(l >= 0.0 && l.is_finite()) {
            return Err(Error::NegativeSmoothing {
                what: Arg::Lambda.into(),
                value: l,
            });
        }
    }
    let s = Smoother::new(data)?;
    steps.tick()?;
    let lam = match lambda {
        Lambda::Given(l) => l,
        Lambda::Gcv => s.minimise_gcv(&steps)?,
    };
    let interpolant = |reported: f64| -> Result<CurveFit> {
        let curve = match merged(data)? {
            Some((x, q)) => natural_cubic_spline(&x, q.as_view())?,
            None => natural_cubic_spline(data.params(), data.points())?,
        };
        let report = FitReport::new(&curve, data, Some(reported));
        steps.finish();
        Ok(CurveFit { curve, report })
    };
    if lam == 0.0 {
        return interpolant(0.0);
    }
    let (coef, _) = match s.solve(lam) {
        Ok(solved) => solved,
        // with every weight positive BᵀWB + λΩ is positive definite for λ > 0 (Ω vanishes
        // only on lines, which B maps to zero at no three distinct parameters): a failed
        // factorisation is λΩ below the rounding of BᵀWB, where the minimiser is its λ → 0
        // limit, the natural interpolant, to rounding (SciPy's banded form solves such λ too)
        Err(Error::SingularSystem { .. }) if s.weights.iter().all(|&w| w > 0.0) => {
            return interpolant(lam);
        }
        Err(e) => return Err(e),
    };
    let curve = s.curve(&coef);
    let report = FitReport::new(&curve, data, Some(lam));
    steps.finish();
    Ok(CurveFit { curve, report })
}

/// The data with the points at each repeated parameter merged into one at their weighted mean
/// (their plain mean when their weights are all zero), or `None` when no parameter repeats:
/// what the smoothing spline with `λ = 0` interpolates, the limit of its minimisers as `λ → 0`
/// (`docs/theory/fitting.md#penalised`). The parameters are non-decreasing ([`Smoother::new`]).
fn merged(data: &FitData<'_>) -> Result<Option<(Vec<f64>, Points)>> {
    let x = data.params();
    if x.windows(2).all(|w| w[0] != w[1]) {
        return Ok(None);
    }
    let pts = data.points();
    let dim = pts.dim();
    let mut xs = Vec::with_capacity(x.len());
    let mut q = Vec::with_capacity(x.len() * dim);
    let mut start = 0;
    while start < x.len() {
        let end = start + x[start..].iter().take_while(|&&v| v == x[start]).count();
        xs.push(x[start]);
        if end - start == 1 {
            q.extend_from_slice(pts.point(start));
        } else {
            let wsum: f64 = (start..end).map(|k| data.weight(k)).sum();
            // all weights zero: the plain mean
            let weight = |k: usize| if wsum > 0.0 { data.weight(k) } else { 1.0 };
            let total: f64 = (start..end).map(weight).sum();
            for c in 0..dim {
                // a convex combination: no partial sum exceeds the largest value
                q.push(
                    (start..end)
                        .map(|k| weight(k) / total * pts.point(k)[c])
                        .sum(),
                );
            }
        }
        start = end;
    }
    Ok(Some((xs, Points::from_flat(dim, q)?)))
}

/// The generalised cross-validation score of the smoothing spline with weight `λ > 0`
/// (Craven & Wahba 1979): `V(λ) = (RSS_w(λ) / (N·d)) / (1 − tr A(λ)/N)²`, with
/// `RSS_w = Σ_k w_k |Q_k − f_λ(ū_k)|²` over the `d` coordinates and
/// `tr A = tr((BᵀWB + λΩ)⁻¹ BᵀWB)` from the band of the inverse, or, where it is the smaller,
/// `N − tr A` from the band of the inverse in the basis of the natural splines (no cancellation
/// near interpolation). With unit weights and 1-D data
/// this is the score SciPy's `make_smoothing_spline` minimises. Near interpolation both the
/// numerator and the denominator vanish; where either is within rounding of zero (`N − tr A <
/// √ε·N`, or `RSS_w < ε·TSS_w`, the weighted total sum of squares about the weighted mean) the
/// score is `+∞` (`docs/theory/fitting.md#gcv`). O(N).
///
/// # Errors
/// As [`smoothing_spline`]; [`Error::NegativeSmoothing`] for `λ ≤ 0`.
pub fn gcv_score(data: &FitData<'_>, lambda: f64) -> Result<f64> {
    if !(lambda > 0.0 && lambda.is_finite()) {
        return Err(Error::NegativeSmoothing {
            what: Arg::Lambda.into(),
            value: lambda,
        });
    }
    Smoother::new(data)?.gcv(lambda)
}

/// Least share of `N` left to the residual degrees of freedom `N − tr A(λ)`, and square root of
/// the least share of the data's total sum of squares left to `RSS_w(λ)`, at which the GCV score
/// is evaluated: `√ε`. Closer to interpolation both vanish and rounding decides the score; above
/// them each keeps about half its digits (a residual RMS of `√ε` times the data's spread is
/// eight orders of magnitude above the rounding of the fitted values).
pub(crate) const GCV_ROUNDING_SHARE: f64 = 1.490_116_119_384_765_6e-8;

/// `Σ_ij X_ij Y_ij` of two symmetric matrices of half-bandwidth 3 stored as [`SymBand::a`]:
/// `tr(XY)` where `X` is the band of a full symmetric matrix and `Y` banded.
fn band_dot(x: &[f64], y: &SymBand) -> f64 {
    let w = 4;
    let mut sum = 0.0;
    for i in 0..y.n {
        for k in 0..w {
            let v = x[i * w + k] * y.a[i * w + k];
            sum += if k == 0 { v } else { 2.0 * v };
        }
    }
    sum
}

/// The natural end conditions `f''(ū_0) = f''(ū_last) = 0` solved for the first and last
/// coefficient: `c_0 = s_1 c_1 + s_2 c_2` and `c_last = e_1 c_(last−1) + e_2 c_(last−2)`. The
/// other coefficients are the coordinates of the natural splines, `c = Z β`.
struct NaturalEnds {
    start: [f64; 2],
    end: [f64; 2],
}

impl NaturalEnds {
    /// From `B_0'', B_1'', B_2''` at the first parameter and `B_(last−2)'', B_(last−1)'',
    /// B_last''` at the last.
    fn new(start: [f64; 3], end: [f64; 3]) -> Self {
        NaturalEnds {
            start: [-start[1] / start[0], -start[2] / start[0]],
            end: [-end[1] / end[2], -end[0] / end[2]],
        }
    }

    /// `Zᵀ A Z` of a symmetric matrix `A` of half-bandwidth 3 over the `m + 2` coefficients:
    /// order `m`, the same half-bandwidth (the ends fold into their neighbours).
    fn reduce(&self, a: &SymBand) -> SymBand {
        let nc = a.n;
        let nd = nc - 2;
        // the entries (j, z) of row i of Z
        let row = |i: usize| -> [(usize, f64); 2] {
            if i == 0 {
                [(0, self.start[0]), (1, self.start[1])]
            } else if i == nc - 1 {
                [(nd - 1, self.end[0]), (nd - 2, self.end[1])]
            } else {
                // the second entry a zero pad
                [(i - 1, 1.0), (i - 1, 0.0)]
            }
        };
        let mut out = SymBand::zeros(nd, 3);
        for i in 0..nc {
            for l in i..(i + 4).min(nc) {
                let v = a.a[i * 4 + l - i];
                for (p, zp) in row(i) {
                    for (q, zq) in row(l) {
                        let c = zp * v * zq;
                        // (ZᵀAZ)_pq gains Z_ip A_il Z_lq, and (for i ≠ l) Z_lp A_li Z_iq
                        if p <= q {
                            out.add(p, q, c);
                        }
                        if i != l && q <= p {
                            out.add(q, p, c);
                        }
                    }
                }
            }
        }
        out
    }
}

/// The banded pieces of the problem, assembled once for all λ (also the objective of the
/// shape-constrained smoothing spline, `super::shape`, and the smoother of each direction of
/// the smoothing spline on a grid, `crate::tensor`).
pub(crate) struct Smoother {
    /// Number of data points (each point at a repeated parameter counted).
    n: usize,
    dim: usize,
    pub(crate) knots: Vec<f64>,
    /// Per data point: the index of its first non-zero B-spline (points at one parameter
    /// share it).
    pub(crate) first: Vec<usize>,
    /// Per data point: its parameter `ū_k`.
    params: Vec<f64>,
    /// Per data point: the 4 non-zero basis values.
    pub(crate) basis: Vec<[f64; 4]>,
    weights: Vec<f64>,
    /// `Q − center`, flat.
    y: Vec<f64>,
    pub(super) center: Vec<f64>,
    pub(crate) gram: SymBand,
    pub(crate) omega: SymBand,
    /// `BᵀW(Q − center)`, flat.
    pub(super) rhs: Vec<f64>,
    /// `TSS_w = Σ_k w_k |Q_k − Q̄|²`, `Q̄` the weighted mean: the data's spread, the scale of
    /// the GCV score's rounding floor.
    spread: f64,
    /// `ZᵀBᵀWBZ` and `ZᵀΩZ`, `Z` the basis of the natural splines (`f'' = 0` at both ends)
    /// among the coefficients: the GCV score's residual degrees of freedom
    /// ([`Smoother::residual_dof`]).
    natural_gram: SymBand,
    natural_omega: SymBand,
}

impl Smoother {
    pub(crate) fn new(data: &FitData<'_>) -> Result<Self> {
        let x = data.params();
        let n = x.len();
        if n < 3 {
            return Err(Error::TooFew {
                what: "data points for a smoothing spline".into(),
                min: 3,
                got: n,
            });
        }
        // the distinct parameters (the knots) and the index of each point's among them: points
        // at one parameter share their basis row, so BᵀWB and BᵀWQ add their weights and
        // weighted values, as for one point at their weighted mean (docs/theory/fitting.md#penalised)
        let mut xs: Vec<f64> = Vec::with_capacity(n);
        let mut first = Vec::with_capacity(n);
        for i in 0..n {
            if i > 0 && x[i] < x[i - 1] {
                return Err(Error::NotIncreasing {
                    what: "x".into(),
                    index: i,
                    value: x[i],
                    previous: x[i - 1],
                });
            }
            if i == 0 || x[i] > x[i - 1] {
                xs.push(x[i]);
            }
            first.push(xs.len() - 1);
        }
        let nd = xs.len();
        if nd < 3 {
            return Err(Error::TooFew {
                what: "distinct parameters for a smoothing spline".into(),
                min: 3,
                got: nd,
            });
        }
        // x_k lies in span j + 3 (j its distinct index; the last one in the last span, nd + 1),
        // whose first B-spline is j (nd − 1 for the last)
        for f in &mut first {
            *f = (*f + 3).min(nd + 1) - 3;
        }
        let pts = data.points();
        let dim = pts.dim();
        let m = nd + 2;
        let mut knots = Vec::with_capacity(nd + 6);
        knots.extend([xs[0]; 3]);
        knots.extend_from_slice(&xs);
        knots.extend([xs[nd - 1]; 3]);
        let center = pts.point(0).to_vec();
        let mut scratch = BasisScratch::new(3);
        let mut basis = Vec::with_capacity(n);
        let mut weights = Vec::with_capacity(n);
        let mut y = Vec::with_capacity(n * dim);
        let mut gram = SymBand::zeros(m, 3);
        let mut rhs = vec![0.0; m * dim];
        let mut nb = [0.0; 4];
        for k in 0..n {
            let first = first[k];
            basis_funs_into(&knots, 3, first + 3, x[k], &mut scratch, &mut nb);
            let w = data.weight(k);
            for a in 0..4 {
                for b in a..4 {
                    gram.add(first + a, first + b, w * nb[a] * nb[b]);
                }
            }
            for (c, (q, o)) in pts.point(k).iter().zip(&center).enumerate() {
                let v = q - o;
                y.push(v);
                for a in 0..4 {
                    rhs[(first + a) * dim + c] += w * nb[a] * v;
                }
            }
            basis.push(nb);
            weights.push(w);
        }
        let wsum: f64 = weights.iter().sum();
        let spread = (0..dim)
            .map(|c| {
                let mean = (0..n).map(|k| weights[k] * y[k * dim + c]).sum::<f64>() / wsum;
                (0..n)
                    .map(|k| weights[k] * (y[k * dim + c] - mean).powi(2))
                    .sum::<f64>()
            })
            .sum();
        // Ω over each span [x_l, x_{l+1}]: B'' is linear, ∫ f g = h/6 (2 f0 g0 + f0 g1 + f1 g0 + 2 f1 g1)
        let mut omega = SymBand::zeros(m, 3);
        let mut ders = [0.0; 12];
        let mut left = [0.0; 4];
        let mut right = [0.0; 4];
        // B_0..B_2'' at the first parameter and B_(m−3)..B_(m−1)'' at the last: the natural
        // end conditions
        let (mut start, mut end) = ([0.0; 3], [0.0; 3]);
        for l in 0..nd - 1 {
            let span = l + 3;
            let h = xs[l + 1] - xs[l];
            basis_ders_into(&knots, 3, span, xs[l], 2, &mut scratch, &mut ders);
            left.copy_from_slice(&ders[8..12]);
            basis_ders_into(&knots, 3, span, xs[l + 1], 2, &mut scratch, &mut ders);
            right.copy_from_slice(&ders[8..12]);
            if l == 0 {
                start.copy_from_slice(&left[..3]);
            }
            if l == nd - 2 {
                end.copy_from_slice(&right[1..]);
            }
            let first = span - 3;
            for a in 0..4 {
                for b in a..4 {
                    let v = h / 6.0
                        * (2.0 * left[a] * left[b]
                            + left[a] * right[b]
                            + right[a] * left[b]
                            + 2.0 * right[a] * right[b]);
                    omega.add(first + a, first + b, v);
                }
            }
        }
        let ends = NaturalEnds::new(start, end);
        let natural_gram = ends.reduce(&gram);
        let natural_omega = ends.reduce(&omega);
        Ok(Smoother {
            n,
            dim,
            knots,
            first,
            params: x.to_vec(),
            basis,
            weights,
            y,
            center,
            gram,
            omega,
            rhs,
            spread,
            natural_gram,
            natural_omega,
        })
    }

    /// Coefficients (minus the center) for `λ > 0`, and the factored matrix.
    fn solve(&self, lam: f64) -> Result<(Vec<f64>, SymBand)> {
        let m = self.factored(lam)?;
        let mut c = self.rhs.clone();
        m.solve(&mut c, self.dim);
        Ok((c, m))
    }

    /// `BᵀWB + λΩ` for `λ > 0`, factored `UᵀDU`.
    ///
    /// # Errors
    /// [`Error::SingularSystem`] as [`smoothing_spline`] names it.
    pub(crate) fn factored(&self, lam: f64) -> Result<SymBand> {
        let mut m = self.gram.clone();
        for (a, o) in m.a.iter_mut().zip(&self.omega.a) {
            *a += lam * o;
        }
        m.factor().map_err(|i| self.singular(i, lam))?;
        Ok(m)
    }

    /// `tr A(λ) = tr((BᵀWB + λΩ)⁻¹ BᵀWB)` from the band of the inverse of the factored `m`
    /// (Hutchinson & de Hoog 1985; `docs/theory/fitting.md#gcv`). O(N).
    pub(crate) fn trace(&self, m: &SymBand) -> f64 {
        band_dot(&m.inverse_band(), &self.gram)
    }

    /// `r = m − tr A(λ)` for `λ > 0`, `m` the distinct parameters: the residual degrees of
    /// freedom of the GCV score, `N − tr A = N − m + r`. Of `r` and `tr A`, the smaller is
    /// computed and the other is `m` minus it: `tr A` by [`Smoother::trace`] of `full`
    /// (`BᵀWB + λΩ` factored); `r = λ·Σ_ij (M_Z⁻¹)_ij (Ω_Z)_ij`, `M_Z = Zᵀ(BᵀWB + λΩ)Z` in the
    /// basis `Z` of the natural splines, where `ZᵀBᵀWBZ` is regular, so that nothing cancels as
    /// `λ → 0` (`docs/theory/fitting.md#gcv`). O(N).
    pub(crate) fn residual_dof(&self, lam: f64, full: &SymBand) -> f64 {
        let trace = self.trace(full);
        let mut mz = self.natural_gram.clone();
        for (a, o) in mz.a.iter_mut().zip(&self.natural_omega.a) {
            *a += lam * o;
        }
        let penalty = if mz.factor().is_ok() {
            lam * band_dot(&mz.inverse_band(), &self.natural_omega)
        } else {
            f64::INFINITY
        };
        if penalty <= trace {
            penalty
        } else {
            mz.n as f64 - trace
        }
    }

    /// The refusal of a factorisation that found no positive pivot at coefficient `i`, naming
    /// its cause: points of positive weight at fewer than two distinct parameters (no λ fixes
    /// a line), or else λΩ below the rounding of `BᵀWB` where points of weight 0 leave the
    /// coefficient to the penalty alone (with every weight positive that λ gives the
    /// interpolant instead, [`smoothing_spline`]).
    fn singular(&self, i: usize, lam: f64) -> Error {
        let mut weighted = self
            .params
            .iter()
            .zip(&self.weights)
            .filter(|(_, &w)| w > 0.0)
            .map(|(x, _)| x);
        let first = weighted.next();
        if !weighted.any(|x| Some(x) != first) {
            return Error::SingularSystem {
                reason: "the points of positive weight lie at fewer than two distinct parameters \
                         and no smoothing weight λ fixes a line through them; give points at two \
                         other parameters a positive weight"
                    .into(),
            };
        }
        // the points of weight 0 under the coefficient's B-spline, support [t_i, t_(i+4)]
        let (a, b) = (self.knots[i], self.knots[(i + 4).min(self.knots.len() - 1)]);
        let unweighted: Vec<String> = self
            .params
            .iter()
            .zip(&self.weights)
            .filter(|(&x, &w)| w == 0.0 && x >= a && x <= b)
            .map(|(x, _)| readable(x).to_string())
            .collect();
        let which = match unweighted.len() {
            0 => "points of weight 0".to_string(),
            1 => format!("the point of weight 0 at x = {}", unweighted[0]),
            n if n <= 4 => format!("the points of weight 0 at x = {}", unweighted.join(", ")),
            n => format!(
                "{n} points of weight 0 between x = {} and {}",
                unweighted[0],
                unweighted[n - 1]
            ),
        };
        Error::SingularSystem {
            reason: format!(
                "λ = {lam} is too small: near x = {a} to {b} {which} leave the curve to the \
                 penalty λ∫|f''|² alone, and it is below the rounding of the other points' \
                 terms; raise λ, or give those points a positive weight",
                lam = readable(&lam),
                a = readable(&a),
                b = readable(&b),
            ),
        }
    }

    fn rss(&self, c: &[f64]) -> f64 {
        let (n, d) = (self.n, self.dim);
        let mut sum = 0.0;
        for k in 0..n {
            let first = self.first[k];
            let nb = &self.basis[k];
            for col in 0..d {
                let f: f64 = (0..4).map(|a| nb[a] * c[(first + a) * d + col]).sum();
                let r = self.y[k * d + col] - f;
                sum += self.weights[k] * r * r;
            }
        }
        sum
    }

    fn gcv(&self, lam: f64) -> Result<f64> {
        let (c, m) = self.solve(lam)?;
        let rss = self.rss(&c);
        let n = self.n as f64;
        // 1 − tr A/N, the repeated points counted apart from r
        let share = ((n - self.natural_gram.n as f64) + self.residual_dof(lam, &m)) / n;
        // near interpolation the score is 0/0 in rounding: not a candidate
        if share < GCV_ROUNDING_SHARE || rss < GCV_ROUNDING_SHARE * GCV_ROUNDING_SHARE * self.spread
        {
            return Ok(f64::INFINITY);
        }
        Ok((rss / (n * self.dim as f64)) / (share * share))
    }

    /// λ minimising the GCV score: a scan in `log λ`, a point a decade, then Brent's method
    /// between the neighbours of the scan's best point (`docs/theory/fitting.md#gcv`).
    ///
    /// The scan runs from twelve decades below `tr(BᵀWB)/tr(Ω)`, where the penalty weighs like
    /// the data over one knot interval (so the spline all but interpolates), to two decades above
    /// `Σw·L³` (`L` the parameter range), where it weighs like the data over the whole range (so
    /// the spline is all but the weighted least-squares line). The score can have several local
    /// minima, and with many closely spaced points the best λ lies many decades above the first
    /// bound, so the scan covers the whole range rather than a fixed width around either end.
    /// λ where the banded system cannot be factored (beyond about 10¹⁶ times the first bound)
    /// score `+∞`. Each score evaluated is a step of `steps`.
    ///
    /// # Errors
    /// [`Error::SingularSystem`] when no score is finite; [`Error::Cancelled`] from `steps`.
    pub(super) fn minimise_gcv(&self, steps: &Steps<'_, '_>) -> Result<f64> {
        let (lo, hi, n_grid) = self.gcv_scan();
        // once cancelled, every further score is skipped (+∞) and the error returned at the end
        let stopped = Cell::new(None);
        let f = |z: f64| match steps.tick() {
            Ok(()) => self.gcv(10f64.powf(z)).unwrap_or(f64::INFINITY),
            Err(e) => {
                stopped.set(Some(e));
                f64::INFINITY
            }
        };
        let cancelled = |stopped: &Cell<Option<Error>>| stopped.take().map_or(Ok(()), Err);
        let mut best = (f64::INFINITY, 0);
        // the scan's scores, then Brent's (about twenty more)
        steps.expect(n_grid as u64 + 1 + 20);
        let grid: Vec<f64> = (0..=n_grid)
            .map(|i| lo + (hi - lo) * i as f64 / n_grid as f64)
            .collect();
        let vals: Vec<f64> = grid.iter().map(|&z| f(z)).collect();
        cancelled(&stopped)?;
        for (i, &v) in vals.iter().enumerate() {
            if v < best.0 {
                best = (v, i);
            }
        }
        if !best.0.is_finite() {
            return Err(Error::SingularSystem {
                reason: "no smoothing weight gives a finite GCV score".into(),
            });
        }
        let i = best.1;
        let a = grid[i.saturating_sub(1)];
        let b = grid[(i + 1).min(n_grid)];
        let z = brent_min(f, a, b, grid[i], best.0, 1e-7);
        cancelled(&stopped)?;
        Ok(10f64.powf(z))
    }

    /// The scan of [`Smoother::minimise_gcv`] in `log₁₀ λ`: from `lo` to `hi` in `n_grid`
    /// steps, a point a decade (the score's minima are decades wide in log λ; Brent refines
    /// within the two decades around the best point).
    pub(crate) fn gcv_scan(&self) -> (f64, f64, usize) {
        let tg: f64 = (0..self.gram.n).map(|i| self.gram.a[i * 4]).sum();
        let to: f64 = (0..self.omega.n).map(|i| self.omega.a[i * 4]).sum();
        let scale = (tg / to).log10();
        let wsum: f64 = self.weights.iter().sum();
        let range = self.knots[self.knots.len() - 1] - self.knots[0];
        let line = (wsum * range.powi(3)).log10() + 2.0;
        let lo = scale - 12.0;
        let hi = if line.is_finite() {
            line.max(scale + 6.0)
        } else {
            scale + 6.0
        };
        // clamped to [2, 400] first, so the cast is exact
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n_grid = (hi - lo).ceil().clamp(2.0, 400.0) as usize;
        (lo, hi, n_grid)
    }

    fn curve(&self, c: &[f64]) -> BSplineCurve {
        let ctrl = self.control(c);
        BSplineCurve::from_raw(3, self.knots.clone(), Points::from_raw(ctrl, self.dim))
    }

    /// The control points of the coefficients `c` (minus the center): `c + 1 center`.
    fn control(&self, c: &[f64]) -> Vec<f64> {
        let mut ctrl = c.to_vec();
        for p in ctrl.chunks_exact_mut(self.dim) {
            for (v, o) in p.iter_mut().zip(&self.center) {
                *v += o;
            }
        }
        ctrl
    }
}

/// The pieces of the smoothing spline with a given `λ > 0` that its derivatives with respect
/// to the data need (`crate::derivatives::SmoothingMap`): `BᵀWB + λΩ` factored as
/// [`Smoother::solve`] factors it, and the rows of `B` with their weights
/// (`docs/theory/derivatives.md#fits`).
pub(crate) struct SmoothingSystem {
    /// `BᵀWB + λΩ`, factored `UᵀDU`.
    pub(crate) matrix: SymBand,
    /// Per data point, the index of its first non-zero cubic B-spline: `min(j + 3, M + 1) − 3`
    /// for the `j`-th of the `M` distinct parameters (points at one parameter share it).
    pub(crate) first: Vec<usize>,
    /// Per data point, the 4 non-zero cubic B-splines, starting at coefficient `first`.
    pub(crate) basis: Vec<[f64; 4]>,
    /// The data weights `w_k`.
    pub(crate) weights: Vec<f64>,
    /// The clamped cubic knot vector of the fit (knots at the distinct data parameters).
    pub(crate) knots: Vec<f64>,
}

/// [`SmoothingSystem`] of `data` (only its parameters and weights matter) for `λ > 0`.
///
/// # Errors
/// As [`smoothing_spline`] with [`Lambda::Given`]`(lam)`.
pub(crate) fn smoothing_system(data: &FitData<'_>, lam: f64) -> Result<SmoothingSystem> {
    Ok(smoothing_values_and_system(data, lam)?.1)
}

/// The control points of [`smoothing_spline`] with [`Lambda::Given`]`(lam)` for `lam > 0`, bit
/// for bit (flat, point-major), with the [`SmoothingSystem`] of the same assembly and the same
/// factorisation: the values and what their derivatives need, with `BᵀWB + λΩ` assembled and
/// factored once (`BᵀWB` and `Ω` do not depend on the data values, so the system is that of
/// [`smoothing_system`]).
///
/// # Errors
/// As [`smoothing_system`]. Where the factorisation fails with every weight positive,
/// [`smoothing_spline`] returns the interpolant instead, which has no such system: this returns
/// the factorisation's error.
pub(crate) fn smoothing_values_and_system(
    data: &FitData<'_>,
    lam: f64,
) -> Result<(Vec<f64>, SmoothingSystem)> {
    let s = Smoother::new(data)?;
    let (coef, matrix) = s.solve(lam)?;
    let control = s.control(&coef);
    Ok((
        control,
        SmoothingSystem {
            matrix,
            first: s.first,
            basis: s.basis,
            weights: s.weights,
            knots: s.knots,
        },
    ))
}

/// Brent's minimisation (golden section with parabolic steps) of `f` on `[a, b]` from the
/// point `x` with value `fx`, to an absolute tolerance `tol` in the argument (Brent 1973, ch. 5).
pub(crate) fn brent_min(
    f: impl Fn(f64) -> f64,
    mut a: f64,
    mut b: f64,
    x0: f64,
    fx0: f64,
    tol: f64,
) -> f64 {
    const GOLD: f64 = 0.381_966_011_250_105;
    let (mut x, mut w, mut v) = (x0, x0, x0);
    let (mut fx, mut fw, mut fv) = (fx0, fx0, fx0);
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..100 {
        let xm = 0.5 * (a + b);
        let tol1 = tol + 1e-10 * x.abs();
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = if xm >= x { tol1 } else { -tol1 };
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= xm { a - x } else { b - x };
            d = GOLD * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else {
            x + tol1.copysign(d)
        };
        let fu = f(u);
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::PointsRef;

    #[test]
    fn gcv_choice_is_the_least_score_of_a_dense_scan() {
        // 2000 points of sin on [0, 10] with pseudo-random noise of spread 0.1: the least score
        // lies near λ = 0.7, more than six decades above tr(BᵀWB)/tr(Ω), and a scan that ended
        // six decades above that ratio chose λ ≈ 0.02 (score 1.4% higher)
        let n = 2000;
        let x: Vec<f64> = (0..n).map(|k| 10.0 * k as f64 / n as f64).collect();
        let y: Vec<f64> = x
            .iter()
            .enumerate()
            .map(|(k, t)| {
                // splitmix64 of k: uniform in [0, 1)
                let mut z = (k as u64)
                    .wrapping_add(1)
                    .wrapping_mul(0x9E37_79B9_7F4A_7C15);
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                let u = (z ^ (z >> 31)) as f64 / 2f64.powi(64);
                t.sin() + 0.1 * 3f64.sqrt() * (2.0 * u - 1.0)
            })
            .collect();
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let fit = smoothing_spline(&data, Lambda::Gcv).unwrap();
        let lam = fit.report.lambda.unwrap();
        let chosen = gcv_score(&data, lam).unwrap();
        let mut best = (f64::INFINITY, 0.0);
        for i in 0..=8 * 16 {
            let l = 10f64.powf(-12.0 + f64::from(i) / 8.0);
            if let Ok(v) = gcv_score(&data, l) {
                if v < best.0 {
                    best = (v, l);
                }
            }
        }
        assert!(
            chosen <= best.0 * (1.0 + 1e-9),
            "GCV chose λ = {lam:e} (score {chosen:e}); the scan finds λ = {:e} (score {:e})",
            best.1,
            best.0
        );
    }

    /// `m − tr A` of the smoothing spline at the distinct parameters `x` with weights `w`, by
    /// Reinsch's form `λ·tr((R + λP)⁻¹P)`, `P = QᵀW⁻¹Q` (Green & Silverman 1994, §2.3): a dense
    /// elimination of the symmetric positive definite `R + λP`.
    fn reinsch_residual(x: &[f64], w: &[f64], lam: f64) -> f64 {
        let (m, k) = (x.len(), x.len() - 2);
        let h: Vec<f64> = x.windows(2).map(|p| p[1] - p[0]).collect();
        // column j of Q: 1/h_j, −1/h_j − 1/h_(j+1), 1/h_(j+1) at rows j, j + 1, j + 2
        let q = |i: usize, j: usize| match i.wrapping_sub(j) {
            0 => 1.0 / h[j],
            1 => -1.0 / h[j] - 1.0 / h[j + 1],
            2 => 1.0 / h[j + 1],
            _ => 0.0,
        };
        let p: Vec<f64> = (0..k * k)
            .map(|e| (0..m).map(|i| q(i, e / k) * q(i, e % k) / w[i]).sum())
            .collect();
        let mut a: Vec<f64> = (0..k * k)
            .map(|e| {
                let (i, j) = (e / k, e % k);
                let r = match i.abs_diff(j) {
                    0 => (h[i] + h[i + 1]) / 3.0,
                    1 => h[i.max(j)] / 6.0,
                    _ => 0.0,
                };
                r + lam * p[e]
            })
            .collect();
        let mut b: Vec<f64> = p.iter().map(|v| lam * v).collect();
        for c in 0..k {
            for r in c + 1..k {
                let f = a[r * k + c] / a[c * k + c];
                for j in 0..k {
                    a[r * k + j] -= f * a[c * k + j];
                    b[r * k + j] -= f * b[c * k + j];
                }
            }
        }
        for r in (0..k).rev() {
            for j in 0..k {
                let s: f64 = (r + 1..k).map(|i| a[r * k + i] * b[i * k + j]).sum();
                b[r * k + j] = (b[r * k + j] - s) / a[r * k + r];
            }
        }
        (0..k).map(|j| b[j * k + j]).sum()
    }

    /// The residual degrees of freedom `m − tr A` near interpolation, with weights and a
    /// repeated parameter, against Reinsch's form over the distinct parameters with the merged
    /// weights: to rounding from `λ = tr(BᵀWB)/tr(Ω)` down to `10⁻¹³` times it, where `m` minus
    /// `tr A` from the band of the inverse of `BᵀWB + λΩ` is 5e-5 off (relative) at `10⁻⁶` and
    /// has no correct digit at `10⁻¹⁰`.
    #[test]
    fn residual_dof_near_interpolation_matches_reinsch() {
        let x = [0.0, 0.4, 0.5, 0.5, 1.1, 1.3, 2.0, 2.2, 2.9, 3.0];
        let w = [1.0, 2.0, 0.5, 1.5, 3.0, 1.0, 0.7, 1.0, 2.0, 1.0];
        let y: Vec<f64> = x.iter().map(|t: &f64| t.sin()).collect();
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x)
            .unwrap()
            .with_weights(&w)
            .unwrap();
        let s = Smoother::new(&data).unwrap();
        let xs = [0.0, 0.4, 0.5, 1.1, 1.3, 2.0, 2.2, 2.9, 3.0];
        let ws = [1.0, 2.0, 2.0, 3.0, 1.0, 0.7, 1.0, 2.0, 1.0];
        let scale = 10f64.powf(s.gcv_scan().0 + 12.0);
        for e in [0.0, -2.0, -4.0, -6.0, -8.0, -10.0, -12.0, -13.0] {
            let lam = scale * 10f64.powf(e);
            let r = s.residual_dof(lam, &s.factored(lam).unwrap());
            let reference = reinsch_residual(&xs, &ws, lam);
            assert!(
                (r - reference).abs() <= 1e-11 * reference,
                "λ = 1e{e} × scale: {r:e} vs {reference:e}"
            );
        }
    }

    #[test]
    fn brent_finds_a_parabola_minimum() {
        let x = brent_min(|z| (z - 0.3) * (z - 0.3) + 1.0, -2.0, 2.0, 0.0, 1.09, 1e-10);
        assert!((x - 0.3).abs() < 1e-8, "{x}");
    }

    #[test]
    fn penalty_is_the_integral_of_the_squared_second_derivative() {
        // for f = Σ c_i B_i, cᵀΩc = ∫ f''², checked by Gauss–Legendre per span
        let x = [0.0, 0.3, 0.5, 1.2, 1.5, 2.0];
        let y = [0.0; 6];
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let s = Smoother::new(&data).unwrap();
        let c: Vec<f64> = (0..8).map(|i| ((i * 5 % 7) as f64).sin()).collect();
        let mut quad = 0.0;
        let curve = BSplineCurve::from_raw(3, s.knots.clone(), Points::from_raw(c.clone(), 1));
        let d2 = curve.derivative().unwrap().derivative().unwrap();
        for w in x.windows(2) {
            let (a, b) = (w[0], w[1]);
            for g in [-1.0 / 3f64.sqrt(), 1.0 / 3f64.sqrt()] {
                let t = 0.5 * (a + b) + 0.5 * (b - a) * g;
                let v = d2.eval(t).unwrap()[0];
                quad += 0.5 * (b - a) * v * v;
            }
        }
        let mut form = 0.0;
        for i in 0..8 {
            for k in 0..4 {
                if i + k < 8 {
                    let v = s.omega.a[i * 4 + k] * c[i] * c[i + k];
                    form += if k == 0 { v } else { 2.0 * v };
                }
            }
        }
        assert!(
            (form - quad).abs() < 1e-12 * quad.abs().max(1.0),
            "{form} vs {quad}"
        );
    }

    /// Data without noise: the score falls towards interpolation, where it is 0/0 only in
    /// rounding. Eleven points of `sin` on `[0, 10]` keep finite scores down to λ = 1e-7 (N − tr A
    /// and RSS about proportional to λ), and GCV chooses a λ whose score is no worse than any of
    /// them: the fit all but interpolates, as SciPy's (its λ 5.9e-6 gives 0.909292 at x = 2). A
    /// floor of half a residual degree of freedom scored λ ≤ 0.0046 `+∞` and chose a 25 % higher
    /// score, 0.905 at x = 2.
    #[test]
    fn gcv_on_data_without_noise_all_but_interpolates() {
        let x: Vec<f64> = (0..=10).map(f64::from).collect();
        let y: Vec<f64> = x.iter().map(|t| t.sin()).collect();
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let fit = smoothing_spline(&data, Lambda::Gcv).unwrap();
        let chosen = gcv_score(&data, fit.report.lambda.unwrap()).unwrap();
        for lam in [1e-7, 1e-6, 5.9e-6, 1e-4, 1e-3, 1e-2] {
            let v = gcv_score(&data, lam).unwrap();
            assert!(v.is_finite(), "λ = {lam}: score {v}");
            assert!(
                chosen <= v * (1.0 + 1e-6),
                "chosen {chosen} above {v} at λ = {lam}"
            );
        }
        let at2 = fit.curve.eval(2.0).unwrap()[0];
        assert!((at2 - 2f64.sin()).abs() < 1e-5, "{at2}");
        // interpolation itself (λ → 0) stays out: its score is rounding
        assert_eq!(gcv_score(&data, 1e-13).unwrap(), f64::INFINITY);
    }

    /// λ so small that `λΩ` vanishes in the rounding of `BᵀWB`: the natural interpolant, the
    /// minimiser's limit, as SciPy's `make_smoothing_spline(lam=1e-300)` gives; zero weights
    /// keep the refusal (the limit then ignores those points).
    #[test]
    fn a_penalty_below_rounding_gives_the_interpolant() {
        let x: Vec<f64> = (0..=10).map(f64::from).collect();
        let y: Vec<f64> = x.iter().map(|t| t.sin()).collect();
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let zero = smoothing_spline(&data, Lambda::Given(0.0)).unwrap();
        for lam in [1e-300, 1e-30, 1e-16] {
            let fit = smoothing_spline(&data, Lambda::Given(lam)).unwrap();
            assert_eq!(fit.report.lambda, Some(lam));
            for t in [0.5, 2.0, 7.3] {
                let (a, b) = (
                    fit.curve.eval(t).unwrap()[0],
                    zero.curve.eval(t).unwrap()[0],
                );
                assert!((a - b).abs() < 1e-12, "λ = {lam}, t = {t}: {a} vs {b}");
            }
        }
        let mut w = vec![1.0; 11];
        w[4] = 0.0;
        let weighted = data.with_weights(&w).unwrap();
        let e = smoothing_spline(&weighted, Lambda::Given(1e-300)).unwrap_err();
        assert!(matches!(e, Error::SingularSystem { .. }), "{e}");
        // the message names the cause, the point of weight 0 and λ, not the data's weights
        let text = e.to_string();
        assert!(
            text.contains("λ = 1e-300 is too small")
                && text.contains("the point of weight 0 at x = 4")
                && text.contains("raise λ"),
            "{text}"
        );
        assert!(!text.contains("two distinct parameters"), "{text}");
        // a larger λ is solved
        assert!(smoothing_spline(&weighted, Lambda::Given(1e-6)).is_ok());
    }

    /// Points of positive weight at one parameter only: no λ fixes a line, and the message says
    /// so and what to give a weight.
    #[test]
    fn one_weighted_parameter_names_the_weights() {
        let x: Vec<f64> = (0..=5).map(f64::from).collect();
        let y = [0.0, 1.0, 0.0, 1.0, 0.0, 1.0];
        let mut w = vec![0.0; 6];
        w[2] = 1.0;
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let weighted = data.with_weights(&w).unwrap();
        let e = smoothing_spline(&weighted, Lambda::Given(1.0)).unwrap_err();
        assert!(
            e.to_string().contains("fewer than two distinct parameters"),
            "{e}"
        );
    }

    /// Points at a repeated parameter: the same minimiser as one point at their weighted mean
    /// with the summed weight (docs/theory/fitting.md#penalised), for a given λ and for λ = 0;
    /// the report counts every point, and the knots are the distinct parameters.
    #[test]
    fn a_repeated_parameter_is_one_point_at_the_weighted_mean_with_the_summed_weight() {
        let x = [0.0, 0.5, 1.0, 1.0, 1.0, 2.0, 3.0, 3.5, 3.5];
        let y = [0.0, 0.4, 1.0, 2.0, 0.5, 1.5, 0.2, -1.0, 3.0];
        let w = [1.0, 2.0, 1.0, 3.0, 0.5, 1.0, 1.0, 0.0, 2.0];
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x)
            .unwrap()
            .with_weights(&w)
            .unwrap();
        // merged by hand: x = 1 carries weight 4.5 at (1 + 6 + 0.25) / 4.5; x = 3.5 weight 2 at 3
        let xm = [0.0, 0.5, 1.0, 2.0, 3.0, 3.5];
        let ym = [0.0, 0.4, 7.25 / 4.5, 1.5, 0.2, 3.0];
        let wm = [1.0, 2.0, 4.5, 1.0, 1.0, 2.0];
        let merged = FitData::new(PointsRef::from_flat(1, &ym).unwrap(), &xm)
            .unwrap()
            .with_weights(&wm)
            .unwrap();
        for lam in [1e-3, 0.1, 10.0, 0.0] {
            let a = smoothing_spline(&data, Lambda::Given(lam)).unwrap();
            let b = smoothing_spline(&merged, Lambda::Given(lam)).unwrap();
            assert_eq!(a.curve.knots(), b.curve.knots(), "λ = {lam}");
            for t in [0.0, 0.3, 1.0, 1.7, 2.9, 3.5] {
                let (fa, fb) = (a.curve.eval(t).unwrap()[0], b.curve.eval(t).unwrap()[0]);
                assert!(
                    (fa - fb).abs() < 1e-13 * 3.0,
                    "λ = {lam}, t = {t}: {fa} vs {fb}"
                );
            }
            assert_eq!(a.report.residuals.len(), 9, "every point's residual");
        }
        // λ = 0 interpolates the weighted means
        let a = smoothing_spline(&data, Lambda::Given(0.0)).unwrap();
        assert!((a.curve.eval(1.0).unwrap()[0] - 7.25 / 4.5).abs() < 1e-14);
        // all weights zero at a repeated parameter: the plain mean
        let w0 = [1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        let data0 = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x)
            .unwrap()
            .with_weights(&w0)
            .unwrap();
        let a = smoothing_spline(&data0, Lambda::Given(0.0)).unwrap();
        assert!((a.curve.eval(1.0).unwrap()[0] - 3.5 / 3.0).abs() < 1e-14);
        // GCV chooses a λ for the data with repeats, scored over all nine points
        let g = smoothing_spline(&data, Lambda::Gcv).unwrap();
        assert!(g.report.lambda.unwrap() > 0.0, "{:?}", g.report.lambda);
        // fewer than three distinct parameters
        let e = smoothing_spline(
            &FitData::new(
                PointsRef::from_flat(1, &[0.0, 1.0, 2.0]).unwrap(),
                &[0.0, 0.0, 1.0],
            )
            .unwrap(),
            Lambda::Given(1.0),
        )
        .unwrap_err();
        assert!(matches!(e, Error::TooFew { min: 3, got: 2, .. }), "{e}");
    }
}
