#!/usr/bin/env bash
# Builds and installs the Python package exactly as the README says (`pip install
# ./crates/hemicontact-py` in a fresh virtual environment), then runs its tests (pytest)
# against the installed wheel and the release binary of the command-line program.
#
# Usage: scripts/test-python.sh [VENV]   (default: target/py-venv; created anew)
# Needs: the release binary target/release/hemicontact (cargo build --release), or
# HEMICONTACT_BIN pointing to one. Fails (non-zero exit) on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${1:-target/py-venv}"
rm -rf "$venv"
python3 -m venv "$venv"
py="$venv/bin/python"
"$py" -m pip install --quiet --disable-pip-version-check --upgrade pip
# The README's install command (it fetches maturin into an isolated build environment).
"$py" -m pip install --quiet --disable-pip-version-check ./crates/hemicontact-py
# Only numpy at import time: importing the package must not need the test extras.
"$py" -c "import hemicontact, sys; assert 'matplotlib' not in sys.modules and 'meshio' not in sys.modules; print('hemicontact', hemicontact.__version__)"
"$py" -m pip install --quiet --disable-pip-version-check pytest meshio matplotlib gmsh
export HEMICONTACT_BIN="${HEMICONTACT_BIN:-$PWD/target/release/hemicontact}"
# Run from the tests' folder so that `import hemicontact` finds the installed package, not
# the source tree.
cd crates/hemicontact-py/tests
"../../../$py" -m pytest -q -p no:cacheprovider .
