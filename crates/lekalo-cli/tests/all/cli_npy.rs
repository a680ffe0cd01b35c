//! End to end: NumPy `.npy` files as points input (`interpolate`) and as samples output
//! (`eval`), and the errors of malformed `.npy` inputs.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use assert_cmd::Command;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// P&T Example 9.1 (docs/theory/interpolation.md#test-vectors), row by row.
const Q: [f64; 10] = lekalo_testkit::vectors::example_9_1::POINTS_FLAT;

/// Q column by column, as a Fortran-order file stores it.
const Q_COLS: [f64; 10] = [0.0, 3.0, -1.0, -4.0, -4.0, 0.0, 4.0, 4.0, 0.0, -3.0];

/// A `.npy` file laid out as `np.save` writes it, with the header dict `dict` and raw `data`.
fn npy(dict: &str, data: &[u8]) -> Vec<u8> {
    let mut header = dict.to_string();
    header.push_str(&" ".repeat((64 - (10 + header.len() + 1) % 64) % 64));
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&u16::try_from(header.len()).unwrap().to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

/// The `(rows, cols)` shape and the data of a little-endian C-order `.npy` file.
fn read_npy(b: &[u8]) -> ((usize, usize), Vec<f64>) {
    assert_eq!(&b[..8], b"\x93NUMPY\x01\x00");
    let len = usize::from(u16::from_le_bytes([b[8], b[9]]));
    let header = std::str::from_utf8(&b[10..10 + len]).unwrap();
    assert!(
        header.contains("'descr': '<f8', 'fortran_order': False"),
        "{header}"
    );
    let shape = header.split("'shape': (").nth(1).unwrap();
    let dims: Vec<usize> = shape[..shape.find(')').unwrap()]
        .split(',')
        .map(|s| s.trim().parse().unwrap())
        .collect();
    let data = b[10 + len..]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    ((dims[0], dims[1]), data)
}

fn le(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn be(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_be_bytes()).collect()
}

fn interpolate(dir: &std::path::Path, input: &str) -> Vec<u8> {
    let out = lekalo()
        .current_dir(dir)
        .args(["interpolate", input, "--degree", "3"])
        .assert()
        .success();
    out.get_output().stdout.clone()
}

#[test]
fn npy_points_interpolate_as_the_csv_does() {
    let d = tempfile::tempdir().unwrap();
    let csv: String = Q
        .chunks(2)
        .map(|p| format!("{},{}\n", p[0], p[1]))
        .collect();
    fs::write(d.path().join("q.csv"), csv).unwrap();
    let files = [
        (
            "c.npy",
            npy(
                "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2), }",
                &le(&Q),
            ),
        ),
        (
            "f.npy",
            npy(
                "{'descr': '<f8', 'fortran_order': True, 'shape': (5, 2), }",
                &le(&Q_COLS),
            ),
        ),
        (
            "b.NPY",
            npy(
                "{'descr': '>f8', 'fortran_order': False, 'shape': (5, 2), }",
                &be(&Q),
            ),
        ),
        (
            "fb.npy",
            npy(
                "{'descr': '>f8', 'fortran_order': True, 'shape': (5, 2), }",
                &be(&Q_COLS),
            ),
        ),
    ];
    let expect = interpolate(d.path(), "q.csv");
    assert!(!expect.is_empty());
    for (name, bytes) in files {
        fs::write(d.path().join(name), bytes).unwrap();
        assert_eq!(
            String::from_utf8(interpolate(d.path(), name)).unwrap(),
            String::from_utf8(expect.clone()).unwrap(),
            "{name}"
        );
    }
}

#[test]
fn eval_writes_npy_samples_matching_the_csv_bit_for_bit() {
    let d = tempfile::tempdir().unwrap();
    fs::write(
        d.path().join("q.npy"),
        npy(
            "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2), }",
            &le(&Q),
        ),
    )
    .unwrap();
    lekalo()
        .current_dir(d.path())
        .args(["interpolate", "q.npy", "-o", "curve.json"])
        .assert()
        .success();
    for extra in [&[][..], &["--derivatives", "1", "--curvature"][..]] {
        let run = |out: &str| {
            lekalo()
                .current_dir(d.path())
                .args(["eval", "curve.json", "--samples", "7", "-o", out])
                .args(extra)
                .assert()
                .success();
        };
        run("s.npy");
        run("s.csv");
        let ((rows, cols), data) = read_npy(&fs::read(d.path().join("s.npy")).unwrap());
        let csv = fs::read_to_string(d.path().join("s.csv")).unwrap();
        let mut lines = csv.lines();
        let header = lines.next().unwrap();
        assert_eq!(cols, header.split(',').count(), "{header}");
        let values: Vec<f64> = lines
            .flat_map(|l| {
                l.split(',')
                    .map(|f| f.parse::<f64>().unwrap())
                    .collect::<Vec<_>>()
            })
            .collect();
        assert_eq!(rows, 7);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&data), bits(&values), "{extra:?}");
    }
    // --format npy to standard output
    let out = lekalo()
        .current_dir(d.path())
        .args(["eval", "curve.json", "--at", "0.5", "--format", "npy"])
        .assert()
        .success();
    let ((rows, cols), _) = read_npy(&out.get_output().stdout);
    assert_eq!((rows, cols), (1, 3));
}

#[test]
fn malformed_npy_inputs_are_named_errors() {
    let d = tempfile::tempdir().unwrap();
    let dict = |descr: &str, shape: &str| {
        format!("{{'descr': {descr}, 'fortran_order': False, 'shape': {shape}, }}")
    };
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "text.npy",
            b"0,0\n1,1\n".to_vec(),
            "text.npy: field `magic`: not a NumPy .npy file",
        ),
        (
            "cut.npy",
            npy(&dict("'<f8'", "(5, 2)"), &le(&Q))[..30].to_vec(),
            "cut.npy: field `header`",
        ),
        (
            "i4.npy",
            npy(&dict("'<i4'", "(5, 2)"), &[0; 40]),
            "i4.npy: field `descr`: dtype '<i4' is not float64",
        ),
        (
            "f4.npy",
            npy(&dict("'<f4'", "(5, 2)"), &[0; 40]),
            "f4.npy: field `descr`: dtype '<f4' is not float64",
        ),
        (
            "obj.npy",
            npy(&dict("'|O'", "(5, 2)"), &[0; 80]),
            "obj.npy: field `descr`: dtype '|O' is not float64",
        ),
        (
            "cube.npy",
            npy(&dict("'<f8'", "(5, 1, 2)"), &le(&Q)),
            "cube.npy: field `shape`: shape (5, 1, 2) is not (n, d)",
        ),
        (
            "short.npy",
            npy(&dict("'<f8'", "(5, 2)"), &le(&Q[..9])),
            "short.npy: field `data`: the header's shape (5, 2) needs 80 bytes",
        ),
        (
            "nan.npy",
            npy(
                &dict("'<f8'", "(5, 2)"),
                &le(&[0.0, 0.0, 3.0, f64::NAN, -1.0, 4.0, -4.0, 0.0, -4.0, -3.0]),
            ),
            "nan.npy: field `[1, 1]`: NaN is not finite",
        ),
    ];
    for (name, bytes, message) in cases {
        fs::write(d.path().join(name), bytes).unwrap();
        lekalo()
            .current_dir(d.path())
            .args(["interpolate", name, "-o", "out.json"])
            .assert()
            .code(2)
            .stderr(contains(message));
        assert!(
            !d.path().join("out.json").exists(),
            "{name}: nothing written"
        );
    }
    lekalo()
        .current_dir(d.path())
        .args(["interpolate", "missing.npy"])
        .assert()
        .code(2)
        .stderr(contains("missing.npy"));
}

#[test]
fn csv_to_curve_to_npz_to_curve_is_exact() {
    let d = tempfile::tempdir().unwrap();
    let csv: String = Q
        .chunks(2)
        .map(|p| format!("{},{}\n", p[0], p[1]))
        .collect();
    fs::write(d.path().join("q.csv"), csv).unwrap();
    let run = |args: &[&str]| {
        lekalo().current_dir(d.path()).args(args).assert().success();
    };
    run(&["interpolate", "q.csv", "-o", "curve.json"]);
    run(&["convert", "curve.json", "-o", "curve.npz"]);
    run(&["convert", "curve.npz", "-o", "back.json"]);
    let read = |f: &str| fs::read_to_string(d.path().join(f)).unwrap();
    assert_eq!(read("back.json"), read("curve.json"));
    // .npy points straight to an .npz curve
    fs::write(
        d.path().join("q.npy"),
        npy(
            "{'descr': '<f8', 'fortran_order': False, 'shape': (5, 2), }",
            &le(&Q),
        ),
    )
    .unwrap();
    run(&["interpolate", "q.npy", "-o", "direct.npz"]);
    assert_eq!(
        fs::read(d.path().join("direct.npz")).unwrap(),
        fs::read(d.path().join("curve.npz")).unwrap()
    );
    // a rational curve keeps its weights
    fs::write(
        d.path().join("arc.json"),
        r#"{"lekalo":1,"type":"nurbs_curve","degree":2,"knots":[0,0,0,1,1,1],"control":[[1,0],[1,1],[0,1]],"weights":[1,0.5,1]}"#,
    )
    .unwrap();
    run(&["convert", "arc.json", "-o", "arc.npz"]);
    run(&["convert", "arc.npz", "-o", "arc-back.json"]);
    let back: serde_json::Value = serde_json::from_str(&read("arc-back.json")).unwrap();
    assert_eq!(back["type"], "nurbs_curve");
    assert_eq!(back["weights"], serde_json::json!([1.0, 0.5, 1.0]));
    // an .npz curve evaluates as its JSON does
    let eval = |f: &str| {
        lekalo()
            .current_dir(d.path())
            .args(["eval", f, "--samples", "9"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone()
    };
    assert_eq!(eval("curve.npz"), eval("curve.json"));
}

#[test]
fn malformed_npz_inputs_are_named_errors() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("text.npz"), "not a zip").unwrap();
    lekalo()
        .current_dir(d.path())
        .args(["convert", "text.npz", "-o", "out.json"])
        .assert()
        .code(2)
        .stderr(contains("text.npz: not a NumPy .npz archive"));
    lekalo()
        .current_dir(d.path())
        .args(["eval", "missing.npz"])
        .assert()
        .code(2)
        .stderr(contains("missing.npz"));
    assert!(!d.path().join("out.json").exists());
}
