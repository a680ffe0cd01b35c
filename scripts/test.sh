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
source scripts/python-env.sh
python_env crates/lekalo-py/requirements-test.txt venv "${LEKALO_VENV:-}" "a few minutes"
install_package
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
