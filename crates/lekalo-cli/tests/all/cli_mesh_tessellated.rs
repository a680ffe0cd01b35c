//! End-to-end tests of the faces of triangles of AP242 files (`TRIANGULATED_FACE`,
//! `COMPLEX_TRIANGULATED_FACE`): meshed to OBJ as given, counted by `info --faces`, and named
//! by `convert --faces`, which writes faces bounded by curves only.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use predicates::str::contains;

use crate::cli_faces::PLATE;
use crate::common;
use common::{dir_with, last_stderr_json, lekalo, p};

/// An AP242 file in inches: a `TRIANGULATED_FACE` of two triangles over the square
/// [0, 1]² at z = 0, and a `COMPLEX_TRIANGULATED_FACE` over [1, 2] × [0, 1] whose four points
/// are named through `pnindex`, with a strip of 4 points and a fan of 4 points (two triangles
/// each, the fan's over the strip's square again); every triangle turns about +z.
const TRIANGLES: &str = "ISO-10303-21;
HEADER;
FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF'));
ENDSEC;
DATA;
#90=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );
#91=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#90);
#92=( CONVERSION_BASED_UNIT('INCH',#91) LENGTH_UNIT() NAMED_UNIT(*) );
#93=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#92)) REPRESENTATION_CONTEXT('',''));
#1=COORDINATES_LIST('',4,((0.,0.,0.),(1.,0.,0.),(1.,1.,0.),(0.,1.,0.)));
#2=TRIANGULATED_FACE('square',#1,4,((0.,0.,1.)),$,(),((1,2,3),(1,3,4)));
#3=COORDINATES_LIST('',6,((9.,9.,9.),(1.,0.,0.),(2.,0.,0.),(1.,1.,0.),(2.,1.,0.),(9.,9.,9.)));
#4=COMPLEX_TRIANGULATED_FACE('',#3,4,(),$,(2,3,4,5),((1,2,3,4)),((2,4,3,1)));
#5=TESSELLATED_SHELL('',(#2,#4),$);
ENDSEC;
END-ISO-10303-21;
";

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

/// The z of `(b − a) × (c − a)` of each triangle.
fn turns(v: &[[f64; 3]], f: &[[usize; 3]]) -> Vec<f64> {
    f.iter()
        .map(|&[a, b, c]| {
            let (a, b, c) = (v[a], v[b], v[c]);
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        })
        .collect()
}

#[test]
fn mesh_writes_the_triangles_as_given_in_millimetres() {
    let d = dir_with(&[("tri.stp", TRIANGLES)]);
    let done = lekalo()
        .args(["mesh", "--tolerance", "1e-3", "--json"])
        .arg(p(&d, "tri.stp"))
        .arg("-o")
        .arg(p(&d, "tri.obj"))
        .assert()
        .success();
    let summary = last_stderr_json(&done);
    assert_eq!(summary["faces"], 0);
    assert_eq!(summary["tessellated"], 2);
    assert_eq!(summary["tessellated_triangles"], 6);
    assert_eq!(summary["deviation"], 0.0);
    let (v, f) = read_obj(&fs::read_to_string(p(&d, "tri.obj")).unwrap());
    // 4 points of the square, 4 of the face through pnindex (not the 6 of its list)
    assert_eq!((v.len(), f.len()), (8, 6));
    let xmax = v.iter().map(|q| q[0]).fold(f64::MIN, f64::max);
    assert_eq!(xmax, 2.0 * 25.4, "inches to millimetres");
    assert!(
        v.iter().all(|q| q[0] >= 0.0 && q[1] <= 25.4),
        "pnindex skips (9, 9, 9)"
    );
    let z = turns(&v, &f);
    assert!(
        z.iter().all(|&z| z > 0.0),
        "every triangle turns about +z: {z:?}"
    );
    // the square, the strip's square and the fan's square again: 3 in²
    let area: f64 = z.iter().map(|z| z / 2.0).sum();
    assert!((area - 3.0 * 25.4 * 25.4).abs() < 1e-9, "{area}");
}

#[test]
fn mesh_joins_faces_of_triangles_to_the_faces_it_meshes() {
    // the plate with a hole (millimetres) and one face of triangles beside it
    let file = PLATE.replacen(
        "ENDSEC;\nEND-ISO-10303-21;",
        "#900=COORDINATES_LIST('',3,((20.,0.,0.),(21.,0.,0.),(20.,1.,0.)));
#901=TRIANGULATED_FACE('',#900,3,(),$,(),((1,2,3)));
ENDSEC;\nEND-ISO-10303-21;",
        1,
    );
    assert_ne!(file, PLATE);
    let d = dir_with(&[("plate.stp", &file), ("alone.stp", PLATE)]);
    let mesh = |name: &str| {
        let done = lekalo()
            .args(["mesh", "--tolerance", "1e-2", "--json"])
            .arg(p(&d, name))
            .arg("-o")
            .arg(p(&d, "m.obj"))
            .assert()
            .success();
        let (v, f) = read_obj(&fs::read_to_string(p(&d, "m.obj")).unwrap());
        (last_stderr_json(&done), v, f)
    };
    let (alone, va, fa) = mesh("alone.stp");
    let (with, v, f) = mesh("plate.stp");
    assert_eq!(
        (with["faces"].clone(), with["tessellated"].clone()),
        (1.into(), 1.into())
    );
    assert_eq!(alone["tessellated"], 0);
    assert_eq!((v.len(), f.len()), (va.len() + 3, fa.len() + 1));
    assert_eq!(
        v[va.len()..],
        [[20.0, 0.0, 0.0], [21.0, 0.0, 0.0], [20.0, 1.0, 0.0]]
    );
    assert_eq!(f.last(), Some(&[va.len(), va.len() + 1, va.len() + 2]));
}

#[test]
fn info_counts_faces_of_triangles_and_skips_none() {
    let d = dir_with(&[("tri.stp", TRIANGLES)]);
    let out = lekalo()
        .args(["info", "--faces", "--json"])
        .arg(p(&d, "tri.stp"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["faces_total"], 0);
    assert_eq!(j["tessellated_total"], 2);
    assert_eq!(j["tessellated_triangles"], 6);
    assert_eq!(j["skipped_total"], 0);
    let t = &j["tessellated"][1];
    assert_eq!(t["id"], 4);
    assert_eq!(t["entity"], "COMPLEX_TRIANGULATED_FACE");
    assert_eq!(
        (t["vertices"].clone(), t["triangles"].clone()),
        (4.into(), 4.into())
    );
    lekalo()
        .args(["info", "--faces"])
        .arg(p(&d, "tri.stp"))
        .assert()
        .success()
        .stdout(contains(
            "0 (0 with pcurves), 2 tessellated (6 triangles), 0 skipped",
        ))
        .stdout(contains(
            "#2 \"square\"  TRIANGULATED_FACE  4 points, 2 triangles, 1 normals",
        ));
}

#[test]
fn convert_faces_names_the_faces_of_triangles_it_does_not_write() {
    let d = dir_with(&[("tri.stp", TRIANGLES)]);
    lekalo()
        .args(["convert", "--faces"])
        .arg(p(&d, "tri.stp"))
        .arg("-o")
        .arg(p(&d, "f.jsonl"))
        .assert()
        .success()
        .stderr(contains(
            "read 0 face(s), 0 with pcurves, and 2 face(s) of triangles (6 triangles: tessellated, written by `lekalo mesh`)",
        ));
    assert_eq!(fs::read_to_string(p(&d, "f.jsonl")).unwrap(), "");
    lekalo()
        .args(["convert", "--faces"])
        .arg(p(&d, "tri.stp"))
        .arg("-o")
        .arg(p(&d, "f.step"))
        .assert()
        .code(2)
        .stderr(contains(
            "no faces to write; its 2 face(s) of triangles are written by `lekalo mesh",
        ));
}

#[test]
fn a_file_whose_only_faces_of_triangles_are_malformed_says_why() {
    // the triangle points at a fifth point of a list of four
    let bad = TRIANGLES
        .replace("((1,2,3),(1,3,4))", "((1,2,5))")
        .replace("(#2,#4)", "(#2)");
    let bad = bad
        .lines()
        .filter(|l| !l.starts_with("#3=") && !l.starts_with("#4="))
        .collect::<Vec<_>>()
        .join("\n");
    let d = dir_with(&[("bad.stp", bad.as_str())]);
    lekalo()
        .args(["mesh", "--tolerance", "1e-3"])
        .arg(p(&d, "bad.stp"))
        .arg("-o")
        .arg(p(&d, "bad.obj"))
        .assert()
        .code(2)
        .stderr(contains("#2"))
        .stderr(contains("no face to mesh"));
    assert!(!d.path().join("bad.obj").exists());
}
