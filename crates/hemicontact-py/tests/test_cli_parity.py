"""The Python package gives the command line's results: the paper example at n = 32
through Python writes byte-identical `solution.vtu` and `contact.csv` files, and a
scenario file solved through `hemicontact.load` equals `hemicontact solve` of that file."""

import pathlib
import subprocess

import hemicontact as hc

from conftest import SCENARIOS


def _same_files(a: pathlib.Path, b: pathlib.Path, names):
    for name in names:
        x, y = (a / name).read_bytes(), (b / name).read_bytes()
        assert x == y, f"{name} differs between {a} and {b}"


def test_paper_n32_through_python_equals_the_cli_bitwise(cli, tmp_path):
    subprocess.run([cli, "paper", "--n", "32", "--out", str(tmp_path / "cli")], check=True,
                   capture_output=True)
    for case, c_kappa in (("locking", 1.0e4), ("no-locking", 0.0)):
        result = hc.solve(hc.paper_example(n=32, c_kappa=c_kappa))
        assert result.converged, result.message
        result.write(tmp_path / "py" / case)
        _same_files(tmp_path / "cli" / case, tmp_path / "py" / case, ["solution.vtu", "contact.csv"])


def test_scenario_file_through_python_equals_the_cli_bitwise(cli, tmp_path):
    # A Gmsh mesh with a relative path: resolved against the scenario's folder.
    scenario = SCENARIOS / "half-disc.toml"
    subprocess.run([cli, "solve", str(scenario), "--out", str(tmp_path / "cli")], check=True,
                   capture_output=True)
    written = hc.solve(hc.load(scenario)).write(tmp_path / "py")
    names = sorted(pathlib.Path(p).name for p in written)
    assert names == sorted(p.name for p in (tmp_path / "cli").iterdir())
    _same_files(tmp_path / "cli", tmp_path / "py", ["solution.vtu", "contact.csv", "deformed.svg"])
