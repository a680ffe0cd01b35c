"""Derivatives of NURBS surface evaluation with respect to the knots, from NumPy
(``lekalo.nurbs_surface_knot_jvp`` / ``_vjp``): against central differences of
``lekalo.NurbsSurface`` evaluation in the interior knots of each direction (relative 1e-7), the
VJP against the same Jacobian and the JVP by the adjoint identity, the end knots held fixed,
the weights mattering, and the errors naming the argument. The mathematics (multiple knots,
the quotient rule, tensor NURBS in any number of variables) is tested in the core,
``crates/lekalo/src/derivatives/knots/``."""

import numpy as np
import pytest

import lekalo

P, Q = 2, 3
RTOL = 1e-7


def case():
    rng = np.random.default_rng(17)
    ku = np.array([0, 0, 0, 0.4, 0.65, 1, 1, 1.0])
    kv = np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net = rng.uniform(-1, 1, (5, 5, 3))
    w = rng.uniform(0.3, 3.0, (5, 5))
    u = np.array([0.1, 0.3, 0.5, 0.85, 0.62])
    v = np.array([0.2, 0.45, 0.7, 0.1, 0.93])
    return ku, kv, net, w, u, v


def values(ku, kv, net, w, u, v):
    return lekalo.NurbsSurface(P, Q, ku, kv, net, w)(u, v)


def interior(knots, degree):
    m = np.zeros(len(knots), bool)
    m[degree + 1 : len(knots) - degree - 1] = True
    return m


def central(f, knots, degree, h=1e-6):
    """The Jacobian of ``f(knots)`` by central differences in the interior knots (zero columns
    for the end knots), ``f(knots).shape + knots.shape``."""
    base = np.asarray(f(knots))
    cols = []
    for k in range(len(knots)):
        if not interior(knots, degree)[k]:
            cols.append(np.zeros_like(base))
            continue
        up, down = knots.copy(), knots.copy()
        up[k] += h
        down[k] -= h
        cols.append((np.asarray(f(up)) - np.asarray(f(down))) / (2 * h))
    return np.stack(cols, axis=-1)


def assert_rel(a, b, what):
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, (what, a.shape, b.shape)
    err = np.max(np.abs(a - b))
    scale = max(np.max(np.abs(b)), 1.0)
    assert err <= RTOL * scale, f"{what}: error {err:.3e} above {RTOL} x {scale:.3e}"


def test_nurbs_surface_knot_kernels_match_central_differences():
    ku, kv, net, w, u, v = case()
    ju = central(lambda k: values(k, kv, net, w, u, v), ku, P)
    jv = central(lambda k: values(ku, k, net, w, u, v), kv, Q)
    rng = np.random.default_rng(3)
    du, dv = rng.uniform(-1, 1, ku.shape), rng.uniform(-1, 1, kv.shape)
    vals, tan = lekalo.nurbs_surface_knot_jvp(P, Q, ku, kv, net, w, u, v, du, dv)
    assert vals.shape == tan.shape == (len(u), 3)
    np.testing.assert_allclose(vals, values(ku, kv, net, w, u, v), rtol=0, atol=1e-14)
    assert_rel(tan, ju @ du + jv @ dv, "knot JVP")
    _, tan_v = lekalo.nurbs_surface_knot_jvp(P, Q, ku, kv, net, w, u, v, knots_v_tangent=dv)
    assert_rel(tan_v, jv @ dv, "knot JVP along v")
    g = rng.uniform(-1, 1, vals.shape)
    gu, gv = lekalo.nurbs_surface_knot_vjp(P, Q, ku, kv, net, w, u, v, g)
    assert gu.shape == ku.shape and gv.shape == kv.shape
    assert np.all(gu[~interior(ku, P)] == 0.0) and np.all(gv[~interior(kv, Q)] == 0.0)
    assert_rel(gu, np.einsum("md,mdk->k", g, ju), "knot VJP along u")
    assert_rel(gv, np.einsum("md,mdk->k", g, jv), "knot VJP along v")
    lhs = np.sum(tan * g)
    assert abs(lhs - gu @ du - gv @ dv) <= 1e-12 * np.sum(np.abs(tan * g))
    # the weights matter: the B-spline surface of the same net moves differently
    bspline = lekalo.bspline_surface_knot_jvp(P, Q, ku, kv, net, u, v, du, dv)[1]
    assert np.max(np.abs(tan - bspline)) > 1e-3


def test_equal_weights_give_the_bspline_surface():
    ku, kv, net, _, u, v = case()
    du = np.random.default_rng(8).uniform(-1, 1, ku.shape)
    _, tan = lekalo.nurbs_surface_knot_jvp(P, Q, ku, kv, net, np.full((5, 5), 2.0), u, v, du)
    want = lekalo.bspline_surface_knot_jvp(P, Q, ku, kv, net, u, v, du)[1]
    np.testing.assert_allclose(tan, want, rtol=0, atol=1e-13)


def test_nurbs_surface_knot_kernels_refuse_bad_input():
    ku, kv, net, w, u, v = case()
    with pytest.raises(lekalo.InputError, match="knots_u_tangent"):
        lekalo.nurbs_surface_knot_jvp(P, Q, ku, kv, net, w, u, v, np.zeros(len(ku) + 1))
    with pytest.raises(lekalo.InputError, match="weights: expected shape"):
        lekalo.nurbs_surface_knot_jvp(P, Q, ku, kv, net, w[:4], u, v)
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.nurbs_surface_knot_vjp(P, Q, ku, kv, net, w, u, v, np.zeros((len(u), 2)))
    with pytest.raises(lekalo.InputError, match="weight"):
        lekalo.nurbs_surface_knot_vjp(P, Q, ku, kv, net, -w, u, v, np.zeros((len(u), 3)))
    with pytest.raises(lekalo.InputError, match="outside"):
        lekalo.nurbs_surface_knot_jvp(P, Q, ku, kv, net, w, u + 1.0, v)
