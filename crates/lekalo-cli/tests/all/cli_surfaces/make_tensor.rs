//! `make bspline-tensor` and `make nurbs-tensor`: splines in N parameters from their control
//! net, read back by `eval`, `info` and `convert`, and their errors (exit code 2, naming the
//! option).

use std::fs;
use std::path::{Path, PathBuf};

use predicates::str::contains;

use super::lekalo;

/// The net's size in each direction.
const SHAPE: [usize; 3] = [3, 2, 4];

/// Control point `(i, j, k)` of the test net: two values that no multilinear function of the
/// indices gives.
fn point(i: usize, j: usize, k: usize) -> [f64; 2] {
    let (x, y, z) = (i as f64, j as f64, k as f64);
    [(1.0 + x + 2.0 * y + 0.7 * z).sin(), x * y - z * z]
}

/// The net as rows `x,y`, the first direction slowest.
fn net_rows() -> String {
    let mut s = String::new();
    for i in 0..SHAPE[0] {
        for j in 0..SHAPE[1] {
            for k in 0..SHAPE[2] {
                let [a, b] = point(i, j, k);
                s.push_str(&format!("{a:?},{b:?}\n"));
            }
        }
    }
    s
}

/// The value at `x` of the piecewise multilinear interpolant of the net whose nodes in
/// direction `a` are at `nodes[a]` (for a degree-1 spline: its knots without the ends' copies):
/// in each direction the cell `[t_m, t_{m+1}]` holding the coordinate and the weights
/// `1 − s`, `s` of its ends, summed over the cell's 8 corners.
fn multilinear(nodes: &[Vec<f64>; 3], x: [f64; 3]) -> [f64; 2] {
    let cell = |t: &[f64], x: f64| {
        let m = (0..t.len() - 1)
            .find(|&m| x <= t[m + 1])
            .unwrap_or(t.len() - 2);
        let s = (x - t[m]) / (t[m + 1] - t[m]);
        [(m, 1.0 - s), (m + 1, s)]
    };
    let (ci, cj, ck) = (
        cell(&nodes[0], x[0]),
        cell(&nodes[1], x[1]),
        cell(&nodes[2], x[2]),
    );
    let mut out = [0.0; 2];
    for (i, wi) in ci {
        for (j, wj) in cj {
            for (k, wk) in ck {
                let p = point(i, j, k);
                for d in 0..2 {
                    out[d] += wi * wj * wk * p[d];
                }
            }
        }
    }
    out
}

/// Evaluation points inside the domain, on cell boundaries and at the corners.
const AT: [[f64; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [0.2, 0.7, 0.45],
    [0.5, 0.3, 1.0 / 3.0],
    [0.9, 0.15, 0.8],
    [1.0, 1.0, 1.0],
];

/// The rows `x1, x2, x3, y1, y2` of `eval --at` at [`AT`] of the spline `file`.
fn evaluated(file: &Path) -> Vec<Vec<f64>> {
    let (columns, rows) = crate::common::eval_at(file, &AT);
    assert_eq!(columns, serde_json::json!(["x1", "x2", "x3", "y1", "y2"]));
    rows
}

/// `lekalo make KIND --control net.csv --net 3x2x4 ARGS -o out`, which must succeed.
fn made(dir: &Path, kind: &str, args: &[&str], out: &str) -> PathBuf {
    let net = dir.join("net.csv");
    fs::write(&net, net_rows()).unwrap();
    let t = dir.join(out);
    lekalo()
        .args(["make", kind, "--control"])
        .arg(&net)
        .args(["--net", "3x2x4"])
        .args(args)
        .arg("-o")
        .arg(&t)
        .assert()
        .success();
    t
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

#[test]
fn a_degree_one_net_evaluates_as_its_multilinear_interpolant() {
    let d = tempfile::tempdir().unwrap();
    let t = made(d.path(), "bspline-tensor", &["--degree", "1"], "t.json");
    let text = fs::read_to_string(&t).unwrap();
    assert!(text.contains("\"type\": \"bspline_tensor\""), "{text}");
    assert!(text.contains("\"shape\": [3,2,4]"), "{text}");
    // clamped uniform knots of degree 1: the nodes at i / (n − 1)
    let uniform = |n: usize| (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    let nodes = [uniform(3), uniform(2), uniform(4)];
    for (row, x) in evaluated(&t).iter().zip(AT) {
        let want = multilinear(&nodes, x);
        assert!(
            close(&row[3..], &want, 1e-14),
            "at {x:?}: {row:?} vs {want:?}"
        );
    }
    lekalo()
        .arg("info")
        .arg(&t)
        .assert()
        .success()
        .stdout(contains(
            "type            B-spline in 3 variables (bspline_tensor)",
        ))
        .stdout(contains("degrees         1 × 1 × 1"))
        .stdout(contains("net             3 × 2 × 4 = 24 control points"))
        .stdout(contains("dimension       2"));
    let copy = d.path().join("copy.json");
    lekalo()
        .arg("convert")
        .arg(&t)
        .arg("-o")
        .arg(&copy)
        .assert()
        .success();
    assert_eq!(fs::read_to_string(&copy).unwrap(), text);
    // a .npy array of the net's shape, the value axis last, makes the same spline
    let flat: Vec<f64> = net_rows()
        .lines()
        .flat_map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()))
        .collect();
    let npy = d.path().join("net.npy");
    fs::write(&npy, super::tensor::npy(&[3, 2, 4, 2], &flat)).unwrap();
    let out = crate::common::output_of(
        lekalo()
            .args(["make", "bspline-tensor", "--control"])
            .arg(&npy)
            .args(["--net", "3x2x4", "--degree", "1"]),
    );
    assert_eq!(String::from_utf8(out).unwrap(), text);
}

#[test]
fn given_knots_and_degrees_per_direction_are_kept() {
    let d = tempfile::tempdir().unwrap();
    // direction 1's nodes at 0, 0.3, 1; direction 3 through --knots-in, at 0, 0.1, 0.5, 1
    let t = made(
        d.path(),
        "bspline-tensor",
        &[
            "--degree",
            "1",
            "--knots-u",
            "0,0,0.3,1,1",
            "--knots-in",
            "3=0,0,1/10,0.5,1,1",
        ],
        "t.json",
    );
    let nodes = [
        vec![0.0, 0.3, 1.0],
        vec![0.0, 1.0],
        vec![0.0, 0.1, 0.5, 1.0],
    ];
    for (row, x) in evaluated(&t).iter().zip(AT) {
        let want = multilinear(&nodes, x);
        assert!(
            close(&row[3..], &want, 1e-14),
            "at {x:?}: {row:?} vs {want:?}"
        );
    }
    // degrees per direction, a knot vector of degree 2 in direction 3
    let t = made(
        d.path(),
        "bspline-tensor",
        &["--degree", "2,1,2", "--knots-in", "3=0,0,0,0.25,1,1,1"],
        "q.json",
    );
    let j = crate::common::json_of(lekalo().arg("info").arg(&t).arg("--json"));
    assert_eq!(j["degrees"], serde_json::json!([2, 1, 2]));
    assert_eq!(
        j["knots"],
        serde_json::json!([
            [0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            [0.0, 0.0, 1.0, 1.0],
            [0.0, 0.0, 0.0, 0.25, 1.0, 1.0, 1.0]
        ])
    );
}

#[test]
fn a_nurbs_net_of_unit_weights_is_the_bspline() {
    let d = tempfile::tempdir().unwrap();
    let b = made(d.path(), "bspline-tensor", &["--degree", "2,1,3"], "b.json");
    let w = d.path().join("weights.txt");
    fs::write(&w, "1\n".repeat(24)).unwrap();
    let weights = w.to_str().unwrap();
    let n = made(
        d.path(),
        "nurbs-tensor",
        &["--degree", "2,1,3", "--weights", weights],
        "n.json",
    );
    let text = fs::read_to_string(&n).unwrap();
    assert!(text.contains("\"type\": \"nurbs_tensor\""), "{text}");
    let (rows_b, rows_n) = (evaluated(&b), evaluated(&n));
    for ((rb, rn), x) in rows_b.iter().zip(&rows_n).zip(AT) {
        assert!(close(rb, rn, 1e-14), "at {x:?}: {rb:?} vs {rn:?}");
    }
    // the weights as a list make the same file
    let ones = vec!["1"; 24].join(",");
    let listed = made(
        d.path(),
        "nurbs-tensor",
        &["--degree", "2,1,3", "--weights", &ones],
        "listed.json",
    );
    assert_eq!(fs::read_to_string(&listed).unwrap(), text);
    lekalo()
        .arg("info")
        .arg(&n)
        .assert()
        .success()
        .stdout(contains(
            "type            NURBS in 3 variables (nurbs_tensor)",
        ));
}

#[test]
fn a_net_of_two_sizes_is_the_surface_of_bspline_surface() {
    let d = tempfile::tempdir().unwrap();
    let net = d.path().join("net.csv");
    fs::write(
        &net,
        "0 0 0\n0 1 0\n0 2 0\n1 0 0\n1 1 1\n1 2 0\n2 0 0\n2 1 0\n2 2 0\n",
    )
    .unwrap();
    let make = |args: &[&str]| {
        crate::common::output_of(
            lekalo()
                .arg("make")
                .args(args)
                .arg("--control")
                .arg(&net)
                .args(["--net", "3x3"]),
        )
    };
    let surface = make(&["bspline-surface", "--degree", "2", "--degree-v", "1"]);
    assert!(String::from_utf8_lossy(&surface).contains("\"bspline_surface\""));
    assert_eq!(make(&["bspline-tensor", "--degree", "2,1"]), surface);
    assert_eq!(make(&["bspline-surface", "--degree", "2,1"]), surface);
    let w = "1,1,1,1,2,1,1,1,1";
    let nurbs = make(&["nurbs-surface", "--degree", "2", "--weights", w]);
    assert_eq!(
        make(&["nurbs-tensor", "--degree", "2", "--weights", w]),
        nurbs
    );
    // the weights as a file of one value a line, as for the splines in N parameters
    let file = d.path().join("w.txt");
    fs::write(&file, w.replace(',', "\n")).unwrap();
    let file = file.to_str().unwrap();
    assert_eq!(
        make(&["nurbs-surface", "--degree", "2", "--weights", file]),
        nurbs
    );
}

#[test]
fn bad_nets_exit_2_naming_the_option() {
    let d = tempfile::tempdir().unwrap();
    let net = d.path().join("net.csv");
    fs::write(&net, net_rows()).unwrap();
    let out = d.path().join("out.json");
    let fails = |args: &[&str], needle: &str| {
        lekalo()
            .arg("make")
            .args(args)
            .arg("--control")
            .arg(&net)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(2)
            .stderr(contains(needle));
        assert!(!out.exists(), "nothing written on a refusal: {args:?}");
    };
    fn tensor<'a>(extra: &[&'a str]) -> Vec<&'a str> {
        let mut v = vec!["bspline-tensor", "--net", "3x2x4", "--degree", "1"];
        v.extend_from_slice(extra);
        v
    }
    // the net's size and the rows
    fails(
        &["bspline-tensor", "--net", "3x2x3", "--degree", "1"],
        "--net 3x2x3: 18 control points, but",
    );
    fails(
        &["bspline-tensor", "--net", "3x0x4", "--degree", "1"],
        "--net",
    );
    fails(
        &["bspline-tensor", "--net", "24", "--degree", "1"],
        "make bspline`",
    );
    fails(&["bspline-tensor", "--degree", "1"], "needs --net");
    fails(
        &["bspline-tensor", "--net", "1000x1000x1000", "--degree", "1"],
        "--net 1000x1000x1000: 1000000000 control points, above the size limit 10000000",
    );
    fails(
        &[
            "--max-size",
            "10",
            "bspline-tensor",
            "--net",
            "3x2x4",
            "--degree",
            "1",
        ],
        "--net 3x2x4: 24 control points, above the size limit 10; give a smaller size, or raise the limit with --max-size 24",
    );
    fails(
        &[
            "bspline-tensor",
            "--net",
            "99999999999x99999999999x9999999",
            "--degree",
            "1",
        ],
        "overflows",
    );
    // degrees
    fails(&["bspline-tensor", "--net", "3x2x4"], "needs --degree");
    fails(
        &["bspline-tensor", "--net", "3x2x4", "--degree", "1,1"],
        "--degree: 2 degrees",
    );
    fails(
        &["bspline-tensor", "--net", "3x2x4", "--degree", "1,2,1"],
        "--degree: direction 2 has 2 control points",
    );
    fails(&tensor(&["--degree-v", "1"]), "--degree-v is for surfaces");
    fails(
        &["bspline", "--degree", "2,3"],
        "--degree: 2 degrees for a curve, which takes one",
    );
    // knots
    fails(
        &tensor(&["--knots-in", "3=0,0,1,1"]),
        "--knots-in 3: 4 knots for direction 3",
    );
    fails(
        &tensor(&["--knots-in", "3=0,0,0.6,0.4,1,1"]),
        "--knots-in 3 (direction 3)",
    );
    fails(
        &tensor(&["--knots-in", "3=0,0,0.5,nan,1,1"]),
        "--knots-in 3",
    );
    fails(&tensor(&["--knots-in", "4=0,0,1,1"]), "--knots-in 4");
    fails(
        &tensor(&["--knots-in", "0,0,1,1"]),
        "--knots-in: \"0,0,1,1\" is not K=LIST",
    );
    fails(
        &tensor(&["--knots-u", "0,0,0.5,1,1", "--knots-in", "1=0,0,0.5,1,1"]),
        "direction 1 already has knots from --knots-u",
    );
    fails(
        &tensor(&["--knots-v", "0,0,1"]),
        "--knots-v: 3 knots for direction 2",
    );
    fails(
        &tensor(&["--knots", "0,0,1,1"]),
        "--knots is a curve's knot vector",
    );
    fails(
        &[
            "bspline-surface",
            "--net",
            "6x4",
            "--degree",
            "1",
            "--knots-in",
            "1=0,0,1,1",
        ],
        "--knots-in K=LIST is a knot vector of a spline in N parameters",
    );
    // weights
    let nurbs = |weights: &str| {
        vec![
            "nurbs-tensor".to_string(),
            "--net".into(),
            "3x2x4".into(),
            "--degree".into(),
            "1".into(),
            "--weights".into(),
            weights.into(),
        ]
    };
    let run = |args: Vec<String>, needle: &str| {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&args, needle);
    };
    let mut w = vec!["1"; 24];
    run(
        nurbs(&w[..23].join(",")),
        "--weights: 23 weights for the 24 control points",
    );
    w[5] = "-0.5";
    run(nurbs(&w.join(",")), "--weights: weight 5 is -0.5");
    w[5] = "0";
    run(nurbs(&w.join(",")), "--weights: weight 5 is 0");
    w[5] = "inf";
    run(nurbs(&w.join(",")), "--weights: value 6 is \"inf\"");
    fails(
        &["nurbs-tensor", "--net", "3x2x4", "--degree", "1"],
        "needs --weights",
    );
    fails(
        &tensor(&["--weights", &vec!["1"; 24].join(",")]),
        "use `lekalo make nurbs-tensor`",
    );
    // a control point that is not a number
    let rows = net_rows();
    let first = rows.lines().next().unwrap();
    let bad = d.path().join("bad.csv");
    fs::write(&bad, rows.replacen(first, "nan,1", 1)).unwrap();
    lekalo()
        .args([
            "make",
            "bspline-tensor",
            "--net",
            "3x2x4",
            "--degree",
            "1",
            "--control",
        ])
        .arg(&bad)
        .assert()
        .code(2)
        .stderr(contains("not finite"));
}
