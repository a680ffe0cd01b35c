"""Hypothesis properties of the main invariants."""

import pickle

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import lekalo

# coordinates of ordinary magnitude: subnormal control points (e.g. all 5e-324) make the
# real-degree test of an elevated Bezier curve report a higher degree, since its tolerance is
# relative to a scale that is itself below the rounding of the elevation
coords = st.one_of(st.just(0.0), st.floats(1e-100, 1e3), st.floats(-1e3, -1e-100))


@st.composite
def distinct_points(draw, min_n=4, max_n=25, dim=None):
    d = dim or draw(st.integers(1, 3))
    n = draw(st.integers(min_n, max_n))
    pts = draw(hnp.arrays(np.float64, (n, d), elements=coords))
    # keep consecutive points apart so that the parametrisation is defined
    steps = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    pts = pts[np.concatenate([[True], steps > 1e-3])]
    if len(pts) < min_n:
        pts = np.cumsum(np.ones((min_n, d)), axis=0)
    return pts


@st.composite
def bspline(draw):
    p = draw(st.integers(1, 5))
    n = draw(st.integers(p + 1, p + 12))
    d = draw(st.integers(1, 3))
    interior = sorted(draw(st.lists(st.floats(0.01, 0.99), min_size=n - p - 1, max_size=n - p - 1)))
    knots = np.concatenate([[0.0] * (p + 1), interior, [1.0] * (p + 1)])
    # no interior knot of multiplicity above p
    for k in range(p + 1, len(knots) - p - 1):
        if np.sum(knots == knots[k]) > p:
            knots[p + 1:n] = np.linspace(0, 1, n - p + 1)[1:-1]
            break
    ctrl = draw(hnp.arrays(np.float64, (n, d), elements=coords))
    return lekalo.BSplineCurve(p, knots, ctrl)


@given(distinct_points())
def test_interpolant_passes_through_the_points(q):
    c = lekalo.interpolate(q, min(3, len(q) - 1))
    t = lekalo.parametrize(q)
    scale = max(1.0, np.abs(q).max())
    assert np.allclose(c(t), q, atol=1e-8 * scale)


@given(bspline(), st.floats(0.0, 1.0))
@example(
    lekalo.BSplineCurve(3, [0.0] * 4 + [1.0] * 4, np.arange(8.0).reshape(4, 2)), 5e-324
)
def test_knot_insertion_does_not_move_the_curve(c, t):
    x = np.linspace(0, 1, 33)
    scale = max(1.0, np.abs(c.control).max())
    gaps = np.abs(c.knots - t)
    if 0 < gaps[gaps > 0].min() < np.finfo(float).tiny:
        # a span narrower than the smallest normal number cannot be evaluated: refused
        with pytest.raises(ValueError, match="smallest normal number"):
            c.insert_knot(t, 1)
        return
    ins = c.insert_knot(t, 1) if c.knots.tolist().count(t) < c.degree else c
    assert np.allclose(ins(x), c(x), atol=1e-11 * scale)


@given(bspline())
def test_convex_hull_and_partition_of_unity(c):
    x = np.linspace(0, 1, 65)
    pts = c(x)
    lo, hi = c.control.min(axis=0), c.control.max(axis=0)
    slack = 1e-12 * max(1.0, np.abs(c.control).max())
    assert np.all(pts >= lo - slack) and np.all(pts <= hi + slack)


@given(bspline())
def test_pickle_json_scipy_round_trips_bit_for_bit(c):
    assert pickle.loads(pickle.dumps(c)) == c
    assert lekalo.BSplineCurve.from_json(c.to_json()) == c
    assert lekalo.from_scipy(lekalo.to_scipy(c, squeeze=False)) == c


@given(bspline(), st.floats(0.05, 0.95))
def test_split_pieces_agree_with_the_curve(c, t):
    a, b = c.split(t)
    xa, xb = np.linspace(0, t, 9), np.linspace(t, 1, 9)
    scale = max(1.0, np.abs(c.control).max())
    assert np.allclose(a(xa), c(xa), atol=1e-10 * scale)
    assert np.allclose(b(xb), c(xb), atol=1e-10 * scale)


@given(st.lists(st.integers(4, 12), min_size=1, max_size=30), st.integers(1, 3))
def test_batch_equals_single(lengths, threads):
    rng = np.random.default_rng(len(lengths))
    off = lekalo.ragged_offsets(lengths)
    pts = rng.standard_normal((off[-1], 2))
    b = lekalo.interpolate_batch(pts, off, 3, threads=threads)
    for i, c in enumerate(lekalo.curves_from_batch(b)):
        assert c == lekalo.interpolate(pts[off[i]:off[i + 1]], 3)


@given(st.integers(0, 6), hnp.arrays(np.float64, st.integers(2, 8), elements=coords))
def test_bezier_elevation_keeps_the_curve(by, c1):
    b = lekalo.BezierCurve(c1)
    e = b.elevate_degree(by)
    t = np.linspace(0, 1, 17)
    assert np.allclose(e(t), b(t), atol=1e-9 * max(1.0, np.abs(c1).max()))
    assert e.real_degree() <= b.degree
