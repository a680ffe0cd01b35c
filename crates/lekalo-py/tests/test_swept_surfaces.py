"""``NurbsSurface.revolve``, ``NurbsSurface.extrude`` and ``NurbsSurface.ruled``: exact swept
surfaces from any curve class, checked point by point (a cylinder's radius, a ruled surface's
straight lines between its edge curves), and the errors naming the argument."""

import math

import numpy as np
import pytest

import lekalo


def samples(s, n=9):
    (u0, u1), (v0, v1) = s.domain
    u, v = np.meshgrid(np.linspace(u0, u1, n), np.linspace(v0, v1, n), indexing="ij")
    return s(u, v), (u, v)


def test_a_segment_turned_about_z_is_a_cylinder():
    seg = lekalo.BSplineCurve(1, [0, 0, 1, 1.0], [[2, 0, 1], [2, 0, 3.0]])
    s = lekalo.NurbsSurface.revolve(seg, [0, 0, 0], [0, 0, 1])
    p, _ = samples(s)
    np.testing.assert_allclose(np.hypot(p[..., 0], p[..., 1]), 2.0, rtol=0, atol=1e-14)
    assert p[..., 2].min() == pytest.approx(1.0) and p[..., 2].max() == pytest.approx(3.0)
    half = lekalo.NurbsSurface.revolve(seg, [0, 0, 0], [0, 0, 1], 0.0, math.pi)
    assert samples(half)[0][..., 1].min() > -1e-14


def test_a_circle_extruded_is_a_cylinder_and_two_lines_rule_a_plane():
    circle = lekalo.NurbsCurve.circle([0, 0, 0], [1, 0, 0], [0, 1, 0], 1.0)
    s = lekalo.NurbsSurface.extrude(circle, [0, 0, 4.0])
    p, (_, v) = samples(s)
    np.testing.assert_allclose(np.hypot(p[..., 0], p[..., 1]), 1.0, rtol=0, atol=1e-14)
    np.testing.assert_allclose(p[..., 2], 4.0 * v, rtol=0, atol=1e-14)
    a = lekalo.BSplineCurve(1, [0, 0, 1, 1.0], [[0, 0, 0], [4, 0, 0.0]])
    arc = lekalo.NurbsCurve.circle([0, 3, 1], [1, 0, 0], [0, 0, 1], 1.0)
    r = lekalo.NurbsSurface.ruled(a, arc)
    p, (u, v) = samples(r)
    # the edges are the curves, at equal relative parameter
    np.testing.assert_allclose(p[:, 0], a(u[:, 0] * 1.0), rtol=0, atol=1e-13)
    np.testing.assert_allclose(p[:, -1], arc(u[:, -1]), rtol=0, atol=1e-13)
    # every v-line is straight: the middle point on the chord
    mid = r(u[:, 0], np.full(len(u), 0.5))
    chord = p[:, -1] - p[:, 0]
    off = np.cross(mid - p[:, 0], chord)
    assert np.abs(off).max() < 1e-12


def test_errors_name_the_argument():
    flat = lekalo.BSplineCurve(1, [0, 0, 1, 1.0], [[0, 0], [1, 1.0]])
    with pytest.raises(lekalo.InputError):
        lekalo.NurbsSurface.revolve(flat, [0, 0, 0], [0, 0, 1])
    line = lekalo.BSplineCurve(1, [0, 0, 1, 1.0], [[0, 0, 0], [1, 1, 0.0]])
    with pytest.raises(lekalo.InputError, match="direction|zero"):
        lekalo.NurbsSurface.extrude(line, [0, 0, 0])
    with pytest.raises(lekalo.InputError, match="dimension"):
        lekalo.NurbsSurface.ruled(line, flat)
    with pytest.raises(lekalo.InputError, match="second: expected a BezierCurve"):
        lekalo.NurbsSurface.ruled(line, "not a curve")
