#!/usr/bin/env bash
# The PyTorch tests of the Python package (lekalo.torch), which scripts/test.sh leaves out:
# PyPI's Linux wheel of torch brings its CUDA packages, about 3 GB to download and 5.3 GB
# installed (docs/differentiable.md, "PyTorch", has the measurements).
#
# 1. a virtual environment with the pinned requirements (crates/lekalo-py/requirements-torch.txt,
#    from PyPI), kept outside the clone under
#    ${XDG_CACHE_HOME:-$HOME/.cache}/lekalo/venv-torch-<hash of that file and the Python version>
#    and reused while the file is unchanged (set LEKALO_TORCH_VENV to choose another place);
# 2. the package built in release mode and installed into it as scripts/test.sh installs it
#    (pip install ./crates/lekalo-py);
# 3. the lekalo.torch tests (crates/lekalo-py/tests/test_torch*.py), which include the PyTorch
#    example of docs/differentiable.md.
#
# Usage: scripts/test-torch.sh [pytest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

source scripts/python-env.sh
python_env crates/lekalo-py/requirements-torch.txt venv-torch "${LEKALO_TORCH_VENV:-}" "about 3 GB from PyPI, several minutes"
# a broken torch fails here, loudly, rather than letting the tests skip themselves
"$venv/bin/python" -c 'import torch; print("torch", torch.__version__)'
install_package
cd "$root/crates/lekalo-py/tests"
"$venv/bin/python" -m pytest -q -p no:cacheprovider "$@" test_torch.py test_torch_nurbs_nets.py
