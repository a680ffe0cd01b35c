//! Whole command lines as a hostile user types them: a subcommand path and its options drawn
//! from the CLI's own grammar (`lekalo_cli::command()`), with hostile values (numbers of any
//! size and sign, lists, fractions, possible values, free text) and input files of hostile
//! contents, run in one process through `lekalo_cli::run`. Any panic is a bug; the exit code
//! must be 0 (success or help), 2 (bad input) or 3 (internal failure, such as an output the
//! file system refuses).
//!
//! Left out, each for a reason: `serve` (it serves until stopped) and `demo` (no user input);
//! `--max-size` and `--max-degree` (raising a limit asks for the work the limit refuses, which
//! `cli_robustness` tests under a memory limit); standard input `-`; and paths outside the
//! scratch directory (free text with a `/` or starting with `.` is dropped). Integers are kept
//! below 10^5 so that one run stays within libFuzzer's time limit; the size limits themselves
//! are tested end to end.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;

/// One subcommand path with its options: (long name, takes a value, possible values).
struct Leaf {
    path: Vec<String>,
    options: Vec<(String, bool, Vec<String>)>,
}

fn leaves() -> &'static [Leaf] {
    static LEAVES: OnceLock<Vec<Leaf>> = OnceLock::new();
    LEAVES.get_or_init(|| {
        let mut out = Vec::new();
        walk(&lekalo_cli::command(), &mut Vec::new(), &mut out);
        out
    })
}

fn walk(cmd: &clap::Command, path: &mut Vec<String>, out: &mut Vec<Leaf>) {
    let name = cmd.get_name().to_string();
    if !path.is_empty() || name != "lekalo" {
        path.push(name);
    }
    if matches!(path.first().map(String::as_str), Some("serve" | "demo")) {
        path.pop();
        return;
    }
    if cmd.has_subcommands() {
        for sub in cmd.get_subcommands() {
            walk(sub, path, out);
        }
    } else {
        let options = cmd
            .get_arguments()
            .filter_map(|a| {
                let long = a.get_long()?;
                if matches!(long, "max-size" | "max-degree" | "help" | "version") {
                    return None;
                }
                let takes = a.get_action().takes_values();
                let values = a
                    .get_possible_values()
                    .iter()
                    .map(|v| v.get_name().to_string())
                    .collect();
                Some((format!("--{long}"), takes, values))
            })
            .collect();
        out.push(Leaf {
            path: path.clone(),
            options,
        });
    }
    path.pop();
}

/// The scratch directory the commands run in (created once; every run's files are rewritten).
fn scratch() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("lekalo-fuzz-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch directory");
        std::env::set_current_dir(&dir).expect("enter the scratch directory");
        // valid objects, so that options reach the computations and not only the readers
        std::fs::write(
            "curve.json",
            r#"{"lekalo":1,"type":"bspline_curve","degree":2,"knots":[0,0,1,2,3,3],"control":[[1,1],[2,3],[4,3]]}"#,
        )
        .expect("fixture");
        std::fs::write(
            "surface.json",
            r#"{"lekalo":1,"type":"bspline_surface","degree_u":2,"degree_v":2,"knots_u":[0,0,0,1,1,1],"knots_v":[0,0,0,1,1,1],"net":[3,3],"control":[[0,0,0],[0,1,0],[0,2,0],[1,0,0],[1,1,1],[1,2,0],[2,0,0],[2,1,0],[2,2,0]]}"#,
        )
        .expect("fixture");
        std::fs::write("points.txt", "0 0\n1 2\n2 1\n3 3\n4 0\n5 2\n").expect("fixture");
        dir
    })
}

/// Input files whose contents the fuzzer chooses, and the valid fixtures.
const INPUTS: &[&str] = &[
    "a.txt", "a.csv", "a.json", "a.jsonl", "a.step", "a.igs", "a.npy", "a.npz", "a.parquet",
    "curve.json", "surface.json", "points.txt", "missing.json",
];
/// Output names, one per format the writers choose by extension.
const OUTPUTS: &[&str] = &[
    "o.json", "o.jsonl", "o.csv", "o.svg", "o.png", "o.step", "o.igs", "o.obj", "o.stl",
    "o.ply", "o.npy", "o.npz", "o.parquet", "o.txt",
];

#[derive(Arbitrary, Debug)]
enum Value {
    Possible(u8),
    Int(i32),
    Number(f64),
    List(Vec<f64>),
    Fraction(i16, u8),
    Pair(u16, u16),
    Percent(u8),
    Input(u8),
    Output(u8),
    Text(String),
}

#[derive(Arbitrary, Debug)]
struct Input {
    leaf: u16,
    options: Vec<(u8, Value)>,
    positionals: Vec<u8>,
    text: String,
    json: String,
    bytes: Vec<u8>,
}

fn number(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else if x.is_nan() {
        "nan".into()
    } else if x > 0.0 {
        "inf".into()
    } else {
        "-inf".into()
    }
}

fn value_text(v: &Value, possible: &[String]) -> Option<String> {
    Some(match v {
        Value::Possible(i) if !possible.is_empty() => possible[usize::from(*i) % possible.len()].clone(),
        Value::Possible(i) => i.to_string(),
        Value::Int(i) => (i % 100_000).to_string(),
        Value::Number(x) => number(*x),
        Value::List(xs) => xs.iter().take(64).map(|x| number(*x)).collect::<Vec<_>>().join(","),
        Value::Fraction(p, q) => format!("{p}/{q}"),
        Value::Pair(a, b) => format!("{},{}", a % 1000, b % 1000),
        Value::Percent(p) => format!("{p}%"),
        Value::Input(i) => INPUTS[usize::from(*i) % INPUTS.len()].to_string(),
        Value::Output(i) => OUTPUTS[usize::from(*i) % OUTPUTS.len()].to_string(),
        Value::Text(t) => {
            if t == "-" || t.contains('/') || t.starts_with('.') || t.contains('\0') {
                return None;
            }
            t.clone()
        }
    })
}

fuzz_target!(|input: Input| {
    scratch();
    let leaves = leaves();
    let leaf = &leaves[usize::from(input.leaf) % leaves.len()];
    for (name, contents) in [
        ("a.txt", input.text.as_bytes()),
        ("a.csv", input.text.as_bytes()),
        ("a.json", input.json.as_bytes()),
        ("a.jsonl", input.json.as_bytes()),
        ("a.step", input.text.as_bytes()),
        ("a.igs", input.text.as_bytes()),
        ("a.npy", &input.bytes[..]),
        ("a.npz", &input.bytes[..]),
        ("a.parquet", &input.bytes[..]),
    ] {
        std::fs::write(name, contents).expect("scratch file");
    }
    let mut args: Vec<String> = vec!["lekalo".into(), "-q".into()];
    args.extend(leaf.path.iter().cloned());
    for p in input.positionals.iter().take(3) {
        args.push(INPUTS[usize::from(*p) % INPUTS.len()].to_string());
    }
    if !leaf.options.is_empty() {
        for (i, v) in input.options.iter().take(8) {
            let (name, takes, possible) = &leaf.options[usize::from(*i) % leaf.options.len()];
            args.push(name.clone());
            if *takes {
                match value_text(v, possible) {
                    Some(t) => args.push(t),
                    None => {
                        args.pop();
                    }
                }
            }
        }
    }
    let code = lekalo_cli::run(&args);
    assert!(
        matches!(code, 0 | 2 | 3),
        "exit code {code} for {args:?}"
    );
});
