//! The examples in `--help` run as written. Every subcommand is found from the help texts (not
//! from a list), must show at least one example, and each example line is parsed from its help
//! text and run in a directory with the fixture files it names. A subcommand's examples run in
//! order, so later ones use what earlier ones wrote, as a reader following them would.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

mod common;

use std::fs;
use std::path::Path;

use common::{help_of, leaf_subcommands, lekalo};

/// Examples that are not run, with the reason.
const NOT_RUN: &[(&str, &str)] = &[
    (
        "serve",
        "starts a server that runs until stopped (the browser tests cover it)",
    ),
    (
        "demo",
        "runs every construction of the documents (the demo smoke step covers it)",
    ),
    (
        "bezier change quintic.json --degree 2",
        "shows a refusal: the real degree is 3",
    ),
];

/// The `lekalo …` lines of a help text: continuation lines (`\`) joined, comments dropped,
/// split into arguments with single quotes grouping.
fn examples(help: &str) -> Vec<Vec<String>> {
    let mut joined: Vec<String> = Vec::new();
    let mut open = false;
    for line in help.lines() {
        let l = line.trim();
        if open {
            if let Some(last) = joined.last_mut() {
                last.push(' ');
                last.push_str(l);
            }
        } else if let Some(rest) = line.strip_prefix("  lekalo ") {
            joined.push(rest.to_string());
        } else {
            continue;
        }
        open = l.ends_with('\\');
        if let Some(last) = joined.last_mut() {
            if open {
                last.pop();
            }
        }
    }
    joined
        .iter()
        .map(|l| l.split(" #").next().unwrap_or(l))
        .map(|l| {
            let mut args = Vec::new();
            for (i, part) in l.split('\'').enumerate() {
                if i % 2 == 1 {
                    args.push(part.to_string());
                } else {
                    args.extend(part.split_whitespace().map(String::from));
                }
            }
            args
        })
        .collect()
}

/// Writes the fixture files the examples name.
fn fixtures(d: &Path) {
    let w = |name: &str, text: &str| fs::write(d.join(name), text).unwrap();
    let rows = |n: usize, f: &dyn Fn(f64) -> String| -> String {
        (0..n)
            .map(|i| f(f64::from(u32::try_from(i).unwrap())) + "\n")
            .collect()
    };
    w("pts.csv", "1,1\n2,3\n4,3\n");
    w("pts4.csv", "1,1\n2,3\n4,3\n5,0\n");
    w(
        "net.csv",
        "0 0 0\n0 1 0\n0 2 0\n1 0 0\n1 1 1\n1 2 0\n2 0 0\n2 1 0\n2 2 0\n",
    );
    let curve = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2, "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[1, 1], [2, 3], [4, 3], [5, 0]]}"#;
    w("curve.json", curve);
    w(
        "many.jsonl",
        &format!("{curve}\n{}\n", curve.replace("[5, 0]", "[6, 1]")),
    );
    w(
        "curve3d.json",
        r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0, 0], [1, 2, 1], [3, 1, 2]]}"#,
    );
    w("data.csv", "1,1\n4,3\n5,0\n");
    w("polyline.csv", "0,0\n3,0\n4,2.5\n7,1\n7.5,6\n");
    w("tangents.csv", "1,0\n1,1\n1,-1\n0,-1\n");
    w(
        "grid.csv",
        &rows(12, &|i| {
            format!("{},{},{}", (i / 3.0).floor(), i % 3.0, (i * 0.3).sin())
        }),
    );
    w("xy.csv", &rows(12, &|i| format!("{i},{}", (i * 0.7).sin())));
    w("lengths.txt", "0.5\n1\n2\n");
    for (name, control) in [
        ("quad.json", "[[0, 0], [1, 2], [2, 0]]"),
        ("cubic.json", "[[0, 0], [1, 2], [3, 2], [4, 0]]"),
        (
            "quintic.json",
            "[[10, 0], [22, 6], [26, 10.4], [16.4, 14.4], [8, 14], [20, 0]]",
        ),
        ("quartic.json", "[[0, 0], [1, 3], [2, -1], [3, 2], [4, 0]]"),
        ("up.json", "[[0, 0], [1, 2], [2, 0]]"),
        ("down.json", "[[0, 0], [1, -2], [2, 0]]"),
        ("before.json", "[[0, 0], [2, 0]]"),
        ("after.json", "[[2, 0], [2, 2]]"),
        ("a.json", "[[0, 0], [2, 2]]"),
        ("b.json", "[[0, 2], [2, 0]]"),
    ] {
        w(
            name,
            &format!(r#"{{"lekalo": 1, "type": "bezier_curve", "control": {control}}}"#),
        );
    }
    for (name, control, weights) in [
        (
            "arc1.json",
            "[[1, 0], [1, 1], [0, 1]]",
            "[1, 0.7071067811865476, 1]",
        ),
        ("arc2.json", "[[1, 0], [0.2, 0.2], [0, 1]]", "[1, 2, 1]"),
    ] {
        w(
            name,
            &format!(
                r#"{{"lekalo": 1, "type": "nurbs_curve", "degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control": {control}, "weights": {weights}}}"#
            ),
        );
    }
    fs::copy(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../lekalo-io/tests/data/occ/mixed_ap242_m.step"
        ),
        d.join("part.step"),
    )
    .unwrap();
    lekalo()
        .current_dir(d)
        .args(["pp", "convert", "curve.json", "-o", "spline.pp.json"])
        .assert()
        .success();
    lekalo()
        .current_dir(d)
        .args([
            "make",
            "bspline-surface",
            "--control",
            "net.csv",
            "--net",
            "3x3",
        ])
        .args(["--degree", "2", "-o", "surface.json"])
        .assert()
        .success();
}

#[test]
fn every_help_example_runs() {
    let mut ran = 0;
    let mut failures = Vec::new();
    for path in leaf_subcommands() {
        let name = path.join(" ");
        if NOT_RUN.iter().any(|(n, _)| *n == name) {
            continue;
        }
        // a subcommand's own help, and its group's (where the group shows the examples)
        let mut list = examples(&help_of(&path));
        if path.len() > 1 {
            list.extend(
                examples(&help_of(&path[..1]))
                    .into_iter()
                    .filter(|a| a.starts_with(&path)),
            );
        }
        list.dedup();
        if list.iter().all(|a| !a.starts_with(&path)) {
            failures.push(format!("`lekalo {name} --help` shows no example of it"));
            continue;
        }
        let d = tempfile::tempdir().unwrap();
        fixtures(d.path());
        for args in list {
            let line = args.join(" ");
            if NOT_RUN.iter().any(|(n, _)| *n == line) {
                continue;
            }
            let o = lekalo().current_dir(d.path()).args(&args).output().unwrap();
            if !o.status.success() {
                failures.push(format!(
                    "`lekalo {line}` failed: {}",
                    String::from_utf8_lossy(&o.stderr)
                ));
            }
            ran += 1;
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(ran >= 100, "{ran} examples");
}
