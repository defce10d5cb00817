"""Bodies of several materials from Python: a ``"material"`` list with one dict per cell
region, regions from the generator's boxes, from arrays or from meshio, and the result's
``material`` per cell. The bimaterial bar (ν = 0, halves of moduli E₁ and E₂ in series,
pulled by σ) stretches by σ (L₁/E₁ + L₂/E₂) exactly."""

import numpy as np
import pytest

import hemicontact as hc

SIGMA, E1, E2 = 35.0, 1000.0, 7000.0

BAR = {
    "mesh": {
        "kind": "rectangle",
        "size": [2.0, 0.5],
        "n": [8, 2],
        "region": [
            {"name": "soft", "min": [0.0, 0.0], "max": [1.0, 0.5]},
            {"name": "stiff", "min": [1.0, 0.0], "max": [2.0, 0.5]},
        ],
    },
    "material": [
        {"part": "soft", "young": E1, "poisson": 0.0},
        {"part": "stiff", "young": E2, "poisson": 0.0},
    ],
    "dirichlet": [
        {"part": "left", "components": ["x"]},
        {"part": "bottom", "components": ["y"]},
    ],
    "loads": {"traction": [{"part": "right", "value": [SIGMA, 0.0]}]},
}


def exact_ux(x):
    return np.where(x <= 1.0, SIGMA * x / E1, SIGMA / E1 + SIGMA * (x - 1.0) / E2)


def test_a_bimaterial_bar_stretches_by_the_sum_of_its_halves():
    r = hc.solve(BAR)
    assert r.converged
    end = SIGMA * (1.0 / E1 + 1.0 / E2)
    assert np.max(np.abs(r.displacement[:, 0] - exact_ux(r.points[:, 0]))) <= 1e-10 * end
    centroid_x = r.points[r.cells][:, :, 0].mean(axis=1)
    assert np.array_equal(r.material, (centroid_x > 1.0).astype(np.int64))
    assert np.allclose(r.stress[:, 0, 0], SIGMA, rtol=1e-9, atol=0.0)


def test_regions_from_arrays_and_meshio_give_the_same_solution():
    generated = hc.Scenario.from_dict(BAR).mesh()
    regions = generated.regions
    assert list(regions) == ["soft", "stiff"]
    assert len(regions["soft"]) + len(regions["stiff"]) == len(generated.cells)
    from_arrays = hc.Mesh.from_arrays(generated.points, generated.cells, generated.facets, regions)
    pytest.importorskip("meshio")
    from_meshio = hc.Mesh.from_meshio(generated.to_meshio())
    reference = hc.solve(BAR)
    for m in (from_arrays, from_meshio):
        assert {k: list(v) for k, v in m.regions.items()} == {k: list(v) for k, v in regions.items()}
        d = {k: v for k, v in BAR.items() if k != "mesh"}
        d["mesh"] = m
        assert np.array_equal(hc.solve(d).displacement, reference.displacement)


def test_bad_regions_are_refused_with_the_cell_named():
    g = hc.Scenario.from_dict(BAR).mesh()
    n = len(g.cells)
    with pytest.raises(hc.ScenarioError, match="cell 0 is in the regions"):
        hc.Mesh.from_arrays(g.points, g.cells, g.facets, {"a": np.arange(n), "b": [0]})
    with pytest.raises(hc.ScenarioError, match="is in no region"):
        hc.Mesh.from_arrays(g.points, g.cells, g.facets, {"a": np.arange(n - 1)})
    with pytest.raises(hc.ScenarioError, match="out of range"):
        hc.Mesh.from_arrays(g.points, g.cells, g.facets, {"a": [n]})


def test_a_material_list_must_name_every_region():
    d = dict(BAR, material=BAR["material"][:1])
    with pytest.raises(hc.ScenarioError, match='no \\[\\[material\\]\\] table for the cell region "stiff"'):
        hc.solve(d)
