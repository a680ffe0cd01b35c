//! A server one client cannot stall: heavy requests compute in the bounded pool while
//! `/api/health` is answered; the budget refuses oversized curves before computing, naming the
//! field; a computation past the deadline is stopped and answered with 504; a full pool and
//! queue answer 503 with `Retry-After`; a fit past the deadline frees its worker; the library's
//! errors name the right field.
//!
//! No test here asserts a speed: the order of events (health answered while the heavy requests
//! are still running) and generous bounds (seconds where milliseconds are expected) only.

#![allow(clippy::missing_assert_message)] // assert_eq! prints both sides

use std::time::{Duration, Instant};

use axum::body::Body;
use axum::http::{header, Request, StatusCode};
use http_body_util::BodyExt;
use lekalo_serve::{router, Limits};
use serde_json::{json, Value};
use tower::ServiceExt;

/// A Bezier curve of degree `n` in the CLI's object format.
fn bezier(n: usize) -> Value {
    let control: Vec<[f64; 2]> = (0..=n)
        .map(|i| {
            let t = i as f64 / n as f64;
            [t, (7.0 * t).sin()]
        })
        .collect();
    json!({"lekalo": 1, "type": "bezier_curve", "control": control})
}

/// The hostile request: a degree-3000 Bezier curve drawn at 10,000 samples.
fn heavy() -> String {
    json!({"curve": bezier(3000), "samples": 10_000}).to_string()
}

/// Limits that let the hostile request through the budget, so that it computes.
fn permissive() -> Limits {
    Limits {
        max_degree: 4000,
        max_work: u64::MAX,
        ..Limits::default()
    }
}

async fn call(
    app: axum::Router,
    route: &str,
    body: String,
) -> (StatusCode, Value, axum::http::HeaderMap) {
    let req = Request::post(route)
        .body(Body::from(body))
        .expect("request");
    let resp = app.oneshot(req).await.expect("infallible");
    let status = resp.status();
    let headers = resp.headers().clone();
    let bytes = resp.into_body().collect().await.expect("body").to_bytes();
    let value = serde_json::from_slice(&bytes)
        .unwrap_or(Value::String(String::from_utf8_lossy(&bytes).into_owned()));
    (status, value, headers)
}

/// The application with `limits`, served on a free loopback port in the background: its
/// address.
async fn serving(limits: Limits) -> std::net::SocketAddr {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
        .await
        .expect("bind");
    let addr = listener.local_addr().expect("addr");
    tokio::spawn(async move { axum::serve(listener, router(limits)).await });
    addr
}

/// One HTTP/1.1 request on a fresh loopback connection: the status code and the body.
async fn raw(addr: std::net::SocketAddr, method: &str, route: &str, body: &str) -> (u16, String) {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut s = tokio::net::TcpStream::connect(addr).await.expect("connect");
    let req = format!(
        "{method} {route} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    );
    s.write_all(req.as_bytes()).await.expect("write");
    let mut answer = String::new();
    s.read_to_string(&mut answer).await.expect("read");
    let code = answer
        .get(9..12)
        .and_then(|c| c.parse().ok())
        .expect("status line");
    let body = answer
        .split_once("\r\n\r\n")
        .map(|(_, b)| b.to_string())
        .unwrap_or_default();
    (code, body)
}

/// Three hostile requests at once on the server's runtime (two async workers): health is
/// answered while all three are still in flight; their computations are stopped at the
/// deadline (504, naming it), and the pool is free again afterwards.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn health_is_answered_while_heavy_requests_compute_and_the_deadline_stops_them() {
    let limits = Limits {
        workers: 2,
        deadline: Duration::from_secs(2),
        timeout: Duration::from_secs(30),
        ..permissive()
    };
    let addr = serving(limits).await;
    let started = Instant::now();
    let body = heavy();
    let heavy: Vec<_> = (0..3)
        .map(|_| {
            let body = body.clone();
            tokio::spawn(async move { raw(addr, "POST", "/api/evaluate", &body).await })
        })
        .collect();
    // let the heavy requests reach the pool
    tokio::time::sleep(Duration::from_millis(300)).await;
    for _ in 0..3 {
        let asked = Instant::now();
        let (code, text) = raw(addr, "GET", "/api/health", "").await;
        let took = asked.elapsed();
        assert_eq!((code, text.as_str()), (200, "ok"));
        assert!(
            took < Duration::from_secs(1),
            "health took {took:?} while the pool computes"
        );
        assert!(
            heavy.iter().all(|h| !h.is_finished()),
            "health was answered while the heavy requests were still in flight"
        );
        // the editor's page too
        let (code, _) = raw(addr, "GET", "/js/main.js", "").await;
        assert_eq!(code, 200);
    }
    for h in heavy {
        let (code, text) = h.await.expect("task");
        assert_eq!(code, 504, "{text}");
        let v: Value = serde_json::from_str(&text).expect("JSON error");
        let msg = v["error"].as_str().expect("message");
        assert!(msg.contains("deadline of 2 s"), "{msg}");
        // the fix in the editor user's words too: what to ask for, and how to give more time
        assert!(
            msg.contains("shape constraints") && msg.contains("`lekalo serve --deadline 30`"),
            "{msg}"
        );
    }
    // degree 3000 at 10,000 samples is minutes of work in a debug build: the answers came
    // at the deadline, not when the work would have ended
    assert!(
        started.elapsed() < Duration::from_secs(20),
        "answered after {:?}",
        started.elapsed()
    );
    // the kernels stopped: the pool computes a small request at once
    let small = json!({"curve": bezier(3), "samples": 50}).to_string();
    let (code, text) = raw(addr, "POST", "/api/evaluate", &small).await;
    assert_eq!(code, 200, "{text}");
}

#[tokio::test]
async fn a_computation_past_a_tiny_deadline_is_answered_with_504() {
    let limits = Limits {
        deadline: Duration::from_millis(50),
        ..permissive()
    };
    let asked = Instant::now();
    let (s, v, _) = call(router(limits), "/api/evaluate", heavy()).await;
    assert_eq!(s, StatusCode::GATEWAY_TIMEOUT, "{v}");
    assert!(
        v["error"].as_str().expect("message").contains("--deadline"),
        "{v}"
    );
    assert!(v["field"].is_null(), "{v}");
    assert!(asked.elapsed() < Duration::from_secs(10), "prompt");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_full_pool_and_queue_answer_503_with_retry_after() {
    let limits = Limits {
        workers: 1,
        queue: 0,
        deadline: Duration::from_secs(60),
        timeout: Duration::from_secs(60),
        ..permissive()
    };
    let app = router(limits);
    let first = tokio::spawn(call(app.clone(), "/api/evaluate", heavy()));
    // the first request holds the only place until it is dropped: ask until refused (its body
    // is read and admitted within milliseconds; the loop only waits for that)
    let mut refused = None;
    for _ in 0..100 {
        tokio::time::sleep(Duration::from_millis(50)).await;
        let small = json!({"curve": bezier(3), "samples": 50}).to_string();
        let (s, v, h) = call(app.clone(), "/api/evaluate", small).await;
        if s == StatusCode::SERVICE_UNAVAILABLE {
            refused = Some((v, h));
            break;
        }
        assert_eq!(s, StatusCode::OK, "{v}");
    }
    let (v, h) = refused.expect("a second request is refused while the first computes");
    assert!(!first.is_finished(), "the first request still computes");
    assert_eq!(
        h.get(header::RETRY_AFTER).and_then(|x| x.to_str().ok()),
        Some("1")
    );
    let msg = v["error"].as_str().expect("message");
    assert!(msg.contains("busy") && msg.contains("--workers"), "{msg}");
    // the health route does not queue
    let req = Request::get("/api/health")
        .body(Body::empty())
        .expect("request");
    let resp = app.clone().oneshot(req).await.expect("infallible");
    assert_eq!(resp.status(), StatusCode::OK);
    // dropping the first request cancels its computation and frees the place
    first.abort();
    let mut served = false;
    for _ in 0..100 {
        tokio::time::sleep(Duration::from_millis(50)).await;
        let small = json!({"curve": bezier(3), "samples": 50}).to_string();
        let (s, _, _) = call(app.clone(), "/api/evaluate", small).await;
        if s == StatusCode::OK {
            served = true;
            break;
        }
    }
    assert!(served, "the place of a dropped request is freed");
}

/// Every way of sending a curve is bounded before computing, and the refusal names the field
/// and the option that raises the limit.
#[tokio::test]
async fn the_budget_refuses_oversized_curves_naming_the_field() {
    let l = Limits::default();
    let many = |n: usize| -> Vec<[f64; 2]> { (0..n).map(|i| [i as f64, 0.0]).collect() };
    let cases: Vec<(&str, Value, &str, &str)> = vec![
        // an object of degree 3000 (the stall of the past), with 10,000 samples
        (
            "/api/evaluate",
            json!({"curve": bezier(3000), "samples": 10_000}),
            "curve.degree",
            "--max-degree",
        ),
        (
            "/api/project",
            json!({"curve": bezier(3000), "point": [0, 0]}),
            "curve.degree",
            "--max-degree",
        ),
        (
            "/api/measure",
            json!({"curve": bezier(3000)}),
            "curve.degree",
            "--max-degree",
        ),
        (
            "/api/export/step",
            json!({"curve": bezier(3000)}),
            "curve.degree",
            "--max-degree",
        ),
        (
            "/api/blend/deform",
            json!({"first": bezier(3), "second": bezier(3000), "continuity": 1}),
            "second.degree",
            "--max-degree",
        ),
        // points to construct from
        (
            "/api/bezier/build",
            json!({"control": many(l.max_degree + 2)}),
            "control.degree",
            "--max-degree",
        ),
        (
            "/api/bspline",
            json!({"control": many(l.max_points + 1), "degree": 3}),
            "control",
            "--max-points",
        ),
        (
            "/api/interpolate",
            json!({"points": many(100), "degree": l.max_degree + 1}),
            "degree",
            "--max-degree",
        ),
        (
            "/api/blend/corners",
            json!({"points": many(10), "continuity": 1000}),
            "continuity",
            "--max-degree",
        ),
        (
            "/api/evaluate",
            json!({"curve": bezier(3), "samples": l.max_samples + 1}),
            "samples",
            "--max-samples",
        ),
        (
            "/api/evaluate",
            json!({"curve": bezier(3), "basis_samples": l.max_samples + 1}),
            "basis_samples",
            "--max-samples",
        ),
        (
            "/api/measure",
            json!({"curve": bezier(3), "at_length": vec![0.5; l.max_points + 1]}),
            "at_length",
            "--max-points",
        ),
        // an expression: the order and the size of the space
        (
            "/api/quasi",
            json!({"expression": "sin(x)", "breakpoints": [0, 1], "order": 200}),
            "order",
            "--max-degree",
        ),
        (
            "/api/quasi",
            json!({"expression": "sin(x)",
                   "breakpoints": (0..5000).map(f64::from).collect::<Vec<_>>(),
                   "order": 60, "continuity": vec![0; 4998]}),
            "breakpoints",
            "--max-points",
        ),
    ];
    for (route, body, field, option) in cases {
        let (s, v, _) = call(router(l), route, body.to_string()).await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{route}: {v}");
        assert_eq!(v["field"], field, "{route}: {v}");
        let msg = v["error"].as_str().expect("message");
        assert!(msg.contains(option), "{route}: {msg}");
    }
    // a file of degree 3000 sent to import
    let (s, v, _) = call(router(l), "/api/import", bezier(3000).to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert_eq!(v["field"], "file.degree");
    // the degree limit raised: the work limit refuses the hostile drawing, naming the samples
    let raised = Limits {
        max_degree: 4000,
        ..l
    };
    let (s, v, _) = call(router(raised), "/api/evaluate", heavy()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    assert_eq!(v["field"], "samples");
    assert!(v["error"].as_str().expect("message").contains("--max-work"));
}

/// The library's errors are mapped to fields by their variant and key, not by their text.
#[tokio::test]
async fn library_errors_name_the_field_they_are_about() {
    let pts: Vec<[f64; 2]> = (0..8).map(|i| [f64::from(i), f64::from(i % 3)]).collect();
    let cubic = json!({"lekalo": 1, "type": "bspline_curve", "degree": 3,
                       "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1],
                       "control": [[0, 0], [1, 2], [2, 2], [3, 0], [4, 1]]});
    let cases: Vec<(&str, Value, &str)> = vec![
        // the end derivative has the wrong dimension: the end one is named, not the start one
        (
            "/api/interpolate",
            json!({"points": pts, "end": "derivatives",
                   "start_derivative": [1, 0], "end_derivative": [1, 0, 0]}),
            "end_derivative",
        ),
        (
            "/api/interpolate",
            json!({"points": pts, "end": "derivatives", "start_derivative": [1, 0, 0],
                   "end_derivative": [1, 0]}),
            "start_derivative",
        ),
        // a derivative given to an end condition that uses none
        (
            "/api/interpolate",
            json!({"points": pts, "end": "natural", "end_derivative": [1, 0]}),
            "end_derivative",
        ),
        // a knot placement that does not go with the end condition
        (
            "/api/interpolate",
            json!({"points": pts, "end": "natural", "knots": "averaged"}),
            "knots",
        ),
        // too many insertions: the count is at fault, not the knot
        (
            "/api/knot/insert",
            json!({"curve": cubic, "t": 0.25, "times": 5}),
            "times",
        ),
        ("/api/knot/insert", json!({"curve": cubic, "t": 2.0}), "t"),
        (
            "/api/knot/remove",
            json!({"curve": cubic, "t": 0.5, "times": 3}),
            "times",
        ),
        (
            "/api/measure",
            json!({"curve": cubic, "tolerance": -1}),
            "tolerance",
        ),
        (
            "/api/quasi",
            json!({"expression": "ln(x - 5)", "breakpoints": [0, 1, 2], "order": 3}),
            "expression",
        ),
        (
            "/api/bspline",
            json!({"control": [[0, 0], [1, 1], [2, 0]], "degree": 1, "weights": [1, 1]}),
            "weights",
        ),
    ];
    for (route, body, field) in cases {
        let (s, v, _) = call(router(Limits::default()), route, body.to_string()).await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{route} {body}: {v}");
        assert_eq!(v["field"], field, "{route} {body}: {v}");
    }
}

/// Whether the only worker is free again after a fit stopped at its deadline: the small fit
/// `small` is answered (200) within forty tries, each earlier try answered 504 (a stopped fit
/// frees its worker at its next cancellation check, one cone-program solve away at most).
async fn a_small_fit_is_answered(addr: std::net::SocketAddr, small: &str) {
    let mut answers = Vec::new();
    for _ in 0..40 {
        let (code, text) = raw(addr, "POST", "/api/fit", small).await;
        answers.push(code);
        if code == 200 {
            break;
        }
        assert_eq!(code, 504, "{text}");
    }
    assert_eq!(
        answers.last(),
        Some(&200),
        "the worker stayed busy: {answers:?}"
    );
}

/// A smoothing fit of `n` noisy samples `(x, y)` by generalised cross-validation: hundreds of
/// GCV scores, each a pass over the points: about 10 s at 400,000 points in a test build, of
/// which reading the request takes about 0.5 s.
fn slow_fit(n: usize) -> String {
    let points: Vec<[f64; 2]> = (0..n)
        .map(|k| {
            let x = k as f64 / n as f64;
            [x, (9.0 * x).sin() + 0.01 * ((k * 7919 % 13) as f64 - 6.0)]
        })
        .collect();
    json!({"points": points, "function": true, "smoothing": "gcv"}).to_string()
}

/// A fit past the deadline is stopped there: with one worker, the slow fit is answered with 504
/// at the deadline, `/api/health` is answered meanwhile, and the worker is soon free for a small
/// fit: within a few of the small fit's own deadlines, far less than the slow fit's remaining
/// seconds of work, which would hold the worker if the fit ignored its cancel flag (the request
/// is read and parsed before the fit can look at the flag, so the first small fit may still
/// wait).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_fit_past_the_deadline_is_stopped_and_its_worker_freed() {
    let limits = Limits {
        workers: 1,
        queue: 1,
        deadline: Duration::from_millis(500),
        timeout: Duration::from_secs(60),
        max_points: 1_000_000,
        body_bytes: 64 << 20,
        ..permissive()
    };
    let addr = serving(limits).await;
    let body = slow_fit(400_000);
    let started = Instant::now();
    let slow = tokio::spawn(async move { raw(addr, "POST", "/api/fit", &body).await });
    tokio::time::sleep(Duration::from_millis(100)).await;
    let (code, text) = raw(addr, "GET", "/api/health", "").await;
    assert_eq!((code, text.as_str()), (200, "ok"));
    assert!(
        !slow.is_finished(),
        "health was answered while the fit computes"
    );
    let (code, text) = slow.await.expect("task");
    assert_eq!(code, 504, "{text}");
    let v: Value = serde_json::from_str(&text).expect("JSON error");
    let msg = v["error"].as_str().expect("message");
    assert!(msg.contains("deadline of 0.5 s"), "{msg}");
    assert!(
        started.elapsed() < Duration::from_secs(15),
        "answered after {:?}",
        started.elapsed()
    );
    // the only worker stopped the slow fit: a small one is computed
    a_small_fit_is_answered(addr, &slow_fit(50)).await;
    let (code, _) = raw(addr, "GET", "/api/health", "").await;
    assert_eq!(code, 200);
}

/// `GET /api/progress`: the answer of one loopback request, as JSON.
async fn progress_of(addr: std::net::SocketAddr, job: &str) -> Value {
    let (code, text) = raw(addr, "GET", &format!("/api/progress?job={job}"), "").await;
    assert_eq!(code, 200, "{text}");
    serde_json::from_str(&text).expect("JSON")
}

/// A heavy request that carries a job id reports its progress while it runs: the share done
/// grows, the time left is estimated, and once the request has ended (at the deadline) the job
/// is no longer running. A job id the server cannot keep is refused, naming the header's rule.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_computation_with_a_job_id_reports_its_progress_until_it_ends() {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let limits = Limits {
        workers: 1,
        deadline: Duration::from_secs(3),
        timeout: Duration::from_secs(30),
        ..permissive()
    };
    let addr = serving(limits).await;
    let body = heavy();
    let request = tokio::spawn(async move {
        let mut s = tokio::net::TcpStream::connect(addr).await.expect("connect");
        let req = format!(
            "POST /api/evaluate HTTP/1.1\r\nhost: x\r\nconnection: close\r\nx-lekalo-job: heavy-1\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n{body}",
            body.len()
        );
        s.write_all(req.as_bytes()).await.expect("write");
        let mut answer = String::new();
        s.read_to_string(&mut answer).await.expect("read");
        answer
    });
    let mut reports = Vec::new();
    for _ in 0..40 {
        tokio::time::sleep(Duration::from_millis(50)).await;
        let p = progress_of(addr, "heavy-1").await;
        if p["running"] == true && p["done"].as_u64() > Some(0) {
            reports.push(p);
            if reports.len() == 2 {
                break;
            }
            tokio::time::sleep(Duration::from_millis(300)).await;
        }
    }
    assert_eq!(reports.len(), 2, "two reports while it runs: {reports:?}");
    let done = |p: &Value| p["done"].as_u64().expect("done");
    let total = reports[0]["total"].as_u64().expect("total");
    assert!(
        total >= done(&reports[1]) && done(&reports[1]) > done(&reports[0]),
        "{reports:?}"
    );
    assert!(
        reports[1]["remaining_s"].as_f64().is_some_and(|r| r > 0.0),
        "{reports:?}"
    );
    assert!(
        reports[1]["elapsed_s"].as_f64() > reports[0]["elapsed_s"].as_f64(),
        "{reports:?}"
    );
    let answer = request.await.expect("task");
    assert!(answer.starts_with("HTTP/1.1 504"), "{answer}");
    let after = progress_of(addr, "heavy-1").await;
    assert_eq!(after["running"], false, "{after}");
    // an id the server cannot keep
    let (code, text) = raw(addr, "GET", "/api/progress?job=a%20b", "").await;
    assert_eq!(code, 400, "{text}");
    assert!(text.contains("job id"), "{text}");
}

/// A shape-constrained fit past the deadline is stopped there as the others are: its cone
/// program (GCV, working set, polish) checks the job's cancel flag, so that with one worker a
/// small constrained fit is computed soon after the slow one's 504 (it ran on for minutes,
/// holding the worker, when the constrained fit took no hook).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_shape_constrained_fit_past_the_deadline_frees_its_worker() {
    let limits = Limits {
        workers: 1,
        queue: 1,
        deadline: Duration::from_millis(500),
        timeout: Duration::from_secs(60),
        ..permissive()
    };
    let addr = serving(limits).await;
    let constrained = |n: usize| {
        // a rising wave with dips, kept increasing: the constraint is active on many spans
        let points: Vec<[f64; 2]> = (0..n)
            .map(|k| {
                let x = 10.0 * k as f64 / n as f64;
                [
                    x,
                    x + (5.0 * x).sin() + 0.1 * ((k * 7919 % 13) as f64 - 6.0),
                ]
            })
            .collect();
        json!({"points": points, "smoothing": "gcv", "increasing": true}).to_string()
    };
    // 8,000 points: 1.2 s of CPU in a release build (3,000 took 0.57 s), several times that in
    // the test build, so the 500 ms deadline falls inside the fit, never after it
    let (code, text) = raw(addr, "POST", "/api/fit", &constrained(8000)).await;
    assert_eq!(code, 504, "{text}");
    a_small_fit_is_answered(addr, &constrained(40)).await;
}
