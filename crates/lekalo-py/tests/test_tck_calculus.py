"""lekalo.scipy's calculus on ``(t, c, k)`` arrays read in place (``tck_derivative``,
``tck_antiderivative``, ``tck_integral``, ``tck_insert``) against SciPy: the derivative of every
order up to the degree (the result has fewer rows than the input), complex and N-D
coefficients, knots that lekalo's curve takes apart (the path it falls back to), and limits
anywhere on the line."""

import numpy as np
import pytest

si = pytest.importorskip("scipy.interpolate")
from lekalo import _lekalo  # noqa: E402
from lekalo import scipy as ls  # noqa: E402


def spline(k, n=40, tail=(), complex_=False, seed=0):
    rng = np.random.default_rng(seed)
    inner = np.sort(rng.uniform(0, 10, n - k - 1))
    t = np.r_[(0.0,) * (k + 1), inner, (10.0,) * (k + 1)]
    c = rng.standard_normal((n,) + tail)
    if complex_:
        c = c + 1j * rng.standard_normal((n,) + tail)
    return t, c


def scale(a):
    return max(1.0, float(np.max(np.abs(a))))


@pytest.mark.parametrize("k", [1, 2, 3, 5])
@pytest.mark.parametrize("tail,complex_", [((), False), ((2, 3), False), ((), True)])
def test_derivatives_of_every_order_and_antiderivatives_match_scipy(k, tail, complex_):
    t, c = spline(k, tail=tail, complex_=complex_)
    # inside the base interval: beyond it the end polynomials of high derivatives grow fast and
    # two evaluation orders differ by more than the values' rounding
    x = np.linspace(0, 10, 101)
    ours, theirs = ls.BSpline(t, c, k), si.BSpline(t, c, k)
    for nu in range(1, k + 1):
        d, e = ours.derivative(nu), theirs.derivative(nu)
        assert d.t.shape == e.t.shape and d.c.shape == e.c.shape
        np.testing.assert_allclose(d(x), e(x), rtol=0, atol=1e-10 * scale(e(x)))
    for nu in (1, 2):
        a, b = ours.antiderivative(nu), theirs.antiderivative(nu)
        np.testing.assert_array_equal(a.t, b.t)
        assert a.c.shape == b.c.shape
        np.testing.assert_allclose(a(x), b(x), rtol=0, atol=1e-10 * scale(b(x)))


def test_tuples_keep_scipys_layout():
    t, c = spline(3)
    tck = (t, np.r_[c, np.zeros(4)], 3)
    for nu in (1, 2, 3):
        ours, theirs = ls.splder(tck, nu), si.splder(tck, nu)
        assert len(ours[1]) == len(theirs[1]) == len(ours[0])
        np.testing.assert_allclose(ours[1], theirs[1], rtol=0, atol=1e-12 * scale(theirs[1]))
    ours, theirs = ls.splantider(tck, 2), si.splantider(tck, 2)
    np.testing.assert_allclose(ours[1], theirs[1], rtol=0, atol=1e-12 * scale(theirs[1]))
    ours, theirs = ls.insert(4.2, tck, m=2), si.insert(4.2, tck, m=2)
    np.testing.assert_array_equal(ours[0], theirs[0])
    np.testing.assert_allclose(ours[1], theirs[1], rtol=0, atol=1e-13 * scale(theirs[1]))


@pytest.mark.parametrize("a,b", [(0.5, 9.5), (9.5, 0.5), (-3.0, 2.0), (3.0, 14.0), (2.0, 2.0), (4.1, 4.2)])
@pytest.mark.parametrize("extrapolate", [True, False])
def test_integrals_anywhere_match_scipy(a, b, extrapolate):
    t, c = spline(3, tail=(2,))
    ours, theirs = ls.BSpline(t, c, 3), si.BSpline(t, c, 3)
    want = theirs.integrate(a, b, extrapolate=extrapolate)
    got = ours.integrate(a, b, extrapolate=extrapolate)
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * scale(want))
    tck = (t, np.r_[c[:, 0], np.zeros(4)], 3)
    assert abs(ls.splint(a, b, tck) - si.splint(a, b, tck)) <= 1e-12 * scale(si.splint(a, b, tck))


def test_repeated_knots_fall_back_to_scipys_rules():
    # a double interior knot: the cubic's second derivative jumps there, its third is not a
    # spline of these knots (SciPy raises), and the first two derivatives agree
    t = np.r_[(0.0,) * 4, 1.0, 2.0, 2.0, 3.0, (4.0,) * 4]
    c = np.arange(len(t) - 4, dtype=float) ** 2
    ours, theirs = ls.BSpline(t, c, 3), si.BSpline(t, c, 3)
    x = np.linspace(0, 4, 41)
    np.testing.assert_allclose(ours.derivative(2)(x), theirs.derivative(2)(x), atol=1e-12)
    with pytest.raises(ValueError):
        theirs.derivative(3)
    with pytest.raises(ValueError):
        ours.derivative(3)


def test_the_bindings_refuse_what_does_not_fit():
    t = np.array([0.0, 0.0, 1.0, 1.0])
    with pytest.raises(_lekalo.Error):
        _lekalo.tck_derivative(t, np.array([[0.0], [1.0]]), 1, 2)
    with pytest.raises(_lekalo.Error):
        _lekalo.tck_integral(t, np.array([[0.0]]), 1, 0.0, 1.0)
    with pytest.raises(_lekalo.Error):
        _lekalo.tck_insert(t, np.array([[0.0], [1.0]]), 1, 2.0)
