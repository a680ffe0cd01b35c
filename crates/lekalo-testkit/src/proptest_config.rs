//! The configuration of property tests, shared by every crate's tests.

use proptest::test_runner::Config;

/// Proptest configuration: `PROPTEST_CASES` if set (the long job of docs/robustness.md), else
/// `default_cases` (sized so that the whole suite stays fast in CI). The rest is proptest's
/// default, in particular the regressions file next to the test's source file.
pub fn config(default_cases: u32) -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default_cases);
    // rejected draws (prop_assume) grow with the case count: allow as many as cases, so that
    // the long job with thousands of cases is not aborted for "too many global rejects"
    Config {
        max_global_rejects: cases.max(1024),
        ..Config::with_cases(cases)
    }
}
