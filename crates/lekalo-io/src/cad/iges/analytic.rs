//! IGES analytic surfaces and polylines as exact NURBS: the plane surface (entity 190), right
//! circular cylindrical surface (192), right circular conical surface (194), spherical surface
//! (196) and toroidal surface (198) of IGES 5.3 §4.48–§4.52, the plane (108, §4.12) bounded by
//! a closed curve, and the linear paths of the copious data entity (106, §4.10).
//!
//! Entities 190–198 point at a point (entity 116, `X, Y, Z`) and at directions (entity 123,
//! `X, Y, Z`, not necessarily of unit length) by their directory entries:
//!
//! | entity | parameters (form 0) | form 1 adds |
//! |---|---|---|
//! | 190 plane | `LOCATION, NORMAL` | `REFDIR` |
//! | 192 cylinder | `LOCATION, AXIS, RADIUS` | `REFDIR` |
//! | 194 cone | `LOCATION, AXIS, RADIUS, SANGLE` (radius at `LOCATION`, semi-angle in degrees) | `REFDIR` |
//! | 196 sphere | `CENTER, RADIUS` | `AXIS, REFDIR` |
//! | 198 torus | `CENTER, AXIS, MAJRAD, MINRAD` | `REFDIR` |
//!
//! The frame is [`Placement::new`] of the location, the axis (the normal of a plane) and the
//! reference direction (or its default when form 0 gives none), and the surfaces are the
//! core's constructors on it ([`BSplineSurface::plane_patch`], [`NurbsSurface::cylinder`],
//! [`NurbsSurface::cone`], [`NurbsSurface::sphere`], [`NurbsSurface::torus`]), as the STEP
//! reader builds ISO 10303-42 elementary surfaces. Spheres and tori are whole. Planes,
//! cylinders and cones have no extent of their own: they are read over the extent of the
//! faces that bound them (trimmed and bounded surfaces, 144 and 143, when faces are read: the
//! control points of their model-space boundary curves, which contain the curves, P&T §4.2,
//! convex hull property; as `step_read/bounds.rs` does for STEP), and listed as skipped
//! otherwise. Their NURBS parameters are not IGES's (form 1 measures angles, the NURBS the
//! rational arc parameter), so a face on one keeps its model-space edges without pcurves.
//!
//! Entity 108: `A, B, C, D, PTR, X, Y, Z, SIZE`, the plane `A x + B y + C z = D`; form 1 is
//! bounded by the closed curve `PTR` points at, form −1 is the same region marking a hole of a
//! containing plane, form 0 is unbounded (`PTR = 0`). Forms ±1 are read as the plane patch over
//! the bounding curve's control points (its extent in the frame of the normal).
//!
//! Entity 106: `IP, N`, then the data points; forms 11 and 63 (`IP = 1`: `ZT`, then `N` pairs
//! `x, y` in the plane `z = ZT`), 12 (`IP = 2`: `N` triples) and 13 (`IP = 3`: `N` sextuples,
//! a point and a vector, the vector not kept) are paths through the points, read as degree-1
//! B-splines with the knots `0, 0, 1, …, N − 1, N − 1` (the polyline exactly); form 63 is
//! closed, its last segment back to the first point. The other forms are points without a
//! path, or drafting annotations, and are skipped naming the form.

use std::collections::{HashMap, HashSet};

use lekalo::surface::{Placement, FULL_TURN};
use lekalo::{BSplineCurve, BSplineSurface, NurbsSurface, Points};

use super::faces::Raw;
use super::fields::{count, real_at};
use super::matrix;
use crate::cad::motion::Motion;
use crate::object::Object;
use crate::shape::{Shape, Surface};

/// The points (entity 116, in millimetres) and directions (entity 123) of a file by the
/// sequence number of their directory entry, each placed by its own matrix (a direction turned
/// only), or why it was not read.
#[derive(Debug, Default)]
pub(super) struct Refs {
    pub(super) points: HashMap<u64, Result<[f64; 3], String>>,
    pub(super) directions: HashMap<u64, Result<[f64; 3], String>>,
}

impl Refs {
    /// Entity 116 or 123 (`ty`) from its parameters, placed by `motion`.
    pub(super) fn add(
        &mut self,
        ty: &str,
        seq: u64,
        f: &[String],
        unit_mm: f64,
        motion: Option<&Motion>,
    ) {
        let xyz = (1..=3)
            .map(|k| real_at(f, k))
            .collect::<Result<Vec<f64>, String>>()
            .map(|v| [v[0], v[1], v[2]]);
        if ty == "116" {
            let p = xyz.map(|mut p| {
                p = p.map(|x| x * unit_mm);
                if let Some(m) = motion {
                    m.point(&mut p);
                }
                p
            });
            self.points.insert(seq, p);
        } else {
            let d = xyz.map(|mut d| {
                if let Some(m) = motion {
                    m.direction(&mut d);
                }
                d
            });
            self.directions.insert(seq, d);
        }
    }

    fn point(&self, id: u64, what: &str) -> Result<[f64; 3], String> {
        match self.points.get(&id) {
            Some(Ok(p)) => Ok(*p),
            Some(Err(why)) => Err(format!("its {what} D{id} was not read: {why}")),
            None => Err(format!(
                "its {what} D{id} is not a point (entity 116) of the file"
            )),
        }
    }

    fn direction(&self, id: u64, what: &str) -> Result<[f64; 3], String> {
        match self.directions.get(&id) {
            Some(Ok(d)) => Ok(*d),
            Some(Err(why)) => Err(format!("its {what} D{id} was not read: {why}")),
            None => Err(format!(
                "its {what} D{id} is not a direction (entity 123) of the file"
            )),
        }
    }
}

/// An analytic surface waiting for the points, directions or curve it points at.
#[derive(Debug, Clone)]
pub(super) enum Analytic {
    /// 190: location, normal, reference direction (form 1).
    Plane {
        location: u64,
        normal: u64,
        reference: Option<u64>,
    },
    /// 192: location, axis, radius (mm), reference direction (form 1).
    Cylinder {
        location: u64,
        axis: u64,
        radius: f64,
        reference: Option<u64>,
    },
    /// 194: location, axis, radius at the location (mm), semi-angle (degrees), reference
    /// direction (form 1).
    Cone {
        location: u64,
        axis: u64,
        radius: f64,
        degrees: f64,
        reference: Option<u64>,
    },
    /// 196: centre, radius (mm), axis and reference direction (form 1).
    Sphere {
        centre: u64,
        radius: f64,
        axis: Option<(u64, u64)>,
    },
    /// 198: centre, axis, major and minor radii (mm), reference direction (form 1).
    Torus {
        centre: u64,
        axis: u64,
        major: f64,
        minor: f64,
        reference: Option<u64>,
    },
    /// 108 form ±1: the plane `n · x = d` (`d` in mm) over the closed curve it points at.
    BoundedPlane {
        normal: [f64; 3],
        d: f64,
        curve: u64,
    },
}

/// Parameter `k` as a pointer to a directory entry.
fn pointer(f: &[String], k: usize, what: &str) -> Result<u64, String> {
    let t = f.get(k).map_or("", |s| s.trim());
    match count(t) {
        Some(x) if x > 0 => Ok(x as u64),
        _ => Err(format!(
            "its {what} (parameter {k}) is \"{t}\", not a pointer to a directory entry"
        )),
    }
}

impl Analytic {
    /// The entity's kind, as the list of skipped entities names it.
    pub(super) fn entity(&self) -> &'static str {
        match self {
            Analytic::Plane { .. } => "IGES entity 190",
            Analytic::Cylinder { .. } => "IGES entity 192",
            Analytic::Cone { .. } => "IGES entity 194",
            Analytic::Sphere { .. } => "IGES entity 196",
            Analytic::Torus { .. } => "IGES entity 198",
            Analytic::BoundedPlane { .. } => "IGES entity 108",
        }
    }

    /// Whether the surface takes its extent from the faces on it.
    pub(super) fn unbounded(&self) -> bool {
        matches!(
            self,
            Analytic::Plane { .. } | Analytic::Cylinder { .. } | Analytic::Cone { .. }
        )
    }

    /// Entity `ty` (108, 190–198) of form `form` from its parameters `f`, lengths times
    /// `unit_mm`; or why it is not read.
    pub(super) fn from_parameters(
        ty: &str,
        form: &str,
        f: &[String],
        unit_mm: f64,
    ) -> Result<Analytic, String> {
        let form = form.trim();
        let num = |k: usize| real_at(f, k);
        let length = |k: usize| num(k).map(|x| x * unit_mm);
        let one = match (ty, form) {
            ("108", "1" | "-1") => false,
            ("108", "" | "0") => {
                return Err("an unbounded plane (form 0) has no extent of its own, and no face bounds it; lekalo reads the planes bounded by a closed curve (forms 1 and -1)".into())
            }
            (_, "" | "0") => false,
            (t, "1") if t != "108" => true,
            _ => {
                let forms = if ty == "108" { "-1, 0 and 1" } else { "0 and 1" };
                return Err(format!(
                    "form {form} is not a form of entity {ty} (IGES 5.3 defines {forms})"
                ));
            }
        };
        let reference = |k: usize| -> Result<Option<u64>, String> {
            if one {
                pointer(f, k, "reference direction REFDIR").map(Some)
            } else {
                Ok(None)
            }
        };
        Ok(match ty {
            "108" => {
                let n = [num(1)?, num(2)?, num(3)?];
                let curve = pointer(f, 5, "bounding curve PTR")?;
                Analytic::BoundedPlane {
                    normal: n,
                    d: length(4)?,
                    curve,
                }
            }
            "190" => Analytic::Plane {
                location: pointer(f, 1, "location LOCATION")?,
                normal: pointer(f, 2, "normal NORMAL")?,
                reference: reference(3)?,
            },
            "192" => Analytic::Cylinder {
                location: pointer(f, 1, "location LOCATION")?,
                axis: pointer(f, 2, "axis AXIS")?,
                radius: length(3)?,
                reference: reference(4)?,
            },
            "194" => Analytic::Cone {
                location: pointer(f, 1, "location LOCATION")?,
                axis: pointer(f, 2, "axis AXIS")?,
                radius: length(3)?,
                degrees: num(4)?,
                reference: reference(5)?,
            },
            "196" => Analytic::Sphere {
                centre: pointer(f, 1, "centre CENTER")?,
                radius: length(2)?,
                axis: if one {
                    Some((
                        pointer(f, 3, "axis AXIS")?,
                        pointer(f, 4, "reference direction REFDIR")?,
                    ))
                } else {
                    None
                },
            },
            _ => Analytic::Torus {
                centre: pointer(f, 1, "centre CENTER")?,
                axis: pointer(f, 2, "axis AXIS")?,
                major: length(3)?,
                minor: length(4)?,
                reference: reference(5)?,
            },
        })
    }

    /// The surface, placed by `motion`: `refs` gives the points and directions, `curve` the
    /// curves read (for 108), `bounds` the control points of the model-space curves of the
    /// faces on it (for 190, 192, 194).
    pub(super) fn build(
        &self,
        refs: &Refs,
        curve: &dyn Fn(u64) -> Option<Object>,
        bounds: Option<&[[f64; 3]]>,
        motion: Option<&Motion>,
    ) -> Result<Shape, String> {
        let lib = |e: lekalo::Error| e.to_string();
        let frame = |at: u64, what: &str, axis: Option<(u64, &str)>, reference: Option<u64>| {
            let o = refs.point(at, what)?;
            let z = axis.map(|(a, what)| refs.direction(a, what)).transpose()?;
            let x = reference
                .map(|r| refs.direction(r, "reference direction"))
                .transpose()?;
            Placement::new(o, z, x).map_err(|e| format!("its frame: {e}"))
        };
        let placed = |s: Surface| {
            let shape = Shape::Surface(s);
            match motion {
                Some(m) => matrix::moved(shape, m).map_err(lib),
                None => Ok(shape),
            }
        };
        let unbounded = |kind: &str| {
            format!("an unbounded {kind} has no extent of its own; lekalo reads it over the faces that bound it (trimmed or bounded surfaces, entities 144 and 143, read as faces with `--faces`), and none does")
        };
        // an unbounded surface is built where its faces are: its frame carried by the motion
        let in_model = |f: Placement| -> Result<Placement, String> {
            let Some(m) = motion else { return Ok(f) };
            rigid(m).then_some(()).ok_or_else(|| {
                "its transformation matrix scales or shears, which lekalo applies to the control points of a bounded surface only: the extent of this unbounded one is taken from its faces in its placed frame".to_string()
            })?;
            let (mut o, mut z, mut x) = (f.origin, f.z, f.x);
            m.point(&mut o);
            m.direction(&mut z);
            m.direction(&mut x);
            Placement::new(o, Some(z), Some(x)).map_err(lib)
        };
        let range = |f: &Placement, k: usize, kind: &str| -> Result<(f64, f64), String> {
            let pts = bounds.ok_or_else(|| unbounded(kind))?;
            let r = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |r, &p| {
                    let c = f.coordinates(p)[k];
                    (r.0.min(c), r.1.max(c))
                });
            if r.0 < r.1 {
                Ok(r)
            } else {
                Err(format!(
                    "the faces on this {kind} give it no extent (their boundary curves' control points span nothing across it)"
                ))
            }
        };
        match *self {
            Analytic::Plane {
                location,
                normal,
                reference,
            } => {
                let f = in_model(frame(
                    location,
                    "location",
                    Some((normal, "normal")),
                    reference,
                )?)?;
                let (u, v) = (range(&f, 0, "plane")?, range(&f, 1, "plane")?);
                BSplineSurface::plane_patch(&f, u, v)
                    .map(|s| Shape::Surface(Surface::BSpline(s)))
                    .map_err(lib)
            }
            Analytic::Cylinder {
                location,
                axis,
                radius,
                reference,
            } => {
                let f = in_model(frame(
                    location,
                    "location",
                    Some((axis, "axis")),
                    reference,
                )?)?;
                let v = range(&f, 2, "cylinder")?;
                NurbsSurface::cylinder(&f, radius, FULL_TURN, v)
                    .map(|s| Shape::Surface(Surface::Nurbs(s)))
                    .map_err(|e| format!("radius {radius} mm: {e}"))
            }
            Analytic::Cone {
                location,
                axis,
                radius,
                degrees,
                reference,
            } => {
                let f = in_model(frame(
                    location,
                    "location",
                    Some((axis, "axis")),
                    reference,
                )?)?;
                let v = range(&f, 2, "cone")?;
                NurbsSurface::cone(&f, radius, degrees.to_radians(), FULL_TURN, v)
                    .map(|s| Shape::Surface(Surface::Nurbs(s)))
                    .map_err(|e| {
                        format!("radius {radius} mm, semi-angle {degrees}° (IGES gives it in degrees, between 0 and 90 exclusive): {e}")
                    })
            }
            Analytic::Sphere {
                centre,
                radius,
                axis,
            } => {
                let f = match axis {
                    Some((a, r)) => frame(centre, "centre", Some((a, "axis")), Some(r))?,
                    None => frame(centre, "centre", None, None)?,
                };
                let half = std::f64::consts::FRAC_PI_2;
                let s = NurbsSurface::sphere(&f, radius, FULL_TURN, (-half, half))
                    .map_err(|e| format!("radius {radius} mm: {e}"))?;
                placed(Surface::Nurbs(s))
            }
            Analytic::Torus {
                centre,
                axis,
                major,
                minor,
                reference,
            } => {
                let f = frame(centre, "centre", Some((axis, "axis")), reference)?;
                let s =
                    NurbsSurface::torus(&f, major, minor, FULL_TURN, FULL_TURN).map_err(|e| {
                        format!("major radius {major} mm, minor radius {minor} mm: {e}")
                    })?;
                placed(Surface::Nurbs(s))
            }
            Analytic::BoundedPlane {
                normal,
                d,
                curve: id,
            } => {
                let n2 = normal.iter().map(|x| x * x).sum::<f64>();
                if !(n2 > 0.0 && n2.is_finite()) {
                    return Err(format!(
                        "its normal (A, B, C) = ({}, {}, {}) is zero: no plane",
                        normal[0], normal[1], normal[2]
                    ));
                }
                let origin = normal.map(|x| x * d / n2);
                let f = Placement::new(origin, Some(normal), None).map_err(lib)?;
                let c = curve(id).ok_or_else(|| {
                    format!("its bounding curve D{id} is not a curve lekalo read (entities 100, 102, 104, 106, 110, 112, 126)")
                })?;
                let cp = c.control_points();
                let mut u = (f64::INFINITY, f64::NEG_INFINITY);
                let mut v = u;
                for p in cp.as_slice().chunks_exact(cp.dim()) {
                    let q = [
                        p[0],
                        p.get(1).copied().unwrap_or(0.0),
                        p.get(2).copied().unwrap_or(0.0),
                    ];
                    let [a, b, _] = f.coordinates(q);
                    u = (u.0.min(a), u.1.max(a));
                    v = (v.0.min(b), v.1.max(b));
                }
                if !(u.0 < u.1 && v.0 < v.1) {
                    return Err(format!(
                        "its bounding curve D{id} encloses no area of the plane (its control points lie on a line)"
                    ));
                }
                let s = BSplineSurface::plane_patch(&f, u, v).map_err(lib)?;
                placed(Surface::BSpline(s))
            }
        }
    }
}

/// Whether a matrix is a rigid motion (an orthonormal `R`, reflections allowed), which maps a
/// cylinder, cone or plane onto one of the same kind and radius.
fn rigid(m: &Motion) -> bool {
    let cols = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(|mut e| {
        m.direction(&mut e);
        e
    });
    (0..3).all(|i| {
        (0..3).all(|j| {
            let dot: f64 = (0..3).map(|k| cols[i][k] * cols[j][k]).sum();
            (dot - if i == j { 1.0 } else { 0.0 }).abs() <= 1e-9
        })
    })
}

/// Entity 106 of form `form` from its parameters `f` as a degree-1 B-spline through its
/// points (in millimetres), or why not. The count `N` is checked against the parameters
/// before the points are allocated.
pub(super) fn copious(form: &str, f: &[String], unit_mm: f64) -> Result<Shape, String> {
    let form = form.trim();
    let (ip, closed) = match form {
        "11" => (1, false),
        "63" => (1, true),
        "12" => (2, false),
        "13" => (3, false),
        "" | "0" | "1" | "2" | "3" => {
            return Err(format!(
                "form {} holds data points without a path between them (lekalo reads the linear paths, forms 11, 12 and 13, and the closed planar curve, form 63)",
                if form.is_empty() { "0" } else { form }
            ))
        }
        _ => {
            return Err(format!(
                "form {form} is a drafting or finite-element form of copious data, not a curve (lekalo reads the linear paths, forms 11, 12 and 13, and the closed planar curve, form 63)"
            ))
        }
    };
    let at = |k: usize| f.get(k).and_then(|s| count(s));
    if at(1) != Some(ip) {
        return Err(format!(
            "form {form} has IP = {ip}, the entity says IP = \"{}\"",
            f.get(1).map_or("", |s| s.trim())
        ));
    }
    let n =
        at(2).ok_or_else(|| "its number of points N (parameter 2) is not a count".to_string())?;
    let (base, stride) = match ip {
        1 => (4, 2),
        2 => (3, 3),
        _ => (3, 6),
    };
    let need = n.checked_mul(stride).and_then(|x| x.checked_add(base));
    if need.is_none_or(|need| need > f.len()) {
        return Err(format!(
            "N = {n} points need {} parameters, the entity has {}; the count or the parameter data are wrong",
            need.map_or_else(|| "more".to_string(), |x| x.to_string()),
            f.len()
        ));
    }
    if n < 2 {
        return Err(format!("N = {n}: a path needs at least 2 points"));
    }
    let zt = if ip == 1 { real_at(f, 3)? } else { 0.0 };
    let mut data = Vec::with_capacity(3 * (n + 1));
    for i in 0..n {
        let k = base + stride * i;
        let z = if ip == 1 { zt } else { real_at(f, k + 2)? };
        data.extend([
            real_at(f, k)? * unit_mm,
            real_at(f, k + 1)? * unit_mm,
            z * unit_mm,
        ]);
    }
    if closed && data[..3] != data[data.len() - 3..] {
        let first = [data[0], data[1], data[2]];
        data.extend(first);
    }
    let m = data.len() / 3;
    let mut knots = Vec::with_capacity(m + 2);
    knots.push(0.0);
    knots.extend((0..m).map(|i| i as f64));
    knots.push((m - 1) as f64);
    let lib = |e: lekalo::Error| e.to_string();
    let pts = Points::from_flat(3, data).map_err(lib)?;
    BSplineCurve::new(1, knots, pts)
        .map(|c| Shape::Curve(Object::BSpline(c)))
        .map_err(lib)
}

/// Composite curves nested deeper than this are not followed for extents.
const MAX_NESTING: usize = 8;

/// The model-space curves of the faces on each surface: for every trimmed surface (144:
/// `PTS, N1, N2, PTO, PTI…`, boundaries 142 with the model-space curve `CPTR` at parameter 4)
/// and bounded surface (143: `TYPE, SPTR, N, BDPT…`, boundaries 141 with `CRVPT` at 5, 8 + K…),
/// the directory entries of its surface's boundary curves, composite curves (102) expanded,
/// each curve once per surface.
pub(super) fn face_curves(raw: &HashMap<u64, Raw>) -> HashMap<u64, HashSet<u64>> {
    let at = |e: &Raw, k: usize| e.fields.get(k).and_then(|s| count(s)).unwrap_or(0) as u64;
    let mut out: HashMap<u64, HashSet<u64>> = HashMap::new();
    for e in raw.values() {
        let (surface, boundaries): (u64, Vec<u64>) = match e.ty.as_str() {
            "144" => {
                let n2 = usize::try_from(at(e, 3)).unwrap_or(0).min(e.fields.len());
                (
                    at(e, 1),
                    std::iter::once(at(e, 4))
                        .chain((5..5 + n2).map(|k| at(e, k)))
                        .collect(),
                )
            }
            "143" => {
                let n = usize::try_from(at(e, 3)).unwrap_or(0).min(e.fields.len());
                (at(e, 2), (4..4 + n).map(|k| at(e, k)).collect())
            }
            _ => continue,
        };
        let set = out.entry(surface).or_default();
        for b in boundaries {
            let Some(be) = raw.get(&b) else { continue };
            let curves: Vec<u64> = match be.ty.as_str() {
                "142" => vec![at(be, 4)],
                "141" => {
                    let mut v = Vec::new();
                    let n = at(be, 4);
                    let mut k = 5usize;
                    for _ in 0..n {
                        if k >= be.fields.len() {
                            break;
                        }
                        v.push(at(be, k));
                        let kk = usize::try_from(at(be, k + 2)).unwrap_or(usize::MAX);
                        k = k.saturating_add(3).saturating_add(kk);
                    }
                    v
                }
                _ => continue,
            };
            for c in curves {
                expand(raw, c, 0, set);
            }
        }
    }
    out
}

/// Adds curve `id` to `set`, or the members of composite curve `id`, at most
/// [`MAX_NESTING`] deep; a composite already in the set is not expanded again.
fn expand(raw: &HashMap<u64, Raw>, id: u64, depth: usize, set: &mut HashSet<u64>) {
    if id == 0 || depth > MAX_NESTING || !set.insert(id) {
        return;
    }
    if let Some(e) = raw.get(&id).filter(|e| e.ty == "102") {
        let n = e.fields.get(1).and_then(|s| count(s)).unwrap_or(0);
        for k in 2..n.saturating_add(2).min(e.fields.len()) {
            if let Some(c) = e.fields.get(k).and_then(|s| count(s)) {
                expand(raw, c as u64, depth + 1, set);
            }
        }
    }
}
