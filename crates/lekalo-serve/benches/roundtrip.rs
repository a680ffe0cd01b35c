//! Round-trip latency of the editor's requests on loopback, two workloads:
//!
//! - the edit of a drag: `POST /api/bspline` with the 200 control points of a cubic B-spline,
//!   one of them moved a little each request, answered with 400 samples and the basis panel
//!   (300 samples per function), as the editor sends on every pointer move (about 60 kB of
//!   JSON);
//! - the heaviest frequent request: interpolate 100 points, answer 1,000 samples of the curve
//!   and the basis panel with the functions active at a parameter (about 110 kB).
//!
//! The client is the smallest HTTP/1.1 client on tokio's sockets: keep-alive connections, a
//! request written in one piece, the answer read by its `Content-Length` (axum answers JSON with
//! one). It is written out here rather than taken from hyper's client because the benchmark
//! needs nothing else, and enabling hyper's client feature would rebuild hyper and axum for
//! every test build of the workspace; its cost per request is a few microseconds, so it does not
//! hide the server's. The server is `lekalo serve`
//! at `LEKALO_URL` when that is set (`bench/serve/run.sh` starts the release binary), otherwise
//! the same router in this process on a free port with the server's two worker threads.
//! Printed for each workload: p50/p90/p99/max of the round trip on one connection, the same
//! with `CLIENTS` connections at once, the handler alone (no socket), and the load average.
//!
//! Usage: `cargo bench -p lekalo-serve --bench roundtrip [-- N]` (N requests, default 2000).

use std::time::{Duration, Instant};

use axum::body::Body;
use axum::http::Request;
use http_body_util::BodyExt;
use lekalo_serve::{router, Limits};
use tokio::io::{AsyncBufReadExt, AsyncReadExt, AsyncWriteExt, BufReader};
use tower::ServiceExt;

/// Connections of the concurrent run.
const CLIENTS: usize = 4;

/// Distinct request bodies of a workload, sent in turn.
const BODIES: usize = 97;

/// One kind of request: its route, its bodies and what its first answer must hold.
struct Workload {
    name: &'static str,
    path: &'static str,
    bodies: Vec<String>,
    check: fn(&serde_json::Value),
}

fn k_f64(k: usize) -> f64 {
    f64::from(u32::try_from(k).unwrap_or(0))
}

/// The drag: point 100 of a 200-point cubic B-spline (the curve of `bench/serve/fps.mjs`)
/// moved along a small loop, with the editor's view options.
fn drag() -> Workload {
    let bodies = (0..BODIES)
        .map(|i| {
            let mut control: Vec<[f64; 2]> = (0..200)
                .map(|k| {
                    let x = k_f64(k);
                    [0.5 + 9.0 * x / 199.0, 3.0 + 2.0 * (x / 7.0).sin()]
                })
                .collect();
            let s = k_f64(i);
            control[100][0] += 0.5 * (s / 20.0).sin();
            control[100][1] += 0.4 * (s / 15.0).cos();
            serde_json::json!({"control": control, "degree": 3, "samples": 400,
                "comb": false, "basis_samples": 300})
            .to_string()
        })
        .collect();
    Workload {
        name: "drag edit (bspline, 200 control points, 400 samples + basis panel)",
        path: "/api/bspline",
        bodies,
        check: |v| {
            assert_eq!(
                v["points"].as_array().map(Vec::len),
                Some(400),
                "400 samples"
            );
            assert_eq!(v["control"].as_array().map(Vec::len), Some(200), "control");
            assert!(v["basis"]["functions"].is_array(), "the basis panel");
        },
    }
}

/// Interpolation of 100 points with 1,000 samples and the basis panel.
fn interpolate() -> Workload {
    let points: Vec<[f64; 2]> = (0..100)
        .map(|k| {
            let x = k_f64(k) / 10.0;
            [x, x.sin() + 0.1 * (10.0 * x).cos()]
        })
        .collect();
    let bodies = (0..BODIES)
        .map(|i| {
            serde_json::json!({"points": points, "degree": 3, "parametrization": "centripetal",
                "samples": 1000, "basis_samples": 300, "at": k_f64(i) / 97.0})
            .to_string()
        })
        .collect();
    Workload {
        name: "interpolate 100 points (1,000 samples + basis panel)",
        path: "/api/interpolate",
        bodies,
        check: |v| {
            assert_eq!(
                v["points"].as_array().map(Vec::len),
                Some(1000),
                "1,000 samples"
            );
            assert!(v["basis"]["functions"].is_array(), "the basis panel");
        },
    }
}

fn quantiles(what: &str, mut times: Vec<Duration>) {
    times.sort();
    // the sample at rank ⌊n·per_mille/1000⌋ (the largest for 1000)
    let q = |per_mille: usize| {
        let i = (times.len() * per_mille / 1000).min(times.len() - 1);
        times[i].as_secs_f64() * 1e3
    };
    println!(
        "{what}: n={} p50={:.3} ms p90={:.3} ms p99={:.3} ms max={:.3} ms",
        times.len(),
        q(500),
        q(900),
        q(990),
        q(1000)
    );
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

/// Reads one answer: the status line, the headers up to the empty line, then
/// `Content-Length` bytes of body.
async fn read_answer(
    r: &mut BufReader<tokio::net::TcpStream>,
    line: &mut String,
    body: &mut Vec<u8>,
) -> u16 {
    line.clear();
    r.read_line(line).await.expect("status line");
    let status = line
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .expect("status");
    let mut length = None;
    loop {
        line.clear();
        r.read_line(line).await.expect("header");
        let h = line.trim_end();
        if h.is_empty() {
            break;
        }
        if let Some((k, v)) = h.split_once(':') {
            if k.eq_ignore_ascii_case("content-length") {
                length = v.trim().parse::<usize>().ok();
            }
        }
    }
    body.resize(length.expect("the answer has a Content-Length"), 0);
    r.read_exact(body).await.expect("body");
    status
}

/// One keep-alive connection: `n` requests of `w` one after the other, each timed from the
/// first byte sent to the last byte of the answer read; the first answer's content is checked.
async fn connection(
    addr: String,
    w: std::sync::Arc<Workload>,
    n: usize,
    offset: usize,
) -> Vec<Duration> {
    let stream = tokio::net::TcpStream::connect(&addr)
        .await
        .expect("connect");
    stream.set_nodelay(true).expect("nodelay");
    let mut r = BufReader::with_capacity(1 << 18, stream);
    let requests: Vec<Vec<u8>> = w
        .bodies
        .iter()
        .map(|b| {
            format!(
                "POST {} HTTP/1.1\r\nhost: {addr}\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n{b}",
                w.path,
                b.len()
            )
            .into_bytes()
        })
        .collect();
    let (mut line, mut answer) = (String::new(), Vec::new());
    let mut times = Vec::with_capacity(n);
    for i in 0..n {
        let t0 = Instant::now();
        r.get_mut()
            .write_all(&requests[(i + offset) % requests.len()])
            .await
            .expect("send");
        let status = read_answer(&mut r, &mut line, &mut answer).await;
        times.push(t0.elapsed());
        assert_eq!(status, 200, "{}", String::from_utf8_lossy(&answer));
        if i == 0 {
            (w.check)(&serde_json::from_slice(&answer).expect("json"));
        }
    }
    times
}

fn main() {
    let n: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(2000);
    let client = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .expect("runtime");
    // the server: `LEKALO_URL`, or the router here with the server's runtime
    let (addr, _server) = match std::env::var("LEKALO_URL") {
        Ok(url) => {
            let hostport = url
                .trim_start_matches("http://")
                .trim_end_matches('/')
                .to_string();
            (hostport, None)
        }
        Err(_) => {
            let rt = tokio::runtime::Builder::new_multi_thread()
                .worker_threads(2)
                .enable_all()
                .build()
                .expect("server runtime");
            let listener = rt
                .block_on(tokio::net::TcpListener::bind("127.0.0.1:0"))
                .expect("bind");
            let addr = listener.local_addr().expect("address").to_string();
            rt.spawn(async move { axum::serve(listener, router(Limits::default())).await });
            (addr, Some(rt))
        }
    };
    println!("server {addr}; load average before: {}", load_average());
    for w in [drag(), interpolate()] {
        let w = std::sync::Arc::new(w);
        let len = w.bodies.first().map_or(0, String::len);
        println!("{} ({len} bytes a request):", w.name);
        client.block_on(async {
            connection(addr.clone(), w.clone(), 200, 0).await; // warm-up
            quantiles(
                "  round trip, one keep-alive connection",
                connection(addr.clone(), w.clone(), n, 0).await,
            );
            let tasks: Vec<_> = (0..CLIENTS)
                .map(|c| tokio::spawn(connection(addr.clone(), w.clone(), n / CLIENTS, c * 13)))
                .collect();
            let mut all = Vec::new();
            for t in tasks {
                all.extend(t.await.expect("client"));
            }
            quantiles(&format!("  round trip, {CLIENTS} connections at once"), all);
            // the handler alone: routing, parsing, the library's construction, drawing, JSON
            let app = router(Limits::default());
            let mut times = Vec::with_capacity(n);
            for i in 0..n {
                let req = Request::post(w.path)
                    .body(Body::from(w.bodies[i % w.bodies.len()].clone()))
                    .expect("request");
                let t0 = Instant::now();
                let resp = app.clone().oneshot(req).await.expect("answer");
                let _ = resp.into_body().collect().await.expect("body");
                times.push(t0.elapsed());
            }
            quantiles("  handler alone (no socket)", times);
        });
        println!("load average after: {}", load_average());
    }
}
