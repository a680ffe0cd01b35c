"""The scalar calls of ``lekalo.scipy`` (one number in: a ``float``, NumPy's ``float64`` or a 0-d
float64 array): one Rust call on the arrays in place, whose result must be the array call's at
that one point, bit for bit, in SciPy's type and shape; anything that call does not take (other
dtypes, layouts, derivative orders, periodic extrapolation) goes the array way unchanged."""

import numpy as np
import pytest
from scipy import interpolate as si

from lekalo import scipy as ls

RNG = np.random.default_rng(11)
XS = np.sort(np.r_[0.0, RNG.uniform(0, 10, 38), 10.0])
YS = np.sin(XS) + 0.3 * np.cos(2.7 * XS)


def _points(lo: float, hi: float, breaks: np.ndarray) -> list:
    """Inside, at every kind of breakpoint, at and beyond both ends, and NaN and infinities."""
    span = hi - lo
    inside = list(np.random.default_rng(5).uniform(lo, hi, 25))
    return inside + list(breaks[:: max(1, len(breaks) // 8)]) + [
        lo, hi, np.nextafter(lo, -np.inf), np.nextafter(hi, np.inf),
        lo - 0.3 * span, hi + 0.3 * span, lo - 7 * span, hi + 7 * span,
        np.nan, np.inf, -np.inf,
    ]  # fmt: skip


def _forms(x: float) -> list:
    """The spellings of one number that take the scalar call."""
    return [float(x), np.float64(x), np.array(x)]


def _same(scalar, batch_of_one, theirs) -> None:
    """The scalar call's result is the array call's at the point, bit for bit, with SciPy's
    type and shape."""
    assert type(scalar) is type(theirs), (type(scalar), type(theirs))
    assert np.shape(scalar) == np.shape(theirs)
    assert np.asarray(scalar).dtype == np.asarray(theirs).dtype
    want = np.asarray(batch_of_one).reshape(np.shape(scalar))
    assert np.array_equal(np.asarray(scalar), want, equal_nan=True), (scalar, want)


def _cases_1d():
    t_s = si.make_interp_spline(XS, YS)
    dydx = np.cos(XS)
    pp = si.CubicSpline(XS, YS)  # breakpoints at the data, none repeated
    bp = si.BPoly.from_power_basis(pp)
    return [
        ("BSpline", lambda e: ls.BSpline(t_s.t, t_s.c, 3, extrapolate=e), lambda e: si.BSpline(t_s.t, t_s.c, 3, extrapolate=e)),
        ("CubicSpline", lambda e: ls.CubicSpline(XS, YS, extrapolate=e), lambda e: si.CubicSpline(XS, YS, extrapolate=e)),
        ("PchipInterpolator", lambda e: ls.PchipInterpolator(XS, YS, extrapolate=e), lambda e: si.PchipInterpolator(XS, YS, extrapolate=e)),
        ("Akima1DInterpolator", lambda e: ls.Akima1DInterpolator(XS, YS, extrapolate=e),
         lambda e: si.Akima1DInterpolator(XS, YS, extrapolate=e)),
        ("CubicHermiteSpline", lambda e: ls.CubicHermiteSpline(XS, YS, dydx, extrapolate=e),
         lambda e: si.CubicHermiteSpline(XS, YS, dydx, extrapolate=e)),
        ("PPoly", lambda e: ls.PPoly(pp.c, pp.x, extrapolate=e), lambda e: si.PPoly(pp.c, pp.x, extrapolate=e)),
        ("PPoly decreasing", lambda e: ls.PPoly(ls.PPoly(pp.c, pp.x).c[:, ::-1].copy(), pp.x[::-1].copy(), extrapolate=e),
         lambda e: si.PPoly(pp.c[:, ::-1].copy(), pp.x[::-1].copy(), extrapolate=e)),
        ("BPoly", lambda e: ls.BPoly(bp.c, bp.x, extrapolate=e), lambda e: si.BPoly(bp.c, bp.x, extrapolate=e)),
    ]  # fmt: skip


@pytest.mark.parametrize("extrapolate", [True, False, "periodic"])
@pytest.mark.parametrize("case", _cases_1d(), ids=lambda c: c[0])
def test_scalar_call_is_the_array_call_at_one_point(case, extrapolate):
    _, ours_of, theirs_of = case
    ours, theirs = ours_of(extrapolate), theirs_of(extrapolate)
    for read_coefficients in (False, True):
        if read_coefficients:
            # the cubics evaluate their power coefficients once a large batch has read them
            ours(np.linspace(-1.0, 11.0, 5000))
        for x in _points(0.0, 10.0, XS):
            for xf in _forms(x):
                got = ours(xf)
                _same(got, ours(np.array([x])), theirs(xf))
                if not np.isfinite(x):
                    continue  # lekalo's NaN at infinite x, documented in docs/moving-from-scipy.md
                # NaN where SciPy gives NaN, and SciPy's values elsewhere (to rounding)
                want = theirs(xf)
                assert np.isnan(got) == np.isnan(want), (x, got, want)
                # SciPy's slopes and coefficients are other sums of the same terms (Pchip's
                # differ by a few 1e-12); far beyond the ends a cubic amplifies their rounding
                tol = 1e-11 if -3.0 <= x <= 13.0 else 1e-9
                np.testing.assert_allclose(got, want, rtol=tol, atol=tol)


@pytest.mark.parametrize("case", _cases_1d(), ids=lambda c: c[0])
def test_scalar_derivative_and_other_spellings_take_the_array_way(case):
    _, ours_of, theirs_of = case
    ours, theirs = ours_of(True), theirs_of(True)
    for x in (0.3, 5.0, 10.0, 12.5):
        for nu in (1, 2):
            _same(ours(x, nu), ours(np.array([x]), nu), theirs(x, nu))
        # other spellings of one number: the array way, SciPy's types
        for xo in (np.float32(x), np.array(x, dtype=np.float32), np.array([x])[0:1].reshape(()), int(x), np.int64(int(x))):
            got, want = ours(xo), theirs(xo)
            assert type(got) is type(want) and np.shape(got) == np.shape(want)
            np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-13)


def test_bspline_scalar_call_on_hostile_arrays_is_the_array_call():
    t_s = si.make_interp_spline(XS, YS)
    t, c = t_s.t, t_s.c
    objects = [
        ls.BSpline(t, c.astype(np.float32), 3),
        ls.BSpline(t, c.astype(np.int64), 3),
        ls.BSpline(t, c + 1j * c, 3),
        ls.BSpline(t, c[:, None], 3),
        ls.BSpline(t, np.c_[c, -c], 3),
        ls.BSpline(t, np.r_[c, [np.nan] * 4], 3),  # NaN beyond the n the knots use
        ls.BSpline.construct_fast(t, np.repeat(c, 2)[::2], 3),  # not contiguous
        ls.BSpline.construct_fast(t.astype(np.float32), c, 3),
    ]
    # a NaN coefficient: SciPy's values (NaN where that B-spline is nonzero); lekalo's array
    # call refuses NaN control points
    c_nan = c.copy()
    c_nan[10] = np.nan
    ours, theirs = ls.BSpline(t, c_nan, 3), si.BSpline(t, c_nan, 3)
    for x in _points(0.0, 10.0, XS)[:-3]:
        got, want = ours(x), theirs(x)
        assert type(got) is type(want) and np.isnan(got) == np.isnan(want), (x, got, want)
        np.testing.assert_allclose(got, want, rtol=1e-11, atol=1e-11)
    for b in objects:
        for x in _points(0.0, 10.0, XS):
            for xf in _forms(x):
                got = b(xf)
                want = b(np.array([x]))
                assert np.shape(got) == want.shape[1:]
                assert np.array_equal(got, want[0], equal_nan=True), (x, got, want)


def test_splev_and_univariate_spline_scalar_calls():
    tck = si.splrep(XS, YS)
    us_l, us_s = ls.UnivariateSpline(XS, YS, s=0), si.UnivariateSpline(XS, YS, s=0)
    for x in _points(0.0, 10.0, XS):
        for xf in _forms(x):
            for ext in (0, 1, 2, 3):
                try:
                    want = ls.splev(np.array([x]), tck, ext=ext)
                except ValueError:
                    with pytest.raises(ValueError):
                        ls.splev(xf, tck, ext=ext)
                    continue
                _same(ls.splev(xf, tck, ext=ext), want, si.splev(xf, tck, ext=ext))
            _same(us_l(xf), us_l(np.array([x])), us_s(xf))
            _same(us_l(xf, 1), us_l(np.array([x]), 1), us_s(xf, 1))
    # a tck whose arrays the scalar call cannot read: the array way, the same numbers
    t, c, k = tck
    for tck_odd in ((list(t), list(c), k), (t.astype(np.float32), c, k), (t, c.astype(np.float32), k)):
        for x in (0.3, 10.0, 11.0, np.nan):
            assert np.array_equal(ls.splev(x, tck_odd), ls.splev(np.array([x]), tck_odd)[0], equal_nan=True)


def test_bivariate_scalar_calls_are_the_array_calls():
    x, y = np.linspace(0, 1, 14), np.linspace(0, 2, 11)
    z = np.sin(3 * x)[:, None] * np.cos(2 * y)[None, :] + x[:, None] * y[None, :] ** 2
    ours, theirs = ls.RectBivariateSpline(x, y, z), si.RectBivariateSpline(x, y, z)
    tck = [*ours.tck, 3, 3]
    pts = _points(0.0, 1.0, x)
    for px in pts:
        for py in (0.0, 0.77, 2.0, 2.5, -1.0, np.inf, -np.inf, np.nan):
            for fx, fy in zip(_forms(px), _forms(py)):
                if np.isnan(px) or np.isnan(py):
                    # FITPACK's NaN (the grid's array call refuses a NaN coordinate)
                    for got in (ours(fx, fy), ours(fx, fy, grid=False), ours.ev(fx, fy), ls.bisplev(fx, fy, tck)):
                        assert np.isnan(got)
                    _same(ours(fx, fy), theirs(fx, fy), theirs(fx, fy))
                    _same(ours.ev(fx, fy), ours.ev(np.array([px]), np.array([py])), theirs.ev(fx, fy))
                    continue
                if np.isinf(px) or np.isinf(py):
                    # FITPACK takes an infinite coordinate at its edge, and so do the array
                    # calls at points: the scalar call's value is the edge's, and theirs
                    ex, ey = np.clip(px, 0.0, 1.0), np.clip(py, 0.0, 2.0)
                    _same(ours.ev(fx, fy), ours.ev(np.array([px]), np.array([py])), theirs.ev(fx, fy))
                    for got, edge, want in (
                        (ours(fx, fy), ours(ex, ey), theirs(fx, fy)),
                        (ours.ev(fx, fy), ours.ev(ex, ey), theirs.ev(fx, fy)),
                        (ls.bisplev(fx, fy, tck), ls.bisplev(ex, ey, tck), si.bisplev(fx, fy, tck)),
                    ):
                        _same(got, edge, want)
                        np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-13)
                    continue
                _same(ours(fx, fy), ours(np.array([px]), np.array([py])), theirs(fx, fy))
                np.testing.assert_allclose(ours(fx, fy), theirs(fx, fy), rtol=1e-13, atol=1e-13)
                _same(ours(fx, fy, grid=False), ours(np.array([px]), np.array([py]), grid=False), theirs(fx, fy, grid=False))
                _same(ours.ev(fx, fy), ours.ev(np.array([px]), np.array([py])), theirs.ev(fx, fy))
                _same(ls.bisplev(fx, fy, tck), ls.bisplev(np.array([px]), np.array([py]), tck), si.bisplev(fx, fy, tck))
                _same(ours(fx, fy, dx=1), ours(np.array([px]), np.array([py]), dx=1), theirs(fx, fy, dx=1))
    # a net the scalar call cannot read (float32 coefficients): the array way
    tck32 = [tck[0], tck[1], np.asarray(tck[2], dtype=np.float32), 3, 3]
    assert ls.bisplev(0.3, 0.4, tck32) == ls.bisplev(np.array([0.3]), np.array([0.4]), tck32)


def test_ppoly_scalar_call_sees_changes_in_place():
    pp = si.PPoly.from_spline(si.make_interp_spline(XS, YS))
    ours = ls.PPoly(pp.c.copy(), pp.x.copy())
    before = ours(4.2)
    ours.c[:, :] *= 2.0
    assert ours(4.2) == 2.0 * before
    assert ours(4.2) == ours(np.array([4.2]))[0]
    ours.x[:] = ours.x * 2.0
    assert ours(8.4) == ours(np.array([8.4]))[0]
