"""The trajectory fit on Spark: ``mapInPandas`` hands each task batches of rows as pandas
DataFrames; each batch is one call of ``lekalo.interpolate_batch``.

    python examples/scale/spark_fit.py DATA_DIR OUT_DIR --master local[2]
    spark-submit --py-files examples/scale/trajectories.py examples/scale/spark_fit.py DATA_DIR OUT_DIR

On a cluster, install the package on every executor (pip install ./crates/lekalo-py, or a
wheel built with maturin) and give paths every executor can read.
"""

from __future__ import annotations

import argparse
import time
from typing import Iterator

import numpy as np
import pandas as pd

DEGREE = 3
SCHEMA = "id long, degree int, knots array<double>, control array<double>"


def fit_batches(frames: Iterator[pd.DataFrame]) -> Iterator[pd.DataFrame]:
    """mapInPandas function: list columns x, y, z -> one curve per row."""
    import lekalo

    for df in frames:
        if len(df) == 0:
            continue
        lengths = df["x"].map(len).to_numpy()
        offsets = lekalo.ragged_offsets(lengths)
        points = np.column_stack([np.concatenate(df[a].to_numpy()) for a in "xyz"])
        b = lekalo.interpolate_batch(points, offsets, DEGREE, threads=1)
        ko, co = b["knot_offsets"], b["control_offsets"]
        flat = b["control"].reshape(-1)
        yield pd.DataFrame(
            {
                "id": df["id"].to_numpy(),
                "degree": np.full(len(df), DEGREE, dtype=np.int32),
                "knots": [b["knots"][ko[i]:ko[i + 1]] for i in range(len(df))],
                "control": [flat[3 * co[i]:3 * co[i + 1]] for i in range(len(df))],
            }
        )


def run(spark, data_dir: str, out_dir: str) -> tuple[int, float]:
    t0 = time.perf_counter()
    df = spark.read.parquet(data_dir)
    out = df.mapInPandas(fit_batches, SCHEMA)
    out.write.mode("overwrite").parquet(out_dir)
    n = spark.read.parquet(out_dir).count()
    return n, time.perf_counter() - t0


def session(master: str):
    """A session on `master`; for local masters the driver binds to the loopback address. The
    Python workers run this interpreter, and this file is shipped to them (fit_batches is
    pickled by reference to it)."""
    import os
    import sys

    from pyspark.sql import SparkSession

    os.environ.setdefault("PYSPARK_PYTHON", sys.executable)
    b = (
        SparkSession.builder.master(master)
        .appName("lekalo-trajectories")
        .config("spark.sql.execution.arrow.maxRecordsPerBatch", "20000")
        .config("spark.ui.enabled", "false")
    )
    if master.startswith("local"):
        b = b.config("spark.driver.host", "127.0.0.1").config("spark.driver.bindAddress", "127.0.0.1")
    spark = b.getOrCreate()
    spark.sparkContext.addPyFile(os.path.abspath(__file__))
    return spark


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("data_dir")
    ap.add_argument("out_dir")
    ap.add_argument("--master", default=None, help="e.g. local[2]; default: spark-submit's")
    a = ap.parse_args()
    spark = session(a.master) if a.master else __import__("pyspark.sql").sql.SparkSession.builder.getOrCreate()
    n, dt = run(spark, a.data_dir, a.out_dir)
    print(f"spark: {n} trajectories in {dt:.2f} s: {n / dt:,.0f} trajectories/s")
    spark.stop()


if __name__ == "__main__":
    main()
