"""Scenarios from Python: dicts of the file's schema, the round trip through `to_dict`,
and errors that name the field as the command line does."""

import copy
import math

import pytest

import hemicontact as hc

from conftest import SCENARIOS

SMALL = {
    "mesh": {"kind": "rectangle", "size": [2.0, 1.0], "n": [8, 4]},
    "material": {"young": 1000.0, "poisson": 0.3},
    "dirichlet": [{"part": "left"}],
    "loads": {"traction": [{"part": "right", "value": [0.0, -10.0]}]},
}


def test_dict_round_trip_gives_the_same_scenario():
    s = hc.paper_example(n=8)
    d = s.to_dict()
    assert hc.Scenario.from_dict(d).to_dict() == d
    assert d["contact"][0]["friction"]["mu"] == {"law": "exponential", "a": 0.4, "b": 0.1, "beta": 100.0}


def test_a_number_for_mu_is_the_constant_law():
    # `"mu": 0.3` is `{"law": "constant", "mu": 0.3}`, as `mu = 0.3` in a file: the same
    # solution bit for bit, and the table form when written back.
    d = hc.paper_example(n=8).to_dict()
    short = copy.deepcopy(d)
    table = copy.deepcopy(d)
    for c in short["contact"]:
        c["friction"]["mu"] = 0.3
    for c in table["contact"]:
        c["friction"]["mu"] = {"law": "constant", "mu": 0.3}
    a, b = hc.solve(short), hc.solve(table)
    assert a.converged and b.converged
    assert (a.displacement == b.displacement).all()
    assert hc.Scenario.from_dict(short).to_dict()["contact"][0]["friction"]["mu"] == {
        "law": "constant",
        "mu": 0.3,
    }
    # A wrong value names both forms.
    for c in short["contact"]:
        c["friction"]["mu"] = "high"
    with pytest.raises(hc.ScenarioError, match="a number"):
        hc.Scenario.from_dict(short)


def test_file_and_dict_give_the_same_solution():
    s = hc.load(SCENARIOS / "paper-elastic.toml")
    a = hc.solve(s)
    b = hc.solve(hc.Scenario.from_dict(s.to_dict()))
    assert (a.displacement == b.displacement).all()


def test_a_cantilever_from_a_dict_bends_down_and_reactions_balance_the_load():
    r = hc.solve(SMALL)
    assert r.converged
    assert r.displacement[:, 1].min() < 0
    # Equilibrium: the reactions at the clamped side balance the traction, 10 N/m over 1 m.
    total = r.reactions.sum(axis=0)
    assert math.isclose(total[1], 10.0, rel_tol=1e-9)
    assert abs(total[0]) < 1e-9 * 10.0


@pytest.mark.parametrize(
    "change, field",
    [
        (lambda d: d["material"].update(young=-1.0), "material.young"),
        (lambda d: d["material"].update(yung=1.0), "material.yung"),
        (lambda d: d["material"].update(poisson=None), "material.poisson"),
        (lambda d: d["mesh"].update(n=[8, "four"]), "mesh.n"),
        (lambda d: d["dirichlet"][0].update(part="nowhere"), "dirichlet[0].part"),
        (lambda d: d["loads"]["traction"][0].update(value=[0.0, math.nan]), "loads.traction[0].value"),
        (lambda d: d.pop("mesh"), "mesh"),
    ],
)
def test_bad_input_raises_a_scenario_error_naming_the_field(change, field):
    d = {k: (dict(v) if isinstance(v, dict) else [dict(x) for x in v]) for k, v in SMALL.items()}
    d["loads"] = {"traction": [dict(SMALL["loads"]["traction"][0])]}
    change(d)
    with pytest.raises(hc.ScenarioError) as e:
        hc.Scenario.from_dict(d).check()
    assert isinstance(e.value, ValueError)
    assert f"`{field}" in str(e.value), str(e.value)


def test_paper_example_arguments_are_checked():
    for n in (0, -3, 2.5, True):
        with pytest.raises(hc.ScenarioError, match="field `n`"):
            hc.paper_example(n=n)
    for c in (-1.0, math.inf, "big"):
        with pytest.raises(hc.ScenarioError, match="field `c_kappa`"):
            hc.paper_example(n=8, c_kappa=c)


def test_a_missing_file_is_an_os_error(tmp_path):
    with pytest.raises(OSError):
        hc.load(tmp_path / "none.toml")
