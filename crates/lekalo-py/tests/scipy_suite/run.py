"""SciPy's own spline tests, run against ``lekalo.scipy``.

    python crates/lekalo-py/tests/scipy_suite/run.py [--build DIR] [pytest arguments...]
    python crates/lekalo-py/tests/scipy_suite/run.py --table   # differences.toml as Markdown

1. Takes the spline test modules (``MODULES``) and their ``data/`` from the SciPy installed in
   the running interpreter, after checking that its version is the one pinned in
   ``crates/lekalo-py/requirements-test.txt`` and that every file is byte for byte the file the
   wheel installed (its ``RECORD`` hash): nothing is copied into the repository.
2. Rewrites only their import statements (``rewrite``): a name of SciPy's spline interface
   (``SPLINE_NAMES``) imported from ``scipy.interpolate`` or one of its private modules comes
   from ``lekalo.scipy`` when ``lekalo.scipy`` provides it, otherwise from ``_lekalo_missing``,
   whose stand-ins raise ``NotImplementedError`` when used, so that the test fails and has to be
   listed; every other name (``interp1d``, ``RegularGridInterpolator``, SciPy's private helpers)
   still comes from SciPy. The build directory (default ``target/scipy-suite``) holds the
   rewritten modules and ``conftest.py`` (a copy of ``harness.py``).
3. Runs pytest there. ``differences.toml`` is the table of deliberate differences: each entry is
   marked ``xfail(strict=True)``, so a listed test that starts passing turns the run red, as does
   any failure not listed. A test that passes without ever calling into ``lekalo.scipy`` (it
   exercises an interpolator that is not a spline, or SciPy's private helpers) is reported as
   skipped with the reason "does not reach lekalo.scipy" (see ``harness.py``).
"""

from __future__ import annotations

import ast
import base64
import hashlib
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[3]
REQUIREMENTS = ROOT / "crates" / "lekalo-py" / "requirements-test.txt"

MODULES = ["test_bsplines.py", "test_fitpack.py", "test_fitpack2.py", "test_polyint.py", "test_interpolate.py"]

# SciPy's spline interface: the names lekalo.scipy is to provide (a name missing from lekalo.scipy
# is imported as a stand-in that raises, never silently taken from SciPy).
SPLINE_NAMES = {
    "BSpline", "make_interp_spline", "make_lsq_spline", "make_smoothing_spline", "make_splrep",
    "make_splprep", "generate_knots", "splrep", "splprep", "splev", "splint", "sproot", "spalde",
    "splder", "splantider", "insert", "dblint", "UnivariateSpline", "InterpolatedUnivariateSpline",
    "LSQUnivariateSpline", "BivariateSpline", "RectBivariateSpline", "SmoothBivariateSpline",
    "LSQBivariateSpline", "LSQSphereBivariateSpline", "SmoothSphereBivariateSpline",
    "RectSphereBivariateSpline", "bisplrep", "bisplev", "CubicSpline", "PchipInterpolator", "pchip",
    "pchip_interpolate", "Akima1DInterpolator", "CubicHermiteSpline", "PPoly", "BPoly",
    "NdBSpline", "make_ndbspl",
}


def fail(message: str) -> None:
    sys.exit(f"scipy_suite: {message}")


def pinned_version() -> str:
    for line in REQUIREMENTS.read_text().splitlines():
        m = re.fullmatch(r"\s*scipy==([^\s#]+).*", line)
        if m:
            return m.group(1)
    fail(f"{REQUIREMENTS} pins no scipy version (a line scipy==X.Y.Z)")
    raise AssertionError("unreachable")


def source_files() -> tuple[Path, dict[str, Path]]:
    """The installed SciPy's test directory and the files to take, each checked against the
    wheel's RECORD; fails unless SciPy is the pinned version."""
    import scipy

    pin = pinned_version()
    if scipy.__version__ != pin:
        fail(f"the installed SciPy is {scipy.__version__}, {REQUIREMENTS.name} pins {pin}: "
             f"run with the test environment of scripts/test.sh (pip install scipy=={pin})")
    site = Path(scipy.__file__).resolve().parents[1]
    records = list(site.glob(f"scipy-{pin}.dist-info/RECORD"))
    if len(records) != 1:
        fail(f"no RECORD of scipy {pin} under {site}: SciPy was not installed from its wheel")
    hashes = {}
    for line in records[0].read_text().splitlines():
        path, recorded, _ = line.rsplit(",", 2)
        if recorded:
            hashes[path] = recorded
    tests = site / "scipy" / "interpolate" / "tests"
    files = {name: tests / name for name in MODULES}
    files.update({f"data/{p.name}": p for p in sorted((tests / "data").iterdir()) if p.is_file()})
    for rel, path in files.items():
        key = f"scipy/interpolate/tests/{rel}"
        if key not in hashes:
            fail(f"{key} is not in SciPy {pin}'s RECORD")
        algo, expected = hashes[key].split("=", 1)
        # RECORD holds the urlsafe base64 of the raw hash, unpadded (PEP 376 / the wheel format)
        want = base64.urlsafe_b64decode(expected + "=" * (-len(expected) % 4)).hex()
        if hashlib.new(algo, path.read_bytes()).hexdigest() != want:
            fail(f"{path} differs from the file SciPy {pin}'s wheel installed: reinstall scipy=={pin}")
    return tests, files


def _is_interpolate(module: str | None) -> bool:
    return module is not None and (module == "scipy.interpolate" or module.startswith("scipy.interpolate."))


def rewrite(source: str, provided: set[str]) -> str:
    """``source`` with each import of a spline name from ``scipy.interpolate`` (or a private module
    of it) replaced by an import from ``lekalo.scipy`` (or ``_lekalo_missing``); nothing else
    changes. Every rewritten statement keeps its indentation and first line."""
    lines = source.splitlines(keepends=True)
    edits = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.ImportFrom) or not _is_interpolate(node.module):
            continue
        groups: dict[str, list[str]] = {}
        for alias in node.names:
            if alias.name in SPLINE_NAMES:
                origin = "lekalo.scipy" if alias.name in provided else "_lekalo_missing"
            else:
                origin = node.module
            groups.setdefault(origin, []).append(alias.name + (f" as {alias.asname}" if alias.asname else ""))
        if set(groups) == {node.module}:
            continue
        indent = lines[node.lineno - 1][: node.col_offset]
        text = "; ".join(f"from {m} import {', '.join(names)}" for m, names in groups.items())
        edits.append((node.lineno, node.end_lineno, indent + text + "\n"))
    for start, end, text in sorted(edits, reverse=True):
        lines[start - 1 : end] = [text] + ["\n"] * (end - start)
    return "".join(lines)


def build(directory: Path) -> None:
    import lekalo.scipy

    if directory.exists() and any(directory.iterdir()) and not (directory / "_lekalo_missing.py").exists():
        fail(f"{directory} is not empty and was not made by this script: choose another --build directory")
    provided = set(lekalo.scipy.__all__)
    _, files = source_files()
    if directory.exists():
        shutil.rmtree(directory)
    (directory / "data").mkdir(parents=True)
    for rel, path in files.items():
        if rel.endswith(".py"):
            (directory / rel).write_text(rewrite(path.read_text(), provided))
        else:
            shutil.copyfile(path, directory / rel)
    shutil.copyfile(HERE / "harness.py", directory / "conftest.py")
    shutil.copyfile(HERE / "differences.toml", directory / "differences.toml")
    missing = sorted(SPLINE_NAMES - provided)
    (directory / "_lekalo_missing.py").write_text(
        '"""Stand-ins for the names of SciPy\'s spline interface that lekalo.scipy does not provide."""\n'
        "from _lekalo_harness import missing\n\n"
        + "".join(f"{name} = missing({name!r})\n" for name in missing)
    )


def table(path: Path = HERE / "differences.toml") -> str:
    """The table of deliberate differences as Markdown (one row per entry, in the file's order),
    as ``docs/scipy.md`` shows it."""
    import tomllib

    rows = ["| test | category | reason |", "|---|---|---|"]
    for entry in tomllib.loads(path.read_text())["difference"]:
        rows.append(f"| `{entry['test']}` | {entry['category']} | {entry['reason']} |")
    return "\n".join(rows) + "\n"


def main(argv: list[str]) -> int:
    if argv == ["--table"]:
        sys.stdout.write(table())
        return 0
    directory = ROOT / "target" / "scipy-suite"
    if argv[:1] == ["--build"]:
        directory = Path(argv[1]).resolve()
        argv = argv[2:]
    build(directory)
    # native tracebacks: pytest's own formatting of the listed (xfail) failures takes minutes
    command = [
        sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "--tb=native", "--rootdir", str(directory),
        *argv, str(directory),
    ]
    return subprocess.call(command, cwd=directory)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
