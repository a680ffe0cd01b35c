//! Every object lekalo reads, by kind: curves ([`Object`]), tensor-product surfaces
//! ([`Surface`]) and piecewise polynomials. Commands dispatch on [`Shape`] so that curve-only
//! operations (evaluation at `t`, derivatives) are never asked of a surface or a pp-form.
//!
//! ```json
//! {"lekalo": 1, "type": "nurbs_surface", "degree_u": 1, "degree_v": 1,
//!  "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1], "net": [2, 2],
//!  "control": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]], "weights": [1, 2, 2, 1]}
//! ```

use lekalo::{BSplineSurface, BezierSurface, NurbsSurface, PiecewisePolynomial, Points};
use serde::Deserialize;

use crate::error::{IoError, IoResult, Location};
use crate::object::{Object, FORMAT_VERSION};
use crate::object_ext::{
    bezier_surface_to_json, bspline_surface_to_json, envelope_type, piecewise_polynomial_to_json,
    read_bezier_surface, read_bspline_surface, read_piecewise_polynomial,
};
use crate::step::SurfaceNet;
use crate::wireframe::Grid;

/// A tensor-product surface of any kind.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Surface {
    /// `"type": "bezier_surface"`.
    Bezier(BezierSurface),
    /// `"type": "bspline_surface"`.
    BSpline(BSplineSurface),
    /// `"type": "nurbs_surface"`.
    Nurbs(NurbsSurface),
}

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
                what: "weights (one per control point)",
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
        }
    }

    /// JSON text of the envelope.
    #[must_use]
    pub fn to_json_pretty(&self) -> String {
        match self {
            Shape::Curve(c) => c.to_json_pretty(),
            Shape::Surface(s) => s.to_json_pretty(),
            Shape::Pp(p) => piecewise_polynomial_to_json(p),
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

impl Surface {
    /// The `type` name in the envelope.
    #[must_use]
    pub fn type_name(&self) -> &'static str {
        match self {
            Surface::Bezier(_) => "bezier_surface",
            Surface::BSpline(_) => "bspline_surface",
            Surface::Nurbs(_) => "nurbs_surface",
        }
    }

    /// Name for people.
    #[must_use]
    pub fn display_name(&self) -> &'static str {
        match self {
            Surface::Bezier(_) => "Bezier surface",
            Surface::BSpline(_) => "B-spline surface",
            Surface::Nurbs(_) => "NURBS surface",
        }
    }

    /// JSON text of the envelope.
    #[must_use]
    pub fn to_json_pretty(&self) -> String {
        match self {
            Surface::Bezier(s) => bezier_surface_to_json(s),
            Surface::BSpline(s) => bspline_surface_to_json(s),
            Surface::Nurbs(s) => nurbs_surface_to_json(s),
        }
    }

    /// Degrees `(p_u, p_v)`.
    #[must_use]
    pub fn degrees(&self) -> (usize, usize) {
        match self {
            Surface::Bezier(s) => (s.degree_u(), s.degree_v()),
            Surface::BSpline(s) => (s.degree_u(), s.degree_v()),
            Surface::Nurbs(s) => (s.degree_u(), s.degree_v()),
        }
    }

    /// Control net size `(nu, nv)`.
    #[must_use]
    pub fn net_size(&self) -> (usize, usize) {
        match self {
            Surface::Bezier(s) => s.net_size(),
            Surface::BSpline(s) => s.net_size(),
            Surface::Nurbs(s) => s.net_size(),
        }
    }

    /// Dimension of the points.
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            Surface::Bezier(s) => s.dim(),
            Surface::BSpline(s) => s.dim(),
            Surface::Nurbs(s) => s.dim(),
        }
    }

    /// Parameter domain `((u0, u1), (v0, v1))`.
    #[must_use]
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        match self {
            Surface::Bezier(s) => s.domain(),
            Surface::BSpline(s) => s.domain(),
            Surface::Nurbs(s) => s.domain(),
        }
    }

    /// Knot vectors `(U, V)` (a Bezier surface's are the clamped `[0…0, 1…1]`).
    #[must_use]
    pub fn knots(&self) -> (Vec<f64>, Vec<f64>) {
        match self {
            Surface::Bezier(s) => {
                let b = s.to_bspline();
                (
                    b.knots_u().as_slice().to_vec(),
                    b.knots_v().as_slice().to_vec(),
                )
            }
            Surface::BSpline(s) => (
                s.knots_u().as_slice().to_vec(),
                s.knots_v().as_slice().to_vec(),
            ),
            Surface::Nurbs(s) => (
                s.knots_u().as_slice().to_vec(),
                s.knots_v().as_slice().to_vec(),
            ),
        }
    }

    /// Cartesian control points, row by row.
    #[must_use]
    pub fn control_points(&self) -> Points {
        match self {
            Surface::Bezier(s) => s.control_points().clone(),
            Surface::BSpline(s) => s.control_points().clone(),
            Surface::Nurbs(s) => s.control_points(),
        }
    }

    /// Weights of a NURBS surface, row by row.
    #[must_use]
    pub fn weights(&self) -> Option<Vec<f64>> {
        match self {
            Surface::Nurbs(s) => Some(s.weights()),
            _ => None,
        }
    }

    /// The point at `(u, v)`.
    ///
    /// # Errors
    /// As the surface's `eval` (a parameter outside the domain).
    pub fn eval(&self, u: f64, v: f64) -> lekalo::Result<Vec<f64>> {
        match self {
            Surface::Bezier(s) => s.eval(u, v),
            Surface::BSpline(s) => s.eval(u, v),
            Surface::Nurbs(s) => s.eval(u, v),
        }
    }

    /// Unit normal at `(u, v)` (3-D surfaces).
    ///
    /// # Errors
    /// As the surface's `normal` (not 3-D, degenerate point).
    pub fn normal(&self, u: f64, v: f64) -> lekalo::Result<[f64; 3]> {
        match self {
            Surface::Bezier(s) => s.normal(u, v),
            Surface::BSpline(s) => s.normal(u, v),
            Surface::Nurbs(s) => s.normal(u, v),
        }
    }

    /// Samples an `nu × nv` grid of points evenly in the domain, point `(i, j)` at
    /// `(i·nv + j)·dim` (the layout of [`Grid`]); with `normals`, also the unit normals
    /// (3 values per point).
    ///
    /// # Errors
    /// [`lekalo::Error::TooFew`] for fewer than 2 samples per direction; the surface's errors.
    pub fn sample_grid(
        &self,
        nu: usize,
        nv: usize,
        normals: bool,
    ) -> lekalo::Result<(Vec<f64>, Option<Vec<f64>>)> {
        if nu < 2 || nv < 2 {
            return Err(lekalo::Error::TooFew {
                what: "samples per direction",
                min: 2,
                got: nu.min(nv),
            });
        }
        let ((u0, u1), (v0, v1)) = self.domain();
        let at = |a: f64, b: f64, k: usize, n: usize| {
            if k + 1 == n {
                b
            } else {
                a + (b - a) * (k as f64) / ((n - 1) as f64)
            }
        };
        let dim = self.dim();
        let mut pts = Vec::with_capacity(nu * nv * dim);
        let mut nrm = normals.then(|| Vec::with_capacity(nu * nv * 3));
        for i in 0..nu {
            let u = at(u0, u1, i, nu);
            for j in 0..nv {
                let v = at(v0, v1, j, nv);
                pts.extend(self.eval(u, v)?);
                if let Some(n) = nrm.as_mut() {
                    n.extend(self.normal(u, v)?);
                }
            }
        }
        Ok((pts, nrm))
    }

    /// Writes the surface into a STEP writer (Bezier surfaces as B-splines on clamped knots;
    /// NURBS in the rational form). Returns the entity id.
    ///
    /// # Errors
    /// As [`crate::StepWriter::add_surface`].
    pub fn add_to_step(&self, w: &mut crate::StepWriter) -> IoResult<usize> {
        let (ku, kv) = self.knots();
        let ctrl = self.control_points();
        let (nu, nv) = self.net_size();
        let weights = self.weights();
        let net = Grid::new(nu, nv, ctrl.dim(), ctrl.as_slice()).map_err(|e| IoError::Invalid {
            at: Location::new("surface").at_field("control"),
            error: e,
        })?;
        w.add_surface(&SurfaceNet {
            degrees: self.degrees(),
            knots: (&ku, &kv),
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
