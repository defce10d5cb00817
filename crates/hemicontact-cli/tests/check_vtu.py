#!/usr/bin/env python3
"""Reads a hemicontact solution.vtu with meshio (an independent VTK reader) and checks it.

Usage: check_vtu.py FILE --points N --cells M [--mean-stress-yy S]

Checks: the numbers of points and triangles; the point arrays `displacement` (3 components)
and the cell arrays `strain`, `stress` (9 components), `von_mises`, `trace_strain`; finite
values; symmetric tensors; `trace_strain` = ε_xx + ε_yy; zero displacement at the clamped
bottom nodes (y = 0); and, if given, the area-weighted mean of σ_yy.

Exit codes: 0 pass, 1 a check failed, 77 meshio (or numpy) is not importable (skip).
"""
import argparse
import sys

try:
    import meshio
    import numpy as np
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"skipped: meshio not available ({e})", file=sys.stderr)
    sys.exit(77)


def fail(msg):
    print(f"check_vtu: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("file")
    ap.add_argument("--points", type=int, required=True)
    ap.add_argument("--cells", type=int, required=True)
    ap.add_argument("--mean-stress-yy", type=float, default=None)
    a = ap.parse_args()

    m = meshio.read(a.file)
    pts = np.asarray(m.points)
    if pts.shape[0] != a.points:
        fail(f"{pts.shape[0]} points, expected {a.points}")
    tri = [b.data for b in m.cells if b.type == "triangle"]
    if len(tri) != 1 or sum(len(b.data) for b in m.cells) != a.cells:
        fail(f"cells {[(b.type, len(b.data)) for b in m.cells]}, expected {a.cells} triangles")
    tri = np.asarray(tri[0])
    if tri.shape != (a.cells, 3) or tri.min() < 0 or tri.max() >= a.points:
        fail(f"bad connectivity, shape {tri.shape}")

    if "displacement" not in m.point_data:
        fail(f"no point array 'displacement' (have {sorted(m.point_data)})")
    u = np.asarray(m.point_data["displacement"]).reshape(a.points, -1)
    if u.shape[1] != 3:
        fail(f"displacement has {u.shape[1]} components, expected 3")

    cell = {}
    for name, comps in [("strain", 9), ("stress", 9), ("von_mises", 1), ("trace_strain", 1)]:
        if name not in m.cell_data:
            fail(f"no cell array '{name}' (have {sorted(m.cell_data)})")
        blocks = m.cell_data[name]
        v = np.concatenate([np.asarray(b).reshape(len(b), -1) for b in blocks])
        if v.shape != (a.cells, comps):
            fail(f"{name} has shape {v.shape}, expected ({a.cells}, {comps})")
        cell[name] = v

    for name, v in [("displacement", u)] + list(cell.items()):
        if not np.all(np.isfinite(v)):
            fail(f"{name} has non-finite values")

    scale_u = max(np.abs(u).max(), 1e-300)
    if np.abs(u).max() == 0.0:
        fail("displacement is identically zero")
    for name in ("strain", "stress"):
        t = cell[name].reshape(-1, 3, 3)
        asym = np.abs(t - np.transpose(t, (0, 2, 1))).max()
        if asym > 1e-12 * max(np.abs(t).max(), 1e-300):
            fail(f"{name} is not symmetric ({asym})")
    eps = cell["strain"].reshape(-1, 3, 3)
    tr = eps[:, 0, 0] + eps[:, 1, 1]
    if np.abs(tr - cell["trace_strain"][:, 0]).max() > 1e-12 * max(np.abs(tr).max(), 1e-300):
        fail("trace_strain differs from strain_xx + strain_yy")
    if cell["von_mises"].min() < 0.0:
        fail("negative von Mises stress")

    bottom = np.abs(pts[:, 1]) < 1e-12
    if not bottom.any():
        fail("no node at y = 0")
    if np.abs(u[bottom]).max() > 1e-14 * scale_u:
        fail(f"displacement at the clamped bottom is {np.abs(u[bottom]).max()}")

    if a.mean_stress_yy is not None:
        p = pts[tri]
        area = 0.5 * np.abs(
            (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
            - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1])
        )
        syy = cell["stress"].reshape(-1, 3, 3)[:, 1, 1]
        mean = float((area * syy).sum() / area.sum())
        if abs(mean - a.mean_stress_yy) > 1e-8 * abs(a.mean_stress_yy):
            fail(f"mean stress_yy = {mean}, expected {a.mean_stress_yy}")

    print(f"check_vtu: ok: {a.points} points, {a.cells} cells, max |u| = {scale_u:.6e}")


if __name__ == "__main__":
    main()
