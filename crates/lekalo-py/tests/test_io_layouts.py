"""The NPZ and Parquet layouts of docs/formats.md from Python, and the same curves as the
library's (when the ``lekalo`` binary and pyarrow are at hand)."""

import os
import shutil
import subprocess

import numpy as np
import pytest

from lekalo import io


def test_npz_round_trip_is_exact(tmp_path):
    knots = np.array([0, 0, 0, 0.1 + 0.2, 1, 1, 1], dtype=np.float64)
    ctrl = np.array([[0, 0], [1, 2], [2, 1 / 3], [3, 0]], dtype=np.float64)
    w = np.array([1, 0.5, 2, 1e-3])
    p = tmp_path / "c.npz"
    io.save_npz_curve(str(p), 2, knots, ctrl, w)
    c = io.load_npz_curve(str(p))
    assert c["degree"] == 2
    assert np.array_equal(c["knots"], knots) and np.array_equal(c["control_points"], ctrl)
    assert np.array_equal(c["weights"], w)
    io.save_npz_curve(str(p), 2, knots, ctrl)
    assert io.load_npz_curve(str(p))["weights"] is None


def _binary():
    exe = os.environ.get("LEKALO_BIN") or shutil.which("lekalo")
    return exe if exe and os.path.exists(exe) else None


def test_parquet_batch_through_the_cli(tmp_path):
    pytest.importorskip("pyarrow")
    exe = _binary()
    if exe is None:
        pytest.skip("no lekalo binary (set LEKALO_BIN)")
    t = np.linspace(0, 1, 6)
    groups = {k: np.column_stack([t + k, np.sin(t * (k + 1))]) for k in range(3)}
    pts = tmp_path / "pts.parquet"
    io.write_points_parquet(str(pts), groups)
    out = tmp_path / "curves.parquet"
    subprocess.run([exe, "interpolate", str(pts), "-o", str(out)], check=True)
    rows = io.read_curves_parquet(str(out))
    assert [r["group"] for r in rows] == [0, 1, 2]
    for r in rows:
        assert r["error"] is None and r["type"] == "bspline_curve"
        csv = tmp_path / "one.csv"
        csv.write_text("".join(f"{x!r},{y!r}\n" for x, y in groups[r["group"]].tolist()))
        npz = tmp_path / "one.npz"
        subprocess.run([exe, "interpolate", str(csv), "-o", str(npz)], check=True)
        one = io.load_npz_curve(str(npz))
        assert r["degree"] == one["degree"]
        assert np.array_equal(r["knots"], one["knots"])
        assert np.array_equal(r["control_points"], one["control_points"])
