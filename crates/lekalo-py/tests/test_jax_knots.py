"""Derivatives with respect to the knots, from NumPy (``lekalo.bspline_curve_knot_jvp`` /
``_vjp``, ``lekalo.bspline_surface_knot_jvp`` / ``_vjp``) and from JAX (``bspline_eval`` and
``bspline_surface_eval`` under ``jax.grad``, ``jacfwd``, ``jacrev``, ``jit`` and ``vmap``):
against central differences of the evaluation in the interior knots (relative 1e-7), the JAX
Jacobians against the library's kernels, the end knots held fixed (zero gradient). The
mathematics (multiple knots, parameters on knots, the adjoint identity) is tested in the core,
``crates/lekalo/src/derivatives/knots_tests.rs``."""

import numpy as np
import pytest

import lekalo

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

from jax_support import assert_rel, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import bspline_eval, bspline_surface_eval, nurbs_eval  # noqa: E402

P = 3


def curve_case(dim=2):
    rng = np.random.default_rng(5)
    knots = np.array([0, 0, 0, 0, 0.3, 0.55, 0.7, 1, 1, 1, 1.0])
    ctrl = rng.uniform(-1, 1, (7, dim))
    u = np.array([0.05, 0.2, 0.41, 0.5, 0.62, 0.8, 0.93])  # off the knots
    return knots, ctrl, u


def surface_case():
    rng = np.random.default_rng(13)
    ku = np.array([0, 0, 0, 0.4, 0.65, 1, 1, 1.0])
    kv = np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net = rng.uniform(-1, 1, (5, 5, 3))
    u = np.array([0.1, 0.3, 0.5, 0.85])
    v = np.array([0.2, 0.45, 0.7, 0.1])
    return ku, kv, net, u, v


def interior(knots, degree):
    """The mask of the interior knots (the derivative's; the ends are held fixed)."""
    m = np.zeros(len(knots), bool)
    m[degree + 1 : len(knots) - degree - 1] = True
    return m


def knot_central(f, knots, degree, h=1e-6):
    """The Jacobian of ``f(knots)`` in the knots by central differences in the interior knots,
    zero columns for the end knots; shape ``f(knots).shape + knots.shape``."""
    cols = []
    mask = interior(knots, degree)
    base = np.asarray(f(knots))
    for k in range(len(knots)):
        if not mask[k]:
            cols.append(np.zeros_like(base))
            continue
        up, down = knots.copy(), knots.copy()
        up[k] += h
        down[k] -= h
        cols.append((np.asarray(f(up)) - np.asarray(f(down))) / (2 * h))
    return np.stack(cols, axis=-1)


def curve_values(knots, ctrl, u):
    return lekalo.bspline_curve_jvp(P, knots, ctrl, u)[0]


# -- the NumPy kernels -----------------------------------------------------------------------


def test_curve_knot_kernels_match_central_differences_and_each_other():
    knots, ctrl, u = curve_case()
    jac = knot_central(lambda k: curve_values(k, ctrl, u), knots, P)  # (7, 2, 11)
    rng = np.random.default_rng(1)
    dk = rng.uniform(-1, 1, knots.shape)
    values, tangent = lekalo.bspline_curve_knot_jvp(P, knots, ctrl, u, dk)
    assert np.array_equal(values, curve_values(knots, ctrl, u))
    assert_rel(tangent, jac @ dk, "knot JVP")
    g = rng.uniform(-1, 1, values.shape)
    gk = lekalo.bspline_curve_knot_vjp(P, knots, ctrl, u, g)
    assert gk.shape == knots.shape
    assert np.all(gk[~interior(knots, P)] == 0.0)
    assert_rel(gk, np.einsum("md,mdk->k", g, jac), "knot VJP")
    # the adjoint identity
    assert abs(np.sum(tangent * g) - gk @ dk) <= 1e-12 * np.sum(np.abs(tangent * g))


def test_surface_knot_kernels_match_central_differences():
    ku, kv, net, u, v = surface_case()

    def values(a, b):
        return lekalo.bspline_surface_jvp(2, 3, a, b, net, u, v)[0]

    ju = knot_central(lambda k: values(k, kv), ku, 2)
    jv = knot_central(lambda k: values(ku, k), kv, 3)
    rng = np.random.default_rng(2)
    du, dv = rng.uniform(-1, 1, ku.shape), rng.uniform(-1, 1, kv.shape)
    vals, tan = lekalo.bspline_surface_knot_jvp(2, 3, ku, kv, net, u, v, du, dv)
    assert np.array_equal(vals, values(ku, kv))
    assert_rel(tan, ju @ du + jv @ dv, "surface knot JVP")
    _, tan_u = lekalo.bspline_surface_knot_jvp(2, 3, ku, kv, net, u, v, knots_u_tangent=du)
    assert_rel(tan_u, ju @ du, "surface knot JVP along u")
    g = rng.uniform(-1, 1, vals.shape)
    gu, gv = lekalo.bspline_surface_knot_vjp(2, 3, ku, kv, net, u, v, g)
    assert_rel(gu, np.einsum("md,mdk->k", g, ju), "surface knot VJP along u")
    assert_rel(gv, np.einsum("md,mdk->k", g, jv), "surface knot VJP along v")


def test_knot_kernels_refuse_bad_shapes():
    knots, ctrl, u = curve_case()
    with pytest.raises(lekalo.InputError, match="knots_tangent"):
        lekalo.bspline_curve_knot_jvp(P, knots, ctrl, u, np.zeros(len(knots) - 1))
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.bspline_curve_knot_vjp(P, knots, ctrl, u, np.zeros((len(u), 3)))
    ku, kv, net, su, sv = surface_case()
    with pytest.raises(lekalo.InputError, match="knots_v_tangent"):
        lekalo.bspline_surface_knot_jvp(2, 3, ku, kv, net, su, sv, None, np.zeros(3))


# -- JAX ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
def test_curve_knot_jacobians(mode, jit):
    knots, ctrl, u = curve_case()
    f = getattr(jax, mode)(lambda k: bspline_eval(k, ctrl, u, P))
    jac = np.asarray(jax.jit(f)(knots) if jit else f(knots))
    want = knot_central(lambda k: curve_values(k, ctrl, u), knots, P)
    assert_rel(jac, want, f"{mode} in the knots")
    # all three arguments at once
    jk, jc, ju = getattr(jax, mode)(lambda k, c, t: bspline_eval(k, c, t, P), argnums=(0, 1, 2))(
        knots, ctrl, u
    )
    assert_rel(jk, want, f"{mode} in the knots, with the others")
    assert jc.shape == (7, 2, 7, 2) and ju.shape == (7, 2, 7)
    plain = lambda c: curve_values(knots, c, u)  # noqa: E731
    assert_rel(jc[:, :, 3, 1], np.asarray(plain(ctrl + np.eye(7)[3][:, None] * np.array([0, 1.0])) - plain(ctrl)), "control")


def test_curve_knot_grad_jvp_vjp_are_the_kernels():
    knots, ctrl, u = curve_case()
    rng = np.random.default_rng(3)
    target = rng.uniform(-1, 1, (len(u), 2))

    def loss(k):
        return jnp.sum((bspline_eval(k, ctrl, u, P) - target) ** 2)

    g = jax.grad(loss)(knots)
    resid = curve_values(knots, ctrl, u) - target
    assert_rel(g, lekalo.bspline_curve_knot_vjp(P, knots, ctrl, u, 2 * resid), "grad")
    assert_rel(jax.jit(jax.grad(loss))(knots), g, "grad under jit")
    dk = rng.uniform(-1, 1, knots.shape)
    _, tan = jax.jvp(lambda k: bspline_eval(k, ctrl, u, P), (knots,), (dk,))
    assert_rel(tan, lekalo.bspline_curve_knot_jvp(P, knots, ctrl, u, dk)[1], "jvp")
    # a 1-D curve (a function) and u of any shape
    y = jax.grad(lambda k: jnp.sum(bspline_eval(k, ctrl[:, 0], u.reshape(7, 1), P)))(knots)
    assert_rel(y, lekalo.bspline_curve_knot_vjp(P, knots, ctrl[:, :1], u, np.ones((7, 1))), "1-D")


def test_curve_knot_derivatives_under_vmap():
    knots, ctrl, u = curve_case()
    shifts = np.array([[0.0, 0.0, 0.0], [0.02, -0.03, 0.05], [-0.04, 0.02, 0.01]])
    batch = np.stack([knots] * 3)
    batch[:, 4:7] += shifts
    f = lambda k: jnp.sum(bspline_eval(k, ctrl, u, P) ** 2)  # noqa: E731
    for mode, got in (
        ("grad", jax.vmap(jax.grad(f))(batch)),
        ("jit(vmap(jacrev))", jax.jit(jax.vmap(jax.jacrev(f)))(batch)),
        ("vmap(jacfwd)", jax.vmap(jax.jacfwd(f))(batch)),
    ):
        for i in range(3):
            want = knot_central(lambda k: np.sum(curve_values(k, ctrl, u) ** 2), batch[i], P)
            assert_rel(got[i], want, f"{mode}, element {i}")
    # knots shared, control points batched
    cs = np.stack([ctrl, 2 * ctrl])
    g = jax.vmap(jax.grad(lambda k, c: jnp.sum(bspline_eval(k, c, u, P))), in_axes=(None, 0))(knots, cs)
    for i in range(2):
        want = lekalo.bspline_curve_knot_vjp(P, knots, cs[i], u, np.ones((len(u), 2)))
        assert_rel(g[i], want, f"shared knots, element {i}")


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_surface_knot_jacobians(mode):
    ku, kv, net, u, v = surface_case()

    def values(a, b):
        return lekalo.bspline_surface_jvp(2, 3, a, b, net, u, v)[0]

    jac = getattr(jax, mode)(lambda a, b: bspline_surface_eval(a, b, net, u, v, 2, 3), argnums=(0, 1))
    for jit in (False, True):
        ju, jv = jax.jit(jac)(ku, kv) if jit else jac(ku, kv)
        assert_rel(ju, knot_central(lambda k: values(k, kv), ku, 2), f"{mode} in knots_u")
        assert_rel(jv, knot_central(lambda k: values(ku, k), kv, 3), f"{mode} in knots_v")
    # vmap over the u knots
    kus = np.stack([ku, ku + np.r_[0, 0, 0, 0.03, -0.02, 0, 0, 0]])
    g = jax.vmap(jax.grad(lambda a: jnp.sum(bspline_surface_eval(a, kv, net, u, v, 2, 3))))(kus)
    for i in range(2):
        ones = np.ones((len(u), 3))
        assert_rel(g[i], lekalo.bspline_surface_knot_vjp(2, 3, kus[i], kv, net, u, v, ones)[0], "vmap")


def test_knots_of_the_other_evaluations_are_still_constants():
    knots, ctrl, u = curve_case()
    w = np.ones(len(ctrl))
    with pytest.raises(NotImplementedError, match="knots"):
        jax.grad(lambda k: jnp.sum(nurbs_eval(k, ctrl, w, u, P)))(knots)
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda k: jnp.sum(bspline_eval(k, ctrl, u, P)))(knots)
