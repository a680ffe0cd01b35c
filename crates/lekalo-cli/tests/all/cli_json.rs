//! `--json` everywhere a command computes a figure or a result: every such subcommand runs with
//! `--json` and its output parses as one JSON object. The subcommands are enumerated from the
//! help texts, so a new command must either appear in the table below or be listed among those
//! that only write objects.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use crate::common;

use common::{dir_with, help_of, leaf_subcommands, lekalo};

/// Commands that write curves, surfaces, files or a server, and compute no figure of their own.
const WRITE_OBJECTS: &[&str] = &[
    "make",
    "convert",
    "plot",
    "interpolate",
    "serve",
    "bezier elevate",
    "bezier change",
    "blend deform",
    "blend corner",
    "blend corners",
    "pp convert",
    "knot insert",
    "knot refine",
    "knot split",
    "knot reverse",
    "knot reparam",
    "knot decompose",
    "knot join",
    "sweep revolve",
    "sweep extrude",
    "sweep ruled",
    "slice",
];

/// One `--json` run per subcommand that reports a result.
const TABLE: &[&[&str]] = &[
    &["info", "curve.json", "--json"],
    &["demo", "--only", "doc000-ends", "--json"],
    &["eval", "curve.json", "--samples", "3", "--json"],
    &[
        "knots", "uniform", "--degree", "3", "--count", "5", "--json",
    ],
    &[
        "knots",
        "averaged",
        "--degree",
        "3",
        "--params",
        "0,5/17,9/17,14/17,1",
        "--json",
    ],
    &[
        "knots",
        "end-derivatives",
        "--degree",
        "3",
        "--params",
        "0,5/17,9/17,14/17,1",
        "--json",
    ],
    &[
        "knots",
        "from-parameters",
        "--degree",
        "3",
        "--params",
        "0,5/17,9/17,14/17,1",
        "--json",
    ],
    &[
        "knots",
        "curry-schoenberg",
        "--order",
        "3",
        "--breakpoints",
        "0,0.5,1",
        "--continuity",
        "2",
        "--json",
    ],
    &[
        "knots",
        "inspect",
        "--knots",
        "0,0,1,2,3,3",
        "--degree",
        "2",
        "--json",
    ],
    &["knots", "basis", "curve.json", "--at", "0,0.5,1", "--json"],
    &["bezier", "real-degree", "quintic.json", "--json"],
    &["bezier", "reduce", "quintic.json", "--json"],
    &[
        "bezier",
        "reduce",
        "quintic.json",
        "--approx",
        "2",
        "--json",
    ],
    &["blend", "spline", "pts.csv", "--local", "arcs", "--json"],
    &["blend", "jump", "--k", "2", "--samples", "3", "--json"],
    &[
        "pp",
        "quasi",
        "--function",
        "exp",
        "--breakpoints",
        "0,1,2",
        "--order",
        "4",
        "--json",
    ],
    &["knot", "remove", "curve.json", "--all", "--json"],
    &["fit", "xy.csv", "--function", "--smooth", "gcv", "--json"],
    &["measure", "curve.json", "--json"],
    &["project", "curve.json", "--point", "1,2", "--json"],
    &["intersect", "curve.json", "line.json", "--json"],
    &["offset", "curve.json", "--distance", "0.1", "--json"],
    &["mesh", "curve.json", "--tolerance", "1e-3", "--json"],
];

#[test]
fn every_result_prints_json() {
    let xy: String = (0..12)
        .map(|i| format!("{i},{}\n", (f64::from(i) * 0.7).sin()))
        .collect();
    let d = dir_with(&[
        (
            "curve.json",
            r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2, "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[1, 1], [2, 3], [4, 3], [5, 0]]}"#,
        ),
        (
            "line.json",
            r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 2], [6, 2]]}"#,
        ),
        (
            "quintic.json",
            r#"{"lekalo": 1, "type": "bezier_curve", "control": [[10, 0], [22, 6], [26, 10.4], [16.4, 14.4], [8, 14], [20, 0]]}"#,
        ),
        ("pts.csv", "0,0\n1,1\n2,1.2\n3,1\n4,0\n"),
        ("xy.csv", &xy),
    ]);
    for args in TABLE {
        let out = lekalo().current_dir(d.path()).args(*args).output().unwrap();
        assert!(
            out.status.success(),
            "`lekalo {}` failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
            panic!(
                "`lekalo {}` printed no JSON ({e}): {}",
                args.join(" "),
                String::from_utf8_lossy(&out.stdout)
            )
        });
        // one object; `eval` writes its rows as an array of records
        assert!(
            v.is_object() || v.is_array(),
            "`lekalo {}`: {v}",
            args.join(" ")
        );
    }
}

#[test]
fn every_command_is_classified() {
    for path in leaf_subcommands() {
        let name = path.join(" ");
        let in_table = TABLE
            .iter()
            .any(|args| args.starts_with(&path.iter().map(String::as_str).collect::<Vec<_>>()));
        let has_flag = help_of(&path).contains("--json");
        if WRITE_OBJECTS.contains(&name.as_str()) {
            assert!(!in_table, "`{name}` is in both lists");
        } else {
            assert!(
                in_table && has_flag,
                "`lekalo {name}`: a new command must take --json and get a row in TABLE, or be \
                 listed in WRITE_OBJECTS"
            );
        }
    }
}
