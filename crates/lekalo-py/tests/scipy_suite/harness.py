"""The ``conftest.py`` of the build directory that ``run.py`` fills with SciPy's spline tests.

- SciPy's own test configuration (``scipy.conftest``: the ``xp`` fixture, markers, FPU checks).
- SciPy's array-API capability table gets, for each object of ``lekalo.scipy`` and each
  stand-in of ``_lekalo_missing``, the entry of the SciPy object it replaces (the tests'
  ``make_xp_test_case`` decorators look objects up in it).
- ``differences.toml`` (copied beside this file): every test whose id matches an entry's
  ``test`` pattern (``*`` matches any characters, nothing else is special) is marked
  ``xfail(strict=True)`` with the entry's category and reason; an entry that matches no test
  fails a whole run.
- A test that passes without calling into ``lekalo.scipy`` during its set-up and call is
  reported as skipped, "does not reach lekalo.scipy": it tests an interpolator that is not a
  spline or SciPy's private helpers, and its passing says nothing about lekalo.
"""

from __future__ import annotations

import re
import sys
import threading
import tomllib
from pathlib import Path

import pytest
from scipy.conftest import *  # noqa: F403  (SciPy's fixtures and hooks)
import scipy.interpolate
from scipy._lib._array_api import xp_capabilities_table

import lekalo.scipy

# the stand-ins of _lekalo_missing are made by this module instance (not a second import of it)
sys.modules["_lekalo_harness"] = sys.modules[__name__]
_LEKALO_DIR = str(Path(lekalo.scipy.__file__).resolve().parent)
_DEFAULT_CAPABILITIES = xp_capabilities_table[scipy.interpolate.BSpline]
_reached = False


def _capabilities_of(name: str) -> dict:
    return xp_capabilities_table.get(getattr(scipy.interpolate, name, None), _DEFAULT_CAPABILITIES)


for _name in lekalo.scipy.__all__:
    xp_capabilities_table[getattr(lekalo.scipy, _name)] = _capabilities_of(_name)


class _Missing(type):
    """The type of a stand-in: any use of the stand-in (a call, a class attribute) raises."""

    def __call__(cls, *args, **kwargs):
        cls._refuse()

    def __getattr__(cls, attr):
        if attr.startswith("__"):
            raise AttributeError(attr)
        return lambda *args, **kwargs: cls._refuse()


def missing(name: str) -> type:
    """A stand-in for SciPy's ``name``, which ``lekalo.scipy`` does not provide."""

    def refuse() -> None:
        global _reached
        _reached = True
        raise NotImplementedError(f"lekalo.scipy does not provide {name}")

    stand_in = _Missing(name, (), {"_refuse": staticmethod(refuse)})
    xp_capabilities_table[stand_in] = _capabilities_of(name)
    return stand_in


def _differences() -> list[dict]:
    path = Path(__file__).resolve().parent / "differences.toml"
    entries = tomllib.loads(path.read_text())["difference"]
    for entry in entries:
        if set(entry) != {"test", "category", "reason"}:
            raise pytest.UsageError(f"{path}: each difference has test, category and reason: {entry}")
    return entries


_DIFFERENCES = _differences()
_PATTERNS = [re.compile(re.escape(e["test"]).replace(r"\*", ".*")) for e in _DIFFERENCES]
_used: set[str] = set()
_listed: list[str] = []  # ids of the collected tests marked as differences


def pytest_collection_modifyitems(config, items):
    for item in items:
        for entry, pattern in zip(_DIFFERENCES, _PATTERNS):
            if pattern.fullmatch(item.nodeid):
                _used.add(entry["test"])
                _listed.append(item.nodeid)
                item.add_marker(pytest.mark.xfail(strict=True, reason=f"{entry['category']}: {entry['reason']}"))
                break


def _stale(config) -> list[str]:
    """The entries of differences.toml that match no collected test, on a whole run."""
    whole = not config.option.keyword and not config.option.markexpr and all(Path(a).is_dir() for a in config.args)
    return [e["test"] for e in _DIFFERENCES if e["test"] not in _used] if whole else []


def pytest_terminal_summary(terminalreporter):
    passed = len(terminalreporter.stats.get("passed", []))
    if passed + len(_listed):
        terminalreporter.write_line(
            f"lekalo.scipy passes {passed} of the {passed + len(_listed)} selected SciPy tests that reach it "
            f"({100 * passed / (passed + len(_listed)):.1f}%); {len(_listed)} are listed in differences.toml"
        )
    stale = _stale(terminalreporter.config)
    if stale:
        terminalreporter.write_line("differences.toml entries that match no test: " + ", ".join(stale), red=True)


def pytest_sessionfinish(session, exitstatus):
    if exitstatus == 0 and _stale(session.config):
        session.exitstatus = 1


def _trace(frame, event, arg):
    global _reached
    if frame.f_code.co_filename.startswith(_LEKALO_DIR):
        _reached = True
    return None


_scipy_runtest_setup = pytest_runtest_setup  # noqa: F405  (SciPy's, kept)


def pytest_runtest_setup(item):
    global _reached
    _reached = False
    sys.settrace(_trace)
    threading.settrace(_trace)
    _scipy_runtest_setup(item)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_teardown(item):
    sys.settrace(None)
    threading.settrace(None)
    return (yield)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item, call):
    report = yield
    if call.when == "call":
        sys.settrace(None)
        threading.settrace(None)
        if report.passed and not _reached and not hasattr(report, "wasxfail"):
            report.outcome = "skipped"
            report.longrepr = (str(item.path), item.location[1] or 0, "Skipped: does not reach lekalo.scipy")
    return report
