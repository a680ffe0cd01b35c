//! Tests of `fit_knots.rs`: the knot JVPs of interpolation and of the least-squares fit
//! against central differences of the fits' control points (relative 1e-7 of the largest
//! difference quotient, at least 1: the step `h = 1e-6` leaves `O(h²)` truncation and
//! `O(ε/h)` rounding, both far below), the VJPs their transposes (to rounding, 1e-12 of the
//! products' scale), the end knots held fixed, and bad input refused.

use super::{Interpolant, LeastSquaresFit};
use crate::error::Error;
use crate::{BSplineCurve, Points};

const H: f64 = 1e-6;
const RTOL: f64 = 1e-7;

/// Cubic knots with interior knots off every parameter used below.
fn knots() -> Vec<f64> {
    vec![0.0, 0.0, 0.0, 0.0, 0.23, 0.46, 0.71, 1.0, 1.0, 1.0, 1.0]
}

/// A tangent of the interior knots (the first and last four are set too, and must be ignored).
fn knot_tangent() -> Vec<f64> {
    (0..11).map(|i| (1.3 * i as f64).sin() + 0.2).collect()
}

/// `knots + s · tangent` on the interior knots only (the end knots fixed).
fn moved(s: f64) -> Vec<f64> {
    let (mut k, t) = (knots(), knot_tangent());
    for i in 4..7 {
        k[i] += s * t[i];
    }
    k
}

fn assert_close(got: &[f64], fd: &[f64], what: &str) {
    assert_eq!(got.len(), fd.len(), "{what}");
    let scale = fd.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (j, (a, b)) in got.iter().zip(fd).enumerate() {
        assert!(
            (a - b).abs() <= RTOL * scale,
            "{what}[{j}]: {a} vs {b} (scale {scale})"
        );
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// 7 parameters (as many as control points), 2-D data.
fn interpolation_data() -> (Vec<f64>, Vec<f64>) {
    let params: Vec<f64> = vec![0.0, 0.1, 0.3, 0.55, 0.62, 0.85, 1.0];
    let points = params
        .iter()
        .flat_map(|x| [(3.0 * x).sin() + 2.0, x * x - 0.5 * x])
        .collect();
    (params, points)
}

#[test]
fn interpolation_knot_jvp_matches_central_differences() {
    let (params, points) = interpolation_data();
    let it = Interpolant::new(3, &knots(), &params, &points, 2).unwrap();
    let jvp = it.knot_jvp(&knot_tangent()).unwrap();
    let at = |s: f64| {
        Interpolant::new(3, &moved(s), &params, &points, 2)
            .unwrap()
            .control_points()
            .to_vec()
    };
    let (plus, minus) = (at(H), at(-H));
    let fd: Vec<f64> = plus
        .iter()
        .zip(&minus)
        .map(|(a, b)| (a - b) / (2.0 * H))
        .collect();
    assert!(
        fd.iter().any(|x| x.abs() > 0.1),
        "a tangent that moves the fit: {fd:?}"
    );
    assert_close(&jvp, &fd, "interpolation knot JVP");
}

#[test]
fn interpolation_knot_vjp_is_the_transpose() {
    let (params, points) = interpolation_data();
    let it = Interpolant::new(3, &knots(), &params, &points, 2).unwrap();
    let tangent = knot_tangent();
    let g: Vec<f64> = (0..14).map(|i| (0.7 * i as f64).cos()).collect();
    let jvp = it.knot_jvp(&tangent).unwrap();
    let vjp = it.knot_vjp(&g).unwrap();
    assert!(
        vjp[..4].iter().chain(&vjp[7..]).all(|&x| x == 0.0),
        "{vjp:?}"
    );
    let (lhs, rhs) = (dot(&g, &jvp), dot(&vjp, &tangent));
    let scale = 1.0 + dot(&g, &g).sqrt() * dot(&jvp, &jvp).sqrt();
    assert!((lhs - rhs).abs() <= 1e-12 * scale, "{lhs} vs {rhs}");
    // the tangents of the end knots are ignored
    let mut ends = vec![0.0; 11];
    ends[..4].fill(1.0);
    ends[7..].fill(-2.0);
    assert!(it.knot_jvp(&ends).unwrap().iter().all(|&x| x == 0.0));
}

/// 40 noisy points in 2-D at unsorted parameters, with weights: a residual that does not
/// vanish, so both terms of the least-squares JVP count.
fn least_squares_data() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let params: Vec<f64> = (0..40).map(|k| ((k * 17) % 40) as f64 / 39.0).collect();
    let points = params
        .iter()
        .enumerate()
        .flat_map(|(k, x)| {
            let noise = 0.05 * (7.1 * k as f64).sin();
            [(4.0 * x).sin() + noise + 10.0, (2.0 * x).cos() * x - noise]
        })
        .collect();
    let weights = (0..40).map(|k| 0.5 + (k % 3) as f64).collect();
    (params, points, weights)
}

#[test]
fn least_squares_knot_jvp_matches_central_differences() {
    let (params, points, weights) = least_squares_data();
    let fit = LeastSquaresFit::new(3, &knots(), &params, &points, 2, Some(&weights)).unwrap();
    let (control, jvp) = fit.knot_jvp(&knot_tangent()).unwrap();
    assert_eq!(
        control,
        fit.control_points().unwrap(),
        "the values, bit for bit"
    );
    let at = |s: f64| {
        LeastSquaresFit::new(3, &moved(s), &params, &points, 2, Some(&weights))
            .unwrap()
            .control_points()
            .unwrap()
    };
    let (plus, minus) = (at(H), at(-H));
    let fd: Vec<f64> = plus
        .iter()
        .zip(&minus)
        .map(|(a, b)| (a - b) / (2.0 * H))
        .collect();
    assert_close(&jvp, &fd, "least-squares knot JVP");
    // the data leave a residual, so the JVP's term Ḃᵀ W r is tested too
    let curve = BSplineCurve::new(3, knots(), Points::from_flat(2, control).unwrap()).unwrap();
    let mut v = vec![0.0; 80];
    curve.eval_batch(&params, &mut v).unwrap();
    let residual = v
        .iter()
        .zip(&points)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(residual > 0.01, "the data leave a residual: {residual}");
}

#[test]
fn least_squares_knot_vjp_is_the_transpose() {
    let (params, points, weights) = least_squares_data();
    let fit = LeastSquaresFit::new(3, &knots(), &params, &points, 2, Some(&weights)).unwrap();
    let tangent = knot_tangent();
    let g: Vec<f64> = (0..14).map(|i| (0.9 * i as f64).sin() - 0.3).collect();
    let (_, jvp) = fit.knot_jvp(&tangent).unwrap();
    let vjp = fit.knot_vjp(&g).unwrap();
    assert!(
        vjp[..4].iter().chain(&vjp[7..]).all(|&x| x == 0.0),
        "{vjp:?}"
    );
    let (lhs, rhs) = (dot(&g, &jvp), dot(&vjp, &tangent));
    let scale = 1.0 + dot(&g, &g).sqrt() * dot(&jvp, &jvp).sqrt();
    assert!((lhs - rhs).abs() <= 1e-12 * scale, "{lhs} vs {rhs}");
}

#[test]
fn least_squares_through_its_space_is_interpolation_like() {
    // with as many parameters as control points the fit interpolates (r = 0): its knot
    // derivatives are interpolation's
    let (params, points) = interpolation_data();
    let fit = LeastSquaresFit::new(3, &knots(), &params, &points, 2, None).unwrap();
    let it = Interpolant::new(3, &knots(), &params, &points, 2).unwrap();
    let (_, a) = fit.knot_jvp(&knot_tangent()).unwrap();
    let b = it.knot_jvp(&knot_tangent()).unwrap();
    assert_close(&a, &b, "square least squares against interpolation");
}

#[test]
fn bad_input_is_refused() {
    let (params, points, weights) = least_squares_data();
    let fit = LeastSquaresFit::new(3, &knots(), &params, &points, 2, Some(&weights)).unwrap();
    let e = fit.knot_jvp(&[0.0; 10]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 11,
                got: 10,
                ..
            }
        ),
        "{e:?}"
    );
    let mut t = knot_tangent();
    t[5] = f64::NAN;
    assert!(matches!(
        fit.knot_jvp(&t).unwrap_err(),
        Error::NonFinite { .. }
    ));
    let e = fit.knot_vjp(&[1.0; 13]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 14,
                got: 13,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(matches!(
        fit.knot_vjp(&[f64::INFINITY; 14]).unwrap_err(),
        Error::NonFinite { .. }
    ));
    let (params, points) = interpolation_data();
    let it = Interpolant::new(3, &knots(), &params, &points, 2).unwrap();
    assert!(matches!(
        it.knot_jvp(&[0.0; 12]).unwrap_err(),
        Error::LengthMismatch { .. }
    ));
    assert!(matches!(
        it.knot_vjp(&[0.0; 13]).unwrap_err(),
        Error::LengthMismatch { .. }
    ));
}
