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

/// A quadratic B-spline curve of two pieces and the 3×3 biquadratic dome as a B-spline surface.
const BSPLINE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2,
 "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[0, 0], [1, 2], [3, 2], [4, 0]]}"#;
const DOME: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 2, "degree_v": 2,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1], "net": [3, 3],
 "control": [[0, 0, 0], [0, 1, 0], [0, 2, 0], [1, 0, 0], [1, 1, 1], [1, 2, 0], [2, 0, 0],
  [2, 1, 0], [2, 2, 0]]}"#;

/// B-spline curves and surfaces: elevated and changed to a degree (the library's
/// `elevate_degree`/`change_degree` of each), a curve reduced approximately; the real degree
/// stays a Bezier notion, refused with what to do instead.
#[test]
fn bspline_curves_and_surfaces_change_degree() {
    let d = setup();
    let curve = d.path().join("curve.json");
    let dome = d.path().join("dome.json");
    fs::write(&curve, BSPLINE).unwrap();
    fs::write(&dome, DOME).unwrap();
    let json = |args: &[&str], input: &std::path::Path| {
        let out = lekalo()
            .arg("bezier")
            .args(args)
            .arg(input)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        serde_json::from_slice::<serde_json::Value>(&out).unwrap()
    };
    let up = json(&["elevate", "--by", "1,2"], &dome);
    assert_eq!(
        (up["degree_u"].as_u64(), up["degree_v"].as_u64()),
        (Some(3), Some(4))
    );
    let up_file = d.path().join("up.json");
    fs::write(&up_file, up.to_string()).unwrap();
    let back = json(&["change", "--degree", "2,2"], &up_file);
    for (a, b) in back["control"].as_array().unwrap().iter().zip(DOME_CONTROL) {
        for (x, y) in a.as_array().unwrap().iter().zip(b) {
            assert!((x.as_f64().unwrap() - y).abs() < 1e-12, "{back}");
        }
    }
    lekalo()
        .args(["bezier", "change", "--degree", "1,2"])
        .arg(&up_file)
        .assert()
        .code(2)
        .stderr(contains("real degree is 2"));
    let cubic = json(&["change", "--degree", "3"], &curve);
    assert_eq!(cubic["degree"], 3);
    let cubic_file = d.path().join("cubic.json");
    fs::write(&cubic_file, cubic.to_string()).unwrap();
    assert_eq!(json(&["change", "--degree", "2"], &cubic_file)["degree"], 2);
    let reduced = json(&["reduce", "--approx", "2", "--json"], &cubic_file);
    assert_eq!(reduced["curve"]["degree"], 2);
    assert!(
        reduced["max_deviation_sampled"].as_f64().unwrap() < 1e-12,
        "{reduced}"
    );
    lekalo()
        .args(["bezier", "reduce", "--approx", "1", "--ends", "free"])
        .arg(&cubic_file)
        .assert()
        .code(2)
        .stderr(contains("free ends would tear the 2 pieces"));
    lekalo()
        .args(["bezier", "real-degree"])
        .arg(&dome)
        .assert()
        .code(2)
        .stderr(contains("knot decompose"));
}

const DOME_CONTROL: [[f64; 3]; 9] = [
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 2.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 1.0],
    [1.0, 2.0, 0.0],
    [2.0, 0.0, 0.0],
    [2.0, 1.0, 0.0],
    [2.0, 2.0, 0.0],
];

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
        .stderr(contains("the real degree is defined for one Bezier piece"));
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
