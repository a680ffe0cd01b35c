//! `fit --sphere`: scattered rows `θ, φ, r` (least squares on given knots, the smoothing
//! condition with weights) and values on a grid of the sphere with pole conditions give the
//! library's spline (knots and coefficients) and its residual; refusals exit 2 naming the
//! option.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;
use std::path::Path;

use lekalo::fit::{
    sphere_grid_smoothing, sphere_least_squares, sphere_smoothing, PoleCondition, SphereData,
    SphereFit, SphereGrid,
};
use lekalo::Progress;
use predicates::str::contains;

use crate::common::{json_of, lekalo};

/// 300 points spread over the sphere (a Fibonacci lattice) with values that are not a
/// spline of the space, and weights that are not all alike.
fn scattered() -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let m = 300;
    let (mut theta, mut phi, mut r, mut w) = (vec![], vec![], vec![], vec![]);
    for i in 0..m {
        let k = f64::from(i);
        let t = (1.0 - (2.0 * k + 1.0) / f64::from(m)).acos();
        let p = (2.4 * k) % std::f64::consts::TAU;
        theta.push(t);
        phi.push(p);
        r.push(t.cos() + 0.3 * t.sin() * p.cos() + 0.05 * (3.0 * p).sin() * t.sin().powi(2));
        w.push(1.0 + 0.5 * f64::from(i % 3));
    }
    (theta, phi, r, w)
}

fn write_rows(path: &Path, cols: &[&[f64]]) {
    let text: String = (0..cols[0].len())
        .map(|i| {
            let row: Vec<String> = cols.iter().map(|c| c[i].to_string()).collect();
            row.join(",") + "\n"
        })
        .collect();
    fs::write(path, text).unwrap();
}

fn list(t: &[f64]) -> String {
    t.iter().map(f64::to_string).collect::<Vec<_>>().join(",")
}

/// The spline of `--json` output equals the library's fit: knots, shape and coefficients, and
/// the report's weighted residual is the library's.
fn assert_same(j: &serde_json::Value, fit: &SphereFit) {
    let o = &j["object"];
    let knots: Vec<Vec<f64>> = serde_json::from_value(o["knots"].clone()).unwrap();
    let want: Vec<Vec<f64>> = fit
        .spline
        .knots()
        .iter()
        .map(|k| k.as_slice().to_vec())
        .collect();
    assert_eq!(knots, want);
    let shape: Vec<usize> = serde_json::from_value(o["shape"].clone()).unwrap();
    assert_eq!(shape, fit.spline.shape());
    let control: Vec<Vec<f64>> = serde_json::from_value(o["control"].clone()).unwrap();
    let got: Vec<f64> = control.iter().map(|r| r[0]).collect();
    assert_eq!(got, fit.spline.control_points().as_slice());
    assert_eq!(j["report"]["weighted_rss"].as_f64().unwrap(), fit.fp);
}

#[test]
fn scattered_least_squares_on_given_knots_is_the_library_fit() {
    let d = tempfile::tempdir().unwrap();
    let (theta, phi, r, _) = scattered();
    let path = d.path().join("tpr.csv");
    write_rows(&path, &[&theta, &phi, &r]);
    let (tt, tp) = ([0.8, 1.6, 2.4], [1.0, 2.0, 3.5, 5.0]);
    let j = json_of(lekalo().arg("fit").arg(&path).args([
        "--sphere",
        "--scattered",
        "--knots-u",
        &list(&tt),
        "--knots-v",
        &list(&tp),
        "--json",
    ]));
    let data = SphereData::new(&theta, &phi, &r, None).unwrap();
    let fit = sphere_least_squares(&data, &tt, &tp, 1e-16).unwrap();
    assert_same(&j, &fit);
    assert!(j["report"]["p"].is_null());
    assert_eq!(j["report"]["rank"].as_u64().unwrap(), fit.rank as u64);
    // the spline has one value at the pole, whatever φ
    let pole = |p: f64| fit.spline.eval(&[0.0, p]).unwrap()[0];
    assert!((pole(0.3) - pole(4.0)).abs() < 1e-12);
}

#[test]
fn scattered_smoothing_with_weights_is_the_library_fit() {
    let d = tempfile::tempdir().unwrap();
    let (theta, phi, r, w) = scattered();
    let path = d.path().join("tpr.csv");
    write_rows(&path, &[&theta, &phi, &r]);
    let wpath = d.path().join("w.txt");
    write_rows(&wpath, &[&w]);
    let s = 0.5;
    let j = json_of(
        lekalo()
            .arg("fit")
            .arg(&path)
            .args(["--sphere", "--scattered", "--s", "0.5", "--weights"])
            .arg(&wpath)
            .arg("--json"),
    );
    let data = SphereData::new(&theta, &phi, &r, Some(&w)).unwrap();
    let fit = sphere_smoothing(&data, s, 1e-16, &Progress::new()).unwrap();
    assert_same(&j, &fit);
    // the smoothing weight was found: the residual is s, and the report says so
    let p = fit.p.expect("a smoothing weight");
    assert_eq!(j["report"]["p"].as_f64().unwrap(), p);
    assert!((fit.fp - s).abs() <= 1e-3 * s, "{}", fit.fp);
    assert!(j["report"]["knot_limit"].is_null());
}

#[test]
fn a_grid_with_pole_conditions_is_the_library_fit() {
    let d = tempfile::tempdir().unwrap();
    let u: Vec<f64> = (1..8).map(|i| 0.4 * f64::from(i)).collect();
    let v: Vec<f64> = (0..10).map(|j| -3.0 + 0.6 * f64::from(j)).collect();
    let r: Vec<f64> = u
        .iter()
        .flat_map(|a| {
            v.iter()
                .map(move |b| a.cos() + a.sin() * b.cos() + 0.02 * (2.0 * b).sin())
        })
        .collect();
    let path = d.path().join("r.csv");
    write_rows(&path, &[&r]);
    let grid = SphereGrid::new(&u, &v, &r).unwrap();
    let cases: [(&[&str], f64, [PoleCondition; 2]); 2] = [
        (
            &["--pole-continuity"],
            0.0,
            [PoleCondition {
                continuity: true,
                ..PoleCondition::default()
            }; 2],
        ),
        (
            &[
                "--s",
                "0.01",
                "--pole-values",
                "1,none",
                "--pole-exact=true,false",
                "--pole-continuity=true,false",
                "--pole-flat=true,false",
            ],
            0.01,
            [
                PoleCondition {
                    value: Some(1.0),
                    exact: true,
                    continuity: true,
                    flat: true,
                },
                PoleCondition::default(),
            ],
        ),
    ];
    for (options, s, poles) in cases {
        let j = json_of(
            lekalo()
                .arg("fit")
                .arg(&path)
                .args(["--sphere", "--grid", "7x10", "--params-u", &list(&u)])
                .args(["--params-v", &list(&v), "--json"])
                .args(options),
        );
        let fit = sphere_grid_smoothing(&grid, s, poles, &Progress::new()).unwrap();
        assert_same(&j, &fit);
    }
}

#[test]
fn refusals_exit_2_naming_the_option() {
    let d = tempfile::tempdir().unwrap();
    let (theta, phi, r, _) = scattered();
    let path = d.path().join("tpr.csv");
    write_rows(&path, &[&theta, &phi, &r]);
    let grid = d.path().join("r.csv");
    write_rows(&grid, &[&[1.0; 20]]);
    let fails = |args: &[&str], file: &Path, words: &[&str]| {
        let mut a = lekalo()
            .arg("fit")
            .arg(file)
            .arg("--sphere")
            .args(args)
            .assert()
            .code(2);
        for w in words {
            a = a.stderr(contains(*w));
        }
    };
    let scat = ["--scattered", "--knots-v", "1,2"];
    fails(
        &[&scat[..], &["--knots-u", "1,4"]].concat(),
        &path,
        &["--knots-u", "tt should be between (0, pi)"],
    );
    fails(
        &["--scattered", "--knots-u", "1", "--knots-v", "2,1"],
        &path,
        &["--knots-v", "increase strictly"],
    );
    fails(
        &["--scattered", "--s", "-1"],
        &path,
        &["--s", "s should be positive"],
    );
    fails(&["--scattered"], &path, &["--knots-u", "--s S"]);
    fails(
        &["--scattered", "--s", "1", "--pole-flat"],
        &path,
        &["--pole-flat", "--sphere --grid"],
    );
    fails(
        &["--scattered", "--s", "1", "--degree", "2"],
        &path,
        &["--degree"],
    );
    fails(&["--s", "1"], &path, &["--scattered", "--grid"]);
    let g = ["--grid", "4x5", "--params-v", "0,1,2,3,4"];
    fails(
        &[&g[..], &["--params-u", "0,1,2,3"]].concat(),
        &grid,
        &["--params-u", "u should be between (0, pi)"],
    );
    fails(
        &[&g[..], &["--params-u", "0.5,1,1.5,2", "--pole-flat"]].concat(),
        &grid,
        &["--pole-flat", "pole_continuity"],
    );
    fails(
        &[
            &g[..],
            &["--params-u", "0.5,1,1.5,2", "--pole-values", "1,x"],
        ]
        .concat(),
        &grid,
        &["--pole-values", "1,none"],
    );
    fails(&g, &grid, &["--params-u"]);
    // pole options without --sphere
    lekalo()
        .arg("fit")
        .arg(&path)
        .args(["--scattered", "--s", "1", "--pole-continuity"])
        .assert()
        .code(2)
        .stderr(contains("--sphere --grid"));
}
