"""lekalo.jax.bspline_eval for a few parameters on a long curve, where the FFI targets evaluate
in place on the operand buffers and check only the knots and control points the parameters'
spans read (``lekalo::derivatives::BorrowedCurve``): the values are bit-for-bit lekalo's, the
derivatives match central differences (relative 1e-7) eagerly, under jit and under vmap, and
a bad number inside a span used, or a parameter outside the domain, gives lekalo's message as
the whole-curve path does, never a value."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import RUNTIME_ERRORS, assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import bspline_eval  # noqa: E402

N = 120  # control points: one or two parameters are far below (degree + 1) per piece


def long_case(dim=2, seed=17):
    rng = np.random.default_rng(seed)
    inner = np.linspace(0, 1, N - 2)[1:-1] + rng.uniform(-0.002, 0.002, N - 4)
    inner[10:12] = inner[10]  # a double knot
    knots = np.r_[[0.0] * 4, inner, [1.0] * 4]
    ctrl = rng.uniform(-1, 1, (N, dim))
    u = np.array([0.5 * (inner[70] + inner[71]), 0.5 * (inner[40] + inner[41])])
    return knots, ctrl, u


def reference(knots, ctrl, u):
    u = np.ascontiguousarray(u, dtype=float)
    return lekalo.bspline_curve_jvp(3, knots, np.ascontiguousarray(ctrl), u)[0]


@pytest.mark.parametrize("where", ["eager", "jit", "vmap"])
def test_values_and_jacobians_of_a_small_call(where):
    knots, ctrl, u = long_case()
    f = lambda c, t: bspline_eval(knots, c, t, 3)  # noqa: E731
    # off the knots, on the double knot, at the ends
    for t in (u, np.r_[knots[14]], np.r_[0.0, 1.0]):
        if where == "vmap":
            got = jax.jit(jax.vmap(f))(np.stack([ctrl, -ctrl]), np.stack([t, t]))
            assert np.array_equal(np.asarray(got[1]), reference(knots, -ctrl, t))
            got = got[0]
        else:
            got = (jax.jit(f) if where == "jit" else f)(ctrl, t)
        assert np.array_equal(np.asarray(got), reference(knots, ctrl, t))
    for mode in ("jacfwd", "jacrev"):
        jac = getattr(jax, mode)(f, argnums=(0, 1))
        if where == "vmap":
            jc, ju = jax.jit(jax.vmap(jac))(np.stack([ctrl, 2 * ctrl]), np.stack([u, u]))
            jc, ju = jc[1], ju[1]
            c = 2 * ctrl
        else:
            jc, ju = (jax.jit(jac) if where == "jit" else jac)(ctrl, u)
            c = ctrl
        assert_rel(jc, central(lambda a: reference(knots, a, u), c, 1e-3), f"{mode} in the control points")
        assert_rel(ju, central(lambda t: reference(knots, c, t), u, 1e-6), f"{mode} in u")
    # the gradient touches the k + 1 control points of each parameter's span only
    g = jax.grad(lambda c: jnp.sum(f(c, u[1:])))(ctrl)
    assert np.count_nonzero(np.asarray(g[:, 0])) == 4


def test_a_bad_number_in_a_span_used_gives_lekalos_message():
    knots, ctrl, u = long_case()
    f = jax.jit(lambda k, c, t: bspline_eval(k, c, t, 3))
    loss = lambda k, c, t: jnp.sum(bspline_eval(k, c, t, 3))  # noqa: E731
    grad = jax.jit(jax.grad(loss, argnums=(1, 2)))
    fwd = jax.jit(jax.jacfwd(loss, argnums=2))
    span = int(np.searchsorted(knots, u[1], side="right")) - 1
    nan_knot = knots.copy()
    nan_knot[span] = np.nan
    unsorted = knots.copy()
    unsorted[span + 1] = knots[span - 1]
    nan_ctrl = ctrl.copy()
    nan_ctrl[span - 1, 1] = np.inf
    cases = (
        (nan_knot, ctrl, "must be finite"),
        (unsorted, ctrl, "sorted|non-decreasing"),
        (knots, nan_ctrl, "must be finite"),
    )
    for k, c, message in cases:
        for call in (f, grad, fwd):
            with pytest.raises(RUNTIME_ERRORS, match=message):
                jax.block_until_ready(call(k, c, u[1:]))
    for call in (f, grad, fwd):
        with pytest.raises(RUNTIME_ERRORS, match=r"1\.5 is outside the domain"):
            jax.block_until_ready(call(knots, ctrl, np.array([1.5])))
        with pytest.raises(RUNTIME_ERRORS, match="lekalo.jax.bspline_eval"):
            jax.block_until_ready(call(knots, ctrl, np.array([np.nan])))
    # under vmap, one bad batch element fails the call
    bad = jax.jit(jax.vmap(lambda c: bspline_eval(knots, c, u, 3)))
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        jax.block_until_ready(bad(np.stack([ctrl, nan_ctrl])))
    # the process lives on, and the next call works
    assert np.array_equal(np.asarray(f(knots, ctrl, u)), reference(knots, ctrl, u))


def test_a_bad_number_outside_the_spans_used_leaves_the_values_exact():
    """Only the spans' numbers define the values: a NaN control point far from the parameters
    does not change them (the whole-curve path, for a large batch, refuses it)."""
    knots, ctrl, u = long_case()
    far = ctrl.copy()
    far[-1] = np.nan
    got = jax.jit(lambda c, t: bspline_eval(knots, c, t, 3))(far, u)
    assert np.array_equal(np.asarray(got), reference(knots, ctrl, u))
    many = np.linspace(0.0, 1.0, 4 * N)
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        jax.block_until_ready(bspline_eval(knots, far, many, 3))
