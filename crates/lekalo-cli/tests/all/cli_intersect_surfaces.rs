//! End-to-end tests of `lekalo intersect` on surfaces: surface–surface and plane sections, the
//! summary, the branches as JSON Lines and STEP, a curve against a surface, refusals.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use predicates::str::contains;

use crate::common;
use common::{dir_with, json_of, lekalo, output_of, p};

/// The bump `z = 4uv(1 − u)(1 − v)` over `x = 2u, y = 2v` (biquadratic, the middle control point
/// raised to 1): height 1/4 in the middle.
const BUMP: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 2, "degree_v": 2,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1], "net": [3, 3],
 "control": [[0, 0, 0], [0, 1, 0], [0, 2, 0], [1, 0, 0], [1, 1, 1], [1, 2, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0]]}"#;
/// The plane z = 0.1 over [0, 2]².
const LEVEL: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 1, "degree_v": 1,
 "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1], "net": [2, 2],
 "control": [[0, 0, 0.1], [0, 2, 0.1], [2, 0, 0.1], [2, 2, 0.1]]}"#;
/// A quarter of the cylinder x² + z² = 1 for y in [0, 2] (exact NURBS).
const QUARTER: &str = r#"{"lekalo": 1, "type": "nurbs_surface", "degree_u": 2, "degree_v": 1,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "net": [3, 2],
 "control": [[1, 0, 0], [1, 2, 0], [1, 0, 1], [1, 2, 1], [0, 0, 1], [0, 2, 1]],
 "weights": [1, 1, 0.7071067811865476, 0.7071067811865476, 1, 1]}"#;
/// A curve (not a surface).
const LINE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 1], "control": [[0, 0, 0], [1, 1, 1]]}"#;

fn bump_z(x: f64, y: f64) -> f64 {
    let (u, v) = (x / 2.0, y / 2.0);
    4.0 * u * v * (1.0 - u) * (1.0 - v)
}

#[test]
fn bump_and_level_plane_give_one_loop() {
    let d = dir_with(&[("bump.json", BUMP), ("level.json", LEVEL)]);
    let out =
        output_of(
            lekalo()
                .current_dir(d.path())
                .args(["intersect", "bump.json", "level.json"]),
        );
    let text = String::from_utf8(out).unwrap();
    assert!(text.starts_with("0 crossing closed "), "{text}");
    assert_eq!(text.lines().count(), 1, "{text}");
    // the branches as JSON Lines: points on both surfaces, a fitted curve
    output_of(lekalo().current_dir(d.path()).args([
        "intersect",
        "bump.json",
        "level.json",
        "--tolerance",
        "1e-7",
        "-o",
        "b.json",
    ]));
    let all: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(p(&d, "b.json")).unwrap()).unwrap();
    assert_eq!(all.as_array().map(Vec::len), Some(1), "{all}");
    let b = &all[0];
    assert_eq!(b["kind"], "crossing");
    assert_eq!(b["closed"], true);
    assert_eq!(b["tolerance"], 1e-7);
    let pts = b["points"].as_array().unwrap();
    assert_eq!(Some(pts.len() as u64), b["point_count"].as_u64());
    for (q, uv) in pts.iter().zip(b["uv_b"].as_array().unwrap()) {
        let (x, y, z) = (
            q[0].as_f64().unwrap(),
            q[1].as_f64().unwrap(),
            q[2].as_f64().unwrap(),
        );
        assert!((z - 0.1).abs() <= 1e-7 && (bump_z(x, y) - z).abs() <= 1e-7);
        // the plane surface's parameters are x/2, y/2
        assert!((uv[0].as_f64().unwrap() - x / 2.0).abs() <= 1e-7);
    }
    assert_eq!(b["curve"]["type"], "bspline_curve");
    assert_eq!(b["curve_uv_a"]["type"], "bspline_curve");
    assert_eq!(b["curve_uv_b"]["type"], "bspline_curve");
    // the curve in space, written back, evaluates on the plane z = 0.1
    fs::write(p(&d, "curve.json"), b["curve"].to_string()).unwrap();
    let j = json_of(lekalo().current_dir(d.path()).args([
        "eval",
        "curve.json",
        "--samples",
        "9",
        "--json",
    ]));
    let rows = j.as_array().unwrap();
    assert_eq!(rows.len(), 9, "{j}");
    let last = &rows[8];
    let z = last["z"]
        .as_f64()
        .or_else(|| last["point"][2].as_f64())
        .unwrap_or(f64::NAN);
    assert!((z - 0.1).abs() <= 1e-6, "{last}");
    // -o FILE.jsonl: the same curve, one a line, read by every command as it is
    lekalo()
        .current_dir(d.path())
        .args([
            "intersect",
            "bump.json",
            "level.json",
            "--tolerance",
            "1e-7",
            "-o",
            "b.jsonl",
        ])
        .assert()
        .success();
    let lines = fs::read_to_string(p(&d, "b.jsonl")).unwrap();
    assert_eq!(lines.lines().count(), 1, "{lines}");
    let c: serde_json::Value = serde_json::from_str(lines.trim()).unwrap();
    assert_eq!(c, b["curve"]);
    let j = json_of(lekalo().current_dir(d.path()).args([
        "eval",
        "b.jsonl",
        "--samples",
        "3",
        "--json",
    ]));
    // every sample on the plane z = 0.1 (to rounding: the curve is fitted in floating point)
    let rows = j["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3, "{j}");
    for r in rows {
        assert!((r[3].as_f64().unwrap() - 0.1).abs() <= 1e-12, "{j}");
    }
}

#[test]
fn plane_section_of_a_nurbs_cylinder_json_summary_and_step() {
    let d = dir_with(&[("quarter.json", QUARTER)]);
    // the plane z = 0.5 x + 0.2 cuts the quarter cylinder in one open arc of an ellipse
    let j = json_of(lekalo().current_dir(d.path()).args([
        "intersect",
        "quarter.json",
        "--plane",
        "0,0,0.2,-0.5,0,1",
        "--json",
        "-o",
        "arc.json",
    ]));
    let list = j.as_array().unwrap();
    assert_eq!(list.len(), 1, "{j}");
    assert_eq!(list[0]["kind"], "crossing");
    assert_eq!(list[0]["closed"], false);
    let all: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(p(&d, "arc.json")).unwrap()).unwrap();
    let b = &all[0];
    assert_eq!(b["uv_b"].as_array().unwrap().len(), 0);
    assert!(b["curve_uv_b"].is_null());
    for q in b["points"].as_array().unwrap() {
        let (x, z) = (q[0].as_f64().unwrap(), q[2].as_f64().unwrap());
        assert!((x.hypot(z) - 1.0).abs() <= 1e-6 && (z - 0.5 * x - 0.2).abs() <= 1e-6);
    }
    output_of(lekalo().current_dir(d.path()).args([
        "intersect",
        "quarter.json",
        "--plane",
        "0,0,0.2,-0.5,0,1",
        "-o",
        "arc.step",
    ]));
    let step = fs::read_to_string(p(&d, "arc.step")).unwrap();
    assert!(step.contains("B_SPLINE_CURVE_WITH_KNOTS"), "{step}");
}

#[test]
fn misses_and_refusals() {
    let d = dir_with(&[("bump.json", BUMP), ("line.json", LINE)]);
    let out = output_of(lekalo().current_dir(d.path()).args([
        "intersect",
        "bump.json",
        "--plane",
        "0,0,5,0,0,1",
    ]));
    assert_eq!(String::from_utf8(out).unwrap(), "no intersection\n");
    lekalo()
        .current_dir(d.path())
        .args(["intersect", "bump.json", "line.json"])
        .assert()
        .code(2)
        .stderr(contains("not a surface"));
    lekalo()
        .current_dir(d.path())
        .args(["intersect", "bump.json", "--plane", "0,0,0,0,0"])
        .assert()
        .code(2)
        .stderr(contains("give 6 numbers"));
    lekalo()
        .current_dir(d.path())
        .args(["intersect", "bump.json", "--plane", "0,0,0,0,0,0"])
        .assert()
        .code(2)
        .stderr(contains("zero vector"));
    lekalo()
        .current_dir(d.path())
        .args(["intersect", "bump.json", "bump.json", "--tolerance=-1"])
        .assert()
        .code(2)
        .stderr(contains("tolerance"));
    lekalo()
        .current_dir(d.path())
        .args([
            "intersect",
            "bump.json",
            "--plane",
            "0,0,0.1,0,0,1",
            "-o",
            "x.csv",
        ])
        .assert()
        .code(2)
        .stderr(contains("jsonl, json or step"));
}

/// A vertical line through the bump's top: one crossing at z = 1/4; the bump's side x = 0 lies
/// on it: an overlap over the whole side. Kinds, parameters and points as the library gives them.
#[test]
fn a_curve_against_a_surface_crossing_and_overlap() {
    const UP: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 1], "control": [[1, 1, -1], [1, 1, 1]]}"#;
    const SIDE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 1], "control": [[0, 0, 0], [0, 2, 0]]}"#;
    let d = dir_with(&[("bump.json", BUMP), ("up.json", UP), ("side.json", SIDE)]);
    let v = json_of(lekalo().current_dir(d.path()).args([
        "intersect",
        "up.json",
        "bump.json",
        "--json",
    ]));
    let hits = v.as_array().unwrap();
    assert_eq!(hits.len(), 1, "{v}");
    assert_eq!(hits[0]["kind"], "crossing", "{v}");
    let num = |x: &serde_json::Value| x.as_f64().unwrap();
    assert!((num(&hits[0]["t"]) - 0.625).abs() <= 1e-12, "{v}");
    assert!((num(&hits[0]["uv"][0]) - 0.5).abs() <= 1e-12, "{v}");
    assert!((num(&hits[0]["uv"][1]) - 0.5).abs() <= 1e-12, "{v}");
    assert!((num(&hits[0]["point"][2]) - 0.25).abs() <= 1e-12, "{v}");
    // the CSV row: KIND,t,u,v,x,y,z
    let out = output_of(
        lekalo()
            .current_dir(d.path())
            .args(["intersect", "up.json", "bump.json"]),
    );
    let text = String::from_utf8(out).unwrap();
    let cells: Vec<&str> = text.trim().split(',').collect();
    assert_eq!(cells.len(), 7, "{text}");
    assert_eq!(cells[0], "crossing", "{text}");
    // the side of the bump lies on it: an overlap over the whole curve, uv at both ends
    let v = json_of(lekalo().current_dir(d.path()).args([
        "intersect",
        "side.json",
        "bump.json",
        "--json",
    ]));
    assert_eq!(v.as_array().map(Vec::len), Some(1), "{v}");
    assert_eq!(v[0]["kind"], "overlap", "{v}");
    assert_eq!(v[0]["t"], serde_json::json!([0.0, 1.0]), "{v}");
    assert!(num(&v[0]["uv"][0][0]).abs() <= 1e-9, "{v}");
    assert!((num(&v[0]["uv"][1][1]) - 1.0).abs() <= 1e-9, "{v}");
    let out =
        output_of(
            lekalo()
                .current_dir(d.path())
                .args(["intersect", "side.json", "bump.json"]),
        );
    assert_eq!(String::from_utf8(out).unwrap(), "overlap,0,1\n");
}
