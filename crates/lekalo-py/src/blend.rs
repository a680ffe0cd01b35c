//! Blending (document 001): registered in `register`.

use pyo3::prelude::*;

/// Adds the blending classes to the module.
pub(crate) fn register(_m: &Bound<'_, PyModule>) -> PyResult<()> {
    Ok(())
}
