//! Shared helpers of the integration tests.

use proptest::test_runner::Config as ProptestConfig;

/// Proptest configuration: `PROPTEST_CASES` if set (the long job of docs/robustness.md), else
/// `default_cases` (sized so that the whole suite stays fast in CI).
pub(crate) fn config(default_cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default_cases);
    ProptestConfig::with_cases(cases)
}
