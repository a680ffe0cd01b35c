//! End-to-end tests of `lekalo fit --grid NUxNV` and `--scattered` with shape constraints:
//! `--increasing[=u|v]`, `--decreasing[=u|v]`, `--min V`, `--max V`, on the whole domain or on
//! a box (`@U0:U1,V0:V1`).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fmt::Write as _;

use assert_cmd::Command;
use lekalo::fit::{surface_shape_violations, SurfaceShape, SurfaceShapeConstraints};
use lekalo::Direction;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// Rows `u v z` of a 16 × 12 table rising in u and v, with a ripple that makes a plain fit dip.
fn table() -> String {
    table_of(16, 12)
}

/// The table of [`table`] on an `nu × nv` grid.
fn table_of(nu: u32, nv: u32) -> String {
    let mut s = String::new();
    for i in 0..nu {
        for j in 0..nv {
            let (u, v) = (
                f64::from(i) / f64::from(nu - 1),
                f64::from(j) / f64::from(nv - 1),
            );
            let noise = 0.15 * (f64::from(7 * i + 3 * j) * 1.7).sin();
            let z = u + 0.5 * v * v + 0.25 * (9.0 * u).sin() + noise;
            writeln!(s, "{u} {v} {z}").unwrap();
        }
    }
    s
}

fn surface_of(args: &[&str], stdin: &str) -> (lekalo::BSplineSurface, serde_json::Value) {
    let out = lekalo()
        .args(args)
        .write_stdin(stdin)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let object = if v["object"].is_null() {
        v.clone()
    } else {
        v["object"].clone()
    };
    let s = lekalo_io::read_bspline_surface(&object.to_string(), "fit").unwrap();
    (s, v)
}

/// `fit` of the table on standard input as a 16 × 12 grid, a 6 × 5 net of degree 2.
const GRID_FIT: [&str; 8] = [
    "fit",
    "-",
    "--grid",
    "16x12",
    "--ctrl-grid",
    "6x5",
    "--degree",
    "2",
];

#[test]
fn a_table_on_a_grid_keeps_rising_in_both_directions() {
    let both = SurfaceShapeConstraints::new()
        .with(SurfaceShape::Increasing(Direction::U))
        .with(SurfaceShape::Increasing(Direction::V));
    let plain = GRID_FIT;
    // rows u, v, z: the plain fit of the table (values only, at the same coordinates) dips
    let values: String = table()
        .lines()
        .map(|l| format!("{}\n", l.split(' ').nth(2).unwrap()))
        .collect();
    let us: Vec<String> = (0..16).map(|i| (f64::from(i) / 15.0).to_string()).collect();
    let vs: Vec<String> = (0..12).map(|j| (f64::from(j) / 11.0).to_string()).collect();
    let (pu, pv) = (us.join(","), vs.join(","));
    let (free, _) = surface_of(
        &[&plain[..], &["--params-u", &pu, "--params-v", &pv]].concat(),
        &values,
    );
    assert!(surface_shape_violations(&free, &both).unwrap()[0] > 1e-3);
    for flags in [
        &["--increasing"][..],
        &["--increasing=u", "--increasing=v"],
        &["--increasing=u,v"],
    ] {
        let (s, _) = surface_of(&[&plain[..], flags].concat(), &table());
        assert_eq!(surface_shape_violations(&s, &both).unwrap(), vec![0.0, 0.0]);
        // values and coordinates given apart: the same surface
        let (t, _) = surface_of(
            &[&plain[..], flags, &["--params-u", &pu, "--params-v", &pv]].concat(),
            &values,
        );
        assert_eq!(s, t);
    }
}

#[test]
fn scattered_rows_keep_bounds_and_a_direction() {
    let mut rows = String::new();
    for k in 0..300 {
        let (u, v) = (
            (f64::from(k) * 0.618_034).fract(),
            (f64::from(k) * 0.414_214).fract(),
        );
        writeln!(
            rows,
            "{u} {v} {}",
            u * (1.0 - v) + 0.2 * (31.0 * f64::from(k)).sin()
        )
        .unwrap();
    }
    let (s, v) = surface_of(
        &[
            "fit",
            "-",
            "--scattered",
            "--ctrl-grid",
            "5x5",
            "--decreasing=v",
            "--min",
            "0",
            "--max",
            "0.8",
            "--max",
            "0.5@0:0.25,0.5:0.9",
            "--json",
        ],
        &rows,
    );
    assert_eq!(
        v["report"]["constraints"],
        serde_json::json!([
            "decreasing in v",
            "min 0",
            "max 0.8",
            "max 0.5 on [0, 0.25] × [0.5, 0.9]"
        ])
    );
    let c = SurfaceShapeConstraints::new()
        .with(SurfaceShape::Decreasing(Direction::V))
        .with(SurfaceShape::AtLeast(0.0))
        .with(SurfaceShape::AtMost(0.8))
        .with_on(SurfaceShape::AtMost(0.5), (0.0, 0.25), (0.5, 0.9));
    assert_eq!(
        surface_shape_violations(&s, &c).unwrap(),
        vec![0.0, 0.0, 0.0, 0.0]
    );
}

#[test]
fn surface_shapes_refuse_what_they_cannot_keep() {
    let grid = GRID_FIT;
    for (flags, message) in [
        (
            &["--min", "2", "--max", "1"][..],
            "min 2, max 1 contradict each other",
        ),
        (&["--convex"], "--convex is a shape of curves"),
        (&["--increasing=w"], "--increasing=u, --increasing=v"),
        (&["--min", "0@0:1"], "is not a box U0:U1,V0:V1"),
        (
            &["--increasing=u@0:2,0:1"],
            "leaves the domain [0, 1] of the fit in u",
        ),
        (&["--min", "x@0:1,0:1"], "is not V or V@U0:U1,V0:V1"),
    ] {
        lekalo()
            .args([&grid[..], flags].concat())
            .write_stdin(table())
            .assert()
            .code(2)
            .stderr(contains(message));
    }
    // points in space are not a table
    let mut bent = String::new();
    for i in 0..16 {
        for j in 0..12 {
            writeln!(
                bent,
                "{} {} 0",
                f64::from(i) + 0.1 * f64::from(j),
                f64::from(j)
            )
            .unwrap();
        }
    }
    lekalo()
        .args([&grid[..], &["--increasing"]].concat())
        .write_stdin(bent)
        .assert()
        .code(2)
        .stderr(contains("off the table's lines"));
}

#[test]
fn a_shape_on_a_box_holds_there_only() {
    // the table falls in u left of u = 0.4 and rises after: increasing in u on the right part
    let mut rows = String::new();
    for i in 0..21 {
        for j in 0..11 {
            let (u, v) = (f64::from(i) / 20.0, f64::from(j) / 10.0);
            let z = (u - 0.4) * (u - 0.4) + 0.3 * v + 0.08 * (23.0 * u + 5.0 * v).sin();
            writeln!(rows, "{u} {v} {z}").unwrap();
        }
    }
    let fit = [
        "fit",
        "-",
        "--grid",
        "21x11",
        "--ctrl-grid",
        "9x6",
        "--degree",
        "2",
        "--json",
    ];
    // the plain fit of z(u, v): a bound it keeps returns it unchanged
    let (free, _) = surface_of(&[&fit[..], &["--max", "1000"]].concat(), &rows);
    let boxed = SurfaceShapeConstraints::new().with_on(
        SurfaceShape::Increasing(Direction::U),
        (0.45, 1.0),
        (0.1, 0.9),
    );
    let minimum =
        SurfaceShapeConstraints::new().with_on(SurfaceShape::AtLeast(0.05), (0.3, 0.5), (0.0, 1.0));
    assert!(surface_shape_violations(&free, &boxed).unwrap()[0] > 1e-3);
    assert!(surface_shape_violations(&free, &minimum).unwrap()[0] > 1e-3);
    let (s, v) = surface_of(
        &[
            &fit[..],
            &["--increasing=u@0.45:1,0.1:0.9", "--min", "0.05@0.3:0.5,0:1"],
        ]
        .concat(),
        &rows,
    );
    // --json on a grid: the object and its report
    assert_eq!(
        v["report"]["constraints"],
        serde_json::json!([
            "increasing in u on [0.45, 1] × [0.1, 0.9]",
            "min 0.05 on [0.3, 0.5] × [0, 1]"
        ])
    );
    assert_eq!(v["report"]["control_points"], 54);
    let rms = v["report"]["rms"].as_f64().unwrap();
    assert!(rms > 0.0 && rms < 0.1, "{rms}");
    assert_eq!(surface_shape_violations(&s, &boxed).unwrap(), vec![0.0]);
    assert_eq!(surface_shape_violations(&s, &minimum).unwrap(), vec![0.0]);
    // left of the box the fit still falls in u, as the data do
    let (mut a, mut b) = ([0.0], [0.0]);
    s.eval_into(0.05, 0.5, &mut a).unwrap();
    s.eval_into(0.25, 0.5, &mut b).unwrap();
    assert!(b[0] < a[0], "{a:?} {b:?}");
}

/// The grid's smoothing spline of `args` (a `bspline_tensor` in two variables) as a surface,
/// with the report.
fn smoothed(args: &[&str], stdin: String) -> (lekalo::BSplineSurface, serde_json::Value) {
    let out = lekalo()
        .args(args)
        .write_stdin(stdin)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let lekalo::Tensor::BSpline(t) =
        lekalo_io::read_tensor(&v["object"].to_string(), "fit").unwrap()
    else {
        panic!("a B-spline tensor: {v}")
    };
    (t.to_surface().unwrap(), v["report"].clone())
}

#[test]
fn a_grid_smoothed_in_shape_keeps_it_with_its_weights_or_its_residual() {
    let rising = SurfaceShapeConstraints::new().with(SurfaceShape::Increasing(Direction::U));
    let base = ["fit", "-", "--grid", "16x12", "--json"];
    // without shapes, rows u, v, z on a grid are points of a surface in space: the table's
    // plain smoothing spline reads its values alone at the coordinates
    let values: String = table()
        .lines()
        .map(|l| format!("{}\n", l.split(' ').nth(2).unwrap()))
        .collect();
    let us: Vec<String> = (0..16).map(|i| (f64::from(i) / 15.0).to_string()).collect();
    let vs: Vec<String> = (0..12).map(|j| (f64::from(j) / 11.0).to_string()).collect();
    let (pu, pv) = (us.join(","), vs.join(","));
    let coordinates = ["--params-u", &pu, "--params-v", &pv];
    let (free, plain) = smoothed(
        &[&base[..], &["--smooth", "1e-5,1e-4"], &coordinates[..]].concat(),
        values.clone(),
    );
    assert!(surface_shape_violations(&free, &rising).unwrap()[0] > 1e-3);
    let (s, report) = smoothed(
        &[&base[..], &["--smooth", "1e-5,1e-4", "--increasing=u"]].concat(),
        table(),
    );
    assert_eq!(surface_shape_violations(&s, &rising).unwrap(), vec![0.0]);
    assert_eq!(report["constraints"][0], "increasing in u");
    // the weights are those given; the residual rises
    assert_eq!(report["lambda"], plain["lambda"]);
    let rss = |r: &serde_json::Value| r["weighted_rss"].as_f64().unwrap();
    assert!(rss(&report) > rss(&plain));
    // the smoothing condition: the residual asked, in shape (on a 14 × 10 table, where the
    // weights it needs keep the program well enough conditioned)
    let small = ["fit", "-", "--grid", "14x10", "--json"];
    let (_, gcv) = smoothed(
        &[&small[..], &["--smooth", "gcv", "--increasing=u"]].concat(),
        table_of(14, 10),
    );
    let target = 1.3 * rss(&gcv);
    let (s, report) = smoothed(
        &[&small[..], &["--s", &target.to_string(), "--increasing=u"]].concat(),
        table_of(14, 10),
    );
    // one value a node at the coordinates gives the same fit as the rows u, v, z
    let (same, _) = smoothed(
        &[
            &base[..],
            &["--smooth", "1e-5,1e-4", "--increasing=u"],
            &coordinates[..],
        ]
        .concat(),
        values,
    );
    let (rows, _) = smoothed(
        &[&base[..], &["--smooth", "1e-5,1e-4", "--increasing=u"]].concat(),
        table(),
    );
    assert_eq!(same, rows);
    assert_eq!(surface_shape_violations(&s, &rising).unwrap(), vec![0.0]);
    assert_eq!(surface_shape_violations(&s, &rising).unwrap(), vec![0.0]);
    assert!((rss(&report) - target).abs() <= 1e-3 * target, "{report}");
    // refusals in the user's words
    for (flags, message) in [
        (&["--smooth", "0", "--increasing=u"][..], "give λ > 0"),
        (&["--s", "1e-9", "--max", "0"], "give s ≥"),
        (
            &["--smooth", "gcv", "--ctrl-grid", "6x5", "--increasing=u"],
            "a knot at every grid line",
        ),
    ] {
        lekalo()
            .args([&base[..], flags].concat())
            .write_stdin(table())
            .assert()
            .code(2)
            .stderr(contains(message));
    }
}
