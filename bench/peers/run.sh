#!/usr/bin/env bash
# Peer comparison in one run: lekalo against SciPy, tinyspline, geomdl and Open CASCADE (OCP)
# on the same data. Creates bench/peers/.venv on first use (PyPI: numpy, scipy, and whichever of
# the optional peers install here), writes the workload data with our example `peer_bench`
# (target/peers-data/*.bin, little-endian f64), times lekalo there, then times the peers on the
# same files and prints ours, theirs and the ratio (medians).
#
# Usage: bench/peers/run.sh [REPEATS]     (default 7 repeats per measurement; ~2-3 minutes)
set -euo pipefail
cd "$(dirname "$0")/../.."
repeats=${1:-7}
venv=bench/peers/.venv
data=target/peers-data

if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
pip=("$venv/bin/pip" install --quiet --disable-pip-version-check)
"${pip[@]}" numpy scipy
for pkg in tinyspline geomdl bezier cadquery-ocp; do
  "${pip[@]}" "$pkg" || echo "peers: $pkg is not installable here; skipped" >&2
done

cargo run --quiet --release --example peer_bench -- "$data" "$repeats"
"$venv/bin/python" bench/peers/peers.py "$data" "$repeats"
