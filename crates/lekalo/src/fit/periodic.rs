//! Closed (periodic) fits: least squares with given knots and the smoothing condition on
//! periodic knots (FITPACK `fpperi`, SciPy's `splrep(per=1)`; `docs/theory/fitting.md#periodic`).
//!
//! A periodic spline of degree `k` on `[a, b)` with breakpoints `a = τ_0 < … < τ_np = b` has
//! the knots `τ` extended by the period `P = b − a` on both sides
//! (`t_{k−j} = t_{k+np−j} − P`, `t_{k+np+j} = t_{k+j} + P`) and `np` free control points
//! `c_0 … c_{np−1}`, repeated: `c_{np+j} = c_j` for `j < k`. The result is an ordinary
//! [`BSplineCurve`] with unclamped knots whose domain is `[a, b]` and which closes with `C^{k−1}`
//! continuity.

use super::cyclic::CyclicQr;
use super::data::{check_in_domain, CurveFit, FitData};
use super::progress::Steps;
use super::smoothing_condition::{
    accepts_least_squares, check_condition_args, check_max_knots, check_reachable, finish,
    jump_rows, next_nplus, rounds_knots, smooth_weight, Added, Knots, LsqPass, Observations,
    Rounds, SMOOTHING_RTOL,
};
use crate::error::{check_degree_bound, check_finite, Error, Result};
use crate::interpolate::parametrization::parametrize_impl;
use crate::numeric::progress::Progress;
use crate::points::PointsRef;
use crate::{Arg, Parametrization};

/// Parameters of the points of a closed polygon: one per point and one more, the end of the
/// period, for the chord back to the first point (as closed interpolation does). Use the first
/// and last as the domain of [`periodic_least_squares`] or [`periodic_smoothing_condition`].
///
/// ```
/// use lekalo::fit::closed_parameters;
/// use lekalo::{Parametrization, PointsRef};
/// let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
/// let u = closed_parameters(PointsRef::from_flat(2, &square)?, Parametrization::ChordLength)?;
/// assert_eq!(u, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`parametrize`](crate::parametrize): too few points, coincident points, non-finite values.
pub fn closed_parameters(points: PointsRef<'_>, method: Parametrization) -> Result<Vec<f64>> {
    parametrize_impl(points, method, true)
}

/// The weighted least-squares closed spline of `degree` with breakpoints `breaks`
/// (`a = τ_0 < τ_1 < … < τ_np = b`): minimises `Σ_k w_k |C(ū_k) − Q_k|²` over the `np` free
/// control points of the periodic spline (module documentation). The same problem as SciPy's
/// `splrep(x, y, t=interior, per=1)` (FITPACK `fpperi` with given knots), which ignores its last
/// data point, the repetition of the first.
///
/// Data parameters lie in `[a, b]`; a parameter `b` is the point `a` of the closed curve. Solved
/// by a banded QR whose band wraps around the corner ([`CyclicQr`]: band plus a border of `k`
/// columns, `docs/theory/fitting.md#periodic`): O(N·k·(k + dim)) time, O(np·k) memory, no
/// dense matrix.
///
/// ```
/// use lekalo::fit::{periodic_least_squares, FitData};
/// use lekalo::PointsRef;
/// use std::f64::consts::TAU;
/// // a trigonometric curve, fitted closed
/// let u: Vec<f64> = (0..60).map(|k| TAU * k as f64 / 60.0).collect();
/// let q: Vec<f64> = u.iter().flat_map(|t| [t.cos(), t.sin()]).collect();
/// let data = FitData::new(PointsRef::from_flat(2, &q)?, &u)?;
/// let breaks: Vec<f64> = (0..=8).map(|j| TAU * j as f64 / 8.0).collect();
/// let fit = periodic_least_squares(&data, 3, &breaks)?;
/// assert!(fit.report.max_residual < 2e-3);
/// let (a, b) = (fit.curve.eval(0.0)?, fit.curve.eval(TAU)?);
/// assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Degree`]; [`Error::TooFew`] for fewer than two breakpoints;
/// [`Error::NonFinite`] / [`Error::NotIncreasing`] / [`Error::KnotMultiplicity`] for
/// breakpoints that are not finite and strictly increasing; [`Error::ParameterOutOfDomain`]
/// for a data parameter outside `[a, b]`; [`Error::SchoenbergWhitney`] when the data leave a
/// control point without data (too few distinct parameters for the spans).
pub fn periodic_least_squares(
    data: &FitData<'_>,
    degree: usize,
    breaks: &[f64],
) -> Result<CurveFit> {
    periodic_least_squares_with_progress(data, degree, breaks, &Progress::new())
}

/// [`periodic_least_squares`] reporting to `progress` before its pass over the data and at the
/// end (`(done, done)`), and stopping with [`Error::Cancelled`] before the pass when its cancel
/// flag is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`periodic_least_squares`], and [`Error::Cancelled`].
pub fn periodic_least_squares_with_progress(
    data: &FitData<'_>,
    degree: usize,
    breaks: &[f64],
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    check_degree_bound(degree)?;
    check_breaks(breaks)?;
    let steps = Steps::new(progress, "closed least-squares fit");
    let (a, b) = (breaks[0], breaks[breaks.len() - 1]);
    let wrapped = wrap_params(data, (a, b))?;
    let obs = observations(data, &wrapped)?;
    let mut pass = LsqPass::new(&obs, degree);
    let (t, _, c) = fit_on(&mut pass, &obs, breaks, &steps)?;
    let fit = finish(data, &obs, degree, t, &c, None);
    steps.finish();
    Ok(fit)
}

/// The closed spline of `degree` with the fewest knots found whose weighted residual sum of
/// squares is at most `s`, or above it by less than [`SMOOTHING_RTOL`]`·s`, on the period
/// `domain = (a, b)` (FITPACK `fpperi`, SciPy's
/// `splrep(x, y, s=…, per=1)`; `docs/theory/fitting.md#periodic`).
///
/// The steps of [`smoothing_condition`](super::smoothing_condition) with periodic knots:
/// start from the least-squares constant (the only periodic polynomial); unless its residual is
/// below `s + SMOOTHING_RTOL·s` (FITPACK's `fp0 − s < acc`), put one knot at the middle distinct parameter, then add knots where the residual
/// is largest (`fpknot`, FITPACK's per-span sums in which the first point counts in the first
/// and the last span), each round one banded QR pass ([`periodic_least_squares`]); on the final
/// knots find the weight `p` of the jump rows of the `k`-th derivative at the interior knots by
/// FITPACK's rational iteration. The rounds stop, and a least-squares spline is accepted as it
/// stands, as for open curves: at the first with `|fp − s| < SMOOTHING_RTOL·s` (`fpperi`'s
/// `abs(fpms) .lt. acc`, which may be above `s`); a smoothed result never exceeds `s`. As
/// FITPACK, no jump is penalised at `a ≡ b`. On data with distinct parameters starting at `a`, this is
/// FITPACK's algorithm step for step (knots and coefficients tested against SciPy). Data
/// parameters lie in `[a, b]`, a parameter `b` standing for `a`; FITPACK's data end with the
/// repetition of the first point at `b`, which it ignores: leave it out (or give it weight 0).
///
/// ```
/// use lekalo::fit::{periodic_smoothing_condition, FitData};
/// use lekalo::PointsRef;
/// use std::f64::consts::TAU;
/// let x: Vec<f64> = (0..200).map(|k| TAU * k as f64 / 200.0).collect();
/// let y: Vec<f64> = x.iter().enumerate().map(|(k, t)| t.cos() + 0.01 * ((k * 7919 % 13) as f64 - 6.0)).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let fit = periodic_smoothing_condition(&data, 3, 0.3, (0.0, TAU))?;
/// assert!(fit.report.weighted_rss < 0.3 * (1.0 + 1e-3));
/// assert!(fit.report.n_ctrl < 20);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::NegativeSmoothing`] for `s < 0` or NaN; [`Error::Degree`] for degree 0;
/// [`Error::EmptyDomain`] / [`Error::NonFinite`] for a bad domain;
/// [`Error::ParameterOutOfDomain`]; [`Error::TooFew`] for fewer than `degree + 1` distinct
/// parameters; [`Error::InvalidArgument`] (about [`Arg::S`](crate::Arg::S)) for `s` below the residual that
/// repeated parameters with different values leave to every function (`b` repeats `a`);
/// [`Error::SingularSystem`] when zero weights leave a coefficient without data.
pub fn periodic_smoothing_condition(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: (f64, f64),
) -> Result<CurveFit> {
    periodic_smoothing_condition_with_progress(data, degree, s, domain, &Progress::new())
}

/// [`periodic_smoothing_condition`] reporting to `progress` after each round of knot addition
/// and each smoothing weight tried (`done` the steps so far, `total` one more: their number is
/// not known ahead; `(done, done)` at the end), and stopping with [`Error::Cancelled`] between
/// two steps when its cancel flag is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`periodic_smoothing_condition`], and [`Error::Cancelled`].
pub fn periodic_smoothing_condition_with_progress(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: (f64, f64),
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    check_condition_args(degree, s)?;
    let steps = Steps::new(
        progress,
        "closed smoothing condition (knot rounds, weights)",
    );
    let k = degree;
    let (obs, sites) = periodic_observations(data, k, domain)?;
    check_reachable(&obs, s)?;
    periodic_rounds(&obs, &sites, k, s, domain, usize::MAX, &steps, &mut |_| {})?.into_fit(
        data,
        &obs,
        k,
        &steps,
        |t, qr, fp0, fp_inf| smooth_periodic(&obs, k, t, qr, s, fp0, fp_inf, &steps),
    )
}

/// The knot vectors of the rounds of [`periodic_smoothing_condition`], in order (SciPy's
/// `generate_knots(…, bc_type="periodic")`): the constant's knots when the constant is the
/// answer, otherwise each round's periodic knot vector, starting with one interior knot; for
/// `s = 0` only the knots of periodic interpolation. `max_knots` (SciPy's `nest`) stops the
/// rounds once a knot vector has that many knots.
///
/// ```
/// use lekalo::fit::{periodic_smoothing_knot_sequence, FitData};
/// use lekalo::PointsRef;
/// use std::f64::consts::TAU;
/// let x: Vec<f64> = (0..40).map(|k| TAU * k as f64 / 40.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| t.sin() + 0.3 * (3.0 * t).cos()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let seq = periodic_smoothing_knot_sequence(&data, 3, 1e-3, (0.0, TAU), None)?;
/// assert_eq!(seq[0].len(), 2 * 3 + 3); // one interior knot
/// assert!(seq.windows(2).all(|w| w[0].len() < w[1].len()));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`periodic_smoothing_condition`]; [`Error::TooFew`] for `max_knots < 2·degree + 2`.
pub fn periodic_smoothing_knot_sequence(
    data: &FitData<'_>,
    degree: usize,
    s: f64,
    domain: (f64, f64),
    max_knots: Option<usize>,
) -> Result<Vec<Vec<f64>>> {
    check_condition_args(degree, s)?;
    let cap = check_max_knots(degree, max_knots)?;
    let (obs, sites) = periodic_observations(data, degree, domain)?;
    rounds_knots(|steps, seen| periodic_rounds(&obs, &sites, degree, s, domain, cap, steps, seen))
}

/// The closed spline of `degree` on the breakpoints `breaks` (`a = τ_0 < … < τ_np = b`) that
/// minimises the sum of squared jumps of the `k`-th derivative at the interior breakpoints
/// subject to a weighted residual sum of squares of `s` (FITPACK `percur` with given knots,
/// SciPy's `make_splrep(x, y, t=…, s=…, bc_type="periodic")`; Dierckx, "Curve and Surface
/// Fitting with Splines", 1993, ch. 5 and 6; `docs/theory/fitting.md#smoothing-on-given-knots`). The smoothing weight is found by the
/// rational iteration of [`periodic_smoothing_condition`]'s last step, between the least-squares
/// constant and the least-squares spline on `breaks`; with no interior breakpoint the answer is
/// the least-squares constant. When the least-squares spline's residual is above `s`, no weight
/// reaches `s` and the result is that spline (its report shows the residual).
///
/// ```
/// use lekalo::fit::{periodic_smoothing_on_knots, FitData};
/// use lekalo::PointsRef;
/// use std::f64::consts::TAU;
/// let x: Vec<f64> = (0..60).map(|k| TAU * k as f64 / 60.0).collect();
/// let y: Vec<f64> = x.iter().map(|t| t.sin() + 0.2 * (5.0 * t).cos()).collect();
/// let data = FitData::new(PointsRef::from_flat(1, &y)?, &x)?;
/// let breaks: Vec<f64> = (0..=12).map(|j| TAU * j as f64 / 12.0).collect();
/// let fit = periodic_smoothing_on_knots(&data, 3, &breaks, 0.5)?;
/// assert!((fit.report.weighted_rss - 0.5).abs() <= 1e-3 * 0.5);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// As [`periodic_least_squares`], and [`Error::NegativeSmoothing`] for `s < 0` or NaN.
pub fn periodic_smoothing_on_knots(
    data: &FitData<'_>,
    degree: usize,
    breaks: &[f64],
    s: f64,
) -> Result<CurveFit> {
    periodic_smoothing_on_knots_with_progress(data, degree, breaks, s, &Progress::new())
}

/// [`periodic_smoothing_on_knots`] reporting to `progress` after its least-squares passes and
/// each smoothing weight tried (`done` the steps so far, `total` one more; `(done, done)` at
/// the end), and stopping with [`Error::Cancelled`] between two steps when its cancel flag is
/// set. The result is the same with or without the hook.
///
/// # Errors
/// As [`periodic_smoothing_on_knots`], and [`Error::Cancelled`].
pub fn periodic_smoothing_on_knots_with_progress(
    data: &FitData<'_>,
    degree: usize,
    breaks: &[f64],
    s: f64,
    progress: &Progress<'_>,
) -> Result<CurveFit> {
    check_condition_args(degree, s)?;
    check_breaks(breaks)?;
    let steps = Steps::new(progress, "closed smoothing on given knots (weights)");
    let k = degree;
    let (a, b) = (breaks[0], breaks[breaks.len() - 1]);
    let wrapped = wrap_params(data, (a, b))?;
    let obs = observations(data, &wrapped)?;
    let mut pass = LsqPass::new(&obs, k);
    let (t, qr, c) = fit_on(&mut pass, &obs, breaks, &steps)?;
    if breaks.len() == 2 {
        steps.finish();
        return Ok(finish(data, &obs, k, t, &c, None));
    }
    let fp_inf = qr.rss;
    let fp0 = fit_on(&mut pass, &obs, &[a, b], &steps)?.1.rss;
    let (c, lambda) = smooth_periodic(&obs, k, &t, &qr, s, fp0, fp_inf, &steps)?;
    let fit = finish(data, &obs, k, t, &c, lambda);
    steps.finish();
    Ok(fit)
}

/// The data of a closed smoothing condition: the observations at the wrapped parameters and
/// FITPACK's sites `a = x_0 < … < x_{m−1} = b`.
fn periodic_observations(
    data: &FitData<'_>,
    k: usize,
    (a, b): (f64, f64),
) -> Result<(Observations, Vec<f64>)> {
    check_breaks(&[a, b])?;
    let wrapped = wrap_params(data, (a, b))?;
    let obs = observations(data, &wrapped)?;
    if obs.sites.len() < k + 1 {
        return Err(Error::TooFew {
            what: "distinct data parameters in the period for the smoothing condition \
                   (degree + 1)"
                .into(),
            min: k + 1,
            got: obs.sites.len(),
        });
    }
    // FITPACK's x(1) = a, …, x(m) = b
    let mut sites = obs.sites.clone();
    if sites[0] > a {
        sites.insert(0, a);
    }
    sites.push(b);
    Ok((obs, sites))
}

/// The knot rounds of [`periodic_smoothing_condition`], at most `cap` interior knots, each
/// round's knot vector (and the constant's when it is the answer) passed to `seen`, each pass a
/// step of `steps`.
#[allow(clippy::too_many_arguments)]
fn periodic_rounds(
    obs: &Observations,
    sites: &[f64],
    k: usize,
    s: f64,
    (a, b): (f64, f64),
    cap: usize,
    steps: &Steps<'_, '_>,
    seen: &mut dyn FnMut(&[f64]),
) -> Result<Rounds<CyclicQr>> {
    let m = sites.len();
    let acc = SMOOTHING_RTOL * s;
    let full = m - 2;
    let mut pass = LsqPass::new(obs, k);
    let mut knots = Knots {
        k,
        a,
        b,
        interior: Vec::new(),
        fpint: Vec::new(),
        nrdata: Vec::new(),
        end_keep: 0,
    };
    let breaks = |interior: &[f64]| {
        let mut v = Vec::with_capacity(interior.len() + 2);
        v.push(a);
        v.extend_from_slice(interior);
        v.push(b);
        v
    };
    if s == 0.0 {
        knots.interior = interpolation_knots(sites, k);
        let (t, _, c) = fit_on(&mut pass, obs, &breaks(&knots.interior), steps)?;
        seen(&t);
        return Ok(Rounds::Done { t, c });
    }
    // the least-squares constant
    let (t, qr, c) = fit_on(&mut pass, obs, &[a, b], steps)?;
    let fp0 = qr.rss;
    // FITPACK `fpperi`: the constant is the answer when `fp0 − s < acc`, within the accuracy
    // above `s` as well as anywhere below it
    if fp0 - s < acc || full == 0 || cap == 0 {
        seen(&t);
        return Ok(Rounds::Done { t, c });
    }
    // one knot at the middle parameter (FITPACK: x((m + 1)/2))
    let mid = m.div_ceil(2) - 1;
    knots.interior.push(sites[mid]);
    knots.nrdata = vec![mid - 1, m - 2 - mid];
    let (mut fpold, mut nplus) = (fp0, 1usize);
    loop {
        let (t, qr, c) = fit_on(&mut pass, obs, &breaks(&knots.interior), steps)?;
        seen(&t);
        let fp = qr.rss;
        let fpms = fp - s;
        if accepts_least_squares(fpms, acc) {
            return Ok(Rounds::Done { t, c });
        }
        if fpms < 0.0 {
            return Ok(Rounds::Smooth {
                t,
                qr,
                fp0,
                fp_inf: fp,
            });
        }
        if knots.count() >= full || knots.count() >= cap {
            // interpolation, or as many knots as allowed
            return Ok(Rounds::Done { t, c });
        }
        nplus = next_nplus(nplus, fpms, fpold - fp, acc);
        fpold = fp;
        pass.residuals(obs, &c);
        span_sums(&mut knots, obs, &pass, &t);
        match knots.add_up_to(sites, nplus, full, cap) {
            Added::Some => {}
            Added::Full => knots.interior = interpolation_knots(sites, k),
            Added::None => return Ok(Rounds::Done { t, c }),
        }
    }
}

/// The smoothing step of a closed fit on the knots `t` with the data's triangle `qr`
/// (repeated coefficients and the jump weight λ), as [`smooth_on`](super::smoothing_condition)
/// for open curves: `[R; B/p]` with the jump rows of the `k`-th derivative at the interior
/// knots, wrapped like the data rows (band `k + 2`, border `k + 1`). Each weight tried is a
/// step of `steps`.
#[allow(clippy::too_many_arguments)]
fn smooth_periodic(
    obs: &Observations,
    k: usize,
    t: &[f64],
    qr: &CyclicQr,
    s: f64,
    fp0: f64,
    fp_inf: f64,
    steps: &Steps<'_, '_>,
) -> Result<(Vec<f64>, Option<f64>)> {
    let pen = jump_rows(t, k);
    let (np, k2, dim) = (qr.n(), k + 2, obs.dim);
    let n8 = pen.rows.len() / k2;
    let solve = |p: f64| -> Result<(Vec<f64>, f64)> {
        let mut g = CyclicQr::new(np, k2, k + 1, dim);
        let mut h = vec![0.0; k2];
        let mut y = vec![0.0; dim];
        let mut penalty = |g: &mut CyclicQr, r: usize| {
            for (hv, v) in h.iter_mut().zip(&pen.rows[r * k2..(r + 1) * k2]) {
                *hv = v / p;
            }
            y.fill(0.0);
            g.add_cyclic(r, &h, &mut y);
        };
        // rows that wrap first, so that first band columns never decrease
        (0..n8)
            .filter(|r| r + k + 1 >= np)
            .for_each(|r| penalty(&mut g, r));
        for j in 0..np {
            let (e, z) = qr.row(j);
            let mut yz = z.to_vec();
            g.add_entries(e.into_iter(), &mut yz);
            if j < n8 && j + k + 1 < np {
                penalty(&mut g, j);
            }
        }
        let c = solve_cyclic(&g)?;
        let fp = qr.rss + qr.residual_of(&c);
        Ok((c, fp))
    };
    let trace: f64 = qr.diagonal().sum();
    let (c, lambda) = match smooth_weight(&solve, np as f64 / trace, s, fp0, fp_inf, steps)? {
        Some((p, _, c)) => (c, Some((p * pen.scale).powi(-2))),
        None => (solve_cyclic(qr)?, None),
    };
    Ok((repeat(&c, np, k, dim), lambda))
}

/// Breakpoints: at least two, finite, strictly increasing.
fn check_breaks(breaks: &[f64]) -> Result<()> {
    if breaks.len() < 2 {
        return Err(Error::TooFew {
            what: "breakpoints of a closed fit (the period's start and end)".into(),
            min: 2,
            got: breaks.len(),
        });
    }
    check_finite("breakpoints of a closed fit", breaks)?;
    if let Some(i) = (1..breaks.len()).find(|&i| breaks[i] < breaks[i - 1]) {
        return Err(Error::NotIncreasing {
            what: Arg::Breakpoints.into(),
            index: i,
            value: breaks[i],
            previous: breaks[i - 1],
        });
    }
    if let Some(i) = (1..breaks.len()).find(|&i| breaks[i] == breaks[i - 1]) {
        return Err(Error::InvalidArgument {
            what: "breakpoints of a closed fit".into(),
            reason: format!(
                "breakpoint {i} repeats breakpoint {} = {}; give strictly increasing breakpoints",
                i - 1,
                breaks[i]
            ),
        });
    }
    Ok(())
}

/// The data parameters in `[a, b]`, `b` replaced by `a`.
fn wrap_params(data: &FitData<'_>, (a, b): (f64, f64)) -> Result<Vec<f64>> {
    check_in_domain(data.params(), (a, b))?;
    Ok(data
        .params()
        .iter()
        .map(|&u| if u == b { a } else { u })
        .collect())
}

/// [`Observations`] of the data at the wrapped parameters.
fn observations(data: &FitData<'_>, wrapped: &[f64]) -> Result<Observations> {
    let mut d = FitData::new(data.points(), wrapped)?;
    if let Some(w) = data.weights() {
        d = d.with_weights(w)?;
    }
    Ok(Observations::new(&d))
}

/// The periodic knot vector of the breakpoints (module documentation).
fn periodic_knots(breaks: &[f64], k: usize) -> Vec<f64> {
    let np = breaks.len() - 1;
    let per = breaks[np] - breaks[0];
    let mut t = vec![0.0; np + 2 * k + 1];
    t[k..=k + np].copy_from_slice(breaks);
    for j in 1..=k {
        t[k - j] = t[k + np - j] - per;
        t[k + np + j] = t[k + j] + per;
    }
    t
}

/// The knots of periodic interpolation at the sites `a = x_0 < … < x_{m−1} = b` (FITPACK):
/// the inner sites for odd degree, the midpoints for even degree.
fn interpolation_knots(sites: &[f64], k: usize) -> Vec<f64> {
    let m = sites.len();
    (1..m - 1)
        .map(|i| {
            if k % 2 == 1 {
                sites[i]
            } else {
                0.5 * (sites[i] + sites[i - 1])
            }
        })
        .collect()
}

/// One least-squares pass on the breakpoints: the knots, the triangle and the control points
/// (all `np + k`, the last `k` repeating the first); the pass is a step of `steps`.
fn fit_on(
    pass: &mut LsqPass,
    obs: &Observations,
    breaks: &[f64],
    steps: &Steps<'_, '_>,
) -> Result<(Vec<f64>, CyclicQr, Vec<f64>)> {
    steps.tick()?;
    let k = pass.k;
    let t = periodic_knots(breaks, k);
    let np = breaks.len() - 1;
    let mut qr = CyclicQr::new(np, k + 1, k, obs.dim);
    pass.fill(obs, &t, |_, _, _| {});
    // rows that wrap around the corner first, so that first band columns never decrease
    let mut y = vec![0.0; obs.dim];
    for wraps in [true, false] {
        for i in 0..obs.x.len() {
            let first = pass.first[i];
            if (first + k >= np) == wraps {
                y.copy_from_slice(&obs.y[i * obs.dim..(i + 1) * obs.dim]);
                qr.add_cyclic(first, &pass.rows[i * (k + 1)..(i + 1) * (k + 1)], &mut y);
            }
        }
    }
    let mut c = vec![0.0; np * obs.dim];
    qr.solve(&mut c).map_err(|col| Error::SchoenbergWhitney {
        basis: col,
        start: t[col],
        end: t[col + k + 1],
    })?;
    let c = repeat(&c, np, k, obs.dim);
    Ok((t, qr, c))
}

/// Back substitution, a zero pivot as [`Error::SingularSystem`].
fn solve_cyclic(qr: &CyclicQr) -> Result<Vec<f64>> {
    let dim = qr.ncols();
    let mut c = vec![0.0; qr.n() * dim];
    qr.solve(&mut c).map_err(|col| Error::SingularSystem {
        reason: format!(
            "control point {col} of the closed fit has no data of positive weight under its \
             basis function; give those points a positive weight, use fewer knots, or remove them"
        ),
    })?;
    Ok(c)
}

/// `np` free control points (flat, `dim` each) extended by the first `k` again.
fn repeat(c: &[f64], np: usize, k: usize, dim: usize) -> Vec<f64> {
    let mut all = Vec::with_capacity((np + k) * dim);
    for i in 0..np + k {
        let j = i % np;
        all.extend_from_slice(&c[j * dim..(j + 1) * dim]);
    }
    all
}

/// FITPACK's per-span residual sums of a periodic fit: a point on a knot counts half to each
/// side, and the first point (at `a ≡ b`) counts whole in the first and in the last span.
fn span_sums(knots: &mut Knots, obs: &Observations, pass: &LsqPass, t: &[f64]) {
    let k = knots.k;
    knots.fpint.clear();
    let (mut l, mut part, mut wrap) = (k, 0.0, 0.0);
    for (&u, &term) in obs.x.iter().zip(&pass.res) {
        let new = u >= t[l];
        if new {
            l += 1;
        }
        part += term;
        if new {
            if l <= k + 1 {
                wrap = term;
            } else {
                knots.fpint.push(part - 0.5 * term);
                part = 0.5 * term;
            }
        }
    }
    knots.fpint.push(part + wrap);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_knots_extend_by_the_period() {
        let t = periodic_knots(&[0.0, 1.0, 3.0, 4.0], 3);
        assert_eq!(
            t,
            vec![-4.0, -3.0, -1.0, 0.0, 1.0, 3.0, 4.0, 5.0, 7.0, 8.0],
            "knots"
        );
        // fewer spans than the degree: the extension wraps more than once
        let t = periodic_knots(&[0.0, 1.0], 3);
        assert_eq!(t, vec![-3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0], "knots");
    }

    /// FITPACK's `fpperi` accepts the least-squares constant when `fp0 − s < acc`, and a
    /// round's least-squares spline when `|fp − s| < acc`, also above `s`: with `s` just below
    /// such a residual the rounds end there, unsmoothed.
    #[test]
    fn a_round_within_the_tolerance_above_s_is_the_answer() {
        use std::f64::consts::TAU;
        let x: Vec<f64> = (0..60).map(|i| TAU * f64::from(i) / 60.0).collect();
        let y: Vec<f64> = (0..60)
            .map(|i| {
                let t = TAU * f64::from(i) / 60.0;
                t.cos() + 0.3 * (2.0 * t).sin() + 0.05 * f64::from((i * 7 + 3) % 11) / 5.0
            })
            .collect();
        let data = FitData::new(crate::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let (k, domain) = (3, (0.0, TAU));
        let fp_of = |t: &[f64]| {
            let breaks = &t[k..t.len() - k];
            periodic_least_squares(&data, k, breaks)
                .unwrap()
                .report
                .weighted_rss
        };
        let seq = periodic_smoothing_knot_sequence(&data, k, 1e-3, domain, None).unwrap();
        assert!(seq.len() >= 3, "{} rounds", seq.len());
        let constant = [0.0, 0.0, 0.0, 0.0, TAU, TAU, TAU, TAU];
        for t in [&constant[..], &seq[2][..]] {
            let fp = fp_of(t);
            let s = fp / (1.0 + 0.5 * SMOOTHING_RTOL);
            let fit = periodic_smoothing_condition(&data, k, s, domain).unwrap();
            assert_eq!(fit.curve.knots().len(), t.len(), "{t:?}");
            assert_eq!(fit.report.lambda, None, "{t:?}: smoothed");
            let rss = fit.report.weighted_rss;
            assert!(
                rss > s && rss < s * (1.0 + SMOOTHING_RTOL),
                "{rss} for s = {s}"
            );
            let s = fp / (1.0 + 2.0 * SMOOTHING_RTOL);
            let fit = periodic_smoothing_condition(&data, k, s, domain).unwrap();
            assert!(fit.curve.knots().len() > t.len(), "{t:?}: rounds stopped");
        }
    }
}
