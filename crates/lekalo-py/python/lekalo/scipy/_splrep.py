"""``make_splrep``, ``make_splprep`` and ``generate_knots`` of ``lekalo.scipy``: SciPy's
smoothing condition (``Σ (w_k (y_k − f(x_k)))² ≤ s`` with FITPACK's knots, or least jumps on
given knots), solved by lekalo's ``make_splrep``, ``make_splprep``, ``fit_periodic`` and
``generate_knots`` (``docs/theory/fitting.md#smoothing-condition``,
``#smoothing-on-given-knots``)."""

from __future__ import annotations

import operator
from typing import Any

import numpy as np

from .. import _lekalo
from ._bspline import BSpline
from ._interpolate import make_interp_spline


def _validate_bc_type(bc_type: Any) -> str:
    if bc_type is None:
        return "not-a-knot"
    if bc_type not in ("not-a-knot", "periodic"):
        raise ValueError(
            f"Only 'not-a-knot' and 'periodic' boundary conditions are recognised, found {bc_type}"
        )
    return bc_type


def _validate_inputs(x: Any, y: Any, w: Any, k: Any, s: float, xb: Any, xe: Any, parametric: bool, periodic: bool):
    """SciPy's checks of the data (``_fitpack_repro._validate_inputs``), in its order and words."""
    x = np.ascontiguousarray(x, dtype=float)
    y = np.ascontiguousarray(y, dtype=float)
    if w is None:
        w = np.ones_like(x, dtype=float)
    else:
        w = np.ascontiguousarray(w, dtype=float)
        if w.ndim != 1:
            raise ValueError(f"{w.ndim = } not implemented yet.")
        if (w < 0).any():
            raise ValueError("Weights must be non-negative")
        if w.sum() == 0:
            raise ValueError("All weights are zero.")
    if y.ndim == 0 or y.ndim > 2:
        raise ValueError(f"{y.ndim = } not supported (must be 1 or 2.)")
    if parametric:
        if y.ndim != 2:
            raise ValueError(f"{y.ndim = } != 2 not supported with {parametric =}.")
    elif y.ndim != 1:
        raise ValueError(f"{y.ndim = } != 1 not supported with {parametric =}.")
    if w.shape[0] != x.shape[0]:
        raise ValueError(f"Weights is incompatible: {w.shape =} != {x.shape}.")
    if x.shape[0] != y.shape[0]:
        raise ValueError(f"Data is incompatible: {x.shape = } and {y.shape = }.")
    if x.ndim != 1 or (x[1:] < x[:-1]).any():
        raise ValueError("Expect `x` to be an ordered 1D sequence.")
    k = operator.index(k)
    if s < 0:
        raise ValueError(f"`s` must be non-negative. Got {s = }")
    if periodic and not np.allclose(y[0], y[-1], atol=1e-15):
        raise ValueError(
            "First and last points does not match which is required for `bc_type='periodic'`."
        )
    return x, y, w, k


def _domain(x: np.ndarray, xb: Any, xe: Any, wider: bool):
    """``(xb, xe)`` when they reach beyond the data (lekalo's ``domain``), ``None`` when they are
    the data's ends; ``wider=False`` where only the data's ends are available."""
    lo = x.min() if xb is None else float(xb)
    hi = x.max() if xe is None else float(xe)
    if lo == x.min() and hi == x.max():
        return None
    if lo > x.min() or hi < x.max():
        raise ValueError(f"xb = {lo} and xe = {hi} must hold the data: xb <= {x.min()} and xe >= {x.max()}")
    if not wider:
        raise NotImplementedError(
            "lekalo.scipy: xb/xe wider than the data go with make_splrep's smoothing condition on "
            "FITPACK's knots (no t, nest or bc_type='periodic')"
        )
    return (lo, hi)


def _smooth(
    x: np.ndarray, y: np.ndarray, w: np.ndarray, k: int, s: float, t: Any, nest: Any, periodic: bool, domain: Any = None
):
    """The curve of the smoothing condition: on the knots ``t`` when given (lekalo's smoothing
    on given knots), else on FITPACK's knots, the last of ``generate_knots`` (lekalo's
    smoothing condition, its end knots at ``domain`` when given); SciPy's ``nest`` checks.
    ``y`` is ``(m,)`` or ``(m, dim)``."""
    if nest is not None:
        if nest < 2 * (k + 1):
            raise ValueError(f"`nest` too small: {nest = } < 2*(k+1) = {2*(k+1)}.")
        if t is not None:
            raise ValueError("Either supply `t` or `nest`.")
        # SciPy smooths on the last knot vector of generate_knots, stopped at nest knots
        t = _knot_sequence(x, y, w, k, s, nest, periodic)[-1]
    if t is not None:
        t = np.ascontiguousarray(t, dtype=float)
        if periodic:
            n = t.shape[0]
            curve, _ = _lekalo.fit_periodic(x, y, w=w * w, k=k, s=float(s), t=t[k + 1:n - k - 1])
            if n == 2 * (k + 1):
                # the least-squares constant, on the given knots as SciPy returns it
                return t, np.ascontiguousarray(curve.control[: k + 1])
        else:
            curve = _lekalo.make_splrep(x, y, w=w, k=k, s=float(s), t=t)
    elif periodic:
        curve, _ = _lekalo.fit_periodic(x, y, w=w * w, k=k, s=float(s))
    elif y.ndim == 1:
        curve = _lekalo.make_splrep(x, y, w=w, k=k, s=float(s), domain=domain, knot_rounds="refit")
    else:
        curve, _ = _lekalo.make_splprep(y, w=w, u=x, k=k, s=float(s), knot_rounds="refit")
    return np.ascontiguousarray(curve.knots), np.ascontiguousarray(curve.control)


def _knot_sequence(x: np.ndarray, y: np.ndarray, w: np.ndarray, k: int, s: float, nest: Any, periodic: bool) -> list:
    """lekalo's rounds of the smoothing condition (``generate_knots``; refitted after every
    knot as SciPy's, except the periodic rounds, which share them as FITPACK's ``fpperi``),
    SciPy's ``nest`` check."""
    if nest is not None and nest < 2 * (k + 1):
        raise ValueError(f"`nest` too small: {nest = } < 2*(k+1) = {2*(k+1)}.")
    rounds = None if periodic else "refit"
    return _lekalo.generate_knots(x, y, w=w, k=k, s=float(s), nest=nest, periodic=periodic, knot_rounds=rounds)


def generate_knots(
    x: Any, y: Any, *, w: Any = None, xb: Any = None, xe: Any = None, k: int = 3, s: float = 0,
    nest: Any = None, bc_type: Any = None,
):
    """``scipy.interpolate.generate_knots``: the knot vectors of FITPACK's rounds of the
    smoothing condition, each with more knots than the last (lekalo's ``generate_knots``); for
    ``s = 0`` only the knots of interpolation."""
    bc_type = _validate_bc_type(bc_type)
    periodic = bc_type == "periodic"
    if s == 0:
        if nest is not None or w is not None:
            raise ValueError("s == 0 is interpolation only")
        # SciPy's knots of interpolation: not-a-knot, periodic for k > 1
        xa = np.asarray(x)
        t = _knot_sequence(np.ascontiguousarray(xa, dtype=float), np.ascontiguousarray(y, dtype=float), None, k, 0.0, None, periodic and k > 1)[-1]
        if k % 2 == 1 and not (periodic and k > 1) and xa.dtype.kind in "iu":
            # the knots are data sites: SciPy keeps the sites' integer dtype
            t = t.astype(xa.dtype)
        yield t
        return
    x, y, w, k = _validate_inputs(x, y, w, k, s, xb, xe, parametric=np.ndim(y) == 2, periodic=periodic)
    _domain(x, xb, xe, wider=False)
    yield from _knot_sequence(x, y, w, k, s, nest, periodic)


def make_splrep(
    x: Any, y: Any, *, w: Any = None, xb: Any = None, xe: Any = None, k: int = 3, s: float = 0,
    t: Any = None, nest: Any = None, bc_type: Any = None,
) -> BSpline:
    """``scipy.interpolate.make_splrep``: with ``s = 0`` the interpolating spline, otherwise the
    spline on FITPACK's knots whose weighted residual is ``s`` (lekalo's ``make_splrep``, its end
    knots at ``xb``/``xe`` when they reach beyond the data; ``fit_periodic`` for
    ``bc_type="periodic"``)."""
    bc_type = _validate_bc_type(bc_type)
    if s == 0:
        if t is not None or w is not None or nest is not None:
            raise ValueError("s==0 is for interpolation only")
        return make_interp_spline(x, y, k=k, bc_type=bc_type)
    periodic = bc_type == "periodic"
    x, y, w, k = _validate_inputs(x, y, w, k, s, xb, xe, parametric=False, periodic=periodic)
    domain = _domain(x, xb, xe, wider=t is None and nest is None and not periodic)
    tt, c = _smooth(x, y, w, k, s, t, nest, periodic, domain)
    return BSpline(tt, c[:, 0], k)


def make_splprep(
    x: Any, *, w: Any = None, u: Any = None, ub: Any = None, ue: Any = None, k: int = 3, s: float = 0,
    t: Any = None, nest: Any = None, bc_type: Any = None,
):
    """``scipy.interpolate.make_splprep``: the parametric curve through (``s = 0``) or near the
    points ``x`` (a list of coordinate arrays or a ``(dim, m)`` array) on FITPACK's knots,
    lekalo's ``make_splprep``; ``u`` defaults to chord length on ``[0, 1]``. Returns
    ``(spline, u)`` with the spline's coordinates on ``axis=1``."""
    bc_type = _validate_bc_type(bc_type)
    periodic = bc_type == "periodic"
    pts = np.stack([np.asarray(xi) for xi in x], axis=1) if isinstance(x, list) else np.stack(list(np.asarray(x)), axis=1)
    if u is None:
        dp = (pts[1:, :] - pts[:-1, :]) ** 2
        u = np.cumsum(np.sqrt(np.sum(dp, axis=1)))
        u = np.concatenate([[0.0], u / u[-1]])
    if s == 0:
        if t is not None or w is not None or nest is not None:
            raise ValueError("s==0 is for interpolation only")
        return make_interp_spline(u, pts.T, k=k, axis=1), u
    u, pts, w, k = _validate_inputs(u, pts, w, k, s, ub, ue, parametric=True, periodic=periodic)
    _domain(u, ub, ue, wider=False)
    tt, c = _smooth(u, pts, w, k, s, t, nest, periodic)
    return BSpline(tt, np.ascontiguousarray(c.T), k, axis=1), u
