"""lekalo.jax through XLA's FFI (bspline_eval, nurbs_eval, bspline_surface_eval,
tensor_bspline_eval): the compiled programs call lekalo's custom-call targets (no host
callback), the derivatives through them match central differences (relative 1e-7) under jit and
vmap, the batch layouts reach the handlers intact, and lekalo's errors (a parameter outside the
domain, a non-positive weight, bad knots) come back as JAX errors carrying lekalo's message."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import bspline_eval, bspline_surface_eval, nurbs_eval, tensor_bspline_eval  # noqa: E402


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


# -- NURBS curves, surfaces and tensor-product splines in N variables --------------------------


def nurbs_case():
    knots, ctrl, u = curve_case(dim=3, seed=5)
    w = np.array([1.0, 0.5, 2.0, 1.5, 0.8, 1.2, 0.9])
    return knots, ctrl, w, u


def nurbs_ref(knots, ctrl, w, u):
    return lekalo.nurbs_curve_jvp(3, knots, ctrl, w, np.ascontiguousarray(u, dtype=float))[0]


def surface_case():
    rng = np.random.default_rng(11)
    ku = np.array([0, 0, 0, 0.4, 1, 1, 1.0])
    kv = np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net = rng.uniform(-1, 1, (4, 5, 3))
    u = np.array([0.1, 0.3, 0.6, 0.85, 0.95])
    v = np.array([0.2, 0.45, 0.7, 0.1, 0.55])
    return ku, kv, net, u, v


def surface_ref(ku, kv, net, u, v):
    u, v = (np.ascontiguousarray(a, dtype=float) for a in (u, v))
    return lekalo.bspline_surface_jvp(2, 3, ku, kv, net, u, v)[0]


TENSOR_DEGREES = (2, 1, 3)


def tensor_case():
    rng = np.random.default_rng(13)
    knots = (
        np.array([0, 0, 0, 0.5, 1, 1, 1.0]),
        np.array([0, 0, 0.3, 1, 1.0]),
        np.array([0, 0, 0, 0, 0.6, 1, 1, 1, 1.0]),
    )
    net = rng.uniform(-1, 1, (4, 3, 5, 2))
    x = rng.uniform(0.02, 0.98, (4, 3))
    return knots, net, x


def tensor_ref(knots, net, x):
    x = np.ascontiguousarray(x, dtype=float)
    return lekalo.tensor_bspline_jvp(list(knots), net, list(TENSOR_DEGREES), x)[0]


def nurbs_f(knots):
    return lambda c, w, t: nurbs_eval(knots, c, w, t, 3)


def surface_f(ku, kv):
    return lambda c, a, b: bspline_surface_eval(ku, kv, c, a, b, 2, 3)


def tensor_f(knots):
    return lambda c, x: tensor_bspline_eval(knots, c, x, TENSOR_DEGREES)


@pytest.mark.parametrize("kind", ["nurbs", "surface", "tensor"])
def test_nurbs_surfaces_and_tensors_compile_to_their_ffi_targets(kind):
    if kind == "nurbs":
        knots, ctrl, w, u = nurbs_case()
        f, args, target = nurbs_f(knots), (ctrl, w, u), "lekalo_nurbs"
    elif kind == "surface":
        ku, kv, net, u, v = surface_case()
        f, args, target = surface_f(ku, kv), (net, u, v), "lekalo_surface"
    else:
        knots, net, x = tensor_case()
        f, args, target = tensor_f(knots), (net, x), "lekalo_tensor"
    argnums = tuple(range(len(args)))
    loss = lambda *a: jnp.sum(f(*a) ** 2)  # noqa: E731
    values = hlo(f, *args)
    assert f"{target}_eval" in values and "callback" not in values
    grad = hlo(jax.grad(loss, argnums=argnums), *args)
    assert f"{target}_vjp" in grad and "callback" not in grad
    forward = hlo(lambda *a: jax.jvp(f, a, a)[1], *args)
    assert f"{target}_jvp" in forward and "callback" not in forward
    batched = hlo(jax.vmap(jax.grad(loss), in_axes=(0,) + (None,) * (len(args) - 1)),
                  np.stack([args[0], args[0]]), *args[1:])
    assert f"{target}_vjp" in batched and "callback" not in batched


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_nurbs_jacobians_under_jit_and_vmap_match_central_differences(mode):
    knots, ctrl, w, u = nurbs_case()
    cs = np.stack([ctrl, -0.5 * ctrl])
    ws = np.stack([w, w[::-1]])
    us = np.stack([u, u[::-1] * 0.97])
    jac = jax.jit(jax.vmap(getattr(jax, mode)(nurbs_f(knots), argnums=(0, 1, 2))))
    jc, jw, ju = jac(cs, ws, us)
    for i in range(2):
        c, wi, t = cs[i], ws[i], us[i]
        assert np.array_equal(np.asarray(jax.jit(nurbs_f(knots))(c, wi, t)), nurbs_ref(knots, c, wi, t))
        assert_rel(jc[i], central(lambda x: nurbs_ref(knots, x, wi, t), c, 1e-3), f"{mode} in P, {i}")
        assert_rel(jw[i], central(lambda x: nurbs_ref(knots, c, x, t), wi, 1e-6), f"{mode} in w, {i}")
        assert_rel(ju[i], central(lambda x: nurbs_ref(knots, c, wi, x), t, 1e-6), f"{mode} in u, {i}")


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_surface_jacobians_under_jit_and_vmap_match_central_differences(mode):
    ku, kv, net, u, v = surface_case()
    nets = np.stack([net, net[::-1]])
    us, vs = np.stack([u, u[::-1]]), np.stack([v, 0.9 * v])
    jac = jax.jit(jax.vmap(getattr(jax, mode)(surface_f(ku, kv), argnums=(0, 1, 2))))
    jn, ju, jv = jac(nets, us, vs)
    for i in range(2):
        c, a, b = nets[i], us[i], vs[i]
        assert np.array_equal(np.asarray(jax.jit(surface_f(ku, kv))(c, a, b)), surface_ref(ku, kv, c, a, b))
        assert_rel(jn[i], central(lambda x: surface_ref(ku, kv, x, a, b), c, 1e-3), f"{mode} in P, {i}")
        assert_rel(ju[i], central(lambda x: surface_ref(ku, kv, c, x, b), a, 1e-6), f"{mode} in u, {i}")
        assert_rel(jv[i], central(lambda x: surface_ref(ku, kv, c, a, x), b, 1e-6), f"{mode} in v, {i}")


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_tensor_jacobians_under_jit_and_vmap_match_central_differences(mode):
    knots, net, x = tensor_case()
    nets = np.stack([net, 2 * net])
    xs = np.stack([x, x[::-1] * 0.95])
    jac = jax.jit(jax.vmap(getattr(jax, mode)(tensor_f(knots), argnums=(0, 1))))
    jn, jx = jac(nets, xs)
    for i in range(2):
        c, p = nets[i], xs[i]
        assert np.array_equal(np.asarray(jax.jit(tensor_f(knots))(c, p)), tensor_ref(knots, c, p))
        assert_rel(jn[i], central(lambda a: tensor_ref(knots, a, p), c, 1e-3), f"{mode} in P, {i}")
        assert_rel(jx[i], central(lambda a: tensor_ref(knots, c, a), p, 1e-6), f"{mode} in x, {i}")
    # a scalar function (no trailing axis), one variable, and a batch of knot vectors
    y = jax.jit(tensor_f(knots))(net[..., 0], x)
    assert np.array_equal(np.asarray(y), tensor_ref(knots, net, x)[:, 0])
    k1, n1 = knots[0], np.ascontiguousarray(net[:, 0, 0, :])
    one = jax.jit(lambda c, t: tensor_bspline_eval((k1,), c, t, (2,)))(n1, x[:, :1])
    assert np.array_equal(np.asarray(one), lekalo.tensor_bspline_jvp([k1], n1, [2], np.ascontiguousarray(x[:, :1]))[0])
    kb = np.stack([knots[1], knots[1]])
    kb[1, 2] = 0.6
    per = jax.jit(jax.vmap(lambda k: tensor_bspline_eval((knots[0], k, knots[2]), net, x, TENSOR_DEGREES)))(kb)
    for i in range(2):
        ki = (knots[0], kb[i], knots[2])
        assert np.array_equal(np.asarray(per[i]), tensor_ref(ki, net, x))


def test_grad_of_losses_of_all_three():
    knots, ctrl, w, u = nurbs_case()
    g = jax.jit(jax.grad(lambda c, x: jnp.sum(nurbs_f(knots)(c, x, u) ** 3), argnums=(0, 1)))(ctrl, w)
    assert_rel(g[0], central(lambda c: np.sum(nurbs_ref(knots, c, w, u) ** 3), ctrl, 1e-4), "nurbs P")
    assert_rel(g[1], central(lambda x: np.sum(nurbs_ref(knots, ctrl, x, u) ** 3), w, 1e-5), "nurbs w")
    ku, kv, net, su, sv = surface_case()
    g = jax.jit(jax.grad(lambda a: jnp.sum(surface_f(ku, kv)(net, a, sv) ** 3)))(su)
    assert_rel(g, central(lambda a: np.sum(surface_ref(ku, kv, net, a, sv) ** 3), su, 1e-6), "surface u")
    tk, tnet, tx = tensor_case()
    g = jax.jit(jax.grad(lambda c: jnp.sum(tensor_f(tk)(c, tx) ** 3)))(tnet)
    assert_rel(g, central(lambda c: np.sum(tensor_ref(tk, c, tx) ** 3), tnet, 1e-4), "tensor P")


def test_bad_inputs_of_all_three_raise_lekalos_message():
    knots, ctrl, w, u = nurbs_case()
    f = jax.jit(nurbs_f(knots))
    loss = jax.jit(jax.grad(lambda c, x, t: jnp.sum(nurbs_f(knots)(c, x, t)), argnums=(0, 1, 2)))
    bad_u = np.array([0.5, 1.25])
    for call in (lambda: f(ctrl, w, bad_u), lambda: loss(ctrl, w, bad_u)):
        with pytest.raises(jax.errors.JaxRuntimeError, match=r"nurbs_eval.*1\.25 is outside the domain"):
            jax.block_until_ready(call())
    bad_w = w.copy()
    bad_w[2] = -1.0
    message = lekalo_message(lambda: lekalo.NurbsCurve(3, knots, ctrl, bad_w))
    for call in (lambda: f(ctrl, bad_w, u), lambda: loss(ctrl, bad_w, u)):
        with pytest.raises(jax.errors.JaxRuntimeError, match="lekalo.jax.nurbs_eval") as e:
            jax.block_until_ready(call())
        assert message in str(e.value)
    ku, kv, net, su, sv = surface_case()
    g = jax.jit(surface_f(ku, kv))
    with pytest.raises(jax.errors.JaxRuntimeError, match=r"bspline_surface_eval.*outside the domain"):
        jax.block_until_ready(g(net, su, sv + 1.0))
    with pytest.raises(jax.errors.JaxRuntimeError, match="outside the domain"):
        jax.block_until_ready(jax.jit(jax.grad(lambda a: jnp.sum(g(net, a, sv))))(su - 1.0))
    tk, tnet, tx = tensor_case()
    h = jax.jit(tensor_f(tk))
    with pytest.raises(jax.errors.JaxRuntimeError, match=r"tensor_bspline_eval.*outside the domain"):
        jax.block_until_ready(h(tnet, tx + 2.0))
    with pytest.raises(jax.errors.JaxRuntimeError, match="outside the domain"):
        jax.block_until_ready(jax.jit(jax.jacfwd(lambda x: h(tnet, x)))(tx - 2.0))
    # the process lives on
    assert np.array_equal(np.asarray(f(ctrl, w, u)), nurbs_ref(knots, ctrl, w, u))


def lekalo_message(make):
    """The message of the error lekalo's own constructor raises."""
    with pytest.raises(lekalo.InputError) as e:
        make()
    return str(e.value)
