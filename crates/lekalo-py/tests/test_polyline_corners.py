"""Polyline corner smoothing: one C^k curve that keeps the segments outside the windows."""

import numpy as np
import pytest

import lekalo

ZIGZAG = np.array([[0.0, 0.0], [3.0, 0.0], [4.0, 2.5], [7.0, 1.0], [7.5, 6.0]])


def test_one_curve_through_the_segment_midpoints():
    c = lekalo.smooth_polyline_corners(ZIGZAG, fraction=0.25, continuity=2)
    assert isinstance(c, lekalo.BSplineCurve)
    assert c.degree == 5
    t = np.linspace(*c.domain, 2001)
    p = c(t)
    # every segment midpoint lies on the curve (windows take a quarter of each segment)
    for a, b in zip(ZIGZAG[:-1], ZIGZAG[1:]):
        m = (a + b) / 2
        assert np.min(np.linalg.norm(p - m, axis=1)) < 1e-2
    assert np.allclose(c(c.domain[0]), ZIGZAG[0], atol=1e-14)
    assert np.allclose(c(c.domain[1]), ZIGZAG[-1], atol=1e-14)


def test_length_window_and_errors():
    c = lekalo.smooth_polyline_corners(ZIGZAG, length=0.5, continuity=3)
    assert c.degree == 7
    with pytest.raises(lekalo.Error, match="segment 1"):
        lekalo.smooth_polyline_corners(ZIGZAG, length=1.6)
    with pytest.raises(lekalo.Error, match="3"):
        lekalo.smooth_polyline_corners(ZIGZAG[:2])
    with pytest.raises(lekalo.Error, match="coincide"):
        lekalo.smooth_polyline_corners(np.array([[0, 0], [1, 0], [1, 0], [1, 1.0]]))
    with pytest.raises((lekalo.Error, ValueError), match="not both"):
        lekalo.smooth_polyline_corners(ZIGZAG, fraction=0.2, length=0.5)
