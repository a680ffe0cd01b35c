"""The piecewise cubics of ``lekalo.scipy`` in SciPy's ``PPoly`` form: ``CubicSpline``,
``CubicHermiteSpline``, ``PchipInterpolator``, ``Akima1DInterpolator``."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import _lekalo
from ._bspline import BSpline, _as_float_array, _from_columns, _real_columns
from ._interpolate import make_interp_spline


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
                if bc not in ("clamped", "natural"):
                    raise ValueError(f"bc_type={bc} is not allowed.")
                return bc
            try:
                order, value = bc
            except Exception as e:
                raise ValueError("A specified derivative value must be given in the form (order, value).") from e
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


pchip = PchipInterpolator


def pchip_interpolate(xi: Any, yi: Any, x: Any, der: Any = 0, axis: int = 0):
    """``scipy.interpolate.pchip_interpolate``: ``PchipInterpolator(xi, yi, axis)`` (or its
    derivatives of the orders ``der``) at ``x``."""
    p = PchipInterpolator(xi, yi, axis=axis)
    if der == 0:
        return p(x)
    if np.ndim(der) == 0:
        return p.derivative(der)(x)
    return [p.derivative(nu)(x) for nu in der]
