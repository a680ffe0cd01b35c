"""Reference maximum errors of the de Boor-Fix quasi-interpolant on the thesis's practical task
(document 003 section 5.3; docs/theory/pp.md#the-two-tau-rules), for every tau rule.

Independent of lekalo: B-splines by the recursive Cox-de Boor definition, psi_i expanded as a
polynomial with exact products, the grid j*0.05. Pure Python (no dependencies):

    python3 crates/lekalo/tests/data/quasi_tau_rules.py

prints one line per rule: name, maximum error, where. crates/lekalo/tests/all/ppform.rs holds the
figures.
"""
import math

x = [0.0, 0.0, 0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0, 3.0, 3.0]
k = 3
n = len(x) - k


def f(t, r):
    s, c = math.sin(t), math.cos(t)
    return [t * c, c - t * s, -2 * s - t * c, -3 * c + t * s][r]


def bspline(i, order, t):
    """b_{i,order}(t), right-continuous, the last interval closed."""
    if order == 1:
        if x[i] <= t < x[i + 1]:
            return 1.0
        last = t == x[-1] and x[i] < x[i + 1] and x[i + 1] == x[-1]
        return 1.0 if last else 0.0
    out = 0.0
    if x[i + order - 1] > x[i]:
        out += (t - x[i]) / (x[i + order - 1] - x[i]) * bspline(i, order - 1, t)
    if x[i + order] > x[i + 1]:
        out += (x[i + order] - t) / (x[i + order] - x[i + 1]) * bspline(i + 1, order - 1, t)
    return out


def poly_mul(a, b):
    out = [0.0] * (len(a) + len(b) - 1)
    for i, u in enumerate(a):
        for j, v in enumerate(b):
            out[i + j] += u * v
    return out


def poly_deriv_at(p, m, z):
    """m-th derivative of sum p[j] z^j at z."""
    total = 0.0
    for j in range(m, len(p)):
        total += p[j] * math.perm(j, m) * z ** (j - m)
    return total


def coefficient(i, tau):
    # psi_i(z) = (x_{i+1} - z) ... (x_{i+k-1} - z) / (k-1)!, coefficients in powers of z
    psi = [1.0]
    for j in range(1, k):
        psi = poly_mul(psi, [x[i + j], -1.0])
    psi = [c / math.factorial(k - 1) for c in psi]
    return sum(
        (-1) ** (k - 1 - r) * poly_deriv_at(psi, k - 1 - r, tau) * f(tau, r) for r in range(k)
    )


def first_knot_after(i):
    return min(v for v in x if v > x[i])


def first_interval_midpoint(i):
    j = next(j for j in range(i, i + k) if x[j] < x[j + 1])
    return 0.5 * (x[j] + x[j + 1])


RULES = {
    "first_knot_after": first_knot_after,
    "left_end_of_support": lambda i: x[i],
    "midpoint": lambda i: 0.5 * (x[i] + x[i + k]),
    "greville": lambda i: sum(x[i + 1 : i + k]) / (k - 1),
    "first_interval_midpoint": first_interval_midpoint,
}

for name, rule in RULES.items():
    c = [coefficient(i, min(max(rule(i), x[i]), x[i + k])) for i in range(n)]
    best = (0.0, 0.0)
    for j in range(61):
        t = 3.0 * j / 60
        q = sum(c[i] * bspline(i, k, t) for i in range(n))
        e = abs(q - f(t, 0))
        if e > best[0]:
            best = (e, t)
    print(f"{name:24s} {best[0]!r:24s} at {best[1]}")
