"""A friction law written in Python, on a mesh made with Gmsh's Python API.

The paper's square (0, 4)² m — E = 2000 Pa, ν = 0.3, plane strain, clamped at the bottom,
pressed by 900 N/m on top, nearly locking (θ = 0.16, C_κ = 10⁴ Pa) — meshed with
unstructured triangles by the `gmsh` package (physical groups `bottom`, `right`, `top`,
`left` become the mesh's boundary parts). Its two vertical sides touch rigid foundations at
gap 0.4 m through normal compliance (c_ν = 10⁴ Pa/m), with Coulomb friction whose
coefficient follows the *linear slip-weakening law* of fault mechanics (Ida 1972):

    μ(r) = μ_s − (μ_s − μ_d) min(r / D_c, 1),

a static coefficient μ_s = 0.4 falling linearly to a dynamic one μ_d = 0.1 over the
critical slip D_c = 0.02 m. The law is a plain numpy function of the array of slips r (m);
the solver calls it once per outer iteration with the slips of all points of a contact part.
Its kink at r = D_c makes it Lipschitz with constant (μ_s − μ_d)/D_c = 15 /m.

Without the `gmsh` package the same square is meshed with numpy (a structured mesh).

Usage: python examples/python/custom_law.py [--h 0.25] [--out out/py-custom-law]
Writes the result files (as `hemicontact solve` does) and, with matplotlib, the interface
figure into --out, and prints a summary.
"""

import argparse
import os

import numpy as np

import hemicontact as hc

MU_S, MU_D, D_C = 0.4, 0.1, 0.02


def slip_weakening(r: np.ndarray) -> np.ndarray:
    """Linear slip weakening μ(r) = μ_s − (μ_s − μ_d) min(r/D_c, 1) (dimensionless)."""
    return MU_S - (MU_S - MU_D) * np.minimum(r / D_C, 1.0)


def gmsh_square(h: float) -> hc.Mesh:
    """The square (0, 4)² meshed by Gmsh with element size h (m), parts named by physical
    groups."""
    import gmsh

    gmsh.initialize(["", "-v", "0"])
    try:
        gmsh.model.add("square")
        occ = gmsh.model.occ
        occ.addRectangle(0.0, 0.0, 0.0, 4.0, 4.0)
        occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        names = {}
        for _, tag in gmsh.model.getEntities(1):
            x, y, _ = gmsh.model.occ.getCenterOfMass(1, tag)
            names[tag] = (
                "bottom" if y < 1e-9 else "top" if y > 4 - 1e-9 else "left" if x < 1e-9 else "right"
            )
        for tag, name in names.items():
            gmsh.model.setPhysicalName(1, gmsh.model.addPhysicalGroup(1, [tag]), name)
        gmsh.model.addPhysicalGroup(2, [1])
        gmsh.model.mesh.generate(2)
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        index = {int(t): i for i, t in enumerate(node_tags)}
        points = coords.reshape(-1, 3)[:, :2]
        _, _, tri_nodes = gmsh.model.mesh.getElements(2, 1)
        cells = np.array([index[int(t)] for t in tri_nodes[0]]).reshape(-1, 3)
        facets = {}
        for tag, name in names.items():
            _, _, line_nodes = gmsh.model.mesh.getElements(1, tag)
            facets[name] = np.array([index[int(t)] for t in line_nodes[0]]).reshape(-1, 2)
    finally:
        gmsh.finalize()
    # Gmsh orients the triangles of a plane surface by its normal; hemicontact refuses
    # clockwise cells rather than reorienting them silently, so orient them here, knowingly.
    p = points[cells]
    area2 = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 2, 0] - p[:, 0, 0]) * (
        p[:, 1, 1] - p[:, 0, 1]
    )
    cells[area2 < 0] = cells[area2 < 0][:, [0, 2, 1]]
    return hc.Mesh.from_arrays(points, cells, facets)


def numpy_square(h: float) -> hc.Mesh:
    """The square (0, 4)² as a structured mesh of right triangles of leg ≈ h (m)."""
    n = max(1, round(4.0 / h))
    x = np.linspace(0.0, 4.0, n + 1)
    X, Y = np.meshgrid(x, x)
    points = np.column_stack([X.ravel(), Y.ravel()])
    v = lambda i, j: j * (n + 1) + i  # noqa: E731
    cells = []
    for j in range(n):
        for i in range(n):
            cells += [[v(i, j), v(i + 1, j), v(i + 1, j + 1)], [v(i, j), v(i + 1, j + 1), v(i, j + 1)]]
    edge = lambda ids: np.column_stack([ids[:-1], ids[1:]])  # noqa: E731
    r = np.arange(n + 1)
    facets = {
        "bottom": edge(v(r, 0)),
        "right": edge(v(n, r)),
        "top": edge(v(r[::-1], n)),
        "left": edge(v(0, r[::-1])),
    }
    return hc.Mesh.from_arrays(points, np.array(cells), facets)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--h", type=float, default=0.25, help="element size (m), default 0.25")
    ap.add_argument("--out", default="out/py-custom-law", help="output folder")
    args = ap.parse_args(argv)
    try:
        mesh, made_by = gmsh_square(args.h), "gmsh"
    except ImportError:
        mesh, made_by = numpy_square(args.h), "numpy (the gmsh package is not installed)"
    print(f"mesh by {made_by}: {mesh}")
    contact = lambda part: {  # noqa: E731
        "part": part,
        "gap": 0.4,
        "law": "normal-compliance",
        "c_nu": 1.0e4,
        "friction": {"bound": "coulomb", "mu": slip_weakening},
    }
    scenario = hc.Scenario.from_dict(
        {
            "title": "Paper square, linear slip-weakening friction written in Python",
            "mesh": mesh,
            "material": {"young": 2000.0, "poisson": 0.3, "plane": "strain"},
            "locking": {"set": "limited-compressibility", "theta": 0.16, "treatment": "penalty",
                        "c_kappa": 1.0e4},
            "dirichlet": [{"part": "bottom"}],
            "loads": {"traction": [{"part": "top", "value": [0.0, -900.0]}]},
            "contact": [contact("left"), contact("right")],
        }
    )
    r = hc.solve(scenario)
    c = r.contact
    print(f"{r.message}; max |u| = {np.abs(r.displacement).max():.4g} m")
    print(f"contact points: {len(c['node'])}, in contact: {(c['normal_state'] == 'contact').sum()}, "
          f"slipping: {(c['friction_state'] == 'slip').sum()}, sticking: {(c['friction_state'] == 'stick').sum()}")
    slipping = c["friction_state"] == "slip"
    if slipping.any():
        # At a slipping point the friction bound is μ(slip) times the pressure.
        expected = slip_weakening(c["slip"][slipping]) * c["pressure"][slipping]
        print(f"max |bound − μ(slip) p| over slipping points: {np.abs(c['bound'][slipping] - expected).max():.2e} Pa")
    for path in r.write(args.out):
        print("wrote", path)
    try:
        import matplotlib

        matplotlib.use("Agg")
        from hemicontact import plot

        path = os.path.join(args.out, "interface-matplotlib.png")  # beside the library's interface.png
        plot.interface(r).savefig(path, dpi=150, bbox_inches="tight")
        print("wrote", path)
    except ImportError:
        print("matplotlib is not installed: no figure")
    return 0 if r.converged else 1


if __name__ == "__main__":
    raise SystemExit(main())
