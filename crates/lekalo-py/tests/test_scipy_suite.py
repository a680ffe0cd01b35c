"""The runner of SciPy's own spline tests (``scipy_suite/run.py``): it changes import statements
only, and ``docs/scipy.md`` shows its table of differences as it is."""

import importlib.util
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
spec = importlib.util.spec_from_file_location("scipy_suite_run", HERE / "scipy_suite" / "run.py")
run = importlib.util.module_from_spec(spec)
spec.loader.exec_module(run)

SOURCE = '''import numpy as np
from scipy.interpolate import (BSpline, interp1d,
    NdBSpline)
from scipy.interpolate._fitpack_py import splev as ev, bisplrep
import scipy.interpolate._fitpack_impl as _impl


def test_x():
    from scipy.interpolate import RegularGridInterpolator as RGI, CubicSpline
    return BSpline, "from scipy.interpolate import BSpline"
'''


def test_rewrite_changes_the_spline_imports_only():
    out = run.rewrite(SOURCE, provided={"BSpline", "splev", "CubicSpline"})
    assert out.splitlines() == [
        "import numpy as np",
        "from lekalo.scipy import BSpline; from scipy.interpolate import interp1d; "
        "from _lekalo_missing import NdBSpline",
        "",
        "from lekalo.scipy import splev as ev; from _lekalo_missing import bisplrep",
        "import scipy.interpolate._fitpack_impl as _impl",
        "",
        "",
        "def test_x():",
        "    from scipy.interpolate import RegularGridInterpolator as RGI; from lekalo.scipy import CubicSpline",
        '    return BSpline, "from scipy.interpolate import BSpline"',
    ]
    # the statements keep their first lines, so SciPy's line numbers still point at its code
    assert out.count("\n") == SOURCE.count("\n")


def test_rewrite_leaves_a_module_without_spline_imports_alone():
    src = "from scipy.interpolate import interp1d\nimport scipy.interpolate as si\n"
    assert run.rewrite(src, provided={"BSpline"}) == src


def test_the_documented_table_is_differences_toml():
    doc = (HERE.parents[2] / "docs" / "scipy.md").read_text(encoding="utf-8")
    begin, end = "<!-- differences:begin -->\n", "<!-- differences:end -->"
    assert begin in doc and end in doc, "docs/scipy.md lost its table markers"
    shown = doc.split(begin, 1)[1].split(end, 1)[0]
    assert shown == run.table(), "docs/scipy.md is out of date: paste `run.py --table` between its markers"


def test_every_difference_names_a_test_a_known_category_and_a_reason():
    import tomllib

    entries = tomllib.loads((HERE / "scipy_suite" / "differences.toml").read_text())["difference"]
    categories = {"not-provided", "not-available", "refusal", "warning", "convention", "rounding", "empty", "defect"}
    assert entries
    for e in entries:
        assert set(e) == {"test", "category", "reason"}, e
        assert e["test"].split("::")[0] in run.MODULES, e
        assert e["category"] in categories, e
        assert e["reason"].strip(), e
    tests = [e["test"] for e in entries]
    assert len(tests) == len(set(tests)), "an entry is listed twice"


@pytest.mark.parametrize("pin", ["scipy==1.17.1\n", "numpy==2\nscipy==0.1  # old\n"])
def test_the_pin_is_read_from_the_requirements(tmp_path, monkeypatch, pin):
    req = tmp_path / "requirements-test.txt"
    req.write_text(pin)
    monkeypatch.setattr(run, "REQUIREMENTS", req)
    assert run.pinned_version() == pin.split("scipy==")[1].split()[0]


def test_another_scipy_than_the_pinned_one_is_refused(tmp_path, monkeypatch):
    pytest.importorskip("scipy")
    req = tmp_path / "requirements-test.txt"
    req.write_text("scipy==0.0.1\n")
    monkeypatch.setattr(run, "REQUIREMENTS", req)
    with pytest.raises(SystemExit, match="pins 0.0.1"):
        run.source_files()


def test_a_foreign_build_directory_is_not_deleted(tmp_path):
    pytest.importorskip("scipy")
    (tmp_path / "precious.txt").write_text("keep me")
    with pytest.raises(SystemExit, match="not made by this script"):
        run.build(tmp_path)
    assert (tmp_path / "precious.txt").read_text() == "keep me"
