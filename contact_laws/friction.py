"""Friction laws μ(|v|): the friction coefficient as a function of the slip speed.

While slipping, f = μ(|v|) N sgn(v) (paper eqs. 5–6); while stuck, |f| ≤ μ(0) N. An
interface that slips at |v| = 0 (just broken away) takes μ(0⁺), its slip side's limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from ._checks import check_real
from .base import FrictionLaw


@dataclass(frozen=True, kw_only=True)
class Coulomb(FrictionLaw):
    """μ(v) = μ: Coulomb friction with equal static and kinetic coefficients.

    Parameters
    ----------
    mu : float
        μ ≥ 0 [-].
    """

    constant_slopes: ClassVar[bool] = True
    mu: float

    def __post_init__(self):
        check_real("Coulomb", "mu", self.mu, low=0.0)

    @staticmethod
    def coefficient(slip_speed, mu):
        return mu

    @staticmethod
    def coefficient_slope(slip_speed, mu):
        return 0.0


@dataclass(frozen=True, kw_only=True)
class ExponentialFriction(FrictionLaw):
    """μ(v) = μ_m + (μ_s − μ_m) exp(−β |v|): the paper's velocity-weakening law, eq. (4).

    Parameters
    ----------
    mu_static : float
        μ_s ≥ 0, the static (maximum) coefficient [-].
    mu_kinetic : float
        μ_m in [0, μ_s], the kinetic coefficient approached at high slip speed [-].
    beta : float
        β ≥ 0, the decay rate [s/m] (applied to the physical slip speed in m/s).
    """

    mu_static: float
    mu_kinetic: float
    beta: float

    def __post_init__(self):
        mu_static = check_real("ExponentialFriction", "mu_static", self.mu_static, low=0.0)
        check_real("ExponentialFriction", "mu_kinetic", self.mu_kinetic, low=0.0, high=mu_static,
                   high_label="mu_static")
        check_real("ExponentialFriction", "beta", self.beta, low=0.0, unit="s/m")

    @staticmethod
    def coefficient(slip_speed, mu_static, mu_kinetic, beta):
        return mu_kinetic + (mu_static - mu_kinetic) * math.exp(-beta * slip_speed)

    @staticmethod
    def coefficient_slope(slip_speed, mu_static, mu_kinetic, beta):
        return -beta * (mu_static - mu_kinetic) * math.exp(-beta * slip_speed)


@dataclass(frozen=True, kw_only=True)
class Stribeck(FrictionLaw):
    """μ(v) = μ_k + (μ_s − μ_k) exp(−(|v|/v_s)^δ): Stribeck velocity weakening.

    Parameters
    ----------
    mu_static : float
        μ_s ≥ 0 [-].
    mu_kinetic : float
        μ_k in [0, μ_s] [-].
    stribeck_velocity : float
        v_s > 0 [m/s], the speed over which μ falls from μ_s towards μ_k.
    exponent : float
        δ in (0, 10]; 2 is the Gaussian shape most often fitted.
    """

    mu_static: float
    mu_kinetic: float
    stribeck_velocity: float
    exponent: float = 2.0

    def __post_init__(self):
        mu_static = check_real("Stribeck", "mu_static", self.mu_static, low=0.0)
        check_real("Stribeck", "mu_kinetic", self.mu_kinetic, low=0.0, high=mu_static,
                   high_label="mu_static")
        check_real("Stribeck", "stribeck_velocity", self.stribeck_velocity, low=0.0,
                   low_open=True, unit="m/s")
        check_real("Stribeck", "exponent", self.exponent, low=0.0, low_open=True, high=10.0)

    @staticmethod
    def coefficient(slip_speed, mu_static, mu_kinetic, stribeck_velocity, exponent):
        ratio = slip_speed / stribeck_velocity
        # the Gaussian shape as a product: a fraction of a power's time
        power = ratio * ratio if exponent == 2.0 else ratio ** exponent
        return mu_kinetic + (mu_static - mu_kinetic) * math.exp(-power)

    @staticmethod
    def coefficient_slope(slip_speed, mu_static, mu_kinetic, stribeck_velocity, exponent):
        # −(μ_s − μ_k) δ r^(δ−1) e^(−r^δ) / v_s with r = |v|/v_s; at |v| = 0 it is 0 for
        # δ > 1, −(μ_s − μ_k)/v_s for δ = 1 and −inf for δ < 1.
        ratio = slip_speed / stribeck_velocity
        if ratio == 0.0 and exponent != 1.0:
            return 0.0 if exponent > 1.0 else -math.inf
        if exponent == 2.0:
            return -(mu_static - mu_kinetic) * 2.0 * ratio * math.exp(-(ratio * ratio)) \
                / stribeck_velocity
        return -(mu_static - mu_kinetic) * exponent * ratio ** (exponent - 1.0) \
            * math.exp(-(ratio ** exponent)) / stribeck_velocity


@dataclass(frozen=True, kw_only=True)
class Regularised(FrictionLaw):
    """f = μ(|v|) N tanh(v / v_ε): a smoothed version of an exact friction law.

    The set-valued sign at v = 0 is replaced by ``tanh(v / v_ε)``, so the interface never
    sticks: it creeps at speeds of order v_ε under a tangential load below μ_s N. Use it only
    when asked for: it trades the exact stick phases for a stiff smooth problem, and it
    converges to the exact law as v_ε → 0.

    Parameters
    ----------
    law : FrictionLaw
        The exact law giving μ(|v|).
    velocity : float
        The regularisation velocity v_ε > 0 [m/s].

    In a scene file, where ``law`` names the class, the exact law is the table ``exact``:
    ``friction = {law = "Regularised", exact = {law = "Coulomb", mu = 0.3}, velocity = 1e-3}``.
    """

    law: FrictionLaw
    velocity: float

    def __post_init__(self):
        if not isinstance(self.law, FrictionLaw) or isinstance(self.law, Regularised):
            raise TypeError("Regularised.law must be an exact FrictionLaw (not itself "
                            f"regularised), got {self.law!r}")
        check_real("Regularised", "velocity", self.velocity, low=0.0, low_open=True, unit="m/s")

    def parameters(self) -> tuple[float, ...]:
        return self.law.parameters()

    @property
    def regularisation_velocity(self) -> float:
        return float(self.velocity)

    @property
    def exact(self) -> FrictionLaw:
        return self.law

    def __call__(self, slip_speed: float) -> float:
        return self.law(slip_speed)

    def slope(self, slip_speed: float) -> float:
        return self.law.slope(slip_speed)
