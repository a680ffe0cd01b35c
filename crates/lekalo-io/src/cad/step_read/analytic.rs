//! Decoding of the analytic geometry (ISO 10303-42 §4.4–4.5): placements, lines, circles,
//! ellipses, polylines and trimmed curves over them; planes, cylinders, cones, spheres, tori,
//! surfaces of revolution and of linear extrusion, converted to exact NURBS by the library.
//!
//! Planes, cylinders, cones and extrusions are unbounded: their parameter ranges come from
//! the faces they carry ([`FaceBounds`]: the vertices of the faces' edges and the control
//! points of the edges' curves, which bound the curves), so the patch read covers every face on
//! the surface. Cylinders and cones take the full turn.

use std::collections::HashMap;
use std::f64::consts::TAU;

use lekalo::surface::{Placement, FULL_TURN};
use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points};

use super::entities::{is_bspline_curve, Reader, IMPLICIT_CURVES};
use super::{list, num, numbers, unnamed, Instance, Why, P};
use crate::object::Object;
use crate::shape::Surface;

/// The curve entities read as analytic curves.
pub(super) const ANALYTIC_CURVES: &[&str] = &["LINE", "CIRCLE", "ELLIPSE", "POLYLINE"];

/// The surface entities read as analytic surfaces.
pub(super) const ANALYTIC_SURFACES: &[&str] = &[
    "PLANE",
    "CYLINDRICAL_SURFACE",
    "CONICAL_SURFACE",
    "SPHERICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "DEGENERATE_TOROIDAL_SURFACE",
    "SURFACE_OF_REVOLUTION",
    "SURFACE_OF_LINEAR_EXTRUSION",
];

/// Deepest chain of curve references followed (trimmed curve of a trimmed curve, surface
/// curve of one…); real files nest one or two.
const MAX_CURVE_DEPTH: usize = 8;

/// A placement in the plane or in space: origin and the unit axes `x`, `y` (and `z` in space).
struct Frame {
    origin: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    space: Option<Placement>,
}

/// A curve that trims can cut: a spline, a conic by its eccentric angle, or a line.
pub(super) enum Basis {
    Spline(Object),
    Ellipse {
        frame: FrameBox,
        a: f64,
        b: f64,
    },
    Line {
        point: Vec<f64>,
        direction: Vec<f64>,
    },
}

/// A boxed frame (kept out of [`Basis`]'s size).
pub(super) struct FrameBox(Box<Frame>);

fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(p, q)| p - q).collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(p, q)| p * q).sum()
}

fn arr3(v: &[f64], what: &str) -> Result<[f64; 3], Why> {
    <[f64; 3]>::try_from(v).map_err(|_| format!("{what} has {} coordinates, not 3", v.len()))
}

fn lib(e: lekalo::Error) -> Why {
    e.to_string()
}

impl Basis {
    /// The whole curve; a line has none.
    pub(super) fn whole(&self) -> Result<Object, Why> {
        match self {
            Basis::Spline(o) => Ok(o.clone()),
            Basis::Ellipse { frame, a, b } => {
                let f = &frame.0;
                Ok(Object::Nurbs(
                    NurbsCurve::ellipse(&f.origin, &f.x, &f.y, *a, *b).map_err(lib)?,
                ))
            }
            Basis::Line { .. } => {
                Err("an unbounded line (no TRIMMED_CURVE or edge bounds it)".into())
            }
        }
    }

    /// The parameter of the curve's point nearest `p` (lines and conics; splines are trimmed
    /// by parameter values only).
    pub(super) fn parameter_of(&self, p: &[f64]) -> Option<f64> {
        match self {
            Basis::Spline(_) => None,
            Basis::Ellipse { frame, a, b } => {
                let f = &frame.0;
                let d = sub(p, &f.origin);
                let t = (dot(&d, &f.y) / b).atan2(dot(&d, &f.x) / a);
                Some(if t < 0.0 { t + TAU } else { t })
            }
            Basis::Line { point, direction } => {
                Some(dot(&sub(p, point), direction) / dot(direction, direction))
            }
        }
    }

    /// The piece from `t1` to `t2` in the direction given by `sense` (ISO 10303-42
    /// `trimmed_curve`, §4.4.29: on a closed conic the piece may pass through angle 0;
    /// `.F.` runs against the curve's direction).
    pub(super) fn piece(&self, t1: f64, t2: f64, sense: bool) -> Result<Object, Why> {
        match self {
            Basis::Spline(o) => {
                if sense != (t1 <= t2) {
                    return Err(format!(
                        "trims {t1} → {t2} with sense_agreement {} wrap around a closed curve",
                        if sense { ".T." } else { ".F." }
                    ));
                }
                let (a, b) = (t1.min(t2), t1.max(t2));
                let piece = restrict(o, a, b).map_err(lib)?;
                if sense {
                    Ok(piece)
                } else {
                    piece.reverse().map_err(lib)
                }
            }
            Basis::Ellipse { frame, a, b } => {
                let f = &frame.0;
                // the sweep from t1 to t2 along the sense, in (0, 2π]
                let mut sweep = (t2 - t1).rem_euclid(TAU);
                if sweep == 0.0 {
                    sweep = TAU;
                }
                if !sense {
                    sweep -= TAU;
                    if sweep == 0.0 {
                        sweep = -TAU;
                    }
                }
                Ok(Object::Nurbs(
                    NurbsCurve::elliptic_arc(&f.origin, &f.x, &f.y, *a, *b, t1, t1 + sweep)
                        .map_err(lib)?,
                ))
            }
            Basis::Line { point, direction } => {
                if t1 == t2 {
                    return Err(format!("the trims {t1} and {t2} of the line coincide"));
                }
                let seg = BSplineCurve::line_segment(point, direction, t1.min(t2), t1.max(t2))
                    .map_err(lib)?;
                let seg = Object::BSpline(seg);
                // a line cannot wrap: the piece between the trims, along the line when
                // `sense` holds and against it when not, whichever trim is the larger (as
                // Open CASCADE's Geom_TrimmedCurve reads a non-periodic basis)
                if sense {
                    Ok(seg)
                } else {
                    seg.reverse().map_err(lib)
                }
            }
        }
    }
}

fn restrict(o: &Object, a: f64, b: f64) -> lekalo::Result<Object> {
    let (lo, hi) = o.domain();
    let mut c = o.clone();
    if a > lo {
        c = c.split_at(a)?.1;
    }
    if b < hi {
        c = c.split_at(b)?.0;
    }
    Ok(c)
}

/// Points that bound the faces on each unbounded surface, by surface id (millimetres).
#[derive(Default)]
pub(super) struct FaceBounds {
    pub(super) points: HashMap<u64, Vec<[f64; 3]>>,
}

impl FaceBounds {
    /// The range of `f(p)` over the points bounding the faces of `surface`.
    fn range(&self, surface: u64, f: impl Fn([f64; 3]) -> f64) -> Option<(f64, f64)> {
        let pts = self.points.get(&surface)?;
        let mut r = (f64::INFINITY, f64::NEG_INFINITY);
        for &p in pts {
            let x = f(p);
            r = (r.0.min(x), r.1.max(x));
        }
        (r.0 < r.1).then_some(r)
    }
}

impl Reader<'_> {
    fn instance(&self, p: &P, what: &str) -> Result<(u64, Instance<'_>), Why> {
        let P::Ref(id) = p else {
            return Err(format!("{what} is not a reference"));
        };
        self.p
            .instances
            .get(id)
            .map(|i| (*id, i))
            .ok_or_else(|| format!("{what} #{id} is not defined"))
    }

    /// A `CARTESIAN_POINT`, 3-D coordinates in millimetres, moved by the placement of the part
    /// being read ([`Reader::motion`]).
    pub(super) fn location(&self, p: &P) -> Result<Vec<f64>, Why> {
        let (id, inst) = self.instance(p, "a point")?;
        let fast = inst
            .has("CARTESIAN_POINT")
            .then(|| inst.numbers())
            .flatten();
        let mut v = match fast {
            Some(v) => v,
            None => {
                let c = inst
                    .get("CARTESIAN_POINT")
                    .and_then(|r| r.get(1))
                    .ok_or_else(|| {
                        format!("#{id} is a {}, not a CARTESIAN_POINT", inst.type_name())
                    })?;
                numbers(c, &format!("the coordinates of #{id}"))?
            }
        };
        if v.len() == 3 {
            v.iter_mut().for_each(|x| *x *= self.scale);
            if let Some(m) = self.motion.get() {
                m.point(&mut v);
            }
        }
        Ok(v)
    }

    /// A `DIRECTION`, 3-D ones turned by the placement of the part being read.
    fn direction(&self, p: &P) -> Result<Vec<f64>, Why> {
        let mut d = self.direction_as_written(p)?;
        if let Some(m) = self.motion.get() {
            m.direction(&mut d);
        }
        Ok(d)
    }

    fn direction_as_written(&self, p: &P) -> Result<Vec<f64>, Why> {
        let (id, inst) = self.instance(p, "a direction")?;
        if let Some(v) = inst.has("DIRECTION").then(|| inst.numbers()).flatten() {
            return Ok(v);
        }
        let c = inst
            .get("DIRECTION")
            .and_then(|r| r.get(1))
            .ok_or_else(|| format!("#{id} is a {}, not a DIRECTION", inst.type_name()))?;
        numbers(c, &format!("the direction ratios of #{id}"))
    }

    /// An `AXIS2_PLACEMENT_3D` or `AXIS2_PLACEMENT_2D`.
    fn frame(&self, p: &P) -> Result<Frame, Why> {
        let (id, inst) = self.instance(p, "the position")?;
        if let Some(r) = inst.get("AXIS2_PLACEMENT_3D") {
            let o = arr3(&self.location(r.get(1).ok_or("no location")?)?, "location")?;
            let opt = |k: usize| -> Result<Option<[f64; 3]>, Why> {
                match r.get(k) {
                    Some(P::Unset) | None => Ok(None),
                    Some(q) => Ok(Some(arr3(&self.direction(q)?, "a direction")?)),
                }
            };
            let pl = Placement::new(o, opt(2)?, opt(3)?).map_err(lib)?;
            return Ok(Frame {
                origin: o.to_vec(),
                x: pl.x.to_vec(),
                y: pl.y.to_vec(),
                space: Some(pl),
            });
        }
        if let Some(r) = inst.get("AXIS2_PLACEMENT_2D") {
            let o = self.location(r.get(1).ok_or("no location")?)?;
            let x = match r.get(2) {
                Some(P::Unset) | None => vec![1.0, 0.0],
                Some(q) => self.direction(q)?,
            };
            let n = x.iter().map(|v| v * v).sum::<f64>().sqrt();
            if o.len() != 2 || x.len() != 2 || !(n > 0.0 && n.is_finite()) {
                return Err(format!(
                    "AXIS2_PLACEMENT_2D #{id} needs a 2-D location and a non-zero 2-D direction"
                ));
            }
            let x = vec![x[0] / n, x[1] / n];
            let y = vec![-x[1], x[0]];
            return Ok(Frame {
                origin: o,
                x,
                y,
                space: None,
            });
        }
        Err(format!(
            "the position #{id} is a {}, not an AXIS2_PLACEMENT_3D or _2D",
            inst.type_name()
        ))
    }

    pub(super) fn placement(&self, p: &P) -> Result<Placement, Why> {
        self.frame(p)?
            .space
            .ok_or_else(|| "a surface placed by a 2-D placement".to_string())
    }

    /// The placement of a `PLANE` instance (its parameters are lengths along the placement's
    /// unit `x` and `y`, as those of the patch [`BSplineSurface::plane_patch`] built for it).
    pub(super) fn plane_placement(&self, inst: &Instance<'_>) -> Option<Placement> {
        self.placement(inst.get("PLANE")?.get(1)?).ok()
    }

    /// A length of the file in millimetres (`dim` 3) or as written (2-D parameter space).
    fn length(&self, p: Option<&P>, what: &str, dim: usize) -> Result<f64, Why> {
        let x = p
            .and_then(num)
            .ok_or_else(|| format!("{what} is not a number"))?;
        Ok(if dim == 3 { x * self.scale } else { x })
    }

    /// The curve `id` as something trims can cut: B-spline, circle, ellipse or line.
    pub(super) fn basis(&self, id: u64) -> Result<Basis, Why> {
        self.basis_at(id, 0)
    }

    /// [`Reader::basis`] at a depth of references (a trimmed curve of a trimmed curve…),
    /// refused beyond [`MAX_CURVE_DEPTH`] so that a cycle of references ends.
    pub(super) fn basis_at(&self, id: u64, depth: usize) -> Result<Basis, Why> {
        if depth > MAX_CURVE_DEPTH {
            return Err(format!(
                "curve #{id} is reached through more than {MAX_CURVE_DEPTH} trimmed or surface curves (a cycle of references?)"
            ));
        }
        let inst = self
            .p
            .instances
            .get(&id)
            .ok_or_else(|| format!("curve #{id} is not defined"))?;
        if is_bspline_curve(&inst) {
            return self.curve(&inst).map(Basis::Spline);
        }
        if let Some(r) = inst.get("CIRCLE") {
            let f = self.frame(r.get(1).ok_or("CIRCLE has no position")?)?;
            let rad = self.length(r.get(2), "the radius", f.origin.len())?;
            return Ok(Basis::Ellipse {
                frame: FrameBox(Box::new(f)),
                a: rad,
                b: rad,
            });
        }
        if let Some(r) = inst.get("ELLIPSE") {
            let f = self.frame(r.get(1).ok_or("ELLIPSE has no position")?)?;
            let dim = f.origin.len();
            let a = self.length(r.get(2), "semi_axis_1", dim)?;
            let b = self.length(r.get(3), "semi_axis_2", dim)?;
            return Ok(Basis::Ellipse {
                frame: FrameBox(Box::new(f)),
                a,
                b,
            });
        }
        if let Some(r) = inst.get("LINE") {
            let point = self.location(r.get(1).ok_or("LINE has no point")?)?;
            let (_, v) = self.instance(r.get(2).ok_or("LINE has no direction")?, "the vector")?;
            let v = v
                .get("VECTOR")
                .filter(|v| v.len() >= 3)
                .ok_or("the LINE's dir is not a VECTOR")?;
            let d = self.direction(&v[1])?;
            let n = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            let m = self.length(v.get(2), "the vector's magnitude", d.len())?;
            if d.len() != point.len() || n <= 0.0 || n.is_nan() {
                return Err(
                    "the LINE's point and direction differ in dimension or the direction is zero"
                        .into(),
                );
            }
            return Ok(Basis::Line {
                point,
                direction: d.iter().map(|x| x / n * m).collect(),
            });
        }
        if let Some(r) = inst.get("POLYLINE") {
            let pts = list(r.get(1).ok_or("POLYLINE has no points")?)
                .ok_or("the POLYLINE's points are not a list")?
                .iter()
                .map(|q| self.location(q))
                .collect::<Result<Vec<_>, _>>()?;
            // ISO 10303-42 §4.4.11: segment i on [i − 1, i]
            let n = pts.len();
            let mut knots = Vec::with_capacity(n + 2);
            knots.push(0.0);
            knots.extend((0..n).map(|i| i as f64));
            knots.push(n.saturating_sub(1) as f64);
            let c =
                BSplineCurve::new(1, knots, Points::from_rows(&pts).map_err(lib)?).map_err(lib)?;
            return Ok(Basis::Spline(Object::BSpline(c)));
        }
        if let Some(r) = inst.get("TRIMMED_CURVE") {
            let mut budget = usize::MAX;
            return self
                .trimmed_at(r, &mut budget, depth + 1)
                .map(|(_, o)| Basis::Spline(o));
        }
        for name in ["SURFACE_CURVE", "SEAM_CURVE", "INTERSECTION_CURVE"] {
            if let Some(P::Ref(c)) = inst.get(name).and_then(|r| unnamed(r).first()) {
                return self.basis_at(*c, depth + 1);
            }
        }
        Err(format!(
            "the curve #{id} is a {} (lekalo reads B-splines, lines, circles, ellipses and polylines)",
            inst.type_name()
        ))
    }

    /// A surface of [`ANALYTIC_SURFACES`], with the bounds its faces give to unbounded ones.
    pub(super) fn analytic_surface(
        &self,
        id: u64,
        inst: &Instance<'_>,
        bounds: &FaceBounds,
        curves: &HashMap<u64, Object>,
    ) -> Result<Surface, Why> {
        let (name, r) = inst
            .records()
            .iter()
            .find(|(n, _)| ANALYTIC_SURFACES.contains(&n.as_str()))
            .ok_or("not an analytic surface")?;
        let unbounded = |kind: &str| format!("unbounded {kind} without a face to bound it");
        match name.as_str() {
            "PLANE" => {
                let f = self.placement(r.get(1).ok_or("PLANE has no position")?)?;
                let u = bounds.range(id, |p| f.coordinates(p)[0]);
                let v = bounds.range(id, |p| f.coordinates(p)[1]);
                let (Some(u), Some(v)) = (u, v) else {
                    return Err(unbounded("plane"));
                };
                Ok(Surface::BSpline(
                    BSplineSurface::plane_patch(&f, u, v).map_err(lib)?,
                ))
            }
            "CYLINDRICAL_SURFACE" => {
                let f = self.placement(r.get(1).ok_or("CYLINDRICAL_SURFACE has no position")?)?;
                let rad = self.length(r.get(2), "the radius", 3)?;
                let v = bounds
                    .range(id, |p| f.coordinates(p)[2])
                    .ok_or_else(|| unbounded("cylinder"))?;
                Ok(Surface::Nurbs(
                    NurbsSurface::cylinder(&f, rad, FULL_TURN, v).map_err(lib)?,
                ))
            }
            "CONICAL_SURFACE" => {
                let f = self.placement(r.get(1).ok_or("CONICAL_SURFACE has no position")?)?;
                let rad = self.length(r.get(2), "the radius", 3)?;
                let angle =
                    r.get(3).and_then(num).ok_or("semi_angle is not a number")? * self.angle;
                let v = bounds
                    .range(id, |p| f.coordinates(p)[2])
                    .ok_or_else(|| unbounded("cone"))?;
                Ok(Surface::Nurbs(
                    NurbsSurface::cone(&f, rad, angle, FULL_TURN, v).map_err(lib)?,
                ))
            }
            "SPHERICAL_SURFACE" => {
                let f = self.placement(r.get(1).ok_or("SPHERICAL_SURFACE has no position")?)?;
                let rad = self.length(r.get(2), "the radius", 3)?;
                let half = std::f64::consts::FRAC_PI_2;
                Ok(Surface::Nurbs(
                    NurbsSurface::sphere(&f, rad, FULL_TURN, (-half, half)).map_err(lib)?,
                ))
            }
            "TOROIDAL_SURFACE" | "DEGENERATE_TOROIDAL_SURFACE" => {
                let f = self.placement(r.get(1).ok_or("TOROIDAL_SURFACE has no position")?)?;
                let big = self.length(r.get(2), "the major radius", 3)?;
                let small = self.length(r.get(3), "the minor radius", 3)?;
                Ok(Surface::Nurbs(
                    NurbsSurface::torus(&f, big, small, FULL_TURN, FULL_TURN).map_err(lib)?,
                ))
            }
            "SURFACE_OF_REVOLUTION" => {
                let c = self.swept(r.get(1), curves)?;
                let (_, ax) = self.instance(r.get(2).ok_or("no axis_position")?, "the axis")?;
                let ax = ax
                    .get("AXIS1_PLACEMENT")
                    .ok_or("the axis is not an AXIS1_PLACEMENT")?;
                let o = arr3(&self.location(ax.get(1).ok_or("no location")?)?, "location")?;
                let z = match ax.get(2) {
                    Some(P::Unset) | None => [0.0, 0.0, 1.0],
                    Some(q) => arr3(&self.direction(q)?, "the axis")?,
                };
                Ok(Surface::Nurbs(
                    NurbsSurface::revolve(&c, o, z, 0.0, TAU).map_err(lib)?,
                ))
            }
            "SURFACE_OF_LINEAR_EXTRUSION" => {
                let c = self.swept(r.get(1), curves)?;
                let (_, v) = self.instance(r.get(2).ok_or("no extrusion_axis")?, "the axis")?;
                let v = v
                    .get("VECTOR")
                    .filter(|v| v.len() >= 3)
                    .ok_or("the extrusion_axis is not a VECTOR")?;
                let d = arr3(&self.direction(&v[1])?, "the extrusion direction")?;
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let m = self.length(v.get(2), "the vector's magnitude", 3)?;
                if !(n > 0.0 && m != 0.0) {
                    return Err("the extrusion vector is zero".into());
                }
                let unit = [d[0] / n, d[1] / n, d[2] / n];
                let vec = [unit[0] * m, unit[1] * m, unit[2] * m];
                // S(u, v) = C(u) + v V: over the faces' points p, v·|V|·sign(m) = p·û − C(u)·û
                // lies between the ranges of p·û and of the curve's control points
                let along = |p: [f64; 3]| p[0] * unit[0] + p[1] * unit[1] + p[2] * unit[2];
                let (plo, phi) = bounds
                    .range(id, along)
                    .ok_or_else(|| unbounded("surface of linear extrusion"))?;
                let cp = c.control_points();
                let (clo, chi) = cp.as_slice().chunks_exact(3).fold(
                    (f64::INFINITY, f64::NEG_INFINITY),
                    |(lo, hi), q| {
                        let x = along([q[0], q[1], q[2]]);
                        (lo.min(x), hi.max(x))
                    },
                );
                let (a, b) = ((plo - chi) / m, (phi - clo) / m);
                Ok(Surface::Nurbs(
                    NurbsSurface::extrude(&c, vec, a.min(b), a.max(b)).map_err(lib)?,
                ))
            }
            other => Err(format!("{other} is not read")),
        }
    }

    /// The swept curve of a swept surface, as a 3-D NURBS curve.
    fn swept(&self, p: Option<&P>, curves: &HashMap<u64, Object>) -> Result<NurbsCurve, Why> {
        let Some(P::Ref(c)) = p else {
            return Err("the swept_curve is not a reference".into());
        };
        let o = match curves.get(c) {
            Some(o) => o.clone(),
            None => self.basis(*c)?.whole()?,
        };
        let n = o.to_nurbs();
        if n.dim() != 3 {
            return Err(format!("the swept curve #{c} is not 3-D"));
        }
        Ok(n)
    }
}

/// Trimmed curves: a basis curve (B-spline, line, conic, polyline) cut at its trims.
impl Reader<'_> {
    /// A `TRIMMED_CURVE` (ISO 10303-42 §4.4.29) over a B-spline, line, circle, ellipse or
    /// polyline, trimmed by parameter values or by points (the parameter of a conic is its
    /// angle, in the file's plane angle unit). `budget` is the number of basis control points
    /// trims may still read: a basis is read once per trim, so without it a file of many short
    /// trims of one long curve would be read in quadratic time.
    pub(super) fn trimmed(&self, r: &[P], budget: &mut usize) -> Result<(u64, Object), Why> {
        self.trimmed_at(r, budget, 0)
    }

    /// [`Reader::trimmed`] at a depth of curve references (see [`Reader::basis_at`]).
    pub(super) fn trimmed_at(
        &self,
        r: &[P],
        budget: &mut usize,
        depth: usize,
    ) -> Result<(u64, Object), Why> {
        if r.len() < 5 {
            return Err(
                "TRIMMED_CURVE needs name, basis_curve, trim_1, trim_2, sense_agreement".into(),
            );
        }
        let P::Ref(basis) = &r[1] else {
            return Err("basis_curve is not a reference".into());
        };
        let inst = self
            .p
            .instances
            .get(basis)
            .ok_or_else(|| format!("basis curve #{basis} is not defined"))?;
        // the count of each basis is kept: a basis is parsed from the text once, not once a trim
        let known = self.basis_sizes.borrow().get(basis).copied();
        let size = known.unwrap_or_else(|| {
            let size = if is_bspline_curve(&inst) {
                inst.records()
                    .iter()
                    .find_map(|(name, r)| {
                        let at = if name == "B_SPLINE_CURVE" {
                            1
                        } else if name == "B_SPLINE_CURVE_WITH_KNOTS"
                            || IMPLICIT_CURVES.iter().any(|(n, _)| n == name)
                        {
                            2
                        } else {
                            return None;
                        };
                        r.get(at).and_then(list).map(<[P]>::len)
                    })
                    .unwrap_or(0)
            } else {
                0
            };
            self.basis_sizes.borrow_mut().insert(*basis, size);
            size
        });
        *budget = budget.checked_sub(size).ok_or_else(|| {
            format!(
                "the basis curve #{basis} ({size} control points) is one of bases trimmed more often than the file's size allows to read"
            )
        })?;
        let curve = self.basis_at(*basis, depth + 1)?;
        let conic = matches!(curve, Basis::Ellipse { .. });
        let master_points = matches!(r.get(5), Some(P::Enum(e)) if e == "CARTESIAN");
        let trim = |p: &P| -> Option<f64> {
            let items = list(p)?;
            let by_value = items.iter().find_map(|x| match x {
                P::Typed(k, v) if k == "PARAMETER_VALUE" => {
                    v.first()
                        .and_then(num)
                        .map(|t| if conic { t * self.angle } else { t })
                }
                _ => None,
            });
            let by_point = || {
                items.iter().find_map(|x| match x {
                    P::Ref(_) => self.location(x).ok().and_then(|q| curve.parameter_of(&q)),
                    _ => None,
                })
            };
            match by_value {
                Some(t) if !master_points => Some(t),
                _ => by_point().or(by_value),
            }
        };
        let (Some(t1), Some(t2)) = (trim(&r[2]), trim(&r[3])) else {
            return Err("not trimmed by parameter values, nor by points on a line or conic".into());
        };
        let sense = match &r[4] {
            P::Enum(e) => e == "T",
            _ => return Err("sense_agreement is not .T. or .F.".into()),
        };
        let piece = curve.piece(t1, t2, sense)?;
        Ok((*basis, piece))
    }
}
