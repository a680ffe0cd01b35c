//! Tests of `geometry.rs`: the arc length's gradient and the closest-point parameters'
//! derivatives against central differences of the values, the VJP the transpose of the JVP.

use super::{ArcLengthGradient, ClosestParameters};
use crate::error::Error;
use crate::points::{Points, PointsRef};
use crate::query::QueryCurve;
use crate::BSplineCurve;

fn cubic(dim: usize) -> BSplineCurve {
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.45, 0.7, 1.0, 1.0, 1.0, 1.0];
    let ctrl: Vec<f64> = (0..7 * dim)
        .map(|i| ((i * 7 + 3) as f64 * 0.61).sin() * 2.0 + (i / dim) as f64)
        .collect();
    BSplineCurve::new(3, knots, Points::from_flat(dim, ctrl).unwrap()).unwrap()
}

fn with_control(c: &BSplineCurve, ctrl: Vec<f64>) -> BSplineCurve {
    BSplineCurve::new(
        c.degree(),
        c.knots().as_slice().to_vec(),
        Points::from_flat(c.dim(), ctrl).unwrap(),
    )
    .unwrap()
}

/// `(f(x + h e_j) − f(x − h e_j)) / 2h` for every `j`.
fn central(f: impl Fn(&[f64]) -> Vec<f64>, x: &[f64], h: f64) -> Vec<Vec<f64>> {
    (0..x.len())
        .map(|j| {
            let (mut up, mut down) = (x.to_vec(), x.to_vec());
            up[j] += h;
            down[j] -= h;
            let (a, b) = (f(&up), f(&down));
            a.iter().zip(&b).map(|(p, q)| (p - q) / (2.0 * h)).collect()
        })
        .collect()
}

fn assert_rel(got: f64, want: f64, scale: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-7 * scale.max(1.0),
        "{what}: {got} against {want}"
    );
}

#[test]
fn arc_length_gradient_is_the_difference_of_the_lengths() {
    for dim in [1, 2, 3] {
        let c = cubic(dim);
        let g = ArcLengthGradient::new(&c).unwrap();
        let length = QueryCurve::from_bspline(&c).unwrap().length().unwrap();
        assert_eq!(g.length().to_bits(), length.to_bits(), "the query's length");
        let ctrl = c.control_points().as_slice().to_vec();
        let fd = central(
            |p| {
                let q = QueryCurve::from_bspline(&with_control(&c, p.to_vec())).unwrap();
                vec![q.length().unwrap()]
            },
            &ctrl,
            1e-5,
        );
        let scale = g.gradient().iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (j, col) in fd.iter().enumerate() {
            assert_rel(
                g.gradient()[j],
                col[0],
                scale,
                &format!("dim {dim}, entry {j}"),
            );
        }
        let t: Vec<f64> = (0..ctrl.len()).map(|i| (i as f64 * 0.3).cos()).collect();
        let jvp = g.jvp(&t).unwrap();
        let vjp = g.vjp(2.0).unwrap();
        let dot: f64 = vjp.iter().zip(&t).map(|(a, b)| a * b).sum();
        assert!((dot - 2.0 * jvp).abs() <= 1e-13 * dot.abs().max(1.0));
    }
}

#[test]
fn arc_length_gradient_of_a_segment_is_its_direction() {
    // a straight line of 4 control points along (3, 4): moving the end control point along it
    // lengthens the curve at rate 1, the inner ones not at all
    let pts: Vec<[f64; 2]> = (0..4).map(|i| [3.0 * i as f64, 4.0 * i as f64]).collect();
    let c = BSplineCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        Points::from_2d(&pts).unwrap(),
    )
    .unwrap();
    let g = ArcLengthGradient::new(&c).unwrap();
    assert!((g.length() - 15.0).abs() < 1e-12);
    let want = [-0.6, -0.8, 0.0, 0.0, 0.0, 0.0, 0.6, 0.8];
    for (a, b) in g.gradient().iter().zip(want) {
        assert!((a - b).abs() < 1e-12, "{:?}", g.gradient());
    }
    let e = g.jvp(&[1.0; 7]).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let e = g.vjp(f64::NAN).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
}

#[test]
fn closest_parameters_derivatives_are_differences_of_the_projections() {
    for dim in [2, 3] {
        let c = cubic(dim);
        // points near the curve, off it, and one beyond the start (its closest point the end)
        let mut x = Vec::new();
        for (k, &t) in [0.12, 0.4, 0.66, 0.9].iter().enumerate() {
            let p = c.eval(t).unwrap();
            x.extend(
                p.iter()
                    .enumerate()
                    .map(|(d, v)| v + 0.05 * ((k + d) as f64).cos()),
            );
        }
        let start = c.eval(0.0).unwrap();
        x.extend(start.iter().map(|v| v - 30.0));
        let cp = ClosestParameters::new(&c, &x).unwrap();
        let q = QueryCurve::from_bspline(&c).unwrap();
        let found = q
            .project_batch(PointsRef::from_flat(dim, &x).unwrap())
            .unwrap();
        for (t, f) in cp.params().iter().zip(&found) {
            assert_eq!(t.to_bits(), f.t.to_bits(), "the projection's parameter");
        }
        assert_eq!(cp.params()[4], 0.0, "beyond the start: the start");
        let ctrl = c.control_points().as_slice().to_vec();
        let params = |curve: &BSplineCurve, pts: &[f64]| {
            let q = QueryCurve::from_bspline(curve).unwrap();
            let f = q
                .project_batch(PointsRef::from_flat(dim, pts).unwrap())
                .unwrap();
            f.iter().map(|p| p.t).collect::<Vec<_>>()
        };
        let fd_ctrl = central(|p| params(&with_control(&c, p.to_vec()), &x), &ctrl, 1e-5);
        let fd_x = central(|p| params(&c, p), &x, 1e-5);
        for (j, col) in fd_ctrl.iter().enumerate() {
            let mut e = vec![0.0; ctrl.len()];
            e[j] = 1.0;
            let got = cp.jvp(Some(&e), None).unwrap();
            for (i, (g, w)) in got.iter().zip(col).enumerate() {
                assert_rel(*g, *w, 1.0, &format!("dim {dim}, control {j}, point {i}"));
            }
        }
        for (j, col) in fd_x.iter().enumerate() {
            let mut e = vec![0.0; x.len()];
            e[j] = 1.0;
            let got = cp.jvp(None, Some(&e)).unwrap();
            for (i, (g, w)) in got.iter().zip(col).enumerate() {
                assert_rel(
                    *g,
                    *w,
                    1.0,
                    &format!("dim {dim}, point coordinate {j}, point {i}"),
                );
            }
        }
        // the VJP is the transpose of the JVP
        let dc: Vec<f64> = (0..ctrl.len()).map(|i| (i as f64 * 0.7).sin()).collect();
        let dx: Vec<f64> = (0..x.len()).map(|i| (i as f64 * 0.4).cos()).collect();
        let g: Vec<f64> = (0..5).map(|i| 1.0 + i as f64).collect();
        let jvp = cp.jvp(Some(&dc), Some(&dx)).unwrap();
        let (gc, gx) = cp.vjp(&g, true, true).unwrap();
        let lhs: f64 = g.iter().zip(&jvp).map(|(a, b)| a * b).sum();
        let rhs: f64 = gc.unwrap().iter().zip(&dc).map(|(a, b)| a * b).sum::<f64>()
            + gx.unwrap().iter().zip(&dx).map(|(a, b)| a * b).sum::<f64>();
        assert!(
            (lhs - rhs).abs() <= 1e-12 * lhs.abs().max(1.0),
            "{lhs} {rhs}"
        );
        assert_eq!(cp.vjp(&g, false, false).unwrap(), (None, None));
    }
}

#[test]
fn closest_parameters_refuse_bad_input() {
    let c = cubic(2);
    let e = ClosestParameters::new(&c, &[0.0, 0.0, 1.0]).unwrap_err();
    assert!(matches!(e, Error::Dimension { .. }), "{e:?}");
    let e = ClosestParameters::new(&c, &[0.0, f64::NAN]).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let cp = ClosestParameters::new(&c, &[0.5, 0.5]).unwrap();
    let e = cp.jvp(Some(&[1.0; 3]), None).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let e = cp.vjp(&[1.0, 2.0], true, false).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
}
