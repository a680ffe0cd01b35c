"""``NdBSpline`` of ``lekalo.scipy``: SciPy's tensor-product B-spline in N variables, evaluated by
lekalo's ``TensorBSpline`` (the same ``(t, c, k)`` layout, ``docs/theory/tensor.md``)."""

from __future__ import annotations

import operator
from typing import Any

import numpy as np

from .. import _lekalo
from ._bspline import _get_dtype


class NdBSpline:
    """``scipy.interpolate.NdBSpline(t, c, k, extrapolate=None)``: values and partial
    derivatives at points ``xi`` of shape ``(..., ndim)``, lekalo's ``TensorBSpline``. Outside
    the base box, ``extrapolate=True`` (the default) continues the polynomials of the end spans
    and ``extrapolate=False`` gives ``nan``, as SciPy."""

    def __init__(self, t: Any, c: Any, k: Any, *, extrapolate: Any = None) -> None:
        ndim = len(t)
        if np.ndim(k) == 0:
            k = (operator.index(k),) * ndim
        if len(k) != ndim:
            raise ValueError(f"{len(t) = } != {len(k) = }.")
        self._k = tuple(operator.index(kd) for kd in k)
        self._t = tuple(np.ascontiguousarray(td, dtype=float) for td in t)
        for d, (td, kd) in enumerate(zip(self._t, self._k)):
            if td.ndim != 1 or td.shape[0] < 2 * kd + 2 or np.any(np.diff(td) < 0):
                raise ValueError(f"Knots in dimension {d} must be a sorted 1D array of at least {2 * kd + 2} values.")
        self.extrapolate = True if extrapolate is None else bool(extrapolate)
        c = np.asarray(c)
        if c.ndim < ndim:
            raise ValueError(f"Coefficients must be at least {ndim}-dimensional.")
        for d in range(ndim):
            n = self._t[d].shape[0] - self._k[d] - 1
            if c.shape[d] != n:
                raise ValueError(
                    f"Knots, coefficients and degree in dimension {d} are inconsistent: got "
                    f"{c.shape[d]} coefficients for {len(self._t[d])} knots, need at least {n} for k={k}."
                )
        self._c = np.ascontiguousarray(c, dtype=_get_dtype(c.dtype))

    @property
    def k(self) -> tuple:
        return self._k

    @property
    def t(self) -> tuple:
        return self._t

    @property
    def c(self) -> np.ndarray:
        return self._c

    def __call__(self, xi: Any, *, nu: Any = None, extrapolate: Any = None) -> np.ndarray:
        ndim = len(self._t)
        extrapolate = self.extrapolate if extrapolate is None else bool(extrapolate)
        if nu is None:
            nu = np.zeros((ndim,), dtype=np.int64)
        else:
            nu = np.asarray(nu, dtype=np.int64)
            if nu.ndim != 1 or nu.shape[0] != ndim:
                raise ValueError(f"invalid number of derivative orders {nu = } for ndim = {ndim}.")
            if any(nu < 0):
                raise ValueError(f"derivatives must be positive, got {nu = }")
        xi = np.asarray(xi, dtype=float)
        shape = xi.shape
        if shape[-1] != ndim:
            raise ValueError(f"Shapes: xi.shape={shape} and ndim={ndim}")
        xi = np.ascontiguousarray(xi.reshape(-1, ndim))
        lo = np.array([td[kd] for td, kd in zip(self._t, self._k)])
        hi = np.array([td[-kd - 1] for td, kd in zip(self._t, self._k)])
        undefined = np.isnan(xi).any(axis=1)  # nan, as SciPy
        outside = np.any((xi < lo) | (xi > hi), axis=1)
        complex_ = self._c.dtype.kind == "c"
        cc = self._c[..., None] if complex_ and self._c.ndim == ndim else self._c
        cc = np.ascontiguousarray(cc.view(float) if complex_ else cc)
        tail = cc.shape[ndim:]
        cc = cc.reshape(cc.shape[:ndim] + (-1,))
        # lekalo's spline, kept between calls while knots and coefficients are unchanged (in
        # place too)
        kept = getattr(self, "_lekalo_", None)
        if (
            kept is not None
            and kept[0] is self._c
            and np.array_equal(kept[1], self._c)
            and all(np.array_equal(a, b) for a, b in zip(kept[2], self._t))
        ):
            spline = kept[3]
        else:
            spline = _lekalo.TensorBSpline(self._t, cc, list(self._k))
            self._lekalo_ = (self._c, self._c.copy(), tuple(td.copy() for td in self._t), spline)
        out = np.full((xi.shape[0], cc.shape[-1]), np.nan)
        # beyond the base box: the end polynomials continued (extrapolate) or nan; a point with
        # a NaN or infinite coordinate is nan either way
        inside = np.all(np.isfinite(xi), axis=1) if extrapolate else ~outside & ~undefined
        if inside.any():
            out[inside] = np.asarray(
                spline(np.ascontiguousarray(xi[inside]), nu=[int(v) for v in nu], extrapolate=extrapolate)
            ).reshape(-1, cc.shape[-1])
        out = out.reshape((xi.shape[0],) + tail)
        if complex_:
            out = np.ascontiguousarray(out).view(np.complex128)
        return out.reshape(shape[:-1] + self._c.shape[ndim:])

    def derivative(self, nu: Any) -> "NdBSpline":
        """``NdBSpline.derivative(nu)``: the partial-derivative spline, degrees lowered by
        ``nu`` (lekalo's ``TensorBSpline.derivative``)."""
        ndim = len(self._t)
        nu = np.asarray(nu, dtype=np.int64)
        if nu.ndim != 1 or nu.shape[0] != ndim:
            raise ValueError(f"invalid number of derivative orders {nu = } for ndim = {ndim}.")
        if any(nu < 0):
            raise ValueError(f"derivative orders must be positive, got {nu = }")
        complex_ = self._c.dtype.kind == "c"
        cc = self._c[..., None] if complex_ and self._c.ndim == ndim else self._c
        cc = np.ascontiguousarray(cc.view(float) if complex_ else cc)
        tail = self._c.shape[ndim:]
        spline = _lekalo.TensorBSpline(self._t, cc.reshape(cc.shape[:ndim] + (-1,)), list(self._k))
        d = spline.derivative([int(v) for v in nu])
        c = np.ascontiguousarray(d.c)
        c = c.reshape(c.shape[:ndim] + (-1,))
        if complex_:
            c = c.view(np.complex128)
        return NdBSpline(d.t, c.reshape(c.shape[:ndim] + tail), tuple(d.k), extrapolate=self.extrapolate)

    @classmethod
    def design_matrix(cls, xvals: Any, t: Any, k: Any, extrapolate: bool = True):
        """``NdBSpline.design_matrix(xvals, t, k, extrapolate=True)``: the ``scipy.sparse``
        CSR array of the basis products at the points ``xvals`` (shape ``(npts, ndim)``), one
        column per coefficient of the C-ordered net, lekalo's ``tensor_design_matrix`` (each row
        the Kronecker product of the per-variable basis rows). ``extrapolate=False`` refuses a
        point outside the base box."""
        from scipy.sparse import csr_array

        xvals = np.asarray(xvals, dtype=float)
        if xvals.ndim != 2:
            raise ValueError(f"xvals: expected an array of shape (npts, ndim), got shape {xvals.shape}")
        ndim = xvals.shape[-1]
        if len(t) != ndim:
            raise ValueError(f"Data and knots are inconsistent: len(t) = {len(t)} for  {ndim = }.")
        if np.ndim(k) == 0:
            k = (operator.index(k),) * ndim
        data, indices, indptr, shape = _lekalo.tensor_design_matrix(
            np.ascontiguousarray(xvals),
            [np.ascontiguousarray(td, dtype=float) for td in t],
            [operator.index(kd) for kd in k],
            extrapolate=bool(extrapolate),
        )
        return csr_array((data, indices, indptr), shape=shape)


def make_ndbspl(points: Any, values: Any, k: Any = 3, *, solver: Any = None, **solver_args: Any) -> NdBSpline:
    """``scipy.interpolate.make_ndbspl(points, values, k=3, *, solver=..., **solver_args)``: the
    tensor-product spline through ``values`` on the grid ``points``, with SciPy's not-a-knot
    knots in every direction (odd degrees). SciPy assembles the collocation matrix of the whole
    grid and hands it to a sparse solver; lekalo solves the same system exactly, one banded
    factorisation per direction and one sweep of solves along each
    (``TensorInterpolation::knot_vectors``, ``docs/theory/tensor.md``), so ``solver`` and its
    arguments are accepted and not used."""
    from ._interpolate import _not_a_knot

    del solver, solver_args
    ndim = len(points)
    if np.ndim(k) == 0:
        k = (k,) * ndim
    k = tuple(operator.index(kd) for kd in k)
    if len(k) != ndim:
        raise ValueError(f"{len(points) = } != {len(k) = }.")
    axes = [np.ascontiguousarray(p, dtype=float) for p in points]
    for kd in k:
        if kd % 2 != 1:
            raise ValueError(f"Odd degree for now only. Got {kd}.")
    t = tuple(_not_a_knot(x, kd) for x, kd in zip(axes, k))
    values = np.asarray(values)
    complex_ = np.iscomplexobj(values)
    v = np.ascontiguousarray(values, dtype=complex if complex_ else float)
    if complex_:
        # real and imaginary parts as two trailing columns, solved together
        v = np.stack((v.real, v.imag), axis=-1)
    spline = _lekalo.TensorBSpline.interpolate_grid(axes, v, degrees=list(k), knots=list(t))
    c = spline.c
    if complex_:
        c = c[..., 0] + 1j * c[..., 1]
    return NdBSpline(t, c, k)
