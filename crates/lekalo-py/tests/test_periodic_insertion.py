"""Knot insertion into periodic splines (``insert_knot_periodic``,
docs/theory/curves.md#periodic-knot-insertion) against FITPACK's ``insert(..., per=True)``, and
the periodic spline unchanged by it."""

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo
import lekalo.scipy as ls


def periodic_tck():
    x = np.linspace(0.0, 2 * np.pi, 15)
    y = np.sin(x) + 0.5 * np.cos(2 * x)
    y[-1] = y[0]
    return si.splrep(x, y, per=1)


@pytest.mark.parametrize("x", [0.0, 0.2, 1.0, 3.1, 5.9, 2 * np.pi])
def test_fitpacks_periodic_insertion(x):
    t, c, k = periodic_tck()
    n = len(t) - k - 1
    tf, cf, _ = si.insert(x, (t, c, k), per=True)
    t2, c2 = lekalo.insert_knot_periodic(k, t, c[:n], x)
    np.testing.assert_allclose(t2, tf, rtol=0, atol=1e-15)
    np.testing.assert_allclose(c2[:, 0], cf[: len(tf) - k - 1], rtol=0, atol=1e-15)
    # a periodic spline stays the same function (on [0, 2π): inserting at the right end leaves
    # an empty last interval, where splev gives 0)
    xs = np.linspace(0, 2 * np.pi, 50)[:-1]
    np.testing.assert_allclose(si.splev(xs, (t2, c2[:, 0], k)), si.splev(xs, (t, c, k)), atol=1e-14)
    # and lekalo.scipy's BSpline.insert_knot / insert are the same numbers
    spl = ls.BSpline(t, c[:n], k, extrapolate="periodic").insert_knot(x)
    np.testing.assert_allclose(spl.t, tf, atol=1e-15)


def test_refusals():
    k = 3
    t = np.array([0.0] * 4 + [2, 3, 4, 5] + [7.0] * 4)
    c = np.ones(len(t) - k - 1)
    with pytest.raises(lekalo.Error, match="interior knots"):
        lekalo.insert_knot_periodic(k, t, c, 3.5)
    with pytest.raises(lekalo.Error):
        lekalo.insert_knot_periodic(k, t, c, 8.0)
    with pytest.raises(lekalo.Error, match="coefficients"):
        lekalo.insert_knot_periodic(k, t, c[:-1], 1.0)


@pytest.mark.parametrize(("x", "m"), [(0.0, 1), (0.0, 3), (2 * np.pi, 2), (1.0, 4), (3.1, 1)])
def test_fitpacks_insertion_at_any_multiplicity(x, m):
    # insert_knot_raw is FITPACK's fpinst with iopt = 0: past multiplicity k + 1 at the ends of
    # the base interval and past k inside, SciPy's insert gives the same knots and coefficients
    xs = np.linspace(0.0, 2 * np.pi, 12)
    t, c, k = si.splrep(xs, np.sin(xs) + 0.3 * xs)
    n = len(t) - k - 1
    tf, cf, _ = si.insert(x, (t, c, k), m=m)
    t2, c2 = lekalo.insert_knot_raw(k, t, c[:n], x, m)
    np.testing.assert_array_equal(t2, tf)
    np.testing.assert_allclose(c2[:, 0], cf[: len(tf) - k - 1], rtol=0, atol=1e-14)
    spl = ls.BSpline(t, c[:n], k).insert_knot(x, m)
    np.testing.assert_array_equal(spl.t, tf)


def test_raw_insertion_refusals():
    t = np.array([0.0] * 4 + [2, 3] + [7.0] * 4)
    c = np.ones(len(t) - 4)
    with pytest.raises(lekalo.Error, match="outside|domain"):
        lekalo.insert_knot_raw(3, t, c, 7.5)
    with pytest.raises(lekalo.Error, match="coefficients"):
        lekalo.insert_knot_raw(3, t, c[:-1], 1.0)
