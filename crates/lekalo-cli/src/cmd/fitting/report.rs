//! A fitted curve written out with its report (residuals, λ or s, control points), or as
//! `{"object": …, "report": …}` with `--json`.

use lekalo_io::CurveJson;
use std::path::PathBuf;

use anyhow::Result;
use lekalo::fit::CurveFit;
use lekalo::Points;
use lekalo_io::Object;
use serde_json::{json, Value};

use super::args::FitArgs;
use crate::context::Context;
use crate::output::emit;
use crate::output::objects::write_curve;

pub(super) fn finish(
    a: &FitArgs,
    obj: Object,
    shown: &Points,
    fit: &CurveFit,
    mut report: Value,
    inputs: &[PathBuf],
    cx: &Context,
) -> Result<()> {
    let r = &fit.report;
    report["max_residual"] = json!(r.max_residual);
    report["max_index"] = json!(r.max_index);
    report["rms"] = json!(r.rms);
    report["weighted_rss"] = json!(r.weighted_rss);
    report["control_points"] = json!(r.n_ctrl);
    report["knots"] = json!(fit.curve.knots().len());
    if let Some(l) = r.lambda {
        report["lambda"] = json!(l);
    }
    if a.per_point {
        report["residuals"] = json!(r.residuals);
    }
    if a.json {
        let object: Value = serde_json::from_str(&obj.to_json_pretty())?;
        let text = serde_json::to_string_pretty(&json!({ "object": object, "report": report }))?;
        return emit(a.out.output.as_deref(), text.as_bytes(), inputs, cx);
    }
    if !cx.is_quiet() {
        crate::output::report(&report_line(&report));
    }
    write_curve(&obj, Some(shown), &a.out, inputs, cx)
}

pub(super) fn report_line(r: &Value) -> String {
    let mut s = format!("fit: {} control points", r["control_points"]);
    if r["tolerance"].is_null() {
        s.push_str(&format!(
            ", residual max {} (point {}), RMS {}, weighted RSS {}",
            r["max_residual"], r["max_index"], r["rms"], r["weighted_rss"]
        ));
    } else {
        // the tolerance bounds the deviation (each point's distance to the curve, or to its
        // point at the data parameter with --parameter-deviation); the residuals are taken at
        // the parameters of those points, so they are the deviations and one line says both
        s.push_str(&format!(
            ", deviation max {} (point {}) within the tolerance {}, RMS {}, weighted RSS {}",
            r["max_deviation"], r["worst_index"], r["tolerance"], r["rms"], r["weighted_rss"]
        ));
    }
    for key in ["lambda", "s"] {
        if !r[key].is_null() {
            s.push_str(&format!(", {key} {}", r[key]));
        }
    }
    s
}
