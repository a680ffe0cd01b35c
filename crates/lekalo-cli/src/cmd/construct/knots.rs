//! `lekalo knots`: knot vectors by the documents' rules, and inspection of a knot vector.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, Subcommand};
use lekalo::KnotVector;
use serde_json::json;

use crate::context::Context;
use crate::exit::bad_input;
use crate::items::load_one;
use crate::output::emit;
use crate::values::{integers, numbers};

/// Arguments of `lekalo knots`.
#[derive(Args, Debug)]
#[command(after_help = "\
Examples (chord-length parameters of P&T Example 9.1; docs/theory/interpolation.md#test-vectors):
  lekalo knots uniform --degree 3 --count 5
  lekalo knots averaged --degree 3 --params 0,5/17,9/17,14/17,1
  lekalo knots end-derivatives --degree 3 --params 0,5/17,9/17,14/17,1
  lekalo knots from-parameters --degree 3 --params 0,5/17,9/17,14/17,1
  lekalo knots curry-schoenberg --order 3 --breakpoints 0,0.5,0.9,1.4,2.1,2.7,3 --continuity 2,2,2,2,2
  lekalo knots inspect --knots 0,0,1,2,3,3 --degree 2
  lekalo knots inspect curve.json")]
pub(crate) struct KnotsArgs {
    #[command(subcommand)]
    rule: Rule,
    /// Print JSON instead of text.
    #[arg(long, global = true)]
    json: bool,
    /// Output file (default: standard output).
    #[arg(short, long, global = true, value_name = "FILE")]
    output: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
enum Rule {
    /// Clamped uniform knots on [0, 1] (document 000 eq. 2).
    #[command(
        after_help = "Example:\n  lekalo knots uniform --degree 3 --count 5   # {0,0,0,0,1/2,1,1,1,1}"
    )]
    Uniform {
        /// Degree p.
        #[arg(long, short = 'p')]
        degree: usize,
        /// Number of control points n + 1.
        #[arg(long)]
        count: usize,
    },
    /// Knots by averaging the parameters (document 000 eq. 3).
    #[command(
        after_help = "Example:\n  lekalo knots averaged --degree 3 --params 0,5/17,9/17,14/17,1   # interior knot 28/51"
    )]
    Averaged(ParamArgs),
    /// Knots for interpolation with end derivatives (document 000 eq. 4).
    #[command(
        after_help = "Example:\n  lekalo knots end-derivatives --degree 3 --params 0,5/17,9/17,14/17,1   # 14/51, 28/51, 40/51"
    )]
    EndDerivatives(ParamArgs),
    /// Knots at the parameters (document 000 eq. 8).
    #[command(
        after_help = "Example:\n  lekalo knots from-parameters --degree 3 --params 0,5/17,9/17,14/17,1"
    )]
    FromParameters(ParamArgs),
    /// Curry–Schoenberg knots from breakpoints and continuity conditions (document 003).
    #[command(
        after_help = "Example (the thesis's practical task):\n  lekalo knots curry-schoenberg --order 3 --breakpoints 0,0.5,0.9,1.4,2.1,2.7,3 --continuity 2,2,2,2,2"
    )]
    CurrySchoenberg {
        /// Order k = degree + 1.
        #[arg(long, short_alias = 'k')]
        order: usize,
        /// Strictly increasing breakpoints ξ1 < ξ2 < … < ξ(l+1), comma-separated.
        #[arg(long, allow_hyphen_values = true)]
        breakpoints: String,
        /// Continuity νi at each interior breakpoint (number of continuous derivatives,
        /// counting the value), one per interior breakpoint.
        #[arg(long, default_value = "")]
        continuity: String,
    },
    /// Distinct knots, multiplicities and domain of a knot vector or of a curve file.
    #[command(
        after_help = "Examples:\n  lekalo knots inspect --knots 0,0,1,2,3,3 --degree 2\n  lekalo knots inspect curve.json"
    )]
    Inspect(KnotSource),
    /// The non-zero basis functions N(i,p) at parameters: each parameter's span and its p + 1
    /// values (Cox–de Boor, P&T A2.2; docs/theory/foundations.md#cox-de-boor-recursion).
    #[command(
        after_help = "Examples (P&T Example 2.3: span 4, values 1/8, 3/4, 1/8):\n  lekalo knots basis --knots 0,0,0,1,2,3,4,4,5,5,5 --degree 2 --at 2.5\n  lekalo knots basis curve.json --at 0,0.25,0.5 --json"
    )]
    Basis {
        #[command(flatten)]
        source: KnotSource,
        /// Parameters in the domain [t(p), t(n+1)], comma-separated (fractions like 5/17 allowed).
        #[arg(long, allow_hyphen_values = true)]
        at: String,
        /// Parameters beyond the domain take the end span's basis polynomials continued
        /// (as SciPy's design matrix does when extrapolating) instead of being refused.
        #[arg(long)]
        extrapolate: bool,
    },
}

/// The knot vector of `inspect` and `basis`: a curve file's, or `--knots` with `--degree`.
#[derive(Args, Debug)]
struct KnotSource {
    /// A curve file whose knots (and degree) to use.
    #[arg(conflicts_with = "knots")]
    input: Option<PathBuf>,
    /// A knot vector, comma-separated.
    #[arg(long, allow_hyphen_values = true)]
    knots: Option<String>,
    /// Degree p, for the domain [t(p), t(n+1)] (a curve file's own degree by default).
    #[arg(long, short = 'p')]
    degree: Option<usize>,
}

impl KnotSource {
    /// The knots and the degree (given, or the curve file's), the file added to `inputs`.
    fn read(&self, inputs: &mut Vec<PathBuf>, cx: &Context) -> Result<(KnotVector, Option<usize>)> {
        match (&self.input, &self.knots) {
            (Some(path), _) => {
                let obj = load_one(cx, path)?;
                inputs.push(path.clone());
                Ok((
                    obj.knots().into_owned(),
                    Some(self.degree.unwrap_or(obj.degree())),
                ))
            }
            (None, Some(k)) => Ok((KnotVector::new(numbers(k, "--knots")?)?, self.degree)),
            (None, None) => bad_input("give a curve file or --knots"),
        }
    }
}

#[derive(Args, Debug)]
struct ParamArgs {
    /// Degree p.
    #[arg(long, short = 'p')]
    degree: usize,
    /// Parameters t̄0 … t̄n, comma-separated, non-decreasing (fractions like 5/17 allowed).
    #[arg(long, allow_hyphen_values = true)]
    params: String,
}

pub(crate) fn run(a: &KnotsArgs, cx: &Context) -> Result<()> {
    let mut inputs = Vec::new();
    let (kv, degree) = match &a.rule {
        Rule::Uniform { degree, count } => {
            cx.check_size(*count, "--count")?;
            cx.check_size(*degree, "--degree")?;
            crate::context::check_memory::<f64>(
                count.saturating_add(*degree).saturating_add(1),
                "--count",
            )?;
            (KnotVector::clamped_uniform(*degree, *count)?, Some(*degree))
        }
        Rule::Averaged(p) => (
            KnotVector::averaged(&numbers(&p.params, "--params")?, p.degree)?,
            Some(p.degree),
        ),
        Rule::EndDerivatives(p) => (
            KnotVector::averaged_with_end_derivatives(&numbers(&p.params, "--params")?, p.degree)?,
            Some(p.degree),
        ),
        Rule::FromParameters(p) => (
            KnotVector::from_parameters(&numbers(&p.params, "--params")?, p.degree)?,
            Some(p.degree),
        ),
        Rule::CurrySchoenberg {
            order,
            breakpoints,
            continuity,
        } => (
            KnotVector::from_breakpoints(
                &numbers(breakpoints, "--breakpoints")?,
                &integers(continuity, "--continuity")?,
                *order,
            )?,
            order.checked_sub(1),
        ),
        Rule::Basis {
            source,
            at,
            extrapolate,
        } => return basis(a, source, at, *extrapolate, cx),
        Rule::Inspect(source) => source.read(&mut inputs, cx)?,
    };
    let text = describe(&kv, degree, a.json)?;
    emit(a.output.as_deref(), text.as_bytes(), &inputs, cx)
}

/// `lekalo knots basis`: the knots and degree of a curve file or of `--knots`/`--degree`, the
/// basis at the parameters of `--at` (continued beyond the domain with `--extrapolate`).
fn basis(
    a: &KnotsArgs,
    source: &KnotSource,
    at: &str,
    extrapolate: bool,
    cx: &Context,
) -> Result<()> {
    let mut inputs = Vec::new();
    let (kv, Some(p)) = source.read(&mut inputs, cx)? else {
        return bad_input("--knots needs --degree");
    };
    let t = numbers(at, "--at")?;
    let text = basis_table(&kv, p, &t, extrapolate, a.json)?;
    emit(a.output.as_deref(), text.as_bytes(), &inputs, cx)
}

/// The non-zero basis functions of degree `p` at each parameter of `t`
/// (`lekalo::basis::design_matrix_into`, the end spans' polynomials beyond the domain with
/// `extrapolate`), as text (a line per parameter) or JSON.
fn basis_table(
    kv: &KnotVector,
    p: usize,
    t: &[f64],
    extrapolate: bool,
    as_json: bool,
) -> Result<String> {
    // a degree the knots can carry (p + 1 <= half their number), so the table's size is bounded
    if kv.len() / 2 <= p {
        return bad_input(format!(
            "--degree {p}: {} knots carry a degree of at most {}",
            kv.len(),
            (kv.len() / 2).saturating_sub(1)
        ));
    }
    let w = p + 1;
    let size = t.len().saturating_mul(w);
    if size > lekalo::MAX_SCALARS {
        return bad_input(format!(
            "--at: {} parameters × {w} values exceed {}; give fewer parameters",
            t.len(),
            lekalo::MAX_SCALARS
        ));
    }
    let mut values = vec![0.0; size];
    let mut spans = vec![0; t.len()];
    lekalo::basis::design_matrix_into(kv, p, t, extrapolate, &mut values, |j, first| {
        spans[j] = first + p;
    })?;
    let rows = t.iter().zip(&spans).zip(values.chunks_exact(p + 1));
    if as_json {
        let rows: Vec<_> = rows
            .map(|((t, span), n)| json!({"t": t, "span": span, "first": span - p, "values": n}))
            .collect();
        return Ok(format!("{:#}\n", json!({"degree": p, "basis": rows})));
    }
    let mut s = String::new();
    for ((t, span), n) in rows {
        let ns: Vec<String> = n.iter().copied().map(lekalo_io::fmt_number).collect();
        let _ = writeln!(
            s,
            "t = {t}  span {span}  N({}..={span}, {p}) = [{}]",
            span - p,
            ns.join(", ")
        );
    }
    Ok(s)
}

/// The knot vector with its multiplicities (and domain for a degree), as text or JSON.
fn describe(kv: &KnotVector, degree: Option<usize>, as_json: bool) -> Result<String> {
    let n_ctrl = degree.and_then(|p| kv.len().checked_sub(p + 1));
    let domain = match (degree, n_ctrl) {
        (Some(p), Some(n)) if n > p => {
            kv.validate_for(p, n)?;
            Some(kv.domain(p))
        }
        (Some(p), _) => {
            return bad_input(format!(
                "{} knots are too few for degree {p} (need at least {})",
                kv.len(),
                2 * p + 2
            ))
        }
        _ => None,
    };
    let distinct = kv.distinct();
    if as_json {
        let d: Vec<_> = distinct
            .iter()
            .map(|(t, m)| json!({"knot": t, "multiplicity": m}))
            .collect();
        let j = json!({
            "knots": kv.as_slice(),
            "distinct_knots": d,
            "degree": degree,
            "control_points": n_ctrl,
            "domain": domain.map(|(a, b)| [a, b]),
            "clamped": degree.map(|p| kv.is_clamped(p)),
        });
        return Ok(format!("{j:#}\n"));
    }
    let mut s = String::new();
    let ks: Vec<String> = kv.as_slice().iter().map(|k| format!("{k}")).collect();
    let _ = writeln!(s, "knots           [{}]", ks.join(", "));
    let _ = writeln!(s, "count           {}", kv.len());
    let ms: Vec<String> = distinct.iter().map(|(t, m)| format!("{t}×{m}")).collect();
    let _ = writeln!(s, "multiplicities  {}", ms.join("  "));
    if let (Some(p), Some(n), Some((lo, hi))) = (degree, n_ctrl, domain) {
        let _ = writeln!(
            s,
            "degree          {p} (order {}), {n} control points",
            p + 1
        );
        let _ = writeln!(
            s,
            "domain          [{lo}, {hi}] ({})",
            if kv.is_clamped(p) {
                "clamped"
            } else {
                "not clamped"
            }
        );
    }
    Ok(s)
}
