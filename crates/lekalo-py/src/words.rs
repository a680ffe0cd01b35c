//! The options every front end shares, read from the library's vocabulary
//! ([`lekalo::vocabulary`]): `knots="at-params"`, `parametrization="centripetal"`,
//! `end="natural"`, `rule="greville"`. An older spelling is still read, with a
//! `DeprecationWarning` naming the canonical word; an unknown word is a `lekalo.Error` that
//! names the argument and lists the words.

use lekalo::vocabulary::Vocabulary;
use pyo3::exceptions::PyDeprecationWarning;
use pyo3::prelude::*;

use crate::error::bad;

/// The value of `text` for the argument `name` (the Python keyword).
pub(crate) fn word<T: Copy + PartialEq + 'static>(
    vocabulary: &'static Vocabulary<T>,
    name: &str,
    text: &str,
) -> PyResult<T> {
    match vocabulary.parse(text) {
        Ok(w) => {
            if w.old_spelling {
                if let Some(canonical) = vocabulary.name(w.value) {
                    Python::attach(|py| {
                        PyErr::warn(
                            py,
                            &py.get_type::<PyDeprecationWarning>(),
                            &std::ffi::CString::new(format!(
                                "{name}={text:?} is an older spelling; write {name}={canonical:?}"
                            ))
                            .unwrap_or_default(),
                            1,
                        )
                    })?;
                }
            }
            Ok(w.value)
        }
        Err(_) => Err(bad(format!(
            "{name}: unknown value {text:?}; use one of {}",
            vocabulary
                .names()
                .iter()
                .map(|n| format!("'{n}'"))
                .collect::<Vec<_>>()
                .join(", ")
        ))),
    }
}
