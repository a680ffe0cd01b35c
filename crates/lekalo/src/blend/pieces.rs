//! The exact NURBS form of a blend spline, one segment at a time
//! (docs/theory/blending.md#blend-splines): for splines through millions of points, whose
//! [`BlendSpline`](crate::BlendSpline) (every segment a deformation of two shared local curves)
//! and whole NURBS would not fit in memory beside the points.

use crate::blend::local_curves::{LocalCurves, SharedCurve};
use crate::blend::spline::{
    blend_segment, elevated_homogeneous, exact_form, local_at, parameters_of, spline_deltas,
    BlendSplineOptions, Segment,
};
use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::numeric::progress::Progress;
use crate::points::{Points, PointsRef};
use crate::BezierForm;

/// The NURBS form of [`BlendSpline::to_nurbs`](crate::BlendSpline::to_nurbs), made segment by
/// segment on demand from the points (segments may be made on several threads at once): memory is three numbers a point (the `Δ_i`, the `s_i` and
/// each segment's weight scale), whatever the degree, and the same control points, knots and
/// weights, bit for bit.
///
/// The NURBS has degree `q` (the highest segment degree; lower ones are elevated), knots
/// `s_0` (`q + 1` times), each interior `s_i` (`q` times) and the last `s` (`q + 1` times), and
/// `q·m + 1` control points for `m` segments: segment `i` owns its `q + 1` homogeneous points
/// less the first, which it shares with segment `i − 1` ([`Self::segment_control`]).
///
/// ```
/// use lekalo::{BlendSpline, BlendSplineOptions, BlendSplinePieces, Parabolas, Points, Progress};
/// let pts = Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]])?;
/// let opts = BlendSplineOptions::default();
/// let pieces = BlendSplinePieces::new(pts.as_view(), &Parabolas, opts, &Progress::new())?;
/// let whole = BlendSpline::new(pts.as_view(), &Parabolas, opts)?.to_nurbs()?;
/// assert_eq!(pieces.to_nurbs(&Progress::new())?, whole);
/// assert_eq!(pieces.knot_count(), whole.knots().len());
/// # Ok::<(), lekalo::Error>(())
/// ```
pub struct BlendSplinePieces<'a> {
    points: PointsRef<'a>,
    local: &'a (dyn LocalCurves + Sync),
    options: BlendSplineOptions,
    deltas: Vec<f64>,
    params: Vec<f64>,
    degree: usize,
    /// The factor of each segment's homogeneous points that makes its first weight equal the
    /// previous segment's last (1 for the first segment).
    scales: Vec<f64>,
}

impl std::fmt::Debug for BlendSplinePieces<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BlendSplinePieces")
            .field("dim", &self.points.dim())
            .field("segments", &self.deltas.len())
            .field("degree", &self.degree)
            .finish_non_exhaustive()
    }
}

/// What the progress reports and cancellation name.
const WHAT: &str = "blend spline";

impl<'a> BlendSplinePieces<'a> {
    /// Checks every segment (as [`BlendSpline::new`](crate::BlendSpline::new) and
    /// [`BlendSpline::to_nurbs`](crate::BlendSpline::to_nurbs) do) and records the degree and
    /// the weight scales: two passes over the segments, reported to `progress` as
    /// `0 … 2m` for `m` segments.
    ///
    /// # Errors
    /// As [`BlendSpline::new`](crate::BlendSpline::new) and
    /// [`BlendSpline::to_nurbs`](crate::BlendSpline::to_nurbs); [`Error::Cancelled`] when
    /// `progress` is cancelled.
    pub fn new(
        points: PointsRef<'a>,
        local: &'a (dyn LocalCurves + Sync),
        options: BlendSplineOptions,
        progress: &Progress<'_>,
    ) -> Result<Self> {
        progress.step(WHAT, 0, 1)?;
        let deltas = spline_deltas(points, options)?;
        let params = parameters_of(&deltas);
        let mut pieces = BlendSplinePieces {
            points,
            local,
            options,
            deltas,
            params,
            degree: 0,
            scales: Vec::new(),
        };
        let m = pieces.deltas.len();
        let total = 2 * m as u64;
        let mut q = 0;
        pieces.for_each_form(progress, 0, total, |_, form| {
            q = q.max(form.degree());
            Ok(())
        })?;
        pieces.degree = q;
        let hd = points.dim() + 1;
        let mut scales = Vec::with_capacity(m);
        let mut prev_w = 1.0;
        pieces.for_each_form(progress, m as u64, total, |i, form| {
            let mut h = elevated_homogeneous(form, q, hd);
            let factor = if i > 0 { prev_w / h[hd - 1] } else { 1.0 };
            if i > 0 {
                h.iter_mut().for_each(|x| *x *= factor);
            }
            // the checks `NurbsCurve::from_homogeneous` makes on the whole form
            crate::points::check_homogeneous(&Points::from_raw(h.clone(), hd))?;
            prev_w = h[h.len() - 1];
            scales.push(factor);
            Ok(())
        })?;
        pieces.scales = scales;
        Ok(pieces)
    }

    /// Calls `f(i, form)` for every segment in order, each form made from the points and
    /// dropped after the call; reports `start + i + 1` of `total`.
    fn for_each_form(
        &self,
        progress: &Progress<'_>,
        start: u64,
        total: u64,
        mut f: impl FnMut(usize, &BezierForm) -> Result<()>,
    ) -> Result<()> {
        let n = self.points.len();
        let mut left = self.local(0)?;
        for i in 0..self.deltas.len() {
            let right = self.local((i + 1) % n)?;
            let seg = self.segment(i, &left, &right)?;
            f(i, &exact_form(&seg)?)?;
            left = right;
            progress.every(WHAT, start + i as u64 + 1, total)?;
        }
        Ok(())
    }

    /// The local curve at point `j` (see [`local_at`]).
    fn local(&self, j: usize) -> Result<Option<[SharedCurve; 2]>> {
        local_at(
            self.points,
            self.local,
            &self.deltas,
            self.options.closed,
            j,
        )
    }

    /// Segment `i` between the local curves `left` (at `P_i`) and `right` (at `P_{i+1}`).
    fn segment(
        &self,
        i: usize,
        left: &Option<[SharedCurve; 2]>,
        right: &Option<[SharedCurve; 2]>,
    ) -> Result<Segment> {
        blend_segment(
            self.points,
            &self.deltas,
            self.options.continuity,
            i,
            left,
            right,
        )
    }

    /// The NURBS degree `q`.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The continuity degree `k` of the options: the spline is `C^k` at its joins when the
    /// local curves declare [`Continuity::Parametric`](crate::Continuity::Parametric) (the
    /// parabolas do), `G^k` otherwise; as
    /// [`BlendSpline::continuity_degree`](crate::BlendSpline::continuity_degree).
    #[must_use]
    pub fn continuity_degree(&self) -> usize {
        self.options.continuity
    }

    /// The dimension of the points (the NURBS's homogeneous points have one more coordinate).
    #[must_use]
    pub fn dim(&self) -> usize {
        self.points.dim()
    }

    /// Number of segments `m`.
    #[must_use]
    pub fn segment_count(&self) -> usize {
        self.deltas.len()
    }

    /// Global parameters `s_0 … s_m` of the points.
    #[must_use]
    pub fn parameters(&self) -> &[f64] {
        &self.params
    }

    /// Number of knots, `q·m + q + 2`.
    #[must_use]
    pub fn knot_count(&self) -> usize {
        self.degree * self.segment_count() + self.degree + 2
    }

    /// Number of control points, `q·m + 1`.
    #[must_use]
    pub fn control_count(&self) -> usize {
        self.degree * self.segment_count() + 1
    }

    /// Knot `j < knot_count()` (see the type docs).
    #[must_use]
    pub fn knot(&self, j: usize) -> f64 {
        let q = self.degree.max(1);
        let m = self.segment_count();
        if j <= self.degree {
            return self.params[0];
        }
        // knots q + 1 … : s_1 (q times), …, s_m (q + 1 times)
        let i = ((j - self.degree - 1) / q).min(m - 1);
        self.params[i + 1]
    }

    /// The homogeneous control points (`(w·x, w, …)`, `dim + 1` numbers each) that segment `i`
    /// adds to the NURBS, into `out` (cleared first): all `q + 1` for the first segment, the
    /// last `q` for the others.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if `i` is not a segment; the errors of [`Self::new`] (which
    /// has checked every segment already).
    pub fn segment_control(&self, i: usize, out: &mut Vec<f64>) -> Result<()> {
        let m = self.segment_count();
        if i >= m {
            return Err(Error::InvalidArgument {
                what: "segment index".into(),
                reason: format!("{i} is not below the segment count {m}"),
            });
        }
        let n = self.points.len();
        let seg = self.segment(i, &self.local(i)?, &self.local((i + 1) % n)?)?;
        let hd = self.dim() + 1;
        let mut h = elevated_homogeneous(&exact_form(&seg)?, self.degree, hd);
        out.clear();
        if i > 0 {
            let factor = self.scales[i];
            h.iter_mut().for_each(|x| *x *= factor);
            out.extend_from_slice(&h[hd..]);
        } else {
            out.extend_from_slice(&h);
        }
        Ok(())
    }

    /// The whole NURBS (what [`BlendSpline::to_nurbs`](crate::BlendSpline::to_nurbs) returns);
    /// reports `0 … m`.
    ///
    /// # Errors
    /// As [`Self::segment_control`]; [`Error::Cancelled`].
    pub fn to_nurbs(&self, progress: &Progress<'_>) -> Result<NurbsCurve> {
        let m = self.segment_count();
        let knots: Vec<f64> = (0..self.knot_count()).map(|j| self.knot(j)).collect();
        let mut ctrl = Vec::with_capacity(self.control_count() * (self.dim() + 1));
        let mut buf = Vec::new();
        for i in 0..m {
            self.segment_control(i, &mut buf)?;
            ctrl.extend_from_slice(&buf);
            progress.every(WHAT, i as u64 + 1, m as u64)?;
        }
        let hom = BSplineCurve::new(self.degree, knots, Points::from_flat(self.dim() + 1, ctrl)?)?;
        NurbsCurve::from_homogeneous(hom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ArcParametrization, BlendSpline, CircularArcs, Parabolas, SplineParameters};
    use std::sync::atomic::AtomicBool;
    use std::sync::Mutex;

    fn wavy(n: usize) -> Points {
        let rows: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                let t = i as f64 * 0.7;
                [t + 0.3 * t.sin(), (1.3 * t).cos() * (1.0 + 0.1 * t)]
            })
            .collect();
        Points::from_2d(&rows).unwrap()
    }

    #[test]
    fn pieces_equal_the_whole_nurbs_bit_for_bit() {
        let arcs = CircularArcs::new(ArcParametrization::RationalQuadratic);
        let families: [&(dyn LocalCurves + Sync); 2] = [&Parabolas, &arcs];
        for n in [2, 3, 4, 9] {
            let pts = wavy(n);
            for local in families {
                for closed in [false, true] {
                    for k in [1, 2, 3] {
                        for parameters in [SplineParameters::Uniform, SplineParameters::ChordLength]
                        {
                            let opts = BlendSplineOptions {
                                continuity: k,
                                closed,
                                parameters,
                            };
                            let whole = BlendSpline::new(pts.as_view(), local, opts)
                                .and_then(|s| s.to_nurbs());
                            let pieces = BlendSplinePieces::new(
                                pts.as_view(),
                                local,
                                opts,
                                &Progress::new(),
                            )
                            .and_then(|p| p.to_nurbs(&Progress::new()));
                            let case = format!("n {n} closed {closed} k {k} {parameters:?}");
                            match (whole, pieces) {
                                (Ok(a), Ok(b)) => assert_eq!(a, b, "{case}"),
                                (Err(a), Err(b)) => assert_eq!(a, b, "{case}"),
                                (a, b) => panic!("{case}: {a:?} vs {b:?}"),
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn progress_reaches_the_total_and_cancel_stops() {
        let n = 3 * 4096;
        let pts = wavy(n);
        let seen = Mutex::new(Vec::new());
        let report = |d: u64, t: u64| seen.lock().unwrap().push((d, t));
        let progress = Progress::new().with_report(&report);
        let p = BlendSplinePieces::new(
            pts.as_view(),
            &Parabolas,
            BlendSplineOptions::default(),
            &progress,
        )
        .unwrap();
        let seen = seen.into_inner().unwrap();
        let total = 2 * p.segment_count() as u64;
        assert_eq!(seen.last(), Some(&(total, total)), "reaches the total");
        assert!(
            seen.windows(2).all(|w| w[0].0 <= w[1].0),
            "monotone: {seen:?}"
        );
        let stop = AtomicBool::new(true);
        let e = p.to_nurbs(&Progress::new().with_cancel(&stop)).unwrap_err();
        assert_eq!(e, Error::Cancelled { what: WHAT }, "cancelled");
    }
}
