//! The versioned JSON envelope of every lekalo object (see `docs/formats.md`).
//!
//! ```json
//! {"lekalo": 1, "type": "bspline_curve", "degree": 2,
//!  "knots": [0, 0, 1, 2, 3, 3], "control": [[1, 1], [2, 3], [4, 3]]}
//! ```
//!
//! `lekalo` is the format version ([`FORMAT_VERSION`]), `type` selects the object, the other
//! fields are the object's. Control points are rows (`[[x, y], …]`) or the flat form
//! `{"dim": 2, "data": [x0, y0, …]}`. Every read goes through the library's validating
//! constructor ([`BSplineCurve::new`] etc.), so a file can never hold an object that the library
//! would refuse. Unknown fields are errors (a misspelt `weigths` must not be ignored).
//!
//! New object kinds (surfaces, piecewise polynomials) are added as variants of [`Object`] with
//! a `type` name, a repr struct and two match arms; readers of older versions reject unknown
//! types by name.

use lekalo::{Arg, BSplineCurve, BezierCurve, Curve, NurbsCurve, Points};
use serde::de::IgnoredAny;
use serde::Deserialize;
use serde_json::{Map, Value};

use crate::error::{IoError, IoResult, Location};
use crate::flat::{self, FlatPoints};

/// The current format version, the value of the `"lekalo"` field.
pub const FORMAT_VERSION: u64 = 1;

/// A curve of any kind as the JSON envelope holds it: the library's [`lekalo::Curve`].
pub type Object = lekalo::Curve;

// The readers take the envelope's `lekalo` and `type` too (checked before, by `Head`), so
// that one typed pass reads the object straight from the text: no `serde_json::Value` tree,
// and a key given twice is an error (serde's derived readers refuse duplicate fields).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BezierJson {
    #[serde(rename = "lekalo")]
    _version: IgnoredAny,
    #[serde(rename = "type")]
    _kind: IgnoredAny,
    #[serde(deserialize_with = "flat::control")]
    control: FlatPoints,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BSplineJson {
    #[serde(rename = "lekalo")]
    _version: IgnoredAny,
    #[serde(rename = "type")]
    _kind: IgnoredAny,
    degree: usize,
    knots: Vec<f64>,
    #[serde(deserialize_with = "flat::control")]
    control: FlatPoints,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NurbsJson {
    #[serde(rename = "lekalo")]
    _version: IgnoredAny,
    #[serde(rename = "type")]
    _kind: IgnoredAny,
    degree: usize,
    knots: Vec<f64>,
    #[serde(deserialize_with = "flat::control")]
    control: FlatPoints,
    weights: Vec<f64>,
}

/// The envelope alone (`lekalo`, `type`); every other field is skipped without being stored.
#[derive(Deserialize)]
pub(crate) struct Head {
    lekalo: Option<Value>,
    #[serde(rename = "type")]
    kind: Option<Value>,
}

impl Head {
    /// Reads the envelope of `text`, refusing text that is not one JSON object.
    pub(crate) fn read(text: &str, at: &Location) -> IoResult<Head> {
        let line = |l: usize| at.clone().at_line(at.line.unwrap_or(1) + l.max(1) - 1);
        if !text.trim_start().starts_with('{') {
            if let Err(e) = serde_json::from_str::<IgnoredAny>(text) {
                return Err(IoError::syntax(
                    line(e.line()),
                    format!("not valid JSON: {e}"),
                ));
            }
            return Err(IoError::syntax(
                at.clone(),
                "expected a JSON object like {\"lekalo\": 1, \"type\": \"bspline_curve\", ...}",
            ));
        }
        serde_json::from_str::<Head>(text).map_err(|e| {
            let msg = flat::message(&e);
            if e.is_data() {
                let mut loc = line(e.line());
                if let Some(f) = backticked(&msg) {
                    loc = loc.at_field(f);
                }
                IoError::syntax(loc, format!("{msg}; each field may appear once"))
            } else {
                IoError::syntax(line(e.line()), format!("not valid JSON: {e}"))
            }
        })
    }

    /// The `type`, if it is a string.
    pub(crate) fn kind(&self) -> Option<&str> {
        self.kind.as_ref().and_then(Value::as_str)
    }
}

/// The `type` names this version reads, for error messages.
const KNOWN_TYPES: &str = "bezier_curve, bspline_curve, nurbs_curve";

/// The versioned JSON envelope of a curve (`docs/formats.md`): written and read with the file,
/// line and field of every error. Implemented for [`lekalo::Curve`].
pub trait CurveJson: Sized {
    /// The envelope as a JSON value (control points as rows).
    #[must_use]
    fn to_json_value(&self) -> Value;

    /// JSON text of the envelope, fields in a fixed order (`lekalo`, `type`, then the object's
    /// fields as in `docs/formats.md`), one control point per line, final newline.
    #[must_use]
    fn to_json_pretty(&self) -> String;

    /// One-line JSON (for JSON Lines), same field order.
    #[must_use]
    fn to_json_line(&self) -> String;

    /// Writes the JSON text of [`CurveJson::to_json_pretty`] (or, not `pretty`, of
    /// [`CurveJson::to_json_line`]) to `w` piece by piece, with no `Value` tree and no copy of
    /// the whole text: a curve of millions of control points costs a few megabytes of buffers,
    /// its long lists formatted in blocks on all cores.
    ///
    /// # Errors
    /// The writer's.
    fn write_json(&self, w: &mut dyn std::io::Write, pretty: bool) -> std::io::Result<()>;

    /// Reads one curve from JSON text. `source` names the input in error messages.
    ///
    /// ```
    /// use lekalo_io::{CurveJson, Object};
    /// let text = r#"{"lekalo": 1, "type": "bspline_curve", "degree": 2,
    ///                "knots": [0, 0, 1, 2, 3, 3], "control": [[1, 1], [2, 3], [4, 3]]}"#;
    /// let obj = Object::from_json_str(text, "example.json").unwrap();
    /// assert_eq!(obj.type_name(), "bspline_curve");
    /// let bad = text.replace("[0, 0, 1, 2, 3, 3]", "[0, 0, 2, 1, 3, 3]");
    /// let e = Object::from_json_str(&bad, "example.json").unwrap_err().to_string();
    /// assert!(e.starts_with("example.json:2: field `knots`"), "{e}");
    /// ```
    ///
    /// # Errors
    /// [`IoError::Syntax`] for malformed JSON, a missing or unsupported version, an unknown
    /// type, missing or unknown fields; [`IoError::Invalid`] when the library's constructor
    /// rejects the data (the field is named).
    fn from_json_str(text: &str, source: &str) -> IoResult<Self>;

    /// Reads one curve from a parsed JSON value; `text` (the value's source text, possibly
    /// empty) is used to find the line of a field named in an error.
    ///
    /// # Errors
    /// As [`CurveJson::from_json_str`].
    fn from_json_value(value: Value, at: &Location, text: &str) -> IoResult<Self>;
}

impl CurveJson for Curve {
    fn to_json_value(&self) -> Value {
        let mut m = Map::new();
        m.insert("lekalo".into(), Value::from(FORMAT_VERSION));
        m.insert("type".into(), Value::from(self.type_name()));
        let rows = |p: &Points| Value::from(p.iter().map(Value::from).collect::<Vec<_>>());
        if let Some(knots) = self.explicit_knots() {
            m.insert("degree".into(), Value::from(self.degree()));
            m.insert("knots".into(), Value::from(knots.as_slice().to_vec()));
        }
        m.insert("control".into(), rows(&self.control_points()));
        if let Some(w) = self.weights() {
            m.insert("weights".into(), Value::from(w));
        }
        Value::Object(m)
    }

    fn to_json_pretty(&self) -> String {
        format_json(self, true)
    }

    fn to_json_line(&self) -> String {
        format_json(self, false)
    }

    fn write_json(&self, w: &mut dyn std::io::Write, pretty: bool) -> std::io::Result<()> {
        crate::json_write::write_object(self, w, pretty, crate::json_write::BLOCK)
    }

    fn from_json_str(text: &str, source: &str) -> IoResult<Curve> {
        let text = crate::atomic::strip_bom_str(text);
        let at = Location::new(source);
        let head = Head::read(text, &at)?;
        curve_from_head(text, &at, &head)
    }

    fn from_json_value(value: Value, at: &Location, text: &str) -> IoResult<Curve> {
        if !value.is_object() {
            return Err(IoError::syntax(
                at.clone(),
                "expected a JSON object like {\"lekalo\": 1, \"type\": \"bspline_curve\", ...}",
            ));
        }
        let own = value.to_string();
        let head = Head::read(&own, &at.clone())?;
        curve_from_head(&own, at, &head).map_err(|e| match e {
            // point messages at the lines of the original text
            IoError::Syntax {
                at: mut loc,
                message,
            } => {
                if let Some(f) = &loc.field {
                    loc.line = line_of_field(text, f).map(|l| at.line.unwrap_or(1) + l - 1);
                }
                IoError::Syntax { at: loc, message }
            }
            IoError::Invalid { at: mut loc, error } => {
                if let Some(f) = &loc.field {
                    loc.line = line_of_field(text, f).map(|l| at.line.unwrap_or(1) + l - 1);
                }
                IoError::Invalid { at: loc, error }
            }
            other => other,
        })
    }
}

fn format_json(c: &Curve, pretty: bool) -> String {
    let mut bytes = Vec::new();
    // writing into a Vec cannot fail
    let _ = c.write_json(&mut bytes, pretty);
    String::from_utf8(bytes).unwrap_or_default()
}

/// Reads the object of `text` whose envelope `head` has been read; `at` may carry the line
/// where `text` starts (JSON Lines).
pub(crate) fn curve_from_head(text: &str, at: &Location, head: &Head) -> IoResult<Curve> {
    let field_at = |field: &str| {
        let mut loc = at.clone().at_field(field);
        if let Some(line) = line_of_field(text, field) {
            loc.line = Some(at.line.unwrap_or(1) + line - 1);
        }
        loc
    };
    match &head.lekalo {
        Some(v) if v.as_u64() == Some(FORMAT_VERSION) => {}
        Some(v) => {
            return Err(IoError::syntax(
                field_at("lekalo"),
                format!(
                "format version {v} is not supported; this lekalo reads version {FORMAT_VERSION}"
            ),
            ))
        }
        None => {
            return Err(IoError::syntax(
                at.clone().at_field("lekalo"),
                format!("missing the format version; add \"lekalo\": {FORMAT_VERSION}"),
            ))
        }
    }
    let Some(kind) = head.kind() else {
        return Err(IoError::syntax(
            at.clone().at_field("type"),
            format!("missing or non-string object type; use one of {KNOWN_TYPES}"),
        ));
    };
    let decode_err = |e: serde_json::Error| {
        let msg = flat::message(&e);
        let loc = match backticked(&msg) {
            // the second occurrence, where the parser stopped
            Some(f) if msg.starts_with("duplicate field") => {
                let mut loc = at.clone().at_field(f);
                loc.line = Some(at.line.unwrap_or(1) + e.line().max(1) - 1);
                loc
            }
            Some(f) if !f.contains('[') && !f.contains('.') => field_at(&f),
            Some(f) => {
                let top = f.split(['[', '.']).next().unwrap_or_default().to_string();
                let mut loc = at.clone().at_field(top);
                loc.line = Some(at.line.unwrap_or(1) + e.line().max(1) - 1);
                loc
            }
            None => at.clone(),
        };
        // the location names the field; say it once
        let msg = match msg.strip_prefix("field `") {
            Some(rest) => rest
                .split_once("`: ")
                .map_or(msg.clone(), |(_, m)| m.to_string()),
            None => msg,
        };
        IoError::syntax(loc, format!("{kind}: {msg}"))
    };
    let invalid = |e: lekalo::Error| IoError::Invalid {
        at: field_of(&e).map_or_else(|| at.clone(), field_at),
        error: e,
    };
    let control = |p: FlatPoints| {
        p.into_points().map_err(|e| IoError::Invalid {
            at: field_at("control"),
            error: e,
        })
    };
    match kind {
        "bezier_curve" => {
            let r: BezierJson = serde_json::from_str(text).map_err(decode_err)?;
            BezierCurve::new(control(r.control)?)
                .map(Object::Bezier)
                .map_err(invalid)
        }
        "bspline_curve" => {
            let r: BSplineJson = serde_json::from_str(text).map_err(decode_err)?;
            BSplineCurve::new(r.degree, r.knots, control(r.control)?)
                .map(Object::BSpline)
                .map_err(invalid)
        }
        "nurbs_curve" => {
            let r: NurbsJson = serde_json::from_str(text).map_err(decode_err)?;
            NurbsCurve::new(r.degree, r.knots, control(r.control)?, r.weights)
                .map(Object::Nurbs)
                .map_err(invalid)
        }
        other => Err(IoError::syntax(
            at.clone().at_field("type"),
            format!("unknown object type \"{other}\"; this lekalo reads {KNOWN_TYPES}"),
        )),
    }
}

/// The field that a library error is about: the field of its argument key, or of its kind.
fn field_of(e: &lekalo::Error) -> Option<&'static str> {
    match (e.arg(), e) {
        (Some(Arg::Knots), _) | (None, lekalo::Error::EmptyDomain { .. }) => Some("knots"),
        (Some(Arg::Weights), _) => Some("weights"),
        (Some(Arg::ControlPoints), _) => Some("control"),
        (None, lekalo::Error::Degree { .. }) => Some("degree"),
        _ => None,
    }
}

/// The first name in backticks in a serde message, e.g. `knots` in "missing field \`knots\`".
fn backticked(msg: &str) -> Option<String> {
    let start = msg.find('`')? + 1;
    let len = msg[start..].find('`')?;
    Some(msg[start..start + len].to_string())
}

/// 1-based line of the first `"field"` key in `text`, if present.
fn line_of_field(text: &str, field: &str) -> Option<usize> {
    let key = format!("\"{field}\"");
    let pos = text.find(&key)?;
    Some(text[..pos].matches('\n').count() + 1)
}

/// Reads JSON Lines: one object per non-blank line (lines starting with `#` are comments).
/// Returns `(line number, object or error)` for every object line, so a batch can report every
/// bad line and go on with the good ones.
#[must_use]
pub fn read_json_lines(text: &str, source: &str) -> Vec<(usize, IoResult<Object>)> {
    crate::atomic::strip_bom_str(text)
        .lines()
        .enumerate()
        .filter(|(_, l)| {
            let t = l.trim();
            !t.is_empty() && !t.starts_with('#')
        })
        .map(|(i, l)| {
            let at = Location::new(source).at_line(i + 1);
            let obj = Head::read(l, &at).and_then(|head| curve_from_head(l, &at, &head));
            (i + 1, obj)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const LECTURE: &str = r#"{
  "lekalo": 1,
  "type": "bspline_curve",
  "degree": 2,
  "knots": [0, 0, 1, 2, 3, 3],
  "control": [[1, 1], [2, 3], [4, 3]]
}"#;

    #[test]
    fn round_trip_every_type() {
        let b = Object::from_json_str(LECTURE, "t").unwrap();
        let Object::BSpline(c) = &b else {
            panic!("wrong type")
        };
        assert_eq!(c.eval(1.5).unwrap(), vec![17.0 / 8.0, 11.0 / 4.0]);
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let ctrl = Points::from_2d(&[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).unwrap();
        let objs = [
            b.clone(),
            Object::Bezier(BezierCurve::new(ctrl.clone()).unwrap()),
            Object::Nurbs(
                NurbsCurve::new(
                    2,
                    vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                    ctrl,
                    vec![1.0, w, 1.0],
                )
                .unwrap(),
            ),
        ];
        for o in objs {
            let back = Object::from_json_str(&o.to_json_pretty(), "t").unwrap();
            assert_eq!(back, o);
            let back = Object::from_json_str(&o.to_json_line(), "t").unwrap();
            assert_eq!(back, o);
            assert!(!o.to_json_line().contains('\n'));
        }
    }

    #[test]
    fn pretty_layout() {
        let o = Object::from_json_str(LECTURE, "t").unwrap();
        assert_eq!(
            o.to_json_pretty(),
            "{\n  \"lekalo\": 1,\n  \"type\": \"bspline_curve\",\n  \"degree\": 2,\n  \"knots\": [0.0, 0.0, 1.0, 2.0, 3.0, 3.0],\n  \"control\": [\n    [1.0, 1.0],\n    [2.0, 3.0],\n    [4.0, 3.0]\n  ]\n}\n"
        );
        assert_eq!(
            o.to_json_line(),
            r#"{"lekalo":1,"type":"bspline_curve","degree":2,"knots":[0.0,0.0,1.0,2.0,3.0,3.0],"control":[[1.0,1.0],[2.0,3.0],[4.0,3.0]]}"#
        );
    }

    #[test]
    fn flat_control_points_accepted() {
        let text = LECTURE.replace(
            "[[1, 1], [2, 3], [4, 3]]",
            r#"{"dim": 2, "data": [1, 1, 2, 3, 4, 3]}"#,
        );
        let a = Object::from_json_str(&text, "t").unwrap();
        assert_eq!(a, Object::from_json_str(LECTURE, "t").unwrap());
    }

    fn err(text: &str) -> String {
        Object::from_json_str(text, "c.json")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn errors_name_line_and_field() {
        let e = err(&LECTURE.replace("\"lekalo\": 1", "\"lekalo\": 9"));
        assert!(
            e.starts_with("c.json:2: field `lekalo`: format version 9"),
            "{e}"
        );
        let e = err(&LECTURE.replace("  \"lekalo\": 1,\n", ""));
        assert!(
            e.contains("field `lekalo`: missing the format version"),
            "{e}"
        );
        let e = err(&LECTURE.replace("bspline_curve", "spline"));
        assert!(e.contains("unknown object type \"spline\""), "{e}");
        let e = err(&LECTURE.replace("\"degree\"", "\"degre\""));
        assert!(
            e.starts_with("c.json:4: field `degre`: bspline_curve: unknown field"),
            "{e}"
        );
        let e = err(&LECTURE.replace("  \"degree\": 2,\n", ""));
        assert!(
            e.contains("field `degree`: bspline_curve: missing field"),
            "{e}"
        );
        let e = err(&LECTURE.replace("[0, 0, 1, 2, 3, 3]", "[0, 0, 1, 2, 3]"));
        assert!(e.starts_with("c.json:5: field `knots`"), "{e}");
        let e = err(&LECTURE.replace("[2, 3]", "[2, 3, 5]"));
        assert!(e.starts_with("c.json:6: field `control`"), "{e}");
        let e = err("{\"lekalo\": 1,\n \"type\": ");
        assert!(e.starts_with("c.json:2: not valid JSON"), "{e}");
        let e = err("[1, 2]");
        assert!(e.contains("expected a JSON object"), "{e}");
        let nurbs = r#"{"lekalo":1,"type":"nurbs_curve","degree":1,"knots":[0,0,1,1],
            "control":[[0,0],[1,1]],"weights":[1,-1]}"#;
        let e = err(nurbs);
        assert!(
            e.starts_with("c.json:2: field `weights`: weight 1 is -1"),
            "{e}"
        );
        let e = err(r#"{"lekalo":1,"type":"bezier_curve","control":[]}"#);
        assert!(e.contains("field `control`"), "{e}");
    }

    #[test]
    fn json_lines_report_each_line() {
        let good = Object::from_json_str(LECTURE, "t").unwrap().to_json_line();
        let text = format!("# comment\n{good}\n\n{{\"lekalo\":1}}\n{good}\n");
        let r = read_json_lines(&text, "many.jsonl");
        assert_eq!(r.len(), 3);
        assert_eq!(r[0].0, 2);
        assert!(r[0].1.is_ok());
        let e = r[1].1.as_ref().unwrap_err().to_string();
        assert!(e.starts_with("many.jsonl:4: field `type`"), "{e}");
        assert_eq!(r[2].0, 5);
    }
}
