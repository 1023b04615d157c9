"""The two contracts a contact law fulfils: normal-contact laws and friction laws.

A law is plain math with its parameters attached. It knows nothing of blades, interfaces or
graphs; an interface composes a gap and an angle with one law of each kind.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import ClassVar

#: Relative step of the central differences that stand in for a derivative a law does not
#: give: about the cube root of the rounding unit, which balances truncation and rounding.
DIFFERENCE_STEP = 6e-6
#: The smallest scales [m, m/s, m/s] the difference steps of ``NormalLaw.gradient`` (in δ
#: and δ̇) and ``FrictionLaw.slope`` (in |v|) are taken relative to.
PENETRATION_SCALE = 1e-6
RATE_SCALE = 1e-3
SPEED_SCALE = 1e-3
#: The slip speed [m/s] at which an interface that slips at zero speed takes its friction
#: law: the smallest positive double. A slip mode's friction at |v| = 0 is the limit
#: μ(0⁺) of its slip side, not μ(0) = μ_s, the stuck side's limit; they differ for a law
#: that jumps at 0. For a law continuous at 0, μ at this speed rounds to μ(0).
ZERO_PLUS_SPEED = 2.2250738585072014e-308


def central_difference(function: Callable[[float], float], at: float, scale: float) -> float:
    """f'(at) by a central difference, the step ``DIFFERENCE_STEP``·max(|at|, scale)."""
    step = DIFFERENCE_STEP * max(abs(at), scale)
    return (function(at + step) - function(at - step)) / (2.0 * step)


@dataclass(frozen=True)
class NormalLaw:
    """Base of normal-contact laws, N(δ, δ̇) ≥ 0.

    ``δ`` is the penetration [m] (positive when the shrouds overlap) and ``δ̇`` its rate [m/s].
    An implementer provides:

    1. a frozen dataclass (``@dataclass(frozen=True)``) deriving from ``NormalLaw`` whose
       fields are the law's parameters, each a real number in SI units;
    2. ``__post_init__`` that validates every field with a message naming the field and its
       allowed range (``contact_laws.check_real`` does it in one line);
    3. a ``@staticmethod normal_force(penetration, rate, *parameters)`` taking the fields in
       declaration order and returning the normal force [N]. It is called while the
       contact is closed (δ > 0), where it must return a finite N ≥ 0, and within a step
       that separates also at δ slightly below 0, where it must stay finite (write
       ``max(penetration, 0.0) ** n`` for a power). It must be written in plain
       arithmetic on floats (``math`` functions, ``max``, ``min``, ``if``) so that numba can
       compile it into the integrator's loop;
    4. optionally ``opens = False`` as a class attribute for a contact that never opens,
       whatever the penetration (a preloaded contact such as ``ConstantLoad``), and
       ``constant_slopes = True`` for a law whose gradient is the same at every closed
       state (N affine in δ and δ̇, as ``LinearSpring``): the tangent flow of a phase
       of such laws is then one matrix exponential;
    5. optionally a ``@staticmethod normal_force_gradient(penetration, rate, *parameters)``
       returning (∂N/∂δ [N/m], ∂N/∂δ̇ [N·s/m]), in the same plain arithmetic. Tangent
       dynamics (Jacobians, Floquet multipliers, Lyapunov exponents) need it; a law without
       it is differentiated by central differences of ``normal_force``, which costs two
       evaluations per partial derivative and about five significant digits.

    A law is evaluated with ``law(penetration, rate)`` and differentiated with
    ``law.gradient(penetration, rate)``. A scene probes a law of one's own for point 3 at
    sample penetrations and rates when it is built, and refuses it with the point at fault;
    a sampled check, not a proof.
    """

    opens: ClassVar[bool] = True
    constant_slopes: ClassVar[bool] = False

    @staticmethod
    def normal_force(penetration: float, rate: float, *parameters: float) -> float:
        raise NotImplementedError

    @staticmethod
    def normal_force_gradient(penetration: float, rate: float,
                              *parameters: float) -> tuple[float, float]:
        raise NotImplementedError

    @classmethod
    def has_analytic_gradient(cls) -> bool:
        """Whether the class gives ``normal_force_gradient`` (else central differences)."""
        return cls.normal_force_gradient is not NormalLaw.normal_force_gradient

    def gradient(self, penetration: float, rate: float = 0.0) -> tuple[float, float]:
        """(∂N/∂δ [N/m], ∂N/∂δ̇ [N·s/m]) at (δ, δ̇): the law's own, else central differences
        with steps relative to max(|δ|, 1 µm) and max(|δ̇|, 1 mm/s)."""
        penetration, rate = float(penetration), float(rate)
        if self.has_analytic_gradient():
            d_penetration, d_rate = type(self).normal_force_gradient(penetration, rate,
                                                                    *self.parameters())
            return float(d_penetration), float(d_rate)
        return (central_difference(lambda d: self(d, rate), penetration, PENETRATION_SCALE),
                central_difference(lambda r: self(penetration, r), rate, RATE_SCALE))

    def parameters(self) -> tuple[float, ...]:
        """The law's parameters in declaration order, as passed to ``normal_force``."""
        return tuple(float(getattr(self, f.name)) for f in fields(self))

    def __call__(self, penetration: float, rate: float = 0.0) -> float:
        return type(self).normal_force(float(penetration), float(rate), *self.parameters())


@dataclass(frozen=True)
class FrictionLaw:
    """Base of friction laws, given by a friction coefficient μ(|v|) ≥ 0.

    While an interface slips with slip velocity ``v`` [m/s] the friction force is
    ``f = μ(|v|) N sgn(v)`` (paper eqs. 5–6); while it sticks, any ``|f| ≤ μ_s N`` with the
    static coefficient ``μ_s = μ(0)``. An implementer provides:

    1. a frozen dataclass deriving from ``FrictionLaw`` whose fields are the law's
       parameters, each a real number in SI units;
    2. ``__post_init__`` that validates every field, naming it and its allowed range;
    3. a ``@staticmethod coefficient(slip_speed, *parameters)`` taking ``|v| ≥ 0`` and the
       fields in declaration order and returning μ ≥ 0, written in plain arithmetic that numba
       can compile. It must not exceed its value at zero speed: μ(0) is the static limit.
       It may jump at zero speed (``mu_kinetic if slip_speed > 0.0 else mu_static``): an
       interface that has just broken away slips with μ(0⁺), the limit from above;
    4. optionally a ``@staticmethod coefficient_slope(slip_speed, *parameters)`` returning
       dμ/d|v| [s/m], in the same plain arithmetic, for tangent dynamics; a law without it
       is differentiated by central differences of ``coefficient``;
    5. optionally ``constant_slopes = True`` as a class attribute where μ is the same at
       every slip speed > 0 (``Coulomb``): the tangent flow of a phase is then one matrix
       exponential.

    A law is evaluated with ``law(slip_speed)`` and differentiated with
    ``law.slope(slip_speed)``; ``law.static_coefficient`` is μ(0). A scene probes a law of
    one's own for point 3 (finite, 0 ≤ μ(v) ≤ ``static_coefficient``) at slip speeds from 0
    to 100 m/s when it is built; a sampled check, not a proof.
    """

    constant_slopes: ClassVar[bool] = False

    @staticmethod
    def coefficient(slip_speed: float, *parameters: float) -> float:
        raise NotImplementedError

    @staticmethod
    def coefficient_slope(slip_speed: float, *parameters: float) -> float:
        raise NotImplementedError

    @classmethod
    def has_analytic_slope(cls) -> bool:
        """Whether the class gives ``coefficient_slope`` (else central differences)."""
        return cls.coefficient_slope is not FrictionLaw.coefficient_slope

    def slope(self, slip_speed: float) -> float:
        """dμ/d|v| [s/m] at the slip speed |v|: the law's own, else a central difference
        with a step relative to max(|v|, 1 mm/s) (one-sided at |v| = 0)."""
        speed = abs(float(slip_speed))
        if self.has_analytic_slope():
            return float(type(self).coefficient_slope(speed, *self.parameters()))
        step = DIFFERENCE_STEP * max(speed, SPEED_SCALE)
        if speed < step:  # μ is defined for |v| ≥ 0 only
            return (self(speed + step) - self(speed)) / step
        return central_difference(self, speed, SPEED_SCALE)

    def parameters(self) -> tuple[float, ...]:
        """The law's parameters in declaration order, as passed to ``coefficient``."""
        return tuple(float(getattr(self, f.name)) for f in fields(self))

    @property
    def static_coefficient(self) -> float:
        """μ_s = μ(0): the largest ratio |f|/N a stuck interface can hold."""
        return self(0.0)

    @property
    def regularisation_velocity(self) -> float:
        """0 for exact (set-valued) friction at v = 0; > 0 [m/s] for a smoothed law."""
        return 0.0

    @property
    def exact(self) -> "FrictionLaw":
        """The law whose ``coefficient`` gives μ(|v|): the law itself unless it is smoothed."""
        return self

    def __call__(self, slip_speed: float) -> float:
        return type(self).coefficient(abs(float(slip_speed)), *self.parameters())
