//! The tests of the HTTP API of `lekalo-serve`, one test binary with one module per subject: every
//! integration test binary links the whole crate, so one binary builds much faster than one per
//! file. A file of this folder that is not declared below would be compiled nowhere;
//! `every_test_file_is_a_module` checks that none is left out.

mod api;
mod assets;
mod connections;
mod fit_query;
mod hostile;
mod openapi;
mod responsive;
mod transport;

/// The server with `limits` on a free loopback port, in the background, as `lekalo serve` runs
/// it ([`lekalo_serve::listen::serve`]): its address.
async fn serving(limits: lekalo_serve::Limits) -> std::net::SocketAddr {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
        .await
        .expect("bind");
    let addr = listener.local_addr().expect("addr");
    tokio::spawn(lekalo_serve::listen::serve(
        listener,
        limits,
        std::future::pending(),
    ));
    addr
}

#[test]
fn every_test_file_is_a_module() {
    lekalo_testkit::assert_every_test_file_is_a_module(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/all"
    ));
}
