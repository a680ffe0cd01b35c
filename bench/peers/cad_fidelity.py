#!/usr/bin/env python3
"""Every judged check of reading STEP and IGES files, lekalo against Open CASCADE, one table row a
file.

    V=target/occ-venv/bin/python   # a venv with cadquery-ocp, numpy and scipy (scripts/occ_step_files.py)
    $V bench/peers/cad_fidelity.py [--repeats 3] [--tolerance 0.1] FILE ...

For each file:

- **counts**, each side: faces, loops (wires), edges (each counted once), surfaces and curves.
  lekalo's come from `lekalo convert --faces` (faces, loops, edges by their file id) and `lekalo
  convert` (the file's curves and surfaces); Open CASCADE's from STEPControl_Reader or
  IGESControl_Reader + TransferRoots (faces, their wires and edges as scripts/occ_step_files.py
  counts them, the distinct surfaces of the faces and the distinct 3-D curves of the edges).
  `dropped` is what lekalo lists on standard error as skipped.
- **read**: each of lekalo's faces is matched to Open CASCADE's face with the nearest centroid of
  edge end points (the six nearest are tried; the smallest difference counts), and compared:
  two B-spline surfaces with the same degrees and nets by their poles, weights and knots (the
  largest difference, relative to the face's size for the poles); otherwise (an analytic surface
  Open CASCADE keeps as such) by the distance from lekalo's surface at 9 x 9 parameters to Open
  CASCADE's surface (ShapeAnalysis_Surface), relative to the face's size. Each face's loops are
  compared as the sorted numbers of edges of its loops (or, where Open CASCADE joined loops that
go round a closed surface into one wire by a seam edge, as the numbers of loops and edges once
its seams are taken out, or, where Open CASCADE split an edge, as loops of the same lengths),
and each of its 3-D edge curves by the
  distance of 9 of its points to the nearest of the Open CASCADE face's edges.
- **write-back**: lekalo writes the faces to STEP and to IGES; Open CASCADE reads them: the
  counts of faces and wires (and edges, for STEP: IGES shares no edges between trimmed
  surfaces) must equal those of its read of the original, BRepCheck_Analyzer must find them
  valid, and each face read back is compared with lekalo's face as above.
- **time**: CPU seconds of a read (median of REPEATS, lekalo and Open CASCADE in C++ alternated:
  bench/peers/cad_read.py's programs), and the ratio Open CASCADE / lekalo.
- **mesh**: `lekalo mesh` of the faces at --tolerance (model units, millimetres): its proved
  deviation, the faces it left out, and the largest gap between neighbouring faces: the mesh's
  boundary segments (used by one triangle) that lie along an edge two faces share (within the
  tolerance of its 3-D curve) are cracks; the gap is the largest distance from such a segment's
  midpoint to the nearest other boundary segment.

A cell fails (marked `!`) when a difference is above 1e-12, a count differs, a face is dropped,
a shape is invalid, a read is slower than Open CASCADE's, or the mesh is above its tolerance.
"""
import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
sys.path.insert(0, str(HERE))

import cad_read  # noqa: E402  (timing programs: build, run)
import occ_step_files as occ  # noqa: E402  (Open CASCADE reading, counting, B-spline makers)
from OCP.BRep import BRep_Tool  # noqa: E402
from OCP.BRepAdaptor import BRepAdaptor_Curve  # noqa: E402
from OCP.GCPnts import GCPnts_AbscissaPoint  # noqa: E402
from OCP.GeomAdaptor import GeomAdaptor_Curve  # noqa: E402
from OCP.Geom import Geom_BSplineSurface, Geom_RectangularTrimmedSurface  # noqa: E402
from OCP.gp import gp_Pnt  # noqa: E402
from OCP.ShapeAnalysis import ShapeAnalysis_Curve, ShapeAnalysis_Surface  # noqa: E402
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_WIRE  # noqa: E402
from OCP.TopExp import TopExp_Explorer  # noqa: E402
from OCP.TopoDS import TopoDS  # noqa: E402

LIMIT = 1e-12
LEKALO = ROOT / "target" / "release" / "lekalo"
SAMPLES = 9
# the Open CASCADE faces with the nearest centroids a face is compared with: a face Open CASCADE
# splits in two (a cylinder between four circles, two bands) has its centroid between theirs
NEAREST = 6


def lekalo(*args):
    """Runs the CLI; (stdout, stderr)."""
    p = subprocess.run([str(LEKALO), *map(str, args)], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"lekalo {' '.join(map(str, args))}: {p.stderr.strip()[-400:]}")
    return p.stdout, p.stderr


def skipped(stderr):
    """The number of entities lekalo lists as skipped on standard error."""
    m = re.findall(r"skipped (\d+) (?:entit|face)", stderr)
    return sum(int(x) for x in m)


# ---- lekalo's objects as Open CASCADE geometry (its evaluator, independent of lekalo's)


def c0_knots(flat, degree, rows, axis):
    """Open CASCADE holds no interior knot of multiplicity degree + 1 (lekalo's exact form of
    IGES piecewise polynomials, entities 112 and 114): where the two control rows (weighted
    points) at such a knot agree (an IGES file prints its patches'
    coefficients to a few digits, so the patches meet only that closely: Open CASCADE joins
    them too) within 1e-5 of the size, the two rows become their midpoint and one knot goes."""
    flat = list(flat)
    k = degree + 1
    while k < len(flat) - degree - 1:
        if flat[k] == flat[k - degree] and flat[k] < flat[-1]:
            i = k - degree - 1  # the last row of the left piece; the next starts the right
            a, b = np.take(rows, i, axis=axis), np.take(rows, i + 1, axis=axis)
            if np.abs(a - b).max() <= 1e-5 * max(np.abs(rows).max(), 1e-300):
                rows = np.delete(rows, i + 1, axis=axis)
                index = [slice(None)] * rows.ndim
                index[axis] = i
                rows[tuple(index)] = 0.5 * (a + b)
                del flat[k]
                continue
        k += 1
    return flat, rows


def to_occ(obj):
    """A lekalo curve or surface (JSON) as Open CASCADE's Geom_BSplineCurve / Surface."""
    if obj["type"].endswith("_surface"):
        nu, nv = obj["net"]
        w = obj.get("weights")
        net = np.asarray(obj["control"], dtype=float).reshape(nu, nv, -1)
        ww = np.asarray(w, dtype=float).reshape(nu, nv, 1) if w else np.ones((nu, nv, 1))
        rows = np.concatenate([net * ww, ww], axis=2)
        ku, rows = c0_knots(obj["knots_u"], obj["degree_u"], rows, 0)
        kv, rows = c0_knots(obj["knots_v"], obj["degree_v"], rows, 1)
        net = (rows[:, :, :-1] / rows[:, :, -1:]).tolist()
        weights = rows[:, :, -1].tolist() if w else None
        uk, um = distinct(ku)
        vk, vm = distinct(kv)
        return occ.surface(net, uk, vk, um, vm, obj["degree_u"], obj["degree_v"], weights)
    w = obj.get("weights")
    pts = np.asarray([list(p) + [0.0] * (3 - len(p)) for p in obj["control"]], dtype=float)
    ww = np.asarray(w, dtype=float).reshape(-1, 1) if w else np.ones((len(pts), 1))
    knots, rows = c0_knots(obj["knots"], obj["degree"], np.concatenate([pts * ww, ww], axis=1), 0)
    k, m = distinct(knots)
    return occ.curve((rows[:, :-1] / rows[:, -1:]).tolist(), k, m, obj["degree"],
                     rows[:, -1].tolist() if w else None)


def distinct(flat):
    knots, mults = [], []
    for t in flat:
        if knots and t == knots[-1]:
            mults[-1] += 1
        else:
            knots.append(t)
            mults.append(1)
    return knots, mults


def xyz(p):
    return np.array([p.X(), p.Y(), p.Z()])


# ---- Open CASCADE's faces


class OccFace:
    """A face Open CASCADE read: its surface (located), loops, edges' curves and the centroid of
    its edges' end points."""

    def __init__(self, face):
        self.face = face
        s = BRep_Tool.Surface_s(face)
        while isinstance(s, Geom_RectangularTrimmedSurface):
            s = s.BasisSurface()
        self.surface = s
        self.loops = []
        # the loops without the seams Open CASCADE adds: a face of a closed surface bounded by
        # two loops that go round it (a cylinder between two circles) is one wire for Open
        # CASCADE, the two circles joined by a seam edge run once each way; as (edges that are
        # not seams, wires + seams)
        plain, seams = 0, 0
        # the length of each wire without its seams
        self.lengths = []
        ex = TopExp_Explorer(face, TopAbs_WIRE)
        while ex.More():
            # the edges that are curves: Open CASCADE adds a degenerated edge at a pole
            n, length = 0, 0.0
            ee = TopExp_Explorer(ex.Current(), TopAbs_EDGE)
            while ee.More():
                e = TopoDS.Edge(ee.Current())
                if not BRep_Tool.Degenerated_s(e):
                    n += 1
                    if BRep_Tool.IsClosed_s(e, face):
                        seams += 1
                    else:
                        plain += 1
                        length += GCPnts_AbscissaPoint.Length_s(BRepAdaptor_Curve(e))
                ee.Next()
            self.loops.append(n)
            self.lengths.append(length)
            ex.Next()
        self.loops.sort()
        self.lengths.sort()
        self.seams = seams
        self.unseamed = (plain, len(self.loops) + seams // 2)
        self.edges = []
        self.adaptors = []
        ends = []
        ex = TopExp_Explorer(face, TopAbs_EDGE)
        while ex.More():
            e = TopoDS.Edge(ex.Current())
            ex.Next()
            if BRep_Tool.Degenerated_s(e):
                continue
            a = BRepAdaptor_Curve(e)
            ends += [xyz(a.Value(a.FirstParameter())), xyz(a.Value(a.LastParameter()))]
            self.edges.append(e)
            self.adaptors.append(a)
        self.centroid = np.mean(ends, axis=0) if ends else np.zeros(3)
        self._analysis = None

    def distance_to_surface(self, p):
        if self._analysis is None:
            self._analysis = ShapeAnalysis_Surface(self.surface)
        a = self._analysis
        a.ValueOfUV(gp_Pnt(*p), 1e-15)
        return a.Gap()

    def distance_to_edges(self, p):
        """Distance from p to the nearest of the face's edges (ShapeAnalysis_Curve::Project)."""
        best = math.inf
        q = gp_Pnt(*p)
        for a in self.adaptors:
            best = min(best, ShapeAnalysis_Curve().Project(a, q, 1e-15, gp_Pnt(), 0.0))
        return best


def occ_faces(shape):
    out = []
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        face = TopoDS.Face(ex.Current())
        ex.Next()
        # a face without a surface (a triangulation only) has no geometry to compare
        if BRep_Tool.Surface_s(face) is not None:
            out.append(OccFace(face))
    return out


def occ_geometry_counts(faces):
    """The edges of the faces that are curves (not the degenerated edges Open CASCADE puts at
    poles), the distinct surfaces of the faces and distinct 3-D curves of their edges: as the shapes
    share them (the same geometry at the same place counts once)."""
    from OCP.OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as IMap
    from OCP.TopExp import TopExp
    surfaces = set()
    edges = IMap()
    for f in faces:
        s = f.surface
        u0, u1, v0, v1 = (max(min(b, 1e3), -1e3) for b in s.Bounds())
        surfaces.add(key(s.DynamicType().Name(),
                         [s.Value(u0 + (u1 - u0) * a, v0 + (v1 - v0) * b)
                          for a, b in ((0.1, 0.2), (0.7, 0.4), (0.3, 0.9))]))
        TopExp.MapShapes_s(f.face, TopAbs_EDGE, edges)
    curves = set()
    count = 0
    for i in range(1, edges.Extent() + 1):
        e = TopoDS.Edge(edges.FindKey(i))
        if BRep_Tool.Degenerated_s(e):
            continue
        count += 1
        a = BRepAdaptor_Curve(e)
        lo, hi = a.FirstParameter(), a.LastParameter()
        curves.add(key(a.GetType(), [a.Value(lo + (hi - lo) * t) for t in (0.0, 0.3, 1.0)]))
    return count, len(surfaces), len(curves)


def key(kind, points):
    return (str(kind), *(round(c, 6) for p in points for c in (p.X(), p.Y(), p.Z())))


# ---- the comparison of one lekalo face with one Open CASCADE face


def size_of(obj):
    c = np.asarray(obj["control"], dtype=float)
    return max(float(np.abs(c).max()), 1e-300)


def samples(lo, hi):
    return [lo + (hi - lo) * k / (SAMPLES - 1) for k in range(SAMPLES)]


def compare_face(ours, theirs):
    """(surface difference, loops equal, edge curve difference) of lekalo's face `ours` (JSON)
    against Open CASCADE's face `theirs`, relative to the face's size."""
    surf = ours["surface"]
    size = size_of(surf)
    s = theirs.surface
    d = None
    if isinstance(s, Geom_BSplineSurface):
        nu, nv = surf["net"]
        if (s.NbUPoles(), s.NbVPoles(), s.UDegree(), s.VDegree()) == (
                nu, nv, surf["degree_u"], surf["degree_v"]):
            j = occ.surface_json(s)
            d = float(np.abs(np.asarray(j["control"]) - np.asarray(surf["control"])).max()) / size
            w0 = np.asarray(j.get("weights", [1.0] * (nu * nv)))
            w1 = np.asarray(surf.get("weights", [1.0] * (nu * nv)))
            # weights are defined up to a common factor: compare the normalised ones
            d = max(d, float(np.abs(w0 / w0.max() - w1 / w1.max()).max()))
            for a, b in ((j["knots_u"], surf["knots_u"]), (j["knots_v"], surf["knots_v"])):
                span = max(abs(b[-1] - b[0]), 1e-300)
                d = max(d, float(np.abs(np.asarray(a) - np.asarray(b)).max()) / span)
    if d is None:
        g = to_occ(surf)
        u0, u1, v0, v1 = g.Bounds()
        d = max(theirs.distance_to_surface(xyz(g.Value(u, v)))
                for u in samples(u0, u1) for v in samples(v0, v1)) / size
    mine = sorted([len(ours["outer"])] + [len(lp) for lp in ours["inner"]])
    # the same loops, or the same loops once the seams Open CASCADE added are taken out, or
    # loops of the same lengths where Open CASCADE split an edge (a full circle shared with a
    # face whose seam is elsewhere is cut at the seam; each of lekalo's edges is checked to lie
    # on Open CASCADE's edges below)
    loops = mine == theirs.loops or (sum(mine), len(mine)) == theirs.unseamed
    if not loops and len(mine) == theirs.unseamed[1]:
        lengths = sorted(sum(GCPnts_AbscissaPoint.Length_s(GeomAdaptor_Curve(to_occ(e["curve"])))
                             for e in lp) for lp in [ours["outer"], *ours["inner"]])
        scale = max(max(lengths), 1e-300)
        if theirs.seams:
            loops = abs(sum(lengths) - sum(theirs.lengths)) <= 1e-9 * scale
        else:
            loops = all(abs(a - b) <= 1e-9 * scale for a, b in zip(lengths, theirs.lengths))
    e = 0.0
    for lp in [ours["outer"], *ours["inner"]]:
        for edge in lp:
            c = to_occ(edge["curve"])
            lo, hi = c.FirstParameter(), c.LastParameter()
            for t in samples(lo, hi):
                e = max(e, theirs.distance_to_edges(xyz(c.Value(t))) / size)
    return d, loops, e


def match(ours, theirs):
    """For each of lekalo's faces, the comparison with the best of the NEAREST Open CASCADE faces
    with the nearest centroids: lists of (surface difference, loops equal, edge difference)."""
    if not theirs:
        return []
    cents = np.array([f.centroid for f in theirs])
    out = []
    for face in ours:
        ends = []
        for lp in [face["outer"], *face["inner"]]:
            for edge in lp:
                c = edge["curve"]["control"]
                ends += [c[0], c[-1]]
        cen = np.mean(np.asarray(ends, dtype=float), axis=0)
        order = np.argsort(np.linalg.norm(cents - cen, axis=1))[:NEAREST]
        out.append(min((compare_face(face, theirs[k]) for k in order),
                       key=lambda r: (r[0] + r[2] > LIMIT, not r[1], r[0] + r[2])))
    return out


def edge_key(e):
    """An edge is its file id at a placement (an assembly places a part's edges more than once):
    the id and its end points."""
    c = e["curve"]["control"]
    return (e["edge_id"], *sorted([tuple(np.round(c[0], 6)), tuple(np.round(c[-1], 6))]))


def lekalo_counts(faces, geometry):
    loops = sum(1 + len(f["inner"]) for f in faces)
    edges = len({edge_key(e) for f in faces for lp in [f["outer"], *f["inner"]] for e in lp})
    kinds = [g["type"] for g in geometry]
    return [len(faces), loops, edges, sum(k.endswith("_surface") for k in kinds),
            sum(k.endswith("_curve") for k in kinds)]


# ---- the mesh


def point_segment(p, a, b):
    """Distance from p to the segment ab."""
    d = b - a
    t = float(np.clip(np.dot(p - a, d) / max(np.dot(d, d), 1e-300), 0.0, 1.0))
    return float(np.linalg.norm(a + t * d - p))


def mesh_check(faces_path, faces, tolerance, tmp):
    """(proved deviation, faces left out, largest gap along shared edges) of lekalo's mesh."""
    obj = os.path.join(tmp, "mesh.obj")
    _, err = lekalo("mesh", faces_path, "-t", tolerance, "--json", "-o", obj)
    summary = json.loads(err[err.index("{"):err.rindex("}") + 1])
    v, t = [], []
    for line in open(obj):
        if line.startswith("v "):
            v.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            t.append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    # the points the faces' meshes have in common are one vertex: those within 1e-9 of the
    # model's size of each other (the faces' meshes meet at points computed on either side)
    v, t = np.asarray(v), np.asarray(t)
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree
    radius = 1e-9 * float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))
    pairs = cKDTree(v).query_pairs(radius, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(v),) * 2)
    _, weld = connected_components(graph, directed=False)
    t = weld[t]
    t = t[(t[:, 0] != t[:, 1]) & (t[:, 1] != t[:, 2]) & (t[:, 2] != t[:, 0])]
    first = np.zeros(weld.max() + 1, dtype=np.intp)
    first[weld] = np.arange(len(v))
    v = v[first]
    # boundary segments: used by one triangle
    seg = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(seg, axis=0, return_counts=True)
    naked = uniq[count == 1]
    # the edges two faces share, as Open CASCADE curves, and dense points along them
    uses = {}
    for f in faces:
        for lp in [f["outer"], *f["inner"]]:
            for e in lp:
                uses.setdefault(edge_key(e), []).append(e["curve"])
    shared, owner, samples_ = [], [], []
    for curves in uses.values():
        if len(curves) < 2:
            continue
        c = to_occ(curves[0])
        lo, hi = c.FirstParameter(), c.LastParameter()
        for k in range(257):
            samples_.append(xyz(c.Value(lo + (hi - lo) * k / 256)))
            owner.append(len(shared))
        shared.append(GeomAdaptor_Curve(c))
    gap, cracks = 0.0, 0
    if len(naked) and shared:
        tree = cKDTree(np.asarray(samples_))
        owner = np.asarray(owner)

        def along(p):
            """The shared edges p lies on, within the tolerance."""
            near = tree.query_ball_point(p, 4 * tolerance)
            out = set()
            for e in {int(owner[i]) for i in near}:
                d = ShapeAnalysis_Curve().Project(shared[e], gp_Pnt(*p), 1e-15, gp_Pnt(), 0.0)
                if d <= tolerance:
                    out.add(e)
            return out

        on = {}
        crack = []
        for i, (a, b) in enumerate(naked):
            for q in (a, b):
                if q not in on:
                    on[q] = along(v[q])
            if on[a] & on[b]:
                crack.append(i)
        cracks = len(crack)
        if crack:
            # the gap at each vertex of such a segment: its distance to the nearest such segment
            # that does not end at it (the other face's side of the edge: a T-junction or a
            # crack)
            segs = naked[crack]
            mid = 0.5 * (v[segs[:, 0]] + v[segs[:, 1]])
            # a segment is within r of p only if its midpoint is within r + half its length:
            # the nearest midpoints give a bound, the ball of that bound plus the longest half
            # holds every segment that can be nearer (a long straight edge is one segment whose
            # midpoint is far from a vertex lying on it)
            reach = 0.5 * float(np.linalg.norm(v[segs[:, 1]] - v[segs[:, 0]], axis=1).max())
            ctree = cKDTree(mid)

            def nearest(q, js):
                width = math.inf
                for j in js:
                    if q not in segs[j]:
                        width = min(width, point_segment(v[q], v[segs[j, 0]], v[segs[j, 1]]))
                return width

            for q in np.unique(segs):
                _, js = ctree.query(v[q], k=min(16, len(mid)))
                width = nearest(q, np.atleast_1d(js))
                if math.isfinite(width):
                    width = nearest(q, ctree.query_ball_point(v[q], width + reach))
                    gap = max(gap, width)
    return summary["deviation"], summary.get("skipped", 0), gap, cracks, summary["triangles"]


# ---- one file


def check_file(path, args, occt_timer):
    row = {"file": path.name}
    with tempfile.TemporaryDirectory() as tmp:
        faces_path = os.path.join(tmp, "faces.jsonl")
        _, err_faces = lekalo("convert", "--faces", path, "-o", faces_path)
        geom_path = os.path.join(tmp, "geometry.jsonl")
        _, err_geom = lekalo("convert", path, "-o", geom_path)
        faces = [json.loads(line) for line in open(faces_path)]
        geometry = [json.loads(line) for line in open(geom_path)]
        row["dropped"] = skipped(err_faces)
        row["ours"] = lekalo_counts(faces, geometry)
        shape = occ.occ_shape(str(path))
        theirs = occ_faces(shape)
        topo = occ.topology(shape)
        row["theirs"] = [topo[0], topo[1], *occ_geometry_counts(theirs)]
        row["valid"] = topo[3]
        read = match(faces, theirs)
        if args.details:
            for k in sorted(range(len(read)), key=lambda k: (read[k][1], -max(read[k][0], read[k][2])))[:8]:
                f = faces[k]
                print(f"  #{f['id']} {f['surface']['type']} loops {[len(f['outer'])] + [len(x) for x in f['inner']]}: surface {read[k][0]:.2e}, loops equal {read[k][1]}, edges {read[k][2]:.2e}", file=sys.stderr)
        row["surface"] = max((r[0] for r in read), default=0.0)
        row["edges"] = max((r[2] for r in read), default=0.0)
        row["loops"] = sum(not r[1] for r in read)
        for ext in ("step", "igs"):
            if not faces:
                row[ext] = None
                continue
            back = os.path.join(tmp, "back." + ext)
            lekalo("convert", faces_path, "-o", back)
            again = occ.occ_shape(back)
            got = occ.topology(again)
            same = got[0] == topo[0] and got[1] == topo[1] and (ext == "igs" or got[2] == topo[2])
            cmp = match(faces, occ_faces(again))
            row[ext] = (same, got[3], max((max(r[0], r[2]) for r in cmp), default=0.0),
                        got[:3])
        row["mesh"] = mesh_check(faces_path, faces, args.tolerance, tmp) if faces else None
    row["time"] = times(path, args.repeats, occt_timer)
    return row


def times(path, repeats, occt):
    ours, theirs = [], []
    if repeats == 0:
        return math.nan, math.nan
    for _ in range(repeats):
        r = cad_read.run([str(cad_read.LEKALO), str(path), "1", "faces"])
        ours.append(r.get("cpu", math.nan))
        if occt:
            r = cad_read.run([str(cad_read.OCCT), str(path), "1"])
            theirs.append(r.get("cpu", math.nan))
    return statistics.median(ours), statistics.median(theirs) if theirs else math.nan


def fmt(x):
    return f"{x:.1e}" if x else "0"


def mark(bad):
    return "!" if bad else ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+", type=Path)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--tolerance", type=float, default=0.1, help="mesh tolerance, mm")
    ap.add_argument("--details", action="store_true", help="the worst faces of each file, on "
                    "standard error")
    ap.add_argument("--release", type=Path, help="a release directory already built (its "
                    "lekalo and examples/cad_read) instead of building this tree's")
    args = ap.parse_args()
    global LEKALO
    if args.release:
        LEKALO = args.release / "lekalo"
        cad_read.LEKALO = args.release / "examples" / "cad_read"
        occt = cad_read.build_occt()
    else:
        subprocess.run(["cargo", "build", "--quiet", "--release", "-p", "lekalo-cli"],
                       cwd=ROOT, check=True)
        occt = cad_read.build()
    print("| file | faces / loops / edges / surfaces / curves: lekalo | Open CASCADE | dropped "
          "| surfaces, edge curves: largest difference | loops differing "
          "| write-back STEP: counts, valid, difference | IGES | read CPU s: lekalo / OCCT "
          f"| mesh -t {args.tolerance:g}: deviation, faces left out, largest gap (boundary segments along shared edges), triangles |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in args.files:
        r = check_file(path, args, occt)
        ours, theirs = r["ours"], r["theirs"]
        counts_bad = ours[:3] != theirs[:3]
        wb = []
        for ext in ("step", "igs"):
            if r[ext] is None:
                wb.append("no faces" + mark(theirs[0]))
                continue
            same, valid, diff, got = r[ext]
            wb.append(f"{'/'.join(map(str, got))} {'valid' if valid else 'INVALID'} {fmt(diff)}"
                      f"{mark(not same or not valid or diff > LIMIT)}")
        t0, t1 = r["time"]
        dev, left, gap, cracks, tris = r["mesh"] or (0.0, 0, 0.0, 0, 0)
        print(f"| {r['file']} | {'/'.join(map(str, ours))}{mark(counts_bad)} "
              f"| {'/'.join(map(str, theirs))}{'' if r['valid'] else ' (invalid)'} "
              f"| {r['dropped']}{mark(r['dropped'])} "
              f"| {fmt(r['surface'])}{mark(r['surface'] > LIMIT)}, "
              f"{fmt(r['edges'])}{mark(r['edges'] > LIMIT)} "
              f"| {r['loops']}{mark(r['loops'])} | {wb[0]} | {wb[1]} "
              f"| {t0:.3f} / {t1:.3f} ({t1 / t0 if t0 > 0 else math.nan:.1f}x){mark(t0 > t1)} "
              f"| {dev:.3g}{mark(dev > args.tolerance)}, {left}{mark(left)}, "
              f"{fmt(gap)} ({cracks}){mark(gap > args.tolerance)}, {tris} |", flush=True)


if __name__ == "__main__":
    main()
