"""Rigid obstacles through the Python dict schema, against independent facts: a plane
obstacle parallel to the contact part reproduces the flat foundation at the same gap; a
circle gives each contact point the circle's normal at its closest point; the
``obstacle`` key survives ``to_dict``; and bad obstacles raise ``ScenarioError`` naming the
field."""

import numpy as np
import pytest

import hemicontact as hc


def _block(foundation):
    """A block [0, 1] × [0, 0.5] pressed down by its top onto a foundation below it."""
    contact = {"part": "bottom", "law": "signorini"}
    contact.update(foundation)
    return {
        "mesh": {"kind": "rectangle", "size": [1.0, 0.5], "n": [8, 4]},
        "material": {"young": 1000.0, "poisson": 0.3},
        "dirichlet": [{"part": "top", "value": [0.0, -0.02]}],
        "contact": [contact],
    }


def test_plane_obstacle_equals_flat_foundation():
    flat = hc.solve(hc.Scenario.from_dict(_block({"gap": 0.004})))
    plane = hc.solve(
        hc.Scenario.from_dict(
            _block({"obstacle": {"kind": "plane", "point": [0.2, -0.004], "normal": [0.0, 3.0]}})
        )
    )
    assert flat.converged and plane.converged
    scale = np.abs(flat.displacement).max()
    assert np.abs(plane.displacement - flat.displacement).max() <= 1e-9 * scale
    assert np.allclose(plane.contact["gap"] + plane.contact["u_nu"], 0.004, rtol=0, atol=1e-15)
    assert np.all(plane.contact["normal"][:, :2] == [0.0, -1.0])


def test_circle_normals_point_from_the_centre():
    centre = np.array([0.5, -1.0])
    radius = 0.999
    s = hc.Scenario.from_dict(
        _block({"obstacle": {"kind": "circle", "center": centre.tolist(), "radius": radius}})
    )
    r = hc.solve(s)
    assert r.converged
    # The top's support carries the block down by 0.02: the nodes meet the circle there.
    carried = np.array([0.0, -0.02])
    x = np.stack([r.contact["x"], r.contact["y"]], axis=1) + carried
    offset = x - centre
    distance = np.linalg.norm(offset, axis=1)
    # The contact normal (outward from the body) points towards the centre.
    normal = -offset / distance[:, None]
    assert np.allclose(r.contact["normal"][:, :2], normal, atol=1e-14)
    # The gap there, and the normal part of the carried translation, make the initial gap.
    assert np.allclose(
        r.contact["gap"] + r.contact["u_nu"], distance - radius + normal @ carried, atol=1e-14
    )
    assert s.to_dict()["contact"][0]["obstacle"] == {
        "kind": "circle",
        "center": centre.tolist(),
        "radius": radius,
    }


@pytest.mark.parametrize(
    "obstacle, field",
    [
        ({"kind": "circle", "center": [0.5, 0.0], "radius": 0.2}, "contact[0].obstacle"),
        ({"kind": "circle", "center": [0.5, -1.0], "radius": -1.0}, "contact[0].obstacle.radius"),
        ({"kind": "plane", "point": [0.0, -1.0], "normal": [0.0, 0.0]}, "contact[0].obstacle.normal"),
        ({"kind": "sphere", "center": [0.5, -1.0], "radius": 0.5}, "contact[0].obstacle.kind"),
    ],
)
def test_bad_obstacles_name_the_field(obstacle, field):
    with pytest.raises(hc.ScenarioError, match=field.replace("[", r"\[").replace("]", r"\]")):
        hc.Scenario.from_dict(_block({"obstacle": obstacle})).check()


def test_gap_and_obstacle_together_are_refused():
    with pytest.raises(hc.ScenarioError, match=r"contact\[0\]\.gap"):
        hc.Scenario.from_dict(
            _block(
                {
                    "gap": 0.1,
                    "obstacle": {"kind": "plane", "point": [0.0, -1.0], "normal": [0.0, 1.0]},
                }
            )
        ).check()
