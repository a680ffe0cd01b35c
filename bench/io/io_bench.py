"""Times lekalo's file paths and the Python peers on the same data; see bench/io/run.sh.

Each figure is the best of --repeats runs (wall time, the whole command for the CLI rows).
"""

import argparse
import os
import subprocess
import time

import numpy as np
import pandas as pd


def best(repeats, f):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def run(*cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def throughput(tool, *args):
    out = subprocess.run([tool, *args], check=True, capture_output=True, text=True).stdout
    # "... in S s: R MB/s"
    secs = float(out.split(" in ")[1].split(" s")[0])
    return secs, out.strip()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--data", required=True)
    ap.add_argument("--lekalo", required=True)
    ap.add_argument("--throughput", required=True)
    a = ap.parse_args()
    os.makedirs(a.data, exist_ok=True)
    n = 10**6
    t = np.arange(n) * 1e-3
    pts = np.column_stack([np.cos(t), np.sin(t), t / 10])
    csv = os.path.join(a.data, "helix1m.csv")
    npy = os.path.join(a.data, "helix1m.npy")
    if not os.path.exists(csv):
        with open(csv, "w") as f:
            f.write("x,y,z\n")
            f.write("\n".join(f"{x!r},{y!r},{z!r}" for x, y, z in pts.tolist()))
            f.write("\n")
    np.save(npy, pts)
    mb = os.path.getsize(csv) / 1e6
    out = os.path.join(a.data, "out")
    os.makedirs(out, exist_ok=True)
    rows = []

    def row(what, secs, note=""):
        rows.append((what, secs, note))
        print(f"{what:58s} {secs:8.3f} s  {note}", flush=True)

    print(f"data: {csv} ({mb:.1f} MB, {n} 3-D points); best of {a.repeats}")
    row(
        "lekalo interpolate helix1m.csv -o curve.json",
        best(a.repeats, lambda: run(a.lekalo, "interpolate", csv, "-o", f"{out}/curve.json")),
    )
    row(
        "lekalo interpolate helix1m.npy -o curve.npz",
        best(a.repeats, lambda: run(a.lekalo, "interpolate", npy, "-o", f"{out}/curve.npz")),
    )
    row(
        "lekalo eval curve.json --samples 1000000 -o samples.csv",
        best(
            a.repeats,
            lambda: run(
                a.lekalo, "eval", f"{out}/curve.json", "--samples", "1000000", "-o", f"{out}/s.csv"
            ),
        ),
    )
    secs, text = throughput(a.throughput, "read", csv, str(a.repeats))
    row("CSV read: lekalo read_points", secs, f"{mb / secs:.0f} MB/s")
    secs = best(a.repeats, lambda: pd.read_csv(csv, dtype=np.float64).to_numpy())
    row("CSV read: pandas.read_csv", secs, f"{mb / secs:.0f} MB/s")
    secs = best(max(1, a.repeats // 3), lambda: np.loadtxt(csv, delimiter=",", skiprows=1))
    row("CSV read: numpy.loadtxt", secs, f"{mb / secs:.0f} MB/s")
    w = f"{out}/written.csv"
    secs, text = throughput(a.throughput, "write", w, str(n), str(a.repeats))
    wmb = os.path.getsize(w) / 1e6
    row("CSV write: lekalo SampleTable::write_csv (t,x,y,z)", secs, f"{wmb / secs:.0f} MB/s")
    table = np.column_stack([t, pts])
    w2 = f"{out}/savetxt.csv"
    secs = best(
        max(1, a.repeats // 3),
        lambda: np.savetxt(w2, table, fmt="%.17g", delimiter=",", header="t,x,y,z", comments=""),
    )
    row("CSV write: numpy.savetxt %.17g", secs, f"{os.path.getsize(w2) / 1e6 / secs:.0f} MB/s")
    frame = pd.DataFrame(table, columns=["t", "x", "y", "z"])
    w3 = f"{out}/pandas.csv"
    secs = best(max(1, a.repeats // 3), lambda: frame.to_csv(w3, index=False))
    row("CSV write: pandas.DataFrame.to_csv", secs, f"{os.path.getsize(w3) / 1e6 / secs:.0f} MB/s")
    # the written text reads back to the same numbers
    back = pd.read_csv(w, dtype=np.float64).to_numpy()
    assert np.array_equal(back, table), "lekalo's CSV does not read back exactly"
    batches(a, out, row)


def batches(a, out, row):
    """20,000 curves x 100 points: interpolated and evaluated Parquet to Parquet, against the
    same curves evaluated as JSON Lines (100 samples each)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    groups, per = 20_000, 100
    pts = os.path.join(a.data, "groups.parquet")
    if not os.path.exists(pts):
        g = np.repeat(np.arange(groups, dtype=np.int64), per)
        s = np.tile(np.linspace(0, 1, per), groups)
        phase = np.repeat(np.arange(groups) * 1e-3, per)
        table = pa.table(
            {"group": g, "x": np.cos(3 * s + phase), "y": np.sin(2 * s + phase), "z": s + phase}
        )
        pq.write_table(table, pts, row_group_size=1 << 20)
    curves = f"{out}/curves.parquet"
    jsonl = f"{out}/curves.jsonl"
    t_int = best(a.repeats, lambda: run(a.lekalo, "interpolate", pts, "-o", curves))
    row("batch: interpolate groups.parquet -> curves.parquet", t_int)
    t_eval = best(
        a.repeats,
        lambda: run(a.lekalo, "eval", curves, "--samples", str(per), "-o", f"{out}/s.parquet"),
    )
    row("batch: eval curves.parquet --samples 100 -> parquet", t_eval)
    t_fused = best(
        a.repeats,
        lambda: run(a.lekalo, "interpolate", pts, "--samples", str(per), "-o", f"{out}/f.parquet"),
    )
    row("batch: interpolate groups.parquet --samples 100 -> parquet (one pass)", t_fused)
    run(a.lekalo, "convert", curves, "-o", jsonl, "--force")
    t_jsonl = best(
        a.repeats,
        lambda: run(a.lekalo, "eval", jsonl, "--samples", str(per), "-o", f"{out}/s.jsonl"),
    )
    row("batch: eval curves.jsonl --samples 100 -> jsonl", t_jsonl)
    row(
        "batch: Parquet interpolate + eval vs JSON Lines eval",
        t_int + t_eval,
        f"{t_jsonl / (t_int + t_eval):.1f}x faster",
    )
    row(
        "batch: Parquet interpolate --samples (one pass) vs JSON Lines eval",
        t_fused,
        f"{t_jsonl / t_fused:.1f}x faster",
    )


if __name__ == "__main__":
    main()
