"""Times the Python peers on the workload files written by `examples/peer_bench.rs` and prints a
table of medians (ns per point) next to lekalo's, with the ratio peer / lekalo.

Usage: peers.py DATA_DIR REPEATS  (run through bench/peers/run.sh)
"""

import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np


def median_ns(fn, points, repeats):
    """Median wall time of `repeats` calls of fn (after one warm-up), in ns per point."""
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times) * 1e9 / points


def main():
    data = Path(sys.argv[1])
    repeats = int(sys.argv[2])
    meta = json.loads((data / "ours.json").read_text())
    p, dim, n_ctrl, n = meta["degree"], meta["dim"], meta["n_ctrl"], meta["n"]
    ours = meta["results"]
    f64 = lambda name: np.fromfile(data / name, dtype="<f8")
    knots = f64("knots.bin")
    ctrl = f64("ctrl.bin").reshape(n_ctrl, dim)
    params = {"sorted": f64("ts_sorted.bin"), "random": f64("ts_random.bin")}
    scale = np.abs(ctrl).max()
    rows = []  # (workload, peer, peer ns/pt, note)

    from scipy.interpolate import BSpline

    spl = BSpline(knots, ctrl, p)
    for order, x in params.items():
        ns = median_ns(lambda: spl(x), n, repeats)
        ref = f64(f"ours_eval_{order}.bin").reshape(n, dim)
        err = np.abs(spl(x) - ref).max() / scale
        rows.append((f"eval_{order}", "scipy BSpline", ns, f"max diff {err:.1e} rel"))
    x = params["sorted"]
    ns = median_ns(lambda: spl(x, nu=1), n, repeats)
    err = np.abs(spl(x, nu=1) - f64("ours_deriv1_sorted.bin").reshape(n, dim)).max()
    err /= np.abs(spl(x, nu=1)).max()
    rows.append(("deriv1_sorted", "scipy BSpline(nu=1)", ns, f"max diff {err:.1e} rel"))

    sub = 100_000
    try:
        import tinyspline as ts

        s = ts.BSpline(n_ctrl, dim, p, ts.BSpline.Opened)
        s.control_points = ctrl.ravel().tolist()
        s.knots = knots.tolist()
        for order, x in params.items():
            xs = x[:sub].tolist()
            ns = median_ns(lambda: s.eval_all(xs), sub, repeats)
            got = np.array(s.eval_all(xs)).reshape(sub, dim)
            err = np.abs(got - f64(f"ours_eval_{order}.bin").reshape(n, dim)[:sub]).max() / scale
            rows.append((f"eval_{order}", "tinyspline eval_all", ns,
                         f"{sub} points; max diff {err:.1e} rel"))
    except ImportError:
        print("peers: tinyspline not installed; skipped", file=sys.stderr)

    try:
        from geomdl import BSpline as GBSpline

        g = GBSpline.Curve()
        g.degree = p
        g.ctrlpts = ctrl.tolist()
        g.knotvector = knots.tolist()
        gsub = 10_000
        for order, x in params.items():
            xs = x[:gsub].tolist()
            ns = median_ns(lambda: g.evaluate_list(xs), gsub, max(1, repeats // 3))
            rows.append((f"eval_{order}", "geomdl evaluate_list", ns, f"{gsub} points, pure Python"))
    except ImportError:
        print("peers: geomdl not installed; skipped", file=sys.stderr)

    try:
        from OCP.Geom import Geom_BSplineCurve
        from OCP.GeomAdaptor import GeomAdaptor_Curve
        from OCP.gp import gp_Pnt

        try:  # OCP 7.x names
            from OCP.TColgp import TColgp_Array1OfPnt
            from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal
        except ImportError:  # cadquery-ocp 8: generic collections
            from OCP.OCP.collections import Array1_double as TColStd_Array1OfReal
            from OCP.OCP.collections import Array1_gp_Pnt as TColgp_Array1OfPnt
            from OCP.OCP.collections import Array1_int as TColStd_Array1OfInteger

        poles = TColgp_Array1OfPnt(1, n_ctrl)
        for i, c in enumerate(ctrl):
            poles.SetValue(i + 1, gp_Pnt(*[float(v) for v in c]))
        distinct, mults = np.unique(knots, return_counts=True)
        kn = TColStd_Array1OfReal(1, len(distinct))
        mu = TColStd_Array1OfInteger(1, len(distinct))
        for i, (k, m) in enumerate(zip(distinct, mults)):
            kn.SetValue(i + 1, float(k))
            mu.SetValue(i + 1, int(m))
        adaptor = GeomAdaptor_Curve(Geom_BSplineCurve(poles, kn, mu, p))
        for order, x in params.items():
            xs = x[:sub].tolist()
            value = adaptor.Value
            ns = median_ns(lambda: [value(t) for t in xs], sub, max(1, repeats // 2))
            # one Python call per point, each returning a new gp_Pnt: this measures the
            # binding (~1-3 µs), not Open CASCADE's C++ evaluator (≈25 ns/point per issue 8)
            rows.append((f"eval_{order}", "OCP GeomAdaptor_Curve.Value", ns,
                         f"{sub} points, one Python call each: measures the binding"))
    except ImportError:
        print("peers: OCP (cadquery-ocp) not installed; skipped", file=sys.stderr)

    print()
    print(f"workload: cubic B-spline, {dim}-D, {n_ctrl} control points, {n} parameters; "
          f"medians of {repeats} runs, ns per point")
    print(f"{'workload':<15} {'lekalo ref':>10} {'lekalo':>8} {'par(2)':>8}  "
          f"{'peer':<30} {'peer':>9} {'peer/lekalo':>11}  note")
    for work, peer, ns, note in rows:
        o = ours[work]
        ref = o.get("reference", float("nan"))
        par = o.get("parallel_2", float("nan"))
        print(f"{work:<15} {ref:>10.1f} {o['fast']:>8.1f} {par:>8.1f}  {peer:<30} {ns:>9.1f} "
              f"{ns / o['fast']:>10.1f}x  {note}")


if __name__ == "__main__":
    main()
