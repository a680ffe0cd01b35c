"""Builds a C++ peer of bench/peers against Open CASCADE with g++, for the benchmark scripts
(cad_read.py, fit_peers.py, bench/python/tolerance_bench.py): the headers from
/usr/include/opencascade or $OCCT_INCLUDE (Debian's libocct-*-dev packages), the libraries from
the system or $OCCT_LIB. The binary goes to target/peers-occt/ and is rebuilt when its source is
newer."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def build(source: str, header: str, libs: list[str]) -> Path | None:
    """The binary of bench/peers/`source` (built if needed), or None, with a note on standard
    error, when `header` or g++ is missing or the build fails."""
    include = os.environ.get("OCCT_INCLUDE", "/usr/include/opencascade")
    if not (Path(include) / header).exists() or not shutil.which("g++"):
        print(f"{source}: no Open CASCADE headers in {include} (Debian: apt-get install "
              "libocct-modeling-algorithms-dev libocct-data-exchange-dev); not timed",
              file=sys.stderr)
        return None
    src = ROOT / "bench" / "peers" / source
    out = ROOT / "target" / "peers-occt" / Path(source).stem
    if out.exists() and out.stat().st_mtime > src.stat().st_mtime:
        return out
    out.parent.mkdir(parents=True, exist_ok=True)
    lib = os.environ.get("OCCT_LIB")
    libdirs = [f"-L{lib}", f"-Wl,-rpath,{lib}"] if lib else []
    cmd = ["g++", "-O2", "-std=c++17", "-Wno-deprecated-declarations", f"-I{include}", str(src),
           "-o", str(out), *libdirs, *libs]
    if subprocess.run(cmd).returncode != 0:
        print(f"{source} did not build; not timed", file=sys.stderr)
        return None
    return out
