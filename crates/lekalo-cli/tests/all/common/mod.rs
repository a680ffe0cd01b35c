//! Helpers shared by the CLI's end-to-end tests: the binary, and a temporary folder of input
//! files.

use std::fs;
use std::path::{Path, PathBuf};

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

/// `lekalo convert --faces <extra…> <input> -o <output>` on files of the folder `d`, its
/// status and messages left to the caller.
pub(crate) fn convert_faces(
    d: &tempfile::TempDir,
    extra: &[&str],
    input: &str,
    output: &str,
) -> assert_cmd::assert::Assert {
    lekalo()
        .args(["convert", "--faces"])
        .args(extra)
        .arg(p(d, input))
        .arg("-o")
        .arg(p(d, output))
        .assert()
}

/// The JSON summary a command printed as the last line of its standard error.
pub(crate) fn last_stderr_json(done: &assert_cmd::assert::Assert) -> serde_json::Value {
    let err = String::from_utf8_lossy(&done.get_output().stderr).into_owned();
    serde_json::from_str(err.lines().last().unwrap()).unwrap()
}

/// The fitted `object` (a function `y(x)`) written to `curve.json` in `d` and evaluated by
/// `lekalo eval --at <at>`: the pairs `(x, y)`.
pub(crate) fn eval_fitted(
    d: &tempfile::TempDir,
    object: &serde_json::Value,
    at: &str,
) -> Vec<(f64, f64)> {
    fs::write(p(d, "curve.json"), serde_json::to_string(object).unwrap()).unwrap();
    let rows =
        json_of(
            lekalo()
                .current_dir(d.path())
                .args(["eval", "curve.json", "--at", at, "--json"]),
        );
    rows.as_array()
        .unwrap()
        .iter()
        .map(|row| (row["t"].as_f64().unwrap(), row["x"].as_f64().unwrap()))
        .collect()
}

/// `lekalo eval FILE --at … --json` of a spline in N parameters at `points` (each a point of
/// its parameters), which must succeed: the columns it names and its rows.
pub(crate) fn eval_at(
    file: &Path,
    points: &[impl AsRef<[f64]>],
) -> (serde_json::Value, Vec<Vec<f64>>) {
    let at: Vec<String> = points
        .iter()
        .flat_map(|p| {
            p.as_ref()
                .iter()
                .map(|x| format!("{x:?}"))
                .collect::<Vec<_>>()
        })
        .collect();
    let j = json_of(
        lekalo()
            .arg("eval")
            .arg(file)
            .args(["--at", &at.join(","), "--json"]),
    );
    let rows = serde_json::from_value(j["rows"].clone()).unwrap();
    (j["columns"].clone(), rows)
}
