//! lekalo's kernels as XLA FFI handlers (typed custom calls, `jax.ffi.ffi_call`), so that
//! `lekalo.jax` runs inside a compiled JAX program with no host callback.
//!
//! - `abi`: the C ABI of `xla/ffi/api/c_api.h` mirrored in Rust, the decoding of a call frame
//!   into slices, the metadata query, errors and caught panics;
//! - `operands`: what every handler does with its buffers, once: the batch axes, a batch
//!   element's slice, the `with_<kind>` flags and the split of a derivative target's operands;
//! - `curve`: B-spline curve evaluation and its JVP and VJP with respect to the knots, the
//!   control points and the parameters (`lekalo::derivatives`, `docs/theory/derivatives.md`);
//! - `nurbs`: the same for NURBS curves, also with respect to the weights;
//! - `interpolate`: interpolation at given parameters and knots, and its JVP and VJP with
//!   respect to the data and the parameters (`lekalo::derivatives::Interpolant`);
//! - `fits`: the least-squares fit on given knots and the smoothing spline with a given `λ`,
//!   and their JVP and VJP with respect to the data (`lekalo::derivatives::LeastSquaresFit`,
//!   `SmoothingFit`);
//! - `geometry`: a B-spline curve's arc length (with respect to the knots and the control
//!   points) and the parameters of its closest points to given points (with respect to the
//!   knots, the control points and the points), with their JVP and VJP (`lekalo::derivatives::ArcLengthGradient`,
//!   `ClosestParameters`);
//! - `surface`: tensor-product B-spline surfaces, with respect to the knots, the net and
//!   `(u, v)`;
//! - `tensor`: tensor-product B-splines in `N` variables, with respect to the knots of each
//!   direction, the net and the points;
//! - `nurbs_surface`: NURBS surfaces, with respect to the knots, the net, the weights and
//!   `(u, v)`;
//! - `tensor_nurbs`: tensor-product NURBS in `N` variables, with respect to the knots of each
//!   direction, the net, the weights and the points.
//!
//! Batching (`jax.vmap`): every argument and result may carry the same leading batch axes (the
//! layout of `vmap_method="broadcast_all"`); a handler runs the kernel once a batch element.
//! Python registers the handlers from [`handlers`] (`lekalo.jax`), one address a target name.

/// A family's `HANDLERS`: the three `extern "C"` entry points of targets `lekalo_<stem>_eval`,
/// `_jvp` and `_vjp`, each [`abi::handle`] around its body, with the Python function's name
/// (`lekalo.jax.<function>`, "(forward derivative)", "(reverse derivative)") in its errors.
///
/// A family whose derivatives reuse a factorisation of the forward pass adds
/// `factor: $factor`, the target `lekalo_<stem>_factor`: the values and the factors that its
/// JVP and VJP targets then take as a residual instead of factoring again.
macro_rules! ffi_targets {
    (stem: $stem:literal, function: $function:literal,
     eval: $eval:path, jvp: $jvp:path, vjp: $vjp:path $(,)?) => {
        ffi_targets!(@targets $stem, $function, $eval, $jvp, $vjp, []);
    };
    (stem: $stem:literal, function: $function:literal,
     eval: $eval:path, factor: $factor:path, jvp: $jvp:path, vjp: $vjp:path $(,)?) => {
        ffi_targets!(@targets $stem, $function, $eval, $jvp, $vjp, [$factor]);
    };
    (@targets $stem:literal, $function:literal, $eval:path, $jvp:path, $vjp:path,
     [$($factor:path)?]) => {
        /// The handlers of this module, by target name.
        pub(super) const HANDLERS: &[(&str, super::Handler)] = {
            use super::abi::{handle, CallFrame, XlaError};
            extern "C" fn eval(frame: *mut CallFrame) -> *mut XlaError {
                handle(frame, concat!("lekalo.jax.", $function), $eval)
            }
            $(
                extern "C" fn factor(frame: *mut CallFrame) -> *mut XlaError {
                    handle(frame, concat!("lekalo.jax.", $function), $factor)
                }
            )?
            extern "C" fn jvp(frame: *mut CallFrame) -> *mut XlaError {
                let target = concat!("lekalo.jax.", $function, " (forward derivative)");
                handle(frame, target, $jvp)
            }
            extern "C" fn vjp(frame: *mut CallFrame) -> *mut XlaError {
                let target = concat!("lekalo.jax.", $function, " (reverse derivative)");
                handle(frame, target, $vjp)
            }
            &[
                (concat!("lekalo_", $stem, "_eval"), eval),
                // (`$factor` named so that the entry repeats with it)
                $((concat!("lekalo_", $stem, "_factor"), { let _ = stringify!($factor); factor }),)?
                (concat!("lekalo_", $stem, "_jvp"), jvp),
                (concat!("lekalo_", $stem, "_vjp"), vjp),
            ]
        };
    };
}

mod abi;
mod curve;
mod fits;
mod geometry;
mod interpolate;
mod nurbs;
mod nurbs_surface;
mod operands;
mod surface;
mod tensor;
mod tensor_nurbs;

use pyo3::prelude::*;
use pyo3::types::PyDict;

/// An `XLA_FFI_Handler`.
type Handler = extern "C" fn(*mut abi::CallFrame) -> *mut abi::XlaError;

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
    let all = [
        curve::HANDLERS,
        fits::HANDLERS[0],
        fits::HANDLERS[1],
        geometry::HANDLERS[0],
        geometry::HANDLERS[1],
        interpolate::HANDLERS,
        nurbs::HANDLERS,
        nurbs_surface::HANDLERS,
        surface::HANDLERS,
        tensor::HANDLERS,
        tensor_nurbs::HANDLERS,
    ];
    for (name, handler) in all.into_iter().flatten() {
        d.set_item(name, *handler as usize)?;
    }
    Ok(d)
}
