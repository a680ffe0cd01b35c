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
``make_ndbspl`` (solved directly, one banded sweep per direction); the spherical
``LSQSphereBivariateSpline``, ``SmoothSphereBivariateSpline`` and ``RectSphereBivariateSpline``
(FITPACK's ``sphere`` and ``spgrid``, with the pole conditions; ``docs/theory/sphere.md``);
``PPoly`` and ``BPoly`` (evaluation, ``derivative``, ``antiderivative``, ``integrate``, ``roots``/``solve``,
``extend``, ``from_spline``, ``from_bernstein_basis``, ``from_power_basis``) and, in
SciPy's ``PPoly`` form, ``CubicSpline``, ``CubicHermiteSpline``, ``PchipInterpolator``
(``pchip``, ``pchip_interpolate``), ``Akima1DInterpolator``. ``UnivariateSpline.set_smoothing_factor``
continues FITPACK's knot rounds from the last fit (``curfit``'s ``iopt=1``); ``splrep`` and
``splprep`` with ``task=1`` raise SciPy 1.17's ``UnboundLocalError``. Not yet: ``task=1`` of
``bisplrep``; ``docs/scipy.md`` lists what SciPy's own tests find missing. The theory is in ``docs/theory/curves.md`` ("Antiderivatives, integrals and
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
from ._cubic import (
    Akima1DInterpolator,
    CubicHermiteSpline,
    CubicSpline,
    PchipInterpolator,
    pchip,
    pchip_interpolate,
)
from ._ppoly import BPoly, PPoly
from ._sphere import (
    LSQSphereBivariateSpline,
    RectSphereBivariateSpline,
    SmoothSphereBivariateSpline,
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
    "LSQSphereBivariateSpline",
    "SmoothSphereBivariateSpline",
    "RectSphereBivariateSpline",
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

# scipy.interpolate's names outside its spline part, with what to use instead: importing one
# from lekalo.scipy raises ImportError with that advice and the list above, not Python's bare
# "cannot import name".
_ELSEWHERE = "it is outside SciPy's spline functions; import it from scipy.interpolate"
_GRID = (
    "it is outside SciPy's spline functions; import it from scipy.interpolate, or for a cubic "
    "spline on the grid use make_ndbspl(points, values, k=3) from lekalo.scipy (SciPy's "
    "not-a-knot ends; RegularGridInterpolator's method='cubic' has its own)"
)
_NOT_PROVIDED = {
    "interp1d": (
        "SciPy keeps it as legacy; for interp1d(x, y, kind='cubic') use "
        "make_interp_spline(x, y, k=3) or CubicSpline(x, y), for kind='linear' "
        "make_interp_spline(x, y, k=1)"
    ),
    "interp2d": "SciPy has removed it; use RectBivariateSpline(x, y, z) on a grid",
    "interpn": _GRID,
    "RegularGridInterpolator": _GRID,
    "griddata": _ELSEWHERE,
    "LinearNDInterpolator": _ELSEWHERE,
    "NearestNDInterpolator": _ELSEWHERE,
    "CloughTocher2DInterpolator": _ELSEWHERE,
    "RBFInterpolator": _ELSEWHERE,
    "Rbf": _ELSEWHERE,
    "BarycentricInterpolator": _ELSEWHERE,
    "barycentric_interpolate": _ELSEWHERE,
    "KroghInterpolator": _ELSEWHERE,
    "krogh_interpolate": _ELSEWHERE,
    "FloaterHormannInterpolator": _ELSEWHERE,
    "AAA": _ELSEWHERE,
    "approximate_taylor_polynomial": _ELSEWHERE,
    "lagrange": _ELSEWHERE,
    "pade": _ELSEWHERE,
    "NdPPoly": "not provided yet; import it from scipy.interpolate",
}


def __getattr__(name: str):
    """Raises ImportError with advice for a scipy.interpolate name lekalo.scipy does not provide
    (``from lekalo.scipy import interp1d``); any other missing name is an AttributeError, so
    ``hasattr`` stays False for it."""
    advice = _NOT_PROVIDED.get(name)
    if advice is None:
        raise AttributeError(f"module 'lekalo.scipy' has no attribute {name!r}")
    raise ImportError(
        f"lekalo.scipy does not provide {name}: {advice}. lekalo.scipy provides SciPy's spline "
        f"part: {', '.join(__all__)}",
        name=name,
    )
