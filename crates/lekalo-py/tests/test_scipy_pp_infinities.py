"""``PPoly`` and ``BPoly`` of ``lekalo.scipy`` where IEEE infinities enter: at infinite points,
where a value overflows and where a power of the local coordinate does, SciPy's values (its end
piece evaluated by its own formula), for the array and the scalar calls, degrees 0 to 5, both
orders of breakpoints, every ``extrapolate``."""

import numpy as np
import pytest
from scipy import interpolate as si

from lekalo import scipy as ls


def _same(a, b) -> bool:
    """Equal bit for bit, NaN equal to NaN (any payload)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.all((a == b) | (np.isnan(a) & np.isnan(b))))


POINTS = np.array([np.inf, -np.inf, np.nan, 0.5, 1e300, -1e300, 1e120, -3e102])


@pytest.mark.parametrize("cls", ["PPoly", "BPoly"])
@pytest.mark.parametrize("k", range(6))
@pytest.mark.parametrize("descending", [False, True])
def test_infinite_points_and_overflows_are_scipy_s(cls, k, descending):
    rng = np.random.default_rng(k)
    x = np.array([0.0, 1.0, 2.0, 3.0])
    if descending:
        x = x[::-1].copy()
    for trial in range(6):
        c = rng.integers(-2, 3, size=(k + 1, 3)).astype(float)
        if trial == 0:
            c[:] = 0
        elif trial == 1:
            c[:-1] = 0
        elif trial == 2:
            c = c[:, :, None] * np.array([1.0, -1.0])
        for ext in (True, False, "periodic"):
            theirs = getattr(si, cls)(c, x, extrapolate=ext)
            ours = getattr(ls, cls)(c, x, extrapolate=ext)
            for nu in range(min(k, 2) + 1):
                with np.errstate(all="ignore"):
                    want = theirs(POINTS, nu)
                assert _same(ours(POINTS, nu), want), (c.tolist(), ext, nu)
                if c.ndim == 2:
                    for p in POINTS:
                        with np.errstate(all="ignore"):
                            want = theirs(p, nu)
                        assert _same(ours(p, nu), want), (c.tolist(), ext, nu, p)


def test_a_constant_ppoly_at_infinity_is_its_end_piece():
    p = ls.PPoly(np.array([[1.0, 2.0, 3.0]]), np.array([0.0, 1.0, 2.0, 3.0]))
    assert p(np.inf) == 3.0 and p(-np.inf) == 1.0
    np.testing.assert_array_equal(p(np.array([-np.inf, np.inf])), [1.0, 3.0])
    assert np.isnan(p(np.nan))
    q = ls.PPoly(np.array([[1.0, 2.0, 3.0]]), np.array([0.0, 1.0, 2.0, 3.0]), extrapolate=False)
    assert np.isnan(q(np.inf))
