//! End-to-end tests of `lekalo fit`: every mode, the report, and bad inputs.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fmt::Write as _;
use std::fs;

use assert_cmd::Command;
use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// 80 noisy samples (x, y) of sin(3x) with a fixed pseudo-noise.
fn function_samples() -> String {
    let mut s = String::new();
    for k in 0..80 {
        let x = f64::from(k) / 79.0 * 3.0;
        let e = 0.02 * ((f64::from(k) * 0.618_033_988_7).fract() - 0.5);
        writeln!(s, "{x} {}", (3.0 * x).sin() + e).unwrap();
    }
    s
}

/// 120 points of a plane spiral.
fn spiral() -> String {
    let mut s = String::new();
    for k in 0..120 {
        let t = 5.0 * f64::from(k) / 119.0;
        writeln!(
            s,
            "{} {}",
            (1.0 + 0.3 * t) * t.cos(),
            (1.0 + 0.3 * t) * t.sin()
        )
        .unwrap();
    }
    s
}

fn run_json(args: &[&str], stdin: &str) -> serde_json::Value {
    let out = lekalo()
        .args(args)
        .write_stdin(stdin)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    serde_json::from_slice(&out).unwrap()
}

#[test]
fn help_has_examples() {
    lekalo()
        .args(["fit", "--help"])
        .assert()
        .success()
        .stdout(contains("Examples:"))
        .stdout(contains("--smooth gcv"));
}

#[test]
fn least_squares_with_constraints_reports_residuals() {
    let v = run_json(
        &[
            "fit",
            "-",
            "--lsq",
            "--ctrl",
            "10",
            "--clamp-ends",
            "--json",
            "--per-point",
        ],
        &spiral(),
    );
    let r = &v["report"];
    assert_eq!(r["control_points"], 10);
    assert_eq!(r["residuals"].as_array().unwrap().len(), 120);
    assert!(r["max_residual"].as_f64().unwrap() < 0.05);
    assert_eq!(v["object"]["type"], "bspline_curve");
    // the first control point is the first data point
    let p0 = &v["object"]["control"][0];
    assert!((p0[0].as_f64().unwrap() - 1.0).abs() < 1e-12 && p0[1].as_f64().unwrap().abs() < 1e-12);
    // a start derivative: P_1 − P_0 = D (t_4 − t_1) / 3
    let v = run_json(
        &[
            "fit",
            "-",
            "--ctrl",
            "10",
            "--clamp-ends",
            "--start-derivative",
            "3,10",
            "--json",
        ],
        &spiral(),
    );
    // the former spelling gives the same curve, with a warning naming the new one
    let old = lekalo()
        .args([
            "fit",
            "-",
            "--ctrl",
            "10",
            "--clamp-ends",
            "--d0",
            "3,10",
            "--json",
        ])
        .write_stdin(spiral())
        .assert()
        .success()
        .stderr(contains(
            "`--d0` of `lekalo fit` is deprecated; write `--start-derivative`",
        ))
        .get_output()
        .stdout
        .clone();
    assert_eq!(
        serde_json::from_slice::<serde_json::Value>(&old).unwrap(),
        v
    );
    let o = &v["object"];
    let t = |i: usize| o["knots"][i].as_f64().unwrap();
    let c = |i: usize, k: usize| o["control"][i][k].as_f64().unwrap();
    let h = (t(4) - t(1)) / 3.0;
    assert!(
        (c(1, 0) - c(0, 0) - 3.0 * h).abs() < 1e-12 && (c(1, 1) - c(0, 1) - 10.0 * h).abs() < 1e-12
    );
}

#[test]
fn smoothing_modes_report_lambda_and_s() {
    let data = function_samples();
    let v = run_json(
        &["fit", "-", "--function", "--smooth", "gcv", "--json"],
        &data,
    );
    assert!(v["report"]["lambda"].as_f64().unwrap() > 0.0);
    let v = run_json(
        &["fit", "-", "--function", "--smooth", "1e-3", "--json"],
        &data,
    );
    assert_eq!(v["report"]["lambda"].as_f64().unwrap(), 1e-3);
    let v = run_json(&["fit", "-", "--function", "--s", "0.01", "--json"], &data);
    assert!(v["report"]["weighted_rss"].as_f64().unwrap() <= 0.01);
    assert_eq!(v["report"]["s"].as_f64().unwrap(), 0.01);
}

/// A repeated x in a smoothing spline: the same curve as one point at the mean of the two
/// values with weight 2 (`docs/theory/fitting.md#penalised`), also with λ by GCV (which counts
/// every row), not an error.
#[test]
fn a_repeated_x_in_a_smoothing_fit_is_one_point_at_the_weighted_mean() {
    let rows: Vec<(f64, f64)> = function_samples()
        .lines()
        .map(|l| {
            let mut it = l.split(' ').map(|v| v.parse::<f64>().unwrap());
            (it.next().unwrap(), it.next().unwrap())
        })
        .collect();
    let (mut repeated, mut merged, mut weights) = (String::new(), String::new(), String::new());
    for (k, &(x, y)) in rows.iter().enumerate() {
        writeln!(repeated, "{x} {y}").unwrap();
        if k == 10 || k == 40 {
            writeln!(repeated, "{x} {}", y + 0.2).unwrap();
            writeln!(merged, "{x} {}", y + 0.1).unwrap();
            writeln!(weights, "2").unwrap();
        } else {
            writeln!(merged, "{x} {y}").unwrap();
            writeln!(weights, "1").unwrap();
        }
    }
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("w.txt"), weights).unwrap();
    let w = d.path().join("w.txt");
    let control = |v: &serde_json::Value| -> Vec<f64> {
        v["object"]["control"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|p| p.as_array().unwrap().iter().map(|c| c.as_f64().unwrap()))
            .collect()
    };
    for lambda in ["1e-3", "0"] {
        let a = run_json(
            &["fit", "-", "--function", "--smooth", lambda, "--json"],
            &repeated,
        );
        let b = run_json(
            &[
                "fit",
                "-",
                "--function",
                "--smooth",
                lambda,
                "--weights",
                w.to_str().unwrap(),
                "--json",
            ],
            &merged,
        );
        assert_eq!(a["object"]["knots"], b["object"]["knots"], "λ = {lambda}");
        let (ca, cb) = (control(&a), control(&b));
        assert_eq!(ca.len(), cb.len());
        for (p, q) in ca.iter().zip(&cb) {
            // data of size 1: the two solves differ by rounding
            assert!((p - q).abs() < 1e-10, "λ = {lambda}: {p} vs {q}");
        }
    }
    let v = run_json(
        &["fit", "-", "--function", "--smooth", "gcv", "--json"],
        &repeated,
    );
    assert!(v["report"]["lambda"].as_f64().unwrap() > 0.0);
}

#[test]
fn smoothing_on_given_knots_meets_s_on_those_knots() {
    let data = function_samples();
    let args = [
        "fit",
        "-",
        "--function",
        "--s",
        "0.2",
        "--knots",
        "0.75,1.5,2.25",
        "--json",
    ];
    let v = run_json(&args, &data);
    let rss = v["report"]["weighted_rss"].as_f64().unwrap();
    assert!((0.2 * (1.0 - 1e-3)..=0.2).contains(&rss), "residual {rss}");
    assert!(v["report"]["lambda"].as_f64().unwrap() > 0.0);
    let knots: Vec<f64> = v["object"]["knots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_f64().unwrap())
        .collect();
    assert_eq!(knots[4..7], [0.75, 1.5, 2.25], "{knots:?}");
    // closed: on the period's breakpoints (chord length on [0, 1])
    let breaks: Vec<String> = (1..12).map(|j| (f64::from(j) / 12.0).to_string()).collect();
    let breaks = breaks.join(",");
    let v = run_json(
        &[
            "fit",
            "-",
            "--periodic",
            "--s",
            "0.5",
            "--knots",
            &breaks,
            "--json",
        ],
        &closed_loop(),
    );
    let rss = v["report"]["weighted_rss"].as_f64().unwrap();
    assert!(
        (0.5 * (1.0 - 1e-3)..=0.5).contains(&rss),
        "closed residual {rss}"
    );
}

#[test]
fn tolerance_fit_stays_within_tol_and_writes_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("spiral.txt");
    let output = dir.path().join("fit.json");
    fs::write(&input, spiral()).unwrap();
    lekalo()
        .args([
            "fit",
            input.to_str().unwrap(),
            "--tolerance",
            "1e-3",
            "-o",
            output.to_str().unwrap(),
        ])
        .assert()
        .success()
        // the residuals are the deviations the tolerance bounds: one maximum, said once
        .stderr(contains("deviation max "))
        .stderr(contains(") within the tolerance 0.001, RMS "))
        .stderr(contains("residual max").not());
    let v: serde_json::Value = serde_json::from_str(&fs::read_to_string(&output).unwrap()).unwrap();
    assert_eq!(v["type"], "bspline_curve");
    let r = run_json(
        &[
            "fit",
            input.to_str().unwrap(),
            "--tolerance",
            "1e-3",
            "--json",
        ],
        "",
    );
    assert!(r["report"]["max_deviation"].as_f64().unwrap() <= 1e-3);
}

/// `fit --tolerance T --json --per-point` on `data`: the report's largest residual and
/// deviation, both within `T`, and every residual its point's deviation.
fn reported_within(data: &str, tol: &str) -> (f64, f64) {
    let r = run_json(
        &["fit", "-", "--tolerance", tol, "--json", "--per-point"],
        data,
    );
    let report = &r["report"];
    let t: f64 = tol.parse().unwrap();
    let (max_res, max_dev) = (
        report["max_residual"].as_f64().unwrap(),
        report["max_deviation"].as_f64().unwrap(),
    );
    assert!(
        max_res <= t && max_dev <= t,
        "tolerance {tol}: residual {max_res}, deviation {max_dev}"
    );
    let (res, dev) = (
        report["residuals"].as_array().unwrap(),
        report["deviations"].as_array().unwrap(),
    );
    assert_eq!(res.len(), dev.len(), "a residual and a deviation per point");
    assert_eq!(res, dev, "every residual is its point's deviation");
    (max_res, max_dev)
}

#[test]
fn tolerance_fit_reports_every_residual_within_the_tolerance() {
    // the README tour's noisy sine: at its chord-length parameters the fit is 0.01006 from a
    // point, at the point's closest point 0.0072; the report gives the latter, within 0.01
    let scan: String = (0..80)
        .map(|i| {
            let x = f64::from(i) / 16.0;
            format!("{x},{}\n", x.sin() + 0.002 * f64::from(i % 5 - 2))
        })
        .collect();
    let (res, _) = reported_within(&scan, "0.01");
    assert!(res < 0.0075, "the tour's fit: {res}");
    lekalo()
        .args(["fit", "-", "--tolerance", "0.01", "-o", "-"])
        .write_stdin(scan.as_str())
        .assert()
        .success()
        .stderr(contains("deviation max 0.0071"))
        .stderr(contains("within the tolerance 0.01, RMS "));
    // others: a spiral, a noisy circle in 3-D, steps, each at a few tolerances
    let circle: String = (0..200)
        .map(|k| {
            let a = f64::from(k) * 0.05;
            let e = 0.01 * ((f64::from(k) * 0.618_033_988_7).fract() - 0.5);
            format!("{} {} {}\n", (1.0 + e) * a.cos(), a.sin(), 0.1 * a + e)
        })
        .collect();
    let steps: String = (0..120)
        .map(|k| format!("{} {}\n", f64::from(k) * 0.1, f64::from(k / 20)))
        .collect();
    for data in [spiral(), circle, steps] {
        for tol in ["0.1", "0.01", "0.001"] {
            reported_within(&data, tol);
        }
    }
}

#[test]
fn robust_fit_returns_weights() {
    let mut data = function_samples();
    data.push_str("1.5 40\n");
    let mut rows: Vec<(f64, f64)> = data
        .lines()
        .map(|l| {
            let mut it = l.split_whitespace().map(|x| x.parse::<f64>().unwrap());
            (it.next().unwrap(), it.next().unwrap())
        })
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let text: String = rows.iter().map(|(x, y)| format!("{x} {y}\n")).collect();
    let v = run_json(
        &[
            "fit",
            "-",
            "--function",
            "--ctrl",
            "12",
            "--robust",
            "tukey",
            "--json",
        ],
        &text,
    );
    let w = v["report"]["robust_weights"].as_array().unwrap();
    assert_eq!(w.len(), 81);
    assert!(w.iter().any(|x| x.as_f64().unwrap() == 0.0));
}

#[test]
fn surfaces_from_grids_and_scattered_rows() {
    let mut grid = String::new();
    for i in 0..12 {
        for j in 0..10 {
            let (x, y) = (f64::from(i), f64::from(j));
            writeln!(grid, "{x} {y} {}", (0.3 * x).sin() * (0.2 * y).cos()).unwrap();
        }
    }
    let out = lekalo()
        .args(["fit", "-", "--grid", "12x10", "--ctrl-grid", "6x5"])
        .write_stdin(grid)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(v["type"], "bspline_surface");
    let mut rows = String::new();
    for k in 0..400 {
        let (u, v) = (
            (f64::from(k) * 0.754_877_666).fract(),
            (f64::from(k) * 0.569_840_291).fract(),
        );
        writeln!(rows, "{u} {v} {}", u * u - v).unwrap();
    }
    let v = run_json(
        &["fit", "-", "--scattered", "--ctrl-grid", "5x5", "--json"],
        &rows,
    );
    assert!(v["report"]["max_residual"].as_f64().unwrap() < 1e-9);
}

#[test]
fn bad_inputs_exit_2_with_the_reason() {
    let data = function_samples();
    for (args, needle) in [
        (vec!["fit", "-", "--function", "--smooth", "-1"], "λ"),
        (
            vec!["fit", "-", "--function", "--s", "-2"],
            "must be finite and ≥ 0",
        ),
        (vec!["fit", "-", "--tolerance", "0"], "tolerance"),
        (
            vec![
                "fit",
                "-",
                "--function",
                "--knots",
                "0.1,0.11,0.12,0.13,0.14",
            ],
            "Schoenberg",
        ),
        (
            vec!["fit", "-", "--function", "--ctrl", "500"],
            "need at least 500",
        ),
        (
            vec!["fit", "-", "--smooth", "gcv", "--s", "1"],
            "choose one mode",
        ),
    ] {
        lekalo()
            .args(&args)
            .write_stdin(data.clone())
            .assert()
            .code(2)
            .stderr(contains(needle));
    }
    // two points and no mode: the message says what the default needs and how to fit them
    let out = lekalo()
        .args(["fit", "-"])
        .write_stdin("0,0\n1,1\n")
        .assert()
        .code(2)
        .get_output()
        .stderr
        .clone();
    let msg = String::from_utf8(out).unwrap();
    assert!(
        msg.contains("2 data points are too few for a fit of degree 3")
            && msg.contains("--degree 1")
            && !msg.contains("asked for"),
        "{msg}"
    );
    lekalo()
        .args(["fit", "-", "--degree", "1"])
        .write_stdin("0,0\n1,1\n")
        .assert()
        .success();
}

/// 90 points of a noisy closed curve (a rounded triangle).
fn closed_loop() -> String {
    let mut s = String::new();
    for k in 0..90 {
        let t = std::f64::consts::TAU * f64::from(k) / 90.0;
        let r = 2.0 + 0.3 * (3.0 * t).cos() + 0.01 * ((f64::from(k) * 0.618).fract() - 0.5);
        writeln!(s, "{} {}", r * t.cos(), r * t.sin()).unwrap();
    }
    s
}

/// Closed data that end on their first point again, to rounding: the refusal names the seam and
/// the fix (leave the repeated point out), and the fit without it runs.
#[test]
fn periodic_fit_of_data_repeating_their_first_point_names_the_fix() {
    let mut data = String::new();
    for k in 0..40 {
        let t = std::f64::consts::TAU * f64::from(k) / 40.0;
        writeln!(data, "{} {}", t.cos(), 0.6 * t.sin()).unwrap();
    }
    let open_data = data.clone();
    writeln!(data, "1 -1.5e-16").unwrap();
    lekalo()
        .args(["fit", "-", "--periodic", "--s", "0.01"])
        .write_stdin(data)
        .assert()
        .code(2)
        .stderr(contains("points 40 and 0").and(contains("leave out a repeated first point")));
    lekalo()
        .args(["fit", "-", "--periodic", "--s", "0.01"])
        .write_stdin(open_data)
        .assert()
        .success();
}

#[test]
fn periodic_fits_close_the_curve() {
    let data = closed_loop();
    for args in [
        vec!["fit", "-", "--periodic", "--s", "0.01", "--json"],
        vec!["fit", "-", "--periodic", "--ctrl", "12", "--json"],
    ] {
        let v = run_json(&args, &data);
        let r = &v["report"];
        assert_eq!(r["periodic"], true);
        assert!(r["max_residual"].as_f64().unwrap() < 0.2, "{r}");
        let obj = &v["object"];
        let ctrl = obj["control"].as_array().unwrap();
        let p = usize::try_from(obj["degree"].as_u64().unwrap()).unwrap();
        // the last `degree` control points repeat the first
        let n = ctrl.len();
        assert_eq!(ctrl[..p], ctrl[n - p..], "{obj}");
    }
    let v = run_json(&["fit", "-", "--periodic", "--s", "0.01", "--json"], &data);
    assert!(v["report"]["weighted_rss"].as_f64().unwrap() <= 0.01);
    // a periodic function: the last row repeats the first and is left out
    let mut f = String::new();
    for k in 0..=60 {
        let x = std::f64::consts::TAU * f64::from(k) / 60.0;
        writeln!(f, "{x} {}", x.cos()).unwrap();
    }
    let v = run_json(
        &[
            "fit",
            "-",
            "--periodic",
            "--function",
            "--ctrl",
            "10",
            "--json",
        ],
        &f,
    );
    assert!(v["report"]["max_residual"].as_f64().unwrap() < 1e-3);
    for (args, why) in [
        (
            vec!["fit", "-", "--periodic", "--tolerance", "0.1"],
            "--periodic",
        ),
        (vec!["fit", "-", "--periodic", "--clamp-ends"], "no ends"),
        (vec!["fit", "-", "--periodic", "--s", "-1"], "s"),
    ] {
        lekalo()
            .args(&args)
            .write_stdin(data.clone())
            .assert()
            .code(2)
            .stderr(contains(why));
    }
}

/// The legend's two figures `max` and `RMS` of `plot --residuals` (`deviations: max …` or, when
/// the segments are drawn stretched, `deviations (drawn ×F): max …`).
fn legend_figures(svg: &str) -> (f64, f64) {
    let at = svg.find("deviations").expect("a deviations legend");
    let at = at
        + svg[at..]
            .find("): max ")
            .map_or_else(|| svg[at..].find(": max ").expect("max") + 6, |i| i + 7);
    let rest = &svg[at..];
    let (max, rest) = rest.split_once(", RMS ").expect("RMS");
    let end = rest.find(['<', '"']).expect("end");
    (max.parse().unwrap(), rest[..end].parse().unwrap())
}

#[test]
fn plot_residuals_draws_the_data_the_fit_and_its_deviations() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    fs::write(p("spiral.txt"), spiral()).unwrap();
    lekalo()
        .args(["fit", &p("spiral.txt"), "--ctrl", "8", "-o", &p("fit.json")])
        .assert()
        .success();
    lekalo()
        .args([
            "plot",
            &p("fit.json"),
            "--points",
            &p("spiral.txt"),
            "--residuals",
            "-o",
            &p("res.svg"),
        ])
        .assert()
        .success();
    let svg = fs::read_to_string(p("res.svg")).unwrap();
    assert!(
        svg.contains("data points") && svg.contains(">curve<"),
        "data and fit drawn"
    );
    // the legend's figures are the closest-point distances `lekalo project` gives
    let out = lekalo()
        .args(["project", &p("fit.json"), "--points", &p("spiral.txt")])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let d: Vec<f64> = String::from_utf8(out)
        .unwrap()
        .lines()
        .skip(1) // the header
        .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(d.len(), 120, "one projection a point");
    let max = d.iter().copied().fold(0.0, f64::max);
    let rms = (d.iter().map(|x| x * x).sum::<f64>() / 120.0).sqrt();
    let (lmax, lrms) = legend_figures(&svg);
    assert!(
        max > 1e-3,
        "an 8-point fit of the spiral deviates visibly: {max}"
    );
    // four significant digits in the legend
    assert!((lmax - max).abs() <= 5e-4 * max, "{lmax} vs {max}");
    assert!((lrms - rms).abs() <= 5e-4 * rms, "{lrms} vs {rms}");
    // the segments: one polyline of two vertices a point, in the deviations' series group
    let start = svg.find("data-label=\"deviations").unwrap();
    let group = &svg[start..start + svg[start..].find("</g>").unwrap()];
    assert_eq!(group.matches("<polyline").count(), 120, "a segment a point");
    assert!(
        group
            .split("points=\"")
            .skip(1)
            .all(|q| q[..q.find('"').unwrap()].split(' ').count() == 2),
        "two vertices a segment"
    );

    // refusals name the option and the files
    lekalo()
        .args(["plot", &p("fit.json"), "--residuals", "-o", &p("x.svg")])
        .assert()
        .code(2)
        .stderr(contains("--points"));
    fs::write(p("p3.txt"), "1 2 3\n4 5 6\n").unwrap();
    lekalo()
        .args([
            "plot",
            &p("fit.json"),
            "--points",
            &p("p3.txt"),
            "--residuals",
            "-o",
            &p("x.svg"),
        ])
        .assert()
        .code(2)
        .stderr(contains("3-D").and(contains("2-D")));
    assert!(
        !dir.path().join("x.svg").exists(),
        "nothing written on a refusal"
    );
}

/// Shape constraints: the options reach the library (the report lists them, the fit keeps a
/// bound and a point), and misuse exits 2 with the reason.
#[test]
fn shape_constraints_from_options() {
    let data = function_samples();
    let v = run_json(
        &[
            "fit",
            "-",
            "--function",
            "--ctrl",
            "12",
            "--increasing=0:0.5",
            "--max",
            "0.9",
            "--min",
            "-0.5@1:3",
            "--through",
            "0=0",
            "--json",
        ],
        &data,
    );
    let names: Vec<&str> = v["report"]["constraints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "increasing on [0, 0.5]",
            "min -0.5 on [1, 3]",
            "max 0.9",
            "y(0) = 0"
        ]
    );
    // a cubic B-spline lies below its largest control point: the bound shows in the control
    // points up to the solver's rounding, and the first one is y(0) = 0
    let ctrl: Vec<f64> = v["object"]["control"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p[0].as_f64().unwrap())
        .collect();
    assert!(ctrl[0].abs() < 1e-12, "{ctrl:?}");
    let unconstrained = run_json(&["fit", "-", "--function", "--ctrl", "12", "--json"], &data);
    // bounds at a point: `V@X` and `=X`, named as such in the report
    let at = run_json(
        &[
            "fit",
            "-",
            "--function",
            "--ctrl",
            "12",
            "--max=0.2@1.5",
            "--increasing=0.25",
            "--json",
        ],
        &data,
    );
    assert_eq!(
        at["report"]["constraints"],
        serde_json::json!(["increasing at 0.25", "max 0.2 at 1.5"]),
        "{at}"
    );
    // an integral, and shape constraints with --periodic (least squares on the period)
    let v = run_json(
        &[
            "fit",
            "-",
            "--function",
            "--ctrl",
            "12",
            "--integral",
            "0:3=0.5",
            "--json",
        ],
        &data,
    );
    assert_eq!(
        v["report"]["constraints"],
        serde_json::json!(["integral over [0, 3] = 0.5"]),
        "{v}"
    );
    let v = run_json(
        &[
            "fit",
            "-",
            "--function",
            "--periodic",
            "--ctrl",
            "10",
            "--max",
            "0.8",
            "--json",
        ],
        &data,
    );
    assert_eq!(
        v["report"]["constraints"],
        serde_json::json!(["max 0.8", "periodic"]),
        "{v}"
    );
    lekalo()
        .args([
            "fit",
            "-",
            "--function",
            "--periodic",
            "--s",
            "0.1",
            "--min",
            "0",
        ])
        .write_stdin(data.clone())
        .assert()
        .code(2)
        .stderr(contains("drop --s"));
    assert!(
        v["report"]["weighted_rss"].as_f64().unwrap()
            > unconstrained["report"]["weighted_rss"].as_f64().unwrap()
    );
    lekalo()
        .args([
            "fit",
            "-",
            "--function",
            "--smooth",
            "1e-3",
            "--convex",
            "--json",
        ])
        .write_stdin(data.clone())
        .assert()
        .success()
        .stdout(contains("\"convex\""));
    // the smoothing condition under constraints: the convex smoothing spline whose residual is S
    let gcv = run_json(
        &[
            "fit",
            "-",
            "--function",
            "--smooth",
            "gcv",
            "--convex",
            "--json",
        ],
        &data,
    );
    let target = 2.0 * gcv["report"]["weighted_rss"].as_f64().unwrap();
    let v = run_json(
        &[
            "fit",
            "-",
            "--function",
            "--s",
            &target.to_string(),
            "--convex",
            "--json",
        ],
        &data,
    );
    let rss = v["report"]["weighted_rss"].as_f64().unwrap();
    assert!(
        (rss - target).abs() <= 1e-3 * target,
        "{rss} against {target}"
    );
    assert!(
        v["report"]["constraints"].to_string().contains("convex"),
        "{v}"
    );
    for (args, reason) in [
        (
            &["fit", "-", "--ctrl", "12", "--increasing"][..],
            "add --function",
        ),
        (
            &[
                "fit",
                "-",
                "--function",
                "--s",
                "0.1",
                "--knots",
                "3",
                "--convex",
            ][..],
            "or --knots with --s",
        ),
        (
            &["fit", "-", "--function", "--tolerance", "0.1", "--convex"][..],
            "drop --tolerance, --robust",
        ),
        (
            &["fit", "-", "--function", "--min", "0@1,2,3"][..],
            "is not an interval A:B or a point X",
        ),
        (
            &["fit", "-", "--function", "--through", "1"][..],
            "is not X=V",
        ),
        (
            &[
                "fit",
                "-",
                "--function",
                "--increasing",
                "--through",
                "0=1",
                "--through",
                "3=0",
            ][..],
            "cannot all hold",
        ),
    ] {
        lekalo()
            .args(args)
            .write_stdin(data.clone())
            .assert()
            .failure()
            .stderr(contains(reason));
    }
}
