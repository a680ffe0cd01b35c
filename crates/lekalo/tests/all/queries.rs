//! Geometric queries against Open CASCADE's answers (`tests/data/queries_occt.json`, made by
//! `tests/data/queries_occt.py`) and their invariants as property tests.

use lekalo::query::CurveIntersection;
use lekalo::{BSplineCurve, NurbsCurve, Points, QueryCurve};
use proptest::prelude::*;
use serde_json::Value;

fn golden() -> Value {
    let text = include_str!("../data/queries_occt.json");
    serde_json::from_str(text).expect("golden file parses")
}

fn curve(v: &Value) -> QueryCurve {
    let degree = usize::try_from(v["degree"].as_u64().expect("degree")).expect("small degree");
    let knots: Vec<f64> = v["knots"]
        .as_array()
        .expect("knots")
        .iter()
        .map(|x| x.as_f64().expect("knot"))
        .collect();
    let rows: Vec<Vec<f64>> = v["control"]
        .as_array()
        .expect("control")
        .iter()
        .map(|p| {
            p.as_array()
                .expect("point")
                .iter()
                .map(|x| x.as_f64().expect("coordinate"))
                .collect()
        })
        .collect();
    let ctrl = Points::from_rows(&rows).expect("points");
    match v.get("weights") {
        Some(w) => {
            let w: Vec<f64> = w
                .as_array()
                .expect("weights")
                .iter()
                .map(|x| x.as_f64().expect("weight"))
                .collect();
            QueryCurve::from_nurbs(&NurbsCurve::new(degree, knots, ctrl, w).expect("nurbs"))
                .expect("query curve")
        }
        None => QueryCurve::from_bspline(&BSplineCurve::new(degree, knots, ctrl).expect("bspline"))
            .expect("query curve"),
    }
}

fn f(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

#[test]
fn lengths_match_open_cascade() {
    let g = golden();
    for l in g["lengths"].as_array().expect("lengths") {
        let name = l["curve"].as_str().expect("name");
        let c = curve(&g["curves"][name]);
        let table = c.arc_length(1e-14).expect("table");
        let ours = table.total();
        let theirs = f(&l["length"]);
        assert!(
            (ours - theirs).abs() <= 1e-12 * theirs,
            "{name}: length {ours} vs OCCT {theirs}"
        );
        for p in l["parts"].as_array().expect("parts") {
            let (a, b) = (f(&p["from"]), f(&p["to"]));
            let ours = table.length_at(b).expect("b") - table.length_at(a).expect("a");
            let theirs = f(&p["length"]);
            assert!(
                (ours - theirs).abs() <= 1e-12 * theirs,
                "{name} [{a}, {b}]: {ours} vs {theirs}"
            );
        }
        for p in l["inverse"].as_array().expect("inverse") {
            let t = table.param_at(f(&p["length"])).expect("param");
            let theirs = f(&p["t"]);
            assert!(
                (t - theirs).abs() <= 1e-10,
                "{name}: t {t} vs OCCT {theirs}"
            );
        }
    }
}

#[test]
fn projections_match_open_cascade() {
    let g = golden();
    for p in g["projections"].as_array().expect("projections") {
        let name = p["curve"].as_str().expect("name");
        let c = curve(&g["curves"][name]);
        let q: Vec<f64> = p["query"]
            .as_array()
            .expect("query")
            .iter()
            .map(f)
            .collect();
        let ours = c.project(&q).expect("projection");
        // OCCT reports interior extrema only: the ends are our candidates too
        let (lo, hi) = c.domain();
        let ends = [lo, hi].map(|t| {
            let e = c.point(t).expect("end");
            e.iter()
                .zip(&q)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
        });
        let theirs = p["closest"]
            .as_object()
            .map_or(f64::INFINITY, |o| f(&o["distance"]))
            .min(ends[0])
            .min(ends[1]);
        assert!(
            (ours.distance - theirs).abs() <= 1e-12 * (1.0 + theirs),
            "{name} {q:?}: distance {} vs OCCT {theirs}",
            ours.distance
        );
        // every OCCT minimum at the least distance is one of ours
        let all = c.project_all(&q, 1e-9).expect("all minima");
        for e in p["extrema"].as_array().expect("extrema") {
            if (f(&e["distance"]) - theirs).abs() <= 1e-10 {
                let t = f(&e["t"]);
                assert!(
                    all.iter().any(|a| (a.t - t).abs() <= 1e-8),
                    "{name} {q:?}: OCCT minimum at {t} missing from {all:?}"
                );
            }
        }
    }
}

#[test]
fn intersections_match_open_cascade() {
    let g = golden();
    for i in g["intersections"].as_array().expect("intersections") {
        let a = curve(&g["curves"][i["a"].as_str().expect("a")]);
        let b = curve(&g["curves"][i["b"].as_str().expect("b")]);
        let ours = a.intersect(&b, 1e-10).expect("intersection");
        let theirs = i["points"].as_array().expect("points");
        assert_eq!(ours.len(), theirs.len(), "{ours:?}");
        for (o, t) in ours.iter().zip(theirs) {
            let CurveIntersection::Point {
                t_a, t_b, point, ..
            } = o
            else {
                panic!("overlap where OCCT sees a point")
            };
            assert!(
                (t_a - f(&t["t_a"])).abs() <= 1e-9,
                "t_a {t_a} vs {}",
                t["t_a"]
            );
            assert!(
                (t_b - f(&t["t_b"])).abs() <= 1e-9,
                "t_b {t_b} vs {}",
                t["t_b"]
            );
            for d in 0..2 {
                assert!(
                    (point[d] - f(&t["point"][d])).abs() <= 1e-9,
                    "{point:?} vs {t}"
                );
            }
        }
    }
}

fn cubic(ctrl: &[[f64; 2]]) -> QueryCurve {
    let n = ctrl.len();
    let mut knots = vec![0.0; 4];
    for i in 1..n - 3 {
        knots.push(i as f64 / (n - 3) as f64);
    }
    knots.extend([1.0; 4]);
    QueryCurve::from_bspline(
        &BSplineCurve::new(3, knots, Points::from_2d(ctrl).expect("pts")).expect("curve"),
    )
    .expect("query")
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

proptest! {
    #![proptest_config(lekalo_testkit::config(64))]

    #[test]
    fn projection_is_orthogonal_and_no_sample_is_closer(
        ctrl in prop::collection::vec(prop::array::uniform2(-10.0..10.0_f64), 4..9),
        q in prop::array::uniform2(-15.0..15.0_f64),
    ) {
        let c = cubic(&ctrl);
        let p = c.project(&q).expect("projection");
        let (lo, hi) = c.domain();
        for i in 0..=400 {
            let s = c.point(lo + (hi - lo) * f64::from(i) / 400.0).expect("sample");
            prop_assert!(distance(&s, &q) >= p.distance - 1e-12 * (1.0 + p.distance),
                "sample {i} closer: {} < {}", distance(&s, &q), p.distance);
        }
        if p.t > lo && p.t < hi && p.distance > 1e-9 {
            // the tangent by a central difference of the exact curve (no curvature at a cusp)
            let h = 1e-6 * (hi - lo);
            let (a, b) = (c.point((p.t - h).max(lo)).expect("a"), c.point((p.t + h).min(hi)).expect("b"));
            let tan = [b[0] - a[0], b[1] - a[1]];
            let tl = tan[0].hypot(tan[1]);
            if tl > 1e-9 * h {
                let r = [q[0] - p.point[0], q[1] - p.point[1]];
                let cos = (r[0] * tan[0] + r[1] * tan[1]) / (tl * p.distance);
                prop_assert!(cos.abs() < 1e-5, "cos {cos} at t {}", p.t);
            }
        }
    }

    #[test]
    fn intersections_lie_on_both(
        a in prop::collection::vec(prop::array::uniform2(-10.0..10.0_f64), 4..8),
        b in prop::collection::vec(prop::array::uniform2(-10.0..10.0_f64), 4..8),
    ) {
        let (ca, cb) = (cubic(&a), cubic(&b));
        for h in ca.intersect(&cb, 1e-9).expect("intersection") {
            if let CurveIntersection::Point { t_a, t_b, point, .. } = h {
                prop_assert!(distance(&ca.point(t_a).expect("a"), &point) <= 1e-9, "on a");
                prop_assert!(distance(&cb.point(t_b).expect("b"), &point) <= 1e-8, "on b");
            }
        }
    }

    #[test]
    fn length_inverse_round_trips(
        ctrl in prop::collection::vec(prop::array::uniform2(-10.0..10.0_f64), 4..9),
        frac in 0.0..1.0_f64,
    ) {
        let c = cubic(&ctrl);
        let table = c.arc_length(1e-13).expect("table");
        let s = frac * table.total();
        let t = table.param_at(s).expect("param");
        let back = table.length_at(t).expect("length");
        prop_assert!((back - s).abs() <= 1e-11 * (1.0 + table.total()), "{back} vs {s}");
    }
}
