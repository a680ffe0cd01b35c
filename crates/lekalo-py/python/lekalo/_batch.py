"""Helpers around the ragged batch form (flat arrays plus offsets)."""

from __future__ import annotations

from typing import Iterable, List, Mapping

import numpy as np

from ._lekalo import BSplineCurve, Error


def ragged_offsets(lengths: Iterable[int]) -> np.ndarray:
    """Offsets ``[0, l0, l0 + l1, ...]`` (int64) for groups of the given lengths.

    >>> ragged_offsets([3, 2]).tolist()
    [0, 3, 5]
    """
    lengths = np.asarray(list(lengths) if not isinstance(lengths, np.ndarray) else lengths)
    if lengths.size and (lengths.min() < 0):
        raise Error("lengths: every group length must be >= 0")
    out = np.zeros(lengths.size + 1, dtype=np.int64)
    np.cumsum(lengths, out=out[1:])
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
