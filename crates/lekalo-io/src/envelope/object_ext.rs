//! The versioned JSON of the objects that are not curves (yet outside [`crate::Object`]):
//! B-spline and Bezier surfaces and piecewise polynomials (docs/formats.md).
//!
//! ```json
//! {"lekalo": 1, "type": "bspline_surface", "degree_u": 1, "degree_v": 1,
//!  "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1], "net": [2, 2],
//!  "control": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]]}
//! {"lekalo": 1, "type": "bezier_surface", "net": [2, 2], "control": [...]}
//! {"lekalo": 1, "type": "piecewise_polynomial", "breakpoints": [0, 1, 2], "order": 2,
//!  "dim": 1, "coefficients": [0, 1, 1, 1]}
//! ```
//!
//! Control nets are row by row: point `(i, j)` is row `i·nv + j` (lekalo's layout). Every read
//! goes through the library's validating constructor; unknown fields are errors.

use lekalo::{BSplineSurface, BezierSurface, PiecewisePolynomial, Points};
use serde::Deserialize;

use crate::error::{IoError, IoResult, Location};
use crate::object::FORMAT_VERSION;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BSplineSurfaceJson {
    lekalo: u64,
    #[serde(rename = "type")]
    kind: String,
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    net: (usize, usize),
    control: Vec<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BezierSurfaceJson {
    lekalo: u64,
    #[serde(rename = "type")]
    kind: String,
    net: (usize, usize),
    control: Vec<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PpJson {
    lekalo: u64,
    #[serde(rename = "type")]
    kind: String,
    breakpoints: Vec<f64>,
    order: usize,
    dim: usize,
    coefficients: Vec<f64>,
}

/// The `type` of an envelope, if the text is a JSON object with a string `type`.
#[must_use]
pub fn envelope_type(text: &str) -> Option<String> {
    // the envelope only: the rest of the text is skipped, not stored
    let text = crate::atomic::strip_bom_str(text);
    crate::object::Head::read(text, &crate::error::Location::new(""))
        .ok()?
        .kind()
        .map(str::to_string)
}

fn decode<T: for<'de> Deserialize<'de>>(text: &str, source: &str, kind: &str) -> IoResult<T> {
    serde_json::from_str(crate::atomic::strip_bom_str(text)).map_err(|e| {
        IoError::syntax(
            Location::new(source).at_line(e.line()),
            format!("{kind}: {e}"),
        )
    })
}

fn check_envelope(version: u64, kind: &str, want: &str, source: &str) -> IoResult<()> {
    if version != FORMAT_VERSION {
        return Err(IoError::syntax(
            Location::new(source).at_field("lekalo"),
            format!(
                "format version {version} is not supported; this lekalo reads version {FORMAT_VERSION}"
            ),
        ));
    }
    if kind != want {
        return Err(IoError::syntax(
            Location::new(source).at_field("type"),
            format!("expected an object of type \"{want}\", found \"{kind}\""),
        ));
    }
    Ok(())
}

fn invalid(source: &str, field: &str, error: lekalo::Error) -> IoError {
    IoError::Invalid {
        at: Location::new(source).at_field(field),
        error,
    }
}

fn rows(p: &Points) -> String {
    let r: Vec<String> = p
        .iter()
        .map(|q| serde_json::to_string(q).unwrap_or_default())
        .collect();
    format!("[\n    {}\n  ]", r.join(",\n    "))
}

fn list(x: &[f64]) -> String {
    serde_json::to_string(x).unwrap_or_default()
}

/// Reads a `bspline_surface`.
///
/// ```
/// let s = lekalo_io::read_bspline_surface(r#"{"lekalo": 1, "type": "bspline_surface",
///   "degree_u": 1, "degree_v": 1, "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1],
///   "net": [2, 2], "control": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]]}"#, "s.json")?;
/// assert_eq!(s.eval(1.0, 1.0)?, vec![1.0, 1.0, 1.0]);
/// let text = lekalo_io::bspline_surface_to_json(&s);
/// assert_eq!(lekalo_io::read_bspline_surface(&text, "again")?, s);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`IoError::Syntax`] for malformed JSON, a wrong version or type, missing or unknown fields;
/// [`IoError::Invalid`] when [`BSplineSurface::new`] rejects the data.
pub fn read_bspline_surface(text: &str, source: &str) -> IoResult<BSplineSurface> {
    let r: BSplineSurfaceJson = decode(text, source, "bspline_surface")?;
    check_envelope(r.lekalo, &r.kind, "bspline_surface", source)?;
    let ctrl = Points::from_rows(&r.control).map_err(|e| invalid(source, "control", e))?;
    BSplineSurface::new(r.degree_u, r.degree_v, r.knots_u, r.knots_v, ctrl, r.net)
        .map_err(|e| invalid(source, "control", e))
}

/// JSON text of a `bspline_surface` (fields in a fixed order, one control point per line).
#[must_use]
pub fn bspline_surface_to_json(s: &BSplineSurface) -> String {
    let (nu, nv) = s.net_size();
    format!(
        "{{\n  \"lekalo\": {FORMAT_VERSION},\n  \"type\": \"bspline_surface\",\n  \"degree_u\": {},\n  \"degree_v\": {},\n  \"knots_u\": {},\n  \"knots_v\": {},\n  \"net\": [{nu}, {nv}],\n  \"control\": {}\n}}\n",
        s.degree_u(),
        s.degree_v(),
        list(s.knots_u().as_slice()),
        list(s.knots_v().as_slice()),
        rows(s.control_points())
    )
}

/// Reads a `bezier_surface`: net size `[n + 1, m + 1]` and the control net row by row.
///
/// # Errors
/// As [`read_bspline_surface`], with [`BezierSurface::new`].
pub fn read_bezier_surface(text: &str, source: &str) -> IoResult<BezierSurface> {
    let r: BezierSurfaceJson = decode(text, source, "bezier_surface")?;
    check_envelope(r.lekalo, &r.kind, "bezier_surface", source)?;
    let ctrl = Points::from_rows(&r.control).map_err(|e| invalid(source, "control", e))?;
    BezierSurface::new(ctrl, r.net).map_err(|e| invalid(source, "control", e))
}

/// JSON text of a `bezier_surface`.
#[must_use]
pub fn bezier_surface_to_json(s: &BezierSurface) -> String {
    let (nu, nv) = s.net_size();
    format!(
        "{{\n  \"lekalo\": {FORMAT_VERSION},\n  \"type\": \"bezier_surface\",\n  \"net\": [{nu}, {nv}],\n  \"control\": {}\n}}\n",
        rows(s.control_points())
    )
}

/// Reads a `piecewise_polynomial` (pp-form: for piece `j`, `c_{j,r} = f^(r)(ξ_j+)/r!`, flat
/// as in [`PiecewisePolynomial::new`]).
///
/// ```
/// let p = lekalo_io::read_piecewise_polynomial(r#"{"lekalo": 1, "type": "piecewise_polynomial",
///   "breakpoints": [0, 1, 2], "order": 2, "dim": 1, "coefficients": [0, 1, 1, 1]}"#, "p.json")?;
/// assert_eq!(p.eval(1.5)?, vec![1.5]);
/// let e = lekalo_io::read_piecewise_polynomial(r#"{"lekalo": 1, "type": "piecewise_polynomial",
///   "breakpoints": [0, 1], "order": 2, "dim": 1, "coefficients": [0]}"#, "p.json").unwrap_err();
/// assert!(e.to_string().contains("coefficients"), "{e}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`read_bspline_surface`], with [`PiecewisePolynomial::new`].
pub fn read_piecewise_polynomial(text: &str, source: &str) -> IoResult<PiecewisePolynomial> {
    let r: PpJson = decode(text, source, "piecewise_polynomial")?;
    check_envelope(r.lekalo, &r.kind, "piecewise_polynomial", source)?;
    PiecewisePolynomial::new(r.breakpoints, r.order, r.dim, r.coefficients)
        .map_err(|e| invalid(source, "coefficients", e))
}

/// JSON text of a `piecewise_polynomial`.
#[must_use]
pub fn piecewise_polynomial_to_json(p: &PiecewisePolynomial) -> String {
    format!(
        "{{\n  \"lekalo\": {FORMAT_VERSION},\n  \"type\": \"piecewise_polynomial\",\n  \"breakpoints\": {},\n  \"order\": {},\n  \"dim\": {},\n  \"coefficients\": {}\n}}\n",
        list(p.breakpoints()),
        p.order(),
        p.dim(),
        list(p.coefficients())
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_errors() {
        let net = Points::from_flat(3, (0..12).map(f64::from).collect()).unwrap();
        let b = BezierSurface::new(net, (2, 2)).unwrap();
        let back = read_bezier_surface(&bezier_surface_to_json(&b), "t").unwrap();
        assert_eq!(back, b);
        let s = b.to_bspline();
        assert_eq!(
            read_bspline_surface(&bspline_surface_to_json(&s), "t").unwrap(),
            s
        );
        let p = PiecewisePolynomial::new(vec![0.0, 1.0], 2, 1, vec![1.0, 2.0]).unwrap();
        assert_eq!(
            read_piecewise_polynomial(&piecewise_polynomial_to_json(&p), "t").unwrap(),
            p
        );
        assert_eq!(
            envelope_type(&bezier_surface_to_json(&b)).as_deref(),
            Some("bezier_surface")
        );
        let e = read_bezier_surface(
            &bezier_surface_to_json(&b).replace("[2, 2]", "[2, 3]"),
            "x.json",
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("x.json: field `control`"), "{e}");
        let e = read_bspline_surface(&bezier_surface_to_json(&b), "x.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("bspline_surface"), "{e}");
        let e = read_piecewise_polynomial(
            &piecewise_polynomial_to_json(&p).replace("\"lekalo\": 1", "\"lekalo\": 7"),
            "x.json",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("format version 7"), "{e}");
        let e = read_bezier_surface(
            &bezier_surface_to_json(&b).replace("\"net\"", "\"nett\""),
            "x.json",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("nett"), "{e}");
    }
}
