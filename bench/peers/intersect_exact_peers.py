"""Curve-curve intersection on the exact-answer suite, lekalo against its peers in one run.

The suite is crates/lekalo/tests/data/intersect_exact.json: planar Bezier pairs whose
intersections were computed with rational and 60-digit arithmetic (intersect_exact.py beside
it). Each case is intersected by

  lekalo          QueryCurve::intersect at 1e-9 (examples/intersect_exact_peer.rs, run before
                  and after the peers: its time is the mean of the two medians)
  bezier-geo      PyPI's `bezier`, Curve.intersect with its default geometric strategy (the
                  compiled Fortran speedup when the wheel carries it; printed below)
  bezier-alg      the same with IntersectionStrategy.ALGEBRAIC (pure Python and NumPy)
  occt            Open CASCADE's Geom2dAPI_InterCurveCurve at 1e-9, in C++
                  (bench/peers/occt_queries.cpp, mode `exact`), when its binary is given

each timed as the median of REPEATS runs, then more while they have taken less than a second in
all (at most 1,001), the rule of examples/query_peer.rs. A peer passes a case when it finds
every exact intersection point and nothing else (kinds aside; a raised error fails the case):
as many points as the exact answer, each exact point matched by one found point whose
parameters on both curves are within 1e-8 of the exact ones for a crossing, 1e-4 for a tangent
contact (a contact of order k is located to about the (k+1)-th root of the tolerance; 1e-4 is
the square root of 1e-8). The worst parameter error of the matched points is printed too.

Usage: intersect_exact_peers.py REPEATS LEKALO_EXAMPLE [OCCT_QUERIES]
(bench/peers/run.sh passes target/release/examples/intersect_exact_peer and, when Open CASCADE's
headers are installed, target/peers-occt/occt_queries.)
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
CASES = ROOT / "crates" / "lekalo" / "tests" / "data" / "intersect_exact.json"
CROSSING_TOL = 1e-8
TANGENT_TOL = 1e-4


def median_s(repeats: int, f) -> float:
    start = time.perf_counter()
    t: list[float] = []
    while len(t) < max(repeats, 1) or (time.perf_counter() - start < 1.0 and len(t) < 1001):
        a = time.perf_counter()
        f()
        t.append(time.perf_counter() - a)
    t.sort()
    return t[len(t) // 2]


def parse_lines(text: str, tag: str) -> dict[int, tuple[float, list[tuple[float, float]]]]:
    """Lines `TAG K SECONDS N t_a t_b x y ...` -> {K: (seconds, [(t_a, t_b), ...])}."""
    out = {}
    for line in text.splitlines():
        f = line.split()
        if not f or f[0] != tag:
            continue
        k, secs, n = int(f[1]), float(f[2]), int(f[3])
        vals = [float(x) for x in f[4:]]
        out[k] = (secs, [(vals[4 * i], vals[4 * i + 1]) for i in range(n)])
    return out


def check(case: dict, found: list[tuple[float, float]] | None) -> tuple[bool, float, str]:
    """(passes, worst parameter error of the matched points, why not)."""
    if found is None:
        return False, float("nan"), "raised"
    want = case["hits"]
    if len(found) != len(want):
        return False, float("nan"), f"{len(found)} points for {len(want)}"
    left = list(found)
    worst = 0.0
    for w in want:
        tol = TANGENT_TOL if w["kind"] == "tangent" else CROSSING_TOL
        err = [max(abs(a - w["t_a"]), abs(b - w["t_b"])) for a, b in left]
        i = int(np.argmin(err))
        if err[i] > tol:
            return False, err[i], f"t = {w['t_a']} missed (nearest {err[i]:.1e} off)"
        worst = max(worst, err[i])
        left.pop(i)
    return True, worst, ""


def bezier_peers(cases: list[dict], repeats: int) -> dict[str, dict]:
    import bezier
    from bezier import _geometric_intersection
    from bezier.hazmat.intersection_helpers import IntersectionStrategy

    compiled = getattr(_geometric_intersection, "_speedup", None) is not None
    print(f"bezier {bezier.__version__}: geometric strategy "
          f"{'compiled (Fortran speedup)' if compiled else 'pure Python (no speedup)'}")
    out: dict[str, dict] = {"bezier-geo": {}, "bezier-alg": {}}
    for name, strategy in [("bezier-geo", IntersectionStrategy.GEOMETRIC),
                           ("bezier-alg", IntersectionStrategy.ALGEBRAIC)]:
        for k, case in enumerate(cases):
            curves = [bezier.Curve(np.asfortranarray(np.array(case[s], dtype=float).T),
                                   degree=len(case[s]) - 1) for s in ("a", "b")]
            try:
                st = curves[0].intersect(curves[1], strategy=strategy)
            except Exception as e:  # the peer's own refusal is its answer: the case fails
                out[name][k] = (float("nan"), None, f"{type(e).__name__}: {e}")
                continue
            t = median_s(repeats, lambda: curves[0].intersect(curves[1], strategy=strategy))
            out[name][k] = (t, [(float(s), float(u)) for s, u in st.T], "")
    return out


def main() -> None:
    repeats, lekalo = int(sys.argv[1]), sys.argv[2]
    occt = sys.argv[3] if len(sys.argv) > 3 else None
    cases = json.loads(CASES.read_text())
    results: dict[str, dict] = {}

    first = parse_lines(subprocess.run([lekalo, str(repeats)], check=True, capture_output=True,
                                       text=True).stdout, "lekalo")
    results.update(bezier_peers(cases, repeats))
    if occt:
        answers = ROOT / "target" / "peers-occt" / "answers"
        answers.mkdir(parents=True, exist_ok=True)
        file = answers / "intersect_exact.txt"
        lines = []
        for k, case in enumerate(cases):
            parts = [str(k)]
            for s in ("a", "b"):
                parts.append(str(len(case[s])))
                parts += [repr(float(x)) for p in case[s] for x in p]
            lines.append(" ".join(parts))
        file.write_text("\n".join(lines) + "\n")
        got = parse_lines(subprocess.run([occt, "exact", str(repeats), str(file)], check=True,
                                         capture_output=True, text=True).stdout, "occt")
        results["occt"] = {k: (t, pts, "") for k, (t, pts) in got.items()}
    after = parse_lines(subprocess.run([lekalo, str(repeats)], check=True, capture_output=True,
                                       text=True).stdout, "lekalo")
    results = {"lekalo": {k: (0.5 * (first[k][0] + after[k][0]), after[k][1], "")
                          for k in after}, **results}

    peers = list(results)
    print(f"\nintersect_exact: {len(cases)} cases, seconds per intersection (median of runs), "
          "'-' = fails the case")
    print(f"{'case':52s}" + "".join(f"{p:>12s}" for p in peers))
    summary = {p: {"pass": 0, "time": 0.0, "worst": 0.0, "why": []} for p in peers}
    for k, case in enumerate(cases):
        row = f"{case['name'][:51]:52s}"
        for p in peers:
            t, found, why = results[p].get(k, (float("nan"), None, "no answer"))
            ok, worst, reason = check(case, found)
            s = summary[p]
            if ok:
                s["pass"] += 1
                s["worst"] = max(s["worst"], worst)
                row += f"{t:12.3e}"
            else:
                s["why"].append(f"case {k}: {why or reason}")
                row += f"{'- ' + f'{t:.1e}' if t == t else '-':>12s}"
            s["time"] += t if t == t else 0.0
        print(row)
    print()
    for p in peers:
        s = summary[p]
        print(f"{p:11s} passes {s['pass']}/{len(cases)}, total {s['time']:.3e} s over all cases "
              f"it answered, worst parameter error where it passes {s['worst']:.1e}")
        for w in s["why"]:
            print(f"{'':13s}{w}")
    passing = [p for p in peers if p != "lekalo" and summary[p]["pass"] == len(cases)]
    ours = summary["lekalo"]["time"]
    if passing:
        best = min(passing, key=lambda p: summary[p]["time"])
        print(f"fastest peer that passes the suite: {best}, {summary[best]['time']:.3e} s; "
              f"lekalo {ours:.3e} s; ratio {summary[best]['time'] / ours:.2f} "
              "(peer's / ours, > 1: lekalo faster)")
    else:
        print("no peer passes the whole suite")
    for p in peers[1:]:
        both = [k for k in range(len(cases))
                if check(cases[k], results[p].get(k, (0, None, ""))[1])[0]]
        if both:
            theirs = sum(results[p][k][0] for k in both)
            mine = sum(results["lekalo"][k][0] for k in both)
            print(f"on the {len(both)} cases {p} passes: {p} {theirs:.3e} s, lekalo {mine:.3e} s, "
                  f"ratio {theirs / mine:.2f}")


if __name__ == "__main__":
    main()
