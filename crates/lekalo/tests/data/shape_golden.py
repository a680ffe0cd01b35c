"""Golden values for the shape-constrained fits (`shape_golden.json`), from an independent conic
program of the same exact formulation, modelled in CVXPY and solved by Clarabel.

Independent of lekalo: the observation matrix is SciPy's `BSpline.design_matrix`; the Bernstein
coefficients of a derivative on a piece of a knot span come from SciPy's `BSpline.derivative`
evaluated at `d + 1` points of the piece and a solve with the Bernstein-Vandermonde matrix (not
from Taylor coefficients, as lekalo does); the smoothing penalty `∫ y''²` is two-point
Gauss-Legendre quadrature per span (exact: `y''` is linear there). Per piece and shape
`σ(y⁽ʳ⁾ − v) ≥ 0`, with Bernstein coefficients `b` of `σ(y⁽ʳ⁾ − v)` of degree `d = p − r`:
`d ≤ 1` or `d ≥ 4`: `b ≥ 0`; `d = 2`: `b₁ + s ≥ 0` and `‖(b₀ − b₂, 2s)‖ ≤ b₀ + b₂` (which implies
`b₀, b₂ ≥ 0`); `d = 3`: the cubic is `τ·σ₁(τ) + (1 − τ)·σ₂(τ)` with `σᵢ = [1, τ] Qᵢ [1, τ]ᵀ` and
2 × 2 Gram matrices `Qᵢ ⪰ 0` in the monomial basis (Markov–Lukács; a semidefinite cone here,
where lekalo writes the same condition as two second-order cones in the Bernstein basis).

Run with CVXPY in a throw-away environment (it is not a test requirement of the project):

    python3 -m venv /tmp/cvx-venv && /tmp/cvx-venv/bin/pip install cvxpy numpy scipy
    /tmp/cvx-venv/bin/python crates/lekalo/tests/data/shape_golden.py

It writes `shape_golden.json` beside itself.

An interior-point answer approaches an optimum whose polynomial touches zero inside a piece (a
double root) only as the square root of its duality gap, about 1e-7 in the values at these
tolerances; where a cubic is constrained (two cones a piece, the cases whose cubics touch their
bounds inside a piece) the reference is therefore polished on its active face (`polish`: the rows at their
bounds made equalities, value and slope zero at each touching point, the touching points chosen
to minimise the objective), which is exact to rounding, and kept only if it keeps every
condition. Where a whole span lies on a bound (a flat stretch) lekalo's tests check such fits by
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


def cubic_sos(bb):
    """The cubic with Bernstein coefficients `bb` is `τ σ₁ + (1 − τ) σ₂` on [0, 1], σᵢ sums of
    squares of degree 2 (Gram matrices Q₁, Q₂ ⪰ 0 over [1, τ]): equal monomial coefficients."""
    # monomial coefficients a_k = Σ_j bb_j [τ^k] B³_j(τ)
    to_mono = np.array([[math.comb(3, j) * math.comb(3 - j, k - j) * (-1) ** (k - j)
                         if k >= j else 0.0 for j in range(4)] for k in range(4)])
    a = to_mono @ bb
    q1 = cp.Variable((2, 2), PSD=True)
    q2 = cp.Variable((2, 2), PSD=True)
    return [a[0] == q2[0, 0],
            a[1] == q1[0, 0] + 2 * q2[0, 1] - q2[0, 0],
            a[2] == 2 * q1[0, 1] + q2[1, 1] - 2 * q2[0, 1],
            a[3] == q1[1, 1] - q2[1, 1]]


def bernstein_weights(d, tau, nu=0):
    """Weights w with p(tau) = w @ bb (nu = 0) or p'(tau) = w @ bb (nu = 1) for the polynomial
    of degree d with Bernstein coefficients bb; tau may be an array (one row per tau)."""
    tau = np.atleast_1d(np.asarray(tau, dtype=float))[:, None]
    if nu == 0:
        j = np.arange(d + 1)
        return np.array([math.comb(d, i) for i in j]) * tau ** j * (1 - tau) ** (d - j)
    low = bernstein_weights(d - 1, tau[:, 0])
    w = np.zeros((len(tau), d + 1))
    w[:, 1:] += d * low
    w[:, :-1] -= d * low
    return w


def polish(H, g, yy, polys, equal, c0, value0, tol=1e-6):
    """The interior-point answer moved onto its active face exactly: coefficients within `tol`
    of a bound become equalities, and a piece whose polynomial touches zero inside at τ gets
    value and slope zero there, τ chosen to minimise the objective (the optimum of the whole
    problem is the least over τ of these equality-constrained optima). An interior-point
    answer approaches such a double root only as the square root of its gap (here about 1e-7
    in values); the polished one is exact to rounding. Kept only if it keeps every condition
    (to 1e-11) and raises the objective by at most 1e-9 relative (the interior-point answer
    may be outside a bound by its feasibility tolerance, lowering its objective); else the
    interior-point answer."""
    rows, rhs, touching = [r for r, _ in equal], [v for _, v in equal], []
    for M, sv in polys:
        bb = M @ c0 - sv
        scale = max(np.abs(M).max(), 1e-300)
        d = len(bb) - 1
        near = np.abs(bb) / scale <= tol
        taus = np.linspace(0.0, 1.0, 2001)
        vals = bernstein_weights(d, taus) @ bb
        # a local minimum inside at zero: a double root (a cubic may have one beside a root
        # at an end)
        inner = [j for j in range(1, 2000) if vals[j] <= vals[j - 1] and vals[j] <= vals[j + 1]]
        j = min(inner, key=lambda j: vals[j]) if inner else None
        if d >= 2 and j is not None and vals[j] / scale <= tol:
            touching.append((M, sv, taus[j]))
        for i in range(d + 1):
            if near[: i + 1].all() or near[i:].all():
                rows.append(M[i])
                rhs.append(sv)

    def solve(taus):
        e_rows, e_rhs = list(rows), list(rhs)
        for (M, sv, _), tau in zip(touching, taus):
            tau = min(max(tau, 0.0), 1.0)
            d = M.shape[0] - 1
            for nu in (0, 1):
                wt = bernstein_weights(d, tau, nu)[0]
                e_rows.append(wt @ M)
                e_rhs.append(wt.sum() * sv)
        n = len(g)
        if not e_rows:
            cc = np.linalg.solve(H, g)
        else:
            E = np.array(e_rows)
            kkt = np.block([[H, E.T], [E, np.zeros((len(E), len(E)))]])
            cc = np.linalg.lstsq(kkt, np.concatenate([g, e_rhs]), rcond=None)[0][:n]
        return cc, float(cc @ H @ cc - 2 * g @ cc + yy)

    if touching:
        from scipy.optimize import minimize
        start = [tau for _, _, tau in touching]
        res = minimize(lambda ts: solve(ts)[1], start, method="Nelder-Mead",
                       options={"xatol": 1e-12, "fatol": 1e-16, "maxiter": 20000})
        coef, value = solve(res.x)
    else:
        coef, value = solve([])
    worst = 0.0
    for M, sv in polys:
        bb = M @ coef - sv
        vals = bernstein_weights(len(bb) - 1, np.linspace(0.0, 1.0, 20001)) @ bb
        worst = min(worst, vals.min() / max(np.abs(M).max(), 1e-300))
    for r, v in equal:
        worst = min(worst, -abs(r @ coef - v))
    if worst >= -1e-11 and value <= value0 * (1 + 1e-9):
        return coef, value
    print("  polish not kept:", worst, value, value0)
    return c0, float(value0)


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
    polys = []  # (Bernstein rows of σ y^(r), σ v) per piece, for the polish
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
            polys.append((sigma * M, sigma * v))
            bb = sigma * (M @ c - v)
            if d == 2:
                aux = cp.Variable()
                cons += [bb[1] + aux >= 0,
                         cp.SOC(bb[0] + bb[2], cp.hstack([bb[0] - bb[2], 2 * aux]))]
            elif d == 3:
                cons += cubic_sos(bb)
            else:
                cons += [bb >= 0]
    equal = []
    for q in case.get("points", []):
        e_rows = np.zeros(n)
        for j in range(n):
            e = np.zeros(n)
            e[j] = 1.0
            s = BSpline(t, e, k)
            e_rows[j] = (s.derivative(q["derivative"]) if q["derivative"] else s)(q["x"])
        cons.append(e_rows @ c == q["value"])
        equal.append((e_rows, q["value"]))
    # the objective as a quadratic form (passed to Clarabel as its P, not as a cone)
    g = B.T @ (w * y)
    obj = cp.quad_form(c, cp.psd_wrap(H)) - 2 * g @ c + float(np.sum(w * y * y))
    prob = cp.Problem(cp.Minimize(obj), cons)
    prob.solve(solver=cp.CLARABEL, tol_gap_abs=1e-14, tol_gap_rel=1e-14, tol_feas=1e-10,
               max_iter=500)
    assert prob.status == "optimal", prob.status
    coef, value = c.value, float(prob.value)
    if any(M.shape[0] == 4 for M, _ in polys):
        # cubics (two cones) are where the interior-point answer is slow to reach a double root
        coef, value = polish(H, g, float(np.sum(w * y * y)), polys, equal, coef, value)
    spl = BSpline(t, coef, k)
    grid = np.linspace(t[k], t[n], 101)
    return {"objective": value, "values_at_x": spl(x).tolist(),
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
    x, y = noisy(101, lambda s: 4 * (s - 0.4) ** 2 - 0.05 + 0.3 * s ** 3, amp=0.01, seed=7)
    out.append({"name": "cubic above 0 where the data dip inside spans (two cones per cubic)",
                "degree": 3, "knots": clamped_uniform(3, 6).tolist(), "x": x.tolist(),
                "y": y.tolist(), "shapes": [{"shape": "min", "level": 0.0}]})
    x, y = noisy(90, lambda s: s + 0.12 * np.sin(10 * s), amp=0.02, seed=8)
    out.append({"name": "increasing quartic (the cubic derivative's two cones)", "degree": 4,
                "knots": clamped_uniform(4, 9).tolist(), "x": x.tolist(), "y": y.tolist(),
                "shapes": [{"shape": "increasing"}]})
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
