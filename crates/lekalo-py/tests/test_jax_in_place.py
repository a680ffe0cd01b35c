"""lekalo.jax.bspline_eval and nurbs_eval for a few parameters on a long curve, where the FFI
targets evaluate in place on the operand buffers and check only the knots, control points (and
weights) the parameters' spans read (``lekalo::derivatives::BorrowedCurve``,
``BorrowedNurbs``): the values are bit-for-bit lekalo's, the
derivatives match central differences (relative 1e-7) eagerly, under jit and under vmap, and
a bad number inside a span used, or a parameter outside the domain, gives lekalo's message as
the whole-curve path does, never a value."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import RUNTIME_ERRORS, assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import bspline_eval, nurbs_eval  # noqa: E402

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


def nurbs_reference(knots, ctrl, w, u):
    u = np.ascontiguousarray(u, dtype=float)
    return lekalo.nurbs_curve_jvp(3, knots, np.ascontiguousarray(ctrl), np.ascontiguousarray(w), u)[0]


@pytest.mark.parametrize("where", ["eager", "jit", "vmap"])
def test_nurbs_small_calls_match_the_built_curve(where):
    """A few parameters on a long NURBS curve: in place (``BorrowedNurbs``), the values bit for
    bit the built curve's, the Jacobians in the control points, weights and ``u`` against
    central differences."""
    knots, ctrl, u = long_case()
    w = np.random.default_rng(3).uniform(0.5, 2.0, N)
    f = lambda c, ws, t: nurbs_eval(knots, c, ws, t, 3)  # noqa: E731
    for t in (u, np.r_[knots[14]], np.r_[0.0, 1.0]):
        if where == "vmap":
            got = jax.jit(jax.vmap(f))(np.stack([ctrl, -ctrl]), np.stack([w, 2 * w]), np.stack([t, t]))
            assert np.array_equal(np.asarray(got[1]), nurbs_reference(knots, -ctrl, 2 * w, t))
            got = got[0]
        else:
            got = (jax.jit(f) if where == "jit" else f)(ctrl, w, t)
        assert np.array_equal(np.asarray(got), nurbs_reference(knots, ctrl, w, t))
    for mode in ("jacfwd", "jacrev"):
        jac = getattr(jax, mode)(f, argnums=(0, 1, 2))
        if where == "vmap":
            jc, jw, ju = jax.jit(jax.vmap(jac))(np.stack([ctrl, 2 * ctrl]), np.stack([w, w]), np.stack([u, u]))
            jc, jw, ju = jc[1], jw[1], ju[1]
            c = 2 * ctrl
        else:
            jc, jw, ju = (jax.jit(jac) if where == "jit" else jac)(ctrl, w, u)
            c = ctrl
        ref = lambda a, b, t: nurbs_reference(knots, a, b, t)  # noqa: E731
        assert_rel(jc, central(lambda a: ref(a, w, u), c, 1e-3), f"{mode} in the control points")
        assert_rel(jw, central(lambda b: ref(c, b, u), w, 1e-4), f"{mode} in the weights")
        assert_rel(ju, central(lambda t: ref(c, w, t), u, 1e-6), f"{mode} in u")
    # the gradient touches the k + 1 weights of each parameter's span only
    g = jax.grad(lambda ws: jnp.sum(f(ctrl, ws, u[1:])))(w)
    assert np.count_nonzero(np.asarray(g)) == 4


def test_nurbs_bad_numbers_in_a_span_used_give_lekalos_message():
    knots, ctrl, u = long_case()
    w = np.ones(N)
    f = jax.jit(lambda c, ws, t: nurbs_eval(knots, c, ws, t, 3))
    grad = jax.jit(jax.grad(lambda c, ws, t: jnp.sum(nurbs_eval(knots, c, ws, t, 3)), argnums=(0, 1, 2)))
    span = int(np.searchsorted(knots, u[1], side="right")) - 1
    for bad, message in ((0.0, "weights must be positive"), (np.nan, "must be finite")):
        ws = w.copy()
        ws[span - 1] = bad
        for call in (f, grad):
            with pytest.raises(RUNTIME_ERRORS, match=message):
                jax.block_until_ready(call(ctrl, ws, u[1:]))
    with pytest.raises(RUNTIME_ERRORS, match=r"1\.5 is outside the domain"):
        jax.block_until_ready(f(ctrl, w, np.array([1.5])))
    # a bad weight far from the parameters is not read: the values are the curve's
    far = w.copy()
    far[-1] = -1.0
    assert np.array_equal(np.asarray(f(ctrl, far, u)), nurbs_reference(knots, ctrl, w, u))
    many = np.linspace(0.0, 1.0, 4 * N)
    with pytest.raises(RUNTIME_ERRORS, match="weights must be positive"):
        jax.block_until_ready(nurbs_eval(knots, ctrl, far, many, 3))
