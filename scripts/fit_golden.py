#!/usr/bin/env python3
"""Golden values for lekalo's fitting tests, computed once with SciPy.

Writes crates/lekalo/tests/data/fit_golden.json. Run from the repository root:

    python3 -m venv target/fitvenv && target/fitvenv/bin/pip install numpy scipy
    target/fitvenv/bin/python scripts/fit_golden.py

The data are deterministic (no random generator): sines plus a fixed pseudo-noise.
"""
import json
import numpy as np
import scipy
from scipy.interpolate import (make_lsq_spline, make_smoothing_spline, splrep,
                               LSQBivariateSpline)


def noise(n, seed):
    # a fixed pseudo-noise in [-0.5, 0.5): fractional parts of k * golden ratio
    k = np.arange(n) + seed
    return np.modf(k * 0.6180339887498949 + 0.1 * np.sin(k))[0] - 0.5


out = {"scipy": scipy.__version__}

# 1. make_lsq_spline, weighted, non-uniform sites, cubic
x = np.sort(np.r_[0.0, np.cumsum(0.5 + np.abs(noise(79, 1)))])
x = 10 * x / x[-1]
y = np.sin(x) + 0.1 * noise(x.size, 7)
w = 1.0 + np.abs(noise(x.size, 3))
k = 3
t = np.r_[[x[0]] * (k + 1), [1.5, 3.0, 4.0, 5.5, 7.0, 8.2], [x[-1]] * (k + 1)]
spl = make_lsq_spline(x, y, t, k, w=w)
out["lsq"] = {"x": x.tolist(), "y": y.tolist(), "w": w.tolist(), "t": t.tolist(),
              "k": k, "c": spl.c.tolist()}

# 1b. the same at a 1e8 offset in x and y
xo = x + 1e8
to = t + 1e8
yo = y + 1e8
spl_o = make_lsq_spline(xo, yo, to, k, w=w)
out["lsq_offset"] = {"c": spl_o.c.tolist()}

# 2. make_smoothing_spline with a given lam, and with GCV
xs = np.linspace(0.0, 6.0, 101) + 0.02 * noise(101, 11)
xs.sort()
ys = np.cos(xs) + 0.2 * noise(xs.size, 5)
ws = 1.0 + 0.5 * np.abs(noise(xs.size, 13))
lam = 0.05
s1 = make_smoothing_spline(xs, ys, w=ws, lam=lam)
s2 = make_smoothing_spline(xs, ys)  # GCV, unit weights
mids = 0.5 * (xs[1:] + xs[:-1])
out["smoothing"] = {"x": xs.tolist(), "y": ys.tolist(), "w": ws.tolist(), "lam": lam,
                    "at": mids.tolist(), "values": s1(mids).tolist(),
                    "gcv_values": s2(xs).tolist()}

# 3. splrep with s (FITPACK curfit)
xr = np.linspace(0.0, 1.0, 400)
yr = np.sin(8 * xr) * np.exp(-xr) + 0.05 * noise(xr.size, 17)
sr = 400 * 0.05 ** 2 / 12  # about the noise's sum of squares
tck, fp, ier, msg = splrep(xr, yr, k=3, s=sr, full_output=True)
out["splrep"] = {"x": xr.tolist(), "y": yr.tolist(), "s": sr, "fp": float(fp),
                 "n_knots": int(len(tck[0])), "n_interior": int(len(tck[0]) - 8),
                 "t": tck[0].tolist(), "c": tck[1][:len(tck[0]) - 4].tolist()}

# 3b. the same data, s = 0 (interpolation), quadratic (midpoint knots) and a weighted quintic
tck0 = splrep(xr[:40], yr[:40], k=2, s=0.0)
wr = 1.0 + 0.5 * np.abs(noise(xr.size, 29))
tck5, fp5, _, _ = splrep(xr, yr, w=wr, k=5, s=sr, full_output=True)
out["splrep_more"] = {"interp_k2": {"t": tck0[0].tolist(), "c": tck0[1][:len(tck0[0]) - 3].tolist()},
                      "weighted_k5": {"w": wr.tolist(), "fp": float(fp5), "t": tck5[0].tolist(),
                                      "c": tck5[1][:len(tck5[0]) - 6].tolist()}}

# 3b'. the same data and s on a domain wider than the data (end knots at xb, xe)
tckw, fpw, _, _ = splrep(xr, yr, k=3, s=sr, xb=-0.25, xe=1.5, full_output=True)
out["splrep_more"]["wide"] = {"xb": -0.25, "xe": 1.5, "fp": float(fpw), "t": tckw[0].tolist(),
                              "c": tckw[1][:len(tckw[0]) - 4].tolist()}

# 3c. periodic: splrep(per=1), least squares with given interior knots and smoothing with s
xp = np.linspace(0.0, 2 * np.pi, 121) + 0.01 * noise(121, 31)
xp[0], xp[-1] = 0.0, 2 * np.pi
xp.sort()
yp = np.cos(xp) + 0.5 * np.sin(2 * xp) + 0.05 * noise(xp.size, 37)
yp[-1] = yp[0]
tp_in = [0.7, 1.5, 2.2, 3.0, 3.9, 4.6, 5.5]
tckp = splrep(xp, yp, k=3, t=tp_in, per=1)
sp = 120 * 0.05 ** 2 / 12
tcks, fps, _, _ = splrep(xp, yp, k=3, s=sp, per=1, full_output=True)
out["splrep_periodic"] = {"x": xp.tolist(), "y": yp.tolist(), "interior": tp_in,
                          "lsq_t": tckp[0].tolist(), "lsq_c": tckp[1][:len(tckp[0]) - 4].tolist(),
                          "s": sp, "fp": float(fps), "t": tcks[0].tolist(),
                          "c": tcks[1][:len(tcks[0]) - 4].tolist()}

# 4. LSQBivariateSpline on scattered data
m = 400
u = 2.0 * (np.modf(np.arange(m) * 0.7548776662466927)[0])
v = 3.0 * (np.modf(np.arange(m) * 0.5698402909980532)[0])
z = np.sin(u) * np.cos(v) + 0.05 * noise(m, 23)
tx = [0.5, 1.0, 1.5]
ty = [0.75, 1.5, 2.25]
bs = LSQBivariateSpline(u, v, z, tx, ty, kx=3, ky=3)
gu = np.linspace(u.min(), u.max(), 7)
gv = np.linspace(v.min(), v.max(), 9)
out["lsq_bivariate"] = {"u": u.tolist(), "v": v.tolist(), "z": z.tolist(), "tx": tx,
                        "ty": ty, "bbox": [u.min(), u.max(), v.min(), v.max()],
                        "grid_u": gu.tolist(), "grid_v": gv.tolist(),
                        "values": bs(gu, gv).ravel().tolist(),
                        "fp": float(bs.get_residual())}

with open("crates/lekalo/tests/data/fit_golden.json", "w") as f:
    json.dump(out, f, indent=1)
print("wrote crates/lekalo/tests/data/fit_golden.json", {k: (v["n_interior"], v["fp"]) for k, v in out.items() if k == "splrep"})
