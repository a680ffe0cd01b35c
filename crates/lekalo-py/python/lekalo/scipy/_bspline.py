"""``BSpline`` and the coefficient helpers of ``lekalo.scipy``: SciPy's interface, lekalo's
``BSplineCurve`` underneath (evaluation with extrapolation, derivative and antiderivative curves,
integrals, knot insertion)."""

from __future__ import annotations

import operator
from typing import Any

import numpy as np

from .. import _lekalo
from ._knots import _augknt, _not_a_knot, _periodic_knots


def _normalize_axis(axis: int, ndim: int) -> int:
    if not -ndim <= axis < ndim:
        raise np.exceptions.AxisError(axis, ndim)
    return axis % ndim


def _get_dtype(dtype: Any) -> Any:
    """SciPy's rule: complex stays complex, everything else becomes float64."""
    return np.complex128 if np.issubdtype(dtype, np.complexfloating) else np.float64


def _as_float_array(x: Any, check_finite: bool = False) -> np.ndarray:
    x = np.ascontiguousarray(x)
    x = np.ascontiguousarray(x, dtype=_get_dtype(x.dtype))
    if check_finite and not np.isfinite(x).all():
        raise ValueError("Array must not contain infs or nans.")
    return x


def _one_number(x: Any) -> float | None:
    """``x`` as a Python float when it is one real number (a ``float``, NumPy's ``float64``, or a
    0-d float64 array), else ``None``: the argument of the scalar calls, which take one Rust call
    on the arrays in place and give the bits of the array call at that one point."""
    if isinstance(x, float):
        return x
    if type(x) is np.ndarray and x.ndim == 0 and x.dtype == np.float64:
        return float(x)
    return None


def _real_columns(c: np.ndarray, n: int) -> np.ndarray:
    """The first ``n`` coefficients as an ``(n, m)`` float64 array (complex: real and imaginary
    parts as separate columns, so that lekalo computes with real points)."""
    cc = np.ascontiguousarray(c[:n].reshape(n, -1))
    if np.iscomplexobj(cc):
        cc = np.ascontiguousarray(cc.view(np.float64))
    return cc


def _from_columns(a: np.ndarray, complex_: bool) -> np.ndarray:
    """Inverse of :func:`_real_columns` on the last axis."""
    a = np.ascontiguousarray(a)
    return a.view(np.complex128) if complex_ else a


def _kept(t: np.ndarray, k: int) -> np.ndarray:
    """Which of the ``n`` B-splines have support: SciPy accepts knots of multiplicity above
    ``k + 1`` (``make_interp_spline(k=0)`` ends on one), whose B-splines vanish identically."""
    n = t.shape[0] - k - 1
    return t[k + 1 : k + 1 + n] > t[:n]


def _curve(t: np.ndarray, cc: np.ndarray, k: int):
    """lekalo's curve for the spline, without the B-splines that vanish identically (one copy
    of their knot each), the same function (lekalo refuses such knot vectors)."""
    kept = _kept(t, k)
    if not kept.all():
        drop = np.flatnonzero(~kept)
        t = np.delete(t, drop)
        cc = np.ascontiguousarray(cc[kept])
    return _lekalo.BSplineCurve(k, t, cc)


class BSpline:
    """Univariate spline in the B-spline basis, ``S(x) = sum_j c_j B_{j,k;t}(x)``, as
    ``scipy.interpolate.BSpline``; evaluation, derivatives and integrals by lekalo."""

    # the classes ``from_power_basis`` converts: ``CubicSpline``, registered by ``_ppoly``, which
    # builds on this module (so this module does not import it)
    _power_basis_types: tuple = ()

    def __init__(self, t: Any, c: Any, k: int, extrapolate: Any = True, axis: int = 0) -> None:
        # the degree as an int from here on: `k=True` (SciPy's 1) must not index the knots as a mask
        k = self.k = int(operator.index(k))
        self.c = np.asarray(c)
        self.t = np.ascontiguousarray(t, dtype=np.float64)
        if extrapolate == "periodic":
            self.extrapolate = extrapolate
        else:
            self.extrapolate = bool(extrapolate)
        n = self.t.shape[0] - self.k - 1
        axis = _normalize_axis(axis, self.c.ndim)
        self.axis = axis
        if axis != 0:
            self.c = np.moveaxis(self.c, axis, 0)
        if k < 0:
            raise ValueError("Spline order cannot be negative.")
        if self.t.ndim != 1:
            raise ValueError("Knot vector must be one-dimensional.")
        if n < self.k + 1:
            raise ValueError(f"Need at least {2 * k + 2} knots for degree {k}")
        if (np.diff(self.t) < 0).any():
            raise ValueError("Knots must be in a non-decreasing order.")
        # sorted knots: t[k] < t[n] means two distinct ones (np.unique only to decide otherwise)
        if not self.t[k] < self.t[n] and len(np.unique(self.t[k : n + 1])) < 2:
            raise ValueError("Need at least two internal knots.")
        if not np.isfinite(self.t).all():
            raise ValueError("Knots should not have nans or infs.")
        if self.c.ndim < 1:
            raise ValueError("Coefficients must be at least 1-dimensional.")
        if self.c.shape[0] < n:
            raise ValueError("Knots, coefficients and degree are inconsistent.")
        self.c = np.ascontiguousarray(self.c, dtype=_get_dtype(self.c.dtype))

    @classmethod
    def construct_fast(cls, t: Any, c: Any, k: int, extrapolate: Any = True, axis: int = 0) -> "BSpline":
        """Construct a spline without making checks (SciPy's ``construct_fast``)."""
        self = object.__new__(cls)
        self.t, self.c, self.k = t, c, k
        self.extrapolate = extrapolate
        self.axis = axis
        return self

    # SciPy keeps the arrays as ``_t`` and ``_c`` behind the ``t`` and ``c`` properties; code
    # (and SciPy's own tests) that reads the private names finds the same arrays here
    @property
    def _t(self) -> np.ndarray:
        return self.t

    @property
    def _c(self) -> np.ndarray:
        return self.c

    @property
    def tck(self):
        """Equivalent to ``(self.t, self.c, self.k)`` (read-only)."""
        return self.t, self.c, self.k

    @classmethod
    def basis_element(cls, t: Any, extrapolate: Any = True) -> "BSpline":
        """The B-spline on the knots ``t`` (degree ``len(t) - 2``), SciPy's construction."""
        k = len(t) - 2
        t = _as_float_array(t)
        t = np.r_[(t[0] - 1,) * k, t, (t[-1] + 1,) * k]
        c = np.zeros_like(t)
        c[k] = 1.0
        return cls.construct_fast(t, c, k, extrapolate)

    @classmethod
    def design_matrix(cls, x: Any, t: Any, k: int, extrapolate: bool = False):
        """The sparse matrix ``B_{j,k}(x_i)`` (``scipy.sparse.csr_array``): its three arrays
        written once by lekalo's ``design_matrix_csr`` (``design_matrix_into``: the basis
        functions at each ``x``, P&T A2.2); with ``extrapolate``, the end spans' basis
        polynomials continue beyond ``[t[k], t[n]]``. The result is SciPy's own sparse type, so
        SciPy must be installed (``ImportError`` naming it otherwise)."""
        try:
            from scipy.sparse import csr_array
        except ImportError as e:
            raise ImportError(
                "lekalo.scipy: BSpline.design_matrix returns a scipy.sparse.csr_array, which needs "
                "SciPy: install the package 'scipy' (pip install scipy)"
            ) from e

        x = _as_float_array(x, True)
        t = _as_float_array(t, True)
        if extrapolate != "periodic":
            extrapolate = bool(extrapolate)
        if k < 0:
            raise ValueError("Spline order cannot be negative.")
        if t.ndim != 1 or np.any(t[1:] < t[:-1]):
            raise ValueError(f"Expect t to be a 1-D sorted array_like, but got t={t}.")
        if len(t) < 2 * k + 2:
            raise ValueError(f"Length t is not enough for k={k}.")
        n = t.shape[0] - k - 1
        if extrapolate == "periodic":
            x = t[k] + (x - t[k]) % (t[n] - t[k])
            extrapolate = False
        elif not extrapolate and (x.min() < t[k] or x.max() > t[n]):
            # NumPy's reductions (SciPy's builtin min and max walk the array as Python floats;
            # both refuse an empty x with a ValueError)
            raise ValueError(f"Out of bounds: x = {x}.")
        data, indices, indptr = _lekalo.design_matrix_csr(t, k, x, extrapolate)
        return csr_array((data, indices, indptr), shape=(len(x), n))

    def _n(self) -> int:
        return self.t.shape[0] - self.k - 1

    def __call__(self, x: Any, nu: int = 0, extrapolate: Any = None) -> np.ndarray:
        """Evaluate the spline or its ``nu``-th derivative at ``x`` (SciPy's shapes: ``x.shape``
        followed by the coefficients' trailing shape, the interpolation axis at ``axis``)."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        xf = _one_number(x)
        if xf is not None and nu == 0 and self.k and extrapolate != "periodic":
            # one number in: lekalo's bspline_value on the arrays as they are (no curve built);
            # anything it does not take (complex or N-D coefficients, ...) goes the array way
            try:
                return np.array(_lekalo.bspline_value(self.t, self.k, self.c, xf, bool(extrapolate)))
            except Exception:
                pass
        x = np.asarray(x)
        x_shape, x_ndim = x.shape, x.ndim
        x = np.ascontiguousarray(x.ravel(), dtype=np.float64)
        n = self._n()
        if extrapolate == "periodic":
            x = self.t[self.k] + (x - self.t[self.k]) % (self.t[n] - self.t[self.k])
            extrapolate = False
        out = self._evaluate(x, nu, bool(extrapolate))
        out = out.reshape(x_shape + self.c.shape[1:])
        if self.axis != 0:
            axes = list(range(out.ndim))
            axes = axes[x_ndim : x_ndim + self.axis] + axes[:x_ndim] + axes[x_ndim + self.axis :]
            out = out.transpose(axes)
        return out

    def _evaluate(self, x: np.ndarray, nu: int, extrapolate: bool) -> np.ndarray:
        nu = operator.index(nu)
        if nu < 0:
            # SciPy 1.17's evaluate_spline refuses it so (earlier SciPy raised ValueError)
            raise NotImplementedError(f"Cannot do derivative order nu= {nu}")
        n = self._n()
        m = int(np.prod(self.c.shape[1:], dtype=np.int64))
        complex_ = np.iscomplexobj(self.c)
        if m == 0 or x.shape[0] == 0:
            return np.full((x.shape[0], m), np.nan, dtype=self.c.dtype)
        # one pass in lekalo: NaN at non-finite x (and outside without extrapolation), the end
        # polynomials continued otherwise (CurveEvaluator::eval_batch_beyond)
        cc = _real_columns(self.c, n)
        try:
            curve = _curve(self.t, cc, self.k)
        except ValueError:
            if np.isfinite(cc).all():
                raise
            # NaN or infinite coefficients (lekalo's curves refuse them, SciPy evaluates them):
            # the spline as a 1-variate tensor product, whose evaluation reads the coefficients
            # in place, unchecked, so that each value is NaN or infinite where SciPy's is
            values = _lekalo.tensor_values(
                (self.t,), cc, (self.k,), x[:, None], [nu] if nu else None,
                "continue" if extrapolate else "nan",
            )
            return _from_columns(values, complex_)
        out = _from_columns(curve.eval_beyond(x, nu, extrapolate), complex_)
        if self.k == 0 and nu == 0 and self.t[n - 1] == self.t[n]:
            # SciPy's span search ends in the last interval even when it is empty: a
            # piecewise constant (make_interp_spline(k=0)) takes its last value from x[-1] on
            ok = np.isfinite(x)
            if not extrapolate:
                ok &= (x >= self.t[self.k]) & (x <= self.t[n])
            out[ok & (x >= self.t[n])] = self.c[n - 1].reshape(-1)
        return out

    def derivative(self, nu: int = 1) -> "BSpline":
        """The derivative spline of order ``nu`` (SciPy's ``splder`` knots ``t[nu:-nu]``, the
        coefficients zero-padded to the knots' length), lekalo's ``tck_derivative`` on the arrays
        as they are (no curve built)."""
        t, c = _derivative_tc(self.t, self.c, self.k, nu)
        return self.construct_fast(t, c, self.k - nu, extrapolate=self.extrapolate, axis=self.axis)

    def antiderivative(self, nu: int = 1) -> "BSpline":
        """The antiderivative of order ``nu`` (SciPy's ``splantider``: degree ``k + nu``, end
        knots repeated), lekalo's ``tck_antiderivative`` on the arrays as they are. A periodic spline's antiderivative does
        not extrapolate (it is not periodic)."""
        t, c = _antiderivative_tc(self.t, self.c, self.k, nu)
        extrapolate = False if self.extrapolate == "periodic" else self.extrapolate
        return self.construct_fast(t, c, self.k + nu, extrapolate=extrapolate, axis=self.axis)

    def integrate(self, a: float, b: float, extrapolate: Any = None):
        """``∫_a^b S(x) dx`` (SciPy's rules: outside the base interval zero unless
        extrapolating; periodic splines integrate whole periods), lekalo's ``tck_integral`` (only
        the coefficients between the limits read)."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        sign = 1
        if b < a:
            a, b = b, a
            sign = -1
        n = self._n()
        tail = self.c.shape[1:]
        m = int(np.prod(tail, dtype=np.int64))
        if m == 0:
            return np.zeros(tail, dtype=self.c.dtype) * sign
        complex_ = np.iscomplexobj(self.c)
        t, cols, k = self.t, _real_columns(self.c, n), self.k
        ts, te = t[k], t[n]

        def piece(lo: float, hi: float, ext: bool) -> np.ndarray:
            # lekalo's integral on the arrays as they are, reading the coefficients between the
            # limits only; the limits lie in the base interval unless extrapolating
            return _lekalo.tck_integral(t, cols, k, float(lo), float(hi))

        if extrapolate == "periodic":
            period = te - ts
            n_periods, left = divmod(b - a, period)
            total = piece(ts, te, False) * n_periods if n_periods > 0 else 0.0
            a = ts + (a - ts) % period
            b = a + left
            if b <= te:
                total = total + piece(a, b, False)
            else:
                total = total + piece(a, te, False) + piece(ts, ts + b - te, False)
        elif not extrapolate:
            a = max(a, ts)
            b = min(b, te)
            total = piece(a, b, False) if a < b else np.zeros(cols.shape[1])
        else:
            total = piece(a, b, True)
        total = _from_columns(np.asarray(total, dtype=np.float64).reshape(1, -1), complex_)
        return np.asarray(total.reshape(tail) * sign)

    @classmethod
    def from_power_basis(cls, pp: Any, bc_type: str = "not-a-knot") -> "BSpline":
        """``BSpline.from_power_basis``: the B-spline form of a ``CubicSpline`` on SciPy's knots
        for ``bc_type``. lekalo's ``CubicSpline`` gives its B-spline form on its own knots
        (``_bspline_form``, by ``make_interp_spline``'s engines); on the same knots its
        coefficients are returned, on a refinement of them lekalo inserts the missing knots
        (``refine_knots``, Boehm)."""
        if not isinstance(pp, cls._power_basis_types):
            raise NotImplementedError(f"Only CubicSpline objects are accepted for now. Got {type(pp)} instead.")
        x, spline = pp.x, pp._bspline_form()
        k = spline.k
        if bc_type == "not-a-knot":
            t = _not_a_knot(x, k)
        elif bc_type in ("natural", "clamped"):
            t = _augknt(x, k)
        elif bc_type == "periodic":
            t = _periodic_knots(x, k)
        else:
            raise TypeError(f"Unknown boundary condition: {bc_type}")
        t0 = spline.t
        if t.shape == t0.shape and np.array_equal(t, t0):
            return cls.construct_fast(t, spline.c, k, pp.extrapolate, pp.axis)
        extra = _knots_to_add(t0, t)
        if extra is None:
            raise NotImplementedError(
                f"lekalo.scipy: from_power_basis with bc_type={bc_type!r} on a spline whose knots are "
                "not a subset of SciPy's knots for it is not available yet"
            )
        n = spline._n()
        complex_ = np.iscomplexobj(spline.c)
        curve = _curve(t0, _real_columns(spline.c, n), k).refine_knots(extra)
        c = _from_columns(curve.control, complex_).reshape((t.shape[0] - k - 1,) + spline.c.shape[1:])
        return cls.construct_fast(t, c, k, pp.extrapolate, pp.axis)

    def insert_knot(self, x: float, m: int = 1) -> "BSpline":
        """The same spline with the knot ``x`` inserted ``m`` times (Boehm, at any
        multiplicity); the coefficients grow by ``m``. A periodic
        spline (``extrapolate="periodic"``) keeps its periodic extension (both FITPACK's
        ``fpinst``, lekalo's ``insert_knot_into``)."""
        t, cc = _insert_tc(self.t, self.c, self.k, x, m, self.extrapolate == "periodic")
        n = self._n()
        cc = cc[: n + m]
        # coefficients beyond the n that the knots use stay at the end, as in SciPy
        cc = np.concatenate([cc, self.c[n:]]) if self.c.shape[0] > n else cc
        return self.construct_fast(t, cc, self.k, self.extrapolate, self.axis)


def _insert_tc(t: np.ndarray, c: np.ndarray, k: int, x: float, m: int, periodic: bool):
    """The knots and coefficients of ``(t, c, k)`` with ``x`` inserted ``m`` times, the
    coefficients padded with zero rows to the knots' length (SciPy's ``insert`` layout): lekalo's
    ``tck_insert`` on the arrays as they are (``insert_knot_into``: Boehm's insertion at any
    multiplicity, or with ``periodic`` the periodic extension kept, both FITPACK's ``fpinst``)."""
    x = float(x)
    if t.ndim != 1 or t.shape[0] < 2 * k + 2:
        raise ValueError(f"Cannot insert a knot: {t.shape[0]} knots for degree {k}, at least 2k + 2 = {2 * k + 2} are needed.")
    if x < t[k] or x > t[-k - 1]:
        raise ValueError(f"Cannot insert a knot at {x}.")
    if m <= 0:
        raise ValueError(f"`m` must be positive, got {m = }.")
    n = t.shape[0] - k - 1
    complex_ = np.iscomplexobj(c)
    cols = _real_columns(c, n)
    if not cols.shape[1]:
        tt, _ = _lekalo.tck_insert(t, np.zeros((n, 1)), k, x, m, periodic)
        return tt, np.zeros((tt.shape[0],) + c.shape[1:], dtype=c.dtype)
    tt, cc = _lekalo.tck_insert(t, cols, k, x, m, periodic)
    return tt, _from_columns(cc, complex_).reshape((tt.shape[0],) + c.shape[1:])


def _knots_to_add(t0: np.ndarray, t: np.ndarray) -> np.ndarray | None:
    """The knots of ``t`` missing from ``t0`` (with multiplicity), or ``None`` when ``t0`` is not
    a sub-multiset of ``t`` or the ends differ."""
    if t0[0] != t[0] or t0[-1] != t[-1]:
        return None
    v0, m0 = np.unique(t0, return_counts=True)
    v, m = np.unique(t, return_counts=True)
    have = dict(zip(v0.tolist(), m0.tolist()))
    if any(have.get(a, 0) > b for a, b in zip(v.tolist(), m.tolist())) or not set(have) <= set(v.tolist()):
        return None
    return np.repeat(v, [b - have.get(a, 0) for a, b in zip(v.tolist(), m.tolist())])


def _empty_values(op, t: np.ndarray, c: np.ndarray, k: int, nu: int):
    """``op`` on values with an empty trailing shape (SciPy's ``n × 0`` arrays): the knots of one
    zero column, and coefficients of the same empty trailing shape."""
    t_new, _ = op(t, np.zeros(c.shape[0]), k, nu)
    return t_new, np.zeros((t_new.shape[0],) + c.shape[1:], dtype=c.dtype)


def _pad_rows(c: np.ndarray, rows: int, fill: np.ndarray | None = None) -> np.ndarray:
    """``c`` with rows appended up to ``rows``: zeros, or copies of ``fill``."""
    extra = rows - c.shape[0]
    if extra <= 0:
        return c
    if fill is None:
        pad = np.zeros((extra,) + c.shape[1:], dtype=c.dtype)
    else:
        pad = np.broadcast_to(fill, (extra,) + c.shape[1:])
    return np.ascontiguousarray(np.concatenate([c, pad]))


def _derivative_tc(t: np.ndarray, c: np.ndarray, k: int, nu: int):
    nu = operator.index(nu)
    if nu < 0:
        return _antiderivative_tc(t, c, k, -nu)
    if nu > k:
        raise ValueError(f"Order of derivative (n = {nu!r}) must be <= order of spline (k = {k!r})")
    if nu == 0:
        return t, c
    if c.ndim > 1 and 0 in c.shape[1:]:
        return _empty_values(_derivative_tc, t, c, k, nu)
    n = t.shape[0] - k - 1
    tail = c.shape[1:]
    complex_ = np.iscomplexobj(c)
    cols = _real_columns(c, n)
    t_new = t[nu:-nu]
    try:
        # one call on the arrays as they are, SciPy's layout out (the rows past n - nu zero)
        cn = _lekalo.tck_derivative(t, cols, k, nu)
        return t_new, _from_columns(cn, complex_).reshape((t_new.shape[0],) + tail)
    except _lekalo.Error:
        pass  # knots lekalo's curve takes apart (B-splines without support, repeated knots)
    curve = _curve(t, cols, k)
    for _ in range(nu):
        curve = curve.derivative()
    if curve.knots.shape[0] != t_new.shape[0]:
        raise ValueError(f"The spline has internal repeated knots and is not differentiable {nu} times")
    cn = _from_columns(curve.control, complex_).reshape((n - nu,) + tail)
    return t_new, _pad_rows(cn, t_new.shape[0])


def _antiderivative_tc(t: np.ndarray, c: np.ndarray, k: int, nu: int):
    nu = operator.index(nu)
    if nu < 0:
        return _derivative_tc(t, c, k, -nu)
    if nu == 0:
        return t, c
    if c.ndim > 1 and 0 in c.shape[1:]:
        return _empty_values(_antiderivative_tc, t, c, k, nu)
    n = t.shape[0] - k - 1
    tail = c.shape[1:]
    complex_ = np.iscomplexobj(c)
    try:
        # one call on the arrays as they are, SciPy's layout out (the knots and coefficients each
        # written once, the rows past n + nu copies of the last); a B-spline without support adds
        # nothing to the running sum, so its coefficient repeats the previous one, as SciPy's
        t_new, cn = _lekalo.tck_antiderivative(t, _real_columns(c, n), k, nu)
        return t_new, _from_columns(cn, complex_).reshape((t_new.shape[0],) + tail)
    except _lekalo.Error:
        pass  # what the library refuses, refused below in SciPy's words
    kept = _kept(t, k)
    if not kept.all():
        # one step on the B-splines with support; those without add nothing to the cumulative
        # sum, so their antiderivative coefficients repeat the previous one (SciPy's layout)
        ctrl = _curve(t, _real_columns(c, n), k).antiderivative(1).control
        full = ctrl[np.r_[0, np.cumsum(kept)]]
        cn = _from_columns(full, complex_).reshape((n + 1,) + tail)
        t1 = np.r_[t[0], t, t[-1]]
        return _antiderivative_tc(t1, _pad_rows(cn, t1.shape[0], cn[-1]), k + 1, nu - 1)
    curve = _curve(t, _real_columns(c, n), k).antiderivative(nu)
    t_new = np.ascontiguousarray(curve.knots)
    cn = _from_columns(curve.control, complex_).reshape((n + nu,) + tail)
    return t_new, _pad_rows(cn, t_new.shape[0], cn[-1])
