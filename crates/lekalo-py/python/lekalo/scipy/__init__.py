"""``lekalo.scipy``: the spline part of ``scipy.interpolate`` computed by lekalo.

Same names, signatures, defaults, return types, shapes, axis handling and errors as SciPy, so
that ``from lekalo.scipy import BSpline, make_interp_spline`` replaces the SciPy import. This
module converts arguments and arranges arrays only; every number comes from lekalo's kernel
(``BSplineCurve`` evaluation, ``eval_extrapolated``, ``derivative``, ``antiderivative``,
``integrate``, ``make_lsq_spline``, ``fit_least_squares``, ``interpolate``). Where
lekalo's native API deliberately differs from SciPy (it refuses parameters outside the domain,
returns ``t.shape + (dim,)``), this module does what SciPy does.

Available: ``BSpline`` (``__call__``, ``derivative``, ``antiderivative``, ``integrate``,
``construct_fast``, ``basis_element``, ``design_matrix``, ``insert_knot``,
``from_power_basis``, ``tck``, periodic extrapolation), ``make_interp_spline`` (not-a-knot,
periodic, ``"clamped"``, first-derivative pairs, second derivatives for cubics, explicit ``t``,
``k = 0 … 5``), ``make_lsq_spline``, ``make_smoothing_spline``, ``make_splrep`` and
``make_splprep`` (FITPACK's knots for ``s > 0``, or given knots ``t``), ``generate_knots``, ``splrep``, ``splprep``, ``splev``,
``splint``, ``sproot``, ``spalde``, ``splder``, ``splantider``, ``insert``, ``UnivariateSpline``,
``InterpolatedUnivariateSpline``, ``LSQUnivariateSpline``, ``RectBivariateSpline`` (FITPACK's
knots and smoothing on grids, ``__call__``, ``ev``, ``partial_derivative``, ``integral``),
``LSQBivariateSpline`` and ``SmoothBivariateSpline`` (FITPACK's ``surfit``, minimal-norm
solutions of rank-deficient systems), ``bisplrep`` (``task`` 0 and -1), ``bisplev``, ``dblint``, ``NdBSpline`` (extrapolating the end polynomials as SciPy, ``derivative``),
``make_ndbspl`` (solved directly, one banded sweep per direction);
``PPoly`` and ``BPoly`` (evaluation, ``derivative``, ``antiderivative``, ``integrate``, ``roots``/``solve``,
``extend``, ``from_spline``, ``from_bernstein_basis``, ``from_power_basis``) and, in
SciPy's ``PPoly`` form, ``CubicSpline``, ``CubicHermiteSpline``, ``PchipInterpolator``
(``pchip``, ``pchip_interpolate``), ``Akima1DInterpolator``. Not yet: mixed end conditions,
``splrep``/``splprep`` with ``task``/``xb``/``xe``, ``PPoly``/``BPoly`` with decreasing
breakpoints, ``BPoly.from_derivatives``, periodic knot insertion, ``bisplrep`` with ``task=1``, the spherical 2-D
classes,
``NdBSpline.design_matrix``; ``docs/scipy.md`` lists what SciPy's own tests find missing. The theory is in ``docs/theory/curves.md`` ("Antiderivatives, integrals and
extrapolation") and ``docs/theory/interpolation.md`` (PCHIP and Akima slopes).
"""

from __future__ import annotations

from ._bspline import BSpline
from ._fitpack import (
    bisplev,
    bisplrep,
    dblint,
    insert,
    spalde,
    splantider,
    splder,
    splev,
    splint,
    splprep,
    splrep,
    sproot,
)
from ._fitpack2 import (
    BivariateSpline,
    InterpolatedUnivariateSpline,
    LSQBivariateSpline,
    LSQUnivariateSpline,
    RectBivariateSpline,
    SmoothBivariateSpline,
    UnivariateSpline,
)
from ._interpolate import make_interp_spline, make_lsq_spline, make_smoothing_spline
from ._ndbspline import NdBSpline, make_ndbspl
from ._ppoly import (
    Akima1DInterpolator,
    BPoly,
    CubicHermiteSpline,
    CubicSpline,
    PchipInterpolator,
    PPoly,
    pchip,
    pchip_interpolate,
)
from ._splrep import generate_knots, make_splprep, make_splrep

__all__ = [
    "BSpline",
    "make_interp_spline",
    "make_lsq_spline",
    "make_smoothing_spline",
    "make_splrep",
    "make_splprep",
    "generate_knots",
    "splrep",
    "splprep",
    "splev",
    "splint",
    "sproot",
    "splder",
    "splantider",
    "insert",
    "spalde",
    "UnivariateSpline",
    "InterpolatedUnivariateSpline",
    "LSQUnivariateSpline",
    "BivariateSpline",
    "RectBivariateSpline",
    "LSQBivariateSpline",
    "SmoothBivariateSpline",
    "bisplrep",
    "bisplev",
    "dblint",
    "NdBSpline",
    "make_ndbspl",
    "CubicSpline",
    "CubicHermiteSpline",
    "PchipInterpolator",
    "pchip",
    "pchip_interpolate",
    "Akima1DInterpolator",
    "PPoly",
    "BPoly",
]
