#!/usr/bin/env python3
"""Golden values for the refitted knot rounds of lekalo's smoothing condition, computed once
with SciPy's `generate_knots` and `make_splrep` (its `_fitpack_repro`, which refits the least
squares after every knot, unlike FITPACK's `curfit` behind `splrep`).

Writes crates/lekalo/tests/data/knot_rounds_golden.json. Run from the repository root:

    python3 -m venv target/fitvenv && target/fitvenv/bin/pip install numpy scipy
    target/fitvenv/bin/python scripts/knot_rounds_golden.py

The data are those of `scripts/fit_golden.py`'s `splrep` cases (no random generator).
"""
import json
import numpy as np
import scipy
from scipy.interpolate import generate_knots, make_splrep, splrep


def noise(n, seed):
    # a fixed pseudo-noise in [-0.5, 0.5): fractional parts of k * golden ratio
    k = np.arange(n) + seed
    return np.modf(k * 0.6180339887498949 + 0.1 * np.sin(k))[0] - 0.5


xr = np.linspace(0.0, 1.0, 400)
yr = np.sin(8 * xr) * np.exp(-xr) + 0.05 * noise(xr.size, 17)
sr = 400 * 0.05 ** 2 / 12  # about the noise's sum of squares
wr = 1.0 + 0.5 * np.abs(noise(xr.size, 29))

out = {"scipy": scipy.__version__, "x": xr.tolist(), "y": yr.tolist(), "w": wr.tolist(),
       "cases": []}
for k, s, weighted in [(3, sr, False), (3, sr / 4, False), (5, sr, True)]:
    w = wr if weighted else None
    seq = [t.tolist() for t in generate_knots(xr, yr, k=k, s=s, w=w)]
    spl = make_splrep(xr, yr, k=k, s=s, w=w)
    fp = float(np.sum(((spl(xr) - yr) * (1.0 if w is None else w)) ** 2))
    # the knots of FITPACK's curfit, for the record: they differ once a round adds two knots
    n_splrep = len(splrep(xr, yr, k=k, s=s, w=w)[0])
    out["cases"].append({"k": k, "s": s, "weighted": weighted, "sequence": seq,
                         "t": spl.t.tolist(), "c": spl.c.tolist(), "fp": fp,
                         "n_knots_splrep": n_splrep})

with open("crates/lekalo/tests/data/knot_rounds_golden.json", "w") as f:
    json.dump(out, f, indent=1)
print("wrote crates/lekalo/tests/data/knot_rounds_golden.json",
      [(c["k"], len(c["sequence"]), len(c["t"]), c["n_knots_splrep"]) for c in out["cases"]])
