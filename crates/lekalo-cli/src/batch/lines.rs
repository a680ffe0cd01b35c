//! JSON Lines batches: the command's work on one curve applied to every line (in parallel,
//! with a progress bar on a terminal), one JSON line out per line in, the failed lines
//! reported after the output is written.

use std::path::{Path, PathBuf};

use anyhow::Result;
use lekalo_io::{IoError, Object};
use rayon::prelude::*;
use serde_json::{json, Value};

use crate::context::Context;
use crate::output::{emit, progress};

/// The curves of a batch: each with its line (or entity) number, or why it could not be read.
pub(crate) type Lines = Vec<(usize, std::result::Result<Object, IoError>)>;

/// `work` applied to every curve of `items`, in parallel: `work(line, curve)` gives the JSON
/// object of its output line, or the message of its failure; a failure (and a line that could
/// not be read) is written as `{"line", "error"}`. Written to `out` (standard output if
/// `None`), then the failures are reported (exit code 2 if any).
pub(crate) fn run(
    cx: &Context,
    items: Lines,
    out: Option<&Path>,
    inputs: &[PathBuf],
    work: impl Fn(usize, Object) -> std::result::Result<Value, String> + Sync,
) -> Result<()> {
    let bar = progress(cx, items.len());
    let lines: Vec<(bool, String)> = items
        .into_par_iter()
        .map(|(line, obj)| {
            let r = obj.map_err(|e| e.to_string()).and_then(|o| work(line, o));
            bar.inc(1);
            match r {
                Ok(j) => (true, j.to_string()),
                Err(e) => (false, json!({"line": line, "error": e}).to_string()),
            }
        })
        .collect();
    bar.finish_and_clear();
    finish(cx, lines, out, inputs)
}

/// Writes the JSON lines of a batch, `(went through, line)`, then reports the failed lines
/// (exit code 2 if any).
pub(crate) fn finish(
    cx: &Context,
    lines: Vec<(bool, String)>,
    out: Option<&Path>,
    inputs: &[PathBuf],
) -> Result<()> {
    let failed: Vec<String> = lines
        .iter()
        .filter(|(ok, _)| !ok)
        .filter_map(|(_, l)| serde_json::from_str::<Value>(l).ok())
        .filter_map(|j| j["error"].as_str().map(str::to_string))
        .collect();
    let mut text = String::new();
    for (_, l) in &lines {
        text.push_str(l);
        text.push('\n');
    }
    emit(out, text.as_bytes(), inputs, cx)?;
    super::failures(
        &failed,
        format!(
            "{} of {} objects failed (listed above and as \"error\" lines in the output)",
            failed.len(),
            lines.len()
        ),
        cx,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every line gives one output line in the input's order; a failed line is written with
    /// its error and makes the batch fail (exit code 2) after the output is written.
    #[test]
    fn each_line_one_output_line_and_failures_after() {
        let dir = std::env::temp_dir().join(format!("lekalo-lines-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("out.jsonl");
        let control = lekalo::Points::from_flat(1, vec![0.0, 1.0]).unwrap();
        let curve = Object::Bezier(lekalo::BezierCurve::new(control).unwrap());
        let items: Lines = (1..=5).map(|l| (l, Ok(curve.clone()))).collect();
        let cx = Context::default().quiet();
        let r = run(&cx, items, Some(&out), &[], |line, o| {
            if line == 3 {
                Err("three".to_string())
            } else {
                Ok(json!({"line": line, "degree": o.degree()}))
            }
        });
        let e = r.unwrap_err();
        assert_eq!(crate::exit::exit_code(&e), crate::exit::EXIT_BAD_INPUT);
        assert!(e.to_string().contains("1 of 5 objects failed"), "{e}");
        let text = std::fs::read_to_string(&out).unwrap();
        let lines: Vec<Value> = text
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(lines.len(), 5, "{text}");
        for (k, l) in lines.iter().enumerate() {
            assert_eq!(l["line"], json!(k + 1), "in order: {text}");
        }
        assert_eq!(lines[2]["error"], json!("three"));
        assert_eq!(lines[0]["degree"], json!(1));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
