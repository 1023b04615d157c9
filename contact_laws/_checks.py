"""Parameter checks shared by the laws and the model: each names the field and the range."""

from __future__ import annotations

import math
from numbers import Integral, Real


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
              whole_floats: bool = False) -> int:
    """Return ``value`` as an int, or raise naming ``owner.field`` and the allowed range.

    Python and numpy integers are accepted, ``bool`` is not. With ``whole_floats`` a float
    of integral value (``3.0``, ``numpy.float64(3)``) is accepted too. A value of another
    type raises ``TypeError``; one outside ``[low, high]`` (either bound optional) raises
    ``ValueError``. ``high_label`` names the upper bound where it is derived (``"N − 1"``).
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
    return number
