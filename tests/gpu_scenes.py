"""Scenes for the tests of batches on a GPU, shared by the test process and the simulator's.

``every_law`` is a grounded chain of five blades whose six interfaces carry every built-in
law (and a normal and a friction law of a user's own, ``tests.laws``), so that one batch
kernel, compiled once, covers them all.
"""


import contact_laws as cl
from shroudnet import AntiPhase, Blade, BladeGroup, Excitation, Interface, Scene
from tests.laws import CubicSpring, RationalWeakening

#: Each interface's laws, from the disc to the casing.
LAWS = (
    (cl.LinearSpring(stiffness=2e5), cl.Coulomb(mu=0.5)),
    (cl.Hertz(stiffness=1e8), cl.ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0)),
    (cl.KelvinVoigt(stiffness=2e5, damping=20.0),
     cl.Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.01)),
    (cl.HuntCrossley(stiffness=1e8, damping=0.5),
     cl.Regularised(law=cl.Coulomb(mu=0.4), velocity=1e-3)),
    (CubicSpring(linear=2e5, cubic=1e13),
     RationalWeakening(mu_static=0.5, mu_kinetic=0.25, speed=0.05)),
    (cl.ConstantLoad(force=5.0), cl.Coulomb(mu=0.3)),
)


def every_law(speed_rpm: float = 4800.0, q1: float = 30.0) -> Scene:
    """The chain disc – b0 … b4 – casing, each interface with a pair of ``LAWS``, a gap
    of 10 µm and a contact angle of 0.3 rad (tan α ≈ 0.31 below the static
    coefficients, so interfaces can stick), forced in anti-phase in engine order 2."""
    group = BladeGroup().add_fixed("disc")
    names = [f"b{i}" for i in range(5)]
    for i, name in enumerate(names):
        group.add_blade(name, Blade(mass=0.1 + 0.01 * i, damping=2.0, stiffness=1e5))
    group.add_fixed("casing")
    ends = ["disc", *names, "casing"]
    for (left, right), (normal, friction) in zip(zip(ends, ends[1:]), LAWS):
        group.connect(left, right, Interface(gap=1e-5, angle=0.3, normal=normal,
                                             friction=friction))
    return Scene(group=group, excitation=Excitation(engine_order=2, amplitudes=(0.0, q1),
                                                    phases=AntiPhase()),
                 speed_rpm=speed_rpm)


#: The speeds of the batch [rpm]: about the blades' resonance (f = 159 Hz at l = 2 is
#: 4770 rpm) and away from it.
SPEEDS = (4200.0, 4600.0, 4900.0, 5300.0, 5800.0)
#: The runs' lengths and steps: short, as the simulator runs each thread in Python.
RUNS = {"transient": 2, "record": 3, "samples_per_period": 8}
STEPS_PER_PERIOD = 64
