//! `lekalo.Error` and its two kinds, as SciPy's users expect them:
//! - `lekalo.InputError(lekalo.Error, ValueError)`: bad input (a value, a shape, a choice);
//! - `lekalo.NumericalError(lekalo.Error, numpy.linalg.LinAlgError)`: a numerical failure on
//!   valid input (a singular or ill-conditioned system), as SciPy raises `LinAlgError`.
//!
//! Both are `ValueError`s (NumPy's `LinAlgError` is one), so code that caught the old
//! `lekalo.Error(ValueError)` still catches every error.
//!
//! A file that cannot be read is also the `OSError` Python raises for it, as `open` and NumPy's
//! `np.load` do: `lekalo.MissingFileError(lekalo.InputError, FileNotFoundError)`,
//! `lekalo.NotAFileError(lekalo.InputError, IsADirectoryError)` and
//! `lekalo.FileAccessError(lekalo.InputError, PermissionError)`, with the operating system's
//! `errno` and the `filename`; `str()` is lekalo's message.

use lekalo::Arg;
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};

create_exception!(
    lekalo,
    Error,
    PyException,
    "Bad input (lekalo.InputError) or a numerical failure (lekalo.NumericalError) reported by \
     lekalo; the message names the problem and the fix."
);

static INPUT_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static NUMERICAL_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static MISSING_FILE: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static NOT_A_FILE: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static FILE_ACCESS: PyOnceLock<Py<PyType>> = PyOnceLock::new();

/// The file errors: each class's name, its builtin `OSError` and its docstring.
const FILE_ERRORS: [(&str, &str, &str); 3] = [
    (
        "MissingFileError",
        "FileNotFoundError",
        "A file to read does not exist: a lekalo.InputError and a FileNotFoundError.",
    ),
    (
        "NotAFileError",
        "IsADirectoryError",
        "A path to read names a folder: a lekalo.InputError and an IsADirectoryError.",
    ),
    (
        "FileAccessError",
        "PermissionError",
        "A file to read may not be read: a lekalo.InputError and a PermissionError.",
    ),
];

/// Makes `InputError` and `NumericalError` (classes with two bases, which Python builds with
/// `type(name, bases, namespace)`) and adds the three classes to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let base = py.get_type::<Error>();
    m.add("Error", &base)?;
    let make = |name: &str,
                first: Bound<'_, PyAny>,
                other: Bound<'_, PyAny>,
                doc: &str|
     -> PyResult<Py<PyType>> {
        let namespace = PyDict::new(py);
        namespace.set_item("__module__", "lekalo")?;
        namespace.set_item("__doc__", doc)?;
        // the message alone, not `OSError`'s `[Errno 2] …: 'path'` (the message names the path)
        namespace.set_item(
            "__str__",
            py.get_type::<pyo3::exceptions::PyBaseException>()
                .getattr("__str__")?,
        )?;
        let bases = PyTuple::new(py, [first, other])?;
        let ty = py
            .get_type::<PyType>()
            .call1((name, bases, namespace))?
            .cast_into::<PyType>()?;
        m.add(name, &ty)?;
        Ok(ty.unbind())
    };
    let input = make(
        "InputError",
        base.clone().into_any(),
        py.get_type::<PyValueError>().into_any(),
        "Bad input: a value, shape or choice lekalo cannot use; the message names the argument and the fix.",
    )?;
    let linalg = py.import("numpy.linalg")?.getattr("LinAlgError")?;
    let numerical = make(
        "NumericalError",
        base.clone().into_any(),
        linalg,
        "A numerical failure on valid input (a singular or ill-conditioned system), as SciPy's LinAlgError.",
    )?;
    let builtins = py.import("builtins")?;
    for ((name, builtin, doc), cell) in
        FILE_ERRORS
            .iter()
            .zip([&MISSING_FILE, &NOT_A_FILE, &FILE_ACCESS])
    {
        let ty = make(
            name,
            input.bind(py).clone().into_any(),
            builtins.getattr(*builtin)?,
            doc,
        )?;
        let _ = cell.set(py, ty);
    }
    let _ = INPUT_ERROR.set(py, input);
    let _ = NUMERICAL_ERROR.set(py, numerical);
    Ok(())
}

/// An error of the kind `numerical` (else bad input) with `message`.
fn raise(numerical: bool, message: String) -> PyErr {
    Python::attach(|py| {
        let cell = if numerical {
            &NUMERICAL_ERROR
        } else {
            &INPUT_ERROR
        };
        match cell.get(py) {
            Some(ty) => PyErr::from_type(ty.bind(py).clone(), message),
            None => Error::new_err(message),
        }
    })
}

/// The Python name of each argument key of the library's errors ([`lekalo::Error::arg`]): the
/// one table from the library's keys to the keyword arguments, `None` for an argument that no
/// keyword of the package sets alone (or that functions spell differently), whose errors keep
/// the library's words. Exhaustive, so that a new key does not compile until it is named here.
pub(crate) const fn argument(arg: Arg) -> Option<&'static str> {
    Some(match arg {
        Arg::Knots => "knots",
        Arg::Parametrization | Arg::Exponent => "parametrization",
        // `interpolate(params=)`, `CubicHermite(params, points, tangents)`,
        // `fit_least_squares(points, params, t)`
        Arg::Parameters => "params",
        Arg::Tangents => "tangents",
        // SciPy's `w` of every fit
        Arg::DataWeights => "w",
        Arg::End => "end",
        Arg::EndDerivatives => "d_start/d_end",
        Arg::StartDerivative => "d_start",
        Arg::EndDerivative => "d_end",
        Arg::Rule => "rule",
        Arg::Expression => "f",
        Arg::Lambda => "lam",
        Arg::Tolerance => "tolerance",
        // relative, as NumPy's and SciPy's `rtol` (`CurveQuery.length_at`, `param_at`)
        Arg::RelativeTolerance => "rtol",
        Arg::S => "s",
        Arg::KnotRounds => "knot_rounds",
        Arg::Eps => "eps",
        Arg::MaxKnots => "max_knots",
        Arg::Bbox => "bbox",
        // the fits on the sphere (SciPy's names)
        Arg::ColatitudeKnots => "tt",
        Arg::LongitudeKnots => "tp",
        Arg::Colatitudes => "u",
        Arg::Longitudes => "v",
        Arg::PoleValues => "pole_values",
        Arg::PoleFlat => "pole_flat",
        Arg::Weights
        | Arg::ControlPoints
        | Arg::Direction
        | Arg::Breakpoints
        | Arg::ContinuityConditions
        | Arg::Continuity
        | Arg::CornerWindow
        | Arg::CornerFraction
        | Arg::CornerLength
        | Arg::Times
        | Arg::Knot => return None,
    })
}

/// The library's error as `lekalo.NumericalError` (a singular or ill-conditioned system, a
/// mesh whose bound stayed above its tolerance) or
/// `lekalo.InputError` (everything else); a refused value of an argument with a keyword
/// ([`argument`]) is named by the keyword (`knots: …`), and any other error about such an
/// argument is written whole under a keyword that is not the library's word for it (`params:
/// parameters (one per point): expected 5, got 3`).
pub(crate) fn lib_err(e: lekalo::Error) -> PyErr {
    let numerical = matches!(
        e,
        lekalo::Error::SingularSystem { .. }
            | lekalo::Error::IllConditioned { .. }
            | lekalo::Error::ToleranceNotMet { .. }
    );
    if let Some((arg, name)) = e.arg().and_then(|a| Some((a, argument(a)?))) {
        match &e {
            lekalo::Error::InvalidArgument { reason, .. } => {
                return raise(false, format!("{name}: {reason}"));
            }
            // the message already names a keyword that is the library's word (`tangents`)
            _ if name != arg.words() => return raise(numerical, format!("{name}: {e}")),
            _ => {}
        }
    }
    raise(numerical, e.to_string())
}

/// The library's error for a function `y(x)`: the sequence it finds decreasing or repeating
/// ([`lekalo::Error::NotIncreasing`], [`lekalo::Error::Repeated`], which the library's
/// interpolation calls its "parameters") is the argument `x`, and the message names it so; other errors as
/// [`lib_err`].
pub(crate) fn function_err(e: lekalo::Error) -> PyErr {
    match e {
        lekalo::Error::NotIncreasing {
            index,
            value,
            previous,
            ..
        } => lib_err(lekalo::Error::NotIncreasing {
            what: "x".into(),
            index,
            value,
            previous,
        }),
        lekalo::Error::Repeated { index, value, .. } => lib_err(lekalo::Error::Repeated {
            what: "x".into(),
            index,
            value,
        }),
        other => lib_err(other),
    }
}

/// The file-format crate's error as `lekalo.InputError`; a file that cannot be read as the
/// `lekalo.InputError` that is also Python's `OSError` for it (module docs), with `errno` and
/// `filename`.
pub(crate) fn io_err(e: lekalo_io::IoError) -> PyErr {
    if let lekalo_io::IoError::Read { path, error } = &e {
        let cell = match error.kind() {
            std::io::ErrorKind::NotFound => Some(&MISSING_FILE),
            std::io::ErrorKind::IsADirectory => Some(&NOT_A_FILE),
            std::io::ErrorKind::PermissionDenied => Some(&FILE_ACCESS),
            _ => None,
        };
        if let Some(cell) = cell {
            let message = e.to_string();
            let made = Python::attach(|py| -> PyResult<PyErr> {
                let Some(ty) = cell.get(py) else {
                    return Ok(Error::new_err(message.clone()));
                };
                let value = ty.bind(py).call1((message.clone(),))?;
                value.setattr("errno", error.raw_os_error())?;
                value.setattr("filename", path.as_os_str())?;
                Ok(PyErr::from_value(value))
            });
            return made.unwrap_or_else(|err| err);
        }
    }
    raise(false, e.message_with(limit_keyword))
}

/// The keyword argument that raises a limit of reading, in a message's "raise the limit with
/// `max_size=N`" ([`lekalo_io::IoError::message_with`]).
fn limit_keyword(limit: lekalo_io::Limit) -> &'static str {
    match limit {
        lekalo_io::Limit::Size => "max_size=",
        lekalo_io::Limit::InputBytes => "max_input_bytes=",
    }
}

/// The library's error as `lekalo.InputError`, prefixed with the Python argument at fault.
pub(crate) fn named(what: &str, e: &lekalo::Error) -> PyErr {
    bad(format!("{what}: {e}"))
}

/// An argument error found by the binding itself (dtype, layout, shape), as
/// `lekalo.InputError`.
pub(crate) fn bad(msg: String) -> PyErr {
    raise(false, msg)
}
