"""SciPy's spherical 2-D classes over lekalo's fits on the sphere (``docs/theory/sphere.md``):
``LSQSphereBivariateSpline`` (FITPACK ``sphere`` on given knots: lekalo's
``fit_sphere_least_squares``), ``SmoothSphereBivariateSpline`` (FITPACK ``sphere`` with the
smoothing condition: ``fit_sphere_smoothing``) and ``RectSphereBivariateSpline`` (FITPACK
``spgrid``: ``fit_sphere_grid``). Each keeps SciPy's signature, checks and messages, and holds
its result as SciPy does, ``tck = (tt, tp, c)`` with degrees ``(3, 3)``, evaluated,
differentiated and integrated by the bivariate base of ``_fitpack2`` (lekalo's
``TensorBSpline``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import _lekalo
from ._fitpack2 import _BivariateSplineBase

_LIMIT_MESSAGES = {
    "max-knots": (
        "The required storage space exceeds the available storage space: nxest or nyest too "
        "small, or s too small. The weighted least-squares spline corresponds to the current "
        "set of knots."
    ),
    "too-many-unknowns": (
        "No more knots can be added because the number of B-spline coefficients already "
        "exceeds the number of data points m: either s or m too small. The weighted "
        "least-squares spline corresponds to the current set of knots."
    ),
    "no-span": (
        "No more knots can be added because the additional knot would coincide with an old "
        "one: either s too small or too large a weight to an inaccurate data point. The "
        "weighted least-squares spline corresponds to the current set of knots."
    ),
}


def _tck(spline: Any) -> tuple:
    tt, tp = spline.t
    return np.asarray(tt), np.asarray(tp), np.asarray(spline.c).ravel()


class SphereBivariateSpline(_BivariateSplineBase):
    """``scipy.interpolate.SphereBivariateSpline``: a bivariate spline in ``(theta, phi)`` on
    the sphere, evaluated with SciPy's argument names."""

    def __call__(self, theta: Any, phi: Any, dtheta: int = 0, dphi: int = 0, grid: bool = True):
        """The spline (or its partial derivative ``(dtheta, dphi)``) on the grid
        ``theta × phi`` or at the points ``(theta, phi)`` (``grid=False``)."""
        theta = np.asarray(theta)
        phi = np.asarray(phi)
        if theta.size > 0 and (theta.min() < 0.0 or theta.max() > np.pi):
            raise ValueError("requested theta out of bounds.")
        return _BivariateSplineBase.__call__(self, theta, phi, dx=dtheta, dy=dphi, grid=grid)

    def ev(self, theta: Any, phi: Any, dtheta: int = 0, dphi: int = 0):
        """The spline at the points ``(theta[i], phi[i])``."""
        return self.__call__(theta, phi, dtheta=dtheta, dphi=dphi, grid=False)


def _check_scattered(theta: Any, phi: Any, w: Any):
    theta, phi = np.asarray(theta, dtype=np.float64), np.asarray(phi, dtype=np.float64)
    if not ((0.0 <= theta).all() and (theta <= np.pi).all()):
        raise ValueError("theta should be between [0, pi]")
    if not ((0.0 <= phi).all() and (phi <= 2.0 * np.pi).all()):
        raise ValueError("phi should be between [0, 2pi]")
    if w is not None:
        w = np.asarray(w, dtype=np.float64)
        if not (w >= 0.0).all():
            raise ValueError("w should be positive")
        if w.ndim == 0:
            w = np.full(theta.size, float(w))
        w = w.ravel()
    return theta.ravel(), phi.ravel(), w


class _ScatteredSphere(SphereBivariateSpline):
    def __call__(self, theta: Any, phi: Any, dtheta: int = 0, dphi: int = 0, grid: bool = True):
        """As :meth:`SphereBivariateSpline.__call__`; ``phi`` must lie in ``[0, 2 pi]``."""
        phi = np.asarray(phi)
        if phi.size > 0 and (phi.min() < 0.0 or phi.max() > 2.0 * np.pi):
            raise ValueError("requested phi out of bounds.")
        return SphereBivariateSpline.__call__(self, theta, phi, dtheta=dtheta, dphi=dphi, grid=grid)


class SmoothSphereBivariateSpline(_ScatteredSphere):
    """``scipy.interpolate.SmoothSphereBivariateSpline(theta, phi, r, w, s, eps)``: the bicubic
    spline on the sphere with FITPACK ``sphere``'s knots whose weighted residual
    ``sum((w (r - s))**2)`` is ``s`` (lekalo's ``fit_sphere_smoothing``); one value at each
    pole and continuous derivatives across them. lekalo's iteration for the smoothing weight
    keeps the residual at or below ``s``. SciPy's ``ValueError`` when the knot rounds stop
    above ``s``."""

    def __init__(self, theta: Any, phi: Any, r: Any, w: Any = None, s: float = 0.0, eps: float = 1e-16) -> None:
        theta, phi, w = _check_scattered(theta, phi, w)
        if not s >= 0.0:
            raise ValueError("s should be positive")
        if not 0.0 < eps < 1.0:
            raise ValueError("eps should be between (0, 1)")
        r = np.asarray(r, dtype=np.float64).ravel()
        spline, fp, _p, _rank, limit = _lekalo.fit_sphere_smoothing(theta, phi, r, float(s), w=w, eps=float(eps))
        if limit is not None:
            raise ValueError(_LIMIT_MESSAGES[limit])
        self.fp = fp
        self.tck = _tck(spline)
        self.degrees = (3, 3)


class LSQSphereBivariateSpline(_ScatteredSphere):
    """``scipy.interpolate.LSQSphereBivariateSpline(theta, phi, r, tt, tp, w, eps)``: the
    weighted least-squares bicubic spline on the sphere with the interior knots ``tt``
    (colatitude) and ``tp`` (longitude), one value at each pole and continuous derivatives
    across them (lekalo's ``fit_sphere_least_squares``; FITPACK's minimal-norm solution of a
    rank-deficient system, threshold ``eps``)."""

    def __init__(self, theta: Any, phi: Any, r: Any, tt: Any, tp: Any, w: Any = None, eps: float = 1e-16) -> None:
        theta, phi, w = _check_scattered(theta, phi, w)
        tt = np.asarray(tt, dtype=np.float64).ravel()
        tp = np.asarray(tp, dtype=np.float64).ravel()
        if not ((0.0 < tt).all() and (tt < np.pi).all()):
            raise ValueError("tt should be between (0, pi)")
        if not ((0.0 < tp).all() and (tp < 2 * np.pi).all()):
            raise ValueError("tp should be between (0, 2pi)")
        if not 0.0 < eps < 1.0:
            raise ValueError("eps should be between (0, 1)")
        r = np.asarray(r, dtype=np.float64).ravel()
        spline, fp, _p, _rank, _limit = _lekalo.fit_sphere_least_squares(
            theta, phi, r, tt, tp, w=w, eps=float(eps)
        )
        self.fp = fp
        self.tck = _tck(spline)
        self.degrees = (3, 3)


def _pair(value: Any) -> tuple:
    if isinstance(value, (bool, np.bool_)):
        return (bool(value), bool(value))
    return tuple(value)


class RectSphereBivariateSpline(SphereBivariateSpline):
    """``scipy.interpolate.RectSphereBivariateSpline(u, v, r, s, pole_continuity, pole_values,
    pole_exact, pole_flat)``: the bicubic spline on the grid ``u × v`` of the sphere whose
    residual sum of squares is ``s`` (``0``: interpolation), with FITPACK ``spgrid``'s knots and
    pole conditions (lekalo's ``fit_sphere_grid``). Pole values and derivatives left free are
    the optimal ones (exactly; FITPACK estimates them by finite differences)."""

    def __init__(
        self, u: Any, v: Any, r: Any, s: float = 0.0, pole_continuity: Any = False,
        pole_values: Any = None, pole_exact: Any = False, pole_flat: Any = False,
    ) -> None:
        if pole_values is None:
            pole_values = (None, None)
        elif isinstance(pole_values, (float, int, np.floating, np.integer)):
            pole_values = (pole_values, pole_values)
        pole_continuity = _pair(pole_continuity)
        pole_exact = _pair(pole_exact)
        pole_flat = _pair(pole_flat)
        u, v = np.ravel(u).astype(np.float64), np.ravel(v).astype(np.float64)
        r = np.asarray(r, dtype=np.float64)
        if not (0.0 < u[0] and u[-1] < np.pi):
            raise ValueError("u should be between (0, pi)")
        if not -np.pi <= v[0] < np.pi:
            raise ValueError("v[0] should be between [-pi, pi)")
        if not v[-1] <= v[0] + 2 * np.pi:
            raise ValueError("v[-1] should be v[0] + 2pi or less ")
        if not np.all(np.diff(u) > 0.0):
            raise ValueError("u must be strictly increasing")
        if not np.all(np.diff(v) > 0.0):
            raise ValueError("v must be strictly increasing")
        if not u.size == r.shape[0]:
            raise ValueError("u dimension of r must have same number of elements as u")
        if not v.size == r.shape[1]:
            raise ValueError("v dimension of r must have same number of elements as v")
        if pole_continuity[1] is False and pole_flat[1] is True:
            raise ValueError("if pole_continuity is False, so must be pole_flat")
        if pole_continuity[0] is False and pole_flat[0] is True:
            raise ValueError("if pole_continuity is False, so must be pole_flat")
        if not s >= 0.0:
            raise ValueError("s should be positive")
        values = tuple(None if x is None else float(x) for x in pole_values)
        spline, fp, _p, _rank, _limit = _lekalo.fit_sphere_grid(
            u, v, np.ascontiguousarray(r), float(s), pole_values=values,
            pole_exact=tuple(bool(x) for x in pole_exact),
            pole_continuity=tuple(bool(x) for x in pole_continuity),
            pole_flat=tuple(bool(x) for x in pole_flat),
        )
        self.fp = fp
        self.tck = _tck(spline)
        self.degrees = (3, 3)
        self.v0 = v[0]

    def __call__(self, theta: Any, phi: Any, dtheta: int = 0, dphi: int = 0, grid: bool = True):
        """As :meth:`SphereBivariateSpline.__call__`."""
        return SphereBivariateSpline.__call__(self, theta, phi, dtheta=dtheta, dphi=dphi, grid=grid)
