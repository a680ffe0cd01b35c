"""Smoothing on given knots and the knot sequence of the smoothing condition, cross-checked
against SciPy's ``make_splrep(t=…)`` and ``generate_knots`` inside the tests.

On given knots both solve the same problem by the same iteration for the smoothing weight from
the same start, so where SciPy's iteration ends with a residual at most s the coefficients agree
to rounding of the banded solves (1e-12 against values of order 1). Where it ends above s (within
its tolerance of 0.1% of s), lekalo continues the same iteration to a residual in
[(1 - 0.1%) s, s]. The knot sequences are FITPACK's knot placement by default: the last is the
knot vector of SciPy's ``splrep`` (FITPACK itself) exactly. SciPy's own ``generate_knots`` adds
the knots of a round one at a time with a new least-squares fit between them, so its
intermediate vectors (and often its last) differ from FITPACK's; ``knot_rounds="refit"`` does
the same, and ``lekalo.scipy`` uses it, so both give SciPy's vectors exactly.
"""

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo

RNG = np.random.default_rng(11)


def noisy(n=60, seed=11):
    rng = np.random.default_rng(seed)
    x = np.r_[0, np.sort(rng.uniform(0, 2 * np.pi, n - 2)), 2 * np.pi]
    y = np.sin(x) + np.cos(2 * x) + 0.05 * rng.standard_normal(n)
    return x, y


@pytest.mark.parametrize("s", [0.5, 1.0, 3.0, 10.0])
def test_make_splrep_on_given_knots_is_scipys(s):
    # the least-squares spline's residual is 0.136, the cubic polynomial's 26.3
    x, y = noisy()
    t = np.r_[[0.0] * 4, np.linspace(0, 2 * np.pi, 9)[1:-1], [2 * np.pi] * 4]
    curve = lekalo.make_splrep(x, y, s=s, t=t)
    ref = si.make_splrep(x, y, s=s, t=t)
    assert np.array_equal(curve.knots, t)
    fp, fp_ref = (np.sum((f(x) - y) ** 2) for f in (lambda u: curve(u)[:, 0], ref))
    if fp_ref <= s:
        assert np.abs(curve.control[:, 0] - ref.c).max() <= 1e-12
    else:
        assert fp_ref <= (1 + 1e-3) * s
        assert (1 - 1e-3) * s <= fp <= s


def test_residual_is_s_between_the_polynomial_and_the_least_squares_spline():
    x, y = noisy()
    t = np.r_[[0.0] * 4, np.linspace(0, 2 * np.pi, 7)[1:-1], [2 * np.pi] * 4]
    w = RNG.uniform(0.5, 2.0, x.size)
    lsq = si.make_lsq_spline(x, y, t, k=3, w=w)
    fp_inf = np.sum((w * (lsq(x) - y)) ** 2)
    s = 4 * fp_inf
    _, report = lekalo.fit_smoothing_condition(x, y, w=w**2, s=s, t=t)
    assert (1 - 1e-3) * s <= report["weighted_rss"] <= s
    assert report["lam"] > 0
    # below the least-squares spline's residual no weight reaches s: that spline
    _, report = lekalo.fit_smoothing_condition(x, y, w=w**2, s=fp_inf / 2, t=t)
    assert report["weighted_rss"] == pytest.approx(fp_inf, rel=1e-10)


def test_fit_periodic_with_knots_and_s_is_scipys_periodic_make_splrep():
    x, y = noisy(80)
    y[-1] = y[0]
    interior = np.linspace(0, 2 * np.pi, 11)[1:-1]
    for s in (0.3, 1.0, 3.0):
        curve, report = lekalo.fit_periodic(x, y, s=s, t=interior)
        ref = si.make_splrep(x, y, s=s, t=curve.knots, bc_type="periodic")
        fp_ref = np.sum((ref(x[:-1]) - y[:-1]) ** 2)
        assert (1 - 1e-3) * s <= report["weighted_rss"] <= s
        if fp_ref <= s:
            assert np.abs(curve.control[:, 0] - ref.c[: len(curve.control)]).max() <= 1e-12
        else:
            assert fp_ref <= (1 + 1e-3) * s


@pytest.mark.parametrize("s", [1e-3, 0.1, 1.0])
def test_generate_knots_ends_on_fitpacks_knots(s):
    x, y = noisy(100)
    seq = lekalo.generate_knots(x, y, s=s)
    assert np.array_equal(seq[-1], si.splrep(x, y, s=s)[0])
    assert all(len(a) < len(b) for a, b in zip(seq, seq[1:]))
    assert len(seq[0]) == 8  # the polynomial first
    # the last knot vector is the one the smoothing condition smooths on
    assert np.array_equal(lekalo.make_splrep(x, y, s=s).knots, seq[-1])


@pytest.mark.parametrize("s", [1e-3, 0.1, 1.0])
def test_refitted_rounds_are_scipys_generate_knots_and_make_splrep(s):
    import lekalo.scipy as ls

    x, y = noisy(200, seed=5)
    ref = list(si.generate_knots(x, y, s=s))
    for seq in (lekalo.generate_knots(x, y, s=s, knot_rounds="refit"), list(ls.generate_knots(x, y, s=s))):
        assert len(seq) == len(ref)
        assert all(np.array_equal(a, b) for a, b in zip(seq, ref))
    assert np.array_equal(lekalo.make_splrep(x, y, s=s, knot_rounds="refit").knots, ref[-1])
    assert np.array_equal(ls.make_splrep(x, y, s=s).t, si.make_splrep(x, y, s=s).t)
    # a parametric curve: SciPy's make_splprep places the same knots
    pts = [np.cos(x) + 0.01 * y, np.sin(x)]
    assert np.array_equal(ls.make_splprep(pts, s=s)[0].t, si.make_splprep(pts, s=s)[0].t)
    if s < 1.0:
        # below, SciPy's make_splrep and its splrep place different knots on these data
        assert not np.array_equal(ref[-1], si.splrep(x, y, s=s)[0])


def test_knot_rounds_is_one_of_two_words():
    x, y = noisy()
    with pytest.raises(ValueError, match="knot_rounds.*'shared', 'refit'"):
        lekalo.make_splrep(x, y, s=1.0, knot_rounds="fresh")
    with pytest.raises(ValueError, match="knot_rounds"):
        lekalo.generate_knots(x, y, s=1.0, periodic=True, knot_rounds="refit")


def test_generate_knots_stops_at_nest_and_refuses_a_smaller_nest():
    x = np.arange(8.0)
    y = np.sin(x * np.pi / 8)
    seq = lekalo.generate_knots(x, y, s=1e-7, nest=10)
    assert np.array_equal(seq[-1], [0, 0, 0, 0, 2, 4, 7, 7, 7, 7])
    with pytest.raises(ValueError, match="max_knots"):
        lekalo.generate_knots(x, y, s=1e-7, nest=7)


def test_periodic_generate_knots_ends_on_fitpacks_knots():
    x, y = noisy(50)
    y[-1] = y[0]
    seq = lekalo.generate_knots(x, y, s=0.2, periodic=True)
    assert np.array_equal(seq[-1], si.splrep(x, y, s=0.2, per=1)[0])
    assert len(seq[0]) == 2 * 3 + 3  # one interior knot first


def test_make_splrep_on_a_wider_domain_is_fitpacks_and_refuses_what_no_spline_reaches():
    # domain=(xb, xe): FITPACK's knots among the data, the end knots at xb and xe (splrep's)
    x, y = noisy()
    curve = lekalo.make_splrep(x, y, s=1.0, domain=(-1.0, 8.0))
    t, _, _ = si.splrep(x, y, s=1.0, xb=-1.0, xe=8.0)
    assert np.array_equal(curve.knots, t)
    assert np.sum((curve(x)[:, 0] - y) ** 2) <= 1.0
    _, report = lekalo.fit_smoothing_condition(x, y, s=1.0, domain=(-1.0, 8.0))
    assert report["weighted_rss"] <= 1.0
    with pytest.raises(lekalo.InputError, match="domain"):
        lekalo.make_splrep(x, y, s=1.0, domain=(1.0, 8.0))
    with pytest.raises(lekalo.InputError, match="drop domain or t"):
        lekalo.make_splrep(x, y, s=1.0, t=t, domain=(-1.0, 8.0))
    # two values at one x leave (0.5² + 0.5²) = 0.5 to every function: s = 0.4 is refused
    xr = np.r_[x[:30], x[29], x[30:]]
    yr = np.r_[y[:30], y[29] + 1.0, y[30:]]
    with pytest.raises(lekalo.InputError, match="s = 0.4 is below"):
        lekalo.make_splrep(xr, yr, s=0.4)
    assert np.sum((lekalo.make_splrep(xr, yr, s=0.6)(xr)[:, 0] - yr) ** 2) <= 0.6
