"""lekalo's XLA FFI targets inside JAX: their registration, the pair of JAX primitives that
makes a kernel's JVP and VJP differentiable by JAX's rules, and ``Kernel``, the differentiable
function of a kernel's three targets (``lekalo.jax`` builds on this).

The native module exports typed XLA custom-call handlers (``_lekalo.xla_ffi_handlers()``,
written against XLA's FFI C ABI in ``crates/lekalo-py/src/xla_ffi/``), registered here for the
CPU once, at import. Values are a plain ``jax.ffi.ffi_call``. A derivative needs more: in a
``jax.custom_jvp`` rule the tangent must be a linear function JAX can transpose (for
``jax.grad``) and batch (for ``jax.vmap``). ``LinearPair`` makes two primitives,

- ``jvp(*residuals, *tangents) -> tangent_out`` (linear in the tangents), lowered to the
  kernel's JVP target, and
- ``vjp(*residuals, cotangent) -> cotangents`` (linear in the cotangent), lowered to its VJP
  target,

each the other's transpose (``⟨ḡ, J ẋ⟩ = ⟨Jᵀ ḡ, ẋ⟩``), so that reverse mode runs lekalo's VJP
kernel and forward mode its JVP kernel, both in compiled code. Under ``vmap`` the batch axes are
moved to the front and unbatched operands broadcast, the layout every handler accepts (one
kernel call a batch element). Which linear inputs are present is a static parameter: a
symbolic-zero tangent is not passed, and a cotangent that is not wanted is not computed.

Every kernel has the same operands: its knot vectors, then its differentiable arrays, one a
kind (control points, weights, parameters...). A kernel whose knots are differentiable (the
evaluations of curves, surfaces and tensor splines) passes them among the arrays, as kinds of
their own (``knots``, ``knots_u``, ``knots_v``, ``knots_0``...), and none as constants. ``Kernel`` is the ``custom_jvp``
function of such a kernel: values by its ``_eval`` target, tangents by ``LinearPair``.
"""

from __future__ import annotations

import ctypes
import functools

import numpy as np

import jax
import jax.numpy as jnp
from jax.custom_derivatives import SymbolicZero
from jax.extend.core import Primitive
from jax.interpreters import ad, batching, mlir

from . import _lekalo
from ._jax_support import _first_order_only, _no_knot_tangent

_REGISTERED = False


def register_targets():
    """Registers lekalo's FFI handlers with XLA for the CPU (once a process)."""
    global _REGISTERED
    if _REGISTERED:
        return
    for name, address in _lekalo.xla_ffi_handlers().items():
        capsule = jax.ffi.pycapsule(ctypes.c_void_p(address))
        jax.ffi.register_ffi_target(name, capsule, platform="cpu")
    _REGISTERED = True


def attributes(static):
    """The custom call's attributes: integers as int64 (``static``: ``(name, value)`` pairs)."""
    return {k: np.int64(v) for k, v in static}


def call(target, result, static, *args):
    """``args`` through the FFI target: ``result`` a ``jax.ShapeDtypeStruct`` (or a list of
    them); batched by leading axes on every operand (``vmap_method="broadcast_all"``)."""
    return jax.ffi.ffi_call(target, result, vmap_method="broadcast_all")(*args, **attributes(static))


def _front(args, dims):
    """The operands with their batch axis first, unbatched ones broadcast to its size."""
    size = next(a.shape[d] for a, d in zip(args, dims) if d is not None)
    return [
        jnp.broadcast_to(a, (size,) + a.shape) if d is None else jnp.moveaxis(a, d, 0)
        for a, d in zip(args, dims)
    ]


class LinearPair:
    """The JVP and VJP primitives of one kernel (see the module docstring).

    ``kinds``: the names of the differentiable inputs, in order (the targets' attributes
    ``with_<kind>`` say which are present); ``like[k]``: the index of the residual whose shape
    and dtype the tangent of ``kinds[k]`` has; ``out_like(residual_avals)``: the shape of the
    JVP's result (the VJP's cotangent). The residuals and ``static`` (``(name, int)`` pairs, the
    targets' other attributes) are the same for both.
    """

    def __init__(self, name, jvp_target, vjp_target, kinds, like, out_shape):
        self.name, self.kinds, self.like, self.out_shape = name, tuple(kinds), tuple(like), out_shape
        self.n_res = max(like) + 1
        self.jvp = Primitive(jvp_target)
        self.vjp = Primitive(vjp_target)
        self.vjp.multiple_results = True
        self.jvp.def_abstract_eval(self._jvp_aval)
        self.vjp.def_abstract_eval(self._vjp_avals)
        for prim, target in ((self.jvp, jvp_target), (self.vjp, vjp_target)):
            prim.def_impl(_compiled(prim))
            mlir.register_lowering(prim, self._lowering(target), platform="cpu")
            batching.primitive_batchers[prim] = _batcher(prim)
        ad.primitive_transposes[self.jvp] = self._jvp_transpose
        ad.primitive_transposes[self.vjp] = self._vjp_transpose
        ad.primitive_jvps[self.jvp] = self._linear_jvp(self.jvp)
        ad.primitive_jvps[self.vjp] = self._linear_jvp(self.vjp)

    # -- shapes and lowering

    def _jvp_aval(self, *args, static, present):
        res = args[: self.n_res]
        return jax.core.ShapedArray(self.out_shape(res), jnp.float64)

    def _vjp_avals(self, *args, static, present):
        res = args[: self.n_res]
        return [
            jax.core.ShapedArray(res[i].shape, jnp.float64)
            for i, p in zip(self.like, present)
            if p
        ]

    def _lowering(self, target):
        rule = jax.ffi.ffi_lowering(target)

        def lower(ctx, *args, static, present):
            flags = {f"with_{k}": np.int64(p) for k, p in zip(self.kinds, present)}
            return rule(ctx, *args, **attributes(static), **flags)

        return lower

    # -- binding

    def tangent(self, residuals, tangents, static):
        """``J ẋ``: ``tangents`` one a kind, ``None`` (or a symbolic zero) for an absent one;
        ``None`` if all are absent."""
        present = tuple(t is not None for t in tangents)
        if not any(present):
            return None
        lin = [t for t in tangents if t is not None]
        return self.jvp.bind(*residuals, *lin, static=static, present=present)

    # -- transposition: each primitive's transpose is the other

    def _jvp_transpose(self, ct, *args, static, present):
        res, lin = args[: self.n_res], args[self.n_res :]
        assert not any(ad.is_undefined_primal(r) for r in res), "a residual is not linear"
        # the cotangents wanted: of the linear inputs being transposed
        wanted, it = [], iter(lin)
        for p in present:
            wanted.append(p and ad.is_undefined_primal(next(it)))
        if type(ct) is ad.Zero or not any(wanted):
            return [None] * len(args)
        outs = iter(self.vjp.bind(*res, ct, static=static, present=tuple(wanted)))
        cts = [next(outs) if w else None for p, w in zip(present, wanted) if p]
        return [None] * self.n_res + cts

    def _vjp_transpose(self, cts, *args, static, present):
        res = args[: self.n_res]
        assert not any(ad.is_undefined_primal(r) for r in res), "a residual is not linear"
        cts_iter = iter(cts)
        tangents = [next(cts_iter) if p else None for p in present]
        tangents = [None if t is None or type(t) is ad.Zero else t for t in tangents]
        out = self.tangent(res, tangents, static)
        return [None] * self.n_res + [out]

    def _linear_jvp(self, prim):
        """Forward mode through a primitive: linear in its last operands, and the residuals
        held constant (a derivative with respect to them would be a second derivative of the
        kernel, which lekalo.jax refuses before it gets here)."""

        def rule(primals, tangents, **params):
            if any(type(t) is not ad.Zero for t in tangents[: self.n_res]):
                raise NotImplementedError(
                    f"lekalo.jax.{self.name}: only first derivatives are supported"
                )
            out = prim.bind(*primals, **params)
            lin = [ad.instantiate_zeros(t) for t in tangents[self.n_res :]]
            return out, prim.bind(*primals[: self.n_res], *lin, **params)

        return rule


def _compiled(prim):
    """The eager implementation of a primitive: its lowering, compiled once for each set of
    parameters."""

    @functools.lru_cache(maxsize=None)
    def jitted(static, present):
        return jax.jit(lambda *a: prim.bind(*a, static=static, present=present))

    def impl(*args, static, present):
        return jitted(static, present)(*args)

    return impl


def _batcher(prim):
    """The batching rule of a primitive whose operands may all carry leading batch axes."""

    def rule(args, dims, **params):
        out = prim.bind(*_front(args, dims), **params)
        return out, ([0] * len(out) if prim.multiple_results else 0)

    return rule


class Kernel:
    """A lekalo kernel as a differentiable JAX function of ``(static, knots, arrays)``:
    ``knots`` a tuple of constant knot vectors (a tangent raises ``NotImplementedError``; knots
    that are differentiable are passed among ``arrays`` instead),
    ``arrays`` a tuple of the differentiable arrays, one for each of ``kinds`` (the targets'
    ``with_<kind>`` flags), ``static`` the targets' integer attributes as ``(name, value)``
    pairs. The values are the target ``{prefix}_eval``, of shape ``out_shape(residuals)``
    (``residuals = knots + arrays``, as arrays or their shapes); the JVP and VJP the targets
    ``{prefix}_jvp`` and ``{prefix}_vjp`` through a ``LinearPair`` (one for each number of knot
    vectors). First derivatives only; ``name`` is the public function's, for the errors.

    A kernel whose derivatives reuse the factorisation of its values gives
    ``factor_shape(residuals)``, the shape of its factors: under differentiation its values come
    from the target ``{prefix}_factor``, which returns them with the factors, and the factors
    join the JVP's and VJP's residuals after the knot vectors, so that neither factors the system
    again (``jax.grad`` runs the values and the VJP: one factorisation, not two). The
    ``out_shape`` of such a kernel reads the residuals from the end (the data last)."""

    def __init__(self, name, prefix, kinds, out_shape, factor_shape=None):
        self.name, self.prefix, self.kinds, self.out_shape = name, prefix, tuple(kinds), out_shape
        self._pairs = {}

        def values(static, knots, arrays):
            residuals = (*knots, *arrays)
            shape = jax.ShapeDtypeStruct(out_shape(residuals), jnp.float64)
            return call(f"{prefix}_eval", shape, static, *residuals)

        def values_and_factors(static, knots, arrays):
            residuals = (*knots, *arrays)
            shapes = [
                jax.ShapeDtypeStruct(out_shape(residuals), jnp.float64),
                jax.ShapeDtypeStruct(factor_shape(residuals), jnp.float64),
            ]
            return call(f"{prefix}_factor", shapes, static, *residuals)

        def jvp(static, primals, tangents):
            (knots, arrays), (dk, da) = primals, tangents
            _no_knot_tangent(name, *dk)
            guard = functools.partial(_first_order_only, name)
            knots, arrays = tuple(map(guard, knots)), tuple(map(guard, arrays))
            if factor_shape is None:
                out = values(static, knots, arrays)
            else:
                out, factors = values_and_factors(static, knots, arrays)
                knots = (*knots, factors)
            lin = [None if isinstance(t, SymbolicZero) else t for t in da]
            tangent = self._pair(len(knots)).tangent((*knots, *arrays), lin, static)
            return out, jnp.zeros_like(out) if tangent is None else tangent

        self._f = jax.custom_jvp(values, nondiff_argnums=(0,))
        self._f.defjvp(jvp, symbolic_zeros=True)

    def _pair(self, n_knots):
        if n_knots not in self._pairs:
            like = tuple(range(n_knots, n_knots + len(self.kinds)))
            self._pairs[n_knots] = LinearPair(
                self.name, f"{self.prefix}_jvp", f"{self.prefix}_vjp",
                kinds=self.kinds, like=like, out_shape=self.out_shape,
            )
        return self._pairs[n_knots]

    def __call__(self, static, knots, arrays):
        return self._f(tuple(static), tuple(knots), tuple(arrays))
