#!/usr/bin/env python3
"""The Hertz benchmarks under mesh refinement: contact radius (half-width in 2D), force
and peak pressure against Hertz's theory, with observed orders and run times, and the
pressure profiles with the Hertz profile overlaid.

Cases (the analytic values are computed from each scenario's data):

- ``hertz2d``: ``scenarios/hertz2d.toml``, a rigid cylinder pressed onto a block by a
  known force per unit thickness F (plane strain, frictionless): a = √(4FR/(πE*)),
  p₀ = 2F/(πa);
- ``hertz3d``: ``scenarios/hertz3d.toml``, a rigid paraboloid indenting a block by d
  (quarter model, frictionless): a = √(Rd), F = (4/3) E* √R d^{3/2}, p₀ = (2/π) E* √(d/R);
- ``hertz3d-force``: ``scenarios/hertz3d-force.toml``, a block 20 a across pushed by a
  known force F onto a flat paraboloid (a/R = 0.02; quarter model, frictionless):
  a = (3FR/(4E*))^{1/3}, p₀ = 3F/(2πa²);
- ``…-friction``: the same with Coulomb friction μ = 0.3 (no closed form: compared with
  the frictionless case and across levels).

Usage (needs the hemicontact Python package, numpy and matplotlib)::

    python scripts/hertz.py [--levels2d 32 64 128 256] [--levels3d 8 16 32]
                            [--levels3f 8 16 32] [--no-friction] [--out out/hertz]
    python scripts/hertz.py --sensitivity 38

Writes ``table.md`` (the table printed), ``pressure-2d.png``, ``pressure-3d.png`` and
``pressure-3d-force.png`` to
the output folder; with ``--sensitivity N``, ``sensitivity.md``: the 3D set-up's departure
from Hertz against the block size and the indenter radius, at N³ cells.
"""

import argparse
import math
import pathlib
import sys
import time

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

import numpy as np

import hemicontact as hc

ROOT = pathlib.Path(__file__).resolve().parent.parent


def hertz(data, dim):
    """Hertz's a, F (whole indenter) and p₀ from the scenario's data."""
    young = data["material"]["young"]
    nu = data["material"]["poisson"]
    e_star = young / (1.0 - nu * nu)
    obstacle = data["contact"][0]["obstacle"]
    radius = obstacle["radius"]
    if dim == 2:
        # Force-driven half model: the traction on the bottom over the half width, twice.
        q = data["loads"]["traction"][0]["value"][1]
        force = 2.0 * q * data["mesh"]["size"][0]
        a = math.sqrt(4.0 * force * radius / (math.pi * e_star))
        return a, force, 2.0 * force / (math.pi * a)
    if "displacement" not in obstacle:
        # Force-driven quarter model: the traction on the bottom over its area, 4 times.
        q = data["loads"]["traction"][0]["value"][2]
        size = data["mesh"]["size"]
        force = 4.0 * q * size[0] * size[1]
        a = (3.0 * force * radius / (4.0 * e_star)) ** (1.0 / 3.0)
        return a, force, 3.0 * force / (2.0 * math.pi * a * a)
    depth = -obstacle["displacement"][2]
    return (
        math.sqrt(radius * depth),
        4.0 / 3.0 * e_star * math.sqrt(radius) * depth**1.5,
        2.0 / math.pi * e_star * math.sqrt(depth / radius),
    )


def measure(result, dim):
    """The computed a, F (whole indenter), p₀, the element size at the contact edge, the
    profile (r, p) along the symmetry line, and the counts of sticking and slipping
    points."""
    c = result.contact
    on_line = np.ones(len(c["x"]), bool) if dim == 2 else c["y"] == 0.0
    r = c["x"][on_line]
    p = c["pressure"][on_line]
    order = np.argsort(r)
    r, p = r[order], p[order]
    touching = r[p > 0.0]
    a = touching.max() if touching.size else 0.0
    k = min(np.searchsorted(r, a), len(r) - 1)
    h = r[k + 1] - r[k] if k + 1 < len(r) else r[k] - r[k - 1]
    force = -(2.0 if dim == 2 else 4.0) * c["force"][:, dim - 1].sum()
    peak = p[r == 0.0][0]
    states = c["friction_state"]
    return a, force, peak, h, (r, p), (states == "stick").sum(), (states == "slip").sum()


def with_friction(data):
    data = dict(data)
    contact = dict(data["contact"][0])
    contact["friction"] = {"bound": "coulomb", "mu": 0.3}
    data["contact"] = [contact]
    return data


def run_case(name, path, levels, friction):
    data = tomllib.loads(path.read_text())
    dim = 3 if data["mesh"]["kind"] == "box" else 2
    exact = hertz(data, dim)
    if friction:
        data = with_friction(data)
    data.pop("output", None)
    base = hc.Scenario.from_dict(data, source=str(path))
    rows = []
    for n in levels:
        scenario = base.with_resolution(n)
        start = time.perf_counter()
        result = hc.solve(scenario)
        wall = time.perf_counter() - start
        if not result.converged:
            print(f"{name} n = {n}: NOT CONVERGED: {result.message}", file=sys.stderr)
        a, force, peak, h, profile, stick, slip = measure(result, dim)
        rows.append(
            {
                "case": name,
                "n": n,
                "dofs": result.summary["sizes"]["dofs"],
                "a": a,
                "h": h,
                "force": force,
                "peak": peak,
                "time": wall,
                "converged": result.converged,
                "profile": profile,
                "stick": stick,
                "slip": slip,
            }
        )
        print(
            f"  {name} n = {n}: {rows[-1]['dofs']} DOFs, a = {a:.5f}, F = {force:.6g}, "
            f"p0 = {peak:.6g}, {wall:.2f} s",
            file=sys.stderr,
        )
    return dim, exact, rows


def orders(values):
    """Observed orders of convergence from successive differences of nested levels (each
    halving the cells): log₂(|v_{k−1} − v_{k−2}| / |v_k − v_{k−1}|), blank for the first two
    levels. They measure the convergence to the discrete model's limit, whatever that
    limit's distance to Hertz."""
    out = [float("nan")] * len(values)
    for k in range(2, len(values)):
        d0, d1 = abs(values[k - 1] - values[k - 2]), abs(values[k] - values[k - 1])
        if d0 > 0 and d1 > 0:
            out[k] = math.log2(d0 / d1)
    return out


def table(dim, exact, rows):
    a0, f0, p0 = exact
    force_label = "F (N/m)" if dim == 2 else "F (N)"
    lines = [
        f"| case | n | DOFs | h at a | a | a − a_H | {force_label} | F/F_H − 1 | order F | p₀ | "
        "p₀/p₀_H − 1 | order p₀ | stick/slip | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    fmt = lambda x: "" if math.isnan(x) else f"{x:.2f}"
    applied = all(abs(r["force"] / f0 - 1.0) < 1e-6 for r in rows)
    for case in dict.fromkeys(row["case"] for row in rows):
        own = [row for row in rows if row["case"] == case]
        order_p = orders([row["peak"] for row in own])
        # A force-driven case's force is the applied load: no order.
        order_f = [float("nan")] * len(own) if applied else orders([row["force"] for row in own])
        for row, of, op in zip(own, order_f, order_p):
            lines.append(
                f"| {row['case']} | {row['n']} | {row['dofs']} | {row['h']:.4f} | "
                f"{row['a']:.4f} | {row['a'] - a0:+.4f} | {row['force']:.5g} | "
                f"{row['force'] / f0 - 1.0:+.2%} | {fmt(of)} | {row['peak']:.4f} | "
                f"{row['peak'] / p0 - 1.0:+.2%} | {fmt(op)} | {row['stick']}/{row['slip']} | "
                f"{row['time']:.2f} |"
            )
    head = (
        f"Hertz ({dim}D): a_H = {a0:.5f} m, F_H = {f0:.6g}, p₀_H = {p0:.6g} Pa"
        + (" (F is the applied load)" if applied else "")
    )
    return head + "\n\n" + "\n".join(lines) + "\n"


def figure(dim, exact, rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    a0, _, p0 = exact
    fig, ax = plt.subplots(figsize=(7.0, 4.2), dpi=110)
    r = np.linspace(0.0, a0, 400)
    ax.plot(r, p0 * np.sqrt(1.0 - (r / a0) ** 2), "k-", lw=2.0, label="Hertz")
    markers = {"": "o", "friction": "s"}
    for case in dict.fromkeys(row["case"] for row in rows):
        last = [row for row in rows if row["case"] == case][-1]
        rr, pp = last["profile"]
        keep = rr <= 1.6 * a0
        kind = "friction" if case.endswith("friction") else ""
        ax.plot(
            rr[keep],
            pp[keep],
            markers[kind] + "--",
            ms=3.5,
            lw=0.8,
            label=f"{case}, n = {last['n']} ({last['dofs']} DOFs)",
        )
    ax.set_xlabel("x (m)" if dim == 2 else "r (m), along the symmetry line y = 0")
    ax.set_ylabel("contact pressure p (Pa)")
    if dim == 2:
        title = "Hertz, 2D: rigid cylinder on a block (plane strain)"
    elif rows[0]["case"].startswith("hertz3d-force"):
        title = "Hertz, 3D: block pressed by a known force onto a rigid paraboloid"
    else:
        title = "Hertz, 3D: rigid paraboloid indenting a block"
    ax.set_title(title)
    ax.set_xlim(0.0, 1.6 * a0)
    ax.set_ylim(0.0, 1.15 * max(p0, max(row["peak"] for row in rows)))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def sensitivity(n, out):
    """The 3D set-up's departure from Hertz against the block size L (a/L) and the
    indenter radius R (a/R), at fixed a = √(Rd) = 0.1 m, on n³-cell meshes graded to a
    first cell of about 0.006 m (L = 4) or 0.01 m (L = 1)."""
    path = ROOT / "scenarios" / "hertz3d.toml"
    base = tomllib.loads(path.read_text())
    base.pop("output", None)
    lines = [
        "| L (m) | R (m) | d (m) | a/L | a/R | DOFs | h at a | a − a_H | F/F_H − 1 | "
        "p₀/p₀_H − 1 | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for size, radius, depth, ratio in ((1.0, 0.5, 0.02, 1.065), (4.0, 0.5, 0.02, 1.123),
                                       (4.0, 5.0, 0.002, 1.123)):
        data = dict(base)
        mesh = dict(base["mesh"])
        mesh.update(
            origin=[0.0, 0.0, -size],
            size=[size] * 3,
            n=[n] * 3,
            progression=[ratio, ratio, 1.0 / ratio],
        )
        data["mesh"] = mesh
        contact = dict(base["contact"][0])
        contact["obstacle"] = dict(contact["obstacle"], radius=radius,
                                   displacement=[0.0, 0.0, -depth])
        data["contact"] = [contact]
        exact = hertz(data, 3)
        start = time.perf_counter()
        result = hc.solve(hc.Scenario.from_dict(data, source=str(path)))
        wall = time.perf_counter() - start
        a, force, peak, h, _, _, _ = measure(result, 3)
        lines.append(
            f"| {size:g} | {radius:g} | {depth:g} | {exact[0] / size:.3f} | "
            f"{exact[0] / radius:.2f} | {result.summary['sizes']['dofs']} | {h:.4f} | "
            f"{a - exact[0]:+.4f} | {force / exact[1] - 1:+.2%} | {peak / exact[2] - 1:+.2%} | "
            f"{wall:.1f} |"
        )
        print(lines[-1], file=sys.stderr)
    text = "\n".join(lines) + "\n"
    (out / "sensitivity.md").write_text(text)
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--levels2d", type=int, nargs="*", default=[32, 64, 128, 256])
    parser.add_argument("--levels3d", type=int, nargs="*", default=[8, 16, 32])
    parser.add_argument(
        "--levels3f",
        type=int,
        nargs="*",
        default=[8, 16, 32],
        help="levels of the force-driven 3D case (hertz3d-force)",
    )
    parser.add_argument("--no-friction", action="store_true")
    parser.add_argument("--out", default="out/hertz")
    parser.add_argument(
        "--sensitivity",
        type=int,
        metavar="N",
        help="only the 3D set-up against block size and indenter radius, on N³ cells",
    )
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.sensitivity:
        print(sensitivity(args.sensitivity, out))
        return
    text = []
    cases = (
        (2, "hertz2d", args.levels2d),
        (3, "hertz3d", args.levels3d),
        (3, "hertz3d-force", args.levels3f),
    )
    for dim, stem, levels in cases:
        if not levels:
            continue
        path = ROOT / "scenarios" / f"{stem}.toml"
        rows = []
        exact = None
        for friction in (False,) if args.no_friction else (False, True):
            name = stem + ("-friction" if friction else "")
            _, exact, case_rows = run_case(name, path, levels, friction)
            rows += case_rows
        text.append(table(dim, exact, rows))
        figure(dim, exact, rows, out / f"pressure-{stem[len('hertz'):]}.png")
    report = "\n".join(text)
    (out / "table.md").write_text(report)
    print(report)


if __name__ == "__main__":
    main()
