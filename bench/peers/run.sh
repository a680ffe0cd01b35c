#!/usr/bin/env bash
# Peer comparison in one run: lekalo against SciPy, tinyspline, geomdl, bezier and Open CASCADE
# (OCP) on the same data. Creates bench/peers/.venv on first use (PyPI: numpy, scipy, and
# whichever of the optional peers install here), writes the workload data with our example
# `peer_bench` (target/peers-data/*.bin, little-endian f64) and times lekalo there once, then
# peers.py times the peers on the same files, workload by workload, each between two more
# timings of lekalo on that workload, and prints ours (the mean of those two medians), theirs
# and the ratio with agreement checks.
#
# Workloads: cubic B-spline evaluation (10^6 parameters); cubic curve interpolation through
# 10^3..10^6 3-D points; bicubic surface interpolation of 100^2..400^2 grids; Bezier degree
# elevation 10 -> 20 and 50 -> 100. Slow peers run on subsets (tinyspline and OCP evaluation on
# 10^5 parameters, geomdl on 10^4; the OCP array fill is timed once above 10^4 points).
#
# Open CASCADE is timed twice: through its Python binding OCP (PyPI's cadquery-ocp), as a Python
# user meets it, and in C++ by bench/peers/occt_bench.cpp, which is built here when OCCT's headers
# and libraries are installed (Debian: apt-get install libocct-modeling-algorithms-dev
# libocct-modeling-data-dev; elsewhere set OCCT_INCLUDE and OCCT_LIB) and skipped otherwise.
#
# Usage: bench/peers/run.sh [REPEATS]     (default 7 repeats per measurement; ~1-2 minutes
#                                          after the build and the first-time venv, plus 1-3
#                                          minutes a repeat for Open CASCADE's query side)
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

# Large NumPy arrays are backed by transparent huge pages: NumPy madvise()s every allocation of
# 4 MiB and more (numpy._core.multiarray._get_madvise_hugepage(), on by default on Linux; the
# peers' output prints it). lekalo gives the same hint for its own large result buffers
# (crates/lekalo/src/numeric/large_buffer.rs), so both pay alike for first touching fresh memory (about
# 2 us a 4 KiB page on a VM otherwise), with no environment settings.
cargo build --quiet --release -p lekalo --example peer_bench
target/release/examples/peer_bench "$data" "$repeats"

occt_include=${OCCT_INCLUDE:-/usr/include/opencascade}
# occt_build NAME HEADER LIBS...: builds bench/peers/NAME.cpp into target/peers-occt/NAME when
# HEADER is installed; otherwise (or if it does not build) says why and how, and fails
occt_build() {
  local name=$1 header=$2
  shift 2
  if ! [ -f "$occt_include/$header" ] || ! command -v g++ >/dev/null; then
    echo "peers: no Open CASCADE headers in $occt_include (Debian: apt-get install" \
      "libocct-modeling-algorithms-dev libocct-modeling-data-dev); $name skipped" >&2
    return 1
  fi
  mkdir -p target/peers-occt
  local occt_lib=()
  if [ -n "${OCCT_LIB:-}" ]; then occt_lib=(-L"$OCCT_LIB" -Wl,-rpath,"$OCCT_LIB"); fi
  g++ -O2 -std=c++17 -Wno-deprecated-declarations -I"$occt_include" \
    "bench/peers/$name.cpp" -o "target/peers-occt/$name" "${occt_lib[@]}" "$@" || {
    echo "peers: $name.cpp did not build against $occt_include; $name skipped" >&2
    return 1
  }
}
occt_bench=()
if occt_build occt_bench GeomAPI_Interpolate.hxx \
    -lTKGeomAlgo -lTKGeomBase -lTKG3d -lTKG2d -lTKMath -lTKernel; then
  occt_bench=(target/peers-occt/occt_bench)
fi

# peers.py times lekalo again just before and just after each workload's peers: the ratios use
# the mean of the two, so that a slow spell of the shared machine does not fall on one side only
"$venv/bin/python" bench/peers/peers.py "$data" "$repeats" target/release/examples/peer_bench \
  "${occt_bench[@]}"

# The geometric queries (crates/lekalo/benches/query.rs) against Open CASCADE in C++:
# bench/peers/occt_queries.cpp times projection, arc length, parameter at length, intersection and
# meshing on the same objects (and counts the mesh's triangles). It needs the same headers and, for meshing, TKMesh, TKTopAlgo and
# TKBRep (Debian: apt-get install libocct-modeling-algorithms-dev libocct-modeling-data-dev);
# without them it is skipped with a note. Compare with `cargo bench -p lekalo --bench query`.
# examples/query_peer.rs prints lekalo's side of the same workloads in the same line format just
# before and just after, on one thread and on all (ratio = Open CASCADE's seconds / lekalo's; the
# mesh lines carry both triangle counts). Open CASCADE projects OCCT_QUERY_POINTS points (default
# 1,000: it takes milliseconds a point) and as many parameter-at-length queries; compare per
# query. compare_queries.py then checks the answers: projections point by point, intersections;
# occt_mesh_deviation.py measures Open CASCADE's mesh against the surface (a few minutes).
occt_queries=()
if occt_build occt_queries GeomAPI_ProjectPointOnCurve.hxx -lTKMesh -lTKTopAlgo -lTKBRep \
    -lTKGeomAlgo -lTKGeomBase -lTKG3d -lTKG2d -lTKMath -lTKernel; then
  occt_queries=(target/peers-occt/occt_queries)
  cargo build --quiet --release -p lekalo --example query_peer
  answers=target/peers-occt/answers
  mkdir -p "$answers"
  uptime
  RAYON_NUM_THREADS=1 target/release/examples/query_peer "$repeats" | sed 's/^lekalo /lekalo-1-thread /'
  target/release/examples/query_peer "$repeats" 100000 "$answers"
  target/peers-occt/occt_queries "$repeats" "${OCCT_QUERY_POINTS:-1000}" "$answers"
  target/release/examples/query_peer "$repeats" | sed 's/^lekalo /lekalo-after /'
  # surface-surface intersection: query_peer writes the surfaces' nets for occt_queries, which
  # measures both sides' points with GeomAPI_ProjectPointOnSurf; lekalo's second run measures
  # Open CASCADE's points with the exact distances (docs/performance/queries.md)
  target/release/examples/query_peer ssi "$repeats" "$answers"
  target/peers-occt/occt_queries ssi "$repeats" "$answers"
  target/release/examples/query_peer ssi "$repeats" "$answers" | sed 's/^lekalo /lekalo-after /'
  uptime
  python3 bench/peers/compare_queries.py "$answers"
  # the true deviation of Open CASCADE's mesh (the face occt_queries wrote to $answers), and
  # lekalo's triangle count at the deviation that mesh reaches (the release CLI)
  cargo build --quiet --release -p lekalo-cli
  "$venv/bin/python" bench/peers/occt_mesh_deviation.py --brep "$answers/occt_mesh.brep" \
    --lekalo target/release/lekalo
fi

# Curve-curve intersection on the exact-answer suite (crates/lekalo/tests/data/intersect_exact.json),
# side by side: lekalo (examples/intersect_exact_peer.rs, before and after the peers), bezier's
# geometric and algebraic strategies, and Open CASCADE's Geom2dAPI_InterCurveCurve in C++
# (occt_queries exact, when it was built above); each case checked against the exact answers
# (which peer passes which case) and timed (docs/performance/queries.md)
cargo build --quiet --release -p lekalo --example intersect_exact_peer
uptime
"$venv/bin/python" bench/peers/intersect_exact_peers.py "$repeats" \
  target/release/examples/intersect_exact_peer "${occt_queries[@]}"
