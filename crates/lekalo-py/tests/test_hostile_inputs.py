"""Hostile arguments to the Python layer: NumPy arrays of every layout and dtype a caller can
pass, and ``lekalo.scipy`` constructors at their edges. Each is read as its float64 C-order copy
would be, or refused with an exception naming the argument; none hangs or crashes."""

import numpy as np
import pytest

import lekalo.scipy as ls

X = np.linspace(0.0, 1.0, 10)
Y = np.sin(3.0 * X)
XS = np.linspace(0.0, 1.0, 40)


@pytest.fixture(scope="module")
def spline():
    return ls.make_interp_spline(X, Y)


def _read_only(a):
    a = a.copy()
    a.flags.writeable = False
    return a


LAYOUTS = {
    "strided": lambda a: np.repeat(a, 3)[::3],
    "reversed": lambda a: a[::-1].copy()[::-1],
    "big-endian": lambda a: a.astype(">f8"),
    "read-only": _read_only,
    "float32 exact": lambda a: a.astype(np.float32).astype(np.float64).astype(np.float32),
    "huge stride": lambda a: np.lib.stride_tricks.as_strided(
        np.repeat(a, 4096), shape=a.shape, strides=(8 * 4096,)
    ),
}


@pytest.mark.parametrize("name", LAYOUTS)
def test_arrays_of_any_layout_evaluate_as_their_float64_copy(spline, name):
    a = LAYOUTS[name](XS)
    expected = spline(np.ascontiguousarray(a, dtype=np.float64))
    assert np.array_equal(spline(a), expected)
    # and as data of a constructor
    b = LAYOUTS[name](X)
    s = ls.make_interp_spline(b, Y)
    assert np.array_equal(s.c, ls.make_interp_spline(np.ascontiguousarray(b, dtype=float), Y).c)


def test_memory_mapped_and_zero_dimensional_arrays(spline, tmp_path):
    mm = np.memmap(tmp_path / "x.dat", dtype="f8", mode="w+", shape=XS.shape)
    mm[:] = XS
    mm.flush()
    ro = np.memmap(tmp_path / "x.dat", dtype="f8", mode="r", shape=XS.shape)
    assert np.array_equal(spline(ro), spline(XS))
    assert ls.make_interp_spline(ro[:10], Y).c.shape == (10,)
    assert spline(np.array(0.5)).shape == ()
    assert np.array_equal(spline(np.arange(2)), spline(np.array([0.0, 1.0])))


def test_degrees_far_above_the_largest_are_refused_before_their_knots_are_made():
    # k = 10^9 made 2·10^9 not-a-knot knots (16 GB) before any check
    for k in (10**9, 2**70):
        with pytest.raises(ValueError, match="above the largest degree"):
            ls.make_interp_spline(X, Y, k=k)
    with pytest.raises(ValueError, match="Need at least 2000000000002 knots"):
        ls.BSpline(np.arange(10.0), np.ones(5), 10**12)


def test_cubic_spline_of_a_number_is_refused_naming_y():
    # SciPy's axis % y.ndim raised ZeroDivisionError
    with pytest.raises(ValueError, match="`y` must have at least 1 dimension"):
        ls.CubicSpline(np.array(1.0), np.array(1.0))


@pytest.mark.parametrize(
    "call, error, match",
    [
        (lambda: ls.make_interp_spline(X, Y, k=-1), ValueError, "non-negative k"),
        (lambda: ls.make_interp_spline(X, Y, axis=5), np.exceptions.AxisError, "axis 5"),
        (lambda: ls.make_interp_spline(X, Y, t=np.array([])), ValueError, "Got 0 knots"),
        (lambda: ls.make_interp_spline(X, Y, t=np.array([0.5])), ValueError, "Got 1 knots"),
        (lambda: ls.BSpline(np.array([]), np.array([]), 3), ValueError, "Need at least 8 knots"),
        (lambda: ls.BSpline(np.array([0.0]), np.array([1.0]), 0), ValueError, "Need at least 2"),
        (lambda: ls.BSpline(np.arange(10.0), np.ones(5), -1), ValueError, "cannot be negative"),
        (lambda: ls.BSpline(np.arange(10.0), np.ones(6), 3, axis=3), np.exceptions.AxisError, "axis 3"),
        (lambda: ls.make_interp_spline(X, Y)(XS, nu=-1), NotImplementedError, "derivative order nu= -1"),
        (lambda: ls.make_interp_spline(X, Y)(XS, nu=2**70), ValueError, "nu must be a whole number"),
        (lambda: ls.splrep(X, Y, k=0), TypeError, "1 <= k= 0 <=5"),
        (lambda: ls.splev(XS, ls.splrep(X, Y), der=-1), ValueError, "0<=der=-1<=k=3"),
        (lambda: ls.BSpline.design_matrix(XS, np.arange(10.0), 10**9), ValueError, "Length t is not enough"),
    ],
)
def test_constructor_edges_are_refused_as_scipy_refuses_them(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_a_boolean_degree_is_the_integer_it_stands_for():
    # SciPy reads k=True as 1; lekalo indexed the knots with the boolean (a mask) and raised
    # "The truth value of an array ... is ambiguous"
    t, c = np.array([0.0, 0.0, 1.0, 1.0]), np.array([2.0, 4.0])
    s = ls.BSpline(t, c, True)
    assert s.k == 1 and type(s.k) is int
    np.testing.assert_array_equal(s(XS), ls.BSpline(t, c, 1)(XS))
