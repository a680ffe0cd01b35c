//! The smoothing condition: the spline with the fewest knots whose weighted residual sum of
//! squares is at most `s` (FITPACK `curfit`/`parcur`, behind SciPy's `splrep`/`splprep`;
//! `docs/theory/fitting.md#smoothing-condition`).

use super::banded::{BandedQr, QrRows};
use super::data::{check_in_domain, CurveFit, FitData, FitReport};
use super::progress::Steps;
use crate::basis::{basis_funs_into, BasisScratch, SpanBasis};
use crate::error::{check_degree_bound, check_finite, readable, Error, Result};
use crate::numeric::progress::Progress;
use crate::points::Points;
use crate::BSplineCurve;

/// Relative accuracy of the final residual: the result has
/// `(1 − SMOOTHING_RTOL)·s ≤ Σ w_k |C(ū_k) − Q_k|² ≤ s` when it is smoothed (FITPACK's
/// `tol = 0.001`, which SciPy's `splrep` keeps).
pub const SMOOTHING_RTOL: f64 = 1e-3;

/// Iterations of the smoothing weight `p` on the final knots (FITPACK's `maxit`, 20 in SciPy).
const MAX_P_ITERATIONS: usize = 20;

/// The B-spline of `degree` with the fewest interior knots found whose weighted residual sum of
/// squares `Σ_k w_k |C(ū_k) − Q_k|²` is at most `s` (Dierckx 1975, 1993 ch. 5; FITPACK `curfit`
/// for functions and `parcur` for parametric curves, as in SciPy's `splrep(s=…)`/`splprep`).
/// FITPACK's weights multiply the residual, ours its square: `w_k = w_FITPACK²`.
///
/// 1. Start with no interior knot: the least-squares polynomial. If its residual is `≤ s`, it is
///    the answer.
/// 2. Otherwise add knots where the residual is largest, as FITPACK's `fpcurf`/`fpknot`: the
///    residual is summed per knot span (a point on a knot counts half to each side), and the span
///    with the largest sum among those with a distinct parameter strictly inside is split at its
///    middle such parameter, the sum shared in proportion. The number added per round starts at
///    1 and follows `nplus = min(2·nplus, max(⌊nplus·(fp − s)/(fp_old − fp)⌋, nplus/2, 1))`.
///    Each round is one least-squares pass: the data rows are reduced into a banded triangle
///    `R` (Householder blocks of the rows of one knot span, `docs/theory/fitting.md#banded-qr`)
///    and kept only for the span residuals. The round stops when `fp ≤ s`, or when the knots are
///    those of interpolation (`s = 0` starts there).
/// 3. On this final knot set, smooth: add the rows `b_j / p` of FITPACK's `fpdisc` (the jumps of
///    the `p`-th derivative at the interior knots, scaled by `k!·(spans/length)^k`) and find `p`
///    with `|fp(p) − s| < SMOOTHING_RTOL·s` by FITPACK's rational interpolation (`fprati`),
///    starting from `p = n / trace R`. Each `p` rotates only the penalty rows into a copy of
///    the data's `R` and reads the data residual off `R` (`fp = rss₀ + ‖R c − Qᵀy‖²`): O(n·k²),
///    no pass over the data.
///
/// On data with distinct parameters this is FITPACK's algorithm step for step, so the knots and
/// coefficients are SciPy's to rounding (tested on stored SciPy values). It differs where FITPACK
/// would return a residual above `s`: a least-squares fit with `s < fp < s + SMOOTHING_RTOL·s`
/// gets more knots instead of being accepted, and a smoothed fit with `fp > s` continues the
/// same iteration towards `s − SMOOTHING_RTOL·s/2`, so the result never exceeds `s`.
/// Repeated parameters are allowed: knots are placed among the distinct ones. Where points share
/// a parameter with different values no function meets them all: every spline leaves at least
/// their spread about the group's weighted mean ([`reachable_floor`]), and an `s` below it is
/// refused (as SciPy's `make_splrep` refuses it) rather than answered with a residual above `s`.
/// The reported λ
/// is the weight of `Σ_j (jump of C^{(k)} at t_j)²`, `λ = (p·k!·(spans/length)^k)^{-2}`.
/// Cost: O(rounds·N·k²) for `N` points, the rounds growing like the logarithm of the knot count.
///
/// ```
/// use lekalo::fit::{smoothing_condition, FitData};
/// use lekalo::PointsRef;
/// let x: Vec<f64> = (0..200).map(|k| k as f64 / 199.0).collect();
/// let y: Vec<f64> = x.iter().enumerate().map(|(k, t)| (6.0 * t).sin() + 0.01 * ((k * 7919 % 13) as f64 - 6.0)).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// // the noise's sum of squares is 0.279
/// let fit = smoothing_condition(&data, 3, 0.3)?;
/// assert!(fit.report.weighted_rss <= 0.3);
/// assert!(fit.report.n_ctrl < 30);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::NegativeSmoothing`] for `s < 0` or NaN; [`Error::Degree`] for degree 0;
/// [`Error::TooFew`] for fewer than `degree + 1` distinct parameters;
/// [`Error::InvalidArgument`] (`what = "s"`) for `s` below the residual that repeated
/// parameters with different values leave to every function;
/// [`Error::SingularSystem`] when zero weights leave a coefficient without data.
pub fn smoothing_condition(data: &FitData<'_>, degree: usize, s: f64) -> Result<CurveFit> {
    smoothing_condition_with_progress(data, degree, s, &Progress::new())
}

/// [`smoothing_condition`] reporting to `progress` after each round of knot addition and each
/// smoothing weight `p` tried (`done` the steps so far, `total` one more: their number is not
/// known ahead; `(done, done)` at the end), and stopping with [`Error::Cancelled`] between two
/// steps when its cancel flag is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`smoothing_condition`], and [`Error::Cancelled`].
pub fn smoothing_condition_with_progress(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    condition_fit(data, degree, s, None, progress)
}

/// [`smoothing_condition`] on the domain `(a, b)`, which holds the data and may reach beyond
/// them: the end knots are `a` and `b` (FITPACK `curfit`'s `xb`, `xe`; SciPy's
/// `splrep(x, y, xb=a, xe=b, s=…)`, `UnivariateSpline(…, bbox=[a, b])`). Everything else is
/// [`smoothing_condition`]'s: the interior knots are placed among the distinct data parameters
/// in the same rounds (for `s = 0` those of interpolation), the residual sums per span now
/// reaching to `a` and `b`, and the jumps of the `k`-th derivative scaled by the spans per
/// length `(b − a)` as FITPACK's `fpdisc`. With `(a, b)` the data's own ends it is
/// [`smoothing_condition`], bit for bit.
///
/// ```
/// use lekalo::fit::{smoothing_condition_in, FitData};
/// use lekalo::PointsRef;
/// let x = [1.0, 2.0, 4.0, 6.0, 8.5];
/// let y = [0.5, 0.8, 1.3, 2.5, 2.8];
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let fit = smoothing_condition_in(&data, 3, 0.1, (-100.0, 100.0))?;
/// assert_eq!(fit.curve.domain(), (-100.0, 100.0));
/// assert!(fit.report.weighted_rss <= 0.1);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`smoothing_condition`]; [`Error::NonFinite`] / [`Error::EmptyDomain`] for a domain
/// that is not finite with `a < b`; [`Error::ParameterOutOfDomain`] for a data parameter
/// outside it.
pub fn smoothing_condition_in(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: (f64, f64),
) -> Result<CurveFit> {
    smoothing_condition_in_with_progress(data, degree, s, domain, &Progress::new())
}

/// [`smoothing_condition_in`] reporting to `progress` as
/// [`smoothing_condition_with_progress`] does.
///
/// # Errors
/// As [`smoothing_condition_in`], and [`Error::Cancelled`].
pub fn smoothing_condition_in_with_progress(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: (f64, f64),
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    condition_fit(data, degree, s, Some(domain), progress)
}

/// The domain `(a, b)` of a fit: finite, `a < b`, holding every data parameter.
fn check_domain(data: &FitData<'_>, (a, b): (f64, f64)) -> Result<()> {
    check_finite("domain (a, b) of the smoothing condition", &[a, b])?;
    if a >= b {
        return Err(Error::EmptyDomain { min: a, max: b });
    }
    check_in_domain(data.params(), (a, b))
}

/// [`smoothing_condition_with_progress`] and [`smoothing_condition_in_with_progress`]: on the
/// data's own domain when `domain` is `None`.
fn condition_fit(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: Option<(f64, f64)>,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    check_condition_args(degree, s)?;
    if let Some(domain) = domain {
        check_domain(data, domain)?;
    }
    let steps = Steps::new(progress, "smoothing condition (knot rounds, weights)");
    let obs = Observations::new(data);
    check_reachable(&obs, s)?;
    let k = degree;
    let fit = match knot_rounds(&obs, k, s, domain, usize::MAX, &steps, &mut |_| {})? {
        Rounds::Done { t, c } => finish(data, &obs, k, t, &c, None),
        Rounds::Smooth { t, qr, fp0, fp_inf } => {
            let (c, lambda) = smooth_on(&obs, k, &t, &qr, s, fp0, fp_inf, &steps)?;
            finish(data, &obs, k, t, &c, lambda)
        }
    };
    steps.finish();
    Ok(fit)
}

/// The knot vectors of the rounds of [`smoothing_condition`], in order: the clamped knot vector
/// of each least-squares pass of step 2 (the first without interior knots, unless `s = 0`,
/// whose only round is on the knots of interpolation). The last is the knot vector the
/// smoothing condition smooths on. This is SciPy's `generate_knots(x, y, k=…, s=…, nest=…)`
/// (Dierckx, "Curve and Surface Fitting with Splines", 1993, ch. 5): `max_knots` (SciPy's `nest`, at least `2·degree + 2`) stops the
/// rounds once a knot vector has that many knots; `None` runs them to the end.
///
/// ```
/// use lekalo::fit::{smoothing_knot_sequence, FitData};
/// use lekalo::PointsRef;
/// let x: Vec<f64> = (0..8).map(|k| k as f64).collect();
/// let y: Vec<f64> = x.iter().map(|v| (v * std::f64::consts::PI / 8.0).sin()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let seq = smoothing_knot_sequence(&data, 3, 1e-7, None)?;
/// let counts: Vec<usize> = seq.iter().map(Vec::len).collect();
/// assert_eq!(counts, vec![8, 9, 10, 11, 12]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`smoothing_condition`]; [`Error::TooFew`] for `max_knots < 2·degree + 2`.
pub fn smoothing_knot_sequence(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    max_knots: Option<usize>,
) -> Result<Vec<Vec<f64>>> {
    check_condition_args(degree, s)?;
    let cap = check_max_knots(degree, max_knots)?;
    let obs = Observations::new(data);
    let mut seq = Vec::new();
    let quiet = Progress::new();
    let steps = Steps::new(&quiet, "");
    knot_rounds(&obs, degree, s, None, cap, &steps, &mut |t| {
        seq.push(t.to_vec());
    })?;
    Ok(seq)
}

/// `max_knots` as a count of interior knots (`usize::MAX` for none), refusing fewer knots than
/// the polynomial has.
pub(super) fn check_max_knots(degree: usize, max_knots: Option<usize>) -> Result<usize> {
    match max_knots {
        None => Ok(usize::MAX),
        Some(n) if n < 2 * degree + 2 => Err(Error::TooFew {
            what: "knots allowed (max_knots, SciPy's nest): the polynomial has 2·degree + 2",
            min: 2 * degree + 2,
            got: n,
        }),
        Some(n) => Ok(n - 2 * degree - 2),
    }
}

/// Where the knot rounds of step 2 ended.
pub(super) enum Rounds {
    /// The answer: the knots and the least-squares coefficients on them.
    Done { t: Vec<f64>, c: Vec<f64> },
    /// Knots whose least-squares residual `fp_inf` is below `s`: smooth on them (step 3).
    Smooth {
        t: Vec<f64>,
        qr: BandedQr,
        fp0: f64,
        fp_inf: f64,
    },
}

/// Step 2 of [`smoothing_condition`]: the rounds of least squares and knot addition, at most
/// `cap` interior knots, each round's knot vector passed to `seen` before its pass, each round a
/// step of `steps`; the end knots at `domain` (checked to hold the data), else at the data's
/// ends.
#[allow(clippy::too_many_arguments)]
fn knot_rounds(
    obs: &Observations,
    k: usize,
    s: f64,
    domain: Option<(f64, f64)>,
    cap: usize,
    steps: &Steps<'_, '_>,
    seen: &mut dyn FnMut(&[f64]),
) -> Result<Rounds> {
    let md = obs.sites.len();
    if md < k + 1 {
        return Err(Error::TooFew {
            what: "distinct data parameters for the smoothing condition (degree + 1)",
            min: k + 1,
            got: md,
        });
    }
    let acc = SMOOTHING_RTOL * s;
    // knot counts of the polynomial and of interpolation
    let (nmin, nmax) = (2 * k + 2, md + k + 1);
    let mut knots = Knots::new(&obs.sites, k, domain);
    if s == 0.0 {
        knots.interpolation(&obs.sites);
    }
    let (mut fp0, mut fpold, mut nplus) = (f64::INFINITY, 0.0, 0usize);
    let mut pass = LsqPass::new(obs, k);
    loop {
        steps.tick()?;
        let t = knots.vector();
        seen(&t);
        let n = t.len();
        let qr = pass.run(obs, &t);
        let c = back_substitute(&qr)?;
        let fp = qr.rss;
        if n == nmin {
            fp0 = fp;
        }
        let fpms = fp - s;
        if fpms < 0.0 || (fpms == 0.0 && s > 0.0) {
            if -fpms < acc || n == nmin {
                return Ok(Rounds::Done { t, c });
            }
            return Ok(Rounds::Smooth {
                t,
                qr,
                fp0,
                fp_inf: fp,
            });
        }
        if n >= nmax || knots.count() >= cap {
            // interpolation, or as many knots as allowed
            return Ok(Rounds::Done { t, c });
        }
        nplus = if n == nmin {
            1
        } else {
            next_nplus(nplus, fpms, fpold - fp, acc)
        };
        fpold = fp;
        pass.residuals(obs, &c);
        knots.span_sums(obs, &pass, &t);
        match knots.add_up_to(&obs.sites, nplus, nmax - 2 * k - 2, cap) {
            Added::Some => {}
            Added::Full => knots.interpolation(&obs.sites),
            // no span holds a parameter strictly inside: as close to interpolation as it gets
            Added::None => return Ok(Rounds::Done { t, c }),
        }
    }
}

/// Step 3 of [`smoothing_condition`] on the knots `t` with the data's least-squares triangle
/// `qr`: the coefficients whose residual is `s` within [`SMOOTHING_RTOL`] and never above, and
/// the jump weight λ; the least-squares coefficients and no λ when no weight reaches `s` from
/// below. `fp0` and `fp_inf` are the residuals of the polynomial (`p = 0`) and of the
/// least-squares spline (`p = ∞`). Each weight tried is a step of `steps`.
#[allow(clippy::too_many_arguments)]
pub(super) fn smooth_on(
    obs: &Observations,
    k: usize,
    t: &[f64],
    qr: &BandedQr,
    s: f64,
    fp0: f64,
    fp_inf: f64,
    steps: &Steps<'_, '_>,
) -> Result<(Vec<f64>, Option<f64>)> {
    let pen = jump_rows(t, k);
    // the triangle of [R; B/p] from scratch in column order (R's row j, then the penalty row
    // starting at column j): O(n·k²) per p, no pass over the data
    let (n, k1, k2, dim) = (qr.n(), k + 1, k + 2, obs.dim);
    let n8 = pen.rows.len() / k2;
    let solve = |p: f64| -> Result<(Vec<f64>, f64)> {
        let mut g = BandedQr::new(n, k2, dim);
        let mut h = vec![0.0; k2];
        let mut y = vec![0.0; dim];
        for j in 0..n {
            let len = k1.min(n - j);
            h[..len].copy_from_slice(&qr.r[j * k1..j * k1 + len]);
            y.copy_from_slice(&qr.z[j * dim..(j + 1) * dim]);
            g.add_row(j, &mut h[..len], &mut y);
            if j < n8 {
                for (hv, v) in h.iter_mut().zip(&pen.rows[j * k2..(j + 1) * k2]) {
                    *hv = v / p;
                }
                y.fill(0.0);
                g.add_row(j, &mut h, &mut y);
            }
        }
        let c = back_substitute(&g)?;
        let fp = qr.rss + qr.residual_of(&c);
        Ok((c, fp))
    };
    // p → 0: the least-squares polynomial (fp0); p → ∞: the least-squares spline (fp_inf)
    let trace: f64 = qr.r.chunks_exact(k + 1).map(|row| row[0]).sum();
    match smooth_weight(&solve, n as f64 / trace, s, fp0, fp_inf, steps)? {
        Some((p, _, c)) => Ok((c, Some((p * pen.scale).powi(-2)))),
        // no weight reached s from below: the least-squares spline on these knots
        None => Ok((back_substitute(qr)?, None)),
    }
}

/// The data sorted by parameter, relative to the first point and weighted for the rows of the
/// least-squares problem.
pub(super) struct Observations {
    /// Parameters, increasing.
    pub(super) x: Vec<f64>,
    /// `√w` (FITPACK's weight).
    pub(super) wf: Vec<f64>,
    /// `√w·(Q − Q_first)`, `dim` per point.
    pub(super) y: Vec<f64>,
    pub(super) dim: usize,
    pub(super) center: Vec<f64>,
    /// The distinct parameters.
    pub(super) sites: Vec<f64>,
}

impl Observations {
    pub(super) fn new(data: &FitData<'_>) -> Self {
        let pts = data.points();
        let dim = pts.dim();
        let center = pts.point(0).to_vec();
        let order: Vec<usize> = data.order().unwrap_or_else(|| (0..data.len()).collect());
        let params = data.params();
        let x: Vec<f64> = order.iter().map(|&i| params[i]).collect();
        let wf: Vec<f64> = order.iter().map(|&i| data.weight(i).sqrt()).collect();
        let mut y = Vec::with_capacity(x.len() * dim);
        for (&i, &w) in order.iter().zip(&wf) {
            y.extend(pts.point(i).iter().zip(&center).map(|(q, o)| w * (q - o)));
        }
        let mut sites = x.clone();
        sites.dedup();
        Observations {
            x,
            wf,
            y,
            dim,
            center,
            sites,
        }
    }
}

/// The least weighted residual sum of squares any function of the parameter leaves on the data
/// `obs`: for each group of points with the same parameter, `Σ_i w_i |Q_i − Q̄|²` about the
/// group's weighted mean `Q̄ = Σ w_i Q_i / Σ w_i` (the minimum of `Σ_i w_i |v − Q_i|²` over one
/// value `v`); 0 when the parameters are distinct. The least-squares spline on the knots of
/// interpolation at the distinct parameters reaches it (it passes through every group's mean).
/// Computed from the rows `√w_i·(Q_i − Q_first)`: `√w_i·(Q_i − Q̄) = y_i − √w_i·Q̄`.
pub(super) fn reachable_floor(obs: &Observations) -> f64 {
    let dim = obs.dim;
    let mut floor = 0.0;
    let mut mean = vec![0.0; dim];
    let mut start = 0;
    while start < obs.x.len() {
        let end = start + obs.x[start..].partition_point(|&u| u == obs.x[start]);
        if end - start > 1 {
            // Σ w·Q = Σ √w·y, Σ w = Σ √w²
            let total: f64 = obs.wf[start..end].iter().map(|w| w * w).sum();
            if total > 0.0 {
                mean.fill(0.0);
                for i in start..end {
                    for (m, y) in mean.iter_mut().zip(&obs.y[i * dim..(i + 1) * dim]) {
                        *m += obs.wf[i] * y;
                    }
                }
                mean.iter_mut().for_each(|m| *m /= total);
                for i in start..end {
                    for (m, y) in mean.iter().zip(&obs.y[i * dim..(i + 1) * dim]) {
                        let r = y - obs.wf[i] * m;
                        floor += r * r;
                    }
                }
            }
        }
        start = end;
    }
    floor
}

/// Refuses a target `s` below [`reachable_floor`]: no spline (no function) has a residual that
/// small, so the smoothing condition has no answer.
pub(super) fn check_reachable(obs: &Observations, s: f64) -> Result<()> {
    let floor = reachable_floor(obs);
    if floor > s {
        return Err(Error::InvalidArgument {
            what: "s",
            reason: format!(
                "s = {} is below {}, the weighted residual sum of squares that every function \
                 leaves where points share a parameter (x) with different values (at best it \
                 passes through each group's weighted mean): give s ≥ {}, or average the points \
                 with a repeated parameter",
                readable(&s),
                readable(&floor),
                readable(&floor)
            ),
        });
    }
    Ok(())
}

/// One least-squares pass over the data for a knot vector, keeping each row's first column and
/// weighted basis values for the span residuals.
pub(super) struct LsqPass {
    pub(super) k: usize,
    pub(super) first: Vec<usize>,
    pub(super) rows: Vec<f64>,
    /// `Σ_d (√w_i·(C_d(ū_i) − Q_{i,d}))²` per point, from [`LsqPass::residuals`].
    pub(super) res: Vec<f64>,
}

impl LsqPass {
    pub(super) fn new(obs: &Observations, k: usize) -> Self {
        LsqPass {
            k,
            first: vec![0; obs.x.len()],
            rows: vec![0.0; obs.x.len() * (k + 1)],
            res: vec![0.0; obs.x.len()],
        }
    }

    /// The banded triangle of `min Σ w |C(ū) − Q|²` for the clamped knots `t` (FITPACK's
    /// observation matrix, reduced as it is built: [`QrRows`]).
    pub(super) fn run(&mut self, obs: &Observations, t: &[f64]) -> BandedQr {
        let k = self.k;
        let mut qr = QrRows::new(t.len() - k - 1, k + 1, obs.dim);
        self.fill(obs, t, |i, first, h| {
            qr.push(first, h, &obs.y[i * obs.dim..(i + 1) * obs.dim]);
        });
        qr.finish()
    }

    /// Every row `√w_i·N_{first..first+k}(ū_i)` for the knots `t` (`t.len() − k − 1` basis
    /// functions, spans found by walking the sorted parameters), kept and passed to
    /// `sink(i, first, row)`. The degrees up to 5 get an unrolled kernel ([`SpanBasis`]).
    pub(super) fn fill(
        &mut self,
        obs: &Observations,
        t: &[f64],
        sink: impl FnMut(usize, usize, &[f64]),
    ) {
        match self.k + 1 {
            2 => self.fill_order::<2>(obs, t, sink),
            3 => self.fill_order::<3>(obs, t, sink),
            4 => self.fill_order::<4>(obs, t, sink),
            5 => self.fill_order::<5>(obs, t, sink),
            6 => self.fill_order::<6>(obs, t, sink),
            _ => self.fill_order::<0>(obs, t, sink),
        }
    }

    /// [`LsqPass::fill`] with the order `W = k + 1` known at compile time (`0`: any order).
    fn fill_order<const W: usize>(
        &mut self,
        obs: &Observations,
        t: &[f64],
        mut sink: impl FnMut(usize, usize, &[f64]),
    ) {
        let k = self.k;
        let w = if W == 0 { k + 1 } else { W };
        let nk1 = t.len() - k - 1;
        let mut basis = SpanBasis::<W>::new();
        let mut scratch = BasisScratch::new(if W == 0 { k } else { 0 });
        let mut span = k;
        basis.set_span(t, span);
        let rows = self.rows.chunks_exact_mut(w);
        for (i, ((h, first), (&u, &wf))) in rows
            .zip(self.first.iter_mut())
            .zip(obs.x.iter().zip(&obs.wf))
            .enumerate()
        {
            if span + 1 < nk1 && u >= t[span + 1] {
                while span + 1 < nk1 && u >= t[span + 1] {
                    span += 1;
                }
                basis.set_span(t, span);
            }
            if W == 0 {
                basis_funs_into(t, k, span, u, &mut scratch, h);
                h.iter_mut().for_each(|v| *v *= wf);
            } else {
                basis.eval(u, wf, h);
            }
            *first = span - k;
            sink(i, span - k, h);
        }
    }

    /// [`LsqPass::res`] for the coefficients `c` (`dim` per basis function; for closed fits the
    /// repeated ones included).
    pub(super) fn residuals(&mut self, obs: &Observations, c: &[f64]) {
        match self.k + 1 {
            2 => self.residuals_order::<2>(obs, c),
            3 => self.residuals_order::<3>(obs, c),
            4 => self.residuals_order::<4>(obs, c),
            5 => self.residuals_order::<5>(obs, c),
            6 => self.residuals_order::<6>(obs, c),
            _ => self.residuals_order::<0>(obs, c),
        }
    }

    fn residuals_order<const W: usize>(&mut self, obs: &Observations, c: &[f64]) {
        let (w, dim) = (if W == 0 { self.k + 1 } else { W }, obs.dim);
        let rows = self.rows.chunks_exact(w).zip(&self.first);
        for ((r, (h, &f)), y) in self.res.iter_mut().zip(rows).zip(obs.y.chunks_exact(dim)) {
            let cs = &c[f * dim..(f + w) * dim];
            *r = (0..dim)
                .map(|d| {
                    let v: f64 = h.iter().enumerate().map(|(j, b)| b * cs[j * dim + d]).sum();
                    (v - y[d]) * (v - y[d])
                })
                .sum();
        }
    }
}

/// What [`Knots::add_up_to`] did.
pub(super) enum Added {
    /// Knots were added.
    Some,
    /// The knot count of interpolation is reached.
    Full,
    /// No span holds a distinct parameter strictly inside.
    None,
}

/// The interior knots of the rounds with FITPACK's bookkeeping per span: the residual sum
/// `fpint` and the number of distinct parameters strictly inside, `nrdata`.
pub(super) struct Knots {
    pub(super) k: usize,
    pub(super) a: f64,
    pub(super) b: f64,
    pub(super) interior: Vec<f64>,
    pub(super) fpint: Vec<f64>,
    pub(super) nrdata: Vec<usize>,
}

impl Knots {
    /// No interior knot; the end knots at `domain`, else at the first and last site. The
    /// bookkeeping counts the sites strictly inside, whatever the domain (FITPACK's
    /// `nrdata(1) = m − 2` with `xb ≤ x(1)`, `xe ≥ x(m)`).
    fn new(sites: &[f64], k: usize, domain: Option<(f64, f64)>) -> Self {
        let (a, b) = domain.unwrap_or((sites[0], sites[sites.len() - 1]));
        Knots {
            k,
            a,
            b,
            interior: Vec::new(),
            fpint: vec![0.0],
            nrdata: vec![sites.len().saturating_sub(2)],
        }
    }

    pub(super) fn count(&self) -> usize {
        self.interior.len()
    }

    /// The clamped knot vector.
    fn vector(&self) -> Vec<f64> {
        let k = self.k;
        let mut t = Vec::with_capacity(self.interior.len() + 2 * k + 2);
        t.extend(std::iter::repeat_n(self.a, k + 1));
        t.extend_from_slice(&self.interior);
        t.extend(std::iter::repeat_n(self.b, k + 1));
        t
    }

    /// The knots of interpolation at the distinct parameters (FITPACK's choice for `s = 0`):
    /// the parameters themselves for odd degree, the midpoints for even degree, leaving out
    /// `⌈(k+1)/2⌉`-ish at each end so that there are `sites − k − 1` of them.
    fn interpolation(&mut self, sites: &[f64]) {
        let k = self.k;
        let count = sites.len().saturating_sub(k + 1);
        let j0 = k / 2 + 1;
        self.interior = (0..count)
            .map(|l| {
                let j = j0 + l;
                if k % 2 == 1 {
                    sites[j]
                } else {
                    0.5 * (sites[j] + sites[j - 1])
                }
            })
            .collect();
    }

    /// `fpint`: the residual of each span, a point on a knot counting half to each side.
    fn span_sums(&mut self, obs: &Observations, pass: &LsqPass, t: &[f64]) {
        let k = self.k;
        let nk1 = t.len() - k - 1;
        self.fpint.clear();
        let (mut l, mut part) = (k + 1, 0.0);
        for (&u, &term) in obs.x.iter().zip(&pass.res) {
            let new = l < nk1 && u >= t[l];
            if new {
                l += 1;
            }
            part += term;
            if new {
                self.fpint.push(part - 0.5 * term);
                part = 0.5 * term;
            }
        }
        self.fpint.push(part);
    }

    /// Adds up to `nplus` knots (FITPACK `fpknot`, one at a time) while fewer than `full`
    /// and `cap` interior knots: [`Added::Full`] when `full` is reached (the caller places the
    /// knots of interpolation), [`Added::None`] when no span could be split.
    pub(super) fn add_up_to(
        &mut self,
        sites: &[f64],
        nplus: usize,
        full: usize,
        cap: usize,
    ) -> Added {
        let before = self.count();
        for _ in 0..nplus {
            if !self.add_one(sites) || self.count() >= full || self.count() >= cap {
                break;
            }
        }
        if self.count() >= full {
            Added::Full
        } else if self.count() == before {
            Added::None
        } else {
            Added::Some
        }
    }

    /// Adds one knot at the middle distinct parameter of the span with the largest residual
    /// sum among those with a parameter strictly inside (FITPACK `fpknot`). Returns `false`
    /// when no span can be split.
    fn add_one(&mut self, sites: &[f64]) -> bool {
        let (mut best, mut fpmax, mut begin) = (None, 0.0, 0usize);
        for (j, (&f, &nd)) in self.fpint.iter().zip(&self.nrdata).enumerate() {
            if nd > 0 && f > fpmax {
                fpmax = f;
                best = Some((j, begin));
            }
            begin += nd + 1;
        }
        let Some((j, begin)) = best else {
            return false;
        };
        let maxpt = self.nrdata[j];
        let ihalf = maxpt / 2 + 1;
        let knot = sites[begin + ihalf];
        self.interior.insert(j, knot);
        self.nrdata[j] = ihalf - 1;
        self.nrdata.insert(j + 1, maxpt - ihalf);
        let am = maxpt as f64;
        self.fpint[j] = fpmax * (ihalf - 1) as f64 / am;
        self.fpint
            .insert(j + 1, fpmax * (maxpt - ihalf) as f64 / am);
        true
    }
}

/// FITPACK's number of knots to add next: `min(2·nplus, max(⌊nplus·fpms/decrease⌋,
/// nplus/2, 1))`, doubling when the last round decreased the residual by less than `acc`.
pub(crate) fn next_nplus(nplus: usize, fpms: f64, decrease: f64, acc: f64) -> usize {
    let npl1 = if decrease > acc {
        // FITPACK truncates the real quotient to an integer
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let v = (nplus as f64 * fpms / decrease).min(1e9) as usize;
        v
    } else {
        nplus * 2
    };
    (nplus * 2).min(npl1.max(nplus / 2).max(1))
}

/// The smoothing weight `p` on the final knots (step 3): FITPACK's iteration from `p0`, between
/// the polynomial's residual `fp0` (`p = 0`) and the least-squares spline's `fp_inf`
/// (`p = ∞`), continued towards `s − SMOOTHING_RTOL·s/2` if it ends above `s`. Returns the
/// result with the largest residual `≤ s`, if any. Each weight tried is a step of `steps`.
pub(crate) fn smooth_weight(
    solve: &impl Fn(f64) -> Result<(Vec<f64>, f64)>,
    p0: f64,
    s: f64,
    fp0: f64,
    fp_inf: f64,
    steps: &Steps<'_, '_>,
) -> Result<Option<Below>> {
    let solve = |p: f64| {
        steps.tick()?;
        solve(p)
    };
    let acc = SMOOTHING_RTOL * s;
    let mut it = PIteration {
        p: p0,
        limit: s,
        low: (0.0, fp0),
        high: (-1.0, fp_inf),
    };
    let mut below = None;
    let last = it.run(&solve, s, acc, &mut below)?;
    if last.1 > s {
        it.run(&solve, s - 0.5 * acc, 0.5 * acc, &mut below)?;
    }
    Ok(below)
}

/// Back substitution in the triangle, a zero pivot (a coefficient without data) as an error.
pub(super) fn back_substitute(qr: &BandedQr) -> Result<Vec<f64>> {
    let mut c = vec![0.0; qr.z.len()];
    qr.solve(&mut c).map_err(|col| Error::SingularSystem {
        reason: format!(
            "control point {col} has no data of positive weight under its basis function; \
             give those points a positive weight or remove them"
        ),
    })?;
    Ok(c)
}

/// FITPACK's discontinuity rows (`fpdisc`): for each interior knot `t_l`, the jump of the
/// `k`-th derivative of the `k + 2` B-splines `N_{l−k−1..=l}` there, divided by `scale`.
pub(crate) struct JumpRows {
    /// `k + 2` entries per interior knot; row `j` starts at coefficient `j`.
    pub(crate) rows: Vec<f64>,
    /// `k!·(spans/length)^k`.
    pub(crate) scale: f64,
}

pub(crate) fn jump_rows(t: &[f64], k: usize) -> JumpRows {
    let n = t.len();
    let nk1 = n - k - 1;
    let spans = nk1 - k;
    let fac = spans as f64 / (t[nk1] - t[k]);
    let mut rows = Vec::with_capacity((nk1 - k - 1) * (k + 2));
    let mut h = vec![0.0; 2 * k + 2];
    for l in k + 1..nk1 {
        // differences from t_l to the k + 1 knots before it and the k + 1 after it
        for i in 0..=k {
            h[i] = t[l] - t[l - k - 1 + i];
            h[k + 1 + i] = t[l] - t[l + 1 + i];
        }
        let r = l - k - 1;
        for j in 0..k + 2 {
            let prod = h[j..=j + k].iter().skip(1).fold(h[j], |a, v| a * v * fac);
            rows.push((t[r + j + k + 1] - t[r + j]) / prod);
        }
    }
    let factorial: f64 = (1..=k).map(|v| v as f64).product();
    JumpRows {
        rows,
        scale: factorial * fac.powi(i32::try_from(k).unwrap_or(i32::MAX)),
    }
}

/// A smoothed result `(p, fp, c)`.
pub(crate) type Below = (f64, f64, Vec<f64>);

/// FITPACK's iteration for the smoothing weight `p`: `fp(p)` decreases from the polynomial's
/// residual (`p = 0`) to the least-squares spline's (`p = ∞`, marked `-1`); `low`/`high` hold
/// `(p, fp)` with `fp` above/below the target.
struct PIteration {
    p: f64,
    /// Results above `limit` (the caller's `s`) are never kept.
    limit: f64,
    low: (f64, f64),
    high: (f64, f64),
}

impl PIteration {
    /// Iterates until `|fp − target| < acc` or [`MAX_P_ITERATIONS`]; returns the last
    /// `(p, fp)` and keeps in `below` the result with the largest `fp ≤ limit`.
    fn run(
        &mut self,
        solve: &impl Fn(f64) -> Result<(Vec<f64>, f64)>,
        target: f64,
        acc: f64,
        below: &mut Option<Below>,
    ) -> Result<(f64, f64)> {
        const SHRINK: f64 = 0.04;
        let (mut f1, mut f3) = (self.low.1 - target, self.high.1 - target);
        let (mut p1, mut p3) = (self.low.0, self.high.0);
        let (mut ich1, mut ich3) = (false, false);
        let mut last = None;
        for iter in 1..=MAX_P_ITERATIONS {
            let p = self.p;
            let (c, fp) = solve(p)?;
            let f2 = fp - target;
            last = Some((p, fp));
            if fp <= self.limit && below.as_ref().is_none_or(|b| fp > b.1) {
                *below = Some((p, fp, c));
            }
            if f2.abs() < acc || iter == MAX_P_ITERATIONS {
                break;
            }
            if !ich3 {
                if f2 - f3 <= acc {
                    // p too large
                    (p3, f3) = (p, f2);
                    self.p = p * SHRINK;
                    if self.p <= p1 {
                        self.p = p1 * 0.9 + p * 0.1;
                    }
                    continue;
                }
                ich3 = f2 < 0.0;
            }
            if !ich1 {
                if f1 - f2 <= acc {
                    // p too small
                    (p1, f1) = (p, f2);
                    self.p = p / SHRINK;
                    if p3 >= 0.0 && self.p >= p3 {
                        self.p = p * 0.1 + p3 * 0.9;
                    }
                    continue;
                }
                ich1 = f2 > 0.0;
            }
            if f2 >= f1 || f2 <= f3 {
                // not the expected convex decrease (rounding): keep the last value
                break;
            }
            self.p = rational_root(p1, f1, p, f2, p3, f3);
            if f2 < 0.0 {
                (p3, f3) = (p, f2);
            } else {
                (p1, f1) = (p, f2);
            }
        }
        self.low = (p1, f1 + target);
        self.high = (p3, f3 + target);
        last.ok_or_else(|| Error::SingularSystem {
            reason: "the smoothing iteration made no step".into(),
        })
    }
}

/// The zero of the rational function `r(p) = (u·p + v)/(p + w)` through `(p1, f1)`,
/// `(p2, f2)`, `(p3, f3)`; `p3 < 0` stands for `p3 = ∞` (FITPACK `fprati`).
fn rational_root(p1: f64, f1: f64, p2: f64, f2: f64, p3: f64, f3: f64) -> f64 {
    if p3 < 0.0 {
        return (p1 * (f1 - f3) * f2 - p2 * (f2 - f3) * f1) / ((f1 - f2) * f3);
    }
    let h1 = f1 * (f2 - f3);
    let h2 = f2 * (f3 - f1);
    let h3 = f3 * (f1 - f2);
    -(p1 * p2 * h3 + p2 * p3 * h1 + p3 * p1 * h2) / (p1 * h1 + p2 * h2 + p3 * h3)
}

/// The curve from the coefficients (relative to the reference point) and its report.
pub(super) fn finish(
    data: &FitData<'_>,
    obs: &Observations,
    k: usize,
    t: Vec<f64>,
    c: &[f64],
    lambda: Option<f64>,
) -> CurveFit {
    let mut flat = c.to_vec();
    for p in flat.chunks_exact_mut(obs.dim) {
        p.iter_mut().zip(&obs.center).for_each(|(v, o)| *v += o);
    }
    let curve = BSplineCurve::from_raw(k, t, Points::from_raw(flat, obs.dim));
    let report = FitReport::new(&curve, data, lambda);
    CurveFit { curve, report }
}

/// The arguments every smoothing condition (open and closed) refuses: `s` negative or not finite,
/// a degree of 0 or beyond the library's bound.
pub(crate) fn check_condition_args(degree: usize, s: f64) -> Result<()> {
    if !(s >= 0.0 && s.is_finite()) {
        return Err(Error::NegativeSmoothing {
            what: "s",
            value: s,
        });
    }
    check_degree_bound(degree)?;
    if degree == 0 {
        return Err(Error::Degree {
            degree,
            reason: "the smoothing condition needs degree ≥ 1".into(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::basis_ders_into;

    #[test]
    fn jump_rows_are_the_scaled_jumps_of_the_top_derivative() {
        let k = 3;
        let t = [0.0, 0.0, 0.0, 0.0, 0.3, 0.45, 1.1, 2.0, 2.0, 2.0, 2.0];
        let rows = jump_rows(&t, k);
        let mut scratch = BasisScratch::new(k);
        let mut ders = vec![0.0; (k + 1) * (k + 1)];
        let mut top = |span: usize| {
            let mid = 0.5 * (t[span] + t[span + 1]);
            basis_ders_into(&t, k, span, mid, k, &mut scratch, &mut ders);
            ders[k * (k + 1)..].to_vec()
        };
        for (r, row) in rows.rows.chunks_exact(k + 2).enumerate() {
            let l = r + k + 1;
            let (left, right) = (top(l - 1), top(l));
            // one sign for the whole row
            let sign = (row[0] * (-left[0])).signum();
            for j in 0..k + 2 {
                let jl = if j <= k { left[j] } else { 0.0 };
                let jr = if j >= 1 { right[j - 1] } else { 0.0 };
                let jump = jr - jl;
                let got = sign * row[j] * rows.scale;
                assert!(
                    (got - jump).abs() <= 1e-9 * jump.abs().max(1.0),
                    "knot {l}, B-spline {j}: {got} vs jump {jump}"
                );
            }
        }
    }

    /// The data of a SciPy `make_splrep` test with a repeated x: the two points at x = 310.1
    /// with values 7.2 and 3.6 leave every function `2·w·1.8² = 12.47…`, so `s = 12` is refused
    /// (as SciPy's `make_splrep` refuses it) and `s = 13` is met.
    #[test]
    fn s_below_the_spread_of_repeated_parameters_is_refused() {
        let x = [
            20.00, 153.81, 175.57, 202.47, 237.11, 253.61, 258.56, 273.40, 284.54, 293.61, 298.56,
            301.86, 305.57, 307.22, 308.45, 310.10, 310.10, 310.50,
        ];
        let y = [
            53.00, 49.50, 48.60, 46.80, 43.20, 40.32, 39.60, 36.00, 32.40, 28.80, 25.20, 21.60,
            18.00, 14.40, 10.80, 7.20, 3.60, 0.0,
        ];
        let w = [1.38723f64 * 1.38723; 18];
        let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x)
            .unwrap()
            .with_weights(&w)
            .unwrap();
        let floor = 2.0 * w[0] * 1.8 * 1.8;
        let obs = Observations::new(&data);
        assert!(
            (reachable_floor(&obs) - floor).abs() <= 1e-12 * floor,
            "floor {} vs {floor}",
            reachable_floor(&obs)
        );
        let e = smoothing_condition(&data, 2, 12.0).unwrap_err();
        assert!(
            matches!(&e, Error::InvalidArgument { what: "s", reason } if reason.contains("12.47")),
            "{e}"
        );
        for s in [13.0, 20.0] {
            let fit = smoothing_condition(&data, 2, s).unwrap();
            assert!(
                fit.report.weighted_rss <= s,
                "s = {s}: residual {}",
                fit.report.weighted_rss
            );
        }
        // distinct parameters: nothing is out of reach
        let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &y).unwrap();
        assert_eq!(reachable_floor(&Observations::new(&data)), 0.0);
    }

    #[test]
    fn rational_root_of_a_rational_function_is_exact() {
        // r(p) = (2p − 3)/(p + 1): zero at 1.5
        let r = |p: f64| (2.0 * p - 3.0) / (p + 1.0);
        let got = rational_root(0.5, r(0.5), 1.0, r(1.0), 4.0, r(4.0));
        assert!((got - 1.5).abs() < 1e-12, "root {got}");
    }
}
