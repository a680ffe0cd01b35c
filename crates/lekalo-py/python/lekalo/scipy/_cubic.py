"""SciPy's piecewise cubics in ``lekalo.scipy`` (SciPy's ``_cubic.py``): ``CubicSpline``,
``CubicHermiteSpline``, ``PchipInterpolator``, ``Akima1DInterpolator``, each a ``PPoly`` whose
coefficients lekalo writes in one call from the data (the slopes, then the pieces in power
form by SciPy's operations: SciPy's numbers, so its values far beyond the ends too); this
module checks SciPy's arguments and rearranges arrays."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import _lekalo
from ._bspline import BSpline, _from_columns, _real_columns
from ._interpolate import make_interp_spline
from ._ppoly import PPoly


def _prepare_input(x: Any, y: Any, axis: int):
    """SciPy's ``prepare_input`` of the piecewise cubics (its checks and messages, in its order),
    without its temporaries the size of the data: the increasing test compares neighbours
    (a boolean array) instead of forming ``np.diff(x)``, which no caller uses."""
    x, y = np.asarray(x), np.asarray(y)
    if np.iscomplexobj(x):
        raise ValueError("`x` must contain real values.")
    x = np.asarray(x, dtype=np.float64)
    y = y.astype(complex if np.iscomplexobj(y) else float, copy=False)
    if y.ndim == 0:
        # SciPy takes `axis % y.ndim` here: ZeroDivisionError
        raise ValueError("`y` must have at least 1 dimension, its `axis` as long as `x`; got a number")
    axis = axis % y.ndim
    if x.ndim != 1:
        raise ValueError("`x` must be 1-dimensional.")
    if x.shape[0] < 2:
        raise ValueError("`x` must contain at least 2 elements.")
    if x.shape[0] != y.shape[axis]:
        raise ValueError(f"The length of `y` along `axis`={axis} doesn't match the length of `x`")
    if not np.isfinite(x).all():
        raise ValueError("`x` must contain only finite values.")
    if not np.isfinite(y).all():
        raise ValueError("`y` must contain only finite values.")
    # x[i + 1] - x[i] <= 0 exactly when x[i + 1] <= x[i] (finite numbers, gradual underflow)
    if (x[1:] <= x[:-1]).any():
        raise ValueError("`x` must be strictly increasing sequence.")
    y = np.moveaxis(y, axis, 0)
    return np.ascontiguousarray(x), y, axis


def _direct_data(x: Any, y: Any, axis: Any) -> bool:
    """Whether ``x`` and ``y`` are what most calls pass: 1-D float64 NumPy arrays of one
    length, at least 2, interpolated along ``axis`` 0. Then SciPy's checks (finite numbers,
    ``x`` strictly increasing) are exactly those of lekalo's one-pass kernels, and
    :func:`_direct_coefficients` makes the coefficients without ``_prepare_input``'s passes."""
    return (
        type(x) is np.ndarray
        and type(y) is np.ndarray
        and x.dtype == np.float64
        and y.dtype == np.float64
        and x.ndim == 1
        and y.ndim == 1
        and x.shape == y.shape
        and x.shape[0] >= 2
        and (axis == 0 or axis == -1)
    )


def _direct_coefficients(kernel: Any, *data: np.ndarray) -> np.ndarray | None:
    """The coefficients ``(4, n - 1)`` that ``kernel`` (lekalo's ``hermite_pp``, ``pchip_pp``
    or ``akima_pp``: the slopes and the pieces in one pass each, the checks folded in) writes
    for data that passed :func:`_direct_data`; ``None`` on data it refuses, for the general
    path to raise SciPy's error in SciPy's order."""
    try:
        return kernel(*data)
    except _lekalo.InputError:
        return None


def _hermite_coefficients(x: np.ndarray, y: np.ndarray, dydx: np.ndarray) -> np.ndarray:
    """SciPy's ``CubicHermiteSpline`` coefficients ``(4, n - 1) + tail`` of values and slopes
    with the interpolation axis first (complex: real and imaginary parts as columns)."""
    n = x.shape[0]
    tail = y.shape[1:]
    complex_ = np.iscomplexobj(y) or np.iscomplexobj(dydx)
    dt = np.complex128 if complex_ else np.float64
    yy = _real_columns(np.asarray(y, dtype=dt), n)
    dd = _real_columns(np.asarray(dydx, dtype=dt), n)
    if yy.shape[1] == 0:
        return np.zeros((4, n - 1) + tail, dtype=dt)
    c = _lekalo.hermite_pp(x, yy, dd)
    return _from_columns(c, complex_).reshape((4, n - 1) + tail)


class _Cubic(PPoly):
    """What the piecewise cubics share: made from SciPy's coefficients ``c`` (highest power
    first, the interpolation axes first) on the breakpoints ``x``."""

    def _init_from_coefficients(self, c: np.ndarray, x: np.ndarray, extrapolate: Any, axis: int) -> None:
        self._c = c
        self.x = x
        self.axis = axis
        self.extrapolate = extrapolate
        self._degree = c.shape[0] - 1
        self._spline_ = None


def _cubic_spline_ends(bc_type: Any, y: np.ndarray, axis: int):
    """SciPy's ``CubicSpline._validate_bc``: the two end conditions (``"not-a-knot"``,
    ``"periodic"`` or ``(order, value)`` with the value of the trailing shape) and ``y`` made
    complex when a value is; SciPy's checks and messages in its order."""
    tail = y.shape[1:]
    if isinstance(bc_type, str):
        if bc_type == "periodic" and not np.allclose(y[0], y[-1], rtol=1e-15, atol=1e-15):
            raise ValueError(
                f"The first and last `y` point along axis {axis} must be identical (within "
                "machine precision) when bc_type='periodic'."
            )
        bc_type = (bc_type, bc_type)
    else:
        if len(bc_type) != 2:
            raise ValueError("`bc_type` must contain 2 elements to specify start and end conditions.")
        if "periodic" in bc_type:
            raise ValueError(
                "'periodic' `bc_type` is defined for both curve ends and cannot be used with "
                "other boundary conditions."
            )
    ends = []
    for bc in bc_type:
        if isinstance(bc, str):
            if bc == "clamped":
                ends.append((1, np.zeros(tail)))
            elif bc == "natural":
                ends.append((2, np.zeros(tail)))
            elif bc in ("not-a-knot", "periodic"):
                ends.append(bc)
            else:
                raise ValueError(f"bc_type={bc} is not allowed.")
        else:
            try:
                order, value = bc
            except Exception as e:
                raise ValueError("A specified derivative value must be given in the form (order, value).") from e
            if order not in [1, 2]:
                raise ValueError("The specified derivative order must be 1 or 2.")
            value = np.asarray(value)
            if value.shape != tail:
                raise ValueError(f"`deriv_value` shape {value.shape} is not the expected one {tail}.")
            if np.issubdtype(value.dtype, np.complexfloating):
                y = y.astype(complex, copy=False)
            ends.append((int(order), value))
    return ends, y


class CubicSpline(_Cubic):
    """``scipy.interpolate.CubicSpline``: the C² cubic through the data with SciPy's end
    conditions (``"not-a-knot"``, ``"clamped"``, ``"natural"``, ``"periodic"``, ``((order,
    value), (order, value))``). lekalo's ``cubic_spline_pp`` solves SciPy's tridiagonal (or
    cyclic) system for the slopes of every column at once (elimination without row swaps, its
    pivots positive; LAPACK ``dgtsv``'s pivoting otherwise) and writes the pieces in power form
    by SciPy's operations: SciPy's coefficients to rounding."""

    def __init__(self, x: Any, y: Any, axis: int = 0, bc_type: Any = "not-a-knot", extrapolate: Any = None) -> None:
        x, y, axis = _prepare_input(x, y, axis)
        n = x.shape[0]
        ends, y = _cubic_spline_ends(bc_type, y, axis)
        if extrapolate is None:
            extrapolate = "periodic" if isinstance(ends[0], str) and ends[0] == "periodic" else True
        tail = y.shape[1:]
        complex_ = np.iscomplexobj(y)
        if y.size == 0:
            c = np.zeros((4, n - 1) + tail, dtype=y.dtype)
        else:

            def end(e: Any) -> Any:
                if isinstance(e, str):
                    return e
                order, value = e
                return order, _real_columns(np.asarray(value, dtype=y.dtype).reshape((1,) + tail), 1)[0]

            try:
                cc = _lekalo.cubic_spline_pp(x, _real_columns(y, n), end(ends[0]), end(ends[1]))
            except _lekalo.InputError as e:
                # the data passed SciPy's checks: what is left is a slope that is not finite (a
                # non-finite end value, or an overflow), which SciPy's CubicHermiteSpline refuses
                raise ValueError("`dydx` must contain only finite values.") from e
            c = _from_columns(cc, complex_).reshape((4, n - 1) + tail)
        self._init_from_coefficients(c, x, extrapolate, axis)
        self._bspline_args = (x, y, ends, axis)

    _bspline_args = None

    def _bspline_form(self) -> BSpline:
        """The same spline as a ``BSpline`` on the knots ``make_interp_spline`` takes for its
        end conditions (not-a-knot, clamped at the ends, or periodic), by
        :func:`make_interp_spline`'s engines on the data (``BSpline.from_power_basis``)."""
        if self._bspline_args is None:
            # made by lekalo (a derivative, an antiderivative): its B-spline form from `c`
            return self._spline
        x, y, ends, axis = self._bspline_args
        n = x.shape[0]
        dl, dr = ([e] if isinstance(e, tuple) else e for e in ends)
        if dl == "periodic":
            spline = make_interp_spline(x, y, k=3, bc_type="periodic", axis=0)
            return BSpline.construct_fast(spline.t, spline.c, 3, axis=axis)
        if n == 2:
            # SciPy's convention: not-a-knot through two points is the chord's slope
            slope = (y[1] - y[0]) / (x[1] - x[0])
            dl = [(1, slope)] if dl == "not-a-knot" else dl
            dr = [(1, slope)] if dr == "not-a-knot" else dr
        dl = None if dl == "not-a-knot" else dl
        dr = None if dr == "not-a-knot" else dr
        if dl is None and dr is None:
            spline = make_interp_spline(x, y, k=3 if n >= 4 else n - 1, axis=0)
        elif dl is None or dr is None:
            # not-a-knot at one end: the knot at the second (next-to-last) point is dropped
            inner = x[2:-1] if dl is None else x[1:-2]
            t = np.r_[(x[0],) * 4, inner, (x[-1],) * 4]
            spline = make_interp_spline(x, y, k=3, t=t, bc_type=(dl, dr), axis=0)
        else:
            spline = make_interp_spline(x, y, k=3, bc_type=(dl, dr), axis=0)
        return BSpline.construct_fast(spline.t, spline.c, spline.k, axis=axis)


class CubicHermiteSpline(_Cubic):
    """``scipy.interpolate.CubicHermiteSpline``: the cubic with values ``y`` and slopes
    ``dydx`` at ``x``, its coefficients written in one pass by lekalo's ``hermite_pp``
    (``cubic_hermite_power_into``: SciPy's operations, its numbers)."""

    def __init__(self, x: Any, y: Any, dydx: Any, axis: int = 0, extrapolate: Any = None) -> None:
        if extrapolate is None:
            extrapolate = True
        if _direct_data(x, y, axis) and _direct_data(x, dydx, axis):
            c = _direct_coefficients(_lekalo.hermite_pp, x, y, dydx)
            if c is not None:
                self._init_from_coefficients(c, x, extrapolate, 0)
                return
        x, y, axis = _prepare_input(x, y, axis)
        dydx = np.moveaxis(np.asarray(dydx), axis, 0)
        if dydx.shape != y.shape:
            raise ValueError("The shapes of `y` and `dydx` must be identical.")
        if not np.all(np.isfinite(dydx)):
            raise ValueError("`dydx` must contain only finite values.")
        self._init_from_coefficients(_hermite_coefficients(x, y, dydx), x, extrapolate, axis)


class PchipInterpolator(_Cubic):
    """``scipy.interpolate.PchipInterpolator``: the monotonicity-preserving piecewise cubic,
    with lekalo's ``pchip_slopes`` (Fritsch–Butland, Moler's ends) and the pieces of
    ``cubic_hermite_power_into`` (SciPy's numbers)."""

    def __init__(self, x: Any, y: Any, axis: int = 0, extrapolate: Any = None) -> None:
        if extrapolate is None:
            extrapolate = True
        if _direct_data(x, y, axis):
            c = _direct_coefficients(_lekalo.pchip_pp, x, y)
            if c is not None:
                self._init_from_coefficients(c, x, extrapolate, 0)
                return
        x, y, axis = _prepare_input(x, y, axis)
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
        self._init_from_coefficients(_hermite_coefficients(x, y, dydx), x, extrapolate, axis)


class Akima1DInterpolator(_Cubic):
    """``scipy.interpolate.Akima1DInterpolator``: the local Akima (``method="akima"``) or
    modified Akima (``"makima"``) piecewise cubic, with lekalo's ``akima_slopes`` and the
    pieces of ``cubic_hermite_power_into``. Extrapolation is off by default, as in SciPy."""

    def __init__(self, x: Any, y: Any, axis: int = 0, *, method: str = "akima", extrapolate: Any = None) -> None:
        if method not in {"akima", "makima"}:
            raise NotImplementedError(f"`method`={method} is unsupported.")
        if _direct_data(x, y, axis):
            c = _direct_coefficients(lambda x_, y_: _lekalo.akima_pp(x_, y_, method), x, y)
            if c is not None:
                self._init_from_coefficients(c, x, False if extrapolate is None else extrapolate, 0)
                return
        x, y, axis = _prepare_input(x, y, axis)
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
        self._init_from_coefficients(_hermite_coefficients(x, y, dydx), x, extrapolate, axis)

    def extend(self, c: Any, x: Any) -> None:
        raise NotImplementedError("Extending a 1-D Akima interpolator is not yet implemented")


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


BSpline._power_basis_types = (CubicSpline,)
