//! End-to-end tests of surfaces and pp-forms in `info`, `convert` and `plot`.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use assert_cmd::Command;
use predicates::str::contains;

const SURFACE: &str = r#"{"lekalo": 1, "type": "nurbs_surface", "degree_u": 2, "degree_v": 1,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "net": [3, 2],
 "control": [[0, 0, 0], [0, 1, 0], [1, 0, 1], [1, 1, 1], [2, 0, 0], [2, 1, 0.5]],
 "weights": [1, 1, 0.7, 0.7, 1, 1]}"#;

// f = x + x²/2 on [0, 1], continued C¹ (value and slope match at 1 and 2, the second
// derivative jumps)
const PP: &str = r#"{"lekalo": 1, "type": "piecewise_polynomial", "breakpoints": [0, 1, 2, 3],
 "order": 3, "dim": 1, "coefficients": [0, 1, 0.5, 1.5, 2, -1, 2.5, 0, 3]}"#;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

#[test]
fn info_on_a_surface_and_a_pp() {
    let d = tempfile::tempdir().unwrap();
    let s = d.path().join("s.json");
    let p = d.path().join("p.json");
    fs::write(&s, SURFACE).unwrap();
    fs::write(&p, PP).unwrap();
    lekalo()
        .arg("info")
        .arg(&s)
        .assert()
        .success()
        .stdout(contains("NURBS surface"))
        .stdout(contains("degree          [2, 1]"))
        .stdout(contains("net             [3, 2]"))
        .stdout(contains("domain          [[0, 1], [0, 1]]"));
    lekalo()
        .arg("info")
        .arg(&p)
        .assert()
        .success()
        .stdout(contains("order           3"))
        .stdout(contains("continuity      1: C^1  2: C^1"));
}

#[test]
fn convert_and_plot_a_surface_and_a_pp() {
    let d = tempfile::tempdir().unwrap();
    let s = d.path().join("s.json");
    let p = d.path().join("p.json");
    fs::write(&s, SURFACE).unwrap();
    fs::write(&p, PP).unwrap();
    for ext in ["step", "obj", "svg", "png", "json"] {
        let out = d.path().join(format!("out.{ext}"));
        lekalo()
            .arg("convert")
            .arg(&s)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        assert!(fs::metadata(&out).unwrap().len() > 100, "{ext}");
    }
    let step = fs::read_to_string(d.path().join("out.step")).unwrap();
    assert!(
        step.contains("RATIONAL_B_SPLINE_SURFACE(((1.,1.),(7.E-1,7.E-1),(1.,1.)))"),
        "{step}"
    );
    let obj = fs::read_to_string(d.path().join("out.obj")).unwrap();
    assert_eq!(
        obj.lines().filter(|l| l.starts_with("vn ")).count(),
        14 * 14
    );
    let csv = d.path().join("p.csv");
    lekalo()
        .arg("convert")
        .arg(&p)
        .arg("-o")
        .arg(&csv)
        .args(["--samples", "5"])
        .assert()
        .success();
    // 1.5 lies in the second piece: 1.5 + 2·0.5 − 0.25 = 2.25
    assert_eq!(
        fs::read_to_string(&csv).unwrap(),
        "x,f\n0,0\n0.75,1.03125\n1.5,2.25\n2.25,2.6875\n3,5.5\n"
    );
    for (input, name) in [(&s, "s.svg"), (&p, "p.svg")] {
        let out = d.path().join(format!("plot-{name}"));
        lekalo()
            .arg("plot")
            .arg(input)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        assert!(fs::read_to_string(&out).unwrap().contains("<svg"));
    }
    lekalo()
        .arg("convert")
        .arg(&p)
        .args(["--to", "step"])
        .assert()
        .code(2)
        .stderr(contains("piecewise_polynomial converts to"));
}

#[test]
fn bad_input_exits_2_naming_the_field() {
    let d = tempfile::tempdir().unwrap();
    let s = d.path().join("s.json");
    fs::write(
        &s,
        SURFACE.replace("[1, 1, 0.7, 0.7, 1, 1]", "[1, 1, 0.7, 0.7, 1]"),
    )
    .unwrap();
    lekalo()
        .arg("info")
        .arg(&s)
        .assert()
        .code(2)
        .stderr(contains("field `weights`"));
    fs::write(&s, SURFACE).unwrap();
    // surfaces are evaluated on (u, v) (tests/all/cli_knot_cad.rs); a piecewise polynomial is not
    lekalo()
        .arg("eval")
        .arg(&s)
        .assert()
        .success()
        .stdout(contains("u,v,x,y,z\n"));
}

fn real(p: &ruststep::ast::Parameter) -> f64 {
    use ruststep::ast::Parameter;
    match p {
        Parameter::Real(x) => *x,
        Parameter::Integer(i) => *i as f64,
        other => panic!("expected a real, got {other:?}"),
    }
}

fn list(p: &ruststep::ast::Parameter) -> &[ruststep::ast::Parameter] {
    match p {
        ruststep::ast::Parameter::List(v) => v,
        other => panic!("expected a list, got {other:?}"),
    }
}

/// `lekalo convert` to STEP, read back with the independent parser `ruststep`: the rational
/// surface rebuilt from the parsed degrees, knots, points and weights evaluates to the same
/// points as the JSON surface.
#[test]
fn step_surface_reads_back_with_ruststep() {
    use ruststep::ast::{EntityInstance, Name, Parameter};
    let d = tempfile::tempdir().unwrap();
    let s = d.path().join("s.json");
    let out = d.path().join("s.step");
    fs::write(&s, SURFACE).unwrap();
    lekalo()
        .arg("convert")
        .arg(&s)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let text = fs::read_to_string(&out).unwrap();
    let ex = ruststep::parser::parse(&text).unwrap();
    let mut points = std::collections::HashMap::new();
    let mut surface = None;
    for e in &ex.data[0].entities {
        match e {
            EntityInstance::Simple { id, record } if record.name == "CARTESIAN_POINT" => {
                let Parameter::List(p) = &record.parameter else {
                    panic!()
                };
                points.insert(*id, list(&p[1]).iter().map(real).collect::<Vec<f64>>());
            }
            EntityInstance::Complex { subsuper, .. } => surface = Some(subsuper.0.clone()),
            EntityInstance::Simple { .. } => {}
        }
    }
    let recs = surface.expect("the rational surface is a complex instance");
    let attrs = |name: &str| {
        let r = recs.iter().find(|r| r.name == name).unwrap();
        list(&r.parameter).to_vec()
    };
    let bs = attrs("B_SPLINE_SURFACE");
    let wk = attrs("B_SPLINE_SURFACE_WITH_KNOTS");
    let w = attrs("RATIONAL_B_SPLINE_SURFACE");
    let deg = |p: &Parameter| match p {
        Parameter::Integer(i) => usize::try_from(*i).unwrap(),
        other => panic!("{other:?}"),
    };
    let expand = |m: &Parameter, k: &Parameter| -> Vec<f64> {
        list(m)
            .iter()
            .zip(list(k))
            .flat_map(|(m, k)| std::iter::repeat_n(real(k), deg(m)))
            .collect()
    };
    let mut ctrl = Vec::new();
    for row in list(&bs[2]) {
        for p in list(row) {
            let Parameter::Ref(Name::Entity(id)) = p else {
                panic!("{p:?}")
            };
            ctrl.push(points[id].clone());
        }
    }
    let weights: Vec<f64> = list(&w[0]).iter().flat_map(list).map(real).collect();
    let nu = list(&bs[2]).len();
    let back = lekalo::NurbsSurface::new(
        deg(&bs[0]),
        deg(&bs[1]),
        expand(&wk[0], &wk[2]),
        expand(&wk[1], &wk[3]),
        lekalo::Points::from_rows(&ctrl).unwrap(),
        weights,
        (nu, ctrl.len() / nu),
    )
    .unwrap();
    let ours = lekalo_io::read_nurbs_surface(SURFACE, "s").unwrap();
    for (u, v) in [(0.0, 0.0), (0.3, 0.7), (0.5, 0.5), (1.0, 0.2), (1.0, 1.0)] {
        let (a, b) = (ours.eval(u, v).unwrap(), back.eval(u, v).unwrap());
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-12, "({u}, {v}): {a:?} vs {b:?}");
        }
    }
}

/// The `data-range` of the SVG's colour bar, and its label.
fn colorbar(svg: &str) -> (String, f64, f64) {
    let g = &svg[svg.find("<g class=\"colorbar\"").expect("a colour bar")..];
    let attr = |name: &str| {
        let at = g.find(&format!("{name}=\"")).expect(name) + name.len() + 2;
        g[at..at + g[at..].find('"').expect("quote")].to_string()
    };
    let range = attr("data-range");
    let (lo, hi) = range.split_once(' ').expect("two numbers");
    (attr("data-label"), lo.parse().unwrap(), hi.parse().unwrap())
}

#[test]
fn a_curvature_map_spans_the_library_curvatures_on_its_grid() {
    let d = tempfile::tempdir().unwrap();
    let s = d.path().join("s.json");
    fs::write(&s, SURFACE).unwrap();
    for (kind, column, label) in [
        ("gaussian", 2, "Gaussian curvature"),
        ("mean", 3, "mean curvature"),
        ("k1", 0, "principal curvature k1"),
        ("k2", 1, "principal curvature k2"),
    ] {
        let svg = d.path().join(format!("{kind}.svg"));
        lekalo()
            .arg("plot")
            .arg(&s)
            .args(["--curvature", kind, "--samples", "9", "-o"])
            .arg(&svg)
            .assert()
            .success();
        let (got_label, lo, hi) = colorbar(&fs::read_to_string(&svg).unwrap());
        assert_eq!(got_label, label);
        // the same 9 × 9 grid through `eval --curvature`: the bar spans its column exactly
        let out = lekalo()
            .arg("eval")
            .arg(&s)
            .args(["--grid", "9x9", "--curvature"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let values: Vec<f64> = String::from_utf8(out)
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                f[f.len() - 4 + column].parse().unwrap()
            })
            .collect();
        assert_eq!(values.len(), 81);
        let min = values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert_eq!((lo, hi), (min, max), "{kind}");
        assert!(hi > lo, "{kind}: the NURBS bump's curvature varies");
    }
    // a curvature map is for shaded 3-D surfaces
    let x = d.path().join("x.svg");
    for (args, why) in [
        (vec!["--curvature", "mean", "--wireframe"], "--wireframe"),
        (vec!["--curvature", "teal"], "teal"),
    ] {
        lekalo()
            .arg("plot")
            .arg(&s)
            .args(&args)
            .arg("-o")
            .arg(&x)
            .assert()
            .code(2)
            .stderr(contains(why));
    }
    let p = d.path().join("p.json");
    fs::write(&p, PP).unwrap();
    lekalo()
        .arg("plot")
        .arg(&p)
        .args(["--curvature", "mean", "-o"])
        .arg(&x)
        .assert()
        .code(2)
        .stderr(contains("--curvature colours a surface"));
    assert!(!x.exists(), "nothing written on a refusal");
}

#[path = "cli_surfaces/tensor.rs"]
mod tensor;

#[path = "cli_surfaces/make_tensor.rs"]
mod make_tensor;

/// The help of `eval`, `convert` and `project` names a surface's parameter columns as the
/// commands write them: the columns of the header before the point's `x`, listed as `u, v`.
#[test]
fn help_names_a_surfaces_columns_as_written() {
    let d = tempfile::tempdir().unwrap();
    let s = d.path().join("s.json");
    fs::write(&s, SURFACE).unwrap();
    let header = |args: &[&str]| {
        let out = lekalo().args(args).arg(&s).assert().success();
        let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
        let first = text.lines().next().unwrap_or_default().to_string();
        let before_x: Vec<&str> = first.split(',').take_while(|c| *c != "x").collect();
        before_x.join(", ")
    };
    let csv = d.path().join("s.csv");
    lekalo()
        .args(["convert", "--samples", "4", "-o"])
        .arg(&csv)
        .arg(&s)
        .assert()
        .success();
    let converted = fs::read_to_string(&csv).unwrap();
    let first = converted.lines().next().unwrap_or_default();
    let before_x: Vec<&str> = first.split(',').take_while(|c| *c != "x").collect();
    let cases = [
        ("eval", header(&["eval", "--uv", "0.5,0.5"])),
        ("project", header(&["project", "--point", "1,0.5,2"])),
        ("convert", before_x.join(", ")),
    ];
    for (command, columns) in cases {
        assert_eq!(
            columns,
            if command == "project" {
                "index, u, v"
            } else {
                "u, v"
            }
        );
        let named = columns.trim_start_matches("index, ");
        let help = lekalo().args([command, "--help"]).assert().success();
        let text = String::from_utf8(help.get_output().stdout.clone()).unwrap();
        assert!(
            text.contains(&format!("{named}, ")) || text.contains(&format!("{named})")),
            "`lekalo {command} --help` does not name the columns {named}:\n{text}"
        );
    }
}

/// `lekalo sweep`: a segment turned a quarter turn about z lies on the cylinder of its
/// distance (every grid point of `eval` at radius 2), a ruled surface has its two curves as
/// edges, and bad vectors and output formats exit with 2 naming the option.
#[test]
fn sweep_builds_exact_surfaces_from_curves() {
    let d = tempfile::tempdir().unwrap();
    let seg = d.path().join("seg.json");
    fs::write(
        &seg,
        r#"{"lekalo": 1, "type": "bezier_curve", "control": [[2, 0, 1], [2, 0, 3]]}"#,
    )
    .unwrap();
    let out = d.path().join("rev.json");
    lekalo()
        .args(["sweep", "revolve"])
        .arg(&seg)
        .args(["--axis-point", "0,0,0", "--axis-direction", "0,0,1"])
        .args(["--angles", "-1.5707963267948966,0", "-o"])
        .arg(&out)
        .assert()
        .success();
    let csv = lekalo()
        .arg("eval")
        .arg(&out)
        .args(["--grid", "5x3"])
        .output()
        .unwrap();
    assert!(csv.status.success());
    let text = String::from_utf8(csv.stdout).unwrap();
    let mut rows = 0;
    for line in text.lines().skip(1) {
        let f: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (x, y) = (f[2], f[3]);
        assert!((x.hypot(y) - 2.0).abs() < 1e-13, "{line}");
        assert!(
            x >= -1e-13 && y <= 1e-13,
            "{line}: not in the fourth quadrant"
        );
        rows += 1;
    }
    assert_eq!(rows, 15);
    let upper = d.path().join("upper.json");
    fs::write(
        &upper,
        r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0, 5], [1, 1, 5], [4, 0, 5]]}"#,
    )
    .unwrap();
    let ruled = d.path().join("ruled.json");
    lekalo()
        .args(["sweep", "ruled"])
        .arg(&seg)
        .arg(&upper)
        .arg("-o")
        .arg(&ruled)
        .assert()
        .success();
    let corners = lekalo()
        .arg("eval")
        .arg(&ruled)
        .args(["--uv", "0,0,1,0,0,1,1,1"])
        .output()
        .unwrap();
    let text = String::from_utf8(corners.stdout).unwrap();
    let got: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').skip(2).map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(
        got,
        vec![
            vec![2.0, 0.0, 1.0],
            vec![2.0, 0.0, 3.0],
            vec![0.0, 0.0, 5.0],
            vec![4.0, 0.0, 5.0]
        ]
    );
    lekalo()
        .args(["sweep", "extrude"])
        .arg(&seg)
        .args(["--direction", "0,0"])
        .assert()
        .code(2)
        .stderr(contains("--direction: 2 numbers"));
    lekalo()
        .args(["sweep", "extrude"])
        .arg(&seg)
        .args(["--direction", "0,0,0"])
        .assert()
        .code(2)
        .stderr(contains("direction"));
    lekalo()
        .args(["sweep", "ruled"])
        .arg(&seg)
        .arg(&upper)
        .arg("-o")
        .arg(d.path().join("r.step"))
        .assert()
        .code(2)
        .stderr(contains("lekalo convert"));
    assert!(!d.path().join("r.step").exists());
}

#[path = "cli_surfaces/slice.rs"]
mod slice;
