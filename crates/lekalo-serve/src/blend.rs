//! The blending routes (document 001, `lekalo blend`): two curves deformed one into the other
//! (`/api/blend/deform`), every corner of a polyline rounded (`/api/blend/corners`) and the
//! curve through points by blending local parabolas (`/api/blend/spline`).
//!
//! Each answers the view of the result with the continuity the library gives it
//! ([`BlendAnswer`]): the knots of these curves have the multiplicity of the pieces' Bezier
//! form (`2k + 1` at a corner's joins), which alone would promise only `C^0`, so the
//! continuity is taken from the library's construction, not read off the knots.

use axum::body::Bytes;
use axum::response::Response;
use lekalo::blend::{
    check_deformation_continuity, deformation_bezier_degree, max_deformation_continuity,
};
use lekalo::{
    smooth_polyline_corners, Arg, BezierCurve, BlendSplineOptions, BlendSplinePieces, CornerWindow,
    Deformation, Parabolas, SplineParameters,
};
use lekalo_io::Object;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::answer::{answer, SMALL};
use crate::api::{curve, parse, points, view_in, CurveView, ViewOptionsFlat};
use crate::error::{field_of, ApiError, ApiResult};
use crate::pool::Job;

/// The answer of a blending route: the view of the curve, and `continuity`, the `k` of the
/// library's result: for the deformation the order of its contact with the first curve at the
/// start and with the second at the end ([`Deformation::continuity`]); for the corners and the
/// curve through points the `C^k` at every join of its pieces
/// ([`lekalo::SmoothedPolyline::continuity`], [`BlendSplinePieces::continuity_degree`]).
#[derive(Debug, Serialize)]
pub struct BlendAnswer {
    /// The drawing of the curve (its fields at the top level of the answer).
    #[serde(flatten)]
    pub view: CurveView,
    /// The continuity degree `k` of the result.
    pub continuity: usize,
}

/// Refuses a continuity `k` whose curve, of degree `degree`, is above the server's limit, naming
/// both: the request gave `k`, and the degree is what it costs.
fn degree_of_k(job: &Job<'_>, k: usize, degree: usize) -> ApiResult<()> {
    let max = job.limits.max_degree;
    if degree > max {
        return Err(ApiError::bad(
            "continuity",
            format!(
                "continuity k = {k} makes a curve of degree {degree}, above the server's limit \
                 {max} (lekalo serve --max-degree): lower k, or use the CLI (lekalo blend)"
            ),
        ));
    }
    Ok(())
}

fn blend_answer(view: CurveView, continuity: usize) -> Response {
    let size = view.size_hint() + SMALL;
    answer(&BlendAnswer { view, continuity }, size)
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DeformRequest {
    first: Value,
    second: Value,
    #[serde(deserialize_with = "crate::fields::count")]
    continuity: usize,
    /// The view options (`samples`, `comb`, `basis_samples`, `at`), as the other routes.
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// `POST /api/blend/deform`: two curves with common end points joined by the deformation of
/// document 001 with continuity `k` (`lekalo blend deform`); the exact Bezier form is returned.
pub(crate) fn deform(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: DeformRequest = parse(body)?;
    let first = bezier_of(curve(job, &r.first, "first")?, "first")?;
    let second = bezier_of(curve(job, &r.second, "second")?, "second")?;
    // the blend's degree (2k − 1) + max(d₁, d₂) grows with k (document 001): bounded before it
    // is built, and a k out of range is refused naming the range the server's limit leaves
    let (d1, d2) = (first.degree(), second.degree());
    let max_k = max_deformation_continuity(d1, d2, job.limits.max_degree);
    if r.continuity > max_k {
        degree_of_k(
            job,
            r.continuity,
            deformation_bezier_degree(d1, d2, r.continuity),
        )?;
    }
    check_deformation_continuity(r.continuity, max_k.max(1))
        .map_err(|e| ApiError::lib("continuity", &e))?;
    let d = Deformation::new(&first, &second, r.continuity)
        .map_err(|e| ApiError::lib(deform_field(&e), &e))?;
    let b = d
        .to_bezier()
        .map_err(|e| ApiError::lib_or("continuity", &e))?;
    let opts = r.view.options();
    let view = view_in(job, &Object::Bezier(b), &opts, "continuity")?;
    Ok(blend_answer(view, d.continuity()))
}

/// The field of a deformation error: the field of its argument key (the continuity, its
/// range), the continuity for the degree it sets, or the second curve (its dimension, its end
/// points that must meet the first's).
fn deform_field(e: &lekalo::Error) -> &'static str {
    match e {
        lekalo::Error::Degree { .. } => "continuity",
        _ => field_of(e).unwrap_or("second"),
    }
}

/// A Bezier curve (a B-spline without interior knots counts too).
fn bezier_of(obj: Object, field: &str) -> ApiResult<BezierCurve> {
    match obj {
        Object::Bezier(c) => Ok(c),
        other => Err(ApiError::bad(
            format!("{field}.type"),
            format!(
                "the editor blends Bezier curves; {field} is a {}",
                other.display_name()
            ),
        )),
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CornersRequest {
    #[serde(deserialize_with = "crate::fields::rows")]
    points: Vec<Vec<f64>>,
    #[serde(deserialize_with = "crate::fields::count")]
    continuity: usize,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    fraction: Option<f64>,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    length: Option<f64>,
    /// The view options (`samples`, `comb`, `basis_samples`, `at`), as the other routes.
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// `POST /api/blend/corners`: every corner of a polyline smoothed with continuity `k` over a
/// window given as a `fraction` of the shorter segment (0.25 when neither is given) or a
/// `length` (`lekalo blend corners`, [`lekalo::smooth_polyline_corners`]).
pub(crate) fn corners(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: CornersRequest = parse(body)?;
    let pts = points(job, &r.points, "points")?;
    // the curve has degree 2k + 1: bounded before it is built
    degree_of_k(
        job,
        r.continuity,
        r.continuity.saturating_mul(2).saturating_add(1),
    )?;
    let (window, field) = match (r.fraction, r.length) {
        (Some(_), Some(_)) => {
            return Err(ApiError::bad(
                "length",
                "give the corner window as fraction or as length, not both",
            ))
        }
        (None, Some(l)) => (CornerWindow::Length(l), "length"),
        (f, None) => (CornerWindow::Fraction(f.unwrap_or(0.25)), "fraction"),
    };
    // the library names the argument an error is about: the window is the field given
    let s = smooth_polyline_corners(pts.as_view(), window, r.continuity).map_err(|e| {
        let field = match e.arg() {
            Some(Arg::CornerWindow | Arg::CornerFraction | Arg::CornerLength) => field,
            _ => field_of(&e).unwrap_or("points"),
        };
        ApiError::lib(field, &e)
    })?;
    let opts = r.view.options();
    let continuity = s.continuity();
    let view = view_in(job, &Object::BSpline(s.into_curve()), &opts, "points")?;
    Ok(blend_answer(view, continuity))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BlendSplineRequest {
    #[serde(deserialize_with = "crate::fields::rows")]
    points: Vec<Vec<f64>>,
    #[serde(deserialize_with = "crate::fields::count")]
    continuity: usize,
    #[serde(default)]
    closed: bool,
    /// The view options (`samples`, `comb`, `basis_samples`, `at`), as the other routes.
    #[serde(flatten)]
    view: ViewOptionsFlat,
}

/// `POST /api/blend/spline`: the curve through the points by blending local parabolas with
/// continuity `k` (`lekalo blend spline --local parabolas`, document 001).
pub(crate) fn spline(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: BlendSplineRequest = parse(body)?;
    let pts = points(job, &r.points, "points")?;
    // the blend's degree grows with k (document 001): bounded before it is built
    job.limits.check_degree(r.continuity, "continuity")?;
    let options = BlendSplineOptions {
        continuity: r.continuity,
        closed: r.closed,
        parameters: SplineParameters::Uniform,
    };
    let field = |e: &lekalo::Error| match e {
        lekalo::Error::Degree { .. } => "continuity",
        _ => field_of(e).unwrap_or("points"),
    };
    // piece by piece, so that the deadline stops it and the size is known before the NURBS
    // is assembled
    let pieces = BlendSplinePieces::new(pts.as_view(), &Parabolas, options, &job.progress)
        .map_err(|e| ApiError::lib(field(&e), &e))?;
    degree_of_k(job, r.continuity, pieces.degree())?;
    job.limits.check_points(pieces.control_count(), "points")?;
    let n = pieces
        .to_nurbs(&job.progress)
        .map_err(|e| ApiError::lib_or("points", &e))?;
    let opts = r.view.options();
    let view = view_in(job, &Object::Nurbs(n), &opts, "points")?;
    Ok(blend_answer(view, pieces.continuity_degree()))
}
