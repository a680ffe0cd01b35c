"""lekalo.jax.bspline_surface_eval and tensor_bspline_eval for a few points on a large net,
where the FFI targets evaluate in place on the operand buffers and check only the knots and
the block of the net each point's cell reads (``lekalo::derivatives::BorrowedSurface``,
``BorrowedTensor``): the values are bit-for-bit lekalo's built object's, the derivatives
match central differences (relative 1e-7) eagerly, under jit and under vmap, and a bad number
inside a block used, or a point outside the domain, gives lekalo's message as the whole-net
path does, never a value."""

import numpy as np
import pytest

jax = pytest.importorskip("jax")
import jax.numpy as jnp  # noqa: E402

import lekalo  # noqa: E402
from jax_support import RUNTIME_ERRORS, assert_rel, central, x64  # noqa: E402,F401  (x64: autouse fixture)
from lekalo.jax import bspline_surface_eval, tensor_bspline_eval  # noqa: E402

DEGREES = (2, 3)


def knots(n, p, rng, double=None):
    inner = np.linspace(0, 1, n - p + 1)[1:-1] + rng.uniform(-0.002, 0.002, n - p - 1)
    if double is not None:
        inner[double + 1] = inner[double]  # a double knot
    return np.r_[[0.0] * (p + 1), inner, [1.0] * (p + 1)]


def surface_case(dim=3, seed=7):
    """A 40 × 36 net: one to three pairs read far fewer points than the net has."""
    rng = np.random.default_rng(seed)
    ku, kv = knots(40, 2, rng, double=12), knots(36, 3, rng)
    net = rng.uniform(-1, 1, (40, 36, dim))
    u = np.array([0.5 * (ku[20] + ku[21]), ku[15], 1.0])  # inside, on the double knot, the end
    v = np.array([0.5 * (kv[10] + kv[11]), 0.3, 0.0])
    return ku, kv, net, u, v


def surface_ref(ku, kv, net, u, v):
    u, v = (np.ascontiguousarray(a, dtype=float) for a in (u, v))
    return lekalo.bspline_surface_jvp(*DEGREES, ku, kv, np.ascontiguousarray(net), u, v)[0]


TENSOR_DEGREES = (2, 1, 3)


def tensor_case(seed=9):
    """A 14 × 12 × 13 net of scalars in 2-D: a point reads 24 of its 2184 points."""
    rng = np.random.default_rng(seed)
    kn = tuple(knots(n, p, rng) for n, p in zip((14, 12, 13), TENSOR_DEGREES))
    net = rng.uniform(-1, 1, (14, 12, 13, 2))
    x = np.array([[0.31, 0.52, 0.77], [kn[0][5], 0.1, kn[2][6]]])
    return kn, net, x


def tensor_ref(kn, net, x):
    x = np.ascontiguousarray(x, dtype=float)
    return lekalo.tensor_bspline_jvp(list(kn), np.ascontiguousarray(net), list(TENSOR_DEGREES), x)[0]


@pytest.mark.parametrize("where", ["eager", "jit", "vmap"])
def test_surface_small_calls_match_the_built_surface(where):
    ku, kv, net, u, v = surface_case()
    f = lambda c, a, b: bspline_surface_eval(ku, kv, c, a, b, *DEGREES)  # noqa: E731
    if where == "vmap":
        got = jax.jit(jax.vmap(f))(np.stack([net, -net]), np.stack([u, u]), np.stack([v, v]))
        assert np.array_equal(np.asarray(got[1]), surface_ref(ku, kv, -net, u, v))
        got = got[0]
    else:
        got = (jax.jit(f) if where == "jit" else f)(net, u, v)
    assert np.array_equal(np.asarray(got), surface_ref(ku, kv, net, u, v))
    # the Jacobians at the interior pair and the one on the double knot (central differences
    # need an open cell around the point)
    a, b = u[:1], v[:1]
    for mode in ("jacfwd", "jacrev"):
        jac = getattr(jax, mode)(f, argnums=(0, 1, 2))
        if where == "vmap":
            jn, ja, jb = jax.jit(jax.vmap(jac))(np.stack([net, 2 * net]), np.stack([a, a]), np.stack([b, b]))
            jn, ja, jb = jn[1], ja[1], jb[1]
            c = 2 * net
        else:
            jn, ja, jb = (jax.jit(jac) if where == "jit" else jac)(net, a, b)
            c = net
        assert_rel(jn, central(lambda x: surface_ref(ku, kv, x, a, b), c, 1e-3), f"{mode} in the net")
        assert_rel(ja, central(lambda x: surface_ref(ku, kv, c, x, b), a, 1e-6), f"{mode} in u")
        assert_rel(jb, central(lambda x: surface_ref(ku, kv, c, a, x), b, 1e-6), f"{mode} in v")
    # the gradient touches the (p + 1)(q + 1) net points of the pair's cell only
    g = jax.grad(lambda c: jnp.sum(f(c, a, b)))(net)
    assert np.count_nonzero(np.asarray(g[..., 0])) == 12


@pytest.mark.parametrize("where", ["eager", "jit", "vmap"])
def test_tensor_small_calls_match_the_built_spline(where):
    kn, net, x = tensor_case()
    f = lambda c, p: tensor_bspline_eval(kn, c, p, TENSOR_DEGREES)  # noqa: E731
    if where == "vmap":
        got = jax.jit(jax.vmap(f))(np.stack([net, -net]), np.stack([x, x]))
        assert np.array_equal(np.asarray(got[1]), tensor_ref(kn, -net, x))
        got = got[0]
    else:
        got = (jax.jit(f) if where == "jit" else f)(net, x)
    assert np.array_equal(np.asarray(got), tensor_ref(kn, net, x))
    p = x[:1]
    for mode in ("jacfwd", "jacrev"):
        jac = getattr(jax, mode)(f, argnums=(0, 1))
        if where == "vmap":
            jn, jx = jax.jit(jax.vmap(jac))(np.stack([net, 2 * net]), np.stack([p, p]))
            jn, jx = jn[1], jx[1]
            c = 2 * net
        else:
            jn, jx = (jax.jit(jac) if where == "jit" else jac)(net, p)
            c = net
        assert_rel(jn, central(lambda a: tensor_ref(kn, a, p), c, 1e-3), f"{mode} in the net")
        assert_rel(jx, central(lambda a: tensor_ref(kn, c, a), p, 1e-6), f"{mode} in x")
    g = jax.grad(lambda c: jnp.sum(f(c, p)))(net)
    assert np.count_nonzero(np.asarray(g[..., 0])) == 3 * 2 * 4


def test_surface_bad_numbers_in_a_block_used_give_lekalos_message():
    ku, kv, net, u, v = surface_case()
    a, b = u[:1], v[:1]
    f = jax.jit(lambda k1, k2, c, s, t: bspline_surface_eval(k1, k2, c, s, t, *DEGREES))
    loss = lambda c, s, t: jnp.sum(bspline_surface_eval(ku, kv, c, s, t, *DEGREES))  # noqa: E731
    grad = jax.jit(jax.grad(loss, argnums=(0, 1, 2)))
    i = int(np.searchsorted(ku, a[0], side="right")) - 1
    j = int(np.searchsorted(kv, b[0], side="right")) - 1
    nan_knot = ku.copy()
    nan_knot[i] = np.nan
    unsorted = kv.copy()
    unsorted[j + 1] = kv[j - 1]
    bad_net = net.copy()
    bad_net[i - 1, j - 2, 1] = np.inf
    for args, message in (
        ((nan_knot, kv, net), "must be finite"),
        ((ku, unsorted, net), "sorted|non-decreasing"),
        ((ku, kv, bad_net), "must be finite"),
    ):
        with pytest.raises(RUNTIME_ERRORS, match=message):
            jax.block_until_ready(f(*args, a, b))
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        jax.block_until_ready(grad(bad_net, a, b))
    with pytest.raises(RUNTIME_ERRORS, match=r"1\.5 is outside the domain"):
        jax.block_until_ready(f(ku, kv, net, np.array([1.5]), b))
    with pytest.raises(RUNTIME_ERRORS, match="lekalo.jax.bspline_surface_eval"):
        jax.block_until_ready(grad(net, a, np.array([np.nan])))
    # a bad number far from the pair is not read: the values are the surface's
    far = net.copy()
    far[-1, -1] = np.nan
    assert np.array_equal(np.asarray(f(ku, kv, far, a, b)), surface_ref(ku, kv, net, a, b))
    # the whole-net path (many pairs) refuses it
    many = np.linspace(0.0, 1.0, 600)
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        jax.block_until_ready(f(ku, kv, far, many, many))


def test_tensor_bad_numbers_in_a_block_used_give_lekalos_message():
    kn, net, x = tensor_case()
    p = x[:1]
    f = jax.jit(lambda k0, c, q: tensor_bspline_eval((k0, kn[1], kn[2]), c, q, TENSOR_DEGREES))
    grad = jax.jit(jax.grad(lambda c, q: jnp.sum(tensor_bspline_eval(kn, c, q, TENSOR_DEGREES)), argnums=(0, 1)))
    spans = [int(np.searchsorted(k, c, side="right")) - 1 for k, c in zip(kn, p[0])]
    nan_knot = kn[0].copy()
    nan_knot[spans[0] + 1] = np.nan
    bad_net = net.copy()
    bad_net[spans[0] - 1, spans[1], spans[2] - 3, 0] = np.nan
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        jax.block_until_ready(f(nan_knot, net, p))
    for call in (lambda: f(kn[0], bad_net, p), lambda: grad(bad_net, p)):
        with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
            jax.block_until_ready(call())
    with pytest.raises(RUNTIME_ERRORS, match=r"outside the domain"):
        jax.block_until_ready(f(kn[0], net, np.array([[0.5, 1.25, 0.5]])))
    far = net.copy()
    far[0, 0, 0] = np.nan
    assert np.array_equal(np.asarray(f(kn[0], far, p)), tensor_ref(kn, net, p))
    many = np.full((200, 3), 0.5)
    with pytest.raises(RUNTIME_ERRORS, match="must be finite"):
        jax.block_until_ready(f(kn[0], far, many))


def test_wrong_shapes_and_empty_points_are_refused_before_the_call():
    ku, kv, net, u, v = surface_case()
    with pytest.raises(lekalo.InputError, match="knots_u must be 1-D with 43 knots"):
        bspline_surface_eval(ku[1:], kv, net, u, v, *DEGREES)
    with pytest.raises(lekalo.InputError, match="one shape"):
        bspline_surface_eval(ku, kv, net, u, v[:2], *DEGREES)
    empty = bspline_surface_eval(ku, kv, net, np.zeros(0), np.zeros(0), *DEGREES)
    assert empty.shape == (0, 3)
    kn, tnet, _ = tensor_case()
    with pytest.raises(lekalo.InputError, match=r"x must have shape \(\.\.\., 3\)"):
        tensor_bspline_eval(kn, tnet, np.zeros((2, 2)), TENSOR_DEGREES)
