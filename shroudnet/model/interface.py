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
``tangent_direction`` t in the points' frame (its left node's, where the nodes carry frames
of their own: ``BladeGroup.add_blade``), orthogonal to n: then δ = n·r − Δ (Δ along
the normal) and v = t·ṙ, and it pushes point a by −(N n + f t), point b by +(N n + f t).
Without directions, points of one component take the angle form above. Points of three
components may slide in the face's plane: ``tangent_directions`` gives t₁ and t₂, and
the friction force f lies in that plane.

Stick is rigid (a constraint on the tangential relative velocity) unless the interface
has a ``tangential_stiffness`` k_t: then it is elastic, a Jenkins element whose slider w
in the tangent plane carries f = k_t (r_t − w) while |f| < μ_s N (DESIGN §7).
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
        contact face and a unit tangent t orthogonal to it, in the points' frame (the
        left node's, where nodes carry frames: ``BladeGroup.add_blade``), both
        given or neither. Then δ = n·(r_a − r_b) − Δ and v = t·(ṙ_a − ṙ_b), and ``angle``
        is not used (leave it out).
    tangent_directions : sequence of one or two unit vectors, optional
        The face's tangent plane: t₁, or t₁ and t₂ (points of 3 components), each
        orthogonal to n and to each other; one direction is ``tangent_direction``. Given
        with ``normal_direction``, in place of ``tangent_direction``.
    tangential_stiffness : float or None
        k_t [N/m] > 0 of an elastic (Jenkins) contact: while stuck the friction force is
        f = k_t (r_t − w), w the slider's position in the tangent plane, frozen until
        |f| reaches μ_s N; None (the default) for rigid stick, a constraint on the
        tangential relative velocity. Needs an exact friction law; two tangent directions
        need it (rigid stick in a plane is not supported).
    """

    gap: float
    angle: float | None = None
    normal: NormalLaw
    friction: FrictionLaw | None = None
    normal_direction: tuple[float, ...] | None = None
    tangent_direction: tuple[float, ...] | None = None
    tangent_directions: tuple[tuple[float, ...], ...] | None = None
    tangential_stiffness: float | None = None

    def __post_init__(self):
        check_real("Interface", "gap", self.gap, unit="m")
        tangents = self._tangents()
        if (self.normal_direction is None) != (tangents is None):
            raise ValueError("Interface needs both normal_direction and tangent_direction "
                             "(or tangent_directions), or neither")
        if self.normal_direction is None:
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
            tangents = _tangent_plane(normal, tangents)
            object.__setattr__(self, "normal_direction", normal)
            object.__setattr__(self, "tangent_directions", tangents)
            object.__setattr__(self, "tangent_direction",
                               tangents[0] if len(tangents) == 1 else None)
        if not isinstance(self.normal, NormalLaw):
            raise TypeError("Interface.normal must be a contact_laws.NormalLaw (e.g. "
                            f"LinearSpring(stiffness=...)), got {self.normal!r}")
        if self.friction is not None and not isinstance(self.friction, FrictionLaw):
            raise TypeError("Interface.friction must be a contact_laws.FrictionLaw or None, "
                            f"got {self.friction!r}")
        self._check_tangential_stiffness()

    def _tangents(self):
        """The tangent directions as given: ``tangent_directions``, or the one
        ``tangent_direction`` (both may be given only where they agree, as a copy made by
        ``dataclasses.replace`` gives them)."""
        one, several = self.tangent_direction, self.tangent_directions
        if several is None:
            return None if one is None else (one,)
        if isinstance(several, (str, bytes)) or not hasattr(several, "__len__") \
                or getattr(several, "ndim", 1) == 0:
            raise TypeError("Interface.tangent_directions must be a sequence of one or two "
                            f"unit vectors, got {several!r}")
        if one is not None and (len(several) != 1 or _unit("tangent_direction", one)
                                != _unit("tangent_directions[0]", several[0])):
            raise ValueError("Interface takes tangent_direction= or tangent_directions=, "
                             "not both")
        return tuple(several)

    def _check_tangential_stiffness(self):
        stiffness = self.tangential_stiffness
        if stiffness is not None:
            object.__setattr__(self, "tangential_stiffness", check_real(
                "Interface", "tangential_stiffness", stiffness, low=0.0, low_open=True,
                unit="N/m"))
            if self.friction is None or self.friction.regularisation_velocity > 0.0:
                raise ValueError("Interface.tangential_stiffness needs an exact friction "
                                 "law (friction=, not regularised): k_t is the stiffness "
                                 "of the contact while it sticks")
        elif self.friction is not None and len(self.tangent_directions or ()) == 2:
            raise ValueError("Interface: rigid stick in two tangent directions is not "
                             "supported; give the contact its tangential_stiffness= k_t "
                             "[N/m] > 0 (elastic stick), or one tangent direction")

    @property
    def components(self) -> int | None:
        """How many components its points must have: that of its directions, or None for
        the angle form (points of one component)."""
        return None if self.normal_direction is None else len(self.normal_direction)

    @property
    def elastic(self) -> bool:
        """Whether it sticks elastically (a finite ``tangential_stiffness``)."""
        return self.tangential_stiffness is not None


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


def _tangent_plane(normal, tangents) -> tuple[tuple[float, ...], ...]:
    """The tangent directions checked: one or two unit vectors of the normal's length,
    orthogonal to it and to each other."""
    if not 1 <= len(tangents) <= 2:
        raise ValueError("Interface.tangent_directions must hold one or two directions, got "
                         f"{len(tangents)}")
    name = "tangent_direction" if len(tangents) == 1 else "tangent_directions"
    units = tuple(_unit(name if len(tangents) == 1 else f"{name}[{k}]", t)
                  for k, t in enumerate(tangents))
    for k, tangent in enumerate(units):
        label = name if len(units) == 1 else f"{name}[{k}]"
        if len(tangent) != len(normal):
            raise ValueError(f"Interface.normal_direction and {label} must have as many "
                             f"components, got {len(normal)} and {len(tangent)}")
        if abs(_dot(normal, tangent)) > _UNIT_TOLERANCE:
            raise ValueError(f"Interface.{label} must be orthogonal to normal_direction, "
                             f"got n·t = {_dot(normal, tangent):.3g}")
    if len(units) == 2 and abs(_dot(*units)) > _UNIT_TOLERANCE:
        raise ValueError("Interface.tangent_directions must be orthogonal to each other, got "
                         f"t₁·t₂ = {_dot(*units):.3g}")
    return units


def _dot(a, b) -> float:
    return sum(p * q for p, q in zip(a, b))
