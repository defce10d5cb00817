"""hemicontact: finite elements for static contact of elastic locking materials with
unilateral contact and nonmonotone, slip-dependent friction.

The solver is the Rust library of the same name; this package drives it from Python:

- :func:`load` reads a TOML scenario, :meth:`Scenario.from_dict` builds one from Python
  dicts and lists (the same schema), :func:`paper_example` gives the paper's example;
- :class:`Mesh` builds a mesh from numpy arrays or a meshio mesh (Gmsh physical groups
  become boundary parts);
- :func:`solve` returns a :class:`Result` with numpy arrays (displacement, strain, stress,
  the contact table), the certificate, the iteration history and the timings;
- :func:`load_path` solves a scenario along its ``[loading]`` path, one :class:`Result`
  per load step;
- :func:`convergence` runs a mesh-refinement study.

Units are SI throughout: lengths and displacements in m, stresses and pressures in Pa,
forces in N (N/m per unit thickness in 2D). Invalid input raises :class:`ScenarioError`
(a ``ValueError``) naming the field, its value and what is allowed.
"""

from ._core import ScenarioError, __version__
from ._mesh import Mesh
from ._result import Result, convergence, load_path, solve
from ._scenario import Scenario, load, paper_example



def __getattr__(name: str):
    # `hemicontact.plot` needs matplotlib: imported on first use, not with the package.
    if name == "plot":
        import importlib

        return importlib.import_module(".plot", __name__)
    raise AttributeError(f"module 'hemicontact' has no attribute {name!r}")


__all__ = [
    "Mesh",
    "Result",
    "Scenario",
    "ScenarioError",
    "__version__",
    "convergence",
    "load",
    "load_path",
    "paper_example",
    "solve",
]
