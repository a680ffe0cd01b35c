"""Hostile input against the piecewise cubics of ``lekalo.scipy`` (``CubicSpline``,
``PchipInterpolator``, ``Akima1DInterpolator``) side by side with SciPy's: NaN and infinities in
``x`` or ``y``, ``x`` not increasing or repeated, data near the largest double, 0, 1 or 2 points,
large and empty arrays, dtypes that are not numbers, ``axis`` out of range or not an integer,
``bc_type``, ``extrapolate`` and ``method`` of every wrong kind, and 2-D and 3-D ``y`` along an
axis. Where SciPy refuses, lekalo refuses with the same exception type; where SciPy computes,
lekalo computes SciPy's values (docs/robustness.md, section 13)."""

import numpy as np
import pytest

import lekalo.scipy as ls

si = pytest.importorskip("scipy.interpolate")

X5 = np.arange(5.0)
Y5 = np.sin(X5)
BIG = np.arange(300_000.0)

CASES = {
    "nan in x": ((np.array([0, np.nan, 2, 3.0]), np.arange(4.0)), {}),
    "inf in x": ((np.array([0, 1, np.inf, 3.0]), np.arange(4.0)), {}),
    "nan in y": ((X5, np.array([0, 1, np.nan, 3, 4.0])), {}),
    "-inf in y": ((X5, np.array([0, 1, -np.inf, 3, 4.0])), {}),
    "decreasing x": ((X5[::-1], Y5), {}),
    "repeated x": ((np.array([0, 1, 1, 2, 3.0]), Y5), {}),
    "x and y near the largest double": ((X5 * 1e307, Y5 * 1e308), {}),
    "y near the largest double": ((X5, Y5 * 1.7e308), {}),
    "x spanning the doubles": ((np.array([-1.7e308, 0, 1.7e308]), np.array([0, 1, 0.0])), {}),
    "subnormal x": ((X5 * 1e-320, Y5), {}),
    "no points": ((np.array([]), np.array([])), {}),
    "one point": ((np.array([0.0]), np.array([1.0])), {}),
    "two points": ((np.array([0.0, 1.0]), np.array([1.0, 2.0])), {}),
    "three points": ((np.array([0.0, 1.0, 2.0]), np.array([1.0, 2.0, 0.0])), {}),
    "lengths differ": ((X5, Y5[:4]), {}),
    "object arrays of numbers": ((np.array([0, 1, 2, 3], dtype=object), np.array([0, 1, 0, 1], dtype=object)), {}),
    "None in an object x": ((np.array([0, 1, None, 3], dtype=object), np.arange(4.0)), {}),
    "complex x": ((X5 + 0j, Y5), {}),
    "strings of numbers as x": ((np.array(["0", "1", "2", "3"]), np.arange(4.0)), {}),
    "strings as y": ((np.arange(4.0), np.array(["a", "b", "c", "d"])), {}),
    "lists of strings": ((["a", "b", "c"], [1, 2, 3]), {}),
    "boolean y": ((X5, np.array([True, False, True, False, True])), {}),
    "integer x and y": ((np.arange(5), np.arange(5) ** 2), {}),
    "2-D x": ((np.arange(6.0).reshape(2, 3), np.arange(6.0).reshape(2, 3)), {}),
    "2-D y along axis 0": ((X5, np.outer(Y5, [1.0, 2.0, 3.0])), {}),
    "2-D y along axis 1": ((X5, np.outer([1.0, 2.0, 3.0], Y5)), {"axis": 1}),
    "3-D y along axis 1": ((X5, np.einsum("i,j,k->ijk", [1.0, -1.0], Y5, [1.0, 2.0, 3.0])), {"axis": 1}),
    "3-D y along axis -1": ((X5, np.einsum("i,j,k->ijk", [1.0, -1.0], [1.0, 2.0, 3.0], Y5)), {"axis": -1}),
    "axis 5": ((X5, np.ones((5, 3))), {"axis": 5}),
    "axis -3": ((X5, np.ones((5, 3))), {"axis": -3}),
    "axis 0.5": ((X5, Y5), {"axis": 0.5}),
    "axis '0'": ((X5, Y5), {"axis": "0"}),
    "axis None": ((X5, Y5), {"axis": None}),
    "axis of the wrong length": ((X5, np.ones((5, 3))), {"axis": 1}),
    "NaN in 2-D y": ((X5, np.where(np.eye(5, 3) > 0, np.nan, 1.0)), {}),
    "y with no columns": ((X5, np.ones((5, 0))), {}),
    "extrapolate 'garbage'": ((X5, Y5), {"extrapolate": "garbage"}),
    "extrapolate 'periodic'": ((X5, Y5), {"extrapolate": "periodic"}),
    "extrapolate 3": ((X5, Y5), {"extrapolate": 3}),
    "extrapolate NaN": ((X5, Y5), {"extrapolate": float("nan")}),
    "300000 points": ((BIG, np.sin(BIG / 1000)), {}),
    "a broadcast y of 10^6 columns": ((X5, np.broadcast_to(0.0, (5, 1_000_000))), {}),
}

BC_TYPES = {
    "garbage": "garbage",
    "an integer": 3,
    "None": None,
    "three ends": ("natural", "natural", "natural"),
    "order 3": ((3, 0.0), (1, 0.0)),
    "order 0": ((0, 0.0), (1, 0.0)),
    "order 1.5": ((1.5, 0.0), (1, 0.0)),
    "a NaN slope": ((1, np.nan), (1, 0.0)),
    "an infinite curvature": ((2, np.inf), "natural"),
    "a value of the wrong shape": ((1, [0.0, 1.0]), (1, 0.0)),
    "a string value": ((1, "a"), (1, 0.0)),
    "periodic with different ends": "periodic",
    "periodic at one end": ("periodic", "natural"),
    "a pair of integers": [1, 2],
    "a dict": {"a": 1},
    "a slope of 1e308": ((1, 1e308), (1, -1e308)),
}


def _outcome(make, probe):
    """``("ok", values at the probe points)`` or ``("error", exception type, message)``."""
    try:
        s = make()
        return ("ok", np.asarray(s(probe)))
    except Exception as e:  # noqa: BLE001 - the type is what is compared
        return ("error", type(e), str(e))


def _compare(case, ours, theirs):
    if theirs[0] == "error":
        assert ours[0] == "error", f"{case}: SciPy raises {theirs[1].__name__}: {theirs[2]}; lekalo computes"
        assert issubclass(ours[1], theirs[1]), (
            f"{case}: SciPy raises {theirs[1].__name__} ({theirs[2]}), lekalo {ours[1].__name__} ({ours[2]})"
        )
        assert ours[2], case
        return
    assert ours[0] == "ok", f"{case}: SciPy computes; lekalo raises {ours[1].__name__}: {ours[2]}"
    a, b = ours[1], theirs[1]
    assert a.shape == b.shape, f"{case}: shape {a.shape} vs SciPy's {b.shape}"
    finite = np.isfinite(b)
    assert (np.isfinite(a) == finite).all(), f"{case}: finite where SciPy's is not, or not where it is"
    scale = np.abs(b[finite]).max(initial=0.0)
    np.testing.assert_allclose(a[finite], b[finite], rtol=1e-9, atol=1e-12 * scale, err_msg=case)


def _probe(args):
    x = np.asarray(args[0])
    if x.dtype.kind in "fiu" and x.ndim == 1 and x.size >= 2 and np.isfinite(x.astype(float)).all():
        xf = x.astype(float)
        return np.r_[xf[:3], (xf[0] + xf[1]) / 2, xf[-1]]
    return np.array([0.5])


# Data SciPy takes and answers with NaN between the points, its arithmetic overflowing without a
# word (x from -1.7e308 to 1.7e308: the width of the domain is not a double); lekalo refuses
# them with a ValueError naming the overflow.
NAN_IN_SCIPY = {"x spanning the doubles"}


@pytest.mark.parametrize("name", ["CubicSpline", "PchipInterpolator", "Akima1DInterpolator"])
@pytest.mark.parametrize("case", list(CASES))
def test_hostile_data_are_refused_or_computed_as_scipy_does(name, case):
    args, kw = CASES[case]
    probe = _probe(args)
    theirs = _outcome(lambda: getattr(si, name)(*args, **kw), probe)
    ours = _outcome(lambda: getattr(ls, name)(*args, **kw), probe)
    if case in NAN_IN_SCIPY:
        mid = np.array([-1e308, 1e308])
        assert np.isnan(getattr(si, name)(*args, **kw)(mid)).all(), case
        assert ours[0] == "error" and issubclass(ours[1], ValueError), f"{name} of {case}: {ours}"
        assert "finite" in ours[2] or "overflows" in ours[2], ours[2]
        return
    _compare(f"{name} of {case}", ours, theirs)


@pytest.mark.parametrize("case", list(BC_TYPES))
def test_hostile_end_conditions_are_refused_or_computed_as_scipy_does(case):
    bc = BC_TYPES[case]
    probe = np.array([0.5, 2.0, 3.5])
    theirs = _outcome(lambda: si.CubicSpline(X5, Y5, bc_type=bc), probe)
    ours = _outcome(lambda: ls.CubicSpline(X5, Y5, bc_type=bc), probe)
    _compare(f"CubicSpline with bc_type {case}", ours, theirs)


@pytest.mark.parametrize("method", ["makima", "akima", "garbage", None, 3])
def test_akima_methods_are_refused_or_computed_as_scipy_does(method):
    probe = np.array([0.5, 2.0, 3.5])
    theirs = _outcome(lambda: si.Akima1DInterpolator(X5, Y5, method=method), probe)
    ours = _outcome(lambda: ls.Akima1DInterpolator(X5, Y5, method=method), probe)
    _compare(f"Akima1DInterpolator with method {method!r}", ours, theirs)


@pytest.mark.parametrize("at", [0, 2, 4])
@pytest.mark.parametrize(
    "call",
    [
        lambda x, y: __import__("lekalo").pchip_slopes(x, y),
        lambda x, y: __import__("lekalo").akima_slopes(x, y, "makima"),
        lambda x, y: __import__("lekalo")._lekalo.pchip_pp(x, y),
        lambda x, y: __import__("lekalo")._lekalo.akima_pp(x, y, "akima"),
    ],
)
def test_lekalo_slopes_name_a_value_that_is_not_finite_as_y(call, at):
    import lekalo

    y = Y5.copy()
    y[at] = np.inf
    with pytest.raises(lekalo.InputError, match=rf"^y\[{at}\] is inf"):
        call(X5, y)
