"""lekalo.jax through XLA's FFI: the compiled programs call lekalo's custom-call targets (no host
callback), the derivatives through them match central differences (relative 1e-7) under jit and
vmap, the batch layouts reach the handlers intact, and lekalo's errors come back as JAX errors
carrying lekalo's message."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import bspline_eval  # noqa: E402


def curve_case(dim=2, seed=3):
    rng = np.random.default_rng(seed)
    knots = np.array([0, 0, 0, 0, 0.2, 0.45, 0.8, 1, 1, 1, 1.0])
    ctrl = rng.uniform(-1, 1, (7, dim))
    u = np.array([0.03, 0.3, 0.5, 0.66, 0.9, 0.99])  # off the knots
    return knots, ctrl, u


def reference(knots, ctrl, u, degree=3):
    knots, ctrl, u = (np.ascontiguousarray(a, dtype=float) for a in (knots, ctrl, u))
    return lekalo.bspline_curve_jvp(degree, knots, ctrl, u)[0]


def hlo(f, *args):
    return jax.jit(f).lower(*args).as_text()


def test_compiled_programs_call_the_ffi_targets_not_a_callback():
    knots, ctrl, u = curve_case()
    f = lambda c, t: bspline_eval(knots, c, t, 3)  # noqa: E731
    loss = lambda c, t: jnp.sum(f(c, t) ** 2)  # noqa: E731
    values = hlo(f, ctrl, u)
    assert "lekalo_bspline_eval" in values and "callback" not in values
    grad = hlo(jax.grad(loss, argnums=(0, 1)), ctrl, u)
    assert "lekalo_bspline_vjp" in grad and "callback" not in grad
    forward = hlo(lambda c, t: jax.jvp(f, (c, t), (c, t))[1], ctrl, u)
    assert "lekalo_bspline_jvp" in forward and "callback" not in forward
    batched = hlo(jax.vmap(jax.grad(loss), in_axes=(0, None)), np.stack([ctrl, ctrl]), u)
    assert "lekalo_bspline_vjp" in batched and "callback" not in batched


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_jacobians_under_jit_and_vmap_match_central_differences(mode):
    knots, ctrl, u = curve_case()
    batch = np.stack([ctrl, -0.5 * ctrl, ctrl[::-1]])
    us = np.stack([u, u[::-1] * 0.97, np.sqrt(u)])
    f = lambda c, t: bspline_eval(knots, c, t, 3)  # noqa: E731
    jac = jax.jit(jax.vmap(getattr(jax, mode)(f, argnums=(0, 1))))
    jc, ju = jac(batch, us)
    for i in range(3):
        fd_c = central(lambda c: reference(knots, c, us[i]), batch[i], 1e-3)
        fd_u = central(lambda t: reference(knots, batch[i], t), us[i], 1e-6)
        assert_rel(jc[i], fd_c, f"{mode} in the control points, element {i}")
        assert_rel(ju[i], fd_u, f"{mode} in u, element {i}")


def test_batched_knots_and_other_batch_axes_reach_the_handlers():
    knots, ctrl, u = curve_case(dim=3)
    # each batch element its own knot vector (a different interior knot), batched on axis 1
    kb = np.stack([knots, knots, knots], axis=1)
    kb[4, 1], kb[5, 2] = 0.25, 0.5
    vals = jax.jit(jax.vmap(lambda k: bspline_eval(k, ctrl, u, 3), in_axes=1))(kb)
    for i in range(3):
        assert np.array_equal(np.asarray(vals[i]), reference(kb[:, i], ctrl, u))
    # the gradient with respect to batched parameters, vmap over axis 1 of u
    ub = np.stack([u, u * 0.5], axis=1)
    loss = lambda t: jnp.sum(bspline_eval(knots, ctrl, t, 3) ** 2)  # noqa: E731
    g = jax.jit(jax.vmap(jax.grad(loss), in_axes=1))(ub)
    for i in range(2):
        fd = central(lambda t: np.sum(reference(knots, ctrl, t) ** 2), ub[:, i], 1e-6)
        assert_rel(g[i], fd, f"grad in u, element {i}")
    # nested vmap: curves x parameter sets, grad in the control points
    cs = np.stack([ctrl, 2 * ctrl])
    per = jax.jit(
        jax.vmap(jax.vmap(jax.grad(lambda c, t: jnp.sum(bspline_eval(knots, c, t, 3) ** 3)),
                          in_axes=(None, 0)), in_axes=(0, None))
    )(cs, ub.T)
    for i in range(2):
        for j in range(2):
            fd = central(lambda c: np.sum(reference(knots, c, ub[:, j]) ** 3), cs[i], 1e-4)
            assert_rel(per[i, j], fd, f"nested vmap grad ({i}, {j})")


def test_empty_and_scalar_inputs():
    knots, ctrl, u = curve_case()
    empty = jax.jit(lambda t: bspline_eval(knots, ctrl, t, 3))(np.zeros(0))
    assert empty.shape == (0, 2)
    g = jax.grad(lambda c: jnp.sum(bspline_eval(knots, c, np.zeros(0), 3)))(ctrl)
    assert np.array_equal(np.asarray(g), np.zeros_like(ctrl))
    # a function (1-D control points) and a scalar parameter
    y = jax.jit(lambda c, t: bspline_eval(knots, c, t, 3))(ctrl[:, 0], np.float64(0.5))
    assert y.shape == () and float(y) == reference(knots, ctrl, [0.5])[0, 0]


def test_a_parameter_outside_the_domain_raises_lekalos_message():
    knots, ctrl, u = curve_case()
    bad = np.array([0.5, 1.25])
    f = jax.jit(lambda c, t: bspline_eval(knots, c, t, 3))
    with pytest.raises(jax.errors.JaxRuntimeError, match=r"1\.25 is outside the domain"):
        f(ctrl, bad).block_until_ready()
    # the derivative targets report it too: forward and reverse mode, batched
    loss = lambda c, t: jnp.sum(bspline_eval(knots, c, t, 3))  # noqa: E731
    with pytest.raises(jax.errors.JaxRuntimeError, match="outside the domain"):
        jax.jit(jax.grad(loss))(ctrl, bad).block_until_ready()
    with pytest.raises(jax.errors.JaxRuntimeError, match="outside the domain"):
        jax.jit(jax.jacfwd(loss, argnums=1))(ctrl, bad).block_until_ready()
    with pytest.raises(jax.errors.JaxRuntimeError, match="outside the domain"):
        jax.jit(jax.vmap(f, in_axes=(None, 0)))(ctrl, np.stack([u[:2], bad])).block_until_ready()
    with pytest.raises(jax.errors.JaxRuntimeError, match="lekalo.jax.bspline_eval"):
        f(ctrl, np.array([np.nan])).block_until_ready()
    # the process lives on, and the next call works
    assert np.array_equal(np.asarray(f(ctrl, u)), reference(knots, ctrl, u))


def test_invalid_knots_raise_lekalos_message():
    knots, ctrl, u = curve_case()
    decreasing = knots.copy()
    decreasing[5] = 0.1  # below knots[4]
    with pytest.raises(jax.errors.JaxRuntimeError, match="lekalo.jax.bspline_eval"):
        jax.jit(lambda k: bspline_eval(k, ctrl, u, 3))(decreasing).block_until_ready()
