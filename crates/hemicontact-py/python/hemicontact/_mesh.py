"""Meshes from numpy arrays and meshio meshes."""

import warnings
from typing import Any, Dict, Mapping, Optional

import numpy as np

from . import _core
from ._core import ScenarioError

#: meshio's cell type of the cells and of the boundary facets, by dimension.
_CELL_TYPE = {2: "triangle", 3: "tetra"}
_FACET_TYPE = {2: "line", 3: "triangle"}


def _error(field: str, value: str, allowed: str) -> ScenarioError:
    return ScenarioError(f"<mesh>: field `{field}` = {value}: {allowed}")


def _index_array(a: Any, field: str, width: int) -> np.ndarray:
    arr = np.asarray(a)
    if arr.size == 0:
        arr = arr.reshape(0, width)
    if arr.ndim != 2 or arr.shape[1] != width:
        raise _error(field, f"an array of shape {arr.shape}", f"an array of shape (k, {width})")
    if not np.issubdtype(arr.dtype, np.integer):
        if np.issubdtype(arr.dtype, np.floating) and np.all(np.isfinite(arr)) and np.all(arr == np.round(arr)):
            arr = arr.astype(np.int64)
        else:
            raise _error(field, f"an array of dtype {arr.dtype}", "integer node indices")
    return np.ascontiguousarray(arr, dtype="<i8")


def _signed_measures(points: np.ndarray, cells: np.ndarray, dim: int) -> np.ndarray:
    p = points[cells]
    e = p[:, 1:, :] - p[:, :1, :]
    return np.linalg.det(e)


def _orient_entities(points: np.ndarray, cells: np.ndarray, tags: np.ndarray, dim: int) -> None:
    """Gmsh orients the cells of a geometric entity by the entity's orientation: a surface
    meshed with its normal along −z gives clockwise triangles throughout. Such an entity —
    every cell negatively oriented — is reoriented in place, with a warning naming it, as
    the library's Gmsh reader does; an entity with cells of both orientations (a tangled
    mesh) is left as it is, for the mesh check to refuse naming its cells."""
    measure = _signed_measures(points, cells, dim)
    for tag in np.unique(tags):
        mine = tags == tag
        if np.all(measure[mine] < 0):
            # The last two vertices swapped, as the library's Gmsh reader does.
            cells[mine] = cells[mine][:, list(range(dim - 1)) + [dim, dim - 1]]
            warnings.warn(
                f"Mesh.from_meshio: the {int(mine.sum())} cells of geometric entity {int(tag)} are "
                "all negatively oriented (the entity's orientation in Gmsh); they were reoriented",
                RuntimeWarning,
                stacklevel=3,
            )


def _drop_unused(p: np.ndarray, c: np.ndarray, parts: Dict[str, np.ndarray]) -> Any:
    """Drops the nodes of ``p`` that no cell of ``c`` uses, with a ``RuntimeWarning``
    naming them: the points, cells and parts renumbered without them, and the node map
    (for each kept node, its index in ``p``); ``None`` for the map when every node is used.
    A part facet on a dropped node is a :class:`ScenarioError` naming it. Indices out of
    range are left for the library to report."""
    n = len(p)
    if c.size and (c.min() < 0 or c.max() >= n):
        return p, c, parts, None
    used = np.zeros(n, dtype=bool)
    used[c.ravel()] = True
    if used.all():
        return p, c, parts, None
    dropped = np.flatnonzero(~used)
    for name, f in parts.items():
        bad = np.isin(f, dropped)
        if bad.any():
            row = int(np.argwhere(bad)[0][0])
            node = int(f[row][bad[row]][0])
            raise _error(
                f"facets[{name!r}][{row}]",
                str(f[row].tolist()),
                f"facets of the cells' boundary: node {node} is used by no cell",
            )
    new = np.cumsum(used) - 1
    listed = ", ".join(str(int(v)) for v in dropped[:10])
    more = f" and {len(dropped) - 10} more" if len(dropped) > 10 else ""
    warnings.warn(
        f"Mesh.from_arrays: {len(dropped)} of {n} nodes are used by no cell and were dropped "
        f"(nodes {listed}{more}): a node without a cell has no stiffness. The mesh, and "
        "every result solved on it, keep the numbering of `points` (NaN displacement at the "
        "dropped nodes); the files Result.write writes number the nodes without them",
        RuntimeWarning,
        stacklevel=3,
    )
    node_map = np.flatnonzero(used)
    renumbered = {name: new[f] for name, f in parts.items()}
    return p[used], new[c], renumbered, node_map


class Mesh:
    """A simplicial mesh: P1 triangles (2D) or tetrahedra (3D), with named boundary parts.

    Coordinates are in m. Cells must be positively oriented (counter-clockwise triangles,
    right-handed tetrahedra); an inverted or degenerate cell is an error naming it, never
    silently reoriented. Boundary facets that belong to no named part form the part
    ``untagged`` (traction-free unless a scenario names it).

    Nodes that no cell uses are dropped from the mesh the solver sees, with a
    ``RuntimeWarning``; ``points``, ``cells``, ``facets`` and the results of a solve keep
    the numbering of the arrays given (see :meth:`from_arrays`).
    """

    def __init__(
        self,
        native: "_core.Mesh",
        node_map: Optional[np.ndarray] = None,
        points: Optional[np.ndarray] = None,
    ) -> None:
        self._native = native
        #: For each node of the solver's mesh, its index in the given points; ``None`` when
        #: no node was dropped.
        self._node_map = node_map
        #: The given points (when nodes were dropped).
        self._points = points

    @property
    def dropped_nodes(self) -> np.ndarray:
        """The indices of the given points that no cell uses, dropped from the solver's
        mesh (empty when every node is used)."""
        if self._node_map is None:
            return np.zeros(0, dtype=np.int64)
        keep = np.zeros(len(self._points), dtype=bool)
        keep[self._node_map] = True
        return np.flatnonzero(~keep)

    def _to_given(self, indices: np.ndarray) -> np.ndarray:
        """Node indices of the solver's mesh in the numbering of the given points."""
        return indices if self._node_map is None else self._node_map[indices]

    @classmethod
    def from_arrays(
        cls,
        points: Any,
        cells: Any,
        facets: Optional[Mapping[str, Any]] = None,
        regions: Optional[Mapping[str, Any]] = None,
    ) -> "Mesh":
        """The mesh of node coordinates ``points`` (N × d, m), cells ``cells`` (M × (d + 1)
        node indices, 0-based), boundary parts ``facets`` (name → K × d node indices) and
        cell regions ``regions`` (name → indices of its cells; every cell in exactly one),
        to which a scenario's ``"material"`` list assigns materials by ``"part"``.

        A 2D mesh may be given with 3 coordinate columns if the third is zero everywhere
        (as meshio stores planar meshes); it is then dropped.

        Nodes that no cell uses (they would have no stiffness) are dropped from the mesh
        the solver sees, with a ``RuntimeWarning`` naming them, as the command line's Gmsh
        reader drops them with a note. The mesh keeps the numbering of ``points``: its
        ``points``, ``cells`` and ``facets``, and the results of a solve on it (``points``,
        ``displacement`` and ``reactions`` with NaN rows at the dropped nodes, ``cells``,
        the contact table's ``node``) use the indices given; ``dropped_nodes`` lists them.
        A boundary facet on such a node is an error.

        Raises :class:`ScenarioError` naming the array and what is allowed.
        """
        p = np.asarray(points, dtype=float)
        if p.ndim != 2 or p.shape[1] not in (2, 3):
            raise _error("points", f"an array of shape {p.shape}", "an array of shape (n, 2) or (n, 3)")
        c = np.asarray(cells)
        if c.ndim != 2 or c.shape[1] not in (3, 4):
            raise _error(
                "cells",
                f"an array of shape {c.shape}",
                "triangles (m, 3) or tetrahedra (m, 4) of node indices",
            )
        dim = c.shape[1] - 1
        if p.shape[1] == 3 and dim == 2:
            if np.any(p[:, 2] != 0.0):
                raise _error(
                    "points",
                    "3 coordinates with z ≠ 0 for triangles",
                    "a planar mesh: 2 coordinates, or z = 0 everywhere",
                )
            p = p[:, :2]
        if p.shape[1] != dim:
            raise _error(
                "points",
                f"{p.shape[1]} coordinates for cells of {dim + 1} nodes",
                f"{dim} coordinates per node",
            )
        if not np.all(np.isfinite(p)):
            bad = int(np.argwhere(~np.isfinite(p))[0][0])
            raise _error(f"points[{bad}]", str(p[bad].tolist()), "finite coordinates")
        c = _index_array(c, "cells", dim + 1)
        given: Dict[str, np.ndarray] = {}
        for name, f in (facets or {}).items():
            if not isinstance(name, str):
                raise _error("facets", f"a part named {name!r}", "part names as str")
            given[name] = _index_array(f, f"facets[{name!r}]", dim)
        cell_regions = []
        for name, r in (regions or {}).items():
            if not isinstance(name, str):
                raise _error("regions", f"a region named {name!r}", "region names as str")
            idx = np.asarray(r).reshape(-1)
            if idx.size and not np.issubdtype(idx.dtype, np.integer):
                raise _error(f"regions[{name!r}]", f"an array of {idx.dtype}", "cell indices (integers)")
            if np.any((idx < 0) | (idx >= len(c))):
                raise _error(f"regions[{name!r}]", "an index out of range", f"cell indices from 0 to {len(c) - 1}")
            cell_regions.append((name, np.ascontiguousarray(idx, dtype="<i8").tobytes()))
        all_points = p
        p, c, given, node_map = _drop_unused(p, c, given)
        parts = [(name, np.ascontiguousarray(f, dtype="<i8").tobytes()) for name, f in given.items()]
        native = _core.Mesh.from_buffers(
            dim,
            np.ascontiguousarray(p, dtype="<f8").tobytes(),
            np.ascontiguousarray(c, dtype="<i8").tobytes(),
            parts,
            cell_regions,
        )
        if node_map is None:
            return cls(native)
        return cls(native, node_map, np.array(all_points, dtype=float))

    @classmethod
    def from_meshio(cls, m: Any) -> "Mesh":
        """The mesh of a meshio mesh ``m``: its triangles (2D) or tetrahedra (3D) are the
        cells, and its lines (2D) or triangles (3D) in a named set — a Gmsh physical group
        (``cell_sets``, or ``gmsh:physical`` tags named by ``field_data``) — are the
        boundary parts, named like the groups. So a pygmsh or gmsh mesh goes straight in.

        A geometric entity (``gmsh:geometrical``) whose cells are all negatively oriented —
        a Gmsh surface meshed with its normal along −z — is reoriented, with a
        ``RuntimeWarning`` naming it (the command line's Gmsh reader does the same, with a
        note); cells of both orientations in one entity are an error naming them.
        """
        blocks = list(m.cells)
        types = {b.type for b in blocks}
        dim = 3 if "tetra" in types else 2
        if _CELL_TYPE[dim] not in types:
            raise _error(
                "cells",
                f"cell types {sorted(types)}",
                "triangles (2D) or tetrahedra (3D): only P1 simplices are supported",
            )
        points = np.asarray(m.points, dtype=float)
        entities = (getattr(m, "cell_data", None) or {}).get("gmsh:geometrical")
        cell_blocks = []
        offset: Dict[int, int] = {}  # block index -> index of its first cell
        n_cells = 0
        for i, b in enumerate(blocks):
            if b.type != _CELL_TYPE[dim]:
                continue
            offset[i] = n_cells
            n_cells += len(b.data)
            data = np.array(b.data, dtype=np.int64)
            tags = np.asarray(entities[i]) if entities is not None else np.zeros(len(data), int)
            _orient_entities(points[:, :dim], data, tags, dim)
            cell_blocks.append(data)
        cells = np.concatenate(cell_blocks, axis=0)
        facet_type = _FACET_TYPE[dim]
        parts: Dict[str, list] = {}
        sets = getattr(m, "cell_sets", None) or {}
        named = {k: v for k, v in sets.items() if not k.startswith("gmsh:")}
        regions: Dict[str, list] = {}
        if named:
            for name, per_block in named.items():
                for i, (block, idx) in enumerate(zip(blocks, per_block)):
                    if block.type == facet_type and idx is not None and len(idx) > 0:
                        parts.setdefault(name, []).append(block.data[np.asarray(idx)])
                    if i in offset and idx is not None and len(idx) > 0:
                        regions.setdefault(name, []).append(offset[i] + np.asarray(idx, dtype=np.int64))
        else:
            tags = (getattr(m, "cell_data", None) or {}).get("gmsh:physical")
            names = {
                int(v[0]): k
                for k, v in (getattr(m, "field_data", None) or {}).items()
                if len(v) > 1 and int(v[1]) == dim - 1
            }
            region_names = {
                int(v[0]): k
                for k, v in (getattr(m, "field_data", None) or {}).items()
                if len(v) > 1 and int(v[1]) == dim
            }
            if tags is not None:
                for i, (block, t) in enumerate(zip(blocks, tags)):
                    if i in offset:
                        for tag in np.unique(t):
                            name = region_names.get(int(tag), str(int(tag)))
                            cells_of = offset[i] + np.flatnonzero(np.asarray(t) == tag)
                            regions.setdefault(name, []).append(cells_of)
                    if block.type != facet_type:
                        continue
                    for tag in np.unique(t):
                        name = names.get(int(tag), str(int(tag)))
                        parts.setdefault(name, []).append(block.data[np.asarray(t) == tag])
        facets = {k: np.concatenate(v, axis=0) for k, v in parts.items()}
        # Cell regions (physical groups of dimension d), cells in none forming `untagged`
        # as the command line's reader does; none at all when the file names no group.
        cell_regions = {k: np.concatenate(v) for k, v in regions.items()}
        if cell_regions:
            covered = np.zeros(n_cells, dtype=bool)
            for idx in cell_regions.values():
                covered[idx] = True
            if not covered.all():
                cell_regions.setdefault("untagged", np.array([], dtype=np.int64))
                cell_regions["untagged"] = np.concatenate(
                    [cell_regions["untagged"], np.flatnonzero(~covered)]
                )
        return cls.from_arrays(points, cells, facets, cell_regions or None)

    @property
    def dim(self) -> int:
        """Spatial dimension (2 or 3)."""
        return self._native.dim

    @property
    def points(self) -> np.ndarray:
        """Node coordinates (N × d, m), as given (with any dropped node)."""
        if self._points is not None:
            return self._points
        return np.frombuffer(self._native.points(), dtype="<f8").reshape(-1, self.dim)

    @property
    def cells(self) -> np.ndarray:
        """Cells (M × (d + 1) node indices)."""
        c = np.frombuffer(self._native.cells(), dtype="<i8").reshape(-1, self.dim + 1)
        return self._to_given(c)

    @property
    def regions(self) -> Dict[str, np.ndarray]:
        """Cell regions: name → indices of its cells (empty for a mesh without regions)."""
        return {name: np.frombuffer(b, dtype="<i8") for name, b in self._native.regions()}

    @property
    def facets(self) -> Dict[str, np.ndarray]:
        """Boundary parts: name → facets (K × d node indices)."""
        return {
            name: self._to_given(np.frombuffer(b, dtype="<i8").reshape(-1, self.dim))
            for name, b in self._native.parts()
        }

    def to_meshio(self) -> Any:
        """The mesh as a meshio mesh (needs meshio): cells, then one facet block per
        boundary part, with ``cell_sets`` naming the parts and the cell regions."""
        import meshio

        blocks = [(_CELL_TYPE[self.dim], self.cells)]
        sets: Dict[str, list] = {}
        parts = self.facets
        for f in parts.values():
            blocks.append((_FACET_TYPE[self.dim], f))
        for i, name in enumerate(parts):
            sets[name] = [
                np.arange(len(b[1])) if j == i + 1 else np.array([], dtype=int)
                for j, b in enumerate(blocks)
            ]
        for name, idx in self.regions.items():
            own = sets.setdefault(name, [np.array([], dtype=int) for _ in blocks])
            own[0] = idx
        return meshio.Mesh(self.points, blocks, cell_sets=sets)

    def __repr__(self) -> str:
        dropped = len(self.dropped_nodes)
        note = f", dropped nodes={dropped}" if dropped else ""
        return (
            f"Mesh(dim={self.dim}, nodes={len(self.points)}{note}, cells={self._native.n_cells}, "
            f"parts={list(self.facets)})"
        )
