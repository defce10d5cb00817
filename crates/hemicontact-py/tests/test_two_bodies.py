"""Two deformable bodies in contact from Python: ``"against"`` in a contact dict pairs the
nodes of one part (the slave side) with the surface of another body's part (the master
side). Two blocks stacked and pressed together (ν = 0) carry the uniform pressure E δ/H at
every point when their interface nodes coincide; the committed punch-on-block scenario
solves and certifies through Python as through the CLI; a free block rests on a held one
from either side of the pair; two free bodies that nothing holds up but their contact with
each other raise ``ScenarioError`` naming both by their cell regions and the motion."""

import numpy as np
import pytest

import hemicontact as hc
from conftest import REPO, SCENARIOS

TWO_BLOCKS = REPO / "crates" / "hemicontact" / "tests" / "data" / "gmsh" / "two-blocks.msh"
E, DELTA, H = 1000.0, 0.01, 1.0


def _pressed(slave="upper_bottom", master="lower_top", held="lower_bottom"):
    return {
        "mesh": {"kind": "gmsh", "file": str(TWO_BLOCKS)},
        "material": {"young": E, "poisson": 0.0},
        "dirichlet": [
            {"part": held},
            {"part": "upper_top", "value": [0.0, -DELTA]},
        ],
        "contact": [{"part": slave, "against": master, "law": "signorini"}],
    }


def test_two_blocks_carry_the_uniform_pressure():
    s = hc.Scenario.from_dict(_pressed())
    r = hc.solve(s)
    assert r.converged, r.message
    p = E * DELTA / H
    assert len(r.contact["pressure"]) == 5
    assert np.allclose(r.contact["pressure"], p, rtol=1e-10, atol=0)
    assert s.to_dict()["contact"][0]["against"] == "lower_top"


def test_punch_on_block_solves_through_python():
    r = hc.solve(hc.load(SCENARIOS / "punch-on-block.toml"))
    assert r.converged, r.message
    # Every point of the punch's bottom presses on the block.
    assert np.all(r.contact["pressure"] > 0.0)


def _resting(slave, master, lower_held=("x", "y")):
    # The upper block held along x only and pressed by p on its top: its vertical
    # translation and its rotation are free, carried by the pair.
    d = _pressed(slave=slave, master=master)
    d["dirichlet"] = [
        {"part": "lower_bottom", "components": list(lower_held)},
        {"part": "upper_top", "components": ["x"]},
    ]
    d["loads"] = {"traction": [{"part": "upper_top", "value": [0.0, -10.0]}]}
    return d


@pytest.mark.parametrize("slave,master", [("upper_bottom", "lower_top"),
                                          ("lower_top", "upper_bottom")])
def test_a_free_body_rests_on_a_held_one_either_side_of_the_pair(slave, master):
    r = hc.solve(hc.Scenario.from_dict(_resting(slave, master)))
    assert r.converged, r.message
    assert np.allclose(r.contact["pressure"], 10.0, rtol=1e-10, atol=0)


def test_two_free_bodies_that_nothing_holds_up_are_refused_naming_their_regions():
    # The lower block held along x only too: both bodies keep free rigid motions, analysed
    # together; their contact carries only their relative motion, so nothing holds them up.
    d = _resting("upper_bottom", "lower_top", lower_held=("x",))
    with pytest.raises(
        hc.ScenarioError,
        match=r"region `lower`.*region `upper`.*together: translation along y",
    ):
        hc.solve(hc.Scenario.from_dict(d))


def test_results_per_body_balance_and_act_equal_and_opposite():
    # The two blocks pressed together: the lower one (body 0, the smaller nodes) pushed
    # down by the pair with the force p × 1 m and held by its bottom's reaction, the upper
    # one pushed up by the pair and down by its top's prescribed displacement.
    r = hc.solve(hc.Scenario.from_dict(_pressed()))
    assert r.converged, r.message
    p = E * DELTA / H
    assert len(r.bodies) == 2
    lower, upper = r.bodies
    assert lower["regions"] == ["lower"] and upper["regions"] == ["upper"]
    assert "lower_top" in lower["parts"] and "upper_bottom" in upper["parts"]
    assert np.allclose(upper["contact_force"], [0.0, p], rtol=0, atol=1e-10 * p)
    assert np.allclose(lower["contact_force"], [0.0, -p], rtol=0, atol=1e-10 * p)
    assert np.allclose(lower["reaction"], [0.0, p], rtol=0, atol=1e-10 * p)
    assert np.allclose(upper["reaction"], [0.0, -p], rtol=0, atol=1e-10 * p)
    for b in r.bodies:
        assert b["imbalance"] < 1e-10
        assert np.all(b["load"] == 0.0)
    # The body of each node: the two blocks, their nodes numbered apart.
    assert set(r.body.tolist()) == {0, 1}
    assert np.bincount(r.body).tolist() == [lower["nodes"], upper["nodes"]]
    on_upper = r.body[r.contact["node"]]
    assert np.all(on_upper == 1)
