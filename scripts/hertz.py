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
- ``…-friction``: the same with Coulomb friction μ = 0.3 (no closed form: compared with
  the frictionless case and across levels).

Usage (needs the hemicontact Python package, numpy and matplotlib)::

    python scripts/hertz.py [--levels2d 32 64 128 256] [--levels3d 8 16 32]
                            [--no-friction] [--out out/hertz]

Writes ``table.md`` (the table printed), ``pressure-2d.png`` and ``pressure-3d.png`` to
the output folder.
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


def order(e0, e1, h0, h1):
    if e0 <= 0 or e1 <= 0 or h0 == h1:
        return float("nan")
    return math.log(e0 / e1) / math.log(h0 / h1)


def table(dim, exact, rows):
    a0, f0, p0 = exact
    force_label = "F (N/m)" if dim == 2 else "F (N)"
    lines = [
        f"| case | n | DOFs | h at a | a | a − a_H | {force_label} | F/F_H − 1 | p₀ | "
        "p₀/p₀_H − 1 | order p₀ | stick/slip | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    previous = None
    for row in rows:
        ep = abs(row["peak"] / p0 - 1.0)
        o = (
            order(previous[0], ep, previous[1], row["h"])
            if previous is not None and previous[2] == row["case"]
            else float("nan")
        )
        previous = (ep, row["h"], row["case"])
        lines.append(
            f"| {row['case']} | {row['n']} | {row['dofs']} | {row['h']:.4f} | "
            f"{row['a']:.4f} | {row['a'] - a0:+.4f} | {row['force']:.5g} | "
            f"{row['force'] / f0 - 1.0:+.2%} | {row['peak']:.4f} | "
            f"{row['peak'] / p0 - 1.0:+.2%} | "
            f"{'' if math.isnan(o) else f'{o:.2f}'} | {row['stick']}/{row['slip']} | "
            f"{row['time']:.2f} |"
        )
    head = (
        f"Hertz ({dim}D): a_H = {a0:.5f} m, F_H = {f0:.6g}, p₀_H = {p0:.6g} Pa"
        + (" (F is the applied load)" if dim == 2 else "")
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
    ax.set_title(
        "Hertz, 2D: rigid cylinder on a block (plane strain)"
        if dim == 2
        else "Hertz, 3D: rigid paraboloid indenting a block"
    )
    ax.set_xlim(0.0, 1.6 * a0)
    ax.set_ylim(0.0, 1.15 * max(p0, max(row["peak"] for row in rows)))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--levels2d", type=int, nargs="*", default=[32, 64, 128, 256])
    parser.add_argument("--levels3d", type=int, nargs="*", default=[8, 16, 32])
    parser.add_argument("--no-friction", action="store_true")
    parser.add_argument("--out", default="out/hertz")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    text = []
    for dim, levels in ((2, args.levels2d), (3, args.levels3d)):
        if not levels:
            continue
        path = ROOT / "scenarios" / f"hertz{dim}d.toml"
        rows = []
        exact = None
        for friction in (False,) if args.no_friction else (False, True):
            name = f"hertz{dim}d" + ("-friction" if friction else "")
            _, exact, case_rows = run_case(name, path, levels, friction)
            rows += case_rows
        text.append(table(dim, exact, rows))
        figure(dim, exact, rows, out / f"pressure-{dim}d.png")
    report = "\n".join(text)
    (out / "table.md").write_text(report)
    print(report)


if __name__ == "__main__":
    main()
