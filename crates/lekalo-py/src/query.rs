//! Geometric queries (`docs/theory/queries.md`): `CurveQuery` and `SurfaceQuery`, the library's
//! `QueryCurve` / `QuerySurface` prepared once from a curve or surface (Bezier pieces normalised
//! to the unit box, a tree of their boxes) and queried many times: length and its inverse,
//! closest points in batches, intersections, offsets, polylines and meshes, curvature,
//! bounding boxes. Batches take and return NumPy arrays; the GIL is released around every
//! computation.

use lekalo::query::{
    Contact, CurveIntersection, IntersectionBranch, PlaneIntersection, SurfaceIntersection,
    DEFAULT_LENGTH_RTOL,
};
use lekalo::{Points, QueryCurve, QuerySurface};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::out_shape;
use crate::convert::IntArg;
use crate::convert::{array, check_size, floats, points_into_array, uv_args, vec1, vec_array};
use crate::curves::{curve_of, PyBSplineCurve};
use crate::error::{bad, lib_err};
use crate::surfaces::surface_of;

/// `length_at` and `param_at` write their default `rtol` as `1e-13` in their text signatures.
const _RTOL_SPELLED: () = assert!(
    DEFAULT_LENGTH_RTOL == 1e-13,
    "update the text signatures of length_at and param_at"
);

/// Applies `f` to every number of the array-like `t` (any shape) and returns the results in an
/// array of `t`'s shape (a Python float for a scalar `t`).
fn map_params<F>(py: Python<'_>, t: &Bound<'_, PyAny>, what: &str, f: F) -> PyResult<Py<PyAny>>
where
    F: Fn(f64) -> lekalo::Result<f64> + Sync,
{
    let ta = floats(t, what)?;
    let ts = ta.data();
    let out: Vec<f64> = py
        .detach(|| ts.iter().map(|&x| f(x)).collect::<lekalo::Result<_>>())
        .map_err(lib_err)?;
    if ta.scalar {
        return Ok(out[0].into_pyobject(py)?.into_any().unbind());
    }
    Ok(array(py, out, ta.shape())?.unbind())
}

/// Query points `(n, dim)` (or one point `(dim,)`) as owned points and whether one was given.
fn query_points(
    obj: &Bound<'_, PyAny>,
    what: &'static str,
    dim: usize,
) -> PyResult<(Points, bool)> {
    let a = floats(obj, what)?;
    if a.shape().len() == 1 && a.shape()[0] == dim {
        return Ok((
            Points::from_flat(dim, a.data().to_vec()).map_err(lib_err)?,
            true,
        ));
    }
    if a.shape().len() != 2 {
        return Err(bad(format!(
            "{what}: expected points (n, {dim}) or one point ({dim},), got shape {:?}",
            a.shape()
        )));
    }
    Ok((a.points(what)?.to_owned(), false))
}

/// Three arrays.
type Arrays3<'py> = (Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>);

/// The result of `project` for `n` query points: the parameters (`width` numbers a point: 1
/// for a curve's `t`, 2 for a surface's `(u, v)`), the closest points (`dim` numbers a point)
/// and the distances, as arrays `(n,)` or `(n, width)`, `(n, dim)`, `(n,)`; for one query
/// point (`one`) without the `n` axis, a lone parameter or distance as a float.
fn projections(
    py: Python<'_>,
    (params, width): (Vec<f64>, usize),
    (closest, dim): (Vec<f64>, usize),
    distances: Vec<f64>,
    one: bool,
) -> PyResult<Arrays3<'_>> {
    let n = distances.len();
    let params = match (one, width) {
        (true, 1) => params[0].into_pyobject(py)?.into_any(),
        (true, _) | (false, 1) => vec_array(py, &params),
        (false, _) => array(py, params, &[n, width])?,
    };
    let closest = if one {
        vec_array(py, &closest)
    } else {
        array(py, closest, &[n, dim])?
    };
    let distances = if one {
        distances[0].into_pyobject(py)?.into_any()
    } else {
        vec_array(py, &distances)
    };
    Ok((params, closest, distances))
}

/// A point answer as a dict: `kind` (the library's word for the contact), the parameters, the
/// point, and `order` for a tangent contact or `gap` for a near miss.
fn point_dict<'py>(
    py: Python<'py>,
    contact: Contact,
    params: &[(&str, Bound<'py, PyAny>)],
    point: &[f64],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", contact.name())?;
    for (k, v) in params {
        d.set_item(*k, v)?;
    }
    d.set_item("point", vec_array(py, point))?;
    if let Some(order) = contact.order() {
        d.set_item("order", order)?;
    }
    if let Contact::NearMiss { gap } = contact {
        d.set_item("gap", gap)?;
    }
    Ok(d)
}

/// Curve–curve answers as dicts: points with `t_a`, `t_b`, overlaps with the intervals.
fn intersections<'py>(
    py: Python<'py>,
    found: Vec<CurveIntersection>,
) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for x in found {
        match x {
            CurveIntersection::Point {
                t_a,
                t_b,
                point,
                contact,
            } => {
                let params = [
                    ("t_a", t_a.into_pyobject(py)?.into_any()),
                    ("t_b", t_b.into_pyobject(py)?.into_any()),
                ];
                out.append(point_dict(py, contact, &params, &point)?)?;
            }
            CurveIntersection::Overlap { a, b } => {
                let d = PyDict::new(py);
                d.set_item("kind", Contact::Overlap.name())?;
                d.set_item("t_a", a)?;
                d.set_item("t_b", b)?;
                out.append(d)?;
            }
        }
    }
    Ok(out)
}

/// A curve prepared for geometric queries: `CurveQuery(curve)` for a `BezierCurve`,
/// `BSplineCurve` or `NurbsCurve` (`docs/theory/queries.md`).
///
/// >>> import numpy as np, lekalo
/// >>> q = lekalo.CurveQuery(lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], 2.0))
/// >>> bool(abs(q.length() - 4 * np.pi) < 1e-9)
/// True
/// >>> t, p, d = q.project([[3.0, 0.0], [0.0, -5.0]])
/// >>> np.round(d, 12).tolist()
/// [1.0, 3.0]
#[pyclass(module = "lekalo", name = "CurveQuery", frozen)]
pub(crate) struct PyCurveQuery {
    inner: QueryCurve,
}

#[pymethods]
impl PyCurveQuery {
    #[new]
    fn new(py: Python<'_>, curve: &Bound<'_, PyAny>) -> PyResult<Self> {
        let c = curve_of(curve, "curve")?;
        let inner = py.detach(|| c.to_query()).map_err(lib_err)?;
        Ok(Self { inner })
    }

    /// The parameter domain.
    #[getter]
    fn domain(&self) -> (f64, f64) {
        self.inner.domain()
    }

    /// The dimension of the points.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// The degree of the pieces.
    #[getter]
    fn degree(&self) -> usize {
        self.inner.degree()
    }

    /// The number of (rational) Bezier pieces.
    #[getter]
    fn piece_count(&self) -> usize {
        self.inner.piece_count()
    }

    /// The arc length of the whole curve, or between the parameters `a` and `b` (adaptive
    /// Gauss–Legendre to a relative tolerance of `1e-12`; `docs/theory/queries.md#arc-length`).
    #[pyo3(signature = (a = None, b = None))]
    fn length(&self, py: Python<'_>, a: Option<f64>, b: Option<f64>) -> PyResult<f64> {
        let (lo, hi) = self.inner.domain();
        let (a, b) = (a.unwrap_or(lo), b.unwrap_or(hi));
        py.detach(|| {
            if (a, b) == (lo, hi) {
                self.inner.length()
            } else {
                self.inner.length_between(a, b)
            }
        })
        .map_err(lib_err)
    }

    /// The length from the start of the domain to every parameter of `t` (any shape), with the
    /// length table built once to the relative tolerance `rtol`.
    // the text signature spells DEFAULT_LENGTH_RTOL for help(); _RTOL_SPELLED keeps them equal
    #[pyo3(signature = (t, rtol = DEFAULT_LENGTH_RTOL), text_signature = "($self, t, rtol=1e-13)")]
    fn length_at(&self, py: Python<'_>, t: &Bound<'_, PyAny>, rtol: f64) -> PyResult<Py<PyAny>> {
        let al = py.detach(|| self.inner.arc_length(rtol)).map_err(lib_err)?;
        map_params(py, t, "t", |x| al.length_at(x))
    }

    /// The inverse of `length_at`: the parameter where the length from the start reaches every
    /// number of `s` (any shape; `0 ≤ s ≤ length()`).
    #[pyo3(signature = (s, rtol = DEFAULT_LENGTH_RTOL), text_signature = "($self, s, rtol=1e-13)")]
    fn param_at(&self, py: Python<'_>, s: &Bound<'_, PyAny>, rtol: f64) -> PyResult<Py<PyAny>> {
        let sa = floats(s, "s")?;
        let ss = sa.data();
        let out = py
            .detach(|| {
                self.inner
                    .arc_length(rtol)
                    .and_then(|al| al.param_at_batch(ss))
            })
            .map_err(lib_err)?;
        if sa.scalar {
            return Ok(out[0].into_pyobject(py)?.into_any().unbind());
        }
        Ok(array(py, out, sa.shape())?.unbind())
    }

    /// Parameters of `n + 1` points at equal arc-length steps from start to end.
    fn equal_steps<'py>(&self, py: Python<'py>, n: IntArg) -> PyResult<Bound<'py, PyAny>> {
        let n = n.count("n")?;
        let t = py
            .detach(|| {
                self.inner
                    .arc_length(DEFAULT_LENGTH_RTOL)
                    .and_then(|al| al.equal_steps(n))
            })
            .map_err(lib_err)?;
        Ok(vec_array(py, &t))
    }

    /// The arc-length parametrised cubic `A(s) ≈ C(t(s))` on `[0, length]` within `tolerance`
    /// (absolute); returns `(BSplineCurve, largest checked deviation)`.
    fn arc_length_spline(&self, py: Python<'_>, tolerance: f64) -> PyResult<(PyBSplineCurve, f64)> {
        let (c, dev) = py
            .detach(|| {
                self.inner
                    .arc_length(DEFAULT_LENGTH_RTOL)
                    .and_then(|al| al.parametrized_spline(tolerance))
            })
            .map_err(lib_err)?;
        Ok((PyBSplineCurve::wrap(c), dev))
    }

    /// Closest points of the curve to `points` (`(n, dim)`, in parallel, or one point `(dim,)`):
    /// `(t, closest, distance)` with shapes `(n,)`, `(n, dim)`, `(n,)` (a float, `(dim,)`, a
    /// float for one point). The global minimum, by subdivision of the pieces and Newton's
    /// method (`docs/theory/queries.md#closest-points`).
    fn project<'py>(&self, py: Python<'py>, points: &Bound<'py, PyAny>) -> PyResult<Arrays3<'py>> {
        let dim = self.inner.dim();
        let (pts, one) = query_points(points, "points", dim)?;
        let r = py
            .detach(|| self.inner.project_batch(pts.as_view()))
            .map_err(lib_err)?;
        let t: Vec<f64> = r.iter().map(|p| p.t).collect();
        let d: Vec<f64> = r.iter().map(|p| p.distance).collect();
        let c: Vec<f64> = r.iter().flat_map(|p| p.point.iter().copied()).collect();
        projections(py, (t, 1), (c, dim), d, one)
    }

    /// Every local minimum of the distance to `point` within `tolerance` of the least, sorted
    /// by distance: a list of `(t, closest, distance)`.
    fn project_all<'py>(
        &self,
        py: Python<'py>,
        point: &Bound<'py, PyAny>,
        tolerance: f64,
    ) -> PyResult<Vec<(f64, Bound<'py, PyAny>, f64)>> {
        let p = vec1(point, "point")?;
        let r = py
            .detach(|| self.inner.project_all(&p, tolerance))
            .map_err(lib_err)?;
        Ok(r.into_iter()
            .map(|x| (x.t, vec_array(py, &x.point), x.distance))
            .collect())
    }

    /// Point inversion: the parameter of `point`, refused (`lekalo.Error`) when it is farther
    /// than `tolerance` from the curve.
    fn invert(&self, py: Python<'_>, point: &Bound<'_, PyAny>, tolerance: f64) -> PyResult<f64> {
        let p = vec1(point, "point")?;
        py.detach(|| self.inner.invert(&p, tolerance))
            .map_err(lib_err)
    }

    /// Intersections with another curve of the same dimension within `tolerance`: a list of
    /// dicts sorted along this curve, `{"kind", "t_a", "t_b", "point"}` with `kind` one of
    /// `"crossing"`, `"tangent"` (and `"order"`, the order of contact), `"end"` (at an end
    /// point of either curve) or `"near-miss"` (and `"gap"`), or `{"kind": "overlap", "t_a":
    /// (a0, a1), "t_b": (b0, b1)}` (`docs/theory/queries.md#kinds-of-contact`).
    #[pyo3(signature = (other, tolerance = 1e-9))]
    fn intersect<'py>(
        &self,
        py: Python<'py>,
        other: &Bound<'py, PyCurveQuery>,
        tolerance: f64,
    ) -> PyResult<Bound<'py, PyList>> {
        let o = &other.get().inner;
        let r = py
            .detach(|| self.inner.intersect(o, tolerance))
            .map_err(lib_err)?;
        intersections(py, r)
    }

    /// Self-intersections of a planar curve, as `intersect` (with `t_a < t_b`).
    #[pyo3(signature = (tolerance = 1e-9))]
    fn self_intersections<'py>(
        &self,
        py: Python<'py>,
        tolerance: f64,
    ) -> PyResult<Bound<'py, PyList>> {
        let r = py
            .detach(|| self.inner.self_intersections(tolerance))
            .map_err(lib_err)?;
        intersections(py, r)
    }

    /// Intersections with the plane (a line in 2-D) through `origin` with `normal`: a list of
    /// dicts sorted by `t`, `{"kind", "t", "point"}` (`kind` `"crossing"`, `"tangent"` with
    /// `"order"`, or `"end"`) or `{"kind": "overlap", "t": (t0, t1)}` where the curve lies in
    /// the plane.
    fn intersect_plane<'py>(
        &self,
        py: Python<'py>,
        origin: &Bound<'py, PyAny>,
        normal: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyList>> {
        let (o, n) = (vec1(origin, "origin")?, vec1(normal, "normal")?);
        let r = py
            .detach(|| self.inner.intersect_plane(&o, &n))
            .map_err(lib_err)?;
        let out = PyList::empty(py);
        for x in r {
            match x {
                PlaneIntersection::Point { t, point, contact } => {
                    let params = [("t", t.into_pyobject(py)?.into_any())];
                    out.append(point_dict(py, contact, &params, &point)?)?;
                }
                PlaneIntersection::Overlap { t } => {
                    let d = PyDict::new(py);
                    d.set_item("kind", Contact::Overlap.name())?;
                    d.set_item("t", t)?;
                    out.append(d)?;
                }
            }
        }
        Ok(out)
    }

    /// Intersections with a surface within `tolerance`: a list of dicts sorted by `t`,
    /// `{"kind", "t", "uv", "point"}` (`kind` as for `intersect`) or `{"kind": "overlap",
    /// "t": (t0, t1), "uv": ((u0, v0), (u1, v1))}` where the curve lies on the surface.
    #[pyo3(signature = (surface, tolerance = 1e-9))]
    fn intersect_surface<'py>(
        &self,
        py: Python<'py>,
        surface: &Bound<'py, PySurfaceQuery>,
        tolerance: f64,
    ) -> PyResult<Bound<'py, PyList>> {
        let s = &surface.get().inner;
        let r = py
            .detach(|| self.inner.intersect_surface(s, tolerance))
            .map_err(lib_err)?;
        let out = PyList::empty(py);
        for x in r {
            match x {
                SurfaceIntersection::Point {
                    t,
                    uv,
                    point,
                    contact,
                } => {
                    let params = [
                        ("t", t.into_pyobject(py)?.into_any()),
                        ("uv", uv.into_pyobject(py)?.into_any()),
                    ];
                    out.append(point_dict(py, contact, &params, &point)?)?;
                }
                SurfaceIntersection::Overlap { t, uv } => {
                    let d = PyDict::new(py);
                    d.set_item("kind", Contact::Overlap.name())?;
                    d.set_item("t", t)?;
                    d.set_item("uv", uv)?;
                    out.append(d)?;
                }
            }
        }
        Ok(out)
    }

    /// The offset of a planar curve at signed distance `d` (to the left of the direction of
    /// travel), approximated within `tolerance`: a dict with `curve` (the untrimmed offset),
    /// `trimmed` (the pieces left after removing loops), `cusps`, `loops` (parameter pairs) and
    /// `deviation` (`docs/theory/queries.md#offsets`).
    fn offset<'py>(&self, py: Python<'py>, d: f64, tolerance: f64) -> PyResult<Bound<'py, PyDict>> {
        let o = py
            .detach(|| self.inner.offset(d, tolerance))
            .map_err(lib_err)?;
        let out = PyDict::new(py);
        out.set_item("curve", PyBSplineCurve::wrap(o.curve))?;
        let trimmed: Vec<PyBSplineCurve> =
            o.trimmed.into_iter().map(PyBSplineCurve::wrap).collect();
        out.set_item("trimmed", trimmed)?;
        out.set_item("cusps", vec_array(py, &o.cusps))?;
        out.set_item("loops", o.loops)?;
        out.set_item("deviation", o.deviation)?;
        Ok(out)
    }

    /// A polyline within `tolerance` (absolute) of the curve: `(params, points, deviation)`
    /// with a proved bound on the deviation (`docs/theory/queries.md#tessellation`).
    fn polyline<'py>(
        &self,
        py: Python<'py>,
        tolerance: f64,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, f64)> {
        let p = py
            .detach(|| self.inner.polyline(tolerance))
            .map_err(lib_err)?;
        Ok((
            vec_array(py, &p.params),
            points_into_array(py, p.points)?,
            p.deviation,
        ))
    }

    /// Curvature `|C' × C''| / |C'|³` at every parameter of `t` (any shape; NaN where
    /// `C' = 0`).
    fn curvature(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        map_params(py, t, "t", |x| {
            Ok(self.inner.curvature_at(x)?.unwrap_or(f64::NAN))
        })
    }

    /// Torsion of a 3-D curve at every parameter of `t` (NaN where the curvature is zero).
    fn torsion(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        map_params(py, t, "t", |x| {
            Ok(self.inner.torsion_at(x)?.unwrap_or(f64::NAN))
        })
    }

    /// Parameters of the inflections of a planar curve (sign changes of `C' × C''`).
    fn inflections<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let t = py.detach(|| self.inner.inflections()).map_err(lib_err)?;
        Ok(vec_array(py, &t))
    }

    /// Local extrema of the curvature: `(t, curvature, is_maximum)` arrays.
    fn curvature_extrema<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let e = py
            .detach(|| self.inner.curvature_extrema())
            .map_err(lib_err)?;
        let t: Vec<f64> = e.iter().map(|x| x.t).collect();
        let k: Vec<f64> = e.iter().map(|x| x.curvature).collect();
        let m: Vec<bool> = e.iter().map(|x| x.maximum).collect();
        Ok((
            vec_array(py, &t),
            vec_array(py, &k),
            PyArray1::from_vec(py, m).into_any(),
        ))
    }

    /// The exact axis-aligned bounding box of the curve (not of its control net): `(lo, hi)`.
    fn bounding_box<'py>(&self, py: Python<'py>) -> (Bound<'py, PyAny>, Bound<'py, PyAny>) {
        let (lo, hi) = py.detach(|| self.inner.bounding_box());
        (vec_array(py, &lo), vec_array(py, &hi))
    }

    fn __repr__(&self) -> String {
        let (a, b) = self.inner.domain();
        format!(
            "CurveQuery(degree={}, pieces={}, dim={}, domain=({a}, {b}))",
            self.inner.degree(),
            self.inner.piece_count(),
            self.inner.dim()
        )
    }
}

/// A surface prepared for geometric queries: `SurfaceQuery(surface)` for a `BezierSurface`,
/// `BSplineSurface` or `NurbsSurface` (`docs/theory/queries.md`).
#[pyclass(module = "lekalo", name = "SurfaceQuery", frozen)]
pub(crate) struct PySurfaceQuery {
    inner: QuerySurface,
}

#[pymethods]
impl PySurfaceQuery {
    #[new]
    fn new(py: Python<'_>, surface: &Bound<'_, PyAny>) -> PyResult<Self> {
        let s = surface_of(surface, "surface")?;
        let inner = py.detach(|| s.to_query()).map_err(lib_err)?;
        Ok(Self { inner })
    }

    /// The dimension of the points.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// The number of (rational) Bezier patches.
    #[getter]
    fn patch_count(&self) -> usize {
        self.inner.patch_count()
    }

    /// Closest points of the surface to `points` (`(n, dim)` or one point `(dim,)`):
    /// `(uv, closest, distance)` with shapes `(n, 2)`, `(n, dim)`, `(n,)`.
    fn project<'py>(&self, py: Python<'py>, points: &Bound<'py, PyAny>) -> PyResult<Arrays3<'py>> {
        let dim = self.inner.dim();
        let (pts, one) = query_points(points, "points", dim)?;
        let r = py
            .detach(|| {
                pts.iter()
                    .map(|p| self.inner.project(p))
                    .collect::<lekalo::Result<Vec<_>>>()
            })
            .map_err(lib_err)?;
        let uv: Vec<f64> = r.iter().flat_map(|p| [p.uv.0, p.uv.1]).collect();
        let d: Vec<f64> = r.iter().map(|p| p.distance).collect();
        let c: Vec<f64> = r.iter().flat_map(|p| p.point.iter().copied()).collect();
        projections(py, (uv, 2), (c, dim), d, one)
    }

    /// A triangle mesh within `tolerance` (absolute) of the surface: `(vertices (m, dim),
    /// uv (m, 2), triangles (k, 3) uint32, deviation)` (`docs/theory/queries.md#tessellation`).
    #[allow(clippy::type_complexity)]
    fn mesh<'py>(
        &self,
        py: Python<'py>,
        tolerance: f64,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>, f64)> {
        let m = py.detach(|| self.inner.mesh(tolerance)).map_err(lib_err)?;
        let nv = m.uv.len();
        let uv: Vec<f64> = m.uv.iter().flatten().copied().collect();
        let nt = m.triangles.len();
        let tri: Vec<u32> = m.triangles.iter().flatten().copied().collect();
        let tri = PyArray1::from_vec(py, tri).reshape([nt, 3])?.into_any();
        Ok((
            points_into_array(py, m.vertices)?,
            array(py, uv, &[nv, 2])?,
            tri,
            m.deviation,
        ))
    }

    /// Curvatures at `(u, v)` (arrays of one shape): `(gaussian, mean, k1, k2)`, each of that
    /// shape (`docs/theory/queries.md#curvature`).
    #[allow(clippy::type_complexity)]
    fn curvature<'py>(
        &self,
        py: Python<'py>,
        u: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
    )> {
        let (ua, uv) = uv_args(u, v)?;
        let n = check_size("u", &[uv.len(), 4])?;
        let mut out = vec![0.0; n];
        py.detach(|| {
            uv.iter()
                .zip(out.chunks_exact_mut(4))
                .try_for_each(|(&[u, v], o)| {
                    let c = self.inner.curvature(u, v)?;
                    o.copy_from_slice(&[c.gaussian, c.mean, c.principal.0, c.principal.1]);
                    Ok(())
                })
        })
        .map_err(lib_err)?;
        let shape = out_shape(&ua, &[]);
        let col = |k: usize| -> PyResult<Bound<'py, PyAny>> {
            let v: Vec<f64> = out.iter().skip(k).step_by(4).copied().collect();
            array(py, v, &shape)
        };
        Ok((col(0)?, col(1)?, col(2)?, col(3)?))
    }

    /// The intersection with another 3-D surface within `tolerance` (an absolute distance):
    /// a list of dicts, one a branch (`docs/theory/queries.md#surface-surface-intersection`):
    /// `kind` (`"crossing"`, `"tangent"` with `"order"`, or `"overlap"`), `closed`, `points`
    /// `(n, 3)`, `uv_a` and `uv_b` `(n, 2)` (the parameters on each surface at every point),
    /// `curve`, `curve_uv_a`, `curve_uv_b` (the branch fitted as a `BSplineCurve` in space and in
    /// each parameter plane, sharing knots; `None` for a contact or an overlap), `length` and
    /// `tolerance`. Every point is within `tolerance` of both surfaces.
    #[pyo3(signature = (other, tolerance = 1e-6))]
    fn intersect<'py>(
        &self,
        py: Python<'py>,
        other: &Bound<'py, PySurfaceQuery>,
        tolerance: f64,
    ) -> PyResult<Bound<'py, PyList>> {
        let o = &other.get().inner;
        let r = py
            .detach(|| self.inner.intersect_surface(o, tolerance))
            .map_err(lib_err)?;
        branches(py, r)
    }

    /// The section by the plane through `origin` with `normal` within `tolerance`: branches as
    /// for `intersect`, with `uv_b` empty and `curve_uv_b` `None`.
    #[pyo3(signature = (origin, normal, tolerance = 1e-6))]
    fn intersect_plane<'py>(
        &self,
        py: Python<'py>,
        origin: &Bound<'py, PyAny>,
        normal: &Bound<'py, PyAny>,
        tolerance: f64,
    ) -> PyResult<Bound<'py, PyList>> {
        let (o, n) = (vec1(origin, "origin")?, vec1(normal, "normal")?);
        let r = py
            .detach(|| self.inner.intersect_plane(&o, &n, tolerance))
            .map_err(lib_err)?;
        branches(py, r)
    }

    fn __repr__(&self) -> String {
        format!(
            "SurfaceQuery(patches={}, dim={})",
            self.inner.patch_count(),
            self.inner.dim()
        )
    }
}

/// Surface–surface branches as dicts (see `SurfaceQuery.intersect`).
fn branches<'py>(py: Python<'py>, found: Vec<IntersectionBranch>) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for b in found {
        let d = PyDict::new(py);
        d.set_item("kind", b.kind.name())?;
        if let Some(order) = b.kind.order() {
            d.set_item("order", order)?;
        }
        d.set_item("closed", b.closed)?;
        d.set_item("length", b.length())?;
        d.set_item("tolerance", b.tolerance)?;
        let n = b.points.len();
        let flat = |v: &[[f64; 2]]| v.iter().flatten().copied().collect::<Vec<f64>>();
        d.set_item(
            "points",
            array(py, b.points.iter().flatten().copied().collect(), &[n, 3])?,
        )?;
        d.set_item("uv_a", array(py, flat(&b.uv_a), &[b.uv_a.len(), 2])?)?;
        d.set_item("uv_b", array(py, flat(&b.uv_b), &[b.uv_b.len(), 2])?)?;
        for (key, c) in [
            ("curve", b.curve),
            ("curve_uv_a", b.curve_uv_a),
            ("curve_uv_b", b.curve_uv_b),
        ] {
            d.set_item(key, c.map(PyBSplineCurve::wrap))?;
        }
        out.append(d)?;
    }
    Ok(out)
}

/// Registers the query classes.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyCurveQuery>()?;
    m.add_class::<PySurfaceQuery>()?;
    Ok(())
}
