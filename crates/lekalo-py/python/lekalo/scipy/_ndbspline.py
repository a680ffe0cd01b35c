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
        # the coefficients as float64 numbers, a view of ``_c`` (a complex value is two trailing
        # numbers), handed to lekalo at every call: changes made in place are seen
        cc = self._c[..., None] if self._c.dtype.kind == "c" and self._c.ndim == ndim else self._c
        self._cc = cc.view(np.float64) if cc.dtype.kind == "c" else cc
        # real values, one number a point: a point given as a tuple takes lekalo's tensor_value
        # on the coefficients as one flat view (changes made in place are seen), its arrays
        # held once by a TensorValueAt so that a call converts only the point
        self._flat = self._cc.reshape(-1) if self._cc.ndim == ndim else None
        self._at = None if self._flat is None else _lekalo.TensorValueAt(self._t, self._flat, self._k)

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
        """Values (or the partial derivative of orders ``nu``) at the points ``xi`` of shape
        ``(..., ndim)``: lekalo's ``tensor_values`` on the knots and coefficients in place
        (``TensorBSplineRef::par_eval_batch_beyond``); beyond the base box the end polynomials
        continued (``extrapolate``) or nan, and nan at a NaN or infinite coordinate, as SciPy.
        One point given as a tuple of numbers is lekalo's ``tensor_value`` (through the arrays held by
        a ``TensorValueAt``), which reads only the few knots and coefficients it needs."""
        extrapolate = self.extrapolate if extrapolate is None else bool(extrapolate)
        if nu is None and type(xi) is tuple and self._at is not None:
            # anything tensor_value does not take (a coordinate that is not a number, the wrong
            # count) goes the array way, which raises SciPy's errors
            try:
                return np.array(self._at.value(xi, extrapolate))
            except Exception:
                pass
        ndim = len(self._t)
        orders = None
        if nu is not None:
            nu = np.asarray(nu, dtype=np.int64)
            if nu.ndim != 1 or nu.shape[0] != ndim:
                raise ValueError(f"invalid number of derivative orders {nu = } for ndim = {ndim}.")
            if any(nu < 0):
                raise ValueError(f"derivatives must be positive, got {nu = }")
            orders = [int(v) for v in nu]
        xi = np.asarray(xi, dtype=float)
        shape = xi.shape
        if shape[-1] != ndim:
            raise ValueError(f"Shapes: xi.shape={shape} and ndim={ndim}")
        if not xi.flags.c_contiguous:
            xi = np.ascontiguousarray(xi)
        out = _lekalo.tensor_values(self._t, self._cc, self._k, xi, orders, "continue" if extrapolate else "nan")
        if self._c.dtype.kind == "c":
            out = out.view(np.complex128)
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
    knots in every direction (data sites for odd degrees, mid-points for even ones, as SciPy's
    ``_not_a_knot``). SciPy assembles the collocation matrix of the whole
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
    # an axis too short for its degree (or empty, or not 1-D) gets no knots here: the library
    # refuses it with its own message (the degree, the count and the degrees allowed) before
    # anything is allocated, where not-a-knot knots of a huge degree would be allocated first
    t = tuple(_not_a_knot(x, kd) if x.ndim == 1 and x.shape[0] > kd else None for x, kd in zip(axes, k))
    values = np.asarray(values)
    complex_ = np.iscomplexobj(values)
    v = np.ascontiguousarray(values, dtype=complex if complex_ else float)
    if complex_:
        # real and imaginary parts as two trailing columns, solved together
        v = np.stack((v.real, v.imag), axis=-1)
    # the coefficients alone, moved into NumPy (no spline object holding a second copy)
    c = _lekalo.TensorBSpline.interpolate_grid_c(axes, v, degrees=list(k), knots=list(t))
    if complex_:
        c = c[..., 0] + 1j * c[..., 1]
    return NdBSpline(t, c, k)
