//! Knot insertion (P&T Algorithm A5.1, Boehm), knot refinement (A5.4, Oslo-type insertion of
//! many knots at once), splitting a curve at a parameter, and Bezier decomposition (the pieces
//! of A5.6) with its inverse, for B-spline curves. The curve is unchanged as a function; only
//! its representation gains knots.

use crate::curve::bezier::{BezierCurve, BezierSegment};
use crate::curve::bspline::BSplineCurve;
use crate::error::readable;
use crate::error::{check_finite, Error, Result, MAX_SCALARS};
use crate::knots::{check_gap, check_inserted_gap};
use crate::points::Points;
use crate::Arg;

impl BSplineCurve {
    /// Inserts the knot `t` `times` times by Boehm's algorithm (P&T §5.2, Algorithm A5.1):
    /// the curve is unchanged, it gains `times` control points, and each new control point is
    /// `Q_i = α_i P_i + (1 − α_i) P_{i−1}` with `α_i = (t − t_i)/(t_{i+p} − t_i)`. Works for
    /// unclamped knot vectors too, including at the ends of the domain. `times = 0` returns a
    /// copy. O((p + times)·p·dim + n·dim).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])?;
    /// let c = BSplineCurve::from_knot_vector(3, KnotVector::clamped_uniform(3, 4)?, ctrl)?;
    /// let d = c.insert_knot(0.5, 2)?;
    /// assert_eq!(d.knots().multiplicity(0.5), 2);
    /// assert_eq!(d.control_points().len(), 6);
    /// let (a, b) = (c.eval(0.3)?, d.eval(0.3)?);
    /// assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is outside the domain or NaN;
    /// [`Error::InvalidArgument`] if the multiplicity of `t` would exceed the degree `p` (so a
    /// degree-0 curve accepts no insertion).
    pub fn insert_knot(&self, t: f64, times: usize) -> Result<BSplineCurve> {
        let (min, max) = self.domain();
        if !(t >= min && t <= max) {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        if times == 0 {
            return Ok(self.clone());
        }
        check_inserted_gap(self.knots.as_slice(), t)?;
        let p = self.degree;
        let s = self.knots.multiplicity(t);
        let total = s.saturating_add(times);
        if total > p {
            let room = p.saturating_sub(s);
            // the fix: fewer insertions, or, where none is left, another knot or a higher degree
            let fix = match (room, p) {
                (0, 0) => "a curve of degree 0 takes no knot: elevate its degree first".to_string(),
                (0, _) => "it has the largest multiplicity already: insert another knot, or \
                           elevate the degree first"
                    .to_string(),
                _ => format!("insert it at most {room} times"),
            };
            return Err(Error::InvalidArgument {
                what: Arg::Times.into(),
                reason: format!(
                    "inserting {t} {times} times would give it multiplicity {total}, more than \
                     the degree {p}; {fix}",
                    t = readable(&t)
                ),
            });
        }
        Ok(self.insert_knot_unchecked(t, times, s))
    }

    /// Algorithm A5.1 for `t` in the domain with multiplicity `s` and `s + r ≤ p`.
    fn insert_knot_unchecked(&self, t: f64, r: usize, s: usize) -> BSplineCurve {
        let p = self.degree;
        let dim = self.dim();
        let u = self.knots.as_slice();
        let pc = self.control.as_slice();
        let n = self.control.len() - 1;
        debug_assert!(s + r <= p && r > 0, "A5.1 preconditions");
        // span k with u_k ≤ t < u_{k+1}, counted over the whole knot vector (not the domain), so
        // that the copies of t already present are u_{k−s+1} … u_k; t < u_m because s ≤ p
        let k = u.partition_point(|&x| x <= t) - 1;
        debug_assert!(k >= p && k - s <= n, "span inside the knot vector");
        let mut knots = Vec::with_capacity(u.len() + r);
        knots.extend_from_slice(&u[..=k]);
        knots.extend(std::iter::repeat_n(t, r));
        knots.extend_from_slice(&u[k + 1..]);
        let mut q = vec![0.0; (n + 1 + r) * dim];
        // unchanged points: P_0 … P_{k−p} and P_{k−s} … P_n (shifted by r)
        q[..(k - p + 1) * dim].copy_from_slice(&pc[..(k - p + 1) * dim]);
        q[(k - s + r) * dim..].copy_from_slice(&pc[(k - s) * dim..]);
        // rw: the p − s + 1 affected points P_{k−p} … P_{k−s}, updated in place
        let mut rw = pc[(k - p) * dim..(k - s + 1) * dim].to_vec();
        let mut l = k - p;
        for j in 1..=r {
            l = k - p + j;
            for i in 0..=(p - j - s) {
                let alpha = (t - u[l + i]) / (u[i + k + 1] - u[l + i]);
                for d in 0..dim {
                    rw[i * dim + d] =
                        alpha * rw[(i + 1) * dim + d] + (1.0 - alpha) * rw[i * dim + d];
                }
            }
            q[l * dim..(l + 1) * dim].copy_from_slice(&rw[..dim]);
            let last = k + r - j - s;
            q[last * dim..(last + 1) * dim]
                .copy_from_slice(&rw[(p - j - s) * dim..(p - j - s + 1) * dim]);
        }
        for i in (l + 1)..(k - s) {
            q[i * dim..(i + 1) * dim].copy_from_slice(&rw[(i - l) * dim..(i - l + 1) * dim]);
        }
        BSplineCurve::from_raw(p, knots, Points::from_raw(q, dim))
    }

    /// Knot refinement: inserts all the knots `x` (non-decreasing, inside the domain) at once by
    /// P&T Algorithm A5.4 (Boehm/Oslo); the curve is unchanged. `x` may repeat a value and may
    /// contain existing knots; an empty `x` returns a copy. O((n + r)·p·dim) for `r` new knots.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 3.0, 2.0])?;
    /// let c = BSplineCurve::from_knot_vector(2, KnotVector::clamped_uniform(2, 4)?, ctrl)?;
    /// let d = c.refine_knots(&[0.25, 0.5, 0.75])?;
    /// assert_eq!(d.control_points().len(), 7);
    /// assert!((c.eval(0.6)?[0] - d.eval(0.6)?[0]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::KnotsNotSorted`] if `x` decreases (lekalo never sorts your
    /// knots); [`Error::ParameterOutOfDomain`] for a knot outside the domain;
    /// [`Error::InvalidArgument`] if some knot's multiplicity would exceed the degree.
    pub fn refine_knots(&self, x: &[f64]) -> Result<BSplineCurve> {
        if x.is_empty() {
            return Ok(self.clone());
        }
        check_finite("new knots", x)?;
        if let Some(i) = (1..x.len()).find(|&i| x[i] < x[i - 1]) {
            return Err(Error::KnotsNotSorted {
                index: i,
                value: x[i],
                previous: x[i - 1],
            });
        }
        let (min, max) = self.domain();
        if let Some(&t) = x.iter().find(|&&t| !(t >= min && t <= max)) {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        for (i, &t) in x.iter().enumerate() {
            check_inserted_gap(self.knots.as_slice(), t)?;
            if i > 0 {
                check_gap(Arg::Knot, x[i - 1], t)?;
            }
        }
        let p = self.degree;
        let mut i = 0;
        while i < x.len() {
            let run = x[i..].iter().take_while(|&&v| v == x[i]).count();
            let total = self.knots.multiplicity(x[i]) + run;
            if total > p {
                return Err(Error::InvalidArgument {
                    what: "refinement knots".into(),
                    reason: format!(
                        "knot {} would get multiplicity {total}, more than the degree {p}",
                        readable(&x[i])
                    ),
                });
            }
            i += run;
        }
        let size = (self.control.len() + x.len()).saturating_mul(self.dim());
        if size > MAX_SCALARS {
            return Err(Error::TooLarge {
                what: "refined control points".into(),
                size,
                max: MAX_SCALARS,
            });
        }
        Ok(self.refine_unchecked(x))
    }

    /// Algorithm A5.4 for a validated, non-empty, sorted `x` inside the domain.
    fn refine_unchecked(&self, x: &[f64]) -> BSplineCurve {
        let p = self.degree;
        let dim = self.dim();
        let u = self.knots.as_slice();
        let pc = self.control.as_slice();
        let n = self.control.len() - 1;
        let m = n + p + 1;
        let r = x.len() - 1;
        let a = self.knots.span_unchecked(p, x[0]);
        let b = self.knots.span_unchecked(p, x[r]) + 1;
        let mut ub = vec![0.0; m + r + 2];
        let mut q = vec![0.0; (n + r + 2) * dim];
        // Q_0 … Q_{a−p} = P_0 … P_{a−p}; Q_{j+r+1} = P_j for j = b − 1 … n
        q[..(a - p + 1) * dim].copy_from_slice(&pc[..(a - p + 1) * dim]);
        q[(b + r) * dim..].copy_from_slice(&pc[(b - 1) * dim..]);
        ub[..=a].copy_from_slice(&u[..=a]);
        ub[b + p + r + 1..].copy_from_slice(&u[b + p..]);
        // i walks the old knots down from b + p − 1, k the new ones from b + p + r
        let mut i = b + p - 1;
        let mut k = b + p + r;
        for j in (0..=r).rev() {
            while x[j] <= u[i] && i > a {
                copy_point(&mut q, k - p - 1, pc, i - p - 1, dim);
                ub[k] = u[i];
                k -= 1;
                i -= 1;
            }
            q.copy_within((k - p) * dim..(k - p + 1) * dim, (k - p - 1) * dim);
            for l in 1..=p {
                let ind = k - p + l;
                let num = ub[k + l] - x[j];
                if num == 0.0 {
                    q.copy_within(ind * dim..(ind + 1) * dim, (ind - 1) * dim);
                } else {
                    let alpha = num / (ub[k + l] - u[i - p + l]);
                    for d in 0..dim {
                        q[(ind - 1) * dim + d] =
                            alpha * q[(ind - 1) * dim + d] + (1.0 - alpha) * q[ind * dim + d];
                    }
                }
            }
            ub[k] = x[j];
            k -= 1;
        }
        BSplineCurve::from_raw(p, ub, Points::from_raw(q, dim))
    }

    /// Splits the curve at `t` into the curve on `[t_min, t]` and the curve on `[t, t_max]`,
    /// both clamped at `t`: `t` is inserted up to multiplicity `p` (P&T Algorithm A5.1; §5.2
    /// "splitting"), then the knots and control points are divided there. The pieces keep the
    /// original parameters, so the left piece at `s` equals the curve at `s`.
    ///
    /// ```
    /// use lekalo::{BSplineCurve, KnotVector, Points};
    /// let ctrl = Points::from_flat(1, vec![0.0, 1.0, 3.0, 2.0])?;
    /// let c = BSplineCurve::from_knot_vector(2, KnotVector::clamped_uniform(2, 4)?, ctrl)?;
    /// let (left, right) = c.split_at(0.3)?;
    /// assert_eq!(left.domain(), (0.0, 0.3));
    /// assert_eq!(right.domain(), (0.3, 1.0));
    /// assert!((left.eval(0.2)?[0] - c.eval(0.2)?[0]).abs() < 1e-15);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is outside the domain or NaN;
    /// [`Error::InvalidArgument`] if `t` is an end of the domain (a piece would be empty).
    pub fn split_at(&self, t: f64) -> Result<(BSplineCurve, BSplineCurve)> {
        let (min, max) = self.domain();
        if !(t >= min && t <= max) {
            return Err(Error::ParameterOutOfDomain { t, min, max });
        }
        if t == min || t == max {
            return Err(Error::InvalidArgument {
                what: "split parameter".into(),
                reason: format!(
                    "t = {t} is an end of the domain [{min}, {max}]; split strictly inside it",
                    t = readable(&t),
                    min = readable(&min),
                    max = readable(&max)
                ),
            });
        }
        check_inserted_gap(self.knots.as_slice(), t)?;
        let p = self.degree;
        let dim = self.dim();
        let s = self.knots.multiplicity(t);
        let full = if s < p {
            self.insert_knot_unchecked(t, p - s, s)
        } else {
            self.clone()
        };
        let u = full.knots.as_slice();
        let c = full.control.as_slice();
        // the copies of t are u_a … u_{a+s'−1}, s' ∈ {p, p + 1}
        let a = u.partition_point(|&x| x < t);
        let s_full = s.max(p);
        let mut left_knots = u[..a].to_vec();
        left_knots.extend(std::iter::repeat_n(t, p + 1));
        let left =
            BSplineCurve::from_raw(p, left_knots, Points::from_raw(c[..a * dim].to_vec(), dim));
        let first_right = a + s_full - p - 1;
        let mut right_knots = vec![t; p + 1];
        right_knots.extend_from_slice(&u[a + s_full..]);
        let right = BSplineCurve::from_raw(
            p,
            right_knots,
            Points::from_raw(c[first_right * dim..].to_vec(), dim),
        );
        debug_assert!(
            left.knots.validate_for(p, left.control.len()).is_ok()
                && right.knots.validate_for(p, right.control.len()).is_ok(),
            "split pieces must be valid"
        );
        Ok((left, right))
    }

    /// Bezier decomposition: the polynomial pieces of the curve on its domain, one per non-empty
    /// knot span, in order. Every distinct knot of the domain (its ends included) is raised to
    /// multiplicity `p` by knot refinement (P&T Algorithm A5.4); then on each span
    /// `[t_k, t_{k+1})` the `p + 1` non-zero B-splines are the Bernstein polynomials of
    /// `[t_k, t_{k+1}]` and `P_{k−p} … P_k` are the Bezier control points. This computes the
    /// same pieces as P&T Algorithm A5.6, and also handles unclamped knot vectors (the pieces
    /// cover only the domain `[t_p, t_{n+1}]`) and knots of multiplicity `p + 1`.
    /// O(n·p·dim).
    ///
    /// ```
    /// use lekalo::{BSplineCurve, Points};
    /// // the lecture's unclamped example: one piece, on the domain [1, 2]
    /// let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    /// let c = BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl)?;
    /// let pieces = c.to_bezier_segments();
    /// assert_eq!(pieces.len(), 1);
    /// assert_eq!((pieces[0].start, pieces[0].end), (1.0, 2.0));
    /// assert_eq!(pieces[0].curve.control_points().as_slice(), &[1.5, 2.0, 2.0, 3.0, 3.0, 3.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    #[must_use]
    pub fn to_bezier_segments(&self) -> Vec<BezierSegment> {
        let p = self.degree;
        let dim = self.dim();
        let (min, max) = self.domain();
        let mut x = Vec::new();
        for (knot, mult) in self.knots.distinct() {
            if knot >= min && knot <= max && mult < p {
                x.extend(std::iter::repeat_n(knot, p - mult));
            }
        }
        let refined = if x.is_empty() {
            self.clone()
        } else {
            self.refine_unchecked(&x)
        };
        let u = refined.knots.as_slice();
        let c = refined.control.as_slice();
        let n = refined.control.len() - 1;
        (p..=n)
            .filter(|&k| u[k] < u[k + 1])
            .map(|k| BezierSegment {
                start: u[k],
                end: u[k + 1],
                curve: BezierCurve::from_raw(Points::from_raw(
                    c[(k - p) * dim..(k + 1) * dim].to_vec(),
                    dim,
                )),
            })
            .collect()
    }

    /// The B-spline made of consecutive Bezier pieces (the inverse of
    /// [`BSplineCurve::to_bezier_segments`]): knots `start_0` and `end_last` with multiplicity
    /// `p + 1`, each join with multiplicity `p` when the adjacent end control points are equal
    /// (the shared point is stored once; the curve is continuous there), else `p + 1` (the curve
    /// jumps there, exactly as the pieces do). Degree-0 pieces always join with multiplicity 1.
    /// (The inverse of P&T A5.6; Curry–Schoenberg, document 003 Theorem 4.5, with `ν = 1` or
    /// `0` at the breakpoints.) O(total control points · dim).
    ///
    /// ```
    /// use lekalo::{BezierCurve, BezierSegment, BSplineCurve, Points};
    /// let a = BezierCurve::new(Points::from_flat(1, vec![0.0, 1.0, 2.0])?)?;
    /// let b = BezierCurve::new(Points::from_flat(1, vec![2.0, 0.0, 5.0])?)?;
    /// let c = BSplineCurve::from_bezier_segments(&[
    ///     BezierSegment { start: 0.0, end: 1.0, curve: a },
    ///     BezierSegment { start: 1.0, end: 3.0, curve: b },
    /// ])?;
    /// assert_eq!(c.knots().as_slice(), &[0.0, 0.0, 0.0, 1.0, 1.0, 3.0, 3.0, 3.0]);
    /// assert_eq!(c.control_points().as_slice(), &[0.0, 1.0, 2.0, 0.0, 5.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::TooFew`] for no segments; [`Error::NonFinite`] for a NaN or infinite `start` or
    /// `end`; [`Error::EmptyDomain`] if some `start ≥ end`; [`Error::InvalidArgument`] if a
    /// segment does not start where the previous one ends; [`Error::Degree`] if the degrees
    /// differ (elevate them first); [`Error::Dimension`] if the dimensions differ.
    pub fn from_bezier_segments(segments: &[BezierSegment]) -> Result<BSplineCurve> {
        let first = segments.first().ok_or(Error::TooFew {
            what: "Bezier segments".into(),
            min: 1,
            got: 0,
        })?;
        let p = first.curve.degree();
        let dim = first.curve.dim();
        for (i, seg) in segments.iter().enumerate() {
            if let Some(value) = [seg.start, seg.end].into_iter().find(|v| !v.is_finite()) {
                return Err(Error::NonFinite {
                    what: "Bezier segment start/end (index = segment)".into(),
                    index: i,
                    value,
                });
            }
            if seg.start >= seg.end {
                return Err(Error::EmptyDomain {
                    min: seg.start,
                    max: seg.end,
                });
            }
            if seg.curve.degree() != p {
                return Err(Error::Degree {
                    degree: seg.curve.degree(),
                    reason: format!(
                        "segment {i} has degree {} but segment 0 has degree {p}; elevate the \
                         segments to one degree first",
                        seg.curve.degree()
                    ),
                });
            }
            if seg.curve.dim() != dim {
                return Err(Error::Dimension {
                    what: "Bezier segment control points (all segments share a dimension)".into(),
                    expected: dim,
                    got: seg.curve.dim(),
                });
            }
            if i > 0 && seg.start != segments[i - 1].end {
                return Err(Error::InvalidArgument {
                    what: "Bezier segments".into(),
                    reason: format!(
                        "segment {i} starts at {} but segment {} ends at {}; the segments must \
                         be consecutive",
                        seg.start,
                        i - 1,
                        segments[i - 1].end
                    ),
                });
            }
        }
        let mut knots = vec![first.start; p + 1];
        let mut ctrl = first.curve.control_points().as_slice().to_vec();
        for pair in segments.windows(2) {
            let prev = pair[0].curve.control_points();
            let next = pair[1].curve.control_points();
            let continuous = p > 0 && prev.point(p) == next.point(0);
            let skip = usize::from(continuous);
            knots.extend(std::iter::repeat_n(pair[1].start, p + 1 - skip));
            ctrl.extend_from_slice(&next.as_slice()[skip * dim..]);
        }
        let last = segments.last().map_or(first.end, |s| s.end);
        knots.extend(std::iter::repeat_n(last, p + 1));
        let curve = BSplineCurve::from_raw(p, knots, Points::from_raw(ctrl, dim));
        debug_assert!(
            curve.knots.validate_for(p, curve.control.len()).is_ok(),
            "curve from Bezier segments must be valid"
        );
        Ok(curve)
    }
}

/// Copies point `src_i` of `src` into point `dst_i` of `dst` (flat, `dim` per point).
fn copy_point(dst: &mut [f64], dst_i: usize, src: &[f64], src_i: usize, dim: usize) {
    dst[dst_i * dim..(dst_i + 1) * dim].copy_from_slice(&src[src_i * dim..(src_i + 1) * dim]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A refused insertion says how many fit, or, where none does, what to do instead.
    #[test]
    fn a_refused_insertion_names_the_fix() {
        let pts = Points::from_2d(&[[0., 0.], [1., 2.], [2., 0.], [3., 1.], [4., 0.]]).unwrap();
        let cubic = BSplineCurve::new(3, vec![0., 0., 0., 0., 0.5, 1., 1., 1., 1.], pts).unwrap();
        let flat =
            BSplineCurve::new(0, vec![0., 1.], Points::from_2d(&[[1., 1.]]).unwrap()).unwrap();
        let full = cubic.insert_knot(0.5, 2).unwrap();
        let cases = [
            (
                &cubic,
                3,
                "multiplicity 4, more than the degree 3; insert it at most 2 times",
            ),
            (
                &full,
                1,
                "multiplicity 4, more than the degree 3; it has the largest multiplicity already: \
                 insert another knot, or elevate the degree first",
            ),
            (
                &flat,
                1,
                "multiplicity 1, more than the degree 0; a curve of degree 0 takes no knot: \
                 elevate its degree first",
            ),
        ];
        for (c, times, want) in cases {
            let e = c.insert_knot(0.5, times).unwrap_err();
            assert_eq!(e.arg(), Some(Arg::Times), "{e}");
            assert!(e.to_string().ends_with(want), "{e}");
        }
    }
}
