"""lekalo from Python, side by side with the Rust library and with SciPy on the same arrays, in
one run.

    python bench/python/bench.py [--repeats 7] [--batch 100000] [--loop 5000]
                                 [--rust-only | --no-rust] [--rust PEER_BENCH_BINARY]

Python against Rust (first, unless --no-rust): the Rust figures are timed in the same run by the
peer benchmark program (`cargo build --release -p lekalo --example peer_bench`, built here
unless --rust names the binary), which writes its workload data (a cubic 3-D curve of 1000
control points and 10^6 sorted and random parameters; helices of 10^3..10^6 points; 100x100 to
400x400 grids) to a temporary folder; the package is timed on those very arrays, its results
compared with the Rust ones bit for bit, and each Rust figure is the mean of a timing just
before and one just after the Python timing of the same workload (as bench/peers does), so
that a busy spell of a shared machine weighs on both sides. Both sides time a call the same
way: repeated to at least 20 ms a sample, median of --repeats samples.

Workloads (cubic, 3-D, as in bench/peers): evaluation of a 1000-control-point B-spline at
10^6 sorted and random parameters; interpolation through 10^6 points; bicubic interpolation of
a 400x400 grid; the overhead of one scalar evaluation; the batch API interpolating 10^5
curves of 100 points, against a Python loop over make_interp_spline (timed on `--loop`
curves and scaled to the batch). Each figure is the median of `--repeats` runs; every result
is checked against SciPy's before it is timed. The Rust figures to compare with are those of
docs/performance.md (criterion and peer_bench on the same machine).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import tempfile
import time
import timeit
from pathlib import Path

import numpy as np
from scipy import interpolate as si

import lekalo


def median_s(fn, repeats):
    fn()
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return statistics.median(out)


ROOT = Path(__file__).resolve().parents[2]


def median_ns(fn, units, repeats):
    """ns per unit of `fn`, timed as peer_bench times the Rust side: the warm-up call sets how
    many calls make one sample of at least 20 ms; the median of `repeats` samples."""
    t0 = time.perf_counter()
    fn()
    inner = max(1, math.ceil(0.02 / max(time.perf_counter() - t0, 1e-9)))
    samples = []
    for _ in range(max(repeats, 1)):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        samples.append((time.perf_counter() - t0) / inner)
    samples.sort()
    return samples[len(samples) // 2] * 1e9 / units


def peer_bench(binary):
    """The Rust timing program: `binary`, or built here in release mode."""
    if binary:
        return binary
    subprocess.run(["cargo", "build", "--quiet", "--release", "-p", "lekalo", "--example", "peer_bench"],
                   cwd=ROOT, check=True)
    return str(ROOT / "target" / "release" / "examples" / "peer_bench")


def rust_times(binary, data, repeats, works):
    """peer_bench's medians (ns per unit) for the named workloads, timings only."""
    subprocess.run([binary, str(data), str(repeats), "rust_bracket.json", ",".join(works)],
                   check=True, stdout=subprocess.DEVNULL)
    return json.loads((data / "rust_bracket.json").read_text())["results"]


def python_vs_rust(binary, repeats):
    """The Python/Rust table: each workload of peer_bench timed from Python on its own data,
    between two Rust timings of the same workload."""
    data = Path(tempfile.mkdtemp(prefix="lekalo-pybench-"))
    subprocess.run([binary, str(data), "1"], check=True, stdout=subprocess.DEVNULL)
    meta = json.loads((data / "ours.json").read_text())
    f64 = lambda name: np.fromfile(data / name, dtype="<f8")  # noqa: E731
    p, dim, k, n = meta["degree"], meta["dim"], meta["n_ctrl"], meta["n"]
    curve = lekalo.BSplineCurve(p, f64("knots.bin"), f64("ctrl.bin").reshape(k, dim))
    out = np.empty((n, dim))
    rows = []

    def check(got, want_file):
        return "bit for bit" if np.array_equal(got, f64(want_file).reshape(got.shape)) else "DIFFERS"

    # (workloads timed together by peer_bench, [(label, workload, Rust key, Python call, units, check)])
    groups = []
    ev = []
    for order in ("sorted", "random"):
        t = f64(f"ts_{order}.bin")
        note = check(curve(t), f"ours_eval_{order}.bin")
        ev.append((f"evaluation {order}, 10^6, K={k}: c(t)", f"eval_{order}", "parallel_2_unpinned",
                   lambda t=t: curve(t), n, note))
        ev.append((f"evaluation {order}, 10^6: c(t, out=buf)", f"eval_{order}", "parallel_2_unpinned",
                   lambda t=t: curve(t, out=out), n, note))
    ts = f64("ts_sorted.bin")
    d1 = np.ascontiguousarray(curve.derivatives(ts, 1)[:, 1])
    ev.append(("point + 1st derivative, sorted, 10^6", "deriv1_sorted", "fast",
               lambda: curve.derivatives(ts, 1), n, check(d1, "ours_deriv1_sorted.bin")))
    groups.append((["eval_sorted", "eval_random", "deriv1_sorted"], ev))
    for m in meta["interp_sizes"]:
        q = f64(f"interp_q_{m}.bin").reshape(m, 3)
        note = check(lekalo.interpolate(q, 3).control, f"interp_ctrl_{m}.bin")
        groups.append(([f"interp_{m}"], [(f"interpolation, {m} points", f"interp_{m}", "fresh",
                                          lambda q=q: lekalo.interpolate(q, 3), m, note)]))
    for m in meta["surface_sizes"]:
        g = f64(f"surf_q_{m}.bin").reshape(m, m, 3)
        note = check(lekalo.interpolate_surface(g, 3, 3).control, f"surf_ctrl_{m}.bin")
        groups.append(([f"surface_{m}"], [(f"surface interpolation, {m}x{m}", f"surface_{m}", "fresh",
                                           lambda g=g: lekalo.interpolate_surface(g, 3, 3), m * m, note)]))
    for works, items in groups:
        before = rust_times(binary, data, repeats, works)
        ours = [median_ns(call, units, repeats) for _, _, _, call, units, _ in items]
        after = rust_times(binary, data, repeats, works)
        for (label, work, key, _, _, note), py_ns in zip(items, ours):
            b, a = before[work][key], after[work][key]
            rows.append((label, (a + b) / 2, abs(a - b) / min(a, b), py_ns, f"{work}/{key}", note))
    print(f"\n{'workload':<42} {'Rust ns':>9} {'Python ns':>10} {'Py/Rust':>8}   Rust bench (change before/after); result")
    for label, rust, change, py, key, note in rows:
        print(f"{label:<42} {rust:9.2f} {py:10.2f} {py / rust:7.2f}x   {key} ({change:.0%}); {note}")
    for f in data.iterdir():
        f.unlink()
    data.rmdir()


def row(work, ours_s, scipy_s, units, note=""):
    ratio = scipy_s / ours_s if scipy_s else float("nan")
    print(
        f"{work:<34} lekalo {ours_s / units * 1e9:9.2f} ns/unit   SciPy {scipy_s / units * 1e9:9.2f} ns/unit"
        f"   {ratio:6.1f}x   {note}"
    )


def mid_sizes(rng, repeats):
    """Per-call times where the binding's fixed costs show: evaluation of the 1000-control-point
    cubic at 10^3..10^5 sorted parameters and interpolation through 10^3..10^5 points. The Rust
    figures to set beside them are criterion's `eval_sorted` (2.6 ns a point, 10^6) and
    `curve_interpolation_cubic_3d` fresh (18.7 µs / 157 µs / 1.73 ms at 10^3 / 10^4 / 10^5),
    docs/performance.md."""
    k = 1000
    knots = np.concatenate([[0] * 4, np.linspace(0, 1, k - 2)[1:-1], [1] * 4])
    ctrl = rng.standard_normal((k, 3))
    c = lekalo.BSplineCurve(3, knots, ctrl)
    ref = si.BSpline(knots, ctrl, 3)
    for n in (1_000, 10_000, 100_000):
        t = np.linspace(0, 1, n)
        reps = max(repeats, 2_000_000 // n)
        ours = median_s(lambda: c(t), reps)
        row(f"eval sorted, {n}, K=1000", ours, median_s(lambda: ref(t), reps), n, f"{ours * 1e6:.1f} us a call")
    for n in (1_000, 10_000, 100_000):
        q = np.cumsum(rng.standard_normal((n, 3)), axis=0)
        u = lekalo.parametrize(q)
        kn = lekalo.interpolate(q, 3).knots
        reps = max(repeats, 200_000 // n)
        ours = median_s(lambda: lekalo.interpolate(q, 3), reps)
        theirs = median_s(lambda: si.make_interp_spline(u, q, k=3, t=kn), reps)
        row(f"interpolation {n} (t = ours)", ours, theirs, n, f"{ours * 1e6:.1f} us a call")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--batch", type=int, default=100_000)
    ap.add_argument("--loop", type=int, default=5000)
    ap.add_argument("--mid-only", action="store_true", help="only the mid-size rows (10^3 to 10^5)")
    ap.add_argument("--rust", help="the peer_bench binary (default: built here with cargo)")
    ap.add_argument("--no-rust", action="store_true", help="skip the Python/Rust table")
    ap.add_argument("--rust-only", action="store_true", help="only the Python/Rust table")
    a = ap.parse_args()
    rng = np.random.default_rng(1)
    print(f"lekalo {lekalo.__file__}; numpy {np.__version__}; scipy {__import__('scipy').__version__}; "
          f"{os.cpu_count()} processors; RAYON_NUM_THREADS={os.environ.get('RAYON_NUM_THREADS', '-')}; "
          f"load average {os.getloadavg()[0]:.1f}")
    if not a.no_rust:
        python_vs_rust(peer_bench(a.rust), a.repeats)
        print(f"load average {os.getloadavg()[0]:.1f}")
        if a.rust_only:
            return
    mid_sizes(rng, a.repeats)
    if a.mid_only:
        return

    # -- scalar evaluation overhead
    k = 1000
    knots = np.concatenate([[0] * 4, np.linspace(0, 1, k - 2)[1:-1], [1] * 4])
    ctrl = rng.standard_normal((k, 3))
    c = lekalo.BSplineCurve(3, knots, ctrl)
    ref = si.BSpline(knots, ctrl, 3)
    n_calls = 200_000
    ours = min(timeit.repeat(lambda: c(0.123), number=n_calls, repeat=5)) / n_calls
    theirs = min(timeit.repeat(lambda: ref(0.123), number=n_calls // 10, repeat=5)) / (n_calls // 10)
    print(f"{'scalar eval, one call':<34} lekalo {ours * 1e6:9.3f} us         SciPy {theirs * 1e6:9.3f} us")

    # -- vectorised evaluation
    n = 1_000_000
    for name, t in (("sorted", np.linspace(0, 1, n)), ("random", rng.random(n))):
        got, want = c(t), ref(t)
        err = np.abs(got - want).max()
        row(f"eval {name}, 10^6, K=1000", median_s(lambda: c(t), a.repeats), median_s(lambda: ref(t), a.repeats), n, f"max diff {err:.1e}")
    t = np.linspace(0, 1, n)
    err = np.abs(c(t, nu=1) - ref(t, nu=1)).max() / np.abs(ref(t, nu=1)).max()
    row("first derivative, 10^6", median_s(lambda: c(t, nu=1), a.repeats), median_s(lambda: ref(t, nu=1), a.repeats), n, f"rel diff {err:.1e}")

    # -- interpolation through 10^6 points (chord length; SciPy with our knots, and not-a-knot)
    q = np.cumsum(rng.standard_normal((n, 3)), axis=0)
    curve = lekalo.interpolate(q, 3)
    u = lekalo.parametrize(q)
    s_ours_knots = si.make_interp_spline(u, q, k=3, t=curve.knots)
    err = np.abs(s_ours_knots.c - curve.control).max() / np.abs(q).max()
    ours_s = median_s(lambda: lekalo.interpolate(q, 3), a.repeats)
    row("interpolation 10^6 (t = ours)", ours_s, median_s(lambda: si.make_interp_spline(u, q, k=3, t=curve.knots), a.repeats), n, f"control rel diff {err:.1e}")
    row("interpolation 10^6 (SciPy not-a-knot)", ours_s, median_s(lambda: si.make_interp_spline(u, q, k=3), a.repeats), n)

    # -- surface interpolation, 400 x 400
    m = 400
    x = np.linspace(0, 1, m)
    X, Y = np.meshgrid(x, x, indexing="ij")
    g = np.stack([X, Y, np.sin(6 * X) * np.cos(4 * Y)], axis=-1)
    s = lekalo.interpolate_surface(g, 3, 3, parametrization="uniform")
    ku, kv = s.knots_u, s.knots_v

    def two_pass(tu=None, tv=None):
        a1 = si.make_interp_spline(x, g.reshape(m, m * 3), k=3, t=tu).c.reshape(m, m, 3)
        b = a1.transpose(1, 0, 2).reshape(m, m * 3)
        return si.make_interp_spline(x, b, k=3, t=tv).c.reshape(m, m, 3).transpose(1, 0, 2)

    err = np.abs(two_pass(ku, kv) - s.control).max()
    row("surface 400x400 (t = ours)", median_s(lambda: lekalo.interpolate_surface(g, 3, 3, parametrization="uniform"), a.repeats),
        median_s(lambda: two_pass(ku, kv), a.repeats), m * m, f"control diff {err:.1e}")

    # -- batch: 10^5 curves x 100 points
    nb, length = a.batch, 100
    pts = np.cumsum(rng.standard_normal((nb * length, 3)), axis=0)
    off = lekalo.ragged_offsets([length] * nb)
    xs = np.linspace(0, 1, length)
    ys = np.ascontiguousarray(pts[:, 0]).reshape(nb, length)
    # 1-D functions y(x) at x = linspace(0, 1): lekalo's default free-end cubic (averaged knots)
    # against make_interp_spline's default not-a-knot cubic, one call per curve
    b1 = lambda: lekalo.interpolate_batch(ys.reshape(-1, 1), off, 3, parametrization="uniform")  # noqa: E731
    b = b1()
    for i in (0, nb - 1):
        cc = lekalo.BSplineCurve(3, b["knots"][b["knot_offsets"][i]:b["knot_offsets"][i + 1]], b["control"][b["control_offsets"][i]:b["control_offsets"][i + 1]])
        ref = si.make_interp_spline(xs, ys[i], k=3, t=cc.knots)
        assert np.allclose(cc(xs)[:, 0], ref(xs), atol=1e-10)
    loop_n = min(a.loop, nb)
    loop_s = median_s(lambda: [si.make_interp_spline(xs, ys[i], k=3) for i in range(loop_n)], 3) * nb / loop_n
    row(f"batch {nb} curves x {length} (1-D)", median_s(b1, max(3, a.repeats // 2)), loop_s, nb, "SciPy: Python loop over make_interp_spline")

    # 3-D curves: chord-length parameters computed per curve in NumPy for SciPy
    def scipy_curve(p):
        d = np.linalg.norm(np.diff(p, axis=0), axis=1)
        u = np.concatenate([[0.0], np.cumsum(d)]) / d.sum()
        return si.make_interp_spline(u, p, k=3)

    b3_s = median_s(lambda: lekalo.interpolate_batch(pts, off, 3), max(3, a.repeats // 2))
    loop3_s = median_s(lambda: [scipy_curve(pts[i * length:(i + 1) * length]) for i in range(loop_n)], 3) * nb / loop_n
    row(f"batch {nb} curves x {length} (3-D)", b3_s, loop3_s, nb, "SciPy: chord parameters + make_interp_spline per curve")
    print(f"calibration: np.empty(3) takes {min(timeit.repeat(lambda: np.empty(3), number=100_000, repeat=5)) / 100_000 * 1e6:.3f} us here")


if __name__ == "__main__":
    main()
