//! `POST /api/project`, `POST /api/measure` and `POST /api/intersect`: the closest point of a
//! curve to a point, the arc length with parameters at given lengths, and the intersections of
//! two curves or the self-intersections of one, each with its kind of contact (`lekalo
//! project`, `lekalo measure`, `lekalo intersect`), thin calls of [`lekalo::QueryCurve`]
//! (`docs/theory/queries.md`).

use axum::body::Bytes;
use axum::response::Response;
use lekalo::QueryCurve;
use lekalo_io::Object;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::answer::{answer, NUMBER_BYTES, SMALL};
use crate::api::{curve, parse};
use crate::error::{ApiError, ApiResult};
use crate::pool::Job;

/// The curve of an object, prepared for queries (as `lekalo measure` and `lekalo project`).
fn query_curve(obj: &Object) -> ApiResult<QueryCurve> {
    obj.to_query().map_err(|e| ApiError::lib_or("curve", &e))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ProjectRequest {
    curve: Value,
    #[serde(deserialize_with = "crate::fields::numbers")]
    point: Vec<f64>,
}

/// The closest point, as `lekalo project --json` names it.
#[derive(Debug, Serialize)]
struct Projection {
    t: f64,
    point: Vec<f64>,
    distance: f64,
}

/// `POST /api/project`: the point of the curve closest to `point` (global: every piece whose
/// bounding box could hold a closer point is searched, `QueryCurve::project`).
pub(crate) fn project(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: ProjectRequest = parse(body)?;
    let q = query_curve(&curve(job, &r.curve, "curve")?)?;
    if r.point.len() != q.dim() {
        return Err(ApiError::bad(
            "point",
            format!(
                "the query point has dimension {}, the curve {}",
                r.point.len(),
                q.dim()
            ),
        ));
    }
    let p = q
        .project(&r.point)
        .map_err(|e| ApiError::lib_or("point", &e))?;
    Ok(answer(
        &Projection {
            t: p.t,
            point: p.point,
            distance: p.distance,
        },
        SMALL,
    ))
}

fn default_rtol() -> f64 {
    1e-12
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MeasureRequest {
    curve: Value,
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::numbers")]
    at_length: Vec<f64>,
    /// The arc length's relative tolerance (`lekalo measure --rtol`).
    #[serde(default = "default_rtol")]
    #[serde(deserialize_with = "crate::fields::number")]
    rtol: f64,
}

#[derive(Debug, Serialize)]
struct AtLength {
    length: f64,
    t: f64,
    point: Vec<f64>,
}

#[derive(Debug, Serialize)]
struct Measure {
    length: f64,
    error_estimate: f64,
    domain: [f64; 2],
    at_length: Vec<AtLength>,
}

/// `POST /api/measure`: the arc length (with its error estimate) and the parameter, and the
/// point, at each length of `at_length` from the start (`lekalo measure --at-length`).
pub(crate) fn measure(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: MeasureRequest = parse(body)?;
    job.limits.check_points(r.at_length.len(), "at_length")?;
    let obj = curve(job, &r.curve, "curve")?;
    let q = query_curve(&obj)?;
    let table = q
        .arc_length(r.rtol)
        .map_err(|e| ApiError::lib_or("curve", &e))?;
    let params = table
        .param_at_batch(&r.at_length)
        .map_err(|e| ApiError::lib_or("at_length", &e))?;
    let at_length = r
        .at_length
        .iter()
        .zip(params)
        .map(|(&length, t)| {
            let point = obj.eval(t).map_err(|e| ApiError::lib_or("curve", &e))?;
            Ok(AtLength { length, t, point })
        })
        .collect::<ApiResult<Vec<_>>>()?;
    let (a, b) = q.domain();
    let size = SMALL + at_length.len() * 4 * NUMBER_BYTES;
    Ok(answer(
        &Measure {
            length: table.total(),
            error_estimate: table.error_estimate(),
            domain: [a, b],
            at_length,
        },
        size,
    ))
}

/// The default distance under which points count as common (`lekalo intersect`'s for curves).
fn default_intersect_tolerance() -> f64 {
    1e-9
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct IntersectRequest {
    curve: Value,
    /// The second curve; without it, the self-intersections of `curve`.
    #[serde(default)]
    other: Option<Value>,
    #[serde(default = "default_intersect_tolerance")]
    #[serde(deserialize_with = "crate::fields::number")]
    tolerance: f64,
}

#[derive(Debug, Serialize)]
struct Intersections {
    /// One answer each, as `lekalo intersect --json` writes it
    /// ([`lekalo_io::curve_intersection_json`]).
    intersections: Vec<Value>,
}

/// `POST /api/intersect`: every crossing, tangent contact, contact at an end, near miss and
/// overlap of `curve` with `other` within `tolerance` (`QueryCurve::intersect`), or, without
/// `other`, the self-intersections of the planar `curve` (`QueryCurve::self_intersections`);
/// each answer with its kind (`docs/theory/queries.md#kinds-of-contact`).
pub(crate) fn intersect(job: &Job<'_>, body: &Bytes) -> ApiResult<Response> {
    let r: IntersectRequest = parse(body)?;
    let qa = query_curve(&curve(job, &r.curve, "curve")?)?;
    let found = match &r.other {
        Some(other) => {
            let qb = query_curve(&curve(job, other, "other")?)?;
            qa.intersect(&qb, r.tolerance)
        }
        None => qa.self_intersections(r.tolerance),
    }
    .map_err(|e| ApiError::lib_or("curve", &e))?;
    let size = SMALL + found.len() * (qa.dim() + 6) * NUMBER_BYTES;
    Ok(answer(
        &Intersections {
            intersections: found
                .iter()
                .map(lekalo_io::curve_intersection_json)
                .collect(),
        },
        size,
    ))
}
