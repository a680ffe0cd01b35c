//! Many connections at once against the server as `lekalo serve` runs it
//! ([`lekalo_serve::listen::serve`]): connections that never finish a request's head are closed
//! after the timeout; beyond `--max-connections` the health route and the page still answer
//! and computing routes are refused with 503; bodies sent slowly by more clients than the pool
//! admits are refused at once, not read.

#![allow(clippy::missing_assert_message)] // assert_eq! prints both sides

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use lekalo_serve::Limits;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

use crate::serving;

/// One request on a fresh connection: the whole answer (status line, headers, body).
async fn request(addr: SocketAddr, method: &str, route: &str, body: &str) -> String {
    let mut s = TcpStream::connect(addr).await.expect("connect");
    let req = format!(
        "{method} {route} HTTP/1.1\r\nhost: x\r\nconnection: close\r\ncontent-type: \
         application/json\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    );
    s.write_all(req.as_bytes()).await.expect("write");
    let mut answer = String::new();
    tokio::time::timeout(Duration::from_secs(20), s.read_to_string(&mut answer))
        .await
        .expect("answered in time")
        .expect("read");
    answer
}

/// `n` connections that send the first bytes of a request's head and stop there.
async fn stalled_heads(addr: SocketAddr, n: usize) -> Vec<TcpStream> {
    let mut held = Vec::with_capacity(n);
    for _ in 0..n {
        let mut s = TcpStream::connect(addr).await.expect("connect");
        s.write_all(b"GET /api/health HTTP/1.1\r\nhost: x\r\nx-slow: ")
            .await
            .expect("write");
        held.push(s);
    }
    held
}

const CURVE: &str = r#"{"curve": {"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1]]}, "samples": 8}"#;

/// Twice as many stalled connections as the server serves: health, the page and a computation
/// are answered on a new connection meanwhile (the computation refused with 503 and
/// `Retry-After` while the connections are all taken), and the stalled connections are closed
/// once the head timeout has passed, after which computations are served again.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn stalled_connections_beyond_the_limit_leave_health_and_the_page_answering() {
    let limits = Limits {
        connections: 64,
        timeout: Duration::from_secs(2),
        deadline: Duration::from_secs(1),
        ..Limits::default()
    };
    let addr = serving(limits).await;
    let mut held = stalled_heads(addr, 128).await;
    let health = request(addr, "GET", "/api/health", "").await;
    assert!(health.starts_with("HTTP/1.1 200"), "{health}");
    assert!(health.ends_with("ok"), "{health}");
    let page = request(addr, "GET", "/", "").await;
    assert!(page.starts_with("HTTP/1.1 200"), "{}", &page[..40]);
    let busy = request(addr, "POST", "/api/evaluate", CURVE).await;
    assert!(busy.starts_with("HTTP/1.1 503"), "{busy}");
    assert!(
        busy.to_ascii_lowercase().contains("retry-after: 1"),
        "{busy}"
    );
    assert!(busy.contains("--max-connections"), "{busy}");
    // the stalled connections are closed after the head timeout: each reads to its end
    let start = Instant::now();
    for s in &mut held {
        let mut rest = Vec::new();
        tokio::time::timeout(Duration::from_secs(20), s.read_to_end(&mut rest))
            .await
            .expect("closed by the server")
            .ok();
    }
    assert!(start.elapsed() < Duration::from_secs(20));
    drop(held);
    // and the places are free again
    let mut answer = String::new();
    for _ in 0..50 {
        answer = request(addr, "POST", "/api/evaluate", CURVE).await;
        if answer.starts_with("HTTP/1.1 200") {
            break;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
}

/// A request head above the buffer is refused (431), not buffered without end.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_huge_request_head_is_refused() {
    let addr = serving(Limits::default()).await;
    let mut s = TcpStream::connect(addr).await.expect("connect");
    let junk = "a".repeat(1 << 20);
    let req = format!("GET /api/health HTTP/1.1\r\nhost: x\r\nx-junk: {junk}\r\n\r\n");
    // the server may close before reading it all
    let _ = s.write_all(req.as_bytes()).await;
    let mut answer = Vec::new();
    let _ = tokio::time::timeout(Duration::from_secs(20), s.read_to_end(&mut answer)).await;
    let answer = String::from_utf8_lossy(&answer);
    assert!(answer.starts_with("HTTP/1.1 431"), "{answer}");
}

/// More clients than the pool admits send their bodies slowly: those beyond `workers + queue`
/// are answered 503 at once, before their bodies are read, and health answers throughout.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn slow_bodies_beyond_the_pool_are_refused_before_they_are_read() {
    let limits = Limits {
        workers: 1,
        queue: 1,
        timeout: Duration::from_secs(5),
        ..Limits::default()
    };
    let addr = serving(limits).await;
    // two admitted requests whose bodies never come
    let mut slow = Vec::new();
    for _ in 0..2 {
        let mut s = TcpStream::connect(addr).await.expect("connect");
        s.write_all(
            b"POST /api/evaluate HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n\
              content-length: 1000\r\n\r\n{",
        )
        .await
        .expect("write");
        slow.push(s);
    }
    tokio::time::sleep(Duration::from_millis(300)).await;
    let start = Instant::now();
    let busy = request(addr, "POST", "/api/evaluate", CURVE).await;
    assert!(busy.starts_with("HTTP/1.1 503"), "{busy}");
    assert!(
        start.elapsed() < Duration::from_secs(3),
        "{:?}",
        start.elapsed()
    );
    let health = request(addr, "GET", "/api/health", "").await;
    assert!(health.starts_with("HTTP/1.1 200"), "{health}");
    // the slow ones end with 408 at the request timeout, and free their places
    for s in &mut slow {
        let mut rest = String::new();
        tokio::time::timeout(Duration::from_secs(20), s.read_to_string(&mut rest))
            .await
            .expect("ended")
            .ok();
        assert!(rest.starts_with("HTTP/1.1 408"), "{rest}");
    }
    let ok = request(addr, "POST", "/api/evaluate", CURVE).await;
    assert!(ok.starts_with("HTTP/1.1 200"), "{ok}");
}
