//! The JSON envelope of tensor-product splines in `N` parameters (`docs/formats.md`):
//! `"bspline_tensor"` and `"nurbs_tensor"`, read through [`lekalo::TensorBSpline::new`] and
//! [`lekalo::TensorNurbs::new`].
//!
//! ```json
//! {"lekalo": 1, "type": "bspline_tensor", "degrees": [1, 1, 1],
//!  "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]], "shape": [2, 2, 2],
//!  "control": [[0], [0], [0], [0], [0], [0], [0], [1]]}
//! ```
//!
//! The control points are listed with the first direction slowest (`shape` is the net size
//! of each direction, `knots[a].len() − degrees[a] − 1`); a `nurbs_tensor` adds one weight per
//! control point in the same order.

use lekalo::{Arg, Points, Tensor, TensorBSpline, TensorNurbs, What};
use serde::Deserialize;

use crate::error::{IoError, IoResult, Location};
use crate::object::FORMAT_VERSION;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TensorJson {
    lekalo: u64,
    #[serde(rename = "type")]
    kind: String,
    degrees: Vec<usize>,
    knots: Vec<Vec<f64>>,
    shape: Vec<usize>,
    control: Vec<Vec<f64>>,
    #[serde(default)]
    weights: Option<Vec<f64>>,
}

/// The `type` name of a tensor spline's envelope.
#[must_use]
pub fn tensor_type_name(t: &Tensor) -> &'static str {
    match t {
        Tensor::BSpline(_) => "bspline_tensor",
        Tensor::Nurbs(_) => "nurbs_tensor",
    }
}

/// Reads a `bspline_tensor` or `nurbs_tensor` (a `nurbs_tensor` needs `weights`, a
/// `bspline_tensor` refuses them).
///
/// ```
/// let t = lekalo_io::read_tensor(r#"{"lekalo": 1, "type": "bspline_tensor",
///   "degrees": [1, 1, 1], "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]],
///   "shape": [2, 2, 2], "control": [[0], [0], [0], [0], [0], [0], [0], [1]]}"#, "t.json")?;
/// assert_eq!(t.n_vars(), 3);
/// let text = lekalo_io::tensor_to_json(&t);
/// assert_eq!(lekalo_io::read_tensor(&text, "again")?, t);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`IoError::Syntax`] for malformed JSON (with the line), a wrong version or type, missing or
/// unknown fields; [`IoError::Invalid`] naming the field (`control`, `knots`, `shape`,
/// `weights`) when the library's constructor rejects the data.
pub fn read_tensor(text: &str, source: &str) -> IoResult<Tensor> {
    let r: TensorJson = serde_json::from_str(crate::atomic::strip_bom_str(text)).map_err(|e| {
        IoError::syntax(
            Location::new(source).at_line(e.line()),
            format!("tensor spline: {e}"),
        )
    })?;
    let at = |field: &str| Location::new(source).at_field(field);
    if r.lekalo != FORMAT_VERSION {
        return Err(IoError::syntax(
            at("lekalo"),
            format!(
                "format version {} is not supported; this lekalo reads version {FORMAT_VERSION}",
                r.lekalo
            ),
        ));
    }
    let rational = match r.kind.as_str() {
        "bspline_tensor" => false,
        "nurbs_tensor" => true,
        other => {
            return Err(IoError::syntax(
                at("type"),
                format!(
                    "expected an object of type \"bspline_tensor\" or \"nurbs_tensor\", found \"{other}\""
                ),
            ))
        }
    };
    let invalid = |field: &str, error| IoError::Invalid {
        at: at(field),
        error,
    };
    // the net sizes the knots imply, checked against `shape` before the points are copied
    let derived: Vec<usize> = r
        .knots
        .iter()
        .zip(&r.degrees)
        .map(|(k, &p)| k.len().saturating_sub(p + 1))
        .collect();
    if r.shape.len() != r.degrees.len() || (r.knots.len() == r.degrees.len() && derived != r.shape)
    {
        return Err(IoError::syntax(
            at("shape"),
            format!(
                "shape {:?} is not the net size the knots and degrees give, {:?} (knots[a].len() − degrees[a] − 1 in each direction)",
                r.shape, derived
            ),
        ));
    }
    let control = Points::from_rows(&r.control).map_err(|e| invalid("control", e))?;
    let field_of = |e: &lekalo::Error| match e {
        lekalo::Error::LengthMismatch { .. } | lekalo::Error::TooLarge { .. } => "control",
        lekalo::Error::NonPositiveWeight { .. } => "weights",
        _ => "knots",
    };
    match (rational, r.weights) {
        (false, None) => TensorBSpline::new(r.degrees, r.knots, control)
            .map(Tensor::BSpline)
            .map_err(|e| invalid(field_of(&e), e)),
        (true, Some(w)) => {
            if w.len() != control.len() {
                return Err(invalid(
                    "weights",
                    lekalo::Error::LengthMismatch {
                        what: What::of(Arg::Weights, "weights (one per control point)"),
                        expected: control.len(),
                        got: w.len(),
                    },
                ));
            }
            if let Some(i) = w.iter().position(|x| !x.is_finite() || *x <= 0.0) {
                return Err(invalid(
                    "weights",
                    lekalo::Error::NonPositiveWeight {
                        index: i,
                        weight: w[i],
                    },
                ));
            }
            TensorNurbs::new(r.degrees, r.knots, control, &w)
                .map(Tensor::Nurbs)
                .map_err(|e| invalid(field_of(&e), e))
        }
        (false, Some(_)) => Err(IoError::syntax(
            at("weights"),
            "a bspline_tensor has no weights; write \"type\": \"nurbs_tensor\" for a rational spline",
        )),
        (true, None) => Err(IoError::syntax(
            at("weights"),
            "a nurbs_tensor needs \"weights\", one per control point",
        )),
    }
}

/// JSON text of a tensor spline's envelope (fields in a fixed order, one control point per
/// line; full precision).
#[must_use]
pub fn tensor_to_json(t: &Tensor) -> String {
    let list = |x: &[f64]| serde_json::to_string(x).unwrap_or_default();
    let knots: Vec<String> = t.knots().iter().map(|k| list(k.as_slice())).collect();
    let ctrl = t.control_points();
    let rows: Vec<String> = ctrl.iter().map(list).collect();
    let weights = t
        .weights()
        .map(|w| format!(",\n  \"weights\": {}", list(&w)))
        .unwrap_or_default();
    format!(
        "{{\n  \"lekalo\": {FORMAT_VERSION},\n  \"type\": \"{}\",\n  \"degrees\": {},\n  \"knots\": [\n    {}\n  ],\n  \"shape\": {},\n  \"control\": [\n    {}\n  ]{weights}\n}}\n",
        tensor_type_name(t),
        serde_json::to_string(t.degrees()).unwrap_or_default(),
        knots.join(",\n    "),
        serde_json::to_string(t.shape()).unwrap_or_default(),
        rows.join(",\n    "),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trilinear() -> Tensor {
        let k = vec![0.0, 0.0, 1.0, 1.0];
        let net = Points::from_flat(2, (0..16).map(f64::from).collect()).unwrap();
        Tensor::BSpline(
            TensorBSpline::new(vec![1, 1, 1], vec![k.clone(), k.clone(), k], net).unwrap(),
        )
    }

    #[test]
    fn round_trip_both_kinds_and_dispatch() {
        let t = trilinear();
        let text = tensor_to_json(&t);
        assert_eq!(read_tensor(&text, "t").unwrap(), t);
        let shape = crate::Shape::from_json_str(&text, "t").unwrap();
        assert_eq!(shape.type_name(), "bspline_tensor");
        assert_eq!(shape.to_json_pretty(), text);
        let Tensor::BSpline(b) = &t else {
            unreachable!("a B-spline")
        };
        let w: Vec<f64> = (0..8).map(|i| 1.0 + f64::from(i) / 8.0).collect();
        let n = Tensor::Nurbs(
            TensorNurbs::new(
                b.degrees().to_vec(),
                b.knots().iter().map(|k| k.as_slice().to_vec()).collect(),
                b.control_points().clone(),
                &w,
            )
            .unwrap(),
        );
        let text = tensor_to_json(&n);
        assert!(text.contains("\"nurbs_tensor\""), "{text}");
        assert_eq!(read_tensor(&text, "n").unwrap(), n);
    }

    #[test]
    fn errors_name_the_field() {
        let text = tensor_to_json(&trilinear());
        let err = |t: &str| read_tensor(t, "x.json").unwrap_err().to_string();
        let e = err(&text.replace("\"shape\": [2,2,2]", "\"shape\": [2,2,3]"));
        assert!(e.contains("field `shape`"), "{e}");
        let e = err(&text.replace("[0.0,0.0,1.0,1.0]", "[0.0,1.0,0.0,1.0]"));
        assert!(e.contains("field `knots`"), "{e}");
        let e = err(&text.replace("[14.0,15.0]", "[14.0]"));
        assert!(e.contains("field `control`"), "{e}");
        let e = err(&text.replace("\"lekalo\": 1", "\"lekalo\": 7"));
        assert!(e.contains("format version 7"), "{e}");
        let e = err(&text.replace("\n}", ",\n  \"weights\": [1]\n}"));
        assert!(e.contains("field `weights`"), "{e}");
        let e = err(&text.replace("bspline_tensor", "nurbs_tensor"));
        assert!(e.contains("needs \"weights\""), "{e}");
        let e = err(&text.replace("\"degrees\"", "\"degree\""));
        assert!(e.contains("x.json"), "{e}");
    }
}
