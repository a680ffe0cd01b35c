//! End-to-end tests of the options of `lekalo fit` that give a fit its own knots and domain:
//! `--domain` of a least-squares curve, and `--knots-u`/`--knots-v`, `--bbox`, `--degree P,Q`,
//! `--params-u`/`--params-v` of grid and scattered surfaces. Each fit reproduces a polynomial
//! of its spline space, so the result is known exactly, also outside the data.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fmt::Write as _;

use crate::common;
use common::{dir_with, eval_fitted, json_of, lekalo, p};

/// The cubic y(x) = 1 − 2x + 0.1x³, which every cubic spline space reproduces.
fn cubic(x: f64) -> f64 {
    1.0 - 2.0 * x + 0.1 * x * x * x
}

/// 40 samples `x y` of [`cubic`] on [0, 10].
fn cubic_samples() -> String {
    let mut s = String::new();
    for k in 0..40 {
        let x = f64::from(k) / 39.0 * 10.0;
        writeln!(s, "{x} {}", cubic(x)).unwrap();
    }
    s
}

/// z(u, v) = u³ − u·v² + 2v, of degree 3 in u and 2 in v.
fn z(u: f64, v: f64) -> f64 {
    u * u * u - u * v * v + 2.0 * v
}

/// 300 scattered rows `u v z` of [`z`] in [0, 1]², by a golden-ratio sequence.
fn scattered_rows() -> String {
    let mut s = String::new();
    for k in 0..300 {
        let u = (f64::from(k) * 0.618_033_988_7).fract();
        let v = (f64::from(k) * 0.754_877_666_2).fract();
        writeln!(s, "{u} {v} {}", z(u, v)).unwrap();
    }
    s
}

/// The unevenly spaced grid parameters: `u_i = (i/(n−1))²·2`, `v_j = 3·j/(n−1) − 1`.
fn grid_u(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            2.0 * t * t
        })
        .collect()
}

fn grid_v(n: usize) -> Vec<f64> {
    (0..n)
        .map(|j| 3.0 * j as f64 / (n - 1) as f64 - 1.0)
        .collect()
}

/// A 12 × 9 grid of points `(u, v, z(u, v))` at [`grid_u`] × [`grid_v`], rows first.
fn grid_points() -> String {
    let mut s = String::new();
    for &u in &grid_u(12) {
        for &v in &grid_v(9) {
            writeln!(s, "{u} {v} {}", z(u, v)).unwrap();
        }
    }
    s
}

fn list(values: &[f64]) -> String {
    values
        .iter()
        .map(f64::to_string)
        .collect::<Vec<_>>()
        .join(",")
}

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The error message of a failing `lekalo ARGS` run in `dir` (exit code 2).
fn refusal(dir: &tempfile::TempDir, args: &[&str]) -> String {
    let out = lekalo()
        .current_dir(dir.path())
        .args(args)
        .assert()
        .code(2)
        .get_output()
        .stderr
        .clone();
    String::from_utf8(out).unwrap()
}

#[test]
fn a_least_squares_curve_reaches_beyond_its_data_with_domain() {
    let d = dir_with(&[("xy.txt", &cubic_samples())]);
    // --ctrl: the interior knots placed over the data, the end knots at the domain's ends
    let fit = json_of(lekalo().current_dir(d.path()).args([
        "fit",
        "xy.txt",
        "--function",
        "--ctrl",
        "6",
        "--domain",
        "-2:12",
        "--json",
    ]));
    let knots = numbers(&fit["object"]["knots"]);
    assert_eq!(knots.len(), 10);
    assert_eq!(&knots[..4], &[-2.0; 4]);
    assert_eq!(&knots[6..], &[12.0; 4]);
    assert!(knots[4] > 0.0 && knots[5] < 10.0, "{knots:?}");
    assert!(fit["report"]["max_residual"].as_f64().unwrap() < 1e-10);
    // --knots: the interior knots given, inside the domain
    lekalo()
        .current_dir(d.path())
        .args([
            "fit",
            "xy.txt",
            "--function",
            "--knots",
            "3,6",
            "--domain",
            "-2:12",
            "-o",
            "wide.json",
            "--json",
        ])
        .assert()
        .success();
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p(&d, "wide.json")).unwrap()).unwrap();
    assert!(written["report"]["max_residual"].as_f64().unwrap() < 1e-10);
    assert_eq!(
        numbers(&written["object"]["knots"]),
        [-2.0, -2.0, -2.0, -2.0, 3.0, 6.0, 12.0, 12.0, 12.0, 12.0]
    );
    // the cubic is reproduced outside the data too, up to the domain's ends
    for (t, x) in eval_fitted(&d, &written["object"], "-2,-1,11,12") {
        assert!(
            (x - cubic(t)).abs() < 1e-9,
            "y({t}) = {x}, not {}",
            cubic(t)
        );
    }
}

/// `--s` with `--domain`: the smoothing condition with its end knots at the domain (splrep's
/// `xb`, `xe`); the cubic's own samples need no interior knot, and the cubic continues to the
/// domain's ends.
#[test]
fn the_smoothing_condition_takes_a_domain_wider_than_the_data() {
    let d = dir_with(&[("xy.txt", &cubic_samples())]);
    let fit = json_of(lekalo().current_dir(d.path()).args([
        "fit",
        "xy.txt",
        "--function",
        "--s",
        "0.01",
        "--domain",
        "-2:12",
        "--json",
    ]));
    assert_eq!(
        numbers(&fit["object"]["knots"]),
        [-2.0, -2.0, -2.0, -2.0, 12.0, 12.0, 12.0, 12.0]
    );
    assert!(fit["report"]["max_residual"].as_f64().unwrap() < 1e-10);
    for (t, x) in eval_fitted(&d, &fit["object"], "-2,11.5") {
        assert!(
            (x - cubic(t)).abs() < 1e-9,
            "y({t}) = {x}, not {}",
            cubic(t)
        );
    }
}

#[test]
fn domain_refuses_what_it_cannot_do_and_says_why() {
    let d = dir_with(&[("xy.txt", &cubic_samples())]);
    let e = refusal(&d, &["fit", "xy.txt", "--function", "--domain", "1:12"]);
    assert!(e.contains("--domain 1:12 does not hold the data"), "{e}");
    assert!(e.contains("--domain 0:12"), "the fix: {e}");
    let e = refusal(&d, &["fit", "xy.txt", "--function", "--domain", "12:1"]);
    assert!(e.contains("not an interval A:B with A < B"), "{e}");
    let e = refusal(
        &d,
        &[
            "fit",
            "xy.txt",
            "--function",
            "--knots",
            "5,13",
            "--domain",
            "-2:12",
        ],
    );
    assert!(e.contains("--knots: the knot 13 is not inside"), "{e}");
    for mode in [["--smooth", "gcv"], ["--tolerance", "0.1"]] {
        let e = refusal(
            &d,
            &[
                "fit",
                "xy.txt",
                "--function",
                mode[0],
                mode[1],
                "--domain",
                "-2:12",
            ],
        );
        assert!(e.contains("drop --domain"), "{e}");
    }
    let e = refusal(
        &d,
        &[
            "fit",
            "xy.txt",
            "--function",
            "--s",
            "0.1",
            "--increasing",
            "--domain",
            "-2:12",
        ],
    );
    assert!(e.contains("drop --domain"), "{e}");
    let e = refusal(&d, &["fit", "xy.txt", "--clamp-ends", "--domain", "-2:12"]);
    assert!(e.contains("--clamp-ends"), "{e}");
    let e = refusal(&d, &["fit", "xy.txt", "--function", "--degree", "3,2"]);
    assert!(
        e.contains("--degree: 2 degrees given; a curve takes one"),
        "{e}"
    );
}

#[test]
fn a_scattered_fit_takes_knots_bbox_and_a_degree_per_direction() {
    let d = dir_with(&[("uvz.txt", &scattered_rows())]);
    let fit = json_of(lekalo().current_dir(d.path()).args([
        "fit",
        "uvz.txt",
        "--scattered",
        "--degree",
        "3,2",
        "--knots-u",
        "0.3,0.6",
        "--knots-v",
        "0.5",
        "--bbox",
        "-0.5:1.5,-1:2",
        "--json",
    ]));
    let s = &fit["object"];
    assert_eq!(
        (s["degree_u"].as_u64(), s["degree_v"].as_u64()),
        (Some(3), Some(2))
    );
    assert_eq!(
        numbers(&s["knots_u"]),
        [-0.5, -0.5, -0.5, -0.5, 0.3, 0.6, 1.5, 1.5, 1.5, 1.5]
    );
    assert_eq!(
        numbers(&s["knots_v"]),
        [-1.0, -1.0, -1.0, 0.5, 2.0, 2.0, 2.0]
    );
    assert!(
        fit["report"]["max_residual"].as_f64().unwrap() < 1e-8,
        "{}",
        fit["report"]
    );
    // z(u, v) is in the space: reproduced also at the corners of the bbox, outside the data
    std::fs::write(p(&d, "s.json"), serde_json::to_string(s).unwrap()).unwrap();
    let rows = json_of(lekalo().current_dir(d.path()).args([
        "eval",
        "s.json",
        "--uv",
        "-0.5,-1,1.5,2,1.2,-0.7",
        "--json",
    ]));
    for row in rows.as_array().unwrap() {
        let (u, v) = (row["u"].as_f64().unwrap(), row["v"].as_f64().unwrap());
        let got = row["x"].as_f64().unwrap();
        assert!(
            (got - z(u, v)).abs() < 1e-7,
            "z({u}, {v}) = {got}, not {}",
            z(u, v)
        );
    }
    // knots in one direction, a count in the other
    let fit = json_of(lekalo().current_dir(d.path()).args([
        "fit",
        "uvz.txt",
        "--scattered",
        "--knots-u",
        "0.5",
        "--ctrl-grid",
        "5x4",
        "--json",
    ]));
    assert_eq!(fit["object"]["net"], serde_json::json!([5, 4]));
}

#[test]
fn scattered_options_are_checked_against_each_other() {
    let d = dir_with(&[("uvz.txt", &scattered_rows())]);
    let e = refusal(
        &d,
        &[
            "fit",
            "uvz.txt",
            "--scattered",
            "--knots-u",
            "0.3,0.6",
            "--ctrl-grid",
            "5x5",
        ],
    );
    assert!(
        e.contains("--ctrl-grid and --knots-u disagree") && e.contains("--ctrl-grid 6x5"),
        "{e}"
    );
    let e = refusal(&d, &["fit", "uvz.txt", "--scattered", "--knots-u", "0.5"]);
    assert!(e.contains("v has neither"), "{e}");
    let e = refusal(
        &d,
        &[
            "fit",
            "uvz.txt",
            "--scattered",
            "--ctrl-grid",
            "5x5",
            "--bbox",
            "0.2:1,0:1",
        ],
    );
    assert!(e.contains("--bbox:") && e.contains("u interval"), "{e}");
    let e = refusal(
        &d,
        &[
            "fit",
            "uvz.txt",
            "--scattered",
            "--ctrl-grid",
            "5x5",
            "--bbox",
            "0:1",
        ],
    );
    assert!(e.contains("is not U0:U1,V0:V1"), "{e}");
    let e = refusal(
        &d,
        &[
            "fit",
            "uvz.txt",
            "--scattered",
            "--ctrl-grid",
            "5x5",
            "--degree",
            "3,2,1",
        ],
    );
    assert!(
        e.contains("a surface takes one, or one per direction"),
        "{e}"
    );
    let e = refusal(
        &d,
        &[
            "fit",
            "uvz.txt",
            "--scattered",
            "--ctrl-grid",
            "5x5",
            "--params-u",
            "0,1",
        ],
    );
    assert!(e.contains("--scattered reads u and v"), "{e}");
    let e = refusal(
        &d,
        &[
            "fit",
            "uvz.txt",
            "--scattered",
            "--ctrl-grid",
            "5x5",
            "--knots",
            "0.5",
        ],
    );
    assert!(e.contains("--knots-u and --knots-v"), "{e}");
    let e = refusal(
        &d,
        &["fit", "uvz.txt", "--knots-u", "0.5", "--bbox", "0:1,0:1"],
    );
    assert!(e.contains("--knots-u, --bbox are for surfaces"), "{e}");
}

#[test]
fn a_grid_fit_takes_its_parameters_and_knots() {
    let v = grid_v(9);
    let v_file: String = v.iter().map(|x| format!("{x}\n")).collect();
    let d = dir_with(&[("grid.txt", &grid_points()), ("v.txt", &v_file)]);
    let u_list = list(&grid_u(12));
    let fit = || {
        let mut c = lekalo();
        c.current_dir(d.path()).args([
            "fit",
            "grid.txt",
            "--grid",
            "12x9",
            "--degree",
            "3,2",
            "--params-u",
            &u_list,
            "--params-v",
            "v.txt",
            "--knots-u",
            "0.5,1",
            "--knots-v",
            "0",
            "-o",
            "s.json",
        ]);
        c
    };
    fit().assert().success();
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p(&d, "s.json")).unwrap()).unwrap();
    assert_eq!(
        numbers(&s["knots_u"]),
        [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 2.0, 2.0, 2.0, 2.0]
    );
    assert_eq!(
        numbers(&s["knots_v"]),
        [-1.0, -1.0, -1.0, 0.0, 2.0, 2.0, 2.0]
    );
    // the points (u, v, z(u, v)) are in the space at these parameters: S(u, v) is the point
    let rows = json_of(lekalo().current_dir(d.path()).args([
        "eval",
        "s.json",
        "--uv",
        "0.3,-0.4,1.7,1.9",
        "--json",
    ]));
    for row in rows.as_array().unwrap() {
        let (u, v) = (row["u"].as_f64().unwrap(), row["v"].as_f64().unwrap());
        let got = [
            row["x"].as_f64().unwrap(),
            row["y"].as_f64().unwrap(),
            row["z"].as_f64().unwrap(),
        ];
        let want = [u, v, z(u, v)];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-9, "S({u}, {v}) = {got:?}, not {want:?}");
        }
    }
    // a wider bbox with placed knots (--ctrl-grid): the end knots move, the parameters stay
    lekalo()
        .current_dir(d.path())
        .args([
            "fit",
            "grid.txt",
            "--grid",
            "12x9",
            "--ctrl-grid",
            "6x4",
            "--params-u",
            &u_list,
            "--params-v",
            "v.txt",
            "--bbox",
            "-1:3,-2:2",
            "-o",
            "wide.json",
        ])
        .assert()
        .success();
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p(&d, "wide.json")).unwrap()).unwrap();
    let (ku, kv) = (numbers(&s["knots_u"]), numbers(&s["knots_v"]));
    assert_eq!((ku.len(), kv.len()), (10, 8));
    assert_eq!((&ku[..4], &ku[6..]), (&[-1.0; 4][..], &[3.0; 4][..]));
    assert_eq!((&kv[..4], &kv[4..]), (&[-2.0; 4][..], &[2.0; 4][..]));
}

#[test]
fn grid_parameters_are_checked() {
    let d = dir_with(&[("grid.txt", &grid_points())]);
    let e = refusal(
        &d,
        &[
            "fit",
            "grid.txt",
            "--grid",
            "12x9",
            "--ctrl-grid",
            "5x4",
            "--params-u",
            "0,1,2",
        ],
    );
    assert!(
        e.contains("--params-u: 3 values for the 12 rows of --grid 12x9"),
        "{e}"
    );
    let e = refusal(
        &d,
        &[
            "fit",
            "grid.txt",
            "--grid",
            "12x9",
            "--ctrl-grid",
            "5x4",
            "--bbox",
            "0.5:1,0:1",
        ],
    );
    assert!(
        e.contains("--bbox: the u parameters of the grid's rows"),
        "{e}"
    );
    let e = refusal(
        &d,
        &[
            "fit",
            "grid.txt",
            "--grid",
            "12x9",
            "--knots-u",
            "0.5",
            "--knots-v",
            "2.5",
        ],
    );
    assert!(e.contains("--knots-v: the knot 2.5 is not inside"), "{e}");
}

#[test]
fn help_lists_the_options() {
    let help = common::help_of(&["fit".to_string()]);
    for option in [
        "--domain <A:B>",
        "--knots-u <LIST>",
        "--knots-v <LIST>",
        "--bbox <U0:U1,V0:V1>",
        "--params-u <LIST|FILE>",
        "--params-v <LIST|FILE>",
        "--degree <P[,Q]>",
    ] {
        assert!(help.contains(option), "{option} missing from fit --help");
    }
}

/// 400 samples of `sin(8x)·e^(−x)` on [0, 1] with a fixed pseudo-noise of amplitude 0.05 (the
/// data of `scripts/knot_rounds_golden.py`).
fn noisy_samples() -> String {
    let mut s = String::new();
    for k in 0..400_i32 {
        let x = f64::from(k) / 399.0;
        let j = f64::from(k + 17);
        let noise = (j * 0.618_033_988_749_894_9 + 0.1 * j.sin()).fract() - 0.5;
        let y = (8.0 * x).sin() * (-x).exp() + 0.05 * noise;
        writeln!(s, "{x} {y}").unwrap();
    }
    s
}

/// `--knot-rounds`: FITPACK's shared rounds (splrep's 16 knots on this data) by default,
/// SciPy's `make_splrep` rounds (a fit after every knot: 15 knots) with `refit`; both within
/// `--s`. Where the rounds do not apply it is refused, and an unknown word lists the two.
#[test]
fn knot_rounds_choose_fitpacks_or_scipys_make_splrep_knots() {
    let d = dir_with(&[("xy.txt", &noisy_samples())]);
    let s = 400.0 * 0.05 * 0.05 / 12.0;
    let fit = |rounds: Option<&str>| {
        let mut args = vec!["fit", "xy.txt", "--function", "--json"];
        let s_text = s.to_string();
        args.extend(["--s", &s_text]);
        if let Some(r) = rounds {
            args.extend(["--knot-rounds", r]);
        }
        json_of(lekalo().current_dir(d.path()).args(&args))
    };
    for (rounds, knots) in [(None, 16), (Some("shared"), 16), (Some("refit"), 15)] {
        let f = fit(rounds);
        assert_eq!(numbers(&f["object"]["knots"]).len(), knots, "{rounds:?}");
        let rss = f["report"]["weighted_rss"].as_f64().unwrap();
        assert!(rss <= s && rss >= 0.999 * s, "{rounds:?}: rss {rss}");
    }
    let e = refusal(
        &d,
        &[
            "fit",
            "xy.txt",
            "--function",
            "--s",
            "0.1",
            "--knot-rounds",
            "fresh",
        ],
    );
    assert!(e.contains("shared") && e.contains("refit"), "{e}");
    let e = refusal(
        &d,
        &["fit", "xy.txt", "--function", "--knot-rounds", "refit"],
    );
    assert!(e.contains("--s"), "{e}");
    for extra in [&["--knots", "0.5"][..], &["--increasing"], &["--periodic"]] {
        let mut args = vec!["fit", "xy.txt", "--function", "--s", "0.1"];
        args.extend(extra);
        args.extend(["--knot-rounds", "refit"]);
        let e = refusal(&d, &args);
        assert!(e.contains("drop --knot-rounds"), "{e}");
    }
}
