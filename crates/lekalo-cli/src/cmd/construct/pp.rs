//! `lekalo pp`: piecewise polynomials ↔ B-splines and quasi-interpolation (document 003).

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, Subcommand};
use lekalo::{
    quasi_interpolate_expression, sample_quasi_interpolant_expression, Expression,
    PiecewisePolynomial, PpSpace, Tau, TauRule, DEFAULT_CONTINUITY_RTOL,
};
use lekalo_io::{CurveJson, Figure, Object, Series, Style, PALETTE};

use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::items::load_one;
use crate::output::encode;
use crate::output::objects::{curve_plot, write_curve, OutArgs};
use crate::output::{emit, format_of};
use crate::values::{integers, numbers};
use crate::words::Words;

/// The τ choice of `pp convert` and `pp quasi`: a rule, or explicit values.
#[derive(Args, Debug)]
pub(crate) struct TauArgs {
    /// τ rule of the de Boor–Fix functionals.
    #[arg(long, value_parser = Words(&lekalo::vocabulary::TAU_RULE), default_value = "first-knot-after")]
    rule: TauRule,
    /// Explicit τ values instead of a rule, one per B-spline, each inside the support of its
    /// B-spline (from knot i to knot i + k): a comma-separated list or a file of one value per
    /// line.
    #[arg(
        long,
        value_name = "LIST|FILE",
        allow_hyphen_values = true,
        conflicts_with = "rule"
    )]
    tau: Option<String>,
}

impl TauArgs {
    /// The explicit values, read once (the caller borrows them as a [`Tau`]).
    fn values(&self, cx: &Context) -> Result<Option<Vec<f64>>> {
        self.tau
            .as_deref()
            .map(|t| crate::cmd::explicit::parameters(cx, t, "--tau"))
            .transpose()
    }

    fn choice<'a>(&self, values: &'a Option<Vec<f64>>) -> Tau<'a> {
        match values {
            Some(v) => Tau::Values(v),
            None => Tau::Rule(self.rule),
        }
    }
}

/// The function of `--function`: a typed expression in `x` ([`lekalo::Expression`]), or one of
/// the names that earlier versions offered (`xcosx`, `sin`, `cos`, `exp`, `runge`).
fn function(text: &str) -> Result<Expression> {
    let expression = match text.trim() {
        "xcosx" => "x*cos(x)",
        "sin" => "sin(x)",
        "cos" => "cos(x)",
        "exp" => "exp(x)",
        "runge" => "1/(1 + x^2)",
        other => other,
    };
    Expression::parse(expression).map_err(|e| BadInput(format!("--function: {e}")).into())
}

/// `lekalo pp` operations.
#[derive(Subcommand, Debug)]
pub(crate) enum PpOp {
    /// B-spline curve → pp-form (local power coefficients), or pp-form → B-spline on the
    /// Curry–Schoenberg knots of --continuity, inferred from the pp-form when not given
    /// (document 003 §5.1).
    #[command(after_help = "\
The pp-form JSON: {\"lekalo\": 1, \"type\": \"piecewise_polynomial\", \"breakpoints\": [...],
\"order\": k, \"dim\": d, \"coefficients\": [...]} with, for each piece j, c_{j,r} = f^(r)(ξ_j+)/r!.

Examples:
  lekalo pp convert curve.json -o curve.pp.json
  lekalo pp convert curve.pp.json -o curve.json       # ν inferred, as `lekalo info` shows it
  lekalo pp convert curve.pp.json --continuity 2,2,2 --rule midpoint -o curve.json")]
    Convert {
        /// A B-spline curve object, or a piecewise polynomial (JSON).
        input: PathBuf,
        /// ν at each interior breakpoint for pp → B-spline: how many derivatives, counting the
        /// value, are continuous there (default: inferred from the pp-form, the continuity that
        /// `lekalo info` reports, so the knots are as few as the pp-form allows).
        #[arg(long)]
        continuity: Option<String>,
        #[command(flatten)]
        tau: TauArgs,
        #[command(flatten)]
        out: OutArgs,
    },
    /// Quasi-interpolate a built-in function in P(k, ξ, ν) (document 003 §5).
    #[command(after_help = "\
Prints the maximum error on a uniform grid (--intervals) to standard error. SVG/PNG output
plots f and its quasi-interpolant, like the thesis's Figure 1.

Examples:
  lekalo pp quasi --function 'x*cos(x)' --breakpoints 0,0.5,0.9,1.4,2.1,2.7,3 --order 3 \\
      --continuity 2,2,2,2,2 --rule left-end-of-support -o fig1.svg    # max error 0.204831
  lekalo pp quasi --function 'exp(x)' --breakpoints 0,1,2 --order 4 -o exp.json
  lekalo pp quasi --function 'exp(x)' --breakpoints 0,1,2 --order 4 --json   # error and curve
  lekalo pp quasi --function 'sin(x)' --breakpoints 0,1,2 --order 2 --continuity 0 --tau 0,0.5,1.5,2")]
    Quasi {
        /// The function of x: an expression such as 'x*cos(x)', '1/(1 + x^2)', 'exp(-x)*sin(3*x)'
        /// (+ − * / ^, sin cos tan exp ln sqrt abs …, pi, e).
        #[arg(long, allow_hyphen_values = true)]
        function: String,
        /// Breakpoints, strictly increasing.
        #[arg(long, allow_hyphen_values = true)]
        breakpoints: String,
        /// Order k = degree + 1.
        #[arg(long, default_value_t = 3)]
        order: usize,
        /// ν at each interior breakpoint (default: k − 1 everywhere).
        #[arg(long)]
        continuity: Option<String>,
        #[command(flatten)]
        tau: TauArgs,
        /// Intervals of the error grid.
        #[arg(long, default_value_t = 60)]
        intervals: usize,
        /// Write one JSON object `{"max_error", "intervals", "curve"}` instead of the curve alone
        /// (the error at full precision).
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        out: OutArgs,
    },
}

/// Arguments of `lekalo pp`.
#[derive(Args, Debug)]
#[command(after_help = "\
Examples:
  lekalo pp convert curve.json -o curve.pp.json
  lekalo pp quasi --function 'x*cos(x)' --breakpoints 0,0.5,0.9,1.4,2.1,2.7,3 --rule midpoint")]
pub(crate) struct PpArgs {
    #[command(subcommand)]
    op: PpOp,
}

/// ν from `--continuity`, or `default` when it is not given.
fn continuity(
    text: Option<&String>,
    n_breakpoints: usize,
    default: impl FnOnce() -> Vec<usize>,
) -> Result<Vec<usize>> {
    let interior = n_breakpoints.saturating_sub(2);
    match text {
        Some(t) => {
            let nu = integers(t, "--continuity")?;
            if nu.len() != interior {
                return bad_input(format!(
                    "--continuity: {} values given; the {n_breakpoints} breakpoints have {interior} interior ones",
                    nu.len()
                ));
            }
            Ok(nu)
        }
        None => Ok(default()),
    }
}

pub(crate) fn run(a: &PpArgs, cx: &Context) -> Result<()> {
    match &a.op {
        PpOp::Convert {
            input,
            continuity: cont,
            tau,
            out,
        } => {
            let (text, name) = lekalo_io::read_input(input)?;
            if lekalo_io::envelope_type(&text).as_deref() == Some("piecewise_polynomial") {
                let p = lekalo_io::read_piecewise_polynomial(&text, &name)?;
                let nu = continuity(cont.as_ref(), p.breakpoints().len(), || {
                    p.continuity(DEFAULT_CONTINUITY_RTOL)
                })?;
                if cont.is_none() && cx.is_verbose() {
                    crate::output::report(&format!(
                        "continuity ν inferred from the pp-form: {nu:?}"
                    ));
                }
                let space = PpSpace::new(p.breakpoints(), &nu, p.order())?;
                let values = tau.values(cx)?;
                let c = p.to_bspline(&space, tau.choice(&values))?;
                return write_curve(
                    &Object::BSpline(c),
                    None,
                    out,
                    std::slice::from_ref(input),
                    cx,
                );
            }
            let obj = load_one(cx, input)?;
            let Some(c) = obj.to_bspline() else {
                return bad_input(format!(
                    "{}: a {} has no pp-form (rational); give a B-spline or Bezier curve",
                    input.display(),
                    obj.display_name()
                ));
            };
            let p = PiecewisePolynomial::from_bspline(&c)?;
            let format = format_of(out.to.as_deref(), out.output.as_deref(), "json");
            if format != "json" {
                return bad_input(format!(
                    "a piecewise polynomial is written as json, not {format}"
                ));
            }
            emit(
                out.output.as_deref(),
                lekalo_io::piecewise_polynomial_to_json(&p).as_bytes(),
                std::slice::from_ref(input),
                cx,
            )
        }
        PpOp::Quasi {
            function: function_text,
            breakpoints,
            order,
            continuity: cont,
            tau,
            intervals,
            json,
            out,
        } => {
            let xi = numbers(breakpoints, "--breakpoints")?;
            let nu = continuity(cont.as_ref(), xi.len(), || {
                vec![order.saturating_sub(1); xi.len().saturating_sub(2)]
            })?;
            let space = PpSpace::new(&xi, &nu, *order)?;
            let f = function(function_text)?;
            let values = tau.values(cx)?;
            let q = quasi_interpolate_expression(&space, tau.choice(&values), &f)?;
            cx.check_size(*intervals, "--intervals")?;
            crate::context::check_memory::<f64>(intervals.saturating_mul(4), "--intervals")?;
            let samples =
                sample_quasi_interpolant_expression(&space, tau.choice(&values), &f, *intervals)?;
            if !cx.is_quiet() {
                crate::output::report(&format!(
                    "max |f − q| on {} intervals: {}",
                    intervals,
                    lekalo_io::fmt_number(samples.max_error())
                ));
            }
            if *json {
                let obj = Object::BSpline(q);
                let j = serde_json::json!({
                    "max_error": samples.max_error(),
                    "intervals": intervals,
                    "curve": obj.to_json_value(),
                });
                return crate::report::print_report(
                    true,
                    &j,
                    crate::report::text_of,
                    out.output.as_deref(),
                    &[],
                    cx,
                );
            }
            let format = format_of(out.to.as_deref(), out.output.as_deref(), "json");
            let obj = Object::BSpline(q);
            if format == "svg" || format == "png" {
                let fig = quasi_figure(&obj, &samples, function_text)?;
                return emit(out.output.as_deref(), &encode(&fig, &format, 2.0)?, &[], cx);
            }
            write_curve(&obj, None, out, &[], cx)
        }
    }
}

/// f and its quasi-interpolant on the grid (the thesis's Figure 1).
pub(crate) fn quasi_figure(q: &Object, s: &lekalo::QuasiSamples, name: &str) -> Result<Figure> {
    let mut fig = curve_plot(q, None, Some(&format!("{name} and its quasi-interpolant")))?;
    fig.series[0].label = Some("quasi-interpolant".into());
    let exact = s.t.iter().zip(&s.exact).map(|(t, y)| [*t, *y]).collect();
    fig.series
        .push(Series::new(Some("f(x)"), exact, Style::Dashed, PALETTE[1]));
    Ok(fig)
}
