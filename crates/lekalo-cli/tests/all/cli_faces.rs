//! End-to-end tests of `--faces`: `convert` writes a STEP file's faces (and an IGES file's
//! trimmed surfaces) as JSON Lines that the
//! library reads back, `info` lists them, and faces that cannot be read are reported.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;
use serde_json::Value;

use crate::common;
use common::{convert_faces, dir_with, lekalo, p};

/// A plate 10 × 10 mm on the plane z = 0 with a round hole of radius 2 about (5, 5), and a
/// second face whose loop names an edge that is not in the file.
pub(crate) const PLATE: &str = "ISO-10303-21;
HEADER;
FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));
ENDSEC;
DATA;
#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#12=CARTESIAN_POINT('',(10.,0.,0.));
#13=CARTESIAN_POINT('',(10.,10.,0.));
#14=CARTESIAN_POINT('',(0.,10.,0.));
#21=VERTEX_POINT('',#1);
#22=VERTEX_POINT('',#12);
#23=VERTEX_POINT('',#13);
#24=VERTEX_POINT('',#14);
#30=DIRECTION('',(1.,0.,0.));
#31=VECTOR('',#30,1.);
#32=LINE('',#1,#31);
#33=DIRECTION('',(0.,1.,0.));
#34=VECTOR('',#33,1.);
#35=LINE('',#12,#34);
#36=LINE('',#14,#31);
#37=LINE('',#1,#34);
#41=EDGE_CURVE('',#21,#22,#32,.T.);
#42=EDGE_CURVE('',#22,#23,#35,.T.);
#43=EDGE_CURVE('',#24,#23,#36,.T.);
#44=EDGE_CURVE('',#21,#24,#37,.T.);
#51=ORIENTED_EDGE('',*,*,#41,.T.);
#52=ORIENTED_EDGE('',*,*,#42,.T.);
#53=ORIENTED_EDGE('',*,*,#43,.F.);
#54=ORIENTED_EDGE('',*,*,#44,.F.);
#55=EDGE_LOOP('',(#51,#52,#53,#54));
#56=FACE_OUTER_BOUND('',#55,.T.);
#60=CARTESIAN_POINT('',(5.,5.,0.));
#61=AXIS2_PLACEMENT_3D('',#60,#2,#3);
#62=CIRCLE('',#61,2.);
#63=CARTESIAN_POINT('',(7.,5.,0.));
#64=VERTEX_POINT('',#63);
#65=EDGE_CURVE('',#64,#64,#62,.T.);
#66=ORIENTED_EDGE('',*,*,#65,.F.);
#67=EDGE_LOOP('',(#66));
#68=FACE_BOUND('',#67,.T.);
#70=ADVANCED_FACE('plate',(#56,#68),#5,.T.);
#80=EDGE_LOOP('',(#51,#999));
#81=FACE_OUTER_BOUND('',#80,.T.);
#82=ADVANCED_FACE('broken',(#81),#5,.T.);
ENDSEC;
END-ISO-10303-21;
";

#[test]
fn convert_faces_writes_face_objects_the_library_reads() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &[], "plate.step", "faces.jsonl")
        .success()
        .stderr(
            contains("read 1 face(s), 1 with pcurves")
                .and(contains("ADVANCED_FACE"))
                .and(contains("#999 of a loop is not defined"))
                .and(contains("(first #82)")),
        );
    let text = fs::read_to_string(p(&d, "faces.jsonl")).unwrap();
    assert_eq!(text.lines().count(), 1);
    let v: Value = serde_json::from_str(text.trim()).unwrap();
    assert_eq!(
        (v["type"].as_str(), v["id"].as_u64(), v["name"].as_str()),
        (Some("face"), Some(70), Some("plate"))
    );
    assert_eq!(v["outer"].as_array().unwrap().len(), 4);
    assert_eq!(v["inner"][0].as_array().unwrap().len(), 1);
    assert_eq!(v["inner"][0][0]["edge_id"].as_u64(), Some(65));
    assert_eq!(
        v["inner"][0][0]["pcurve"]["control"][0]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    let f = lekalo_io::read_face(text.trim(), "faces.jsonl").unwrap();
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(1.0, 1.0) && !region.contains(5.0, 5.0));
    // the default output is unchanged: curves and surfaces
    lekalo()
        .arg("convert")
        .arg(p(&d, "plate.step"))
        .arg("-o")
        .arg(p(&d, "shapes.jsonl"))
        .assert()
        .success();
    let shapes = fs::read_to_string(p(&d, "shapes.jsonl")).unwrap();
    assert!(!shapes.contains("\"face\"") && shapes.contains("bspline_surface"));
}

#[test]
fn info_faces_lists_loops_and_pcurves() {
    let d = dir_with(&[("plate.step", PLATE)]);
    lekalo()
        .args(["info", "--faces"])
        .arg(p(&d, "plate.step"))
        .assert()
        .success()
        .stdout(
            contains("faces           1 (1 with pcurves), 1 skipped")
                .and(contains(
                    "#70 \"plate\"  bspline_surface #5  edges: outer 4, inner 1  pcurves",
                ))
                .and(contains(
                    "skipped #82 ADVANCED_FACE: edge #999 of a loop is not defined",
                )),
        );
    let out = lekalo()
        .args(["info", "--faces", "--json", "-q"])
        .arg(p(&d, "plate.step"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        v["faces"][0]["loops"][0]["edge_ids"],
        serde_json::json!([41, 42, 43, 44])
    );
    assert_eq!(v["faces"][0]["pcurves"], Value::Bool(true));
    assert_eq!(v["skipped"][0]["id"].as_u64(), Some(82));
}

/// A file of 500 faces that cannot be read (two reasons): `info --faces` lists the first 20 and
/// counts the rest by reason (it listed every one); `--all-skipped` lists them all; the JSON
/// has the same listing, the total and the kinds.
#[test]
fn info_faces_bounds_the_skipped_faces_it_lists() {
    let mut step = String::from("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n");
    for i in 1..=500 {
        let surface = if i % 2 == 1 { 999_999 } else { 999_998 };
        step += &format!("#{i}=ADVANCED_FACE('f{i}',(),#{surface},.T.);\n");
    }
    step += "#999998=PARABOLA('',#999997,1.);\nENDSEC;\nEND-ISO-10303-21;\n";
    let d = dir_with(&[("many.step", step.as_str())]);
    let out = lekalo()
        .args(["info", "--faces", "-q"])
        .arg(p(&d, "many.step"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.matches("\nskipped #").count(), 20, "{text}");
    assert!(text.contains("skipped #20 ADVANCED_FACE") && !text.contains("skipped #21 "));
    assert!(
        text.contains("skipped faces by reason (20 listed of 500; --all-skipped lists every one):")
            && text
                .contains("     250 ADVANCED_FACE: its surface #999999 is not defined (first #1)")
            && text.contains("     250 ADVANCED_FACE: its surface #999998 was not read: not read"),
        "{text}"
    );
    let all = lekalo()
        .args(["info", "--faces", "--all-skipped", "-q"])
        .arg(p(&d, "many.step"))
        .output()
        .unwrap();
    let all = String::from_utf8(all.stdout).unwrap();
    assert_eq!(all.matches("\nskipped #").count(), 500);
    assert!(!all.contains("by reason"), "{all}");
    let out = lekalo()
        .args(["info", "--faces", "--json", "-q"])
        .arg(p(&d, "many.step"))
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["skipped_total"], 500);
    assert_eq!(v["skipped"].as_array().map(Vec::len), Some(20));
    assert_eq!(v["skipped_kinds"][0]["count"], 250);
    assert_eq!(v["skipped_kinds"].as_array().map(Vec::len), Some(2));
    // the option belongs to --faces
    lekalo()
        .args(["info", "--all-skipped"])
        .arg(p(&d, "many.step"))
        .assert()
        .code(2)
        .stderr(contains("--faces"));
}

#[test]
fn faces_refuse_what_they_cannot_write_or_read() {
    let d = dir_with(&[
        ("plate.step", PLATE),
        (
            "c.json",
            r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1]]}"#,
        ),
    ]);
    convert_faces(&d, &[], "plate.step", "faces.csv")
        .code(2)
        .stderr(contains(
            "faces are written as jsonl (one face a line), step or iges",
        ));
    lekalo()
        .args(["info", "--faces"])
        .arg(p(&d, "c.json"))
        .assert()
        .code(2)
        .stderr(contains("--faces reads the faces of a STEP file"));
    // the size limit holds for faces too
    convert_faces(&d, &["--max-size", "20"], "plate.step", "faces.jsonl")
        .code(2)
        .stderr(contains("--max-size"));
}

/// A 10 × 10 mm plate (128, D1) trimmed by a 144 (D31) whose outer boundary (142, D23) is a
/// composite curve (102) of four lines in space and four in `(u, v)`, and whose hole (142, D29)
/// is the square `[3, 7]²` as one 126 in space and one in `(u, v)`; a second 144 (D33) names a
/// surface D99 that is not in the file. Written by `plate` in
/// crates/lekalo-io/src/cad/iges/faces_tests.rs.
const PLATE_IGES: &str = "\
lekalo spline export                                                    S      1
1H,,1H;,9Hplate.igs,9Hplate.igs,6Hlekalo,5H0.1.0,32,308,15,308,15,      G      1
9Hplate.igs,1.,2,2HMM,1,1.,15H20000101.000000,1.E-10,1.44E2,6Hlekalo,0H,G      2
11,0,15H20000101.000000;                                                G      3
     128       1       0       0       0       0       0       000000000D      1
     128       0       0       2       0                               0D      2
     126       3       0       0       0       0       0       000000000D      3
     126       0       0       2       0                               0D      4
     126       5       0       0       0       0       0       000000000D      5
     126       0       0       2       0                               0D      6
     126       7       0       0       0       0       0       000000000D      7
     126       0       0       2       0                               0D      8
     126       9       0       0       0       0       0       000000000D      9
     126       0       0       2       0                               0D     10
     126      11       0       0       0       0       0       000000000D     11
     126       0       0       2       0                               0D     12
     126      13       0       0       0       0       0       000000000D     13
     126       0       0       2       0                               0D     14
     126      15       0       0       0       0       0       000000000D     15
     126       0       0       2       0                               0D     16
     126      17       0       0       0       0       0       000000000D     17
     126       0       0       2       0                               0D     18
     102      19       0       0       0       0       0       000000000D     19
     102       0       0       1       0                               0D     20
     102      20       0       0       0       0       0       000000000D     21
     102       0       0       1       0                               0D     22
     142      21       0       0       0       0       0       000000000D     23
     142       0       0       1       0                               0D     24
     126      22       0       0       0       0       0       000000000D     25
     126       0       0       2       0                               0D     26
     126      24       0       0       0       0       0       000000000D     27
     126       0       0       3       0                               0D     28
     142      27       0       0       0       0       0       000000000D     29
     142       0       0       1       0                               0D     30
     144      28       0       0       0       0       0       000000000D     31
     144       0       0       1       0                               0D     32
     144      29       0       0       0       0       0       000000000D     33
     144       0       0       1       0                               0D     34
128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,       1P      1
0.,1.E1,0.,0.,0.,1.E1,0.,1.E1,1.E1,0.,0.,1.,0.,1.;                     1P      2
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,0.,0.,0.,1.E1,0.,0.,0.,1.,0.,        3P      3
0.,1.;                                                                 3P      4
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,1.E1,0.,0.,1.E1,1.E1,0.,0.,1.,       5P      5
0.,0.,1.;                                                              5P      6
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,1.E1,1.E1,0.,0.,1.E1,0.,0.,1.,       7P      7
0.,0.,1.;                                                              7P      8
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,0.,1.E1,0.,0.,0.,0.,0.,1.,0.,        9P      9
0.,1.;                                                                 9P     10
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,0.,0.,0.,1.,0.,0.,0.,1.,0.,0.,      11P     11
1.;                                                                   11P     12
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,1.,0.,0.,1.,1.,0.,0.,1.,0.,0.,      13P     13
1.;                                                                   13P     14
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,1.,0.,0.,1.,0.,0.,      15P     15
1.;                                                                   15P     16
126,1,1,1,0,1,0,0.,0.,1.,1.,1.,1.,0.,1.,0.,0.,0.,0.,0.,1.,0.,0.,      17P     17
1.;                                                                   17P     18
102,4,3,5,7,9;                                                        19P     19
102,4,11,13,15,17;                                                    21P     20
142,0,1,21,19,1;                                                      23P     21
126,4,1,1,0,1,0,0.,0.,1.,2.,3.,4.,4.,1.,1.,1.,1.,1.,3.,3.,0.,3.,      25P     22
7.,0.,7.,7.,0.,7.,3.,0.,3.,3.,0.,0.,4.,0.,0.,1.;                      25P     23
126,4,1,1,0,1,0,0.,0.,1.,2.,3.,4.,4.,1.,1.,1.,1.,1.,3.E-1,3.E-1,      27P     24
0.,3.E-1,7.E-1,0.,7.E-1,7.E-1,0.,7.E-1,3.E-1,0.,3.E-1,3.E-1,0.,       27P     25
0.,4.,0.,0.,1.;                                                       27P     26
142,0,1,27,25,1;                                                      29P     27
144,1,1,1,23,29;                                                      31P     28
144,99,1,0,23;                                                        33P     29
S      1G      3D     34P     29                                        T      1
";

#[test]
fn iges_trimmed_surfaces_convert_and_list_as_faces() {
    let d = dir_with(&[("plate.igs", PLATE_IGES)]);
    convert_faces(&d, &[], "plate.igs", "faces.jsonl")
        .success()
        .stderr(
            contains("read 1 face(s), 1 with pcurves")
                .and(contains("IGES entity 144"))
                .and(contains("surface D99 is not an entity"))
                .and(contains("(first D33)")),
        );
    let text = fs::read_to_string(p(&d, "faces.jsonl")).unwrap();
    assert_eq!(text.lines().count(), 1);
    let f = lekalo_io::read_face(text.trim(), "faces.jsonl").unwrap();
    assert_eq!((f.id, f.surface_id), (31, 1));
    assert_eq!(f.edge_ids, vec![vec![3, 5, 7, 9], vec![25]]);
    assert!(f.face.loops().all(lekalo::topology::Loop::has_pcurves));
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(0.1, 0.1) && !region.contains(0.5, 0.5));
    lekalo()
        .args(["info", "--faces"])
        .arg(p(&d, "plate.igs"))
        .assert()
        .success()
        .stdout(
            contains("D31 \"\"  bspline_surface D1  edges: outer 4, inner 1  pcurves")
                .and(contains("skipped D33 IGES entity 144: its surface D99")),
        );
    let out = lekalo()
        .args(["info", "--faces", "--json", "-q"])
        .arg(p(&d, "plate.igs"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (v["faces_total"].as_u64(), v["skipped_total"].as_u64()),
        (Some(1), Some(1))
    );
    assert_eq!(
        v["faces"][0]["loops"][1]["edge_ids"],
        serde_json::json!([25])
    );
    assert_eq!(v["skipped"][0]["id"].as_u64(), Some(33));
}

/// An IGES file of curves and surfaces and no trimmed surface (the plate's geometry written
/// again, each entity independent): its surface is an untrimmed face bounded by its domain,
/// as Open CASCADE reads it.
#[test]
fn iges_surfaces_nothing_trims_convert_as_untrimmed_faces() {
    let d = dir_with(&[("plate.igs", PLATE_IGES)]);
    let run = |args: &[&str]| lekalo().current_dir(d.path()).args(args).assert();
    run(&["convert", "plate.igs", "-o", "loose.igs"]).success();
    let loose = fs::read_to_string(p(&d, "loose.igs")).unwrap();
    assert!(!loose.contains("\n     144"), "no trimmed surface: {loose}");
    run(&["convert", "--faces", "loose.igs", "-o", "faces.jsonl"])
        .success()
        .stderr(contains("read 1 face(s), 1 with pcurves"));
    let text = fs::read_to_string(p(&d, "faces.jsonl")).unwrap();
    assert_eq!(text.lines().count(), 1);
    let f = lekalo_io::read_face(text.trim(), "faces.jsonl").unwrap();
    assert_eq!(f.id, f.surface_id);
    assert_eq!(f.edge_ids, vec![vec![0; 4]]);
    let region = f.face.trim_region().unwrap();
    assert!(region.contains(0.5, 0.5) && region.contains(0.05, 0.95));
}

/// The plate's faces as JSON Lines, then STEP and IGES from them, read back: the same faces.
#[test]
fn face_lines_convert_to_step_and_iges_and_back() {
    let d = dir_with(&[("plate.step", PLATE)]);
    let run = |args: &[&str]| lekalo().current_dir(d.path()).args(args).assert().success();
    run(&["convert", "--faces", "plate.step", "-o", "faces.jsonl"]);
    run(&["convert", "faces.jsonl", "-o", "faces.step"]);
    run(&["convert", "faces.jsonl", "-o", "faces.igs"]);
    let step = fs::read_to_string(p(&d, "faces.step")).unwrap();
    for entity in [
        "ADVANCED_FACE('plate'",
        "FACE_OUTER_BOUND",
        "FACE_BOUND",
        "SURFACE_CURVE",
        "PCURVE",
        "OPEN_SHELL",
        "SHELL_BASED_SURFACE_MODEL",
    ] {
        assert!(step.contains(entity), "{entity}: {step}");
    }
    // --faces of STEP straight to IGES, and the faces read from each file are the same
    run(&["convert", "--faces", "faces.step", "-o", "again.igs"]);
    run(&["convert", "--faces", "faces.step", "-o", "from-step.jsonl"]);
    run(&["convert", "--faces", "faces.igs", "-o", "from-iges.jsonl"]);
    let surfaces_and_loops = |name: &str| -> Vec<(Value, Value, Value)> {
        fs::read_to_string(p(&d, name))
            .unwrap()
            .lines()
            .map(|l| {
                let mut v: Value = serde_json::from_str(l).unwrap();
                let strip = |lp: &mut Value| {
                    for e in lp.as_array_mut().unwrap() {
                        e.as_object_mut().unwrap().remove("edge_id");
                    }
                };
                strip(&mut v["outer"]);
                for lp in v["inner"].as_array_mut().unwrap() {
                    strip(lp);
                }
                (v["surface"].clone(), v["outer"].clone(), v["inner"].clone())
            })
            .collect()
    };
    let original = surfaces_and_loops("faces.jsonl");
    assert_eq!(original.len(), 1);
    assert_eq!(surfaces_and_loops("from-step.jsonl"), original);
    assert_eq!(surfaces_and_loops("from-iges.jsonl"), original);
    // info lists the faces of the JSON Lines file
    lekalo()
        .current_dir(d.path())
        .args(["info", "faces.jsonl"])
        .assert()
        .success()
        .stdout(contains("faces           1 (1 with pcurves), 0 skipped").and(contains("plate")));
    // a line that is not a face is named
    fs::write(
        p(&d, "mixed.jsonl"),
        fs::read_to_string(p(&d, "faces.jsonl")).unwrap()
            + r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1]]}"#,
    )
    .unwrap();
    lekalo()
        .current_dir(d.path())
        .args(["convert", "mixed.jsonl", "-o", "m.step"])
        .assert()
        .code(2)
        .stderr(contains("mixed.jsonl:2").and(contains("face")));
}
