"""The direct constructions of ``lekalo.scipy``'s piecewise cubics and piecewise polynomials:
``CubicHermiteSpline``, ``PchipInterpolator`` and ``Akima1DInterpolator`` made from 1-D float64
arrays by one lekalo kernel each (``hermite_pp``, ``pchip_pp``, ``akima_pp``: the slopes and
SciPy's power coefficients with the checks folded in), and the breakpoint test of ``PPoly`` and
``BPoly`` (``breakpoints_sorted``). Each against the general path (bit for bit), SciPy's values,
and SciPy's errors on hostile input."""

import numpy as np
import pytest
from scipy import interpolate as si

from lekalo import _lekalo
from lekalo import scipy as ls


def _data(n: int, seed: int = 0):
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(0.2, 1.5, n))
    y = np.sin(x) * 3 + np.where(np.arange(n) % 11 < 3, 0.0, x)  # flat stretches, turns
    dydx = np.cos(x) * 2
    return x, y, dydx


CLASSES = {
    "CubicHermiteSpline": lambda m, x, y, d: m.CubicHermiteSpline(x, y, d),
    "PchipInterpolator": lambda m, x, y, d: m.PchipInterpolator(x, y),
    "Akima1DInterpolator": lambda m, x, y, d: m.Akima1DInterpolator(x, y),
    "makima": lambda m, x, y, d: m.Akima1DInterpolator(x, y, method="makima"),
}


def _bits(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


@pytest.mark.parametrize("name", CLASSES)
@pytest.mark.parametrize("n", [2, 3, 4, 5, 64, 65, 66, 67, 1000])
def test_direct_spline_is_the_general_paths_bit_for_bit(name, n):
    x, y, d = _data(n)
    make = CLASSES[name]
    direct = make(ls, x, y, d)
    # a column of values (n, 1) takes the general path: _prepare_input, the slopes, hermite_pp
    general = make(ls, x, y[:, None], d[:, None])
    np.testing.assert_array_equal(_bits(direct._spline.t), _bits(general._spline.t))
    np.testing.assert_array_equal(_bits(direct._spline.c), _bits(general._spline.c.ravel()))
    assert direct.x is x and direct.axis == 0 and direct.c.shape == (4, n - 1)
    theirs = make(si, x, y, d)
    xe = np.linspace(x[0] - 1, x[-1] + 1, 501)
    for nu in (0, 1):
        want = theirs(xe, nu)
        np.testing.assert_allclose(direct(xe, nu), want, rtol=0, atol=1e-13 * np.nanmax(np.abs(want)))
    assert direct.extrapolate == theirs.extrapolate
    np.testing.assert_allclose(direct.c, theirs.c, rtol=0, atol=1e-12 * np.abs(theirs.c).max())


def _error(make, module, *args):
    try:
        make(module, *args)
    except Exception as e:  # noqa: BLE001 - the type and message are compared
        return type(e), str(e)
    return None


def _hostile(n: int = 100):
    x, y, d = _data(n)
    cases = []
    for what, at, value in [("x", 50, np.nan), ("x", 0, -np.inf), ("x", n - 1, np.inf), ("x", 40, None),
                            ("y", 99, np.nan), ("y", 3, np.inf), ("d", 0, np.nan), ("d", 77, -np.inf)]:
        xx, yy, dd = x.copy(), y.copy(), d.copy()
        arr = {"x": xx, "y": yy, "d": dd}[what]
        arr[at] = arr[at - 1] if value is None else value  # None: a repeated abscissa
        cases.append((f"{what}[{at}]={value}", xx, yy, dd))
    cases.append(("unsorted", x[::-1].copy(), y, d))
    cases.append(("swapped", np.r_[x[1], x[0], x[2:]], y, d))
    cases.append(("huge width", np.r_[-1.7e308, x[1:-1], 1.7e308], y, d))
    cases.append(("one point", x[:1], y[:1], d[:1]))
    cases.append(("empty", x[:0], y[:0], d[:0]))
    cases.append(("lengths", x, y[:-1], d[:-1]))
    cases.append(("slopes length", x, y, d[:-1]))
    cases.append(("integers", np.arange(n), np.arange(n) ** 2, np.arange(n)))
    cases.append(("float32", x.astype(np.float32), y.astype(np.float32), d.astype(np.float32)))
    cases.append(("lists", list(x), list(y), list(d)))
    cases.append(("strided", np.repeat(x, 2)[::2], np.repeat(y, 2)[::2], d))
    cases.append(("overflowing slopes", np.array([0.0, 1e-300, 2e-300, 3e-300]), np.array([0.0, 1e300, 2e300, 2.5e300]),
                  np.zeros(4)))
    return cases


@pytest.mark.parametrize("name", CLASSES)
def test_hostile_input_as_scipy(name):
    make = CLASSES[name]
    for label, x, y, d in _hostile():
        theirs = _error(make, si, x, y, d)
        ours = _error(make, ls, x, y, d)
        if label in ("overflowing slopes", "huge width"):
            # SciPy returns infinite or NaN coefficients; lekalo names the overflow
            assert ours is None or (issubclass(ours[0], ValueError) and "overflow" in ours[1]), ours
            continue
        if theirs is None:
            assert ours is None, (label, ours)
            xe = np.linspace(np.min(x), np.max(x), 7)
            with np.errstate(all="ignore"):
                a, b = make(ls, x, y, d)(xe), make(si, x, y, d)(xe)
            finite = np.isfinite(b)
            assert (np.isfinite(a) == finite).all(), label
            np.testing.assert_allclose(a[finite], b[finite], rtol=1e-12, atol=0, err_msg=label)
        else:
            assert ours is not None, (label, theirs)
            assert issubclass(ours[0], ValueError) and issubclass(theirs[0], ValueError), (label, ours, theirs)
            assert ours[1] == theirs[1], (label, ours, theirs)


def test_the_kernels_refuse_what_they_cannot_take():
    x, y, _ = _data(10)
    with pytest.raises(ValueError, match="one row of values per breakpoint"):
        _lekalo.pchip_pp(x, y[:-1])
    with pytest.raises(ValueError, match="one value per breakpoint"):
        _lekalo.akima_pp(x, np.c_[y, y])
    with pytest.raises(ValueError, match="'akima' or 'makima'"):
        _lekalo.akima_pp(x, y, "spline")
    with pytest.raises(_lekalo.InputError, match="strictly increasing"):
        _lekalo.pchip_pp(x[::-1].copy(), y)


BREAKPOINTS = {
    "increasing": np.arange(5.0),
    "decreasing": np.arange(5.0)[::-1].copy(),
    "repeated": np.array([0.0, 1.0, 1.0, 2.0, 3.0]),
    "repeated decreasing": np.array([3.0, 2.0, 2.0, 1.0, 0.0]),
    "unsorted": np.array([0.0, 2.0, 1.0, 3.0, 4.0]),
    "nan": np.array([0.0, 1.0, np.nan, 3.0, 4.0]),
    "infinite end": np.array([0.0, 1.0, 2.0, 3.0, np.inf]),
    "equal infinities": np.array([0.0, 1.0, 2.0, np.inf, np.inf]),
    "all equal": np.full(5, 2.0),
    "long, one swap": np.r_[np.arange(3000.0)[:2000], 1998.5, np.arange(3000.0)[2001:]],
}


@pytest.mark.parametrize("label", BREAKPOINTS)
@pytest.mark.parametrize("cls", ["PPoly", "BPoly"])
def test_breakpoint_test_is_scipys(label, cls):
    x = BREAKPOINTS[label]
    c = np.random.default_rng(1).standard_normal((3, x.size - 1))
    theirs = _error(lambda m, *a: getattr(m, cls)(*a), si, c, x)
    ours = _error(lambda m, *a: getattr(m, cls)(*a), ls, c, x)
    assert ours == theirs, label
    if theirs is None and np.isfinite(x).all() and x[0] != x[-1]:
        xe = np.linspace(min(x[0], x[-1]), max(x[0], x[-1]), 11)
        np.testing.assert_allclose(getattr(ls, cls)(c, x)(xe), getattr(si, cls)(c, x)(xe), rtol=1e-13, atol=1e-13)
