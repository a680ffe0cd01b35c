//! End-to-end tests of `lekalo pp` (document 003).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use crate::common;

use std::fs;

use common::lekalo;
use predicates::str::contains;

const LECTURE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2,
 "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[1, 1], [2, 3], [4, 3], [5, 0]]}"#;

const THESIS: [&str; 6] = [
    "--breakpoints",
    "0,0.5,0.9,1.4,2.1,2.7,3",
    "--order",
    "3",
    "--continuity",
    "2,2,2,2,2",
];

#[test]
fn help_has_examples() {
    for op in ["convert", "quasi"] {
        lekalo()
            .args(["pp", op, "--help"])
            .assert()
            .success()
            .stdout(contains("Examples:"));
    }
}

#[test]
fn quasi_reproduces_the_thesis_error() {
    lekalo()
        .args(["pp", "quasi", "--function", "x*cos(x)"])
        .args(THESIS)
        .args(["--rule", "left-end-of-support"])
        .assert()
        .success()
        .stdout(contains("bspline_curve"))
        .stderr(contains("0.204831"));
    let d = tempfile::tempdir().unwrap();
    let svg = d.path().join("fig1.svg");
    lekalo()
        .args(["pp", "quasi", "--function", "x*cos(x)"])
        .args(THESIS)
        .arg("-o")
        .arg(&svg)
        .assert()
        .success();
    assert!(fs::read_to_string(svg).unwrap().contains("f(x)"));
    for f in ["sin", "cos", "exp", "runge"] {
        lekalo()
            .args([
                "pp",
                "quasi",
                "--function",
                f,
                "--breakpoints",
                "0,1,2",
                "--order",
                "4",
            ])
            .assert()
            .success();
    }
}

#[test]
fn convert_round_trip() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("c.json");
    fs::write(&c, LECTURE).unwrap();
    let pp = d.path().join("c.pp.json");
    lekalo()
        .args(["pp", "convert"])
        .arg(&c)
        .arg("-o")
        .arg(&pp)
        .assert()
        .success();
    let text = fs::read_to_string(&pp).unwrap();
    assert!(text.contains("piecewise_polynomial"), "{text}");
    let out = lekalo()
        .args(["pp", "convert", "--continuity", "2"])
        .arg(&pp)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let want = [[1.0, 1.0], [2.0, 3.0], [4.0, 3.0], [5.0, 0.0]];
    for (i, w) in want.iter().enumerate() {
        for k in 0..2 {
            let got = v["control"][i][k].as_f64().unwrap();
            assert!((got - w[k]).abs() < 1e-12, "{i} {k}: {got}");
        }
    }
}

#[test]
fn bad_input_exit_code_2_names_the_problem() {
    lekalo()
        .args([
            "pp",
            "quasi",
            "--function",
            "x*cos(x)",
            "--breakpoints",
            "0,2,1",
        ])
        .assert()
        .code(2)
        .stderr(contains("error:"));
    lekalo()
        .args([
            "pp",
            "quasi",
            "--function",
            "x*cos(x)",
            "--breakpoints",
            "0,1,2",
        ])
        .args(["--continuity", "2,2"])
        .assert()
        .code(2)
        .stderr(contains("--continuity: 2 values given"));
    lekalo()
        .args(["pp", "quasi", "--function", "tan", "--breakpoints", "0,1"])
        .assert()
        .code(2)
        .stderr(contains("tan"));
    // a function undefined at a breakpoint: where, why, and the fix, under the option
    lekalo()
        .args([
            "pp",
            "quasi",
            "--function",
            "log(x)",
            "--breakpoints",
            "0,1,2",
        ])
        .assert()
        .code(2)
        .stderr(contains(
            "error: --function: undefined at x = 0: ln of 0 (a logarithm needs a positive \
             argument); quasi-interpolation evaluates f on the whole range of the breakpoints, \
             [0, 2] (f and its derivatives up to order 2 at the points τ, f where the error is \
             measured): choose breakpoints where f is defined, or another f",
        ));
    let d = tempfile::tempdir().unwrap();
    let bad = d.path().join("bad.pp.json");
    fs::write(
        &bad,
        r#"{"lekalo":1,"type":"piecewise_polynomial","breakpoints":[0,1],"order":2,"dim":1,"coefficients":[1]}"#,
    )
    .unwrap();
    lekalo()
        .args(["pp", "convert"])
        .arg(&bad)
        .assert()
        .code(2)
        .stderr(contains("coefficients"));
    let nurbs = d.path().join("n.json");
    fs::write(
        &nurbs,
        r#"{"lekalo":1,"type":"nurbs_curve","degree":1,"knots":[0,0,1,1],"control":[[0,0],[1,1]],"weights":[1,2]}"#,
    )
    .unwrap();
    lekalo()
        .args(["pp", "convert"])
        .arg(&nurbs)
        .assert()
        .code(2)
        .stderr(contains("rational"));
}

// A quadratic B-spline with a double knot at 1 (only C⁰ there) and a simple knot at 2.
const KINKED: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2,
 "knots": [0, 0, 0, 1, 1, 2, 3, 3, 3], "control": [[0, 0], [1, 2], [2, 0], [3, 1], [4, 4], [5, 0]]}"#;

fn curve_json(args: &[&str], input: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&common::stdout_of(args, Some(input))).unwrap()
}

// Without --continuity, pp → B-spline infers ν (1 at the kink, 2 at the simple knot, as `info`
// reports) and gives back the original knots and control points.
#[test]
fn convert_infers_continuity() {
    let d = common::dir_with(&[("c.json", KINKED)]);
    let pp = common::p(&d, "c.pp.json");
    lekalo()
        .args(["pp", "convert"])
        .arg(common::p(&d, "c.json"))
        .arg("-o")
        .arg(&pp)
        .assert()
        .success();
    let info = curve_json(&["info", "--json"], &pp);
    let m: Vec<u64> = info["continuity"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["continuous_derivatives"].as_u64().unwrap())
        .collect();
    assert_eq!(m, [1, 2]);
    let v = curve_json(&["pp", "convert"], &pp);
    assert_eq!(
        v["knots"],
        serde_json::json!([0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0])
    );
    let want = [[0, 0], [1, 2], [2, 0], [3, 1], [4, 4], [5, 0]];
    for (i, w) in want.iter().enumerate() {
        for k in 0..2 {
            let got = v["control"][i][k].as_f64().unwrap();
            assert!((got - f64::from(w[k])).abs() < 1e-12, "{i} {k}: {got}");
        }
    }
}

// Explicit τ values: the first-interval-midpoint rule's points given by hand give the same curve,
// bit for bit; a wrong count or a value outside its support is refused, naming it.
#[test]
fn explicit_tau_values() {
    let d = tempfile::tempdir().unwrap();
    let base = [
        "pp",
        "quasi",
        "--function",
        "sin",
        "--breakpoints",
        "0,1,2",
        "--order",
        "3",
    ];
    let run = |extra: &[&str]| common::stdout_of(&[&base[..], extra, &["-q"]].concat(), None);
    // knots 0 0 0 1 2 2 2: first non-empty intervals (0,1) (0,1) (0,1) (1,2)
    let by_rule = run(&["--rule", "first-interval-midpoint"]);
    let by_values = run(&["--tau", "0.5,0.5,0.5,1.5"]);
    assert_eq!(by_rule, by_values);
    let file = d.path().join("tau.txt");
    fs::write(&file, "0.5\n0.5\n0.5\n1.5\n").unwrap();
    assert_eq!(run(&["--tau", file.to_str().unwrap()]), by_rule);
    assert_ne!(run(&["--rule", "greville"]), by_rule);
    lekalo()
        .args(base)
        .args(["--tau", "0.5,0.5,0.5"])
        .assert()
        .code(2)
        .stderr(contains("τ values"))
        .stderr(contains("4"));
    lekalo()
        .args(base)
        .args(["--tau", "1.5,0.5,0.5,1.5"]) // b_1's support is [0, 1]
        .assert()
        .code(2)
        .stderr(contains("τ number 1 is 1.5"));
    lekalo()
        .args(base)
        .args(["--tau", "0.5,0.5,0.5,1.5", "--rule", "midpoint"])
        .assert()
        .code(2)
        .stderr(contains("--rule"));
}
