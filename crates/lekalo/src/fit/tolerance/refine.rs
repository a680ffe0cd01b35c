//! The knot insertion and removal of [`fit_tolerance`](super::fit_tolerance): knots inserted
//! where points are beyond `tol`, then removed where a local least-squares refit stays within
//! it (`docs/theory/fitting.md#tolerance`).

use super::deviation::{deviations, deviations_full, deviations_full_with_feet, smaller, Tracked};
use super::{Deviation, ToleranceOptions};
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::fit::data::FitData;
use crate::fit::lsq::{least_squares, EndConstraints};
use crate::knots::KnotVector;
use crate::numeric::linalg::solve_dense;
use crate::numeric::progress::Progress;
use crate::points::{Points, PointsRef};
use crate::BSplineCurve;

/// Points above which [`fit_tolerance`](super::fit_tolerance) places its knots on a sample of the data first.
pub(super) const SAMPLE_ABOVE: usize = 1 << 18;

/// Points in that sample (about; the last point is added).
pub(super) const SAMPLE_SIZE: usize = 1 << 17;

/// Knots of the sample's fit on either side of a knot inserted for all points that
/// [`refine`] tries again for removal.
pub(super) const NEIGHBOURS: usize = 4;

/// [`fit_tolerance`](super::fit_tolerance) on many points: the knots are found on every `s`-th point (about
/// `sample_size` of them, the last point included, at their own data parameters), and that
/// curve is measured against all points, one pass. Where a point is beyond `tol`, the knot
/// insertion of [`refine`] continues from the sample's knots on all points, and only the knots
/// it adds are tried for removal. Dense data between the sampled points rarely needs more, so
/// the cost is that of the sample's fit plus a pass or two over the data instead of a pass per
/// round and a local refit per knot.
pub(super) fn fit_sample_first(
    points: PointsRef<'_>,
    params: &[f64],
    opts: &ToleranceOptions,
    progress: &Progress<'_>,
    sample_size: usize,
) -> Result<(BSplineCurve, Vec<f64>, Vec<f64>)> {
    let (flat, sample_params) = sample_of(points, params, sample_size);
    let sample = PointsRef::from_flat(points.dim(), &flat)?;
    let (curve, _, _) = refine(sample, &sample_params, opts, progress, &[])?;
    // the sample's curve against every point: distances of all (exact per point, projected)
    let skip = if opts.deviation == Deviation::Distance {
        -1.0
    } else {
        opts.tol
    };
    let (dev, feet) = deviations_full_with_feet(&curve, points, params, opts.deviation, skip)?;
    if dev.iter().all(|&d| d <= opts.tol) {
        return Ok((curve, dev, feet));
    }
    let (curve, dev, feet) = refine(points, params, opts, progress, &interior_knots(&curve))?;
    let fresh = deviations_full_with_feet(&curve, points, params, opts.deviation, -1.0)?;
    let (dev, feet) = smaller((dev, feet), fresh);
    Ok((curve, dev, feet))
}

/// Every `s`-th point and its parameter, `s` = `⌈n / size⌉`, and the last point.
pub(super) fn sample_of(
    points: PointsRef<'_>,
    params: &[f64],
    size: usize,
) -> (Vec<f64>, Vec<f64>) {
    let n = points.len();
    let mut picked: Vec<usize> = (0..n).step_by(n.div_ceil(size.max(1))).collect();
    if picked.last() != Some(&(n - 1)) {
        picked.push(n - 1);
    }
    let flat = picked
        .iter()
        .flat_map(|&i| points.point(i))
        .copied()
        .collect();
    (flat, picked.iter().map(|&i| params[i]).collect())
}

/// Knot insertion and removal of [`fit_tolerance`](super::fit_tolerance) from the interior knots `start`, at the
/// data parameters `params`: the curve, an upper bound of every point's deviation and the foot
/// where that bound was measured (`NaN`: at the data parameter). Knots of `start` are kept; only
/// those inserted are tried for removal.
pub(super) fn refine(
    points: PointsRef<'_>,
    params: &[f64],
    opts: &ToleranceOptions,
    progress: &Progress<'_>,
    start: &[f64],
) -> Result<(BSplineCurve, Vec<f64>, Vec<f64>)> {
    let (tol, p) = (opts.tol, opts.degree);
    let data = FitData::new(points, params)?;
    let (a, b) = (params[0], params[params.len() - 1]);
    let ends = EndConstraints::points();
    let mut interior: Vec<f64> = start.to_vec();
    // knot sites that keep the Schoenberg–Whitney conditions (see smoothing_condition)
    let mut distinct = params.to_vec();
    distinct.dedup();
    if distinct.len() < p + 1 {
        return Err(Error::TooFew {
            what: "distinct data parameters for a tolerance fit (degree + 1)".into(),
            min: p + 1,
            got: distinct.len(),
        });
    }
    let sites = &distinct[p.div_ceil(2)..distinct.len() - (p + 2) / 2];
    let fit = |interior: &[f64]| -> Result<(BSplineCurve, Vec<f64>)> {
        let kv = clamped(a, b, p, interior);
        let f = least_squares(&data, p, &kv, &ends)?;
        let dev = deviations(
            &f.curve,
            points,
            params,
            &f.report.residuals,
            opts.deviation,
            tol,
        )?;
        Ok((f.curve, dev))
    };
    let (mut curve, mut dev) = fit(&interior)?;
    let mut round = 0;
    loop {
        round += 1;
        progress.step("tolerance fit (knot insertion)", round, round + 1)?;
        let bad = bad_spans(params, &dev, tol, a, b, &interior);
        if bad.is_empty() {
            break;
        }
        let before = interior.len();
        for (lo, hi) in bad {
            // the middle knot site strictly inside the span
            let i = sites.partition_point(|&v| v <= lo);
            let j = sites.partition_point(|&v| v < hi);
            if i < j {
                interior.push(sites[(i + j - 1) / 2]);
            } else {
                // no site inside (an end span): the nearest unused sites on either side
                let right = sites[j..].iter().find(|c| !interior.contains(c));
                let left = sites[..i].iter().rev().find(|c| !interior.contains(c));
                interior.extend(right.into_iter().chain(left).copied());
            }
        }
        if interior.len() == before {
            break;
        }
        interior.sort_by(f64::total_cmp);
        interior.dedup();
        (curve, dev) = fit(&interior)?;
    }
    // removal: first within the remaining budget (exact bound), then by refitting
    let worst = dev.iter().fold(0.0_f64, |m, &v| m.max(v));
    if start.is_empty() && worst < tol && !interior.is_empty() {
        let (removed_curve, removed) = curve.remove_all_removable_knots(tol - worst)?;
        if removed > 0 {
            let d = deviations_full(&removed_curve, points, params, opts.deviation, tol)?;
            if d.iter().all(|&v| v <= tol) {
                curve = removed_curve;
                interior = interior_knots(&curve);
            }
        }
    }
    // removal by local refits: each knot once, in order
    let mut tracked = Tracked::new(&curve, points, params, opts.deviation, tol)?;
    let mut k = 0;
    // knots of `start` more than NEIGHBOURS knots away from every inserted one are kept: the
    // fit there is the one the start was made for
    let inserted: Vec<bool> = interior
        .iter()
        .map(|u| start.binary_search_by(|v| v.total_cmp(u)).is_err())
        .collect();
    let mut candidate = vec![false; interior.len()];
    for (i, _) in inserted.iter().enumerate().filter(|(_, &new)| new) {
        let (lo, hi) = (
            i.saturating_sub(NEIGHBOURS),
            (i + NEIGHBOURS).min(interior.len() - 1),
        );
        candidate[lo..=hi].fill(true);
    }
    let (mut tried, to_try) = (0, candidate.iter().filter(|&&c| c).count() as u64);
    while k < interior.len() {
        if !candidate[k] {
            k += 1;
            continue;
        }
        progress.step("tolerance fit (knot removal)", tried, to_try)?;
        tried += 1;
        match remove_locally(&curve, p + 1 + k, points, params)? {
            Some((trial, changed)) => {
                if tracked.accept(&trial, changed, points, params, tol)? {
                    curve = trial;
                    interior.remove(k);
                    candidate.remove(k);
                } else {
                    k += 1;
                }
            }
            None => k += 1,
        }
    }
    progress.step("tolerance fit (knot removal)", to_try, to_try)?;
    Ok((curve, tracked.dev, tracked.feet))
}

pub(super) fn clamped(a: f64, b: f64, p: usize, interior: &[f64]) -> KnotVector {
    let mut k = Vec::with_capacity(interior.len() + 2 * p + 2);
    k.extend(std::iter::repeat_n(a, p + 1));
    k.extend_from_slice(interior);
    k.extend(std::iter::repeat_n(b, p + 1));
    KnotVector::from_raw(k)
}

pub(super) fn interior_knots(curve: &BSplineCurve) -> Vec<f64> {
    let t = curve.knots().as_slice();
    let p = curve.degree();
    t[p + 1..t.len() - p - 1].to_vec()
}

/// Spans `[lo, hi)` (between consecutive breakpoints) that hold a point with deviation `> tol`.
pub(super) fn bad_spans(
    params: &[f64],
    dev: &[f64],
    tol: f64,
    a: f64,
    b: f64,
    interior: &[f64],
) -> Vec<(f64, f64)> {
    let mut bps = Vec::with_capacity(interior.len() + 2);
    bps.push(a);
    bps.extend_from_slice(interior);
    bps.push(b);
    let mut bad = vec![false; bps.len() - 1];
    for (&u, &d) in params.iter().zip(dev) {
        if d > tol {
            let j = (bps.partition_point(|&v| v <= u).max(1) - 1).min(bad.len() - 1);
            bad[j] = true;
        }
    }
    (0..bad.len())
        .filter(|&j| bad[j])
        .map(|j| (bps[j], bps[j + 1]))
        .collect()
}
/// Control points refitted on either side of the `p + 1` a removed knot touches, in the local
/// refit of [`fit_tolerance`](super::fit_tolerance). The influence of a least-squares change decays by a constant
/// factor per span (about 0.27 for cubics), so a few spans give nearly the freedom of a global
/// refit at the cost of the data under them.
pub(super) const REFIT_MARGIN: usize = 6;

/// The curve without its knot `j` (an index into the full knot vector, interior), with the
/// control points near it refitted by least squares to the data under the part of the curve
/// they move, and that part's parameter interval; `None` when the local system is singular
/// (too few data there).
///
/// Removing `t_j` leaves the basis functions `N_i` for `i ≤ j − p − 2` and shifts those with
/// `i ≥ j` down by one (their knots are unchanged); `p + 1` new functions replace the `p + 2`
/// that held `t_j`. The new ones and `REFIT_MARGIN` on either side are free (the end control
/// points stay fixed: the curve keeps interpolating the end points); the others keep their
/// control points, so the curve is unchanged outside the support of the free functions.
pub(super) fn remove_locally(
    curve: &BSplineCurve,
    j: usize,
    points: PointsRef<'_>,
    params: &[f64],
) -> Result<Option<(BSplineCurve, (f64, f64))>> {
    let p = curve.degree();
    let dim = points.dim();
    let t = curve.knots().as_slice();
    let old = curve.control_points();
    let n = old.len() - 1; // control points after the removal
    let mut knots = t.to_vec();
    knots.remove(j);
    let (lo, hi) = (
        (j - p - 1).saturating_sub(REFIT_MARGIN).max(1),
        (j - 1 + REFIT_MARGIN).min(n - 2),
    );
    if n < 3 || lo > hi {
        return Ok(None);
    }
    let mut ctrl: Vec<f64> = Vec::with_capacity(n * dim);
    for i in 0..n {
        let from = if i + p + 2 <= j { i } else { i + 1 };
        ctrl.extend_from_slice(old.point(from));
    }
    let changed = (knots[lo], knots[hi + p + 1]);
    let (i0, i1) = (
        params.partition_point(|&u| u < changed.0),
        params.partition_point(|&u| u <= changed.1),
    );
    let m = hi - lo + 1;
    if i1 - i0 < m {
        return Ok(None);
    }
    let kv = KnotVector::from_raw(knots);
    let mut scratch = BasisScratch::new(p);
    let mut basis = vec![0.0; p + 1];
    let (mut gram, mut rhs) = (vec![0.0; m * m], vec![0.0; m * dim]);
    let mut r = vec![0.0; dim];
    for k in i0..i1 {
        let u = params[k];
        let span = kv.find_span(p, u)?;
        basis_funs_into(kv.as_slice(), p, span, u, &mut scratch, &mut basis);
        r.copy_from_slice(points.point(k));
        for (a, &na) in basis.iter().enumerate() {
            let i = span - p + a;
            if i < lo || i > hi {
                for (x, c) in r.iter_mut().zip(&ctrl[i * dim..(i + 1) * dim]) {
                    *x -= na * c;
                }
            }
        }
        for (a, &na) in basis.iter().enumerate() {
            let i = span - p + a;
            if i < lo || i > hi {
                continue;
            }
            for (b, &nb) in basis.iter().enumerate() {
                let l = span - p + b;
                if l >= lo && l <= hi {
                    gram[(i - lo) * m + (l - lo)] += na * nb;
                }
            }
            for (x, &rv) in rhs[(i - lo) * dim..(i - lo + 1) * dim].iter_mut().zip(&r) {
                *x += na * rv;
            }
        }
    }
    // the normal equations of a few well-conditioned B-spline columns; singular when a free
    // function has no data under it
    if solve_dense(&mut gram, &mut rhs, m, dim).is_err() {
        return Ok(None);
    }
    ctrl[lo * dim..(hi + 1) * dim].copy_from_slice(&rhs);
    let trial = BSplineCurve::from_knot_vector(p, kv, Points::from_flat(dim, ctrl)?)?;
    Ok(Some((trial, changed)))
}
