"""``lekalo.scipy`` constructions whose arrays lekalo writes once: ``BSpline.design_matrix`` (the
three CSR arrays by ``design_matrix_csr``), ``sproot``'s knot checks, ``LSQUnivariateSpline``'s
residual; each against SciPy's result and SciPy's errors."""

import numpy as np
import pytest
from scipy import interpolate as si

from lekalo import _lekalo
from lekalo import scipy as ls


def _knots(k: int, rng: np.random.Generator) -> np.ndarray:
    inner = np.r_[0.0, np.sort(rng.uniform(0, 10, 9)), 10.0]
    inner[5] = inner[4]  # a double interior knot
    return np.r_[[0.0] * k, inner, [10.0] * k]


@pytest.mark.parametrize("k", [0, 1, 2, 3, 5])
def test_design_matrix_is_scipys_csr_array(k):
    rng = np.random.default_rng(k)
    t = _knots(k, rng)
    x = np.r_[rng.uniform(0, 10, 60), 0.0, 10.0, t[k + 1 : -k - 1] if k else t[1:-1]]
    ours, theirs = ls.BSpline.design_matrix(x, t, k), si.BSpline.design_matrix(x, t, k)
    assert type(ours) is type(theirs) and ours.shape == theirs.shape
    assert ours.indices.dtype == theirs.indices.dtype == np.int32
    assert ours.indptr.dtype == theirs.indptr.dtype
    np.testing.assert_array_equal(ours.indptr, theirs.indptr)
    np.testing.assert_allclose(ours.toarray(), theirs.toarray(), rtol=0, atol=1e-14)
    # every row a partition of unity on its k + 1 consecutive columns
    np.testing.assert_allclose(np.asarray(ours.sum(axis=1)).ravel(), 1.0, rtol=0, atol=1e-14)
    beyond = np.r_[x, -2.5, 12.0, np.nextafter(0.0, -1.0), np.nextafter(10.0, 11.0)]
    for mode in (True, "periodic"):
        ours, theirs = ls.BSpline.design_matrix(beyond, t, k, mode), si.BSpline.design_matrix(beyond, t, k, mode)
        np.testing.assert_array_equal(ours.indices, theirs.indices)
        scale = np.abs(theirs.toarray()).max()
        np.testing.assert_allclose(ours.toarray(), theirs.toarray(), rtol=0, atol=1e-13 * scale)


def test_design_matrix_refuses_what_scipy_refuses():
    t = _knots(3, np.random.default_rng(1))
    for x in ([0.5, np.nan], [0.5, np.inf]):
        with pytest.raises(ValueError):
            si.BSpline.design_matrix(np.array(x), t, 3)
        with pytest.raises(ValueError):
            ls.BSpline.design_matrix(np.array(x), t, 3)
    with pytest.raises(ValueError, match="Out of bounds"):
        ls.BSpline.design_matrix(np.array([0.5, 10.5]), t, 3)
    with pytest.raises(ValueError, match="Length t is not enough"):
        ls.BSpline.design_matrix(np.array([0.5]), t[:7], 3)
    # an empty x without extrapolation: SciPy's ValueError (its min() of nothing); with it, an
    # empty matrix of the right width
    for m in (si, ls):
        with pytest.raises(ValueError):
            m.BSpline.design_matrix(np.array([]), t, 3)
    assert ls.BSpline.design_matrix(np.array([]), t, 3, True).shape == si.BSpline.design_matrix(np.array([]), t, 3, True).shape
    # the binding itself: lekalo's errors, naming the argument
    with pytest.raises(_lekalo.Error, match="x"):
        _lekalo.design_matrix_csr(t, 3, np.array([0.5, np.nan]), True)
    with pytest.raises(_lekalo.Error):
        _lekalo.design_matrix_csr(t, 3, np.array([11.0]), False)
    with pytest.raises(_lekalo.Error):
        _lekalo.design_matrix_csr(t, 30, np.array([1.0]), False)


def test_sproot_checks_the_knots_as_fitpack():
    t = np.r_[[0.0] * 4, np.linspace(0, 10, 12)[1:-1], [10.0] * 4]
    c = np.r_[np.sin(np.linspace(0.1, 7, t.size - 4)), np.zeros(4)]
    np.testing.assert_allclose(ls.sproot((t, c, 3)), si.sproot((t, c, 3)), rtol=0, atol=1e-12)
    for bad in (np.r_[t[:6], t[6] - 0.1, t[7:]][::-1], np.r_[t[:6], t[5], t[7:]]):
        with pytest.raises(TypeError, match="t1<="):
            si.sproot((bad, c, 3))
        with pytest.raises(TypeError, match="t1<="):
            ls.sproot((bad, c, 3))
    # a NaN knot: FITPACK's comparisons let it through, lekalo refuses it in the same words
    with pytest.raises(TypeError, match="t1<="):
        ls.sproot((np.r_[t[:5], np.nan, t[6:]], c, 3))


@pytest.mark.parametrize("weighted", [False, True])
def test_lsq_univariate_residual_is_the_weighted_sum_of_squares(weighted):
    rng = np.random.default_rng(4)
    x = np.sort(rng.uniform(0, 10, 300))
    y = np.sin(x) + 0.1 * rng.standard_normal(300)
    w = rng.uniform(0.5, 2.0, 300) if weighted else None
    knots = np.linspace(1, 9, 7)
    ours, theirs = ls.LSQUnivariateSpline(x, y, knots, w=w), si.LSQUnivariateSpline(x, y, knots, w=w)
    ww = np.ones_like(x) if w is None else w
    # FITPACK's fp: the squares reflected out of the QR, the evaluated sum to rounding
    evaluated = float(np.sum((ww * (ours(x) - y)) ** 2))
    assert abs(ours.get_residual() - evaluated) <= 1e-12 * evaluated
    assert abs(ours.get_residual() - theirs.get_residual()) <= 1e-10 * theirs.get_residual()


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_lsq_univariate_against_scipy_for_every_degree(k):
    rng = np.random.default_rng(10 + k)
    x = np.sort(rng.uniform(-3, 7, 500))
    x[100:103] = x[100]  # repeated abscissae: least squares takes them
    y = np.cos(x) + 0.05 * rng.standard_normal(500)
    w = rng.uniform(0.2, 3.0, 500)
    knots = np.linspace(-2, 6, 11)
    for weights in (None, w):
        ours = ls.LSQUnivariateSpline(x, y, knots, w=weights, k=k)
        theirs = si.LSQUnivariateSpline(x, y, knots, w=weights, k=k)
        np.testing.assert_allclose(ours.get_knots(), theirs.get_knots(), rtol=0, atol=0)
        np.testing.assert_allclose(ours.get_coeffs(), theirs.get_coeffs(), rtol=1e-9, atol=1e-12)
        assert abs(ours.get_residual() - theirs.get_residual()) <= 1e-9 * theirs.get_residual()
    # a spline space that holds the data's polynomial: fp is rounding, as FITPACK's
    exact = ls.LSQUnivariateSpline(x, 1 + x**k, knots, k=k)
    assert exact.get_residual() <= 1e-20 * float(np.sum((1 + x**k) ** 2))


def test_lsq_univariate_refuses_hostile_input():
    x = np.linspace(0, 10, 50)
    y = np.sin(x)
    knots = [2.5, 5.0, 7.5]
    for bad in (np.nan, np.inf, -np.inf):
        yb = y.copy()
        yb[7] = bad
        with pytest.raises(ValueError, match="y"):
            ls.LSQUnivariateSpline(x, yb, knots)
        with pytest.raises(ValueError, match="NaNs or infs"):
            ls.LSQUnivariateSpline(x, yb, knots, check_finite=True)
    # no data: SciPy reads the ends x[0] and x[-1] first and raises an IndexError
    with pytest.raises(IndexError):
        ls.LSQUnivariateSpline(np.array([]), np.array([]), knots)
    with pytest.raises(ValueError, match="increasing"):
        ls.LSQUnivariateSpline(x[::-1], y, knots)
    with pytest.raises(ValueError, match="Schoenberg-Whitney"):
        ls.LSQUnivariateSpline(x, y, [5.0, 2.5])
    # knots crowded in a gap of the data: a basis function without data (Schoenberg-Whitney),
    # which SciPy's fpchec refuses too
    gap = ([3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0], np.r_[x[:10], x[40:]], np.r_[y[:10], y[40:]])
    with pytest.raises(ValueError, match="Schoenberg"):
        ls.LSQUnivariateSpline(gap[1], gap[2], gap[0])
    with pytest.raises(ValueError, match="Schoenberg"):
        si.LSQUnivariateSpline(gap[1], gap[2], gap[0])
    # integer data are read as float64, as SciPy's
    xi, yi = np.arange(30), np.arange(30) % 7
    ours, theirs = ls.LSQUnivariateSpline(xi, yi, [10, 20]), si.LSQUnivariateSpline(xi, yi, [10, 20])
    np.testing.assert_allclose(ours.get_coeffs(), theirs.get_coeffs(), rtol=1e-10, atol=1e-12)
    assert abs(ours.get_residual() - theirs.get_residual()) <= 1e-10 * theirs.get_residual()


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_interpolated_univariate_residual_is_fitpacks_zero(k):
    """SciPy's ``get_residual()`` of an interpolating spline is FITPACK's ``fp = 0.0`` exactly,
    whatever the weights, not the rounding left at the data."""
    rng = np.random.default_rng(20 + k)
    x = np.cumsum(rng.exponential(1.0, 200))
    y = rng.standard_normal(200) * 1e3
    for w in (None, rng.uniform(0.1, 10, 200)):
        ours, theirs = ls.InterpolatedUnivariateSpline(x, y, w=w, k=k), si.InterpolatedUnivariateSpline(x, y, w=w, k=k)
        assert theirs.get_residual() == 0.0
        assert ours.get_residual() == 0.0
        np.testing.assert_allclose(ours(x), y, rtol=0, atol=1e-9 * np.abs(y).max())
        np.testing.assert_allclose(ours.get_coeffs(), theirs.get_coeffs(), rtol=1e-8, atol=1e-8 * np.abs(y).max())
    assert ls.UnivariateSpline(x, y, k=k, s=0).get_residual() == si.UnivariateSpline(x, y, k=k, s=0).get_residual() == 0.0


def test_interpolated_univariate_refuses_what_scipy_refuses():
    x = np.linspace(0, 1, 20)
    y = x**2
    for xb, word in ((x[::-1], "x must be increasing if s > 0"), (np.r_[x[:5], x[4], x[6:]], "x must be strictly increasing")):
        for m in (si, ls):
            with pytest.raises(ValueError, match=word):
                m.InterpolatedUnivariateSpline(xb, y)
    # lengths before strictness, as SciPy's order
    for m in (si, ls):
        with pytest.raises(ValueError, match="same length"):
            m.InterpolatedUnivariateSpline(np.r_[x[:5], x[4], x[6:]], y[:-1])
    for bad in (np.nan, np.inf):
        yb = y.copy()
        yb[3] = bad
        for k in (1, 3, 5):
            with pytest.raises(ValueError):
                ls.InterpolatedUnivariateSpline(x, yb, k=k)
            with pytest.raises(ValueError):
                ls.splrep(x, yb, k=k)
    ours = ls.InterpolatedUnivariateSpline(np.arange(12), np.arange(12) ** 2)
    theirs = si.InterpolatedUnivariateSpline(np.arange(12), np.arange(12) ** 2)
    np.testing.assert_allclose(ours.get_coeffs(), theirs.get_coeffs(), rtol=1e-10, atol=1e-10)


def test_design_matrix_without_scipy_names_the_package(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "scipy.sparse", None)
    with pytest.raises(ImportError, match="install the package 'scipy'"):
        ls.BSpline.design_matrix(np.array([0.5]), np.r_[[0.0] * 4, [1.0] * 4], 3)


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5, 7])
def test_design_matrix_of_many_unsorted_points_is_scipys(k):
    """Many points (the bucket table's spans) against SciPy's matrix, with repeated and end
    points, sorted and unsorted."""
    rng = np.random.default_rng(30 + k)
    t = np.r_[[0.0] * k, np.sort(rng.uniform(0, 10, 40)), 0.0, 10.0, [10.0] * k]
    t.sort()
    x = np.r_[rng.uniform(0, 10, 3000), t[k : -k], [5.0] * 5, 0.0, 10.0]
    for xs in (x, np.sort(x)):
        ours, theirs = ls.BSpline.design_matrix(xs, t, k), si.BSpline.design_matrix(xs, t, k)
        np.testing.assert_array_equal(ours.indices, theirs.indices)
        np.testing.assert_allclose(ours.data, theirs.data, rtol=0, atol=1e-14)
        beyond = np.r_[xs, -1.0, 11.5]
        ours, theirs = ls.BSpline.design_matrix(beyond, t, k, True), si.BSpline.design_matrix(beyond, t, k, True)
        np.testing.assert_array_equal(ours.indices, theirs.indices)
        np.testing.assert_allclose(ours.data, theirs.data, rtol=0, atol=1e-12)
    for bad in (np.nan, np.inf, -np.inf, 10.5):
        with pytest.raises(ValueError):
            ls.BSpline.design_matrix(np.r_[x, bad], t, k)
