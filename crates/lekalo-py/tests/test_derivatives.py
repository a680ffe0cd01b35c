"""The NumPy derivative kernels (lekalo.bspline_curve_jvp / _vjp / _linearize and the surface
ones): shapes, the layer's conversions, agreement between the three, and errors. The
mathematics is tested in the core (crates/lekalo/src/derivatives/tests.rs)."""

import numpy as np
import pytest

import lekalo

KNOTS = np.array([0, 0, 0, 0.4, 1, 1, 1.0])
CTRL = np.array([[0, 0], [1, 2], [3, 2], [4, 0.0]])


def test_curve_kernels_shapes_and_agreement():
    t = np.array([[0.1, 0.5, 0.9]])  # any shape
    dc = np.arange(8.0).reshape(4, 2)
    dt = np.array([[1.0, -2.0, 0.5]])
    values, tangent = lekalo.bspline_curve_jvp(2, KNOTS, CTRL, t, dc, dt)
    assert values.shape == tangent.shape == (1, 3, 2)
    # the curve object's evaluation runs by polynomial pieces: equal to rounding
    np.testing.assert_allclose(values, lekalo.BSplineCurve(2, KNOTS, CTRL)(t), rtol=0, atol=1e-14)
    lin = lekalo.bspline_curve_linearize(2, KNOTS, CTRL, t)
    assert lin["first"].dtype == np.int64 and lin["first"].shape == (1, 3)
    assert lin["basis"].shape == (1, 3, 3)
    assert np.array_equal(lin["values"], values)
    rows = lin["first"][..., None] + np.arange(3)
    applied = np.einsum("...k,...kd->...d", lin["basis"], dc[rows]) + lin["derivatives"] * dt[..., None]
    np.testing.assert_allclose(applied, tangent, rtol=1e-14, atol=1e-14)
    g = np.ones_like(values)
    gc, gt = lekalo.bspline_curve_vjp(2, KNOTS, CTRL, t, g)
    assert gc.shape == CTRL.shape and gt.shape == t.shape
    # the VJP is the transpose of the JVP
    assert np.isclose(np.sum(g * tangent), np.sum(gc * dc) + np.sum(gt * dt), rtol=1e-14)
    # no tangent: zero
    assert not np.any(lekalo.bspline_curve_jvp(2, KNOTS, CTRL, t)[1])


def test_surface_kernels_shapes_and_agreement():
    net = np.arange(24.0).reshape(3, 4, 2) ** 1.5
    ku, kv = np.array([0, 0, 0.5, 1, 1.0]), np.array([0, 0, 0, 0.5, 1, 1, 1.0])
    u, v = np.array([0.2, 0.7]), np.array([0.3, 0.9])
    dn = np.ones_like(net)
    values, tangent = lekalo.bspline_surface_jvp(1, 2, ku, kv, net, u, v, dn, u_tangent=np.ones(2))
    assert np.allclose(values, lekalo.BSplineSurface(1, 2, ku, kv, net)(u, v), rtol=0, atol=1e-13)
    lin = lekalo.bspline_surface_linearize(1, 2, ku, kv, net, u, v)
    assert np.array_equal(lin["values"], values)
    # a constant net tangent moves every point by it (partition of unity), plus S_u
    np.testing.assert_allclose(tangent, 1 + lin["derivatives_u"], rtol=1e-14)
    g = np.ones_like(values)
    gn, gu, gv = lekalo.bspline_surface_vjp(1, 2, ku, kv, net, u, v, g)
    assert gn.shape == net.shape and gu.shape == gv.shape == u.shape
    np.testing.assert_allclose(gn.sum(), 2 * 2, rtol=1e-14)  # two points, two coordinates
    np.testing.assert_allclose(gv, lin["derivatives_v"].sum(axis=-1), rtol=1e-14)


def test_kernels_refuse_bad_input():
    t = np.array([0.5])
    with pytest.raises(lekalo.InputError, match="control_tangent: shape"):
        lekalo.bspline_curve_jvp(2, KNOTS, CTRL, t, np.zeros((3, 2)))
    with pytest.raises(lekalo.InputError, match="cotangent: shape"):
        lekalo.bspline_curve_vjp(2, KNOTS, CTRL, t, np.zeros((1, 3)))
    with pytest.raises(lekalo.InputError, match="outside the domain"):
        lekalo.bspline_curve_linearize(2, KNOTS, CTRL, np.array([2.0]))
    with pytest.raises(lekalo.InputError, match="finite"):
        lekalo.bspline_curve_jvp(2, KNOTS, CTRL, t, t_tangent=np.array([np.nan]))
    with pytest.raises(lekalo.InputError, match="knots"):
        lekalo.bspline_curve_vjp(3, KNOTS, CTRL, t, np.zeros((1, 2)))


def test_nurbs_kernels_shapes_and_agreement():
    w = np.array([1.0, 2.0, 0.5, 1.0])
    t = np.array([0.1, 0.5, 0.9])
    dc, dw, dt = np.ones_like(CTRL), np.array([0.0, 1.0, 0.0, 0.0]), np.ones(3)
    values, tangent = lekalo.nurbs_curve_jvp(2, KNOTS, CTRL, w, t, dc, dw, dt)
    np.testing.assert_allclose(values, lekalo.NurbsCurve(2, KNOTS, CTRL, w)(t), rtol=0, atol=1e-14)
    lin = lekalo.nurbs_curve_linearize(2, KNOTS, CTRL, w, t)
    assert np.array_equal(lin["values"], values)
    np.testing.assert_allclose(lin["basis"].sum(axis=-1), 1.0, rtol=1e-14)  # rational partition of unity
    g = np.arange(6.0).reshape(3, 2)
    gc, gw, gt = lekalo.nurbs_curve_vjp(2, KNOTS, CTRL, w, t, g)
    assert gc.shape == CTRL.shape and gw.shape == w.shape and gt.shape == t.shape
    assert np.isclose(np.sum(g * tangent), np.sum(gc * dc) + np.sum(gw * dw) + np.sum(gt * dt), rtol=1e-13)
    with pytest.raises(lekalo.InputError, match="weights_tangent: shape"):
        lekalo.nurbs_curve_jvp(2, KNOTS, CTRL, w, t, weights_tangent=np.ones(3))


def test_interpolation_kernels_against_scipy_and_each_other():
    x = np.array([0.0, 0.1, 0.35, 0.6, 0.8, 1.0])
    knots = np.array([0, 0, 0, 0, 0.35, 0.6, 1, 1, 1, 1.0])
    y = np.sin(3 * x)[:, None] * [1.0, 2.0]
    # the JVP of a linear map is the map: the interpolant's control points
    scipy = pytest.importorskip("scipy.interpolate")
    ref = scipy.make_interp_spline(x, y, k=3, t=knots).c
    np.testing.assert_allclose(lekalo.interpolation_jvp(3, knots, x, y), ref, rtol=1e-12, atol=1e-13)
    # the VJP is its transpose: <g, A^-1 y> = <A^-T g, y>
    g = np.cos(np.arange(12.0)).reshape(6, 2)
    gy = lekalo.interpolation_vjp(3, knots, x, g)
    assert gy.shape == g.shape
    assert np.isclose(np.sum(g * ref), np.sum(gy * y), rtol=1e-12)
    with pytest.raises(lekalo.InputError, match="knots"):
        lekalo.interpolation_vjp(3, knots[:-1], x, g)


def test_fit_values_and_factors_give_the_fits_and_their_derivatives_bit_for_bit():
    """A fit's values with its map as numbers (one factorisation): the values are the fit's and
    the JVP and VJP through `factors=` those of the kernels that factor on their own, bit for
    bit; factors of the wrong length are refused, naming them."""
    rng = np.random.default_rng(5)
    x = np.sort(rng.uniform(0, 1, 30))
    x[0], x[-1] = 0.0, 1.0
    y = np.stack([np.sin(3 * x), np.cos(2 * x) + 5.0], axis=-1)
    t = np.array([0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1.0])
    dq = np.cos(np.arange(60.0)).reshape(30, 2)
    for w in (None, rng.uniform(0.5, 2, 30)):
        control, f = lekalo.least_squares_values_and_factors(3, t, x, y, w)
        assert np.array_equal(control, lekalo.fit_least_squares(y, x, t, 3, w=w)[0].control)
        assert f.shape == (lekalo._lekalo.least_squares_map_flat_len(30, 6, 3),)
        g = np.sin(np.arange(12.0)).reshape(6, 2)
        assert np.array_equal(
            lekalo.least_squares_vjp(3, t, x, g, w, factors=f), lekalo.least_squares_vjp(3, t, x, g, w)
        )
        assert np.array_equal(
            lekalo.least_squares_jvp(3, t, x, dq, w, factors=f), lekalo.least_squares_jvp(3, t, x, dq, w)
        )
        control, f = lekalo.smoothing_values_and_factors(x, y, 1e-3, w)
        assert np.array_equal(control, lekalo.fit_smoothing(x, y, w, 1e-3)[0].control)
        assert f.shape == (lekalo._lekalo.smoothing_map_flat_len(30),)
        g = np.sin(np.arange(64.0)).reshape(32, 2)
        assert np.array_equal(
            lekalo.smoothing_vjp(x, 1e-3, g, w, factors=f), lekalo.smoothing_vjp(x, 1e-3, g, w)
        )
        assert np.array_equal(
            lekalo.smoothing_jvp(x, 1e-3, dq, w, factors=f), lekalo.smoothing_jvp(x, 1e-3, dq, w)
        )
    # 1-D data: 1-D control points
    c1, _ = lekalo.least_squares_values_and_factors(3, t, x, y[:, 0])
    assert c1.shape == (6,)
    with pytest.raises(lekalo.InputError, match="factors"):
        lekalo.least_squares_vjp(3, t, x, np.ones((6, 2)), factors=np.ones(7))
    with pytest.raises(lekalo.InputError, match="factors"):
        lekalo.smoothing_vjp(x, 1e-3, np.ones((32, 2)), factors=np.ones(7))
