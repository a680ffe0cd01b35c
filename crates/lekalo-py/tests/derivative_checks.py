"""What the derivative tests of lekalo.jax and lekalo.torch share, without importing either:
the Jacobian by central differences and the relative comparison at the tolerance the
derivatives promise (1e-7 relative, ``docs/differentiable.md``)."""

import numpy as np

RTOL = 1e-7


def central(f, x, h):
    """Jacobian of f at x by central differences, shape f(x).shape + x.shape."""
    x = np.asarray(x, dtype=float)
    cols = []
    for i in range(x.size):
        e = np.zeros(x.size)
        e[i] = h
        e = e.reshape(x.shape)
        cols.append((np.asarray(f(x + e)) - np.asarray(f(x - e))) / (2 * h))
    return np.stack(cols, axis=-1).reshape(np.shape(f(x)) + x.shape)


def assert_rel(a, b, what):
    """``a`` equals ``b`` to ``RTOL`` relative to the largest entry of ``b`` (at least 1)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, (what, a.shape, b.shape)
    err = np.max(np.abs(a - b)) if a.size else 0.0
    scale = max(np.max(np.abs(b)) if b.size else 0.0, 1.0)
    assert err <= RTOL * scale, f"{what}: error {err:.3e} above {RTOL} x {scale:.3e}"


def interior(knots, degree):
    """The mask of the interior knots (the derivative's; the ends are held fixed)."""
    m = np.zeros(len(knots), bool)
    m[degree + 1 : len(knots) - degree - 1] = True
    return m


def knot_central(f, knots, degree, h=1e-6):
    """The Jacobian of ``f(knots)`` in the knots by central differences in the interior knots,
    zero columns for the end knots (moving those would unsort the knots, and the derivatives
    hold them fixed); shape ``f(knots).shape + knots.shape``."""
    knots = np.asarray(knots, dtype=float)
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
