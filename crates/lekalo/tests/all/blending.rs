//! Blending with jump-smoothing polynomials (document 001; docs/theory/blending.md): deformations,
//! splines through points, corner smoothing. Continuity is *measured*: derivatives up to order k
//! agree at the joins, derivative k + 1 in general does not.

use lekalo_testkit::config;

use lekalo::{
    ArcParametrization, BezierCurve, BlendSpline, BlendSplineOptions, CircularArcs, Continuity,
    CornerTransition, Deformation, Error, FnCurve, FnLocalCurves, NurbsCurve, Parabolas,
    ParametricCurve, Points, SharedCurve, SplineParameters,
};
use proptest::prelude::*;
use std::sync::Arc;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

// Relative agreement of two derivative vectors.
fn agree(a: &[f64], b: &[f64], rtol: f64) -> bool {
    dist(a, b) <= rtol * norm(a).max(norm(b)).max(1.0)
}

// Asserts C^k at a join: rows 0..=k agree to `rtol`, row k + 1 differs by more than `gap`
// (relative).
fn assert_ck(left: &Points, right: &Points, k: usize, rtol: f64, gap: f64, what: &str) {
    for l in 0..=k {
        assert!(
            agree(left.point(l), right.point(l), rtol),
            "{what}: derivative {l} differs: {:?} vs {:?}",
            left.point(l),
            right.point(l)
        );
    }
    let (a, b) = (left.point(k + 1), right.point(k + 1));
    assert!(
        dist(a, b) > gap * norm(a).max(norm(b)),
        "{what}: derivative {} unexpectedly agrees: {a:?} vs {b:?}",
        k + 1
    );
}

fn bezier(rows: &[[f64; 2]]) -> BezierCurve {
    BezierCurve::new(Points::from_2d(rows).unwrap()).unwrap()
}

fn spline(
    rows: &[[f64; 2]],
    local: &dyn lekalo::LocalCurves,
    k: usize,
    closed: bool,
    parameters: SplineParameters,
) -> BlendSpline {
    let pts = Points::from_2d(rows).unwrap();
    let opts = BlendSplineOptions {
        continuity: k,
        closed,
        parameters,
    };
    BlendSpline::new(pts.as_view(), local, opts).unwrap()
}

// ---------------------------------------------------------------- deformation (document 001 §2)

// Two cubics with common end points (first control legs differ).
fn cubic_pair(c: [f64; 8], e: [f64; 4]) -> (BezierCurve, BezierCurve) {
    let p1 = bezier(&[[c[0], c[1]], [c[2], c[3]], [c[4], c[5]], [c[6], c[7]]]);
    let p2 = bezier(&[
        [c[0], c[1]],
        [c[2] + 0.5 + e[0], c[3] - 0.7 + e[1]],
        [c[4] + e[2], c[5] - 0.6 - e[3]],
        [c[6], c[7]],
    ]);
    (p1, p2)
}

proptest! {
    #![proptest_config(config(48))]

    // Contact of order exactly k with p_1 at u = 0 and with p_2 at u = 1
    // (docs/theory/blending.md#why-the-index-is-k-1), for k = 1 … 4, and the exact Bezier form of
    // degree (2k − 1) + 3 agrees.
    #[test]
    fn deformation_has_contact_of_order_k(
        c in prop::array::uniform8(-3.0f64..3.0),
        e in prop::array::uniform4(0.0f64..1.0),
        k in 1usize..=4,
    ) {
        let (p1, p2) = cubic_pair(c, e);
        let p = Deformation::new(&p1, &p2, k).unwrap();
        let d0 = p.eval_derivatives(0.0, k + 1).unwrap();
        let d1 = p.eval_derivatives(1.0, k + 1).unwrap();
        let mut e1 = vec![0.0; 2 * (k + 2)];
        let mut e2 = vec![0.0; 2 * (k + 2)];
        p1.eval_derivatives_into(0.0, k + 1, &mut e1).unwrap();
        p2.eval_derivatives_into(1.0, k + 1, &mut e2).unwrap();
        let e1 = Points::from_flat(2, e1).unwrap();
        let e2 = Points::from_flat(2, e2).unwrap();
        assert_ck(&d0, &e1, k, 1e-12, 1e-6, "u = 0");
        assert_ck(&d1, &e2, k, 1e-12, 1e-6, "u = 1");
        let b = p.to_bezier().unwrap();
        prop_assert_eq!(b.degree(), 2 * k - 1 + 3);
        for step in 0..=10 {
            let u = f64::from(step) / 10.0;
            prop_assert!(dist(&b.eval(u).unwrap(), &ParametricCurve::eval(&p, u).unwrap()) < 1e-12);
        }
    }
}

// k = 1 is the linear blend (1 − u) p_1 + u p_2 (document 001 §2, the simplest case).
#[test]
fn k1_is_the_linear_blend() {
    let (p1, p2) = cubic_pair(
        [0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 3.0, 0.0],
        [0.1, 0.2, 0.3, 0.4],
    );
    let p = Deformation::new(&p1, &p2, 1).unwrap();
    for step in 0..=8 {
        let u = f64::from(step) / 8.0;
        let (a, b) = (p1.eval(u).unwrap(), p2.eval(u).unwrap());
        let expect: Vec<f64> = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (1.0 - u) * x + u * y)
            .collect();
        assert!(
            dist(&ParametricCurve::eval(&p, u).unwrap(), &expect) < 1e-15,
            "u = {u}"
        );
    }
}

// Curves on other domains are mapped to [0, 1]; derivatives scale by the domain length.
#[test]
fn deformation_of_a_closure_and_a_bezier() {
    // (t, t²) on [0, 2] and the straight line from (0,0) to (2,4) as a Bezier on [0, 1]
    let parabola = FnCurve::new(2, (0.0, 2.0), |t: f64, order: usize, out: &mut [f64]| {
        out.fill(0.0);
        out[..2].copy_from_slice(&[t, t * t]);
        if order >= 1 {
            out[2..4].copy_from_slice(&[1.0, 2.0 * t]);
        }
        if order >= 2 {
            out[5] = 2.0;
        }
        Ok(())
    })
    .unwrap();
    let line = bezier(&[[0.0, 0.0], [2.0, 4.0]]);
    let p = Deformation::new(&parabola, &line, 2).unwrap();
    let d = p.eval_derivatives(0.0, 2).unwrap();
    // parabola in u: (2u, 4u²): derivatives (2, 0), (0, 8)
    assert_eq!(d.point(1), &[2.0, 0.0]);
    assert_eq!(d.point(2), &[0.0, 8.0]);
    let d = p.eval_derivatives(1.0, 2).unwrap();
    assert_eq!(d.point(1), &[2.0, 4.0]);
    assert_eq!(d.point(2), &[0.0, 0.0]);
    // w_1(1/2) = 1/2: mid point is the average of (1, 1) and (1, 2)
    assert_eq!(ParametricCurve::eval(&p, 0.5).unwrap(), vec![1.0, 1.5]);
    assert!(matches!(p.to_bezier(), Err(Error::InvalidArgument { .. })));
}

// Golden: the blend of two circular arcs of document 001 (k = 1, 2, 3), values from an
// independent evaluation (Python: circles through (0,0),(1,1),(2,1) and (1,1),(2,1),(3,3),
// centres (1.5, −0.5) and (1.5, 2.5), radius √2.5, angle linear in u, Bernstein-sum w).
#[test]
fn golden_blend_of_two_arcs() {
    let pts = [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 3.0]];
    let golden = [
        (1, 0.25, [1.246_729_635_691_702_1, 1.030_361_153_979_864_3]),
        (2, 0.25, [1.246_729_635_691_702_1, 1.041_746_586_722_313_5]),
        (3, 0.1, [1.097_493_439_680_726_3, 1.028_550_917_628_095_1]),
    ];
    for (k, u, expect) in golden {
        let s = spline(
            &pts,
            &CircularArcs::default(),
            k,
            false,
            SplineParameters::Uniform,
        );
        let got = s.segment(1).unwrap();
        let p = ParametricCurve::eval(got, u).unwrap();
        assert!(dist(&p, &expect) < 1e-14, "k = {k}: {p:?}");
        // by symmetry the middle of the segment is (1.5, 1) for every k
        let mid = ParametricCurve::eval(got, 0.5).unwrap();
        assert!(dist(&mid, &[1.5, 1.0]) < 1e-14, "k = {k}: {mid:?}");
    }
}

// ---------------------------------------------------------------- splines (document 001 §3)

// docs/theory/blending.md#local-curves: parabolas at parameters (−1, 0, 1), (0, 1, 2) with k = 1
// give exactly the uniform Catmull–Rom spline.
#[test]
fn golden_parabolas_k1_are_catmull_rom() {
    let pts = [
        [0.0, 0.0],
        [1.0, 2.0],
        [3.0, 3.0],
        [4.0, 0.0],
        [6.0, 1.0],
        [7.0, -1.0],
    ];
    let s = spline(&pts, &Parabolas, 1, false, SplineParameters::Uniform);
    for i in 1..pts.len() - 2 {
        let (a, b, c, d) = (pts[i - 1], pts[i], pts[i + 1], pts[i + 2]);
        for step in 0..=10 {
            let u = f64::from(step) / 10.0;
            let cr: Vec<f64> = (0..2)
                .map(|j| {
                    0.5 * (2.0 * b[j]
                        + (-a[j] + c[j]) * u
                        + (2.0 * a[j] - 5.0 * b[j] + 4.0 * c[j] - d[j]) * u * u
                        + (-a[j] + 3.0 * b[j] - 3.0 * c[j] + d[j]) * u * u * u)
                })
                .collect();
            let got = s.eval(i as f64 + u).unwrap();
            assert!(
                dist(&got, &cr) < 1e-13,
                "segment {i}, u = {u}: {got:?} vs {cr:?}"
            );
        }
    }
    // and Catmull–Rom is exactly C¹, not C²
    assert_eq!(s.continuity(), Continuity::Parametric);
    for j in 1..s.segment_count() {
        let l = s.segment_derivatives(j - 1, 1.0, 2).unwrap();
        let r = s.segment_derivatives(j, 0.0, 2).unwrap();
        assert_ck(&l, &r, 1, 1e-13, 1e-3, "Catmull–Rom join");
    }
}

const ZIGZAG: [[f64; 2]; 7] = [
    [0.0, 0.0],
    [1.0, 1.5],
    [2.5, 1.0],
    [3.0, -0.5],
    [4.5, 0.2],
    [5.0, 2.0],
    [6.5, 1.5],
];

// Points on the ellipse (3 cos t, 2 sin t) at uneven angles 0°, 50°, 110°, 160°, 230°, 300°.
fn ellipse_loop() -> Vec<[f64; 2]> {
    [0.0_f64, 50.0, 110.0, 160.0, 230.0, 300.0]
        .iter()
        .map(|a| [3.0 * a.to_radians().cos(), 2.0 * a.to_radians().sin()])
        .collect()
}

// C^k constructions: derivatives in the global parameter agree up to k at every join,
// k + 1 does not; the points are interpolated. Open and closed, uniform and chord length.
#[test]
fn parametric_constructions_are_ck() {
    let arcs = CircularArcs::new(ArcParametrization::GlobalAngle);
    let cases: [(&dyn lekalo::LocalCurves, SplineParameters, &str); 4] = [
        (&Parabolas, SplineParameters::Uniform, "parabolas, uniform"),
        (
            &Parabolas,
            SplineParameters::ChordLength,
            "parabolas, chord",
        ),
        (
            &Parabolas,
            SplineParameters::Centripetal,
            "parabolas, centripetal",
        ),
        (
            &arcs,
            SplineParameters::ChordLength,
            "global-angle arcs, chord",
        ),
    ];
    for (local, params, name) in cases {
        for closed in [false, true] {
            for k in 1..=4 {
                let s = spline(&ZIGZAG, local, k, closed, params);
                assert_eq!(s.continuity(), Continuity::Parametric, "{name}");
                let n_seg = s.segment_count();
                assert_eq!(n_seg, if closed { 7 } else { 6 }, "{name}");
                for (i, p) in ZIGZAG.iter().enumerate() {
                    let at = s.eval(s.parameters()[i]).unwrap();
                    assert!(dist(&at, p) < 1e-12, "{name}: P_{i} not interpolated");
                }
                let joins: Vec<usize> = if closed {
                    (0..n_seg).collect()
                } else {
                    (1..n_seg).collect()
                };
                for j in joins {
                    let prev = (j + n_seg - 1) % n_seg;
                    let l = s.segment_derivatives(prev, 1.0, k + 1).unwrap();
                    let r = s.segment_derivatives(j, 0.0, k + 1).unwrap();
                    let what = format!("{name}, closed = {closed}, k = {k}, join {j}");
                    assert_ck(&l, &r, k, 1e-9, 1e-4, &what);
                }
            }
        }
    }
}

// Document 001's arcs (angle linear on each arc) are only G^k: across P_j the l-th derivatives
// differ by exactly ρ^l, ρ = (β Δ_{j−1}) / (α Δ_j), the ratio of the angular speeds (β/α with
// uniform parameters; docs/theory/blending.md#parametric-and-geometric-continuity).
#[test]
fn uniform_angle_arcs_are_gk_with_speed_ratio() {
    let s0 = spline(
        &ZIGZAG,
        &CircularArcs::default(),
        1,
        false,
        SplineParameters::Uniform,
    );
    assert_eq!(s0.continuity(), Continuity::Geometric);
    let mut tested = 0;
    for k in 1..=4 {
        let s = spline(
            &ZIGZAG,
            &CircularArcs::default(),
            k,
            false,
            SplineParameters::Uniform,
        );
        for j in 1..s.segment_count() {
            let l = s.segment_derivatives(j - 1, 1.0, k + 1).unwrap();
            let r = s.segment_derivatives(j, 0.0, k + 1).unwrap();
            // the circle through P_{j-1}, P_j, P_{j+1}: arc angles α (P_{j−1}P_j), β (P_jP_{j+1})
            let (alpha, beta) = arc_angles(ZIGZAG[j - 1], ZIGZAG[j], ZIGZAG[j + 1]);
            let rho = beta / alpha;
            if (rho - 1.0).abs() < 0.05 {
                continue; // nearly equal arcs: G^k and C^k cannot be told apart here
            }
            tested += 1;
            for order in 1..=k {
                let scaled: Vec<f64> = l
                    .point(order)
                    .iter()
                    .map(|x| x * rho.powi(i32::try_from(order).unwrap()))
                    .collect();
                assert!(
                    agree(&scaled, r.point(order), 1e-10),
                    "k = {k}, join {j}, order {order}"
                );
                // and therefore not C^k
                assert!(
                    !agree(l.point(order), r.point(order), 1e-3),
                    "k = {k}, join {j}"
                );
            }
            let scaled: Vec<f64> = l
                .point(k + 1)
                .iter()
                .map(|x| x * rho.powi(i32::try_from(k + 1).unwrap()))
                .collect();
            assert!(
                !agree(&scaled, r.point(k + 1), 1e-4),
                "k = {k}, join {j}: order k+1"
            );
        }
    }
    assert!(tested >= 8, "only {tested} joins with unequal arcs");
}

// Angles subtended by the arcs AB and BC of the circle through A, B, C (independent formula:
// the inscribed angle at the third point is half the central angle).
fn arc_angles(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> (f64, f64) {
    let angle_at = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        // angle at p between p→q and p→r
        let (u, v) = ([q[0] - p[0], q[1] - p[1]], [r[0] - p[0], r[1] - p[1]]);
        (u[0] * v[1] - u[1] * v[0])
            .abs()
            .atan2(u[0] * v[0] + u[1] * v[1])
    };
    // arc AB not containing C has central angle 2·∠ACB
    (2.0 * angle_at(c, a, b), 2.0 * angle_at(a, b, c))
}

// Rational-quadratic arcs: G^k (both sides osculate the same circle to order k), and the
// spline is exactly a NURBS of degree (2k − 1) + 4 that matches the evaluation.
#[test]
fn rational_arcs_are_gk_and_exact_nurbs() {
    let arcs = CircularArcs::new(ArcParametrization::RationalQuadratic);
    for (k, params) in [1, 2, 3].into_iter().flat_map(|k| {
        [
            (k, SplineParameters::Uniform),
            (k, SplineParameters::ChordLength),
        ]
    }) {
        for closed in [false, true] {
            // the closed zigzag would need an arc of 247°: use an uneven convex loop instead
            let ellipse = ellipse_loop();
            let pts: &[[f64; 2]] = if closed { &ellipse } else { &ZIGZAG };
            let s = spline(pts, &arcs, k, closed, params);
            assert_eq!(s.continuity(), Continuity::Geometric);
            let n_seg = s.segment_count();
            for j in 1..n_seg {
                // left side = the left piece of L_j, right side = its right piece
                let l = s.segment_derivatives(j - 1, 1.0, k).unwrap();
                let r = s.segment_derivatives(j, 0.0, k).unwrap();
                let seg_l = s.segment(j - 1).unwrap();
                let seg_r = s.segment(j).unwrap();
                let mut a = vec![0.0; 2 * (k + 1)];
                let mut b = vec![0.0; 2 * (k + 1)];
                seg_l
                    .second()
                    .eval_derivatives_into(0.0, k, &mut a)
                    .unwrap();
                seg_r.first().eval_derivatives_into(0.0, k, &mut b).unwrap();
                for order in 0..=k {
                    assert!(
                        agree(l.point(order), &a[2 * order..2 * order + 2], 1e-10),
                        "left {order}"
                    );
                    assert!(
                        agree(r.point(order), &b[2 * order..2 * order + 2], 1e-10),
                        "right {order}"
                    );
                }
                // tangent direction and (k ≥ 2) curvature agree: geometric continuity
                let (t1, t2) = (l.point(1), r.point(1));
                let cross = t1[0] * t2[1] - t1[1] * t2[0];
                assert!(
                    cross.abs() < 1e-10 * norm(t1) * norm(t2),
                    "tangents, join {j}"
                );
                let (ca, cb) = (
                    dist(&pts[j - 1], &pts[j]),
                    dist(&pts[j], &pts[(j + 1) % pts.len()]),
                );
                if params == SplineParameters::Uniform {
                    // end speeds are the chords 2 r sin(θ/2): equal only for equal chords
                    assert!(
                        (norm(t2) / norm(t1) - cb / ca).abs() < 1e-10,
                        "speed ratio, join {j}"
                    );
                    if (ca / cb - 1.0).abs() > 0.05 {
                        assert!(!agree(t1, t2, 1e-3), "speeds differ: G^k, not C^k");
                    }
                } else {
                    // a rational quadratic arc has end speed 2 r sin(θ/2) = its chord, so with
                    // chord-length parameters the speed is 1 on both sides: C¹ …
                    assert!(agree(t1, t2, 1e-10), "chord length: C¹, join {j}");
                    // … but not C² (the tangential accelerations differ)
                    if k >= 2 {
                        assert!(!agree(l.point(2), r.point(2), 1e-3), "not C², join {j}");
                    }
                }
                if k >= 2 {
                    let curv =
                        |d1: &[f64], d2: &[f64]| (d1[0] * d2[1] - d1[1] * d2[0]) / norm(d1).powi(3);
                    let (c1, c2) = (curv(l.point(1), l.point(2)), curv(r.point(1), r.point(2)));
                    assert!(
                        (c1 - c2).abs() < 1e-9 * c1.abs().max(1.0),
                        "curvature {c1} vs {c2}"
                    );
                }
            }
            let nurbs = s.to_nurbs().unwrap();
            assert_eq!(nurbs.degree(), 2 * k - 1 + 4);
            let (a, b) = nurbs.domain();
            assert_eq!((a, b), (0.0, s.parameters()[n_seg]));
            for step in 0..=60 {
                let t = b * (f64::from(step) / 60.0);
                let got = nurbs.eval(t).unwrap();
                let expect = s.eval(t).unwrap();
                assert!(
                    dist(&got, &expect) < 1e-12,
                    "k = {k}, t = {t}: {got:?} vs {expect:?}"
                );
            }
            assert!(nurbs.weights().iter().all(|&w| w > 0.0), "positive weights");
        }
    }
}

// Points on a circle: document 001's arc spline reproduces the circle exactly (both local
// curves of every segment are the same arc).
#[test]
fn golden_points_on_a_circle_give_the_circle() {
    let angles = [0.0_f64, 40.0, 100.0, 180.0, 250.0];
    let pts: Vec<[f64; 2]> = angles
        .iter()
        .map(|a| {
            [
                2.0 * a.to_radians().cos() + 1.0,
                2.0 * a.to_radians().sin() - 3.0,
            ]
        })
        .collect();
    for k in 1..=3 {
        let s = spline(
            &pts,
            &CircularArcs::default(),
            k,
            true,
            SplineParameters::Uniform,
        );
        for i in 0..s.segment_count() {
            let a0 = angles[i];
            let a1 = if i + 1 < angles.len() {
                angles[i + 1]
            } else {
                360.0
            };
            for step in 0..=4 {
                let u = f64::from(step) / 4.0;
                let a = (a0 + u * (a1 - a0)).to_radians();
                let expect = [2.0 * a.cos() + 1.0, 2.0 * a.sin() - 3.0];
                let got = s.eval(i as f64 + u).unwrap();
                assert!(dist(&got, &expect) < 1e-14, "k = {k}, segment {i}, u = {u}");
            }
        }
    }
}

// Collinear points: arcs degenerate to the straight line.
#[test]
fn collinear_points_give_straight_segments() {
    let pts = [[0.0, 0.0], [1.0, 1.0], [3.0, 3.0], [4.0, 4.0]];
    for p in [
        ArcParametrization::UniformAngle,
        ArcParametrization::RationalQuadratic,
    ] {
        let s = spline(
            &pts,
            &CircularArcs::new(p),
            2,
            false,
            SplineParameters::Uniform,
        );
        for step in 0..=30 {
            let t = f64::from(step) / 10.0;
            let q = s.eval(t).unwrap();
            assert!((q[0] - q[1]).abs() < 1e-14, "{p:?}: off the line at {t}");
        }
    }
}

// Parabola splines export exactly as a polynomial (unit-weight) NURBS of degree 2k + 1.
#[test]
fn parabola_spline_exports_exactly() {
    for k in 1..=3 {
        let s = spline(&ZIGZAG, &Parabolas, k, true, SplineParameters::ChordLength);
        let n = s.to_nurbs().unwrap();
        assert_eq!(n.degree(), 2 * k + 1);
        assert!(n.weights().iter().all(|&w| w == 1.0));
        let end = s.parameters()[s.segment_count()];
        for step in 0..=70 {
            let t = end * (f64::from(step) / 70.0);
            assert!(
                dist(&n.eval(t).unwrap(), &s.eval(t).unwrap()) < 1e-12,
                "t = {t}"
            );
        }
    }
    // angle-parametrised arcs have no exact form
    let s = spline(
        &ZIGZAG,
        &CircularArcs::default(),
        2,
        false,
        SplineParameters::Uniform,
    );
    assert!(matches!(s.to_nurbs(), Err(Error::InvalidArgument { .. })));
}

// User-supplied local curves: here straight pieces (a polyline), C^k trivially at the ends of
// each segment but a G^0 polyline overall, declared Geometric; the spline is the polyline.
#[test]
fn user_local_curves() {
    let lines = FnLocalCurves::new(
        |p: [&[f64]; 3], (dl, dr): (f64, f64)| -> lekalo::Result<[SharedCurve; 2]> {
            let seg = |a: &[f64], b: &[f64], t0: f64, t1: f64| -> lekalo::Result<SharedCurve> {
                let mut c = a.to_vec();
                c.extend_from_slice(b);
                let curve = lekalo::BSplineCurve::new(
                    1,
                    vec![t0, t0, t1, t1],
                    Points::from_flat(a.len(), c)?,
                )?;
                Ok(Arc::new(curve))
            };
            Ok([seg(p[0], p[1], -dl, 0.0)?, seg(p[1], p[2], 0.0, dr)?])
        },
        Continuity::Geometric,
    );
    let s = spline(&ZIGZAG, &lines, 3, false, SplineParameters::Uniform);
    let q = s.eval(2.5).unwrap();
    assert!(dist(&q, &[2.75, 0.25]) < 1e-15, "{q:?}");
    assert_eq!(s.to_nurbs().unwrap().degree(), 5 + 1);
}

// ---------------------------------------------------------------- corners

// Golden: the right-angle corner (−1,0) → (0,0) → (0,1) smoothed on the window
// [(−0.5, 0), (0, 0.5)] with k = 1; by hand at u = 1/4: w_1 = 5/32, q_1 = (−3/8, 5/64),
// q_2 = (−27/64, 1/8), p = (3/4) q_1 + (1/4) q_2 = (−99/256, 23/256).
#[test]
fn golden_smoothed_corner() {
    let before = bezier(&[[-1.0, 0.0], [0.0, 0.0]]);
    let after = bezier(&[[0.0, 0.0], [0.0, 1.0]]);
    let c = CornerTransition::new(&before, 0.5, &after, 0.5, 1).unwrap();
    let p = ParametricCurve::eval(&c, 0.25).unwrap();
    assert_eq!(p, vec![-99.0 / 256.0, 23.0 / 256.0]);
    assert_eq!(ParametricCurve::eval(&c, 0.5).unwrap(), vec![-0.25, 0.25]);
    assert_eq!(c.window_lengths(), (0.5, 0.5));
}

// Corner transition between two cubics: contact of order k with `before` at t_start and with
// `after` at t_end (derivatives scaled by the window lengths), for k = 1 … 4; with equal windows
// the composite curve is C^k.
#[test]
fn corner_transition_has_contact_k() {
    let before = bezier(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.5], [3.0, 0.0]]);
    let after = bezier(&[[3.0, 0.0], [3.5, 1.0], [3.2, 2.0], [4.0, 3.0]]);
    for k in 1..=4 {
        let c = CornerTransition::new(&before, 0.7, &after, 0.3, k).unwrap();
        let (h, h2) = c.window_lengths();
        assert!((h - h2).abs() < 1e-15, "equal windows {h} {h2}");
        let scale = |p: &Points| -> Points {
            let mut v = p.as_slice().to_vec();
            for l in 0..p.len() {
                for d in 0..2 {
                    v[2 * l + d] *= h.powi(i32::try_from(l).unwrap());
                }
            }
            Points::from_flat(2, v).unwrap()
        };
        let mut e = vec![0.0; 2 * (k + 2)];
        before.eval_derivatives_into(0.7, k + 1, &mut e).unwrap();
        let b = scale(&Points::from_flat(2, e.clone()).unwrap());
        assert_ck(
            &c.eval_derivatives(0.0, k + 1).unwrap(),
            &b,
            k,
            1e-12,
            1e-6,
            "start",
        );
        after.eval_derivatives_into(0.3, k + 1, &mut e).unwrap();
        let a = scale(&Points::from_flat(2, e).unwrap());
        assert_ck(
            &c.eval_derivatives(1.0, k + 1).unwrap(),
            &a,
            k,
            1e-12,
            1e-6,
            "end",
        );
    }
}

// ---------------------------------------------------------------- exact forms and errors

// A rational × rational deformation: two quarter-circle NURBS with common ends blend into a
// rational Bezier of degree (2k − 1) + 2 + 2.
#[test]
fn rational_deformation_is_exact() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let up = NurbsCurve::new(
        2,
        knots.clone(),
        Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap(),
        vec![1.0, w, 1.0],
    )
    .unwrap();
    // the other quarter circle through the same ends, centre (1, 1)
    let down = NurbsCurve::new(
        2,
        knots,
        Points::from_2d(&[[1.0, 0.0], [0.0, 0.0], [0.0, 1.0]]).unwrap(),
        vec![1.0, w, 1.0],
    )
    .unwrap();
    for k in 1..=3 {
        let p = Deformation::new(&up, &down, k).unwrap();
        let n = p.to_nurbs().unwrap();
        assert_eq!(n.degree(), 2 * k - 1 + 4);
        for step in 0..=20 {
            let u = f64::from(step) / 20.0;
            assert!(dist(&n.eval(u).unwrap(), &ParametricCurve::eval(&p, u).unwrap()) < 1e-14);
        }
        // NURBS derivatives (quotient rule) against central differences
        let d = p.eval_derivatives(0.3, 1).unwrap();
        let hstep = 1e-6;
        let fd: Vec<f64> = ParametricCurve::eval(&p, 0.3 + hstep)
            .unwrap()
            .iter()
            .zip(ParametricCurve::eval(&p, 0.3 - hstep).unwrap())
            .map(|(a, b)| (a - b) / (2.0 * hstep))
            .collect();
        assert!(dist(d.point(1), &fd) < 1e-8, "k = {k}");
    }
}

#[test]
fn errors() {
    let a = bezier(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]);
    let b = bezier(&[[0.0, 0.0], [1.0, -1.0], [2.0, 0.1]]);
    assert!(matches!(
        Deformation::new(&a, &b, 2),
        Err(Error::EndPointMismatch {
            end: "end (u = 1)",
            ..
        })
    ));
    assert!(matches!(
        Deformation::new(&a, &a, 0),
        Err(Error::InvalidArgument { .. })
    ));
    let line3 =
        BezierCurve::new(Points::from_3d(&[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]).unwrap()).unwrap();
    assert!(matches!(
        Deformation::new(&a, &line3, 1),
        Err(Error::Dimension { .. })
    ));
    let p = Deformation::new(&a, &a, 2).unwrap();
    assert!(matches!(
        p.eval_derivatives(1.5, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        p.eval_derivatives_into(0.5, 1, &mut [0.0; 3]),
        Err(Error::LengthMismatch { .. })
    ));
    // corners
    assert!(matches!(
        CornerTransition::new(&a, 0.5, &b, 0.5, 1),
        Err(Error::EndPointMismatch { .. })
    ));
    let c = bezier(&[[2.0, 0.0], [3.0, 1.0]]);
    assert!(matches!(
        CornerTransition::new(&a, 1.0, &c, 0.5, 1),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "window start t_start"
    ));
    assert!(matches!(
        CornerTransition::new(&a, 0.5, &c, 0.0, 1),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "window end t_end"
    ));
    assert!(matches!(
        CornerTransition::new(&a, 0.5, &c, 0.5, 0),
        Err(Error::InvalidArgument { .. })
    ));
    // closures
    let f = |_: f64, _: usize, out: &mut [f64]| {
        out.fill(f64::NAN);
        Ok(())
    };
    assert!(matches!(
        FnCurve::new(2, (1.0, 1.0), f),
        Err(Error::EmptyDomain { .. })
    ));
    assert!(matches!(
        FnCurve::new(0, (0.0, 1.0), f),
        Err(Error::Dimension { .. })
    ));
    let nan = FnCurve::new(2, (0.0, 1.0), f).unwrap();
    assert!(matches!(nan.eval(0.5), Err(Error::NonFinite { .. })));
    // splines
    let opts = BlendSplineOptions::default();
    let two = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0]]).unwrap();
    let closed = BlendSplineOptions {
        closed: true,
        ..opts
    };
    assert!(matches!(
        BlendSpline::new(two.as_view(), &Parabolas, closed),
        Err(Error::TooFew { min: 3, .. })
    ));
    let dup = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]]).unwrap();
    assert!(matches!(
        BlendSpline::new(dup.as_view(), &Parabolas, opts),
        Err(Error::CoincidentPoints {
            first: 1,
            second: 2
        })
    ));
    let zero_k = BlendSplineOptions {
        continuity: 0,
        ..opts
    };
    assert!(matches!(
        BlendSpline::new(two.as_view(), &Parabolas, zero_k),
        Err(Error::InvalidArgument { .. })
    ));
    // an arc of more than 180°: P_1 → P_2 the long way round the circle through the three
    let wide = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [0.5, 0.1], [2.0, 2.0]]).unwrap();
    let rational = CircularArcs::new(ArcParametrization::RationalQuadratic);
    assert!(matches!(
        BlendSpline::new(wide.as_view(), &rational, opts),
        Err(Error::InvalidArgument { .. })
    ));
    // non-monotone global angle: a tiny step next to a huge one with uniform parameters
    let global = CircularArcs::new(ArcParametrization::GlobalAngle);
    let skew = Points::from_2d(&[[0.0, 0.0], [0.01, 0.001], [5.0, 5.0], [10.0, 0.0]]).unwrap();
    assert!(matches!(
        BlendSpline::new(skew.as_view(), &global, opts),
        Err(Error::InvalidArgument { .. })
    ));
    let s = BlendSpline::new(two.as_view(), &Parabolas, opts).unwrap();
    assert!(matches!(
        s.eval(2.0),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        s.segment_derivatives(5, 0.0, 1),
        Err(Error::InvalidArgument { .. })
    ));
    assert_eq!(s.eval(0.5).unwrap(), vec![0.5, 0.0]);
    // absurd derivative orders are refused before allocating
    assert!(matches!(
        s.eval_derivatives(0.5, usize::MAX),
        Err(Error::TooLarge { .. })
    ));
    assert!(matches!(
        p.eval_derivatives(0.5, usize::MAX),
        Err(Error::TooLarge { .. })
    ));
    let before = bezier(&[[0.0, 0.0], [2.0, 0.0]]);
    let corner = CornerTransition::new(&before, 0.5, &c, 0.5, 1).unwrap();
    assert!(matches!(
        corner.eval_derivatives(0.5, usize::MAX),
        Err(Error::TooLarge { .. })
    ));
}

// Angle-parametrised arcs have no exact form: the Hermite approximation meets the tolerance,
// reproduces the derivatives up to order k at the nodes (so it keeps the spline's G^k joins),
// and its measured error is an honest estimate of the true one (checked on a 10x finer grid).
#[test]
fn approximation_of_arc_splines() {
    for k in 1..=3 {
        let s = spline(
            &ZIGZAG,
            &CircularArcs::default(),
            k,
            false,
            SplineParameters::Uniform,
        );
        let tol = 1e-7;
        let a = s.approximate(tol).unwrap();
        assert!(a.max_error() <= tol, "k = {k}");
        let c = a.curve();
        assert_eq!(c.degree(), 2 * k + 1);
        let end = s.parameters()[s.segment_count()];
        let mut worst = 0.0_f64;
        for step in 0..=2000 {
            let t = end * (f64::from(step) / 2000.0);
            worst = worst.max(dist(&c.eval(t).unwrap(), &s.eval(t).unwrap()));
        }
        assert!(worst <= 2.0 * tol, "k = {k}: true error {worst}");
        // derivatives at an interior node from the right
        let node = s.parameters()[2];
        let exact = s.eval_derivatives(node, k).unwrap();
        let approx = c.eval_derivatives(node, k).unwrap();
        for l in 0..=k {
            assert!(
                agree(exact.point(l), approx.point(l), 1e-9),
                "k = {k}, order {l}"
            );
        }
    }
    assert!(matches!(
        spline(&ZIGZAG, &Parabolas, 1, false, SplineParameters::Uniform).approximate(-1.0),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "tolerance"
    ));
}

// Corner transitions between single Bezier / rational Bezier pieces have an exact form.
#[test]
fn corner_transition_exact_forms() {
    let before = bezier(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.5], [3.0, 0.0]]);
    let after = bezier(&[[3.0, 0.0], [3.5, 1.0], [3.2, 2.0], [4.0, 3.0]]);
    let w = std::f64::consts::FRAC_1_SQRT_2;
    // quarter circle from (1, 0) to (0, 1), then a straight line on to (-2, 1), on [0, 2]
    let arc = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap(),
        vec![1.0, w, 1.0],
    )
    .unwrap();
    let line = lekalo::BSplineCurve::new(
        1,
        vec![0.0, 0.0, 2.0, 2.0],
        Points::from_2d(&[[0.0, 1.0], [-2.0, 1.0]]).unwrap(),
    )
    .unwrap();
    for k in 1..=3 {
        let c = CornerTransition::new(&before, 0.6, &after, 0.25, k).unwrap();
        let Some(lekalo::BezierForm::Polynomial(b)) = c.bezier_form() else {
            panic!("polynomial corner must have a Bezier form")
        };
        assert_eq!(b.degree(), 2 * k - 1 + (2 * k + 1).max(3));
        let r = CornerTransition::new(&arc, 0.5, &line, 1.0, k).unwrap();
        let Some(lekalo::BezierForm::Rational(n)) = r.bezier_form() else {
            panic!("rational corner must have a rational form")
        };
        for step in 0..=20 {
            let u = f64::from(step) / 20.0;
            let (e1, e2) = (c.eval(u).unwrap(), r.eval(u).unwrap());
            assert!(dist(&b.eval(u).unwrap(), &e1) < 1e-13, "k = {k}, u = {u}");
            assert!(dist(&n.eval(u).unwrap(), &e2) < 1e-13, "k = {k}, u = {u}");
        }
    }
}

proptest! {
    #![proptest_config(config(32))]

    // Random 3D polygons: parabola and global-angle arc splines interpolate the points, are C^k
    // in the chord-length parameter at every join (k + 1 generally not: only the lower orders
    // are asserted here, since random data can agree by chance), and commute with translations.
    #[test]
    fn random_3d_splines_are_ck_and_translation_invariant(
        steps in prop::collection::vec(prop::array::uniform3(-1.0f64..1.0), 4..8),
        k in 1usize..=3,
        closed in any::<bool>(),
        shift in prop::array::uniform3(-100.0f64..100.0),
    ) {
        // a walk with steps of length at least 0.3 (no coincident points)
        let mut pts = vec![[0.0, 0.0, 0.0]];
        for s in &steps {
            let n = norm(s);
            prop_assume!(n > 0.1);
            let last = pts[pts.len() - 1];
            pts.push([0.0; 3]);
            let len = 0.3 + n;
            let q = pts.len() - 1;
            for d in 0..3 {
                pts[q][d] = last[d] + s[d] / n * len;
            }
        }
        if closed {
            prop_assume!(dist(&pts[0], &pts[pts.len() - 1]) > 0.3);
        }
        let opts = BlendSplineOptions { continuity: k, closed, parameters: SplineParameters::ChordLength };
        let arcs = CircularArcs::new(ArcParametrization::GlobalAngle);
        for (local, may_fail) in [(&Parabolas as &dyn lekalo::LocalCurves, false), (&arcs, true)] {
            let p = Points::from_3d(&pts).unwrap();
            let Ok(s) = BlendSpline::new(p.as_view(), local, opts) else {
                // GlobalAngle refuses non-monotone angle parametrisations; parabolas never fail
                prop_assert!(may_fail);
                continue;
            };
            for (i, q) in pts.iter().enumerate() {
                prop_assert!(dist(&s.eval(s.parameters()[i]).unwrap(), q) < 1e-12 * (1.0 + norm(q)));
            }
            let n_seg = s.segment_count();
            let first = usize::from(!closed);
            for j in first..n_seg {
                let prev = (j + n_seg - 1) % n_seg;
                let l = s.segment_derivatives(prev, 1.0, k).unwrap();
                let r = s.segment_derivatives(j, 0.0, k).unwrap();
                for order in 0..=k {
                    prop_assert!(agree(l.point(order), r.point(order), 1e-8), "join {}, order {}", j, order);
                }
            }
            let moved: Vec<[f64; 3]> = pts.iter().map(|p| [p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]]).collect();
            let m = BlendSpline::new(Points::from_3d(&moved).unwrap().as_view(), local, opts).unwrap();
            let end = s.parameters()[n_seg];
            for step in 0..=12 {
                let t = end * (f64::from(step) / 12.0);
                let a = s.eval(t).unwrap();
                // chord lengths of the moved points differ in the last bits
                let b = m.eval(t.min(m.parameters()[n_seg])).unwrap();
                for d in 0..3 {
                    prop_assert!((a[d] + shift[d] - b[d]).abs() < 1e-9 * (1.0 + shift[d].abs()));
                }
            }
        }
    }
}

// Golden: spline through (0,0), (1,2), (3,3), (4,0) with parabolas at uniform parameters, the
// middle segment at u = 3/10; exact rationals computed independently (Python `fractions`:
// Lagrange parabolas at (−1, 0, 1) and (0, 1, 2), w_1 = 3u² − 2u³, w_2 = 10u³ − 15u⁴ + 6u⁵).
#[test]
fn golden_parabola_spline_values() {
    let pts = [[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]];
    let golden = [
        (2, [38_509.0 / 25_000.0, 30_913.0 / 12_500.0]),
        (3, [3_823_117.0 / 2_500_000.0, 12_281_851.0 / 5_000_000.0]),
    ];
    for (k, expect) in golden {
        let s = spline(&pts, &Parabolas, k, false, SplineParameters::Uniform);
        let got = s.eval(1.3).unwrap();
        assert!(
            dist(&got, &expect) < 1e-14,
            "k = {k}: {got:?} vs {expect:?}"
        );
    }
}

// Mixed local curves (a collinear triple gives straight pieces of degree 1 next to rational
// arcs): the segments are elevated to a common degree and the NURBS still matches.
#[test]
fn mixed_degrees_export_exactly() {
    let pts = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 1.0], [3.5, 2.5]];
    let arcs = CircularArcs::new(ArcParametrization::RationalQuadratic);
    for k in 1..=2 {
        let s = spline(&pts, &arcs, k, false, SplineParameters::ChordLength);
        let forms = s.to_bezier_segments().unwrap();
        let degrees: Vec<usize> = forms.iter().map(lekalo::BezierForm::degree).collect();
        assert!(degrees.iter().min() < degrees.iter().max(), "{degrees:?}");
        let n = s.to_nurbs().unwrap();
        let end = s.parameters()[s.segment_count()];
        for step in 0..=40 {
            let t = end * (f64::from(step) / 40.0);
            assert!(
                dist(&n.eval(t).unwrap(), &s.eval(t).unwrap()) < 1e-12,
                "k = {k}, t = {t}"
            );
        }
    }
}
