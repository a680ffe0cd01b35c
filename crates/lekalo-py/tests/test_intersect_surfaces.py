"""Surface-surface intersections and plane sections from Python: branches as dicts with their
kind, points on both surfaces, parameters and fitted curves, checked against the implicit
equations of the surfaces."""

import numpy as np
import pytest

import lekalo

H = np.sqrt(0.5)
# a quarter of the cylinder x² + z² = 1 for y in [0, 2] (exact NURBS)
QUARTER = lekalo.NurbsSurface(
    2, 1, [0, 0, 0, 1, 1, 1], [0, 0, 1, 1],
    [[[1, 0, 0], [1, 2, 0]], [[1, 0, 1], [1, 2, 1]], [[0, 0, 1], [0, 2, 1]]],
    [[1, 1], [H, H], [1, 1]],
)
# the bump z = 4uv(1 - u)(1 - v) over x = 2u, y = 2v
BUMP = lekalo.BSplineSurface(
    2, 2, [0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1],
    [[[0, 0, 0], [0, 1, 0], [0, 2, 0]], [[1, 0, 0], [1, 1, 1], [1, 2, 0]],
     [[2, 0, 0], [2, 1, 0], [2, 2, 0]]],
)


def at(surface, uv):
    """The surface's points at the rows of `uv` (n, 2)."""
    uv = np.ascontiguousarray(np.asarray(uv).T)
    return surface(uv[0], uv[1])


def plane(z):
    """The plane z = const over [0, 2]² as a bilinear surface."""
    return lekalo.BSplineSurface(
        1, 1, [0, 0, 1, 1], [0, 0, 1, 1],
        [[[0, 0, z], [0, 2, z]], [[2, 0, z], [2, 2, z]]],
    )


def test_bump_and_a_plane_meet_in_one_closed_loop():
    a, b = lekalo.SurfaceQuery(BUMP), lekalo.SurfaceQuery(plane(0.1))
    branches = a.intersect(b, tolerance=1e-7)
    assert len(branches) == 1
    br = branches[0]
    assert br["kind"] == "crossing" and br["closed"]
    p = br["points"]
    assert p.shape[1] == 3 and br["uv_a"].shape == (len(p), 2) == br["uv_b"].shape
    u, v = p[:, 0] / 2, p[:, 1] / 2
    assert np.abs(p[:, 2] - 0.1).max() <= 1e-7
    assert np.abs(4 * u * v * (1 - u) * (1 - v) - p[:, 2]).max() <= 1e-7
    assert np.allclose(at(BUMP, br["uv_a"]), p, atol=1e-9)
    # the fitted curves share their parameter: C(t) ≈ S₁(c₁(t)) ≈ S₂(c₂(t))
    t = np.linspace(*br["curve"].domain, 50)
    c, c1, c2 = br["curve"](t), br["curve_uv_a"](t), br["curve_uv_b"](t)
    assert np.abs(at(BUMP, c1) - c).max() <= 4e-7
    assert np.abs(at(plane(0.1), c2) - c).max() <= 4e-7
    assert br["length"] > 0 and br["tolerance"] == 1e-7


def test_plane_section_of_a_cylinder_is_an_elliptic_arc():
    q = lekalo.SurfaceQuery(QUARTER)
    branches = q.intersect_plane([0, 0, 0.2], [-0.5, 0, 1])
    assert [b["kind"] for b in branches] == ["crossing"]
    b = branches[0]
    assert not b["closed"] and b["uv_b"].shape == (0, 2) and b["curve_uv_b"] is None
    x, z = b["points"][:, 0], b["points"][:, 2]
    assert np.abs(np.hypot(x, z) - 1).max() <= 1e-6
    assert np.abs(z - 0.5 * x - 0.2).max() <= 1e-6


def test_contact_miss_and_errors():
    q = lekalo.SurfaceQuery(QUARTER)
    # the plane z = 1 touches the quarter cylinder along its edge line x = 0
    touch = q.intersect_plane([0, 0, 2], [0, 0, 1])
    assert touch == []
    hit = lekalo.SurfaceQuery(BUMP).intersect_plane([1, 1, 0.25], [0, 0, 1])
    assert [(b["kind"], b.get("order")) for b in hit] == [("tangent", 1)]
    assert np.allclose(hit[0]["points"][0], [1, 1, 0.25], atol=1e-3)
    with pytest.raises(lekalo.Error):
        q.intersect_plane([0, 0, 0], [0, 0, 0])
    with pytest.raises(lekalo.Error):
        q.intersect(q, tolerance=-1)
