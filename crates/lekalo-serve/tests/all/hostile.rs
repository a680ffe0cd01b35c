//! Every computing route of `docs/openapi.json` under a battery of hostile requests made from a
//! valid body of its own: each field removed, each field replaced by every JSON type and by
//! numbers of every size (1e308, 2^64, 10^9 samples or points, a tolerance of 1e-300), one
//! coordinate of each list replaced, and whole bodies that are deeply nested, oversized, empty
//! or not JSON. Each request is answered within the deadline with 200 or a 4xx whose body is a
//! JSON error naming the problem; none reaches a 5xx (a crash, a stall stopped by the deadline,
//! an internal failure), and `/api/health` answers throughout.

#![allow(clippy::missing_assert_message)] // assert_eq! prints both sides

use std::time::{Duration, Instant};

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use lekalo_serve::{router, Limits};
use serde_json::{json, Value};
use tower::ServiceExt;

/// A valid body of each computing route.
fn routes() -> Vec<(&'static str, Value)> {
    let curve = json!({"lekalo": 1, "type": "bspline_curve", "degree": 2,
        "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[0, 0], [1, 2], [3, 2], [4, 0]]});
    let other = json!({"lekalo": 1, "type": "bezier_curve", "control": [[0, 1], [4, 1]]});
    let bez = json!({"lekalo": 1, "type": "bezier_curve",
        "control": [[0, 0], [1, 2], [3, 2], [4, 0]]});
    let down = json!({"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [2, -2], [4, 0]]});
    let up = json!({"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [2, 2], [4, 0]]});
    let pts = json!([[0, 0], [1, 2], [2, 0], [3, 2], [4, 0], [5, 1]]);
    vec![
        (
            "/api/evaluate",
            json!({"curve": curve, "samples": 50, "comb": true, "basis_samples": 9, "at": 0.5}),
        ),
        (
            "/api/bspline",
            json!({"control": [[0, 0], [1, 2], [3, 2], [4, 0]], "degree": 2, "samples": 20}),
        ),
        (
            "/api/bezier/build",
            json!({"control": [[0, 0], [1, 2], [3, 2]], "samples": 20}),
        ),
        (
            "/api/interpolate",
            json!({"points": pts, "degree": 3, "samples": 20}),
        ),
        (
            "/api/bezier",
            json!({"curve": bez, "op": "elevate", "by": 2}),
        ),
        (
            "/api/blend/deform",
            json!({"first": up, "second": down, "continuity": 3}),
        ),
        (
            "/api/blend/corners",
            json!({"points": pts, "continuity": 1, "fraction": 0.3}),
        ),
        ("/api/blend/spline", json!({"points": pts, "continuity": 1})),
        (
            "/api/quasi",
            json!({"expression": "sin(x)", "breakpoints": [0, 1, 2, 3], "order": 3, "intervals": 20}),
        ),
        (
            "/api/fit",
            json!({"points": pts, "smoothing": "gcv", "degree": 3}),
        ),
        ("/api/project", json!({"curve": curve, "point": [1, 1]})),
        (
            "/api/measure",
            json!({"curve": curve, "at_length": [0.5, 1], "rtol": 1e-9}),
        ),
        (
            "/api/intersect",
            json!({"curve": curve, "other": other, "tolerance": 1e-9}),
        ),
        (
            "/api/knot/insert",
            json!({"curve": curve, "t": 0.5, "times": 1}),
        ),
        (
            "/api/knot/remove",
            json!({"curve": curve, "t": 1, "times": 1, "tolerance": 1e-6}),
        ),
        ("/api/import", curve.clone()),
        ("/api/export/json", json!({"curve": curve})),
        ("/api/export/step", json!({"curve": curve})),
    ]
}

/// What replaces a field: every JSON type, and numbers of every size.
fn replacements() -> Vec<Value> {
    let deep = (0..200).fold(json!(0), |v, _| json!([v]));
    vec![
        Value::Null,
        json!("x"),
        json!(""),
        json!(true),
        json!({}),
        json!([]),
        json!([[]]),
        json!({"a": [1, {"b": null}]}),
        deep,
        json!(0),
        json!(-1),
        json!(0.5),
        json!(1e-300),
        json!(-1e-300),
        json!(1e308),
        json!(-1e308),
        json!(1_000_000_000u64),
        json!(4_294_967_296u64),
        json!(u64::MAX),
        json!(i64::MIN),
        json!("NaN"),
        json!("Infinity"),
    ]
}

/// A route's answer: status, body, and how long it took.
async fn send(app: &axum::Router, route: &str, body: Body) -> (StatusCode, Value, Duration) {
    let req = Request::post(route)
        .header("content-type", "application/json")
        .body(body)
        .expect("request");
    let start = Instant::now();
    let resp = app.clone().oneshot(req).await.expect("infallible");
    let status = resp.status();
    let bytes = resp.into_body().collect().await.expect("body").to_bytes();
    let value = serde_json::from_slice(&bytes)
        .unwrap_or_else(|_| Value::String(String::from_utf8_lossy(&bytes).into_owned()));
    (status, value, start.elapsed())
}

/// Asserts the rules of the module docs on one answer, `case` naming the request.
fn check(case: &str, status: StatusCode, v: &Value, took: Duration, deadline: Duration) {
    assert!(
        status == StatusCode::OK || status.is_client_error(),
        "{case}: {status} {v}"
    );
    if status.is_client_error() {
        let msg = v["error"].as_str().unwrap_or_default();
        assert!(
            !msg.is_empty(),
            "{case}: {status} without a JSON error: {v}"
        );
        assert!(
            !msg.contains("panic") && !msg.contains("internal"),
            "{case}: {msg}"
        );
    }
    assert!(took < deadline, "{case}: answered after {took:?}");
}

/// The places in `v` (a body) that hold a value: every field, and the first element of every
/// list and the first number of every list of lists, as JSON pointers.
fn places(v: &Value, at: &str, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let p = format!("{at}/{k}");
                out.push(p.clone());
                places(x, &p, out);
            }
        }
        Value::Array(a) => {
            if let Some(x) = a.first() {
                let p = format!("{at}/0");
                out.push(p.clone());
                places(x, &p, out);
            }
            if a.len() > 1 {
                out.push(format!("{at}/{}", a.len() - 1));
            }
        }
        _ => {}
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_route_answers_hostile_fields_with_a_json_4xx_in_time() {
    let limits = Limits::default();
    // generous: the deadline of a computation, plus reading and answering, in a debug build
    let deadline = limits.deadline + Duration::from_secs(5);
    let app = router(limits);
    let mut cases = 0;
    for (route, base) in routes() {
        let (s, v, _) = send(&app, route, Body::from(base.to_string())).await;
        assert_eq!(s, StatusCode::OK, "{route}: the valid body: {v}");
        let mut at = Vec::new();
        places(&base, "", &mut at);
        for p in &at {
            // removed
            let mut body = base.clone();
            let (parent, key) = p.rsplit_once('/').expect("a pointer");
            let removed = match body.pointer_mut(parent) {
                Some(Value::Object(m)) => m.remove(key).is_some(),
                Some(Value::Array(a)) => key
                    .parse::<usize>()
                    .ok()
                    .filter(|&i| i < a.len())
                    .map(|i| a.remove(i))
                    .is_some(),
                _ => false,
            };
            if removed {
                let (s, v, took) = send(&app, route, Body::from(body.to_string())).await;
                check(&format!("{route} without {p}"), s, &v, took, deadline);
                cases += 1;
            }
            // replaced
            for r in replacements() {
                let mut body = base.clone();
                if let Some(slot) = body.pointer_mut(p) {
                    *slot = r.clone();
                }
                let (s, v, took) = send(&app, route, Body::from(body.to_string())).await;
                check(&format!("{route} with {p} = {r}"), s, &v, took, deadline);
                cases += 1;
            }
        }
    }
    assert!(cases > 2000, "{cases} cases");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_route_refuses_hostile_bodies_with_a_json_4xx_in_time() {
    let limits = Limits::default();
    let deadline = limits.deadline + Duration::from_secs(5);
    let max = limits.body_bytes;
    let app = router(limits);
    let nested_array = "[".repeat(100_000);
    let nested_object = "{\"a\":".repeat(100_000);
    let nested_field = format!("{{\"curve\": {}", "[".repeat(100_000));
    let big_string = format!("{{\"curve\": \"{}\"}}", "x".repeat(max + 1));
    let big_list = format!("{{\"points\": [{}[0, 0]]}}", "[0, 0], ".repeat(max / 8));
    let many_points = format!(
        "{{\"points\": [{}], \"degree\": 3}}",
        (0..200_000)
            .map(|i| format!("[{i},0]"))
            .collect::<Vec<_>>()
            .join(",")
    );
    let bodies: Vec<(&str, Vec<u8>)> = vec![
        ("empty", Vec::new()),
        ("null", b"null".to_vec()),
        ("a list", b"[]".to_vec()),
        ("a number", b"1e999".to_vec()),
        ("not JSON", b"curve=1".to_vec()),
        ("not UTF-8", b"{\"curve\": \"\xff\"}".to_vec()),
        ("truncated", b"{\"curve\": {\"lekalo\": 1,".to_vec()),
        ("trailing", b"{} {}".to_vec()),
        ("NaN", b"{\"curve\": NaN, \"points\": [[NaN, 1]]}".to_vec()),
        (
            "1e999",
            b"{\"points\": [[1e999, 1], [0, 0]], \"t\": 1e999}".to_vec(),
        ),
        ("nested arrays", nested_array.into_bytes()),
        ("nested objects", nested_object.into_bytes()),
        ("nested field", nested_field.into_bytes()),
        ("a string above the body limit", big_string.into_bytes()),
        ("a list above the body limit", big_list.into_bytes()),
        ("200000 points", many_points.into_bytes()),
    ];
    for (route, _) in routes() {
        for (what, body) in &bodies {
            let (s, v, took) = send(&app, route, Body::from(body.clone())).await;
            let case = format!("{route}: {what}");
            check(&case, s, &v, took, deadline);
            assert!(s.is_client_error(), "{case}: {s} {v}");
        }
    }
}
