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

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    /// A scratch folder, removed when dropped (also when the test panics).
    struct Scratch(std::path::PathBuf);

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = fs::remove_dir_all(&self.0);
        }
    }

    /// A scratch folder of test files: `main.rs` with `main`, and empty `files`.
    fn folder(name: &str, main: &str, files: &[&str]) -> Scratch {
        let dir =
            std::env::temp_dir().join(format!("lekalo-testkit-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("sub")).unwrap();
        fs::create_dir_all(dir.join("helpers")).unwrap();
        fs::write(dir.join("main.rs"), main).unwrap();
        for f in files {
            fs::write(dir.join(f), "").unwrap();
        }
        Scratch(dir)
    }

    #[test]
    fn declared_files_and_folders_pass() {
        // `sub/` has no mod.rs: it holds the submodules of `sub.rs`
        let dir = folder(
            "ok",
            "//! tests\n\nmod helpers;\nmod sub;\n",
            &[
                "sub.rs",
                "helpers/mod.rs",
                "sub/inner.rs",
                "x.proptest-regressions",
            ],
        );
        assert_every_test_file_is_a_module(dir.0.to_str().unwrap());
    }

    #[test]
    #[should_panic(expected = "declare `mod helpers;`, `mod left_out;` in main.rs")]
    fn a_left_out_file_is_named() {
        let dir = folder(
            "missing",
            "mod sub;\n",
            &["sub.rs", "left_out.rs", "helpers/mod.rs"],
        );
        assert_every_test_file_is_a_module(dir.0.to_str().unwrap());
    }
}
