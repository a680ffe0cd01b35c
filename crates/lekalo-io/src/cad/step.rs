//! STEP (ISO 10303-21 exchange structure, application protocol AP214 `AUTOMOTIVE_DESIGN`):
//! B-spline and NURBS curves and surfaces as `B_SPLINE_CURVE_WITH_KNOTS` /
//! `B_SPLINE_SURFACE_WITH_KNOTS`, the rational ones as the complex entity instance with
//! `RATIONAL_B_SPLINE_CURVE` / `RATIONAL_B_SPLINE_SURFACE` (ISO 10303-42 §4.3.4, 4.3.7).
//!
//! The file carries what Open CASCADE (and so FreeCAD) needs to import it: the product
//! structure (`PRODUCT` … `PRODUCT_DEFINITION_SHAPE`), a shape representation
//! (`GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION` with a `GEOMETRIC_CURVE_SET` for
//! curves; `GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION` with a `GEOMETRIC_SET` when
//! there are surfaces) and a 3-D geometric context with units (millimetre, radian, steradian) and
//! an uncertainty. Knots are written as distinct values with multiplicities, as the schema
//! requires; points of dimension below 3 are padded with zeros. Entity instances are numbered
//! `#1, #2, …` in order of writing, so the output is deterministic.
//!
//! The writers take plain nets ([`CurveNet`], [`SurfaceNet`]) so that any curve or surface type
//! plugs in by exposing its degree, knots, control net and weights.

use std::fmt::Write as _;

use lekalo::PointsRef;

use crate::error::{IoError, IoResult};
use crate::object::Object;
use crate::wireframe::Grid;

/// A B-spline or NURBS curve as plain data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveNet<'a> {
    /// Degree `p`.
    pub degree: usize,
    /// The full knot vector, `n + p + 2` values for `n + 1` control points.
    pub knots: &'a [f64],
    /// Control points (dimension 1 to 3).
    pub points: PointsRef<'a>,
    /// Weights of a rational curve, one per control point.
    pub weights: Option<&'a [f64]>,
}

/// A tensor-product B-spline or NURBS surface as plain data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceNet<'a> {
    /// Degrees in `u` and `v`.
    pub degrees: (usize, usize),
    /// Knot vectors in `u` (`nu + p_u + 1` values) and `v` (`nv + p_v + 1`).
    pub knots: (&'a [f64], &'a [f64]),
    /// Control net, point `(i, j)` at `data[(i * nv + j) * dim ..]`.
    pub net: Grid<'a>,
    /// Weights in the same `(i, j)` order, for a rational surface.
    pub weights: Option<&'a [f64]>,
}

/// Builds one STEP file from curves and surfaces.
#[derive(Debug, Clone)]
pub struct StepWriter {
    lines: Vec<String>,
    curves: Vec<usize>,
    surfaces: Vec<usize>,
    /// The shape representation of the faces written by `add_faces` (`step_faces.rs`).
    pub(crate) faces_rep: Option<usize>,
    name: String,
    /// The largest dimension of the curves added by `add_curve`.
    curve_dim: usize,
}

/// The type of the representation context of a file of curves that all had 2 (or fewer)
/// coordinates: their points are padded with `z = 0` for CAD systems (which read no 2-D curve
/// from a curve set), and lekalo's reader gives them back in 2-D.
pub(crate) const PLANE_DRAWING: &str = "2D drawing in the plane z = 0";

/// Ids of the fixed preamble entities.
pub(crate) const CONTEXT_ID: usize = 14;
const PRODUCT_SHAPE_ID: usize = 8;

impl StepWriter {
    /// A writer for a product called `name` (also the file name in the header).
    #[must_use]
    pub fn new(name: &str) -> Self {
        let n = step_string(name);
        let lines = vec![
            "APPLICATION_CONTEXT('core data for automotive mechanical design processes')".into(),
            "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#1)".into(),
            "PRODUCT_CONTEXT('',#1,'mechanical')".into(),
            format!("PRODUCT({n},{n},'',(#3))"),
            "PRODUCT_DEFINITION_FORMATION('','',#4)".into(),
            "PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design')".into(),
            "PRODUCT_DEFINITION('design','',#5,#6)".into(),
            "PRODUCT_DEFINITION_SHAPE('','',#7)".into(),
            "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#4))".into(),
            "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))".into(),
            "(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))".into(),
            "(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())".into(),
            "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#10,'distance_accuracy_value','confusion accuracy')".into(),
            "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#13))GLOBAL_UNIT_ASSIGNED_CONTEXT((#10,#11,#12))REPRESENTATION_CONTEXT('lekalo','3D context with units and uncertainty'))".into(),
        ];
        debug_assert_eq!(lines.len(), CONTEXT_ID, "preamble ids");
        StepWriter {
            lines,
            curves: Vec::new(),
            surfaces: Vec::new(),
            faces_rep: None,
            name: name.to_string(),
            curve_dim: 0,
        }
    }

    /// Appends an entity instance; returns its id.
    pub(crate) fn add(&mut self, entity: String) -> usize {
        self.lines.push(entity);
        self.lines.len()
    }

    /// A `CARTESIAN_POINT` of 3 coordinates (fewer padded with zeros).
    pub(crate) fn add_point(&mut self, p: &[f64]) -> usize {
        self.add_point_in(p, 3)
    }

    /// A `CARTESIAN_POINT` of `coords` coordinates (`p` padded with zeros).
    fn add_point_in(&mut self, p: &[f64], coords: usize) -> usize {
        let mut c = [0.0; 3];
        c[..p.len()].copy_from_slice(p);
        let xs: Vec<String> = c[..coords].iter().map(|&x| step_real(x)).collect();
        self.add(format!("CARTESIAN_POINT('',({}))", xs.join(",")))
    }

    /// Fails once faces are written: a file holds faces or loose curves and surfaces.
    fn check_no_faces(&self) -> IoResult<()> {
        if self.faces_rep.is_some() {
            return Err(IoError::Unsupported {
                what: "a STEP file of faces holds only faces; write the curves and surfaces to another file".into(),
            });
        }
        Ok(())
    }

    /// True when curves or surfaces were added with `add_curve` or `add_surface`.
    pub(crate) fn has_loose_geometry(&self) -> bool {
        !(self.curves.is_empty() && self.surfaces.is_empty())
    }

    /// Adds a curve; returns its entity id.
    ///
    /// # Errors
    /// [`IoError::Unsupported`] for points of dimension above 3, inconsistent counts or
    /// non-positive weights.
    pub fn add_curve(&mut self, c: &CurveNet<'_>) -> IoResult<usize> {
        self.check_no_faces()?;
        let id = self.write_curve(c, 3)?;
        self.curves.push(id);
        self.curve_dim = self.curve_dim.max(c.points.dim());
        Ok(id)
    }

    /// Writes a curve with points of `coords` coordinates (2 for curves in a surface's
    /// parameters) without listing it in the file's geometric set; returns its entity id.
    pub(crate) fn write_curve(&mut self, c: &CurveNet<'_>, coords: usize) -> IoResult<usize> {
        let n = c.points.len();
        check_dim(c.points.dim())?;
        check_counts("curve", c.knots.len(), n, c.degree)?;
        if let Some(w) = c.weights {
            check_weights(w, n)?;
        }
        if c.points.dim() > coords {
            return Err(IoError::Unsupported {
                what: format!(
                    "a curve of {} coordinates where {coords} are written",
                    c.points.dim()
                ),
            });
        }
        let ids: Vec<usize> = c
            .points
            .iter()
            .map(|p| self.add_point_in(p, coords))
            .collect();
        let (mults, knots) = distinct(c.knots);
        let pts = ref_list(&ids);
        let id = match c.weights {
            None => self.add(format!(
                "B_SPLINE_CURVE_WITH_KNOTS('',{},{pts},.UNSPECIFIED.,.F.,.F.,{mults},{knots},.UNSPECIFIED.)",
                c.degree
            )),
            Some(w) => self.add(format!(
                "(BOUNDED_CURVE()B_SPLINE_CURVE({},{pts},.UNSPECIFIED.,.F.,.F.)B_SPLINE_CURVE_WITH_KNOTS({mults},{knots},.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE({})REPRESENTATION_ITEM(''))",
                c.degree,
                real_list(w)
            )),
        };
        Ok(id)
    }

    /// Adds a surface; returns its entity id.
    ///
    /// # Errors
    /// As [`StepWriter::add_curve`], per direction.
    pub fn add_surface(&mut self, s: &SurfaceNet<'_>) -> IoResult<usize> {
        self.check_no_faces()?;
        let id = self.write_surface(s)?;
        self.surfaces.push(id);
        Ok(id)
    }

    /// Writes a surface without listing it in the file's geometric set; returns its entity id.
    pub(crate) fn write_surface(&mut self, s: &SurfaceNet<'_>) -> IoResult<usize> {
        let g = &s.net;
        check_dim(g.dim)?;
        check_counts("surface (u direction)", s.knots.0.len(), g.nu, s.degrees.0)?;
        check_counts("surface (v direction)", s.knots.1.len(), g.nv, s.degrees.1)?;
        if let Some(w) = s.weights {
            check_weights(w, g.nu * g.nv)?;
        }
        let mut rows = Vec::with_capacity(g.nu);
        for i in 0..g.nu {
            let ids: Vec<usize> = (0..g.nv)
                .map(|j| {
                    let base = (i * g.nv + j) * g.dim;
                    self.add_point(&g.data[base..base + g.dim])
                })
                .collect();
            rows.push(ref_list(&ids));
        }
        let net = format!("({})", rows.join(","));
        let (um, uk) = distinct(s.knots.0);
        let (vm, vk) = distinct(s.knots.1);
        let (du, dv) = s.degrees;
        let id = match s.weights {
            None => self.add(format!(
                "B_SPLINE_SURFACE_WITH_KNOTS('',{du},{dv},{net},.UNSPECIFIED.,.F.,.F.,.F.,{um},{vm},{uk},{vk},.UNSPECIFIED.)"
            )),
            Some(w) => {
                let wrows: Vec<String> = w.chunks(g.nv).map(real_list).collect();
                self.add(format!(
                    "(BOUNDED_SURFACE()B_SPLINE_SURFACE({du},{dv},{net},.UNSPECIFIED.,.F.,.F.,.F.)B_SPLINE_SURFACE_WITH_KNOTS({um},{vm},{uk},{vk},.UNSPECIFIED.)GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_SURFACE(({}))REPRESENTATION_ITEM('')SURFACE())",
                    wrows.join(",")
                ))
            }
        };
        Ok(id)
    }

    /// Adds a curve object (Bezier curves as B-splines on clamped knots `[0…0, 1…1]`).
    ///
    /// # Errors
    /// As [`StepWriter::add_curve`].
    pub fn add_object(&mut self, obj: &Object) -> IoResult<usize> {
        let knots = obj.knots();
        let ctrl = obj.control_points();
        let weights = obj.weights();
        self.add_curve(&CurveNet {
            degree: obj.degree(),
            knots: knots.as_slice(),
            points: ctrl.as_view(),
            weights: weights.as_deref(),
        })
    }

    /// The complete exchange structure. `timestamp` goes into `FILE_NAME` (pass a fixed value
    /// for reproducible files).
    #[must_use]
    pub fn finish(mut self, timestamp: &str) -> String {
        let items: Vec<usize> = self.curves.iter().chain(&self.surfaces).copied().collect();
        let rep = if let Some(rep) = self.faces_rep {
            rep
        } else if self.surfaces.is_empty() {
            if self.curve_dim <= 2 {
                self.lines[CONTEXT_ID - 1] = self.lines[CONTEXT_ID - 1].replace(
                    "'3D context with units and uncertainty'",
                    &step_string(PLANE_DRAWING),
                );
            }
            let set = self.add(format!("GEOMETRIC_CURVE_SET('',{})", ref_list(&items)));
            self.add(format!(
                "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#{set}),#{CONTEXT_ID})"
            ))
        } else {
            let set = self.add(format!("GEOMETRIC_SET('',{})", ref_list(&items)));
            self.add(format!(
                "GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION('',(#{set}),#{CONTEXT_ID})"
            ))
        };
        self.add(format!(
            "SHAPE_DEFINITION_REPRESENTATION(#{PRODUCT_SHAPE_ID},#{rep})"
        ));
        let mut s = String::new();
        let name = step_string(&self.name);
        let _ = writeln!(s, "ISO-10303-21;");
        let _ = writeln!(s, "HEADER;");
        let _ = writeln!(s, "FILE_DESCRIPTION(('lekalo spline export'),'2;1');");
        let _ = writeln!(
            s,
            "FILE_NAME({name},{},('lekalo'),(''),'lekalo {}','lekalo','');",
            step_string(timestamp),
            env!("CARGO_PKG_VERSION")
        );
        let _ = writeln!(
            s,
            "FILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));"
        );
        let _ = writeln!(s, "ENDSEC;");
        let _ = writeln!(s, "DATA;");
        for (i, e) in self.lines.iter().enumerate() {
            let _ = writeln!(s, "#{}={e};", i + 1);
        }
        let _ = writeln!(s, "ENDSEC;");
        let _ = writeln!(s, "END-ISO-10303-21;");
        s
    }
}

fn check_dim(dim: usize) -> IoResult<()> {
    if dim == 0 || dim > 3 {
        return Err(IoError::Unsupported {
            what: format!(
                "STEP holds points in 1 to 3 dimensions, these have {dim}; project the data first"
            ),
        });
    }
    Ok(())
}

fn check_counts(what: &str, n_knots: usize, n_ctrl: usize, degree: usize) -> IoResult<()> {
    if n_ctrl < degree + 1 || n_knots != n_ctrl + degree + 1 {
        return Err(IoError::Unsupported {
            what: format!(
                "{what}: {n_knots} knots, {n_ctrl} control points and degree {degree} do not fit (need knots = points + degree + 1 and points > degree)"
            ),
        });
    }
    Ok(())
}

fn check_weights(w: &[f64], n: usize) -> IoResult<()> {
    if w.len() != n || w.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
        return Err(IoError::Unsupported {
            what: format!("need {n} positive finite weights, got {}", w.len()),
        });
    }
    Ok(())
}

/// `(multiplicities, distinct knots)` as STEP lists: `(3,1,3)` and `(0.,0.5,1.)`.
fn distinct(knots: &[f64]) -> (String, String) {
    let mut mults: Vec<usize> = Vec::new();
    let mut values: Vec<f64> = Vec::new();
    for &k in knots {
        match values.last() {
            Some(&v) if v == k => {
                if let Some(m) = mults.last_mut() {
                    *m += 1;
                }
            }
            _ => {
                values.push(k);
                mults.push(1);
            }
        }
    }
    let m: Vec<String> = mults.iter().map(usize::to_string).collect();
    (format!("({})", m.join(",")), real_list(&values))
}

fn ref_list(ids: &[usize]) -> String {
    let v: Vec<String> = ids.iter().map(|i| format!("#{i}")).collect();
    format!("({})", v.join(","))
}

fn real_list(v: &[f64]) -> String {
    let v: Vec<String> = v.iter().map(|&x| step_real(x)).collect();
    format!("({})", v.join(","))
}

/// A REAL token of ISO 10303-21 §6.3.2: digits, a mandatory decimal point, optional exponent,
/// e.g. `1.`, `-0.5`, `1.5E-07`. Shortest round-trip representation of the `f64`.
#[must_use]
pub fn step_real(x: f64) -> String {
    let s = format!("{x:E}"); // e.g. "1.5E-7", "1E0", "-2.5E3"
    let (mant, exp) = s.split_once('E').unwrap_or((&s, "0"));
    let mant = if mant.contains('.') {
        mant.to_string()
    } else {
        format!("{mant}.")
    };
    if exp == "0" {
        mant
    } else {
        format!("{mant}E{exp}")
    }
}

/// A STRING token: single-quoted, quotes doubled, non-ASCII replaced by `?` (Part 21 strings
/// are ISO 8859-1 without the `\X2\` encoding that not every reader handles).
pub(crate) fn step_string(s: &str) -> String {
    let clean: String = s
        .chars()
        .map(|c| {
            if c.is_ascii() && !c.is_ascii_control() {
                c
            } else {
                '?'
            }
        })
        .collect();
    format!("'{}'", clean.replace('\'', "''").replace('\\', "\\\\"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_and_strings() {
        assert_eq!(step_real(1.0), "1.");
        assert_eq!(step_real(0.5), "5.E-1");
        assert_eq!(step_real(-2500.0), "-2.5E3");
        assert_eq!(step_real(0.0), "0.");
        assert_eq!(step_real(1.5e-7), "1.5E-7");
        for x in [0.1, 1.0 / 3.0, -123.456e-200, 28.0 / 51.0] {
            let s = step_real(x);
            assert_eq!(s.replace(".E", "E").parse::<f64>().unwrap(), x, "{s}");
        }
        assert_eq!(step_string("it's"), "'it''s'");
        assert_eq!(step_string("Лекало"), "'??????'");
        assert_eq!(distinct(&[0.0, 0.0, 1.0, 2.0, 3.0, 3.0]).0, "(2,1,1,2)");
    }

    #[test]
    fn rejects_bad_nets() {
        let pts = [0.0; 12];
        let p4 = PointsRef::from_flat(4, &pts).unwrap();
        let mut w = StepWriter::new("x");
        let c = CurveNet {
            degree: 1,
            knots: &[0.0, 0.0, 1.0, 1.0, 1.0],
            points: p4,
            weights: None,
        };
        assert!(matches!(w.add_curve(&c), Err(IoError::Unsupported { .. })));
        let p2 = PointsRef::from_flat(2, &pts).unwrap();
        let c = CurveNet { points: p2, ..c };
        assert!(w.add_curve(&c).is_err());
        let c = CurveNet {
            knots: &[0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0],
            ..c
        };
        assert!(w.add_curve(&c).is_ok());
        let c = CurveNet {
            weights: Some(&[1.0, 1.0, 0.0, 1.0, 1.0, 1.0]),
            ..c
        };
        assert!(w.add_curve(&c).is_err());
    }
}
