"""lekalo.jax.nurbs_surface_eval and tensor_nurbs_eval, and the NumPy kernels beneath them
(lekalo.nurbs_surface_jvp / _vjp, lekalo.tensor_nurbs_jvp / _vjp): values bit-for-bit
lekalo's, Jacobians in every argument (net, weights, parameters, knots) from jacfwd and jacrev
against central finite differences (relative 1e-7) eagerly, under jit and under vmap, grad,
jax.jvp / jax.vjp against the kernels, the VJP kernels as the JVP kernels' transposes, and the
errors. The derivative mathematics is tested in the core (crates/lekalo/src/derivatives/)."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import RUNTIME_ERRORS, assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import nurbs_surface_eval, tensor_nurbs_eval  # noqa: E402


def interior_central(f, knots, degree, h=1e-6):
    """The Jacobian of ``f(knots)`` by central differences in the interior knots, zero columns
    for the ``degree + 1`` first and last (held fixed)."""
    base = np.asarray(f(knots))
    cols = []
    for k in range(len(knots)):
        if k < degree + 1 or k >= len(knots) - degree - 1:
            cols.append(np.zeros_like(base))
            continue
        up, down = knots.copy(), knots.copy()
        up[k] += h
        down[k] -= h
        cols.append((np.asarray(f(up)) - np.asarray(f(down))) / (2 * h))
    return np.stack(cols, axis=-1)


# -- NURBS surfaces ------------------------------------------------------------------------------

P, Q = 2, 3


def surface_case():
    rng = np.random.default_rng(23)
    ku = np.array([0, 0, 0, 0.4, 1, 1, 1.0])
    kv = np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net = rng.uniform(-1, 1, (4, 5, 3))
    w = rng.uniform(0.4, 2.5, (4, 5))
    u = np.array([0.1, 0.3, 0.6, 0.85])
    v = np.array([0.2, 0.45, 0.7, 0.1])  # (u, v) off the knots
    return ku, kv, net, w, u, v


def surface_values(ku, kv, net, w, u, v):
    return lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v)[0]


def test_surface_values_are_lekalos_bit_for_bit():
    ku, kv, net, w, u, v = surface_case()
    ref = surface_values(ku, kv, net, w, u, v)
    assert np.array_equal(ref, lekalo.NurbsSurface(P, Q, ku, kv, net, w)(u, v))
    assert np.array_equal(np.asarray(nurbs_surface_eval(ku, kv, net, w, u, v, P, Q)), ref)
    jitted = jax.jit(nurbs_surface_eval, static_argnums=(6, 7))
    assert np.array_equal(np.asarray(jitted(ku, kv, net, w, u, v, P, Q)), ref)
    assert nurbs_surface_eval(ku, kv, net, w, u.reshape(2, 2), v.reshape(2, 2), P, Q).shape == (2, 2, 3)


def test_surface_kernels_vjp_is_the_transpose_of_the_jvp():
    ku, kv, net, w, u, v = surface_case()
    rng = np.random.default_rng(3)
    dn, dw, du, dv = rng.normal(size=net.shape), rng.normal(size=w.shape), rng.normal(size=4), rng.normal(size=4)
    vals, tan = lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v, dn, dw, du, dv)
    g = rng.normal(size=vals.shape)
    gn, gw, gu, gv = lekalo.nurbs_surface_vjp(P, Q, ku, kv, net, w, u, v, g)
    assert gn.shape == net.shape and gw.shape == w.shape and gu.shape == u.shape
    lhs = np.sum(g * tan)
    rhs = np.sum(gn * dn) + np.sum(gw * dw) + np.sum(gu * du) + np.sum(gv * dv)
    assert abs(lhs - rhs) <= 1e-13 * max(1.0, abs(lhs)) * g.size
    # each tangent against central differences
    assert_rel(lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v, weights_tangent=dw)[1],
               central(lambda x: surface_values(ku, kv, net, x, u, v), w, 1e-6).reshape(vals.shape + (-1,)) @ dw.ravel(),
               "weight JVP")


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
def test_surface_jacobians_match_central_differences(mode, jit):
    ku, kv, net, w, u, v = surface_case()
    f = lambda a, b, c, ws, x, y: nurbs_surface_eval(a, b, c, ws, x, y, P, Q)  # noqa: E731
    jac = getattr(jax, mode)(f, argnums=(0, 1, 2, 3, 4, 5))
    jac = jax.jit(jac) if jit else jac
    jku, jkv, jn, jw, ju, jv = jac(ku, kv, net, w, u, v)
    plain = surface_values
    assert_rel(jn, central(lambda c: plain(ku, kv, c, w, u, v), net, 1e-3), f"{mode} in the net")
    assert_rel(jw, central(lambda ws: plain(ku, kv, net, ws, u, v), w, 1e-6), f"{mode} in the weights")
    assert_rel(ju, central(lambda x: plain(ku, kv, net, w, x, v), u, 1e-6), f"{mode} in u")
    assert_rel(jv, central(lambda y: plain(ku, kv, net, w, u, y), v, 1e-6), f"{mode} in v")
    assert_rel(jku, interior_central(lambda k: plain(k, kv, net, w, u, v), ku, P), f"{mode} in knots_u")
    assert_rel(jkv, interior_central(lambda k: plain(ku, k, net, w, u, v), kv, Q), f"{mode} in knots_v")


def test_surface_grad_jvp_vjp_and_vmap():
    ku, kv, net, w, u, v = surface_case()
    f = lambda c, ws, x, y: nurbs_surface_eval(ku, kv, c, ws, x, y, P, Q)  # noqa: E731
    loss = lambda c, ws, x, y: jnp.sum(f(c, ws, x, y) ** 2)  # noqa: E731
    grads = jax.jit(jax.grad(loss, argnums=(0, 1, 2, 3)))(net, w, u, v)
    loss_np = lambda c, ws, x, y: float(np.sum(surface_values(ku, kv, c, ws, x, y) ** 2))  # noqa: E731
    args = [net, w, u, v]
    for i, (g, h) in enumerate(zip(grads, (1e-5, 1e-6, 1e-6, 1e-6))):
        def one(x, i=i):
            return loss_np(*(x if j == i else a for j, a in enumerate(args)))

        assert_rel(g, central(one, args[i], h), f"grad in argument {i}")
    # jax.jvp and jax.vjp are the kernels
    rng = np.random.default_rng(5)
    tangents = tuple(rng.normal(size=np.shape(a)) for a in args)
    _, tan = jax.jvp(f, tuple(args), tangents)
    assert_rel(tan, lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v, *tangents)[1], "jvp")
    g = rng.normal(size=(4, 3))
    _, pullback = jax.vjp(f, *args)
    for a, b in zip(pullback(g), lekalo.nurbs_surface_vjp(P, Q, ku, kv, net, w, u, v, g)):
        assert_rel(a, b, "vjp")
    # vmap over weight sets and nets: values and per-element gradients
    ws = np.stack([w, w[::-1], 1.0 + 0 * w])
    nets = np.stack([net, -net, 0.5 * net])
    vals = jax.jit(jax.vmap(lambda c, x: f(c, x, u, v)))(nets, ws)
    per = jax.jit(jax.vmap(jax.grad(lambda c, x: loss(c, x, u, v), argnums=(0, 1))))(nets, ws)
    for i in range(3):
        assert np.array_equal(np.asarray(vals[i]), surface_values(ku, kv, nets[i], ws[i], u, v))
        fw = central(lambda x: loss_np(nets[i], x, u, v), ws[i], 1e-6)
        fn = central(lambda c: loss_np(c, ws[i], u, v), nets[i], 1e-5)
        assert_rel(per[1][i], fw, "vmap(grad) in the weights")
        assert_rel(per[0][i], fn, "vmap(grad) in the net")
    # the parameters batched, forward mode, and the knots under vmap
    us = np.stack([u, 0.9 * u])
    ju = jax.jit(jax.vmap(jax.jacfwd(lambda x: f(net, w, x, v))))(us)
    for i in range(2):
        assert_rel(ju[i], central(lambda x: surface_values(ku, kv, net, w, x, v), us[i], 1e-6), "vmap(jacfwd) in u")
    kus = np.stack([ku, np.array([0, 0, 0, 0.55, 1, 1, 1.0])])
    gk = jax.vmap(jax.grad(lambda k: jnp.sum(nurbs_surface_eval(k, kv, net, w, u, v, P, Q))))(kus)
    for i in range(2):
        fd = interior_central(lambda k: np.sum(surface_values(k, kv, net, w, u, v)), kus[i], P)
        assert_rel(gk[i], fd, "vmap(grad) in knots_u")


def test_surface_errors_name_the_argument():
    ku, kv, net, w, u, v = surface_case()
    with pytest.raises(lekalo.InputError, match="weights"):
        nurbs_surface_eval(ku, kv, net, w[:3], u, v, P, Q)
    with pytest.raises(lekalo.InputError, match="knots_v"):
        nurbs_surface_eval(ku, kv[:-1], net, w, u, v, P, Q)
    with pytest.raises(lekalo.InputError, match="one shape"):
        nurbs_surface_eval(ku, kv, net, w, u, v[:2], P, Q)
    with pytest.raises(RUNTIME_ERRORS, match="domain"):
        nurbs_surface_eval(ku, kv, net, w, u + 1.0, v, P, Q).block_until_ready()
    bad = w.copy()
    bad[1, 1] = -1.0
    with pytest.raises(RUNTIME_ERRORS, match="eight|weight"):
        nurbs_surface_eval(ku, kv, net, bad, u, v, P, Q).block_until_ready()
    with pytest.raises(lekalo.InputError, match="weights_tangent"):
        lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v, weights_tangent=np.zeros(3))
    with pytest.raises(lekalo.InputError, match="(?i)finite"):
        lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v, weights_tangent=np.full(w.shape, np.nan))
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.nurbs_surface_vjp(P, Q, ku, kv, net, w, u, v, np.zeros((4, 2)))
    with pytest.raises(lekalo.InputError, match="domain"):
        lekalo.nurbs_surface_vjp(P, Q, ku, kv, net, w, u - 1.0, v, np.zeros((4, 3)))


# -- tensor-product NURBS in N variables -------------------------------------------------------

DEGREES = (2, 1, 3)


def tensor_case(dim=2):
    rng = np.random.default_rng(29)
    knots = (
        np.array([0, 0, 0, 0.35, 0.6, 1, 1, 1.0]),
        np.array([0, 0, 0.4, 1, 1.0]),
        np.array([0, 0, 0, 0, 0.55, 1, 1, 1, 1.0]),
    )
    net = rng.uniform(-1, 1, (5, 3, 5, dim))
    w = rng.uniform(0.4, 2.5, (5, 3, 5))
    x = np.array([[0.1, 0.2, 0.3], [0.5, 0.7, 0.8], [0.9, 0.05, 0.45], [0.3, 0.55, 0.62]])
    return knots, net, w, x  # x off the knots


def tensor_values(knots, net, w, x):
    return lekalo.tensor_nurbs_jvp(list(knots), net, list(DEGREES), w, x)[0]


def test_tensor_values_are_lekalos_bit_for_bit():
    knots, net, w, x = tensor_case()
    ref = tensor_values(knots, net, w, x)
    assert np.array_equal(ref, lekalo.TensorNurbs(list(knots), net, list(DEGREES), w)(x))
    assert np.array_equal(np.asarray(tensor_nurbs_eval(knots, net, w, x, DEGREES)), ref)
    jitted = jax.jit(tensor_nurbs_eval, static_argnums=4)
    assert np.array_equal(np.asarray(jitted(knots, net, w, x, DEGREES)), ref)
    # a scalar function, and points of any leading shape
    y = tensor_nurbs_eval(knots, net[..., 0], w, x.reshape(2, 2, 3), DEGREES)
    assert y.shape == (2, 2)
    assert np.array_equal(np.asarray(y).ravel(), ref[:, 0])


def test_tensor_kernels_vjp_is_the_transpose_of_the_jvp():
    knots, net, w, x = tensor_case()
    rng = np.random.default_rng(31)
    dn, dw, dx = rng.normal(size=net.shape), rng.normal(size=w.shape), rng.normal(size=x.shape)
    vals, tan = lekalo.tensor_nurbs_jvp(list(knots), net, list(DEGREES), w, x, dn, dw, dx)
    g = rng.normal(size=vals.shape)
    gn, gw, gx = lekalo.tensor_nurbs_vjp(list(knots), net, list(DEGREES), w, x, g)
    assert (gn.shape, gw.shape, gx.shape) == (net.shape, w.shape, x.shape)
    lhs = np.sum(g * tan)
    rhs = np.sum(gn * dn) + np.sum(gw * dw) + np.sum(gx * dx)
    assert abs(lhs - rhs) <= 1e-13 * max(1.0, abs(lhs)) * g.size


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
def test_tensor_jacobians_match_central_differences(mode, jit):
    knots, net, w, x = tensor_case()

    def f(k0, k1, k2, c, ws, p):
        return tensor_nurbs_eval((k0, k1, k2), c, ws, p, DEGREES)

    jac = getattr(jax, mode)(f, argnums=(0, 1, 2, 3, 4, 5))
    jac = jax.jit(jac) if jit else jac
    *jk, jn, jw, jx = jac(*knots, net, w, x)
    assert_rel(jn, central(lambda c: tensor_values(knots, c, w, x), net, 1e-3), f"{mode} in the net")
    assert_rel(jw, central(lambda ws: tensor_values(knots, net, ws, x), w, 1e-6), f"{mode} in the weights")
    assert_rel(jx, central(lambda p: tensor_values(knots, net, w, p), x, 1e-6), f"{mode} in x")
    for a in range(3):
        def one(k, a=a):
            return tensor_values(knots[:a] + (k,) + knots[a + 1 :], net, w, x)

        assert_rel(jk[a], interior_central(one, knots[a], DEGREES[a]), f"{mode} in knots[{a}]")


def test_tensor_grad_jvp_vjp_and_vmap():
    knots, net, w, x = tensor_case()
    f = lambda c, ws, p: tensor_nurbs_eval(knots, c, ws, p, DEGREES)  # noqa: E731
    loss = lambda c, ws, p: jnp.sum(f(c, ws, p) ** 2)  # noqa: E731
    loss_np = lambda c, ws, p: float(np.sum(tensor_values(knots, c, ws, p) ** 2))  # noqa: E731
    gn, gw, gx = jax.jit(jax.grad(loss, argnums=(0, 1, 2)))(net, w, x)
    assert_rel(gn, central(lambda c: loss_np(c, w, x), net, 1e-5), "grad in the net")
    assert_rel(gw, central(lambda ws: loss_np(net, ws, x), w, 1e-6), "grad in the weights")
    assert_rel(gx, central(lambda p: loss_np(net, w, p), x, 1e-6), "grad in x")
    rng = np.random.default_rng(37)
    tangents = (rng.normal(size=net.shape), rng.normal(size=w.shape), rng.normal(size=x.shape))
    _, tan = jax.jvp(f, (net, w, x), tangents)
    assert_rel(tan, lekalo.tensor_nurbs_jvp(list(knots), net, list(DEGREES), w, x, *tangents)[1], "jvp")
    g = rng.normal(size=(x.shape[0], 2))
    _, pullback = jax.vjp(f, net, w, x)
    for a, b in zip(pullback(g), lekalo.tensor_nurbs_vjp(list(knots), net, list(DEGREES), w, x, g)):
        assert_rel(a, b, "vjp")
    # vmap over weight sets: values, grad in the weights, and jacfwd in the points
    ws = np.stack([w, w[::-1], 1.0 + 0 * w])
    vals = jax.jit(jax.vmap(lambda s: f(net, s, x)))(ws)
    per = jax.jit(jax.vmap(jax.grad(lambda s: loss(net, s, x))))(ws)
    jx = jax.jit(jax.vmap(jax.jacfwd(lambda s, p: f(net, s, p), argnums=1), in_axes=(0, None)))(ws, x)
    for i in range(3):
        assert np.array_equal(np.asarray(vals[i]), tensor_values(knots, net, ws[i], x))
        assert_rel(per[i], central(lambda s: loss_np(net, s, x), ws[i], 1e-6), "vmap(grad) in the weights")
        assert_rel(jx[i], central(lambda p: tensor_values(knots, net, ws[i], p), x, 1e-6), "vmap(jacfwd) in x")


def test_tensor_errors_name_the_argument():
    knots, net, w, x = tensor_case()
    with pytest.raises(lekalo.InputError, match="weights"):
        tensor_nurbs_eval(knots, net, w[:2], x, DEGREES)
    with pytest.raises(lekalo.InputError, match="knots"):
        tensor_nurbs_eval(knots[:2], net, w, x, DEGREES)
    with pytest.raises(lekalo.InputError, match=r"\(\.\.\., 3\)"):
        tensor_nurbs_eval(knots, net, w, x[:, :2], DEGREES)
    with pytest.raises(RUNTIME_ERRORS, match="domain"):
        tensor_nurbs_eval(knots, net, w, x + 1.0, DEGREES).block_until_ready()
    with pytest.raises(lekalo.InputError, match="w_tangent"):
        lekalo.tensor_nurbs_jvp(list(knots), net, list(DEGREES), w, x, w_tangent=np.zeros(3))
    with pytest.raises(lekalo.InputError, match="(?i)finite"):
        lekalo.tensor_nurbs_jvp(list(knots), net, list(DEGREES), w, x, x_tangent=np.full(x.shape, np.inf))
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.tensor_nurbs_vjp(list(knots), net, list(DEGREES), w, x, np.zeros((4, 3)))
    with pytest.raises(lekalo.InputError, match="domain"):
        lekalo.tensor_nurbs_vjp(list(knots), net, list(DEGREES), w, x - 1.0, np.zeros((4, 2)))
