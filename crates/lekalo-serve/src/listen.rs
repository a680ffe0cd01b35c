//! Connections: how `lekalo serve` accepts them and bounds them (`docs/serve.md`, "Security
//! and limits"). hyper's HTTP/1 server is driven here directly, because `axum::serve` sets no
//! timer, so no header timeout: a client that opens connections and never finishes a request's
//! head would keep each of them, and its memory and file descriptor, for ever.
//!
//! - A connection has [`Limits::timeout`] to send each request's head, and hyper's read buffer
//!   stops at [`MAX_HEAD_BYTES`]: a connection that sends nothing, sends its head a byte at a
//!   time, or stays idle that long between two requests is closed; a head larger than the
//!   buffer is answered with 431. The body's time is the request's (`--timeout`, 408) and its
//!   size `--max-body` (413); a computing request's body is read only once the pool admits it
//!   ([`crate::pool`]).
//! - At most [`Limits::connections`] connections are served by the whole application at once.
//!   A connection beyond them is served by the light routes alone (the pages, `/api/health`,
//!   `/api/openapi.json`, `/api/progress`; every computing route answers 503 with
//!   `Retry-After`), with [`OVERFLOW_HEAD_TIMEOUT`] for its head and no keep-alive, and at most
//!   [`OVERFLOW_CONNECTIONS`] of those at once; a connection past them too is closed at once.
//!   So a client holding thousands of connections open neither stops the health route and the
//!   page from answering nor makes the server's memory grow beyond the connections' buffers.
//! - Ctrl-C stops accepting; the connections finish their requests and close.

use std::convert::Infallible;
use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use axum::http::{header, Method, StatusCode};
use axum::response::IntoResponse;
use axum::{Json, Router};
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use serde_json::json;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{watch, OwnedSemaphorePermit, Semaphore};

use crate::pool::{Pool, RETRY_AFTER_SECONDS};
use crate::Limits;

/// The largest request head (request line and headers) a connection may send, in bytes: hyper's
/// read buffer of one connection stops there (431 above it). hyper's smallest allowed value is
/// 8 KiB; an editor request's head is a few hundred bytes.
pub const MAX_HEAD_BYTES: usize = 64 << 10;

/// Connections served by the light routes alone once [`Limits::connections`] are open.
pub const OVERFLOW_CONNECTIONS: usize = 1024;

/// The time an overflow connection has to send its request's head.
pub const OVERFLOW_HEAD_TIMEOUT: Duration = Duration::from_secs(1);

/// Serves the application with `limits` on `listener` until `shutdown` completes (module docs).
///
/// # Errors
/// None in practice: a failed `accept` (too many open files, a connection reset before it was
/// accepted) is waited out and accepting goes on.
pub async fn serve(
    listener: TcpListener,
    limits: Limits,
    shutdown: impl Future<Output = ()> + Send,
) -> std::io::Result<()> {
    let pool = Arc::new(Pool::new(limits));
    let full = crate::app(pool.clone(), crate::routes());
    let light = crate::app(pool, light_routes());
    let served = Arc::new(Semaphore::new(limits.connections.max(1)));
    let overflow = Arc::new(Semaphore::new(OVERFLOW_CONNECTIONS));
    let (stop, stopped) = watch::channel(false);
    let mut shutdown = std::pin::pin!(shutdown);
    loop {
        let stream = tokio::select! {
            () = &mut shutdown => break,
            accepted = listener.accept() => match accepted {
                Ok((stream, _)) => stream,
                Err(_) => {
                    // out of file descriptors, or a connection reset in the backlog: the
                    // connections being served close within their timeouts
                    tokio::time::sleep(Duration::from_millis(20)).await;
                    continue;
                }
            },
        };
        if let Ok(permit) = Arc::clone(&served).try_acquire_owned() {
            let conn = Connection {
                app: full.clone(),
                head_timeout: limits.timeout,
                keep_alive: true,
                permit,
            };
            tokio::spawn(conn.serve(stream, stopped.clone()));
        } else if let Ok(permit) = Arc::clone(&overflow).try_acquire_owned() {
            let conn = Connection {
                app: light.clone(),
                head_timeout: OVERFLOW_HEAD_TIMEOUT,
                keep_alive: false,
                permit,
            };
            tokio::spawn(conn.serve(stream, stopped.clone()));
        }
        // else: dropped, the connection is closed at once
    }
    let _ = stop.send(true);
    drop(stopped);
    stop.closed().await;
    Ok(())
}

/// One accepted connection and what serves it.
struct Connection {
    app: Router,
    head_timeout: Duration,
    keep_alive: bool,
    /// Its place among the served connections, given back when it closes.
    permit: OwnedSemaphorePermit,
}

impl Connection {
    async fn serve(self, stream: TcpStream, mut stop: watch::Receiver<bool>) {
        let _place = self.permit;
        let mut builder = http1::Builder::new();
        builder
            .timer(TokioTimer::new())
            .header_read_timeout(self.head_timeout)
            .max_buf_size(MAX_HEAD_BYTES)
            .keep_alive(self.keep_alive);
        let service = TowerToHyperService::new(self.app);
        let conn = builder.serve_connection(TokioIo::new(stream), service);
        let mut conn = std::pin::pin!(conn);
        tokio::select! {
            _ = conn.as_mut() => return,
            _ = stop.wait_for(|&s| s) => conn.as_mut().graceful_shutdown(),
        }
        // the request in flight, if any, is answered; a failed connection has nothing to tell
        let _ = conn.await;
    }
}

/// The routes an overflow connection is served: the pages and the routes that never wait for
/// the pool ([`crate::routes`]'s `GET` routes); every other route is answered with 503.
fn light_routes() -> Vec<(&'static str, Method, axum::routing::MethodRouter<Arc<Pool>>)> {
    crate::routes()
        .into_iter()
        .map(|(path, method, handler)| {
            if method == Method::GET {
                (path, method, handler)
            } else {
                (path, method, axum::routing::any(too_many_connections))
            }
        })
        .collect()
}

/// 503 with `Retry-After`: the server serves [`Limits::connections`] connections already.
async fn too_many_connections() -> Result<axum::response::Response, Infallible> {
    Ok((
        StatusCode::SERVICE_UNAVAILABLE,
        [
            (header::RETRY_AFTER, RETRY_AFTER_SECONDS.to_string()),
            (header::CONNECTION, "close".to_string()),
        ],
        Json(json!({
            "error": format!(
                "the server has too many open connections (lekalo serve --max-connections); \
                 try again in {RETRY_AFTER_SECONDS} s"
            ),
            "field": null,
        })),
    )
        .into_response())
}
