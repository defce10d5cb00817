"""The paper's example from Python: solves it with locking (C_κ = 10⁴ Pa) and without
(C_κ = 0), draws the two deformed meshes side by side (the paper's Fig. 3) and the contact
quantities along the two contact sides of each, and runs a small refinement study.

Usage: python examples/python/paper.py [--n 64] [--out out/py-paper]
                                       [--levels 8,16,32,64] [--reference 256]

Needs the package with its plot extra: pip install "./crates/hemicontact-py[plot]".
Writes PNG files into --out and prints each path and the study's table.
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import hemicontact as hc  # noqa: E402
from hemicontact import plot  # noqa: E402

CASES = [
    (1.0e4, "ckappa1e4", r"$C_\kappa = 10^4$ Pa (locking)"),
    (0.0, "ckappa0", r"$C_\kappa = 0$ (no locking)"),
]


def _levels(text: str):
    try:
        levels = [int(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--levels {text!r}: comma-separated integers, e.g. 8,16,32"
        ) from None
    if not levels or min(levels) < 1:
        raise argparse.ArgumentTypeError(f"--levels {text!r}: integers ≥ 1, e.g. 8,16,32")
    return levels


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=64, help="squares per side of the mesh (default 64)")
    ap.add_argument("--out", default="out/py-paper", help="output folder (default out/py-paper)")
    ap.add_argument("--levels", type=_levels, default=[8, 16, 32, 64],
                    help="refinement levels, squares per side (default 8,16,32,64)")
    ap.add_argument("--reference", type=int, default=256,
                    help="squares per side of the reference solution (default 256)")
    args = ap.parse_args(argv)
    if args.n < 1 or args.reference < 1:
        ap.error("--n and --reference: integers ≥ 1")
    os.makedirs(args.out, exist_ok=True)
    written = []

    results = []
    for c_kappa, tag, label in CASES:
        r = hc.solve(hc.paper_example(n=args.n, c_kappa=c_kappa))
        print(f"{label}: {r.message}; max |u| = {abs(r.displacement).max():.4g} m")
        results.append((r, tag, label))

    fig, axes = plt.subplots(1, 2, figsize=(11.5, 7.0), layout="constrained")
    for ax, (r, _, label) in zip(axes, results):
        plot.deformed(r, ax=ax, title=f"{label}, {args.n}×{args.n} mesh")
    path = os.path.join(args.out, "deformed.png")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    written.append(path)

    for r, tag, label in results:
        fig = plot.interface(r)
        fig.suptitle(f"Contact along the sides, {label}, {args.n}×{args.n} mesh", fontsize=11)
        path = os.path.join(args.out, f"interface-{tag}.png")
        fig.savefig(path, dpi=120, bbox_inches="tight")
        plt.close(fig)
        written.append(path)

    study = hc.convergence(hc.paper_example(n=args.levels[0], c_kappa=1.0e4), args.levels,
                           args.reference)
    print(f"\nrefinement study, C_κ = 10⁴ Pa, reference {args.reference}×{args.reference}:")
    print(f"{'n':>6} {'h (m)':>9} {'dofs':>8} {'error':>11} {'order':>6} {'outer':>6} {'newton':>7}")
    for row in study:
        order = "" if row["order_edge"] is None else f"{row['order_edge']:.2f}"
        print(f"{row['n']:>6} {row['h_edge']:>9.4g} {row['dofs']:>8} {row['error']:>11.4e} "
              f"{order:>6} {row['outer']:>6} {row['newton']:>7}")
    fig = plot.convergence(study, title=f"Paper example, $C_\\kappa = 10^4$ Pa: refinement "
                                        f"against a {args.reference}×{args.reference} mesh")
    path = os.path.join(args.out, "convergence.png")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    written.append(path)

    print("\nwritten:")
    for p in written:
        print(f"  {p}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
