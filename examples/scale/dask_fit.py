"""The trajectory fit on Dask distributed: one task per Parquet file, each a single batch call
(see trajectories.py). Give a scheduler address to run on a cluster, or --workers N for a
LocalCluster of N single-threaded worker processes on this machine.

    python examples/scale/dask_fit.py DATA_DIR OUT_DIR --workers 2
    python examples/scale/dask_fit.py DATA_DIR OUT_DIR --scheduler tcp://scheduler:8786

The input and output directories must be visible to every worker (a shared file system or an
object store path that pyarrow reads).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from dask.distributed import Client, LocalCluster

sys.path.insert(0, str(Path(__file__).resolve().parent))
import trajectories  # noqa: E402


def run(client: Client, data_dir: str, out_dir: str, threads_per_task: int = 1) -> tuple[int, float]:
    """Fits every file on the cluster; returns (trajectories, seconds)."""
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    files = trajectories.input_files(data_dir)
    t0 = time.perf_counter()
    futures = client.map(
        trajectories.fit_file,
        files,
        [str(Path(out_dir) / Path(f).name) for f in files],
        threads=threads_per_task,
        pure=False,
    )
    n = sum(client.gather(futures))
    return n, time.perf_counter() - t0


def local_client(workers: int) -> Client:
    # one single-threaded process per worker; each task runs lekalo on one thread, so N workers
    # use N processors
    cluster = LocalCluster(
        n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    )
    return Client(cluster)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("data_dir")
    ap.add_argument("out_dir")
    ap.add_argument("--scheduler", help="address of a running scheduler (tcp://host:8786)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster workers when no scheduler is given")
    a = ap.parse_args()
    client = Client(a.scheduler) if a.scheduler else local_client(a.workers)
    with client:
        client.upload_file(str(Path(__file__).resolve().parent / "trajectories.py"))
        n, dt = run(client, a.data_dir, a.out_dir)
    print(f"dask: {n} trajectories in {dt:.2f} s: {n / dt:,.0f} trajectories/s")


if __name__ == "__main__":
    main()
