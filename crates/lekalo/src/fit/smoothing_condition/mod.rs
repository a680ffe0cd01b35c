//! The smoothing condition: the spline with the fewest knots whose weighted residual sum of
//! squares is at most `s`, within FITPACK's tolerance (FITPACK `curfit`/`parcur`, behind SciPy's `splrep`/`splprep`;
//! `docs/theory/fitting.md#smoothing-condition`).
//!
//! | file | what it does |
//! |---|---|
//! | `mod.rs` | [`smoothing_condition`] and its variants, the checks of their arguments, the curve and report from the coefficients |
//! | `lsq_pass.rs` | the data as rows of the least-squares problem, the residual no spline gets below, one least-squares pass over the data for a knot vector |
//! | `knot_rounds.rs` | step 2: the rounds of least squares and knot addition (FITPACK `fpcurf`/`fpknot`) |
//! | `weight.rs` | step 3: the smoothing weight `p` on the final knots, by FITPACK's rational iteration (`fpdisc`, `fprati`) |

mod knot_rounds;
mod lsq_pass;
#[cfg(test)]
mod tests;
mod weight;

use crate::Arg;
use knot_rounds::knot_rounds;
pub(crate) use knot_rounds::{accepts_least_squares, next_nplus};
pub(in crate::fit) use knot_rounds::{Added, Knots};
pub(in crate::fit) use lsq_pass::{back_substitute, check_reachable, LsqPass, Observations};
pub(in crate::fit) use weight::smooth_on;
pub(crate) use weight::{jump_rows, smooth_weight};

use super::data::{check_in_domain, CurveFit, FitData, FitReport};
use super::progress::Steps;
use crate::error::{check_degree_bound, check_finite, Error, Result};
use crate::numeric::progress::Progress;
use crate::points::Points;
use crate::BSplineCurve;

/// How a round of the smoothing condition's knot addition places its second and later knots
/// (step 2 of [`smoothing_condition`]; `docs/theory/fitting.md#smoothing-condition`). The first
/// knot of a round is the same for both; so are the number of knots a round adds and when the
/// rounds stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KnotRounds {
    /// FITPACK's `fpcurf`/`fpknot` (Dierckx 1993, §5.2.1), as SciPy's `splrep`, `splprep` and
    /// `UnivariateSpline`: one least-squares pass a round; the residual sum of a split span is
    /// shared between its two halves in proportion to the parameters each holds.
    #[default]
    Shared,
    /// SciPy's `generate_knots`, `make_splrep` and `make_splprep` (`_fitpack_repro`): the least
    /// squares refitted after each knot, and the next knot placed by the residual sums of that
    /// fit. One pass a knot: more work, and a different knot vector once a round adds more than
    /// one knot.
    Refit,
}

/// Relative accuracy of the final residual `fp = Σ w_k |C(ū_k) − Q_k|²` (FITPACK's
/// `tol = 0.001`, which SciPy's `splrep` keeps; `acc = SMOOTHING_RTOL·s`): the knot rounds
/// stop at the first least-squares spline with `|fp − s| < acc` and return it as it is, which
/// may lie above `s` by less than `acc` (FITPACK `fpcurf`'s `abs(fpms) .lt. acc`); one with
/// `fp ≤ s − acc` is smoothed to `(1 − SMOOTHING_RTOL)·s ≤ fp ≤ s`.
pub const SMOOTHING_RTOL: f64 = 1e-3;

/// The B-spline of `degree` with the fewest interior knots found whose weighted residual sum of
/// squares `fp = Σ_k w_k |C(ū_k) − Q_k|²` is at most `s`, or above it by less than
/// `SMOOTHING_RTOL·s` (Dierckx 1975, 1993 ch. 5; FITPACK `curfit`
/// for functions and `parcur` for parametric curves, as in SciPy's `splrep(s=…)`/`splprep`).
/// FITPACK's weights multiply the residual, ours its square: `w_k = w_FITPACK²`.
///
/// 1. Start with no interior knot: the least-squares polynomial. If its residual is below
///    `s + SMOOTHING_RTOL·s`, it is the answer.
/// 2. Otherwise add knots where the residual is largest, as FITPACK's `fpcurf`/`fpknot`: the
///    residual is summed per knot span (a point on a knot counts half to each side), and the span
///    with the largest sum among those with a distinct parameter strictly inside is split at its
///    middle such parameter, the sum shared in proportion, unless the split leaves an end short
///    of parameters (unlike FITPACK, whose knots can crowd an end until the system is singular
///    to rounding; `docs/theory/fitting.md#smoothing-condition`). The number added per round starts at
///    1 and follows `nplus = min(2·nplus, max(⌊nplus·(fp − s)/(fp_old − fp)⌋, nplus/2, 1))`.
///    Each round is one least-squares pass: the data rows are reduced into a banded triangle
///    `R` (Householder blocks of the rows of one knot span, `docs/theory/fitting.md#banded-qr`)
///    and kept only for the span residuals. The rounds stop when `fp < s + SMOOTHING_RTOL·s`, or
///    when the knots are those of interpolation (`s = 0` starts there, and a round where no span
///    can be split goes there). A least-squares spline with `|fp − s| < SMOOTHING_RTOL·s` is the
///    answer as it stands, as FITPACK's `fpcurf` accepts it (`abs(fpms) .lt. acc`), also when
///    `fp > s`.
/// 3. On a final knot set with `fp ≤ s − SMOOTHING_RTOL·s`, smooth: add the rows `b_j / p` of FITPACK's `fpdisc` (the jumps of
///    the `p`-th derivative at the interior knots, scaled by `k!·(spans/length)^k`) and find `p`
///    with `|fp(p) − s| < SMOOTHING_RTOL·s` by FITPACK's rational interpolation (`fprati`),
///    starting from `p = n / trace R`. Each `p` rotates only the penalty rows into a copy of
///    the data's `R` and reads the data residual off `R` (`fp = rss₀ + ‖R c − Qᵀy‖²`): O(n·k²),
///    no pass over the data.
///
/// On data with distinct parameters this is FITPACK's algorithm step for step, so the knots and
/// coefficients are SciPy's to rounding (tested on stored SciPy values), except where a split
/// would leave an end short of parameters (above), and where FITPACK's smoothing weight would
/// give a residual above `s`: the iteration for `p` continues towards `s − SMOOTHING_RTOL·s/2`,
/// so a smoothed result never exceeds `s` (a least-squares one may, by less than
/// `SMOOTHING_RTOL·s`, as FITPACK's).
/// Repeated parameters are allowed: knots are placed among the distinct ones. Where points share
/// a parameter with different values no function meets them all: every spline leaves at least
/// their spread about the group's weighted mean ([`reachable_floor`](lsq_pass::reachable_floor)), and an `s` below it is
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
/// assert!(fit.report.weighted_rss < 0.3 * (1.0 + 1e-3));
/// assert!(fit.report.n_ctrl < 30);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::NegativeSmoothing`] for `s < 0` or NaN; [`Error::Degree`] for degree 0;
/// [`Error::TooFew`] for fewer than `degree + 1` distinct parameters;
/// [`Error::InvalidArgument`] (about [`Arg::S`](crate::Arg::S)) for `s` below the residual that repeated
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
    smoothing_condition_with_rounds(data, degree, s, None, KnotRounds::Shared, progress)
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
/// assert!(fit.report.weighted_rss < 0.1 * (1.0 + 1e-3));
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
    smoothing_condition_with_rounds(data, degree, s, Some(domain), KnotRounds::Shared, progress)
}

/// The domain `(a, b)` of a fit: finite, `a < b`, holding every data parameter.
fn check_domain(data: &FitData<'_>, (a, b): (f64, f64)) -> Result<()> {
    check_finite("domain (a, b) of the smoothing condition", &[a, b])?;
    if a >= b {
        return Err(Error::EmptyDomain { min: a, max: b });
    }
    check_in_domain(data.params(), (a, b))
}

/// [`smoothing_condition_with_progress`] (`domain` `None`: the data's own ends) and
/// [`smoothing_condition_in_with_progress`] (`domain` given) with a round's knots placed as
/// `rounds` says: [`KnotRounds::Refit`] gives SciPy's `make_splrep(x, y, s=…)` (the knots of
/// SciPy's `generate_knots`), [`KnotRounds::Shared`] FITPACK's `curfit` (SciPy's `splrep`).
///
/// ```
/// use lekalo::fit::{smoothing_condition_with_rounds, FitData, KnotRounds};
/// use lekalo::{PointsRef, Progress};
/// let x: Vec<f64> = (0..200).map(|k| k as f64 / 199.0).collect();
/// let y: Vec<f64> = x.iter().enumerate().map(|(k, t)| (6.0 * t).sin() + 0.01 * ((k * 7919 % 13) as f64 - 6.0)).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let quiet = Progress::new();
/// let fit = smoothing_condition_with_rounds(&data, 3, 0.3, None, KnotRounds::Refit, &quiet)?;
/// assert!(fit.report.weighted_rss < 0.3 * (1.0 + 1e-3));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`smoothing_condition_in_with_progress`].
pub fn smoothing_condition_with_rounds(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: Option<(f64, f64)>,
    rounds: KnotRounds,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    smoothing_condition_with_limit(
        data,
        degree,
        s,
        domain,
        rounds,
        KnotLimit::Unlimited,
        progress,
    )
}

/// How many knots the rounds of the smoothing condition may place (FITPACK `curfit`'s `nest`,
/// counting the end knots), and what they do there.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KnotLimit {
    /// No limit below the knots of interpolation (`nest = m + k + 1`, as SciPy's `splrep`).
    #[default]
    Unlimited,
    /// At most this many knots: a round that reaches them ends the rounds with the
    /// least-squares spline on them, whatever its residual (FITPACK `curfit`, `ier = 1`).
    Stop(usize),
    /// The rounds stop at this many knots as [`KnotLimit::Stop`], then go on from the knots
    /// reached without limit, the next round adding one knot as the first round does: SciPy's
    /// `UnivariateSpline`, which calls `fpcurf` with `nest = max(m/2, 2k + 2)` and, on
    /// `ier = 1`, again with `iopt = 1`, `nest = m + k + 1` and that `ier = 1`, which resets
    /// FITPACK's `nplus` to 1. The knots differ from an unlimited run's from the limit on.
    Resume(usize),
}

/// [`smoothing_condition_with_rounds`] with the knots the rounds may place bounded as `limit`
/// says (FITPACK `curfit`'s `nest`; Dierckx 1993, §5.2.1): [`KnotLimit::Resume`] with
/// `max(m/2, 2·degree + 2)` for `m` data gives SciPy's `UnivariateSpline(x, y, s=…)`.
///
/// ```
/// use lekalo::fit::{smoothing_condition_with_limit, FitData, KnotLimit, KnotRounds};
/// use lekalo::{PointsRef, Progress};
/// let x: Vec<f64> = (0..40).map(|k| k as f64 / 4.0).collect();
/// let y: Vec<f64> = x.iter().enumerate().map(|(k, t)| t.sin() + 0.1 * ((k * 7919 % 13) as f64 - 6.0) / 6.0).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let quiet = Progress::new();
/// let fit = |limit| smoothing_condition_with_limit(&data, 3, 0.05, None, KnotRounds::Shared, limit, &quiet);
/// // stopped at 20 knots: the least-squares spline on them, its residual above s
/// let stopped = fit(KnotLimit::Stop(20))?;
/// assert_eq!(stopped.curve.knots().len(), 20);
/// assert!(stopped.report.weighted_rss > 0.05);
/// // resumed from them: the residual within s again
/// let resumed = fit(KnotLimit::Resume(20))?;
/// assert!(resumed.report.weighted_rss < 0.05 * 1.001);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`smoothing_condition_in_with_progress`]; [`Error::TooFew`] for a limit below
/// `2·degree + 2`.
pub fn smoothing_condition_with_limit(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: Option<(f64, f64)>,
    rounds: KnotRounds,
    limit: KnotLimit,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    let start = RoundsStart::Fresh(limit);
    smoothing_condition_from(data, degree, s, domain, rounds, start, progress).map(|(f, _)| f)
}

/// Where the knot rounds of a smoothing condition ended, for a later call with another `s` on
/// the same data to go on from: what FITPACK's `fpcurf` keeps between calls for `curfit`'s
/// `iopt = 1` (in `fpint(n)`, `fpint(n − 1)`, `nrdata(n)` and `ier`; Dierckx, "Curve and
/// Surface Fitting with Splines", 1993, §5.2.1), as SciPy's
/// `UnivariateSpline.set_smoothing_factor` uses it. Returned by [`smoothing_condition_from`].
#[derive(Debug, Clone, PartialEq)]
pub struct RoundsState {
    /// The interior knots of the last least-squares pass: those of the fit.
    pub interior: Vec<f64>,
    /// `fp0`: the weighted residual sum of squares of the least-squares polynomial.
    pub fp0: f64,
    /// `fpold`: the residual of the least-squares pass before the last (0 when the last pass
    /// was the first of its call).
    pub fp_before: f64,
    /// `nplus`: the number of knots the round before the last pass set out to add.
    pub nplus: usize,
    /// Whether the next round adds one knot, as a first round does (FITPACK's `ier ≠ 0`: the
    /// rounds ended at the polynomial, at interpolation or at their knot limit).
    pub restart: bool,
    /// The knot limit a continuation runs under: the call's own, or [`KnotLimit::Unlimited`]
    /// once the rounds went past a [`KnotLimit::Resume`] limit (SciPy's `nest` raised to
    /// `m + k + 1` for good).
    pub limit: KnotLimit,
}

impl RoundsState {
    /// The state fits the distinct data parameters `sites`: finite residuals, interior knots
    /// strictly increasing strictly inside the first and last parameter, at most `full` of
    /// them (those of interpolation), and each at a parameter unless there are `full` (the
    /// knots of interpolation, between the parameters for even degree), as the rounds place
    /// them.
    fn check(&self, sites: &[f64], full: usize) -> Result<()> {
        let bad = |reason: String| Error::InvalidArgument {
            what: ROUNDS_STATE.into(),
            reason: format!(
                "{reason}; continue only from the state an earlier smoothing condition on the \
                 same data returned"
            ),
        };
        check_finite(ROUNDS_STATE, &[self.fp0, self.fp_before])?;
        check_finite(ROUNDS_STATE, &self.interior)?;
        let (first, last) = (sites[0], sites[sites.len() - 1]);
        if self.interior.len() > full {
            return Err(bad(format!(
                "{} interior knots, more than the {full} of interpolation",
                self.interior.len()
            )));
        }
        let mut before = first;
        for (i, &u) in self.interior.iter().enumerate() {
            if !(u > before && u < last) {
                return Err(bad(format!(
                    "interior knot {i} = {u} is not strictly between {before} and {last}"
                )));
            }
            if self.interior.len() < full && sites.binary_search_by(|v| v.total_cmp(&u)).is_err() {
                return Err(bad(format!(
                    "interior knot {i} = {u} is not a data parameter, where the rounds place knots"
                )));
            }
            before = u;
        }
        Ok(())
    }
}

/// What the errors about a [`RoundsState`] name.
const ROUNDS_STATE: &str = "state of earlier knot rounds (RoundsState)";

/// Where [`smoothing_condition_from`] starts its knot rounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RoundsStart<'a> {
    /// From the least-squares polynomial (FITPACK `curfit`'s `iopt = 0`), under this limit.
    Fresh(KnotLimit),
    /// From where an earlier call on the same data ended (`curfit`'s `iopt = 1`), under the
    /// limit it left ([`RoundsState::limit`]).
    Continue(&'a RoundsState),
}

impl RoundsStart<'_> {
    /// The knot limit the rounds run under.
    fn limit(self) -> KnotLimit {
        match self {
            RoundsStart::Fresh(limit) => limit,
            RoundsStart::Continue(st) => st.limit,
        }
    }
}

/// [`smoothing_condition_with_limit`] started as `start` says, returning with the fit the
/// [`RoundsState`] a later call goes on from: FITPACK `curfit` with `iopt = 0` for
/// [`RoundsStart::Fresh`], with `iopt = 1` for [`RoundsStart::Continue`] (Dierckx 1993, §5.2.1;
/// SciPy's `UnivariateSpline.set_smoothing_factor`, which calls `fpcurf` again on the state of
/// the last fit). A continuation with `s > 0` starts over from the polynomial when the earlier
/// fit had no interior knot or `s ≥ fp0`; otherwise its first round is the least-squares pass
/// on the earlier knots, which is the answer, or is smoothed (step 3), when its residual is
/// within or below `s`, and otherwise gets knots added as the earlier rounds would have gone on:
/// `nplus` from the earlier rounds' last two residuals and count (one knot when
/// [`RoundsState::restart`]), the knots where the residual is largest. Its knots may differ
/// from a fresh fit's with the same `s`, whose rounds took other counts of knots on the way
/// (`nplus` depends on `s`). With `s = 0` both give the knots of interpolation.
///
/// ```
/// use lekalo::fit::{smoothing_condition_from, FitData, KnotLimit, KnotRounds, RoundsStart};
/// use lekalo::{PointsRef, Progress};
/// let x: Vec<f64> = (0..60).map(|k| k as f64 / 6.0).collect();
/// let y: Vec<f64> = x.iter().enumerate().map(|(k, t)| t.sin() + 0.1 * ((k * 7919 % 13) as f64 - 6.0) / 6.0).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let quiet = Progress::new();
/// let fit = |s, start| smoothing_condition_from(&data, 3, s, None, KnotRounds::Shared, start, &quiet);
/// let (coarse, state) = fit(1.0, RoundsStart::Fresh(KnotLimit::Unlimited))?;
/// // s = 0.2 needs more knots: the rounds go on from the coarse fit's knots
/// let (fine, _) = fit(0.2, RoundsStart::Continue(&state))?;
/// assert!(fine.curve.knots().len() > coarse.curve.knots().len());
/// assert!(fine.report.weighted_rss < 0.2 * 1.001);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`smoothing_condition_with_limit`]; [`Error::NonFinite`] / [`Error::InvalidArgument`]
/// for a [`RoundsState`] that does not fit the data (knots not strictly increasing inside the
/// data's parameters, not at data parameters, more than interpolation's).
pub fn smoothing_condition_from(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: Option<(f64, f64)>,
    rounds: KnotRounds,
    start: RoundsStart<'_>,
    progress: &Progress<'_>,
) -> Result<(CurveFit, RoundsState)> {
    check_condition_args(degree, s)?;
    if let Some(domain) = domain {
        check_domain(data, domain)?;
    }
    let steps = Steps::new(progress, "smoothing condition (knot rounds, weights)");
    let obs = Observations::new(data);
    check_reachable(&obs, s)?;
    let k = degree;
    let (ended, state) = knot_rounds(&obs, k, s, domain, rounds, start, &steps, &mut |_| {})?;
    let fit = ended.into_fit(data, &obs, k, &steps, |t, qr, fp0, fp_inf| {
        smooth_on(&obs, k, t, qr, s, fp0, fp_inf, &steps)
    })?;
    Ok((fit, state))
}

/// The knot vectors of the rounds of [`smoothing_condition`], in order: the clamped knot vector
/// of each least-squares pass of step 2 (the first without interior knots, unless `s = 0`,
/// whose only round is on the knots of interpolation). The last is the knot vector the
/// smoothing condition smooths on (Dierckx, "Curve and Surface Fitting with Splines", 1993,
/// ch. 5). With [`KnotRounds::Refit`] this is SciPy's `generate_knots(x, y, k=…, s=…, nest=…)`;
/// with [`KnotRounds::Shared`] the rounds of FITPACK's `curfit` (SciPy's `splrep`).
/// `max_knots` (SciPy's `nest`, at least `2·degree + 2`) stops the rounds once a knot vector
/// has that many knots; `None` runs them to the end.
///
/// ```
/// use lekalo::fit::{smoothing_knot_sequence, FitData, KnotRounds};
/// use lekalo::PointsRef;
/// let x: Vec<f64> = (0..8).map(|k| k as f64).collect();
/// let y: Vec<f64> = x.iter().map(|v| (v * std::f64::consts::PI / 8.0).sin()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let seq = smoothing_knot_sequence(&data, 3, 1e-7, None, KnotRounds::Refit)?;
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
    rounds: KnotRounds,
) -> Result<Vec<Vec<f64>>> {
    check_condition_args(degree, s)?;
    check_max_knots(degree, max_knots)?;
    let start = RoundsStart::Fresh(max_knots.map_or(KnotLimit::Unlimited, KnotLimit::Stop));
    let obs = Observations::new(data);
    rounds_knots(|steps, seen| knot_rounds(&obs, degree, s, None, rounds, start, steps, seen))
}

/// The knot vectors a knot-round loop `rounds(steps, seen)` passes to `seen`, in order, with
/// no progress reported: the knot sequences of [`smoothing_knot_sequence`] and
/// [`crate::fit::periodic_smoothing_knot_sequence`].
pub(in crate::fit) fn rounds_knots<R>(
    rounds: impl FnOnce(&Steps<'_, '_>, &mut dyn FnMut(&[f64])) -> Result<R>,
) -> Result<Vec<Vec<f64>>> {
    let mut seq = Vec::new();
    let quiet = Progress::new();
    let steps = Steps::new(&quiet, "");
    rounds(&steps, &mut |t| seq.push(t.to_vec()))?;
    Ok(seq)
}

/// `max_knots` as a count of interior knots (`usize::MAX` for none), refusing fewer knots than
/// the polynomial has.
pub(in crate::fit) fn check_max_knots(degree: usize, max_knots: Option<usize>) -> Result<usize> {
    match max_knots {
        None => Ok(usize::MAX),
        Some(n) if n < 2 * degree + 2 => Err(Error::TooFew {
            what: "knots allowed (max_knots, SciPy's nest): the polynomial has 2·degree + 2".into(),
            min: 2 * degree + 2,
            got: n,
        }),
        Some(n) => Ok(n - 2 * degree - 2),
    }
}
/// Where the knot rounds of step 2 ended, `Q` the least-squares triangle of the data (banded
/// for open curves, cyclic for closed ones).
pub(in crate::fit) enum Rounds<Q> {
    /// The answer: the knots and the least-squares coefficients on them.
    Done { t: Vec<f64>, c: Vec<f64> },
    /// Knots whose least-squares residual `fp_inf` is below `s`: smooth on them (step 3).
    Smooth {
        t: Vec<f64>,
        qr: Q,
        fp0: f64,
        fp_inf: f64,
    },
}

impl<Q> Rounds<Q> {
    /// The fitted curve and its report: the least-squares coefficients when the rounds ended
    /// with the answer, else those of `smooth(t, qr, fp0, fp_inf)` (coefficients and λ, step
    /// 3); `steps` finished.
    pub(super) fn into_fit(
        self,
        data: &FitData<'_>,
        obs: &Observations,
        k: usize,
        steps: &Steps<'_, '_>,
        smooth: impl FnOnce(&[f64], &Q, f64, f64) -> Result<(Vec<f64>, Option<f64>)>,
    ) -> Result<CurveFit> {
        let fit = match self {
            Rounds::Done { t, c } => finish(data, obs, k, t, &c, None),
            Rounds::Smooth { t, qr, fp0, fp_inf } => {
                let (c, lambda) = smooth(&t, &qr, fp0, fp_inf)?;
                finish(data, obs, k, t, &c, lambda)
            }
        };
        steps.finish();
        Ok(fit)
    }
}

/// The curve from the coefficients (relative to the reference point) and its report.
pub(in crate::fit) fn finish(
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
            what: Arg::S.into(),
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
