//! `lekalo.Error`, a subclass of `ValueError` carrying the library's message.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;

create_exception!(
    lekalo,
    Error,
    PyValueError,
    "Bad input or a numerical failure reported by lekalo; the message names the problem and the fix."
);

/// The library's error as `lekalo.Error`, with its message.
pub(crate) fn lib_err(e: lekalo::Error) -> PyErr {
    Error::new_err(e.to_string())
}

/// The file-format crate's error as `lekalo.Error`.
pub(crate) fn io_err(e: lekalo_io::IoError) -> PyErr {
    Error::new_err(e.to_string())
}

/// An argument error found by the binding itself (dtype, layout, shape).
pub(crate) fn bad(msg: String) -> PyErr {
    Error::new_err(msg)
}
