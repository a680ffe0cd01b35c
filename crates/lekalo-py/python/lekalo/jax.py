"""B-spline evaluation as JAX functions: lekalo's kernels inside ``jax.jit``, ``jax.vmap`` and
``jax.grad`` / ``jax.jacfwd`` / ``jax.jacrev``.

- ``bspline_eval(knots, control_points, u, degree)``: ``C(u)`` of a B-spline curve, shape
  ``u.shape + (dim,)`` (``u.shape`` for 1-D control points);
- ``nurbs_eval(knots, control_points, weights, u, degree)``: ``C(u)`` of a NURBS curve,
  differentiable also with respect to the weights;
- ``bspline_surface_eval(knots_u, knots_v, control_points, u, v, degree_u, degree_v)``:
  ``S(u, v)`` of a tensor-product B-spline surface (control net ``(nu, nv, dim)``);
- ``tensor_bspline_eval(knots, control_points, x, degrees)``: ``S(x)`` of a tensor-product
  B-spline in ``N`` variables at points ``(..., N)``;
- ``fit_least_squares(points, params, t, k=3, *, w=None)`` and
  ``fit_smoothing(x, y, w=None, lam=...)``: the control points of the least-squares fit and of
  the smoothing spline, differentiable with respect to the data;
- ``interpolate(points, params, t, k=3)``: the control points of the interpolant through
  ``points`` at ``params`` on the knots ``t``, differentiable with respect to the data and the
  parameters.

The evaluations are differentiable, in forward and reverse mode, with respect to the control
points and the parameters; the knots and degrees are constants.

``bspline_eval`` runs inside the compiled program: its values, JVP and VJP are XLA custom calls
(FFI targets written against XLA's C ABI in the native module, ``lekalo._jax_ffi``), no host
callback. The values are lekalo's evaluation (the reference de Boor evaluation for small
batches, the fast evaluator of ``lekalo.BSplineCurve.__call__`` from 16 parameters a polynomial
piece; the two agree to 1e-14 relative to the control points); the JVP and VJP are lekalo's
kernels (``lekalo.bspline_curve_jvp``, ``lekalo.bspline_curve_vjp``), so ``jax.grad`` runs
lekalo's reverse-mode kernel.

The other functions still call lekalo through ``jax.pure_callback`` (bit-for-bit the
library's evaluation, about 0.3 ms a call for the callback alone); their derivatives come from
the library's linearisation (e.g. ``lekalo.bspline_curve_linearize``): the sparse basis matrix,
``p + 1`` entries a parameter, applied by a JAX gather (JVP) whose transpose JAX derives (a
scatter, for VJP), plus ``C'(u)`` times the parameter tangent (``docs/theory/derivatives.md``).

Requirements and limits, each with a clear error:

- float64 only: enable it with ``jax.config.update("jax_enable_x64", True)`` first;
- first derivatives: a second derivative (``jax.hessian``, ``jacfwd(jacrev(...))``) raises
  ``NotImplementedError``;
- no derivatives with respect to the knots (``NotImplementedError``): pass them as constants;
- parameters must lie in the domain: outside it, the error raised inside lekalo (the FFI
  target or the callback) reaches the caller as ``jax.errors.JaxRuntimeError`` carrying lekalo's
  message, which names the parameter and the domain (eagerly and under ``jit``);
- runs on the CPU: the FFI targets are registered for the CPU platform only, and the callbacks
  copy device arrays to the host.

>>> import jax, jax.numpy as jnp
>>> jax.config.update("jax_enable_x64", True)
>>> from lekalo.jax import bspline_eval
>>> knots = jnp.array([0, 0, 0, 0, 1, 1, 1, 1.0])
>>> ctrl = jnp.array([[0, 0], [1, 2], [3, 2], [4, 0.0]])
>>> bspline_eval(knots, ctrl, jnp.array([0.5]), 3).tolist()
[[2.0, 1.5]]
>>> g = jax.grad(lambda c: bspline_eval(knots, c, jnp.array([0.5]), 3)[0, 1])(ctrl)
>>> g[:, 1].tolist()  # the basis functions at 0.5
[0.125, 0.375, 0.375, 0.125]
"""

from __future__ import annotations

from functools import partial

import numpy as np

try:
    import jax
    import jax.numpy as jnp
    from jax.custom_derivatives import SymbolicZero
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "lekalo.jax needs JAX; install it with `pip install lekalo[jax]` (or `pip install jax`)"
    ) from e

from . import _jax_ffi, _lekalo
from ._lekalo import InputError
from ._jax_fits import fit_least_squares, fit_smoothing, interpolate
from ._jax_support import (
    _CURVE_KEYS,
    _callback,
    _curve_lin_shapes,
    _degree,
    _fields_cb,
    _first_order_only,
    _float64,
    _linearized,
    _no_knot_tangent,
    _require_x64,
    _struct,
    _values_cb,
)

__all__ = [
    "bspline_eval",
    "nurbs_eval",
    "bspline_surface_eval",
    "tensor_bspline_eval",
    "fit_least_squares",
    "fit_smoothing",
    "interpolate",
]

_jax_ffi.register_targets()


# -- curves ------------------------------------------------------------------------------------


def _curve_out_shape(res):
    """``C(u)``'s shape from the residuals ``(knots, ctrl, u)``: ``u.shape + (dim,)``."""
    _, ctrl, u = res
    return u.shape + ctrl.shape[-1:]


# the curve's JVP (tangents of the control points and of u) and VJP, as XLA FFI targets
_CURVE_LINEAR = _jax_ffi.LinearPair(
    "bspline_eval", "lekalo_bspline_jvp", "lekalo_bspline_vjp",
    kinds=("control", "parameter"), like=(1, 2), out_shape=_curve_out_shape,
)


def _curve_values(degree, knots, ctrl, u):
    shape = _struct(u.shape + ctrl.shape[-1:])
    return _jax_ffi.call("lekalo_bspline_eval", shape, (("degree", degree),), knots, ctrl, u)


@partial(jax.custom_jvp, nondiff_argnums=(0,))
def _curve(degree, knots, ctrl, u):
    return _curve_values(degree, knots, ctrl, u)


@partial(_curve.defjvp, symbolic_zeros=True)
def _curve_jvp(degree, primals, tangents):
    dk, dc, du = tangents
    _no_knot_tangent("bspline_eval", dk)
    guard = partial(_first_order_only, "bspline_eval")
    knots, ctrl, u = (guard(a) for a in primals)
    values = _curve_values(degree, knots, ctrl, u)
    lin = [None if isinstance(t, SymbolicZero) else t for t in (dc, du)]
    tangent = _CURVE_LINEAR.tangent((knots, ctrl, u), lin, (("degree", degree),))
    return values, jnp.zeros_like(values) if tangent is None else tangent


def bspline_eval(knots, control_points, u, degree):
    """``C(u)`` of the B-spline curve of ``degree`` on ``knots`` with ``control_points``
    (``(n, dim)``, or ``(n,)`` for a function), at the parameters ``u`` (any shape, in the
    domain ``[knots[degree], knots[n]]``). Returns ``u.shape + (dim,)`` (``u.shape`` for 1-D
    control points), lekalo's evaluation as an XLA custom call (no host callback).

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points`` and ``u``; ``knots`` and ``degree`` are constants (``degree``
    a Python int). At an interior knot where ``C'`` jumps, the derivative in ``u`` is the
    right-hand one.
    """
    name = "bspline_eval"
    _require_x64(name)
    degree = _degree(degree, "degree", name)
    knots = _float64(knots, "knots", name)
    ctrl = _float64(control_points, "control_points", name)
    u = _float64(u, "u", name)
    if knots.ndim != 1:
        raise InputError(f"lekalo.jax.{name}: knots must be 1-D, got shape {knots.shape}")
    if ctrl.ndim not in (1, 2):
        raise InputError(
            f"lekalo.jax.{name}: control_points must be (n, dim) or (n,), got shape {ctrl.shape}"
        )
    n = ctrl.shape[0]
    if knots.shape[0] != n + degree + 1:
        raise InputError(
            f"lekalo.jax.{name}: {n} control points of degree {degree} need {n + degree + 1} "
            f"knots (control points + degree + 1), got {knots.shape[0]}"
        )
    scalar_dim = ctrl.ndim == 1
    c2 = ctrl[:, None] if scalar_dim else ctrl
    out = _curve(degree, knots, c2, u.reshape(-1))
    out = out.reshape(u.shape + c2.shape[-1:])
    return out[..., 0] if scalar_dim else out


# -- NURBS curves ------------------------------------------------------------------------------


def _nurbs_values_cb(degree, *arrays):
    return _values_cb(_lekalo.nurbs_curve_jvp, (degree,), (1, 2, 1, 1), *arrays)


def _nurbs_linearize_cb(degree, *arrays):
    kernel = _lekalo.nurbs_curve_linearize
    return _fields_cb(kernel, (degree,), (1, 2, 1, 1), _CURVE_KEYS, *arrays)


@partial(jax.custom_jvp, nondiff_argnums=(0,))
def _nurbs(degree, knots, ctrl, w, u):
    shape = _struct(u.shape + ctrl.shape[-1:])
    return _callback(partial(_nurbs_values_cb, degree), shape, knots, ctrl, w, u)


@partial(_nurbs.defjvp, symbolic_zeros=True)
def _nurbs_jvp(degree, primals, tangents):
    knots, ctrl, w, u = primals
    dk, dc, dw, du = tangents
    _no_knot_tangent("nurbs_eval", dk)
    m, dim, width = u.shape[0], ctrl.shape[-1], degree + 1
    cb, shapes = partial(_nurbs_linearize_cb, degree), _curve_lin_shapes(m, dim, width)
    values, slopes, first, basis = _linearized("nurbs_eval", cb, shapes, knots, ctrl, w, u)
    rows = first[:, None] + jnp.arange(width)  # (m, p + 1) control-point indices
    tangent = jnp.zeros((m, dim), jnp.float64)
    if not isinstance(dc, SymbolicZero):
        tangent = tangent + jnp.einsum("mk,mkd->md", basis, dc[rows])
    if not isinstance(dw, SymbolicZero):
        # dC/dw_j = R_j (P_j - C) / w_j
        coef = basis * dw[rows] / w[rows]
        tangent = tangent + jnp.einsum("mk,mkd->md", coef, ctrl[rows] - values[:, None, :])
    if not isinstance(du, SymbolicZero):
        tangent = tangent + slopes * du[:, None]
    return values, tangent


def nurbs_eval(knots, control_points, weights, u, degree):
    """``C(u)`` of the NURBS curve of ``degree`` on ``knots`` with Euclidean ``control_points``
    (``(n, dim)``) and positive ``weights`` (``(n,)``), at the parameters ``u`` (any shape).
    Returns ``u.shape + (dim,)``, bit-for-bit lekalo's evaluation.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``weights`` and ``u``; ``knots`` and ``degree`` are constants.
    """
    name = "nurbs_eval"
    _require_x64(name)
    degree = _degree(degree, "degree", name)
    knots = _float64(knots, "knots", name)
    ctrl = _float64(control_points, "control_points", name)
    w = _float64(weights, "weights", name)
    u = _float64(u, "u", name)
    if ctrl.ndim != 2:
        raise InputError(f"lekalo.jax.{name}: control_points must be (n, dim), got shape {ctrl.shape}")
    n = ctrl.shape[0]
    if w.shape != (n,):
        raise InputError(
            f"lekalo.jax.{name}: weights must be one a control point, shape ({n},), got {w.shape}"
        )
    if knots.ndim != 1 or knots.shape[0] != n + degree + 1:
        raise InputError(
            f"lekalo.jax.{name}: {n} control points of degree {degree} need {n + degree + 1} "
            f"knots (control points + degree + 1), got shape {knots.shape}"
        )
    out = _nurbs(degree, knots, ctrl, w, u.reshape(-1))
    return out.reshape(u.shape + ctrl.shape[-1:])


# -- surfaces ----------------------------------------------------------------------------------


_SURFACE_KEYS = (
    "values",
    "derivatives_u",
    "derivatives_v",
    "first_u",
    "first_v",
    "basis_u",
    "basis_v",
)


def _surface_values_cb(degrees, *arrays):
    return _values_cb(_lekalo.bspline_surface_jvp, degrees, (1, 1, 3, 1, 1), *arrays)


def _surface_linearize_cb(degrees, *arrays):
    kernel = _lekalo.bspline_surface_linearize
    return _fields_cb(kernel, degrees, (1, 1, 3, 1, 1), _SURFACE_KEYS, *arrays)


@partial(jax.custom_jvp, nondiff_argnums=(0,))
def _surface(degrees, ku, kv, ctrl, u, v):
    shape = _struct(u.shape + ctrl.shape[-1:])
    return _callback(partial(_surface_values_cb, degrees), shape, ku, kv, ctrl, u, v)


@partial(_surface.defjvp, symbolic_zeros=True)
def _surface_jvp(degrees, primals, tangents):
    ku, kv, ctrl, u, v = primals
    dku, dkv, dc, du, dv = tangents
    _no_knot_tangent("bspline_surface_eval", dku, dkv)
    (p, q), m, dim = degrees, u.shape[0], ctrl.shape[-1]
    index = _struct((m,), jnp.int64)
    shapes = (_struct((m, dim)),) * 3 + (index, index, _struct((m, p + 1)), _struct((m, q + 1)))
    cb = partial(_surface_linearize_cb, degrees)
    values, su, sv, fu, fv, bu, bv = _linearized(
        "bspline_surface_eval", cb, shapes, ku, kv, ctrl, u, v
    )
    tangent = jnp.zeros((m, dim), jnp.float64)
    if not isinstance(dc, SymbolicZero):
        rows = (fu[:, None] + jnp.arange(p + 1))[:, :, None]  # (m, p + 1, 1)
        cols = (fv[:, None] + jnp.arange(q + 1))[:, None, :]  # (m, 1, q + 1)
        tangent = tangent + jnp.einsum("mk,ml,mkld->md", bu, bv, dc[rows, cols])
    if not isinstance(du, SymbolicZero):
        tangent = tangent + su * du[:, None]
    if not isinstance(dv, SymbolicZero):
        tangent = tangent + sv * dv[:, None]
    return values, tangent


def bspline_surface_eval(knots_u, knots_v, control_points, u, v, degree_u, degree_v):
    """``S(u, v)`` of the tensor-product B-spline surface of degrees ``(degree_u, degree_v)`` on
    ``knots_u``, ``knots_v`` with the control net ``control_points`` (``(nu, nv, dim)``), at
    parameters ``u``, ``v`` of one shape. Returns ``u.shape + (dim,)``, bit-for-bit lekalo's
    evaluation.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``u`` and ``v``; knots and degrees are constants.
    """
    name = "bspline_surface_eval"
    _require_x64(name)
    degrees = (_degree(degree_u, "degree_u", name), _degree(degree_v, "degree_v", name))
    ku = _float64(knots_u, "knots_u", name)
    kv = _float64(knots_v, "knots_v", name)
    ctrl = _float64(control_points, "control_points", name)
    u = _float64(u, "u", name)
    v = _float64(v, "v", name)
    if ctrl.ndim != 3:
        raise InputError(
            f"lekalo.jax.{name}: control_points must be a net (nu, nv, dim), got shape {ctrl.shape}"
        )
    for k, n, d, what in ((ku, ctrl.shape[0], degrees[0], "u"), (kv, ctrl.shape[1], degrees[1], "v")):
        if k.ndim != 1 or k.shape[0] != n + d + 1:
            raise InputError(
                f"lekalo.jax.{name}: knots_{what} must be 1-D with {n + d + 1} knots (net size "
                f"{n} + degree {d} + 1 along {what}), got shape {k.shape}"
            )
    if u.shape != v.shape:
        raise InputError(
            f"lekalo.jax.{name}: u and v must have one shape, got {u.shape} and {v.shape} "
            "(jnp.meshgrid for a grid)"
        )
    out = _surface(degrees, ku, kv, ctrl, u.reshape(-1), v.reshape(-1))
    return out.reshape(u.shape + ctrl.shape[-1:])


# -- tensor-product splines in N variables ---------------------------------------------------------


def _tensor_kernel(kernel, degrees, *a):
    """``kernel(knots, ctrl, degrees, x)`` on the arrays ``(*knots, ctrl, x)``."""
    n = len(degrees)
    return kernel(list(a[:n]), a[n], list(degrees), a[n + 1])


def _tensor_values_cb(degrees, *args):
    kernel = partial(_tensor_kernel, _lekalo.tensor_bspline_jvp)
    return _values_cb(kernel, (degrees,), (1,) * len(degrees) + (len(degrees) + 1, 2), *args)


def _tensor_linearize_cb(degrees, *args):
    kernel = partial(_tensor_kernel, _lekalo.tensor_bspline_linearize)
    keys = ("values", "partials", "first", "basis")
    return _fields_cb(kernel, (degrees,), (1,) * len(degrees) + (len(degrees) + 1, 2), keys, *args)


@partial(jax.custom_jvp, nondiff_argnums=(0,))
def _tensor(degrees, knots, ctrl, x):
    shape = _struct(x.shape[:1] + ctrl.shape[-1:])
    return _callback(partial(_tensor_values_cb, degrees), shape, *knots, ctrl, x)


@partial(_tensor.defjvp, symbolic_zeros=True)
def _tensor_jvp(degrees, primals, tangents):
    knots, ctrl, x = primals
    dk, dc, dx = tangents
    name = "tensor_bspline_eval"
    _no_knot_tangent(name, *dk)
    n, m, dim = len(degrees), x.shape[0], ctrl.shape[-1]
    widths = [p + 1 for p in degrees]
    shapes = (
        _struct((m, dim)),
        _struct((m, n, dim)),
        _struct((m, n), jnp.int64),
        _struct((m, sum(widths))),
    )
    values, partials, first, basis = _linearized(
        name, partial(_tensor_linearize_cb, degrees), shapes, *knots, ctrl, x
    )
    tangent = jnp.zeros((m, dim), jnp.float64)
    if not isinstance(dc, SymbolicZero):
        # the Π (p_a + 1) block of the net a point touches, one multi-index a column
        block = np.array(list(np.ndindex(*widths)), dtype=np.int64).reshape(-1, n)  # (K, N)
        offsets = np.concatenate([[0], np.cumsum(widths)[:-1]]).astype(np.int64)
        index = tuple(first[:, a, None] + block[None, :, a] for a in range(n))  # N × (m, K)
        weight = jnp.prod(
            jnp.stack([basis[:, offsets[a] + block[:, a]] for a in range(n)]), axis=0
        )  # (m, K)
        tangent = tangent + jnp.einsum("mk,mkd->md", weight, dc[index])
    if not isinstance(dx, SymbolicZero):
        tangent = tangent + jnp.einsum("mnd,mn->md", partials, dx)
    return values, tangent


def tensor_bspline_eval(knots, control_points, x, degrees):
    """``S(x)`` of the tensor-product B-spline in ``N`` variables with degrees ``degrees`` (a
    tuple of ``N`` Python ints), knot vectors ``knots`` (a tuple of ``N`` 1-D arrays) and
    coefficients ``control_points`` (``(n_1, ..., n_N, dim)``, or ``(n_1, ..., n_N)`` for a
    scalar function), at the points ``x`` of shape ``(..., N)``. Returns ``x.shape[:-1] +
    (dim,)`` (``x.shape[:-1]`` for scalar coefficients), bit-for-bit
    ``lekalo.TensorBSpline(knots, control_points, degrees)(x)``.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points`` and ``x``: the net's Jacobian is the product of the ``N``
    basis vectors on the ``Π (p_a + 1)`` block a point touches (a JAX gather whose transpose is
    a scatter-add), the points' the partial derivatives ``∂S/∂x_a``
    (``lekalo.tensor_bspline_linearize``). The knots and degrees are constants.
    """
    name = "tensor_bspline_eval"
    _require_x64(name)
    if isinstance(degrees, (int, np.integer)) or not hasattr(degrees, "__len__"):
        raise InputError(f"lekalo.jax.{name}: degrees must be a tuple of Python ints, one a variable")
    degrees = tuple(_degree(d, f"degrees[{a}]", name) for a, d in enumerate(degrees))
    n = len(degrees)
    if not hasattr(knots, "__len__") or len(knots) != n:
        raise InputError(
            f"lekalo.jax.{name}: knots must be a tuple of {n} 1-D arrays, one a variable"
        )
    knots = tuple(_float64(k, f"knots[{a}]", name) for a, k in enumerate(knots))
    ctrl = _float64(control_points, "control_points", name)
    x = _float64(x, "x", name)
    if ctrl.ndim not in (n, n + 1):
        raise InputError(
            f"lekalo.jax.{name}: control_points must be (n_1, ..., n_{n}, dim) or (n_1, ..., "
            f"n_{n}), got shape {ctrl.shape}"
        )
    for a, (k, p) in enumerate(zip(knots, degrees)):
        if k.ndim != 1 or k.shape[0] != ctrl.shape[a] + p + 1:
            raise InputError(
                f"lekalo.jax.{name}: knots[{a}] must be 1-D with {ctrl.shape[a] + p + 1} knots "
                f"(net size {ctrl.shape[a]} + degree {p} + 1), got shape {k.shape}"
            )
    if x.ndim < 1 or x.shape[-1] != n:
        raise InputError(
            f"lekalo.jax.{name}: x must have shape (..., {n}), the coordinates on the last "
            f"axis, got {x.shape}"
        )
    scalar = ctrl.ndim == n
    c = ctrl[..., None] if scalar else ctrl
    out = _tensor(degrees, knots, c, x.reshape(-1, n))
    out = out.reshape(x.shape[:-1] + c.shape[-1:])
    return out[..., 0] if scalar else out
