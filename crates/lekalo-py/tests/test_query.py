"""Geometric queries: exact answers on circles, lines and parabolas (the library's own test
cases), dense-sampling and SciPy quadrature cross-checks, and the named errors."""

import numpy as np
import pytest
from scipy import integrate

import lekalo

RNG = np.random.default_rng(5)
R = 2.0
CIRCLE = lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], R)


def wavy():
    x = np.linspace(0, 4, 12)
    return lekalo.interpolate(np.column_stack([x, np.sin(2 * x)]), 3)


def test_length_and_its_inverse():
    q = lekalo.CurveQuery(CIRCLE)
    assert abs(q.length() - 2 * np.pi * R) <= 1e-12 * 2 * np.pi * R
    # a polyline's length is exact (the library's doc example)
    line = lekalo.BSplineCurve(1, [0, 0, 1, 2, 2], [[0, 0], [3, 4], [3, 0]])
    assert lekalo.CurveQuery(line).length() == pytest.approx(9.0, rel=1e-14)
    assert lekalo.CurveQuery(line).length(0.0, 1.0) == pytest.approx(5.0, rel=1e-14)
    # against SciPy's adaptive quadrature of |C'|
    c = wavy()
    qc = lekalo.CurveQuery(c)
    a, b = c.domain
    ref, _ = integrate.quad(lambda t: np.linalg.norm(c(t, nu=1)), a, b, limit=200, epsabs=0, epsrel=1e-13)
    assert qc.length() == pytest.approx(ref, rel=1e-10)
    t = np.linspace(a, b, 17)
    s = qc.length_at(t)
    assert s.shape == t.shape and s[0] == 0 and s[-1] == pytest.approx(ref, rel=1e-10)
    assert np.allclose(qc.param_at(s), t, rtol=0, atol=1e-10)
    assert isinstance(qc.param_at(float(s[3])), float)
    steps = qc.equal_steps(8)
    assert np.allclose(np.diff(qc.length_at(steps)), ref / 8, rtol=1e-9)
    spline, dev = qc.arc_length_spline(1e-6)
    assert dev <= 1e-6 and spline.domain[1] == pytest.approx(ref, rel=1e-10)
    # the arc length's tolerance is relative (`rtol`, as NumPy's), every other one an absolute
    # distance (`tolerance`): a refused one is named by the keyword the caller typed
    for call in (lambda: qc.length_at(t, rtol=-1.0), lambda: qc.param_at(s, rtol=float("nan"))):
        with pytest.raises(lekalo.InputError, match="^rtol: "):
            call()
    with pytest.raises(lekalo.InputError, match="^tolerance: "):
        qc.arc_length_spline(-1.0)


def test_projection_batch_matches_dense_sampling():
    c = wavy()
    q = lekalo.CurveQuery(c)
    pts = RNG.random((200, 2)) * [4, 3] - [0, 1.5]
    t, p, d = q.project(pts)
    assert t.shape == (200,) and p.shape == (200, 2) and d.shape == (200,)
    assert np.allclose(c(t), p, atol=1e-12)
    assert np.allclose(np.linalg.norm(p - pts, axis=1), d, atol=1e-12)
    dense = c(np.linspace(*c.domain, 20001))
    brute = np.sqrt(((pts[:, None, :] - dense[None, :, :]) ** 2).sum(-1)).min(1)
    # the global minimum: never farther than the brute-force sample, and within its spacing
    assert np.all(d <= brute + 1e-12) and np.all(brute - d < 1e-3)
    # one point in, scalars out; the circle's exact answer
    t0, p0, d0 = lekalo.CurveQuery(CIRCLE).project([3.0, 3.0])
    assert d0 == pytest.approx(np.sqrt(18) - R, abs=1e-14)
    assert np.allclose(p0, [np.sqrt(2), np.sqrt(2)], atol=1e-14)


def test_project_all_and_invert():
    parabola = lekalo.BSplineCurve(2, [0, 0, 0, 1, 1, 1], [[-2, 4], [0, -4], [2, 4]])
    q = lekalo.CurveQuery(parabola)
    allm = q.project_all([0.0, 2.0], 1e-9)
    assert len(allm) == 2
    assert all(abs(abs(p[0]) - np.sqrt(1.5)) < 1e-12 for _, p, _ in allm)
    t = q.invert(parabola(0.3), 1e-9)
    assert t == pytest.approx(0.3, abs=1e-12)
    with pytest.raises(lekalo.Error):
        q.invert([0.0, 10.0], 1e-9)


def test_offset_polyline_curvature_bbox():
    q = lekalo.CurveQuery(CIRCLE)
    off = q.offset(0.5, 1e-6)
    assert off["deviation"] <= 1e-6 and len(off["cusps"]) == 0
    ts = np.linspace(*off["curve"].domain, 101)
    radii = np.linalg.norm(off["curve"](ts), axis=1)
    assert np.abs(radii - (R - 0.5)).max() <= 1e-6 or np.abs(radii - (R + 0.5)).max() <= 1e-6
    params, pts, dev = q.polyline(1e-4)
    assert dev <= 1e-4 and np.allclose(np.linalg.norm(pts, axis=1), R, atol=1e-12)
    # the chords' sagitta is the deviation: within the bound
    mid = (pts[1:] + pts[:-1]) / 2
    assert (R - np.linalg.norm(mid, axis=1)).max() <= 1e-4
    k = q.curvature(np.linspace(0, 1, 9))
    assert np.allclose(k, 1 / R, rtol=1e-12)
    assert isinstance(q.curvature(0.25), float)
    lo, hi = q.bounding_box()
    assert np.allclose(lo, [-R, -R], atol=1e-12) and np.allclose(hi, [R, R], atol=1e-12)
    w = lekalo.CurveQuery(wavy())
    assert len(w.inflections()) >= 2
    t, kk, ismax = w.curvature_extrema()
    assert len(t) == len(kk) == len(ismax) and ismax.dtype == bool
    # a helix-like 3-D curve has torsion; a planar one has none
    z = np.linspace(0, 1, 8)
    helix = lekalo.interpolate(np.column_stack([np.cos(3 * z), np.sin(3 * z), z]), 3)
    assert np.all(np.abs(lekalo.CurveQuery(helix).torsion(np.linspace(0.1, 0.9, 5))) > 0.01)


def test_surface_queries():
    i, j = np.meshgrid(np.linspace(0, 1, 6), np.linspace(0, 1, 5), indexing="ij")
    grid = np.stack([i, j, 0.3 * np.sin(3 * i) * np.cos(2 * j)], axis=-1)
    surf = lekalo.interpolate_surface(grid, 3, 3)
    q = lekalo.SurfaceQuery(surf)
    pts = np.column_stack([RNG.random(20), RNG.random(20), RNG.random(20) - 0.5])
    uv, p, d = q.project(pts)
    u, v = np.ascontiguousarray(uv.T)
    assert uv.shape == (20, 2) and np.allclose(surf(u, v), p, atol=1e-10)
    assert np.allclose(np.linalg.norm(p - pts, axis=1), d, atol=1e-12)
    verts, muv, tri, dev = q.mesh(1e-3)
    assert tri.dtype == np.uint32 and tri.shape[1] == 3 and tri.max() < len(verts)
    mu, mv = np.ascontiguousarray(muv.T)
    assert dev <= 1e-3 and np.allclose(surf(mu, mv), verts, atol=1e-12)
    # a tolerance whose mesh would not fit in memory is refused before meshing (mesh(1e-8) of
    # a small surface killed the interpreter with SIGABRT)
    # named by the keyword, from the error's key (the library says "tessellation tolerance")
    with pytest.raises(lekalo.InputError, match="^tolerance: 1e-10 needs about"):
        q.mesh(1e-10)
    # a plane has zero curvature; a sphere-free check: K = k1·k2, H = (k1 + k2)/2
    g, h, k1, k2 = q.curvature(np.array([0.3, 0.7]), np.array([0.4, 0.2]))
    assert np.allclose(g, k1 * k2, rtol=1e-10, atol=1e-12) and np.allclose(h, (k1 + k2) / 2, rtol=1e-10)


def test_query_errors():
    with pytest.raises(lekalo.Error, match="BezierCurve, BSplineCurve or NurbsCurve"):
        lekalo.CurveQuery("not a curve")
    q = lekalo.CurveQuery(CIRCLE)
    with pytest.raises(lekalo.Error):
        q.project([[np.nan, 0.0]])
    with pytest.raises(lekalo.Error, match="expected points"):
        q.project(np.zeros((2, 2, 2)))
    with pytest.raises(lekalo.Error):
        q.project([[1.0, 2.0, 3.0]])
    with pytest.raises(lekalo.Error):
        q.curvature(5.0)
    with pytest.raises(lekalo.Error):
        q.polyline(-1.0)
    with pytest.raises(lekalo.Error):
        q.param_at(100.0)
    with pytest.raises(lekalo.Error):
        q.intersect_plane([0.0, 0.0], [0.0, 0.0])
    with pytest.raises(lekalo.Error, match="BezierSurface"):
        lekalo.SurfaceQuery(CIRCLE)
