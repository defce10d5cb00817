"""Solving, and the results of a solve as numpy arrays."""

import json
import os
import warnings
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _core
from ._mesh import Mesh
from ._scenario import PathLike, Scenario, load


def _f64(b: bytes, *shape: int) -> np.ndarray:
    return np.frombuffer(b, dtype="<f8").reshape(shape)


def _body(b: Dict[str, Any]) -> Dict[str, Any]:
    """One entry of ``summary.json``'s ``bodies`` with its force vectors as arrays."""
    out = dict(b)
    for key in ("load", "reaction", "contact_force"):
        out[key] = np.array(out[key], dtype=float)
    return out


def _totals(t: Dict[str, Any]) -> Dict[str, Any]:
    """One entry of ``summary.json``'s ``contact_totals`` with its vectors as arrays."""
    out = dict(t)
    for key in ("force", "force_tangential", "max_pressure_at"):
        if out[key] is not None:
            out[key] = np.array(out[key], dtype=float)
    return out


class Result:
    """The result of a solve. Arrays are numpy arrays in SI units.

    - ``points`` (N × d, m), ``cells`` (M × (d + 1)), ``displacement`` (N × d, m),
      ``reactions`` (N × d, N; N/m in 2D: the force of each prescribed DOF);
    - per cell: ``strain`` (M × 3 × 3), ``stress`` (M × 3 × 3, Pa, locking stress
      included), ``von_mises`` (M, Pa), ``trace_strain`` (M), ``locking_active`` (M, 0/1),
      ``locking_multiplier`` (M, Pa), ``material`` (M, the index of each cell's material:
      its position in the scenario's ``"material"`` list, 0 for one material);
    - ``contact``: a dict of arrays, one entry per contact point, one key per column of
      ``contact.csv`` (``node``, ``boundary``, ``x``, ``y``, ``z``, ``weight``, ``u_nu``,
      ``gap``, ``u_tau_1``, ``u_tau_2``, ``slip``, ``pressure``, ``bound``,
      ``force_normal``, ``force_tangential_1``, ``force_tangential_2``, ``normal_state``,
      ``friction_state``, ``normal_residual``, ``friction_residual``, ``force_scale``,
      ``slip_scale``) and the vectors
      ``normal`` (the unit contact normal, columns ``nu_x``, ``nu_y``, ``nu_z``), ``force``
      (interface force on the body, N) and
      ``friction_traction`` (tangential traction on the body, force / weight, Pa), K × 3;
    - ``contact_totals``: one dict per contact boundary (``[[contact]]`` entry, in order),
      the ``contact_totals`` of ``summary.json``: ``part``; the counts ``points``,
      ``n_contact``, ``n_stick``, ``n_slip``; ``force`` (Σ_i R_i, the resultant interface
      force on the body, N; N/m in 2D), ``force_normal`` (Σ_i R_i·ν_i, negative when
      pressed) and ``force_tangential`` (the resultant of the tangential parts);
      ``contact_measure`` (Σ w_i over the points in contact: contact length in m in 2D,
      area in m² in 3D, the lumped nodal measure, accurate to about one element size);
      ``max_pressure`` (Pa, 0 without contact), ``max_pressure_node`` and
      ``max_pressure_at`` (its reference coordinates, m; both ``None`` without contact).
      The vectors are numpy arrays of d components;
    - ``body`` (N): the body of each node, the bodies being the connected components of
      the mesh numbered by their smallest node (−1 at a node in no cell); ``bodies``: one
      dict per body, the ``bodies`` of ``summary.json``: ``nodes``, ``cells``, ``regions``
      and ``parts`` (the names of the cell regions and boundary parts on it), the resultant
      ``load`` (external loads), ``reaction`` (supports) and ``contact_force`` (interface
      forces: R_i at its contact points, −N_j R_i at its master nodes of a pair), numpy
      arrays of d components (N; N/m in 2D), whose sum vanishes at equilibrium, and
      ``imbalance`` (the norm of that sum over the largest of the three);
    - on a mesh whose unused nodes :meth:`Mesh.from_arrays` dropped, the nodal arrays
      (``points``, ``displacement``, ``reactions``), ``cells`` and ``contact["node"]`` use
      the numbering of the points given, with NaN rows at the dropped nodes;
    - ``converged``, ``message``, ``certificate`` (dict), ``history`` (``outer`` and
      ``newton`` lists of dicts), ``timings`` (dict, s), ``summary`` (the whole
      ``summary.json`` as a dict);
    - ``load_factor``: the factor λ by which the scenario's loads and prescribed
      displacements were multiplied (1 for a plain solve; see :func:`load_path`);
    - ``notes``: the notes of ``summary.json`` (list of str): those of the scenario
      (deprecated forms, shared nodes, Gmsh notes, obstacles the mesh does not resolve),
      then those of the solution (the small-deformation check, see
      ``summary["small_deformation"]``); ``flagged_notes``: those among them that question
      the input or the result — an obstacle the mesh does not resolve, a deformation too
      large for the model — which :func:`solve` and :func:`load_path` raise as
      ``RuntimeWarning``.
    """

    def __init__(self, native: "_core.Solution", mesh: Optional[Mesh] = None) -> None:
        self._native = native
        self.dim: int = native.dim
        #: The result's title (the scenario's, else ``scenario``).
        self.title: str = native.title
        self.converged: bool = native.converged
        self.message: str = native.message
        #: The load factor λ (dimensionless) of this solve.
        self.load_factor: float = native.load_factor
        self.summary: Dict[str, Any] = json.loads(native.summary_json())
        self.notes: List[str] = list(self.summary["notes"])
        self.flagged_notes: List[str] = list(native.flagged_notes)
        report = self.summary["report"]
        self.certificate: Dict[str, Any] = report["certificate"]
        self.history: Dict[str, List[Dict[str, Any]]] = {
            "outer": report["outer"],
            "newton": report["newton"],
        }
        self.timings: Dict[str, Any] = report["timings"]
        self.contact_totals: List[Dict[str, Any]] = [
            _totals(t) for t in self.summary["contact_totals"]
        ]
        self.bodies: List[Dict[str, Any]] = [_body(b) for b in self.summary["bodies"]]
        d = self.dim
        self.points = _f64(native.points(), -1, d)
        self.cells = np.frombuffer(native.cells(), dtype="<i8").reshape(-1, d + 1)
        self.displacement = _f64(native.displacement(), -1, d)
        self.reactions = _f64(native.reactions(), -1, d)
        self.body = np.frombuffer(native.body(), dtype="<i8")
        fields = {name: (k, b) for name, k, b in native.cell_fields()}
        self.strain = _f64(fields["strain"][1], -1, 3, 3)
        self.stress = _f64(fields["stress"][1], -1, 3, 3)
        self.von_mises = _f64(fields["von_mises"][1], -1)
        self.trace_strain = _f64(fields["trace_strain"][1], -1)
        self.locking_active = _f64(fields["locking_active"][1], -1).astype(np.int64)
        self.locking_multiplier = _f64(fields["locking_multiplier"][1], -1)
        self.material = _f64(fields["material"][1], -1).astype(np.int64)
        numeric, text = native.contact_columns()
        contact: Dict[str, np.ndarray] = {}
        for name, k, b in numeric:
            a = _f64(b, -1) if k == 1 else _f64(b, -1, k)
            contact[name] = a.astype(np.int64) if name == "node" else a
        for name, values in text:
            contact[name] = np.array(values, dtype=str)
        self.contact = contact
        if mesh is not None and mesh._node_map is not None:
            self._renumber(mesh)

    def _renumber(self, mesh: Mesh) -> None:
        """Gives the nodal arrays in the numbering of the points given to
        :meth:`Mesh.from_arrays`, which dropped the nodes no cell uses: NaN rows there."""
        node_map = mesh._node_map
        n = len(mesh.points)

        def expand(a: np.ndarray) -> np.ndarray:
            out = np.full((n,) + a.shape[1:], np.nan)
            out[node_map] = a
            return out

        self.points = mesh.points
        self.displacement = expand(self.displacement)
        self.reactions = expand(self.reactions)
        body = np.full(n, -1, dtype=np.int64)
        body[node_map] = self.body
        self.body = body
        self.cells = node_map[self.cells]
        self.contact["node"] = node_map[self.contact["node"]]

    def write(self, folder: PathLike) -> List[str]:
        """Writes the files ``hemicontact solve`` writes — ``solution.vtu``,
        ``contact.csv``, ``deformed.svg``/``.png`` and ``summary.json`` (as the scenario's
        ``[output]`` asks) — into ``folder``, as one result set: the folder's previous
        content is replaced only once every file is written. Returns the paths written."""
        return [os.fspath(p) for p in self._native.write(os.fspath(folder))]

    def to_meshio(self) -> Any:
        """The solution as a meshio mesh (needs meshio): point data ``displacement`` and
        ``reaction``, cell data ``strain``, ``stress`` (flattened 3 × 3), ``von_mises``,
        ``trace_strain``, ``locking_active``, ``locking_multiplier`` and ``material``."""
        import meshio

        cell_type = "triangle" if self.dim == 2 else "tetra"
        pad = lambda a: np.hstack([a, np.zeros((len(a), 3 - self.dim))])  # noqa: E731
        return meshio.Mesh(
            pad(self.points),
            [(cell_type, self.cells)],
            point_data={"displacement": pad(self.displacement), "reaction": pad(self.reactions)},
            cell_data={
                "strain": [self.strain.reshape(-1, 9)],
                "stress": [self.stress.reshape(-1, 9)],
                "von_mises": [self.von_mises],
                "trace_strain": [self.trace_strain],
                "locking_active": [self.locking_active],
                "locking_multiplier": [self.locking_multiplier],
                "material": [self.material],
            },
        )

    def __repr__(self) -> str:
        state = "converged" if self.converged else "NOT converged"
        return f"Result({self.title!r}, {state}, nodes={len(self.points)}, contact points={len(self.contact['node'])})"


ScenarioLike = Union[Scenario, Dict[str, Any], PathLike]


def _scenario(s: ScenarioLike) -> Scenario:
    if isinstance(s, Scenario):
        return s
    if isinstance(s, dict):
        return Scenario.from_dict(s)
    if isinstance(s, (str, os.PathLike)):
        return load(s)
    raise TypeError(f"a Scenario, a dict or a path is needed, not {type(s).__name__}")


def solve(scenario: ScenarioLike) -> Result:
    """Solves ``scenario`` (a :class:`Scenario`, a dict of the scenario schema, or the path
    of a TOML file) and returns its :class:`Result`.

    The GIL is released during the solve, and Ctrl-C interrupts it with
    ``KeyboardInterrupt``. A solve that does not converge (or whose certificate fails)
    is not an exception: it returns the last iterate with ``converged == False`` and emits a
    ``RuntimeWarning`` with the solver's message. Invalid input raises
    :class:`ScenarioError`. A scenario with ``[loading]`` is solved along its load path
    (as :func:`load_path`) and the last step solved is returned."""
    s = _scenario(scenario)
    result = Result(_core.solve(s._native), s._mesh)
    for note in result.flagged_notes:
        warnings.warn(f"{result.title}: {note}", RuntimeWarning, stacklevel=2)
    if not result.converged:
        warnings.warn(
            f"{result.title}: {result.message}; the result holds the last iterate "
            "(converged == False)",
            RuntimeWarning,
            stacklevel=2,
        )
    return result


def load_path(scenario: ScenarioLike) -> List[Result]:
    """Solves ``scenario`` along its ``[loading]`` path — the problem with every load
    (tractions, body force) and prescribed displacement multiplied by each load factor λ in
    turn, each step starting from the last step's displacement — and returns one
    :class:`Result` per step solved, in order, each with its ``load_factor``. Without
    ``[loading]``, one plain solve (λ = 1). The path stops after the first step that does
    not converge (a ``RuntimeWarning`` says so); the list then ends with that step. The GIL
    is released while it runs, and Ctrl-C interrupts it with ``KeyboardInterrupt``."""
    s = _scenario(scenario)
    steps = [Result(native, s._mesh) for native in _core.load_path(s._native)]
    _warn_path_notes(steps)
    if steps and not steps[-1].converged:
        warnings.warn(
            f"{steps[-1].title}: {steps[-1].message}; the load path stops at step "
            f"{len(steps)} (converged == False)",
            RuntimeWarning,
            stacklevel=2,
        )
    return steps


def _warn_path_notes(steps: List[Result]) -> None:
    """Raises the flagged notes of a load path as ``RuntimeWarning``: those of the first
    step that has any (the obstacle notes are the same in every step), and how many later
    steps have notes of their own."""
    flagged = [(k, r) for k, r in enumerate(steps, 1) if r.flagged_notes]
    if not flagged:
        return
    k, first = flagged[0]
    for note in first.flagged_notes:
        warnings.warn(
            f"{first.title} (step {k} of {len(steps)}): {note}", RuntimeWarning, stacklevel=3
        )
    later = [j for j, r in flagged[1:] if r.flagged_notes != first.flagged_notes]
    if later:
        warnings.warn(
            f"{len(later)} later step(s) of the load path have such notes too, the last at "
            f"step {later[-1]}; each Result lists its own in flagged_notes",
            RuntimeWarning,
            stacklevel=3,
        )


def convergence(
    scenario: ScenarioLike, levels: Sequence[int], reference: int
) -> List[Dict[str, Any]]:
    """The mesh-refinement study of ``scenario`` (a generated mesh): solves on each level
    (squares along x, increasing) and on a reference mesh of ``reference`` squares, and
    returns one dict per level — ``n``, ``h_edge`` (m), ``h_area`` (m², the element
    measure), ``dofs``, ``error`` (relative energy-norm error against the reference),
    ``order_edge`` and ``order_area`` (observed orders from the previous level, ``None``
    where undefined), ``outer``, ``newton``, ``converged``, ``seconds``. The GIL is released
    while it runs, and Ctrl-C interrupts it with ``KeyboardInterrupt``."""
    s = _scenario(scenario)
    study = json.loads(_core.convergence(s._native, [int(n) for n in levels], int(reference)))
    return study["levels"]
