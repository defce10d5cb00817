#!/usr/bin/env python3
"""Reads hemicontact .vtu files with meshio and with VTK's own reader and compares them.

Usage: check_readers.py FILE...

Checks, for every file: each `<DataArray format="appended">` has an offset of its own (no two
arrays share one); meshio (`meshio.read`) and `vtkXMLUnstructuredGridReader` read the same
points, the same cell connectivity, and the same point, cell and field arrays: the same
names, the same dtype, the same shape (tuples × components) and the same bytes (values
equal exactly, NaN included).

meshio converts raw appended data to base64 before reading it and finds the array of each
block by its offset; if that lookup lands on the wrong array, meshio silently returns one
array's values under another's name. The byte comparison with VTK, which reads each array
at its own offset, is what catches it.

Exit codes: 0 pass, 1 a check failed, 77 meshio, vtk or numpy is not importable (skip).
"""
import re
import sys
import xml.etree.ElementTree as ET

try:
    import meshio
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"skipped: meshio or vtk not available ({e})", file=sys.stderr)
    sys.exit(77)


def fail(path, msg):
    print(f"check_readers: FAIL: {path}: {msg}", file=sys.stderr)
    sys.exit(1)


def appended_arrays(path):
    """(section, name, offset) of every appended DataArray, in document order."""
    raw = open(path, "rb").read()
    start = re.search(rb"<AppendedData[^>]*>", raw)
    if start is None:
        fail(path, "no <AppendedData> element")
    root = ET.fromstring(raw[: start.start()].decode() + "</VTKFile>")
    out = []
    for parent in root.iter():
        for da in parent.findall("DataArray"):
            if da.get("format") == "appended":
                out.append((parent.tag, da.get("Name"), int(da.get("offset"))))
    return out


def as_table(a, n_components=None):
    """A numpy array as (tuples, components), C-contiguous; by default as many components
    as the array has entries per first index (1 for a 1-D array)."""
    a = np.ascontiguousarray(np.asarray(a))
    if n_components is None:
        n_components = int(np.prod(a.shape[1:], dtype=np.int64)) if a.ndim > 1 else 1
    return a.reshape(-1, n_components) if a.size else a.reshape(0, n_components)


def vtk_table(arr):
    return as_table(vtk_to_numpy(arr), arr.GetNumberOfComponents())


def same(path, what, m, v):
    """meshio's array m and VTK's v: same dtype, shape and bytes."""
    if m.dtype != v.dtype:
        fail(path, f"{what}: meshio dtype {m.dtype}, VTK {v.dtype}")
    if m.shape != v.shape:
        fail(path, f"{what}: meshio shape {m.shape}, VTK {v.shape}")
    if m.tobytes() != v.tobytes():
        bad = np.flatnonzero(
            (m.view(np.uint8).reshape(len(m), -1) != v.view(np.uint8).reshape(len(v), -1)).any(
                axis=1
            )
        )
        k = int(bad[0])
        fail(
            path,
            f"{what}: meshio and VTK differ in {len(bad)} of {len(m)} tuples; first at "
            f"tuple {k}: meshio {m[k].tolist()}, VTK {v[k].tolist()}",
        )


def check(path):
    arrays = appended_arrays(path)
    seen = {}
    for section, name, offset in arrays:
        if offset in seen:
            fail(path, f"{section} {name} shares the offset {offset} with {seen[offset]}")
        seen[offset] = f"{section} {name}"

    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    if g is None or g.GetNumberOfPoints() == 0:
        fail(path, "VTK read no points")
    m = meshio.read(path)

    same(path, "points", as_table(m.points), vtk_table(g.GetPoints().GetData()))
    if len(m.cells) != 1:
        fail(path, f"meshio: {len(m.cells)} cell blocks, expected 1")
    cells = m.cells[0].data
    vconn = vtk_to_numpy(g.GetCells().GetConnectivityArray())
    same(
        path,
        "connectivity",
        as_table(cells.astype(np.int64), cells.shape[1]),
        as_table(vconn.astype(np.int64), cells.shape[1]),
    )

    sections = [
        ("point", m.point_data, g.GetPointData(), lambda a: a),
        ("cell", m.cell_data, g.GetCellData(), lambda blocks: np.concatenate(blocks)),
        ("field", m.field_data, g.GetFieldData(), lambda a: a),
    ]
    counted = 0
    for kind, mdata, vdata, join in sections:
        vnames = [vdata.GetArrayName(i) for i in range(vdata.GetNumberOfArrays())]
        if sorted(mdata) != sorted(vnames):
            fail(path, f"{kind} arrays: meshio {sorted(mdata)}, VTK {sorted(vnames)}")
        for name in vnames:
            v = vtk_table(vdata.GetAbstractArray(name))
            same(path, f"{kind} array {name}", as_table(join(mdata[name])), v)
            counted += 1
    # Every appended array is one of those compared or the points or the cells.
    cell_arrays = sum(1 for s, _, _ in arrays if s == "Cells")
    if counted + 1 + cell_arrays != len(arrays):
        fail(path, f"compared {counted} data arrays, the file has {len(arrays)} appended arrays")
    return len(arrays)


def main():
    files = sys.argv[1:]
    if not files:
        print("usage: check_readers.py FILE...", file=sys.stderr)
        sys.exit(2)
    total = 0
    for path in files:
        total += check(path)
    print(f"check_readers: ok: {len(files)} files, {total} arrays read the same by meshio and VTK")


if __name__ == "__main__":
    main()
