"""Reference values for crates/lekalo/tests/all/interpolation.rs (`scipy_agreement`).

Independent implementation: SciPy's make_interp_spline (banded LU with pivoting, gbsv) and
CubicSpline. Run with any recent SciPy:  python3 interpolation_scipy.py
The data, parameters and knots are built here from their definitions (document 000 eq. 3, 4, 8;
chord length), not taken from lekalo.
"""
import numpy as np
from scipy.interpolate import make_interp_spline, CubicSpline

k = np.arange(10.0)
q = np.stack([k + 0.3 * np.sin(1.7 * k), np.cos(0.9 * k), 0.02 * k * k], axis=1)
d0, dn = np.array([1.0, -0.5, 0.25]), np.array([0.5, 2.0, -1.0])
us = [0.05, 0.37, 0.81, 0.999]


def chord(pts):
    d = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    t = np.concatenate([[0.0], np.cumsum(d)]) / d.sum()
    t[-1] = 1.0
    return t


def averaged(t, p):
    n = len(t) - 1
    inner = [t[j:j + p].mean() for j in range(1, n - p + 1)]
    return np.concatenate([[t[0]] * (p + 1), inner, [t[-1]] * (p + 1)])


def averaged_ends(t, p):
    n = len(t) - 1
    inner = [t[j:j + p].mean() for j in range(0, n - p + 2)]
    return np.concatenate([[t[0]] * (p + 1), inner, [t[-1]] * (p + 1)])


def show(name, f):
    print(name)
    for u in us:
        print("    (%r, [%s])," % (u, ", ".join(repr(float(v)) for v in f(u))))


t = chord(q)
show("free cubic", make_interp_spline(t, q, k=3, t=averaged(t, 3)))
show("free quintic", make_interp_spline(t, q, k=5, t=averaged(t, 5)))
show("A.2 quartic", make_interp_spline(t, q, k=4, t=averaged_ends(t, 4),
                                       bc_type=([(1, d0)], [(1, dn)])))
show("A.3 clamped cubic", CubicSpline(t, q, bc_type=((1, d0), (1, dn))))
show("natural cubic", CubicSpline(t, q, bc_type="natural"))
closed = np.vstack([q, q[:1]])
show("periodic cubic", CubicSpline(chord(closed), closed, bc_type="periodic"))
