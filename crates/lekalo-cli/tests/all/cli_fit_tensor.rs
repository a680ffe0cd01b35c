//! `fit --grid AxBxC` and `fit --scattered` in three variables: data sampled from a spline of
//! the fitted space give that spline back (its control points), a knot count the grid cannot
//! determine names the option and the direction, and a region without data is refused with
//! exit 2 naming the control point, or filled by `--penalty`.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;
use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// Interior knots of the known spline, per direction (degrees 2, 2, 1).
const INNER: [&[f64]; 3] = [&[0.3, 0.6], &[0.5], &[0.4, 0.7]];
const DEGREES: [usize; 3] = [2, 2, 1];

/// A spline in three variables with the knots of [`INNER`] and irregular control values
/// (not a polynomial: its interior knots matter), written as `bspline_tensor` JSON.
fn known_spline(dir: &Path) -> (PathBuf, Vec<f64>) {
    let mut knots = Vec::new();
    let mut shape = Vec::new();
    for (inner, &p) in INNER.iter().zip(&DEGREES) {
        let mut k = vec![0.0; p + 1];
        k.extend_from_slice(inner);
        k.extend(vec![1.0; p + 1]);
        shape.push(k.len() - p - 1);
        knots.push(k);
    }
    let n: usize = shape.iter().product();
    let control: Vec<f64> = (0..n)
        .map(|i| ((i * 37 + 11) % 23) as f64 / 7.0 - 1.5)
        .collect();
    let rows: Vec<Vec<f64>> = control.iter().map(|&c| vec![c]).collect();
    let j = serde_json::json!({"lekalo": 1, "type": "bspline_tensor", "degrees": DEGREES,
        "knots": knots, "shape": shape, "control": rows});
    let path = dir.join("known.json");
    fs::write(&path, j.to_string()).unwrap();
    (path, control)
}

/// The known spline's values at the rows of `at` (three columns), through `lekalo eval`.
fn sample(spline: &Path, at: &Path) -> Vec<f64> {
    let out = lekalo()
        .arg("eval")
        .arg(spline)
        .arg("--at-file")
        .arg(at)
        .args(["--format", "json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let e: serde_json::Value = serde_json::from_slice(&out).unwrap();
    e["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r[3].as_f64().unwrap())
        .collect()
}

fn control(j: &serde_json::Value) -> Vec<f64> {
    j["control"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r[0].as_f64().unwrap())
        .collect()
}

fn list(t: &[f64]) -> String {
    t.iter().map(f64::to_string).collect::<Vec<_>>().join(",")
}

/// The grid's coordinates in direction `a` (`m` of them, uneven, from 0 to 1).
fn axis(m: usize) -> Vec<f64> {
    (0..m)
        .map(|k| {
            let t = k as f64 / (m - 1) as f64;
            t * t * 0.3 + t * 0.7
        })
        .collect()
}

fn assert_close(got: &[f64], want: &[f64], tol: f64) {
    assert_eq!(got.len(), want.len());
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= tol, "control point {i}: {g} vs {w}");
    }
}

#[test]
fn a_grid_sampled_from_a_spline_of_the_space_gives_it_back() {
    let d = tempfile::tempdir().unwrap();
    let (known, want) = known_spline(d.path());
    let axes = [axis(9), axis(7), axis(6)];
    let mut nodes = String::new();
    for &x in &axes[0] {
        for &y in &axes[1] {
            for &z in &axes[2] {
                nodes.push_str(&format!("{x},{y},{z}\n"));
            }
        }
    }
    let at = d.path().join("nodes.csv");
    fs::write(&at, nodes).unwrap();
    let values = sample(&known, &at);
    let v = d.path().join("values.txt");
    fs::write(&v, list(&values).replace(',', "\n")).unwrap();
    let out = lekalo()
        .arg("fit")
        .arg(&v)
        .args(["--grid", "9x7x6", "--degree", "2,2,1", "--json"])
        .args(["--knots-u", &list(INNER[0]), "--knots-v", &list(INNER[1])])
        .args(["--knots-in", &format!("3={}", list(INNER[2]))])
        .args(["--params-u", &list(&axes[0]), "--params-v", &list(&axes[1])])
        .args(["--params-in", &format!("3={}", list(&axes[2]))])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let j: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(j["object"]["type"], "bspline_tensor");
    assert_eq!(j["object"]["shape"], serde_json::json!([5, 4, 4]));
    assert_close(&control(&j["object"]), &want, 1e-12);
    assert!(j["report"]["max_residual"].as_f64().unwrap() < 1e-12);
    assert_eq!(j["report"]["control_points"], 80);
}

#[test]
fn scattered_points_sampled_from_a_spline_of_the_space_give_it_back() {
    let d = tempfile::tempdir().unwrap();
    let (known, want) = known_spline(d.path());
    // a deterministic spread of 400 points in [0, 1]³ (the additive recurrence of the
    // plastic number's powers)
    let (a1, a2, a3) = (
        0.819_172_513_396_164,
        0.671_043_606_703_789,
        0.549_700_477_901_970,
    );
    let mut rows = String::new();
    let mut points = Vec::new();
    for k in 1..=400 {
        let f = |a: f64| (0.5 + a * f64::from(k)).fract();
        let p = [f(a1), f(a2), f(a3)];
        rows.push_str(&format!("{},{},{}\n", p[0], p[1], p[2]));
        points.push(p);
    }
    let at = d.path().join("at.csv");
    fs::write(&at, rows).unwrap();
    let values = sample(&known, &at);
    let mut data = String::new();
    for (p, y) in points.iter().zip(&values) {
        data.push_str(&format!("{},{},{},{y}\n", p[0], p[1], p[2]));
    }
    let x = d.path().join("xyzw.csv");
    fs::write(&x, data).unwrap();
    let t = d.path().join("fitted.json");
    lekalo()
        .arg("fit")
        .arg(&x)
        .args(["--scattered", "--degree", "2,2,1", "--bbox", "0:1,0:1,0:1"])
        .args(["--knots-u", &list(INNER[0]), "--knots-v", &list(INNER[1])])
        .args(["--knots-in", &format!("3={}", list(INNER[2])), "-o"])
        .arg(&t)
        .assert()
        .success()
        .stderr(contains("fit: 5x4x4 = 80 control points"));
    let j: serde_json::Value = serde_json::from_str(&fs::read_to_string(&t).unwrap()).unwrap();
    assert_eq!(
        j["knots"][2],
        serde_json::json!([0.0, 0.0, 0.4, 0.7, 1.0, 1.0])
    );
    assert_close(&control(&j), &want, 1e-10);
}

#[test]
fn more_knots_than_the_grid_determines_name_the_option_and_the_direction() {
    let d = tempfile::tempdir().unwrap();
    let v = d.path().join("values.txt");
    fs::write(&v, "1\n".repeat(6 * 5 * 4)).unwrap();
    lekalo()
        .arg("fit")
        .arg(&v)
        .args(["--grid", "6x5x4", "--degree", "2", "--param", "uniform"])
        .args(["--ctrl-grid", "4x4x6", "--knots-in", "3=0.2,0.4,0.6"])
        .assert()
        .code(2)
        .stderr(contains("--knots-in 3"))
        .stderr(contains("direction 3"))
        .stderr(contains("more than its 4 grid values"));
    // --ctrl-grid sizes one per direction
    lekalo()
        .arg("fit")
        .arg(&v)
        .args(["--grid", "6x5x4", "--ctrl-grid", "4x4"])
        .assert()
        .code(2)
        .stderr(contains(
            "--ctrl-grid 4x4: 2 sizes for a fit in 3 variables",
        ));
}

#[test]
fn a_region_without_data_is_refused_naming_the_control_point() {
    let d = tempfile::tempdir().unwrap();
    // points of [0, 1]³ except the corner box (0.5, 1]³
    let mut rows = String::new();
    for i in 0..8 {
        for j in 0..8 {
            for k in 0..8 {
                let p = [i, j, k].map(|c| f64::from(c) / 7.0);
                if p.iter().all(|&c| c > 0.5) {
                    continue;
                }
                rows.push_str(&format!("{},{},{},{}\n", p[0], p[1], p[2], p[0] + p[2]));
            }
        }
    }
    let x = d.path().join("hole.csv");
    fs::write(&x, rows).unwrap();
    lekalo()
        .arg("fit")
        .arg(&x)
        .args(["--scattered", "--ctrl-grid", "4x4x4", "--degree", "2"])
        .assert()
        .code(2)
        .stderr(contains("control point (4, 4, 4) of the 4x4x4 net"))
        .stderr(contains("x1 in [0.5, 1], x2 in [0.5, 1], x3 in [0.5, 1]"))
        .stderr(contains("holds 0 data points"))
        .stderr(contains("give --penalty"))
        .stderr(contains("EmptySupport").not());
    // the penalty fills the corner: a linear field, whose net of degree 1 on even knots has
    // no second differences, is recovered there
    let fit = d.path().join("filled.json");
    lekalo()
        .arg("fit")
        .arg(&x)
        .args(["--scattered", "--ctrl-grid", "4x4x4", "--degree", "1"])
        .args(["--penalty", "1e-3", "-o"])
        .arg(&fit)
        .assert()
        .success();
    let at = d.path().join("corner.txt");
    fs::write(&at, "0.8,0.9,0.75\n").unwrap();
    let v = sample(&fit, &at);
    assert!((v[0] - 1.55).abs() < 1e-9, "{v:?}");
    // a grid's fit takes no penalty
    let axes = [axis(5), axis(5), axis(5)];
    let mut grid = String::new();
    for a in &axes[0] {
        for b in &axes[1] {
            for c in &axes[2] {
                grid.push_str(&format!("{}\n", a + b * c));
            }
        }
    }
    let g = d.path().join("grid.csv");
    fs::write(&g, grid).unwrap();
    lekalo()
        .arg("fit")
        .arg(&g)
        .args(["--grid", "5x5x5", "--ctrl-grid", "4x4x4", "--penalty", "1"])
        .assert()
        .code(2)
        .stderr(contains("drop --penalty"));
}

#[test]
fn s_smooths_a_grid_with_the_fewest_knots_and_zero_interpolates() {
    let d = tempfile::tempdir().unwrap();
    let axes = [axis(9), axis(8), axis(7)];
    // a smooth function plus a fixed pattern of noise (sum of squares 9·8·7·0.01² = 0.0504)
    let mut values = Vec::new();
    let mut k = 0;
    for &x in &axes[0] {
        for &y in &axes[1] {
            for &z in &axes[2] {
                let noise = if k % 2 == 0 { 0.01 } else { -0.01 };
                values.push((2.0 * x).sin() + y * z + noise);
                k += 1;
            }
        }
    }
    let v = d.path().join("values.txt");
    fs::write(&v, list(&values).replace(',', "\n")).unwrap();
    let run = |s: &str| -> serde_json::Value {
        let out = lekalo()
            .arg("fit")
            .arg(&v)
            .args(["--grid", "9x8x7", "--s", s, "--json"])
            .args(["--params-u", &list(&axes[0]), "--params-v", &list(&axes[1])])
            .args(["--params-in", &format!("3={}", list(&axes[2]))])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        serde_json::from_slice(&out).unwrap()
    };
    // the cubic polynomial leaves 0.0546: S = 0.04 needs knots and a smoothing weight
    let smooth = run("0.04");
    let rss = smooth["report"]["weighted_rss"].as_f64().unwrap();
    assert!((0.04 * (1.0 - 1e-3)..=0.04).contains(&rss), "{rss}");
    assert!(smooth["report"]["control_points"].as_u64().unwrap() < 9 * 8 * 7);
    let exact = run("0");
    assert_eq!(exact["object"]["shape"], serde_json::json!([9, 8, 7]));
    assert!(exact["report"]["max_residual"].as_f64().unwrap() < 1e-12);
    // the knots are the smoothing's own
    lekalo()
        .arg("fit")
        .arg(&v)
        .args(["--grid", "9x8x7", "--s", "0.06", "--ctrl-grid", "4x4x4"])
        .assert()
        .code(2)
        .stderr(contains("--s places the knots"));
}

/// `--scattered --s S` places FITPACK surfit's knots itself: the weighted residual sum of
/// squares is at most S (and within 0.1 % of it when smoothed), in two and in three variables
/// (their number from --degree), and knots given with it are refused.
#[test]
fn s_smooths_scattered_data_with_surfit_knots() {
    let d = tempfile::tempdir().unwrap();
    let mut rows2 = String::new();
    let mut rows3 = String::new();
    for i in 0..400 {
        let k = f64::from(i);
        let (x, y, z) = (
            (k * 0.754_877_666).fract(),
            (k * 0.569_840_291).fract(),
            (k * 0.438_047_065).fract(),
        );
        let noise = 0.01 * f64::from(i % 7 - 3);
        rows2.push_str(&format!(
            "{x},{y},{}\n",
            (3.0 * x).sin() * (2.0 * y).cos() + noise
        ));
        rows3.push_str(&format!("{x},{y},{z},{}\n", x * y + z * z + noise));
    }
    let (p2, p3) = (d.path().join("xyz.csv"), d.path().join("xyzw.csv"));
    fs::write(&p2, rows2).unwrap();
    fs::write(&p3, rows3).unwrap();
    for (path, extra, s) in [(&p2, vec![], 0.05), (&p3, vec!["--degree", "2,2,1"], 0.02)] {
        let out = lekalo()
            .arg("fit")
            .arg(path)
            .args(["--scattered", "--s", &s.to_string(), "--json"])
            .args(&extra)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let j: serde_json::Value = serde_json::from_slice(&out).unwrap();
        let r = &j["report"];
        let rss = r["weighted_rss"].as_f64().unwrap();
        assert!(rss <= s, "{r}");
        if r["p"].is_number() {
            assert!(rss >= 0.999 * s, "{r}");
        }
        assert!(r["knot_limit"].is_null(), "{r}");
        assert!(r["control_points"].as_u64().unwrap() < 400, "{r}");
        assert_eq!(
            j["object"]["degrees"].as_array().unwrap().len(),
            2 + extra.len() / 2
        );
    }
    lekalo()
        .arg("fit")
        .arg(&p2)
        .args(["--scattered", "--s", "0.05", "--ctrl-grid", "5x5"])
        .assert()
        .code(2)
        .stderr(contains("--s places the knots").and(contains("surfit")));
}

/// `f(x, y, z)` on the uniform grid of `[0, 1]³` with 8 × 7 × 6 nodes, one value a row, the
/// first direction slowest.
fn grid_of(dir: &Path, name: &str, f: impl Fn(f64, f64, f64, usize) -> f64) -> PathBuf {
    let mut s = String::new();
    let mut k = 0;
    for i in 0..8 {
        for j in 0..7 {
            for l in 0..6 {
                let (x, y, z) = (f64::from(i) / 7.0, f64::from(j) / 6.0, f64::from(l) / 5.0);
                s.push_str(&format!("{:?}\n", f(x, y, z, k)));
                k += 1;
            }
        }
    }
    let path = dir.join(name);
    fs::write(&path, s).unwrap();
    path
}

fn fit_json(args: &[&str], file: &Path) -> serde_json::Value {
    let out = lekalo()
        .arg("fit")
        .arg(file)
        .args(args)
        .arg("--json")
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    serde_json::from_slice(&out).unwrap()
}

/// `--smooth` on a grid: the smoothing spline with one λ per direction (or GCV) reproduces
/// data linear in each variable for any λ, reports the weights it used, and chooses them by
/// GCV on noisy data; a surface grid (two sizes) takes it too.
#[test]
fn smoothing_spline_on_a_grid_takes_one_weight_per_direction_or_gcv() {
    let d = tempfile::tempdir().unwrap();
    let f = |x: f64, y: f64, z: f64| 100.0 + x * y - 2.0 * z + 3.0 * x * y * z;
    let exact = grid_of(d.path(), "exact.csv", |x, y, z, _| f(x, y, z));
    let j = fit_json(
        &[
            "--grid", "8x7x6", "--param", "uniform", "--smooth", "0.1,1,0",
        ],
        &exact,
    );
    assert_eq!(j["report"]["lambda"], serde_json::json!([0.1, 1.0, 0.0]));
    assert_eq!(j["object"]["shape"], serde_json::json!([10, 9, 8]));
    assert!(j["report"]["max_residual"].as_f64().unwrap() < 1e-11);
    let spline = d.path().join("exact.json");
    fs::write(&spline, j["object"].to_string()).unwrap();
    let at = d.path().join("at.csv");
    fs::write(&at, "0.3,0.8,0.55\n0.91,0.12,0.4\n").unwrap();
    for (v, p) in sample(&spline, &at)
        .iter()
        .zip([[0.3, 0.8, 0.55], [0.91, 0.12, 0.4]])
    {
        assert!((v - f(p[0], p[1], p[2])).abs() < 1e-11, "{v} at {p:?}");
    }
    // noisy data: GCV in every direction
    let noisy = grid_of(d.path(), "noisy.csv", |x, y, z, k| {
        (3.0 * x).sin() * y + z + 0.05 * (((k * 7919) % 13) as f64 / 6.0 - 1.0)
    });
    let j = fit_json(&["--grid", "8x7x6", "--smooth", "gcv"], &noisy);
    let lambda: Vec<f64> = j["report"]["lambda"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(lambda.len(), 3);
    assert!(lambda.iter().all(|&l| l > 0.0), "{lambda:?}");
    let trace = j["report"]["trace"].as_f64().unwrap();
    assert!(trace > 1.0 && trace < 336.0, "{trace}");
    assert!(j["report"]["gcv"].as_f64().unwrap() > 0.0);
    // a surface grid, one weight given and one chosen
    let mut s = String::new();
    for i in 0..12 {
        for j in 0..9 {
            s.push_str(&format!(
                "{:?}\n",
                f64::from(i * j).sqrt() + f64::from((i + 2 * j) % 3) * 0.1
            ));
        }
    }
    let surface = d.path().join("surface.csv");
    fs::write(&surface, s).unwrap();
    let j = fit_json(&["--grid", "12x9", "--smooth", "1e-3,gcv"], &surface);
    assert_eq!(j["report"]["lambda"][0], 1e-3);
    assert!(j["report"]["lambda"][1].as_f64().unwrap() > 0.0);
    assert_eq!(j["object"]["shape"], serde_json::json!([14, 11]));
}

#[test]
fn smoothing_spline_on_a_grid_refuses_what_it_does_not_take() {
    let d = tempfile::tempdir().unwrap();
    let v = grid_of(d.path(), "v.csv", |x, y, z, _| x + y * z);
    for (extra, says) in [
        (
            &["--smooth", "1,2"][..],
            "2 weights for a grid of 3 directions",
        ),
        (&["--smooth", "often"][..], "neither a number nor gcv"),
        (&["--smooth", "-1"][..], "λ"),
        (
            &["--smooth", "1", "--ctrl-grid", "4x4x4"][..],
            "--ctrl-grid",
        ),
        (&["--smooth", "1", "--degree", "2"][..], "--degree"),
        (&["--smooth", "1", "--bbox", "0:1,0:1,0:1"][..], "--bbox"),
    ] {
        lekalo()
            .arg("fit")
            .arg(&v)
            .args(["--grid", "8x7x6"])
            .args(extra)
            .assert()
            .code(2)
            .stderr(contains(says));
    }
    // a curve takes one weight
    let xy = d.path().join("xy.csv");
    fs::write(&xy, "0,0\n1,1\n2,0\n3,1\n4,0\n").unwrap();
    lekalo()
        .arg("fit")
        .arg(&xy)
        .args(["--function", "--smooth", "1,2"])
        .assert()
        .code(2)
        .stderr(contains("a curve takes one λ"));
}
