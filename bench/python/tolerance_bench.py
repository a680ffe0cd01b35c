"""Tolerance fits of a space curve: lekalo's fewest-control-points fit within a distance against
SciPy's `splprep`, side by side on the same points, at growing sizes.

    python bench/python/tolerance_bench.py [--sizes 10000,100000,1000000,2000000] [--tol 1e-6]
                                           [--repeats 1] [--scipy-limit 60]

Data: N points of the helix (cos 4πu, sin 4πu, u) for u uniform in [0, 1], without noise, so a
curve within `tol` exists at every size. lekalo: `fit_tolerance(points, tol)` (cubic; every
point within `tol` of the curve, measured by its closest point). SciPy has no such fit; its
nearest is `splprep(points, s=N·tol²)`, the smoothing condition that bounds the root mean
square residual by `tol` (not the largest), with its own knot placement. Prints, per size, the
best of --repeats times, the control points each uses, and each fit's largest and root mean
square distance at the data (lekalo's by closest points, as it promises; SciPy's at its own
parameters, an upper bound of the distance). SciPy is skipped at sizes after one where it took
longer than --scipy-limit seconds. The figures belong in docs/performance/fitting.md, with the
machine's load.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from scipy.interpolate import splev, splprep

import lekalo


def helix(n):
    u = np.linspace(0.0, 1.0, n)
    return np.column_stack([np.cos(4 * np.pi * u), np.sin(4 * np.pi * u), u])


def best_of(repeats, f):
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="10000,100000,1000000,2000000")
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--scipy-limit", type=float, default=60.0)
    a = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f}; tol {a.tol:g}")
    scipy_on = True
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
        print(line, flush=True)


if __name__ == "__main__":
    main()
