"""Derivatives with respect to the knots, from NumPy (``lekalo.bspline_curve_knot_jvp`` /
``_vjp``, ``lekalo.bspline_surface_knot_jvp`` / ``_vjp``, ``lekalo.nurbs_curve_knot_jvp`` /
``_vjp``, ``lekalo.tensor_bspline_knot_jvp`` / ``_vjp``) and from JAX (``bspline_eval``,
``bspline_surface_eval``, ``nurbs_eval``, ``tensor_bspline_eval``, ``interpolate`` and
``fit_least_squares`` under ``jax.grad``,
``jacfwd``, ``jacrev``, ``jit`` and ``vmap``, in float64): against central differences of the
evaluation in the interior knots (relative 1e-7), the JAX Jacobians against the library's
kernels, the end knots held fixed (zero gradient). The mathematics (multiple knots, parameters
on knots, the adjoint identity) is tested in the core, ``crates/lekalo/src/derivatives/knots/``."""

import numpy as np
import pytest

import lekalo

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

from jax_support import assert_rel, x64  # noqa: E402,F401  (x64: autouse fixture)
from derivative_checks import interior, knot_central  # noqa: E402
from lekalo.jax import bspline_eval, bspline_surface_eval, fit_least_squares, interpolate, nurbs_eval, tensor_bspline_eval  # noqa: E402

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


# -- NURBS curves and tensor-product splines in N variables ---------------------------------------


def nurbs_case():
    knots, ctrl, u = curve_case()
    w = np.array([1.0, 0.6, 1.7, 0.9, 1.3, 0.5, 1.1])
    return knots, ctrl, w, u


def nurbs_values(knots, ctrl, w, u):
    return lekalo.nurbs_curve_jvp(P, knots, ctrl, w, u)[0]


DEGREES = (2, 1, 3)


def tensor_case(dim=2):
    rng = np.random.default_rng(17)
    knots = (
        np.array([0, 0, 0, 0.35, 0.6, 1, 1, 1.0]),
        np.array([0, 0, 0.4, 1, 1.0]),
        np.array([0, 0, 0, 0, 0.55, 1, 1, 1, 1.0]),
    )
    net = rng.uniform(-1, 1, (5, 3, 5, dim))
    x = np.array([[0.1, 0.2, 0.3], [0.5, 0.7, 0.8], [0.9, 0.05, 0.45], [0.3, 0.55, 0.62], [0.7, 0.3, 0.95]])
    return knots, net, x  # x off the knots


def tensor_values(knots, net, x):
    return lekalo.tensor_bspline_jvp(list(knots), net, list(DEGREES), x)[0]


def tensor_knot_jacobians(knots, net, x):
    """The Jacobian in each knot vector by central differences."""
    out = []
    for a in range(3):
        def f(k, a=a):
            return tensor_values(knots[:a] + (k,) + knots[a + 1 :], net, x)

        out.append(knot_central(f, knots[a], DEGREES[a]))
    return out


def test_nurbs_knot_kernels_match_central_differences_and_each_other():
    knots, ctrl, w, u = nurbs_case()
    jac = knot_central(lambda k: nurbs_values(k, ctrl, w, u), knots, P)  # (7, 2, 11)
    rng = np.random.default_rng(4)
    dk = rng.uniform(-1, 1, knots.shape)
    values, tangent = lekalo.nurbs_curve_knot_jvp(P, knots, ctrl, w, u, dk)
    assert np.array_equal(values, nurbs_values(knots, ctrl, w, u))
    assert_rel(tangent, jac @ dk, "NURBS knot JVP")
    g = rng.uniform(-1, 1, values.shape)
    gk = lekalo.nurbs_curve_knot_vjp(P, knots, ctrl, w, u, g)
    assert gk.shape == knots.shape and gk.dtype == np.float64
    assert np.all(gk[~interior(knots, P)] == 0.0)
    assert_rel(gk, np.einsum("md,mdk->k", g, jac), "NURBS knot VJP")
    assert abs(np.sum(tangent * g) - gk @ dk) <= 1e-12 * np.sum(np.abs(tangent * g))
    # the weights matter: the B-spline of the same control points moves differently
    assert np.max(np.abs(tangent - lekalo.bspline_curve_knot_jvp(P, knots, ctrl, u, dk)[1])) > 1e-3


def test_tensor_knot_kernels_match_central_differences():
    knots, net, x = tensor_case()
    jacs = tensor_knot_jacobians(knots, net, x)  # (5, 2, len(knots[a])) each
    rng = np.random.default_rng(6)
    dks = [rng.uniform(-1, 1, k.shape) for k in knots]
    values, tangent = lekalo.tensor_bspline_knot_jvp(list(knots), net, list(DEGREES), x, dks)
    assert np.array_equal(values, tensor_values(knots, net, x))
    assert_rel(tangent, sum(j @ d for j, d in zip(jacs, dks)), "tensor knot JVP")
    _, middle = lekalo.tensor_bspline_knot_jvp(knots, net, DEGREES, x, [None, dks[1], None])
    assert_rel(middle, jacs[1] @ dks[1], "tensor knot JVP of the second variable")
    g = rng.uniform(-1, 1, values.shape)
    gks = lekalo.tensor_bspline_knot_vjp(knots, net, DEGREES, x, g)
    assert isinstance(gks, tuple) and len(gks) == 3
    for a, (gk, jac) in enumerate(zip(gks, jacs)):
        assert gk.shape == knots[a].shape
        assert np.all(gk[~interior(knots[a], DEGREES[a])] == 0.0)
        assert_rel(gk, np.einsum("md,mdk->k", g, jac), f"tensor knot VJP of variable {a}")
    lhs = np.sum(tangent * g)
    assert abs(lhs - sum(gk @ d for gk, d in zip(gks, dks))) <= 1e-12 * np.sum(np.abs(tangent * g))
    # scalar coefficients: values and cotangents without a trailing axis
    vals, tan = lekalo.tensor_bspline_knot_jvp(knots, net[..., 0], DEGREES, x, dks)
    assert vals.shape == tan.shape == (len(x),)
    assert_rel(tan, sum(j[:, 0] @ d for j, d in zip(jacs, dks)), "scalar coefficients")


def test_nurbs_and_tensor_knot_kernels_refuse_bad_shapes():
    knots, ctrl, w, u = nurbs_case()
    with pytest.raises(lekalo.InputError, match="knots_tangent"):
        lekalo.nurbs_curve_knot_jvp(P, knots, ctrl, w, u, np.zeros(len(knots) + 1))
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.nurbs_curve_knot_vjp(P, knots, ctrl, w, u, np.zeros(len(u)))
    kt, net, x = tensor_case()
    with pytest.raises(lekalo.InputError, match="t_tangent: 2 entries for 3 variables"):
        lekalo.tensor_bspline_knot_jvp(kt, net, DEGREES, x, [None, None])
    with pytest.raises(lekalo.InputError, match=r"t_tangent\[2\]"):
        lekalo.tensor_bspline_knot_jvp(kt, net, DEGREES, x, [None, None, np.zeros(3)])
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.tensor_bspline_knot_vjp(kt, net, DEGREES, x, np.zeros((len(x), 3)))


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
def test_nurbs_knot_jacobians(mode, jit):
    knots, ctrl, w, u = nurbs_case()
    f = getattr(jax, mode)(lambda k: nurbs_eval(k, ctrl, w, u, P))
    jac = np.asarray(jax.jit(f)(knots) if jit else f(knots))
    assert jac.dtype == np.float64
    want = knot_central(lambda k: nurbs_values(k, ctrl, w, u), knots, P)
    assert_rel(jac, want, f"{mode} in the knots")
    # all four arguments at once
    jk, jc, jw, ju = getattr(jax, mode)(lambda k, c, ws, t: nurbs_eval(k, c, ws, t, P), argnums=(0, 1, 2, 3))(
        knots, ctrl, w, u
    )
    assert_rel(jk, want, f"{mode} in the knots, with the others")
    assert jc.shape == (7, 2, 7, 2) and jw.shape == (7, 2, 7) and ju.shape == (7, 2, 7)


def test_nurbs_knot_grad_jvp_and_vmap_are_the_kernels():
    knots, ctrl, w, u = nurbs_case()
    rng = np.random.default_rng(8)
    target = rng.uniform(-1, 1, (len(u), 2))

    def loss(k):
        return jnp.sum((nurbs_eval(k, ctrl, w, u, P) - target) ** 2)

    g = jax.grad(loss)(knots)
    resid = nurbs_values(knots, ctrl, w, u) - target
    assert_rel(g, lekalo.nurbs_curve_knot_vjp(P, knots, ctrl, w, u, 2 * resid), "grad")
    assert_rel(jax.jit(jax.grad(loss))(knots), g, "grad under jit")
    dk = rng.uniform(-1, 1, knots.shape)
    _, tan = jax.jvp(lambda k: nurbs_eval(k, ctrl, w, u, P), (knots,), (dk,))
    assert_rel(tan, lekalo.nurbs_curve_knot_jvp(P, knots, ctrl, w, u, dk)[1], "jvp")
    # a batch of knot vectors, and of weights with the knots shared
    batch = np.stack([knots] * 3)
    batch[:, 4:7] += np.array([[0.0, 0.0, 0.0], [0.02, -0.03, 0.05], [-0.04, 0.02, 0.01]])
    f = lambda k: jnp.sum(nurbs_eval(k, ctrl, w, u, P) ** 2)  # noqa: E731
    for mode, got in (
        ("vmap(grad)", jax.vmap(jax.grad(f))(batch)),
        ("jit(vmap(jacfwd))", jax.jit(jax.vmap(jax.jacfwd(f)))(batch)),
    ):
        for i in range(3):
            want = knot_central(lambda k: np.sum(nurbs_values(k, ctrl, w, u) ** 2), batch[i], P)
            assert_rel(got[i], want, f"{mode}, element {i}")
    ws = np.stack([w, w[::-1]])
    g = jax.vmap(jax.grad(lambda k, ww: jnp.sum(nurbs_eval(k, ctrl, ww, u, P))), in_axes=(None, 0))(knots, ws)
    for i in range(2):
        want = lekalo.nurbs_curve_knot_vjp(P, knots, ctrl, ws[i], u, np.ones((len(u), 2)))
        assert_rel(g[i], want, f"shared knots, element {i}")


def test_nurbs_knot_gradient_of_a_small_call():
    """Two parameters on 40 control points: the values run in place, the knot derivative on the
    built curve."""
    rng = np.random.default_rng(9)
    n = 40
    knots = np.r_[[0.0] * 3, np.linspace(0, 1, n - 2), [1.0] * 3]
    ctrl, w, u = rng.uniform(-1, 1, (n, 2)), rng.uniform(0.5, 2, n), np.array([0.313, 0.702])
    g = jax.jit(jax.grad(lambda k: jnp.sum(nurbs_eval(k, ctrl, w, u, P) ** 2)))(knots)
    resid = 2 * nurbs_values(knots, ctrl, w, u)
    assert_rel(g, lekalo.nurbs_curve_knot_vjp(P, knots, ctrl, w, u, resid), "small call")
    assert np.count_nonzero(np.asarray(g)) <= 2 * 2 * P


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_tensor_knot_jacobians(mode):
    knots, net, x = tensor_case()
    want = tensor_knot_jacobians(knots, net, x)
    jac = getattr(jax, mode)(lambda *k: tensor_bspline_eval(k, net, x, DEGREES), argnums=(0, 1, 2))
    for jit in (False, True):
        got = jax.jit(jac)(*knots) if jit else jac(*knots)
        for a in range(3):
            assert np.asarray(got[a]).dtype == np.float64
            assert_rel(got[a], want[a], f"{mode} in knots[{a}], jit {jit}")
    # the knots with the coefficients and the points
    jk, jn, jx = getattr(jax, mode)(lambda k, c, p: tensor_bspline_eval((knots[0], k, knots[2]), c, p, DEGREES),
                                    argnums=(0, 1, 2))(knots[1], net, x)
    assert_rel(jk, want[1], f"{mode} in knots[1], with the others")
    assert jn.shape == (5, 2) + net.shape and jx.shape == (5, 2, 5, 3)


def test_tensor_knot_grad_jvp_and_vmap_are_the_kernels():
    knots, net, x = tensor_case()
    rng = np.random.default_rng(10)
    g = rng.uniform(-1, 1, (len(x), 2))
    grads = jax.grad(lambda *k: jnp.sum(tensor_bspline_eval(k, net, x, DEGREES) * g), argnums=(0, 1, 2))(*knots)
    for a, (got, want) in enumerate(zip(grads, lekalo.tensor_bspline_knot_vjp(knots, net, DEGREES, x, g))):
        assert_rel(got, want, f"grad of knots[{a}]")
    dks = tuple(rng.uniform(-1, 1, k.shape) for k in knots)
    _, tan = jax.jit(lambda k, d: jax.jvp(lambda *kk: tensor_bspline_eval(kk, net, x, DEGREES), k, d))(knots, dks)
    assert_rel(tan, lekalo.tensor_bspline_knot_jvp(knots, net, DEGREES, x, dks)[1], "jvp")
    # a batch of first knot vectors (vmap of grad, and of jacrev under jit), a scalar function
    batch = np.stack([knots[0], knots[0] + np.r_[0, 0, 0, 0.03, -0.02, 0, 0, 0]])

    def f(k0, c):
        return jnp.sum(tensor_bspline_eval((k0, knots[1], knots[2]), c, x, DEGREES) ** 2)

    for mode, got in (
        ("vmap(grad)", jax.vmap(jax.grad(f), in_axes=(0, None))(batch, net[..., 0])),
        ("jit(vmap(jacrev))", jax.jit(jax.vmap(jax.jacrev(f), in_axes=(0, None)))(batch, net[..., 0])),
    ):
        for i in range(2):
            k = (batch[i], knots[1], knots[2])
            twice = 2 * tensor_values(k, net[..., 0], x)
            want = lekalo.tensor_bspline_knot_vjp(k, net[..., 0], DEGREES, x, twice)[0]
            assert_rel(got[i], want, f"{mode}, element {i}")


def test_knot_derivatives_compile_to_the_ffi_targets():
    knots, ctrl, w, u = nurbs_case()
    text = jax.jit(jax.grad(lambda k: jnp.sum(nurbs_eval(k, ctrl, w, u, P)))).lower(knots).as_text()
    assert "lekalo_nurbs_vjp" in text and "callback" not in text
    kt, net, x = tensor_case()
    grad = jax.grad(lambda k: jnp.sum(tensor_bspline_eval((kt[0], k, kt[2]), net, x, DEGREES)))
    text = jax.jit(grad).lower(kt[1]).as_text()
    assert "lekalo_tensor_vjp" in text and "callback" not in text


def test_second_derivatives_in_the_knots_raise():
    knots, ctrl, w, u = nurbs_case()
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda k: jnp.sum(bspline_eval(k, ctrl, u, P)))(knots)
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda k: jnp.sum(nurbs_eval(k, ctrl, w, u, P)))(knots)
    kt, net, x = tensor_case()
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.jacfwd(jax.grad(lambda k: jnp.sum(tensor_bspline_eval((k, kt[1], kt[2]), net, x, DEGREES))))(kt[0])


# -- interpolation in its knots --------------------------------------------------------------


INTERP_KNOTS = np.array([0, 0, 0, 0, 0.23, 0.46, 0.71, 1, 1, 1, 1.0])  # off every parameter


def interp_case():
    x = np.array([0.0, 0.1, 0.3, 0.55, 0.62, 0.85, 1.0])
    return x, np.stack([np.sin(3 * x) + 2, x * x - 0.5 * x], axis=-1)


def interpolated(knots, x, y):
    return lekalo.interpolation_jvp(P, knots, x, y)


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
def test_interpolation_knot_jacobians(mode, jit):
    x, y = interp_case()
    f = lambda k: interpolate(y, x, k, P)  # noqa: E731
    jac = getattr(jax, mode)(f)
    got = (jax.jit(jac) if jit else jac)(INTERP_KNOTS)
    want = knot_central(lambda k: interpolated(k, x, y), INTERP_KNOTS, P)  # (7, 2, 11)
    assert_rel(got, want, f"{mode}, jit={jit}")
    assert np.all(np.asarray(got)[..., ~interior(INTERP_KNOTS, P)] == 0), "end knots held fixed"
    # 1-D data: 1-D control points, the first coordinate's Jacobian
    g1 = getattr(jax, mode)(lambda k: interpolate(y[:, 0], x, k, P))(INTERP_KNOTS)
    assert_rel(g1, want[:, 0], f"{mode}, 1-D data")


def test_interpolation_knots_with_data_and_parameters_and_the_kernels():
    x, y = interp_case()
    rng = np.random.default_rng(8)
    dk, dy = rng.uniform(-1, 1, INTERP_KNOTS.shape), rng.uniform(-1, 1, y.shape)
    dx = np.concatenate([[0.0], rng.uniform(-1, 1, 5), [0.0]])
    # every tangent at once: the sum of the three directional derivatives
    h = 1e-6
    fd = (interpolated(INTERP_KNOTS + h * dk * interior(INTERP_KNOTS, P), x + h * dx, y + h * dy)
          - interpolated(INTERP_KNOTS - h * dk * interior(INTERP_KNOTS, P), x - h * dx, y - h * dy)) / (2 * h)
    f = jax.jit(lambda k, p, q: interpolate(q, p, k, P))
    _, tangent = jax.jvp(f, (INTERP_KNOTS, x, y), (dk, dx, dy))
    assert_rel(tangent, fd, "JVP in knots, parameters and data")
    # the knot part is the library's kernel, and the VJP its transpose
    _, knots_only = jax.jvp(lambda k: interpolate(y, x, k, P), (INTERP_KNOTS,), (dk,))
    assert_rel(knots_only, lekalo.interpolation_knot_jvp(P, INTERP_KNOTS, x, y, dk)[1], "knot JVP")
    g = rng.uniform(-1, 1, y.shape)
    _, pull = jax.vjp(f, INTERP_KNOTS, x, y)
    gk, gx, gy = pull(jnp.asarray(g))
    assert_rel(gk, lekalo.interpolation_knot_vjp(P, INTERP_KNOTS, x, y, g), "knot VJP")
    assert np.all(np.asarray(gk)[~interior(INTERP_KNOTS, P)] == 0)
    assert_rel(float(gk @ dk + gx @ dx + jnp.sum(gy * dy)), float(np.sum(g * fd)), "VJP the JVP's transpose")


def test_interpolation_knot_gradient_under_vmap():
    x, y = interp_case()
    target = np.linspace(-1, 1, y.size).reshape(y.shape)
    loss = lambda k: jnp.sum((interpolate(y, x, k, P) - target) ** 2)  # noqa: E731
    loss_np = lambda k: np.sum((interpolated(k, x, y) - target) ** 2)  # noqa: E731
    shifted = INTERP_KNOTS.copy()
    shifted[4:7] += np.array([0.02, -0.03, 0.04])
    batch = np.stack([INTERP_KNOTS, shifted])
    for mode, got in (
        ("vmap(grad)", jax.vmap(jax.grad(loss))(batch)),
        ("jit(vmap(grad))", jax.jit(jax.vmap(jax.grad(loss)))(batch)),
        ("grad(sum(vmap))", jax.grad(lambda b: jnp.sum(jax.vmap(loss)(b)))(batch)),
    ):
        for i in range(2):
            assert_rel(got[i], knot_central(loss_np, batch[i], P), f"{mode}, element {i}")
    # the knots batched with the data
    ys = np.stack([y, 2 * y - 1])
    jac = jax.vmap(jax.jacrev(lambda k, q: interpolate(q, x, k, P)))(batch, ys)
    for i in range(2):
        want = knot_central(lambda k: interpolated(k, x, ys[i]), batch[i], P)
        assert_rel(jac[i], want, f"vmap(jacrev) with the data, element {i}")


def test_interpolation_knot_gradient_compiles_to_the_ffi_target():
    x, y = interp_case()
    grad = jax.grad(lambda k: jnp.sum(interpolate(y, x, k, P) ** 2))
    text = jax.jit(grad).lower(INTERP_KNOTS).as_text()
    assert "lekalo_interpolate_vjp" in text and "callback" not in text
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda k: jnp.sum(interpolate(y, x, k, P)))(INTERP_KNOTS)


# -- the least-squares fit in its knots ------------------------------------------------------


def lsq_knot_case():
    rng = np.random.default_rng(5)
    x = rng.permutation(np.linspace(0, 1, 40))
    y = np.stack([np.sin(4 * x) + 10, np.cos(2 * x) * x], axis=-1) + 0.05 * rng.standard_normal((40, 2))
    return x, y, rng.uniform(0.5, 2.5, 40)


def lsq_fitted(knots, x, y, w=None):
    return lekalo.least_squares_knot_jvp(P, knots, x, y, np.zeros(len(knots)), w)[0]


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
@pytest.mark.parametrize("weighted", [False, True])
def test_least_squares_knot_jacobians(mode, jit, weighted):
    x, y, w = lsq_knot_case()
    w = w if weighted else None
    f = lambda k: fit_least_squares(y, x, k, P, w=w)  # noqa: E731
    jac = getattr(jax, mode)(f)
    got = (jax.jit(jac) if jit else jac)(INTERP_KNOTS)
    want = knot_central(lambda k: lsq_fitted(k, x, y, w), INTERP_KNOTS, P)
    assert_rel(got, want, f"{mode}, jit={jit}, weighted={weighted}")
    assert np.all(np.asarray(got)[..., ~interior(INTERP_KNOTS, P)] == 0), "end knots held fixed"


def test_least_squares_knots_with_data_kernels_and_vmap():
    x, y, w = lsq_knot_case()
    rng = np.random.default_rng(9)
    dk, dy = rng.uniform(-1, 1, INTERP_KNOTS.shape), rng.uniform(-1, 1, y.shape)
    f = jax.jit(lambda k, q: fit_least_squares(q, x, k, P, w=w))
    vals, tangent = jax.jvp(f, (INTERP_KNOTS, y), (dk, dy))
    assert np.array_equal(np.asarray(vals), lsq_fitted(INTERP_KNOTS, x, y, w))
    want = lekalo.least_squares_knot_jvp(P, INTERP_KNOTS, x, y, dk, w)[1] + lekalo.least_squares_jvp(P, INTERP_KNOTS, x, dy, w)
    assert_rel(tangent, want, "JVP in the knots and the data")
    g = rng.uniform(-1, 1, vals.shape)
    gk, gy = jax.vjp(f, INTERP_KNOTS, y)[1](jnp.asarray(g))
    assert_rel(gk, lekalo.least_squares_knot_vjp(P, INTERP_KNOTS, x, y, g, w), "knot VJP")
    assert_rel(gy, lekalo.least_squares_vjp(P, INTERP_KNOTS, x, g, w), "data VJP")
    target = np.linspace(-1, 1, g.size).reshape(g.shape)
    loss = lambda k: jnp.sum((fit_least_squares(y, x, k, P, w=w) - target) ** 2)  # noqa: E731
    loss_np = lambda k: np.sum((lsq_fitted(k, x, y, w) - target) ** 2)  # noqa: E731
    shifted = INTERP_KNOTS.copy()
    shifted[4:7] += np.array([0.02, -0.03, 0.04])
    batch = np.stack([INTERP_KNOTS, shifted])
    for mode, got in (
        ("vmap(grad)", jax.vmap(jax.grad(loss))(batch)),
        ("jit(vmap(grad))", jax.jit(jax.vmap(jax.grad(loss)))(batch)),
    ):
        for i in range(2):
            assert_rel(got[i], knot_central(loss_np, batch[i], P), f"{mode}, element {i}")
    text = jax.jit(jax.grad(loss)).lower(INTERP_KNOTS).as_text()
    assert "lekalo_fit_least_squares_vjp" in text and "callback" not in text
