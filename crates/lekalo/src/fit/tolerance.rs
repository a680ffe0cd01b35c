//! Fitting to a tolerance: a B-spline within `tol` of every point with few control points
//! (`docs/theory/fitting.md#tolerance`).

use super::data::FitData;
use super::lsq::{least_squares, EndConstraints};
use crate::error::{Error, Result};
use crate::interpolate::{parametrize, Parametrization};
use crate::knots::KnotVector;
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
///    more by refitting without it, kept out when the refit is still within `tol` (a trial
///    stops at its first point beyond `tol`, looking near the removed knot first).
///
/// Deviation is the distance to the curve ([`Deviation::Distance`], a closest-point projection
/// per point) or at the data parameter ([`Deviation::Parameter`]). O(rounds·N·p²) plus the
/// projections.
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
    let data = FitData::new(points, &params)?;
    let (a, b) = (params[0], params[params.len() - 1]);
    let ends = EndConstraints::points();
    let mut interior: Vec<f64> = Vec::new();
    // knot sites that keep the Schoenberg–Whitney conditions (see smoothing_condition)
    let mut distinct = params.clone();
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
            &params,
            &f.report.residuals,
            opts.deviation,
            tol,
        )?;
        Ok((f.curve, dev))
    };
    let (mut curve, mut dev) = fit(&interior)?;
    loop {
        let bad = bad_spans(&params, &dev, tol, a, b, &interior);
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
    if worst < tol && !interior.is_empty() {
        let (removed_curve, removed) = curve.remove_all_removable_knots(tol - worst)?;
        if removed > 0 {
            let d = deviations_full(&removed_curve, points, &params, opts.deviation, tol)?;
            if d.iter().all(|&v| v <= tol) {
                curve = removed_curve;
                dev = d;
                interior = interior_knots(&curve);
            }
        }
    }
    let mut k = 0;
    while k < interior.len() {
        let mut trial = interior.clone();
        let removed = trial.remove(k);
        let kv = clamped(a, b, p, &trial);
        // a fit that fails (a span without data) keeps the knot, as one beyond tol does
        let kept = least_squares(&data, p, &kv, &ends).ok().and_then(|f| {
            let d = deviations_within(
                &f.curve,
                points,
                &params,
                &f.report.residuals,
                opts.deviation,
                tol,
                removed,
            );
            d.transpose().map(|d| d.map(|d| (f.curve, d)))
        });
        match kept {
            Some(Ok((c, d))) => (curve, dev, interior) = (c, d, trial),
            Some(Err(e)) => return Err(e),
            None => k += 1,
        }
    }
    // the exact distances of the final curve (the rounds kept upper bounds below tol)
    if opts.deviation == Deviation::Distance {
        dev = deviations_full(&curve, points, &params, opts.deviation, -1.0)?;
    }
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

/// Points projected per block by [`deviations_within`] before it looks for one beyond `tol`.
const TRIAL_BLOCK: usize = 4096;

/// [`deviations`] with `skip_below = tol` for a trial curve, or `None` as soon as one is beyond
/// `tol`: the points are projected in blocks, those with parameters nearest `near` (the removed
/// knot, around which the curve changed most) first. The same deviations as [`deviations`] when
/// all are within `tol` (each projection depends only on its point).
fn deviations_within(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    at_param: &[f64],
    how: Deviation,
    tol: f64,
    near: f64,
) -> Result<Option<Vec<f64>>> {
    let mut dev = at_param.to_vec();
    if how == Deviation::Parameter {
        return Ok(dev.iter().all(|&v| v <= tol).then_some(dev));
    }
    let mut todo: Vec<usize> = (0..dev.len()).filter(|&i| dev[i] > tol).collect();
    todo.sort_by(|&i, &j| {
        (params[i] - near)
            .abs()
            .total_cmp(&(params[j] - near).abs())
    });
    for block in todo.chunks(TRIAL_BLOCK) {
        let feet = project(curve, points, params, block)?;
        for (&i, &(_, d)) in block.iter().zip(&feet) {
            dev[i] = dev[i].min(d);
            if dev[i] > tol || dev[i].is_nan() {
                return Ok(None);
            }
        }
    }
    Ok(dev.iter().all(|&v| v <= tol).then_some(dev))
}

fn deviations_full(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    how: Deviation,
    skip_below: f64,
) -> Result<Vec<f64>> {
    let dim = points.dim();
    let mut out = vec![0.0; params.len() * dim];
    curve.evaluator().eval_batch(params, &mut out)?;
    let at: Vec<f64> = out
        .chunks_exact(dim)
        .zip(points.iter())
        .map(|(c, q)| {
            c.iter()
                .zip(q)
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    deviations(curve, points, params, &at, how, skip_below)
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
    let (a, b) = curve.domain();
    let dim = points.dim();
    let eval = curve.evaluator();
    let mut u: Vec<f64> = todo.iter().map(|&i| params[i]).collect();
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
    fn a_trial_stops_at_a_point_beyond_tol_and_otherwise_measures_every_point() {
        let (curve, q, _, start, offsets) = offset_points();
        let points = PointsRef::from_flat(2, &q).unwrap();
        let mut at = vec![0.0; start.len() * 2];
        curve.eval_batch(&start, &mut at).unwrap();
        let at: Vec<f64> = at
            .chunks_exact(2)
            .zip(points.iter())
            .map(|(c, p)| (c[0] - p[0]).hypot(c[1] - p[1]))
            .collect();
        let how = Deviation::Distance;
        // every |δ| ≤ 1e-3 < tol: the deviations of a full measurement
        let tol = 2e-3;
        let all = deviations(&curve, points, &start, &at, how, tol).unwrap();
        let within = deviations_within(&curve, points, &start, &at, how, tol, 0.5).unwrap();
        assert_eq!(within.as_ref(), Some(&all), "all within tol");
        for (k, ((&d, &a), &o)) in all.iter().zip(&at).zip(&offsets).enumerate() {
            // projected beyond tol at the parameter, kept as the upper bound below it
            let want = if a > tol { o } else { a };
            assert!((d - want).abs() <= 1e-13, "point {k}: {d} vs {want}");
        }
        // tol below the largest offset: refused
        let tol = 0.9 * offsets.iter().fold(0.0_f64, |m, &v| m.max(v));
        let within = deviations_within(&curve, points, &start, &at, how, tol, 0.5).unwrap();
        assert!(within.is_none(), "a point beyond tol refuses the trial");
        let at_only =
            deviations_within(&curve, points, &start, &at, Deviation::Parameter, tol, 0.5);
        assert!(
            at_only.unwrap().is_none(),
            "parameter deviations beyond tol refuse it too"
        );
    }
}
