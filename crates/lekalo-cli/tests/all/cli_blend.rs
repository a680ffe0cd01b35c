//! End-to-end tests of `lekalo blend` (document 001).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use assert_cmd::Command;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

fn setup() -> tempfile::TempDir {
    let d = tempfile::tempdir().unwrap();
    let files = [
        (
            "up.json",
            r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0],[1,2],[2,0]]}"#,
        ),
        (
            "down.json",
            r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0],[1,-2],[2,0]]}"#,
        ),
        (
            "arc.json",
            r#"{"lekalo":1,"type":"nurbs_curve","degree":2,"knots":[0,0,0,1,1,1],
                "control":[[0,0],[1,1],[2,0]],"weights":[1,0.7071067811865476,1]}"#,
        ),
        (
            "far.json",
            r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0],[1,2],[3,0]]}"#,
        ),
        (
            "a.json",
            r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0],[2,0]]}"#,
        ),
        (
            "b.json",
            r#"{"lekalo":1,"type":"bezier_curve","control":[[2,0],[2,2]]}"#,
        ),
        ("pts.txt", "0 0\n1 1\n2 1.2\n3 1\n4 0\n5 -1\n"),
        (
            "hexagon.txt",
            "1 0\n0.5 0.87\n-0.5 0.87\n-1 0\n-0.5 -0.87\n0.5 -0.87\n",
        ),
    ];
    for (n, t) in files {
        fs::write(d.path().join(n), t).unwrap();
    }
    d
}

#[test]
fn help_has_examples() {
    for op in ["deform", "spline", "corner", "corners"] {
        lekalo()
            .args(["blend", op, "--help"])
            .assert()
            .success()
            .stdout(contains("Examples:"));
    }
}

#[test]
fn deform_exact_bezier_and_nurbs() {
    let d = setup();
    let f = |n: &str| d.path().join(n);
    let out = lekalo()
        .args(["blend", "deform", "-k", "2"])
        .arg(f("up.json"))
        .arg(f("down.json"))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(v["type"], "bezier_curve");
    // degree (2k − 1) + 2 = 5
    assert_eq!(v["control"].as_array().unwrap().len(), 6);
    lekalo()
        .args(["blend", "deform", "-k", "1"])
        .arg(f("up.json"))
        .arg(f("arc.json"))
        .assert()
        .success()
        .stdout(contains("nurbs_curve"));
}

#[test]
fn spline_every_local_kind_open_and_closed() {
    let d = setup();
    let (pts, hexagon) = (d.path().join("pts.txt"), d.path().join("hexagon.txt"));
    for (local, ty) in [
        ("parabolas", "nurbs_curve"),
        ("rational-arcs", "nurbs_curve"),
        ("arcs", "bspline_curve"),
        ("global-arcs", "bspline_curve"),
    ] {
        for closed in [false, true] {
            let mut c = lekalo();
            c.args([
                "blend", "spline", "-k", "2", "--params", "chord", "--local", local,
            ]);
            if closed {
                c.arg("--closed").arg(&hexagon);
            } else {
                c.arg(&pts);
            }
            c.assert().success().stdout(contains(ty));
        }
    }
    lekalo()
        .args(["blend", "spline", "--params", "chord", "--to", "svg"])
        .arg(&pts)
        .assert()
        .success()
        .stdout(contains("data points"));
}

#[test]
fn corner_transition() {
    let d = setup();
    let out = lekalo()
        .args([
            "blend", "corner", "--from", "0.5", "--until", "0.5", "-k", "2",
        ])
        .arg(d.path().join("a.json"))
        .arg(d.path().join("b.json"))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(v["control"].as_array().unwrap().len(), 9); // degree 4k = 8
}

#[test]
fn bad_input_exit_code_2_names_the_problem() {
    let d = setup();
    let f = |n: &str| d.path().join(n);
    lekalo()
        .args(["blend", "deform"])
        .arg(f("up.json"))
        .arg(f("far.json"))
        .assert()
        .code(2)
        .stderr(contains("end point"));
    // the library's error about the continuity is written with the option that sets it
    lekalo()
        .args(["blend", "deform", "-k", "0"])
        .arg(f("up.json"))
        .arg(f("down.json"))
        .assert()
        .code(2)
        .stderr(contains(
            "error: --continuity: got 0; k must be in 1..=1025 (k = 1 is the linear blend; \
             the deformation uses w_(k-1))",
        ));
    lekalo()
        .args(["blend", "corner", "--from", "1.5", "--until", "0.5"])
        .arg(f("a.json"))
        .arg(f("b.json"))
        .assert()
        .code(2)
        .stderr(contains("window"));
    lekalo()
        .args(["blend", "corner", "--from", "x", "--until", "0.5"])
        .arg(f("a.json"))
        .arg(f("b.json"))
        .assert()
        .code(2)
        .stderr(contains("--from: value 1"));
    let two = f("two.txt");
    fs::write(&two, "0 0\n").unwrap();
    lekalo()
        .args(["blend", "spline"])
        .arg(&two)
        .assert()
        .code(2)
        .stderr(contains("spline points"));
    // a rational quadratic arc must be shorter than a half circle
    let turn = f("turn.txt");
    fs::write(&turn, "0 0\n1 2\n3 2.5\n4 0.5\n6 1\n").unwrap();
    lekalo()
        .args(["blend", "spline", "--closed", "--local", "rational-arcs"])
        .arg(&turn)
        .assert()
        .code(2)
        .stderr(contains("shorter than 180°"));
}
