"""lekalo.scipy against scipy.interpolate on the same inputs: values, derivatives, integrals,
extrapolation, knots and coefficients, shapes and axes, errors."""

import numpy as np
import pytest

si = pytest.importorskip("scipy.interpolate")
import lekalo.scipy as ls  # noqa: E402


def close(a, b, rtol=1e-12):
    """Equal to ``rtol`` relative to the larger magnitude of the two arrays (and same shape)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, (a.shape, b.shape)
    assert a.dtype == b.dtype, (a.dtype, b.dtype)
    scale = max(np.abs(np.nan_to_num(a)).max(initial=0.0), np.abs(np.nan_to_num(b)).max(initial=0.0), 1e-300)
    np.testing.assert_allclose(a, b, rtol=rtol, atol=rtol * scale, equal_nan=True)


def data(n=13, tail=(), seed=0):
    rng = np.random.default_rng(seed)
    x = np.sort(rng.uniform(0.0, 4.0, n))
    y = rng.standard_normal((n,) + tail)
    return x, y


XX = np.linspace(-1.0, 5.0, 41)


@pytest.mark.parametrize("k", [0, 1, 2, 3, 4, 5])
@pytest.mark.parametrize("tail", [(), (2,), (3, 2)])
def test_make_interp_spline_not_a_knot(k, tail):
    x, y = data(tail=tail)
    a, b = si.make_interp_spline(x, y, k=k), ls.make_interp_spline(x, y, k=k)
    assert isinstance(b, ls.BSpline) and b.k == a.k and b.axis == a.axis
    close(b.t, a.t)
    close(b.c, a.c, 1e-11)
    for nu in range(k + 2):
        close(b(XX, nu), a(XX, nu), 1e-11)
        close(b(XX, nu, extrapolate=False), a(XX, nu, extrapolate=False), 1e-11)
    close(b(1.7), a(1.7))
    if k > 0:
        # (SciPy extrapolates a piecewise constant's antiderivative from its empty last
        # interval; lekalo.scipy follows SciPy for values, not for that integral yet)
        close(b.integrate(-0.5, 4.5), a.integrate(-0.5, 4.5), 1e-11)
    close(b.integrate(3.0, 0.2, extrapolate=False), a.integrate(3.0, 0.2, extrapolate=False))
    for nu in (1, 2):
        sa, sb = a.antiderivative(nu), b.antiderivative(nu)
        close(sb.t, sa.t)
        close(sb.c, sa.c, 1e-11)
        # (k = 0: beyond the last node SciPy evaluates the empty last interval of these
        # knots, a degenerate value that lekalo.scipy does not copy)
        xs = XX if k > 0 else XX[XX < x[-1]]
        close(sb(xs), sa(xs), 1e-11)
    if k >= 1:
        da, db = a.derivative(), b.derivative()
        close(db.t, da.t)
        close(db.c, da.c, 1e-11)


@pytest.mark.parametrize("axis", [0, 1, -1])
def test_axis_handling(axis):
    rng = np.random.default_rng(3)
    x = np.linspace(0.0, 1.0, 9)
    y = rng.standard_normal((4, 9, 3))
    y = np.moveaxis(y, 1, axis)
    a = si.make_interp_spline(x, y, axis=axis)
    b = ls.make_interp_spline(x, y, axis=axis)
    assert b.axis == a.axis
    close(b.c, a.c)
    xx = np.linspace(-0.2, 1.2, 12).reshape(3, 4)
    close(b(xx), a(xx))
    close(b(xx, 2), a(xx, 2))
    close(b.integrate(0.1, 0.8), a.integrate(0.1, 0.8))
    close(b.antiderivative()(xx), a.antiderivative()(xx))


@pytest.mark.parametrize(
    "bc",
    [
        "clamped",
        "natural",
        ([(1, 2.0)], [(1, -1.0)]),
        ([(2, 0.0)], [(2, 0.0)]),
    ],
)
@pytest.mark.parametrize("tail", [(), (2,)])
def test_boundary_conditions(bc, tail):
    x, y = data(n=10, tail=tail, seed=5)
    if not isinstance(bc, str) and tail:
        bc = tuple([(o, np.full(tail, v)) for o, v in side] for side in bc)
    a = si.make_interp_spline(x, y, k=3, bc_type=bc)
    b = ls.make_interp_spline(x, y, k=3, bc_type=bc)
    close(b.t, a.t)
    close(b.c, a.c, 1e-11)
    close(b(XX), a(XX), 1e-11)
    close(b(XX, 1), a(XX, 1), 1e-11)


def test_explicit_knots_and_lsq():
    x, y = data(n=40, tail=(2,), seed=7)
    t = np.r_[(x[0],) * 4, np.linspace(x[0], x[-1], 9)[1:-1], (x[-1],) * 4]
    w = np.linspace(0.5, 2.0, x.size)
    a, b = si.make_lsq_spline(x, y, t, k=3, w=w), ls.make_lsq_spline(x, y, t, k=3, w=w)
    close(b.c, a.c, 1e-11)
    close(b(XX), a(XX), 1e-11)
    t2 = si.make_interp_spline(x[:12], y[:12]).t
    a = si.make_interp_spline(x[:12], y[:12], t=t2)
    b = ls.make_interp_spline(x[:12], y[:12], t=t2)
    close(b.c, a.c, 1e-11)


def test_bspline_direct_construction_and_periodic_evaluation():
    t = np.array([0.0, 0.0, 0.0, 1.0, 2.5, 3.0, 4.0, 4.0, 4.0])
    c = np.array([1.0, -2.0, 0.5, 3.0, 1.0, -1.0])
    for ext in (True, False, "periodic"):
        a, b = si.BSpline(t, c, 2, extrapolate=ext), ls.BSpline(t, c, 2, extrapolate=ext)
        assert b.extrapolate == a.extrapolate
        close(b(XX * 3), a(XX * 3))
        close(b(XX * 3, 1), a(XX * 3, 1))
        for lo, hi in [(-3.0, 13.5), (0.5, 2.0), (6.0, -1.0)]:
            close(b.integrate(lo, hi), a.integrate(lo, hi), 1e-11)
    # unclamped knots; coefficients longer than needed are ignored, as in SciPy
    t = np.arange(10.0)
    c = np.r_[np.cos(np.arange(6.0)), 7.0, 7.0]
    a, b = si.BSpline(t, c, 3), ls.BSpline(t, c, 3)
    close(b(XX * 2), a(XX * 2))
    close(b.integrate(1.0, 8.5), a.integrate(1.0, 8.5))
    close(b.antiderivative()(XX * 2), a.antiderivative()(XX * 2))
    close(b.tck[1], a.tck[1])


def test_basis_element_and_design_matrix():
    a = si.BSpline.basis_element([0.0, 1.0, 2.0, 4.0])
    b = ls.BSpline.basis_element([0.0, 1.0, 2.0, 4.0])
    close(b.t, a.t)
    close(b(XX), a(XX))
    x = np.linspace(0.0, 4.0, 17)
    t = np.r_[0, 0, 0, 0, 1, 2.5, 4, 4, 4, 4.0]
    da, db = si.BSpline.design_matrix(x, t, 3), ls.BSpline.design_matrix(x, t, 3)
    close(db.toarray(), da.toarray())
    xe = np.linspace(-1.0, 5.0, 13)
    da = si.BSpline.design_matrix(xe, t, 3, extrapolate=True)
    db = ls.BSpline.design_matrix(xe, t, 3, extrapolate=True)
    close(db.toarray(), da.toarray())
    with pytest.raises(ValueError):
        ls.BSpline.design_matrix(xe, t, 3)


def test_complex_and_empty_values():
    x = np.linspace(0.0, 2.0, 8)
    y = np.exp(1j * x)
    a, b = si.make_interp_spline(x, y), ls.make_interp_spline(x, y)
    close(b.c, a.c)
    close(b(XX), a(XX))
    # (SciPy 1.17's integrate fails on complex coefficients; lekalo's works)
    close(b.integrate(0.0, 1.5), si.make_interp_spline(x, y.real).integrate(0.0, 1.5) + 1j * si.make_interp_spline(x, y.imag).integrate(0.0, 1.5))
    y0 = np.zeros((8, 0))
    a, b = si.make_interp_spline(x, y0), ls.make_interp_spline(x, y0)
    assert b.c.shape == a.c.shape
    assert b(XX).shape == a(XX).shape


def test_fitpack_functions():
    x, y = data(n=15, seed=11)
    for k in (1, 2, 3, 5):
        ta = si.splrep(x, y, k=k)
        tb = ls.splrep(x, y, k=k)
        close(tb[0], ta[0])
        close(tb[1], ta[1], 1e-11)
        assert tb[2] == ta[2]
        for der in range(k + 1):
            for ext in (0, 1, 3):
                close(ls.splev(XX, tb, der, ext), si.splev(XX, ta, der, ext), 1e-11)
        close(ls.splev(2.0, tb), si.splev(2.0, ta))
        with pytest.raises(ValueError) as ea:
            si.splev(XX, ta, ext=2)
        with pytest.raises(ValueError) as eb:
            ls.splev(XX, tb, ext=2)
        # SciPy's message first, then the x outside and what the other ext values do
        assert str(eb.value).startswith(str(ea.value)), (str(eb.value), str(ea.value))
        assert "x = -1 is outside the base interval" in str(eb.value)
        assert "ext=0" in str(eb.value)
        assert ls.splint(0.5, 3.0, tb) == pytest.approx(si.splint(0.5, 3.0, ta), rel=1e-12)
        assert ls.splint(-2.0, 9.0, tb) == pytest.approx(si.splint(-2.0, 9.0, ta), rel=1e-12)
        for n in (1, 2):
            if n <= k:
                da, db = si.splder(ta, n), ls.splder(tb, n)
                close(db[0], da[0])
                close(db[1], da[1], 1e-11)
                assert db[2] == da[2]
            aa, ab = si.splantider(ta, n), ls.splantider(tb, n)
            close(ab[0], aa[0])
            close(ab[1], aa[1], 1e-11)
            assert ab[2] == aa[2]
    # interior knots given: least squares
    t = np.linspace(x[0], x[-1], 6)[1:-1]
    close(ls.splrep(x, y, t=t)[1], si.splrep(x, y, t=t)[1], 1e-11)
    # BSpline objects pass through
    spl = si.make_interp_spline(x, y)
    lspl = ls.make_interp_spline(x, y)
    close(ls.splev(XX, lspl), si.splev(XX, spl), 1e-11)
    assert float(ls.splint(0.0, 3.0, lspl)) == pytest.approx(float(si.splint(0.0, 3.0, spl)), rel=1e-12)


@pytest.mark.parametrize(
    "args",
    [
        (np.arange(5.0), np.ones(2), 3),  # too few coefficients
        (np.arange(3.0), np.ones(5), 3),  # too few knots
        (np.array([0.0, 2.0, 1.0, 3.0, 4.0]), np.ones(3), 1),  # not sorted
        (np.array([0.0, 1.0, np.nan, 3.0, 4.0]), np.ones(3), 1),
        (np.arange(5.0), np.ones(3), -1),
    ],
)
def test_constructor_errors_match(args):
    with pytest.raises(ValueError) as ea:
        si.BSpline(*args)
    with pytest.raises(ValueError) as eb:
        ls.BSpline(*args)
    assert str(eb.value) == str(ea.value)


def test_interp_errors_match():
    x = np.array([0.0, 1.0, 1.0, 2.0])
    for bad in [
        dict(x=x, y=np.ones(4)),
        dict(x=np.arange(4.0), y=np.ones(5)),
        dict(x=np.arange(6.0), y=np.ones(6), k=0, bc_type="clamped"),
        dict(x=np.arange(6.0), y=np.ones(6), bc_type="clampd"),
    ]:
        with pytest.raises(ValueError) as ea:
            si.make_interp_spline(**bad)
        with pytest.raises(ValueError) as eb:
            ls.make_interp_spline(**bad)
        assert type(eb.value) is type(ea.value)


def test_univariate_spline_ext_raise_names_the_x_and_the_choices():
    x, y = data(n=15, seed=11)
    with pytest.raises(ValueError) as ea:
        si.UnivariateSpline(x, y, ext="raise")(9.0)
    with pytest.raises(ValueError) as eb:
        ls.UnivariateSpline(x, y, ext="raise")(9.0)
    assert str(eb.value).startswith(str(ea.value)), (str(eb.value), str(ea.value))
    assert "x = 9 is outside" in str(eb.value)


def spaced(n=9, tail=(2,), seed=1):
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 4.0, n) + rng.uniform(-0.1, 0.1, n)
    return x, rng.standard_normal((n,) + tail), rng.standard_normal((n,) + tail)


@pytest.mark.parametrize("bc", ["not-a-knot", "natural", "clamped", "d1", "d2"])
@pytest.mark.parametrize("tail", [(), (2,)])
def test_cubic_spline(bc, tail):
    x, y, _ = spaced(tail=tail)
    if bc == "d1":
        bc = ((1, np.ones(tail)), (1, np.zeros(tail)))
    elif bc == "d2":
        bc = ((2, np.full(tail, 0.5)), (2, np.zeros(tail)))
    a, b = si.CubicSpline(x, y, bc_type=bc), ls.CubicSpline(x, y, bc_type=bc)
    close(b.x, a.x)
    close(b.c, a.c)
    for nu in range(5):
        close(b(XX, nu), a(XX, nu))
    close(b(XX, extrapolate=False), a(XX, extrapolate=False))
    close(b.integrate(-1.0, 5.0), a.integrate(-1.0, 5.0))
    close(b.integrate(0.5, 3.0), a.integrate(0.5, 3.0))
    close(b.integrate(-1.0, 3.0, extrapolate=False), a.integrate(-1.0, 3.0, extrapolate=False))
    for nu in (1, 2):
        close(b.derivative(nu).c, a.derivative(nu).c)
        close(b.antiderivative(nu).c, a.antiderivative(nu).c)
        close(b.antiderivative(nu)(XX), a.antiderivative(nu)(XX))


def test_cubic_spline_short_data_and_axis():
    x, y, _ = spaced(tail=(2,))
    for n in (2, 3):
        a, b = si.CubicSpline(x[:n], y[:n]), ls.CubicSpline(x[:n], y[:n])
        close(b.c, a.c)
        close(b(XX), a(XX))
    yt = np.ascontiguousarray(y.T)
    a, b = si.CubicSpline(x, yt, axis=1), ls.CubicSpline(x, yt, axis=1)
    assert b.axis == a.axis
    close(b.c, a.c)
    close(b(XX[:5]), a(XX[:5]))


def test_cubic_hermite_spline():
    x, y, d = spaced()
    a, b = si.CubicHermiteSpline(x, y, d), ls.CubicHermiteSpline(x, y, d)
    close(b.c, a.c)
    for nu in range(4):
        close(b(XX, nu), a(XX, nu))
    close(b.integrate(-0.5, 4.5), a.integrate(-0.5, 4.5))


@pytest.mark.parametrize("tail", [(), (3,)])
def test_pchip(tail):
    rng = np.random.default_rng(4)
    x = np.sort(rng.uniform(0.0, 4.0, 12))
    y = np.cumsum(rng.uniform(-0.2, 1.0, (12,) + tail), axis=0)
    y[4:6] = y[4]  # a flat stretch
    a, b = si.PchipInterpolator(x, y), ls.PchipInterpolator(x, y)
    close(b.c, a.c)
    for nu in range(4):
        close(b(XX, nu), a(XX, nu))
    close(b.integrate(0.2, 3.9), a.integrate(0.2, 3.9))
    a, b = si.PchipInterpolator(x[:2], y[:2]), ls.PchipInterpolator(x[:2], y[:2])
    close(b.c, a.c)


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("tail", [(), (2,)])
def test_periodic_interpolation(k, tail):
    rng = np.random.default_rng(8)
    x = np.sort(np.r_[0.0, rng.uniform(0.0, 6.0, 9), 6.0])
    y = rng.standard_normal((11,) + tail)
    y[-1] = y[0]
    a = si.make_interp_spline(x, y, k=k, bc_type="periodic")
    b = ls.make_interp_spline(x, y, k=k, bc_type="periodic")
    assert b.extrapolate == a.extrapolate
    close(b.t, a.t)
    close(b.c, a.c, 1e-11)
    for nu in range(k + 1):
        close(b(XX * 3, nu), a(XX * 3, nu), 1e-11)
    close(b.integrate(-4.0, 17.0), a.integrate(-4.0, 17.0), 1e-11)
    if k == 3:
        a, b = si.CubicSpline(x, y, bc_type="periodic"), ls.CubicSpline(x, y, bc_type="periodic")
        assert b.extrapolate == a.extrapolate
        close(b.c, a.c, 1e-11)
        close(b(XX * 3), a(XX * 3), 1e-11)


@pytest.mark.parametrize("method", ["akima", "makima"])
@pytest.mark.parametrize("tail", [(), (3,)])
def test_akima(method, tail):
    rng = np.random.default_rng(6)
    x = np.sort(rng.uniform(0.0, 4.0, 12))
    y = rng.standard_normal((12,) + tail)
    y[3:6] = 1.0  # a flat stretch
    a = si.Akima1DInterpolator(x, y, method=method)
    b = ls.Akima1DInterpolator(x, y, method=method)
    assert b.extrapolate == a.extrapolate
    close(b.c, a.c)
    for nu in range(4):
        close(b(XX, nu), a(XX, nu))
        close(b(XX, nu, extrapolate=True), a(XX, nu, extrapolate=True))
    close(b.integrate(0.5, 3.5), a.integrate(0.5, 3.5))
    a = si.Akima1DInterpolator(x[:2], y[:2], method=method)
    b = ls.Akima1DInterpolator(x[:2], y[:2], method=method)
    close(b.c, a.c)


def test_smoothing():
    rng = np.random.default_rng(0)
    x = np.linspace(0.0, 6.0, 60)
    y = np.sin(x) + 0.1 * rng.standard_normal(60)
    w = rng.uniform(0.5, 2.0, 60)
    for k in (1, 3, 5):
        for s in (0.1, 0.5, 3.0):
            ta, tb = si.splrep(x, y, w=w, s=s, k=k), ls.splrep(x, y, w=w, s=s, k=k)
            close(tb[0], ta[0])  # FITPACK's knots
            assert tb[1].shape == ta[1].shape
            # both meet FITPACK's tolerance on the smoothing condition
            fp = np.sum((w * (ls.splev(x, tb) - y)) ** 2)
            assert abs(fp - s) <= 0.001 * s + 1e-12 or len(tb[0]) == 2 * k + 2, (k, s, fp)
    for lam in (1e-3, 0.1):
        a = si.make_smoothing_spline(x, y, lam=lam)
        b = ls.make_smoothing_spline(x, y, lam=lam)
        close(b.t, a.t)
        close(b.c, a.c, 1e-10)
    a, b = si.make_smoothing_spline(x, y), ls.make_smoothing_spline(x, y)
    close(b(XX), a(XX), 1e-5)  # lam by generalised cross-validation: two minimisers


def test_insert_knot_and_zero_dimensional_integrals():
    x, y = data(n=10, tail=(2,), seed=2)
    a, b = si.make_interp_spline(x, y), ls.make_interp_spline(x, y)
    for at, m in [(1.3, 1), (2.0, 2), (x[4], 1)]:
        ia, ib = a.insert_knot(at, m), b.insert_knot(at, m)
        close(ib.t, ia.t)
        close(ib.c, ia.c)
        close(ib(XX), ia(XX), 1e-11)
    with pytest.raises(ValueError):
        b.insert_knot(x[-1] + 1.0)
    e = ls.BSpline.basis_element([0.0, 1.0, 2.0])
    for ext in (True, False):
        r = e.integrate(0.0, 1.0, extrapolate=ext)
        assert isinstance(r, np.ndarray) and r.ndim == 0


def test_periodic_splrep_and_smoothing_of_3d_values():
    rng = np.random.default_rng(1)
    x = np.linspace(0.0, 2 * np.pi, 40)
    y = np.cos(x) + 0.05 * rng.standard_normal(40)
    y[-1] = y[0]
    for k in (1, 3, 5):
        a, b = si.splrep(x, y, per=1, k=k), ls.splrep(x, y, per=1, k=k)
        close(b[0], a[0])
        close(b[1], a[1], 1e-11)
        close(ls.splev(XX, b), si.splev(XX, a), 1e-11)
        a, b = si.splrep(x, y, per=1, k=k, s=0.02), ls.splrep(x, y, per=1, k=k, s=0.02)
        close(b[0], a[0])  # FITPACK's periodic knots
    y3 = rng.standard_normal((40, 2, 2))
    a, b = si.make_smoothing_spline(x, y3, lam=0.1), ls.make_smoothing_spline(x, y3, lam=0.1)
    close(b.c, a.c, 1e-11)


def test_make_splrep_and_make_splprep():
    rng = np.random.default_rng(3)
    x = np.linspace(0.0, 6.0, 50)
    y = np.sin(x) + 0.1 * rng.standard_normal(50)
    w = rng.uniform(0.5, 2.0, 50)
    for k in (1, 3, 5):
        b = ls.make_splrep(x, y, w=w, k=k, s=0.5)
        assert type(b) is ls.BSpline and b.c.shape == (len(b.t) - k - 1,)
        # SciPy's own make_splrep knots (a fit after every knot), unequal weights too
        close(b.t, si.make_splrep(x, y, w=w, k=k, s=0.5).t)
        fp = np.sum((w * (b(x) - y)) ** 2)
        assert abs(fp - 0.5) <= 0.001 * 0.5, (k, fp)
    close(ls.make_splrep(x, y).c, si.make_splrep(x, y).c)  # s = 0 interpolates
    with pytest.raises(ValueError, match="interpolation only"):
        ls.make_splrep(x, y, w=w)
    with pytest.raises(ValueError, match="boundary conditions"):
        ls.make_splrep(x, y, s=1.0, bc_type="natural")
    # on given knots (residuals: 0.864 for the cubic, 0.719 on these knots): SciPy's smoothing
    tk = np.array([0, 0, 0, 0, 3, 6, 6, 6, 6], dtype=float)
    close(ls.make_splrep(x, y, s=0.8, t=tk).c, si.make_splrep(x, y, s=0.8, t=tk).c)
    # periodic: FITPACK's knots and residual (the last point closes the period and is not
    # counted), with SciPy's weights squared into lekalo's
    yp = np.cos(x) + 0.05 * rng.standard_normal(50)
    yp[-1] = yp[0]
    (ta, fpa, _, _), tb = si.splrep(x, yp, w=w, s=0.05, per=1, full_output=1), ls.splrep(x, yp, w=w, s=0.05, per=1)
    close(tb[0], ta[0])
    close(np.sum((w * (ls.splev(x, tb) - yp))[:-1] ** 2), fpa, 1e-8)
    close(ls.make_splrep(x, yp, w=w, s=0.05, bc_type="periodic").t, ta[0])
    pts = [np.cos(x), np.sin(2 * x) + 0.01 * rng.standard_normal(50)]
    (a, ua), (b, ub) = si.make_splprep(pts, s=0.01), ls.make_splprep(pts, s=0.01)
    close(ub, ua)
    close(b.t, a.t)  # SciPy's own make_splprep knots (a fit after every knot)
    assert b.c.shape == (len(b.t) - 4, 2) and b(ub).shape == np.shape(pts)


def test_insert_pchip_interpolate_and_from_power_basis():
    x, y = data(n=12, seed=4)
    tck = si.splrep(x, y)
    ta, tb = si.insert(1.7, tck, m=2), ls.insert(1.7, tck, m=2)
    close(tb[0], ta[0])
    close(tb[1], ta[1])
    ib = ls.insert(1.7, ls.make_interp_spline(x, y))
    assert type(ib) is ls.BSpline
    close(ib(XX), si.insert(1.7, si.make_interp_spline(x, y))(XX), 1e-11)
    assert ls.pchip is ls.PchipInterpolator
    for der in (0, 1, [0, 2]):
        close(ls.pchip_interpolate(x, y, XX, der=der), si.pchip_interpolate(x, y, XX, der=der), 1e-11)
    for bc in ("not-a-knot", "natural", "clamped"):
        b = ls.BSpline.from_power_basis(ls.CubicSpline(x, y, bc_type=bc), bc_type=bc)
        close(b.t, si.make_interp_spline(x, y, bc_type=bc).t)
        close(b.c, si.make_interp_spline(x, y, bc_type=bc).c, 1e-10)
    # a not-a-knot spline on the knots of a natural one: lekalo inserts the two knots it lacks
    b = ls.BSpline.from_power_basis(ls.CubicSpline(x, y), bc_type="natural")
    close(b(XX), ls.CubicSpline(x, y)(XX), 1e-11)
    with pytest.raises(NotImplementedError):
        ls.BSpline.from_power_basis(ls.PchipInterpolator(x, y))


def test_batched_gcv_smoothing_chooses_a_weight_per_column():
    rng = np.random.default_rng(5)
    x = np.linspace(0.0, 10.0, 30)
    y = np.sin(x)[:, None] * [1.0, 0.1] + 0.2 * rng.standard_normal((30, 2))
    b = ls.make_smoothing_spline(x, y)
    for j in range(2):
        close(b.c[:, j], ls.make_smoothing_spline(x, y[:, j]).c)
    with pytest.raises(ValueError, match="too many axes"):
        ls.splrep(x, y)


def test_spalde_and_splprep():
    x, y = data(n=15, seed=6)
    tck = si.splrep(x, y)
    for at in (x[0], 1.3, x[-1]):
        close(ls.spalde(at, tck), si.spalde(at, tck), 1e-11)
    assert len(ls.spalde([1.0, 2.0], tck)) == 2
    with pytest.raises(TypeError):
        ls.spalde(1.0, ls.BSpline(*tck))
    a = np.linspace(0.0, 2 * np.pi, 30)
    pts = [np.cos(a), 0.5 * np.sin(a)]
    for per in (0, 1):
        for s in (0.0, 1e-3, None):  # None: FITPACK's default m - sqrt(2m)
            (ta, ua), (tb, ub) = si.splprep(pts, s=s, per=per), ls.splprep(pts, s=s, per=per)
            close(tb[0], ta[0])
            close(ub, ua)
            assert len(tb[1]) == 2 and tb[1][0].shape == ta[1][0].shape
            # FITPACK's tolerance on the smoothing condition, relative to the data (amplitude 1)
            np.testing.assert_allclose(np.array(ls.splev(ub, tb)), np.array(si.splev(ua, ta)), rtol=0, atol=1e-5)
    (tb, ub), fp, ier, msg = ls.splprep(pts, s=1e-3, full_output=1)
    assert ier == 0 and abs(fp - 1e-3) <= 1e-6
    with pytest.raises(ValueError, match="Invalid inputs"):
        ls.splprep([[1.0, 3.0, 2.0, 4.0]], u=[0, 0.3, 0.2, 1])


def test_univariate_spline_family():
    rng = np.random.default_rng(7)
    x = np.linspace(0.0, 5.0, 40)
    y = np.sin(x) + 0.05 * rng.standard_normal(40)
    for cls_args in [("UnivariateSpline", dict(s=0.1)), ("InterpolatedUnivariateSpline", {}),
                     ("LSQUnivariateSpline", dict(t=[1.0, 2.5, 4.0]))]:
        name, kw = cls_args
        args = (x, y, kw.pop("t")) if "t" in kw else (x, y)
        a, b = getattr(si, name)(*args, **kw), getattr(ls, name)(*args, **kw)
        close(b.get_knots(), a.get_knots())
        close(b.get_coeffs(), a.get_coeffs(), 1e-6)
        close(b(XX), a(XX), 1e-6)
        close(b(XX, ext="const"), a(XX, ext="const"), 1e-6)
        close(b.integral(0.5, 4.0), a.integral(0.5, 4.0), 1e-6)
        close(b.derivatives(2.0), a.derivatives(2.0), 1e-5)
        close(b.derivative()(XX[5:30]), a.derivative()(XX[5:30]), 1e-5)
        close(b.get_residual(), a.get_residual(), 1e-3)
    with pytest.raises(ValueError, match="Schoenberg-Whitney"):
        ls.LSQUnivariateSpline(x, y, [1.0], bbox=(3.0, 0.0))
    with pytest.raises(ValueError, match="x must be increasing"):
        ls.UnivariateSpline(x[::-1], y)


def test_lsq_univariate_spline_without_data_raises_as_scipy():
    """No data: SciPy reads ``x[0]`` for the end that ``bbox`` leaves open (an ``IndexError``);
    with both ends given, FITPACK's check refuses the data (a ``ValueError``)."""
    empty = np.array([])
    for t, bbox in [([], (None, None)), ([0.5], (None, None)), ([0.5], (0.0, None)), ([0.5], (0.0, 1.0))]:
        index_error = []
        for m in (si, ls):
            with pytest.raises((IndexError, ValueError)) as e:
                m.LSQUnivariateSpline(empty, empty, t, bbox=bbox)
            index_error.append(issubclass(e.type, IndexError))
        assert index_error[0] == index_error[1], (t, bbox, index_error)
        assert index_error[0] == (bbox[1] is None), (t, bbox)
    with pytest.raises(IndexError):
        ls.LSQUnivariateSpline([], [], [])
    # too few points for the degree: a ValueError on both sides
    for m in (si, ls):
        with pytest.raises(ValueError):
            m.LSQUnivariateSpline([0.0, 1.0], [0.0, 1.0], [0.5])


def test_univariate_spline_set_smoothing_factor():
    """SciPy's tutorial: ``spl.set_smoothing_factor(0.5)`` after the default ``s``. FITPACK's
    ``iopt=1`` starts over when ``s`` reaches the polynomial's residual or there is no interior
    knot, smooths on the current knots when their least-squares residual is already at most
    ``s``, and otherwise adds knots to them as FITPACK's rounds would have gone on (the last
    three cases, the third past SciPy's knot limit ``nest = 25``)."""
    rng = np.random.default_rng(1)
    x = np.linspace(-3.0, 3.0, 50)
    y = np.exp(-x**2) + 0.1 * rng.standard_normal(50)
    xs = np.linspace(-3.0, 3.0, 101)
    for s1, s2, kw in [(None, 0.5, {}), (0.5, 5.0, {}), (0.5, 1.0, {}), (0.3, 0.31, {}), (0.5, 0.0, {}),
                       (0.5, 1.0, dict(k=5)), (1.0, 2.0, dict(bbox=[-4.0, 4.0])), (1.0, 8.0, dict(w=np.full(50, 2.0))),
                       (1.0, 0.3, {}), (5.0, 0.2, {}), (1.0, 0.05, {})]:
        a, b = si.UnivariateSpline(x, y, s=s1, **kw), ls.UnivariateSpline(x, y, s=s1, **kw)
        a.set_smoothing_factor(s2)
        b.set_smoothing_factor(s2)
        close(b.get_knots(), a.get_knots())
        # FITPACK stops with |fp - s| < 0.001 s, lekalo with fp in [0.999 s, s] (docs/scipy.md)
        assert b.get_residual() <= s2 * (1 + 1e-12) + 1e-25
        close(b.get_residual(), a.get_residual(), 2e-3)
        close(b(xs), a(xs), 1e-3)
    with pytest.raises(NotImplementedError, match="interpolating"):
        ls.UnivariateSpline(x, y, s=0).set_smoothing_factor(0.5)
    lsq = ls.LSQUnivariateSpline(x, y, [0.0])
    before = lsq(xs)
    with pytest.warns(UserWarning, match="smoothing factor unchanged"):
        lsq.set_smoothing_factor(0.3)
    close(lsq(xs), before)


def test_boolean_weights_mask_points_out_as_in_scipy():
    """SciPy's ``UnivariateSpline`` docstring masks NaN data with ``w=~np.isnan(y)``: a boolean
    array of weights is read as 0.0 and 1.0 by ``splrep``, ``UnivariateSpline`` and
    ``make_smoothing_spline``, and weights of the wrong length are SciPy's errors."""
    x = np.linspace(0.0, 10.0, 30)
    y = np.sin(x)
    y[4] = np.nan
    w = np.isnan(y)
    y[w] = 0.0
    a, b = si.UnivariateSpline(x, y, w=~w), ls.UnivariateSpline(x, y, w=~w)
    close(b.get_knots(), a.get_knots())
    close(b(XX), a(XX), 1e-6)
    close(ls.splev(XX, ls.splrep(x, y, w=~w, s=1.0)), si.splev(XX, si.splrep(x, y, w=~w, s=1.0)), 1e-6)
    ok = np.ones(30, dtype=bool)
    close(ls.make_smoothing_spline(x, y, w=ok, lam=0.1)(XX), si.make_smoothing_spline(x, y, w=ok, lam=0.1)(XX), 1e-8)
    with pytest.raises(ValueError, match="Invalid vector of weights"):
        ls.make_smoothing_spline(x, y, w=~w)
    with pytest.raises(TypeError, match=r"len\(w\)=29 is not equal to m=30"):
        ls.splrep(x, y, w=np.ones(29), s=1.0)


def test_ndbspline():
    rng = np.random.default_rng(8)
    t = (np.r_[[0.0] * 4, 1.0, 2.5, [4.0] * 4], np.r_[[0.0] * 3, 2.0, [3.0] * 3])
    k = (3, 2)
    for tail, dtype in [((), float), ((2,), float), ((), complex)]:
        c = rng.standard_normal((6, 4) + tail)
        if dtype is complex:
            c = c + 1j * rng.standard_normal((6, 4) + tail)
        a, b = si.NdBSpline(t, c, k), ls.NdBSpline(t, c, k)
        xi = np.stack([rng.uniform(0, 4, (5, 3)), rng.uniform(0, 3, (5, 3))], axis=-1)
        close(b(xi), a(xi), 1e-11)
        close(b(xi, nu=(1, 2)), a(xi, nu=(1, 2)), 1e-10)
    out = ls.NdBSpline(t, c, k, extrapolate=False)([[5.0, 1.0], [1.0, 1.0], [np.nan, 1.0]])
    assert np.isnan(out[0]) and np.isfinite(out[1]) and np.isnan(out[2])
    # extrapolation (the default) continues the end polynomials, as SciPy's
    far = [[5.0, 1.0], [-0.5, 3.5]]
    close(ls.NdBSpline(t, c, k)(far), si.NdBSpline(t, c, k)(far), 1e-10)
    close(ls.NdBSpline(t, c, k).derivative((1, 1))(xi), si.NdBSpline(t, c, k).derivative((1, 1))(xi), 1e-10)
    with pytest.raises(ValueError, match="inconsistent"):
        ls.NdBSpline(t, c[:5], k)


def test_derivatives_and_antiderivatives_of_empty_values():
    x = np.linspace(0.0, 3.0, 7)
    y = np.zeros((7, 0))
    for name in ("PchipInterpolator", "CubicSpline"):
        a, b = getattr(si, name)(x, y), getattr(ls, name)(x, y)
        for f in (lambda p: p.derivative(), lambda p: p.derivative(2), lambda p: p.antiderivative(2)):
            assert f(b)(XX).shape == f(a)(XX).shape == (XX.size, 0)
    s = ls.make_interp_spline(x, y)
    assert s.derivative().c.shape[1:] == s.antiderivative().c.shape[1:] == (0,)
    close(s.antiderivative().t, si.make_interp_spline(x, y).antiderivative().t)


def pp_data(order=4, pieces=6, tail=(), seed=3, complex_=False):
    rng = np.random.default_rng(seed)
    x = np.sort(rng.uniform(0.0, 4.0, pieces + 1))
    c = rng.uniform(-1.0, 1.0, (order, pieces) + tail)
    if complex_:
        c = c + 1j * rng.uniform(-1.0, 1.0, c.shape)
    return c, x


@pytest.mark.parametrize("cls", ["PPoly", "BPoly"])
@pytest.mark.parametrize("tail,axis", [((), 0), ((3,), 0), ((2, 3), 1), ((3,), 1)])
@pytest.mark.parametrize("complex_", [False, True])
def test_ppoly_bpoly_evaluation_calculus_and_axes(cls, tail, axis, complex_):
    c, x = pp_data(tail=tail, complex_=complex_)
    c = np.moveaxis(np.moveaxis(c, 1, axis + 1), 0, axis) if axis else c
    a, b = getattr(si, cls)(c, x, axis=axis), getattr(ls, cls)(c, x, axis=axis)
    assert type(b) is getattr(ls, cls) and b.axis == a.axis and b.extrapolate == a.extrapolate
    close(b.c, a.c, 0)
    close(b.x, a.x, 0)
    xx = XX.reshape(1, -1)
    with pytest.raises(ValueError):
        b(xx, -1)
    for nu in range(6 if cls == "PPoly" else 4):  # SciPy's BPoly fails beyond the degree
        close(b(xx, nu), a(xx, nu), 1e-9)
        close(b(xx, nu, extrapolate=False), a(xx, nu, extrapolate=False), 1e-9)
    for nu in (1, 2, 5):
        close(b.derivative(nu).c, a.derivative(nu).c, 1e-9)
        assert b.derivative(nu).axis == axis
    for nu in (1, 2):
        close(b.antiderivative(nu).c, a.antiderivative(nu).c, 1e-9)
        close(b.antiderivative(nu)(XX), a.antiderivative(nu)(XX), 1e-9)
    for lo, hi in [(0.3, 2.9), (2.9, 0.3), (-1.0, 5.0)]:
        close(b.integrate(lo, hi), a.integrate(lo, hi), 1e-9)
        close(b.integrate(lo, hi, extrapolate=False), a.integrate(lo, hi, extrapolate=False), 1e-9)


@pytest.mark.parametrize("cls", ["PPoly", "BPoly"])
def test_ppoly_bpoly_periodic_extend_and_errors(cls):
    c, x = pp_data(order=3, pieces=5)
    a = getattr(si, cls)(c, x, extrapolate="periodic")
    b = getattr(ls, cls)(c, x, extrapolate="periodic")
    close(b(XX), a(XX), 1e-12)
    close(b(XX, 1), a(XX, 1), 1e-10)
    for lo, hi in [(-3.0, 7.5), (5.0, -2.0)]:
        close(b.integrate(lo, hi), a.integrate(lo, hi), 1e-10)
    c2 = pp_data(order=5, pieces=2, seed=4)[0]
    x2 = x[-1] + np.array([0.5, 1.5])
    a, b = getattr(si, cls)(c, x), getattr(ls, cls)(c, x)
    a.extend(c2, x2)
    b.extend(c2, x2)
    close(b.x, a.x, 0)
    close(b.c, a.c, 1e-12)
    close(b(XX + 1.0), a(XX + 1.0), 1e-10)
    unsorted = x.copy()
    unsorted[[1, 2]] = unsorted[[2, 1]]
    for bad in [dict(c=[1.0, 2.0], x=[0, 1]), dict(c=c, x=unsorted), dict(c=c, x=x[:-1]), dict(c=c, x=x, axis=1)]:
        with pytest.raises(ValueError):
            getattr(si, cls)(**bad)
        with pytest.raises(ValueError):
            getattr(ls, cls)(**bad)


def test_ppoly_conversions_and_from_spline():
    c, x = pp_data(order=5, pieces=4, tail=(2,))
    a, b = si.PPoly(c, x), ls.PPoly(c, x)
    ab, bb = si.BPoly.from_power_basis(a), ls.BPoly.from_power_basis(b)
    assert type(bb) is ls.BPoly
    close(bb.c, ab.c, 1e-10)
    # the power coefficients are derivatives at the breakpoints (SciPy: binomial sums)
    close(ls.PPoly.from_bernstein_basis(bb).c, si.PPoly.from_bernstein_basis(ab).c, 1e-8)
    with pytest.raises(TypeError):
        ls.PPoly.from_bernstein_basis(b)
    with pytest.raises(TypeError):
        ls.BPoly.from_power_basis(bb)
    xs, y = data()
    tck = si.splrep(xs, y[:, None][:, 0], s=0, k=4)
    pa, pb = si.PPoly.from_spline(tck), ls.PPoly.from_spline(tck)
    close(pb.x, pa.x, 0)
    close(pb(XX), pa(XX), 1e-11)
    close(pb.c, pa.c, 1e-9)
    spl = ls.make_interp_spline(xs, y)
    assert isinstance(ls.CubicSpline(xs, y), ls.PPoly)
    close(ls.PPoly.from_spline(spl)(XX), spl(XX), 1e-12)
    # roots: lekalo's PiecewisePolynomial.solve, SciPy's conventions
    close(pb.roots(), pa.roots(), 1e-12)


@pytest.mark.parametrize("tail", [(), (2,), (2, 3)])
@pytest.mark.parametrize("orders", [None, 3, [1, 2, 3, 4, 5]])
def test_bpoly_from_derivatives(tail, orders):
    # lekalo's piecewise_hermite_bernstein: 1 to 4 derivatives at each of 6 breakpoints
    rng = np.random.default_rng(5)
    xi = np.sort(rng.uniform(0.0, 4.0, 6))
    yi = [rng.standard_normal((1 + i % 4,) + tail) for i in range(6)]
    if orders is not None:
        # (SciPy refuses some orders that lekalo's rule serves by drawing from the other end)
        yi = [rng.standard_normal((3,) + tail) for _ in range(6)]
    a = si.BPoly.from_derivatives(xi, yi, orders=orders)
    b = ls.BPoly.from_derivatives(xi, yi, orders=orders)
    assert type(b) is ls.BPoly
    close(b.c, a.c, 1e-11)
    # on the breakpoints' span: outside, the degree-7 Bernstein extrapolation of a short end
    # piece is ill-conditioned in both (relative differences 1e-9 at 0.2 out, 1e-6 at x = 5)
    xs = np.linspace(xi[0], xi[-1], 41)
    for nu in range(3):
        close(b(xs, nu), a(xs, nu), 1e-10)


def test_bpoly_from_derivatives_single_piece_and_errors():
    ya, yb = [1.0, 2.0, 3.0], [4.0, 0.5 + 1j]
    close(ls.BPoly._construct_from_derivatives(0.5, 2.0, ya, yb), si.BPoly._construct_from_derivatives(0.5, 2.0, ya, yb), 1e-14)
    for xi, yi, kw in [([0, 1], [[0]], {}), ([0, 0, 1], [[0], [0], [0]], {}), ([0, 1, 2], [[0, 1], [0], [1, 2]], {"orders": 0}), ([0, 1], [[0, 1], [1, 2]], {"orders": 4})]:
        with pytest.raises(ValueError):
            si.BPoly.from_derivatives(xi, yi, **kw)
        with pytest.raises(ValueError):
            ls.BPoly.from_derivatives(xi, yi, **kw)


@pytest.mark.parametrize("cls", ["PPoly", "BPoly"])
@pytest.mark.parametrize("tail", [(), (2,)])
def test_decreasing_breakpoints(cls, tail):
    # lekalo's PiecewisePolynomial.from_decreasing / to_decreasing (PPoly), the Bernstein
    # coefficients reversed (BPoly)
    c, x = pp_data(order=4, pieces=6, tail=tail)
    xd = x[::-1].copy()
    a, b = getattr(si, cls)(c, xd), getattr(ls, cls)(c, xd)
    for nu in range(3):
        close(b(XX, nu), a(XX, nu), 1e-11)
    close(b.derivative().c, a.derivative().c, 1e-11)
    close(b.derivative()(XX), a.derivative()(XX), 1e-11)
    close(b.antiderivative()(XX), a.antiderivative()(XX), 1e-11)
    close(b.antiderivative().c, a.antiderivative().c, 1e-11)
    for lo, hi in [(-1.0, 5.0), (3.5, 0.2), (1.0, 1.5)]:
        close(b.integrate(lo, hi), a.integrate(lo, hi), 1e-11)
        close(b.integrate(lo, hi, extrapolate=False), a.integrate(lo, hi, extrapolate=False), 1e-11)
    if cls == "PPoly" and tail == ():
        close(np.sort(b.roots()), np.sort(a.roots()), 1e-12)
    if cls == "BPoly":
        close(ls.PPoly.from_bernstein_basis(b)(XX), si.PPoly.from_bernstein_basis(a)(XX), 1e-11)


def test_ppoly_pp_form_integral_and_antiderivative():
    # lekalo's PiecewisePolynomial.antiderivative / integral_extrapolated on the given pieces
    c, x = pp_data(order=5, pieces=5, tail=(3,))
    a, b = si.PPoly(c, x), ls.PPoly(c, x)
    for nu in (1, 2, 3):
        close(b.antiderivative(nu).c, a.antiderivative(nu).c, 1e-13)
    for lo, hi in [(-2.0, 6.0), (3.0, 0.5), (0.1, 0.2)]:
        close(b.integrate(lo, hi), a.integrate(lo, hi), 1e-13)


@pytest.mark.parametrize("cls", ["PPoly", "BPoly"])
def test_ppoly_bpoly_see_coefficients_changed_in_place(cls):
    c, x = pp_data(tail=(2,))
    a, b = getattr(si, cls)(c.copy(), x.copy()), getattr(ls, cls)(c.copy(), x.copy())
    close(b(XX), a(XX), 1e-10)
    for p in (a, b):
        p.c[:, 2] *= 3.0
        p.x += 0.5
    close(b(XX), a(XX), 1e-10)
    close(b(XX, 1, extrapolate="periodic"), a(XX, 1, extrapolate="periodic"), 1e-9)
    d = ls.PPoly(c, x).derivative()
    d.c[-1] += 1.0
    close(d(XX), si.PPoly(c, x).derivative()(XX) + 1.0, 1e-12)


@pytest.mark.parametrize("cls", ["PPoly", "BPoly"])
def test_ppoly_bpoly_of_empty_values(cls):
    x = np.array([0.0, 1.0, 2.0, 3.0])
    a, b = getattr(si, cls)(np.zeros((4, 3, 0)), x), getattr(ls, cls)(np.zeros((4, 3, 0)), x)
    close(b(XX), a(XX))
    close(b.derivative().c, a.derivative().c)
    close(b.antiderivative().c, a.antiderivative().c)
    close(b.integrate(0.0, 2.0), a.integrate(0.0, 2.0))


def test_splprep_on_given_knots_is_fitpacks():
    # splprep(task=-1, t=...): least squares on the interior knots, ends at ub/ue (FITPACK's
    # parcur with iopt=-1)
    s = np.linspace(0, 1, 11)
    pts = [np.sin(2 * np.pi * s), np.cos(2 * np.pi * s) + s]
    t = np.r_[[0.0] * 4, [0.3, 0.5, 0.8], [1.0] * 4]
    (ta, ca, _), ua = si.splprep(pts, task=-1, t=t)
    (tb, cb, _), ub = ls.splprep(pts, task=-1, t=t)
    np.testing.assert_allclose(tb, ta, atol=1e-15)
    np.testing.assert_allclose(ub, ua, atol=1e-15)
    n = len(ta) - 4
    np.testing.assert_allclose(np.asarray(cb)[:, :n], np.asarray(ca)[:, :n], atol=1e-12)


@pytest.mark.parametrize("t", [None, [1.0, 2.5]])
def test_splrep_with_wider_end_knots_is_fitpacks(t):
    # splrep(xb=, xe=) puts the end knots there, for interpolation and for given knots
    x = np.linspace(0.0, 4.0, 9)
    y = np.exp(-x) * np.cos(2 * x)
    ta, ca, _ = si.splrep(x, y, xb=-1.0, xe=5.0, t=t)
    tb, cb, _ = ls.splrep(x, y, xb=-1.0, xe=5.0, t=t)
    np.testing.assert_allclose(tb, ta, atol=1e-15)
    np.testing.assert_allclose(cb, ca, atol=1e-10 * np.abs(ca).max())


@pytest.mark.parametrize(
    "kw",
    [dict(s=0), dict(s=0.5), dict(s=100), dict(t=[3, 6]), dict(task=-1, t=[3, 6]),
     dict(s=0.5, per=1), dict(s=0, per=1), dict(w=np.full(21, 2.0), s=0.5)],
)
def test_splrep_full_output_reports_fitpacks_fp_ier_and_message(kw):
    # interpolation (-1), the least-squares polynomial (-2), the smoothing condition and least
    # squares on given knots (0): FITPACK's residual, code and words
    x = np.linspace(0, 10, 21)
    y = np.cos(x)
    _, fpa, iera, msga = si.splrep(x, y, full_output=True, **kw)
    _, fpb, ierb, msgb = ls.splrep(x, y, full_output=True, **kw)
    assert (ierb, msgb) == (iera, msga)
    # the smoothing condition meets s within FITPACK's 0.001 s, not at FITPACK's bits
    assert fpb == pytest.approx(fpa, rel=1e-3 if kw.get("s") else 1e-12, abs=1e-15)


@pytest.mark.parametrize("a, b", [(0.0, 3.0), (-1.0, 30.0), (3.0, 0.0), (2.2, 7.7)])
def test_splint_full_output_gives_the_integrals_of_the_b_splines(a, b):
    x = np.linspace(0, 10, 21)
    tck = si.splrep(x, np.cos(x))
    n = len(tck[0]) - tck[2] - 1
    va, wa = si.splint(a, b, tck, full_output=True)
    vb, wb = ls.splint(a, b, tck, full_output=True)
    assert vb == pytest.approx(va, abs=1e-14)
    # FITPACK leaves the last k + 1 entries unset; lekalo's are zero
    np.testing.assert_allclose(wb[:n], wa[:n], rtol=0, atol=1e-15)
    assert wb.shape == (len(tck[0]),) and not wb[n:].any()


@pytest.mark.parametrize("lam", [1e-300, 1e-20])
def test_make_smoothing_spline_with_a_penalty_below_rounding_interpolates(lam):
    # SciPy solves such lam in the natural basis; lekalo gives the same limit, the interpolant
    x = np.linspace(0, 10, 11)
    y = np.sin(x)
    t = np.linspace(0, 10, 41)
    np.testing.assert_allclose(
        ls.make_smoothing_spline(x, y, lam=lam)(t), si.make_smoothing_spline(x, y, lam=lam)(t), rtol=0, atol=1e-13
    )


def test_make_smoothing_spline_gcv_on_data_without_noise_all_but_interpolates():
    # the GCV score falls towards interpolation; SciPy's choice and lekalo's lie on that flat
    # stretch, both within 1e-5 of the interpolant
    x = np.linspace(0, 10, 11)
    y = np.sin(x)
    t = np.linspace(0, 10, 41)
    interp = si.make_smoothing_spline(x, y, lam=1e-300)(t)
    np.testing.assert_allclose(ls.make_smoothing_spline(x, y)(t), interp, rtol=0, atol=1e-5)
    np.testing.assert_allclose(si.make_smoothing_spline(x, y)(t), interp, rtol=0, atol=1e-4)
