#!/usr/bin/env python3
"""Reads a hemicontact .vtu with VTK's own reader and compares it with values computed in Rust.

Usage: check_vtk.py FILE EXPECTED_JSON

EXPECTED_JSON holds `points` and `displacement` (N × 3), `cells`, `point_fields` and
`cell_fields` ([name, components] in order), `title`, `time` (the load factor) and `version`.

Checks: the XML root declares `compressor="vtkZLibDataCompressor"` and
`header_type="UInt64"`; vtkXMLUnstructuredGridReader reads it without error; the point and
cell arrays are exactly the expected names, in order, with their numbers of components; the
FieldData holds `TITLE`, `hemicontact_version`, `units` and `codes` as NUL-terminated UTF-8
bytes, and `TimeValue`; the points and the displacement equal the expected values exactly.

Exit codes: 0 pass, 1 a check failed, 77 vtk (or numpy) is not importable (skip).
"""
import json
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
    print(f"check_vtk: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def xml_root(path):
    """The attributes of the VTKFile element (the XML before the appended data)."""
    raw = open(path, "rb").read()
    head = raw[: raw.index(b"<AppendedData")].decode()
    return ET.fromstring(head + "</VTKFile>").attrib


def text(fd, name):
    a = fd.GetAbstractArray(name)
    if a is None:
        fail(f"no FieldData array {name}")
    if a.GetDataTypeAsString() != "unsigned char":
        fail(f"{name} is {a.GetDataTypeAsString()}, expected unsigned char")
    b = bytes(vtk_to_numpy(a))
    if not b.endswith(b"\0"):
        fail(f"{name} does not end in NUL")
    return b[:-1].decode("utf-8")


def main():
    path, expected = sys.argv[1], json.load(open(sys.argv[2]))
    root = xml_root(path)
    if root.get("compressor") != "vtkZLibDataCompressor":
        fail(f"compressor {root.get('compressor')!r}")
    if root.get("header_type") != "UInt64":
        fail(f"header_type {root.get('header_type')!r}")

    errors = vtk.vtkStringOutputWindow()
    vtk.vtkOutputWindow.SetInstance(errors)
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0 or "ERROR" in errors.GetOutput():
        fail(f"VTK reader error: {errors.GetOutput()}")
    g = r.GetOutput()

    pts = vtk_to_numpy(g.GetPoints().GetData())
    if g.GetNumberOfCells() != expected["cells"]:
        fail(f"{g.GetNumberOfCells()} cells, expected {expected['cells']}")
    for kind, data in (("point_fields", g.GetPointData()), ("cell_fields", g.GetCellData())):
        got = [[data.GetArrayName(i), data.GetArray(i).GetNumberOfComponents()]
               for i in range(data.GetNumberOfArrays())]
        if got != expected[kind]:
            fail(f"{kind}: {got}, expected {expected[kind]}")

    fd = g.GetFieldData()
    if text(fd, "TITLE") != expected["title"]:
        fail(f"TITLE {text(fd, 'TITLE')!r}")
    if text(fd, "hemicontact_version") != expected["version"]:
        fail(f"hemicontact_version {text(fd, 'hemicontact_version')!r}")
    units = text(fd, "units").splitlines()
    names = [f[0] for f in expected["point_fields"] + expected["cell_fields"]]
    if [u.split(":")[0] for u in units] != names:
        fail(f"units {units}")
    if "2 slip" not in text(fd, "codes"):
        fail(f"codes {text(fd, 'codes')!r}")
    t = fd.GetArray("TimeValue")
    if t is None or t.GetNumberOfTuples() != 1 or t.GetValue(0) != expected["time"]:
        fail(f"TimeValue {None if t is None else vtk_to_numpy(t)}")

    want = np.array(expected["points"])
    if pts.shape != want.shape or not np.array_equal(pts, want):
        fail("points differ from the mesh nodes")
    u = vtk_to_numpy(g.GetPointData().GetArray("displacement"))
    if not np.array_equal(u, np.array(expected["displacement"])):
        fail(f"displacement differs, max {np.abs(u - np.array(expected['displacement'])).max()}")
    print(f"check_vtk: ok: {len(pts)} points, {g.GetNumberOfCells()} cells")


if __name__ == "__main__":
    main()
