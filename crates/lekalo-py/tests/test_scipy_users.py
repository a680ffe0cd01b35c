"""SciPy users' code run through ``lekalo.scipy``: each test is a snippet written the way
tutorials, notebooks and question-and-answer threads call ``scipy.interpolate``, as a function
of the module ``si``. It runs once with ``scipy.interpolate`` and once with ``lekalo.scipy``
(only the import differs) and the two results are compared: types (tuple, list, ndarray, numpy
scalar), shapes, dtypes and values, the exception raised and the warnings given.

Tolerances: where both compute the same mathematics (interpolation, least squares on given
knots, evaluation of the same coefficients), values agree to rounding, 1e-12 relative with an
absolute floor of 1e-12 times the data's size (the conditioning of the small banded systems
here is far below 1e3). Where SciPy's FITPACK stops its smoothing iteration anywhere within
0.001*s of s and lekalo within 0.001*s below s (docs/scipy.md), the same knots give fits whose
values differ by what that difference in s moves them: 1e-3 relative to the data's size.
"""

import copy
import pickle
import warnings

import numpy as np
import pytest

import lekalo.scipy as ls

si_scipy = pytest.importorskip("scipy.interpolate")

RTOL = 1e-12  # same mathematics, rounding only


class Outcome:
    """What one run of a snippet gave: its value or exception, and its warnings."""

    def __init__(self, fn, module):
        self.value = None
        self.error = None
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                self.value = fn(module)
            except Exception as exc:  # the exception is part of the behaviour compared
                self.error = exc
        self.warnings = sorted({w.category.__name__ for w in caught})


def compare(ref, got, rtol, scale, path="result"):
    """Recursively compares SciPy's result ``ref`` with lekalo's ``got``: the same container
    types and lengths, the same array shapes and dtypes, values within ``rtol`` relative and
    ``rtol * scale`` absolute."""
    if isinstance(ref, (tuple, list)):
        assert type(got) is type(ref), f"{path}: {type(got).__name__} where SciPy gives {type(ref).__name__}"
        assert len(got) == len(ref), f"{path}: length {len(got)} where SciPy gives {len(ref)}"
        for i, (r, g) in enumerate(zip(ref, got)):
            compare(r, g, rtol, scale, f"{path}[{i}]")
    elif isinstance(ref, dict):
        assert isinstance(got, dict) and set(got) == set(ref), path
        for key in ref:
            compare(ref[key], got[key], rtol, scale, f"{path}[{key!r}]")
    elif isinstance(ref, np.ndarray):
        assert isinstance(got, np.ndarray), f"{path}: {type(got).__name__} where SciPy gives ndarray"
        assert got.shape == ref.shape, f"{path}: shape {got.shape} where SciPy gives {ref.shape}"
        assert got.dtype == ref.dtype, f"{path}: dtype {got.dtype} where SciPy gives {ref.dtype}"
        if ref.dtype.kind in "fc":
            np.testing.assert_allclose(got, ref, rtol=rtol, atol=rtol * scale, equal_nan=True, err_msg=path)
        else:
            np.testing.assert_array_equal(got, ref, err_msg=path)
    elif isinstance(ref, (bool, int, str, type(None))) and not isinstance(ref, np.generic):
        assert type(got) is type(ref), f"{path}: {type(got).__name__} where SciPy gives {type(ref).__name__}"
        assert got == ref, f"{path}: {got!r} where SciPy gives {ref!r}"
    elif isinstance(ref, (float, complex, np.generic)):
        assert type(got) is type(ref), f"{path}: {type(got).__name__} where SciPy gives {type(ref).__name__}"
        np.testing.assert_allclose(got, ref, rtol=rtol, atol=rtol * scale, equal_nan=True, err_msg=path)
    else:
        raise TypeError(f"{path}: the snippet returns {type(ref).__name__}; return arrays or numbers")


def same(fn, rtol=RTOL, scale=1.0, messages=False):
    """Runs the snippet ``fn(si)`` with SciPy and with lekalo.scipy and compares the outcomes.
    ``scale`` is the size of the data, for the absolute floor of the comparison."""
    ref = Outcome(fn, si_scipy)
    got = Outcome(fn, ls)
    if ref.error is not None:
        assert got.error is not None, f"SciPy raises {ref.error!r}; lekalo returns {got.value!r}"
        assert isinstance(got.error, type(ref.error)), f"lekalo raises {got.error!r} where SciPy raises {ref.error!r}"
    else:
        assert got.error is None, f"lekalo raises {got.error!r} where SciPy returns"
        compare(ref.value, got.value, rtol, scale)
    assert got.warnings == ref.warnings, f"lekalo warns {got.warnings} where SciPy warns {ref.warnings}"
    return ref, got


def noisy(n=40, seed=0):
    rng = np.random.default_rng(seed)
    x = np.linspace(0, 10, n)
    return x, np.sin(x) + 0.1 * rng.standard_normal(n)


XS = np.linspace(-0.5, 10.5, 57)  # plotting grid, past both ends


# ---------------------------------------------------------------- FITPACK's functions


def test_splrep_splev_tutorial():
    """splrep of a sampled sine, splev on a fine grid for plotting (the reference guide's example)."""

    def snippet(si):
        x = np.linspace(0, 10, 10)
        y = np.sin(x)
        tck = si.splrep(x, y)
        x2 = np.linspace(0, 10, 200)
        return tck, si.splev(x2, tck)

    same(snippet)


def test_splrep_smoothing_full_output():
    """splrep(x, y, s=..., full_output=1) returns (tck, fp, ier, msg) on noisy data."""

    def snippet(si):
        x, y = noisy()
        tck, fp, ier, msg = si.splrep(x, y, s=0.5, full_output=1)
        return tck[0], tck[2], fp, ier, si.splev(XS, tck)

    # FITPACK stops within 0.001*s of s on either side, lekalo within 0.001*s below it: the
    # residual fp and the values differ by that much (module docstring).
    same(snippet, rtol=1e-3)


def test_splev_derivatives_and_ext_modes():
    """splev(x, tck, der=n) and every ext= mode (0 extrapolate, 1 zeros, 2 raise, 3 const) past the data."""

    def snippet(si):
        x = np.arange(0.0, 10.0)
        tck = si.splrep(x, np.cos(x))
        out = [si.splev(XS, tck, der=d) for d in range(4)]
        out += [si.splev(XS, tck, ext=e) for e in (0, 1, 3)]
        return out

    same(snippet, scale=10.0)

    def raises(si):
        x = np.arange(0.0, 10.0)
        return si.splev(XS, si.splrep(x, np.cos(x)), ext=2)

    same(raises)


def test_splrep_lists_and_integers():
    """splrep on Python lists of integers (data typed in by hand), k=2, evaluated at an integer list."""

    def snippet(si):
        x = [0, 3, 6, 9, 12, 15]
        y = [5, 3, 8, 2, 7, 1]
        tck = si.splrep(x, y, k=2)
        return tck, si.splev([1, 2, 4, 14], tck)

    same(snippet, scale=10.0)


def test_splrep_periodic_per1():
    """splrep(..., per=1) of one period of sampled data; the last y is not used."""

    def snippet(si):
        x = np.linspace(0, 2 * np.pi, 21)
        y = np.sin(x) + 0.5 * np.cos(2 * x)
        tck = si.splrep(x, y, per=1)
        return tck, si.splev(np.linspace(-1, 8, 50), tck)

    same(snippet)


def test_splrep_given_knots_weights():
    """splrep with interior knots t (task=-1, least squares) and weights 1/sigma."""

    def snippet(si):
        x, y = noisy(60, seed=1)
        sigma = np.full_like(x, 0.1)
        tck, fp, ier, msg = si.splrep(x, y, w=1 / sigma, t=[2.0, 4.0, 5.0, 6.0, 8.0], task=-1, full_output=True)
        return tck, fp, ier, si.splev(XS, tck)

    same(snippet)


def test_splrep_default_s_with_weights():
    """splrep with weights and s left at None: SciPy's default s = m - sqrt(2m)."""

    def snippet(si):
        x, y = noisy(50, seed=2)
        tck = si.splrep(x, y, w=np.full(50, 10.0))
        return tck[0], si.splev(XS, tck)

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_splint_sproot_spalde():
    """Area under a fitted curve (splint), its zeros (sproot) and all derivatives at a point (spalde)."""

    def snippet(si):
        x = np.linspace(0.3, 10, 30)
        tck = si.splrep(x, np.sin(x))
        return si.splint(0, np.pi, tck), si.sproot(tck), si.spalde(2.5, tck), si.spalde([1.0, 2.0], tck)

    same(snippet)


@pytest.mark.xfail(
    strict=True,
    reason="rounding (not in differences.toml): the interpolant of sin on linspace(0, 10, 30) has "
    "first coefficient exactly 0.0 in lekalo and 8.6e-19 in SciPy's splrep, so lekalo's sproot "
    "reports the root at the left end x = 0 and SciPy's does not (also UnivariateSpline.roots)",
)
def test_sproot_zero_at_first_point():
    """sproot of a sampled sine whose first sample is the zero sin(0)."""

    def snippet(si):
        x = np.linspace(0, 10, 30)
        return si.sproot(si.splrep(x, np.sin(x)))

    same(snippet)


def test_splder_splantider():
    """splder / splantider of a tck tuple, evaluated with splev; the pair is the identity."""

    def snippet(si):
        x = np.linspace(0, 10, 25)
        tck = si.splrep(x, np.exp(-x / 3) * np.sin(x))
        d = si.splder(tck)
        a = si.splantider(tck, 2)
        return d, a, si.splev(XS, d), si.splev(XS, si.splder(si.splantider(tck)))

    same(snippet)


def test_splprep_closed_curve():
    """splprep([x, y], s=0, per=True) of a closed outline, splev on u_new gives a list of coordinates."""

    def snippet(si):
        phi = np.linspace(0, 2 * np.pi, 17)
        r = 1 + 0.3 * np.cos(3 * phi)
        x, y = r * np.cos(phi), r * np.sin(phi)
        x[-1], y[-1] = x[0], y[0]
        tck, u = si.splprep([x, y], s=0, per=True)
        u_new = np.linspace(u.min(), u.max(), 100)
        x_new, y_new = si.splev(u_new, tck)
        return tck[0], tck[2], u, si.splev(u_new, tck), x_new, si.splev(u_new, tck, der=1)

    same(snippet)


def test_splprep_smoothing_default_s():
    """splprep on noisy 3-D points with the default s (m - sqrt(2m)) and no u; the tck structure is a list."""

    def snippet(si):
        rng = np.random.default_rng(3)
        t = np.linspace(0, 4 * np.pi, 60)
        pts = [np.cos(t), np.sin(t), t / 5]
        pts = [p + 0.01 * rng.standard_normal(t.size) for p in pts]
        (t_knots, c, k), u = si.splprep(pts)
        return type(c).__name__, len(c), k, u, si.splev(np.linspace(0, 1, 30), (t_knots, c, k))

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_splprep_full_output_and_list_structure():
    """The question-and-answer thread's splprep call: s=3.0, k=3, nest=-1 on short integer data, tckp and u returned."""

    def snippet(si):
        x = np.array([0, 3, 6, 9, 12, 15])
        y = np.array([0.530, 0.546, 0.586, 0.658, 0.727, 0.801])
        tckp, u = si.splprep([x, y], s=3.0, k=3, nest=-1)
        return tckp, u, si.splev(np.linspace(0, 1, 40), tckp)

    same(snippet, scale=15.0)


def test_insert_knot_tck():
    """insert(x, tck) adds a knot to a tck tuple without changing the curve."""

    def snippet(si):
        x = np.linspace(0, 10, 12)
        tck = si.splrep(x, np.sqrt(x + 1))
        t2, c2, k2 = si.insert(3.3, tck, m=2)
        # the padding after the n - k - 1 coefficients is not read by splev: SciPy leaves whatever
        # its work array held there (uninitialised memory, or the last knot), lekalo zeros
        return t2, c2[: len(t2) - k2 - 1], len(c2), k2, si.splev(XS, (t2, c2, k2))

    same(snippet)


# ---------------------------------------------------------------- the FITPACK classes


def test_univariatespline_default_s():
    """UnivariateSpline(x, y) with s=None (s = len(w)), called on a grid, knots, coefficients, residual."""

    def snippet(si):
        x, y = noisy(80, seed=4)
        spl = si.UnivariateSpline(x, 10 * y)
        return spl(XS), spl.get_knots(), spl.get_residual(), spl.integral(1, 9)

    same(snippet, rtol=1e-3, scale=10.0)  # smoothing condition: within 0.001*s (module docstring)


def test_univariatespline_s0_derivative_roots():
    """UnivariateSpline(..., s=0): derivative(), antiderivative(), roots(), nu= call, derivatives(x)."""

    def snippet(si):
        x = np.linspace(0, 10, 40)
        spl = si.UnivariateSpline(x, np.sin(x), s=0)
        d = spl.derivative()
        a = spl.antiderivative()
        return (spl(XS, nu=1), d(XS), a(XS), spl.roots(), d.roots(), spl.derivatives(2.0),
                spl.get_coeffs(), float(spl.integral(0, np.pi)))

    same(snippet)


def test_univariatespline_ext_modes():
    """UnivariateSpline ext= 'extrapolate', 'zeros', 'raise', 'const' (and integers), also passed to __call__."""

    def snippet(si):
        x = np.linspace(1, 9, 20)
        y = np.log(x)
        return [si.UnivariateSpline(x, y, s=0, ext=e)(XS) for e in ("extrapolate", "zeros", "const", 0, 1, 3)] + [
            si.UnivariateSpline(x, y, s=0)(XS, ext="const")
        ]

    same(snippet)

    def raises(si):
        x = np.linspace(1, 9, 20)
        return si.UnivariateSpline(x, np.log(x), s=0, ext="raise")(XS)

    same(raises)


def test_univariatespline_weights_bbox():
    """UnivariateSpline with weights from error bars, bbox wider than the data, k=4."""

    def snippet(si):
        x, y = noisy(50, seed=5)
        spl = si.UnivariateSpline(x, y, w=np.full(50, 1 / 0.1), bbox=[-1, 11], k=4, s=50)
        return spl.get_knots(), spl(XS)

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_univariatespline_set_smoothing_factor():
    """The tutorial's UnivariateSpline, then spl.set_smoothing_factor(0.5) to smooth more."""

    def snippet(si):
        rng = np.random.default_rng(0)
        x = np.linspace(-3, 3, 50)
        y = np.exp(-(x**2)) + 0.1 * rng.standard_normal(50)
        spl = si.UnivariateSpline(x, y)
        first = spl(np.linspace(-3, 3, 100))
        spl.set_smoothing_factor(0.5)
        return first, spl(np.linspace(-3, 3, 100)), spl.get_knots()

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_interpolatedunivariatespline_scalar_and_decreasing():
    """InterpolatedUnivariateSpline called with a scalar gives a 0-d array; decreasing x is refused."""

    def snippet(si):
        x = np.linspace(0, 5, 11)
        spl = si.InterpolatedUnivariateSpline(x, x**3 - 2 * x, k=3)
        v = spl(2.5)
        return v, type(v).__name__, spl(2.5, nu=2), spl.integral(0, 5)

    same(snippet, scale=125.0)

    def decreasing(si):
        x = np.linspace(5, 0, 11)
        return si.InterpolatedUnivariateSpline(x, x**2)(1.0)

    same(decreasing)


def test_lsqunivariatespline_knots():
    """LSQUnivariateSpline with interior knots from np.linspace, and its knots/coefficients/residual."""

    def snippet(si):
        x, y = noisy(100, seed=6)
        t = np.linspace(1, 9, 7)
        spl = si.LSQUnivariateSpline(x, y, t, k=3)
        return spl(XS), spl.get_knots(), spl.get_coeffs(), float(spl.get_residual())

    same(snippet)


def test_univariatespline_float32_data():
    """float32 measurements (from a file) go into UnivariateSpline; the result dtype is SciPy's."""

    def snippet(si):
        x, y = noisy(30, seed=7)
        spl = si.UnivariateSpline(x.astype(np.float32), y.astype(np.float32), s=0)
        return spl(XS.astype(np.float32)), spl(np.float32(2.0))

    same(snippet)


# ---------------------------------------------------------------- make_interp_spline and BSpline


def test_interp1d_cubic_replacement():
    """interp1d(x, y, kind='cubic') replaced by make_interp_spline(x, y, k=3): SciPy's own interp1d gives the values."""
    x = np.linspace(0, 10, 15)
    y = np.cos(x**2 / 9.0)
    xs = np.linspace(0, 10, 101)
    ref = si_scipy.interp1d(x, y, kind="cubic")(xs)
    got = ls.make_interp_spline(x, y, k=3)(xs)
    np.testing.assert_allclose(got, ref, rtol=RTOL, atol=RTOL)  # the same not-a-knot interpolant
    ref1 = si_scipy.interp1d(x, y)(xs)
    got1 = ls.make_interp_spline(x, y, k=1)(xs)
    np.testing.assert_allclose(got1, ref1, rtol=RTOL, atol=RTOL)


def test_make_interp_spline_bc_types():
    """make_interp_spline with bc_type 'natural', 'clamped', explicit derivative pairs, and k=5."""

    def snippet(si):
        x = np.linspace(0, 2, 12)
        y = np.exp(x)
        out = []
        for bc in ("natural", "clamped", ([(1, 1.0)], [(1, np.exp(2))]), ([(2, 1.0)], [(1, 7.0)]), "not-a-knot", None):
            b = si.make_interp_spline(x, y, k=3, bc_type=bc)
            out += [b.t, b.c, b(np.linspace(-0.2, 2.2, 30))]
        out.append(si.make_interp_spline(x, y, k=5)(np.linspace(0, 2, 30)))
        return out

    same(snippet, scale=10.0)


def test_make_interp_spline_axis1_2d():
    """Several signals as rows of a 2-D y interpolated along axis=1; the call returns rows too."""

    def snippet(si):
        x = np.linspace(0, 1, 9)
        y = np.vstack([np.sin(3 * x), np.cos(3 * x), x**2])
        b = si.make_interp_spline(x, y, axis=1)
        return b(np.linspace(0, 1, 20)), b.c.shape, b.axis, b.derivative()(0.5)

    same(snippet)


def test_make_interp_spline_complex():
    """Complex y (a phasor) interpolated by make_interp_spline, values and derivative complex."""

    def snippet(si):
        x = np.linspace(0, 3, 10)
        y = np.exp(1j * x)
        b = si.make_interp_spline(x, y)
        return b(np.linspace(0, 3, 31)), b(np.linspace(0, 3, 31), nu=1), b.derivative()(1.5), b.antiderivative()(x)

    same(snippet)


def test_make_interp_spline_complex_integrate():
    """BSpline.integrate of a complex interpolant: SciPy 1.17 raises ValueError, lekalo integrates
    the real and imaginary parts (the value SciPy gives for each part on its own)."""
    x = np.linspace(0, 3, 10)
    with pytest.raises(ValueError):
        si_scipy.make_interp_spline(x, np.exp(1j * x)).integrate(0, 3)
    got = ls.make_interp_spline(x, np.exp(1j * x)).integrate(0, 3)
    ref = si_scipy.make_interp_spline(x, np.cos(x)).integrate(0, 3) + 1j * si_scipy.make_interp_spline(x, np.sin(x)).integrate(0, 3)
    np.testing.assert_allclose(got, ref, rtol=RTOL)  # the same interpolant, integrated part by part


def test_bspline_by_hand_extrapolate():
    """BSpline(t, c, k) from hand-written knots; extrapolate=False gives NaN outside, 'periodic' wraps."""

    def snippet(si):
        t = [0, 0, 0, 0, 1, 2, 3, 3, 3, 3]
        c = [-1, 2, 0, -1, 1, 3]
        k = 3
        xs = np.linspace(-1, 4, 26)
        return (si.BSpline(t, c, k)(xs), si.BSpline(t, c, k, extrapolate=False)(xs),
                si.BSpline(t, c, k, extrapolate="periodic")(xs), si.BSpline(t, c, k)(xs, extrapolate=False))

    same(snippet)


def test_bspline_calculus():
    """BSpline derivative(), antiderivative(), integrate() with extrapolate, nu= in the call."""

    def snippet(si):
        x = np.linspace(0, np.pi, 10)
        b = si.make_interp_spline(x, np.sin(x))
        return (b.derivative(2)(x), b.antiderivative()(x), b.integrate(0, np.pi), b.integrate(-1, 4),
                b.integrate(-1, 4, extrapolate=False), b(x, nu=3), b.derivative().k)

    same(snippet)


def test_bspline_basis_element_design_matrix():
    """BSpline.basis_element for plotting one basis function; design_matrix for a hand-made least squares."""

    def snippet(si):
        b = si.BSpline.basis_element([0, 1, 2, 3])
        xs = np.linspace(0, 3, 13)
        t = np.r_[[0.0] * 3, np.linspace(0, 1, 5), [1.0] * 3]
        m = si.BSpline.design_matrix(np.linspace(0, 1, 9), t, 3)
        return b(xs), b.t, m.toarray(), m.shape

    same(snippet)


def test_make_lsq_spline_and_make_smoothing_spline():
    """make_lsq_spline with knots built by np.r_ and make_smoothing_spline with a given lam."""

    def snippet(si):
        x, y = noisy(60, seed=8)
        t = np.r_[(x[0],) * 4, [2.5, 5.0, 7.5], (x[-1],) * 4]
        b = si.make_lsq_spline(x, y, t, k=3)
        s = si.make_smoothing_spline(x, y, lam=0.1)
        return b.c, b(XS), s(XS)

    same(snippet, rtol=1e-10)  # the penalised system of make_smoothing_spline is solved to rounding of its condition (~1e4)


def test_make_smoothing_spline_gcv():
    """make_smoothing_spline(x, y) with lam=None: the GCV choice of the smoothing parameter."""

    def snippet(si):
        x, y = noisy(200, seed=9)
        return si.make_smoothing_spline(x, y)(x)

    # Both minimise the same GCV score by different searches (docs/scipy.md): on noisy data with
    # one minimum they agree to the minimisers' tolerance, about 1e-5 of lam; values to 1e-4.
    same(snippet, rtol=1e-4)


def test_make_splrep_make_splprep():
    """SciPy's newer make_splrep(x, y, s=...) returning a BSpline, and make_splprep for a curve."""

    def snippet(si):
        x, y = noisy(50, seed=10)
        b = si.make_splrep(x, y, s=0.4)
        spl, u = si.make_splprep([np.cos(x / 2), np.sin(x / 2)], s=0.01)
        return b.t, b(XS), u, spl(np.linspace(0, 1, 20))

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_bspline_check_finite():
    """make_interp_spline refuses NaN data with check_finite=True (the default)."""

    def snippet(si):
        x = np.arange(6.0)
        y = np.array([0, 1, np.nan, 2, 3, 4.0])
        return si.make_interp_spline(x, y)

    same(snippet)


# ---------------------------------------------------------------- the piecewise cubics


def test_cubicspline_bc_types_and_calculus():
    """CubicSpline with bc_type 'clamped', 'natural', 'not-a-knot', ((1, 0), (2, 0)); nu=, derivative, integrate, roots."""

    def snippet(si):
        x = np.arange(10)
        y = np.sin(x)
        out = []
        for bc in ("not-a-knot", "clamped", "natural", ((1, 0.0), (2, 0.0))):
            cs = si.CubicSpline(x, y, bc_type=bc)
            out += [cs(XS), cs(XS, 1), cs(XS, nu=2), cs.derivative()(XS), cs.antiderivative()(XS),
                    cs.integrate(0, 9), cs.roots(), cs.solve(0.5), cs.c, cs.x]
        return out

    same(snippet, scale=10.0)


def test_cubicspline_periodic_and_extrapolate():
    """CubicSpline(..., bc_type='periodic') of a closed signal, extrapolate='periodic' and extrapolate=False."""

    def snippet(si):
        theta = np.linspace(0, 2 * np.pi, 9)
        y = np.c_[np.cos(theta), np.sin(theta)]
        cs = si.CubicSpline(theta, y, bc_type="periodic")
        xs = np.linspace(-1, 8, 40)
        return (cs(xs), cs(xs, extrapolate=False),
                si.CubicSpline(theta, y[:, 0], extrapolate=False)(xs), cs.integrate(0, 10), cs.extrapolate)

    same(snippet)


def test_cubicspline_axis1_float32_int():
    """CubicSpline of float32 rows along axis=1, and of integer arrays; dtypes as SciPy's."""

    def snippet(si):
        x = np.arange(6)
        y = (np.arange(18).reshape(3, 6) ** 2).astype(np.float32)
        cs = si.CubicSpline(x, y, axis=1)
        ci = si.CubicSpline(np.array([0, 1, 2, 4]), np.array([0, 1, 4, 16]))
        return cs(np.linspace(0, 5, 11)), cs.c.dtype.name, ci(np.array([0, 1, 3])), ci(3), ci.c

    same(snippet, scale=300.0)


def test_cubicspline_decreasing_x():
    """CubicSpline with x decreasing (a profile measured from the far end)."""

    def snippet(si):
        x = np.linspace(10, 0, 11)
        cs = si.CubicSpline(x, np.sqrt(x + 1))
        return cs(XS), cs.x, cs.integrate(0, 10)

    same(snippet, scale=4.0)


def test_cubicspline_complex():
    """CubicSpline of complex samples (a complex frequency response)."""

    def snippet(si):
        f = np.linspace(0, 5, 12)
        h = 1 / (1 + 1j * f)
        cs = si.CubicSpline(f, h)
        return cs(np.linspace(0, 5, 30)), cs(2.5, 1), cs.integrate(0, 5)

    same(snippet)


def test_pchip_monotone_and_extrapolate():
    """PchipInterpolator for monotone data with extrapolate=False, pchip_interpolate with der=, list inputs."""

    def snippet(si):
        x = [0, 1, 2, 3, 4, 5, 6]
        y = [0, 0.1, 0.1, 0.5, 2.0, 2.1, 3.0]
        p = si.PchipInterpolator(x, y, extrapolate=False)
        xs = np.linspace(-1, 7, 33)
        return p(xs), si.PchipInterpolator(x, y)(xs), si.pchip_interpolate(x, y, xs, der=1), si.pchip_interpolate(x, y, xs, der=[0, 2]), p.derivative()(2.5)

    same(snippet, scale=3.0)


def test_akima_and_makima():
    """Akima1DInterpolator, default and method='makima', extrapolate=True, on data with a flat stretch."""

    def snippet(si):
        x = np.arange(11.0)
        y = np.array([0, 0, 0, 0.5, 0.4, 5.8, 5.9, 6.0, 6.0, 6.0, 6.5])
        a = si.Akima1DInterpolator(x, y)
        m = si.Akima1DInterpolator(x, y, method="makima", extrapolate=True)
        return a(XS), m(XS), a(XS, nu=1), m.integrate(0, 10)

    same(snippet, scale=6.0)


def test_cubichermite_spline():
    """CubicHermiteSpline(x, y, dydx) from positions and velocities of a trajectory."""

    def snippet(si):
        t = np.linspace(0, 2, 7)
        pos = np.c_[np.cos(t), np.sin(t)]
        vel = np.c_[-np.sin(t), np.cos(t)]
        h = si.CubicHermiteSpline(t, pos, vel)
        return h(np.linspace(0, 2, 25)), h(1.0, 1), h.integrate(0, 2)

    same(snippet)


def test_ppoly_from_spline_and_from_power_basis():
    """PPoly.from_spline(tck) and BSpline.from_power_basis(CubicSpline) conversions."""

    def snippet(si):
        x = np.linspace(0, 4, 9)
        tck = si.splrep(x, x * np.exp(-x))
        p = si.PPoly.from_spline(tck)
        b = si.BSpline.from_power_basis(si.CubicSpline(x, np.cos(x)))
        return p(XS / 2.5), p.roots(), b.t, b.c, b(x)

    same(snippet)


# ---------------------------------------------------------------- surfaces and grids


def test_rectbivariatespline_grid_ev():
    """RectBivariateSpline on a meshgrid: grid call, ev at scattered points, grid=False, dx/dy, integral."""

    def snippet(si):
        x = np.linspace(0, 4, 9)
        y = np.linspace(-2, 2, 11)
        X, Y = np.meshgrid(x, y, indexing="ij")
        Z = np.sin(X) * np.exp(-(Y**2))
        spl = si.RectBivariateSpline(x, y, Z)
        xi = np.array([0.3, 1.7, 3.9])
        yi = np.array([-1.5, 0.0, 1.1])
        return (spl(np.linspace(0, 4, 5), np.linspace(-2, 2, 6)), spl.ev(xi, yi), spl(xi, yi, grid=False),
                spl(xi, yi, dx=1, grid=False), spl.ev(xi, yi, dy=1), spl.integral(0, 4, -2, 2),
                spl(1.0, 1.0), spl.get_knots()[0])

    same(snippet)


def test_rectbivariatespline_smoothed_lists():
    """RectBivariateSpline with s>0 on noisy image data given as Python lists, kx=ky=2, bbox."""

    def snippet(si):
        rng = np.random.default_rng(11)
        x = list(range(12))
        y = list(range(10))
        Z = (np.add.outer(np.arange(12.0), np.arange(10.0)) / 5 + 0.1 * rng.standard_normal((12, 10))).tolist()
        spl = si.RectBivariateSpline(x, y, Z, kx=2, ky=2, s=1.0, bbox=[-1, 12, -1, 10])
        return spl(np.arange(12), np.arange(10)), spl.get_knots(), float(spl.get_residual())

    same(snippet, rtol=1e-3, scale=4.0)  # smoothing condition: within 0.001*s (module docstring)


def test_bisplrep_bisplev():
    """bisplrep on scattered samples of a surface, bisplev on a grid and with dx= (the tutorial's pattern,
    data without symmetry: an odd function of (x, y) such as (x + 0.7 y) exp(-6 (x^2 + 1.3 y^2)) ties
    the residuals of mirrored panels exactly, and which of them gets a knot is then decided by
    rounding, as in test_bisplrep_smoothed_tutorial_surface)."""

    def snippet(si):
        x, y = np.mgrid[-1:1:15j, -1:1:15j]
        z = (x + 0.7 * y) * np.exp(-6.0 * ((x - 0.13) ** 2 + 1.3 * (y + 0.21) ** 2))
        tck = si.bisplrep(x, y, z, s=0)
        xn = np.linspace(-1, 1, 7)
        return tck[0], tck[1], tck[4], si.bisplev(xn, xn, tck), si.bisplev(xn, xn, tck, dx=1), si.bisplev(0.2, 0.3, tck)

    same(snippet)


@pytest.mark.xfail(
    strict=True,
    reason="needs Rust (not in differences.toml): the tie-breaking of test_bisplrep_tutorial_interpolation "
    "with smoothing: SciPy's tx [-0.265, -0.075, 0], lekalo's [-0.370, 0, 0.411]; lekalo.scipy.bisplrep "
    "of the points in reversed order gives SciPy's knots exactly",
)
def test_bisplrep_smoothed_tutorial_surface():
    """bisplrep(x, y, z, s=...) of SciPy's tutorial surface (x + y) exp(-6 (x^2 + y^2)) with smoothing."""

    def snippet(si):
        x, y = np.mgrid[-1:1:15j, -1:1:15j]
        z = (x + y) * np.exp(-6.0 * (x * x + y * y))
        tck = si.bisplrep(x, y, z, s=0.05)
        xn = np.linspace(-1, 1, 7)
        return tck[0], tck[1], si.bisplev(xn, xn, tck)

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


@pytest.mark.xfail(
    strict=True,
    reason="needs Rust (not in differences.toml): on SciPy's tutorial surface, symmetric under "
    "(x, y) -> (-y, -x), lekalo's surfit knots are SciPy's mirrored (tx = -ty[::-1] of SciPy's); "
    "its knot choice breaks ties in the opposite data order: lekalo.scipy.bisplrep of the "
    "points in reversed order gives SciPy's knots exactly",
)
def test_bisplrep_tutorial_interpolation():
    """SciPy's tutorial: bisplrep(x, y, z, s=0) on mgrid[-1:1:20j, -1:1:20j], bisplev on a finer grid."""

    def snippet(si):
        x, y = np.mgrid[-1:1:20j, -1:1:20j]
        z = (x + y) * np.exp(-6.0 * (x * x + y * y))
        tck = si.bisplrep(x, y, z, s=0)
        xn = np.linspace(-1, 1, 7)
        return tck[0], tck[1], tck[4], si.bisplev(xn, xn, tck), si.bisplev(xn, xn, tck, dx=1), si.bisplev(0.2, 0.3, tck)

    same(snippet)


def test_smooth_and_lsq_bivariate_spline():
    """SmoothBivariateSpline of scattered points and LSQBivariateSpline with chosen knots, ev at points."""

    def snippet(si):
        rng = np.random.default_rng(12)
        x = rng.uniform(0, 1, 200)
        y = rng.uniform(0, 1, 200)
        z = np.cos(3 * x) * y + 0.01 * rng.standard_normal(200)
        sm = si.SmoothBivariateSpline(x, y, z, s=200 * 0.01**2)
        lsq = si.LSQBivariateSpline(x, y, z, [0.3, 0.6], [0.5], kx=3, ky=3)
        p = np.array([0.25, 0.5, 0.75])
        return sm.ev(p, p), lsq.ev(p, p), lsq.get_coeffs(), lsq(p, p)

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def ndbspl_snippet(si, **solver):
    """make_ndbspl on a 3-D grid (the cubic RegularGridInterpolator replacement) evaluated at an (n, 3) array."""
    g = [np.linspace(0, 1, 6), np.linspace(0, 2, 7), np.linspace(-1, 1, 5)]
    X = np.meshgrid(*g, indexing="ij")
    v = np.sin(X[0]) + X[1] ** 2 * X[2]
    # make_ndbspl is not exported by scipy.interpolate 1.17; users import it from its module
    make_ndbspl = getattr(si, "make_ndbspl", None) or __import__("scipy.interpolate._ndbspline", fromlist=["x"]).make_ndbspl
    nd = make_ndbspl(g, v, k=3, **solver)
    nd = si.NdBSpline(nd.t, nd.c, 3)  # rebuilt by the public class, as from saved knots
    pts = np.array([[0.1, 0.5, 0.3], [0.9, 1.9, -0.7], [0.5, 1.0, 0.0]])
    d = nd.derivative((1, 0, 0))
    return nd(pts), nd(pts, nu=(0, 1, 1)), [ti.copy() for ti in nd.t], d(pts), type(nd.t).__name__


def test_make_ndbspl_direct_solver():
    """make_ndbspl(points, values, k=3, solver=spsolve): the grid interpolant solved directly."""
    from scipy.sparse.linalg import spsolve

    same(lambda si: ndbspl_snippet(si, solver=spsolve), scale=4.0)


def test_make_ndbspl_default_solver():
    """make_ndbspl(points, values, k=3) with SciPy's default iterative solver (gcrotmk)."""
    # SciPy's gcrotmk stops at a relative residual of 1e-5 (its default rtol); lekalo solves the
    # same system exactly (differences.toml, test_solver_err_not_converged): the values differ
    # by that much times the condition of the collocation matrix (about 10 here).
    same(ndbspl_snippet, rtol=1e-4, scale=4.0)


# ---------------------------------------------------------------- objects as users keep them


def test_pickle_and_deepcopy():
    """Fitted splines saved with pickle and duplicated with copy.deepcopy evaluate as the originals."""

    def snippet(si):
        x = np.linspace(0, 5, 20)
        y = np.tanh(x - 2)
        objs = [si.make_interp_spline(x, y), si.CubicSpline(x, y), si.UnivariateSpline(x, y, s=0),
                si.PchipInterpolator(x, y), si.RectBivariateSpline(x, x, np.outer(y, y))]
        out = []
        for o in objs[:4]:
            out += [pickle.loads(pickle.dumps(o))(XS / 2), copy.deepcopy(o)(XS / 2)]
        r = objs[4]
        out += [pickle.loads(pickle.dumps(r))(x, x), copy.deepcopy(r).ev(x, x)]
        return out

    same(snippet)


def test_np_vectorize_and_scalar_loops():
    """A spline used inside np.vectorize and in a Python loop of scalars (float(spl(v)))."""

    def snippet(si):
        x = np.linspace(0, 5, 20)
        spl = si.make_interp_spline(x, np.cos(x))
        us = si.UnivariateSpline(x, np.cos(x), s=0)
        f = np.vectorize(lambda v: spl(v) * 2)
        g = np.vectorize(us)
        loop = [float(spl(v)) for v in np.linspace(0, 5, 7)]
        return f(np.linspace(0, 5, 7)), g(np.linspace(0, 5, 7)), loop, type(spl(1.0)).__name__, spl(1.0).shape

    same(snippet)


def test_plotting_prep_shapes():
    """Plot preparation: xs = np.linspace(x.min(), x.max(), 500) evaluated by every 1-D interpolator, 1-D results of length 500."""

    def snippet(si):
        x = np.array([1.0, 2.0, 4.0, 5.0, 7.0, 8.0])
        y = np.array([2.0, 3.0, 2.5, 4.0, 3.0, 1.0])
        xs = np.linspace(x.min(), x.max(), 500)
        return [f(xs) for f in (si.CubicSpline(x, y), si.PchipInterpolator(x, y), si.Akima1DInterpolator(x, y),
                                si.make_interp_spline(x, y), si.InterpolatedUnivariateSpline(x, y))] + [
            si.splev(xs, si.splrep(x, y))
        ]

    same(snippet, scale=4.0)


def test_regulargridinterpolator_cubic_replacement():
    """RegularGridInterpolator(points, values, method='cubic') replaced by make_ndbspl(points, values, k=3), as the ImportError advises."""
    with pytest.raises(ImportError, match="make_ndbspl"):
        from lekalo.scipy import RegularGridInterpolator  # noqa: F401
    g = [np.linspace(0, 1, 6), np.linspace(0, 2, 7), np.linspace(-1, 1, 5)]
    X = np.meshgrid(*g, indexing="ij")
    v = np.sin(X[0]) + X[1] ** 2 * X[2]
    pts = np.array([[0.1, 0.5, 0.3], [0.9, 1.9, -0.7], [0.5, 1.0, 0.0]])
    ref = si_scipy.RegularGridInterpolator(g, v, method="cubic")(pts)
    got = ls.make_ndbspl(g, v, k=3)(pts)
    # SciPy's cubic grid interpolator is make_ndbspl solved by gcrotmk to a relative residual of
    # 1e-5; lekalo's solve is exact (test_make_ndbspl_default_solver)
    np.testing.assert_allclose(got, ref, rtol=1e-4, atol=1e-4 * 4.0)


def test_interp1d_import_advice():
    """`from lekalo.scipy import interp1d` (a changed import line) says what to use instead."""
    with pytest.raises(ImportError, match="make_interp_spline"):
        from lekalo.scipy import interp1d  # noqa: F401


def test_splev_with_bspline_object_and_2d_x():
    """splev(x, spl) with a BSpline object instead of a tck tuple, and x given as a 2-D array (a meshgrid)."""

    def snippet(si):
        x = np.linspace(0, 4, 12)
        b = si.make_interp_spline(x, np.sqrt(x + 1))
        tck = si.splrep(x, np.sqrt(x + 1))
        xx = np.linspace(0, 4, 12).reshape(3, 4)
        return si.splev(xx, b), si.splev(xx, tck), si.splev(xx, tck, der=1), si.splint(0, 4, b), b(xx)

    same(snippet, scale=3.0)


def test_splrep_xb_xe_and_quiet():
    """splrep with xb/xe wider than the data (end knots placed there), k=1 (a piecewise-linear tck)."""

    def snippet(si):
        x = np.linspace(1, 9, 9)
        y = x**2
        tck = si.splrep(x, y, xb=0, xe=10, s=0)
        tck1 = si.splrep(x, y, k=1)
        return tck, si.splev(XS, tck), tck1, si.splev(XS, tck1)

    same(snippet, scale=100.0)


def test_splprep_given_u_weights():
    """splprep with the parameter u chosen as cumulative chord length, ub/ue, weights and k=2."""

    def snippet(si):
        x = np.array([0.0, 1.0, 2.5, 3.0, 4.2, 5.0, 6.5])
        y = np.array([0.0, 0.8, 1.0, 0.4, -0.3, -0.1, 0.6])
        d = np.r_[0, np.cumsum(np.hypot(np.diff(x), np.diff(y)))]
        tck, u = si.splprep([x, y], u=d, ub=0, ue=d[-1], w=np.ones(7), k=2, s=0)
        return tck, u, si.splev(np.linspace(0, d[-1], 25), tck)

    same(snippet, scale=7.0)


def test_splprep_ub_ue():
    """splprep with ub/ue: ignored without u (FITPACK's u on [0, 1]), end knots at them with u and s=0, refused inside u."""

    def snippet(si):
        x = np.array([0.0, 1.0, 2.5, 3.0, 4.2, 5.0, 6.5])
        y = np.array([0.0, 0.8, 1.0, 0.4, -0.3, -0.1, 0.6])
        u = np.linspace(0, 1, 7)
        out = []
        for kw in (dict(ub=0, ue=1, s=0), dict(u=u, ub=-0.1, ue=1.2, s=0),
                   dict(u=u**2, ue=1.5, s=0, k=2), dict(u=u, ub=-0.1, ue=1.2, s=0, full_output=1)):
            out.append(si.splprep([x, y], **kw))
        return out

    same(snippet, scale=7.0)

    def smoothed(si):
        x = np.array([0.0, 1.0, 2.5, 3.0, 4.2, 5.0, 6.5])
        return si.splprep([x, np.sin(x)], ub=-5, ue=7, s=0.1)

    same(smoothed, rtol=1e-3, scale=7.0)  # smoothing condition: within 0.001*s (module docstring)

    def inside(si):
        x = np.arange(7.0)
        return si.splprep([x, x**2], u=np.linspace(0, 1, 7), ub=0.1, s=0)

    same(inside)


def test_splprep_ub_ue_smoothing():
    """splprep(..., u=u, ub=..., ue=..., s>0): a smoothed curve on a parameter interval wider than u."""

    def snippet(si):
        x, y = noisy(20, seed=15)
        return si.splprep([x, y], u=np.linspace(0, 1, 20), ub=-0.1, ue=1.1, s=0.5)

    same(snippet, rtol=1e-3, scale=10.0)


def test_splrep_splprep_task_1():
    """splrep(..., task=1) and splprep(..., task=1) after a first fit, as their docstrings describe: SciPy 1.17 raises UnboundLocalError (its cache is a local name), with knots t too."""

    def splrep_task1(si):
        x, y = noisy(30, seed=16)
        si.splrep(x, y, s=1.0)
        return si.splrep(x, y, s=0.5, task=1)

    def splprep_task1(si):
        x, y = noisy(30, seed=16)
        si.splprep([x, y], s=1.0)
        return si.splprep([x, y], s=0.5, task=1)

    def splrep_task1_knots(si):
        x, y = noisy(30, seed=16)
        return si.splrep(x, y, t=[3.0, 5.0, 7.0], task=1)

    same(splrep_task1)
    same(splprep_task1)
    same(splrep_task1_knots, scale=2.0)


def test_splprep_full_output():
    """splprep(..., full_output=1) returns ((tck, u), fp, ier, msg) and quiet messages."""

    def snippet(si):
        x, y = noisy(30, seed=13)
        (tck, u), fp, ier, msg = si.splprep([x, y], s=0.5, full_output=1)
        return tck[0], u, fp, ier

    same(snippet, rtol=1e-3, scale=10.0)  # smoothing condition: within 0.001*s (module docstring)


def test_univariatespline_check_finite_and_decreasing():
    """UnivariateSpline with a NaN in y and check_finite=True, and with x decreasing (both refused by SciPy)."""

    def nan(si):
        x = np.arange(8.0)
        y = np.where(x == 3, np.nan, x)
        return si.UnivariateSpline(x, y, check_finite=True)(x)

    same(nan)

    def decreasing(si):
        x = np.arange(8.0)[::-1]
        return si.UnivariateSpline(x, x**2)(x)

    same(decreasing)


def test_univariatespline_nan_mask_weights():
    """Missing data handled with w = ~np.isnan(y) and the NaN replaced by 0 (SciPy's documented idiom)."""

    def snippet(si):
        x, y = noisy(40, seed=14)
        y[[5, 17, 30]] = np.nan
        w = np.isnan(y)
        y[w] = 0.0
        spl = si.UnivariateSpline(x, y, w=~w)
        return spl(XS), spl.get_knots()

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_bspline_vector_valued_coefficients():
    """BSpline(t, c, k) with 2-D c (a planar curve's control points), values of shape (n, 2), and its tck."""

    def snippet(si):
        t = [0, 0, 0, 1, 2, 3, 3, 3]
        c = np.array([[0, 0], [1, 2], [3, 3], [4, 1], [5, 0]], dtype=float)
        b = si.BSpline(t, c, 2)
        return b(np.linspace(0, 3, 13)), b(1.5), b.derivative()(np.linspace(0, 3, 5)), b.integrate(0, 3), b.c.shape

    same(snippet, scale=5.0)


def test_pchip_axis1_and_scalar():
    """PchipInterpolator of rows (axis=1) evaluated at a scalar, and pchip alias with extrapolate."""

    def snippet(si):
        x = np.array([0.0, 1.0, 3.0, 4.0, 7.0])
        y = np.array([[1, 2, 2, 5, 6], [0, -1, 3, 3, 2]], dtype=float)
        p = si.PchipInterpolator(x, y, axis=1)
        q = si.pchip(x, y[0])
        return p(2.0), p(np.array([[0.5, 6.0]])), q(8.0), p.integrate(0, 7), q.roots()

    same(snippet, scale=6.0)


def test_rectbivariatespline_unsorted_grid_call():
    """RectBivariateSpline called on an unsorted grid (refused by SciPy: use grid=False or sort) and with integer ints."""

    def snippet(si):
        x = np.arange(6)
        y = np.arange(7)
        spl = si.RectBivariateSpline(x, y, np.add.outer(x**2, y).astype(float))
        return spl([3, 1, 2], [0, 1])

    same(snippet)

    def ok(si):
        x = np.arange(6)
        y = np.arange(7)
        spl = si.RectBivariateSpline(x, y, np.add.outer(x**2, y).astype(float))
        return spl([3, 1, 2], [0, 1, 2], grid=False), spl(np.array([1, 2, 3]), np.array([0, 1])), spl.ev(2, 3)

    same(ok, scale=30.0)


def test_ndbspline_extrapolate_false():
    """NdBSpline built from saved t and c with extrapolate=False: NaN outside the grid."""

    def snippet(si):
        t1 = np.r_[[0.0] * 3, 0.5, [1.0] * 3]
        t2 = np.r_[[0.0] * 4, [2.0] * 4]
        c = np.arange(16.0).reshape(4, 4)
        nd = si.NdBSpline((t1, t2), c, (2, 3), extrapolate=False)
        xi = np.array([[0.2, 0.5], [1.2, 0.5], [0.7, -0.1], [0.7, 1.9]])
        return nd(xi), nd(xi, extrapolate=True), nd(np.array([0.3, 1.0]))

    same(snippet, scale=16.0)


def test_check_finite_false_fast_path():
    """make_interp_spline(..., check_finite=False) and CubicSpline on clean data: the fast path users take in loops."""

    def snippet(si):
        x = np.linspace(0, 1, 50)
        y = np.sin(8 * x)
        return si.make_interp_spline(x, y, check_finite=False)(x[:-1] + 0.01), si.make_lsq_spline(
            x, y, np.r_[[0.0] * 4, 0.3, 0.6, [1.0] * 4], check_finite=False).c

    same(snippet)


# ---------------------------------------------------------------- odd but common usages


def test_tck_as_lists_from_json():
    """A tck saved to JSON and read back as lists ([t, c, k] of Python floats) fed to splev, splint, splder and BSpline(*tck)."""

    def snippet(si):
        x = np.linspace(0, 6, 14)
        t, c, k = si.splrep(x, np.cos(x))
        tck = [t.tolist(), c.tolist(), int(k)]
        b = si.BSpline(*tck)
        return si.splev(XS / 2, tck), si.splint(1, 5, tck), si.sproot(tck), si.splev(XS / 2, si.insert(2.0, tck)), b(XS / 2), b.c.dtype.name

    same(snippet)


def test_splder_of_tck_lists():
    """splder / splantider of a tck of lists: SciPy 1.17 raises AttributeError ('list' object has no
    attribute 'shape'), lekalo takes the lists as arrays, SciPy's result for the arrays."""
    x = np.linspace(0, 6, 14)
    t, c, k = si_scipy.splrep(x, np.cos(x))
    lists = [t.tolist(), c.tolist(), int(k)]
    for f in ("splder", "splantider"):
        with pytest.raises(AttributeError):
            getattr(si_scipy, f)(lists)
        compare(getattr(si_scipy, f)((t, c, k)), getattr(ls, f)(lists), RTOL, 1.0)


def test_scalar_x_types():
    """Scalars of every kind users pass: Python int/float, np.float64, a 0-d array; the results' types and shapes."""

    def snippet(si):
        x = np.linspace(0, 4, 9)
        y = x**3
        tck = si.splrep(x, y)
        b = si.make_interp_spline(x, y)
        cs = si.CubicSpline(x, y)
        us = si.UnivariateSpline(x, y, s=0)
        out = []
        for v in (2, 2.5, np.float64(2.5), np.array(2.5), np.float32(2.5)):
            out += [si.splev(v, tck), b(v), cs(v), us(v)]
        return out

    same(snippet, scale=64.0)


def test_make_interp_spline_k0_k1_periodic():
    """make_interp_spline with k=0 (steps), k=1 (polyline) and bc_type='periodic' for a closed signal."""

    def snippet(si):
        x = np.linspace(0, 1, 9)
        y = np.cos(2 * np.pi * x)
        b0 = si.make_interp_spline(x, y, k=0)
        b1 = si.make_interp_spline(x, y, k=1)
        bp = si.make_interp_spline(x, y, bc_type="periodic")
        xs = np.linspace(-0.3, 1.3, 33)
        return b0.t, b0(np.linspace(0, 1, 17)), b1(xs), bp(xs), bp.extrapolate, bp(xs, nu=1)

    same(snippet)


def test_integer_and_float32_inputs_to_make_interp_spline():
    """make_interp_spline of integer data (pixel rows) and of float32 samples: dtypes of t, c and values as SciPy's."""

    def snippet(si):
        x = np.arange(8)
        y = np.array([3, 5, 4, 9, 12, 11, 7, 6])
        b = si.make_interp_spline(x, y)
        f = si.make_interp_spline(x.astype(np.float32), y.astype(np.float32))
        return b.t, b.c, b(np.array([0.5, 3.5])), f.c.dtype.name, f(np.float32(2.5)), f(np.array([1.5], dtype=np.float32))

    same(snippet, scale=12.0)


def test_meshgrid_xy_mistake_rectbivariatespline():
    """Z from np.meshgrid(x, y) (indexing='xy', shape (ny, nx)) passed to RectBivariateSpline(x, y, Z): SciPy refuses it."""

    def snippet(si):
        x = np.linspace(0, 1, 6)
        y = np.linspace(0, 2, 8)
        X, Y = np.meshgrid(x, y)
        return si.RectBivariateSpline(x, y, X * Y)

    same(snippet)

    def transposed(si):
        x = np.linspace(0, 1, 6)
        y = np.linspace(0, 2, 8)
        X, Y = np.meshgrid(x, y)
        spl = si.RectBivariateSpline(x, y, (X * Y + X**2).T)
        return spl(x, y), spl(x, y, dx=1, dy=1), spl.partial_derivative(1, 0)(0.5, 1.0)

    same(transposed, scale=3.0)


def test_bisplev_unsorted_and_derivatives():
    """bisplev with unsorted coordinates (refused) and with both dx and dy on a tck from bisplrep with smoothing."""

    def snippet(si):
        rng = np.random.default_rng(16)
        x, y = rng.uniform(-1, 1, (2, 120))
        z = x * y + 0.3 * x**2
        tck = si.bisplrep(x, y, z, kx=3, ky=3, s=0.0)
        g = np.linspace(-0.9, 0.9, 5)
        return si.bisplev(g, g, tck, dx=1, dy=1), si.bisplev(g, g[::-1], tck)

    same(snippet)


def test_splrep_unsorted_or_repeated_x():
    """splrep with x not sorted, or with a repeated x and s=0: SciPy's errors."""

    def unsorted(si):
        x = np.array([0.0, 2.0, 1.0, 3.0, 4.0, 5.0])
        return si.splrep(x, x**2)

    same(unsorted)


@pytest.mark.xfail(
    strict=True,
    reason="refusal (not in differences.toml): splrep(x, y, s=0) with a repeated x; SciPy returns "
    "NaN coefficients ([nan]*5 + [25, 0, ...]), lekalo.scipy raises ValueError('Expect x to not have duplicates')",
)
def test_splrep_repeated_x():
    """splrep with a repeated x and s=0 (SciPy: 'the user is responsible for assuring that the values of x are unique')."""

    def repeated(si):
        x = np.array([0.0, 1.0, 1.0, 3.0, 4.0, 5.0])
        return si.splrep(x, x**2, s=0)

    same(repeated)


def test_univariatespline_roots_non_cubic_and_few_points():
    """UnivariateSpline.roots() of a quadratic (SciPy: cubics only) and a fit with fewer points than k + 1."""

    def roots(si):
        x = np.linspace(0, 6, 20)
        return si.UnivariateSpline(x, np.sin(x), k=2, s=0).roots()

    same(roots)


@pytest.mark.xfail(
    strict=True,
    reason="exception type (not in differences.toml): UnivariateSpline with m <= k; SciPy raises its "
    "Fortran wrapper's private _dfitpack.error('(m>k) failed for hidden m: fpcurf0:m=3'), "
    "lekalo.scipy TypeError('m > k must hold') as SciPy's splrep does",
)
def test_univariatespline_fewer_points_than_k_plus_1():
    """UnivariateSpline of three points with k=3."""

    def few(si):
        return si.UnivariateSpline([0.0, 1.0, 2.0], [1.0, 2.0, 0.0], k=3)

    same(few)


def test_heavy_smoothing_to_a_polynomial():
    """splrep / UnivariateSpline with s so large that the fit is the least-squares cubic (no interior knots, ier=-2)."""

    def snippet(si):
        x, y = noisy(30, seed=17)
        tck, fp, ier, msg = si.splrep(x, y, s=1e6, full_output=True)
        us = si.UnivariateSpline(x, y, s=1e6)
        return tck, fp, ier, us.get_knots(), us(XS)

    same(snippet, scale=10.0)


def test_splint_reversed_limits_and_bspline_integrate():
    """Integrals with the limits reversed (b < a) by splint, BSpline.integrate, UnivariateSpline.integral, CubicSpline.integrate."""

    def snippet(si):
        x = np.linspace(0, 3, 10)
        y = np.exp(x)
        return (si.splint(2.5, 0.5, si.splrep(x, y)), si.make_interp_spline(x, y).integrate(2.5, 0.5),
                si.UnivariateSpline(x, y, s=0).integral(2.5, 0.5), si.CubicSpline(x, y).integrate(2.5, 0.5))

    same(snippet, scale=20.0)


def test_cubicspline_periodic_mismatch_and_repeated_x():
    """CubicSpline(bc_type='periodic') with y[0] != y[-1], and with a repeated x: SciPy's ValueError."""

    def periodic(si):
        x = np.linspace(0, 1, 6)
        return si.CubicSpline(x, x**2, bc_type="periodic")

    same(periodic)

    def repeated(si):
        return si.CubicSpline([0, 1, 1, 2], [0, 1, 2, 3])

    same(repeated)


def test_pchip_akima_decreasing_x():
    """PchipInterpolator and Akima1DInterpolator with x decreasing (data read from the far end)."""

    def snippet(si):
        x = np.linspace(5, 0, 8)
        y = np.sqrt(x)
        return si.PchipInterpolator(x, y)

    same(snippet)

    def akima(si):
        x = np.linspace(5, 0, 8)
        return si.Akima1DInterpolator(x, np.sqrt(x))

    same(akima)


def test_cubicspline_clamped_2d_with_values():
    """CubicSpline of 2-D points with first-derivative end conditions given as arrays per column."""

    def snippet(si):
        t = np.linspace(0, 1, 7)
        pts = np.c_[np.cos(t), np.sin(t), t**2]
        cs = si.CubicSpline(t, pts, bc_type=((1, np.array([0.0, 1.0, 0.0])), (1, np.array([-np.sin(1), np.cos(1), 2.0]))))
        return cs(np.linspace(0, 1, 15)), cs(1.0, 1), cs.c.shape

    same(snippet)


def test_cubicspline_solve_and_ppoly_roots():
    """CubicSpline.solve(y) to find where a curve crosses a level, with discontinuity and extrapolate flags."""

    def snippet(si):
        x = np.arange(12.0)
        cs = si.CubicSpline(x, np.sin(x))
        return cs.solve(0.3), cs.solve(0.3, extrapolate=False), cs.roots(discontinuity=False), cs.derivative().roots()

    same(snippet)


def test_lsqunivariatespline_bad_knots():
    """LSQUnivariateSpline with interior knots that leave a span without data: SciPy's ValueError (Schoenberg-Whitney)."""

    def snippet(si):
        x = np.linspace(0, 10, 30)
        return si.LSQUnivariateSpline(x, np.sin(x), [1.0, 1.01, 1.02, 1.03, 1.04, 1.05, 5.0])(x)

    same(snippet)


def test_make_smoothing_spline_weights():
    """make_smoothing_spline with weights 1/sigma^2 and lam given; evaluated past the data."""

    def snippet(si):
        x, y = noisy(50, seed=18)
        w = np.linspace(1, 3, 50)
        b = si.make_smoothing_spline(x, y, w=w, lam=0.5)
        return b(XS), b.t.shape, b.k

    same(snippet, rtol=1e-10)  # the penalised system is solved to rounding of its condition (~1e4)


def test_rectspherebivariatespline_lat_lon():
    """RectSphereBivariateSpline of a colatitude/longitude grid (SciPy's documentation pattern), ev at points."""

    def snippet(si):
        lats = np.linspace(10, 170, 9) * np.pi / 180
        lons = np.linspace(0, 350, 18) * np.pi / 180
        data = np.dot(np.atleast_2d(90.0 - np.linspace(-80.0, 80.0, 9)).T, np.atleast_2d(180.0 - np.abs(np.linspace(0.0, 350.0, 18)))).T.T
        lut = si.RectSphereBivariateSpline(lats, lons, data)
        new_lats = np.linspace(20, 160, 5) * np.pi / 180
        new_lons = np.linspace(5, 340, 6) * np.pi / 180
        return lut(new_lats, new_lons), lut.ev(new_lats, new_lons[:5])

    same(snippet, scale=3e4)


def test_splprep_single_coordinate_and_splev_der():
    """splprep of a single coordinate list ([x]) and splev's derivative of a parametric tck."""

    def snippet(si):
        x = np.linspace(0, 1, 10) ** 2
        tck, u = si.splprep([x], s=0)
        return tck[0], tck[1], u, si.splev(np.linspace(0, 1, 7), tck, der=1)

    same(snippet)


def test_fwhm_from_spline_roots():
    """Full width at half maximum: UnivariateSpline(x, y - y.max()/2, s=0).roots() unpacked as r1, r2 (a peak profile)."""

    def snippet(si):
        x = np.linspace(-5, 5, 41)
        y = np.exp(-x**2 / 2.0) + 0.05
        r1, r2 = si.UnivariateSpline(x, y - y.max() / 2, s=0).roots()
        peak = si.UnivariateSpline(x, y, s=0).derivative().roots()
        return r2 - r1, r1, peak

    same(snippet, scale=5.0)


def test_rectbivariatespline_uint8_image_and_masked():
    """RectBivariateSpline of an 8-bit image (cv2.imread gives uint8) and of a masked array read from netCDF."""

    def snippet(si):
        img = ((np.add.outer(np.arange(16), np.arange(12) ** 1.5) * 3) % 256).astype(np.uint8)
        sp = si.RectBivariateSpline(np.arange(16), np.arange(12), img)
        z = np.ma.masked_array(np.sin(np.add.outer(np.linspace(0, 1, 9), np.linspace(0, 2, 10))))
        sm = si.RectBivariateSpline(np.linspace(0, 1, 9), np.linspace(0, 2, 10), z)
        xi = np.linspace(0, 15, 7)
        yi = np.linspace(0, 11, 5)
        return sp(xi, yi), sp.ev(xi[:5], yi), sm(0.33, 1.21), sm.ev([0.1, 0.9], [0.1, 1.9])

    same(snippet, scale=256.0)


def test_interp2d_transition_guide():
    """SciPy's interp2d transition guide: RectBivariateSpline(x, y, z.T) for the regular grid, bisplrep(kx=1, ky=1) for scattered data."""

    def snippet(si):
        x = np.arange(-2.01, 2.01, 0.25)
        y = np.arange(-2.01, 3.01, 0.25)
        xx, yy = np.meshgrid(x, y)
        z = np.sin(xx**2 + 2.0 * yy**2)
        r = si.RectBivariateSpline(x, y, z.T, kx=3, ky=3, s=0)
        xn = np.linspace(-2, 2, 9)
        yn = np.linspace(-2, 3, 11)
        small = si.RectBivariateSpline(np.array([0.0, 0.60, 1.0]), np.array([0.0, 0.25, 0.80, 1.0]),
                                       np.array([[1.4, 6.5, 1.5, 1.8], [8.9, 7.3, 1.1, 1.09], [4.5, 9.2, 1.8, 1.2]]),
                                       kx=2, ky=2, s=0)
        return r(xn, yn).T, small([0.60], [0.25]), small([0.25], [0.60])

    same(snippet, scale=10.0)


def test_bisplrep_linear_scattered():
    """bisplrep(x, y, z, kx=1, ky=1, s=0) of scattered measurements (interp2d's linear scattered path), bisplev on a grid."""

    def snippet(si):
        rng = np.random.default_rng(19)
        x = rng.uniform(0, 4, 60)
        y = rng.uniform(0, 3, 60)
        z = np.hypot(x - 2, y - 1.5)
        tck, fp, ier, msg = si.bisplrep(x, y, z, kx=1, ky=1, s=0, full_output=1)
        return tck[0].shape, tck[1].shape, ier, si.bisplev(np.linspace(0.5, 3.5, 4), np.linspace(0.5, 2.5, 3), tck)

    same(snippet, rtol=1e-9, scale=3.0)  # a least-squares system of 60 rows: rounding of its condition (~1e3)


def test_splines_inside_quad_brentq_minimize():
    """A spline handed to scipy.integrate.quad, scipy.optimize.brentq and minimize_scalar (scalar calls, float results)."""
    from scipy.integrate import quad
    from scipy.optimize import brentq, minimize_scalar

    def snippet(si):
        x = np.linspace(0, 6, 25)
        y = np.sin(x) * np.exp(-x / 4)
        out = []
        for f in (si.make_interp_spline(x, y), si.CubicSpline(x, y), si.UnivariateSpline(x, y, s=0),
                  si.PchipInterpolator(x, y), lambda v, tck=si.splrep(x, y): si.splev(v, tck)):
            area, _ = quad(f, 0, 6)
            out += [area, brentq(f, 2, 4), float(minimize_scalar(f, bounds=(3, 6), method="bounded").x)]
        return out

    # quad's adaptive rule and the root finders decide their steps from the values: a rounding
    # difference can move an iterate, each result within the solvers' tolerances (1.5e-8, 2e-12)
    same(snippet, rtol=1e-7)


def test_pickle_more_objects():
    """pickle and copy.copy of the other objects users save: LSQ/Interpolated splines, a periodic BSpline, NdBSpline, PPoly, Akima, smoothing surfaces."""

    def snippet(si):
        x = np.linspace(0, 5, 20)
        y = np.cos(x)
        objs = [si.LSQUnivariateSpline(x, y, [1.0, 2.5, 4.0]), si.InterpolatedUnivariateSpline(x, y, ext=3),
                si.BSpline(np.arange(8.0), np.arange(4.0), 3, extrapolate="periodic"),
                si.PPoly.from_spline(si.splrep(x, y)), si.Akima1DInterpolator(x, y, method="makima"),
                si.CubicHermiteSpline(x, y, -np.sin(x))]
        out = []
        for o in objs:
            out += [pickle.loads(pickle.dumps(o))(XS / 2), copy.copy(o)(XS / 2)]
        nd = si.NdBSpline((np.r_[[0.0] * 4, 2.5, [5.0] * 4], np.r_[[0.0] * 3, [1.0] * 3]), np.arange(15.0).reshape(5, 3), (3, 2))
        out.append(pickle.loads(pickle.dumps(nd))(np.array([[1.0, 0.5], [4.0, 0.2]])))
        return out

    same(snippet, scale=15.0)

    def surface(si):
        rng = np.random.default_rng(20)
        px, py = rng.uniform(0, 5, (2, 80))
        sb = si.SmoothBivariateSpline(px, py, np.sin(px) * py, s=1.0)
        return pickle.loads(pickle.dumps(sb)).ev(px[:5], py[:5]), copy.deepcopy(sb)(1.0, 2.0)

    same(surface, rtol=1e-3, scale=5.0)  # smoothing condition: within 0.001*s (module docstring)


def test_bspline_negative_nu():
    """BSpline called with nu=-1 (hoping for an antiderivative): SciPy 1.17 raises NotImplementedError, arrays and scalars alike."""

    def array(si):
        x = np.linspace(0, 5, 12)
        return si.make_interp_spline(x, np.sin(x))(x, nu=-1)

    same(array)

    def scalar(si):
        x = np.linspace(0, 5, 12)
        return si.make_interp_spline(x, np.sin(x))(1.0, nu=-1)

    same(scalar)

    def periodic(si):
        return si.BSpline(np.arange(8.0), np.arange(4.0), 3, extrapolate="periodic")(2.5, nu=-1)

    same(periodic)


@pytest.mark.xfail(
    strict=True,
    reason="refusal (not in differences.toml): UnivariateSpline(x, y) with NaN in y and check_finite "
    "left False; SciPy returns an object (its class switched to InterpolatedUnivariateSpline) whose "
    "values are NaN, lekalo.scipy raises lekalo.InputError (a ValueError) naming y[5]",
)
def test_univariatespline_nan_in_y_unchecked():
    """UnivariateSpline of data with a NaN, check_finite not set (SciPy's default False)."""

    def snippet(si):
        x = np.linspace(0, 5, 12)
        return si.UnivariateSpline(x, np.where(x > 2, np.nan, np.sin(x)))(x)

    same(snippet)


@pytest.mark.xfail(
    strict=True,
    reason="refusal (not in differences.toml): splprep of points with NaN coordinates; SciPy returns "
    "NaN knots, coefficients and u, lekalo.scipy raises lekalo.InputError (a ValueError) naming points[11]",
)
def test_splprep_nan_points():
    """splprep of a digitised curve with missing (NaN) coordinates."""

    def snippet(si):
        x = np.linspace(0, 5, 12)
        return si.splprep([x, np.where(x > 2, np.nan, np.sin(x))])

    same(snippet)


def test_univariatespline_class_after_fit():
    """type(spl).__name__ as a notebook shows it: SciPy's UnivariateSpline becomes InterpolatedUnivariateSpline for s=0
    and LSQUnivariateSpline for the least-squares polynomial, also after set_smoothing_factor; a user's subclass stays."""

    def snippet(si):
        x = np.linspace(0, 5, 12)
        y = np.sin(x)
        xn, yn = noisy(60, seed=21)

        class Mine(si.UnivariateSpline):
            pass

        u = si.UnivariateSpline(xn, yn)
        names = [type(u).__name__]
        u.set_smoothing_factor(0.5)
        names.append(type(u).__name__)
        names += [type(si.UnivariateSpline(x, y, s=0)).__name__, type(si.UnivariateSpline(xn, yn, s=0.5)).__name__,
                  type(Mine(x, y, s=0)).__name__, type(si.UnivariateSpline(x, y, s=0).derivative()).__name__]
        return names, isinstance(si.UnivariateSpline(x, y, s=0), si.UnivariateSpline)

    same(snippet)


def test_splrep_given_knots_mistakes():
    """splrep(x, y, t=...) with the usual mistakes: the full knot vector of a BSpline (ends included), a knot past the data,
    knots crowded where there is no data, more knots than points; SciPy's TypeError or ValueError for each."""
    x = np.linspace(0, 5, 12)
    for t in ([0.0, 0.0, 0.0, 0.0, 2.5, 5.0, 5.0, 5.0, 5.0], [1.0, 2.0, 6.0], [2.0, 1.0, 3.0], [1.0, 1.0, 1.0, 1.0, 2.0],
              [1.0, 1.01, 1.02, 1.03], list(np.linspace(0.1, 4.9, 12)), [1.5, 3.5]):
        same(lambda si, t=t: si.splrep(x, np.sin(x), t=t))


@pytest.mark.xfail(
    strict=True,
    reason="refusal (not in differences.toml): make_lsq_spline on knots crowded where there is no data "
    "(Schoenberg-Whitney fails); SciPy 1.17's default method='qr' returns one solution of the rank-deficient "
    "system (c[0] = -5e-18, ...), lekalo.scipy raises lekalo.InputError (a ValueError) naming basis function 3",
)
def test_make_lsq_spline_rank_deficient():
    """make_lsq_spline with interior knots [1, 1.01, 1.02, 1.03] on data spaced 0.45 apart."""

    def snippet(si):
        x = np.linspace(0, 5, 12)
        return si.make_lsq_spline(x, np.sin(x), np.r_[[0.0] * 4, 1, 1.01, 1.02, 1.03, [5.0] * 4])(x)

    same(snippet, rtol=1e-6)


@pytest.mark.xfail(
    strict=True,
    reason="refusal (not in differences.toml): negative weights; FITPACK squares w_i (y_i - s(x_i)) "
    "and SciPy accepts w < 0 (the fit of |w|), lekalo.scipy raises lekalo.InputError (a ValueError): "
    "'data weight 0 is -1: weights must be finite and >= 0'",
)
def test_univariatespline_negative_weights():
    """UnivariateSpline with weights computed as 1/error where the error column came out negative."""

    def snippet(si):
        x, y = noisy(30, seed=22)
        return si.UnivariateSpline(x, y, w=-np.full(30, 10.0))(XS)

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_empty_query_points():
    """Evaluating at an empty selection (xs[mask] where the mask is all False): every interpolator's shape, and splev's ValueError."""
    x = np.linspace(0, 5, 12)
    y = np.sin(x)
    xq = x[x > 10]

    def snippet(si):
        y3 = np.stack([y, 2 * y])
        return (si.CubicSpline(x, y3, axis=1)(xq), si.make_interp_spline(x, y)(xq), si.PchipInterpolator(x, y)(xq),
                si.UnivariateSpline(x, y, s=0)(xq), si.RectBivariateSpline(x, x, np.outer(y, y)).ev(xq, xq),
                si.splev(xq, si.make_interp_spline(x, y)))

    same(snippet)
    for kw in ({}, {"der": 1}, {"ext": 2}):
        same(lambda si, kw=kw: si.splev(xq, si.splrep(x, y), **kw))
    same(lambda si: si.splev(xq, si.splprep([x, y], s=0)[0]))


def test_make_ndbspl_even_and_mixed_degrees():
    """make_ndbspl(points, values, k=2) and k=(4, 1): SciPy documents odd degrees and takes even ones (mid-point knots)."""
    from scipy.sparse.linalg import spsolve

    def snippet(si):
        make_ndbspl = getattr(si, "make_ndbspl", None) or __import__("scipy.interpolate._ndbspline", fromlist=["x"]).make_ndbspl
        rng = np.random.default_rng(23)
        g = [np.sort(rng.uniform(0, 1, 7)), np.linspace(0, 2, 8)]
        v = rng.normal(size=(7, 8))
        pts = np.c_[rng.uniform(-0.1, 1.1, 15), rng.uniform(-0.1, 2.1, 15)]
        return [make_ndbspl(g, v, k=k, solver=spsolve)(pts) for k in (2, (4, 1), 4)]

    # the same collocation systems solved directly; a quartic on random data: condition ~1e3
    same(snippet, rtol=1e-10, scale=3.0)


def test_univariatespline_small_s_many_knots():
    """UnivariateSpline(x, y, s=small) on noisy data, where FITPACK needs more than m/2 knots."""

    def snippet(si):
        x = np.linspace(0, 10, 40)
        y = np.sin(x) + 0.1 * np.random.default_rng(0).standard_normal(40)
        spl = si.UnivariateSpline(x, y, s=0.05)
        return spl.get_knots(), spl(np.linspace(0, 10, 201))

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_splrep_textbook_s_residual_just_above_s():
    """splrep(x, y, s=m*sigma**2), the tutorial's choice of s for noise of known sigma."""

    def snippet(si):
        x = np.linspace(0, 10, 50)
        y = np.sin(x) + 0.1 * np.random.default_rng(147).standard_normal(50)
        tck = si.splrep(x, y, s=len(x) * 0.1**2)
        return tck[0], si.splev(np.linspace(0, 10, 101), tck)

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_splprep_closed_curve_given_angles():
    """splprep([x, y], u=theta, s=0, per=1): a closed outline parametrised by its polar angle, evaluated past the period."""

    def snippet(si):
        theta = np.linspace(0, 2 * np.pi, 13)
        theta[1:-1] += 0.1 * np.sin(3 * theta[1:-1])
        r = 1 + 0.2 * np.cos(3 * theta)
        out = []
        for k in (1, 2, 3, 5):
            tck, u = si.splprep([r * np.cos(theta), r * np.sin(theta)], u=theta, s=0, per=1, k=k)
            out += [tck[0], tck[1], u, si.splev(np.linspace(-1, 8, 30), tck), si.splev(1.0, tck, der=1)]
        return out

    same(snippet, scale=2.0)


def test_splprep_closed_curve_given_angles_smoothed():
    """splprep([x, y], u=theta, s=..., per=1) of a noisy closed outline."""

    def snippet(si):
        theta = np.linspace(0, 2 * np.pi, 40)
        rng = np.random.default_rng(24)
        r = 1 + 0.2 * np.cos(3 * theta) + 0.01 * rng.standard_normal(40)
        return si.splprep([r * np.cos(theta), r * np.sin(theta)], u=theta, s=0.01, per=1)

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_univariatespline_set_smoothing_factor_smaller():
    """UnivariateSpline(x, y, s=1.0) then spl.set_smoothing_factor(0.2) to follow the data more closely."""

    def snippet(si):
        x, y = noisy(60, seed=25)
        spl = si.UnivariateSpline(x, y, s=1.0)
        spl.set_smoothing_factor(0.2)
        return spl(XS), spl.get_knots()

    same(snippet, rtol=1e-3)  # smoothing condition: within 0.001*s (module docstring)


def test_univariatespline_set_smoothing_factor_goes_on_from_the_knots():
    """UnivariateSpline(x, y, s=20) then set_smoothing_factor(1.0), and on to 0.1: FITPACK adds knots to the coarse fit's, other knots than a fresh UnivariateSpline(x, y, s=1.0) takes."""

    def snippet(si):
        x = np.arange(200) / 20.0
        y = np.sin(x) * np.cos(0.3 * x * x) + 0.05 * np.random.default_rng(31).standard_normal(200)
        spl = si.UnivariateSpline(x, y, s=20.0)
        # copies: SciPy's get_knots is a view of the array that set_smoothing_factor refills
        out = [spl.get_knots().copy()]
        for s in (1.0, 0.1, 0.5):
            spl.set_smoothing_factor(s)
            out += [spl.get_knots().copy(), spl(XS)]
        return out

    same(snippet, rtol=1e-3, scale=2.0)  # smoothing condition: within 0.001*s (module docstring)


def test_interp2d_bug_for_bug_bisplrep():
    """SciPy's interp2d transition guide, the legacy-compatible path: bisplrep(xx, yy, z, kx=3, ky=3, s=0) on meshgrid data, bisplev on new axes."""

    def snippet(si):
        x = np.linspace(0, 5, 12)
        xx, yy = np.meshgrid(x, x)
        z = np.sin(xx) * np.sin(yy)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # the guide's replacement runs without a warning
            tck, fp, ier, msg = si.bisplrep(xx.ravel(), yy.ravel(), z.ravel(), kx=3, ky=3, s=0.0, full_output=1)
            tck2 = si.bisplrep(xx.ravel(), yy.ravel(), z.ravel(), kx=3, ky=3, s=0.0)
        xn = np.linspace(0, 5, 9)
        return tck[0], tck[1], fp, ier, si.bisplev(xn, xn, tck2)

    # the minimal-norm interpolant of a rank-deficient system (156 coefficients, 144 points):
    # both reach it by orthogonal factorisations, to the rounding of its condition (~1e4)
    same(snippet, rtol=1e-9)


def test_bisplrep_zero_weight_for_missing_point():
    """bisplrep with w=0 to drop a bad measurement (as UnivariateSpline allows): FITPACK's surfit refuses weights <= 0."""

    def snippet(si):
        rng = np.random.default_rng(26)
        x, y = rng.uniform(0, 1, (2, 40))
        w = np.ones(40)
        w[7] = 0.0
        return si.bisplrep(x, y, x * y, w=w, s=0.1)

    same(snippet)


@pytest.mark.xfail(
    strict=True,
    reason="SciPy defect (documented in docs/scipy.md, not in differences.toml): RectBivariateSpline with "
    "kx=3, ky=1 on a 7 x 19 noisy grid and s = m*sigma**2; when x reaches its knots of interpolation, "
    "SciPy 1.17's fpregr writes y's knots of interpolation over y's 4 interior knots and goes on with "
    "stale counts (11 and 21 knots at the end, fp = 1.00004 s); lekalo keeps FITPACK's rounds "
    "(11 and 10 knots, fp = 0.99999 s); values apart by 0.14 (data of size 1, noise 0.1)",
)
def test_rectbivariatespline_mixed_degrees_smoothing():
    """RectBivariateSpline(x, y, Z, kx=3, ky=1, s=Z.size*sigma**2): cubic across, piecewise linear along a noisy profile grid."""

    def snippet(si):
        x = np.linspace(0, 1, 7)
        y = np.linspace(0, 2, 19)
        Z = np.sin(3 * np.add.outer(x, y)) + 0.1 * np.random.default_rng(3).standard_normal((7, 19))
        spl = si.RectBivariateSpline(x, y, Z, kx=3, ky=1, s=Z.size * 0.1**2)
        return [len(t) for t in spl.get_knots()], spl(np.linspace(0, 1, 11), np.linspace(0, 2, 21))

    same(snippet, rtol=1e-3, scale=1.0)  # smoothing condition: within 0.001*s (module docstring)


def test_rectbivariatespline_knots_in_order_where_scipy_leaves_them_unsorted():
    """The defect behind the expected failure above, on a 7 x 24 noisy grid with kx=3, ky=1: SciPy's
    ty comes back out of order; lekalo.scipy's knots are sorted and its residual meets the smoothing
    condition (FITPACK's: below s, or above it by less than 0.001*s)."""
    x = np.linspace(0, 1, 7)
    y = np.linspace(0, 2, 24)
    Z = np.sin(3 * np.add.outer(x, y)) + 0.1 * np.random.default_rng(17).standard_normal((7, 24))
    s = Z.size * 0.1**2
    ty_scipy = si_scipy.RectBivariateSpline(x, y, Z, kx=3, ky=1, s=s).get_knots()[1]
    assert np.any(np.diff(ty_scipy) < 0)  # SciPy 1.17's fpregr (docs/scipy.md)
    spl = ls.RectBivariateSpline(x, y, Z, kx=3, ky=1, s=s)
    for t in spl.get_knots():
        assert np.all(np.diff(t) >= 0)
    residual = np.sum((spl(x, y) - Z) ** 2)
    assert residual < 1.001 * s
    assert spl.get_residual() == pytest.approx(residual, rel=1e-9)
