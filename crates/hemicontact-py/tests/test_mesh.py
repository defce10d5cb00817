"""Meshes from numpy arrays and meshio: the same mesh gives the same solution, the parts
keep their names, and invalid arrays are refused with the array named."""

import numpy as np
import pytest

import hemicontact as hc

from test_scenarios import SMALL


def test_a_mesh_from_arrays_equals_the_generated_mesh():
    s = hc.Scenario.from_dict(SMALL)
    generated = s.mesh()
    m = hc.Mesh.from_arrays(generated.points, generated.cells, generated.facets)
    assert np.array_equal(m.points, generated.points) and np.array_equal(m.cells, generated.cells)
    d = s.to_dict()
    d["mesh"] = m
    a, b = hc.solve(s), hc.solve(d)
    assert np.array_equal(a.displacement, b.displacement)


def test_unnamed_boundary_facets_form_the_part_untagged():
    g = hc.Scenario.from_dict(SMALL).mesh()
    m = hc.Mesh.from_arrays(g.points, g.cells, {"left": g.facets["left"]})
    assert list(m.facets) == ["left", "untagged"]
    total = sum(len(f) for f in g.facets.values())
    assert len(m.facets["untagged"]) == total - len(g.facets["left"])


def test_a_planar_mesh_with_a_zero_z_column_is_accepted():
    g = hc.Scenario.from_dict(SMALL).mesh()
    p3 = np.hstack([g.points, np.zeros((len(g.points), 1))])
    assert np.array_equal(hc.Mesh.from_arrays(p3, g.cells).points, g.points)


def test_meshio_round_trip_keeps_points_cells_and_parts():
    g = hc.Scenario.from_dict(SMALL).mesh()
    back = hc.Mesh.from_meshio(g.to_meshio())
    assert np.array_equal(back.points, g.points) and np.array_equal(back.cells, g.cells)
    assert {k: v.tolist() for k, v in back.facets.items()} == {k: v.tolist() for k, v in g.facets.items()}


def test_meshio_file_round_trip_of_a_result(tmp_path):
    import meshio

    r = hc.solve(SMALL)
    path = tmp_path / "r.vtu"
    meshio.write(path, r.to_meshio())
    m = meshio.read(path)
    assert np.array_equal(m.point_data["displacement"][:, :2], r.displacement)
    assert np.allclose(m.cell_data["von_mises"][0], r.von_mises, rtol=0, atol=0)


def test_a_clockwise_triangle_is_refused_not_reoriented():
    points = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    with pytest.raises(hc.ScenarioError, match="cell 0"):
        hc.Mesh.from_arrays(points, [[0, 2, 1]])


@pytest.mark.parametrize(
    "points, cells, facets, named",
    [
        ([[0.0, 0.0], [1.0, 0.0]], [[0, 1]], None, "cells"),
        ([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [[0, 1, 5]], None, "out of range"),
        ([[0.0, 0.0], [1.0, 0.0], [0.0, np.nan]], [[0, 1, 2]], None, "points[2]"),
        ([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [[0, 1, -2]], None, "cells"),
        ([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [[0, 1, 2]], {"base": [[0, 1, 2]]}, "facets['base']"),
        ([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [[0.5, 1, 2]], None, "cells"),
    ],
)
def test_invalid_arrays_are_refused_naming_them(points, cells, facets, named):
    with pytest.raises(hc.ScenarioError) as e:
        hc.Mesh.from_arrays(points, cells, facets)
    assert named in str(e.value), str(e.value)


def test_a_gmsh_file_through_meshio_equals_the_library_reader():
    import meshio

    from conftest import SCENARIOS

    m = meshio.read(SCENARIOS / "meshes" / "half-disc.msh")
    # Gmsh meshed this surface clockwise: the whole entity is reoriented, with a warning.
    with pytest.warns(RuntimeWarning, match="geometric entity"):
        mesh = hc.Mesh.from_meshio(m)
    s = hc.load(SCENARIOS / "half-disc.toml")
    g = s.mesh()
    assert np.array_equal(mesh.points, g.points) and np.array_equal(mesh.cells, g.cells)
    assert {k: v.tolist() for k, v in mesh.facets.items()} == {k: v.tolist() for k, v in g.facets.items()}
    d = s.to_dict()
    d["mesh"] = mesh
    assert np.array_equal(hc.solve(d).displacement, hc.solve(s).displacement)


def test_an_entity_of_both_orientations_is_refused_naming_a_cell():
    import meshio

    from conftest import SCENARIOS

    m = meshio.read(SCENARIOS / "meshes" / "half-disc.msh")
    for block in m.cells:
        if block.type == "triangle":
            block.data[0] = block.data[0][[1, 0, 2]]  # one cell against the others
    with pytest.raises(hc.ScenarioError, match="inverted"):
        hc.Mesh.from_meshio(m)


def _with_unused_node(g, at):
    """The mesh ``g`` with an extra node, used by no cell, inserted at index ``at``."""
    points = np.insert(g.points, at, [[5.0, 5.0]], axis=0)
    shift = lambda a: np.where(a >= at, a + 1, a)  # noqa: E731
    return points, shift(g.cells), {k: shift(v) for k, v in g.facets.items()}


def test_a_node_no_cell_uses_is_dropped_with_a_warning_and_results_keep_the_numbering():
    s = hc.Scenario.from_dict(SMALL)
    g = s.mesh()
    points, cells, facets = _with_unused_node(g, 7)
    with pytest.warns(RuntimeWarning, match=r"1 of 46 nodes are used by no cell .*\(nodes 7\)"):
        m = hc.Mesh.from_arrays(points, cells, facets)
    # The mesh keeps the numbering given.
    assert np.array_equal(m.points, points) and np.array_equal(m.cells, cells)
    assert {k: v.tolist() for k, v in m.facets.items()} == {k: v.tolist() for k, v in facets.items()}
    assert m.dropped_nodes.tolist() == [7]
    d = s.to_dict()
    d["mesh"] = m
    r, reference = hc.solve(d), hc.solve(s)
    # The same mesh without the node: the same solution, at the same nodes.
    keep = np.arange(len(points)) != 7
    assert np.array_equal(r.displacement[keep], reference.displacement)
    assert np.all(np.isnan(r.displacement[7])) and np.all(np.isnan(r.reactions[7]))
    assert np.array_equal(r.points, points) and np.array_equal(r.cells, cells)
    assert r.converged


def test_a_facet_on_a_node_no_cell_uses_is_refused_naming_it():
    g = hc.Scenario.from_dict(SMALL).mesh()
    points, cells, facets = _with_unused_node(g, 7)
    facets["stray"] = np.array([[7, 0]])
    with pytest.raises(hc.ScenarioError, match=r"facets\['stray'\]\[0\].*node 7 is used by no cell"):
        hc.Mesh.from_arrays(points, cells, facets)


def test_overlapping_cells_are_named_as_an_overlap():
    # The unit square as two triangles, plus a third over half of each: the bottom edge is
    # then shared by cells 0 and 2, both above it.
    points = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    facets = {"bottom": [[0, 1]], "right": [[1, 2]], "top": [[2, 3]], "left": [[3, 0]]}
    hc.Mesh.from_arrays(points, [[0, 1, 2], [0, 2, 3]], facets)
    with pytest.raises(hc.ScenarioError) as e:
        hc.Mesh.from_arrays(points, [[0, 1, 2], [0, 2, 3], [0, 1, 3]], facets)
    text = str(e.value)
    assert "cells overlap" in text and "cell 0 and cell 2; cell 1 and cell 2" in text, text


def test_a_result_with_a_dropped_node_is_drawn(tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    s = hc.Scenario.from_dict(SMALL)
    points, cells, facets = _with_unused_node(s.mesh(), 7)
    with pytest.warns(RuntimeWarning):
        m = hc.Mesh.from_arrays(points, cells, facets)
    d = s.to_dict()
    d["mesh"] = m
    r = hc.solve(d)
    fig = hc.plot.deformed(r)
    # The axes frame the body, not the stray node at (5, 5).
    assert fig.axes[0].get_xlim()[1] < 3.0
    r.write(tmp_path / "out")
    assert (tmp_path / "out" / "solution.vtu").is_file()
