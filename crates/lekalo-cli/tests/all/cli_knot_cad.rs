//! End-to-end tests of surfaces in `make`/`eval`/`convert`, the `knot` family and STEP input:
//! every figure is compared with the library's own, bit for bit.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use lekalo::{BSplineCurve, BSplineSurface, NurbsSurface, Points};
use lekalo_io::{read_step, Object, Shape, Surface};
use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::common;
use common::{dir_with, lekalo, p};

/// `lekalo convert INPUT -o OUTPUT` inside `d`, which must succeed.
fn convert(d: &tempfile::TempDir, input: &str, output: &str) {
    lekalo()
        .arg("convert")
        .arg(p(d, input))
        .arg("-o")
        .arg(p(d, output))
        .assert()
        .success();
}

const NET: &str = "0 0 0\n0 1 0\n0 2 0.5\n1 0 0\n1 1 1\n1 2 0\n2 0 0.25\n2 1 0\n2 2 0\n";
const CURVE: &str = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2,
 "knots": [0, 0, 0, 0.5, 1, 1, 1], "control": [[1, 1], [2, 3], [4, 3], [5, 0]]}"#;

fn library_surface() -> BSplineSurface {
    let rows: Vec<Vec<f64>> = NET
        .lines()
        .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
        .collect();
    let ctrl = Points::from_rows(&rows).unwrap();
    BSplineSurface::new(
        2,
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        ctrl,
        (3, 3),
    )
    .unwrap()
}

/// The CSV's rows as numbers by column name.
fn csv(text: &str) -> (Vec<String>, Vec<Vec<Option<f64>>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().ok()).collect())
        .collect();
    (header, rows)
}

#[test]
fn surface_make_and_eval_agree_with_the_library_to_the_bit() {
    let d = dir_with(&[("net.txt", NET)]);
    lekalo()
        .args(["make", "bspline-surface", "--control"])
        .arg(p(&d, "net.txt"))
        .args(["--net", "3x3", "--degree", "2", "-o"])
        .arg(p(&d, "s.json"))
        .assert()
        .success();
    let out = lekalo()
        .arg("eval")
        .arg(p(&d, "s.json"))
        .args([
            "--uv",
            "0.3,0.7",
            "--uv",
            "0.5,1e-7",
            "--derivatives",
            "2",
            "--normals",
            "--curvature",
        ])
        .assert()
        .success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let (h, rows) = csv(&text);
    let col = |r: usize, name: &str| rows[r][h.iter().position(|x| x == name).unwrap()].unwrap();
    let s = library_surface();
    for (r, (u, v)) in [(0.3, 0.7), (0.5, 1e-7)].into_iter().enumerate() {
        let pt = s.eval(u, v).unwrap();
        let d = s.eval_derivatives(u, v, 2).unwrap();
        let n = s.normal(u, v).unwrap();
        let k =
            lekalo::surface_curvature(d.point(3), d.point(1), d.point(6), d.point(4), d.point(2))
                .unwrap();
        assert_eq!(col(r, "z").to_bits(), pt[2].to_bits());
        assert_eq!(col(r, "du1v0z").to_bits(), d.point(3)[2].to_bits());
        assert_eq!(col(r, "du1v1y").to_bits(), d.point(4)[1].to_bits());
        assert_eq!(col(r, "du0v2z").to_bits(), d.point(2)[2].to_bits());
        assert_eq!(col(r, "nx").to_bits(), n[0].to_bits());
        assert_eq!(col(r, "gaussian").to_bits(), k.gaussian.to_bits());
        assert_eq!(col(r, "k2").to_bits(), k.k2.to_bits());
    }
    assert!(
        text.contains(",1e-7,"),
        "exponent notation for small numbers: {text}"
    );
    // a grid, and JSON
    let out = lekalo()
        .arg("eval")
        .arg(p(&d, "s.json"))
        .args(["--grid", "2x3", "--format", "json"])
        .assert()
        .success();
    let j: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(j.as_array().unwrap().len(), 6);
    assert_eq!(j[5]["v"], 1.0);
    // wrong use is exit code 2 with a message naming the option
    lekalo()
        .arg("eval")
        .arg(p(&d, "s.json"))
        .args(["--uv", "0.3"])
        .assert()
        .code(2)
        .stderr(contains("--uv"));
    lekalo()
        .arg("eval")
        .arg(p(&d, "s.json"))
        .args(["--uv", "3,0"])
        .assert()
        .code(2);
    lekalo()
        .args(["make", "bspline-surface", "--control"])
        .arg(p(&d, "net.txt"))
        .args(["--net", "2x3", "--degree", "1"])
        .assert()
        .code(2)
        .stderr(contains("--net 2x3 needs 6 control points"));
    // convert to CSV samples
    lekalo()
        .arg("convert")
        .arg(p(&d, "s.json"))
        .args(["--to", "csv", "--samples", "9"])
        .assert()
        .success()
        .stdout(contains("u,v,x,y,z\n0,0,0,0,0\n"));
}

#[test]
fn nurbs_surface_make_and_step_round_trip() {
    let d = dir_with(&[("net.txt", NET)]);
    lekalo()
        .args(["make", "nurbs-surface", "--control"])
        .arg(p(&d, "net.txt"))
        .args([
            "--net",
            "3x3",
            "--degree",
            "2",
            "--weights",
            "1,1,1,1,2,1,1,1,0.5",
            "-o",
        ])
        .arg(p(&d, "n.json"))
        .assert()
        .success();
    convert(&d, "n.json", "n.step");
    convert(&d, "n.step", "back.json");
    let a = fs::read_to_string(p(&d, "n.json")).unwrap();
    let b = fs::read_to_string(p(&d, "back.json")).unwrap();
    let sa = Shape::from_json_str(&a, "a").unwrap();
    let sb = Shape::from_json_str(&b, "b").unwrap();
    let (Shape::Surface(Surface::Nurbs(x)), Shape::Surface(Surface::Nurbs(y))) = (&sa, &sb) else {
        panic!("NURBS surfaces expected")
    };
    assert_eq!(x.weights(), y.weights());
    assert_eq!(x.control_points(), y.control_points());
    let _: &NurbsSurface = x;
}

#[test]
fn knot_family_matches_the_library() {
    let d = dir_with(&[("c.json", CURVE)]);
    let Shape::Curve(Object::BSpline(c)) = Shape::from_json_str(CURVE, "c").unwrap() else {
        panic!("a B-spline")
    };
    let read = |name: &str| -> Shape {
        Shape::from_json_str(&fs::read_to_string(p(&d, name)).unwrap(), name).unwrap()
    };
    lekalo()
        .args(["knot", "insert"])
        .arg(p(&d, "c.json"))
        .args(["--at", "0.25", "--times", "2", "-o"])
        .arg(p(&d, "i.json"))
        .assert()
        .success();
    let inserted = c.insert_knot(0.25, 2).unwrap();
    assert_eq!(
        read("i.json"),
        Shape::Curve(Object::BSpline(inserted.clone()))
    );
    lekalo()
        .args(["knot", "remove"])
        .arg(p(&d, "i.json"))
        .args(["--at", "0.25", "-o"])
        .arg(p(&d, "r.json"))
        .assert()
        .success()
        .stderr(contains("removed 2 knot copies").and(contains("0.25×2")));
    let tol = inserted.default_removal_tolerance();
    assert_eq!(
        read("r.json"),
        Shape::Curve(Object::BSpline(
            inserted.remove_knot(0.25, 2, tol).unwrap().0
        ))
    );
    lekalo()
        .args(["knot", "refine"])
        .arg(p(&d, "c.json"))
        .args(["--knots", "0.1,0.6", "-o"])
        .arg(p(&d, "f.json"))
        .assert()
        .success();
    assert_eq!(
        read("f.json"),
        Shape::Curve(Object::BSpline(c.refine_knots(&[0.1, 0.6]).unwrap()))
    );
    lekalo()
        .args(["knot", "reverse"])
        .arg(p(&d, "c.json"))
        .arg("-o")
        .arg(p(&d, "v.json"))
        .assert()
        .success();
    assert_eq!(
        read("v.json"),
        Shape::Curve(Object::BSpline(c.reverse().unwrap()))
    );
    lekalo()
        .args(["knot", "reparam"])
        .arg(p(&d, "c.json"))
        .args(["--interval", "-1,3", "-o"])
        .arg(p(&d, "m.json"))
        .assert()
        .success();
    assert_eq!(
        read("m.json"),
        Shape::Curve(Object::BSpline(c.reparametrize(-1.0, 3.0).unwrap()))
    );
    // split: two lines of JSON Lines
    let out = lekalo()
        .args(["knot", "split"])
        .arg(p(&d, "c.json"))
        .args(["--at", "0.3"])
        .assert()
        .success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let (l, r) = c.split_at(0.3).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        Shape::from_json_str(lines[0], "l").unwrap(),
        Shape::Curve(Object::BSpline(l))
    );
    assert_eq!(
        Shape::from_json_str(lines[1], "r").unwrap(),
        Shape::Curve(Object::BSpline(r))
    );
    // decompose and join: the same curve with breakpoints of full multiplicity
    lekalo()
        .args(["knot", "decompose"])
        .arg(p(&d, "c.json"))
        .arg("-o")
        .arg(p(&d, "pieces.jsonl"))
        .assert()
        .success();
    lekalo()
        .args(["knot", "join"])
        .arg(p(&d, "pieces.jsonl"))
        .arg("-o")
        .arg(p(&d, "j.json"))
        .assert()
        .success();
    let joined = BSplineCurve::from_bezier_segments(&c.to_bezier_segments()).unwrap();
    assert_eq!(read("j.json"), Shape::Curve(Object::BSpline(joined)));
    // docs/cli.md: `knot remove --all` on the joined curve gives the original knots back
    lekalo()
        .args(["knot", "remove"])
        .arg(p(&d, "j.json"))
        .arg("--all")
        .arg("-o")
        .arg(p(&d, "back.json"))
        .assert()
        .success();
    let Shape::Curve(Object::BSpline(back)) = read("back.json") else {
        panic!("knot remove writes a B-spline curve")
    };
    assert_eq!(back.knots(), c.knots(), "the original knots");
    // errors: a parameter outside the domain, remove on a surface
    lekalo()
        .args(["knot", "insert"])
        .arg(p(&d, "c.json"))
        .args(["--at", "2"])
        .assert()
        .code(2);
    lekalo()
        .args(["knot", "split"])
        .arg(p(&d, "c.json"))
        .args(["--at", "x"])
        .assert()
        .code(2)
        .stderr(contains("--at"));
}

#[test]
fn knot_operations_on_surfaces_in_u_and_v() {
    let d = dir_with(&[("net.txt", NET)]);
    lekalo()
        .args(["make", "bspline-surface", "--control"])
        .arg(p(&d, "net.txt"))
        .args(["--net", "3x3", "--degree", "2", "-o"])
        .arg(p(&d, "s.json"))
        .assert()
        .success();
    let s = library_surface();
    lekalo()
        .args(["knot", "insert"])
        .arg(p(&d, "s.json"))
        .args(["--dir", "v", "--at", "0.5", "-o"])
        .arg(p(&d, "i.json"))
        .assert()
        .success();
    let got = Shape::from_json_str(&fs::read_to_string(p(&d, "i.json")).unwrap(), "i").unwrap();
    assert_eq!(
        got,
        Shape::Surface(Surface::BSpline(s.insert_knot_v(0.5, 1).unwrap()))
    );
    lekalo()
        .args(["knot", "remove"])
        .arg(p(&d, "s.json"))
        .args(["--at", "0.5"])
        .assert()
        .code(2)
        .stderr(contains("curves"));
    lekalo()
        .args(["knot", "decompose"])
        .arg(p(&d, "i.json"))
        .arg("-o")
        .arg(p(&d, "patches.jsonl"))
        .assert()
        .success();
    assert_eq!(
        fs::read_to_string(p(&d, "patches.jsonl"))
            .unwrap()
            .lines()
            .count(),
        2
    );
}

#[test]
fn step_from_open_cascade_converts_both_ways() {
    let data = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../lekalo-io/tests/data/occ/mixed_ap242_m.step"
    );
    let d = tempfile::tempdir().unwrap();
    lekalo()
        .arg("convert")
        .arg(data)
        .arg("-o")
        .arg(p(&d, "all.jsonl"))
        .assert()
        .success()
        .stderr(contains("length unit metre").and(contains("skipped")));
    let text = fs::read_to_string(p(&d, "all.jsonl")).unwrap();
    let direct = read_step(&fs::read_to_string(data).unwrap(), "m").unwrap();
    assert_eq!(text.lines().count(), direct.shapes.len());
    for (line, (_, shape)) in text.lines().zip(&direct.shapes) {
        assert_eq!(&Shape::from_json_str(line, "l").unwrap(), shape);
    }
    convert(&d, "all.jsonl", "again.step");
    let again = read_step(&fs::read_to_string(p(&d, "again.step")).unwrap(), "again").unwrap();
    assert_eq!(again.shapes.len(), direct.shapes.len());
    lekalo()
        .arg("convert")
        .arg(data)
        .args(["--to", "json"])
        .assert()
        .code(2)
        .stderr(contains("json output takes one"));
    // IGES both ways: the same objects as JSON Lines
    convert(&d, "all.jsonl", "all.igs");
    convert(&d, "all.igs", "from-iges.jsonl");
    assert_eq!(fs::read_to_string(p(&d, "from-iges.jsonl")).unwrap(), text);
}

#[test]
fn machine_readable_real_degree_and_quasi_error() {
    // a quintic of lower real degree; the figures are the library's
    let quintic = r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [0.6, 1.2], [1.2, 1.8], [1.8, 1.8], [2.4, 1.2], [3, 0]]}"#;
    let d = dir_with(&[("q.json", quintic)]);
    let out = lekalo()
        .args(["bezier", "real-degree"])
        .arg(p(&d, "q.json"))
        .arg("--json")
        .assert()
        .success();
    let j: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    let Shape::Curve(Object::Bezier(b)) = Shape::from_json_str(quintic, "q").unwrap() else {
        panic!("a Bezier curve")
    };
    assert_eq!(j["degree"], 5);
    assert_eq!(j["real_degree"], b.real_degree());
    assert!(b.real_degree() < 5);
    assert_eq!(j["defect"], 5 - b.real_degree());
    let args = [
        "pp",
        "quasi",
        "--function",
        "x*cos(x)",
        "--breakpoints",
        "0,0.5,0.9,1.4,2.1,2.7,3",
        "--order",
        "3",
        "--continuity",
        "2,2,2,2,2",
        "--rule",
        "left-end-of-support",
        "--json",
    ];
    let out = lekalo().args(args).assert().success();
    let j: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    let e = j["max_error"].as_f64().unwrap();
    assert!((e - 0.204831).abs() < 5e-7, "{e}");
    assert_eq!(j["curve"]["type"], "bspline_curve");
}

#[test]
fn blend_jump_prints_exact_coefficients_and_samples() {
    let out = lekalo()
        .args(["blend", "jump", "--k", "1", "--samples", "5", "--json"])
        .assert()
        .success();
    let j: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(j["monomial"], serde_json::json!(["0", "0", "3", "-2"]));
    assert_eq!(j["bernstein"], serde_json::json!(["0", "0", "1", "1"]));
    let w = lekalo::JumpPolynomial::new(1).unwrap();
    for s in j["samples"].as_array().unwrap() {
        let u = s["u"].as_f64().unwrap();
        assert_eq!(
            s["w"].as_f64().unwrap().to_bits(),
            w.eval(u).unwrap().to_bits()
        );
    }
    lekalo()
        .args(["blend", "jump", "--k", "2"])
        .assert()
        .success()
        .stdout(contains("monomial   a_0 … a_5: 0 0 0 10 -15 6"));
    lekalo()
        .args(["blend", "jump", "--k", "5000"])
        .assert()
        .code(2);
}

/// A STEP or IGES file is read by every command that reads a curve: `info`, `eval` and
/// `measure` of the curve a STEP file holds give what they give for its JSON.
#[test]
fn commands_read_a_curve_from_step_and_iges() {
    let d = tempfile::tempdir().unwrap();
    fs::write(
        d.path().join("c.json"),
        r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2, "knots": [0, 0, 1, 2, 3, 3], "control": [[1, 1, 0], [2, 3, 0], [4, 3, 0]]}"#,
    )
    .unwrap();
    convert(&d, "c.json", "c.step");
    convert(&d, "c.json", "c.igs");
    let run = |args: &[&str]| {
        let out = lekalo().current_dir(d.path()).args(args).assert().success();
        String::from_utf8(out.get_output().stdout.clone()).unwrap()
    };
    for file in ["c.step", "c.igs"] {
        assert_eq!(
            run(&["eval", file, "--at", "1.5"]),
            run(&["eval", "c.json", "--at", "1.5"]),
            "{file}"
        );
        assert!(run(&["info", file]).contains("control points  3"), "{file}");
        assert_eq!(
            run(&["measure", file]),
            run(&["measure", "c.json"]),
            "{file}"
        );
    }
}

#[test]
fn step_reports_what_it_skipped_by_kind_and_count() {
    // a circle and a sphere are read; two planes without a face and a triangulated face are not
    let step = "ISO-10303-21;
HEADER;
FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF'));
ENDSEC;
DATA;
#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=AXIS2_PLACEMENT_3D('',#1,$,$);
#3=CIRCLE('',#2,2.);
#4=SPHERICAL_SURFACE('',#2,1.);
#5=PLANE('',#2);
#6=PLANE('',#2);
#7=COORDINATES_LIST('',3,((0.,0.,0.),(1.,0.,0.),(0.,1.,0.)));
#8=COMPLEX_TRIANGULATED_FACE('',#7,3,((0.,0.,1.)),$,(),(),((1,2,3)));
ENDSEC;
END-ISO-10303-21;
";
    let d = dir_with(&[("part.step", step)]);
    lekalo()
        .arg("convert")
        .arg(p(&d, "part.step"))
        .arg("-o")
        .arg(p(&d, "all.jsonl"))
        .assert()
        .success()
        .stderr(
            contains("read 1 curve(s) and 1 surface(s)")
                .and(contains("skipped 3 entities:"))
                .and(contains(
                    "2 PLANE: unbounded plane without a face to bound it (first #5)",
                ))
                .and(contains("1 COMPLEX_TRIANGULATED_FACE: tessellated")),
        );
    let text = fs::read_to_string(p(&d, "all.jsonl")).unwrap();
    assert_eq!(text.lines().count(), 2);
    // info describes every shape of the file, a curve and a surface, one JSON line each
    let out = lekalo()
        .arg("info")
        .arg(p(&d, "part.step"))
        .assert()
        .success();
    let lines: Vec<serde_json::Value> = String::from_utf8(out.get_output().stdout.clone())
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(
        (lines[0]["line"].as_u64(), lines[1]["line"].as_u64()),
        (Some(1), Some(2))
    );
    assert_eq!(lines[0]["dim"], 3);
    assert!(lines[1]["degree"].is_array(), "{}", lines[1]);
}

/// `--max-size` bounds what a STEP or IGES file may hold: a curve of 2,000 control points and
/// 2,004 knots, written by `convert`, is read back under the default limit and refused under a
/// smaller one, naming the count and the option, with nothing written.
#[test]
fn cad_files_past_max_size_are_refused_naming_the_count() {
    let n = 2000;
    let control: Vec<[f64; 3]> = (0..n)
        .map(|i| [f64::from(i), (f64::from(i) * 0.01).sin(), 0.0])
        .collect();
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(|i| f64::from(i) / f64::from(n - 3)));
    knots.extend([1.0; 4]);
    let curve = serde_json::json!({"lekalo": 1, "type": "bspline_curve", "degree": 3,
        "knots": knots, "control": control});
    let d = dir_with(&[("c.json", &curve.to_string())]);
    for ext in ["step", "igs"] {
        let cad = format!("c.{ext}");
        convert(&d, "c.json", &cad);
        convert(&d, &cad, "back.json");
        lekalo()
            .args(["--max-size", "3000", "convert"])
            .arg(p(&d, &cad))
            .arg("-o")
            .arg(p(&d, "small.json"))
            .assert()
            .code(2)
            .stderr(contains("4004 control points and knots").and(contains("--max-size 4004")));
        assert!(!p(&d, "small.json").exists(), "{ext}: nothing written");
    }
}

/// `knot join` of any curves: the halves of `split` give the curve back over its domain,
/// a line and an arc become one rational curve, and a gap exits with 2 naming it.
#[test]
fn join_takes_any_curves_one_after_another() {
    let d = dir_with(&[("c.json", CURVE)]);
    lekalo()
        .args(["knot", "split"])
        .arg(p(&d, "c.json"))
        .args(["--at", "0.3", "-o"])
        .arg(p(&d, "halves.jsonl"))
        .assert()
        .success();
    lekalo()
        .args(["knot", "join"])
        .arg(p(&d, "halves.jsonl"))
        .arg("-o")
        .arg(p(&d, "whole.json"))
        .assert()
        .success();
    let text = |f: &str| fs::read_to_string(p(&d, f)).unwrap();
    let (Shape::Curve(whole), Shape::Curve(c)) = (
        Shape::from_json_str(&text("whole.json"), "w").unwrap(),
        Shape::from_json_str(CURVE, "c").unwrap(),
    ) else {
        panic!("curves")
    };
    assert_eq!(whole.domain(), (0.0, 1.0));
    for k in 0..=20 {
        let t = f64::from(k) / 20.0;
        let (a, b) = (whole.eval(t).unwrap(), c.eval(t).unwrap());
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-14), "{t}");
    }
    // the curve's end (5, 0) on to a quarter circle about (5, 1): one NURBS of degree 2
    let arc = r#"{"lekalo": 1, "type": "nurbs_curve", "degree": 2, "knots": [0, 0, 0, 1, 1, 1],
 "control": [[5, 0], [6, 0], [6, 1]], "weights": [1, 0.7071067811865476, 1]}"#;
    let line = |x: &str| x.replace('\n', "");
    fs::write(
        p(&d, "two.jsonl"),
        format!("{}\n{}\n", line(CURVE), line(arc)),
    )
    .unwrap();
    lekalo()
        .args(["knot", "join"])
        .arg(p(&d, "two.jsonl"))
        .arg("-o")
        .arg(p(&d, "two.json"))
        .assert()
        .success();
    let Shape::Curve(two) = Shape::from_json_str(&text("two.json"), "t").unwrap() else {
        panic!("a curve")
    };
    assert!(two.is_rational() && two.domain() == (0.0, 2.0));
    let m = two.eval(1.5).unwrap();
    assert!(
        ((m[0] - 5.0).hypot(m[1] - 1.0) - 1.0).abs() < 1e-14,
        "{m:?}"
    );
    // the arc moved off the curve's end: a gap of 0.5, named
    fs::write(
        p(&d, "gap.jsonl"),
        format!(
            "{}\n{}\n",
            line(CURVE),
            line(&arc.replace("[[5, 0]", "[[5.5, 0]"))
        ),
    )
    .unwrap();
    lekalo()
        .args(["knot", "join"])
        .arg(p(&d, "gap.jsonl"))
        .assert()
        .code(2)
        .stderr(contains("member 2 starts 5e-1 from the end of member 1"));
}

/// An IGES file of the given entities (type, form, parameters), each with its own parameter
/// lines and directory entries `2k + 1`, in millimetres.
fn iges_of(entities: &[(u32, i32, &str)]) -> String {
    let mut out = format!("{:<72}S{:>7}\n", "analytic", 1);
    out += &format!("{:<72}G{:>7}\n", "1H,,1H;;", 1);
    let (mut d, mut pd) = (String::new(), String::new());
    let mut line = 1;
    for (k, (ty, form, params)) in entities.iter().enumerate() {
        let seq = 2 * k + 1;
        d += &format!(
            "{ty:>8}{line:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{seq:>7}\n",
            0, 0, 0, 0, 0, 0, "00000000"
        );
        d += &format!(
            "{ty:>8}{:>8}{:>8}{:>8}{form:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}\n",
            0,
            0,
            1,
            "",
            "",
            "",
            0,
            seq + 1
        );
        pd += &format!("{params:<64}{seq:>8}P{line:>7}\n");
        line += 1;
    }
    out += &d;
    out += &pd;
    let t = format!("S      1G      1D{:>7}P{:>7}", 2 * entities.len(), line - 1);
    out + &format!("{t:<72}T{:>7}\n", 1)
}

#[test]
fn iges_analytic_surfaces_and_paths_are_read_and_the_rest_reported() {
    // a sphere (196 over the point 116) and a 3-D path (106 form 12) are read; a cylinder
    // without a face to bound it and an offset curve are not
    let text = iges_of(&[
        (116, 0, "116,1.,2.,3.;"),
        (196, 0, "196,1,2.5;"),
        (106, 12, "106,2,3,0.,0.,0.,1.,0.,0.,1.,1.,0.;"),
        (123, 0, "123,0.,0.,1.;"),
        (192, 0, "192,1,7,4.;"),
        (130, 0, "130,5,1,0,0,0,0,1.,0.,1.,0.,0.,0.,1.,0.,1.;"),
    ]);
    let d = dir_with(&[("part.igs", &text)]);
    lekalo()
        .arg("convert")
        .arg(p(&d, "part.igs"))
        .arg("-o")
        .arg(p(&d, "all.jsonl"))
        .assert()
        .success()
        .stderr(
            contains("read 1 curve(s) and 1 surface(s)")
                .and(contains("skipped 2 entities:"))
                .and(contains("IGES entity 192: an unbounded cylinder"))
                .and(contains("IGES entity 130: an offset curve")),
        );
    let text = fs::read_to_string(p(&d, "all.jsonl")).unwrap();
    let shapes: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(shapes.len(), 2);
    assert!(
        shapes.iter().any(|s| s["type"] == "nurbs_surface"),
        "{text}"
    );
    assert!(
        shapes.iter().any(|s| s["type"] == "bspline_curve"),
        "{text}"
    );
    let out = lekalo()
        .arg("info")
        .arg(p(&d, "part.igs"))
        .assert()
        .success();
    let info = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    assert_eq!(info.lines().count(), 2, "{info}");
}
