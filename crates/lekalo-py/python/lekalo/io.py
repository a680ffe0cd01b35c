"""The file layouts of the ``lekalo`` tool in Python (docs/formats.md), with NumPy and pyarrow.

A curve moves between the CLI, Python and a Spark or DuckDB job without conversion scripts:

- ``.npz`` curves (section 6b): :func:`load_npz_curve`, :func:`save_npz_curve`;
- Parquet batches (section 6c): :func:`write_points_parquet` writes point sets in the long layout
  that ``lekalo interpolate pts.parquet -o curves.parquet`` reads, :func:`read_curves_parquet`
  reads the curves it writes (one dict per row).

pyarrow is needed only by the Parquet functions.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

__all__ = [
    "load_npz_curve",
    "save_npz_curve",
    "write_points_parquet",
    "read_curves_parquet",
]


def load_npz_curve(path: str) -> dict[str, Any]:
    """The members of a curve ``.npz``: ``degree`` (int), ``knots`` (n + p + 1,),
    ``control_points`` (n, d) and ``weights`` (n,) or None for a B-spline."""
    with np.load(path) as z:
        weights = z["weights"] if "weights" in z.files else None
        control = z["control_points"]
        return {
            "degree": int(z["degree"]),
            "knots": np.asarray(z["knots"], dtype=np.float64),
            "control_points": control.reshape(len(control), -1).astype(np.float64, copy=False),
            "weights": None if weights is None else np.asarray(weights, dtype=np.float64),
        }


def save_npz_curve(path: str, degree: int, knots, control_points, weights=None) -> None:
    """Writes a B-spline (or, with ``weights``, a NURBS) curve as the ``.npz`` lekalo reads."""
    arrays = {
        "degree": np.int64(degree),
        "knots": np.asarray(knots, dtype=np.float64),
        "control_points": np.asarray(control_points, dtype=np.float64),
    }
    if weights is not None:
        arrays["weights"] = np.asarray(weights, dtype=np.float64)
    np.savez(path, **arrays)


def _coordinate_names(dim: int) -> list[str]:
    return ["x", "y", "z"][:dim] if dim <= 3 else [f"x{k}" for k in range(1, dim + 1)]


def write_points_parquet(path: str, groups: Mapping[Any, Any], key: str = "group") -> None:
    """Writes point sets ``{key: (n, d) array}`` in the long layout: the key column, then one
    double column per coordinate (``x, y, z`` or ``x1 … xd``), the rows of a group consecutive."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    arrays = [np.asarray(p, dtype=np.float64).reshape(len(p), -1) for p in groups.values()]
    dims = {a.shape[1] for a in arrays}
    if len(dims) != 1:
        raise ValueError(f"point sets of several dimensions {sorted(dims)}; one file holds one")
    dim = dims.pop()
    keys = [k for k, a in zip(groups.keys(), arrays) for _ in range(len(a))]
    data = np.concatenate(arrays) if arrays else np.zeros((0, dim))
    table = pa.table(
        {key: keys, **{n: data[:, c] for c, n in enumerate(_coordinate_names(dim))}}
    )
    pq.write_table(table, path)


def read_curves_parquet(path: str) -> list[dict[str, Any]]:
    """The rows of a curves file: dicts with the key column, ``type``, ``degree``, ``knots``,
    ``control_points`` (n, d), ``weights`` (None unless rational) and ``error`` (None, or why
    the group gave no curve; the curve fields are then None)."""
    import pyarrow.parquet as pq

    rows = pq.read_table(path).to_pylist()
    out = []
    for r in rows:
        # absent lists are written empty (older files: null); both read as None
        failed = r.get("error") is not None
        control = r.pop("control")
        r["control_points"] = (
            None if failed or control is None else np.array(control, dtype=np.float64)
        )
        r["knots"] = np.array(r["knots"], dtype=np.float64) if r["knots"] else None
        r["weights"] = np.array(r["weights"], dtype=np.float64) if r["weights"] else None
        out.append(r)
    return out
