//! Helpers shared by the CLI's end-to-end tests: the binary, and a temporary folder of input
//! files.

// each test binary uses its own subset of these
#![allow(dead_code)]

use std::fs;
use std::path::PathBuf;

use assert_cmd::Command;

/// The `lekalo` binary built for the tests.
pub(crate) fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// A temporary folder holding the given `(name, contents)` files.
pub(crate) fn dir_with(files: &[(&str, &str)]) -> tempfile::TempDir {
    let d = tempfile::tempdir().unwrap();
    for (name, text) in files {
        fs::write(d.path().join(name), text).unwrap();
    }
    d
}

/// The path of `name` inside the folder `d`.
pub(crate) fn p(d: &tempfile::TempDir, name: &str) -> PathBuf {
    d.path().join(name)
}

/// The standard output of `lekalo ARGS [FILE]`, which must succeed.
pub(crate) fn stdout_of(args: &[&str], file: Option<&std::path::Path>) -> Vec<u8> {
    let mut cmd = lekalo();
    cmd.args(args);
    if let Some(f) = file {
        cmd.arg(f);
    }
    cmd.assert().success().get_output().stdout.clone()
}
