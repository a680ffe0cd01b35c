"""lekalo.jax beside interpax (pure-JAX interpolation), side by side in one run.

    python bench/python/jax_bench.py [--points 1000000] [--n 1000] [--repeats 5] [--sample 0.2]

Run it with the package installed in release mode (`maturin develop --release` in
crates/lekalo-py) and interpax beside it (`pip install interpax`; a benchmark dependency only).
The data: --n sorted sites on [0, 10] (a jittered uniform grid), values sin(x) + 0.5 cos(3.1 x);
the spline is the cubic not-a-knot interpolant of them on both sides (lekalo: the control points
of `lekalo.jax.interpolate` on the knots of `scipy.interpolate.make_interp_spline`; interpax:
`interpax.CubicSpline`, a piecewise polynomial), evaluated at --points random parameters. The
workloads, each a `jax.jit`-compiled function of its arrays:

- evaluate: the spline at the parameters, its coefficients given (lekalo: control points,
  `bspline_eval`; interpax: the polynomial pieces' coefficients, `CubicSpline.__call__`);
- gradient: `jax.grad` of `sum(w * spline(u))` with respect to those coefficients;
- interpolate + evaluate, and its gradient with respect to the data values (the spline built
  inside the function: lekalo's `interpolate`, interpax's `CubicSpline(x, y)`);
- small call: one parameter, evaluation and gradient: the cost of calling from JAX, beside the
  floor of any host callback (a `jax.pure_callback` that returns its input) and that of JAX's
  own dispatch of a compiled function of the same arrays (`c[:1] * u`, no custom call);
- the floor of an FFI call: JAX's dispatch of lekalo's target on a curve of degree 0 with one
  control point (next to nothing read or computed); lekalo's own share of a small call is its
  time less this one;
- small calls of lekalo alone (interpax has no NURBS, fits or tensor splines): `nurbs_eval` and
  its gradient at one parameter on the same knots (weights 1 + 0.5 sin), `fit_least_squares`
  of 40 points on 7 cubic control points and `fit_smoothing` of 40 points, values and gradient
  in the data, a bicubic surface on a 24 × 24 net at one pair and a tricubic tensor spline on a
  24³ net at one point, values and gradient in the net (the in-place path).

Timing: the median of --repeats samples, each a call (ended by `block_until_ready`) repeated to
at least --sample seconds, after one call that compiles; lekalo is timed just before and just
after interpax and the mean of the two medians is used, as bench/python/scipy_bench.py does.
Every lekalo result is compared with interpax's (largest difference relative to the largest
value). The goals: lekalo at least 10x interpax at 10^6 parameters, and at most 20 us a small
call. Results go to docs/differentiable.md.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from typing import Any, Callable

import numpy as np

import jax

jax.config.update("jax_enable_x64", True)
import equinox as eqx  # noqa: E402  (interpax's dependency: its splines are equinox modules)
import interpax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
from scipy import interpolate as si  # noqa: E402

import lekalo  # noqa: E402
from lekalo.jax import (  # noqa: E402
    bspline_eval,
    bspline_surface_eval,
    fit_least_squares,
    fit_smoothing,
    interpolate,
    nurbs_eval,
    tensor_bspline_eval,
)

LARGE_GOAL = 10.0
SMALL_GOAL_S = 20e-6


def timed(f: Callable[[], Any], repeats: int, sample: float) -> float:
    """Median seconds of one call of `f` (its result made ready) over `repeats` samples of at
    least `sample` s each, after one call (the compilation)."""
    jax.block_until_ready(f())
    samples = []
    for _ in range(repeats):
        n, start = 0, time.perf_counter()
        while True:
            jax.block_until_ready(f())
            n += 1
            elapsed = time.perf_counter() - start
            if elapsed >= sample:
                break
        samples.append(elapsed / n)
    return statistics.median(samples)


def rel(a: Any, b: Any) -> float:
    a, b = np.asarray(a), np.asarray(b)
    return float(np.max(np.abs(a - b)) / max(float(np.max(np.abs(b))), 1e-300))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, default=1_000_000, help="parameters to evaluate at")
    ap.add_argument("--n", type=int, default=1000, help="data sites (control points)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--sample", type=float, default=0.2, help="least seconds of one timing sample")
    a = ap.parse_args()
    print(
        f"lekalo {lekalo.__version__}, interpax {interpax.__version__}, JAX {jax.__version__}, "
        f"NumPy {np.__version__}; {os.cpu_count()} processors, load average "
        f"{os.getloadavg()[0]:.1f}; median of {a.repeats}, float64, CPU"
    )
    rng = np.random.default_rng(1)
    n, m = a.n, a.points
    x = np.linspace(0.0, 10.0, n)
    x[1:-1] += rng.uniform(-0.3, 0.3, n - 2) * (10.0 / (n - 1))
    y = np.sin(x) + 0.5 * np.cos(3.1 * x)
    t = si.make_interp_spline(x, y).t  # not-a-knot cubic knots
    u = np.sort(rng.uniform(0.0, 10.0, m))
    w = rng.standard_normal(m)
    u1 = np.array([4.2])
    xj, yj, tj, uj, wj, u1j = map(jnp.asarray, (x, y, t, u, w, u1))

    ctrl = interpolate(yj, xj, tj)
    spline = interpax.CubicSpline(xj, yj)  # not-a-knot, as lekalo's knots

    def with_coef(c):
        return eqx.tree_at(lambda s: s.c, spline, c)

    l_eval = jax.jit(lambda c, s: bspline_eval(tj, c, s, 3))
    i_eval = jax.jit(lambda c, s: with_coef(c)(s))
    l_grad = jax.jit(jax.grad(lambda c, s, g: jnp.sum(g * bspline_eval(tj, c, s, 3))))
    i_grad = jax.jit(jax.grad(lambda c, s, g: jnp.sum(g * with_coef(c)(s))))
    l_build = jax.jit(lambda q, s: bspline_eval(tj, interpolate(q, xj, tj), s, 3))
    i_build = jax.jit(lambda q, s: interpax.CubicSpline(xj, q, check=False)(s))
    l_build_grad = jax.jit(
        jax.grad(lambda q, s, g: jnp.sum(g * bspline_eval(tj, interpolate(q, xj, tj), s, 3)))
    )
    i_build_grad = jax.jit(jax.grad(lambda q, s, g: jnp.sum(g * interpax.CubicSpline(xj, q, check=False)(s))))
    c_i = spline.c
    g1 = jnp.ones(1)

    # (name, size, goal kind, lekalo call, interpax call, compare the results?)
    cases = [
        ("evaluate", m, "large", lambda: l_eval(ctrl, uj), lambda: i_eval(c_i, uj), True),
        ("gradient in the coefficients", m, "large",
         lambda: l_grad(ctrl, uj, wj), lambda: i_grad(c_i, uj, wj), False),
        ("interpolate + evaluate", m, "large", lambda: l_build(yj, uj), lambda: i_build(yj, uj), True),
        ("gradient in the data values", m, "large",
         lambda: l_build_grad(yj, uj, wj), lambda: i_build_grad(yj, uj, wj), True),
        ("small call: evaluate", 1, "small", lambda: l_eval(ctrl, u1j), lambda: i_eval(c_i, u1j), True),
        ("small call: gradient", 1, "small",
         lambda: l_grad(ctrl, u1j, g1), lambda: i_grad(c_i, u1j, g1), False),
    ]
    rows = []
    for name, size, kind, ours, theirs, compare in cases:
        diff = f"{rel(ours(), theirs()):.1e}" if compare else "(other coefficients)"
        before = timed(ours, a.repeats, a.sample)
        peer = timed(theirs, a.repeats, a.sample)
        after = timed(ours, a.repeats, a.sample)
        mean = (before + after) / 2
        ratio = peer / mean
        if kind == "large":
            met, goal = ratio >= LARGE_GOAL, f">= {LARGE_GOAL:.0f}x"
        else:
            met, goal = mean <= SMALL_GOAL_S, f"<= {SMALL_GOAL_S * 1e6:.0f} us"
        spread = abs(after - before) / min(after, before)
        rows.append((name, size, peer, mean, ratio, goal, met, diff, spread))
        print(f"  {name} [{size:,}]: interpax {peer:.3g} s, lekalo {mean:.3g} s, {ratio:.2f}x, "
              f"{'met' if met else 'MISSED'}", flush=True)

    print()
    print("| workload | parameters | interpax s | lekalo s | interpax / lekalo | goal | met | "
          "max difference (relative) | lekalo before/after |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, size, peer, ours, ratio, goal, met, diff, spread in rows:
        print(f"| {name} | {size:,} | {peer:.3g} | {ours:.3g} | {ratio:.2f}x | {goal} | "
              f"{'yes' if met else '**no**'} | {diff} | {100 * spread:.0f} % apart |")
    # the floor of a small call: one host callback that returns its input, nothing of lekalo
    noop = jax.jit(lambda s: jax.pure_callback(np.asarray, jax.ShapeDtypeStruct(s.shape, s.dtype), s))
    floor = timed(lambda: noop(u1j), a.repeats, a.sample)
    # and JAX's own dispatch of a compiled function of the same arguments, no custom call
    plain = jax.jit(lambda c, s: c[:1] * s)
    dispatch = timed(lambda: plain(ctrl, u1j), a.repeats, a.sample)
    # and JAX's dispatch of a trivial FFI call: lekalo's target on a curve of degree 0 with one
    # control point (two knots), one parameter, so that next to nothing is read or computed
    k0, p0, t0 = jnp.asarray([0.0, 1.0]), jnp.asarray([[2.0]]), jnp.asarray([0.42])
    trivial = jax.jit(lambda c, s: bspline_eval(k0, c, s, 0))
    ffi_floor = timed(lambda: trivial(p0, t0), a.repeats, a.sample)
    print(f"\nthe floor of a small call: a jit-compiled jax.pure_callback returning its input, "
          f"{floor * 1e6:.0f} us; a jit-compiled c[:1] * u of the same arrays (JAX's dispatch, "
          f"no custom call), {dispatch * 1e6:.0f} us; a trivial FFI call (bspline_eval of degree "
          f"0 on one control point), {ffi_floor * 1e6:.0f} us")
    for name, _, _, ours, _, _, _, _, _ in [r for r in rows if r[1] == 1]:
        print(f"lekalo's own share of '{name}' (its time less the trivial FFI call): "
              f"{(ours - ffi_floor) * 1e6:.1f} us")
    # lekalo alone: small calls of the other targets
    ws = jnp.asarray(1.0 + 0.5 * np.sin(np.arange(n)))
    c2 = ctrl[:, None]
    n_eval = jax.jit(lambda c, v, s: nurbs_eval(tj, c, v, s, 3))
    n_grad = jax.jit(jax.grad(lambda c, v, s: jnp.sum(nurbs_eval(tj, c, v, s, 3)), argnums=(0, 1)))
    xs = jnp.linspace(0.0, 1.0, 40)
    ys = jnp.stack([jnp.sin(3 * xs), jnp.cos(2 * xs)], axis=-1)
    t7 = jnp.asarray([0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1.0])
    f_lsq = jax.jit(lambda q: fit_least_squares(q, xs, t7, 3))
    g_lsq = jax.jit(jax.grad(lambda q: jnp.sum(fit_least_squares(q, xs, t7, 3) ** 2)))
    f_sm = jax.jit(lambda q: fit_smoothing(xs, q, None, 1e-3))
    g_sm = jax.jit(jax.grad(lambda q: jnp.sum(fit_smoothing(xs, q, None, 1e-3) ** 2)))
    alone = [
        ("nurbs_eval, one parameter", lambda: n_eval(c2, ws, u1j)),
        ("nurbs_eval gradient (control points, weights)", lambda: n_grad(c2, ws, u1j)),
        ("fit_least_squares, 40 points", lambda: f_lsq(ys)),
        ("fit_least_squares gradient", lambda: g_lsq(ys)),
        ("fit_smoothing, 40 points", lambda: f_sm(ys)),
        ("fit_smoothing gradient", lambda: g_sm(ys)),
    ]
    print("\n| small call, lekalo alone | lekalo us |")
    print("|---|---|")
    for name, f in alone:
        print(f"| {name} | {timed(f, a.repeats, a.sample) * 1e6:.1f} |", flush=True)
    # surfaces and tensor splines: one point on a large net (the in-place path)
    rng2 = np.random.default_rng(2)
    k24 = jnp.asarray(np.r_[[0.0] * 3, np.linspace(0, 1, 22), [1.0] * 3])
    net = jnp.asarray(rng2.uniform(-1, 1, (24, 24, 3)))
    tnet = jnp.asarray(rng2.uniform(-1, 1, (24, 24, 24)))
    a1, b1, x1 = jnp.asarray([0.42]), jnp.asarray([0.37]), jnp.asarray([[0.42, 0.37, 0.61]])
    surf = lambda c: bspline_surface_eval(k24, k24, c, a1, b1, 3, 3)  # noqa: E731
    tens = lambda c: tensor_bspline_eval((k24, k24, k24), c, x1, (3, 3, 3))  # noqa: E731
    nets = [
        ("bspline_surface_eval, one pair, bicubic 24 x 24 net", jax.jit(surf), net),
        ("its gradient in the net", jax.jit(jax.grad(lambda c: jnp.sum(surf(c)))), net),
        ("tensor_bspline_eval, one point, tricubic 24^3 net", jax.jit(tens), tnet),
        ("its gradient in the net", jax.jit(jax.grad(lambda c: jnp.sum(tens(c)))), tnet),
    ]
    for name, f, c in nets:
        print(f"| {name} | {timed(lambda: f(c), a.repeats, a.sample) * 1e6:.1f} |", flush=True)
    print(f"\nload average at the end {os.getloadavg()[0]:.1f}")
    missed = [r[0] for r in rows if not r[6]]
    print(f"\n{len(rows) - len(missed)} of {len(rows)} workloads meet their goal"
          + (f"; missed: {', '.join(missed)}" if missed else ""))


if __name__ == "__main__":
    main()
