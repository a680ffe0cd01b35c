//! Smoothing every corner of a polyline into one curve
//! (docs/theory/blending.md#polyline-corners); the construction is documented on
//! [`smooth_polyline_corners`].

use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::points::{Points, PointsRef};
use crate::Arg;
use crate::{BSplineCurve, BezierCurve, BezierSegment};

/// The largest continuity degree [`smooth_polyline_corners`] accepts. The curve has degree
/// `2k + 1`, and 16 (degree 33) is far beyond any practical rounding while keeping the Bernstein
/// coefficients of the transitions accurate in `f64`.
pub const MAX_POLYLINE_CONTINUITY: usize = 16;

/// How much of the two segments at a corner its transition replaces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CornerWindow {
    /// A fraction `f ∈ (0, 1/2]` of the shorter of the corner's two segments, cut on both
    /// sides. Never too large: two windows on one segment take at most all of it.
    Fraction(f64),
    /// The same length `r > 0` on both sides of every corner; each segment must be at least as
    /// long as the windows of its corners together.
    Length(f64),
}

/// A polyline with its corners smoothed: one B-spline and where its parts lie.
#[derive(Debug, Clone, PartialEq)]
pub struct SmoothedPolyline {
    curve: BSplineCurve,
    continuity: usize,
    windows: Vec<f64>,
    straight: Vec<(f64, f64)>,
}

impl SmoothedPolyline {
    /// The curve: degree `2k + 1`, knots at the ends of the straight parts and transitions with
    /// multiplicity `2k + 1` (piecewise Bezier form; the curve is `C^k` there).
    #[must_use]
    pub fn curve(&self) -> &BSplineCurve {
        &self.curve
    }

    /// The continuity degree `k`: the curve is `C^k` at every join of a transition with a
    /// straight part (or with the next transition), although its knots there have multiplicity
    /// `2k + 1`, which alone would promise only `C^0`.
    #[must_use]
    pub fn continuity(&self) -> usize {
        self.continuity
    }

    /// The curve, owned.
    #[must_use]
    pub fn into_curve(self) -> BSplineCurve {
        self.curve
    }

    /// The window length `r_j` at each interior point `j = 1 … n−2` (index `j − 1`): the
    /// transition starts `r_j` before the corner and ends `r_j` after it, on a parameter
    /// interval of length `2 r_j`.
    #[must_use]
    pub fn windows(&self) -> &[f64] {
        &self.windows
    }

    /// The parameter interval of the straight part of each segment `i` (points `i` to `i+1`),
    /// where the curve is that segment, traversed at unit speed. Empty (`start == end`) when the
    /// windows take the whole segment.
    #[must_use]
    pub fn straight_spans(&self) -> &[(f64, f64)] {
        &self.straight
    }
}

#[allow(unused_imports)] // named in the documentation
use crate::blend::corner::CornerTransition;

/// Smooths every interior corner of the polyline `points` (at least three points, any
/// dimension) with continuity degree `continuity = k ≥ 1`, and returns the result as one curve
/// (docs/theory/blending.md#polyline-corners).
///
/// Construction: corner `j` (point `X = P_j`, unit directions `d_{j−1}` in and `d_j` out) gets a
/// window `r_j` (see [`CornerWindow`]). Segments are kept exactly outside the windows, on
/// parameter intervals equal to their length (unit speed). The pieces
/// `[X − r_j d_{j−1}, X]` and `[X, X + r_j d_j]` are replaced by one Bezier curve of degree
/// `n = 2k + 1` on a parameter interval of length `2 r_j`, whose control points are `k + 1`
/// evenly spaced points (spacing `δ = 2 r_j / n`) on each leg, `P_i = X − (r_j − iδ) d_{j−1}` and
/// `P_{n−i} = X + (r_j − iδ) d_j` for `i = 0 … k`. Equal spacing makes the derivatives of orders
/// `2 … k` vanish at both ends and the first derivative the legs' unit-speed one, so the curve is
/// `C^k` with the straight parts (not only `G^k`); the control polygon turns one way only, so
/// by variation diminishing the transition has no inflection: its curvature keeps one sign
/// through the corner (a fair corner). The straight parts are elevated to degree `2k + 1` and
/// the pieces are joined by [`BSplineCurve::from_bezier_segments`] with their common end points
/// stored once. The domain is `[0, Σ L_i]`, the polyline's length.
///
/// Document 001's deformation ([`CornerTransition`]) of the two legs is `C^k` too but inflects
/// twice inside every corner window, for every `k` (docs/theory/blending.md#polyline-corners).
///
/// ```
/// use lekalo::{smooth_polyline_corners, CornerWindow, Points};
/// let square = Points::from_2d(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])?;
/// let s = smooth_polyline_corners(square.as_view(), CornerWindow::Fraction(0.25), 2)?;
/// assert_eq!((s.curve().degree(), s.continuity()), (5, 2));
/// assert_eq!(s.windows(), &[0.5, 0.5]);
/// // the middle segment's straight part: x = 2, y from 0.5 to 1.5, at unit speed
/// let (a, _) = s.straight_spans()[1];
/// let p = s.curve().eval(a + 0.5)?;
/// assert!((p[0] - 2.0).abs() < 1e-14 && (p[1] - 1.0).abs() < 1e-14);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::TooFew`] for fewer than three points; [`Error::InvalidArgument`] for a continuity
/// outside `1..=`[`MAX_POLYLINE_CONTINUITY`], for repeated consecutive points (a segment no
/// longer than rounding of the data's scale), for a window fraction outside `(0, 1/2]` or a
/// window length that is not positive, and for a window length too large for a segment (the
/// message names the segment and the largest length that fits); [`Error::NonFinite`] for a NaN
/// or infinite coordinate or window.
pub fn smooth_polyline_corners(
    points: PointsRef<'_>,
    window: CornerWindow,
    continuity: usize,
) -> Result<SmoothedPolyline> {
    let n = points.len();
    if n < 3 {
        return Err(Error::TooFew {
            what: "polyline points (a corner needs three)".into(),
            min: 3,
            got: n,
        });
    }
    if continuity == 0 || continuity > MAX_POLYLINE_CONTINUITY {
        return Err(Error::InvalidArgument {
            what: Arg::Continuity.into(),
            reason: format!("got {continuity}; must be in 1..={MAX_POLYLINE_CONTINUITY}"),
        });
    }
    check_finite("polyline coordinates", points.as_slice())?;
    let dim = points.dim();
    let lengths = segment_lengths(points)?;
    let windows = corner_windows(&lengths, window)?;
    // window of the corner at point i (0 at the end points)
    let r_at = |i: usize| {
        if i == 0 || i == n - 1 {
            0.0
        } else {
            windows[i - 1]
        }
    };
    let dir = |i: usize| -> Vec<f64> {
        let (a, b) = (points.point(i), points.point(i + 1));
        a.iter().zip(b).map(|(x, y)| (y - x) / lengths[i]).collect()
    };
    let along = |x: &[f64], d: &[f64], t: f64| -> Vec<f64> {
        x.iter()
            .zip(d)
            .map(|(x, d)| x + t * d)
            .collect::<Vec<f64>>()
    };
    let degree = 2 * continuity + 1;
    let mut segments = Vec::with_capacity(2 * n);
    let mut straight = Vec::with_capacity(n - 1);
    let mut s = 0.0;
    for i in 0..n - 1 {
        let d = dir(i);
        let (p, q) = (points.point(i), points.point(i + 1));
        let start = if i == 0 {
            p.to_vec()
        } else {
            along(p, &d, r_at(i))
        };
        let end = if i == n - 2 {
            q.to_vec()
        } else {
            along(q, &d, -r_at(i + 1))
        };
        let len = lengths[i] - r_at(i) - r_at(i + 1);
        if len > 0.0 {
            segments.push(BezierSegment {
                start: s,
                end: s + len,
                curve: straight_piece(&start, &end, degree)?,
            });
            straight.push((s, s + len));
            s += len;
        } else {
            straight.push((s, s));
        }
        if i + 1 < n - 1 {
            let r = r_at(i + 1);
            let next = dir(i + 1);
            let after_end = along(q, &next, r);
            let mut piece = transition(q, &d, &next, r, continuity);
            pin_ends(&mut piece, &end, &after_end, dim);
            segments.push(BezierSegment {
                start: s,
                end: s + 2.0 * r,
                curve: BezierCurve::new(Points::from_flat(dim, piece)?)?,
            });
            s += 2.0 * r;
        }
    }
    Ok(SmoothedPolyline {
        curve: BSplineCurve::from_bezier_segments(&segments)?,
        continuity,
        windows,
        straight,
    })
}

/// Segment lengths, refusing repeated points (length within rounding of the data's scale).
fn segment_lengths(points: PointsRef<'_>) -> Result<Vec<f64>> {
    let scale = points
        .as_slice()
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    (0..points.len() - 1)
        .map(|i| {
            let len = crate::blend::deformation::dist(points.point(i), points.point(i + 1));
            if len <= 4.0 * f64::EPSILON * scale || len == 0.0 {
                return Err(Error::InvalidArgument {
                    what: "polyline points".into(),
                    reason: format!(
                        "points {i} and {} coincide (segment length {len:e}); remove the \
                         repeated point",
                        i + 1
                    ),
                });
            }
            if !len.is_finite() {
                return Err(Error::NonFinite {
                    what: "polyline segment length (index = segment; rescale the points)".into(),
                    index: i,
                    value: len,
                });
            }
            Ok(len)
        })
        .collect()
}

/// The window `r_j` of each interior corner, checked against the segments.
fn corner_windows(lengths: &[f64], window: CornerWindow) -> Result<Vec<f64>> {
    let corners = lengths.len() - 1;
    let windows: Vec<f64> =
        match window {
            CornerWindow::Fraction(f) => {
                check_finite(Arg::CornerFraction, &[f])?;
                if !(f > 0.0 && f <= 0.5) {
                    return Err(Error::InvalidArgument {
                        what: Arg::CornerFraction.into(),
                        reason: format!(
                        "got {f}; it must lie in (0, 0.5] (a fraction of the shorter segment at \
                         each corner)", f = readable(&f)),
                    });
                }
                (0..corners)
                    .map(|j| f * lengths[j].min(lengths[j + 1]))
                    .collect()
            }
            CornerWindow::Length(r) => {
                check_finite(Arg::CornerLength, &[r])?;
                if r <= 0.0 {
                    return Err(Error::InvalidArgument {
                        what: Arg::CornerLength.into(),
                        reason: format!("got {r}; it must be positive", r = readable(&r)),
                    });
                }
                vec![r; corners]
            }
        };
    let last = lengths.len() - 1;
    for (i, &len) in lengths.iter().enumerate() {
        let left = if i == 0 { 0.0 } else { windows[i - 1] };
        let right = if i == last { 0.0 } else { windows[i] };
        if left + right > len {
            let fits = lengths
                .iter()
                .enumerate()
                .map(|(i, l)| if i == 0 || i == last { *l } else { l / 2.0 })
                .fold(f64::INFINITY, f64::min);
            return Err(Error::InvalidArgument {
                what: Arg::CornerWindow.into(),
                reason: format!(
                    "segment {i} (points {i} to {}) is {len} long but its corner windows take \
                     {}; the largest window length that fits every segment is {fits} (or give \
                     a fraction)",
                    i + 1,
                    readable(&(left + right)),
                    len = readable(&len),
                    fits = readable(&fits)
                ),
            });
        }
    }
    Ok(windows)
}

/// The segment `start → end` as a Bezier curve of `degree` (evenly spaced control points, the
/// ends exact).
fn straight_piece(start: &[f64], end: &[f64], degree: usize) -> Result<BezierCurve> {
    let mut ctrl = Vec::with_capacity((degree + 1) * start.len());
    for m in 0..=degree {
        if m == degree {
            ctrl.extend_from_slice(end);
        } else {
            #[allow(clippy::cast_precision_loss)] // degree ≤ 64
            let t = m as f64 / degree as f64;
            ctrl.extend(start.iter().zip(end).map(|(a, b)| a + t * (b - a)));
        }
    }
    BezierCurve::new(Points::from_flat(start.len(), ctrl)?)
}

/// The transition at corner `x` (directions `d_in`, `d_out`, window `r`) as flat Bezier control
/// points of degree `n = 2k + 1`: `k + 1` points spaced `δ = 2r/n` on each leg, starting `r` from
/// the corner (docs/theory/blending.md#polyline-corners).
fn transition(x: &[f64], d_in: &[f64], d_out: &[f64], r: f64, continuity: usize) -> Vec<f64> {
    let n = 2 * continuity + 1;
    #[allow(clippy::cast_precision_loss)] // n ≤ 33
    let delta = 2.0 * r / n as f64;
    let mut ctrl = Vec::with_capacity((n + 1) * x.len());
    for i in 0..=continuity {
        #[allow(clippy::cast_precision_loss)]
        let back = r - i as f64 * delta;
        ctrl.extend(x.iter().zip(d_in).map(|(x, d)| x - back * d));
    }
    for i in (0..=continuity).rev() {
        #[allow(clippy::cast_precision_loss)]
        let ahead = r - i as f64 * delta;
        ctrl.extend(x.iter().zip(d_out).map(|(x, d)| x + ahead * d));
    }
    ctrl
}

/// Sets the transition's end control points to the straight parts' end points, so that the
/// pieces share them bit for bit (they agree to rounding already).
fn pin_ends(ctrl: &mut [f64], start: &[f64], end: &[f64], dim: usize) {
    let n = ctrl.len();
    ctrl[..dim].copy_from_slice(start);
    ctrl[n - dim..].copy_from_slice(end);
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn smooth(rows: &[[f64; 2]], window: CornerWindow, k: usize) -> Result<SmoothedPolyline> {
        smooth_polyline_corners(Points::from_2d(rows)?.as_view(), window, k)
    }

    /// Largest jump of the derivatives `0..=order` (in the curve's parameter) over the joins of
    /// the Bezier pieces, relative to the size rounding gives them: `|P| (p / h)^l` for control
    /// points of size `|P|`, degree `p` and the shorter piece length `h` (the l-th derivative is
    /// `p!/(p−l)! Δ^l P / h^l`).
    fn max_relative_jump(curve: &BSplineCurve, order: usize) -> f64 {
        let pieces = curve.to_bezier_segments();
        let size = curve.control_points().max_abs();
        #[allow(clippy::cast_precision_loss)]
        let p = curve.degree() as f64;
        let mut worst = 0.0_f64;
        for w in pieces.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            let left = a
                .curve
                .eval_derivatives(1.0, order)
                .unwrap_or_else(|e| panic!("{e}"));
            let right = b
                .curve
                .eval_derivatives(0.0, order)
                .unwrap_or_else(|e| panic!("{e}"));
            let (ha, hb) = (a.end - a.start, b.end - b.start);
            for l in 0..=order {
                let l = i32::try_from(l).unwrap_or(i32::MAX);
                let rows = left.point(l as usize).iter().zip(right.point(l as usize));
                let jump = rows.fold(0.0_f64, |m, (x, y)| {
                    m.max((x / ha.powi(l) - y / hb.powi(l)).abs())
                });
                worst = worst.max(jump / (size * (p / ha.min(hb)).powi(l)));
            }
        }
        worst
    }

    /// Length of the polyline up to point `i`.
    fn lengths_before(rows: &[[f64; 2]], i: usize) -> f64 {
        rows.windows(2)
            .take(i)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum()
    }

    /// Signed curvature numerators `x'y'' − x''y'` of a planar curve at `m` parameters per
    /// Bezier piece, with the piece's start parameter.
    fn turning(curve: &BSplineCurve, m: usize) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        for piece in curve.to_bezier_segments() {
            for j in 1..m {
                #[allow(clippy::cast_precision_loss)]
                let u = j as f64 / m as f64;
                let d = piece
                    .curve
                    .eval_derivatives(u, 2)
                    .unwrap_or_else(|e| panic!("{e}"));
                let (d1, d2) = (d.point(1), d.point(2));
                out.push((piece.start, d1[0] * d2[1] - d1[1] * d2[0]));
            }
        }
        out
    }

    #[test]
    fn corners_turn_one_way() -> Result<()> {
        // every corner of the zigzag, and the tour's three-point polyline: the curvature inside a
        // corner window keeps the sign of the corner's turn (document 001's deformation of the two
        // legs changes sign twice there)
        for rows in [&ZIGZAG[..], &[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]][..]] {
            for k in 1..=4 {
                for f in [0.25, 0.5] {
                    let s = smooth(rows, CornerWindow::Fraction(f), k)?;
                    let spans = s.straight_spans();
                    for (j, w) in spans.windows(2).enumerate() {
                        let (from, to) = (w[0].1, w[1].0);
                        let (a, b, c) = (rows[j], rows[j + 1], rows[j + 2]);
                        let turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
                        let size = s.curve().control_points().max_abs();
                        for (start, cross) in turning(s.curve(), 16) {
                            if start >= from && start < to {
                                assert!(
                                    cross * turn.signum() > -1e-12 * size,
                                    "k = {k}, f = {f}, corner {}: curvature {cross:e} against the turn",
                                    j + 1
                                );
                            }
                        }
                    }
                }
            }
        }
        Ok(())
    }

    const ZIGZAG: [[f64; 2]; 5] = [[0.0, 0.0], [3.0, 0.0], [4.0, 2.5], [7.0, 1.0], [7.5, 6.0]];

    #[test]
    fn passes_through_segment_midpoints_and_keeps_segments_straight() -> Result<()> {
        for (window, k) in [
            (CornerWindow::Fraction(0.3), 1),
            (CornerWindow::Fraction(0.5), 2),
            (CornerWindow::Length(0.8), 3),
        ] {
            let s = smooth(&ZIGZAG, window, k)?;
            assert_eq!(s.curve().degree(), 2 * k + 1, "degree 2k + 1 for k = {k}");
            for (i, &(a, b)) in s.straight_spans().iter().enumerate() {
                let (p, q) = (ZIGZAG[i], ZIGZAG[i + 1]);
                let len = (q[0] - p[0]).hypot(q[1] - p[1]);
                let r_left = if i == 0 { 0.0 } else { s.windows()[i - 1] };
                let mid = a + len / 2.0 - r_left;
                let at = lengths_before(&ZIGZAG, i) + r_left;
                assert!(
                    (a - at).abs() < 1e-14 * 20.0,
                    "straight part {i} starts at its arc length {at}, not {a}"
                );
                if mid > a && mid < b {
                    let m = s.curve().eval(mid)?;
                    let want = [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
                    for (x, y) in m.iter().zip(want) {
                        assert!(
                            (x - y).abs() <= 1e-14 * 7.5,
                            "{window:?} k={k} mid {i}: {m:?}"
                        );
                    }
                }
                // unit speed along the segment's direction on the straight part
                if b > a {
                    let d = s.curve().eval_derivatives((a + b) / 2.0, 2)?;
                    let dir = [(q[0] - p[0]) / len, (q[1] - p[1]) / len];
                    for c in 0..2 {
                        assert!(
                            (d.point(1)[c] - dir[c]).abs() < 1e-12,
                            "speed on segment {i}"
                        );
                        assert!(d.point(2)[c].abs() < 1e-10, "segment {i} is straight");
                    }
                }
            }
        }
        Ok(())
    }

    #[test]
    fn the_pp_form_measures_the_continuity_the_result_reports() -> Result<()> {
        // every join has D^2 … D^k = 0 on both sides: the continuity test must scale the
        // jumps by the derivatives' size over the pieces, not by their (zero) values at the joins
        // (the symmetric zigzag's x is a straight line in the parameter: its D^2 … vanish)
        let symmetric = [[0.0, 0.0], [1.0, 2.0], [2.0, 0.0], [3.0, 2.0], [4.0, 0.0]];
        for (k, rows) in (1..=4).flat_map(|k| [(k, &ZIGZAG), (k, &symmetric)]) {
            let s = smooth(rows, CornerWindow::Fraction(0.3), k)?;
            let nu = crate::PiecewisePolynomial::from_bspline(s.curve())?
                .continuity(crate::DEFAULT_CONTINUITY_RTOL);
            assert!(!nu.is_empty(), "joins");
            assert!(
                nu.iter().all(|&n| n == s.continuity() + 1),
                "k = {k}: ν = {nu:?}, C^{} reported",
                s.continuity()
            );
        }
        Ok(())
    }

    #[test]
    fn is_c_k_at_every_join_and_not_smoother() -> Result<()> {
        for k in 1..=4 {
            let s = smooth(&ZIGZAG, CornerWindow::Fraction(0.4), k)?;
            // the continuity the result reports is the one its joins have
            let k = s.continuity();
            let jump = max_relative_jump(s.curve(), k);
            assert!(jump < 1e-13, "k = {k}: derivative jump {jump:e}");
            // the (k+1)-th derivative jumps at a corner: the check above can fail
            let next = max_relative_jump(s.curve(), k + 1);
            assert!(
                next > 1e-6,
                "k = {k}: order k+1 jump {next:e} should be visible"
            );
        }
        Ok(())
    }

    #[test]
    fn windows_by_fraction_and_length() -> Result<()> {
        let s = smooth(&ZIGZAG, CornerWindow::Fraction(0.25), 2)?;
        let l = |i: usize| (ZIGZAG[i + 1][0] - ZIGZAG[i][0]).hypot(ZIGZAG[i + 1][1] - ZIGZAG[i][1]);
        for j in 0..3 {
            assert_eq!(
                s.windows()[j],
                0.25 * l(j).min(l(j + 1)),
                "corner {}",
                j + 1
            );
        }
        let total: f64 = (0..4).map(l).sum::<f64>();
        let (_, end) = s.curve().domain();
        assert!((end - total).abs() < 1e-13, "domain end {end} vs {total}");
        let s = smooth(&ZIGZAG, CornerWindow::Length(1.0), 1)?;
        assert_eq!(s.windows(), &[1.0, 1.0, 1.0]);
        Ok(())
    }

    #[test]
    fn works_in_3d_and_on_collinear_points() -> Result<()> {
        let p = Points::from_3d(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [2.0, 1.0, 1.0],
        ])?;
        let s = smooth_polyline_corners(p.as_view(), CornerWindow::Fraction(0.3), 2)?;
        assert!(max_relative_jump(s.curve(), 2) < 1e-13, "3d C^2");
        let s = smooth(
            &[[0.0, 0.0], [1.0, 0.0], [3.0, 0.0]],
            CornerWindow::Fraction(0.5),
            2,
        )?;
        for t in [0.2, 0.7, 1.1, 2.0] {
            let y = s.curve().eval(t)?[1];
            assert!(
                y.abs() < 1e-15,
                "a straight corner stays on the line, y = {y}"
            );
        }
        Ok(())
    }

    #[test]
    fn bad_input_gives_named_errors() {
        let e = smooth(&[[0.0, 0.0], [1.0, 0.0]], CornerWindow::Fraction(0.2), 2);
        assert!(
            matches!(e, Err(Error::TooFew { min: 3, got: 2, .. })),
            "{e:?}"
        );
        let e = smooth(
            &[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
            CornerWindow::Fraction(0.2),
            2,
        );
        assert!(
            matches!(&e, Err(Error::InvalidArgument { what, reason }) if reason.contains("points 1 and 2 coincide") && what.words() == "polyline points"),
            "{e:?}"
        );
        let e = smooth(&ZIGZAG, CornerWindow::Length(1.6), 2);
        assert!(
            matches!(&e, Err(Error::InvalidArgument { what, reason }) if reason.contains("segment 1 (points 1 to 2)") && what.arg() == Some(Arg::CornerWindow)),
            "{e:?}"
        );
        for f in [0.0, -0.1, 0.6] {
            let e = smooth(&ZIGZAG, CornerWindow::Fraction(f), 2);
            assert!(
                matches!(
                    e,
                    Err(Error::InvalidArgument { what, .. }) if what.arg() == Some(Arg::CornerFraction)
                ),
                "{f}: {e:?}"
            );
        }
        let e = smooth(&ZIGZAG, CornerWindow::Length(f64::NAN), 2);
        assert!(matches!(e, Err(Error::NonFinite { .. })), "{e:?}");
        for k in [0, MAX_POLYLINE_CONTINUITY + 1] {
            let e = smooth(&ZIGZAG, CornerWindow::Fraction(0.2), k);
            assert!(
                matches!(
                    e,
                    Err(Error::InvalidArgument { what, .. }) if what.arg() == Some(Arg::Continuity)
                ),
                "{k}: {e:?}"
            );
        }
        let e = Points::from_flat(2, vec![0.0, 0.0, 1.0, f64::NAN, 2.0, 0.0]);
        assert!(matches!(e, Err(Error::NonFinite { index: 3, .. })), "{e:?}");
    }

    proptest! {
        #[test]
        fn random_polylines_are_c_k(
            raw in proptest::collection::vec((-10.0..10.0_f64, -10.0..10.0_f64), 3..8),
            f in 0.05..0.5_f64,
            k in 1usize..4,
        ) {
            let rows: Vec<[f64; 2]> = raw.iter().map(|&(x, y)| [x, y]).collect();
            let distinct = rows.windows(2).all(|w| (w[0][0] - w[1][0]).hypot(w[0][1] - w[1][1]) > 1e-3);
            prop_assume!(distinct);
            let s = smooth(&rows, CornerWindow::Fraction(f), k).map_err(|e| TestCaseError::fail(e.to_string()))?;
            let jump = max_relative_jump(s.curve(), k);
            prop_assert!(jump < 1e-13, "jump {:e}", jump);
            // the ends are the polyline's end points (to rounding of the evaluation)
            let (a, b) = s.curve().domain();
            for (t, want) in [(a, rows[0]), (b, rows[rows.len() - 1])] {
                let p = s.curve().eval(t).map_err(|e| TestCaseError::fail(e.to_string()))?;
                prop_assert!((p[0] - want[0]).abs() < 1e-14 && (p[1] - want[1]).abs() < 1e-14, "{:?} vs {:?}", p, want);
            }
        }
    }
}
