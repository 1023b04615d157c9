"""The mode of an interface: the piece of the nonsmooth model that currently applies."""

from __future__ import annotations

from enum import IntEnum


class Mode(IntEnum):
    """Interface modes, stored as small integers in the modes arrays.

    OPEN: no contact (δ ≤ 0), no force. STICK: closed, slip velocity held at zero, friction a
    constraint force. SLIP_POSITIVE / SLIP_NEGATIVE: closed and slipping with v > 0 / v < 0,
    friction ±μ(|v|) N. A closed interface without exact friction (frictionless or
    regularised) is in a slip mode whose sign is not used.
    """

    OPEN = 0
    STICK = 1
    SLIP_POSITIVE = 2
    SLIP_NEGATIVE = 3
