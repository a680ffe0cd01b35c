//! The JSON API: one handler per construction, each a thin call of the library.
//!
//! Requests and answers carry curves in the CLI's object format (`docs/formats.md`,
//! `{"lekalo": 1, "type": "bspline_curve", ...}`), read by [`Object::from_json_str`], so the
//! same validation and the same messages apply as in `lekalo`. Every answer that returns a
//! curve also returns its drawing ([`CurveView`]): samples, control polygon, knots on the
//! curve and, when asked, the curvature comb and the basis functions.
//!
//! Sizes are bounded twice: by the body limit of the server (`docs/serve.md`) and by the
//! budget of [`Limits`](crate::Limits) ([`crate::budget`]), checked for every curve a request
//! sends or asks for before anything is computed, so that a small request cannot ask for a
//! huge computation. The handlers run in the [`crate::pool`], and their drawings are stopped
//! at the deadline through the job's progress hook.

use axum::body::Bytes;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use lekalo::vocabulary::{self, EndKind};
use lekalo::{
    BSplineCurve, BezierCurve, CurveInterpolation, EndConditions, KnotPlacement, KnotVector,
    NurbsCurve, Parametrization, Points,
};
use lekalo_io::CurveJson;
use lekalo_io::Object;

use crate::words::word;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::answer::{answer, SMALL};
use crate::error::{ApiError, ApiResult};

use crate::error::field_of;
use crate::pool::Job;
pub(crate) use crate::view::{default_samples, view_answer};
pub use crate::view::{
    view, view_in, BasisFunction, BasisView, Comb, CurveView, KnotMark, ViewOptions, MAX_SAMPLES,
};
/// Most points (data points, control points, polyline corners) one request may carry (the
/// default of [`Limits::max_points`](crate::Limits::max_points)).
pub const MAX_POINTS: usize = 10_000;
/// Highest degree of a curve the API reads or builds (the default of
/// [`Limits::max_degree`](crate::Limits::max_degree)): the editor draws every basis function,
/// whose count grows with the degree.
pub const MAX_API_DEGREE: usize = 64;

/// Reads a request body: JSON of type `T`, with the field of a type error named
/// (`points[3]`, `degree`).
pub(crate) fn parse<T: DeserializeOwned>(body: &Bytes) -> ApiResult<T> {
    let de = &mut serde_json::Deserializer::from_slice(body);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let whole = e.path().to_string() == "." && !e.inner().is_syntax() && !e.inner().is_eof();
        whole
            .then(|| unplaced(body))
            .flatten()
            .unwrap_or_else(|| request_error(e))
    })
}

/// The view options every drawing request takes ([`ViewOptionsFlat`]).
const VIEW_FIELDS: &[&str] = &["samples", "comb", "basis_samples", "at"];

/// The error of a valid JSON `body` that serde refused without a path: a body that is not an
/// object (`[1, 2]`, `null`), refused by what it is rather than by the handler's type name; or
/// a bad view option, which the requests take through `#[serde(flatten)]`, where serde
/// loses the path (`"samples": -1` was refused with the field `""`): read again on its own, it
/// is named. `None` when neither is the cause.
fn unplaced(body: &Bytes) -> Option<ApiError> {
    let value: Value = serde_json::from_slice(body).ok()?;
    let Value::Object(map) = value else {
        let what = match value {
            Value::Array(_) => "an array",
            Value::String(_) => "a string",
            Value::Number(_) => "a number",
            Value::Bool(_) => "true or false",
            _ => "null",
        };
        return Some(ApiError::bad(
            "",
            format!(
                "the request body is {what}; it must be a JSON object of the route's fields \
                 (docs/openapi.json)"
            ),
        ));
    };
    let view: serde_json::Map<String, Value> = map
        .into_iter()
        .filter(|(k, _)| VIEW_FIELDS.contains(&k.as_str()))
        .collect();
    serde_path_to_error::deserialize::<_, ViewOptionsFlat>(Value::Object(view))
        .err()
        .map(request_error)
}

/// The answer to a body that is not the request's JSON: the field of a type error, or
/// "not valid JSON" for the body as a whole (field `""`).
pub(crate) fn request_error(e: serde_path_to_error::Error<serde_json::Error>) -> ApiError {
    let path = e.path().to_string();
    let inner = e.into_inner();
    if inner.is_syntax() || inner.is_eof() {
        return ApiError::bad("", format!("not valid JSON: {inner}"));
    }
    if path == "." {
        return ApiError::bad("", inner.to_string());
    }
    // the field is named: its message is shown next to its control, where the position of the
    // value in the request's text ("at line 1 column 58") means nothing
    let text = inner.to_string();
    let position = format!(" at line {} column {}", inner.line(), inner.column());
    let message = text.strip_suffix(&position).unwrap_or(&text).to_string();
    ApiError::bad(path, message)
}

/// A curve object in the CLI's format, read as the CLI reads a file named `field`, with its
/// degree and control points within the job's limits ([`Limits::check_curve`](crate::Limits::check_curve)).
pub(crate) fn curve(job: &Job<'_>, value: &Value, field: &str) -> ApiResult<Object> {
    let text = value.to_string();
    let obj = Object::from_json_str(&text, field).map_err(|e| ApiError::io(field, &e))?;
    job.limits.check_curve(&obj, field)?;
    Ok(obj)
}

/// 2-D points as the library's [`Points`], with the count bounded.
pub(crate) fn points(job: &Job<'_>, rows: &[Vec<f64>], field: &str) -> ApiResult<Points> {
    job.limits.check_points(rows.len(), field)?;
    if let Some(i) = rows.iter().position(|r| r.len() != 2) {
        return Err(ApiError::bad(
            format!("{field}[{i}]"),
            format!(
                "point {i} has {} coordinates; the editor's points are (x, y)",
                rows[i].len()
            ),
        ));
    }
    Points::from_rows(rows).map_err(|e| ApiError::lib_or(field, &e))
}

/// The answer of an order change: the view with its degree, real degree and the deviation of
/// an approximate reduction.
#[derive(Debug, Serialize)]
struct BezierAnswer {
    view: CurveView,
    degree: usize,
    real_degree: usize,
    deviation: Option<Deviation>,
}

/// Deviation of an approximate degree reduction (`lekalo bezier`).
#[derive(Debug, Serialize)]
struct Deviation {
    sampled: f64,
    bound: f64,
}

fn bezier_answer(view: CurveView, real_degree: usize, deviation: Option<Deviation>) -> Response {
    let size = view.size_hint() + SMALL;
    let a = BezierAnswer {
        degree: view.degree,
        view,
        real_degree,
        deviation,
    };
    answer(&a, size)
}

/// `POST /api/evaluate`: the drawing of a curve.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct EvaluateRequest {
    curve: Value,
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// [`ViewOptions`] as fields of a request (serde's `flatten` and `deny_unknown_fields` do not
/// combine, so the fields are repeated here and in the other requests through this struct).
#[derive(Debug, Default, Deserialize)]
pub(crate) struct ViewOptionsFlat {
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_count")]
    samples: Option<usize>,
    #[serde(default)]
    comb: bool,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_count")]
    basis_samples: Option<usize>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    at: Option<f64>,
}

impl ViewOptionsFlat {
    pub(crate) fn options(&self) -> ViewOptions {
        ViewOptions {
            samples: self.samples.unwrap_or_else(default_samples),
            comb: self.comb,
            basis_samples: self.basis_samples,
            at: self.at,
        }
    }
}

pub(crate) fn evaluate(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: EvaluateRequest = parse(body)?;
    let obj = curve(job, &r.curve, "curve")?;
    Ok(view_answer(&view_in(
        job,
        &obj,
        &r.view.options(),
        "curve",
    )?))
}

/// The parametrisation of a request: a word of [`lekalo::vocabulary::PARAMETRIZATION`]
/// (chord length when left out), or the exponent `e` of `|ΔQ|^e` when given.
pub(crate) fn parametrization(
    word: Option<&str>,
    exponent: Option<f64>,
) -> ApiResult<Parametrization> {
    let p = crate::words::word(
        &vocabulary::PARAMETRIZATION,
        "parametrization",
        word,
        Parametrization::ChordLength,
    )?;
    Ok(exponent.map_or(p, Parametrization::Exponent))
}

fn default_degree() -> usize {
    3
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct InterpolateRequest {
    #[serde(deserialize_with = "crate::fields::rows")]
    points: Vec<Vec<f64>>,
    #[serde(default = "default_degree")]
    #[serde(deserialize_with = "crate::fields::count")]
    degree: usize,
    /// A word of [`lekalo::vocabulary::PARAMETRIZATION`].
    #[serde(default)]
    parametrization: Option<String>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    exponent: Option<f64>,
    /// A word of [`lekalo::vocabulary::KNOT_PLACEMENT`].
    #[serde(default)]
    knots: Option<String>,
    /// A word of [`lekalo::vocabulary::END_CONDITION`].
    #[serde(default)]
    end: Option<String>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_numbers")]
    start_derivative: Option<Vec<f64>>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_numbers")]
    end_derivative: Option<Vec<f64>>,
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// `POST /api/interpolate`: global interpolation (`lekalo interpolate`).
pub(crate) fn interpolate(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: InterpolateRequest = parse(body)?;
    let pts = points(job, &r.points, "points")?;
    let degree = job.limits.check_degree(r.degree, "degree")?;
    let param = parametrization(r.parametrization.as_deref(), r.exponent)?;
    let kind = word(
        &vocabulary::END_CONDITION,
        "end",
        r.end.as_deref(),
        EndKind::Free,
    )?;
    let end = kind
        .condition(r.start_derivative.clone(), r.end_derivative.clone())
        .map_err(|e| {
            // a kind that needs both derivatives lacks one; any other was given one
            let needs_both = matches!(kind, EndKind::Derivatives | EndKind::Second);
            let at_fault = if needs_both {
                r.start_derivative.is_none()
            } else {
                r.start_derivative.is_some()
            };
            let field = if at_fault {
                "start_derivative"
            } else {
                "end_derivative"
            };
            ApiError::lib(field, &e)
        })?;
    let knots = word(
        &vocabulary::KNOT_PLACEMENT,
        "knots",
        r.knots.as_deref(),
        KnotPlacement::Auto,
    )?;
    let c = CurveInterpolation::new(degree)
        .parametrization(param)
        .knot_placement(knots)
        .end_condition(end)
        .interpolate(pts.as_view())
        .map_err(|e| ApiError::lib(interpolation_field(&e), &e))?;
    let out = Object::BSpline(c);
    Ok(view_answer(&view_in(
        job,
        &out,
        &r.view.options(),
        "points",
    )?))
}

/// The request field an interpolation error is about: the degree, the field of the error's
/// key (knots, exponent, a derivative), or the points.
fn interpolation_field(e: &lekalo::Error) -> &'static str {
    match e {
        lekalo::Error::Degree { .. } => "degree",
        _ => field_of(e).unwrap_or("points"),
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum BezierOp {
    Elevate,
    ReduceExact,
    ReduceApprox,
}

impl crate::fields::Choice for BezierOp {
    const WORDS: &'static [(&'static str, Self)] = &[
        ("elevate", Self::Elevate),
        ("reduce_exact", Self::ReduceExact),
        ("reduce_approx", Self::ReduceApprox),
    ];
}

#[derive(Debug, Clone, Copy, Default)]
enum Ends {
    Free,
    #[default]
    Points,
    Tangents,
}

impl crate::fields::Choice for Ends {
    const WORDS: &'static [(&'static str, Self)] = &[
        ("free", Self::Free),
        ("points", Self::Points),
        ("tangents", Self::Tangents),
    ];
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BezierRequest {
    curve: Value,
    #[serde(deserialize_with = "crate::fields::choice")]
    op: BezierOp,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_count")]
    by: Option<usize>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_count")]
    target: Option<usize>,
    #[serde(default, deserialize_with = "crate::fields::choice")]
    ends: Ends,
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// `POST /api/bezier`: order change of a Bezier curve (`lekalo bezier`, document 004).
pub(crate) fn bezier(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: BezierRequest = parse(body)?;
    let Object::Bezier(c) = curve(job, &r.curve, "curve")? else {
        return Err(ApiError::bad(
            "curve.type",
            "order change works on a bezier_curve; convert the curve first",
        ));
    };
    let (out, deviation) = match r.op {
        BezierOp::Elevate => {
            let by = r.by.unwrap_or(1);
            job.limits
                .check_degree(c.degree().saturating_add(by), "by")?;
            let e = c
                .elevate_degree(by)
                .map_err(|e| ApiError::lib_or("by", &e))?;
            (e, None)
        }
        BezierOp::ReduceExact => (c.reduce_degree_exact(), None),
        BezierOp::ReduceApprox => {
            let target = r.target.unwrap_or_else(|| c.degree().saturating_sub(1));
            job.limits.check_degree(target, "target")?;
            let ends = match r.ends {
                Ends::Free => EndConditions::Free,
                Ends::Points => EndConditions::Points,
                Ends::Tangents => EndConditions::Tangents,
            };
            let red = c
                .reduce_degree_approx(target, ends)
                .map_err(|e| ApiError::lib_or("target", &e))?;
            (
                red.curve,
                Some(Deviation {
                    sampled: red.max_deviation_sampled,
                    bound: red.max_deviation_bound,
                }),
            )
        }
    };
    let real_degree = out.real_degree();
    let v = view_in(job, &Object::Bezier(out), &r.view.options(), "curve")?;
    Ok(bezier_answer(v, real_degree, deviation))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct KnotRequest {
    curve: Value,
    #[serde(deserialize_with = "crate::fields::number")]
    t: f64,
    #[serde(default = "one")]
    #[serde(deserialize_with = "crate::fields::count")]
    times: usize,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    tolerance: Option<f64>,
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

fn one() -> usize {
    1
}

/// `POST /api/knot/insert` (P&T A5.1, `lekalo knot insert`).
pub(crate) fn knot_insert(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: KnotRequest = parse(body)?;
    let obj = curve(job, &r.curve, "curve")?;
    let out = obj
        .insert_knot(r.t, r.times)
        .map_err(|e| ApiError::lib(knot_field(&e), &e))?;
    Ok(view_answer(&view_in(
        job,
        &out,
        &r.view.options(),
        "times",
    )?))
}

/// `POST /api/knot/remove` (Tiller's removal, P&T A5.8, `lekalo knot remove`); answers the
/// curve and how many times the knot was removed within the tolerance.
pub(crate) fn knot_remove(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: KnotRequest = parse(body)?;
    let obj = curve(job, &r.curve, "curve")?;
    let tol = r
        .tolerance
        .unwrap_or_else(|| obj.default_removal_tolerance());
    let (out, removed) = obj
        .remove_knot(r.t, r.times, tol)
        .map_err(|e| ApiError::lib(knot_field(&e), &e))?;
    #[derive(Serialize)]
    struct Removed {
        view: CurveView,
        removed: usize,
    }
    let view = view_in(job, &out, &r.view.options(), "curve")?;
    let size = view.size_hint() + SMALL;
    Ok(answer(&Removed { view, removed }, size))
}

/// The field of a knot insertion or removal error: the count (`times`), the removal
/// tolerance, or the knot `t` (by the error's key, [`field_of`]).
fn knot_field(e: &lekalo::Error) -> &'static str {
    field_of(e).unwrap_or("t")
}

/// `POST /api/import`: the body is the CLI's JSON text of one curve; answers its drawing, or
/// the CLI's error for it.
pub(crate) fn import(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let text = lekalo_io::utf8_text(body, "file").map_err(|e| ApiError::io("file", &e))?;
    let obj = Object::from_json_str(text, "file").map_err(|e| ApiError::io("file", &e))?;
    Ok(view_answer(&view_in(
        job,
        &obj,
        &ViewOptions::default(),
        "file",
    )?))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ExportRequest {
    curve: Value,
}

/// `POST /api/export/json`: the curve as the CLI writes it, as a download.
pub(crate) fn export_json(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: ExportRequest = parse(body)?;
    let obj = curve(job, &r.curve, "curve")?;
    Ok(download(
        obj.to_json_pretty(),
        "application/json",
        "curve.json",
    ))
}

/// Fixed STEP timestamp, so that the same curve gives the same file (as in the CLI).
const STEP_TIMESTAMP: &str = "2000-01-01T00:00:00";

/// `POST /api/export/step`: the curve as an ISO 10303-21 file (`lekalo convert -o x.step`).
pub(crate) fn export_step(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: ExportRequest = parse(body)?;
    let obj = curve(job, &r.curve, "curve")?;
    let mut w = lekalo_io::StepWriter::new("curve");
    w.add_object(&obj).map_err(|e| ApiError::io("curve", &e))?;
    Ok(download(
        w.finish(STEP_TIMESTAMP),
        "application/step",
        "curve.step",
    ))
}

fn download(text: String, mime: &'static str, name: &str) -> Response {
    (
        [
            (header::CONTENT_TYPE, mime.to_string()),
            (
                header::CONTENT_DISPOSITION,
                format!("attachment; filename=\"{name}\""),
            ),
        ],
        text,
    )
        .into_response()
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BuildRequest {
    #[serde(deserialize_with = "crate::fields::rows")]
    control: Vec<Vec<f64>>,
    #[serde(deserialize_with = "crate::fields::count")]
    degree: usize,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_numbers")]
    knots: Option<Vec<f64>>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_numbers")]
    weights: Option<Vec<f64>>,
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// `POST /api/bspline`: a B-spline (or, with `weights`, NURBS) curve from control points and
/// degree, with the given knots or the clamped uniform ones (`lekalo make bspline`); the
/// library's constructor validates (P&T eq. 2.1 conditions: sorted knots, `m = n + p + 1`).
pub(crate) fn bspline(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: BuildRequest = parse(body)?;
    let control = points(job, &r.control, "control")?;
    let degree = job.limits.check_degree(r.degree, "degree")?;
    if let Some(k) = &r.knots {
        job.limits.check_points(k.len(), "knots")?;
    }
    let field = |e: &lekalo::Error| match e {
        lekalo::Error::Degree { .. } => "degree",
        lekalo::Error::TooFew { .. } => "control",
        lekalo::Error::NonPositiveWeight { .. } => "weights",
        _ => field_of(e).unwrap_or("knots"),
    };
    let knots = match r.knots {
        Some(k) => k,
        None => KnotVector::clamped_uniform(degree, control.len())
            .map_err(|e| ApiError::lib(field(&e), &e))?
            .into_vec(),
    };
    let obj = match r.weights {
        Some(w) => NurbsCurve::new(degree, knots, control, w).map(Object::Nurbs),
        None => BSplineCurve::new(degree, knots, control).map(Object::BSpline),
    }
    .map_err(|e| ApiError::lib(field(&e), &e))?;
    Ok(view_answer(&view_in(
        job,
        &obj,
        &r.view.options(),
        "control",
    )?))
}

/// `POST /api/bezier/build`: a Bezier curve from its control points, drawn.
pub(crate) fn bezier_build(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Req {
        #[serde(deserialize_with = "crate::fields::rows")]
        control: Vec<Vec<f64>>,
        #[serde(flatten)]
        view: ViewOptionsFlat,
    }
    let r: Req = parse(body)?;
    let c = BezierCurve::new(points(job, &r.control, "control")?)
        .map_err(|e| ApiError::lib_or("control", &e))?;
    let real = c.real_degree();
    let v = view_in(job, &Object::Bezier(c), &r.view.options(), "control")?;
    Ok(bezier_answer(v, real, None))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A curve through 100 points of a wave (the editor's round-trip benchmark), and a NURBS
    /// curve in 3-D.
    fn curves() -> Vec<Object> {
        let rows: Vec<Vec<f64>> = (0..100)
            .map(|k| {
                let x = f64::from(k) / 10.0;
                vec![x, x.sin() + 0.1 * (10.0 * x).cos()]
            })
            .collect();
        let c = CurveInterpolation::new(3)
            .parametrization(Parametrization::Centripetal)
            .interpolate(
                points(&Job::unbounded(&crate::Limits::default()), &rows, "points")
                    .expect("points")
                    .as_view(),
            )
            .expect("interpolation");
        let p = Points::from_flat(
            3,
            vec![0.0, 0.0, 0.0, 1.0, 2.0, 0.5, 3.0, 2.0, 1.0, 4.0, 0.0, 2.0],
        )
        .expect("points");
        let n = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0],
            p,
            vec![1.0, 2.0, 0.5, 1.0],
        )
        .expect("nurbs");
        vec![Object::BSpline(c), Object::Nurbs(n)]
    }

    #[test]
    fn the_size_hint_of_a_view_holds_its_text_without_waste() {
        for obj in curves() {
            for (samples, comb, basis_samples) in [(1000, false, Some(300)), (10, true, None)] {
                let opt = ViewOptions {
                    samples,
                    comb,
                    basis_samples,
                    at: Some(0.5),
                };
                let v = view(&obj, &opt).expect("view");
                let text = serde_json::to_vec(&v).expect("text");
                let hint = v.size_hint();
                assert!(
                    text.len() <= hint && hint <= 2 * text.len() + 1024,
                    "{} with {opt:?}: {} bytes, hint {hint}",
                    obj.type_name(),
                    text.len()
                );
            }
        }
    }

    #[test]
    fn the_view_s_curve_reads_back_to_the_curve() {
        for obj in curves() {
            let v = view(&obj, &ViewOptions::default()).expect("view");
            let text = serde_json::to_string(&v).expect("text");
            let back: Value = serde_json::from_str(&text).expect("json");
            let read = Object::from_json_str(&back["curve"].to_string(), "curve").expect("curve");
            assert_eq!(read, obj);
        }
    }
}
