//! The fitting and query routes checked against the library: `/api/fit` (smoothing spline with
//! λ given or by GCV, smoothing condition s), `/api/project`, `/api/measure`, `/api/intersect`,
//! and the τ rules and explicit τ values of `/api/quasi`.

#![allow(clippy::missing_assert_message)] // assert_eq! prints both sides

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use lekalo::fit::{
    smoothing_condition, smoothing_condition_with_rounds, smoothing_spline, CurveFit, FitData,
    KnotRounds, Lambda,
};
use lekalo::{
    parametrize, quasi_interpolate, BSplineCurve, Expression, Parametrization, Points, PpSpace,
    QueryCurve, Tau, TauRule,
};
use lekalo_io::CurveJson;
use lekalo_io::Object;
use lekalo_serve::{router, Limits};
use serde_json::{json, Value};
use tower::ServiceExt;

async fn call(route: &str, body: &Value) -> (StatusCode, Value) {
    let req = Request::post(route)
        .body(Body::from(body.to_string()))
        .expect("request");
    let resp = router(Limits::default())
        .oneshot(req)
        .await
        .expect("infallible");
    let status = resp.status();
    let bytes = resp.into_body().collect().await.expect("body").to_bytes();
    (status, serde_json::from_slice(&bytes).expect("JSON answer"))
}

async fn ok(route: &str, body: &Value) -> Value {
    let (s, v) = call(route, body).await;
    assert_eq!(s, StatusCode::OK, "{route}: {v}");
    v
}

/// The field and message of a 400 answer.
async fn bad(route: &str, body: &Value) -> (String, String) {
    let (s, v) = call(route, body).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{route}: {v}");
    (
        v["field"].as_str().expect("field").to_string(),
        v["error"].as_str().expect("message").to_string(),
    )
}

/// 40 points of a wave with a fixed, irregular disturbance.
fn noisy() -> Vec<[f64; 2]> {
    (0..40)
        .map(|i| {
            let x = 0.6 + f64::from(i) * 0.22;
            let noise = f64::from((i * 7919) % 13) / 13.0 - 0.5;
            [x, 3.0 + 1.8 * (0.9 * x).sin() + 0.6 * noise]
        })
        .collect()
}

fn library_fit(pts: &[[f64; 2]], f: impl Fn(&FitData<'_>) -> lekalo::Result<CurveFit>) -> CurveFit {
    let p = Points::from_2d(pts).expect("points");
    let u = parametrize(p.as_view(), Parametrization::ChordLength).expect("parameters");
    let data = FitData::new(p.as_view(), &u).expect("data");
    f(&data).expect("fit")
}

fn check_report(v: &Value, fit: &CurveFit) {
    let r = &v["report"];
    assert_eq!(
        v["view"]["curve"],
        Object::BSpline(fit.curve.clone()).to_json_value(),
        "the library's curve"
    );
    assert_eq!(r["rms"].as_f64(), Some(fit.report.rms), "RMS");
    assert_eq!(
        r["max_residual"].as_f64(),
        Some(fit.report.max_residual),
        "max residual"
    );
    assert_eq!(
        r["weighted_rss"].as_f64(),
        Some(fit.report.weighted_rss),
        "weighted RSS"
    );
    assert_eq!(
        r["control_points"].as_u64(),
        Some(fit.report.n_ctrl as u64),
        "control points"
    );
    assert_eq!(
        r["knots"].as_u64(),
        Some(fit.curve.knots().len() as u64),
        "knots"
    );
}

#[tokio::test]
async fn fitting_answers_the_library_s_curve_and_report() {
    let pts = noisy();
    for lambda in [0.0, 1e-4, 0.1] {
        let v = ok(
            "/api/fit",
            &json!({"points": pts, "smoothing": "lambda", "lambda": lambda, "samples": 5}),
        )
        .await;
        let fit = library_fit(&pts, |d| smoothing_spline(d, Lambda::Given(lambda)));
        check_report(&v, &fit);
        assert_eq!(v["report"]["lambda"].as_f64(), Some(lambda));
    }
    let v = ok("/api/fit", &json!({"points": pts, "smoothing": "gcv"})).await;
    let fit = library_fit(&pts, |d| smoothing_spline(d, Lambda::Gcv));
    check_report(&v, &fit);
    assert!(v["report"]["lambda"].as_f64().expect("λ") > 0.0);

    let v = ok(
        "/api/fit",
        &json!({"points": pts, "smoothing": "s", "s": 1.0, "degree": 3}),
    )
    .await;
    let fit = library_fit(&pts, |d| smoothing_condition(d, 3, 1.0));
    check_report(&v, &fit);
    let (a, b) = fit.curve.domain();
    let interior = fit
        .curve
        .knots()
        .distinct()
        .iter()
        .filter(|&&(k, _)| k > a && k < b)
        .count();
    assert_eq!(
        v["report"]["interior_knots"].as_u64(),
        Some(interior as u64)
    );
    assert!(v["report"]["weighted_rss"].as_f64().expect("rss") <= 1.0);
    assert_eq!(v["report"]["s"].as_f64(), Some(1.0));
    // the refitted rounds of SciPy's make_splrep, as the library places them (other knots than
    // the shared rounds' on these data)
    for s in [0.01, 0.1] {
        let v = ok(
            "/api/fit",
            &json!({"points": pts, "smoothing": "s", "s": s, "knot_rounds": "refit"}),
        )
        .await;
        let quiet = lekalo::Progress::new();
        let fit = library_fit(&pts, |d| {
            smoothing_condition_with_rounds(d, 3, s, None, KnotRounds::Refit, &quiet)
        });
        check_report(&v, &fit);
        let shared = library_fit(&pts, |d| smoothing_condition(d, 3, s));
        assert_ne!(shared.curve.knots(), fit.curve.knots(), "s = {s}");
    }

    // samples y(x) of a function: x is the parameter, the fit is one-dimensional and the view
    // draws its graph (x, y(x))
    let v = ok(
        "/api/fit",
        &json!({"points": pts, "function": true, "lambda": 1e-3, "samples": 3}),
    )
    .await;
    let x: Vec<f64> = pts.iter().map(|p| p[0]).collect();
    let y = Points::from_flat(1, pts.iter().map(|p| p[1]).collect()).expect("y");
    let data = FitData::new(y.as_view(), &x).expect("data");
    let mut fit = smoothing_spline(&data, Lambda::Given(1e-3)).expect("fit");
    fit.curve = fit.curve.graph().expect("graph");
    check_report(&v, &fit);
}

#[tokio::test]
async fn fitting_errors_name_the_field() {
    let pts = noisy();
    for (body, field, needle) in [
        (json!({"points": pts, "lambda": -1}), "lambda", "≥ 0"),
        (
            json!({"points": pts, "smoothing": "s", "s": -2}),
            "s",
            "≥ 0",
        ),
        (json!({"points": pts}), "lambda", "needs the value lambda"),
        (
            json!({"points": pts, "smoothing": "s"}),
            "s",
            "needs the value s",
        ),
        (
            json!({"points": pts[..2], "lambda": 1}),
            "points",
            "at least 3",
        ),
        (
            json!({"points": pts, "smoothing": "s", "s": 1, "degree": 0}),
            "degree",
            "degree",
        ),
        (
            json!({"points": pts, "smoothing": "s", "s": 1, "degree": 500}),
            "degree",
            "limit",
        ),
        (
            json!({"points": pts, "smoothing": "s", "s": 1, "knot_rounds": "fresh"}),
            "knot_rounds",
            "unknown value \"fresh\"; use one of shared, refit",
        ),
        (
            json!({"points": pts, "smoothing": "lamda"}),
            "smoothing",
            "unknown value \"lamda\"; use one of lambda, gcv, s",
        ),
        (
            json!({"points": pts, "smoothing": 1}),
            "smoothing",
            "expected one of lambda, gcv, s",
        ),
        (
            json!({"points": [[0, 0], [0, 0], [1, 1], [2, 0]], "lambda": 1}),
            "points",
            "",
        ),
    ] {
        let (f, msg) = bad("/api/fit", &body).await;
        assert_eq!(f, field, "{body}: {msg}");
        assert!(msg.contains(needle), "{body}: {msg}");
    }
}

const CURVE: &str = r#"{"lekalo": 1, "type": "nurbs_curve", "degree": 2,
  "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[0, 0], [1, 2], [3, 2], [4, 0]],
  "weights": [1, 2, 0.5, 1]}"#;

fn query_curve() -> (Value, QueryCurve, Object) {
    let v: Value = serde_json::from_str(CURVE).expect("json");
    let obj = Object::from_json_str(CURVE, "curve").expect("curve");
    let Object::Nurbs(n) = &obj else {
        panic!("a NURBS curve")
    };
    (v, QueryCurve::from_nurbs(n).expect("query curve"), obj)
}

#[tokio::test]
async fn projection_and_arc_length_are_the_library_s() {
    let (curve, q, obj) = query_curve();
    for p in [[2.0, 3.0], [-1.0, 0.5], [4.0, -1.0], [1.5, 1.0]] {
        let v = ok("/api/project", &json!({"curve": curve, "point": p})).await;
        let lib = q.project(&p).expect("projection");
        assert_eq!(v["t"].as_f64(), Some(lib.t), "{p:?}");
        assert_eq!(v["distance"].as_f64(), Some(lib.distance), "{p:?}");
        assert_eq!(v["point"], json!(lib.point), "{p:?}");
    }
    let v = ok(
        "/api/measure",
        &json!({"curve": curve, "at_length": [0, 1, 2.5]}),
    )
    .await;
    let table = q.arc_length(1e-12).expect("arc length");
    assert_eq!(v["length"].as_f64(), Some(table.total()));
    assert_eq!(v["error_estimate"].as_f64(), Some(table.error_estimate()));
    assert_eq!(v["domain"], json!([0.0, 2.0]));
    for (i, l) in [0.0, 1.0, 2.5].into_iter().enumerate() {
        let t = table.param_at(l).expect("parameter");
        assert_eq!(v["at_length"][i]["t"].as_f64(), Some(t), "length {l}");
        assert_eq!(
            v["at_length"][i]["point"],
            json!(obj.eval(t).expect("point")),
            "length {l}"
        );
    }
    // a Bezier curve and a plain B-spline too
    let bez = json!({"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1], [2, 0]]});
    let v = ok("/api/measure", &json!({"curve": bez})).await;
    let c = lekalo::BezierCurve::new(
        Points::from_2d(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]).expect("p"),
    )
    .expect("bezier");
    let lib = QueryCurve::from_bezier(&c)
        .expect("query")
        .arc_length(1e-12)
        .expect("length")
        .total();
    assert_eq!(v["length"].as_f64(), Some(lib));
}

/// A Bezier curve of the given 2-D control points, as the API's object and as the library's
/// query curve.
fn bezier(control: &[[f64; 2]]) -> (Value, QueryCurve) {
    let v = json!({"lekalo": 1, "type": "bezier_curve", "control": control});
    let c = lekalo::BezierCurve::new(Points::from_2d(control).expect("points")).expect("bezier");
    (v, QueryCurve::from_bezier(&c).expect("query curve"))
}

#[tokio::test]
async fn intersections_and_their_kinds_are_the_library_s() {
    use lekalo::query::{Contact, CurveIntersection};
    // a cubic with a loop: one crossing of itself
    let (looped, q) = bezier(&[[0.0, 0.0], [4.0, 2.0], [-1.0, 2.0], [3.0, 0.0]]);
    let v = ok("/api/intersect", &json!({"curve": looped})).await;
    let lib = q.self_intersections(1e-9).expect("self-intersections");
    assert_eq!(lib.len(), 1, "{lib:?}");
    let CurveIntersection::Point {
        t_a,
        t_b,
        point,
        contact,
    } = &lib[0]
    else {
        panic!("{lib:?}")
    };
    assert_eq!(*contact, Contact::Crossing);
    assert_eq!(
        v["intersections"],
        json!([{"kind": "crossing", "t_a": t_a, "t_b": t_b, "point": point}])
    );
    // a parabola touching the line y = 1 at its top: a tangent contact of order 1
    let (arch, qa) = bezier(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]);
    let (line, ql) = bezier(&[[0.0, 1.0], [2.0, 1.0]]);
    let v = ok("/api/intersect", &json!({"curve": arch, "other": line})).await;
    let lib = qa.intersect(&ql, 1e-9).expect("intersections");
    let CurveIntersection::Point {
        t_a,
        t_b,
        point,
        contact,
    } = &lib[0]
    else {
        panic!("{lib:?}")
    };
    assert_eq!(*contact, Contact::Tangent { order: 1 });
    assert_eq!(
        v["intersections"],
        json!([{"kind": "tangent", "t_a": t_a, "t_b": t_b, "point": point, "order": 1}])
    );
    // the same line, 1e-10 lower than the top: a near miss with its gap, at tolerance 1e-9
    let (low, qlow) = bezier(&[[0.0, 1.0 + 1e-10], [2.0, 1.0 + 1e-10]]);
    let v = ok("/api/intersect", &json!({"curve": arch, "other": low})).await;
    let lib = qa.intersect(&qlow, 1e-9).expect("intersections");
    let Contact::NearMiss { gap } = lib[0].contact() else {
        panic!("{lib:?}")
    };
    assert_eq!(v["intersections"][0]["kind"], "near-miss", "{v}");
    assert_eq!(v["intersections"][0]["gap"].as_f64(), Some(gap), "{v}");
    // a curve along a part of another: an overlap with both intervals
    let (half, qh) = bezier(&[[1.0, 1.0], [2.0, 1.0]]);
    let v = ok("/api/intersect", &json!({"curve": line, "other": half})).await;
    let lib = ql.intersect(&qh, 1e-9).expect("intersections");
    let CurveIntersection::Overlap { a, b } = &lib[0] else {
        panic!("{lib:?}")
    };
    assert_eq!(
        v["intersections"],
        json!([{"kind": "overlap", "a": [a.0, a.1], "b": [b.0, b.1]}])
    );
    // errors name their field
    let (f, msg) = bad(
        "/api/intersect",
        &json!({"curve": arch, "other": line, "tolerance": -1}),
    )
    .await;
    assert_eq!(f, "tolerance", "{msg}");
    let space = json!({"lekalo": 1, "type": "bezier_curve", "control": [[0, 0, 0], [1, 1, 1]]});
    let (f, msg) = bad("/api/intersect", &json!({"curve": arch, "other": space})).await;
    assert!(f == "curve" || f == "other", "{f}: {msg}");
    assert!(msg.contains('3') && msg.contains('2'), "{msg}");
}

#[tokio::test]
async fn query_errors_name_the_field() {
    let (curve, _, _) = query_curve();
    for (route, body, field, needle) in [
        (
            "/api/project",
            json!({"curve": curve, "point": [1, 2, 3]}),
            "point",
            "dimension 3",
        ),
        (
            "/api/project",
            json!({"curve": curve}),
            "",
            "missing field `point`",
        ),
        (
            "/api/measure",
            json!({"curve": curve, "at_length": [100]}),
            "at_length",
            "length",
        ),
        (
            "/api/measure",
            json!({"curve": curve, "at_length": [-1]}),
            "at_length",
            "length",
        ),
        (
            "/api/measure",
            json!({"curve": curve, "rtol": -1}),
            "rtol",
            "",
        ),
        // the relative tolerance is `rtol`, as on the command line and in Python
        (
            "/api/measure",
            json!({"curve": curve, "tolerance": 1e-6}),
            "",
            "unknown field `tolerance`",
        ),
        (
            "/api/measure",
            json!({"curve": {"lekalo": 1, "type": "bspline_curve", "degree": 1, "knots": [0, 1], "control": [[0, 0]]}}),
            "curve",
            "",
        ),
        (
            "/api/project",
            json!({"curve": curve, "point": [1, 2], "extra": 1}),
            "",
            "unknown field",
        ),
    ] {
        let (f, msg) = bad(route, &body).await;
        assert!(f.starts_with(field), "{route} {body}: field {f}: {msg}");
        assert!(msg.contains(needle), "{route} {body}: {msg}");
    }
}

#[tokio::test]
async fn quasi_interpolation_takes_every_tau_rule_and_explicit_tau() {
    let breaks = [0.0, 0.5, 1.0, 2.0];
    let space = PpSpace::new(&breaks, &[2, 2], 3).expect("space");
    let f = Expression::parse("exp(x)").expect("expression");
    let lib = |tau: Tau<'_>| -> BSplineCurve {
        quasi_interpolate(&space, tau, |x, d| {
            f.derivatives(x, d).expect("derivatives")[d]
        })
        .expect("quasi-interpolant")
    };
    for (name, rule) in [
        ("first_knot_after", TauRule::FirstKnotAfter),
        ("left_end_of_support", TauRule::LeftEndOfSupport),
        ("midpoint", TauRule::Midpoint),
        ("greville", TauRule::Greville),
        ("first_interval_midpoint", TauRule::FirstIntervalMidpoint),
    ] {
        let v = ok(
            "/api/quasi",
            &json!({"expression": "exp(x)", "breakpoints": breaks, "order": 3, "rule": name}),
        )
        .await;
        assert_eq!(
            v["view"]["curve"],
            Object::BSpline(lib(Tau::Rule(rule))).to_json_value(),
            "{name}"
        );
    }
    let tau = [0.0, 0.3, 0.8, 1.5, 2.0];
    let v = ok(
        "/api/quasi",
        &json!({"expression": "exp(x)", "breakpoints": breaks, "order": 3, "tau": tau}),
    )
    .await;
    assert_eq!(
        v["view"]["curve"],
        Object::BSpline(lib(Tau::Values(&tau))).to_json_value()
    );
    let (field, msg) = bad(
        "/api/quasi",
        &json!({"expression": "exp(x)", "breakpoints": breaks, "order": 3, "tau": [0, 5, 1, 1.5, 2]}),
    )
    .await;
    assert_eq!(field, "tau", "{msg}");
    assert!(msg.contains("outside the support"), "{msg}");
    let (field, msg) = bad(
        "/api/quasi",
        &json!({"expression": "exp(x)", "breakpoints": breaks, "order": 3, "tau": [0, 1]}),
    )
    .await;
    assert_eq!(field, "tau", "{msg}");
}

/// A shape-constrained smoothing of noisy rising data: the answer is the graph of the library's
/// constrained spline, and it rises; `s` with constraints is refused at `smoothing`.
#[tokio::test]
async fn fitting_with_shape_constraints_is_the_library_s() {
    use lekalo::fit::{
        constrained_smoothing_condition, constrained_smoothing_spline, Shape, ShapeConstraints,
    };
    let pts: Vec<[f64; 2]> = (0..30)
        .map(|k| {
            let x = f64::from(k) / 29.0;
            [x, x + 0.08 * (f64::from(k) * 2.3).sin()]
        })
        .collect();
    let v = ok(
        "/api/fit",
        &json!({"points": pts, "smoothing": "lambda", "lambda": 1e-6, "increasing": true, "min": 0.0, "samples": 50}),
    )
    .await;
    let x: Vec<f64> = pts.iter().map(|p| p[0]).collect();
    let y: Vec<f64> = pts.iter().map(|p| p[1]).collect();
    let data = FitData::new(lekalo::PointsRef::from_flat(1, &y).unwrap(), &x).unwrap();
    let rules = ShapeConstraints::new()
        .with(Shape::Increasing)
        .with(Shape::AtLeast(0.0));
    let fit = constrained_smoothing_spline(&data, Lambda::Given(1e-6), &rules).unwrap();
    let graph = Object::BSpline(fit.curve.graph().unwrap());
    assert_eq!(v["view"]["curve"], graph.to_json_value());
    let drawn = v["view"]["points"].as_array().unwrap();
    let ys: Vec<f64> = drawn.iter().map(|p| p[1].as_f64().unwrap()).collect();
    assert!(ys.windows(2).all(|w| w[1] >= w[0] - 1e-12), "rises: {ys:?}");
    // a residual target s with a shape: the constrained smoothing spline whose residual is s,
    // as `lekalo fit --increasing --s S`
    let v = ok(
        "/api/fit",
        &json!({"points": pts, "smoothing": "s", "s": 0.1, "increasing": true}),
    )
    .await;
    let inc = ShapeConstraints::new().with(Shape::Increasing);
    let fit = constrained_smoothing_condition(&data, 0.1, &inc).unwrap();
    let graph = Object::BSpline(fit.curve.graph().unwrap());
    assert_eq!(v["view"]["curve"], graph.to_json_value());
    assert_eq!(
        v["report"]["weighted_rss"].as_f64(),
        Some(fit.report.weighted_rss)
    );
    let (field, msg) = bad(
        "/api/fit",
        &json!({"points": pts, "smoothing": "s", "s": 0.1, "convex": true, "knot_rounds": "refit"}),
    )
    .await;
    assert_eq!(field, "knot_rounds", "{msg}");
}
