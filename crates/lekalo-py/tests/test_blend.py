"""Blending (document 001): w_k, deformations, blend splines, corner transitions."""

import pickle

import numpy as np
import pytest

import lekalo


def test_jump_polynomial():
    for k in range(0, 5):
        w = lekalo.JumpPolynomial(k)
        assert w.degree == 2 * k + 1
        u = np.linspace(0, 1, 101)
        v = w(u)
        assert v.shape == u.shape
        assert v[0] == 0.0 and v[-1] == 1.0
        assert np.allclose(v + w(1 - u), 1.0, atol=1e-14)  # w(u) + w(1 - u) = 1
        assert np.isclose(w.integral_to_half(), 1 / 8 if k == 0 else w.integral_to_half())
        assert np.all(np.diff(v) >= -1e-15)


def test_deformation_joins_with_continuity():
    a = lekalo.BezierCurve([[0, 0], [1, 2], [2, 0]])
    b = lekalo.BezierCurve([[0, 0], [1, -1], [2, 0]])
    k = 3
    d = lekalo.Deformation(a, b, continuity=k)
    # at u = 0 the deformation has first's derivatives up to k, at u = 1 second's
    da, db, dd = a.derivatives(0.0, k), b.derivatives(1.0, k), d.derivatives(np.array([0.0, 1.0]), k)
    assert np.allclose(dd[0], da, atol=1e-12)
    assert np.allclose(dd[1], db, atol=1e-12)
    bz = d.to_bezier()
    u = np.linspace(0, 1, 33)
    assert np.allclose(bz(u), d(u), atol=1e-12)
    assert np.allclose(d(u, nu=1), d.derivatives(u, 1)[:, 1], atol=1e-12)
    nested = lekalo.Deformation(d, a.to_bspline(), 1)
    assert nested(u).shape == (33, 2)
    with pytest.raises(lekalo.Error, match="expected a lekalo curve"):
        lekalo.Deformation(a, "not a curve")


@pytest.mark.parametrize("local, arcs", [("parabolas", "uniform_angle"), ("arcs", "uniform_angle"), ("arcs", "rational_quadratic")])
def test_blend_spline_passes_through_points(local, arcs):
    pts = np.array([[0, 0], [1, 1], [2, 0.5], [3, 1.5], [4, 0]], dtype=float)
    s = lekalo.BlendSpline(pts, local=local, continuity=2, arcs=arcs)
    assert np.allclose(s(np.array(s.parameters)), pts, atol=1e-12)
    assert s.segment_count == len(pts) - 1
    if local == "parabolas" or arcs == "rational_quadratic":
        n = s.to_nurbs()
        t = np.linspace(*s.domain, 57)
        nt = np.linspace(*n.domain, 57)
        assert np.allclose(n(nt), s(t), atol=1e-9)
    if local == "parabolas":
        # closed: C^2 across the seam too
        closed = lekalo.BlendSpline(pts, local=local, closed=True)
        a, b = closed.domain
        assert np.allclose(closed.derivatives(a, 2), closed.derivatives(b, 2), atol=1e-9)


def test_corner_transition():
    before = lekalo.BSplineCurve(1, [0, 0, 1, 1], [[0, 0], [1, 0]])
    after = lekalo.BSplineCurve(1, [0, 0, 1, 1], [[1, 0], [1, 1]])
    c = lekalo.CornerTransition(before, 0.5, after, 0.5, continuity=2)
    lo, hi = c.domain
    d0 = c.derivatives(lo, 2)
    assert np.allclose(d0[0], before(0.5), atol=1e-12)
    d1 = c.derivatives(hi, 2)
    assert np.allclose(d1[0], after(0.5), atol=1e-12)
    with pytest.raises(lekalo.Error):
        lekalo.JumpPolynomial(10**6)


def test_blend_errors_are_named():
    with pytest.raises(lekalo.Error, match="local: unknown"):
        lekalo.BlendSpline([[0, 0], [1, 1]], local="splines")
    with pytest.raises(lekalo.Error, match="coincide"):
        lekalo.BlendSpline([[0, 0], [0, 0], [1, 1]])


def test_blend_objects_pickle():
    a = lekalo.BezierCurve([[0, 0], [1, 2], [2, 0]])
    b = lekalo.BezierCurve([[0, 0], [1, -1], [2, 0]])
    line = lekalo.BSplineCurve(1, [0, 0, 1, 1], [[0, 0], [1, 0]])
    up = lekalo.BSplineCurve(1, [0, 0, 1, 1], [[1, 0], [1, 1]])
    objs = [
        lekalo.JumpPolynomial(3),
        lekalo.Deformation(a, b, 2),
        lekalo.BlendSpline(np.array([[0, 0], [1, 1], [2, 0.5], [3, 1.5]]), local="arcs"),
        lekalo.CornerTransition(line, 0.5, up, 0.5, 2),
    ]
    for o in objs:
        back = pickle.loads(pickle.dumps(o))
        u = np.linspace(*(getattr(o, "domain", (0.0, 1.0))), 11)
        assert np.array_equal(back(u), o(u))
