"""Interpolation and interop, cross-checked against SciPy inside the tests."""

import re
from pathlib import Path

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo

RNG = np.random.default_rng(11)


def test_make_interp_spline_same_curve():
    # lekalo's free-end cubic through (x, y) with de Boor's averaged knots (document 000 eq. 3)
    # is the curve SciPy's make_interp_spline builds when given the same knots
    x = np.sort(RNG.random(30)) * 10
    y = RNG.standard_normal((30, 2))
    c = lekalo.interpolate(y, 3, params=x)
    ref = si.make_interp_spline(x, y, k=3, t=c.knots)
    xx = np.linspace(x[0], x[-1], 500)
    assert np.allclose(c(xx), ref(xx), atol=1e-10)
    assert np.allclose(c.control, ref.c, atol=1e-10)
    for k in (1, 2, 5):
        ck = lekalo.interpolate(y, k, params=x)
        assert np.allclose(ck(xx), si.make_interp_spline(x, y, k=k, t=ck.knots)(xx), atol=1e-9)
    # the natural and clamped cubics are make_interp_spline's with the same bc_type
    nat = lekalo.interpolate(y, 3, params=x, end="natural")
    assert np.allclose(nat(xx), si.make_interp_spline(x, y, k=3, bc_type="natural")(xx), atol=1e-10)
    zero = np.zeros(2)
    cl = lekalo.interpolate(y, 3, params=x, end="derivatives", d_start=zero, d_end=zero)
    assert np.allclose(cl(xx), si.make_interp_spline(x, y, k=3, bc_type="clamped")(xx), atol=1e-10)


def test_natural_spline_matches_cubic_spline():
    x = np.sort(RNG.random(40)) * 3
    y = np.sin(3 * x)
    ref = si.CubicSpline(x, y, bc_type="natural")
    c = lekalo.natural_cubic_spline(x, y)
    xx = np.linspace(x[0], x[-1], 1000)
    assert np.allclose(c(xx)[:, 0], ref(xx), atol=1e-12)
    assert np.allclose(c(xx, nu=1)[:, 0], ref(xx, 1), atol=1e-9)
    # the same through interpolate(..., end="natural", knots at the parameters)
    c2 = lekalo.interpolate(y, 3, params=x, end="natural", knots="at-params")
    assert np.allclose(c2(xx)[:, 0], ref(xx), atol=1e-12)


def test_clamped_spline_matches_cubic_spline():
    x = np.linspace(0, 2, 25)
    y = np.column_stack([np.cos(x), x**2])
    d0, d1 = np.array([0.0, 0.0]), np.array([-np.sin(2.0), 4.0])
    ref = si.CubicSpline(x, y, bc_type=((1, d0), (1, d1)))
    c = lekalo.interpolate(y, 3, params=x, knots="at-params", end="derivatives", d_start=d0, d_end=d1)
    xx = np.linspace(0, 2, 777)
    assert np.allclose(c(xx), ref(xx), atol=1e-12)
    dd0, dd1 = np.array([-1.0, 2.0]), np.array([-np.cos(2.0), 2.0])
    ref2 = si.CubicSpline(x, y, bc_type=((2, dd0), (2, dd1)))
    c2 = lekalo.interpolate(y, 3, params=x, knots="at-params", end="second", d_start=dd0, d_end=dd1)
    assert np.allclose(c2(xx), ref2(xx), atol=1e-12)


def test_periodic_matches_cubic_spline():
    x = np.linspace(0, 2 * np.pi, 17)
    y = np.column_stack([np.cos(x), np.sin(2 * x)])
    y[-1] = y[0]
    ref = si.CubicSpline(x, y, bc_type="periodic")
    c = lekalo.interpolate(y[:-1], 3, params=x, end="periodic")
    xx = np.linspace(0, 2 * np.pi, 400)
    assert np.allclose(c(xx), ref(xx), atol=1e-12)


@pytest.mark.parametrize("param", ["uniform", "chord", "centripetal", 0.3])
@pytest.mark.parametrize("knots", ["auto", "averaged", "uniform", "at-params"])
@pytest.mark.parametrize("degree", [1, 2, 3, 5])
def test_every_configuration_interpolates(param, knots, degree):
    q = RNG.standard_normal((12, 3))
    try:
        c = lekalo.interpolate(q, degree, parametrization=param, knots=knots)
    except lekalo.Error as e:
        # only a documented unsupported combination may refuse, and it says so
        assert "knot" in str(e) or "degree" in str(e)
        return
    t = lekalo.parametrize(q, param)
    assert np.allclose(c(t), q, atol=1e-9)


def test_end_derivatives_any_degree():
    q = RNG.standard_normal((10, 2))
    d0, d1 = np.array([1.0, 0.0]), np.array([0.0, -1.0])
    c = lekalo.interpolate(q, 4, end="derivatives", d_start=d0, d_end=d1)
    assert np.allclose(c(0.0, nu=1), d0, atol=1e-9) and np.allclose(c(1.0, nu=1), d1, atol=1e-9)
    with pytest.raises(lekalo.InputError, match="d_start/d_end: the end condition derivatives needs a derivative at the start and at the end"):
        lekalo.interpolate(q, 3, end="derivatives", d_start=d0)


def test_surface_interpolation():
    u = np.linspace(0, 1, 12)
    v = np.linspace(0, 2, 9)
    U, V = np.meshgrid(u, v, indexing="ij")
    grid = np.stack([U, V, np.sin(U * 3) * np.cos(V)], axis=-1)
    s = lekalo.interpolate_surface(grid, 3, 3, parametrization="uniform")
    pu, pv = np.linspace(0, 1, 12), np.linspace(0, 1, 9)
    assert np.allclose(s.grid(pu, pv), grid, atol=1e-12)
    with pytest.raises(lekalo.Error, match="3-D array"):
        lekalo.interpolate_surface(grid[0])


def test_hermite_matches_pchip():
    x = np.sort(RNG.random(20)) * 5
    y = np.cumsum(RNG.random(20))
    h = lekalo.CubicHermite.function(x, y, tangents="monotone")
    xx = np.linspace(x[0], x[-1], 500)
    hy = h(xx)[:, 0]
    assert np.all(np.diff(hy) >= -1e-12)  # monotone data stay monotone
    assert np.allclose(h(x)[:, 0], y, atol=1e-14)
    # with SciPy's tangents given, the Hermite curve is CubicHermiteSpline bit for bit in value
    d = RNG.standard_normal(20)
    ref = si.CubicHermiteSpline(x, y, d)
    h2 = lekalo.CubicHermite(x, y, d)
    assert np.allclose(h2(xx)[:, 0], ref(xx), atol=1e-12)
    assert np.allclose(h2.to_bspline()(xx)[:, 0], ref(xx), atol=1e-12)
    cr = lekalo.CubicHermite.from_points(RNG.standard_normal((8, 2)), tangents="cardinal", tension=0.5)
    assert cr(np.linspace(0, 1, 5)).shape == (5, 2)


def test_scipy_round_trips_bit_for_bit():
    x = np.sort(RNG.random(15))
    y = RNG.standard_normal((15, 3))
    bs = si.make_interp_spline(x, y, k=3)
    c = lekalo.from_scipy(bs)
    back = lekalo.to_scipy(c)
    assert np.array_equal(back.t, bs.t) and np.array_equal(back.c, bs.c) and back.k == bs.k
    assert lekalo.from_scipy(back) == c
    xx = np.linspace(x[0], x[-1], 300)
    assert np.allclose(c(xx), bs(xx), atol=1e-13)
    # 1-D coefficients come back 1-D
    b1 = si.make_interp_spline(x, y[:, 0], k=3)
    assert np.array_equal(lekalo.to_scipy(lekalo.from_scipy(b1)).c, b1.c)
    # PPoly (CubicSpline is one)
    cs = si.CubicSpline(x, y)
    pp = lekalo.from_scipy(cs)
    assert np.allclose(pp(xx), cs(xx), atol=1e-13)
    pb = lekalo.to_scipy(pp)
    assert np.array_equal(pb.c, cs.c) and np.array_equal(pb.x, cs.x)
    assert lekalo.from_scipy(pb) == pp
    # lekalo's pp-form of a B-spline evaluates like SciPy's PPoly.from_spline
    mine = lekalo.to_scipy(c, "PPoly")
    for d in range(3):
        ref_pp = si.PPoly.from_spline(si.BSpline(c.knots, c.control[:, d], c.degree))
        assert np.allclose(mine(xx)[:, d], ref_pp(xx), atol=1e-12)
    # BPoly: a continuous piecewise Bezier is a B-spline with interior knots of multiplicity k
    bp = lekalo.to_scipy(c, "BPoly")
    assert np.allclose(bp(xx), bs(xx), atol=1e-12)
    c_bp = lekalo.from_scipy(bp)
    back_bp = lekalo.to_scipy(c_bp, "BPoly")
    assert np.array_equal(back_bp.c, bp.c) and np.array_equal(back_bp.x, bp.x)
    assert np.allclose(c_bp(xx), bs(xx), atol=1e-12)
    broken = si.BPoly(RNG.standard_normal((3, 2, 1)), [0, 1, 2])
    with pytest.raises(lekalo.Error, match="do not join"):
        lekalo.from_scipy(broken)


def test_from_scipy_bpoly_of_a_cubic_spline_joins_up_to_rounding():
    # BPoly.from_power_basis of a CubicSpline: neighbouring pieces meet up to an ulp or so
    x = np.linspace(0, 2 * np.pi, 12)
    bp = si.BPoly.from_power_basis(si.CubicSpline(x, np.sin(x)))
    jumps = np.abs(bp.c[-1, :-1] - bp.c[0, 1:])
    assert jumps.max() > 0, "the case needs pieces that differ by rounding"
    c = lekalo.from_scipy(bp)
    xx = np.linspace(0, 2 * np.pi, 200)
    assert np.allclose(c(xx)[:, 0], bp(xx), atol=1e-13)
    # a jump of a millionth of the data's size is still refused, with the numbers
    broken = si.BPoly(bp.c.copy(), bp.x)
    broken.c[0, 6] += 1e-6
    with pytest.raises(lekalo.Error, match="pieces 5 and 6 do not join .* differ by 1e-06"):
        lekalo.from_scipy(broken)


def test_geomdl_dict_round_trip():
    objs = [
        lekalo.interpolate(RNG.standard_normal((6, 3))),
        lekalo.NurbsCurve.circle([0, 0, 0], [1, 0, 0], [0, 1, 0], 1.0),
        lekalo.BSplineSurface(2, 1, [0, 0, 0, 1, 1, 1], [0, 0, 1, 1], RNG.standard_normal((3, 2, 3))),
        lekalo.NurbsSurface(1, 1, [0, 0, 1, 1], [0, 0, 1, 1], RNG.standard_normal((2, 2, 3)), RNG.random((2, 2)) + 0.5),
    ]
    for o in objs:
        d = lekalo.to_geomdl(o)
        assert d["shape"]["count"] == 1
        back = lekalo.from_geomdl(d)
        assert type(back) is type(o)
        if isinstance(o, lekalo.NurbsCurve):
            t = np.linspace(*o.domain, 50)
            assert np.allclose(back(t), o(t), atol=1e-14)
        elif isinstance(o, lekalo.NurbsSurface):
            assert np.allclose(back.grid([0, 0.5, 1], [0, 1]), o.grid([0, 0.5, 1], [0, 1]), atol=1e-14)
        else:
            assert back == o


def test_design_matrix_is_scipys():
    # the banded basis values at sorted and unsorted parameters, against SciPy's design matrix
    # (P&T A2.2 on both sides; the same values to rounding)
    t = np.r_[[0.0] * 4, np.sort(RNG.random(20)), [1.0] * 4]
    for x in (np.linspace(0, 1, 301), RNG.random(200)):
        ours = lekalo.design_matrix(x, t, 3)
        ref = si.BSpline.design_matrix(x, t, 3)
        assert ours.shape == ref.shape == (len(x), len(t) - 4)
        assert np.allclose(ours.toarray(), ref.toarray(), rtol=0, atol=4e-16)
        assert np.allclose(ours.sum(axis=1), 1.0, rtol=0, atol=1e-15)
    spans, values = lekalo.basis_functions(t, 3, np.array([0.0, 0.5, 1.0]))
    assert spans.dtype == np.int64 and values.shape == (3, 4)
    # the first span, and at the right end the last non-empty one (n = len(t) - 5)
    assert spans[0] == 3 and spans[-1] == len(t) - 5
    assert values[0].tolist() == [1.0, 0.0, 0.0, 0.0] and values[-1].tolist() == [0.0, 0.0, 0.0, 1.0]


@pytest.mark.parametrize(
    "x, degree, match",
    [
        (np.array([0.5, np.nan]), 3, r"x\[1\] is NaN"),
        (np.array([1.5]), 3, "outside"),
        (np.array([0.5]), 40, "degree"),
    ],
)
def test_basis_functions_refuse_bad_input(x, degree, match):
    t = np.r_[[0.0] * 4, 0.5, [1.0] * 4]
    with pytest.raises(lekalo.Error, match=match):
        lekalo.basis_functions(t, degree, x)


@pytest.mark.parametrize(
    "call",
    [
        lambda x, y: lekalo.natural_cubic_spline(x, y),
        lambda x, y: lekalo.CubicHermite.function(x, y),
        lambda x, y: lekalo.pchip_slopes(x, y),
        lambda x, y: lekalo.akima_slopes(x, y),
        lambda x, y: lekalo.interpolate_with_end_derivatives(
            x, y, [0, 0, 0, 0, 1, 2, 3, 3, 3, 3], 3, start=[(1, 0.0)], end=[(2, 0.0)]
        ),
    ],
)
def test_functions_of_x_name_an_unsorted_x(call):
    # a function y(x) calls its abscissae x, as the caller does, not the library's "parameters"
    x = np.array([0.0, 2.0, 1.0, 3.0])
    with pytest.raises(lekalo.InputError) as e:
        call(x, np.sin(x))
    message = str(e.value)
    assert "x[2] = 1" in message and "x[1] = 2" in message and "parameters" not in message, message


def test_scipy_argument_order_is_refused_with_the_lekalo_call():
    x = np.linspace(0, 1, 12)
    y = np.sin(x)
    t = np.r_[[0.0] * 4, np.linspace(0, 1, 6)[1:-1], [1.0] * 4]
    c = RNG.standard_normal(8)
    # SciPy's BSpline(t, c, k), make_interp_spline(x, y) and design_matrix(x, t, k) orders
    with pytest.raises(lekalo.Error, match=r"got an array of shape \(12,\).*lekalo\.BSplineCurve\(k, t, c\)"):
        lekalo.BSplineCurve(t, c, 3)
    with pytest.raises(lekalo.Error, match=r"lekalo\.interpolate\(y, k, params=x\)"):
        lekalo.interpolate(x, y)
    with pytest.raises(lekalo.Error, match=r"lekalo\.design_matrix\(x, t, k\)"):
        lekalo.basis_functions(x, t, 3)
    # lekalo's own orders work
    curve = lekalo.BSplineCurve(3, t, c)
    assert np.allclose(curve(x)[:, 0], si.BSpline(t, c, 3)(x), atol=1e-14)
    assert lekalo.interpolate(y, 3, params=x).degree == 3
    assert lekalo.basis_functions(t, 3, x)[1].shape == (12, 4)


def test_messages_name_python_spellings_not_rust_items():
    pts = RNG.standard_normal((6, 2))
    with pytest.raises(lekalo.InputError) as e:
        lekalo.interpolate(pts, 3, knots="at-params", end="free")
    message = str(e.value)
    assert "KnotPlacement" not in message and message.startswith("knots: ") and "auto" in message, message
    net = RNG.standard_normal((4, 3, 3))
    with pytest.raises(lekalo.Error) as e:
        lekalo.BSplineSurface(2, 2, [0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1], net)
    assert "net_size" not in str(e.value) and "rows of the net" in str(e.value), str(e.value)


def test_version_is_the_crates():
    cargo = (Path(__file__).resolve().parents[3] / "Cargo.toml").read_text()
    version = re.search(r'^version = "([^"]+)"', cargo, flags=re.M).group(1)
    assert lekalo.__version__ == version


@pytest.mark.parametrize(
    ("k", "start", "end"),
    [
        (3, [(1, 0.5)], [(2, -1.0)]),
        (3, [], [(1, 2.0), (2, 0.0)]),
        (2, [], [(1, 8.0)]),
        (5, [(1, -12.0), (2, 1.0)], [(1, 8.0), (2, 3.0)]),
    ],
)
def test_end_derivatives_per_end_match_scipy(k, start, end):
    # conditions chosen per end (docs/theory/interpolation.md#derivative-conditions-per-end)
    # give SciPy's make_interp_spline, which solves the same square system
    x = np.linspace(0.0, 3.0, 9) ** 1.2
    y = np.sin(2 * x) + 0.2 * x
    ref = si.make_interp_spline(x, y, k=k, bc_type=(start or None, end or None))
    c = lekalo.interpolate_with_end_derivatives(x, y, ref.t, k, start=start, end=end)
    np.testing.assert_allclose(c.control[:, 0], ref.c, rtol=0, atol=1e-11 * np.abs(ref.c).max())
    for order, value in start:
        assert abs(np.ravel(c(x[0], order))[0] - value) < 1e-9
    for order, value in end:
        assert abs(np.ravel(c(x[-1], order))[0] - value) < 1e-9


def test_end_derivatives_per_end_refusals():
    x = np.arange(4.0)
    t = np.r_[[0.0] * 4, [1.0, 2.0], [3.0] * 4]
    with pytest.raises(lekalo.Error, match="conditions"):
        lekalo.interpolate_with_end_derivatives(x, x, t, 3, start=[(1, 0.0)])
    with pytest.raises(lekalo.Error, match="order"):
        lekalo.interpolate_with_end_derivatives(x, x, t, 3, start=[(4, 0.0)], end=[(1, 0.0)])


@pytest.mark.parametrize(
    "call",
    [
        lambda x, y: lekalo.natural_cubic_spline(x, y),
        lambda x, y: lekalo.CubicHermite.function(x, y),
    ],
)
def test_functions_of_x_name_a_repeated_x(call):
    # two values at one x: the message names x and both indices, and says what to do
    x = np.array([0.0, 1.0, 1.0, 3.0])
    with pytest.raises(lekalo.InputError) as e:
        call(x, np.array([0.0, 1.0, 2.0, 3.0]))
    message = str(e.value)
    assert "x[1] and x[2] are both 1" in message and "merge" in message, message
    assert "parameters" not in message, message


def test_a_wrong_count_names_its_keyword():
    # the library's error carries the argument's key; Python writes it as its keyword
    pts = np.array([[0, 0], [1, 2], [2, 1], [3, 3], [4, 0]], dtype=float)
    with pytest.raises(
        lekalo.InputError, match=re.escape("params: parameters (one per point): expected 5, got 3")
    ):
        lekalo.interpolate(pts, params=[0, 1, 2])
    with pytest.raises(
        lekalo.InputError, match=re.escape("params: parameters (one per point): expected 5, got 2")
    ):
        lekalo.CubicHermite([0, 1], pts, pts)
    # a keyword that is the library's word is not written twice
    with pytest.raises(lekalo.InputError) as e:
        lekalo.CubicHermite([0, 1, 2, 3, 4], pts, pts[:2])
    assert str(e.value) == "tangents (one per point): expected 5, got 2"
    with pytest.raises(
        lekalo.InputError, match=re.escape("w: data weights (one per data point): expected 5, got 2")
    ):
        lekalo.make_lsq_spline(np.arange(5.0), pts[:, 1], [0, 0, 0, 0, 4, 4, 4, 4], w=[1, 2])
