//! Tests of `fitting.rs`: the fits' JVPs against the fits of the tangents, the VJPs against
//! their transposes, and the maps' flat forms.
use super::{LeastSquaresMap, SmoothingMap};
use crate::error::Error;
use crate::fit::{least_squares, smoothing_spline, EndConstraints, FitData, Lambda};
use crate::knots::KnotVector;
use crate::oracle::proptest_config;
use crate::points::PointsRef;
use proptest::prelude::*;

/// Sorted parameters from gaps, starting at 0.
fn params_of(gaps: &[f64]) -> Vec<f64> {
    let mut ts = vec![0.0];
    for g in gaps {
        ts.push(ts[ts.len() - 1] + g);
    }
    ts
}

/// `<a, b>` and the scale against which its rounding is measured.
fn dot(a: &[f64], b: &[f64]) -> (f64, f64) {
    let s: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let m: f64 = a.iter().zip(b).map(|(x, y)| (x * y).abs()).sum();
    (s, m)
}

fn close(a: &[f64], b: &[f64], rtol: f64) -> std::result::Result<(), TestCaseError> {
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        prop_assert!(
            (x - y).abs() <= rtol * scale,
            "entry {}: {} against {}",
            i,
            x,
            y
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(64))]

    /// The least-squares JVP is the fit of the tangent (the fit is linear in the data), and
    /// the VJP is its transpose.
    #[test]
    fn least_squares_jvp_is_the_fit_and_vjp_its_transpose(
        p in 1usize..=4,
        interior in 0usize..4,
        gaps in prop::collection::vec(0.01f64..1.0, 25..40),
        dim in 1usize..=3,
        weighted in any::<bool>(),
        seed in prop::collection::vec(-1.0f64..1.0, 40 * 3 * 3),
    ) {
        let ts = params_of(&gaps);
        let (a, b) = (ts[0], ts[ts.len() - 1]);
        let mut knots = vec![a; p + 1];
        for j in 1..=interior {
            knots.push(a + (b - a) * j as f64 / (interior + 1) as f64);
        }
        knots.extend(std::iter::repeat_n(b, p + 1));
        let kv = KnotVector::new(knots).unwrap();
        let m = ts.len();
        let w: Vec<f64> = (0..m).map(|k| 0.5 + seed[2 * m * dim + k].abs()).collect();
        let weights = weighted.then_some(w.as_slice());
        let map = LeastSquaresMap::new(p, &kv, &ts, weights).unwrap();
        let dq = &seed[..m * dim];
        let dp = map.jvp(dq, dim).unwrap();
        let mut data = FitData::new(PointsRef::from_flat(dim, dq).unwrap(), &ts).unwrap();
        if let Some(w) = weights {
            data = data.with_weights(w).unwrap();
        }
        let fit = least_squares(&data, p, &kv, &EndConstraints::none()).unwrap();
        close(&dp, fit.curve.control_points().as_slice(), 1e-10)?;
        let g = &seed[m * dim..m * dim + map.n_ctrl() * dim];
        let gq = map.vjp(g, dim).unwrap();
        let ((lhs, l1), (rhs, r1)) = (dot(g, &dp), dot(&gq, dq));
        prop_assert!((lhs - rhs).abs() <= 1e-12 * (l1 + r1), "{} against {}", lhs, rhs);
    }

    /// The smoothing JVP is the smoothing spline of the tangent, and the VJP its transpose;
    /// also with repeated parameters (a zero gap), which share one basis row.
    #[test]
    fn smoothing_jvp_is_the_fit_and_vjp_its_transpose(
        gaps in prop::collection::vec(prop_oneof![4 => 0.01f64..1.0, 1 => Just(0.0)], 4..30),
        log_lambda in -9.0f64..0.0,
        dim in 1usize..=3,
        weighted in any::<bool>(),
        seed in prop::collection::vec(-1.0f64..1.0, 32 * 3 * 3),
    ) {
        let ts = params_of(&gaps);
        let m = ts.len();
        prop_assume!(gaps.iter().filter(|g| **g > 0.0).count() >= 2, "three distinct parameters");
        // λ relative to the data's scale, over the range the GCV scan covers (up to where
        // the fit is all but the least-squares line, `λ ≈ Σw·L³`): beyond it `G` is as
        // ill-conditioned as `λ/(Σw·L³)` and both sides of the checks lose digits to it
        let range = ts[m - 1] - ts[0];
        let lam = 10f64.powf(log_lambda) * m as f64 * range.powi(3);
        let w: Vec<f64> = (0..m).map(|k| 0.5 + seed[2 * 32 * 3 + k].abs()).collect();
        let weights = weighted.then_some(w.as_slice());
        let map = SmoothingMap::new(&ts, lam, weights).unwrap();
        let dq = &seed[..m * dim];
        let dp = map.jvp(dq, dim).unwrap();
        let mut data = FitData::new(PointsRef::from_flat(dim, dq).unwrap(), &ts).unwrap();
        if let Some(w) = weights {
            data = data.with_weights(w).unwrap();
        }
        let fit = smoothing_spline(&data, Lambda::Given(lam)).unwrap();
        prop_assert_eq!(fit.curve.knots().as_slice(), map.knots());
        // the same operations as the fit (shifted data, the same factors): the same bits
        prop_assert_eq!(dp.as_slice(), fit.curve.control_points().as_slice());
        let g = &seed[32 * 3..32 * 3 + map.n_ctrl() * dim];
        let gq = map.vjp(g, dim).unwrap();
        let ((lhs, l1), (rhs, r1)) = (dot(g, &dp), dot(&gq, dq));
        // rounding grows with the condition of G = RᵀR, at least (max R_ii / min R_ii)²
        let lin = map.linearize();
        let diag = lin.triangle.iter().step_by(lin.bandwidth);
        let (hi, lo) = diag.fold((0.0f64, f64::INFINITY), |(h, l), &d| (h.max(d), l.min(d)));
        let kappa = (hi / lo).powi(2);
        let tol = 16.0 * f64::EPSILON * kappa.max(1.0) * (l1 + r1);
        prop_assert!((lhs - rhs).abs() <= tol, "{} against {} (κ ≥ {:e})", lhs, rhs, kappa);
    }
}

/// `(RᵀR)⁻¹ BᵀW q` from a [`FitLinearization`], dense: what a framework computes with it.
fn apply(lin: &super::FitLinearization, q: &[f64]) -> Vec<f64> {
    let (n, bw) = (lin.n_ctrl, lin.bandwidth);
    let mut x = vec![0.0; n];
    for (k, &f) in lin.first.iter().enumerate() {
        for a in 0..lin.width {
            x[f + a] += lin.weights[k] * lin.basis[k * lin.width + a] * q[k];
        }
    }
    let r = |i: usize, j: usize| {
        if j >= i && j - i < bw {
            lin.triangle[i * bw + j - i]
        } else {
            0.0
        }
    };
    for i in 0..n {
        x[i] = (x[i] - (0..i).map(|k| r(k, i) * x[k]).sum::<f64>()) / r(i, i);
    }
    for i in (0..n).rev() {
        x[i] = (x[i] - (i + 1..n).map(|k| r(i, k) * x[k]).sum::<f64>()) / r(i, i);
    }
    x
}

#[test]
fn linearizations_give_the_maps() {
    let ts: Vec<f64> = (0..30).map(|k| (k as f64 / 29.0).powf(1.3)).collect();
    let q: Vec<f64> = ts.iter().map(|t| (5.0 * t).sin()).collect();
    let w: Vec<f64> = (0..30).map(|k| 1.0 + (k % 3) as f64).collect();
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0]).unwrap();
    let lsq = LeastSquaresMap::new(3, &kv, &ts, Some(&w)).unwrap();
    let sm = SmoothingMap::new(&ts, 1e-4, Some(&w)).unwrap();
    for (lin, want) in [
        (lsq.linearize(), lsq.jvp(&q, 1).unwrap()),
        (sm.linearize(), sm.jvp(&q, 1).unwrap()),
    ] {
        let got = apply(&lin, &q);
        assert_eq!(got.len(), want.len());
        for (a, b) in got.iter().zip(&want) {
            assert!((a - b).abs() <= 1e-10 * b.abs().max(1.0), "{a} against {b}");
        }
    }
}

#[test]
fn errors_name_the_problem() {
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
    let ts = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0];
    let map = LeastSquaresMap::new(2, &kv, &ts, None).unwrap();
    let e = map.jvp(&[1.0; 5], 1).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 6,
                got: 5,
                ..
            }
        ),
        "{e:?}"
    );
    let e = map.vjp(&[1.0, f64::NAN, 0.0, 0.0], 1).unwrap_err();
    assert!(matches!(e, Error::NonFinite { index: 1, .. }), "{e:?}");
    let e = map.vjp(&[], 0).unwrap_err();
    assert!(matches!(e, Error::Dimension { .. }), "{e:?}");
    // no data under the last basis functions
    let e = LeastSquaresMap::new(2, &kv, &[0.0, 0.1, 0.2, 0.3, 0.4], None).unwrap_err();
    assert!(matches!(e, Error::SchoenbergWhitney { .. }), "{e:?}");
    // weight 0 on the only data of the second span
    let e = LeastSquaresMap::new(
        2,
        &kv,
        &[0.0, 0.1, 0.2, 0.3, 0.7, 0.8],
        Some(&[1.0, 1.0, 1.0, 1.0, 0.0, 0.0]),
    )
    .unwrap_err();
    assert!(matches!(e, Error::SchoenbergWhitney { .. }), "{e:?}");
    let e = LeastSquaresMap::new(2, &kv, &[0.0, 0.2, 0.4, 0.6, 1.5], None).unwrap_err();
    assert!(matches!(e, Error::ParameterOutOfDomain { .. }), "{e:?}");
    let e = SmoothingMap::new(&ts, -1.0, None).unwrap_err();
    assert!(matches!(e, Error::NegativeSmoothing { .. }), "{e:?}");
    let e = SmoothingMap::new(&ts, 0.0, None).unwrap_err();
    assert!(matches!(e, Error::InvalidArgument { .. }), "{e:?}");
    // a repeated parameter is the smoothing spline's (one basis row for both points); a
    // decreasing one, or fewer than three distinct, are refused as the fit refuses them
    let map = SmoothingMap::new(&[0.0, 0.5, 0.5, 1.0], 1.0, None).unwrap();
    assert_eq!((map.n_data(), map.n_ctrl()), (4, 5));
    let e = SmoothingMap::new(&[0.0, 0.5, 0.4, 1.0], 1.0, None).unwrap_err();
    assert!(matches!(e, Error::NotIncreasing { index: 2, .. }), "{e:?}");
    let e = SmoothingMap::new(&[0.0, 0.5, 0.5, 0.5], 1.0, None).unwrap_err();
    assert!(matches!(e, Error::TooFew { got: 2, .. }), "{e:?}");
    let map = SmoothingMap::new(&ts, 1.0, None).unwrap();
    let e = map.vjp(&[1.0; 6], 1).unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                expected: 8,
                got: 6,
                ..
            }
        ),
        "{e:?}"
    );
}
