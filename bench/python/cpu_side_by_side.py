"""scipy_bench.py's workloads side by side in CPU time, in one process.

    python bench/python/cpu_side_by_side.py NAME [NAME ...] [--size 100000] [--samples 7]

For each workload of `scipy_bench.py` whose name contains one of the NAMEs (at --size), SciPy's
and lekalo's calls alternate in samples of about 20 ms of CPU each; printed are the medians of
the CPU time a call (`time.process_time`: user and system time of every thread, so that time
spent waiting for a core on a loaded machine does not count) and of the minor page faults a call
(`getrusage`). The process first builds every workload of that size, as the benchmark does, so
the allocator's thresholds are those of the benchmark (no page fault on either side for the
constructions of docs/moving-from-scipy.md, "what a fair side-by-side is").
"""

from __future__ import annotations

import argparse
import resource
import statistics
import time
import warnings

import numpy as np

import scipy_bench as sb


def sample(f, reps: int) -> tuple[float, float]:
    """CPU seconds and minor page faults a call over `reps` calls."""
    r0, c0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt, time.process_time()
    for _ in range(reps):
        f()
    c1, r1 = time.process_time(), resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    return (c1 - c0) / reps, (r1 - r0) / reps


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="+")
    ap.add_argument("--size", type=int, default=100_000)
    ap.add_argument("--samples", type=int, default=7)
    a = ap.parse_args()
    args = argparse.Namespace(per_point_max=100_000, ndbspl_n=20, sizes=[a.size])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cases = sb.cases(a.size, args, np.random.default_rng(a.size))
        for c in cases:
            if not any(name in c.name for name in a.names):
                continue
            c.theirs(), c.ours()
            start = time.process_time()
            c.theirs()
            reps = max(3, int(0.02 / max(time.process_time() - start, 1e-5)))
            runs = [(sample(c.theirs, reps), sample(c.ours, reps)) for _ in range(a.samples)]
            sp = statistics.median(s[0][0] for s in runs)
            ours = statistics.median(s[1][0] for s in runs)
            faults = [statistics.median(s[i][1] for s in runs) for i in (0, 1)]
            print(f"{c.name} [{c.kind}, {c.n:,}]: SciPy {sp * 1e6:.0f} us, lekalo {ours * 1e6:.0f} us of CPU a "
                  f"call, {sp / ours:.1f}x; page faults a call {faults[0]:.0f} and {faults[1]:.0f}", flush=True)


if __name__ == "__main__":
    main()
