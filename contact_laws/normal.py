"""Normal-contact laws N(δ, δ̇): the force pressing two shrouds apart while they overlap.

Each ``normal_force`` is called only while the contact is closed (penetration δ > 0);
``normal_force_gradient`` gives (∂N/∂δ, ∂N/∂δ̇), zero where a law clips its force at 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from ._checks import check_real
from .base import NormalLaw


@dataclass(frozen=True, kw_only=True)
class LinearSpring(NormalLaw):
    """N = k_c δ: a linear contact spring, the paper's eqs. (2)–(3).

    Parameters
    ----------
    stiffness : float
        Contact stiffness k_c > 0 [N/m].
    """

    constant_slopes: ClassVar[bool] = True
    stiffness: float

    def __post_init__(self):
        check_real("LinearSpring", "stiffness", self.stiffness, low=0.0, low_open=True, unit="N/m")

    @staticmethod
    def normal_force(penetration, rate, stiffness):
        return stiffness * penetration

    @staticmethod
    def normal_force_gradient(penetration, rate, stiffness):
        return stiffness, 0.0


@dataclass(frozen=True, kw_only=True)
class Hertz(NormalLaw):
    """N = k δ^n: Hertzian contact (n = 3/2 for two elastic spheres).

    Parameters
    ----------
    stiffness : float
        k > 0 [N/m^n].
    exponent : float
        n in [1, 3]; 1.5 is the Hertz point contact, 1 recovers ``LinearSpring``.
    """

    stiffness: float
    exponent: float = 1.5

    def __post_init__(self):
        check_real("Hertz", "stiffness", self.stiffness, low=0.0, low_open=True, unit="N/m^n")
        check_real("Hertz", "exponent", self.exponent, low=1.0, high=3.0)

    @staticmethod
    def normal_force(penetration, rate, stiffness, exponent):
        # A trial state inside a step that separates can hold δ < 0: no force, not NaN.
        depth = max(penetration, 0.0)
        if exponent == 1.5:  # the point contact: δ √δ takes a fraction of a power's time
            return stiffness * depth * math.sqrt(depth)
        return stiffness * depth ** exponent

    @staticmethod
    def normal_force_gradient(penetration, rate, stiffness, exponent):
        # ∂N/∂δ = k n δ^(n−1); at δ ≤ 0 the contact carries no force, so 0 (also for n = 1).
        if penetration <= 0.0:
            return 0.0, 0.0
        if exponent == 1.5:
            return stiffness * 1.5 * math.sqrt(penetration), 0.0
        return stiffness * exponent * penetration ** (exponent - 1.0), 0.0


@dataclass(frozen=True, kw_only=True)
class KelvinVoigt(NormalLaw):
    """N = max(0, k δ + c δ̇): a spring and a dashpot in parallel.

    The force is clipped at zero so that a separating contact never pulls the shrouds
    together.

    Parameters
    ----------
    stiffness : float
        k > 0 [N/m].
    damping : float
        c ≥ 0 [N·s/m].
    """

    stiffness: float
    damping: float

    def __post_init__(self):
        check_real("KelvinVoigt", "stiffness", self.stiffness, low=0.0, low_open=True, unit="N/m")
        check_real("KelvinVoigt", "damping", self.damping, low=0.0, unit="N·s/m")

    @staticmethod
    def normal_force(penetration, rate, stiffness, damping):
        return max(0.0, stiffness * penetration + damping * rate)

    @staticmethod
    def normal_force_gradient(penetration, rate, stiffness, damping):
        # (k, c) where the force is positive; 0 where it is clipped.
        if stiffness * penetration + damping * rate <= 0.0:
            return 0.0, 0.0
        return stiffness, damping


@dataclass(frozen=True, kw_only=True)
class HuntCrossley(NormalLaw):
    """N = max(0, k δ^n (1 + d δ̇)): Hunt–Crossley contact, damping that vanishes with δ.

    Unlike Kelvin–Voigt the force is continuous at first touch. With a coefficient of
    restitution e and an impact speed v₀, Lankarani–Nikravesh give d ≈ 3(1 − e²)/(4 v₀).

    Parameters
    ----------
    stiffness : float
        k > 0 [N/m^n].
    damping : float
        d ≥ 0 [s/m].
    exponent : float
        n in [1, 3].
    """

    stiffness: float
    damping: float
    exponent: float = 1.5

    def __post_init__(self):
        check_real("HuntCrossley", "stiffness", self.stiffness, low=0.0, low_open=True,
                   unit="N/m^n")
        check_real("HuntCrossley", "damping", self.damping, low=0.0, unit="s/m")
        check_real("HuntCrossley", "exponent", self.exponent, low=1.0, high=3.0)

    @staticmethod
    def normal_force(penetration, rate, stiffness, damping, exponent):
        return max(0.0, stiffness * max(penetration, 0.0) ** exponent * (1.0 + damping * rate))

    @staticmethod
    def normal_force_gradient(penetration, rate, stiffness, damping, exponent):
        # ∂N/∂δ = k n δ^(n−1) (1 + d δ̇), ∂N/∂δ̇ = k δ^n d; 0 where the force is clipped.
        if penetration <= 0.0 or 1.0 + damping * rate <= 0.0:
            return 0.0, 0.0
        elastic = stiffness * penetration ** exponent
        return exponent * elastic / penetration * (1.0 + damping * rate), elastic * damping


@dataclass(frozen=True, kw_only=True)
class ConstantLoad(NormalLaw):
    """N = F: a contact held closed by a preload (e.g. a centrifugally loaded damper).

    The contact never opens, whatever the relative displacement: only its tangential
    state (stick or slip) changes.

    Parameters
    ----------
    force : float
        F ≥ 0 [N].
    """

    opens: ClassVar[bool] = False
    constant_slopes: ClassVar[bool] = True
    force: float

    def __post_init__(self):
        check_real("ConstantLoad", "force", self.force, low=0.0, unit="N")

    @staticmethod
    def normal_force(penetration, rate, force):
        return force

    @staticmethod
    def normal_force_gradient(penetration, rate, force):
        return 0.0, 0.0
