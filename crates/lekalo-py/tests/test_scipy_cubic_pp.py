"""The piecewise cubics of ``lekalo.scipy`` made as SciPy makes them, ``PPoly`` coefficients
written by lekalo from the data: ``CubicSpline`` (SciPy's tridiagonal or cyclic system for the
slopes, ``cubic_spline_pp``: SciPy's coefficients to rounding) and the Hermite family
(``hermite_pp``, ``pchip_pp``, ``akima_pp``: bit for bit), their values far beyond the ends,
SciPy's errors on hostile input, and lekalo's general path (the B-spline of
``make_interp_spline``)."""

import warnings

import numpy as np
import pytest
from scipy import interpolate as si

from lekalo import _lekalo
from lekalo import scipy as ls


def _bits(a) -> np.ndarray:
    a = np.ascontiguousarray(a)
    if np.iscomplexobj(a):
        a = a.view(np.float64)
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


def _data(n: int, tail=(), seed=0, complex_=False):
    rng = np.random.default_rng(seed)
    # uneven steps, some much longer than their neighbours (LAPACK's row swaps)
    x = np.cumsum(rng.uniform(0.05, 1.0, n) * np.where(rng.uniform(size=n) < 0.1, 20.0, 1.0))
    y = rng.standard_normal((n,) + tail)
    if complex_:
        y = y + 1j * rng.standard_normal((n,) + tail)
    return x, y


def _close(ours, theirs, rtol=1e-11):
    """Coefficients equal to rounding: each row (power) within ``rtol`` of its largest entry;
    the values (the last row) bit for bit. Two backward-stable solves of the slopes differ by
    about the system's condition times the rounding unit (1e-13 relative on the steps of
    :func:`_data`, which vary twentyfold), and the cubic coefficient, a difference of slopes
    divided by ``h``, loses up to two digits more; the values are compared at 1e-13."""
    ours, theirs = np.asarray(ours), np.asarray(theirs)
    assert ours.shape == theirs.shape and ours.dtype == theirs.dtype
    for m in range(theirs.shape[0]):
        scale = np.abs(theirs[m]).max() if theirs[m].size else 0.0
        np.testing.assert_allclose(ours[m], theirs[m], rtol=0, atol=rtol * scale, err_msg=f"row {m}")
    np.testing.assert_array_equal(_bits(ours[-1]), _bits(theirs[-1]))


BCS = [
    "not-a-knot",
    "clamped",
    "natural",
    ((1, 0.5), (2, -1.0)),
    ((2, 3.0), "not-a-knot"),
    ("not-a-knot", (1, -2.0)),
    ("natural", "clamped"),
]


@pytest.mark.parametrize("bc", BCS)
@pytest.mark.parametrize("n", [2, 3, 4, 5, 17, 300])
def test_cubic_spline_coefficients_are_scipy_s(bc, n):
    x, y = _data(n, seed=n)
    theirs, ours = si.CubicSpline(x, y, bc_type=bc), ls.CubicSpline(x, y, bc_type=bc)
    _close(ours.c, theirs.c)
    assert ours.c.shape == theirs.c.shape and ours.extrapolate == theirs.extrapolate
    xe = np.linspace(x[0] - 3, x[-1] + 3, 301)
    for nu in (0, 1, 2, 3):
        # 3 beyond the ends the cubic terms amplify the slopes' rounding (see _close)
        want = theirs(xe, nu)
        np.testing.assert_allclose(ours(xe, nu), want, rtol=1e-12, atol=1e-12 * np.abs(want).max())


@pytest.mark.parametrize("n", [2, 3, 4, 5, 9, 200])
def test_periodic_cubic_spline_is_scipy_s(n):
    x, y = _data(n, tail=(2,), seed=3)
    y[-1] = y[0]
    theirs, ours = si.CubicSpline(x, y, bc_type="periodic"), ls.CubicSpline(x, y, bc_type="periodic")
    _close(ours.c, theirs.c)
    assert ours.extrapolate == "periodic"
    xe = np.linspace(x[0] - 2 * (x[-1] - x[0]), x[-1] + 1, 201)
    np.testing.assert_allclose(ours(xe), theirs(xe), rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("axis", [0, 1, -1])
def test_columns_complex_values_and_axes_are_scipy_s(axis):
    x, y = _data(40, tail=(3, 2), seed=5, complex_=True)
    y = np.moveaxis(y, 0, axis)
    # the end values have the trailing shape of y with its interpolation axis first
    bc = ((1, np.full((3, 2), 0.25 - 1j)), "natural")
    theirs, ours = si.CubicSpline(x, y, axis=axis, bc_type=bc), ls.CubicSpline(x, y, axis=axis, bc_type=bc)
    # complex values: lekalo's two real columns, SciPy's complex solve
    _close(ours.c, theirs.c)
    xe = np.linspace(x[0] - 1, x[-1] + 1, 57)
    np.testing.assert_allclose(ours(xe), theirs(xe), rtol=1e-13, atol=1e-13)
    # a real spline with a complex end value becomes complex, as in SciPy
    xr, yr = _data(10, seed=6)
    c = ls.CubicSpline(xr, yr, bc_type=((1, 1j), (2, 0.0))).c
    want = si.CubicSpline(xr, yr, bc_type=((1, 1j), (2, 0.0))).c
    _close(c, want)


def test_the_tridiagonal_solve_is_the_general_path_to_rounding():
    # the slopes of SciPy's system against lekalo's B-spline of the same conditions
    # (make_interp_spline's engines), every kind of end
    for bc in BCS + ["periodic"]:
        x, y = _data(120, seed=11)
        if bc == "periodic":
            y[-1] = y[0]
        s = ls.CubicSpline(x, y, bc_type=bc)
        b = s._bspline_form()
        xe = np.linspace(x[0], x[-1], 777)
        np.testing.assert_allclose(s(xe), b(xe), rtol=0, atol=1e-12 * np.abs(y).max())


def test_empty_columns_and_from_power_basis():
    x = np.arange(5.0)
    s = ls.CubicSpline(x, np.zeros((5, 0)))
    assert s.c.shape == si.CubicSpline(x, np.zeros((5, 0))).c.shape
    y = np.sin(x)
    for bc in ("not-a-knot", "natural", "clamped"):
        b = ls.BSpline.from_power_basis(ls.CubicSpline(x, y, bc_type=bc), bc_type=bc)
        np.testing.assert_allclose(b.c, si.BSpline.from_power_basis(si.CubicSpline(x, y, bc_type=bc), bc_type=bc).c, atol=1e-12)


def _error(module, *args, **kw):
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            module.CubicSpline(*args, **kw)
    except Exception as e:  # noqa: BLE001 - the type and message are compared
        return type(e).__name__, str(e)
    return None


@pytest.mark.parametrize(
    "args, kw",
    [
        ((np.arange(4.0), np.array([0.0, 1.0, 2.0, 5.0])), {"bc_type": "periodic"}),
        ((np.arange(4.0), np.arange(4.0)), {"bc_type": ("periodic", "not-a-knot")}),
        ((np.arange(4.0), np.arange(4.0)), {"bc_type": "weird"}),
        ((np.arange(4.0), np.arange(4.0)), {"bc_type": ("natural", "weird")}),
        ((np.arange(4.0), np.arange(4.0)), {"bc_type": ((3, 0.0), "natural")}),
        ((np.arange(4.0), np.arange(4.0)), {"bc_type": ((1, [0.0, 1.0]), "natural")}),
        ((np.arange(4.0), np.arange(4.0)), {"bc_type": ((1,), "natural")}),
        ((np.arange(4.0), np.arange(4.0)), {"bc_type": ("natural", "natural", "natural")}),
        ((np.arange(4.0), np.array([0.0, np.nan, 1.0, 2.0])), {}),
        ((np.arange(4.0), np.array([0.0, np.inf, 1.0, 2.0])), {}),
        ((np.array([0.0, 2.0, 1.0, 3.0]), np.arange(4.0)), {}),
        ((np.array([0.0, 1.0, 1.0, 3.0]), np.arange(4.0)), {}),
        ((np.array([0.0]), np.array([1.0])), {}),
        ((np.arange(4.0), np.arange(5.0)), {}),
        ((np.arange(4.0) + 0j, np.arange(4.0)), {}),
    ],
)
def test_hostile_input_raises_scipy_s_error(args, kw):
    assert _error(ls, *args, **kw) == _error(si, *args, **kw)


def test_non_finite_end_values_raise_scipy_s_error():
    x, y = _data(6)
    for v in (np.nan, np.inf):
        bc = ((1, v), "natural")
        assert _error(ls, x, y, bc_type=bc) == _error(si, x, y, bc_type=bc)


HERMITE = {
    "CubicHermiteSpline": lambda m, x, y, d: m.CubicHermiteSpline(x, y, d),
    "PchipInterpolator": lambda m, x, y, d: m.PchipInterpolator(x, y),
    "Akima1DInterpolator": lambda m, x, y, d: m.Akima1DInterpolator(x, y, extrapolate=True),
    "makima": lambda m, x, y, d: m.Akima1DInterpolator(x, y, method="makima", extrapolate=True),
}


@pytest.mark.parametrize("name", HERMITE)
@pytest.mark.parametrize("tail", [(), (1,), (3,)])
def test_hermite_coefficients_are_scipy_s_bits(name, tail):
    x, y = _data(150, tail=tail, seed=2)
    d = np.cos(np.arange(y.size)).reshape(y.shape)
    ours, theirs = HERMITE[name](ls, x, y, d), HERMITE[name](si, x, y, d)
    np.testing.assert_array_equal(_bits(ours.c), _bits(theirs.c))


@pytest.mark.parametrize("name", HERMITE)
def test_hermite_family_far_beyond_its_ends_is_scipy_s(name):
    # pieces of 1e-4 over 10^5 points, evaluated up to 1 beyond the ends: the cubic terms of
    # the end pieces dominate there, so coefficients that lost digits would show by 1e-4
    n = 100_000
    x = np.linspace(0.0, 10.0, n)
    y = np.sin(x) + 0.3 * np.sin(37 * x)
    d = np.cos(x)
    ours, theirs = HERMITE[name](ls, x, y, d), HERMITE[name](si, x, y, d)
    far = np.array([-1.0, -0.25, 10.001, 10.5, 11.0])
    many = np.concatenate([far, np.linspace(0, 10, 5000)])  # a large batch reads in place
    for pts in (far, many):
        want = theirs(pts)
        np.testing.assert_allclose(ours(pts), want, rtol=3e-16 * 16, atol=0)
    for p in far:
        assert abs(float(ours(p)) - float(theirs(p))) <= 5e-15 * abs(float(theirs(p)))


def test_the_kernels_refuse_bad_data_by_name():
    x = np.arange(4.0)
    with pytest.raises(_lekalo.InputError, match="finite"):
        _lekalo.pchip_pp(x, np.array([0.0, np.nan, 1.0, 2.0]))
    with pytest.raises(_lekalo.InputError, match="Hermite slopes"):
        _lekalo.cubic_spline_pp(x, np.arange(4.0), (1, np.array([np.nan])), "not-a-knot")
    with pytest.raises(_lekalo.InputError, match="y"):
        _lekalo.akima_pp(x, np.arange(3.0))
    with pytest.raises(_lekalo.InputError, match="dydx"):
        _lekalo.hermite_pp(x, np.arange(4.0), np.arange(3.0))
    with pytest.raises(_lekalo.InputError, match="end"):
        _lekalo.cubic_spline_pp(x, np.arange(4.0), "not-a-knot", (3, np.zeros(1)))
    with pytest.raises(_lekalo.InputError, match="both"):
        _lekalo.cubic_spline_pp(x, np.arange(4.0), "periodic", "not-a-knot")
    with pytest.raises(_lekalo.InputError, match="end derivative"):
        _lekalo.cubic_spline_pp(x, np.arange(4.0), (1, np.zeros(2)), "not-a-knot")
    # other dtypes are read as float64
    ints = _lekalo.cubic_spline_pp(x, np.arange(4, dtype=np.int32), "not-a-knot", "not-a-knot")
    np.testing.assert_array_equal(ints, _lekalo.cubic_spline_pp(x, np.arange(4.0), "not-a-knot", "not-a-knot"))
