"""Load stepping from Python: `load_path` returns one Result per step with its load
factor, a linear problem scales exactly, `solve` of a scenario with `[loading]` is the
path's last step, one step is the plain solve bitwise, and bad `[loading]` input names the
field."""

import numpy as np
import pytest

import hemicontact as hc


def block(loading=None, contact=True):
    s = {
        "mesh": {"kind": "rectangle", "size": [1.0, 1.0], "n": [4, 4]},
        "material": {"young": 1000.0, "poisson": 0.3},
        "dirichlet": [{"part": "bottom"}],
        "loads": {"traction": [{"part": "top", "value": [5.0, -300.0]}]},
    }
    if contact:
        s["contact"] = [{"part": "right", "gap": 0.01, "c_nu": 1.0e4}]
    if loading is not None:
        s["loading"] = loading
    return s


def test_linear_problem_scales_with_the_load_factor():
    steps = hc.load_path(block({"factors": [0.25, 0.5, 1.0]}, contact=False))
    assert [r.load_factor for r in steps] == [0.25, 0.5, 1.0]
    u1 = steps[-1].displacement
    scale = abs(u1).max()
    for r in steps:
        assert r.converged, r.message
        # Hooke's law without contact is linear: u(λ) = λ u(1) to round-off.
        assert abs(r.displacement - r.load_factor * u1).max() <= 1e-10 * scale


def test_solve_with_loading_is_the_last_step_and_one_step_the_plain_solve():
    path = hc.load_path(block({"steps": 3}))
    assert len(path) == 3 and path[-1].load_factor == 1.0
    last = hc.solve(block({"steps": 3}))
    assert last.load_factor == 1.0
    assert np.array_equal(last.displacement, path[-1].displacement)
    plain = hc.solve(block())
    assert plain.load_factor == 1.0
    one = hc.solve(block({"steps": 1}))
    assert np.array_equal(one.displacement, plain.displacement)
    assert np.array_equal(one.reactions, plain.reactions)


def test_a_step_writes_its_results(tmp_path):
    path = hc.load_path(block({"factors": [0.5, 1.0]}))
    written = path[0].write(tmp_path / "step")
    names = sorted(p.rsplit("/", 1)[-1] for p in written)
    assert "solution.vtu" in names and "summary.json" in names and "contact.csv" in names
    vtu = (tmp_path / "step" / "solution.vtu").read_bytes()
    assert b"TimeValue" in vtu


@pytest.mark.parametrize(
    "loading, field",
    [
        ({"steps": 0}, "loading.steps"),
        ({"factors": []}, "loading.factors"),
        ({"factors": [0.5, 0.25]}, "loading.factors[1]"),
        ({"factors": [-1.0]}, "loading.factors[0]"),
        ({}, "loading"),
    ],
)
def test_bad_loading_names_the_field(loading, field):
    with pytest.raises(hc.ScenarioError, match=field.replace("[", r"\[").replace("]", r"\]")):
        hc.load_path(block(loading))
