//! `interpolate --grid` with the parameters of some directions given (`--params-u`,
//! `--params-v`, `--params-in K=LIST|FILE`: the axes of a lookup table), and the default
//! parametrisation of a grid of values in 3 or more directions (equally spaced, so that equal
//! neighbouring values, a flat stretch of a table, are no error).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;
use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// The axes of the table: uneven, the third negative at its start.
const U: [f64; 5] = [0.0, 1.0, 2.0, 4.0, 8.0];
const V: [f64; 4] = [10.0, 10.5, 12.0, 13.0];
const W: [f64; 4] = [-1.0, 0.0, 1.0, 3.0];

/// A table over the grid `U × V × W` whose value does not change along the third axis where
/// `v` is 10 (a flat stretch: chord-length parameters would find coincident values there).
fn f(u: f64, v: f64, w: f64) -> f64 {
    u.sin() + (v - 10.0) * w
}

fn table(dir: &Path) -> PathBuf {
    let mut s = String::new();
    for u in U {
        for v in V {
            for w in W {
                s.push_str(&format!("{:?}\n", f(u, v, w)));
            }
        }
    }
    let p = dir.join("table.txt");
    fs::write(&p, s).unwrap();
    p
}

fn list(axis: &[f64]) -> String {
    axis.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// The values of the spline `file` at `points` (`lekalo eval --at … --json`).
fn eval(file: &Path, points: &[[f64; 3]]) -> Vec<f64> {
    let (_, rows) = crate::common::eval_at(file, points);
    rows.iter().map(|r| r[3]).collect()
}

#[test]
fn the_spline_passes_through_the_table_at_its_axes() {
    let d = tempfile::tempdir().unwrap();
    let v = table(d.path());
    let w_file = d.path().join("w.txt");
    fs::write(&w_file, "-1\n0\n1\n3\n").unwrap();
    let t = d.path().join("table.json");
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "5x4x4", "--degree", "3,2,3"])
        .args([
            "--params-u",
            &list(&U),
            "--params-in",
            &format!("2={}", list(&V)),
        ])
        .arg("--params-in")
        .arg(format!("3={}", w_file.display()))
        .arg("-o")
        .arg(&t)
        .assert()
        .success();
    let j: serde_json::Value = serde_json::from_str(&fs::read_to_string(&t).unwrap()).unwrap();
    let domain: Vec<[f64; 2]> = serde_json::from_value(j["domain"].clone()).unwrap_or_else(|_| {
        // the JSON keeps the knots; the domain is their ends
        (0..3)
            .map(|a| {
                let k = j["knots"][a].as_array().unwrap();
                [k[0].as_f64().unwrap(), k[k.len() - 1].as_f64().unwrap()]
            })
            .collect()
    });
    assert_eq!(domain, [[0.0, 8.0], [10.0, 13.0], [-1.0, 3.0]]);
    let nodes: Vec<[f64; 3]> = U
        .iter()
        .flat_map(|&u| {
            V.iter()
                .flat_map(move |&v| W.iter().map(move |&w| [u, v, w]))
        })
        .collect();
    let got = eval(&t, &nodes);
    for (p, y) in nodes.iter().zip(got) {
        let want = f(p[0], p[1], p[2]);
        assert!(
            (y - want).abs() <= 1e-12 * (1.0 + want.abs()),
            "{p:?}: {y} ≠ {want}"
        );
    }
}

#[test]
fn a_flat_table_interpolates_with_equally_spaced_parameters_by_default() {
    let d = tempfile::tempdir().unwrap();
    let v = table(d.path());
    let (a, b) = (d.path().join("a.json"), d.path().join("b.json"));
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "5x4x4", "-o"])
        .arg(&a)
        .assert()
        .success();
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "5x4x4", "--param", "uniform", "-o"])
        .arg(&b)
        .assert()
        .success();
    assert_eq!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
    // chord length, asked for, meets the flat stretch and says which option to change
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "5x4x4", "--param", "chord"])
        .assert()
        .code(2)
        .stderr(contains("coincide"));
    // the same default in `fit --grid`: least squares with as many control points as values
    // is the interpolant, so it takes each value at its node's equally spaced parameters
    let c = d.path().join("c.json");
    lekalo()
        .arg("fit")
        .arg(&v)
        .args(["--grid", "5x4x4", "--ctrl-grid", "5x4x4", "-o"])
        .arg(&c)
        .assert()
        .success();
    let nodes = [[2, 1, 3], [4, 0, 0], [1, 3, 2]];
    let at: Vec<[f64; 3]> = nodes
        .iter()
        .map(|n| [n[0] as f64 / 4.0, n[1] as f64 / 3.0, n[2] as f64 / 3.0])
        .collect();
    for (n, y) in nodes.iter().zip(eval(&c, &at)) {
        let want = f(U[n[0]], V[n[1]], W[n[2]]);
        assert!(
            (y - want).abs() <= 1e-10 * (1.0 + want.abs()),
            "{n:?}: {y} ≠ {want}"
        );
    }
}

#[test]
fn a_surface_grid_takes_the_parameters_of_its_rows_and_columns() {
    let d = tempfile::tempdir().unwrap();
    // a 4 × 3 grid of 3-D points
    let mut s = String::new();
    for i in 0..4 {
        for j in 0..3 {
            s.push_str(&format!("{i} {j} {}\n", (i * j) as f64 * 0.5));
        }
    }
    let g = d.path().join("grid.txt");
    fs::write(&g, s).unwrap();
    let out = d.path().join("s.json");
    lekalo()
        .arg("interpolate")
        .arg(&g)
        .args(["--grid", "4x3", "--degree", "2", "--params-u", "0,1,3,4"])
        .args(["--params-v", "0,2,3", "-o"])
        .arg(&out)
        .assert()
        .success();
    // the grid point (2, 1) sits at (u, v) = (3, 2)
    let text = lekalo()
        .arg("eval")
        .arg(&out)
        .args(["--uv", "3,2"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let row: Vec<f64> = String::from_utf8(text)
        .unwrap()
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    for (got, want) in row.iter().zip([3.0, 2.0, 2.0, 1.0, 1.0]) {
        assert!((got - want).abs() < 1e-14, "{row:?}");
    }
}

#[test]
fn wrong_parameters_name_the_option_and_the_direction() {
    let d = tempfile::tempdir().unwrap();
    let v = table(d.path());
    let fails = |args: &[&str], text: &str| {
        lekalo()
            .arg("interpolate")
            .arg(&v)
            .args(["--grid", "5x4x4"])
            .args(args)
            .assert()
            .code(2)
            .stderr(contains(text));
    };
    fails(
        &["--params-in", "3=0,1,2"],
        "--params-in 3: 3 values for the 4 grid values of direction 3",
    );
    fails(
        &["--params-u", "0,1,1,2,3"],
        "--params-u: parameters 1 and 1 of direction 1 are not increasing",
    );
    fails(
        &["--params-v", "0,1,2,3", "--params-in", "2=0,1,2,3"],
        "direction 2 already has parameters from --params-v",
    );
    fails(
        &["--params-in", "5=0,1"],
        "--params-in 5: the spline has 3 directions",
    );
    fails(
        &["--params", "0,1,2,3,4"],
        "--params gives a curve's parameters",
    );
    // the output is never written over a file of parameters
    let w = d.path().join("w.txt");
    fs::write(&w, "-1\n0\n1\n3\n").unwrap();
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "5x4x4", "--params-in"])
        .arg(format!("3={}", w.display()))
        .arg("-o")
        .arg(&w)
        .assert()
        .code(2);
    assert_eq!(fs::read_to_string(&w).unwrap(), "-1\n0\n1\n3\n");
}

/// An output path equal to a `--params-in` file (or to the values file) is refused by
/// `interpolate --grid` and `fit --grid` in three directions, and the file keeps its bytes.
#[test]
fn an_output_equal_to_a_parameter_file_or_the_values_is_refused() {
    let d = tempfile::tempdir().unwrap();
    let values = table(d.path());
    let params = d.path().join("w.txt");
    let text: String = W.iter().map(|w| format!("{w:?}\n")).collect();
    fs::write(&params, &text).unwrap();
    let given = format!("3={}", params.display());
    for (command, extra) in [
        ("interpolate", vec![]),
        ("fit", vec!["--ctrl-grid", "5x4x4"]),
    ] {
        for target in [&params, &values] {
            let before = fs::read(target).unwrap();
            lekalo()
                .arg(command)
                .arg(&values)
                .args(["--grid", "5x4x4", "--degree", "2", "--params-in", &given])
                .args(&extra)
                .args(["--to", "json", "-o"])
                .arg(target)
                .assert()
                .code(2)
                .stderr(contains("it is an input file"));
            assert_eq!(
                fs::read(target).unwrap(),
                before,
                "{command}: {target:?} changed"
            );
        }
    }
}
