"""Two queries of a B-spline curve as JAX functions: ``arc_length`` and ``closest_parameter`` of
``lekalo.jax``, differentiable where they are smooth with respect to the knots, the control
points (and the query points), by lekalo's XLA FFI targets (values, JVP and VJP compiled into the program,
no host callback; ``lekalo::derivatives::ArcLengthGradient`` and ``ClosestParameters``,
``docs/theory/derivatives.md``, "Arc length and closest points")."""

from __future__ import annotations

from ._jax_ffi import Kernel
from ._lekalo import InputError
from ._jax_support import _degree, _float64, _require_x64


def _length_out_shape(res):
    """The length's shape from the residuals ``(knots, ctrl)``: the batch axes only."""
    return res[1].shape[:-2]


def _closest_out_shape(res):
    """The parameters' shape from the residuals ``(knots, ctrl, x)``: one a point."""
    return res[2].shape[:-1]


# values, JVP and VJP as the FFI targets ``lekalo_arc_length_*`` and
# ``lekalo_closest_parameter_*`` (``xla_ffi/geometry.rs``)
# (the knots are among the differentiable arrays, a kind of their own)
_LENGTH = Kernel("arc_length", "lekalo_arc_length", ("knots", "control"), _length_out_shape)
_CLOSEST = Kernel(
    "closest_parameter",
    "lekalo_closest_parameter",
    ("knots", "control", "point"),
    _closest_out_shape,
)


def _curve_args(name, knots, control_points, degree):
    """The checked curve arguments: ``(degree, knots, control points as (n, dim))``."""
    _require_x64(name)
    degree = _degree(degree, "degree", name)
    knots = _float64(knots, "knots", name)
    ctrl = _float64(control_points, "control_points", name)
    if knots.ndim != 1:
        raise InputError(f"lekalo.jax.{name}: knots must be 1-D, got shape {knots.shape}")
    if ctrl.ndim not in (1, 2) or ctrl.shape[0] == 0:
        raise InputError(
            f"lekalo.jax.{name}: control_points must be (n, dim) or (n,) with n >= 1, got "
            f"shape {ctrl.shape}"
        )
    n = ctrl.shape[0]
    if knots.shape[0] != n + degree + 1:
        raise InputError(
            f"lekalo.jax.{name}: {n} control points of degree {degree} need {n + degree + 1} "
            f"knots (control points + degree + 1), got {knots.shape[0]}"
        )
    return degree, knots, ctrl[:, None] if ctrl.ndim == 1 else ctrl


def arc_length(knots, control_points, degree):
    """The length of the B-spline curve of ``degree`` on ``knots`` with ``control_points``
    (``(n, dim)``, or ``(n,)`` for a curve in one dimension) over its domain: ``lekalo.QueryCurve``'s length (adaptive Gauss–Legendre quadrature of ``|C'|`` to
    1e-13 relative), a scalar.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points``: ``∂L/∂P_j = ∫ N'_j(t) C'(t)/|C'(t)| dt`` on the nodes of
    the quadrature that computes ``L`` (where ``C' = 0``, a cusp, the length is not
    differentiable and the node adds nothing); and with respect to ``knots``
    (``lekalo::derivatives::ArcLengthGradient::with_knots``): the interior knots by the knot
    derivative of ``C'`` on the same nodes, the domain's ends ``knots[degree]`` and
    ``knots[n]`` by the length's invariance under an affine map of the knots. The
    ``degree`` knots outside each end move with it: their entries of the gradient are zero,
    and a tangent that moves a clamped end with all its copies is read from
    ``knots[degree]`` (``knots[n]``). ``degree`` is a constant.
    """
    name = "arc_length"
    degree, knots, ctrl = _curve_args(name, knots, control_points, degree)
    return _LENGTH((("degree", degree),), (), (knots, ctrl))


def closest_parameter(knots, control_points, x, degree):
    """The parameters of the closest points of the B-spline curve of ``degree`` on ``knots``
    with ``control_points`` (``(n, dim)``) to the points ``x`` (``(..., dim)``; ``(dim,)`` for
    one): ``lekalo.QueryCurve.project``'s parameters, shape ``x.shape[:-1]``.

    Differentiable (first order, forward and reverse mode, under ``jit`` and ``vmap``) with
    respect to ``control_points`` and ``x`` where the closest point is unique and isolated, by
    the implicit function theorem on ``g(t) = (C(t) - x)·C'(t) = 0``:
    ``ṫ = (C'·ẋ - Σ_j (N_j C' + N'_j (C - x))·Ṗ_j) / (|C'|² + (C - x)·C'')``; at an end of the
    domain, or at a corner of the curve (a knot where ``C'`` jumps), the parameter stays
    there (derivative 0). A point at the curve's centre of curvature (no isolated minimum of
    the distance) raises lekalo's error.

    Differentiable with respect to ``knots`` too
    (``lekalo::derivatives::ClosestParameters::with_knots``): ``ṫ = ℓ(t) − (C'·∂C/∂τ·r +
    (C - x)·∂C'/∂τ·r) / g'`` with ``ℓ`` the affine map that moves the domain's ends as
    ``knots[degree]`` and ``knots[n]`` and ``r`` the rest of the knot tangent, on the interior
    knots; at an end the parameter moves with that end, at a corner with the corner's knot.
    The ``degree`` knots outside each end move with it (their gradient entries are zero).
    ``degree`` is a constant.
    """
    name = "closest_parameter"
    degree, knots, ctrl = _curve_args(name, knots, control_points, degree)
    x = _float64(x, "x", name)
    dim = ctrl.shape[-1]
    if x.ndim < 1 or x.shape[-1] != dim:
        raise InputError(
            f"lekalo.jax.{name}: x must have shape (..., {dim}), the coordinates of the "
            f"points on the last axis, got {x.shape}"
        )
    if x.size == 0:
        raise InputError(
            f"lekalo.jax.{name}: x of shape {x.shape} holds no point; give at least one"
        )
    out = _CLOSEST((("degree", degree),), (), (knots, ctrl, x.reshape(-1, dim)))
    return out.reshape(x.shape[:-1])
