//! End-to-end tests of the geometric-query subcommands: measure, project, intersect, mesh.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use predicates::str::contains;

mod common;
use common::{dir_with, lekalo, p};

/// A polyline (0,0) → (3,4) → (3,0): length 9.
const POLY: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 2, 2], "control": [[0, 0], [3, 4], [3, 0]]}"#;
/// The line y = 1 from x = −2 to 4.
const LINE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 1], "control": [[-2, 1], [4, 1]]}"#;
/// A cubic with a loop.
const LOOP: &str =
    r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [3, 2], [-1, 2], [2, 0]]}"#;
/// z = x² over [0, 1]², bilinear in y.
const SURFACE: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 2, "degree_v": 1,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "net": [3, 2],
 "control": [[0, 0, 0], [0, 1, 0], [0.5, 0, 0], [0.5, 1, 0], [1, 0, 1], [1, 1, 1]]}"#;

#[test]
fn measure_length_and_inverse() {
    let d = dir_with(&[("poly.json", POLY)]);
    let out = lekalo()
        .args(["measure", "--json", "--at-length", "5,7"])
        .arg(p(&d, "poly.json"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((j["length"].as_f64().unwrap() - 9.0).abs() < 1e-13);
    // length 7 is 2 along the second leg of length 4: t = 1.5
    assert!((j["at_length"][1]["t"].as_f64().unwrap() - 1.5).abs() < 1e-12);
    assert_eq!(j["bounding_box"]["max"][1].as_f64().unwrap(), 4.0);
    // a length beyond the curve is bad input
    lekalo()
        .args(["measure", "--at-length", "10"])
        .arg(p(&d, "poly.json"))
        .assert()
        .code(2)
        .stderr(contains("arc length"));
}

#[test]
fn project_single_batch_and_all() {
    let d = dir_with(&[("poly.json", POLY), ("q.csv", "3.5,2\n-1,-1\n")]);
    lekalo()
        .args(["project", "--point", "4,2"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stdout(contains("0,1.5,3,2,1\n"));
    let out = lekalo()
        .args(["project", "--json", "--points"])
        .arg(p(&d, "q.csv"))
        .arg(p(&d, "poly.json"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j.as_array().unwrap().len(), 2);
    assert!((j[1]["distance"].as_f64().unwrap() - 2f64.sqrt()).abs() < 1e-14);
    lekalo()
        .args(["project", "--point", "nan,1"])
        .arg(p(&d, "poly.json"))
        .assert()
        .code(2);
}

#[test]
fn intersect_pairs_self_and_plane() {
    let d = dir_with(&[
        ("poly.json", POLY),
        ("line.json", LINE),
        ("loop.json", LOOP),
    ]);
    let out = lekalo()
        .args(["intersect", "--json"])
        .arg(p(&d, "poly.json"))
        .arg(p(&d, "line.json"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let hits = j.as_array().unwrap();
    assert_eq!(hits.len(), 2, "{j}");
    assert!((hits[0]["point"][0].as_f64().unwrap() - 0.75).abs() < 1e-12);
    lekalo()
        .args(["intersect", "--self"])
        .arg(p(&d, "loop.json"))
        .assert()
        .success()
        .stdout(contains("point,"));
    lekalo()
        .args(["intersect", "--plane", "0,2,0,1"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stdout(contains("point,"));
    lekalo()
        .arg("intersect")
        .arg(p(&d, "poly.json"))
        .assert()
        .code(2)
        .stderr(contains("second curve"));
}

#[test]
fn mesh_writes_obj_stl_and_reports_the_bound() {
    let d = dir_with(&[("s.json", SURFACE), ("poly.json", POLY)]);
    lekalo()
        .args(["mesh", "--tolerance", "1e-3", "-o"])
        .arg(p(&d, "s.obj"))
        .arg(p(&d, "s.json"))
        .assert()
        .success();
    let obj = fs::read_to_string(p(&d, "s.obj")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), 32);
    lekalo()
        .args(["mesh", "--tolerance", "1e-3", "-o"])
        .arg(p(&d, "s.stl"))
        .arg(p(&d, "s.json"))
        .assert()
        .success();
    assert!(fs::read_to_string(p(&d, "s.stl"))
        .unwrap()
        .starts_with("solid lekalo"));
    let out = lekalo()
        .args(["mesh", "--json", "--tolerance", "1e-3"])
        .arg(p(&d, "s.json"))
        .output()
        .unwrap();
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(j["deviation"].as_f64().unwrap() <= 1e-3);
    lekalo()
        .args(["mesh", "--tolerance", "0"])
        .arg(p(&d, "s.json"))
        .assert()
        .code(2);
    lekalo()
        .args(["mesh", "--tolerance", "0.01"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stdout(contains("l 1 2 3"));
}
