//! The documentation runs as written: every `sh` block of `README.md`, `docs/cli.md` and
//! `docs/formats.md` is run line by line by `sh`, in order, in one empty folder per page (each
//! page makes its own input files, as a reader starting from nothing would), with the test build of `lekalo` first on
//! `PATH`. A line `#   TEXT` right under a command quotes the command's output: the
//! quoted lines must be the first lines of its standard output, compared up to an ellipsis `…`
//! where the text has one (the rest of the line is a comment), in full otherwise. Commands that
//! cannot run here are listed in [`NOT_RUN`] with the reason; every entry must still be in the
//! text, so the list cannot go stale.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Commands of the pages that are not run, matched by the start of the line, with the reason.
const NOT_RUN: &[(&str, &str)] = &[
    (
        "cargo run --release --bin lekalo -- demo",
        "a release build of the workspace; the tour runs `lekalo demo` itself",
    ),
    (
        "scripts/test.sh",
        "every test of the project, this one included",
    ),
    (
        "pip install ./crates/lekalo-py",
        "builds and installs the Python package (scripts/test.sh does, and runs its README)",
    ),
    (
        "lekalo serve",
        "runs until stopped (the server's tests and the browser tests cover it)",
    ),
    (
        "PROPTEST_CASES=5000 cargo test",
        "the long property-test job",
    ),
    (
        "FUZZ_SECONDS=60 scripts/fuzz.sh",
        "needs cargo-fuzz and a nightly toolchain",
    ),
    ("cargo bench", "criterion benchmarks, minutes long"),
    (
        "bench/peers/run.sh",
        "needs SciPy, tinyspline and Open CASCADE",
    ),
    (
        "cargo run --release -p lekalo --example par_placement",
        "a timing example",
    ),
];

/// One command of a block: its line (continuations joined) and the output lines it quotes.
struct Step {
    line: String,
    quoted: Vec<String>,
}

/// The commands of the `sh` blocks of a Markdown page, in order.
fn steps(page: &str) -> Vec<Step> {
    let mut out: Vec<Step> = Vec::new();
    let mut in_sh = false;
    let mut open = false;
    for line in page.lines() {
        if line.starts_with("```") {
            in_sh = !in_sh && line.trim() == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        if open {
            if let Some(last) = out.last_mut() {
                last.line.push('\n');
                last.line.push_str(line);
            }
            open = line.ends_with('\\');
            continue;
        }
        if let Some(quote) = line.strip_prefix("#   ") {
            if let Some(last) = out.last_mut() {
                last.quoted.push(quote.to_string());
            }
            continue;
        }
        if line.trim().is_empty() || line.trim_start().starts_with('#') {
            continue;
        }
        open = line.ends_with('\\');
        out.push(Step {
            line: line.to_string(),
            quoted: Vec::new(),
        });
    }
    out
}

/// `PATH` with the folder of the test build of `lekalo` first.
fn path_with_lekalo() -> std::ffi::OsString {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_lekalo"));
    let dir = bin.parent().expect("the binary has a folder").to_path_buf();
    let rest = std::env::var_os("PATH").unwrap_or_default();
    std::env::join_paths(std::iter::once(dir).chain(std::env::split_paths(&rest)))
        .expect("PATH joins")
}

/// Where `quoted` disagrees with the output `stdout`, the message.
fn compare(quoted: &[String], stdout: &str) -> Option<String> {
    let lines: Vec<&str> = stdout.lines().collect();
    for (i, q) in quoted.iter().enumerate() {
        let got = lines.get(i).copied().unwrap_or("");
        let ok = match q.split_once('…') {
            Some((prefix, _)) => got.starts_with(prefix),
            None => got == q.trim_end(),
        };
        if !ok {
            return Some(format!(
                "output line {} is `{got}`, the text quotes `{q}`",
                i + 1
            ));
        }
    }
    None
}

/// Runs the `sh` blocks of `page` (named `name` in messages) in `dir`; failures are collected,
/// the [`NOT_RUN`] entries met are marked in `used`. Returns the number of commands run.
fn run_page(
    name: &str,
    page: &str,
    dir: &Path,
    used: &mut [bool],
    failures: &mut Vec<String>,
) -> usize {
    let path = path_with_lekalo();
    let mut ran = 0;
    for step in steps(page) {
        if let Some(i) = NOT_RUN.iter().position(|(p, _)| step.line.starts_with(p)) {
            used[i] = true;
            continue;
        }
        let o = Command::new("sh")
            .arg("-c")
            .arg(&step.line)
            .current_dir(dir)
            .env("PATH", &path)
            .output()
            .expect("sh runs");
        ran += 1;
        let stdout = String::from_utf8_lossy(&o.stdout);
        if !o.status.success() {
            failures.push(format!(
                "{name}: `{}` failed ({}): {}",
                step.line,
                o.status,
                String::from_utf8_lossy(&o.stderr)
            ));
        } else if let Some(why) = compare(&step.quoted, &stdout) {
            failures.push(format!("{name}: `{}`: {why}", step.line));
        }
    }
    ran
}

#[test]
fn readme_cli_and_formats_docs_run_as_written() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let mut used = vec![false; NOT_RUN.len()];
    let mut failures = Vec::new();

    // the README's tour makes its own files: an empty folder
    let readme = fs::read_to_string(format!("{root}/README.md")).expect("README.md");
    let d = tempfile::tempdir().expect("a temporary folder");
    let ran = run_page("README.md", &readme, d.path(), &mut used, &mut failures);
    if ran < 25 {
        failures.push(format!("only {ran} README commands ran"));
    }

    // docs/cli.md too runs in an empty folder: its first block makes the files the others read
    let cli = fs::read_to_string(format!("{root}/docs/cli.md")).expect("docs/cli.md");
    let d = tempfile::tempdir().expect("a temporary folder");
    let ran = run_page("docs/cli.md", &cli, d.path(), &mut used, &mut failures);
    if ran < 40 {
        failures.push(format!("only {ran} docs/cli.md commands ran"));
    }

    // docs/formats.md's Parquet block makes its point sets from a CSV before it reads them
    let formats = fs::read_to_string(format!("{root}/docs/formats.md")).expect("docs/formats.md");
    let d = tempfile::tempdir().expect("a temporary folder");
    let ran = run_page(
        "docs/formats.md",
        &formats,
        d.path(),
        &mut used,
        &mut failures,
    );
    if ran < 7 {
        failures.push(format!("only {ran} docs/formats.md commands ran"));
    }

    for (i, (line, _)) in NOT_RUN.iter().enumerate() {
        if !used[i] {
            failures.push(format!(
                "NOT_RUN lists `{line}`, which no page has any more"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn quoted_output_is_compared() {
    let quoted = vec!["t,x".to_string(), "1.5,2.12…  (a comment)".to_string()];
    assert_eq!(compare(&quoted, "t,x\n1.5,2.125\n"), None);
    assert!(
        compare(&quoted, "t,x\n1.5,2.2\n").is_some(),
        "a different number"
    );
    assert!(
        compare(&quoted, "t,y\n1.5,2.125\n").is_some(),
        "a different header"
    );
    assert!(compare(&quoted, "t,x\n").is_some(), "a missing line");
    let s = steps("```sh\nprintf 'a' > f   # x\nlekalo eval f \\\n  --at 1\n#   t,x\n# a comment\n```\n```rust\nlet x = 1;\n```\n");
    assert_eq!(s.len(), 2, "two commands");
    assert_eq!(s[1].line, "lekalo eval f \\\n  --at 1");
    assert_eq!(s[1].quoted, vec!["t,x".to_string()]);
}
