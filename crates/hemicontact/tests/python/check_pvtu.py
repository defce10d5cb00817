#!/usr/bin/env python3
"""Reads hemicontact's parallel output with VTK's parallel reader and compares it with the
serial file.

Usage: check_pvtu.py FOLDER...

Each FOLDER holds `solution.pvtu` with its pieces and the serial `solution.vtu` of the same
solution. Checks: `vtkXMLPUnstructuredGridReader` reads the index and every piece; the
grid it assembles has every cell of the serial file once (its `cell_id` values are a
permutation of 0 … cells − 1) and every point array, cell array and point coordinate equals
the serial one at the `node_id` / `cell_id` it carries, exactly, and so are every cell's
nodes (through `node_id`).

Exit codes: 0 pass, 1 a check failed, 77 vtk or numpy is not importable (skip).
"""
import os
import sys

try:
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"skipped: vtk not available ({e})", file=sys.stderr)
    sys.exit(77)


def fail(path, msg):
    print(f"check_pvtu: FAIL: {path}: {msg}", file=sys.stderr)
    sys.exit(1)


def read(reader, path):
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def arrays(data):
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}


for folder in sys.argv[1:]:
    index = os.path.join(folder, "solution.pvtu")
    grid = read(vtk.vtkXMLPUnstructuredGridReader(), index)
    serial = read(vtk.vtkXMLUnstructuredGridReader(), os.path.join(folder, "solution.vtu"))
    if grid.GetNumberOfCells() != serial.GetNumberOfCells():
        fail(index, f"{grid.GetNumberOfCells()} cells, the serial file {serial.GetNumberOfCells()}")
    points, cells = arrays(grid.GetPointData()), arrays(grid.GetCellData())
    if "node_id" not in points or "cell_id" not in cells:
        fail(index, "no node_id or cell_id")
    node, cell = points.pop("node_id"), cells.pop("cell_id")
    if not np.array_equal(np.sort(cell), np.arange(serial.GetNumberOfCells())):
        fail(index, "cell_id is not every cell once")
    for name, values, ids, reference in [
        *[(n, v, node, arrays(serial.GetPointData())) for n, v in points.items()],
        *[(n, v, cell, arrays(serial.GetCellData())) for n, v in cells.items()],
    ]:
        if name not in reference:
            fail(index, f"array {name} is not in the serial file")
        if values.dtype != reference[name].dtype or not np.array_equal(values, reference[name][ids], equal_nan=True):
            fail(index, f"array {name} differs from the serial file")
    if set(points) != set(arrays(serial.GetPointData())) or set(cells) != set(arrays(serial.GetCellData())):
        fail(index, "not the serial file's arrays")
    # Every cell's nodes, through node_id, are the serial cell's.
    nv = grid.GetCell(0).GetNumberOfPoints() if grid.GetNumberOfCells() else 0
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, nv)
    conn_serial = vtk_to_numpy(serial.GetCells().GetConnectivityArray()).reshape(-1, nv)
    if not np.array_equal(node[conn], conn_serial[cell]):
        fail(index, "the cells' nodes differ from the serial file")
    xyz = vtk_to_numpy(grid.GetPoints().GetData())
    if not np.array_equal(xyz, vtk_to_numpy(serial.GetPoints().GetData())[node]):
        fail(index, "point coordinates differ from the serial file")
print(f"check_pvtu: {len(sys.argv) - 1} parallel files read by VTK as their serial files")
