"""Shape-constrained fits from Python: the keyword arguments reach the library and return the
usual curve types; bad arguments and contradictory constraints raise lekalo.InputError. (The
mathematics is tested in the Rust core.)"""

import numpy as np
import pytest

import lekalo

X = np.linspace(0.0, 1.0, 60)
Y = X + 0.15 * np.sin(12 * X)
T = [0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1]
FINE = np.linspace(0.0, 1.0, 2001)


def values(c, x=FINE):
    return c(x)[:, 0]


def test_lsq_increasing_keeps_its_shape_and_type():
    free = lekalo.make_lsq_spline(X, Y, T)
    assert (np.diff(values(free)) < 0).any()
    c = lekalo.make_lsq_spline(X, Y, T, increasing=True)
    assert isinstance(c, lekalo.BSplineCurve)
    assert (np.diff(values(c)) >= -1e-12).all()


def test_intervals_bounds_and_points():
    c, report = lekalo.fit_least_squares(
        Y, X, T, convex=[(0.0, 0.3)], max=(0.9, 0.5, 1.0), min=0.0, through=(0.0, 0.05), slope_at=(1.0, 1.0)
    )
    v = values(c)
    assert v.min() >= -1e-12
    assert v[FINE >= 0.5].max() <= 0.9 + 1e-12
    assert abs(values(c, [0.0])[0] - 0.05) < 1e-12
    assert abs(c(np.array([1.0]), 1)[0, 0] - 1.0) < 1e-12
    assert report["n_ctrl"] == 8


def test_smoothing_with_and_without_lambda():
    c = lekalo.make_smoothing_spline(X, Y, lam=1e-4, decreasing=[(0.9, 1.0)])
    assert (np.diff(values(c)[FINE >= 0.9]) <= 1e-12).all()
    c, report = lekalo.fit_smoothing(X, Y, concave=True)
    assert report["lam"] > 0
    assert (c(FINE, 2)[:, 0] <= 1e-9).all()


def test_inactive_constraints_give_the_unconstrained_fit():
    free = lekalo.make_lsq_spline(X, Y, T)
    c = lekalo.make_lsq_spline(X, Y, T, min=-10.0, max=10.0)
    assert np.array_equal(c.control, free.control)


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"increasing": "yes"}, "increasing: give True"),
        ({"min": "low"}, "min: give a number"),
        ({"through": 1.0}, "through: give (x, v)"),
        ({"increasing": (0.5, 0.2)}, "ends before it starts"),
        ({"increasing": True, "through": [(0.0, 1.0), (1.0, 0.0)]}, "cannot all hold"),
    ],
)
def test_bad_arguments_raise_input_error(kwargs, words):
    with pytest.raises(lekalo.InputError, match=words.replace("(", r"\(").replace(")", r"\)")):
        lekalo.make_lsq_spline(X, Y, T, **kwargs)


def test_shape_constraints_need_values_not_points():
    with pytest.raises(lekalo.InputError, match="dimension"):
        lekalo.fit_least_squares(np.c_[X, Y], X, T, increasing=True)
    with pytest.raises(lekalo.InputError, match="through"):
        lekalo.fit_least_squares(Y, X, T, clamp_ends=True, increasing=True)


def test_smoothing_condition_with_constraints():
    # the increasing smoothing spline whose residual sum of squares is s (λ found by bisection)
    _, gcv = lekalo.fit_smoothing(X, Y, increasing=True)
    s = 2.0 * gcv["weighted_rss"]
    c, report = lekalo.fit_smoothing_condition(X, Y, s=s, increasing=True)
    assert isinstance(c, lekalo.BSplineCurve)
    assert abs(report["weighted_rss"] - s) <= 1e-3 * s
    assert report["lam"] > gcv["lam"]
    assert (np.diff(values(c)) >= -1e-12).all()
    # the same curve as the constrained smoothing spline of that λ
    again = lekalo.make_smoothing_spline(X, Y, lam=report["lam"], increasing=True)
    assert np.array_equal(values(again), values(c))
    with pytest.raises(lekalo.InputError, match="drop t and k"):
        lekalo.fit_smoothing_condition(X, Y, s=s, t=T, increasing=True)
    with pytest.raises(lekalo.InputError, match="give s"):
        lekalo.fit_smoothing_condition(X, Y, s=1e-12, increasing=True)


def test_bounds_at_points():
    # (v, x): a bound on the value at x alone; (x, x): a derivative's sign at x alone
    free = lekalo.make_lsq_spline(X, Y, T)
    cap = float(values(free, [0.5])[0]) - 0.1
    c = lekalo.make_lsq_spline(X, Y, T, max=(cap, 0.5), min=[(-5.0, 0.2), (-5.0, 0.1, 0.3)])
    assert abs(values(c, [0.5])[0] - cap) < 1e-12
    pinned = lekalo.make_lsq_spline(X, Y, T, through=(0.5, cap))
    assert np.abs(values(c) - values(pinned)).max() < 1e-10
    falls = float(FINE[np.argmin(free(FINE, 1)[:, 0])])
    c = lekalo.make_lsq_spline(X, Y, T, increasing=(falls, falls))
    assert abs(c(np.array([falls]), 1)[0, 0]) < 1e-12


def test_make_splrep_takes_the_shape_keywords():
    _, gcv = lekalo.fit_smoothing(X, Y, increasing=True)
    s = 2.0 * gcv["weighted_rss"]
    c = lekalo.make_splrep(X, Y, s=s, increasing=True)
    assert isinstance(c, lekalo.BSplineCurve)
    assert (np.diff(values(c)) >= -1e-12).all()
    assert abs(((values(c, X) - Y) ** 2).sum() - s) <= 1e-3 * s
    # make_splrep's weights are SciPy's (squared into the condition's)
    w = np.full_like(X, 2.0)
    again, report = lekalo.fit_smoothing_condition(X, Y, s=4.0 * s, w=w * w, increasing=True)
    assert np.array_equal(values(lekalo.make_splrep(X, Y, s=4.0 * s, w=w, increasing=True)), values(again))
    with pytest.raises(lekalo.InputError, match="drop knot_rounds"):
        lekalo.make_splrep(X, Y, s=s, knot_rounds="refit", convex=True)


def test_integrals_and_periodicity():
    c = lekalo.make_lsq_spline(X, Y, T, integral=(0.0, 1.0, 0.6), increasing=True)
    assert abs(c.integrate(0.0, 1.0)[0] - 0.6) < 1e-12
    assert (np.diff(values(c)) >= -1e-12).all()
    wave = np.sin(2 * np.pi * X) + 0.3 * X
    c, report = lekalo.fit_least_squares(wave, X, T, periodic=True, max=0.9)
    ends = c(np.array([0.0, 1.0]), 0)[:, 0], c(np.array([0.0, 1.0]), 1)[:, 0], c(np.array([0.0, 1.0]), 2)[:, 0]
    for d in ends:
        assert abs(d[1] - d[0]) < 1e-9 * (1 + abs(d[0]))
    assert values(c).max() <= 0.9 + 1e-12
    with pytest.raises(lekalo.InputError, match="periodic: give True"):
        lekalo.make_lsq_spline(X, Y, T, periodic="yes")
    with pytest.raises(lekalo.InputError, match="integral: give"):
        lekalo.make_lsq_spline(X, Y, T, integral=1.0)
