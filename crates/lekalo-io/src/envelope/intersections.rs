//! The JSON of intersection answers, as `lekalo intersect --json` writes them and the
//! editor's `POST /api/intersect` returns them: every answer names its kind of contact
//! (`docs/theory/queries.md#kinds-of-contact`), points carry the order of a tangent contact or
//! the gap of a near miss, overlaps their parameter intervals.

use lekalo::query::{Contact, CurveIntersection, PlaneIntersection, SurfaceIntersection};
use serde_json::{json, Map, Value};

/// The JSON object of a point answer: its kind, the given parameter fields and the point, then
/// the order of a tangent contact or the gap of a near miss.
fn point_json(contact: Contact, params: &[(&str, f64)], point: &[f64]) -> Value {
    let mut m = Map::new();
    m.insert("kind".into(), json!(contact.name()));
    for (k, t) in params {
        m.insert((*k).into(), json!(t));
    }
    m.insert("point".into(), json!(point));
    if let Some(order) = contact.order() {
        m.insert("order".into(), json!(order));
    }
    if let Contact::NearMiss { gap } = contact {
        m.insert("gap".into(), json!(gap));
    }
    Value::Object(m)
}

/// One answer of a curve–curve intersection (`QueryCurve::intersect`, `self_intersections`):
/// `{kind, t_a, t_b, point[, order][, gap]}` or an overlap `{kind, a: [t0, t1], b: [t0, t1]}`
/// (`docs/theory/queries.md#kinds-of-contact`).
pub fn curve_intersection_json(h: &CurveIntersection) -> Value {
    match h {
        CurveIntersection::Point {
            t_a,
            t_b,
            point,
            contact,
        } => point_json(*contact, &[("t_a", *t_a), ("t_b", *t_b)], point),
        CurveIntersection::Overlap { a, b } => {
            json!({"kind": h.contact().name(), "a": [a.0, a.1], "b": [b.0, b.1]})
        }
    }
}

/// One answer of a curve–plane intersection: `{kind, t, point[, order][, gap]}` or an overlap
/// `{kind, t: [t0, t1]}`.
pub fn plane_intersection_json(h: &PlaneIntersection) -> Value {
    match h {
        PlaneIntersection::Point { t, point, contact } => point_json(*contact, &[("t", *t)], point),
        PlaneIntersection::Overlap { t } => json!({"kind": h.contact().name(), "t": [t.0, t.1]}),
    }
}

/// One answer of a curve–surface intersection: `{kind, t, point, uv[, order][, gap]}` or an
/// overlap `{kind, t: [t0, t1], uv: [[u0, v0], [u1, v1]]}`.
pub fn surface_intersection_json(h: &SurfaceIntersection) -> Value {
    match h {
        SurfaceIntersection::Point {
            t,
            uv,
            point,
            contact,
        } => {
            let mut v = point_json(*contact, &[("t", *t)], point);
            v["uv"] = json!([uv.0, uv.1]);
            v
        }
        SurfaceIntersection::Overlap { t, uv } => json!({
            "kind": h.contact().name(),
            "t": [t.0, t.1],
            "uv": [[uv.0 .0, uv.0 .1], [uv.1 .0, uv.1 .1]],
        }),
    }
}
