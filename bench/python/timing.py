"""The timing the Python benchmarks share: the best of several runs of a call."""

from __future__ import annotations

import time


def best_of(repeats, f):
    """The shortest of `repeats` wall-clock times of `f()` (time.perf_counter), and the last
    result."""
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out
