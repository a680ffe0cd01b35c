"""``UnivariateSpline``, ``InterpolatedUnivariateSpline`` and ``LSQUnivariateSpline`` of
``lekalo.scipy``: SciPy's object interface to FITPACK's ``curfit``, over lekalo's fits
(``splrep``: the smoothing condition on FITPACK's knots, interpolation, least squares on given
knots) and lekalo's evaluation, integrals and derivatives (``splev``, ``splint``, ``spalde``,
``splder``, ``splantider``). The 2-D classes ``RectBivariateSpline`` (FITPACK's ``regrid``:
lekalo's ``fit_tensor_grid_smoothing``), ``SmoothBivariateSpline`` (FITPACK's ``surfit``:
lekalo's ``fit_tensor_scattered_smoothing``) and ``LSQBivariateSpline`` (lekalo's
``fit_tensor_scattered``), evaluated, differentiated and integrated by lekalo's
``TensorBSpline``."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .. import _lekalo
from ._bivariate import (
    _SURFIT_MESSAGES,
    _box,
    _dblint,
    _evaluate,
    _finite_box,
    _grid_of_infinite_box,
    _surfit,
    _tensor,
    _value,
)
from ._bspline import _one_number, _pad_rows
from ._fitpack import _splrep_rounds, spalde, splantider, splder, splev, splint, sproot
from ._interpolate import make_lsq_spline

_EXTRAP_MODES = {0: 0, "extrapolate": 0, 1: 1, "zeros": 1, 2: 2, "raise": 2, 3: 3, "const": 3}


def _ext_mode(ext: Any) -> int:
    try:
        return _EXTRAP_MODES[ext]
    except (KeyError, TypeError):
        raise ValueError(f"Unknown extrapolation mode {ext}.") from None


class UnivariateSpline:
    """``scipy.interpolate.UnivariateSpline``: the spline of degree ``k`` on FITPACK's knots whose
    weighted residual ``Σ (w_i (y_i − s(x_i)))²`` is ``s`` (``len(w)`` by default), lekalo's
    ``splrep`` with SciPy's knot limit: the rounds stop at ``max(m // 2, 2k + 2)`` knots and go
    on from there, as SciPy's second ``curfit`` call (lekalo's ``fit_smoothing_condition(nest=…,
    resume=True)``), whose ``report["rounds"]`` ``set_smoothing_factor`` continues."""

    def __init__(
        self, x: Any, y: Any, w: Any = None, bbox: Any = (None, None), k: int = 3, s: Any = None,
        ext: Any = 0, check_finite: bool = False,
    ) -> None:
        x, y, w, bbox, self.ext = self.validate_input(x, y, w, bbox, k, s, ext, check_finite)
        if s is None:
            s = float(len(x) if w is None else len(w))
        self._fit(x, y, w, bbox, k, s, None)
        self._reset_class()

    def _reset_class(self) -> None:
        """SciPy's change of class after a fit, from FITPACK's ``ier``: the interpolating spline
        (``ier = -1``, ``s = 0``) is an ``InterpolatedUnivariateSpline``, the least-squares
        polynomial (``ier = -2``, no interior knot) an ``LSQUnivariateSpline``; otherwise the
        class stays, and a user's subclass always keeps its own, as in SciPy."""
        k, s = self._data[5], self._data[6]
        if s == 0:
            cls = InterpolatedUnivariateSpline
        elif len(self._eval_args[0]) == 2 * k + 2:
            cls = LSQUnivariateSpline
        else:
            return
        if self.__class__ in (UnivariateSpline, InterpolatedUnivariateSpline, LSQUnivariateSpline):
            self.__class__ = cls

    @staticmethod
    def validate_input(x: Any, y: Any, w: Any, bbox: Any, k: int, s: Any, ext: Any, check_finite: bool):
        """SciPy's checks, in its order and words."""
        return UnivariateSpline._checked_input(x, y, w, bbox, k, s, ext, check_finite)

    @staticmethod
    def _checked_input(
        x: Any, y: Any, w: Any, bbox: Any, k: int, s: Any, ext: Any, check_finite: bool, strict: bool = False
    ):
        """``validate_input``; with ``strict`` (``InterpolatedUnivariateSpline``) also SciPy's
        "x must be strictly increasing", raised after the others as SciPy raises it, from the
        same one pass over ``x``."""
        x, y, bbox = np.asarray(x), np.asarray(y), np.asarray(bbox)
        if w is not None:
            w = np.asarray(w)
        if check_finite:
            w_finite = np.isfinite(w).all() if w is not None else True
            if not np.isfinite(x).all() or not np.isfinite(y).all() or not w_finite:
                raise ValueError("x and y array must not contain NaNs or infs.")
        increasing = True
        if s is None or s > 0:
            if strict:
                # one comparison a pair: strictly increasing, else whether increasing at all
                increasing = bool(np.all(x[1:] > x[:-1])) if x.ndim == 1 else bool(np.all(np.diff(x) > 0.0))
            if not (strict and increasing) and not np.all(np.diff(x) >= 0.0):
                raise ValueError("x must be increasing if s > 0")
        elif not np.all(np.diff(x) > 0.0):
            raise ValueError("x must be strictly increasing if s = 0")
        if x.size != y.size:
            raise ValueError("x and y should have a same length")
        elif w is not None and not x.size == y.size == w.size:
            raise ValueError("x, y, and w should have a same length")
        elif bbox.shape != (2,):
            raise ValueError("bbox shape should be (2,)")
        elif not (1 <= k <= 5):
            raise ValueError("k should be 1 <= k <= 5")
        elif s is not None and not s >= 0.0:
            raise ValueError("s should be s >= 0.0")
        ext = _ext_mode(ext)
        if not increasing:
            raise ValueError("x must be strictly increasing")
        return x, y, w, bbox, ext

    def _fit(self, x: Any, y: Any, w: Any, bbox: Any, k: int, s: float, t: Any) -> None:
        xb, xe = bbox
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        self._data = (x, y, w, xb, xe, k, s)
        # SciPy's curfit call: nest = max(m // 2, 2k + 2) knots, then on ier = 1 (nest reached)
        # a second call with iopt = 1 from the knots reached and nest = m + k + 1; the state of
        # the rounds kept for set_smoothing_factor (FITPACK's fpint, nrdata, ier)
        nest = None if s == 0 or t is not None else max(len(x) // 2, 2 * k + 2)
        self._eval_args, self._rounds = _splrep_rounds(x, y, w, xb, xe, k, 0, s, t, 0, 0, 1, nest=nest)
        self._set_residual()

    def _set_residual(self) -> None:
        """FITPACK's ``fp`` of the fit of ``self._data``: 0 for the interpolating spline."""
        x, y, w, _, _, _, s = self._data
        if s == 0:
            # FITPACK reports fp = 0 for the interpolating spline (s = 0), not the rounding left
            self._fp = 0.0
            return
        ww = np.ones_like(x) if w is None else np.asarray(w, dtype=np.float64)
        self._fp = float(np.sum((ww * (splev(x, self._eval_args) - y)) ** 2))

    @classmethod
    def _from_tck(cls, tck: Any, ext: int = 0) -> "UnivariateSpline":
        self = cls.__new__(cls)
        t, c, k = tck
        self._eval_args = tck
        self._data = (None, None, None, None, None, k, None)
        self._rounds = None
        self._fp = None
        self.ext = ext
        return self

    def __call__(self, x: Any, nu: int = 0, ext: Any = None) -> np.ndarray:
        if _one_number(x) is not None:  # splev's scalar call
            return splev(x, self._eval_args, der=nu, ext=self.ext if ext is None else _ext_mode(ext))
        x = np.asarray(x)
        if x.size == 0:
            return np.array([])
        ext = self.ext if ext is None else _ext_mode(ext)
        return splev(x, self._eval_args, der=nu, ext=ext)

    def get_knots(self) -> np.ndarray:
        t, _, k = self._eval_args
        return t[k : len(t) - k]

    def get_coeffs(self) -> np.ndarray:
        t, c, k = self._eval_args
        return c[: len(t) - k - 1]

    def get_residual(self) -> float:
        return self._fp

    def integral(self, a: float, b: float) -> float:
        return splint(a, b, self._eval_args)

    def derivatives(self, x: float) -> np.ndarray:
        return spalde(x, self._eval_args)

    def roots(self):
        """The zeros of the spline (cubic only, as FITPACK's ``sproot``)."""
        k = self._eval_args[2]
        if k == 3:
            t = self._eval_args[0]
            return sproot(self._eval_args, mest=3 * (len(t) - 7))
        raise NotImplementedError("finding roots unsupported for non-cubic splines")

    def derivative(self, n: int = 1) -> "UnivariateSpline":
        tck = splder(self._eval_args, n)
        # FITPACK's constant extrapolation of the spline is not that of its derivative
        return UnivariateSpline._from_tck(tck, ext=1 if self.ext == 3 else self.ext)

    def antiderivative(self, n: int = 1) -> "UnivariateSpline":
        return UnivariateSpline._from_tck(splantider(self._eval_args, n), ext=self.ext)

    def set_smoothing_factor(self, s: float) -> None:
        """Refit with the smoothing factor ``s``, continuing from the knots of the last fit as
        FITPACK's ``curfit`` with ``iopt=1`` (SciPy's ``fpcurf1``), lekalo's
        ``fit_smoothing_condition(start=...)``: where ``s`` is at least the residual of the
        least-squares polynomial, or the last fit had no interior knot, the rounds start over;
        otherwise the least-squares spline on the current knots is kept, or smoothed, when its
        residual is within or below ``s``, and gets knots added as the earlier rounds would have
        gone on when above, under SciPy's knot limit of the last fit. ``s = 0`` interpolates.
        After an interpolating fit (``s = 0``) FITPACK reads a residual it never set: that case
        raises ``NotImplementedError``."""
        x, y, w, xb, xe, k, s_old = self._data
        if x is None:
            raise TypeError(
                "set_smoothing_factor needs the data of a fit; this spline was made from knots and "
                "coefficients (a derivative or antiderivative): make a UnivariateSpline from the data"
            )
        if s_old is None:
            warnings.warn("smoothing factor unchanged for LSQ spline with fixed knots", stacklevel=2)
            return
        s = float(s)
        if not s >= 0.0:
            raise ValueError("s should be s >= 0.0")
        xb = x[0] if xb is None else float(xb)
        xe = x[-1] if xe is None else float(xe)
        if s > 0.0 and s_old == 0.0:
            # FITPACK's iopt=1 after s=0 reads a residual that its interpolation never set
            raise NotImplementedError(
                "lekalo.scipy: UnivariateSpline.set_smoothing_factor after an interpolating fit "
                "(s=0) is not available: make a new UnivariateSpline(x, y, s=s) instead"
            )
        if s == 0.0:
            self._fit(x, y, w, (xb, xe), k, s, None)
        else:
            self._data = (x, y, w, xb, xe, k, s)
            self._eval_args, self._rounds = _splrep_rounds(
                x, y, w, xb, xe, k, 0, s, None, 0, 0, 1, start=self._rounds
            )
            self._set_residual()
        self._reset_class()


class InterpolatedUnivariateSpline(UnivariateSpline):
    """``scipy.interpolate.InterpolatedUnivariateSpline``: the interpolating spline (``s = 0``).
    ``get_residual()`` is FITPACK's ``fp = 0`` for interpolation, as SciPy's (not the rounding
    left at the data)."""

    def __init__(
        self, x: Any, y: Any, w: Any = None, bbox: Any = (None, None), k: int = 3, ext: Any = 0,
        check_finite: bool = False,
    ) -> None:
        x, y, w, bbox, self.ext = self._checked_input(x, y, w, bbox, k, None, ext, check_finite, strict=True)
        self._fit(x, y, w, bbox, k, 0.0, None)


class LSQUnivariateSpline(UnivariateSpline):
    """``scipy.interpolate.LSQUnivariateSpline``: the weighted least-squares spline on the
    interior knots ``t`` (lekalo's ``make_lsq_spline``)."""

    def __init__(
        self, x: Any, y: Any, t: Any, w: Any = None, bbox: Any = (None, None), k: int = 3, ext: Any = 0,
        check_finite: bool = False,
    ) -> None:
        # (validate_input refuses a decreasing x, with s=None, in SciPy's first words)
        x, y, w, bbox, self.ext = self.validate_input(x, y, w, bbox, k, None, ext, check_finite)
        x = np.asarray(x, dtype=np.float64)
        # the ends not given in bbox are x[0] and x[-1], as SciPy reads them: an IndexError for
        # no data
        xb = x[0] if bbox[0] is None else float(bbox[0])
        xe = x[-1] if bbox[1] is None else float(bbox[1])
        t = np.asarray(t, dtype=np.float64)
        # FITPACK's first check of the knots (fpchec): sorted, strictly inside [xb, xe]; lekalo's
        # make_lsq_spline checks the Schoenberg-Whitney conditions on the data
        inner = np.concatenate([[xb], t, [xe]])
        if not (np.all(inner[1:] >= inner[:-1]) and inner[0] < inner[1] and inner[-2] < inner[-1]):
            raise ValueError("Interior knots t must satisfy Schoenberg-Whitney conditions")
        if x.shape[0] < k + 1:
            # FITPACK's fpchec (k + 1 <= n - k - 1 <= m), SciPy's ValueError
            raise ValueError(
                "The input parameters have been rejected by fpchec: the spline of degree k needs "
                f"at least k + 1 = {k + 1} data points, got {x.shape[0]}"
            )
        tt = np.concatenate([[xb] * (k + 1), t, [xe] * (k + 1)])
        # make_lsq_spline's checks that lekalo's fit does not make in SciPy's words (x is sorted:
        # validate_input); finiteness, lengths and Schoenberg-Whitney are lekalo's
        if x[0] < xb or x[-1] > xe:
            raise ValueError(f"Out of bounds w/ x = {x}.")
        # the fit and FITPACK's fp, sum((w * (s(x) - y))**2), the squares reflected out of the
        # banded QR (no evaluation pass over the data)
        curve, fp = _lekalo.make_lsq_spline_fp(
            x, np.asarray(y, dtype=np.float64), tt, k, None if w is None else np.asarray(w, dtype=np.float64)
        )
        c = np.ascontiguousarray(curve.control[:, 0])
        self._data = (x, y, w, xb, xe, k, None)
        self._eval_args = (tt, _pad_rows(c, tt.shape[0]), k)
        self._fp = fp


# -- the 2-D FITPACK classes (docs/scipy.md): tensor-product splines of lekalo's core --------


class _BivariateSplineBase:
    """SciPy's base of the 2-D FITPACK classes: ``tck = (tx, ty, c)`` (``c`` flat, ``x``
    slowest) and ``degrees = (kx, ky)``, evaluated by lekalo's ``TensorBSpline``."""

    @classmethod
    def _from_tck(cls, tck: Any):
        self = cls.__new__(cls)
        if len(tck) != 5:
            raise ValueError("tck should be a 5 element tuple of tx, ty, c, kx, ky")
        self.tck = tuple(tck[:3])
        self.degrees = tuple(tck[3:])
        return self

    def get_residual(self) -> float:
        """The weighted residual sum of squares of the fit (FITPACK's ``fp``)."""
        return self.fp

    def get_knots(self):
        """The knot vectors ``(tx, ty)``, end knots included."""
        return self.tck[:2]

    def get_coeffs(self) -> np.ndarray:
        """The coefficients, flat (``x`` slowest)."""
        return self.tck[2]

    def __call__(self, x: Any, y: Any, dx: int = 0, dy: int = 0, grid: bool = True) -> np.ndarray:
        """The spline (or its partial derivative ``(dx, dy)``) on the grid ``x × y`` (``grid``,
        shape ``(len(x), len(y))``, both increasing) or at the points ``(x, y)`` broadcast. One
        number each (values only): lekalo's ``tensor_value`` on the arrays in place, the array
        call's bits in its shape."""
        if not dx and not dy:
            xf, yf = _one_number(x), _one_number(y)
            if xf is not None and yf is not None:
                v = _value(self.tck, self.degrees, xf, yf)
                if v is not None:
                    if not grid:
                        return np.array(v)
                    out = np.empty((1, 1))  # (quicker than np.array([[v]]), the same array)
                    out[0, 0] = v
                    return out
        x = np.asarray(x)
        y = np.asarray(y)
        dtype = np.asarray(self.tck[2]).dtype
        if grid:
            if x.size == 0 or y.size == 0:
                return np.zeros((x.size, y.size), dtype=dtype)
            if x.size >= 2 and not np.all(np.diff(x.ravel()) >= 0.0):
                raise ValueError("x must be strictly increasing when `grid` is True")
            if y.size >= 2 and not np.all(np.diff(y.ravel()) >= 0.0):
                raise ValueError("y must be strictly increasing when `grid` is True")
            return _evaluate(self.tck, self.degrees, x, y, dx, dy, True)
        if x.shape != y.shape:
            x, y = np.broadcast_arrays(x, y)
        if x.size == 0:
            return np.zeros(x.shape, dtype=dtype)
        return _evaluate(self.tck, self.degrees, x, y, dx, dy, False)

    def partial_derivative(self, dx: int, dy: int):
        """The partial derivative ``(dx, dy)`` as a spline of degrees ``(kx - dx, ky - dy)``
        (lekalo's ``TensorBSpline.derivative``)."""
        if dx == 0 and dy == 0:
            return self
        kx, ky = self.degrees
        if not (dx >= 0 and dy >= 0):
            raise ValueError("order of derivative must be positive or zero")
        if not (dx < kx and dy < ky):
            raise ValueError("order of derivative must be less than degree of spline")
        tx, ty = (np.asarray(t, dtype=np.float64) for t in self.tck[:2])
        if not _finite_box(tx, ty):
            # an infinite end of the box: FITPACK's pardtc drops dx (dy) knots at each end and
            # its coefficients are NaN, as every value of such a spline
            tx, ty = tx[dx : len(tx) - dx], ty[dy : len(ty) - dy]
            size = (len(tx) - (kx - dx) - 1) * (len(ty) - (ky - dy) - 1)
            return _DerivedBivariateSpline._from_tck((tx, ty, np.full(size, np.nan), kx - dx, ky - dy))
        d = _tensor(*self.tck, kx, ky).derivative([int(dx), int(dy)])
        tx, ty = d.t
        return _DerivedBivariateSpline._from_tck(
            (np.asarray(tx), np.asarray(ty), np.asarray(d.c).ravel(), kx - dx, ky - dy)
        )


class BivariateSpline(_BivariateSplineBase):
    """``scipy.interpolate.BivariateSpline``: evaluation (``ev``) and integrals of the 2-D
    splines."""

    def ev(self, xi: Any, yi: Any, dx: int = 0, dy: int = 0) -> np.ndarray:
        """The spline at the points ``(xi[i], yi[i])``."""
        xf, yf = _one_number(xi), _one_number(yi)
        if xf is not None and yf is not None and not dx and not dy:
            v = _value(self.tck, self.degrees, xf, yf)
            if v is not None:
                return np.array(v)
        return self.__call__(xi, yi, dx=dx, dy=dy, grid=False)

    def integral(self, xa: float, xb: float, ya: float, yb: float) -> float:
        """``∫_xa^xb ∫_ya^yb s(x, y) dy dx`` over the base box (limits taken into it, as
        FITPACK's ``dblint``), lekalo's ``TensorBSpline.integral``."""
        return _dblint(self.tck, self.degrees, xa, xb, ya, yb)

    @staticmethod
    def _validate_input(x: Any, y: Any, z: Any, w: Any, kx: int, ky: int, eps: Any):
        x, y, z = np.asarray(x), np.asarray(y), np.asarray(z)
        if not x.size == y.size == z.size:
            raise ValueError("x, y, and z should have a same length")
        if w is not None:
            w = np.asarray(w)
            if x.size != w.size:
                raise ValueError("x, y, z, and w should have a same length")
            elif not np.all(w >= 0.0):
                raise ValueError("w should be positive")
        if (eps is not None) and (not 0.0 < eps < 1.0):
            raise ValueError("eps should be between (0, 1)")
        if not x.size >= (kx + 1) * (ky + 1):
            raise ValueError("The length of x, y and z should be at least (kx+1) * (ky+1)")
        return x, y, z, w


class _DerivedBivariateSpline(_BivariateSplineBase):
    """A partial derivative of a 2-D spline: no data, so no residual."""

    _invalid_why = (
        "is unavailable, because _DerivedBivariateSpline instance is not constructed from data "
        "that are to be interpolated or smoothed, but derived from the underlying knots and "
        "coefficients of another spline object"
    )

    @property
    def fp(self):
        raise AttributeError(f'attribute "fp" {self._invalid_why}')

    def get_residual(self):
        raise AttributeError(f'method "get_residual" {self._invalid_why}')


class RectBivariateSpline(BivariateSpline):
    """``scipy.interpolate.RectBivariateSpline(x, y, z, bbox, kx, ky, s, maxit)``: the spline on
    the grid ``x × y`` with FITPACK's knots whose residual sum of squares is at most ``s``
    (``s = 0``: interpolation), lekalo's ``fit_tensor_grid_smoothing``
    (``docs/theory/tensor.md#smoothing-on-grids``). lekalo's iteration for the smoothing weight
    keeps the residual at or below ``s`` and its own bound on the iterations; ``maxit`` is
    accepted and not used. Values that are NaN or infinite give, as SciPy, the knots of
    interpolation, ``fp = 0`` and NaN coefficients (SciPy leaves its last row and column
    finite, an accident of its order of rotations; here every one is NaN)."""

    def __init__(
        self, x: Any, y: Any, z: Any, bbox: Any = [None] * 4, kx: int = 3, ky: int = 3, s: Any = 0,  # noqa: B006
        maxit: int = 20,
    ) -> None:
        x, y, bbox = np.ravel(x), np.ravel(y), np.ravel(np.asarray(bbox, dtype=object))
        z = np.asarray(z)
        if not np.all(np.diff(x) > 0.0):
            raise ValueError("x must be strictly increasing")
        if not np.all(np.diff(y) > 0.0):
            raise ValueError("y must be strictly increasing")
        if not x.size == z.shape[0]:
            raise ValueError("x dimension of z must have same number of elements as x")
        if not y.size == z.shape[1]:
            raise ValueError("y dimension of z must have same number of elements as y")
        if not bbox.shape == (4,):
            raise ValueError("bbox shape should be (4,)")
        if s is not None and not s >= 0.0:
            raise ValueError("s should be s >= 0.0")
        del maxit
        x = np.ascontiguousarray(x, dtype=np.float64)
        y = np.ascontiguousarray(y, dtype=np.float64)
        xb, xe, yb, ye = (None if b is None else float(b) for b in bbox)
        box = [
            (x[0] if xb is None else xb, x[-1] if xe is None else xe),
            (y[0] if yb is None else yb, y[-1] if ye is None else ye),
        ]
        z = np.ascontiguousarray(z, dtype=np.float64)
        s = float(0.0 if s is None else s)
        infinite = _grid_of_infinite_box(x, y, box, kx, ky)
        if infinite is not None:
            # an infinite end of the box: SciPy's knots of interpolation, fp = 0, NaN values
            self.fp = 0.0
            self.tck = infinite
            self.degrees = kx, ky
            return
        try:
            spline, fp, _ = _lekalo.fit_tensor_grid_smoothing([x, y], z, s, [int(kx), int(ky)], bbox=box)
            c = np.asarray(spline.c).ravel()
        except ValueError:
            if np.isfinite(z).all():
                raise
            # values that are NaN or infinite: FITPACK's residuals are NaN, so no knot set is
            # accepted before the knots of interpolation (whatever s), where its fpregr sets
            # fp = 0, and the solve spreads the NaN over the coefficients; the same knots here
            # (lekalo's, which do not depend on the values), fp = 0 and every coefficient NaN
            spline, _, _ = _lekalo.fit_tensor_grid_smoothing(
                [x, y], np.zeros_like(z), 0.0, [int(kx), int(ky)], bbox=box
            )
            fp, c = 0.0, np.full(np.asarray(spline.c).size, np.nan)
        tx, ty = spline.t
        self.fp = fp
        self.tck = (np.asarray(tx), np.asarray(ty), c)
        self.degrees = kx, ky


class SmoothBivariateSpline(BivariateSpline):
    """``scipy.interpolate.SmoothBivariateSpline(x, y, z, w, bbox, kx, ky, s, eps)``: the spline
    on scattered points with FITPACK ``surfit``'s knots whose weighted residual is ``s``
    (``len(x)`` by default), lekalo's ``fit_tensor_scattered_smoothing``
    (``docs/theory/tensor.md#smoothing-scattered-data``), SciPy's knot bounds
    ``nxest = max(kx + 1 + sqrt(m/2), 2(kx + 1))`` and FITPACK's minimal-norm solution of a
    rank-deficient system with the threshold ``eps``. lekalo's iteration for the smoothing
    weight keeps the residual at or below ``s``; SciPy warns as FITPACK reports."""

    def __init__(
        self, x: Any, y: Any, z: Any, w: Any = None, bbox: Any = [None] * 4,  # noqa: B006
        kx: int = 3, ky: int = 3, s: Any = None, eps: float = 1e-16,
    ) -> None:
        x, y, z, w = self._validate_input(x, y, z, w, kx, ky, eps)
        bbox = np.ravel(np.asarray(bbox, dtype=object))
        if not bbox.shape == (4,):
            raise ValueError("bbox shape should be (4,)")
        if s is not None and not s >= 0.0:
            raise ValueError("s should be s >= 0.0")
        x = np.asarray(x, dtype=np.float64).ravel()
        y = np.asarray(y, dtype=np.float64).ravel()
        z = np.asarray(z, dtype=np.float64).ravel()
        m = x.size
        nxest = max(int(kx + 1 + np.sqrt(m / 2)), 2 * (kx + 1))
        nyest = max(int(ky + 1 + np.sqrt(m / 2)), 2 * (ky + 1))
        s = float(m) if s is None else float(s)
        tx, ty, c, fp, ier = _surfit(
            x, y, z, w, _box(x, y, bbox), kx, ky, s, 1e-16 if eps is None else eps, nxest, nyest
        )
        if ier not in (0, -1, -2):
            warnings.warn(_SURFIT_MESSAGES.get(ier, f"ier={ier}"), stacklevel=2)
        self.fp = fp
        self.tck = (tx, ty, c)
        self.degrees = kx, ky


def _default_lower(data: np.ndarray, t: np.ndarray) -> float:
    """SciPy's default lower bound of the box of ``LSQBivariateSpline`` (its ``calc_b`` over the
    knot array ``t`` of length ``nx``, end places included): the data's minimum unless a knot
    place lies at or below it, else that place minus the knot array's span over its length."""
    v1, v2 = float(data.min()), float(t.min())
    if v2 > v1:
        return v1
    return v2 - (float(t.max()) - v2) / len(t)


def _default_upper(data: np.ndarray, t: np.ndarray) -> float:
    """SciPy's default upper bound (``calc_e``), the mirror of :func:`_default_lower`."""
    v1, v2 = float(data.max()), float(t.max())
    if v2 < v1:
        return v1
    return v2 + (v2 - float(t.min())) / len(t)


class LSQBivariateSpline(BivariateSpline):
    """``scipy.interpolate.LSQBivariateSpline(x, y, z, tx, ty, w, bbox, kx, ky, eps)``: the
    weighted least-squares spline on scattered points with the interior knots ``tx``, ``ty``,
    lekalo's ``fit_tensor_scattered`` with FITPACK's minimal-norm solution of a rank-deficient
    system (threshold ``eps``, default ``1e-16``; SciPy's warning names the deficiency).
    FITPACK's weights multiply the residual: lekalo's are their squares. The box entries left
    ``None`` take SciPy's defaults: computed from the data and the knot array of length ``nx``
    whose end places hold zeros (the box then reaches beyond the data whenever ``0`` is at or
    below the smallest coordinate), and, when the system is rank deficient, computed once more
    from the knot array holding the first box, as SciPy's second call of ``surfit`` does."""

    def __init__(
        self, x: Any, y: Any, z: Any, tx: Any, ty: Any, w: Any = None, bbox: Any = [None] * 4,  # noqa: B006
        kx: int = 3, ky: int = 3, eps: Any = None,
    ) -> None:
        x, y, z, w = self._validate_input(x, y, z, w, kx, ky, eps)
        bbox = np.ravel(np.asarray(bbox, dtype=object))
        if not bbox.shape == (4,):
            raise ValueError("bbox shape should be (4,)")
        x = np.asarray(x, dtype=np.float64).ravel()
        y = np.asarray(y, dtype=np.float64).ravel()
        z = np.asarray(z, dtype=np.float64).ravel()
        tx = np.asarray(tx, dtype=np.float64).ravel()
        ty = np.asarray(ty, dtype=np.float64).ravel()
        nx, ny = 2 * kx + 2 + len(tx), 2 * ky + 2 + len(ty)
        tx1, ty1 = np.zeros(nx), np.zeros(ny)
        tx1[kx + 1 : nx - kx - 1] = tx
        ty1[ky + 1 : ny - ky - 1] = ty
        given = [None if b is None else float(b) for b in bbox]
        ww = None if w is None else np.asarray(w, dtype=np.float64) ** 2
        pts = np.ascontiguousarray(np.stack([x, y], axis=-1))
        eps = 1e-16 if eps is None else float(eps)
        ncof = (nx - kx - 1) * (ny - ky - 1)
        for attempt in range(2):
            xb, xe, yb, ye = (
                _default_lower(x, tx1) if given[0] is None else given[0],
                _default_upper(x, tx1) if given[1] is None else given[1],
                _default_lower(y, ty1) if given[2] is None else given[2],
                _default_upper(y, ty1) if given[3] is None else given[3],
            )
            tx1[: kx + 1], tx1[nx - kx - 1 :] = xb, xe
            ty1[: ky + 1], ty1[ny - ky - 1 :] = yb, ye
            spline, _, fp, rank = _lekalo.fit_tensor_scattered(
                pts, z, (tx1.copy(), ty1.copy()), [int(kx), int(ky)], w=ww, eps=eps,
                full_output=True,
            )
            if rank == ncof or attempt == 1 or all(g is not None for g in given):
                break
        # FITPACK reports ier = -rank; SciPy warns for ier < -2
        if rank < ncof and rank > 2:
            warnings.warn(_SURFIT_MESSAGES[-3] % (ncof - rank), stacklevel=2)
        self.fp = fp
        t0, t1 = spline.t
        self.tck = (np.asarray(t0), np.asarray(t1), np.asarray(spline.c).ravel())
        self.degrees = kx, ky
