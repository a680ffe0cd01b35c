//! Writing answers: JSON text serialized straight from the library's types into one buffer
//! sized for the answer, with no `serde_json::Value` tree and no `Vec` per point.
//!
//! - [`answer`] turns a serializable answer into a 200 response, its text written into a
//!   buffer reserved at the answer's expected size (`CurveView::size_hint`), so that a view of
//!   thousands of points is written without the buffer growing and being copied on the way.
//! - [`rows`] writes a [`Points`] as rows `[[x, y], …]` from its flat storage.
//! - [`object`] writes a curve in the CLI's object format, the text of
//!   [`Object::to_json_line`] byte for byte (a test below checks it), so the curve of an answer
//!   is read back by `lekalo` and by the API exactly.
//!
//! Numbers are written by `serde_json`: the shortest text that reads back to the same `f64`,
//! `null` for a number that is not finite.

use axum::body::Body;
use axum::http::{header, HeaderValue};
use axum::response::{IntoResponse, Response};
use lekalo::Points;
use lekalo_io::{Object, FORMAT_VERSION};
use serde::ser::{SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};

/// Bytes one number takes at most in most answers: 17 significant digits, sign, point,
/// exponent and the separator.
pub(crate) const NUMBER_BYTES: usize = 24;

/// Bytes reserved for an answer of a few numbers.
pub(crate) const SMALL: usize = 256;

/// The 200 answer with `v` as JSON, written into one buffer of `size` bytes reserved at once
/// (it grows if `size` was too small).
pub(crate) fn answer(v: &impl Serialize, size: usize) -> Response {
    let mut buf = Vec::with_capacity(size);
    match serde_json::to_writer(&mut buf, v) {
        Ok(()) => (
            [(
                header::CONTENT_TYPE,
                HeaderValue::from_static("application/json"),
            )],
            Body::from(buf),
        )
            .into_response(),
        // the answer types serialize maps with string keys only; a failure is a defect of
        // this crate, answered as such rather than with half a text
        Err(e) => crate::ApiError {
            status: axum::http::StatusCode::INTERNAL_SERVER_ERROR,
            message: format!("writing the answer failed: {e}"),
            field: None,
        }
        .into_response(),
    }
}

/// Serializes `p` as rows `[[x, y], …]` (`serialize_with` helper).
///
/// # Errors
/// The serializer's.
pub(crate) fn rows<S: Serializer>(p: &Points, s: S) -> Result<S::Ok, S::Error> {
    let mut seq = s.serialize_seq(Some(p.len()))?;
    for row in p.iter() {
        seq.serialize_element(row)?;
    }
    seq.end()
}

/// Serializes a curve as the CLI writes it on one line ([`Object::to_json_line`]): `lekalo`,
/// `type`, then `degree`, `knots`, `control` and `weights` as the type has them
/// (`docs/formats.md`).
///
/// # Errors
/// The serializer's.
pub(crate) fn object<S: Serializer>(obj: &Object, s: S) -> Result<S::Ok, S::Error> {
    struct Control<'a>(&'a Points);
    impl Serialize for Control<'_> {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            rows(self.0, s)
        }
    }
    let knots = obj.explicit_knots();
    let degree = knots.map(|_| obj.degree());
    let control = obj.control_points();
    let weights = obj.weights();
    let mut m = s.serialize_map(None)?;
    m.serialize_entry("lekalo", &FORMAT_VERSION)?;
    m.serialize_entry("type", obj.type_name())?;
    if let Some(d) = degree {
        m.serialize_entry("degree", &d)?;
    }
    if let Some(k) = knots {
        m.serialize_entry("knots", k.as_slice())?;
    }
    m.serialize_entry("control", &Control(&control))?;
    if let Some(w) = weights {
        m.serialize_entry("weights", &w)?;
    }
    m.end()
}

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::{BSplineCurve, BezierCurve, NurbsCurve};
    use lekalo_io::CurveJson;

    struct Curve(Object);
    impl Serialize for Curve {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            object(&self.0, s)
        }
    }

    fn curves() -> Vec<Object> {
        let p = Points::from_2d(&[[0.0, 0.1], [1.5, 2.0], [3.0, -2.25e-7], [4.0, 1e21]])
            .expect("points");
        let knots = vec![0.0, 0.0, 0.0, 0.3, 1.0, 1.0, 1.0];
        vec![
            Object::Bezier(BezierCurve::new(p.clone()).expect("bezier")),
            Object::BSpline(BSplineCurve::new(2, knots.clone(), p.clone()).expect("bspline")),
            Object::Nurbs(
                NurbsCurve::new(2, knots, p, vec![1.0, 0.5, 2.0, 1.0 / 3.0]).expect("nurbs"),
            ),
        ]
    }

    #[test]
    fn a_curve_is_written_as_the_cli_writes_it_on_one_line() {
        for obj in curves() {
            let text = serde_json::to_string(&Curve(obj.clone())).expect("text");
            assert_eq!(text, obj.to_json_line(), "{}", obj.type_name());
            // and it reads back to the same curve
            assert_eq!(
                Object::from_json_str(&text, "answer").expect("read back"),
                obj
            );
        }
    }

    #[test]
    fn rows_are_the_points_and_non_finite_numbers_are_null() {
        #[derive(Serialize)]
        struct R(#[serde(serialize_with = "rows")] Points);
        let p = Points::from_flat(3, vec![1.0, 0.5, -2.0, 3.0, 1e-300, 7.0]).expect("points");
        assert_eq!(
            serde_json::to_string(&R(p)).expect("text"),
            "[[1.0,0.5,-2.0],[3.0,1e-300,7.0]]"
        );
        assert_eq!(
            serde_json::to_string(&[f64::NAN, 1.0]).expect("text"),
            "[null,1.0]"
        );
    }
}
