//! The examples in `--help` run as written. Every subcommand is found from the help texts (not
//! from a list), must show at least one example, and each example line is parsed from its help
//! text and run in a directory with the fixture files it names. A subcommand's examples run in
//! order, so later ones use what earlier ones wrote, as a reader following them would. The
//! `sh` blocks of the README and of `docs/cli.md` run as written too ([`doc_blocks`]).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use crate::common;
mod doc_blocks;
mod doc_options;

use std::fs;
use std::path::Path;

use common::{help_of, leaf_subcommands, lekalo};

/// Commands whose examples start a server that runs until stopped (the browser tests cover it).
const SERVERS: &[&str] = &["serve"];

/// Examples that are not run, with the reason.
const NOT_RUN: &[(&str, &str)] = &[
    (
        "demo",
        "runs every construction of the documents (the demo smoke step covers it)",
    ),
    ("demo -o gallery", "the same, with every figure rendered"),
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

/// Text of `n` rows made by `f(i)`.
fn rows(n: usize, f: &dyn Fn(f64) -> String) -> String {
    (0..n)
        .map(|i| f(f64::from(u32::try_from(i).unwrap())) + "\n")
        .collect()
}

fn bezier(control: &str) -> String {
    format!(r#"{{"lekalo": 1, "type": "bezier_curve", "control": {control}}}"#)
}

/// Files that differ between commands (a grid of another size, curves with common ends).
fn overrides(path: &str) -> Vec<(&'static str, String)> {
    // nets of 3 or 5 rows, 4 columns, bilinear (real degree 1 in u and v)
    let net = |n: usize| {
        rows(n, &|i| {
            format!(
                "{} {} {}",
                (i / 4.0).floor(),
                i % 4.0,
                (i / 4.0).floor() * (i % 4.0)
            )
        })
    };
    match path {
        "interpolate" => vec![("pts.csv", "1,1\n2,3\n4,3\n5,0\n".into())],
        // one weight per point of the 6 × 5 × 4 net values.csv
        "make" => vec![("weights.txt", rows(120, &|i| format!("{}", 1.0 + 0.5 * (i % 3.0))))],
        "bezier elevate" => vec![("net.csv", net(12))],
        "bezier" | "bezier reduce" | "bezier real-degree" | "bezier change" => {
            vec![("net.csv", net(20))]
        }
        "blend deform" | "blend" => vec![
            ("a.json", bezier("[[0, 0], [1, 2], [2, 0]]")),
            ("b.json", bezier("[[0, 0], [1, -1], [2, 0]]")),
        ],
        "blend corner" => vec![
            ("a.json", bezier("[[0, 0], [2, 0]]")),
            ("b.json", bezier("[[2, 0], [2, 2]]")),
        ],
        "pp convert" | "pp" => vec![(
            "curve.json",
            r#"{"lekalo": 1, "type": "bspline_curve", "degree": 3, "knots": [0, 0, 0, 0, 1, 2, 3, 4, 4, 4, 4], "control": [[0, 0], [1, 2], [2, 3], [3, 1], [4, 0], [5, 2], [6, 1]]}"#.into(),
        )],
        "fit" => vec![
            ("scan.csv", rows(60, &|i| format!("{},{}", i * 0.1, (i * 0.1).sin()))),
            ("track.csv", rows(40, &|i| format!("{},{}", (i * 0.15).cos(), (i * 0.15).sin()))),
            ("xy.csv", rows(30, &|i| format!("{i},{}", (i * 0.3).sin()))),
            ("w.txt", rows(30, &|_| "1".into())),
            (
                "loop.csv",
                rows(40, &|i| format!("{},{}", (i * 0.157).cos(), 0.5 * (i * 0.157).sin())),
            ),
            ("grid.csv", rows(600, &|i| format!("{},{},{}", (i / 20.0).floor(), i % 20.0, (i * 0.01).sin()))),
            ("uvz.csv", rows(300, &|i| format!("{},{},{}", (i * 0.37) % 1.0, (i * 0.61) % 1.0, (i * 0.1).sin()))),
            ("xyzw.csv", rows(300, &|i| format!("{},{},{},{}", (i * 0.37) % 1.0, (i * 0.61) % 1.0, (i * 0.43) % 1.0, (i * 0.1).sin()))),
            // theta, phi, r on the sphere, and the values of a 7 x 10 grid on it
            ("tpr.csv", rows(300, &|i| {
                let (t, p) = ((1.0 - (2.0 * i + 1.0) / 300.0).acos(), (2.4 * i) % std::f64::consts::TAU);
                format!("{t},{p},{}", t.cos() + 0.3 * t.sin() * p.cos())
            })),
            ("r.csv", rows(70, &|i| {
                let (t, p) = (0.4 * (1.0 + (i / 10.0).floor()), 0.6 * (i % 10.0));
                format!("{}", t.cos() + t.sin() * p.cos())
            })),
        ],
        // a plane surface in 2-D, so that 2-D queries suit the curve and the surface
        "project" => vec![
            (
                "surface-net.csv",
                "0 0\n1 0\n2 0\n0 1\n1 1\n2 1\n0 2\n1 2\n2 2\n".into(),
            ),
            ("queries.csv", "1,1\n0.5,0.2\n".into()),
        ],
        "intersect" => vec![
            ("loop.json", bezier("[[0, 0], [3, 3], [0, 3], [3, 0]]")),
            ("space.json", bezier("[[0, 0, 0], [1, 1, 2], [2, 0, 2]]")),
            // the plane z = 0.1 as a surface, cutting the bump surface.json in a loop
            (
                "level.json",
                r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 1, "degree_v": 1, "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1], "net": [2, 2], "control": [[0, 0, 0.1], [0, 2, 0.1], [2, 0, 0.1], [2, 2, 0.1]]}"#.into(),
            ),
        ],
        // a twisted cubic: a space curve with torsion
        "eval" => vec![(
            "helix.json",
            bezier("[[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]]"),
        )],
        // a second space curve for the ruled surface between it and curve3d.json
        "sweep ruled" => vec![("upper.json", bezier("[[0, 0, 1], [1, 2, 2], [3, 1, 3]]"))],
        "offset" => vec![(
            "ellipse.json",
            r#"{"lekalo": 1, "type": "nurbs_curve", "degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control": [[2, 0], [2, 1], [0, 1]], "weights": [1, 0.7071067811865476, 1]}"#.into(),
        )],
        _ => Vec::new(),
    }
}

/// Writes the fixture files the examples of `path` name.
fn fixtures(d: &Path, path: &str) {
    let w = |name: &str, text: &str| fs::write(d.join(name), text).unwrap();
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
    // a 6 × 5 × 4 grid of values, a trilinear spline in 3 parameters and points for it
    w(
        "values.csv",
        &rows(120, &|i| format!("{}", (i * 0.1).sin())),
    );
    w(
        "tensor.json",
        r#"{"lekalo": 1, "type": "bspline_tensor", "degrees": [1, 1, 1], "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]], "shape": [2, 2, 2], "control": [[0], [1], [2], [3], [4], [5], [6], [7]]}"#,
    );
    w("points.csv", "0,0,0\n0.5,0.5,0.5\n");
    w("lengths.txt", "0.5\n1\n2\n");
    for (name, control) in [
        ("quad.json", "[[0, 0], [1, 2], [2, 0]]"),
        ("cubic.json", "[[10, 0], [30, 10], [0, 20], [20, 0]]"),
        ("quartic.json", "[[0, 0], [1, 3], [2, -1], [3, 2], [4, 0]]"),
        ("up.json", "[[0, 0], [1, 2], [2, 0]]"),
        ("down.json", "[[0, 0], [1, -2], [2, 0]]"),
        ("before.json", "[[0, 0], [2, 0]]"),
        ("after.json", "[[2, 0], [2, 2]]"),
        ("a.json", "[[0, 0], [2, 2]]"),
        ("b.json", "[[0, 2], [2, 0]]"),
    ] {
        w(name, &bezier(control));
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
    w("control.csv", "0,0\n1,2\n3,2\n4,0\n");
    w(
        "surface-net.csv",
        "0 0 0\n0 1 0\n0 2 0\n1 0 0\n1 1 1\n1 2 0\n2 0 0\n2 1 0\n2 2 0\n",
    );
    for (name, text) in overrides(path) {
        w(name, &text);
    }
    // document 004's Example 2: the cubic elevated to degree 5 (real degree 3)
    lekalo()
        .current_dir(d)
        .args([
            "bezier",
            "elevate",
            "cubic.json",
            "--by",
            "2",
            "-o",
            "quintic.json",
        ])
        .assert()
        .success();
    lekalo()
        .current_dir(d)
        .args(["pp", "convert", "curve.json", "-o", "spline.pp.json"])
        .assert()
        .success();
    // the faces of part.step as JSON Lines (mesh of faces)
    lekalo()
        .current_dir(d)
        .args(["convert", "part.step", "-o", "faces.jsonl", "--faces"])
        .assert()
        .success();
    lekalo()
        .current_dir(d)
        .args([
            "make",
            "bspline-surface",
            "--control",
            "surface-net.csv",
            "--net",
            "3x3",
        ])
        .args(["--degree", "2", "-o", "surface.json"])
        .assert()
        .success();
}

/// Runs `list` in a fresh folder of fixtures for `path`; failures are collected.
fn run_all(path: &str, list: &[Vec<String>], failures: &mut Vec<String>) -> usize {
    let d = tempfile::tempdir().unwrap();
    fixtures(d.path(), path);
    let mut ran = 0;
    for args in list {
        let line = args.join(" ");
        if NOT_RUN.iter().any(|(n, _)| *n == line) {
            continue;
        }
        let o = lekalo().current_dir(d.path()).args(args).output().unwrap();
        if !o.status.success() {
            failures.push(format!(
                "`lekalo {line}` failed: {}",
                String::from_utf8_lossy(&o.stderr)
            ));
        }
        ran += 1;
    }
    ran
}

#[test]
fn every_help_example_runs() {
    let mut ran = 0;
    let mut failures = Vec::new();
    let leaves = leaf_subcommands();
    // the groups' own examples (`lekalo knot --help`), each group in order in one folder
    let mut groups: Vec<Vec<String>> = leaves
        .iter()
        .filter(|p| p.len() > 1)
        .map(|p| p[..1].to_vec())
        .collect();
    groups.dedup();
    for group in &groups {
        let list = examples(&help_of(group));
        ran += run_all(&group.join(" "), &list, &mut failures);
    }
    for path in &leaves {
        let name = path.join(" ");
        if SERVERS.contains(&name.as_str()) {
            continue;
        }
        let list = examples(&help_of(path));
        ran += run_all(&name, &list, &mut failures);
        // a reader asks the subcommand itself: its own help shows it at work (its group's
        // list is one `--help` away, unseen)
        if !list.iter().any(|a| a.starts_with(path)) {
            failures.push(format!("`lekalo {name} --help` shows no example of it"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(ran >= 100, "{ran} examples");
}
