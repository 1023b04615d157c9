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

Between points of substructures (``BladeGroup.connect`` with (node, point) ends), whose
displacements r have d ≤ 3 components, the relative displacement is r = r_a − r_b, and the
interface may give its face's unit ``normal_direction`` n and a unit
``tangent_direction`` t in the points' frame, orthogonal to n: then δ = n·r − Δ (Δ along
the normal) and v = t·ṙ, and it pushes point a by −(N n + f t), point b by +(N n + f t).
Without directions, points of one component take the angle form above.
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
    normal_direction, tangent_direction : sequence of float, optional
        For an interface between points of d components (d ≤ 3): the unit normal n of the
        contact face and a unit tangent t orthogonal to it, in the points' frame, both
        given or neither. Then δ = n·(r_a − r_b) − Δ and v = t·(ṙ_a − ṙ_b), and ``angle``
        is not used (leave it out).
    """

    gap: float
    angle: float | None = None
    normal: NormalLaw
    friction: FrictionLaw | None = None
    normal_direction: tuple[float, ...] | None = None
    tangent_direction: tuple[float, ...] | None = None

    def __post_init__(self):
        check_real("Interface", "gap", self.gap, unit="m")
        directions = (self.normal_direction, self.tangent_direction)
        if (directions[0] is None) != (directions[1] is None):
            raise ValueError("Interface needs both normal_direction and tangent_direction, "
                             "or neither")
        if directions[0] is None:
            if self.angle is None:
                raise ValueError("Interface needs angle= (the contact angle α in [0, π/2] "
                                 "[rad]), or normal_direction= and tangent_direction=")
            check_real("Interface", "angle", self.angle, low=0.0, high=math.pi / 2,
                       unit="rad")
        else:
            if self.angle is not None:
                raise ValueError("Interface takes angle= or the directions "
                                 "(normal_direction=, tangent_direction=), not both")
            normal = _unit("normal_direction", self.normal_direction)
            tangent = _unit("tangent_direction", self.tangent_direction)
            if len(normal) != len(tangent):
                raise ValueError("Interface.normal_direction and tangent_direction must have "
                                 f"as many components, got {len(normal)} and {len(tangent)}")
            if abs(sum(a * b for a, b in zip(normal, tangent))) > _UNIT_TOLERANCE:
                raise ValueError("Interface.tangent_direction must be orthogonal to "
                                 f"normal_direction, got n·t = "
                                 f"{sum(a * b for a, b in zip(normal, tangent)):.3g}")
            object.__setattr__(self, "normal_direction", normal)
            object.__setattr__(self, "tangent_direction", tangent)
        if not isinstance(self.normal, NormalLaw):
            raise TypeError("Interface.normal must be a contact_laws.NormalLaw (e.g. "
                            f"LinearSpring(stiffness=...)), got {self.normal!r}")
        if self.friction is not None and not isinstance(self.friction, FrictionLaw):
            raise TypeError("Interface.friction must be a contact_laws.FrictionLaw or None, "
                            f"got {self.friction!r}")

    @property
    def components(self) -> int | None:
        """How many components its points must have: that of its directions, or None for
        the angle form (points of one component)."""
        return None if self.normal_direction is None else len(self.normal_direction)


#: How far from 1 a direction's length, and from 0 the normal's dot product with the
#: tangent, may be.
_UNIT_TOLERANCE = 1e-9


def _unit(name, values) -> tuple[float, ...]:
    try:
        components = tuple(float(value) for value in values)
    except (TypeError, ValueError) as error:
        raise TypeError(f"Interface.{name} must be a sequence of 1 to 3 numbers, got "
                        f"{values!r}") from error
    if not 1 <= len(components) <= 3 or not all(math.isfinite(c) for c in components):
        raise ValueError(f"Interface.{name} must hold 1 to 3 finite numbers, got {values!r}")
    length = math.sqrt(sum(c * c for c in components))
    if abs(length - 1.0) > _UNIT_TOLERANCE:
        raise ValueError(f"Interface.{name} must be a unit vector, got {values!r} of length "
                         f"{length:.6g}")
    return components
