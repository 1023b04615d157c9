"""Random blade groups and consistent random states, for property tests."""

import math

import numpy as np
from hypothesis import strategies as st

from shroudnet import Blade, BladeGroup, Excitation, Interface, Mode, Scene
from shroudnet.engine.clusters import cluster_labels
from tests.laws import friction_laws, normal_laws

GAP = 1e-5


@st.composite
def blades(draw):
    return Blade(mass=draw(st.floats(0.01, 1.0)), damping=draw(st.floats(0.0, 10.0)),
                 stiffness=draw(st.floats(1e4, 1e6)))


@st.composite
def interfaces(draw, angle=st.floats(0.0, math.pi / 2)):
    return Interface(gap=draw(st.floats(-GAP, GAP)), angle=draw(angle),
                     normal=draw(normal_laws()),
                     friction=draw(st.one_of(st.none(), friction_laws())))


@st.composite
def scenes(draw, shapes=("chain", "ring", "grounded chain"), n=st.integers(2, 6)):
    """A chain, a ring, or a chain held by fixed nodes at both ends, with random parts."""
    shape = draw(st.sampled_from(shapes))
    count = draw(n if shape != "ring" else n.filter(lambda k: k >= 3))
    names = [f"b{i}" for i in range(count)]
    group = BladeGroup()
    for name in names:
        group.add_blade(name, draw(blades()))
    pairs = list(zip(names, names[1:]))
    if shape == "ring":
        pairs.append((names[-1], names[0]))
    if shape == "grounded chain":
        group.add_fixed("disc").add_fixed("casing")
        pairs = [("disc", names[0])] + pairs + [(names[-1], "casing")]
    for left, right in pairs:
        group.connect(left, right, draw(interfaces()))
    phases = draw(st.lists(st.floats(0.0, 2 * math.pi), min_size=count, max_size=count))
    excitation = Excitation(engine_order=draw(st.integers(1, 4)),
                            amplitudes=(draw(st.floats(-20.0, 20.0)), draw(st.floats(0.0, 50.0)),
                                        draw(st.floats(0.0, 10.0))),
                            phases=phases)
    return Scene(group=group, excitation=excitation, speed_rpm=draw(st.floats(1000.0, 9000.0)))


@st.composite
def states(draw, scene, stick=st.booleans()):
    """(t, x, v, modes) consistent with each other: stuck blades share one velocity."""
    a = scene.arrays
    n = a.n_blades
    x = np.array(draw(st.lists(st.floats(-4 * GAP, 4 * GAP), min_size=n, max_size=n)))
    u = np.where(a.left >= 0, x[a.left], 0.0) - np.where(a.right >= 0, x[a.right], 0.0)
    closed = ((u - a.gap) * a.sin_angle > 0) | ~a.opens
    stuck = np.array([bool(closed[e] and a.can_stick[e] and draw(stick))
                      for e in range(a.n_interfaces)], dtype=bool)
    labels, grounded, _ = cluster_labels(n, n, a.left, a.right, stuck)
    cluster_v = np.array(draw(st.lists(st.floats(-1.0, 1.0), min_size=len(grounded),
                                       max_size=len(grounded))))
    v = np.where(grounded[labels], 0.0, cluster_v[labels])
    du = np.where(a.left >= 0, v[a.left], 0.0) - np.where(a.right >= 0, v[a.right], 0.0)
    modes = np.where(~closed, Mode.OPEN,
                     np.where(stuck, Mode.STICK,
                              np.where(du >= 0, Mode.SLIP_POSITIVE, Mode.SLIP_NEGATIVE)))
    t = draw(st.floats(0.0, 1.0)) * scene.excitation_period
    return t, x, v, modes


def incidence(scene):
    """B (n_interfaces × n_blades): +1 at the left blade, −1 at the right blade."""
    a = scene.arrays
    B = np.zeros((a.n_interfaces, a.n_blades))
    for e in range(a.n_interfaces):
        if a.left[e] >= 0:
            B[e, a.left[e]] = 1.0
        if a.right[e] >= 0:
            B[e, a.right[e]] = -1.0
    return B


def external_forces(scene, t, x, v):
    """Q(t) − C ẋ − K x [N], computed here from the scene's own parts."""
    a = scene.arrays
    q = np.full(a.n_blades, scene.excitation.amplitudes[0])
    for h, amplitude in enumerate(scene.excitation.amplitudes[1:], start=1):
        q = q + amplitude * np.sin(h * (a.excitation_frequency * t + a.phases))
    return a.excitation_scale * q - a.damping * v - a.stiffness * x
