"""The compiled loop's own law evaluation: every law, through the kernel's dispatch.

The kernel calls each interface's law by the index of its class and a padded row of its
parameters. A wrong index, a parameter passed out of order or a sign lost in the dispatch
would not show in the law's own tests; here the kernel's normal and friction forces are
held against the forces written out by hand from each law's formula (paper eqs. 2–6).
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import contact_laws as cl
from shroudnet import Blade, BladeGroup, Excitation, Interface, Mode, Scene
from shroudnet.engine.generate import kernel_scene, load_kernel
from shroudnet.engine.records import new_work
from tests.laws import CubicSpring, RationalWeakening

#: One interface for each law, each normal law paired with a different friction law, with
#: every parameter distinct so that a swapped pair changes the force. Beside each law, its
#: formula: N(δ, δ̇) [N] or μ(|v|), written out here from the law's documented definition.
NORMAL = [
    (cl.LinearSpring(stiffness=3.0e5), lambda d, r: 3.0e5 * d),
    (cl.Hertz(stiffness=2.0e9, exponent=1.5), lambda d, r: 2.0e9 * d ** 1.5),
    (cl.KelvinVoigt(stiffness=4.0e5, damping=30.0), lambda d, r: max(0.0, 4.0e5 * d + 30.0 * r)),
    (cl.HuntCrossley(stiffness=5.0e9, damping=0.7, exponent=1.3),
     lambda d, r: max(0.0, 5.0e9 * d ** 1.3 * (1.0 + 0.7 * r))),
    (cl.ConstantLoad(force=12.5), lambda d, r: 12.5),
    (CubicSpring(linear=2.0e5, cubic=7.0e13), lambda d, r: 2.0e5 * d + 7.0e13 * d ** 3),
]
FRICTION = [
    (cl.Coulomb(mu=0.35), lambda v: 0.35),
    (cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0),
     lambda v: 0.3 + 0.2 * math.exp(-5.0 * v)),
    (cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01),
     lambda v: 0.2 + 0.4 * math.exp(-(v / 0.01) ** 2)),
    (RationalWeakening(mu_static=0.45, mu_kinetic=0.25, speed=0.05),
     lambda v: 0.25 + 0.2 / (1.0 + v / 0.05)),
    (cl.Regularised(law=cl.Coulomb(mu=0.4), velocity=1e-3), lambda v: 0.4),
    (None, None),
]
REGULARISED = 4  # the index of the Regularised law above: f = μ N tanh(v / v_ε)


def all_laws_scene():
    """Six blades in a chain of five interfaces and a sixth to a fixed node."""
    group = BladeGroup()
    names = [f"b{i}" for i in range(6)]
    for name in names:
        group.add_blade(name, Blade(mass=0.1, damping=1.0, stiffness=1e5))
    group.add_fixed("disc")
    pairs = list(zip(names, names[1:])) + [(names[-1], "disc")]
    for (left, right), (normal, _), (friction, _) in zip(pairs, NORMAL, FRICTION):
        group.connect(left, right, Interface(gap=1e-5, angle=0.7, normal=normal,
                                             friction=friction))
    return Scene(group=group, speed_rpm=6000.0,
                 excitation=Excitation(engine_order=2, amplitudes=(0.0, 10.0), phases=[0.0] * 6))


SCENE = all_laws_scene()


def test_the_formulas_here_agree_with_the_laws_in_python():
    """A check on this file's transcription (the laws' own values are pinned by hand in
    ``test_contact_laws``), so that a failure below points at the kernel."""
    for law, formula in NORMAL:
        for d, r in ((1e-7, 0.0), (2e-6, 0.3), (5e-5, -0.2)):
            assert law(d, r) == pytest.approx(formula(d, r), rel=1e-12)
    for law, formula in FRICTION[:-1]:
        for v in (0.0, 3e-3, 0.02, 0.4):
            assert law(v) == pytest.approx(formula(v), rel=1e-12)


@pytest.mark.slow  # compiles a kernel with every law
@given(penetration=st.lists(st.floats(1e-9, 1e-4), min_size=6, max_size=6),
       rate=st.lists(st.floats(-0.5, 0.5), min_size=6, max_size=6),
       slip=st.lists(st.floats(-2.0, 2.0).filter(lambda v: v != 0.0), min_size=6, max_size=6),
       stuck=st.lists(st.booleans(), min_size=6, max_size=6))
def test_kernel_forces_follow_each_laws_formula(penetration, rate, slip, stuck):
    """Closed interfaces, slipping or stuck: N from the normal law; while slipping
    f = ±μ(|v|) N by the slip's sign (eqs. 5–6), μ N tanh(v/v_ε) when regularised; while
    stuck no sliding friction (the static one is a constraint force); open ones carry
    nothing."""
    kernel = load_kernel(SCENE)
    s = kernel_scene(SCENE)
    work = new_work.py_func(6, 6, 0)
    work.penetration[:] = penetration
    work.rate[:] = rate
    work.slip[:] = slip
    modes = np.array([Mode.STICK if hold and f is not None else
                      Mode.SLIP_POSITIVE if v > 0 else Mode.SLIP_NEGATIVE
                      for hold, v, (f, _) in zip(stuck, slip, FRICTION)], dtype=np.int64)
    kernel.forces_at(s, modes, work)
    for e in range(6):
        normal = NORMAL[e][1](penetration[e], rate[e])
        assert work.normal[e] == pytest.approx(normal, rel=1e-12, abs=1e-300)
        mu = FRICTION[e][1]
        if mu is None or modes[e] == Mode.STICK:
            expected = 0.0
        elif e == REGULARISED:
            expected = mu(abs(slip[e])) * normal * math.tanh(slip[e] / 1e-3)
        else:
            expected = math.copysign(mu(abs(slip[e])) * normal, slip[e])
        assert work.friction[e] == pytest.approx(expected, rel=1e-12, abs=1e-300)


@pytest.mark.slow  # compiles a kernel with every law
def test_open_interfaces_carry_no_force():
    kernel = load_kernel(SCENE)
    work = new_work.py_func(6, 6, 0)
    work.penetration[:] = 1e-6
    work.rate[:] = 0.1
    work.slip[:] = 0.3
    modes = np.full(6, Mode.OPEN, dtype=np.int64)
    kernel.forces_at(kernel_scene(SCENE), modes, work)
    assert not work.normal.any() and not work.friction.any()
