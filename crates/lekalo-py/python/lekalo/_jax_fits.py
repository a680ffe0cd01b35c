"""Control points from data as JAX functions: ``interpolate``, ``fit_least_squares`` and
``fit_smoothing`` of ``lekalo.jax``, differentiable with respect to the data (and the
interpolation's parameters and knots, and the least-squares fit's knots) by the library's
linearisations and adjoint solves with the same banded factorisation (``docs/theory/derivatives.md``). Each runs as lekalo's XLA FFI targets
(values, JVP and VJP compiled into the program, no host callback)."""

from __future__ import annotations

from functools import lru_cache, partial

import jax
import jax.numpy as jnp
import numpy as np
from jax.custom_derivatives import SymbolicZero

from . import _lekalo
from ._jax_ffi import Kernel
from ._lekalo import InputError
from ._jax_support import _degree, _float64, _require_x64


# -- interpolation -------------------------------------------------------------------------------


def _interp_out_shape(res):
    """The control points' shape from the residuals ``(t, points, params)``: the points'."""
    return res[1].shape


# values, JVP and VJP as the FFI targets ``lekalo_interpolate_*`` (``xla_ffi/interpolate.rs``); the
# knots are differentiable, so they are passed among the arrays (a kind of their own)
_INTERP = Kernel(
    "interpolate", "lekalo_interpolate", ("knots", "data", "parameter"), _interp_out_shape
)


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
    used. Differentiable with respect to the interior knots ``t[k + 1 : m]`` as well:
    ``Ṗ = -A⁻¹ (Ȧ P)``, ``τ̄ = -J_Pᵀ (A⁻ᵀ P̄)`` (``Interpolant::knot_jvp``, ``::knot_vjp``,
    "Knots of the fits"); the tangent of the ``k + 1`` first and last knots is ignored and their
    cotangent is zero. ``k`` is a constant. The parameters must satisfy the Schoenberg–Whitney
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
    out = _INTERP((("degree", k),), (), (t, q, params))
    return out[:, 0] if scalar else out


# -- fits ----------------------------------------------------------------------------------------


@partial(jax.custom_jvp, nondiff_argnums=(0, 1))
def _constant(name, what, x):
    """``x``, refusing a derivative with respect to it: the fits are differentiated with respect
    to the data values (and the least-squares fit's knots) only."""
    return x


@partial(_constant.defjvp, symbolic_zeros=True)
def _constant_jvp(name, what, primals, tangents):
    if not isinstance(tangents[0], SymbolicZero):
        raise NotImplementedError(
            f"lekalo.jax.{name}: derivatives with respect to {what} are not supported (the fit "
            "is differentiated with respect to the data values only, and the least-squares "
            "fit's knots); pass them as constants "
            "(close over them, or wrap them in jax.lax.stop_gradient)"
        )
    return primals[0], jnp.zeros_like(primals[0])


@lru_cache(maxsize=None)
def _least_squares_kernel(k):
    """The FFI targets ``lekalo_fit_least_squares_*`` (``xla_ffi/fits.rs``) for degree ``k``:
    residuals ``(params, w, t, points)`` (with the factors before the knots in the
    derivatives'), control points ``(len(t) - k - 1, dim)``; the knots and the points are the
    differentiable kinds. Under differentiation the values and the factors come from
    ``lekalo_fit_least_squares_factor``, whose banded QR the data's JVP and VJP reuse
    (``lekalo::derivatives::LeastSquaresMap::to_flat``); the knots' refit
    (``LeastSquaresFit::knot_jvp``, ``::knot_vjp``)."""

    def out_shape(res):
        t, q = res[-2], res[-1]
        return q.shape[:-2] + (t.shape[-1] - k - 1, q.shape[-1])

    def factor_shape(res):
        t, q = res[-2], res[-1]
        n_flat = _lekalo.least_squares_map_flat_len(q.shape[-2], t.shape[-1] - k - 1, k)
        return q.shape[:-2] + (n_flat,)

    return Kernel(
        "fit_least_squares", "lekalo_fit_least_squares", ("knots", "data"), out_shape,
        factor_shape=factor_shape,
    )


def _smoothing_out_shape(res):
    """The control points' shape from the residuals ``(x, w, lam, y)`` (with the factors before
    ``y`` in the derivatives'): ``(len(x) + 2, dim)``."""
    y = res[-1]
    return y.shape[:-2] + (y.shape[-2] + 2, y.shape[-1])


def _smoothing_factor_shape(res):
    """The shape of the smoothing spline's factors from the residuals ``(x, w, lam, y)``: the
    map of its factorisation as numbers (``lekalo::derivatives::SmoothingMap::to_flat``)."""
    y = res[-1]
    return y.shape[:-2] + (_lekalo.smoothing_map_flat_len(y.shape[-2]),)


# values, JVP and VJP as the FFI targets ``lekalo_fit_smoothing_*`` (``xla_ffi/fits.rs``); under
# differentiation the values and the factors come from ``lekalo_fit_smoothing_factor``, whose
# factorisation the JVP and VJP reuse
_SMOOTHING = Kernel(
    "fit_smoothing", "lekalo_fit_smoothing", ("data",), _smoothing_out_shape,
    factor_shape=_smoothing_factor_shape,
)


def _nonempty(name, what, q, need):
    if q.size == 0:
        # XLA skips a custom call with an empty result, so lekalo would never see this call
        raise InputError(f"lekalo.jax.{name}: {what} of shape {q.shape} are empty; {need}")


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
    respect to ``points``: the fit is linear in them, ``P = (BᵀWB)⁻¹ BᵀW Q``, so
    ``Ṗ = (BᵀWB)⁻¹ BᵀW Q̇`` and ``Q̄ = W B (BᵀWB)⁻¹ P̄``, with the sparse rows of ``B`` and the
    triangle of lekalo's banded QR (``lekalo::derivatives::LeastSquaresFit``,
    ``docs/theory/derivatives.md``, "Fits"); and with respect to the interior knots
    ``t[k + 1 : len(t) - k - 1]``: ``Ṗ = -G⁻¹ (BᵀW Ḃ P + Ḃᵀ W r)``, ``G = BᵀWB``, ``r = B P - Q``
    (``LeastSquaresFit::knot_jvp``, ``::knot_vjp``, "Knots of the fits"; the tangent of the
    ``k + 1`` first and last knots is ignored and their cotangent is zero). Values, JVP and VJP
    are lekalo's XLA FFI targets, compiled into the program (no host callback). ``params``,
    ``w`` and ``k`` are constants (a derivative with respect to them raises
    ``NotImplementedError``). A problem
    with the data (a basis function with no data under it, NaN values, parameters outside the
    knots) reaches the caller as ``jax.errors.JaxRuntimeError`` carrying lekalo's message.
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
    _nonempty(name, "points", q, "the fit needs data points of at least one coordinate")
    what = "the parameters or the weights"
    params, w = (_constant(name, what, a) for a in (params, w))
    static = (("degree", k), ("weighted", int(weighted)))
    out = _least_squares_kernel(k)(static, (params, w), (t, q))
    return out[:, 0] if scalar else out


def fit_smoothing(x, y, w=None, lam=None):
    """The control points of the cubic smoothing spline with the given penalty ``lam > 0``,
    minimising ``Σ w_k |y_k - f(x_k)|² + lam ∫ |f''|²``: ``lekalo.fit_smoothing(x, y, w,
    lam)[0].control``, bit for bit, shape ``(len(x) + 2, dim)`` (``(len(x) + 2,)`` for 1-D
    ``y``). The knots are ``x`` with its ends repeated four times,
    ``jnp.concatenate([x[:1].repeat(3), x, x[-1:].repeat(3)])``.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``y``: the fit is linear in it, ``P = (BᵀWB + lam Ω)⁻¹ BᵀW y``, so
    ``Ṗ = (BᵀWB + lam Ω)⁻¹ BᵀW ẏ`` and ``ȳ = W B (BᵀWB + lam Ω)⁻¹ P̄``, with the fit's banded
    factorisation (``lekalo::derivatives::SmoothingFit``). Values, JVP and VJP are lekalo's XLA
    FFI targets (no host callback). ``x``, ``w`` and ``lam`` are constants; ``lam`` must be
    given (a Python float): the GCV choice depends on the data and is not differentiated.
    ``x`` must be strictly increasing (the result has one control point a value, plus 2);
    lekalo's errors on the data reach the caller as ``jax.errors.JaxRuntimeError``.
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
    _nonempty(name, "y", q, "the smoothing spline needs at least 3 values of at least one coordinate")
    x, w = (_constant(name, "x or the weights", a) for a in (x, w))
    lam = jnp.asarray(lam, jnp.float64)
    out = _SMOOTHING((("weighted", int(weighted)),), (x, w, lam), (q,))
    return out[:, 0] if scalar else out
