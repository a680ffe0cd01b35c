//! Splines in three or more parameters: `interpolate --grid AxBxC`, `eval`, `info`,
//! `convert`, and their errors (exit code 2, naming the option or field).

use std::fs;
use std::path::Path;

use predicates::str::contains;

use super::lekalo;

/// `f(x, y, z) = x·y + z²` on the uniform grid of `[0, 1]³` with `shape` nodes, one value a
/// row, the first direction slowest.
fn values(shape: [u32; 3]) -> String {
    let mut s = String::new();
    let at = |k: u32, n: u32| f64::from(k) / f64::from(n - 1);
    for i in 0..shape[0] {
        for j in 0..shape[1] {
            for k in 0..shape[2] {
                let (x, y, z) = (at(i, shape[0]), at(j, shape[1]), at(k, shape[2]));
                s.push_str(&format!("{:?}\n", x * y + z * z));
            }
        }
    }
    s
}

fn interpolated(dir: &Path) -> std::path::PathBuf {
    let v = dir.join("values.txt");
    fs::write(&v, values([5, 4, 3])).unwrap();
    let t = dir.join("tensor.json");
    lekalo()
        .args(["interpolate"])
        .arg(&v)
        .args([
            "--grid", "5x4x3", "--degree", "3,3,2", "--param", "uniform", "-o",
        ])
        .arg(&t)
        .assert()
        .success();
    t
}

#[test]
fn a_grid_of_values_interpolates_evaluates_and_reports() {
    let d = tempfile::tempdir().unwrap();
    let t = interpolated(d.path());
    let text = fs::read_to_string(&t).unwrap();
    assert!(text.contains("\"type\": \"bspline_tensor\""), "{text}");
    assert!(text.contains("\"shape\": [5,4,3]"), "{text}");
    // the spline space holds the polynomial: it is reproduced everywhere
    let out = lekalo()
        .arg("eval")
        .arg(&t)
        .args(["--at", "0.3,0.7,0.45,1,1,1", "--json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let j: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(j["columns"], serde_json::json!(["x1", "x2", "x3", "y"]));
    let y0 = j["rows"][0][3].as_f64().unwrap();
    assert!((y0 - (0.3 * 0.7 + 0.45 * 0.45)).abs() < 1e-12, "{y0}");
    assert!((j["rows"][1][3].as_f64().unwrap() - 2.0).abs() < 1e-12);
    // a file of points, CSV out
    let p = d.path().join("points.csv");
    fs::write(&p, "0,0,0\n0.5,0.5,0.5\n").unwrap();
    lekalo()
        .arg("eval")
        .arg(&t)
        .arg("--at-file")
        .arg(&p)
        .assert()
        .success()
        .stdout(contains("x1,x2,x3,y\n0,0,0,"))
        .stdout(contains("0.5,0.5,0.5,0.5"));
    lekalo()
        .arg("info")
        .arg(&t)
        .assert()
        .success()
        .stdout(contains("parameters      3"))
        .stdout(contains("degrees         3 × 3 × 2"))
        .stdout(contains("net             5 × 4 × 3 = 60 control points"))
        // numbers as the other objects' info writes them, not JSON's 0.0
        .stdout(contains(
            "type            B-spline in 3 variables (bspline_tensor)",
        ))
        .stdout(contains("domain          [0, 1] × [0, 1] × [0, 1]"));
    let copy = d.path().join("copy.json");
    lekalo()
        .arg("convert")
        .arg(&t)
        .arg("-o")
        .arg(&copy)
        .assert()
        .success();
    assert_eq!(fs::read_to_string(&copy).unwrap(), text);
    lekalo()
        .arg("convert")
        .arg(&t)
        .args(["--to", "step"])
        .assert()
        .code(2)
        .stderr(contains("converts to json or npz"));
}

/// A float64 `.npy` file of `shape` holding `data` (C order).
pub(super) fn npy(shape: &[usize], data: &[f64]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(ToString::to_string).collect();
    let mut header = format!(
        "{{'descr': '<f8', 'fortran_order': False, 'shape': ({},), }}",
        dims.join(", ")
    );
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend(u16::try_from(header.len()).unwrap().to_le_bytes());
    out.extend(header.as_bytes());
    for v in data {
        out.extend(v.to_le_bytes());
    }
    out
}

#[test]
fn a_npy_grid_is_read_with_its_shape_or_as_rows() {
    let d = tempfile::tempdir().unwrap();
    let t = interpolated(d.path());
    let expected = fs::read_to_string(&t).unwrap();
    let data: Vec<f64> = values([5, 4, 3])
        .lines()
        .map(|l| l.parse().unwrap())
        .collect();
    for shape in [vec![5, 4, 3], vec![60], vec![60, 1], vec![5, 4, 3, 1]] {
        let f = d.path().join("values.npy");
        fs::write(&f, npy(&shape, &data)).unwrap();
        let out = lekalo()
            .arg("interpolate")
            .arg(&f)
            .args(["--grid", "5x4x3", "--degree", "3,3,2", "--param", "uniform"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        assert_eq!(String::from_utf8(out).unwrap(), expected, "{shape:?}");
    }
    let f = d.path().join("values.npy");
    fs::write(&f, npy(&[3, 4, 5], &data)).unwrap();
    lekalo()
        .arg("interpolate")
        .arg(&f)
        .args(["--grid", "5x4x3"])
        .assert()
        .code(2)
        .stderr(contains("neither the grid's"));
}

#[test]
fn two_sizes_keep_the_surface_and_a_degree_list_is_u_then_v() {
    let d = tempfile::tempdir().unwrap();
    let pts = d.path().join("grid.csv");
    let mut s = String::new();
    for i in 0..4 {
        for j in 0..3 {
            s.push_str(&format!("{i},{j},{}\n", i * j + j * j));
        }
    }
    fs::write(&pts, s).unwrap();
    let run = |args: &[&str]| {
        lekalo()
            .arg("interpolate")
            .arg(&pts)
            .args(["--grid", "4x3"])
            .args(args)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone()
    };
    let a = run(&["--degree", "3", "--degree-v", "2"]);
    assert_eq!(a, run(&["--degree", "3,2"]));
    assert!(String::from_utf8_lossy(&a).contains("\"bspline_surface\""));
}

#[test]
fn bad_grids_exit_2_naming_the_option() {
    let d = tempfile::tempdir().unwrap();
    let v = d.path().join("values.txt");
    fs::write(&v, values([5, 4, 3])).unwrap();
    let fails = |args: &[&str], needle: &str| {
        lekalo()
            .arg("interpolate")
            .arg(&v)
            .args(args)
            .assert()
            .code(2)
            .stderr(contains(needle));
    };
    fails(&["--grid", "5x4x4"], "--grid 5x4x4: 80 grid nodes");
    fails(&["--grid", "5x4x3", "--degree", "3,3,3"], "--degree");
    fails(
        &["--grid", "5x4x3", "--degree", "3,3"],
        "--degree: 2 degrees",
    );
    fails(&["--grid", "5x0x3"], "--grid");
    fails(&["--grid", "100000x100000x100000"], "--grid");
    fails(&["--grid", "99999999999x99999999999x9999999"], "overflows");
    fails(&["--degree", "3,2"], "--degree: 2 degrees given");
    let nan = d.path().join("nan.txt");
    fs::write(&nan, "1\nnan\n1\n1\n").unwrap();
    lekalo()
        .arg("interpolate")
        .arg(&nan)
        .args(["--grid", "1x2x2"])
        .assert()
        .code(2)
        .stderr(contains("not finite"));
}

/// `eval` of `t` with `args` exits 2 with `needle` on stderr.
fn eval_refused(t: &Path, args: &[&str], needle: &str) {
    lekalo()
        .arg("eval")
        .arg(t)
        .args(args)
        .assert()
        .code(2)
        .stderr(contains(needle));
}

#[test]
fn bad_points_and_files_exit_2() {
    let d = tempfile::tempdir().unwrap();
    let t = interpolated(d.path());
    let eval = |args: &[&str], needle: &str| eval_refused(&t, args, needle);
    eval(&["--at", "0.5,0.5"], "--at: 2 values");
    eval(&["--at", "0.5,0.5,2"], "tensor.json");
    eval(&[], "--at-file");
    eval(
        &["--at", "0.5,0.5,0.5", "--derivatives", "1"],
        "--derivatives",
    );
    let text = fs::read_to_string(&t).unwrap();
    let bad = d.path().join("bad.json");
    fs::write(
        &bad,
        text.replace("\"shape\": [5,4,3]", "\"shape\": [5,4,4]"),
    )
    .unwrap();
    lekalo()
        .arg("info")
        .arg(&bad)
        .assert()
        .code(2)
        .stderr(contains("field `shape`"));
}

#[test]
fn a_nurbs_tensor_evaluates_with_its_weights() {
    let d = tempfile::tempdir().unwrap();
    let t = d.path().join("n.json");
    // the trilinear net x + 2y + 4z, weight 3 at the corner (1, 1, 1)
    fs::write(
        &t,
        r#"{"lekalo": 1, "type": "nurbs_tensor", "degrees": [1, 1, 1],
        "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]], "shape": [2, 2, 2],
        "control": [[0], [4], [2], [6], [1], [5], [3], [7]],
        "weights": [1, 1, 1, 1, 1, 1, 1, 3]}"#,
    )
    .unwrap();
    // at a corner: the control point; at the centre: Σ w P / Σ w = (28 + 14) / 10
    lekalo()
        .arg("eval")
        .arg(&t)
        .args(["--at", "1,1,1,0.5,0.5,0.5"])
        .assert()
        .success()
        .stdout(contains("1,1,1,7\n0.5,0.5,0.5,4.2\n"));
    lekalo()
        .arg("info")
        .arg(&t)
        .assert()
        .success()
        .stdout(contains(
            "type            NURBS in 3 variables (nurbs_tensor)",
        ))
        .stdout(contains("control box     [0] .. [7]"));
}

/// `eval --at` of `file` on a few points of `[0, 1]³`, as CSV text.
fn eval_at(file: &Path) -> String {
    eval_csv(file, &["--at", "0.3,0.7,0.45,1,1,1,0,0.25,0.5"])
}

#[test]
fn a_tensor_converts_to_npz_and_back_and_the_npz_is_read_by_eval_and_info() {
    let d = tempfile::tempdir().unwrap();
    let b = interpolated(d.path());
    let n = d.path().join("n.json");
    fs::write(
        &n,
        r#"{"lekalo": 1, "type": "nurbs_tensor", "degrees": [1, 1, 1],
        "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]], "shape": [2, 2, 2],
        "control": [[0, 1], [4, 1], [2, 1], [6, 1], [1, 1], [5, 1], [3, 1], [7, 1]],
        "weights": [1, 1, 1, 1, 1, 1, 1, 3]}"#,
    )
    .unwrap();
    for (json, kind) in [(&b, "bspline_tensor"), (&n, "nurbs_tensor")] {
        let npz = json.with_extension("npz");
        lekalo()
            .arg("convert")
            .arg(json)
            .arg("-o")
            .arg(&npz)
            .assert()
            .success();
        assert_eq!(&fs::read(&npz).unwrap()[..2], b"PK", "a zip archive");
        let back = d.path().join(format!("{kind}-back.json"));
        lekalo()
            .arg("convert")
            .arg(&npz)
            .arg("-o")
            .arg(&back)
            .assert()
            .success();
        // the JSON of the JSON: the same text as the archive's JSON
        let again = d.path().join(format!("{kind}-again.json"));
        lekalo()
            .arg("convert")
            .arg(json)
            .arg("-o")
            .arg(&again)
            .assert()
            .success();
        assert_eq!(
            fs::read_to_string(&back).unwrap(),
            fs::read_to_string(&again).unwrap(),
            "{kind}"
        );
        assert_eq!(eval_at(&npz), eval_at(json), "{kind}");
        lekalo()
            .arg("info")
            .arg(&npz)
            .assert()
            .success()
            .stdout(contains(format!("in 3 variables ({kind})")));
    }
    // a damaged archive (knots_1 renamed in the local and central headers): exit 2 naming
    // the missing member
    let bad = d.path().join("bad.npz");
    let mut bytes = fs::read(b.with_extension("npz")).unwrap();
    let mut renamed = 0;
    while let Some(at) = bytes.windows(9).position(|w| w == b"knots_1.n") {
        bytes[at..at + 7].copy_from_slice(b"knots_9");
        renamed += 1;
    }
    assert_eq!(renamed, 2);
    fs::write(&bad, bytes).unwrap();
    lekalo()
        .arg("eval")
        .arg(&bad)
        .args(["--at", "0.5,0.5,0.5"])
        .assert()
        .code(2)
        .stderr(contains("knots_1"));
}

#[test]
fn interpolate_and_make_write_npz_when_the_output_asks_for_it() {
    let d = tempfile::tempdir().unwrap();
    let json = interpolated(d.path());
    // interpolate --grid: the same spline as its JSON, written straight as an archive
    let npz = d.path().join("direct.npz");
    lekalo()
        .arg("interpolate")
        .arg(d.path().join("values.txt"))
        .args([
            "--grid", "5x4x3", "--degree", "3,3,2", "--param", "uniform", "-o",
        ])
        .arg(&npz)
        .assert()
        .success();
    assert_eq!(&fs::read(&npz).unwrap()[..2], b"PK", "a zip archive");
    assert_eq!(eval_at(&npz), eval_at(&json));
    // make bspline-tensor: the net of that spline's values as control points, both ways
    let (mj, mz) = (d.path().join("made.json"), d.path().join("made.npz"));
    for out in [&mj, &mz] {
        lekalo()
            .args(["make", "bspline-tensor", "--control"])
            .arg(d.path().join("values.txt"))
            .args(["--net", "5x4x3", "--degree", "2,2,1", "-o"])
            .arg(out)
            .assert()
            .success();
    }
    assert_eq!(&fs::read(&mz).unwrap()[..2], b"PK", "a zip archive");
    assert_eq!(eval_at(&mz), eval_at(&mj));
    // any other format is refused before the spline is computed, naming both
    lekalo()
        .arg("interpolate")
        .arg(d.path().join("values.txt"))
        .args(["--grid", "5x4x3", "-o"])
        .arg(d.path().join("t.csv"))
        .assert()
        .code(2)
        .stderr(contains("written as json or npz, not \"csv\""));
    assert!(!d.path().join("t.csv").exists());
}

/// The CSV that `eval` writes for `args`.
fn eval_csv(t: &Path, args: &[&str]) -> String {
    let out = lekalo()
        .arg("eval")
        .arg(t)
        .args(args)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    String::from_utf8(out).unwrap()
}

/// A grid's values as a Parquet table (one row a node, the first direction slowest) give the
/// spline of the same values as text, byte for byte; `eval --grid` gives, row for row, the
/// values of `eval --at-file` at the grid's points, as CSV or a Parquet table that reads back
/// to the same numbers.
#[test]
fn parquet_tables_in_and_out_and_eval_on_a_grid() {
    let d = tempfile::tempdir().unwrap();
    let t = interpolated(d.path());
    let expected = fs::read_to_string(&t).unwrap();
    let data: Vec<f64> = values([5, 4, 3])
        .lines()
        .map(|l| l.parse().unwrap())
        .collect();
    let pq = d.path().join("values.parquet");
    fs::write(
        &pq,
        lekalo_io::table_to_parquet(&["f".into()], &data).unwrap(),
    )
    .unwrap();
    let out = lekalo()
        .arg("interpolate")
        .arg(&pq)
        .args(["--grid", "5x4x3", "--degree", "3,3,2", "--param", "uniform"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert_eq!(String::from_utf8(out).unwrap(), expected);

    // the grid 3 × 2 × 4 of [0, 1]³, first direction slowest, as a points file
    let axis = |m: u32| -> Vec<f64> { (0..m).map(|k| f64::from(k) / f64::from(m - 1)).collect() };
    let mut points = String::new();
    for x in axis(3) {
        for y in axis(2) {
            for z in axis(4) {
                points.push_str(&format!("{x:?},{y:?},{z:?}\n"));
            }
        }
    }
    let at = d.path().join("at.csv");
    fs::write(&at, &points).unwrap();
    let on_grid = eval_csv(&t, &["--grid", "3x2x4"]);
    assert_eq!(on_grid, eval_csv(&t, &["--at-file", at.to_str().unwrap()]));
    assert_eq!(on_grid.lines().count(), 1 + 24);
    // --at first, then the grid
    let both = eval_csv(&t, &["--at", "0.5,0.5,0.5", "--grid", "3x2x4"]);
    let first = eval_csv(&t, &["--at", "0.5,0.5,0.5"]);
    assert_eq!(
        both,
        format!("{}{}", first, on_grid.split_once('\n').unwrap().1)
    );

    // the same points as a Parquet table in, the samples as a Parquet table out
    let flat: Vec<f64> = points
        .lines()
        .flat_map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()))
        .collect();
    let at_pq = d.path().join("at.parquet");
    let names = ["u".to_string(), "v".to_string(), "w".to_string()];
    fs::write(&at_pq, lekalo_io::table_to_parquet(&names, &flat).unwrap()).unwrap();
    assert_eq!(
        eval_csv(&t, &["--at-file", at_pq.to_str().unwrap()]),
        on_grid
    );
    let samples = d.path().join("samples.parquet");
    lekalo()
        .arg("eval")
        .arg(&t)
        .args(["--grid", "3x2x4", "-o"])
        .arg(&samples)
        .assert()
        .success();
    // read back: columns x1, x2, x3, y, the numbers of the CSV
    let (back, columns, _) = lekalo_io::read_parquet_points(&samples, 1000).unwrap();
    assert_eq!(columns, ["x1", "x2", "x3", "y"]);
    let csv: Vec<f64> = on_grid
        .lines()
        .skip(1)
        .flat_map(|l| {
            l.split(',')
                .map(|v| v.parse::<f64>().unwrap())
                .collect::<Vec<_>>()
        })
        .collect();
    assert_eq!(back.as_slice(), csv.as_slice());
}

/// Parquet tables and `--grid` that cannot be used exit 2 naming the file, the column, the row
/// or the option.
#[test]
fn bad_parquet_tables_and_grids_exit_2() {
    let d = tempfile::tempdir().unwrap();
    let t = interpolated(d.path());
    let eval = |args: &[&str], needle: &str| eval_refused(&t, args, needle);
    eval(
        &["--grid", "3x3"],
        "--grid 3x3: 2 sizes for a spline in 3 parameters",
    );
    eval(&["--grid", "3x0x3"], "--grid");
    eval(
        &["--grid", "1000x1000x1000"],
        "--grid 1000x1000x1000: 1000000000 points, above the size limit",
    );
    eval(
        &["--grid", "2x2x2", "--format", "xlsx"],
        "use csv, json, npy or parquet",
    );
    // two columns for three parameters
    let two = d.path().join("two.parquet");
    let names = ["a".to_string(), "b".to_string()];
    fs::write(
        &two,
        lekalo_io::table_to_parquet(&names, &[0.5; 6]).unwrap(),
    )
    .unwrap();
    eval(
        &["--at-file", two.to_str().unwrap()],
        "--at-file needs 3 columns, one per parameter; found 2",
    );
    // more rows than --max-size
    lekalo()
        .args(["--max-size", "2", "eval"])
        .arg(&t)
        .arg("--at-file")
        .arg(&two)
        .assert()
        .code(2)
        .stderr(contains("3 rows, above the limit of 2 points"))
        .stderr(contains("--max-size 3"));
    // a string column (a batch's key) is not a coordinate
    let keyed = d.path().join("keyed.parquet");
    let mut w = lekalo_io::ParquetBatchWriter::new(fs::File::create(&keyed).unwrap());
    let pts = lekalo::Points::from_flat(3, vec![0.5; 6]).unwrap();
    w.write_points(
        "name",
        &["x", "y", "z"],
        &[(lekalo_io::GroupKey::Str("a".into()), pts)],
    )
    .unwrap();
    w.close(|_| Ok(())).unwrap();
    eval(&["--at-file", keyed.to_str().unwrap()], "field `name`");
    // a grid table of the wrong number of rows
    lekalo()
        .arg("interpolate")
        .arg(&two)
        .args(["--grid", "2x2x2"])
        .assert()
        .code(2)
        .stderr(contains("8 grid nodes"));
}
