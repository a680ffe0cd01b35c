"""Curves, surfaces, pp-forms: evaluation against SciPy, operations, JSON and pickle."""

import json
import math
import pickle
from pathlib import Path

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo

RNG = np.random.default_rng(7)


def lecture_curve():
    return lekalo.BSplineCurve(2, [0, 0, 1, 2, 3, 3], [[1, 1], [2, 3], [4, 3]])


def test_lecture_example():
    c = lecture_curve()
    assert c.domain == (1.0, 2.0)
    assert c(1.5).tolist() == [17 / 8, 11 / 4]
    d = c.derivatives(1.5, 2)
    assert d.shape == (3, 2)
    assert np.array_equal(d[0], c(1.5))


def test_bspline_matches_scipy_bspline():
    t = np.concatenate([[0] * 4, np.sort(RNG.random(20)), [1] * 4])
    ctrl = RNG.standard_normal((24, 3))
    c = lekalo.BSplineCurve(3, t, ctrl)
    ref = si.BSpline(t, ctrl, 3)
    x = np.linspace(0, 1, 1001)
    assert np.allclose(c(x), ref(x), rtol=0, atol=1e-13)
    # large batches take the parallel path: same numbers
    xl = RNG.random(100_000)
    assert np.allclose(c(xl), ref(xl), rtol=0, atol=1e-13)
    for nu in (1, 2, 3):
        assert np.allclose(c(x, nu=nu), ref(x, nu=nu), rtol=1e-9, atol=1e-9 * np.abs(ref(x, nu=nu)).max())
    # derivatives of every order at once
    xs = np.linspace(0, 1, 21)
    d = c.derivatives(xs, 3)
    for nu in range(4):
        assert np.allclose(d[:, nu], ref(xs, nu=nu), rtol=1e-9, atol=1e-8 * max(1, np.abs(d[:, nu]).max()))


def test_shapes_and_layouts():
    c = lecture_curve()
    t = np.linspace(1, 2, 12).reshape(3, 4)
    assert c(t).shape == (3, 4, 2)
    assert c(t.T).shape == (4, 3, 2)  # F-ordered parameters
    assert np.array_equal(c(t.T), c(np.ascontiguousarray(t.T)))
    assert c([1.0, 1.5]).shape == (2, 2)
    # F-ordered control points give the same curve as C-ordered ones
    ctrl = np.asfortranarray(np.array([[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]))
    assert lekalo.BSplineCurve(2, [0, 0, 1, 2, 3, 3], ctrl) == c
    # strided views (every other column, a reversed slice) are copied once, not refused
    wide = np.zeros((3, 4))
    wide[:, ::2] = [[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]
    assert lekalo.BSplineCurve(2, [0, 0, 1, 2, 3, 3], wide[:, ::2]) == c
    back = np.linspace(2, 1, 7)[::-1]
    assert np.array_equal(c(back), c(np.ascontiguousarray(back)))


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: lekalo.BSplineCurve(2, [0, 0, 1, 2, 3, 3], np.array([[1, 1], [2, 3], [4, 3]]) + 0j), "dtype complex128 is not a real number type"),
        (lambda: lekalo.BSplineCurve(2, [0, 0, 1, 2, 3, 3], [[1, np.nan], [2, 3], [4, 3]]), "finite"),
        (lambda: lekalo.BSplineCurve(2, [0, 0, 2, 1, 3, 3], [[1, 1], [2, 3], [4, 3]]), "knots"),
        (lambda: lekalo.BSplineCurve(2, [0, 0, 1, 2, 3], [[1, 1], [2, 3], [4, 3]]), "expected 6, got 5"),
        (lambda: lekalo.BSplineCurve(2, [0, 0, 1, 2, 3, 3], np.ones((3, 2, 2))), "2-D array"),
        (lambda: lecture_curve()(0.5), "outside the domain"),
        (lambda: lecture_curve()(np.array([1.5, np.nan])), "outside the domain|finite"),
        (lambda: lecture_curve()(np.array(["1.5", "2"])), "dtype <U3 is not a real number type"),
        (lambda: lecture_curve()(np.array([1.5, None])), "dtype object is not a real number type"),
        (lambda: lecture_curve()("abc"), "sequence of numbers"),
        (lambda: lecture_curve().derivatives(1.5, 10**9), "order|too large"),
        (lambda: lekalo.interpolate(np.zeros((1, 2))), "need at least|too few|points"),
        (lambda: lekalo.interpolate(RNG.random((5, 2)), degree=0), "degree"),
        (lambda: lekalo.interpolate(np.ones((5, 2))), "coincide"),
        (lambda: lekalo.interpolate(RNG.random((5, 2)), knots="bogus"), "knots: unknown"),
        (lambda: lekalo.evaluate_batch(3, np.zeros(8), [0, 8], np.zeros((4, 1)), [0, 4], np.zeros(1), [0, 2]), "last offset"),
    ],
)
def test_named_errors(make, match):
    with pytest.raises(lekalo.Error, match=match) as e:
        make()
    assert isinstance(e.value, ValueError)


def test_integer_and_float32_arrays_read_as_float64():
    # as SciPy, which converts them: the same curve as from float64 arrays or lists of ints
    pts = [[0, 0], [1, 2], [2, 0], [3, 1]]
    ref = lekalo.interpolate(np.array(pts, dtype=np.float64))
    for dtype in (np.int64, np.int32, np.uint8, np.float32):
        assert lekalo.interpolate(np.array(pts, dtype=dtype)) == ref, dtype
    assert lekalo.interpolate(pts) == ref
    c = lecture_curve()
    t = np.array([1, 2])
    assert np.array_equal(c(t), c(t.astype(np.float64)))
    assert np.array_equal(c(t.astype(np.float32)), c(t.astype(np.float64)))
    knots = np.array([0, 0, 1, 2, 3, 3])
    assert lekalo.BSplineCurve(2, knots, np.array([[1, 1], [2, 3], [4, 3]])) == c


def _pp():
    """A piecewise quadratic in one coordinate on [0, 1, 2] (pieces by power coefficients)."""
    return lekalo.PiecewisePolynomial([0.0, 1.0, 2.0], np.ones((2, 3, 1)))


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda c: c.derivatives(1.5, -1), "order"),
        (lambda c: c(1.5, -1), "nu"),
        (lambda c: c(1.5, nu=np.int64(-2)), "nu"),
        (lambda c: c.antiderivative(-1), "n"),
        (lambda c: c.insert_knot(1.5, -1), "times"),
        (lambda c: c.elevate_degree(-1), "by"),
        (lambda c: c.eval_extrapolated(1.5, -1), "nu"),
        (lambda c: lekalo.BezierCurve([[0, 0], [1, 1], [2, 0]])(0.5, -1), "nu"),
        (lambda c: lekalo.BezierCurve([[0, 0], [1, 1], [2, 0]]).derivatives(0.5, -1), "order"),
        (lambda c: lekalo.BSplineCurve.clamped(-1, [[0, 0], [1, 1]]), "degree"),
        (lambda c: lekalo.BSplineCurve(-2, [0, 1], [[0, 0]]), "degree"),
        (lambda c: lekalo.interpolate([[0, 0], [1, 1], [2, 0]], degree=-1), "degree"),
        (lambda c: lekalo.CurveQuery(c).equal_steps(-3), "n"),
        (lambda c: lekalo.make_lsq_spline(np.linspace(0, 1, 9), np.ones(9), [0, 0, 1, 1], k=-1), "k"),
        (lambda c: lekalo.make_splrep(np.linspace(0, 1, 9), np.ones(9), k=-1), "k"),
        (lambda c: lekalo.generate_knots(np.linspace(0, 1, 9), np.ones(9), nest=-1), "nest"),
        (lambda c: lekalo.fit_surface_grid(np.ones((5, 5, 3)), degree=(-1, 3)), "degree"),
        (lambda c: lekalo.fit_surface_grid(np.ones((5, 5, 3)), n_ctrl=(4, -4)), "n_ctrl"),
        (lambda c: _pp()(0.5, -1), "nu"),
        (lambda c: _pp().eval_extrapolated(0.5, -1), "nu"),
        (lambda c: _pp().derivative(-1), "j"),
        (lambda c: _pp().antiderivative(-1), "n"),
    ],
)
def test_negative_counts_and_orders_are_named_input_errors(call, name):
    # not Python's OverflowError "can't convert negative int to unsigned"
    with pytest.raises(lekalo.InputError, match=rf"(^|: ){name} must be a (whole|non-negative|pair of whole)") as e:
        call(lecture_curve())
    assert isinstance(e.value, ValueError)


def test_huge_output_refused():
    c = lecture_curve()
    with pytest.raises(lekalo.Error, match="too large"):
        c.derivatives(np.ones(1), 2**40)


def test_knot_operations_keep_the_curve():
    c = lekalo.interpolate(RNG.standard_normal((12, 2)))
    x = np.linspace(*c.domain, 301)
    for d in (
        c.insert_knot(0.37, 2),
        c.refine_knots(np.array([0.1, 0.2, 0.2, 0.8])),
        c.elevate_degree(2),
        c.reverse().reverse(),
    ):
        assert np.allclose(d(x), c(x), atol=1e-12)
    a, b = c.split(0.4)
    assert a.domain == (0.0, 0.4) and b.domain == (0.4, 1.0)
    assert np.allclose(a(x[x <= 0.4]), c(x[x <= 0.4]), atol=1e-12)
    c2, removed = c.insert_knot(0.37, 2).remove_knot(0.37, 2)
    assert removed == 2 and np.allclose(c2(x), c(x), atol=1e-10)
    segs = c.to_bezier_segments()
    for start, end, bez in segs:
        assert np.allclose(bez(0.5), c((start + end) / 2), atol=1e-12)
    r = c.reparametrize(2.0, 5.0)
    assert r.domain == (2.0, 5.0) and np.allclose(r(2 + 3 * x), c(x), atol=1e-12)
    dc = c.derivative()
    assert np.allclose(dc(x), c(x, nu=1), atol=1e-9)


def test_bezier_degree_change():
    b = lekalo.BezierCurve(RNG.standard_normal((4, 3)))
    e = b.elevate_degree(3)
    assert e.degree == 6 and e.real_degree() == 3
    back = e.change_degree(3)
    assert np.allclose(back.control, b.control, atol=1e-12)
    with pytest.raises(lekalo.Error):
        e.change_degree(2)
    t = np.linspace(0, 1, 50)
    assert np.allclose(e(t), b(t), atol=1e-13)
    left, right = b.split(0.25)
    assert np.allclose(left(1.0), b(0.25), atol=1e-14)
    mono = b.to_monomial()
    assert np.allclose(lekalo.BezierCurve.from_monomial(mono).control, b.control, atol=1e-12)
    r, bound = b.elevate_degree(2).reduce_degree_approx(3)
    assert bound < 1e-9 and np.allclose(r(t), b(t), atol=1e-9)
    # a Bezier curve as SciPy's BPoly of one piece
    assert np.allclose(lekalo.to_scipy(b)(t), b(t), atol=1e-13)


def test_nurbs_circle():
    c = lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], 2.0)
    t = np.linspace(*c.domain, 1001)
    r = np.linalg.norm(c(t), axis=1)
    assert np.allclose(r, 2.0, atol=1e-13)
    d = c.derivatives(t[:10], 1)
    assert np.allclose(np.einsum("ij,ij->i", d[:, 0], d[:, 1]), 0, atol=1e-12)
    a, b = c.split(0.5 * sum(c.domain))
    assert np.allclose(np.linalg.norm(a(np.linspace(*a.domain, 9)), axis=1), 2.0, atol=1e-13)
    assert c.insert_knot(0.3) != c
    arc = lekalo.NurbsCurve.arc_through_points([1, 0], [0, 1], [-1, 0])
    assert np.allclose(np.linalg.norm(arc(np.linspace(*arc.domain, 17)), axis=1), 1.0, atol=1e-13)


def test_surfaces():
    net = RNG.standard_normal((5, 4, 3))
    ku = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
    kv = [0, 0, 0, 0.4, 1, 1, 1]
    s = lekalo.BSplineSurface(3, 2, ku, kv, net)
    us, vs = np.linspace(0, 1, 7), np.linspace(0, 1, 6)
    u, v = np.meshgrid(us, vs, indexing="ij")
    # the same surface by SciPy: a B-spline in u of B-splines in v
    ref = np.empty(u.shape + (3,))
    for i, uu in enumerate(us):
        rows = si.BSpline(np.array(ku, float), net, 3)(uu)  # (4, 3): control row in v
        ref[i] = si.BSpline(np.array(kv, float), rows, 2)(v[i])
    assert np.allclose(s(u, v), ref, atol=1e-13)
    assert np.allclose(s.grid(us, vs), ref, atol=1e-13)
    # a strided view (a column) is read as its copy would be
    assert np.array_equal(s.grid(u[:, 0], vs), s.grid(np.ascontiguousarray(u[:, 0]), vs))
    d = s.derivatives(0.3, 0.6, 1)
    assert d.shape == (2, 2, 3) and np.allclose(d[0, 0], s(0.3, 0.6))
    n = s.normal(0.3, 0.6)
    assert np.isclose(np.linalg.norm(n), 1.0)
    s2 = s.insert_knot_u(0.3).insert_knot_v(0.7, 2)
    assert np.allclose(s2(u, v), s(u, v), atol=1e-12)
    a, b = s.split_u(0.5)
    assert a.domain[0] == (0.0, 0.5)
    iso = s.iso_curve_u(0.25)
    assert np.allclose(iso(us), s(us, np.full(7, 0.25)), atol=1e-13)
    bz = lekalo.BezierSurface(RNG.standard_normal((3, 4, 3)))
    assert bz.degrees == (2, 3)
    assert np.allclose(bz.to_bspline()(u, v), bz(u, v), atol=1e-13)
    assert bz.elevate_degree(1, 1).real_degrees() == (2, 3)
    w = RNG.random((5, 4)) + 0.5
    ns = lekalo.NurbsSurface(3, 2, ku, kv, net, w)
    # the rational surface is the projection of its homogeneous surface
    hom = lekalo.BSplineSurface(3, 2, ku, kv, np.concatenate([net * w[..., None], w[..., None]], axis=2))
    h = hom(u, v)
    assert np.allclose(ns(u, v), h[..., :3] / h[..., 3:], atol=1e-12)
    assert np.allclose(ns.grid(us, vs), ns(u, v), atol=1e-13)
    with pytest.raises(lekalo.Error, match="shapes differ"):
        s(np.zeros(3), np.zeros(4))


def test_pp_form():
    c = lekalo.interpolate(RNG.standard_normal((9, 2)))
    pp = c.to_pp()
    x = np.linspace(0, 1, 101)
    assert np.allclose(pp(x), c(x), atol=1e-12)
    assert np.allclose(pp(x, nu=2), c(x, nu=2), atol=1e-8)
    assert np.allclose(pp.derivative(1)(x), c(x, nu=1), atol=1e-9)
    space = lekalo.PpSpace(pp.breakpoints, 4, [3] * (len(pp.breakpoints) - 2))
    assert space.contains(pp)
    back = pp.to_bspline(space)
    assert np.allclose(back(x), c(x), atol=1e-10)
    # quasi-interpolation reproduces a cubic exactly
    f = lambda t, r: [t**3, 3 * t**2, 6 * t, 6.0][r] if r < 4 else 0.0  # noqa: E731
    q = lekalo.quasi_interpolate(lekalo.PpSpace([0, 0.3, 0.6, 1.0], 4, [2, 2]), f)
    assert np.allclose(q(x)[:, 0], x**3, atol=1e-12)
    with pytest.raises(ZeroDivisionError):
        lekalo.quasi_interpolate(space, lambda t, r: 1 / 0)
    assert len(space.truncated_power_basis()) == space.dimension


def test_large_results_written_in_full():
    """Results of 2^15 numbers and more are NumPy arrays allocated without zeros: every entry
    must be written (compared with SciPy everywhere, NaN-free), for points, derivatives and
    surfaces, and an error found late in a batch still raises."""
    t = np.concatenate([[0] * 4, np.sort(RNG.random(30)), [1] * 4])
    ctrl = RNG.standard_normal((34, 3))
    c, ref = lekalo.BSplineCurve(3, t, ctrl), si.BSpline(t, ctrl, 3)
    for _ in range(3):  # reused memory from the allocator, too
        x = RNG.random(40_000)
        np.testing.assert_allclose(c(x), ref(x), rtol=0, atol=1e-12)
        d = c.derivatives(x, 2)
        for k in range(3):
            np.testing.assert_allclose(d[:, k], ref(x, nu=k), rtol=1e-10, atol=1e-9)
            # c(x, nu=k) goes through blocks of derivatives: the same numbers
            assert np.array_equal(c(x, nu=k), d[:, k])
        np.testing.assert_allclose(c(x.reshape(200, 200)), ref(x).reshape(200, 200, 3), rtol=0, atol=1e-12)
    bad = RNG.random(40_000)
    bad[-1] = 1.5
    with pytest.raises(lekalo.Error):
        c(bad)
    with pytest.raises(lekalo.Error):
        c(bad, nu=1)
    circle = lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], 2.0)
    x = np.linspace(*circle.domain, 5000).reshape(50, 100)
    assert np.array_equal(circle(x, nu=2), circle.derivatives(x, 2)[..., 2, :])
    assert circle(0.3, nu=1).shape == (2,)
    s = lekalo.interpolate_surface(RNG.standard_normal((6, 7, 3)), 3, 3)
    u, v = RNG.random(20_000), RNG.random(20_000)
    got = s(u, v)
    assert got.shape == (20_000, 3) and np.isfinite(got).all()
    np.testing.assert_allclose(got[:50], np.array([s(a, b) for a, b in zip(u[:50], v[:50])]), rtol=0, atol=1e-13)
    np.testing.assert_allclose(s.grid(u[:200], v[:200])[7, 11], s(u[7], v[11]), rtol=0, atol=1e-13)


def xcosx(t, r):
    """The r-th derivative of x cos x, by the command-line tool's formula."""
    h = math.pi / 2
    return t * math.cos(t + r * h) + r * math.cos(t + (r - 1) * h)


def test_quasi_tau_like_cli():
    """Every τ choice (the first-interval-midpoint rule, a rule, explicit values) gives the
    command-line tool's coefficients; data/make_pp_quasi_cli.py wrote them."""
    ref = json.loads((Path(__file__).parent / "data" / "pp_quasi_cli.json").read_text())
    space = lekalo.PpSpace(ref["breakpoints"], ref["order"], ref["continuity"])
    for case in ref["cases"]:
        flag, value = case["choice"]
        rule = value.replace("-", "_") if flag == "--rule" else np.array(value.split(","), dtype=float)
        q = lekalo.quasi_interpolate(space, xcosx, rule=rule)
        want = lekalo.from_json(json.dumps(case["curve"]))
        assert np.array_equal(q.knots, want.knots), case["command"]
        np.testing.assert_allclose(q.control, want.control, rtol=0, atol=1e-15, err_msg=case["command"])
    # the rules differ on these repeated knots, so the test tells them apart
    q = lekalo.quasi_interpolate(space, xcosx, rule="first-interval-midpoint")
    assert not np.allclose(q.control, lekalo.quasi_interpolate(space, xcosx).control)
    # τ never on a knot: a member of the space comes back from its pp-form exactly, even across
    # the discontinuity at the triple knot
    back = q.to_pp().to_bspline(space, "first-interval-midpoint")
    np.testing.assert_allclose(back.control, q.control, rtol=0, atol=1e-14)
    with pytest.raises(lekalo.Error, match="first-interval-midpoint"):
        lekalo.quasi_interpolate(space, xcosx, rule="first-interval")
    with pytest.raises(lekalo.Error):
        lekalo.quasi_interpolate(space, xcosx, rule=np.zeros(3))
    with pytest.raises(lekalo.Error, match="rule"):
        lekalo.quasi_interpolate(space, xcosx, rule=np.full(11, np.nan))


def test_quasi_of_a_function_undefined_at_a_breakpoint_names_where_and_the_fix():
    """ln x on breakpoints from 0: τ = 0 is where it is undefined; the message says so, under
    the argument f, with the fix (breakpoints where f is defined)."""
    space = lekalo.PpSpace([0.0, 1.0, 2.0], 3)

    def log(t, r):
        return [np.log(t), 1 / t, -1 / t**2][r] if t > 0 else -np.inf

    with np.errstate(divide="ignore"):
        with pytest.raises(lekalo.InputError) as e:
            lekalo.quasi_interpolate(space, log, rule="left-end-of-support")
    msg = str(e.value)
    assert msg.startswith("f: undefined at x = 0: the function returned -inf for its value"), msg
    assert "choose breakpoints where f is defined" in msg, msg
    # breakpoints inside the domain: no refusal
    assert np.all(np.isfinite(lekalo.quasi_interpolate(lekalo.PpSpace([0.5, 1.0, 2.0], 3), log).control))


def all_objects():
    c = lekalo.interpolate(RNG.standard_normal((7, 3)))
    yield c
    yield lecture_curve()
    yield lekalo.BezierCurve(RNG.standard_normal((5, 2)))
    yield lekalo.NurbsCurve.circle([0, 0, 0], [1, 0, 0], [0, 1, 0], 1.5)
    yield lekalo.BSplineSurface(2, 1, [0, 0, 0, 1, 1, 1], [0, 0, 1, 1], RNG.standard_normal((3, 2, 3)))
    yield lekalo.BezierSurface(RNG.standard_normal((3, 3, 3)))
    yield lekalo.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], RNG.standard_normal((2, 2, 3)), RNG.random((2, 2)) + 0.1)
    yield c.to_pp()
    yield lekalo.CubicHermite.from_points(RNG.standard_normal((6, 2)))
    yield lekalo.PpSpace([0, 1, 2, 3], 3, [1, 2])


@pytest.mark.parametrize("obj", list(all_objects()), ids=lambda o: type(o).__name__)
def test_pickle_round_trip_bit_for_bit(obj):
    back = pickle.loads(pickle.dumps(obj))
    assert type(back) is type(obj)
    assert back == obj


@pytest.mark.parametrize("obj", [o for o in all_objects() if hasattr(o, "to_json")], ids=lambda o: type(o).__name__)
def test_json_round_trip_bit_for_bit(obj):
    text = obj.to_json()
    assert text.startswith('{\n  "lekalo": 1')
    assert type(obj).from_json(text) == obj
    assert lekalo.from_json(text) == obj


def test_json_errors_are_named():
    text = lecture_curve().to_json().replace("[0.0, 0.0, 1.0, 2.0, 3.0, 3.0]", "[0.0, 0.0, 2.0, 1.0, 3.0, 3.0]")
    with pytest.raises(lekalo.Error, match="knots"):
        lekalo.BSplineCurve.from_json(text)
    with pytest.raises(lekalo.Error, match="expected a bezier_curve"):
        lekalo.BezierCurve.from_json(lecture_curve().to_json())
    with pytest.raises(lekalo.Error, match="not valid JSON"):
        lekalo.from_json("{")


def test_nurbs_shares_the_bspline_knot_operations():
    # the knot operations are written once for B-spline and NURBS classes: NURBS curves gain
    # remove_all_removable_knots, NURBS surfaces knot insertion and splitting
    c = lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], 2.0)
    refined = c.insert_knot(0.3, 2)
    back, removed = refined.remove_all_removable_knots()
    assert removed == 2 and len(back.knots) == len(c.knots)
    t = np.linspace(0, 1, 50)
    assert np.allclose(back(t), c(t), atol=1e-12)
    net = np.array([[[0, 0, 0], [0, 1, 0], [0, 2, 1]], [[1, 0, 0], [1, 1, 1], [1, 2, 0]]], dtype=float)
    w = np.array([[1.0, 2.0, 1.0], [1.0, 0.5, 1.0]])
    s = lekalo.NurbsSurface(1, 2, [0, 0, 1, 1], [0, 0, 0, 1, 1, 1], net, w)
    u, v = np.linspace(0, 1, 7), np.linspace(0, 1, 7)
    assert np.allclose(s.insert_knot_u(0.4)(u, v), s(u, v), atol=1e-13)
    assert np.allclose(s.insert_knot_v(0.6, 2)(u, v), s(u, v), atol=1e-13)
    a, b = s.split_v(0.5)
    assert np.allclose(a(0.3, 0.2), s(0.3, 0.2), atol=1e-13) and np.allclose(b(0.3, 0.8), s(0.3, 0.8), atol=1e-13)
    assert repr(s).startswith("NurbsSurface(degrees=(1, 2), net=(2, 3)")


def test_out_receives_the_points():
    c = lekalo.NurbsCurve.circle([0, 0], [1, 0], [0, 1], 2.0)
    b = lekalo.interpolate(np.array([[0, 0], [1, 2], [3, 2], [4, 0]], dtype=float))
    t = np.linspace(0, 1, 37)
    for curve in (b, c):
        buf = np.empty((37, 2))
        got = curve(t, out=buf)
        assert got is buf and np.array_equal(buf, curve(t))
    with pytest.raises(lekalo.Error, match="shape"):
        b(t, out=np.empty((36, 2)))
    with pytest.raises(lekalo.Error, match="float64"):
        b(t, out=np.empty((37, 2), dtype=np.float32))
    with pytest.raises(lekalo.Error, match="C-contiguous"):
        b(t, out=np.empty((2, 37)).T)
    # an output that is also the input is refused, not silently overwritten while read
    buf = np.zeros((4, 1))
    one_d = lekalo.interpolate(np.array([0.0, 1.0, 0.5, 2.0]))
    with pytest.raises(lekalo.Error, match="in use"):
        one_d(buf[:, 0], out=buf)


def test_help_shows_how_to_call_curves_and_surfaces():
    # `__call__` is a slot, whose own help is Python's "Call self as a function": the class
    # docstring, which help() shows first, gives the call
    import pydoc

    for cls, call in [
        (lekalo.BezierCurve, "c(t, nu=0)"),
        (lekalo.BSplineCurve, "c(t, nu=0, *, out=None)"),
        (lekalo.NurbsCurve, "c(t, nu=0, *, out=None)"),
        (lekalo.BezierSurface, "s(u, v)"),
        (lekalo.BSplineSurface, "s(u, v)"),
        (lekalo.NurbsSurface, "s(u, v)"),
    ]:
        assert call in pydoc.render_doc(cls, renderer=pydoc.plaintext), cls.__name__


def test_graph_of_a_function_is_t_and_its_value():
    y = lekalo.BSplineCurve(2, [0, 0, 0, 1, 2, 2, 2], [[1.0], [3.0], [0.0], [2.0]])
    g = y.graph()
    t = np.linspace(0, 2, 41)
    np.testing.assert_allclose(g(t), np.column_stack([t, y(t)[:, 0]]), atol=1e-15)
    with pytest.raises(lekalo.Error):
        g.graph()  # a plane curve is not a function
