"""``UnivariateSpline``, ``InterpolatedUnivariateSpline`` and ``LSQUnivariateSpline`` of
``lekalo.scipy``: SciPy's object interface to FITPACK's ``curfit``, over lekalo's fits
(``splrep``: the smoothing condition on FITPACK's knots, interpolation, least squares on given
knots) and lekalo's evaluation, integrals and derivatives (``splev``, ``splint``, ``spalde``,
``splder``, ``splantider``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._bspline import _pad_rows
from ._fitpack import spalde, splantider, splder, splev, splint, splrep, sproot
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
    ``splrep``."""

    def __init__(
        self, x: Any, y: Any, w: Any = None, bbox: Any = (None, None), k: int = 3, s: Any = None,
        ext: Any = 0, check_finite: bool = False,
    ) -> None:
        x, y, w, bbox, self.ext = self.validate_input(x, y, w, bbox, k, s, ext, check_finite)
        if s is None:
            s = float(len(x) if w is None else len(w))
        self._fit(x, y, w, bbox, k, s, None)

    @staticmethod
    def validate_input(x: Any, y: Any, w: Any, bbox: Any, k: int, s: Any, ext: Any, check_finite: bool):
        """SciPy's checks, in its order and words."""
        x, y, bbox = np.asarray(x), np.asarray(y), np.asarray(bbox)
        if w is not None:
            w = np.asarray(w)
        if check_finite:
            w_finite = np.isfinite(w).all() if w is not None else True
            if not np.isfinite(x).all() or not np.isfinite(y).all() or not w_finite:
                raise ValueError("x and y array must not contain NaNs or infs.")
        if s is None or s > 0:
            if not np.all(np.diff(x) >= 0.0):
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
        return x, y, w, bbox, _ext_mode(ext)

    def _fit(self, x: Any, y: Any, w: Any, bbox: Any, k: int, s: float, t: Any) -> None:
        xb, xe = bbox
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        self._data = (x, y, w, xb, xe, k, s)
        self._eval_args = splrep(x, y, w=w, xb=xb, xe=xe, k=k, s=s, t=t)
        ww = np.ones_like(x) if w is None else np.asarray(w, dtype=np.float64)
        self._fp = float(np.sum((ww * (splev(x, self._eval_args) - y)) ** 2))

    @classmethod
    def _from_tck(cls, tck: Any, ext: int = 0) -> "UnivariateSpline":
        self = cls.__new__(cls)
        t, c, k = tck
        self._eval_args = tck
        self._data = (None, None, None, None, None, k, None)
        self._fp = None
        self.ext = ext
        return self

    def __call__(self, x: Any, nu: int = 0, ext: Any = None) -> np.ndarray:
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
        raise NotImplementedError("lekalo.scipy: UnivariateSpline.set_smoothing_factor is not available yet")


class InterpolatedUnivariateSpline(UnivariateSpline):
    """``scipy.interpolate.InterpolatedUnivariateSpline``: the interpolating spline (``s = 0``)."""

    def __init__(
        self, x: Any, y: Any, w: Any = None, bbox: Any = (None, None), k: int = 3, ext: Any = 0,
        check_finite: bool = False,
    ) -> None:
        x, y, w, bbox, self.ext = self.validate_input(x, y, w, bbox, k, None, ext, check_finite)
        if not np.all(np.diff(x) > 0.0):
            raise ValueError("x must be strictly increasing")
        self._fit(x, y, w, bbox, k, 0.0, None)
        self._fp = 0.0


class LSQUnivariateSpline(UnivariateSpline):
    """``scipy.interpolate.LSQUnivariateSpline``: the weighted least-squares spline on the
    interior knots ``t`` (lekalo's ``make_lsq_spline``)."""

    def __init__(
        self, x: Any, y: Any, t: Any, w: Any = None, bbox: Any = (None, None), k: int = 3, ext: Any = 0,
        check_finite: bool = False,
    ) -> None:
        x, y, w, bbox, self.ext = self.validate_input(x, y, w, bbox, k, None, ext, check_finite)
        if not np.all(np.diff(x) >= 0.0):
            raise ValueError("x must be increasing")
        x = np.asarray(x, dtype=np.float64)
        xb = x[0] if bbox[0] is None else float(bbox[0])
        xe = x[-1] if bbox[1] is None else float(bbox[1])
        t = np.asarray(t, dtype=np.float64)
        # FITPACK's first check of the knots (fpchec): sorted, strictly inside [xb, xe]; lekalo's
        # make_lsq_spline checks the Schoenberg-Whitney conditions on the data
        inner = np.concatenate([[xb], t, [xe]])
        if not (np.all(inner[1:] >= inner[:-1]) and inner[0] < inner[1] and inner[-2] < inner[-1]):
            raise ValueError("Interior knots t must satisfy Schoenberg-Whitney conditions")
        tt = np.concatenate([[xb] * (k + 1), t, [xe] * (k + 1)])
        spl = make_lsq_spline(x, np.asarray(y, dtype=np.float64), tt, k, w=w)
        self._data = (x, y, w, xb, xe, k, None)
        self._eval_args = (spl.t, _pad_rows(spl.c, spl.t.shape[0]), k)
        ww = np.ones_like(x) if w is None else np.asarray(w, dtype=np.float64)
        self._fp = float(np.sum((ww * (spl(x) - y)) ** 2))
