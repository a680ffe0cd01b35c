"""Control points from data as JAX functions: ``interpolate``, ``fit_least_squares`` and
``fit_smoothing`` of ``lekalo.jax``, differentiable with respect to the data (and the
interpolation's parameters) by the library's linearisations and adjoint solves with the same
banded factorisation (``docs/theory/derivatives.md``). ``interpolate`` runs as lekalo's XLA FFI
targets (values, JVP and VJP compiled into the program); the fits call lekalo through
``jax.pure_callback``."""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp
import numpy as np
from jax.custom_derivatives import SymbolicZero

from . import _lekalo
from ._jax_ffi import Kernel
from ._lekalo import InputError
from ._jax_support import (
    _callback,
    _degree,
    _first_order_only,
    _float64,
    _linearized,
    _looped,
    _no_knot_tangent,
    _require_x64,
    _struct,
)


# -- interpolation -------------------------------------------------------------------------------


def _interp_out_shape(res):
    """The control points' shape from the residuals ``(t, points, params)``: the points'."""
    return res[1].shape


# values, JVP and VJP as the FFI targets ``lekalo_interpolate_*`` (``xla_ffi/interpolate.rs``)
_INTERP = Kernel("interpolate", "lekalo_interpolate", ("data", "parameter"), _interp_out_shape)


def _points_at_params(name, k, points, params, t):
    """The arguments of ``lekalo.jax.{name}(points, params, t, k)`` checked in order: ``k``
    a degree, ``points`` as ``(m, dim)`` (and whether they were 1-D), ``params`` one a point,
    all in float64. Returns ``(k, params, t, scalar, points)``."""
    _require_x64(name)
    k = _degree(k, "k", name)
    points = _float64(points, "points", name)
    params = _float64(params, "params", name)
    t = _float64(t, "t", name)
    scalar, q = _points_arg(points, name, "points")
    m = q.shape[0]
    if params.shape != (m,):
        raise InputError(
            f"lekalo.jax.{name}: params must be one a point, shape ({m},), got {params.shape}"
        )
    return k, params, t, scalar, q


def interpolate(points, params, t, k=3):
    """The control points of the B-spline of degree ``k`` on the knots ``t`` that interpolates
    ``points`` (``(m, dim)``, or ``(m,)`` for a function) at the sorted ``params``, one a control
    point (``len(t) == m + k + 1``): the solution of the collocation system ``A P = points``,
    ``A[r, i] = N_{i,k}(params[r])``, with lekalo's banded factorisation
    (``lekalo.interpolation_jvp(k, t, params, points)``, bit for bit; the same control points as
    ``scipy.interpolate.make_interp_spline(params, points, k, t=t)``). Shape ``(m, dim)`` (or
    ``(m,)``).

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``points`` and ``params``: ``Ṗ = A⁻¹ (Q̇ - C'(params) ẋ)`` and, in reverse mode,
    ``Q̄ = A⁻ᵀ P̄``, ``x̄_r = -C'(params_r) · Q̄_r`` (the adjoint solve with the same banded
    factors), ``C'`` the interpolant's derivative (``lekalo::derivatives::Interpolant``,
    ``docs/theory/derivatives.md``, "Interpolation"). Values, JVP and VJP are lekalo's XLA FFI
    targets, compiled into the program (no host callback). At a parameter on an interior knot
    where ``C'`` jumps (a knot of multiplicity ``k`` or more), the right-hand derivative is
    used. ``t`` and ``k`` are constants. The parameters must satisfy the Schoenberg–Whitney
    condition (``t[r] < params[r] < t[r + k + 1]``, ends excepted); otherwise lekalo's error
    reaches the caller as ``jax.errors.JaxRuntimeError``.
    """
    name = "interpolate"
    k, params, t, scalar, q = _points_at_params(name, k, points, params, t)
    m = q.shape[0]
    if t.ndim != 1 or t.shape[0] != m + k + 1:
        raise InputError(
            f"lekalo.jax.{name}: {m} points of degree {k} need {m + k + 1} knots (points + "
            f"degree + 1: as many control points as points), got t of shape {t.shape}"
        )
    if q.size == 0:
        # XLA skips a custom call with an empty result, so lekalo would never see this call
        raise InputError(
            f"lekalo.jax.{name}: points of shape {q.shape} are empty; interpolation of degree "
            f"{k} needs at least {k + 1} points of at least one coordinate"
        )
    out = _INTERP((("degree", k),), (t,), (q, params))
    return out[:, 0] if scalar else out


# -- fits ----------------------------------------------------------------------------------------


def _constant_only(name, what, *tangents):
    if any(not isinstance(t, SymbolicZero) for t in tangents):
        raise NotImplementedError(
            f"lekalo.jax.{name}: derivatives with respect to {what} are not supported (the fit "
            "is differentiated with respect to the data values only); pass them as constants "
            "(close over them, or wrap them in jax.lax.stop_gradient)"
        )


def _banded_normal_solve(tri, z):
    """``(RᵀR)⁻¹ z`` for the banded upper triangle ``R`` (row ``i`` of ``tri`` holds
    ``R[i, i:i + bw]``) and ``z`` of shape ``(n, d)``: a forward sweep with ``Rᵀ`` and a backward
    sweep with ``R``, each a ``lax.scan`` over the rows carrying the ``bw - 1`` neighbours solved
    last. Linear in ``z``, so JAX transposes it (reverse mode) and batches it (``vmap``)."""
    n, bw = tri.shape
    diag = tri[:, 0]
    if bw == 1:
        return z / (diag * diag)[:, None]
    i = jnp.arange(n)[:, None]
    k = jnp.arange(1, bw)[None, :]
    # Rᵀ y = z: y_i = (z_i - Σ_k R[i - k, i] y_{i - k}) / R[i, i]
    lower = jnp.where(i - k >= 0, tri[jnp.clip(i - k, 0), k], 0.0)
    # R x = y: x_i = (y_i - Σ_k R[i, i + k] x_{i + k}) / R[i, i]
    upper = jnp.where(i + k < n, tri[:, 1:], 0.0)

    def sweep(window, row):
        zi, coef, d = row
        xi = (zi - coef @ window) / d
        return jnp.concatenate([xi[None], window[:-1]]), xi

    start = jnp.zeros((bw - 1,) + z.shape[1:], z.dtype)
    _, y = jax.lax.scan(sweep, start, (z, lower, diag))
    _, x = jax.lax.scan(sweep, start, (y, upper, diag), reverse=True)
    return x


def _fit_tangent(first, basis, weights, tri, dq):
    """``(RᵀR)⁻¹ BᵀW dq`` from a fit's linearisation: a scatter-add of the weighted sparse rows,
    then the banded solve (``docs/theory/derivatives.md``, "Fits")."""
    rows = first[:, None] + jnp.arange(basis.shape[1])
    contrib = (weights[:, None] * basis)[..., None] * dq[:, None, :]
    z = jnp.zeros((tri.shape[0], dq.shape[1]), dq.dtype).at[rows].add(contrib)
    return _banded_normal_solve(tri, z)


def _fit_linearization_shapes(m, width, n, bw):
    return (_struct((m,), jnp.int64), _struct((m, width)), _struct((m,)), _struct((n, bw)))


def _lin_tuple(d):
    return d["first"], d["basis"], d["weights"], d["triangle"]


def _lsq_values_cb(k, weighted, points, params, t, w):
    def one(q, x, kn, ws):
        fit = _lekalo.fit_least_squares(q, x, kn, k, w=ws if weighted else None)[0]
        return (np.asarray(fit.control).reshape(len(kn) - k - 1, q.shape[-1]),)

    return _looped(one, (2, 1, 1, 1), points, params, t, w)[0]


def _lsq_linearize_cb(k, weighted, params, t, w):
    def one(x, kn, ws):
        return _lin_tuple(_lekalo.least_squares_linearize(k, kn, x, ws if weighted else None))

    return _looped(one, (1, 1, 1), params, t, w)


@partial(jax.custom_jvp, nondiff_argnums=(0, 1))
def _lsq(k, weighted, points, params, t, w):
    shape = _struct((t.shape[0] - k - 1, points.shape[1]))
    return _callback(partial(_lsq_values_cb, k, weighted), shape, points, params, t, w)


@partial(_lsq.defjvp, symbolic_zeros=True)
def _lsq_jvp(k, weighted, primals, tangents):
    points, params, t, w = primals
    dq, dx, dt, dw = tangents
    name = "fit_least_squares"
    _constant_only(name, "the parameters, the knots or the weights", dx, dt, dw)
    guard = partial(_first_order_only, name)
    values = _lsq(k, weighted, guard(points), params, t, w)
    if isinstance(dq, SymbolicZero):
        return values, jnp.zeros_like(values)
    n, m = t.shape[0] - k - 1, params.shape[0]
    shapes = _fit_linearization_shapes(m, k + 1, n, k + 1)
    lin = _linearized(name, partial(_lsq_linearize_cb, k, weighted), shapes, params, t, w)
    return values, _fit_tangent(*lin, dq)


def _points_arg(points, name, what):
    if points.ndim not in (1, 2):
        raise InputError(
            f"lekalo.jax.{name}: {what} must be (m, dim) or (m,), got shape {points.shape}"
        )
    return points.ndim == 1, points[:, None] if points.ndim == 1 else points


def _weights_arg(w, m, name):
    if w is None:
        return False, jnp.ones((m,), jnp.float64)
    w = _float64(w, "w", name)
    if w.shape != (m,):
        raise InputError(f"lekalo.jax.{name}: w must be one a data point, shape ({m},), got {w.shape}")
    return True, w


def fit_least_squares(points, params, t, k=3, *, w=None):
    """The control points of the weighted least-squares B-spline of degree ``k`` on the knots
    ``t`` through ``points`` (``(m, dim)``, or ``(m,)`` for a function) at ``params``:
    ``lekalo.fit_least_squares(points, params, t, k, w=w)[0].control``, bit for bit, shape
    ``(len(t) - k - 1, dim)`` (or ``(len(t) - k - 1,)``). ``w`` weighs the squared residuals,
    ``Σ w_k |C(params_k) - points_k|²``.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``points``: the fit is linear in them, ``P = (BᵀWB)⁻¹ BᵀW Q``, and its
    derivatives apply the sparse rows of ``B`` and the triangle of lekalo's banded QR
    (``lekalo.least_squares_linearize``). ``params``, ``t``, ``w`` and ``k`` are constants.
    """
    name = "fit_least_squares"
    k, params, t, scalar, q = _points_at_params(name, k, points, params, t)
    m = q.shape[0]
    if t.ndim != 1 or t.shape[0] < 2 * (k + 1):
        raise InputError(
            f"lekalo.jax.{name}: t must be a 1-D knot vector of at least 2 (k + 1) = "
            f"{2 * (k + 1)} knots, got shape {t.shape}"
        )
    weighted, w = _weights_arg(w, m, name)
    out = _lsq(k, weighted, q, params, t, w)
    return out[:, 0] if scalar else out


def _smoothing_values_cb(lam, weighted, x, y, w):
    def one(xs, ys, ws):
        fit = _lekalo.fit_smoothing(xs, ys, ws if weighted else None, lam)[0]
        return (np.asarray(fit.control).reshape(xs.shape[0] + 2, ys.shape[-1]),)

    return _looped(one, (1, 2, 1), x, y, w)[0]


def _smoothing_linearize_cb(lam, weighted, x, w):
    def one(xs, ws):
        return _lin_tuple(_lekalo.smoothing_linearize(xs, lam, ws if weighted else None))

    return _looped(one, (1, 1), x, w)


@partial(jax.custom_jvp, nondiff_argnums=(0, 1))
def _smoothing(lam, weighted, x, y, w):
    shape = _struct((x.shape[0] + 2, y.shape[1]))
    return _callback(partial(_smoothing_values_cb, lam, weighted), shape, x, y, w)


@partial(_smoothing.defjvp, symbolic_zeros=True)
def _smoothing_jvp(lam, weighted, primals, tangents):
    x, y, w = primals
    dx, dy, dw = tangents
    name = "fit_smoothing"
    _constant_only(name, "x or the weights", dx, dw)
    guard = partial(_first_order_only, name)
    values = _smoothing(lam, weighted, x, guard(y), w)
    if isinstance(dy, SymbolicZero):
        return values, jnp.zeros_like(values)
    m = x.shape[0]
    shapes = _fit_linearization_shapes(m, 4, m + 2, 4)
    lin = _linearized(name, partial(_smoothing_linearize_cb, lam, weighted), shapes, x, w)
    return values, _fit_tangent(*lin, dy)


def fit_smoothing(x, y, w=None, lam=None):
    """The control points of the cubic smoothing spline with the given penalty ``lam > 0``,
    minimising ``Σ w_k |y_k - f(x_k)|² + lam ∫ |f''|²``: ``lekalo.fit_smoothing(x, y, w,
    lam)[0].control``, bit for bit, shape ``(len(x) + 2, dim)`` (``(len(x) + 2,)`` for 1-D
    ``y``). The knots are ``x`` with its ends repeated four times,
    ``jnp.concatenate([x[:1].repeat(3), x, x[-1:].repeat(3)])``.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``y``: the fit is linear in it, ``P = (BᵀWB + lam Ω)⁻¹ BᵀW y``, applied with the
    fit's banded factorisation (``lekalo.smoothing_linearize``). ``x``, ``w`` and ``lam`` are
    constants; ``lam`` must be given (a Python float): the GCV choice depends on the data and is
    not differentiated.
    """
    name = "fit_smoothing"
    _require_x64(name)
    if lam is None or isinstance(lam, bool) or not isinstance(lam, (int, float, np.floating, np.integer)):
        raise InputError(
            f"lekalo.jax.{name}: give lam > 0 as a Python float (a constant); the GCV choice of "
            f"lam depends on the data and is not differentiated, got {lam!r}"
        )
    lam = float(lam)
    if not lam > 0.0 or not np.isfinite(lam):
        raise InputError(f"lekalo.jax.{name}: lam must be finite and > 0, got {lam}")
    x = _float64(x, "x", name)
    y = _float64(y, "y", name)
    scalar, q = _points_arg(y, name, "y")
    m = q.shape[0]
    if x.shape != (m,):
        raise InputError(f"lekalo.jax.{name}: x must be one a value, shape ({m},), got {x.shape}")
    weighted, w = _weights_arg(w, m, name)
    out = _smoothing(lam, weighted, x, q, w)
    return out[:, 0] if scalar else out
