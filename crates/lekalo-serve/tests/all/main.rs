//! The tests of the HTTP API of `lekalo-serve`, one test binary with one module per subject: every
//! integration test binary links the whole crate, so one binary builds much faster than one per
//! file. A file of this folder that is not declared below would be compiled nowhere;
//! `every_test_file_is_a_module` checks that none is left out.

mod api;
mod assets;
mod connections;
mod fit_query;
mod openapi;
mod responsive;
mod transport;

#[test]
fn every_test_file_is_a_module() {
    lekalo_testkit::assert_every_test_file_is_a_module(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/all"
    ));
}
