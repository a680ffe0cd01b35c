//! Offsets of planar curves: `C(t) + d·N(t)` approximated by a cubic B-spline within a
//! tolerance, with the cusps where `d·κ = 1` found and the loops between them trimmed
//! (`docs/theory/queries.md#offsets`).

use super::intersect::CurveIntersection;
use super::pieces::{check_tolerance, dist, QueryCurve};
use crate::basis::BasisScratch;
use crate::error::readable;
use crate::error::{check_finite, Error, Result};
use crate::fit::{least_squares, EndConstraints, FitData};
use crate::{Arg, BSplineCurve, KnotVector, PointsRef, What};

/// Samples of the exact offset in every knot span of the fit (and one at every knot): a
/// cubic piece has four coefficients, so the least-squares problem is well posed span by span.
const SAMPLES_PER_SPAN: usize = 6;
/// Check points of the deviation in every knot span.
const CHECKS_PER_SPAN: usize = 16;
/// A span whose deviation `e` exceeds the tolerance is split into `⌈(e / (aim·tol))^{1/4}⌉`
/// equal parts (the error of a cubic fit falls with the fourth power of the span).
const SPLIT_AIM: f64 = 0.8;
/// Most samples of the exact offset in all.
const MAX_SAMPLES: usize = 1 << 21;
/// Shortest span, relative to the domain, that is still split: below it the tolerance is
/// taken to be under the rounding of the curve.
const MIN_SPAN: f64 = 1e-10;
/// Golden-section steps refining the largest deviation in each knot span. The bracket starts
/// at two check intervals (1/8 of the span `H`) and shrinks by 0.618 a step: 20 steps leave
/// `8e-6·H`. The deviation of a cubic fit oscillates like a polynomial of low degree on the
/// span (`|e''| ≲ 100·max e / H²`, as for a Chebyshev polynomial of degree 5), so the maximum
/// can rise above the best point found by at most `50·(8e-6)² ≈ 3e-9` of itself.
const GOLDEN_STEPS: usize = 20;

/// The error of a point where the base curve has no normal.
fn no_normal(t: f64) -> Error {
    Error::InvalidArgument {
        what: "curve to offset".into(),
        reason: format!(
            "C'(t) = 0 at t = {t}: the normal, hence the offset, is undefined",
            t = readable(&t)
        ),
    }
}

/// The offset of a planar curve.
#[derive(Debug, Clone)]
pub struct Offset {
    /// The whole offset as one cubic B-spline on the base curve's parameters (loops included):
    /// `curve(t) ≈ C(t) + d·N(t)`.
    pub curve: BSplineCurve,
    /// The offset with its loops cut out: the parts between the trimmed intervals.
    pub trimmed: Vec<BSplineCurve>,
    /// Parameters of the cusps (`d·κ(t) = 1`).
    pub cusps: Vec<f64>,
    /// The parameter intervals removed as loops: each from the self-intersection on the
    /// part before a pair of cusps to the one after it.
    pub loops: Vec<(f64, f64)>,
    /// Largest deviation `|curve(t) − (C(t) + d·N(t))|` found: at 16 check points in every
    /// knot span of `curve`, refined by golden-section search around the largest of them.
    pub deviation: f64,
}

impl QueryCurve {
    /// The exact offset point `C(t) + d·N(t)` and the factor `1 − d·κ(t)` (signed curvature,
    /// left normal `N = (−y', x')/|C'|`); `None` where `C' = 0`. Evaluated on the piece holding
    /// `t` without allocating (it runs for every sample and check point).
    fn offset_point(&self, t: f64, d: f64, scratch: &mut Vec<f64>) -> Option<([f64; 2], f64)> {
        let k = self.piece_of(t);
        self.offset_local(k, self.local(k, t), d, scratch)
            .map(|(p, _, f)| (p, f))
    }

    /// The offset point `C + d·N`, the base curve's derivative `C'` and the factor
    /// `1 − d·κ` at the local parameter `s` of piece `k` (one-sided at the piece's ends);
    /// `None` where `C' = 0`.
    fn offset_local(
        &self,
        k: usize,
        s: f64,
        d: f64,
        scratch: &mut Vec<f64>,
    ) -> Option<([f64; 2], [f64; 2], f64)> {
        let mut out = [0.0; 6];
        self.eval_local(k, s, 2, scratch, &mut out);
        let (a, b) = self.spans[k];
        let h = b - a;
        let c = [
            self.centre[0] + self.scale * out[0],
            self.centre[1] + self.scale * out[1],
        ];
        let (x1, y1) = (self.scale * out[2] / h, self.scale * out[3] / h);
        let (x2, y2) = (self.scale * out[4] / (h * h), self.scale * out[5] / (h * h));
        let speed = x1.hypot(y1);
        if !(speed > 0.0) {
            return None;
        }
        let kappa = (x1 * y2 - y1 * x2) / (speed * speed * speed);
        Some((
            [c[0] - d * y1 / speed, c[1] + d * x1 / speed],
            [x1, y1],
            1.0 - d * kappa,
        ))
    }

    /// The self-intersection `O(a) = O(b)` of the exact offset near `(a, b)`, found on the
    /// fitted offset: Newton's method on `O(a) − O(b) = 0` with the Jacobian `[O'(a), −O'(b)]`,
    /// `O' = C'·(1 − d·κ)`, while the steps shrink, `a` and `b` kept in `lims`; `None` if it
    /// does not converge (the fitted cut is kept).
    fn refine_cut(
        &self,
        (mut a, mut b): (f64, f64),
        lims: ((f64, f64), (f64, f64)),
        d: f64,
        scratch: &mut Vec<f64>,
    ) -> Option<(f64, f64)> {
        let mut jet = |t: f64| -> Option<([f64; 2], [f64; 2])> {
            let k = self.piece_of(t);
            self.offset_jet(k, self.local(k, t), d, scratch)
        };
        let span = (lims.1 .1 - lims.0 .0).abs();
        let mut last = f64::INFINITY;
        for _ in 0..30 {
            let ((p, u), (q, w)) = (jet(a)?, jet(b)?);
            let r = [p[0] - q[0], p[1] - q[1]];
            let det = u[0] * -w[1] + w[0] * u[1];
            if !(det.abs() > 0.0) {
                return None;
            }
            // [u, −w] (da, db)ᵀ = −r
            let da = (-r[0] * -w[1] - -w[0] * -r[1]) / det;
            let db = (u[0] * -r[1] - u[1] * -r[0]) / det;
            a += da;
            b += db;
            if !(a >= lims.0 .0 && a <= lims.0 .1 && b >= lims.1 .0 && b <= lims.1 .1) {
                return None;
            }
            let step = da.abs().max(db.abs());
            if step <= 4.0 * f64::EPSILON * span {
                return Some((a, b));
            }
            if step >= last {
                // rounding stops the steps shrinking; anything larger does not converge
                return (step <= 1e-9 * span).then_some((a, b));
            }
            last = step;
        }
        None
    }

    /// The offset `O = C + d·N` and its derivative `O' = C'·(1 − d·κ)` at the local parameter
    /// `s` of piece `k` (one-sided at the piece's ends); `None` where `C' = 0`.
    fn offset_jet(
        &self,
        k: usize,
        s: f64,
        d: f64,
        scratch: &mut Vec<f64>,
    ) -> Option<([f64; 2], [f64; 2])> {
        let (p, v, f) = self.offset_local(k, s, d, scratch)?;
        Some((p, [v[0] * f, v[1] * f]))
    }

    /// Knot multiplicity of the fitted cubic at the start of piece `k` of the base curve: the
    /// offset of a curve that is `C^j` there is in general only `C^{j−1}` (its derivative
    /// `C'·(1 − d·κ)` holds the curvature), so a double knot lets the cubic follow the jump of
    /// the second derivative; a triple knot where the first derivative jumps (relative
    /// difference above `1e-9`), and four where the offset itself jumps (the base curve has a
    /// corner: the normal turns there; a gap above `1e-12` of the curve's size).
    fn offset_multiplicity(&self, k: usize, d: f64, scratch: &mut Vec<f64>) -> usize {
        match (
            self.offset_jet(k - 1, 1.0, d, scratch),
            self.offset_jet(k, 0.0, d, scratch),
        ) {
            (Some((p, v)), Some((q, w))) => {
                if dist(&p, &q) > 1e-12 * (self.scale + d.abs()) {
                    4
                } else if dist(&v, &w) > 1e-9 * v[0].hypot(v[1]).max(w[0].hypot(w[1])) {
                    3
                } else {
                    2
                }
            }
            _ => 4,
        }
    }

    /// The exact offset at the breakpoints `breaks` and at [`SAMPLES_PER_SPAN`] − 1 equally
    /// spaced points inside every span between them: the parameters and the points (flat
    /// `x, y`). A breakpoint where the offset jumps (multiplicity 4 in `mult`, see
    /// [`QueryCurve::fit_offset`]) has no sample: its two sides differ.
    fn offset_samples(
        &self,
        d: f64,
        breaks: &[f64],
        mult: &[usize],
        scratch: &mut Vec<f64>,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = (breaks.len() - 1) * SAMPLES_PER_SPAN + 1;
        let mut ts = Vec::with_capacity(n);
        for (k, w) in breaks.windows(2).enumerate() {
            let h = (w[1] - w[0]) / SAMPLES_PER_SPAN as f64;
            let first = usize::from(k > 0 && mult[k] > 3);
            ts.extend((first..SAMPLES_PER_SPAN).map(|i| w[0] + h * i as f64));
        }
        ts.push(breaks[breaks.len() - 1]);
        let mut pts = Vec::with_capacity(2 * ts.len());
        for &t in &ts {
            let (p, _) = self
                .offset_point(t, d, scratch)
                .ok_or_else(|| no_normal(t))?;
            pts.extend(p);
        }
        Ok((ts, pts))
    }

    /// The largest deviation `e(t) = |curve(t) − (C(t) + d·N(t))|` in each span between the
    /// breakpoints `breaks` (the distinct knots of `curve`): at [`CHECKS_PER_SPAN`] check
    /// points `(j + ½)/CHECKS_PER_SPAN` of the span (none of them a sample of
    /// [`QueryCurve::offset_samples`]); if all of them are within `tolerance`, also by
    /// golden-section search for the maximum of `e` between the neighbours of the largest check
    /// point of each span. The search stops as soon as it finds a deviation above `tolerance`:
    /// the span is split then, and into the same number of parts (a deviation refined from
    /// check points within the tolerance stays far below the `12.8·tol` that would ask for
    /// three).
    fn span_deviations(
        &self,
        curve: &BSplineCurve,
        breaks: &[f64],
        d: f64,
        tolerance: f64,
        scratch: &mut Vec<f64>,
    ) -> Result<Vec<f64>> {
        let p = curve.degree();
        let mut basis = BasisScratch::new(p);
        let mut n = vec![0.0; p + 1];
        // `span`: the knot span of `curve` holding `t` (all of a window's inner points share it)
        let mut e = |span: usize, t: f64| -> Result<f64> {
            let (o, _) = self
                .offset_point(t, d, scratch)
                .ok_or_else(|| no_normal(t))?;
            let mut q = [0.0; 2];
            curve.eval_span(span, t, &mut basis, &mut n, &mut q);
            Ok(dist(&q, &o))
        };
        const G: f64 = 0.618_033_988_749_894_9;
        let spans = breaks.len() - 1;
        let (mut out, mut at, mut knot_span) = (
            Vec::with_capacity(spans),
            Vec::with_capacity(spans),
            Vec::with_capacity(spans),
        );
        for w in breaks.windows(2) {
            let span = curve.knots().find_span(p, 0.5 * (w[0] + w[1]))?;
            let h = (w[1] - w[0]) / CHECKS_PER_SPAN as f64;
            let (mut best, mut arg) = (0.0_f64, w[0]);
            for j in 0..CHECKS_PER_SPAN {
                let t = w[0] + h * (j as f64 + 0.5);
                let v = e(span, t)?;
                if v > best {
                    (best, arg) = (v, t);
                }
            }
            out.push(best);
            at.push(arg);
            knot_span.push(span);
        }
        if out.iter().any(|&x| x > tolerance) {
            return Ok(out);
        }
        for (k, w) in breaks.windows(2).enumerate() {
            let (span, h) = (knot_span[k], (w[1] - w[0]) / CHECKS_PER_SPAN as f64);
            let (mut a, mut b) = ((at[k] - h).max(w[0]), (at[k] + h).min(w[1]));
            let (mut x1, mut x2) = (b - G * (b - a), a + G * (b - a));
            let (mut f1, mut f2) = (e(span, x1)?, e(span, x2)?);
            for _ in 0..GOLDEN_STEPS {
                if f1.max(f2) > tolerance {
                    break;
                }
                if f1 > f2 {
                    b = x2;
                    (x2, f2) = (x1, f1);
                    x1 = b - G * (b - a);
                    f1 = e(span, x1)?;
                } else {
                    a = x1;
                    (x1, f1) = (x2, f2);
                    x2 = a + G * (b - a);
                    f2 = e(span, x2)?;
                }
            }
            out[k] = out[k].max(f1).max(f2);
        }
        Ok(out)
    }

    /// The least-squares cubic with the breakpoints `breaks` (interior multiplicities `mult`)
    /// through the ends of the exact offset, fitted to its samples
    /// ([`QueryCurve::offset_samples`]).
    fn fit_offset(
        &self,
        d: f64,
        breaks: &[f64],
        mult: &[usize],
        scratch: &mut Vec<f64>,
    ) -> Result<BSplineCurve> {
        let (lo, hi) = (breaks[0], breaks[breaks.len() - 1]);
        let mut knots = vec![lo; 4];
        for (&b, &m) in breaks[1..breaks.len() - 1].iter().zip(&mult[1..]) {
            knots.extend(std::iter::repeat_n(b, m));
        }
        knots.extend([hi; 4]);
        let (ts, pts) = self.offset_samples(d, breaks, mult, scratch)?;
        Ok(least_squares(
            &FitData::new(PointsRef::from_flat(2, &pts)?, &ts)?,
            3,
            &KnotVector::from_raw(knots),
            &EndConstraints::points(),
        )?
        .curve)
    }

    /// The offset as a cubic B-spline within `tolerance` of the exact offset at the base
    /// curve's parameters, with few control points, and the largest deviation found
    /// (`docs/theory/queries.md#offsets`):
    ///
    /// 1. breakpoints: the base curve's, with the multiplicities of
    ///    [`QueryCurve::offset_multiplicity`];
    /// 2. least squares ([`QueryCurve::fit_offset`]); the deviation of every span
    ///    ([`QueryCurve::span_deviations`], at the check points, then refined by golden-section
    ///    search once they are all within the tolerance); every span above the tolerance is
    ///    split into `⌈(e / (0.8·tol))^{1/4}⌉` equal parts, and the fit repeated;
    /// 3. once every span is within the tolerance, the spans are placed anew by
    ///    [`redistribute`] (as many as the error model asks for) and step 2 runs again;
    /// 4. of the two fits the one with fewer control points is kept, after removing the knots
    ///    whose removal moves it by at most the tolerance less its deviation
    ///    ([`BSplineCurve::remove_all_removable_knots`]; the deviation is measured again).
    fn approximate_offset(
        &self,
        d: f64,
        tolerance: f64,
        scratch: &mut Vec<f64>,
    ) -> Result<(BSplineCurve, f64)> {
        let (lo, hi) = self.domain();
        let mut breaks: Vec<f64> = self.spans.iter().map(|s| s.0).collect();
        breaks.push(hi);
        let mut mult: Vec<usize> = vec![1; breaks.len() - 1];
        for (k, m) in mult.iter_mut().enumerate().skip(1) {
            *m = self.offset_multiplicity(k, d, scratch);
        }
        let max = |e: &[f64]| e.iter().fold(0.0_f64, |m, &x| m.max(x));
        let mut best: Option<(BSplineCurve, f64)> = None;
        let mut redistributed = false;
        loop {
            let spans = breaks.len() - 1;
            if spans * SAMPLES_PER_SPAN + 1 > MAX_SAMPLES {
                return Err(Error::TooLarge {
                    what: "samples of the exact offset (tolerance not reached)".into(),
                    size: spans * SAMPLES_PER_SPAN + 1,
                    max: MAX_SAMPLES,
                });
            }
            let fit = self.fit_offset(d, &breaks, &mult, scratch)?;
            let errs = self.span_deviations(&fit, &breaks, d, tolerance, scratch)?;
            let worst = max(&errs);
            if worst > tolerance {
                let mut nb = Vec::with_capacity(2 * breaks.len());
                let mut nm = Vec::with_capacity(2 * breaks.len());
                for k in 0..spans {
                    nb.push(breaks[k]);
                    nm.push(mult[k]);
                    if errs[k] > tolerance {
                        let h = breaks[k + 1] - breaks[k];
                        if h <= MIN_SPAN * (hi - lo) {
                            return Err(Error::InvalidArgument {
                                what: What::of(Arg::Tolerance, "offset tolerance"),
                                reason: format!(
                                    "{tolerance} is not reached even on spans of {h:e} near \
                                     t = {}: raise it above the rounding of the curve's \
                                     coordinates",
                                    breaks[k],
                                    tolerance = readable(&tolerance)
                                ),
                            });
                        }
                        let n = (errs[k] / (SPLIT_AIM * tolerance)).powf(0.25).ceil();
                        // clamped to [2, 16] first: the cast is exact
                        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                        let n = n.clamp(2.0, 16.0) as usize;
                        nb.extend((1..n).map(|i| breaks[k] + h * i as f64 / n as f64));
                        nm.extend(std::iter::repeat_n(1, n - 1));
                    }
                }
                nb.push(hi);
                breaks = nb;
                mult = nm;
                continue;
            }
            let mut done = (fit, worst);
            let (fewer, removed) = done.0.remove_all_removable_knots(tolerance - worst)?;
            if removed > 0 {
                let mut rb = fewer.knots().as_slice().to_vec();
                rb.dedup();
                let w = max(&self.span_deviations(&fewer, &rb, d, tolerance, scratch)?);
                if w <= tolerance {
                    done = (fewer, w);
                }
            }
            best = match best {
                Some(b) if b.0.control_points().len() <= done.0.control_points().len() => Some(b),
                _ => Some(done),
            };
            if redistributed {
                break;
            }
            redistributed = true;
            (breaks, mult) = redistribute(&breaks, &mult, &errs, SPLIT_AIM * tolerance);
        }
        Ok(best.expect("an accepted fit"))
    }

    /// The offset of a planar curve at signed distance `d` (positive to the left of the
    /// direction of travel) as a cubic B-spline within `tolerance` of `C(t) + d·N(t)`, on the
    /// curve's own parameters, with few control points: a least-squares cubic on breakpoints
    /// chosen adaptively (the curve's own, double where the offset's second derivative jumps;
    /// spans split where the deviation exceeds the tolerance, then spread anew so that each
    /// deviates about as much; removable knots removed), its deviation measured at 16 check
    /// points of every span and refined by golden-section search
    /// (`docs/theory/queries.md#offsets`). Cusps (`d·κ = 1`) are found by bisection between
    /// the curvature extrema and inflections, where the signed curvature is monotone; between
    /// two cusps where `1 − d·κ < 0` the offset runs backwards and forms a loop, cut out at the
    /// self-intersection of the parts before and after.
    ///
    /// ```
    /// use lekalo::{NurbsCurve, QueryCurve};
    /// // a circle of radius 2 offset inwards by 0.5 is the circle of radius 1.5
    /// let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0)?;
    /// let off = QueryCurve::from_nurbs(&c)?.offset(0.5, 1e-6)?;
    /// assert!(off.deviation <= 1e-6 && off.cusps.is_empty());
    /// let p = off.curve.eval(0.3)?;
    /// assert!((p[0].hypot(p[1]) - 1.5).abs() < 1e-6);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] unless planar; [`Error::NonFinite`] / [`Error::InvalidArgument`] for
    /// a bad distance or tolerance, or a curve with a stationary point (`C' = 0`, no normal);
    /// [`Error::InvalidArgument`] for a tolerance not reached on spans of `1e-10` of the domain
    /// (below the rounding of the coordinates); [`Error::TooLarge`] if the fit needs more
    /// than 2^21 samples.
    pub fn offset(&self, d: f64, tolerance: f64) -> Result<Offset> {
        if self.dim != 2 {
            return Err(Error::Dimension {
                what:
                    "curve to offset (an offset is taken in the plane: give a curve of 2-D points)"
                        .into(),
                expected: 2,
                got: self.dim,
            });
        }
        check_finite("offset distance", &[d])?;
        check_tolerance(What::of(Arg::Tolerance, "offset tolerance"), tolerance)?;
        // the offset's coordinates are known to about 1e-16 of the curve's size plus |d|
        let rounding = 1e-14 * (self.scale + d.abs());
        if tolerance < rounding {
            return Err(Error::InvalidArgument {
                what: What::of(Arg::Tolerance, "offset tolerance"),
                reason: format!(
                    "{tolerance} is below the rounding of the offset's coordinates (about \
                     1e-14 of the curve's size plus the distance: {rounding:e}); raise it",
                    tolerance = readable(&tolerance)
                ),
            });
        }
        let mut scratch = Vec::new();
        let (curve, worst) = self.approximate_offset(d, tolerance, &mut scratch)?;
        // cusps: 1 − dκ is monotone between the curvature extrema and inflections
        let mut breaks: Vec<f64> = self.spans.iter().map(|s| s.0).collect();
        breaks.push(self.domain().1);
        breaks.extend(self.curvature_extrema()?.iter().map(|e| e.t));
        breaks.extend(self.inflections()?);
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let h =
            |t: f64, scratch: &mut Vec<f64>| self.offset_point(t, d, scratch).map_or(0.0, |x| x.1);
        let mut cusps = Vec::new();
        for w in breaks.windows(2) {
            let (mut lo, mut hi) = (w[0], w[1]);
            let (flo, fhi) = (h(lo, &mut scratch), h(hi, &mut scratch));
            if !(flo * fhi < 0.0) {
                continue;
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if (h(mid, &mut scratch) < 0.0) == (flo < 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            cusps.push(0.5 * (lo + hi));
        }
        // loops: between consecutive cusps where the offset runs backwards
        let (lo, hi) = self.domain();
        let mut loops = Vec::new();
        let mut bounds = vec![lo];
        bounds.extend(&cusps);
        bounds.push(hi);
        for i in 1..bounds.len().saturating_sub(2) {
            let (c1, c2) = (bounds[i], bounds[i + 1]);
            if h(0.5 * (c1 + c2), &mut scratch) >= 0.0 {
                continue;
            }
            let before = sub_curve(&curve, bounds[i - 1], c1)?;
            let after = sub_curve(&curve, c2, bounds[i + 2])?;
            let hits = QueryCurve::from_bspline(&before)?
                .intersect(&QueryCurve::from_bspline(&after)?, tolerance)?;
            let best = hits
                .iter()
                .filter_map(|x| match x {
                    CurveIntersection::Point { t_a, t_b, .. } => Some((*t_a, *t_b)),
                    CurveIntersection::Overlap { .. } => None,
                })
                .min_by(|x, y| ((c1 - x.0) + (x.1 - c2)).total_cmp(&((c1 - y.0) + (y.1 - c2))));
            if let Some(cut) = best {
                let lims = ((bounds[i - 1], c1), (c2, bounds[i + 2]));
                loops.push(self.refine_cut(cut, lims, d, &mut scratch).unwrap_or(cut));
            }
        }
        let mut trimmed = Vec::new();
        let mut start = lo;
        for &(a, b) in &loops {
            if a > start {
                trimmed.push(sub_curve(&curve, start, a)?);
            }
            start = b;
        }
        if hi > start {
            trimmed.push(sub_curve(&curve, start, hi)?);
        }
        Ok(Offset {
            curve,
            trimmed,
            cusps,
            loops,
            deviation: worst,
        })
    }
}

/// Breakpoints for the same curve with the spans spread so that each is expected to deviate
/// by about `aim` (de Boor's equidistribution, *A Practical Guide to Splines*, ch. XII):
/// between every two breakpoints of multiplicity above one (kept), the density
/// `(e_k / aim)^{1/4} / h_k` of span `k` (the error of a cubic fit grows with the fourth power
/// of the span `h_k`) is integrated, and `⌈integral⌉` spans put at equal steps of it. `mult[k]`
/// is the multiplicity of `breaks[k]` (`mult[0]` unused); the result has the same form.
fn redistribute(breaks: &[f64], mult: &[usize], errs: &[f64], aim: f64) -> (Vec<f64>, Vec<usize>) {
    let last = breaks.len() - 1;
    let (mut nb, mut nm) = (vec![breaks[0]], vec![1]);
    let mut start = 0;
    for end in 1..=last {
        if end < last && mult[end] == 1 {
            continue;
        }
        // the spans start..end; a span far within the tolerance still counts a little
        let w: Vec<f64> = (start..end)
            .map(|k| (errs[k] / aim).powf(0.25).max(1e-3))
            .collect();
        let total: f64 = w.iter().sum();
        // the spans' weights are at most (e/aim)^{1/4} for errors below the tolerance (under
        // 1.2 a span) and at least 1e-3: total is a small positive multiple of the span count
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = (total.ceil() as usize).max(1);
        let step = total / n as f64;
        let (mut k, mut acc) = (0, 0.0);
        for i in 1..n {
            let target = step * i as f64;
            while k + 1 < w.len() && acc + w[k] < target {
                acc += w[k];
                k += 1;
            }
            let f = ((target - acc) / w[k]).clamp(0.0, 1.0);
            let (a, b) = (breaks[start + k], breaks[start + k + 1]);
            nb.push(a + f * (b - a));
            nm.push(1);
        }
        nb.push(breaks[end]);
        if end < last {
            nm.push(mult[end]);
        }
        start = end;
    }
    (nb, nm)
}

/// The part of `c` on `[a, b]` (inside its domain, `a < b`).
fn sub_curve(c: &BSplineCurve, a: f64, b: f64) -> Result<BSplineCurve> {
    let (lo, hi) = c.domain();
    let right = if a > lo { c.split_at(a)?.1 } else { c.clone() };
    Ok(if b < hi { right.split_at(b)?.0 } else { right })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{NurbsCurve, Points};

    #[test]
    fn offset_is_within_tolerance_and_at_distance() {
        let c = BSplineCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [2.0, -1.0], [4.0, 1.0], [5.0, 0.0]])
                .unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let off = q.offset(0.1, 1e-6).unwrap();
        assert!(off.deviation <= 1e-6, "{}", off.deviation);
        // every offset point is at distance |d| from the curve (where no loop is trimmed)
        for i in 0..=50 {
            let t = f64::from(i) / 50.0;
            let p = off.curve.eval(t).unwrap();
            let pr = q.project(&p).unwrap();
            assert!((pr.distance - 0.1).abs() <= 2e-6, "t {t}: {}", pr.distance);
        }
    }

    /// The exact offset point of `q` at `t` (independent of the fit's samples and checks).
    fn exact(q: &QueryCurve, t: f64, d: f64) -> [f64; 2] {
        q.offset_point(t, d, &mut Vec::new()).unwrap().0
    }

    #[test]
    fn offset_of_a_circle_is_the_circle_with_few_control_points() {
        // radius 2 offset inwards (left of the counter-clockwise circle) by 0.5: radius 1.5
        let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 2.0).unwrap();
        let q = QueryCurve::from_nurbs(&c).unwrap();
        for (d, r, tol, most) in [
            (0.5, 1.5, 1e-6, 72),
            (-0.5, 2.5, 1e-6, 80),
            (0.5, 1.5, 1e-4, 28),
            (0.5, 1.5, 1e-9, 360),
        ] {
            let off = q.offset(d, tol).unwrap();
            let n = off.curve.control_points().len();
            // measured: 70, 78, 26 and 348 (interpolating each quarter at 8, 16, ... offset
            // points, as a cubic with a knot at every point, needs at least 97)
            assert!(n <= most, "d {d}, tol {tol}: {n} control points");
            assert!(off.deviation <= tol, "{}", off.deviation);
            // radius at 20,000 points that are neither samples nor check points
            let mut worst = 0.0_f64;
            for i in 0..20_000 {
                let t = (f64::from(i) + 0.377) / 20_000.0;
                let p = off.curve.eval(t).unwrap();
                worst = worst.max((p[0].hypot(p[1]) - r).abs());
            }
            assert!(worst <= tol, "d {d}, tol {tol}: radius off by {worst}");
        }
    }

    #[test]
    fn offset_of_a_polyline_has_a_corner_where_the_base_has_one() {
        // an L of two lines: the offset jumps across the corner (the normal turns by 90°)
        let c = BSplineCurve::new(
            1,
            vec![0.0, 0.0, 0.5, 1.0, 1.0],
            Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]).unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let off = q.offset(0.1, 1e-9).unwrap();
        assert!(off.deviation <= 1e-9);
        // two straight pieces: a discontinuous cubic of 8 control points
        assert_eq!(off.curve.control_points().len(), 8);
        let (a, b) = (off.curve.eval(0.25).unwrap(), off.curve.eval(0.75).unwrap());
        assert!(
            (a[0] - 0.5).abs() < 1e-9 && (a[1] - 0.1).abs() < 1e-9,
            "{a:?}"
        );
        assert!(
            (b[0] - 0.9).abs() < 1e-9 && (b[1] - 0.5).abs() < 1e-9,
            "{b:?}"
        );
    }

    #[test]
    fn an_unreachable_tolerance_is_refused() {
        let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1e3).unwrap();
        let q = QueryCurve::from_nurbs(&c).unwrap();
        let e = q.offset(1.0, 1e-15).unwrap_err();
        assert!(e.to_string().contains("offset tolerance"), "{e}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
        /// Random planar cubics, offset to the side where `|d|·κ < 0.9` everywhere (no cusp):
        /// the deviation at 4,000 points that are neither samples nor check points of the fit
        /// is within the tolerance, and the reported deviation is the largest found.
        #[test]
        fn offset_is_within_tolerance_at_independent_points(
            ctrl in proptest::collection::vec(proptest::array::uniform2(-10.0..10.0_f64), 4..9),
            frac in -0.9..0.9_f64,
            tol_exp in -9..-3_i32,
        ) {
            let n = ctrl.len();
            let mut knots = vec![0.0; 4];
            knots.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
            knots.extend([1.0; 4]);
            let c = BSplineCurve::new(3, knots, Points::from_2d(&ctrl).unwrap()).unwrap();
            let q = QueryCurve::from_bspline(&c).unwrap();
            // the largest curvature and the smallest speed on a fine grid
            let (mut kmax, mut vmin) = (0.0_f64, f64::INFINITY);
            for i in 0..=2000 {
                let v = q.eval_global(f64::from(i) / 2000.0, 2, &mut Vec::new());
                let s = v[2].hypot(v[3]);
                vmin = vmin.min(s);
                kmax = kmax.max((v[2] * v[5] - v[3] * v[4]).abs() / (s * s * s));
            }
            // a regular curve, not too tightly curved: few spans reach the tolerance
            proptest::prop_assume!(vmin > 1.0 && kmax < 10.0);
            let d = frac / kmax;
            let tol = 10f64.powi(tol_exp);
            let off = q.offset(d, tol).unwrap();
            proptest::prop_assert!(off.cusps.is_empty());
            proptest::prop_assert!(off.deviation <= tol);
            for i in 0..4000 {
                let t = (f64::from(i) + 0.6180339887) / 4000.0;
                let e = dist(&off.curve.eval(t).unwrap(), &exact(&q, t, d));
                proptest::prop_assert!(e <= tol, "t {}: {} > {}", t, e, tol);
            }
        }
    }

    #[test]
    fn inner_offset_of_an_ellipse_has_cusps_and_loops() {
        // a stretched circle: radius of curvature b²/a = 0.25 at the ends of the long axis
        let c = NurbsCurve::circle(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap();
        let h = c.homogeneous();
        let mut data = h.control_points().as_slice().to_vec();
        for p in data.chunks_exact_mut(3) {
            p[0] *= 2.0; // x scaled: the ellipse x²/4 + y² = 1
        }
        let e = NurbsCurve::from_homogeneous(
            BSplineCurve::new(
                2,
                h.knots().as_slice().to_vec(),
                Points::from_flat(3, data).unwrap(),
            )
            .unwrap(),
        )
        .unwrap();
        let q = QueryCurve::from_nurbs(&e).unwrap();
        // inward (left of the counter-clockwise ellipse) by 0.6 > 0.25: swallowtails at both ends
        let off = q.offset(0.6, 1e-6).unwrap();
        assert_eq!(off.cusps.len(), 4, "{:?}", off.cusps);
        assert!(!off.loops.is_empty(), "loops {:?}", off.loops);
        // each cut is a self-intersection of the exact offset, to rounding
        for &(a, b) in &off.loops {
            let gap = dist(&exact(&q, a, 0.6), &exact(&q, b, 0.6));
            assert!(gap <= 1e-14, "loop ({a}, {b}): {gap}");
        }
    }
}
