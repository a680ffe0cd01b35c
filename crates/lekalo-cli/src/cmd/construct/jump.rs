//! `lekalo blend jump`: the jump-smoothing polynomial `w_k` of document 001 — its exact monomial
//! and Bernstein coefficients and samples of it (all from `lekalo::JumpPolynomial`).

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use lekalo::JumpPolynomial;
use lekalo_io::fmt_number;

use crate::context::Context;
use crate::exit::bad_input;

/// Arguments of `lekalo blend jump`.
#[derive(Args, Debug)]
pub(crate) struct JumpArgs {
    /// The index k: `w_k` has degree 2k + 1, `w_k(0) = 0`, `w_k(1) = 1` and k vanishing
    /// derivatives at both ends.
    #[arg(long)]
    k: usize,
    /// Samples of `w_k` at evenly spaced u in [0, 1].
    #[arg(long, short = 'n', default_value_t = 11)]
    samples: usize,
    /// Print one JSON object (coefficients as decimal integer strings, exact).
    #[arg(long)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn run(a: &JumpArgs, cx: &Context) -> Result<()> {
    if !(2..=10_000_000).contains(&a.samples) {
        return bad_input("--samples must be between 2 and 10000000");
    }
    let w = JumpPolynomial::new(a.k)?;
    let mono: Vec<String> = w
        .monomial_coefficients()
        .iter()
        .map(ToString::to_string)
        .collect();
    let bern: Vec<String> = w
        .bernstein_coefficients()
        .iter()
        .map(ToString::to_string)
        .collect();
    let n = a.samples;
    let mut rows = Vec::with_capacity(n);
    for i in 0..n {
        // the last sample exactly 1
        #[allow(clippy::cast_precision_loss)]
        let u = if i + 1 == n {
            1.0
        } else {
            i as f64 / (n - 1) as f64
        };
        rows.push((u, w.eval(u)?));
    }
    let report = serde_json::json!({
        "k": a.k,
        "degree": w.degree(),
        "monomial": mono,
        "bernstein": bern,
        "samples": rows.iter().map(|(u, y)| serde_json::json!({"u": u, "w": y})).collect::<Vec<_>>(),
    });
    let text = |_: &serde_json::Value| {
        let mut s = String::new();
        let _ = writeln!(s, "w_{} (degree {})", a.k, w.degree());
        let _ = writeln!(s, "monomial   a_0 … a_{}: {}", w.degree(), mono.join(" "));
        let _ = writeln!(s, "bernstein  b_0 … b_{}: {}", w.degree(), bern.join(" "));
        let _ = writeln!(s, "u,w");
        for (u, y) in &rows {
            let _ = writeln!(s, "{},{}", fmt_number(*u), fmt_number(*y));
        }
        s
    };
    crate::report::print_report(a.json, &report, text, a.output.as_deref(), &[], cx)
}
