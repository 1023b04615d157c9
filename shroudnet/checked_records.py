"""One check for every result record: each field holds what its annotation says, finite.

A result record (``Simulation``, ``Spectrum``, ``PeriodicOrbit``, …) is made by the library,
but it is public, and it is made again from files. ``check_record`` reads the record's
dataclass annotations and refuses, naming the record and the field, a value of another
type (``TypeError``) or a number or array that is not finite (``ValueError``), except in
the fields the record's class names in ``NON_FINITE``, which may hold NaN or ±inf (a
quantity not computed, a Lyapunov exponent of −inf after a stick phase). It knows these
annotations: ``float``, ``int``, ``bool``, ``str``, ``complex``, ``np.ndarray``,
``tuple[...]``, ``dict``, ``None`` and the project's classes, and their unions; any other
annotation is left to the record.
"""

from __future__ import annotations

import cmath
import math
import sys
from dataclasses import fields
from numbers import Complex, Integral, Real

import numpy as np

_SIMPLE = {
    "float": lambda v: isinstance(v, Real) and not isinstance(v, bool | np.bool_),
    "int": lambda v: isinstance(v, Integral) and not isinstance(v, bool | np.bool_),
    "bool": lambda v: isinstance(v, bool | np.bool_),
    "str": lambda v: isinstance(v, str),
    "complex": lambda v: isinstance(v, Complex) and not isinstance(v, bool | np.bool_),
    "np.ndarray": lambda v: isinstance(v, np.ndarray),
    "None": lambda v: v is None,
    "dict": lambda v: isinstance(v, dict),
    "tuple": lambda v: isinstance(v, tuple | list),
}


def _alternatives(annotation: str) -> list[str]:
    """The top-level members of a union annotation, each without its brackets' content."""
    parts, depth, current = [], 0, ""
    for char in annotation:
        depth += char == "["
        depth -= char == "]"
        if char == "|" and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += char
    parts.append(current.strip())
    return [part.split("[", 1)[0].strip() for part in parts]


def _matches(record, kind: str, value) -> bool | None:
    """Whether ``value`` is of ``kind``; None where the kind is not one this check knows."""
    if kind in _SIMPLE:
        return _SIMPLE[kind](value)
    found = vars(sys.modules[type(record).__module__]).get(kind)
    if isinstance(found, type):
        return isinstance(value, found)
    return None


def _finite(value, depth: int = 0) -> bool:
    """Whether a number, an array of numbers or a tuple or list of them (two levels down)
    is finite; anything else counts as finite."""
    if isinstance(value, np.ndarray):
        return value.dtype.kind not in "fc" or bool(np.isfinite(value).all())
    if isinstance(value, Integral | bool | np.bool_):
        return True
    if isinstance(value, Real):
        return math.isfinite(value)
    if isinstance(value, Complex):
        return cmath.isfinite(value)
    if isinstance(value, tuple | list) and depth < 2:
        return all(_finite(item, depth + 1) for item in value)
    return True


def check_record(record) -> None:
    """Raise naming ``Record.field`` where a field of the dataclass ``record`` is not of its
    annotated type (``TypeError``) or holds a non-finite number (``ValueError``), except in
    the fields its class names in ``NON_FINITE`` (a tuple of field names)."""
    owner = type(record).__name__
    may_be_non_finite = getattr(type(record), "NON_FINITE", ())
    for field in fields(record):
        value = getattr(record, field.name)
        annotation = field.type if isinstance(field.type, str) else getattr(
            field.type, "__name__", str(field.type))
        verdicts = [_matches(record, kind, value) for kind in _alternatives(annotation)]
        if verdicts and None not in verdicts and not any(verdicts):
            raise TypeError(f"{owner}.{field.name} must be {annotation}, got "
                            f"{type(value).__name__} {value!r:.80}")
        if field.name not in may_be_non_finite and not _finite(value):
            raise ValueError(f"{owner}.{field.name} must be finite, got a NaN or an infinity")
