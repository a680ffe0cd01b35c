"""Golden values for the shape-constrained fits (`shape_golden.json`), from an independent conic
program of the same exact formulation, modelled in CVXPY and solved by Clarabel.

Independent of lekalo: the observation matrix is SciPy's `BSpline.design_matrix`; the Bernstein
coefficients of a derivative on a piece of a knot span come from SciPy's `BSpline.derivative`
evaluated at `d + 1` points of the piece and a solve with the Bernstein-Vandermonde matrix (not
from Taylor coefficients, as lekalo does); the smoothing penalty `∫ y''²` is two-point
Gauss-Legendre quadrature per span (exact: `y''` is linear there). Per piece and shape
`σ(y⁽ʳ⁾ − v) ≥ 0`, with Bernstein coefficients `b` of `σ(y⁽ʳ⁾ − v)` of degree `d = p − r`:
`d ≤ 1` or `d ≥ 3`: `b ≥ 0`; `d = 2`: `b₁ + s ≥ 0` and `‖(b₀ − b₂, 2s)‖ ≤ b₀ + b₂` (which implies `b₀, b₂ ≥ 0`).

Run with CVXPY in a throw-away environment (it is not a test requirement of the project):

    python3 -m venv /tmp/cvx-venv && /tmp/cvx-venv/bin/pip install cvxpy numpy scipy
    /tmp/cvx-venv/bin/python crates/lekalo/tests/data/shape_golden.py

It writes `shape_golden.json` beside itself.

The cases have optima that touch their bounds at isolated points (strict complementarity), where
an interior-point answer is accurate to far better than the 1e-8 the tests ask. Where a whole span
lies on a bound (a flat stretch) the interior-point reference is only good to about 1e-7 in the
values; lekalo polishes its answer on the active face there, and its tests check such fits by
exact root finding and the objective instead of against these values.
"""

import json
import math
import os

import cvxpy as cp
import numpy as np
from scipy.interpolate import BSpline

SIGN = {"increasing": (1, 1.0), "decreasing": (1, -1.0), "convex": (2, 1.0),
        "concave": (2, -1.0), "min": (0, 1.0), "max": (0, -1.0)}


def clamped_uniform(k, n, lo=0.0, hi=1.0):
    inner = np.linspace(lo, hi, n - k + 1)
    return np.concatenate([[lo] * k, inner, [hi] * k])


def bernstein_rows(t, k, n, r, lo, hi):
    """(d + 1) x n matrix: Bernstein coefficients on [lo, hi] of y^(r) as rows over c."""
    d = k - r
    tau = (np.arange(d + 1) + 0.5) / (d + 1) if d > 0 else np.array([0.5])
    xs = lo + (hi - lo) * tau
    vals = np.zeros((d + 1, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = 1.0
        s = BSpline(t, e, k)
        vals[:, j] = s.derivative(r)(xs) if r > 0 else s(xs)
    bv = np.array([[math.comb(d, i) * tt ** i * (1 - tt) ** (d - i) for i in range(d + 1)]
                   for tt in tau])
    return np.linalg.solve(bv, vals)


def fit(case):
    x = np.array(case["x"])
    y = np.array(case["y"])
    w = np.array(case["w"]) if case.get("w") is not None else np.ones_like(x)
    k = case["degree"]
    t = np.array(case["knots"])
    n = len(t) - k - 1
    c = cp.Variable(n)
    B = BSpline.design_matrix(x, t, k).toarray()
    H = B.T @ (w[:, None] * B)
    lam = case.get("lambda")
    if lam is not None:
        g = np.array([-1.0, 1.0]) / math.sqrt(3.0)
        rows, wts = [], []
        for s in range(k, n):
            a, b = t[s], t[s + 1]
            if b <= a:
                continue
            for gg in g:
                xg = 0.5 * (a + b) + 0.5 * (b - a) * gg
                row = np.zeros(n)
                for j in range(n):
                    e = np.zeros(n)
                    e[j] = 1.0
                    row[j] = BSpline(t, e, k).derivative(2)(xg)
                rows.append(row)
                wts.append(0.5 * (b - a))
        D = np.array(rows) * np.sqrt(lam * np.array(wts))[:, None]
        H = H + D.T @ D
    cons = []
    for sh in case["shapes"]:
        r, sigma = SIGN[sh["shape"]]
        v = sh.get("level", 0.0)
        a, b = sh["interval"] if sh.get("interval") else (t[k], t[n])
        d = k - r
        for s in range(k, n):
            lo, hi = max(t[s], a), min(t[s + 1], b)
            if lo >= hi:
                continue
            M = bernstein_rows(t, k, n, r, lo, hi)
            bb = sigma * (M @ c - v)
            if d == 2:
                aux = cp.Variable()
                cons += [bb[1] + aux >= 0,
                         cp.SOC(bb[0] + bb[2], cp.hstack([bb[0] - bb[2], 2 * aux]))]
            else:
                cons += [bb >= 0]
    for q in case.get("points", []):
        e_rows = np.zeros(n)
        for j in range(n):
            e = np.zeros(n)
            e[j] = 1.0
            s = BSpline(t, e, k)
            e_rows[j] = (s.derivative(q["derivative"]) if q["derivative"] else s)(q["x"])
        cons.append(e_rows @ c == q["value"])
    # the objective as a quadratic form (passed to Clarabel as its P, not as a cone)
    g = B.T @ (w * y)
    obj = cp.quad_form(c, cp.psd_wrap(H)) - 2 * g @ c + float(np.sum(w * y * y))
    prob = cp.Problem(cp.Minimize(obj), cons)
    prob.solve(solver=cp.CLARABEL, tol_gap_abs=1e-14, tol_gap_rel=1e-14, tol_feas=1e-10,
               max_iter=500)
    assert prob.status == "optimal", prob.status
    spl = BSpline(t, c.value, k)
    grid = np.linspace(t[k], t[n], 101)
    return {"objective": float(prob.value), "values_at_x": spl(x).tolist(),
            "grid": grid.tolist(), "values_at_grid": spl(grid).tolist()}


def noisy(n, f, amp=0.05, seed=0):
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 1.0, n)
    return x, f(x) + amp * rng.standard_normal(n)


def cases():
    out = []
    x, y = noisy(120, lambda s: s + 0.15 * np.sin(9 * s), seed=1)
    out.append({"name": "increasing cubic (cone per span)", "degree": 3,
                "knots": clamped_uniform(3, 14).tolist(), "x": x.tolist(), "y": y.tolist(),
                "shapes": [{"shape": "increasing"}]})
    x, y = noisy(90, lambda s: np.abs(s - 0.6) + 0.1 * np.cos(11 * s), seed=2)
    out.append({"name": "convex cubic on an interval, below a bound", "degree": 3,
                "knots": clamped_uniform(3, 12).tolist(), "x": x.tolist(), "y": y.tolist(),
                "shapes": [{"shape": "convex", "interval": [0.25, 1.0]},
                           {"shape": "max", "level": 0.5}]})
    x, y = noisy(80, lambda s: np.sin(7 * s), amp=0.1, seed=3)
    w = (1.0 + x).tolist()
    out.append({"name": "quadratic between bounds, weighted (cone per span)", "degree": 2,
                "knots": clamped_uniform(2, 10).tolist(), "x": x.tolist(), "y": y.tolist(),
                "w": w, "shapes": [{"shape": "min", "level": -0.9},
                                   {"shape": "max", "level": 0.9}]})
    x, y = noisy(70, lambda s: 1 - s ** 2 + 0.2 * np.sin(13 * s), seed=4)
    out.append({"name": "decreasing concave quadratic through a point", "degree": 2,
                "knots": clamped_uniform(2, 9).tolist(), "x": x.tolist(), "y": y.tolist(),
                "shapes": [{"shape": "decreasing"}, {"shape": "concave"}],
                "points": [{"x": 0.0, "derivative": 0, "value": 1.0}]})
    x, y = noisy(40, lambda s: np.tanh(6 * (s - 0.5)) + 0.3 * np.sin(15 * s), amp=0.05, seed=5)
    knots = np.concatenate([[x[0]] * 3, x, [x[-1]] * 3]).tolist()
    out.append({"name": "smoothing spline, increasing", "degree": 3, "knots": knots,
                "lambda": 1e-4, "x": x.tolist(), "y": y.tolist(),
                "shapes": [{"shape": "increasing"}]})
    x, y = noisy(100, lambda s: np.exp(2 * s), amp=0.3, seed=6)
    out.append({"name": "increasing and convex above 1, with a slope", "degree": 3,
                "knots": clamped_uniform(3, 16).tolist(), "x": x.tolist(), "y": y.tolist(),
                "shapes": [{"shape": "increasing"}, {"shape": "convex"},
                           {"shape": "min", "level": 1.0}],
                "points": [{"x": 0.0, "derivative": 1, "value": 0.5}]})
    return out


def main():
    res = []
    for case in cases():
        case.update(fit(case))
        res.append(case)
        print(case["name"], case["objective"])
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "shape_golden.json")
    with open(path, "w") as f:
        json.dump({"source": "crates/lekalo/tests/data/shape_golden.py (CVXPY + Clarabel)",
                   "cases": res}, f, indent=1)


if __name__ == "__main__":
    main()
