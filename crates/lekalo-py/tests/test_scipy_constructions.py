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
    assert ours.get_residual() == float(np.sum((ww * (ours(x) - y)) ** 2))
    assert abs(ours.get_residual() - theirs.get_residual()) <= 1e-10 * theirs.get_residual()
