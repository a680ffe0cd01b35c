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

/// The library's error as `lekalo.Error`, with its message in Python's words
/// ([`python_terms`]).
pub(crate) fn lib_err(e: lekalo::Error) -> PyErr {
    Error::new_err(python_terms(&e.to_string()))
}

/// `(library wording, Python wording)`: the few library messages that name Rust items, as
/// the Python package spells them (the command line has its own table).
const TERMS: [(&str, &str); 3] = [
    ("use KnotPlacement::Auto", "use knots='auto'"),
    ("net_size.0", "control.shape[0]"),
    ("net_size.1", "control.shape[1]"),
];

/// `message` with every Rust item of [`TERMS`] replaced by its Python spelling.
pub(crate) fn python_terms(message: &str) -> String {
    let mut out = message.to_string();
    for (library, python) in TERMS {
        if out.contains(library) {
            out = out.replace(library, python);
        }
    }
    out
}

/// The file-format crate's error as `lekalo.Error`.
pub(crate) fn io_err(e: lekalo_io::IoError) -> PyErr {
    Error::new_err(e.to_string())
}

/// An argument error found by the binding itself (dtype, layout, shape).
pub(crate) fn bad(msg: String) -> PyErr {
    Error::new_err(msg)
}
