//! The envelope of a face (`"type": "face"`, docs/formats.md): its surface, its loops of edges
//! with their curves and pcurves as nested envelopes, the ids and name it had in its file.
//!
//! ```json
//! {"lekalo": 1, "type": "face", "id": 70, "name": "plate", "surface_id": 5, "same_sense": true,
//!  "surface": {"lekalo": 1, "type": "bspline_surface", …},
//!  "outer": [{"edge_id": 41, "curve": {"lekalo": 1, "type": "bspline_curve", …},
//!             "pcurve": {"lekalo": 1, "type": "bspline_curve", …}}, …],
//!  "inner": [[…]], "pcurves": null}
//! ```

use lekalo::topology::{Edge, Face, Loop};
use lekalo::{Curve, Surface};
use serde_json::Value;

use crate::error::{IoError, IoResult, Location};
use crate::object::{CurveJson, FORMAT_VERSION};
use crate::shape::Shape;
use crate::step_read::{StepFace, STEP_SHARED_VERTEX_RTOL};

/// The edges of a loop as a JSON list, each envelope in its writer's field order.
fn edges_text(lp: &Loop, ids: Option<&Vec<u64>>) -> String {
    let edges: Vec<String> = lp
        .edges()
        .iter()
        .enumerate()
        .map(|(k, e)| {
            let id = ids
                .and_then(|ids| ids.get(k))
                .map_or(String::new(), |id| format!(r#""edge_id":{id},"#));
            let pcurve = e
                .pcurve()
                .map_or("null".to_string(), CurveJson::to_json_line);
            format!(
                r#"{{{id}"curve":{},"pcurve":{pcurve}}}"#,
                e.curve().to_json_line()
            )
        })
        .collect();
    format!("[{}]", edges.join(","))
}

/// The face envelope of `f` on one line (JSON Lines): `id`, `name`, `surface_id`, `same_sense`,
/// `surface`, `outer` and `inner` (each edge's `edge_id`, `curve` and `pcurve`, `null` when it
/// has none) and `pcurves` (why the edges have no pcurves, or `null`).
///
/// ```
/// let text = "ISO-10303-21;HEADER;ENDSEC;DATA;
/// #1=CARTESIAN_POINT('',(0.,0.,0.));#2=DIRECTION('',(0.,0.,1.));#3=DIRECTION('',(1.,0.,0.));
/// #4=AXIS2_PLACEMENT_3D('',#1,#2,#3);#5=PLANE('',#4);#6=CIRCLE('',#4,1.);
/// #7=CARTESIAN_POINT('',(1.,0.,0.));#8=VERTEX_POINT('',#7);#9=EDGE_CURVE('',#8,#8,#6,.T.);
/// #10=ORIENTED_EDGE('',*,*,#9,.T.);#11=EDGE_LOOP('',(#10));#12=FACE_OUTER_BOUND('',#11,.T.);
/// #13=ADVANCED_FACE('disc',(#12),#5,.T.);ENDSEC;END-ISO-10303-21;";
/// let r = lekalo_io::read_step_faces(text, "disc.step", usize::MAX)?;
/// let line = lekalo_io::face_to_json_line(&r.faces[0]);
/// assert!(line.starts_with(r#"{"lekalo":1,"type":"face","id":13,"name":"disc""#));
/// assert_eq!(lekalo_io::read_face(&line, "disc.jsonl")?, r.faces[0]);
/// # Ok::<(), lekalo_io::IoError>(())
/// ```
#[must_use]
pub fn face_to_json_line(f: &StepFace) -> String {
    let text = |x: &str| Value::from(x).to_string();
    let inner: Vec<String> = f
        .face
        .inner()
        .iter()
        .enumerate()
        .map(|(i, lp)| edges_text(lp, f.edge_ids.get(i + 1)))
        .collect();
    format!(
        r#"{{"lekalo":{FORMAT_VERSION},"type":"face","id":{},"name":{},"surface_id":{},"same_sense":{},"surface":{},"outer":{},"inner":[{}],"pcurves":{}}}"#,
        f.id,
        text(&f.name),
        f.surface_id,
        f.face.same_sense(),
        Shape::Surface(f.face.surface().clone()).to_json_line(),
        edges_text(f.face.outer(), f.edge_ids.first()),
        inner.join(","),
        f.pcurves.as_deref().map_or("null".to_string(), text),
    )
}

/// Reads a face envelope ([`face_to_json_line`]), checked as [`Face::new`] checks it: loops
/// closed within [`STEP_SHARED_VERTEX_RTOL`] of the model size, the largest gap the STEP
/// reader accepts (in a loop its file's vertices close), so that every face it reads comes back
/// from its JSON line (the envelope has no vertices to tell the two tolerances apart).
/// `id`, `name`, `surface_id`,
/// `edge_id`, `same_sense` (true) and `pcurves` may be left out.
///
/// # Errors
/// [`IoError::Syntax`] naming the field for malformed JSON, a wrong version or type, a missing
/// `surface` or `outer`; the readers' errors for the nested surface and curves (the field
/// named, e.g. `outer[2].pcurve`); [`IoError::Invalid`] when [`Face::new`] refuses the loops.
pub fn read_face(text: &str, source: &str) -> IoResult<StepFace> {
    let at = Location::new(source);
    let v: Value = serde_json::from_str(crate::atomic::strip_bom_str(text))
        .map_err(|e| IoError::syntax(at.clone().at_line(e.line()), format!("face: {e}")))?;
    let field = |name: &str| at.clone().at_field(name);
    let err = |name: &str, why: String| IoError::syntax(field(name), why);
    if v.get("lekalo").and_then(Value::as_u64) != Some(FORMAT_VERSION) {
        return Err(err(
            "lekalo",
            format!("expected format version {FORMAT_VERSION}"),
        ));
    }
    if v.get("type").and_then(Value::as_str) != Some("face") {
        return Err(err("type", "expected an object of type \"face\"".into()));
    }
    // the optional fields: left out (or null) takes the default; any other type or an id that
    // is not a whole number of 64 bits is an error naming the field, never a silent default
    let whole = |x: &Value, name: &str| {
        x.as_u64().ok_or_else(|| {
            err(
                name,
                format!("{x} is not an id: give a whole number from 0 to 2^64 − 1"),
            )
        })
    };
    let given = |x: &Value, name: &str| v.get(name).is_some() && !x.is_null();
    let null = Value::Null;
    let id = match v.get("id").unwrap_or(&null) {
        x if given(x, "id") => whole(x, "id")?,
        _ => 0,
    };
    let surface_id = match v.get("surface_id").unwrap_or(&null) {
        x if given(x, "surface_id") => whole(x, "surface_id")?,
        _ => 0,
    };
    let text = |name: &str| -> IoResult<Option<String>> {
        match v.get(name) {
            None | Some(Value::Null) => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(x) => Err(err(name, format!("{x} is not a text: give a JSON string"))),
        }
    };
    let name = text("name")?.unwrap_or_default();
    let pcurves = text("pcurves")?;
    let same_sense = match v.get("same_sense") {
        None | Some(Value::Null) => true,
        Some(Value::Bool(b)) => *b,
        Some(x) => return Err(err("same_sense", format!("{x} is not true or false"))),
    };
    let Some(sv) = v.get("surface") else {
        return Err(err("surface", "a face needs its surface".into()));
    };
    let surface: Surface =
        match Shape::from_json_str(&sv.to_string(), &format!("{source}: surface"))? {
            Shape::Surface(s) => s,
            other => {
                return Err(err(
                    "surface",
                    format!("expected a surface, found a {}", other.type_name()),
                ))
            }
        };
    let read_loop = |lv: &Value, what: &str| -> IoResult<(Loop, Vec<u64>)> {
        let Some(items) = lv.as_array() else {
            return Err(err(what, "expected a list of edges".into()));
        };
        let mut edges = Vec::with_capacity(items.len());
        let mut ids = Vec::with_capacity(items.len());
        for (k, e) in items.iter().enumerate() {
            let here = format!("{what}[{k}]");
            let curve = |key: &str| -> IoResult<Option<Curve>> {
                match e.get(key) {
                    None | Some(Value::Null) => Ok(None),
                    Some(c) => {
                        Curve::from_json_value(c.clone(), &field(&format!("{here}.{key}")), "")
                            .map(Some)
                    }
                }
            };
            let Some(c) = curve("curve")? else {
                return Err(err(&here, "an edge needs its curve".into()));
            };
            ids.push(match e.get("edge_id") {
                None | Some(Value::Null) => 0,
                Some(x) => whole(x, &format!("{here}.edge_id"))?,
            });
            edges.push(
                Edge::new(c, curve("pcurve")?).map_err(|error| IoError::Invalid {
                    at: field(&format!("{here}.pcurve")),
                    error,
                })?,
            );
        }
        let lp = Loop::new(edges).map_err(|error| IoError::Invalid {
            at: field(what),
            error,
        })?;
        Ok((lp, ids))
    };
    let Some(ov) = v.get("outer") else {
        return Err(err("outer", "a face needs its outer loop".into()));
    };
    let (outer, outer_ids) = read_loop(ov, "outer")?;
    let mut edge_ids = vec![outer_ids];
    let mut inner = Vec::new();
    let inner_loops = match v.get("inner") {
        None | Some(Value::Null) => &[][..],
        Some(Value::Array(list)) => &list[..],
        Some(x) => {
            return Err(err(
                "inner",
                format!("{x} is not a list of loops: give [] for a face without holes"),
            ))
        }
    };
    {
        for (i, lv) in inner_loops.iter().enumerate() {
            let (lp, ids) = read_loop(lv, &format!("inner[{i}]"))?;
            inner.push(lp);
            edge_ids.push(ids);
        }
    }
    let face =
        Face::new(surface, outer, inner, same_sense, STEP_SHARED_VERTEX_RTOL).map_err(|error| {
            IoError::Invalid {
                at: field("outer"),
                error,
            }
        })?;
    Ok(StepFace {
        id,
        name,
        surface_id,
        face,
        edge_ids,
        pcurves,
    })
}
