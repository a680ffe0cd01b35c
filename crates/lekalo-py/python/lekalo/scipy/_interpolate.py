"""The interpolating and fitting constructors of ``lekalo.scipy``: SciPy's knot choices and
boundary conditions, lekalo's solves."""

from __future__ import annotations

import operator
from typing import Any

import numpy as np

from .. import _lekalo
from ._bspline import (
    BSpline,
    _as_float_array,
    _from_columns,
    _get_dtype,
    _normalize_axis,
    _real_columns,
)
from ._knots import _augknt, _not_a_knot, _periodic_knots


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
    SciPy's knots and boundary conditions, solved by lekalo's ``interpolate_with_end_derivatives``
    (without derivative conditions the collocation matrix, totally positive, by banded
    elimination without pivoting as SciPy's LU; with derivative conditions of any orders, chosen
    per end, by banded QR)."""
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
    if k > _lekalo.MAX_DEGREE:
        # refused before the knots of that degree are made: SciPy allocates 2 (k + 1) of them
        raise ValueError(
            f"k = {k} is above the largest degree lekalo interpolates, {_lekalo.MAX_DEGREE}; "
            "use a smaller k"
        )
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
        # the collocation matrix alone, totally positive: lekalo eliminates it without pivoting
        ctrl = _lekalo.interpolate_with_end_derivatives(x, yy, t, k).control
    else:

        def conditions(ords, vals):
            return [
                (int(o), _real_columns(np.asarray(v, dtype=y.dtype).reshape((1,) + tail), 1)[0])
                for o, v in zip(ords, vals)
            ]

        start = conditions(deriv_l_ords, deriv_l_vals)
        end = conditions(deriv_r_ords, deriv_r_vals)
        ctrl = _lekalo.interpolate_with_end_derivatives(x, yy, t, k, start=start, end=end).control
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
    the least score of a scan over the whole range, where SciPy's bounded search can stop at
    another local minimum: ``docs/scipy.md``)."""
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
    if w is not None:
        # SciPy reads the weights as an array (a boolean mask too) and refuses any w <= 0
        w = np.ascontiguousarray(w, dtype=float)
        if any(w <= 0):
            raise ValueError("Invalid vector of weights")
    tail = y.shape[1:]
    n = x.shape[0]
    cols = _real_columns(y, n)
    if lam is None and cols.shape[1] > 1:
        # SciPy chooses the GCV weight for each column of a batch on its own
        fits = [_lekalo.make_smoothing_spline(x, np.ascontiguousarray(cols[:, j]), w, None) for j in range(cols.shape[1])]
        knots = fits[0].knots
        control = np.concatenate([f.control for f in fits], axis=1)
    else:
        curve = _lekalo.make_smoothing_spline(x, cols, w, lam)
        knots, control = curve.knots, curve.control
    c = np.ascontiguousarray(control).reshape((-1,) + tail)
    return BSpline.construct_fast(np.ascontiguousarray(knots), c, 3, axis=axis)
