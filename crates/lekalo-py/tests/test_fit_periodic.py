"""Closed fits, cross-checked against SciPy's ``splrep(per=1)`` inside the tests.

The periodic least-squares and smoothing-condition problems have unique answers, solved here by
a cyclic banded QR and in FITPACK by its own rotations. With given knots the coefficients agree to
1e-9 of the data's scale (values of order 1); the smoothing condition's knots agree to rounding
(1e-14 of the period), and its curves as far as the two stopping rules allow (see that test).
"""

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo

RNG = np.random.default_rng(5)


def periodic_data(n=121):
    x = np.sort(RNG.random(n)) * 2 * np.pi
    x[0], x[-1] = 0.0, 2 * np.pi
    y = np.cos(x) + 0.5 * np.sin(3 * x) + 0.02 * RNG.standard_normal(n)
    y[-1] = y[0]
    return x, y


def scipy_coefficients(tck):
    t, c, k = tck
    return t, c[: len(t) - k - 1]


def test_fit_periodic_with_knots_is_scipys_splrep_per():
    x, y = periodic_data()
    interior = np.linspace(0, 2 * np.pi, 9)[1:-1]
    curve, report = lekalo.fit_periodic(x, y, t=interior)
    t, c = scipy_coefficients(si.splrep(x, y, t=interior, per=1))
    assert np.abs(curve.knots - t).max() <= 1e-14 * 2 * np.pi
    assert np.abs(curve.control[:, 0] - c).max() <= 1e-9
    assert report["n_ctrl"] == len(c)


def test_fit_periodic_smoothing_condition_is_scipys_splrep_per():
    # Both stop the search for the smoothing parameter on the same final knots once the residual
    # is near s: FITPACK within 0.1% of s on either side, lekalo within [(1 - 0.1%) s, s]. The
    # knots are the same to rounding; the two smoothing parameters may differ inside that band,
    # so the curves are compared at the size such a residual change allows: an RMS difference at
    # the data within sqrt(0.2% of s / n) (of order 1e-3 here, against values of order 1).
    x, y = periodic_data()
    s = 0.025
    curve, report = lekalo.fit_periodic(x, y, s=s)
    tck, fp, ier, _ = si.splrep(x, y, s=s, per=1, full_output=1)
    t, c = scipy_coefficients(tck)
    assert ier <= 0 and abs(fp - s) <= 1e-3 * s
    assert (1 - 1e-3) * s <= report["weighted_rss"] <= s
    assert len(curve.knots) == len(t)
    assert np.abs(curve.knots - t).max() <= 1e-14 * 2 * np.pi
    assert len(curve.control) == len(c)
    n = len(x) - 1
    diff = curve(x[:n])[:, 0] - si.splev(x[:n], tck)
    assert np.sqrt((diff**2).mean()) <= np.sqrt(2e-3 * s / n)


def closure_gap(curve, a, b):
    """Largest difference of value and derivatives up to degree - 1 across the seam."""
    return max(
        np.abs(curve(np.array([a]), nu) - curve(np.array([b]), nu)).max()
        for nu in range(curve.degree)
    )


def test_fit_closed_closes_the_polygon_smoothly_within_s():
    a = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    r = 1 + 0.2 * np.cos(5 * a) + 0.01 * RNG.standard_normal(len(a))
    pts = np.column_stack([r * np.cos(a), r * np.sin(a)])
    s = 0.02
    curve, u = lekalo.fit_closed(pts, s=s)
    assert len(u) == len(pts) + 1 and u[0] == 0.0
    assert closure_gap(curve, u[0], u[-1]) <= 1e-9
    rss = ((curve(u[:-1]) - pts) ** 2).sum()
    assert rss <= s * (1 + 1e-12)


def test_closed_fits_name_bad_input():
    x, y = periodic_data()
    with pytest.raises(lekalo.Error, match="s"):
        lekalo.fit_periodic(x, y, s=-1.0)
    with pytest.raises(lekalo.Error):
        lekalo.fit_periodic(x[:1], y[:1])
    with pytest.raises(lekalo.Error):
        lekalo.fit_periodic(x, y, s=np.nan)
    with pytest.raises(lekalo.Error):
        lekalo.fit_closed(np.zeros((5, 2)), s=0.1)
