"""Conversions to and from SciPy (``BSpline``, ``PPoly``, ``BPoly``) and geomdl's dict form.

Every conversion copies numbers without arithmetic, so a round trip is bit for bit. SciPy is
imported only when a SciPy object is made.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._lekalo import (
    BezierCurve,
    BSplineCurve,
    BSplineSurface,
    Error,
    NurbsCurve,
    NurbsSurface,
    PiecewisePolynomial,
    basis_functions,
)


def _values(c: np.ndarray, what: str) -> np.ndarray:
    """Coefficients with a trailing value axis: ``(..., dim)``."""
    c = np.asarray(c, dtype=np.float64)
    return c


def design_matrix(x: Any, t: Any, k: int):
    """The B-spline design matrix ``N_{i,k}(x_j)`` as a ``scipy.sparse.csr_array`` of shape
    ``(len(x), len(t) - k - 1)``, as ``scipy.interpolate.BSpline.design_matrix(x, t, k)``: row
    ``j`` holds the ``k + 1`` values of ``basis_functions(t, k, x)`` at columns
    ``span_j - k .. span_j``. Parameters outside ``[t[k], t[-k-1]]`` raise ``lekalo.Error``.
    """
    from scipy.sparse import csr_array

    spans, values = basis_functions(t, k, x)
    m, w = values.shape
    indices = (spans - k)[:, None] + np.arange(w)
    indptr = np.arange(0, m * w + 1, w)
    n = len(np.asarray(t)) - k - 1
    return csr_array((values.ravel(), indices.ravel(), indptr), shape=(m, n))


_JOIN_RTOL = 1e-12
"""Relative tolerance of ``from_scipy`` for a ``BPoly``'s pieces to join: the end coefficient of
one piece and the start coefficient of the next may differ by this much times the largest
coefficient magnitude (rounding, not a jump)."""


def from_scipy(obj: Any):
    """A lekalo object with the same numbers as a SciPy spline.

    - ``scipy.interpolate.BSpline`` -> ``BSplineCurve`` (knots ``t``, control points the first
      ``len(t) - k - 1`` rows of ``c``);
    - ``PPoly`` (and ``CubicSpline``, ``Akima1DInterpolator``, ...) -> ``PiecewisePolynomial``
      (SciPy's highest-power-first coefficients reordered to lekalo's lowest-first);
    - ``BPoly`` -> ``BSplineCurve`` whose Bezier pieces are the ``BPoly`` pieces (interior
      knots of multiplicity ``k``); the pieces must join (end and start coefficients equal up to
      ``1e-12`` times the largest coefficient magnitude: rounding, as in a ``CubicSpline``
      converted with ``BPoly.from_power_basis``), otherwise ``lekalo.Error``.

    Scalar-valued SciPy splines become dimension 1; ``to_scipy`` gives them back 1-D.
    """
    from scipy import interpolate as si

    if isinstance(obj, si.BSpline):
        t = np.asarray(obj.t, dtype=np.float64)
        k = int(obj.k)
        n = len(t) - k - 1
        c = np.asarray(obj.c, dtype=np.float64)[:n]
        if c.ndim == 1:
            c = c[:, None]
        elif c.ndim != 2:
            raise Error(f"BSpline.c: expected 1 or 2 dimensions, got shape {c.shape}")
        return BSplineCurve(k, t, np.ascontiguousarray(c))
    if isinstance(obj, si.BPoly):
        x = np.asarray(obj.x, dtype=np.float64)
        c = np.asarray(obj.c, dtype=np.float64)
        if c.ndim == 2:
            c = c[:, :, None]
        if c.ndim != 3:
            raise Error(f"BPoly.c: expected 2 or 3 dimensions, got shape {c.shape}")
        order, m, dim = c.shape
        p = order - 1
        if p > 0 and m > 1:
            # pieces join when the end and start coefficients agree up to rounding, relative to
            # the size of the coefficients (a CubicSpline's BPoly differs there by an ulp or so)
            tol = _JOIN_RTOL * max(float(np.max(np.abs(c))), np.finfo(np.float64).tiny)
            jump = np.max(np.abs(c[-1, :-1] - c[0, 1:]), axis=-1)
            gaps = np.nonzero(~(jump <= tol))[0]
            if gaps.size:
                g = gaps[0]
                raise Error(
                    f"BPoly: pieces {g} and {g + 1} do not join at x = {x[g + 1]} "
                    f"(the coefficients differ by {jump[g]:.3g}, more than {tol:.3g}, "
                    f"{_JOIN_RTOL:g} of their largest magnitude); a B-spline curve is continuous "
                    "(convert each piece with BezierCurve(c[:, j]))"
                )
        if p == 0:
            knots = x
            control = c[0]
        else:
            knots = np.concatenate([[x[0]] * (p + 1)] + [[xi] * p for xi in x[1:-1]] + [[x[-1]] * (p + 1)])
            rows = [c[:, 0]] + [c[1:, j] for j in range(1, m)]
            control = np.concatenate(rows)
        return BSplineCurve(p, knots, np.ascontiguousarray(control))
    if isinstance(obj, si.PPoly):
        x = np.asarray(obj.x, dtype=np.float64)
        c = np.asarray(obj.c, dtype=np.float64)
        if c.ndim == 2:
            c = c[:, :, None]
        if c.ndim != 3:
            raise Error(f"PPoly.c: expected 2 or 3 dimensions, got shape {c.shape}")
        coef = np.ascontiguousarray(np.moveaxis(c[::-1], 0, 1))
        return PiecewisePolynomial(x, coef)
    raise Error(
        f"from_scipy: {type(obj).__name__} is not supported; use scipy.interpolate.BSpline, PPoly or BPoly"
    )


def _squeeze(c: np.ndarray, squeeze: bool) -> np.ndarray:
    return c[..., 0] if squeeze and c.shape[-1] == 1 else c


def to_scipy(obj: Any, kind: Optional[str] = None, *, squeeze: bool = True):
    """The SciPy spline with the same numbers.

    ``BSplineCurve`` -> ``BSpline`` (default), ``BPoly`` (``kind="BPoly"``: its Bezier pieces) or
    ``PPoly`` (``kind="PPoly"``); ``BezierCurve`` -> ``BPoly`` on ``[0, 1]``;
    ``PiecewisePolynomial`` -> ``PPoly``. Dimension 1 gives SciPy's 1-D coefficients unless
    ``squeeze=False``. SciPy's splines extrapolate by default; lekalo's raise outside the
    domain, so the results are ``extrapolate=False`` (NaN outside).
    """
    from scipy import interpolate as si

    if isinstance(obj, NurbsCurve):
        raise Error("to_scipy: SciPy has no rational splines; use obj.homogeneous() for (w*P, w)")
    if isinstance(obj, BezierCurve):
        c = obj.control[:, None, :]
        return si.BPoly(_squeeze(c, squeeze), np.array([0.0, 1.0]), extrapolate=False)
    if isinstance(obj, PiecewisePolynomial):
        coef = obj.coefficients  # (pieces, order, dim)
        c = np.ascontiguousarray(np.moveaxis(coef, 1, 0)[::-1])
        return si.PPoly(_squeeze(c, squeeze), obj.breakpoints, extrapolate=False)
    if isinstance(obj, BSplineCurve):
        kind = (kind or "BSpline").lower()
        if kind == "bspline":
            return si.BSpline(obj.knots, _squeeze(obj.control, squeeze), obj.degree, extrapolate=False)
        if kind == "ppoly":
            return to_scipy(obj.to_pp(), squeeze=squeeze)
        if kind == "bpoly":
            segs = obj.to_bezier_segments()
            x = np.array([segs[0][0]] + [s[1] for s in segs])
            c = np.stack([s[2].control for s in segs], axis=1)  # (order, pieces, dim)
            return si.BPoly(_squeeze(c, squeeze), x, extrapolate=False)
        raise Error(f"to_scipy: unknown kind {kind!r}; use 'BSpline', 'PPoly' or 'BPoly'")
    raise Error(f"to_scipy: {type(obj).__name__} has no SciPy counterpart")


def to_geomdl(obj: Any) -> dict:
    """geomdl's dict form (``exchange.export_json``'s ``shape`` entry) of a curve or surface:
    ``{"shape": {"type": "curve" | "surface", "count": 1, "data": [ {...} ]}}``. Surface
    control points are listed with ``v`` varying fastest, as geomdl and lekalo both store them.
    """
    if isinstance(obj, BezierCurve):
        obj = obj.to_bspline()
    if isinstance(obj, (BSplineCurve, NurbsCurve)):
        item = {
            "type": "spline",
            "rational": isinstance(obj, NurbsCurve),
            "dimension": obj.dim,
            "degree": obj.degree,
            "knotvector": obj.knots.tolist(),
            "control_points": {"points": obj.control.tolist()},
        }
        if isinstance(obj, NurbsCurve):
            item["control_points"]["weights"] = obj.weights.tolist()
        kind = "curve"
    elif isinstance(obj, (BSplineSurface, NurbsSurface)):
        nu, nv = obj.net_size
        item = {
            "type": "spline",
            "rational": isinstance(obj, NurbsSurface),
            "dimension": obj.dim,
            "degree": list(obj.degrees),
            "knotvector": [obj.knots_u.tolist(), obj.knots_v.tolist()],
            "size": [nu, nv],
            "control_points": {"points": obj.control.reshape(nu * nv, obj.dim).tolist()},
        }
        if isinstance(obj, NurbsSurface):
            item["control_points"]["weights"] = obj.weights.reshape(-1).tolist()
        kind = "surface"
    else:
        raise Error(f"to_geomdl: {type(obj).__name__} has no geomdl counterpart")
    return {"shape": {"type": kind, "count": 1, "data": [item]}}


def from_geomdl(data: dict):
    """The lekalo object of geomdl's dict form (the whole ``{"shape": ...}`` dict, or one item
    of its ``data`` list; a container of several gives a list)."""
    if "shape" in data:
        shape = data["shape"]
        items = [from_geomdl(dict(d, _kind=shape["type"])) for d in shape["data"]]
        return items[0] if len(items) == 1 else items
    try:
        cp = data["control_points"]
        pts = np.asarray(cp["points"], dtype=np.float64)
        weights = cp.get("weights")
        kind = data.get("_kind") or ("surface" if "size" in data else "curve")
        if kind == "curve":
            p, kv = int(data["degree"]), np.asarray(data["knotvector"], dtype=np.float64)
            if weights is not None and data.get("rational", True):
                return NurbsCurve(p, kv, pts, np.asarray(weights, dtype=np.float64))
            return BSplineCurve(p, kv, pts)
        if kind == "surface":
            (p, q), (ku, kv) = data["degree"], data["knotvector"]
            nu, nv = data["size"]
            net = pts.reshape(nu, nv, -1)
            ku = np.asarray(ku, dtype=np.float64)
            kv = np.asarray(kv, dtype=np.float64)
            if weights is not None and data.get("rational", True):
                w = np.asarray(weights, dtype=np.float64).reshape(nu, nv)
                return NurbsSurface(int(p), int(q), ku, kv, net, w)
            return BSplineSurface(int(p), int(q), ku, kv, net)
    except KeyError as e:
        raise Error(f"from_geomdl: the dict has no key {e.args[0]!r}") from None
    raise Error(f"from_geomdl: shape type {kind!r} is not supported (curve, surface)")
