//! The examples in `--help` run as written: the example lines of `make`, `eval`, `convert` and
//! `knot` are parsed from the help text and run, in order, in a directory with the fixture files
//! they name (later examples use what earlier ones wrote, as a reader following them would).

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;

use assert_cmd::Command;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// The `lekalo …` lines of a help text, comments dropped, split into arguments.
fn examples(help: &str) -> Vec<Vec<String>> {
    help.lines()
        .filter_map(|l| l.strip_prefix("  lekalo "))
        .map(|l| l.split(" #").next().unwrap_or(l))
        .map(|l| l.split_whitespace().map(String::from).collect())
        .collect()
}

#[test]
fn help_examples_run() {
    let d = tempfile::tempdir().unwrap();
    let w = |name: &str, text: &str| fs::write(d.path().join(name), text).unwrap();
    w("pts.csv", "1,1\n2,3\n4,3\n");
    w(
        "net.csv",
        "0 0 0\n0 1 0\n0 2 0\n1 0 0\n1 1 1\n1 2 0\n2 0 0\n2 1 0\n2 2 0\n",
    );
    let curve = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2, "knots": [0, 0, 0, 1, 2, 2, 2], "control": [[1, 1], [2, 3], [4, 3], [5, 0]]}"#;
    w("curve.json", curve);
    w(
        "many.jsonl",
        &format!("{curve}\n{}\n", curve.replace("[5, 0]", "[6, 1]")),
    );
    fs::copy(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../lekalo-io/tests/data/occ/mixed_ap242_m.step"
        ),
        d.path().join("part.step"),
    )
    .unwrap();
    lekalo()
        .current_dir(d.path())
        .args(["pp", "convert", "curve.json", "-o", "spline.pp.json"])
        .assert()
        .success();
    let mut ran = 0;
    for cmd in ["make", "eval", "convert", "knot"] {
        let out = lekalo().args([cmd, "--help"]).assert().success();
        let help = String::from_utf8(out.get_output().stdout.clone()).unwrap();
        let list = examples(&help);
        assert!(!list.is_empty(), "`lekalo {cmd} --help` has no examples");
        for args in list {
            let run = lekalo().current_dir(d.path()).args(&args).assert();
            let o = run.get_output();
            assert!(
                o.status.success(),
                "`lekalo {}` failed: {}",
                args.join(" "),
                String::from_utf8_lossy(&o.stderr)
            );
            ran += 1;
        }
    }
    assert!(ran >= 30, "{ran} examples");
}
