//! End-to-end tests of the `lekalo` binary: every subcommand, bad input (exit code 2, the
//! message names the file, line and field) and internal failure (exit code 3).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;
use std::path::Path;

use predicates::prelude::*;
use predicates::str::contains;

use crate::common;
use common::{dir_with, lekalo, p};

const LECTURE: &str = r#"{
  "lekalo": 1,
  "type": "bspline_curve",
  "degree": 2,
  "knots": [0, 0, 1, 2, 3, 3],
  "control": [[1, 1], [2, 3], [4, 3]]
}
"#;

const HALF_CIRCLE: &str = r#"{"lekalo": 1, "type": "nurbs_curve", "degree": 2,
 "knots": [0, 0, 0, 0.5, 0.5, 1, 1, 1],
 "control": [[1, 0, 0.5], [1, 1, 0.5], [0, 1, 0.5], [-1, 1, 0.5], [-1, 0, 0.5]],
 "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1]}"#;

#[test]
fn every_subcommand_has_help_with_examples() {
    for sub in ["make", "eval", "info", "knots", "convert", "plot", "demo"] {
        lekalo()
            .args([sub, "--help"])
            .assert()
            .success()
            .stdout(contains("Example"));
    }
    for rule in [
        "uniform",
        "averaged",
        "end-derivatives",
        "from-parameters",
        "curry-schoenberg",
        "inspect",
        "basis",
    ] {
        lekalo()
            .args(["knots", rule, "--help"])
            .assert()
            .success()
            .stdout(contains("Example"));
    }
    lekalo().arg("--help").assert().success().stdout(contains(
        "Exit codes: 0 success, 2 bad input, 3 internal failure",
    ));
    // a usage error is bad input too
    lekalo().args(["eval"]).assert().code(2);
}

/// A subcommand's help lists its own options first and the global ones apart, under their
/// own heading; `demo` takes `-o/--output` as every other command (and `--out` still).
#[test]
fn help_keeps_global_options_apart_and_demo_takes_output() {
    let out = lekalo().args(["knot", "insert", "-h"]).output().unwrap();
    let help = String::from_utf8(out.stdout).unwrap();
    let own = help.find("Options:").expect("own options");
    let global = help
        .find("Global options:")
        .expect("a heading for the global options");
    let max_size = help.find("--max-size").expect("--max-size listed");
    let at = own + help[own..].find("--at <AT>").expect("--at listed");
    assert!(at < global && global < max_size, "{help}");
    let d = tempfile::tempdir().unwrap();
    for flag in ["-o", "--out"] {
        let dir = d.path().join(flag.trim_start_matches('-'));
        lekalo()
            .args(["demo", "--only", "doc002-bspline", flag])
            .arg(&dir)
            .assert()
            .success();
        assert!(dir.join("index.html").is_file(), "{flag}: no gallery");
    }
}

#[test]
fn make_info_eval_the_lecture_curve() {
    let d = dir_with(&[("pts.csv", "x,y\n1,1\n2,3\n4,3\n")]);
    let curve = p(&d, "lecture.json");
    lekalo()
        .args([
            "make",
            "bspline",
            "--degree",
            "2",
            "--knots",
            "0,0,1,2,3,3",
            "--control",
        ])
        .arg(p(&d, "pts.csv"))
        .arg("-o")
        .arg(&curve)
        .assert()
        .success();
    let made = fs::read_to_string(&curve).unwrap();
    assert!(
        made.contains("\"knots\": [0.0, 0.0, 1.0, 2.0, 3.0, 3.0]"),
        "{made}"
    );
    lekalo()
        .arg("info")
        .arg(&curve)
        .assert()
        .success()
        .stdout(contains("degree          2 (order 3)"))
        .stdout(contains("domain          [1, 2] (not clamped)"))
        .stdout(contains("0×2  1×1  2×1  3×2"));
    let out = lekalo()
        .arg("info")
        .arg(&curve)
        .arg("--json")
        .output()
        .unwrap();
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["start"], serde_json::json!([1.5, 2.0]));
    // document 002, B-splines: P(1.5) = (17/8, 11/4); P' = (t, 4 − 2t)
    lekalo()
        .arg("eval")
        .arg(&curve)
        .args(["--at", "1,1.5,2", "-d", "1"])
        .assert()
        .success()
        .stdout("t,x,y,d1x,d1y\n1,1.5,2,1,2\n1.5,2.125,2.75,1.5,1\n2,3,3,2,0\n");
    let out = lekalo()
        .arg("eval")
        .arg(&curve)
        .args(["--samples", "3", "--curvature", "--format", "json"])
        .output()
        .unwrap();
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j.as_array().unwrap().len(), 3);
    assert_eq!(j[2]["curvature"], serde_json::json!(0.5)); // |(2,0)×(1,−2)| / 2³
                                                           // standard input
    lekalo()
        .args(["eval", "-", "--at", "1.5"])
        .write_stdin(LECTURE)
        .assert()
        .success()
        .stdout(contains("1.5,2.125,2.75"));
    // bezier and nurbs from points on standard input
    lekalo()
        .args(["make", "bezier", "--control", "-"])
        .write_stdin("0 0\n1 2\n2 0\n")
        .assert()
        .success()
        .stdout(contains("\"type\": \"bezier_curve\""));
    lekalo()
        .args([
            "make",
            "nurbs",
            "--control",
            "-",
            "--degree",
            "2",
            "--weights",
            "1,0.5,1",
        ])
        .write_stdin("[[1,0],[1,1],[0,1]]")
        .assert()
        .success()
        .stdout(contains("\"weights\": [1.0, 0.5, 1.0]"));
}

#[test]
fn bad_input_names_file_line_and_field() {
    let d = dir_with(&[
        (
            "c.json",
            &LECTURE.replace("[0, 0, 1, 2, 3, 3]", "[0, 0, 2, 1, 3, 3]"),
        ),
        ("v.json", &LECTURE.replace("\"lekalo\": 1", "\"lekalo\": 7")),
        ("ok.json", LECTURE),
        ("pts.csv", "x,y\n1,1\n2,oops\n"),
    ]);
    lekalo()
        .arg("eval")
        .arg(p(&d, "c.json"))
        .assert()
        .code(2)
        .stderr(contains("c.json:5: field `knots`"));
    lekalo()
        .arg("info")
        .arg(p(&d, "v.json"))
        .assert()
        .code(2)
        .stderr(contains(
            "v.json:2: field `lekalo`: format version 7 is not supported",
        ));
    lekalo()
        .arg("eval")
        .arg(p(&d, "missing.json"))
        .assert()
        .code(2)
        .stderr(contains("cannot read").and(contains("missing.json")));
    lekalo()
        .arg("eval")
        .arg(p(&d, "ok.json"))
        .args(["--at", "2.5"])
        .assert()
        .code(2)
        .stderr(contains("parameter 2.5 is outside the domain [1, 2]"));
    lekalo()
        .arg("eval")
        .arg(p(&d, "ok.json"))
        .args(["--at", "1,abc"])
        .assert()
        .code(2)
        .stderr(contains("--at: value 2 is \"abc\""));
    lekalo()
        .args(["make", "bezier", "--control"])
        .arg(p(&d, "pts.csv"))
        .assert()
        .code(2)
        .stderr(contains(
            "pts.csv:3: field `y`: cannot read \"oops\" as a number",
        ));
    lekalo()
        .args(["make", "bspline", "--degree", "3", "--control", "-"])
        .write_stdin("0 0\n1 1\n")
        .assert()
        .code(2)
        .stderr(contains("degree"));
}

/// An output in a folder that does not exist is the user's input (exit code 2), named with the
/// folder and the fix, for every command that writes (they share one atomic writer); nothing
/// is created.
#[test]
fn an_output_in_a_missing_folder_is_bad_input() {
    let d = dir_with(&[("ok.json", LECTURE), ("pts.csv", "0,0\n1,2\n2,1\n3,3\n")]);
    let folder = p(&d, "no/such/dir");
    let commands: [(&[&str], &str); 4] = [
        (&["convert", "ok.json"], "out.json"),
        (&["interpolate", "pts.csv"], "out.json"),
        (&["knot", "insert", "ok.json", "--at", "1.5"], "out.json"),
        (&["eval", "ok.json", "--samples", "5"], "out.csv"),
    ];
    for (args, name) in commands {
        let out = folder.join(name);
        lekalo()
            .current_dir(d.path())
            .args(args)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(2)
            .stderr(contains(format!(
                "cannot write {}: the folder {} does not exist; create it or choose \
                 another output path",
                out.display(),
                folder.display()
            )));
    }
    assert!(!d.path().join("no").exists());
}

/// An error about the tolerance names the option `--tolerance`, the one spelling of every
/// command (the library's key `Arg::Tolerance`, through the command line's table), and exits
/// with 2; `fit --tol`, the older spelling, is still read with a warning.
#[test]
fn an_error_about_the_tolerance_names_the_option() {
    let d = dir_with(&[
        ("c.json", LECTURE),
        ("pts.csv", "0,0\n1,2\n2,1\n3,3\n4,0\n5,1\n"),
    ]);
    let cases: [(&[&str], &str); 8] = [
        (
            &["fit", "pts.csv", "--tolerance", "-1"],
            "error: --tolerance: tolerance -1: it must be finite and > 0",
        ),
        (
            &["offset", "c.json", "--distance", "0.1", "--tolerance=-1"],
            "error: c.json: --tolerance: -1 is not a positive finite tolerance",
        ),
        (
            &["intersect", "c.json", "c.json", "--tolerance=NaN"],
            "error: c.json: --tolerance: NaN is not a positive finite tolerance",
        ),
        (
            &["intersect", "c.json", "--self", "--tolerance=0"],
            "error: c.json: --tolerance: 0 is not a positive finite tolerance",
        ),
        (
            &["measure", "c.json", "--rtol=0"],
            "error: c.json: --rtol: 0 is not a positive finite tolerance",
        ),
        (
            &["knot", "remove", "c.json", "--at", "1", "--tolerance=-1"],
            "error: --tolerance: ",
        ),
        (
            &[
                "blend",
                "spline",
                "pts.csv",
                "--local",
                "arcs",
                "--tolerance=0",
            ],
            "error: --tolerance: ",
        ),
        (
            &["mesh", "c.json", "--tolerance=-1"],
            "error: c.json: --tolerance: ",
        ),
    ];
    for (args, needle) in cases {
        lekalo()
            .current_dir(d.path())
            .args(args)
            .assert()
            .code(2)
            .stderr(contains(needle));
    }
    lekalo()
        .current_dir(d.path())
        .args(["fit", "pts.csv", "--tol", "0.5"])
        .assert()
        .success()
        .stderr(contains(
            "`--tol` of `lekalo fit` is deprecated; write `--tolerance`",
        ));
    // the relative tolerance is --rtol; the old spelling works, hidden, with a warning
    lekalo()
        .current_dir(d.path())
        .args(["measure", "c.json", "--tolerance", "1e-9"])
        .assert()
        .success()
        .stdout(contains("length "))
        .stderr(contains(
            "`--tolerance` of `lekalo measure` is deprecated; write `--rtol`",
        ));
    lekalo()
        .current_dir(d.path())
        .args(["measure", "--help"])
        .assert()
        .success()
        .stdout(contains("--rtol <RTOL>").and(contains("--tolerance <").not()));
}

/// A failure to write on valid input (the device is full) is an internal failure: exit code 3.
#[cfg(target_os = "linux")]
#[test]
fn a_full_device_is_exit_code_3() {
    let d = dir_with(&[("ok.json", LECTURE)]);
    lekalo()
        .arg("convert")
        .arg(p(&d, "ok.json"))
        .args(["-o", "/dev/full"])
        .assert()
        .code(3)
        .stderr(contains("cannot write /dev/full"));
}

#[test]
fn knots_basis_at_parameters() {
    // P&T Example 2.3: degree 2 over {0,0,0,1,2,3,4,4,5,5,5} at 2.5, span 4, values 1/8, 3/4, 1/8
    // (docs/theory/foundations.md#cox-de-boor-recursion); and the right end of the domain
    let out = lekalo()
        .args([
            "knots",
            "basis",
            "--knots",
            "0,0,0,1,2,3,4,4,5,5,5",
            "--degree",
            "2",
            "--at",
            "2.5,5",
            "--json",
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["degree"], 2);
    assert_eq!(j["basis"][0]["span"], 4);
    assert_eq!(j["basis"][0]["first"], 2);
    assert_eq!(
        j["basis"][0]["values"],
        serde_json::json!([0.125, 0.75, 0.125])
    );
    assert_eq!(j["basis"][1]["span"], 7);
    assert_eq!(j["basis"][1]["values"], serde_json::json!([0.0, 0.0, 1.0]));
    // outside the domain, NaN, a degree the knots cannot carry, no degree: named errors
    for (args, message) in [
        (vec!["--degree", "2", "--at", "5.5"], "outside the domain"),
        (vec!["--degree", "2", "--at", "nan"], "--at"),
        (vec!["--degree", "9", "--at", "1"], "degree"),
        (vec!["--at", "1"], "--knots needs --degree"),
    ] {
        lekalo()
            .args(["knots", "basis", "--knots", "0,0,0,1,2,3,4,4,5,5,5"])
            .args(args)
            .assert()
            .code(2)
            .stderr(contains(message));
    }
}

#[test]
fn knots_basis_extrapolates_the_end_spans_when_asked() {
    // degree 1 on {0,0,1,2,2}: beyond 2 the last span's lines (2 − t, t − 1), before 0 the
    // first span's (1 − t, t)
    let out = lekalo()
        .args([
            "knots",
            "basis",
            "--knots",
            "0,0,1,2,2",
            "--degree",
            "1",
            "--at",
            "3,-1,0.5",
            "--extrapolate",
            "--json",
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["basis"][0]["first"], 1);
    assert_eq!(j["basis"][0]["values"], serde_json::json!([-1.0, 2.0]));
    assert_eq!(j["basis"][1]["first"], 0);
    assert_eq!(j["basis"][1]["values"], serde_json::json!([2.0, -1.0]));
    assert_eq!(j["basis"][2]["values"], serde_json::json!([0.5, 0.5]));
    // without the flag the same parameter is refused
    lekalo()
        .args([
            "knots",
            "basis",
            "--knots",
            "0,0,1,2,2",
            "--degree",
            "1",
            "--at",
            "3",
        ])
        .assert()
        .code(2)
        .stderr(contains("outside the domain"));
}

#[test]
fn knots_build_and_inspect() {
    // averaged chord-length knots of P&T Example 9.1, interior 28/51
    // (docs/theory/interpolation.md#averaged-knots)
    let out = lekalo()
        .args([
            "knots",
            "averaged",
            "--degree",
            "3",
            "--params",
            "0,5/17,9/17,14/17,1",
            "--json",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let k: Vec<f64> = serde_json::from_value(j["knots"].clone()).unwrap();
    assert_eq!(k.len(), 9);
    assert!((k[4] - 28.0 / 51.0).abs() < 1e-15, "{k:?}");
    assert_eq!(j["domain"], serde_json::json!([0.0, 1.0]));
    lekalo()
        .args([
            "knots", "uniform", "--degree", "3", "--count", "5", "--json",
        ])
        .assert()
        .success()
        .stdout(contains("\"clamped\": true"));
    lekalo()
        .args([
            "knots",
            "end-derivatives",
            "-p",
            "2",
            "--params",
            "0,5/17,9/17,14/17,1",
        ])
        .assert()
        .success()
        .stdout(contains(format!("{}", 31.0 / 34.0)));
    lekalo()
        .args([
            "knots",
            "from-parameters",
            "-p",
            "3",
            "--params",
            "0,5/17,9/17,14/17,1",
        ])
        .assert()
        .success()
        .stdout(contains("count           11"));
    lekalo()
        .args([
            "knots",
            "curry-schoenberg",
            "--order",
            "3",
            "--breakpoints",
            "0,0.5,0.9,1.4,2.1,2.7,3",
            "--continuity",
            "2,2,2,2,2",
        ])
        .assert()
        .success()
        .stdout(contains("[0, 0, 0, 0.5, 0.9, 1.4, 2.1, 2.7, 3, 3, 3]"))
        .stdout(contains("8 control points"));
    lekalo()
        .args([
            "knots",
            "curry-schoenberg",
            "--order",
            "3",
            "--breakpoints",
            "0,1,2",
            "--continuity",
            "2,2",
        ])
        .assert()
        .code(2)
        .stderr(contains("continuity conditions"));
    lekalo()
        .args([
            "knots",
            "inspect",
            "--knots",
            "0,0,1,2,3,3",
            "--degree",
            "2",
        ])
        .assert()
        .success()
        .stdout(contains("domain          [1, 2] (not clamped)"))
        .stdout(contains("0×2  1×1  2×1  3×2"));
    lekalo()
        .args(["knots", "inspect", "--knots", "0,1,0.5"])
        .assert()
        .code(2)
        .stderr(contains("knot"));
    let d = dir_with(&[("c.json", HALF_CIRCLE)]);
    lekalo()
        .args(["knots", "inspect"])
        .arg(p(&d, "c.json"))
        .assert()
        .success()
        .stdout(contains("0.5×2"));
}

#[test]
fn convert_formats_and_never_overwrite_inputs() {
    let d = dir_with(&[("c.json", LECTURE), ("n.json", HALF_CIRCLE)]);
    let input = p(&d, "c.json");
    for (ext, check) in [
        ("csv", "t,x,y\n1,1.5,2\n"),
        ("svg", "<svg"),
        ("obj", "v 1.5 2 0\n"),
        ("jsonl", "{\"lekalo\":1,\"type\":\"bspline_curve\""),
        ("step", "ISO-10303-21;"),
    ] {
        let out = p(&d, &format!("out.{ext}"));
        lekalo()
            .arg("convert")
            .arg(&input)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        let text = fs::read_to_string(&out).unwrap();
        assert!(
            text.starts_with(check) || text.contains(check),
            "{ext}: {text}"
        );
    }
    let png = p(&d, "out.png");
    lekalo()
        .arg("convert")
        .arg(&input)
        .arg("-o")
        .arg(&png)
        .assert()
        .success();
    assert_eq!(&fs::read(&png).unwrap()[1..4], b"PNG");
    // JSON round trip: the converted file reads back to the same curve
    let back = p(&d, "back.json");
    lekalo()
        .arg("convert")
        .arg(p(&d, "out.jsonl"))
        .arg("-o")
        .arg(&back)
        .assert()
        .success();
    lekalo()
        .args(["eval", "--at", "1.5"])
        .arg(&back)
        .assert()
        .stdout(contains("1.5,2.125,2.75"));
    // inputs are never overwritten
    lekalo()
        .arg("convert")
        .arg(&input)
        .arg("-o")
        .arg(&input)
        .args(["--to", "json"])
        .assert()
        .code(2)
        .stderr(contains("it is an input file"));
    assert_eq!(fs::read_to_string(&input).unwrap(), LECTURE);
    lekalo()
        .arg("convert")
        .arg(&input)
        .args(["--to", "dxf"])
        .assert()
        .code(2)
        .stderr(contains("unknown output format \"dxf\""));
}

#[test]
fn plot_svg_png_basis_and_data_points() {
    let d = dir_with(&[
        ("c.json", LECTURE),
        ("n.json", HALF_CIRCLE),
        ("data.csv", "1.5 2\n3 3\n"),
    ]);
    let svg = p(&d, "c.svg");
    lekalo()
        .arg("plot")
        .arg(p(&d, "c.json"))
        .arg("--points")
        .arg(p(&d, "data.csv"))
        .arg("-o")
        .arg(&svg)
        .assert()
        .success();
    let text = fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("data points") && text.contains("control polygon"),
        "{text}"
    );
    let basis = lekalo()
        .arg("plot")
        .arg(p(&d, "c.json"))
        .arg("--basis")
        .output()
        .unwrap();
    let text = String::from_utf8(basis.stdout).unwrap();
    assert_eq!(
        text.matches("<g class=\"series\" data-label=\"N").count(),
        3,
        "three basis functions"
    );
    assert_eq!(
        text.matches("<polyline").count(),
        4,
        "three basis functions and the zero line"
    );
    let png = p(&d, "n.png");
    lekalo()
        .arg("plot")
        .arg(p(&d, "n.json"))
        .args(["--azimuth", "30", "--scale", "1"])
        .arg("-o")
        .arg(&png)
        .assert()
        .success();
    let bytes = fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    assert_eq!(
        u32::from_be_bytes([bytes[16], bytes[17], bytes[18], bytes[19]]),
        640
    );
    lekalo()
        .arg("plot")
        .arg(p(&d, "c.json"))
        .arg("--points")
        .arg(p(&d, "c.json"))
        .assert()
        .code(2)
        .stderr(contains("c.json"));
}

#[test]
fn json_lines_batches_report_bad_lines_and_go_on() {
    let good = r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0],[1,2],[2,0]]}"#;
    let bad = r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0],[1]]}"#;
    let batch: String = (0..40)
        .map(|i| {
            if i == 7 {
                format!("{bad}\n")
            } else {
                format!("{good}\n")
            }
        })
        .collect();
    let d = dir_with(&[("many.jsonl", &batch)]);
    let out = p(&d, "samples.jsonl");
    lekalo()
        .arg("eval")
        .arg(p(&d, "many.jsonl"))
        .args(["--at", "0.5"])
        .arg("-o")
        .arg(&out)
        .assert()
        .code(2)
        .stderr(contains("many.jsonl:8: field `control`"))
        .stderr(contains("1 of 40 objects failed"));
    let lines: Vec<serde_json::Value> = fs::read_to_string(&out)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 40);
    assert_eq!(lines[0]["columns"], serde_json::json!(["t", "x", "y"]));
    assert_eq!(lines[0]["rows"], serde_json::json!([[0.5, 1.0, 1.0]]));
    assert_eq!(lines[7]["line"], serde_json::json!(8));
    assert!(lines[7]["error"].is_string());
    let good_only: String = (0..5).map(|_| format!("{good}\n")).collect();
    lekalo()
        .args(["info", "-", "--jsonl"])
        .write_stdin(good_only.clone())
        .assert()
        .success()
        .stdout(predicate::function(|s: &str| s.lines().count() == 5));
    // every object of a batch goes into one STEP file
    let d2 = dir_with(&[("few.jsonl", &good_only)]);
    let step = p(&d2, "all.step");
    lekalo()
        .arg("convert")
        .arg(p(&d2, "few.jsonl"))
        .arg("-o")
        .arg(&step)
        .assert()
        .success();
    let text = fs::read_to_string(&step).unwrap();
    assert_eq!(text.matches("B_SPLINE_CURVE_WITH_KNOTS(").count(), 5);
}

#[test]
fn quiet_and_verbose() {
    let d = dir_with(&[("c.json", LECTURE)]);
    lekalo()
        .args(["--verbose", "info"])
        .arg(p(&d, "c.json"))
        .assert()
        .success()
        .stderr(contains("read 1 object(s) from"));
    lekalo()
        .args(["info", "--quiet"])
        .arg(p(&d, "c.json"))
        .assert()
        .success()
        .stderr("");
    lekalo()
        .args(["--quiet", "--verbose", "demo"])
        .assert()
        .code(2);
}

#[test]
fn demo_writes_the_gallery() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("gallery");
    lekalo()
        .arg("demo")
        .arg("--out")
        .arg(&out)
        .assert()
        .success()
        .stdout(contains("(0.125, 0.75, 0.125)"))
        .stdout(contains("(2.125, 2.75)"))
        .stdout(contains("checks reproduce the documents").and(contains("[FAIL]").not()));
    let html = fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("<img src=\"doc002-bspline-2.svg\""), "{html}");
    assert!(!html.contains("class=\"fail\""));
    let svgs = fs::read_dir(&out)
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().extension() == Some("svg".as_ref()))
        .count();
    assert_eq!(svgs, html.matches(".svg\" alt=").count());
    assert!(Path::new(&out)
        .join("doc003-curry-schoenberg-1.svg")
        .exists());
}

/// The STEP file written by `convert`, read back with ruststep (an independent ISO 10303-21
/// parser), evaluates to the same points as the curve.
#[test]
fn step_reads_back_with_an_independent_parser() {
    use ruststep::ast::{EntityInstance, Name, Parameter};
    let d = dir_with(&[("n.json", HALF_CIRCLE)]);
    let step = p(&d, "n.stp");
    lekalo()
        .arg("convert")
        .arg(p(&d, "n.json"))
        .arg("-o")
        .arg(&step)
        .assert()
        .success();
    let text = fs::read_to_string(&step).unwrap();
    let ex = ruststep::parser::parse(&text).unwrap();
    let mut points = std::collections::HashMap::new();
    let mut curve = None;
    for e in &ex.data[0].entities {
        match e {
            EntityInstance::Simple { id, record } if record.name == "CARTESIAN_POINT" => {
                let Parameter::List(ps) = &record.parameter else {
                    panic!()
                };
                let Parameter::List(c) = &ps[1] else { panic!() };
                let xyz: Vec<f64> = c
                    .iter()
                    .map(|v| {
                        if let Parameter::Real(x) = v {
                            *x
                        } else {
                            panic!()
                        }
                    })
                    .collect();
                points.insert(*id, xyz);
            }
            EntityInstance::Complex { subsuper, .. } => curve = Some(subsuper.0.clone()),
            _ => {}
        }
    }
    let recs = curve.expect("the rational curve is a complex entity");
    let get = |name: &str| match &recs.iter().find(|r| r.name == name).unwrap().parameter {
        Parameter::List(v) => v.clone(),
        _ => panic!(),
    };
    let reals = |p: &Parameter| -> Vec<f64> {
        let Parameter::List(v) = p else { panic!() };
        v.iter()
            .map(|x| match x {
                Parameter::Real(r) => *r,
                Parameter::Integer(i) => *i as f64,
                _ => panic!(),
            })
            .collect()
    };
    let b = get("B_SPLINE_CURVE");
    let Parameter::Integer(degree) = b[0] else {
        panic!()
    };
    let Parameter::List(refs) = &b[1] else {
        panic!()
    };
    let rows: Vec<Vec<f64>> = refs
        .iter()
        .map(|r| match r {
            Parameter::Ref(Name::Entity(id)) => points[id].clone(),
            _ => panic!(),
        })
        .collect();
    let k = get("B_SPLINE_CURVE_WITH_KNOTS");
    let Parameter::List(mults) = &k[0] else {
        panic!()
    };
    let mults: Vec<usize> = mults
        .iter()
        .map(|m| match m {
            Parameter::Integer(i) => usize::try_from(*i).unwrap(),
            _ => panic!("multiplicities are integers"),
        })
        .collect();
    let knots: Vec<f64> = mults
        .iter()
        .zip(reals(&k[1]))
        .flat_map(|(m, t)| std::iter::repeat_n(t, *m))
        .collect();
    let weights = reals(&get("RATIONAL_B_SPLINE_CURVE")[0]);
    let back = lekalo::NurbsCurve::new(
        usize::try_from(degree).unwrap(),
        knots,
        lekalo::Points::from_rows(&rows).unwrap(),
        weights,
    )
    .unwrap();
    // compare with `lekalo eval` of the original at 21 parameters
    let out = lekalo()
        .arg("eval")
        .arg(p(&d, "n.json"))
        .args(["-n", "21"])
        .output()
        .unwrap();
    let csv = String::from_utf8(out.stdout).unwrap();
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let q = back.eval(v[0]).unwrap();
        for k in 0..3 {
            assert!(
                (q[k] - v[k + 1]).abs() < 1e-14,
                "t = {}: {q:?} vs {v:?}",
                v[0]
            );
        }
        // on the half circle of radius 1 at height 0.5
        assert!((q[0].hypot(q[1]) - 1.0).abs() < 1e-14 && q[2] == 0.5);
    }
}

/// `lekalo info` on a points file (a new user's first try) says it holds points and which
/// commands make an object of them.
#[test]
fn info_of_a_points_file_names_the_commands_that_make_an_object() {
    let d = dir_with(&[("pts.txt", "1 1\n2 3\n4 3\n")]);
    lekalo()
        .current_dir(d.path())
        .args(["info", "pts.txt"])
        .assert()
        .code(2)
        .stderr(contains("pts.txt holds points (3 of dimension 2)"))
        .stderr(contains("lekalo interpolate pts.txt -o curve.json"));
}

/// A closed pipe is not an internal failure: `lekalo demo --out DIR 2>&1 | head -n 1` ends
/// quietly with 0 (the gallery's note on standard error comes after `head` has gone).
#[test]
fn closed_output_pipes_end_quietly() {
    let d = tempfile::tempdir().unwrap();
    let bin = env!("CARGO_BIN_EXE_lekalo");
    for cmd in [
        format!("'{bin}' demo --out gallery 2>&1 | head -n 1"),
        format!("'{bin}' demo 2>&1 | head -n 1"),
    ] {
        let o = std::process::Command::new("bash")
            .args(["-c", &format!("set -o pipefail; {cmd}")])
            .current_dir(d.path())
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "`{cmd}`: {}: {}",
            o.status,
            String::from_utf8_lossy(&o.stderr)
        );
    }
    // a note on a standard error already closed does not stop the command before its output
    fs::write(
        d.path().join("scan.csv"),
        (0..40)
            .map(|i| format!("{},{}\n", f64::from(i) * 0.1, (f64::from(i) * 0.1).sin()))
            .collect::<String>(),
    )
    .unwrap();
    let mut child = std::process::Command::new(bin)
        .args(["fit", "scan.csv", "--tolerance", "0.01", "-o", "fit.json"])
        .current_dir(d.path())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    let status = child.wait().unwrap();
    assert!(
        status.success(),
        "fit with a closed standard error: {status}"
    );
    assert!(d.path().join("fit.json").exists(), "the fit was written");
}
