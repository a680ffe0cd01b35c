//! Exact circles and circular arcs as NURBS (P&T §7.5, Algorithm A7.1) and the arc through
//! three points: every point at distance `r` from the centre within `1e-14·r` (plus the
//! rounding `ε·|centre|` of the coordinates themselves), end points, pieces, planes, errors.

use lekalo::{Error, NurbsCurve, Result};

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(p, q)| p * q).sum()
}

fn norm(v: &[f64]) -> f64 {
    dot(v, v).sqrt()
}

/// `v − (v·e) e` for a unit vector `e`.
fn reject(v: &[f64], e: &[f64]) -> Vec<f64> {
    let c = dot(v, e);
    v.iter().zip(e).map(|(p, q)| p - c * q).collect()
}

/// Distance from `p` to `c`.
fn dist(p: &[f64], c: &[f64]) -> f64 {
    p.iter()
        .zip(c)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt()
}

/// Largest deviation `| |C(t) − centre| − r |` over 2001 parameters.
fn max_radius_error(curve: &NurbsCurve, center: &[f64], r: f64) -> f64 {
    (0..=2000)
        .map(|k| {
            let p = curve.eval(f64::from(k) / 2000.0).unwrap();
            (dist(&p, center) - r).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn circles_are_exact_for_many_radii_and_centres() {
    let e1 = [1.0, 0.0];
    let e2 = [0.0, 1.0];
    for &r in &[1e-3, 0.5, 1.0, 7.25, 1e3, 1e6] {
        for center in [[0.0, 0.0], [0.3, -0.7], [1e3, -1e3], [-2.5e3, 1e3]] {
            let c = NurbsCurve::circle(&center, &e1, &e2, r).unwrap();
            let err = max_radius_error(&c, &center, r);
            // rounding of the coordinates themselves: ε·|centre| per coordinate
            let cn = norm(&center);
            let tol = 1e-14 * r + 4.0 * f64::EPSILON * cn;
            assert!(
                err <= tol,
                "r = {r}, centre {center:?}: error {err:e} > {tol:e}"
            );
            if cn <= r {
                assert!(err <= 1e-14 * r, "r = {r}: error {err:e} above 1e-14·r");
            }
            assert_eq!(c.eval(0.0).unwrap(), c.eval(1.0).unwrap(), "closed");
        }
    }
}

#[test]
fn arcs_of_every_sweep_in_3d_and_4d() {
    use std::f64::consts::PI;
    // an oblique frame in 3-D (axes not unit length), and one in 4-D
    let frames: [(Vec<f64>, Vec<f64>, Vec<f64>); 2] = [
        (
            vec![1e3, 2.0, -3.0],
            vec![2.0, -2.0, 1.0],
            vec![1.0, 2.0, 2.0],
        ),
        (
            vec![0.5, -1.0, 2.0, 3.0],
            vec![1.0, 1.0, 1.0, 1.0],
            vec![1.0, -1.0, 1.0, -1.0],
        ),
    ];
    for (center, x, y) in &frames {
        let xh: Vec<f64> = x.iter().map(|v| v / norm(x)).collect();
        let yh: Vec<f64> = y.iter().map(|v| v / norm(y)).collect();
        for &r in &[0.25, 3.0, 2e3] {
            for &(s, e, pieces) in &[
                (0.0, 0.5 * PI, 1),
                (0.3, 0.3 + 0.75 * PI, 2),
                (-1.0, 2.0, 2),
                (1.0, 1.0 + 1.5 * PI, 3),
                (0.0, 1.999 * PI, 4),
                (2.0, 2.0 - 1.25 * PI, 3),
                (-PI, PI, 4),
            ] {
                let c = NurbsCurve::circular_arc(center, x, y, r, s, e).unwrap();
                let err = max_radius_error(&c, center, r);
                let tol = 1e-14 * r + 4.0 * f64::EPSILON * norm(center);
                assert!(err <= tol, "r={r} [{s},{e}]: {err:e}");
                // end points at the requested angles
                for (t, angle) in [(0.0, s), (1.0, e)] {
                    let p = c.eval(t).unwrap();
                    for k in 0..center.len() {
                        let want = center[k] + r * (angle.cos() * xh[k] + angle.sin() * yh[k]);
                        assert!((p[k] - want).abs() <= tol * 4.0, "end {t} of [{s},{e}]");
                    }
                }
                // the curve stays in the plane of the frame
                let p = c.eval(0.37).unwrap();
                let d: Vec<f64> = p.iter().zip(center).map(|(a, b)| a - b).collect();
                let off = reject(&reject(&d, &xh), &yh);
                assert!(norm(&off) <= tol * 4.0, "plane");
                // pieces: ⌈|Δ|/90°⌉
                assert_eq!(c.control_points().len(), 2 * pieces + 1, "[{s},{e}]");
            }
        }
    }
}

#[test]
fn negative_sweep_runs_clockwise() {
    use std::f64::consts::FRAC_PI_2;
    let c = NurbsCurve::circular_arc(&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0, 0.0, -FRAC_PI_2)
        .unwrap();
    let p = c.eval(1.0).unwrap();
    assert!(p[0].abs() < 1e-16 && (p[1] + 1.0).abs() < 1e-16, "{p:?}");
    let mid = c.eval(0.5).unwrap();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(
        (mid[0] - h).abs() < 1e-15 && (mid[1] + h).abs() < 1e-15,
        "{mid:?}"
    );
}

#[test]
fn arc_through_points_hits_all_three() {
    // points on known circles, in several orders and dimensions
    type Case = (Vec<f64>, f64, Vec<f64>, Vec<f64>);
    let cases: Vec<Case> = vec![
        (vec![1.0, 2.0], 5.0, vec![1.0, 0.0], vec![0.0, 1.0]),
        (vec![1e3, -1e3], 1e3, vec![0.6, 0.8], vec![-0.8, 0.6]),
        (
            vec![1e3, 2e3, -5e2],
            0.75,
            vec![0.0, 0.6, 0.8],
            vec![1.0, 0.0, 0.0],
        ),
        (
            vec![1.0, 1.0, 1.0, 1.0, 1.0],
            2.0,
            vec![0.5, 0.5, 0.5, 0.5, 0.0],
            vec![0.0, 0.0, 0.0, 0.0, 1.0],
        ),
    ];
    let triples = [
        (0.0, 1.0, 2.0),
        (0.0, 3.0, 4.5),
        (1.0, 0.2, -2.0),
        (0.0, 3.0, 6.0),
        (2.0, 2.01, 2.02),
    ];
    for (center, r, x, y) in &cases {
        let at = |th: f64| -> Vec<f64> {
            (0..center.len())
                .map(|k| center[k] + r * (th.cos() * x[k] + th.sin() * y[k]))
                .collect()
        };
        for &(ta, tb, tc) in &triples {
            let (a, b, c) = (at(ta), at(tb), at(tc));
            let arc = NurbsCurve::arc_through_points(&a, &b, &c).unwrap();
            assert_eq!(arc.eval(0.0).unwrap(), a, "starts at a");
            assert_eq!(arc.eval(1.0).unwrap(), c, "ends at c");
            // relative error of the centre ~ ε / sin β: generous for the 0.02 rad triple
            let tol = 1e-14 * r + 8.0 * f64::EPSILON * norm(center);
            let tol = if tb - ta < 0.1 { tol * 1e3 } else { tol };
            let err = max_radius_error(&arc, center, *r);
            assert!(
                err <= tol,
                "centre {center:?}, r {r}, {ta},{tb},{tc}: {err:e}"
            );
            // b is on the arc: the closest sampled point converges to it
            let closest = (0..=4000)
                .map(|k| dist(&arc.eval(f64::from(k) / 4000.0).unwrap(), &b))
                .fold(f64::INFINITY, f64::min);
            // sampling step ≤ 2π r / 4000 · (speed variation ≤ 2)
            assert!(closest < 4.0 * r * 1e-3, "b off the arc: {closest}");
            // the sweep: the arc from a to c through b is the long one iff b is not
            // between them going the short way
            let d = arc.eval_derivatives(0.0, 1).unwrap();
            let tangent = d.point(1);
            let to_b: Vec<f64> = b.iter().zip(&a).map(|(p, q)| p - q).collect();
            assert!(dot(tangent, &to_b) > 0.0, "leaves a towards b");
        }
    }
}

#[test]
fn arc_through_points_rejects_degenerate_input() {
    let e = NurbsCurve::arc_through_points(&[0.0, 0.0], &[1.0, 1.0], &[2.0, 2.0]).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidArgument { reason, .. } if reason.contains("collinear")),
        "{e}"
    );
    // collinear within 1e-10 relative
    let e = NurbsCurve::arc_through_points(&[0.0, 0.0], &[1.0, 1e-11], &[2.0, 0.0]);
    assert!(matches!(e, Err(Error::InvalidArgument { .. })), "{e:?}");
    // 1e-9 is still a (huge) circle
    assert!(NurbsCurve::arc_through_points(&[0.0, 0.0], &[1.0, 1e-9], &[2.0, 0.0]).is_ok());
    for (a, b, c) in [
        ([0.0, 0.0], [0.0, 0.0], [1.0, 0.0]),
        ([0.0, 0.0], [1.0, 0.0], [1.0, 0.0]),
        ([1.0, 0.0], [0.0, 1.0], [1.0, 0.0]),
        ([3.0, 3.0], [3.0, 3.0], [3.0, 3.0]),
    ] {
        let e = NurbsCurve::arc_through_points(&a, &b, &c).unwrap_err();
        assert!(
            matches!(&e, Error::InvalidArgument { reason, .. } if reason.contains("coincide")),
            "{e}"
        );
    }
    assert!(matches!(
        NurbsCurve::arc_through_points(&[0.0], &[1.0], &[2.0]),
        Err(Error::Dimension { expected: 2, .. })
    ));
    assert!(matches!(
        NurbsCurve::arc_through_points(&[0.0, 1.0], &[1.0, 0.0, 0.0], &[2.0, 0.0]),
        Err(Error::Dimension { .. })
    ));
    assert!(matches!(
        NurbsCurve::arc_through_points(&[0.0, 1.0], &[1.0, f64::NAN], &[2.0, 0.0]),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        NurbsCurve::arc_through_points(&[-1e308, 0.0], &[0.0, 1e308], &[1e308, 0.0]),
        Err(Error::NonFinite { .. })
    ));
}

#[test]
fn circular_arc_rejects_bad_input() {
    let (c, x, y) = ([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]);
    let bad = |r: Result<NurbsCurve>, what: &str| {
        assert!(
            matches!(&r, Err(Error::InvalidArgument { what: w, .. }) if w.words() == what),
            "{what}: {r:?}"
        );
    };
    bad(
        NurbsCurve::circular_arc(&c, &x, &y, 0.0, 0.0, 1.0),
        "radius",
    );
    bad(
        NurbsCurve::circular_arc(&c, &x, &y, -1.0, 0.0, 1.0),
        "radius",
    );
    bad(
        NurbsCurve::circular_arc(&c, &x, &y, f64::INFINITY, 0.0, 1.0),
        "radius",
    );
    bad(
        NurbsCurve::circular_arc(&c, &x, &y, 1.0, 1.0, 1.0),
        "arc angles",
    );
    bad(
        NurbsCurve::circular_arc(&c, &x, &y, 1.0, 0.0, 6.3),
        "arc angles",
    );
    bad(
        NurbsCurve::circular_arc(&c, &[0.0, 0.0], &y, 1.0, 0.0, 1.0),
        "x_axis",
    );
    bad(
        NurbsCurve::circular_arc(&c, &x, &[0.0, 0.0], 1.0, 0.0, 1.0),
        "y_axis",
    );
    bad(
        NurbsCurve::circular_arc(&c, &x, &[1e-6, 1.0], 1.0, 0.0, 1.0),
        "y_axis",
    );
    // tiny non-orthogonality is accepted and removed
    let arc = NurbsCurve::circular_arc(&c, &x, &[1e-12, 1.0], 1.0, 0.0, 2.0).unwrap();
    assert!(max_radius_error(&arc, &c, 1.0) < 1e-14, "re-orthogonalised");
    // a full turn written as start + 2π is accepted and closed
    let s = 0.1;
    let arc = NurbsCurve::circular_arc(&c, &x, &y, 1.0, s, s + std::f64::consts::TAU).unwrap();
    assert_eq!(arc.eval(0.0).unwrap(), arc.eval(1.0).unwrap(), "closed");
    assert!(matches!(
        NurbsCurve::circular_arc(&c, &x, &y, 1.0, f64::NAN, 1.0),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        NurbsCurve::circular_arc(&[0.0], &[1.0], &[1.0], 1.0, 0.0, 1.0),
        Err(Error::Dimension { .. })
    ));
    assert!(matches!(
        NurbsCurve::circular_arc(&c, &[1.0, 0.0, 0.0], &y, 1.0, 0.0, 1.0),
        Err(Error::Dimension { .. })
    ));
    assert!(matches!(
        NurbsCurve::circle(&[1e308, 0.0], &x, &y, 1e308),
        Err(Error::NonFinite { .. })
    ));
}

#[test]
fn circles_with_a_normal_lie_in_their_plane() {
    for normal in [
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        [0.0, -3.0, 0.0],
        [1.0, 2.0, 3.0],
        [-1e-3, 5.0, 1e3],
    ] {
        for (centre, r) in [
            ([0.0, 0.0, 0.0], 1.0),
            ([1e3, -2.0, 7.0], 1e3),
            ([0.5, 0.5, 0.5], 0.01),
        ] {
            let c = NurbsCurve::circle_with_normal(centre, normal, r).unwrap();
            let nh: Vec<f64> = normal.iter().map(|x| x / norm(&normal)).collect();
            let tol = 1e-14 * r + 4.0 * f64::EPSILON * norm(&centre);
            assert!(
                max_radius_error(&c, &centre, r) <= tol,
                "radius, normal {normal:?}"
            );
            for k in 0..=20 {
                let p = c.eval(f64::from(k) / 20.0).unwrap();
                let d: Vec<f64> = p.iter().zip(&centre).map(|(a, b)| a - b).collect();
                assert!(dot(&d, &nh).abs() <= 2.0 * tol, "plane, normal {normal:?}");
            }
            // counter-clockwise about the normal: (C − centre) × C' points along n
            let d = c.eval_derivatives(0.1, 1).unwrap();
            let (p, v) = (d.point(0), d.point(1));
            let q = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
            let cross = [
                q[1] * v[2] - q[2] * v[1],
                q[2] * v[0] - q[0] * v[2],
                q[0] * v[1] - q[1] * v[0],
            ];
            assert!(dot(&cross, &nh) > 0.0, "orientation");
        }
    }
    assert!(matches!(
        NurbsCurve::circle_with_normal([0.0; 3], [0.0; 3], 1.0),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "normal"
    ));
    assert!(matches!(
        NurbsCurve::circle_with_normal([0.0; 3], [0.0, f64::NAN, 1.0], 1.0),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        NurbsCurve::circle_with_normal([0.0; 3], [0.0, 0.0, 1.0], -1.0),
        Err(Error::InvalidArgument { what, .. }) if what.words() == "radius"
    ));
}
