//! Hostile requests at the transport level, against the server as `lekalo serve` runs it
//! ([`lekalo_serve::listen::serve`], [`lekalo_serve::transport`]): compressed bodies (good ones
//! read, bombs refused after `--max-body` bytes of output, unknown encodings refused), bodies
//! that never end or trickle in, odd paths and methods, HTTP/1.0 and pipelined requests. Every
//! refusal is the API's JSON error, and `/api/health` answers throughout.

#![allow(clippy::missing_assert_message)] // assert_eq! prints both sides

use std::io::Write;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use lekalo_serve::Limits;
use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use crate::serving;

/// Sends `bytes` on a fresh connection and reads the whole answer (the server closes it).
async fn exchange(addr: SocketAddr, bytes: &[u8]) -> String {
    let mut s = TcpStream::connect(addr).await.expect("connect");
    // the server may answer and close before it has read everything
    let _ = s.write_all(bytes).await;
    let mut answer = Vec::new();
    let _ = tokio::time::timeout(Duration::from_secs(30), s.read_to_end(&mut answer)).await;
    String::from_utf8_lossy(&answer).into_owned()
}

/// A POST of `body` to `route` with the extra header lines `headers` (each ending in CRLF).
fn post(route: &str, headers: &str, body: &[u8]) -> Vec<u8> {
    let mut req = format!(
        "POST {route} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: \
         application/json\r\ncontent-length: {}\r\n{headers}\r\n",
        body.len()
    )
    .into_bytes();
    req.extend_from_slice(body);
    req
}

/// The status code and the JSON body of an answer.
fn status_and_json(answer: &str) -> (u16, Value) {
    let code = answer
        .get(9..12)
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("no status line: {answer:.200}"));
    let body = answer.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    let json = serde_json::from_str(body)
        .unwrap_or_else(|e| panic!("answer {code} is not JSON ({e}): {answer:.400}"));
    (code, json)
}

async fn health(addr: SocketAddr) {
    let answer = exchange(
        addr,
        b"GET /api/health HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n",
    )
    .await;
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
}

const CURVE: &str = r#"{"curve": {"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1]]}, "samples": 8}"#;

/// `data` in each encoding the server reads, with the encoding's name.
fn encoded(data: &[u8]) -> [(&'static str, Vec<u8>); 3] {
    [
        ("gzip", gzip(data)),
        ("deflate", deflate(data)),
        ("br", brotli(data)),
    ]
}

/// The answer to `body` posted to `/api/evaluate` with `content-encoding: name`.
async fn evaluate_encoded(addr: SocketAddr, name: &str, body: &[u8]) -> String {
    exchange(
        addr,
        &post(
            "/api/evaluate",
            &format!("content-encoding: {name}\r\n"),
            body,
        ),
    )
    .await
}

fn gzip(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    e.write_all(data).expect("gzip");
    e.finish().expect("gzip")
}

fn deflate(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    e.write_all(data).expect("deflate");
    e.finish().expect("deflate")
}

fn brotli(data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut e = brotli::CompressorWriter::new(&mut out, 4096, 11, 22);
        e.write_all(data).expect("br");
    }
    out
}

/// A request body compressed with gzip, deflate or br is read as the JSON it inflates to, and
/// answered as the same body sent plainly.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn compressed_bodies_are_read() {
    let addr = serving(Limits::default()).await;
    let plain = exchange(addr, &post("/api/evaluate", "", CURVE.as_bytes())).await;
    let (code, want) = status_and_json(&plain);
    assert_eq!(code, 200, "{plain}");
    for (name, body) in encoded(CURVE.as_bytes()) {
        let answer = evaluate_encoded(addr, name, &body).await;
        let (code, got) = status_and_json(&answer);
        assert_eq!((code, &got), (200, &want), "{name}");
    }
}

/// Decompression bombs: bodies of about 260 KB (gzip, deflate; far less with br) that inflate
/// to 256 MiB of JSON-looking text are refused with 413 once `--max-body` bytes are out, quickly,
/// and the server answers health meanwhile and after.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn decompression_bombs_are_refused_at_the_body_limit() {
    let addr = serving(Limits::default()).await;
    let mut inflated = b"{\"points\": [".to_vec();
    inflated.resize(256 << 20, b' ');
    for (name, body) in encoded(&inflated) {
        assert!(body.len() < 300_000, "{name}: {} bytes", body.len());
        let start = Instant::now();
        let answer = evaluate_encoded(addr, name, &body).await;
        let (code, json) = status_and_json(&answer);
        assert_eq!(code, 413, "{name}: {answer:.300}");
        let message = json["error"].as_str().expect("message");
        assert!(
            message.contains("decompressed") && message.contains("--max-body"),
            "{message}"
        );
        assert!(
            start.elapsed() < Duration::from_secs(5),
            "{name}: {:?}",
            start.elapsed()
        );
        health(addr).await;
    }
}

/// A body in an encoding the server does not read, or a corrupt compressed body: 415 naming
/// the encoding and the ones read, or 400; never the body taken as it is.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn unknown_encodings_and_corrupt_streams_are_refused() {
    let addr = serving(Limits::default()).await;
    for encoding in ["zstd", "compress", "gzip, gzip", "x-bomb"] {
        let answer = exchange(
            addr,
            &post(
                "/api/evaluate",
                &format!("content-encoding: {encoding}\r\n"),
                CURVE.as_bytes(),
            ),
        )
        .await;
        let (code, json) = status_and_json(&answer);
        assert_eq!(code, 415, "{encoding}: {answer}");
        let message = json["error"].as_str().expect("message");
        assert!(
            message.contains(&format!("\"{encoding}\"")) && message.contains("gzip, deflate, br"),
            "{message}"
        );
        assert!(
            answer.to_ascii_lowercase().contains("accept-encoding:"),
            "{answer}"
        );
    }
    // a gzip header followed by garbage, and plain JSON labelled gzip
    let mut broken = gzip(CURVE.as_bytes());
    broken.truncate(12);
    broken.extend_from_slice(b"\xff\xfe not deflate data at all");
    for body in [broken, CURVE.as_bytes().to_vec()] {
        let answer = exchange(
            addr,
            &post("/api/evaluate", "content-encoding: gzip\r\n", &body),
        )
        .await;
        let (code, json) = status_and_json(&answer);
        assert_eq!(code, 400, "{answer}");
        assert!(
            json["error"]
                .as_str()
                .is_some_and(|m| m.contains("could not be read")),
            "{json}"
        );
    }
    health(addr).await;
}

/// The body's `Content-Type`: JSON, `+json` types, plain text (a browser's `fetch` of a string)
/// and no header at all are read as JSON; a form (`curl -d`'s default), a multipart upload,
/// XML, an image, or a charset other than UTF-8 is refused with 415 and the API's JSON error
/// naming the header and what to send, whatever the body; `/api/health` answers throughout.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bodies_that_are_not_json_or_text_are_refused_by_their_content_type() {
    let addr = serving(Limits::default()).await;
    let raw = |content_type: Option<&str>, body: &str| {
        let header = content_type.map_or(String::new(), |t| format!("content-type: {t}\r\n"));
        format!(
            "POST /api/evaluate HTTP/1.1\r\nhost: x\r\nconnection: close\r\n{header}content-length: {}\r\n\r\n{body}",
            body.len()
        )
    };
    for accepted in [
        None,
        Some("application/json"),
        Some("Application/JSON; charset=UTF-8"),
        Some("text/plain;charset=utf-8"),
        Some("application/merge-patch+json"),
    ] {
        let answer = exchange(addr, raw(accepted, CURVE).as_bytes()).await;
        assert_eq!(status_and_json(&answer).0, 200, "{accepted:?}: {answer}");
    }
    for refused in [
        "application/x-www-form-urlencoded",
        "multipart/form-data; boundary=XyZ",
        "application/xml",
        "image/png",
        "application/octet-stream",
        "",
        "application/json; charset=utf-16",
        "text/plain; charset=latin1",
    ] {
        let answer = exchange(addr, raw(Some(refused), CURVE).as_bytes()).await;
        let (code, json) = status_and_json(&answer);
        assert_eq!(code, 415, "{refused}: {answer}");
        let message = json["error"].as_str().expect("message");
        assert!(
            message.contains(&format!("Content-Type \"{refused}\""))
                && (message.contains("application/json") || message.contains("UTF-8")),
            "{message}"
        );
        assert_eq!(json["field"], Value::Null);
    }
    // a form's body is refused before it is read: a declared length far beyond what is sent
    let answer = exchange(
        addr,
        b"POST /api/evaluate HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: multipart/form-data; boundary=b\r\ncontent-length: 1000000\r\n\r\n--b\r\n",
    )
    .await;
    assert_eq!(status_and_json(&answer).0, 415, "{answer}");
    health(addr).await;
}

/// A chunked body that never ends, and one that trickles in a byte every 200 ms: both are cut
/// off at `--timeout` with 408 and the JSON error naming it, and health answers meanwhile.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn endless_and_trickling_bodies_end_at_the_timeout() {
    let limits = Limits {
        timeout: Duration::from_secs(2),
        ..Limits::default()
    };
    let addr = serving(limits).await;
    let head = "POST /api/evaluate HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n\
                transfer-encoding: chunked\r\n\r\n";
    let mut endless = TcpStream::connect(addr).await.expect("connect");
    endless
        .write_all(format!("{head}1\r\n{{\r\n").as_bytes())
        .await
        .expect("write");
    let trickle = tokio::spawn(async move {
        let mut s = TcpStream::connect(addr).await.expect("connect");
        s.write_all(head.as_bytes()).await.expect("write");
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(6) {
            if s.write_all(b"1\r\n \r\n").await.is_err() {
                break;
            }
            tokio::time::sleep(Duration::from_millis(200)).await;
        }
        let mut answer = Vec::new();
        let _ = tokio::time::timeout(Duration::from_secs(10), s.read_to_end(&mut answer)).await;
        (
            String::from_utf8_lossy(&answer).into_owned(),
            start.elapsed(),
        )
    });
    tokio::time::sleep(Duration::from_millis(300)).await;
    health(addr).await;
    let start = Instant::now();
    let mut answer = Vec::new();
    let _ = tokio::time::timeout(Duration::from_secs(10), endless.read_to_end(&mut answer)).await;
    let answer = String::from_utf8_lossy(&answer);
    assert!(
        start.elapsed() < Duration::from_secs(5),
        "{:?}",
        start.elapsed()
    );
    let (code, json) = status_and_json(&answer);
    assert_eq!(code, 408, "{answer}");
    assert!(
        json["error"]
            .as_str()
            .is_some_and(|m| m.contains("--timeout")),
        "{json}"
    );
    let (answer, _) = trickle.await.expect("trickle");
    let (code, _) = status_and_json(&answer);
    assert_eq!(code, 408, "{answer}");
    health(addr).await;
}

/// A body declared larger than `--max-body`: 413 with the JSON error, before it is sent.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_declared_length_above_the_limit_is_refused_in_json() {
    let addr = serving(Limits::default()).await;
    let answer = exchange(
        addr,
        b"POST /api/evaluate HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n\
          content-length: 10000000000\r\n\r\n{",
    )
    .await;
    let (code, json) = status_and_json(&answer);
    assert_eq!(code, 413, "{answer}");
    assert!(
        json["error"]
            .as_str()
            .is_some_and(|m| m.contains("--max-body")),
        "{json}"
    );
}

/// Paths that climb (`..`, `%2e%2e`), carry a NUL, or are long; methods the route does not
/// take; a query string of 60 KiB: 404 or 405, or 431 for a head above 64 KiB, never a file
/// of the disk; health answers after each.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn odd_paths_and_methods_are_refused() {
    let addr = serving(Limits::default()).await;
    let long = format!("/{}", "a/".repeat(20_000));
    let query = format!("/api/health?{}", "q=1&".repeat(15_000));
    for path in [
        "/../../etc/passwd",
        "/%2e%2e/%2e%2e/etc/passwd",
        "/js/..%2f..%2fCargo.toml",
        "/api/health%00",
        "/app.css%00.json",
        "//api/health",
        long.as_str(),
    ] {
        let answer = exchange(
            addr,
            format!("GET {path} HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n").as_bytes(),
        )
        .await;
        let code = &answer[9..12];
        assert!(code == "404" || code == "400", "{path:.60}: {answer:.300}");
        assert!(
            !answer.contains("[package]") && !answer.contains("root:"),
            "{answer:.300}"
        );
        if code == "404" {
            let (_, json) = status_and_json(&answer);
            assert!(json["error"].is_string(), "{json}");
        }
    }
    // a long query string on a route that takes none is ignored
    let answer = exchange(
        addr,
        format!("GET {query} HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n").as_bytes(),
    )
    .await;
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer:.300}");
    for method in ["PUT", "DELETE", "PATCH"] {
        let answer = exchange(
            addr,
            format!("{method} /api/evaluate HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-length: 0\r\n\r\n")
                .as_bytes(),
        )
        .await;
        assert!(answer.starts_with("HTTP/1.1 405"), "{method}: {answer}");
    }
    health(addr).await;
}

/// HTTP/1.0 requests, with and without a body, and pipelined requests on one connection: each
/// answered, in order.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn http_1_0_and_pipelined_requests_are_answered_in_order() {
    let addr = serving(Limits::default()).await;
    let answer = exchange(addr, b"GET /api/health HTTP/1.0\r\n\r\n").await;
    assert!(answer.starts_with("HTTP/1.0 200"), "{answer}");
    assert!(answer.ends_with("ok"), "{answer}");
    let mut req = format!(
        "POST /api/evaluate HTTP/1.0\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n",
        CURVE.len()
    )
    .into_bytes();
    req.extend_from_slice(CURVE.as_bytes());
    let answer = exchange(addr, &req).await;
    let (code, json) = status_and_json(&answer);
    assert_eq!(code, 200, "{answer:.300}");
    assert!(json["curve"].is_object(), "{json}");
    // two requests at once on one connection, the second closing it
    let mut pipelined = Vec::new();
    pipelined.extend_from_slice(b"GET /api/health HTTP/1.1\r\nhost: x\r\n\r\n");
    pipelined.extend_from_slice(&post("/api/evaluate", "", CURVE.as_bytes())[..]);
    let answers = exchange(addr, &pipelined).await;
    // the evaluate request carries `connection: close`; nothing after it is answered
    let statuses: Vec<&str> = answers
        .match_indices("HTTP/1.1 ")
        .map(|(i, _)| &answers[i + 9..i + 12])
        .collect();
    assert_eq!(statuses, ["200", "200"], "{answers:.600}");
    assert!(answers.contains("\r\n\r\nok"), "{answers:.300}");
}
