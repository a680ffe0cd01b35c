#!/usr/bin/env python3
"""Reading STEP and IGES files: lekalo against Open CASCADE, side by side in one run.

    python3 bench/peers/cad_read.py [--repeats 5] [--sizes 50,100,200] [FILE ...]

For each file, lekalo (the release example `cad_read` of lekalo-io: the file's text, its curves
and surfaces, and with `faces` its faces too, as `lekalo convert --faces` reads them) and Open
CASCADE in C++ (`bench/peers/occt_cad_read.cpp`: `STEPControl_Reader::ReadFile` and
`TransferRoots`, or `IGESControl_Reader` likewise, which build the file's curves, surfaces and
faces) are run alternately, one whole read a process, REPEATS times each; the table gives the
median wall time and CPU time (all threads) of a read, the process start not timed, and the
ratios Open CASCADE / lekalo with faces (above 1: lekalo is faster), and the peak resident
memory of each reader's process (VmHWM, which each program reads at its end; the largest of the
runs), to compare with the file's size; `result` is the memory that lekalo's
result with faces holds alone (the bytes its allocator counts as live once the text is
dropped), part of its peak that is not the reading's own. On a machine shared with other work the
CPU times are the steadier comparison.

Without FILE arguments the files are generated: STEP files of B-spline faces of about 50, 100
and 200 MB (--sizes, in MB), written into target/cad-read/ (never committed; built again only
when missing), to show the time growing linearly with the size. Each face is a bicubic B-spline
surface on an 8 x 8 net bounded by four B-spline edges with their pcurves, the structure Open
CASCADE itself writes. Files above 100 MB are read 3 times at most.

Open CASCADE is built from its C++ headers (Debian: apt-get install libocct-data-exchange-dev;
elsewhere set OCCT_INCLUDE and OCCT_LIB); without them only lekalo is timed, with a message.
The timings are of one run on whatever else the machine does: compare the ratios, which come
from reads a few seconds apart.
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import occt_build  # beside this script

ROOT = Path(__file__).resolve().parents[2]
TARGET = ROOT / "target"
OCCT = TARGET / "peers-occt" / "occt_cad_read"
LEKALO = TARGET / "release" / "examples" / "cad_read"

# the control net of a generated face, and its degree
NET = 8
DEGREE = 3
# faces in one open shell of a generated file
SHELL = 100


def build():
    """Builds lekalo's example and, when the headers are there, Open CASCADE's reader; returns
    whether Open CASCADE is timed."""
    subprocess.run(["cargo", "build", "--quiet", "--release", "-p", "lekalo-io",
                    "--example", "cad_read"], cwd=ROOT, check=True)
    return build_occt()


def build_occt():
    """Builds Open CASCADE's reader when the headers are there; returns whether it is timed."""
    return occt_build.build("occt_cad_read.cpp", "STEPControl_Reader.hxx",
                            ["-lTKSTEP", "-lTKIGES", "-lTKXSBase", "-lTKBRep", "-lTKTopAlgo",
                             "-lTKG3d", "-lTKMath", "-lTKernel"]) == OCCT


def real(x):
    """A real as Part 21 writes it: 12 significant digits, always with a decimal point."""
    s = f"{x:.12G}"
    mantissa, _, exp = s.partition("E")
    if "." not in mantissa:
        mantissa += "."
    return mantissa + ("E" + str(int(exp)) if exp else "")


def generate(path, megabytes):
    """A STEP file (AP214, millimetres) of about `megabytes` MB of B-spline faces on a grid of
    wavy patches, written with deterministic values."""
    header = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('lekalo reading benchmark'),'2;1');
FILE_NAME('bsplines','2000-01-01T00:00:00',('bench'),('lekalo'),'cad_read.py','cad_read.py','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
#1 = APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#2);
#2 = APPLICATION_CONTEXT('core data for automotive mechanical design processes');
#3 = SHAPE_DEFINITION_REPRESENTATION(#4,#10);
#4 = PRODUCT_DEFINITION_SHAPE('','',#5);
#5 = PRODUCT_DEFINITION('design','',#6,#9);
#6 = PRODUCT_DEFINITION_FORMATION('','',#7);
#7 = PRODUCT('bsplines','bsplines','',(#8));
#8 = MECHANICAL_CONTEXT('',#2,'mechanical');
#9 = PRODUCT_DEFINITION_CONTEXT('part definition',#2,'design');
#10 = MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#11,#15),#20);
#11 = AXIS2_PLACEMENT_3D('',#12,#13,#14);
#12 = CARTESIAN_POINT('',(0.,0.,0.));
#13 = DIRECTION('',(0.,0.,1.));
#14 = DIRECTION('',(1.,0.,0.));
#20 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#24))
GLOBAL_UNIT_ASSIGNED_CONTEXT((#21,#22,#23)) REPRESENTATION_CONTEXT('Context #1','3D Context') );
#21 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );
#22 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );
#23 = ( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() );
#24 = UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#21,'distance_accuracy_value','');
"""
    # bytes of one face, measured on the first: the number of faces follows
    out = []
    faces = []
    nid = [100]

    def new(text):
        i = nid[0]
        nid[0] += 1
        out.append(f"#{i} = {text};\n")
        return i

    def patch(k):
        gx, gy = k % 1000, k // 1000
        pts = [[new("CARTESIAN_POINT('',(%s,%s,%s))" % (
            real(gx * 10.0 + 10.0 * i / (NET - 1)), real(gy * 10.0 + 10.0 * j / (NET - 1)),
            real(math.sin(0.37 * (gx * (NET - 1) + i)) * math.cos(0.23 * (gy * (NET - 1) + j)))))
            for j in range(NET)] for i in range(NET)]
        inner = NET - DEGREE - 1
        mults = "(%d,%s%d)" % (DEGREE + 1, "1," * inner, DEGREE + 1)
        knots = "(" + ",".join(real(t / (inner + 1)) for t in range(inner + 2)) + ")"
        net = ",".join("(" + ",".join(f"#{p}" for p in row) + ")" for row in pts)
        surf = new(f"B_SPLINE_SURFACE_WITH_KNOTS('',{DEGREE},{DEGREE},({net}),.UNSPECIFIED.,"
                   f".F.,.F.,.F.,{mults},{mults},{knots},{knots},.UNSPECIFIED.)")
        corner = {c: new(f"VERTEX_POINT('',#{pts[c[0]][c[1]]})")
                  for c in [(0, 0), (NET - 1, 0), (NET - 1, NET - 1), (0, NET - 1)]}
        # the four sides: the net's boundary rows, and their lines in the (u, v) square
        sides = [((0, 0), (NET - 1, 0), [pts[i][0] for i in range(NET)], (0.0, 0.0), (1.0, 0.0)),
                 ((NET - 1, 0), (NET - 1, NET - 1), pts[NET - 1], (1.0, 0.0), (0.0, 1.0)),
                 ((0, NET - 1), (NET - 1, NET - 1), [pts[i][NET - 1] for i in range(NET)],
                  (0.0, 1.0), (1.0, 0.0)),
                 ((0, 0), (0, NET - 1), pts[0], (0.0, 0.0), (0.0, 1.0))]
        oes = []
        for (a, b, row, origin, d), sense in zip(sides, [".T.", ".T.", ".F.", ".F."]):
            curve = new(f"B_SPLINE_CURVE_WITH_KNOTS('',{DEGREE},(" + ",".join(
                f"#{p}" for p in row) + f"),.UNSPECIFIED.,.F.,.F.,{mults},{knots},.UNSPECIFIED.)")
            o = new("CARTESIAN_POINT('',(%s,%s))" % (real(origin[0]), real(origin[1])))
            dr = new("DIRECTION('',(%s,%s))" % (real(d[0]), real(d[1])))
            v = new(f"VECTOR('',#{dr},1.)")
            line = new(f"LINE('',#{o},#{v})")
            ctx = new("( GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() "
                      "REPRESENTATION_CONTEXT('2D SPACE','') )")
            rep = new(f"DEFINITIONAL_REPRESENTATION('',(#{line}),#{ctx})")
            pc = new(f"PCURVE('',#{surf},#{rep})")
            sc = new(f"SURFACE_CURVE('',#{curve},(#{pc}),.PCURVE_S1.)")
            edge = new(f"EDGE_CURVE('',#{corner[a]},#{corner[b]},#{sc},.T.)")
            oes.append(new(f"ORIENTED_EDGE('',*,*,#{edge},{sense})"))
        loop = new("EDGE_LOOP('',(" + ",".join(f"#{e}" for e in oes) + "))")
        bound = new(f"FACE_OUTER_BOUND('',#{loop},.T.)")
        faces.append(new(f"ADVANCED_FACE('',(#{bound}),#{surf},.T.)"))

    patch(0)
    per_face = sum(len(s) for s in out)
    count = max(1, int(megabytes * 1e6 / per_face))
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".part")
    with open(tmp, "w") as f:
        f.write(header)
        for k in range(1, count):
            patch(k)
            if len(out) > 100_000:
                f.writelines(out)
                out.clear()
        # open shells of SHELL faces (a part's worth each), in one surface model
        shells = []
        for k in range(0, len(faces), SHELL):
            shells.append(new("OPEN_SHELL('',(" + ",".join(
                f"#{i}" for i in faces[k:k + SHELL]) + "))"))
        f.writelines(out)
        f.write("#15 = SHELL_BASED_SURFACE_MODEL('',(" + ",".join(f"#{i}" for i in shells)
                + "));\n")
        f.write("ENDSEC;\nEND-ISO-10303-21;\n")
    tmp.rename(path)


def run(cmd):
    """The fields of the one line a timing binary prints: {'seconds': .., 'shapes': ..,
    'peak_mb': .., ..}; 'peak_mb' is the peak resident memory of the process that the binary
    reads from Linux's /proc/self/status (VmHWM) at its end, or else the maximum resident set
    size the kernel reports to this parent (which counts this Python process's own memory at
    the fork, some 16 MB, as the child's), in MB."""
    with tempfile.TemporaryFile(mode="w+") as errors:
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=errors, text=True)
        out = p.stdout.read()
        p.stdout.close()
        # reaped here, with the child's own resource usage (not Popen.wait, which drops it)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        errors.seek(0)
        err = errors.read()
    if p.returncode != 0:
        return {"error": (err or out).strip().splitlines()[-1:]}
    words = out.split()
    r = {words[i]: float(words[i + 1]) for i in range(0, len(words) - 1, 2)}
    if not r.get("peak_mb"):
        # ru_maxrss is in KiB on Linux
        r["peak_mb"] = usage.ru_maxrss * 1024 / 1e6
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*", type=Path)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--sizes", default="50,100,200", help="generated files, MB")
    args = ap.parse_args()
    occt = build()
    files = args.files
    if not files:
        for mb in [int(s) for s in args.sizes.split(",") if s]:
            p = TARGET / "cad-read" / f"bsplines_{mb}mb.step"
            if not p.exists():
                print(f"cad_read: writing {p}", file=sys.stderr)
                generate(p, mb)
            files.append(p)
    print(f"{'file':<30} {'MB':>6} | wall s: {'lekalo':>7} {'+faces':>7} {'OCCT':>7} {'ratio':>6}"
          f" | CPU s: {'+faces':>7} {'OCCT':>7} {'ratio':>6}"
          f" | peak MB: {'lekalo':>7} {'+faces':>7} {'OCCT':>7} {'result':>7} | faces lekalo/OCCT")
    for path in files:
        mb = path.stat().st_size / 1e6
        repeats = min(args.repeats, 3) if mb > 100 else args.repeats
        got = {"ours": [], "faces": [], "occt": []}
        last = {}
        for _ in range(max(1, repeats)):
            runs = [("ours", [str(LEKALO), str(path), "1"]),
                    ("faces", [str(LEKALO), str(path), "1", "faces"])]
            if occt:
                runs.append(("occt", [str(OCCT), str(path), "1"]))
            for key, cmd in runs:
                r = run(cmd)
                last[key] = r
                if "seconds" in r:
                    got[key].append((r["seconds"], r["cpu"], r["peak_mb"],
                                     r.get("result_mb", math.nan)))

        def med(key, k):
            return statistics.median(t[k] for t in got[key]) if got[key] else math.nan

        def peak(key):
            # the largest of the runs: the memory a read needs
            return max(t[2] for t in got[key]) if got[key] else math.nan

        def ratio(a, b):
            # a read below the clock's resolution has no ratio
            return a / b if b > 0 else math.nan

        faces = "/".join(str(int(last.get(k, {}).get("faces", -1))) if "faces" in last.get(k, {})
                         else str(last.get(k, {}).get("error", "-")) for k in ["faces", "occt"])
        print(f"{path.name:<30} {mb:6.1f} | wall s: {med('ours', 0):7.3f} {med('faces', 0):7.3f} "
              f"{med('occt', 0):7.3f} {ratio(med('occt', 0), med('faces', 0)):5.1f}x"
              f" | CPU s: {med('faces', 1):7.3f} {med('occt', 1):7.3f} "
              f"{ratio(med('occt', 1), med('faces', 1)):5.1f}x"
              f" | peak MB: {peak('ours'):7.0f} {peak('faces'):7.0f} {peak('occt'):7.0f}"
              f" {med('faces', 3):7.0f}"
              f" | {faces}", flush=True)


if __name__ == "__main__":
    main()
