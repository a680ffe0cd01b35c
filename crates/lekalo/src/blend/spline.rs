//! Interpolating spline curves by blending local three-point curves (document 001 §3;
//! docs/theory/blending.md#blend-splines);
//! the mathematics is documented on [`BlendSpline`].

use crate::blend::deformation::{BezierForm, Deformation, ParametricCurve};
use crate::blend::local_curves::{line_piece, Continuity, LocalCurves, SharedCurve};
use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::points::{Points, PointsRef};
use crate::Arg;

/// Global parameters `s_i` of the points (`Δ_i = s_{i+1} − s_i`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SplineParameters {
    /// `Δ_i = 1` (document 001 and Catmull–Rom).
    #[default]
    Uniform,
    /// `Δ_i = |P_{i+1} − P_i|`.
    ChordLength,
    /// `Δ_i = |P_{i+1} − P_i|^{1/2}`.
    Centripetal,
}

/// Options of [`BlendSpline::new`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlendSplineOptions {
    /// Continuity degree `k ≥ 1` (blending with `w_{k−1}`).
    pub continuity: usize,
    /// Closed curve (cyclic indices) or open.
    pub closed: bool,
    /// Global parameters of the points.
    pub parameters: SplineParameters,
}

impl Default for BlendSplineOptions {
    /// `k = 2`, open, uniform parameters.
    fn default() -> Self {
        BlendSplineOptions {
            continuity: 2,
            closed: false,
            parameters: SplineParameters::Uniform,
        }
    }
}

pub(crate) type Segment = Deformation<SharedCurve, SharedCurve>;

/// An interpolating spline curve built by blending local three-point curves (document 001 §3;
/// docs/theory/blending.md#blend-splines): the construction, the end rule and which continuity each
/// family of local curves gives are documented below.
///
/// # Construction
/// Points `P_0 … P_{n−1}` get global parameters `s_0 < s_1 < …` ([`SplineParameters`]) with
/// `Δ_i = s_{i+1} − s_i`. At every interior point `P_j` a **local curve** `L_j` passes through
/// `P_{j−1}, P_j, P_{j+1}`, in its own parameter `σ` taking the values `−Δ_{j−1}, 0, Δ_j` there
/// (so `σ = s − s_j`). It is given as two pieces: the *left* piece on `[−Δ_{j−1}, 0]`
/// (from `P_{j−1}` to `P_j`) and the *right* piece on `[0, Δ_j]` (from `P_j` to `P_{j+1}`).
///
/// The segment from `P_i` to `P_{i+1}` is the [`Deformation`] of the right piece of `L_i` into the
/// left piece of `L_{i+1}` (both run from `P_i` to `P_{i+1}`):
/// `p_i(u) = (1 − w_{k−1}(u)) L_i(u Δ_i) + w_{k−1}(u) L_{i+1}((u − 1) Δ_i)`, `u = (s − s_i)/Δ_i`.
/// By document 001 §2, segment `i` ends with the derivatives (to order `k`) of `L_{i+1}`'s left
/// piece and segment `i + 1` starts with those of `L_{i+1}`'s right piece.
///
/// # C^k or G^k: which one each construction has
/// - If the two pieces of every `L_j` are **one curve** of `σ` (the same function on both sides of
///   0), the spline is **C^k in the global parameter `s`**: [`Parabolas`] (the quadratic Lagrange
///   interpolant in `σ`; with uniform parameters and `k = 1` this is exactly **Catmull–Rom**,
///   docs/theory/blending.md#local-curves) and [`CircularArcs`] with
///   [`ArcParametrization::GlobalAngle`] (the angle on the circle is the quadratic in `σ` through
///   the three points' angles; docs/theory/blending.md#parametric-and-geometric-continuity).
/// - If each piece is parametrised on its own, the two sides of `P_j` are the same curve (the
///   same circle) traced at different speeds: the spline is only **G^k** (geometric continuity,
///   derivatives agree after a reparametrisation). This is document 001's own construction:
///   [`ArcParametrization::UniformAngle`] (angle linear on each arc; across `P_{j}` the l-th
///   derivatives differ by `(β Δ_{j−1} / (α Δ_j))^l` with `α, β` the angles of the arcs
///   `P_{j−1}P_j`, `P_jP_{j+1}`), and [`ArcParametrization::RationalQuadratic`] (each arc as a
///   rational quadratic Bezier, which makes the spline an exact NURBS). A rational quadratic arc
///   leaves its ends with speed `2r sin(θ/2)`, its chord; so with
///   [`SplineParameters::ChordLength`] the speeds match and the rational arc spline is `C¹` and
///   `G^k`, but not `C²` (tested).
///
/// [`BlendSpline::continuity`] reports which one holds; the tests measure exactly that.
///
/// # End segments and closed curves (not addressed by the source; our rule)
/// An open curve has no local curve at `P_0` and `P_{n−1}`: the first segment is the left piece
/// of `L_1` and the last the right piece of `L_{n−2}`, unblended (so the spline ends on the
/// three-point curves through the first and last three points, and the continuity at `P_1` and
/// `P_{n−2}` is the same as elsewhere). Two points give the straight segment. A closed curve uses
/// cyclic indices (`n ≥ 3` points, the segment `P_{n−1} → P_0` included; do not repeat `P_0`).
///
/// ```
/// use lekalo::{BlendSpline, BlendSplineOptions, Continuity, Parabolas, ParametricCurve, Points};
/// let pts = Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]])?;
/// let opts = BlendSplineOptions { continuity: 2, ..Default::default() };
/// let s = BlendSpline::new(pts.as_view(), &Parabolas, opts)?;
/// assert_eq!(s.continuity(), Continuity::Parametric); // C² in the uniform parameter
/// assert_eq!(s.eval(1.0)?, vec![1.0, 1.0]);              // interpolates P_1 at s_1 = 1
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// Document 001's example, circular arcs, as a closed curve exported to CAD as one NURBS:
///
/// ```
/// use lekalo::{ArcParametrization, BlendSpline, BlendSplineOptions, CircularArcs, Continuity};
/// use lekalo::{ParametricCurve, Points, SplineParameters};
/// let pts = Points::from_2d(&[[0.0, 0.0], [2.0, 0.0], [3.0, 1.5], [1.0, 2.5], [-0.5, 1.0]])?;
/// let arcs = CircularArcs::new(ArcParametrization::RationalQuadratic);
/// let opts = BlendSplineOptions {
///     continuity: 2,
///     closed: true,
///     parameters: SplineParameters::ChordLength,
/// };
/// let s = BlendSpline::new(pts.as_view(), &arcs, opts)?;
/// assert_eq!(s.continuity(), Continuity::Geometric); // G² (and C¹ with chord-length params)
/// let nurbs = s.to_nurbs()?;                          // exact: degree (2k − 1) + 2 + 2 = 7
/// assert_eq!(nurbs.degree(), 7);
/// let t = 0.37 * s.parameters()[5];
/// let (a, b) = (nurbs.eval(t)?, s.eval(t)?);
/// assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
/// # Ok::<(), lekalo::Error>(())
/// ```
#[derive(Clone)]
pub struct BlendSpline {
    dim: usize,
    params: Vec<f64>,
    segments: Vec<Segment>,
    continuity_degree: usize,
    continuity: Continuity,
    closed: bool,
}

impl std::fmt::Debug for BlendSpline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BlendSpline")
            .field("dim", &self.dim)
            .field("params", &self.params)
            .field("continuity_degree", &self.continuity_degree)
            .field("continuity", &self.continuity)
            .field("closed", &self.closed)
            .finish_non_exhaustive()
    }
}

impl BlendSpline {
    /// The spline through `points` with local curves from `local`.
    ///
    /// # Errors
    /// [`Error::TooFew`] with fewer than 2 points (3 when closed); [`Error::CoincidentPoints`]
    /// if two consecutive points coincide; [`Error::InvalidArgument`] if `continuity == 0`;
    /// errors of the local curves (e.g. [`CircularArcs`] with
    /// [`ArcParametrization::RationalQuadratic`] and an arc of 180° or more);
    /// [`Error::EndPointMismatch`] if user-supplied pieces do not run between the points.
    pub fn new(
        points: PointsRef<'_>,
        local: &dyn LocalCurves,
        options: BlendSplineOptions,
    ) -> Result<Self> {
        let deltas = spline_deltas(points, options)?;
        let n = points.len();
        let n_seg = deltas.len();
        let params = parameters_of(&deltas);
        // local curves L_j at the points that have both neighbours
        let locals = (0..n)
            .map(|j| local_at(points, local, &deltas, options.closed, j))
            .collect::<Result<Vec<_>>>()?;
        let mut segments = Vec::with_capacity(n_seg);
        for i in 0..n_seg {
            let j = (i + 1) % n;
            segments.push(blend_segment(
                points,
                &deltas,
                options.continuity,
                i,
                &locals[i],
                &locals[j],
            )?);
        }
        let dim = points.dim();
        Ok(BlendSpline {
            dim,
            params,
            segments,
            continuity_degree: options.continuity,
            continuity: local.continuity(),
            closed: options.closed,
        })
    }

    /// The continuity degree `k`.
    #[must_use]
    pub fn continuity_degree(&self) -> usize {
        self.continuity_degree
    }

    /// Whether the joins are `C^k` or only `G^k` (see the type docs).
    #[must_use]
    pub fn continuity(&self) -> Continuity {
        self.continuity
    }

    /// Whether the curve is closed.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Global parameters `s_0 = 0 < s_1 < … ` of the points (the segment ends; for a closed
    /// curve the last is the parameter of `P_0` again).
    #[must_use]
    pub fn parameters(&self) -> &[f64] {
        &self.params
    }

    /// Number of segments.
    #[must_use]
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// Segment `i` (from `P_i` to `P_{i+1}`) as a deformation in its local `u ∈ [0, 1]`, or `None`
    /// past the end.
    #[must_use]
    pub fn segment(&self, i: usize) -> Option<&Deformation<SharedCurve, SharedCurve>> {
        self.segments.get(i)
    }

    /// Derivatives of segment `i` at its local `u ∈ [0, 1]` with respect to the **global**
    /// parameter `s` (`d^l/ds^l = Δ_i^{−l} d^l/du^l`): the one-sided derivatives at the joins.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if `i` is not a segment; [`Error::ParameterOutOfDomain`];
    /// [`Error::NonFinite`] if a derivative overflows; [`Error::TooLarge`] for an order above
    /// [`MAX_DERIVATIVE_ORDER`](crate::MAX_DERIVATIVE_ORDER).
    pub fn segment_derivatives(&self, i: usize, u: f64, order: usize) -> Result<Points> {
        crate::blend::deformation::check_order(order)?;
        let seg = self.segments.get(i).ok_or_else(|| Error::InvalidArgument {
            what: "segment index".into(),
            reason: format!("{i} is not below the segment count {}", self.segments.len()),
        })?;
        let mut d = seg.eval_derivatives(u, order)?;
        let delta = self.params[i + 1] - self.params[i];
        let mut scale = 1.0;
        for l in 1..=order {
            scale /= delta;
            d.point_mut(l).iter_mut().for_each(|x| *x *= scale);
        }
        // Δ_i^{−l} overflows for a tiny segment and a high order (found by the `blending`
        // fuzz target): an error, never inf·0 = NaN inside an Ok
        crate::error::check_finite(
            "blend spline derivatives (overflow: the segment is too short for this order)",
            d.as_slice(),
        )?;
        Ok(d)
    }

    /// Derivatives at the global parameter `s` (right-sided at interior joins, left-sided at the
    /// end), rows `0 … order`.
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] unless `s_0 ≤ s ≤ s_last`.
    pub fn eval_derivatives(&self, s: f64, order: usize) -> Result<Points> {
        let (i, u) = self.locate(s)?;
        self.segment_derivatives(i, u, order)
    }

    fn locate(&self, s: f64) -> Result<(usize, f64)> {
        let (min, max) = (self.params[0], self.params[self.params.len() - 1]);
        if !(s >= min && s <= max) {
            return Err(Error::ParameterOutOfDomain { t: s, min, max });
        }
        let n_seg = self.segments.len();
        let i = self.params[1..n_seg].partition_point(|&p| p <= s);
        let u = ((s - self.params[i]) / (self.params[i + 1] - self.params[i])).clamp(0.0, 1.0);
        Ok((i, u))
    }

    /// The segments in exact Bezier form (see [`Deformation::to_nurbs`]).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if a local curve has no Bezier form (angle-parametrised arcs,
    /// closures).
    pub fn to_bezier_segments(&self) -> Result<Vec<BezierForm>> {
        self.segments.iter().map(exact_form).collect()
    }

    /// The whole spline as one NURBS curve in the global parameter `s`, exactly: the segments'
    /// (rational) Bezier forms elevated to a common degree `q` and joined with interior knots of
    /// multiplicity `q` at the `s_i` (a `C^0` knot structure carrying the exact `C^k`/`G^k` shape;
    /// knot removal can reduce it). Each rational segment is rescaled (a constant factor on its
    /// homogeneous points, which leaves it unchanged) so that shared end points have equal
    /// weights.
    ///
    /// # Errors
    /// As [`BlendSpline::to_bezier_segments`].
    pub fn to_nurbs(&self) -> Result<NurbsCurve> {
        let forms = self.to_bezier_segments()?;
        let q = forms.iter().map(BezierForm::degree).max().unwrap_or(1);
        let hd = self.dim + 1;
        let mut ctrl: Vec<f64> = Vec::new();
        let mut knots = vec![self.params[0]; q + 1];
        for (i, form) in forms.iter().enumerate() {
            let mut h = elevated_homogeneous(form, q, hd);
            if i > 0 {
                // scale so the first weight equals the previous segment's last
                let prev_w = ctrl[ctrl.len() - 1];
                let factor = prev_w / h[hd - 1];
                h.iter_mut().for_each(|x| *x *= factor);
                ctrl.extend_from_slice(&h[hd..]);
            } else {
                ctrl.extend_from_slice(&h);
            }
            let s = self.params[i + 1];
            let mult = if i + 1 == forms.len() { q + 1 } else { q };
            knots.extend(std::iter::repeat_n(s, mult));
        }
        let hom = BSplineCurve::new(q, knots, Points::from_flat(hd, ctrl)?)?;
        NurbsCurve::from_homogeneous(hom)
    }
}

/// The validated `Δ_i` of a spline through `points` (one per segment).
///
/// # Errors
/// As [`BlendSpline::new`]: too few points, `k = 0`, coincident consecutive points.
pub(crate) fn spline_deltas(
    points: PointsRef<'_>,
    options: BlendSplineOptions,
) -> Result<Vec<f64>> {
    let n = points.len();
    let min = if options.closed { 3 } else { 2 };
    if n < min {
        return Err(Error::TooFew {
            what: "spline points".into(),
            min,
            got: n,
        });
    }
    if options.continuity == 0 {
        return Err(Error::InvalidArgument {
            what: Arg::Continuity.into(),
            reason: "must be at least 1 (k = 1: tangent continuity with w_0(u) = u)".into(),
        });
    }
    let n_seg = if options.closed { n } else { n - 1 };
    let mut deltas = Vec::with_capacity(n_seg);
    for i in 0..n_seg {
        let j = (i + 1) % n;
        let chord = dot_diff(points.point(i), points.point(j)).sqrt();
        if chord <= f64::MIN_POSITIVE {
            return Err(Error::CoincidentPoints {
                first: i,
                second: j,
            });
        }
        deltas.push(match options.parameters {
            SplineParameters::Uniform => 1.0,
            SplineParameters::ChordLength => chord,
            SplineParameters::Centripetal => chord.sqrt(),
        });
    }
    Ok(deltas)
}

/// The global parameters `s_0 = 0, s_{i+1} = s_i + Δ_i`.
pub(crate) fn parameters_of(deltas: &[f64]) -> Vec<f64> {
    let mut params = Vec::with_capacity(deltas.len() + 1);
    params.push(0.0);
    for d in deltas {
        params.push(params[params.len() - 1] + d);
    }
    params
}

/// The local curve `L_j` (its left and right pieces), or `None` at the ends of an open curve.
pub(crate) fn local_at(
    points: PointsRef<'_>,
    local: &dyn LocalCurves,
    deltas: &[f64],
    closed: bool,
    j: usize,
) -> Result<Option<[SharedCurve; 2]>> {
    let n = points.len();
    let n_seg = deltas.len();
    if !(closed || (j > 0 && j + 1 < n)) {
        return Ok(None);
    }
    let jm = (j + n - 1) % n;
    let jp = (j + 1) % n;
    local
        .pieces(
            [points.point(jm), points.point(j), points.point(jp)],
            (deltas[(j + n_seg - 1) % n_seg], deltas[j % n_seg]),
        )
        .map(Some)
}

/// Segment `i` from the local curves at its ends (`li` at `P_i`, `lj` at `P_{i+1}`).
pub(crate) fn blend_segment(
    points: PointsRef<'_>,
    deltas: &[f64],
    continuity: usize,
    i: usize,
    li: &Option<[SharedCurve; 2]>,
    lj: &Option<[SharedCurve; 2]>,
) -> Result<Segment> {
    let (first, second) = match (li, lj) {
        (Some(li), Some(lj)) => (li[1].clone(), lj[0].clone()),
        (None, Some(lj)) => (lj[0].clone(), lj[0].clone()),
        (Some(li), None) => (li[1].clone(), li[1].clone()),
        (None, None) => {
            let j = (i + 1) % points.len();
            let line = line_piece(points.point(i), points.point(j), 0.0, deltas[i])?;
            (line.clone(), line)
        }
    };
    Deformation::new(first, second, continuity)
}

/// A segment's exact (rational) Bezier form.
///
/// # Errors
/// [`Error::InvalidArgument`] if its local curves have none.
pub(crate) fn exact_form(segment: &Segment) -> Result<BezierForm> {
    segment.bezier_form().ok_or_else(|| Error::InvalidArgument {
        what: "local curves".into(),
        reason: "the exact form needs polynomial or rational Bezier local curves \
                 (Parabolas or RationalQuadratic arcs)"
            .into(),
    })
}

/// The homogeneous control points (`hd = dim + 1` per point) of `form` elevated to degree `q`.
pub(crate) fn elevated_homogeneous(form: &BezierForm, q: usize, hd: usize) -> Vec<f64> {
    let n = form.to_nurbs();
    let h = n.homogeneous().control_points().as_slice();
    if form.degree() < q {
        crate::blend::bernstein::product(&vec![1.0; q - form.degree() + 1], h, hd)
    } else {
        h.to_vec()
    }
}

fn dot_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

impl ParametricCurve for BlendSpline {
    fn dim(&self) -> usize {
        self.dim
    }
    fn domain(&self) -> (f64, f64) {
        (self.params[0], self.params[self.params.len() - 1])
    }
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
        let d = self.eval_derivatives(t, order)?;
        if out.len() != d.as_slice().len() {
            return Err(Error::LengthMismatch {
                what: "derivative output ((order + 1) · dim)".into(),
                expected: d.as_slice().len(),
                got: out.len(),
            });
        }
        out.copy_from_slice(d.as_slice());
        Ok(())
    }
}
