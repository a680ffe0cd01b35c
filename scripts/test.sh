#!/usr/bin/env bash
# Every test of the project: the Rust workspace, then the Python package.
#
# 1. cargo test --workspace
# 2. a virtual environment with the pinned test requirements
#    (crates/lekalo-py/requirements-test.txt, from PyPI), kept outside the clone under
#    ${XDG_CACHE_HOME:-$HOME/.cache}/lekalo/venv-<hash of that file and the Python version> and
#    reused while the file is unchanged (set LEKALO_VENV to choose another place);
# 3. the package built in release mode and installed into it (pip install ./crates/lekalo-py,
#    the command users run), and its pytest suite, which includes the Dask and Spark examples
#    at a small size (Spark is skipped, saying why, when Java is missing);
# 4. SciPy's own spline tests at the pinned version, run against lekalo.scipy
#    (crates/lekalo-py/tests/scipy_suite/run.py; docs/scipy.md);
# 5. scripts/test-browser.sh, when it exists.
#
# Usage: scripts/test.sh [pytest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

echo "== cargo test --workspace"
cargo test --workspace

echo "== Python package"
python=${PYTHON:-python3}
req=crates/lekalo-py/requirements-test.txt
key=$( (cat "$req"; "$python" -c 'import sys; print(sys.version)') | sha256sum | cut -c1-16)
venv=${LEKALO_VENV:-${XDG_CACHE_HOME:-$HOME/.cache}/lekalo/venv-$key}
if [ ! -x "$venv/bin/python" ] || [ ! -f "$venv/.complete" ]; then
  echo "creating $venv (first run with these requirements: a few minutes)"
  rm -rf "$venv"
  mkdir -p "$(dirname "$venv")"
  "$python" -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check -r "$req"
  touch "$venv/.complete"
else
  echo "reusing $venv"
fi
export PATH="$venv/bin:$PATH"
# the same command as for users, without build isolation so that the pinned maturin and the
# workspace's target/ (already built dependencies) are used
"$venv/bin/pip" install --quiet --disable-pip-version-check --no-build-isolation --force-reinstall --no-deps ./crates/lekalo-py
# tests run against the installed package, from outside the source tree
cd "$root/crates/lekalo-py/tests"
"$venv/bin/python" -m pytest -q -p no:cacheprovider "$@" .
cd "$root"

echo "== SciPy's spline tests against lekalo.scipy"
"$venv/bin/python" crates/lekalo-py/tests/scipy_suite/run.py -q

if [ -x scripts/test-browser.sh ]; then
  echo "== browser tests"
  scripts/test-browser.sh
fi
