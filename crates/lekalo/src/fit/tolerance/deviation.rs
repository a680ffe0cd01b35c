//! The deviations of the data from a curve in [`fit_tolerance`](super::fit_tolerance): at the
//! data parameters, by projection (Newton's method, all points together), and tracked through
//! the local changes of knot removal (`docs/theory/fitting.md#tolerance`).

use super::Deviation;
use crate::error::Result;
use crate::points::{Points, PointsRef};
use crate::BSplineCurve;

/// Deviations of every point. The distance is at most the deviation at the parameter, so only
/// points beyond `skip_below` there are projected (the others keep that upper bound);
/// `skip_below < 0` projects every point.
pub(super) fn deviations(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    at_param: &[f64],
    how: Deviation,
    skip_below: f64,
) -> Result<Vec<f64>> {
    Ok(deviations_with_feet(curve, points, params, at_param, how, skip_below)?.0)
}

/// [`deviations`] and, per point, the parameter of the closest point found by the projection
/// (`NaN` where the deviation is the one at the data parameter).
pub(super) fn deviations_with_feet(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    at_param: &[f64],
    how: Deviation,
    skip_below: f64,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut dev = at_param.to_vec();
    let mut feet = vec![f64::NAN; dev.len()];
    if how == Deviation::Distance {
        let todo: Vec<usize> = (0..dev.len()).filter(|&i| dev[i] > skip_below).collect();
        let found = project(curve, points, params, &todo)?;
        for (&i, &(u, d)) in todo.iter().zip(&found) {
            if d < dev[i] {
                (dev[i], feet[i]) = (d, u);
            }
        }
    }
    Ok((dev, feet))
}

pub(super) fn deviations_full(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    how: Deviation,
    skip_below: f64,
) -> Result<Vec<f64>> {
    Ok(deviations_full_with_feet(curve, points, params, how, skip_below)?.0)
}

/// [`deviations_full`] with the feet of [`deviations_with_feet`].
pub(super) fn deviations_full_with_feet(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
    how: Deviation,
    skip_below: f64,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let at = at_parameter(curve, points, params)?;
    deviations_with_feet(curve, points, params, &at, how, skip_below)
}

/// Per point the smaller of two measurements `(deviation, foot)` of the same curve (a foot
/// `NaN`: at the data parameter).
pub(super) fn smaller(a: (Vec<f64>, Vec<f64>), b: (Vec<f64>, Vec<f64>)) -> (Vec<f64>, Vec<f64>) {
    let (mut dev, mut feet) = a;
    for (i, (d, f)) in b.0.into_iter().zip(b.1).enumerate() {
        if d < dev[i] {
            (dev[i], feet[i]) = (d, f);
        }
    }
    (dev, feet)
}

/// Points measured per block by [`Tracked::accept`] before it looks for one beyond `tol`.
pub(super) const TRIAL_BLOCK: usize = 1024;

/// Deviations kept up to date through local changes of the curve: per point the deviation at
/// its data parameter (`at`) and an upper bound of its distance to the curve (`dev`), from the
/// foot `feet[i]` of a projection (`NaN`: none, `dev = at`). `reach` bounds `|foot − param|`,
/// so a change of the curve on `[a, b]` concerns only the points with parameters in
/// `[a − reach, b + reach]`.
pub(super) struct Tracked {
    at: Vec<f64>,
    pub(super) dev: Vec<f64>,
    pub(super) feet: Vec<f64>,
    reach: f64,
    how: Deviation,
}

impl Tracked {
    pub(super) fn new(
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
    pub(super) fn measure(
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

    pub(super) fn commit(&mut self, todo: &[usize], dev: &[f64], feet: &[f64], params: &[f64]) {
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
    pub(super) fn accept(
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
pub(super) fn local_part(curve: &BSplineCurve, lo: f64, hi: f64) -> Result<BSplineCurve> {
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
pub(super) fn at_parameter(
    curve: &BSplineCurve,
    points: PointsRef<'_>,
    params: &[f64],
) -> Result<Vec<f64>> {
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
pub(super) const NEWTON_STEPS: usize = 8;

/// Closest points on `curve` to the points `todo` by Newton's method on
/// `(C(u) − Q)·C'(u) = 0` from their data parameters (at most [`NEWTON_STEPS`] steps, kept in
/// the domain, stopped when the step vanishes or the second derivative of the squared
/// distance is not positive): per point the parameter and distance of the closest iterate.
/// All points take their steps together, one batch evaluation of `C, C', C''` per step
/// ([`CurveEvaluator`](crate::CurveEvaluator), no allocation per point).
pub(super) fn project(
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
pub(super) fn project_from(
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
