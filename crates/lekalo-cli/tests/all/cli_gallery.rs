//! End-to-end test: `lekalo demo --out DIR` writes the gallery with a section for every
//! document's constructions, and the summary table lists them with all checks passing; a
//! redraw of one entry (`--only ID`) keeps the others.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use assert_cmd::Command;
use predicates::str::contains;

#[test]
fn demo_gallery_has_every_documents_section() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("gallery");
    let run = Command::cargo_bin("lekalo")
        .unwrap()
        .args(["demo", "--out"])
        .arg(&out)
        .assert()
        .success()
        .stdout(contains("0.204831"))
        .stdout(contains("(10, 0); (30, 10); (0, 20); (20, 0)"));
    let summary = String::from_utf8(run.get_output().stdout.clone()).unwrap();
    assert!(!summary.contains("[FAIL]"), "{summary}");
    // the captions' redraw command, `demo --only ID --out DIR`, keeps the other entries
    let before = fs::read_to_string(out.join("index.html")).unwrap();
    Command::cargo_bin("lekalo")
        .unwrap()
        .args(["demo", "--only", "doc000-ends", "--out"])
        .arg(&out)
        .assert()
        .success();
    let index = fs::read_to_string(out.join("index.html")).unwrap();
    assert_eq!(index, before, "a redraw of one entry rewrote the gallery");
    for id in [
        "doc000-curves",
        "doc000-ends",
        "doc000-surface",
        "doc001-jump",
        "doc001-deformation",
        "doc001-spline",
        "doc001-corner",
        "doc002-hermite",
        "doc003-quasi",
        "doc004-elevation",
        "doc004-reduction",
        "doc004-surface",
    ] {
        assert!(
            index.contains(&format!("<section id=\"{id}\">")),
            "no section {id}"
        );
        assert!(summary.contains(&format!("[{id}]")), "no summary for {id}");
        let svg = fs::read_to_string(out.join(format!("{id}-1.svg"))).unwrap();
        assert!(svg.starts_with("<svg") || svg.contains("<svg"), "{id}");
    }
}
