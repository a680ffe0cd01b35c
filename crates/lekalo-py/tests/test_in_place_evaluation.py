"""lekalo.scipy's objects that evaluate SciPy's arrays in place (``tensor_values``,
``tensor_grid_values``, ``ppoly_values``): values equal to SciPy's, changes made to the arrays
in place seen, NaN and points beyond the box as SciPy treats them."""

import numpy as np
import pytest
from scipy import interpolate as si

from lekalo import _lekalo
from lekalo import scipy as ls


def _nd():
    rng = np.random.default_rng(7)
    t = (np.r_[[0.0] * 3, np.sort(rng.uniform(0, 1, 5)), [1.0] * 3],) * 3
    c = rng.standard_normal((7, 7, 7))
    return t, c


def test_ndbspline_sees_coefficients_changed_in_place_and_treats_nan_as_scipy():
    t, c = _nd()
    ours, theirs = ls.NdBSpline(t, c.copy(), 3), si.NdBSpline(t, c.copy(), 3)
    xi = np.random.default_rng(1).uniform(-0.2, 1.2, (50, 3))
    xi[3, 1] = np.nan
    np.testing.assert_allclose(ours(xi), theirs(xi), rtol=1e-13, atol=1e-13)
    ours.c[2, 3, 4] += 1.0
    theirs.c[2, 3, 4] += 1.0
    np.testing.assert_allclose(ours(xi), theirs(xi), rtol=1e-13, atol=1e-13)
    got, want = ours(xi, extrapolate=False), theirs(xi, extrapolate=False)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    np.testing.assert_allclose(got[~np.isnan(got)], want[~np.isnan(want)], rtol=1e-13, atol=1e-13)
    assert np.isnan(ours(xi)[3])


def test_tensor_values_refuses_bad_arrays_by_name():
    t, c = _nd()
    with pytest.raises(ValueError, match="beyond"):
        _lekalo.tensor_values(t, c, 3, np.zeros((1, 3)), None, "wrap")
    with pytest.raises(ValueError, match="c: axis 1"):
        _lekalo.tensor_values(t, np.ascontiguousarray(c[:, :6]), 3, np.zeros((1, 3)))
    with pytest.raises(ValueError, match="t"):
        _lekalo.tensor_values((t[0][::-1], t[1], t[2]), c, 3, np.zeros((1, 3)))


def test_bivariate_values_clamp_to_the_box_and_see_changes():
    x, y = np.linspace(0, 1, 12), np.linspace(0, 2, 9)
    z = np.sin(3 * x)[:, None] * np.cos(y)[None, :]
    ours, theirs = ls.RectBivariateSpline(x, y, z), si.RectBivariateSpline(x, y, z)
    px, py = np.array([-0.5, 0.3, 1.5]), np.array([0.5, 2.5, -1.0])
    np.testing.assert_allclose(ours.ev(px, py), theirs.ev(px, py), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(ours(px, np.sort(py)), theirs(px, np.sort(py)), rtol=1e-13, atol=1e-13)
    tck = [np.array(a) for a in theirs.tck] + [3, 3]
    tck[2][5] += 2.0
    np.testing.assert_allclose(ls.bisplev(px, np.sort(py), tck), si.bisplev(px, np.sort(py), tck), rtol=1e-13, atol=1e-13)


def test_ppoly_in_place_with_repeated_breakpoints_and_changes():
    rng = np.random.default_rng(3)
    # an empty interior piece (SciPy also evaluates an empty last piece beyond the end, which
    # lekalo skips for the last non-empty one)
    x = np.array([0.0, 1.0, 1.0, 2.0, 3.0])
    c = rng.standard_normal((4, 4, 2))
    ours, theirs = ls.PPoly(c.copy(), x), si.PPoly(c.copy(), x)
    xp = np.r_[rng.uniform(-1, 4, 40), x]
    np.testing.assert_allclose(ours(xp), theirs(xp), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(ours(xp, 2), theirs(xp, 2), rtol=1e-13, atol=1e-13)
    ours.c[1, 2, 0] += 5.0
    theirs.c[1, 2, 0] += 5.0
    np.testing.assert_allclose(ours(xp), theirs(xp), rtol=1e-13, atol=1e-13)
    assert ours(0.5).shape == theirs(0.5).shape


@pytest.mark.parametrize("descending", [False, True])
def test_bpoly_in_place_has_scipy_bits_and_sees_changes(descending):
    rng = np.random.default_rng(5)
    x = np.sort(rng.uniform(0, 10, 12))
    c = rng.uniform(-2, 2, (4, 11))
    if descending:
        x, c = x[::-1].copy(), c[::-1, ::-1].copy()
    ours, theirs = ls.BPoly(c.copy(), x), si.BPoly(c.copy(), x)
    xp = rng.uniform(-2, 12, 300)
    # the cubic's Bernstein sum written out as SciPy writes it: the same bits
    assert np.array_equal(ours(xp), theirs(xp))
    for nu in (1, 2, 3, 4):
        np.testing.assert_allclose(ours(xp, nu), theirs(xp, nu), rtol=1e-11, atol=1e-11)
    # one number, changes in place, no extrapolation, periodic: as SciPy
    ours.c[2, 5] += 3.0
    theirs.c[2, 5] += 3.0
    assert np.array_equal(ours(xp), theirs(xp))
    at = float(xp[7])
    assert ours(at).shape == () and ours(at) == theirs(at)
    got, want = ours(xp, extrapolate=False), theirs(xp, extrapolate=False)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    np.testing.assert_array_equal(got[~np.isnan(got)], want[~np.isnan(want)])
    np.testing.assert_allclose(ours(xp, extrapolate="periodic"), theirs(xp, extrapolate="periodic"), rtol=1e-13)
    assert np.isnan(ours(np.array([np.nan, 1.0])))[0]


def test_bpoly_of_high_degree_and_vector_values():
    rng = np.random.default_rng(9)
    x = np.r_[0.0, np.sort(rng.uniform(0, 3, 6)), 3.0]
    c = rng.standard_normal((7, 7, 2, 3))
    ours, theirs = ls.BPoly(c, x), si.BPoly(c, x)
    xp = rng.uniform(-0.5, 3.5, (20, 5))
    for nu in (0, 1, 3):
        got = ours(xp, nu)
        assert got.shape == theirs(xp, nu).shape
        np.testing.assert_allclose(got, theirs(xp, nu), rtol=1e-11, atol=1e-11)


def test_cubics_hold_scipy_s_coefficients_for_every_batch():
    rng = np.random.default_rng(11)
    x = np.linspace(0, 10, 200) + rng.uniform(-0.01, 0.01, 200)
    y = np.sin(x)
    xp = rng.uniform(-0.5, 10.5, 5000)
    for make in (
        lambda m: m.CubicSpline(x, y),
        lambda m: m.PchipInterpolator(x, y),
        lambda m: m.Akima1DInterpolator(x, y, extrapolate=True),
        lambda m: m.CubicHermiteSpline(x, y, np.cos(x)),
    ):
        ours, theirs = make(ls), make(si)
        # made with SciPy's coefficients (the Hermite family's bit for bit, CubicSpline's to
        # rounding), no B-spline form
        assert ours._c is not None and ours._spline_ is None
        if isinstance(ours, ls.CubicSpline):
            # the cubic coefficient, a difference of slopes over h², to 1e-11 of its row
            for m in range(4):
                np.testing.assert_allclose(ours.c[m], theirs.c[m], rtol=0, atol=1e-11 * np.abs(theirs.c[m]).max())
        else:
            np.testing.assert_array_equal(ours.c.view(np.uint64), theirs.c.view(np.uint64))
        small = ours(xp[:10])
        np.testing.assert_allclose(ours(xp), theirs(xp), rtol=1e-13, atol=1e-13)
        np.testing.assert_array_equal(ours(xp)[:10], small)
        np.testing.assert_allclose(ours(xp, 1), theirs(xp, 1), rtol=1e-12, atol=1e-12)
        assert abs(float(ours(0.3)) - float(theirs(0.3))) < 1e-13


def test_ndbspline_scalar_calls_are_the_batch_bits_and_see_changes():
    """A point given as a tuple (the held arrays of TensorValueAt) has the bits of the same point
    in a batch, inside, beyond the box, at NaN, for one degree in every variable and for mixed
    degrees; changes made to c in place are seen; the object pickles."""
    import pickle

    rng = np.random.default_rng(3)
    for k in (1, 2, 3, 5, (3, 2, 1)):
        ks = (k,) * 3 if np.ndim(k) == 0 else k
        t = tuple(np.r_[[0.0] * (kd + 1), np.sort(rng.uniform(0, 1, 4)), [1.0] * (kd + 1)] for kd in ks)
        c = rng.standard_normal(tuple(len(td) - kd - 1 for td, kd in zip(t, ks)))
        for extrapolate in (True, False):
            ours = ls.NdBSpline(t, c.copy(), k, extrapolate=extrapolate)
            xi = rng.uniform(-0.3, 1.3, (40, 3))
            xi[5, 2] = np.nan
            batch = ours(xi)
            for x, want in zip(xi, batch):
                got = ours(tuple(float(v) for v in x))
                assert isinstance(got, np.ndarray) and got.shape == ()
                assert np.array_equal(got, want, equal_nan=True), (k, extrapolate, x)
            theirs = si.NdBSpline(t, c, k, extrapolate=extrapolate)
            np.testing.assert_allclose(ours((0.3, 0.6, 0.2)), theirs((0.3, 0.6, 0.2)), rtol=1e-13, atol=1e-13)
            ours.c[1, 1, 1] += 2.0
            assert ours((0.3, 0.6, 0.2)) == ours(np.array([[0.3, 0.6, 0.2]]))[0]
            again = pickle.loads(pickle.dumps(ours))
            assert again((0.3, 0.6, 0.2)) == ours((0.3, 0.6, 0.2))
    # a tuple the scalar path does not take goes the array way, with SciPy's errors
    with pytest.raises(ValueError):
        ours((0.3, 0.6))


@pytest.mark.parametrize("count", [2**14 - 1, 2**14, 2**14 + 1])
def test_ndbspline_large_batches_in_cell_order_have_the_bits_of_small_ones(count):
    """Batches at the cell-order size on a net above 2^15 numbers, the points random, sorted
    backwards and with NaN and out-of-box points: the bits of the same points in small batches
    (which keep the order of the points), and SciPy's values."""
    rng = np.random.default_rng(count)
    t = (np.r_[[0.0] * 3, np.linspace(0, 1, 34), [1.0] * 3],) * 3
    c = rng.standard_normal((36, 36, 36))
    ours = ls.NdBSpline(t, c, 3)
    xi = rng.uniform(-0.2, 1.2, (count, 3))
    xi[::97, 1] = np.nan
    backwards = xi[np.lexsort(xi.T[::-1])[::-1]]
    for points in (xi, backwards):
        for extrapolate in (True, False):
            whole = ours(points, extrapolate=extrapolate)
            parts = np.concatenate([ours(p, extrapolate=extrapolate) for p in np.array_split(points, 8)])
            assert np.array_equal(whole, parts, equal_nan=True)
    want = si.NdBSpline(t, c, 3)(xi)
    np.testing.assert_allclose(ours(xi), want, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("cls", [ls.PPoly, ls.BPoly])
@pytest.mark.parametrize("degree", range(6))
@pytest.mark.parametrize("ends_repeated", [False, True])
def test_large_scalar_batches_have_the_bits_of_single_points(cls, degree, ends_repeated):
    # a batch of many points a piece takes the branch-free path (one split a bucket of the
    # piece table, NaN selected afterwards); each point alone takes the general one: the same
    # bits, at NaN, infinities, beyond the ends and at the breakpoints, continued or NaN, with
    # and without the empty end pieces of PPoly.from_spline
    rng = np.random.default_rng(degree)
    x = np.sort(rng.uniform(-2.0, 3.0, 40))
    if ends_repeated:
        x = np.r_[[x[0]] * 3, x, [x[-1]] * 3]
    c = rng.standard_normal((degree + 1, x.size - 1))
    f, g = cls(c, x), getattr(si, cls.__name__)(c, x)
    xp = np.r_[rng.uniform(-3.0, 4.0, 20000), x, np.nan, np.inf, -np.inf, x[0] - 1e-9, x[-1] + 1e-9]
    for extrapolate in (True, False):
        batch = f(xp, extrapolate=extrapolate)
        single = np.array([f(float(v), extrapolate=extrapolate) for v in xp])
        nan = np.isnan(single)
        assert np.array_equal(np.isnan(batch), nan)
        bits = np.where(nan, 0.0, batch).view(np.int64) == np.where(nan, 0.0, single).view(np.int64)
        assert bits.all(), xp[~bits][:5]
        # SciPy at the finite points (at ±∞ lekalo gives NaN for every degree, SciPy a value
        # for degree 0), inside the ends when the end pieces are empty (beyond them SciPy
        # continues the empty piece, lekalo the last non-empty one)
        finite = np.isfinite(xp)
        if ends_repeated:
            finite &= (x[0] <= xp) & (xp < x[-1])
        want = g(xp[finite], extrapolate=extrapolate)
        assert np.array_equal(np.isnan(batch[finite]), np.isnan(want))
        ok = ~np.isnan(want)
        np.testing.assert_allclose(batch[finite][ok], want[ok], rtol=1e-12, atol=1e-12 * np.abs(want[ok]).max())


def test_large_scalar_batches_refuse_wrong_dtypes_and_take_empty_input():
    x = np.linspace(0.0, 1.0, 11)
    c = np.ones((4, 10))
    f = ls.PPoly(c, x)
    assert f(np.array([], dtype=np.float64)).shape == (0,)
    np.testing.assert_array_equal(f(np.full(100, 0.5, dtype=np.float32)), f(np.full(100, 0.5)))
    with pytest.raises((TypeError, ValueError)):
        f(np.array(["a"] * 100))


@pytest.mark.parametrize("degrees", [(1, 1), (2, 2), (3, 3), (4, 4), (5, 5), (3, 1), (1, 4)])
@pytest.mark.parametrize("count", [1, 3, 4, 5, 9, 2047, 2048, 2049])
def test_bivariate_and_ndbspline_batches_of_every_size_are_scipy_s_and_their_points_bits(degrees, count):
    """The batches of ``RectBivariateSpline.ev`` and ``NdBSpline`` at sizes around the kernels'
    blocks of four points and the parallel threshold, degrees 1 to 5 and mixed, with NaN,
    infinite and out-of-box coordinates at every position of a block: SciPy's values, and each
    point's value the bits of that point alone."""
    kx, ky = degrees
    rng = np.random.default_rng(count * 10 + kx)
    x, y = np.linspace(0.0, 1.0, 12), np.linspace(0.0, 2.0, 11)
    z = np.sin(3 * x)[:, None] * np.cos(2 * y)[None, :] + x[:, None] * y[None, :]
    ours, theirs = ls.RectBivariateSpline(x, y, z, kx=kx, ky=ky), si.RectBivariateSpline(x, y, z, kx=kx, ky=ky)
    px, py = rng.uniform(-0.3, 1.3, count), rng.uniform(-0.5, 2.5, count)
    for i, bad in enumerate([np.nan, np.inf, -np.inf, 1.6]):
        if 5 * i < count:
            (px if i % 2 else py)[5 * i] = bad
    got, want = ours.ev(px, py), theirs.ev(px, py)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    ok = ~np.isnan(want)
    np.testing.assert_allclose(got[ok], want[ok], rtol=1e-12, atol=1e-12)
    alone = np.array([ours.ev(px[i : i + 1], py[i : i + 1])[0] for i in range(count)])
    assert np.array_equal(got, alone, equal_nan=True)
    # the same points through NdBSpline (two variables), extrapolated and not
    t, c = ours.get_knots(), ours.get_coeffs().reshape(len(ours.get_knots()[0]) - kx - 1, -1)
    nd_ours, nd_theirs = ls.NdBSpline(t, c, degrees), si.NdBSpline(t, c, degrees)
    pts = np.stack([px, py], axis=-1)
    for extrapolate in (True, False):
        got, want = nd_ours(pts, extrapolate=extrapolate), nd_theirs(pts, extrapolate=extrapolate)
        assert np.array_equal(np.isnan(got), np.isnan(want))
        ok = ~np.isnan(want)
        scale = max([1.0, *np.abs(want[ok])])
        np.testing.assert_allclose(got[ok], want[ok], rtol=1e-12, atol=1e-12 * scale)
        alone = np.array([nd_ours(pts[i : i + 1], extrapolate=extrapolate)[0] for i in range(count)])
        assert np.array_equal(got, alone, equal_nan=True)


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("count", [3, 4, 5, 2049])
def test_trivariate_batches_of_every_size_are_scipy_s_and_their_points_bits(k, count):
    """``NdBSpline`` in three variables of one degree (the blocked fixed-size kernel) at sizes
    around its blocks and the parallel threshold, with NaN, infinite and out-of-box points."""
    rng = np.random.default_rng(100 * k + count)
    t = (np.r_[[0.0] * k, np.linspace(0, 1, 6), [1.0] * k],) * 3
    c = rng.standard_normal((5 + k,) * 3)
    ours, theirs = ls.NdBSpline(t, c, k), si.NdBSpline(t, c, k)
    xi = rng.uniform(-0.2, 1.2, (count, 3))
    for i, bad in enumerate([np.nan, np.inf, -np.inf, 3.0]):
        if 5 * i < count:
            xi[5 * i, i % 3] = bad
    for extrapolate in (True, False):
        got, want = ours(xi, extrapolate=extrapolate), theirs(xi, extrapolate=extrapolate)
        assert np.array_equal(np.isnan(got), np.isnan(want))
        ok = ~np.isnan(want)
        scale = max([1.0, *np.abs(want[ok])])
        np.testing.assert_allclose(got[ok], want[ok], rtol=1e-11, atol=1e-11 * scale)
        alone = np.array([ours(xi[i : i + 1], extrapolate=extrapolate)[0] for i in range(count)])
        assert np.array_equal(got, alone, equal_nan=True)
