"""Tolerance fits of a space curve: lekalo's fewest-control-points fit within a distance against
SciPy's `splprep`, side by side on the same points, at growing sizes.

    python bench/python/tolerance_bench.py [--sizes 10000,100000,1000000,2000000] [--tol 1e-6]
                                           [--repeats 1] [--scipy-limit 60] [--occ-limit 120]

Data: N points of the helix (cos 4πu, sin 4πu, u) for u uniform in [0, 1], without noise, so a
curve within `tol` exists at every size. lekalo: `fit_tolerance(points, tol)` (cubic; every
point within `tol` of the curve, measured by its closest point). SciPy has no such fit; its
nearest is `splprep(points, s=N·tol²)`, the smoothing condition that bounds the root mean
square residual by `tol` (not the largest), with its own knot placement. Prints, per size, the
best of --repeats times, the control points each uses, and each fit's largest and root mean
square distance at the data (lekalo's by closest points, as it promises; SciPy's at its own
parameters, an upper bound of the distance). SciPy is skipped at sizes after one where it took
longer than --scipy-limit seconds.

Open CASCADE's nearest call, `GeomAPI_PointsToBSpline` (degree 3 to 8, C2, the same tolerance),
is timed too when its headers are installed (Debian: libocct-modeling-algorithms-dev and
libocct-foundation-dev): `bench/peers/occt_fit.cpp` is built with g++ into target/, reads the
points from a binary file and times the call alone in C++ (wall and CPU); its largest distance
is measured by projecting up to 100,000 of the points on its curve. A run
longer than --occ-limit seconds is stopped, and Open CASCADE is skipped at the larger sizes.
The figures belong in docs/performance/fitting.md, with the machine's load.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.interpolate import splev, splprep

import lekalo
from timing import best_of


def helix(n):
    u = np.linspace(0.0, 1.0, n)
    return np.column_stack([np.cos(4 * np.pi * u), np.sin(4 * np.pi * u), u])


sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "peers"))
from occt_build import build  # noqa: E402  (bench/peers/occt_build.py)


def occt_fit(binary, pts, tol, limit):
    """Open CASCADE's fit of `pts` within `tol` (cubic to degree 8): the JSON of
    bench/peers/occt_fit.cpp, or None past `limit` seconds."""
    with tempfile.NamedTemporaryFile(suffix=".bin") as f:
        np.ascontiguousarray(pts, dtype="<f8").tofile(f.name)
        try:
            out = subprocess.run([str(binary), f.name, "3", "1", repr(tol), "8"],
                                 capture_output=True, text=True, timeout=limit, check=True)
        except subprocess.TimeoutExpired:
            return None
    return json.loads(out.stdout)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="10000,100000,1000000,2000000")
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--scipy-limit", type=float, default=60.0)
    ap.add_argument("--occ-limit", type=float, default=120.0)
    a = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}; tol {a.tol:g}")
    scipy_on = True
    occt = build("occt_fit.cpp", "GeomAPI_PointsToBSpline.hxx",
                 ["-lTKGeomAlgo", "-lTKGeomBase", "-lTKG3d", "-lTKG2d", "-lTKMath", "-lTKernel"])
    occ_on = occt is not None
    for n in (int(s) for s in a.sizes.split(",")):
        pts = helix(n)
        t_l, (curve, report) = best_of(a.repeats, lambda: lekalo.fit_tolerance(pts, a.tol))
        line = (
            f"N {n}: lekalo {t_l:.2f} s, {len(curve.control)} control points, "
            f"max {report['max_deviation']:.2e}"
        )
        if scipy_on:
            t_s, (tck, u) = best_of(
                a.repeats, lambda: splprep(pts.T, s=n * a.tol**2, k=3, quiet=1)
            )
            d = np.linalg.norm(np.array(splev(u, tck)).T - pts, axis=1)
            line += (
                f"; SciPy splprep {t_s:.2f} s, {len(tck[1][0])} control points, "
                f"max {d.max():.2e}, rms {np.sqrt((d**2).mean()):.2e}; "
                f"lekalo {t_s / t_l:.1f}x"
            )
            scipy_on = t_s <= a.scipy_limit
        else:
            line += "; SciPy skipped (slower than --scipy-limit at the last size)"
        if occ_on:
            occ = occt_fit(occt, pts, a.tol, a.occ_limit)
            if occ is None:
                line += f"; Open CASCADE stopped after {a.occ_limit:g} s"
                occ_on = False
            else:
                t_o = occ["secs"]
                line += (
                    f"; Open CASCADE PointsToBSpline {t_o:.2f} s (CPU {occ['cpu']:.2f} s), "
                    f"{occ['n_ctrl']} control points of degree {occ['degree']}, "
                    f"max {occ['max_deviation']:.2e}; lekalo {t_o / t_l:.1f}x"
                )
        print(line, flush=True)


if __name__ == "__main__":
    main()
