//! Knot removal for B-spline curves with a tolerance (P&T §5.4, Algorithm A5.8) and the
//! simplification that removes every removable knot.
//!
//! ## Tolerance
//! A tolerance is an **absolute distance** in the units of the control points: a removal is
//! accepted only if the new curve `C̃` satisfies `|C(t) − C̃(t)| ≤ tolerance` for every `t` in the
//! domain. Choose it relative to the curve's scale, e.g. `1e-6 · extent` for a visually exact
//! fit; [`BSplineCurve::default_removal_tolerance`] gives
//! `DEFAULT_REMOVAL_RTOL · extent + 64 ε · max|P|`, which removes only knots that are removable up
//! to rounding (such as knots just inserted, or the extra knots of
//! [`BSplineCurve::from_bezier_segments`] and of degree elevation per Bezier segment).
//!
//! ## Error bound
//! After removing `k` copies of the knot `u`, inserting them back into `C̃` by Boehm's algorithm
//! (exact) gives control points `Q'_i` on the original knot vector, and
//! `C(t) − C̃(t) = Σ_i N_{i,p}(t) (P_i − Q'_i)`; by partition of unity and non-negativity
//! `|C(t) − C̃(t)| ≤ max_i |P_i − Q'_i|` (P&T §5.4, the bound behind eq. 5.30). lekalo
//! computes this bound for every candidate instead of trusting the single distance test of A5.8,
//! so the guarantee also holds for several copies and for knots of multiplicity `p + 1`.

use crate::curve::bspline::BSplineCurve;
use crate::error::readable;
use crate::error::{Error, Result};
use crate::points::Points;
use crate::{Arg, What};

/// Relative part of [`BSplineCurve::default_removal_tolerance`]: `1e-12` times the extent
/// (bounding-box diagonal) of the control net.
///
/// Knot-removal tolerances in lekalo are **absolute distances** in the units of the control
/// points: a removal is accepted only if the new curve `C̃` satisfies `|C(t) − C̃(t)| ≤ tolerance`
/// on the whole domain. Choose it relative to the curve's scale (e.g. `1e-6 · extent` for a
/// visually exact fit); the default, `DEFAULT_REMOVAL_RTOL · extent + 64 ε · max|P|`, removes
/// only knots that are removable up to rounding. The bound is checked exactly: inserting the
/// removed copies back into `C̃` (Boehm, exact) gives control points `Q'_i` on the original
/// knots, and `C − C̃ = Σ N_{i,p} (P_i − Q'_i)`, so by partition of unity and non-negativity
/// `|C − C̃| ≤ max_i |P_i − Q'_i|` (P&T §5.4).
pub const DEFAULT_REMOVAL_RTOL: f64 = 1e-12;

/// Rounding part of the default tolerance, in units of `ε · max|P|`: the coefficients of A5.8
/// divide by `α ∈ (0, 1)`, so a removable knot is reproduced only up to a few ulps of the
/// coordinates' magnitude (which can exceed the extent when the curve is far from the origin).
const ROUNDING_ULPS: f64 = 64.0;

impl BSplineCurve {
    /// The default knot-removal tolerance: `DEFAULT_REMOVAL_RTOL · extent + 64 ε · max|P|`, where
    /// `extent` is the bounding-box diagonal of the control points and `max|P|` their largest
    /// coordinate. Removes only knots that are removable
    /// up to rounding. See [`DEFAULT_REMOVAL_RTOL`] for what a removal tolerance means.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let c = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4)?, ctrl)?;
    /// let tol = c.default_removal_tolerance();
    /// assert!(tol > 0.0 && tol < 1e-11);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn default_removal_tolerance(&self) -> f64 {
        default_tolerance(self.control_points())
    }

    /// Removes the interior knot `t` up to `times` times (P&T §5.4, Algorithm A5.8), keeping
    /// the curve within `tolerance` (an absolute distance, see [`DEFAULT_REMOVAL_RTOL`]): copies are
    /// removed one at a time and the removal stops at the first copy whose removal would move
    /// the curve by more than `tolerance` from `self`. Returns the new curve and the number of
    /// copies removed (`0 ..= times`; `0` returns a copy of `self`).
    ///
    /// Each copy: with `r` the last index of `t` and `s` its multiplicity, the `p − s + 1`
    /// control points `P_{r−p} … P_{r−s}` are replaced by `p − s` points computed from both
    /// ends by inverting Boehm's formula (P&T eq. 5.28),
    /// `Q_i = (P_i − (1 − α_i) Q_{i−1}) / α_i`, `Q_{j−1} = (P_j − α_j Q_j) / (1 − α_j)`,
    /// `α_k = (t − t_k) / (t_{k+p+1} − t_k)`; where the two sweeps meet their average is kept.
    /// The deviation from `self` is then bounded exactly by re-insertion
    /// ([`DEFAULT_REMOVAL_RTOL`]) instead of by A5.8's single distance test, so the guarantee
    /// holds for several copies and for knots of multiplicity `p + 1` too.
    /// O(times·(n + p²)·dim).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let c = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4)?, ctrl)?;
    /// let d = c.insert_knot(0.4, 2)?;
    /// let (back, removed) = d.remove_knot(0.4, 2, d.default_removal_tolerance())?;
    /// assert_eq!(removed, 2);
    /// assert_eq!(back.knots(), c.knots());
    /// for (a, b) in back.control_points().as_slice().iter().zip(c.control_points().as_slice()) {
    ///     assert!((a - b).abs() < 1e-14);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `tolerance`; [`Error::InvalidArgument`] for a
    /// negative `tolerance`, for `t` at an end of the domain (removing it would change the
    /// domain), for a `t` that is not a knot, or for `times` above the multiplicity of `t`;
    /// [`Error::ParameterOutOfDomain`] if `t` is outside the domain or NaN.
    pub fn remove_knot(
        &self,
        t: f64,
        times: usize,
        tolerance: f64,
    ) -> Result<(BSplineCurve, usize)> {
        check_tolerance(tolerance)?;
        let (min, max) = self.domain();
        if !(t >= min && t <= max) {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        if t == min || t == max {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Knot, "knot to remove"),
                reason: format!(
                    "t = {t} is an end of the domain [{min}, {max}]; only knots strictly inside \
                     the domain can be removed",
                    t = readable(&t),
                    min = readable(&min),
                    max = readable(&max)
                ),
            });
        }
        let s = self.knots().multiplicity(t);
        if s == 0 {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Knot, "knot to remove"),
                reason: format!(
                    "t = {t} is not a knot of the curve; pass one of its knots",
                    t = readable(&t)
                ),
            });
        }
        if times > s {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Times, "knot removal count"),
                reason: format!(
                    "knot {t} has multiplicity {s}, so it cannot be removed {times} times; \
                     remove it at most {s} times",
                    t = readable(&t)
                ),
            });
        }
        let mut current = self.clone();
        let mut removed = 0;
        while removed < times {
            let candidate = remove_once(&current, t);
            let deviation = point_deviations(self, &candidate, t, removed + 1)
                .map_or(f64::INFINITY, |d| d.iter().fold(0.0_f64, |m, &x| m.max(x)));
            if !within(deviation, tolerance) {
                break;
            }
            current = candidate;
            removed += 1;
        }
        Ok((current, removed))
    }

    /// Removes every interior knot copy whose removal keeps the curve within `tolerance` of
    /// `self` (an absolute distance, see [`DEFAULT_REMOVAL_RTOL`]), and returns the new curve and the
    /// number of copies removed. Knots are tried from left to right, each copy by
    /// [`BSplineCurve::remove_knot`]'s step, in passes until nothing more can be removed. The
    /// error bound of each removal is charged to the breakpoint intervals of `self` it affects
    /// (the supports of the changed B-splines), and a removal is accepted only if the
    /// accumulated bound stays `≤ tolerance` on every interval — by the triangle inequality the
    /// final curve is then within `tolerance` of `self` everywhere. O(passes·n·(n + p²)·dim).
    ///
    /// Use it after operations that introduce removable knots: [`BSplineCurve::from_bezier_segments`]
    /// (joins of multiplicity `p`), degree elevation per Bezier segment, knot refinement.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 3.0, 2.0, 5.0])?;
    /// let c = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 5)?, ctrl)?;
    /// let pieces = BSplineCurve::from_bezier_segments(&c.to_bezier_segments())?;
    /// assert_eq!(pieces.control_points().len(), 7);
    /// let (simple, removed) = pieces.remove_all_removable_knots(1e-12)?;
    /// assert_eq!(removed, 2);
    /// assert_eq!(simple.knots(), c.knots());
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `tolerance`; [`Error::InvalidArgument`] for a
    /// negative one.
    pub fn remove_all_removable_knots(&self, tolerance: f64) -> Result<(BSplineCurve, usize)> {
        check_tolerance(tolerance)?;
        Ok(remove_all(self, tolerance))
    }

    /// [`BSplineCurve::remove_all_removable_knots`] with
    /// [`BSplineCurve::default_removal_tolerance`]: removes the knots that are removable up to
    /// rounding, so the curve is unchanged. Returns the curve and the number of copies removed.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 3.0, 2.0])?;
    /// let c = BSplineCurve::from_knot_vector(2, KnotVector::clamped_uniform(2, 4)?, ctrl)?;
    /// let (simple, removed) = c.refine_knots(&[0.2, 0.7, 0.7])?.simplify();
    /// assert_eq!((removed, simple.knots()), (3, c.knots()));
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn simplify(&self) -> (BSplineCurve, usize) {
        remove_all(self, self.default_removal_tolerance())
    }
}

/// `DEFAULT_REMOVAL_RTOL · extent + ROUNDING_ULPS · ε · max|P|`, at most `f64::MAX`.
pub(crate) fn default_tolerance(control: &Points) -> f64 {
    (DEFAULT_REMOVAL_RTOL * control.extent() + ROUNDING_ULPS * f64::EPSILON * control.max_abs())
        .min(f64::MAX)
}

/// `deviation ≤ tolerance`; false for a NaN deviation, so a NaN never passes as removable.
fn within(deviation: f64, tolerance: f64) -> bool {
    deviation <= tolerance
}

/// A removal tolerance must be finite and non-negative.
pub(crate) fn check_tolerance(tolerance: f64) -> Result<()> {
    if !tolerance.is_finite() {
        return Err(Error::NonFinite {
            what: Arg::Tolerance.into(),
            index: 0,
            value: tolerance,
        });
    }
    if tolerance < 0.0 {
        return Err(Error::InvalidArgument {
            what: Arg::Tolerance.into(),
            reason: format!(
                "{tolerance} is negative; pass an absolute distance ≥ 0 (e.g. the curve's \
                 default_removal_tolerance)",
                tolerance = readable(&tolerance)
            ),
        });
    }
    Ok(())
}

/// One removal of the interior knot `t` (a knot strictly inside the domain) without a
/// tolerance test: the step of P&T Algorithm A5.8 (eq. 5.28), with the two sweeps averaged where
/// they meet.
fn remove_once(c: &BSplineCurve, t: f64) -> BSplineCurve {
    let p = c.degree();
    let dim = c.dim();
    let u = c.knots().as_slice();
    let pc = c.control_points().as_slice();
    let n = c.control_points().len() - 1;
    // r: last index of t; s: its multiplicity. t inside the domain gives r ≥ p + s, r ≤ n.
    let r = u.partition_point(|&x| x <= t) - 1;
    let s = u[..=r].iter().rev().take_while(|&&x| x == t).count();
    debug_assert!(s >= 1 && r >= p + s && r <= n, "interior knot for removal");
    let first = r - p; // first changed control point
    let last = r - s; // last changed control point (first − 1 for s = p + 1)
    let off = first - 1;
    // left[k − off] = L_k, right[k − off] = R_k for k = off ..= last: the new points computed
    // from the left (L_off = P_off) and from the right (R_last = P_{last+1})
    let width = last + 1 - off;
    let mut left = vec![0.0; width * dim];
    let mut right = vec![0.0; width * dim];
    left[..dim].copy_from_slice(&pc[off * dim..first * dim]);
    right[(width - 1) * dim..].copy_from_slice(&pc[(last + 1) * dim..(last + 2) * dim]);
    let (mut i, mut j) = (first, last);
    while j > i {
        let ai = (t - u[i]) / (u[i + p + 1] - u[i]);
        let aj = (t - u[j]) / (u[j + p + 1] - u[j]);
        debug_assert!(ai > 0.0 && aj < 1.0, "0 < α < 1 at an interior knot");
        for d in 0..dim {
            let li = (pc[i * dim + d] - (1.0 - ai) * left[(i - 1 - off) * dim + d]) / ai;
            left[(i - off) * dim + d] = li;
            let rj = (pc[j * dim + d] - aj * right[(j - off) * dim + d]) / (1.0 - aj);
            right[(j - 1 - off) * dim + d] = rj;
        }
        i += 1;
        j -= 1;
    }
    // left is known for k ≤ i − 1, right for k ≥ j, and j ∈ {i − 1, i}
    let mut q = Vec::with_capacity(n * dim);
    q.extend_from_slice(&pc[..off * dim]);
    for k in off..=last {
        let (l, rr) = (&left[(k - off) * dim..], &right[(k - off) * dim..]);
        if k < i && k >= j {
            q.extend((0..dim).map(|d| 0.5 * (l[d] + rr[d])));
        } else if k < i {
            q.extend_from_slice(&l[..dim]);
        } else {
            q.extend_from_slice(&rr[..dim]);
        }
    }
    q.extend_from_slice(&pc[(last + 2) * dim..]);
    let mut knots = u.to_vec();
    knots.remove(r);
    let out = BSplineCurve::from_raw(p, knots, Points::from_raw(q, dim));
    debug_assert!(
        out.knots()
            .validate_for(p, out.control_points().len())
            .is_ok(),
        "removal keeps a valid knot vector"
    );
    out
}

/// `|P_i − Q'_i|` for every control point of `original`, where `Q'` are the control points of
/// `reduced` after inserting `t` back `k` times (so on `original`'s knot vector). `None` only
/// if re-insertion fails, which the callers' invariants exclude.
fn point_deviations(
    original: &BSplineCurve,
    reduced: &BSplineCurve,
    t: f64,
    k: usize,
) -> Option<Vec<f64>> {
    let p = original.degree();
    let target = original.knots().multiplicity(t);
    // Boehm insertion reaches multiplicity p; a knot of multiplicity p + 1 (a jump) is then
    // reached by doubling the point the curve passes through at t
    let by_insertion = if target > p { k - 1 } else { k };
    let back = reduced.insert_knot(t, by_insertion).ok()?;
    let dim = back.dim();
    let mut points = back.control_points().as_slice().to_vec();
    if target > p {
        let a = back.knots().as_slice().partition_point(|&x| x < t);
        let join = points[(a - 1) * dim..a * dim].to_vec();
        points.splice(a * dim..a * dim, join);
    }
    let orig = original.control_points().as_slice();
    debug_assert_eq!(points.len(), orig.len(), "re-insertion restores the count");
    if points.len() != orig.len() {
        return None;
    }
    Some(
        orig.chunks_exact(dim)
            .zip(points.chunks_exact(dim))
            .map(|(a, b)| {
                a.iter()
                    .zip(b)
                    .map(|(x, y)| (x - y) * (x - y))
                    .sum::<f64>()
                    .sqrt()
            })
            .collect(),
    )
}

/// Removes every removable knot copy within `tolerance` (validated), charging each removal's
/// bound to the breakpoint intervals of `c` it affects. Each attempt works on a local window of
/// the curve (the arithmetic is the same as on the whole curve, since removal and re-insertion
/// change only `p − s + 2` points), so an attempt costs O(p²·dim + log n) plus the O(n) splice
/// of an accepted removal.
fn remove_all(c: &BSplineCurve, tolerance: f64) -> (BSplineCurve, usize) {
    let p = c.degree();
    let dim = c.dim();
    let (min, max) = c.domain();
    // breakpoints of the original domain and the error bound charged to each interval
    let mut breaks: Vec<f64> = c
        .knots()
        .distinct()
        .into_iter()
        .map(|(k, _)| k)
        .filter(|&k| k > min && k < max)
        .collect();
    breaks.insert(0, min);
    breaks.push(max);
    let mut charged = vec![0.0_f64; breaks.len() - 1];
    let mut knots = c.knots().as_slice().to_vec();
    let mut points = c.control_points().as_slice().to_vec();
    let mut removed = 0;
    loop {
        let mut changed = false;
        let interior: Vec<f64> = breaks[1..breaks.len() - 1].to_vec();
        for t in interior {
            loop {
                let lo_t = knots.partition_point(|&x| x < t);
                let hi_t = knots.partition_point(|&x| x <= t);
                if hi_t == lo_t {
                    break;
                }
                let (r, s) = (hi_t - 1, hi_t - lo_t);
                let n = points.len() / dim - 1;
                // window of points a ..= b around the changed ones (first − 1 ..= last + 1),
                // padded by p so that t is strictly inside the window's own domain
                let a = (r - p - 1).saturating_sub(p);
                let b = (r - s + 1 + p).min(n);
                let window = BSplineCurve::from_raw(
                    p,
                    knots[a..=b + p + 1].to_vec(),
                    Points::from_raw(points[a * dim..(b + 1) * dim].to_vec(), dim),
                );
                let candidate = remove_once(&window, t);
                let Some(dev) = point_deviations(&window, &candidate, t, 1) else {
                    break;
                };
                let worst = dev.iter().fold(0.0_f64, |m, &x| m.max(x));
                if !within(worst, tolerance) {
                    break;
                }
                // the change Σ N_i δ_i lives on the supports [t_i, t_{i+p+1}] of the changed i
                let changed_pts: Vec<usize> = (0..dev.len()).filter(|&i| dev[i] > 0.0).collect();
                let range = match (changed_pts.first(), changed_pts.last()) {
                    (Some(&i0), Some(&i1)) => {
                        let (lo, hi) = (knots[a + i0], knots[a + i1 + p + 1]);
                        // intervals [breaks[k], breaks[k+1]] with breaks[k] < hi and
                        // breaks[k+1] > lo
                        let k0 = breaks.partition_point(|&x| x <= lo).saturating_sub(1);
                        let k1 = breaks.partition_point(|&x| x < hi).min(charged.len());
                        k0..k1.max(k0)
                    }
                    _ => 0..0,
                };
                if charged[range.clone()]
                    .iter()
                    .any(|&e| !within(e + worst, tolerance))
                {
                    break;
                }
                for e in &mut charged[range] {
                    *e += worst;
                }
                knots.remove(r);
                points.splice(
                    a * dim..(b + 1) * dim,
                    candidate.control_points().as_slice().iter().copied(),
                );
                removed += 1;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let out = BSplineCurve::from_raw(p, knots, Points::from_raw(points, dim));
    debug_assert!(
        out.knots()
            .validate_for(p, out.control_points().len())
            .is_ok(),
        "simplified curve must be valid"
    );
    (out, removed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knots::KnotVector;

    fn cubic() -> BSplineCurve {
        let ctrl =
            Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [6.0, 1.0]]).unwrap();
        BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 5).unwrap(), ctrl).unwrap()
    }

    #[test]
    fn insert_then_remove_at_every_multiplicity() {
        let c = cubic();
        for times in 1..=3 {
            let d = c.insert_knot(0.25, times).unwrap();
            let (back, removed) = d.remove_knot(0.25, times, 1e-12).unwrap();
            assert_eq!(removed, times, "all inserted copies are removable");
            assert_eq!(back.knots(), c.knots(), "knots restored");
            for (a, b) in back
                .control_points()
                .as_slice()
                .iter()
                .zip(c.control_points().as_slice())
            {
                assert!((a - b).abs() < 1e-13, "control point {a} vs {b}");
            }
        }
    }

    #[test]
    fn original_knot_of_a_generic_curve_is_kept() {
        let c = cubic();
        let (same, removed) = c.remove_knot(0.5, 1, 1e-9).unwrap();
        assert_eq!(removed, 0, "a generic cubic's knot changes the curve");
        assert_eq!(same, c, "nothing removed means an identical curve");
    }

    #[test]
    fn equal_jump_is_removable_unequal_is_not() {
        // degree 1 with a knot of multiplicity 2 (a jump) between equal and unequal points
        let equal = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0, 2.0, 2.0],
            Points::from_flat(1, vec![0.0, 3.0, 3.0, 5.0]).unwrap(),
        )
        .unwrap();
        let (c, removed) = equal.remove_knot(1.0, 2, 0.0).unwrap();
        // the jump copy goes exactly; 0 → 3 on [0, 1] then 3 → 5 on [1, 2] is not one line
        assert_eq!(
            removed, 1,
            "only the jump copy is removable with tolerance 0"
        );
        assert_eq!(c.knots().as_slice(), &[0.0, 0.0, 1.0, 2.0, 2.0]);
        assert_eq!(c.control_points().as_slice(), &[0.0, 3.0, 5.0]);
        // the second copy moves C(1) from 3 to 2.5
        assert_eq!(equal.remove_knot(1.0, 2, 0.49).unwrap().1, 1, "0.5 > 0.49");
        assert_eq!(equal.remove_knot(1.0, 2, 0.5).unwrap().1, 2, "0.5 ≤ 0.5");
        let jump = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0, 2.0, 2.0],
            Points::from_flat(1, vec![0.0, 3.0, 4.0, 5.0]).unwrap(),
        )
        .unwrap();
        assert_eq!(
            jump.remove_knot(1.0, 1, 0.49).unwrap().1,
            0,
            "half-jump 0.5 > 0.49"
        );
        let (c, removed) = jump.remove_knot(1.0, 1, 0.5).unwrap();
        assert_eq!(removed, 1, "the merged point is 0.5 from both sides");
        assert_eq!(c.control_points().as_slice(), &[0.0, 3.5, 5.0]);
    }
}
