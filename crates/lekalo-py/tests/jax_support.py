"""What the lekalo.jax tests share: float64 switched on for each test, the Jacobian by
central differences, and the relative comparison at the tolerance the derivatives promise
(1e-7 relative, ``docs/differentiable.md``)."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")

RTOL = 1e-7


@pytest.fixture(autouse=True)
def x64():
    """float64 for the test, the previous setting restored after it."""
    old = jax.config.jax_enable_x64
    jax.config.update("jax_enable_x64", True)
    yield
    jax.config.update("jax_enable_x64", old)


def central(f, x, h):
    """Jacobian of f at x by central differences, shape f(x).shape + x.shape."""
    x = np.asarray(x, dtype=float)
    cols = []
    for i in range(x.size):
        e = np.zeros(x.size)
        e[i] = h
        e = e.reshape(x.shape)
        cols.append((np.asarray(f(x + e)) - np.asarray(f(x - e))) / (2 * h))
    return np.stack(cols, axis=-1).reshape(np.shape(f(x)) + x.shape)


def assert_rel(a, b, what):
    """``a`` equals ``b`` to ``RTOL`` relative to the largest entry of ``b`` (at least 1)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, (what, a.shape, b.shape)
    err = np.max(np.abs(a - b)) if a.size else 0.0
    scale = max(np.max(np.abs(b)) if b.size else 0.0, 1.0)
    assert err <= RTOL * scale, f"{what}: error {err:.3e} above {RTOL} x {scale:.3e}"


# What an error inside one of lekalo's FFI targets reaches the caller as: JAX raises
# `jax.errors.JaxRuntimeError` from a call that compiles, and `ValueError` (the error's code is
# XLA's INVALID_ARGUMENT) from a call of an already compiled function through JAX's C++ fast
# path; both carry lekalo's message.
RUNTIME_ERRORS = (jax.errors.JaxRuntimeError, ValueError)
