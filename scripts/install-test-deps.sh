#!/usr/bin/env bash
# Installs the Python packages the test suite uses to read outputs with real readers
# (meshio for .vtu). Tests that need them skip with a message when they are missing.
set -euo pipefail
python3 -c "import meshio" 2>/dev/null && exit 0
python3 -m pip install --quiet --disable-pip-version-check meshio
