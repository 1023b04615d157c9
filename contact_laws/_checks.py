"""Parameter checks shared by the laws: each names the field and the allowed range."""

from __future__ import annotations

import math
from numbers import Real


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
