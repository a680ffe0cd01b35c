//! The layout of a crate's integration tests: one binary, `tests/all/main.rs`, whose modules are
//! the test files beside it.

use std::collections::BTreeSet;
use std::path::Path;

/// Checks that `main.rs` in `dir` declares every test file of `dir` as a module (`mod name;`):
/// a file `name.rs`, or a folder `name/` with a `mod.rs`. A folder without `mod.rs` holds the
/// submodules of `name.rs`. A file left out would be compiled and run nowhere.
///
/// # Panics
/// Naming the files that are not modules, or when `dir` or its `main.rs` cannot be read.
#[track_caller]
pub fn assert_every_test_file_is_a_module(dir: &str) {
    let dir = Path::new(dir);
    let main = std::fs::read_to_string(dir.join("main.rs")).expect("main.rs of the tests");
    let declared: BTreeSet<&str> = main
        .lines()
        .filter_map(|l| l.trim().strip_prefix("mod ")?.strip_suffix(';'))
        .collect();
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(dir).expect("the tests' folder") {
        let path = entry.expect("a folder entry").path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        let module = if path.is_dir() {
            path.join("mod.rs").exists().then_some(name)
        } else {
            name.strip_suffix(".rs").filter(|&m| m != "main")
        };
        if let Some(m) = module {
            if !declared.contains(m) {
                missing.push(m.to_string());
            }
        }
    }
    missing.sort();
    assert!(
        missing.is_empty(),
        "{}: declare `mod {};` in main.rs",
        dir.display(),
        missing.join(";`, `mod ")
    );
}
