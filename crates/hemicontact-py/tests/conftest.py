"""Shared fixtures of the Python package's tests: the repository's paths and the
command-line program the bitwise comparisons run."""

import os
import pathlib
import shutil

import pytest

REPO = pathlib.Path(__file__).resolve().parents[3]
SCENARIOS = REPO / "scenarios"


@pytest.fixture(scope="session")
def cli() -> str:
    """The `hemicontact` binary: $HEMICONTACT_BIN, else target/release/hemicontact of this
    repository. Its absence is a failure, not a skip: the comparison is a requirement."""
    path = os.environ.get("HEMICONTACT_BIN") or str(REPO / "target" / "release" / "hemicontact")
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        found = shutil.which("hemicontact")
        assert found, (
            f"the hemicontact binary is needed for the comparison with the CLI: build it "
            f"(cargo build --release) or set HEMICONTACT_BIN (looked at {path})"
        )
        path = found
    return path
