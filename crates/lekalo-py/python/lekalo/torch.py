"""B-spline evaluation and fits as PyTorch functions: ``torch.autograd.Function`` wrappers of
lekalo's NumPy kernels, differentiable in reverse mode (``loss.backward()``,
``torch.autograd.grad``).

- ``bspline_eval(knots, control_points, u, degree)``: ``C(u)`` of a B-spline curve;
- ``nurbs_eval(knots, control_points, weights, u, degree)``: ``C(u)`` of a NURBS curve;
- ``bspline_surface_eval(knots_u, knots_v, control_points, u, v, degree_u, degree_v)``;
- ``nurbs_surface_eval(knots_u, knots_v, control_points, weights, u, v, degree_u, degree_v)``:
  ``S(u, v)`` of a NURBS surface;
- ``tensor_bspline_eval(knots, control_points, x, degrees)``: ``N``-variate tensor splines;
- ``tensor_nurbs_eval(knots, control_points, weights, x, degrees)``: ``N``-variate tensor NURBS;
- ``fit_least_squares(points, params, t, k=3, *, w=None)`` and
  ``fit_smoothing(x, y, w=None, lam=...)``: the control points of the fits, differentiable with
  respect to the data (the least-squares fit also with respect to its knots).

Each forward calls the library's kernel (the values are bit-for-bit lekalo's evaluation or fit)
and each backward its vector-Jacobian product (``lekalo.bspline_curve_vjp``, ...,
``lekalo.least_squares_vjp``, ``lekalo.smoothing_vjp``; ``docs/theory/derivatives.md``). A fit's
forward pass keeps the map of its factorisation (``lekalo.least_squares_values_and_factors``,
``lekalo.smoothing_values_and_factors``), which its backward pass applies (``factors=``):
one factorisation a fit, not two.
Leading batch axes of the control points (or of the data of a fit) are looped over, one library
call a batch element.

Limits, each with a clear error:

- float64 tensors only (``torch.float64``; ``lekalo.InputError`` otherwise);
- first derivatives in reverse mode: no ``torch.func.jvp`` / forward-mode AD, no double
  backward (``create_graph=True`` derivatives of the backward are not tracked);
- the knots of the six evaluations may ask for their gradient (the interior knots':
  ``lekalo.bspline_curve_knot_vjp``, ``lekalo.nurbs_curve_knot_vjp``,
  ``lekalo.bspline_surface_knot_vjp``, ``lekalo.tensor_bspline_knot_vjp``,
  ``lekalo.nurbs_surface_knot_vjp``, ``lekalo.tensor_nurbs_knot_vjp``; the ``degree + 1``
  first and last of a direction are held fixed, their gradient zero), and so may the knots of
  ``fit_least_squares`` (``lekalo.least_squares_knot_vjp``); the knots of ``fit_smoothing``
  (its ``x``), the degrees, fit parameters and weights are constants (plain arrays or tensors
  whose gradient is not asked for);
- runs on the CPU: tensors on another device are copied to the host and back.
"""

from __future__ import annotations

import numpy as np

try:
    import torch
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "lekalo.torch needs PyTorch 2.0 or newer, which is not installed: `pip install torch`, "
        "or install lekalo with its extra, `pip install \"./crates/lekalo-py[torch]\"` from a "
        "clone of the repository"
    ) from e

from . import _lekalo
from ._lekalo import InputError

__all__ = [
    "bspline_eval",
    "nurbs_eval",
    "bspline_surface_eval",
    "nurbs_surface_eval",
    "tensor_bspline_eval",
    "tensor_nurbs_eval",
    "fit_least_squares",
    "fit_smoothing",
]


def _tensor(x, what, name):
    """A float64 tensor (an array or a number is converted; another dtype is refused)."""
    if not isinstance(x, torch.Tensor):
        x = torch.as_tensor(np.asarray(x, dtype=np.float64))
    if x.dtype != torch.float64:
        raise InputError(
            f"lekalo.torch.{name}: {what} must be torch.float64, got {x.dtype}; "
            "convert with .double()"
        )
    return x


def _np(x):
    return np.ascontiguousarray(x.detach().cpu().numpy())


def _constant(x, what, name):
    """A constant argument as a NumPy array (refusing a tensor that asks for its gradient)."""
    if isinstance(x, torch.Tensor):
        if x.requires_grad:
            raise InputError(
                f"lekalo.torch.{name}: derivatives with respect to {what} are not supported; "
                "pass it as a constant (.detach())"
            )
        return _np(x.double())
    return np.asarray(x, dtype=np.float64)


def _knots(x, what, name):
    """Knots that may ask for their gradient: a float64 tensor (shared by the batch)."""
    if isinstance(x, torch.Tensor) and x.requires_grad:
        return _tensor(x, what, name)
    return torch.from_numpy(_constant(x, what, name))


def _batch_sum(a, batch):
    """A cotangent of an argument the batch shares: summed over the batch axes."""
    return a.sum(axis=tuple(range(len(batch)))) if batch else a


def _looped(fn, batch, *arrays):
    """``fn`` over the batch shape ``batch``: ``arrays`` are ``(array, batched)`` pairs, a
    batched array indexed by the batch index and a shared one passed whole; one call a batch
    element, the results stacked."""
    if batch == ():
        return fn(*(a for a, _ in arrays))
    results = []
    for idx in np.ndindex(*batch):
        results.append(fn(*(a[idx] if b else a for a, b in arrays)))
    if isinstance(results[0], tuple):
        return tuple(
            np.stack([r[k] for r in results]).reshape(batch + results[0][k].shape)
            for k in range(len(results[0]))
        )
    return np.stack(results).reshape(batch + results[0].shape)


def _out(a, like):
    return torch.from_numpy(np.ascontiguousarray(a)).to(like.device)


def _batch_of(ctrl_nd, core, *others):
    """The batch shape of the control points (``core`` trailing axes), and for each other
    argument with its core rank whether it carries the same batch axes."""
    batch = tuple(ctrl_nd.shape[: ctrl_nd.ndim - core])
    flags = []
    for a, c in others:
        lead = tuple(a.shape[: a.ndim - c])
        if lead not in ((), batch):
            raise InputError(
                f"batch axes {lead} of an argument differ from the control points' {batch}"
            )
        flags.append(lead == batch and lead != ())
    return batch, flags


# -- curves ------------------------------------------------------------------------------------


class _BSplineCurve(torch.autograd.Function):
    @staticmethod
    def forward(ctx, ctrl, u, knots_t, degree):
        c, t, knots = _np(ctrl), _np(u), _np(knots_t)
        batch, (ub,) = _batch_of(c, 2, (t, 1))
        ctx.save_for_backward(ctrl, u, knots_t)
        ctx.args = (knots, degree, batch, ub)
        vals = _looped(lambda cc, tt: _lekalo.bspline_curve_jvp(degree, knots, cc, tt)[0], batch, (c, True), (t, ub))
        return _out(vals, ctrl)

    @staticmethod
    def backward(ctx, g):
        ctrl, u, knots_t = ctx.saved_tensors
        knots, degree, batch, ub = ctx.args
        arrays = ((_np(ctrl), True), (_np(u), ub), (_np(g), True))
        gc, gu = _looped(
            lambda cc, tt, gg: _lekalo.bspline_curve_vjp(degree, knots, cc, tt, gg),
            batch,
            *arrays,
        )
        if not ub and batch:
            gu = gu.sum(axis=tuple(range(len(batch))))
        gk = None
        if ctx.needs_input_grad[2]:
            gk = _looped(
                lambda cc, tt, gg: _lekalo.bspline_curve_knot_vjp(degree, knots, cc, tt, gg),
                batch,
                *arrays,
            )
            gk = _out(_batch_sum(gk, batch), knots_t)
        return _out(gc, ctrl), _out(gu, u), gk, None


def bspline_eval(knots, control_points, u, degree):
    """``C(u)`` of the B-spline curve of ``degree`` on ``knots`` with ``control_points``
    (``(..., n, dim)``: leading axes are a batch of curves) at the parameters ``u`` (``(m,)``,
    shared, or ``(..., m)`` with the same batch axes). Returns ``(..., m, dim)``, bit-for-bit
    lekalo's evaluation; differentiable with respect to ``control_points``, ``u`` and ``knots``
    (the interior knots; the ``degree + 1`` first and last are held fixed).
    """
    name = "bspline_eval"
    ctrl = _tensor(control_points, "control_points", name)
    u = _tensor(u, "u", name)
    knots = _knots(knots, "the knots", name)
    if ctrl.ndim < 2:
        raise InputError(f"lekalo.torch.{name}: control_points must be (..., n, dim), got {tuple(ctrl.shape)}")
    return _BSplineCurve.apply(ctrl, u, knots, int(degree))


class _NurbsCurve(torch.autograd.Function):
    @staticmethod
    def forward(ctx, ctrl, w, u, knots_t, degree):
        c, ws, t, knots = _np(ctrl), _np(w), _np(u), _np(knots_t)
        batch, (wb, ub) = _batch_of(c, 2, (ws, 1), (t, 1))
        ctx.save_for_backward(ctrl, w, u, knots_t)
        ctx.args = (knots, degree, batch, wb, ub)
        vals = _looped(
            lambda cc, ww, tt: _lekalo.nurbs_curve_jvp(degree, knots, cc, ww, tt)[0],
            batch,
            (c, True),
            (ws, wb),
            (t, ub),
        )
        return _out(vals, ctrl)

    @staticmethod
    def backward(ctx, g):
        ctrl, w, u, knots_t = ctx.saved_tensors
        knots, degree, batch, wb, ub = ctx.args
        arrays = ((_np(ctrl), True), (_np(w), wb), (_np(u), ub), (_np(g), True))
        gc, gw, gu = _looped(
            lambda cc, ww, tt, gg: _lekalo.nurbs_curve_vjp(degree, knots, cc, ww, tt, gg),
            batch,
            *arrays,
        )
        axes = tuple(range(len(batch)))
        if not wb and batch:
            gw = gw.sum(axis=axes)
        if not ub and batch:
            gu = gu.sum(axis=axes)
        gk = None
        if ctx.needs_input_grad[3]:
            gk = _looped(
                lambda cc, ww, tt, gg: _lekalo.nurbs_curve_knot_vjp(degree, knots, cc, ww, tt, gg),
                batch,
                *arrays,
            )
            gk = _out(_batch_sum(gk, batch), knots_t)
        return _out(gc, ctrl), _out(gw, w), _out(gu, u), gk, None


def nurbs_eval(knots, control_points, weights, u, degree):
    """``C(u)`` of the NURBS curve with Euclidean ``control_points`` (``(..., n, dim)``) and
    ``weights`` (``(n,)`` or ``(..., n)``) at ``u`` (``(m,)`` or ``(..., m)``); differentiable
    with respect to the control points, the weights, ``u`` and ``knots`` (the interior knots;
    the ``degree + 1`` first and last are held fixed)."""
    name = "nurbs_eval"
    ctrl = _tensor(control_points, "control_points", name)
    w = _tensor(weights, "weights", name)
    u = _tensor(u, "u", name)
    knots = _knots(knots, "the knots", name)
    return _NurbsCurve.apply(ctrl, w, u, knots, int(degree))


# -- surfaces ----------------------------------------------------------------------------------


class _BSplineSurface(torch.autograd.Function):
    @staticmethod
    def forward(ctx, net, u, v, ku_t, kv_t, degrees):
        c, a, b, ku, kv = _np(net), _np(u), _np(v), _np(ku_t), _np(kv_t)
        batch, (ab, bb) = _batch_of(c, 3, (a, 1), (b, 1))
        ctx.save_for_backward(net, u, v, ku_t, kv_t)
        ctx.args = (ku, kv, degrees, batch, ab, bb)
        vals = _looped(
            lambda cc, x, y: _lekalo.bspline_surface_jvp(*degrees, ku, kv, cc, x, y)[0],
            batch,
            (c, True),
            (a, ab),
            (b, bb),
        )
        return _out(vals, net)

    @staticmethod
    def backward(ctx, g):
        net, u, v, ku_t, kv_t = ctx.saved_tensors
        ku, kv, degrees, batch, ab, bb = ctx.args
        arrays = ((_np(net), True), (_np(u), ab), (_np(v), bb), (_np(g), True))
        gc, gu, gv = _looped(
            lambda cc, x, y, gg: _lekalo.bspline_surface_vjp(*degrees, ku, kv, cc, x, y, gg),
            batch,
            *arrays,
        )
        gku = gkv = None
        if ctx.needs_input_grad[3] or ctx.needs_input_grad[4]:
            gku, gkv = _looped(
                lambda cc, x, y, gg: _lekalo.bspline_surface_knot_vjp(*degrees, ku, kv, cc, x, y, gg),
                batch,
                *arrays,
            )
            gku = _out(_batch_sum(gku, batch), ku_t) if ctx.needs_input_grad[3] else None
            gkv = _out(_batch_sum(gkv, batch), kv_t) if ctx.needs_input_grad[4] else None
        axes = tuple(range(len(batch)))
        if not ab and batch:
            gu = gu.sum(axis=axes)
        if not bb and batch:
            gv = gv.sum(axis=axes)
        return _out(gc, net), _out(gu, u), _out(gv, v), gku, gkv, None


def bspline_surface_eval(knots_u, knots_v, control_points, u, v, degree_u, degree_v):
    """``S(u, v)`` of the tensor-product B-spline surface with the net ``control_points``
    (``(..., nu, nv, dim)``) at pairs ``u``, ``v`` (``(m,)`` each, or with the batch axes);
    differentiable with respect to the net, ``u``, ``v`` and the interior knots."""
    name = "bspline_surface_eval"
    net = _tensor(control_points, "control_points", name)
    u = _tensor(u, "u", name)
    v = _tensor(v, "v", name)
    ku = _knots(knots_u, "the knots", name)
    kv = _knots(knots_v, "the knots", name)
    return _BSplineSurface.apply(net, u, v, ku, kv, (int(degree_u), int(degree_v)))


class _NurbsSurface(torch.autograd.Function):
    @staticmethod
    def forward(ctx, net, w, u, v, ku_t, kv_t, degrees):
        c, ws, a, b, ku, kv = _np(net), _np(w), _np(u), _np(v), _np(ku_t), _np(kv_t)
        batch, (wb, ab, bb) = _batch_of(c, 3, (ws, 2), (a, 1), (b, 1))
        ctx.save_for_backward(net, w, u, v, ku_t, kv_t)
        ctx.args = (ku, kv, degrees, batch, wb, ab, bb)
        vals = _looped(
            lambda cc, ww, x, y: _lekalo.nurbs_surface_jvp(*degrees, ku, kv, cc, ww, x, y)[0],
            batch,
            (c, True),
            (ws, wb),
            (a, ab),
            (b, bb),
        )
        return _out(vals, net)

    @staticmethod
    def backward(ctx, g):
        net, w, u, v, ku_t, kv_t = ctx.saved_tensors
        ku, kv, degrees, batch, wb, ab, bb = ctx.args
        arrays = ((_np(net), True), (_np(w), wb), (_np(u), ab), (_np(v), bb), (_np(g), True))
        gc, gw, gu, gv = _looped(
            lambda cc, ww, x, y, gg: _lekalo.nurbs_surface_vjp(*degrees, ku, kv, cc, ww, x, y, gg),
            batch,
            *arrays,
        )
        gku = gkv = None
        if ctx.needs_input_grad[4] or ctx.needs_input_grad[5]:
            gku, gkv = _looped(
                lambda cc, ww, x, y, gg: _lekalo.nurbs_surface_knot_vjp(
                    *degrees, ku, kv, cc, ww, x, y, gg
                ),
                batch,
                *arrays,
            )
            gku = _out(_batch_sum(gku, batch), ku_t) if ctx.needs_input_grad[4] else None
            gkv = _out(_batch_sum(gkv, batch), kv_t) if ctx.needs_input_grad[5] else None
        axes = tuple(range(len(batch)))
        if not wb and batch:
            gw = gw.sum(axis=axes)
        if not ab and batch:
            gu = gu.sum(axis=axes)
        if not bb and batch:
            gv = gv.sum(axis=axes)
        return _out(gc, net), _out(gw, w), _out(gu, u), _out(gv, v), gku, gkv, None


def nurbs_surface_eval(knots_u, knots_v, control_points, weights, u, v, degree_u, degree_v):
    """``S(u, v)`` of the NURBS surface with the Euclidean net ``control_points``
    (``(..., nu, nv, dim)``) and positive ``weights`` (``(nu, nv)`` or with the batch axes) at
    pairs ``u``, ``v`` (``(m,)`` each, or with the batch axes); differentiable with respect to
    the net, the weights, ``u``, ``v`` and the interior knots."""
    name = "nurbs_surface_eval"
    net = _tensor(control_points, "control_points", name)
    w = _tensor(weights, "weights", name)
    u = _tensor(u, "u", name)
    v = _tensor(v, "v", name)
    ku = _knots(knots_u, "the knots", name)
    kv = _knots(knots_v, "the knots", name)
    return _NurbsSurface.apply(net, w, u, v, ku, kv, (int(degree_u), int(degree_v)))


# -- tensor-product splines ----------------------------------------------------------------------


class _TensorSpline(torch.autograd.Function):
    @staticmethod
    def forward(ctx, ctrl, x, degrees, *knots_t):
        n = len(degrees)
        c, p, knots = _np(ctrl), _np(x), [_np(k) for k in knots_t]
        batch, (xb,) = _batch_of(c, n + 1, (p, 2))
        ctx.save_for_backward(ctrl, x, *knots_t)
        ctx.args = (knots, degrees, batch, xb)
        vals = _looped(
            lambda cc, pp: _lekalo.tensor_bspline_jvp(knots, cc, degrees, pp)[0],
            batch,
            (c, True),
            (p, xb),
        )
        return _out(vals, ctrl)

    @staticmethod
    def backward(ctx, g):
        ctrl, x, *knots_t = ctx.saved_tensors
        knots, degrees, batch, xb = ctx.args
        arrays = ((_np(ctrl), True), (_np(x), xb), (_np(g), True))
        gc, gx = _looped(
            lambda cc, pp, gg: _lekalo.tensor_bspline_vjp(knots, cc, degrees, pp, gg),
            batch,
            *arrays,
        )
        if not xb and batch:
            gx = gx.sum(axis=tuple(range(len(batch))))
        gks = [None] * len(knots)
        if any(ctx.needs_input_grad[3:]):
            got = _looped(
                lambda cc, pp, gg: _lekalo.tensor_bspline_knot_vjp(knots, cc, degrees, pp, gg),
                batch,
                *arrays,
            )
            gks = [
                _out(_batch_sum(gk, batch), kt) if wanted else None
                for gk, kt, wanted in zip(got, knots_t, ctx.needs_input_grad[3:])
            ]
        return (_out(gc, ctrl), _out(gx, x), None, *gks)


def tensor_bspline_eval(knots, control_points, x, degrees):
    """``S(x)`` of the tensor-product B-spline in ``N`` variables (``knots`` a sequence of ``N``
    1-D arrays, ``degrees`` of ``N`` ints) with coefficients ``control_points``
    (``(..., n_1, ..., n_N, dim)``) at the points ``x`` (``(m, N)`` or ``(..., m, N)``):
    ``(..., m, dim)``; differentiable with respect to the coefficients, ``x`` and ``knots``
    (the interior knots of each variable; the ``degree + 1`` first and last are held fixed)."""
    name = "tensor_bspline_eval"
    ctrl = _tensor(control_points, "control_points", name)
    x = _tensor(x, "x", name)
    knots = [_knots(k, "the knots", name) for k in knots]
    return _TensorSpline.apply(ctrl, x, tuple(int(d) for d in degrees), *knots)


class _TensorNurbs(torch.autograd.Function):
    @staticmethod
    def forward(ctx, ctrl, w, x, degrees, *knots_t):
        n = len(degrees)
        c, ws, p, knots = _np(ctrl), _np(w), _np(x), [_np(k) for k in knots_t]
        batch, (wb, xb) = _batch_of(c, n + 1, (ws, n), (p, 2))
        ctx.save_for_backward(ctrl, w, x, *knots_t)
        ctx.args = (knots, degrees, batch, wb, xb)
        vals = _looped(
            lambda cc, ww, pp: _lekalo.tensor_nurbs_jvp(knots, cc, degrees, ww, pp)[0],
            batch,
            (c, True),
            (ws, wb),
            (p, xb),
        )
        return _out(vals, ctrl)

    @staticmethod
    def backward(ctx, g):
        ctrl, w, x, *knots_t = ctx.saved_tensors
        knots, degrees, batch, wb, xb = ctx.args
        arrays = ((_np(ctrl), True), (_np(w), wb), (_np(x), xb), (_np(g), True))
        gc, gw, gx = _looped(
            lambda cc, ww, pp, gg: _lekalo.tensor_nurbs_vjp(knots, cc, degrees, ww, pp, gg),
            batch,
            *arrays,
        )
        axes = tuple(range(len(batch)))
        if not wb and batch:
            gw = gw.sum(axis=axes)
        if not xb and batch:
            gx = gx.sum(axis=axes)
        gks = [None] * len(knots)
        if any(ctx.needs_input_grad[4:]):
            got = _looped(
                lambda cc, ww, pp, gg: _lekalo.tensor_nurbs_knot_vjp(knots, cc, degrees, ww, pp, gg),
                batch,
                *arrays,
            )
            gks = [
                _out(_batch_sum(gk, batch), kt) if wanted else None
                for gk, kt, wanted in zip(got, knots_t, ctx.needs_input_grad[4:])
            ]
        return (_out(gc, ctrl), _out(gw, w), _out(gx, x), None, *gks)


def tensor_nurbs_eval(knots, control_points, weights, x, degrees):
    """``S(x)`` of the tensor-product NURBS in ``N`` variables (``knots`` a sequence of ``N``
    1-D arrays, ``degrees`` of ``N`` ints) with Euclidean coefficients ``control_points``
    (``(..., n_1, ..., n_N, dim)``) and positive ``weights`` (``(n_1, ..., n_N)`` or with the
    batch axes) at the points ``x`` (``(m, N)`` or ``(..., m, N)``): ``(..., m, dim)``;
    differentiable with respect to the coefficients, the weights, ``x`` and ``knots`` (the
    interior knots of each variable; the ``degree + 1`` first and last are held fixed)."""
    name = "tensor_nurbs_eval"
    ctrl = _tensor(control_points, "control_points", name)
    w = _tensor(weights, "weights", name)
    x = _tensor(x, "x", name)
    knots = [_knots(k, "the knots", name) for k in knots]
    return _TensorNurbs.apply(ctrl, w, x, tuple(int(d) for d in degrees), *knots)


# -- fits ----------------------------------------------------------------------------------------


class _LeastSquares(torch.autograd.Function):
    @staticmethod
    def forward(ctx, q, params, t_t, k, w):
        y, t = _np(q), _np(t_t)
        batch = tuple(y.shape[:-2])

        def one(yy):
            return _lekalo.least_squares_values_and_factors(k, t, params, yy, w)

        # the values and the map of their one banded QR, which the backward pass applies
        control, factors = _looped(one, batch, (y, True))
        ctx.save_for_backward(t_t)
        ctx.args = (params, t, k, w, batch, factors, y)
        return _out(control, q)

    @staticmethod
    def backward(ctx, g):
        (t_t,) = ctx.saved_tensors
        params, t, k, w, batch, factors, y = ctx.args
        gn = _np(g)
        gq = gk = None
        if ctx.needs_input_grad[0]:

            def one(gg, f):
                return _lekalo.least_squares_vjp(k, t, params, gg, w, factors=f)

            gq = _out(_looped(one, batch, (gn, True), (factors, True)), g)
        if ctx.needs_input_grad[2]:

            def knot(yy, gg):
                return _lekalo.least_squares_knot_vjp(k, t, params, yy, gg, w)

            gk = _out(_batch_sum(_looped(knot, batch, (y, True), (gn, True)), batch), t_t)
        return gq, None, gk, None, None


def fit_least_squares(points, params, t, k=3, *, w=None):
    """The control points (``(..., len(t) - k - 1, dim)``) of the weighted least-squares
    B-spline of degree ``k`` on the knots ``t`` through ``points`` (``(..., m, dim)``: leading
    axes are a batch of data sets) at ``params``: ``lekalo.fit_least_squares(points, params, t,
    k, w=w)[0].control``, bit for bit. Differentiable with respect to ``points`` and ``t`` (the
    interior knots, by ``lekalo.least_squares_knot_vjp``, summed over a batch; the ``k + 1``
    first and last are held fixed); ``params``, ``k`` and ``w`` are constants."""
    name = "fit_least_squares"
    q = _tensor(points, "points", name)
    if q.ndim < 2:
        raise InputError(f"lekalo.torch.{name}: points must be (..., m, dim), got {tuple(q.shape)}")
    params = _constant(params, "the parameters", name)
    t = _knots(t, "the knots", name)
    w = None if w is None else _constant(w, "the weights", name)
    return _LeastSquares.apply(q, params, t, int(k), w)


class _Smoothing(torch.autograd.Function):
    @staticmethod
    def forward(ctx, q, x, w, lam):
        y = _np(q)
        batch = tuple(y.shape[:-2])

        def one(yy):
            return _lekalo.smoothing_values_and_factors(x, yy, lam, w)

        # the values and the map of their one factorisation, which the backward pass applies
        control, factors = _looped(one, batch, (y, True))
        ctx.args = (x, w, lam, batch, factors)
        return _out(control, q)

    @staticmethod
    def backward(ctx, g):
        x, w, lam, batch, factors = ctx.args

        def one(gg, f):
            return _lekalo.smoothing_vjp(x, lam, gg, w, factors=f)

        gq = _looped(one, batch, (_np(g), True), (factors, True))
        return _out(gq, g), None, None, None


def fit_smoothing(x, y, w=None, lam=None):
    """The control points (``(..., len(x) + 2, dim)``) of the cubic smoothing spline with the
    given penalty ``lam > 0`` through ``y`` (``(..., m, dim)``) at ``x``:
    ``lekalo.fit_smoothing(x, y, w, lam)[0].control``, bit for bit. Differentiable with respect
    to ``y``; ``x``, ``w`` and ``lam`` are constants (``lam`` must be given: the GCV choice is
    not differentiated)."""
    name = "fit_smoothing"
    if lam is None or not float(lam) > 0.0:
        raise InputError(
            f"lekalo.torch.{name}: give lam > 0 (a number); the GCV choice of lam depends on "
            f"the data and is not differentiated, got {lam!r}"
        )
    q = _tensor(y, "y", name)
    if q.ndim < 2:
        raise InputError(f"lekalo.torch.{name}: y must be (..., m, dim), got {tuple(q.shape)}")
    x = _constant(x, "x", name)
    w = None if w is None else _constant(w, "the weights", name)
    return _Smoothing.apply(q, x, w, float(lam))
