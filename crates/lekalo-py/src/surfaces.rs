//! `BezierSurface`, `BSplineSurface`, `NurbsSurface`: control nets are `(nu, nv, dim)` arrays;
//! evaluation at `(u, v)` arrays of one shape gives `shape + (dim,)`, on a grid
//! `(len(us), len(vs), dim)`.

use lekalo::{BSplineSurface, BezierSurface, NurbsSurface, Points};
use lekalo_io::{Shape, Surface};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::IntArg;
use crate::convert::{array, check_size, filled, floats, grid_points, uv_args, vec1, vec_array};
use crate::convert::{out_shape, reduce};
use crate::curves::{curve_of, PyBSplineCurve, PyBezierCurve, PyNurbsCurve};
use crate::error::{bad, io_err, lib_err};

/// Two knot vectors, a control net and its size `(nu, nv)`.
type KnotsAndNet = (Vec<f64>, Vec<f64>, Points, (usize, usize));

/// The knot vectors `knots_u`, `knots_v` and the control net `control` of a B-spline or NURBS
/// surface, with the net's size.
fn knots_and_net(
    knots_u: &Bound<'_, PyAny>,
    knots_v: &Bound<'_, PyAny>,
    control: &Bound<'_, PyAny>,
) -> PyResult<KnotsAndNet> {
    let (ku, kv) = (vec1(knots_u, "knots_u")?, vec1(knots_v, "knots_v")?);
    let (p, size) = net_arg(control, "control")?;
    Ok((ku, kv, p, size))
}

/// The B-spline surface `BSplineSurface(degree_u, degree_v, knots_u, knots_v, control)`.
pub(crate) fn bspline_surface_arg(
    (degree_u, degree_v): (usize, usize),
    knots_u: &Bound<'_, PyAny>,
    knots_v: &Bound<'_, PyAny>,
    control: &Bound<'_, PyAny>,
) -> PyResult<BSplineSurface> {
    let (ku, kv, p, size) = knots_and_net(knots_u, knots_v, control)?;
    BSplineSurface::new(degree_u, degree_v, ku, kv, p, size).map_err(lib_err)
}

/// A NURBS surface from its degrees, knots, net `(nu, nv, dim)` and weights `(nu, nv)`.
pub(crate) fn nurbs_surface_arg(
    (degree_u, degree_v): (usize, usize),
    knots_u: &Bound<'_, PyAny>,
    knots_v: &Bound<'_, PyAny>,
    control: &Bound<'_, PyAny>,
    weights: &Bound<'_, PyAny>,
) -> PyResult<NurbsSurface> {
    let (ku, kv, p, size) = knots_and_net(knots_u, knots_v, control)?;
    let w = floats(weights, "weights")?;
    if w.shape() != [size.0, size.1] {
        return Err(bad(format!(
            "weights: expected shape ({}, {}), got {:?}",
            size.0,
            size.1,
            w.shape()
        )));
    }
    NurbsSurface::new(degree_u, degree_v, ku, kv, p, w.data().to_vec(), size).map_err(lib_err)
}

/// A control net `(nu, nv, dim)` as points and its size.
pub(crate) fn net_arg(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Points, (usize, usize))> {
    let a = floats(obj, what)?;
    let (p, size) = grid_points(&a, what)?;
    Ok((p.to_owned(), size))
}

fn net_array<'py>(
    py: Python<'py>,
    p: &Points,
    (nu, nv): (usize, usize),
) -> PyResult<Bound<'py, PyAny>> {
    array(py, p.as_slice().to_vec(), &[nu, nv, p.dim()])
}

fn shape_of(text: &str) -> PyResult<Shape> {
    Shape::from_json_str(text, "json").map_err(io_err)
}

/// The methods every surface class shares, written once: evaluation, derivatives, normals, JSON,
/// pickling and equality; the `knots` form adds the knot vectors, tensor-grid evaluation, knot
/// insertion and splitting of the B-spline and NURBS surfaces.
macro_rules! surface_common {
    ($ty:ident, $variant:ident, $name:literal, knots $curve:ident, { $($extra:tt)* }) => {
        surface_common!($ty, $variant, $name, {
            $($extra)*

            /// The iso-curve `S(·, v)`.
            fn iso_curve_u(&self, v: f64) -> PyResult<$curve> {
                Ok($curve::wrap(self.inner.iso_curve_u(v).map_err(lib_err)?))
            }

            /// The iso-curve `S(u, ·)`.
            fn iso_curve_v(&self, u: f64) -> PyResult<$curve> {
                Ok($curve::wrap(self.inner.iso_curve_v(u).map_err(lib_err)?))
            }

            /// The degrees `(p, q)`.
            #[getter]
            fn degrees(&self) -> (usize, usize) {
                (self.inner.degree_u(), self.inner.degree_v())
            }

            /// The knot vector in `u`.
            #[getter]
            fn knots_u<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
                vec_array(py, self.inner.knots_u().as_slice())
            }

            /// The knot vector in `v`.
            #[getter]
            fn knots_v<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
                vec_array(py, self.inner.knots_v().as_slice())
            }

            /// Points on the tensor grid `us × vs`: `(len(us), len(vs), dim)`.
            fn grid(
                &self,
                py: Python<'_>,
                us: &Bound<'_, PyAny>,
                vs: &Bound<'_, PyAny>,
            ) -> PyResult<Py<PyAny>> {
                let (ua, va) = (floats(us, "us")?, floats(vs, "vs")?);
                let (u, v) = (ua.vector("us")?, va.vector("vs")?);
                let dim = self.inner.dim();
                check_size("us, vs", &[u.len(), v.len(), dim])?;
                let out = filled(py, &[u.len(), v.len(), dim], |out| {
                    self.inner.eval_grid(u, v, out)
                })?;
                Ok(out.unbind())
            }

            /// Inserts `u` into the `u` knots `times` times (P&T A5.3).
            #[pyo3(signature = (u, times = IntArg::of(1)), text_signature = "($self, u, times=1)")]
            fn insert_knot_u(&self, py: Python<'_>, u: f64, times: IntArg) -> PyResult<Self> {
                let times = times.count("times")?;
                let inner = py
                    .detach(|| self.inner.insert_knot_u(u, times))
                    .map_err(lib_err)?;
                Ok(Self { inner })
            }

            /// Inserts `v` into the `v` knots `times` times (P&T A5.3).
            #[pyo3(signature = (v, times = IntArg::of(1)), text_signature = "($self, v, times=1)")]
            fn insert_knot_v(&self, py: Python<'_>, v: f64, times: IntArg) -> PyResult<Self> {
                let times = times.count("times")?;
                let inner = py
                    .detach(|| self.inner.insert_knot_v(v, times))
                    .map_err(lib_err)?;
                Ok(Self { inner })
            }

            /// Splits at `u` into two surfaces (parameters kept).
            fn split_u(&self, py: Python<'_>, u: f64) -> PyResult<(Self, Self)> {
                let (a, b) = py.detach(|| self.inner.split_at_u(u)).map_err(lib_err)?;
                Ok((Self { inner: a }, Self { inner: b }))
            }

            /// Splits at `v` into two surfaces (parameters kept).
            fn split_v(&self, py: Python<'_>, v: f64) -> PyResult<(Self, Self)> {
                let (a, b) = py.detach(|| self.inner.split_at_v(v)).map_err(lib_err)?;
                Ok((Self { inner: a }, Self { inner: b }))
            }

            fn __repr__(&self) -> String {
                let (nu, nv) = self.inner.net_size();
                format!(
                    concat!(stringify!($variant), "Surface(degrees=({}, {}), net=({}, {}), dim={})"),
                    self.inner.degree_u(),
                    self.inner.degree_v(),
                    nu,
                    nv,
                    self.inner.dim()
                )
            }
        });
    };
    ($ty:ident, $variant:ident, $name:literal, { $($extra:tt)* }) => {
        #[pymethods]
        impl $ty {
            $($extra)*

            /// The dimension of the points.
            #[getter]
            fn dim(&self) -> usize {
                self.inner.dim()
            }

            /// The parameter domain `((u0, u1), (v0, v1))`.
            #[getter]
            fn domain(&self) -> ((f64, f64), (f64, f64)) {
                self.inner.domain()
            }

            /// The net size `(nu, nv)`.
            #[getter]
            fn net_size(&self) -> (usize, usize) {
                self.inner.net_size()
            }

            /// Points at `(u, v)` (arrays of one shape, or numbers): `shape + (dim,)`.
            fn __call__(
                &self,
                py: Python<'_>,
                u: &Bound<'_, PyAny>,
                v: &Bound<'_, PyAny>,
            ) -> PyResult<Py<PyAny>> {
                let (ua, uv) = uv_args(u, v)?;
                let dim = self.inner.dim();
                check_size("u, v", &[uv.len(), dim])?;
                let out = filled(py, &out_shape(&ua, &[dim]), |out| {
                    uv.iter()
                        .zip(out.chunks_exact_mut(dim))
                        .try_for_each(|(&[u, v], o)| self.inner.eval_into(u, v, o))
                })?;
                Ok(out.unbind())
            }

            /// Partial derivatives `∂^{a+b} S / ∂u^a ∂v^b` for `a, b ≤ order` at `(u, v)`:
            /// `shape + (order + 1, order + 1, dim)` indexed `[..., a, b, :]`.
            fn derivatives(
                &self,
                py: Python<'_>,
                u: &Bound<'_, PyAny>,
                v: &Bound<'_, PyAny>,
                order: IntArg,
            ) -> PyResult<Py<PyAny>> {
                let order = order.count("order")?;
                let (ua, uv) = uv_args(u, v)?;
                let dim = self.inner.dim();
                let k = order.saturating_add(1);
                let row = check_size("order", &[k, k, dim])?;
                check_size("u, v", &[uv.len(), row])?;
                let out = filled(py, &out_shape(&ua, &[k, k, dim]), |out| {
                    uv.iter()
                        .zip(out.chunks_exact_mut(row))
                        .try_for_each(|(&[u, v], o)| {
                            let d = self.inner.eval_derivatives(u, v, order)?;
                            o.copy_from_slice(d.as_slice());
                            Ok(())
                        })
                })?;
                Ok(out.unbind())
            }

            /// Unit normals at `(u, v)` (3-D surfaces): `shape + (3,)`.
            fn normal(
                &self,
                py: Python<'_>,
                u: &Bound<'_, PyAny>,
                v: &Bound<'_, PyAny>,
            ) -> PyResult<Py<PyAny>> {
                let (ua, uv) = uv_args(u, v)?;
                check_size("u, v", &[uv.len(), 3])?;
                let out = filled(py, &out_shape(&ua, &[3]), |out| {
                    uv.iter()
                        .zip(out.chunks_exact_mut(3))
                        .try_for_each(|(&[u, v], o)| {
                            o.copy_from_slice(&self.inner.normal(u, v)?);
                            Ok(())
                        })
                })?;
                Ok(out.unbind())
            }

            /// JSON text in the command-line tool's format.
            fn to_json(&self) -> String {
                Shape::Surface(Surface::$variant(self.inner.clone())).to_json_pretty()
            }

            /// Reads the surface from JSON text.
            #[staticmethod]
            fn from_json(text: &str) -> PyResult<Self> {
                match shape_of(text)? {
                    Shape::Surface(Surface::$variant(s)) => Ok(Self { inner: s }),
                    other => Err(bad(format!(
                        concat!("expected a ", $name, ", got {}"),
                        other.type_name()
                    ))),
                }
            }

            fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
                reduce(py, self.to_json())
            }

            fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
                other
                    .cast::<Self>()
                    .is_ok_and(|o| o.get().inner == self.inner)
            }
        }
    };
}

/// A tensor-product Bezier surface on `[0, 1]²` (docs/theory/surfaces.md).
///
/// Call: `s(u, v)`: the points at `(u, v)` (arrays of one shape, or numbers), `shape + (dim,)`.
///
/// >>> import numpy as np, lekalo
/// >>> net = np.array([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]], dtype=float)
/// >>> lekalo.BezierSurface(net)(0.5, 0.25)
/// array([0.5  , 0.25 , 0.125])
#[pyclass(module = "lekalo", name = "BezierSurface", frozen)]
pub(crate) struct PyBezierSurface {
    pub(crate) inner: BezierSurface,
}

surface_common!(PyBezierSurface, Bezier, "bezier_surface", {
    #[new]
    fn new(control: &Bound<'_, PyAny>) -> PyResult<Self> {
        let (p, size) = net_arg(control, "control")?;
        Ok(Self {
            inner: BezierSurface::new(p, size).map_err(lib_err)?,
        })
    }

    /// The degrees `(nu − 1, nv − 1)`.
    #[getter]
    fn degrees(&self) -> (usize, usize) {
        (self.inner.degree_u(), self.inner.degree_v())
    }

    /// The control net `(nu, nv, dim)`.
    #[getter]
    fn control<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        net_array(py, self.inner.control_points(), self.inner.net_size())
    }

    /// The iso-curve `S(·, v)` as a Bezier curve in `u`.
    fn iso_curve_u(&self, v: f64) -> PyResult<PyBezierCurve> {
        Ok(PyBezierCurve::wrap(
            self.inner.iso_curve_u(v).map_err(lib_err)?,
        ))
    }

    /// The iso-curve `S(u, ·)` as a Bezier curve in `v`.
    fn iso_curve_v(&self, u: f64) -> PyResult<PyBezierCurve> {
        Ok(PyBezierCurve::wrap(
            self.inner.iso_curve_v(u).map_err(lib_err)?,
        ))
    }

    /// Degree elevation by `(by_u, by_v)` (document 004).
    fn elevate_degree(&self, py: Python<'_>, by_u: IntArg, by_v: IntArg) -> PyResult<Self> {
        let by_u = by_u.count("by_u")?;
        let by_v = by_v.count("by_v")?;
        Ok(Self {
            inner: py
                .detach(|| self.inner.elevate_degree(by_u, by_v))
                .map_err(lib_err)?,
        })
    }

    /// Exact degree change to `(new_u, new_v)`, refused below the real degrees.
    fn change_degree(&self, py: Python<'_>, new_u: IntArg, new_v: IntArg) -> PyResult<Self> {
        let new_u = new_u.count("new_u")?;
        let new_v = new_v.count("new_v")?;
        Ok(Self {
            inner: py
                .detach(|| self.inner.change_degree(new_u, new_v))
                .map_err(lib_err)?,
        })
    }

    /// The real degrees `(u, v)`: the least degrees that represent the same surface.
    fn real_degrees(&self) -> (usize, usize) {
        self.inner.real_degrees()
    }

    /// The same surface as a B-spline surface.
    fn to_bspline(&self) -> PyBSplineSurface {
        PyBSplineSurface {
            inner: self.inner.to_bspline(),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "BezierSurface(degrees=({}, {}), dim={})",
            self.inner.degree_u(),
            self.inner.degree_v(),
            self.inner.dim()
        )
    }
});

/// A tensor-product B-spline surface (docs/theory/surfaces.md).
///
/// Call: `s(u, v)`: the points at `(u, v)` (arrays of one shape, or numbers), `shape + (dim,)`.
#[pyclass(module = "lekalo", name = "BSplineSurface", frozen)]
pub(crate) struct PyBSplineSurface {
    pub(crate) inner: BSplineSurface,
}

surface_common!(PyBSplineSurface, BSpline, "bspline_surface", knots PyBSplineCurve, {
    #[new]
    fn new(
        degree_u: IntArg,
        degree_v: IntArg,
        knots_u: &Bound<'_, PyAny>,
        knots_v: &Bound<'_, PyAny>,
        control: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let degree_u = degree_u.count("degree_u")?;
        let degree_v = degree_v.count("degree_v")?;
        let inner = bspline_surface_arg((degree_u, degree_v), knots_u, knots_v, control)?;
        Ok(Self { inner })
    }

    /// The control net `(nu, nv, dim)`.
    #[getter]
    fn control<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        net_array(py, self.inner.control_points(), self.inner.net_size())
    }

    /// Degree elevation by `(by_u, by_v)`.
    fn elevate_degree(&self, py: Python<'_>, by_u: IntArg, by_v: IntArg) -> PyResult<Self> {
        let by_u = by_u.count("by_u")?;
        let by_v = by_v.count("by_v")?;
        Ok(Self {
            inner: py
                .detach(|| self.inner.elevate_degree(by_u, by_v))
                .map_err(lib_err)?,
        })
    }
});

/// A tensor-product NURBS surface (docs/theory/surfaces.md).
///
/// Call: `s(u, v)`: the points at `(u, v)` (arrays of one shape, or numbers), `shape + (dim,)`.
#[pyclass(module = "lekalo", name = "NurbsSurface", frozen)]
pub(crate) struct PyNurbsSurface {
    pub(crate) inner: NurbsSurface,
}

surface_common!(PyNurbsSurface, Nurbs, "nurbs_surface", knots PyNurbsCurve, {
    #[new]
    fn new(
        degree_u: IntArg,
        degree_v: IntArg,
        knots_u: &Bound<'_, PyAny>,
        knots_v: &Bound<'_, PyAny>,
        control: &Bound<'_, PyAny>,
        weights: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let degree_u = degree_u.count("degree_u")?;
        let degree_v = degree_v.count("degree_v")?;
        Ok(Self {
            inner: nurbs_surface_arg((degree_u, degree_v), knots_u, knots_v, control, weights)?,
        })
    }

    /// The Euclidean control net `(nu, nv, dim)`.
    #[getter]
    fn control<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        net_array(py, &self.inner.control_points(), self.inner.net_size())
    }

    /// The weights `(nu, nv)`.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (nu, nv) = self.inner.net_size();
        array(py, self.inner.weights(), &[nu, nv])
    }

    /// The surface swept by the 3-D `curve` (any curve class) turning about the axis through
    /// `axis_point` along `axis_direction`, from `start_angle` to `end_angle` (radians,
    /// counterclockwise seen from the axis's tip): `u` along the arcs, `v` the curve's
    /// parameter (`lekalo::NurbsSurface::revolve`, exact, P&T A8.1).
    #[staticmethod]
    #[pyo3(signature = (curve, axis_point, axis_direction, start_angle = 0.0,
                        end_angle = std::f64::consts::TAU))]
    fn revolve(
        curve: &Bound<'_, PyAny>,
        axis_point: [f64; 3],
        axis_direction: [f64; 3],
        start_angle: f64,
        end_angle: f64,
    ) -> PyResult<Self> {
        let c = curve_of(curve, "curve")?.to_nurbs();
        let inner = NurbsSurface::revolve(&c, axis_point, axis_direction, start_angle, end_angle)
            .map_err(lib_err)?;
        Ok(Self { inner })
    }

    /// The 3-D `curve` moved along `direction`: `S(u, v) = C(u) + v·direction`, `v` in
    /// `[v0, v1]` (`lekalo::NurbsSurface::extrude`, exact, P&T §8.3).
    #[staticmethod]
    #[pyo3(signature = (curve, direction, v0 = 0.0, v1 = 1.0))]
    fn extrude(curve: &Bound<'_, PyAny>, direction: [f64; 3], v0: f64, v1: f64) -> PyResult<Self> {
        let c = curve_of(curve, "curve")?.to_nurbs();
        let inner = NurbsSurface::extrude(&c, direction, v0, v1).map_err(lib_err)?;
        Ok(Self { inner })
    }

    /// The ruled surface `(1 − v)·first(u) + v·second(u)` between two curves of one dimension,
    /// each on `[0, 1]` by the affine change of its parameter (`lekalo::NurbsSurface::ruled`,
    /// exact, P&T §8.2).
    #[staticmethod]
    fn ruled(first: &Bound<'_, PyAny>, second: &Bound<'_, PyAny>) -> PyResult<Self> {
        let a = curve_of(first, "first")?.to_nurbs();
        let b = curve_of(second, "second")?.to_nurbs();
        let inner = NurbsSurface::ruled(&a, &b).map_err(lib_err)?;
        Ok(Self { inner })
    }
});

/// The Python object of a surface of any kind: the class of its kind.
pub(crate) fn surface_to_py(py: Python<'_>, s: lekalo::Surface) -> PyResult<Py<PyAny>> {
    Ok(match s {
        lekalo::Surface::Bezier(inner) => Py::new(py, PyBezierSurface { inner })?.into_any(),
        lekalo::Surface::BSpline(inner) => Py::new(py, PyBSplineSurface { inner })?.into_any(),
        lekalo::Surface::Nurbs(inner) => Py::new(py, PyNurbsSurface { inner })?.into_any(),
    })
}

/// The library's surface of an object of any of the three surface classes (`what` names the
/// argument in the error for any other object).
pub(crate) fn surface_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<lekalo::Surface> {
    if let Ok(s) = obj.cast::<PyBSplineSurface>() {
        return Ok(lekalo::Surface::BSpline(s.get().inner.clone()));
    }
    if let Ok(s) = obj.cast::<PyNurbsSurface>() {
        return Ok(lekalo::Surface::Nurbs(s.get().inner.clone()));
    }
    if let Ok(s) = obj.cast::<PyBezierSurface>() {
        return Ok(lekalo::Surface::Bezier(s.get().inner.clone()));
    }
    Err(crate::error::bad(format!(
        "{what}: expected a BezierSurface, BSplineSurface or NurbsSurface, got {}",
        obj.get_type().name()?
    )))
}
