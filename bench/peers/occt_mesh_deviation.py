"""The true deviation of Open CASCADE's mesh of the benchmark surface, measured: the bicubic
50x50-patch surface of crates/lekalo/benches/query_workloads/mod.rs (control points
(i/52, j/52, 0.3 sin 0.4i cos 0.3j + 0.1 sin(0.9i + 0.5j)), clamped uniform knots on [0, 1]),
meshed by BRepMesh_IncrementalMesh at deflection 1e-4 (absolute, not relative, as in
occt_queries.cpp; lekalo's tolerance is absolute too, and the surface spans the unit square).

Open CASCADE checks the deflection at sampled points only; lekalo's mesh has a deviation bound
proved from each part's control net. This reads the triangulation (nodes, UV nodes, triangles)
and measures, at ten barycentric points of EVERY triangle (the centroid, the three edge
midpoints, the three points (2/3, 1/6, 1/6) and the three points (1/6, 5/12, 5/12)):

  (a) parametric deviation |S(sum l_i uv_i) - sum l_i P_i|, the quantity lekalo bounds: the
      triangle's point against the surface point at the interpolated parameters;
  (b) distance from the triangle's point sum l_i P_i to the surface: closest point by Newton's
      method from the interpolated parameters (vectorised), checked against Open CASCADE's
      GeomAPI_ProjectPointOnSurf on the worst points and a random sample. (b) <= (a) always.

Then the triangles with the largest sampled deviations are searched on a finer barycentric grid
(step 1/24), since the maximum over a triangle is not in general at a sampled point; the
fractions of triangles above the tolerance count the ten sampled points only (lower bounds).
The surface is evaluated here in NumPy, from its power-basis patches; the script checks that
against Open CASCADE's evaluation at random points and at the mesh's nodes.

With --lekalo PATH (the release CLI, target/release/lekalo), lekalo's triangle count is also
measured at the tolerances that Open CASCADE's mesh actually reaches ((a) and (b) maxima, a
little rounded up), for the comparison at the same bound. Where the lekalo Python package is
importable, its mesh at the deflection is measured the same way on 2*10^5 of its triangles, as
a check of the measurement ((a) within its proved bound) and for its (b).

    python bench/peers/occt_mesh_deviation.py [--brep FILE] [--lekalo target/release/lekalo]
    python bench/peers/occt_mesh_deviation.py --lekalo-mesh target/answers/lekalo_mesh.txt

With --lekalo-mesh FILE (written by `cargo run --release --example query_peer -- 1 1000 DIR`
as DIR/lekalo_mesh.txt) only lekalo's mesh of the surface is measured, at the ten points of
every one of its triangles and on the fine grid of its worst ones, without Open CASCADE's.

Without --brep the face is meshed here with OCP (cadquery-ocp; 1-3 minutes); with it, the
meshed face is read from FILE, e.g. target/peers-occt/answers/occt_mesh.brep, which
occt_queries.cpp writes with an ANSWERS_DIR (Open CASCADE in C++, as in the benchmark table).
Needs numpy and OCP; bench/peers/run.sh runs it in bench/peers/.venv.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_BSplineSurface
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Pnt
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Shape

try:  # OCP 7.x names
    from OCP.TColgp import TColgp_Array2OfPnt as Array2_Pnt
    from OCP.TColStd import TColStd_Array1OfInteger as Array1_Int
    from OCP.TColStd import TColStd_Array1OfReal as Array1_Real
except ImportError:  # cadquery-ocp 8
    from OCP.OCP.collections import Array1_double as Array1_Real
    from OCP.OCP.collections import Array1_int as Array1_Int
    from OCP.OCP.collections import Array2_gp_Pnt as Array2_Pnt

N = 53  # control points per direction
PIECES = N - 3
DEGREE = 3
TOL = 1e-4

# barycentric sample points of every triangle: centroid, edge midpoints, two rings of three
SAMPLES = np.array(
    [[1 / 3, 1 / 3, 1 / 3]]
    + [[0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5]]
    + [[2 / 3, 1 / 6, 1 / 6], [1 / 6, 2 / 3, 1 / 6], [1 / 6, 1 / 6, 2 / 3]]
    + [[1 / 6, 5 / 12, 5 / 12], [5 / 12, 1 / 6, 5 / 12], [5 / 12, 5 / 12, 1 / 6]]
)
FINE = 24  # barycentric grid step 1/FINE on the worst triangles
WORST = 2000  # triangles searched on the fine grid
LEKALO_SAMPLE = 200_000  # triangles of lekalo's mesh measured alike


def control_net():
    i, j = np.meshgrid(np.arange(N, dtype=float), np.arange(N, dtype=float), indexing="ij")
    z = 0.3 * np.sin(0.4 * i) * np.cos(0.3 * j) + 0.1 * np.sin(0.9 * i + 0.5 * j)
    return np.stack([i / (N - 1), j / (N - 1), z], axis=-1)


def knot_vector():
    return np.array([0.0] * 3 + [k / PIECES for k in range(PIECES + 1)] + [1.0] * 3)


def basis(knots, span, u):
    """The DEGREE + 1 B-spline basis functions nonzero on knot span `span` at `u` (Cox-de Boor)."""
    n = np.zeros(DEGREE + 1)
    n[0] = 1.0
    left, right = np.zeros(DEGREE + 1), np.zeros(DEGREE + 1)
    for j in range(1, DEGREE + 1):
        left[j] = u - knots[span + 1 - j]
        right[j] = knots[span + j] - u
        saved = 0.0
        for r in range(j):
            t = n[r] / (right[r + 1] + left[j - r])
            n[r] = saved + right[r + 1] * t
            saved = left[j - r] * t
        n[j] = saved
    return n


def power_patches(net, knots):
    """Coefficients C[su, sv, a, b, :] of S = sum C t^a w^b on piece (su, sv), t, w in [0, 1]."""
    ts = np.linspace(0.0, 1.0, DEGREE + 1)
    vander = np.vander(ts, DEGREE + 1, increasing=True)
    m = np.empty((PIECES, DEGREE + 1, DEGREE + 1))  # [piece, power, function]
    for s in range(PIECES):
        span = s + DEGREE
        a, b = knots[span], knots[span + 1]
        vals = np.array([basis(knots, span, a + t * (b - a)) for t in ts])
        m[s] = np.linalg.solve(vander, vals)
    c = np.empty((PIECES, PIECES, DEGREE + 1, DEGREE + 1, 3))
    for su in range(PIECES):
        for sv in range(PIECES):
            block = net[su : su + DEGREE + 1, sv : sv + DEGREE + 1]
            c[su, sv] = np.einsum("ai,ijd,bj->abd", m[su], block, m[sv])
    return c


class Surface:
    """The benchmark surface in NumPy: points and first and second derivatives at arrays of
    (u, v), piece by piece in the power basis."""

    def __init__(self):
        self.net = control_net()
        self.knots = knot_vector()
        self.c = power_patches(self.net, self.knots)

    def eval(self, uv, derivs=False):
        u = np.clip(uv[:, 0], 0.0, 1.0) * PIECES
        v = np.clip(uv[:, 1], 0.0, 1.0) * PIECES
        su = np.minimum(np.floor(u), PIECES - 1).astype(np.intp)
        sv = np.minimum(np.floor(v), PIECES - 1).astype(np.intp)
        t, w = u - su, v - sv
        c = self.c[su, sv]  # (n, 4, 4, 3)
        k = np.arange(DEGREE + 1)
        tp = t[:, None] ** k
        wp = w[:, None] ** k
        s = np.einsum("na,nabd,nb->nd", tp, c, wp)
        if not derivs:
            return s
        # derivatives of the powers, scaled from the piece's [0, 1] to the surface's parameters
        km1 = np.maximum(k - 1, 0)
        km2 = np.maximum(k - 2, 0)
        tp1 = k * t[:, None] ** km1 * PIECES
        wp1 = k * w[:, None] ** km1 * PIECES
        tp2 = k * (k - 1) * t[:, None] ** km2 * PIECES**2
        wp2 = k * (k - 1) * w[:, None] ** km2 * PIECES**2
        su_ = np.einsum("na,nabd,nb->nd", tp1, c, wp)
        sv_ = np.einsum("na,nabd,nb->nd", tp, c, wp1)
        suu = np.einsum("na,nabd,nb->nd", tp2, c, wp)
        suv = np.einsum("na,nabd,nb->nd", tp1, c, wp1)
        svv = np.einsum("na,nabd,nb->nd", tp, c, wp2)
        return s, su_, sv_, suu, suv, svv

    def project(self, x, uv, iterations=30):
        """Closest points to x by Newton's method on |S(u, v) - x|^2 from uv, in the domain,
        each step halved while it does not bring the point closer, Gauss-Newton where the
        Hessian is not positive, until the steps are below 1e-13 or after `iterations`:
        (uv, distance, number of points not converged). The distance is that of a surface
        point, so never below the true distance; a local minimum would be above it."""
        uv = uv.copy()
        d = np.linalg.norm(self.eval(uv) - x, axis=1)
        active = np.arange(len(x))
        for _ in range(iterations):
            if len(active) == 0:
                break
            new, d_new = self._newton_step(x[active], uv[active], d[active])
            moved = np.abs(new - uv[active]).max(axis=1)
            uv[active], d[active] = new, d_new
            active = active[moved > 1e-13]
        return uv, d, len(active)

    def _newton_step(self, x, uv, d):
        s, su, sv, suu, suv, svv = self.eval(uv, derivs=True)
        r = s - x
        dot = lambda a, b: np.einsum("nd,nd->n", a, b)
        g0, g1 = dot(su, r), dot(sv, r)
        j11, j12, j22 = dot(su, su), dot(su, sv), dot(sv, sv)
        h11, h12, h22 = j11 + dot(suu, r), j12 + dot(suv, r), j22 + dot(svv, r)
        det = h11 * h22 - h12 * h12
        gn = (det <= 0) | (h11 <= 0)
        h11, h12, h22 = np.where(gn, j11, h11), np.where(gn, j12, h12), np.where(gn, j22, h22)
        det = h11 * h22 - h12 * h12
        step = np.stack([(h22 * g0 - h12 * g1) / det, (h11 * g1 - h12 * g0) / det], axis=1)
        # a step out of the domain in one parameter: that parameter to the side, the other by
        # Newton's method along it (the closest point of the surface, not of its extension)
        out_u = (uv[:, 0] - step[:, 0] < 0.0) | (uv[:, 0] - step[:, 0] > 1.0)
        out_v = (uv[:, 1] - step[:, 1] < 0.0) | (uv[:, 1] - step[:, 1] > 1.0)
        only_v, only_u = out_u & ~out_v, out_v & ~out_u
        step[only_v, 1] = g1[only_v] / h22[only_v]
        step[only_u, 0] = g0[only_u] / h11[only_u]
        new = np.clip(uv - step, 0.0, 1.0)
        d_new = np.linalg.norm(self.eval(new) - x, axis=1)
        for _ in range(30):
            worse = d_new > d
            if not worse.any():
                break
            step[worse] *= 0.5
            new[worse] = np.clip(uv[worse] - step[worse], 0.0, 1.0)
            d_new[worse] = np.linalg.norm(self.eval(new[worse]) - x[worse], axis=1)
        keep = d_new > d  # no step improved: stay
        new[keep], d_new[keep] = uv[keep], d[keep]
        return new, d_new


def occ_surface():
    net = Array2_Pnt(1, N, 1, N)
    for i in range(N):
        for j in range(N):
            z = 0.3 * math.sin(0.4 * i) * math.cos(0.3 * j) + 0.1 * math.sin(0.9 * i + 0.5 * j)
            net.SetValue(i + 1, j + 1, gp_Pnt(i / (N - 1), j / (N - 1), z))
    knots = Array1_Real(1, PIECES + 1)
    mults = Array1_Int(1, PIECES + 1)
    for i in range(PIECES + 1):
        knots.SetValue(i + 1, i / PIECES)
        mults.SetValue(i + 1, 4 if i in (0, PIECES) else 1)
    return Geom_BSplineSurface(net, knots, knots, mults, mults, DEGREE, DEGREE)


def occ_mesh(brep, deflection):
    """The meshed face: read from `brep`, or meshed here (OCP) at `deflection`."""
    if brep:
        shape = TopoDS_Shape()
        if not BRepTools.Read_s(shape, brep, BRep_Builder()):
            sys.exit(f"cannot read {brep}")
        exp = TopExp_Explorer(shape, TopAbs_FACE)
        to_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face  # OCP 7.x / 8
        face = to_face(exp.Current())
        return face, f"read from {brep}"
    face = BRepBuilderAPI_MakeFace(occ_surface(), 1e-7).Face()
    t0 = time.perf_counter()
    BRepMesh_IncrementalMesh(face, deflection, False, 0.5, False)
    return face, f"meshed here with OCP in {time.perf_counter() - t0:.1f} s"


def triangulation(face):
    loc = TopLoc_Location()
    tri = BRep_Tool.Triangulation_s(face, loc)
    if tri is None or not tri.HasUVNodes():
        sys.exit("the face has no triangulation with UV nodes")
    if not loc.IsIdentity():
        sys.exit("the face's triangulation has a location; not expected here")
    nn, nt = tri.NbNodes(), tri.NbTriangles()
    xyz = np.empty((nn, 3))
    uv = np.empty((nn, 2))
    for i in range(nn):
        p = tri.Node(i + 1)
        q = tri.UVNode(i + 1)
        xyz[i] = (p.X(), p.Y(), p.Z())
        uv[i] = (q.X(), q.Y())
    tris = np.empty((nt, 3), dtype=np.intp)
    for k in range(nt):
        tris[k] = tri.Triangle(k + 1).Get()
    return xyz, uv, tris - 1


def deviations(surf, xyz, uv, tris, bary, recheck, chunk=40_000):
    """(a) and (b) at barycentric points `bary` (m, 3) of every triangle: arrays (n, m), and
    the number of projections not converged. (b) starts from the interpolated parameters; where
    it is above `recheck` or among the largest 1% of a chunk, also from the triangle's three
    corners, keeping the nearest (Newton's method can stop at a local minimum, which only
    overestimates (b))."""
    n, m = len(tris), len(bary)
    par = np.empty((n, m))
    dist = np.empty((n, m))
    unconverged = 0
    for lo in range(0, n, chunk):
        t = tris[lo : lo + chunk]
        p = np.einsum("sk,nkd->nsd", bary, xyz[t]).reshape(-1, 3)
        q = np.einsum("sk,nkd->nsd", bary, uv[t]).reshape(-1, 2)
        par[lo : lo + len(t)] = np.linalg.norm(surf.eval(q) - p, axis=1).reshape(-1, m)
        _, d, left = surf.project(p, q)
        unconverged += left
        far = np.flatnonzero(d > min(recheck, np.quantile(d, 0.99)))
        for corner in range(3):
            starts = uv[np.repeat(t[:, corner], m)[far]]
            _, d2, left = surf.project(p[far], starts)
            d[far] = np.minimum(d[far], d2)
            unconverged += left
        dist[lo : lo + len(t)] = d.reshape(-1, m)
    return par, dist, unconverged


def fine_grid(k):
    pts = [(i / k, j / k, (k - i - j) / k) for i in range(k + 1) for j in range(k + 1 - i)]
    return np.array([p for p in pts if max(p) < 1.0])  # without the vertices


def measure_lekalo_mesh(path, deflection):
    """(a) and (b) at the ten points of every triangle of lekalo's mesh read from `path`
    (query_peer's lekalo_mesh.txt), then on the fine grid of the worst ones: (a) must stay
    within the proved deviation the file states."""
    with open(path) as f:
        nv, nt, bound = f.readline().split()
        nv, nt, bound = int(nv), int(nt), float(bound)
        verts = np.loadtxt(f, max_rows=nv)
        tris = np.loadtxt(f, dtype=np.intp, max_rows=nt)
    xyz, uv = verts[:, :3], np.ascontiguousarray(verts[:, 3:])
    surf = Surface()
    node_err = np.linalg.norm(surf.eval(uv) - xyz, axis=1).max()
    print(f"lekalo mesh ({path}): {nt} triangles, {nv} vertices, proved deviation {bound:.4e}; "
          f"vertices vs S(uv): {node_err:.1e}")
    t0 = time.perf_counter()
    par, dist, left = deviations(surf, xyz, uv, tris, SAMPLES, 0.5 * deflection)
    print(f"{len(SAMPLES)} barycentric points of each triangle ({time.perf_counter() - t0:.0f} s; "
          f"projections not converged: {left}):")
    for name, per in (("(a) parametric |S(uv) - L|", par.max(axis=1)),
                      ("(b) distance to the surface", dist.max(axis=1))):
        q = np.quantile(per, [0.5, 0.99])
        print(f"  {name}: max {per.max():.4e}; median {q[0]:.3e}, 99% {q[1]:.3e}; triangles "
              f"above {deflection:g}: {np.count_nonzero(per > deflection)}")
    worst = np.unique(np.concatenate([np.argsort(par.max(axis=1))[-WORST:],
                                      np.argsort(dist.max(axis=1))[-WORST:]]))
    fpar, fdist, _ = deviations(surf, xyz, uv, tris[worst], fine_grid(FINE), 0.5 * deflection,
                                chunk=1000)
    max_par = max(fpar.max(), par.max())
    print(f"the {len(worst)} worst triangles on a barycentric grid of step 1/{FINE}: (a) max "
          f"{max_par:.4e} ({max_par / bound:.4f} of the proved {bound:.4e}), (b) max "
          f"{max(fdist.max(), dist.max()):.4e}")
    if max_par > bound * (1 + 1e-9):
        sys.exit("lekalo's mesh is above its proved deviation")


def lekalo_counts(cli, tolerances):
    """Triangle count and proved deviation of lekalo's mesh (`cli mesh --json`) per tolerance."""
    net = control_net()
    doc = {
        "lekalo": 1,
        "type": "bspline_surface",
        "degree_u": DEGREE,
        "degree_v": DEGREE,
        "knots_u": knot_vector().tolist(),
        "knots_v": knot_vector().tolist(),
        "net": [N, N],
        "control": net.reshape(-1, 3).tolist(),
    }
    out = []
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "surface.json")
        with open(path, "w") as f:
            json.dump(doc, f)
        for tol in tolerances:
            r = subprocess.run(
                [cli, "mesh", path, "--tolerance", repr(tol), "--json"],
                check=True,
                capture_output=True,
                text=True,
            )
            out.append((tol, json.loads(r.stdout)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--brep", help="meshed face written by occt_queries.cpp (occt_mesh.brep)")
    ap.add_argument("--deflection", type=float, default=TOL)
    ap.add_argument("--lekalo", help="lekalo CLI, for its counts at the measured deviations")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--lekalo-mesh", help="lekalo's mesh written by the example query_peer "
                    "(lekalo_mesh.txt): measure it alone")
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    if args.lekalo_mesh:
        measure_lekalo_mesh(args.lekalo_mesh, args.deflection)
        return

    surf = Surface()
    geom = occ_surface()
    # the NumPy evaluation against Open CASCADE's at random parameters
    uvr = rng.random((2000, 2))
    ours = surf.eval(uvr)
    theirs = np.array([(lambda p: (p.X(), p.Y(), p.Z()))(geom.Value(u, v)) for u, v in uvr])
    eval_err = np.abs(ours - theirs).max()

    face, how = occ_mesh(args.brep, args.deflection)
    xyz, uv, tris = triangulation(face)
    node_err = np.linalg.norm(surf.eval(uv) - xyz, axis=1).max()
    lo, hi = xyz.min(axis=0), xyz.max(axis=0)
    print(f"Open CASCADE mesh ({how}): {len(tris)} triangles, {len(xyz)} nodes, deflection "
          f"{args.deflection:g} (absolute); bounding box {np.round(lo, 4)} .. {np.round(hi, 4)}, "
          f"diagonal {np.linalg.norm(hi - lo):.4f}")
    print(f"checks: NumPy surface vs Open CASCADE at 2000 random (u, v): {eval_err:.1e}; "
          f"nodes vs S(UV node): {node_err:.1e}")

    t0 = time.perf_counter()
    par, dist, left = deviations(surf, xyz, uv, tris, SAMPLES, 0.5 * args.deflection)
    tmax_par, tmax_dist = par.max(axis=1), dist.max(axis=1)
    n = len(tris)
    print(f"\n{len(SAMPLES)} barycentric points of each of the {n} triangles "
          f"({time.perf_counter() - t0:.0f} s; projections not converged: {left}):")
    for name, per in (("(a) parametric |S(uv) - L|", tmax_par),
                      ("(b) distance to the surface", tmax_dist)):
        q = np.quantile(per, [0.5, 0.9, 0.99, 0.999])
        above = np.count_nonzero(per > args.deflection)
        print(f"  {name}: max {per.max():.4e}; median {q[0]:.3e}, 90% {q[1]:.3e}, "
              f"99% {q[2]:.3e}, 99.9% {q[3]:.3e}; triangles above {args.deflection:g}: "
              f"{above} ({100 * above / n:.2f}%), above 2x: "
              f"{np.count_nonzero(per > 2 * args.deflection)}")

    # the worst triangles on a finer grid, by each measure
    grid = fine_grid(FINE)
    worst = np.unique(np.concatenate([np.argsort(tmax_par)[-WORST:],
                                      np.argsort(tmax_dist)[-WORST:]]))
    fpar, fdist, fleft = deviations(surf, xyz, uv, tris[worst], grid, 0.5 * args.deflection,
                                   chunk=1000)
    max_par = max(fpar.max(), tmax_par.max())
    max_dist = max(fdist.max(), tmax_dist.max())
    k = worst[np.argmax(fpar.max(axis=1))]
    corners = uv[tris[k]]
    print(f"\nthe {len(worst)} worst triangles on a barycentric grid of step 1/{FINE} "
          f"({len(grid)} points each; projections not converged: {fleft}): (a) max "
          f"{max_par:.4e}, (b) max {max_dist:.4e}; "
          f"worst (a) in triangle {k}, UV corners {np.round(corners, 5).tolist()}")

    # (b) checked against Open CASCADE's projection: the worst points and random ones
    pick = [np.unravel_index(i, dist.shape) for i in np.argsort(dist, axis=None)[-200:]]
    pick += [(int(i), int(j)) for i, j in zip(rng.integers(0, n, 300),
                                             rng.integers(0, len(SAMPLES), 300))]
    ours_farther, theirs_farther = 0.0, 0.0
    for i, j in pick:
        p = SAMPLES[j] @ xyz[tris[i]]
        proj = GeomAPI_ProjectPointOnSurf(gp_Pnt(*p), geom)
        if proj.NbPoints() == 0:
            continue
        d = dist[i, j] - proj.LowerDistance()
        ours_farther, theirs_farther = max(ours_farther, d), max(theirs_farther, -d)
    print(f"(b) against GeomAPI_ProjectPointOnSurf at {len(pick)} points (the 200 farthest, 300 at "
          f"random): ours farther by at most {ours_farther:.1e}, Open CASCADE's by at most "
          f"{theirs_farther:.1e}")

    try:
        import lekalo
    except ImportError:
        lekalo = None
    if lekalo is not None:
        # the same measurement of lekalo's mesh, on a sample of its triangles: (a) must stay
        # within its proved deviation
        q = lekalo.SurfaceQuery(lekalo.BSplineSurface(DEGREE, DEGREE, knot_vector(),
                                                      knot_vector(), control_net()))
        lv, luv, lt, bound = q.mesh(args.deflection)
        lt = lt.astype(np.intp)
        sample = lt[rng.choice(len(lt), min(len(lt), LEKALO_SAMPLE), replace=False)]
        lpar, ldist, _ = deviations(surf, lv, luv, sample, SAMPLES, 0.5 * args.deflection)
        print(f"\nlekalo's mesh at {args.deflection:g} (Python package): {len(lt)} triangles, "
              f"proved deviation {bound:.4e}; at the same ten points of {len(sample)} of its "
              f"triangles: (a) max {lpar.max():.4e}, (b) max {ldist.max():.4e}, (b) median "
              f"{np.median(ldist.max(axis=1)):.3e}")

    if args.lekalo:
        # tolerances a little above the measured maxima, so that lekalo's proved bound covers them
        tols = [args.deflection,
                float(f"{math.ceil(max_par * 1e6) / 1e6:.6g}"),
                float(f"{math.ceil(max_dist * 1e6) / 1e6:.6g}")]
        print()
        for tol, r in lekalo_counts(args.lekalo, sorted(set(tols))):
            print(f"lekalo mesh --tolerance {tol:g}: {r['triangles']} triangles, "
                  f"{r['vertices']} vertices, proved deviation {r['deviation']:.4e} "
                  f"({r['triangles'] / n:.2f}x Open CASCADE's count)")


if __name__ == "__main__":
    main()
