"""How the trajectory fit of examples/scale grows from 1 to 2 workers, on Dask and on Spark.

    python bench/python/scale_bench.py [--trajectories 200000] [--files 8] [--repeats 2]
                                       [--engines dask,spark] [--keep DIR]

Generates the Parquet data once (examples/scale/trajectories.py), then times, for each engine,
one warm-up run and `--repeats` timed runs with 1 worker, then the same with 2 workers: Dask
`LocalCluster` with 1 or 2 single-threaded worker processes, Spark `local[1]` or `local[2]`. Every output is checked against
`lekalo.interpolate` on a sample (`check_output`). Prints the best time of each and the ratio
(best of 1 worker / best of 2 workers). Spark is skipped, saying why, when pyspark or Java is
missing. The figures belong in docs/scale.md with the machine's load at the time.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "scale"))
import trajectories  # noqa: E402


def timed_runs(engine, data, out, workers):
    """Runs of `engine` ("dask" or "spark") with `workers` workers: one warm-up (imports and
    the first task on every worker), then timed runs, each output checked."""
    if engine == "dask":
        import dask_fit

        client = dask_fit.local_client(workers)
        run, close = (lambda: dask_fit.run(client, data, out)), client.close
    else:
        import spark_fit

        spark = spark_fit.session(f"local[{workers}]")
        run, close = (lambda: spark_fit.run(spark, data, out)), spark.stop
    try:
        run()
        while True:
            n, dt = run()
            trajectories.check_output(data, out)
            yield n, dt
    finally:
        close()


def spark_missing():
    try:
        import pyspark  # noqa: F401
    except ImportError:
        return "pyspark is not installed"
    if shutil.which("java") is None:
        return "no java on PATH"
    return None


def measure(name, data, base, repeats):
    best = {}
    for workers in (1, 2):
        out = os.path.join(base, f"out-{name}-{workers}")
        gen = timed_runs(name, data, out, workers)
        times = []
        for _ in range(repeats):
            n, dt = next(gen)
            times.append(dt)
        gen.close()
        best[workers] = (n, min(times))
        print(f"{name} {workers} worker(s): {', '.join(f'{t:.2f}' for t in times)} s "
              f"(best {n / min(times):,.0f} trajectories/s)", flush=True)
    ratio = best[1][1] / best[2][1]
    print(f"{name}: 1 -> 2 workers {ratio:.2f}x", flush=True)
    return ratio


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--trajectories", type=int, default=200_000)
    ap.add_argument("--files", type=int, default=8)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--engines", default="dask,spark")
    ap.add_argument("--keep", help="folder for the data (kept); default a temporary one")
    a = ap.parse_args()
    base = a.keep or tempfile.mkdtemp(prefix="lekalo-scale-")
    data = os.path.join(base, "data")
    if not os.path.isdir(data):
        t0 = time.perf_counter()
        trajectories.make_dataset(data, a.trajectories, a.files)
        print(f"data: {a.trajectories} trajectories in {a.files} files ({time.perf_counter() - t0:.1f} s)")
    print(f"{os.cpu_count()} processors; load average {os.getloadavg()[0]:.1f}", flush=True)
    engines = a.engines.split(",")
    if "dask" in engines:
        measure("dask", data, base, a.repeats)
    if "spark" in engines:
        why = spark_missing()
        if why:
            print(f"spark: skipped ({why})")
        else:
            measure("spark", data, base, a.repeats)
    print(f"load average after: {os.getloadavg()[0]:.1f}")
    if not a.keep:
        shutil.rmtree(base, ignore_errors=True)


if __name__ == "__main__":
    main()
