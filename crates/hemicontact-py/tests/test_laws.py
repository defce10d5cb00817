"""Friction coefficients written in Python: the same law as a built-in one gives the same
solution, the callable sees whole arrays once per outer iteration, and a failing callable
is reported naming the law."""

import math
import sys

import numpy as np
import pytest

import hemicontact as hc

# The paper's law: μ(r) = (a − b) e^{−βr} + b with a = 0.4, b = 0.1, β = 100 /m.
A, B, BETA = 0.4, 0.1, 100.0


def exponential(r):
    return (A - B) * np.exp(-BETA * r) + B


def paper_with(mu, n=16, part=None):
    d = hc.paper_example(n=n).to_dict()
    for k, c in enumerate(d["contact"]):
        if part is None or c["part"] == part:
            c["friction"]["mu"] = mu
    return d


def test_a_python_law_equal_to_the_builtin_one_gives_the_same_solution():
    builtin = hc.solve(hc.paper_example(n=16))
    custom = hc.solve(paper_with(exponential))
    assert builtin.converged and custom.converged
    scale = np.abs(builtin.displacement).max()
    assert np.abs(custom.displacement - builtin.displacement).max() <= 1e-12 * scale
    assert len(custom.history["outer"]) == len(builtin.history["outer"])


def test_the_callable_gets_all_slips_of_a_part_once_per_outer_iteration():
    arrays = []

    def counted(r):
        arrays.append(r.copy())
        return exponential(r)

    r = hc.solve(paper_with(counted, part="left"))
    calls = [len(a) for a in arrays]
    validation = [n for n in calls if n == 122]
    solve_calls = [n for n in calls if n != 122]
    left = r.contact["boundary"] == "left"
    points = int(left.sum())
    # The last call of the solve (the certificate's) sees the slips of the result, in m.
    # (Calls with the 122 sampling slips are the checks: validation, and the uniqueness
    # condition's estimates in the summary.)
    assert np.array_equal([a for a in arrays if len(a) != 122][-1], r.contact["slip"][left])
    # Arrays of all the part's points, never single points.
    assert set(solve_calls) == {points}, calls
    # Once at the start, once per outer iteration, once for the certificate.
    assert len(solve_calls) == len(r.history["outer"]) + 2, (len(solve_calls), len(r.history["outer"]))
    assert validation, "the law is sampled when the scenario is checked"


def test_the_dict_round_trip_keeps_the_callable_and_convergence_uses_it():
    s = hc.Scenario.from_dict(paper_with(exponential, n=4))
    assert s.to_dict()["contact"][0]["friction"]["mu"] is exponential
    a = hc.convergence(s, [4, 8], 16)
    b = hc.convergence(hc.paper_example(n=4), [4, 8], 16)
    assert [x["error"] for x in a] == pytest.approx([x["error"] for x in b], rel=1e-9)


class Boom(Exception):
    pass


def test_an_exception_in_the_callable_propagates_as_itself_naming_the_law():
    def failing(r):
        if r.max() > 0:
            raise Boom("no friction data for this slip")
        return exponential(r)

    with pytest.raises(Boom) as e:
        hc.solve(paper_with(failing, part="right"))
    if sys.version_info >= (3, 11):
        notes = " ".join(getattr(e.value, "__notes__", []))
        assert "contact[1].friction.mu (" in notes and "failing" in notes and "'right'" in notes, notes


@pytest.mark.parametrize(
    "law, says",
    [
        (lambda r: np.where(r > 0, np.nan, 0.3), "NaN"),
        (lambda r: 0.3 - 10.0 * r, "-"),
        (lambda r: exponential(r)[:-1], "shape"),
        (lambda r: "much", "a str"),
    ],
)
def test_a_bad_value_is_a_scenario_error_naming_the_law(law, says):
    with pytest.raises(hc.ScenarioError) as e:
        hc.solve(paper_with(law, part="left"))
    text = str(e.value)
    assert "contact[0].friction.mu" in text and says in text, text


def test_a_constant_scalar_result_is_accepted_as_a_constant_law():
    a = hc.solve(paper_with(lambda r: 0.25))
    d = hc.paper_example(n=16).to_dict()
    for c in d["contact"]:
        c["friction"]["mu"] = {"law": "constant", "mu": 0.25}
    b = hc.solve(d)
    assert np.abs(a.displacement - b.displacement).max() <= 1e-12 * np.abs(b.displacement).max()


def test_the_custom_law_example_runs(tmp_path):
    import importlib.util
    import pathlib
    import subprocess

    example = pathlib.Path(__file__).resolve().parents[3] / "examples" / "python" / "custom_law.py"
    out = subprocess.run(
        [sys.executable, str(example), "--h", "0.5", "--out", str(tmp_path)],
        capture_output=True, text=True, timeout=300,
    )
    assert out.returncode == 0, out.stdout + out.stderr
    made_by = "mesh by gmsh" if importlib.util.find_spec("gmsh") else "mesh by numpy"
    assert made_by in out.stdout, out.stdout
    # The friction bound of every slipping point is the law's μ(slip) times the pressure.
    line = next(l for l in out.stdout.splitlines() if l.startswith("max |bound"))
    assert float(line.split(":")[1].split()[0]) <= 1e-12, line
    assert (tmp_path / "solution.vtu").is_file() and (tmp_path / "interface.png").is_file()
