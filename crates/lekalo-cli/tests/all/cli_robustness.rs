//! Hostile, huge and interrupted runs of the `lekalo` binary: nothing panics (exit code 101)
//! or aborts (134), nothing is silently dropped or half-written, every refusal names the file,
//! line and field or the option. The limits are listed in docs/robustness.md.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Stdio;

use predicates::prelude::PredicateBooleanExt as _;
use predicates::str::contains;

use crate::common;
use common::{dir_with, lekalo, p};

const LECTURE: &str = r#"{
  "lekalo": 1,
  "type": "bspline_curve",
  "degree": 2,
  "knots": [0, 0, 1, 2, 3, 3],
  "control": [[1, 1], [2, 3], [4, 3]]
}
"#;

fn bin() -> PathBuf {
    assert_cmd::cargo::cargo_bin("lekalo")
}

/// Files in `dir` other than `keep`: temporary files left behind would show up here.
fn debris(dir: &Path, keep: &[&str]) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !keep.contains(&n.as_str()))
        .collect()
}

/// Runs the binary with `args` under an address-space limit of `kib` KiB (`ulimit -v`), in
/// `dir`; returns (exit code, stderr).
fn run_limited(dir: &Path, kib: u64, args: &[&str]) -> (i32, String) {
    let mut script = format!("ulimit -v {kib}; exec '{}'", bin().display());
    for a in args {
        let _ = write!(script, " '{a}'");
    }
    let out = std::process::Command::new("bash")
        .arg("-c")
        .arg(&script)
        .current_dir(dir)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A B-spline curve of degree 1 through `n` points of a spiral, as JSON.
fn big_polyline(n: usize) -> String {
    let mut s = String::from(r#"{"lekalo":1,"type":"bspline_curve","degree":1,"knots":[0"#);
    for i in 0..n {
        let _ = write!(s, ",{i}");
    }
    let _ = write!(s, ",{}],\"control\":[", n - 1);
    for i in 0..n {
        let t = i as f64 / n as f64 * 20.0;
        let _ = write!(
            s,
            "{}[{},{}]",
            if i > 0 { "," } else { "" },
            t.cos() * (1.0 + t),
            t.sin() * (1.0 + t)
        );
    }
    s.push_str("]}\n");
    s
}

/// A Bezier curve with `n` control points.
fn bezier(n: usize) -> String {
    let rows: Vec<String> = (0..n)
        .map(|i| format!("[{},{}]", i, (i % 7) as f64 * 0.5))
        .collect();
    format!(
        r#"{{"lekalo":1,"type":"bezier_curve","control":[{}]}}"#,
        rows.join(",")
    )
}

const SURFACE: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 1, "degree_v": 1,
 "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1], "net": [2, 2],
 "control": [[0, 0, 0], [0, 1, 0], [1, 0, 1], [1, 1, 1]]}"#;

/// z = x² + y² on [0, 1]² (a paraboloid: curved in both directions).
const BOWL: &str = r#"{"lekalo": 1, "type": "bspline_surface", "degree_u": 2, "degree_v": 2,
 "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1], "net": [3, 3],
 "control": [[0, 0, 0], [0, 0.5, 0], [0, 1, 1], [0.5, 0, 0], [0.5, 0.5, 0], [0.5, 1, 1],
             [1, 0, 1], [1, 0.5, 1], [1, 1, 2]]}"#;

#[test]
fn no_option_writes_over_a_file_the_command_reads() {
    // Each command reads a second file through an option. Only the main input used to be
    // protected: naming the second one as the output replaced it with exit 0.
    let d = dir_with(&[
        ("c.json", LECTURE),
        ("s.json", SURFACE),
        ("uv.csv", "0.5,0.5\n0.25,0.75\n"),
        ("q.csv", "1,2\n3,3\n"),
        ("pts.csv", "0,0\n1,1\n2,0\n3,1\n4,0\n"),
        ("w.json", "[[1], [1], [1], [1], [1]]\n"),
        ("tan.json", "[[1, 0], [1, 0], [1, 0], [1, 0], [1, 0]]\n"),
        ("over.svg", "1,2\n3,3\n"),
        ("len.txt", "0.5\n1\n"),
    ]);
    let cases: [&[&str]; 6] = [
        &["eval", "s.json", "--uv-file", "uv.csv", "-o", "uv.csv"],
        &["project", "c.json", "--points", "q.csv", "-o", "q.csv"],
        &[
            "fit",
            "pts.csv",
            "--weights",
            "w.json",
            "--ctrl",
            "4",
            "-o",
            "w.json",
        ],
        &[
            "interpolate",
            "pts.csv",
            "--tangents",
            "tan.json",
            "-o",
            "tan.json",
        ],
        &["plot", "c.json", "--points", "over.svg", "-o", "over.svg"],
        &["measure", "c.json", "--lengths", "len.txt", "-o", "len.txt"],
    ];
    for args in cases {
        let file = args[args.len() - 1];
        let before = fs::read(p(&d, file)).unwrap();
        let out = lekalo().current_dir(d.path()).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(&format!("refusing to write {file}: it is an input file")),
            "{args:?}: {err}"
        );
        assert_eq!(
            fs::read(p(&d, file)).unwrap(),
            before,
            "{args:?} changed {file}"
        );
        assert_eq!(
            debris(d.path(), &[])
                .iter()
                .filter(|n| n.contains(".tmp"))
                .count(),
            0
        );
        // the same command with another output succeeds, so the refusal is the protection
        let mut other: Vec<String> = args.iter().map(ToString::to_string).collect();
        let ext = Path::new(file)
            .extension()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        *other.last_mut().unwrap() = format!("fresh.{ext}");
        let out = lekalo()
            .current_dir(d.path())
            .args(&other)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{other:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// Exit code and standard error of `lekalo ARGS` run in `dir`.
fn code_and_stderr(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = lekalo().current_dir(dir).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn sizes_set_by_an_option_are_refused_before_allocation_naming_it() {
    let d = dir_with(&[
        ("s.json", BOWL),
        ("c.json", LECTURE),
        ("uvz.csv", "0,0,0\n1,0,1\n0,1,1\n1,1,2\n0.5,0.5,1\n"),
    ]);
    // a 3000 x 3000 net asked for 648 GB and aborted
    let (code, err) = code_and_stderr(
        d.path(),
        &["fit", "uvz.csv", "--scattered", "--ctrl-grid", "3000x3000"],
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--ctrl-grid 3000x3000") && err.contains("--max-size"),
        "{err}"
    );
    // a tolerance of 1e-8 aborted on memory; 1e-300 was printed as a 300-digit decimal
    // 0 was "0e0 is below 1e-12 times the object's size 1e0" with no tolerance to use; each
    // refusal carries the key of the tolerance, so it is written under the option
    for (tol, says) in [
        ("1e-8", "use a tolerance of at least"),
        (
            "1e-300",
            "rounding would decide the bound; use a tolerance of at least",
        ),
        ("0", "0 is below 1e-12 times the object's size"),
    ] {
        let (code, err) = code_and_stderr(d.path(), &["mesh", "s.json", "-t", tol, "-o", "m.obj"]);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains(&format!("error: s.json: --tolerance: {tol} ")) && err.contains(says),
            "{err}"
        );
        assert!(err.len() < 400, "numbers in exponent notation: {err}");
        assert!(!p(&d, "m.obj").exists());
    }
    // a table of samples × columns held in memory
    let (code, err) = code_and_stderr(
        d.path(),
        &[
            "eval",
            "c.json",
            "--samples",
            "3000000",
            "--curvature",
            "-o",
            "e.npy",
        ],
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--samples 3000000: 3000000 samples of 4 columns are 12000000 values"),
        "{err}"
    );
    assert_eq!(
        debris(d.path(), &["s.json", "c.json", "uvz.csv"]),
        Vec::<String>::new()
    );
    // an interval of ±1e308 was reported as "knots[0] is NaN"
    let (code, err) = code_and_stderr(
        d.path(),
        &["knot", "reparam", "c.json", "--interval=-1e308,1e308"],
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--interval -1e308,1e308: "), "{err}");
}

#[test]
fn plots_of_one_dimensional_points_do_not_panic() {
    let d = dir_with(&[("p.txt", "0\n1\n3\n4\n")]);
    for (args, out) in [
        (vec!["interpolate", "p.txt"], "a.svg"),
        (vec!["interpolate", "p.txt"], "a.png"),
        (
            vec!["interpolate", "p.txt", "--hermite", "catmull-rom"],
            "b.svg",
        ),
        (vec!["blend", "spline", "p.txt"], "c.svg"),
        (
            vec!["blend", "spline", "p.txt", "--local", "parabolas"],
            "d.png",
        ),
    ] {
        lekalo()
            .current_dir(d.path())
            .args(&args)
            .args(["-o", out])
            .assert()
            .success();
        assert!(p(&d, out).exists(), "{args:?}");
    }
}

#[test]
fn declared_sizes_are_refused_before_allocation_under_a_memory_limit() {
    let d = dir_with(&[("t.json", LECTURE)]);
    let cases: [(&[&str], &str); 4] = [
        (
            &[
                "pp",
                "quasi",
                "--function",
                "sin",
                "--breakpoints",
                "0,1",
                "--intervals",
                "1000000000000",
            ],
            "--intervals 1000000000000 is above the size limit 10000000; raise the limit with --max-size",
        ),
        (
            &["knots", "uniform", "--degree", "3", "--count", "1000000000"],
            "--count 1000000000 is above the size limit",
        ),
        (
            &["eval", "t.json", "--at", "1.5", "-d", "100000000"],
            "--derivatives 100000000 is above 1000",
        ),
        (
            &["convert", "t.json", "--samples", "1000000000", "-o", "x.csv"],
            "--samples 1000000000 is above the size limit",
        ),
    ];
    for (args, msg) in cases {
        let (code, err) = run_limited(d.path(), 1_500_000, args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(msg), "{args:?}: {err}");
    }
    // raising --max-size past what the machine allows is an error too, not an abort
    let (code, err) = run_limited(
        d.path(),
        1_500_000,
        &[
            "--max-size",
            "100000000000",
            "knots",
            "uniform",
            "--degree",
            "3",
            "--count",
            "50000000000",
        ],
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--count: cannot reserve memory"), "{err}");
    assert_eq!(debris(d.path(), &["t.json"]), Vec::<String>::new());
}

#[test]
fn high_degree_bezier_work_is_limited_under_a_memory_limit() {
    let d = dir_with(&[
        ("big.json", &bezier(1_000_000)),
        ("mid.json", &bezier(20_000)),
    ]);
    for op in ["real-degree", "reduce"] {
        let (code, err) = run_limited(d.path(), 2_000_000, &["bezier", op, "big.json"]);
        assert_eq!(code, 2, "{op}: {err}");
        assert!(
            err.contains("degree 999999 is above the degree limit 2000")
                && err.contains("--max-degree"),
            "{op}: {err}"
        );
    }
    for args in [
        &["info", "mid.json"][..],
        &["plot", "mid.json", "-o", "m.svg"],
    ] {
        let (code, err) = run_limited(d.path(), 2_000_000, args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains("degree 19999") && err.contains("--max-degree"),
            "{err}"
        );
    }
    fs::write(p(&d, "b600.json"), bezier(601)).unwrap();
    lekalo()
        .current_dir(d.path())
        .args(["bezier", "reduce", "b600.json", "--approx", "3"])
        .assert()
        .code(2)
        .stderr(contains(
            "approximate reduction of degree 600 is above its limit 500",
        ))
        .stderr(contains("--max-degree 2400"));
}

#[test]
fn a_missing_input_or_a_folder_is_named_with_the_fix_not_an_os_error_number() {
    let d = dir_with(&[("c.json", LECTURE)]);
    fs::create_dir(d.path().join("data")).unwrap();
    for (args, reason) in [
        (
            &["fit", "scna.csv", "--ctrl", "8"][..],
            "cannot read scna.csv: no such file; check the name and the folder",
        ),
        (
            &["eval", "cuve.json", "--at", "1.5"][..],
            "make the file first",
        ),
        (&["info", "data"][..], "cannot read data: it is a folder"),
    ] {
        let (code, err) = code_and_stderr(d.path(), args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(reason), "{args:?}: {err}");
        assert!(!err.contains("os error"), "{args:?}: {err}");
    }
}

#[test]
fn a_first_line_with_a_number_is_data_not_a_header() {
    let d = dir_with(&[
        ("h.csv", "0,0a\n1,1\n2,0\n3,1\n4,4\n"),
        ("named.csv", "x,y\n0,0\n1,1\n2,0\n3,1\n"),
    ]);
    lekalo()
        .current_dir(d.path())
        .args(["interpolate", "h.csv"])
        .assert()
        .code(2)
        .stderr(contains(
            "h.csv:1: field `2`: cannot read \"0a\" as a number",
        ));
    // the user can say the first line is a header
    let out = lekalo()
        .current_dir(d.path())
        .args(["--header", "yes", "make", "bezier", "--control", "h.csv"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(text.matches("],").count() + 1, 4, "{text}");
    lekalo()
        .current_dir(d.path())
        .args(["--header", "no", "make", "bezier", "--control", "named.csv"])
        .assert()
        .code(2)
        .stderr(contains("named.csv:1: field `1`"));
    let out = lekalo()
        .current_dir(d.path())
        .args(["make", "bezier", "--control", "named.csv"])
        .output()
        .unwrap();
    assert!(out.status.success());
}

#[test]
fn byte_order_marks_are_stripped_from_every_text_input() {
    let bom = "\u{feff}";
    let line = LECTURE.replace('\n', " ");
    let d = dir_with(&[
        ("p.csv", &format!("{bom}0,0\n1,1\n2,0\n3,1\n4,4\n")),
        ("p.txt", &format!("{bom}0 0\n1 1\n2 0\n")),
        ("p.json", &format!("{bom}[[0,0],[1,1],[2,0]]")),
        ("t.json", &format!("{bom}{LECTURE}")),
        ("m.jsonl", &format!("{bom}{line}\n{line}\n")),
    ]);
    let out = lekalo()
        .current_dir(d.path())
        .args(["make", "bezier", "--control", "p.csv"])
        .output()
        .unwrap();
    assert!(out.status.success());
    // all five points, the first one too
    assert!(String::from_utf8_lossy(&out.stdout).contains("[0.0, 0.0],"));
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).matches("],").count(),
        4
    );
    for f in ["p.txt", "p.json"] {
        lekalo()
            .current_dir(d.path())
            .args(["make", "bezier", "--control", f])
            .assert()
            .success()
            .stdout(contains("[0.0, 0.0]"));
    }
    lekalo()
        .current_dir(d.path())
        .args(["info", "t.json"])
        .assert()
        .success();
    lekalo()
        .current_dir(d.path())
        .args(["eval", "m.jsonl", "--at", "1.5"])
        .assert()
        .success()
        .stdout(contains("\"line\":2"));
}

#[test]
fn duplicate_json_keys_are_refused() {
    let d = dir_with(&[
        (
            "dup.json",
            "{\"lekalo\":1,\"type\":\"bspline_curve\",\n\"degree\":2,\n\"degree\":1,\"knots\":[0,0,1,2,3,3],\"control\":[[1,1],[2,3],[4,3]]}",
        ),
        ("dupp.json", r#"{"dim": 2, "data": [1, 2], "dim": 1}"#),
        (
            "dupt.json",
            r#"{"lekalo":1,"type":"bezier_curve","type":"bspline_curve","control":[[0,0],[1,1]]}"#,
        ),
    ]);
    lekalo()
        .current_dir(d.path())
        .args(["info", "dup.json"])
        .assert()
        .code(2)
        .stderr(contains("dup.json:3: field `degree`"))
        .stderr(contains("duplicate field `degree`"));
    lekalo()
        .current_dir(d.path())
        .args(["info", "dupt.json"])
        .assert()
        .code(2)
        .stderr(contains("duplicate field `type`"));
    lekalo()
        .current_dir(d.path())
        .args(["make", "bezier", "--control", "dupp.json"])
        .assert()
        .code(2)
        .stderr(contains("dupp.json:1"))
        .stderr(contains("duplicate key `dim`"));
}

#[test]
fn non_finite_view_angles_are_refused() {
    let d = dir_with(&[("t.json", LECTURE)]);
    for (opt, val) in [
        ("--azimuth", "nan"),
        ("--elevation", "inf"),
        ("--azimuth", "-inf"),
    ] {
        lekalo()
            .current_dir(d.path())
            .args(["plot", "t.json", "-o", "a.svg", opt, val])
            .assert()
            .code(2)
            .stderr(contains(format!("{opt} ")))
            .stderr(contains("finite"));
    }
    assert_eq!(debris(d.path(), &["t.json"]), Vec::<String>::new());
}

#[test]
fn extreme_coordinates_plot_with_finite_ticks() {
    let curve = |a: &str, b: &str| {
        format!(r#"{{"lekalo":1,"type":"bezier_curve","control":[[{a},{a}],[{b},{a}],[{b},{b}]]}}"#)
    };
    let d = dir_with(&[
        ("huge.json", &curve("-1.7e308", "1.7e308")),
        ("big.json", &curve("1e300", "5e300")),
        ("tiny.json", &curve("1e-320", "5e-320")),
    ]);
    for f in ["huge.json", "big.json", "tiny.json"] {
        lekalo()
            .current_dir(d.path())
            .args(["plot", f, "-o", "x.svg"])
            .assert()
            .success();
        let svg = fs::read_to_string(p(&d, "x.svg")).unwrap();
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{f}: {svg}");
        // the curve is drawn, not an empty frame
        assert!(svg.contains("<polyline points=\""), "{f}");
        // the x axis' tick labels: centred text elements whose body starts with a number
        let labels: Vec<&str> = svg
            .split("<text ")
            .skip(1)
            .filter_map(|s| s.split_once('>'))
            .filter(|(attrs, _)| attrs.contains("text-anchor=\"middle\""))
            .filter_map(|(_, body)| body.split('<').next())
            .filter(|s| {
                s.chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_digit() || c == '-')
            })
            .collect();
        assert!(labels.len() >= 2, "{f}: {labels:?}");
        assert!(
            labels.iter().any(|l| *l != "0"),
            "{f}: every tick reads 0: {labels:?}"
        );
        let mut distinct = labels.clone();
        distinct.dedup();
        assert_eq!(distinct.len(), labels.len(), "{f}: {labels:?}");
    }
}

#[test]
fn ignored_options_are_refused_naming_both() {
    let d = dir_with(&[
        ("pts.txt", "0 0\n1 2\n2 3\n3 1\n4 0\n5 2\n"),
        ("t.json", LECTURE),
    ]);
    let cases: [(&[&str], &[&str]); 6] = [
        (&["--grid", "2x3", "--end", "second"], &["--grid", "--end"]),
        (
            &["--grid", "2x3", "--hermite", "cardinal"],
            &["--grid", "--hermite"],
        ),
        (&["--tension", "0.5"], &["--tension", "--hermite"]),
        (
            &["--hermite", "catmull-rom", "--tension", "0.5"],
            &["--tension", "--hermite cardinal"],
        ),
        (
            &["--hermite", "monotone", "--end", "natural"],
            &["--hermite", "--end"],
        ),
        (
            &["--function", "--knots", "uniform"],
            &["--function", "--knots"],
        ),
    ];
    for (extra, names) in cases {
        let a = lekalo()
            .current_dir(d.path())
            .arg("interpolate")
            .arg("pts.txt")
            .args(extra)
            .assert()
            .code(2);
        let err = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
        for n in names {
            assert!(err.contains(n), "{extra:?}: {err}");
        }
    }
    for args in [
        &["convert", "t.json", "-o", "x.csv", "--samples", "0"][..],
        &["convert", "t.json", "-o", "x.svg", "--samples", "1"],
        &["plot", "t.json", "-o", "x.svg", "--samples", "0"],
        &["plot", "t.json", "-o", "x.svg", "--samples", "1000000000"],
        &["eval", "t.json", "--samples", "0"],
        &["info", "t.json", "--samples", "0"],
    ] {
        lekalo()
            .current_dir(d.path())
            .args(args)
            .assert()
            .code(2)
            .stderr(contains("--samples"));
    }
}

#[cfg(unix)]
#[test]
fn write_protected_outputs_need_force_and_keep_their_mode() {
    use std::os::unix::fs::PermissionsExt;
    let d = dir_with(&[
        ("t.json", LECTURE),
        ("out.csv", "old\n"),
        ("open.csv", "old\n"),
    ]);
    fs::set_permissions(p(&d, "out.csv"), fs::Permissions::from_mode(0o444)).unwrap();
    fs::set_permissions(p(&d, "open.csv"), fs::Permissions::from_mode(0o640)).unwrap();
    lekalo()
        .current_dir(d.path())
        .args(["eval", "t.json", "-o", "out.csv"])
        .assert()
        .code(2)
        .stderr(contains(
            "refusing to replace out.csv: it is write-protected; give --force",
        ));
    assert_eq!(fs::read_to_string(p(&d, "out.csv")).unwrap(), "old\n");
    lekalo()
        .current_dir(d.path())
        .args(["eval", "t.json", "-o", "out.csv", "--force"])
        .assert()
        .success();
    assert!(fs::read_to_string(p(&d, "out.csv"))
        .unwrap()
        .starts_with("t,x,y"));
    let mode = |f: &str| fs::metadata(p(&d, f)).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode("out.csv"), 0o444);
    lekalo()
        .current_dir(d.path())
        .args(["eval", "t.json", "-o", "open.csv"])
        .assert()
        .success();
    assert_eq!(mode("open.csv"), 0o640);
    assert_eq!(
        debris(d.path(), &["t.json", "out.csv", "open.csv"]),
        Vec::<String>::new()
    );
}

#[cfg(unix)]
#[test]
fn created_files_honour_the_umask() {
    use std::os::unix::fs::PermissionsExt;
    let d = dir_with(&[("t.json", LECTURE)]);
    for (umask, want) in [("022", 0o644), ("027", 0o640), ("077", 0o600)] {
        let out = format!("u{umask}.csv");
        let status = std::process::Command::new("bash")
            .arg("-c")
            .arg(format!(
                "umask {umask}; exec '{}' eval t.json -o {out}",
                bin().display()
            ))
            .current_dir(d.path())
            .status()
            .unwrap();
        assert!(status.success());
        let mode = fs::metadata(p(&d, &out)).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, want, "umask {umask}");
    }
}

#[test]
fn json_lines_are_handled_alike_in_every_command() {
    let line = LECTURE.replace('\n', " ");
    let text = format!("{line}\n{{\"lekalo\":1}}\n\n{line}\nnot json\n");
    let d = dir_with(&[("m.jsonl", &text)]);
    for (args, out) in [
        (&["convert", "m.jsonl", "-o", "all.step"][..], "all.step"),
        (&["convert", "m.jsonl", "-o", "all.jsonl"], "all.jsonl"),
        (
            &["eval", "m.jsonl", "--at", "1.5", "-o", "e.jsonl"],
            "e.jsonl",
        ),
        (&["info", "m.jsonl", "-o", "i.jsonl"], "i.jsonl"),
    ] {
        lekalo()
            .current_dir(d.path())
            .args(args)
            .assert()
            .code(2)
            .stderr(contains("m.jsonl:2: field `type`"))
            .stderr(contains("m.jsonl:5: not valid JSON"))
            .stderr(contains("2 of 4 objects failed"));
        let written = fs::read_to_string(p(&d, out)).unwrap();
        assert!(!written.is_empty(), "{args:?}: the good lines are written");
    }
    let all = fs::read_to_string(p(&d, "all.jsonl")).unwrap();
    assert_eq!(all.lines().count(), 2);
    let step = fs::read_to_string(p(&d, "all.step")).unwrap();
    assert_eq!(step.matches("B_SPLINE_CURVE_WITH_KNOTS").count(), 2);
}

/// Starts `lekalo args` in `dir`, waits until its temporary output file appears (it is
/// writing), sends `signal` and returns the exit code, or `None` if the command finished first.
#[cfg(unix)]
fn interrupt_while_writing(dir: &Path, args: &[&str], signal: &str) -> Option<i32> {
    let mut child = std::process::Command::new(bin())
        .args(args)
        .current_dir(dir)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let writing = || {
        fs::read_dir(dir)
            .unwrap()
            .any(|e| e.unwrap().file_name().to_string_lossy().ends_with(".tmp"))
    };
    loop {
        if child.try_wait().unwrap().is_some() {
            return None;
        }
        if writing() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let _ = std::process::Command::new("kill")
        .args([format!("-{signal}"), child.id().to_string()])
        .status();
    let sent = std::time::Instant::now();
    let status = child.wait().unwrap();
    // the handler's grace period is 0.7 s; the bound leaves room for a loaded machine
    assert!(
        sent.elapsed() < std::time::Duration::from_secs(5),
        "{signal}: stopped after {:?}",
        sent.elapsed()
    );
    status.code()
}

#[cfg(unix)]
#[test]
fn an_interrupt_leaves_no_temporary_file() {
    let d = dir_with(&[("t.json", LECTURE)]);
    let eval = [
        "eval",
        "t.json",
        "--samples",
        "10000000",
        "-d",
        "2",
        "-o",
        "out.csv",
    ];
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        let got = interrupt_while_writing(d.path(), &eval, signal);
        if let Some(got) = got {
            assert_eq!(got, code, "{signal}");
            assert!(!p(&d, "out.csv").exists(), "no partial output");
        }
        let left = debris(d.path(), &["t.json", "out.csv"]);
        assert_eq!(left, Vec::<String>::new(), "{signal}");
    }
}

/// A blend spline of parabolas through `p.csv` into `s.json`.
const BLEND_PARABOLAS: [&str; 7] = [
    "blend",
    "spline",
    "p.csv",
    "--local",
    "parabolas",
    "-o",
    "s.json",
];

/// `n` points of a wavy line as CSV.
fn wavy_csv(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        let t = i as f64 * 0.01;
        let _ = writeln!(s, "{},{}", t + 0.3 * (7.0 * t).sin(), (3.0 * t).cos());
    }
    s
}

#[cfg(unix)]
#[test]
fn an_interrupted_blend_spline_stops_cleanly_with_the_signal_code() {
    // the blend is computed and written segment by segment and checks the cancel flag
    let d = dir_with(&[("p.csv", &wavy_csv(300_000))]);
    let args = BLEND_PARABOLAS;
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        if let Some(got) = interrupt_while_writing(d.path(), &args, signal) {
            assert_eq!(got, code, "{signal}");
            assert!(!p(&d, "s.json").exists(), "no partial output");
        }
        let left = debris(d.path(), &["p.csv", "s.json"]);
        assert_eq!(left, Vec::<String>::new(), "{signal}");
    }
}

/// Starts `lekalo args` in `dir`, lets it compute for `after` (it writes nothing before its
/// result), sends `signal` and returns the exit code, or `None` if the command finished first.
#[cfg(unix)]
fn interrupt_while_computing(
    dir: &Path,
    args: &[&str],
    signal: &str,
    after: std::time::Duration,
) -> Option<i32> {
    let mut child = std::process::Command::new(bin())
        .args(args)
        .current_dir(dir)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while started.elapsed() < after {
        if child.try_wait().unwrap().is_some() {
            return None;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let _ = std::process::Command::new("kill")
        .args([format!("-{signal}"), child.id().to_string()])
        .status();
    let sent = std::time::Instant::now();
    let status = child.wait().unwrap();
    // the handler's grace period is 0.7 s; the bound leaves room for a loaded machine
    assert!(
        sent.elapsed() < std::time::Duration::from_secs(5),
        "{signal}: stopped after {:?}",
        sent.elapsed()
    );
    status.code()
}

/// Every long fitting mode stops on a signal with its code and writes no output: smoothing by
/// GCV, the smoothing condition, the tolerance fit, a closed fit (each checks the cancel flag
/// between steps of its work; seconds of work on 300,000 points, where least squares takes a
/// fraction of a second).
#[cfg(unix)]
#[test]
fn an_interrupted_fit_stops_cleanly_with_the_signal_code_in_every_mode() {
    let d = dir_with(&[("p.csv", &wavy_csv(300_000))]);
    let modes: [&[&str]; 4] = [
        &["--smooth", "gcv"],
        &["--s", "1e-9"],
        &["--tolerance", "1e-7"],
        &["--periodic", "--s", "1e-9"],
    ];
    let mut interrupted = 0;
    for mode in modes {
        let mut args = vec!["fit", "p.csv", "-o", "f.json"];
        args.extend_from_slice(mode);
        let after = std::time::Duration::from_millis(700);
        if let Some(got) = interrupt_while_computing(d.path(), &args, "INT", after) {
            assert_eq!(got, 130, "{mode:?}");
            assert!(!p(&d, "f.json").exists(), "{mode:?}: no output");
            interrupted += 1;
        }
        let _ = fs::remove_file(p(&d, "f.json"));
        let left = debris(d.path(), &["p.csv"]);
        assert_eq!(left, Vec::<String>::new(), "{mode:?}");
    }
    assert!(
        interrupted >= 3,
        "only {interrupted} fits ran long enough to be interrupted"
    );
}

#[test]
fn a_large_blend_spline_stays_within_a_memory_limit_and_draws_no_bar_off_a_terminal() {
    // 150,000 points (4 MB of CSV): the whole NURBS alone would take 24 MB and the blend
    // spline's segments 31 times the input; streamed, a few numbers a point are held
    let text = wavy_csv(150_000);
    let d = dir_with(&[("p.csv", &text)]);
    let kib = 400_000 + 3 * text.len() as u64 / 1024;
    let args = BLEND_PARABOLAS;
    let (code, err) = run_limited(d.path(), kib, &args);
    assert_eq!(code, 0, "{err}");
    // standard error is a pipe here: no progress bar, not a byte of it
    assert!(
        !err.contains('\r') && !err.contains('\u{1b}'),
        "bar drawn off a terminal: {err:?}"
    );
    let back = fs::read_to_string(p(&d, "s.json")).unwrap();
    assert!(
        back.starts_with("{\n  \"lekalo\": 1,\n  \"type\": \"nurbs_curve\",\n  \"degree\": 5,")
            && back.ends_with("]\n}\n"),
        "a whole NURBS"
    );
    // 5 control points a segment and one more
    assert_eq!(
        back.matches("\n    [").count(),
        5 * 149_999 + 1,
        "control points"
    );
}

#[cfg(unix)]
#[test]
fn a_closed_pipe_stops_quietly() {
    let d = dir_with(&[("t.json", LECTURE)]);
    let out = std::process::Command::new("bash")
        .arg("-c")
        .arg(format!(
            "'{}' eval t.json --samples 200000 | head -c 10 > /dev/null; echo \"${{PIPESTATUS[0]}}\"",
            bin().display()
        ))
        .current_dir(d.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        stdout.trim(),
        "0",
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_png_of_a_million_control_points_is_decimated() {
    let d = dir_with(&[("big.json", &big_polyline(1_000_000))]);
    lekalo()
        .current_dir(d.path())
        .args(["plot", "big.json", "-o", "big.png", "--no-knots"])
        .assert()
        .success();
    let png = fs::read(p(&d, "big.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    lekalo()
        .current_dir(d.path())
        .args(["plot", "big.json", "-o", "big.svg"])
        .assert()
        .success();
    let svg = fs::read_to_string(p(&d, "big.svg")).unwrap();
    assert!(
        svg.contains(" of 1000000 points)"),
        "the legend says the polygon is decimated"
    );
    assert!(svg.len() < 5_000_000, "{} bytes", svg.len());
}

#[test]
fn info_and_convert_of_a_large_curve_stay_within_a_memory_limit() {
    // about 40 MB of JSON; the limit leaves room for the binary and its threads but not for a
    // tree of JSON values (which needed more than 20 times the text)
    let text = big_polyline(1_000_000);
    let d = dir_with(&[("big.json", &text)]);
    let kib = 400_000 + 3 * text.len() as u64 / 1024;
    for args in [
        &["info", "big.json"][..],
        &["convert", "big.json", "-o", "big.jsonl"],
        &["eval", "big.json", "--samples", "1000", "-o", "e.csv"],
    ] {
        let (code, err) = run_limited(d.path(), kib, args);
        assert_eq!(code, 0, "{args:?}: {err}");
    }
}

// Hints name the command line's options, not the library's items.
#[test]
fn hints_name_options_not_library_items() {
    let d = dir_with(&[("p.txt", "0 0\n1 1\n2 0\n3 1\n4 4\n")]);
    lekalo()
        .args(["interpolate", "--knots", "uniform", "--end", "natural"])
        .arg(p(&d, "p.txt"))
        .assert()
        .code(2)
        .stderr(contains(
            "error: --knots: averaged or uniform knots do not go with",
        ))
        .stderr(contains("use the knot placement \"auto\""))
        .stderr(contains("KnotPlacement").not());
}

/// A refusal with its notes on a standard error already closed (`lekalo info bad.step 2>&1 |
/// head -1`) exits with 2, as it does with standard error open: the notes' `eprintln!` panicked
/// on the closed pipe and the command exited with 3, an internal error. The STEP file's two
/// trimmed curves refer to each other: skipped with the reason, no stack overflow.
#[test]
fn a_refusal_with_standard_error_closed_is_still_a_refusal() {
    let cycle = "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n\
#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=DIRECTION('',(1.,0.,0.));\n#3=VECTOR('',#2,1.);\n\
#4=LINE('',#1,#3);\n\
#5=TRIMMED_CURVE('',#6,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.)),.T.,.PARAMETER.);\n\
#6=TRIMMED_CURVE('',#5,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.)),.T.,.PARAMETER.);\n\
ENDSEC;\nEND-ISO-10303-21;\n";
    let d = dir_with(&[("cycle.step", cycle)]);
    lekalo()
        .arg("info")
        .arg(p(&d, "cycle.step"))
        .assert()
        .code(2)
        .stderr(contains("a cycle of references?"))
        .stderr(contains("no curve or surface lekalo reads"));
    let mut child = std::process::Command::new(bin())
        .arg("info")
        .arg(p(&d, "cycle.step"))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    let status = child.wait().unwrap();
    assert_eq!(
        status.code(),
        Some(2),
        "info with a closed standard error: {status}"
    );
}

/// A message quotes names from the user's files: a JSON key holding an escape sequence
/// (`\u001b[2J` clears the terminal) or a NUL reached standard error as raw bytes; every control
/// character but newline and tab is now written as an escape.
#[test]
fn control_characters_from_a_file_reach_standard_error_as_escapes() {
    let d = dir_with(&[(
        "esc.json",
        r#"{"lekalo": 1, "type": "bezier_curve", "control": [[0, 0], [1, 1]], "\u001b[2J\u0000": 1}"#,
    )]);
    let out = lekalo()
        .arg("info")
        .arg(p(&d, "esc.json"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("\\u{1b}[2J\\u{0}") && !err.contains('\u{1b}') && !err.contains('\0'),
        "{err:?}"
    );
}

/// An endless device, an endless pipe on standard input, and a file larger than the input limit
/// (`--max-input-bytes`), through the main input and through every option that reads a second
/// file: each used to be read until the memory ran out (a device or a pipe has no size to check
/// first). Each is refused with exit 2 naming the input, the limit and the option, quickly, and
/// under an address-space limit far below what an unbounded read would take.
#[cfg(target_os = "linux")]
#[test]
fn endless_and_oversized_inputs_are_refused_at_the_input_limit() {
    let d = dir_with(&[
        ("c.json", LECTURE),
        ("s.json", SURFACE),
        ("pts.csv", "0,0\n1,1\n2,0\n3,1\n4,0\n"),
    ]);
    let big: String = (0..300).map(|i| format!("{i},{}\n", i % 7)).collect();
    fs::write(p(&d, "big.csv"), &big).unwrap();
    let size = big.len();
    let limit = "1000000";
    let endless: [&[&str]; 8] = [
        &["interpolate", "/dev/zero"],
        &["interpolate", "pts.csv", "--tangents", "/dev/zero"],
        &["eval", "s.json", "--uv-file", "/dev/zero"],
        &["project", "c.json", "--points", "/dev/zero"],
        &["fit", "pts.csv", "--weights", "/dev/zero", "--ctrl", "4"],
        &["plot", "c.json", "--points", "/dev/zero", "-o", "p.svg"],
        &["measure", "c.json", "--lengths", "/dev/zero"],
        &["info", "/dev/zero"],
    ];
    for args in endless {
        let mut all = vec!["--max-input-bytes", limit];
        all.extend_from_slice(args);
        let start = std::time::Instant::now();
        // 512 MiB of address space: an unbounded read of /dev/zero passes it within a second
        let (code, err) = run_limited(d.path(), 512 * 1024, &all);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains(
                "/dev/zero: more than 1000000 bytes, above the input limit of 1000000 bytes; \
                 raise the limit with a larger --max-input-bytes"
            ),
            "{args:?}: {err}"
        );
        assert!(
            start.elapsed().as_secs() < 20,
            "{args:?} took {:?}",
            start.elapsed()
        );
    }
    // an endless pipe on standard input (a child process that never stops writing)
    let mut yes = std::process::Command::new("yes")
        .arg("1,2")
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let out = std::process::Command::new(bin())
        .current_dir(d.path())
        .args(["--max-input-bytes", limit, "interpolate", "-"])
        .stdin(yes.stdout.take().unwrap())
        .output()
        .unwrap();
    let _ = yes.kill();
    let _ = yes.wait();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("<stdin>: more than 1000000 bytes, above the input limit of 1000000 bytes"),
        "{err}"
    );
    // a regular file is refused by its size, before it is read, with the value that admits it
    let below = (size - 1).to_string();
    let (code, err) = code_and_stderr(
        d.path(),
        &["--max-input-bytes", &below, "interpolate", "big.csv"],
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(&format!(
            "big.csv: {size} bytes, above the input limit of {below} bytes; raise the limit \
             with --max-input-bytes {size}"
        )),
        "{err}"
    );
    // at the limit it is read
    let at = size.to_string();
    let out = lekalo()
        .current_dir(d.path())
        .args([
            "--max-input-bytes",
            &at,
            "interpolate",
            "big.csv",
            "-o",
            "b.json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(debris(d.path(), &[]).iter().all(|n| !n.contains(".tmp")));
}
