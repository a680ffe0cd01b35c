"""lekalo.scipy against scipy.interpolate where the inputs are not finite: NaN or infinite data,
coefficients and coordinates give NaN where SciPy gives NaN, the box's edge where FITPACK takes
an infinite coordinate there, and the error where SciPy raises. Also PCHIP's slopes, which
take SciPy's operations in SciPy's order (the same bits)."""

import numpy as np
import pytest

si = pytest.importorskip("scipy.interpolate")
import lekalo.scipy as ls  # noqa: E402
from lekalo import _lekalo  # noqa: E402

X, Y = np.linspace(0.0, 1.0, 8), np.linspace(0.0, 2.0, 9)
Z = np.sin(3 * X)[:, None] * np.cos(2 * Y)[None, :] + X[:, None] * Y[None, :]


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("where", [(0, 0), (2, 5), (7, 8)])
@pytest.mark.parametrize("options", [dict(), dict(s=0.1), dict(s=10.0), dict(kx=2, ky=1, bbox=[-1.0, 2.0, None, None])])
def test_rect_bivariate_spline_of_values_not_finite_is_nan(bad, where, options):
    z = Z.copy()
    z[where] = bad
    theirs, ours = si.RectBivariateSpline(X, Y, z, **options), ls.RectBivariateSpline(X, Y, z, **options)
    # FITPACK: the knots of interpolation whatever s, fp = 0
    for a, b in zip(ours.get_knots(), theirs.get_knots()):
        np.testing.assert_array_equal(a, b)
    assert ours.fp == theirs.fp == 0.0
    assert ours.get_residual() == theirs.get_residual()
    # every coefficient SciPy leaves NaN is NaN here (here all are)
    c_theirs, c_ours = theirs.get_coeffs(), ours.get_coeffs()
    assert c_ours.shape == c_theirs.shape
    assert np.isnan(c_theirs).sum() > 0
    assert np.isnan(c_ours).all()
    # inside the box, where SciPy's values are NaN, so are these (here all are; how far
    # FITPACK's rotations spread the NaN depends on the degrees)
    xs, ys = np.linspace(0.0, 0.9, 7), np.linspace(0.0, 1.8, 6)
    want = theirs(xs, ys)
    assert np.isnan(want).any()
    assert np.isnan(ours(xs, ys)).all()
    assert np.isnan(ours.ev(xs, ys[:1].repeat(7))).all()
    assert np.isnan(ours.ev(0.5, 0.5))


@pytest.mark.parametrize("axis", ["x", "y"])
def test_rect_bivariate_spline_of_nan_coordinates_raises_as_scipy(axis):
    x, y = X.copy(), Y.copy()
    (x if axis == "x" else y)[3] = np.nan
    with pytest.raises(ValueError) as theirs:
        si.RectBivariateSpline(x, y, Z)
    with pytest.raises(ValueError) as ours:
        ls.RectBivariateSpline(x, y, Z)
    assert str(ours.value) == str(theirs.value) == f"{axis} must be strictly increasing"


def test_rect_bivariate_spline_ev_takes_infinite_coordinates_at_the_edge():
    theirs, ours = si.RectBivariateSpline(X, Y, Z), ls.RectBivariateSpline(X, Y, Z)
    inf = np.inf
    px = np.array([inf, -inf, 0.5, 0.5, inf, -inf, np.nan, 0.25, inf])
    py = np.array([0.5, 0.5, inf, -inf, inf, -inf, 0.5, np.nan, np.nan])
    want = theirs.ev(px, py)
    got = ours.ev(px, py)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-13)
    # the edge's value, bit for bit
    edge = ours.ev(np.clip(px, 0.0, 1.0), np.clip(py, 0.0, 2.0))
    assert np.array_equal(got, edge, equal_nan=True)
    # every point alone gives the batch's bits
    for i in range(len(px)):
        assert np.array_equal(ours.ev(float(px[i]), float(py[i])), got[i], equal_nan=True)
    # the same through bisplev's grid and the derivatives' path
    tck = [*ours.tck, 3, 3]
    np.testing.assert_allclose(
        ls.bisplev(np.array([-inf, 0.5, inf]), np.array([-inf, 1.0, inf]), tck),
        si.bisplev(np.array([-inf, 0.5, inf]), np.array([-inf, 1.0, inf]), tck),
        rtol=1e-13, atol=1e-13,
    )
    np.testing.assert_allclose(ours.ev(px[:6], py[:6], dx=1), theirs.ev(px[:6], py[:6], dx=1), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize(
    "ends",
    [dict(x0=True), dict(x1=True), dict(y0=True), dict(y1=True), dict(x0=True, x1=True, y1=True), dict(bbox=True)],
    ids=lambda e: "-".join(e),
)
@pytest.mark.parametrize("options", [dict(), dict(s=0.1), dict(kx=1, ky=2), dict(kx=5, ky=4), dict(kx=2, ky=3, s=5.0)])
def test_rect_bivariate_spline_of_an_infinite_box_end_is_scipy_s(ends, options):
    x, y, bbox = X.copy(), Y.copy(), [None] * 4
    if ends.get("x0"):
        x[0] = -np.inf
    if ends.get("x1"):
        x[-1] = np.inf
    if ends.get("y0"):
        y[0] = -np.inf
    if ends.get("y1"):
        y[-1] = np.inf
    if ends.get("bbox"):
        bbox = [-np.inf, None, None, np.inf]
    theirs = si.RectBivariateSpline(x, y, Z, bbox=bbox, **options)
    ours = ls.RectBivariateSpline(x, y, Z, bbox=bbox, **options)
    # FITPACK's knots of interpolation with the infinite ends, fp = 0, NaN coefficients
    for a, b in zip(ours.get_knots(), theirs.get_knots()):
        np.testing.assert_allclose(a, b, rtol=1e-15, atol=0.0)
    assert ours.fp == theirs.fp == 0.0
    assert ours.get_coeffs().shape == theirs.get_coeffs().shape
    assert np.isnan(ours.get_coeffs()).all() and np.isnan(theirs.get_coeffs()).all()
    # every value NaN, as SciPy's: grid, points, one point, bisplev, integral, derivatives
    xs, ys = np.linspace(0.0, 0.9, 7), np.linspace(0.0, 1.8, 6)
    kx, ky = ours.degrees
    d = (1, 0) if kx > 1 else (0, 1)
    for got, want in [
        (ours(xs, ys), theirs(xs, ys)),
        (ours.ev(xs, ys[:1].repeat(7)), theirs.ev(xs, ys[:1].repeat(7))),
        (ours.ev(0.5, 0.5), theirs.ev(0.5, 0.5)),
        (ours(0.5, 0.5), theirs(0.5, 0.5)),
        (ours(xs, ys, *d), theirs(xs, ys, *d)),
        (ls.bisplev(xs, ys, (*ours.tck, *ours.degrees)), si.bisplev(xs, ys, (*theirs.tck, *theirs.degrees))),
        (ours.integral(0.1, 0.5, 0.2, 1.0), theirs.integral(0.1, 0.5, 0.2, 1.0)),
    ]:
        assert np.shape(got) == np.shape(want)
        assert np.isnan(got).all() and np.isnan(want).all()
    d_ours, d_theirs = ours.partial_derivative(*d), theirs.partial_derivative(*d)
    assert d_ours.degrees == d_theirs.degrees == (kx - d[0], ky - d[1])
    for a, b in zip(d_ours.tck, d_theirs.tck):
        np.testing.assert_allclose(a, b, rtol=1e-15, atol=0.0)
    assert np.isnan(d_ours(xs, xs, grid=False)).all() and np.isnan(d_theirs(xs, xs, grid=False)).all()


def test_rect_bivariate_spline_of_an_infinite_coordinate_beyond_a_finite_bbox_raises():
    x = X.copy()
    x[-1] = np.inf
    with pytest.raises(ValueError):
        si.RectBivariateSpline(x, Y, Z, bbox=[0.0, 1.0, None, None])
    with pytest.raises(ValueError):
        ls.RectBivariateSpline(x, Y, Z, bbox=[0.0, 1.0, None, None])


@pytest.mark.parametrize("bad", [np.nan, np.inf])
@pytest.mark.parametrize("extrapolate", [True, False])
@pytest.mark.parametrize("tail", [(), (2,)])
def test_bspline_with_coefficients_not_finite_evaluates_as_scipy(bad, extrapolate, tail):
    rng = np.random.default_rng(3)
    k, n = 3, 12
    t = np.r_[[0.0] * k, np.linspace(0.0, 10.0, n - k + 1), [10.0] * k]
    c = rng.standard_normal((n,) + tail)
    c[5] = bad
    theirs, ours = si.BSpline(t, c, k, extrapolate), ls.BSpline(t, c, k, extrapolate)
    # inside, at every knot, outside, and at NaN
    x = np.r_[np.linspace(-1.0, 11.0, 97), t, np.nan]
    for nu in (0, 1, 2):
        want, got = theirs(x, nu), ours(x, nu)
        assert got.shape == want.shape
        assert np.array_equal(np.isnan(got), np.isnan(want)), nu
        assert np.array_equal(np.isinf(got), np.isinf(want)), nu
        ok = np.isfinite(want)
        assert ok.any() and (~ok).any()
        np.testing.assert_allclose(got[ok], want[ok], rtol=1e-12, atol=1e-12 * np.abs(want[ok]).max())
    # one number: the array call's value at it
    for v in (0.5, 4.2, 9.9):
        assert np.array_equal(ours(v), ours(np.array([v]))[0], equal_nan=True)


def test_pchip_slopes_are_scipys_bits():
    rng = np.random.default_rng(11)
    for trial in range(60):
        n = int(rng.integers(3, 40))
        x = np.unique(rng.uniform(0.0, 10.0, n))
        y = rng.standard_normal(len(x)) * 10.0 ** rng.uniform(-6, 6)
        if trial % 3 == 0:
            y = np.cumsum(np.abs(y))  # monotone, the harmonic mean at every interior node
        want = si.PchipInterpolator._find_derivatives(x, y, np)
        got = np.asarray(_lekalo.pchip_slopes(x, y)).ravel()
        assert np.array_equal(got, want), trial
