//! The smoothing condition: the spline with the fewest knots whose weighted residual sum of
//! squares is at most `s` (FITPACK `curfit`/`parcur`, behind SciPy's `splrep`/`splprep`;
//! `docs/theory/fitting.md#smoothing-condition`).

use super::banded::GivensQr;
use super::data::{CurveFit, FitData, FitReport};
use super::lsq::{accumulate, solve_control, Fixed};
use crate::basis::{basis_ders_into, BasisScratch};
use crate::error::{check_degree_bound, Error, Result};
use crate::knots::KnotVector;
use crate::BSplineCurve;

/// Relative accuracy of the final residual: the result has
/// `(1 − SMOOTHING_RTOL)·s ≤ Σ w_k |C(ū_k) − Q_k|² ≤ s` when it is smoothed (FITPACK's 0.001).
pub const SMOOTHING_RTOL: f64 = 1e-3;

/// The B-spline of `degree` with the fewest interior knots found whose weighted residual sum of
/// squares `Σ_k w_k |C(ū_k) − Q_k|²` is at most `s` (Dierckx 1975, 1993 ch. 5; FITPACK `curfit`
/// for functions and `parcur` for parametric curves, as in SciPy's `splrep(s=…)`/`splprep`).
///
/// 1. Start with no interior knot: the least-squares polynomial. If its residual is `≤ s`, it is
///    the answer.
/// 2. Otherwise add knots where the residual is largest: the span with the largest residual sum
///    that holds data strictly inside is split at its middle data parameter. The number of knots
///    added per round grows as in FITPACK (`nplus = min(2·nplus, max(nplus·fpms/Δfp, nplus/2, 1))`),
///    and each round refits by least squares ([`least_squares`](super::least_squares)), until the
///    residual is `≤ s` (at the latest when the knots are the data parameters: interpolation).
/// 3. On this final knot set, smooth: minimise `Σ w |C − Q|² + λ Σ_j (jump of C^{(p)} at t_j)²`
///    (FITPACK's discontinuity penalty; its null space is the polynomials of degree `p`), with
///    λ found by a secant (Illinois) iteration in `log λ` so that the residual is `s` within
///    [`SMOOTHING_RTOL`]`·s`, never above `s`. The penalty rows are rotated into the data's banded
///    QR, so each λ costs O(n·p²), not a pass over the data.
///
/// It differs from FITPACK in the knot position (the middle data point of the span, where FITPACK
/// balances the residual halves by its `fpint` estimates), in recomputing the span residuals after
/// each round instead of updating estimates, and in the root finder (FITPACK interpolates `p = 1/λ`
/// rationally, `fprati`). `s = 0` interpolates. Cost: O(rounds·N·p²).
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
/// [`Error::TooFew`] for fewer than `degree + 1` distinct parameters.
pub fn smoothing_condition(data: &FitData<'_>, degree: usize, s: f64) -> Result<CurveFit> {
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
    let p = degree;
    let mut x = data.params().to_vec();
    x.sort_by(f64::total_cmp);
    x.dedup();
    if x.len() < p + 1 {
        return Err(Error::TooFew {
            what: "distinct data parameters for the smoothing condition (degree + 1)",
            min: p + 1,
            got: x.len(),
        });
    }
    let (a, b) = (x[0], x[x.len() - 1]);
    // knot sites: the distinct parameters x_i, ⌈p/2⌉ ≤ i ≤ N − 1 − (p+2)/2 (FITPACK's
    // interpolation knots for s = 0); any subset keeps the Schoenberg–Whitney conditions
    let sites = &x[p.div_ceil(2)..x.len() - (p + 2) / 2];
    let wmax = data
        .weights()
        .map_or(1.0, |w| w.iter().fold(0.0_f64, |m, &v| m.max(v)));
    let fixed = Fixed::free(data);
    let mut interior: Vec<f64> = Vec::new();
    let (mut nplus, mut fpold) = (1usize, f64::INFINITY);
    let (kv, qr, mut fit) = loop {
        let kv = clamped(a, b, p, &interior);
        let n_ctrl = interior.len() + p + 1;
        let qr = accumulate(data, p, &kv, n_ctrl, &fixed, p + 2);
        let control = solve_control(&qr, data, p, &kv, n_ctrl, &fixed)?;
        let curve = BSplineCurve::from_raw(p, kv.as_slice().to_vec(), control);
        let fp = qr.rss * wmax;
        let report = FitReport::new(&curve, data, None);
        let fit = CurveFit { curve, report };
        // interpolation reached: every distinct parameter carries a control point
        if fp <= s || interior.len() >= sites.len() {
            break (kv, qr, fit);
        }
        // FITPACK's rule for the number of knots to add
        if fpold.is_finite() {
            let npl1 = if fpold - fp > SMOOTHING_RTOL * s {
                let v = nplus as f64 * (fp - s) / (fpold - fp);
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let v = v.min(1e9) as usize;
                v
            } else {
                nplus * 2
            };
            nplus = (nplus * 2).min(npl1.max(nplus / 2).max(1));
        }
        fpold = fp;
        let added = add_knots(data, &fit, &kv, p, sites, &mut interior, nplus);
        if added == 0 {
            break (kv, qr, fit);
        }
    };
    let fp0 = fit.report.weighted_rss;
    if fp0 >= (1.0 - SMOOTHING_RTOL) * s || interior.is_empty() {
        return Ok(fit);
    }
    // smooth on the final knots: RSS(λ) increases from fp0 < s to the polynomial fit's residual
    let pen = jump_rows(&kv, p);
    let n_ctrl = interior.len() + p + 1;
    let wide = qr.widened(p + 2);
    let solve = |lam: f64| -> Option<(Vec<f64>, f64)> {
        let mut q = wide.clone();
        let sl = lam.sqrt();
        let mut y = vec![0.0; data.points().dim()];
        for (first, row) in &pen {
            let mut h: Vec<f64> = row.iter().map(|v| v * sl).collect();
            y.iter_mut().for_each(|v| *v = 0.0);
            q.add_row(*first, &mut h, &mut y);
        }
        let mut c = vec![0.0; n_ctrl * y.len()];
        q.solve(&mut c).ok()?;
        let rss = (qr.rss + qr.residual_of(&c)) * wmax;
        Some((c, rss))
    };
    let lam = find_lambda(&solve, &qr, &pen, s)?;
    if let Some((c, _)) = solve(lam) {
        let control = super::lsq::assemble(&c, &fixed, n_ctrl, data.points().dim());
        let curve = BSplineCurve::from_raw(p, kv.as_slice().to_vec(), control);
        let report = FitReport::new(&curve, data, Some(lam));
        fit = CurveFit { curve, report };
    }
    Ok(fit)
}

fn clamped(a: f64, b: f64, p: usize, interior: &[f64]) -> KnotVector {
    let mut k = Vec::with_capacity(interior.len() + 2 * p + 2);
    k.extend(std::iter::repeat_n(a, p + 1));
    k.extend_from_slice(interior);
    k.extend(std::iter::repeat_n(b, p + 1));
    KnotVector::from_raw(k)
}

/// Adds up to `count` knots, each in the span with the largest weighted residual sum among the
/// spans with a knot site `x` strictly inside, at the middle such site. Returns how many were
/// added.
fn add_knots(
    data: &FitData<'_>,
    fit: &CurveFit,
    kv: &KnotVector,
    p: usize,
    x: &[f64],
    interior: &mut Vec<f64>,
    count: usize,
) -> usize {
    let t = kv.as_slice();
    // breakpoints and residual sums per span
    let mut bps: Vec<f64> = Vec::with_capacity(interior.len() + 2);
    bps.push(t[p]);
    bps.extend_from_slice(interior);
    bps.push(t[t.len() - 1 - p]);
    let mut sums = vec![0.0; bps.len() - 1];
    for (k, &u) in data.params().iter().enumerate() {
        let r = fit.report.residuals[k];
        let j = (bps.partition_point(|&v| v <= u).max(1) - 1).min(sums.len() - 1);
        sums[j] += data.weight(k) * r * r;
    }
    let mut added = 0;
    for _ in 0..count {
        // the span with the largest sum that has a distinct parameter strictly inside
        let mut best: Option<(usize, f64)> = None;
        for j in 0..sums.len() {
            let lo = x.partition_point(|&v| v <= bps[j]);
            let hi = x.partition_point(|&v| v < bps[j + 1]);
            if lo < hi && best.is_none_or(|(_, s)| sums[j] > s) {
                best = Some((j, sums[j]));
            }
        }
        let Some((j, _)) = best else { break };
        let lo = x.partition_point(|&v| v <= bps[j]);
        let hi = x.partition_point(|&v| v < bps[j + 1]);
        let knot = x[(lo + hi - 1) / 2];
        // split the span's sum in proportion to the parameters on each side
        let left = ((lo + hi - 1) / 2 - lo + 1) as f64 / (hi - lo + 1) as f64;
        let total = sums[j];
        sums[j] = total * left;
        sums.insert(j + 1, total * (1.0 - left));
        bps.insert(j + 1, knot);
        added += 1;
    }
    interior.clear();
    interior.extend_from_slice(&bps[1..bps.len() - 1]);
    added
}

/// The rows of the discontinuity penalty: for each interior knot `t_l` (simple), the jump of
/// the `p`-th derivative, a functional of the `p + 2` coefficients `l − p − 1 ..= l`.
fn jump_rows(kv: &KnotVector, p: usize) -> Vec<(usize, Vec<f64>)> {
    let t = kv.as_slice();
    let n_ctrl = t.len() - p - 1;
    let mut scratch = BasisScratch::new(p);
    let mut ders = vec![0.0; (p + 1) * (p + 1)];
    let mut dp = |span: usize| -> Vec<f64> {
        let mid = 0.5 * (t[span] + t[span + 1]);
        basis_ders_into(t, p, span, mid, p, &mut scratch, &mut ders);
        ders[p * (p + 1)..].to_vec()
    };
    let mut rows = Vec::new();
    for l in p + 1..n_ctrl {
        let (left, right) = (dp(l - 1), dp(l));
        // coefficients l−p−1 ..= l: left covers l−p−1 ..= l−1, right covers l−p ..= l
        let mut row = vec![0.0; p + 2];
        for i in 0..=p {
            row[i] -= left[i];
            row[i + 1] += right[i];
        }
        rows.push((l - p - 1, row));
    }
    rows
}

/// λ with `(1 − SMOOTHING_RTOL)·s ≤ RSS(λ) ≤ s`, by bracketing in `log λ` and the Illinois
/// variant of regula falsi.
fn find_lambda(
    solve: &impl Fn(f64) -> Option<(Vec<f64>, f64)>,
    qr: &GivensQr,
    pen: &[(usize, Vec<f64>)],
    s: f64,
) -> Result<f64> {
    let f = |z: f64| solve(10f64.powf(z)).map(|(_, r)| r - s);
    let fail = || Error::SingularSystem {
        reason: "the smoothing iteration found no weight with the residual at s".into(),
    };
    // scale: the data matrix's diagonal against the penalty's
    let bw = qr.r.len() / qr.n().max(1);
    let td: f64 = (0..qr.n()).map(|i| qr.r[i * bw] * qr.r[i * bw]).sum();
    let tp: f64 = pen.iter().flat_map(|(_, r)| r.iter().map(|v| v * v)).sum();
    let mut z0 = (td / tp.max(f64::MIN_POSITIVE)).log10();
    let mut f0 = f(z0).ok_or_else(fail)?;
    let mut step = 2.0;
    // bracket: f(lo) ≤ 0 < f(hi)
    let (mut lo, mut flo, mut hi, mut fhi);
    if f0 > 0.0 {
        (hi, fhi) = (z0, f0);
        loop {
            z0 -= step;
            f0 = f(z0).ok_or_else(fail)?;
            if f0 <= 0.0 {
                (lo, flo) = (z0, f0);
                break;
            }
            (hi, fhi) = (z0, f0);
            step *= 2.0;
            if step > 1e3 {
                return Err(fail());
            }
        }
    } else {
        (lo, flo) = (z0, f0);
        loop {
            z0 += step;
            f0 = f(z0).ok_or_else(fail)?;
            if f0 > 0.0 {
                (hi, fhi) = (z0, f0);
                break;
            }
            (lo, flo) = (z0, f0);
            step *= 2.0;
            if step > 1e3 {
                // the residual never reaches s: the smoothest fit is still within it
                return Ok(10f64.powf(lo));
            }
        }
    }
    let mut side = 0i8;
    // the true residual excess at `lo` (`flo` is halved by the Illinois rule)
    let mut at_lo = flo;
    for _ in 0..200 {
        if -at_lo <= SMOOTHING_RTOL * s || hi - lo < 1e-12 {
            break;
        }
        let z = (lo * fhi - hi * flo) / (fhi - flo);
        let z = if z > lo && z < hi { z } else { 0.5 * (lo + hi) };
        let fz = f(z).ok_or_else(fail)?;
        if fz <= 0.0 {
            (lo, flo, at_lo) = (z, fz, fz);
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        } else {
            (hi, fhi) = (z, fz);
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        }
    }
    Ok(10f64.powf(lo))
}
