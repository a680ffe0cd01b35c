//! Decoding of the entities read: B-spline curves and surfaces (plain or complex instances,
//! rational or not), their points and knots; the other geometry, which is listed as skipped.

use std::cell::{Cell, RefCell};

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points};

use super::parse::Parsed;
use super::{int, list, numbers, Instance, Why, P};
use crate::error::Location;
use crate::object::Object;
use crate::shape::Surface;

/// Tessellated geometry (AP242 meshes: triangulated faces and surface sets, tessellated
/// shells, solids and curve sets), reported as skipped.
pub(super) const TESSELLATED: &[&str] = &[
    "TRIANGULATED_FACE",
    "COMPLEX_TRIANGULATED_FACE",
    "TRIANGULATED_SURFACE_SET",
    "COMPLEX_TRIANGULATED_SURFACE_SET",
    "TESSELLATED_SHELL",
    "TESSELLATED_SOLID",
    "TESSELLATED_CURVE_SET",
    "TESSELLATED_POINT_SET",
];

/// Curve and surface entities that are geometry but not read, reported as skipped.
pub(super) const OTHER_GEOMETRY: &[&str] = &[
    "PARABOLA",
    "HYPERBOLA",
    "OFFSET_CURVE_2D",
    "OFFSET_CURVE_3D",
    "COMPOSITE_CURVE",
    "COMPOSITE_CURVE_ON_SURFACE",
    "BOUNDARY_CURVE",
    "OUTER_BOUNDARY_CURVE",
    "OFFSET_SURFACE",
    "RECTANGULAR_TRIMMED_SURFACE",
];

pub(super) struct Reader<'a> {
    pub(super) p: &'a Parsed<'a>,
    pub(super) source: &'a str,
    pub(super) scale: f64,
    /// The plane angle unit in radians (1 for radians, π/180 for degrees).
    pub(super) angle: f64,
    /// The most control points and knots the file's B-splines may hold together (`--max-size`).
    pub(super) max_size: usize,
    /// Control points and knots read so far.
    pub(super) used: Cell<usize>,
    /// The refusal, once the file went past [`Reader::max_size`].
    pub(super) over: RefCell<Option<(String, u64)>>,
    /// The control points of each basis of trimmed curves met, by id (see
    /// [`Reader::trimmed`]).
    pub(super) basis_sizes: RefCell<std::collections::HashMap<u64, usize>>,
    /// The placement of the part whose geometry is being read, in an assembly
    /// (`assembly.rs`): 3-D points and directions are moved by it; `None` reads them as
    /// written.
    pub(super) motion: Cell<Option<crate::cad::motion::Motion>>,
}

impl Reader<'_> {
    /// Counts `n` more control points or knots of the entity being read (`what`), before they
    /// are allocated: past [`Reader::max_size`] the entity is refused and the refusal kept for
    /// the whole read ([`IoError::OverLimit`](crate::IoError::OverLimit) in `read_step`).
    pub(super) fn charge(&self, n: usize, what: &str) -> Result<(), Why> {
        let total = self.used.get().saturating_add(n);
        if total > self.max_size {
            let why = format!(
                "{total} control points and knots with this entity's {n} {what}, above the size limit {}",
                self.max_size
            );
            self.over
                .borrow_mut()
                .get_or_insert_with(|| (why.clone(), total as u64));
            return Err(why);
        }
        self.used.set(total);
        Ok(())
    }
}

/// The knots of one direction, each repeated by its multiplicity, for `n` control points of
/// degree `degree` (`dir` is `""`, `"u "` or `"v "` in messages). Those need `n + degree + 1`
/// knots: a degree or a sum of multiplicities that does not fit is refused before anything is
/// allocated, so that a multiplicity of 2^31 in a 300-byte file asks for no memory, and a sum
/// beyond the range of the integers is an error rather than a wrap.
fn expand_knots(mults: &P, knots: &P, n: usize, degree: usize, dir: &str) -> Result<Vec<f64>, Why> {
    let m: Vec<usize> = list(mults)
        .and_then(|l| l.iter().map(int).collect::<Option<Vec<_>>>())
        .ok_or_else(|| {
            format!("{dir}knot_multiplicities is not a list of non-negative integers")
        })?;
    let k = numbers(knots, &format!("{dir}knots"))?;
    if m.len() != k.len() {
        return Err(format!(
            "{} {dir}knot multiplicities for {} knots",
            m.len(),
            k.len()
        ));
    }
    if degree >= n {
        return Err(format!(
            "{dir}degree {degree} needs at least {} control points, there are {n}",
            degree.saturating_add(1)
        ));
    }
    // n and degree < n come from lists of the file, so this sum is far below usize::MAX
    let expected = n + degree + 1;
    let total = m.iter().try_fold(0usize, |sum, &x| sum.checked_add(x));
    match total {
        Some(t) if t == expected => {}
        Some(t) => {
            return Err(format!(
                "the {dir}knot multiplicities add up to {t} knots; {n} control points of degree {degree} need {expected}"
            ))
        }
        None => {
            return Err(format!(
                "the {dir}knot multiplicities add up to more than 2^64 knots; {n} control points of degree {degree} need {expected}"
            ))
        }
    }
    let mut out = Vec::with_capacity(expected);
    for (x, n) in k.iter().zip(&m) {
        out.extend(std::iter::repeat_n(*x, *n));
    }
    Ok(out)
}

/// The knot forms of ISO 10303-42 whose knots are implied (`knot_type`, §4.3.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum KnotForm {
    /// `UNIFORM_*`: simple knots with spacing 1, the first at `-degree`.
    Uniform,
    /// `QUASI_UNIFORM_*`: simple interior knots with spacing 1 and ends of multiplicity
    /// `degree + 1`, from 0.
    QuasiUniform,
    /// `BEZIER_*` (and `PIECEWISE_BEZIER_*`): knots 0, 1, 2, … of multiplicity `degree`, ends
    /// `degree + 1`.
    PiecewiseBezier,
}

/// The curve entities of an implied knot form.
pub(super) const IMPLICIT_CURVES: &[(&str, KnotForm)] = &[
    ("UNIFORM_CURVE", KnotForm::Uniform),
    ("QUASI_UNIFORM_CURVE", KnotForm::QuasiUniform),
    ("BEZIER_CURVE", KnotForm::PiecewiseBezier),
    ("PIECEWISE_BEZIER_CURVE", KnotForm::PiecewiseBezier),
];

/// The surface entities of an implied knot form.
const IMPLICIT_SURFACES: &[(&str, KnotForm)] = &[
    ("UNIFORM_SURFACE", KnotForm::Uniform),
    ("QUASI_UNIFORM_SURFACE", KnotForm::QuasiUniform),
    ("BEZIER_SURFACE", KnotForm::PiecewiseBezier),
    ("PIECEWISE_BEZIER_SURFACE", KnotForm::PiecewiseBezier),
];

/// The knots of one direction: given by multiplicities and values, or implied by the form.
enum Knots<'a> {
    Given(&'a P, &'a P),
    Implied(KnotForm),
}

impl Knots<'_> {
    fn expand(&self, n: usize, degree: usize, dir: &str) -> Result<Vec<f64>, Why> {
        match self {
            Knots::Given(m, k) => expand_knots(m, k, n, degree, dir),
            Knots::Implied(f) => implicit_knots(*f, n, degree, dir),
        }
    }
}

/// The `n + degree + 1` knots that ISO 10303-42 implies for `n` control points of `degree`
/// (the functions `default_b_spline_knots` and `default_b_spline_knot_mult` of §4.3.4):
/// uniform: `−d, −d + 1, …, n` (each once); quasi-uniform: `0, 1, …, n − d`, the ends repeated
/// `d + 1` times; piecewise Bezier (and Bezier): `0, 1, …, (n − 1)/d`, the ends repeated
/// `d + 1` times and the interior `d` times, which needs `n − 1` divisible by `d`.
pub(super) fn implicit_knots(
    form: KnotForm,
    n: usize,
    degree: usize,
    dir: &str,
) -> Result<Vec<f64>, Why> {
    if degree >= n || degree == 0 {
        return Err(format!(
            "{dir}degree {degree} of an implicit-knot B-spline needs a degree of at least 1 and at least {} control points, there are {n}",
            degree.saturating_add(1)
        ));
    }
    // n and degree < n come from lists of the file, so these sums are far below usize::MAX
    let mut k = Vec::with_capacity(n + degree + 1);
    match form {
        KnotForm::Uniform => k.extend((0..n + degree + 1).map(|i| i as f64 - degree as f64)),
        KnotForm::QuasiUniform => {
            let last = (n - degree) as f64;
            k.extend(std::iter::repeat_n(0.0, degree));
            k.extend((0..=n - degree).map(|i| i as f64));
            k.extend(std::iter::repeat_n(last, degree));
        }
        KnotForm::PiecewiseBezier => {
            if (n - 1) % degree != 0 {
                return Err(format!(
                    "a piecewise Bezier {dir}form of degree {degree} has 1 + {degree}·k control points, there are {n}"
                ));
            }
            let pieces = (n - 1) / degree;
            k.push(0.0);
            for i in 0..=pieces {
                k.extend(std::iter::repeat_n(i as f64, degree));
            }
            k.push(pieces as f64);
        }
    }
    Ok(k)
}

impl Reader<'_> {
    pub(super) fn at(&self, id: u64) -> Location {
        let mut loc = Location::new(self.source);
        if let Some(i) = self.p.instances.get(&id) {
            loc = loc.at_line(i.line());
        }
        loc
    }

    fn point(&self, p: &P) -> Result<Vec<f64>, Why> {
        let P::Ref(id) = p else {
            return Err("a control point is not a reference to a CARTESIAN_POINT".into());
        };
        let inst = self
            .p
            .instances
            .get(id)
            .ok_or_else(|| format!("control point #{id} is not defined"))?;
        if !inst.has("CARTESIAN_POINT") {
            return Err(format!(
                "control point #{id} is a {}, not a CARTESIAN_POINT",
                inst.type_name()
            ));
        }
        if let Some(coords) = inst.numbers() {
            return Ok(coords);
        }
        let c = inst.get("CARTESIAN_POINT").unwrap_or_default();
        let coords = c
            .get(1)
            .ok_or_else(|| format!("CARTESIAN_POINT #{id} has no coordinates"))
            .and_then(|c| numbers(c, &format!("the coordinates of #{id}")))?;
        Ok(coords)
    }

    fn points(&self, p: &P) -> Result<Points, Why> {
        let items = list(p).ok_or("control_points_list is not a list")?;
        self.charge(items.len(), "control points")?;
        let rows = items
            .iter()
            .map(|q| self.point(q))
            .collect::<Result<Vec<_>, _>>()?;
        let mut pts = Points::from_rows(&rows).map_err(|e| e.to_string())?;
        if pts.dim() == 3 && self.scale != 1.0 {
            let s = self.scale;
            pts = Points::from_flat(3, pts.as_slice().iter().map(|x| x * s).collect())
                .map_err(|e| e.to_string())?;
        }
        if let (3, Some(m)) = (pts.dim(), self.motion.get()) {
            let mut flat = pts.as_slice().to_vec();
            flat.chunks_exact_mut(3).for_each(|p| m.point(p));
            pts = Points::from_flat(3, flat).map_err(|e| e.to_string())?;
        }
        Ok(pts)
    }

    /// A B-spline curve instance (simple or complex, rational or not), with its knots given
    /// (`B_SPLINE_CURVE_WITH_KNOTS`) or implied by its form (`UNIFORM_CURVE`,
    /// `QUASI_UNIFORM_CURVE`, `BEZIER_CURVE`, see [`implicit_knots`]).
    pub(super) fn curve(&self, inst: &Instance<'_>) -> Result<Object, Why> {
        let (degree, ctrl, knots, weights) = if let Some(r) = inst
            .get("B_SPLINE_CURVE_WITH_KNOTS")
            .filter(|r| r.len() >= 9)
        {
            (&r[1], &r[2], Knots::Given(&r[6], &r[7]), None)
        } else if let Some((form, r)) = IMPLICIT_CURVES
            .iter()
            .find_map(|&(n, f)| Some((f, inst.get(n).filter(|r| r.len() >= 3)?)))
        {
            (&r[1], &r[2], Knots::Implied(form), None)
        } else {
            let b = inst
                .get("B_SPLINE_CURVE")
                .filter(|r| r.len() >= 2)
                .ok_or("no B_SPLINE_CURVE record with degree and control points")?;
            let knots = match inst
                .get("B_SPLINE_CURVE_WITH_KNOTS")
                .filter(|r| r.len() >= 2)
            {
                Some(k) => Knots::Given(&k[0], &k[1]),
                None => Knots::Implied(
                    IMPLICIT_CURVES
                        .iter()
                        .find(|(n, _)| inst.has(n))
                        .map(|&(_, f)| f)
                        .ok_or("B_SPLINE_CURVE without a knot form (B_SPLINE_CURVE_WITH_KNOTS, UNIFORM_CURVE, QUASI_UNIFORM_CURVE or BEZIER_CURVE)")?,
                ),
            };
            let w = inst.get("RATIONAL_B_SPLINE_CURVE").and_then(|r| r.first());
            (&b[0], &b[1], knots, w)
        };
        let degree = int(degree).ok_or("degree is not a non-negative integer")?;
        let ctrl = self.points(ctrl)?;
        self.charge(ctrl.len().saturating_add(degree).saturating_add(1), "knots")?;
        let knots = knots.expand(ctrl.len(), degree, "")?;
        let obj = match weights {
            None => {
                Object::BSpline(BSplineCurve::new(degree, knots, ctrl).map_err(|e| e.to_string())?)
            }
            Some(w) => {
                let w = numbers(w, "weights_data")?;
                Object::Nurbs(NurbsCurve::new(degree, knots, ctrl, w).map_err(|e| e.to_string())?)
            }
        };
        Ok(obj)
    }

    /// A B-spline surface instance (simple or complex, rational or not), with its knots given
    /// or implied by its form as for curves.
    pub(super) fn surface(&self, inst: &Instance<'_>) -> Result<Surface, Why> {
        let simple = inst
            .get("B_SPLINE_SURFACE_WITH_KNOTS")
            .filter(|r| r.len() >= 13);
        let (du, dv, net, ku, kv, weights) = if let Some(r) = simple {
            (
                &r[1],
                &r[2],
                &r[3],
                Knots::Given(&r[8], &r[10]),
                Knots::Given(&r[9], &r[11]),
                None,
            )
        } else if let Some((form, r)) = IMPLICIT_SURFACES
            .iter()
            .find_map(|&(n, f)| Some((f, inst.get(n).filter(|r| r.len() >= 4)?)))
        {
            (
                &r[1],
                &r[2],
                &r[3],
                Knots::Implied(form),
                Knots::Implied(form),
                None,
            )
        } else {
            let b = inst
                .get("B_SPLINE_SURFACE")
                .filter(|r| r.len() >= 3)
                .ok_or("no B_SPLINE_SURFACE record with degrees and control points")?;
            let (ku, kv) = match inst
                .get("B_SPLINE_SURFACE_WITH_KNOTS")
                .filter(|r| r.len() >= 4)
            {
                Some(k) => (Knots::Given(&k[0], &k[2]), Knots::Given(&k[1], &k[3])),
                None => {
                    let form = IMPLICIT_SURFACES
                        .iter()
                        .find(|(n, _)| inst.has(n))
                        .map(|&(_, f)| f)
                        .ok_or("B_SPLINE_SURFACE without a knot form (B_SPLINE_SURFACE_WITH_KNOTS, UNIFORM_SURFACE, QUASI_UNIFORM_SURFACE or BEZIER_SURFACE)")?;
                    (Knots::Implied(form), Knots::Implied(form))
                }
            };
            let w = inst
                .get("RATIONAL_B_SPLINE_SURFACE")
                .and_then(|r| r.first());
            (&b[0], &b[1], &b[2], ku, kv, w)
        };
        let du = int(du).ok_or("u_degree is not a non-negative integer")?;
        let dv = int(dv).ok_or("v_degree is not a non-negative integer")?;
        let rows = list(net).ok_or("control_points_list is not a list of lists")?;
        let nu = rows.len();
        let mut nv = 0;
        let mut flat: Vec<f64> = Vec::new();
        let mut dim = 0;
        for (i, row) in rows.iter().enumerate() {
            let pts = self.points(row)?;
            if i == 0 {
                nv = pts.len();
                dim = pts.dim();
            } else if pts.len() != nv || pts.dim() != dim {
                return Err(format!(
                    "row {i} of the control net has {} points of dimension {}, row 0 has {nv} of dimension {dim}",
                    pts.len(),
                    pts.dim()
                ));
            }
            flat.extend_from_slice(pts.as_slice());
        }
        let ctrl = Points::from_flat(dim.max(1), flat).map_err(|e| e.to_string())?;
        self.charge(nu.saturating_add(du).saturating_add(1), "u knots")?;
        let ku = ku.expand(nu, du, "u ")?;
        self.charge(nv.saturating_add(dv).saturating_add(1), "v knots")?;
        let kv = kv.expand(nv, dv, "v ")?;
        Ok(match weights {
            None => Surface::BSpline(
                BSplineSurface::new(du, dv, ku, kv, ctrl, (nu, nv)).map_err(|e| e.to_string())?,
            ),
            Some(w) => {
                let mut ws = Vec::with_capacity(nu * nv);
                for row in list(w).ok_or("weights_data is not a list of lists")? {
                    ws.extend(numbers(row, "a row of weights_data")?);
                }
                Surface::Nurbs(
                    NurbsSurface::new(du, dv, ku, kv, ctrl, ws, (nu, nv))
                        .map_err(|e| e.to_string())?,
                )
            }
        })
    }
}

pub(super) fn is_bspline_curve(i: &Instance<'_>) -> bool {
    i.has("B_SPLINE_CURVE_WITH_KNOTS")
        || i.has("B_SPLINE_CURVE")
        || IMPLICIT_CURVES.iter().any(|(n, _)| i.has(n))
}

pub(super) fn is_bspline_surface(i: &Instance<'_>) -> bool {
    i.has("B_SPLINE_SURFACE_WITH_KNOTS")
        || i.has("B_SPLINE_SURFACE")
        || IMPLICIT_SURFACES.iter().any(|(n, _)| i.has(n))
}
