//! Fitting to a tolerance: a B-spline within `tol` of every point with few control points
//! (`docs/theory/fitting.md#tolerance`).

use super::data::FitData;
use super::lsq::{least_squares, EndConstraints};
use crate::basis::{basis_funs_into, BasisScratch};
use crate::error::{Error, Result};
use crate::interpolate::{parametrize, Parametrization};
use crate::knots::KnotVector;
use crate::numeric::linalg::solve_dense;
use crate::numeric::progress::Progress;
use crate::points::Points;
use crate::points::PointsRef;
use crate::BSplineCurve;

/// How the deviation of a data point from the curve is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Deviation {
    /// The distance to the curve: `min_u |C(u) − Q_k|`, by a closest-point projection (Newton's
    /// method on `(C(u) − Q_k)·C'(u) = 0` from the data parameter, kept in the domain).
    #[default]
    Distance,
    /// The distance at the data parameter, `|C(ū_k) − Q_k|` (larger or equal).
    Parameter,
}

/// Options of [`fit_tolerance`].
#[derive(Debug, Clone, PartialEq)]
pub struct ToleranceOptions {
    /// Degree of the curve.
    pub degree: usize,
    /// Largest accepted deviation, a distance in the data's units (`> 0`).
    pub tol: f64,
    /// How the deviation is measured.
    pub deviation: Deviation,
    /// Data parameters.
    pub parametrization: Parametrization,
}

impl ToleranceOptions {
    /// Degree and tolerance; distance deviation and chord-length parameters.
    #[must_use]
    pub fn new(degree: usize, tol: f64) -> Self {
        ToleranceOptions {
            degree,
            tol,
            deviation: Deviation::Distance,
            parametrization: Parametrization::ChordLength,
        }
    }
}

/// The result of [`fit_tolerance`].
#[derive(Debug, Clone, PartialEq)]
pub struct ToleranceFit {
    /// The curve; it starts at the first point and ends at the last.
    pub curve: BSplineCurve,
    /// The data parameters used.
    pub params: Vec<f64>,
    /// Deviation of every point (as measured by [`ToleranceOptions::deviation`]).
    pub deviations: Vec<f64>,
    /// The largest deviation (`≤ tol`).
    pub max_deviation: f64,
    /// Index of the point where it occurs.
    pub worst_index: usize,
    /// Curve parameter of the closest point to that data point.
    pub worst_param: f64,
}

/// A B-spline of the requested degree within `tol` of every point, with few control points (the
/// operation of Open CASCADE's `GeomAPI_PointsToBSpline` and geomdl's `approximate_curve`).
///
/// 1. Parameters by [`ToleranceOptions::parametrization`]; start with a single Bezier piece.
/// 2. Least squares with both end points interpolated ([`least_squares`]); measure every
///    deviation; split every knot span holding a point with deviation `> tol` at its middle data
///    parameter; repeat. Each split keeps data in every span (Schoenberg–Whitney), and at worst
///    the knots reach the data parameters, where the fit interpolates.
/// 3. Remove knots while the bound holds: with `m` the largest deviation, every knot whose
///    removal moves the curve by at most `tol − m` is removed
///    ([`BSplineCurve::remove_all_removable_knots`], whose bound is exact), so by the triangle
///    inequality the deviation stays `≤ tol`; then each remaining interior knot is tried once
///    more by a local refit without it (six control points on either side of the
///    ones the knot touches are refitted to the data under them, the others kept), kept out
///    when the points under the changed part of the curve are still within `tol`. Outside that
///    part the curve is unchanged, so each trial costs the data near the knot, not all of it.
///
/// 4. Above 2^18 points, steps 1–3 run on a sample of about 2^17 of them (every `s`-th point and
///    the last); the sample's curve is measured against all points and returned when every one is
///    within `tol`; otherwise step 2 continues on all points from the sample's knots and step 3
///    tries the added knots and their neighbours (`docs/theory/fitting.md#tolerance`).
///
/// Deviation is the distance to the curve ([`Deviation::Distance`], a closest-point projection
/// per point) or at the data parameter ([`Deviation::Parameter`]). O(rounds·N·p²) plus the
/// projections; the rounds double the knots, so they are about `log₂` of the control points.
///
/// ```
/// use lekalo::fit::{fit_tolerance, ToleranceOptions};
/// use lekalo::PointsRef;
/// let q: Vec<f64> = (0..200).flat_map(|k| { let t = k as f64 / 199.0 * 3.0; [t, t.sin()] }).collect();
/// let fit = fit_tolerance(PointsRef::from_flat(2, &q)?, &ToleranceOptions::new(3, 1e-4))?;
/// assert!(fit.max_deviation <= 1e-4);
/// assert!(fit.curve.control_points().len() < 20);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::NonPositiveTolerance`] for `tol ≤ 0` or NaN; [`Error::Degree`] for degree 0;
/// [`Error::TooFew`] for fewer than `degree + 1` points; the parametrisation's errors (e.g.
/// [`Error::CoincidentPoints`] for chord-length parameters of repeated points);
/// [`Error::IllConditioned`] if even interpolation misses `tol` (a tolerance below the data's
/// rounding).
pub fn fit_tolerance(points: PointsRef<'_>, opts: &ToleranceOptions) -> Result<ToleranceFit> {
    fit_tolerance_with_progress(points, opts, &Progress::new())
}

/// [`fit_tolerance`] reporting to `progress` after each round of knot insertion (`done` the
/// round, `total` one more: the rounds' number is not known ahead) and after each knot tried for
/// removal (`done` of `total` knots), and stopping with [`Error::Cancelled`] when its cancel flag
/// is set. The result is the same with or without the hook.
///
/// # Errors
/// As [`fit_tolerance`], and [`Error::Cancelled`].
pub fn fit_tolerance_with_progress(
    points: PointsRef<'_>,
    opts: &ToleranceOptions,
    progress: &Progress<'_>,
) -> Result<ToleranceFit> {
    let tol = opts.tol;
    if !(tol > 0.0 && tol.is_finite()) {
        return Err(Error::NonPositiveTolerance { value: tol });
    }
    let p = opts.degree;
    crate::error::check_degree_bound(p)?;
    if p == 0 {
        return Err(Error::Degree {
            degree: p,
            reason: "a tolerance fit needs degree ≥ 1".into(),
        });
    }
    if points.len() < p + 1 {
        return Err(Error::TooFew {
            what: "points for a tolerance fit (degree + 1)",
            min: p + 1,
            got: points.len(),
        });
    }
    let params = parametrize(points, opts.parametrization)?;
    let (curve, dev) = if points.len() > SAMPLE_ABOVE {
        fit_sample_first(points, &params, opts, progress, SAMPLE_SIZE)?
    } else {
        let (curve, dev) = refine(points, &params, opts, progress, &[])?;
        // the distances of the final curve from every data parameter; the removal kept upper
        // bounds (distances to points of this same curve), so each point keeps the smaller
        let dev = if opts.deviation == Deviation::Distance {
            let fresh = deviations_full(&curve, points, &params, opts.deviation, -1.0)?;
            dev.iter().zip(fresh).map(|(&d, f)| d.min(f)).collect()
        } else {
            dev
        };
        (curve, dev)
    };
    let (mut worst_index, mut max_deviation) = (0, 0.0);
    for (i, &d) in dev.iter().enumerate() {
        if d > max_deviation {
            (worst_index, max_deviation) = (i, d);
        }
    }
    if max_deviation > tol || max_deviation.is_nan() {
        // every site carries a knot (interpolation) and rounding still exceeds tol
        return Err(Error::IllConditioned {
            reason: format!(
                "the closest fit found deviates by {max_deviation} at point {worst_index}, more \
                 than the tolerance {tol}; raise the tolerance above the data's rounding"
            ),
        });
    }
    let worst_param = project(&curve, points, &params, &[worst_index])?[0].0;
    Ok(ToleranceFit {
        curve,
        params,
        deviations: dev,
        max_deviation,
        worst_index,
        worst_param,
    })
}

/// Points above which [`fit_tolerance`] places its knots on a sample of the data first.
const SAMPLE_ABOVE: usize = 1 << 18;

/// Points in that sample (about; the last point is added).
const SAMPLE_SIZE: usize = 1 << 17;

/// Knots of the sample's fit on either side of a knot inserted for all points that
/// [`refine`] tries again for removal.
const NEIGHBOURS: usize = 4;

/// [`fit_tolerance`] on many points: the knots are found on every `s`-th point (about
/// `sample_size` of them, the last point included, at their own data parameters), and that
/// curve is measured against all points, one pass. Where a point is beyond `tol`, the knot
/// insertion of [`refine`] continues from the sample's knots on all points, and only the knots
/// it adds are tried for removal. Dense data between the sampled points rarely needs more, so
/// the cost is that of the sample's fit plus a pass or two over the data instead of a pass per
/// round and a local refit per knot.
fn fit_sample_first(
    points: PointsRef<'_>,
    params: &[f64],
    opts: &ToleranceOptions,
    progress: &Progress<'_>,
    sample_size: usize,
) -> Result<(BSplineCurve, Vec<f64>)> {
    let (flat, sample_params) = sample_of(points, params, sample_size);
    let sample = PointsRef::from_flat(points.dim(), &flat)?;
    let (curve, _) = refine(sample, &sample_params, opts, progress, &[])?;
    // the sample's curve against every point: distances of all (exact per point, projected)
    let skip = if opts.deviation == Deviation::Distance {
        -1.0
    } else {
        opts.tol
    };
    let dev = deviations_full(&curve, points, params, opts.deviation, skip)?;
    if dev.iter().all(|&d| d <= opts.tol) {
        return Ok((curve, dev));
    }
    let (curve, dev) = refine(points, params, opts, progress, &interior_knots(&curve))?;
    let fresh = deviations_full(&curve, points, params, opts.deviation, -1.0)?;
    Ok((
        curve,
        dev.iter().zip(fresh).map(|(&d, f)| d.min(f)).collect(),
    ))
}

/// Every `s`-th point and its parameter, `s` = `⌈n / size⌉`, and the last point.
fn sample_of(points: PointsRef<'_>, params: &[f64], size: usize) -> (Vec<f64>, Vec<f64>) {
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

/// Knot insertion and removal of [`fit_tolerance`] from the interior knots `start`, at the
/// data parameters `params`: the curve and an upper bound of every point's deviation. Knots of
/// `start` are kept; only those inserted are tried for removal.
fn refine(
    points: PointsRef<'_>,
    params: &[f64],
    opts: &ToleranceOptions,
    progress: &Progress<'_>,
    start: &[f64],
) -> Result<(BSplineCurve, Vec<f64>)> {
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
            what: "distinct data parameters for a tolerance fit (degree + 1)",
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
    Ok((curve, tracked.dev))
}

fn clamped(a: f64, b: f64, p: usize, interior: &[f64]) -> KnotVector {
    let mut k = Vec::with_capacity(interior.len() + 2 * p + 2);
    k.extend(std::iter::repeat_n(a, p + 1));
    k.extend_from_slice(interior);
    k.extend(std::iter::repeat_n(b, p + 1));
    KnotVector::from_raw(k)
}

fn interior_knots(curve: &BSplineCurve) -> Vec<f64> {
    let t = curve.knots().as_slice();
    let p = curve.degree();
    t[p + 1..t.len() - p - 1].to_vec()
}

/// Spans `[lo, hi)` (between consecutive breakpoints) that hold a point with deviation `> tol`.
fn bad_spans(
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

/// Deviations of every point. The distance is at most the deviation at the parameter, so only
/// points beyond `skip_below` there are projected (the others keep that upper bound);
/// `skip_below < 0` projects every point.
fn deviations(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    at_param: &[f64],
    how: Deviation,
    skip_below: f64,
) -> Result<Vec<f64>> {
    let mut dev = at_param.to_vec();
    if how == Deviation::Distance {
        let todo: Vec<usize> = (0..dev.len()).filter(|&i| dev[i] > skip_below).collect();
        let feet = project(curve, points, params, &todo)?;
        for (&i, &(_, d)) in todo.iter().zip(&feet) {
            dev[i] = dev[i].min(d);
        }
    }
    Ok(dev)
}

fn deviations_full(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    how: Deviation,
    skip_below: f64,
) -> Result<Vec<f64>> {
    let at = at_parameter(curve, points, params)?;
    deviations(curve, points, params, &at, how, skip_below)
}

/// Control points refitted on either side of the `p + 1` a removed knot touches, in the local
/// refit of [`fit_tolerance`]. The influence of a least-squares change decays by a constant
/// factor per span (about 0.27 for cubics), so a few spans give nearly the freedom of a global
/// refit at the cost of the data under them.
const REFIT_MARGIN: usize = 6;

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
fn remove_locally(
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

/// Points measured per block by [`Tracked::accept`] before it looks for one beyond `tol`.
const TRIAL_BLOCK: usize = 1024;

/// Deviations kept up to date through local changes of the curve: per point the deviation at
/// its data parameter (`at`) and an upper bound of its distance to the curve (`dev`), from the
/// foot `feet[i]` of a projection (`NaN`: none, `dev = at`). `reach` bounds `|foot − param|`,
/// so a change of the curve on `[a, b]` concerns only the points with parameters in
/// `[a − reach, b + reach]`.
struct Tracked {
    at: Vec<f64>,
    dev: Vec<f64>,
    feet: Vec<f64>,
    reach: f64,
    how: Deviation,
}

impl Tracked {
    fn new(
        curve: &BSplineCurve,
        points: PointsRef<'_>,
        params: &[f64],
        how: Deviation,
        tol: f64,
    ) -> Result<Self> {
        let at = at_parameter(curve, points, params)?;
        let mut t = Tracked {
            dev: at.clone(),
            feet: vec![f64::NAN; at.len()],
            at,
            reach: 0.0,
            how,
        };
        let todo: Vec<usize> = (0..t.at.len()).filter(|&i| t.at[i] > tol).collect();
        let (dev, feet) = t.measure(curve, points, params, &todo, tol)?;
        t.commit(&todo, &dev, &feet, params);
        Ok(t)
    }

    /// Deviations of the points `todo` from `curve`, given their `at` values: projected when
    /// beyond `tol` at the parameter (distance mode).
    fn measure(
        &self,
        curve: &BSplineCurve,
        points: PointsRef<'_>,
        params: &[f64],
        todo: &[usize],
        tol: f64,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let mut dev: Vec<f64> = todo.iter().map(|&i| self.at[i]).collect();
        let mut feet = vec![f64::NAN; todo.len()];
        if self.how == Deviation::Distance {
            let far: Vec<usize> = (0..todo.len()).filter(|&s| dev[s] > tol).collect();
            let idx: Vec<usize> = far.iter().map(|&s| todo[s]).collect();
            // from the last foot where there is one: Newton then needs a step or two
            let starts: Vec<f64> = idx
                .iter()
                .map(|&i| {
                    if self.feet[i].is_finite() {
                        self.feet[i]
                    } else {
                        params[i]
                    }
                })
                .collect();
            for (&s, &(u, d)) in far.iter().zip(&project_from(curve, points, &starts, &idx)?) {
                if d < dev[s] {
                    (dev[s], feet[s]) = (d, u);
                }
            }
        }
        Ok((dev, feet))
    }

    fn commit(&mut self, todo: &[usize], dev: &[f64], feet: &[f64], params: &[f64]) {
        for ((&i, &d), &f) in todo.iter().zip(dev).zip(feet) {
            self.dev[i] = d;
            self.feet[i] = f;
            if !f.is_nan() {
                self.reach = self.reach.max((f - params[i]).abs());
            }
        }
    }

    /// Takes `trial` (equal to the tracked curve outside `changed`) if every deviation stays
    /// within `tol`; the points concerned are measured again, the others keep theirs.
    fn accept(
        &mut self,
        trial: &BSplineCurve,
        changed: (f64, f64),
        points: PointsRef<'_>,
        params: &[f64],
        tol: f64,
    ) -> Result<bool> {
        let inside = |u: f64| u >= changed.0 && u <= changed.1;
        let (i0, i1) = (
            params.partition_point(|&u| u < changed.0 - self.reach),
            params.partition_point(|&u| u <= changed.1 + self.reach),
        );
        // under the change: new deviations at the parameter
        let (c0, c1) = (
            params.partition_point(|&u| u < changed.0),
            params.partition_point(|&u| u <= changed.1),
        );
        let dim = points.dim();
        // the part of the trial curve these points can reach: its evaluator costs the spans
        // there, not the whole curve's (a trial per knot would otherwise cost O(n) each)
        let trial = &local_part(
            trial,
            changed.0 - 2.0 * self.reach,
            changed.1 + 2.0 * self.reach,
        )?;
        let under = PointsRef::from_flat(dim, &points.as_slice()[c0 * dim..c1 * dim])?;
        let fresh = at_parameter(trial, under, &params[c0..c1])?;
        // outside it, points whose foot lay in the changed part fall back to their parameter
        let todo: Vec<usize> = (i0..i1)
            .filter(|&i| (c0..c1).contains(&i) || self.feet[i].is_finite() && inside(self.feet[i]))
            .collect();
        if fresh.iter().any(|&d| d > tol) && self.how == Deviation::Parameter {
            return Ok(false);
        }
        let saved: Vec<f64> = todo.iter().map(|&i| self.at[i]).collect();
        self.at[c0..c1].copy_from_slice(&fresh);
        // measured in blocks from the middle of the change outwards (where the curve moved
        // most): a refused trial usually stops in its first block
        let middle = 0.5 * (changed.0 + changed.1);
        let mut order = todo.clone();
        order.sort_by(|&i, &j| {
            (params[i] - middle)
                .abs()
                .total_cmp(&(params[j] - middle).abs())
        });
        let mut measured = Vec::with_capacity(order.len());
        let mut within = true;
        for block in order.chunks(TRIAL_BLOCK) {
            let (dev, feet) = self.measure(trial, points, params, block, tol)?;
            if dev.iter().any(|&d| d > tol || d.is_nan()) {
                within = false;
                break;
            }
            measured.push((block, dev, feet));
        }
        if within {
            for (block, dev, feet) in measured {
                self.commit(block, &dev, &feet, params);
            }
        } else {
            for (&i, &a) in todo.iter().zip(&saved) {
                self.at[i] = a;
            }
        }
        Ok(within)
    }
}

/// The piece of `curve` over the knot spans that meet `[lo, hi]` (clamped to the domain): the
/// control points and knots of those spans, an unclamped B-spline equal to `curve` on its
/// domain, which covers `[lo, hi]`. Projections onto it stay inside it, so the distances found
/// are distances to points of `curve`.
fn local_part(curve: &BSplineCurve, lo: f64, hi: f64) -> Result<BSplineCurve> {
    let p = curve.degree();
    let (a, b) = curve.domain();
    let kv = curve.knots();
    let s0 = kv.find_span(p, lo.clamp(a, b))?;
    let s1 = kv.find_span(p, hi.clamp(a, b))?;
    let t = kv.as_slice();
    let ctrl = curve.control_points();
    let dim = ctrl.dim();
    let flat = ctrl.as_slice()[(s0 - p) * dim..(s1 + 1) * dim].to_vec();
    BSplineCurve::new(
        p,
        t[s0 - p..=s1 + p + 1].to_vec(),
        Points::from_flat(dim, flat)?,
    )
}

/// `|C(ū_k) − Q_k|` for every point.
fn at_parameter(curve: &BSplineCurve, points: PointsRef<'_>, params: &[f64]) -> Result<Vec<f64>> {
    let dim = points.dim();
    let mut out = vec![0.0; params.len() * dim];
    curve.evaluator().eval_batch(params, &mut out)?;
    Ok(out
        .chunks_exact(dim)
        .zip(points.iter())
        .map(|(c, q)| {
            c.iter()
                .zip(q)
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt()
        })
        .collect())
}

/// Newton steps of [`project`].
const NEWTON_STEPS: usize = 8;

/// Closest points on `curve` to the points `todo` by Newton's method on
/// `(C(u) − Q)·C'(u) = 0` from their data parameters (at most [`NEWTON_STEPS`] steps, kept in
/// the domain, stopped when the step vanishes or the second derivative of the squared
/// distance is not positive): per point the parameter and distance of the closest iterate.
/// All points take their steps together, one batch evaluation of `C, C', C''` per step
/// ([`CurveEvaluator`](crate::CurveEvaluator), no allocation per point).
fn project(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    todo: &[usize],
) -> Result<Vec<(f64, f64)>> {
    let starts: Vec<f64> = todo.iter().map(|&i| params[i]).collect();
    project_from(curve, points, &starts, todo)
}

/// [`project`] from the given start parameters (one per point of `todo`), e.g. the feet of a
/// projection on a nearby curve.
fn project_from(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    starts: &[f64],
    todo: &[usize],
) -> Result<Vec<(f64, f64)>> {
    let (a, b) = curve.domain();
    let dim = points.dim();
    let eval = curve.evaluator();
    let mut u: Vec<f64> = starts.to_vec();
    let mut best = vec![(0.0, f64::INFINITY); todo.len()];
    let mut active: Vec<usize> = (0..todo.len()).collect();
    let (mut ts, mut ders) = (Vec::new(), Vec::new());
    for step in 0..=NEWTON_STEPS {
        ts.clear();
        ts.extend(active.iter().map(|&j| u[j]));
        ders.resize(ts.len() * 3 * dim, 0.0);
        eval.eval_derivatives_batch(&ts, 2, &mut ders)?;
        let mut kept = 0;
        for slot in 0..active.len() {
            let j = active[slot];
            let d = &ders[slot * 3 * dim..(slot + 1) * 3 * dim];
            let (c, c1, c2) = (&d[..dim], &d[dim..2 * dim], &d[2 * dim..]);
            let q = points.point(todo[j]);
            let (mut dist2, mut f, mut df) = (0.0, 0.0, 0.0);
            for k in 0..dim {
                let r = c[k] - q[k];
                dist2 += r * r;
                f += r * c1[k];
                df += c1[k] * c1[k] + r * c2[k];
            }
            let dist = dist2.sqrt();
            if dist < best[j].1 || best[j].1.is_infinite() {
                best[j] = (u[j], dist);
            }
            if step == NEWTON_STEPS || df <= 0.0 || df.is_nan() {
                continue;
            }
            let next = (u[j] - f / df).clamp(a, b);
            if (next - u[j]).abs() <= 1e-15 * (b - a) {
                continue;
            }
            u[j] = next;
            active[kept] = j;
            kept += 1;
        }
        active.truncate(kept);
        if active.is_empty() {
            break;
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Points;

    /// A plane cubic turning by about a quarter circle (radius of curvature near 1), and points
    /// `Q = C(u) + δ·n(u)` off it along the normal, `|δ| ≤ 1e-3`: their feet `u`, data parameters
    /// off by up to 1 % of the domain, and `|δ|`.
    #[allow(clippy::type_complexity)]
    fn offset_points() -> (BSplineCurve, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
        let ctrl = Points::from_2d(&[
            [1.0, 0.0],
            [1.0, 0.3],
            [0.9, 0.6],
            [0.6, 0.9],
            [0.3, 1.0],
            [0.0, 1.0],
        ])
        .unwrap();
        let kv = KnotVector::clamped_uniform(3, 6).unwrap();
        let curve = BSplineCurve::from_knot_vector(3, kv, ctrl).unwrap();
        let (mut q, mut feet, mut start, mut offsets) = (vec![], vec![], vec![], vec![]);
        for k in 1..40 {
            let u = f64::from(k) / 40.0;
            let d = curve.eval_derivatives(u, 1).unwrap();
            let (c, c1) = (d.point(0), d.point(1));
            let len = c1[0].hypot(c1[1]);
            let delta = 1e-3 * (f64::from(k % 7) - 3.0) / 3.0;
            q.extend([c[0] - delta * c1[1] / len, c[1] + delta * c1[0] / len]);
            feet.push(u);
            // the data parameter is off by up to 1 % of the domain
            start.push(u + 0.01 * (f64::from(k % 5) - 2.0) / 2.0);
            offsets.push(delta.abs());
        }
        (curve, q, feet, start, offsets)
    }

    #[test]
    fn projection_finds_the_foot_of_points_off_the_curve_along_its_normal() {
        // for |δ| below the radius of curvature the foot is C(u), at |δ|
        let (curve, q, feet, start, offsets) = offset_points();
        let todo: Vec<usize> = (0..feet.len()).collect();
        let points = PointsRef::from_flat(2, &q).unwrap();
        let got = project(&curve, points, &start, &todo).unwrap();
        for (k, (&(u, dist), (&foot, &delta))) in
            got.iter().zip(feet.iter().zip(&offsets)).enumerate()
        {
            assert!(
                (dist - delta).abs() <= 1e-13,
                "point {k}: distance {dist} vs {delta}"
            );
            assert!((u - foot).abs() <= 1e-9, "point {k}: foot {u} vs {foot}");
        }
        // only the listed points, in their order
        let some = project(&curve, points, &start, &[5, 2]).unwrap();
        assert_eq!(some, vec![got[5], got[2]], "subset in the order given");
    }

    #[test]
    fn a_local_removal_changes_the_curve_only_where_it_says() {
        // a dense sample of a wave, fitted with many knots; removing one moves the curve only on
        // the reported interval, bit for bit elsewhere
        let q: Vec<f64> = (0..2000)
            .flat_map(|k| {
                let x = f64::from(k) / 1999.0 * 6.0;
                [x, (2.0 * x).sin()]
            })
            .collect();
        let points = PointsRef::from_flat(2, &q).unwrap();
        let params: Vec<f64> = (0..2000).map(|k| f64::from(k) / 1999.0).collect();
        let data = FitData::new(points, &params).unwrap();
        let interior: Vec<f64> = (1..40).map(|k| f64::from(k) / 40.0).collect();
        let kv = clamped(0.0, 1.0, 3, &interior);
        let curve = least_squares(&data, 3, &kv, &EndConstraints::points())
            .unwrap()
            .curve;
        let j = 3 + 1 + 20;
        let (trial, (a, b)) = remove_locally(&curve, j, points, &params).unwrap().unwrap();
        assert_eq!(
            trial.control_points().len(),
            curve.control_points().len() - 1
        );
        assert!(a < interior[20] && interior[20] < b, "[{a}, {b}]");
        let mut moved = 0;
        for &u in &params {
            let (c, t) = (curve.eval(u).unwrap(), trial.eval(u).unwrap());
            if u < a || u > b {
                assert_eq!(c, t, "unchanged at {u} outside [{a}, {b}]");
            } else if c != t {
                moved += 1;
            }
        }
        assert!(moved > 0, "the refit moved the curve under the change");
        // and the refit is a least-squares fit there: close to the data
        let dev = at_parameter(&trial, points, &params).unwrap();
        let worst = dev.iter().fold(0.0_f64, |m, &d| m.max(d));
        assert!(worst < 1e-3, "{worst}");
    }

    #[test]
    fn progress_reports_and_cancels_without_changing_the_fit() {
        use std::sync::atomic::AtomicBool;
        use std::sync::Mutex;
        let q: Vec<f64> = (0..4000)
            .flat_map(|k| {
                let x = f64::from(k) / 3999.0 * 6.0;
                [x, (3.0 * x).sin()]
            })
            .collect();
        let points = PointsRef::from_flat(2, &q).unwrap();
        let opts = ToleranceOptions::new(3, 1e-5);
        let plain = fit_tolerance(points, &opts).unwrap();
        let seen = Mutex::new(Vec::new());
        let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
        let hooked =
            fit_tolerance_with_progress(points, &opts, &Progress::new().with_report(&report))
                .unwrap();
        assert_eq!(hooked, plain, "the hook changes nothing");
        let seen = seen.into_inner().unwrap();
        let last = *seen.last().unwrap();
        assert!(
            last.0 == last.1 && last.1 > 0,
            "ends at its total: {last:?}"
        );
        let stop = AtomicBool::new(true);
        let e = fit_tolerance_with_progress(points, &opts, &Progress::new().with_cancel(&stop));
        assert!(matches!(e, Err(Error::Cancelled { .. })), "{e:?}");
    }

    /// Fits of `q` by the whole algorithm and by the sample-first path with samples of
    /// `sample` points: (control points, largest deviation) of each, both checked against a
    /// full measurement.
    fn both_ways(q: &[f64], dim: usize, tol: f64, sample: usize) -> [(usize, f64); 2] {
        let points = PointsRef::from_flat(dim, q).unwrap();
        let opts = ToleranceOptions::new(3, tol);
        let params = parametrize(points, opts.parametrization).unwrap();
        let progress = Progress::new();
        let (whole, _) = refine(points, &params, &opts, &progress, &[]).unwrap();
        let (sampled, dev) = fit_sample_first(points, &params, &opts, &progress, sample).unwrap();
        let full = deviations_full(&sampled, points, &params, opts.deviation, -1.0).unwrap();
        for (k, (&d, &f)) in dev.iter().zip(&full).enumerate() {
            assert!(d <= tol && d <= f, "point {k}: {d} {f}");
        }
        [&whole, &sampled].map(|c| {
            let d = deviations_full(c, points, &params, opts.deviation, -1.0).unwrap();
            (
                c.control_points().len(),
                d.iter().fold(0.0, |m: f64, &v| m.max(v)),
            )
        })
    }

    #[test]
    fn a_sample_places_the_knots_of_dense_smooth_data() {
        // a helix: the sample's knots hold for every point, found in one pass
        let n = 40_000;
        let q: Vec<f64> = (0..n)
            .flat_map(|k| {
                let u = f64::from(k) / f64::from(n - 1);
                let a = 4.0 * std::f64::consts::PI * u;
                [a.cos(), a.sin(), u]
            })
            .collect();
        let [whole, sampled] = both_ways(&q, 3, 1e-6, 2_000);
        assert!(sampled.1 <= 1e-6, "{sampled:?}");
        assert_eq!(sampled.0, whole.0, "{sampled:?} {whole:?}");
    }

    #[test]
    fn where_the_sample_misses_points_knots_are_added_and_pruned_for_all() {
        // noise of 0.9·tol between the sampled points: the sample's curve misses some, the
        // insertion for all points adds knots, and the removal near them keeps the count
        // within a few percent of the whole algorithm's
        let (n, tol) = (20_000_u32, 1e-4);
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut noise = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1_u64 << 53) as f64 - 0.5
        };
        let q: Vec<f64> = (0..n)
            .flat_map(|k| {
                let x = f64::from(k) / f64::from(n - 1) * 6.0;
                [x, (3.0 * x).sin() + 0.9 * tol * noise()]
            })
            .collect();
        let points = PointsRef::from_flat(2, &q).unwrap();
        let opts = ToleranceOptions::new(3, tol);
        let params = parametrize(points, opts.parametrization).unwrap();
        let (flat, ps) = sample_of(points, &params, 1_000);
        let sample = PointsRef::from_flat(2, &flat).unwrap();
        let (first, _) = refine(sample, &ps, &opts, &Progress::new(), &[]).unwrap();
        let misses = deviations_full(&first, points, &params, opts.deviation, -1.0).unwrap();
        assert!(
            misses.iter().any(|&d| d > tol),
            "the fallback is not exercised"
        );
        let [whole, sampled] = both_ways(&q, 2, tol, 1_000);
        assert!(sampled.1 <= tol, "{sampled:?}");
        assert!(
            sampled.0 as f64 <= 1.03 * whole.0 as f64,
            "{sampled:?} against {whole:?}"
        );
    }

    #[test]
    fn the_local_part_of_a_curve_is_the_curve_there() {
        let (curve, ..) = offset_points();
        let fine = curve
            .refine_knots(&[0.1, 0.2, 0.35, 0.5, 0.6, 0.8])
            .unwrap();
        for (lo, hi) in [(0.0, 0.05), (0.15, 0.4), (0.55, 1.0), (-1.0, 2.0)] {
            let part = local_part(&fine, lo, hi).unwrap();
            let (a, b) = part.domain();
            assert!(
                a <= lo.max(0.0) && b >= hi.min(1.0),
                "{lo} {hi}: [{a}, {b}]"
            );
            for k in 0..=20 {
                let u = a + (b - a) * f64::from(k) / 20.0;
                assert_eq!(part.eval(u).unwrap(), fine.eval(u).unwrap(), "at {u}");
            }
        }
    }

    #[test]
    fn tracked_deviations_are_those_of_a_full_measurement() {
        let q: Vec<f64> = (0..3000)
            .flat_map(|k| {
                let x = f64::from(k) / 2999.0 * 6.0;
                [x.cos() * (1.0 + 0.1 * x), x.sin() * (1.0 + 0.1 * x)]
            })
            .collect();
        let points = PointsRef::from_flat(2, &q).unwrap();
        for how in [Deviation::Distance, Deviation::Parameter] {
            let opts = ToleranceOptions {
                deviation: how,
                ..ToleranceOptions::new(3, 1e-6)
            };
            let fit = fit_tolerance(points, &opts).unwrap();
            let full = deviations_full(&fit.curve, points, &fit.params, how, -1.0).unwrap();
            for (k, (&d, &f)) in fit.deviations.iter().zip(&full).enumerate() {
                assert!(
                    d <= 1e-6 && f <= 1e-6 * (1.0 + 1e-9),
                    "{how:?} point {k}: {d} {f}"
                );
                assert!(d <= f, "{how:?} point {k}: kept the smaller bound");
            }
        }
    }
}
