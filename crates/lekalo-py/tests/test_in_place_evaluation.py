"""lekalo.scipy's objects that evaluate SciPy's arrays in place (``tensor_values``,
``tensor_grid_values``, ``ppoly_values``): values equal to SciPy's, changes made to the arrays
in place seen, NaN and points beyond the box as SciPy treats them."""

import numpy as np
import pytest
from scipy import interpolate as si

from lekalo import _lekalo
from lekalo import scipy as ls


def _nd():
    rng = np.random.default_rng(7)
    t = (np.r_[[0.0] * 3, np.sort(rng.uniform(0, 1, 5)), [1.0] * 3],) * 3
    c = rng.standard_normal((7, 7, 7))
    return t, c


def test_ndbspline_sees_coefficients_changed_in_place_and_treats_nan_as_scipy():
    t, c = _nd()
    ours, theirs = ls.NdBSpline(t, c.copy(), 3), si.NdBSpline(t, c.copy(), 3)
    xi = np.random.default_rng(1).uniform(-0.2, 1.2, (50, 3))
    xi[3, 1] = np.nan
    np.testing.assert_allclose(ours(xi), theirs(xi), rtol=1e-13, atol=1e-13)
    ours.c[2, 3, 4] += 1.0
    theirs.c[2, 3, 4] += 1.0
    np.testing.assert_allclose(ours(xi), theirs(xi), rtol=1e-13, atol=1e-13)
    got, want = ours(xi, extrapolate=False), theirs(xi, extrapolate=False)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    np.testing.assert_allclose(got[~np.isnan(got)], want[~np.isnan(want)], rtol=1e-13, atol=1e-13)
    assert np.isnan(ours(xi)[3])


def test_tensor_values_refuses_bad_arrays_by_name():
    t, c = _nd()
    with pytest.raises(ValueError, match="beyond"):
        _lekalo.tensor_values(t, c, 3, np.zeros((1, 3)), None, "wrap")
    with pytest.raises(ValueError, match="c: axis 1"):
        _lekalo.tensor_values(t, np.ascontiguousarray(c[:, :6]), 3, np.zeros((1, 3)))
    with pytest.raises(ValueError, match="t"):
        _lekalo.tensor_values((t[0][::-1], t[1], t[2]), c, 3, np.zeros((1, 3)))


def test_bivariate_values_clamp_to_the_box_and_see_changes():
    x, y = np.linspace(0, 1, 12), np.linspace(0, 2, 9)
    z = np.sin(3 * x)[:, None] * np.cos(y)[None, :]
    ours, theirs = ls.RectBivariateSpline(x, y, z), si.RectBivariateSpline(x, y, z)
    px, py = np.array([-0.5, 0.3, 1.5]), np.array([0.5, 2.5, -1.0])
    np.testing.assert_allclose(ours.ev(px, py), theirs.ev(px, py), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(ours(px, np.sort(py)), theirs(px, np.sort(py)), rtol=1e-13, atol=1e-13)
    tck = [np.array(a) for a in theirs.tck] + [3, 3]
    tck[2][5] += 2.0
    np.testing.assert_allclose(ls.bisplev(px, np.sort(py), tck), si.bisplev(px, np.sort(py), tck), rtol=1e-13, atol=1e-13)


def test_ppoly_in_place_with_repeated_breakpoints_and_changes():
    rng = np.random.default_rng(3)
    # an empty interior piece (SciPy also evaluates an empty last piece beyond the end, which
    # lekalo skips for the last non-empty one)
    x = np.array([0.0, 1.0, 1.0, 2.0, 3.0])
    c = rng.standard_normal((4, 4, 2))
    ours, theirs = ls.PPoly(c.copy(), x), si.PPoly(c.copy(), x)
    xp = np.r_[rng.uniform(-1, 4, 40), x]
    np.testing.assert_allclose(ours(xp), theirs(xp), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(ours(xp, 2), theirs(xp, 2), rtol=1e-13, atol=1e-13)
    ours.c[1, 2, 0] += 5.0
    theirs.c[1, 2, 0] += 5.0
    np.testing.assert_allclose(ours(xp), theirs(xp), rtol=1e-13, atol=1e-13)
    assert ours(0.5).shape == theirs(0.5).shape
