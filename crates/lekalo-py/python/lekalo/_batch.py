"""Helpers around the ragged batch form (flat arrays plus offsets)."""

from __future__ import annotations

from typing import Iterable, List, Mapping

import numpy as np

from ._lekalo import BSplineCurve, Error


_INT64_MAX = int(np.iinfo(np.int64).max)


def ragged_offsets(lengths: Iterable[int]) -> np.ndarray:
    """Offsets ``[0, l0, l0 + l1, ...]`` (int64) for groups of the given lengths.

    Every length must be a whole number >= 0 (``3`` or ``3.0``, not ``2.5``), and their sum
    must fit an int64 offset; anything else raises ``lekalo.Error`` naming the first bad
    length, instead of truncating it or wrapping the offsets around to negative numbers.

    >>> ragged_offsets([3, 2]).tolist()
    [0, 3, 5]
    """
    # a list stays Python objects (exact integers of any size) until it is checked
    a = lengths if isinstance(lengths, np.ndarray) else np.asarray(list(lengths), dtype=object)
    if a.ndim != 1:
        raise Error(f"lengths: expected a 1-D sequence of group lengths, got shape {a.shape}")
    if a.size == 0:
        return np.zeros(1, dtype=np.int64)
    if a.dtype.kind in "iu":
        # integer arrays: checked without a Python loop
        low = int(a.min())
        if low < 0:
            i = int(np.argmax(a < 0))
            raise Error(f"lengths[{i}] is {int(a[i])}: every group length must be >= 0")
        high = int(a.max())
        total = high * a.size
        if total > _INT64_MAX:
            total = sum(int(x) for x in a.tolist())
        values = a
    elif a.dtype.kind in "fO":
        values = a.tolist()
        for i, x in enumerate(values):
            if isinstance(x, (float, np.floating)) and np.isfinite(x) and float(x).is_integer():
                x = int(x)
            if isinstance(x, np.integer):
                x = int(x)
            if not isinstance(x, int) or isinstance(x, bool):
                raise Error(f"lengths[{i}] is {x!r}: a group length is a whole number of rows")
            if x < 0:
                raise Error(f"lengths[{i}] is {x}: every group length must be >= 0")
            values[i] = x
        total = sum(values)
    else:
        raise Error(f"lengths: dtype {a.dtype} is not a number type; give whole numbers of rows")
    if total > _INT64_MAX:
        raise Error(
            f"lengths: the total {total} is beyond the largest int64 offset {_INT64_MAX}"
        )
    out = np.zeros(a.size + 1, dtype=np.int64)
    np.cumsum(np.asarray(values, dtype=np.int64), out=out[1:])
    return out


def curves_from_batch(batch: Mapping[str, object]) -> List[BSplineCurve]:
    """The curves of a batch result as ``BSplineCurve`` objects (one Python object per curve:
    for inspection, not for large batches)."""
    p = int(batch["degree"])
    k, ko = batch["knots"], batch["knot_offsets"]
    c, co = batch["control"], batch["control_offsets"]
    return [
        BSplineCurve(p, k[ko[i]:ko[i + 1]], c[co[i]:co[i + 1]])
        for i in range(len(ko) - 1)
    ]


def curves_to_batch(curves: List[BSplineCurve]) -> dict:
    """The ragged form of B-spline curves of one degree and dimension."""
    if not curves:
        raise Error("curves: need at least one curve")
    p = curves[0].degree
    if any(c.degree != p for c in curves):
        raise Error("curves: all curves of a batch must have the same degree")
    knots = [c.knots for c in curves]
    ctrl = [c.control for c in curves]
    return {
        "degree": p,
        "knots": np.concatenate(knots),
        "knot_offsets": ragged_offsets([len(k) for k in knots]),
        "control": np.concatenate(ctrl),
        "control_offsets": ragged_offsets([len(c) for c in ctrl]),
    }
