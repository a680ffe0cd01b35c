"""What every function of ``lekalo.jax`` shares: argument checks, the first-order guard, and
the host-callback plumbing (``jax.pure_callback`` with a loop over batch axes) of the functions
that have no XLA FFI target yet (``interpolate`` and the fits)."""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp
import numpy as np
from jax.custom_derivatives import SymbolicZero

from ._lekalo import InputError


def _require_x64(name):
    if not jax.config.jax_enable_x64:
        raise InputError(
            f"lekalo.jax.{name} computes in float64: enable it with "
            "jax.config.update('jax_enable_x64', True) at the start of the program"
        )


def _float64(x, what, name):
    x = jnp.asarray(x)
    if not jnp.issubdtype(x.dtype, jnp.floating) and not jnp.issubdtype(x.dtype, jnp.integer):
        raise InputError(f"lekalo.jax.{name}: {what} must be real numbers, got dtype {x.dtype}")
    return x.astype(jnp.float64)


def _degree(d, what, name):
    if isinstance(d, (bool, np.bool_)) or not isinstance(d, (int, np.integer)) or d < 0:
        raise InputError(
            f"lekalo.jax.{name}: {what} must be a non-negative Python int (a static value), "
            f"got {d!r}"
        )
    return int(d)


def _looped(fn, core_ndims, *arrays):
    """``fn`` on arrays with leading batch axes (``vmap_method="expand_dims"``: an unbatched
    argument has size-1 batch axes): one call a batch element, the results stacked."""
    arrays = [np.asarray(a) for a in arrays]
    batch_shapes = [a.shape[: a.ndim - c] for a, c in zip(arrays, core_ndims)]
    batch = np.broadcast_shapes(*batch_shapes)
    if batch == ():
        return fn(*arrays)
    results = []
    for idx in np.ndindex(*batch):
        parts = []
        for a, bs in zip(arrays, batch_shapes):
            off = len(batch) - len(bs)
            parts.append(a[tuple(0 if s == 1 else idx[off + k] for k, s in enumerate(bs))])
        results.append(fn(*parts))
    return tuple(
        np.stack([r[k] for r in results]).reshape(batch + results[0][k].shape)
        for k in range(len(results[0]))
    )


@partial(jax.custom_jvp, nondiff_argnums=(0,))
def _first_order_only(name, x):
    return x


@partial(_first_order_only.defjvp, symbolic_zeros=True)
def _first_order_only_jvp(name, primals, tangents):
    (x,), (dx,) = primals, tangents
    if not isinstance(dx, SymbolicZero):
        raise NotImplementedError(
            f"lekalo.jax.{name}: only first derivatives are supported (jax.grad, jax.jacfwd, "
            "jax.jacrev, jax.jvp, jax.vjp); a second derivative (jax.hessian, nested jacfwd/"
            "jacrev) would differentiate the derivative kernels themselves"
        )
    return x, jnp.zeros_like(x)


def _no_knot_tangent(name, *tangents):
    if any(not isinstance(t, SymbolicZero) for t in tangents):
        raise NotImplementedError(
            f"lekalo.jax.{name}: derivatives with respect to the knots are not supported; pass "
            "the knots as constants (close over them, or wrap them in jax.lax.stop_gradient)"
        )


# -- host callbacks ------------------------------------------------------------------------------


def _struct(shape, dtype=jnp.float64):
    return jax.ShapeDtypeStruct(shape, dtype)


def _callback(cb, shapes, *args):
    """``cb(*args)`` run on the host by ``jax.pure_callback`` into ``shapes``; under ``vmap``
    the batch axes lead (``vmap_method="expand_dims"``) and ``cb`` loops over them
    (``_looped``)."""
    return jax.pure_callback(cb, shapes, *args, vmap_method="expand_dims")


def _linearized(name, cb, shapes, *args):
    """``_callback`` of a linearisation on ``args``, each through ``_first_order_only`` so that
    a second derivative of ``lekalo.jax.{name}`` raises."""
    guard = partial(_first_order_only, name)
    return _callback(cb, shapes, *(guard(a) for a in args))
