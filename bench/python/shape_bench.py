"""Shape-constrained least squares: lekalo against a general-purpose modelling tool (CVXPY) with
the same solver (Clarabel), side by side on the same data and the same exact formulation.

    python bench/python/shape_bench.py [--points 100000] [--coefficients 200] [--repeats 3]

Needs CVXPY, which is not a requirement of the project: run it from an environment that has both
lekalo and CVXPY (e.g. `pip install cvxpy` into a copy of the test environment).

Data: the workload of `cargo bench -p lekalo --bench fit_shape`: N points on [0, 1],
y = x² + 0.05 sin 9x + 0.02 of a deterministic saw-tooth noise, a clamped uniform cubic knot
vector with C coefficients, the fit increasing, convex and y ≥ 0 on the whole domain.

Prints the best of --repeats wall-clock times and, beside it, the least CPU time of the same runs
(process time, all threads: steadier on a loaded machine), of:
- lekalo: `lekalo.make_lsq_spline(x, y, t, 3, increasing=True, convex=True, min=0.0)`, the whole
  fit from the data, and `make_lsq_spline` without constraints beside it;
- CVXPY: `Problem.solve(solver=CLARABEL)`, the first call (CVXPY compiles the problem) and the
  best of the later ones (the compilation cached: the solver's work alone), of the conic program of
  `crates/lekalo/tests/data/shape_golden.py` (Bernstein coefficients of y', y'' and y on every
  span; the exact second-order-cone conditions of the quadratic y' and of the cubic y, the
  latter as lekalo writes it, two cones a span, where the golden values use 2 x 2 semidefinite
  Gram matrices), its objective given as
  the normal equations' quadratic form. Only the modelling tool's own work is timed: the normal equations and the Bernstein rows, built with NumPy and
  SciPy, are prepared once before the clock starts, so the ratio favours CVXPY.
Then the ratio, and the two fits' largest difference at the data relative to the data's range
(CVXPY at Clarabel's default tolerances, as a user calls it).
The figures belong in docs/performance/fitting.md, "Shape constraints", with the machine's load.
"""

from __future__ import annotations

import argparse
import math

import numpy as np
from scipy.interpolate import BSpline

import lekalo
import time


def best_of(repeats, f):
    """The least wall-clock time (time.perf_counter) and the least CPU time (time.process_time)
    of `repeats` runs of `f()`, and the last result."""
    wall, cpu, out = float("inf"), float("inf"), None
    for _ in range(repeats):
        w0, c0 = time.perf_counter(), time.process_time()
        out = f()
        wall = min(wall, time.perf_counter() - w0)
        cpu = min(cpu, time.process_time() - c0)
    return (wall, cpu), out


def workload(n, m):
    x = np.arange(n) / (n - 1)
    k = np.arange(n)
    saw = ((k * 7919) % 1009) / 504.5 - 1.0
    y = x * x + 0.05 * np.sin(9.0 * x) + 0.02 * saw
    inner = np.linspace(0.0, 1.0, m - 3 + 1)
    t = np.concatenate([[0.0] * 3, inner, [1.0] * 3])
    return x, y, t


def bernstein_rows(t, k, r, lo, hi):
    """(d + 1) x n: the Bernstein coefficients of y^(r) on [lo, hi], rows over the coefficients
    (values of the n basis functions' derivatives at d + 1 points, solved against the
    Bernstein-Vandermonde matrix, as shape_golden.py does)."""
    n = len(t) - k - 1
    d = k - r
    tau = (np.arange(d + 1) + 0.5) / (d + 1)
    basis = BSpline(t, np.eye(n), k)
    vals = (basis.derivative(r) if r > 0 else basis)(lo + (hi - lo) * tau)
    bv = np.array([[math.comb(d, i) * s ** i * (1 - s) ** (d - i) for i in range(d + 1)]
                   for s in tau])
    return np.linalg.solve(bv, vals)


def cvxpy_problem(x, y, t, k=3):
    import cvxpy as cp

    n = len(t) - k - 1
    B = BSpline.design_matrix(x, t, k)
    H = (B.T @ B).toarray()
    g = B.T @ y
    c = cp.Variable(n)
    cons = []
    for s in range(k, n):
        lo, hi = t[s], t[s + 1]
        if hi <= lo:
            continue
        # increasing: y' of degree 2, the exact cone condition
        b = bernstein_rows(t, k, 1, lo, hi) @ c
        aux = cp.Variable()
        cons += [b[1] + aux >= 0, cp.SOC(b[0] + b[2], cp.hstack([b[0] - b[2], 2 * aux]))]
        # convex: y'' of degree 1, its two Bernstein coefficients
        cons += [bernstein_rows(t, k, 2, lo, hi) @ c >= 0]
        # y >= 0: the cubic as tau q1 + (1 - tau) q2, q1 = (3 b1 - 2a, s, b3) and
        # q2 = (b0, a, 3 b2 - 2s) non-negative on the line (exact: two cones, as lekalo's)
        b = bernstein_rows(t, k, 0, lo, hi) @ c
        a_, s_ = cp.Variable(), cp.Variable()
        u0, w2 = 3 * b[1] - 2 * a_, 3 * b[2] - 2 * s_
        cons += [cp.SOC(u0 + b[3], cp.hstack([u0 - b[3], 2 * s_])),
                 cp.SOC(b[0] + w2, cp.hstack([b[0] - w2, 2 * a_]))]
    obj = cp.quad_form(c, cp.psd_wrap(H)) - 2 * g @ c + float(y @ y)
    return cp.Problem(cp.Minimize(obj), cons), c


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=100_000)
    ap.add_argument("--coefficients", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    x, y, t = workload(a.points, a.coefficients)
    shape = dict(increasing=True, convex=True, min=0.0)
    t_free, _ = best_of(a.repeats, lambda: lekalo.make_lsq_spline(x, y, t, 3))
    t_lek, fit = best_of(a.repeats, lambda: lekalo.make_lsq_spline(x, y, t, 3, **shape))
    import cvxpy as cp

    prob, c = cvxpy_problem(x, y, t)
    t_first, _ = best_of(1, lambda: prob.solve(solver=cp.CLARABEL))
    # later solves reuse CVXPY's compilation of the problem: only the solver's work
    t_cvx, _ = best_of(a.repeats, lambda: prob.solve(solver=cp.CLARABEL))
    ours = np.asarray(fit(x)).reshape(-1)
    theirs = BSpline(t, c.value, 3)(x)
    gap = float(np.max(np.abs(ours - theirs)) / (y.max() - y.min()))

    def ms(tt):
        return f"{tt[0] * 1e3:9.2f} ms wall {tt[1] * 1e3:9.2f} ms CPU"

    print(f"{a.points} points, {a.coefficients} cubic coefficients, increasing, convex, y >= 0")
    print(f"lekalo make_lsq_spline, unconstrained  {ms(t_free)}")
    print(f"lekalo make_lsq_spline, constrained    {ms(t_lek)} "
          f"({t_lek[0] / t_free[0]:.1f}x wall, {t_lek[1] / t_free[1]:.1f}x CPU the unconstrained)")
    print(f"CVXPY + Clarabel, compile and solve    {ms(t_first)} "
          f"({prob.status}, {len(prob.constraints)} constraint blocks)")
    print(f"CVXPY + Clarabel, solve again          {ms(t_cvx)}")
    for name, i in (("wall", 0), ("CPU", 1)):
        print(f"ratio CVXPY / lekalo ({name}): {t_first[i] / t_lek[i]:.1f}x with CVXPY's "
              f"compilation, {t_cvx[i] / t_lek[i]:.1f}x its solve alone")
    print(f"largest difference of the fits at the data, relative to the data's range: {gap:.2e}")


if __name__ == "__main__":
    main()
