//! Objects of any kind for Python: the class of each curve, surface or piecewise polynomial
//! read from the CLI's JSON (`docs/formats.md`); `from_json` is also what pickling calls.

use lekalo_io::Shape;
use pyo3::prelude::*;

use crate::convert::from_json_shape;
use crate::curves::curve_to_py;
use crate::error::bad;
use crate::pp::PyPiecewisePolynomial;
use crate::surfaces::surface_to_py;

/// Python object for any shape read from JSON.
pub(crate) fn shape_to_py(py: Python<'_>, shape: Shape) -> PyResult<Py<PyAny>> {
    Ok(match shape {
        Shape::Curve(c) => curve_to_py(py, c)?,
        Shape::Surface(s) => surface_to_py(py, s)?,
        Shape::Pp(p) => Py::new(py, PyPiecewisePolynomial { inner: p })?.into_any(),
        other => {
            return Err(bad(format!(
                "JSON object of type {:?} has no Python class",
                other.type_name()
            )))
        }
    })
}

/// Reads any lekalo object from its JSON text (the CLI's format, `docs/formats.md`).
#[pyfunction]
pub(crate) fn from_json(py: Python<'_>, text: &str) -> PyResult<Py<PyAny>> {
    let shape = py.detach(|| from_json_shape(text))?;
    shape_to_py(py, shape)
}
