"""SciPy's piecewise polynomials in ``lekalo.scipy``: ``PPoly`` (local power basis) and
``BPoly`` (Bernstein basis), evaluated by lekalo on SciPy's arrays in place, their calculus on
lekalo's pp-form or B-spline form (the piecewise cubics in ``PPoly`` form are in ``_cubic.py``);
this module only rearranges arrays."""

from __future__ import annotations

import math
import operator
from typing import Any

import numpy as np

from .. import _lekalo
from ._bspline import BSpline, _curve, _from_columns, _get_dtype, _one_number, _real_columns


def _pieces(x: np.ndarray, c: np.ndarray):
    """The breakpoints and the coefficients of the pieces of nonzero length (SciPy accepts
    repeated breakpoints, whose empty pieces are never evaluated; lekalo's are strictly
    monotonic)."""
    keep = np.diff(x) != 0
    if keep.all():
        return x, c
    return x[np.r_[True, keep]], c[:, keep]


def _columns(c: np.ndarray) -> tuple[np.ndarray, bool]:
    """``c`` of shape ``(order, pieces) + tail`` as ``(order, pieces, columns)`` float64 (a
    complex value is two columns, its real and imaginary parts)."""
    complex_ = np.iscomplexobj(c)
    cc = np.ascontiguousarray(c.reshape(c.shape[0], c.shape[1], -1))
    if complex_:
        cc = np.ascontiguousarray(cc.view(np.float64))
    return cc, complex_


def _spline_derivative(s: BSpline, nu: int) -> BSpline:
    """lekalo's derivative of the spline on lekalo's knots (a piecewise polynomial may jump at
    its breakpoints, which SciPy's ``splder`` layout refuses)."""
    n = s._n()
    complex_ = np.iscomplexobj(s.c)
    cols = _real_columns(s.c, n)
    if cols.shape[1] == 0:
        t = s.t[nu:-nu]
        return BSpline.construct_fast(t, np.zeros((t.size - s.k + nu - 1,) + s.c.shape[1:]), s.k - nu, s.extrapolate, s.axis)
    curve = _curve(s.t, cols, s.k)
    for _ in range(nu):
        curve = curve.derivative()
    control = np.asarray(curve.control)
    c = _from_columns(control, complex_).reshape((control.shape[0],) + s.c.shape[1:])
    return BSpline.construct_fast(np.asarray(curve.knots), c, s.k - nu, s.extrapolate, s.axis)


def _points_and_order(x: Any, nu: Any) -> tuple[np.ndarray, int]:
    """The points as an array (an object array as float64) and the derivative order as a
    non-negative int, with SciPy's errors: the argument checks of both call paths."""
    x = np.asarray(x)
    if x.dtype == object:
        x = x.astype(np.float64)
    nu = operator.index(nu)
    if nu < 0:
        raise ValueError("Order of derivative cannot be negative")
    return x, nu


def _points_at_axis(out: np.ndarray, ndim: int, axis: int) -> np.ndarray:
    """Values of shape ``x.shape + tail`` (``ndim`` the dimension of ``x``) with the point axes
    moved to ``axis`` of the tail, SciPy's layout."""
    if axis == 0:
        return out
    axes = list(range(out.ndim))
    return out.transpose(axes[ndim : ndim + axis] + axes[:ndim] + axes[ndim + axis :])


# The least batch for which a piecewise polynomial made from a spline reads its coefficients
# (O(pieces), once) to evaluate them in place, Horner's rule on SciPy's layout, about twice as
# fast a point as the B-spline evaluator's basis kernel (docs/moving-from-scipy.md). The two
# agree to rounding (a few 1e-16 relative), not bit for bit.
_READ_COEFFICIENTS_MIN = 4096


class _PPolyBase:
    """What ``PPoly`` and ``BPoly`` share, as in SciPy: the attributes ``c`` (coefficients,
    shape ``(order, pieces) + tail``), ``x`` (breakpoints), ``extrapolate`` and ``axis``; a
    lekalo B-spline that is the same piecewise polynomial does the evaluation, the derivatives,
    the antiderivatives and the integrals (SciPy's conventions: right-continuous pieces, the
    end pieces continued when extrapolating, ``"periodic"`` wrapping into ``[x[0], x[-1]]``).
    Objects made by lekalo (derivatives, conversions) read their coefficients off the B-spline
    when ``c`` is first asked for."""

    def __init__(self, c: Any, x: Any, extrapolate: Any = None, axis: int = 0) -> None:
        c = np.asarray(c)
        x = np.ascontiguousarray(x, dtype=np.float64)
        if extrapolate is None:
            extrapolate = True
        elif extrapolate != "periodic":
            extrapolate = bool(extrapolate)
        if c.ndim < 2:
            raise ValueError("Coefficients array must be at least 2-dimensional.")
        if not (0 <= axis < c.ndim - 1):
            raise ValueError(f"axis={axis} must be between 0 and {c.ndim - 1}")
        if axis:
            # the interpolation axes first (twice the identity for axis 0)
            c = np.moveaxis(c, axis + 1, 0)
            c = np.moveaxis(c, axis + 1, 0)
        if x.ndim != 1:
            raise ValueError("x must be 1-dimensional")
        if x.size < 2:
            raise ValueError("at least 2 breakpoints are needed")
        if c.shape[0] == 0:
            raise ValueError("polynomial must be at least of order 0")
        if c.shape[1] == 0:
            raise ValueError("number of intervals must be positive")
        if c.shape[1] != x.size - 1:
            raise ValueError("number of coefficients != len(x)-1")
        # SciPy's np.all(dx >= 0) or np.all(dx <= 0) on dx = np.diff(x), in one pass
        if not _lekalo.breakpoints_sorted(x):
            raise ValueError("`x` must be strictly increasing or decreasing.")
        dtype = complex if np.iscomplexobj(c) else float
        self._c = np.ascontiguousarray(c, dtype=dtype)
        self.x = x
        self.extrapolate = extrapolate
        self.axis = axis
        self._degree = c.shape[0] - 1
        self._spline_ = None

    @classmethod
    def construct_fast(cls, c: Any, x: Any, extrapolate: Any = None, axis: int = 0):
        """Construct without checks (SciPy's ``construct_fast``): ``c`` and ``x`` must have the
        right shapes and dtypes, ``c`` with the interpolation axes first."""
        self = object.__new__(cls)
        self._c = c
        self.x = x
        self.axis = axis
        self.extrapolate = True if extrapolate is None else extrapolate
        self._degree = c.shape[0] - 1
        self._spline_ = None
        return self

    @classmethod
    def _from_spline_lazy(cls, spline: BSpline, x: np.ndarray, extrapolate: Any, axis: int, degree: int):
        """The piecewise polynomial that is ``spline`` on the breakpoints ``x`` (its
        coefficients read off the spline when asked for)."""
        self = object.__new__(cls)
        self._c = None
        self.x = x
        self.axis = axis
        self.extrapolate = extrapolate
        self._degree = degree
        self._spline_ = spline
        return self

    def _init_from_spline(self, spline: BSpline, x: np.ndarray, extrapolate: Any, axis: int, degree: int = 3) -> None:
        """Initialise a subclass (``CubicSpline``, ...) from lekalo's spline."""
        self._c = None
        self.x = x
        self.axis = axis
        self.extrapolate = extrapolate
        self._degree = degree
        self._spline_ = spline

    @property
    def c(self) -> np.ndarray:
        if self._c is None:
            self._c = self._read_coefficients()
            self._source = (self._c, self.x, self._c.copy(), self.x.copy())
        return self._c

    @c.setter
    def c(self, value: Any) -> None:
        self._c = value
        self._degree = value.shape[0] - 1
        self._spline_ = None

    # what the spline was made from (c and x, and copies of them), so that coefficients or
    # breakpoints changed in place after the first evaluation are seen, as in SciPy
    _source = None
    # lekalo's curve of the spline, made on the first evaluation
    _curve_ = None

    @property
    def _spline(self) -> BSpline:
        s = self._spline_
        if s is not None and self._source is not None:
            c, x, c0, x0 = self._source
            if not (self._c is c and self.x is x and np.array_equal(c, c0) and np.array_equal(x, x0)):
                s = None
        if s is None:
            x, c = _pieces(self.x, self._c)
            tail = c.shape[2:]
            cc, complex_ = _columns(c)
            t, control = self._spline_form(x, cc)
            s = BSpline.construct_fast(
                t, _from_columns(control, complex_).reshape((control.shape[0],) + tail), self._degree, axis=self.axis
            )
            self._spline_ = s
            self._curve_ = None
            self._source = (self._c, self.x, self._c.copy(), self.x.copy())
        return s

    def _lekalo_curve(self):
        """lekalo's B-spline curve of ``_spline`` (real columns), kept between calls."""
        s = self._spline
        if self._curve_ is None or self._curve_[0] is not s:
            self._curve_ = (s, _curve(s.t, _real_columns(s.c, s._n()), s.k))
        return self._curve_[1]

    def _evaluator(self):
        """What evaluates: lekalo's curve of the spline (``PPoly`` overrides this)."""
        return self._lekalo_curve()

    def _tail(self) -> tuple:
        return self._spline.c.shape[1:] if self._c is None else self._c.shape[2:]

    # lekalo's evaluation of the class's coefficient arrays in place (at points, at a number)
    _values_in_place = None
    _value_in_place = None
    # (c, x, whether they can be evaluated in place): the checks of the arrays' dtype and
    # layout, made once for a pair of arrays (neither changes in place)
    _in_place = (None, None, False)

    def __call__(self, x: Any, nu: int = 0, extrapolate: Any = None) -> np.ndarray:
        """The value (or ``nu``-th derivative) at ``x``, shape ``x.shape`` inserted at ``axis``
        into the coefficients' trailing shape. Real coefficients given: lekalo's evaluation of
        SciPy's arrays in place (``c`` and ``x`` as they are now, changed in place or not), one
        pass. Coefficients read off a spline (the cubics, derivatives, conversions): read
        once, on the first batch of at least as many points as pieces and
        ``_READ_COEFFICIENTS_MIN``, then the same; smaller batches and one number evaluate the
        spline itself (whose values at its ends are its end coefficients exactly). Otherwise lekalo's B-spline of the
        piecewise polynomial."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        c = self._c
        xf = _one_number(x)
        if (
            c is None
            and xf is None
            and self._values_in_place is not None
            and getattr(x, "size", 0) >= max(self.x.size - 1, _READ_COEFFICIENTS_MIN)
        ):
            s = self._spline_
            if s is not None and s.c.dtype == np.float64:
                c = self.c
        if c is not None:
            xb = self.x
            checked = self._in_place
            if checked[0] is not c or checked[1] is not xb:
                ok = c.dtype == np.float64 and c.flags.c_contiguous and c.size > 0 and xb.dtype == np.float64
                checked = self._in_place = (c, xb, bool(ok and xb[-1] != xb[0]))
            if checked[2]:
                if xf is not None and c.ndim == 2 and type(nu) is int and nu >= 0 and extrapolate != "periodic":
                    return np.array(self._value_in_place(c, xb, xf, nu, bool(extrapolate)))
                return self._call_in_place(c, xb, x, nu, extrapolate)
        if xf is not None and nu == 0 and extrapolate != "periodic":
            # one number in: lekalo's bspline_value on the B-spline's arrays (the B-spline's
            # own call for what it does not take)
            s = self._spline
            if s.k:
                try:
                    return np.array(_lekalo.bspline_value(s.t, s.k, s.c, xf, bool(extrapolate)))
                except Exception:
                    pass
            return s(x, 0, extrapolate)
        x, nu = _points_and_order(x, nu)
        if nu > self._degree:
            return self.derivative(nu)(x, 0, extrapolate)
        s = self._spline
        n = s._n()
        if not (extrapolate is True or extrapolate == "periodic") or s.k == 0 or nu > s.k or s.c.size == 0:
            return s(x, nu, extrapolate)
        xf = np.ascontiguousarray(x.ravel(), dtype=np.float64)
        # the common case without BSpline's checks: lekalo's curve, kept between calls
        ev = self._evaluator()
        if isinstance(ev, _lekalo.BSplineCurve):
            # one pass, NaN at NaN or infinite x (as BSpline gives)
            if extrapolate == "periodic":
                xf = s.t[s.k] + (xf - s.t[s.k]) % (s.t[n] - s.t[s.k])
            vals = ev.eval_beyond(xf, nu, True)
        else:
            if not np.isfinite(xf).all():
                return s(x, nu, extrapolate)
            if extrapolate == "periodic":
                xf = s.t[s.k] + (xf - s.t[s.k]) % (s.t[n] - s.t[s.k])
            vals = ev.eval_extrapolated(xf, nu)
        out = _from_columns(vals, np.iscomplexobj(s.c)).reshape(x.shape + s.c.shape[1:])
        return _points_at_axis(out, x.ndim, self.axis)

    def _call_in_place(self, c: np.ndarray, xb: np.ndarray, x: Any, nu: Any, extrapolate: Any) -> np.ndarray:
        """``__call__`` on the coefficient arrays in place (real, C-contiguous): periodic
        points wrapped into ``[x[0], x[-1]]`` first, as SciPy does."""
        x, nu = _points_and_order(x, nu)
        xf = np.ascontiguousarray(x.ravel(), dtype=np.float64)
        if extrapolate == "periodic":
            xf = xb[0] + (xf - xb[0]) % (xb[-1] - xb[0])
            extrapolate = False
        cc = c if c.ndim <= 3 else c.reshape(c.shape[0], c.shape[1], -1)
        vals = self._values_in_place(cc, xb, xf, nu, bool(extrapolate))
        out = vals.reshape(x.shape + c.shape[2:])
        return _points_at_axis(out, x.ndim, self.axis)

    def derivative(self, nu: int = 1):
        """The ``nu``-th derivative as a piecewise polynomial of the same class (order reduced
        by ``nu``; zero of order 1 beyond the degree), lekalo's B-spline derivative."""
        nu = operator.index(nu)
        if nu < 0:
            return self.antiderivative(-nu)
        if nu == 0:
            return self._from_spline_lazy(self._spline, self.x, self.extrapolate, self.axis, self._degree)
        if nu > self._degree or nu > self._spline.k:
            # zero: of order 1 beyond the degree (SciPy's shape), else of the reduced order
            order = 1 if nu > self._degree else self._degree - nu + 1
            z = np.zeros((order, self.x.size - 1) + self._tail(), dtype=self._spline.c.dtype)
            return self.construct_fast(z, self.x, self.extrapolate, self.axis)
        return self._from_spline_lazy(_spline_derivative(self._spline, nu), self.x, self.extrapolate, self.axis, self._degree - nu)

    def antiderivative(self, nu: int = 1):
        """The ``nu``-th antiderivative (zero at ``x[0]``, continuous), of the same class;
        lekalo's B-spline antiderivative. A periodic one does not extrapolate."""
        nu = operator.index(nu)
        if nu < 0:
            return self.derivative(-nu)
        if nu == 0:
            return self.derivative(0)
        s = self._spline
        cols = _real_columns(s.c, s._n())
        if self.x[-1] < self.x[0] and cols.shape[1] > 0:
            # SciPy's antiderivative vanishes at x[0], here the right end: lekalo's pp-form
            # antiderivative anchored there, written back as a B-spline on the same breakpoints
            pp = _curve(s.t, cols, s.k).to_pp().antiderivative(nu, float(self.x[0]))
            curve = pp.to_bspline(_lekalo.PpSpace(np.asarray(pp.breakpoints), pp.order))
            control = np.asarray(curve.control)
            c = _from_columns(control, np.iscomplexobj(s.c)).reshape((control.shape[0],) + s.c.shape[1:])
            s = BSpline.construct_fast(np.asarray(curve.knots), c, pp.order - 1, axis=s.axis)
        else:
            s = s.antiderivative(nu)
        extrapolate = False if self.extrapolate == "periodic" else self.extrapolate
        return self._from_spline_lazy(s, self.x, extrapolate, self.axis, self._degree + nu)

    def integrate(self, a: float, b: float, extrapolate: Any = None) -> np.ndarray:
        """``∫_a^b`` of the piecewise polynomial (NaN outside ``[x[0], x[-1]]`` unless
        extrapolating; periodic: whole periods), lekalo's B-spline integral."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        if extrapolate != "periodic" and not extrapolate:
            lo, hi = min(self.x[0], self.x[-1]), max(self.x[0], self.x[-1])
            if min(a, b) < lo or max(a, b) > hi:
                return np.full(self._tail(), np.nan, dtype=self._spline.c.dtype)
            extrapolate = False
        return self._spline.integrate(a, b, extrapolate=extrapolate)

    def extend(self, c: Any, x: Any) -> None:
        """Add pieces ``c`` on breakpoints ``x`` (all to the right or all to the left of the
        present ones; the orders made equal first)."""
        c = np.asarray(c)
        x = np.asarray(x, dtype=np.float64)
        if c.ndim < 2:
            raise ValueError("invalid dimensions for c")
        if x.ndim != 1:
            raise ValueError("invalid dimensions for x")
        if x.shape[0] != c.shape[1]:
            raise ValueError(f"Shapes of x {x.shape} and c {c.shape} are incompatible")
        if c.shape[2:] != self.c.shape[2:] or c.ndim != self.c.ndim:
            raise ValueError(f"Shapes of c {c.shape} and self.c {self.c.shape} are incompatible")
        if c.size == 0:
            return
        dx = np.diff(x)
        if not (np.all(dx >= 0) or np.all(dx <= 0)):
            raise ValueError("`x` is not sorted.")
        if self.x[-1] >= self.x[0]:
            if not x[-1] >= x[0]:
                raise ValueError("`x` is in the different order than `self.x`.")
            if x[0] >= self.x[-1]:
                action = "append"
            elif x[-1] <= self.x[0]:
                action = "prepend"
            else:
                raise ValueError("`x` is neither on the left or on the right from `self.x`.")
        else:
            if not x[-1] <= x[0]:
                raise ValueError("`x` is in the different order than `self.x`.")
            if x[0] <= self.x[-1]:
                action = "append"
            elif x[-1] >= self.x[0]:
                action = "prepend"
            else:
                raise ValueError("`x` is neither on the left or on the right from `self.x`.")
        mine, theirs = self._same_order(self.c, c)
        dtype = np.result_type(mine.dtype, theirs.dtype)
        if action == "append":
            self._c = np.ascontiguousarray(np.concatenate([mine, theirs], axis=1), dtype=dtype)
            self.x = np.r_[self.x, x]
        else:
            self._c = np.ascontiguousarray(np.concatenate([theirs, mine], axis=1), dtype=dtype)
            self.x = np.r_[x, self.x]
        self._degree = self._c.shape[0] - 1
        self._spline_ = None


class PPoly(_PPolyBase):
    """``scipy.interpolate.PPoly``: a piecewise polynomial in the local power basis,
    ``S(x) = sum_m c[m, i] (x - x[i])^(k-m)`` on ``x[i] <= x < x[i+1]``. lekalo's
    ``PiecewisePolynomial`` with its B-spline form (``to_bspline`` on the unconstrained space,
    de Boor–Fix) computes every number."""

    @staticmethod
    def _spline_form(x: np.ndarray, cc: np.ndarray):
        order = cc.shape[0]
        decreasing = x[-1] < x[0]
        space = _lekalo.PpSpace(np.ascontiguousarray(x[::-1]) if decreasing else x, order)
        if cc.shape[2] == 0:
            return np.asarray(space.knots), np.zeros((space.dimension, 0))
        # lekalo stores the local power coefficients lowest power first, (pieces, order, dim)
        # decreasing: pieces about their right ends, lekalo's pp-form of the same function
        curve = PPoly._lekalo_pp(x, cc).to_bspline(space)
        return np.asarray(curve.knots), np.asarray(curve.control)

    # lekalo's pp-form of the given coefficients, made on the first evaluation: (spline, pp)
    _pp_ = None

    # Horner's rule in each piece on the given coefficients in place, on breakpoints in either
    # order (lekalo's ppoly_values, PowerFormRef), without the B-spline form being made
    _values_in_place = staticmethod(_lekalo.ppoly_values)
    _value_in_place = staticmethod(_lekalo.ppoly_value)

    @staticmethod
    def _lekalo_pp(x: np.ndarray, cc: np.ndarray):
        """lekalo's ``PiecewisePolynomial`` of coefficients ``cc`` (highest power first,
        ``(order, pieces, columns)``) on the breakpoints ``x``, increasing or decreasing."""
        local = np.ascontiguousarray(cc[::-1].transpose(1, 0, 2))  # lowest power first
        if x[-1] < x[0]:
            return _lekalo.PiecewisePolynomial.from_decreasing(x, local)
        return _lekalo.PiecewisePolynomial(x, local)

    def _evaluator(self):
        """With coefficients given, lekalo's pp-form itself (Horner's rule in each piece,
        the end pieces continued), as SciPy evaluates; otherwise lekalo's curve."""
        s = self._spline
        if self._c is None:
            return self._lekalo_curve()
        if self._pp_ is None or self._pp_[0] is not s:
            x, c = _pieces(self.x, self._c)
            cc, _ = _columns(c)
            self._pp_ = (s, self._lekalo_pp(x, cc))
        return self._pp_[1]

    def derivative(self, nu: int = 1) -> "PPoly":
        """The ``nu``-th derivative. With coefficients given (not read off a spline),
        lekalo's ``PiecewisePolynomial.derivative`` on the pp-form itself, as SciPy does (on
        decreasing breakpoints through lekalo's ``from_decreasing``/``to_decreasing``);
        otherwise lekalo's B-spline derivative."""
        nu = operator.index(nu)
        if nu <= 0 or nu > self._degree or self._c is None:
            return super().derivative(nu)
        x, c = _pieces(self.x, self._c)
        cc, complex_ = _columns(c)
        if cc.shape[2] == 0 or x.size != self.x.size:
            return super().derivative(nu)
        pp = self._lekalo_pp(x, cc).derivative(nu)
        coefficients = pp.to_decreasing()[1] if x[-1] < x[0] else pp.coefficients
        d = np.asarray(coefficients)[:, ::-1].transpose(1, 0, 2)  # highest power first
        d = _from_columns(np.ascontiguousarray(d), complex_).reshape(d.shape[:2] + self._c.shape[2:])
        return self.construct_fast(np.ascontiguousarray(d), self.x, self.extrapolate, self.axis)

    def antiderivative(self, nu: int = 1) -> "PPoly":
        """The ``nu``-th antiderivative, zero with its first ``nu - 1`` derivatives at
        ``x[0]``. With coefficients given, lekalo's ``PiecewisePolynomial.antiderivative`` on
        the pp-form itself, as SciPy does; otherwise lekalo's B-spline antiderivative."""
        nu = operator.index(nu)
        if nu <= 0 or self._c is None:
            return super().antiderivative(nu)
        x, c = _pieces(self.x, self._c)
        cc, complex_ = _columns(c)
        if cc.shape[2] == 0 or x.size != self.x.size:
            return super().antiderivative(nu)
        pp = self._evaluator().antiderivative(nu, float(self.x[0]))
        coefficients = pp.to_decreasing()[1] if x[-1] < x[0] else pp.coefficients
        d = np.asarray(coefficients)[:, ::-1].transpose(1, 0, 2)  # highest power first
        d = _from_columns(np.ascontiguousarray(d), complex_).reshape(d.shape[:2] + self._c.shape[2:])
        extrapolate = False if self.extrapolate == "periodic" else self.extrapolate
        return self.construct_fast(np.ascontiguousarray(d), self.x, extrapolate, self.axis)

    def integrate(self, a: float, b: float, extrapolate: Any = None) -> np.ndarray:
        """``∫_a^b``; with coefficients given and not periodic, lekalo's
        ``PiecewisePolynomial.integral_extrapolated`` on the pp-form itself (NaN outside
        ``[x[0], x[-1]]`` unless extrapolating), as SciPy does; otherwise lekalo's B-spline
        integral."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        if self._c is None or extrapolate == "periodic" or self._c.size == 0 or not np.isfinite([a, b]).all():
            return super().integrate(a, b, extrapolate)
        if not extrapolate:
            lo, hi = min(self.x[0], self.x[-1]), max(self.x[0], self.x[-1])
            if min(a, b) < lo or max(a, b) > hi:
                return np.full(self._tail(), np.nan, dtype=self._spline.c.dtype)
        v = np.asarray(self._evaluator().integral_extrapolated(float(a), float(b)))
        return _from_columns(v, np.iscomplexobj(self._c)).reshape(self._c.shape[2:])

    def _read_coefficients(self) -> np.ndarray:
        s = self._spline
        k = self._degree
        n = s._n()
        tail = s.c.shape[1:]
        cols = _real_columns(s.c, n)
        if cols.shape[1] > 0 and s.k <= k:
            # lekalo's pp-form of the spline, when its breakpoints are ours
            pp = _curve(s.t, cols, s.k).to_pp()
            xb = np.asarray(pp.breakpoints)
            decreasing = self.x[-1] < self.x[0]
            if xb.shape == self.x.shape and np.array_equal(xb, self.x[::-1] if decreasing else self.x):
                # decreasing: each piece about its right end (lekalo's left limits there)
                coefficients = pp.to_decreasing()[1] if decreasing else pp.coefficients
                cc = np.asarray(coefficients)[:, ::-1].transpose(1, 0, 2)  # highest power first
                c = _from_columns(np.ascontiguousarray(cc), np.iscomplexobj(s.c))
                c = c.reshape(cc.shape[:2] + tail)
                if c.shape[0] < k + 1:
                    c = np.concatenate([np.zeros((k + 1 - c.shape[0],) + c.shape[1:], dtype=c.dtype), c])
                return np.ascontiguousarray(c)
        if self.x[-1] < self.x[0]:
            raise NotImplementedError(
                "lekalo.scipy: PPoly coefficients on decreasing breakpoints that are not the spline's breakpoints"
            )
        # elsewhere (repeated breakpoints, breakpoints that are not knots):
        # c[k - m, i] = S^(m)(x_i+) / m!, lekalo's derivatives at the left breakpoints
        xs = self.x[:-1]
        rows = [
            BSpline.construct_fast(s.t, s.c, s.k)._evaluate(xs, m, True).reshape((xs.size,) + s.c.shape[1:])
            / math.factorial(m)
            for m in range(k, -1, -1)
        ]
        return np.ascontiguousarray(np.stack(rows))

    @staticmethod
    def _same_order(a: np.ndarray, b: np.ndarray):
        # zero leading (highest-power) coefficients raise the order of a power form exactly
        k = max(a.shape[0], b.shape[0])
        pad = lambda c: np.concatenate([np.zeros((k - c.shape[0],) + c.shape[1:], dtype=c.dtype), c])  # noqa: E731
        return pad(a), pad(b)

    def solve(self, y: float = 0.0, discontinuity: bool = True, extrapolate: Any = None):
        """The real solutions of ``S(x) = y`` with SciPy's conventions (lekalo's
        ``PiecewisePolynomial.solve``): a piece identically ``y`` as ``x_i, nan``, sign changes
        across jumps with ``discontinuity``, the end pieces extended with ``extrapolate``. One
        array, or an object array of arrays for trailing dimensions."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        c = self.c
        if np.issubdtype(c.dtype, np.complexfloating):
            raise ValueError("Root finding is only for real-valued polynomials")
        y = float(y)
        tail = c.shape[2:]
        if c.shape[0] == 0:
            return np.array([], dtype=float)
        x, cp = _pieces(self.x, np.asarray(c, dtype=np.float64))
        cc = np.ascontiguousarray(cp.reshape(cp.shape[0], cp.shape[1], -1))
        if cc.shape[2] == 0:
            roots = []
        else:
            # decreasing breakpoints: the same function on increasing ones (lekalo's
            # from_decreasing), so the roots come in increasing order
            pp = self._lekalo_pp(x, cc)
            roots = pp.solve(y, discontinuity=bool(discontinuity), extrapolate=bool(extrapolate))
        if c.ndim == 2:
            return roots[0]
        r2 = np.empty(int(np.prod(tail)), dtype=object)
        for i, r in enumerate(roots):
            r2[i] = r
        return r2.reshape(tail)

    def roots(self, discontinuity: bool = True, extrapolate: Any = None):
        return self.solve(0, discontinuity, extrapolate)

    @classmethod
    def from_spline(cls, tck: Any, extrapolate: Any = None) -> "PPoly":
        """The piecewise polynomial of a spline (``BSpline`` or ``(t, c, k)``) on the
        breakpoints ``t``, SciPy's form; lekalo evaluates it."""
        if isinstance(tck, BSpline):
            t, c, k = tck.tck
            if extrapolate is None:
                extrapolate = tck.extrapolate
        else:
            t, c, k = tck
            if extrapolate is None:
                extrapolate = True
        t = np.ascontiguousarray(t, dtype=np.float64)
        c = np.asarray(c)
        n = t.size - k - 1
        spline = BSpline.construct_fast(t, np.ascontiguousarray(c[:n], dtype=_get_dtype(c.dtype)), k)
        return cls._from_spline_lazy(spline, t, extrapolate, 0, k)

    @classmethod
    def from_bernstein_basis(cls, bp: "BPoly", extrapolate: Any = None) -> "PPoly":
        """The power form of a ``BPoly`` (lekalo's B-spline of it, its derivatives at the
        breakpoints)."""
        if not isinstance(bp, BPoly):
            raise TypeError(f".from_bernstein_basis only accepts BPoly instances. Got {type(bp)} instead.")
        if extrapolate is None:
            extrapolate = bp.extrapolate
        return cls._from_spline_lazy(bp._spline, bp.x, extrapolate, bp.axis, bp._degree)


class BPoly(_PPolyBase):
    """``scipy.interpolate.BPoly``: a piecewise polynomial in the Bernstein basis of each piece,
    ``S(x) = sum_a c[a, i] b_{a,k}((x - x[i]) / (x[i+1] - x[i]))``. Those coefficients are the
    B-spline coefficients of the same function on knots of multiplicity ``k + 1`` at every
    breakpoint, so lekalo's B-spline computes every number; coefficients of results are
    lekalo's Bézier pieces (``to_bezier_segments``)."""

    # the Bernstein sum in each piece on the given coefficients in place, on breakpoints in
    # either order (lekalo's bpoly_values, BernsteinFormRef), without the B-spline form
    _values_in_place = staticmethod(_lekalo.bpoly_values)
    _value_in_place = staticmethod(_lekalo.bpoly_value)

    @staticmethod
    def _spline_form(x: np.ndarray, cc: np.ndarray):
        order = cc.shape[0]
        if x[-1] < x[0]:
            # decreasing breakpoints: the pieces in increasing order, each one's Bernstein
            # coefficients reversed (b_{a,k}(1 - u) = b_{k-a,k}(u))
            x, cc = x[::-1], cc[::-1, ::-1]
        t = np.repeat(x, order)
        return t, np.ascontiguousarray(cc.transpose(1, 0, 2)).reshape(cc.shape[0] * cc.shape[1], cc.shape[2])

    def _read_coefficients(self) -> np.ndarray:
        decreasing = self.x[-1] < self.x[0]
        xs = self.x[::-1] if decreasing else self.x
        s = self._spline
        n = s._n()
        tail = s.c.shape[1:]
        complex_ = np.iscomplexobj(s.c)
        cols = _real_columns(s.c, n)
        pieces = self.x.size - 1
        if cols.shape[1] == 0:
            return np.zeros((s.k + 1, pieces) + tail, dtype=s.c.dtype)
        curve = _curve(s.t, cols, s.k)
        x, _ = _pieces(xs, np.zeros((1, pieces)))
        missing = np.setdiff1d(x[1:-1], s.t)
        if missing.size:
            curve = curve.refine_knots(missing)
        segments = curve.to_bezier_segments()
        ctrl = np.stack([np.asarray(seg[2].control) for seg in segments])  # (pieces, order, columns)
        if ctrl.shape[0] != x.size - 1:
            raise NotImplementedError("lekalo.scipy: BPoly coefficients of a spline with knots outside its breakpoints")
        c = _from_columns(np.ascontiguousarray(ctrl.transpose(1, 0, 2)), complex_)
        c = c.reshape((ctrl.shape[1], ctrl.shape[0]) + tail)
        if x.size != self.x.size:
            full = np.zeros((c.shape[0], pieces) + tail, dtype=c.dtype)
            full[:, np.diff(xs) > 0] = c
            c = full
        if decreasing:
            c = c[::-1, ::-1]
        return np.ascontiguousarray(c)

    @staticmethod
    def _raise_degree(c: np.ndarray, d: int) -> np.ndarray:
        """The Bernstein coefficients of the same pieces at degree ``k + d`` (lekalo's degree
        elevation of the B-spline with every breakpoint of full multiplicity)."""
        c = np.asarray(c)
        if d == 0:
            return c
        order, pieces = c.shape[0], c.shape[1]
        tail = c.shape[2:]
        cc, complex_ = _columns(c)
        if cc.shape[2] == 0:
            return np.zeros((order + d, pieces) + tail, dtype=c.dtype)
        x = np.arange(pieces + 1, dtype=np.float64)
        t, control = BPoly._spline_form(x, cc)
        curve = _curve(t, control, order - 1).elevate_degree(d)
        up = np.asarray(curve.control).reshape(pieces, order + d, -1).transpose(1, 0, 2)
        return _from_columns(np.ascontiguousarray(up), complex_).reshape((order + d, pieces) + tail)

    @classmethod
    def _same_order(cls, a: np.ndarray, b: np.ndarray):
        k = max(a.shape[0], b.shape[0])
        return cls._raise_degree(a, k - a.shape[0]), cls._raise_degree(b, k - b.shape[0])

    @classmethod
    def from_power_basis(cls, pp: PPoly, extrapolate: Any = None) -> "BPoly":
        """The Bernstein form of a ``PPoly`` (lekalo's B-spline of it cut into Bézier pieces)."""
        if not isinstance(pp, PPoly):
            raise TypeError(f".from_power_basis only accepts PPoly instances. Got {type(pp)} instead.")
        if extrapolate is None:
            extrapolate = pp.extrapolate
        return cls._from_spline_lazy(pp._spline, pp.x, extrapolate, pp.axis, pp._degree)

    @classmethod
    def from_derivatives(cls, xi: Any, yi: Any, orders: Any = None, extrapolate: Any = None) -> "BPoly":
        """The piecewise polynomial in Bernstein form with the derivatives ``yi[i]`` (value,
        first derivative, ...) at ``xi[i]``, of degree ``orders[i]`` on piece ``i`` when given:
        lekalo's ``piecewise_hermite_bernstein``. As in SciPy every piece is then raised to the
        order ``max(len(yi[i]) + len(yi[i+1]), orders)`` (lekalo's degree elevation)."""
        xi = np.asarray(xi)
        if len(xi) != len(yi):
            raise ValueError("xi and yi need to have the same length")
        if np.any(xi[1:] - xi[:1] <= 0):
            raise ValueError("x coordinates are not in increasing order")
        m = len(xi) - 1
        try:
            k = max(len(yi[i]) + len(yi[i + 1]) for i in range(m))
        except TypeError as e:
            raise ValueError("Using a 1-D array for y? Please .reshape(-1, 1).") from e
        if orders is not None:
            if isinstance(orders, (int, np.integer)):
                orders = [orders] * m
            orders = [operator.index(o) for o in orders]
            k = max(k, max(orders))
            if any(o <= 0 for o in orders):
                raise ValueError("Orders must be positive.")
        ys = [np.asarray(y) for y in yi]
        tail = ys[0].shape[1:]
        complex_ = any(np.iscomplexobj(y) for y in ys)
        dt = np.complex128 if complex_ else np.float64
        for y in ys:
            if y.shape[1:] != tail:
                raise ValueError(f"Shapes of ya {ys[0].shape} and yb {y.shape} are incompatible")
        cols = [_real_columns(np.asarray(y, dtype=dt), y.shape[0]) for y in ys]
        if cols[0].shape[1] == 0:
            order = k
            c = np.zeros((order, m) + tail, dtype=dt)
        else:
            curve = _lekalo.piecewise_hermite_bernstein(np.asarray(xi, dtype=np.float64), cols, orders)
            order = curve.degree + 1
            ctrl = np.asarray(curve.control).reshape(m, order, -1).transpose(1, 0, 2)
            c = _from_columns(np.ascontiguousarray(ctrl), complex_).reshape((order, m) + tail)
            if order < k:
                c = cls._raise_degree(c, k - order)
        return cls(c, xi, extrapolate)

    @staticmethod
    def _construct_from_derivatives(xa: float, xb: float, ya: Any, yb: Any):
        """The Bernstein coefficients on ``[xa, xb]`` of the polynomial of least degree with the
        derivatives ``ya`` at ``xa`` and ``yb`` at ``xb``: lekalo's ``hermite_bernstein``."""
        ya, yb = np.asarray(ya), np.asarray(yb)
        if ya.shape[1:] != yb.shape[1:]:
            raise ValueError(f"Shapes of ya {ya.shape} and yb {yb.shape} are incompatible")
        complex_ = np.iscomplexobj(ya) or np.iscomplexobj(yb)
        dt = np.complex128 if complex_ else np.float64
        tail = ya.shape[1:]
        ca = _real_columns(np.asarray(ya, dtype=dt), ya.shape[0])
        cb = _real_columns(np.asarray(yb, dtype=dt), yb.shape[0])
        n = ya.shape[0] + yb.shape[0]
        if ca.shape[1] == 0:
            return np.zeros((n,) + tail, dtype=dt)
        c = _lekalo.hermite_bernstein(float(xa), float(xb), ca, cb)
        return _from_columns(np.asarray(c), complex_).reshape((n,) + tail)
