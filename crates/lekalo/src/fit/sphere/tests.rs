//! The laws of the fits on the sphere: periodic in φ, one value at each pole, the derivative
//! across a pole of the form `a cos φ + b sin φ`, constants reproduced exactly, grid data
//! interpolated at `s = 0`, the smoothing condition met, and SciPy's messages for bad input.

use super::scattered::RESIDUAL_HEADROOM;
use super::space::{PI, TWO_PI};
use super::*;
use crate::fit::SMOOTHING_RTOL;
use crate::numeric::progress::Progress;
use crate::Error;
use proptest::prelude::*;

/// A smooth function on the sphere (a function of the point `(x, y, z)`, so well defined at
/// the poles).
fn field(theta: f64, phi: f64) -> f64 {
    let (x, y, z) = (
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    );
    1.0 + 0.5 * x - 0.3 * y * z + 0.8 * z * z + 0.2 * x * y
}

/// Scattered points: a spiral over the sphere (deterministic), poles included.
fn spiral(m: usize) -> (Vec<f64>, Vec<f64>) {
    let golden = PI * (3.0 - 5f64.sqrt());
    let mut theta = vec![0.0];
    let mut phi = vec![1.0];
    for k in 1..m - 1 {
        let z = 1.0 - 2.0 * k as f64 / (m - 1) as f64;
        theta.push(z.acos());
        phi.push((golden * k as f64).rem_euclid(TWO_PI));
    }
    theta.push(PI);
    phi.push(2.0);
    (theta, phi)
}

fn value(fit: &SphereFit, theta: f64, phi: f64) -> f64 {
    fit.spline.eval(&[theta, phi]).unwrap()[0]
}

fn partial(fit: &SphereFit, theta: f64, phi: f64, orders: [usize; 2]) -> f64 {
    fit.spline.eval_partial(&[theta, phi], &orders).unwrap()[0]
}

/// The invariants of every spline on the sphere with continuity at the poles.
fn check_sphere_laws(fit: &SphereFit, c1: [bool; 2], tol: f64) {
    for &theta in &[0.0, 0.3, 1.4, 2.9, PI] {
        // periodic in φ: value and first derivatives agree at 0 and 2π
        for orders in [[0, 0], [1, 0], [0, 1], [0, 2]] {
            let (a, b) = (
                partial(fit, theta, 0.0, orders),
                partial(fit, theta, TWO_PI, orders),
            );
            assert!(
                (a - b).abs() <= tol,
                "not periodic at θ = {theta}, {orders:?}: {a} vs {b}"
            );
        }
    }
    for (pole, theta) in [(0, 0.0), (1, PI)] {
        let v0 = value(fit, theta, 0.3);
        for k in 0..12 {
            let phi = TWO_PI * k as f64 / 12.0;
            let v = value(fit, theta, phi);
            assert!(
                (v - v0).abs() <= tol,
                "two values at pole {pole}: {v} vs {v0}"
            );
        }
        if c1[pole] {
            // ∂s/∂θ = a cos φ + b sin φ at the φ knots
            let tp = fit.spline.knots()[1].as_slice();
            let knots = &tp[3..tp.len() - 4];
            let d: Vec<f64> = knots
                .iter()
                .map(|&p| partial(fit, theta, p, [1, 0]))
                .collect();
            let (a, b) = (
                partial(fit, theta, 0.0, [1, 0]),
                partial(fit, theta, PI / 2.0, [1, 0]),
            );
            if knots.len() >= 4 && knots.iter().any(|&p| p == PI / 2.0) {
                for (&p, &dv) in knots.iter().zip(&d) {
                    let want = a * p.cos() + b * p.sin();
                    assert!(
                        (dv - want).abs() <= tol * (1.0 + a.abs() + b.abs()),
                        "pole {pole} φ {p}: {dv} vs {want}"
                    );
                }
            }
        }
    }
}

#[test]
fn least_squares_reproduces_constants_and_keeps_the_laws() {
    let (theta, phi) = spiral(400);
    let r = vec![3.0; theta.len()];
    let data = SphereData::new(&theta, &phi, &r, None).unwrap();
    let tt = [0.5, 1.0, 1.5, 2.0, 2.6];
    let tp = [1.0, PI / 2.0, 2.5, PI, 4.0, 3.0 * PI / 2.0, 5.5];
    let fit = sphere_least_squares(&data, &tt, &tp, 1e-16).unwrap();
    assert!(fit.fp < 1e-20, "fp = {}", fit.fp);
    for &(t, p) in &[(0.0, 0.0), (0.7, 3.0), (PI, 6.0), (1.3, TWO_PI)] {
        assert!((value(&fit, t, p) - 3.0).abs() < 1e-12);
    }
    let r: Vec<f64> = theta.iter().zip(&phi).map(|(&t, &p)| field(t, p)).collect();
    let data = SphereData::new(&theta, &phi, &r, None).unwrap();
    let fit = sphere_least_squares(&data, &tt, &tp, 1e-16).unwrap();
    check_sphere_laws(&fit, [true, true], 1e-10);
    // a smooth field is approximated well by 5 × 8 spans
    let err = (0..50)
        .map(|k| {
            let (t, p) = (0.05 + 3.0 * k as f64 / 50.0, 0.1 * k as f64);
            (value(&fit, t, p) - field(t, p)).abs()
        })
        .fold(0.0, f64::max);
    assert!(err < 5e-3, "max error {err}");
    // the residual is the sum of squares at the data
    let rss: f64 = theta
        .iter()
        .zip(&phi)
        .zip(&r)
        .map(|((&t, &p), &v)| (value(&fit, t, p) - v).powi(2))
        .sum();
    assert!((rss - fit.fp).abs() <= 1e-10 * rss.max(1e-30));
}

#[test]
fn smoothing_meets_the_condition() {
    let (theta, phi) = spiral(300);
    let r: Vec<f64> = theta
        .iter()
        .zip(&phi)
        .enumerate()
        .map(|(k, (&t, &p))| field(t, p) + 0.01 * ((k * 7919 % 101) as f64 / 50.0 - 1.0))
        .collect();
    let data = SphereData::new(&theta, &phi, &r, None).unwrap();
    let poly = sphere_smoothing(&data, 1e10, 1e-16, &Progress::new()).unwrap();
    assert!(poly.p.is_none() && poly.spline.shape() == &[4, 4][..]);
    for s in [2.0, 0.3, 0.05] {
        let fit = sphere_smoothing(&data, s, 1e-16, &Progress::new()).unwrap();
        assert!(
            fit.fp <= s * (1.0 + SMOOTHING_RTOL),
            "fp {} > s {s}",
            fit.fp
        );
        if fit.p.is_some() {
            assert!(
                fit.fp >= (1.0 - SMOOTHING_RTOL) * s,
                "fp {} far below s {s}",
                fit.fp
            );
        }
        check_sphere_laws(&fit, [true, true], 1e-9);
    }
    // a constant: the polynomial, exactly
    let ones = vec![1.0; theta.len()];
    let data = SphereData::new(&theta, &phi, &ones, None).unwrap();
    let fit = sphere_smoothing(&data, 3.5, 1e-16, &Progress::new()).unwrap();
    assert!(fit.fp < 1e-25 && (value(&fit, 1.0, 1.0) - 1.0).abs() < 1e-14);
}

fn grid_data(mu: usize, mv: usize, v0: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let u: Vec<f64> = (0..mu).map(|i| (i as f64 + 0.5) * PI / mu as f64).collect();
    let v: Vec<f64> = (0..mv)
        .map(|j| v0 + j as f64 * TWO_PI / mv as f64)
        .collect();
    let mut r = Vec::with_capacity(mu * mv);
    for &a in &u {
        for &b in &v {
            r.push(field(a, b));
        }
    }
    (u, v, r)
}

#[test]
fn grid_interpolates_at_zero_s_with_every_pole_condition() {
    let (u, v, r) = grid_data(9, 12, -1.0);
    let grid = SphereGrid::new(&u, &v, &r).unwrap();
    for continuity in [false, true] {
        for (value, exact) in [(None, false), (Some(1.8), true), (Some(1.7), false)] {
            for flat in [false, continuity] {
                let pole = PoleCondition {
                    value,
                    exact,
                    continuity,
                    flat,
                };
                let fit =
                    sphere_grid_smoothing(&grid, 0.0, [pole, pole], &Progress::new()).unwrap();
                let mut back = vec![0.0; r.len()];
                fit.spline.eval_grid(&[&u, &v], None, &mut back).unwrap();
                let err = back
                    .iter()
                    .zip(&r)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                assert!(err < 1e-12, "{pole:?}: error {err}");
                let north = value.unwrap_or_else(|| partial_of(&fit, 0.0));
                assert!((partial_of(&fit, 0.0) - north).abs() < 1e-12, "{pole:?}");
                for k in 0..8 {
                    let phi = v[0] + k as f64;
                    assert!(
                        (fit.spline.eval(&[0.0, phi.min(v[0] + TWO_PI)]).unwrap()[0] - north).abs()
                            < 1e-12
                    );
                    if flat {
                        let d = fit
                            .spline
                            .eval_partial(&[0.0, phi.min(v[0] + TWO_PI)], &[1, 0])
                            .unwrap()[0];
                        assert!(d.abs() < 1e-10, "not flat: {d}");
                    }
                }
            }
        }
    }
}

fn partial_of(fit: &SphereFit, theta: f64) -> f64 {
    let phi0 = fit.spline.knots()[1].as_slice()[3];
    fit.spline.eval(&[theta, phi0]).unwrap()[0]
}

/// SciPy's `test_negative_evaluation`: FITPACK's knots and pole values for `s = 0` give its
/// interpolated values to 6 decimals.
#[test]
fn grid_interpolation_matches_fitpack() {
    let lats = [25.0f64, 30.0, 35.0, 40.0, 45.0];
    let lons = [-90.0f64, -85.0, -80.0, -75.0, 70.0];
    let u: Vec<f64> = lats.iter().map(|d| d.to_radians()).collect();
    let v: Vec<f64> = lons.iter().map(|d| d.to_radians()).collect();
    // SciPy's data: meshgrid(lats, lons)[0] + [1], whose row i (the colatitude u_i) holds
    // lats + lons[i]
    let mut r = Vec::new();
    for lo in lons {
        for la in lats {
            r.push(la + lo);
        }
    }
    let grid = SphereGrid::new(&u, &v, &r).unwrap();
    let fit =
        sphere_grid_smoothing(&grid, 0.0, [PoleCondition::default(); 2], &Progress::new()).unwrap();
    let q = |la: f64, lo: f64| {
        fit.spline
            .eval(&[la.to_radians(), lo.to_radians()])
            .unwrap()[0]
    };
    let want = [[-45.0, -42.480862], [-49.0625, -46.54315]];
    for (i, la) in [35.0, 37.5].into_iter().enumerate() {
        for (j, lo) in [-80.0, -77.5].into_iter().enumerate() {
            assert!(
                (q(la, lo) - want[i][j]).abs() < 1.5e-6,
                "({la}, {lo}): {} vs {}",
                q(la, lo),
                want[i][j]
            );
        }
    }
}

#[test]
fn bad_input_is_refused_in_scipys_words() {
    let (t, p, r) = (vec![0.5, 1.0, 4.0], vec![0.1, 0.2, 0.3], vec![1.0; 3]);
    let e = SphereData::new(&t, &p, &r, None).unwrap_err();
    assert!(
        e.to_string().contains("theta should be between [0, pi]"),
        "{e}"
    );
    let p2 = vec![0.1, 7.0, 0.3];
    let t2 = vec![0.5, 1.0, 2.0];
    let e = SphereData::new(&t2, &p2, &r, None).unwrap_err();
    assert!(
        e.to_string().contains("phi should be between [0, 2pi]"),
        "{e}"
    );
    let w = vec![1.0, -1.0, 1.0];
    let e = SphereData::new(&t2, &p, &r, Some(&w)).unwrap_err();
    assert!(e.to_string().contains("w should be positive"), "{e}");
    let data = SphereData::new(&t2, &p, &r, None).unwrap();
    for (tt, tp, words) in [
        (vec![-0.1], vec![1.0], "tt should be between (0, pi)"),
        (vec![PI], vec![1.0], "tt should be between (0, pi)"),
        (vec![1.0], vec![TWO_PI], "tp should be between (0, 2pi)"),
    ] {
        let e = sphere_least_squares(&data, &tt, &tp, 1e-16).unwrap_err();
        assert!(e.to_string().contains(words), "{e}");
    }
    for eps in [0.0, 1.0] {
        let e = sphere_least_squares(&data, &[1.0], &[1.0], eps).unwrap_err();
        assert!(
            e.to_string().contains("eps should be between (0, 1)"),
            "{e}"
        );
    }
    let e = sphere_smoothing(&data, -1.0, 1e-16, &Progress::new()).unwrap_err();
    assert!(e.to_string().contains("s should be positive"), "{e}");
    let (u, v, r) = grid_data(5, 6, 0.0);
    let mut bad_u = u.clone();
    bad_u[0] = 0.0;
    let e = SphereGrid::new(&bad_u, &v, &r).unwrap_err();
    assert!(e.to_string().contains("u should be between (0, pi)"), "{e}");
    let bad_v: Vec<f64> = v.iter().map(|x| x - 3.5).collect();
    let e = SphereGrid::new(&u, &bad_v, &r).unwrap_err();
    assert!(
        e.to_string().contains("v[0] should be between [-pi, pi)"),
        "{e}"
    );
    let mut long_v = v.clone();
    long_v[5] = TWO_PI + 0.1;
    let e = SphereGrid::new(&u, &long_v, &r).unwrap_err();
    assert!(
        e.to_string().contains("v[-1] should be v[0] + 2pi or less"),
        "{e}"
    );
    let e = SphereGrid::new(&u, &v, &r[1..]).unwrap_err();
    assert!(matches!(e, Error::LengthMismatch { .. }), "{e}");
    let grid = SphereGrid::new(&u, &v, &r).unwrap();
    let e = sphere_grid_smoothing(&grid, -1.0, [PoleCondition::default(); 2], &Progress::new())
        .unwrap_err();
    assert!(e.to_string().contains("s should be positive"), "{e}");
    let flat = PoleCondition {
        flat: true,
        ..PoleCondition::default()
    };
    let e = sphere_grid_smoothing(
        &grid,
        0.0,
        [flat, PoleCondition::default()],
        &Progress::new(),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("if pole_continuity is False, so must be pole_flat"),
        "{e}"
    );
}

proptest! {
    #![proptest_config(crate::oracle::proptest_config(16))]

    /// On a grid, for any `s` between 0 and the residual of the spline without interior
    /// knots: the residual is at most `s` (within `SMOOTHING_RTOL·s` of it when smoothed), the
    /// spline is periodic in φ with one value at each pole, and a constant added to the data
    /// is added to the fit.
    #[test]
    fn grid_smoothing_meets_s(
        mu in 5usize..12,
        mv in 5usize..14,
        v0 in -3.0f64..3.0,
        fraction in 0.01f64..0.9,
        continuity in any::<bool>(),
        noise in proptest::collection::vec(-0.05f64..0.05, 17),
        offset in -100.0f64..100.0,
    ) {
        let (u, v, mut r) = grid_data(mu, mv, v0);
        for (k, x) in r.iter_mut().enumerate() {
            *x += noise[k % noise.len()];
        }
        let pole = PoleCondition { continuity, ..PoleCondition::default() };
        let grid = SphereGrid::new(&u, &v, &r).unwrap();
        let top = sphere_grid_smoothing(&grid, 1e12, [pole; 2], &Progress::new()).unwrap();
        let s = fraction * top.fp;
        prop_assume!(s > 1e-8);
        let fit = sphere_grid_smoothing(&grid, s, [pole; 2], &Progress::new()).unwrap();
        prop_assert!(fit.fp <= s * (1.0 + SMOOTHING_RTOL), "fp {} > s {}", fit.fp, s);
        if fit.p.is_some() {
            prop_assert!(fit.fp >= (1.0 - SMOOTHING_RTOL) * s);
        }
        let ends = fit.spline.knots()[1].as_slice();
        let (a, b) = (ends[3], ends[ends.len() - 4]);
        prop_assert!((b - a - TWO_PI).abs() < 1e-12);
        for &t in &[0.0, 1.0, PI] {
            let (x, y) = (fit.spline.eval(&[t, a]).unwrap()[0], fit.spline.eval(&[t, b]).unwrap()[0]);
            prop_assert!((x - y).abs() < 1e-9);
        }
        let n0 = fit.spline.eval(&[0.0, a]).unwrap()[0];
        let n1 = fit.spline.eval(&[0.0, a + 2.0]).unwrap()[0];
        prop_assert!((n0 - n1).abs() < 1e-9);
        let shifted: Vec<f64> = r.iter().map(|x| x + offset).collect();
        let moved = sphere_grid_smoothing(&SphereGrid::new(&u, &v, &shifted).unwrap(), s, [pole; 2], &Progress::new()).unwrap();
        prop_assert_eq!(moved.spline.shape(), fit.spline.shape());
        let x = moved.spline.eval(&[1.0, a + 1.0]).unwrap()[0] - offset;
        let y = fit.spline.eval(&[1.0, a + 1.0]).unwrap()[0];
        prop_assert!((x - y).abs() < 1e-7 * (1.0 + offset.abs()), "{} vs {}", x, y);
    }

    /// Least squares on scattered data: periodic, one value at each pole, derivatives across
    /// the poles of the form `a cos φ + b sin φ`, and constants reproduced.
    #[test]
    fn scattered_laws(
        m in 150usize..300,
        c in -10.0f64..10.0,
        ntt in 1usize..5,
    ) {
        let (theta, phi) = spiral(m);
        let tt: Vec<f64> = (1..=ntt).map(|i| PI * i as f64 / (ntt + 1) as f64).collect();
        let tp = [PI / 2.0, PI, 3.0 * PI / 2.0, 1.0];
        let mut tp = tp.to_vec();
        tp.sort_by(f64::total_cmp);
        let r: Vec<f64> = theta.iter().zip(&phi).map(|(&t, &p)| field(t, p) + c).collect();
        let data = SphereData::new(&theta, &phi, &r, None).unwrap();
        let fit = sphere_least_squares(&data, &tt, &tp, 1e-16).unwrap();
        check_sphere_laws(&fit, [true, true], 1e-9);
        let flat = vec![c; m];
        let data = SphereData::new(&theta, &phi, &flat, None).unwrap();
        let fit = sphere_least_squares(&data, &tt, &tp, 1e-16).unwrap();
        prop_assert!((fit.spline.eval(&[1.1, 2.2]).unwrap()[0] - c).abs() < 1e-11 * (1.0 + c.abs()));
    }
}

/// No data, one point, or weights that are all 0 are refused as FITPACK refuses them
/// (`m >= 2`, a positive weight): each made a spline with `fp = 0` and no error.
#[test]
fn empty_data_or_all_zero_weights_are_refused() {
    for m in [0, 1] {
        let t = vec![1.0; m];
        let e = SphereData::new(&t, &t, &t, None).unwrap_err();
        assert!(
            matches!(e, Error::TooFew { min: 2, got, .. } if got == m),
            "{e:?}"
        );
    }
    let (theta, phi) = spiral(50);
    let r = vec![1.0; 50];
    let w = vec![0.0; 50];
    let e = SphereData::new(&theta, &phi, &r, Some(&w)).unwrap_err();
    assert!(e.to_string().contains("every weight is 0"), "{e}");
    let mut w = w;
    w[7] = 1.0;
    assert!(SphereData::new(&theta, &phi, &r, Some(&w)).is_ok());
}

/// Values near the largest double (`r * 1e300`) made the residual sums of squares infinite and
/// the spline NaN, refused later as "coordinates" that the caller never gave: they are refused
/// naming `r`, its index and the rescaling; just inside the bound, a constant is still
/// reproduced exactly (the bound leaves the fit's arithmetic finite).
#[test]
fn values_whose_squares_overflow_are_refused_naming_r() {
    let (theta, phi) = spiral(60);
    let m = theta.len();
    let bound = (f64::MAX / m as f64).sqrt() / RESIDUAL_HEADROOM;
    let mut r: Vec<f64> = theta.iter().zip(&phi).map(|(t, p)| field(*t, *p)).collect();
    r.iter_mut().for_each(|v| *v *= 1e300);
    let e = SphereData::new(&theta, &phi, &r, None).unwrap_err();
    assert_eq!(e.arg(), None, "{e:?}");
    let msg = e.to_string();
    assert!(msg.starts_with("invalid r: r["), "{msg}");
    assert!(msg.contains("divide r by a power of ten"), "{msg}");
    // the weight counts: modest values with a huge weight are the same overflow
    let ones = vec![1.0; m];
    let w = vec![1e300; m];
    let e = SphereData::new(&theta, &phi, &ones, Some(&w)).unwrap_err();
    assert!(e.to_string().contains("(times its weight)"), "{e}");
    // just inside the bound: a constant is reproduced
    let c = bound * 0.99;
    let flat = vec![c; m];
    let data = SphereData::new(&theta, &phi, &flat, None).unwrap();
    let fit = sphere_least_squares(&data, &[1.0, 2.0], &[1.0, 3.0], 1e-16).unwrap();
    for (t, p) in [(0.3, 1.0), (1.5, 4.0), (PI, 0.0)] {
        assert!(
            (value(&fit, t, p) / c - 1.0).abs() < 1e-12,
            "{} at ({t}, {p})",
            value(&fit, t, p)
        );
    }
    // a grid alike
    let (u, v, mut rg) = grid_data(6, 8, 0.0);
    rg.iter_mut().for_each(|x| *x *= 1e300);
    let e = SphereGrid::new(&u, &v, &rg).unwrap_err();
    assert!(e.to_string().starts_with("invalid r: r["), "{e}");
}
