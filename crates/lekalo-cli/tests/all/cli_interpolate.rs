//! End-to-end tests of `lekalo interpolate` (document 000; document 002, four-point cubic and
//! Hermite segment).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use assert_cmd::Command;
use predicates::str::contains;

/// P&T Example 9.1 (docs/theory/interpolation.md#test-vectors).
const Q: &str = lekalo_testkit::vectors::example_9_1::POINTS_TEXT;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

fn json(out: &[u8]) -> serde_json::Value {
    serde_json::from_slice(out).unwrap()
}

fn control(v: &serde_json::Value, i: usize) -> (f64, f64) {
    let p = &v["control"][i];
    (p[0].as_f64().unwrap(), p[1].as_f64().unwrap())
}

fn close(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() < 5e-7 && (a.1 - b.1).abs() < 5e-7
}

#[test]
fn help_has_examples() {
    lekalo()
        .args(["interpolate", "--help"])
        .assert()
        .success()
        .stdout(contains("Examples:"))
        .stdout(contains("--end periodic"));
}

#[test]
fn curves_reproduce_the_test_vectors() {
    let d = tempfile::tempdir().unwrap();
    let q = d.path().join("q.txt");
    fs::write(&q, Q).unwrap();
    let cases: [(&[&str], usize, (f64, f64)); 6] = [
        (&["--param", "chord"], 1, (7.316964, 3.686778)),
        (&["--param", "centripetal"], 1, (6.844809, 3.683071)),
        (&["--param", "uniform"], 2, (-8.0 / 3.0, 7.5)),
        (
            &["--exponent", "1", "--degree", "2"],
            1,
            (5.767270, 4.323172),
        ),
        (
            &[
                "--end",
                "derivatives",
                "--d0",
                "1,2",
                "--dn",
                "-3,-1",
                "--knots",
                "at-params",
            ],
            2,
            (5.671017, 5.171684),
        ),
        (&["--end", "natural"], 1, (1.808397, 1.637040)),
    ];
    for (args, i, want) in cases {
        let out = lekalo()
            .arg("interpolate")
            .arg(&q)
            .args(args)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let got = control(&json(&out), i);
        assert!(close(got, want), "{args:?}: {got:?} vs {want:?}");
    }
    let out = lekalo()
        .arg("interpolate")
        .arg(&q)
        .args(["--end", "second", "--d0", "2,-1", "--dn", "0.5,4"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert!(close(control(&json(&out), 1), (1.792028, 1.645498)));
    lekalo()
        .arg("interpolate")
        .arg(&q)
        .args(["--end", "periodic"])
        .assert()
        .success()
        .stdout(contains("bspline_curve"));
}

#[test]
fn surfaces_functions_hermite_and_formats() {
    let d = tempfile::tempdir().unwrap();
    let q = d.path().join("q.txt");
    fs::write(&q, Q).unwrap();
    let mut grid = String::new();
    for k in 0..4 {
        for l in 0..3 {
            grid.push_str(&format!("{k} {l} {}\n", k * l));
        }
    }
    let g = d.path().join("grid.txt");
    fs::write(&g, grid).unwrap();
    for (name, needle) in [
        ("s.json", "bspline_surface"),
        ("s.svg", "<svg"),
        ("s.step", "B_SPLINE_SURFACE_WITH_KNOTS"),
        ("s.obj", "vn "),
    ] {
        let out = d.path().join(name);
        lekalo()
            .arg("interpolate")
            .arg(&g)
            .args(["--grid", "4x3"])
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        assert!(fs::read_to_string(&out).unwrap().contains(needle), "{name}");
    }
    let xy = d.path().join("xy.csv");
    fs::write(&xy, "x,y\n0,1\n1,3\n2,2\n4,5\n").unwrap();
    lekalo()
        .arg("interpolate")
        .arg(&xy)
        .arg("--function")
        .args(["--to", "csv"])
        .assert()
        .success()
        .stdout(contains("t,x\n0,1\n"));
    lekalo()
        .arg("interpolate")
        .arg(&xy)
        .args(["--function", "--hermite", "monotone", "--to", "svg"])
        .assert()
        .success()
        .stdout(contains("data points"));
    lekalo()
        .arg("interpolate")
        .arg(&q)
        .args(["--hermite", "cardinal", "--tension", "0.5", "--to", "step"])
        .assert()
        .success()
        .stdout(contains("B_SPLINE_CURVE_WITH_KNOTS"));
}

#[test]
fn bad_input_exit_code_2_names_the_problem() {
    let d = tempfile::tempdir().unwrap();
    let q = d.path().join("q.txt");
    fs::write(&q, Q).unwrap();
    let bad = |args: &[&str], msg: &str| {
        lekalo()
            .arg("interpolate")
            .arg(&q)
            .args(args)
            .assert()
            .code(2)
            .stderr(contains(msg.to_string()));
    };
    bad(
        &["--end", "derivatives"],
        "--start-derivative/--end-derivative: the end condition derivatives needs a derivative at the start and at the end",
    );
    bad(
        &["--start-derivative", "1,2"],
        "--start-derivative/--end-derivative: end derivatives are used by the end conditions derivatives and second, not by free",
    );
    bad(
        &[
            "--end",
            "derivatives",
            "--start-derivative",
            "1,x",
            "--end-derivative",
            "0,0",
        ],
        "--start-derivative: value 2",
    );
    // the old spellings still work, with a warning naming the new ones
    bad(
        &["--d0", "1,2"],
        "`--d0` of `lekalo interpolate` is deprecated; write `--start-derivative`",
    );
    bad(&["--degree", "7"], "degree");
    bad(&["--grid", "4by3"], "--grid: \"4by3\" is not a grid size");
    bad(&["--grid", "2x2"], "grid points");
    bad(&["--to", "pdf"], "unknown output format \"pdf\"");
    bad(&["--function"], "x must be strictly increasing: row 3");
    let one = d.path().join("one.txt");
    fs::write(&one, "1\n2\n3\n").unwrap();
    lekalo()
        .arg("interpolate")
        .arg(&one)
        .arg("--function")
        .assert()
        .code(2)
        .stderr(contains("two columns"));
    let dup = d.path().join("dup.txt");
    fs::write(&dup, "0 0\n0 0\n1 1\n").unwrap();
    lekalo()
        .arg("interpolate")
        .arg(&dup)
        .assert()
        .code(2)
        .stderr(contains("error:"));
    lekalo()
        .args(["interpolate", "missing.csv"])
        .assert()
        .code(2)
        .stderr(contains("missing.csv"));
}

#[test]
fn max_condition_refuses_crowded_points_and_passes_the_others() {
    let d = tempfile::tempdir().unwrap();
    // points 4 and 5 lie 1e-12 apart: κ_1 ≈ 3.5e12 with chord-length parameters
    let crowded = d.path().join("crowded.txt");
    let mut rows: Vec<String> = (0..10)
        .map(|k| format!("{} {}", k, f64::from(k).sin()))
        .collect();
    rows.insert(5, format!("{} {}", 4.0 + 1e-12, 4.0_f64.sin()));
    fs::write(&crowded, rows.join("\n")).unwrap();
    let q = d.path().join("q.txt");
    fs::write(&q, Q).unwrap();
    lekalo()
        .args([
            "interpolate",
            crowded.to_str().unwrap(),
            "--max-condition",
            "1e8",
        ])
        .assert()
        .code(2)
        .stderr(contains("condition number"))
        .stderr(contains("max_condition"));
    // without the limit the same data interpolate (the residual stays small)
    lekalo()
        .args(["interpolate", crowded.to_str().unwrap()])
        .assert()
        .success();
    lekalo()
        .args(["interpolate", q.to_str().unwrap(), "--max-condition", "1e8"])
        .assert()
        .success();
    let grid = d.path().join("grid.txt");
    let g: Vec<String> = (0..4)
        .flat_map(|i| (0..4).map(move |j| format!("{i} {j} {}", (i * j) % 3)))
        .collect();
    fs::write(&grid, g.join("\n")).unwrap();
    lekalo()
        .args([
            "interpolate",
            grid.to_str().unwrap(),
            "--grid",
            "4x4",
            "--max-condition",
            "1e8",
        ])
        .assert()
        .success();
    lekalo()
        .args([
            "interpolate",
            q.to_str().unwrap(),
            "--function",
            "--max-condition",
            "1e8",
        ])
        .assert()
        .code(2)
        .stderr(contains("--max-condition applies"));
    lekalo()
        .args(["interpolate", q.to_str().unwrap(), "--max-condition", "0.5"])
        .assert()
        .code(2)
        .stderr(contains("condition limit"));
}

/// A CSV file large enough to be read by all cores (positioned reads of its parts) gives the
/// curve that the same text gives through standard input (read by one thread); a byte that is
/// not UTF-8 far into it is named by its place, as for standard input.
#[test]
fn a_large_file_read_in_parallel_is_read_as_standard_input() {
    let d = tempfile::tempdir().unwrap();
    let mut text = String::from("x,y,z\n");
    let mut i = 0u32;
    while text.len() < (9 << 20) {
        let t = f64::from(i) * 1e-3;
        text.push_str(&format!("{},{},{}\n", t.cos(), t.sin(), t / 10.0));
        i += 1;
    }
    let big = d.path().join("big.csv");
    fs::write(&big, &text).unwrap();
    let from_file = lekalo()
        .args(["interpolate", "--to", "json"])
        .arg(&big)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let from_stdin = lekalo()
        .args(["interpolate", "--to", "json", "-"])
        .write_stdin(text.clone())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert!(
        from_file == from_stdin,
        "the same curve from a file and from stdin"
    );
    assert_eq!(
        json(&from_file)["control"].as_array().unwrap().len(),
        i as usize
    );
    let mut bytes = text.into_bytes();
    let at = bytes.len() - 1000;
    bytes[at] = 0xff;
    let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
    fs::write(&big, &bytes).unwrap();
    let message = |cmd: &mut Command| {
        String::from_utf8_lossy(&cmd.assert().code(2).get_output().stderr).into_owned()
    };
    let file = message(lekalo().arg("interpolate").arg(&big));
    let stdin = message(lekalo().args(["interpolate", "-"]).write_stdin(bytes));
    let want = format!("not UTF-8 text at line {line}, column ");
    let byte = format!("(byte {at})");
    assert!(
        file.contains(&want) && stdin.contains(&want) && file.contains(&byte),
        "{file}\n{stdin}"
    );
}

/// Two points that coincide are named by the lines of the file that hold them (after its
/// header, blank and comment lines), for `interpolate` and for `fit`.
#[test]
fn coinciding_points_are_named_by_their_lines() {
    let d = tempfile::tempdir().unwrap();
    let pts = d.path().join("dup.csv");
    fs::write(&pts, "x,y\n0,0\n# a comment\n1,1\n\n1,1\n3,9\n").unwrap();
    for args in [&["interpolate"][..], &["fit", "--tolerance", "0.1"]] {
        lekalo()
            .args(args)
            .arg(&pts)
            .assert()
            .code(2)
            .stderr(contains("dup.csv lines 4 and 6: points 1 and 2 coincide"));
    }
}

/// A list of the wrong length is named by its option: the library's error carries the
/// argument's key, which the command line writes as its own option, with the counts.
#[test]
fn a_wrong_count_names_its_option() {
    let d = tempfile::tempdir().unwrap();
    let path = |name: &str| d.path().join(name);
    fs::write(path("pts.txt"), "0 0\n1 2\n2 1\n3 3\n4 0\n").unwrap();
    fs::write(path("tan.txt"), "1 0\n1 1\n").unwrap();
    fs::write(path("w.txt"), "1\n2\n").unwrap();
    let cases: [(&[&str], &str); 5] = [
        (
            &["interpolate", "pts.txt", "--params", "0,1,2"],
            "error: --params: parameters (one per point): expected 5, got 3",
        ),
        (
            &[
                "interpolate",
                "pts.txt",
                "--params",
                "0,1,2",
                "--end",
                "derivatives",
                "--start-derivative",
                "1,0",
                "--end-derivative",
                "1,0",
            ],
            "error: --params: parameters (one per point): expected 5, got 3",
        ),
        (
            &["interpolate", "pts.txt", "--tangents", "tan.txt"],
            "error: --tangents: tangents (one per point): expected 5, got 2",
        ),
        (
            &["fit", "pts.txt", "--ctrl", "4", "--weights", "w.txt"],
            "--weights: data weights (one per data point): expected 5, got 2",
        ),
        (
            &["fit", "pts.txt", "--function", "--weights", "w.txt"],
            "--weights: data weights (one per data point): expected 5, got 2",
        ),
    ];
    for (args, want) in cases {
        let out = lekalo().current_dir(d.path()).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

/// `--function` takes x from the first column: `--params` and `--tangents` with it are
/// refused by name, not silently dropped (the curve was that of `--function` alone).
#[test]
fn function_refuses_params_and_tangents() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("xy.csv"), "0,0\n1,2\n2,1\n3,3\n").unwrap();
    fs::write(d.path().join("tan.csv"), "1,0\n1,0\n1,0\n1,0\n").unwrap();
    for (option, value) in [("--params", "0,1,2,3"), ("--tangents", "tan.csv")] {
        let out = lekalo()
            .current_dir(d.path())
            .args(["interpolate", "xy.csv", "--function", option, value])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{option}: {err}");
        assert!(
            err.contains("'--function' cannot be used with") && err.contains(option),
            "{option}: {err}"
        );
    }
}
