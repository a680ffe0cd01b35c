//! Knot insertion into splines given as arrays (knots and coefficients, SciPy's layout), as
//! FITPACK's `fpinst` does it: periodic splines with their periodic extension
//! (docs/theory/curves.md#periodic-knot-insertion) and insertion at any multiplicity
//! (docs/theory/curves.md#knot-insertion-on-raw-knots).

use lekalo::{Points, PointsRef};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::convert::IntArg;
use crate::convert::{floats, points_into_array, vec1, vec_array};
use crate::error::lib_err;

/// The spline of `knots` and coefficients `control` through the library's knot insertion
/// `insert(knots, control)`, run with the GIL released: `(knots, control)` as arrays.
fn inserted<'py>(
    py: Python<'py>,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    insert: impl Send + FnOnce(&[f64], PointsRef<'_>) -> lekalo::Result<(Vec<f64>, Points)>,
) -> PyResult<Bound<'py, PyTuple>> {
    let t = vec1(knots, "knots")?;
    let ca = floats(control, "control")?;
    let c = ca.points("control")?;
    let (t2, c2) = py.detach(|| insert(&t, c)).map_err(lib_err)?;
    PyTuple::new(py, [vec_array(py, &t2), points_into_array(py, c2)?])
}

/// The periodic spline of degree `k` with `knots` and coefficients `control` (`(n − k − 1,)` or
/// `(n − k − 1, dim)`) with `x` inserted `times` times, the periodic extension kept: returns
/// `(knots, control)` (`lekalo::insert_knot_periodic`; FITPACK's `fpinst`, SciPy's
/// `insert(..., per=True)`).
///
/// >>> import lekalo
/// >>> t, c = lekalo.insert_knot_periodic(1, [-1.0, 0.0, 1.0, 2.0, 3.0], [1.0, 0.0, 1.0], 0.5)
/// >>> t.tolist(), c[:, 0].tolist()
/// ([-1.0, 0.0, 0.5, 1.0, 2.0, 2.5], [1.0, 0.5, 0.0, 1.0])
#[pyfunction]
#[pyo3(signature = (k, knots, control, x, times = IntArg::of(1)), text_signature = "(k, knots, control, x, times=1)")]
pub(crate) fn insert_knot_periodic<'py>(
    py: Python<'py>,
    k: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    x: f64,
    times: IntArg,
) -> PyResult<Bound<'py, PyTuple>> {
    let k = k.count("k")?;
    let times = times.count("times")?;
    inserted(py, knots, control, |t, c| {
        lekalo::insert_knot_periodic(k, t, c, x, times)
    })
}

/// The spline of degree `k` with `knots` and coefficients `control` (`(n − k − 1,)` or
/// `(n − k − 1, dim)`) with `x` inserted `times` times at any multiplicity, past `k + 1` at the
/// ends of the base interval and past `k` inside: returns `(knots, control)`
/// (`lekalo::insert_knot_raw`; FITPACK's `fpinst` with `iopt = 0`, SciPy's `insert`).
///
/// >>> import lekalo
/// >>> t, c = lekalo.insert_knot_raw(1, [0.0, 0.0, 1.0, 1.0], [0.0, 1.0], 0.0)
/// >>> t.tolist(), c[:, 0].tolist()
/// ([0.0, 0.0, 0.0, 1.0, 1.0], [0.0, 0.0, 1.0])
#[pyfunction]
#[pyo3(signature = (k, knots, control, x, times = IntArg::of(1)), text_signature = "(k, knots, control, x, times=1)")]
pub(crate) fn insert_knot_raw<'py>(
    py: Python<'py>,
    k: IntArg,
    knots: &Bound<'py, PyAny>,
    control: &Bound<'py, PyAny>,
    x: f64,
    times: IntArg,
) -> PyResult<Bound<'py, PyTuple>> {
    let k = k.count("k")?;
    let times = times.count("times")?;
    inserted(py, knots, control, |t, c| {
        lekalo::insert_knot_raw(k, t, c, x, times)
    })
}
