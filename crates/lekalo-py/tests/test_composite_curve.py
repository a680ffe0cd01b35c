"""``lekalo.composite_curve``: curves joined one after another (``lekalo::Curve::composite``,
IGES's composite curve): each member's shape kept over consecutive parameter intervals, the
highest degree, rational when any member is, and gaps closed within the tolerance or
refused naming the members."""

import numpy as np
import pytest

import lekalo

H = np.sqrt(0.5)


def line():
    return lekalo.BSplineCurve(1, [0.0, 0.0, 1.0, 1.0], [[0.0, 0.0], [1.0, 0.0]])


def arc(start=(1.0, 0.0)):
    # a quarter circle about (1, 1) from (1, 0) to (2, 1)
    return lekalo.NurbsCurve(2, [0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                             [list(start), [2.0, 0.0], [2.0, 1.0]], [1.0, H, 1.0])


def test_members_are_kept_over_consecutive_intervals():
    cubic = lekalo.BezierCurve([[2.0, 1.0], [2.0, 2.0], [1.0, 3.0], [0.0, 3.0]])
    c = lekalo.composite_curve([line(), arc(), cubic])
    assert isinstance(c, lekalo.NurbsCurve) and c.degree == 3
    assert c.domain == (0.0, 3.0)
    t = np.linspace(0.0, 1.0, 21)
    np.testing.assert_allclose(c(t), line()(t), rtol=0, atol=1e-14)
    np.testing.assert_allclose(c(1.0 + t), arc()(t), rtol=0, atol=1e-14)
    np.testing.assert_allclose(c(2.0 + t), cubic(t), rtol=0, atol=1e-14)
    # polynomial members stay polynomial
    p = lekalo.composite_curve([line(), lekalo.BSplineCurve(1, [0.0, 0.0, 2.0, 2.0],
                                                            [[1.0, 0.0], [1.0, 2.0]])])
    assert isinstance(p, lekalo.BSplineCurve) and p.domain == (0.0, 3.0)


def test_gaps_are_closed_within_the_tolerance_or_refused():
    off = arc(start=(1.0 + 1e-6, 0.0))
    with pytest.raises(lekalo.InputError, match="member 2 starts"):
        lekalo.composite_curve([line(), off])
    c = lekalo.composite_curve([line(), off], tolerance=1e-5)
    assert c(1.0).tolist() == [1.0, 0.0]
    for bad in (-1.0, float("nan")):
        with pytest.raises(lekalo.InputError, match="tolerance"):
            lekalo.composite_curve([line(), arc()], tolerance=bad)
    with pytest.raises(lekalo.InputError):
        lekalo.composite_curve([])
    with pytest.raises(lekalo.InputError, match=r"curves\[1\]"):
        lekalo.composite_curve([line(), "not a curve"])
