"""Argument checks shared by the laws, the model and every public function: each names the
field, and the type or range allowed (``TypeError`` for a wrong type, ``ValueError`` for a
wrong value)."""

from __future__ import annotations

import inspect
import math
from numbers import Integral, Real

import numpy as np


def check_real(owner: str, field: str, value: object, *, low: float = -math.inf,
               high: float = math.inf, low_open: bool = False, unit: str = "",
               high_label: str = "") -> float:
    """Return ``value`` as a finite float, or raise naming ``owner.field`` and the allowed range.

    The range is ``[low, high]``, or ``(low, high]`` when ``low_open``; ``high_label`` names
    the upper bound where it is another field (``"mu_static"``).
    """
    name = f"{owner}.{field}"
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__} {value!r}")
    number = float(value)
    bracket = "(" if low_open or math.isinf(low) else "["
    upper = f"{high_label} = {high:g}" if high_label else f"{high:g}"
    closing = ")" if math.isinf(high) else "]"
    allowed = f"{bracket}{low:g}, {upper}{closing}" + (f" {unit}" if unit else "")
    if math.isnan(number):
        raise ValueError(f"{name} must be a number in {allowed}, got NaN")
    below = number <= low if low_open else number < low
    if below or number > high or math.isinf(number):
        raise ValueError(f"{name} must be in {allowed}, got {number:g}")
    return number


def check_int(owner: str, field: str, value: object, *, low: int | None = None,
              high: int | None = None, unit: str = "", high_label: str = "",
              whole_floats: bool = False, most: int | None = None) -> int:
    """Return ``value`` as an int, or raise naming ``owner.field`` and the allowed range.

    Python and numpy integers are accepted, ``bool`` is not. With ``whole_floats`` a float
    of integral value (``3.0``, ``numpy.float64(3)``) is accepted too. A value of another
    type raises ``TypeError``; one outside ``[low, high]`` (either bound optional) raises
    ``ValueError``. ``high_label`` names the upper bound where it is derived (``"N − 1"``).
    ``most`` is a limit of what can be computed rather than of what makes sense (the most
    periods a run can span): beyond it the message says so on its own.
    """
    name = f"{owner}.{field}" if owner else field
    kind = "an int (or a whole float)" if whole_floats else "an int"
    if isinstance(value, Integral) and not isinstance(value, bool):
        number = int(value)
    elif whole_floats and isinstance(value, Real) and not isinstance(value, bool | Integral) \
            and math.isfinite(value) and float(value).is_integer():
        number = int(value)
    else:
        raise TypeError(f"{name} must be {kind}, got {type(value).__name__} {value!r}")
    upper = f"{high_label} = {high}" if high_label else f"{high}"
    bounds = [f">= {low}"] * (low is not None) + [f"<= {upper}"] * (high is not None)
    if (low is not None and number < low) or (high is not None and number > high):
        raise ValueError(f"{name} must be an int {' and '.join(bounds)}"
                         + (f" {unit}" if unit else "") + f", got {number}")
    if most is not None and number > most:
        raise ValueError(f"{name} must be at most {most:,}" + (f" {unit}" if unit else "")
                         + f", the most that can be computed; got {number:,}")
    return number


def _name(owner: str, field: str) -> str:
    return f"{owner}.{field}" if owner else field


def _shown(value: object) -> str:
    """``value`` as a message shows it: its type and a repr cut to 80 characters."""
    text = repr(value)
    return f"{type(value).__name__} {text if len(text) <= 80 else text[:77] + '...'}"


def check_array(owner: str, field: str, value: object, *, shape: tuple[int | None, ...],
                low: float = -math.inf, high: float = math.inf, low_open: bool = False,
                unit: str = "", min_length: int = 0) -> np.ndarray:
    """Return ``value`` as a new float array of ``shape``, or raise naming ``owner.field``.

    ``shape`` gives each axis's length, ``None`` for any: ``(None,)`` is a sequence of any
    length, ``(3, 3)`` a 3 × 3 matrix and ``()`` a single number. A 0-d array, a number or a
    string where a sequence is expected, and a sequence of non-numbers, raise
    ``TypeError``; the wrong number of axes or length, fewer than ``min_length`` entries
    along the first axis, a NaN, an infinity or an entry outside ``[low, high]`` (``(low,
    high]`` when ``low_open``) raise ``ValueError``.
    """
    name = _name(owner, field)
    kind = "a number" if shape == () else (
        "a sequence of numbers" if len(shape) == 1 else f"a {len(shape)}-d array of numbers")
    if isinstance(value, str | bytes | bool | np.bool_) or value is None \
            or (_ndim(value) == 0 and shape != ()) or isinstance(value, dict | set):
        raise TypeError(f"{name} must be {kind}, got {_shown(value)}")
    try:
        raw = np.asarray(value)
        if raw.dtype.kind == "O":  # mixed: numbers only if each entry is one
            raw = np.array(value, dtype=float) if all(
                isinstance(v, Real) and not isinstance(v, bool) for v in raw.flat) else raw
    except (TypeError, ValueError) as error:
        raise TypeError(f"{name} must be {kind}, got {_shown(value)} ({error})") from None
    if raw.dtype.kind not in "iuf":
        raise TypeError(f"{name} must be {kind}, got {_shown(value)}")
    array = np.array(raw, dtype=float)
    wanted = "×".join("n" if n is None else str(n) for n in shape) or "scalar"
    if array.ndim != len(shape) or any(n is not None and n != m
                                       for n, m in zip(shape, array.shape)):
        raise ValueError(f"{name} must have shape ({wanted}), got shape {array.shape}")
    if array.ndim and array.shape[0] < min_length:
        raise ValueError(f"{name} needs at least {min_length} entries, got {array.shape[0]}")
    if not np.isfinite(array).all():
        raise ValueError(f"{name} must be finite, got values that are not finite (NaN or "
                         f"±inf) in {_shown(value)}")
    below = array <= low if low_open else array < low
    if below.any() or (array > high).any():
        bracket = "(" if low_open or math.isinf(low) else "["
        closing = ")" if math.isinf(high) else "]"
        allowed = f"{bracket}{low:g}, {high:g}{closing}" + (f" {unit}" if unit else "")
        bad = array[below | (array > high)].flat[0]
        raise ValueError(f"{name} must lie in {allowed}, got {bad:g}")
    return array


def _ndim(value: object) -> int:
    """numpy's number of axes of ``value``; −1 for a ragged nesting, which has none."""
    try:
        return np.ndim(value)
    except ValueError:
        return -1


def check_sequence(owner: str, field: str, value: object, *, expected: str = "a sequence",
                   min_length: int = 0) -> tuple:
    """Return ``value`` as a tuple if it is a list, tuple, range or 1-d array (of anything:
    the items are checked by the caller), or raise naming ``owner.field``: ``TypeError``
    for another type (a string, a number, a 0-d array, a set), ``ValueError`` for fewer
    than ``min_length`` items."""
    name = _name(owner, field)
    if not (isinstance(value, list | tuple | range)
            or (isinstance(value, np.ndarray) and value.ndim == 1)):
        raise TypeError(f"{name} must be {expected}, got {_shown(value)}")
    if len(value) < min_length:
        raise ValueError(f"{name} needs at least {min_length} items, got {len(value)}")
    return tuple(value)


def check_callable(owner: str, field: str, value: object, *, expected: str = "a function"
                   ) -> object:
    """Return ``value`` if it can be called, or raise ``TypeError`` naming ``owner.field``
    and what is ``expected`` (``"a function speed -> Scene"``)."""
    if not callable(value) or isinstance(value, type):
        raise TypeError(f"{_name(owner, field)} must be {expected}, got {_shown(value)}")
    return value


def check_calls_with(owner: str, field: str, value: object, arguments: int, *,
                     expected: str) -> object:
    """Return ``value`` if it is a callable that takes ``arguments`` positional arguments
    (as far as its signature tells), or raise ``TypeError`` naming ``owner.field`` and what
    is ``expected`` ("a callable progress(done, total)")."""
    check_callable(owner, field, value, expected=expected)
    try:
        signature = inspect.signature(value)
    except (TypeError, ValueError):  # a builtin without one: taken on trust
        return value
    try:
        signature.bind(*range(arguments))
    except TypeError:
        raise TypeError(f"{_name(owner, field)} must be {expected}, got {_shown(value)}, "
                        f"which does not take {arguments} arguments") from None
    return value


def check_instance(owner: str, field: str, value: object, kinds: type | tuple[type, ...], *,
                   expected: str = "", optional: bool = False) -> object:
    """Return ``value`` if it is an instance of ``kinds`` (or None, when ``optional``), or
    raise ``TypeError`` naming ``owner.field`` and the expected type (``expected`` words it,
    by default the types' names: "a Scene")."""
    if (optional and value is None) or isinstance(value, kinds):
        return value
    names = [k.__name__ for k in (kinds if isinstance(kinds, tuple) else (kinds,))]
    wanted = expected or "a " + " or ".join(names) + (" or None" if optional else "")
    raise TypeError(f"{_name(owner, field)} must be {wanted}, got {_shown(value)}")


def check_choice(owner: str, field: str, value: object, choices: tuple[str, ...]) -> str:
    """Return ``value`` if it is one of the strings ``choices``, or raise naming
    ``owner.field`` and the choices (``TypeError`` for a non-string)."""
    name = _name(owner, field)
    listed = ", ".join(repr(c) for c in choices)
    if not isinstance(value, str):
        raise TypeError(f"{name} must be one of {listed}, got {_shown(value)}")
    if value not in choices:
        raise ValueError(f"{name} must be one of {listed}, got {value!r}")
    return value
