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


def _require_x64(name):
    if not jax.config.jax_enable_x64:
        raise InputError(
            f"lekalo.jax.{name} computes in float64: enable it with "
            "jax.config.update('jax_enable_x64', True) at the start of the program"
        )


def _float64(x, what, name):
    x = jnp.asarray(x)
    if not jnp.issubdtype(x.dtype, jnp.floating) and not jnp.issubdtype(x.dtype, jnp.integer):
        raise InputError(f"lekalo.jax.{name}: {what} must be real numbers, got dtype {x.dtype}")
    return x.astype(jnp.float64)


def _degree(d, what, name):
    if isinstance(d, (bool, np.bool_)) or not isinstance(d, (int, np.integer)) or d < 0:
        raise InputError(
            f"lekalo.jax.{name}: {what} must be a non-negative Python int (a static value), "
            f"got {d!r}"
        )
    return int(d)


def _looped(fn, core_ndims, *arrays):
    """``fn`` on arrays with leading batch axes (``vmap_method="expand_dims"``: an unbatched
    argument has size-1 batch axes): one call a batch element, the results stacked."""
    arrays = [np.asarray(a) for a in arrays]
    batch_shapes = [a.shape[: a.ndim - c] for a, c in zip(arrays, core_ndims)]
    batch = np.broadcast_shapes(*batch_shapes)
    if batch == ():
        return fn(*arrays)
    results = []
    for idx in np.ndindex(*batch):
        parts = []
        for a, bs in zip(arrays, batch_shapes):
            off = len(batch) - len(bs)
            parts.append(a[tuple(0 if s == 1 else idx[off + k] for k, s in enumerate(bs))])
        results.append(fn(*parts))
    return tuple(
        np.stack([r[k] for r in results]).reshape(batch + results[0][k].shape)
        for k in range(len(results[0]))
    )


@partial(jax.custom_jvp, nondiff_argnums=(0,))
def _first_order_only(name, x):
    return x


@partial(_first_order_only.defjvp, symbolic_zeros=True)
def _first_order_only_jvp(name, primals, tangents):
    (x,), (dx,) = primals, tangents
    if not isinstance(dx, SymbolicZero):
        raise NotImplementedError(
            f"lekalo.jax.{name}: only first derivatives are supported (jax.grad, jax.jacfwd, "
            "jax.jacrev, jax.jvp, jax.vjp); a second derivative (jax.hessian, nested jacfwd/"
            "jacrev) would differentiate the derivative kernels themselves"
        )
    return x, jnp.zeros_like(x)


def _no_knot_tangent(name, *tangents):
    if any(not isinstance(t, SymbolicZero) for t in tangents):
        raise NotImplementedError(
            f"lekalo.jax.{name}: derivatives with respect to the knots are not supported; pass "
            "the knots as constants (close over them, or wrap them in jax.lax.stop_gradient)"
        )


# -- host callbacks ------------------------------------------------------------------------------


def _struct(shape, dtype=jnp.float64):
    return jax.ShapeDtypeStruct(shape, dtype)


def _callback(cb, shapes, *args):
    """``cb(*args)`` run on the host by ``jax.pure_callback`` into ``shapes``; under ``vmap``
    the batch axes lead (``vmap_method="expand_dims"``) and ``cb`` loops over them
    (``_looped``)."""
    return jax.pure_callback(cb, shapes, *args, vmap_method="expand_dims")


def _linearized(name, cb, shapes, *args):
    """``_callback`` of a linearisation on ``args``, each through ``_first_order_only`` so that
    a second derivative of ``lekalo.jax.{name}`` raises."""
    guard = partial(_first_order_only, name)
    return _callback(cb, shapes, *(guard(a) for a in args))


def _values_cb(kernel, static, core_ndims, *arrays):
    """The values (first result) of the JVP kernel ``kernel(*static, *element)``, each batch
    element of ``arrays`` in turn."""
    return _looped(lambda *a: (kernel(*static, *a)[0],), core_ndims, *arrays)[0]


def _fields_cb(kernel, static, core_ndims, keys, *arrays):
    """The entries ``keys`` of the dict ``kernel(*static, *element)`` returns (a
    linearisation), each batch element of ``arrays`` in turn."""
    return _looped(lambda *a: tuple(kernel(*static, *a)[k] for k in keys), core_ndims, *arrays)


_CURVE_KEYS = ("values", "derivatives", "first", "basis")


def _curve_lin_shapes(m, dim, width):
    """The shapes of a curve's linearisation at ``m`` parameters: values and derivatives
    ``(m, dim)``, first indices ``(m,)``, basis ``(m, width)``."""
    return (_struct((m, dim)), _struct((m, dim)), _struct((m,), jnp.int64), _struct((m, width)))


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


# -- interpolation -------------------------------------------------------------------------------


def _interp_solve_cb(k, params, t, b):
    def one(x, kn, v):
        return (np.asarray(_lekalo.interpolation_jvp(k, kn, x, v)),)

    return _looped(one, (1, 1, 2), params, t, b)[0]


def _interp_solve_transposed_cb(k, params, t, g):
    def one(x, kn, v):
        return (np.asarray(_lekalo.interpolation_vjp(k, kn, x, v)),)

    return _looped(one, (1, 1, 2), params, t, g)[0]


def _curve_linearize_cb(degree, *arrays):
    """The curve's linearisation (``lekalo.bspline_curve_linearize``) by host callback: the
    interpolation's JVP rule reads ``C'`` and the collocation rows from it."""
    return _fields_cb(_lekalo.bspline_curve_linearize, (degree,), (1, 2, 1), _CURVE_KEYS, *arrays)


def _collocation_solve(k, params, t, first, basis, b):
    """``A⁻¹ b`` for the collocation matrix ``A[r, i] = N_{i,k}(params[r])`` (rows ``first``,
    ``basis``) as a ``jax.lax.custom_linear_solve``: the solve is lekalo's
    ``interpolation_jvp``, the transposed solve (reverse mode) its ``interpolation_vjp``, both
    with the one banded factorisation; ``A`` itself (a gather, for JAX's own bookkeeping) is
    never inverted by JAX."""
    rows = first[:, None] + jnp.arange(basis.shape[1])

    def matvec(x):
        return jnp.einsum("mk,mkd->md", basis, x[rows])

    def solve(_, rhs):
        return _callback(partial(_interp_solve_cb, k), _struct(rhs.shape), params, t, rhs)

    def solve_transposed(_, rhs):
        cb = partial(_interp_solve_transposed_cb, k)
        return _callback(cb, _struct(rhs.shape), params, t, rhs)

    return jax.lax.custom_linear_solve(matvec, b, solve, solve_transposed)


@partial(jax.custom_jvp, nondiff_argnums=(0,))
def _interp(k, points, params, t):
    return _callback(partial(_interp_solve_cb, k), _struct(points.shape), params, t, points)


@partial(_interp.defjvp, symbolic_zeros=True)
def _interp_jvp(k, primals, tangents):
    points, params, t = primals
    dq, dx, dt = tangents
    name = "interpolate"
    _no_knot_tangent(name, dt)
    guard = partial(_first_order_only, name)
    ctrl = _interp(k, guard(points), guard(params), guard(t))
    if isinstance(dq, SymbolicZero) and isinstance(dx, SymbolicZero):
        return ctrl, jnp.zeros_like(ctrl)
    m, dim = points.shape
    # the interpolant's linearisation at its own parameters: the rows of A and C'(params)
    _, slopes, first, basis = _callback(
        partial(_curve_linearize_cb, k),
        _curve_lin_shapes(m, dim, k + 1),
        guard(t),
        ctrl,
        guard(params),
    )
    # A(x) P = Q, so A Ṗ = Q̇ - Ȧ P = Q̇ - C'(x) ẋ
    rhs = jnp.zeros((m, dim), jnp.float64)
    if not isinstance(dq, SymbolicZero):
        rhs = rhs + dq
    if not isinstance(dx, SymbolicZero):
        rhs = rhs - slopes * dx[:, None]
    return ctrl, _collocation_solve(k, guard(params), guard(t), first, basis, rhs)


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
    respect to ``points`` and ``params``: ``Ṗ = A⁻¹ (Q̇ - C'(params) ẋ)``, the solve being
    lekalo's ``interpolation_jvp`` and, in reverse mode, the adjoint solve
    ``interpolation_vjp`` (a ``jax.lax.custom_linear_solve``), ``C'`` the interpolant's
    derivative (``docs/theory/derivatives.md``, "Interpolation"). At a parameter on an interior
    knot where ``C'`` jumps (a knot of multiplicity ``k`` or more), the right-hand derivative is
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
    out = _interp(k, q, params, t)
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
