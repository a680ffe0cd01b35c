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
fn mesh_of_faces_refuses_a_tolerance_too_small() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &["-q"], "plate.step", "faces.jsonl").success();
    lekalo()
        .args(["mesh", "--tolerance", "0"])
        .arg(p(&d, "faces.jsonl"))
        .assert()
        .failure()
        .stderr(predicates::str::contains("--tolerance 0"));
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

#[test]
fn mesh_of_faces_lists_the_faces_without_pcurves_and_meshes_the_others() {
    let d = dir_with(&[("plate.step", PLATE)]);
    convert_faces(&d, &["-q"], "plate.step", "faces.jsonl").success();
    let line = fs::read_to_string(p(&d, "faces.jsonl")).unwrap();
    let mut bare: Value = serde_json::from_str(line.trim()).unwrap();
    without_pcurves(&mut bare);
    fs::write(p(&d, "bare.jsonl"), format!("{bare}\n")).unwrap();
    fs::write(p(&d, "both.jsonl"), format!("{}\n{bare}\n", line.trim())).unwrap();
    let out = lekalo()
        .args(["mesh", "--tolerance", "1e-3", "--json"])
        .arg(p(&d, "both.jsonl"))
        .arg("-o")
        .arg(p(&d, "plate.obj"))
        .assert()
        .success()
        .stderr(predicates::str::contains("1 of 2 faces not meshed"));
    let summary = last_stderr_json(&out);
    assert_eq!(summary["faces"].as_u64(), Some(1));
    assert_eq!(summary["skipped"].as_u64(), Some(1));
    lekalo()
        .args(["mesh", "--tolerance", "1e-3"])
        .arg(p(&d, "bare.jsonl"))
        .arg("-o")
        .arg(p(&d, "bare.obj"))
        .assert()
        .code(2)
        .stderr(predicates::str::contains("none of the 1 faces has"));
    assert!(!p(&d, "bare.obj").exists());
}
