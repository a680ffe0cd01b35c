"""Golden values for the geometric queries from Open CASCADE (PyPI's cadquery-ocp).

Writes queries_occt.json beside this file: arc lengths and parameters at lengths
(GCPnts_AbscissaPoint), closest points with every extremum (GeomAPI_ProjectPointOnCurve) and
planar curve-curve intersections (Geom2dAPI_InterCurveCurve) of the curves defined below; the
test crates/lekalo/tests/all/queries.rs rebuilds the same curves in lekalo and compares.

    python3 -m venv target/ocp-venv && target/ocp-venv/bin/pip install cadquery-ocp
    target/ocp-venv/bin/python crates/lekalo/tests/data/queries_occt.py
"""
import json
import math
from pathlib import Path

from OCP.GCPnts import GCPnts_AbscissaPoint
from OCP.Geom import Geom_BSplineCurve
from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.Geom2dAPI import Geom2dAPI_InterCurveCurve, Geom2dAPI_ProjectPointOnCurve
from OCP.GeomAdaptor import GeomAdaptor_Curve
from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
from OCP.gp import gp_Pnt, gp_Pnt2d

try:  # OCP 7.x names
    from OCP.TColgp import TColgp_Array1OfPnt as Array1_Pnt
    from OCP.TColgp import TColgp_Array1OfPnt2d as Array1_Pnt2d
    from OCP.TColStd import TColStd_Array1OfInteger as Array1_Int
    from OCP.TColStd import TColStd_Array1OfReal as Array1_Real
except ImportError:  # cadquery-ocp 8
    from OCP.OCP.collections import Array1_double as Array1_Real
    from OCP.OCP.collections import Array1_gp_Pnt as Array1_Pnt
    from OCP.OCP.collections import Array1_gp_Pnt2d as Array1_Pnt2d
    from OCP.OCP.collections import Array1_int as Array1_Int

# The curves: degree, full knot vector, control points (2-D or 3-D), optional weights.
CURVES = {
    "cubic2d": {
        "degree": 3,
        "knots": [0, 0, 0, 0, 0.15, 0.4, 0.5, 0.8, 1, 1, 1, 1],
        "control": [[0, 0], [1, 2], [2.5, -1], [4, 3], [5, -2], [6.5, 1], [7, 3], [9, 0]],
    },
    "cubic2d_b": {
        "degree": 3,
        "knots": [0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1],
        "control": [[-1, 1], [2, -2], [3, 3], [6, -1], [8, 2], [10, 0.5]],
    },
    "cubic3d": {
        "degree": 3,
        "knots": [0, 0, 0, 0, 1, 2, 3, 3, 3, 3],
        "control": [[0, 0, 0], [1, 2, 1], [3, 3, -1], [5, 0, 2], [6, -2, 0], [8, 1, 1]],
    },
    "rational2d": {
        "degree": 2,
        "knots": [0, 0, 0, 0.5, 1, 1, 1],
        "control": [[1, 0], [1, 1.5], [-0.5, 1.5], [-1, 0]],
        "weights": [1, 0.6, 1.7, 1],
    },
}


def knots_mults(full):
    ks, ms = [], []
    for k in full:
        if ks and k == ks[-1]:
            ms[-1] += 1
        else:
            ks.append(float(k))
            ms.append(1)
    return ks, ms


def arr_real(xs):
    a = Array1_Real(1, len(xs))
    for i, x in enumerate(xs):
        a.SetValue(i + 1, float(x))
    return a


def arr_int(xs):
    a = Array1_Int(1, len(xs))
    for i, x in enumerate(xs):
        a.SetValue(i + 1, int(x))
    return a


def curve3d(c):
    ctrl = c["control"]
    poles = Array1_Pnt(1, len(ctrl))
    for i, p in enumerate(ctrl):
        p3 = list(map(float, p)) + [0.0] * (3 - len(p))
        poles.SetValue(i + 1, gp_Pnt(*p3))
    ks, ms = knots_mults(c["knots"])
    if "weights" in c:
        return Geom_BSplineCurve(poles, arr_real(c["weights"]), arr_real(ks), arr_int(ms), c["degree"])
    return Geom_BSplineCurve(poles, arr_real(ks), arr_int(ms), c["degree"])


def curve2d(c):
    ctrl = c["control"]
    poles = Array1_Pnt2d(1, len(ctrl))
    for i, p in enumerate(ctrl):
        poles.SetValue(i + 1, gp_Pnt2d(float(p[0]), float(p[1])))
    ks, ms = knots_mults(c["knots"])
    if "weights" in c:
        return Geom2d_BSplineCurve(poles, arr_real(c["weights"]), arr_real(ks), arr_int(ms), c["degree"])
    return Geom2d_BSplineCurve(poles, arr_real(ks), arr_int(ms), c["degree"])


def lengths(name, c):
    ad = GeomAdaptor_Curve(curve3d(c))
    a, b = ad.FirstParameter(), ad.LastParameter()
    total = GCPnts_AbscissaPoint.Length_s(ad, 1e-14)
    parts = []
    for f0, f1 in [(0.0, 0.37), (0.2, 0.9), (0.5, 1.0)]:
        u0, u1 = a + f0 * (b - a), a + f1 * (b - a)
        parts.append({"from": u0, "to": u1, "length": GCPnts_AbscissaPoint.Length_s(ad, u0, u1, 1e-14)})
    inverse = []
    for f in [0.1, 0.25, 0.5, 0.75, 0.99]:
        s = f * total
        ap = GCPnts_AbscissaPoint(1e-14, ad, s, a)
        inverse.append({"length": s, "t": ap.Parameter()})
    return {"curve": name, "length": total, "parts": parts, "inverse": inverse}


def projections(name, c, queries):
    g = curve3d(c)
    out = []
    for q in queries:
        q3 = list(map(float, q)) + [0.0] * (3 - len(q))
        pr = GeomAPI_ProjectPointOnCurve(gp_Pnt(*q3), g)
        ext = [{"t": pr.Parameter(i), "distance": pr.Distance(i)} for i in range(1, pr.NbPoints() + 1)]
        best = {"t": pr.LowerDistanceParameter(), "distance": pr.LowerDistance()} if pr.NbPoints() else None
        out.append({"curve": name, "query": q, "closest": best, "extrema": ext})
    return out


def intersections(a, b):
    ca, cb = curve2d(CURVES[a]), curve2d(CURVES[b])
    inter = Geom2dAPI_InterCurveCurve(ca, cb, 1e-10)
    pts = []
    for i in range(1, inter.NbPoints() + 1):
        p = inter.Point(i)
        # the parameters on both curves: the point projected back onto each
        t_a = Geom2dAPI_ProjectPointOnCurve(p, ca).LowerDistanceParameter()
        t_b = Geom2dAPI_ProjectPointOnCurve(p, cb).LowerDistanceParameter()
        pts.append({"t_a": t_a, "t_b": t_b, "point": [p.X(), p.Y()]})
    return {"a": a, "b": b, "points": pts, "segments": inter.NbSegments()}


def main():
    queries2d = [[3.0, 4.0], [5.0, -1.0], [-3.0, 0.5], [10.0, 2.0], [4.5, 0.5], [1.2, 0.9], [7.5, 5.0]]
    queries3d = [[3.0, 4.0, 0.0], [5.0, -1.0, 2.0], [-3.0, 0.5, 1.0], [4.0, 0.5, 0.5], [9.0, 3.0, -2.0]]
    queriesr = [[0.0, 0.0], [0.3, 2.0], [2.0, 1.0], [-1.5, -0.5], [0.0, 1.0]]
    out = {
        "generator": "crates/lekalo/tests/data/queries_occt.py (Open CASCADE via cadquery-ocp)",
        "curves": CURVES,
        "lengths": [lengths(n, c) for n, c in CURVES.items()],
        "projections": projections("cubic2d", CURVES["cubic2d"], queries2d)
        + projections("cubic3d", CURVES["cubic3d"], queries3d)
        + projections("rational2d", CURVES["rational2d"], queriesr),
        "intersections": [intersections("cubic2d", "cubic2d_b")],
    }
    path = Path(__file__).with_name("queries_occt.json")
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
