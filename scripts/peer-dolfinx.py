#!/usr/bin/env python3
"""The frictionless Hertz benchmarks solved by a peer code on the same meshes: DOLFINx with
a Nitsche contact term and PETSc's Newton (SNES), against hemicontact, one thread each.

For each case and mesh size the script
1. solves the scenario with hemicontact (``RAYON_NUM_THREADS=1``) and reads its mesh (the
   nodes and cells of ``solution.vtu``), Newton count and solve time (``summary.json``);
2. builds a DOLFINx mesh from the same nodes and cells and solves the same problem
   (material, supports, loads, indenter) with symmetric Nitsche contact (θ = 1,
   γ = γ₀ E / h, γ₀ = 100) by SNES (Newton with backtracking line search), its linear
   systems by MUMPS (LU) and by CG + GAMG (rigid-body near null space);
3. prints the Newton counts, the times and their ratios, and the contact force of both.

The contact condition is written with the vertical gap between the block's top and the
indenter's profile, as in Hertz's theory; hemicontact projects each node on the obstacle.
The two discrete problems therefore differ at second order in the slope of the profile;
the contact forces printed show by how much.

The 2D case is driven by force and its block is held by contact alone: from u = 0 Newton's
first system would be singular, so the peer starts from a uniform upward displacement of
δ = 0.002 m (an active set around the apex), as a user of a general code would.

Usage (Python 3.12 with ``pip install dolfinx-solver-real meshio``; hemicontact built with
``cargo build --release``)::

    python scripts/peer-dolfinx.py [--bin target/release/hemicontact]
                                   [--levels2d 128 256] [--levels3d 32]
                                   [--gamma0 100] [--linesearch bt] [--solvers MUMPS GAMG]

γ₀ = 100 with the backtracking line search is the robust choice: with γ₀ = 10 the
symmetric Nitsche matrix is no longer positive definite on these meshes (CG + GAMG fails on
the first system) and full Newton steps (``--linesearch basic``) diverge on the 2D case at
n = 256. A failed peer solve is printed as failed, with SNES's reason.

Times are wall-clock seconds: hemicontact's is ``report.timings.total`` (the whole solve,
its symbolic analysis included); DOLFINx's is ``SNES.solve`` (assembly, factorizations or
multigrid set-ups and solves), after the forms are compiled and the matrix created.
"""

import os

for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import pathlib  # noqa: E402
import subprocess  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import tomllib  # noqa: E402

import dolfinx_solver  # noqa: E402,F401  (orders MPI ahead of the bindings)
import basix.ufl  # noqa: E402
import dolfinx  # noqa: E402
import dolfinx.fem.petsc  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
import ufl  # noqa: E402
from mpi4py import MPI  # noqa: E402
from petsc4py import PETSc  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent


def hemicontact(binary, scenario_text, work, name):
    """Solves with hemicontact on one thread; returns (points, cells, summary)."""
    path = work / f"{name}.toml"
    path.write_text(scenario_text)
    out = work / name
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    subprocess.run([binary, "solve", str(path), "--out", str(out)], check=True, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    mesh = meshio.read(out / "solution.vtu")
    cells = np.vstack([c.data for c in mesh.cells])
    summary = json.loads((out / "summary.json").read_text())
    return mesh.points, cells, summary


def nitsche(points, cells, data, dim, petsc_options, prefix):
    """Solves the scenario `data` (a Hertz case) on the mesh with Nitsche contact; returns
    (Newton steps, SNES seconds, converged reason, contact force along the indenter axis)."""
    x = np.ascontiguousarray(points[:, :dim])
    cell = "triangle" if dim == 2 else "tetrahedron"
    element = basix.ufl.element("Lagrange", cell, 1, shape=(dim,))
    msh = dolfinx.mesh.create_mesh(MPI.COMM_SELF, cells.astype(np.int64), ufl.Mesh(element), x)
    V = dolfinx.fem.functionspace(msh, ("Lagrange", 1, (dim,)))
    young, nu = data["material"]["young"], data["material"]["poisson"]
    mu = young / (2 * (1 + nu))
    lam = young * nu / ((1 + nu) * (1 - 2 * nu))  # plane strain in 2D, 3D Lamé
    fdim = dim - 1
    top = 0.0
    tol = 1e-9
    facets = lambda f: dolfinx.mesh.locate_entities_boundary(msh, fdim, f)
    top_facets = facets(lambda p: np.isclose(p[dim - 1], top, atol=tol))
    bottom_facets = facets(lambda p: np.isclose(p[dim - 1], -1.0, atol=tol))
    tags = np.concatenate([top_facets, bottom_facets])
    values = np.concatenate([np.full_like(top_facets, 1), np.full_like(bottom_facets, 2)])
    order = np.argsort(tags)
    mt = dolfinx.mesh.meshtags(msh, fdim, tags[order], values[order].astype(np.int32))
    ds = ufl.Measure("ds", domain=msh, subdomain_data=mt)
    # One quadrature for the contact terms of the residual and of the Jacobian: UFL would
    # estimate different degrees for the two, put their active sets at different points
    # and make Newton converge only linearly.
    dc = ufl.Measure("ds", domain=msh, subdomain_data=mt, metadata={"quadrature_degree": 4})

    u, v = dolfinx.fem.Function(V), ufl.TestFunction(V)
    eps = lambda w: ufl.sym(ufl.grad(w))
    sigma = lambda w: 2 * mu * eps(w) + lam * ufl.tr(eps(w)) * ufl.Identity(dim)
    n = ufl.FacetNormal(msh)
    h = ufl.CellDiameter(msh)
    gamma = GAMMA0 * young / h
    X = ufl.SpatialCoordinate(msh)
    obstacle = data["contact"][0]["obstacle"]
    radius = obstacle["radius"]
    if dim == 2:
        # Circle of centre (0, R) touching the top at the origin: its lower profile.
        r2 = X[0] ** 2
        profile = radius - ufl.sqrt(ufl.max_value(radius**2 - r2, 0.0))
        shift = 0.0
    else:
        # Paraboloid z = r²/(2R), translated by the scenario's displacement.
        r2 = X[0] ** 2 + X[1] ** 2
        profile = r2 / (2 * radius)
        shift = obstacle["displacement"][2]
    gap = profile + shift - X[dim - 1]
    un = ufl.dot(u, n)
    sn = lambda w: ufl.dot(ufl.dot(sigma(w), n), n)
    contact = ufl.min_value(sn(u) - gamma * (un - gap), 0.0)
    F = (ufl.inner(sigma(u), eps(v)) * ufl.dx
         - (1 / gamma) * sn(u) * sn(v) * dc(1)
         + (1 / gamma) * contact * (sn(v) - gamma * ufl.dot(v, n)) * dc(1))
    bcs = []
    if dim == 2:
        q = data["loads"]["traction"][0]["value"]
        F -= ufl.dot(ufl.as_vector(q), v) * ds(2)
        left = facets(lambda p: np.isclose(p[0], 0.0, atol=tol))
        dofs = dolfinx.fem.locate_dofs_topological(V.sub(0), fdim, left)
        bcs.append(dolfinx.fem.dirichletbc(0.0, dofs, V.sub(0)))
        # Held by contact alone: start pushed into the cylinder by δ.
        u.x.array[1::2] = 0.002
    else:
        zero = np.zeros(3)
        dofs = dolfinx.fem.locate_dofs_topological(V, fdim, bottom_facets)
        bcs.append(dolfinx.fem.dirichletbc(zero, dofs, V))
        for k in (0, 1):
            side = facets(lambda p, k=k: np.isclose(p[k], 0.0, atol=tol))
            dofs = dolfinx.fem.locate_dofs_topological(V.sub(k), fdim, side)
            bcs.append(dolfinx.fem.dirichletbc(0.0, dofs, V.sub(k)))
    problem = dolfinx.fem.petsc.NonlinearProblem(F, u, bcs=bcs, petsc_options=petsc_options,
                                                 petsc_options_prefix=prefix)
    if petsc_options.get("pc_type") == "gamg":
        problem.A.setNearNullSpace(rigid_modes(V, dim))
    snes = problem.solver
    t = time.perf_counter()
    problem.solve()
    seconds = time.perf_counter() - t
    steps, reason = snes.getIterationNumber(), snes.getConvergedReason()
    force = dolfinx.fem.assemble_scalar(dolfinx.fem.form(contact * n[dim - 1] * dc(1)))
    return steps, seconds, reason, force


def rigid_modes(V, dim):
    """The rigid-body motions of V as a PETSc near null space (for GAMG)."""
    x = V.tabulate_dof_coordinates()
    n = x.shape[0]
    modes = []
    for k in range(dim):
        m = np.zeros((n, dim))
        m[:, k] = 1.0
        modes.append(m)
    pairs = [(0, 1)] if dim == 2 else [(0, 1), (1, 2), (2, 0)]
    for a, b in pairs:
        m = np.zeros((n, dim))
        m[:, a], m[:, b] = -x[:, b], x[:, a]
        modes.append(m)
    basis, _ = np.linalg.qr(np.column_stack([m.ravel() for m in modes]))
    size = V.dofmap.index_map.size_local * dim
    vecs = [PETSc.Vec().createWithArray(np.ascontiguousarray(basis[:size, k]),
                                        comm=MPI.COMM_SELF) for k in range(basis.shape[1])]
    return PETSc.NullSpace().create(vectors=vecs)


# Nitsche parameter γ₀ (γ = γ₀ E / h) and SNES line search; set from the command line.
GAMMA0 = 100.0
OPTIONS = {
    "MUMPS": {"ksp_type": "preonly", "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"},
    "GAMG": {"ksp_type": "cg", "ksp_rtol": 1e-10, "pc_type": "gamg"},
}
SNES = {"snes_type": "newtonls", "snes_linesearch_type": "bt", "snes_rtol": 1e-10,
        "snes_atol": 1e-14, "snes_stol": 0.0, "snes_max_it": 50}


def main():
    global GAMMA0
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "hemicontact"))
    ap.add_argument("--levels2d", type=int, nargs="*", default=[128, 256])
    ap.add_argument("--levels3d", type=int, nargs="*", default=[32])
    ap.add_argument("--gamma0", type=float, default=GAMMA0, help="Nitsche γ₀ (default 100)")
    ap.add_argument("--linesearch", default="bt", help="SNES line search (default bt)")
    ap.add_argument("--solvers", nargs="*", default=list(OPTIONS), help="MUMPS and/or GAMG")
    args = ap.parse_args()
    GAMMA0 = args.gamma0
    SNES["snes_linesearch_type"] = args.linesearch
    rows = []
    with tempfile.TemporaryDirectory(prefix="peer-dolfinx-") as tmp:
        work = pathlib.Path(tmp)
        for dim, name, levels in ((2, "hertz2d", args.levels2d), (3, "hertz3d", args.levels3d)):
            text = (ROOT / "scenarios" / f"{name}.toml").read_text()
            data = tomllib.loads(text)
            default = data["mesh"]["n"]
            for n in levels:
                case = text.replace(f"n = {default}", f"n = {[n] * dim}")
                if case == text and default != [n] * dim:
                    raise SystemExit(f"cannot set the mesh size in {name}.toml")
                points, cells, summary = hemicontact(args.bin, case, work, f"{name}-{n}")
                report = summary["report"]
                h_newton = len(report["newton"])
                h_time = report["timings"]["total"]
                h_force = contact_force(summary, dim)
                for label, opts in ((k, OPTIONS[k]) for k in args.solvers):
                    steps, seconds, reason, force = nitsche(
                        points, cells, data, dim, {**SNES, **opts}, f"{name}{n}{label}_")
                    rows.append((name, n, report["n_dofs"], h_newton, h_time, label, steps,
                                 seconds, reason, h_force, force))
                    print_row(rows[-1])
    print()
    print("| case | n | DOFs | hemicontact Newton | hemicontact s | peer | peer Newton "
          "| peer s | ratio hemicontact / peer | force hemicontact | force peer |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        name, n, dofs, hn, ht, label, pn, pt, reason, hf, pf = r
        if reason > 0:
            print(f"| {name} | {n} | {dofs} | {hn} | {ht:.2f} | DOLFINx + {label} | {pn} "
                  f"| {pt:.2f} | {ht / pt:.2f} | {hf:.5g} | {pf:.5g} |")
        else:
            print(f"| {name} | {n} | {dofs} | {hn} | {ht:.2f} | DOLFINx + {label} | failed "
                  f"after {pn} (SNES reason {reason}) | — | — | {hf:.5g} | — |")


def contact_force(summary, dim):
    """hemicontact's contact force along the indenter axis (the modelled part)."""
    totals = summary.get("contact_totals") or []
    return sum(t["force"][dim - 1] for t in totals) if totals else float("nan")


def print_row(r):
    name, n, dofs, hn, ht, label, pn, pt, reason, hf, pf = r
    print(f"{name} n = {n} ({dofs} DOFs): hemicontact {hn} Newton, {ht:.2f} s; DOLFINx + "
          f"{label}: {pn} Newton (reason {reason}), {pt:.2f} s; ratio {ht / pt:.2f}; "
          f"force {hf:.5g} / {pf:.5g}", flush=True)


if __name__ == "__main__":
    main()
