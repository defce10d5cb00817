"""The figures of hemicontact.plot: axes labels with units, the artists each figure promises
(colorbar, foundations at the known gap, a capped number of arrows, the state band, the
orders of a refinement study), bad input as ValueError, no matplotlib at import time, and
the example script as a smoke test. Everything renders with the Agg backend (no display)."""

import math
import pathlib
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.quiver import Quiver, QuiverKey  # noqa: E402

import hemicontact as hc  # noqa: E402
from hemicontact import plot  # noqa: E402

from conftest import REPO  # noqa: E402

# The paper's example: the square (0, 4)², sides `left` (x = 0) and `right` (x = 4) in
# contact with foundations at the initial gap 0.4 m; the bottom is clamped.
SIDE, GAP = 4.0, 0.4


@pytest.fixture(scope="module")
def paper16():
    return hc.solve(hc.paper_example(n=16))


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _colorbars(fig):
    axes = [a for ax in fig.axes for a in [ax, *ax.child_axes]]
    return [ax._colorbar for ax in axes if getattr(ax, "_colorbar", None) is not None]


def _legend_texts(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_importing_the_package_does_not_import_matplotlib():
    code = "import sys, hemicontact; assert 'matplotlib' not in sys.modules, 'imported'"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_deformed_has_labelled_axes_a_colorbar_with_unit_and_the_magnification(paper16):
    fig = plot.deformed(paper16, field="von_mises", scale=2.0)
    assert isinstance(fig, matplotlib.figure.Figure)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "y (m)"
    assert "displacements × 2" in ax.get_title()
    bars = _colorbars(fig)
    assert len(bars) == 1 and bars[0].ax.get_ylabel() == "von Mises stress (Pa)"
    # The colour range is the field's range.
    lo, hi = bars[0].mappable.get_clim()
    assert (lo, hi) == (paper16.von_mises.min(), paper16.von_mises.max())


@pytest.mark.parametrize(
    "field, label",
    [("trace_strain", "volumetric strain tr ε (–)"), ("locking_multiplier", "locking multiplier (Pa)"),
     ("pressure", "contact pressure p (Pa)")],
)
def test_every_field_gets_a_colorbar_with_its_unit(paper16, field, label):
    fig = plot.deformed(paper16, field=field)
    assert [b.ax.get_ylabel() for b in _colorbars(fig)] == [label]


def test_no_field_no_colorbar(paper16):
    assert _colorbars(plot.deformed(paper16)) == []


def test_foundations_lie_at_the_gap_along_the_outward_normals_over_the_whole_side(paper16):
    ax = plot.deformed(paper16).axes[0]
    texts = _legend_texts(ax)
    assert "foundation of left (gap 0.4 m)" in texts and "foundation of right (gap 0.4 m)" in texts
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    for name, x in (("left", -GAP), ("right", SIDE + GAP)):
        ln = lines[f"foundation of {name} (gap 0.4 m)"]
        assert np.allclose(ln.get_xdata(), x, rtol=0, atol=1e-12)
        # From the clamped corner (no contact point, reached by the collinear edge) to the top.
        y = np.asarray(ln.get_ydata())
        assert math.isclose(y.min(), 0.0, abs_tol=1e-12) and math.isclose(y.max(), SIDE)
        assert np.all(np.diff(y) > 0)


def test_arrows_are_capped_per_part_and_show_the_tractions(paper16):
    fine = hc.solve(hc.paper_example(n=128))
    for cap in (5, plot.MAX_ARROWS):
        ax = plot.deformed(fine, max_arrows=cap).axes[0]
        quivers = [c for c in ax.collections if isinstance(c, Quiver)]
        assert len(quivers) == 1
        n = quivers[0].N
        # 128 contact points per side, two sides: every k-th point with k = ceil(128 / cap).
        assert 2 <= n <= 2 * cap
        assert any(isinstance(a, QuiverKey) and a.text.get_text().endswith(" Pa") for a in ax.artists)
    # The arrows are the interface forces divided by the nodes' weights, at the deformed nodes.
    ax = plot.deformed(paper16, scale=1.0).axes[0]
    q = next(c for c in ax.collections if isinstance(c, Quiver))
    c = paper16.contact
    at = paper16.points[c["node"]] + paper16.displacement[c["node"]]
    for (x, y), u, v in zip(q.get_offsets(), q.U, q.V):
        i = int(np.argmin(np.hypot(at[:, 0] - x, at[:, 1] - y)))
        assert np.allclose([u, v], c["force"][i, :2] / c["weight"][i], rtol=1e-12)
        assert c["normal_state"][i] == "contact"


def test_a_result_without_contact_says_so_and_draws_no_arrows():
    r = hc.solve({
        "mesh": {"kind": "rectangle", "size": [2.0, 1.0], "n": [8, 4]},
        "material": {"young": 1000.0, "poisson": 0.3},
        "dirichlet": [{"part": "left"}],
        "loads": {"traction": [{"part": "right", "value": [0.0, -10.0]}]},
    })
    ax = plot.deformed(r).axes[0]
    assert "no contact parts" in ax.get_title()
    assert not [c for c in ax.collections if isinstance(c, Quiver)]
    with pytest.raises(ValueError, match="no contact points"):
        plot.interface(r)


def test_bad_input_is_a_value_error_naming_the_argument(paper16):
    with pytest.raises(ValueError, match="field = 'stress'"):
        plot.deformed(paper16, field="stress")
    with pytest.raises(ValueError, match="scale = -1"):
        plot.deformed(paper16, scale=-1.0)
    with pytest.raises(ValueError, match="max_arrows = 0"):
        plot.deformed(paper16, max_arrows=0)
    three_d = hc.solve(hc.load(REPO / "scenarios" / "paper3d.toml").with_resolution(4))
    assert three_d.dim == 3
    for f in (plot.deformed, plot.interface):
        with pytest.raises(ValueError, match="result.dim = 3"):
            f(three_d)
    with pytest.raises(ValueError, match="part = 'top'"):
        plot.interface(paper16, part="top")
    _, ax = plt.subplots()
    with pytest.raises(ValueError, match="2 contact parts"):
        plot.interface(paper16, ax=ax)


def test_interface_curves_run_along_each_side_with_the_state_band(paper16):
    fig = plot.interface(paper16)
    c = paper16.contact
    h = SIDE / 16
    panels = [ax for ax in fig.axes if ax.get_ylabel().startswith("traction (")]
    assert len(panels) == 2
    for ax, name, x0 in zip(panels, ("left", "right"), (0.0, SIDE)):
        # The clamped corner is no contact point: the side's points run from y = h to y = 4.
        assert ax.get_xlabel() == f"arc length s along {name} from ({x0:.3g}, {h:.3g}) (m)"
        lines = {ln.get_label(): ln for ln in ax.get_lines()}
        rows = np.flatnonzero(c["boundary"] == name)
        rows = rows[np.argsort(c["y"][rows])]
        s = lines["contact pressure p"].get_xdata()
        assert np.allclose(s, c["y"][rows] - h, rtol=0, atol=1e-12)
        assert math.isclose(s[-1], SIDE - h)
        assert np.array_equal(lines["contact pressure p"].get_ydata(), c["pressure"][rows])
        assert np.array_equal(lines["friction bound F"].get_ydata(), c["bound"][rows])
        ft = np.linalg.norm(c["friction_traction"][rows], axis=1)
        assert np.array_equal(lines["friction traction ‖σ_τ‖"].get_ydata(), ft)
        texts = _legend_texts(ax)
        states = set(np.where(c["normal_state"][rows] == "separated", "separated",
                              c["friction_state"][rows]))
        for st in states:
            assert f"state: {plot.STATE_LABELS.get(st, st)}" in texts
    # One band (an inset axes above each panel) with one coloured span per contact point.
    bands = [child for ax in panels for child in ax.child_axes]
    assert len(bands) == 2
    for band in bands:
        spans = sum(len(col.get_paths()) for col in band.collections)
        assert spans == 16


def test_interface_draws_one_part_into_a_given_axes(paper16):
    fig, ax = plt.subplots()
    assert plot.interface(paper16, part="right", ax=ax) is fig
    assert "along right" in ax.get_xlabel()


def _rows(errors, hs):
    rows = []
    for i, (e, h) in enumerate(zip(errors, hs)):
        order = None if i == 0 else math.log(errors[i - 1] / e) / math.log(hs[i - 1] / h)
        rows.append({"n": 4 * 2**i, "h_edge": h, "h_area": h * h / 2, "error": e,
                     "order_edge": order, "order_area": None if order is None else order / 2})
    return rows


def test_convergence_annotates_the_orders_of_the_rows_without_overlap():
    study = hc.convergence(hc.paper_example(n=4), [4, 8, 16], 32)
    fig = plot.convergence(study)
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert ax.get_xlabel() == "edge length h (m)"
    assert ax.get_ylabel() == "relative energy-norm error"
    notes = [t for t in ax.texts if t.get_gid() == "order"]
    assert [t.get_text() for t in notes] == [f"{r['order_edge']:.2f}" for r in study[1:]]
    fig.canvas.draw()
    boxes = [t.get_window_extent() for t in notes]
    assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:])


@pytest.mark.parametrize("h, slope, unit", [("edge", 1.0, "(m)"), ("area", 0.5, "(m²)")])
def test_convergence_reference_slope_is_that_of_p1_elements(h, slope, unit):
    rows = _rows([0.2, 0.11, 0.06, 0.031], [0.5, 0.25, 0.125, 0.0625])
    ax = plot.convergence(rows, h=h).axes[0]
    assert ax.get_xlabel().endswith(unit)
    ref = next(ln for ln in ax.get_lines() if ln.get_label().startswith("reference slope"))
    x, y = np.log(ref.get_xdata()), np.log(ref.get_ydata())
    assert math.isclose((y[1] - y[0]) / (x[1] - x[0]), slope, rel_tol=1e-12)
    key = "order_edge" if h == "edge" else "order_area"
    notes = [t.get_text() for t in ax.texts if t.get_gid() == "order"]
    assert notes == [f"{r[key]:.2f}" for r in rows[1:]]


def test_convergence_rejects_bad_rows():
    with pytest.raises(ValueError, match="h = 'volume'"):
        plot.convergence(_rows([0.2, 0.1], [0.5, 0.25]), h="volume")
    with pytest.raises(ValueError, match="error = 0.0"):
        plot.convergence([{"n": 4, "h_edge": 1.0, "h_area": 0.5, "error": 0.0,
                           "order_edge": None, "order_area": None}])
    with pytest.raises(ValueError, match="levels = \\[\\]"):
        plot.convergence([])


def test_the_example_script_writes_its_figures(tmp_path):
    script = REPO / "examples" / "python" / "paper.py"
    out = tmp_path / "figs"
    run = subprocess.run(
        [sys.executable, str(script), "--n", "8", "--out", str(out), "--levels", "4,8",
         "--reference", "16"],
        capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 0, run.stderr
    names = ["deformed.png", "interface-ckappa1e4.png", "interface-ckappa0.png", "convergence.png"]
    for name in names:
        path = out / name
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", path
        assert str(path) in run.stdout
    # The study's table: one line per level.
    assert pathlib.Path(out).is_dir() and run.stdout.count("\n     4 ") == 1
