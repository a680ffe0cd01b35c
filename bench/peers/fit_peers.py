#!/usr/bin/env python3
"""Fitting side by side with SciPy, same data, same run.

lekalo's example `fit_peer` writes the workloads of crates/lekalo/benches/fit.rs to DIR and times
itself (median of REPEATS); this script then times SciPy on the same files and prints both, the
ratio SciPy / lekalo and agreement checks:
- lsq: make_lsq_spline, 10^6 points, 1000 cubic control points;
- gcv: make_smoothing_spline with GCV (lam=None), 10^5 points;
- smooth_lam: make_smoothing_spline with lam given, 10^5 points;
- splrep: splrep(s=N sigma^2), 10^5 points: residual and knot count beside SciPy's;
- surface: LSQBivariateSpline, 10^5 scattered points, 30 x 30 cubic net.
- tolerance: Open CASCADE's GeomAPI_PointsToBSpline in C++ (bench/peers/occt_fit.cpp, built here
  with g++ when the headers are in /usr/include/opencascade or $OCCT_INCLUDE), 10^5 points, the
  same tolerance: time, control points and maximum distance side by side.

Usage: bench/peers/fit_peers.py [REPEATS] [--no-build]   (from the repository root; needs numpy and scipy:
python3 -m venv target/fitvenv && target/fitvenv/bin/pip install numpy scipy)
"""
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np
from scipy.interpolate import (LSQBivariateSpline, make_lsq_spline, make_smoothing_spline,
                               splrep)

DIR = "target/fit-peers"
repeats = int(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].isdigit() else 5


def load(name):
    return np.fromfile(f"{DIR}/{name}.bin", dtype="<f8")


def median_secs(fn, reps, warm=True):
    out = fn() if warm else None
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def lekalo_run():
    out = subprocess.run(["target/release/examples/fit_peer", DIR, str(repeats)],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


if "--no-build" not in sys.argv:
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "lekalo", "--example", "fit_peer"],
                   check=True)


before = lekalo_run()
print("lekalo (before):", json.dumps(before), flush=True)
rows = []

x, y, t = load("lsq_x"), load("lsq_y"), load("lsq_t")
secs, spl = median_secs(lambda: make_lsq_spline(x, y, t, 3), repeats)
c = load("lsq_c_lekalo")
rows.append(("lsq 10^6 / 1000 cubic", "make_lsq_spline", "lsq", secs,
             f"max |c - c_scipy| = {np.abs(c - spl.c).max():.2e}"))

xs, ys = load("smooth_x"), load("smooth_y")
secs, spl = median_secs(lambda: make_smoothing_spline(xs, ys, lam=1e-6), repeats)
rss = float(np.sum((spl(xs) - ys) ** 2))
rows.append(("smoothing lam=1e-6 10^5", "make_smoothing_spline(lam)", "smooth_lam", secs,
             f"RSS scipy {rss:.6g}"))

s = len(xs) * 0.05 ** 2
secs, (tck, fp, ier, msg) = median_secs(lambda: splrep(xs, ys, k=3, s=s, full_output=True),
                                        repeats)
rows.append(("smoothing condition 10^5", "splrep(s)", "splrep", secs,
             f"s {s:.6g}: scipy fp {fp:.6g}, {len(tck[0])} knots"))

r = load("surf_rows").reshape(-1, 3)
tk = load("surf_t")[4:-4]
secs, bs = median_secs(lambda: LSQBivariateSpline(r[:, 0], r[:, 1], r[:, 2], tk, tk, kx=3, ky=3,
                                                  bbox=[0, 1, 0, 1]), repeats)
print(rows, flush=True)
rows.append(("scattered surface 10^5 / 30x30", "LSQBivariateSpline", "surface", secs,
             f"RSS scipy {bs.get_residual():.6g}"))

# its GCV search runs Python loops over the data (minutes at 10^5): timed once; at 10^5 its
# banded Cholesky has failed ("the problem is ill-posed"), which is reported as such
try:
    secs, spl = median_secs(lambda: make_smoothing_spline(xs, ys), 1, warm=False)
    rss = float(np.sum((spl(xs) - ys) ** 2))
    rows.append(("smoothing GCV 10^5", "make_smoothing_spline(lam=None)", "gcv", secs,
                 f"RSS scipy {rss:.6g}"))
except (ValueError, np.linalg.LinAlgError) as e:
    print(f"smoothing GCV 10^5: SciPy failed: {e}", flush=True)
after = lekalo_run()
print(f"{'workload':34} {'peer':34} {'lekalo s':>10} {'peer s':>10} {'ratio':>7}  notes")
for name, peer, key, peer_secs, note in rows:
    ours = 0.5 * (before[key]["secs"] + after[key]["secs"])
    extra = {k: v for k, v in after[key].items() if k != "secs"}
    print(f"{name:34} {peer:34} {ours:10.4f} {peer_secs:10.4f} {peer_secs / ours:7.1f}  "
          f"{note}; lekalo {extra}")
tol = after["tolerance"]
ours = 0.5 * (before["tolerance"]["secs"] + tol["secs"])
occt = None
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from occt_build import build  # noqa: E402  (beside this script)

binary = build("occt_fit.cpp", "GeomAPI_PointsToBSpline.hxx",
               ["-lTKGeomAlgo", "-lTKGeomBase", "-lTKG3d", "-lTKG2d", "-lTKMath", "-lTKernel"])
if binary:
    occt = json.loads(subprocess.run([str(binary), f"{DIR}/tol_q.bin", "2", str(repeats),
                                      str(tol["tol"]), "3"], check=True, capture_output=True,
                                     text=True).stdout)
if occt:
    print(f"{'tolerance fit 10^5, tol ' + str(tol['tol']):34} {'GeomAPI_PointsToBSpline (C++)':34} "
          f"{ours:10.4f} {occt['secs']:10.4f} {occt['secs'] / ours:7.1f}  control points "
          f"{tol['n_ctrl']} vs {occt['n_ctrl']}; max distance {tol['max_deviation']:.3g} vs "
          f"{occt['max_deviation']:.3g}")
else:
    print(f"tolerance fit 10^5: {ours:.3f} s, {tol['n_ctrl']} control points, "
          f"max deviation {tol['max_deviation']:.3g} <= {tol['tol']}")
