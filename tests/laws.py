"""Law factories shared by the tests: every built-in law, and one written by a user."""

import math
from dataclasses import dataclass

from hypothesis import strategies as st

import contact_laws as cl


@dataclass(frozen=True, kw_only=True)
class CubicSpring(cl.NormalLaw):
    """A user's own normal law, N = k1 δ + k3 δ³, in a few lines."""

    linear: float
    cubic: float

    def __post_init__(self):
        cl.check_real("CubicSpring", "linear", self.linear, low=0.0, unit="N/m")
        cl.check_real("CubicSpring", "cubic", self.cubic, low=0.0, unit="N/m³")

    @staticmethod
    def normal_force(penetration, rate, linear, cubic):
        return linear * penetration + cubic * penetration**3


@dataclass(frozen=True, kw_only=True)
class PreloadedStop(cl.NormalLaw):
    """A stop held by a preloaded spring, N = F0 + k δ: the force jumps to F0 on contact.

    It may also carry the faults a law of one's own can have, for the tests of how a run
    stops: NaN beyond δ = ``reach``, as an interpolation table read past its end gives, and
    a force that jumps by ``jump`` where δ passes ``step``; by default it has neither.
    They are fields, not classes of their own, because each law class of one's own
    compiles a kernel: every scene with a stop and Coulomb friction shares one."""

    preload: float
    stiffness: float
    reach: float = math.inf
    step: float = math.inf
    jump: float = 0.0

    def __post_init__(self):
        cl.check_real("PreloadedStop", "preload", self.preload, low=0.0, unit="N")
        cl.check_real("PreloadedStop", "stiffness", self.stiffness, low=0.0, unit="N/m")

    @staticmethod
    def normal_force(penetration, rate, preload, stiffness, reach, step, jump):
        if penetration > reach:
            return math.nan
        return preload + stiffness * penetration + (jump if penetration > step else 0.0)


@dataclass(frozen=True, kw_only=True)
class RationalWeakening(cl.FrictionLaw):
    """A user's own friction law, μ = μ_k + (μ_s − μ_k)/(1 + |v|/v_c)."""

    mu_static: float
    mu_kinetic: float
    speed: float

    def __post_init__(self):
        mu_s = cl.check_real("RationalWeakening", "mu_static", self.mu_static, low=0.0)
        cl.check_real("RationalWeakening", "mu_kinetic", self.mu_kinetic, low=0.0, high=mu_s,
                      high_label="mu_static")
        cl.check_real("RationalWeakening", "speed", self.speed, low=0.0, low_open=True)

    @staticmethod
    def coefficient(slip_speed, mu_static, mu_kinetic, speed):
        return mu_kinetic + (mu_static - mu_kinetic) / (1.0 + slip_speed / speed)


@dataclass(frozen=True, kw_only=True)
class StaticKinetic(cl.FrictionLaw):
    """A user's own textbook friction: μ_s at rest, μ_k < μ_s as soon as it slips, so the
    friction jumps down at breakaway (μ(0⁺) = μ_k)."""

    mu_static: float
    mu_kinetic: float

    def __post_init__(self):
        mu_s = cl.check_real("StaticKinetic", "mu_static", self.mu_static, low=0.0)
        cl.check_real("StaticKinetic", "mu_kinetic", self.mu_kinetic, low=0.0, high=mu_s,
                      high_label="mu_static")

    @staticmethod
    def coefficient(slip_speed, mu_static, mu_kinetic):
        return mu_kinetic if slip_speed > 0.0 else mu_static


def normal_laws(stiffness=st.floats(1e4, 1e7)):
    return st.one_of(
        st.builds(cl.LinearSpring, stiffness=stiffness),
        st.builds(cl.Hertz, stiffness=stiffness, exponent=st.floats(1.0, 2.0)),
        st.builds(cl.KelvinVoigt, stiffness=stiffness, damping=st.floats(0.0, 50.0)),
        st.builds(cl.HuntCrossley, stiffness=stiffness, damping=st.floats(0.0, 5.0),
                  exponent=st.floats(1.0, 2.0)),
        st.builds(cl.ConstantLoad, force=st.floats(0.0, 100.0)),
        st.builds(CubicSpring, linear=stiffness, cubic=st.floats(0.0, 1e12)),
    )


@st.composite
def friction_laws(draw, regularised=True):
    mu_s = draw(st.floats(0.0, 2.0))
    mu_k = draw(st.floats(0.0, 1.0)) * mu_s
    law = draw(st.sampled_from([
        cl.Coulomb(mu=mu_s),
        cl.ExponentialFriction(mu_static=mu_s, mu_kinetic=mu_k, beta=5.0),
        cl.Stribeck(mu_static=mu_s, mu_kinetic=mu_k, stribeck_velocity=0.01),
        RationalWeakening(mu_static=mu_s, mu_kinetic=mu_k, speed=0.02),
    ]))
    if regularised and draw(st.booleans()) and draw(st.booleans()):
        return cl.Regularised(law=law, velocity=draw(st.floats(1e-5, 1e-2)))
    return law


EVERY_NORMAL_LAW = [
    cl.LinearSpring(stiffness=1e5), cl.Hertz(stiffness=1e8), cl.Hertz(stiffness=1e6, exponent=1.0),
    cl.KelvinVoigt(stiffness=1e5, damping=20.0), cl.HuntCrossley(stiffness=1e8, damping=0.5),
    cl.ConstantLoad(force=10.0), CubicSpring(linear=1e5, cubic=1e13),
]
EVERY_FRICTION_LAW = [
    cl.Coulomb(mu=0.3), cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0),
    cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01),
    cl.Regularised(law=cl.Coulomb(mu=0.3), velocity=1e-3),
    RationalWeakening(mu_static=0.5, mu_kinetic=0.25, speed=0.05),
]


def static_limit(law):
    """μ_s of a friction law as the test gave it (``mu`` or ``mu_static``).

    Read from the law's own parameters, never from ``static_coefficient`` or the scene's
    arrays, so that a friction-limit test computes μ_s N without asking the code under test.
    """
    exact = law.law if isinstance(law, cl.Regularised) else law
    return float(exact.mu if isinstance(exact, cl.Coulomb) else exact.mu_static)
