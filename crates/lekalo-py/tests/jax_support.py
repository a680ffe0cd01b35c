"""What the lekalo.jax tests share: float64 switched on for each test, and (from
derivative_checks, shared with the lekalo.torch tests) the Jacobian by central differences and
the relative comparison at the tolerance the derivatives promise (1e-7 relative,
``docs/differentiable.md``)."""

import pytest

jax = pytest.importorskip("jax")

from derivative_checks import RTOL, assert_rel, central  # noqa: E402,F401  (re-exported)


@pytest.fixture(autouse=True)
def x64():
    """float64 for the test, the previous setting restored after it."""
    old = jax.config.jax_enable_x64
    jax.config.update("jax_enable_x64", True)
    yield
    jax.config.update("jax_enable_x64", old)


# What an error inside one of lekalo's FFI targets reaches the caller as: JAX raises
# `jax.errors.JaxRuntimeError` from a call that compiles, and `ValueError` (the error's code is
# XLA's INVALID_ARGUMENT) from a call of an already compiled function through JAX's C++ fast
# path; both carry lekalo's message.
RUNTIME_ERRORS = (jax.errors.JaxRuntimeError, ValueError)
