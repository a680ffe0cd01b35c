"""Hermite interpolation in Bernstein form (``hermite_bernstein``,
``piecewise_hermite_bernstein``), piecewise polynomials on decreasing breakpoints
(``PiecewisePolynomial.from_decreasing`` / ``to_decreasing``) and the pp-form's own
extrapolated evaluation, antiderivative and integral (docs/theory/pp.md), checked against the
conditions that define them and against SciPy's ``BPoly`` / ``PPoly``."""

import math

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo


def test_hermite_bernstein_reproduces_the_derivatives():
    ya = np.array([[0.3, 1.0], [-1.0, 0.0], [2.0, 0.5]])
    yb = np.array([[1.0, -2.0], [0.25, 3.0]])
    c = lekalo.hermite_bernstein(1.0, 2.5, ya, yb)
    assert c.shape == (5, 2)
    curve = lekalo.BSplineCurve(4, [1.0] * 5 + [2.5] * 5, c)
    for q in range(3):
        np.testing.assert_allclose(curve.eval_extrapolated([1.0], q)[0], ya[q], rtol=1e-13, atol=1e-13)
    for q in range(2):
        np.testing.assert_allclose(curve.eval_extrapolated([2.5], q)[0], yb[q], rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(c, si.BPoly._construct_from_derivatives(1.0, 2.5, ya, yb), rtol=1e-14)


def test_piecewise_hermite_bernstein_is_scipys_from_derivatives():
    xi = np.array([0.0, 1.0, 2.5, 3.0])
    yi = [[1.0, 0.0], [2.0], [0.0, 1.0, -1.0], [1.0, 2.0]]
    f = lekalo.piecewise_hermite_bernstein(xi, [np.asarray(y) for y in yi])
    ref = si.BPoly.from_derivatives(xi, yi)
    assert f.degree + 1 == ref.c.shape[0]
    # the control points are the Bernstein coefficients piece after piece
    np.testing.assert_allclose(np.asarray(f.control)[:, 0], ref.c.T.ravel(), rtol=1e-13, atol=1e-14)
    g = lekalo.piecewise_hermite_bernstein(xi, [np.asarray(y) for y in yi], orders=[1, 1, 1])
    assert g.degree == 1
    with pytest.raises(lekalo.Error, match="orders"):
        lekalo.piecewise_hermite_bernstein(xi, [np.asarray(y) for y in yi], orders=[3, 1, 1])
    with pytest.raises(lekalo.Error, match="breakpoints"):
        lekalo.piecewise_hermite_bernstein(xi[::-1].copy(), [np.asarray(y) for y in yi])


def test_decreasing_round_trip_and_values():
    rng = np.random.default_rng(1)
    x = np.sort(rng.uniform(0, 5, 7))[::-1].copy()
    c = rng.uniform(-1, 1, (6, 4, 2))  # (pieces, order, dim), lowest power first, about x[i]
    f = lekalo.PiecewisePolynomial.from_decreasing(x, c)
    np.testing.assert_array_equal(f.breakpoints, x[::-1])
    xb, cb = f.to_decreasing()
    np.testing.assert_array_equal(xb, x)
    np.testing.assert_allclose(cb, c, rtol=1e-13, atol=1e-14)
    ref = si.PPoly(np.ascontiguousarray(c[:, ::-1].transpose(1, 0, 2)), x)
    xs = np.linspace(-1, 6, 29)
    np.testing.assert_allclose(f.eval_extrapolated(xs), ref(xs), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(f.eval_extrapolated(xs, 2), ref(xs, 2), rtol=1e-12, atol=1e-12)
    with pytest.raises(lekalo.Error, match="decreasing"):
        lekalo.PiecewisePolynomial.from_decreasing(x[::-1].copy(), c)


def test_antiderivative_and_integral_in_pp_form():
    rng = np.random.default_rng(4)
    x = np.sort(rng.uniform(0, 3, 5))
    c = rng.uniform(-1, 1, (4, 3, 1))
    f = lekalo.PiecewisePolynomial(x, c)
    ref = si.PPoly(np.ascontiguousarray(c[:, ::-1, 0].T), x)
    for n in (1, 2):
        g = f.antiderivative(n)
        assert g.order == 3 + n
        np.testing.assert_allclose(np.asarray(g.coefficients)[:, ::-1, 0].T, ref.antiderivative(n).c, rtol=1e-13, atol=1e-15)
    # anchored elsewhere: vanishes there with its first derivative
    h = f.antiderivative(2, anchor=1.7)
    np.testing.assert_allclose(h.eval_extrapolated([1.7]), [[0.0]], atol=1e-15)
    np.testing.assert_allclose(h.eval_extrapolated([1.7], 1), [[0.0]], atol=1e-15)
    for a, b in [(-1.0, 4.0), (2.0, 0.5)]:
        assert math.isclose(f.integral_extrapolated(a, b)[0], ref.integrate(a, b), rel_tol=1e-13)
