"""Open CASCADE's mesh of the benchmark surface through OCP (cadquery-ocp): the triangle count
and time of BRepMesh_IncrementalMesh at deflection 1e-4 on the bicubic 50x50-patch surface of
crates/lekalo/benches/query.rs (the C++ peer bench/peers/occt_queries.cpp times it too, but
cannot read the triangulation with Debian's headers).

    target/ocp-venv/bin/python bench/peers/occt_queries.py
"""
import math
import time

from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.Geom import Geom_BSplineSurface
from OCP.gp import gp_Pnt
from OCP.TopLoc import TopLoc_Location

try:  # OCP 7.x names
    from OCP.TColgp import TColgp_Array2OfPnt as Array2_Pnt
    from OCP.TColStd import TColStd_Array1OfInteger as Array1_Int
    from OCP.TColStd import TColStd_Array1OfReal as Array1_Real
except ImportError:  # cadquery-ocp 8
    from OCP.OCP.collections import Array1_double as Array1_Real
    from OCP.OCP.collections import Array1_int as Array1_Int
    from OCP.OCP.collections import Array2_gp_Pnt as Array2_Pnt

N = 53
net = Array2_Pnt(1, N, 1, N)
for i in range(N):
    for j in range(N):
        z = 0.3 * math.sin(0.4 * i) * math.cos(0.3 * j) + 0.1 * math.sin(0.9 * i + 0.5 * j)
        net.SetValue(i + 1, j + 1, gp_Pnt(i / (N - 1), j / (N - 1), z))
pieces = N - 3
knots = Array1_Real(1, pieces + 1)
mults = Array1_Int(1, pieces + 1)
for i in range(pieces + 1):
    knots.SetValue(i + 1, i / pieces)
    mults.SetValue(i + 1, 4 if i in (0, pieces) else 1)
surf = Geom_BSplineSurface(net, knots, knots, mults, mults, 3, 3)
times = []
for _ in range(3):
    face = BRepBuilderAPI_MakeFace(surf, 1e-7).Face()
    t0 = time.perf_counter()
    BRepMesh_IncrementalMesh(face, 1e-4, False, 0.5, False)
    times.append(time.perf_counter() - t0)
tri = BRep_Tool.Triangulation_s(face, TopLoc_Location())
print(f"mesh_50x50 OCP BRepMesh_IncrementalMesh(1e-4): median {sorted(times)[1]:.3f} s, "
      f"{tri.NbTriangles()} triangles, {tri.NbNodes()} nodes")
