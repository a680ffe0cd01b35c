"""Tensor-product splines in N variables: lekalo beside SciPy, side by side in one run.

    python bench/python/tensor_bench.py [--repeats 5] [--n3 128] [--n4 32] [--points 1000000]
                                        [--ndbspl-n 20] [--rgi-points 2000]

Run it with the package installed in release mode (`pip install ./crates/lekalo-py`, as
scripts/test.sh does) and SciPy beside it. Workloads, each on an uneven grid of a smooth field
(the coordinates jittered, values offset by 10, degree 3 in every direction):

- construction of the interpolating spline of an n3^3 grid (and an n4^4 grid) of scalars:
  lekalo's `lekalo.scipy.make_ndbspl` (SciPy's not-a-knot knots; one banded factorisation per
  direction and one sweep of solves along each, in Rust), against SciPy's fastest correct
  route, the same sweep by hand in NumPy: `make_interp_spline(x_d, c, k=3, axis=d)` for every
  direction d in turn (banded LAPACK solves along each axis), and SciPy's own `make_ndbspl` on a
  smaller grid (--ndbspl-n; its sparse solve of the whole system does not reach 128^3 in
  minutes) with `solver=scipy.sparse.linalg.spsolve`, the direct solver its tests use;
- evaluation of the cubic 3-variate spline at --points random points: lekalo's `NdBSpline`
  against SciPy's `NdBSpline` (same t, c, k), and `RegularGridInterpolator(method="cubic")` on
  the same grid (timed on --rgi-points points and reported per point: it builds 1-D splines
  at every call);
- peak memory of the n3^3 construction, in a fresh process (the peak resident size above
  what the process held just before the call, the peak reset by /proc/self/clear_refs), as a
  multiple of the input's size.

Every lekalo result is checked against SciPy's before it is timed: coefficients against the
NumPy sweep's, values against SciPy's NdBSpline. Timing: the median of --repeats samples, each
a call repeated to at least 20 ms; lekalo is timed just before and just after its peers and
the mean of the two medians is used, so that a busy moment of a shared machine weighs on both
sides. Results go to docs/performance.md ("N-variate splines").
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time

import numpy as np
import scipy
from scipy import interpolate as si
from scipy.sparse import linalg as ssl

import lekalo
from lekalo import scipy as ls

# public from SciPy 1.18 on; from 1.12 in the private module
make_ndbspl = getattr(si, "make_ndbspl", None)
if make_ndbspl is None:
    from scipy.interpolate._ndbspline import make_ndbspl


def timed(f, repeats: int) -> float:
    """Median seconds of one call of `f` over `repeats` samples of at least 20 ms each."""
    f()
    samples = []
    for _ in range(repeats):
        n, start = 0, time.perf_counter()
        while True:
            f()
            n += 1
            elapsed = time.perf_counter() - start
            if elapsed >= 0.02:
                break
        samples.append(elapsed / n)
    return statistics.median(samples)


def grid(n: int, ndim: int, rng: np.random.Generator):
    """Uneven axes on [0, 1] (jittered uniform) and a smooth field on their grid."""
    axes = []
    for _ in range(ndim):
        x = np.linspace(0.0, 1.0, n)
        x[1:-1] += rng.uniform(-0.3, 0.3, n - 2) / (n - 1)
        axes.append(x)
    # the field is a product of one function per axis: built as an outer product, in place, so
    # that making it needs no memory beyond the grid itself (the memory figure depends on that)
    values = np.cos(3.0 * axes[0])
    for d in range(1, ndim):
        values = np.multiply.outer(values, np.cos(3.0 * axes[d] + d))
    values += 10.0
    return axes, np.ascontiguousarray(values)


def numpy_sweep(axes, values, k=3):
    """SciPy's banded 1-D interpolation along every axis in turn: the coefficients of the
    tensor-product not-a-knot interpolant (the fastest correct route with SciPy)."""
    c = values
    t = []
    for d, x in enumerate(axes):
        spl = si.make_interp_spline(x, c, k=k, axis=d)
        c = np.moveaxis(spl.c, 0, d)  # BSpline keeps the interpolation axis first
        t.append(spl.t)
    return tuple(t), c


def bracket(lekalo_call, peers, repeats):
    """lekalo timed before and after the peers; returns (lekalo mean, [peer times], spread)."""
    before = timed(lekalo_call, repeats)
    times = [timed(p, repeats) for p in peers]
    after = timed(lekalo_call, repeats)
    return (before + after) / 2, times, abs(after - before) / min(before, after)


def memory_child(n: int) -> None:
    """Prints the peak memory of one n^3 construction above the memory held before it, in
    bytes, and the input's size: the kernel's peak (VmHWM) is reset just before the call
    (`/proc/self/clear_refs`), so earlier temporaries do not hide it (Linux only)."""

    def status(field: str) -> int:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(field + ":"):
                    return int(line.split()[1]) * 1024
        raise RuntimeError(f"no {field} in /proc/self/status")

    axes, values = grid(n, 3, np.random.default_rng(1))
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
    before = status("VmRSS")
    spline = ls.make_ndbspl(axes, values, k=3)
    after = status("VmHWM")
    print(json.dumps({"extra": after - before, "input": values.nbytes, "coefficients": spline.c.nbytes}))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--n3", type=int, default=128)
    ap.add_argument("--n4", type=int, default=32)
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--ndbspl-n", type=int, default=20)
    ap.add_argument("--rgi-points", type=int, default=2000)
    ap.add_argument("--memory-child", type=int, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.memory_child:
        memory_child(a.memory_child)
        return
    rng = np.random.default_rng(0)
    print(f"lekalo {lekalo.__version__}, SciPy {scipy.__version__}, NumPy {np.__version__}; median of {a.repeats}")
    rows = []

    # construction, 3 and 4 variables
    for ndim, n in ((3, a.n3), (4, a.n4)):
        axes, values = grid(n, ndim, rng)
        t, c = numpy_sweep(axes, values)
        ours = ls.make_ndbspl(axes, values, k=3)
        for d in range(ndim):
            assert np.array_equal(ours.t[d], t[d]), f"knots of direction {d} differ"
        err = np.max(np.abs(ours.c - c)) / np.max(np.abs(c))
        assert err < 1e-12, f"coefficients differ by {err:.1e}"
        mean, (sweep,), spread = bracket(lambda: ls.make_ndbspl(axes, values, k=3), [lambda: numpy_sweep(axes, values)], a.repeats)
        rows.append((f"interpolation {n}^{ndim} ({values.size:,} values)", mean, "make_interp_spline along each axis", sweep, f"coefficients within {err:.1e}", spread))

    # SciPy's make_ndbspl, where its solve finishes
    axes, values = grid(a.ndbspl_n, 3, rng)
    ours = ls.make_ndbspl(axes, values, k=3)
    theirs = make_ndbspl(axes, values, k=3, solver=ssl.spsolve)
    err = np.max(np.abs(ours.c - theirs.c)) / np.max(np.abs(theirs.c))
    assert err < 1e-12, f"make_ndbspl coefficients differ by {err:.1e}"
    mean, (nd,), spread = bracket(lambda: ls.make_ndbspl(axes, values, k=3),
                                  [lambda: make_ndbspl(axes, values, k=3, solver=ssl.spsolve)], max(1, a.repeats // 2))
    rows.append((f"interpolation {a.ndbspl_n}^3 ({values.size:,} values)", mean, "make_ndbspl(solver=spsolve)", nd, f"coefficients within {err:.1e}", spread))

    # evaluation of the n3^3 cubic at random points
    axes, values = grid(a.n3, 3, rng)
    ours = ls.make_ndbspl(axes, values, k=3)
    theirs = si.NdBSpline(ours.t, ours.c, 3)
    xi = rng.uniform(0.0, 1.0, (a.points, 3))
    v_ours, v_theirs = ours(xi), theirs(xi)
    err = np.max(np.abs(v_ours - v_theirs)) / np.max(np.abs(v_theirs))
    assert err < 1e-12, f"values differ by {err:.1e}"
    mean, (nd_eval,), spread = bracket(lambda: ours(xi), [lambda: theirs(xi)], a.repeats)
    rows.append((f"evaluation, {a.points:,} random points, cubic {a.n3}^3", mean, "NdBSpline.__call__", nd_eval, f"values within {err:.1e}", spread))
    rgi = si.RegularGridInterpolator(axes, values, method="cubic")
    few = xi[: a.rgi_points]
    rgi_err = np.max(np.abs(rgi(few) - ours(few))) / np.max(np.abs(values))
    start = time.perf_counter()
    rgi(few)
    rgi_time = (time.perf_counter() - start) / len(few) * a.points
    rows.append((f"evaluation, {a.points:,} random points, cubic {a.n3}^3", mean, f"RegularGridInterpolator(cubic) (timed on {len(few):,}, scaled)", rgi_time,
                 f"values within {rgi_err:.1e}", spread))

    print()
    print("| workload | lekalo s | peer | peer s | ratio | agreement | lekalo before/after |")
    print("|---|---|---|---|---|---|---|")
    for what, ours_s, peer, peer_s, agree, spread in rows:
        print(f"| {what} | {ours_s:.4g} | {peer} | {peer_s:.4g} | {peer_s / ours_s:.1f}x | {agree} | {100 * spread:.0f} % apart |")

    out = subprocess.run([sys.executable, __file__, "--memory-child", str(a.n3)], capture_output=True, text=True, check=True)
    m = json.loads(out.stdout)
    print(f"\npeak memory of the {a.n3}^3 construction: {m['extra'] / 2**20:.1f} MiB above what the process held "
          f"(the input's {m['input'] / 2**20:.1f} MiB included there); input + extra = {(m['extra'] + m['input']) / m['input']:.2f}x the input, "
          f"the result's {m['coefficients'] / 2**20:.1f} MiB of coefficients included")


if __name__ == "__main__":
    main()
