"""The per-part contact totals of a result (``Result.contact_totals``, the
``contact_totals`` of ``summary.json``) against independent facts: a block pressed by a
uniform pressure q onto a frictionless foundation carries q × the loaded length (area)
through its whole face, with the pressure q on it; a block short of its foundation carries
nothing; and the totals are the sums of the contact table's rows."""

import numpy as np

import hemicontact as hc

TOL = 1e-8


def _block(size, n, q, contact):
    """A block of `size` on an `n` grid, rollers on its sides, pressed by `q` on its top
    onto the foundations `contact`."""
    d = len(size)
    rollers = [("left", "x"), ("right", "x")] + ([("front", "y"), ("back", "y")] if d == 3 else [])
    return {
        "mesh": {"kind": "rectangle" if d == 2 else "box", "size": list(size), "n": list(n)},
        "material": {"young": 1000.0, "poisson": 0.3},
        "dirichlet": [{"part": p, "components": [c]} for p, c in rollers],
        "loads": {"traction": [{"part": "top", "value": [0.0] * (d - 1) + [-q]}]},
        "contact": contact,
    }


def _assert_pressed(t, q, measure, points, d):
    load = q * measure
    assert t["part"] == "bottom"
    assert (t["points"], t["n_contact"], t["n_stick"], t["n_slip"]) == (points, points, 0, 0)
    assert t["force"].shape == (d,) and t["force_tangential"].shape == (d,)
    assert abs(t["force"][-1] - load) < TOL * load
    assert abs(t["force_normal"] + load) < TOL * load
    assert np.all(np.abs(t["force"][:-1]) < TOL * load)
    assert np.all(np.abs(t["force_tangential"]) < TOL * load)
    assert abs(t["contact_measure"] - measure) < 1e-12 * measure
    assert abs(t["max_pressure"] - q) < TOL * q
    assert t["max_pressure_at"].shape == (d,) and t["max_pressure_at"][-1] == 0.0


def test_a_pressed_block_carries_the_pressure_times_the_length():
    a, n, q = 2.0, 8, 50.0
    r = hc.solve(_block([a, 1.0], [n, 4], q, [{"part": "bottom", "gap": 0.0, "c_nu": 2.0e4}]))
    assert r.converged, r.message
    assert len(r.contact_totals) == 1
    _assert_pressed(r.contact_totals[0], q, a, n + 1, 2)


def test_a_pressed_box_carries_the_pressure_times_the_area():
    a, b, q = 2.0, 1.5, 40.0
    r = hc.solve(
        _block([a, b, 1.0], [4, 3, 2], q, [{"part": "bottom", "gap": 0.0, "law": "signorini"}])
    )
    assert r.converged, r.message
    _assert_pressed(r.contact_totals[0], q, a * b, 5 * 4, 3)


def test_a_block_short_of_its_foundation_carries_nothing():
    # Hanging from its top under its weight: the bottom sags by about 0.004 m < gap 0.1.
    f = 10.0
    d = {
        "mesh": {"kind": "rectangle", "size": [1.0, 1.0], "n": [4, 4]},
        "material": {"young": 1000.0, "poisson": 0.3},
        "dirichlet": [
            {"part": "top"},
            {"part": "left", "components": ["x"]},
            {"part": "right", "components": ["x"]},
        ],
        "loads": {"body_force": [0.0, -f]},
        "contact": [{"part": "bottom", "gap": 0.1, "c_nu": 2.0e4}],
    }
    r = hc.solve(d)
    assert r.converged, r.message
    (t,) = r.contact_totals
    assert (t["points"], t["n_contact"], t["n_stick"], t["n_slip"]) == (5, 0, 0, 0)
    assert np.all(np.abs(t["force"]) < TOL * f) and abs(t["force_normal"]) < TOL * f
    assert t["contact_measure"] == 0.0 and t["max_pressure"] == 0.0
    assert t["max_pressure_node"] is None and t["max_pressure_at"] is None


def test_the_totals_are_the_sums_of_the_contact_table():
    # The paper example: friction, two contact parts' worth of states; the totals of each
    # boundary against sums over the rows of `contact` computed here.
    r = hc.solve(hc.paper_example(n=16))
    assert r.converged, r.message
    c = r.contact
    d = r.dim
    assert [t["part"] for t in r.contact_totals] == [
        e["part"] for e in r.summary["contact_totals"]
    ]
    assert sum(t["points"] for t in r.contact_totals) == len(c["node"])
    for t in r.contact_totals:
        rows = c["boundary"] == t["part"]
        assert t["points"] == rows.sum()
        in_contact = rows & (c["normal_state"] == "contact")
        assert t["n_contact"] == in_contact.sum()
        assert t["n_stick"] == (rows & (c["friction_state"] == "stick")).sum()
        assert t["n_slip"] == (rows & (c["friction_state"] == "slip")).sum()
        force = c["force"][rows, :d]
        scale = np.abs(force).sum() + 1e-300
        assert np.allclose(t["force"], force.sum(axis=0), rtol=0, atol=1e-12 * scale)
        normal = c["normal"][rows, :d]
        f_n = (force * normal).sum(axis=1)
        assert abs(t["force_normal"] - f_n.sum()) <= 1e-12 * scale
        tangential = force - f_n[:, None] * normal
        assert np.allclose(t["force_tangential"], tangential.sum(axis=0), rtol=0, atol=1e-12 * scale)
        assert abs(t["contact_measure"] - c["weight"][in_contact].sum()) <= 1e-12 * c["weight"][rows].sum()
        if in_contact.any():
            assert t["max_pressure"] == c["pressure"][in_contact].max()
            node = t["max_pressure_node"]
            assert c["pressure"][rows & (c["node"] == node)].max() == t["max_pressure"]
            assert np.array_equal(t["max_pressure_at"], r.points[node])
