//! Results that commands print: one `--json` flag and one way to write a result, as a JSON
//! object (numbers at full precision: the shortest decimal that reads back to the same `f64`,
//! which is what `serde_json` writes) or as text (numbers through [`lekalo_io::fmt_number`]:
//! the same digits, in exponent notation when very large or very small).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use serde_json::Value;

use crate::context::Context;
use crate::output::emit;

/// `--json`, for every command that computes a figure or a result.
#[derive(Args, Debug, Clone, Copy, Default)]
pub(crate) struct JsonFlag {
    /// Print the result as one JSON object (full-precision numbers) instead of text.
    #[arg(long)]
    pub(crate) json: bool,
}

/// Writes `report` to `out` (standard output when `None`): pretty JSON with `--json`, else the
/// text `text` makes of it (see [`text_of`] for a generic one).
pub(crate) fn print_report(
    json: bool,
    report: &Value,
    text: impl FnOnce(&Value) -> String,
    out: Option<&Path>,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let body = if json {
        format!("{report:#}\n")
    } else {
        text(report)
    };
    emit(out, body.as_bytes(), inputs, cx)
}

/// A number as text output writes it (see the module docs).
pub(crate) fn number(x: f64) -> String {
    lekalo_io::fmt_number(x)
}

/// A JSON value as text: numbers through [`number`], strings bare, arrays space-separated.
pub(crate) fn value_text(v: &Value) -> String {
    match v {
        Value::Number(n) => n
            .as_u64()
            .map(|u| u.to_string())
            .or_else(|| n.as_i64().map(|i| i.to_string()))
            .unwrap_or_else(|| number(n.as_f64().unwrap_or(f64::NAN))),
        Value::String(s) => s.clone(),
        Value::Array(items) => items.iter().map(value_text).collect::<Vec<_>>().join(" "),
        Value::Null => "-".into(),
        other => other.to_string(),
    }
}

/// A flat report as `key: value` lines, keys with underscores as words (`max_error` becomes
/// "max error"); nested objects are written as JSON.
pub(crate) fn text_of(report: &Value) -> String {
    let mut s = String::new();
    if let Value::Object(map) = report {
        for (k, v) in map {
            let v = match v {
                Value::Object(_) => v.to_string(),
                _ => value_text(v),
            };
            let _ = writeln!(s, "{}: {v}", k.replace('_', " "));
        }
    } else {
        let _ = writeln!(s, "{}", value_text(report));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn text_uses_exponent_notation_for_extreme_numbers() {
        let t = text_of(&json!({"max_error": 1.5e-20, "count": 3, "knots": [0.0, 0.5, 1e17]}));
        // keys in order (serde_json sorts them)
        assert_eq!(t, "count: 3\nknots: 0 0.5 1e17\nmax error: 1.5e-20\n");
    }

    #[test]
    fn json_numbers_round_trip() {
        let x = 0.1 + 0.2;
        let text = format!("{:#}", json!({ "x": x }));
        let back: Value = serde_json::from_str(&text).unwrap_or(Value::Null);
        assert_eq!(back["x"].as_f64(), Some(x), "{text}");
    }
}
