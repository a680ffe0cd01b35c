//! The local curves that a blended spline is made of (document 001 §3;
//! docs/theory/blending.md#local-curves): a family ([`LocalCurves`]) gives, for three consecutive
//! points, two pieces through them: parabolas ([`Parabolas`]), circular arcs ([`CircularArcs`]) or
//! your own ([`FnLocalCurves`]).

use std::sync::Arc;

use crate::blend::deformation::ParametricCurve;
use crate::curve::bspline::BSplineCurve;
use crate::curve::nurbs::NurbsCurve;
use crate::error::{Error, Result};
use crate::points::Points;

/// A shared, thread-safe curve: the pieces of local curves.
pub type SharedCurve = Arc<dyn ParametricCurve + Send + Sync>;

/// The kind of continuity of a spline at its joins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Continuity {
    /// Parametric `C^k`: derivatives up to order `k` in the global parameter agree.
    Parametric,
    /// Geometric `G^k`: derivatives up to order `k` agree after a reparametrisation.
    Geometric,
}

/// A family of local curves through three consecutive points
/// (docs/theory/blending.md#local-curves).
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
                Points::from_flat(dim, ctrl)?,
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
    /// Angle the quadratic in `σ` through the three points' angles
    /// (docs/theory/blending.md#parametric-and-geometric-continuity): the spline is `C^k` in the
    /// global parameter (use [`SplineParameters::ChordLength`]). Collinear points fall back to the
    /// parabola.
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
/// cross-product formula in 3-D, in any dimension;
/// docs/theory/blending.md#circle-through-three-points).
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
                what: "derivative output ((order + 1) · dim)".into(),
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
pub(crate) fn line_piece(p: &[f64], q: &[f64], a: f64, b: f64) -> Result<SharedCurve> {
    let mut ctrl = p.to_vec();
    ctrl.extend_from_slice(q);
    Ok(Arc::new(BSplineCurve::new(
        1,
        vec![a, a, b, b],
        Points::from_flat(p.len(), ctrl)?,
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
                        what: "spline parameters for GlobalAngle arcs".into(),
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
                        what: "points for rational quadratic arcs".into(),
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
                        Points::from_flat(dim, ctrl)?,
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

    // the cross-product centre formula in 3D (docs/theory/blending.md#circle-through-three-points),
    // against the Gram solve
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
