//! End-to-end tests of `lekalo bezier` (document 004).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use crate::common;

use std::fs;

use common::lekalo;
use predicates::str::contains;

/// Document 004, Example 2: a formally quintic cubic.
const QUINTIC: &str = r#"{"lekalo": 1, "type": "bezier_curve",
 "control": [[10, 0], [22, 6], [19, 12], [11, 15], [8, 12], [20, 0]]}"#;

fn setup() -> tempfile::TempDir {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("quintic.json"), QUINTIC).unwrap();
    let mut net = String::new();
    for i in 0..4 {
        for j in 0..4 {
            net.push_str(&format!("{i} {j} {}\n", (i * j) % 3));
        }
    }
    fs::write(d.path().join("net.txt"), net).unwrap();
    d
}

#[test]
fn help_has_examples() {
    for op in ["elevate", "reduce", "real-degree", "change"] {
        lekalo()
            .args(["bezier", op, "--help"])
            .assert()
            .success()
            .stdout(contains("Examples:"));
    }
}

#[test]
fn example_2_real_degree_reduce_and_refusal() {
    let d = setup();
    let q = d.path().join("quintic.json");
    lekalo()
        .args(["bezier", "real-degree"])
        .arg(&q)
        .assert()
        .success()
        .stdout("degree 5\nreal degree 3\ndefect 2\n");
    let out = lekalo()
        .args(["bezier", "reduce"])
        .arg(&q)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let want = [[10.0, 0.0], [30.0, 10.0], [0.0, 20.0], [20.0, 0.0]];
    for (i, w) in want.iter().enumerate() {
        for k in 0..2 {
            let got = v["control"][i][k].as_f64().unwrap();
            assert!((got - w[k]).abs() < 1e-12, "{i} {k}: {got}");
        }
    }
    lekalo()
        .args(["bezier", "change", "--degree", "2"])
        .arg(&q)
        .assert()
        .code(2)
        .stderr(contains("real degree is 3"));
    // approximate reduction below the real degree: shape changes, deviation printed
    lekalo()
        .args(["bezier", "reduce", "--approx", "2"])
        .arg(&q)
        .assert()
        .success()
        .stdout(contains("bezier_curve"))
        .stderr(contains("max deviation"));
    lekalo()
        .args(["bezier", "change", "--degree", "4"])
        .arg(&q)
        .assert()
        .success()
        .stdout(contains("bezier_curve"));
    let out = lekalo()
        .args(["bezier", "elevate", "--by", "2"])
        .arg(&q)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(v["control"].as_array().unwrap().len(), 8);
    let svg = d.path().join("e.svg");
    lekalo()
        .args(["bezier", "elevate"])
        .arg(&q)
        .arg("-o")
        .arg(&svg)
        .assert()
        .success();
    assert!(fs::read_to_string(svg).unwrap().contains("<svg"));
}

#[test]
fn surfaces() {
    let d = setup();
    let net = d.path().join("net.txt");
    let surf = |args: &[&str]| {
        lekalo()
            .arg("bezier")
            .args(args)
            .arg("--surface")
            .arg(&net)
            .args(["--net", "4x4"])
            .assert()
    };
    surf(&["real-degree"])
        .success()
        .stdout(contains("degrees 3 3\n"));
    let elevated = surf(&["elevate", "--by", "1,2"])
        .success()
        .stdout(contains("\"type\": \"bezier_surface\""))
        .stdout(contains("\"net\": [5, 6]"))
        .get_output()
        .stdout
        .clone();
    // the bezier_surface object is read back as input, and its real degrees are still (3, 3)
    let obj = d.path().join("elevated.json");
    fs::write(&obj, elevated).unwrap();
    lekalo()
        .args(["bezier", "real-degree"])
        .arg(&obj)
        .assert()
        .success()
        .stdout("degrees 4 5\nreal degrees 3 3\ndefects 1 2\n");
    lekalo()
        .args(["bezier", "change", "--degree", "3,3", "--to", "obj"])
        .arg(&obj)
        .assert()
        .success()
        .stdout(contains("vn "));
    surf(&["change", "--degree", "3,5", "--to", "step"])
        .success()
        .stdout(contains("B_SPLINE_SURFACE_WITH_KNOTS"));
    surf(&["reduce"])
        .success()
        .stdout(contains("\"net\": [4, 4]"));
    surf(&["change", "--degree", "2,3"])
        .code(2)
        .stderr(contains("real degree is 3"));
}

#[test]
fn bad_input_exit_code_2_names_the_problem() {
    let d = setup();
    let q = d.path().join("quintic.json");
    let net = d.path().join("net.txt");
    lekalo()
        .args(["bezier", "real-degree"])
        .assert()
        .code(2)
        .stderr(contains("no input"));
    lekalo()
        .args(["bezier", "elevate", "--by", "1,2"])
        .arg(&q)
        .assert()
        .code(2)
        .stderr(contains("--by: give one number for a curve"));
    lekalo()
        .args(["bezier", "elevate", "--by", "x"])
        .arg(&q)
        .assert()
        .code(2)
        .stderr(contains("--by"));
    lekalo()
        .args(["bezier", "reduce", "--surface"])
        .arg(&net)
        .args(["--net", "3x4"])
        .assert()
        .code(2)
        .stderr(contains("error:"));
    let bs = d.path().join("bs.json");
    fs::write(
        &bs,
        r#"{"lekalo":1,"type":"bspline_curve","degree":1,"knots":[0,0,1,1],"control":[[0,0],[1,1]]}"#,
    )
    .unwrap();
    lekalo()
        .args(["bezier", "reduce"])
        .arg(&bs)
        .assert()
        .code(2)
        .stderr(contains("takes a Bezier curve"));
    // B-spline curves can be elevated
    lekalo()
        .args(["bezier", "elevate", "--by", "2"])
        .arg(&bs)
        .assert()
        .success()
        .stdout(contains("\"degree\": 3"));
    let nurbs = d.path().join("n.json");
    fs::write(
        &nurbs,
        r#"{"lekalo":1,"type":"nurbs_curve","degree":1,"knots":[0,0,1,1],"control":[[0,0],[1,1]],"weights":[1,2]}"#,
    )
    .unwrap();
    lekalo()
        .args(["bezier", "elevate"])
        .arg(&nurbs)
        .assert()
        .code(2)
        .stderr(contains("NURBS curve"));
    lekalo()
        .args(["bezier", "reduce", "--approx", "2", "--ends", "tangents"])
        .arg(&q)
        .assert()
        .code(2)
        .stderr(contains("degree"));
}

// The control points as a points file (CSV with a header, text, JSON list) give the same results,
// bit for bit, as the bezier_curve object.
#[test]
fn control_points_file_as_input() {
    let d = setup();
    let files = [
        ("q.csv", "x,y\n10,0\n22,6\n19,12\n11,15\n8,12\n20,0\n"),
        ("q.txt", "10 0\n22 6\n19 12\n11 15\n8 12\n20 0\n"),
        (
            "q.points.json",
            "[[10, 0], [22, 6], [19, 12], [11, 15], [8, 12], [20, 0]]",
        ),
    ];
    let q = d.path().join("quintic.json");
    for op in [
        &["bezier", "real-degree", "--json"][..],
        &["bezier", "reduce"],
        &["bezier", "elevate", "--by", "2"],
    ] {
        let want = common::stdout_of(op, Some(&q));
        for (name, text) in files {
            let p = d.path().join(name);
            fs::write(&p, text).unwrap();
            assert_eq!(common::stdout_of(op, Some(&p)), want, "{op:?} {name}");
        }
    }
    let one = d.path().join("one.csv");
    fs::write(&one, "").unwrap();
    lekalo()
        .args(["bezier", "real-degree"])
        .arg(&one)
        .assert()
        .code(2)
        .stderr(contains("one.csv"));
}
