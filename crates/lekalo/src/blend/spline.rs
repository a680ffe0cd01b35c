//! Interpolating spline curves by blending local three-point curves (document 001, digest §B.3);
//! the mathematics is documented on [`BlendSpline`].

use std::sync::Arc;

use crate::blend::deformation::{BezierForm, Deformation, ParametricCurve};
use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::points::{Points, PointsRef};

/// A shared, thread-safe curve: the pieces of local curves.
pub type SharedCurve = Arc<dyn ParametricCurve + Send + Sync>;

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

/// The kind of continuity of a spline at its joins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Continuity {
    /// Parametric `C^k`: derivatives up to order `k` in the global parameter agree.
    Parametric,
    /// Geometric `G^k`: derivatives up to order `k` agree after a reparametrisation.
    Geometric,
}

/// A family of local curves through three consecutive points (digest §B.3).
pub trait LocalCurves {
    /// The local curve through `points[0], points[1], points[2]` taking them at the parameters
    /// `−delta.0, 0, delta.1`, as its left piece on `[−delta.0, 0]` and right piece on
    /// `[0, delta.1]`.
    ///
    /// # Errors
    /// Whatever makes the points unusable for this family.
    fn pieces(&self, points: [&[f64]; 3], delta: (f64, f64)) -> Result<[SharedCurve; 2]>;

    /// [`Continuity::Parametric`] only if the two pieces are restrictions of one smooth curve
    /// of `σ` (then the spline is `C^k`); [`Continuity::Geometric`] otherwise (the default).
    fn continuity(&self) -> Continuity {
        Continuity::Geometric
    }
}

/// Local curves given by a closure `f(points, delta) -> [left, right]` (see [`LocalCurves`]),
/// declaring the continuity they give.
pub struct FnLocalCurves<F> {
    f: F,
    continuity: Continuity,
}

impl<F> std::fmt::Debug for FnLocalCurves<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FnLocalCurves")
            .field("continuity", &self.continuity)
            .finish_non_exhaustive()
    }
}

impl<F: Fn([&[f64]; 3], (f64, f64)) -> Result<[SharedCurve; 2]>> FnLocalCurves<F> {
    /// Wraps the closure; `continuity` is what the pieces give (see
    /// [`LocalCurves::continuity`]).
    pub fn new(f: F, continuity: Continuity) -> Self {
        FnLocalCurves { f, continuity }
    }
}

impl<F: Fn([&[f64]; 3], (f64, f64)) -> Result<[SharedCurve; 2]>> LocalCurves for FnLocalCurves<F> {
    fn pieces(&self, points: [&[f64]; 3], delta: (f64, f64)) -> Result<[SharedCurve; 2]> {
        (self.f)(points, delta)
    }
    fn continuity(&self) -> Continuity {
        self.continuity
    }
}

/// Quadratic Lagrange interpolants `q(σ)` through `(−Δ_l, P_0), (0, P_1), (Δ_r, P_2)` (Newton
/// form `q = P_0 + f[0,1](σ + Δ_l) + f[0,1,2](σ + Δ_l) σ`). Both pieces are the same parabola,
/// so the spline is `C^k`; each piece is returned as a quadratic Bezier (B-spline on the
/// piece's interval), so [`BlendSpline::to_nurbs`] is exact with degree `2k + 1`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Parabolas;

impl LocalCurves for Parabolas {
    fn pieces(&self, points: [&[f64]; 3], delta: (f64, f64)) -> Result<[SharedCurve; 2]> {
        let [p0, p1, p2] = points;
        let (dl, dr) = delta;
        let dim = p0.len();
        // divided differences
        let f01: Vec<f64> = (0..dim).map(|d| (p1[d] - p0[d]) / dl).collect();
        let f12: Vec<f64> = (0..dim).map(|d| (p2[d] - p1[d]) / dr).collect();
        let f012: Vec<f64> = (0..dim).map(|d| (f12[d] - f01[d]) / (dl + dr)).collect();
        let q = |s: f64, d: usize| p0[d] + f01[d] * (s + dl) + f012[d] * (s + dl) * s;
        let dq = |s: f64, d: usize| f01[d] + f012[d] * (2.0 * s + dl);
        let piece = |a: f64, b: f64, pa: &[f64], pb: &[f64]| -> Result<SharedCurve> {
            // Bezier of the restriction to [a, b]: q(a), q(a) + q'(a)(b − a)/2, q(b), with the
            // end points taken from the data (q interpolates them; no rounding at the joins)
            let mut ctrl = Vec::with_capacity(3 * dim);
            ctrl.extend_from_slice(pa);
            ctrl.extend((0..dim).map(|d| q(a, d) + 0.5 * (b - a) * dq(a, d)));
            ctrl.extend_from_slice(pb);
            Ok(Arc::new(BSplineCurve::new(
                2,
                vec![a, a, a, b, b, b],
                Points::new(ctrl, dim)?,
            )?))
        };
        Ok([piece(-dl, 0.0, p0, p1)?, piece(0.0, dr, p1, p2)?])
    }
    fn continuity(&self) -> Continuity {
        Continuity::Parametric
    }
}

/// How each circular arc is parametrised (see [`BlendSpline`] for the continuity each gives).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ArcParametrization {
    /// Angle linear on each arc (document 001; spline `G^k`).
    #[default]
    UniformAngle,
    /// Each arc a rational quadratic Bezier with weights `1, cos(θ/2), 1` (P&T §7.5): the spline
    /// is an exact NURBS (`G^k`). Arcs must be shorter than a half circle.
    RationalQuadratic,
    /// Angle the quadratic in `σ` through the three points' angles (digest §B.3 note 2): the
    /// spline is `C^k` in the global parameter (use [`SplineParameters::ChordLength`]). Collinear
    /// points fall back to the parabola.
    GlobalAngle,
}

/// Circular arcs through three consecutive points (document 001's example): the circle through
/// `P_{j−1}, P_j, P_{j+1}`, traversed in that order; a straight line when the points are
/// collinear (`sin²` of the angle at `P_j` below [`CircularArcs::COLLINEAR_SIN2`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct CircularArcs {
    /// How the arcs are parametrised.
    pub parametrization: ArcParametrization,
}

impl CircularArcs {
    /// Points whose chords `a = P_0 − P_1`, `b = P_2 − P_1` satisfy
    /// `|a|²|b|² − (a·b)² ≤ COLLINEAR_SIN2 · |a|²|b|²` (the squared sine of the angle at `P_1`)
    /// are treated as collinear. Below this the radius would exceed ~10⁶ chords and the circle
    /// evaluation `O + r(…)` would lose 6 digits to cancellation; the sagitta ignored is below
    /// 10⁻⁶ of a chord.
    pub const COLLINEAR_SIN2: f64 = 1e-12;

    /// Arcs with the given parametrisation.
    #[must_use]
    pub fn new(parametrization: ArcParametrization) -> Self {
        CircularArcs { parametrization }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The circle through three points: centre, radius, an orthonormal pair `(e_1, e_2)` with
/// `P_0 = O + r e_1`, and the angles `0 < φ_1 < φ_2 < 2π` of `P_1, P_2` (traversal order).
/// `None` when collinear. Centre from the 2×2 Gram system
/// `[a·a a·b; a·b b·b] (x, y) = (|a|²/2, |b|²/2)`, `O = P_1 + x a + y b` (equivalent to the
/// digest's cross-product formula, §B.3 note 1, in any dimension).
struct Circle {
    centre: Vec<f64>,
    radius: f64,
    e1: Vec<f64>,
    e2: Vec<f64>,
    phi1: f64,
    phi2: f64,
}

fn circle_through(points: [&[f64]; 3]) -> Option<Circle> {
    let [p0, p1, p2] = points;
    let dim = p0.len();
    if dim < 2 {
        return None;
    }
    let a: Vec<f64> = (0..dim).map(|d| p0[d] - p1[d]).collect();
    let b: Vec<f64> = (0..dim).map(|d| p2[d] - p1[d]).collect();
    let (aa, bb, ab) = (dot(&a, &a), dot(&b, &b), dot(&a, &b));
    let det = aa * bb - ab * ab;
    if det <= CircularArcs::COLLINEAR_SIN2 * aa * bb {
        return None;
    }
    let x = 0.5 * (aa * bb - bb * ab) / det;
    let y = 0.5 * (bb * aa - aa * ab) / det;
    let centre: Vec<f64> = (0..dim).map(|d| p1[d] + x * a[d] + y * b[d]).collect();
    let rel = |p: &[f64]| -> Vec<f64> { (0..dim).map(|d| p[d] - centre[d]).collect() };
    let (r0, r1, r2) = (rel(p0), rel(p1), rel(p2));
    let radius = dot(&r1, &r1).sqrt();
    let e1: Vec<f64> = r0.iter().map(|v| v / radius).collect();
    let ortho = |v: &[f64]| -> Vec<f64> {
        let c = dot(v, &e1);
        v.iter().zip(&e1).map(|(x, e)| x - c * e).collect()
    };
    let mut e2 = ortho(&r2);
    if dot(&e2, &e2) < 1e-12 * radius * radius {
        e2 = ortho(&r1); // P_2 diametrically opposite P_0
    }
    let n2 = dot(&e2, &e2).sqrt();
    e2.iter_mut().for_each(|v| *v /= n2);
    // a second Gram–Schmidt pass ("twice is enough"): r2 is nearly parallel to e1 for nearly
    // collinear points, and the first pass leaves e2·e1 ~ ε·r/chord, which atan2 below would turn
    // into an angle error of that size (a position error of r times it)
    let again = ortho(&e2);
    let n2 = dot(&again, &again).sqrt();
    e2 = again.iter().map(|v| v / n2).collect();
    let angle = |v: &[f64], e2: &[f64]| {
        dot(v, e2)
            .atan2(dot(v, &e1))
            .rem_euclid(std::f64::consts::TAU)
    };
    let (mut phi1, mut phi2) = (angle(&r1, &e2), angle(&r2, &e2));
    if phi1 >= phi2 {
        // P_1 is not between P_0 and P_2 in this orientation: traverse the other way
        e2.iter_mut().for_each(|v| *v = -*v);
        phi1 = std::f64::consts::TAU - phi1;
        phi2 = std::f64::consts::TAU - phi2;
    }
    // small arc angles from their chords, 2·asin(c / 2r): accurate relative to the angle, so the
    // arcs meet the points to rounding of the chord even when r is 10⁶ chords
    let chord_angle = |p: &[f64], q: &[f64], approx: f64| {
        if approx < std::f64::consts::FRAC_PI_2 {
            let c = (0..dim).map(|d| (p[d] - q[d]).powi(2)).sum::<f64>().sqrt();
            2.0 * (0.5 * c / radius).min(1.0).asin()
        } else {
            approx
        }
    };
    let beta = chord_angle(p1, p2, phi2 - phi1);
    phi1 = chord_angle(p0, p1, phi1);
    phi2 = phi1 + beta;
    Some(Circle {
        centre,
        radius,
        e1,
        e2,
        phi1,
        phi2,
    })
}

/// An arc `c(σ) = O + r (cos θ e_1 + sin θ e_2)` on `[a, b]` with `θ(σ) = φ + u(σ)`,
/// `u(σ) = u_1 σ + u_2 σ²`, where `σ = 0` is the middle point `P_1 = O + r (cos φ e_1 + sin φ e_2)`
/// of the local circle.
///
/// Points are evaluated relative to `P_1` (the `anchor`), by the half-angle differences
/// `cos θ − cos φ = −2 sin(φ + u/2) sin(u/2)`, `sin θ − sin φ = 2 cos(φ + u/2) sin(u/2)`, so that
/// rounding scales with the chord, not with the radius: nearly collinear triples have radii of
/// up to ~10⁶ chords (see [`CircularArcs::COLLINEAR_SIN2`]), where `O + r e^{iθ}` would lose six
/// digits at the data points.
#[derive(Debug, Clone)]
struct ArcPiece {
    anchor: Vec<f64>,
    phi: f64,
    radius: f64,
    e1: Vec<f64>,
    e2: Vec<f64>,
    domain: (f64, f64),
    /// `[u_1, u_2]`.
    u: [f64; 2],
}

impl ParametricCurve for ArcPiece {
    fn dim(&self) -> usize {
        self.anchor.len()
    }
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    /// Derivatives of `e^{iθ(σ)}` from its Taylor coefficients: with
    /// `θ(σ + δ) = θ + θ' δ + θ_2 δ²`, `e^{iθ(σ+δ)} = e^{iθ} Σ e_n δ^n` where `e_0 = 1`,
    /// `(n + 1) e_{n+1} = iθ' e_n + 2iθ_2 e_{n−1}` (from `E' = f' E`), and the `l`-th derivative
    /// is `l! e_l e^{iθ}`. O(order · dim).
    fn eval_derivatives_into(&self, t: f64, order: usize, out: &mut [f64]) -> Result<()> {
        let (a, b) = self.domain;
        if !(t >= a && t <= b) {
            return Err(Error::ParameterOutOfDomain { t, min: a, max: b });
        }
        let dim = self.dim();
        crate::blend::deformation::check_order(order)?;
        if out.len() != (order + 1) * dim {
            return Err(Error::LengthMismatch {
                what: "derivative output ((order + 1) · dim)",
                expected: (order + 1) * dim,
                got: out.len(),
            });
        }
        let [u1, t2] = self.u;
        let u = (u1 + t2 * t) * t;
        let theta = self.phi + u;
        let speed = u1 + 2.0 * t2 * t;
        let (s, c) = theta.sin_cos();
        // complex Taylor coefficients (re, im)
        let (mut prev, mut cur) = ((0.0, 0.0), (1.0, 0.0));
        let mut factorial = 1.0;
        for l in 0..=order {
            if l > 0 {
                // (l) e_l = iθ' e_{l−1} + 2iθ_2 e_{l−2}
                let n = l as f64;
                let next = (
                    (-speed * cur.1 - 2.0 * t2 * prev.1) / n,
                    (speed * cur.0 + 2.0 * t2 * prev.0) / n,
                );
                prev = cur;
                cur = next;
                factorial *= n;
            }
            if l == 0 {
                // P_1 + r (e^{iθ} − e^{iφ}) by half-angle differences
                let sh = (0.5 * u).sin();
                let (sm, cm) = (self.phi + 0.5 * u).sin_cos();
                let (dc, ds) = (-2.0 * sm * sh, 2.0 * cm * sh);
                for d in 0..dim {
                    out[d] = self.anchor[d] + self.radius * (dc * self.e1[d] + ds * self.e2[d]);
                }
                continue;
            }
            // l! e_l e^{iθ}
            let re = factorial * (cur.0 * c - cur.1 * s);
            let im = factorial * (cur.0 * s + cur.1 * c);
            for d in 0..dim {
                out[l * dim + d] = self.radius * (re * self.e1[d] + im * self.e2[d]);
            }
        }
        Ok(())
    }
}

/// Straight piece from `p` at `a` to `q` at `b`, as a degree-1 B-spline.
fn line_piece(p: &[f64], q: &[f64], a: f64, b: f64) -> Result<SharedCurve> {
    let mut ctrl = p.to_vec();
    ctrl.extend_from_slice(q);
    Ok(Arc::new(BSplineCurve::new(
        1,
        vec![a, a, b, b],
        Points::new(ctrl, p.len())?,
    )?))
}

impl LocalCurves for CircularArcs {
    fn pieces(&self, points: [&[f64]; 3], delta: (f64, f64)) -> Result<[SharedCurve; 2]> {
        let (dl, dr) = delta;
        let Some(circle) = circle_through(points) else {
            return match self.parametrization {
                ArcParametrization::GlobalAngle => Parabolas.pieces(points, delta),
                _ => Ok([
                    line_piece(points[0], points[1], -dl, 0.0)?,
                    line_piece(points[1], points[2], 0.0, dr)?,
                ]),
            };
        };
        let (alpha, beta) = (circle.phi1, circle.phi2 - circle.phi1);
        let arc = |domain: (f64, f64), u: [f64; 2]| -> SharedCurve {
            Arc::new(ArcPiece {
                anchor: points[1].to_vec(),
                phi: alpha,
                radius: circle.radius,
                e1: circle.e1.clone(),
                e2: circle.e2.clone(),
                domain,
                u,
            })
        };
        match self.parametrization {
            // θ(σ) = α + u(σ): the middle point P_1 sits at angle φ_1 = α, σ = 0
            ArcParametrization::UniformAngle => Ok([
                arc((-dl, 0.0), [alpha / dl, 0.0]),
                arc((0.0, dr), [beta / dr, 0.0]),
            ]),
            ArcParametrization::GlobalAngle => {
                // Newton form θ(σ) = f01 (σ + Δ_l) + c (σ + Δ_l) σ through (−Δ_l, 0), (0, α),
                // (Δ_r, α + β)
                let f01 = alpha / dl;
                let c = (beta / dr - f01) / (dl + dr);
                let slope = |s: f64| f01 + c * (2.0 * s + dl);
                if slope(-dl) <= 0.0 || slope(dr) <= 0.0 {
                    return Err(Error::InvalidArgument {
                        what: "spline parameters for GlobalAngle arcs",
                        reason: format!(
                            "the angle on the circle through the points would not be monotone \
                             (arc angles {alpha:.3e}, {beta:.3e} for parameter steps {dl:.3e}, \
                             {dr:.3e}); use chord-length parameters or UniformAngle"
                        ),
                    });
                }
                // the same quadratic about σ = 0: θ(σ) = α + slope(0) σ + c σ²
                Ok([
                    arc((-dl, 0.0), [slope(0.0), c]),
                    arc((0.0, dr), [slope(0.0), c]),
                ])
            }
            ArcParametrization::RationalQuadratic => {
                let limit = std::f64::consts::PI * (1.0 - 1e-9);
                if alpha >= limit || beta >= limit {
                    return Err(Error::InvalidArgument {
                        what: "points for rational quadratic arcs",
                        reason: format!(
                            "an arc spans {:.1}°, but a rational quadratic Bezier arc must be \
                             shorter than 180°; add points or use UniformAngle",
                            alpha.max(beta).to_degrees()
                        ),
                    });
                }
                let rational = |from: f64, angle: f64, a: f64, b: f64| -> Result<SharedCurve> {
                    // P&T §7.5: middle control point on the bisector at distance r / cos(θ/2),
                    // middle weight cos(θ/2)
                    let w = (0.5 * angle).cos();
                    let mid = from + 0.5 * angle;
                    let dim = circle.centre.len();
                    let at = |phi: f64, rad: f64| -> Vec<f64> {
                        (0..dim)
                            .map(|d| {
                                circle.centre[d]
                                    + rad * (phi.cos() * circle.e1[d] + phi.sin() * circle.e2[d])
                            })
                            .collect()
                    };
                    let mut ctrl = at(from, circle.radius);
                    ctrl.extend(at(mid, circle.radius / w));
                    ctrl.extend(at(from + angle, circle.radius));
                    Ok(Arc::new(NurbsCurve::new(
                        2,
                        vec![a, a, a, b, b, b],
                        Points::new(ctrl, dim)?,
                        vec![1.0, w, 1.0],
                    )?))
                };
                // exact end points: the pieces must meet the data points to rounding
                Ok([
                    rational(0.0, alpha, -dl, 0.0)?,
                    rational(alpha, beta, 0.0, dr)?,
                ])
            }
        }
    }
    fn continuity(&self) -> Continuity {
        match self.parametrization {
            ArcParametrization::GlobalAngle => Continuity::Parametric,
            _ => Continuity::Geometric,
        }
    }
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

type Segment = Deformation<SharedCurve, SharedCurve>;

/// An interpolating spline curve built by blending local three-point curves (document 001,
/// digest §B.3): the construction, the end rule and which continuity each family of local
/// curves gives are documented below.
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
/// By §B.2, segment `i` ends with the derivatives (to order `k`) of `L_{i+1}`'s left piece and
/// segment `i + 1` starts with those of `L_{i+1}`'s right piece.
///
/// # C^k or G^k: which one each construction has
/// - If the two pieces of every `L_j` are **one curve** of `σ` (the same function on both sides of
///   0), the spline is **C^k in the global parameter `s`**: [`Parabolas`] (the quadratic Lagrange
///   interpolant in `σ`; with uniform parameters and `k = 1` this is exactly **Catmull–Rom**,
///   digest §B.3 note 3) and [`CircularArcs`] with [`ArcParametrization::GlobalAngle`] (the angle
///   on the circle is the quadratic in `σ` through the three points' angles; digest §B.3 note 2).
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
        let n = points.len();
        let min = if options.closed { 3 } else { 2 };
        if n < min {
            return Err(Error::TooFew {
                what: "spline points",
                min,
                got: n,
            });
        }
        if options.continuity == 0 {
            return Err(Error::InvalidArgument {
                what: "continuity degree k",
                reason: "must be at least 1 (k = 1: tangent continuity with w_0(u) = u)".into(),
            });
        }
        let dim = points.dim();
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
        let mut params = Vec::with_capacity(n_seg + 1);
        params.push(0.0);
        for d in &deltas {
            params.push(params[params.len() - 1] + d);
        }
        // local curves L_j at the points that have both neighbours
        let mut locals: Vec<Option<[SharedCurve; 2]>> = Vec::with_capacity(n);
        for j in 0..n {
            let has_both = options.closed || (j > 0 && j + 1 < n);
            if !has_both {
                locals.push(None);
                continue;
            }
            let jm = (j + n - 1) % n;
            let jp = (j + 1) % n;
            let pieces = local.pieces(
                [points.point(jm), points.point(j), points.point(jp)],
                (deltas[(j + n_seg - 1) % n_seg], deltas[j % n_seg]),
            )?;
            locals.push(Some(pieces));
        }
        let mut segments = Vec::with_capacity(n_seg);
        for i in 0..n_seg {
            let j = (i + 1) % n;
            let (first, second) = match (&locals[i], &locals[j]) {
                (Some(li), Some(lj)) => (li[1].clone(), lj[0].clone()),
                (None, Some(lj)) => (lj[0].clone(), lj[0].clone()),
                (Some(li), None) => (li[1].clone(), li[1].clone()),
                (None, None) => {
                    let line = line_piece(points.point(i), points.point(j), 0.0, deltas[i])?;
                    (line.clone(), line)
                }
            };
            segments.push(Deformation::new(first, second, options.continuity)?);
        }
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
            what: "segment index",
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
        self.segments
            .iter()
            .map(|s| {
                s.bezier_form().ok_or_else(|| Error::InvalidArgument {
                    what: "local curves",
                    reason: "the exact form needs polynomial or rational Bezier local curves \
                             (Parabolas or RationalQuadratic arcs)"
                        .into(),
                })
            })
            .collect()
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
            let n = form.to_nurbs();
            let h = n.homogeneous().control_points().as_slice();
            let mut h = if form.degree() < q {
                crate::blend::bernstein::product(&vec![1.0; q - form.degree() + 1], h, hd)
            } else {
                h.to_vec()
            };
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
        let hom = BSplineCurve::new(q, knots, Points::new(ctrl, hd)?)?;
        NurbsCurve::from_homogeneous(hom)
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
                what: "derivative output ((order + 1) · dim)",
                expected: d.as_slice().len(),
                got: out.len(),
            });
        }
        out.copy_from_slice(d.as_slice());
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn central_difference(c: &dyn ParametricCurve, t: f64, order: usize, h: f64) -> Vec<f64> {
        let dim = c.dim();
        let mut plus = vec![0.0; (order + 1) * dim];
        let mut minus = vec![0.0; (order + 1) * dim];
        c.eval_derivatives_into(t + h, order, &mut plus).unwrap();
        c.eval_derivatives_into(t - h, order, &mut minus).unwrap();
        let lo = (order - 1) * dim..order * dim;
        plus[lo.clone()]
            .iter()
            .zip(&minus[lo])
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect()
    }

    // the digest's cross-product centre formula (§B.3 note 1) in 3D, against the Gram solve
    #[test]
    fn circle_through_three_points_in_3d() {
        let (a, b, c) = ([1.0, 2.0, 0.5], [2.0, 0.0, 1.0], [0.0, -1.0, 2.0]);
        let circle = circle_through([&a, &b, &c]).unwrap();
        let cross = |u: [f64; 3], v: [f64; 3]| {
            [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ]
        };
        let sub = |u: [f64; 3], v: [f64; 3]| [u[0] - v[0], u[1] - v[1], u[2] - v[2]];
        let (aa, bb) = (sub(a, c), sub(b, c));
        let axb = cross(aa, bb);
        let n2: f64 = axb.iter().map(|x| x * x).sum();
        let (la, lb) = (dot(&aa, &aa), dot(&bb, &bb));
        let m = [
            lb * aa[0] - la * bb[0],
            lb * aa[1] - la * bb[1],
            lb * aa[2] - la * bb[2],
        ];
        // O = C + (|a|² b − |b|² a) × (a × b) / (2 |a × b|²)
        let q = cross([-m[0], -m[1], -m[2]], axb);
        for d in 0..3 {
            let o = c[d] + q[d] / (2.0 * n2);
            assert!((circle.centre[d] - o).abs() < 1e-14, "centre[{d}]");
        }
        assert!(
            0.0 < circle.phi1 && circle.phi1 < circle.phi2,
            "order of traversal"
        );
        // P_1 and P_2 at their angles
        for (phi, p) in [(circle.phi1, b), (circle.phi2, c)] {
            for d in 0..3 {
                let x = circle.centre[d]
                    + circle.radius * (phi.cos() * circle.e1[d] + phi.sin() * circle.e2[d]);
                assert!((x - p[d]).abs() < 1e-14, "point at {phi}");
            }
        }
        assert!(circle_through([&[0.0, 0.0], &[1.0, 1.0], &[3.0, 3.0]]).is_none());
        assert!(circle_through([&[0.0], &[1.0], &[3.0]]).is_none());
    }

    // both traversal orientations: P_1 counter-clockwise or clockwise between P_0 and P_2
    #[test]
    fn arcs_pass_through_the_points_in_order() {
        for sign in [1.0, -1.0] {
            let p = [[1.0, 0.0], [0.0, sign], [-1.0, 0.0]];
            let arcs = CircularArcs::default();
            let [left, right] = arcs.pieces([&p[0], &p[1], &p[2]], (1.0, 2.0)).unwrap();
            assert_eq!(left.domain(), (-1.0, 0.0));
            assert_eq!(right.domain(), (0.0, 2.0));
            let mid = left.eval(-0.5).unwrap();
            let s = std::f64::consts::FRAC_1_SQRT_2;
            assert!((mid[0] - s).abs() < 1e-15 && (mid[1] - sign * s).abs() < 1e-15);
            let end = right.eval(2.0).unwrap();
            assert!((end[0] + 1.0).abs() < 1e-15 && end[1].abs() < 1e-15);
        }
    }

    // arc pieces with a quadratic angle: derivatives against central differences of the
    // next-lower derivative
    #[test]
    fn arc_piece_derivatives() {
        // θ(σ) = 0.3 + 0.9 σ − 0.2 σ² on the circle O + 1.5 (cos θ e_1 + sin θ e_2)
        let (centre, radius, phi) = ([1.0, -2.0, 0.5], 1.5, 0.3_f64);
        let (e1, e2) = ([0.6, 0.8, 0.0], [0.0, 0.0, 1.0]);
        let on_circle = |theta: f64| -> Vec<f64> {
            (0..3)
                .map(|d| centre[d] + radius * (theta.cos() * e1[d] + theta.sin() * e2[d]))
                .collect()
        };
        let piece = ArcPiece {
            anchor: on_circle(phi),
            phi,
            radius,
            e1: e1.to_vec(),
            e2: e2.to_vec(),
            domain: (0.0, 2.0),
            u: [0.9, -0.2],
        };
        // the anchored half-angle form is the circle
        for k in 0..=8 {
            let t = f64::from(k) / 4.0;
            let q = piece.eval(t).unwrap();
            let expect = on_circle(phi + 0.9 * t - 0.2 * t * t);
            for d in 0..3 {
                assert!((q[d] - expect[d]).abs() < 1e-15, "point at {t}");
            }
        }
        for order in 1..=5 {
            let mut out = vec![0.0; (order + 1) * 3];
            piece.eval_derivatives_into(0.7, order, &mut out).unwrap();
            let fd = central_difference(&piece, 0.7, order, 1e-5);
            for d in 0..3 {
                assert!((out[order * 3 + d] - fd[d]).abs() < 1e-8, "order {order}");
            }
        }
        assert!(matches!(
            piece.eval(2.5),
            Err(Error::ParameterOutOfDomain { .. })
        ));
        assert!(matches!(
            piece.eval_derivatives_into(0.5, 1, &mut [0.0; 3]),
            Err(Error::LengthMismatch { .. })
        ));
    }

    // a nearly collinear triple (radius ~10⁵ chords): the arc pieces still meet the data points
    // to rounding of the chord, not of the radius
    #[test]
    fn nearly_collinear_arcs_hit_the_points() {
        let p = [[0.0, 0.0], [1.0, 1e-5], [2.0, 0.0]];
        let circle = circle_through([&p[0], &p[1], &p[2]]).unwrap();
        assert!(circle.radius > 1e4, "radius {}", circle.radius);
        for par in [
            ArcParametrization::UniformAngle,
            ArcParametrization::GlobalAngle,
        ] {
            let arcs = CircularArcs::new(par);
            let [left, right] = arcs.pieces([&p[0], &p[1], &p[2]], (1.0, 1.0)).unwrap();
            let checks = [
                (&left, -1.0, p[0]),
                (&left, 0.0, p[1]),
                (&right, 0.0, p[1]),
                (&right, 1.0, p[2]),
            ];
            for (piece, t, q) in checks {
                let got = piece.eval(t).unwrap();
                // 1e-12 of the extent (2): the radius of such a circle is itself only known to
                // ~1e-7 relative, which moves the sagitta (1e-5) by ~1e-12
                for d in 0..2 {
                    assert!((got[d] - q[d]).abs() < 2e-12, "{par:?} at {t}: {got:?}");
                }
            }
        }
    }

    // rational pieces are the arcs: every point at distance r from the centre
    #[test]
    fn rational_pieces_lie_on_the_circle() {
        let p = [[0.0, 0.0], [2.0, 1.0], [3.0, 3.0]];
        let circle = circle_through([&p[0], &p[1], &p[2]]).unwrap();
        let arcs = CircularArcs::new(ArcParametrization::RationalQuadratic);
        let pieces = arcs.pieces([&p[0], &p[1], &p[2]], (1.0, 1.0)).unwrap();
        for piece in &pieces {
            let (a, b) = piece.domain();
            assert!(piece.bezier_form().is_some(), "rational Bezier form");
            for step in 0..=10 {
                let q = piece.eval(a + (b - a) * f64::from(step) / 10.0).unwrap();
                let r =
                    ((q[0] - circle.centre[0]).powi(2) + (q[1] - circle.centre[1]).powi(2)).sqrt();
                assert!((r - circle.radius).abs() < 1e-14, "radius {r}");
            }
        }
    }
}
