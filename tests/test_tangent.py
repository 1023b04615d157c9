"""Tangent dynamics: the Jacobian of every mode's vector field, the monodromy matrix
through every kind of switch, and Lyapunov exponents.

Each is checked against a reference computed here, independently of the tangent flow:
central differences of the plain-Python assembly (``assemble``), central differences of
the trajectory the plain integrator computes (``simulate``), and closed forms (damped
linear oscillators, a cluster moving as one body).

Most scenes are ``facing_pads`` scenes, which hold every built-in exact law, so that they
share one kernel with ``test_physics_references``; one with a law of the user's own shares
its kernel with ``test_prescribed`` (``beside_a_still_node``).
"""

import math
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from contact_laws import (
    ConstantLoad,
    Coulomb,
    ExponentialFriction,
    Hertz,
    HuntCrossley,
    KelvinVoigt,
    LinearSpring,
    Regularised,
    Stribeck,
)
from shroudnet import (
    Adaptive,
    Blade,
    BladeGroup,
    ConstantVelocity,
    Excitation,
    Interface,
    Scene,
    SimulationError,
    assemble,
    classify,
    lyapunov,
    monodromy,
    simulate,
)
from shroudnet.analysis.stability import stroboscopic_step
from shroudnet.engine.codes import STICK
from shroudnet.engine.generate import kernel_scene, load_kernel
from shroudnet.io.scenefile import load
from shroudnet.scenes import three_blade_paper
from tests.groups import states
from tests.laws import StaticKinetic
from tests.test_physics_references import BLADE, FAR, IDLE, IDLE_BLADE, SPEED_RPM, facing_pads

#: The trajectories the differences are taken of: as exact as the integrator goes.
EXACT = Adaptive(rtol=1e-12)
#: Relative step of the differences, and the agreement asked of the monodromy matrix.
DIFFERENCE = 1e-5
AGREEMENT = 1e-6


def stroboscopic_map(scene, periods, y, event_tolerance=1e-10):
    """The state after ``periods`` periods from y = (x, ẋ), by ``simulate``."""
    n = len(y) // 2
    run = simulate(scene, periods, method=EXACT, samples_per_period=1,
                   initial=(y[:n], y[n:]), event_capacity=0,
                   event_tolerance=event_tolerance)
    return np.concatenate([run.x[-1], run.v[-1]])


def differenced_monodromy(scene, periods, y, scale, event_tolerance=1e-10):
    """∂(map)/∂y by fourth-order central differences, step ``DIFFERENCE``·scale_j, of runs
    that locate their switches to ``event_tolerance`` [s]."""
    columns = []
    for j in range(len(y)):
        step = DIFFERENCE * scale[j]
        values = {}
        for k in (-2, -1, 1, 2):
            moved = y.copy()
            moved[j] += k * step
            values[k] = stroboscopic_map(scene, periods, moved, event_tolerance)
        columns.append((8.0 * (values[1] - values[-1]) - (values[2] - values[-2]))
                       / (12.0 * step))
    return np.array(columns).T


def state_scale(y):
    """Per component, the largest |x| or |ẋ| of the state: the scale differences and
    errors are measured against."""
    n = len(y) // 2
    return np.concatenate([np.full(n, np.abs(y[:n]).max()), np.full(n, np.abs(y[n:]).max())])


def scaled_error(matrix, reference, scale):
    """max |M − M_ref| / max |M_ref| in the coordinates y_j / scale_j."""
    inverse = 1.0 / scale
    a = inverse[:, None] * matrix * scale[None, :]
    b = inverse[:, None] * reference * scale[None, :]
    return np.abs(a - b).max() / np.abs(b).max()


def settled_state(scene, periods):
    run = simulate(scene, periods, samples_per_period=1, event_capacity=0)
    return np.concatenate([run.x[-1], run.v[-1]])


def settled_through_every_switch(scene, periods):
    """``settled_state``, whose next period closes, separates, sticks and breaks away."""
    y = settled_state(scene, periods)
    counts = simulate(scene, 1, method=EXACT, samples_per_period=1,
                      initial=np.split(y, 2)).events.counts
    assert all(counts[kind] > 0 for kind in ("closing", "separation", "sticking",
                                             "breakaway")), counts
    return y


def free_oscillators(scene, blades=None):
    """The monodromy of blades without contact: exp(A T_e), A = [[0, I], [−k/m, −c/m]]."""
    a = scene.arrays
    n = a.n_blades
    system = np.zeros((2 * n, 2 * n))
    system[:n, n:] = np.eye(n)
    system[n:, :n] = -np.diag(a.stiffness / a.mass)
    system[n:, n:] = -np.diag(a.damping / a.mass)
    return scipy.linalg.expm(system * scene.excitation_period)


# ---- the Jacobian of each mode's vector field ---------------------------------------------

ALL_LAWS = (
    Interface(gap=1e-5, angle=0.7, normal=LinearSpring(stiffness=1e6),
              friction=ExponentialFriction(mu_static=0.5, mu_kinetic=0.3, beta=5.0)),
    Interface(gap=-1e-5, angle=1.1, normal=Hertz(stiffness=1e9, exponent=1.5),
              friction=Stribeck(mu_static=0.6, mu_kinetic=0.2, stribeck_velocity=0.05)),
    Interface(gap=0.0, angle=0.4, normal=KelvinVoigt(stiffness=1e6, damping=30.0),
              friction=Coulomb(mu=0.3)),
    Interface(gap=5e-6, angle=0.9, normal=HuntCrossley(stiffness=1e9, damping=0.5),
              friction=Regularised(law=ExponentialFriction(mu_static=0.5, mu_kinetic=0.3,
                                                           beta=2.0), velocity=0.05)),
    Interface(gap=0.0, angle=1.3, normal=ConstantLoad(force=20.0),
              friction=Stribeck(mu_static=0.5, mu_kinetic=0.4, stribeck_velocity=0.02)),
)


def all_laws_chain():
    """Five blades between two fixed nodes, one interface with each built-in law."""
    group = BladeGroup().add_fixed("disc").add_fixed("casing")
    names = [f"b{i}" for i in range(5)]
    for k, name in enumerate(names):
        group.add_blade(name, Blade(mass=0.05 + 0.02 * k, damping=1.0 + k,
                                    stiffness=2e5 + 1e5 * k))
    for left, right, interface in zip(["disc"] + names[:-1], names, ALL_LAWS):
        group.connect(left, right, interface)
    excitation = Excitation(engine_order=1, amplitudes=(1.0, 20.0), phases=[0.3 * k for k in
                                                                             range(5)])
    return Scene(group=group, excitation=excitation, speed_rpm=6000.0)


CHAIN = all_laws_chain()


def differenced_field_jacobian(scene, t, y, modes):
    """∂(ẋ, ẍ)/∂(x, ẋ) by central differences of ``assemble`` in fixed modes."""
    n = len(y) // 2
    scale = np.concatenate([np.full(n, 1e-5), np.full(n, 0.1)])

    def field(state):
        return np.concatenate([state[n:], assemble(scene, t, state[:n], state[n:],
                                                   modes).acceleration])

    columns = []
    for j in range(2 * n):
        step = 1e-6 * scale[j]
        moved_up, moved_down = y.copy(), y.copy()
        moved_up[j] += step
        moved_down[j] -= step
        columns.append((field(moved_up) - field(moved_down)) / (2.0 * step))
    return np.array(columns).T


def near_a_kink(scene, x, v, modes):
    """Whether a law is evaluated within a difference step of where it has a kink: a
    contact at δ = 0 (Hertz, Hunt–Crossley) or at the clip of a damped law."""
    a = scene.arrays
    u = np.where(a.left >= 0, x[a.left], 0.0) - np.where(a.right >= 0, x[a.right], 0.0)
    du = np.where(a.left >= 0, v[a.left], 0.0) - np.where(a.right >= 0, v[a.right], 0.0)
    penetration, rate = (u - a.gap) * a.sin_angle, du * a.sin_angle
    for e, law in enumerate(a.normal_laws):
        if isinstance(law, ConstantLoad):
            continue
        if abs(penetration[e]) < 1e-8:
            return True
        if penetration[e] > 0.0 and law(penetration[e], rate[e]) < 1e-3:  # clipped
            return True
    return False


@settings(max_examples=40)
@given(data=st.data())
def test_mode_jacobian_agrees_with_differences_of_the_assembly_for_every_law(data):
    t, x, v, modes = data.draw(states(CHAIN))
    assume(not near_a_kink(CHAIN, x, v, modes))
    kernel = load_kernel(CHAIN, tangent=True)
    jacobian, acceleration = kernel.linearise_at(t, x, v, modes.astype(np.int64),
                                                 kernel_scene(CHAIN), np.zeros((10, 0)))
    reference = differenced_field_jacobian(CHAIN, t, np.concatenate([x, v]), modes)
    np.testing.assert_allclose(acceleration, assemble(CHAIN, t, x, v, modes).acceleration,
                               rtol=1e-12, atol=1e-9)
    row_scale = np.abs(reference).max(axis=1, keepdims=True) + 1.0
    assert (np.abs(jacobian - reference) <= 1e-5 * row_scale).all()


# ---- monodromy: closed forms --------------------------------------------------------------

def test_monodromy_without_contact_is_that_of_damped_linear_oscillators():
    scene = three_blade_paper(gap=1.0)
    y0 = ([1e-5, -2e-5, 3e-5], [0.01, 0.0, -0.02])
    matrix = monodromy(scene, 1, initial=y0)
    expected = free_oscillators(scene)
    assert np.abs(matrix - expected).max() <= 1e-8 * np.abs(expected).max()
    moduli = np.sort(np.abs(np.linalg.eigvals(matrix)))
    a = scene.arrays
    decay = np.exp(-a.damping / (2 * a.mass) * scene.excitation_period)
    np.testing.assert_allclose(moduli, np.sort(np.repeat(decay, 2)), rtol=1e-8)


def test_monodromy_of_an_all_stuck_cluster_moves_it_as_one_body():
    """Three blades held together by a large preload: relative displacements stay as they
    are, relative velocities vanish (projected at the start: zero multipliers), and the
    cluster's mean moves as one damped oscillator of the total mass."""
    grip = Interface(gap=0.0, angle=0.0, normal=ConstantLoad(force=1e5),
                     friction=Coulomb(mu=1.0))
    group = BladeGroup()
    for name in ("a", "b", "c"):
        group.add_blade(name, BLADE)
    group.connect("a", "b", grip).connect("b", "c", grip)
    for k, interface in enumerate(IDLE):  # the laws of the shared kernel, never reached
        group.add_blade(f"idle{k}", BLADE).add_fixed(f"pad{k}")
        group.connect(f"idle{k}", f"pad{k}", interface)
    n = 3 + len(IDLE)
    scene = Scene(group=group, excitation=Excitation(
        engine_order=1, amplitudes=(0.0, 5.0), phases=[0.0] * n), speed_rpm=6000.0)
    matrix = monodromy(scene, 1)
    cluster = [0, 1, 2, n, n + 1, n + 2]
    m, c, k = BLADE.mass, BLADE.damping, BLADE.stiffness
    body = scipy.linalg.expm(np.array([[0.0, 1.0], [-k / m, -c / m]])
                             * scene.excitation_period)
    mean = np.zeros((2, 6))  # (X, Ẋ) of the cluster from its blades' (x, ẋ)
    mean[0, :3] = mean[1, 3:] = 1.0 / 3.0
    expected = np.zeros((6, 6))
    for i in range(3):
        expected[i] = body[0] @ mean - mean[0]   # x_i = X + (x_i − X) at the start
        expected[i, i] += 1.0
        expected[3 + i] = body[1] @ mean         # ẋ_i = Ẋ
    block = matrix[np.ix_(cluster, cluster)]
    assert np.abs(block - expected).max() <= 1e-8 * np.abs(expected).max()
    assert np.sum(np.abs(np.linalg.eigvals(block)) < 1e-12) == 2  # one per stuck interface


# ---- monodromy against differences of the trajectory, every kind of switch -----------------

def pads_scene(interface, amplitudes=(0.0, 20.0), blade=BLADE):
    return facing_pads([(blade, interface)], amplitudes)


def beside_a_still_node(interface, amplitudes=(0.0, 20.0), blade=BLADE):
    """A blade facing its fixed pad across ``interface``, without idle blades, and two
    contacts that never act: one pressed by a constant load along y (α = 0, no friction:
    no force along x) on a prescribed node at rest, and a spring contact to a wall 1 m
    away. For a friction law of one's own, which gets a kernel of its own whatever the
    scene: with a constant load and a spring contact (contact events), a prescribed node
    and no other law, every such scene has the law classes and effects of
    ``test_prescribed``'s shaker case with the same friction, and they all compile one
    kernel (the compile is nearly all of such a test's time). The idle contacts add
    nothing to the motion or to the monodromy, which has the blade's rows only."""
    group = BladeGroup().add_blade("blade1", blade).add_fixed("pad1")
    group.connect("blade1", "pad1", interface)
    group.add_prescribed("still", ConstantVelocity(velocity=0.0)).add_fixed("wall")
    group.connect("blade1", "still", Interface(gap=0.0, angle=0.0,
                                                normal=ConstantLoad(force=1.0)))
    group.connect("blade1", "wall", Interface(gap=FAR, angle=1.0,
                                               normal=LinearSpring(stiffness=1e6)))
    excitation = Excitation(engine_order=1, amplitudes=amplitudes, phases=[0.0])
    return Scene(group=group, excitation=excitation, speed_rpm=SPEED_RPM)


def start_of(scene, x0, v0):
    """The state with the first blade at x0, v0 and every other one (idle) at rest."""
    idle = [0.0] * (len(scene.blades) - 1)
    return np.array([x0] + idle + [v0] + idle, dtype=float)


CASES = {
    # a blade knocking on a frictionless spring pad: impacts only
    "impact": (pads_scene(Interface(gap=1e-4, angle=1.2, normal=LinearSpring(stiffness=1e7))),
               (0.0, 0.0), 30),
    # knocking on a damped pad: the force jumps by c δ̇ sin α as the contact closes, so
    # the closing saltation has a jump term, and the contact guard's gradient counts (on a
    # spring pad N(0) = 0, and both vanish)
    "damped impact": (pads_scene(Interface(gap=1e-4, angle=1.2,
                                           normal=KelvinVoigt(stiffness=1e7, damping=100.0))),
                      (0.0, 0.0), 30),
    # knocking on a stiffening pad, N = k δ²: the contact's stiffness grows with the
    # penetration all through each impact, so every stage of a step has slopes of its own
    # (at the exponent 1.5 of a Hertz contact, N'' = ∞ at δ = 0, and the differenced runs
    # are off by 2.8e-5)
    "stiffening impact": (pads_scene(Interface(gap=1e-4, angle=1.2,
                                               normal=Hertz(stiffness=1e11, exponent=2.0))),
                          (0.0, 0.0), 30),
    # pressed against its pad and slipping to and fro: slip reversals
    "slip reversal": (pads_scene(Interface(gap=0.0, angle=0.5, normal=ConstantLoad(force=5.0),
                                           friction=ExponentialFriction(
                                               mu_static=0.5, mu_kinetic=0.3, beta=5.0))),
                      (0.0, 0.0), 20),
    # pressed harder: stick phases, breakaway and sticking every period (μ(0⁺) = μ_s: the
    # vector field is continuous at breakaway, and its saltation is P alone)
    "stick and breakaway": (pads_scene(Interface(gap=0.0, angle=0.5,
                                                 normal=ConstantLoad(force=40.0),
                                                 friction=Stribeck(mu_static=0.6,
                                                                   mu_kinetic=0.4,
                                                                   stribeck_velocity=0.05))),
                            (0.0, 0.0), 20),
    # stick and breakaway with a friction that drops from μ_s to μ_k as it slips (μ(0⁺)
    # = μ_k): the breakaway saltation's jump term (0.41 off while f⁺ took μ(0))
    "friction dropping at breakaway": (
        beside_a_still_node(Interface(gap=0.0, angle=0.5, normal=ConstantLoad(force=40.0),
                                      friction=StaticKinetic(mu_static=0.6, mu_kinetic=0.4))),
        (0.0, 0.0), 20),
    # the same friction, pressed by a preloaded spring pad: the normal force moves with
    # the blade, so the breakaway guard μ_s N − |f| changes with N too (with a constant
    # load it does not), and the jump term carries its gradient
    "stick and breakaway on a spring pad": (
        beside_a_still_node(Interface(gap=-1e-4, angle=0.5, normal=LinearSpring(stiffness=1e6),
                                      friction=StaticKinetic(mu_static=0.6, mu_kinetic=0.4)),
                            amplitudes=(0.0, 10.0)),
        (0.0, 0.0), 20),
    # the paper's group: impacts and slip on two coupled interfaces
    "paper group": (three_blade_paper(), None, 50),
}


#: Cases with a law of the user's own: they compile a kernel, one between them and
#: ``test_prescribed``'s shaker case (``beside_a_still_node``).
OWN_KERNEL = {"friction dropping at breakaway", "stick and breakaway on a spring pad"}


@pytest.mark.parametrize("case", [pytest.param(case, marks=pytest.mark.slow)
                                  if case in OWN_KERNEL else case for case in sorted(CASES)])
def test_monodromy_agrees_with_differences_of_the_trajectory(case):
    scene, start, transient = CASES[case]
    if start is None:
        y = settled_state(scene, transient)
    else:
        run = simulate(scene, transient, samples_per_period=1,
                       initial=np.split(start_of(scene, *start), 2), event_capacity=0)
        y = np.concatenate([run.x[-1], run.v[-1]])
    counts = simulate(scene, 1, method=EXACT, samples_per_period=1,
                      initial=np.split(y, 2)).events.counts
    expected_kinds = {"impact": ("closing", "separation"),
                      "damped impact": ("closing", "separation"),
                      "stiffening impact": ("closing", "separation"),
                      "slip reversal": ("reversal",),
                      "stick and breakaway": ("sticking", "breakaway"),
                      "stick and breakaway on a spring pad": ("sticking", "breakaway"),
                      "friction dropping at breakaway": ("sticking", "breakaway"),
                      "paper group": ("closing", "separation", "reversal")}[case]
    assert all(counts[kind] > 0 for kind in expected_kinds), counts
    scale = state_scale(y)
    scale[scale == 0.0] = 1.0
    n = len(y) // 2
    matrix = monodromy(scene, 1, initial=(y[:n], y[n:]), method=EXACT)
    reference = differenced_monodromy(scene, 1, y, scale, LOCATED.get(case, 1e-10))
    assert scaled_error(matrix, reference, scale) <= LOOSER.get(case, AGREEMENT)


#: Cases whose differences are noisier than the monodromy matrix's error. The damped pad's
#: force is clipped at 0 just before the contact opens (k δ + c δ̇ = 0), a kink in the
#: vector field that the steps are not located at: the differenced runs carry an error that
#: moves with their start, and their differences are off by 3.5e-5 (1.5e-4 at rtol 1e-10,
#: 5e-6 at 1e-13, converging on the monodromy matrix). A wrong saltation is off by O(1).
LOOSER = {"damped impact": 1e-4}
#: Cases whose differenced runs locate their switches closer than the default 1e-10
#: periods. Where the friction drops at breakaway the acceleration jumps, so the
#: differences feel where each switch is located: they agree to 1.4e-5 at 1e-10, and to
#: 1.6e-8 at 1e-13 (as on the shaker of ``test_prescribed``).
LOCATED = {"friction dropping at breakaway": 1e-13}


def gripped_ring(preload):
    """Four blades in a ring (stiffnesses 1, 1.1, 1.2, 1.3 × 10⁵ N/m), each interface pressed
    by ``preload`` [N] with Stribeck friction, forced with phases 0, 0.5, 1, 1.5 rad; then
    the ``IDLE`` blades of the shared kernel."""
    grip = Interface(gap=0.0, angle=0.5, normal=ConstantLoad(force=preload),
                     friction=Stribeck(mu_static=0.6, mu_kinetic=0.4, stribeck_velocity=0.05))
    names = [f"b{k}" for k in range(4)]
    group = BladeGroup()
    for k, name in enumerate(names):
        group.add_blade(name, Blade(mass=0.1, damping=2.0, stiffness=1e5 * (1 + 0.1 * k)))
    for left, right in zip(names, names[1:] + names[:1]):
        group.connect(left, right, grip)
    for k, interface in enumerate(IDLE):
        group.add_blade(f"idle{k}", IDLE_BLADE).add_fixed(f"pad{k}")
        group.connect(f"idle{k}", f"pad{k}", interface)
    phases = [0.5 * k for k in range(4)] + [0.0] * len(IDLE)
    return Scene(group=group, excitation=Excitation(engine_order=1, amplitudes=(0.0, 20.0),
                                                    phases=phases), speed_rpm=6000.0)


def stick_manifold(scene, y):
    """Directions of the state space a start y may move in and keep its stuck interfaces
    stuck: every displacement, and the common velocity of each stick cluster of the ring
    (interfaces whose two blades move alike). The idle blades' velocities are left out:
    one is stuck to its pad."""
    a = scene.arrays
    n = len(y) // 2
    v = y[n:]
    cluster = list(range(4))
    for e in range(4):
        if v[a.left[e]] == v[a.right[e]]:
            low, high = sorted((cluster[a.left[e]], cluster[a.right[e]]))
            cluster = [low if c == high else c for c in cluster]
    directions = list(np.eye(2 * n)[:n])
    for c in sorted(set(cluster)):
        d = np.zeros(2 * n)
        d[[n + i for i in range(4) if cluster[i] == c]] = 1.0
        directions.append(d)
    return directions


@pytest.mark.parametrize(("preload", "stuck", "together"), [
    (400.0, [0, 1, 2, 3], 0),   # the ring stuck all period: one cluster closing on itself
    (20.0, [0, 1, 2, 3], 0),    # stuck at the start; it breaks open and sticks again
    (12.0, [0, 2], 2),          # two clusters; interfaces 1 and 3 join them and reverse together
])
def test_monodromy_of_a_stuck_ring_agrees_with_differences_along_its_stick_clusters(
        preload, stuck, together):
    """A stuck start depends on its start only along its stick clusters (the relative
    velocities of stuck interfaces are projected away), so the differences are taken in
    those directions only. Interfaces that join the same two clusters switch at the same
    instant by construction: one switching surface, one saltation, not a refusal."""
    scene = gripped_ring(preload)
    y = settled_state(scene, 60)
    n = len(y) // 2
    assert [e for e in range(4) if y[n + scene.arrays.left[e]] == y[n + scene.arrays.right[e]]] \
        == stuck
    times = simulate(scene, 1, method=EXACT, samples_per_period=1,
                     initial=np.split(y, 2)).events.time
    assert np.sum(np.diff(times) == 0.0) == together
    matrix = monodromy(scene, 1, initial=np.split(y, 2), method=EXACT)
    scale = state_scale(y)
    scale[scale == 0.0] = 1.0
    for direction in stick_manifold(scene, y):
        step = DIFFERENCE * np.abs(scale * direction).max()
        values = {k: stroboscopic_map(scene, 1, y + k * step * direction)
                  for k in (-2, -1, 1, 2)}
        differenced = (8.0 * (values[1] - values[-1]) - (values[2] - values[-2])) / (12.0 * step)
        exact = matrix @ direction
        assert np.abs((exact - differenced) / scale).max() \
            <= AGREEMENT * np.abs(exact / scale).max()


SAME_INSTANT_PAD = Interface(gap=1e-4, angle=1.2, normal=LinearSpring(stiffness=1e7),
                             friction=Coulomb(mu=0.3))


def test_apart_interfaces_switching_at_the_same_instant_multiply_their_saltations():
    """Two identical blades, each against its own pad, started alike, switch at the same
    instant, as the sectors of a ring do by its symmetry. Their switches do not see each
    other, so the monodromy is defined; it agrees with differences of the trajectory, and
    a kick to one blade leaves the other alone."""
    scene = facing_pads([(BLADE, SAME_INSTANT_PAD), (BLADE, SAME_INSTANT_PAD)], (0.0, 20.0))
    y = settled_state(scene, 20)
    counts = simulate(scene, 1, initial=np.split(y, 2)).events.counts
    assert counts["closing"] >= 2 and counts["separation"] >= 2, counts
    n = len(y) // 2
    scale = state_scale(y)
    scale[scale == 0.0] = 1.0
    matrix = monodromy(scene, 1, initial=(y[:n], y[n:]), method=EXACT)
    # Measured 1.35e-6: the differences couple the blades through the steps they share
    # (3e-7 where the monodromy has exactly 0), and noise of that size is all they add.
    assert scaled_error(matrix, differenced_monodromy(scene, 1, y, scale), scale) \
        <= 2 * AGREEMENT
    assert np.all(matrix[[0, n], :][:, [1, n + 1]] == 0.0)
    assert np.all(matrix[[1, n + 1], :][:, [0, n]] == 0.0)


RING_24 = Path(__file__).resolve().parents[1] / "examples" / "scenes" / \
    "ring_24_travelling_wave.toml"


def test_a_rings_interfaces_switching_together_by_its_symmetry_multiply_their_saltations():
    """The 24-blade ring (Hertz contacts, Stribeck friction) forced in engine order 2, from
    a state with its half-turn symmetry: interfaces e and e + 12 switch at the same
    instants, each pair located as one switch. Where a vector field is continuous across
    its switch (stick onset, breakaway with μ(0⁺) = μ_s, closing and opening), f⁺ − P f⁻
    is rounding and location error, on the neighbours too, not a force that changed; and
    where a stick onset or a breakaway makes a neighbour hold or break away with it, that
    neighbour's jump belongs to its switch. Every pair's saltations commute: none is
    singular, and the monodromy agrees with differences of the trajectory along the stick
    clusters of its start, its multipliers with theirs."""
    scene = load(RING_24).scene
    y = settled_state(scene, 100)
    n = len(y) // 2
    half = (np.arange(n) + n // 2) % n
    y = 0.5 * (y + y[np.concatenate([half, n + half])])
    times = simulate(scene, 1, method=EXACT, samples_per_period=1,
                     initial=np.split(y, 2)).events.time
    assert np.sum(np.diff(times) == 0.0) >= 100
    step = stroboscopic_step(scene, 1, np.split(y, 2), method=EXACT)
    assert step.singular == 0, step.singular_reason("the monodromy")
    # The start's stick clusters: a start may move along their common velocity only.
    a = scene.arrays
    modes = simulate(scene, 1, samples_per_period=1, initial=np.split(y, 2)).modes[0]
    cluster = np.arange(n)
    for e in np.flatnonzero(modes == STICK):
        cluster[cluster == cluster[a.right[e]]] = cluster[a.left[e]]
    along = np.eye(2 * n)
    for i in range(n):
        members = np.flatnonzero(cluster == cluster[i])
        along[n + i] = 0.0
        along[n + i, n + members] = a.mass[members] / a.mass[members].sum()
    scale = state_scale(y)
    columns = []
    for j in range(2 * n):
        direction = along[:, j] * 1e-4 * scale[j]
        values = {k: stroboscopic_map(scene, 1, y + k * direction, 1e-13)
                  for k in (-2, -1, 1, 2)}
        columns.append((8.0 * (values[1] - values[-1]) - (values[2] - values[-2]))
                       / (12.0 * 1e-4 * scale[j]))
    reference = np.array(columns).T
    # Measured: 9.6e-7 (0.58, and 93 switches called singular, where the pairs' saltations
    # were not split); largest multipliers 1.4308716 against 1.4308713.
    assert scaled_error(step.jacobian, reference, scale) <= 2 * AGREEMENT
    exact = np.sort(np.abs(np.linalg.eigvals(step.jacobian)))[::-1][:4]
    differenced = np.sort(np.abs(np.linalg.eigvals(reference)))[::-1][:4]
    assert np.abs(exact - differenced).max() <= AGREEMENT * exact[0]


def test_interfaces_of_one_blade_switching_at_the_same_instant_are_reported():
    """A blade between two blades pushed in opposition touches both at once: the two
    switches change its acceleration together, and the monodromy says where, instead of
    multiplying in one saltation matrix."""
    group = BladeGroup().add_blade("a", BLADE).add_blade("b", IDLE_BLADE)
    group.add_blade("c", BLADE)
    group.connect("a", "b", SAME_INSTANT_PAD).connect("b", "c", SAME_INSTANT_PAD)
    for k, interface in enumerate(IDLE, start=1):  # the laws of the other tests' kernel
        group.add_blade(f"idle{k}", IDLE_BLADE).add_fixed(f"idle_pad{k}")
        group.connect(f"idle{k}", f"idle_pad{k}", interface)
    excitation = Excitation(engine_order=1, amplitudes=(0.0, 20.0),
                            phases=[0.0, 0.0, math.pi] + [0.0] * len(IDLE))
    scene = Scene(group=group, excitation=excitation, speed_rpm=6000.0)
    with pytest.raises(SimulationError, match="together with another interface"):
        monodromy(scene, 2)


# ---- Lyapunov exponents ---------------------------------------------------------------------

def test_lyapunov_exponents_without_contact_are_minus_c_over_2m():
    scene = three_blade_paper(gap=1.0)
    result = lyapunov(scene, 40, transient=0, exponents=6,
                      initial=([1e-5, 0.0, -1e-5], [0.0, 0.01, 0.0]))
    a = scene.arrays
    expected = -a.damping[0] / (2 * a.mass[0]) * scene.excitation_period
    np.testing.assert_allclose(result.per_period, expected, rtol=2e-2)
    np.testing.assert_allclose(result.per_second, expected / scene.excitation_period,
                               rtol=2e-2)


def test_sum_of_all_exponents_is_the_mean_phase_space_contraction():
    """Frictionless linear-spring impacts: the vector field's divergence is −Σ c_i/m_i in
    every mode and each switch keeps phase-space volume (the field is continuous there),
    so the 2N exponents sum to −Σ c_i/m_i · T_e per period."""
    scene = three_blade_paper(gamma1=1.0, friction=None)
    result = lyapunov(scene, 20, transient=20, exponents=6)
    assert simulate(scene, 5).events.counts["closing"] > 0
    a = scene.arrays
    contraction = -np.sum(a.damping / a.mass) * scene.excitation_period
    assert result.per_period.sum() == pytest.approx(contraction, rel=1e-6)


def test_largest_exponent_of_a_stable_orbit_is_the_log_of_its_largest_multiplier():
    """The paper's period-3 orbit at γ1 = 3.5 (Fig. 6): λ_max = ln|μ_max| / 3."""
    scene = three_blade_paper(gamma1=3.5)
    y = settled_state(scene, 300)
    n = len(y) // 2
    multipliers = np.linalg.eigvals(monodromy(scene, 3, initial=(y[:n], y[n:])))
    expected = np.log(np.abs(multipliers).max()) / 3
    result = lyapunov(scene, 300, transient=0, initial=(y[:n], y[n:]))
    assert expected < 0.0
    assert result.largest == pytest.approx(expected, abs=max(3 * result.error[0], 0.01))


def test_the_papers_chaotic_case_has_a_positive_exponent_beyond_its_error():
    result = lyapunov(three_blade_paper(gamma1=8.8), 200, transient=100)
    assert result.is_positive()
    assert result.largest > 0.1


# ---- classification by λ_max ----------------------------------------------------------------

ELEVEN = {  # the paper's chosen points (docs/guide/analysis.md, the paper's claims)
    "γ1 = 1": {"gamma1": 1.0}, "γ1 = 3.5": {"gamma1": 3.5}, "γ1 = 5.31": {"gamma1": 5.31},
    "γ1 = 6": {"gamma1": 6.0}, "γ1 = 8.8": {"gamma1": 8.8}, "5030 rpm": {"speed_rpm": 5030.0},
    "5790 rpm": {"speed_rpm": 5790.0}, "5990 rpm": {"speed_rpm": 5990.0},
    "q1 = 5 N": {"q1": 5.0}, "q1 = 20 N": {"q1": 20.0}, "q1 = 50 N": {"q1": 50.0},
}


@pytest.mark.parametrize("case", ELEVEN)
def test_the_papers_cases_are_classified_alike_from_100_and_500_recorded_periods(case):
    scene = three_blade_paper(**ELEVEN[case])
    short = classify(simulate(scene, 400, samples_per_period=20), "blade2", skip=300)
    long = classify(simulate(scene, 800, samples_per_period=20), "blade2", skip=300)
    assert short.label == long.label != "undetermined", (short, long)
    if long.period is None:
        assert math.isfinite(long.lyapunov) and math.isfinite(short.lyapunov)


def test_a_record_too_short_is_undetermined_with_its_reason():
    sim = simulate(three_blade_paper(), 5)
    kind = classify(sim, "blade2", skip=0)
    assert kind.label == "undetermined"
    assert "10" in kind.reason
    assert classify(sim, "blade2", skip=0, exponent=False).label == "undetermined"
