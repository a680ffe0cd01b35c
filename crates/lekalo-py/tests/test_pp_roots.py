"""Roots of piecewise polynomials (``PiecewisePolynomial.solve``, docs/theory/pp.md#roots),
checked against SciPy's ``PPoly.solve`` and ``sproot`` inside the tests.

Simple roots agree with SciPy's to rounding of the root (SciPy takes companion-matrix eigenvalues
and one Newton step, lekalo isolates and bisects, then the same Newton step): 1e-12 for roots of
order 1 in x of a well-conditioned spline.
"""

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo


def lekalo_pp(x, c):
    """lekalo's pp-form of SciPy's (order, pieces) coefficients, highest power first."""
    return lekalo.PiecewisePolynomial(x, np.ascontiguousarray(c[::-1, :, None].transpose(1, 0, 2)))


@pytest.mark.parametrize("extrapolate", [True, False])
def test_solve_is_scipys_on_a_random_cubic_spline(extrapolate):
    rng = np.random.default_rng(2)
    x = np.sort(rng.uniform(0, 10, 25))
    y = np.sin(x) + 0.3 * rng.standard_normal(25)
    cs = si.CubicSpline(x, y)
    for level in (0.0, 0.4):
        mine = lekalo_pp(cs.x, cs.c).solve(level, extrapolate=extrapolate)[0]
        ref = cs.solve(level, extrapolate=extrapolate)
        assert mine.shape == ref.shape
        assert np.abs(mine - ref).max() <= 1e-12


def test_identically_zero_pieces_and_jumps_follow_scipys_convention():
    x = np.array([0, 0.4, 0.6, 1.0])
    c = np.array([[-1, 0.25], [0, 0], [-1, 0.25]]).T
    r = lekalo_pp(x, c).solve(0.0)[0]
    assert np.array_equal(r, [0.25, 0.4, np.nan, 0.85], equal_nan=True)
    jump = lekalo_pp(np.array([0, 0.5, 1]), np.array([[1.0, -1.0]]))
    assert np.array_equal(jump.solve(0.0)[0], [0.5])
    assert jump.solve(0.0, discontinuity=False)[0].size == 0


def test_every_coordinate_is_solved():
    x = np.array([0.0, 1.0, 2.0])
    c = np.zeros((2, 2, 2))
    c[:, :, 0] = [[1.0, 1.0], [-0.5, 0.5]]  # x − 0.5 on both pieces
    c[:, :, 1] = [[-1.0, -1.0], [1.5, 0.5]]  # 1.5 − x
    pp = lekalo.PiecewisePolynomial(x, np.ascontiguousarray(c[::-1].transpose(1, 0, 2)))
    r = pp.solve(0.0, extrapolate=False)
    assert [a.tolist() for a in r] == [[0.5], [1.5]]


def test_lekalo_scipy_sproot_is_fitpacks():
    x = np.linspace(0.1, 15, 40)
    tck = si.splrep(x, np.sin(x))
    from lekalo.scipy import sproot

    assert np.abs(sproot(tck) - si.sproot(tck)).max() <= 1e-12
    with pytest.warns(RuntimeWarning, match="exceeds mest"):
        assert sproot(tck, mest=2).size == 2
    with pytest.raises(ValueError, match="cubic"):
        sproot((tck[0], tck[1], 2))
