//! Closed (periodic) fits: golden values from SciPy's `splrep(per=1)` (the `splrep_periodic`
//! entry of `tests/data/fit_golden.json`, made by `scripts/fit_golden.py`), closure and
//! reproduction as properties, and named errors.

use lekalo::fit::{
    closed_parameters, periodic_least_squares, periodic_smoothing_condition, FitData,
    SMOOTHING_RTOL,
};
use lekalo::{BSplineCurve, Error, Parametrization, PointsRef};
use proptest::prelude::*;

use lekalo_testkit::assert_close;
use serde_json::Value;
use std::f64::consts::TAU;

fn golden() -> Value {
    let g: Value =
        serde_json::from_str(include_str!("../data/fit_golden.json")).expect("golden JSON parses");
    g["splrep_periodic"].clone()
}

fn vec_of(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn coefficients(c: &BSplineCurve) -> Vec<f64> {
    c.control_points().iter().map(|p| p[0]).collect()
}

/// SciPy's data end with the first point repeated at 2π, which FITPACK ignores: it is left out.
fn scipy_data(g: &Value) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut y) = (vec_of(&g["x"]), vec_of(&g["y"]));
    x.pop();
    y.pop();
    (x, y)
}

#[test]
fn periodic_least_squares_matches_scipy_splrep_with_knots() {
    let g = golden();
    let (x, y) = scipy_data(&g);
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let mut breaks = vec![0.0];
    breaks.extend(vec_of(&g["interior"]));
    breaks.push(TAU);
    let fit = periodic_least_squares(&data, 3, &breaks).unwrap();
    assert_close(
        fit.curve.knots().as_slice(),
        &vec_of(&g["lsq_t"]),
        1e-14,
        "knots",
    );
    assert_close(
        &coefficients(&fit.curve),
        &vec_of(&g["lsq_c"]),
        1e-12,
        "coefficients",
    );
}

#[test]
fn periodic_smoothing_condition_matches_scipy_splrep_per() {
    let g = golden();
    let (x, y) = scipy_data(&g);
    let s = g["s"].as_f64().unwrap();
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let fit = periodic_smoothing_condition(&data, 3, s, (0.0, TAU)).unwrap();
    let rss = fit.report.weighted_rss;
    assert!(
        rss <= s && rss >= (1.0 - SMOOTHING_RTOL) * s,
        "rss {rss}, s {s}, SciPy's fp {}",
        g["fp"]
    );
    assert_close(
        fit.curve.knots().as_slice(),
        &vec_of(&g["t"]),
        1e-14,
        "knots",
    );
    assert_close(
        &coefficients(&fit.curve),
        &vec_of(&g["c"]),
        1e-9,
        "coefficients",
    );
    assert!(fit.report.lambda.is_some(), "smoothed on the final knots");
}

/// Value and the first `degree − 1` derivatives agree at both ends of the period.
fn assert_closed(c: &BSplineCurve, (a, b): (f64, f64)) {
    let p = c.degree();
    let (da, db) = (
        c.eval_derivatives(a, p - 1).unwrap(),
        c.eval_derivatives(b, p - 1).unwrap(),
    );
    for d in 0..p {
        for (u, v) in da.point(d).iter().zip(db.point(d)) {
            assert!(
                (u - v).abs() <= 1e-9 * (1.0 + u.abs()),
                "derivative {d}: {u} at a vs {v} at b"
            );
        }
    }
}

#[test]
fn closed_fits_of_a_closed_polygon_close_smoothly() {
    // a noisy five-lobed curve, parametrised closed by chord length
    let n = 300;
    let q: Vec<f64> = (0..n)
        .flat_map(|k| {
            let t = TAU * k as f64 / n as f64;
            let r = 2.0 + 0.3 * (5.0 * t).cos() + 0.01 * ((k * 37 % 11) as f64 - 5.0);
            [r * t.cos(), r * t.sin(), 0.1 * (2.0 * t).sin()]
        })
        .collect();
    let pts = PointsRef::from_flat(3, &q).unwrap();
    let u = closed_parameters(pts, Parametrization::ChordLength).unwrap();
    assert_eq!(u.len(), n + 1, "one parameter more than points");
    let (a, b) = (u[0], u[n]);
    let data = FitData::new(pts, &u[..n]).unwrap();
    for p in [2, 3, 5] {
        let breaks: Vec<f64> = (0..=24).map(|j| a + (b - a) * j as f64 / 24.0).collect();
        let lsq = periodic_least_squares(&data, p, &breaks).unwrap();
        assert_closed(&lsq.curve, (a, b));
        assert!(lsq.report.max_residual < 0.1, "lsq degree {p}");
        let sm = periodic_smoothing_condition(&data, p, 0.02, (a, b)).unwrap();
        assert_closed(&sm.curve, (a, b));
        assert!(
            sm.report.weighted_rss <= 0.02,
            "rss {}",
            sm.report.weighted_rss
        );
    }
    // s = 0: closed interpolation
    let interp = periodic_smoothing_condition(&data, 3, 0.0, (a, b)).unwrap();
    assert!(interp.report.max_residual < 1e-9, "interpolates");
    // s above the constant's residual: the constant (the centroid)
    let big = periodic_smoothing_condition(&data, 3, 1e6, (a, b)).unwrap();
    assert_eq!(big.report.n_ctrl, 4, "one free control point, repeated");
}

#[test]
fn closed_fit_errors_are_named() {
    let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    let y = [0.0, 1.0, 0.0, -1.0, 0.0, 1.0];
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let e = periodic_least_squares(&data, 3, &[0.0]).unwrap_err();
    assert!(matches!(e, Error::TooFew { .. }), "one breakpoint: {e:?}");
    let e = periodic_least_squares(&data, 3, &[0.0, 3.0, 2.0, 6.0]).unwrap_err();
    assert!(matches!(e, Error::NotIncreasing { .. }), "unsorted: {e:?}");
    let e = periodic_least_squares(&data, 3, &[0.0, 3.0, 3.0, 6.0]).unwrap_err();
    assert!(
        matches!(e, Error::InvalidArgument { .. }),
        "repeated: {e:?}"
    );
    let e = periodic_least_squares(&data, 3, &[0.0, f64::NAN, 6.0]).unwrap_err();
    assert!(matches!(e, Error::NonFinite { .. }), "NaN: {e:?}");
    let e = periodic_least_squares(&data, 3, &[0.0, 2.0, 4.5]).unwrap_err();
    assert!(
        matches!(e, Error::ParameterOutOfDomain { .. }),
        "outside: {e:?}"
    );
    // seven spans for six parameters: a control point without data
    let many: Vec<f64> = (0..=7).map(|j| 6.0 * j as f64 / 7.0).collect();
    let e = periodic_least_squares(&data, 3, &many).unwrap_err();
    assert!(
        matches!(e, Error::SchoenbergWhitney { .. }),
        "too many: {e:?}"
    );
    let e = periodic_smoothing_condition(&data, 3, -1.0, (0.0, 6.0)).unwrap_err();
    assert!(matches!(e, Error::NegativeSmoothing { .. }), "s < 0: {e:?}");
    let e = periodic_smoothing_condition(&data, 0, 1.0, (0.0, 6.0)).unwrap_err();
    assert!(matches!(e, Error::Degree { .. }), "degree 0: {e:?}");
    let e = periodic_smoothing_condition(&data, 3, 1.0, (6.0, 6.0)).unwrap_err();
    assert!(
        matches!(e, Error::TooFew { .. } | Error::InvalidArgument { .. }),
        "empty period: {e:?}"
    );
    let few = FitData::new(PointsRef::from_flat(1, &y[..2]).unwrap(), &x[..2]).unwrap();
    let e = periodic_smoothing_condition(&few, 3, 0.1, (0.0, 6.0)).unwrap_err();
    assert!(matches!(e, Error::TooFew { .. }), "two points: {e:?}");
}

proptest! {
    #![proptest_config(lekalo_testkit::config(32))]

    /// A constant, and data sampled from a closed spline of the same space, are reproduced
    /// exactly, also far from the origin.
    #[test]
    fn a_closed_spline_of_the_space_is_reproduced(
        coeffs in prop::collection::vec(-5.0..5.0f64, 6..12),
        degree in 1usize..5,
        offset in prop::sample::select(vec![0.0, 1e6]),
    ) {
        let np = coeffs.len();
        let breaks: Vec<f64> = (0..=np)
            .map(|j| offset + j as f64 + 0.06 * ((j * 7 % 5) as f64))
            .collect();
        let (a, b) = (breaks[0], breaks[np]);
        let x: Vec<f64> = (0..40 * np).map(|k| a + (b - a) * k as f64 / (40 * np) as f64).collect();
        let constant = vec![coeffs[0]; x.len()];
        let data = FitData::new(PointsRef::from_flat(1, &constant).unwrap(), &x).unwrap();
        let fit = periodic_least_squares(&data, degree, &breaks).unwrap();
        prop_assert!(fit.report.max_residual < 1e-12, "constant: {}", fit.report.max_residual);
        // a closed spline of the space: the fit of a sine, sampled
        let sine: Vec<f64> = x.iter().map(|t| coeffs[1] * (TAU * (t - a) / (b - a)).sin() + coeffs[2]).collect();
        let data = FitData::new(PointsRef::from_flat(1, &sine).unwrap(), &x).unwrap();
        let spline = periodic_least_squares(&data, degree, &breaks).unwrap().curve;
        let mut sampled = vec![0.0; x.len()];
        spline.eval_batch(&x, &mut sampled).unwrap();
        let data = FitData::new(PointsRef::from_flat(1, &sampled).unwrap(), &x).unwrap();
        let again = periodic_least_squares(&data, degree, &breaks).unwrap();
        prop_assert!(again.report.max_residual < 1e-10, "reproduced: {}", again.report.max_residual);
        prop_assert!(again.curve.control_points().len() == np + degree, "np free, degree repeated");
    }
}
