//! Planar curve–curve intersections and self-intersections: the search of `planar.rs`, then
//! its solutions grouped into answers (`docs/theory/queries.md#intersections`).

use super::super::pieces::{check_tolerance, dist, dot, QueryCurve};
use super::super::project::ProjectScratch;
use super::planar::{overlapping_pairs, PlaneNets, Raw, Search, Sub};
use super::{Contact, CurveIntersection};
use crate::error::{Error, Result};
use crate::{Arg, What};

/// Step of the probes beside a solution, as a fraction of the first curve's domain: the gap
/// there tells a crossing from a contact or an overlap.
const PROBE: f64 = 1e-6;

/// A solution in the curves' parameters: `t_a`, `t_b`, the gap, and whether it is a transversal
/// crossing (see [`QueryCurve::assemble`]).
pub(super) type Solution = (f64, f64, f64, bool);

impl QueryCurve {
    /// The common frame of two curves (the first one's centre, the larger scale) and both
    /// curves' pieces in it.
    fn planar_frame(&self, other: &QueryCurve) -> (PlaneNets, PlaneNets, f64) {
        let scale = self.scale.max(other.scale);
        (
            PlaneNets::new(self, &self.centre, scale),
            PlaneNets::new(other, &self.centre, scale),
            scale,
        )
    }

    /// Every intersection of this planar curve with `other`, in the order of this curve's
    /// parameter. Points closer than `tolerance` (absolute, in the curves' units) count as
    /// common; a tangential contact is one [`CurveIntersection::Point`] (where the gap is least);
    /// stretches where the curves coincide to rounding are [`CurveIntersection::Overlap`]s.
    ///
    /// The pairs of pieces whose boxes overlap are found by sort and sweep, then searched by
    /// Bezier clipping (Sederberg–Nishita 1990), halving and Newton's method
    /// (`docs/theory/queries.md#intersections`).
    ///
    /// ```
    /// use lekalo::query::CurveIntersection;
    /// use lekalo::{BSplineCurve, NurbsCurve, Points, QueryCurve};
    /// let circle = QueryCurve::from_nurbs(&NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0)?)?;
    /// let line = BSplineCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], Points::from_2d(&[[-2.0, 0.5], [2.0, 0.5]])?)?;
    /// let hits = circle.intersect(&QueryCurve::from_bspline(&line)?, 1e-10)?;
    /// assert_eq!(hits.len(), 2);
    /// if let CurveIntersection::Point { point, .. } = &hits[0] {
    ///     assert!((point[0] - 0.75f64.sqrt()).abs() < 1e-12 && (point[1] - 0.5).abs() < 1e-12);
    /// }
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless both curves are planar; [`Error::InvalidArgument`] for a bad
    /// tolerance; [`Error::TooLarge`] if more than 2^20 sub-curve pairs would be examined.
    pub fn intersect(&self, other: &QueryCurve, tolerance: f64) -> Result<Vec<CurveIntersection>> {
        check_tolerance(
            What::of(Arg::Tolerance, "intersection tolerance"),
            tolerance,
        )?;
        if self.dim != 2 || other.dim != 2 {
            if self.dim != other.dim {
                return Err(Error::Dimension {
                    what: "curves for an intersection".into(),
                    expected: self.dim,
                    got: other.dim,
                });
            }
            let solutions = self.space_solutions(other, tolerance)?;
            return Ok(self.assemble(other, solutions, tolerance));
        }
        let (na, nb, scale) = self.planar_frame(other);
        let tol = tolerance / scale;
        let boxes = |n: &PlaneNets| -> Vec<[f64; 4]> {
            (0..n.piece_count())
                .map(|k| super::planar::net_box(n.piece(k)))
                .collect()
        };
        let pairs = overlapping_pairs(&boxes(&na), &boxes(&nb), tol, false);
        let mut search = Search::new(&na, &nb, tol);
        let subs: Vec<(Sub, Sub)> = pairs
            .into_iter()
            .map(|(i, j)| (search.piece(false, i), search.piece(true, j)))
            .collect();
        let raw = search.run(subs)?;
        // a crossing is transversal when the first-order gap at the probes, |A'|·h·sin θ, is
        // ten times the tolerance (a thousand times what the probes test for)
        let h = PROBE * (self.domain().1 - self.domain().0);
        let solutions = raw
            .into_iter()
            .map(|r: Raw| {
                let (a0, a1) = self.spans[r.ka];
                let speed = r.speed_a / (a1 - a0) * scale;
                let transversal = speed * h * r.sin >= 10.0 * tolerance;
                (
                    self.global(r.ka, r.s),
                    other.global(r.kb, r.u),
                    r.gap,
                    transversal,
                )
            })
            .collect();
        Ok(self.assemble(other, solutions, tolerance))
    }

    /// Self-intersections of a planar curve: each point where two different parameters meet,
    /// as [`CurveIntersection::Point`] with `t_a < t_b` (and overlaps of the curve with itself
    /// as intervals). Pieces whose hodograph does not lie in an open half-plane (which may loop)
    /// are halved until it does, so every loop is found; the shared ends of consecutive
    /// sub-curves, and a closed curve's start and end, are not intersections.
    ///
    /// # Errors
    /// As [`QueryCurve::intersect`].
    pub fn self_intersections(&self, tolerance: f64) -> Result<Vec<CurveIntersection>> {
        self.check_planar(self)?;
        check_tolerance(
            What::of(Arg::Tolerance, "intersection tolerance"),
            tolerance,
        )?;
        let (na, _, scale) = self.planar_frame(self);
        let tol = tolerance / scale;
        let mut search = Search::new(&na, &na, tol);
        let mut subs = Vec::new();
        for k in 0..self.piece_count() {
            let mut stack = vec![(search.piece(false, k), 0_u32)];
            let mut done = Vec::new();
            while let Some((s, depth)) = stack.pop() {
                if depth >= 12 || Search::turns_less_than_pi(&s) {
                    done.push(s);
                } else {
                    let (l, r) = search.halve(s);
                    stack.push((r, depth + 1));
                    stack.push((l, depth + 1));
                }
            }
            subs.extend(done);
        }
        let boxes: Vec<[f64; 4]> = subs.iter().map(Search::sub_box).collect();
        let copy = |x: &Sub| Sub {
            k: x.k,
            s: x.s,
            net: x.net.clone(),
        };
        let pairs: Vec<(Sub, Sub)> = overlapping_pairs(&boxes, &boxes, tol, true)
            .into_iter()
            .map(|(i, j)| (copy(&subs[i]), copy(&subs[j])))
            .collect();
        let raw = search.run(pairs)?;
        let (lo, hi) = self.domain();
        let closed = dist(&self.point(lo)?, &self.point(hi)?) <= tolerance;
        let span = hi - lo;
        let keep = |&(ta, tb, _): &(f64, f64, f64)| {
            // a meeting of neighbouring parameters is the curve itself, not a crossing
            let (ta, tb) = (ta.min(tb), ta.max(tb));
            let trivial = tb - ta <= 1e-9 * span
                || (closed && ta - lo <= 1e-9 * span && hi - tb <= 1e-9 * span);
            !trivial
        };
        let mut raw: Vec<(f64, f64, f64)> = raw
            .into_iter()
            .map(|r| (self.global(r.ka, r.s), self.global(r.kb, r.u), r.gap))
            .filter(|x| keep(x))
            .map(|(ta, tb, g)| (ta.min(tb), ta.max(tb), g))
            .collect();
        // one answer per crossing: solutions from several sub-curve pairs that meet at the same
        // pair of parameters (the gap to the curve itself cannot group them, it is zero)
        raw.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
        let mut out: Vec<(f64, f64, f64)> = Vec::new();
        for r in raw {
            if let Some(o) = out
                .iter_mut()
                .find(|o| (o.0 - r.0).abs() <= 1e-6 * span && (o.1 - r.1).abs() <= 1e-6 * span)
            {
                if r.2 < o.2 {
                    *o = r;
                }
                continue;
            }
            out.push(r);
        }
        // transversal as for two curves (the first-order gap at the probes); a contact of the
        // curve with itself is named tangent, of order 1 (its order is not measured)
        let h = PROBE * span;
        let mut scratch = Vec::new();
        Ok(out
            .into_iter()
            .map(|(t_a, t_b, _)| {
                let a = self.eval_global(t_a, 1, &mut scratch);
                let b = self.eval_global(t_b, 1, &mut scratch);
                let (da, db) = (&a[2..4], &b[2..4]);
                let (la, lb) = (dot(da, da).sqrt(), dot(db, db).sqrt());
                let sin = ((da[0] * db[1] - da[1] * db[0]) / (la * lb)).abs();
                let contact = if la * h * sin >= 10.0 * tolerance {
                    Contact::Crossing
                } else {
                    Contact::Tangent { order: 1 }
                };
                CurveIntersection::Point {
                    t_a,
                    t_b,
                    point: a[..2].to_vec(),
                    contact,
                }
            })
            .collect())
    }

    fn check_planar(&self, other: &QueryCurve) -> Result<()> {
        for c in [self, other] {
            if c.dim != 2 {
                return Err(Error::Dimension {
                    what: "curves for a planar intersection".into(),
                    expected: 2,
                    got: c.dim,
                });
            }
        }
        Ok(())
    }

    /// Groups solutions `(t_a, t_b, gap, transversal)` into answers
    /// (`docs/theory/queries.md#kinds-of-contact`). Sorted by `t_a`, neighbours are joined when
    /// they are the same crossing (both transversal and their points within `tolerance`) or,
    /// when either is not transversal, when the curve between them stays within `tolerance` of
    /// `other` (its middle is projected). A group of transversal solutions is one
    /// [`Contact::Crossing`] (or [`Contact::End`]) at its least gap. Any other group, and a
    /// single solution whose gap stays below `tolerance / 100` at the probes either side of it,
    /// is one contact refined from its least-gap solution when the stretch within the tolerance
    /// about it is short (bracketed by doubling steps inside the domain, clear of the other
    /// groups, and not within `tolerance / 100` across: no overlap); otherwise it is grown to
    /// where the gap exceeds the tolerance: an overlap if the gap stays below
    /// `tolerance / 100` across it (its ends put on the curves' end points they are at), otherwise
    /// a contact at its least gap, refined and named by [`QueryCurve::classify_contact`]. A
    /// transversal crossing (angle `θ` between the tangents) needs no probe: the gap there is
    /// `|A'|·h·sin θ` to first order, which the caller has found to be at least
    /// `1000·tolerance / 100`.
    pub(super) fn assemble(
        &self,
        other: &QueryCurve,
        mut raw: Vec<Solution>,
        tolerance: f64,
    ) -> Vec<CurveIntersection> {
        raw.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
        let (lo, hi) = self.domain();
        // the gap at `t` (the distance to `other`, by its global projection) and the foot's
        // parameter there; infinite (and 0) outside the domain or where the projection fails.
        // The projections reuse one set of buffers.
        let projection =
            std::cell::RefCell::new((ProjectScratch::default(), Vec::new(), vec![0.0; self.dim]));
        let gap = |t: f64| -> (f64, f64) {
            if !(t >= lo && t <= hi) {
                return (f64::INFINITY, 0.0);
            }
            let (w, scratch, p) = &mut *projection.borrow_mut();
            self.eval_global_into(t, 0, scratch, p);
            match other.project_reusing(p, w) {
                Ok((u, d)) => (d, u),
                Err(_) => (f64::INFINITY, 0.0),
            }
        };
        // whether the gap at `t` is within `limit`: first from the foot point near `u` (an upper
        // bound of the gap, so a yes is final), then from a lower bound of the distance to
        // `other`'s pieces (so a no is final), else by the global projection; with the foot's
        // parameter, to start the next one from
        let scratch = std::cell::RefCell::new((Vec::new(), Vec::new()));
        let within = |t: f64, u: f64, limit: f64| -> (bool, f64) {
            let (d, u) = self.near_gap(other, t, u, limit, &mut scratch.borrow_mut());
            if d <= limit {
                return (true, u);
            }
            if !(t >= lo && t <= hi) {
                return (false, u);
            }
            {
                let (w, scratch, p) = &mut *projection.borrow_mut();
                self.eval_global_into(t, 0, scratch, p);
                if other.farther_than(p, limit, w) {
                    return (false, u);
                }
            }
            let (d, v) = gap(t);
            (d <= limit, if d.is_finite() { v } else { u })
        };
        let at = |t: f64| self.point(t).unwrap_or_default();
        // the answers of one contact refined and classified from `(ta, tb)`
        let contact_points = |ta: f64, tb: f64| {
            self.classify_contact(other, ta, tb, tolerance)
                .into_iter()
                .map(|(t_a, t_b, contact)| CurveIntersection::Point {
                    t_a,
                    t_b,
                    point: at(t_a),
                    contact,
                })
        };
        let on_b = |t: f64| other.point(t).unwrap_or_default();
        // the branches: a solution joins the latest group whose last solution is the same
        // crossing, or runs along the same stretch of both curves (the middles of the two steps,
        // on each curve, within a quarter of the step, and the first curve between them within
        // the tolerance of `other`), so that a crossing inside an overlap (a loop of a curve
        // overlapping itself) stays apart
        let mut groups: Vec<Vec<Solution>> = Vec::new();
        for r in raw {
            let found = groups.iter().rposition(|g| {
                let last = g[g.len() - 1];
                if last.3 && r.3 {
                    return dist(&at(last.0), &at(r.0)) <= tolerance;
                }
                let (ma, mb) = (at(0.5 * (last.0 + r.0)), on_b(0.5 * (last.1 + r.1)));
                let step = dist(&at(last.0), &at(r.0)) + dist(&on_b(last.1), &on_b(r.1));
                dist(&ma, &mb) <= 0.125 * step + tolerance
                    && within(0.5 * (last.0 + r.0), 0.5 * (last.1 + r.1), tolerance).0
            });
            match found {
                Some(i) => groups[i].push(r),
                None => groups.push(vec![r]),
            }
        }
        groups.sort_by(|x, y| x[0].0.total_cmp(&y[0].0));
        let mut out = Vec::new();
        for (gi, g) in groups.iter().enumerate() {
            let (mut a0, mut a1) = (g[0].0, g[g.len() - 1].0);
            let transversal = g.iter().all(|r| r.3);
            // a single solution may still sit in an overlap or a tangential contact: the gap
            // stays tiny a little way to either side
            let probe = || {
                let h = PROBE * (hi - lo);
                [(a0 - h, g[0].1), (a1 + h, g[g.len() - 1].1)]
                    .iter()
                    .filter(|(t, _)| *t >= lo && *t <= hi)
                    .all(|&(t, u)| within(t, u, tolerance / 100.0).0)
            };
            let best = g.iter().fold(g[0], |b, r| if r.2 < b.2 { *r } else { b });
            // the stretch about a group of contact solutions where the gap is within the
            // tolerance, bracketed by steps doubling from the probe's (to 1% of the domain at
            // most): when it ends on both sides inside the domain, clear of the other groups, and
            // the gap does not stay within a hundredth of the tolerance across it (no overlap),
            // the group is one contact, refined from its least-gap solution as a lone contact
            // is, without the growth by bisection and the golden-section search below (some two
            // hundred projections)
            let short_contact = || {
                let span = hi - lo;
                // each step's foot point starts from the last one's
                let side = |from: f64, mut u: f64, dir: f64| {
                    let mut h = PROBE * span;
                    while h <= 1e-2 * span {
                        let t = from + dir * h;
                        if t < lo || t > hi {
                            return None;
                        }
                        let (ok, v) = within(t, u, tolerance);
                        if !ok {
                            return Some((t, v));
                        }
                        u = v;
                        h *= 2.0;
                    }
                    None
                };
                let (Some((l, ul)), Some((r, ur))) =
                    (side(a0, g[0].1, -1.0), side(a1, g[g.len() - 1].1, 1.0))
                else {
                    return false;
                };
                let clear = groups
                    .iter()
                    .enumerate()
                    .all(|(i, n)| i == gi || n.iter().all(|x| x.0 < l || x.0 > r));
                clear
                    && !(1..10).all(|i| {
                        let f = f64::from(i) / 10.0;
                        within(l + (r - l) * f, ul + (ur - ul) * f, tolerance / 100.0).0
                    })
            };
            if !transversal && ((g.len() > 1 && a1 > a0) || probe()) {
                if short_contact() {
                    out.extend(contact_points(best.0, best.1));
                    continue;
                }
                // grow to where the gap exceeds the tolerance (bisection, 60 steps each side),
                // one other group at a time: an overlap that reaches another group (a crossing
                // of another stretch of a curve inside the overlap) goes on past it
                let others = groups.iter().enumerate().filter(|(i, _)| *i != gi);
                let mut left: Vec<f64> = others
                    .clone()
                    .map(|(_, n)| n[n.len() - 1].0)
                    .filter(|t| *t < a0)
                    .collect();
                left.sort_by(|x, y| y.total_cmp(x));
                let mut right: Vec<f64> = others.map(|(_, n)| n[0].0).filter(|t| *t > a1).collect();
                right.sort_by(f64::total_cmp);
                let ok = |t: f64| gap(t).0 <= tolerance;
                a0 = grow_past(a0, &left, lo, ok);
                a1 = grow_past(a1, &right, hi, ok);
                let coincide = (1..10).all(|i| {
                    let t = a0 + (a1 - a0) * f64::from(i) / 10.0;
                    gap(t).0 <= tolerance / 100.0
                });
                if coincide {
                    let (a0, b0) = self.overlap_end(other, a0, tolerance);
                    let (a1, b1) = self.overlap_end(other, a1, tolerance);
                    out.push(CurveIntersection::Overlap {
                        a: (a0, a1),
                        b: (b0, b1),
                    });
                    continue;
                }
                // one contact: the least gap, by golden-section search on [a0, a1] (80 steps),
                // then refined on the tangency system
                let t = golden_min(a0, a1, |t| gap(t).0);
                let (_, u) = gap(t);
                out.extend(contact_points(t, u));
                continue;
            }
            let point = at(best.0);
            let contact = if transversal {
                if self.at_an_end(other, &point, tolerance) {
                    Contact::End
                } else {
                    Contact::Crossing
                }
            } else {
                // a lone contact whose gap grows at once beside it: named as a contact
                out.extend(contact_points(best.0, best.1));
                continue;
            };
            out.push(CurveIntersection::Point {
                t_a: best.0,
                t_b: best.1,
                point,
                contact,
            });
        }
        out.sort_by(|x, y| first_t(x).total_cmp(&first_t(y)));
        merge_overlaps(out, self.domain(), other.domain())
    }

    /// An upper bound of the gap from this curve at `t` to `other`, and where on `other` it is
    /// measured: the distance to the foot point of `A(t)` on `other` found by Newton's method on
    /// `(B(u) − A(t))·B'(u) = 0` from `u` (at most 6 steps, clamped to `other`'s domain; the
    /// nearest of its iterates). Any point of `other` bounds the gap from above, so a bound within
    /// a limit needs no global projection; the steps stop at the first iterate within `limit`
    /// (the caller's question is answered). Infinite for `t` outside the domain.
    fn near_gap(
        &self,
        other: &QueryCurve,
        t: f64,
        u: f64,
        limit: f64,
        bufs: &mut (Vec<f64>, Vec<f64>),
    ) -> (f64, f64) {
        let (lo, hi) = self.domain();
        let (blo, bhi) = other.domain();
        if !(t >= lo && t <= hi && u.is_finite()) {
            return (f64::INFINITY, u);
        }
        let n = other.dim;
        // the point of this curve, then other's point and derivatives, in `buf` (no allocation)
        let (scratch, buf) = (&mut bufs.0, &mut bufs.1);
        buf.clear();
        buf.resize(4 * n.max(self.dim), 0.0);
        let (p, b) = buf.split_at_mut(n.max(self.dim));
        let k = self.piece_of(t);
        self.eval_local(k, self.local(k, t), 0, scratch, b);
        for d in 0..n {
            p[d] = self.centre[d] + self.scale * b[d];
        }
        let mut u = u.clamp(blo, bhi);
        let mut best = (f64::INFINITY, u);
        for _ in 0..6 {
            let k = other.piece_of(u);
            other.eval_local(k, other.local(k, u), 2, scratch, b);
            let h = other.spans[k].1 - other.spans[k].0;
            let (mut f, mut fp, mut sq) = (0.0, 0.0, 0.0);
            for i in 0..n {
                let e = other.centre[i] + other.scale * b[i] - p[i];
                let d1 = other.scale * b[n + i] / h;
                let d2 = other.scale * b[2 * n + i] / (h * h);
                sq += e * e;
                f += e * d1;
                fp += d1 * d1 + e * d2;
            }
            let d = sq.sqrt();
            if d < best.0 {
                best = (d, u);
            }
            if d <= limit || !(fp > 0.0) {
                break;
            }
            let next = (u - f / fp).clamp(blo, bhi);
            if next == u {
                break;
            }
            u = next;
        }
        best
    }

    /// An end of an overlap, found by bisection at `t` on this curve: put on the end point of
    /// either curve it is at (within the tolerance along the curve), so that it is exact to
    /// rounding rather than to the tolerance; returns `(t_a, t_b)`.
    fn overlap_end(&self, other: &QueryCurve, t: f64, tolerance: f64) -> (f64, f64) {
        let p = self.point(t).unwrap_or_default();
        let (lo, hi) = self.domain();
        let mut best: Option<(f64, f64, f64)> = None; // (distance, t_a, t_b)
        let mut offer = |d: f64, ta: f64, tb: f64| {
            if d <= 2.0 * tolerance && best.is_none_or(|b| d < b.0) {
                best = Some((d, ta, tb));
            }
        };
        for e in [lo, hi] {
            if let Ok(q) = self.point(e) {
                if let Ok(pr) = other.project(&q) {
                    offer(dist(&p, &q), e, pr.t);
                }
            }
        }
        let (blo, bhi) = other.domain();
        for e in [blo, bhi] {
            if let Ok(q) = other.point(e) {
                if let Ok(pr) = self.project(&q) {
                    offer(dist(&p, &q), pr.t, e);
                }
            }
        }
        match best {
            Some((_, ta, tb)) => (ta, tb),
            None => (t, other.project(&p).map_or(f64::NAN, |pr| pr.t)),
        }
    }
}

/// Overlaps from several groups joined: two whose intervals meet (within `10⁻⁹` of the domain)
/// on both curves are one; a point inside an overlap on the first curve whose parameter on the
/// second is within 1% of that domain from the overlap's (linearly interpolated) is a part of it
/// and dropped (a crossing of another branch, such as a loop's, stays).
fn merge_overlaps(
    answers: Vec<CurveIntersection>,
    (lo, hi): (f64, f64),
    (blo, bhi): (f64, f64),
) -> Vec<CurveIntersection> {
    let (ea, eb) = (1e-9 * (hi - lo), 1e-9 * (bhi - blo));
    let meets = |x: (f64, f64), y: (f64, f64), e: f64| {
        x.0.min(x.1) <= y.0.max(y.1) + e && y.0.min(y.1) <= x.0.max(x.1) + e
    };
    let mut overlaps: Vec<((f64, f64), (f64, f64))> = Vec::new();
    for x in &answers {
        if let CurveIntersection::Overlap { a, b } = x {
            if let Some(o) = overlaps
                .iter_mut()
                .find(|o| meets(o.0, *a, ea) && meets(o.1, *b, eb))
            {
                // sorted by the start on the first curve: the later one extends the end
                if a.1 > o.0 .1 {
                    o.0 .1 = a.1;
                    o.1 .1 = b.1;
                }
                continue;
            }
            overlaps.push((*a, *b));
        }
    }
    let inside = |t_a: f64, t_b: f64| {
        overlaps.iter().any(|(a, b)| {
            if !(t_a >= a.0 - ea && t_a <= a.1 + ea) {
                return false;
            }
            let f = if a.1 > a.0 {
                (t_a - a.0) / (a.1 - a.0)
            } else {
                0.0
            };
            (t_b - (b.0 + f * (b.1 - b.0))).abs() <= 1e-2 * (bhi - blo)
        })
    };
    let mut out: Vec<CurveIntersection> = answers
        .into_iter()
        .filter(|x| match x {
            CurveIntersection::Point { t_a, t_b, .. } => !inside(*t_a, *t_b),
            CurveIntersection::Overlap { .. } => false,
        })
        .collect();
    out.extend(
        overlaps
            .into_iter()
            .map(|(a, b)| CurveIntersection::Overlap { a, b }),
    );
    out.sort_by(|x, y| first_t(x).total_cmp(&first_t(y)));
    out
}

/// The first parameter of an answer on the first curve (for sorting).
fn first_t(x: &CurveIntersection) -> f64 {
    match x {
        CurveIntersection::Point { t_a, .. } => *t_a,
        CurveIntersection::Overlap { a, .. } => a.0.min(a.1),
    }
}

/// Moves `from` towards `limit` while `ok` holds: steps doubling from `1e-12·|limit − from|`
/// (at most 64) find the first point where it fails (when they reach the limit, 32 equal steps
/// from the last good point to it), then bisection (60 steps) the last point where it holds.
/// Returns `from` when it fails at once.
pub(super) fn grow(from: f64, limit: f64, ok: impl Fn(f64) -> bool) -> f64 {
    let span = limit - from;
    if span == 0.0 {
        return from;
    }
    let mut good = from;
    let mut h = 1e-12 * span;
    let mut bad = limit;
    let mut reached = true;
    for _ in 0..64 {
        let t = from + h;
        if (span > 0.0 && t >= limit) || (span < 0.0 && t <= limit) {
            break;
        }
        if ok(t) {
            good = t;
            h *= 2.0;
        } else {
            bad = t;
            reached = false;
            break;
        }
    }
    if reached {
        // the last step reached the limit: the limit holds only if the stretch before it does
        // (a meeting of another branch at the limit is not this one), checked at 32 points
        let first_bad = (1..=32)
            .map(|i| good + (limit - good) * f64::from(i) / 32.0)
            .find(|&t| !ok(t));
        match first_bad {
            None => return limit,
            Some(t) => bad = t,
        }
    }
    for _ in 0..60 {
        let m = 0.5 * (good + bad);
        if m == good || m == bad {
            break;
        }
        if ok(m) {
            good = m;
        } else {
            bad = m;
        }
    }
    good
}

/// [`grow`] from `from` towards `end` through the `stops` in between (in order of distance):
/// past each stop that the stretch reaches in full, on to the next.
fn grow_past(from: f64, stops: &[f64], end: f64, ok: impl Fn(f64) -> bool) -> f64 {
    let mut t = from;
    for &limit in stops.iter().chain([&end]) {
        t = grow(t, limit, &ok);
        if t != limit {
            break;
        }
    }
    t
}

/// Minimum of `f` on `[a, b]` by golden-section search, 80 steps.
pub(super) fn golden_min(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (a, b);
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..80 {
        if fc <= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
        if b - a <= 1e-16 * (1.0 + a.abs()) {
            break;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::super::super::pieces::dist;
    use super::*;
    use crate::query::PlaneIntersection;
    use crate::{BSplineCurve, NurbsCurve, Points};

    fn line(a: [f64; 2], b: [f64; 2]) -> QueryCurve {
        let c = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            Points::from_2d(&[a, b]).unwrap(),
        )
        .unwrap();
        QueryCurve::from_bspline(&c).unwrap()
    }

    fn circle(r: f64) -> QueryCurve {
        QueryCurve::from_nurbs(
            &NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], r).unwrap(),
        )
        .unwrap()
    }

    #[test]
    fn tangent_line_gives_one_point() {
        let hits = circle(1.0)
            .intersect(&line([-2.0, 1.0], [2.0, 1.0]), 1e-9)
            .unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        match &hits[0] {
            CurveIntersection::Point { point, .. } => {
                assert!(
                    point[0].abs() < 1e-4 && (point[1] - 1.0).abs() < 1e-8,
                    "{point:?}"
                );
            }
            CurveIntersection::Overlap { .. } => panic!("tangency reported as overlap"),
        }
    }

    #[test]
    fn overlapping_lines_give_an_interval() {
        let hits = line([0.0, 0.0], [2.0, 0.0])
            .intersect(&line([1.0, 0.0], [3.0, 0.0]), 1e-9)
            .unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        match hits[0] {
            CurveIntersection::Overlap { a, b } => {
                assert!(
                    (a.0 - 0.5).abs() < 1e-9 && (a.1 - 1.0).abs() < 1e-12,
                    "{a:?}"
                );
                assert!(b.0.abs() < 1e-9 && (b.1 - 0.5).abs() < 1e-9, "{b:?}");
            }
            CurveIntersection::Point { .. } => panic!("overlap reported as a point"),
        }
    }

    #[test]
    fn crossing_points_lie_on_both() {
        let a = circle(1.0);
        let b = circle(1.2);
        assert!(a.intersect(&b, 1e-9).unwrap().is_empty(), "concentric");
        let shifted = QueryCurve::from_nurbs(
            &NurbsCurve::circle(&[1.0, 0.3], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap(),
        )
        .unwrap();
        let hits = a.intersect(&shifted, 1e-10).unwrap();
        assert_eq!(hits.len(), 2, "{hits:?}");
        for h in hits {
            let CurveIntersection::Point {
                t_a, t_b, point, ..
            } = h
            else {
                panic!("not a point")
            };
            assert!(dist(&a.point(t_a).unwrap(), &point) < 1e-12, "on a");
            assert!(dist(&shifted.point(t_b).unwrap(), &point) < 1e-10, "on b");
        }
    }

    #[test]
    fn loop_of_a_cubic() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [3.0, 2.0], [-1.0, 2.0], [2.0, 0.0]]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let hits = q.self_intersections(1e-10).unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        let CurveIntersection::Point { t_a, t_b, .. } = hits[0] else {
            panic!("not a point")
        };
        assert!(t_a < t_b, "ordered");
        assert!(
            dist(&q.point(t_a).unwrap(), &q.point(t_b).unwrap()) < 1e-9,
            "same point"
        );
        // a circle does not cross itself
        assert!(
            circle(1.0).self_intersections(1e-10).unwrap().is_empty(),
            "circle"
        );
    }

    fn bezier(pts: &[[f64; 2]]) -> QueryCurve {
        let n = pts.len();
        let mut knots = vec![0.0; n];
        knots.extend(vec![1.0; n]);
        QueryCurve::from_bspline(
            &BSplineCurve::new(n - 1, knots, Points::from_2d(pts).unwrap()).unwrap(),
        )
        .unwrap()
    }

    /// The roots of `y(t) = c` by the curve–plane root finder, as `(t, point)`.
    fn height_roots(curve: &QueryCurve, c: f64) -> Vec<(f64, Vec<f64>)> {
        curve
            .intersect_plane(&[0.0, c], &[0.0, 1.0])
            .unwrap()
            .into_iter()
            .map(|h| match h {
                PlaneIntersection::Point { t, point, .. } => (t, point),
                PlaneIntersection::Overlap { .. } => panic!("an overlap with y = {c}"),
            })
            .collect()
    }

    fn points(hits: &[CurveIntersection]) -> Vec<(f64, f64, Vec<f64>)> {
        hits.iter()
            .map(|h| match h {
                CurveIntersection::Point {
                    t_a, t_b, point, ..
                } => (*t_a, *t_b, point.clone()),
                CurveIntersection::Overlap { .. } => {
                    panic!("overlap where a point is expected: {hits:?}")
                }
            })
            .collect()
    }

    #[test]
    fn crossing_at_shared_piece_ends_is_one_answer() {
        // both diagonals of the square [0, 2]² in two pieces each: the crossing (1, 1) is the
        // end of two pieces on each curve, so four piece pairs reach it
        let two = |a: [f64; 2], b: [f64; 2]| {
            let c = BSplineCurve::new(
                1,
                vec![0.0, 0.0, 0.5, 1.0, 1.0],
                Points::from_2d(&[a, [1.0, 1.0], b]).unwrap(),
            )
            .unwrap();
            QueryCurve::from_bspline(&c).unwrap()
        };
        let hits = points(
            &two([0.0, 0.0], [2.0, 2.0])
                .intersect(&two([0.0, 2.0], [2.0, 0.0]), 1e-9)
                .unwrap(),
        );
        assert_eq!(hits.len(), 1, "{hits:?}");
        let (t_a, t_b, p) = &hits[0];
        assert!(
            (t_a - 0.5).abs() < 1e-15 && (t_b - 0.5).abs() < 1e-15,
            "{hits:?}"
        );
        assert!(
            (p[0] - 1.0).abs() < 1e-15 && (p[1] - 1.0).abs() < 1e-15,
            "{p:?}"
        );
    }

    #[test]
    fn touching_parabolas_give_one_point() {
        // y = x² and y = −x² touch at the origin (the gap is 2x²)
        let up = bezier(&[[-1.0, 1.0], [0.0, -1.0], [1.0, 1.0]]);
        let down = bezier(&[[-1.0, -1.0], [0.0, 1.0], [1.0, -1.0]]);
        for tol in [1e-9, 1e-6] {
            let hits = points(&up.intersect(&down, tol).unwrap());
            assert_eq!(hits.len(), 1, "tol {tol}: {hits:?}");
            let (_, _, p) = &hits[0];
            // within the contact the gap 2x² is at most the tolerance
            assert!(
                2.0 * p[0] * p[0] <= tol && p[1].abs() <= tol,
                "tol {tol}: {p:?}"
            );
        }
    }

    #[test]
    fn triple_root_is_one_point() {
        // y = x³ on [−1, 1] (x linear in the parameter) against the x axis: a crossing of
        // multiplicity 3, with parallel tangents
        let cubic = bezier(&[
            [-1.0, -1.0],
            [-1.0 / 3.0, 1.0],
            [1.0 / 3.0, -1.0],
            [1.0, 1.0],
        ]);
        let axis = bezier(&[[-2.0, 0.0], [2.0, 0.0]]);
        let hits = points(&cubic.intersect(&axis, 1e-9).unwrap());
        assert_eq!(hits.len(), 1, "{hits:?}");
        let (t_a, _, p) = &hits[0];
        assert!(p[0].abs().powi(3) <= 1e-9 && p[1].abs() <= 1e-9, "{p:?}");
        assert!((t_a - 0.5).abs() <= 1e-3, "{t_a}");
    }

    #[test]
    fn parabola_arcs_overlap_on_their_common_part() {
        // y = x² for x ∈ [−1, 1] and for x ∈ [0, 2]: they coincide for x ∈ [0, 1]
        let a = bezier(&[[-1.0, 1.0], [0.0, -1.0], [1.0, 1.0]]);
        let b = bezier(&[[0.0, 0.0], [1.0, 0.0], [2.0, 4.0]]);
        let hits = a.intersect(&b, 1e-9).unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        let CurveIntersection::Overlap { a: ia, b: ib } = hits[0] else {
            panic!("a point where the arcs overlap: {hits:?}")
        };
        assert!(
            (ia.0 - 0.5).abs() < 1e-6 && (ia.1 - 1.0).abs() < 1e-12,
            "{ia:?}"
        );
        assert!(ib.0.abs() < 1e-6 && (ib.1 - 0.5).abs() < 1e-6, "{ib:?}");
    }

    #[test]
    fn rational_crossings_are_exact() {
        // a unit circle and a circle of radius 1 about (1, 0) meet at (1/2, ±√3/2)
        let moved = QueryCurve::from_nurbs(
            &NurbsCurve::circle(&[1.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap(),
        )
        .unwrap();
        let hits = points(&circle(1.0).intersect(&moved, 1e-12).unwrap());
        assert_eq!(hits.len(), 2, "{hits:?}");
        let mut ys: Vec<f64> = hits.iter().map(|h| h.2[1]).collect();
        ys.sort_by(f64::total_cmp);
        for (h, y) in hits.iter().zip([0.75f64.sqrt(), -(0.75f64.sqrt())]) {
            assert!((h.2[0] - 0.5).abs() < 1e-14, "{h:?}");
            assert!(ys.iter().any(|v| (v - y).abs() < 1e-14), "{ys:?} lacks {y}");
        }
    }

    /// The crossings of the uniform cubic B-spline with control points `ctrl` and the line
    /// `y = c`, against the roots of its height (the curve–plane root finder): `expected` of
    /// each, the same parameters and points.
    fn line_crossings_are_the_roots(ctrl: &[[f64; 2]], c: f64, expected: usize) {
        let n = ctrl.len();
        let mut knots = vec![0.0; 4];
        knots.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
        knots.extend([1.0; 4]);
        let curve = QueryCurve::from_bspline(
            &BSplineCurve::new(3, knots, Points::from_2d(ctrl).unwrap()).unwrap(),
        )
        .unwrap();
        let roots = height_roots(&curve, c);
        assert_eq!(roots.len(), expected, "{roots:?}");
        let line = bezier(&[[-30.0, c], [30.0, c]]);
        let hits = points(&curve.intersect(&line, 1e-9).unwrap());
        assert_eq!(hits.len(), expected, "{hits:?}");
        for ((t, _, p), (r, q)) in hits.iter().zip(&roots) {
            assert!(
                (t - r).abs() <= 1e-9 && dist(p, q) <= 1e-9,
                "{t} vs {r}: {p:?}"
            );
        }
    }

    /// A shallow dip through a line (found by the property test below): the piece is flat to
    /// 1% of its size, yet crosses `y = c` twice, 0.0075 apart in the parameter; each crossing
    /// is found.
    #[test]
    fn a_flat_piece_that_crosses_a_line_twice_gives_both_crossings() {
        let ctrl = [
            [0.0, 0.0],
            [-7.939298392427483, 8.475966024050374],
            [0.0, 0.18057993752048637],
            [7.364495452110797, 8.772201555088136],
            [0.0, 0.0],
            [0.0, 0.0],
        ];
        line_crossings_are_the_roots(&ctrl, 3.592_837_653_954_960_7, 4);
    }

    /// A shallow crossing near a piece's end (found by the property test below): the curve runs
    /// within 0.002 of `y = c` before it crosses at 2.5e-4 rad, so Newton's method from the
    /// flat pair's chords starts far off and stalls at the end; the pair is halved again and
    /// the crossing found.
    #[test]
    fn a_shallow_crossing_near_an_end_is_found() {
        let ctrl = [
            [7.422339813839777, -1.3923007278852106],
            [-6.360489991617422, -1.563441890391513],
            [0.0, 0.0],
            [0.0, 0.0],
        ];
        line_crossings_are_the_roots(&ctrl, -1.390_700_982_248_104, 1);
    }

    /// Two crossings of one piece 0.09 apart in its parameter (found by the property test
    /// below): Newton's method from a pair around the second converges to the first, outside
    /// the pair's intervals; that is not the pair's answer, and the second is found.
    #[test]
    fn a_pair_does_not_answer_with_a_neighbours_crossing() {
        let ctrl = [
            [0.0, 0.0],
            [0.0, 0.0],
            [0.0, 7.233800935733193],
            [-8.383876178193463, 2.875942544947581],
            [0.0, 5.25604298076829],
            [0.0, -2.976700161953739],
            [0.0, 0.0],
        ];
        line_crossings_are_the_roots(&ctrl, 3.911_905_096_333_211_6, 4);
    }

    proptest::proptest! {
        /// Every transversal root of `y(t) = c` (found by the curve–plane root finder, an
        /// independent method) is one crossing with the line `y = c`, and nothing else is found.
        #[test]
        fn crossings_with_a_line_are_the_roots_of_the_height(
            ctrl in proptest::collection::vec(proptest::array::uniform2(-10.0..10.0_f64), 4..9),
            c in -8.0..8.0_f64,
        ) {
            let n = ctrl.len();
            let mut knots = vec![0.0; 4];
            knots.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
            knots.extend([1.0; 4]);
            let curve = QueryCurve::from_bspline(
                &BSplineCurve::new(3, knots, Points::from_2d(&ctrl).unwrap()).unwrap(),
            )
            .unwrap();
            let roots = height_roots(&curve, c);
            // only clear crossings: slope of y well away from zero, roots apart
            let slope = |t: f64| {
                let h = 1e-7;
                let (a, b) = (curve.point((t - h).max(0.0)).unwrap(), curve.point((t + h).min(1.0)).unwrap());
                (b[1] - a[1]) / (2.0 * h)
            };
            proptest::prop_assume!(roots.iter().all(|(t, _)| slope(*t).abs() > 1e-2));
            proptest::prop_assume!(roots.windows(2).all(|w| w[1].0 - w[0].0 > 1e-6));
            let line = bezier(&[[-30.0, c], [30.0, c]]);
            let hits = points(&curve.intersect(&line, 1e-9).unwrap());
            proptest::prop_assert_eq!(hits.len(), roots.len(), "{:?} vs {:?}", hits, roots);
            for ((t, _, p), (r, _)) in hits.iter().zip(&roots) {
                proptest::prop_assert!((t - r).abs() <= 1e-9, "{} vs {}", t, r);
                proptest::prop_assert!((p[1] - c).abs() <= 1e-9, "{:?} off y = {}", p, c);
            }
        }
    }
}
