#!/usr/bin/env python3
"""The two-body benchmarks of docs/benchmarks.md: Hertz between two elastic cylinders and
between two elastic spheres, and Cattaneo–Mindlin between two elastic cylinders and between
two elastic spheres, under mesh refinement, with the contact pressure and the friction
traction against the closed forms.

The meshes are built as in ``crates/hemicontact/tests/bodies/hertz_two_bodies.rs``, so the numbers
reproduce its tables: each body is the generated block [0, 1] × [y0, y0 + 1] (a quarter box
[0, 1]² × [z0, z0 + 1] in 3D, cells cut "uniform"), graded towards the contact point, its
contact face moved onto the circle (sphere) of its radius through the origin by the lift
R − √(R² − x²), weighted by 1 − |y| so that it fades to the far face. The two bodies are
merged into one mesh (lower first, boundary parts prefixed ``lower_`` and ``upper_``, cell
regions ``lower`` and ``upper``); the upper body's bottom (slave) is paired with the lower
body's top (master).

Cases (the analytic values are computed from the data below):

- **cylinders** (plane strain, frictionless): R₁ = 2 m, E₁ = 10 Pa, ν₁ = 0.3 (upper);
  R₂ = 3 m, E₂ = 20 Pa, ν₂ = 0.25 (lower); half models (rollers on x = 0), the lower
  bottom held along y, the traction q = 0.025 Pa on the upper top: F = 2q per unit length,
  1/R* = 1/R₁ + 1/R₂, 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂, a = √(4FR*/(πE*)),
  p₀ = 2F/(πa) (Johnson, §4.2). Level n: n × n cells per body, progression 1.017^(128/n).
- **spheres** (frictionless): the same materials, R₁ = 5 m, R₂ = 10 m, quarter models,
  q = 0.000306 Pa: F = 4q, a = (3FR*/(4E*))^{1/3}, p₀ = 3F/(2πa²). Level n: n³ cuboids
  per body, progression 20^(1/n).
- **Cattaneo–Mindlin**: two identical cylinders (R = 20 m, E = 10 Pa, ν = 0.3), full width
  (each half block mirrored about x = 0), pressed by q = 0.0025 Pa on the upper top
  (P = 2q), sheared by moving the upper top and sides by s = 4e-4 m along x, the lower
  bottom clamped and its sides held along x; exact Coulomb friction μ = 0.3. Cattaneo:
  c = a √(1 − Q/(μP)), q(x) = μp₀√(1 − x²/a²) in the slip zones c ≤ |x| ≤ a and
  μp₀[√(1 − x²/a²) − (c/a)√(1 − x²/c²)] in the stick zone (Johnson, §7.1).
- **Cattaneo–Mindlin, spheres** (``cattaneo_mindlin_stick_zone_and_traction_of_two_spheres``):
  two identical spheres (R = 20 m, E = 10 Pa, ν = 0.3), whole bodies [−1, 1]² × [0, 1]
  (the quarter box mirrored about x = 0, then y = 0; the lower body the upper one's mirror
  image about z = 0), pressed by q = P/4 on the upper top, P = 4E*a³/(3R*) for a = 0.1 m
  (R* = R/2, E* = E/(2(1 − ν²))), sheared by moving the upper top and sides by (s, 0),
  s = 1.8e-4 m, along x and y, the lower bottom clamped and its sides held along x and y;
  exact Coulomb friction μ = 0.3. Mindlin: c = a (1 − Q/(μP))^{1/3}, q(r) along Q as the
  cylinders' q(x) with r for x (Johnson, §7.1). Measured as the Rust test: a_FE the largest
  radius with a positive pressure, c_FE the largest |x| of the sticking points on y = 0, h
  the gap from it to the next point there, the traction error at the in-contact points with
  r < a and |r − c| > 1.5 h. Level n: 4n³ cuboids per body, progression 20^(1/n).

Usage (needs the hemicontact Python package, numpy and matplotlib; gmsh for
``--write-meshes``)::

    python scripts/two_bodies.py [--levels-cylinders 32 64 128] [--levels-spheres 8 12 16]
                                 [--cattaneo 64] [--cattaneo-spheres 12] [--skip-spheres]
                                 [--skip-cattaneo-spheres] [--out out/two-bodies]
    python scripts/two_bodies.py --levels-cylinders 32 --cattaneo 32 --skip-spheres
                                 --skip-cattaneo-spheres
    python scripts/two_bodies.py --levels-cylinders --skip-spheres --cattaneo
                                 --cattaneo-spheres 12 16   # the friction of the spheres
    python scripts/two_bodies.py --write-meshes

(n = 12 of the spheres with friction takes about 1.5 min, n = 16 about 3 min.) An option
given with no levels (``--cattaneo``) skips that case. Writes ``table.md`` (the tables
printed), ``pressure-cylinders.png``, ``pressure-spheres.png``, ``cattaneo-mindlin.png``
and ``cattaneo-mindlin-spheres.png`` (of the last level) to the output folder. With
``--write-meshes`` it writes instead the meshes of the committed scenarios
(``scenarios/two-cylinders.toml`` at n = 32, ``scenarios/cattaneo-mindlin.toml`` at
n = 32, ``scenarios/two-spheres.toml`` at n = 8, ``scenarios/cattaneo-spheres.toml`` at
n = 6) as Gmsh 4.1 ASCII files to ``scenarios/meshes/``.
"""

import argparse
import math
import pathlib
import sys
import time

import numpy as np

import hemicontact as hc

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Hertz between two cylinders (upper: 1, lower: 2) and between two spheres.
CYLINDERS = {"radii": (2.0, 3.0), "q": 0.025}
SPHERES = {"radii": (5.0, 10.0), "q": 0.000306}
MATERIALS = {"upper": (10.0, 0.3), "lower": (20.0, 0.25)}  # (E in Pa, ν)
# Cattaneo–Mindlin: two identical cylinders.
CATTANEO = {"radius": 20.0, "young": 10.0, "poisson": 0.3, "mu": 0.3, "q": 0.0025,
            "shear": 4.0e-4}
# Cattaneo–Mindlin: two identical spheres, pressed to a = 0.1 m (P from it), sheared by s.
CATTANEO_SPHERES = {"radius": 20.0, "young": 10.0, "poisson": 0.3, "mu": 0.3, "a": 0.1,
                    "shear": 1.8e-4}
# The levels of the committed scenario files (their meshes: --write-meshes).
COMMITTED = {"two-cylinders": 32, "cattaneo-mindlin": 32, "two-spheres": 8,
             "cattaneo-spheres": 6}


def grading_2d(n):
    """The progression of a 2D level: 1.017^(128/n), nested with the Rust test's levels.
    For 128/n a power of two it is computed by squaring, as the test's `powi` does (the
    same bits)."""
    k = 128 // n if 128 % n == 0 else 0
    if k & (k - 1) == 0 and k > 0:
        r = 1.017
        while k > 1:
            r, k = r * r, k // 2
        return r
    return 1.017 ** (128.0 / n)


def grading_3d(n):
    """The progression of a 3D level: cells growing by a factor 20 across the body."""
    return 20.0 ** (1.0 / n)


# --------------------------------------------------------------------------------------
# Meshes
# --------------------------------------------------------------------------------------


def generated(dim, n, r, side):
    """The generated block of one body: [0, 1] × [y0, y0 + 1] (2D) or [0, 1]² × [z0, z0 + 1]
    (3D), n cells per side cut "uniform", graded by r towards x = 0 (and y = 0 in 3D) and
    towards the contact face (y = 0, z = 0 in 3D); y0 = 0 for the upper body (side = +1),
    −1 for the lower. Returns (points, cells, {part: facets})."""
    lower = side < 0.0
    normal = (1.0 / r) if lower else r
    spec = {
        "kind": "rectangle" if dim == 2 else "box",
        "origin": [0.0] * (dim - 1) + [-1.0 if lower else 0.0],
        "size": [1.0] * dim,
        "n": [n] * dim,
        "pattern": "uniform",
        "progression": [r] * (dim - 1) + [normal],
    }
    # A throwaway scenario (held at its bottom to be valid) whose mesh is the block.
    data = {"mesh": spec, "material": {"young": 1.0, "poisson": 0.3},
            "dirichlet": [{"part": "bottom"}]}
    mesh = hc.Scenario.from_dict(data).mesh()
    return mesh.points.copy(), mesh.cells.copy(), dict(mesh.facets)


def reflected_3d(points, cells, facets):
    """The mirror image of a 3D mesh about z = 0: cells and facets reoriented (two
    vertices swapped), the parts ``top`` and ``bottom`` renamed into each other in place
    (the parts' order kept, as the Rust test's `reflected`)."""
    points = points.copy()
    points[:, 2] *= -1.0
    swap = {"top": "bottom", "bottom": "top"}
    facets = {swap.get(k, k): v[:, [1, 0, 2]] for k, v in facets.items()}
    return points, cells[:, [1, 0, 2, 3]], facets


def body(dim, n, r, side, radius):
    """One body: the generated block with its face y = 0 (z = 0) moved onto the circle
    (sphere) of `radius` through the origin, curving away from the other body, the lift
    weighted by 1 − |y| (1 − |z|).

    In 3D both bodies are cut alike, as in the Rust test: the box generator splits each
    cube into six tetrahedra around its diagonal from its smallest to its largest corner,
    so a box generated above z = 0 would put such a corner at the apex, where the quarter
    model's symmetry planes meet, and load the nodes on those planes unevenly (the peak
    pressure 12 % low). The upper body is the mirror image of a box generated below
    z = 0, whose apex corner is shared by two tetrahedra only."""
    if dim == 3 and side > 0.0:
        points, cells, facets = reflected_3d(*generated(dim, n, r, -1.0))
    else:
        points, cells, facets = generated(dim, n, r, side)
    # R² − x² (− y²), subtracted in the Rust test's order (the same bits).
    radicand = radius * radius - points[:, 0] ** 2
    if dim == 3:
        radicand -= points[:, 1] ** 2
    lift = radius - np.sqrt(radicand)
    points[:, dim - 1] += side * lift * (1.0 - np.abs(points[:, dim - 1]))
    return points, cells, facets


def mirrored(half):
    """The full width [−1, 1] of a 2D body from its half [0, 1]: the half mirrored about
    x = 0 (the nodes on x = 0 shared, the mirrored cells reoriented), parts ``bottom``,
    ``top`` (both halves) and ``sides`` (x = ±1), as in the Rust test."""
    points, cells, facets = half
    image = np.arange(len(points))
    off_axis = np.flatnonzero(points[:, 0] != 0.0)
    image[off_axis] = len(points) + np.arange(len(off_axis))
    images = points[off_axis] * np.array([-1.0, 1.0])
    all_points = np.vstack([points, images])
    # Mirroring reverses the orientation: swap the first two vertices.
    all_cells = np.vstack([cells, image[cells[:, [1, 0, 2]]]])

    def both(name):
        f = facets[name]
        return np.vstack([f, image[f[:, [1, 0]]]])

    parts = {"bottom": both("bottom"), "top": both("top"), "sides": both("right")}
    return all_points, all_cells, parts


def mirrored_3d(mesh, axis, inner):
    """A 3D mesh (points, cells, facets) and its mirror image about the plane
    x[axis] = 0, the nodes on that plane shared (the images of the others appended in
    order, the mirrored cells reoriented and appended), as the Rust test's `mirrored_3d`:
    each part keeps its name and gains its image's facets (each facet followed by its
    image), except `inner` (the facets on the plane), which is dropped."""
    points, cells, facets = mesh
    image = np.arange(len(points))
    off_plane = np.flatnonzero(points[:, axis] != 0.0)
    image[off_plane] = len(points) + np.arange(len(off_plane))
    images = points[off_plane].copy()
    images[:, axis] *= -1.0
    all_points = np.vstack([points, images])
    # Mirroring reverses the orientation: swap the first two vertices.
    all_cells = np.vstack([cells, image[cells[:, [1, 0, 2, 3]]]])
    parts = {
        name: np.stack([f, image[f[:, [1, 0, 2]]]], axis=1).reshape(-1, 3)
        for name, f in facets.items()
        if name != inner
    }
    return all_points, all_cells, parts


def whole_ball(n, r, radius):
    """The whole upper body [−1, 1]² × [0, 1] of the Cattaneo–Mindlin spheres from its
    quarter (`body`): mirrored about x = 0 (dropping ``left``), then about y = 0
    (dropping ``front``); parts ``right`` (x = ±1), ``back`` (y = ±1), ``bottom``,
    ``top``."""
    half = mirrored_3d(body(3, n, r, 1.0, radius), 0, "left")
    return mirrored_3d(half, 1, "front")


def merged(lower, upper):
    """The two bodies in one mesh, lower first: (points, cells, facets, regions), the
    parts prefixed ``lower_`` and ``upper_``, the regions ``lower`` and ``upper``."""
    offset = len(lower[0])
    points = np.vstack([lower[0], upper[0]])
    cells = np.vstack([lower[1], upper[1] + offset])
    facets = {f"lower_{k}": v for k, v in lower[2].items()}
    facets.update({f"upper_{k}": v + offset for k, v in upper[2].items()})
    regions = {
        "lower": np.arange(len(lower[1])),
        "upper": len(lower[1]) + np.arange(len(upper[1])),
    }
    return points, cells, facets, regions


def cylinders_mesh(n, radii=CYLINDERS["radii"]):
    """The two Hertz cylinders at level n (half models)."""
    r = grading_2d(n)
    return merged(body(2, n, r, -1.0, radii[1]), body(2, n, r, 1.0, radii[0]))


def spheres_mesh(n, radii=SPHERES["radii"]):
    """The two Hertz spheres at level n (quarter models)."""
    r = grading_3d(n)
    return merged(body(3, n, r, -1.0, radii[1]), body(3, n, r, 1.0, radii[0]))


def cattaneo_mesh(n):
    """The two Cattaneo–Mindlin cylinders at level n (full width: 2n × n cells each)."""
    r, radius = grading_2d(n), CATTANEO["radius"]
    return merged(
        mirrored(body(2, n, r, -1.0, radius)), mirrored(body(2, n, r, 1.0, radius))
    )


def cattaneo_spheres_mesh(n):
    """The two Cattaneo–Mindlin spheres at level n (whole bodies: 4n³ cuboids each), the
    lower body the upper one's mirror image about z = 0, as in the Rust test: two
    differently cut bodies would differ in their discrete Poisson expansion under the
    normal load, a radial slip that the stick zone locks in."""
    upper = whole_ball(n, grading_3d(n), CATTANEO_SPHERES["radius"])
    return merged(reflected_3d(*upper), upper)


def to_mesh(arrays):
    """The `hc.Mesh` of (points, cells, facets, regions)."""
    points, cells, facets, regions = arrays
    return hc.Mesh.from_arrays(points, cells, facets=facets, regions=regions)


def write_msh(arrays, path):
    """Writes (points, cells, facets, regions) of a two-body mesh as a Gmsh 4.1 ASCII file:
    one discrete surface (volume in 3D) per region, a physical group of the region's name,
    one discrete curve (surface) per boundary part, a physical group of the part's name.
    Node tags are the indices plus one, in order, so the file's nodes are the mesh's."""
    import gmsh

    points, cells, facets, regions = arrays
    dim = points.shape[1]
    xyz = points if dim == 3 else np.column_stack([points, np.zeros(len(points))])
    cell_type, facet_type = (2, 1) if dim == 2 else (4, 2)
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(path.stem)
        for tag, (name, own) in enumerate(regions.items(), start=1):
            body_cells = cells[own]
            nodes = np.unique(body_cells)
            assert np.array_equal(nodes, np.arange(nodes[0], nodes[-1] + 1)), "bodies apart"
            gmsh.model.addDiscreteEntity(dim, tag)
            gmsh.model.mesh.addNodes(dim, tag, (nodes + 1).tolist(), xyz[nodes].ravel().tolist())
            gmsh.model.mesh.addElementsByType(
                tag, cell_type, [], (body_cells + 1).ravel().tolist()
            )
            gmsh.model.addPhysicalGroup(dim, [tag], name=name)
        for tag, (name, lines) in enumerate(facets.items(), start=1):
            gmsh.model.addDiscreteEntity(dim - 1, tag)
            gmsh.model.mesh.addElementsByType(tag, facet_type, [], (lines + 1).ravel().tolist())
            gmsh.model.addPhysicalGroup(dim - 1, [tag], name=name)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.write(str(path))
    finally:
        gmsh.finalize()


# --------------------------------------------------------------------------------------
# Scenarios (the same as the committed TOML files, with the mesh in memory)
# --------------------------------------------------------------------------------------


def roller(part, component, value=0.0, dim=2):
    """A Dirichlet condition on one component of a part."""
    values = [0.0] * dim
    values["xyz".index(component)] = value
    return {"part": part, "components": [component], "value": values}


def hertz_scenario(mesh, dim, q):
    """The Hertz pair (cylinders or spheres): rollers on the symmetry planes, the lower
    bottom held along y (z), the traction q on the upper top, frictionless Signorini."""
    up = "xyz"[dim - 1]
    dirichlet = []
    for b in ("lower", "upper"):
        dirichlet.append(roller(f"{b}_left", "x", dim=dim))
        if dim == 3:
            dirichlet.append(roller(f"{b}_front", "y", dim=dim))
    dirichlet.append(roller("lower_bottom", up, dim=dim))
    load = [0.0] * dim
    load[-1] = -q
    return {
        "mesh": mesh,
        "material": [
            {"part": b, "young": MATERIALS[b][0], "poisson": MATERIALS[b][1]}
            for b in ("lower", "upper")
        ],
        "dirichlet": dirichlet,
        "loads": {"traction": [{"part": "upper_top", "value": load}]},
        "contact": [{"part": "upper_bottom", "against": "lower_top", "law": "signorini"}],
    }


def cattaneo_scenario(mesh):
    """Cattaneo–Mindlin: pressed by q, sheared by s, exact Coulomb friction μ."""
    k = CATTANEO
    return {
        "mesh": mesh,
        "material": {"young": k["young"], "poisson": k["poisson"]},
        "dirichlet": [
            {"part": "lower_bottom", "components": ["x", "y"], "value": [0.0, 0.0]},
            roller("upper_top", "x", k["shear"]),
            roller("upper_sides", "x", k["shear"]),
            roller("lower_sides", "x"),
        ],
        "loads": {"traction": [{"part": "upper_top", "value": [0.0, -k["q"]]}]},
        "contact": [
            {
                "part": "upper_bottom",
                "against": "lower_top",
                "law": "signorini",
                "friction": {"bound": "coulomb", "mu": k["mu"], "exact": True},
            }
        ],
    }


def cattaneo_spheres_load():
    """The Cattaneo–Mindlin spheres' load: (P, R*, E*), P = 4E*a³/(3R*) pressing them to
    the contact radius a, R* = R/2, E* = E/(2(1 − ν²))."""
    k = CATTANEO_SPHERES
    r_star, e_star = k["radius"] / 2.0, k["young"] / (2.0 * (1.0 - k["poisson"] ** 2))
    return 4.0 * e_star * k["a"] ** 3 / (3.0 * r_star), r_star, e_star


def cattaneo_spheres_scenario(mesh):
    """Cattaneo–Mindlin between two spheres: the lower bottom clamped, its sides held
    along x and y; the upper top and sides moved by (s, 0) along x and y (the vertical
    translation free, carried by the pair), the upper top loaded by P/4 (area 4 m²);
    exact Coulomb friction μ."""
    k = CATTANEO_SPHERES
    force = cattaneo_spheres_load()[0]

    def along_xy(part, value=0.0):
        return {"part": part, "components": ["x", "y"], "value": [value, 0.0, 0.0]}

    return {
        "mesh": mesh,
        "material": {"young": k["young"], "poisson": k["poisson"]},
        "dirichlet": [
            {"part": "lower_bottom", "components": ["x", "y", "z"], "value": [0.0] * 3},
            along_xy("lower_right"),
            along_xy("lower_back"),
            along_xy("upper_top", k["shear"]),
            along_xy("upper_right", k["shear"]),
            along_xy("upper_back", k["shear"]),
        ],
        "loads": {"traction": [{"part": "upper_top", "value": [0.0, 0.0, -force / 4.0]}]},
        "contact": [
            {
                "part": "upper_bottom",
                "against": "lower_top",
                "law": "signorini",
                "friction": {"bound": "coulomb", "mu": k["mu"], "exact": True},
            }
        ],
    }


# --------------------------------------------------------------------------------------
# Closed forms
# --------------------------------------------------------------------------------------


def combined(radii, materials):
    """R* and E* of two bodies: 1/R* = Σ 1/R_i, 1/E* = Σ (1 − ν_i²)/E_i."""
    r_star = 1.0 / sum(1.0 / r for r in radii)
    e_star = 1.0 / sum((1.0 - nu * nu) / e for e, nu in materials)
    return r_star, e_star


def hertz_cylinders(force, r_star, e_star):
    """Hertz's half-width a and peak pressure p₀ of two cylinders under F per length."""
    a = math.sqrt(4.0 * force * r_star / (math.pi * e_star))
    return a, 2.0 * force / (math.pi * a)


def hertz_spheres(force, r_star, e_star):
    """Hertz's contact radius a and peak pressure p₀ of two spheres under F."""
    a = (3.0 * force * r_star / (4.0 * e_star)) ** (1.0 / 3.0)
    return a, 3.0 * force / (2.0 * math.pi * a * a)


def cattaneo_traction(x, a, c, mu_p0):
    """Cattaneo's tangential traction q(x) (zero outside the contact)."""
    x = np.asarray(x, float)
    inside = np.abs(x) < a
    slip = np.where(inside, mu_p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None)), 0.0)
    stick = (c / a) * mu_p0 * np.sqrt(np.clip(1.0 - (x / c) ** 2, 0.0, None)) if c > 0 else 0.0
    return np.where(np.abs(x) < c, slip - stick, slip)


def mindlin_traction(r, a, c, mu_p0):
    """Mindlin's tangential traction q(r) between two identical spheres, along Q: the
    cylinders' form with r for x (Johnson, §7.1)."""
    return cattaneo_traction(r, a, c, mu_p0)


# --------------------------------------------------------------------------------------
# Measurements
# --------------------------------------------------------------------------------------


def profile(x, p):
    """From the points (x, p) along a line from the contact's centre, as the Rust test:
    the spacing of the points at the edge (the last interval ending at or beyond a_FE), the
    edge a_FE (the farthest point with a positive pressure) and the pressure at x = 0."""
    touching = x[p > 0.0]
    a_fe = max(touching.max(), 0.0) if touching.size else 0.0
    peak = p[x == 0.0][0]
    xs = np.sort(x)
    beyond = np.flatnonzero(xs[1:] >= a_fe)
    h = xs[beyond[0] + 1] - xs[beyond[0]] if beyond.size else xs[1] - xs[0]
    return h, a_fe, peak


def timed_solve(scenario):
    """The result of a solve and its wall time (s); warns if it did not converge."""
    start = time.perf_counter()
    result = hc.solve(scenario)
    wall = time.perf_counter() - start
    if not result.converged:
        print(f"NOT CONVERGED: {result.message}", file=sys.stderr)
    return result, wall


def hertz_level(dim, n):
    """One Hertz level (cylinders in 2D, spheres in 3D): a dict of the measured values and
    the profile (x, p) along the symmetry line y = 0."""
    case = CYLINDERS if dim == 2 else SPHERES
    arrays = cylinders_mesh(n) if dim == 2 else spheres_mesh(n)
    points = arrays[0]
    result, wall = timed_solve(hertz_scenario(to_mesh(arrays), dim, case["q"]))
    c = result.contact
    at = points[c["node"]]
    on_line = np.ones(len(at), bool) if dim == 2 else at[:, 1] == 0.0
    x, p = at[on_line, 0], c["pressure"][on_line]
    h, a_fe, peak = profile(x, p)
    order = np.argsort(x)
    return {
        "n": n,
        "dofs": result.summary["sizes"]["dofs"],
        "h": h,
        "a": a_fe,
        "peak": peak,
        # The pair's force on the half (quarter) model against the load it carries.
        "force": abs(c["force"][:, dim - 1].sum()) / case["q"],
        "converged": result.converged,
        "message": result.message,
        "time": wall,
        "profile": (x[order], p[order]),
    }


def cattaneo_level(n):
    """The Cattaneo–Mindlin solve at level n: the measured values against the closed form,
    as in the Rust test, and the profile along the interface."""
    k = CATTANEO
    arrays = cattaneo_mesh(n)
    points, _, facets, _ = arrays
    result, wall = timed_solve(cattaneo_scenario(to_mesh(arrays)))
    c = result.contact
    x = points[c["node"], 0]
    force = 2.0 * k["q"]
    r_star, e_star = combined((k["radius"],) * 2, [(k["young"], k["poisson"])] * 2)
    a, p0 = hertz_cylinders(force, r_star, e_star)
    mu = k["mu"]
    big_q = abs(c["force"][:, 0].sum())
    normal = abs(c["force"][:, 1].sum())
    # Q as the upper body's supports apply it (its top and sides, each node once).
    held = np.unique(np.concatenate([facets["upper_top"], facets["upper_sides"]]))
    applied = abs(result.reactions[held, 0].sum())
    ratio = big_q / (mu * force)
    c_exact = a * math.sqrt(1.0 - ratio)
    touching = c["pressure"] > 0.0
    stick = touching & (c["friction_state"] == "stick")
    a_fe = np.abs(x[touching]).max()
    c_fe = np.abs(x[stick]).max() if stick.any() else 0.0
    beyond = x[touching & (x > c_fe)]
    h = beyond.min() - c_fe if beyond.size else float("nan")
    # The traction against Cattaneo's, away from the stick–slip edges (1.5 elements).
    traction = np.abs(c["friction_traction"][:, 0])
    keep = touching & (np.abs(np.abs(x) - c_exact) > 1.5 * h) & (np.abs(x) < a)
    exact = cattaneo_traction(x[keep], a, c_exact, mu * p0)
    errors = np.abs(traction[keep] - exact) / (mu * p0)
    worst = errors.max() if errors.size else float("nan")
    order = np.argsort(x)
    sign = np.sign(c["friction_traction"][:, 0].sum()) or 1.0
    return {
        "n": n,
        "dofs": result.summary["sizes"]["dofs"],
        "force": force,
        "normal": normal,
        "Q": big_q,
        "applied": applied,
        "ratio": ratio,
        "a": a,
        "a_fe": a_fe,
        "p0": p0,
        "c": c_exact,
        "c_fe": c_fe,
        "h": h,
        "worst": worst,
        "worst_at": x[keep][np.argmax(errors)] if errors.size else float("nan"),
        "stick": int(stick.sum()),
        "slip": int((touching & ~stick).sum()),
        "converged": result.converged,
        "message": result.message,
        "time": wall,
        "profile": (
            x[order],
            sign * c["friction_traction"][order, 0],
            c["pressure"][order],
            c["friction_state"][order],
        ),
    }


def cattaneo_spheres_level(n):
    """The Cattaneo–Mindlin solve between two spheres at level n: the measured values
    against the closed form, as in the Rust test, and every in-contact point (r, traction
    along x, state)."""
    k = CATTANEO_SPHERES
    arrays = cattaneo_spheres_mesh(n)
    points, _, facets, _ = arrays
    result, wall = timed_solve(cattaneo_spheres_scenario(to_mesh(arrays)))
    c = result.contact
    at = points[c["node"]]
    force, r_star, e_star = cattaneo_spheres_load()
    a, p0 = hertz_spheres(force, r_star, e_star)
    mu = k["mu"]
    big_q = abs(c["force"][:, 0].sum())
    normal = abs(c["force"][:, 2].sum())
    # Q as the upper body's supports apply it (its top and sides, each node once).
    held = np.unique(np.concatenate(
        [facets[f"upper_{name}"].ravel() for name in ("top", "right", "back")]))
    applied = abs(result.reactions[held, 0].sum())
    ratio = big_q / (mu * force)
    c_exact = a * (1.0 - ratio) ** (1.0 / 3.0)
    touching = c["pressure"] > 0.0
    stick = c["friction_state"] == "stick"
    rho = np.hypot(at[:, 0], at[:, 1])
    a_fe = rho[touching].max()
    # Along the symmetry line y = 0.
    line = touching & (at[:, 1] == 0.0)
    x = np.abs(at[:, 0])
    c_fe = x[line & stick].max() if (line & stick).any() else 0.0
    beyond = x[line & (x > c_fe)]
    h = beyond.min() - c_fe if beyond.size else float("inf")
    # The traction along x against Mindlin's, away from the stick–slip edge (1.5
    # elements) and inside a.
    traction = np.abs(c["friction_traction"][:, 0])
    keep = touching & (np.abs(rho - c_exact) > 1.5 * h) & (rho < a)
    exact = mindlin_traction(rho[keep], a, c_exact, mu * p0)
    errors = np.abs(traction[keep] - exact) / (mu * p0)
    worst = errors.max() if errors.size else float("nan")
    sign = np.sign(c["friction_traction"][:, 0].sum()) or 1.0
    return {
        "n": n,
        "dofs": result.summary["sizes"]["dofs"],
        "force": force,
        "normal": normal,
        "Q": big_q,
        "applied": applied,
        "ratio": ratio,
        "a": a,
        "a_fe": a_fe,
        "p0": p0,
        "c": c_exact,
        "c_fe": c_fe,
        "h": h,
        "worst": worst,
        "worst_at": rho[keep][np.argmax(errors)] if errors.size else float("nan"),
        "compared": int(keep.sum()),
        "stick": int((line & stick).sum()),
        "slip": int((line & ~stick).sum()),
        "converged": result.converged,
        "message": result.message,
        "time": wall,
        "points": (rho[touching], sign * c["friction_traction"][touching, 0],
                   c["friction_state"][touching]),
    }


# --------------------------------------------------------------------------------------
# Tables
# --------------------------------------------------------------------------------------


def hertz_table(title, exact, rows):
    """The refinement table of a Hertz case."""
    a, p0 = exact
    lines = [
        title,
        "",
        "| n | DOFs | h at a | a_FE | (a_FE − a)/h | p₀_FE | p₀ error | pair force / load − 1 "
        "| converged | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for row in rows:
        lines.append(
            f"| {row['n']} | {row['dofs']} | {row['h']:.5f} | {row['a']:.5f} | "
            f"{(row['a'] - a) / row['h']:+.2f} | {row['peak']:.5f} | "
            f"{100.0 * (row['peak'] / p0 - 1.0):+.2f} % | {row['force'] - 1.0:+.1e} | "
            f"{'yes' if row['converged'] else 'NO'} | {row['time']:.1f} |"
        )
    return "\n".join(lines) + "\n"


def cattaneo_table(row):
    """The computed values of a Cattaneo–Mindlin level against the closed form."""
    k = CATTANEO
    return "\n".join(
        [
            f"Cattaneo–Mindlin (n = {row['n']}, {row['dofs']} DOFs, "
            f"{'converged' if row['converged'] else 'NOT CONVERGED'}, {row['time']:.1f} s): "
            f"P = {row['force']:g} N/m (pair {row['normal']:.6g}), μ = {k['mu']}, "
            f"p₀ = {row['p0']:.5f} Pa",
            "",
            "| | computed | Cattaneo–Mindlin |",
            "|---|---|---|",
            f"| Q (pair; supports {row['applied']:.6e}) | {row['Q']:.4e} N/m = "
            f"{row['ratio']:.3f} μP | |",
            f"| half-width a | {row['a_fe']:.5f} m | {row['a']:.5f} m |",
            f"| stick half-width c | {row['c_fe']:.5f} m (h = {row['h']:.5f} there; "
            f"(c_FE − c)/h = {(row['c_fe'] - row['c']) / row['h']:+.2f}) | {row['c']:.5f} m |",
            f"| traction, largest error away from the stick–slip edges | "
            f"{100.0 * row['worst']:.2f} % of μp₀ (at x = {row['worst_at']:+.4f} m) | |",
            f"| points stick / slip | {row['stick']} / {row['slip']} | |",
        ]
    ) + "\n"


def cattaneo_spheres_table(rows):
    """The levels of Cattaneo–Mindlin between two spheres against the closed form."""
    k = CATTANEO_SPHERES
    force, r_star, e_star = cattaneo_spheres_load()
    a, p0 = hertz_spheres(force, r_star, e_star)
    lines = [
        f"Cattaneo–Mindlin, two spheres: R = {k['radius']:g} m, E = {k['young']:g} Pa, "
        f"ν = {k['poisson']}, μ = {k['mu']}, s = {k['shear']:g} m; P = {force:.6e} N, "
        f"a = {a:.5f} m, p₀ = {p0:.5f} Pa; c = a (1 − Q/(μP))^(1/3); traction error: "
        f"largest |q_x − Mindlin's| / μp₀ at the in-contact points with r < a and "
        f"|r − c| > 1.5 h; stick / slip: the in-contact points on y = 0",
        "",
        "| n | DOFs | Q (pair) | Q/(μP) | Q (supports) / Q (pair) − 1 | a_FE | c | c_FE "
        "| h at c_FE | (c_FE − c)/h | traction error (at r) | points compared "
        "| stick / slip on y = 0 | converged | time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for row in rows:
        lines.append(
            f"| {row['n']} | {row['dofs']} | {row['Q']:.6e} N | {row['ratio']:.3f} | "
            f"{row['applied'] / row['Q'] - 1.0:+.1e} | {row['a_fe']:.5f} | {row['c']:.5f} | "
            f"{row['c_fe']:.5f} | {row['h']:.5f} | {(row['c_fe'] - row['c']) / row['h']:+.2f} | "
            f"{100.0 * row['worst']:.2f} % of μp₀ (r = {row['worst_at']:.4f} m) | "
            f"{row['compared']} | {row['stick']} / {row['slip']} | "
            f"{'yes' if row['converged'] else 'NO'} | {row['time']:.1f} |"
        )
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------------------
# Figures
# --------------------------------------------------------------------------------------


def pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def pressure_figure(exact, rows, title, xlabel, path):
    """The FE contact pressure of each level against x, Hertz's ellipse overlaid."""
    plt = pyplot()
    a, p0 = exact
    fig, ax = plt.subplots(figsize=(7.0, 4.2), dpi=110)
    r = np.linspace(0.0, a, 400)
    ax.plot(r, p0 * np.sqrt(1.0 - (r / a) ** 2), "k-", lw=2.0,
            label=f"Hertz (a = {a:.4f} m, p₀ = {p0:.4f} Pa)")
    for row, marker in zip(rows, "osd^v<>"):
        x, p = row["profile"]
        keep = x <= 1.6 * a
        ax.plot(x[keep], p[keep], marker + "--", ms=3.5, lw=0.8,
                label=f"n = {row['n']} ({row['dofs']} DOFs)")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("contact pressure p (Pa)")
    ax.set_title(title)
    ax.set_xlim(0.0, 1.6 * a)
    ax.set_ylim(0.0, 1.15 * max(p0, max(row["peak"] for row in rows)))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def cattaneo_figure(row, path):
    """The tangential traction against x with Cattaneo's q(x), the slip zones shaded, the
    FE points coloured by state, and μp for reference."""
    plt = pyplot()
    mu, a, c, p0 = CATTANEO["mu"], row["a"], row["c"], row["p0"]
    x, t, p, state = row["profile"]
    fig, ax = plt.subplots(figsize=(7.5, 4.4), dpi=110)
    for k, (lo, hi) in enumerate(((-a, -c), (c, a))):
        ax.axvspan(lo, hi, color="tab:orange", alpha=0.12, lw=0,
                   label="slip zones c ≤ |x| ≤ a (Cattaneo)" if k == 0 else None)
    xx = np.linspace(-1.3 * a, 1.3 * a, 801)
    ax.plot(xx, mu * p0 * np.sqrt(np.clip(1.0 - (xx / a) ** 2, 0.0, None)), "k:", lw=1.2,
            label="μ p, Hertz")
    ax.plot(xx, cattaneo_traction(xx, a, c, mu * p0), "k-", lw=2.0,
            label=f"Cattaneo q(x) (c = {c:.4f} m)")
    near = np.abs(x) <= 1.3 * a
    ax.plot(x[near], mu * p[near], "--", color="tab:green", lw=1.0, label="μ p, FE")
    ax.plot(x[near], t[near], "-", color="tab:blue", lw=0.8)
    for name, colour, marker in (("stick", "tab:blue", "o"), ("slip", "tab:red", "s"),
                                 ("separated", "tab:gray", "x")):
        sel = near & (state == name)
        if sel.any():
            ax.plot(x[sel], t[sel], marker, color=colour, ms=4, ls="none",
                    label=f"FE traction, {name} ({sel.sum()})")
    ax.text(0.5 * (c + a), 0.04 * mu * p0, "slip", ha="center", color="tab:orange")
    ax.text(-0.5 * (c + a), 0.04 * mu * p0, "slip", ha="center", color="tab:orange")
    ax.text(0.0, 0.04 * mu * p0, "stick", ha="center", color="tab:blue")
    ax.set_xlabel("x (m), along the interface")
    ax.set_ylabel("tangential traction q (Pa)")
    ax.set_title(f"Cattaneo–Mindlin: two cylinders, Q = {row['ratio']:.3f} μP, "
                 f"n = {row['n']} ({row['dofs']} DOFs)", fontsize=11)
    ax.set_xlim(-1.3 * a, 1.3 * a)
    ax.set_ylim(0.0, 1.25 * mu * p0)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=7.5)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def cattaneo_spheres_figure(row, path):
    """The tangential traction along x of every in-contact point against its radius r,
    stick and slip marked apart, with Mindlin's q(r), μp (Hertz) and the slip annulus."""
    plt = pyplot()
    mu, a, c, p0 = CATTANEO_SPHERES["mu"], row["a"], row["c"], row["p0"]
    rho, t, state = row["points"]
    fig, ax = plt.subplots(figsize=(7.5, 4.4), dpi=110)
    ax.axvspan(c, a, color="tab:orange", alpha=0.12, lw=0,
               label="slip annulus c ≤ r ≤ a (Mindlin)")
    rr = np.linspace(0.0, 1.3 * a, 801)
    ax.plot(rr, mu * p0 * np.sqrt(np.clip(1.0 - (rr / a) ** 2, 0.0, None)), "k:", lw=1.2,
            label="μ p, Hertz")
    ax.plot(rr, mindlin_traction(rr, a, c, mu * p0), "k-", lw=2.0,
            label=f"Mindlin q(r) (c = {c:.4f} m)")
    for name, colour, marker in (("stick", "tab:blue", "o"), ("slip", "tab:red", "s")):
        sel = state == name
        if sel.any():
            ax.plot(rho[sel], t[sel], marker, color=colour, ms=3.5, ls="none", alpha=0.8,
                    clip_on=False, label=f"FE traction, {name} ({sel.sum()} points)")
    ax.text(0.5 * (c + a), 0.04 * mu * p0, "slip", ha="center", color="tab:orange")
    ax.text(0.5 * c, 0.04 * mu * p0, "stick", ha="center", color="tab:blue")
    ax.set_xlabel("r (m), distance from the contact's centre")
    ax.set_ylabel("tangential traction along x, q (Pa)")
    ax.set_title(f"Cattaneo–Mindlin: two spheres, Q = {row['ratio']:.3f} μP, "
                 f"n = {row['n']} ({row['dofs']} DOFs)", fontsize=11)
    ax.set_xlim(0.0, 1.3 * a)
    ax.set_ylim(0.0, 1.25 * mu * p0)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=7.5)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


# --------------------------------------------------------------------------------------
# Main
# --------------------------------------------------------------------------------------


def run_hertz(dim, levels, out):
    """The refinement table and the pressure figure of the cylinders (2D) or spheres (3D)."""
    case = CYLINDERS if dim == 2 else SPHERES
    mats = [MATERIALS["upper"], MATERIALS["lower"]]
    r_star, e_star = combined(case["radii"], mats)
    force = (2.0 if dim == 2 else 4.0) * case["q"]
    exact = (hertz_cylinders if dim == 2 else hertz_spheres)(force, r_star, e_star)
    rows = []
    for n in levels:
        rows.append(hertz_level(dim, n))
        row = rows[-1]
        print(f"  {'cylinders' if dim == 2 else 'spheres'} n = {n}: {row['dofs']} DOFs, "
              f"a = {row['a']:.5f}, p0 = {row['peak']:.5f}, {row['message']}, "
              f"{row['time']:.1f} s", file=sys.stderr)
    unit = "N/m" if dim == 2 else "N"
    name = "cylinders" if dim == 2 else "spheres"
    title = (f"Hertz, two {name}: F = {force:g} {unit}, R* = {r_star:.4f} m, "
             f"E* = {e_star:.4f} Pa, a = {exact[0]:.5f} m, p₀ = {exact[1]:.5f} Pa")
    if dim == 2:
        pressure_figure(exact, rows, "Hertz: two elastic cylinders (plane strain)",
                        "x (m)", out / "pressure-cylinders.png")
    else:
        pressure_figure(exact, rows, "Hertz: two elastic spheres (quarter models)",
                        "x (m), along the symmetry line y = 0", out / "pressure-spheres.png")
    return hertz_table(title, exact, rows)


def run_cattaneo_spheres(levels, out):
    """The table of Cattaneo–Mindlin between two spheres and the traction figure of its
    last level."""
    rows = []
    for n in levels:
        rows.append(cattaneo_spheres_level(n))
        row = rows[-1]
        print(f"  Cattaneo–Mindlin spheres n = {n}: {row['dofs']} DOFs, "
              f"Q = {row['ratio']:.3f} μP, {row['message']}, {row['time']:.1f} s",
              file=sys.stderr)
    cattaneo_spheres_figure(rows[-1], out / "cattaneo-mindlin-spheres.png")
    return cattaneo_spheres_table(rows)


def write_meshes():
    """The meshes of the committed scenarios, written to scenarios/meshes/."""
    folder = ROOT / "scenarios" / "meshes"
    meshes = (
        ("two-cylinders", cylinders_mesh),
        ("cattaneo-mindlin", cattaneo_mesh),
        ("two-spheres", spheres_mesh),
        ("cattaneo-spheres", cattaneo_spheres_mesh),
    )
    for stem, build in meshes:
        path = folder / f"{stem}.msh"
        write_msh(build(COMMITTED[stem]), path)
        print(f"wrote {path.relative_to(ROOT)} (n = {COMMITTED[stem]}, "
              f"{path.stat().st_size / 1024:.0f} kB)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--levels-cylinders", type=int, nargs="*", default=[32, 64, 128])
    parser.add_argument("--levels-spheres", type=int, nargs="*", default=[8, 12, 16])
    parser.add_argument("--cattaneo", type=int, nargs="*", default=[64],
                        help="levels of Cattaneo–Mindlin (n: 2n × n cells per body)")
    parser.add_argument("--cattaneo-spheres", type=int, nargs="*", default=[12],
                        help="levels of Cattaneo–Mindlin between two spheres (n: 4n³ "
                             "cuboids per body; 16 takes about 1.5 min)")
    parser.add_argument("--skip-spheres", action="store_true")
    parser.add_argument("--skip-cattaneo-spheres", action="store_true")
    parser.add_argument("--out", default="out/two-bodies")
    parser.add_argument("--write-meshes", action="store_true",
                        help="only write the meshes of the committed scenario files")
    args = parser.parse_args()
    if args.write_meshes:
        write_meshes()
        return
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    text = []
    if args.levels_cylinders:
        text.append(run_hertz(2, args.levels_cylinders, out))
    if args.levels_spheres and not args.skip_spheres:
        text.append(run_hertz(3, args.levels_spheres, out))
    for k, n in enumerate(args.cattaneo):
        row = cattaneo_level(n)
        print(f"  Cattaneo–Mindlin n = {n}: {row['dofs']} DOFs, {row['message']}, "
              f"{row['time']:.1f} s", file=sys.stderr)
        text.append(cattaneo_table(row))
        if k == len(args.cattaneo) - 1:
            cattaneo_figure(row, out / "cattaneo-mindlin.png")
    if args.cattaneo_spheres and not args.skip_cattaneo_spheres:
        text.append(run_cattaneo_spheres(args.cattaneo_spheres, out))
    report = "\n".join(text)
    (out / "table.md").write_text(report)
    print(report)


if __name__ == "__main__":
    main()
