"""lekalo.jax.fit_least_squares, fit_smoothing and tensor_bspline_eval, and the NumPy kernels
under them (least_squares_jvp/_vjp/_linearize, smoothing_*, tensor_bspline_*): values
bit-for-bit the plain fits' and evaluation's, Jacobians from jacfwd and jacrev (eager, under
jit and under vmap) against central finite differences to 1e-7 relative, and the errors for
what is not supported. The mathematics is tested in the core (crates/lekalo/src/derivatives/)."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import RUNTIME_ERRORS, assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import fit_least_squares, fit_smoothing, tensor_bspline_eval  # noqa: E402


def lsq_case(dim=2):
    rng = np.random.default_rng(3)
    x = np.sort(rng.uniform(0, 1, 40))
    x[0], x[-1] = 0.0, 1.0
    y = np.stack([np.sin(3 * x + d) for d in range(dim)], axis=-1) + 0.05 * rng.normal(size=(40, dim))
    t = np.array([0, 0, 0, 0, 0.25, 0.5, 0.8, 1, 1, 1, 1.0])
    w = rng.uniform(0.5, 2.0, 40)
    return x, y, t, w


def plain_lsq(y, x, t, w=None):
    return lekalo.fit_least_squares(y, x, t, 3, w=w)[0].control.reshape(len(t) - 4, -1)


def plain_smoothing(x, y, w, lam):
    return lekalo.fit_smoothing(x, y, w, lam)[0].control.reshape(len(x) + 2, -1)


@pytest.mark.parametrize("weighted", [False, True])
@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_least_squares_jacobians_match_central_differences(weighted, mode):
    x, y, t, w = lsq_case()
    w = w if weighted else None
    f = lambda q: fit_least_squares(q, x, t, 3, w=w)  # noqa: E731
    got = np.asarray(f(y))
    assert np.array_equal(got, plain_lsq(y, x, t, w)), "values bit-for-bit the plain fit's"
    assert np.array_equal(np.asarray(jax.jit(f)(y)), got)
    jac = jax.jit(getattr(jax, mode)(f))(y)
    assert_rel(jac, central(lambda q: plain_lsq(q, x, t, w), y, 1e-3), f"{mode} in the data")
    # 1-D data: 1-D control points
    y1 = np.ascontiguousarray(y[:, 0])
    assert fit_least_squares(y1, x, t, 3, w=w).shape == (len(t) - 4,)
    j1 = getattr(jax, mode)(lambda q: fit_least_squares(q, x, t, 3, w=w))(y1)
    assert_rel(j1, central(lambda q: plain_lsq(q, x, t, w)[:, 0], y1, 1e-3), f"{mode}, 1-D data")


@pytest.mark.parametrize("weighted", [False, True])
@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_smoothing_jacobians_match_central_differences(weighted, mode):
    x, y, _, w = lsq_case()
    w = w if weighted else None
    lam = 1e-4
    f = lambda q: fit_smoothing(x, q, w, lam)  # noqa: E731
    got = np.asarray(f(y))
    assert np.array_equal(got, plain_smoothing(x, y, w, lam))
    jac = jax.jit(getattr(jax, mode)(f))(y)
    assert_rel(jac, central(lambda q: plain_smoothing(x, q, w, lam), y, 1e-3), f"{mode} in y")


def test_fit_gradients_vmap_and_kernels():
    x, y, t, w = lsq_case()
    target = np.linspace(-1, 1, 7 * 2).reshape(7, 2)
    loss = lambda q: jnp.sum((fit_least_squares(q, x, t, 3, w=w) - target) ** 2)  # noqa: E731
    loss_np = lambda q: np.sum((plain_lsq(q, x, t, w) - target) ** 2)  # noqa: E731
    batch = np.stack([y, 2 * y, y[::-1]])
    per = jax.jit(jax.vmap(jax.grad(loss)))(batch)
    summed = jax.grad(lambda b: jnp.sum(jax.vmap(loss)(b)))(batch)
    for i in range(3):
        fd = central(loss_np, batch[i], 1e-4)
        assert_rel(per[i], fd, "vmap(grad)")
        assert_rel(summed[i], fd, "grad(vmap)")
    vals = jax.vmap(lambda q: fit_smoothing(x, q, None, 1e-3))(batch)
    for i in range(3):
        assert np.array_equal(np.asarray(vals[i]), plain_smoothing(x, batch[i], None, 1e-3))
    # the NumPy kernels: jvp is the fit of the tangent, vjp its transpose, the linearisation's
    # pieces rebuild the map
    dq, g = np.cos(7 * y), np.sin(np.arange(14.0)).reshape(7, 2)
    dp = lekalo.least_squares_jvp(3, t, x, dq, w)
    np.testing.assert_allclose(dp, plain_lsq(dq, x, t, w), rtol=1e-10, atol=1e-12)
    gq = lekalo.least_squares_vjp(3, t, x, g, w)
    assert gq.shape == y.shape
    assert abs(np.sum(g * dp) - np.sum(gq * dq)) <= 1e-12 * np.sum(np.abs(g * dp))
    ds = lekalo.smoothing_jvp(x, 1e-3, dq, w)
    np.testing.assert_allclose(ds, plain_smoothing(x, dq, w, 1e-3), rtol=1e-9, atol=1e-12)
    gs = lekalo.smoothing_vjp(x, 1e-3, np.ones((42, 2)), w)
    assert abs(np.sum(ds) - np.sum(gs * dq)) <= 1e-12 * np.sum(np.abs(ds)) * 10
    lin = lekalo.least_squares_linearize(3, t, x, w)
    assert lin["first"].dtype == np.int64 and lin["basis"].shape == (40, 4)
    assert lin["triangle"].shape == (7, 4) and lin["weights"].shape == (40,)
    assert lekalo.smoothing_linearize(x, 1e-3)["triangle"].shape == (42, 4)


def test_fits_compile_to_the_ffi_targets_not_a_callback():
    x, y, t, w = lsq_case()
    lsq = lambda q: jnp.sum(fit_least_squares(q, x, t, 3, w=w) ** 2)  # noqa: E731
    sm = lambda q: jnp.sum(fit_smoothing(x, q, w, 1e-3) ** 2)  # noqa: E731
    for f, stem in ((lsq, "lekalo_fit_least_squares"), (sm, "lekalo_fit_smoothing")):
        values = jax.jit(f).lower(y).as_text()
        assert f"{stem}_eval" in values and "callback" not in values
        grad = jax.jit(jax.grad(f)).lower(y).as_text()
        assert f"{stem}_vjp" in grad and "callback" not in grad
        forward = jax.jit(lambda q: jax.jvp(f, (q,), (q,))[1]).lower(y).as_text()
        assert f"{stem}_jvp" in forward and "callback" not in forward


@pytest.mark.parametrize("kind", ["least_squares", "smoothing"])
def test_fit_derivatives_reuse_the_forward_factorisation_with_the_same_bits(kind):
    """Under differentiation a fit's forward pass returns its factorisation with the values
    (the `_factor` target) and the JVP and VJP apply it: a gradient compiles to that call and
    the VJP, with no second values call, and the derivatives have the bits of the NumPy
    kernels, which factor the system on their own."""
    x, y, t, w = lsq_case()
    dq = np.sin(np.arange(80.0)).reshape(40, 2)
    if kind == "smoothing":
        stem, g = "lekalo_fit_smoothing", np.cos(np.arange(84.0)).reshape(42, 2)
        fit = lambda q, weights: fit_smoothing(x, q, weights, 1e-3)  # noqa: E731
        plain = lambda q, weights: plain_smoothing(x, q, weights, 1e-3)  # noqa: E731
        vjp = lambda weights: lekalo.smoothing_vjp(x, 1e-3, g, weights)  # noqa: E731
        jvp = lambda weights: lekalo.smoothing_jvp(x, 1e-3, dq, weights)  # noqa: E731
    else:
        stem, g = "lekalo_fit_least_squares", np.cos(np.arange(14.0)).reshape(7, 2)
        fit = lambda q, weights: fit_least_squares(q, x, t, 3, w=weights)  # noqa: E731
        plain = lambda q, weights: plain_lsq(q, x, t, weights)  # noqa: E731
        vjp = lambda weights: lekalo.least_squares_vjp(3, t, x, g, weights)  # noqa: E731
        jvp = lambda weights: lekalo.least_squares_jvp(3, t, x, dq, weights)  # noqa: E731
    for weights in (None, w):
        loss = lambda q: jnp.sum(jnp.asarray(g) * fit(q, weights))  # noqa: E731
        text = jax.jit(jax.grad(loss)).lower(y).as_text()
        assert f"{stem}_factor" in text and f"{stem}_eval" not in text
        got = np.asarray(jax.jit(jax.grad(loss))(y))
        assert np.array_equal(got, vjp(weights)), "VJP bits"
        vals, tan = jax.jvp(lambda q: fit(q, weights), (y,), (dq,))
        assert np.array_equal(np.asarray(vals), plain(y, weights)), "values"
        assert np.array_equal(np.asarray(tan), jvp(weights)), "JVP"
        # a batch of data sets: each element's values and factors, each one's VJP
        batch = np.stack([y, 2 * y + 1])
        per = np.asarray(jax.jit(jax.vmap(jax.grad(loss)))(batch))
        for i in range(2):
            assert np.array_equal(per[i], vjp(weights)), "vmap(grad) bits"


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_fit_jacobians_under_vmap_and_eagerly_match_central_differences(mode):
    x, y, t, w = lsq_case()
    batch = np.stack([y, np.cos(5 * y) + 10.0])
    for weights in (None, w):
        f = lambda q: fit_least_squares(q, x, t, 3, w=weights)  # noqa: E731
        plain = lambda q: plain_lsq(q, x, t, weights)  # noqa: E731
        jac = jax.vmap(getattr(jax, mode)(f))(batch)
        eager = getattr(jax, mode)(f)(batch[1])
        for i in range(2):
            assert_rel(jac[i], central(plain, batch[i], 1e-3), f"{mode} under vmap, element {i}")
        assert_rel(eager, central(plain, batch[1], 1e-3), f"{mode} eagerly")
        g = lambda q: fit_smoothing(x, q, weights, 2e-4)  # noqa: E731
        splain = lambda q: plain_smoothing(x, q, weights, 2e-4)  # noqa: E731
        jac = jax.jit(jax.vmap(getattr(jax, mode)(g)))(batch)
        for i in range(2):
            assert_rel(jac[i], central(splain, batch[i], 1e-3), f"{mode} of the smoothing, {i}")
        # 1-D data under vmap
        y1 = batch[:, :, 0]
        j1 = jax.vmap(getattr(jax, mode)(lambda q: fit_smoothing(x, q, weights, 2e-4)))(y1)
        assert_rel(j1[0], central(lambda q: splain(q)[:, 0], y1[0], 1e-3), f"{mode}, 1-D y")


def test_fit_errors_carry_lekalos_message_under_jit_and_vmap():
    x, y, t, w = lsq_case()
    bad = y.copy()
    bad[4, 1] = np.nan
    for f in (
        lambda q: fit_least_squares(q, x, t, 3),
        jax.jit(lambda q: fit_least_squares(q, x, t, 3)),
        lambda q: fit_smoothing(x, q, None, 1e-3),
        jax.jit(lambda q: fit_smoothing(x, q, None, 1e-3)),
    ):
        with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
            np.asarray(f(bad))
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        np.asarray(jax.vmap(lambda q: fit_least_squares(q, x, t, 3))(np.stack([y, bad])))
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        np.asarray(jax.jit(jax.grad(lambda q: jnp.sum(fit_smoothing(x, q, None, 1e-3))))(bad))
    # a singular fit: every parameter below 0.75, so the last spans hold no data
    xs = x * 0.7
    singular = lambda q: fit_least_squares(q, xs, t, 3)  # noqa: E731
    for f in (singular, jax.jit(singular), jax.jit(jax.grad(lambda q: jnp.sum(singular(q))))):
        with pytest.raises(RUNTIME_ERRORS, match="Schoenberg.Whitney"):
            np.asarray(f(y))
    with pytest.raises(RUNTIME_ERRORS, match="Schoenberg.Whitney"):
        np.asarray(jax.vmap(jax.jacfwd(singular))(np.stack([y, y])))
    # weight zero on all the data of the last span is as singular
    w0 = np.where(x > 0.8, 0.0, 1.0)
    with pytest.raises(RUNTIME_ERRORS, match="Schoenberg.Whitney"):
        np.asarray(fit_least_squares(y, x, t, 3, w=w0))
    with pytest.raises(RUNTIME_ERRORS, match="outside"):
        np.asarray(fit_least_squares(y, x + 0.5, t, 3))
    with pytest.raises(RUNTIME_ERRORS, match="repeated"):
        np.asarray(fit_smoothing(np.concatenate([x[:5], x[4:-1]]), y, None, 1e-3))
    with pytest.raises(RUNTIME_ERRORS, match="weight"):
        np.asarray(fit_smoothing(x, y, -w, 1e-3))
    # wrong shapes, dtypes and empty arrays: lekalo.InputError before any call
    with pytest.raises(lekalo.InputError, match="empty"):
        fit_least_squares(np.zeros((40, 0)), x, t)
    with pytest.raises(lekalo.InputError, match="empty"):
        fit_smoothing(np.zeros(0), np.zeros(0), None, 1e-3)
    with pytest.raises(lekalo.InputError, match="real numbers"):
        fit_least_squares(y.astype(complex), x, t)
    with pytest.raises(lekalo.InputError, match="real numbers"):
        fit_smoothing(x, y > 0, None, 1e-3)
    with pytest.raises(lekalo.InputError, match=r"\(m, dim\) or \(m,\)"):
        fit_least_squares(y[None], x, t)
    with pytest.raises(lekalo.InputError, match="w must be one a data point"):
        fit_least_squares(y, x, t, w=w[:-1])
    with pytest.raises(lekalo.InputError, match="x must be one a value"):
        fit_smoothing(x[:-1], y, None, 1e-3)
    with pytest.raises(lekalo.InputError, match="at least 2"):
        fit_least_squares(y, x, t[:5])
    with pytest.raises(lekalo.InputError, match="lam must be finite"):
        fit_smoothing(x, y, None, -1.0)
    with pytest.raises(NotImplementedError, match="data values only"):
        jax.jacrev(lambda ws: fit_least_squares(y, x, t, 3, w=ws))(w)
    with pytest.raises(NotImplementedError, match="data values only"):
        jax.grad(lambda xs: jnp.sum(fit_smoothing(xs, y, None, 1e-3)))(x)


def tensor_case(scalar=False):
    rng = np.random.default_rng(5)
    knots = (
        np.array([0, 0, 0, 0.5, 1, 1, 1.0]),
        np.array([0, 0, 0.3, 0.6, 1, 1.0]),
        np.array([0, 0, 0, 0, 1, 1, 1, 1.0]),
    )
    degrees = (2, 1, 3)
    shape = (4, 4, 4) if scalar else (4, 4, 4, 2)
    ctrl = rng.uniform(-1, 1, shape)
    x = np.array([[0.1, 0.2, 0.3], [0.7, 0.45, 0.9], [0.35, 0.8, 0.05], [0.55, 0.1, 0.6]])
    return knots, ctrl, x, degrees


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
@pytest.mark.parametrize("scalar", [False, True])
def test_tensor_jacobians_match_central_differences(mode, scalar):
    knots, ctrl, x, degrees = tensor_case(scalar)
    f = lambda c, p: tensor_bspline_eval(knots, c, p, degrees)  # noqa: E731
    spline = lambda c: lekalo.TensorBSpline(knots, c, list(degrees))  # noqa: E731
    plain = lambda c, p: spline(c)(p)  # noqa: E731
    got = np.asarray(f(ctrl, x))
    assert np.array_equal(got, plain(ctrl, x)), "values bit-for-bit TensorBSpline's"
    assert np.array_equal(lekalo.tensor_bspline_jvp(knots, ctrl, list(degrees), x)[0], got)
    jc, jx = jax.jit(getattr(jax, mode)(f, argnums=(0, 1)))(ctrl, x)
    assert_rel(jc, central(lambda c: plain(c, x), ctrl, 1e-3), f"{mode} in the net")
    assert_rel(jx, central(lambda p: plain(ctrl, p), x, 1e-6), f"{mode} in x")


def test_tensor_vmap_grad_and_kernels():
    knots, ctrl, x, degrees = tensor_case()
    f = lambda c: jnp.sum(tensor_bspline_eval(knots, c, x, degrees) ** 2)  # noqa: E731
    plain = lambda c: float(np.sum(lekalo.TensorBSpline(knots, c, list(degrees))(x) ** 2))  # noqa: E731
    batch = np.stack([ctrl, -0.5 * ctrl])
    g = jax.jit(jax.vmap(jax.grad(f)))(batch)
    for i in range(2):
        assert_rel(g[i], central(plain, batch[i], 1e-5), "vmap(grad) over nets")
    # points of any leading shape
    assert tensor_bspline_eval(knots, ctrl, x.reshape(2, 2, 3), degrees).shape == (2, 2, 2)
    # the NumPy vjp is the transpose of the jvp
    dc, dx = np.cos(ctrl), np.sin(x)
    _, tan = lekalo.tensor_bspline_jvp(knots, ctrl, list(degrees), x, dc, dx)
    cot = np.arange(8.0).reshape(4, 2)
    gc, gx = lekalo.tensor_bspline_vjp(knots, ctrl, list(degrees), x, cot)
    assert gc.shape == ctrl.shape and gx.shape == x.shape
    lhs, rhs = np.sum(cot * tan), np.sum(gc * dc) + np.sum(gx * dx)
    assert abs(lhs - rhs) <= 1e-12 * max(abs(lhs), 1.0)
    lin = lekalo.tensor_bspline_linearize(knots, ctrl, list(degrees), x)
    assert lin["partials"].shape == (4, 3, 2) and lin["first"].shape == (4, 3)
    assert lin["basis"].shape == (4, 3 + 2 + 4)


def test_unsupported_and_bad_input_say_so():
    x, y, t, w = lsq_case()
    with pytest.raises(NotImplementedError, match="data values only"):
        jax.grad(lambda p: jnp.sum(fit_least_squares(y, p, t, 3)))(x)
    with pytest.raises(NotImplementedError, match="data values only"):
        jax.jacfwd(lambda ws: fit_smoothing(x, y, ws, 1e-3))(w)
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda q: jnp.sum(fit_least_squares(q, x, t, 3) ** 2))(y)
    with pytest.raises(lekalo.InputError, match="lam > 0"):
        fit_smoothing(x, y)
    with pytest.raises(lekalo.InputError, match="params must be one a point"):
        fit_least_squares(y, x[:-1], t)
    knots, ctrl, p, degrees = tensor_case()
    with pytest.raises(lekalo.InputError, match=r"shape \(\.\.\., 3\)"):
        tensor_bspline_eval(knots, ctrl, p[:, :2], degrees)
    with pytest.raises(RUNTIME_ERRORS, match="outside the domain"):
        tensor_bspline_eval(knots, ctrl, p + 1.0, degrees).block_until_ready()
    # the kernels' errors name the fix
    with pytest.raises(lekalo.InputError, match="λ = 0"):
        lekalo.smoothing_jvp(x, 0.0, y)
    with pytest.raises(lekalo.Error):
        lekalo.least_squares_jvp(3, t, x, y[:-1])
