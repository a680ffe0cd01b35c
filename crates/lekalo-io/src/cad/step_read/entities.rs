//! Decoding of the entities read: B-spline curves and surfaces (plain or complex instances,
//! rational or not), their points and knots, and trimmed curves split at their parameters; the
//! other geometry, which is listed as skipped.

use lekalo::{BSplineCurve, BSplineSurface, NurbsCurve, NurbsSurface, Points};

use super::parse::Parsed;
use super::{int, list, num, numbers, Instance, Why, P};
use crate::error::Location;
use crate::object::Object;
use crate::shape::Surface;

/// Curve and surface entities that are geometry but not read, reported as skipped.
pub(super) const OTHER_GEOMETRY: &[&str] = &[
    "LINE",
    "CIRCLE",
    "ELLIPSE",
    "PARABOLA",
    "HYPERBOLA",
    "POLYLINE",
    "OFFSET_CURVE_2D",
    "OFFSET_CURVE_3D",
    "PLANE",
    "CYLINDRICAL_SURFACE",
    "CONICAL_SURFACE",
    "SPHERICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "SURFACE_OF_REVOLUTION",
    "SURFACE_OF_LINEAR_EXTRUSION",
    "OFFSET_SURFACE",
    "RECTANGULAR_TRIMMED_SURFACE",
    "BEZIER_CURVE",
    "UNIFORM_CURVE",
    "QUASI_UNIFORM_CURVE",
    "BEZIER_SURFACE",
    "UNIFORM_SURFACE",
    "QUASI_UNIFORM_SURFACE",
];

pub(super) struct Reader<'a> {
    pub(super) p: &'a Parsed,
    pub(super) source: &'a str,
    pub(super) scale: f64,
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

impl Reader<'_> {
    pub(super) fn at(&self, id: u64) -> Location {
        let mut loc = Location::new(self.source);
        if let Some(i) = self.p.instances.get(&id) {
            loc = loc.at_line(i.line);
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
        let c = inst.get("CARTESIAN_POINT").ok_or_else(|| {
            format!(
                "control point #{id} is a {}, not a CARTESIAN_POINT",
                inst.type_name()
            )
        })?;
        let coords = c
            .get(1)
            .ok_or_else(|| format!("CARTESIAN_POINT #{id} has no coordinates"))
            .and_then(|c| numbers(c, &format!("the coordinates of #{id}")))?;
        Ok(coords)
    }

    fn points(&self, p: &P) -> Result<Points, Why> {
        let rows = list(p)
            .ok_or("control_points_list is not a list")?
            .iter()
            .map(|q| self.point(q))
            .collect::<Result<Vec<_>, _>>()?;
        let mut pts = Points::from_rows(&rows).map_err(|e| e.to_string())?;
        if pts.dim() == 3 && self.scale != 1.0 {
            let s = self.scale;
            pts = Points::from_flat(3, pts.as_slice().iter().map(|x| x * s).collect())
                .map_err(|e| e.to_string())?;
        }
        Ok(pts)
    }

    /// A B-spline curve instance (simple or complex, rational or not).
    pub(super) fn curve(&self, inst: &Instance) -> Result<Object, Why> {
        let (degree, ctrl, mults, knots, weights) = if let Some(r) = inst
            .get("B_SPLINE_CURVE_WITH_KNOTS")
            .filter(|r| r.len() >= 9)
        {
            (&r[1], &r[2], &r[6], &r[7], None)
        } else {
            let b = inst
                .get("B_SPLINE_CURVE")
                .filter(|r| r.len() >= 2)
                .ok_or("no B_SPLINE_CURVE record with degree and control points")?;
            let k = inst
                .get("B_SPLINE_CURVE_WITH_KNOTS")
                .filter(|r| r.len() >= 2)
                .ok_or("implicit knots (only B_SPLINE_CURVE_WITH_KNOTS is read)")?;
            let w = inst.get("RATIONAL_B_SPLINE_CURVE").and_then(|r| r.first());
            (&b[0], &b[1], &k[0], &k[1], w)
        };
        let degree = int(degree).ok_or("degree is not a non-negative integer")?;
        let ctrl = self.points(ctrl)?;
        let knots = expand_knots(mults, knots, ctrl.len(), degree, "")?;
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

    /// A B-spline surface instance (simple or complex, rational or not).
    pub(super) fn surface(&self, inst: &Instance) -> Result<Surface, Why> {
        let simple = inst
            .get("B_SPLINE_SURFACE_WITH_KNOTS")
            .filter(|r| r.len() >= 13);
        let (du, dv, net, um, vm, uk, vk, weights) = if let Some(r) = simple {
            (&r[1], &r[2], &r[3], &r[8], &r[9], &r[10], &r[11], None)
        } else {
            let b = inst
                .get("B_SPLINE_SURFACE")
                .filter(|r| r.len() >= 3)
                .ok_or("no B_SPLINE_SURFACE record with degrees and control points")?;
            let k = inst
                .get("B_SPLINE_SURFACE_WITH_KNOTS")
                .filter(|r| r.len() >= 4)
                .ok_or("implicit knots (only B_SPLINE_SURFACE_WITH_KNOTS is read)")?;
            let w = inst
                .get("RATIONAL_B_SPLINE_SURFACE")
                .and_then(|r| r.first());
            (&b[0], &b[1], &b[2], &k[0], &k[1], &k[2], &k[3], w)
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
        let ku = expand_knots(um, uk, nu, du, "u ")?;
        let kv = expand_knots(vm, vk, nv, dv, "v ")?;
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

    /// A `TRIMMED_CURVE` over a B-spline curve, trimmed by parameter values. `budget` is the
    /// number of basis control points trims may still read: a basis is read once per trim, so
    /// without it a file of many short trims of one long curve would be read in quadratic time.
    pub(super) fn trimmed(&self, r: &[P], budget: &mut usize) -> Result<(u64, Object), Why> {
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
        if !is_bspline_curve(inst) {
            return Err(format!(
                "the basis curve #{basis} is a {} (only B-spline bases are read)",
                inst.type_name()
            ));
        }
        let size = ["B_SPLINE_CURVE_WITH_KNOTS", "B_SPLINE_CURVE"]
            .iter()
            .find_map(|name| {
                let r = inst.get(name)?;
                let at = usize::from(*name == "B_SPLINE_CURVE_WITH_KNOTS") + 1;
                r.get(at).and_then(list).map(<[P]>::len)
            })
            .unwrap_or(0);
        *budget = budget.checked_sub(size).ok_or_else(|| {
            format!(
                "the basis curve #{basis} ({size} control points) is one of bases trimmed more often than the file's size allows to read"
            )
        })?;
        let curve = self.curve(inst)?;
        let trim = |p: &P| -> Option<f64> {
            list(p)?.iter().find_map(|x| match x {
                P::Typed(k, v) if k == "PARAMETER_VALUE" => v.first().and_then(num),
                _ => None,
            })
        };
        let (Some(t1), Some(t2)) = (trim(&r[2]), trim(&r[3])) else {
            return Err("trimmed by points, not by PARAMETER_VALUE".into());
        };
        let sense = match &r[4] {
            P::Enum(e) => e == "T",
            _ => return Err("sense_agreement is not .T. or .F.".into()),
        };
        if sense != (t1 <= t2) {
            return Err(format!(
                "trims {t1} → {t2} with sense_agreement {} wrap around a closed curve",
                if sense { ".T." } else { ".F." }
            ));
        }
        let (a, b) = (t1.min(t2), t1.max(t2));
        let piece = restrict(&curve, a, b).map_err(|e| e.to_string())?;
        let piece = if sense {
            piece
        } else {
            reverse(&piece).map_err(|e| e.to_string())?
        };
        Ok((*basis, piece))
    }
}

fn split(o: &Object, t: f64) -> lekalo::Result<(Object, Object)> {
    Ok(match o {
        Object::Nurbs(c) => {
            let (a, b) = c.split_at(t)?;
            (Object::Nurbs(a), Object::Nurbs(b))
        }
        Object::BSpline(c) => {
            let (a, b) = c.split_at(t)?;
            (Object::BSpline(a), Object::BSpline(b))
        }
        Object::Bezier(c) => {
            let (a, b) = c.to_bspline().split_at(t)?;
            (Object::BSpline(a), Object::BSpline(b))
        }
    })
}

/// The piece of `o` over `[a, b]` (the curve itself where a trim is at its end).
fn restrict(o: &Object, a: f64, b: f64) -> lekalo::Result<Object> {
    let (lo, hi) = o.domain();
    let mut c = o.clone();
    if a > lo {
        c = split(&c, a)?.1;
    }
    if b < hi {
        c = split(&c, b)?.0;
    }
    Ok(c)
}

fn reverse(o: &Object) -> lekalo::Result<Object> {
    Ok(match o {
        Object::Nurbs(c) => Object::Nurbs(c.reverse()?),
        Object::BSpline(c) => Object::BSpline(c.reverse()?),
        Object::Bezier(c) => Object::BSpline(c.to_bspline().reverse()?),
    })
}

pub(super) fn is_bspline_curve(i: &Instance) -> bool {
    i.has("B_SPLINE_CURVE_WITH_KNOTS") || i.has("B_SPLINE_CURVE")
}

pub(super) fn is_bspline_surface(i: &Instance) -> bool {
    i.has("B_SPLINE_SURFACE_WITH_KNOTS") || i.has("B_SPLINE_SURFACE")
}
