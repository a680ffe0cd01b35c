# Sourced by scripts/test.sh and scripts/test-torch.sh: one virtual environment per set of
# pinned requirements, and the package installed into it the way users install it.
#
# python_env REQUIREMENTS NAME OVERRIDE NOTE
#   sets $venv to $OVERRIDE when set, else to
#   ${XDG_CACHE_HOME:-$HOME/.cache}/lekalo/NAME-<hash of REQUIREMENTS and the Python version>,
#   creates it from REQUIREMENTS (PyPI) unless a complete one is there (NOTE says how long the
#   first run takes), and puts it first on PATH.
# install_package
#   pip install ./crates/lekalo-py into $venv, without build isolation so that the pinned maturin
#   and the workspace's target/ (already built dependencies) are used.
python_env() {
  local req=$1 name=$2 override=$3 note=$4
  local python=${PYTHON:-python3}
  local key
  key=$( (cat "$req"; "$python" -c 'import sys; print(sys.version)') | sha256sum | cut -c1-16)
  venv=${override:-${XDG_CACHE_HOME:-$HOME/.cache}/lekalo/$name-$key}
  if [ ! -x "$venv/bin/python" ] || [ ! -f "$venv/.complete" ]; then
    echo "creating $venv (first run with these requirements: $note)"
    rm -rf "$venv"
    mkdir -p "$(dirname "$venv")"
    "$python" -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check -r "$req"
    touch "$venv/.complete"
  else
    echo "reusing $venv"
  fi
  export PATH="$venv/bin:$PATH"
}

install_package() {
  "$venv/bin/pip" install --quiet --disable-pip-version-check --no-build-isolation --force-reinstall --no-deps ./crates/lekalo-py
}
