//! The integration tests of the `lekalo` library, one test binary with one module per subject:
//! every integration test binary links the whole crate, so one binary builds much faster than one
//! per file. A file of this folder that is not declared below would be compiled nowhere;
//! `every_test_file_is_a_module` checks that none is left out.

mod arcs;
mod blending;
mod condition;
mod degree_change;
mod determinism;
mod extremes;
mod fast_eval;
mod fit;
mod fit_periodic;
mod fuzz_regressions;
mod interpolation;
mod intersect_exact;
mod ops;
mod ppform;
mod properties;
mod queries;
mod surfaces;
mod theory_links;

#[test]
fn every_test_file_is_a_module() {
    lekalo_testkit::assert_every_test_file_is_a_module(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/all"
    ));
}
