"""lekalo.jax.arc_length and closest_parameter: values lekalo's (`CurveQuery.length`,
`CurveQuery.project`), Jacobians from jacfwd and jacrev (eager, under jit and vmap) against
central finite differences of those values to 1e-7 relative, in the control points, the
points and the knots, and the errors. The mathematics is tested in the core
(crates/lekalo/src/derivatives/geometry_tests.rs, geometry_knots_tests.rs)."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import RUNTIME_ERRORS, assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import arc_length, bspline_eval, closest_parameter  # noqa: E402

KNOTS = np.array([0, 0, 0, 0, 0.3, 0.45, 0.7, 1, 1, 1, 1.0])


def control(dim=2, shift=0.0):
    i = np.arange(7 * dim, dtype=float)
    return (np.sin((i * 7 + 3) * 0.61) * 2 + i // dim + shift).reshape(7, dim)


def query(ctrl):
    return lekalo.CurveQuery(lekalo.BSplineCurve(3, KNOTS, np.asarray(ctrl)))


def plain_length(ctrl):
    return np.array(query(ctrl).length())


def points_near(ctrl):
    c = lekalo.BSplineCurve(3, KNOTS, np.asarray(ctrl))
    near = c(np.array([0.12, 0.4, 0.66, 0.9]))
    return np.asarray(near) + 0.05 * np.cos(np.arange(near.size)).reshape(near.shape)


def plain_params(ctrl, x):
    return np.asarray(query(ctrl).project(x)[0], dtype=float)


@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_arc_length_jacobians_match_central_differences(dim, mode):
    ctrl = control(dim)
    f = lambda c: arc_length(KNOTS, c, 3)  # noqa: E731
    assert float(f(ctrl)) == float(plain_length(ctrl)), "the length is lekalo's"
    assert float(jax.jit(f)(ctrl)) == float(plain_length(ctrl))
    fd = central(plain_length, ctrl, 1e-5)
    for jit in (False, True):
        jac = getattr(jax, mode)(f)
        jac = jax.jit(jac) if jit else jac
        assert_rel(jac(ctrl), fd, f"{mode}, jit={jit}")
    # 1-D control points: a curve in one dimension
    if dim == 1:
        assert_rel(jax.grad(f)(ctrl[:, 0]), fd[:, 0], "1-D control points")


def test_arc_length_under_vmap_and_as_a_loss():
    batch = np.stack([control(), control(shift=1.0) * 1.5])
    f = lambda c: arc_length(KNOTS, c, 3)  # noqa: E731
    vals = jax.vmap(f)(batch)
    grads = jax.jit(jax.vmap(jax.grad(f)))(batch)
    summed = jax.grad(lambda b: jnp.sum(jax.vmap(f)(b)))(batch)
    for i in range(2):
        assert float(vals[i]) == float(plain_length(batch[i]))
        fd = central(plain_length, batch[i], 1e-5)
        assert_rel(grads[i], fd, "vmap(grad)")
        assert_rel(summed[i], fd, "grad(vmap)")
    # a loss mixing the length and a fit to points, through both kernels in one program
    u = jnp.linspace(0, 1, 9)
    target = bspline_eval(KNOTS, jnp.asarray(control()), u, 3) + 0.1
    loss = lambda c: arc_length(KNOTS, c, 3) + jnp.sum((bspline_eval(KNOTS, c, u, 3) - target) ** 2)  # noqa: E731
    loss_np = lambda c: plain_length(c) + np.sum((np.asarray(bspline_eval(KNOTS, c, u, 3)) - target) ** 2)  # noqa: E731
    assert_rel(jax.jit(jax.grad(loss))(control()), central(loss_np, control(), 1e-5), "loss")
    text = jax.jit(jax.grad(f)).lower(control()).as_text()
    assert "lekalo_arc_length_vjp" in text and "callback" not in text


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_closest_parameter_jacobians_match_central_differences(mode):
    for dim in (2, 3):
        ctrl = control(dim)
        x = points_near(ctrl)
        f = lambda c, p: closest_parameter(KNOTS, c, p, 3)  # noqa: E731
        assert np.array_equal(np.asarray(f(ctrl, x)), plain_params(ctrl, x)), "lekalo's parameters"
        fd_c = central(lambda c: plain_params(c, x), ctrl, 1e-5)
        fd_x = central(lambda p: plain_params(ctrl, p), x, 1e-5)
        for jit in (False, True):
            jac = getattr(jax, mode)(f, argnums=(0, 1))
            jac = jax.jit(jac) if jit else jac
            jc, jx = jac(ctrl, x)
            assert_rel(jc, fd_c, f"{mode} in the control points, dim {dim}, jit={jit}")
            assert_rel(jx, fd_x, f"{mode} in the points, dim {dim}, jit={jit}")


def test_closest_parameter_vmap_one_point_ends_and_errors():
    ctrl = control()
    x = points_near(ctrl)
    f = lambda c, p: closest_parameter(KNOTS, c, p, 3)  # noqa: E731
    # one point: a scalar; vmap over points and over curves
    assert f(ctrl, x[1]).shape == ()
    per = jax.vmap(jax.grad(f, argnums=1), in_axes=(None, 0))(ctrl, x)
    for i in range(4):
        fd = central(lambda p: plain_params(ctrl, p[None])[0], x[i], 1e-5)
        assert_rel(per[i], fd, "vmap(grad) over points")
    batch = np.stack([ctrl, ctrl * 1.1 + 0.2])
    jc = jax.jit(jax.vmap(jax.jacrev(f), in_axes=(0, None)))(batch, x)
    for i in range(2):
        assert_rel(jc[i], central(lambda c: plain_params(c, x), batch[i], 1e-5), "vmap(jacrev)")
    # beyond the start the closest point is the start, and stays there
    far = np.asarray(ctrl[0]) - 30.0
    assert float(f(ctrl, far)) == 0.0
    assert np.all(np.asarray(jax.grad(f, argnums=(0, 1))(ctrl, far)[0]) == 0.0)
    with pytest.raises(RUNTIME_ERRORS, match="not finite|NaN|non-finite"):
        jax.block_until_ready(f(ctrl, np.array([np.nan, 0.0])))
    with pytest.raises(lekalo.InputError, match=r"\(\.\.\., 2\)"):
        f(ctrl, np.zeros(3))
    with pytest.raises(NotImplementedError, match="first derivatives"):
        jax.hessian(lambda c: arc_length(KNOTS, c, 3))(ctrl)
    with pytest.raises(lekalo.InputError, match="knots"):
        arc_length(KNOTS[:-1], ctrl, 3)


# The knot moves the knot derivatives are checked along: each interior knot alone, and each
# clamped end with its four copies (a single end copy cannot move both ways and stay sorted).
MOVES = [np.eye(len(KNOTS))[k] for k in range(4, 7)] + [
    np.r_[np.ones(4), np.zeros(7)],
    np.r_[np.zeros(7), np.ones(4)],
]


def along_moves(f, knots, h=1e-6):
    """Central differences of ``f`` along each of ``MOVES``: shape ``f().shape + (moves,)``."""
    cols = [(np.asarray(f(knots + h * e)) - np.asarray(f(knots - h * e))) / (2 * h) for e in MOVES]
    return np.stack(cols, axis=-1)


def length_on(knots, ctrl):
    return np.array(lekalo.CurveQuery(lekalo.BSplineCurve(3, knots, np.asarray(ctrl))).length())


def params_on(knots, ctrl, x):
    q = lekalo.CurveQuery(lekalo.BSplineCurve(3, knots, np.asarray(ctrl)))
    return np.asarray(q.project(x)[0], dtype=float)


@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_arc_length_knot_jacobians_match_central_differences(dim, mode):
    ctrl = control(dim)
    f = lambda k, c: arc_length(k, c, 3)  # noqa: E731
    fd_k = along_moves(lambda k: length_on(k, ctrl), KNOTS)
    fd_c = central(plain_length, ctrl, 1e-5)
    for jit in (False, True):
        jac = getattr(jax, mode)(f, argnums=(0, 1))
        jac = jax.jit(jac) if jit else jac
        jk, jc = jac(KNOTS, ctrl)
        assert_rel(np.stack([np.asarray(jk) @ e for e in MOVES]), fd_k, f"{mode} knots, jit={jit}")
        assert_rel(jc, fd_c, f"{mode} control points with the knots, jit={jit}")
        # the knots outside the domain's ends move with them: no entry of their own
        assert np.all(np.asarray(jk)[[0, 1, 2, 8, 9, 10]] == 0.0)


def test_arc_length_knot_gradient_under_vmap():
    ctrl = control()
    batch = np.stack([KNOTS, KNOTS * 2.0 - 0.5])
    f = lambda k: arc_length(k, ctrl, 3)  # noqa: E731
    grads = jax.jit(jax.vmap(jax.grad(f)))(batch)
    tangents = jax.vmap(lambda k, t: jax.jvp(f, (k,), (t,))[1], in_axes=(0, None))(batch, MOVES[0])
    for i in range(2):
        fd = along_moves(lambda k: length_on(k, ctrl), batch[i])
        assert_rel(np.stack([np.asarray(grads[i]) @ e for e in MOVES]), fd, "vmap(grad) knots")
        assert_rel(tangents[i], fd[0], "vmap(jvp) knots")
    text = jax.jit(jax.grad(f)).lower(KNOTS).as_text()
    assert "lekalo_arc_length_vjp" in text and "callback" not in text


@pytest.mark.parametrize("mode", ["jacfwd", "jacrev"])
def test_closest_parameter_knot_jacobians_match_central_differences(mode):
    for dim in (2, 3):
        ctrl = control(dim)
        # near the curve, and beyond its start (the closest point the start, moving with it)
        x = np.vstack([points_near(ctrl), np.asarray(ctrl[0]) - 30.0])
        f = lambda k, c, p: closest_parameter(k, c, p, 3)  # noqa: E731
        fd_k = along_moves(lambda k: params_on(k, ctrl, x), KNOTS)
        for jit in (False, True):
            jac = getattr(jax, mode)(f, argnums=(0, 1, 2))
            jac = jax.jit(jac) if jit else jac
            jk, jc, jx = jac(KNOTS, ctrl, x)
            got = np.stack([np.asarray(jk) @ e for e in MOVES], axis=-1)
            assert_rel(got, fd_k, f"{mode} knots, dim {dim}, jit={jit}")
            assert_rel(jc, central(lambda c: plain_params(c, x), ctrl, 1e-5), "control points")
            assert_rel(jx, central(lambda p: plain_params(ctrl, p), x, 1e-5), "points")
        assert float(got[-1, 3]) == 1.0, "beyond the start: the start's tangent"


def test_closest_parameter_knot_gradient_under_vmap():
    ctrl = control()
    x = points_near(ctrl)
    f = lambda k, p: closest_parameter(k, ctrl, p, 3)  # noqa: E731
    per = jax.jit(jax.vmap(jax.grad(f), in_axes=(None, 0)))(KNOTS, x)
    for i in range(4):
        fd = along_moves(lambda k: params_on(k, ctrl, x[i][None])[0], KNOTS)
        assert_rel(np.stack([np.asarray(per[i]) @ e for e in MOVES]), fd, "vmap(grad) knots")
    with pytest.raises(RUNTIME_ERRORS, match="not finite|NaN|non-finite"):
        bad = KNOTS.copy()
        bad[5] = np.nan
        jax.block_until_ready(jax.grad(f)(bad, x[0]))
