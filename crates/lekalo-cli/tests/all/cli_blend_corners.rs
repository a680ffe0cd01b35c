//! End-to-end tests of `lekalo blend corners`: a polyline smoothed at every corner into one
//! curve, the same bits as the library's `smooth_polyline_corners`.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use lekalo_io::CurveJson;
use std::fs;

use assert_cmd::Command;
use lekalo::{smooth_polyline_corners, CornerWindow, Points};
use lekalo_io::Object;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

const ZIGZAG: [[f64; 2]; 5] = [[0.0, 0.0], [3.0, 0.0], [4.0, 2.5], [7.0, 1.0], [7.5, 6.0]];

fn zigzag_csv() -> String {
    ZIGZAG.iter().map(|[x, y]| format!("{x},{y}\n")).collect()
}

#[test]
fn corners_agree_with_the_library_to_the_last_bit() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("zigzag.csv"), zigzag_csv()).unwrap();
    let pts = Points::from_2d(&ZIGZAG).unwrap();
    for (arg, window, k) in [
        ("25%", CornerWindow::Fraction(0.25), "2"),
        ("0.8", CornerWindow::Length(0.8), "3"),
        ("50%", CornerWindow::Fraction(0.5), "1"),
    ] {
        let out = lekalo()
            .current_dir(d.path())
            .args(["blend", "corners", "zigzag.csv", "--window", arg])
            .args(["--continuity", k])
            .assert()
            .success();
        let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
        let Ok(Object::BSpline(c)) = Object::from_json_str(&text, "stdout") else {
            panic!("not a B-spline: {text}");
        };
        let want = smooth_polyline_corners(pts.as_view(), window, k.parse().unwrap()).unwrap();
        assert_eq!(&c, want.curve(), "--window {arg} --continuity {k}");
    }
}

#[test]
fn the_corners_plot_shows_the_polyline_under_the_curve() {
    // the README tour's polyline: the figure draws it (dashed, first) rather than marking its
    // three points, two of which lay hidden under the curve's end marks
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("pts.txt"), "1 1\n2 3\n4 3\n").unwrap();
    lekalo()
        .current_dir(d.path())
        .args([
            "blend", "corners", "pts.txt", "--window", "25%", "-o", "r.svg",
        ])
        .assert()
        .success();
    let svg = fs::read_to_string(d.path().join("r.svg")).unwrap();
    let corners = svg
        .find("data-label=\"corners of the polyline\"")
        .expect("the polyline's corners are marked and in the legend");
    let curve = svg.find("data-label=\"curve\"").expect("the curve");
    assert!(corners < curve, "the polyline is drawn under the curve");
    // the dashed polyline through the three points, then one marker at its one corner
    let dashed = svg[..corners]
        .rfind("<polyline")
        .map(|i| &svg[i..corners])
        .expect("the polyline is drawn");
    let points = dashed
        .split("points=\"")
        .nth(1)
        .and_then(|p| p.split('"').next());
    assert_eq!(
        points.map(|p| p.split_whitespace().count()),
        Some(3),
        "{dashed}"
    );
    assert!(dashed.contains("stroke-dasharray"), "{dashed}");
    assert_eq!(svg[corners..curve].matches("<circle").count(), 1);
    assert!(
        !svg.contains("data points"),
        "its vertices are not data to fit"
    );
    assert_eq!(lekalo_io::check_svg(&svg, None), Vec::<String>::new());
}

#[test]
fn corners_write_plots_and_samples() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("zigzag.csv"), zigzag_csv()).unwrap();
    for out in ["smooth.svg", "smooth.png", "smooth.csv"] {
        lekalo()
            .current_dir(d.path())
            .args(["blend", "corners", "zigzag.csv", "-o", out])
            .assert()
            .success();
        assert!(
            fs::metadata(d.path().join(out)).unwrap().len() > 100,
            "{out}"
        );
    }
}

#[test]
fn corners_bad_input_names_the_problem() {
    let d = tempfile::tempdir().unwrap();
    let cases = [
        ("two.csv", "0,0\n1,0\n", "25%", "at least 3"),
        (
            "repeat.csv",
            "0,0\n1,0\n1,0\n1,1\n",
            "25%",
            "points 1 and 2 coincide",
        ),
        ("nan.csv", "0,0\n1,nan\n2,0\n", "25%", "nan"),
        (
            "zigzag.csv",
            &zigzag_csv(),
            "1.6",
            "segment 1 (points 1 to 2)",
        ),
        ("zigzag.csv", &zigzag_csv(), "60%", "(0, 0.5]"),
        ("zigzag.csv", &zigzag_csv(), "-1", "must be positive"),
        ("zigzag.csv", &zigzag_csv(), "wide", "--window"),
    ];
    for (name, text, window, message) in cases {
        fs::write(d.path().join(name), text).unwrap();
        lekalo()
            .current_dir(d.path())
            .args(["blend", "corners", name, "--window", window])
            .assert()
            .code(2)
            .stderr(contains(message));
    }
}

/// The README tour's corner: `measure` finds one curvature maximum and no inflection (a
/// rounded corner turns one way).
#[test]
fn the_tour_corner_is_fair() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("pts.txt"), "1 1\n2 3\n4 3\n").unwrap();
    lekalo()
        .current_dir(d.path())
        .args([
            "blend",
            "corners",
            "pts.txt",
            "--window",
            "25%",
            "--continuity",
            "2",
        ])
        .args(["-o", "rounded.json"])
        .assert()
        .success();
    let out = lekalo()
        .current_dir(d.path())
        .args(["measure", "rounded.json", "--json"])
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(v["inflections"], serde_json::json!([]), "{v}");
    let extrema = v["curvature_extrema"].as_array().unwrap();
    assert_eq!(extrema.len(), 1, "{v}");
    assert_eq!(extrema[0]["kind"], "max");
}

#[test]
fn the_pp_form_of_the_corners_reports_their_continuity() {
    // the joins' knots have multiplicity 2k + 1 = the degree; `pp convert` then `info` measure
    // the curve itself: C^k at every join, also for the symmetric zigzag whose x is a line
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("zigzag.csv"), zigzag_csv()).unwrap();
    fs::write(d.path().join("teeth.csv"), "0,0\n1,2\n2,0\n3,2\n4,0\n").unwrap();
    for (input, k) in [("zigzag.csv", "2"), ("teeth.csv", "2"), ("teeth.csv", "3")] {
        lekalo()
            .current_dir(d.path())
            .args([
                "blend",
                "corners",
                input,
                "--window",
                "30%",
                "--continuity",
                k,
            ])
            .args(["-o", "smooth.json"])
            .assert()
            .success();
        lekalo()
            .current_dir(d.path())
            .args([
                "pp",
                "convert",
                "smooth.json",
                "-o",
                "smooth.pp.json",
                "--force",
            ])
            .assert()
            .success();
        let out = lekalo()
            .current_dir(d.path())
            .args(["info", "smooth.pp.json", "--json"])
            .assert()
            .success();
        let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
        let joins = v["continuity"].as_array().expect("continuity");
        assert_eq!(joins.len(), 6, "{input}: {v}");
        for j in joins {
            assert_eq!(j["smoothness"], format!("C^{k}"), "{input}, k = {k}: {j}");
        }
    }
}
