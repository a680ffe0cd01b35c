"""The fits on the sphere (``fit_sphere_least_squares``, ``fit_sphere_smoothing``,
``fit_sphere_grid``) and SciPy's three spherical classes of ``lekalo.scipy`` over them, against
SciPy's on the same data: FITPACK's least-squares spline on given knots to rounding, FITPACK's
knots for the smoothing condition and a residual within its tolerance of ``s`` (never above),
FITPACK's interpolant on a grid with every pole condition, and SciPy's errors."""

import subprocess
import sys

import numpy as np
import pytest

import lekalo
import lekalo.scipy as ls

interpolate = pytest.importorskip("scipy.interpolate")


def field(t, p):
    return np.cos(t) ** 2 + 0.5 * np.sin(t) * np.cos(p) - 0.3 * np.sin(t) ** 2 * np.sin(2 * p)


def scattered(seed, m=500):
    rng = np.random.default_rng(seed)
    theta = np.arccos(rng.uniform(-1.0, 1.0, m))
    phi = rng.uniform(0.0, 2 * np.pi, m)
    return theta, phi, field(theta, phi) + 0.01 * rng.standard_normal(m)


def queries(seed, v0=0.0, n=60):
    rng = np.random.default_rng(seed + 100)
    return rng.uniform(0.0, np.pi, n), rng.uniform(v0, v0 + 2 * np.pi, n)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_least_squares_is_fitpacks(seed):
    theta, phi, r = scattered(seed)
    tt, tp = np.linspace(0.3, 2.8, 6), np.linspace(0.5, 5.8, 9)
    w = np.random.default_rng(seed).uniform(0.5, 2.0, theta.size)
    ref = interpolate.LSQSphereBivariateSpline(theta, phi, r, tt, tp, w=w)
    got = ls.LSQSphereBivariateSpline(theta, phi, r, tt, tp, w=w)
    for a, b in zip(got.get_knots(), ref.get_knots()):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-15)
    np.testing.assert_allclose(got.get_coeffs(), ref.get_coeffs(), rtol=0, atol=1e-12)
    assert got.get_residual() == pytest.approx(ref.get_residual(), rel=1e-10)
    qt, qp = queries(seed)
    np.testing.assert_allclose(got.ev(qt, qp), ref.ev(qt, qp), rtol=0, atol=1e-12)
    np.testing.assert_allclose(got(np.sort(qt[:7]), np.sort(qp[:5]), dtheta=1, dphi=1),
                               ref(np.sort(qt[:7]), np.sort(qp[:5]), dtheta=1, dphi=1), rtol=0, atol=1e-10)


@pytest.mark.parametrize("s", [5.0, 1.0, 0.1])
def test_smoothing_has_fitpacks_knots_and_meets_s(s):
    theta, phi, r = scattered(0)
    ref = interpolate.SmoothSphereBivariateSpline(theta, phi, r, s=s)
    got = ls.SmoothSphereBivariateSpline(theta, phi, r, s=s)
    for a, b in zip(got.get_knots(), ref.get_knots()):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-14)
    # FITPACK stops within 0.001·s of s on either side; lekalo within 0.001·s below it
    assert (1 - 1e-3) * s <= got.get_residual() <= s
    qt, qp = queries(0)
    # the weights differ by as much as the residuals within that tolerance move them
    np.testing.assert_allclose(got.ev(qt, qp), ref.ev(qt, qp), rtol=0, atol=1e-3)
    # one value at each pole, whatever the longitude
    for pole in (0.0, np.pi):
        values = got.ev(np.full(8, pole), np.linspace(0, 2 * np.pi, 8))
        np.testing.assert_allclose(values, values[0], rtol=0, atol=1e-12)


def grid(seed, mu=15, mv=20, v0=-1.0):
    rng = np.random.default_rng(seed)
    u = np.linspace(0.1, 3.0, mu)
    v = np.linspace(v0, v0 + 2 * np.pi, mv, endpoint=False)
    return u, v, field(u[:, None], v[None, :]) + 0.01 * rng.standard_normal((mu, mv))


POLES = [
    {},
    {"pole_continuity": True},
    {"pole_values": 1.0, "pole_exact": True},
    {"pole_values": (1.0, 1.0)},
    {"pole_continuity": True, "pole_flat": True},
    {"pole_continuity": (True, False), "pole_values": (None, 1.0)},
]


@pytest.mark.parametrize("poles", POLES)
def test_grid_interpolation_is_fitpacks(poles):
    u, v, r = grid(0)
    ref = interpolate.RectSphereBivariateSpline(u, v, r, **poles)
    got = ls.RectSphereBivariateSpline(u, v, r, **poles)
    for a, b in zip(got.get_knots(), ref.get_knots()):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-14)
    np.testing.assert_allclose(got(u, v), r, rtol=0, atol=1e-12)
    qt, qp = queries(0, v[0])
    np.testing.assert_allclose(got.ev(qt, qp), ref.ev(qt, qp), rtol=0, atol=1e-9)


@pytest.mark.parametrize("poles", [{}, {"pole_values": (1.0, 1.0)}, {"pole_continuity": (True, False), "pole_values": (None, 1.0)}])
@pytest.mark.parametrize("s", [0.01, 0.1])
def test_grid_smoothing_meets_s(poles, s):
    u, v, r = grid(1)
    ref = interpolate.RectSphereBivariateSpline(u, v, r, s=s, **poles)
    got = ls.RectSphereBivariateSpline(u, v, r, s=s, **poles)
    assert (1 - 1e-3) * s <= got.get_residual() <= s
    values = got(u, v)
    assert ((values - r) ** 2).sum() == pytest.approx(got.get_residual(), rel=1e-9)
    # the same knots as FITPACK on this data, where FITPACK met its own condition: with a C1
    # pole and s = 0.01 its rounds end at the interpolant (fp = 0 < s), which is not a
    # smoothing result to compare knots with
    if abs(ref.get_residual() - s) <= 1e-3 * s:
        for a, b in zip(got.get_knots(), ref.get_knots()):
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-14)
    else:
        assert ref.get_residual() == 0.0


def test_native_entries_return_tensor_splines():
    theta, phi, r = scattered(3)
    spline, fp, p, rank, limit = lekalo.fit_sphere_least_squares(theta, phi, r, [1.0, 2.0], [1.5, 3.0, 4.5])
    assert isinstance(spline, lekalo.TensorBSpline) and p is None and limit is None
    assert spline.k == (3, 3) or tuple(spline.k) == (3, 3)
    values = spline(np.column_stack([theta, phi]))
    assert fp == pytest.approx(((values - r) ** 2).sum(), rel=1e-10)
    spline, fp, p, rank, limit = lekalo.fit_sphere_smoothing(theta, phi, r, 0.5)
    assert fp <= 0.5 and limit is None
    u, v, g = grid(2)
    spline, fp, p, rank, limit = lekalo.fit_sphere_grid(u, v, g, 0.0, pole_continuity=(True, True))
    assert fp < 1e-20
    assert spline.t[1][3] == v[0] and spline.t[1][-4] == pytest.approx(v[0] + 2 * np.pi, abs=0)


def test_errors_in_scipys_words():
    theta, phi, r = scattered(4, 50)
    with pytest.raises(ValueError, match=r"theta should be between \[0, pi\]"):
        lekalo.fit_sphere_least_squares(theta + 4.0, phi, r, [1.0], [1.0])
    with pytest.raises(ValueError, match=r"tt should be between \(0, pi\)"):
        lekalo.fit_sphere_least_squares(theta, phi, r, [4.0], [1.0])
    with pytest.raises(ValueError, match=r"s should be positive"):
        lekalo.fit_sphere_smoothing(theta, phi, r, -1.0)
    with pytest.raises(ValueError, match=r"w should be positive"):
        lekalo.fit_sphere_smoothing(theta, phi, r, 1.0, w=-np.ones(50))
    u, v, g = grid(0)
    with pytest.raises(ValueError, match=r"v\[0\] should be between \[-pi, pi\)"):
        lekalo.fit_sphere_grid(u, v + 7.0, g)
    with pytest.raises(ValueError, match="if pole_continuity is False, so must be pole_flat"):
        lekalo.fit_sphere_grid(u, v, g, pole_flat=(True, False))
    with pytest.raises(ValueError, match="one value per node"):
        lekalo.fit_sphere_grid(u, v, g[:, :-1])
    with pytest.raises(ValueError, match="requested theta out of bounds"):
        ls.LSQSphereBivariateSpline(theta, phi, r, [1.0], [1.0])(4.0, 1.0)
    with pytest.raises(ValueError, match="u should be between"):
        ls.RectSphereBivariateSpline(np.r_[0.0, u[1:]], v, g)


def test_hostile_data_is_refused_not_fitted():
    """Data a fit on the sphere cannot honestly be made from is refused, where each was a
    spline with success: the grid's values transposed (the right count in the wrong shape,
    read row by row as if it were (len(u), len(v))), no data or one point (FITPACK's m >= 2),
    and weights that are all 0."""
    u, v, g = grid(0)
    assert g.shape[0] != g.shape[1]
    with pytest.raises(lekalo.InputError, match=r"one value per node of u × v, in the shape"):
        lekalo.fit_sphere_grid(u, v, np.ascontiguousarray(g.T))
    theta, phi, r = scattered(4, 50)
    with pytest.raises(lekalo.InputError, match="need at least 2, got 0"):
        lekalo.fit_sphere_smoothing(theta[:0], phi[:0], r[:0], 1.0)
    with pytest.raises(lekalo.InputError, match="need at least 2, got 1"):
        lekalo.fit_sphere_least_squares(theta[:1], phi[:1], r[:1], [1.0], [1.0])
    with pytest.raises(ValueError, match="every weight is 0"):
        ls.LSQSphereBivariateSpline(theta, phi, r, [1.0], [1.0], w=np.zeros(50))


def test_a_triangle_the_system_cannot_hold_raises_instead_of_aborting():
    """Knots whose least-squares triangle is within lekalo's size limit but more memory than
    the process may have (an address-space limit of 3 GB, 9 GB asked for) raise a named
    InputError: the allocation aborted the interpreter."""
    code = """
import resource, numpy as np, lekalo
resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
rng = np.random.default_rng(1)
th = rng.uniform(0.1, 3.0, 400); ph = rng.uniform(0.1, 6.1, 400)
try:
    lekalo.fit_sphere_least_squares(th, ph, np.cos(th), np.linspace(0.01, 3.1, 600), np.linspace(0.01, 6.2, 600))
except lekalo.InputError as e:
    print("refused:", e)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "more memory than the system gives; give fewer knots" in out.stdout, out.stdout
