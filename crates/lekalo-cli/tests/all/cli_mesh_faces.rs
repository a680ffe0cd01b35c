//! End-to-end tests of `lekalo mesh` of faces: a STEP plate with a round hole, converted to face
//! JSON Lines, meshed to OBJ with the hole left out and the area of the plate.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use serde_json::Value;

use crate::cli_faces::PLATE;
use crate::common;
use common::{convert_faces, dir_with, last_stderr_json, lekalo, p};

/// The vertices and triangles of an OBJ file.
fn read_obj(text: &str) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let (mut v, mut f) = (Vec::new(), Vec::new());
    for l in text.lines() {
        let w: Vec<&str> = l.split_whitespace().collect();
        match w.first() {
            Some(&"v") => v.push([1, 2, 3].map(|k| w[k].parse::<f64>().unwrap())),
            Some(&"f") => f.push(
                [1, 2, 3].map(|k| w[k].split('/').next().unwrap().parse::<usize>().unwrap() - 1),
            ),
            _ => {}
        }
    }
    (v, f)
}

#[test]
fn mesh_of_face_lines_leaves_the_hole_out() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &["-q"], "plate.step", "faces.jsonl").success();
    let tol = 1e-3;
    let out = lekalo()
        .args(["mesh", "--tolerance", "1e-3", "--json"])
        .arg(p(&d, "faces.jsonl"))
        .arg("-o")
        .arg(p(&d, "plate.obj"))
        .assert()
        .success();
    let summary = last_stderr_json(&out);
    assert_eq!(summary["faces"].as_u64(), Some(1));
    assert!(summary["deviation"].as_f64().unwrap() <= tol);
    let (v, f) = read_obj(&fs::read_to_string(p(&d, "plate.obj")).unwrap());
    assert_eq!(summary["triangles"].as_u64(), Some(f.len() as u64));
    let mut area = 0.0;
    for t in &f {
        let [a, b, c] = t.map(|k| v[k]);
        let c0 = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
        // no triangle in the hole of radius 2 about (5, 5)
        assert!(((c0[0] - 5.0).powi(2) + (c0[1] - 5.0).powi(2)).sqrt() >= 2.0 - tol);
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
    }
    // 100 − 4π within the area between the circle and its polygon (length 4π times tol)
    let exact = 100.0 - 4.0 * std::f64::consts::PI;
    assert!(
        area >= exact - 1e-9 && area - exact <= 4.0 * std::f64::consts::PI * tol,
        "{area}"
    );
}

#[test]
fn mesh_of_face_lines_on_standard_input_is_that_of_the_file() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &["-q"], "plate.step", "faces.jsonl").success();
    let lines = fs::read_to_string(p(&d, "faces.jsonl")).unwrap();
    let from_file = lekalo()
        .args(["mesh", "--tolerance", "1e-3", "--json"])
        .arg(p(&d, "faces.jsonl"))
        .arg("-o")
        .arg(p(&d, "file.obj"))
        .assert()
        .success();
    // `-` is read once and recognised by its first line, as a file of face envelopes is
    let from_stdin = lekalo()
        .args(["mesh", "-", "--tolerance", "1e-3", "--json", "-o"])
        .arg(p(&d, "stdin.obj"))
        .write_stdin(lines)
        .assert()
        .success();
    assert_eq!(last_stderr_json(&from_stdin), last_stderr_json(&from_file));
    assert_eq!(
        fs::read_to_string(p(&d, "stdin.obj")).unwrap(),
        fs::read_to_string(p(&d, "file.obj")).unwrap()
    );
}

/// `info -` and `convert -` read standard input once and take it for faces when its first line
/// is a face envelope, as `mesh -` does; for JSON Lines of curves when its first line is a whole
/// object and more follow; for a STEP file when it opens with `ISO-10303-21;`. Each gives what
/// the same command gives for the file.
#[test]
fn info_and_convert_of_standard_input_read_what_the_file_holds() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &["-q"], "plate.step", "faces.jsonl").success();
    let lines = fs::read_to_string(p(&d, "faces.jsonl")).unwrap();
    let from_file = lekalo()
        .args(["info", "--json"])
        .arg(p(&d, "faces.jsonl"))
        .assert()
        .success();
    let from_stdin = lekalo()
        .args(["info", "--json", "-"])
        .write_stdin(lines.clone())
        .assert()
        .success();
    let stdout = |a: &assert_cmd::assert::Assert| {
        String::from_utf8_lossy(&a.get_output().stdout).into_owned()
    };
    assert_eq!(stdout(&from_stdin), stdout(&from_file));
    let report: Value = serde_json::from_str(&stdout(&from_file)).unwrap();
    assert_eq!(report["faces_total"].as_u64(), Some(1), "{report}");
    lekalo()
        .args(["convert", "-", "-o"])
        .arg(p(&d, "again.jsonl"))
        .write_stdin(lines.clone())
        .assert()
        .success();
    assert_eq!(fs::read_to_string(p(&d, "again.jsonl")).unwrap(), lines);
    // the STEP file itself on standard input: its faces, and its shapes
    lekalo()
        .args(["convert", "-", "--faces", "-q", "-o"])
        .arg(p(&d, "step.jsonl"))
        .write_stdin(PLATE)
        .assert()
        .success();
    assert_eq!(fs::read_to_string(p(&d, "step.jsonl")).unwrap(), lines);
    lekalo()
        .args(["convert", "-q", "-o"])
        .arg(p(&d, "shapes-file.jsonl"))
        .arg(p(&d, "plate.step"))
        .assert()
        .success();
    lekalo()
        .args(["convert", "-", "-q", "-o"])
        .arg(p(&d, "shapes-stdin.jsonl"))
        .write_stdin(PLATE)
        .assert()
        .success();
    assert_eq!(
        fs::read_to_string(p(&d, "shapes-stdin.jsonl")).unwrap(),
        fs::read_to_string(p(&d, "shapes-file.jsonl")).unwrap()
    );
    // two curves, one a line, on standard input: a batch, as from a .jsonl file
    let curve = r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1]]}"#;
    let two = format!("{curve}\n{curve}\n");
    let out = lekalo()
        .args(["info", "--json", "-"])
        .write_stdin(two)
        .assert()
        .success();
    assert_eq!(stdout(&out).lines().count(), 2, "{}", stdout(&out));
}

#[test]
fn mesh_of_faces_refuses_a_tolerance_too_small() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &["-q"], "plate.step", "faces.jsonl").success();
    lekalo()
        .args(["mesh", "--tolerance", "0"])
        .arg(p(&d, "faces.jsonl"))
        .assert()
        .failure()
        .stderr(predicates::str::contains("--tolerance: 0 "));
}

/// Removes every edge's pcurve from a face's JSON.
fn without_pcurves(face: &mut Value) {
    let strip = |edges: &mut Value| {
        for e in edges.as_array_mut().unwrap() {
            e.as_object_mut().unwrap().remove("pcurve");
        }
    };
    strip(&mut face["outer"]);
    if let Some(inner) = face["inner"].as_array_mut() {
        inner.iter_mut().for_each(strip);
    }
}

/// The area of the triangles of an OBJ file.
fn obj_area(v: &[[f64; 3]], f: &[[usize; 3]]) -> f64 {
    f.iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| v[k]);
            let (e, g) = (
                [0, 1, 2].map(|i| b[i] - a[i]),
                [0, 1, 2].map(|i| c[i] - a[i]),
            );
            let n = [
                e[1] * g[2] - e[2] * g[1],
                e[2] * g[0] - e[0] * g[2],
                e[0] * g[1] - e[1] * g[0],
            ];
            0.5 * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
        })
        .sum()
}

/// A tube of radius 1 and height 2 about the z axis: a cylindrical face bounded by two circles
/// and its seam line (used twice), none of its edges with a pcurve.
const TUBE: &str = "ISO-10303-21;
HEADER;
FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));
ENDSEC;
DATA;
#201=CARTESIAN_POINT('',(0.,0.,0.));
#202=DIRECTION('',(0.,0.,1.));
#203=DIRECTION('',(1.,0.,0.));
#204=AXIS2_PLACEMENT_3D('',#201,#202,#203);
#205=CYLINDRICAL_SURFACE('',#204,1.);
#206=CARTESIAN_POINT('',(0.,0.,2.));
#207=AXIS2_PLACEMENT_3D('',#206,#202,#203);
#208=CIRCLE('',#204,1.);
#209=CIRCLE('',#207,1.);
#210=CARTESIAN_POINT('',(1.,0.,0.));
#211=CARTESIAN_POINT('',(1.,0.,2.));
#212=VERTEX_POINT('',#210);
#213=VERTEX_POINT('',#211);
#214=VECTOR('',#202,1.);
#215=LINE('',#210,#214);
#230=EDGE_CURVE('',#212,#212,#208,.T.);
#231=EDGE_CURVE('',#213,#213,#209,.T.);
#232=EDGE_CURVE('',#212,#213,#215,.T.);
#240=ORIENTED_EDGE('',*,*,#230,.T.);
#241=ORIENTED_EDGE('',*,*,#232,.T.);
#242=ORIENTED_EDGE('',*,*,#231,.F.);
#243=ORIENTED_EDGE('',*,*,#232,.F.);
#244=EDGE_LOOP('',(#240,#241,#242,#243));
#245=FACE_OUTER_BOUND('',#244,.T.);
#246=ADVANCED_FACE('tube',(#245),#205,.T.);
ENDSEC;
END-ISO-10303-21;
";

#[test]
fn mesh_of_faces_projects_the_missing_pcurves_and_lists_the_faces_off_their_surface() {
    let d = dir_with(&[("plate.step", PLATE), ("tube.step", TUBE)]);
    for name in ["plate", "tube"] {
        convert_faces(
            &d,
            &["-q"],
            &format!("{name}.step"),
            &format!("{name}.jsonl"),
        )
        .success();
    }
    let plate = fs::read_to_string(p(&d, "plate.jsonl")).unwrap();
    let tube = fs::read_to_string(p(&d, "tube.jsonl")).unwrap();
    assert!(tube.contains(r#""pcurve":null"#), "{tube}");
    // the plate without its pcurves, and once more with its plane lifted 1 mm off its edges
    let mut bare: Value = serde_json::from_str(plate.trim()).unwrap();
    without_pcurves(&mut bare);
    let mut lifted = bare.clone();
    lifted["id"] = Value::from(99);
    for c in lifted["surface"]["control"].as_array_mut().unwrap() {
        c[2] = Value::from(c[2].as_f64().unwrap() + 1.0);
    }
    let lifted_text = lifted.to_string();
    fs::write(
        p(&d, "all.jsonl"),
        format!("{}\n{bare}\n{lifted_text}\n", tube.trim()),
    )
    .unwrap();
    let tol = 1e-3;
    let out = lekalo()
        .args(["mesh", "--tolerance", "1e-3", "--json"])
        .arg(p(&d, "all.jsonl"))
        .arg("-o")
        .arg(p(&d, "all.obj"))
        .assert()
        .success()
        .stderr(predicates::str::contains("1 of 3 faces not meshed"))
        .stderr(predicates::str::contains("face #99"));
    let summary = last_stderr_json(&out);
    assert_eq!(summary["faces"].as_u64(), Some(2));
    assert_eq!(summary["skipped"].as_u64(), Some(1));
    assert_eq!(summary["skipped_faces"][0]["id"].as_u64(), Some(99));
    let reason = summary["skipped_faces"][0]["reason"].as_str().unwrap();
    assert!(
        reason.contains("does not lie on the face's surface"),
        "{reason}"
    );
    // the tube (4π, radius 1 and height 2) and the plate with its hole (100 − 4π): inscribed
    // triangles lose at most tol of the tube's area per unit area, and each trim at most tol
    // times its length (the tube's two circles and seam twice, the plate's square and circle)
    let (v, f) = read_obj(&fs::read_to_string(p(&d, "all.obj")).unwrap());
    let area = obj_area(&v, &f);
    let exact = 100.0;
    let pi = std::f64::consts::PI;
    let bound = (4.0 * pi + (4.0 * pi + 4.0) + (40.0 + 4.0 * pi)) * tol;
    assert!((area - exact).abs() <= bound, "{area}");
    // the faces that are meshed are the mesh of these faces alone, in one pass
    fs::write(p(&d, "good.jsonl"), format!("{}\n{bare}\n", tube.trim())).unwrap();
    lekalo()
        .args(["mesh", "--tolerance", "1e-3"])
        .arg(p(&d, "good.jsonl"))
        .arg("-o")
        .arg(p(&d, "good.obj"))
        .assert()
        .success();
    assert_eq!(
        fs::read_to_string(p(&d, "all.obj")).unwrap(),
        fs::read_to_string(p(&d, "good.obj")).unwrap(),
        "a face left out changes the others' mesh"
    );
    // the lifted face alone: nothing to mesh, and the reason
    fs::write(p(&d, "lifted.jsonl"), format!("{lifted_text}\n")).unwrap();
    lekalo()
        .args(["mesh", "--tolerance", "1e-3"])
        .arg(p(&d, "lifted.jsonl"))
        .arg("-o")
        .arg(p(&d, "lifted.obj"))
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "none of the 1 faces can be meshed",
        ))
        .stderr(predicates::str::contains("does not lie on"));
    assert!(!p(&d, "lifted.obj").exists());
}

/// A band of the cylinder of radius 1 between its circles at `z = 0` and `z = 2`: two loops, each
/// one circle going once round, no seam edge and no pcurve (the face on the left of each circle
/// seen from outside: the lower counter-clockwise from above, the upper clockwise).
const BAND: &str = "ISO-10303-21;
HEADER;
FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));
ENDSEC;
DATA;
#201=CARTESIAN_POINT('',(0.,0.,0.));
#202=DIRECTION('',(0.,0.,1.));
#203=DIRECTION('',(1.,0.,0.));
#204=AXIS2_PLACEMENT_3D('',#201,#202,#203);
#205=CYLINDRICAL_SURFACE('',#204,1.);
#206=CARTESIAN_POINT('',(0.,0.,2.));
#207=AXIS2_PLACEMENT_3D('',#206,#202,#203);
#208=CIRCLE('',#204,1.);
#209=CIRCLE('',#207,1.);
#210=CARTESIAN_POINT('',(1.,0.,0.));
#211=CARTESIAN_POINT('',(1.,0.,2.));
#212=VERTEX_POINT('',#210);
#213=VERTEX_POINT('',#211);
#230=EDGE_CURVE('',#212,#212,#208,.T.);
#231=EDGE_CURVE('',#213,#213,#209,.T.);
#240=ORIENTED_EDGE('',*,*,#230,.T.);
#241=EDGE_LOOP('',(#240));
#242=FACE_OUTER_BOUND('',#241,.T.);
#243=ORIENTED_EDGE('',*,*,#231,.F.);
#244=EDGE_LOOP('',(#243));
#245=FACE_BOUND('',#244,.T.);
#246=ADVANCED_FACE('band',(#242,#245),#205,.T.);
ENDSEC;
END-ISO-10303-21;
";

/// The band has no seam edge: the mesher cuts it along a seam. Its mesh has the band's area,
/// its only open edges are on the two circles (no crack along the cut), and its normals point
/// out of the cylinder.
#[test]
fn mesh_of_a_band_without_a_seam_edge_cuts_it_along_a_seam() {
    let d = dir_with(&[("band.step", BAND)]);
    convert_faces(&d, &["-q"], "band.step", "band.jsonl").success();
    let tol = 1e-3;
    let out = lekalo()
        .args(["mesh", "--tolerance", "1e-3", "--json"])
        .arg(p(&d, "band.jsonl"))
        .arg("-o")
        .arg(p(&d, "band.obj"))
        .assert()
        .success();
    let summary = last_stderr_json(&out);
    assert_eq!(summary["faces"].as_u64(), Some(1));
    assert_eq!(summary["skipped"].as_u64(), Some(0));
    let (v, f) = read_obj(&fs::read_to_string(p(&d, "band.obj")).unwrap());
    // 2π r h = 4π within tol per unit area and tol times the two circles' length
    let pi = std::f64::consts::PI;
    let area = obj_area(&v, &f);
    assert!(
        (area - 4.0 * pi).abs() <= (4.0 * pi + 4.0 * pi) * tol,
        "{area}"
    );
    // edges used by one triangle only, the vertices taken by their printed coordinates: all on
    // the circles
    let key = |k: usize| format!("{:?}", v[k]);
    let mut count = std::collections::HashMap::new();
    for t in &f {
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let (a, b) = (key(t[i]), key(t[j]));
            *count
                .entry(if a < b { (a, b) } else { (b, a) })
                .or_insert(0) += 1;
        }
    }
    let on_circle = |s: &str| {
        let z: f64 = s
            .trim_end_matches(']')
            .rsplit(", ")
            .next()
            .unwrap()
            .parse()
            .unwrap();
        z.abs() < 1e-9 || (z - 2.0).abs() < 1e-9
    };
    for ((a, b), n) in &count {
        assert!(
            *n <= 2 && (*n == 2 || (on_circle(a) && on_circle(b))),
            "{a} {b} {n}"
        );
    }
    for t in &f {
        let [a, b, c] = t.map(|k| v[k]);
        let (e, g) = (
            [0, 1, 2].map(|i| b[i] - a[i]),
            [0, 1, 2].map(|i| c[i] - a[i]),
        );
        let n = [e[1] * g[2] - e[2] * g[1], e[2] * g[0] - e[0] * g[2]];
        let m = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
        assert!(n[0] * m[0] + n[1] * m[1] > 0.0, "a triangle faces in");
    }
}

/// The loop `l` (a JSON list of edges) moved by `du` in `u` (and `x`: the plate's plane is
/// `(u, v, 0)`).
fn shifted(l: &Value, du: f64) -> Value {
    let mut l = l.clone();
    for e in l.as_array_mut().unwrap() {
        for key in ["curve", "pcurve"] {
            for c in e[key]["control"].as_array_mut().unwrap() {
                c[0] = Value::from(c[0].as_f64().unwrap() + du);
            }
        }
    }
    l
}

#[test]
fn mesh_of_faces_with_bad_trims_lists_them_and_reports_the_repairs() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &["-q"], "plate.step", "plate.jsonl").success();
    let plate: Value =
        serde_json::from_str(fs::read_to_string(p(&d, "plate.jsonl")).unwrap().trim()).unwrap();
    let hole = &plate["inner"][0];
    // #77: the hole moved 4 along u reaches u = 11, past the plane's domain [0, 10]
    let mut outside = plate.clone();
    outside["id"] = Value::from(77);
    outside["inner"] = Value::from(vec![shifted(hole, 4.0)]);
    // #78: a hole of one point, dropped
    let mut point = plate.clone();
    point["id"] = Value::from(78);
    let line = |dim: usize| {
        let c = if dim == 2 {
            vec![5.0, 5.0]
        } else {
            vec![5.0, 5.0, 0.0]
        };
        serde_json::json!({"lekalo": 1, "type": "bspline_curve", "degree": 1,
            "knots": [0, 0, 1, 1], "control": [c.clone(), c]})
    };
    point["inner"] = serde_json::json!([[{"curve": line(3), "pcurve": line(2)}]]);
    // #79: two holes crossing
    let mut crossing = plate.clone();
    crossing["id"] = Value::from(79);
    crossing["inner"] = Value::from(vec![hole.clone(), shifted(hole, 1.0)]);
    let text: String = [&plate, &outside, &point, &crossing]
        .iter()
        .map(|f| format!("{f}\n"))
        .collect();
    fs::write(p(&d, "bad.jsonl"), text).unwrap();
    let out = lekalo()
        .args(["mesh", "--tolerance", "1e-2", "--json"])
        .arg(p(&d, "bad.jsonl"))
        .arg("-o")
        .arg(p(&d, "bad.obj"))
        .assert()
        .success()
        .stderr(predicates::str::contains("2 of 4 faces not meshed"))
        .stderr(predicates::str::contains(
            "face #78 (plate): inner loop 1 has no length (a hole of one point): dropped",
        ));
    let summary = last_stderr_json(&out);
    assert_eq!(summary["faces"].as_u64(), Some(2));
    let skipped = summary["skipped_faces"].as_array().unwrap();
    assert_eq!(skipped.len(), 2);
    assert_eq!(skipped[0]["id"].as_u64(), Some(77));
    let reason = skipped[0]["reason"].as_str().unwrap();
    assert!(
        reason.starts_with(
            "inner loop 1 leaves the surface's domain: edge 0's curve in (u, v) reaches (11, 5), past its side u = 10"
        ),
        "{reason}"
    );
    assert_eq!(skipped[1]["id"].as_u64(), Some(79));
    let reason = skipped[1]["reason"].as_str().unwrap();
    assert!(
        reason.starts_with("inner loop 2 crosses inner loop 1 near (u, v) = "),
        "{reason}"
    );
    assert_eq!(summary["repaired"][0]["id"].as_u64(), Some(78));
    // the plate and the plate without the hole of one point: 100 − 4π + 100
    let (v, f) = read_obj(&fs::read_to_string(p(&d, "bad.obj")).unwrap());
    let area = obj_area(&v, &f);
    let exact = 200.0 - 4.0 * std::f64::consts::PI;
    assert!(area >= exact - 1e-9 && area - exact <= 0.2, "{area}");
}

/// A STEP plate whose hole crosses its outer loop, meshed from the STEP file itself: refused
/// naming the face's instance, the loops and where they cross; exit 2, nothing written.
#[test]
fn mesh_of_a_step_face_whose_hole_crosses_its_boundary_names_the_face_and_loops() {
    let crossing = PLATE
        .replace(
            "#60=CARTESIAN_POINT('',(5.,5.,0.));",
            "#60=CARTESIAN_POINT('',(9.5,5.,0.));",
        )
        .replace(
            "#63=CARTESIAN_POINT('',(7.,5.,0.));",
            "#63=CARTESIAN_POINT('',(11.5,5.,0.));",
        );
    assert_ne!(crossing, PLATE);
    let d = dir_with(&[("cross.step", crossing.as_str())]);
    lekalo()
        .args(["mesh", "-q", "--tolerance", "1e-2"])
        .arg(p(&d, "cross.step"))
        .arg("-o")
        .arg(p(&d, "cross.obj"))
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "face #70 (plate): inner loop 1 crosses the outer loop near (u, v) = (10, ",
        ));
    assert!(!p(&d, "cross.obj").exists());
}
