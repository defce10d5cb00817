"""User-defined laws written in Python: how a scenario dict carries them, and the adapter
through which the solver calls them with numpy arrays.

Three kinds, each in a ``[[contact]]`` entry of the dict:

- a friction coefficient μ(r) of the slip r (m):
  ``{"friction": {"bound": "coulomb", "mu": f}}`` (or ``"mu": {"law": "slip", "function":
  f}``). ``f`` gets a 1-D array of slips, once per outer iteration.
- a friction coefficient or Tresca bound μ(x) of the position x (m) of the contact point
  in the reference configuration: ``"mu": {"law": "position", "function": f}``. ``f`` gets
  an ``(n, d)`` array of positions, once per outer iteration.
- a normal compliance p(δ) of the penetration δ = u_ν − g (m), with its derivative:
  ``"normal": {"law": "compliance", "p": p, "dp": dp}``, in place of ``law``/``c_nu``.
  ``p`` and ``dp`` get 1-D arrays of penetrations δ ≥ 0 at every energy evaluation.

Each callable returns an array with one value per point (or a scalar): finite and ≥ 0;
dimensionless for a Coulomb bound, Pa for a Tresca bound, Pa for ``p``, Pa/m for ``dp``.
"""

import decimal
import numbers
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np

from ._core import ScenarioError

#: A law found in a scenario dict: (contact index, kind, callable, derivative or None,
#: label). The kind is ``"slip"``, ``"position"`` or ``"compliance"``; the label names the
#: callable and the part, e.g. ``weakening, part 'left'``.
Law = Tuple[int, str, Callable[..., Any], Optional[Callable[..., Any]], str]


def _fname(f: Callable[..., Any]) -> str:
    return getattr(f, "__qualname__", None) or getattr(f, "__name__", None) or type(f).__name__


def law_name(k: int, kind: str, label: str) -> str:
    """The name of a law in messages: its field path and label."""
    field = "normal" if kind == "compliance" else "friction.mu"
    return f"contact[{k}].{field} ({label})"


def _friction_law(k: int, part: Any, mu: Any) -> Optional[Law]:
    """The Python law of a ``mu`` value, if it is one."""
    if callable(mu):
        return (k, "slip", mu, None, f"{_fname(mu)}, part {part!r}")
    if isinstance(mu, dict) and mu.get("law") in ("slip", "position"):
        f = mu.get("function")
        extra = sorted(set(mu) - {"law", "function"})
        if not callable(f) or extra:
            raise ScenarioError(
                f"<dict>: field `contact[{k}].friction.mu` = {mu!r}: "
                f'{{"law": "{mu["law"]}", "function": f}} with a callable f'
            )
        return (k, mu["law"], f, None, f"{_fname(f)}, part {part!r}")
    return None


def _normal_law(k: int, c: Dict[str, Any]) -> Law:
    """The Python compliance law of the ``normal`` entry of contact entry ``c``."""
    normal = c["normal"]
    allowed = '{"law": "compliance", "p": p, "dp": dp} with callables p(δ) (Pa) and dp(δ) (Pa/m)'
    if (
        not isinstance(normal, dict)
        or normal.get("law") != "compliance"
        or set(normal) != {"law", "p", "dp"}
        or not callable(normal["p"])
        or not callable(normal["dp"])
    ):
        raise ScenarioError(f"<dict>: field `contact[{k}].normal` = {normal!r}: {allowed}")
    for key in ("law", "c_nu"):
        if key in c:
            raise ScenarioError(
                f"<dict>: field `contact[{k}].{key}` = {c[key]!r}: not with `normal` (the "
                "normal law is the one `normal` gives)"
            )
    p = normal["p"]
    return (k, "compliance", p, normal["dp"], f"{_fname(p)}, part {c.get('part')!r}")


def extract(d: Dict[str, Any]) -> Tuple[Dict[str, Any], List[Law]]:
    """The scenario dict ``d`` with every Python law replaced by a placeholder law the
    schema accepts, and the laws taken out."""
    contact = d.get("contact")
    if not isinstance(contact, list):
        return d, []
    laws: List[Law] = []
    entries = []
    for k, c in enumerate(contact):
        if not isinstance(c, dict):
            entries.append(c)
            continue
        friction = c.get("friction")
        mu = friction.get("mu") if isinstance(friction, dict) else None
        law = _friction_law(k, c.get("part"), mu)
        if law is not None:
            laws.append(law)
            c = dict(c)
            c["friction"] = dict(friction, mu={"law": "constant", "mu": 0.0})
        if "normal" in c:
            laws.append(_normal_law(k, c))
            c = {key: v for key, v in c.items() if key != "normal"}
            c.update(law="normal-compliance", c_nu=1.0)
        entries.append(c)
    if not laws:
        return d, []
    out = dict(d)
    out["contact"] = entries
    return out, laws


def restore(d: Dict[str, Any], laws: List[Law]) -> Dict[str, Any]:
    """The inverse of :func:`extract` on a dict of the schema."""
    for k, kind, f, df, _ in laws:
        c = d["contact"][k]
        if kind == "slip":
            c["friction"]["mu"] = f
        elif kind == "position":
            c["friction"]["mu"] = {"law": "position", "function": f}
        else:
            c.pop("law", None)
            c.pop("c_nu", None)
            c["normal"] = {"law": "compliance", "p": f, "dp": df}
    return d


#: What an array of a dtype kind that is not a number holds, in messages.
_NOT_NUMBERS = {
    "b": "boolean values",
    "c": "complex values",
    "U": "strings",
    "S": "bytes",
    "M": "datetimes",
    "m": "time spans (timedelta)",
    "V": "raw or structured values",
}

#: Why converting such values to floats would be wrong, where it would succeed.
_WHY = {
    "b": "; True would count as 1",
    "c": "; the imaginary part would be lost",
    "U": "; text is not parsed as a number",
    "S": "; text is not parsed as a number",
}


def _is_real_number(v: Any) -> bool:
    """Whether ``v`` is a real number: an int or float (Python's or numpy's, any
    :class:`numbers.Real`, or a :class:`decimal.Decimal`), not a bool."""
    return isinstance(v, (numbers.Real, decimal.Decimal)) and not isinstance(v, (bool, np.bool_))


def _real(y: Any, name: str, what: str) -> np.ndarray:
    """The values ``y`` a law returned as a float array, if they are real numbers (floats
    or integers, dtype kinds ``i``, ``u`` and ``f``, or objects that are such numbers):
    every other dtype — booleans, complex numbers (even with a zero imaginary part),
    strings, bytes, datetimes and time spans, raw or structured values — and objects
    that are not real numbers (strings, ``None``, …) are a :class:`ScenarioError` naming
    the law and the dtype or value — converting them would turn ``True`` into 1, drop an
    imaginary part or parse ``"0.3"`` as a number without a word."""
    allowed = f"real numbers (float or int), one per {what}"
    try:
        a = np.asarray(y)
    except (TypeError, ValueError):
        raise ScenarioError(f"{name}: returned a {type(y).__name__}: {allowed}") from None
    kind = a.dtype.kind
    if kind == "O":
        for bad in a.flat:
            if not _is_real_number(bad):
                raise ScenarioError(f"{name}: returned a {type(bad).__name__} value ({bad!r}): {allowed}")
        try:
            return a.astype(float)
        except (TypeError, ValueError, OverflowError):
            raise ScenarioError(f"{name}: returned a {type(y).__name__}: {allowed}") from None
    if kind in "iuf":
        return a.astype(float)
    if a.shape == () and kind in "US":
        raise ScenarioError(f"{name}: returned a {type(y).__name__} ({y!r}): {allowed}")
    held = _NOT_NUMBERS.get(kind, "values that are not numbers")
    raise ScenarioError(f"{name}: returned {held} (dtype {a.dtype}): {allowed}{_WHY.get(kind, '')}")


def evaluate(f: Callable[..., Any], data: bytes, dim: int, name: str, what: str) -> bytes:
    """The user's callable ``f`` at the points of ``data`` (float64 bytes: slips or
    penetrations (m) for ``dim == 0``, else positions (m), ``dim`` per point), as float64
    bytes, one value per point. An exception of ``f`` propagates as itself, with a note
    naming the law (Python ≥ 3.11); a result of the wrong shape or type (anything but real
    numbers: booleans, complex numbers, strings, bytes, datetimes, other objects) is a
    :class:`ScenarioError` naming the law. ``what`` names
    the argument in messages."""
    x = np.frombuffer(data, dtype="<f8").copy()
    if dim > 0:
        x = x.reshape(-1, dim)
    n = x.shape[0]
    try:
        y = f(x)
    except Exception as e:
        if hasattr(e, "add_note"):
            e.add_note(f"raised by the law {name}")
        raise
    values = _real(y, name, what)
    if values.shape == ():
        values = np.full(n, float(values))
    if values.shape != (n,):
        raise ScenarioError(
            f"{name}: returned an array of shape {values.shape} for {n} {what}s: one value "
            f"per {what}"
        )
    return np.ascontiguousarray(values, dtype="<f8").tobytes()
