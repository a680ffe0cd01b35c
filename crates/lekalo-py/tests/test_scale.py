"""The scale examples (examples/scale) at a small size: Parquet in and out, one process, Dask
distributed on a LocalCluster, Spark on local[2]."""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "scale"
sys.path.insert(0, str(EXAMPLES))

import trajectories  # noqa: E402

N = 3000


@pytest.fixture(scope="module")
def data_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("traj")
    trajectories.make_dataset(str(d), N, files=4, seed=5)
    return str(d)


def test_one_process(data_dir, tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    n = sum(trajectories.fit_file(p, str(out / Path(p).name)) for p in trajectories.input_files(data_dir))
    assert n == N
    assert trajectories.check_output(data_dir, str(out)) == N


def test_dask_local_cluster(data_dir, tmp_path):
    pytest.importorskip("dask.distributed")
    import dask_fit

    with dask_fit.local_client(2) as client:
        client.upload_file(str(EXAMPLES / "trajectories.py"))
        n, _ = dask_fit.run(client, data_dir, str(tmp_path / "out"))
    assert n == N
    assert trajectories.check_output(data_dir, str(tmp_path / "out")) == N


def test_spark_local(data_dir, tmp_path):
    pytest.importorskip("pyspark")
    java = shutil.which("java")
    if java is None:
        pytest.skip("Spark needs Java (a JDK 17 or newer on PATH); none found, so the Spark example is not run")
    probe = subprocess.run([java, "-version"], capture_output=True, text=True)
    if probe.returncode != 0:
        pytest.skip(f"Spark needs a working Java; `java -version` failed: {probe.stderr.strip()[:200]}")
    import spark_fit

    spark = spark_fit.session("local[2]")
    try:
        n, _ = spark_fit.run(spark, data_dir, str(tmp_path / "out"))
    finally:
        spark.stop()
    assert n == N
    assert trajectories.check_output(data_dir, str(tmp_path / "out")) == N


def test_batch_matches_per_row(data_dir):
    import pyarrow.parquet as pq

    import lekalo

    table = pq.read_table(trajectories.input_files(data_dir)[0]).slice(0, 50)
    out = trajectories.fit_table(table)
    for r in (0, 49):
        pts = np.column_stack([np.asarray(table.column(a)[r].values) for a in "xyz"])
        c = lekalo.interpolate(pts, 3)
        assert np.array_equal(np.asarray(out.column("knots")[r].values), c.knots)
        assert np.array_equal(np.asarray(out.column("control")[r].values), c.control.reshape(-1))
