"""SciPy's knot vectors for interpolation, shared by ``make_interp_spline``, ``CubicSpline`` and
``BSpline.from_power_basis``: not-a-knot, the data sites with clamped ends, and periodic."""

from __future__ import annotations

import numpy as np


def _clamped(inner: np.ndarray, first: float, last: float, m: int) -> np.ndarray:
    """``inner`` between ``m`` copies of ``first`` and of ``last``: one array written once (no
    intermediate copies, each a fresh allocation the size of the data)."""
    n = inner.shape[0]
    t = np.empty(n + 2 * m, dtype=inner.dtype)
    t[:m] = first
    t[m : m + n] = inner
    t[m + n :] = last
    return t


def _not_a_knot(x: np.ndarray, k: int) -> np.ndarray:
    """SciPy's not-a-knot knots (de Boor XIII(12)): data sites for odd ``k`` and mid-points for
    even ``k``, without the ``(k+1)//2`` (``k//2``) first and last, end knots of multiplicity
    ``k + 1`` (FITPACK's choice for ``s = 0``, too)."""
    if k % 2 == 1:
        k2 = (k + 1) // 2
        t = x
    else:
        k2 = k // 2
        t = (x[1:] + x[:-1]) / 2
    t = t[k2:-k2]
    return _clamped(t, x[0], x[-1], k + 1)


def _augknt(x: np.ndarray, k: int) -> np.ndarray:
    """The data sites with end knots of multiplicity ``k + 1``."""
    return _clamped(x, x[0], x[-1], k)


def _periodic_knots(x: np.ndarray, k: int) -> np.ndarray:
    """SciPy's periodic knot vector (``_periodic_knots``)."""
    xc = np.copy(x)
    n = len(xc)
    if k % 2 == 0:
        dx = np.diff(xc)
        xc[1:-1] -= dx[:-1] / 2
    dx = np.diff(xc)
    t = np.zeros(n + 2 * k)
    t[k:-k] = xc
    for i in range(0, k):
        t[k - i - 1] = t[k - i] - dx[-(i % (n - 1)) - 1]
        t[-k + i] = t[-k + i - 1] + dx[i % (n - 1)]
    return t
