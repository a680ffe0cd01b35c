"""``lekalo.scipy``: the spline part of ``scipy.interpolate`` computed by lekalo.

Same names, signatures, defaults, return types, shapes, axis handling and errors as SciPy, so
that ``from lekalo.scipy import BSpline, make_interp_spline`` replaces the SciPy import. This
module converts arguments and arranges arrays only; every number comes from lekalo's kernel
(``BSplineCurve`` evaluation, ``eval_extrapolated``, ``derivative``, ``antiderivative``,
``integrate``, ``make_lsq_spline``, ``fit_least_squares``, ``interpolate``). Where
lekalo's native API deliberately differs from SciPy (it refuses parameters outside the domain,
returns ``t.shape + (dim,)``), this module does what SciPy does.

Available: ``BSpline`` (``__call__``, ``derivative``, ``antiderivative``, ``integrate``,
``construct_fast``, ``basis_element``, ``design_matrix``, ``tck``, periodic extrapolation),
``make_interp_spline`` (not-a-knot, periodic, ``"clamped"``, first-derivative pairs, second
derivatives for cubics, explicit ``t``, ``k = 0 … 5``), ``make_lsq_spline``,
``make_smoothing_spline``, ``splrep`` (FITPACK's knots for ``s > 0``), ``splev``, ``splint``,
``splder``, ``splantider``; in SciPy's ``PPoly`` form ``CubicSpline``, ``CubicHermiteSpline``,
``PchipInterpolator``, ``Akima1DInterpolator``. Not yet: mixed end conditions, ``splrep``
with ``per``/``task``/``xb``/``xe``, ``PPoly.roots``/``solve``, the 2-D FITPACK classes and
``NdBSpline``. The theory is in ``docs/theory/curves.md`` ("Antiderivatives, integrals and
extrapolation") and ``docs/theory/interpolation.md`` (PCHIP and Akima slopes).
"""

from __future__ import annotations

import math
import operator
from typing import Any

import numpy as np

from . import _lekalo

__all__ = [
    "BSpline",
    "make_interp_spline",
    "make_lsq_spline",
    "make_smoothing_spline",
    "splrep",
    "splev",
    "splint",
    "splder",
    "splantider",
    "CubicSpline",
    "CubicHermiteSpline",
    "PchipInterpolator",
    "Akima1DInterpolator",
]


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

    def __init__(self, t: Any, c: Any, k: int, extrapolate: Any = True, axis: int = 0) -> None:
        self.k = operator.index(k)
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
        if len(np.unique(self.t[k : n + 1])) < 2:
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
        """The sparse matrix ``B_{j,k}(x_i)`` (``scipy.sparse.csr_array``), lekalo's basis
        functions at each ``x`` (``basis_functions``); with ``extrapolate``, the end spans'
        basis polynomials continue beyond ``[t[k], t[n]]``."""
        from scipy.sparse import csr_array

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
        elif not extrapolate and ((min(x) < t[k]) or (max(x) > t[n])):
            raise ValueError(f"Out of bounds: x = {x}.")
        spans, rows = _lekalo.basis_functions(t, k, np.clip(x, t[k], t[n]))
        outside = (x < t[k]) | (x > t[n])
        if outside.any():
            # the end spans' basis polynomials at x: the curve whose control points are the
            # unit vectors of R^n, continued beyond the domain
            eye = _lekalo.BSplineCurve(k, t, np.eye(n))
            full = eye.eval_extrapolated(x[outside])
            cols = (spans[outside] - k)[:, None] + np.arange(k + 1)
            rows = np.array(rows, copy=True)
            rows[outside] = np.take_along_axis(full, cols, axis=1)
        indices = (spans - k)[:, None] + np.arange(k + 1)
        indptr = np.arange(0, len(x) * (k + 1) + 1, k + 1)
        return csr_array((rows.ravel(), indices.ravel(), indptr), shape=(len(x), n))

    def _n(self) -> int:
        return self.t.shape[0] - self.k - 1

    def __call__(self, x: Any, nu: int = 0, extrapolate: Any = None) -> np.ndarray:
        """Evaluate the spline or its ``nu``-th derivative at ``x`` (SciPy's shapes: ``x.shape``
        followed by the coefficients' trailing shape, the interpolation axis at ``axis``)."""
        if extrapolate is None:
            extrapolate = self.extrapolate
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
            raise ValueError(f"Cannot do derivative order {nu}.")
        n = self._n()
        m = int(np.prod(self.c.shape[1:], dtype=np.int64))
        complex_ = np.iscomplexobj(self.c)
        out = np.full((x.shape[0], m), np.nan, dtype=self.c.dtype)
        if m == 0 or x.shape[0] == 0:
            return out
        ok = np.isfinite(x)
        if not extrapolate:
            ok &= (x >= self.t[self.k]) & (x <= self.t[n])
        curve = _curve(self.t, _real_columns(self.c, n), self.k)
        vals = curve.eval_extrapolated(x[ok], nu)
        out[ok] = _from_columns(vals, complex_)
        if self.k == 0 and nu == 0 and self.t[n - 1] == self.t[n]:
            # SciPy's span search ends in the last interval even when it is empty: a
            # piecewise constant (make_interp_spline(k=0)) takes its last value from x[-1] on
            out[ok & (x >= self.t[n])] = self.c[n - 1].reshape(-1)
        return out

    def derivative(self, nu: int = 1) -> "BSpline":
        """The derivative spline of order ``nu`` (SciPy's ``splder`` knots ``t[nu:-nu]``, the
        coefficients zero-padded to the knots' length), from lekalo's derivative curve."""
        t, c = _derivative_tc(self.t, self.c, self.k, nu)
        return self.construct_fast(t, c, self.k - nu, extrapolate=self.extrapolate, axis=self.axis)

    def antiderivative(self, nu: int = 1) -> "BSpline":
        """The antiderivative of order ``nu`` (SciPy's ``splantider``: degree ``k + nu``, end
        knots repeated), lekalo's ``antiderivative``. A periodic spline's antiderivative does
        not extrapolate (it is not periodic)."""
        t, c = _antiderivative_tc(self.t, self.c, self.k, nu)
        extrapolate = False if self.extrapolate == "periodic" else self.extrapolate
        return self.construct_fast(t, c, self.k + nu, extrapolate=extrapolate, axis=self.axis)

    def integrate(self, a: float, b: float, extrapolate: Any = None):
        """``∫_a^b S(x) dx`` (SciPy's rules: outside the base interval zero unless
        extrapolating; periodic splines integrate whole periods), lekalo's ``integrate``."""
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
        curve = _curve(self.t, _real_columns(self.c, n), self.k)
        ts, te = self.t[self.k], self.t[n]

        def piece(lo: float, hi: float, ext: bool) -> np.ndarray:
            return curve.integrate(float(lo), float(hi), ext)

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
            total = piece(a, b, False) if a < b else np.zeros(curve.dim)
        else:
            total = piece(a, b, True)
        total = _from_columns(np.asarray(total, dtype=np.float64).reshape(1, -1), complex_)
        return np.asarray(total.reshape(tail) * sign)

    def insert_knot(self, x: float, m: int = 1) -> "BSpline":
        """The same spline with the knot ``x`` inserted ``m`` times (Boehm), lekalo's
        ``insert_knot``; the coefficients grow by ``m``."""
        x = float(x)
        if x < self.t[self.k] or x > self.t[-self.k - 1]:
            raise ValueError(f"Cannot insert a knot at {x}.")
        if m <= 0:
            raise ValueError(f"`m` must be positive, got {m = }.")
        if self.extrapolate == "periodic":
            raise NotImplementedError("lekalo.scipy: periodic knot insertion is not available yet")
        n = self._n()
        complex_ = np.iscomplexobj(self.c)
        curve = _curve(self.t, _real_columns(self.c, n), self.k).insert_knot(x, m)
        cc = _from_columns(curve.control, complex_).reshape((n + m,) + self.c.shape[1:])
        return self.construct_fast(np.ascontiguousarray(curve.knots), cc, self.k, self.extrapolate, self.axis)


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
    n = t.shape[0] - k - 1
    tail = c.shape[1:]
    complex_ = np.iscomplexobj(c)
    curve = _curve(t, _real_columns(c, n), k)
    for _ in range(nu):
        curve = curve.derivative()
    t_new = t[nu:-nu] if nu > 0 else t
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
    n = t.shape[0] - k - 1
    tail = c.shape[1:]
    complex_ = np.iscomplexobj(c)
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


# -- interpolation -------------------------------------------------------------------------


def _not_a_knot(x: np.ndarray, k: int) -> np.ndarray:
    """SciPy's not-a-knot knots (de Boor XIII(12)): data sites for odd ``k`` and mid-points for
    even ``k``, without the ``(k+1)//2`` (``k//2``) first and last, end knots of multiplicity
    ``k + 1`` (FITPACK's choice for ``s = 0``, too)."""
    if k % 2 == 1:
        k2 = (k + 1) // 2
        t = x.copy()
    else:
        k2 = k // 2
        t = (x[1:] + x[:-1]) / 2
    t = t[k2:-k2]
    return np.r_[(x[0],) * (k + 1), t, (x[-1],) * (k + 1)]


def _augknt(x: np.ndarray, k: int) -> np.ndarray:
    """The data sites with end knots of multiplicity ``k + 1``."""
    return np.r_[(x[0],) * k, x, (x[-1],) * k]


def _convert_string_aliases(deriv: Any, target_shape: tuple) -> Any:
    if isinstance(deriv, str):
        if deriv == "clamped":
            deriv = [(1, np.zeros(target_shape))]
        elif deriv == "natural":
            deriv = [(2, np.zeros(target_shape))]
        else:
            raise ValueError(f"Unknown boundary condition : {deriv}")
    return deriv


def _process_deriv_spec(deriv: Any):
    if deriv is not None:
        try:
            ords, vals = zip(*deriv)
        except TypeError as e:
            msg = "Derivatives, `bc_type`, should be specified as a pair of iterables of pairs of (order, value)."
            raise ValueError(msg) from e
    else:
        ords, vals = [], []
    return np.atleast_1d(ords, vals)


def make_interp_spline(
    x: Any, y: Any, k: int = 3, t: Any = None, bc_type: Any = None, axis: int = 0, check_finite: bool = True
) -> BSpline:
    """The interpolating B-spline of degree ``k`` (``scipy.interpolate.make_interp_spline``):
    SciPy's knots and boundary conditions, solved by lekalo (``make_lsq_spline`` on as many
    coefficients as conditions, a square banded QR; ``fit_least_squares`` with end
    derivatives; ``interpolate`` with second derivatives at the ends)."""
    if bc_type is None or bc_type == "not-a-knot" or bc_type == "periodic":
        deriv_l, deriv_r = None, None
    elif isinstance(bc_type, str):
        deriv_l, deriv_r = bc_type, bc_type
    else:
        try:
            deriv_l, deriv_r = bc_type
        except TypeError as e:
            raise ValueError(f"Unknown boundary condition: {bc_type}") from e
    y = np.asarray(y)
    axis = _normalize_axis(axis, y.ndim)
    x = _as_float_array(x, check_finite)
    y = _as_float_array(y, check_finite)
    y = np.moveaxis(y, axis, 0)
    if bc_type == "periodic" and not np.allclose(y[0], y[-1], atol=1e-15):
        raise ValueError("First and last points does not match while periodic case expected")
    if x.size != y.shape[0]:
        raise ValueError(f"Shapes of x {x.shape} and y {y.shape} are incompatible")
    if np.any(x[1:] == x[:-1]):
        raise ValueError("Expect x to not have duplicates")
    if x.ndim != 1 or np.any(x[1:] < x[:-1]):
        raise ValueError("Expect x to be a 1D strictly increasing sequence.")
    if k == 0:
        if any(v is not None for v in (t, deriv_l, deriv_r)):
            raise ValueError("Too much info for k=0: t and bc_type can only be None.")
        t = np.r_[x, x[-1]]
        c = np.ascontiguousarray(y, dtype=_get_dtype(y.dtype))
        return BSpline.construct_fast(t, c, k, axis=axis)
    if k == 1 and t is None:
        if not (deriv_l is None and deriv_r is None):
            raise ValueError("Too much info for k=1: bc_type can only be None.")
        t = np.r_[x[0], x, x[-1]]
        c = np.ascontiguousarray(y, dtype=_get_dtype(y.dtype))
        return BSpline.construct_fast(t, c, k, axis=axis)
    k = operator.index(k)
    if bc_type == "periodic" and t is not None:
        raise NotImplementedError(
            "For periodic case t is constructed automatically and can not be passed manually"
        )
    if bc_type == "periodic":
        return _make_periodic_spline(x, y, k, axis)
    if t is None:
        t = _not_a_knot(x, k) if deriv_l is None and deriv_r is None else _augknt(x, k)
    t = _as_float_array(t, check_finite)
    if k < 0:
        raise ValueError("Expect non-negative k.")
    if t.ndim != 1 or np.any(t[1:] < t[:-1]):
        raise ValueError("Expect t to be a 1-D sorted array_like.")
    if t.size < x.size + k + 1:
        raise ValueError(f"Got {t.size} knots, need at least {x.size + k + 1}.")
    if (x[0] < t[k]) or (x[-1] > t[-k]):
        raise ValueError(f"Out of bounds w/ x = {x}.")
    deriv_l = _convert_string_aliases(deriv_l, y.shape[1:])
    deriv_l_ords, deriv_l_vals = _process_deriv_spec(deriv_l)
    nleft = deriv_l_ords.shape[0]
    deriv_r = _convert_string_aliases(deriv_r, y.shape[1:])
    deriv_r_ords, deriv_r_vals = _process_deriv_spec(deriv_r)
    nright = deriv_r_ords.shape[0]
    if not all(0 <= i <= k for i in deriv_l_ords):
        raise ValueError(f"Bad boundary conditions at {t[0]}.")
    if not all(0 <= i <= k for i in deriv_r_ords):
        raise ValueError(f"Bad boundary conditions at {t[-1]}.")
    n = x.size
    nt = t.size - k - 1
    if nt - n != nleft + nright:
        raise ValueError(
            f"The number of derivatives at boundaries does not match: expected {nt - n}, got {nleft}+{nright}"
        )
    tail = y.shape[1:]
    if y.size == 0:
        c = np.zeros((nt,) + tail, dtype=float)
        return BSpline.construct_fast(t, c, k, axis=axis)
    complex_ = np.iscomplexobj(y)
    yy = _real_columns(y, n)
    if nleft == 0 and nright == 0:
        ctrl = _lekalo.make_lsq_spline(x, yy, t, k).control
    elif (
        nleft == 1
        and nright == 1
        and deriv_l_ords[0] == 1
        and deriv_r_ords[0] == 1
        and t[0] == t[k]
        and t[-1] == t[-k - 1]
        and x[0] == t[0]
        and x[-1] == t[-1]
    ):
        d0 = _real_columns(np.asarray(deriv_l_vals[0], dtype=y.dtype).reshape((1,) + tail), 1)[0]
        d1 = _real_columns(np.asarray(deriv_r_vals[0], dtype=y.dtype).reshape((1,) + tail), 1)[0]
        curve, _ = _lekalo.fit_least_squares(yy, x, t, k, clamp_ends=True, d_start=d0, d_end=d1)
        ctrl = curve.control
    elif (
        k == 3
        and nleft == 1
        and nright == 1
        and deriv_l_ords[0] == 2
        and deriv_r_ords[0] == 2
        and np.array_equal(t, _augknt(x, k))
    ):
        d0 = _real_columns(np.asarray(deriv_l_vals[0], dtype=y.dtype).reshape((1,) + tail), 1)[0]
        d1 = _real_columns(np.asarray(deriv_r_vals[0], dtype=y.dtype).reshape((1,) + tail), 1)[0]
        curve = _lekalo.interpolate(yy, 3, params=x, knots="at-params", end="second", d_start=d0, d_end=d1)
        if not np.array_equal(curve.knots, t):
            raise NotImplementedError("lekalo.scipy: second-derivative ends on these knots are not available yet")
        ctrl = curve.control
    else:
        raise NotImplementedError(
            f"lekalo.scipy: bc_type={bc_type!r} with k={k} is not available yet "
            "(supported: not-a-knot, clamped/first derivatives, natural cubics)"
        )
    c = _from_columns(ctrl, complex_).reshape((nt,) + tail)
    return BSpline.construct_fast(t, c, k, axis=axis)


def _make_periodic_spline(x: np.ndarray, y: np.ndarray, k: int, axis: int) -> BSpline:
    """The periodic interpolant on SciPy's periodic knots (interior knots at the data for odd
    ``k``, at the mid-points for even ``k``, continued by the period), solved by lekalo's
    ``fit_periodic`` with ``s = 0`` on those interior knots (its cyclic banded system)."""
    n = x.shape[0]
    xc = x.copy()
    if k % 2 == 0:
        xc[1:-1] -= np.diff(x)[:-1] / 2
    tail = y.shape[1:]
    nt = n + k - 1
    if y.size == 0:
        t = _periodic_knots(x, k)
        return BSpline.construct_fast(t, np.zeros((nt,) + tail), k, extrapolate="periodic", axis=axis)
    complex_ = np.iscomplexobj(y)
    curve, _ = _lekalo.fit_periodic(x, _real_columns(y, n), k=k, s=0.0, t=xc[1:-1])
    t = np.ascontiguousarray(curve.knots)
    c = _from_columns(curve.control, complex_).reshape((nt,) + tail)
    return BSpline.construct_fast(t, c, k, extrapolate="periodic", axis=axis)


def _periodic_knots(x: np.ndarray, k: int) -> np.ndarray:
    """SciPy's periodic knot vector (``_periodic_knots``)."""
    xc = np.copy(x)
    n = len(xc)
    if k % 2 == 0:
        dx = np.diff(xc)
        xc[1:-1] -= dx[:-1] / 2
    dx = np.diff(xc)
    t = np.zeros(n + 2 * k)
    t[k:-k] = xc
    for i in range(0, k):
        t[k - i - 1] = t[k - i] - dx[-(i % (n - 1)) - 1]
        t[-k + i] = t[-k + i - 1] + dx[i % (n - 1)]
    return t


def make_lsq_spline(
    x: Any, y: Any, t: Any, k: int = 3, w: Any = None, axis: int = 0, check_finite: bool = True, *, method: str = "qr"
) -> BSpline:
    """The weighted least-squares spline on the knots ``t`` (``scipy.interpolate.make_lsq_spline``),
    lekalo's banded-QR ``make_lsq_spline``."""
    x = _as_float_array(x, check_finite)
    y = _as_float_array(y, check_finite)
    t = _as_float_array(t, check_finite)
    w = np.ones_like(x) if w is None else _as_float_array(w, check_finite)
    k = operator.index(k)
    axis = _normalize_axis(axis, y.ndim)
    y = np.moveaxis(y, axis, 0)
    if x.ndim != 1:
        raise ValueError("Expect x to be a 1-D sequence.")
    if x.shape[0] < k + 1:
        raise ValueError("Need more x points.")
    if k < 0:
        raise ValueError("Expect non-negative k.")
    if t.ndim != 1 or np.any(t[1:] - t[:-1] < 0):
        raise ValueError("Expect t to be a 1D strictly increasing sequence.")
    if x.size != y.shape[0]:
        raise ValueError(f"Shapes of x {x.shape} and y {y.shape} are incompatible")
    if k > 0 and np.any((x < t[k]) | (x > t[-k])):
        raise ValueError(f"Out of bounds w/ x = {x}.")
    if x.size != w.size:
        raise ValueError(f"Shapes of x {x.shape} and w {w.shape} are incompatible")
    if method not in ("qr", "norm-eq"):
        raise ValueError(f"method={method} is not understood.")
    if np.any(x[1:] - x[:-1] < 0):
        raise ValueError("Expect x to be a sorted 1D sequence.")
    n = t.size - k - 1
    tail = y.shape[1:]
    complex_ = np.iscomplexobj(y)
    ctrl = _lekalo.make_lsq_spline(x, _real_columns(y, x.size), t, k, w).control
    c = _from_columns(ctrl, complex_).reshape((n,) + tail)
    return BSpline.construct_fast(t, c, k, axis=axis)


def make_smoothing_spline(x: Any, y: Any, w: Any = None, lam: Any = None, *, axis: int = 0) -> BSpline:
    """``scipy.interpolate.make_smoothing_spline``: the penalised cubic smoothing spline with
    knots at the data, ``lam`` given or chosen by generalised cross-validation, lekalo's
    ``make_smoothing_spline`` (with ``lam`` the same spline to rounding; the GCV ``lam`` is
    found by lekalo's own minimiser, so it agrees to the minimiser's tolerance)."""
    x = np.ascontiguousarray(x, dtype=float)
    y = np.asarray(y)
    axis = _normalize_axis(axis, y.ndim)
    y = np.moveaxis(np.ascontiguousarray(y, dtype=float), axis, 0)
    if any(x[1:] - x[:-1] <= 0):
        raise ValueError("``x`` should be an ascending array")
    if x.ndim != 1 or x.shape[0] != y.shape[0]:
        raise ValueError(f"``x`` should be 1D and {x.shape = } == {y.shape = }")
    if x.shape[0] < 5:
        raise ValueError("``x`` and ``y`` length must be at least 5")
    tail = y.shape[1:]
    n = x.shape[0]
    curve = _lekalo.make_smoothing_spline(x, _real_columns(y, n), w, lam)
    c = np.ascontiguousarray(curve.control).reshape((-1,) + tail)
    return BSpline.construct_fast(np.ascontiguousarray(curve.knots), c, 3, axis=axis)


# -- the FITPACK-style functions -----------------------------------------------------------


def splrep(
    x: Any, y: Any, w: Any = None, xb: Any = None, xe: Any = None, k: int = 3, task: int = 0,
    s: Any = None, t: Any = None, full_output: int = 0, per: int = 0, quiet: int = 1,
):
    """``scipy.interpolate.splrep`` for interpolation (``s = 0``, the default without weights;
    FITPACK's knots are SciPy's not-a-knot ones) and for least squares on given interior knots
    ``t``. Returns ``(t, c, k)`` with ``c`` zero-padded to ``len(t)``, as FITPACK."""
    x = np.atleast_1d(np.asarray(x, dtype=np.float64))
    y = np.atleast_1d(np.asarray(y, dtype=np.float64))
    m = len(x)
    if s is None:
        s = 0.0 if w is None else m - np.sqrt(2 * m)
    if not (1 <= k <= 5):
        raise TypeError(f"1 <= k= {k} <=5 must hold")
    if task != 0 or (xb is not None and xb != x[0]) or (xe is not None and xe != x[-1]):
        raise NotImplementedError("lekalo.scipy.splrep: task and xb/xe are not available yet")
    if y.ndim != 1 or len(y) != m:
        raise TypeError("Lengths of the first three arguments (x,y,w) must be equal")
    if m <= k:
        raise TypeError("m > k must hold")
    if per:
        # lekalo's periodic fit is splrep(per=1)'s: the last point closes the period, FITPACK's
        # knots and smoothing condition, or least squares on the interior knots t
        curve, _ = _lekalo.fit_periodic(
            x, y, w=w, k=k, s=float(s), t=None if t is None else np.asarray(t, dtype=np.float64)
        )
        spl = BSpline.construct_fast(np.ascontiguousarray(curve.knots), np.ascontiguousarray(curve.control[:, 0]), k)
    elif t is not None:
        tt = np.r_[(x[0],) * (k + 1), np.asarray(t, dtype=np.float64), (x[-1],) * (k + 1)]
        spl = make_lsq_spline(x, y, tt, k, w=w)
    elif s == 0 and w is None:
        spl = make_interp_spline(x, y, k=k)
    else:
        # FITPACK's knot placement and smoothing condition, lekalo's make_splrep: the same
        # knots; the coefficients meet FITPACK's tolerance |fp - s| <= 0.001 s, not its bits
        curve = _lekalo.make_splrep(x, y, w=w, k=k, s=float(s))
        spl = BSpline.construct_fast(np.ascontiguousarray(curve.knots), np.ascontiguousarray(curve.control[:, 0]), k)
    tck = (spl.t, _pad_rows(spl.c, spl.t.shape[0]), spl.k)
    if full_output:
        return tck, 0.0, 0, ""
    return tck


def splev(x: Any, tck: Any, der: int = 0, ext: int = 0):
    """``scipy.interpolate.splev``: the spline (or its ``der``-th derivative) at ``x``;
    ``ext`` 0 extrapolates, 1 gives zero, 2 raises ``ValueError``, 3 gives the boundary value
    outside the base interval."""
    if isinstance(tck, BSpline):
        if tck.c.ndim > 1:
            raise ValueError(
                "Calling splev() with BSpline objects with c.ndim > 1 is not allowed. "
                "Use BSpline.__call__(x) instead."
            )
        try:
            extrapolate = {0: True}[ext]
        except KeyError as e:
            raise ValueError(f"Extrapolation mode {ext} is not supported by BSpline.") from e
        return tck(x, der, extrapolate=extrapolate)
    t, c, k = tck
    try:
        c[0][0]
        parametric = True
    except Exception:
        parametric = False
    if parametric:
        return list(map(lambda c, x=x, t=t, k=k: splev(x, [t, c, k], der, ext), c))
    if not (0 <= der <= k):
        raise ValueError(f"0<=der={der}<=k={k} must hold")
    if ext not in (0, 1, 2, 3):
        raise ValueError(f"ext = {ext} not in (0, 1, 2, 3) ")
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    x = np.asarray(x)
    shape = x.shape
    x = np.atleast_1d(x).ravel().astype(np.float64)
    n = t.shape[0] - k - 1
    lo, hi = t[k], t[n]
    outside = (x < lo) | (x > hi)
    if ext == 2 and outside.any():
        raise ValueError("Error code returned by splev: 1")
    # FITPACK clips to the boundary value for ext=3 only for the function itself; its
    # derivatives (splder) extrapolate
    xx = np.clip(x, lo, hi) if ext == 3 and der == 0 else x
    y = BSpline.construct_fast(t, c, k)._evaluate(xx, der, True)[:, 0]
    if ext == 1:
        y[outside] = 0.0
    return y.reshape(shape)


def splint(a: float, b: float, tck: Any, full_output: int = 0):
    """``scipy.interpolate.splint``: ``∫_a^b`` of the spline over the base interval (limits
    clipped to it, as FITPACK), lekalo's ``integrate``."""
    if isinstance(tck, BSpline):
        if tck.c.ndim > 1:
            raise ValueError(
                "Calling splint() with BSpline objects with c.ndim > 1 is not allowed. "
                "Use BSpline.integrate() instead."
            )
        if full_output != 0:
            raise ValueError("full_output = True is not supported with BSpline objects.")
        return tck.integrate(a, b, extrapolate=False)
    t, c, k = tck
    try:
        c[0][0]
        return list(map(lambda c, a=a, b=b, t=t, k=k: splint(a, b, [t, c, k]), c))
    except Exception:
        pass
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    val = BSpline.construct_fast(t, c, k, extrapolate=False).integrate(a, b, extrapolate=False)
    val = float(val)
    if full_output:
        return val, None
    return val


def splder(tck: Any, n: int = 1):
    """``scipy.interpolate.splder``: the derivative spline, lekalo's derivative curve."""
    if isinstance(tck, BSpline):
        return tck.derivative(n)
    t, c, k = tck
    if n < 0:
        return splantider(tck, -n)
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    if n > k:
        raise ValueError(f"Order of derivative (n = {n!r}) must be <= order of spline (k = {k!r})")
    t2, c2 = _derivative_tc(t, c, k, n)
    return t2, c2, k - n


def splantider(tck: Any, n: int = 1):
    """``scipy.interpolate.splantider``: the antiderivative spline, lekalo's antiderivative."""
    if isinstance(tck, BSpline):
        return tck.antiderivative(n)
    t, c, k = tck
    if n < 0:
        return splder(tck, -n)
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    t2, c2 = _antiderivative_tc(t, c, k, n)
    return t2, c2, k + n


# -- piecewise cubics in SciPy's PPoly form -------------------------------------------------


class _SplinePPoly:
    """SciPy's ``PPoly`` interface (``x``, ``c``, ``axis``, ``extrapolate``, ``__call__``,
    ``derivative``, ``antiderivative``, ``integrate``) over a lekalo B-spline that is the same
    piecewise polynomial: evaluation, derivatives and integrals are lekalo's, and ``c`` (local
    power coefficients, highest degree first) is read off lekalo's derivatives at the
    breakpoints, ``c[k - m, i] = S^{(m)}(x_i+) / m!``."""

    def __init__(self, spline: BSpline, x: np.ndarray, extrapolate: Any, axis: int, degree: int = 3) -> None:
        self._spline = spline
        self._degree = degree
        self.x = x
        self.extrapolate = extrapolate
        self.axis = axis
        self._c = None

    @property
    def c(self) -> np.ndarray:
        if self._c is None:
            s = self._spline
            k = self._degree
            xs = self.x[:-1]
            rows = [
                BSpline.construct_fast(s.t, s.c, s.k)._evaluate(xs, m, True).reshape((xs.size,) + s.c.shape[1:])
                / math.factorial(m)
                for m in range(k, -1, -1)
            ]
            self._c = np.ascontiguousarray(np.stack(rows))
        return self._c

    def __call__(self, x: Any, nu: int = 0, extrapolate: Any = None) -> np.ndarray:
        if extrapolate is None:
            extrapolate = self.extrapolate
        if nu < 0:
            return self.antiderivative(-nu)(x, 0, extrapolate)
        return self._spline(x, nu, extrapolate)

    def derivative(self, nu: int = 1) -> "_SplinePPoly":
        if nu < 0:
            return self.antiderivative(-nu)
        s = self._spline
        if nu > s.k:
            z = BSpline.construct_fast(np.r_[self.x[0], self.x[-1]], np.zeros((1,) + s.c.shape[1:]), 0, axis=s.axis)
            return _SplinePPoly(z, self.x, self.extrapolate, self.axis, max(self._degree - nu, 0))
        return _SplinePPoly(s.derivative(nu), self.x, self.extrapolate, self.axis, self._degree - nu)

    def antiderivative(self, nu: int = 1) -> "_SplinePPoly":
        if nu < 0:
            return self.derivative(-nu)
        return _SplinePPoly(self._spline.antiderivative(nu), self.x, self.extrapolate, self.axis, self._degree + nu)

    def integrate(self, a: float, b: float, extrapolate: Any = None) -> np.ndarray:
        if extrapolate is None:
            extrapolate = self.extrapolate
        if extrapolate is False or extrapolate == 0:
            lo, hi = self.x[0], self.x[-1]
            if min(a, b) < lo or max(a, b) > hi:
                return np.full(self._spline.c.shape[1:], np.nan)
        return self._spline.integrate(a, b, extrapolate=bool(extrapolate) if extrapolate != "periodic" else extrapolate)


def _prepare_input(x: Any, y: Any, axis: int):
    x = _as_float_array(x, True)
    y = np.asarray(y)
    if np.issubdtype(y.dtype, np.complexfloating):
        dtype = complex
    else:
        dtype = float
    y = y.astype(dtype, copy=False)
    axis = axis % y.ndim
    if x.ndim != 1:
        raise ValueError("`x` must be 1-dimensional.")
    if x.shape[0] < 2:
        raise ValueError("`x` must contain at least 2 elements.")
    if x.shape[0] != y.shape[axis]:
        raise ValueError(f"The length of `y` along `axis`={axis} doesn't match the length of `x`")
    if not np.all(np.isfinite(x)):
        raise ValueError("`x` must contain only finite values.")
    if not np.all(np.isfinite(y)):
        raise ValueError("`y` must contain only finite values.")
    dx = np.diff(x)
    if np.any(dx <= 0):
        raise ValueError("`x` must be strictly increasing sequence.")
    y = np.moveaxis(y, axis, 0)
    return x, dx, y, axis


class CubicSpline(_SplinePPoly):
    """``scipy.interpolate.CubicSpline``: the C² cubic through the data with SciPy's end
    conditions (``"not-a-knot"``, ``"clamped"``, ``"natural"``, ``((order, value), (order,
    value))`` with equal orders), the solve by lekalo (:func:`make_interp_spline`'s engines);
    the result has SciPy's ``PPoly`` interface."""

    def __init__(self, x: Any, y: Any, axis: int = 0, bc_type: Any = "not-a-knot", extrapolate: Any = None) -> None:
        x, dx, y, axis = _prepare_input(x, y, axis)
        n = x.shape[0]
        if extrapolate is None:
            extrapolate = "periodic" if bc_type == "periodic" else True
        if bc_type == "periodic":
            if not np.allclose(y[0], y[-1], rtol=1e-15, atol=1e-15):
                raise ValueError(
                    f"The first and last `y` point along axis {axis} must be identical (within "
                    "machine precision) when bc_type='periodic'."
                )
            if n < 4:
                raise NotImplementedError("lekalo.scipy: periodic CubicSpline needs 4 points or more")
            spline = make_interp_spline(x, y, k=3, bc_type="periodic", axis=0)
            spline = BSpline.construct_fast(spline.t, spline.c, 3, axis=axis)
            super().__init__(spline, x, extrapolate, axis)
            return
        if isinstance(bc_type, str):
            if bc_type not in ("not-a-knot", "clamped", "natural"):
                raise ValueError(f"bc_type={bc_type} is not allowed.")
            left = right = bc_type
        else:
            try:
                left, right = bc_type
            except (TypeError, ValueError) as e:
                raise ValueError("`bc_type` must contain 2 elements to specify start and end conditions.") from e
        tail = y.shape[1:]

        def side(bc: Any):
            if bc == "not-a-knot":
                return None
            if isinstance(bc, str):
                return bc
            order, value = bc
            if order not in (1, 2):
                raise ValueError("The specified derivative order must be 1 or 2.")
            value = np.asarray(value)
            if value.shape != tail:
                raise ValueError(f"`deriv_value` shape {value.shape} is not the expected one {tail}.")
            return [(order, value)]

        dl, dr = side(left), side(right)
        if dl is None and dr is None:
            kk = 3 if n >= 4 else n - 1
            spline = make_interp_spline(x, y, k=kk, axis=0)
        elif dl is None or dr is None:
            raise NotImplementedError("lekalo.scipy: not-a-knot at one end only is not available yet")
        else:
            spline = make_interp_spline(x, y, k=3, bc_type=(dl, dr), axis=0)
        spline = BSpline.construct_fast(spline.t, spline.c, spline.k, axis=axis)
        super().__init__(spline, x, extrapolate, axis)


class CubicHermiteSpline(_SplinePPoly):
    """``scipy.interpolate.CubicHermiteSpline``: the cubic with values ``y`` and slopes
    ``dydx`` at ``x``, lekalo's ``CubicHermite`` written as a B-spline (double knots)."""

    def __init__(self, x: Any, y: Any, dydx: Any, axis: int = 0, extrapolate: Any = None) -> None:
        if extrapolate is None:
            extrapolate = True
        x, dx, y, axis = _prepare_input(x, y, axis)
        dydx = np.moveaxis(np.asarray(dydx), axis, 0)
        if dydx.shape != y.shape:
            raise ValueError("The shapes of `y` and `dydx` must be identical.")
        if not np.all(np.isfinite(dydx)):
            raise ValueError("`dydx` must contain only finite values.")
        super().__init__(_hermite_spline(x, y, dydx, axis), x, extrapolate, axis)


def _hermite_spline(x: np.ndarray, y: np.ndarray, dydx: np.ndarray, axis: int) -> BSpline:
    n = x.shape[0]
    tail = y.shape[1:]
    complex_ = np.iscomplexobj(y) or np.iscomplexobj(dydx)
    dt = np.complex128 if complex_ else np.float64
    yy = _real_columns(np.asarray(y, dtype=dt), n)
    dd = _real_columns(np.asarray(dydx, dtype=dt), n)
    if yy.shape[1] == 0:
        t = np.r_[x[0], x[0], np.repeat(x, 2), x[-1], x[-1]]
        return BSpline.construct_fast(t, np.zeros((2 * n,) + tail, dtype=dt), 3, axis=axis)
    curve = _lekalo.CubicHermite(x, yy, dd).to_bspline()
    c = _from_columns(np.ascontiguousarray(curve.control), complex_).reshape((-1,) + tail)
    return BSpline.construct_fast(np.ascontiguousarray(curve.knots), c, 3, axis=axis)


class PchipInterpolator(_SplinePPoly):
    """``scipy.interpolate.PchipInterpolator``: the monotonicity-preserving piecewise cubic,
    with lekalo's ``pchip_slopes`` (Fritsch–Butland, Moler's ends) and ``CubicHermite``."""

    def __init__(self, x: Any, y: Any, axis: int = 0, extrapolate: Any = None) -> None:
        if extrapolate is None:
            extrapolate = True
        x, _, y, axis = _prepare_input(x, y, axis)
        if np.iscomplexobj(y):
            msg = (
                "`PchipInterpolator` only works with real values for `y`. If you are trying to "
                "use the real components of the passed array, use `np.real` on the array before "
                "passing to `PchipInterpolator`."
            )
            raise ValueError(msg)
        n = x.shape[0]
        yy = _real_columns(y, n)
        if yy.shape[1] == 0:
            dydx = np.zeros_like(y)
        else:
            dydx = _lekalo.pchip_slopes(x, yy).reshape(y.shape)
        super().__init__(_hermite_spline(x, y, dydx, axis), x, extrapolate, axis)


class Akima1DInterpolator(_SplinePPoly):
    """``scipy.interpolate.Akima1DInterpolator``: the local Akima (``method="akima"``) or
    modified Akima (``"makima"``) piecewise cubic, with lekalo's ``akima_slopes`` and
    ``CubicHermite``. Extrapolation is off by default, as in SciPy."""

    def __init__(self, x: Any, y: Any, axis: int = 0, *, method: str = "akima", extrapolate: Any = None) -> None:
        if method not in {"akima", "makima"}:
            raise NotImplementedError(f"`method`={method} is unsupported.")
        x, _, y, axis = _prepare_input(x, y, axis)
        if np.iscomplexobj(y):
            msg = (
                "`Akima1DInterpolator` only works with real values for `y`. If you are trying to "
                "use the real components of the passed array, use `np.real` on the array before "
                "passing to `Akima1DInterpolator`."
            )
            raise ValueError(msg)
        extrapolate = False if extrapolate is None else extrapolate
        n = x.shape[0]
        yy = _real_columns(y, n)
        if yy.shape[1] == 0:
            dydx = np.zeros_like(y)
        else:
            dydx = _lekalo.akima_slopes(x, yy, method).reshape(y.shape)
        super().__init__(_hermite_spline(x, y, dydx, axis), x, extrapolate, axis)
