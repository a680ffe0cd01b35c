"""The 2-D FITPACK routines behind ``lekalo.scipy``'s functions (``bisplrep``, ``bisplev``,
``dblint``) and classes (``RectBivariateSpline``, ``SmoothBivariateSpline``,
``LSQBivariateSpline``): SciPy's ``(tx, ty, c, kx, ky)`` as lekalo's ``TensorBSpline``, its
values and partial derivatives (``bispev``, ``parder``, ``bispeu``, ``pardeu``), its integral
(``dblint``), and ``surfit`` as lekalo's scattered smoothing, with FITPACK's messages."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import _lekalo


def _tensor(tx: Any, ty: Any, c: Any, kx: int, ky: int):
    """lekalo's ``TensorBSpline`` of FITPACK's ``(tx, ty, c, kx, ky)`` (``c`` flat, ``x`` slowest)."""
    tx = np.ascontiguousarray(tx, dtype=np.float64)
    ty = np.ascontiguousarray(ty, dtype=np.float64)
    nx, ny = len(tx) - kx - 1, len(ty) - ky - 1
    c = np.ascontiguousarray(np.asarray(c, dtype=np.float64)[: nx * ny]).reshape(nx, ny)
    return _lekalo.TensorBSpline((tx, ty), c, [int(kx), int(ky)])


def _clip(v: np.ndarray, t: np.ndarray, k: int) -> np.ndarray:
    """FITPACK's evaluation (``fpbisp``) takes a coordinate outside the base interval at its end."""
    return np.clip(np.asarray(v, dtype=np.float64), t[k], t[len(t) - k - 1])


def _evaluate(tck: Any, degrees: Any, x: Any, y: Any, dx: int, dy: int, grid: bool) -> np.ndarray:
    """SciPy's ``bispev``/``parder`` (``grid``) and ``bispeu``/``pardeu`` (points): values of the
    spline or of its partial derivative ``(dx, dy)``, computed as the values of the derivative
    spline (lekalo's ``TensorBSpline.derivative``, as ``partial_derivative`` returns it)."""
    tx, ty, c = tck[:3]
    kx, ky = degrees
    tx = np.asarray(tx, dtype=np.float64)
    ty = np.asarray(ty, dtype=np.float64)
    if dx or dy:
        if not (0 <= dx < kx and 0 <= dy < ky):
            raise ValueError(
                f"Error code returned by {'parder' if grid else 'pardeu'}: 10 (derivative orders "
                f"dx={dx}, dy={dy} must satisfy 0 <= dx < kx={kx}, 0 <= dy < ky={ky})"
            )
    if not _finite_box(tx, ty):
        if grid:
            _check_grid_size(x, y)
        return np.full((np.size(x), np.size(y)) if grid else np.shape(x), np.nan)
    if dx or dy:
        spline = _tensor(tx, ty, c, kx, ky).derivative([int(dx), int(dy)])
        tx, ty = (np.asarray(t) for t in spline.t)
        kx, ky = kx - dx, ky - dy
    else:
        # values: lekalo's tensor_values on the arrays in place (no spline built, nothing of
        # the coefficients copied), coordinates outside the base box taken at its edge
        tx = np.ascontiguousarray(tx)
        ty = np.ascontiguousarray(ty)
        nx, ny = len(tx) - kx - 1, len(ty) - ky - 1
        net = np.ascontiguousarray(np.asarray(c, dtype=np.float64)[: nx * ny]).reshape(nx, ny)
        if grid:
            _check_grid_size(x, y)
            # coordinates outside the base box are taken at its edge by tensor_grid_values
            xs = np.ascontiguousarray(x, dtype=np.float64).ravel()
            ys = np.ascontiguousarray(y, dtype=np.float64).ravel()
            return _lekalo.tensor_grid_values((tx, ty), net, (int(kx), int(ky)), (xs, ys), None, True)
        pts = np.empty(np.shape(x) + (2,))
        pts[..., 0] = x
        pts[..., 1] = y
        return _lekalo.tensor_values((tx, ty), net, (int(kx), int(ky)), pts, None, "clamp")
    if grid:
        _check_grid_size(x, y)
        xs = _clip(x, tx, kx).ravel()
        ys = _clip(y, ty, ky).ravel()
        return np.asarray(spline.grid(np.ascontiguousarray(xs), np.ascontiguousarray(ys)))
    pts = np.stack([_clip(x, tx, kx).ravel(), _clip(y, ty, ky).ravel()], axis=-1)
    return np.asarray(spline(np.ascontiguousarray(pts))).reshape(np.shape(x))


def _finite_box(tx: np.ndarray, ty: np.ndarray) -> bool:
    """Whether the knots are finite. A box with an infinite end (``RectBivariateSpline`` of a
    grid whose first or last coordinate is infinite, or of an infinite ``bbox``) has knots
    there that FITPACK keeps: its basis on such a span is ``inf/inf``, so every value, derivative
    and integral of the spline is NaN, as SciPy's, and its coefficients are NaN."""
    return bool(np.isfinite(tx).all() and np.isfinite(ty).all())


def _grid_of_infinite_box(x: np.ndarray, y: np.ndarray, box: Any, kx: int, ky: int):
    """FITPACK's ``regrid`` on a box with an infinite end (``x[0] = -inf`` or ``x[-1] = inf``,
    the only places a strictly increasing grid holds one, or an infinite ``bbox`` end): the
    knots of interpolation, whose interior knots are data points (odd degree) or midpoints of
    neighbours (even degree) away from the ends, so they are lekalo's knots of the grid with
    finite stand-ins for the infinite ends, and the box's ends (infinite) repeated ``k + 1``
    times at each side; ``fp = 0`` and every coefficient NaN, as SciPy returns them (its
    residuals and solve meet ``inf``). Returns ``(tx, ty, c)``, or ``None`` when the box is
    finite."""
    if all(np.isfinite(e) for end in box for e in end):
        return None
    axes, boxes = [], []
    for v, (lo, hi) in zip((x, y), box):
        w = v.copy()
        finite = w[np.isfinite(w)]
        first = finite[0] if finite.size else 0.0
        last = finite[-1] if finite.size else 0.0
        if np.isneginf(w[0]):
            w[0] = first - 1.0
        if np.isposinf(w[-1]):
            w[-1] = last + 1.0
        axes.append(w)
        boxes.append((w[0] - 1.0 if np.isinf(lo) else lo, w[-1] + 1.0 if np.isinf(hi) else hi))
    spline, _, _ = _lekalo.fit_tensor_grid_smoothing(
        axes, np.zeros((x.size, y.size)), 0.0, [int(kx), int(ky)], bbox=boxes
    )
    knots = []
    for t, k, (lo, hi) in zip(spline.t, (kx, ky), box):
        t = np.array(t)
        if np.isinf(lo):
            t[: k + 1] = lo
        if np.isinf(hi):
            t[len(t) - k - 1 :] = hi
        knots.append(t)
    return knots[0], knots[1], np.full(np.asarray(spline.c).size, np.nan)


def _value(tck: Any, degrees: Any, x: float, y: float):
    """The spline's value at the one point ``(x, y)`` (a coordinate outside the base box, or
    infinite, taken at its edge, as FITPACK), lekalo's ``tensor_value`` reading the few knots and coefficients it
    needs in place; ``None`` when the arrays are not float64 arrays it can read (the caller then
    takes the array way, which converts them and raises SciPy's errors)."""
    try:
        # "clamp": an infinite coordinate taken at its edge and NaN at a NaN one, as FITPACK
        return _lekalo.tensor_value(tck[:2], tck[2], degrees, (x, y), "clamp")
    except Exception:
        return None


def _check_grid_size(x: Any, y: Any) -> None:
    if np.size(x) * np.size(y) > _lekalo.MAX_SCALARS:
        raise MemoryError(
            f"a grid of {np.size(x)} x {np.size(y)} values exceeds lekalo's size limit "
            f"{_lekalo.MAX_SCALARS} (MAX_SCALARS); evaluate it in parts"
        )


def _dblint(tck: Any, degrees: Any, xa: float, xb: float, ya: float, yb: float) -> float:
    tx, ty, c = tck[:3]
    kx, ky = degrees
    tx = np.asarray(tx, dtype=np.float64)
    ty = np.asarray(ty, dtype=np.float64)
    if not _finite_box(tx, ty):
        return float("nan")
    bounds = [
        (float(_clip(xa, tx, kx)), float(_clip(xb, tx, kx))),
        (float(_clip(ya, ty, ky)), float(_clip(yb, ty, ky))),
    ]
    return float(np.asarray(_tensor(tx, ty, c, kx, ky).integral(bounds)).ravel()[0])


# FITPACK's surfit messages as SciPy words them (``ier`` -> text), for its warnings.
_SURFIT_MESSAGES = {
    1: """
The required storage space exceeds the available storage space: nxest
or nyest too small, or s too small.
The weighted least-squares spline corresponds to the current set of
knots.""",
    4: """
No more knots can be added because the number of b-spline coefficients
(nx-kx-1)*(ny-ky-1) already exceeds the number of data points m:
either s or m too small.
The weighted least-squares spline corresponds to the current set of
knots.""",
    5: """
No more knots can be added because the additional knot would (quasi)
coincide with an old one: s too small or too large a weight to an
inaccurate data point.
The weighted least-squares spline corresponds to the current set of
knots.""",
    -3: """
The coefficients of the spline returned have been computed as the
minimal norm least-squares solution of a (numerically) rank deficient
system (deficiency=%i). If deficiency is large, the results may be
inaccurate. Deficiency may strongly depend on the value of eps.""",
}

# lekalo's reason for stopping the knot rounds above s -> FITPACK's ier
_LIMIT_IER = {"max-knots": 1, "coefficients-exceed-data": 4, "knots-coincide": 5}


def _box(x: np.ndarray, y: np.ndarray, bbox: Any):
    """FITPACK's box: ``bbox = [xb, xe, yb, ye]``, ``None`` entries taken from the data."""
    xb, xe, yb, ye = (None if b is None else float(b) for b in bbox)
    return (
        (float(x.min()) if xb is None else xb, float(x.max()) if xe is None else xe),
        (float(y.min()) if yb is None else yb, float(y.max()) if ye is None else ye),
    )


def _surfit(x: Any, y: Any, z: Any, w: Any, box: Any, kx: int, ky: int, s: float, eps: float,
            nxest: int, nyest: int):
    """FITPACK's ``surfit`` with ``iopt = 0``: lekalo's ``fit_tensor_scattered_smoothing`` with
    the minimal-norm rank choice and the knot bounds ``nxest``, ``nyest``; FITPACK's weights
    multiply the residual (lekalo's are their squares). Returns ``(tx, ty, c, fp, ier)``."""
    pts = np.ascontiguousarray(np.stack([x, y], axis=-1), dtype=np.float64)
    ww = None if w is None else np.asarray(w, dtype=np.float64) ** 2
    spline, fp, p, rank, limit = _lekalo.fit_tensor_scattered_smoothing(
        pts, np.ascontiguousarray(z, dtype=np.float64), float(s), [int(kx), int(ky)], w=ww,
        bbox=box, max_knots=[int(nxest), int(nyest)], eps=float(eps),
    )
    tx, ty = (np.asarray(t) for t in spline.t)
    c = np.asarray(spline.c).ravel()
    ncof = c.size
    polynomial = len(tx) == 2 * kx + 2 and len(ty) == 2 * ky + 2
    if limit == "coefficients-exceed-data" and s == 0.0 and rank == (len(x) if w is None else np.count_nonzero(w)):
        # interpolation (s = 0) with more coefficients than points, of rank the number of
        # weighted points: FITPACK's rotations leave no residual row, so its fp is 0 exactly
        # and it accepts the minimal-norm interpolant (ier = -rank) where lekalo's residual is
        # the rounding of the evaluation
        fp, limit = 0.0, None
    # FITPACK's order: a knot limit; the polynomial below s (rank not reported); the rank; an
    # interpolating spline; the polynomial within the tolerance of s
    if limit is not None:
        ier = _LIMIT_IER[limit]
    elif polynomial and fp < s - 1e-3 * s:
        ier = -2
    elif rank != ncof:
        ier = -rank
    elif p is None and fp <= 0.0:
        ier = -1
    elif p is None and polynomial:
        ier = -2
    else:
        ier = 0
    return tx, ty, c, fp, ier
