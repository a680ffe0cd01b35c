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


def big_spline(n=5000, seed=3):
    # the benchmark's data: a jittered uniform grid on [0, 10]
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 10.0, n)
    x[1:-1] += rng.uniform(-0.3, 0.3, n - 2) * (10.0 / (n - 1))
    s = si.make_interp_spline(x, np.sin(x) + 0.5 * np.cos(3.1 * x))
    return s.t, s.c


def test_one_pass_calculus_on_a_large_spline_matches_scipy():
    # the benchmark's shape: thousands of coefficients, the one-pass kernels (AVX2 where the
    # processor has it) against SciPy's NumPy passes, knots bit for bit
    t, c = big_spline()
    tck = (t, np.r_[c, np.zeros(4)], 3)
    x = np.linspace(0, 10, 1001)
    ours, theirs = ls.BSpline(t, c, 3), si.BSpline(t, c, 3)
    # a running sum of n terms: rounding up to n·eps times the sum of their magnitudes
    eps = np.finfo(float).eps
    sum_bound = len(c) * eps * float(np.sum(np.abs(c * (t[4:] - t[:-4]))))
    d, e = ours.derivative(), theirs.derivative()
    np.testing.assert_array_equal(d.t, e.t)
    # one difference quotient a row, SciPy's operations in another order: a few ulps apart
    np.testing.assert_allclose(d.c, e.c, rtol=4 * eps, atol=0)
    d, e = ours.derivative(2), theirs.derivative(2)
    np.testing.assert_array_equal(d.t, e.t)
    np.testing.assert_allclose(d(x), e(x), rtol=0, atol=1e-10 * scale(e(x)))
    for nu in (1, 2):
        a, b = ours.antiderivative(nu), theirs.antiderivative(nu)
        np.testing.assert_array_equal(a.t, b.t)
        np.testing.assert_allclose(a(x), b(x), rtol=0, atol=10 * (1 + nu) * sum_bound)
    o, s = ls.splder(tck), si.splder(tck)
    np.testing.assert_array_equal(o[0], s[0])
    assert o[1].shape == s[1].shape and o[2] == s[2]
    np.testing.assert_allclose(o[1], s[1], rtol=4 * eps, atol=0)
    o, s = ls.splantider(tck), si.splantider(tck)
    np.testing.assert_array_equal(o[0], s[0])
    assert o[1].shape == s[1].shape and o[2] == s[2]
    np.testing.assert_allclose(o[1], s[1], rtol=0, atol=sum_bound)


@pytest.mark.parametrize(
    "a,b", [(0.5, 9.5), (9.5, 0.5), (-3.0, 2.0), (3.0, 14.0), (2.0, 2.0), (-5.0, -1.0), (-1.0, -5.0), (12.0, 11.0)]
)
def test_splint_is_bspline_integrate_bit_for_bit(a, b):
    # splint's direct call on the tuple's arrays against BSpline.integrate without
    # extrapolation (the general path): the same bits, and FITPACK's value
    t, c = big_spline(400)
    tck = (t, np.r_[c, np.zeros(4)], 3)
    got = ls.splint(a, b, tck)
    want = float(ls.BSpline(t, c, 3).integrate(a, b, extrapolate=False))
    assert type(got) is float
    assert got == want or (got == 0.0 and want == 0.0)
    assert abs(got - si.splint(a, b, tck)) <= 1e-12 * scale(c)
    if max(min(a, b), 0.0) >= min(max(a, b), 10.0):
        # an empty interval (after clipping to the base interval) is +0.0, as FITPACK's
        assert np.copysign(1.0, got) == 1.0


def test_splint_hostile_limits_and_dtypes():
    t, c = big_spline(200)
    tck = (t, np.r_[c, np.zeros(4)], 3)
    assert np.isnan(ls.splint(np.nan, 3.0, tck)) and np.isnan(si.splint(np.nan, 3.0, tck))
    assert np.isnan(ls.splint(3.0, np.nan, tck))
    ti = np.r_[[0] * 4, np.arange(1, 10), [10] * 4]
    ci = np.arange(len(ti))
    assert ls.splint(1, 7, (ti, ci, 3)) == pytest.approx(si.splint(1, 7, (ti, ci, 3)), abs=1e-12)


def test_insert_checks_the_knots_and_coefficients_it_reads():
    t, c = big_spline(300)
    n = len(c)
    tck = (t, np.r_[c, np.zeros(4)], 3)
    # valid input: SciPy's knots, coefficients to rounding, int dtypes read as floats
    # (SciPy's padding after the coefficients is not initialised: compared up to it)
    for x, m in ((0.0, 1), (2.5, 1), (2.5, 3), (10.0, 1)):
        o, s = ls.insert(x, tck, m), si.insert(x, tck, m)
        np.testing.assert_array_equal(o[0], s[0])
        np.testing.assert_allclose(o[1][: n + m], s[1][: n + m], rtol=0, atol=1e-13)
        assert not o[1][n + m :].any()
    ti = np.r_[[0] * 4, np.arange(1, 10), [10] * 4]
    ci = np.r_[np.arange(len(ti) - 4), [0] * 4]
    o, s = ls.insert(4.5, (ti, ci, 3)), si.insert(4.5, (ti, ci, 3))
    m = len(o[0]) - 4
    np.testing.assert_allclose(o[1][:m], s[1][:m], rtol=0, atol=1e-13)
    assert not o[1][m:].any()
    # a NaN coefficient away from x is copied, as FITPACK copies it; where x's interval reads
    # it, refused by name
    far = 200
    cn = c.copy()
    cn[far] = np.nan
    tck_n = (t, np.r_[cn, np.zeros(4)], 3)
    o, s = ls.insert(1.0, tck_n), si.insert(1.0, tck_n)
    np.testing.assert_array_equal(np.isnan(o[1][: n + 1]), np.isnan(s[1][: n + 1]))
    near = float(t[far + 2] + t[far + 3]) / 2
    with pytest.raises(ValueError, match="coefficients after insertion"):
        ls.insert(near, tck_n)
    # a knot out of order or NaN: copied away from x, refused near it
    # (x where the binary search over the other knots still finds x's interval: NaN reads as
    # above every x, the small knot as below)
    for bad, x in ((np.nan, (t[far - 2] + t[far - 1]) / 2), (float(t[far - 50]), (t[far + 1] + t[far + 2]) / 2)):
        tb = t.copy()
        tb[far] = bad
        o = ls.insert(1.0, (tb, tck[1], 3))
        np.testing.assert_array_equal(o[0][far + 1], bad)
        with pytest.raises(ValueError, match="knot"):
            ls.insert(float(x), (tb, tck[1], 3))
    # outside the base interval, NaN, empty and too short
    for x in (-1.0, 11.0):
        with pytest.raises(ValueError):
            ls.insert(x, tck)
    with pytest.raises(ValueError):
        ls.insert(np.nan, tck)
    with pytest.raises(ValueError):
        ls.insert(1.0, (np.zeros(0), np.zeros(0), 3))
    with pytest.raises(ValueError):
        _lekalo.tck_insert(t, c[: n - 1].reshape(-1, 1), 3, 1.0)


def test_sproot_on_many_coefficients_and_hostile_input():
    # about 38 zeros spread over thousands of spans, most of them in blocks the sign test skips
    n = 3000
    tz = np.r_[(0.0,) * 4, np.linspace(0, 10, n - 2)[1:-1], (10.0,) * 4]
    cz = np.sin(np.linspace(0.1, 120, n))
    tck = (tz, np.r_[cz, np.zeros(4)], 3)
    ours, theirs = ls.sproot(tck, mest=n), si.sproot(tck, mest=n)
    assert ours.shape == theirs.shape
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-12)
    # integer arrays are read as floats
    ti = np.r_[[0] * 4, np.arange(1, 10), [10] * 4]
    ci = np.r_[np.arange(len(ti) - 4) - 5, [0] * 4]
    np.testing.assert_allclose(ls.sproot((ti, ci, 3)), si.sproot((ti, ci, 3)), atol=1e-12)
    # a NaN coefficient is refused by lekalo as bad input (not as FITPACK's knot TypeError)
    cn = tck[1].copy()
    cn[500] = np.nan
    with pytest.raises(ValueError):
        ls.sproot((tz, cn, 3), mest=n)
    # too few coefficients, a decreasing end knot
    with pytest.raises(ValueError, match="coefficients"):
        ls.sproot((tz, cz[:100], 3))
    tb = tz.copy()
    tb[1] = -1.0
    with pytest.raises(TypeError, match="t1<="):
        ls.sproot((tb, tck[1], 3))
