"""Smoothing splines with λ chosen by GCV: lekalo against SciPy's make_smoothing_spline, side by
side on the same data, at the sizes where SciPy's GCV still runs.

    python bench/python/gcv_bench.py [--sizes 1000,2000,3000,5000] [--repeats 3]

Data: N sorted uniform parameters on [0, 10] (duplicates merged), y = sin x + noise of standard
deviation 0.1 (seed 1, one draw per size in turn). Prints, per size, the best of --repeats times
of `make_smoothing_spline(x, y)` (lam=None: GCV) on both sides, their ratio, the largest
difference of the two curves on 4001 points, and each fit's residual sum of squares next to the
noise's N σ², so that a fit that failed silently shows. The figures belong in
docs/performance.md, "Fitting", with the machine's load.
"""

from __future__ import annotations

import argparse
import os

import numpy as np
from scipy.interpolate import make_smoothing_spline

import lekalo
from timing import best_of


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1000,2000,3000,5000")
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    rng = np.random.default_rng(1)
    print(f"load average {os.getloadavg()[0]:.1f}")
    for n in (int(s) for s in a.sizes.split(",")):
        x = np.unique(rng.uniform(0, 10, n))
        y = np.sin(x) + 0.1 * rng.standard_normal(x.size)
        t_l, c = best_of(a.repeats, lambda: lekalo.make_smoothing_spline(x, y))
        rss_l = float(((c(x)[:, 0] - y) ** 2).sum())
        try:
            t_s, s = best_of(a.repeats, lambda: make_smoothing_spline(x, y))
        except ValueError as e:
            print(f"N {x.size}: lekalo {t_l * 1e3:.1f} ms, RSS {rss_l:.2f}; SciPy failed: {e}")
            continue
        xx = np.linspace(x[0], x[-1], 4001)
        diff = float(np.abs(c(xx)[:, 0] - s(xx)).max())
        rss_s = float(((s(x) - y) ** 2).sum())
        print(
            f"N {x.size}: SciPy {t_s * 1e3:.1f} ms, lekalo {t_l * 1e3:.1f} ms, {t_s / t_l:.0f}x; "
            f"max difference {diff:.1e}; RSS SciPy {rss_s:.2f}, lekalo {rss_l:.2f}, "
            f"N sigma^2 {x.size * 0.01:.1f}"
        )


if __name__ == "__main__":
    main()
