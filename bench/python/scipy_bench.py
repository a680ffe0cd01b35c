"""lekalo.scipy beside scipy.interpolate: every public name, side by side in one run.

    python bench/python/scipy_bench.py [--sizes 100000,1000000] [--repeats 3] [--only NAME]
                                       [--per-point-max 100000] [--ndbspl-n 20] [--sample 0.02]

Run it with the package installed in release mode (`pip install ./crates/lekalo-py`, or
`maturin develop --release` in crates/lekalo-py) and SciPy beside it. For each size N of
--sizes, every construction and evaluation path of `lekalo.scipy` is timed against the SciPy
call it replaces, on the same arrays:

- data: N strictly increasing sites on [0, 10] (a jittered uniform grid), values
  sin(x) + 0.5 cos(3.1 x), plus noise of 0.01 for the smoothing fits (s = 1.2 N 0.01^2, twice that for the
  parametric fits of 2-D points);
  evaluation at N random points of [0, 10];
- construction workloads build an object (or a tuple) from N data points, or from a spline of
  N coefficients (BSpline, derivative, antiderivative, integrate, insert_knot, splder, ...);
  piecewise polynomials (PPoly, BPoly and the cubics) are timed with one evaluation after
  the construction, since lekalo.scipy defers its B-spline form to the first call;
- evaluation workloads evaluate a spline of 1000 data points at N random points (2-D: the
  RectBivariateSpline of a 100x100 grid, NdBSpline: a 20^3 grid, at N random points);
- scalar workloads: one Python float in (`spl(0.3)`, `splev(0.3, tck)`, ...), timed in a loop.

Workloads that loop over the points in Python on SciPy's side as well (`spalde`, whose
SciPy version calls FITPACK once a point) and SciPy's GCV choice of `lam` in
`make_smoothing_spline` are capped at --per-point-max points; SciPy's `make_ndbspl` (a sparse
solve of the whole system) runs on an --ndbspl-n^3 grid.

Every lekalo result is compared with SciPy's (values at 1000 check points, coefficients, or
the arrays returned): the largest difference relative to the largest SciPy value is printed.
Timing: the median of --repeats samples, each a call repeated to at least --sample seconds;
lekalo is timed just before and just after SciPy and the mean of the two medians is used, so
that a busy moment of a shared machine weighs on both sides. The goals: constructions at
least 5x SciPy, evaluations at least 10x, a scalar call at most 2 us. Results go to
docs/moving-from-scipy.md.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time
import warnings
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
import scipy
from scipy import interpolate as si

import lekalo
from lekalo import scipy as ls

# public from SciPy 1.18 on; from 1.12 in the private module
sp_make_ndbspl = getattr(si, "make_ndbspl", None)
if sp_make_ndbspl is None:
    from scipy.interpolate._ndbspline import make_ndbspl as sp_make_ndbspl

GOALS = {"construction": 5.0, "evaluation": 10.0}
SCALAR_GOAL_S = 2e-6


def timed(f: Callable[[], Any], repeats: int, sample: float) -> float:
    """Median seconds of one call of `f` over `repeats` samples of at least `sample` s each."""
    f()
    samples = []
    for _ in range(repeats):
        n, start = 0, time.perf_counter()
        while True:
            f()
            n += 1
            elapsed = time.perf_counter() - start
            if elapsed >= sample:
                break
        samples.append(elapsed / n)
    return statistics.median(samples)


def rel(a: Any, b: Any) -> float:
    """Largest |a - b| relative to the largest |b| (0 for equal empty arrays)."""
    a = np.asarray(a, dtype=complex if np.iscomplexobj(a) or np.iscomplexobj(b) else float)
    b = np.asarray(b, dtype=a.dtype)
    if a.shape != b.shape:
        return math.inf
    if b.size == 0:
        return 0.0
    scale = max(float(np.max(np.abs(b))), 1e-300)
    return float(np.max(np.abs(a - b))) / scale


def knot_rounds(ours: list, theirs: list) -> float | str:
    """The knot vectors of generate_knots: the largest difference when every round agrees in
    size, else how many leading rounds are the same and how many rounds each side makes."""
    if len(ours) == len(theirs) and all(a.shape == b.shape for a, b in zip(ours, theirs)):
        return max(rel(a, b) for a, b in zip(ours, theirs))
    same = 0
    while same < min(len(ours), len(theirs)) and rel(ours[same], theirs[same]) < 1e-12:
        same += 1
    return f"rounds: first {same} equal, {len(ours)} against {len(theirs)}"


@dataclass
class Case:
    name: str  # the SciPy call
    kind: str  # construction, evaluation, scalar
    n: int  # points or coefficients
    theirs: Callable[[], Any]
    ours: Callable[[], Any]
    agree: Callable[[Any, Any], float]  # (ours, theirs) -> relative difference


def data(n: int, rng: np.random.Generator):
    x = np.linspace(0.0, 10.0, n)
    x[1:-1] += rng.uniform(-0.3, 0.3, n - 2) * (10.0 / (n - 1))
    y = np.sin(x) + 0.5 * np.cos(3.1 * x)
    noisy = y + 0.01 * rng.standard_normal(n)
    return x, y, noisy


def cases(n: int, a: argparse.Namespace, rng: np.random.Generator) -> list[Case]:
    """The workloads at size n."""
    x, y, noisy = data(n, rng)
    xe = rng.uniform(0.0, 10.0, n)
    check = np.linspace(0.0, 10.0, 1001)
    s = 1.2 * n * 0.01**2  # a little above the noise: FITPACK stops with few knots
    out: list[Case] = []

    def add(name, kind, theirs, ours, agree=None, size=n):
        out.append(Case(name, kind, size, theirs, ours, agree or rel))

    def values(a_, b_):  # two callables, compared on the check points
        return rel(a_(check), b_(check))

    def tck_values(a_, b_):
        return rel(si.splev(check, tuple(a_)), si.splev(check, tuple(b_)))

    # a spline of n coefficients (SciPy's interpolant of the data), and a small one to evaluate
    big_s = si.make_interp_spline(x, y)
    big_l = ls.BSpline(big_s.t, big_s.c, big_s.k)
    t_big, c_big = big_s.t, big_s.c
    tck_big = (t_big, np.r_[c_big, np.zeros(4)], 3)
    xs, ys, _ = data(1000, np.random.default_rng(7))
    small_s = si.make_interp_spline(xs, ys)
    small_l = ls.BSpline(small_s.t, small_s.c, 3)
    tck_small = si.splrep(xs, ys)

    # BSpline
    add("BSpline(t, c, k)", "construction", lambda: si.BSpline(t_big, c_big, 3), lambda: ls.BSpline(t_big, c_big, 3),
        lambda o, t: rel(o.c, t.c))
    add("BSpline.__call__", "evaluation", lambda: small_s(xe), lambda: small_l(xe))
    add("BSpline.__call__(nu=1)", "evaluation", lambda: small_s(xe, 1), lambda: small_l(xe, 1))
    add("BSpline.derivative", "construction", lambda: big_s.derivative(), lambda: big_l.derivative(), values)
    add("BSpline.antiderivative", "construction", lambda: big_s.antiderivative(), lambda: big_l.antiderivative(), values)
    add("BSpline.integrate", "construction", lambda: big_s.integrate(0.5, 9.5), lambda: big_l.integrate(0.5, 9.5))
    add("BSpline.insert_knot", "construction", lambda: big_s.insert_knot(5.0), lambda: big_l.insert_knot(5.0), values)
    add("BSpline.design_matrix", "evaluation", lambda: si.BSpline.design_matrix(xe, small_s.t, 3),
        lambda: ls.BSpline.design_matrix(xe, small_s.t, 3), lambda o, t: float(abs(o - t).max()))

    # the make_* constructors
    add("make_interp_spline", "construction", lambda: si.make_interp_spline(x, y), lambda: ls.make_interp_spline(x, y), values)
    t_lsq = np.r_[(x[0],) * 4, np.linspace(x[0], x[-1], max(n // 20, 4))[1:-1], (x[-1],) * 4]
    add("make_lsq_spline", "construction", lambda: si.make_lsq_spline(x, noisy, t_lsq), lambda: ls.make_lsq_spline(x, noisy, t_lsq), values)
    add("make_smoothing_spline(lam)", "construction", lambda: si.make_smoothing_spline(x, noisy, lam=1e-3),
        lambda: ls.make_smoothing_spline(x, noisy, lam=1e-3), values)
    if n <= a.per_point_max:
        add("make_smoothing_spline (GCV)", "construction", lambda: si.make_smoothing_spline(x, noisy),
            lambda: ls.make_smoothing_spline(x, noisy), values)
    add("make_splrep", "construction", lambda: si.make_splrep(x, noisy, s=s), lambda: ls.make_splrep(x, noisy, s=s), values)
    pts = np.vstack([np.cos(x / 3), np.sin(x / 3)]) + 0.01 * rng.standard_normal((2, n))
    add("make_splprep", "construction", lambda: si.make_splprep(pts, s=2 * s)[0], lambda: ls.make_splprep(pts, s=2 * s)[0],
        lambda o, t: rel(o(np.linspace(0, 1, 1001)), t(np.linspace(0, 1, 1001))))
    add("generate_knots", "construction", lambda: list(si.generate_knots(x, noisy, s=s)),
        lambda: list(ls.generate_knots(x, noisy, s=s)), knot_rounds)

    # FITPACK's functions
    add("splrep (s=0)", "construction", lambda: si.splrep(x, y), lambda: ls.splrep(x, y), tck_values)
    add("splrep (s>0)", "construction", lambda: si.splrep(x, noisy, s=s), lambda: ls.splrep(x, noisy, s=s), tck_values)
    add("splprep", "construction", lambda: si.splprep(pts, s=2 * s)[0], lambda: ls.splprep(pts, s=2 * s)[0],
        lambda o, t: rel(si.splev(np.linspace(0, 1, 1001), o), si.splev(np.linspace(0, 1, 1001), t)))
    add("splev", "evaluation", lambda: si.splev(xe, tck_small), lambda: ls.splev(xe, tck_small))
    add("splev(der=1)", "evaluation", lambda: si.splev(xe, tck_small, 1), lambda: ls.splev(xe, tck_small, 1))
    add("splint", "construction", lambda: si.splint(0.5, 9.5, tck_big), lambda: ls.splint(0.5, 9.5, tck_big))
    # a cubic with 16 zeros, none at an end, n coefficients
    ts_ = np.r_[(0.0,) * 4, np.linspace(0, 10, n - 2)[1:-1], (10.0,) * 4]
    tck_roots = (ts_, np.r_[np.sin(np.linspace(0.1, 50, n)), np.zeros(4)], 3)
    add("sproot", "construction", lambda: si.sproot(tck_roots, mest=n), lambda: ls.sproot(tck_roots, mest=n))
    m = min(n, a.per_point_max)
    add("spalde", "evaluation", lambda: si.spalde(xe[:m], tck_small), lambda: ls.spalde(xe[:m], tck_small), size=m)
    add("splder", "construction", lambda: si.splder(tck_big), lambda: ls.splder(tck_big), tck_values)
    add("splantider", "construction", lambda: si.splantider(tck_big), lambda: ls.splantider(tck_big), tck_values)
    add("insert", "construction", lambda: si.insert(5.0, tck_big), lambda: ls.insert(5.0, tck_big), tck_values)

    # FITPACK's classes
    add("UnivariateSpline", "construction", lambda: si.UnivariateSpline(x, noisy, s=s), lambda: ls.UnivariateSpline(x, noisy, s=s), values)
    add("InterpolatedUnivariateSpline", "construction", lambda: si.InterpolatedUnivariateSpline(x, y),
        lambda: ls.InterpolatedUnivariateSpline(x, y), values)
    add("LSQUnivariateSpline", "construction", lambda: si.LSQUnivariateSpline(x, noisy, t_lsq[4:-4]),
        lambda: ls.LSQUnivariateSpline(x, noisy, t_lsq[4:-4]), values)
    us_s, us_l = si.UnivariateSpline(xs, ys, s=0), ls.UnivariateSpline(xs, ys, s=0)
    add("UnivariateSpline.__call__", "evaluation", lambda: us_s(xe), lambda: us_l(xe))

    # 2-D
    g = int(round(math.sqrt(n)))
    gx, gy = np.linspace(0, 1, g), np.linspace(0, 2, g)
    z = np.sin(3 * gx)[:, None] * np.cos(2 * gy)[None, :]
    add(f"RectBivariateSpline ({g}x{g})", "construction", lambda: si.RectBivariateSpline(gx, gy, z),
        lambda: ls.RectBivariateSpline(gx, gy, z), lambda o, t: rel(o.ev(check / 10, check / 5), t.ev(check / 10, check / 5)), g * g)
    hx, hy = np.linspace(0, 1, 100), np.linspace(0, 2, 100)
    hz = np.sin(3 * hx)[:, None] * np.cos(2 * hy)[None, :]
    rb_s, rb_l = si.RectBivariateSpline(hx, hy, hz), ls.RectBivariateSpline(hx, hy, hz)
    ex, ey = xe / 10, rng.uniform(0, 2, n)
    add("RectBivariateSpline.ev", "evaluation", lambda: rb_s.ev(ex, ey), lambda: rb_l.ev(ex, ey))
    add(f"RectBivariateSpline.__call__ ({g}x{g} grid)", "evaluation", lambda: rb_s(gx, gy), lambda: rb_l(gx, gy), size=g * g)
    tck2 = (rb_s.tck[0], rb_s.tck[1], rb_s.tck[2], 3, 3)
    add(f"bisplev ({g}x{g} grid)", "evaluation", lambda: si.bisplev(gx, gy, tck2), lambda: ls.bisplev(gx, gy, tck2), size=g * g)
    sx, sy = rng.uniform(0, 1, n), rng.uniform(0, 2, n)
    sz = np.sin(3 * sx) * np.cos(2 * sy) + 0.01 * rng.standard_normal(n)
    ktx, kty = np.linspace(0, 1, 12)[1:-1], np.linspace(0, 2, 12)[1:-1]
    add("LSQBivariateSpline", "construction", lambda: si.LSQBivariateSpline(sx, sy, sz, ktx, kty),
        lambda: ls.LSQBivariateSpline(sx, sy, sz, ktx, kty), lambda o, t: rel(o.ev(check / 10, check / 5), t.ev(check / 10, check / 5)))

    # piecewise polynomials; construction timed with one evaluation after it (see above)
    dydx = np.cos(x) - 1.55 * np.sin(3.1 * x)
    for name, sp_make, ls_make in (
        ("CubicSpline", lambda: si.CubicSpline(x, y), lambda: ls.CubicSpline(x, y)),
        ("PchipInterpolator", lambda: si.PchipInterpolator(x, y), lambda: ls.PchipInterpolator(x, y)),
        ("Akima1DInterpolator", lambda: si.Akima1DInterpolator(x, y), lambda: ls.Akima1DInterpolator(x, y)),
        ("CubicHermiteSpline", lambda: si.CubicHermiteSpline(x, y, dydx), lambda: ls.CubicHermiteSpline(x, y, dydx)),
    ):
        add(name, "construction", lambda f=sp_make: f()(0.3), lambda f=ls_make: f()(0.3))
        out[-1].agree = lambda o, t, f=sp_make, g_=ls_make: values(g_(), f())
    for name, cls_s, cls_l in (("CubicSpline", si.CubicSpline, ls.CubicSpline),
                               ("PchipInterpolator", si.PchipInterpolator, ls.PchipInterpolator),
                               ("Akima1DInterpolator", si.Akima1DInterpolator, ls.Akima1DInterpolator)):
        ps, pl = cls_s(xs, ys), cls_l(xs, ys)
        add(f"{name}.__call__", "evaluation", lambda p=ps: p(xe), lambda p=pl: p(xe))
    ch_s = si.CubicHermiteSpline(xs, ys, np.cos(xs))
    ch_l = ls.CubicHermiteSpline(xs, ys, np.cos(xs))
    add("CubicHermiteSpline.__call__", "evaluation", lambda: ch_s(xe), lambda: ch_l(xe))
    cs_big = si.CubicSpline(x, y)  # breakpoints at the data, none repeated
    pp_big = si.PPoly(cs_big.c, cs_big.x)
    cpp, xpp = pp_big.c, pp_big.x
    add("PPoly(c, x)", "construction", lambda: si.PPoly(cpp, xpp)(0.3), lambda: ls.PPoly(cpp, xpp)(0.3))
    out[-1].agree = lambda o, t: values(ls.PPoly(cpp, xpp), si.PPoly(cpp, xpp))
    add("PPoly.from_spline", "construction", lambda: si.PPoly.from_spline(tck_big)(0.3), lambda: ls.PPoly.from_spline(tck_big)(0.3))
    out[-1].agree = lambda o, t: values(ls.PPoly.from_spline(tck_big), si.PPoly.from_spline(tck_big))
    bp_big = si.BPoly.from_power_basis(pp_big)
    cbp = bp_big.c
    add("BPoly(c, x)", "construction", lambda: si.BPoly(cbp, xpp)(0.3), lambda: ls.BPoly(cbp, xpp)(0.3))
    out[-1].agree = lambda o, t: values(ls.BPoly(cbp, xpp), si.BPoly(cbp, xpp))
    pp_small_s = si.PPoly.from_spline(small_s)
    pp_s, pp_l = si.PPoly(pp_small_s.c, pp_small_s.x), ls.PPoly(pp_small_s.c, pp_small_s.x)
    add("PPoly.__call__", "evaluation", lambda: pp_s(xe), lambda: pp_l(xe))
    bp_small = si.BPoly.from_power_basis(pp_small_s)
    bp_s, bp_l = si.BPoly(bp_small.c, bp_small.x), ls.BPoly(bp_small.c, bp_small.x)
    add("BPoly.__call__", "evaluation", lambda: bp_s(xe), lambda: bp_l(xe))

    # N variables
    nd_small = ls.make_ndbspl([np.linspace(0, 1, 20)] * 3, np.random.default_rng(3).standard_normal((20, 20, 20)))
    r = a.ndbspl_n
    axes_r = [np.linspace(0, 1, r)] * 3
    vals_r = np.cos(3 * axes_r[0])[:, None, None] * np.sin(2 * axes_r[1])[None, :, None] * (1 + axes_r[2])[None, None, :]
    from scipy.sparse.linalg import spsolve

    add(f"make_ndbspl ({r}^3, spsolve)", "construction", lambda: sp_make_ndbspl(axes_r, vals_r, k=3, solver=spsolve),
        lambda: ls.make_ndbspl(axes_r, vals_r, k=3), lambda o, t: rel(o.c, t.c), size=r**3)
    nd_s = si.NdBSpline(nd_small.t, nd_small.c, 3)
    xi = rng.uniform(0, 1, (n, 3))
    add("NdBSpline.__call__ (20^3)", "evaluation", lambda: nd_s(xi), lambda: nd_small(xi))

    # scalar calls (n is irrelevant; kept once, at the first size)
    if n == a.sizes[0]:
        for name, fs, fl in (
            ("BSpline(0.3)", lambda: small_s(0.3), lambda: small_l(0.3)),
            ("splev(0.3, tck)", lambda: si.splev(0.3, tck_small), lambda: ls.splev(0.3, tck_small)),
            ("UnivariateSpline(0.3)", lambda: us_s(0.3), lambda: us_l(0.3)),
            ("CubicSpline(0.3)", lambda: ps(0.3), lambda: pl(0.3)),
            ("PPoly(0.3)", lambda: pp_s(0.3), lambda: pp_l(0.3)),
            ("BPoly(0.3)", lambda: bp_s(0.3), lambda: bp_l(0.3)),
            ("CubicHermiteSpline(0.3)", lambda: ch_s(0.3), lambda: ch_l(0.3)),
            ("RectBivariateSpline.ev(0.3, 0.3)", lambda: rb_s.ev(0.3, 0.3), lambda: rb_l.ev(0.3, 0.3)),
            ("bisplev(0.3, 0.3, tck)", lambda: si.bisplev(0.3, 0.3, tck2), lambda: ls.bisplev(0.3, 0.3, tck2)),
            ("NdBSpline((0.3, 0.3, 0.3))", lambda: nd_s((0.3, 0.3, 0.3)), lambda: nd_small((0.3, 0.3, 0.3))),
        ):
            add(name, "scalar", fs, fl, size=1)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=lambda v: [int(s) for s in v.split(",")], default=[100_000, 1_000_000])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sample", type=float, default=0.02, help="least seconds of one timing sample")
    ap.add_argument("--only", help="only the workloads whose name contains this text")
    ap.add_argument("--per-point-max", type=int, default=100_000)
    ap.add_argument("--ndbspl-n", type=int, default=20)
    a = ap.parse_args()
    print(f"lekalo {lekalo.__version__}, SciPy {scipy.__version__}, NumPy {np.__version__}; "
          f"{os.cpu_count()} processors, load average {os.getloadavg()[0]:.1f}; median of {a.repeats}")
    rows = []
    for n in a.sizes:
        rng = np.random.default_rng(n)
        for c in cases(n, a, rng):
            if a.only and a.only not in c.name:
                continue
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ours = c.ours()
                try:
                    theirs = c.theirs()
                except Exception as e:  # SciPy fails on this workload: lekalo timed alone
                    failed = f"SciPy raises {type(e).__name__}: {str(e).splitlines()[0][:60]}"
                    mean = timed(c.ours, a.repeats, a.sample)
                    rows.append((c, math.nan, mean, math.nan, "-", True, failed, 0.0))
                    print(f"  {c.name} [{c.kind}, {c.n:,}]: lekalo {mean:.3g} s; {failed}", flush=True)
                    continue
                diff = c.agree(ours, theirs)
                before = timed(c.ours, a.repeats, a.sample)
                sp = timed(c.theirs, a.repeats, a.sample)
                after = timed(c.ours, a.repeats, a.sample)
            mean = (before + after) / 2
            ratio = sp / mean
            if c.kind == "scalar":
                met = mean <= SCALAR_GOAL_S
                goal = "<= 2 us"
            else:
                met = ratio >= GOALS[c.kind]
                goal = f">= {GOALS[c.kind]:.0f}x"
            rows.append((c, sp, mean, ratio, goal, met, diff, abs(after - before) / min(after, before)))
            print(f"  {c.name} [{c.kind}, {c.n:,}]: SciPy {sp:.3g} s, lekalo {mean:.3g} s, {ratio:.1f}x, "
                  f"{'met' if met else 'MISSED'}, difference {diff if isinstance(diff, str) else f'{diff:.1e}'}", flush=True)

    print()
    print("| SciPy call | kind | N | SciPy s | lekalo s | ratio | goal | met | max difference (relative) | lekalo before/after |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for c, sp, ours, ratio, goal, met, diff, spread in rows:
        agree = diff if isinstance(diff, str) else f"{diff:.1e}"
        print(f"| `{c.name}` | {c.kind} | {c.n:,} | {sp:.3g} | {ours:.3g} | {ratio:.1f}x | {goal} | "
              f"{'yes' if met else '**no**'} | {agree} | {100 * spread:.0f} % apart |")
    missed = [c.name for c, *_, met, _, _ in rows if not met]
    print(f"\n{len(rows) - len(missed)} of {len(rows)} workloads meet their goal"
          + (f"; missed: {', '.join(sorted(set(missed)))}" if missed else ""))


if __name__ == "__main__":
    main()
