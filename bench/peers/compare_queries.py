"""Compares the answers of the query peers (examples/query_peer.rs and occt_queries.cpp, each
run with an ANSWERS_DIR): projections point by point over the points both sides projected, and
intersection points in order.

    python3 bench/peers/compare_queries.py ANSWERS_DIR

Projection: a closest point is a global minimum of the distance, so of two answers for the same
query point the smaller distance is the better one; the counts say how often each side is
farther than the other by more than 1e-12 of the curve's size (about 10 here) plus 1e-12 of the
distance. Intersections: the count on each side and the largest difference of parameters and
points between the k-th answers.
"""
import sys
from pathlib import Path


def floats(path):
    return [[float(x) for x in line.split()] for line in path.read_text().splitlines() if line]


def main():
    d = Path(sys.argv[1])
    ours = [r[0] for r in floats(d / "lekalo_project.txt")]
    theirs = [r[0] for r in floats(d / "occt_project.txt")]
    n = min(len(ours), len(theirs))
    size = 10.0
    slack = lambda a, b: 1e-12 * size + 1e-12 * max(a, b)
    none = sum(1 for t in theirs[:n] if t < 0)
    worse = [i for i in range(n) if theirs[i] >= 0 and ours[i] > theirs[i] + slack(ours[i], theirs[i])]
    better = [i for i in range(n) if theirs[i] < 0 or theirs[i] > ours[i] + slack(ours[i], theirs[i])]
    gain = max((theirs[i] - ours[i] for i in better if theirs[i] >= 0), default=0.0)
    print(
        f"project: {n} points compared; lekalo farther at {len(worse)}, Open CASCADE farther at "
        f"{len(better) - none} (by up to {gain:.3e}), no answer from Open CASCADE at {none}"
    )
    if worse:
        print(f"  lekalo farther at points {worse[:10]}")
    a = floats(d / "lekalo_intersect.txt")
    b = floats(d / "occt_intersect.txt")
    line = f"intersect: lekalo {len(a)} points, Open CASCADE {len(b)} points"
    if len(a) == len(b) and a:
        dt = max(max(abs(x[0] - y[0]), abs(x[1] - y[1])) for x, y in zip(a, b))
        dp = max(max(abs(x[2] - y[2]), abs(x[3] - y[3])) for x, y in zip(a, b))
        line += f"; largest difference of parameters {dt:.2e}, of coordinates {dp:.2e}"
    print(line)


if __name__ == "__main__":
    main()
