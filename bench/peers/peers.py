"""Times the Python peers on the workload files written by `examples/peer_bench.rs` and prints one
table of medians next to lekalo's, with the ratio peer / lekalo, plus agreement checks.

Workloads (data and our results from `peer_bench`, little-endian f64 files):
- eval_*: cubic 3-D B-spline, 1000 control points, 10^6 parameters (ns per parameter);
- interp_N: cubic global interpolation through N 3-D points of a wobbly helix, chord-length
  parameters, averaged knots (ns per point);
- surface_N: bicubic interpolation of an N x N grid, averaged chord-length parameters (ns per
  grid point);
- elevate_A_B: Bezier degree elevation A -> B of one 3-D curve (µs per curve).

Usage: peers.py DATA_DIR REPEATS [PEER_BENCH [OCCT_BENCH]]  (run through bench/peers/run.sh)
- with the path of the peer_bench binary, lekalo is timed again, workload by workload, just
  before and just after that workload's peers, and the ratios use the mean of those two timings,
  so that both sides of a ratio fall in the same few seconds of a shared, noisy machine;
- with the path of the C++ harness built from occt_bench.cpp, Open CASCADE is also timed in C++,
  inside the same brackets.
Without PEER_BENCH the ratios use the timings in DATA_DIR/ours.json.
"""
import functools

import json
import math
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

# shortest time of one timed sample: quick calls are repeated inside a sample up to this
# (the same rule as peer_bench.rs)
MIN_SAMPLE_SECS = 0.02
# the OCP array fill costs several µs per point in Python: above this size it is timed once
OCP_FILL_ONCE_ABOVE = 10_000


def median_ns(fn, units, repeats):
    """Median wall time of `repeats` samples of fn (after one warm-up call that also sets how many
    calls make one sample), in ns per unit."""
    t0 = time.perf_counter()
    fn()
    once = time.perf_counter() - t0
    inner = max(1, math.ceil(MIN_SAMPLE_SECS / max(once, 1e-9)))
    times = []
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        times.append((time.perf_counter() - t0) / inner)
    return statistics.median(times) * 1e9 / units


def rel(a, b, scale=None):
    """max |a - b| / max |b| (or / scale)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.abs(a - b).max() / (np.abs(b).max() if scale is None else scale)


def try_import(what, fn):
    try:
        return fn()
    except ImportError:
        print(f"peers: {what} not installed; skipped", file=sys.stderr)
        return None


class Table:
    def __init__(self, ours):
        self.ours = ours
        self.rows = []  # (workload, unit, our two keys, peer, peer figure, note)

    def add(self, work, peer, value, note, unit="ns/pt", keys=("fast", "parallel_2")):
        # our figures are looked up when printing (`ours` may by then hold the bracketed means)
        self.rows.append((work, unit, keys, peer, value, note))

    def print(self):
        # grouped by workload, in the order the workloads first appear (the C++ peers come last)
        first = {}
        for i, row in enumerate(self.rows):
            first.setdefault(row[0], i)
        self.rows.sort(key=lambda row: first[row[0]])
        print(f"{'workload':<16} {'unit':<8} {'lekalo':>9} {'alt':>9}  {'peer':<40} "
              f"{'peer':>10} {'ratio':>7} {'/alt':>7}  note")
        for work, unit, keys, peer, value, note in self.rows:
            o = self.ours[work]
            ours, alt = o.get(keys[0], math.nan), o.get(keys[1], math.nan)
            if "reference" in o:
                note = f"lekalo ref {o['reference']:.1f}; {note}"
            scale = 1e-3 if unit == "µs/curve" else 1.0
            ratio = value / ours
            ralt = f"{value / alt:>6.1f}x" if not math.isnan(alt) else f"{'':>7}"
            altf = f"{alt * scale:>9.2f}" if not math.isnan(alt) else f"{'–':>9}"
            print(f"{work:<16} {unit:<8} {ours * scale:>9.2f} {altf}  {peer:<40} "
                  f"{value * scale:>10.2f} {ratio:>6.1f}x {ralt}  {note}")


def evaluation(data, meta, repeats, table, f64):
    """eval_sorted, eval_random, deriv1_sorted: SciPy, tinyspline, geomdl and OCP."""
    p, dim, n_ctrl, n = meta["degree"], meta["dim"], meta["n_ctrl"], meta["n"]
    knots = f64("knots.bin")
    ctrl = f64("ctrl.bin").reshape(n_ctrl, dim)
    params = {"sorted": f64("ts_sorted.bin"), "random": f64("ts_random.bin")}
    scale = np.abs(ctrl).max()

    from scipy.interpolate import BSpline

    spl = BSpline(knots, ctrl, p)
    for order, x in params.items():
        ns = median_ns(lambda: spl(x), n, repeats)
        ref = f64(f"ours_eval_{order}.bin").reshape(n, dim)
        err = rel(spl(x), ref, scale)
        table.add(f"eval_{order}", "scipy BSpline", ns, f"diff {err:.1e} rel")
    x = params["sorted"]
    ns = median_ns(lambda: spl(x, nu=1), n, repeats)
    err = rel(f64("ours_deriv1_sorted.bin").reshape(n, dim), spl(x, nu=1))
    table.add("deriv1_sorted", "scipy BSpline(nu=1)", ns, f"diff {err:.1e} rel")

    sub = 100_000
    ts = try_import("tinyspline", lambda: __import__("tinyspline"))
    if ts:
        s = ts.BSpline(n_ctrl, dim, p, ts.BSpline.Opened)
        s.control_points = ctrl.ravel().tolist()
        s.knots = knots.tolist()
        for order, x in params.items():
            xs = x[:sub].tolist()
            ns = median_ns(lambda: s.eval_all(xs), sub, repeats)
            got = np.array(s.eval_all(xs)).reshape(sub, dim)
            err = rel(got, f64(f"ours_eval_{order}.bin").reshape(n, dim)[:sub], scale)
            table.add(f"eval_{order}", "tinyspline eval_all (10^5)", ns, f"diff {err:.1e} rel")

    geomdl = try_import("geomdl", lambda: __import__("geomdl.BSpline").BSpline)
    if geomdl:
        g = geomdl.Curve()
        g.degree = p
        g.ctrlpts = ctrl.tolist()
        g.knotvector = knots.tolist()
        gsub = 10_000
        for order, x in params.items():
            xs = x[:gsub].tolist()
            ns = median_ns(lambda: g.evaluate_list(xs), gsub, max(1, repeats // 3))
            table.add(f"eval_{order}", "geomdl evaluate_list (10^4)", ns, "pure Python")

    ocp = ocp_modules()
    if ocp:
        poles = ocp["Array1_Pnt"](1, n_ctrl)
        for i, c in enumerate(ctrl.tolist()):
            poles.SetValue(i + 1, ocp["gp_Pnt"](*c))
        distinct, mults = np.unique(knots, return_counts=True)
        kn = ocp["Array1_Real"](1, len(distinct))
        mu = ocp["Array1_Int"](1, len(distinct))
        for i, (k, m) in enumerate(zip(distinct, mults)):
            kn.SetValue(i + 1, float(k))
            mu.SetValue(i + 1, int(m))
        adaptor = ocp["GeomAdaptor_Curve"](ocp["Geom_BSplineCurve"](poles, kn, mu, p))
        value = adaptor.Value
        for order, x in params.items():
            xs = x[:sub].tolist()
            ns = median_ns(lambda: [value(t) for t in xs], sub, max(1, repeats // 2))
            # one Python call per point, each returning a new gp_Pnt: this measures the
            # binding (~1-3 µs), not Open CASCADE's C++ evaluator (≈25 ns/point in its C++ harness)
            table.add(f"eval_{order}", "OCP GeomAdaptor_Curve.Value (10^5)", ns,
                      "one Python call per point: the binding")


@functools.cache
def ocp_modules():
    """The OCP names used here, for OCP 7.x and cadquery-ocp 8 (generic collections), or None
    (said once) when OCP is not installed."""
    return try_import("OCP (cadquery-ocp)", _ocp_modules)


def _ocp_modules():
    from OCP.Approx import Approx_ParametrizationType
    from OCP.Geom import Geom_BSplineCurve
    from OCP.GeomAdaptor import GeomAdaptor_Curve
    from OCP.GeomAPI import GeomAPI_Interpolate, GeomAPI_PointsToBSplineSurface
    from OCP.gp import gp_Pnt

    try:  # OCP 7.x names
        from OCP.TColgp import TColgp_Array1OfPnt as Array1_Pnt
        from OCP.TColgp import TColgp_Array2OfPnt as Array2_Pnt
        from OCP.TColgp import TColgp_HArray1OfPnt as HArray1_Pnt
        from OCP.TColStd import TColStd_Array1OfInteger as Array1_Int
        from OCP.TColStd import TColStd_Array1OfReal as Array1_Real
        from OCP.TColStd import TColStd_HArray1OfReal as HArray1_Real
    except ImportError:  # cadquery-ocp 8
        from OCP.OCP.collections import Array1_double as Array1_Real
        from OCP.OCP.collections import Array1_gp_Pnt as Array1_Pnt
        from OCP.OCP.collections import Array1_int as Array1_Int
        from OCP.OCP.collections import Array2_gp_Pnt as Array2_Pnt
        from OCP.OCP.collections import HArray1_double as HArray1_Real
        from OCP.OCP.collections import HArray1_gp_Pnt as HArray1_Pnt
    return dict(locals())


def interpolation(meta, repeats, table, f64, sizes):
    """interp_N for N in sizes: SciPy three ways and OCP three ways."""
    from scipy.interpolate import BSpline, make_interp_spline

    keys = ("fresh", "workspace")
    ocp = ocp_modules()
    for n in sizes:
        work = f"interp_{n}"
        q = f64(f"interp_q_{n}.bin").reshape(n, 3)
        t = f64(f"interp_t_{n}.bin")
        knots = f64(f"interp_knots_{n}.bin")
        ours = f64(f"interp_ctrl_{n}.bin").reshape(-1, 3)
        scale = np.abs(q).max()
        ours_err = rel(BSpline(knots, ours, 3)(t), q, scale)

        ns = median_ns(lambda: make_interp_spline(t, q, k=3), n, repeats)
        s = make_interp_spline(t, q, k=3)
        err = rel(s(t), q, scale)
        table.add(work, "scipy make_interp_spline (not-a-knot)", ns,
                  f"at data {err:.1e}", keys=keys)

        ns = median_ns(lambda: make_interp_spline(t, q, k=3, t=knots), n, repeats)
        s = make_interp_spline(t, q, k=3, t=knots)
        err = rel(s(t), q, scale)
        cerr = rel(s.c, ours)
        table.add(work, "scipy make_interp_spline(t=our knots)", ns,
                  f"at data {err:.1e} (ours {ours_err:.1e}); ctrl vs ours {cerr:.1e}",
                  keys=keys)

        # the whole workload as a SciPy user writes it: chord-length parameters by NumPy, then
        # the solve (the rows above are handed our parameters and knots, which lekalo's time
        # includes computing)
        def chord_params():
            d = np.linalg.norm(np.diff(q, axis=0), axis=1)
            s = np.concatenate(([0.0], np.cumsum(d)))
            return s / s[-1]

        def averaged_knots(tt):
            # u_{j+3} = (t_j + t_{j+1} + t_{j+2}) / 3, j = 1 .. n-4 (document 000 eq. 3)
            inner = np.convolve(tt[1:-1], np.ones(3) / 3.0, mode="valid")
            return np.concatenate((np.zeros(4), inner, np.ones(4)))

        def scipy_whole():
            tt = chord_params()
            return make_interp_spline(tt, q, k=3, t=averaged_knots(tt))

        ns = median_ns(scipy_whole, n, repeats)
        s = scipy_whole()
        table.add(work, "scipy NumPy chord+knots, make_interp_spline", ns,
                  f"whole workload; at data {rel(s(t), q, scale):.1e}; "
                  f"ctrl vs ours {rel(s.c, ours):.1e}", keys=keys)

        if ocp:
            gp = ocp["gp_Pnt"]
            ql, tl = q.tolist(), t.tolist()

            def fill():
                pts = ocp["HArray1_Pnt"](1, n)
                par = ocp["HArray1_Real"](1, n)
                for i, (x, y, z) in enumerate(ql):
                    pts.SetValue(i + 1, gp(x, y, z))
                for i, v in enumerate(tl):
                    par.SetValue(i + 1, v)
                return pts, par

            t0 = time.perf_counter()
            pts, par = fill()
            fill_ns = (time.perf_counter() - t0) * 1e9 / n
            if n <= OCP_FILL_ONCE_ABOVE:
                fill_ns = median_ns(fill, n, repeats)

            def solve():
                it = ocp["GeomAPI_Interpolate"](pts, par, False, 1e-12)
                it.Perform()
                return it.Curve()

            ns = median_ns(solve, n, repeats)
            c = solve()
            step = max(1, n // 2000)
            err = max(c.Value(tl[i]).Distance(gp(*ql[i])) for i in range(0, n, step)) / scale
            # Open CASCADE's own scheme: knots at all the parameters, n + 2 poles (two end
            # conditions of its own), so only the fit at the data is compared
            table.add(work, "OCP GeomAPI_Interpolate (solve)", ns,
                      f"at data {err:.1e}; {c.NbPoles()} poles", keys=keys)
            once = " (fill timed once)" if n > OCP_FILL_ONCE_ABOVE else ""
            table.add(work, "OCP GeomAPI_Interpolate (fill+solve)", fill_ns + ns,
                      f"array fill {fill_ns:.0f} ns/pt{once}", keys=keys)

            # the whole workload in Open CASCADE: its own chord-length parameters (cumulative
            # distances, not normalised) and the solve
            def solve_own():
                it = ocp["GeomAPI_Interpolate"](pts, False, 1e-12)
                it.Perform()
                return it.Curve()

            ns = median_ns(solve_own, n, repeats)
            c = solve_own()
            dist = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))))
            sl = (dist * (c.LastParameter() / dist[-1])).tolist()
            err = max(c.Value(sl[i]).Distance(gp(*ql[i])) for i in range(0, n, step)) / scale
            table.add(work, "OCP GeomAPI_Interpolate (own params+solve)", ns,
                      f"whole workload; at data {err:.1e}", keys=keys)


def at_grid(ku, kv, ctrl, u, v, g):
    """max |S(u_k, v_l) - q_kl| / max |q| for the tensor-product cubic with control net ctrl."""
    from scipy.interpolate import BSpline

    bu = BSpline.design_matrix(u, ku, 3).toarray()
    bv = BSpline.design_matrix(v, kv, 3).toarray()
    s = np.einsum("ki,ijc,lj->klc", bu, ctrl, bv, optimize=True)
    return rel(s, g, np.abs(g).max())


def surface(meta, repeats, table, f64, sizes):
    """surface_N for N in sizes: SciPy's two passes and OCP."""
    from scipy.interpolate import make_interp_spline

    keys = ("fresh", "-")
    ocp = ocp_modules()
    for n in sizes:
        work = f"surface_{n}"
        g = f64(f"surf_q_{n}.bin").reshape(n, n, 3)
        u, v = f64(f"surf_u_{n}.bin"), f64(f"surf_v_{n}.bin")
        ku, kv = f64(f"surf_ku_{n}.bin"), f64(f"surf_kv_{n}.bin")
        ours = f64(f"surf_ctrl_{n}.bin").reshape(n, n, 3)
        scale = np.abs(g).max()

        def two_pass(tu=None, tv=None):
            # u pass: all n*3 numbers of a grid row as right-hand sides; then the v pass on
            # the transposed intermediate net
            a = make_interp_spline(u, g.reshape(n, n * 3), k=3, t=tu).c.reshape(n, n, 3)
            b = a.transpose(1, 0, 2).reshape(n, n * 3)
            return make_interp_spline(v, b, k=3, t=tv).c.reshape(n, n, 3).transpose(1, 0, 2)

        ns = median_ns(lambda: two_pass(ku, kv), n * n, repeats)
        got = two_pass(ku, kv)
        table.add(work, "scipy 2-pass make_interp_spline(t=ours)", ns,
                  f"at data {at_grid(ku, kv, got, u, v, g):.1e} "
                  f"(ours {at_grid(ku, kv, ours, u, v, g):.1e}); "
                  f"ctrl vs ours {rel(got, ours):.1e}", keys=keys)
        ns = median_ns(lambda: two_pass(), n * n, repeats)
        table.add(work, "scipy 2-pass make_interp_spline", ns, "not-a-knot", keys=keys)

        if ocp:
            gl = g.tolist()
            gp = ocp["gp_Pnt"]

            def fill():
                a = ocp["Array2_Pnt"](1, n, 1, n)
                for k in range(n):
                    for l in range(n):
                        a.SetValue(k + 1, l + 1, gp(*gl[k][l]))
                return a

            t0 = time.perf_counter()
            arr = fill()
            fill_ns = (time.perf_counter() - t0) * 1e9 / (n * n)
            chord = ocp["Approx_ParametrizationType"].Approx_ChordLength

            def solve():
                s = ocp["GeomAPI_PointsToBSplineSurface"]()
                s.Interpolate(arr, chord)
                return s.Surface()

            ns = median_ns(solve, n * n, max(1, repeats // 2))
            s = solve()
            # its knots are its parameters: check the surface at a sub-grid of the data
            idx = range(0, n, max(1, n // 40))
            err = max(s.Value(s.UKnot(k + 1), s.VKnot(l + 1)).Distance(gp(*gl[k][l]))
                      for k in idx for l in idx) / scale
            table.add(work, "OCP PointsToBSplineSurface.Interpolate", ns,
                      f"at data {err:.1e}; fill {fill_ns:.0f} ns/pt more", keys=keys)


def elevation(meta, repeats, table, f64, pairs):
    """elevate_A_B for (A, B) in pairs: NumPy, tinyspline and bezier."""
    from math import comb

    keys = ("plan", "elevate_degree")
    unit = "µs/curve"
    ts = try_import("tinyspline", lambda: __import__("tinyspline"))
    bz = try_import("bezier", lambda: __import__("bezier"))
    for a, b in pairs:
        work = f"elevate_{a}_{b}"
        p = f64(f"elev_in_{a}_{b}.bin").reshape(a + 1, 3)
        ours = f64(f"elev_out_{a}_{b}.bin").reshape(b + 1, 3)
        r = b - a

        # NumPy with the (b+1) x (a+1) matrix C(a,i) C(r,j-i) / C(b,j) precomputed (as our plan)
        m = np.array([[comb(a, i) * comb(r, j - i) / comb(b, j) if 0 <= j - i <= r else 0.0
                       for i in range(a + 1)] for j in range(b + 1)])
        ns = median_ns(lambda: m @ p, 1, repeats)
        table.add(work, "NumPy M @ P (M precomputed)", ns,
                  f"diff {rel(m @ p, ours):.1e} rel", unit=unit, keys=keys)

        if ts:
            s = ts.BSpline(a + 1, 3, a, ts.BSpline.Clamped)
            s.control_points = p.ravel().tolist()
            ns = median_ns(lambda: s.elevate_degree(r), 1, repeats)
            got = np.array(s.elevate_degree(r).control_points).reshape(-1, 3)
            note = (f"diff {rel(got, ours):.1e} rel" if got.shape == ours.shape
                    else f"{len(got)} points, not {b + 1}")
            table.add(work, "tinyspline BSpline.elevate_degree", ns, note, unit=unit, keys=keys)

        if bz:
            nodes = np.asfortranarray(p.T)

            def by_one():
                c = bz.Curve(nodes, a, copy=False, verify=False)
                for _ in range(r):
                    c = c.elevate()
                return c

            ns = median_ns(by_one, 1, repeats)
            got = by_one().nodes.T
            table.add(work, f"bezier Curve.elevate() x{r}", ns,
                      f"diff {rel(got, ours):.1e} rel", unit=unit, keys=keys)


def occt_cpp(binary, data, meta, repeats, table, evaluate=False, interp=(), surf=(), elev=()):
    """Open CASCADE timed in C++ by the harness built from occt_bench.cpp, on the same files: its
    geometry kernel without a Python binding's per-call cost. Only the workloads named."""
    args = [binary, str(data), str(repeats), str(meta["n_ctrl"]), str(meta["n"] if evaluate else 0),
            ",".join(map(str, interp)), ",".join(map(str, surf)),
            ";".join(f"{a},{b}" for a, b in elev)]
    out = subprocess.run(args, check=True, stdout=subprocess.PIPE, text=True).stdout
    for line in out.splitlines():
        work, peer, ns, note = line.split("\t")
        if work.startswith("interp_"):
            keys, unit = ("fresh", "workspace"), "ns/pt"
        elif work.startswith("surface_"):
            keys, unit = ("fresh", "-"), "ns/pt"
        elif work.startswith("elevate_"):
            keys, unit = ("plan", "elevate_degree"), "µs/curve"
        else:
            keys, unit = ("fast", "parallel_2"), "ns/pt"
        table.add(work, peer, float(ns), note, unit=unit, keys=keys)


def time_ours(binary, data, repeats, works):
    """lekalo's medians for the named workloads, from a timings-only run of peer_bench."""
    subprocess.run([binary, str(data), str(repeats), "ours_bracket.json", ",".join(works)],
                   check=True, stdout=subprocess.DEVNULL)
    return json.loads((data / "ours_bracket.json").read_text())["results"]


def bracket(before, after):
    """lekalo's figures as the mean of its medians timed before and after the peers, so that a
    slow spell of the shared machine weighs on both sides alike; also the largest relative change
    between the two timings, per workload."""
    combined, change = {}, {}
    for work, keys in before.items():
        combined[work] = dict(keys)
        for key, b in keys.items():
            a = after.get(work, {}).get(key)
            if isinstance(b, (int, float)) and isinstance(a, (int, float)):
                combined[work][key] = (a + b) / 2
                change[work] = max(change.get(work, 0.0), abs(a - b) / min(a, b))
    return combined, change


def main():
    data = Path(sys.argv[1])
    repeats = int(sys.argv[2])
    ours_again = sys.argv[3] if len(sys.argv) > 3 else None
    occt = sys.argv[4] if len(sys.argv) > 4 else None
    meta = json.loads((data / "ours.json").read_text())
    f64 = lambda name: np.fromfile(data / name, dtype="<f8")
    table = Table(meta["results"])
    # (workloads, their Python peers, the same workloads in the C++ harness)
    groups = [(["eval_sorted", "eval_random", "deriv1_sorted"],
               lambda: evaluation(data, meta, repeats, table, f64), {"evaluate": True})]
    groups += [([f"interp_{n}"], functools.partial(interpolation, meta, repeats, table, f64, [n]),
                {"interp": [n]}) for n in meta["interp_sizes"]]
    groups += [([f"surface_{n}"], functools.partial(surface, meta, repeats, table, f64, [n]),
                {"surf": [n]}) for n in meta["surface_sizes"]]
    groups += [([f"elevate_{a}_{b}"],
                functools.partial(elevation, meta, repeats, table, f64, [(a, b)]),
                {"elev": [(a, b)]}) for a, b in meta["elevations"]]
    before, after = {}, {}
    t0 = time.perf_counter()
    for works, python_peers, cpp in groups:
        if ours_again:
            before.update(time_ours(ours_again, data, repeats, works))
        python_peers()
        if occt:
            occt_cpp(occt, data, meta, repeats, table, **cpp)
        if ours_again:
            after.update(time_ours(ours_again, data, repeats, works))
    secs = time.perf_counter() - t0
    if ours_again:
        table.ours, change = bracket(before, after)
        print()
        print("lekalo timed again just before and just after each workload's peers; the ratios "
              "use the mean of those two medians. Their largest change, per workload:")
        print("  " + ", ".join(f"{w} {c * 100:.0f}%" for w, c in change.items()))
    print()
    print(f"medians of {repeats} samples (short calls repeated within a sample to >= "
          f"{MIN_SAMPLE_SECS * 1e3:.0f} ms); ratio = peer / lekalo, /alt = peer / lekalo alt")
    print("lekalo | alt: eval = fast | parallel(2); interp = fresh | InterpolationWorkspace; "
          "surface = interpolate_surface; elevate = ElevationPlan::apply_into | "
          "BezierCurve::elevate_degree")
    table.print()
    try:
        from numpy._core import multiarray
        thp = multiarray._get_madvise_hugepage()
    except (ImportError, AttributeError):
        thp = "unknown"
    print(f"NumPy madvise(MADV_HUGEPAGE) for large arrays: {thp}; lekalo gives the same hint "
          "for its result buffers of 4 MiB and more")
    print(f"(peers{' and brackets' if ours_again else ''} took {secs:.0f} s)")


if __name__ == "__main__":
    main()
