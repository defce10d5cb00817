"""Generates the Gmsh test meshes of hemicontact (format 4.1, ASCII and binary).

The .msh files are committed: the tests and CI do not need Gmsh. Run this script only to
regenerate them (the output depends on the Gmsh version; these were made with 4.15):

    python3 -m venv /tmp/gmsh-venv && /tmp/gmsh-venv/bin/pip install gmsh
    /tmp/gmsh-venv/bin/python crates/hemicontact/tests/data/gmsh/generate.py

(If `import gmsh` fails for missing system libraries: apt-get install libglu1-mesa
libxcursor1 libxft2 libxinerama1 libxrender1.)

Meshes (all P1: triangles in 2D, tetrahedra in 3D; boundary parts = physical groups of
dimension d - 1, and one physical group of dimension d for the domain):

- square.msh, square-binary.msh: the square [0,4]^2, physical lines bottom, right, top,
  left (as the rectangle generator names them) and the surface "domain"; unstructured,
  element size 1.
- cube.msh, cube-binary.msh: the cube [0,1]^3, physical surfaces left (x = 0), right
  (x = 1), front (y = 0), back (y = 1), bottom (z = 0), top (z = 1) (as the box generator)
  and the volume "body"; element size 0.5.
- ../../../../../scenarios/meshes/half-disc.msh: the lower half of the disc of radius 1
  centred at (0, 1): physical lines "contact" (the arc) and "top" (the flat side y = 1), the
  surface "body"; element size 0.1 (0.05 on the arc). Used by scenarios/half-disc.toml.
- ../../../../../scenarios/meshes/punch-on-block.msh: two bodies meshed apart, with no
  shared node: the block [0,1] x [0,0.5] (surface "block"; physical lines "block_bottom",
  "block_top", "block_sides"; element size 0.1 at the bottom, 0.025 at the top) and the
  punch [0.25,0.75] x [0.5,0.7] on it (surface "punch"; lines "punch_bottom", "punch_top",
  "punch_sides"; element size 0.02 at the bottom, 0.05 at the top): non-matching meshes
  along the interface y = 0.5. Used by scenarios/punch-on-block.toml.

- ../../../../../scenarios/meshes/fault.msh: two blocks meshed apart, one on the other:
  [0,4] x [0,1] (surface "host"; lines "host_bottom", "host_top", "host_sides"; element
  size 0.125 at the top, 0.25 at the bottom) and [0,4] x [1,2] (surface "upper"; lines
  "upper_bottom", "upper_top", "upper_sides"; element size 0.1 at the bottom, 0.25 at the
  top): non-matching meshes along the fault y = 1. Used by scenarios/fault.toml.

- crack.msh: the block [0,2] x [0,1] (surface "body"; lines "bottom", "top", "sides") cut by
  the crack y = 0.5, 0.5 <= x <= 1.5 (element size 0.125, 0.0625 at the crack's tips): the
  line "crack_lower" embedded in the surface, then Gmsh's Crack plugin duplicates its inner
  nodes for the cells above it, whose faces form the physical line "crack_upper". The two
  faces' nodes coincide; the tips are shared.

- two-blocks.msh: the blocks [0,1] x [0,0.5] ("lower") and [0,1] x [0.5,1] ("upper"),
  meshed apart from their own points (not merged), so that their nodes on the interface
  y = 0.5 coincide: physical lines "lower_bottom", "lower_top", "lower_sides",
  "upper_bottom", "upper_top", "upper_sides"; element size 0.25.

The files with errors (bad-*.msh) are hand-written variants of tiny.msh (a unit square of
two triangles, also hand-written); see tests/input/gmsh.rs for the error each must give.
"""

import os

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIO_MESHES = os.path.normpath(os.path.join(HERE, "../../../../../scenarios/meshes"))


def write(path, binary):
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
    gmsh.write(path)
    print(os.path.relpath(path), os.path.getsize(path), "bytes")


def square():
    gmsh.model.add("square")
    g = gmsh.model.geo
    p = [g.addPoint(x, y, 0, 1.0) for x, y in [(0, 0), (4, 0), (4, 4), (0, 4)]]
    lines = [g.addLine(p[i], p[(i + 1) % 4]) for i in range(4)]
    surface = g.addPlaneSurface([g.addCurveLoop(lines)])
    g.synchronize()
    for line, name in zip(lines, ["bottom", "right", "top", "left"]):
        gmsh.model.addPhysicalGroup(1, [line], name=name)
    gmsh.model.addPhysicalGroup(2, [surface], name="domain")
    gmsh.model.mesh.generate(2)
    write(os.path.join(HERE, "square.msh"), False)
    write(os.path.join(HERE, "square-binary.msh"), True)
    gmsh.model.remove()


def cube():
    gmsh.model.add("cube")
    box = gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    names = {}
    for _, s in gmsh.model.getBoundary([(3, box)], oriented=False):
        x, y, z = gmsh.model.occ.getCenterOfMass(2, s)
        for name, (axis, value) in {
            "left": (0, 0.0), "right": (0, 1.0), "front": (1, 0.0),
            "back": (1, 1.0), "bottom": (2, 0.0), "top": (2, 1.0),
        }.items():
            if abs((x, y, z)[axis] - value) < 1e-9:
                names[name] = s
    for name in ["left", "right", "front", "back", "bottom", "top"]:
        gmsh.model.addPhysicalGroup(2, [names[name]], name=name)
    gmsh.model.addPhysicalGroup(3, [box], name="body")
    gmsh.model.mesh.setSize(gmsh.model.getEntities(0), 0.5)
    gmsh.model.mesh.generate(3)
    write(os.path.join(HERE, "cube.msh"), False)
    write(os.path.join(HERE, "cube-binary.msh"), True)
    gmsh.model.remove()


def half_disc():
    gmsh.model.add("half-disc")
    g = gmsh.model.geo
    fine, coarse = 0.05, 0.1
    centre = g.addPoint(0, 1, 0, coarse)
    right = g.addPoint(1, 1, 0, fine)
    bottom = g.addPoint(0, 0, 0, fine)
    left = g.addPoint(-1, 1, 0, fine)
    arc1 = g.addCircleArc(right, centre, bottom)
    arc2 = g.addCircleArc(bottom, centre, left)
    top = g.addLine(left, right)
    surface = g.addPlaneSurface([g.addCurveLoop([arc1, arc2, top])])
    g.synchronize()
    gmsh.model.addPhysicalGroup(1, [arc1, arc2], name="contact")
    gmsh.model.addPhysicalGroup(1, [top], name="top")
    gmsh.model.addPhysicalGroup(2, [surface], name="body")
    gmsh.model.mesh.generate(2)
    os.makedirs(SCENARIO_MESHES, exist_ok=True)
    write(os.path.join(SCENARIO_MESHES, "half-disc.msh"), False)
    gmsh.model.remove()


def rectangle(g, x0, y0, x1, y1, size, top_size):
    """The lines bottom, right, top, left of a rectangle and its surface; element size
    `size` at the bottom corners, `top_size` at the top corners."""
    corners = [(x0, y0, size), (x1, y0, size), (x1, y1, top_size), (x0, y1, top_size)]
    p = [g.addPoint(x, y, 0, h) for x, y, h in corners]
    lines = [g.addLine(p[i], p[(i + 1) % 4]) for i in range(4)]
    return lines, g.addPlaneSurface([g.addCurveLoop(lines)])


def name_blocks(blocks):
    """Synchronizes, names each rectangle's lines `NAME_bottom`, `NAME_top`, `NAME_sides`
    and its surface `NAME`, and meshes."""
    gmsh.model.geo.synchronize()
    for name, lines, surface in blocks:
        bottom, right, top, left = lines
        gmsh.model.addPhysicalGroup(1, [bottom], name=f"{name}_bottom")
        gmsh.model.addPhysicalGroup(1, [top], name=f"{name}_top")
        gmsh.model.addPhysicalGroup(1, [left, right], name=f"{name}_sides")
        gmsh.model.addPhysicalGroup(2, [surface], name=name)
    gmsh.model.mesh.generate(2)


def punch_on_block():
    gmsh.model.add("punch-on-block")
    g = gmsh.model.geo
    block_lines, block = rectangle(g, 0.0, 0.0, 1.0, 0.5, 0.1, 0.025)
    punch_lines, punch = rectangle(g, 0.25, 0.5, 0.75, 0.7, 0.02, 0.05)
    name_blocks([("block", block_lines, block), ("punch", punch_lines, punch)])
    os.makedirs(SCENARIO_MESHES, exist_ok=True)
    write(os.path.join(SCENARIO_MESHES, "punch-on-block.msh"), False)
    gmsh.model.remove()


def fault():
    gmsh.model.add("fault")
    g = gmsh.model.geo
    host_lines, host = rectangle(g, 0.0, 0.0, 4.0, 1.0, 0.25, 0.125)
    upper_lines, upper = rectangle(g, 0.0, 1.0, 4.0, 2.0, 0.1, 0.25)
    name_blocks([("host", host_lines, host), ("upper", upper_lines, upper)])
    write(os.path.join(SCENARIO_MESHES, "fault.msh"), False)
    gmsh.model.remove()


def crack():
    gmsh.model.add("crack")
    g = gmsh.model.geo
    p = [g.addPoint(x, y, 0, 0.125) for x, y in [(0, 0), (2, 0), (2, 1), (0, 1)]]
    lines = [g.addLine(p[i], p[(i + 1) % 4]) for i in range(4)]
    surface = g.addPlaneSurface([g.addCurveLoop(lines)])
    tips = [g.addPoint(x, 0.5, 0, 0.0625) for x in (0.5, 1.5)]
    line = g.addLine(*tips)
    g.synchronize()
    gmsh.model.mesh.embed(1, [line], 2, surface)
    bottom, right, top, left = lines
    gmsh.model.addPhysicalGroup(1, [bottom], name="bottom")
    gmsh.model.addPhysicalGroup(1, [top], name="top")
    gmsh.model.addPhysicalGroup(1, [left, right], name="sides")
    lower = gmsh.model.addPhysicalGroup(1, [line], name="crack_lower")
    gmsh.model.addPhysicalGroup(2, [surface], name="body")
    gmsh.model.mesh.generate(2)
    # New nodes for the cells on one side of the crack, their faces in a new group (the
    # plugin's normal is that of the plane of a 1D crack).
    gmsh.plugin.setNumber("Crack", "Dimension", 1)
    gmsh.plugin.setNumber("Crack", "PhysicalGroup", lower)
    gmsh.plugin.setNumber("Crack", "NewPhysicalGroup", 100)
    gmsh.plugin.setNumber("Crack", "NormalX", 0)
    gmsh.plugin.setNumber("Crack", "NormalY", 0)
    gmsh.plugin.setNumber("Crack", "NormalZ", 1)
    gmsh.plugin.run("Crack")
    gmsh.model.setPhysicalName(1, 100, "crack_upper")
    write(os.path.join(HERE, "crack.msh"), False)
    gmsh.model.remove()


def two_blocks():
    gmsh.model.add("two-blocks")
    g = gmsh.model.geo
    lower_lines, lower = rectangle(g, 0.0, 0.0, 1.0, 0.5, 0.25, 0.25)
    upper_lines, upper = rectangle(g, 0.0, 0.5, 1.0, 1.0, 0.25, 0.25)
    name_blocks([("lower", lower_lines, lower), ("upper", upper_lines, upper)])
    write(os.path.join(HERE, "two-blocks.msh"), False)
    gmsh.model.remove()


def main():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    square()
    cube()
    half_disc()
    punch_on_block()
    fault()
    crack()
    two_blocks()
    gmsh.finalize()


if __name__ == "__main__":
    main()
