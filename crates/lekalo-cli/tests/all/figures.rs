//! Looks at every figure as a reader would: every SVG of the demo gallery (with its caption)
//! and the plots of every kind the command line writes. In each, every text and legend box
//! lies inside the canvas, no two legend entries overlap, no coordinate is NaN or infinite,
//! every labelled series shows past what is drawn over it (or its caption says it coincides
//! with another), no text overlaps another, a legend entry or a curve, colour bars carry their
//! ends' values, framed axes are named, the caption's colour and dash words match the lines,
//! and the rendered image is not blank ([`lekalo_io::check_svg`]). Every PNG decodes and is
//! not blank.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;
use std::path::Path;

use assert_cmd::Command;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// Undoes the gallery's HTML escaping.
fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&amp;", "&")
}

/// The caption of figure `name` in the gallery's index page.
fn caption<'a>(index: &'a str, name: &str) -> &'a str {
    let start = index
        .find(&format!("<figure id=\"{name}\">"))
        .unwrap_or_else(|| panic!("no <figure> {name} in the index"));
    let rest = &index[start..];
    let a = rest.find("<figcaption>").expect("a caption") + "<figcaption>".len();
    let b = rest.find("</figcaption>").expect("the caption's end");
    &rest[a..b]
}

/// Fraction of pixels of a PNG that are not white.
fn ink(png: &Path) -> f64 {
    let pixmap = resvg::tiny_skia::Pixmap::load_png(png)
        .unwrap_or_else(|e| panic!("{}: {e}", png.display()));
    let drawn = pixmap
        .pixels()
        .iter()
        .filter(|p| p.red() < 230 || p.green() < 230 || p.blue() < 230)
        .count();
    drawn as f64 / pixmap.pixels().len() as f64
}

#[test]
fn every_gallery_figure_reads_well() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("gallery");
    lekalo()
        .args(["--quiet", "demo", "--out"])
        .arg(&out)
        .assert()
        .success();
    let index = fs::read_to_string(out.join("index.html")).unwrap();
    let mut names: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            (p.extension() == Some("svg".as_ref()))
                .then(|| p.file_stem().unwrap().to_string_lossy().into_owned())
        })
        .collect();
    names.sort();
    assert!(names.len() >= 20, "only {} figures", names.len());
    let mut problems = Vec::new();
    for name in &names {
        let svg = fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
        let text = unescape(caption(&index, name));
        // two or three sentences, a theory link and the command that redraws the figure
        let sentences = text
            .split("<span")
            .next()
            .unwrap_or_default()
            .matches(". ")
            .count()
            + 1;
        if sentences < 2 {
            problems.push(format!("{name}: the caption is one sentence: {text}"));
        }
        let command = text
            .split("Redraw: <code>")
            .nth(1)
            .and_then(|c| c.split("</code>").next())
            .unwrap_or_default();
        if !text.contains("docs/theory/") || !command.contains("lekalo ") {
            problems.push(format!(
                "{name}: the caption lacks its theory link or command"
            ));
        }
        for p in lekalo_io::check_svg(&svg, Some(&text)) {
            problems.push(format!("{name}: {p}"));
        }
        let png = out.join(format!("{name}.png"));
        let share = ink(&png);
        if share < 0.005 {
            problems.push(format!("{name}.png is blank ({share} of it drawn)"));
        }
        // thumbnails link to every figure
        if !index.contains(&format!("<img src=\"{name}.png\"")) {
            problems.push(format!("{name}: no thumbnail in the index"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

const LECTURE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2,
 "knots": [0, 0, 1, 2, 3, 3], "control": [[1, 1], [2, 3], [4, 3]]}"#;

const HALF_CIRCLE: &str = r#"{"lekalo": 1, "type": "nurbs_curve", "degree": 2,
 "knots": [0, 0, 0, 0.5, 0.5, 1, 1, 1],
 "control": [[1, 0, 0.5], [1, 1, 0.5], [0, 1, 0.5], [-1, 1, 0.5], [-1, 0, 0.5]],
 "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1]}"#;

const SURFACE: &str = r#"{"lekalo": 1, "type": "nurbs_surface", "degree_u": 2, "degree_v": 1,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "net": [3, 2],
 "control": [[0, 0, 0], [0, 1, 0], [1, 0, 1], [1, 1, 1], [2, 0, 0], [2, 1, 0.5]],
 "weights": [1, 1, 0.7, 0.7, 1, 1]}"#;

/// The README tour's dome: a flat surface (height 1/4 over a 2 × 2 square).
const DOME: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 2, "degree_v": 2,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1], "net": [3, 3],
 "control": [[0, 0, 0], [0, 1, 0], [0, 2, 0], [1, 0, 0], [1, 1, 1], [1, 2, 0], [2, 0, 0],
   [2, 1, 0], [2, 2, 0]]}"#;

const PP: &str = r#"{"lekalo": 1, "type": "piecewise_polynomial", "breakpoints": [0, 1, 2, 3],
 "order": 3, "dim": 1, "coefficients": [0, 1, 0.5, 1.5, 2, -1, 2.5, 0, 3]}"#;

/// Twenty cubic basis functions: more than the palette's colours.
const MANY: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 3,
 "knots": [0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 17, 17, 17],
 "control": [[0,0],[1,1],[2,0],[3,1],[4,0],[5,1],[6,0],[7,1],[8,0],[9,1],[10,0],[11,1],[12,0],
   [13,1],[14,0],[15,1],[16,0],[17,1],[18,0],[19,1]]}"#;

#[test]
fn every_kind_of_cli_plot_reads_well() {
    let d = tempfile::tempdir().unwrap();
    let path = |n: &str| d.path().join(n);
    for (name, text) in [
        ("c.json", LECTURE),
        ("n.json", HALF_CIRCLE),
        ("s.json", SURFACE),
        ("dome.json", DOME),
        ("p.json", PP),
        ("many.json", MANY),
        (
            "quintic.json",
            r#"{"lekalo": 1, "type": "bezier_curve",
             "control": [[10, 0], [22, 6], [19, 12], [11, 15], [8, 12], [20, 0]]}"#,
        ),
        ("data.csv", "1.5 2\n3 3\n"),
        ("q.txt", lekalo_testkit::vectors::example_9_1::POINTS_TEXT),
        (
            "grid.txt",
            "0 0 0\n0 1 0\n0 2 0\n1 0 0\n1 1 1\n1 2 2\n2 0 0\n2 1 2\n2 2 4\n3 0 0\n3 1 3\n3 2 6\n",
        ),
    ] {
        fs::write(path(name), text).unwrap();
    }
    let c = path("c.json");
    let n = path("n.json");
    let s = path("s.json");
    let dome = path("dome.json");
    let pp = path("p.json");
    let many = path("many.json");
    let quintic = path("quintic.json");
    let data = path("data.csv");
    let q = path("q.txt");
    let grid = path("grid.txt");
    // the README tour's polyline, whose corner `blend corners` rounds
    let tour = path("tour.txt");
    fs::write(&tour, "1 1\n2 3\n4 3\n").unwrap();
    let title =
        "A title long enough to run past the canvas of a default plot, on purpose, to see it grow";
    let runs: Vec<(&str, Vec<&std::ffi::OsStr>)> = vec![
        (
            "curve",
            vec![
                "plot".as_ref(),
                c.as_os_str(),
                "--points".as_ref(),
                data.as_os_str(),
            ],
        ),
        (
            "basis",
            vec!["plot".as_ref(), c.as_os_str(), "--basis".as_ref()],
        ),
        (
            "many-basis",
            vec!["plot".as_ref(), many.as_os_str(), "--basis".as_ref()],
        ),
        (
            "long-title",
            vec![
                "plot".as_ref(),
                c.as_os_str(),
                "--title".as_ref(),
                title.as_ref(),
            ],
        ),
        (
            "nurbs-3d",
            vec![
                "plot".as_ref(),
                n.as_os_str(),
                "--azimuth".as_ref(),
                "30".as_ref(),
            ],
        ),
        ("surface", vec!["plot".as_ref(), s.as_os_str()]),
        (
            "dome",
            vec!["plot".as_ref(), dome.as_os_str(), "--net".as_ref()],
        ),
        (
            "dome-curvature",
            vec![
                "plot".as_ref(),
                dome.as_os_str(),
                "--curvature".as_ref(),
                "gaussian".as_ref(),
            ],
        ),
        (
            "surface-net",
            vec![
                "plot".as_ref(),
                s.as_os_str(),
                "--net".as_ref(),
                "--iso".as_ref(),
                "3".as_ref(),
            ],
        ),
        (
            "surface-wire",
            vec![
                "plot".as_ref(),
                s.as_os_str(),
                "--wireframe".as_ref(),
                "--samples".as_ref(),
                "12".as_ref(),
            ],
        ),
        ("pp", vec!["plot".as_ref(), pp.as_os_str()]),
        ("convert-surface", vec!["convert".as_ref(), s.as_os_str()]),
        (
            "interpolate",
            vec![
                "interpolate".as_ref(),
                q.as_os_str(),
                "--degree".as_ref(),
                "3".as_ref(),
            ],
        ),
        (
            "interpolate-grid",
            vec![
                "interpolate".as_ref(),
                grid.as_os_str(),
                "--grid".as_ref(),
                "4x3".as_ref(),
            ],
        ),
        (
            "elevate",
            vec!["bezier".as_ref(), "elevate".as_ref(), quintic.as_os_str()],
        ),
        (
            "tour-corners",
            vec![
                "blend".as_ref(),
                "corners".as_ref(),
                tour.as_os_str(),
                "--window".as_ref(),
                "25%".as_ref(),
                "--continuity".as_ref(),
                "2".as_ref(),
            ],
        ),
        (
            "quasi",
            vec![
                "pp".as_ref(),
                "quasi".as_ref(),
                "--function".as_ref(),
                "x*cos(x)".as_ref(),
                "--breakpoints".as_ref(),
                "0,0.5,0.9,1.4,2.1,2.7,3".as_ref(),
                "--order".as_ref(),
                "3".as_ref(),
                "--continuity".as_ref(),
                "2,2,2,2,2".as_ref(),
            ],
        ),
    ];
    let mut problems = Vec::new();
    for (name, args) in runs {
        for ext in ["svg", "png"] {
            let out = path(&format!("{name}.{ext}"));
            lekalo().args(&args).arg("-o").arg(&out).assert().success();
            if ext == "svg" {
                let svg = fs::read_to_string(&out).unwrap();
                for p in lekalo_io::check_svg(&svg, None) {
                    problems.push(format!("{name}: {p}"));
                }
            } else if ink(&out) < 0.005 {
                problems.push(format!("{name}.png is blank"));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
