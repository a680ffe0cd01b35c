"""lekalo.jax: values bit-for-bit lekalo's, Jacobians from jacfwd and jacrev against central
finite differences (relative 1e-7) eagerly, under jit and under vmap, and the errors for what
is not supported (float32, second derivatives, parameters outside the domain); the knot
derivatives are in test_jax_knots.py. The derivative mathematics is tested in the core
(crates/lekalo/src/derivatives/)."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import RUNTIME_ERRORS, assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import bspline_eval, bspline_surface_eval, interpolate, nurbs_eval  # noqa: E402


def curve_case(dim=3):
    rng = np.random.default_rng(7)
    knots = np.array([0, 0, 0, 0, 0.3, 0.55, 1, 1, 1, 1.0])
    ctrl = rng.uniform(-1, 1, (6, dim))
    u = np.array([0.05, 0.2, 0.41, 0.5, 0.7, 0.93])  # off the knots
    return knots, ctrl, u


def surface_case():
    rng = np.random.default_rng(11)
    ku = np.array([0, 0, 0, 0.4, 1, 1, 1.0])
    kv = np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net = rng.uniform(-1, 1, (4, 5, 3))
    u = np.array([0.1, 0.3, 0.6, 0.85])
    v = np.array([0.2, 0.45, 0.7, 0.1])
    return ku, kv, net, u, v


def test_values_are_lekalos_bit_for_bit_and_agree_with_scipy():
    knots, ctrl, u = curve_case()
    got = np.asarray(bspline_eval(knots, ctrl, u, 3))
    ref = lekalo.bspline_curve_jvp(3, knots, ctrl, u)[0]
    assert np.array_equal(got, ref)
    assert np.array_equal(np.asarray(jax.jit(bspline_eval, static_argnums=3)(knots, ctrl, u, 3)), ref)
    scipy = pytest.importorskip("scipy.interpolate")
    np.testing.assert_allclose(got, scipy.BSpline(knots, ctrl, 3)(u), rtol=1e-14, atol=1e-15)
    # any shape of u, and a function (1-D control points)
    assert bspline_eval(knots, ctrl, u.reshape(2, 3), 3).shape == (2, 3, 3)
    y = bspline_eval(knots, ctrl[:, 0], u, 3)
    assert y.shape == u.shape and np.array_equal(np.asarray(y), ref[:, 0])


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
def test_curve_jacobians_match_central_differences(mode, jit):
    knots, ctrl, u = curve_case()
    jac = getattr(jax, mode)
    f = lambda c, t: bspline_eval(knots, c, t, 3)  # noqa: E731
    jc, ju = jac(f, argnums=(0, 1))(ctrl, u) if not jit else jax.jit(jac(f, argnums=(0, 1)))(ctrl, u)
    plain = lambda c, t: lekalo.bspline_curve_jvp(3, knots, c, t)[0]  # noqa: E731
    assert_rel(jc, central(lambda c: plain(c, u), ctrl, 1e-3), f"{mode} in the control points")
    assert_rel(ju, central(lambda t: plain(ctrl, t), u, 1e-6), f"{mode} in u")


def test_grad_of_a_loss_and_jvp_vjp():
    knots, ctrl, u = curve_case()
    target = np.ones((u.size, 3))
    loss = lambda c, t: jnp.sum((bspline_eval(knots, c, t, 3) - target) ** 2)  # noqa: E731
    gc, gu = jax.jit(jax.grad(loss, argnums=(0, 1)))(ctrl, u)
    f = lambda c, t: np.sum((lekalo.bspline_curve_jvp(3, knots, c, t)[0] - target) ** 2)  # noqa: E731
    assert_rel(gc, central(lambda c: f(c, u), ctrl, 1e-5), "grad in the control points")
    assert_rel(gu, central(lambda t: f(ctrl, t), u, 1e-6), "grad in u")
    # jax.jvp and jax.vjp agree with lekalo's own kernels
    dc, du = np.full_like(ctrl, 0.5), np.linspace(-1, 1, u.size)
    _, tan = jax.jvp(lambda c, t: bspline_eval(knots, c, t, 3), (ctrl, u), (dc, du))
    assert_rel(tan, lekalo.bspline_curve_jvp(3, knots, ctrl, u, dc, du)[1], "jvp")
    g = np.arange(u.size * 3, dtype=float).reshape(u.size, 3)
    _, pullback = jax.vjp(lambda c, t: bspline_eval(knots, c, t, 3), ctrl, u)
    for a, b in zip(pullback(g), lekalo.bspline_curve_vjp(3, knots, ctrl, u, g)):
        assert_rel(a, b, "vjp")


def test_vmap_over_curves_and_parameters():
    knots, ctrl, u = curve_case()
    batch = np.stack([ctrl, 2 * ctrl, ctrl[::-1]])
    us = np.stack([u, u[::-1] * 0.9])
    f = lambda c, t: bspline_eval(knots, c, t, 3)  # noqa: E731
    vals = jax.jit(jax.vmap(jax.vmap(f, in_axes=(None, 0)), in_axes=(0, None)))(batch, us)
    for i, c in enumerate(batch):
        for j, t in enumerate(us):
            assert np.array_equal(np.asarray(vals[i, j]), lekalo.bspline_curve_jvp(3, knots, c, t)[0])
    # gradients per curve: vmap of grad, and grad of vmap
    loss = lambda c: jnp.sum(f(c, u) ** 3)  # noqa: E731
    per_curve = jax.jit(jax.vmap(jax.grad(loss)))(batch)
    summed = jax.jit(jax.grad(lambda b: jnp.sum(jax.vmap(loss)(b))))(batch)
    loss_np = lambda c: np.sum(lekalo.bspline_curve_jvp(3, knots, c, u)[0] ** 3)  # noqa: E731
    for i, c in enumerate(batch):
        fd = central(loss_np, c, 1e-5)
        assert_rel(per_curve[i], fd, "vmap(grad)")
        assert_rel(summed[i], fd, "grad(vmap)")
    # the parameters batched too, forward mode
    ju = jax.jit(jax.vmap(jax.jacfwd(f, argnums=1), in_axes=(0, 0)))(batch[:2], us)
    for i in range(2):
        fd = central(lambda t: lekalo.bspline_curve_jvp(3, knots, batch[i], t)[0], us[i], 1e-6)
        assert_rel(ju[i], fd, "vmap(jacfwd) in u")


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_nurbs_jacobians_match_central_differences(mode):
    knots, ctrl, u = curve_case()
    w = np.array([1.0, 0.5, 2.0, 1.5, 0.8, 1.2])
    f = lambda c, ws, t: nurbs_eval(knots, c, ws, t, 3)  # noqa: E731
    plain = lambda c, ws, t: lekalo.nurbs_curve_jvp(3, knots, c, ws, t)[0]  # noqa: E731
    assert np.array_equal(np.asarray(f(ctrl, w, u)), plain(ctrl, w, u))
    np.testing.assert_allclose(plain(ctrl, w, u), lekalo.NurbsCurve(3, knots, ctrl, w)(u), atol=1e-14)
    jc, jw, ju = jax.jit(getattr(jax, mode)(f, argnums=(0, 1, 2)))(ctrl, w, u)
    assert_rel(jc, central(lambda c: plain(c, w, u), ctrl, 1e-3), f"{mode} in the control points")
    assert_rel(jw, central(lambda ws: plain(ctrl, ws, u), w, 1e-6), f"{mode} in the weights")
    assert_rel(ju, central(lambda t: plain(ctrl, w, t), u, 1e-6), f"{mode} in u")
    # vmap of grad over weight sets
    ws = np.stack([w, w[::-1]])
    g = jax.vmap(jax.grad(lambda x: jnp.sum(f(ctrl, x, u) ** 2)))(ws)
    for i in range(2):
        fd = central(lambda x: np.sum(plain(ctrl, x, u) ** 2), ws[i], 1e-6)
        assert_rel(g[i], fd, "vmap(grad) over weights")


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_surface_jacobians_match_central_differences(mode):
    ku, kv, net, u, v = surface_case()
    f = lambda c, a, b: bspline_surface_eval(ku, kv, c, a, b, 2, 3)  # noqa: E731
    plain = lambda c, a, b: lekalo.bspline_surface_jvp(2, 3, ku, kv, c, a, b)[0]  # noqa: E731
    assert np.array_equal(np.asarray(f(net, u, v)), plain(net, u, v))
    jn, ju, jv = jax.jit(getattr(jax, mode)(f, argnums=(0, 1, 2)))(net, u, v)
    assert_rel(jn, central(lambda c: plain(c, u, v), net, 1e-3), f"{mode} in the net")
    assert_rel(ju, central(lambda a: plain(net, a, v), u, 1e-6), f"{mode} in u")
    assert_rel(jv, central(lambda b: plain(net, u, b), v, 1e-6), f"{mode} in v")
    # vmap over nets
    batch = np.stack([net, -net])
    g = jax.vmap(jax.grad(lambda c: jnp.sum(f(c, u, v) ** 2)))(batch)
    for i in range(2):
        fd = central(lambda c: float(np.sum(plain(c, u, v) ** 2)), batch[i], 1e-5)
        assert_rel(g[i], fd, "vmap(grad) over nets")


def interpolation_case(dim=2):
    """Nine sorted parameters with not-a-knot cubic knots (the interior data sites but the
    second and the second last): Schoenberg–Whitney holds."""
    rng = np.random.default_rng(5)
    x = np.array([0.0, 0.08, 0.21, 0.35, 0.47, 0.6, 0.74, 0.88, 1.0])
    t = np.r_[[x[0]] * 4, x[2:-2], [x[-1]] * 4]
    q = rng.uniform(-1, 1, (x.size, dim))
    return q, x, t


def plain_interpolate(q, x, t, k=3):
    return lekalo.interpolation_jvp(k, t, x, q)


def test_interpolation_values_are_lekalos_and_scipys():
    q, x, t = interpolation_case()
    got = np.asarray(interpolate(q, x, t))
    assert np.array_equal(got, plain_interpolate(q, x, t))
    assert np.array_equal(np.asarray(jax.jit(interpolate, static_argnums=3)(q, x, t, 3)), got)
    # the interpolant passes through the data
    np.testing.assert_allclose(lekalo.bspline_curve_jvp(3, t, got, x)[0], q, rtol=0, atol=1e-14)
    scipy = pytest.importorskip("scipy.interpolate")
    np.testing.assert_allclose(got, scipy.make_interp_spline(x, q, 3, t=t).c, rtol=0, atol=1e-13)
    y = interpolate(q[:, 0], x, t)
    assert y.shape == (x.size,) and np.array_equal(np.asarray(y), got[:, 0])
    # degree 1 on the parameters themselves: the control points are the data
    t1 = np.r_[x[0], x, x[-1]]
    np.testing.assert_allclose(np.asarray(interpolate(q, x, t1, 1)), q, rtol=0, atol=1e-15)


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("jit", [False, True])
def test_interpolation_jacobians_match_central_differences(mode, jit):
    q, x, t = interpolation_case()
    jac = getattr(jax, mode)(lambda a, b: interpolate(a, b, t), argnums=(0, 1))
    jq, jx = (jax.jit(jac) if jit else jac)(q, x)
    assert_rel(jq, central(lambda a: plain_interpolate(a, x, t), q, 1e-3), f"{mode} in the data")
    # the end parameters sit on the ends of the domain: central differences only inside
    inner = lambda b: plain_interpolate(q, np.r_[x[0], b, x[-1]], t)  # noqa: E731
    assert_rel(np.asarray(jx)[..., 1:-1], central(inner, x[1:-1], 1e-6), f"{mode} in the parameters")
    # at the ends, one-sided differences of second order
    h = 1e-6
    for i, s in ((0, 1.0), (x.size - 1, -1.0)):
        xs = [x.copy() for _ in range(3)]
        for j, xi in enumerate(xs):
            xi[i] += s * j * h
        f0, f1, f2 = (plain_interpolate(q, xi, t) for xi in xs)
        fd = s * (-3 * f0 + 4 * f1 - f2) / (2 * h)
        assert_rel(np.asarray(jx)[..., i], fd, f"{mode} in the end parameter {i}")


def test_interpolation_grad_jvp_vjp_and_vmap():
    q, x, t = interpolation_case()
    u = np.linspace(0.03, 0.97, 23)
    loss = lambda a, b: jnp.sum(bspline_eval(t, interpolate(a, b, t), u, 3) ** 2)  # noqa: E731
    loss_np = lambda a, b: np.sum(  # noqa: E731
        lekalo.bspline_curve_jvp(3, t, plain_interpolate(a, b, t), u)[0] ** 2
    )
    for grad in (jax.grad(loss, argnums=(0, 1)), jax.jit(jax.grad(loss, argnums=(0, 1)))):
        gq, gx = grad(q, x)
        assert_rel(gq, central(lambda a: loss_np(a, x), q, 1e-5), "grad in the data")
        inner = central(lambda b: loss_np(q, np.r_[x[0], b, x[-1]]), x[1:-1], 1e-6)
        assert_rel(np.asarray(gx)[1:-1], inner, "grad in the parameters")
    # jax.jvp and jax.vjp agree with lekalo's kernels
    dq = np.linspace(-1, 1, q.size).reshape(q.shape)
    _, tan = jax.jvp(lambda a: interpolate(a, x, t), (q,), (dq,))
    assert_rel(tan, lekalo.interpolation_jvp(3, t, x, dq), "jvp")
    g = np.cos(np.arange(q.size)).reshape(q.shape)
    _, pullback = jax.vjp(lambda a: interpolate(a, x, t), q)
    assert_rel(pullback(g)[0], lekalo.interpolation_vjp(3, t, x, g), "vjp")
    # vmap over data sets and parameter sets, of the function and of grad; grad of vmap
    qs = np.stack([q, -2 * q, q[::-1]])
    xs = np.stack([x, x + 0.02 * np.sin(2 * np.pi * x), x - 0.02 * np.sin(np.pi * x)])
    vals = jax.jit(jax.vmap(lambda a, b: interpolate(a, b, t)))(qs, xs)
    per = jax.jit(jax.vmap(jax.grad(loss, argnums=(0, 1))))(qs, xs)
    summed = jax.jit(jax.grad(lambda a, b: jnp.sum(jax.vmap(loss)(a, b)), argnums=(0, 1)))(qs, xs)
    for i in range(3):
        assert np.array_equal(np.asarray(vals[i]), plain_interpolate(qs[i], xs[i], t))
        fq = central(lambda a: loss_np(a, xs[i]), qs[i], 1e-5)
        fx = central(lambda b: loss_np(qs[i], np.r_[0.0, b, 1.0]), xs[i][1:-1], 1e-6)
        for (gq, gx), what in ((per, "vmap(grad)"), (summed, "grad(vmap)")):
            assert_rel(gq[i], fq, f"{what} in the data")
            assert_rel(np.asarray(gx[i])[1:-1], fx, f"{what} in the parameters")
    # vmap of jacfwd and jacrev in the data, the parameters shared
    for mode in ("jacfwd", "jacrev"):
        jq = jax.jit(jax.vmap(getattr(jax, mode)(lambda a: interpolate(a, x, t))))(qs)
        for i in range(3):
            assert_rel(jq[i], central(lambda a: plain_interpolate(a, x, t), qs[i], 1e-3), f"vmap({mode})")


def test_interpolation_refuses_what_it_cannot_do():
    q, x, t = interpolation_case()
    with pytest.raises(lekalo.InputError, match="need 13 knots"):
        interpolate(q, x, t[:-1])
    with pytest.raises(lekalo.InputError, match=r"params must be one a point, shape \(9,\)"):
        interpolate(q, x[:-1], t)
    with pytest.raises(lekalo.InputError, match="Python int"):
        interpolate(q, x, t, 3.0)
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda a: jnp.sum(interpolate(a, x, t) ** 2))(q)
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.jacfwd(jax.jacrev(lambda b: jnp.sum(interpolate(q, b, t) ** 2)))(x)
    # Schoenberg–Whitney violated: lekalo's error reaches the caller
    bunched = np.r_[x[:3] * 0.1, x[3:]]
    bunched[3:6] = [0.03, 0.04, 0.05]
    bunched = np.sort(bunched)
    with pytest.raises(RUNTIME_ERRORS, match="Schoenberg"):
        interpolate(q, bunched, t).block_until_ready()
    jax.config.update("jax_enable_x64", False)
    with pytest.raises(lekalo.InputError, match="jax_enable_x64"):
        interpolate(q, x, t)


def test_interpolation_runs_as_ffi_targets_and_bad_data_gives_lekalos_message():
    q, x, t = interpolation_case()
    f = lambda a, b: interpolate(a, b, t)  # noqa: E731
    loss = lambda a, b: jnp.sum(f(a, b) ** 2)  # noqa: E731
    for g in (f, jax.grad(loss, argnums=(0, 1)), jax.jacfwd(loss, argnums=(0, 1))):
        text = jax.jit(g).lower(q, x).as_text()
        assert "lekalo_interpolate" in text and "callback" not in text
    nan_q = q.copy()
    nan_q[4, 1] = np.nan
    nan_x = x.copy()
    nan_x[3] = np.nan
    for a, b, message in ((nan_q, x, "must be finite"), (q, nan_x, r"parameters\[3\] is NaN")):
        for call in (f, jax.jit(f), jax.jit(jax.grad(loss, argnums=(0, 1))), jax.jacfwd(loss, argnums=1)):
            with pytest.raises(RUNTIME_ERRORS, match=message):
                jax.block_until_ready(call(a, b))
        batched = jax.jit(jax.vmap(f))
        with pytest.raises(RUNTIME_ERRORS, match=message):
            jax.block_until_ready(batched(np.stack([q, a]), np.stack([x, b])))
    # unsorted parameters, knots that are not sorted: lekalo's messages
    with pytest.raises(RUNTIME_ERRORS, match="lekalo.jax.interpolate"):
        jax.block_until_ready(f(q, x[::-1].copy()))
    bad_t = t.copy()
    bad_t[5] = 0.9
    with pytest.raises(RUNTIME_ERRORS, match="non-decreasing"):
        jax.block_until_ready(interpolate(q, x, bad_t))
    # empty arrays and a zero dimension (XLA would skip the call): refused before it
    with pytest.raises(lekalo.InputError, match=r"shape \(0, 2\) are empty"):
        interpolate(np.zeros((0, 2)), np.zeros(0), np.zeros(4))
    with pytest.raises(lekalo.InputError, match="at least 4 points of at least one coordinate"):
        jax.jit(lambda a: interpolate(a, x, t))(np.zeros((9, 0)))
    # too few points for the degree: lekalo's message from the target
    with pytest.raises(RUNTIME_ERRORS, match="lekalo.jax.interpolate"):
        jax.block_until_ready(interpolate(q[:2], x[:2], np.r_[[0.0] * 4, [1.0] * 2]))
    # wrong dtypes: integers are converted, anything else is refused before the call
    got = interpolate(np.round(q * 4).astype(np.int32), x, t)
    assert np.array_equal(np.asarray(got), plain_interpolate(np.round(q * 4), x, t))
    with pytest.raises(lekalo.InputError, match="real numbers"):
        interpolate(q.astype(np.complex128), x, t)
    with pytest.raises(lekalo.InputError, match=r"\(m, dim\) or \(m,\)"):
        interpolate(q[None], x, t)
    # the process lives on, and the next call works
    assert np.array_equal(np.asarray(jax.jit(f)(q, x)), plain_interpolate(q, x, t))


def test_unsupported_transformations_say_so():
    knots, ctrl, u = curve_case()
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda t: jnp.sum(bspline_eval(knots, ctrl, t, 3)))(u)
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda c: jnp.sum(bspline_eval(knots, c, u, 3) ** 2))(ctrl)
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda k: jnp.sum(bspline_eval(k, ctrl, u, 3)))(knots)
    # knots behind stop_gradient are constants
    g = jax.grad(lambda c, k: jnp.sum(bspline_eval(jax.lax.stop_gradient(k), c, u, 3)))(ctrl, knots)
    assert g.shape == ctrl.shape


def test_bad_input_is_refused_with_the_fix():
    knots, ctrl, u = curve_case()
    with pytest.raises(lekalo.InputError, match="need 10 knots"):
        bspline_eval(knots[:-1], ctrl, u, 3)
    with pytest.raises(lekalo.InputError, match="Python int"):
        bspline_eval(knots, ctrl, u, 3.0)
    with pytest.raises(lekalo.InputError, match="one shape"):
        ku, kv, net, su, sv = surface_case()
        bspline_surface_eval(ku, kv, net, su, sv[:2], 2, 3)
    # errors inside the FFI target reach the caller as JAX's runtime error with lekalo's message
    with pytest.raises(RUNTIME_ERRORS, match="1.5 is outside the domain"):
        bspline_eval(knots, ctrl, np.array([0.5, 1.5]), 3).block_until_ready()
    with pytest.raises(RUNTIME_ERRORS, match="outside the domain"):
        jax.jit(bspline_eval, static_argnums=3)(knots, ctrl, np.array([-0.5]), 3).block_until_ready()
    jax.config.update("jax_enable_x64", False)
    with pytest.raises(lekalo.InputError, match="jax_enable_x64"):
        bspline_eval(knots, ctrl, u, 3)


def test_the_docs_examples_run():
    """The python blocks of docs/differentiable.md run as written, in one namespace."""
    import re
    from pathlib import Path

    doc = Path(__file__).resolve().parents[3] / "docs" / "differentiable.md"
    blocks = re.findall(r"^```python\n(.*?)^```", doc.read_text(encoding="utf-8"), flags=re.S | re.M)
    assert blocks, "docs/differentiable.md has no python block"
    namespace = {"__name__": "docs"}
    for code in blocks:
        exec(compile(code, str(doc), "exec"), namespace)
    assert namespace["jac_u"].shape == (7, 2, 7)
    assert namespace["g_data"].shape == (60, 2) and namespace["jac_y"].shape == (14, 12)
    assert namespace["grad_pts"].shape == (2, 3) and namespace["vals"].shape == (2,)
    assert namespace["g_ys"].shape == (8,) and namespace["g_xs"].shape == (8,)
    assert namespace["coef"].shape == (2, 8) and namespace["g_len"].shape == (5, 2)
    assert namespace["t_star"].shape == (2,) and namespace["dt_dq"].shape == (2, 2, 2)
    g_knots = np.asarray(namespace["g_knots"])
    assert g_knots.shape == (10,) and np.all(g_knots[:4] == 0) and np.all(g_knots[6:] == 0)
    assert np.all(g_knots[4:6] != 0)


def test_the_module_docstring_examples_run():
    import doctest

    import lekalo.jax

    result = doctest.testmod(lekalo.jax)
    assert result.attempted > 0 and result.failed == 0, result
