"""What every function of ``lekalo.jax`` shares: argument checks and the first-order guard."""

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
