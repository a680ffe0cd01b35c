"""Fit a cubic B-spline to each trajectory of a Parquet data set, and write each curve's knots
and control points back to Parquet. The fitting of one file (or one Arrow table) is
``fit_table``: a single call of ``lekalo.interpolate_batch`` on the flat coordinates and the
list offsets that Arrow already stores, so no Python object is made per trajectory.

Input: Parquet files with one row per trajectory: ``id`` (int64) and ``x``, ``y``, ``z``
(list<double>, one entry per sample). Output: ``id``, ``degree`` (int32), ``knots``
(list<double>) and ``control`` (list<double>, x0 y0 z0 x1 ...).

    python examples/scale/trajectories.py make DATA_DIR --trajectories 1000000 --files 16
    python examples/scale/trajectories.py fit DATA_DIR OUT_DIR            # one process
    python examples/scale/dask_fit.py DATA_DIR OUT_DIR --workers 2        # Dask
    python examples/scale/spark_fit.py DATA_DIR OUT_DIR --master local[2] # Spark
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

import lekalo

DEGREE = 3


def make_table(n: int, seed: int, first_id: int = 0, min_len: int = 20, max_len: int = 120) -> pa.Table:
    """``n`` random smooth 3-D trajectories (random walks in velocity) of random lengths."""
    rng = np.random.default_rng(seed)
    lengths = rng.integers(min_len, max_len + 1, n)
    offsets = lekalo.ragged_offsets(lengths)
    total = int(offsets[-1])
    vel = rng.standard_normal((total, 3)).cumsum(axis=0) * 0.05 + rng.standard_normal((total, 3)) * 0.01
    vel += 1.0  # keep consecutive samples apart
    start = np.repeat(offsets[:-1], lengths)
    csum = np.cumsum(vel, axis=0)
    base = np.where(start[:, None] > 0, csum[np.maximum(start - 1, 0)], 0.0)
    pos = csum - base
    off32 = pa.array(offsets.astype(np.int32))
    cols = {
        "id": pa.array(np.arange(first_id, first_id + n, dtype=np.int64)),
        **{a: pa.ListArray.from_arrays(off32, pa.array(pos[:, k])) for k, a in enumerate("xyz")},
    }
    return pa.table(cols)


def table_points(table: pa.Table):
    """Flat ``(total, 3)`` points and int64 offsets from the list columns (one copy, to the
    point-major layout)."""
    cols = [table.column(a).combine_chunks() for a in "xyz"]
    offsets = np.asarray(cols[0].offsets, dtype=np.int64)
    base = offsets[0]
    offsets = offsets - base
    vals = [np.asarray(c.values)[base:base + offsets[-1]] for c in cols]
    return np.column_stack(vals), offsets


def fit_arrays(points: np.ndarray, offsets: np.ndarray, threads: int | None = None) -> dict:
    """The batch fit: one call for all trajectories."""
    return lekalo.interpolate_batch(points, offsets, DEGREE, threads=threads)


def curves_table(ids: pa.Array, batch: dict) -> pa.Table:
    """The fitted curves as an Arrow table (lists share the batch's flat arrays)."""
    ko = pa.array(batch["knot_offsets"].astype(np.int32))
    co = pa.array((batch["control_offsets"] * 3).astype(np.int32))
    return pa.table(
        {
            "id": ids,
            "degree": pa.array(np.full(len(ids), batch["degree"], dtype=np.int32)),
            "knots": pa.ListArray.from_arrays(ko, pa.array(batch["knots"])),
            "control": pa.ListArray.from_arrays(co, pa.array(batch["control"].reshape(-1))),
        }
    )


def fit_table(table: pa.Table, threads: int | None = None) -> pa.Table:
    points, offsets = table_points(table)
    return curves_table(table.column("id").combine_chunks(), fit_arrays(points, offsets, threads))


def fit_file(src: str, dst: str, threads: int | None = None) -> int:
    """Fits every trajectory of one Parquet file into ``dst``; returns the count. The output
    is written to a temporary name and renamed, so a file is never half-written. ``threads``
    bounds the task's processors: the fit's, and with ``threads=1`` the Parquet reader's too
    (pyarrow decodes columns on its own thread pool otherwise), so that one single-threaded
    engine worker keeps to one processor and N workers scale to N."""
    table = pq.read_table(src, use_threads=threads is None or threads > 1)
    out = fit_table(table, threads)
    tmp = dst + ".tmp"
    # no dictionary encoding: knots and control points are distinct floats, for which building
    # a dictionary (and then giving it up) took half the time of the write and saved nothing
    pq.write_table(out, tmp, use_dictionary=False)
    os.replace(tmp, dst)
    return table.num_rows


def make_dataset(directory: str, n: int, files: int, seed: int = 0) -> list[str]:
    Path(directory).mkdir(parents=True, exist_ok=True)
    per = -(-n // files)
    paths = []
    for f in range(files):
        k = min(per, n - f * per)
        if k <= 0:
            break
        p = str(Path(directory) / f"part-{f:04d}.parquet")
        pq.write_table(make_table(k, seed + f, first_id=f * per), p)
        paths.append(p)
    return paths


def input_files(directory: str) -> list[str]:
    return sorted(str(p) for p in Path(directory).glob("*.parquet"))


def check_output(data_dir: str, out_dir: str, sample: int = 5) -> int:
    """Checks that every trajectory has a curve and that sampled curves pass through their
    points; returns the number of curves."""
    src = pq.read_table(data_dir).sort_by("id")
    out = pq.read_table(out_dir).sort_by("id")
    assert src.num_rows == out.num_rows, (src.num_rows, out.num_rows)
    assert np.array_equal(np.asarray(src.column("id")), np.asarray(out.column("id")))
    rows = np.linspace(0, src.num_rows - 1, sample).astype(int)
    for r in rows:
        pts = np.column_stack([np.asarray(src.column(a)[int(r)].values) for a in "xyz"])
        knots = np.asarray(out.column("knots")[int(r)].values)
        ctrl = np.asarray(out.column("control")[int(r)].values).reshape(-1, 3)
        c = lekalo.BSplineCurve(int(out.column("degree")[int(r)].as_py()), knots, ctrl)
        err = np.abs(c(lekalo.parametrize(pts)) - pts).max()
        assert err <= 1e-9 * max(1.0, np.abs(pts).max()), (r, err)
    return out.num_rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("make", help="write a synthetic data set")
    m.add_argument("data_dir")
    m.add_argument("--trajectories", type=int, default=1_000_000)
    m.add_argument("--files", type=int, default=16)
    f = sub.add_parser("fit", help="fit every file in this process")
    f.add_argument("data_dir")
    f.add_argument("out_dir")
    f.add_argument("--threads", type=int, default=None)
    a = ap.parse_args()
    if a.cmd == "make":
        make_dataset(a.data_dir, a.trajectories, a.files)
        return
    Path(a.out_dir).mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    n = sum(fit_file(p, str(Path(a.out_dir) / Path(p).name), a.threads) for p in input_files(a.data_dir))
    dt = time.perf_counter() - t0
    print(f"{n} trajectories in {dt:.2f} s: {n / dt:,.0f} trajectories/s")


if __name__ == "__main__":
    main()
