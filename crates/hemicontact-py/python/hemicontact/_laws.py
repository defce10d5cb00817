"""User-defined laws written in Python: how a scenario dict carries them, and the adapter
through which the solver calls them with numpy arrays.

A friction coefficient μ(r) of the slip r (m) may be a callable where a scenario gives
``mu``: ``{"friction": {"bound": "coulomb", "mu": f}}``. The solver calls ``f`` with a numpy
array of the slips of all points of the contact part, once per outer iteration (and once for
the certificate), never per point, and expects an array of the same shape (or a scalar) of
values ≥ 0: dimensionless for a Coulomb bound, Pa for a Tresca bound.
"""

from typing import Any, Callable, Dict, List, Tuple

import numpy as np

from ._core import ScenarioError

#: A law found in a scenario dict: (contact index, callable, the law's name in messages).
Law = Tuple[int, Callable[..., Any], str]


def law_name(k: int, part: Any, f: Callable[..., Any]) -> str:
    """The name of the friction coefficient of contact entry ``k`` in messages."""
    fname = getattr(f, "__qualname__", None) or getattr(f, "__name__", None) or type(f).__name__
    return f"contact[{k}].friction.mu ({fname}, part {part!r})"


def extract(d: Dict[str, Any]) -> Tuple[Dict[str, Any], List[Law]]:
    """The scenario dict ``d`` with every callable ``mu`` replaced by a placeholder law the
    schema accepts, and the callables taken out."""
    contact = d.get("contact")
    if not isinstance(contact, list):
        return d, []
    laws: List[Law] = []
    entries = []
    for k, c in enumerate(contact):
        friction = c.get("friction") if isinstance(c, dict) else None
        mu = friction.get("mu") if isinstance(friction, dict) else None
        if callable(mu):
            laws.append((k, mu, law_name(k, c.get("part"), mu)))
            c = dict(c)
            c["friction"] = dict(friction, mu={"law": "constant", "mu": 0.0})
        entries.append(c)
    if not laws:
        return d, []
    out = dict(d)
    out["contact"] = entries
    return out, laws


def restore(d: Dict[str, Any], laws: List[Law]) -> Dict[str, Any]:
    """The inverse of :func:`extract` on a dict of the schema."""
    for k, f, _ in laws:
        d["contact"][k]["friction"]["mu"] = f
    return d


def evaluate(f: Callable[..., Any], slips: bytes, name: str) -> bytes:
    """μ at the slips (float64 bytes, m) by the user's callable ``f``, as float64 bytes.
    An exception of ``f`` propagates as itself, with a note naming the law (Python ≥ 3.11);
    a result of the wrong shape or type is a :class:`ScenarioError` naming the law."""
    r = np.frombuffer(slips, dtype="<f8").copy()
    try:
        mu = f(r)
    except Exception as e:
        if hasattr(e, "add_note"):
            e.add_note(f"raised by the friction coefficient {name}")
        raise
    try:
        values = np.asarray(mu, dtype=float)
    except (TypeError, ValueError):
        raise ScenarioError(
            f"{name}: returned a {type(mu).__name__}: an array of numbers, one per slip"
        ) from None
    if values.shape == ():
        values = np.full(r.shape, float(values))
    if values.shape != r.shape:
        raise ScenarioError(
            f"{name}: returned an array of shape {values.shape} for {r.shape[0]} slips: one "
            "value per slip"
        )
    return np.ascontiguousarray(values, dtype="<f8").tobytes()
