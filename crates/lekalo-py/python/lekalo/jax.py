"""B-spline evaluation as JAX functions: lekalo's kernels inside ``jax.jit``, ``jax.vmap`` and
``jax.grad`` / ``jax.jacfwd`` / ``jax.jacrev``.

- ``bspline_eval(knots, control_points, u, degree)``: ``C(u)`` of a B-spline curve, shape
  ``u.shape + (dim,)`` (``u.shape`` for 1-D control points);
- ``nurbs_eval(knots, control_points, weights, u, degree)``: ``C(u)`` of a NURBS curve,
  differentiable also with respect to the weights;
- ``bspline_surface_eval(knots_u, knots_v, control_points, u, v, degree_u, degree_v)``:
  ``S(u, v)`` of a tensor-product B-spline surface (control net ``(nu, nv, dim)``);
- ``nurbs_surface_eval(knots_u, knots_v, control_points, weights, u, v, degree_u, degree_v)``:
  ``S(u, v)`` of a NURBS surface, differentiable also with respect to the weights;
- ``tensor_bspline_eval(knots, control_points, x, degrees)``: ``S(x)`` of a tensor-product
  B-spline in ``N`` variables at points ``(..., N)``;
- ``tensor_nurbs_eval(knots, control_points, weights, x, degrees)``: ``S(x)`` of a
  tensor-product NURBS in ``N`` variables, differentiable also with respect to the weights;
- ``fit_least_squares(points, params, t, k=3, *, w=None)`` and
  ``fit_smoothing(x, y, w=None, lam=...)``: the control points of the least-squares fit and of
  the smoothing spline, differentiable with respect to the data (and the least-squares fit's
  interior knots);
- ``interpolate(points, params, t, k=3)``: the control points of the interpolant through
  ``points`` at ``params`` on the knots ``t``, differentiable with respect to the data, the
  parameters and the interior knots;
- ``arc_length(knots, control_points, degree)``: a B-spline curve's length, differentiable with
  respect to the knots and the control points;
- ``closest_parameter(knots, control_points, x, degree)``: the parameters of the curve's
  closest points to the points ``x``, differentiable with respect to the knots, the control
  points and ``x``.

The evaluations are differentiable, in forward and reverse mode, with respect to the control
points, the parameters and the knots (the interior ones: the ``degree + 1`` first and last
knots of a direction bound the domain and are held fixed, their gradient zero;
``docs/theory/derivatives.md``, "Knots"). The degrees are constants, and so are the knots of
``fit_smoothing``.

The six evaluations run inside the compiled program: their values, JVPs and VJPs are XLA
custom calls (FFI targets written against XLA's C ABI in the native module,
``lekalo._jax_ffi``), no host callback. The values are lekalo's evaluation (for curves, the
reference de Boor evaluation for small batches and the fast evaluator of
``lekalo.BSplineCurve.__call__`` / ``lekalo.NurbsCurve.__call__`` from 16 parameters a
polynomial piece, the two agreeing to 1e-14 relative to the control points; for surfaces and
tensor splines, bit for bit ``eval_batch``). A curve evaluated at fewer than one parameter for
every ``degree + 1`` control points, and a surface or tensor spline at fewer than one point for
every ``Π (degree + 1)`` net points (a small call), is evaluated in place on the arrays,
checking only the knots and control points of the spans (cells) used (the same numbers, and
lekalo's error for a bad number in them); the JVPs and VJPs are lekalo's kernels
(``lekalo.bspline_curve_jvp``, ``lekalo.nurbs_curve_vjp``, ``lekalo.bspline_surface_vjp``,
``lekalo.tensor_bspline_vjp`` and their twins), so ``jax.grad`` runs lekalo's reverse-mode
kernel.

``interpolate`` runs the same way, as FFI targets for its values, JVP and VJP (the banded
solve, its adjoint and the interpolant's derivative at the parameters,
``lekalo::derivatives::Interpolant``), and so do the fits (``fit_least_squares``,
``fit_smoothing``: bit-for-bit the library's control points, and the derivatives in the data by
the fit's banded factorisation, ``lekalo::derivatives::LeastSquaresFit``, ``SmoothingFit``).
No function here calls back to Python.

Requirements and limits, each with a clear error:

- float64 only: enable it with ``jax.config.update("jax_enable_x64", True)`` first;
- first derivatives: a second derivative (``jax.hessian``, ``jacfwd(jacrev(...))``) raises
  ``NotImplementedError``;
- derivatives with respect to the knots of ``fit_smoothing`` raise ``NotImplementedError``:
  pass them as constants (``interpolate``, ``fit_least_squares``, ``arc_length`` and
  ``closest_parameter`` are differentiable in their knots);
- parameters must lie in the domain (and NURBS weights be positive): otherwise the error
  raised inside lekalo's FFI target reaches the caller carrying lekalo's
  message, which names the parameter and the domain (eagerly and under ``jit``), as
  ``jax.errors.JaxRuntimeError``, or as ``ValueError`` when JAX runs an already compiled
  function through its C++ fast path;
- runs on the CPU: the FFI targets are registered for the CPU platform only.

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

import numpy as np

try:
    import jax
    import jax.numpy as jnp
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "lekalo.jax needs JAX 0.4.34 or newer, which is not installed: `pip install jax`, "
        "or install lekalo with its extra, `pip install \"./crates/lekalo-py[jax]\"` from a "
        "clone of the repository"
    ) from e

from . import _jax_ffi
from ._lekalo import InputError
from ._jax_fits import fit_least_squares, fit_smoothing, interpolate
from ._jax_geometry import arc_length, closest_parameter
from ._jax_support import _degree, _float64, _require_x64

__all__ = [
    "bspline_eval",
    "nurbs_eval",
    "bspline_surface_eval",
    "nurbs_surface_eval",
    "tensor_bspline_eval",
    "tensor_nurbs_eval",
    "fit_least_squares",
    "fit_smoothing",
    "interpolate",
    "arc_length",
    "closest_parameter",
]

_jax_ffi.register_targets()


# -- curves ------------------------------------------------------------------------------------


def _curve_out_shape(res):
    """``C(u)``'s shape from the residuals ``(knots, ctrl, u)``: ``u.shape + (dim,)``."""
    _, ctrl, u = res
    return u.shape + ctrl.shape[-1:]


_CURVE = _jax_ffi.Kernel(
    "bspline_eval", "lekalo_bspline", ("knots", "control", "parameter"), _curve_out_shape
)


def bspline_eval(knots, control_points, u, degree):
    """``C(u)`` of the B-spline curve of ``degree`` on ``knots`` with ``control_points``
    (``(n, dim)``, or ``(n,)`` for a function), at the parameters ``u`` (any shape, in the
    domain ``[knots[degree], knots[n]]``). Returns ``u.shape + (dim,)`` (``u.shape`` for 1-D
    control points), lekalo's evaluation as an XLA custom call (no host callback).

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``u`` and ``knots``; ``degree`` is a constant (a Python int).
    At an interior knot where ``C'`` jumps, the derivative in ``u`` is the right-hand one. The
    knots' derivative (``lekalo.bspline_curve_knot_jvp`` / ``_vjp``) covers the interior knots
    ``knots[degree + 1 : n]``; the first and last ``degree + 1`` are held fixed (zero
    gradient). At a knot of multiplicity ``μ > 1`` it is one-sided: the first copy's is the
    derivative of decreasing it, the last copy's of increasing it, and the copies' gradients
    sum to that of moving them together.
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
    out = _CURVE((("degree", degree),), (), (knots, c2, u.reshape(-1)))
    out = out.reshape(u.shape + c2.shape[-1:])
    return out[..., 0] if scalar_dim else out


# -- NURBS curves ------------------------------------------------------------------------------


def _nurbs_out_shape(res):
    """``C(u)``'s shape from the residuals ``(knots, ctrl, w, u)``: ``u.shape + (dim,)``."""
    _, ctrl, _, u = res
    return u.shape + ctrl.shape[-1:]


_NURBS = _jax_ffi.Kernel(
    "nurbs_eval", "lekalo_nurbs", ("knots", "control", "weight", "parameter"), _nurbs_out_shape
)


def nurbs_eval(knots, control_points, weights, u, degree):
    """``C(u)`` of the NURBS curve of ``degree`` on ``knots`` with Euclidean ``control_points``
    (``(n, dim)``) and positive ``weights`` (``(n,)``), at the parameters ``u`` (any shape).
    Returns ``u.shape + (dim,)``, lekalo's evaluation as an XLA custom call (no host callback).

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``weights``, ``u`` and ``knots`` (the interior knots, with
    ``bspline_eval``'s conventions: the knot derivative of the homogeneous curve
    ``(w P, w)``, then the quotient rule, ``lekalo.nurbs_curve_knot_jvp`` / ``_vjp``);
    ``degree`` is a constant. A non-positive weight raises lekalo's error from the custom call.
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
    out = _NURBS((("degree", degree),), (), (knots, ctrl, w, u.reshape(-1)))
    return out.reshape(u.shape + ctrl.shape[-1:])


# -- surfaces ----------------------------------------------------------------------------------


def _surface_out_shape(res):
    """``S(u, v)``'s shape from the residuals ``(ku, kv, net, uv)``: ``uv.shape[:-1] +
    (dim,)``."""
    _, _, net, uv = res
    return uv.shape[:-1] + net.shape[-1:]


_SURFACE = _jax_ffi.Kernel(
    "bspline_surface_eval",
    "lekalo_surface",
    ("knots_u", "knots_v", "control", "parameter"),
    _surface_out_shape,
)


def bspline_surface_eval(knots_u, knots_v, control_points, u, v, degree_u, degree_v):
    """``S(u, v)`` of the tensor-product B-spline surface of degrees ``(degree_u, degree_v)`` on
    ``knots_u``, ``knots_v`` with the control net ``control_points`` (``(nu, nv, dim)``), at
    parameters ``u``, ``v`` of one shape. Returns ``u.shape + (dim,)``, bit-for-bit lekalo's
    evaluation, as an XLA custom call (no host callback).

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``u``, ``v``, ``knots_u`` and ``knots_v`` (the interior
    knots of each direction, as ``bspline_eval``'s); the degrees are constants.
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
    static = (("degree_u", degrees[0]), ("degree_v", degrees[1]))
    uv = jnp.stack([u.reshape(-1), v.reshape(-1)], axis=-1)
    out = _SURFACE(static, (), (ku, kv, ctrl, uv))
    return out.reshape(u.shape + ctrl.shape[-1:])


# -- NURBS surfaces ------------------------------------------------------------------------------


def _nurbs_surface_out_shape(res):
    """``S(u, v)``'s shape from the residuals ``(ku, kv, net, w, uv)``: ``uv.shape[:-1] +
    (dim,)``."""
    _, _, net, _, uv = res
    return uv.shape[:-1] + net.shape[-1:]


_NURBS_SURFACE = _jax_ffi.Kernel(
    "nurbs_surface_eval",
    "lekalo_nurbs_surface",
    ("knots_u", "knots_v", "control", "weight", "parameter"),
    _nurbs_surface_out_shape,
)


def nurbs_surface_eval(knots_u, knots_v, control_points, weights, u, v, degree_u, degree_v):
    """``S(u, v)`` of the NURBS surface of degrees ``(degree_u, degree_v)`` on ``knots_u``,
    ``knots_v`` with the Euclidean control net ``control_points`` (``(nu, nv, dim)``) and
    positive ``weights`` (``(nu, nv)``), at parameters ``u``, ``v`` of one shape. Returns
    ``u.shape + (dim,)``, bit-for-bit ``lekalo.NurbsSurface``'s evaluation, as an XLA custom
    call (no host callback).

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``weights``, ``u``, ``v``, ``knots_u`` and ``knots_v``, by
    lekalo's kernels (``lekalo.nurbs_surface_jvp`` / ``_vjp``: the rational basis
    ``R_kl = N_k M_l w_kl / W`` for the net, ``N_k M_l (P_kl − S) / W`` for the weights, the
    quotient rule ``(A_u − W_u S) / W`` for the parameters; ``lekalo.nurbs_surface_knot_jvp`` /
    ``_vjp`` for the interior knots of each direction, with ``bspline_eval``'s conventions).
    The degrees are constants. A non-positive weight raises lekalo's error from the custom call.
    """
    name = "nurbs_surface_eval"
    _require_x64(name)
    degrees = (_degree(degree_u, "degree_u", name), _degree(degree_v, "degree_v", name))
    ku = _float64(knots_u, "knots_u", name)
    kv = _float64(knots_v, "knots_v", name)
    ctrl = _float64(control_points, "control_points", name)
    w = _float64(weights, "weights", name)
    u = _float64(u, "u", name)
    v = _float64(v, "v", name)
    if ctrl.ndim != 3:
        raise InputError(
            f"lekalo.jax.{name}: control_points must be a net (nu, nv, dim), got shape {ctrl.shape}"
        )
    if w.shape != ctrl.shape[:2]:
        raise InputError(
            f"lekalo.jax.{name}: weights must be one a net point, shape {ctrl.shape[:2]}, got {w.shape}"
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
    static = (("degree_u", degrees[0]), ("degree_v", degrees[1]))
    uv = jnp.stack([u.reshape(-1), v.reshape(-1)], axis=-1)
    out = _NURBS_SURFACE(static, (), (ku, kv, ctrl, w, uv))
    return out.reshape(u.shape + ctrl.shape[-1:])


# -- tensor-product splines in N variables ---------------------------------------------------------


def _tensor_out_shape(res):
    """``S(x)``'s shape from the residuals ``(*knots, net, x)``: ``x.shape[:-1] + (dim,)``."""
    net, x = res[-2:]
    return x.shape[:-1] + net.shape[-1:]


_TENSOR = {}


def _tensor_kernel(n):
    """The kernel of splines in ``n`` variables: one differentiable kind a knot vector
    (``knots_0``, ...), then the net and the points."""
    if n not in _TENSOR:
        kinds = tuple(f"knots_{a}" for a in range(n)) + ("control", "point")
        _TENSOR[n] = _jax_ffi.Kernel("tensor_bspline_eval", "lekalo_tensor", kinds, _tensor_out_shape)
    return _TENSOR[n]


def tensor_bspline_eval(knots, control_points, x, degrees):
    """``S(x)`` of the tensor-product B-spline in ``N`` variables with degrees ``degrees`` (a
    tuple of ``N`` Python ints), knot vectors ``knots`` (a tuple of ``N`` 1-D arrays) and
    coefficients ``control_points`` (``(n_1, ..., n_N, dim)``, or ``(n_1, ..., n_N)`` for a
    scalar function), at the points ``x`` of shape ``(..., N)``. Returns ``x.shape[:-1] +
    (dim,)`` (``x.shape[:-1]`` for scalar coefficients), bit-for-bit
    ``lekalo.TensorBSpline(knots, control_points, degrees)(x)``.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``x`` and ``knots``, by lekalo's kernels as XLA custom calls
    (``lekalo.tensor_bspline_jvp`` and ``lekalo.tensor_bspline_vjp``: the net's Jacobian is the
    product of the ``N`` basis vectors on the ``Π (p_a + 1)`` block a point touches, the points'
    the partial derivatives ``∂S/∂x_a``; ``lekalo.tensor_bspline_knot_jvp`` / ``_vjp``: along
    each variable the curve's knot derivative on the net contracted with the other variables'
    basis functions, the interior knots of each variable, with ``bspline_eval``'s conventions).
    The degrees are constants.
    """
    name = "tensor_bspline_eval"
    _require_x64(name)
    if isinstance(degrees, (int, np.integer)) or not hasattr(degrees, "__len__"):
        raise InputError(f"lekalo.jax.{name}: degrees must be a tuple of Python ints, one a variable")
    degrees = tuple(_degree(d, f"degrees[{a}]", name) for a, d in enumerate(degrees))
    n = len(degrees)
    if n == 0:
        raise InputError(f"lekalo.jax.{name}: degrees is empty; a tensor spline has at least one variable")
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
    static = (("n_vars", n),) + tuple((f"degree_{a}", p) for a, p in enumerate(degrees))
    out = _tensor_kernel(n)(static, (), (*knots, c, x.reshape(-1, n)))
    out = out.reshape(x.shape[:-1] + c.shape[-1:])
    return out[..., 0] if scalar else out


# -- tensor-product NURBS in N variables -----------------------------------------------------------


def _tensor_nurbs_out_shape(res):
    """``S(x)``'s shape from the residuals ``(*knots, net, w, x)``: ``x.shape[:-1] + (dim,)``."""
    net, _, x = res[-3:]
    return x.shape[:-1] + net.shape[-1:]


_TENSOR_NURBS = {}


def _tensor_nurbs_kernel(n):
    """The kernel of NURBS in ``n`` variables: one differentiable kind a knot vector, then the
    net, the weights and the points."""
    if n not in _TENSOR_NURBS:
        kinds = tuple(f"knots_{a}" for a in range(n)) + ("control", "weight", "point")
        _TENSOR_NURBS[n] = _jax_ffi.Kernel(
            "tensor_nurbs_eval", "lekalo_tensor_nurbs", kinds, _tensor_nurbs_out_shape
        )
    return _TENSOR_NURBS[n]


def tensor_nurbs_eval(knots, control_points, weights, x, degrees):
    """``S(x)`` of the tensor-product NURBS in ``N`` variables with degrees ``degrees`` (a tuple
    of ``N`` Python ints), knot vectors ``knots`` (a tuple of ``N`` 1-D arrays), Euclidean
    coefficients ``control_points`` (``(n_1, ..., n_N, dim)``, or ``(n_1, ..., n_N)`` for a
    scalar function) and positive ``weights`` (``(n_1, ..., n_N)``), at the points ``x`` of
    shape ``(..., N)``. Returns ``x.shape[:-1] + (dim,)`` (``x.shape[:-1]`` for scalar
    coefficients), bit-for-bit ``lekalo.TensorNurbs(knots, control_points, degrees,
    weights)(x)``.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``, ``weights``, ``x`` and ``knots``, by lekalo's kernels as XLA
    custom calls (``lekalo.tensor_nurbs_jvp`` / ``_vjp``: the rational basis
    ``R_k = B_k w_k / W`` on the ``Π (p_a + 1)`` block a point touches, ``B_k (P_k − S) / W``
    for the weights, the quotient rule ``(A_a − W_a S) / W`` for the points;
    ``lekalo.tensor_nurbs_knot_jvp`` / ``_vjp`` for the interior knots of each variable, with
    ``bspline_eval``'s conventions). The degrees are constants.
    """
    name = "tensor_nurbs_eval"
    _require_x64(name)
    if isinstance(degrees, (int, np.integer)) or not hasattr(degrees, "__len__"):
        raise InputError(f"lekalo.jax.{name}: degrees must be a tuple of Python ints, one a variable")
    degrees = tuple(_degree(d, f"degrees[{a}]", name) for a, d in enumerate(degrees))
    n = len(degrees)
    if n == 0:
        raise InputError(f"lekalo.jax.{name}: degrees is empty; a tensor NURBS has at least one variable")
    if not hasattr(knots, "__len__") or len(knots) != n:
        raise InputError(
            f"lekalo.jax.{name}: knots must be a tuple of {n} 1-D arrays, one a variable"
        )
    knots = tuple(_float64(k, f"knots[{a}]", name) for a, k in enumerate(knots))
    ctrl = _float64(control_points, "control_points", name)
    w = _float64(weights, "weights", name)
    x = _float64(x, "x", name)
    if ctrl.ndim not in (n, n + 1):
        raise InputError(
            f"lekalo.jax.{name}: control_points must be (n_1, ..., n_{n}, dim) or (n_1, ..., "
            f"n_{n}), got shape {ctrl.shape}"
        )
    if w.shape != ctrl.shape[:n]:
        raise InputError(
            f"lekalo.jax.{name}: weights must be one a net point, shape {ctrl.shape[:n]}, got {w.shape}"
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
    static = (("n_vars", n),) + tuple((f"degree_{a}", p) for a, p in enumerate(degrees))
    out = _tensor_nurbs_kernel(n)(static, (), (*knots, c, w, x.reshape(-1, n)))
    out = out.reshape(x.shape[:-1] + c.shape[-1:])
    return out[..., 0] if scalar else out
