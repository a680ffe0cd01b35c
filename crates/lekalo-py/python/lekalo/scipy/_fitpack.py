"""The FITPACK-style functions of ``lekalo.scipy`` (``splrep``, ``splev``, ``splint``, ``splder``,
``splantider``) on ``(t, c, k)`` tuples and ``BSpline`` objects."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .. import _lekalo
from ._bivariate import _dblint, _evaluate, _surfit, _value
from ._bspline import BSpline, _antiderivative_tc, _derivative_tc, _insert_tc, _one_number, _pad_rows
from ._interpolate import _not_a_knot, make_interp_spline, make_lsq_spline


class _TckCurve:
    """A curve given by SciPy-side knots and coefficients, read as splprep reads lekalo's curves
    (``knots``, ``control``, values at parameters)."""

    def __init__(self, t: np.ndarray, c: np.ndarray, k: int) -> None:
        self.knots, self.control = t, c
        self._spline = BSpline.construct_fast(t, c, k)

    def __call__(self, u: np.ndarray) -> np.ndarray:
        return self._spline(u)


def _fpchec(x: np.ndarray, t: np.ndarray, k: int) -> int:
    """FITPACK's ``fpchec`` as SciPy 1.17's ``curfit`` reports it: 0 where the full knot vector
    ``t`` suits the sorted data ``x`` for degree ``k``, else ten times the number of the first
    condition that fails: 1 ``k + 1 <= n - k - 1 <= m``, 2 the end knots in order, 3 the interior
    knots strictly increasing and strictly inside the end knots, 4 the data within the end
    knots, 5 Schoenberg-Whitney (FITPACK's greedy matching of the basis functions to data)."""
    n, m, k1 = len(t), len(x), k + 1
    nk1 = n - k1
    if nk1 < k1 or nk1 > m:
        return 10
    if np.any(t[:k] > t[1:k1]) or np.any(t[n - k :] < t[n - k - 1 : n - 1]):
        return 20
    if np.any(t[k1 : nk1 + 1] <= t[k:nk1]):
        return 30
    if x[0] < t[k] or x[-1] > t[nk1]:
        return 40
    if x[0] >= t[k1] or x[-1] <= t[nk1 - 1]:
        return 50
    j = np.arange(1, nk1 - 1)
    if j.size:
        # the data point of basis function j: the first after the previous one beyond t[j],
        # which must come before the last point and lie below t[j + k + 1]
        q = np.arange(j.size)
        first = np.searchsorted(x, t[j], side="right")
        i = np.maximum(1, np.maximum.accumulate(first - q)) + q
        if i[-1] > m - 2 or np.any(x[i] >= t[j + k1]):
            return 50
    return 0


def _check_knots(x: np.ndarray, t: np.ndarray, k: int) -> None:
    """SciPy's refusal of knots that FITPACK's ``fpchec`` rejects: ``ValueError`` for their
    count (``ier = 10``), SciPy's ``TypeError("An error occurred")`` for its other codes."""
    code = _fpchec(x, t, k)
    if code == 10:
        raise ValueError(
            f"Error on input data: {len(t) - 2 * k - 2} interior knots for {len(x)} points of "
            f"degree {k}: FITPACK needs k + 1 <= n - k - 1 <= m"
        )
    if code:
        what = {
            20: "the end knots are not in order",
            30: "the interior knots t must be strictly increasing and strictly inside (xb, xe)",
            40: "the data lie outside the end knots",
            50: "the knots t do not satisfy the Schoenberg-Whitney conditions with the data x",
        }[code]
        raise TypeError(f"An error occurred: {what} (FITPACK's fpchec, ier={code})")


def splrep(
    x: Any, y: Any, w: Any = None, xb: Any = None, xe: Any = None, k: int = 3, task: int = 0,
    s: Any = None, t: Any = None, full_output: int = 0, per: int = 0, quiet: int = 1,
):
    """``scipy.interpolate.splrep`` for interpolation (``s = 0``, the default without weights;
    FITPACK's knots are SciPy's not-a-knot ones), the smoothing condition (lekalo's
    ``fit_smoothing_condition``, ``make_splrep``'s fit) and least squares on given interior knots
    ``t`` (``task=-1``), with the end knots at ``xb`` and ``xe``; ``per=1`` ignores ``xb``/``xe``
    as FITPACK's ``percur`` does. ``task=1`` raises SciPy 1.17's ``UnboundLocalError``. Returns
    ``(t, c, k)`` with ``c`` zero-padded to ``len(t)``, as FITPACK."""
    return _splrep(x, y, w, xb, xe, k, task, s, t, full_output, per, quiet)


def _splrep(
    x: Any, y: Any, w: Any, xb: Any, xe: Any, k: int, task: int, s: Any, t: Any, full_output: int, per: int,
    quiet: int,
):
    """``splrep``'s result: ``(t, c, k)``, with ``fp``, ``ier`` and the message for
    ``full_output``."""
    return _splrep_rounds(x, y, w, xb, xe, k, task, s, t, full_output, per, quiet)[0]


def _splrep_rounds(
    x: Any, y: Any, w: Any, xb: Any, xe: Any, k: int, task: int, s: Any, t: Any, full_output: int, per: int,
    quiet: int, nest: Any = None, start: Any = None,
):
    """``splrep`` and the state of FITPACK's knot rounds (the report's ``"rounds"`` of lekalo's
    ``fit_smoothing_condition``) where they ran, else ``None``. With ``nest`` (``s > 0``, no
    ``t``, ``per=0``) the rounds stop at ``nest`` knots and go on from the knots reached, as
    SciPy's ``UnivariateSpline`` calls FITPACK's ``curfit`` (lekalo's ``resume``); with
    ``start`` (a state) they go on from an earlier fit's knots under the limit it carries, as
    ``curfit`` with ``iopt=1``."""
    x = np.atleast_1d(np.asarray(x, dtype=np.float64))
    y = np.atleast_1d(np.asarray(y, dtype=np.float64))
    m = len(x)
    if w is not None:
        # FITPACK's wrapper reads any real array as doubles: boolean masks (SciPy's ``w=~isnan(y)``) too
        w = np.atleast_1d(np.asarray(w, dtype=np.float64))
        if len(w) != m:
            raise TypeError(f"len(w)={len(w)} is not equal to m={m}")
    if s is None:
        s = 0.0 if w is None else m - np.sqrt(2 * m)
    if not (1 <= k <= 5):
        raise TypeError(f"1 <= k= {k} <=5 must hold")
    if task not in (-1, 0, 1):
        raise TypeError("task must be -1, 0 or 1")
    if task == -1 and t is None:
        raise TypeError("Knots must be given for task=-1")
    # FITPACK's periodic fit (percur) takes its period from the data and ignores xb/xe
    xb = x[0] if xb is None or per else float(xb)
    xe = x[-1] if xe is None or per else float(xe)
    if y.ndim != 1:
        raise ValueError(f"too many axes: {y.ndim} (effrank={y.ndim}), expected rank=1")
    if len(y) != m:
        raise TypeError("Lengths of the first three arguments (x,y,w) must be equal")
    if m <= k:
        raise TypeError("m > k must hold")
    if task == 1:
        # SciPy's splrep keeps the previous call's knots in a name that its own task <= 0
        # branch makes local, so task=1 fails before reaching FITPACK, with knots t too
        # (SciPy 1.17)
        raise UnboundLocalError(
            "cannot access local variable '_curfit_cache' where it is not associated with a value "
            "(SciPy's splrep(task=1) raises this: it keeps no earlier fit to continue; "
            "UnivariateSpline(x, y, s=s0).set_smoothing_factor(s) continues FITPACK's knot rounds)"
        )
    if m and (xb > x[0] or xe < x[-1]):
        raise ValueError("Error on input data: xb <= x[0] and xe >= x[-1] must hold")
    wide = m > 0 and (xb != x[0] or xe != x[-1])
    rounds = None
    if per:
        # lekalo's periodic fit is splrep(per=1)'s: the last point closes the period, FITPACK's
        # knots and smoothing condition, or least squares on the interior knots t
        curve, _ = _lekalo.fit_periodic(
            x, y, w=None if w is None else np.asarray(w, dtype=np.float64) ** 2, k=k, s=float(s), t=None if t is None else np.asarray(t, dtype=np.float64)
        )
        spl = BSpline.construct_fast(np.ascontiguousarray(curve.knots), np.ascontiguousarray(curve.control[:, 0]), k)
    elif t is not None:
        tt = np.r_[(xb,) * (k + 1), np.asarray(t, dtype=np.float64), (xe,) * (k + 1)]
        _check_knots(x, tt, k)
        spl = make_lsq_spline(x, y, tt, k, w=w)
    elif s == 0 and w is None and wide:
        # FITPACK's interpolation knots (the not-a-knot ones) with the ends at xb and xe
        tt = _not_a_knot(x, k)
        tt[: k + 1], tt[-k - 1 :] = xb, xe
        spl = make_lsq_spline(x, y, tt, k)
    elif s == 0 and w is None:
        # lekalo's solve (k >= 2) refuses NaN and infinity itself: no NumPy pass over the data
        # before it; k = 1 keeps the data as they are, so NumPy checks them
        spl = make_interp_spline(x, y, k=k, check_finite=k <= 1)
    else:
        # FITPACK's knot placement and smoothing condition, lekalo's fit_smoothing_condition:
        # the same knots; the coefficients meet FITPACK's tolerance |fp - s| <= 0.001 s, not its
        # bits; the end knots at xb and xe; the rounds' state kept for a continuation
        # SciPy's weights squared into lekalo's; negative ones passed on for lekalo to refuse
        ws = None if w is None else np.where(w >= 0, w * w, w)
        curve, report = _lekalo.fit_smoothing_condition(
            x, y, w=ws, k=k, s=float(s), domain=(xb, xe) if wide else None,
            nest=nest, resume=nest is not None, start=start,
        )
        rounds = report["rounds"]
        spl = BSpline.construct_fast(np.ascontiguousarray(curve.knots), np.ascontiguousarray(curve.control[:, 0]), k)
    tck = (spl.t, _pad_rows(spl.c, spl.t.shape[0]), spl.k)
    if full_output:
        # FITPACK's fp (the weighted residual sum of squares), ier and message: -1 for the
        # interpolating spline (fp = 0 as FITPACK reports it), -2 where the smoothing condition
        # kept the least-squares polynomial (no interior knot), 0 otherwise
        if s == 0 and t is None:
            return (tck, 0.0, -1, _CURFIT_MESSAGES[-1]), rounds
        rows = slice(None, -1) if per else slice(None)
        ww = 1.0 if w is None else w[rows]
        fp = float(np.sum((ww * (spl(x[rows]) - y[rows])) ** 2))
        ier = -2 if t is None and not per and spl.t.shape[0] == 2 * k + 2 else 0
        return (tck, fp, ier, _CURFIT_MESSAGES[ier]), rounds
    return tck, rounds


# FITPACK's curfit messages as SciPy's splrep words them
_CURFIT_MESSAGES = {
    0: "The spline has a residual sum of squares fp such that abs(fp-s)/s<=0.001",
    -1: "The spline is an interpolating spline (fp=0)",
    -2: "The spline is weighted least-squares polynomial of degree k.\n"
    "fp gives the upper bound fp0 for the smoothing factor s",
}


def splev(x: Any, tck: Any, der: int = 0, ext: int = 0):
    """``scipy.interpolate.splev``: the spline (or its ``der``-th derivative) at ``x``;
    ``ext`` 0 extrapolates, 1 gives zero, 2 raises ``ValueError``, 3 gives the boundary value
    outside the base interval."""
    if isinstance(tck, BSpline):
        if tck.c.ndim > 1:
            raise ValueError(
                "Calling splev() with BSpline objects with c.ndim > 1 is not allowed. "
                "Use BSpline.__call__(x) instead."
            )
        try:
            extrapolate = {0: True}[ext]
        except KeyError as e:
            raise ValueError(f"Extrapolation mode {ext} is not supported by BSpline.") from e
        return tck(x, der, extrapolate=extrapolate)
    t, c, k = tck
    xf = _one_number(x)
    if xf is not None and der == 0 and ext == 0 and k and type(c) is np.ndarray and c.ndim == 1:
        # one number in: lekalo's bspline_value on the arrays as they are; anything it does not
        # take (knots that are not a float64 array, ...) goes the array way
        try:
            return np.array(_lekalo.bspline_value(t, k, c, xf, True))
        except Exception:
            pass
    try:
        c[0][0]
        parametric = True
    except Exception:
        parametric = False
    if parametric:
        return list(map(lambda c, x=x, t=t, k=k: splev(x, [t, c, k], der, ext), c))
    if not (0 <= der <= k):
        raise ValueError(f"0<=der={der}<=k={k} must hold")
    if ext not in (0, 1, 2, 3):
        raise ValueError(f"ext = {ext} not in (0, 1, 2, 3) ")
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    x = np.asarray(x)
    shape = x.shape
    x = np.atleast_1d(x).ravel().astype(np.float64)
    if x.size == 0:
        # FITPACK's splev and splder refuse m < 1 points (ier = 10), as SciPy reports it
        raise ValueError("Invalid input data: no points x to evaluate the spline at (SciPy's splev refuses an empty x)")
    n = t.shape[0] - k - 1
    lo, hi = t[k], t[n]
    outside = (x < lo) | (x > hi)
    if ext == 2 and outside.any():
        # SciPy's words first (code matching on them keeps working), then which x and the choices
        raise ValueError(
            f"Found x value not in the domain: x = {x[outside][0]:g} is outside the base interval "
            f"[{lo:g}, {hi:g}] of the spline; ext=2 ('raise') refuses it, ext=0 ('extrapolate') "
            "continues the end polynomials, ext=1 ('zeros') gives 0, ext=3 ('const') the boundary value"
        )
    # FITPACK clips to the boundary value for ext=3 only for the function itself; its
    # derivatives (splder) extrapolate
    xx = np.clip(x, lo, hi) if ext == 3 and der == 0 else x
    y = BSpline.construct_fast(t, c, k)._evaluate(xx, der, True)[:, 0]
    if ext == 1:
        y[outside] = 0.0
    return y.reshape(shape)


def splint(a: float, b: float, tck: Any, full_output: int = 0):
    """``scipy.interpolate.splint``: ``∫_a^b`` of the spline over the base interval (limits
    clipped to it, as FITPACK), lekalo's ``integrate``."""
    if isinstance(tck, BSpline):
        if tck.c.ndim > 1:
            raise ValueError(
                "Calling splint() with BSpline objects with c.ndim > 1 is not allowed. "
                "Use BSpline.integrate() instead."
            )
        if full_output != 0:
            raise ValueError("full_output = True is not supported with BSpline objects.")
        return tck.integrate(a, b, extrapolate=False)
    t, c, k = tck
    try:
        c[0][0]
        return list(map(lambda c, a=a, b=b, t=t, k=k: splint(a, b, [t, c, k]), c))
    except Exception:
        pass
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    n = t.shape[0] - k - 1
    if c.ndim == 1 and c.shape[0] >= n > 0:
        # one call on the arrays as they are: the limits ordered and clipped to the base
        # interval (BSpline.integrate's rules without extrapolation, the same numbers)
        lo, hi, sign = (a, b, 1) if not b < a else (b, a, -1)
        lo, hi = max(lo, t[k]), min(hi, t[n])
        if lo < hi:
            val = float(_lekalo.tck_integral(t, c[:n], k, float(lo), float(hi))[0])
            val = val if sign > 0 else -val
        else:
            # FITPACK's: NaN for a NaN limit, else 0 (not -0 for reversed limits)
            val = float("nan") if a != a or b != b else 0.0
    else:
        val = float(BSpline.construct_fast(t, c, k, extrapolate=False).integrate(a, b, extrapolate=False))
    if full_output:
        # FITPACK's wrk: the integrals of the B-splines over [a, b] clipped to the base interval
        # (lekalo's basis_integrals_into, FITPACK's fpintb); the last k + 1 entries, which
        # FITPACK leaves unset, are zero
        n = t.shape[0] - k - 1
        lo, hi = t[k], t[n]
        wrk = np.zeros(t.shape[0])
        wrk[:n] = _lekalo.tck_basis_integrals(np.ascontiguousarray(t), k, min(max(a, lo), hi), min(max(b, lo), hi))
        return val, wrk
    return val


def splder(tck: Any, n: int = 1):
    """``scipy.interpolate.splder``: the derivative spline, lekalo's derivative curve."""
    if isinstance(tck, BSpline):
        return tck.derivative(n)
    t, c, k = tck
    if n < 0:
        return splantider(tck, -n)
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    if n > k:
        raise ValueError(f"Order of derivative (n = {n!r}) must be <= order of spline (k = {k!r})")
    t2, c2 = _derivative_tc(t, c, k, n)
    return t2, c2, k - n


def splantider(tck: Any, n: int = 1):
    """``scipy.interpolate.splantider``: the antiderivative spline, lekalo's antiderivative."""
    if isinstance(tck, BSpline):
        return tck.antiderivative(n)
    t, c, k = tck
    if n < 0:
        return splder(tck, -n)
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    t2, c2 = _antiderivative_tc(t, c, k, n)
    return t2, c2, k + n


def insert(x: float, tck: Any, m: int = 1, per: int = 0):
    """``scipy.interpolate.insert``: the knot ``x`` inserted ``m`` times (Boehm), lekalo's
    ``insert_knot_into`` on the arrays as they are; a ``(t, c, k)`` tuple gives a tuple with
    ``c`` zero-padded to ``len(t)``, a ``BSpline`` a ``BSpline``."""
    if isinstance(tck, BSpline):
        spl = BSpline(tck.t, tck.c, tck.k, extrapolate="periodic" if per else tck.extrapolate, axis=tck.axis)
        out = spl.insert_knot(x, m)
        return BSpline(out.t, out.c, out.k)
    t, c, k = tck
    try:
        c[0][0]
        parametric = True
    except Exception:
        parametric = False
    if parametric:
        cc = []
        for c_vals in c:
            tt, cc_val, kk = insert(x, [t, c_vals, k], m, per)
            cc.append(cc_val)
        return (tt, cc, kk)
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    n = t.shape[0] - k - 1
    tt, cc = _insert_tc(t, c[:n], k, x, m, bool(per))
    return tt, cc, k


def sproot(tck: Any, mest: int = 10):
    """``scipy.interpolate.sproot``: the zeros of a cubic spline in its base interval (FITPACK's
    ``sproot``), found by lekalo's ``tck_zeros`` on the B-spline (spans whose coefficients share
    one sign skipped, the others solved in power form; intervals where the spline vanishes give
    no zero; the base interval widened by rounding, docs/theory/curves.md#zeros-of-a-spline). At
    most ``mest`` zeros, with FITPACK's warning when there are more."""
    if isinstance(tck, BSpline):
        if tck.c.ndim > 1:
            raise ValueError("Calling sproot() with BSpline objects with c.ndim > 1 is not allowed.")
        t, c, k = tck.tck
    else:
        t, c, k = tck
    if k != 3:
        raise ValueError("sproot works only for cubic (k=3) splines")
    try:
        c[0][0]
        parametric = True
    except Exception:
        parametric = False
    if parametric:
        return [sproot((t, ci, k), mest) for ci in c]
    t = np.ascontiguousarray(t, dtype=np.float64)
    if len(t) < 8:
        raise TypeError(f"The number of knots {len(t)}>=8")
    n = len(t) - k - 1
    c = np.asarray(c, dtype=np.float64).reshape(-1)
    if c.shape[0] < n:
        raise ValueError(f"sproot: {c.shape[0]} coefficients for {len(t)} knots of a cubic; at least {n} are needed")
    # FITPACK's knot condition (sorted, t[k] < ... < t[n]) checked by lekalo in one pass over
    # the knots, refused as FITPACK's TypeError
    z = _lekalo.tck_zeros(t, c[:n], k, fitpack_knots=True)
    # the base interval, widened by rounding: a zero at an end falls on either side of it
    a, b = t[k], t[n]
    tol = 4 * np.finfo(float).eps * max(abs(a), abs(b), b - a)
    z = z[(z >= a - tol) & (z <= b + tol)]
    if z.size > mest:
        warnings.warn(RuntimeWarning("The number of zeros exceeds mest"), stacklevel=2)
        z = z[:mest]
    return z


def spalde(x: Any, tck: Any):
    """``scipy.interpolate.spalde``: the spline's derivatives of orders ``0 … k`` at ``x``
    (lekalo's ``derivatives``); a list of such arrays for several ``x`` or parametric ``c``."""
    if isinstance(tck, BSpline):
        raise TypeError("spalde does not accept BSpline instances.")
    t, c, k = tck
    try:
        c[0][0]
        parametric = True
    except Exception:
        parametric = False
    if parametric:
        return list(map(lambda c, x=x, t=t, k=k: spalde(x, [t, c, k]), c))
    x = np.atleast_1d(x)
    t = np.asarray(t, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    n = t.shape[0] - k - 1
    xs = np.ascontiguousarray(x.ravel(), dtype=np.float64)
    if not ((t[k] <= xs) & (xs <= t[n])).all():
        raise ValueError("Invalid input data. t(k)<=x<=t(n-k+1) must hold.")
    # all the points in one call of lekalo's derivatives; several points give a list of rows,
    # as SciPy's point-by-point loop does
    curve = _lekalo.BSplineCurve(k, t, np.ascontiguousarray(c[:n].reshape(n, 1)))
    d = curve.derivatives(xs, k)[:, :, 0]
    return list(d) if len(x) > 1 else d[0]


_PARCUR_MESSAGES = {
    0: "The spline has a residual sum of squares fp such that abs(fp-s)/s<=0.001",
    -1: "The spline is an interpolating spline (fp=0)",
}


def splprep(
    x: Any, w: Any = None, u: Any = None, ub: Any = None, ue: Any = None, k: int = 3, task: int = 0,
    s: Any = None, t: Any = None, full_output: int = 0, nest: Any = None, per: int = 0, quiet: int = 1,
):
    """``scipy.interpolate.splprep``: the parametric spline of FITPACK's ``parcur``/``clocur``
    (``per=1``) through or near the points ``x`` (``(dim, m)``), lekalo's ``make_splprep`` and
    ``fit_closed`` on FITPACK's knots; with knots ``t`` (``task=-1``) lekalo's ``make_lsq_spline``
    on their interior knots, the end knots at ``ub`` and ``ue``. ``ub``/``ue`` are read with ``u``
    only, as FITPACK reads them; beyond the ends of ``u`` they are the end knots of the
    interpolating curve (``s = 0``) and of the smoothing condition (``make_splprep``'s
    ``domain``). With ``u`` and ``per=1``: the closed interpolating curve for ``s = 0``, and
    lekalo's ``fit_periodic`` on the period ``[u[0], u[-1]]`` for ``s > 0`` (FITPACK's
    ``clocur``). ``task=1`` raises SciPy's ``UnboundLocalError``. Returns ``([t, [c_0, …], k],
    u)`` (with ``fp``, ``ier``, ``msg`` for ``full_output``)."""
    x = np.array(np.atleast_1d(x), dtype=np.float64)
    idim, m = x.shape
    if per:
        x[:, -1] = x[:, 0]
    if not 0 < idim < 11:
        raise TypeError("0 < idim < 11 must hold")
    if task > 0:
        # SciPy's splprep keeps the previous call's state in a name that its own task <= 0
        # branch makes local, so task=1 fails at its first use (SciPy 1.17)
        raise UnboundLocalError(
            "cannot access local variable '_parcur_cache' where it is not associated with a value "
            "(SciPy's splprep(task=1) raises this: it keeps no earlier fit to continue)"
        )
    w = np.ones(m) if w is None else np.atleast_1d(np.asarray(w, dtype=np.float64))
    if not (1 <= k <= 5):
        raise TypeError(f"1 <= k= {k} <=5 must hold")
    if not (-1 <= task <= 1):
        raise TypeError("task must be -1, 0 or 1")
    if len(w) != m or (u is not None and len(u) != m):
        raise TypeError("Mismatch of input dimensions")
    if s is None:
        s = m - np.sqrt(2 * m)
    if t is None and task == -1:
        raise TypeError("Knots must be given for task=-1")
    if m <= k:
        raise TypeError("m > k must hold")
    if per and (t is not None or task == -1):
        raise NotImplementedError("lekalo.scipy.splprep: t with per=1 is not available yet")
    if u is None or per:
        # FITPACK reads ub/ue only with given parameters u: parcur computes u itself on [0, 1]
        # (ub = 0, ue = 1) and clocur takes no interval, so SciPy ignores them here
        ub = ue = None
    elif ub is not None or ue is not None:
        u0, u1 = float(np.asarray(u, dtype=np.float64)[0]), float(np.asarray(u, dtype=np.float64)[-1])
        ub = u0 if ub is None else float(ub)
        ue = u1 if ue is None else float(ue)
        if ub > u0 or ue < u1:
            # FITPACK's parcur: ub <= u[0] and ue >= u[-1] must hold (ier = 10)
            raise ValueError("Invalid inputs.")
        if ub == u0 and ue == u1:
            ub = ue = None  # the interval of the data: the default
        elif t is None and s == 0:
            # FITPACK's interpolating curve (fppara with s = 0): the interior knots at the
            # parameters (odd k) or between them (even k), the end knots at ub and ue, so the
            # least squares on these knots below
            uu0 = np.asarray(u, dtype=np.float64)
            j = k // 2 + 1
            inner = uu0[j : m - k - 1 + j] if k % 2 else 0.5 * (uu0[j : m - k - 1 + j] + uu0[j - 1 : m - k - 2 + j])
            t = np.r_[(ub,) * (k + 1), inner, (ue,) * (k + 1)]
    pts = np.ascontiguousarray(x.T)
    if u is None and np.any(np.all(pts[1:] == pts[:-1], axis=1)):
        # two consecutive points coincide: the chord-length parameters do not increase
        raise ValueError("Invalid inputs")
    if u is not None and np.any(np.diff(np.asarray(u, dtype=np.float64)) <= 0):
        raise ValueError("Invalid inputs")
    if t is not None:
        # FITPACK's parcur with iopt = -1: least squares on the interior knots of t, the end
        # knots at ub and ue (the ends of u by default), u FITPACK's (lekalo's chord length)
        uu = _lekalo.parametrize(pts, "chord") if u is None else np.asarray(u, dtype=np.float64)
        t = np.atleast_1d(np.asarray(t, dtype=np.float64))
        if t.shape[0] < 2 * k + 2:
            raise TypeError(f"There must be at least 2*k+2 knots for task=-1, got {t.shape[0]}")
        ub = uu[0] if ub is None else float(ub)
        ue = uu[-1] if ue is None else float(ue)
        knots = np.r_[(ub,) * (k + 1), t[k + 1 : -k - 1], (ue,) * (k + 1)]
        curve = _lekalo.make_lsq_spline(uu, pts, knots, k, w)
    elif per and u is not None and s == 0:
        # FITPACK's clocur with s = 0 on the given parameters: the periodic interpolating spline
        # (SciPy's make_interp_spline(u, x, bc_type="periodic"), the same knots and
        # coefficients), its knots continued periodically beyond the ends as clocur's are
        uu = np.asarray(u, dtype=np.float64)
        b = make_interp_spline(uu, pts, k=k, bc_type="periodic")
        knots = b.t
        if k % 2:
            period = uu[-1] - uu[0]
            knots = np.r_[uu[-k - 1 : -1] - period, uu, uu[1 : k + 1] + period]
        curve = _TckCurve(knots, b.c, k)
    elif per and u is not None:
        # FITPACK's clocur with given parameters: the closed smoothing condition on the period
        # [u[0], u[-1]], the last point (the first again) left out, as fpclos leaves it
        uu = np.asarray(u, dtype=np.float64)
        curve, _ = _lekalo.fit_periodic(uu, pts, w=w**2, k=k, s=float(s))
    elif per:
        curve, uu = _lekalo.fit_closed(np.ascontiguousarray(pts[:-1]), w=w[:-1] ** 2, k=k, s=float(s))
    else:
        # FITPACK's parcur: the smoothing condition, the end knots at ub and ue when given
        domain = None if ub is None else (ub, ue)
        uu = None if u is None else np.asarray(u, dtype=np.float64)
        curve, uu = _lekalo.make_splprep(pts, w=w, u=uu, k=k, s=float(s), domain=domain)
    tt = np.ascontiguousarray(curve.knots)
    c = np.ascontiguousarray(np.asarray(curve.control).T)
    tcku = [tt, list(c), k], np.asarray(uu)
    if full_output:
        rows = slice(None, -1) if per else slice(None)
        fp = float(np.sum((w[rows, None] * (curve(np.asarray(uu))[rows] - pts[rows])) ** 2))
        ier = -1 if s == 0 else 0
        return tcku, fp, ier, _PARCUR_MESSAGES[ier]
    return tcku


# FITPACK's surfit messages as SciPy's bisplrep words them: ier -> (text, exception or None)
_SURFIT_IER = {
    0: ("The spline has a residual sum of squares fp such that abs(fp-s)/s<=0.001", None),
    -1: ("The spline is an interpolating spline (fp=0)", None),
    -2: ("The spline is weighted least-squares polynomial of degree kx and ky."
         "\nfp gives the upper bound fp0 for the smoothing factor s", None),
    -3: ("Warning. The coefficients of the spline have been computed as the\n"
         "minimal norm least-squares solution of a rank deficient system.", None),
    1: ("The required storage space exceeds the available storage space.\n"
        "Probable causes: nxest or nyest too small or s is too small. (fp>s)", ValueError),
    4: ("No more knots can be added because the number of B-spline\n"
        "coefficients already exceeds the number of data points m.\n"
        "Probable causes: either s or m too small. (fp>s)", ValueError),
    5: ("No more knots can be added because the additional knot would\n"
        "coincide with an old one. Probable cause: s too small or too large\n"
        "a weight to an inaccurate data point. (fp>s)", ValueError),
}


def bisplrep(
    x: Any, y: Any, z: Any, w: Any = None, xb: Any = None, xe: Any = None, yb: Any = None,
    ye: Any = None, kx: int = 3, ky: int = 3, task: int = 0, s: Any = None, eps: float = 1e-16,
    tx: Any = None, ty: Any = None, full_output: int = 0, nxest: Any = None, nyest: Any = None,
    quiet: int = 1,
):
    """``scipy.interpolate.bisplrep``: FITPACK's ``surfit`` as a list ``[tx, ty, c, kx, ky]``.
    ``task = 0``: the spline with FITPACK's knots whose weighted residual is ``s`` (default
    ``m - sqrt(2m)``), lekalo's ``fit_tensor_scattered_smoothing``
    (``docs/theory/tensor.md#smoothing-scattered-data``); ``task = -1``: least squares on the
    full knot vectors ``tx``, ``ty``, lekalo's ``fit_tensor_scattered``. Both with FITPACK's
    minimal-norm solution of a rank-deficient system (threshold ``eps``). ``task = 1`` (resume
    from the knots of the previous call) is not available. SciPy's checks, warnings and
    ``full_output``."""
    x, y, z = map(np.ravel, [x, y, z])
    m = len(x)
    if not (m == len(y) == len(z)):
        raise TypeError("len(x)==len(y)==len(z) must hold.")
    w = np.ones(m) if w is None else np.atleast_1d(w)
    if not len(w) == m:
        raise TypeError(f"len(w)={len(w)} is not equal to m={m}")
    if not (-1 <= task <= 1):
        raise TypeError("task must be -1, 0 or 1")
    if task == 1:
        raise NotImplementedError("lekalo.scipy: bisplrep with task=1 (resume from the previous knots) is not available")
    if s is None:
        s = m - np.sqrt(2 * m)
    if task == -1 and tx is None:
        raise TypeError("Knots_x must be given for task=-1")
    if task == -1 and ty is None:
        raise TypeError("Knots_y must be given for task=-1")
    if task == -1 and len(tx) < 2 * kx + 2:
        raise TypeError("There must be at least 2*kx+2 knots_x for task=-1")
    if task == -1 and len(ty) < 2 * ky + 2:
        raise TypeError("There must be at least 2*ky+2 knots_x for task=-1")
    if not ((1 <= kx <= 5) and (1 <= ky <= 5)):
        raise TypeError(f"Given degree of the spline (kx,ky={kx},{ky}) is not supported. (1<=k<=5)")
    if m < (kx + 1) * (ky + 1):
        raise TypeError("m >= (kx+1)(ky+1) must hold")
    if nxest is None:
        nxest = int(kx + np.sqrt(m / 2))
    if nyest is None:
        nyest = int(ky + np.sqrt(m / 2))
    nxest, nyest = max(nxest, 2 * kx + 3), max(nyest, 2 * ky + 3)
    if task >= 0 and s == 0:
        nxest = int(kx + np.sqrt(3 * m))
        nyest = int(ky + np.sqrt(3 * m))
    # FITPACK's workspace for these sizes (SciPy's formula), refused beyond lekalo's size limit
    # before any array is read
    u, v = nxest - kx - 1, nyest - ky - 1
    km, ne = max(kx, ky) + 1, max(nxest, nyest)
    bx, by = kx * v + ky + 1, ky * u + kx + 1
    b1, b2 = (bx, bx + v - ky) if bx <= by else (by, by + u - kx)
    lwrk1 = u * v * (2 + b1 + b2) + 2 * (u + v + km * (m + ne) + ne - kx - ky) + b2 + 1
    if lwrk1 >= _lekalo.MAX_SCALARS:
        raise OverflowError("Too many data points to interpolate")
    nonpositive = np.flatnonzero(np.asarray(w, dtype=np.float64) <= 0.0)
    if nonpositive.size:
        # FITPACK's surfit takes weights > 0 only (ier = 10), whatever the task; after SciPy's
        # size check, which reads no array; SciPy's words first
        i = int(nonpositive[0])
        raise ValueError(f"Invalid inputs. FITPACK's surfit takes weights > 0 only: w[{i}] = {w[i]}")
    xb = float(x.min()) if xb is None else float(xb)
    xe = float(x.max()) if xe is None else float(xe)
    yb = float(y.min()) if yb is None else float(yb)
    ye = float(y.max()) if ye is None else float(ye)
    x, y, z, w = (np.ascontiguousarray(a, dtype=np.float64) for a in (x, y, z, w))
    if task == 0:
        tx, ty, c, fp, ier = _surfit(x, y, z, w, [(xb, xe), (yb, ye)], kx, ky, s, eps, nxest, nyest)
    else:
        tx = np.asarray(tx, dtype=np.float64).copy()
        ty = np.asarray(ty, dtype=np.float64).copy()
        tx[: kx + 1], tx[len(tx) - kx - 1:] = xb, xe
        ty[: ky + 1], ty[len(ty) - ky - 1:] = yb, ye
        spline, _, fp, rank = _lekalo.fit_tensor_scattered(
            np.ascontiguousarray(np.stack([x, y], axis=-1)), z, (tx, ty), [int(kx), int(ky)],
            w=w**2, eps=float(eps), full_output=True,
        )
        c = np.asarray(spline.c).ravel()
        ier = -rank if rank != c.size else 0
    tck = [tx, ty, c, kx, ky]
    ierm = min(11, max(-3, ier))
    message = _SURFIT_IER[ierm][0]
    if ierm <= 0 and not quiet:
        warnings.warn(
            RuntimeWarning(message + f"\tkx,ky={kx},{ky} nx,ny={len(tx)},{len(ty)} m={m} fp={fp} s={s}"),
            stacklevel=2,
        )
    if ierm > 0 and not full_output:
        warnings.warn(
            RuntimeWarning(message + f"\n\tkx,ky={kx},{ky} nx,ny={len(tx)},{len(ty)} m={m} fp={fp} s={s}"),
            stacklevel=2,
        )
    if full_output:
        return tck, fp, ier, message
    return tck


def bisplev(x: Any, y: Any, tck: Any, dx: int = 0, dy: int = 0):
    """``scipy.interpolate.bisplev``: the 2-D spline ``tck = [tx, ty, c, kx, ky]`` (or its
    partial derivative ``(dx, dy)``) on the grid ``x × y`` (increasing), squeezed as SciPy
    squeezes it; lekalo's ``TensorBSpline``, coordinates outside the base box taken at its
    edge as FITPACK's ``bispev``."""
    tx, ty, c, kx, ky = tck
    if not (0 <= dx < kx):
        raise ValueError(f"0 <= dx = {dx} < kx = {kx} must hold")
    if not (0 <= dy < ky):
        raise ValueError(f"0 <= dy = {dy} < ky = {ky} must hold")
    xf, yf = _one_number(x), _one_number(y)
    if xf is not None and yf is not None and not dx and not dy:
        v = _value((tx, ty, c), (kx, ky), xf, yf)
        if v is not None:
            return np.float64(v)
    x, y = map(np.atleast_1d, [x, y])
    if len(x.shape) != 1 or len(y.shape) != 1:
        raise ValueError("First two entries should be rank-1 arrays.")
    if x.size == 0 or y.size == 0:
        return np.zeros((x.size, y.size))
    if (x.size >= 2 and not np.all(np.diff(x) >= 0.0)) or (y.size >= 2 and not np.all(np.diff(y) >= 0.0)):
        raise ValueError("Invalid input data: x and y must be increasing")
    z = _evaluate((tx, ty, c), (kx, ky), x, y, dx, dy, True)
    z.shape = len(x), len(y)
    if len(z) > 1:
        return z
    if len(z[0]) > 1:
        return z[0]
    return z[0][0]


def dblint(xa: float, xb: float, ya: float, yb: float, tck: Any) -> float:
    """``scipy.interpolate.dblint``: ``∫_xa^xb ∫_ya^yb`` of the 2-D spline
    ``tck = [tx, ty, c, kx, ky]`` over the base box (limits taken into it, as FITPACK),
    lekalo's ``TensorBSpline.integral``."""
    tx, ty, c, kx, ky = tck
    return _dblint((tx, ty, c), (kx, ky), xa, xb, ya, yb)
