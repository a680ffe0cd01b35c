//! What the tests of the lekalo crates share, written once: float closeness assertions, the
//! property tests' configuration, slow reference oracles and the documents' test vectors.
//!
//! The kit works on plain numbers (slices of `f64`) and does not depend on `lekalo`, so that the
//! core's unit tests, its integration tests and the front ends' tests all use the same copy; the
//! few adapters from the library's types live beside the tests that need them (the core's
//! `src/oracle.rs` for its unit tests).
//!
//! - [`close`]: `|got − want| ≤ tol` coordinate by coordinate, absolute, absolute plus relative,
//!   or relative.
//! - [`proptest_config`]: the case count of property tests (`PROPTEST_CASES`, docs/robustness.md).
//! - [`oracle`]: B-spline and Bezier curves by their definitions (Cox–de Boor recursion,
//!   Bernstein formula), for comparison with the fast kernels.
//! - [`vectors`]: the test vectors of docs/theory/interpolation.md#test-vectors.
//! - [`alloc`]: an allocator that counts the bytes live and their peak, for the tests and
//!   examples that measure memory.
//! - [`layout`]: every crate's integration tests are one binary, `tests/all/main.rs`; its check
//!   that no test file is left out.

pub mod alloc;
pub mod close;
pub mod layout;
pub mod oracle;
pub mod proptest_config;
pub mod vectors;

pub use close::{assert_close, assert_close_relative, assert_near};
pub use layout::assert_every_test_file_is_a_module;
pub use proptest_config::config;
