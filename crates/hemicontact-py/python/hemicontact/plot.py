"""Figures of a :class:`~hemicontact.Result` and of a refinement study (needs matplotlib).

This module imports matplotlib when it is imported itself; ``import hemicontact`` does not
import it. Every function takes an optional matplotlib ``Axes`` (``ax=None`` makes a new
figure) and returns the ``Figure`` it drew on:

- :func:`deformed`: the deformed mesh of a 2D result with the undeformed outline, the
  foundations, the contact states and the interface tractions as arrows, optionally coloured
  by a cell field or the contact pressure;
- :func:`interface`: contact pressure, friction traction and friction bound against the arc
  length along each contact part, with the stick/slip/separated state as a coloured band;
- :func:`convergence`: the relative energy-norm error of a refinement study against the
  mesh size on log-log axes, with the observed orders and a reference slope.

Units are SI: lengths in m, stresses, pressures and tractions in Pa (in 2D the tractions are
forces per unit thickness and per unit boundary length, N/m², i.e. Pa).
"""

import math
import textwrap
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter

#: Cell fields :func:`deformed` can colour by: attribute, colorbar label (with unit).
CELL_FIELDS: Dict[str, str] = {
    "von_mises": "von Mises stress (Pa)",
    "trace_strain": "volumetric strain tr ε (–)",
    "locking_multiplier": "locking multiplier (Pa)",
}
#: The nodal field :func:`deformed` can colour the contact points by, and its label.
POINT_FIELDS: Dict[str, str] = {"pressure": "contact pressure p (Pa)"}

#: Default largest number of traction arrows per contact part in :func:`deformed`.
MAX_ARROWS = 24

#: Colours of the contact states (markers in :func:`deformed`, band in :func:`interface`).
STATE_COLORS: Dict[str, str] = {
    "separated": "#b8b8b8",
    "contact": "#2ca02c",
    "stick": "#1f5fd6",
    "slip": "#d62728",
}
STATE_LABELS: Dict[str, str] = {
    "separated": "separated",
    "contact": "contact, no friction",
    "stick": "stick",
    "slip": "slip",
}
_PREFIXES = [(1e9, "GPa"), (1e6, "MPa"), (1e3, "kPa"), (1.0, "Pa")]
_FOUNDATION_COLORS = ["#5b3a1a", "#6a3d9a", "#1b7837", "#b35806"]


def _axes(ax: Any, figsize: Tuple[float, float]) -> Tuple[Any, Any]:
    if ax is None:
        fig, ax = plt.subplots(figsize=figsize, layout="constrained")
        return fig, ax
    return ax.figure, ax


def _colorbar(fig: Any, ax: Any, mappable: Any, label: str) -> Any:
    """A colorbar as tall as the drawn (equal-aspect) axes box, just right of it."""
    cax = ax.inset_axes([1.03, 0.0, 0.035, 1.0])
    return fig.colorbar(mappable, cax=cax, label=label)


def _wrap(title: str, width: int = 44) -> str:
    return "\n".join(textwrap.wrap(title, width)) if title else ""


def _require_2d(result: Any, what: str) -> None:
    if result.dim != 2:
        raise ValueError(
            f"{what}: result.dim = {result.dim}: only 2D results are drawn (write a 3D "
            "result with Result.write or Result.to_meshio and view it in ParaView)"
        )


def _boundary_edges(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """The boundary edges of a triangulation (edges of exactly one triangle), each oriented
    with the body on its left, so that its outward normal is (dy, −dx)/length."""
    p = points
    a, b, c = cells[:, 0], cells[:, 1], cells[:, 2]
    area2 = (p[b, 0] - p[a, 0]) * (p[c, 1] - p[a, 1]) - (p[b, 1] - p[a, 1]) * (p[c, 0] - p[a, 0])
    ccw = np.where(area2[:, None] >= 0, cells, cells[:, [0, 2, 1]])
    edges = np.concatenate([ccw[:, [0, 1]], ccw[:, [1, 2]], ccw[:, [2, 0]]])
    key = np.sort(edges, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return edges[counts[inverse.ravel()] == 1]


class _Part:
    """One contact part's points in order along its boundary: ``index`` into the contact
    table, ``s`` the arc length (m) from the first point, ``chain`` the node chain of the
    part's boundary (the contact nodes plus, at each end, a collinear boundary edge to a
    node that is not a contact point, e.g. a corner on a support)."""

    def __init__(self, name: str, index: np.ndarray, s: np.ndarray, chain: List[int]) -> None:
        self.name = name
        self.index = index
        self.s = s
        self.chain = chain


def _parts(result: Any) -> List[_Part]:
    """The contact parts of a 2D result, in the order of the contact table, each sorted
    along its boundary. A part's points are walked along the boundary edges of the mesh and
    read from the end with the smaller y (then the smaller x): vertical sides bottom to top,
    horizontal ones left to right."""
    c = result.contact
    names = list(dict.fromkeys(c["boundary"].tolist()))
    edges = _boundary_edges(result.points, result.cells)
    pts = result.points
    # Start key: y, then x, with y compared to 1e-9 of the mesh's extent (round-off ties).
    tol = 1e-9 * float(np.ptp(pts, axis=0).max())

    def first(n: int) -> Tuple[float, float]:
        return (round(pts[n, 1] / tol) if tol > 0 else pts[n, 1], pts[n, 0])

    out = []
    for name in names:
        rows = np.flatnonzero(c["boundary"] == name)
        nodes = c["node"][rows]
        row_of = {int(n): int(r) for n, r in zip(nodes, rows)}
        inside = np.isin(edges, nodes)
        neighbours: Dict[int, List[int]] = {int(n): [] for n in nodes}
        for a, b in edges[inside.all(axis=1)]:
            neighbours[int(a)].append(int(b))
            neighbours[int(b)].append(int(a))
        left = set(row_of)
        chains: List[List[int]] = []
        while left:
            ends = [n for n in left if len([m for m in neighbours[n] if m in left]) <= 1]
            pool = ends or sorted(left)
            start = min(pool, key=first)
            chain = [start]
            left.discard(start)
            while True:
                nxt = [m for m in neighbours[chain[-1]] if m in left]
                if not nxt:
                    break
                chain.append(nxt[0])
                left.discard(nxt[0])
            chains.append(chain)
        chains.sort(key=lambda ch: first(ch[0]))
        order = [n for ch in chains for n in ch]
        xy = pts[order]
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
        chain = _extend(order, edges, pts, c, row_of)
        out.append(_Part(name, np.array([row_of[n] for n in order]), s, chain))
    return out


def _extend(order: List[int], edges: np.ndarray, pts: np.ndarray, c: Dict[str, np.ndarray],
            row_of: Dict[int, int]) -> List[int]:
    """Prepends/appends to the node chain ``order`` the boundary edge at each end that leads
    to a node which is not a contact point and is collinear with the part (its outward
    normal equals the end point's normal), so the foundation spans the whole side."""
    contact_nodes = set(c["node"].tolist())
    chain = list(order)
    for at_end in (False, True):
        end = chain[-1] if at_end else chain[0]
        normal = c["normal"][row_of[end], :2]
        for a, b in edges:
            other = b if a == end else a if b == end else None
            if other is None or int(other) in contact_nodes:
                continue
            d = pts[b] - pts[a]
            edge_normal = np.array([d[1], -d[0]]) / np.linalg.norm(d)
            if edge_normal @ normal > 1.0 - 1e-9:
                if at_end:
                    chain.append(int(other))
                else:
                    chain.insert(0, int(other))
                break
    return chain


def _initial_gap(result: Any) -> np.ndarray:
    """The initial gap g (m) of each contact point: the current gap g − u_ν plus u_ν."""
    return result.contact["gap"] + result.contact["u_nu"]


def _nice(x: float) -> float:
    """The 1-2-5 number nearest below ``x`` > 0."""
    e = math.floor(math.log10(x))
    for m in (5.0, 2.0, 1.0):
        if m * 10**e <= x:
            return m * 10**e
    return 10**e


def _fmt(x: float) -> str:
    return f"{x:g}" if 1e-3 <= abs(x) < 1e5 else f"{x:.0e}"


def deformed(
    result: Any,
    field: Optional[str] = None,
    scale: float = 1.0,
    forces: bool = True,
    ax: Any = None,
    *,
    max_arrows: int = MAX_ARROWS,
    title: Optional[str] = None,
    legend: bool = True,
) -> Any:
    """The deformed mesh of a 2D ``result`` (the paper's Fig. 2/3 view); returns the Figure.

    Drawn in m, equal scales: the deformed triangles at positions x + ``scale`` · u (the
    magnification is stated in the title), the undeformed outline (dashed), the foundations
    of the contact parts (thick lines named in the legend: each part's boundary shifted by
    its initial gap g = (g − u_ν) + u_ν along the outward normal ν), the contact points
    coloured by state (separated, stick, slip) and, if ``forces``, the interface tractions
    R_i / w_i (Pa: the interface force on node i, N/m per unit thickness, divided by the
    node's share w_i of the boundary length, m) as arrows at the deformed contact points, to
    the scale of the reference arrow drawn in the axes' top right corner. At most
    ``max_arrows`` arrows are drawn per contact part (every k-th point along the part) so
    that they stay apart on fine meshes.

    ``field`` colours the cells by ``"von_mises"`` (Pa), ``"trace_strain"`` (–) or
    ``"locking_multiplier"`` (Pa), or the contact points by ``"pressure"`` (Pa), with a
    colorbar. A result without contact parts says so in the title. ``title`` replaces the
    result's title; ``legend=False`` leaves the legend out (e.g. on all but one panel).

    Raises ``ValueError`` for a 3D result, an unknown field, a scale that is not a finite
    number ≥ 0, or ``max_arrows`` < 1.
    """
    _require_2d(result, "deformed")
    if field is not None and field not in CELL_FIELDS and field not in POINT_FIELDS:
        allowed = ", ".join(repr(f) for f in [*CELL_FIELDS, *POINT_FIELDS])
        raise ValueError(f"deformed: field = {field!r}: one of None, {allowed}")
    if isinstance(scale, bool) or not isinstance(scale, (int, float)) or not (
        math.isfinite(scale) and scale >= 0
    ):
        raise ValueError(f"deformed: scale = {scale!r}: a finite number ≥ 0")
    if isinstance(max_arrows, bool) or not isinstance(max_arrows, int) or max_arrows < 1:
        raise ValueError(f"deformed: max_arrows = {max_arrows!r}: an integer ≥ 1")
    X = result.points
    cells = result.cells
    # Nodes no cell uses (dropped by Mesh.from_arrays, NaN displacement) are not drawn.
    used = np.unique(cells)
    P = X + scale * np.nan_to_num(result.displacement)
    c = result.contact
    handles: List[Any] = []
    parts = _parts(result) if len(c["node"]) else []
    gap0 = _initial_gap(result) if parts else np.zeros(0)

    # Axis limits (m): body, deformed body and foundations, with an empty strip on top for
    # the reference arrow; a new figure gets the height that fits them.
    lo = np.minimum(X[used].min(axis=0), P[used].min(axis=0))
    hi = np.maximum(X[used].max(axis=0), P[used].max(axis=0))
    for part in parts:
        q = X[c["node"][part.index]] + gap0[part.index, None] * c["normal"][part.index, :2]
        lo, hi = np.minimum(lo, q.min(axis=0)), np.maximum(hi, q.max(axis=0))
    size = float(max(hi - lo))
    pad = 0.06 * size
    xlim = (lo[0] - pad, hi[0] + pad)
    ylim = (lo[1] - pad, hi[1] + 0.16 * size)
    tall = (ylim[1] - ylim[0]) / (xlim[1] - xlim[0])
    fig, ax = _axes(ax, (6.4, min(10.0, max(3.5, 4.8 * tall + 2.1))))

    # Cells: coloured by a field, else light; the mesh lines thinner on fine meshes.
    lw = 0.5 if len(cells) <= 2000 else 0.25 if len(cells) <= 10000 else 0.0
    if field in CELL_FIELDS:
        values = getattr(result, field)
        mappable = ax.tripcolor(P[:, 0], P[:, 1], cells, facecolors=values, cmap="viridis",
                                edgecolors="none", rasterized=True)
        _colorbar(fig, ax, mappable, CELL_FIELDS[field])
        if lw > 0:
            ax.triplot(P[:, 0], P[:, 1], cells, color="white", lw=lw * 0.6, alpha=0.35)
    else:
        ax.tripcolor(P[:, 0], P[:, 1], cells, np.zeros(len(cells)), cmap="Greys", vmin=0,
                     vmax=8, edgecolors="none", rasterized=True)
        if lw > 0:
            ax.triplot(P[:, 0], P[:, 1], cells, color="#7f8fb0", lw=lw)
    edges = _boundary_edges(X, cells)
    segs_x = np.stack([X[edges[:, 0]], X[edges[:, 1]], np.full((len(edges), 2), np.nan)], 1)
    segs_p = np.stack([P[edges[:, 0]], P[edges[:, 1]], np.full((len(edges), 2), np.nan)], 1)
    h_und, = ax.plot(*segs_x.reshape(-1, 2).T, "--", color="0.45", lw=1.0, label="undeformed")
    h_def, = ax.plot(*segs_p.reshape(-1, 2).T, "-", color="0.1", lw=1.2, label="deformed")
    handles += [h_und, h_def]

    for k, part in enumerate(parts):
        # Foundation: the part's chain shifted by g along the node normals; the end nodes
        # added by _extend take their neighbour's normal and gap.
        core = list(c["node"][part.index])
        pad_front = part.chain[: part.chain.index(core[0])]
        pad_back = part.chain[part.chain.index(core[-1]) + 1 :]
        rows = [part.index[0]] * len(pad_front) + list(part.index) + [part.index[-1]] * len(pad_back)
        xy = X[part.chain] + gap0[rows, None] * c["normal"][rows, :2]
        g = float(np.median(gap0[part.index]))
        h, = ax.plot(xy[:, 0], xy[:, 1], "-", color=_FOUNDATION_COLORS[k % 4], lw=3.0,
                     solid_capstyle="butt", label=f"foundation of {part.name} (gap {g:.3g} m)")
        handles.append(h)

    if parts:
        state = np.where(c["normal_state"] == "separated", "separated", c["friction_state"])
        state = np.where(state == "none", "contact", state)
        pc = P[c["node"]]
        if field in POINT_FIELDS:
            sc = ax.scatter(pc[:, 0], pc[:, 1], c=c[field], s=22, cmap="plasma", zorder=4,
                            edgecolors="k", linewidths=0.3)
            _colorbar(fig, ax, sc, POINT_FIELDS[field])
        else:
            for st in ("separated", "contact", "stick", "slip"):
                on = state == st
                if on.any():
                    h = ax.scatter(pc[on, 0], pc[on, 1], s=10, color=STATE_COLORS[st],
                                   zorder=4, label=STATE_LABELS[st], linewidths=0)
                    handles.append(h)

    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal")

    # Green arrows on the plain mesh, black (white-edged) ones over a coloured field.
    arrow = "k" if field in CELL_FIELDS else "#008c3c"
    if parts and forces:
        traction = c["force"][:, :2] / c["weight"][:, None]
        mag = np.linalg.norm(traction, axis=1)
        # Tractions below 1e-9 of the body's largest stress are round-off of equilibrium
        # (the force of a separated point is zero by the contact law): not drawn.
        floor = 1e-9 * max(float(np.abs(result.stress).max()), float(mag.max()), 1e-300)
        top = float(mag.max()) if len(mag) else 0.0
        if top <= floor:
            handles.append(Line2D([], [], color=arrow, lw=2,
                                  label="interface traction: zero (no contact)"))
        else:
            chosen = []
            for part in parts:
                step = max(1, math.ceil(len(part.index) / max_arrows))
                chosen.extend(part.index[::step])
            chosen = np.array([i for i in chosen if mag[i] > floor], dtype=int)
            ref = _nice(top)
            length = 0.12 * size  # the longest arrow, m
            per_m = top / length  # Pa per m of arrow
            quiver = ax.quiver(P[c["node"][chosen], 0], P[c["node"][chosen], 1],
                               traction[chosen, 0], traction[chosen, 1], angles="xy",
                               scale_units="xy", scale=per_m, color=arrow, width=0.004,
                               edgecolor="white" if field in CELL_FIELDS else arrow,
                               linewidth=0.4, zorder=5, label="interface traction")
            ax.quiverkey(quiver, 0.80, 0.95, ref, f"{_fmt(ref)} Pa", labelpos="W",
                         coordinates="axes", fontproperties={"size": 9})
            handles.append(Line2D([], [], color=arrow, lw=2,
                                  label=f"interface traction R/w ({len(chosen)} arrows)"))

    head = title if title is not None else result.title
    lines = [_wrap(head)]
    extra = f"displacements × {scale:g}"
    if not len(c["node"]):
        extra += "; no contact parts"
    lines.append(extra)
    ax.set_title("\n".join(lines), fontsize=11)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if legend:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.11), ncol=2,
                  fontsize=8.5, frameon=False, columnspacing=1.2, handlelength=1.8)
    return fig


def _states(result: Any, rows: np.ndarray) -> np.ndarray:
    c = result.contact
    st = np.where(c["friction_state"][rows] == "none", "contact", c["friction_state"][rows])
    return np.where(c["normal_state"][rows] == "separated", "separated", st)


def interface(result: Any, part: Optional[str] = None, ax: Any = None) -> Any:
    """The contact quantities along each contact part of a 2D ``result`` (the paper's
    Fig. 2 as curves); returns the Figure.

    One panel per contact part (side by side), or only ``part``: the contact pressure p
    (Pa), the magnitude of the friction traction ‖σ_τ‖ (Pa, recovered from equilibrium)
    and the friction bound F (Pa) against the arc length s (m) along the part, measured
    from the part's first point (the end with the smaller y, then the smaller x; the axis
    label gives its coordinates). A band above each panel shows the state of each contact
    point: separated, contact without friction, stick or slip.

    ``ax`` draws one part (``part``, or the result's only part) into an existing axes.
    Raises ``ValueError`` for a 3D result, a result without contact, an unknown ``part``,
    or ``ax`` with several parts and no ``part``.
    """
    _require_2d(result, "interface")
    parts = _parts(result) if len(result.contact["node"]) else []
    if not parts:
        raise ValueError(f"interface: the result {result.title!r} has no contact points")
    names = [p.name for p in parts]
    if part is not None:
        if part not in names:
            raise ValueError(f"interface: part = {part!r}: one of {', '.join(map(repr, names))}")
        parts = [p for p in parts if p.name == part]
    if ax is not None and len(parts) > 1:
        raise ValueError(
            f"interface: ax given but the result has {len(parts)} contact parts "
            f"({', '.join(map(repr, names))}): choose one with part="
        )
    if ax is None:
        fig, axes = plt.subplots(1, len(parts), figsize=(5.2 * len(parts), 4.6),
                                 layout="constrained", squeeze=False, sharey=True)
        axes = list(axes[0])
        fig.suptitle(_wrap(result.title, 80), fontsize=11)
    else:
        fig, axes = ax.figure, [ax]
    c = result.contact
    # Tractions below 1e-9 of the body's largest stress are round-off of equilibrium.
    floor = 1e-9 * max(float(np.abs(result.stress).max()), 1e-300)
    for a, p in zip(axes, parts):
        rows = p.index
        s = p.s
        ft = np.linalg.norm(c["friction_traction"][rows], axis=1)
        a.plot(s, c["pressure"][rows], "-o", ms=2.5, lw=1.4, color="k",
               label="contact pressure p")
        a.plot(s, ft, "-", lw=2.4, color="#1f77b4", label="friction traction ‖σ_τ‖")
        a.plot(s, c["bound"][rows], "--", lw=1.4, color="#ff7f0e", label="friction bound F",
               dashes=(4, 3))
        a.set_xlim(s[0], s[-1] if s[-1] > s[0] else s[0] + 1.0)
        top = max(float(c["pressure"][rows].max()), float(c["bound"][rows].max()), float(ft.max()))
        if top <= floor:
            # Round-off only (every point separated): a unit range, and say so.
            top = 1.0
            a.text(0.5, 0.5, "no interface traction (every point separated)",
                   transform=a.transAxes, ha="center", va="center", fontsize=9, color="0.3")
        a.set_ylim(0.0, 1.08 * top)
        # Tick labels in Pa, kPa, MPa or GPa (the data stay in Pa): no exponent label,
        # which the state band would hide.
        factor, unit = next((f, u) for f, u in _PREFIXES if top >= f or f == 1.0)
        a.yaxis.set_major_formatter(FuncFormatter(lambda v, _, f=factor: f"{v / f:g}"))
        x0, y0 = result.points[c["node"][rows[0]]]
        a.set_xlabel(f"arc length s along {p.name} from ({x0:.3g}, {y0:.3g}) (m)")
        a.set_ylabel(f"traction ({unit})")
        a.grid(alpha=0.3)
        # State band above the panel: one span per point, halfway to its neighbours.
        band = a.inset_axes([0.0, 1.015, 1.0, 0.06], sharex=a)
        mid = (s[1:] + s[:-1]) / 2
        left = np.concatenate([[s[0]], mid])
        right = np.concatenate([mid, [s[-1]]])
        states = _states(result, rows)
        for st in ("separated", "contact", "stick", "slip"):
            on = states == st
            band.broken_barh(list(zip(left[on], (right - left)[on])), (0, 1),
                             color=STATE_COLORS[st])
        band.set_ylim(0, 1)
        band.set_yticks([])
        band.tick_params(axis="x", labelbottom=False, bottom=False)
        for side in band.spines.values():
            side.set_linewidth(0.5)
        a.set_title(f"contact part {p.name}", fontsize=10, pad=24)
        seen = [st for st in ("separated", "contact", "stick", "slip") if (states == st).any()]
        handles = a.get_legend_handles_labels()[0] + [
            Patch(color=STATE_COLORS[st], label=f"state: {STATE_LABELS[st]}") for st in seen
        ]
        a.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2,
                 fontsize=8.5, frameon=False)
    return fig


def convergence(levels: Sequence[Dict[str, Any]], ax: Any = None, h: str = "edge", *,
                title: Optional[str] = None) -> Any:
    """The relative energy-norm error of a refinement study (the rows of
    :func:`hemicontact.convergence`) against the mesh size on log-log axes; returns the
    Figure.

    ``h="edge"`` plots against the edge length h (m, ``h_edge``), ``h="area"`` against the
    element measure (m², ``h_area``). Each segment between consecutive levels is labelled
    with the observed order of its finer level (``order_edge`` or ``order_area``, two
    decimals), placed alternately below and above the segment; a dashed line of the
    expected order of P1 elements in the energy norm (1 in h, ½ in the element measure)
    is drawn through the coarsest point for reference.

    Raises ``ValueError`` for ``h`` other than "edge"/"area", fewer than one row, or an
    error that is not a positive finite number.
    """
    if h not in ("edge", "area"):
        raise ValueError(f"convergence: h = {h!r}: 'edge' or 'area'")
    rows = list(levels)
    if not rows:
        raise ValueError("convergence: levels = []: at least one row of a refinement study")
    key, order_key = ("h_edge", "order_edge") if h == "edge" else ("h_area", "order_area")
    x = np.array([float(r[key]) for r in rows])
    err = np.array([float(r["error"]) if r["error"] is not None else math.nan for r in rows])
    for r, e in zip(rows, err):
        if not (math.isfinite(e) and e > 0):
            raise ValueError(f"convergence: the row n = {r.get('n')}: error = {r['error']!r}: "
                             "a positive finite number (log axes)")
    fig, ax = _axes(ax, (6.0, 4.8))
    ax.loglog(x, err, "o-", color="k", lw=1.5, ms=5, label="relative energy-norm error")
    expected = 1.0 if h == "edge" else 0.5
    if len(x) > 1:
        xr = np.array([x.min(), x.max()])
        yr = err[np.argmax(x)] * 0.6 * (xr / x.max()) ** expected
        ax.loglog(xr, yr, "--", color="0.5", lw=1.2,
                  label=f"reference slope {expected:g} (P1, energy norm)")
    for i in range(1, len(rows)):
        order = rows[i][order_key]
        if order is None:
            continue
        xm = math.sqrt(x[i] * x[i - 1])
        ym = math.sqrt(err[i] * err[i - 1])
        below = i % 2 == 1
        ax.annotate(f"{order:.2f}", (xm, ym), xytext=(8 if below else -8, -12 if below else 12),
                    textcoords="offset points", ha="left" if below else "right",
                    va="top" if below else "bottom", fontsize=9, color="#1f4e9c",
                    gid="order")
    ax.set_xlabel("edge length h (m)" if h == "edge" else "element measure |T| (m²)")
    ax.set_ylabel("relative energy-norm error")
    ax.grid(which="both", alpha=0.25)
    ax.set_title(title if title is not None else "refinement study (labels: observed order)",
                 fontsize=11)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=1, fontsize=9,
              frameon=False)
    lo, hi = x.min(), x.max()
    ax.set_xlim(lo / 1.5, hi * 1.5)
    # The levels' own sizes as tick labels (log minor labels collide).
    ax.xaxis.set_major_locator(FixedLocator(sorted(set(x.tolist()))))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())
    return fig
