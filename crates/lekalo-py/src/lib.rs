//! # lekalo-py — the Python package `lekalo`
//!
//! The native module `lekalo._lekalo`, built by maturin into one `abi3` wheel for `CPython` ≥ 3.9;
//! the pure-Python package around it (`python/lekalo/`) adds SciPy and geomdl interop and the
//! type stubs. This crate holds conversions and argument handling only: every computation is a
//! call of the `lekalo` library, made with the GIL released.
//!
//! - arrays: `convert` (float64, C- or F-ordered, the last axis is the dimension; C-ordered
//!   arrays are borrowed, not copied);
//! - errors: `error` (`lekalo.Error`, with `lekalo.InputError`, a `ValueError`, and
//!   `lekalo.NumericalError`, a `numpy.linalg.LinAlgError`);
//! - classes: `curves` (their calculus in `calculus`), `surfaces`, `tensor` (N variables,
//!   SciPy's `NdBSpline`; `tensor_nurbs`: its rational twin; `tensor_values`: SciPy's
//!   `(t, c, k)` arrays evaluated in place),
//!   `interp` (interpolation, Hermite; SciPy's Hermite slopes in `slopes`), `pp`, `blend`; knot insertion into periodic splines given as arrays: `periodic`;
//! - fitting: `fit` (SciPy-named `make_*` functions and `fit_*` with reports); `sphere` (the
//!   bicubic splines on the sphere of SciPy's three `*SphereBivariateSpline` classes);
//! - CAD files: `faces` (`read_step`, `read_iges`, `write_step`, `write_iges`, `Face`: a surface
//!   trimmed by loops of edges);
//! - geometric queries: `query` (`CurveQuery`, `SurfaceQuery`);
//! - SciPy's test of a piecewise polynomial's breakpoints (sorted one way): `breakpoints`;
//! - SciPy's `(t, c, k)` arrays: derivative and antiderivative coefficients and integrals read in
//!   place, without a curve built: `tck`;
//! - many curves at once: `batch`;
//! - derivatives of evaluation for automatic differentiation: `derivatives` (the kernels under
//!   `lekalo.jax`); `xla_ffi`: kernels as XLA FFI handlers, called by `lekalo.jax` from inside
//!   compiled JAX programs.

mod batch;
mod blend;
mod breakpoints;
mod calculus;
mod convert;
mod curves;
mod derivatives;
mod error;
mod faces;
mod fit;
mod hermite_pp;
mod interp;
mod objects;
mod periodic;
mod pp;
mod query;
mod shape;
mod slopes;
mod sphere;
mod surfaces;
mod tck;
mod tensor;
mod tensor_fit;
mod tensor_nurbs;
mod tensor_values;
mod words;
mod xla_ffi;

use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _lekalo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    error::register(m)?;
    m.add("MAX_SCALARS", lekalo::MAX_SCALARS)?;
    m.add("MAX_DEGREE", lekalo::MAX_DEGREE)?;
    // the package's version is the crate's (pyproject.toml takes it from Cargo.toml)
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<curves::PyBezierCurve>()?;
    m.add_class::<curves::PyBSplineCurve>()?;
    m.add_class::<curves::PyNurbsCurve>()?;
    m.add_class::<surfaces::PyBezierSurface>()?;
    m.add_class::<surfaces::PyBSplineSurface>()?;
    m.add_class::<surfaces::PyNurbsSurface>()?;
    m.add_class::<interp::PyCubicHermite>()?;
    m.add_class::<pp::PyPiecewisePolynomial>()?;
    m.add_class::<pp::PyPpSpace>()?;
    m.add_class::<tensor::PyTensorBSpline>()?;
    m.add_class::<tensor_nurbs::PyTensorNurbs>()?;
    m.add_function(wrap_pyfunction!(objects::from_json, m)?)?;
    m.add_function(wrap_pyfunction!(faces::read_step, m)?)?;
    m.add_function(wrap_pyfunction!(faces::read_iges, m)?)?;
    m.add_function(wrap_pyfunction!(faces::write_step, m)?)?;
    m.add_function(wrap_pyfunction!(faces::write_iges, m)?)?;
    m.add_function(wrap_pyfunction!(faces::mesh_faces, m)?)?;
    m.add_class::<faces::PyFace>()?;
    m.add_function(wrap_pyfunction!(interp::interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(interp::parametrize, m)?)?;
    m.add_function(wrap_pyfunction!(interp::basis_functions, m)?)?;
    m.add_function(wrap_pyfunction!(interp::design_matrix_csr, m)?)?;
    m.add_function(wrap_pyfunction!(interp::natural_cubic_spline, m)?)?;
    m.add_function(wrap_pyfunction!(
        interp::interpolate_with_end_derivatives,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(interp::interpolate_surface, m)?)?;
    m.add_function(wrap_pyfunction!(interp::cubic_through_four_points, m)?)?;
    m.add_function(wrap_pyfunction!(pp::quasi_interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(pp::hermite_bernstein, m)?)?;
    m.add_function(wrap_pyfunction!(pp::ppoly_values, m)?)?;
    m.add_function(wrap_pyfunction!(pp::ppoly_value, m)?)?;
    m.add_function(wrap_pyfunction!(pp::bpoly_values, m)?)?;
    m.add_function(wrap_pyfunction!(pp::bpoly_value, m)?)?;
    m.add_function(wrap_pyfunction!(periodic::insert_knot_periodic, m)?)?;
    m.add_function(wrap_pyfunction!(periodic::insert_knot_raw, m)?)?;
    m.add_function(wrap_pyfunction!(curves::composite_curve, m)?)?;
    m.add_function(wrap_pyfunction!(pp::piecewise_hermite_bernstein, m)?)?;
    m.add_function(wrap_pyfunction!(batch::interpolate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::evaluate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(calculus::bspline_value, m)?)?;
    blend::register(m)?;
    breakpoints::register(m)?;
    derivatives::register(m)?;
    fit::register(m)?;
    query::register(m)?;
    slopes::register(m)?;
    sphere::register(m)?;
    tensor_fit::register(m)?;
    tensor_values::register(m)?;
    tck::register(m)?;
    hermite_pp::register(m)?;
    xla_ffi::register(m)?;
    Ok(())
}
