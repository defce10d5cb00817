"""Notes on inputs and results that make no sense, through Python: a solve beyond small
deformation (a block whose bottom must reach a plane 2 m up while its top is clamped at
y = 1, so that it moves by at least 2 m and its cells turn inside out) and an obstacle
smaller than the mesh (a circle of radius 1 mm poking 0.5 mm into the block between two
nodes 0.125 m apart) each raise a ``RuntimeWarning`` and are listed in ``Result.notes``;
a small deformation raises none; an obstacle facing away from the body is refused."""

import warnings

import pytest

import hemicontact as hc


def _block(obstacle, top=(0.0, 0.0), size=(1.0, 1.0), n=(4, 4)):
    return {
        "mesh": {"kind": "rectangle", "size": list(size), "n": list(n)},
        "material": {"young": 1000.0, "poisson": 0.3},
        "dirichlet": [{"part": "top", "value": list(top)}],
        "contact": [{"part": "bottom", "law": "signorini", "obstacle": obstacle}],
    }


DEEP = _block({"kind": "plane", "point": [0.0, 2.0], "normal": [0.0, 1.0]})


def test_a_deformation_too_large_for_the_model_warns():
    with pytest.warns(RuntimeWarning, match="small deformation") as record:
        r = hc.solve(DEEP)
    messages = [str(w.message) for w in record if "small deformation" in str(w.message)]
    assert len(messages) == 3, messages
    assert r.converged
    check = r.summary["small_deformation"]
    # The bottom nodes end at y ≥ 2: moved by at least 2 m, 2/√2 of the diagonal.
    assert check["max_displacement_ratio"] >= 2**0.5 * (1 - 1e-6)
    assert check["inverted_cells"] > 0 and check["strain_limit"] == 0.1
    assert r.notes == r.summary["notes"]
    assert [n for n in r.notes if n.startswith("small deformation")] == r.flagged_notes


def test_a_load_path_warns_with_its_first_step_noted():
    d = dict(DEEP, loading={"steps": 3})
    with pytest.warns(RuntimeWarning) as record:
        steps = hc.load_path(d)
    messages = [str(w.message) for w in record]
    assert any("(step 1 of 3)" in m and "small deformation" in m for m in messages), messages
    assert all(s.flagged_notes for s in steps)


def test_a_small_deformation_warns_nothing():
    d = _block({"kind": "plane", "point": [0.0, -0.001], "normal": [0.0, 1.0]}, top=(0.0, -0.01))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = hc.solve(d)
    assert r.converged and r.flagged_notes == [] and r.notes == []
    assert r.summary["small_deformation"]["max_strain"] < 0.1


def test_an_obstacle_smaller_than_the_mesh_warns():
    d = _block(
        {"kind": "circle", "center": [0.5625, -0.0005], "radius": 0.001},
        top=(0.0, 0.0),
        size=(1.0, 0.5),
        n=(8, 4),
    )
    with pytest.warns(RuntimeWarning) as record:
        r = hc.solve(d)
    messages = [str(w.message) for w in record]
    assert any("radius of curvature R = 0.001 m" in m for m in messages), messages
    assert any("reaches 0.0005 m into the body" in m for m in messages), messages
    assert len(r.flagged_notes) == 2, r.flagged_notes
    assert any("radius of curvature" in n for n in hc.Scenario.from_dict(d).check())


def test_an_obstacle_facing_away_is_refused():
    d = _block({"kind": "plane", "point": [0.0, -0.01], "normal": [0.0, -1.0]})
    with pytest.raises(hc.ScenarioError, match=r"contact\[0\]\.obstacle.*the body lies inside"):
        hc.solve(d)
