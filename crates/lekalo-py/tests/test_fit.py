"""Fitting, cross-checked against SciPy inside the tests where SciPy solves the same problem.

Tolerances are relative to the data's scale (values of order 1 here): the same least-squares or
penalised problem solved by two stable methods agrees to ~1e-10 of the data (QR by Givens
rotations here, FITPACK's / SciPy's own factorisations there); smaller differences would be
rounding of a particular factorisation, not a different answer.
"""

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo
import lekalo.scipy

RNG = np.random.default_rng(23)
RTOL = 1e-10  # relative to max |y|, see the module docstring


def noisy(n=200, dim=None):
    x = np.sort(RNG.random(n))
    x[0], x[-1] = 0.0, 1.0
    y = np.sin(6 * x) + 0.05 * RNG.standard_normal(n)
    if dim == 2:
        y = np.column_stack([y, np.cos(3 * x) + 0.05 * RNG.standard_normal(n)])
    return x, y


def close(a, b, scale):
    return np.abs(np.asarray(a) - np.asarray(b)).max() <= RTOL * scale


def test_make_lsq_spline_is_scipys():
    x, y = noisy(dim=2)
    w = RNG.random(len(x)) + 0.5
    t = np.r_[[0.0] * 4, np.linspace(0, 1, 9)[1:-1], [1.0] * 4]
    c = lekalo.make_lsq_spline(x, y, t, k=3, w=w)
    ref = si.make_lsq_spline(x, y, t, k=3, w=w)
    assert np.array_equal(c.knots, t)
    assert close(c.control, ref.c, np.abs(y).max())
    xx = np.linspace(0, 1, 301)
    assert close(c(xx), ref(xx), np.abs(y).max())
    # one-dimensional data come back as (n, 1)
    y0 = y[:, 0]  # a strided view, copied once on the way in
    c1 = lekalo.make_lsq_spline(x, y0, t, k=3)
    assert close(c1(xx)[:, 0], si.make_lsq_spline(x, y[:, 0], t, k=3)(xx), np.abs(y).max())


def test_fit_least_squares_report_and_end_constraints():
    x, y = noisy(dim=2)
    t = lekalo.place_knots(x, 8, 3)
    assert len(t) == 8 + 4 and t[0] == 0.0 and t[-1] == 1.0
    c, rep = lekalo.fit_least_squares(y, x, t, 3)
    res = np.linalg.norm(c(x) - y, axis=1)
    assert np.allclose(rep["residuals"], res, rtol=0, atol=1e-13)
    assert np.isclose(rep["max_residual"], res.max(), rtol=1e-14) and rep["max_index"] == int(res.argmax())
    assert rep["n_ctrl"] == 8 and rep["lam"] is None
    assert np.isclose(rep["weighted_rss"], (res**2).sum(), rtol=1e-12)
    # clamped ends pass exactly through the first and last point; derivatives as asked
    d0, d1 = np.array([1.0, 0.0]), np.array([0.0, -1.0])
    cc, _ = lekalo.fit_least_squares(y, x, t, 3, clamp_ends=True, d_start=d0, d_end=d1)
    assert np.allclose(cc(0.0), y[0], atol=1e-13) and np.allclose(cc(1.0), y[-1], atol=1e-13)
    assert np.allclose(cc(0.0, nu=1), d0, atol=1e-11) and np.allclose(cc(1.0, nu=1), d1, atol=1e-11)
    # the unconstrained fit has the smaller residual
    assert rep["weighted_rss"] <= lekalo.fit_least_squares(y, x, t, 3, clamp_ends=True)[1]["weighted_rss"]


@pytest.mark.parametrize("lam", [1e-6, 1e-3, 1.0])
def test_make_smoothing_spline_given_lambda_is_scipys(lam):
    x, y = noisy(150)
    w = RNG.random(len(x)) + 0.5
    c = lekalo.make_smoothing_spline(x, y, w=w, lam=lam)
    ref = si.make_smoothing_spline(x, y, w=w, lam=lam)
    xx = np.linspace(0, 1, 401)
    # the same curve to 1e-6 of the data; SciPy solves the penalised normal equations, whose
    # rounding grows with λ, so the two differ in the last digits by up to ~1e-7 of the data
    assert np.abs(c(xx)[:, 0] - ref(xx)).max() <= 1e-6 * np.abs(y).max()
    # and lekalo's is the better minimiser of the common objective (to rounding)
    ours = objective(lambda t: c(t)[:, 0], lambda t: c(t, nu=2)[:, 0], x, y, w, lam)
    theirs = objective(ref, lambda t: ref(t, 2), x, y, w, lam)
    assert ours <= theirs * (1 + 1e-12)


def test_a_penalty_too_small_for_points_of_weight_zero_names_them_and_lambda():
    """Points of weight 0 leave their stretch of the curve to the penalty alone; a λ below the
    rounding of the other terms cannot fix it there. The message names λ, the points and the
    fix, not the weights of the data as a whole."""
    x = np.arange(11.0)
    y = np.sin(x)
    w = np.ones(11)
    w[4] = 0.0
    with pytest.raises(lekalo.NumericalError) as e:
        lekalo.make_smoothing_spline(x, y, w=w, lam=1e-300)
    msg = str(e.value)
    assert "λ = 1e-300 is too small" in msg and "the point of weight 0 at x = 4" in msg, msg
    assert "raise λ" in msg and "two distinct parameters" not in msg, msg
    assert np.all(np.isfinite(lekalo.make_smoothing_spline(x, y, w=w, lam=1e-6).control))


def objective(f, f2, x, y, w, lam):
    # Σ w (y − f)² + λ ∫ f''²; f'' is linear between the data (the knots), so two-point
    # Gauss–Legendre on each interval integrates f''² exactly
    a, b = x[:-1], x[1:]
    h, m = (b - a) / 2, (a + b) / 2
    g = 1 / np.sqrt(3)
    integral = (h * (f2(m - g * h) ** 2 + f2(m + g * h) ** 2)).sum()
    return (w * (y - f(x)) ** 2).sum() + lam * integral


def test_smoothing_spline_gcv_minimises_the_score():
    x, y = noisy(120)
    c, rep = lekalo.fit_smoothing(x, y)
    lam = rep["lam"]
    assert lam > 0
    best = lekalo.gcv_score(x, y, lam)
    for f in (0.5, 2.0):
        assert best <= lekalo.gcv_score(x, y, lam * f)
    # the GCV fit is close to SciPy's GCV fit (the two choose λ by different minimisers of the
    # same score, so the curves agree to the noise level's fraction, not to rounding)
    ref = si.make_smoothing_spline(x, y)
    xx = np.linspace(0, 1, 201)
    assert np.abs(c(xx)[:, 0] - ref(xx)).max() < 0.02
    assert np.allclose(lekalo.make_smoothing_spline(x, y)(xx), c(xx), rtol=0, atol=0)


def test_smoothing_spline_gcv_agrees_with_scipy_on_many_close_points():
    # 2000 noisy points of sin on [0, 10]: the least GCV score lies many decades above the scale
    # of one knot interval, beyond a local minimum; both libraries must find the least one, and
    # then the curves agree to a small fraction of the noise (the minimum is flat in λ)
    rng = np.random.default_rng(1)
    x = np.unique(rng.uniform(0, 10, 2000))
    y = np.sin(x) + 0.1 * rng.standard_normal(x.size)
    c, rep = lekalo.fit_smoothing(x, y)
    ref = si.make_smoothing_spline(x, y)
    xx = np.linspace(x[0], x[-1], 4001)
    assert np.abs(c(xx)[:, 0] - ref(xx)).max() < 0.01 * 0.1
    # and lekalo's λ scores no worse than any λ of a scan four points a decade
    lams = 10.0 ** np.arange(-9.0, 1.01, 0.25)
    assert lekalo.gcv_score(x, y, rep["lam"]) <= min(lekalo.gcv_score(x, y, l) for l in lams) * (1 + 1e-9)


def test_make_splrep_meets_the_smoothing_condition():
    x, y = noisy(300)
    for s in (0.5, 0.8, 2.0):
        c, rep = lekalo.fit_smoothing_condition(x, y, s=s)
        rss = ((c(x)[:, 0] - y) ** 2).sum()
        assert rss <= s * (1 + 1e-12) and np.isclose(rss, rep["weighted_rss"], rtol=1e-10)
        # about as few knots as FITPACK (different knot positions: within 25 %)
        t_ref, _, _ = si.splrep(x, y, s=s)
        assert len(c.knots) <= 1.25 * len(t_ref)
    # SciPy's weights multiply the residual before squaring, in make_splrep as in splrep
    w = RNG.random(len(x)) + 0.5
    cw = lekalo.make_splrep(x, y, w=w, s=0.8)
    assert ((w * (cw(x)[:, 0] - y)) ** 2).sum() <= 0.8 * (1 + 1e-12)
    # s = 0 interpolates, like splrep(s=0)
    xs, ys = x[::10].copy(), y[::10].copy()
    c0 = lekalo.make_splrep(xs, ys, s=0.0)
    assert np.abs(c0(xs)[:, 0] - ys).max() < 1e-12


def test_make_splrep_meets_s_where_fitpack_crowds_knots_at_an_end():
    # degree 5 on x = 0..32 with 2, 3, 4, 13, 17 twice and s = 1.23 x the floor (the weighted
    # spread of the repeated x about their means): FITPACK's knot placement reaches knots at
    # every x up to the one beside the end, where SciPy's make_splrep fails with a NaN residual
    # and lekalo's core returned a singular system; it now meets SciPy's condition
    # sum((w (y - f(x)))**2) <= s, with the core's answer
    y = np.array([
        -4.029037990677428, 9.626101361258689, 0.0, 0.0, -8.09980283348563, -9.509489074122564,
        0.0, 0.0, 0.0, 1.8918808915477918, 1.9405890176149876, 0.0, 0.0, 7.846190464689588, 0.0,
        -9.204206745791021, -4.016889001352744, -9.307541950201875, -4.755798299639974, 0.0,
        3.833506526127549, 0.0, 0.0, 0.0, 1.1354758863512153, 7.549532139157431, 0.0, 0.0,
        -7.34383642430111, 8.75869212873954, -8.867087234609334, 8.056407855360233, 0.0,
        9.000191895698398, -4.641608455235483, 0.0, 0.0, 0.0,
    ])
    w2 = np.array([
        1.3948055878700059, 1.2355587283940903, 0.1, 0.1, 0.1, 2.9646235104941034, 0.1,
        2.0818083801274727, 0.1, 0.1, 0.1, 0.2165681611212658, 0.1, 2.2251924929218525, 0.1,
        0.1, 0.1, 2.731590005783488, 0.1, 0.1, 0.1, 0.23721576009323747, 0.11836492440495122,
        0.5492957943882473, 0.8533706638154716, 0.4221225413728792, 1.8056462804377271, 0.1,
        2.0050406311688556, 2.1142023999314556, 1.7751549551796757, 2.351344344566852, 0.1,
        2.3651192272081234, 0.1, 0.1, 2.850006039009024, 0.1,
    ])
    x = np.sort(np.r_[np.arange(33.0), [17.0, 2.0, 4.0, 3.0, 13.0]])
    floor = 0.0
    for v in np.unique(x):
        at = x == v
        mean = (w2[at] * y[at]).sum() / w2[at].sum()
        floor += (w2[at] * (y[at] - mean) ** 2).sum()
    s = 1.2304497694341847 * floor
    w = np.sqrt(w2)  # SciPy's weights multiply the residual
    core, rep = lekalo.fit_smoothing_condition(x, y, w=w2, k=5, s=s)
    ours = lekalo.make_splrep(x, y, w=w, k=5, s=s)
    # SciPy's make_splrep knots (a fit after every knot), which lekalo.scipy places
    refit = lekalo.make_splrep(x, y, w=w, k=5, s=s, knot_rounds="refit")
    dropin = lekalo.scipy.make_splrep(x, y, w=w, k=5, s=s)
    assert np.array_equal(ours.knots, core.knots) and np.array_equal(dropin.t, refit.knots)
    for f, same in ((ours(x)[:, 0], core(x)[:, 0]), (dropin(x), refit(x)[:, 0])):
        rss = ((w * (y - f)) ** 2).sum()
        assert (1 - 2e-3) * s <= rss <= s * (1 + 1e-12), (rss, s)
        assert np.allclose(f, same, rtol=0, atol=1e-12 * np.abs(y).max())
    assert np.isclose(rep["weighted_rss"], ((w * (y - core(x)[:, 0])) ** 2).sum(), rtol=1e-10)
    # below the floor no function meets s: refused naming s
    with pytest.raises(lekalo.InputError, match="^s: "):
        lekalo.make_splrep(x, y, w=w, k=5, s=0.999 * floor)


def test_fit_smoothing_condition_continues_from_the_rounds_of_a_report():
    x, y = noisy(300)
    c, rep = lekalo.fit_smoothing_condition(x, y, s=1.5, nest=150, resume=True)
    r = rep["rounds"]
    assert set(r) == {"knots", "fp0", "fp_before", "nplus", "restart", "nest", "resume"}
    assert len(r["knots"]) > 0 and r["fp0"] > 1.5
    assert np.array_equal(r["knots"], c.knots[4:-4]) and r["nest"] == 150 and r["resume"] is True
    # continued with a smaller s: the earlier knots kept, more added, the condition met
    c2, rep2 = lekalo.fit_smoothing_condition(x, y, s=0.8, start=r)
    assert set(r["knots"]) <= set(c2.knots) and len(c2.knots) > len(c.knots)
    assert rep2["weighted_rss"] <= 0.8 * (1 + 1e-3)
    # lekalo.scipy's UnivariateSpline continues the same rounds (SciPy's set_smoothing_factor)
    spl = lekalo.scipy.UnivariateSpline(x, y, s=1.5)
    spl.set_smoothing_factor(0.8)
    assert np.array_equal(spl.get_knots(), c2.knots[3:-3])
    # the state carries its limit and knots; no rounds with t or shape constraints
    with pytest.raises(lekalo.InputError, match="^nest: "):
        lekalo.fit_smoothing_condition(x, y, s=0.8, start=r, nest=150)
    with pytest.raises(lekalo.InputError, match="^start: "):
        lekalo.fit_smoothing_condition(x, y, s=0.8, start=r, t=c.knots)
    with pytest.raises(lekalo.InputError, match="^start: "):
        lekalo.fit_smoothing_condition(x, y, s=0.8, start=r, increasing=True, k=3)
    with pytest.raises(lekalo.InputError, match='^start: no "fp0"'):
        lekalo.fit_smoothing_condition(x, y, s=0.8, start={k: v for k, v in r.items() if k != "fp0"})
    moved = dict(r, knots=r["knots"] + 1e-3)
    with pytest.raises(ValueError, match="not a data parameter"):
        lekalo.fit_smoothing_condition(x, y, s=0.8, start=moved)
    assert "rounds" not in lekalo.fit_smoothing_condition(x, y, s=0.8, t=c.knots)[1]


def test_make_splprep_domain_puts_the_end_knots():
    th = np.linspace(0, 1.5 * np.pi, 60)
    pts = np.column_stack([np.cos(th), np.sin(th)]) + 0.01 * RNG.standard_normal((60, 2))
    u = np.linspace(0.0, 1.0, 60)
    c, uu = lekalo.make_splprep(pts, u=u, s=0.05, domain=(-0.2, 1.3))
    assert np.array_equal(uu, u)
    assert np.all(c.knots[:4] == -0.2) and np.all(c.knots[-4:] == 1.3)
    assert ((c(u) - pts) ** 2).sum() <= 0.05 * (1 + 1e-3)
    with pytest.raises(lekalo.InputError, match="^domain: "):
        lekalo.make_splprep(pts, u=u, s=0.05, domain=(0.1, 1.3))
    with pytest.raises(lekalo.InputError, match="^domain: "):
        lekalo.make_splprep(pts, u=u, s=0.05, domain=(-0.2, 1.3), t=[0.0] * 4 + [1.0] * 4)


def test_make_splprep_parametric():
    th = np.linspace(0, 1.5 * np.pi, 120)
    pts = np.column_stack([np.cos(th), np.sin(th)]) + 0.01 * RNG.standard_normal((120, 2))
    c, u = lekalo.make_splprep(pts, s=120 * 0.01**2 * 2)
    assert u[0] == 0 and u[-1] == 1 and np.all(np.diff(u) > 0)
    assert np.allclose(u, lekalo.parametrize(pts, "chord"), rtol=0, atol=0)
    assert ((c(u) - pts) ** 2).sum() <= 120 * 0.01**2 * 2 * (1 + 1e-12)
    assert c.control.shape[0] < 30


def test_fit_tolerance():
    t = np.linspace(0, 3, 400)
    pts = np.column_stack([t, np.sin(t)])
    for dev in ("distance", "parameter"):
        c, rep = lekalo.fit_tolerance(pts, 1e-4, 3, deviation=dev)
        assert rep["max_deviation"] <= 1e-4
        assert c.control.shape[0] < 25
        assert np.allclose(c(0.0), pts[0]) and np.allclose(c(1.0), pts[-1])
    # the "parameter" deviation is the distance at the data parameter, checked here directly
    assert np.allclose(np.linalg.norm(c(rep["params"]) - pts, axis=1), rep["deviations"], atol=1e-13)


def test_fit_tolerance_deviations_are_the_residuals_at_the_closest_params():
    # the README tour's noisy sine: within 0.01 at each point's closest point, where the
    # residual is measured; at the chord-length parameters one point is 0.01006 away
    x = np.arange(80) / 16
    pts = np.column_stack([x, np.sin(x) + 0.002 * (np.arange(80) % 5 - 2)])
    c, rep = lekalo.fit_tolerance(pts, 0.01)
    residuals = np.linalg.norm(c(rep["closest_params"]) - pts, axis=1)
    # evaluated here by another path than the library's report: equal to rounding of the data
    np.testing.assert_allclose(residuals, rep["deviations"], rtol=0, atol=1e-14 * np.abs(pts).max())
    assert residuals.max() <= 0.01
    assert rep["worst_param"] == rep["closest_params"][rep["worst_index"]]
    assert np.linalg.norm(c(rep["params"]) - pts, axis=1).max() > 0.01


def test_fit_tolerance_takes_the_tolerance_keyword_of_every_query():
    # one name for an absolute tolerance across the package (and `--tolerance` on the command
    # line); `tol` is not a keyword of lekalo's own functions
    x = np.linspace(0, 1, 60)
    pts = np.column_stack([x, np.sin(3 * x)])
    c, rep = lekalo.fit_tolerance(pts, tolerance=1e-3)
    assert rep["max_deviation"] <= 1e-3
    with pytest.raises(TypeError):
        lekalo.fit_tolerance(pts, tol=1e-3)
    with pytest.raises(lekalo.InputError, match="^tolerance -1: "):
        lekalo.fit_tolerance(pts, tolerance=-1.0)


def test_fit_tolerance_of_noisy_data_as_the_readme_shows():
    # the package README's example: a tolerance of twice the noise gives few control points
    x = np.linspace(0, 1, 200)
    y = np.sin(6 * x) + 0.05 * np.random.default_rng(0).standard_normal(200)
    c, rep = lekalo.fit_tolerance(np.column_stack([x, y]), 0.1)
    assert c.control.shape[0] == 9
    assert abs(rep["max_deviation"] - 0.0987) < 1e-4


def test_fit_robust_rejects_an_outlier():
    x = np.linspace(0, 1, 60)
    y = 2 * x
    y[30] = 50.0
    t = np.r_[[0.0] * 4, [1 / 3, 2 / 3], [1.0] * 4]
    c, rep = lekalo.fit_robust(x, y, t, 3, loss="tukey")
    assert rep["robust_weights"][30] == 0.0
    assert abs(c(0.5)[0] - 1.0) < 1e-6
    assert rep["iterations"] >= 1 and rep["scale"] >= 0
    # the plain least squares is pulled by the outlier
    assert abs(lekalo.make_lsq_spline(x, y, t)(0.5)[0] - 1.0) > 0.1
    h, _ = lekalo.fit_robust(x, y, t, 3, loss="huber")
    assert abs(h(0.5)[0] - 1.0) < abs(lekalo.make_lsq_spline(x, y, t)(0.5)[0] - 1.0)


def test_fit_surface_grid_and_scattered():
    i, j = np.meshgrid(np.arange(20.0), np.arange(15.0), indexing="ij")
    grid = np.stack([i, j, np.sin(0.3 * i) * np.cos(0.2 * j)], axis=-1)
    s = lekalo.fit_surface_grid(grid, (8, 6), (3, 3))
    assert s.control.shape == (8, 6, 3)
    # scattered values z(u, v) on given knots: SciPy's LSQBivariateSpline, same knots
    u, v = RNG.random(400), RNG.random(400)
    z = np.sin(3 * u) * np.cos(2 * v)
    ti = np.array([0.25, 0.5, 0.75])
    tk = np.r_[[0.0] * 4, ti, [1.0] * 4]
    surf, res, rss = lekalo.fit_surface_scattered(np.column_stack([u, v, z]), tk, tk, (3, 3))
    ref = si.LSQBivariateSpline(u, v, z, ti, ti, bbox=[0, 1, 0, 1], kx=3, ky=3)
    uu, vv = RNG.random(50), RNG.random(50)
    assert np.abs(surf(uu, vv)[:, 0] - ref.ev(uu, vv)).max() <= 1e-9
    assert np.isclose(rss, (res**2).sum(), rtol=1e-10)


def test_fit_least_squares_on_a_domain_wider_than_the_data():
    # t is the full knot vector: its end knots are the domain, here beyond the data on [0, 1]
    rng = np.random.default_rng(31)
    x = np.sort(rng.random(120))
    y = np.sin(6 * x) + 0.05 * rng.standard_normal(120)
    t = np.r_[[-0.5] * 4, [0.2, 0.45, 0.7], [1.6] * 4]
    c, rep = lekalo.fit_least_squares(y, x, t, 3)
    assert c.domain == (-0.5, 1.6)
    ref = si.make_lsq_spline(x, y, t, 3)
    outside = np.array([-0.5, -0.2, 1.3, 1.6])
    assert np.abs(c(outside)[:, 0] - ref(outside)).max() <= RTOL * np.abs(ref(outside)).max()
    assert np.abs(c(x)[:, 0] - ref(x)).max() <= RTOL * np.abs(y).max()
    # a cubic is reproduced everywhere on the domain, also outside the data
    def cubic(s):
        return 1 - 2 * s + 3 * s**3

    exact, rep = lekalo.fit_least_squares(cubic(x), x, t, 3)
    assert rep["max_residual"] <= 1e-12
    np.testing.assert_allclose(exact(outside)[:, 0], cubic(outside), rtol=0, atol=1e-11)


def test_fit_surface_scattered_bbox_and_degree_per_direction():
    # SciPy's LSQBivariateSpline(tx, ty, bbox, kx, ky) is the fit on the knot vectors
    # [bbox ends] * (k + 1) around the interior knots: tu, tv carry both
    rng = np.random.default_rng(37)
    u, v = rng.random(400), rng.random(400)
    z = np.sin(3 * u) * np.cos(2 * v)
    tx, ty = np.array([0.3, 0.6]), np.array([0.5])
    bbox = [-0.5, 1.5, -1.0, 2.0]
    tu = np.r_[[bbox[0]] * 4, tx, [bbox[1]] * 4]
    tv = np.r_[[bbox[2]] * 3, ty, [bbox[3]] * 3]
    surf, res, rss = lekalo.fit_surface_scattered(np.column_stack([u, v, z]), tu, tv, (3, 2))
    assert surf.degrees == (3, 2)
    assert surf.domain == ((-0.5, 1.5), (-1.0, 2.0))
    ref = si.LSQBivariateSpline(u, v, z, tx, ty, bbox=bbox, kx=3, ky=2)
    inside = rng.random((2, 50))
    assert np.abs(surf(inside[0], inside[1])[:, 0] - ref.ev(inside[0], inside[1])).max() <= 1e-9
    # outside the data, up to the bbox's corners: the same spline (the corner coefficients, far
    # from the data, carry the two factorisations' rounding: 1e-10 here, under 1e-9 for 20
    # other random data sets)
    ou, ov = np.array([-0.5, -0.3, 1.2, 1.5]), np.array([-1.0, 1.8, -0.4, 2.0])
    assert np.abs(surf(ou, ov)[:, 0] - ref.ev(ou, ov)).max() <= 1e-9


def test_fit_surface_grid_at_given_parameters_and_knots():
    i, j = np.meshgrid(np.arange(20.0), np.arange(15.0), indexing="ij")
    grid = np.stack([i, j, np.sin(0.3 * i) * np.cos(0.2 * j)], axis=-1)
    s = lekalo.fit_surface_grid(grid, (8, 6), (3, 3))
    # its own knots, given, give the same surface (the parameters are computed the same way)
    same = lekalo.fit_surface_grid(grid, degree=(3, 3), tu=s.knots_u, tv=s.knots_v)
    np.testing.assert_array_equal(same.control, s.control)
    # given parameters: z = u^2 - u v on a grid at u, v, degree 2 on a coarser net holds it exactly
    u, v = np.linspace(0.0, 2.0, 11), np.linspace(-1.0, 1.0, 9)
    U, V = np.meshgrid(u, v, indexing="ij")
    g = np.stack([U, V, U**2 - U * V], axis=-1)
    tu = np.r_[[0.0] * 3, 0.5, 1.2, [2.0] * 3]
    f = lekalo.fit_surface_grid(g, (4, 5), (2, 2), u=u, v=v, tu=tu)
    assert f.control.shape == (5, 5, 3)
    np.testing.assert_array_equal(f.knots_u, tu)
    pt = f(np.array([0.7]), np.array([0.3]))
    np.testing.assert_allclose(pt[0], [0.7, 0.3, 0.49 - 0.21], atol=1e-13)
    with pytest.raises(lekalo.InputError, match="^n_ctrl: give the net's size"):
        lekalo.fit_surface_grid(g, degree=(2, 2), u=u, v=v, tu=tu)
    with pytest.raises(lekalo.InputError, match="u parameters"):
        lekalo.fit_surface_grid(g, (4, 5), (2, 2), u=u[:-1], v=v)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda x, y: lekalo.make_smoothing_spline(x, y, lam=-1.0), "λ"),
        (lambda x, y: lekalo.make_splrep(x, y, s=-1.0), "s"),
        (lambda x, y: lekalo.make_lsq_spline(x, y, [0, 0, 1, 1], k=5), "degree"),
        (lambda x, y: lekalo.fit_tolerance(np.column_stack([x, y]), 0.0), "tolerance"),
        (lambda x, y: lekalo.fit_robust(x, y, [0, 0, 0, 0, 1, 1, 1, 1], loss="cauchy"), "loss"),
        (lambda x, y: lekalo.fit_tolerance(np.column_stack([x, y]), 1e-3, deviation="x"), "deviation"),
        (lambda x, y: lekalo.make_lsq_spline(x, y[:-1].copy(), [0, 0, 0, 0, 1, 1, 1, 1]), "x and y differ in length: x has 40 values, y has 39 rows"),
        (lambda x, y: lekalo.make_smoothing_spline(x[:-1].copy(), y), "x and y differ in length: x has 39 values, y has 40 rows"),
        (lambda x, y: lekalo.make_splrep(x, y[:-1].copy(), s=0.1), "give one x per row of y"),
        (lambda x, y: lekalo.make_lsq_spline(x.astype(np.complex128), y, [0, 0, 0, 0, 1, 1, 1, 1]), "not a real number type"),
    ],
)
def test_bad_input_is_a_named_error(call, match):
    x, y = noisy(40)
    with pytest.raises(lekalo.Error, match=match):
        call(x, y)


def test_a_repeated_x_in_a_smoothing_spline_is_one_point_at_the_weighted_mean():
    # Σ w_k (y_k − f(x))² over the points at one x is (Σ w_k)(ȳ − f(x))² + const: the same
    # minimiser as one point at the weighted mean ȳ with the summed weight
    # (docs/theory/fitting.md#penalised); SciPy refuses a repeated x, and so does lekalo.scipy
    # data of their own (the module's generator feeds the other tests)
    x = np.linspace(0.0, 1.0, 40)
    y = np.sin(6 * x) + 0.05 * np.cos(37 * x)
    w = 1.0 + 0.5 * np.sin(11 * x) ** 2
    xr = np.insert(x, [10, 25], x[[10, 25]])
    yr = np.insert(y, [10, 25], [y[10] + 0.3, y[25] - 0.2])
    wr = np.insert(w, [10, 25], [2.0, 0.5])
    ym, wm = y.copy(), w.copy()
    for i, (dy, dw) in zip((10, 25), ((0.3, 2.0), (-0.2, 0.5))):
        wm[i] = w[i] + dw
        ym[i] = (w[i] * y[i] + dw * (y[i] + dy)) / wm[i]
    xx = np.linspace(0, 1, 201)
    for lam in (1e-4, 1e-2, 0.0):
        c, rep = lekalo.fit_smoothing(xr, yr, w=wr, lam=lam)
        ref = lekalo.make_smoothing_spline(x, ym, w=wm, lam=lam)
        assert np.abs(c(xx) - ref(xx)).max() <= RTOL * np.abs(y).max(), lam
        assert len(rep["residuals"]) == len(xr)
    c, rep = lekalo.fit_smoothing(xr, yr, w=wr)  # λ by GCV over all 42 points
    assert rep["lam"] > 0
    with pytest.raises(ValueError, match="ascending"):
        lekalo.scipy.make_smoothing_spline(xr, yr)
    with pytest.raises(ValueError):
        si.make_smoothing_spline(xr, yr)
    # a decreasing x is still refused, and named x
    with pytest.raises(lekalo.InputError, match=r"^x must be in increasing order"):
        lekalo.make_smoothing_spline(x[::-1].copy(), y)


def test_nan_and_schoenberg_whitney_are_errors():
    x, y = noisy(40)
    y[3] = np.nan
    with pytest.raises(lekalo.Error, match="finite|NaN"):
        lekalo.make_smoothing_spline(x, y)
    x, y = noisy(40)
    # a knot span without data
    x = x * 0.4
    x[-1] = 1.0
    with pytest.raises(lekalo.Error):
        lekalo.make_lsq_spline(x, y, [0, 0, 0, 0, 0.5, 0.6, 0.7, 1, 1, 1, 1])


def test_scipy_coordinate_arrays_are_refused_with_the_call_that_reads_them():
    # SciPy's parametric fits take [x, y] (shape (dim, n)); lekalo takes points as rows
    x = np.arange(6.0)
    y = x**2
    calls = [
        lambda: lekalo.make_splprep([x, y], s=0.1),
        lambda: lekalo.fit_tolerance([x, y], 0.1),
        lambda: lekalo.interpolate([x, y]),
    ]
    for call in calls:
        with pytest.raises(lekalo.InputError, match=r"shape \(2, 6\).*np\.column_stack"):
            call()
    curve, u = lekalo.make_splprep(np.column_stack([x, y]), s=0.1)
    assert curve.dim == 2 and len(u) == 6
