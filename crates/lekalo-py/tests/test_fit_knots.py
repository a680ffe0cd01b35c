"""lekalo.interpolation_knot_jvp / _vjp and lekalo.least_squares_knot_jvp / _vjp: the
derivatives of the fits' control points with respect to the knots against central differences
of the fits (relative 1e-7 of the largest difference quotient, at least 1), the VJPs the
transposes of the JVPs, the end knots held fixed, shapes and errors
(docs/theory/derivatives.md, "Knots of the fits")."""

import numpy as np
import pytest

import lekalo
from derivative_checks import assert_rel, knot_central

KNOTS = np.array([0, 0, 0, 0, 0.23, 0.46, 0.71, 1, 1, 1, 1.0])  # off every parameter below
TANGENT = np.sin(1.3 * np.arange(11)) + 0.2


def interpolation_case():
    x = np.array([0.0, 0.1, 0.3, 0.55, 0.62, 0.85, 1.0])
    return x, np.stack([np.sin(3 * x) + 2, x * x - 0.5 * x], axis=-1)


def interpolated(knots, x, y):
    return lekalo.interpolation_knot_jvp(3, knots, x, y, np.zeros(len(knots)))[0]


def test_interpolation_knot_derivatives():
    x, y = interpolation_case()
    control, jvp = lekalo.interpolation_knot_jvp(3, KNOTS, x, y, TANGENT)
    assert control.shape == jvp.shape == (7, 2)
    assert np.array_equal(control, lekalo.interpolation_jvp(3, KNOTS, x, y))
    jac = knot_central(lambda k: interpolated(k, x, y), KNOTS, 3)  # (7, 2, 11), end columns zero
    assert_rel(jvp, jac @ TANGENT, "interpolation JVP")
    g = np.cos(0.7 * np.arange(14)).reshape(7, 2)
    vjp = lekalo.interpolation_knot_vjp(3, KNOTS, x, y, g)
    assert vjp.shape == (11,)
    assert_rel(vjp, np.einsum("ij,ijk->k", g, jac), "interpolation VJP")
    assert np.all(vjp[:4] == 0) and np.all(vjp[7:] == 0)
    # 1-D data give 1-D control points
    c1, j1 = lekalo.interpolation_knot_jvp(3, KNOTS, x, y[:, 0], TANGENT)
    assert c1.shape == j1.shape == (7,)
    assert_rel(j1, jvp[:, 0], "1-D data")


def least_squares_case():
    rng = np.random.default_rng(5)
    x = rng.permutation(np.linspace(0, 1, 40))
    y = np.stack([np.sin(4 * x) + 10, np.cos(2 * x) * x], axis=-1) + 0.05 * rng.standard_normal((40, 2))
    return x, y, rng.uniform(0.5, 2.5, 40)


def test_least_squares_knot_derivatives():
    x, y, w = least_squares_case()
    control, jvp = lekalo.least_squares_knot_jvp(3, KNOTS, x, y, TANGENT, w)
    assert control.shape == jvp.shape == (7, 2)
    assert np.array_equal(control, lekalo.fit_least_squares(y, x, KNOTS, 3, w=w)[0].control)

    def fitted(k):
        return lekalo.fit_least_squares(y, x, k, 3, w=w)[0].control

    jac = knot_central(fitted, KNOTS, 3)
    assert_rel(jvp, jac @ TANGENT, "least-squares JVP")
    g = np.sin(0.9 * np.arange(14)).reshape(7, 2) - 0.3
    vjp = lekalo.least_squares_knot_vjp(3, KNOTS, x, y, g, w)
    assert_rel(vjp, np.einsum("ij,ijk->k", g, jac), "least-squares VJP")
    assert np.all(vjp[:4] == 0) and np.all(vjp[7:] == 0)


def test_bad_input_says_so():
    x, y, w = least_squares_case()
    with pytest.raises(lekalo.InputError, match="knot tangent"):
        lekalo.least_squares_knot_jvp(3, KNOTS, x, y, TANGENT[:-1], w)
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.least_squares_knot_vjp(3, KNOTS, x, y, np.ones((6, 2)), w)
    xi, yi = interpolation_case()
    with pytest.raises(lekalo.InputError):
        lekalo.interpolation_knot_jvp(3, KNOTS, xi[:-1], yi[:-1], TANGENT)
