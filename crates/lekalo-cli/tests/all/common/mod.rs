//! Helpers shared by the CLI's end-to-end tests: the binary, and a temporary folder of input
//! files.

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

/// The standard output of a command, which must succeed (its standard error is the failure's
/// message).
pub(crate) fn output_of(cmd: &mut Command) -> Vec<u8> {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// The JSON a command writes to standard output, which must succeed.
pub(crate) fn json_of(cmd: &mut Command) -> serde_json::Value {
    serde_json::from_slice(&output_of(cmd)).unwrap()
}

/// The help text of `lekalo <path…> --help`.
pub(crate) fn help_of(path: &[String]) -> String {
    let out = lekalo().args(path).arg("--help").output().unwrap();
    assert!(
        out.status.success(),
        "`lekalo {} --help` failed",
        path.join(" ")
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Every leaf subcommand of `lekalo`, as argument paths (`["knot", "insert"]`), read from the
/// `Commands:` sections of the help texts, so that a new command is found without a list.
pub(crate) fn leaf_subcommands() -> Vec<Vec<String>> {
    fn walk(path: Vec<String>, out: &mut Vec<Vec<String>>) {
        let help = help_of(&path);
        let children: Vec<String> = help
            .lines()
            .skip_while(|l| l.trim() != "Commands:")
            .skip(1)
            .take_while(|l| !l.trim().is_empty())
            .filter_map(|l| {
                l.strip_prefix("  ")?
                    .split_whitespace()
                    .next()
                    .map(String::from)
            })
            .filter(|name| name != "help")
            .collect();
        if children.is_empty() {
            out.push(path);
        } else {
            for c in children {
                let mut p = path.clone();
                p.push(c);
                walk(p, out);
            }
        }
    }
    let mut out = Vec::new();
    walk(Vec::new(), &mut out);
    out
}
