#!/usr/bin/env bash
# Installs the Python packages the test suite uses to read outputs with real readers
# (meshio and VTK's own Python package `vtk` for .vtu and .pvd) into a virtual environment,
# and prints its interpreter.
#
# Usage: scripts/install-test-deps.sh [VENV]   (default: target/test-venv)
# Then: export HEMICONTACT_PYTHON="$PWD/VENV/bin/python" before `cargo test`.
# Fails (non-zero exit) if the environment cannot be created or the install fails.
set -euo pipefail
venv="${1:-target/test-venv}"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check meshio vtk
"$venv/bin/python" -c "import meshio, numpy, vtk"
echo "$venv/bin/python"
