#!/usr/bin/env python3
"""STEP and IGES test files written by an independent kernel (Open CASCADE, through PyPI's
cadquery-ocp), and the check that Open CASCADE reads lekalo's STEP and IGES output back.

    python3 -m venv target/occ-venv && target/occ-venv/bin/pip install cadquery-ocp
    target/occ-venv/bin/python scripts/occ_step_files.py write   # test data (run once)
    target/occ-venv/bin/python scripts/occ_step_files.py check target/release/lekalo

`write` builds B-spline and NURBS curves and surfaces with Open CASCADE, writes them with
STEPControl_Writer (AP214 in millimetres, AP242 in metres; curves as a geometric curve set,
surfaces as faces), reads each file back with STEPControl_Reader and stores what Open CASCADE
read (degree, knots, control points, weights, in millimetres) next to the files as
`<name>.expect.json`: crates/lekalo-io/tests/data/occ/. It does the same for IGES with
IGESControl_Writer (curves as entity 126, faces as entity 144 over entity 128, in millimetres and
in metres) and IGESControl_Reader. The Rust tests read the files and compare with these values bit
for bit (both sides parse the same decimal text).

`check LEKALO` runs the round trip through the command line: lekalo reads each file, inserts a
knot into every curve (a modification that keeps the geometry), writes STEP and IGES; Open
CASCADE reads lekalo's files and every curve and surface is compared with the original at 101 (11 x 11)
parameters: the largest distance must be below 1e-12 of the object's size.

`check` then does the same for faces: Open CASCADE builds solids (a box, a box with a round hole
through it, converted to B-spline faces with pcurves) and writes them to STEP; lekalo reads their
faces (`convert --faces`), writes them as JSON Lines and from there to STEP and IGES. Open
CASCADE reads lekalo's files: the numbers of faces, wires and edges must be those of the
original, BRepCheck_Analyzer must find the shapes valid, and the areas must agree within 1e-9.
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace
from OCP.BRep import BRep_Builder
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.gp import gp_Pnt
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.STEPControl import (STEPControl_AsIs, STEPControl_GeometricCurveSet,
                             STEPControl_Reader, STEPControl_Writer)
try:  # OCP 7.x names
    from OCP.TColgp import TColgp_Array1OfPnt, TColgp_Array2OfPnt
    from OCP.TColStd import (TColStd_Array1OfInteger, TColStd_Array1OfReal,
                             TColStd_Array2OfReal)
except ImportError:  # cadquery-ocp 8
    from OCP.OCP.collections import Array1_double as TColStd_Array1OfReal
    from OCP.OCP.collections import Array1_gp_Pnt as TColgp_Array1OfPnt
    from OCP.OCP.collections import Array1_int as TColStd_Array1OfInteger
    from OCP.OCP.collections import Array2_double as TColStd_Array2OfReal
    from OCP.OCP.collections import Array2_gp_Pnt as TColgp_Array2OfPnt
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "crates", "lekalo-io", "tests", "data", "occ")


def arr1(values, cls=TColStd_Array1OfReal):
    a = cls(1, len(values))
    for i, v in enumerate(values):
        a.SetValue(i + 1, v)
    return a


def curve(poles, knots, mults, degree, weights=None):
    p = TColgp_Array1OfPnt(1, len(poles))
    for i, q in enumerate(poles):
        p.SetValue(i + 1, gp_Pnt(*q))
    k, m = arr1(knots), arr1(mults, TColStd_Array1OfInteger)
    if weights is None:
        return Geom_BSplineCurve(p, k, m, degree)
    return Geom_BSplineCurve(p, arr1(weights), k, m, degree)


def surface(net, uk, vk, um, vm, du, dv, weights=None):
    nu, nv = len(net), len(net[0])
    p = TColgp_Array2OfPnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            p.SetValue(i + 1, j + 1, gp_Pnt(*net[i][j]))
    args = [arr1(uk), arr1(vk), arr1(um, TColStd_Array1OfInteger), arr1(vm, TColStd_Array1OfInteger), du, dv]
    if weights is None:
        return Geom_BSplineSurface(p, *args)
    w = TColStd_Array2OfReal(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            w.SetValue(i + 1, j + 1, weights[i][j])
    return Geom_BSplineSurface(p, w, *args)


def curves():
    s = math.sqrt(0.5)
    return [
        # a cubic with non-uniform knots and awkward coordinates
        curve([(0.0, 0.0, 0.0), (1.0 / 3.0, 2.0, 0.1), (2.5, 2.0 / 7.0, -1.0), (4.0, 1e-3, 0.5),
               (5.0, 3.0, 2.0 / 3.0), (7.0, 0.0, 0.0)],
              [0.0, 0.3, 0.7, 1.0], [4, 1, 1, 4], 3),
        # a quarter circle, rational
        curve([(10.0, 0.0, 0.0), (10.0, 10.0, 0.0), (0.0, 10.0, 0.0)], [0.0, 1.0], [3, 3], 2,
              [1.0, s, 1.0]),
        # a rational quartic on a non-unit domain with a double knot
        curve([(0.0, 0.0, 1.0), (1.0, 2.0, 0.0), (2.0, -1.0, 3.0), (3.0, 0.5, 0.25), (4.0, 4.0, 4.0),
               (5.0, 1.0, -2.0), (6.0, 0.0, 0.0)],
              [2.0, 3.5, 5.0], [5, 2, 5], 4, [1.0, 0.8, 1.7, 0.6, 2.0, 0.9, 1.0]),
    ]


def surfaces():
    net = [[(float(i), float(j), math.sin(i + 0.3 * j) / 3.0) for j in range(4)] for i in range(5)]
    w = [[1.0 + 0.1 * ((i * 7 + j * 3) % 5) for j in range(4)] for i in range(5)]
    return [
        surface(net, [0.0, 0.4, 1.0], [0.0, 1.0], [3, 2, 3], [4, 4], 2, 3),
        surface(net, [0.0, 1.0, 2.5], [0.0, 1.0], [3, 2, 3], [4, 4], 2, 3, w),
    ]


def write_step(path, schema, unit, curves_, surfaces_):
    Interface_Static.SetCVal_s("write.step.schema", schema)
    Interface_Static.SetCVal_s("write.step.unit", unit)
    w = STEPControl_Writer()
    for c in curves_:
        e = BRepBuilderAPI_MakeEdge(c).Edge()
        assert w.Transfer(e, STEPControl_GeometricCurveSet) == IFSelect_RetDone
    for s in surfaces_:
        f = BRepBuilderAPI_MakeFace(s, 1e-9).Face()
        assert w.Transfer(f, STEPControl_AsIs) == IFSelect_RetDone
    assert w.Write(path) == IFSelect_RetDone, path


def write_iges(path, unit, curves_, surfaces_):
    from OCP.IGESControl import IGESControl_Controller, IGESControl_Writer
    IGESControl_Controller.Init_s()
    w = IGESControl_Writer(unit, 0)  # mode 0: faces (entity 144 over 128), not BRep solids
    for c in curves_:
        assert w.AddShape(BRepBuilderAPI_MakeEdge(c).Edge())
    for s in surfaces_:
        assert w.AddShape(BRepBuilderAPI_MakeFace(s, 1e-9).Face())
    w.ComputeModel()
    assert w.Write(path), path


def read_step(path):
    r = reader(path)
    r.TransferRoots()
    shape = r.OneShape()
    out = []
    ex = TopExp_Explorer(shape, TopAbs_EDGE, TopAbs_FACE)
    seen = set()
    while ex.More():
        e = TopoDS.Edge(ex.Current())
        ex.Next()
        a = BRepAdaptor_Curve(e)
        c = a.BSpline()
        key = ("c", c.NbPoles(), c.Pole(1).X(), c.Pole(1).Y())
        if key in seen:
            continue
        seen.add(key)
        out.append(curve_json(c))
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        f = TopoDS.Face(ex.Current())
        ex.Next()
        out.append(surface_json(BRepAdaptor_Surface(f).BSpline()))
    return out


def reader(path):
    """Open CASCADE's reader of the file (IGES for .igs and .iges, else STEP), the file read."""
    if path.lower().endswith((".igs", ".iges")):
        from OCP.IGESControl import IGESControl_Reader
        r = IGESControl_Reader()
    else:
        r = STEPControl_Reader()
    assert r.ReadFile(path) == IFSelect_RetDone, path
    return r


def flat_knots(knots, mults):
    out = []
    for k, m in zip(knots, mults):
        out += [k] * m
    return out


def curve_json(c):
    n = c.NbPoles()
    k = [c.Knot(i) for i in range(1, c.NbKnots() + 1)]
    m = [c.Multiplicity(i) for i in range(1, c.NbKnots() + 1)]
    pts = [[c.Pole(i).X(), c.Pole(i).Y(), c.Pole(i).Z()] for i in range(1, n + 1)]
    j = {"kind": "curve", "degree": c.Degree(), "knots": flat_knots(k, m), "control": pts}
    if c.IsRational():
        j["weights"] = [c.Weight(i) for i in range(1, n + 1)]
    return j


def surface_json(s):
    nu, nv = s.NbUPoles(), s.NbVPoles()
    uk = flat_knots([s.UKnot(i) for i in range(1, s.NbUKnots() + 1)],
                    [s.UMultiplicity(i) for i in range(1, s.NbUKnots() + 1)])
    vk = flat_knots([s.VKnot(i) for i in range(1, s.NbVKnots() + 1)],
                    [s.VMultiplicity(i) for i in range(1, s.NbVKnots() + 1)])
    pts = [[s.Pole(i, j).X(), s.Pole(i, j).Y(), s.Pole(i, j).Z()]
           for i in range(1, nu + 1) for j in range(1, nv + 1)]
    j = {"kind": "surface", "degree": [s.UDegree(), s.VDegree()], "knots_u": uk, "knots_v": vk,
         "net": [nu, nv], "control": pts}
    if s.IsURational() or s.IsVRational():
        j["weights"] = [s.Weight(i, j) for i in range(1, nu + 1) for j in range(1, nv + 1)]
    return j


FILES = [
    ("curves_ap214_mm", "AP214CD", "MM", True, False),
    ("surfaces_ap214_mm", "AP214CD", "MM", False, True),
    ("mixed_ap242_m", "AP242DIS", "M", True, True),
]
# IGES files: (name, unit)
IGES_FILES = [("mixed_iges_mm", "MM"), ("mixed_iges_m", "M")]


def write():
    os.makedirs(DATA, exist_ok=True)
    for name, schema, unit, with_c, with_s in FILES:
        path = os.path.join(DATA, name + ".step")
        write_step(path, schema, unit, curves() if with_c else [], surfaces() if with_s else [])
        # a fixed header date, so that rewriting the data changes only what changed
        text = open(path).read()
        start = text.index("FILE_NAME(")
        date = text.index("'", text.index(",", start) + 1)
        end = text.index("'", date + 1)
        text = text[:date + 1] + "2000-01-01T00:00:00" + text[end:]
        open(path, "w").write(text)
        expect = read_step(path)
        with open(os.path.join(DATA, name + ".expect.json"), "w") as f:
            json.dump(expect, f, indent=1)
        print(f"{path}: {len(expect)} objects")
    for name, unit in IGES_FILES:
        path = os.path.join(DATA, name + ".igs")
        write_iges(path, unit, curves(), surfaces())
        # the global section's dates (YYYYMMDD.HHNNSS) fixed, at the same width so that the
        # 80-column layout holds
        text = re.sub(r"\d{8}\.\d{6}", "20000101.000000", open(path).read())
        open(path, "w").write(text)
        expect = read_step(path)
        with open(os.path.join(DATA, name + ".expect.json"), "w") as f:
            json.dump(expect, f, indent=1)
        print(f"{path}: {len(expect)} objects")


def distance(a, b):
    return math.sqrt((a.X() - b.X()) ** 2 + (a.Y() - b.Y()) ** 2 + (a.Z() - b.Z()) ** 2)


def deviation(a, b):
    """Largest distance between two curves or two surfaces at 101 (11 x 11) parameters of a's
    domain, relative to the size of a's control net; inf for different kinds or domains."""
    if isinstance(a, Geom_BSplineCurve) != isinstance(b, Geom_BSplineCurve):
        return math.inf
    origin = gp_Pnt(0, 0, 0)
    worst = 0.0
    if isinstance(a, Geom_BSplineCurve):
        lo, hi = a.FirstParameter(), a.LastParameter()
        if (lo, hi) != (b.FirstParameter(), b.LastParameter()):
            return math.inf
        size = max(distance(a.Pole(i), origin) for i in range(1, a.NbPoles() + 1))
        for k in range(101):
            t = lo + (hi - lo) * k / 100
            worst = max(worst, distance(a.Value(t), b.Value(t)) / size)
        return worst
    if a.Bounds() != b.Bounds():
        return math.inf
    u0, u1, v0, v1 = a.Bounds()
    size = max(distance(a.Pole(i, j), origin)
               for i in range(1, a.NbUPoles() + 1) for j in range(1, a.NbVPoles() + 1))
    for i in range(11):
        for j in range(11):
            u, v = u0 + (u1 - u0) * i / 10, v0 + (v1 - v0) * j / 10
            worst = max(worst, distance(a.Value(u, v), b.Value(u, v)) / size)
    return worst


def compare(orig, back):
    """For every object Open CASCADE read from the original file, the closest object it read
    from lekalo's file; the largest of these deviations."""
    return max(min(deviation(a, b) for b in back) for a in orig)


def occ_objects(path):
    r = reader(path)
    r.TransferRoots()
    shape = r.OneShape()
    out = []
    for kind, conv in ((TopAbs_EDGE, lambda x: BRepAdaptor_Curve(TopoDS.Edge(x)).BSpline()),
                       (TopAbs_FACE, lambda x: BRepAdaptor_Surface(TopoDS.Face(x)).BSpline())):
        ex = TopExp_Explorer(shape, kind, TopAbs_FACE) if kind == TopAbs_EDGE else TopExp_Explorer(shape, kind)
        while ex.More():
            out.append(conv(ex.Current()))
            ex.Next()
    return out


def check(lekalo):
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for name, *_ in FILES:
            src = os.path.join(DATA, name + ".step")
            jl = os.path.join(tmp, name + ".jsonl")
            subprocess.run([lekalo, "-q", "convert", src, "-o", jl], check=True)
            # modify: insert a knot in the middle of every curve's domain (same geometry)
            lines = open(jl).read().splitlines()
            out_lines = []
            for k, line in enumerate(lines):
                one = os.path.join(tmp, f"{name}_{k}.json")
                open(one, "w").write(line + "\n")
                obj = json.loads(line)
                if obj["type"].endswith("_curve"):
                    lo, hi = obj["knots"][obj["degree"]], obj["knots"][-obj["degree"] - 1]
                    mod = os.path.join(tmp, f"{name}_{k}_mod.json")
                    subprocess.run([lekalo, "-q", "knot", "insert", one, "--at", repr((lo + hi) / 2),
                                    "-o", mod], check=True)
                    one = mod
                out_lines.append(json.dumps(json.load(open(one))))
            mod_jl = os.path.join(tmp, name + "_mod.jsonl")
            open(mod_jl, "w").write("\n".join(out_lines) + "\n")
            back = os.path.join(tmp, name + "_back.step")
            subprocess.run([lekalo, "-q", "convert", mod_jl, "-o", back], check=True)
            orig, again = occ_objects(src), occ_objects(back)
            w = compare(orig, again)
            print(f"{name}: {len(orig)} objects, Open CASCADE reads lekalo's STEP file back, "
                  f"largest relative distance {w:.3g}")
            worst = max(worst, w)
            igs = os.path.join(tmp, name + "_back.igs")
            subprocess.run([lekalo, "-q", "convert", mod_jl, "-o", igs], check=True)
            w = compare(orig, occ_objects(igs))
            print(f"{name}: Open CASCADE reads lekalo's IGES file (entities 126, 128), "
                  f"largest relative distance {w:.3g}")
            worst = max(worst, w)
    assert worst <= 1e-12, worst
    print(f"all files: largest relative distance {worst:.3g} (limit 1e-12)")
    check_faces(lekalo)


def occ_shape(path):
    r = reader(path)
    r.TransferRoots()
    return r.OneShape()


def topology(shape):
    """Faces, and the wires and edges of the faces (each counted once), whether BRepCheck finds the shape valid, area."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.TopAbs import TopAbs_WIRE
    from OCP.TopExp import TopExp
    try:
        from OCP.TopTools import TopTools_IndexedMapOfShape
    except ImportError:  # cadquery-ocp 8
        from OCP.OCP.collections import (
            IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as TopTools_IndexedMapOfShape)
    faces = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, TopAbs_FACE, faces)
    counts = [faces.Extent()]
    for kind in (TopAbs_WIRE, TopAbs_EDGE):
        # those of the faces (a file may hold loose curves too)
        m = TopTools_IndexedMapOfShape()
        for i in range(1, faces.Extent() + 1):
            TopExp.MapShapes_s(faces.FindKey(i), kind, m)
        counts.append(m.Extent())
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props, 1e-10)
    return (*counts, BRepCheck_Analyzer(shape).IsValid(), props.Mass())


def check_faces(lekalo):
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepBuilderAPI import BRepBuilderAPI_NurbsConvert
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir
    box = BRepPrimAPI_MakeBox(10.0, 20.0, 5.0).Shape()
    cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5.0, 10.0, -1.0), gp_Dir(0.0, 0.0, 1.0)), 2.0, 7.0).Shape()
    solids = {
        "box": box,
        "box_with_hole": BRepAlgoAPI_Cut(box, cyl).Shape(),
    }
    with tempfile.TemporaryDirectory() as tmp:
        sources = []
        for name, shape in solids.items():
            path = os.path.join(tmp, name + ".step")
            w = STEPControl_Writer()
            w.Transfer(BRepBuilderAPI_NurbsConvert(shape, True).Shape(), STEPControl_AsIs)
            assert w.Write(path) == IFSelect_RetDone
            sources.append((name, path))
        for name in ("surfaces_ap214_mm", "mixed_ap242_m"):
            sources.append((name, os.path.join(DATA, name + ".step")))
        for name, src in sources:
            jl = os.path.join(tmp, name + "_faces.jsonl")
            subprocess.run([lekalo, "-q", "convert", src, "--faces", "-o", jl], check=True)
            orig = topology(occ_shape(src))
            for ext in ("step", "igs"):
                back = os.path.join(tmp, name + "_faces." + ext)
                subprocess.run([lekalo, "-q", "convert", jl, "-o", back], check=True)
                got = topology(occ_shape(back))
                print(f"{name} -> lekalo {ext}: Open CASCADE reads {got[0]} faces, {got[1]} wires, "
                      f"{got[2]} edges, valid {got[3]}, area {got[4]:.12g} "
                      f"(original: {orig[0]}, {orig[1]}, {orig[2]}, valid {orig[3]}, area {orig[4]:.12g})")
                assert got[0] == orig[0] and got[1] == orig[1], (name, ext, got, orig)
                # IGES shares no edges between trimmed surfaces: each face has its own
                if ext == "step":
                    assert got[2] == orig[2], (name, ext, got, orig)
                assert got[3], (name, ext, "BRepCheck_Analyzer finds the shape invalid")
                assert abs(got[4] - orig[4]) <= 1e-9 * orig[4], (name, ext, got[4], orig[4])
    print("faces: Open CASCADE reads lekalo's STEP and IGES faces with the original topology")


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "write":
        write()
    elif len(sys.argv) >= 3 and sys.argv[1] == "check":
        check(sys.argv[2])
    else:
        sys.exit(__doc__)
