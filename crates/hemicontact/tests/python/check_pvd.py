#!/usr/bin/env python3
"""Reads a hemicontact .pvd collection of load steps and each dataset it lists with VTK.

Usage: check_pvd.py FILE N PUSH_X PUSH_Y

Checks: the collection is a `VTKFile` of type `Collection` with N `DataSet` entries whose
`timestep` values increase; each `file` is relative, exists beside the collection and is read
by vtkXMLGenericDataObjectReader as an unstructured grid whose `TimeValue` equals the
timestep; at the top side (y = 1) the displacement is the prescribed timestep × (PUSH_X,
PUSH_Y).

Exit codes: 0 pass, 1 a check failed, 77 vtk (or numpy) is not importable (skip).
"""
import os
import sys
import xml.etree.ElementTree as ET

try:
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"skipped: vtk not available ({e})", file=sys.stderr)
    sys.exit(77)


def fail(msg):
    print(f"check_pvd: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def main():
    path, n = sys.argv[1], int(sys.argv[2])
    push = np.array([float(sys.argv[3]), float(sys.argv[4]), 0.0])
    root = ET.parse(path).getroot()
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        fail(f"root {root.tag} {root.attrib}")
    sets = root.findall("./Collection/DataSet")
    if len(sets) != n:
        fail(f"{len(sets)} datasets, expected {n}")
    times = [float(s.get("timestep")) for s in sets]
    if any(b <= a for a, b in zip(times, times[1:])):
        fail(f"timesteps not increasing: {times}")
    folder = os.path.dirname(os.path.abspath(path))
    for s, t in zip(sets, times):
        rel = s.get("file")
        if os.path.isabs(rel):
            fail(f"absolute path {rel}")
        file = os.path.join(folder, rel)
        if not os.path.isfile(file):
            fail(f"{rel} does not exist beside the collection")
        r = vtk.vtkXMLGenericDataObjectReader()
        r.SetFileName(file)
        r.Update()
        g = r.GetOutput()
        if not g.IsA("vtkUnstructuredGrid"):
            fail(f"{rel} is a {g.GetClassName()}")
        tv = g.GetFieldData().GetArray("TimeValue")
        if tv is None or tv.GetValue(0) != t:
            fail(f"{rel}: TimeValue {None if tv is None else tv.GetValue(0)}, timestep {t}")
        pts = vtk_to_numpy(g.GetPoints().GetData())
        u = vtk_to_numpy(g.GetPointData().GetArray("displacement"))
        top = np.abs(pts[:, 1] - 1.0) < 1e-12
        if not top.any():
            fail(f"{rel}: no node at y = 1")
        if np.abs(u[top] - t * push).max() > 1e-15:
            fail(f"{rel}: top displacement {u[top][0]}, expected {t * push}")
    print(f"check_pvd: ok: {n} datasets at {times}")


if __name__ == "__main__":
    main()
