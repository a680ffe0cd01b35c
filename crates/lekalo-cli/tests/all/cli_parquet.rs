//! End to end: Parquet batches through `interpolate`, `eval` and `convert`, compared with the
//! single-file path curve by curve, and the errors of bad groups and malformed files.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use crate::common;

use lekalo_io::CurveJson;
use std::fs::{self, File};
use std::path::Path;

use common::{dir_with, lekalo, p};
use lekalo::Points;
use lekalo_io::{GroupKey, Object, ParquetBatchWriter};
use predicates::str::contains;

/// P&T Example 9.1's points (docs/theory/interpolation.md#test-vectors), moved and stretched by
/// `k`.
fn points(k: f64) -> Points {
    let rows: Vec<[f64; 2]> = lekalo_testkit::vectors::example_9_1::POINTS
        .iter()
        .map(|r| [r[0] + k, r[1] * (1.0 + k / 7.0)])
        .collect();
    Points::from_rows(&rows).unwrap()
}

fn curves(path: &Path, key: &str) -> Vec<(GroupKey, Result<Object, String>)> {
    let mut out = Vec::new();
    lekalo_io::read_curve_groups(path, Some(key), |c| {
        out.extend(
            c.into_iter()
                .map(|(k, o)| (k, o.map_err(|e| e.to_string()))),
        );
        Ok(())
    })
    .unwrap();
    out
}

/// Groups 0 to 3 (keyed `scan`) in two row groups, the first holding the first `split` of them,
/// the second starting with group 9, whose two points cannot carry a cubic: an error of that
/// group only. Returns the good groups.
fn scans_with_a_bad_group(path: &std::path::Path, split: usize) -> Vec<(GroupKey, Points)> {
    let mut w = ParquetBatchWriter::new(File::create(path).unwrap());
    let groups: Vec<(GroupKey, Points)> = (0..4)
        .map(|k| {
            (
                GroupKey::Int(k),
                points(f64::from(u8::try_from(k).unwrap())),
            )
        })
        .collect();
    w.write_points("scan", &["x", "y"], &groups[..split])
        .unwrap();
    let mut rest = vec![(
        GroupKey::Int(9),
        Points::from_rows(&[[0.0, 0.0], [1.0, 1.0]]).unwrap(),
    )];
    rest.extend_from_slice(&groups[split..]);
    w.write_points("scan", &["x", "y"], &rest).unwrap();
    w.close(|_| Ok(())).unwrap();
    groups
}

#[test]
fn interpolate_eval_convert_a_batch() {
    let d = dir_with(&[]);
    let input = p(&d, "pts.parquet");
    let groups = scans_with_a_bad_group(&input, 3);
    let out = p(&d, "curves.parquet");
    lekalo()
        .args(["--group-column", "scan", "interpolate"])
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(2)
        .stderr(contains("pts.parquet: group 9:"))
        .stderr(contains("1 of 5 groups failed"));
    let got = curves(&out, "scan");
    assert_eq!(got.len(), 5);
    for (k, pts) in &groups {
        // the same curve as the single-file path, bit for bit
        let csv = p(&d, "one.csv");
        let text: String = pts
            .iter()
            .map(|q| format!("{:?},{:?}\n", q[0], q[1]))
            .collect();
        fs::write(&csv, text).unwrap();
        let one = p(&d, "one.json");
        lekalo()
            .arg("interpolate")
            .arg(&csv)
            .arg("-o")
            .arg(&one)
            .assert()
            .success();
        let expect = Object::from_json_str(&fs::read_to_string(&one).unwrap(), "one").unwrap();
        let (_, c) = got.iter().find(|(g, _)| g == k).unwrap();
        assert_eq!(c.as_ref().unwrap(), &expect, "group {k}");
    }
    let (_, bad) = got.iter().find(|(g, _)| *g == GroupKey::Int(9)).unwrap();
    assert!(
        bad.as_ref().unwrap_err().contains("group 9: no curve"),
        "{bad:?}"
    );

    // curves -> JSON Lines -> Parquet: the same curves
    let jsonl = p(&d, "curves.jsonl");
    lekalo()
        .args(["--group-column", "scan", "convert"])
        .arg(&out)
        .arg("-o")
        .arg(&jsonl)
        .assert()
        .code(2);
    let text = fs::read_to_string(&jsonl).unwrap();
    assert_eq!(text.lines().count(), 5);
    let failed = text.lines().nth(3).unwrap();
    assert!(
        failed.starts_with("{\"error\":") && failed.ends_with("\"scan\":9}"),
        "{text}"
    );
    let good: String = text
        .lines()
        .filter(|l| !l.contains("\"error\""))
        .map(|l| format!("{l}\n"))
        .collect();
    fs::write(&jsonl, good).unwrap();
    let back = p(&d, "back.parquet");
    lekalo()
        .arg("convert")
        .arg(&jsonl)
        .arg("-o")
        .arg(&back)
        .assert()
        .success();
    let again = curves(&back, "line");
    let ok: Vec<&Object> = got.iter().filter_map(|(_, c)| c.as_ref().ok()).collect();
    assert_eq!(again.len(), ok.len());
    for ((k, c), o) in again.iter().zip(&ok) {
        assert_eq!(c.as_ref().unwrap(), *o, "line {k}");
    }

    // samples of every curve
    let samples = p(&d, "samples.parquet");
    lekalo()
        .args(["eval"])
        .arg(&back)
        .args(["--samples", "7", "-o"])
        .arg(&samples)
        .args(["--group-column", "line"])
        .assert()
        .success();
    assert!(fs::metadata(&samples).unwrap().len() > 0);
}

#[test]
fn malformed_inputs_are_named() {
    let d = dir_with(&[("bad.parquet", "not parquet at all")]);
    lekalo()
        .arg("interpolate")
        .arg(p(&d, "bad.parquet"))
        .arg("-o")
        .arg(p(&d, "c.parquet"))
        .assert()
        .code(2)
        .stderr(contains("bad.parquet: not a readable Parquet file"));
    assert!(!p(&d, "c.parquet").exists(), "nothing half-written");
    lekalo()
        .arg("interpolate")
        .arg(p(&d, "bad.parquet"))
        .arg("-o")
        .arg(p(&d, "c.json"))
        .assert()
        .code(2)
        .stderr(contains("give -o FILE.parquet"));
    lekalo()
        .arg("interpolate")
        .arg(p(&d, "bad.parquet"))
        .args(["--function", "-o"])
        .arg(p(&d, "c.parquet"))
        .assert()
        .code(2)
        .stderr(contains("--function"));
}

/// Points of a noisy helix arc, 40 of them, moved by `k`.
fn arc(k: f64) -> Points {
    let rows: Vec<[f64; 3]> = (0..40)
        .map(|i| {
            let t = f64::from(i) * 0.1;
            let noise = 1e-3 * ((f64::from(i) * 7.3).sin());
            [t.cos() + k, t.sin() + noise, t * 0.3]
        })
        .collect();
    Points::from_rows(&rows).unwrap()
}

#[test]
fn fit_a_batch_as_one_file_each() {
    let d = dir_with(&[]);
    let input = p(&d, "arcs.parquet");
    let groups: Vec<(GroupKey, Points)> = ["a", "b", "c"]
        .iter()
        .zip([0.0, 1.0, 2.5])
        .map(|(k, s)| (GroupKey::Str((*k).to_string()), arc(s)))
        .collect();
    let mut w = ParquetBatchWriter::new(File::create(&input).unwrap());
    w.write_points("group", &["x", "y", "z"], &groups).unwrap();
    // two points: too few for 8 control points, an error of that group only
    w.write_points(
        "group",
        &["x", "y", "z"],
        &[(
            GroupKey::Str("short".into()),
            Points::from_rows(&[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]).unwrap(),
        )],
    )
    .unwrap();
    w.close(|_| Ok(())).unwrap();
    for mode in [
        &["--ctrl", "8"][..],
        &["--smooth", "1e-4"],
        &["--tolerance", "0.01"],
    ] {
        let out = p(&d, "fitted.parquet");
        lekalo()
            .arg("fit")
            .arg(&input)
            .args(mode)
            .arg("-o")
            .arg(&out)
            .arg("--force")
            .assert()
            .code(2)
            .stderr(contains("arcs.parquet: group \"short\":"))
            .stderr(contains("1 of 4 groups failed"));
        let got = curves(&out, "group");
        assert_eq!(got.len(), 4, "{mode:?}");
        for (k, pts) in &groups {
            let csv = p(&d, "one.csv");
            let text: String = pts
                .iter()
                .map(|q| format!("{:?},{:?},{:?}\n", q[0], q[1], q[2]))
                .collect();
            fs::write(&csv, text).unwrap();
            let one = p(&d, "one.json");
            lekalo()
                .args(["--quiet", "fit"])
                .arg(&csv)
                .args(mode)
                .arg("-o")
                .arg(&one)
                .arg("--force")
                .assert()
                .success();
            let expect = Object::from_json_str(&fs::read_to_string(&one).unwrap(), "one").unwrap();
            let (_, c) = got.iter().find(|(g, _)| g == k).unwrap();
            assert_eq!(c.as_ref().unwrap(), &expect, "group {k} {mode:?}");
        }
    }
    // options for one points file are refused
    lekalo()
        .arg("fit")
        .arg(&input)
        .args(["--json", "-o"])
        .arg(p(&d, "x.parquet"))
        .assert()
        .code(2)
        .stderr(contains("a Parquet batch is fitted by open curves"));
}

/// `interpolate --samples N` of a batch: in one pass, the file that `interpolate` and then
/// `eval --samples N` write, byte for byte (so every sample bit for bit); a bad group is
/// reported with its key and the others are written.
#[test]
fn interpolate_and_sample_in_one_pass() {
    let d = dir_with(&[]);
    let input = p(&d, "pts.parquet");
    let groups = scans_with_a_bad_group(&input, 2);
    let curves = p(&d, "curves.parquet");
    lekalo()
        .args(["--group-column", "scan", "interpolate"])
        .arg(&input)
        .arg("-o")
        .arg(&curves)
        .assert()
        .code(2);
    let two = p(&d, "two.parquet");
    lekalo()
        .args(["--group-column", "scan", "eval"])
        .arg(&curves)
        .args(["--samples", "9", "-o"])
        .arg(&two)
        .assert()
        .code(2);
    let one = p(&d, "one.parquet");
    lekalo()
        .args(["--group-column", "scan", "interpolate"])
        .arg(&input)
        .args(["--samples", "9", "-o"])
        .arg(&one)
        .assert()
        .code(2)
        .stderr(contains("pts.parquet: group 9:"))
        .stderr(contains("1 of 5 groups failed"));
    let bytes = fs::read(&one).unwrap();
    assert!(bytes.len() > 4 * 9 * 3 * 8, "the samples of 4 curves");
    assert!(
        bytes == fs::read(&two).unwrap(),
        "the same file as interpolate, then eval"
    );

    // the same file whatever the row groups of the input: one group a row group
    let split = p(&d, "split.parquet");
    let mut w = ParquetBatchWriter::new(File::create(&split).unwrap());
    for g in &groups {
        w.write_points("scan", &["x", "y"], std::slice::from_ref(g))
            .unwrap();
    }
    w.close(|_| Ok(())).unwrap();
    lekalo()
        .args(["--group-column", "scan", "interpolate"])
        .arg(&split)
        .args(["--samples", "9", "-o"])
        .arg(&one)
        .arg("--force")
        .assert()
        .success();
    lekalo()
        .args(["--group-column", "scan", "eval"])
        .arg(&curves)
        .args(["--samples", "9", "-o"])
        .arg(&two)
        .arg("--force")
        .assert()
        .code(2);
    assert!(
        fs::read(&one).unwrap() == fs::read(&two).unwrap(),
        "the good groups' samples"
    );

    // samples are written as Parquet, and only for a batch
    lekalo()
        .arg("interpolate")
        .arg(&input)
        .args(["--samples", "9", "-o"])
        .arg(p(&d, "s.csv"))
        .assert()
        .code(2)
        .stderr(contains("give -o FILE.parquet"));
    let csv = p(&d, "one.csv");
    fs::write(&csv, "0,0\n1,1\n2,0\n3,1\n").unwrap();
    lekalo()
        .arg("interpolate")
        .arg(&csv)
        .args(["--samples", "9"])
        .assert()
        .code(2)
        .stderr(contains("--samples samples the curves of a Parquet batch"));
}

/// A CSV of point sets with a key column converts to a batch that reads back as the same point
/// sets (bit for bit, in order, with the CSV's keys), and each curve interpolated from the batch
/// is the curve of its group's own file. A CSV without the key column is refused naming it
/// and `--group-column`.
#[test]
fn a_csv_with_a_key_column_converts_to_a_batch() {
    let mut csv = String::from("scan,x,y\n");
    let mut one = String::new();
    for k in [3, 1] {
        for r in points(f64::from(k)).iter() {
            csv.push_str(&format!("{k},{},{}\n", r[0], r[1]));
            if k == 1 {
                one.push_str(&format!("{},{}\n", r[0], r[1]));
            }
        }
    }
    let d = dir_with(&[("scans.csv", &csv), ("one.csv", &one)]);
    lekalo()
        .current_dir(d.path())
        .args([
            "--group-column",
            "scan",
            "convert",
            "scans.csv",
            "-o",
            "scans.parquet",
        ])
        .assert()
        .success();
    let mut groups = Vec::new();
    lekalo_io::read_point_groups(&p(&d, "scans.parquet"), Some("scan"), |g| {
        groups.extend(g);
        Ok(())
    })
    .unwrap();
    let groups: Vec<(GroupKey, Points)> =
        groups.into_iter().map(|(k, g)| (k, g.unwrap())).collect();
    assert_eq!(
        groups,
        vec![
            (GroupKey::Int(3), points(3.0)),
            (GroupKey::Int(1), points(1.0))
        ]
    );
    lekalo()
        .current_dir(d.path())
        .args([
            "--group-column",
            "scan",
            "interpolate",
            "scans.parquet",
            "-o",
            "curves.parquet",
        ])
        .assert()
        .success();
    lekalo()
        .current_dir(d.path())
        .args(["interpolate", "one.csv", "-o", "one.json"])
        .assert()
        .success();
    let single =
        Object::from_json_str(&fs::read_to_string(p(&d, "one.json")).unwrap(), "one").unwrap();
    let batch = curves(&p(&d, "curves.parquet"), "scan");
    assert_eq!(batch[1].0, GroupKey::Int(1));
    assert_eq!(batch[1].1.as_ref().unwrap(), &single);
    // the key column is named by --group-column; without it the message says so
    lekalo()
        .current_dir(d.path())
        .args(["convert", "scans.csv", "-o", "again.parquet"])
        .assert()
        .code(2)
        .stderr(contains(
            "scans.csv:1: the header `scan,x,y` has no key column `group`; name the column \
             that groups the points `group`, or give its name with --group-column NAME",
        ));
    assert!(!p(&d, "again.parquet").exists());
}
