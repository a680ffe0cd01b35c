"""Intersections from Python: every answer is a dict naming its kind of contact (the library's
words: crossing, tangent, end, near-miss, overlap), with exact answers where the inputs give
them, and the named errors."""

import numpy as np
import pytest

import lekalo

R = 2.0
CIRCLE = lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], R)
PARABOLA = lekalo.CurveQuery(lekalo.BezierCurve([[-1, 1], [0, -1], [1, 1]]))


def line(a, b):
    return lekalo.CurveQuery(lekalo.BSplineCurve(1, [0, 0, 1, 1], [a, b]))


def test_crossings_of_a_circle_and_a_line():
    c = lekalo.CurveQuery(CIRCLE)
    hits = c.intersect(line([-3, 1], [3, 1]))
    assert [h["kind"] for h in hits] == ["crossing", "crossing"]
    assert np.allclose(sorted(h["point"][0] for h in hits), [-np.sqrt(3), np.sqrt(3)], atol=1e-12)
    for h in hits:
        assert np.allclose(CIRCLE(h["t_a"]), h["point"], atol=1e-14)


def test_a_tangent_is_exact_and_has_its_order():
    # y = x² and its tangent y = x − 1/4 at x = 1/2: t = 3/4 on both, to the last bit
    hits = PARABOLA.intersect(line([-1, -1.25], [1, 0.75]))
    assert len(hits) == 1
    h = hits[0]
    assert h["kind"] == "tangent" and h["order"] == 1
    assert h["t_a"] == 0.75 and h["t_b"] == 0.75
    assert np.array_equal(h["point"], [0.5, 0.25])
    # y = x³ against its inflectional tangent: order 2
    cubic = lekalo.CurveQuery(lekalo.BezierCurve([[-1, -1], [-1 / 3, 1], [1 / 3, -1], [1, 1]]))
    hits = cubic.intersect(line([-2, 0], [2, 0]))
    assert [(h["kind"], h.get("order")) for h in hits] == [("tangent", 2)]


def test_near_tangent_lines_are_a_near_miss_or_two_crossings():
    below = PARABOLA.intersect(line([-2, -1e-11], [2, -1e-11]))
    assert [h["kind"] for h in below] == ["near-miss"]
    assert below[0]["gap"] == pytest.approx(1e-11, abs=1e-20)
    above = PARABOLA.intersect(line([-2, 1e-12], [2, 1e-12]))
    assert [h["kind"] for h in above] == ["crossing", "crossing"]
    assert np.allclose([h["point"][0] for h in above], [-1e-6, 1e-6], atol=1e-15)


def test_end_points_and_overlaps():
    # the parabola's ends lie on y = 1
    hits = PARABOLA.intersect(line([-2, 1], [2, 1]))
    assert [h["kind"] for h in hits] == ["end", "end"]
    # two collinear segments share [1, 2]
    hits = line([0, 0], [2, 0]).intersect(line([1, 0], [3, 0]))
    assert len(hits) == 1 and hits[0]["kind"] == "overlap"
    assert np.allclose(hits[0]["t_a"], (0.5, 1.0), atol=1e-14)
    assert np.allclose(hits[0]["t_b"], (0.0, 0.5), atol=1e-14)


def test_self_intersections_name_their_kind():
    loop = lekalo.interpolate(np.array([[0, 0], [2, 2], [3, 0], [2, -1], [1, 1], [0, 2]], float), 3)
    selfx = lekalo.CurveQuery(loop).self_intersections()
    assert len(selfx) == 1 and selfx[0]["kind"] == "crossing"
    assert selfx[0]["t_a"] < selfx[0]["t_b"]
    assert np.allclose(loop(selfx[0]["t_a"]), loop(selfx[0]["t_b"]), atol=1e-9)


def test_plane_crossings_tangents_and_overlaps():
    c = lekalo.CurveQuery(CIRCLE)
    hits = c.intersect_plane([0.0, 1.0], [0.0, 1.0])
    assert [h["kind"] for h in hits] == ["crossing", "crossing"]
    assert np.allclose(sorted(h["point"][0] for h in hits), [-np.sqrt(3), np.sqrt(3)], atol=1e-12)
    # the line y = 2 touches the circle at its top, the knot t = 1/4
    top = c.intersect_plane([0.0, 2.0], [0.0, 1.0])
    assert [(h["kind"], h["order"]) for h in top] == [("tangent", 1)]
    assert top[0]["t"] == pytest.approx(0.25, abs=1e-15)
    # a cubic lying in the plane z = 2: the whole domain
    flat = lekalo.CurveQuery(lekalo.BezierCurve([[0, 0, 2], [1, 2, 2], [2, -1, 2], [3, 0.5, 2]]))
    assert flat.intersect_plane([0, 0, 2], [0, 0, 1]) == [{"kind": "overlap", "t": (0.0, 1.0)}]


def test_space_curves_and_surfaces():
    # a vertical line through the patch z = xy
    net = np.array([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]], float)
    s = lekalo.SurfaceQuery(lekalo.BSplineSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], net))
    hits = line([0.5, 0.5, -1], [0.5, 0.5, 1]).intersect_surface(s)
    assert [h["kind"] for h in hits] == ["crossing"]
    assert np.allclose(hits[0]["point"], [0.5, 0.5, 0.25], atol=1e-9)
    assert np.allclose(hits[0]["uv"], [0.5, 0.5], atol=1e-9)
    # its iso-curve u = 1/2 lies on it: an overlap with (u, v) at both ends
    iso = line([0.5, 0, 0], [0.5, 1, 0.5]).intersect_surface(s)
    assert len(iso) == 1 and iso[0]["kind"] == "overlap" and iso[0]["t"] == (0.0, 1.0)
    assert np.allclose(iso[0]["uv"], [(0.5, 0.0), (0.5, 1.0)], atol=1e-9)
    # two space segments crossing at (1, 1, 1)
    hits = line([0, 0, 0], [2, 2, 2]).intersect(line([0, 2, 0], [2, 0, 2]))
    assert [h["kind"] for h in hits] == ["crossing"]
    assert np.allclose(hits[0]["point"], [1, 1, 1], atol=1e-12)


def test_errors():
    with pytest.raises(lekalo.Error):
        lekalo.CurveQuery(CIRCLE).intersect_plane([0.0, 0.0], [0.0, 0.0])
    with pytest.raises(lekalo.Error, match="dimension"):
        line([0, 0], [1, 1]).intersect(line([0, 0, 0], [1, 1, 1]))
    with pytest.raises(lekalo.Error):
        PARABOLA.intersect(PARABOLA, tolerance=-1.0)
