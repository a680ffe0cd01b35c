//! lekalo's kernels as XLA FFI handlers (typed custom calls, `jax.ffi.ffi_call`), so that
//! `lekalo.jax` runs inside a compiled JAX program with no host callback.
//!
//! - `abi`: the C ABI of `xla/ffi/api/c_api.h` mirrored in Rust, the decoding of a call frame
//!   into slices, the metadata query, errors and caught panics;
//! - `curve`: B-spline curve evaluation and its JVP and VJP with respect to the control points
//!   and the parameters (`lekalo::derivatives`, `docs/theory/derivatives.md`).
//!
//! Batching (`jax.vmap`): every argument and result may carry the same leading batch axes (the
//! layout of `vmap_method="broadcast_all"`); a handler runs the kernel once a batch element.
//! Python registers the handlers from [`handlers`] (`lekalo.jax`), one address a target name.

mod abi;
mod curve;

use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Registers the functions of this module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(xla_ffi_handlers, m)?)?;
    Ok(())
}

/// The XLA FFI handlers, `name -> address` of an `XLA_FFI_Error* handler(XLA_FFI_CallFrame*)`
/// for `jax.ffi.register_ffi_target(name, jax.ffi.pycapsule(address), platform="cpu")`.
#[pyfunction]
fn xla_ffi_handlers(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for (name, handler) in curve::HANDLERS {
        d.set_item(name, *handler as usize)?;
    }
    Ok(d)
}

/// The leading batch axes shared by all buffers, each buffer having `core` trailing axes:
/// returns the number of batch elements and, a buffer, the size of one element.
fn batch_layout(dims: &[(&str, &[i64], usize)]) -> Result<(usize, Vec<usize>), String> {
    let Some(&(_, first, first_core)) = dims.first() else {
        return Ok((1, Vec::new()));
    };
    let lead = first.len().checked_sub(first_core).ok_or_else(|| {
        format!(
            "{} has rank {}, fewer than {first_core}",
            dims[0].0,
            first.len()
        )
    })?;
    let batch_dims = &first[..lead];
    let to_usize = |d: &[i64]| -> Option<usize> {
        d.iter()
            .try_fold(1usize, |acc, &x| acc.checked_mul(usize::try_from(x).ok()?))
    };
    let batch = to_usize(batch_dims).ok_or("bad batch dimensions")?;
    let mut sizes = Vec::with_capacity(dims.len());
    for &(what, d, core) in dims {
        if d.len() != lead + core || d[..lead] != *batch_dims {
            return Err(format!(
                "{what} has shape {d:?}; the leading (batch) axes must be {batch_dims:?}, \
                 followed by {core} axes"
            ));
        }
        sizes.push(to_usize(&d[lead..]).ok_or("bad dimensions")?);
    }
    Ok((batch, sizes))
}
