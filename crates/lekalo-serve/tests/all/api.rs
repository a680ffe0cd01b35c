//! The API's answers checked against the library's, and hostile requests (malformed JSON,
//! NaN, huge arrays and sizes, deep nesting, slow clients), without a port
//! (`tower::ServiceExt::oneshot`) except for the slow-client test on loopback.

use lekalo_io::CurveJson;
use std::pin::Pin;
use std::task::{Context, Poll};
use std::time::Duration;

use axum::body::Body;
use axum::http::{header, Request, StatusCode};
use http_body_util::BodyExt;
use lekalo::{
    BSplineCurve, BezierCurve, CurveInterpolation, Deformation, EndConditions, Parametrization,
    PiecewisePolynomial, Points, DEFAULT_CONTINUITY_RTOL,
};
use lekalo_io::Object;
use lekalo_serve::{router, Limits};
use serde_json::{json, Value};
use tower::ServiceExt;

async fn call_with(
    limits: Limits,
    route: &str,
    body: Body,
) -> (StatusCode, Value, Vec<(String, String)>) {
    let req = Request::post(route)
        .header(header::ORIGIN, "http://evil.example")
        .body(body)
        .expect("request");
    let resp = router(limits).oneshot(req).await.expect("infallible");
    let status = resp.status();
    let headers = resp
        .headers()
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_str().unwrap_or("").to_string()))
        .collect();
    let bytes = resp.into_body().collect().await.expect("body").to_bytes();
    let value = serde_json::from_slice(&bytes)
        .unwrap_or(Value::String(String::from_utf8_lossy(&bytes).into_owned()));
    (status, value, headers)
}

async fn call(route: &str, body: impl Into<String>) -> (StatusCode, Value) {
    let (s, v, _) = call_with(Limits::default(), route, Body::from(body.into())).await;
    (s, v)
}

async fn ok(route: &str, body: &Value) -> Value {
    let (s, v) = call(route, body.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{route}: {v}");
    v
}

async fn bad(route: &str, body: impl Into<String>) -> (String, String) {
    let (s, v) = call(route, body).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{route}: {v}");
    (
        v["field"].as_str().unwrap_or("").to_string(),
        v["error"].as_str().expect("message").to_string(),
    )
}

fn rows(v: &Value) -> Vec<Vec<f64>> {
    serde_json::from_value(v.clone()).expect("rows of numbers")
}

const CURVE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2,
  "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[0, 0], [1, 2], [3, 2], [4, 0]]}"#;

#[tokio::test]
async fn evaluate_answers_the_library_s_points_knots_comb_and_basis() {
    let curve: Value = serde_json::from_str(CURVE).expect("json");
    let v = ok(
        "/api/evaluate",
        &json!({"curve": curve, "samples": 5, "comb": true, "basis_samples": 9, "at": 0.5}),
    )
    .await;
    let c = BSplineCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0],
        Points::from_2d(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).expect("points"),
    )
    .expect("curve");
    let pts = rows(&v["points"]);
    for (i, t) in [0.0, 0.5, 1.0, 1.5, 2.0].iter().enumerate() {
        assert_eq!(pts[i], c.eval(*t).expect("eval"), "point at t = {t}");
    }
    // knots 0, 1, 2 with multiplicities 3, 1, 3 and their points
    let marks = v["knot_marks"].as_array().expect("marks");
    assert_eq!(marks.len(), 3);
    assert_eq!(marks[1]["multiplicity"], 1);
    assert_eq!(
        rows(&json!([marks[1]["point"]]))[0],
        c.eval(1.0).expect("eval")
    );
    // curvature from the library's derivatives
    let d = c.eval_derivatives(0.5, 2).expect("derivatives");
    let k = lekalo::curvature(&d.as_slice()[2..4], &d.as_slice()[4..6]).expect("κ");
    assert_eq!(v["comb"]["curvature"][1].as_f64(), Some(k));
    // 4 basis functions; at t = 0.5 the active ones are N_0..N_2 with the library's values
    assert_eq!(v["basis"]["functions"].as_array().expect("fns").len(), 4);
    assert_eq!(v["basis"]["active"], json!([0, 1, 2]));
    let (_, n) = lekalo::basis::basis_functions(c.knots(), 2, 0.5).expect("basis");
    assert_eq!(v["basis"]["active_values"], json!(n));
}

#[tokio::test]
async fn interpolation_is_the_library_s() {
    let p = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.0], [6.0, 1.0]];
    let v = ok(
        "/api/interpolate",
        &json!({"points": p, "degree": 3, "parametrization": "centripetal", "knots": "averaged",
                "end": "derivatives", "start_derivative": [1, 0], "end_derivative": [0, -1]}),
    )
    .await;
    let c = CurveInterpolation::new(3)
        .parametrization(Parametrization::Centripetal)
        .knot_placement(lekalo::KnotPlacement::Averaged)
        .end_condition(lekalo::EndCondition::FirstDerivatives {
            start: vec![1.0, 0.0],
            end: vec![0.0, -1.0],
        })
        .interpolate(Points::from_2d(&p).expect("points").as_view())
        .expect("interpolation");
    assert_eq!(v["curve"], Object::BSpline(c).to_json_value());
    for end in ["free", "natural", "periodic"] {
        let v = ok(
            "/api/interpolate",
            &json!({"points": p, "end": end, "samples": 3}),
        )
        .await;
        assert_eq!(v["degree"], 3, "{end}");
    }
    let (field, msg) = bad(
        "/api/interpolate",
        json!({"points": p, "end": "derivatives"}).to_string(),
    )
    .await;
    assert_eq!(field, "start_derivative", "{msg}");
    let (field, msg) = bad(
        "/api/interpolate",
        json!({"points": p, "degree": 7}).to_string(),
    )
    .await;
    assert_eq!(field, "degree", "{msg}");
}

/// The smoothness at every interior break of a B-spline curve, as the library measures it on
/// its piecewise polynomial form: the `m` of `C^m` (`ν − 1`, `lekalo::PiecewisePolynomial::continuity`).
fn measured_continuity(curve: &Value) -> Vec<usize> {
    let Object::BSpline(c) = Object::from_json_str(&curve.to_string(), "answer").expect("curve")
    else {
        panic!("a B-spline curve: {curve}");
    };
    PiecewisePolynomial::from_bspline(&c)
        .expect("pp form")
        .continuity(DEFAULT_CONTINUITY_RTOL)
        .into_iter()
        .map(|nu| nu - 1)
        .collect()
}

#[tokio::test]
async fn the_blends_report_the_continuity_the_library_gives_them() {
    // corners: the knots at the joins have multiplicity 2k + 1 = degree (C^0 by the knots
    // alone); the answer's continuity is the library's k, and the drawn curve has it
    let zigzag = json!([[0, 0], [1, 2], [2, 0], [3, 2], [4, 0]]);
    for k in 1..=4 {
        let v = ok(
            "/api/blend/corners",
            &json!({"points": zigzag, "continuity": k, "fraction": 0.3}),
        )
        .await;
        assert_eq!(v["continuity"], k, "corners, k = {k}");
        let degree = v["degree"].as_u64().expect("degree");
        assert!(
            v["knot_marks"][1]["multiplicity"].as_u64() == Some(degree),
            "a join's knot has the multiplicity of the degree: {}",
            v["knot_marks"][1]
        );
        let m = measured_continuity(&v["curve"]);
        assert!(!m.is_empty(), "interior joins");
        assert_eq!(m.iter().min(), Some(&k), "k = {k}: measured {m:?}");
    }
    // the curve through points: C^k at its joins (parabolas), as the library's options say
    let v = ok(
        "/api/blend/spline",
        &json!({"points": zigzag, "continuity": 3}),
    )
    .await;
    assert_eq!(v["continuity"], 3);
    // a k whose curve is above the degree limit is refused naming k and the degree it makes
    for route in ["/api/blend/corners", "/api/blend/spline"] {
        let (field, msg) = bad(
            route,
            json!({"points": zigzag, "continuity": 40}).to_string(),
        )
        .await;
        assert_eq!(field, "continuity", "{msg}");
        assert!(
            msg.starts_with(
                "continuity k = 40 makes a curve of degree 81, above the server's limit 64"
            ),
            "{route}: {msg}"
        );
    }
    // the deformation: the order of its contact with the two curves at the ends
    let up = BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [2.0, 2.0], [4.0, 0.0]]).expect("p"))
        .expect("up");
    let down =
        BezierCurve::new(Points::from_2d(&[[0.0, 0.0], [2.0, -2.0], [4.0, 0.0]]).expect("p"))
            .expect("down");
    let v = ok(
        "/api/blend/deform",
        &json!({"first": Object::Bezier(up.clone()).to_json_value(),
                "second": Object::Bezier(down.clone()).to_json_value(), "continuity": 3}),
    )
    .await;
    let d = Deformation::new(&up, &down, 3).expect("deformation");
    assert_eq!(v["continuity"], d.continuity());
    assert_eq!(v["curve"]["type"], "bezier_curve");
}

#[tokio::test]
async fn bezier_order_change_blend_and_knots_are_the_library_s() {
    let ctrl = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
    let bez = BezierCurve::new(Points::from_2d(&ctrl).expect("points")).expect("curve");
    let obj = Object::Bezier(bez.clone()).to_json_value();
    let v = ok(
        "/api/bezier",
        &json!({"curve": obj, "op": "elevate", "by": 2}),
    )
    .await;
    assert_eq!(
        v["view"]["curve"],
        Object::Bezier(bez.elevate_degree(2).expect("elevate")).to_json_value()
    );
    assert_eq!(
        (v["degree"].clone(), v["real_degree"].clone()),
        (json!(5), json!(3))
    );
    let v = ok(
        "/api/bezier",
        &json!({"curve": obj, "op": "reduce_approx", "target": 2, "ends": "points"}),
    )
    .await;
    let r = bez
        .reduce_degree_approx(2, EndConditions::Points)
        .expect("reduce");
    assert_eq!(
        v["deviation"]["sampled"].as_f64(),
        Some(r.max_deviation_sampled)
    );
    let (field, _) = bad(
        "/api/bezier",
        json!({"curve": obj, "op": "reduce_approx", "target": 1, "ends": "tangents"}).to_string(),
    )
    .await;
    assert_eq!(field, "target");
    // the library's refusal of the target degree and the limit on the elevated degree name
    // their fields; the library's key, when its error has one, would name another
    let (field, msg) = bad(
        "/api/bezier",
        json!({"curve": obj, "op": "reduce_approx", "target": 2, "ends": "tangents"}).to_string(),
    )
    .await;
    assert_eq!(field, "target", "{msg}");
    let (field, msg) = bad(
        "/api/bezier",
        json!({"curve": obj, "op": "elevate", "by": 1_000_000}).to_string(),
    )
    .await;
    assert_eq!(field, "by", "{msg}");

    let down = [[0.0, 0.0], [2.0, -2.0], [4.0, 0.0]];
    let second = BezierCurve::new(Points::from_2d(&down).expect("points")).expect("curve");
    let v = ok(
        "/api/blend/deform",
        &json!({"first": obj, "second": Object::Bezier(second.clone()).to_json_value(), "continuity": 2}),
    )
    .await;
    let d = Deformation::new(&bez, &second, 2).expect("deformation");
    assert_eq!(
        v["curve"],
        Object::Bezier(d.to_bezier().expect("exact")).to_json_value()
    );
    // k out of range names the range the server's degree limit leaves for these cubics,
    // (2k − 1) + 3 ≤ 64: k ≤ 31, not the library's own bound
    let (field, msg) = bad(
        "/api/blend/deform",
        json!({"first": obj, "second": obj, "continuity": 0}).to_string(),
    )
    .await;
    assert_eq!(field, "continuity");
    assert!(msg.contains("must be in 1..=31"), "{msg}");
    let v = ok(
        "/api/blend/deform",
        &json!({"first": obj, "second": obj, "continuity": 31}),
    )
    .await;
    assert_eq!(v["degree"], 64, "the highest k the limit allows is served");
    let (field, msg) = bad(
        "/api/blend/deform",
        json!({"first": obj, "second": obj, "continuity": 32}).to_string(),
    )
    .await;
    assert_eq!(field, "continuity");
    assert!(
        msg.starts_with(
            "continuity k = 32 makes a curve of degree 66, above the server's limit 64"
        ),
        "{msg}"
    );
    // corners smoothed over a window (as `lekalo blend corners`), the curve through the points
    // by blended parabolas (as `lekalo blend spline`)
    let zigzag = json!([[0, 0], [1, 2], [2, 0], [3, 2]]);
    let v = ok(
        "/api/blend/corners",
        &json!({"points": zigzag, "continuity": 2, "fraction": 0.3}),
    )
    .await;
    assert_eq!(v["curve"]["type"], "bspline_curve");
    assert_eq!(v["degree"], 5, "degree 2k + 1");
    for (body, want) in [
        (json!({"points": zigzag, "continuity": 0}), "continuity"),
        (
            json!({"points": zigzag, "continuity": 2, "fraction": 0.7}),
            "fraction",
        ),
        (
            json!({"points": zigzag, "continuity": 2, "length": 5.0}),
            "length",
        ),
        (
            json!({"points": [[0, 0], [1, 1]], "continuity": 2}),
            "points",
        ),
    ] {
        let (field, msg) = bad("/api/blend/corners", body.to_string()).await;
        assert_eq!(field, want, "{msg}");
    }
    let v = ok(
        "/api/blend/spline",
        &json!({"points": zigzag, "continuity": 2, "closed": true}),
    )
    .await;
    assert_eq!(v["curve"]["type"], "nurbs_curve");

    let curve: Value = serde_json::from_str(CURVE).expect("json");
    let v = ok(
        "/api/knot/insert",
        &json!({"curve": curve, "t": 0.5, "times": 1}),
    )
    .await;
    assert_eq!(v["control"].as_array().map(Vec::len), Some(5));
    let v = ok("/api/knot/remove", &json!({"curve": v["curve"], "t": 0.5})).await;
    assert_eq!(v["removed"], 1, "the inserted knot is removable");
    let (field, msg) = bad(
        "/api/knot/remove",
        json!({"curve": curve, "t": 0.3}).to_string(),
    )
    .await;
    assert_eq!(field, "t", "{msg}");
    // a refused tolerance is named by the library's key, through the server's table
    let (field, msg) = bad(
        "/api/knot/remove",
        json!({"curve": curve, "t": 0.5, "tolerance": -1.0}).to_string(),
    )
    .await;
    assert_eq!(field, "tolerance", "{msg}");
}

#[tokio::test]
async fn quasi_interpolation_of_a_typed_function_matches_the_cli() {
    // the thesis's example, as `lekalo pp quasi --function 'x*cos(x)' ... --rule left-end-of-support`
    let v = ok(
        "/api/quasi",
        &json!({"expression": "x * cos(x)", "breakpoints": [0, 0.5, 0.9, 1.4, 2.1, 2.7, 3],
                "order": 3, "rule": "left_end_of_support", "intervals": 60}),
    )
    .await;
    let e = v["max_error"].as_f64().expect("max error");
    assert!((e - 0.204831).abs() < 5e-7, "max error {e}");
    for (expr, needle) in [("x*coz(x)", "unknown name"), ("1/x", "division by zero")] {
        let (field, msg) = bad(
            "/api/quasi",
            json!({"expression": expr, "breakpoints": [0, 1, 2], "order": 3}).to_string(),
        )
        .await;
        assert_eq!(field, "expression");
        assert!(msg.contains(needle), "{msg}");
    }
}

#[tokio::test]
async fn object_errors_are_the_cli_s_with_the_field() {
    let unsorted = CURVE.replace("[0, 0, 0, 1, 2, 2, 2]", "[0, 0, 0, 3, 2, 2, 2]");
    // the API reads the object from its compact text: the same reader, the same message
    let compact = serde_json::from_str::<Value>(&unsorted)
        .expect("json")
        .to_string();
    let cli = Object::from_json_str(&compact, "curve").expect_err("unsorted");
    let (field, msg) = bad("/api/evaluate", format!("{{\"curve\": {unsorted}}}")).await;
    assert_eq!(field, "curve.knots");
    assert_eq!(msg, cli.to_string());
    let (field, _) = bad("/api/import", CURVE.replace("\"degree\"", "\"degre\"")).await;
    assert_eq!(field, "file.degre", "unknown field named");
    let (field, _) = bad(
        "/api/bspline",
        json!({"control": [[0, 0], [1, 1]], "degree": 1, "weights": [1, -1]}).to_string(),
    )
    .await;
    assert_eq!(field, "weights");
}

/// An imported file that is not UTF-8 is named as the command line names it, by its field, line
/// and column: it was `the file is not UTF-8 text` with the field `""`.
#[tokio::test]
async fn an_import_that_is_not_utf8_names_the_line_and_column() {
    let mut body = CURVE.as_bytes().to_vec();
    let at = CURVE.find("bspline_curve").expect("type");
    body[at] = 0xe9; // a Latin-1 é
    let (s, v, _) = call_with(Limits::default(), "/api/import", Body::from(body)).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert_eq!(v["field"], "file", "{v}");
    let want = format!("not UTF-8 text at line 1, column {} (byte {at})", at + 1);
    assert!(v["error"].as_str().expect("message").contains(&want), "{v}");
}

#[tokio::test]
async fn hostile_json_is_refused_with_a_named_error() {
    for (body, field) in [
        ("{\"curve\": ", ""),                                 // truncated
        ("not json", ""),                                     // not JSON
        ("{\"points\": [[0, NaN]]}", ""),                     // NaN is not JSON
        ("{\"points\": [[0, 1e999]], \"degree\": 1}", ""),    // overflows to inf
        ("{\"points\": [[0, 1]], \"degree\": -1}", "degree"), // negative size
        ("{\"points\": [[0, 1, 2]]}", "points[0]"),           // wrong dimension
        ("{\"points\": \"x\"}", "points"),                    // wrong type
    ] {
        let (f, msg) = bad("/api/interpolate", body).await;
        assert_eq!(f, field, "{body}: {msg}");
    }
    // the view options, which the requests take through serde's `flatten`, are named as well
    // (they were refused with the field "")
    let curve: Value = serde_json::from_str(CURVE).expect("json");
    for (route, key, value) in [
        ("/api/evaluate", "samples", json!(-1)),
        ("/api/evaluate", "samples", json!(3.5)),
        ("/api/evaluate", "basis_samples", json!(1e20)),
        ("/api/evaluate", "comb", json!("yes")),
        ("/api/evaluate", "at", json!("x")),
        ("/api/bspline", "samples", json!(-2)),
    ] {
        let mut body = if route == "/api/evaluate" {
            json!({"curve": curve})
        } else {
            json!({"control": [[0, 0], [1, 1]], "degree": 1})
        };
        body[key] = value;
        let (f, msg) = bad(route, body.to_string()).await;
        assert_eq!(f, key, "{route} {body}: {msg}");
    }
    // a body that is not an object is refused as such, not by the handler's type name
    for (body, what) in [
        ("[1, 2]", "an array"),
        ("null", "null"),
        ("\"x\"", "a string"),
    ] {
        let (f, msg) = bad("/api/evaluate", body).await;
        assert_eq!(f, "", "{body}");
        assert!(
            msg.starts_with(&format!(
                "the request body is {what}; it must be a JSON object"
            )),
            "{msg}"
        );
        assert!(!msg.contains("Request"), "{msg}");
    }
    let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
    // nesting where any JSON is allowed (the curve object) stops at serde_json's depth limit
    let (f, msg) = bad("/api/evaluate", format!("{{\"curve\": {deep}}}")).await;
    assert!(msg.contains("recursion limit"), "{f}: {msg}");
}

#[tokio::test]
async fn huge_sizes_are_refused() {
    let curve: Value = serde_json::from_str(CURVE).expect("json");
    let (field, _) = bad(
        "/api/evaluate",
        json!({"curve": curve, "samples": 1_000_000_000_u64}).to_string(),
    )
    .await;
    assert_eq!(field, "samples");
    let many = vec![[0.5, 0.5]; lekalo_serve::api::MAX_POINTS + 1];
    let (field, msg) = bad("/api/interpolate", json!({"points": many}).to_string()).await;
    assert_eq!(field, "points");
    assert!(msg.contains("at most"), "{msg}");
    let (field, _) = bad(
        "/api/bezier",
        json!({"curve": {"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1]]},
               "op": "elevate", "by": usize::MAX})
        .to_string(),
    )
    .await;
    assert_eq!(field, "by");
    // a body above the limit: 413, before any parsing
    let limits = Limits {
        body_bytes: 1000,
        ..Limits::default()
    };
    let (s, _, _) = call_with(limits, "/api/interpolate", Body::from(vec![b' '; 5000])).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE);
}

#[tokio::test]
async fn no_cors_headers_and_named_404() {
    let (s, v, headers) = call_with(Limits::default(), "/api/nothing", Body::empty()).await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    assert!(v["error"].is_string());
    let curve: Value = serde_json::from_str(CURVE).expect("json");
    let (s, _, headers2) = call_with(
        Limits::default(),
        "/api/export/step",
        Body::from(json!({"curve": curve}).to_string()),
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    for (k, _) in headers.iter().chain(&headers2) {
        assert!(!k.starts_with("access-control-"), "CORS header {k}");
    }
    assert!(headers2
        .iter()
        .any(|(k, v)| k == "content-disposition" && v.contains("curve.step")));
}

/// A request body that sends a few bytes and then nothing, forever.
struct Stalled(bool);

impl http_body::Body for Stalled {
    type Data = axum::body::Bytes;
    type Error = std::convert::Infallible;
    fn poll_frame(
        mut self: Pin<&mut Self>,
        _: &mut Context<'_>,
    ) -> Poll<Option<Result<http_body::Frame<Self::Data>, Self::Error>>> {
        if self.0 {
            return Poll::Pending;
        }
        self.0 = true;
        Poll::Ready(Some(Ok(http_body::Frame::data(
            axum::body::Bytes::from_static(b"{\"points\": ["),
        ))))
    }
}

#[tokio::test]
async fn a_slow_client_gets_408_and_others_are_served_meanwhile() {
    let limits = Limits {
        timeout: Duration::from_millis(300),
        ..Limits::default()
    };
    let (s, _, _) = call_with(limits, "/api/interpolate", Body::new(Stalled(false))).await;
    assert_eq!(s, StatusCode::REQUEST_TIMEOUT);

    // on loopback: a connection that stalls in its body does not block another one
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
        .await
        .expect("bind");
    let addr = listener.local_addr().expect("addr");
    tokio::spawn(async move { axum::serve(listener, router(limits)).await });
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut slow = tokio::net::TcpStream::connect(addr).await.expect("connect");
    slow.write_all(
        b"POST /api/interpolate HTTP/1.1\r\nhost: x\r\ncontent-length: 100\r\n\r\n{\"po",
    )
    .await
    .expect("write");
    let mut fast = tokio::net::TcpStream::connect(addr).await.expect("connect");
    fast.write_all(b"GET /api/health HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n")
        .await
        .expect("write");
    let mut answer = String::new();
    tokio::time::timeout(Duration::from_secs(5), fast.read_to_string(&mut answer))
        .await
        .expect("answered while the other client stalls")
        .expect("read");
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
    let mut rest = String::new();
    tokio::time::timeout(Duration::from_secs(5), slow.read_to_string(&mut rest))
        .await
        .expect("the stalled request ends")
        .expect("read");
    assert!(rest.starts_with("HTTP/1.1 408"), "{rest}");
}

/// One HTTP/1.1 request on a fresh loopback connection; the status line's code.
async fn raw(addr: std::net::SocketAddr, route: &str, body: &str) -> u16 {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut s = tokio::net::TcpStream::connect(addr).await.expect("connect");
    let req = format!(
        "POST {route} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    );
    s.write_all(req.as_bytes()).await.expect("write");
    let mut answer = String::new();
    s.read_to_string(&mut answer).await.expect("read");
    answer
        .get(9..12)
        .and_then(|c| c.parse().ok())
        .expect("status line")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bounded_load_on_loopback_every_request_answered() {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
        .await
        .expect("bind");
    let addr = listener.local_addr().expect("addr");
    tokio::spawn(async move { axum::serve(listener, router(Limits::default())).await });
    let pts: Vec<[f64; 2]> = (0..100)
        .map(|i| {
            let t = f64::from(i) / 10.0;
            [t, t.sin()]
        })
        .collect();
    let good = json!({"points": pts, "samples": 1000, "basis_samples": 200, "at": 0.5}).to_string();
    let mut tasks = Vec::new();
    for client in 0..8 {
        let good = good.clone();
        tasks.push(tokio::spawn(async move {
            let mut codes = Vec::new();
            for i in 0..25 {
                // every fifth request is hostile: it must be refused, not crash anything
                let (body, want) = if (client + i) % 5 == 0 {
                    ("{\"points\": [[0, NaN]]}", 400)
                } else {
                    (good.as_str(), 200)
                };
                codes.push((raw(addr, "/api/interpolate", body).await, want));
            }
            codes
        }));
    }
    let mut answered = 0;
    for t in tasks {
        for (got, want) in t.await.expect("client task") {
            assert_eq!(got, want, "status");
            answered += 1;
        }
    }
    assert_eq!(answered, 200, "every request answered");
    assert_eq!(raw(addr, "/api/interpolate", &good).await, 200, "still up");
}

/// A misspelled field is refused, naming it, by every route that takes a request object (the
/// documented rule "a request naming an unknown field is an error"): a typo must not leave the
/// default in place and answer as if it had been understood.
#[tokio::test]
async fn every_route_refuses_a_misspelled_field() {
    let curve = json!({"lekalo": 1, "type": "bspline_curve", "degree": 2,
        "knots": [0, 0, 0, 0.5, 1, 1, 1], "control": [[0, 0], [1, 2], [2, 2], [3, 0]]});
    let bezier = json!({"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 2], [2, 0]]});
    let points = json!([[0, 0], [1, 2], [2, 1], [3, 3], [4, 0], [5, 1]]);
    for (route, body) in [
        ("/api/evaluate", json!({"curve": curve})),
        ("/api/bspline", json!({"control": points, "degree": 3})),
        ("/api/bezier/build", json!({"control": points})),
        ("/api/interpolate", json!({"points": points})),
        ("/api/bezier", json!({"curve": bezier, "op": "elevate"})),
        (
            "/api/blend/deform",
            json!({"first": bezier, "second": bezier, "continuity": 1}),
        ),
        (
            "/api/blend/corners",
            json!({"points": points, "continuity": 1}),
        ),
        (
            "/api/blend/spline",
            json!({"points": points, "continuity": 1}),
        ),
        (
            "/api/quasi",
            json!({"expression": "x", "breakpoints": [0, 1, 2], "order": 2}),
        ),
        ("/api/fit", json!({"points": points, "smoothing": "gcv"})),
        ("/api/project", json!({"curve": curve, "point": [1, 1]})),
        ("/api/measure", json!({"curve": curve})),
        ("/api/intersect", json!({"curve": curve, "other": bezier})),
        ("/api/knot/insert", json!({"curve": curve, "t": 0.25})),
        ("/api/knot/remove", json!({"curve": curve, "t": 0.5})),
        ("/api/export/json", json!({"curve": curve})),
    ] {
        // the body as it is is answered
        let (s, v) = call(route, body.to_string()).await;
        assert_eq!(s, StatusCode::OK, "{route}: {v}");
        let mut typo = body.clone();
        typo["degre"] = json!(2);
        let (f, msg) = bad(route, typo.to_string()).await;
        assert!(
            msg.contains("unknown field `degre`"),
            "{route}: a misspelled field answered with field {f:?}: {msg}"
        );
    }
}

/// A count that is not a whole number, or a coordinate that is not a number, is refused next
/// to its field in the editor's words: no Rust type (`usize`, `f64`) and no position in the
/// request's text, which the person at the editor never sees.
#[tokio::test]
async fn type_errors_name_the_kind_of_value_not_a_rust_type() {
    let points = json!([[0, 0], [1, 2], [2, 1], [3, 3]]);
    for (route, body, field, says) in [
        (
            "/api/interpolate",
            json!({"points": points, "degree": 2.5}),
            "degree",
            "2.5`, expected a whole number ≥ 0",
        ),
        (
            "/api/blend/corners",
            json!({"points": points, "continuity": -1}),
            "continuity",
            "-1`, expected a whole number ≥ 0",
        ),
        (
            "/api/quasi",
            json!({"expression": "x", "breakpoints": [0, 1, 2], "order": 2.5}),
            "order",
            "expected a whole number ≥ 0",
        ),
        (
            "/api/bspline",
            json!({"control": [[0, 0], [1, "a"]], "degree": 1}),
            "control[1][1]",
            "string \"a\", expected a number",
        ),
        (
            "/api/fit",
            json!({"points": points, "lambda": "big"}),
            "lambda",
            "expected a number",
        ),
    ] {
        let (f, msg) = bad(route, body.to_string()).await;
        assert_eq!(f, field, "{route}: {msg}");
        assert!(msg.contains(says), "{route}: {msg}");
        assert!(
            !msg.contains("usize") && !msg.contains("f64") && !msg.contains("line 1"),
            "{route}: {msg}"
        );
    }
    // a whole number written as JavaScript may write it is that number
    let (s, v) = call(
        "/api/interpolate",
        json!({"points": points, "degree": 2.0}).to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["degree"], json!(2), "{v}");
}
