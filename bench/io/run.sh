#!/usr/bin/env bash
# Data in and out, side by side in one run: lekalo's text, NumPy and Parquet paths against
# pandas.read_csv, numpy.loadtxt, numpy.savetxt and pandas.DataFrame.to_csv on the same files.
# Creates target/io-venv on first use (PyPI: numpy, pandas, pyarrow) and the data under
# target/io-data (a 3-D helix of 10^6 points as CSV and .npy).
#
# Usage: bench/io/run.sh [REPEATS]     (default 5; best of the repeats is reported)
set -euo pipefail
cd "$(dirname "$0")/../.."
repeats=${1:-5}
venv=target/io-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -c 'import numpy, pandas, pyarrow' 2>/dev/null ||
  "$venv/bin/pip" install --quiet numpy pandas pyarrow
cargo build --release --quiet -p lekalo-cli
cargo build --release --quiet -p lekalo-io --example text_throughput
"$venv/bin/python" bench/io/io_bench.py --repeats "$repeats" --data target/io-data \
  --lekalo target/release/lekalo --throughput target/release/examples/text_throughput
