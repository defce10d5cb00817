"""Scenarios: TOML files, Python dicts of the same schema, and the paper's example."""

import math
import os
from typing import Any, Dict, List, Mapping, Optional, Union

from . import _core, _laws
from ._core import ScenarioError
from ._mesh import Mesh

PathLike = Union[str, "os.PathLike[str]"]

#: Largest mesh resolution of :func:`paper_example` (squares per side).
MAX_PAPER_N = 4096


class Scenario:
    """A contact problem as a scenario file describes it: mesh, material and locking,
    supports, loads, contact parts with their laws, solver settings and outputs (see the
    scenario reference in the repository's docs; every key of a TOML scenario is a key
    here). A scenario is checked completely when it is solved or by :meth:`check`.
    """

    def __init__(
        self,
        native: "_core.Scenario",
        mesh: Optional[Mesh] = None,
        laws: Optional[List[_laws.Law]] = None,
    ) -> None:
        self._native = native
        self._mesh = mesh
        self._laws = laws or []

    @classmethod
    def from_dict(
        cls,
        d: Mapping[str, Any],
        *,
        source: str = "<dict>",
        base_dir: Optional[PathLike] = None,
    ) -> "Scenario":
        """The scenario of the dict ``d``, with the schema of a scenario file: tables are
        dicts, arrays of tables lists of dicts, e.g.
        ``{"mesh": {"kind": "rectangle", "size": [4.0, 4.0], "n": [16, 16]},
        "material": {"young": 2000.0, "poisson": 0.3}, ...}``.

        ``d["mesh"]`` may also be a :class:`Mesh` (a mesh built in memory), the ``mu``
        of a ``[contact.friction]`` table a Python callable μ(r) of the slip or
        ``{"law": "position", "function": f}`` for μ(x) of the position, and a contact
        entry may give ``"normal": {"law": "compliance", "p": p, "dp": dp}`` (see below). ``source``
        names the scenario in error messages; relative file paths (``mesh.file``) are
        resolved against ``base_dir`` (default: the working folder). Numpy arrays and
        scalars are accepted where lists and numbers are.

        **User-defined friction coefficients.** ``"mu": f`` with a callable ``f`` makes
        μ(r) a law written in Python: the solver calls ``f`` with a numpy array of the slips
        r (m) of all points of the contact part — once per outer iteration, once at the
        start and once for the certificate, never per point — and expects an array of the
        same shape (or a scalar) of finite values ≥ 0 (dimensionless for ``bound =
        "coulomb"``, Pa for ``"tresca"``). When the scenario is checked, ``f`` is sampled
        at r = 0 and at 121 slips from 1e-10 to 100 m (ten per decade); the uniqueness check then uses the
        largest sampled value and secant slope as estimates of sup μ and its Lipschitz
        constant. An exception raised by ``f`` propagates as itself (with a note naming
        the law on Python ≥ 3.11); a NaN, negative or wrongly shaped result raises
        :class:`ScenarioError` naming the law and the slip.

        **Friction varying along the interface.** ``"mu": {"law": "position", "function":
        f}`` makes μ a function of the position x (m) of each contact point in the
        reference configuration, independent of the slip: with ``bound = "tresca"`` a
        friction bound F(x) in Pa. ``f`` gets an ``(n, d)`` array of the positions of all
        points of the part, once per outer iteration, and returns ``n`` finite values ≥ 0;
        it is checked at the part's nodes when the scenario is, and μ₀ of the uniqueness
        check is its largest value there (its Lipschitz constant in the slip is 0).

        **Normal compliance.** ``"normal": {"law": "compliance", "p": p, "dp": dp}`` in a
        contact entry (instead of ``law`` and ``c_nu``) gives the contact pressure
        p(δ) (Pa) of the penetration δ = u_ν − g (m) and its derivative dp(δ) (Pa/m); the
        pressure is 0 where δ ≤ 0. The law must be monotone: when the scenario is checked,
        p and dp are sampled at δ = 0 and 101 penetrations from 1e-10 to 1 times the body's
        diameter, and p(0) = 0, finite values ≥ 0, p nondecreasing and dp equal to the
        slope of p (to 1e-3) are required. The normal law is not frozen within an outer
        iteration, so ``p`` is called at every energy evaluation (each Newton step and
        line-search trial) with the penetrating points of the part and the 8 Gauss–Legendre
        nodes of each [0, δ] (the energy ∫₀^δ p, exact for polynomial p of degree ≤ 15),
        ``dp`` with the penetrating points when the Newton matrix is assembled.

        Raises :class:`ScenarioError` naming the field for unknown keys, wrong types or
        values out of range.
        """
        if not isinstance(d, Mapping):
            raise ScenarioError(
                f"{source}: field `(scenario)` = a {type(d).__name__}: a dict of tables"
            )
        value, laws = _laws.extract(dict(d))
        value = dict(value)
        mesh = value.get("mesh")
        native_mesh = None
        if isinstance(mesh, Mesh):
            native_mesh = mesh._native
            del value["mesh"]
        else:
            mesh = None
        base = os.fspath(base_dir) if base_dir is not None else None
        native = _core.Scenario.from_dict(value, source, native_mesh, base, laws)
        return cls(native, mesh, laws)

    def to_dict(self) -> Dict[str, Any]:
        """The scenario as a dict of the file's schema (every setting, defaults included);
        ``Scenario.from_dict(s.to_dict())`` gives the same scenario. A mesh given in memory
        is the :class:`Mesh` under ``"mesh"``, a friction coefficient written in Python its
        callable under ``"mu"``."""
        d = self._native.to_dict()
        if self._mesh is not None:
            d["mesh"] = self._mesh
        return _laws.restore(d, self._laws)

    @property
    def source(self) -> str:
        """Where the scenario came from: a path, ``<dict>``, or ``<built-in paper>``."""
        return self._native.source

    @property
    def title(self) -> Optional[str]:
        """The scenario's title, if any."""
        return self._native.title

    def with_resolution(self, n: int) -> "Scenario":
        """The same scenario with ``n`` squares along x (generated meshes only), for
        refinement studies."""
        native = self._native.with_resolution(_count(n, "n", self.source))
        return Scenario(native, self._mesh, self._laws)

    def check(self) -> List[str]:
        """Resolves and validates everything (mesh, laws, supports, loads, settings)
        without solving; returns the notes (warnings that do not stop a run). Raises
        :class:`ScenarioError` on invalid input."""
        return self._native.check()

    def mesh(self) -> Mesh:
        """The mesh the scenario solves on (generated, read from a file, or given)."""
        return self._mesh if self._mesh is not None else Mesh(self._native.mesh())

    def __repr__(self) -> str:
        title = f", title={self.title!r}" if self.title else ""
        return f"Scenario(source={self.source!r}{title})"


def _count(n: Any, field: str, source: str, largest: Optional[int] = None) -> int:
    if isinstance(n, bool) or not isinstance(n, int) or n < 1 or (largest and n > largest):
        top = f" to {largest}" if largest else ""
        raise ScenarioError(f"{source}: field `{field}` = {n!r}: an integer from 1{top}")
    return n


def load(path: PathLike) -> Scenario:
    """Reads the TOML scenario file at ``path`` (relative mesh files are resolved against
    its folder). Raises :class:`ScenarioError` for invalid content and ``OSError`` if the
    file cannot be read."""
    return Scenario(_core.Scenario.from_file(os.fspath(path)))


def paper_example(n: int = 128, c_kappa: float = 1.0e4) -> Scenario:
    """The paper's example (Barboteu, Han, Migórski 2018) as ``hemicontact paper`` solves
    it: the square (0, 4)² m on an ``n × n`` mesh, E = 2000 Pa, ν = 0.3, plane strain,
    clamped at the bottom, pressed by 900 N/m on top, nearly locking with limited
    compressibility θ = 0.16 and compliance ``c_kappa`` (Pa; 0: no locking), both vertical
    sides in frictional normal-compliance contact with slip-weakening Coulomb friction."""
    source = "<built-in paper>"
    n = _count(n, "n", source, MAX_PAPER_N)
    if isinstance(c_kappa, bool) or not isinstance(c_kappa, (int, float)):
        raise ScenarioError(f"{source}: field `c_kappa` = {c_kappa!r}: a number ≥ 0 (Pa)")
    c = float(c_kappa)
    if not (math.isfinite(c) and c >= 0.0):
        raise ScenarioError(f"{source}: field `c_kappa` = {c!r}: a finite number ≥ 0 (Pa)")
    return Scenario(_core.Scenario.paper(n, c))
