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
        # Converted to floats, these would lose an imaginary part or read True as 1.
        (lambda r: exponential(r) + 0j, "complex values"),
        (lambda r: [0.3 + 0.1j] * len(r), "complex values"),
        (lambda r: r >= 0.0, "boolean values"),
        (lambda r: True, "boolean values"),
        (lambda r: np.array([0.3] * (len(r) - 1) + [True], dtype=object), "bool value"),
        # Numbers as text, dates and other non-numbers: refused as booleans are, in any dtype.
        (lambda r: np.full(len(r), "0.3"), "strings (dtype <U3)"),
        (lambda r: ["0.3"] * len(r), "strings (dtype <U3)"),
        (lambda r: np.array(["0.3"] * len(r), dtype=object), "str value ('0.3')"),
        (lambda r: np.array([0.3] * (len(r) - 1) + ["0.3"], dtype=object), "str value ('0.3')"),
        (lambda r: np.full(len(r), b"0.3"), "bytes (dtype |S3)"),
        (lambda r: np.array([b"0.3"] * len(r), dtype=object), "bytes value (b'0.3')"),
        (lambda r: np.array([0.3] * (len(r) - 1) + [None], dtype=object), "NoneType value (None)"),
        (lambda r: np.full(len(r), np.datetime64("2024-01-01")), "datetimes (dtype datetime64[D])"),
        (lambda r: np.full(len(r), np.timedelta64(3, "s")), "time spans (timedelta) (dtype timedelta64[s])"),
        (lambda r: np.zeros(len(r), dtype="V8"), "raw or structured values (dtype |V8)"),
        (lambda r: np.zeros(len(r), dtype=[("mu", "f8")]), "raw or structured values"),
    ],
)
def test_a_bad_value_is_a_scenario_error_naming_the_law(law, says):
    with pytest.raises(hc.ScenarioError) as e:
        hc.solve(paper_with(law, part="left"))
    text = str(e.value)
    assert "contact[0].friction.mu" in text and says in text, text


def test_real_numbers_of_any_numeric_dtype_or_as_objects_give_the_float_law():
    # The same μ = 0.25 as float32 and as objects (Python and numpy floats): every
    # real-number form is accepted and gives the solution of the float64 values.
    reference = hc.solve(paper_with(lambda r: np.full(len(r), 0.25)))
    for law in (
        lambda r: np.full(len(r), 0.25, dtype=np.float32),
        lambda r: np.array([0.25] * len(r), dtype=object),
        lambda r: np.array([np.float64(0.25)] * len(r), dtype=object),
    ):
        s = hc.solve(paper_with(law))
        assert s.converged
        assert np.array_equal(s.displacement, reference.displacement)
    # An integer coefficient (μ = 1) as int64 and as unsigned integers.
    one = hc.solve(paper_with(lambda r: np.ones(len(r))))
    for law in (lambda r: np.ones(len(r), dtype=np.int64), lambda r: np.ones(len(r), dtype=np.uint8)):
        assert np.array_equal(hc.solve(paper_with(law)).displacement, one.displacement)


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


# A friction bound of the position and a normal compliance written in Python.


def tresca_with(mu, n=16):
    d = hc.paper_example(n=n).to_dict()
    for c in d["contact"]:
        c["friction"]["bound"] = "tresca"
        c["friction"]["mu"] = mu
    return d


def test_a_constant_tresca_bound_of_the_position_equals_the_built_in_constant_bound():
    seen = []

    def thirty(x):
        seen.append(x.shape)
        return np.full(len(x), 30.0)

    a = hc.solve(tresca_with({"law": "constant", "mu": 30.0}))
    b = hc.solve(tresca_with({"law": "position", "function": thirty}))
    assert a.converged and b.converged
    assert a.certificate["n_slip"] > 0, "some points slip: the bound matters"
    scale = np.abs(a.displacement).max()
    assert np.abs(b.displacement - a.displacement).max() <= 1e-12 * scale
    # (n, 2) arrays of the 16 points of a side, once per part per outer iteration, and a
    # few more calls per part (validation and the uniqueness check at the part's 17 nodes,
    # the start, the certificate): never one call per point.
    assert all(s in ((16, 2), (17, 2)) for s in seen), set(seen)
    assert len(seen) <= 2 * (len(b.history["outer"]) + 5)


def test_the_bound_at_each_contact_point_is_the_callable_at_its_coordinates():
    r = hc.solve(tresca_with({"law": "position", "function": lambda x: 10.0 + 5.0 * x[:, 1]}))
    assert r.converged
    expected = 10.0 + 5.0 * r.contact["y"]
    assert np.abs(r.contact["bound"] - expected).max() <= 1e-12 * expected.max()
    # μ₀ of the uniqueness check: the largest value at the contact nodes, F(·, 4) = 30 Pa.
    assert r.summary["uniqueness"]["mu0"] == 30.0


def test_a_negative_bound_of_the_position_is_a_scenario_error_naming_the_law():
    with pytest.raises(hc.ScenarioError) as e:
        hc.solve(tresca_with({"law": "position", "function": lambda x: 2.0 - x[:, 1]}))
    text = str(e.value)
    assert "contact[0].friction.mu (" in text and "<lambda>, part 'left')" in text, text
    assert "μ(x = [0.0, 2.25] m) = -0.25" in text and "≥ 0" in text, text


def with_compliance(p, dp, n=16):
    d = hc.paper_example(n=n).to_dict()
    for c in d["contact"]:
        del c["law"], c["c_nu"]
        c["normal"] = {"law": "compliance", "p": p, "dp": dp}
    return d


C_NU = 1e4  # the paper's c_ν (Pa/m)


def test_a_linear_python_compliance_equals_the_built_in_one():
    sizes = []

    def p(x):
        sizes.append(len(x))
        return C_NU * x

    a = hc.solve(hc.paper_example(n=16))
    b = hc.solve(with_compliance(p, lambda x: np.full_like(x, C_NU)))
    assert a.converged and b.converged
    scale = np.abs(a.displacement).max()
    assert np.abs(b.displacement - a.displacement).max() <= 1e-12 * scale
    assert np.abs(b.contact["pressure"] - a.contact["pressure"]).max() <= 1e-12 * scale * C_NU
    # Whole arrays: the penetrating points of a side (≤ 16), or 9 times as many with the
    # quadrature nodes, or the 3 × 102 validation samples; never one call per point.
    assert max(sizes) == 306 and all(s <= 9 * 16 for s in sizes if s != 306)


def test_a_block_on_a_cubic_python_foundation_sinks_by_the_closed_form_penetration():
    c, q, gap = 1e9, 50.0, 0.01
    d = {
        "mesh": {"kind": "rectangle", "size": [1.0, 1.0], "n": [6, 6]},
        "material": {"young": 1000.0, "poisson": 0.3},
        "dirichlet": [
            {"part": "left", "components": ["x"]},
            {"part": "right", "components": ["x"]},
        ],
        "loads": {"traction": [{"part": "top", "value": [0.0, -q]}]},
        "contact": [
            {
                "part": "bottom",
                "gap": gap,
                "normal": {"law": "compliance", "p": lambda x: c * x**3, "dp": lambda x: 3 * c * x**2},
            }
        ],
    }
    r = hc.solve(d)
    assert r.converged
    delta = (q / c) ** (1.0 / 3.0)  # p(δ) = q
    assert np.abs(r.contact["gap"] + delta).max() <= 1e-9 * delta
    assert np.abs(r.contact["pressure"] - q).max() <= 1e-8 * q
    back = hc.Scenario.from_dict(d).to_dict()["contact"][0]
    assert back["normal"]["p"] is d["contact"][0]["normal"]["p"] and "c_nu" not in back


@pytest.mark.parametrize(
    "p, dp, says",
    [
        (lambda x: C_NU * x + 1.0, lambda x: np.full_like(x, C_NU), "p(0)"),
        (lambda x: C_NU * np.minimum(x, 1e-3) - x, lambda x: np.full_like(x, C_NU), "monotone"),
        (lambda x: C_NU * x, lambda x: np.full_like(x, 2 * C_NU), "derivative of p"),
        (lambda x: np.where(x > 1e-3, np.nan, C_NU * x), lambda x: np.full_like(x, C_NU), "NaN"),
    ],
)
def test_a_compliance_that_is_not_monotone_and_consistent_is_a_scenario_error(p, dp, says):
    with pytest.raises(hc.ScenarioError) as e:
        hc.solve(with_compliance(p, dp, n=4))
    text = str(e.value)
    assert "contact[0].normal (<lambda>, part 'left')" in text and says in text, text


def test_an_exception_in_a_compliance_law_propagates_as_itself_naming_the_law():
    def p(x):
        if len(x) < 303:  # after validation: during the solve
            raise Boom("asperity model out of range")
        return C_NU * x

    with pytest.raises(Boom) as e:
        hc.solve(with_compliance(p, lambda x: np.full_like(x, C_NU), n=8))
    if sys.version_info >= (3, 11):
        notes = " ".join(getattr(e.value, "__notes__", []))
        assert "contact[0].normal (" in notes and ".p, part 'left')" in notes, notes


def test_normal_with_law_or_c_nu_in_the_same_entry_is_a_scenario_error():
    d = with_compliance(lambda x: C_NU * x, lambda x: np.full_like(x, C_NU), n=4)
    d["contact"][1]["c_nu"] = 5.0
    with pytest.raises(hc.ScenarioError, match=r"contact\[1\]\.c_nu"):
        hc.Scenario.from_dict(d)
    d = with_compliance(lambda x: C_NU * x, None, n=4)
    with pytest.raises(hc.ScenarioError, match=r"contact\[0\]\.normal"):
        hc.Scenario.from_dict(d)
