//! End-to-end tests of the geometric-query subcommands: measure, project, intersect, offset,
//! mesh.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::common;
use common::{dir_with, json_of, lekalo, output_of, p};

/// A polyline (0,0) → (3,4) → (3,0): length 9.
const POLY: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 2, 2], "control": [[0, 0], [3, 4], [3, 0]]}"#;
/// The line y = 1 from x = −2 to 4.
const LINE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 1], "control": [[-2, 1], [4, 1]]}"#;
/// A cubic with a loop.
const LOOP: &str =
    r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [3, 2], [-1, 2], [2, 0]]}"#;
/// The parabola y = x² on [−1, 1] (t = (x + 1)/2): radius of curvature 1/2 at the vertex.
const PARABOLA: &str =
    r#"{"lekalo": 1, "type": "bezier_curve", "control": [[-1, 1], [0, -1], [1, 1]]}"#;
/// A gently curved planar cubic (curvature well below 10 everywhere).
const WAVE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 3,
 "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1], "control": [[0, 0], [1, 1], [2, -0.5], [3, 0.5], [4, 0]]}"#;
/// A space curve (no offset).
const SPACE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 1,
 "knots": [0, 0, 1, 1], "control": [[0, 0, 0], [1, 1, 1]]}"#;
/// z = x² over [0, 1]², bilinear in y.
const SURFACE: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 2, "degree_v": 1,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "net": [3, 2],
 "control": [[0, 0, 0], [0, 1, 0], [0.5, 0, 0], [0.5, 1, 0], [1, 0, 1], [1, 1, 1]]}"#;

#[test]
fn measure_length_and_inverse() {
    let d = dir_with(&[("poly.json", POLY)]);
    let j = json_of(
        lekalo()
            .args(["measure", "--json", "--at-length", "5,7"])
            .arg(p(&d, "poly.json")),
    );
    assert!((j["length"].as_f64().unwrap() - 9.0).abs() < 1e-13);
    // length 7 is 2 along the second leg of length 4: t = 1.5
    assert!((j["at_length"][1]["t"].as_f64().unwrap() - 1.5).abs() < 1e-12);
    assert_eq!(j["bounding_box"]["max"][1].as_f64().unwrap(), 4.0);
    // a length beyond the curve is bad input
    lekalo()
        .args(["measure", "--at-length", "10"])
        .arg(p(&d, "poly.json"))
        .assert()
        .code(2)
        .stderr(contains("arc length"));
}

/// An S-shaped cubic: x = 3t, y = 3t(1 − t)(1 − 2t), whose `C' × C'' = 3y''` changes sign at
/// t = 1/2 only.
const S_CURVE: &str =
    r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1], [2, -1], [3, 0]]}"#;

/// The exact quarter circle of `lekalo make nurbs --help`: its curvature is constant, so it
/// has no curvature extrema (rounding once made 22 of them).
#[test]
fn measure_of_an_exact_arc_reports_no_curvature_extrema() {
    let arc = r#"{"lekalo": 1, "type": "nurbs_curve", "degree": 2, "knots": [0, 0, 0, 1, 1, 1],
        "control": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.7071067811865476, 1]}"#;
    let d = dir_with(&[("arc.json", arc), ("parabola.json", PARABOLA)]);
    let j = json_of(lekalo().args(["measure", "--json"]).arg(p(&d, "arc.json")));
    assert_eq!(j["curvature_extrema"], serde_json::json!([]), "{j}");
    // a real extremum stays: the parabola's vertex
    let j = json_of(
        lekalo()
            .args(["measure", "--json"])
            .arg(p(&d, "parabola.json")),
    );
    assert_eq!(
        j["curvature_extrema"].as_array().map(Vec::len),
        Some(1),
        "{j}"
    );
}

#[test]
fn measure_reports_the_inflections_of_planar_curves() {
    let d = dir_with(&[
        ("s.json", S_CURVE),
        ("parabola.json", PARABOLA),
        ("space.json", SPACE),
    ]);
    let json = |name: &str| json_of(lekalo().args(["measure", "--json"]).arg(p(&d, name)));
    let t: Vec<f64> = json("s.json")["inflections"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(t.len(), 1, "{t:?}");
    assert!((t[0] - 0.5).abs() < 1e-12, "{t:?}");
    assert_eq!(json("parabola.json")["inflections"], serde_json::json!([]));
    // a space curve has no signed curvature: no inflections key
    assert!(json("space.json").get("inflections").is_none());
    lekalo()
        .arg("measure")
        .arg(p(&d, "s.json"))
        .assert()
        .success()
        .stdout(contains("inflections at t = 0.5"));
    lekalo()
        .arg("measure")
        .arg(p(&d, "parabola.json"))
        .assert()
        .success()
        .stdout(contains("inflections none"));
}

#[test]
fn measure_surface_box_is_the_surface_not_its_net() {
    // z = 4u(1 − u): the net reaches z = 2, the surface z = 1
    let arch = SURFACE.replace(
        "[0.5, 0, 0], [0.5, 1, 0], [1, 0, 1], [1, 1, 1]",
        "[0.5, 0, 2], [0.5, 1, 2], [1, 0, 0], [1, 1, 0]",
    );
    let d = dir_with(&[("arch.json", arch.as_str())]);
    let j = json_of(lekalo().args(["measure", "--json"]).arg(p(&d, "arch.json")));
    let b = &j["bounding_box"];
    assert!((b["max"][2].as_f64().unwrap() - 1.0).abs() <= b["tolerance"].as_f64().unwrap());
    assert_eq!(b["min"][2].as_f64().unwrap(), 0.0);
    assert_eq!(j["domain"]["v"][1].as_f64().unwrap(), 1.0);
    lekalo()
        .args(["measure", "--at-length", "1"])
        .arg(p(&d, "arch.json"))
        .assert()
        .code(2)
        .stderr(contains("measure curves"));
}

#[test]
fn plot_comb_draws_teeth_for_planar_curves_only() {
    let d = dir_with(&[
        ("p.json", PARABOLA),
        ("space.json", SPACE),
        ("s.json", SURFACE),
    ]);
    let svg = String::from_utf8(output_of(
        lekalo()
            .args(["plot", "--comb", "--comb-teeth", "5"])
            .arg(p(&d, "p.json")),
    ))
    .unwrap();
    assert!(svg.contains("curvature comb"), "no comb legend");
    let plain = lekalo().arg("plot").arg(p(&d, "p.json")).output().unwrap();
    assert!(svg.len() > plain.stdout.len(), "the comb adds nothing");
    for bad in ["space.json", "s.json"] {
        lekalo()
            .args(["plot", "--comb"])
            .arg(p(&d, bad))
            .assert()
            .code(2);
    }
    lekalo()
        .args(["plot", "--comb", "--comb-teeth", "1"])
        .arg(p(&d, "p.json"))
        .assert()
        .code(2);
}

#[test]
fn project_single_batch_and_all() {
    let d = dir_with(&[("poly.json", POLY), ("q.csv", "3.5,2\n-1,-1\n")]);
    lekalo()
        .args(["project", "--point", "4,2"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stdout("index,t,x,y,distance\n0,1.5,3,2,1\n");
    // a surface's rows have u, v; the header names them as `eval` does
    let surf = dir_with(&[(
        "net.csv",
        "0 0 0\n0 1 0\n0 2 0\n1 0 0\n1 1 1\n1 2 0\n2 0 0\n2 1 0\n2 2 0\n",
    )]);
    lekalo()
        .args([
            "make",
            "bspline-surface",
            "--net",
            "3x3",
            "--degree",
            "2",
            "--control",
        ])
        .arg(p(&surf, "net.csv"))
        .arg("-o")
        .arg(p(&surf, "s.json"))
        .assert()
        .success();
    let out = output_of(
        lekalo()
            .args(["project", "--point", "1,1,2"])
            .arg(p(&surf, "s.json")),
    );
    let out = String::from_utf8(out).unwrap();
    assert!(out.starts_with("index,u,v,x,y,z,distance\n0,"), "{out}");
    let j = json_of(
        lekalo()
            .args(["project", "--json", "--points"])
            .arg(p(&d, "q.csv"))
            .arg(p(&d, "poly.json")),
    );
    assert_eq!(j.as_array().unwrap().len(), 2);
    assert!((j[1]["distance"].as_f64().unwrap() - 2f64.sqrt()).abs() < 1e-14);
    // a distance of 2^-23 reads as the tables write it (1.1920928955078125e-7), not as
    // 0.00000011920928955078125
    let out = String::from_utf8(output_of(
        lekalo()
            .args(["project", "--point", "3.00000011920928955078125,2"])
            .arg(p(&d, "poly.json")),
    ))
    .unwrap();
    let distance = out.lines().nth(1).unwrap().rsplit(',').next().unwrap();
    assert_eq!(distance, "1.1920928955078125e-7", "{out}");
    lekalo()
        .args(["project", "--point", "nan,1"])
        .arg(p(&d, "poly.json"))
        .assert()
        .code(2);
}

/// Query points of another dimension than the curve's or surface's are refused naming where
/// they come from, both dimensions and the fix, with `--all` too (no Rust `[3.0, 1.0]`).
#[test]
fn project_names_the_dimensions_and_the_fix() {
    let d = dir_with(&[
        ("poly.json", POLY),
        ("q3.csv", "3,1,0\n0,3,1\n"),
        (
            "s.json",
            r#"{"lekalo": 1, "type": "bezier_surface", "net": [2, 2], "control": [[0, 0, 0], [0, 4, 0], [4, 0, 0], [4, 4, 0]]}"#,
        ),
    ]);
    let curve_fix = "poly.json is 2-D: give points of 2 coordinates (x,y), or a curve of the \
                     points' dimension";
    let cases: [(&[&str], &str, String); 5] = [
        (
            &["--point", "3,1,0"],
            "poly.json",
            format!("error: --point 3,1,0 has 3 coordinates, but the curve {curve_fix}"),
        ),
        (
            &["--point", "3,1,0", "--all", "1e-9"],
            "poly.json",
            format!("error: --point 3,1,0 has 3 coordinates, but the curve {curve_fix}"),
        ),
        (
            &["--points", "q3.csv"],
            "poly.json",
            format!("error: q3.csv: the points are 3-D, but the curve {curve_fix}"),
        ),
        (
            &["--points", "q3.csv", "--all", "1e-9"],
            "poly.json",
            format!("error: q3.csv: the points are 3-D, but the curve {curve_fix}"),
        ),
        (
            &["--point", "1"],
            "s.json",
            "error: --point 1 has 1 coordinate, but the surface s.json is 3-D: give points of 3 \
             coordinates (x,y,z), or a surface of the points' dimension"
                .to_string(),
        ),
    ];
    for (args, input, want) in cases {
        let out = lekalo()
            .current_dir(d.path())
            .arg("project")
            .arg(input)
            .args(args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end(), want, "{args:?}");
    }
}

#[test]
fn intersect_pairs_self_and_plane() {
    let d = dir_with(&[
        ("poly.json", POLY),
        ("line.json", LINE),
        ("loop.json", LOOP),
    ]);
    let j = json_of(
        lekalo()
            .args(["intersect", "--json"])
            .arg(p(&d, "poly.json"))
            .arg(p(&d, "line.json")),
    );
    let hits = j.as_array().unwrap();
    assert_eq!(hits.len(), 2, "{j}");
    assert!((hits[0]["point"][0].as_f64().unwrap() - 0.75).abs() < 1e-12);
    assert_eq!(hits[0]["kind"], "crossing", "{j}");
    lekalo()
        .args(["intersect", "--self"])
        .arg(p(&d, "loop.json"))
        .assert()
        .success()
        .stdout(contains("crossing,"));
    lekalo()
        .args(["intersect", "--plane", "0,2,0,1"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stdout(contains("crossing,"));
    // nothing found: no rows, and a note saying so (none with --quiet)
    lekalo()
        .args(["intersect", "--plane", "0,9,0,1"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stdout("")
        .stderr(contains("no intersection"));
    lekalo()
        .args(["--quiet", "intersect", "--plane", "0,9,0,1"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stderr("");
    lekalo()
        .arg("intersect")
        .arg(p(&d, "poly.json"))
        .assert()
        .code(2)
        .stderr(contains("second curve"));
}

/// The tangent of the parabola y = x² at x = 1/2: y = x − 1/4 (exact in binary).
const TANGENT: &str =
    r#"{"lekalo": 1, "type": "bezier_curve", "control": [[-1, -1.25], [1, 0.75]]}"#;
/// A cubic in the plane z = 2.
const FLAT_CUBIC: &str = r#"{"lekalo": 1, "type": "bezier_curve",
 "control": [[0, 0, 2], [1, 2, 2], [2, -1, 2], [3, 0.5, 2]]}"#;
/// The same cubic's part over [1/4, 1] (de Casteljau, exact in binary), on [0, 1].
const FLAT_PART: &str = r#"{"lekalo": 1, "type": "bezier_curve",
 "control": [[0.75, 0.7109375, 2], [1.5, 0.78125, 2], [2.25, -0.625, 2], [3, 0.5, 2]]}"#;

#[test]
fn intersect_names_each_kind_of_contact() {
    let d = dir_with(&[
        ("parabola.json", PARABOLA),
        ("tangent.json", TANGENT),
        ("line.json", LINE),
        ("poly.json", POLY),
        ("flat.json", FLAT_CUBIC),
        ("part.json", FLAT_PART),
    ]);
    // a tangent contact of order 1, exact: t = 3/4 on both
    let j = json_of(
        lekalo()
            .args(["intersect", "--json"])
            .arg(p(&d, "parabola.json"))
            .arg(p(&d, "tangent.json")),
    );
    assert_eq!(j.as_array().unwrap().len(), 1, "{j}");
    assert_eq!(j[0]["kind"], "tangent", "{j}");
    assert_eq!(j[0]["order"], 1, "{j}");
    assert_eq!(j[0]["t_a"].as_f64().unwrap(), 0.75, "{j}");
    assert_eq!(j[0]["t_b"].as_f64().unwrap(), 0.75, "{j}");
    // the text output names the kind in the first column
    lekalo()
        .arg("intersect")
        .arg(p(&d, "parabola.json"))
        .arg(p(&d, "tangent.json"))
        .assert()
        .success()
        .stdout(contains("tangent,0.75,0.75,0.5,0.25"));
    // the parabola's ends (∓1, 1) lie on the line y = 1: two contacts at end points
    let j = json_of(
        lekalo()
            .args(["intersect", "--json"])
            .arg(p(&d, "parabola.json"))
            .arg(p(&d, "line.json")),
    );
    let kinds: Vec<&str> = j
        .as_array()
        .unwrap()
        .iter()
        .map(|h| h["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["end", "end"], "{j}");
    // a cubic lying in the plane z = 2: one overlap over its whole domain
    let j = json_of(
        lekalo()
            .args(["intersect", "--json", "--plane", "0,0,2,0,0,1"])
            .arg(p(&d, "flat.json")),
    );
    assert_eq!(j, serde_json::json!([{"kind": "overlap", "t": [0.0, 1.0]}]));
    // space curves sharing a stretch: an overlap with both parameter intervals
    let j = json_of(
        lekalo()
            .args(["intersect", "--json"])
            .arg(p(&d, "flat.json"))
            .arg(p(&d, "part.json")),
    );
    assert_eq!(j.as_array().unwrap().len(), 1, "{j}");
    assert_eq!(j[0]["kind"], "overlap", "{j}");
    let num = |v: &serde_json::Value| v.as_f64().unwrap();
    assert!(
        (num(&j[0]["a"][0]) - 0.25).abs() < 1e-14 && num(&j[0]["a"][1]) == 1.0,
        "{j}"
    );
    assert!(
        num(&j[0]["b"][0]).abs() < 1e-14 && num(&j[0]["b"][1]) == 1.0,
        "{j}"
    );
    // curves of different dimensions are refused
    lekalo()
        .arg("intersect")
        .arg(p(&d, "flat.json"))
        .arg(p(&d, "line.json"))
        .assert()
        .code(2)
        .stderr(contains("dimension"));
}

/// JSON Lines of surfaces (a batch, not face envelopes): the refusal says what mesh reads and
/// what to do, not a JSON parse error about trailing characters.
#[test]
fn mesh_of_a_batch_of_surfaces_names_what_it_reads() {
    let line = serde_json::to_string(&serde_json::from_str::<serde_json::Value>(SURFACE).unwrap())
        .unwrap();
    let d = dir_with(&[
        ("two.jsonl", &format!("{line}\n{line}\n")),
        ("one.jsonl", &format!("{line}\n")),
    ]);
    lekalo()
        .args(["mesh", "--tolerance", "1e-3"])
        .arg(p(&d, "two.jsonl"))
        .assert()
        .code(2)
        .stderr(contains("2 objects").and(contains("write each line to a .json file")));
    lekalo()
        .args(["mesh", "--tolerance", "1e-3", "-o"])
        .arg(p(&d, "one.obj"))
        .arg(p(&d, "one.jsonl"))
        .assert()
        .success();
}

#[test]
fn mesh_writes_obj_stl_and_reports_the_bound() {
    let d = dir_with(&[("s.json", SURFACE), ("poly.json", POLY)]);
    lekalo()
        .args(["mesh", "--tolerance", "1e-3", "-o"])
        .arg(p(&d, "s.obj"))
        .arg(p(&d, "s.json"))
        .assert()
        .success();
    let obj = fs::read_to_string(p(&d, "s.obj")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), 32);
    lekalo()
        .args(["mesh", "--tolerance", "1e-3", "-o"])
        .arg(p(&d, "s.stl"))
        .arg(p(&d, "s.json"))
        .assert()
        .success();
    assert!(fs::read_to_string(p(&d, "s.stl"))
        .unwrap()
        .starts_with("solid lekalo"));
    let j = json_of(
        lekalo()
            .args(["mesh", "--json", "--tolerance", "1e-3"])
            .arg(p(&d, "s.json")),
    );
    assert!(j["deviation"].as_f64().unwrap() <= 1e-3);
    lekalo()
        .args(["mesh", "--tolerance", "0"])
        .arg(p(&d, "s.json"))
        .assert()
        .code(2);
    lekalo()
        .args(["mesh", "--tolerance", "0.01"])
        .arg(p(&d, "poly.json"))
        .assert()
        .success()
        .stdout(contains("l 1 2 3"));
}

/// The B-spline curve of a JSON object.
fn curve_of(j: &serde_json::Value) -> lekalo::BSplineCurve {
    match lekalo_io::Shape::from_json_str(&j.to_string(), "test").unwrap() {
        lekalo_io::Shape::Curve(lekalo_io::Object::BSpline(c)) => c,
        other => panic!("not a B-spline curve: {}", other.type_name()),
    }
}

#[test]
fn offset_is_at_the_distance_within_the_tolerance() {
    let d = dir_with(&[("wave.json", WAVE)]);
    let wave = curve_of(&serde_json::from_str(WAVE).unwrap());
    let base = lekalo::QueryCurve::from_bspline(&wave).unwrap();
    for dist in [0.05_f64, -0.05] {
        let out = p(&d, "off.json");
        output_of(
            lekalo()
                .args([
                    "offset",
                    "--distance",
                    &dist.to_string(),
                    "--tolerance",
                    "1e-7",
                    "-o",
                ])
                .arg(&out)
                .arg(p(&d, "wave.json")),
        );
        let j: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(&out).unwrap()).unwrap();
        let c = curve_of(&j);
        let (a, b) = c.domain();
        for i in 0..=200 {
            let t = a + (b - a) * f64::from(i) / 200.0;
            let q = c.eval(t).unwrap();
            let pr = base.project(&q).unwrap();
            assert!(
                (pr.distance - dist.abs()).abs() <= 1e-7 * (1.0 + 1e-9),
                "d {dist}, t {t}: distance {}",
                pr.distance
            );
            // on the side the sign says: left of the travel direction for d > 0
            let tan = wave.eval_derivatives(pr.t, 1).unwrap();
            let tan = tan.point(1);
            let cross = tan[0] * (q[1] - pr.point[1]) - tan[1] * (q[0] - pr.point[0]);
            assert!(cross * dist > 0.0, "d {dist}, t {t}: wrong side");
        }
        fs::remove_file(&out).unwrap();
    }
}

#[test]
fn offset_reports_cusps_and_trims_the_loop() {
    let d = dir_with(&[("parabola.json", PARABOLA)]);
    let input = p(&d, "parabola.json");
    // d = 1 towards the centre of curvature, twice the vertex's radius: a swallowtail
    let j = json_of(
        lekalo()
            .args(["offset", "--json", "--distance", "1"])
            .arg(&input),
    );
    assert!(j["deviation"].as_f64().unwrap() <= 1e-6, "{j}");
    // cusps where κ = 2/(1 + 4x²)^{3/2} = 1: x = ±√((2^{2/3} − 1)/4), t = (x + 1)/2
    let xc = ((2f64.powf(2.0 / 3.0) - 1.0) / 4.0).sqrt();
    let cusps: Vec<f64> = j["cusps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap())
        .collect();
    assert_eq!(cusps.len(), 2, "{j}");
    assert!((cusps[0] - (1.0 - xc) / 2.0).abs() < 1e-9, "{cusps:?}");
    assert!((cusps[1] - (1.0 + xc) / 2.0).abs() < 1e-9, "{cusps:?}");
    // the loop closes on the axis x = 0: x − 2x/√(1 + 4x²) = 0 at x = ±√3/2
    let loops = j["loops"].as_array().unwrap();
    assert_eq!(loops.len(), 1, "{j}");
    let xl = 3f64.sqrt() / 2.0;
    assert!(
        (loops[0][0].as_f64().unwrap() - (1.0 - xl) / 2.0).abs() < 1e-6,
        "{j}"
    );
    assert!(
        (loops[0][1].as_f64().unwrap() - (1.0 + xl) / 2.0).abs() < 1e-6,
        "{j}"
    );
    let trimmed = j["trimmed"].as_array().unwrap();
    assert_eq!(trimmed.len(), 2, "{j}");
    // the two parts meet at the cut point (0, x² + 1/√(1 + 4x²)) = (0, 3/4 + 1/2)
    let end = curve_of(&trimmed[0])
        .eval(curve_of(&trimmed[0]).domain().1)
        .unwrap();
    let start = curve_of(&trimmed[1])
        .eval(curve_of(&trimmed[1]).domain().0)
        .unwrap();
    for q in [&end, &start] {
        assert!(q[0].abs() < 1e-6 && (q[1] - 1.25).abs() < 1e-6, "{q:?}");
    }
    // --trim writes the two parts as JSON Lines and says why on standard error
    let out = lekalo()
        .args(["offset", "--trim", "--distance", "1"])
        .arg(&input)
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(String::from_utf8_lossy(&out.stdout).lines().count(), 2);
    assert!(String::from_utf8_lossy(&out.stderr).contains("2 cusp(s)"));
    // away from the centre of curvature: no cusp, one part
    let j = json_of(
        lekalo()
            .args(["offset", "--json", "--distance", "-1"])
            .arg(&input),
    );
    assert!(j["cusps"].as_array().unwrap().is_empty(), "{j}");
    assert_eq!(j["trimmed"].as_array().unwrap().len(), 1, "{j}");
}

#[test]
fn offset_refuses_bad_input() {
    let d = dir_with(&[("space.json", SPACE), ("wave.json", WAVE)]);
    for (file, args, says) in [
        ("space.json", ["--distance", "1"], "dimension"),
        ("wave.json", ["--distance", "nan"], "offset distance"),
        (
            "wave.json",
            ["--tolerance", "0"],
            "--tolerance: 0 is not a positive",
        ),
    ] {
        lekalo()
            .arg("offset")
            .args(args)
            .args(if args[0] == "--distance" {
                vec![]
            } else {
                vec!["--distance", "1"]
            })
            .arg(p(&d, file))
            .assert()
            .code(2)
            .stderr(contains(says));
    }
}

/// The twisted cubic (t, t², t³) on [0, 1]: torsion 3 / (9t⁴ + 9t² + 1).
const TWISTED: &str = r#"{"lekalo": 1, "type": "bezier_curve",
 "control": [[0, 0, 0], [0.3333333333333333, 0, 0], [0.6666666666666666, 0.3333333333333333, 0], [1, 1, 1]]}"#;

#[test]
fn eval_torsion_of_a_space_curve_and_refusals() {
    let d = dir_with(&[
        ("twisted.json", TWISTED),
        ("parabola.json", PARABOLA),
        ("surface.json", SURFACE),
        ("space_line.json", SPACE),
    ]);
    let j = json_of(
        lekalo()
            .args(["eval", "--at", "0,0.5,1", "--torsion", "--json"])
            .arg(p(&d, "twisted.json")),
    );
    for (row, t) in j.as_array().unwrap().iter().zip([0.0f64, 0.5, 1.0]) {
        let exact = 3.0 / (9.0 * t.powi(4) + 9.0 * t * t + 1.0);
        let tau = row["torsion"].as_f64().unwrap();
        assert!((tau - exact).abs() < 1e-12, "τ({t}) = {tau}, exact {exact}");
    }
    // CSV: the column is last, after the curvature
    lekalo()
        .args(["eval", "--at", "0", "--curvature", "--torsion"])
        .arg(p(&d, "twisted.json"))
        .assert()
        .success()
        .stdout(contains("t,x,y,z,curvature,torsion\n0,0,0,0,2,3\n"));
    // a straight line has no osculating plane: the field is empty, not a number
    lekalo()
        .args(["eval", "--at", "0.5", "--torsion"])
        .arg(p(&d, "space_line.json"))
        .assert()
        .success()
        .stdout("t,x,y,z,torsion\n0.5,0.5,0.5,0.5,\n");
    // a planar curve and a surface are refused, saying what to do
    lekalo()
        .args(["eval", "--at", "0.5", "--torsion"])
        .arg(p(&d, "parabola.json"))
        .assert()
        .code(2)
        .stderr(contains("needs a 3-D curve and this one is 2-D"))
        .stderr(contains("drop --torsion"));
    lekalo()
        .args(["eval", "--torsion"])
        .arg(p(&d, "surface.json"))
        .assert()
        .code(2)
        .stderr(contains("--torsion is for 3-D curves"));
}
