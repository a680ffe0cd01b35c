"""Exact answers of planar curve-curve intersections for `tests/all/intersect_exact.rs`.

Every input is a Bezier curve (control points exactly representable in binary), so the
intersections of the curves as stored are algebraic numbers: they are computed here with
Python's `fractions` (the polynomials exactly) and `decimal` (the roots to 60 digits, by
bisection on a sign change or on the derivative at a double root), and written to
`intersect_exact.json` as the nearest doubles (repr), with each case's expected kinds.

Run: python3 crates/lekalo/tests/data/intersect_exact.py > crates/lekalo/tests/data/intersect_exact.json
"""

import json
from decimal import Decimal, getcontext
from fractions import Fraction as F
from math import comb

getcontext().prec = 80


def bezier_poly(ctrl, axis):
    """Power-basis coefficients (lowest first) of one coordinate of a Bezier curve."""
    n = len(ctrl) - 1
    c = [F(0)] * (n + 1)
    for i, p in enumerate(ctrl):
        # C(n, i) t^i (1 - t)^(n - i)
        for j in range(n - i + 1):
            c[i + j] += F(p[axis]) * comb(n, i) * comb(n - i, j) * (-1) ** j
    return c


def ev(c, t):
    r = 0
    for a in reversed(c):
        r = r * t + a
    return r


def deriv(c):
    return [k * c[k] for k in range(1, len(c))]


def bisect(c, lo, hi):
    """The root of the polynomial `c` in [lo, hi] (a sign change), to 60 digits."""
    lo, hi = Decimal(lo.numerator) / lo.denominator, Decimal(hi.numerator) / hi.denominator
    dc = [Decimal(a.numerator) / a.denominator for a in c]
    flo = ev(dc, lo)
    for _ in range(220):
        m = (lo + hi) / 2
        fm = ev(dc, m)
        if fm == 0:
            return m
        if (fm > 0) == (flo > 0):
            lo, flo = m, fm
        else:
            hi = m
    return (lo + hi) / 2


def roots_in_unit(c, grid=4096):
    """Simple roots of `c` in (0, 1) by sign changes on a fine rational grid."""
    out = []
    for k in range(grid):
        a, b = F(k, grid), F(k + 1, grid)
        fa, fb = ev(c, a), ev(c, b)
        if fa == 0:
            out.append(Decimal(a.numerator) / a.denominator)
        elif fa * fb < 0:
            out.append(bisect(c, a, b))
    return out


def line_param(line, point_x, point_y):
    """Parameter of the point (on the line) along the segment line[0] -> line[1]."""
    (x0, y0), (x1, y1) = [(Decimal(F(p[0]).numerator) / F(p[0]).denominator,
                           Decimal(F(p[1]).numerator) / F(p[1]).denominator) for p in line]
    dx, dy = x1 - x0, y1 - y0
    return ((point_x - x0) * dx + (point_y - y0) * dy) / (dx * dx + dy * dy)


def curve_line(name, curve, line, kinds=None):
    """Crossings of a Bezier curve with a line segment: roots of n . (C(t) - L0)."""
    (x0, y0), (x1, y1) = line
    nx, ny = -(F(y1) - F(y0)), F(x1) - F(x0)
    cx, cy = bezier_poly(curve, 0), bezier_poly(curve, 1)
    f = [nx * a + ny * b for a, b in zip(cx, cy)]
    f[0] -= nx * F(x0) + ny * F(y0)
    hits = []
    dcx = [Decimal(a.numerator) / a.denominator for a in cx]
    dcy = [Decimal(a.numerator) / a.denominator for a in cy]
    for t in roots_in_unit(f):
        px, py = ev(dcx, t), ev(dcy, t)
        u = line_param(line, px, py)
        if 0 <= u <= 1:
            hits.append({"t_a": float(t), "t_b": float(u), "point": [float(px), float(py)],
                         "kind": "crossing"})
    if kinds:
        for h, k in zip(hits, kinds):
            h["kind"] = k
    return {"name": name, "a": curve, "b": line, "hits": hits}


def tangent_to_parabola(name, a):
    """The parabola y = x^2, x = 2t - 1, and its tangent line at x = a (a dyadic), as a
    segment over x in [-1, 1]: one tangent contact of order 1 at t = u = (a + 1) / 2."""
    parabola = [[-1.0, 1.0], [0.0, -1.0], [1.0, 1.0]]
    y = lambda x: 2 * a * x - a * a
    line = [[-1.0, y(-1.0)], [1.0, y(1.0)]]
    assert all(F(p[1]) == 2 * F(a) * F(p[0]) - F(a) ** 2 for p in line), "dyadic"
    t = (a + 1) / 2
    return {"name": name, "a": parabola, "b": line,
            "hits": [{"t_a": t, "t_b": t, "point": [a, a * a], "kind": "tangent", "order": 1}]}


cases = [
    tangent_to_parabola("parabola and its tangent at x = 1/2", 0.5),
    tangent_to_parabola("parabola and its tangent at x = -3/8", -0.375),
    tangent_to_parabola("parabola and its tangent at x = 0.7890625", 0.7890625),
    curve_line("cubic and a line, three crossings",
               [[0.0, 0.0], [1.0, 3.0], [2.0, -3.0], [3.0, 0.5]], [[-0.5, 0.125], [3.5, 0.375]]),
    curve_line("cubic and a steep line, one crossing",
               [[0.0, 0.0], [1.0, 2.0], [2.0, 2.0], [3.0, 0.0]], [[0.3, -1.0], [0.7, 3.0]]),
    curve_line("quartic and a line, four crossings near the ends",
               [[0.0, 1.0], [0.25, -3.0], [0.5, 5.0], [0.75, -3.0], [1.0, 1.0]],
               [[-0.25, 0.1], [1.25, 0.2]]),
    {"name": "y = x^3 and its inflectional tangent", "a":
        [[-1.0, -1.0], [-1.0 / 3.0, 1.0], [1.0 / 3.0, -1.0], [1.0, 1.0]],
     "b": [[-2.0, 0.0], [2.0, 0.0]],
     # the x of the control points is not exact (1/3), but x(1/2) = 0 and y(1/2) = 0 exactly
     # by symmetry of the stored doubles
     "hits": [{"t_a": 0.5, "t_b": 0.5, "point": [0.0, 0.0], "kind": "tangent", "order": 2}]},
]
print(json.dumps(cases, indent=1))
