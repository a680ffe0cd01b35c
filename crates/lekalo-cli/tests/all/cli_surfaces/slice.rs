//! `lekalo slice` and `lekalo knot insert --axis` on splines in N parameters: the sliced
//! spline is the original with the fixed parameters put in, the refined one the same
//! spline, a NURBS stays rational, a surface's slice is its iso-curve, and each mistake of
//! `--fix`/`--axis` exits with 2 naming the option.

use std::fs;
use std::path::Path;

use assert_cmd::Command;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// A NURBS in three variables, degrees 2, 1, 3 with an interior knot in each direction,
/// irregular control values of dimension 2 and weights that are not all equal.
fn nurbs_tensor(d: &Path) {
    let knots = [
        vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0],
        vec![-1.0, -1.0, 0.5, 2.0, 2.0],
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 1.0, 1.0, 1.0, 1.0],
    ];
    let shape = [4usize, 3, 5];
    let n: usize = shape.iter().product();
    let control: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let i = i as f64;
            [((i * 1.7).sin() * 3.0).round() / 2.0, (i * 0.37) % 1.3]
        })
        .collect();
    let weights: Vec<f64> = (0..n).map(|i| 1.0 + ((i * 7) % 5) as f64 / 4.0).collect();
    let j = serde_json::json!({"lekalo": 1, "type": "nurbs_tensor", "degrees": [2, 1, 3],
        "knots": knots, "shape": shape, "control": control, "weights": weights});
    fs::write(d.join("t.json"), j.to_string()).unwrap();
}

/// `lekalo eval FILE --at …` as rows of values (the columns after the parameters).
fn eval(d: &Path, file: &str, points: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let at: Vec<String> = points.iter().flatten().map(f64::to_string).collect();
    let out = lekalo()
        .current_dir(d)
        .args(["eval", file, "--at", &at.join(","), "--format", "json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let e: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let n = points[0].len();
    e["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array().unwrap()[n..]
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect()
        })
        .collect()
}

fn close(a: &[Vec<f64>], b: &[Vec<f64>]) {
    for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
        assert!((x - y).abs() <= 1e-13 * (1.0 + y.abs()), "{a:?} vs {b:?}");
    }
}

const POINTS: [[f64; 3]; 4] = [
    [0.1, -0.7, 0.2],
    [0.55, 0.5, 0.9],
    [0.93, 1.8, 0.31],
    [0.4, 1.2, 0.0],
];

#[test]
fn a_slice_is_the_spline_with_the_fixed_parameter_put_in() {
    let d = tempfile::tempdir().unwrap();
    nurbs_tensor(d.path());
    lekalo()
        .current_dir(d.path())
        .args(["slice", "t.json", "--fix", "2=0.75", "-o", "plane.json"])
        .assert()
        .success();
    let plane: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("plane.json")).unwrap()).unwrap();
    assert_eq!(plane["type"], "nurbs_tensor");
    assert_eq!(plane["degrees"], serde_json::json!([2, 3]));
    let full: Vec<Vec<f64>> = POINTS.iter().map(|p| vec![p[0], 0.75, p[2]]).collect();
    let free: Vec<Vec<f64>> = POINTS.iter().map(|p| vec![p[0], p[2]]).collect();
    close(
        &eval(d.path(), "plane.json", &free),
        &eval(d.path(), "t.json", &full),
    );
    // two fixed: a curve-like spline in one parameter, written as SciPy's arrays
    lekalo()
        .current_dir(d.path())
        .args([
            "slice", "t.json", "--fix", "3=0.3", "--fix", "1=0.2", "-o", "line.npz",
        ])
        .assert()
        .success();
    let full: Vec<Vec<f64>> = POINTS.iter().map(|p| vec![0.2, p[1], 0.3]).collect();
    let free: Vec<Vec<f64>> = POINTS.iter().map(|p| vec![p[1]]).collect();
    close(
        &eval(d.path(), "line.npz", &free),
        &eval(d.path(), "t.json", &full),
    );
}

#[test]
fn knot_insertion_along_a_direction_keeps_the_spline() {
    let d = tempfile::tempdir().unwrap();
    nurbs_tensor(d.path());
    lekalo()
        .current_dir(d.path())
        .args([
            "knot", "insert", "t.json", "--axis", "3", "--at", "0.6", "--times", "2",
        ])
        .args(["-o", "refined.json"])
        .assert()
        .success();
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("refined.json")).unwrap()).unwrap();
    assert_eq!(r["shape"], serde_json::json!([4, 3, 7]));
    assert_eq!(
        r["knots"][2],
        serde_json::json!([0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 0.6, 1.0, 1.0, 1.0, 1.0])
    );
    let pts: Vec<Vec<f64>> = POINTS.iter().map(|p| p.to_vec()).collect();
    close(
        &eval(d.path(), "refined.json", &pts),
        &eval(d.path(), "t.json", &pts),
    );
}

#[test]
fn a_surface_slice_is_its_iso_curve() {
    let d = tempfile::tempdir().unwrap();
    fs::write(
        d.path().join("net.csv"),
        "0 0 0\n0 1 0\n0 2 1\n1 0 0\n1 1 2\n1 2 0\n2 0 1\n2 1 0\n2 2 0\n",
    )
    .unwrap();
    lekalo()
        .current_dir(d.path())
        .args([
            "make",
            "bspline-surface",
            "--control",
            "net.csv",
            "--net",
            "3x3",
        ])
        .args(["--degree", "2", "-o", "s.json"])
        .assert()
        .success();
    lekalo()
        .current_dir(d.path())
        .args(["slice", "s.json", "--fix", "v=0.3", "-o", "iso.json"])
        .assert()
        .success();
    let iso: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("iso.json")).unwrap()).unwrap();
    assert!(iso["type"].as_str().unwrap().ends_with("_curve"), "{iso}");
    // `lekalo eval FILE OPTION VALUE`'s first point, `x, y, z`
    let point = |file: &str, option: &str, value: &str| -> Vec<f64> {
        let out = lekalo()
            .current_dir(d.path())
            .args(["eval", file, option, value, "--format", "json"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let e: serde_json::Value = serde_json::from_slice(&out).unwrap();
        ["x", "y", "z"].map(|k| e[0][k].as_f64().unwrap()).to_vec()
    };
    for u in [0.0, 0.35, 1.0] {
        let c = point("iso.json", "--at", &u.to_string());
        let s = point("s.json", "--uv", &format!("{u},0.3"));
        // the iso-curve's evaluation is the surface's along v first: equal to rounding
        close(&[c], &[s]);
    }
}

#[test]
fn mistakes_name_the_option() {
    let d = tempfile::tempdir().unwrap();
    nurbs_tensor(d.path());
    for (args, says) in [
        (
            vec!["slice", "t.json", "--fix", "4=0.5"],
            "directions run from 1 to 3",
        ),
        (vec!["slice", "t.json", "--fix", "0=0.5"], "count from 1"),
        (
            vec!["slice", "t.json", "--fix", "2=0.5", "--fix", "2=1"],
            "fixed twice",
        ),
        (
            vec![
                "slice", "t.json", "--fix", "1=0", "--fix", "2=0", "--fix", "3=0",
            ],
            "lekalo eval",
        ),
        (
            vec!["slice", "t.json", "--fix", "1=1.5"],
            "--fix: parameter 1.5",
        ),
        (vec!["slice", "t.json", "--fix", "1"], "K=X"),
        (
            vec!["knot", "insert", "t.json", "--axis", "4", "--at", "0.5"],
            "--axis 4",
        ),
        (
            vec!["knot", "refine", "t.json", "--knots", "0.5"],
            "knot insert --axis",
        ),
    ] {
        lekalo()
            .current_dir(d.path())
            .args(&args)
            .assert()
            .code(2)
            .stderr(contains(says));
    }
}
