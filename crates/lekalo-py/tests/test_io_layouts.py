"""The NPZ and Parquet layouts of docs/formats.md from Python, and the same curves as the
library's: the command-line tool's Parquet output read by pyarrow, pandas and DuckDB with no
help (the ``lekalo`` binary: ``LEKALO_BIN``, the PATH, or the workspace's own build)."""

import os
import shutil
import subprocess
from pathlib import Path

import duckdb
import numpy as np
import pandas as pd
import pytest

import lekalo
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
    if not exe:
        # the workspace's build (scripts/test.sh runs cargo test, which builds it, first)
        root = Path(__file__).resolve().parents[3]
        built = [root / "target" / p / "lekalo" for p in ("debug", "release")]
        built = [b for b in built if b.exists()]
        exe = str(max(built, key=lambda b: b.stat().st_mtime)) if built else None
    assert exe and os.path.exists(exe), (
        "no lekalo binary: build it (cargo build -p lekalo-cli) or set LEKALO_BIN"
    )
    return exe


def test_parquet_batch_through_the_cli(tmp_path):
    exe = _binary()
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


def _groups():
    """Four 3-D point sets of different sizes, keyed 10, 11, 12, 13."""
    rng = np.random.default_rng(7)
    out = {}
    for k, n in zip(range(10, 14), (5, 9, 17, 40)):
        t = np.sort(rng.random(n)) * 3
        out[k] = np.column_stack([np.cos(t * k), np.sin(t), t + rng.random(n) * 1e-3])
    return out


def test_duckdb_and_pandas_read_the_curves_and_samples(tmp_path):
    exe = _binary()
    groups = _groups()
    pts = tmp_path / "pts.parquet"
    io.write_points_parquet(str(pts), groups)
    curves, samples = tmp_path / "curves.parquet", tmp_path / "samples.parquet"
    subprocess.run([exe, "interpolate", str(pts), "-o", str(curves)], check=True)
    subprocess.run([exe, "eval", str(curves), "--samples", "9", "-o", str(samples)], check=True)
    lib = {k: lekalo.interpolate(p) for k, p in groups.items()}

    frame = pd.read_parquet(curves)
    assert list(frame["group"]) == sorted(groups)
    for r in frame.itertuples():
        c = lib[r.group]
        assert r.type == "bspline_curve" and r.degree == c.degree and r.dim == 3
        assert pd.isna(r.error) and len(r.weights) == 0
        assert np.array_equal(np.asarray(r.knots), c.knots)
        assert np.array_equal(np.stack(r.control), c.control)

    con = duckdb.connect()
    rows = con.execute(
        'SELECT "group", degree, knots, control, error FROM read_parquet(?) ORDER BY "group"',
        [str(curves)],
    ).fetchall()
    assert [r[0] for r in rows] == sorted(groups)
    for key, degree, knots, control, error in rows:
        c = lib[key]
        assert error is None and degree == c.degree
        assert np.array_equal(np.array(knots), c.knots)
        assert np.array_equal(np.array(control), c.control)

    s = con.execute(
        'SELECT "group", t, x, y, z FROM read_parquet(?) ORDER BY "group", t', [str(samples)]
    ).fetchnumpy()
    assert sorted(set(s["group"].tolist())) == sorted(groups)
    for key, c in lib.items():
        m = s["group"] == key
        t = s["t"][m]
        a, b = c.domain
        assert len(t) == 9 and t[0] == a and t[-1] == b
        got = np.column_stack([s["x"][m], s["y"][m], s["z"][m]])
        want = c(t)
        scale = np.abs(c.control).max()
        assert np.allclose(got, want, rtol=0, atol=1e-13 * scale), np.abs(got - want).max()
    assert pd.read_parquet(samples).shape == (9 * len(groups), 5)

    # the one pass (interpolate and sample, no curves file) writes the same samples, bit for bit
    fused = tmp_path / "fused.parquet"
    subprocess.run(
        [exe, "interpolate", str(pts), "--samples", "9", "-o", str(fused)], check=True
    )
    assert pd.read_parquet(fused).equals(pd.read_parquet(samples))


def test_the_npz_snippet_of_formats_md_runs_as_written(tmp_path, monkeypatch):
    # the first python block of docs/formats.md, in a folder holding curve.npz, as after
    # `lekalo convert curve.json -o curve.npz`; the file it writes reads back as its cubic
    import re

    doc = Path(__file__).resolve().parents[3] / "docs" / "formats.md"
    code = re.findall(r"^```python\n(.*?)^```", doc.read_text(encoding="utf-8"), re.S | re.M)[0]
    monkeypatch.chdir(tmp_path)
    io.save_npz_curve("curve.npz", 2, np.array([0, 0, 0, 1, 1, 1.0]), np.eye(3)[:, :2])
    exec(compile(code, "docs/formats.md, python block 1", "exec"), {})
    back = io.load_npz_curve("mine.npz")
    assert back["degree"] == 3 and len(back["control_points"]) == 5


def test_the_parquet_table_snippet_of_formats_md_runs_as_written(tmp_path, monkeypatch):
    # the python block of "Parquet tables": pandas writes a grid's values, the command line
    # interpolates them and evaluates the spline on a finer grid into a table pandas reads
    exe = _binary()
    doc = Path(__file__).resolve().parents[3] / "docs" / "formats.md"
    text = doc.read_text().split("### Parquet tables", 1)[1]
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("PATH", os.path.dirname(exe) + os.pathsep + os.environ["PATH"])
    scope = {}
    exec(compile(code, "docs/formats.md, Parquet tables", "exec"), scope)
    field, values = scope["field"], scope["values"]
    assert list(field.columns) == ["x1", "x2", "x3", "y"]
    assert len(field) == 11 * 9 * 7
    # the first direction slowest; the interpolant passes through the values at the nodes
    # (i/5, j/4, k/3), which the finer grid (i/10, j/8, k/6) holds
    y = field["y"].to_numpy().reshape(11, 9, 7)
    np.testing.assert_allclose(y[::2, ::2, ::2], values, rtol=0, atol=1e-12)
    # the parameters a + (b - a)·(k/(m - 1)), here k/10 to the bit
    x1 = field["x1"].to_numpy().reshape(11, 9, 7)
    assert np.array_equal(x1[:, 0, 0], np.arange(11) / 10)


def test_parquet_tables_written_by_pandas(tmp_path):
    # integer, float32 and float64 columns; evaluation points and scattered rows; the errors
    # of a null and a non-finite number name the row and the column
    exe = _binary()
    rng = np.random.default_rng(5)
    values = rng.random((5, 4, 4))
    grid = tmp_path / "grid.parquet"
    pd.DataFrame({"f": values.ravel()}).to_parquet(grid)
    npy = tmp_path / "grid.npy"
    np.save(npy, values)
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    subprocess.run([exe, "interpolate", str(grid), "--grid", "5x4x4", "-o", str(a)], check=True)
    subprocess.run([exe, "interpolate", str(npy), "--grid", "5x4x4", "-o", str(b)], check=True)
    assert a.read_text() == b.read_text()
    at = pd.DataFrame(
        {
            "i": np.array([0, 1, 1], dtype=np.int32),
            "h": np.array([0.5, 0.25, 1], dtype=np.float32),
            "d": [0.125, 0.75, 0.5],
        }
    )
    at.to_parquet(tmp_path / "at.parquet")
    got = subprocess.run(
        [exe, "eval", str(a), "--at-file", str(tmp_path / "at.parquet"), "--json"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    want = subprocess.run(
        [exe, "eval", str(a), "--at", "0,0.5,0.125,1,0.25,0.75,1,1,0.5", "--json"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    assert got == want
    # scattered rows x1, x2, x3, y from a table
    pts = rng.random((400, 3))
    rows = pd.DataFrame(pts, columns=["x", "y", "z"]).assign(v=pts.sum(axis=1))
    rows.to_parquet(tmp_path / "rows.parquet")
    fitted = tmp_path / "fitted.json"
    subprocess.run(
        [exe, "fit", str(tmp_path / "rows.parquet"), "--scattered", "--degree", "1",
         "--ctrl-grid", "2x2x2", "--bbox", "0:1,0:1,0:1", "-o", str(fitted)],
        check=True,
    )
    out = subprocess.run(
        [exe, "eval", str(fitted), "--at", "0.3,0.4,0.5", "--json"],
        check=True, capture_output=True, text=True,
    ).stdout
    import json

    assert abs(json.loads(out)["rows"][0][3] - 1.2) < 1e-12
    # a null and a non-finite number
    bad = pd.DataFrame({"x": [0.5, None, 0.5], "y": [0.5, 0.5, 0.5], "z": [0.1, 0.2, 0.3]})
    bad.to_parquet(tmp_path / "null.parquet")
    r = subprocess.run(
        [exe, "eval", str(a), "--at-file", str(tmp_path / "null.parquet")],
        capture_output=True, text=True,
    )
    assert r.returncode == 2
    assert "field `x`" in r.stderr and "row 2" in r.stderr, r.stderr
    nulls = pd.DataFrame({"x": pd.array([1, None, 0], dtype="Int64"), "y": [0.5] * 3, "z": [0.5] * 3})
    nulls.to_parquet(tmp_path / "int-null.parquet")
    r = subprocess.run(
        [exe, "eval", str(a), "--at-file", str(tmp_path / "int-null.parquet")],
        capture_output=True, text=True,
    )
    assert r.returncode == 2
    assert "row 2: null" in r.stderr, r.stderr
