//! Tests of the shape-constrained fits: exactness by independent root finding, inactive
//! constraints, infeasibility, golden values from an independent conic solver.

use super::*;
use crate::fit::{least_squares, smoothing_spline, EndConstraints, FitData, Lambda};
use crate::{BSplineCurve, KnotVector, PointsRef};
use serde_json::Value;

/// The least value of `σ(y⁽ʳ⁾ − v)` over `[a, b]`, found independently of the fit's Bernstein
/// rows: on each span, the Taylor polynomial of `y⁽ʳ⁾` (degree ≤ 3) at the span's start from
/// [`BSplineCurve::eval_derivatives`], minimised at the ends and at the real roots of its
/// derivative (quadratic formula).
fn min_by_roots(curve: &BSplineCurve, r: usize, sigma: f64, v: f64, a: f64, b: f64) -> f64 {
    let p = curve.degree();
    let t = curve.knots().as_slice();
    let mut m = f64::INFINITY;
    for s in p..t.len() - p - 1 {
        let (lo, hi) = (t[s].max(a), t[s + 1].min(b));
        if lo >= hi {
            continue;
        }
        // Taylor coefficients of y⁽ʳ⁾ at t[s] (right limits: evaluate just inside is not exact,
        // so use the polynomial of the span through the derivatives at its midpoint)
        let mid = 0.5 * (t[s] + t[s + 1]);
        let ders = curve.eval_derivatives(mid, p).unwrap();
        let g: Vec<f64> = (r..=p).map(|k| ders.point(k)[0]).collect();
        let eval = |x: f64| {
            let h = x - mid;
            let mut acc = 0.0;
            let mut f = 1.0;
            for (k, gk) in g.iter().enumerate() {
                if k > 0 {
                    f *= h / k as f64;
                }
                acc += gk * f;
            }
            sigma * (acc - v)
        };
        let mut cand = vec![lo, hi];
        // roots of the derivative of y⁽ʳ⁾ (degree ≤ 2 in h): g1 + g2 h + g3 h²/2
        let (c0, c1, c2) = (
            g.get(1).copied().unwrap_or(0.0),
            g.get(2).copied().unwrap_or(0.0),
            0.5 * g.get(3).copied().unwrap_or(0.0),
        );
        if c2 != 0.0 {
            let disc = c1 * c1 - 4.0 * c2 * c0;
            if disc >= 0.0 {
                let qq = -0.5 * (c1 + c1.signum() * disc.sqrt());
                if qq != 0.0 {
                    cand.push(mid + qq / c2);
                    cand.push(mid + c0 / qq);
                }
            }
        } else if c1 != 0.0 {
            cand.push(mid - c0 / c1);
        }
        for x in cand.into_iter().filter(|x| *x >= lo && *x <= hi) {
            m = m.min(eval(x));
        }
    }
    m
}

fn noisy(n: usize, f: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    let y = x
        .iter()
        .enumerate()
        .map(|(k, &t)| f(t) + 0.05 * (((k * 7919) % 101) as f64 / 50.0 - 1.0))
        .collect();
    (x, y)
}

#[test]
fn increasing_cubic_holds_exactly() {
    let (x, y) = noisy(200, |t| (6.0 * t).sin() * 0.2 + t);
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 20).unwrap();
    let c = ShapeConstraints::new().with(Shape::Increasing);
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    let m = min_by_roots(&fit.curve, 1, 1.0, 0.0, 0.0, 1.0);
    let free = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
    assert!(m >= -1e-12, "min y' = {m}");
    // the constraint binds: the fit gives up some of the free fit's residual
    assert!(
        fit.report.weighted_rss > free.report.weighted_rss,
        "constraint inactive"
    );
}

/// The constraints of a golden case (`tests/data/shape_golden.py`).
fn golden_constraints(case: &Value) -> ShapeConstraints {
    let mut c = ShapeConstraints::new();
    for s in case["shapes"].as_array().unwrap() {
        let level = s["level"].as_f64().unwrap_or(0.0);
        let shape = match s["shape"].as_str().unwrap() {
            "increasing" => Shape::Increasing,
            "decreasing" => Shape::Decreasing,
            "convex" => Shape::Convex,
            "concave" => Shape::Concave,
            "min" => Shape::AtLeast(level),
            "max" => Shape::AtMost(level),
            other => panic!("unknown shape {other}"),
        };
        c = match s["interval"].as_array() {
            Some(ab) => c.with_on(shape, ab[0].as_f64().unwrap(), ab[1].as_f64().unwrap()),
            None => c.with(shape),
        };
    }
    for q in case["points"].as_array().map_or(&[][..], |v| v.as_slice()) {
        c = c.with_point(
            q["x"].as_f64().unwrap(),
            usize::try_from(q["derivative"].as_u64().unwrap()).unwrap(),
            q["value"].as_f64().unwrap(),
        );
    }
    c
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// `∫ y''²` of a cubic spline: `y''` is linear on each span, `h/3 (a² + ab + b²)`.
fn curvature_energy(curve: &BSplineCurve) -> f64 {
    let t = curve.knots().as_slice();
    let p = curve.degree();
    let mut e = 0.0;
    for s in p..t.len() - p - 1 {
        let h = t[s + 1] - t[s];
        if h <= 0.0 {
            continue;
        }
        // exact values at the ends of the span from the midpoint's Taylor expansion
        let mid = 0.5 * (t[s] + t[s + 1]);
        let d = curve.eval_derivatives(mid, 3).unwrap();
        let (m2, m3) = (d.point(2)[0], d.point(3)[0]);
        let (a, b) = (m2 - 0.5 * h * m3, m2 + 0.5 * h * m3);
        e += h / 3.0 * (a * a + a * b + b * b);
    }
    e
}

/// Golden values from an independent conic program of the same formulation (CVXPY + Clarabel,
/// `tests/data/shape_golden.py`): fitted values within 1e-8 of the data's range, an objective
/// no worse than the reference's by 1e-9 relative, and every shape holding by root finding.
#[test]
fn golden_values_from_an_independent_conic_program() {
    let golden: Value =
        serde_json::from_str(include_str!("../../../tests/data/shape_golden.json")).unwrap();
    for case in golden["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let (x, y) = (floats(&case["x"]), floats(&case["y"]));
        let w = case.get("w").filter(|w| !w.is_null()).map(floats);
        let mut data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        if let Some(w) = &w {
            data = data.with_weights(w).unwrap();
        }
        let c = golden_constraints(case);
        let degree = usize::try_from(case["degree"].as_u64().unwrap()).unwrap();
        let lambda = case["lambda"].as_f64();
        let fit = match lambda {
            Some(l) => constrained_smoothing_spline(&data, Lambda::Given(l), &c).unwrap(),
            None => {
                let kv = KnotVector::new(floats(&case["knots"])).unwrap();
                constrained_least_squares(&data, degree, &kv, &c).unwrap()
            }
        };
        let range = y.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v))
            - y.iter().fold(f64::INFINITY, |m, v| m.min(*v));
        let objective =
            fit.report.weighted_rss + lambda.map_or(0.0, |l| l * curvature_energy(&fit.curve));
        let reference = case["objective"].as_f64().unwrap();
        eprintln!(
            "{name}: objective {objective:.17e} reference {reference:.17e} ({:e} relative)",
            (objective - reference) / reference
        );
        for (xs, want) in [("x", "values_at_x"), ("grid", "values_at_grid")] {
            let (xs, want) = (floats(&case[xs]), floats(&case[want]));
            let mut got = vec![0.0; xs.len()];
            fit.curve.eval_batch(&xs, &mut got).unwrap();
            let worst = got
                .iter()
                .zip(&want)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(
                worst <= 1e-8 * range,
                "{name}: values differ by {worst:e} (range {range})"
            );
        }
        assert!(
            objective <= reference * (1.0 + 1e-9),
            "{name}: objective {objective} above the reference {reference}"
        );
        let (lo, hi) = fit.curve.domain();
        let scale = y.iter().map(|v| (v - y[0]).abs()).fold(0.0, f64::max);
        for s in &c.shapes {
            let r = s.shape.derivative_order();
            let (a, b) = s.interval.unwrap_or((lo, hi));
            let m = min_by_roots(&fit.curve, r, s.shape.sign(), s.shape.level(), a, b);
            let tol = 1e-12 * scale / (hi - lo).powi(i32::try_from(r).unwrap());
            assert!(m >= -tol, "{name}: {s} violated by {m:e}");
        }
        for q in &c.points {
            let v = fit.curve.eval_derivatives(q.x, q.derivative).unwrap();
            let err = (v.point(q.derivative)[0] - q.value).abs();
            assert!(err <= 1e-12 * scale, "{name}: {q} off by {err:e}");
        }
    }
}

#[test]
fn inactive_constraints_return_the_unconstrained_fit() {
    let (x, y) = noisy(80, |t| 2.0 * t + t * t);
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 8).unwrap();
    let c = ShapeConstraints::new()
        .with(Shape::Increasing)
        .with(Shape::AtLeast(-1.0))
        .with_on(Shape::AtMost(10.0), 0.2, 0.9);
    let free = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    assert_eq!(fit, free, "inactive constraints changed the fit");
    let free = smoothing_spline(&data, Lambda::Given(1e-3)).unwrap();
    let fit = constrained_smoothing_spline(&data, Lambda::Given(1e-3), &c).unwrap();
    assert_eq!(
        fit, free,
        "inactive constraints changed the smoothing spline"
    );
}

#[test]
fn constraints_on_an_interval_and_gcv_hold_exactly() {
    let (x, y) = noisy(150, |t| (5.0 * t).sin());
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let c = ShapeConstraints::new()
        .with_on(Shape::Increasing, 0.0, 0.3)
        .with_on(Shape::Concave, 0.1, 0.7)
        .with_on(Shape::AtLeast(0.0), 0.5, 1.0);
    let fit = constrained_smoothing_spline(&data, Lambda::Gcv, &c).unwrap();
    assert!(fit.report.lambda.unwrap() > 0.0, "GCV chose no λ");
    for (s, (r, sigma, v, a, b)) in [
        (1, 1.0, 0.0, 0.0, 0.3),
        (2, -1.0, 0.0, 0.1, 0.7),
        (0, 1.0, 0.0, 0.5, 1.0),
    ]
    .into_iter()
    .enumerate()
    {
        let m = min_by_roots(&fit.curve, r, sigma, v, a, b);
        assert!(m >= -1e-12, "constraint {s}: {m:e}");
    }
    assert!(shape_violations(&fit.curve, &c)
        .unwrap()
        .iter()
        .all(|v| *v <= 1e-12));
}

#[test]
fn the_smoothing_condition_is_met_under_constraints() {
    // 40 points: the spline has a knot at each, and y'' by the independent Taylor check
    // carries rounding of about ε·|c|/h² (1e-13 here, 1e-11 at 120 points)
    let (x, y) = noisy(40, |t| t * t);
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let c = ShapeConstraints::new()
        .with(Shape::Increasing)
        .with(Shape::Convex);
    // the residual of the constrained spline grows with λ, so every s between its ends is met
    let r0 = constrained_smoothing_spline(&data, Lambda::Gcv, &c)
        .unwrap()
        .report
        .weighted_rss;
    for s in [1.2 * r0, 2.0 * r0, 4.0 * r0] {
        let fit = constrained_smoothing_condition(&data, s, &c).unwrap();
        assert!(
            (fit.report.weighted_rss - s).abs() <= CONDITION_RTOL * s,
            "s = {s}: residual {}",
            fit.report.weighted_rss
        );
        assert!(
            min_by_roots(&fit.curve, 1, 1.0, 0.0, 0.0, 1.0) >= -1e-12,
            "s = {s}: y' < 0"
        );
        let m2 = min_by_roots(&fit.curve, 2, 1.0, 0.0, 0.0, 1.0);
        assert!(
            m2 >= -1e-12,
            "s = {s}: min y'' = {m2:e}, {:?}, λ {:?}",
            shape_violations(&fit.curve, &c),
            fit.report.lambda
        );
        // it is the constrained smoothing spline of the λ it reports
        let again =
            constrained_smoothing_spline(&data, Lambda::Given(fit.report.lambda.unwrap()), &c)
                .unwrap();
        assert_eq!(again.curve, fit.curve, "s = {s}");
    }
    // below what the constraints allow: refused, naming s
    let e = constrained_smoothing_condition(&data, 1e-9, &c).unwrap_err();
    assert!(e.to_string().contains("give s ≥"), "{e}");
    // numbers as a user writes them: no Rust exponent form (`5.35e1`, `1e0`) for plain
    // values, and the bound suggested in four digits, rounded up so that it is enough
    let text = e.to_string();
    let bound: f64 = text
        .split("give s ≥ ")
        .nth(1)
        .and_then(|t| t.split(',').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("a bound to type back: {text}"));
    assert!(text.contains("above s = 1e-9;"), "{text}");
    assert!(
        format!("{bound:e}").len() <= "1.234e-5".len(),
        "four digits: {text}"
    );
    let fit = constrained_smoothing_condition(&data, bound, &c).unwrap();
    assert!(
        fit.report.weighted_rss <= bound * (1.0 + CONDITION_RTOL),
        "{text}"
    );
    // above what a straight line leaves: the straightest fit
    let fit = constrained_smoothing_condition(&data, 1e3, &c).unwrap();
    assert!(fit.report.weighted_rss < 1e3);
    assert!(matches!(
        constrained_smoothing_condition(&data, -1.0, &c),
        Err(crate::Error::NegativeSmoothing { .. })
    ));
}

#[test]
fn contradictory_constraints_are_named() {
    let (x, y) = noisy(30, |t| t);
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 6).unwrap();
    let c = ShapeConstraints::new()
        .with(Shape::Convex)
        .with(Shape::AtMost(0.0))
        .with_point(0.5, 0, 1.0);
    let e = constrained_least_squares(&data, 3, &kv, &c).unwrap_err();
    let crate::Error::InfeasibleConstraints { conflicting } = &e else {
        panic!("expected InfeasibleConstraints, got {e:?}");
    };
    assert!(
        conflicting.iter().any(|s| s == "max 0") && conflicting.iter().any(|s| s == "y(0.5) = 1"),
        "{conflicting:?}"
    );
}

#[test]
fn bad_constraints_are_refused() {
    let (x, y) = noisy(30, |t| t);
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 6).unwrap();
    for c in [
        ShapeConstraints::new().with_on(Shape::Increasing, 0.5, 0.2),
        ShapeConstraints::new().with_on(Shape::Increasing, -1.0, 0.2),
        ShapeConstraints::new().with_point(2.0, 0, 0.0),
        ShapeConstraints::new().with_point(0.5, 4, 0.0),
    ] {
        let e = constrained_least_squares(&data, 3, &kv, &c).unwrap_err();
        assert!(
            matches!(
                e,
                crate::Error::InvalidArgument { what, .. } if what.words() == "shape constraints"
            ),
            "{e:?}"
        );
    }
    let nan = ShapeConstraints::new().with(Shape::AtLeast(f64::NAN));
    let e = constrained_least_squares(&data, 3, &kv, &nan).unwrap_err();
    assert!(matches!(e, crate::Error::NonFinite { .. }), "{e:?}");
    let two = [0.0, 1.0, 1.0, 2.0];
    let d2 = FitData::new(PointsRef::from_flat(2, &two).unwrap(), &[0.0, 1.0]).unwrap();
    let e = constrained_least_squares(&d2, 1, &KnotVector::clamped_uniform(1, 2).unwrap(), &nan)
        .unwrap_err();
    assert!(matches!(e, crate::Error::Dimension { .. }), "{e:?}");
    let e = constrained_smoothing_spline(&data, Lambda::Given(0.0), &nan).unwrap_err();
    assert!(matches!(e, crate::Error::NegativeSmoothing { .. }), "{e:?}");
}

/// The working set (pieces grown from the unconstrained fit's violations) returns the optimum of
/// the whole cone program: the same coefficients to rounding, on data whose constraints are
/// active on a few spans only (a dip in a rising convex curve, a bound crossed near one end).
#[test]
fn the_working_set_gives_the_whole_program_s_answer() {
    let (x, y) = noisy(2000, |t| {
        t * t + 0.3 * t + 0.08 * (-((t - 0.6) / 0.05).powi(2)).exp() * (40.0 * t).sin()
    });
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 40).unwrap();
    for c in [
        ShapeConstraints::new().with(Shape::Increasing),
        ShapeConstraints::new()
            .with(Shape::Increasing)
            .with(Shape::Convex)
            .with(Shape::AtLeast(0.0)),
        ShapeConstraints::new()
            .with_on(Shape::Concave, 0.5, 0.7)
            .with(Shape::AtMost(1.2))
            .with_point(0.0, 0, 0.0),
    ] {
        let ws =
            fits::constrained_least_squares_by(&data, 3, &kv, &c, working_set::Rows::WorkingSet)
                .unwrap();
        let all =
            fits::constrained_least_squares_by(&data, 3, &kv, &c, working_set::Rows::All).unwrap();
        let free = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
        assert!(
            ws.report.weighted_rss > free.report.weighted_rss,
            "{c:?}: constraints inactive"
        );
        let (a, b) = (
            ws.curve.control_points().as_slice(),
            all.curve.control_points().as_slice(),
        );
        let size = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let worst = a
            .iter()
            .zip(b)
            .map(|(u, v)| (u - v).abs())
            .fold(0.0, f64::max);
        // a bound on a cubic that the optimum touches inside a span puts the face at a point
        // τ* found by secant steps on a multiplier that is flat there: the two programs'
        // polished answers agree to a few units of 1e-12, not to the last digits
        assert!(
            worst <= 5e-12 * size,
            "{c:?}: coefficients differ by {worst:e} (size {size})"
        );
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]
    /// Whatever the data, the working-set answer keeps every constraint exactly (the check of
    /// `shape_violations`, by the exact minimum on each piece).
    #[test]
    fn the_working_set_answer_keeps_every_constraint(
        m in 60usize..400,
        spans in 4usize..30,
        wiggle in 0.0f64..0.5,
        freq in 2.0f64..30.0,
        which in 0usize..4,
    ) {
        let (x, y) = noisy(m, |t| t * t + wiggle * (freq * t).sin());
        let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
        let kv = KnotVector::clamped_uniform(3, spans).unwrap();
        let c = match which {
            0 => ShapeConstraints::new().with(Shape::Increasing),
            1 => ShapeConstraints::new().with(Shape::Convex).with(Shape::AtLeast(0.0)),
            2 => ShapeConstraints::new()
                .with(Shape::Increasing)
                .with(Shape::Convex)
                .with(Shape::AtLeast(0.0)),
            _ => ShapeConstraints::new()
                .with_on(Shape::Decreasing, 0.0, 0.4)
                .with(Shape::AtMost(1.0)),
        };
        let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
        let scale = y.iter().map(|v| (v - y[0]).abs()).fold(0.0, f64::max);
        let v = shape_violations(&fit.curve, &c).unwrap();
        // the domain is [0, 1]: the scale of y⁽ʳ⁾ is that of y
        for (s, v) in c.shapes.iter().zip(&v) {
            proptest::prop_assert!(*v <= SHAPE_RTOL * scale, "{s}: violated by {v:e}");
        }
    }
}

/// The constrained smoothing spline with a hook: the same bits as without, monotone reports
/// ending at their total, and a set cancel flag stops it with `Cancelled` (the server's deadline
/// relies on it: the cone program of thousands of points otherwise ran for minutes).
#[test]
fn constrained_smoothing_with_a_hook_is_unchanged_and_stops_when_cancelled() {
    use crate::fit::progress::tests::{check_hook, same_bits};
    // a rising wave with dips, kept increasing: the constraint is active on several spans
    let (x, y) = noisy(200, |t| t + 0.2 * (25.0 * t).sin());
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let c = ShapeConstraints::new().with(Shape::Increasing);
    for lambda in [Lambda::Gcv, Lambda::Given(1e-6)] {
        check_hook(
            "constrained smoothing spline",
            |p| constrained_smoothing_spline_with_progress(&data, lambda, &c, p),
            |a, b| {
                same_bits(
                    a.curve.control_points().as_slice(),
                    b.curve.control_points().as_slice(),
                ) && same_bits(&a.report.residuals, &b.report.residuals)
            },
        );
    }
}

/// A cubic kept above 0 where the data's parabola dips below it inside the one knot span: the
/// exact condition (two cones per cubic, Markov–Lukács) reaches the optimum, which its
/// relaxation to samples (`y(x_j) ≥ 0` at 40,001 points, a larger feasible set, solved as a
/// linear-inequality program) bounds from below; the signs of the Bernstein coefficients
/// (sufficient only) cannot reach it, as the fit's own coefficients, negative, show.
#[test]
fn a_bound_on_a_cubic_is_exact_not_stricter() {
    use super::program::ConeProgram;
    use super::row::Row;
    use crate::fit::banded::SymBand;
    let x: Vec<f64> = (0..101).map(|k| f64::from(k) / 100.0).collect();
    let y: Vec<f64> = x
        .iter()
        .map(|t| 4.0 * (t - 0.4) * (t - 0.4) - 0.05 + 0.3 * t * t * t)
        .collect();
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    // one span: the control points are the cubic's Bernstein coefficients
    let kv = KnotVector::clamped_uniform(3, 4).unwrap();
    let c = ShapeConstraints::new().with(Shape::AtLeast(0.0));
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    let m = min_by_roots(&fit.curve, 0, 1.0, 0.0, 0.0, 1.0);
    assert!(m >= -1e-12, "min y = {m}");
    let ctrl = fit.curve.control_points().as_slice();
    assert!(
        ctrl.iter().any(|v| *v < -0.01),
        "the fit's Bernstein coefficients {ctrl:?} are all ≥ 0: the stricter condition"
    );
    // the relaxation: ½cᵀ(BᵀB)c − (Bᵀy)ᵀc with y(x_j) ≥ 0 at samples
    let mut p = SymBand::zeros(4, 3);
    let mut q = vec![0.0; 4];
    for (&xk, &yk) in x.iter().zip(&y) {
        let (b, _) = super::bernstein::bernstein_weights(3, xk);
        for i in 0..4 {
            q[i] -= b[i] * yk;
            for j in i..4 {
                p.add(i, j, b[i] * b[j]);
            }
        }
    }
    let mut relaxed = ConeProgram::new(p, q);
    for k in 0..=40_000 {
        let (b, _) = super::bernstein::bernstein_weights(3, f64::from(k) / 40_000.0);
        let row = Row {
            first: 0,
            coef: b,
            aux: None,
            constant: 0.0,
        };
        relaxed.inequalities.push((row, 0));
    }
    let cr = relaxed.solve(0.0).unwrap();
    let yy: f64 = y.iter().map(|v| v * v).sum();
    let rss_relaxed = 2.0 * relaxed.objective(&cr) + yy;
    let rss = fit.report.weighted_rss;
    assert!(
        rss >= rss_relaxed * (1.0 - 1e-9) && rss <= rss_relaxed * (1.0 + 1e-6),
        "residual {rss} against the sampled relaxation's {rss_relaxed}"
    );
}

/// Bounds at given points (an interval `[x, x]`): a value bound the data cross is met with
/// equality, so the fit is the one with that value prescribed (a point equality), and a slope
/// bound at another point holds; both reported as kept.
#[test]
fn bounds_at_points_hold_and_bind_as_equalities() {
    let (x, y) = noisy(120, |t| t + 0.2 * (5.0 * t).sin());
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 10).unwrap();
    let free = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
    let at = |c: &BSplineCurve, x: f64, r: usize| c.eval_derivatives(x, r).unwrap().point(r)[0];
    let cap = at(&free.curve, 0.5, 0) - 0.3;
    let c = ShapeConstraints::new()
        .with_on(Shape::AtMost(cap), 0.5, 0.5)
        .with_on(Shape::AtLeast(-50.0), 0.9, 0.9);
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    assert_eq!(c.describe(0), format!("max {cap} at 0.5"));
    let v = shape_violations(&fit.curve, &c).unwrap();
    assert!(v.iter().all(|v| *v <= 1e-12), "{v:?}");
    let pinned = ShapeConstraints::new().with_point(0.5, 0, cap);
    let eq = constrained_least_squares(&data, 3, &kv, &pinned).unwrap();
    for k in 0..=50 {
        let t = f64::from(k) / 50.0;
        let (a, b) = (at(&fit.curve, t, 0), at(&eq.curve, t, 0));
        assert!((a - b).abs() <= 1e-10, "at {t}: {a} vs {b}");
    }
    // a sign of the slope at a point where the free fit falls: the slope there becomes 0
    let (x, y) = noisy(120, |t| (std::f64::consts::TAU * t).sin());
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let free = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
    assert!(at(&free.curve, 0.5, 1) < -1.0, "the free fit rises at 0.5");
    let c = ShapeConstraints::new().with_on(Shape::Increasing, 0.5, 0.5);
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    let slope = at(&fit.curve, 0.5, 1);
    assert!(slope.abs() <= 1e-12, "y'(0.5) = {slope}");
    assert!(
        fit.report.weighted_rss > free.report.weighted_rss,
        "the slope's sign did not bind"
    );
}

/// An integral prescribed: the fit's integral (by the curve's antiderivative, not the program's
/// rows) takes the value; prescribing the free fit's own integral leaves the free fit; and it
/// combines with a shape.
#[test]
fn integrals_hold_and_leave_a_consistent_fit_alone() {
    let (x, y) = noisy(150, |t| 0.3 + t * t);
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 9).unwrap();
    let free = least_squares(&data, 3, &kv, &EndConstraints::none()).unwrap();
    let own = free.curve.integral(0.2, 0.7).unwrap()[0];
    let same = ShapeConstraints::new().with_integral(0.2, 0.7, own);
    let fit = constrained_least_squares(&data, 3, &kv, &same).unwrap();
    for k in 0..=40 {
        let t = f64::from(k) / 40.0;
        let (a, b) = (
            fit.curve.eval(t).unwrap()[0],
            free.curve.eval(t).unwrap()[0],
        );
        assert!((a - b).abs() <= 1e-10, "at {t}: {a} vs {b}");
    }
    let c = ShapeConstraints::new()
        .with_integral(0.0, 1.0, 1.0)
        .with(Shape::Increasing);
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    let got = fit.curve.integral(0.0, 1.0).unwrap()[0];
    assert!((got - 1.0).abs() <= 1e-12, "integral {got}");
    let m = min_by_roots(&fit.curve, 1, 1.0, 0.0, 0.0, 1.0);
    assert!(m >= -1e-12, "min y' = {m}");
    assert!(
        fit.report.weighted_rss > free.report.weighted_rss,
        "the integral did not bind"
    );
    let v = shape_violations(&fit.curve, &c).unwrap();
    assert!(v.iter().all(|v| *v <= 1e-12), "{v:?}");
    let bad = ShapeConstraints::new().with_integral(0.5, 2.0, 1.0);
    assert!(
        constrained_least_squares(&data, 3, &kv, &bad).is_err(),
        "an integral leaving the domain is refused"
    );
}

/// Periodicity on clamped knots: the clamped cubics whose value, slope and curvature agree at
/// the ends are the periodic cubic splines with the same breakpoints, so the fit is the
/// periodic least squares (`periodic_least_squares`, a cyclic banded QR) to rounding; with a
/// bound it still closes.
#[test]
fn periodicity_gives_the_periodic_least_squares() {
    let n = 120;
    let x: Vec<f64> = (0..n).map(|k| f64::from(k) / f64::from(n)).collect();
    let y: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            (std::f64::consts::TAU * t).sin()
                + 0.4 * t
                + 0.05 * (((k * 7919) % 101) as f64 / 50.0 - 1.0)
        })
        .collect();
    let data = FitData::new(PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let kv = KnotVector::clamped_uniform(3, 13).unwrap();
    let c = ShapeConstraints::new().with_periodicity();
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    let breaks: Vec<f64> = (0..=10).map(|j| f64::from(j) / 10.0).collect();
    let periodic = crate::fit::periodic_least_squares(&data, 3, &breaks).unwrap();
    for k in 0..=100 {
        let t = f64::from(k) / 100.0;
        let (a, b) = (
            fit.curve.eval(t).unwrap()[0],
            periodic.curve.eval(t).unwrap()[0],
        );
        assert!((a - b).abs() <= 1e-9, "at {t}: {a} vs {b}");
    }
    let c = c.with(Shape::AtMost(0.9));
    let fit = constrained_least_squares(&data, 3, &kv, &c).unwrap();
    let v = shape_violations(&fit.curve, &c).unwrap();
    assert!(v.iter().all(|v| *v <= 1e-12), "{v:?}");
    let (d0, d1) = (
        fit.curve.eval_derivatives(0.0, 2).unwrap(),
        fit.curve.eval_derivatives(1.0, 2).unwrap(),
    );
    for r in 0..3 {
        let (a, b) = (d0.point(r)[0], d1.point(r)[0]);
        assert!(
            (a - b).abs() <= 1e-9 * (1.0 + a.abs()),
            "y^({r}): {a} vs {b}"
        );
    }
}
