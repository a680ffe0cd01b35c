"""lekalo: spline curves and surfaces, NumPy in and out.

Bezier, B-spline and NURBS curves and surfaces; interpolation with every parametrisation, knot
placement and end condition; natural and Hermite splines; piecewise polynomials and
quasi-interpolation; fitting (``make_lsq_spline``, ``make_smoothing_spline``, ``make_splrep``,
``fit_tolerance``, robust and surface fits); geometric queries (``CurveQuery``, ``SurfaceQuery``:
length, closest points, intersections, offsets, tessellation, curvature); many small curves at
once from flat arrays (``interpolate_batch``, ``evaluate_batch``); derivatives of evaluation for
automatic differentiation (``bspline_curve_jvp``, ``bspline_curve_vjp``, ... and the JAX functions
of ``lekalo.jax``). The computations are the Rust
library ``lekalo``'s, run with the GIL released.

Conventions (see the package README, "SciPy users start here"):

- arrays are float64; points are ``(n, dim)``, the last axis is the dimension, and a 1-D array
  is ``n`` values (dimension 1); C-ordered arrays are used in place, F-ordered ones copied once;
- evaluation returns ``t.shape + (dim,)``, also for dimension 1;
- parameters outside a curve's domain raise ``lekalo.Error`` (no extrapolation);
- every error is a ``lekalo.Error`` with the library's message: ``lekalo.InputError`` (also a
  ``ValueError``) for bad input, ``lekalo.NumericalError`` (also NumPy's ``LinAlgError``, as
  SciPy raises) for a numerical failure on valid input; a file that cannot be read is also
  the ``OSError`` Python raises for it (``lekalo.MissingFileError`` is a ``FileNotFoundError``,
  ``lekalo.NotAFileError`` an ``IsADirectoryError``, ``lekalo.FileAccessError`` a
  ``PermissionError``).

>>> import numpy as np, lekalo
>>> c = lekalo.interpolate(np.array([[0, 0], [1, 2], [3, 2], [4, 0]], dtype=float))
>>> c(np.linspace(0, 1, 5)).shape
(5, 2)
"""

from __future__ import annotations

from ._lekalo import (
    __version__,
    MAX_DEGREE,
    MAX_SCALARS,
    BezierCurve,
    BezierSurface,
    BSplineCurve,
    BSplineSurface,
    CubicHermite,
    Error,
    Face,
    FileAccessError,
    InputError,
    MissingFileError,
    NotAFileError,
    NumericalError,
    NurbsCurve,
    NurbsSurface,
    PiecewisePolynomial,
    PpSpace,
    TensorBSpline,
    CurveQuery,
    SurfaceQuery,
    basis_functions,
    bspline_curve_jvp,
    bspline_curve_vjp,
    bspline_curve_linearize,
    bspline_surface_jvp,
    bspline_surface_vjp,
    bspline_surface_linearize,
    interpolation_jvp,
    interpolation_vjp,
    least_squares_jvp,
    least_squares_vjp,
    least_squares_linearize,
    smoothing_jvp,
    smoothing_vjp,
    smoothing_linearize,
    tensor_bspline_jvp,
    tensor_bspline_vjp,
    tensor_bspline_linearize,
    nurbs_curve_jvp,
    nurbs_curve_vjp,
    nurbs_curve_linearize,
    cubic_through_four_points,
    evaluate_batch,
    fit_least_squares,
    fit_robust,
    fit_periodic,
    fit_closed,
    fit_smoothing,
    fit_smoothing_condition,
    fit_surface_grid,
    fit_surface_scattered,
    fit_tensor_grid,
    fit_tensor_grid_smoothing,
    fit_tensor_scattered,
    tensor_design_matrix,
    fit_tensor_scattered_smoothing,
    fit_sphere_least_squares,
    fit_sphere_smoothing,
    fit_sphere_grid,
    fit_tolerance,
    from_json,
    read_step,
    read_iges,
    write_step,
    write_iges,
    mesh_faces,
    gcv_score,
    generate_knots,
    make_lsq_spline,
    make_smoothing_spline,
    make_splprep,
    make_splrep,
    place_knots,
    interpolate,
    interpolate_batch,
    interpolate_surface,
    natural_cubic_spline,
    interpolate_with_end_derivatives,
    pchip_slopes,
    akima_slopes,
    parametrize,
    quasi_interpolate,
    hermite_bernstein,
    piecewise_hermite_bernstein,
    insert_knot_periodic,
    insert_knot_raw,
)
from . import _lekalo
from ._interop import design_matrix, from_geomdl, from_scipy, to_geomdl, to_scipy
from ._batch import curves_from_batch, curves_to_batch, ragged_offsets

Error.__module__ = "lekalo"

# blending (document 001), when the native module has it
for _name in ("JumpPolynomial", "Deformation", "BlendSpline", "CornerTransition", "smooth_polyline_corners"):
    if hasattr(_lekalo, _name):
        globals()[_name] = getattr(_lekalo, _name)

__all__ = [
    "MAX_DEGREE",
    "MAX_SCALARS",
    "BezierCurve",
    "BezierSurface",
    "BSplineCurve",
    "BSplineSurface",
    "CubicHermite",
    "Error",
    "InputError",
    "MissingFileError",
    "NotAFileError",
    "FileAccessError",
    "NumericalError",
    "NurbsCurve",
    "NurbsSurface",
    "PiecewisePolynomial",
    "PpSpace",
    "TensorBSpline",
    "CurveQuery",
    "SurfaceQuery",
    "basis_functions",
    "bspline_curve_jvp",
    "bspline_curve_vjp",
    "bspline_curve_linearize",
    "bspline_surface_jvp",
    "bspline_surface_vjp",
    "bspline_surface_linearize",
    "interpolation_jvp",
    "interpolation_vjp",
    "least_squares_jvp",
    "least_squares_vjp",
    "least_squares_linearize",
    "smoothing_jvp",
    "smoothing_vjp",
    "smoothing_linearize",
    "tensor_bspline_jvp",
    "tensor_bspline_vjp",
    "tensor_bspline_linearize",
    "nurbs_curve_jvp",
    "nurbs_curve_vjp",
    "nurbs_curve_linearize",
    "cubic_through_four_points",
    "curves_from_batch",
    "curves_to_batch",
    "design_matrix",
    "evaluate_batch",
    "fit_least_squares",
    "fit_robust",
    "fit_periodic",
    "fit_closed",
    "fit_smoothing",
    "fit_smoothing_condition",
    "fit_surface_grid",
    "fit_surface_scattered",
    "fit_tensor_grid",
    "fit_tensor_grid_smoothing",
    "fit_tensor_scattered",
    "tensor_design_matrix",
    "fit_tensor_scattered_smoothing",
    "fit_sphere_least_squares",
    "fit_sphere_smoothing",
    "fit_sphere_grid",
    "fit_tolerance",
    "from_geomdl",
    "from_json",
    "read_step",
    "read_iges",
    "write_step",
    "write_iges",
    "mesh_faces",
    "Face",
    "gcv_score",
    "make_lsq_spline",
    "make_smoothing_spline",
    "make_splprep",
    "make_splrep",
    "generate_knots",
    "place_knots",
    "from_scipy",
    "interpolate",
    "interpolate_batch",
    "interpolate_surface",
    "natural_cubic_spline",
    "interpolate_with_end_derivatives",
    "pchip_slopes",
    "akima_slopes",
    "parametrize",
    "quasi_interpolate",
    "hermite_bernstein",
    "piecewise_hermite_bernstein",
    "insert_knot_periodic",
    "insert_knot_raw",
    "ragged_offsets",
    "to_geomdl",
    "to_scipy",
] + [n for n in ("JumpPolynomial", "Deformation", "BlendSpline", "CornerTransition", "smooth_polyline_corners") if n in globals()]
