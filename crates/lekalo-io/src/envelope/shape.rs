//! Every object lekalo reads, by kind: curves ([`Object`]), tensor-product surfaces
//! ([`Surface`]) and piecewise polynomials. Commands dispatch on [`Shape`] so that curve-only
//! operations (evaluation at `t`, derivatives) are never asked of a surface or a pp-form.
//!
//! ```json
//! {"lekalo": 1, "type": "nurbs_surface", "degree_u": 1, "degree_v": 1,
//!  "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1], "net": [2, 2],
//!  "control": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]], "weights": [1, 2, 2, 1]}
//! ```

use lekalo::{Arg, NurbsSurface, PiecewisePolynomial, Points, What};
use serde::Deserialize;

use crate::error::{IoError, IoResult, Location};
use crate::object::{CurveJson, Object, FORMAT_VERSION};
use crate::object_ext::{
    bezier_surface_to_json, bspline_surface_to_json, envelope_type, piecewise_polynomial_to_json,
    read_bezier_surface, read_bspline_surface, read_piecewise_polynomial,
};
use crate::step::SurfaceNet;
use crate::wireframe::Grid;

/// A tensor-product surface of any kind: the library's [`lekalo::Surface`].
pub use lekalo::Surface;

/// Any object of any kind.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Shape {
    /// A curve (Bezier, B-spline, NURBS).
    Curve(Object),
    /// A surface.
    Surface(Surface),
    /// `"type": "piecewise_polynomial"`.
    Pp(PiecewisePolynomial),
    /// A tensor-product spline in `N` parameters (`"bspline_tensor"`, `"nurbs_tensor"`).
    Tensor(lekalo::Tensor),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NurbsSurfaceJson {
    lekalo: u64,
    #[serde(rename = "type")]
    kind: String,
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    net: (usize, usize),
    control: Vec<Vec<f64>>,
    weights: Vec<f64>,
}

/// Reads a `nurbs_surface`: as `bspline_surface` plus one weight per control point (same
/// row-by-row order).
///
/// ```
/// let s = lekalo_io::read_nurbs_surface(r#"{"lekalo": 1, "type": "nurbs_surface",
///   "degree_u": 1, "degree_v": 1, "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1],
///   "net": [2, 2], "control": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]],
///   "weights": [1, 1, 1, 1]}"#, "s.json")?;
/// assert_eq!(s.eval(1.0, 1.0)?, vec![1.0, 1.0, 1.0]);
/// let text = lekalo_io::nurbs_surface_to_json(&s);
/// assert_eq!(lekalo_io::read_nurbs_surface(&text, "again")?, s);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`IoError::Syntax`] for malformed JSON, a wrong version or type, missing or unknown fields;
/// [`IoError::Invalid`] when [`NurbsSurface::new`] rejects the data (field `weights` for a
/// weight problem, else `control`).
pub fn read_nurbs_surface(text: &str, source: &str) -> IoResult<NurbsSurface> {
    let r: NurbsSurfaceJson =
        serde_json::from_str(crate::atomic::strip_bom_str(text)).map_err(|e| {
            IoError::syntax(
                Location::new(source).at_line(e.line()),
                format!("nurbs_surface: {e}"),
            )
        })?;
    if r.lekalo != FORMAT_VERSION {
        return Err(IoError::syntax(
            Location::new(source).at_field("lekalo"),
            format!(
                "format version {} is not supported; this lekalo reads version {FORMAT_VERSION}",
                r.lekalo
            ),
        ));
    }
    if r.kind != "nurbs_surface" {
        return Err(IoError::syntax(
            Location::new(source).at_field("type"),
            format!(
                "expected an object of type \"nurbs_surface\", found \"{}\"",
                r.kind
            ),
        ));
    }
    let invalid = |field: &str, error| IoError::Invalid {
        at: Location::new(source).at_field(field),
        error,
    };
    let ctrl = Points::from_rows(&r.control).map_err(|e| invalid("control", e))?;
    let n = r.net.0.saturating_mul(r.net.1);
    if r.weights.len() != n {
        return Err(invalid(
            "weights",
            lekalo::Error::LengthMismatch {
                what: What::of(Arg::Weights, "weights (one per control point)"),
                expected: n,
                got: r.weights.len(),
            },
        ));
    }
    if let Some(i) = r.weights.iter().position(|w| !w.is_finite() || *w <= 0.0) {
        return Err(invalid(
            "weights",
            lekalo::Error::NonPositiveWeight {
                index: i,
                weight: r.weights[i],
            },
        ));
    }
    NurbsSurface::new(
        r.degree_u, r.degree_v, r.knots_u, r.knots_v, ctrl, r.weights, r.net,
    )
    .map_err(|e| invalid("control", e))
}

/// JSON text of a `nurbs_surface` (fields in a fixed order, one control point per line).
#[must_use]
pub fn nurbs_surface_to_json(s: &NurbsSurface) -> String {
    let (nu, nv) = s.net_size();
    let list = |x: &[f64]| serde_json::to_string(x).unwrap_or_default();
    let ctrl = s.control_points();
    let rows: Vec<String> = ctrl.iter().map(list).collect();
    format!(
        "{{\n  \"lekalo\": {FORMAT_VERSION},\n  \"type\": \"nurbs_surface\",\n  \"degree_u\": {},\n  \"degree_v\": {},\n  \"knots_u\": {},\n  \"knots_v\": {},\n  \"net\": [{nu}, {nv}],\n  \"control\": [\n    {}\n  ],\n  \"weights\": {}\n}}\n",
        s.degree_u(),
        s.degree_v(),
        list(s.knots_u().as_slice()),
        list(s.knots_v().as_slice()),
        rows.join(",\n    "),
        list(&s.weights())
    )
}

impl Shape {
    /// Reads one object of any kind, dispatching on its `type`.
    ///
    /// ```
    /// use lekalo_io::Shape;
    /// let pp = r#"{"lekalo": 1, "type": "piecewise_polynomial", "breakpoints": [0, 1],
    ///              "order": 2, "dim": 1, "coefficients": [0, 1]}"#;
    /// assert!(matches!(Shape::from_json_str(pp, "p.json")?, Shape::Pp(_)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// As the reader of the type ([`Object::from_json_str`] for curves and unknown types).
    pub fn from_json_str(text: &str, source: &str) -> IoResult<Shape> {
        Ok(match envelope_type(text).as_deref() {
            Some("bezier_surface") => {
                Shape::Surface(Surface::Bezier(read_bezier_surface(text, source)?))
            }
            Some("bspline_surface") => {
                Shape::Surface(Surface::BSpline(read_bspline_surface(text, source)?))
            }
            Some("nurbs_surface") => {
                Shape::Surface(Surface::Nurbs(read_nurbs_surface(text, source)?))
            }
            Some("piecewise_polynomial") => Shape::Pp(read_piecewise_polynomial(text, source)?),
            Some("bspline_tensor" | "nurbs_tensor") => {
                Shape::Tensor(crate::tensor_json::read_tensor(text, source)?)
            }
            _ => Shape::Curve(Object::from_json_str(text, source)?),
        })
    }

    /// The `type` name in the envelope.
    #[must_use]
    pub fn type_name(&self) -> &'static str {
        match self {
            Shape::Curve(c) => c.type_name(),
            Shape::Surface(s) => s.type_name(),
            Shape::Pp(_) => "piecewise_polynomial",
            Shape::Tensor(t) => crate::tensor_json::tensor_type_name(t),
        }
    }

    /// JSON text of the envelope.
    #[must_use]
    pub fn to_json_pretty(&self) -> String {
        match self {
            Shape::Curve(c) => c.to_json_pretty(),
            Shape::Surface(s) => s.to_json_pretty(),
            Shape::Pp(p) => piecewise_polynomial_to_json(p),
            Shape::Tensor(t) => crate::tensor_json::tensor_to_json(t),
        }
    }

    /// JSON text of the envelope on one line, as JSON Lines hold it (no space after a colon or
    /// comma, as [`Object::to_json_line`]).
    ///
    /// ```
    /// use lekalo_io::{Shape, Surface};
    /// let net = lekalo::Points::from_3d(&[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0]])?;
    /// let s = Shape::Surface(Surface::Bezier(lekalo::BezierSurface::new(net, (2, 2))?));
    /// assert_eq!(
    ///     s.to_json_line(),
    ///     r#"{"lekalo":1,"type":"bezier_surface","net":[2,2],"control":[[0.0,0.0,0.0],[0.0,1.0,0.0],[1.0,0.0,0.0],[1.0,1.0,1.0]]}"#
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn to_json_line(&self) -> String {
        match self {
            Shape::Curve(c) => c.to_json_line(),
            // the pretty text's only white space is its layout: no number or name holds any
            other => other
                .to_json_pretty()
                .split_ascii_whitespace()
                .collect::<String>(),
        }
    }
}

/// The versioned JSON envelope of a surface (`docs/formats.md`). Implemented for
/// [`lekalo::Surface`].
pub trait SurfaceJson {
    /// JSON text of the envelope.
    #[must_use]
    fn to_json_pretty(&self) -> String;
}

impl SurfaceJson for Surface {
    fn to_json_pretty(&self) -> String {
        match self {
            Surface::Bezier(s) => bezier_surface_to_json(s),
            Surface::BSpline(s) => bspline_surface_to_json(s),
            Surface::Nurbs(s) => nurbs_surface_to_json(s),
        }
    }
}

impl crate::StepWriter {
    /// Writes a surface of any kind (Bezier surfaces as B-splines on clamped knots; NURBS in
    /// the rational form). Returns the entity id.
    ///
    /// # Errors
    /// As [`crate::StepWriter::add_surface`].
    pub fn add_any_surface(&mut self, s: &Surface) -> IoResult<usize> {
        let (ku, kv) = s.knots();
        let ctrl = s.control_points();
        let (nu, nv) = s.net_size();
        let weights = s.weights();
        let net = Grid::new(nu, nv, ctrl.dim(), ctrl.as_slice()).map_err(|e| IoError::Invalid {
            at: Location::new("surface").at_field("control"),
            error: e,
        })?;
        self.add_surface(&SurfaceNet {
            degrees: s.degrees(),
            knots: (ku.as_slice(), kv.as_slice()),
            net,
            weights: weights.as_deref(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nurbs() -> NurbsSurface {
        let ctrl = Points::from_rows(&[
            vec![0.0, 0.0, 0.0],
            vec![0.0, 1.0, 0.0],
            vec![1.0, 0.0, 0.0],
            vec![1.0, 1.0, 1.0],
        ])
        .unwrap();
        NurbsSurface::new(
            1,
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![0.0, 0.0, 1.0, 1.0],
            ctrl,
            vec![1.0, 2.0, 2.0, 1.0],
            (2, 2),
        )
        .unwrap()
    }

    #[test]
    fn nurbs_surface_round_trip_and_dispatch() {
        let s = nurbs();
        let text = nurbs_surface_to_json(&s);
        assert_eq!(read_nurbs_surface(&text, "t").unwrap(), s);
        let shape = Shape::from_json_str(&text, "t").unwrap();
        assert_eq!(shape, Shape::Surface(Surface::Nurbs(s)));
        assert_eq!(shape.to_json_pretty(), text);
    }

    #[test]
    fn nurbs_surface_errors_name_the_field() {
        let text = nurbs_surface_to_json(&nurbs());
        let e = read_nurbs_surface(&text.replace("[1.0,2.0,2.0,1.0]", "[1.0,2.0,2.0]"), "x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("field `weights`"), "{e}");
        let e = read_nurbs_surface(
            &text.replace("[1.0,2.0,2.0,1.0]", "[1.0,-2.0,2.0,1.0]"),
            "x",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("field `weights`"), "{e}");
        let e = read_nurbs_surface(&text.replace("\"lekalo\": 1", "\"lekalo\": 9"), "x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("format version 9"), "{e}");
        let e = read_nurbs_surface(&text.replace("nurbs_surface", "bspline_surface"), "x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("nurbs_surface"), "{e}");
    }

    #[test]
    fn sample_grid_hits_corners_and_gives_unit_normals() {
        let s = Surface::Nurbs(nurbs());
        let (p, n) = s.sample_grid(3, 4, true).unwrap();
        assert_eq!(p.len(), 3 * 4 * 3);
        assert_eq!(&p[p.len() - 3..], &[1.0, 1.0, 1.0]);
        for q in n.unwrap().chunks(3) {
            let len = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-12, "{len}");
        }
        assert!(s.sample_grid(1, 4, false).is_err());
    }
}
