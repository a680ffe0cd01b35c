//! Condition estimate of curve interpolation: `CurveInterpolation::condition` against
//! the dense `κ_1` of the collocation matrix, the limit of `CurveInterpolation::max_condition`,
//! and what nearly coincident points do to the condition number and to the interpolant.

use lekalo_testkit::config;

use lekalo::basis::basis_functions;
use lekalo::{
    parametrize, BSplineCurve, CurveInterpolation, EndCondition, Error, KnotPlacement, KnotVector,
    Parametrization, Points, PointsRef, SurfaceInterpolation,
};
use proptest::prelude::*;

/// Residual tolerance at the data relative to the data's extent (the interpolation tests' criterion).
const REL: f64 = 1e-12;

/// `n` unit-spaced points on a wave, 2-D.
fn wave(n: usize) -> Vec<[f64; 2]> {
    (0..n).map(|k| [k as f64, (k as f64).sin()]).collect()
}

/// The wave with an extra point `gap` beyond point 4 (so points 4 and 5 nearly coincide).
fn with_near_duplicate(gap: f64) -> Points {
    let mut d = wave(10);
    d.insert(5, [d[4][0] + gap, d[4][1]]);
    Points::from_2d(&d).unwrap()
}

/// Largest distance (max-norm) of the curve at the parameters from the data, relative to the
/// data's extent.
fn relative_residual(curve: &BSplineCurve, q: PointsRef<'_>, t: &[f64]) -> f64 {
    let data = q.as_slice();
    let extent = data.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0_f64;
    for (k, tk) in t.iter().enumerate() {
        let c = curve.eval(*tk).unwrap();
        for (a, b) in c.iter().zip(q.point(k)) {
            worst = worst.max((a - b).abs());
        }
    }
    worst / extent
}

/// Dense `κ_1` (test-only reference, O(n³)) of the free-end collocation matrix that
/// `interpolate` solves: rows `t̄_1 … t̄_{n−1}`, unknowns `P_1 … P_{n−1}`,
/// `A[r][c] = N_{c+1,p}(t̄_{r+1})`, with the knots of the curve it returns.
fn dense_free_end_kappa(curve: &BSplineCurve, t: &[f64]) -> f64 {
    let p = curve.degree();
    let m = t.len() - 2;
    let mut a = vec![0.0; m * m];
    for r in 0..m {
        let (span, vals) = basis_functions(curve.knots(), p, t[r + 1]).unwrap();
        for (j, v) in vals.iter().enumerate() {
            let i = span - p + j;
            if (1..=m).contains(&i) {
                a[r * m + i - 1] = *v;
            }
        }
    }
    norm1(&a, m) * norm1(&inverse(&a, m), m)
}

fn norm1(a: &[f64], n: usize) -> f64 {
    (0..n)
        .map(|c| (0..n).map(|r| a[r * n + c].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// Gauss–Jordan inverse with partial pivoting.
fn inverse(a: &[f64], n: usize) -> Vec<f64> {
    let mut m = a.to_vec();
    let mut inv = vec![0.0; n * n];
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    for k in 0..n {
        let piv = (k..n)
            .max_by(|&x, &y| m[x * n + k].abs().total_cmp(&m[y * n + k].abs()))
            .unwrap();
        for j in 0..n {
            m.swap(k * n + j, piv * n + j);
            inv.swap(k * n + j, piv * n + j);
        }
        let d = m[k * n + k];
        assert!(d != 0.0, "singular reference matrix");
        for j in 0..n {
            m[k * n + j] /= d;
            inv[k * n + j] /= d;
        }
        for i in (0..n).filter(|&i| i != k) {
            let f = m[i * n + k];
            if f != 0.0 {
                for j in 0..n {
                    m[i * n + j] -= f * m[k * n + j];
                    inv[i * n + j] -= f * inv[k * n + j];
                }
            }
        }
    }
    inv
}

#[test]
fn well_spaced_data_are_well_conditioned() {
    // uniform cubic: interior rows (1/6, 2/3, 1/6), κ_1 ≈ 5.48 for any length
    let q = Points::from_2d(&wave(200)).unwrap();
    for param in [Parametrization::Uniform, Parametrization::ChordLength] {
        let kappa = CurveInterpolation::new(3)
            .parametrization(param)
            .condition(q.as_view())
            .unwrap();
        assert!((1.0..10.0).contains(&kappa), "{param:?}: κ_1 = {kappa}");
    }
    // degree 1 interpolation solves the identity (exactly with the parameters k/256, whose
    // hat functions are exactly 1 at their knots); two points leave nothing to solve
    let q = Points::from_2d(&wave(257)).unwrap();
    let linear = CurveInterpolation::new(1)
        .parametrization(Parametrization::Uniform)
        .condition(q.as_view())
        .unwrap();
    assert_eq!(linear, 1.0);
    let two = Points::from_2d(&[[0.0, 0.0], [1.0, 2.0]]).unwrap();
    assert_eq!(
        CurveInterpolation::new(1).condition(two.as_view()).unwrap(),
        1.0
    );
}

#[test]
fn estimate_matches_the_dense_condition_number() {
    // uneven spacing, degrees 2, 3, 5, chord length: the estimate is a lower bound within 3
    let mut d = wave(14);
    for (k, p) in d.iter_mut().enumerate() {
        p[0] += 0.4 * ((k * k) as f64).sin();
    }
    let q = Points::from_2d(&d).unwrap();
    let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
    for p in [2, 3, 5] {
        let interp = CurveInterpolation::new(p);
        let curve = interp.interpolate(q.as_view()).unwrap();
        let exact = dense_free_end_kappa(&curve, &t);
        let est = interp.condition(q.as_view()).unwrap();
        assert!(
            est >= exact / 3.0 && est <= exact * (1.0 + 1e-12),
            "degree {p}: estimate {est}, dense {exact}"
        );
    }
}

#[test]
fn nearly_coincident_points_are_ill_conditioned_but_still_interpolated() {
    // Measured (gap g between points 4 and 5 of unit-spaced data, chord length, cubic):
    // κ_1 ≈ 3.5/g — 3.5e3 for g = 1e-3, 3.5e12 for g = 1e-12 — while the residual at the data
    // stays at rounding level (~1e-15): the elimination is backward stable (totally positive
    // matrix, de Boor & Pinkus 1977), so a large κ_1 bounds the error of the control points,
    // not of the interpolation conditions. Centripetal parameters cut κ_1 by √g.
    let q = with_near_duplicate(1e-12);
    let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
    let chord = CurveInterpolation::new(3);
    let kappa = chord.condition(q.as_view()).unwrap();
    assert!(kappa > 1e11, "κ_1 = {kappa}");
    let centripetal = chord
        .clone()
        .parametrization(Parametrization::Centripetal)
        .condition(q.as_view())
        .unwrap();
    assert!(
        centripetal < kappa * 1e-5,
        "centripetal κ_1 = {centripetal}"
    );

    // without a limit: an accurate interpolant (default fused path and general path alike)
    let curve = chord.interpolate(q.as_view()).unwrap();
    let res = relative_residual(&curve, q.as_view(), &t);
    assert!(res <= REL, "relative residual {res}");
    let general = chord.clone().max_condition(f64::INFINITY);
    let other = general.interpolate(q.as_view()).unwrap();
    let res = relative_residual(&other, q.as_view(), &t);
    assert!(res <= REL, "general path: relative residual {res}");
    // the two paths round their Cox–de Boor rows differently (the fused one shares the
    // reciprocals of the knot differences): their control points may differ by up to about
    // κ·ε of the data's extent, here ~1e-5 of it, while both fit the data to rounding
    let extent = q.as_slice().iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let worst = other
        .control_points()
        .as_slice()
        .iter()
        .zip(curve.control_points().as_slice())
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        worst <= kappa * f64::EPSILON * extent,
        "paths differ by {worst:e} (κ_1 = {kappa:e})"
    );

    // with a limit: a clear error naming the estimate, the limit and the fix
    let e = chord
        .clone()
        .max_condition(1e8)
        .interpolate(q.as_view())
        .unwrap_err();
    let Error::IllConditioned { reason } = &e else {
        panic!("expected IllConditioned, got {e:?}");
    };
    assert!(reason.contains(&format!("{kappa:.3e}")), "{reason}");
    assert!(reason.contains("1e8"), "{reason}");
    assert!(reason.contains("centripetal"), "{reason}");
    // the limit is a bound on the estimate, not a threshold on the data: just above passes
    assert!(chord
        .max_condition(kappa * 1.001)
        .interpolate(q.as_view())
        .is_ok());
}

#[test]
fn every_end_condition_is_estimated() {
    let q = with_near_duplicate(1e-9);
    let well = Points::from_2d(&wave(12)).unwrap();
    let d = vec![1.0, 0.0];
    let configs = [
        CurveInterpolation::new(3).end_condition(EndCondition::FirstDerivatives {
            start: d.clone(),
            end: d.clone(),
        }),
        CurveInterpolation::new(4).end_condition(EndCondition::FirstDerivatives {
            start: d.clone(),
            end: d.clone(),
        }),
        CurveInterpolation::new(3).end_condition(EndCondition::Natural),
        CurveInterpolation::new(3).end_condition(EndCondition::SecondDerivatives {
            start: d.clone(),
            end: d.clone(),
        }),
        CurveInterpolation::new(2).knot_placement(KnotPlacement::Uniform),
        CurveInterpolation::new(5),
    ];
    for c in configs {
        let bad = c.condition(q.as_view()).unwrap();
        let good = c.condition(well.as_view()).unwrap();
        assert!(bad > 1e7 && good < 1e3, "{c:?}: κ_1 {bad} vs {good}");
        assert!(matches!(
            c.clone().max_condition(1e6).interpolate(q.as_view()),
            Err(Error::IllConditioned { .. })
        ));
        // under the limit the result is the unlimited one
        assert_eq!(
            c.clone()
                .max_condition(1e6)
                .interpolate(well.as_view())
                .unwrap(),
            c.interpolate(well.as_view()).unwrap(),
            "{c:?}"
        );
    }
}

#[test]
fn interpolate_at_honours_the_limit() {
    let t = [0.0, 1.0, 2.0, 2.0 + 1e-10, 3.0, 4.0, 5.0];
    let y = Points::from_flat(1, vec![0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
    let e = CurveInterpolation::new(3)
        .max_condition(1e8)
        .interpolate_at(y.as_view(), &t)
        .unwrap_err();
    assert!(matches!(e, Error::IllConditioned { .. }), "{e:?}");
    assert!(CurveInterpolation::new(3)
        .interpolate_at(y.as_view(), &t)
        .is_ok());
}

#[test]
fn invalid_limit_is_invalid_argument() {
    let q = Points::from_2d(&wave(8)).unwrap();
    for limit in [0.5, 0.0, -1.0, f64::NAN] {
        let e = CurveInterpolation::new(3)
            .max_condition(limit)
            .interpolate(q.as_view())
            .unwrap_err();
        assert!(
            matches!(
                e,
                Error::InvalidArgument { what, .. } if what.words().contains("max_condition")
            ),
            "{limit}: {e:?}"
        );
    }
}

#[test]
fn periodic_curves_have_no_estimate_yet() {
    let q = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap();
    let closed = CurveInterpolation::new(3).end_condition(EndCondition::Periodic);
    for r in [
        closed.condition(q.as_view()),
        closed
            .clone()
            .max_condition(1e8)
            .interpolate(q.as_view())
            .map(|_| 0.0),
    ] {
        assert!(
            matches!(r, Err(Error::InvalidArgument { ref reason, .. }) if reason.contains("periodic")),
            "{r:?}"
        );
    }
    assert!(closed.interpolate(q.as_view()).is_ok());
}

/// Dense `κ_1` of the full collocation matrix `A[k][i] = N_{i,p}(t[k])` (all rows and columns,
/// as the surface passes solve them).
fn dense_full_kappa(knots: &KnotVector, p: usize, t: &[f64]) -> f64 {
    let m = t.len();
    let mut a = vec![0.0; m * m];
    for (k, tk) in t.iter().enumerate() {
        let (span, vals) = basis_functions(knots, p, *tk).unwrap();
        for (j, v) in vals.iter().enumerate() {
            a[k * m + span - p + j] = *v;
        }
    }
    norm1(&a, m) * norm1(&inverse(&a, m), m)
}

/// A 7 × 5 grid on a wavy sheet; row 3 moved to `gap` beyond row 2.
fn sheet(gap: Option<f64>) -> Points {
    let mut data = Vec::new();
    for k in 0..7 {
        let x = match gap {
            Some(g) if k == 3 => 2.0 + g,
            _ => f64::from(k),
        };
        for l in 0..5 {
            let y = f64::from(l) * (1.0 + 0.1 * f64::from(l));
            data.extend([x, y, (0.5 * x).sin() * (0.3 * y).cos()]);
        }
    }
    Points::from_flat(3, data).unwrap()
}

#[test]
fn surface_estimate_is_the_product_of_the_directions() {
    for (gap, p, q) in [(None, 3, 3), (None, 2, 4), (Some(1e-6), 3, 2)] {
        let grid = sheet(gap);
        let fit = SurfaceInterpolation::new(p, q).parametrization(Parametrization::ChordLength);
        let (s, report) = fit.interpolate_with_report(grid.as_view(), 7, 5).unwrap();
        let exact = dense_full_kappa(s.knots_u(), p, report.params_u())
            * dense_full_kappa(s.knots_v(), q, report.params_v());
        let est = fit.condition(grid.as_view(), 7, 5).unwrap();
        assert_eq!(report.condition(), est, "the report's estimate");
        // each direction's estimate is within 3 below its κ_1 (f64 solves: relative κ·ε)
        assert!(
            est >= exact / 9.0 && est <= exact * (1.0 + 64.0 * f64::EPSILON * exact),
            "{gap:?}, ({p}, {q}): estimate {est}, dense {exact}"
        );
        // under the limit the result is the unlimited one
        let limited = fit
            .clone()
            .max_condition(1e15)
            .interpolate(grid.as_view(), 7, 5)
            .unwrap();
        assert_eq!(limited, s);
        assert_eq!(fit.interpolate(grid.as_view(), 7, 5).unwrap(), s);
    }
}

#[test]
fn surface_with_crowded_rows_is_ill_conditioned() {
    let grid = sheet(Some(1e-10));
    let fit = SurfaceInterpolation::new(3, 3).parametrization(Parametrization::ChordLength);
    let kappa = fit.condition(grid.as_view(), 7, 5).unwrap();
    assert!(kappa > 1e9, "κ_1 = {kappa}");
    let e = fit
        .clone()
        .max_condition(1e8)
        .interpolate(grid.as_view(), 7, 5)
        .unwrap_err();
    let Error::IllConditioned { reason } = &e else {
        panic!("expected IllConditioned, got {e:?}");
    };
    assert!(
        reason.contains(&format!("{kappa:.3e}")) && reason.contains("1e8"),
        "{reason}"
    );
    // well-spaced: small
    let fine = fit.condition(sheet(None).as_view(), 7, 5).unwrap();
    assert!(fine < 100.0, "κ_1 = {fine}");
    for limit in [0.0, f64::NAN] {
        assert!(matches!(
            fit.clone()
                .max_condition(limit)
                .interpolate(grid.as_view(), 7, 5),
            Err(Error::InvalidArgument { .. })
        ));
    }
}

proptest! {
    #![proptest_config(config(32))]

    /// Random steps (ratios up to 1e4) and degrees: the estimate is within a factor 3 below the
    /// dense κ_1 of the collocation matrix and not above it.
    #[test]
    fn estimate_is_a_tight_lower_bound(
        steps in prop::collection::vec(1e-4_f64..1.0, 6..30),
        p in 2usize..6,
    ) {
        let mut x = 0.0;
        let mut d = vec![[0.0, 0.0]];
        for (k, s) in steps.iter().enumerate() {
            x += s;
            d.push([x, if k % 2 == 0 { 0.3 * s } else { -0.2 * s }]);
        }
        let q = Points::from_2d(&d).unwrap();
        prop_assume!(p < d.len());
        let interp = CurveInterpolation::new(p);
        let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
        let curve = interp.interpolate(q.as_view()).unwrap();
        let exact = dense_free_end_kappa(&curve, &t);
        let est = interp.condition(q.as_view()).unwrap();
        // both are computed in f64: relative errors of order κ_1·ε
        prop_assert!(
            est >= exact / 3.0 && est <= exact * (1.0 + 64.0 * f64::EPSILON * exact),
            "degree {}: estimate {}, dense {}", p, est, exact
        );
    }
}

/// `n` points of a wobbly 3-D helix, unevenly spaced (as the interpolation benchmark's).
fn helix(n: usize) -> Points {
    let mut data = Vec::with_capacity(3 * n);
    for i in 0..n {
        let s = i as f64 * 0.01;
        let w = s + 0.003 * (7.0 * s).sin();
        data.extend([w.cos(), w.sin(), 0.1 * w + 0.01 * (3.0 * w).cos()]);
    }
    Points::from_flat(3, data).unwrap()
}

#[test]
fn uniform_knots_on_chord_parameters_are_never_silently_wrong() {
    // Uniform knots ignore where the chord-length parameters fall: on this helix the
    // collocation matrix's κ_1 grows from 43 at 20 points to 1e17 at 100 and 1e43 at 200.
    // Whatever the size, the result either passes within the documented residual bound
    // (INTERPOLATION_RESIDUAL_RTOL of the extent plus the evaluation's rounding) or is an error.
    let mut refused = Vec::new();
    for n in [20, 50, 100, 200, 1000, 3000] {
        let q = helix(n);
        let t = parametrize(q.as_view(), Parametrization::ChordLength).unwrap();
        let got = CurveInterpolation::new(3)
            .knot_placement(KnotPlacement::Uniform)
            .interpolate(q.as_view());
        match got {
            Ok(curve) => {
                // relative_residual divides by the largest |coordinate| (about the extent here)
                let r = relative_residual(&curve, q.as_view(), &t);
                assert!(
                    r <= 2.0 * lekalo::INTERPOLATION_RESIDUAL_RTOL,
                    "n = {n}: Ok with residual {r:e}"
                );
            }
            Err(e) => {
                assert!(
                    matches!(
                        e,
                        Error::IllConditioned { .. } | Error::SingularSystem { .. }
                    ),
                    "n = {n}: {e}"
                );
                refused.push(n);
            }
        }
    }
    // 200 and 1000 points used to come back as Ok, up to 1e21 away from the data
    assert!(
        refused.contains(&200) && refused.contains(&1000),
        "refused: {refused:?}"
    );
    let e = CurveInterpolation::new(3)
        .knot_placement(KnotPlacement::Uniform)
        .interpolate(helix(1000).as_view())
        .unwrap_err();
    assert!(e.to_string().contains("misses data point"), "{e}");
}

#[test]
fn end_derivatives_far_beyond_the_data_scale_are_refused_not_returned_off_the_data() {
    // end derivatives up to 1e6 on data of size 4 interpolate within the bound; 1e12 makes
    // control points of 1e11 whose evaluations cancel to a miss of 7e-7: refused, with the
    // control points' size in the message
    let q = Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.5], [3.0, 2.0], [4.0, 0.0]]).unwrap();
    let first = |d: f64| EndCondition::FirstDerivatives {
        start: vec![d, 0.0],
        end: vec![0.0, d],
    };
    let second = |d: f64| EndCondition::SecondDerivatives {
        start: vec![d, 0.0],
        end: vec![0.0, d],
    };
    for d in [1.0, 1e3, 1e6] {
        for end in [first(d), second(d)] {
            let c = CurveInterpolation::new(3)
                .end_condition(end)
                .interpolate(q.as_view());
            assert!(c.is_ok(), "d = {d:e}: {c:?}");
        }
    }
    let e = CurveInterpolation::new(3)
        .end_condition(first(1e12))
        .interpolate(q.as_view())
        .unwrap_err();
    assert!(matches!(e, Error::IllConditioned { .. }), "{e}");
    assert!(e.to_string().contains("control points reach"), "{e}");
    assert!(e.to_string().contains("end derivatives"), "{e}");
}
