//! Tests of `geometry_knots.rs`: the arc length's and the closest parameters' derivatives in
//! the knots against central differences of the values (an interior knot, a double knot moved
//! as one, and each clamped end moved with its copies), the VJP the transpose of the JVP, and
//! the refusals.

use super::{ArcLengthGradient, ClosestParameters};
use crate::error::Error;
use crate::points::{Points, PointsRef};
use crate::query::QueryCurve;
use crate::BSplineCurve;

fn curve(p: usize, knots: Vec<f64>, dim: usize) -> BSplineCurve {
    let n = knots.len() - p - 1;
    let ctrl: Vec<f64> = (0..n * dim)
        .map(|i| ((i * 7 + 3) as f64 * 0.61).sin() * 2.0 + (i / dim) as f64)
        .collect();
    BSplineCurve::new(p, knots, Points::from_flat(dim, ctrl).unwrap()).unwrap()
}

fn with_knots(c: &BSplineCurve, knots: Vec<f64>) -> BSplineCurve {
    BSplineCurve::new(c.degree(), knots, c.control_points().clone()).unwrap()
}

fn length(c: &BSplineCurve) -> f64 {
    QueryCurve::from_bspline(c).unwrap().length().unwrap()
}

fn params(c: &BSplineCurve, x: &[f64]) -> Vec<f64> {
    let q = QueryCurve::from_bspline(c).unwrap();
    let f = q
        .project_batch(PointsRef::from_flat(c.dim(), x).unwrap())
        .unwrap();
    f.iter().map(|p| p.t).collect()
}

/// The knot moves a test differentiates along: each simple interior knot alone, each interior
/// knot value with all its copies, and each clamped end with its `p + 1` copies.
fn moves(c: &BSplineCurve) -> Vec<Vec<f64>> {
    let (p, n) = (c.degree(), c.control_points().len());
    let knots = c.knots().as_slice();
    let mut out = Vec::new();
    let mut start = vec![0.0; knots.len()];
    start[..=p].fill(1.0);
    out.push(start);
    let mut end = vec![0.0; knots.len()];
    end[n..].fill(1.0);
    out.push(end);
    let mut k = p + 1;
    while k < n {
        let mut e = vec![0.0; knots.len()];
        while k < n && (e.iter().all(|v| *v == 0.0) || knots[k] == knots[k - 1]) {
            e[k] = 1.0;
            k += 1;
        }
        out.push(e);
    }
    out
}

fn moved(knots: &[f64], e: &[f64], h: f64) -> Vec<f64> {
    knots.iter().zip(e).map(|(k, d)| k + h * d).collect()
}

fn assert_rel(got: f64, want: f64, scale: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-7 * scale.max(1.0),
        "{what}: {got} against {want}"
    );
}

fn cases(dim: usize) -> Vec<BSplineCurve> {
    vec![
        curve(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.45, 0.7, 1.0, 1.0, 1.0, 1.0],
            dim,
        ),
        curve(2, vec![-1.0, -1.0, -1.0, 0.2, 0.2, 0.9, 2.0, 2.0, 2.0], dim),
        curve(1, vec![0.0, 0.0, 0.4, 0.5, 1.5, 1.5], dim),
        curve(3, vec![0.0, 0.0, 0.0, 0.0, 2.0, 2.0, 2.0, 2.0], dim),
    ]
}

#[test]
fn arc_length_knot_gradient_is_the_difference_of_the_lengths() {
    for dim in [1, 2, 3] {
        for c in cases(dim) {
            let g = ArcLengthGradient::with_knots(&c).unwrap();
            assert_eq!(g.length().to_bits(), length(&c).to_bits());
            let plain = ArcLengthGradient::new(&c).unwrap();
            assert_eq!(plain.gradient(), g.gradient(), "the same control gradient");
            let knots = c.knots().as_slice();
            let h = 1e-6;
            for e in moves(&c) {
                let fd = (length(&with_knots(&c, moved(knots, &e, h)))
                    - length(&with_knots(&c, moved(knots, &e, -h))))
                    / (2.0 * h);
                let got = g.knot_jvp(&e).unwrap();
                assert_rel(
                    got,
                    fd,
                    g.length(),
                    &format!("degree {}, dim {dim}, move {e:?}", c.degree()),
                );
            }
            // the VJP is the JVP's transpose
            let t: Vec<f64> = (0..knots.len()).map(|i| (i as f64 * 0.7).cos()).collect();
            let vjp = g.knot_vjp(-1.5).unwrap();
            let dot: f64 = vjp.iter().zip(&t).map(|(a, b)| a * b).sum();
            let jvp = g.knot_jvp(&t).unwrap();
            assert!((dot + 1.5 * jvp).abs() <= 1e-13 * dot.abs().max(1.0));
        }
    }
}

#[test]
fn arc_length_of_a_reparameterised_curve_is_unchanged() {
    // an affine map of all the knots moves nothing: the gradient is orthogonal to it
    let c = cases(2).remove(0);
    let g = ArcLengthGradient::with_knots(&c).unwrap();
    let knots = c.knots().as_slice();
    assert!(g.knot_jvp(&vec![1.0; knots.len()]).unwrap().abs() < 1e-12);
    assert!(g.knot_jvp(knots).unwrap().abs() < 1e-12);
    // a polyline's length does not depend on its knots
    let g = ArcLengthGradient::with_knots(&cases(3).remove(2)).unwrap();
    for v in g.knot_gradient().unwrap() {
        assert!(v.abs() < 1e-12, "{:?}", g.knot_gradient());
    }
}

#[test]
fn closest_parameter_knot_derivatives_are_differences_of_the_projections() {
    for dim in [2, 3] {
        for c in cases(dim) {
            let (lo, hi) = c.domain();
            let mut x = Vec::new();
            for (k, f) in [0.12, 0.4, 0.66, 0.9].iter().enumerate() {
                let p = c.eval(lo + f * (hi - lo)).unwrap();
                x.extend(
                    p.iter()
                        .enumerate()
                        .map(|(d, v)| v + 0.05 * ((k + d) as f64).cos()),
                );
            }
            // beyond each end: the closest points are the ends
            x.extend(c.eval(lo).unwrap().iter().map(|v| v - 30.0));
            x.extend(c.eval(hi).unwrap().iter().map(|v| v + 30.0));
            let cp = ClosestParameters::with_knots(&c, &x).unwrap();
            assert_eq!(cp.params(), params(&c, &x).as_slice());
            assert_eq!((cp.params()[4], cp.params()[5]), (lo, hi));
            let knots = c.knots().as_slice();
            let h = 1e-6;
            for e in moves(&c) {
                let up = params(&with_knots(&c, moved(knots, &e, h)), &x);
                let down = params(&with_knots(&c, moved(knots, &e, -h)), &x);
                let got = cp.knot_jvp(&e).unwrap();
                for i in 0..got.len() {
                    let fd = (up[i] - down[i]) / (2.0 * h);
                    let what = format!("degree {}, dim {dim}, point {i}, move {e:?}", c.degree());
                    assert_rel(got[i], fd, 1.0, &what);
                }
            }
            // the control-point derivative too, which the corner of the double knot (point 1
            // of the quadratic) pins to the knot
            let ctrl = c.control_points().as_slice();
            for j in 0..ctrl.len() {
                let shifted = |d: f64| {
                    let mut p = ctrl.to_vec();
                    p[j] += d;
                    let pts = Points::from_flat(dim, p).unwrap();
                    params(
                        &BSplineCurve::new(c.degree(), knots.to_vec(), pts).unwrap(),
                        &x,
                    )
                };
                let (up, down) = (shifted(h), shifted(-h));
                let mut e = vec![0.0; ctrl.len()];
                e[j] = 1.0;
                let got = cp.jvp(Some(&e), None).unwrap();
                for i in 0..got.len() {
                    let fd = (up[i] - down[i]) / (2.0 * h);
                    let what = format!("degree {}, point {i}, control {j}", c.degree());
                    assert_rel(got[i], fd, 1.0, &what);
                }
            }
            let t: Vec<f64> = (0..knots.len()).map(|i| (i as f64 * 0.7).cos()).collect();
            let g: Vec<f64> = (0..cp.params().len())
                .map(|i| (i as f64 * 1.3).sin() + 0.2)
                .collect();
            let jvp = cp.knot_jvp(&t).unwrap();
            let vjp = cp.knot_vjp(&g).unwrap();
            let a: f64 = jvp.iter().zip(&g).map(|(p, q)| p * q).sum();
            let b: f64 = vjp.iter().zip(&t).map(|(p, q)| p * q).sum();
            assert!((a - b).abs() <= 1e-12 * a.abs().max(1.0), "{a} against {b}");
        }
    }
}

#[test]
fn knot_derivatives_refuse_bad_input() {
    let c = cases(2).remove(0);
    let len = c.knots().len();
    let plain = ArcLengthGradient::new(&c).unwrap();
    let e = plain.knot_jvp(&vec![0.0; len]).unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
    let g = ArcLengthGradient::with_knots(&c).unwrap();
    let e = g.knot_jvp(&vec![0.0; len - 1]).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let mut bad = vec![0.0; len];
    bad[5] = f64::INFINITY;
    let e = g.knot_jvp(&bad).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = g.knot_vjp(f64::NAN).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");

    let x = c.eval(0.5).unwrap();
    let plain = ClosestParameters::new(&c, &x).unwrap();
    let e = plain.knot_vjp(&[1.0]).unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
    let cp = ClosestParameters::with_knots(&c, &x).unwrap();
    let e = cp.knot_jvp(&vec![0.0; len + 1]).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let e = cp.knot_jvp(&bad).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
    let e = cp.knot_vjp(&[1.0, 2.0]).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e:?}");
    let e = cp.knot_vjp(&[f64::NAN]).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "{e:?}");
}
