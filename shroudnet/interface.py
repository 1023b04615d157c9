"""Interfaces: the edges of a group, where two shrouds may touch, rub and stick.

Sign convention, with the interface's left blade i and right blade j::

        blade i                 blade j
      ┌────────┐   gap Δ    ┌────────┐
      │        │◄──────────►│        │      x →
      └────────┘            └────────┘
   relative displacement u = x_i − x_j;   the contact closes when u > Δ

The contact face is inclined at the contact angle α to the direction of motion, so
penetration δ = (u − Δ) sin α, slip velocity v = u̇ cos α, and the interface pushes blade i
by −F and blade j by +F with F = N sin α + f cos α (paper eqs. 2–7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from contact_laws import FrictionLaw, NormalLaw, check_real


@dataclass(frozen=True, kw_only=True)
class Interface:
    """One shroud interface: geometry composed with a normal law and a friction law.

    Parameters
    ----------
    gap : float
        Δ [m], the clearance at rest along x; negative means interference (preload).
    angle : float
        The contact angle α in [0, π/2] [rad]. α = π/2 is a face normal to x (pure impact, no
        tangential force along x); α = 0 a face along x (pure rubbing, no normal push).
    normal : contact_laws.NormalLaw
        The normal-contact law N(δ, δ̇).
    friction : contact_laws.FrictionLaw or None
        The friction law μ(|v|); None for a frictionless interface.
    """

    gap: float
    angle: float
    normal: NormalLaw
    friction: FrictionLaw | None = None

    def __post_init__(self):
        check_real("Interface", "gap", self.gap, unit="m")
        check_real("Interface", "angle", self.angle, low=0.0, high=math.pi / 2, unit="rad")
        if not isinstance(self.normal, NormalLaw):
            raise TypeError("Interface.normal must be a contact_laws.NormalLaw (e.g. "
                            f"LinearSpring(stiffness=...)), got {self.normal!r}")
        if self.friction is not None and not isinstance(self.friction, FrictionLaw):
            raise TypeError("Interface.friction must be a contact_laws.FrictionLaw or None, "
                            f"got {self.friction!r}")
