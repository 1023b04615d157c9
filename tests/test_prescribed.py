"""Prescribed-motion nodes: a belt, a shaker, a measured path.

Checked against references computed here, independently of the loop: the closed form of a
block stuck to a belt (it moves with the belt until k x reaches μ_s N), the complex linear
solve of a blade shaken through a coupling, the energy balance with the motion's work as
input, central differences of the trajectory for the monodromy matrix, and the motions'
own derivatives by differences.
"""

import math

import numpy as np
import pytest

from contact_laws import ConstantLoad, Coulomb, LinearSpring, Stribeck
from shroudnet import (
    Adaptive,
    AntiPhase,
    Blade,
    BladeGroup,
    ConstantVelocity,
    Coupling,
    Excitation,
    FixedStep,
    HarmonicMotion,
    Interface,
    Mode,
    MotionTable,
    Scene,
    assemble,
    linear_modes,
    monodromy,
    periodic_orbit,
    simulate,
)
from shroudnet.engine.assembly import law_forces
from shroudnet.engine.codes import EventKind
from shroudnet.engine.generate import flags
from shroudnet.references.blades import solve_ivp_baseline
from shroudnet.scenes import three_blade_paper
from tests.laws import StaticKinetic
from tests.test_tangent import EXACT, differenced_monodromy, scaled_error, state_scale

NO_EXCITATION = Excitation(engine_order=1, amplitudes=(0.0,), phases=AntiPhase())
BLOCK = Blade(mass=1.0, damping=0.0, stiffness=1e4)
LOAD = 10.0
FRICTION = Stribeck(mu_static=0.4, mu_kinetic=0.25, stribeck_velocity=0.05)
BELT_SPEED = 0.1


def belt(motion=ConstantVelocity(velocity=BELT_SPEED), block=BLOCK, speed_rpm=600.0,
         load=LOAD, friction=FRICTION, far_wall=False):
    """A block on a spring to ground, pressed on a moving belt with velocity-weakening
    friction; no excitation. u = x_block − x_belt, so the slip velocity is ẋ − V.

    With ``far_wall``, also a spring contact to a fixed wall 1 m away, which the block never
    reaches: for a friction law of one's own, the scene then has the law classes and
    effects of ``test_tangent``'s ``beside_a_still_node`` scenes, and shares their kernel."""
    group = BladeGroup().add_blade("block", block).add_prescribed("belt", motion)
    group.connect("block", "belt", Interface(gap=0.0, angle=0.0, normal=ConstantLoad(force=load),
                                             friction=friction))
    if far_wall:
        group.add_fixed("wall").connect("block", "wall", Interface(
            gap=1.0, angle=1.0, normal=LinearSpring(stiffness=1e6)))
    return Scene(group=group, excitation=NO_EXCITATION, speed_rpm=speed_rpm)


# ---- the motions ------------------------------------------------------------------------

MOTIONS = [ConstantVelocity(velocity=-0.3, position=2e-3),
           HarmonicMotion(amplitude=1e-4, frequency=80.0, phase=0.4),
           MotionTable(times=(0.0, 0.01, 0.03, 0.04, 0.07),
                       displacements=(0.0, 1e-4, -2e-4, 0.5e-4, 1e-4))]


@pytest.mark.parametrize("motion", MOTIONS, ids=lambda m: type(m).__name__)
def test_each_motion_is_the_derivative_of_the_one_before(motion):
    t = np.linspace(0.005, 0.06, 12) + 1e-3  # off the table's knots, where ẍ has kinks
    h = 1e-6
    for value, rate in ((motion.displacement_at, motion.velocity_at),
                        (motion.velocity_at, motion.acceleration_at)):
        difference = (value(t + h) - value(t - h)) / (2 * h)
        assert np.allclose(difference, rate(t), rtol=1e-6, atol=1e-9 * np.abs(rate(t)).max()
                           + 1e-12)


def test_a_table_passes_through_its_points_and_its_acceleration_is_linear_between_them():
    table = MOTIONS[2]
    assert np.allclose(table.displacement_at(np.array(table.times)), table.displacements,
                       atol=1e-18)
    terms = table.terms()
    middle = 0.5 * (terms.knot_times[1] + terms.knot_times[2])
    assert table.acceleration_at(middle) == pytest.approx(
        0.5 * (terms.knot_accelerations[1] + terms.knot_accelerations[2]), rel=1e-12)


@pytest.mark.parametrize("times, displacements, message", [
    ((0.0, 0.1, 0.1), (0.0, 1.0, 2.0), r"times must increase strictly: times\[2\]"),
    ((0.0, 0.1), (0.0,), "one value per time"),
    ((0.0,), (0.0,), "at least 2 points"),
    ((0.0, math.nan), (0.0, 1.0), r"times\[1\] must be finite"),
    ((0.0, 1.0), (0.0, math.inf), r"displacements\[1\] must be finite"),
])
def test_a_bad_table_is_refused_naming_what_is_wrong(times, displacements, message):
    with pytest.raises(ValueError, match=message):
        MotionTable(times=times, displacements=displacements)


def test_bad_motions_and_nodes_are_refused():
    with pytest.raises(ValueError, match="HarmonicMotion.frequency"):
        HarmonicMotion(amplitude=1e-3, frequency=0.0)
    with pytest.raises(ValueError, match="HarmonicMotion.amplitude"):
        HarmonicMotion(amplitude=-1.0, frequency=10.0)
    with pytest.raises(TypeError, match="add_prescribed"):
        BladeGroup().add_prescribed("belt", 0.1)
    group = BladeGroup().add_fixed("wall").add_prescribed("belt", ConstantVelocity(velocity=1.0))
    with pytest.raises(ValueError, match="neither node is a blade"):
        group.connect("wall", "belt", Coupling(stiffness=1.0))
    assert group.fixed == ["wall"] and [name for name, _ in group.prescribed] == ["belt"]
    with pytest.raises(ValueError, match="is prescribed, not a blade"):
        group.blade("belt")


def test_kernels_carry_prescribed_motion_code_only_for_scenes_with_such_nodes():
    assert flags(belt().arrays)["HAS_PRESCRIBED"]
    assert not flags(three_blade_paper().arrays)["HAS_PRESCRIBED"]


def test_a_run_that_would_leave_its_table_is_refused_before_any_work():
    scene = belt(MotionTable(times=(0.0, 0.5), displacements=(0.0, 0.05)))
    with pytest.raises(ValueError, match="'belt': its MotionTable covers t = 0 … 0.5 s, but "
                                         "the run spans 0 … 1 s"):
        simulate(scene, 10)


def test_a_blade_held_only_by_a_prescribed_node_is_held():
    group = BladeGroup().add_blade("tip", Blade(mass=0.1, damping=0.0, stiffness=0.0))
    group.add_prescribed("shaker", HarmonicMotion(amplitude=1e-4, frequency=50.0))
    group.connect("tip", "shaker", Coupling(stiffness=4e4))
    scene = Scene(group=group, excitation=NO_EXCITATION, speed_rpm=3000.0)
    # about its path the shaker holds the tip as a fixed node would: ω² = k_c/m
    assert linear_modes(scene).frequencies[0] == pytest.approx(
        math.sqrt(4e4 / 0.1) / (2 * math.pi), rel=1e-12)


# ---- a block on a belt: the stick–slip limit cycle ------------------------------------------

def test_a_block_stuck_to_the_belt_moves_with_it_until_the_spring_reaches_the_static_limit():
    """From x = 0 at the belt's speed the block sticks, x = V t, until k x = μ_s N: the
    first breakaway is at t = μ_s N / (k V)."""
    scene = belt()
    run = simulate(scene, 6, method=Adaptive(rtol=1e-10), samples_per_period=200,
                   initial=([0.0], [BELT_SPEED]))
    first = run.events.time[run.events.kind == EventKind.BREAKAWAY][0]
    assert first == pytest.approx(FRICTION.mu_static * LOAD / (1e4 * BELT_SPEED), abs=1e-11)
    stuck = run.modes[:, 0] == Mode.STICK
    assert stuck.sum() > 20
    assert np.all(run.v[stuck, 0] == BELT_SPEED)  # exactly: the cluster moves with the belt
    assert np.all(run.x[stuck, 0] <= FRICTION.mu_static * LOAD / 1e4 * (1 + 1e-9))


def test_the_block_settles_on_a_stick_slip_limit_cycle_and_its_energy_balances():
    """No force excites the block: the belt's work feeds the friction loss. The cycle's
    breakaways all happen at k x = μ_s N, so their spacing settles to the cycle's period."""
    run = simulate(belt(), 40, method=Adaptive(rtol=1e-10), samples_per_period=50)
    kinds = run.events.kind
    breakaways = run.events.time[kinds == EventKind.BREAKAWAY]
    assert len(breakaways) > 20 and run.events.counts["sticking"] >= len(breakaways) - 1
    spacing = np.diff(breakaways)
    assert np.abs(spacing[-5:] - spacing[-1]).max() < 1e-9 * spacing[-1]
    ledger = run.energy
    assert ledger.excitation_work > 0.1 and ledger.friction_loss > 0.9 * ledger.excitation_work
    # measured 4e-11 of the work
    assert abs(ledger.residual) < 1e-8 * ledger.excitation_work


def test_a_table_of_a_straight_line_is_the_belt_itself():
    straight = MotionTable(times=(0.0, 1.0, 2.0), displacements=(0.0, BELT_SPEED,
                                                                 2 * BELT_SPEED))
    runs = [simulate(belt(motion), 10, method=Adaptive(rtol=1e-10), samples_per_period=20)
            for motion in (ConstantVelocity(velocity=BELT_SPEED), straight)]
    assert runs[0].events.counts == runs[1].events.counts
    assert np.abs(runs[0].x - runs[1].x).max() < 1e-12


def test_fixed_steps_stick_to_the_belt_as_the_adaptive_ones_do():
    run = simulate(belt(), 4, method=FixedStep(steps_per_period=2000), samples_per_period=100,
                   initial=([0.0], [BELT_SPEED]))
    first = run.events.time[run.events.kind == EventKind.BREAKAWAY][0]
    assert first == pytest.approx(FRICTION.mu_static * LOAD / (1e4 * BELT_SPEED), abs=1e-9)
    stuck = run.modes[:, 0] == Mode.STICK
    assert np.all(run.v[stuck, 0] == BELT_SPEED)


def test_assembly_of_a_stuck_block_moves_it_with_a_shaking_belt():
    shaker = HarmonicMotion(amplitude=1e-4, frequency=20.0, phase=0.3)
    scene = belt(shaker)
    t = 0.01
    x = np.array([2e-5])
    v = np.array([float(shaker.velocity_at(t))])
    done = assemble(scene, t, x, v, [Mode.STICK])
    a_p = float(shaker.acceleration_at(t))
    assert done.acceleration[0] == a_p
    # m a = −k x − F with F the static friction (α = 0): F = −k x − m a
    assert done.friction_force[0] == pytest.approx(-1e4 * x[0] - 1.0 * a_p, rel=1e-12)


@pytest.mark.parametrize("case", ["belt", "shaker and a coupled base"])
def test_stick_slip_on_a_moving_node_follows_the_plain_solve_ivp_implementation(case):
    """The plain implementation evaluates each motion where the loop integrates it as a
    state: the two agree through every stick, breakaway and stick again."""
    if case == "belt":  # just below the belt's speed: both slip, then stick at once
        scene, periods, start = belt(), 10, ([0.0], [0.999 * BELT_SPEED])
    else:
        group = BladeGroup().add_blade("blade", Blade(mass=0.1, damping=2.0, stiffness=1e5))
        group.add_prescribed("shaker", HarmonicMotion(amplitude=1e-4, frequency=100.0,
                                                      phase=0.3))
        group.connect("blade", "shaker", Interface(gap=0.0, angle=0.0,
                                                   normal=ConstantLoad(force=12.0),
                                                   friction=FRICTION))
        group.add_prescribed("base", HarmonicMotion(amplitude=5e-5, frequency=100.0,
                                                    phase=1.0))
        group.connect("blade", "base", Coupling(stiffness=2e4, damping=0.5))
        scene = Scene(group=group, excitation=NO_EXCITATION, speed_rpm=6000.0)
        periods, start = 6, None
    compiled = simulate(scene, periods, method=Adaptive(rtol=1e-10, atol=1e-14),
                        samples_per_period=1, event_tolerance=1e-12, initial=start)
    counts = compiled.events.counts
    assert counts["sticking"] > 0 and counts["breakaway"] > 0, counts
    plain = solve_ivp_baseline(scene, periods, rtol=1e-10, atol=1e-14, initial=start)
    assert plain.switches == sum(counts.values())
    # the scales: the largest sampled |x|, and the largest speed of a sample or a motion
    speeds = [np.abs(motion.velocity_at(np.linspace(0.0, 0.01, 101))).max()
              for _, motion in scene.group.prescribed]
    assert np.abs(plain.x - compiled.x).max() < 1e-7 * np.abs(compiled.x).max()
    assert np.abs(plain.v - compiled.v).max() < 1e-7 * max(np.abs(compiled.v).max(), *speeds)


# ---- a blade shaken through a coupling: the linear closed form --------------------------------

def shaken_blade(amplitude=1e-4, frequency=100.0):
    """A blade on its ground spring, joined to a shaker by a spring and damper; the scene's
    period is the shaker's."""
    group = BladeGroup().add_blade("blade", Blade(mass=0.1, damping=2.0, stiffness=1e5))
    group.add_prescribed("shaker", HarmonicMotion(amplitude=amplitude, frequency=frequency))
    group.connect("blade", "shaker", Coupling(stiffness=2e4, damping=1.0))
    return Scene(group=group, excitation=NO_EXCITATION, speed_rpm=60.0 * frequency)


def test_a_blade_shaken_through_a_coupling_follows_the_linear_solve():
    """x_p = Im(A e^{iωt}) gives x = Im(X e^{iωt}), X = (k_c + iω c_c) A /
    (k + k_c − ω² m + iω (c + c_c)); started on it, the run stays on it."""
    scene = shaken_blade()
    w = 2 * math.pi * 100.0
    X = (2e4 + 1j * w * 1.0) * 1e-4 / (1e5 + 2e4 - w * w * 0.1 + 1j * w * 3.0)
    run = simulate(scene, 5, method=Adaptive(rtol=1e-11), samples_per_period=40,
                   initial=([X.imag], [w * X.real]))
    expected = (X * np.exp(1j * w * run.t)).imag
    assert np.abs(run.x[:, 0] - expected).max() < 1e-8 * abs(X)
    ledger = run.energy
    # the shaker's work per period is what the two dampers dissipate, π ω (c|X|² + c_c|X − A|²)
    assert ledger.excitation_work == pytest.approx(
        5 * math.pi * w * (2.0 * abs(X) ** 2 + 1.0 * abs(X - 1e-4) ** 2), rel=1e-7)
    assert abs(ledger.residual) < 1e-9 * ledger.excitation_work


# ---- the monodromy matrix of a blade shaken through friction ----------------------------------

def test_monodromy_through_stick_and_breakaway_on_a_shaker_agrees_with_differences():
    """A blade pressed on a harmonic shaker sticks to it, breaks away and sticks again
    every period. Sticking projects its velocity onto the shaker's, and the saltation
    carries the shaker's acceleration in P f⁻. Measured 6e-10."""
    scene = belt(HarmonicMotion(amplitude=1e-4, frequency=100.0),
                 block=Blade(mass=0.1, damping=2.0, stiffness=1e5), speed_rpm=6000.0,
                 load=12.0)
    assert_monodromy_agrees_with_differences(scene)


@pytest.mark.slow  # compiles a kernel for its law (shared with test_tangent's cases)
def test_monodromy_of_friction_that_drops_at_breakaway_on_a_shaker_agrees_with_differences():
    """With μ(0) = μ_s and μ(0⁺) = μ_k < μ_s, the friction drops by (μ_s − μ_k) N as the
    blade breaks away from the shaker: the breakaway saltation gets a jump term,
    (f⁺ − P f⁻) nᵀ / (nᵀ f⁻ + ∂g/∂t), where f⁺ is the slip side's field, μ(0⁺) at zero
    slip, and ∂g/∂t carries the shaker's jerk (the stuck blade's ∂ẍ/∂t). Measured 3e-8;
    f⁺ taken with μ(0) gives 2.2, the jerk left out 0.93. The acceleration's jump makes
    the differences feel where each switch is located, so their runs locate to 1e-13 s
    (at the default 1e-10 s they agree to 2e-5 only)."""
    scene = belt(HarmonicMotion(amplitude=1e-4, frequency=100.0),
                 block=Blade(mass=0.1, damping=2.0, stiffness=1e5), speed_rpm=6000.0,
                 load=12.0, friction=StaticKinetic(mu_static=0.4, mu_kinetic=0.3),
                 far_wall=True)
    assert_monodromy_agrees_with_differences(scene, event_tolerance=1e-13)


@pytest.mark.parametrize(("mode", "sign"), [(Mode.SLIP_POSITIVE, 1.0),
                                          (Mode.SLIP_NEGATIVE, -1.0)])
def test_an_interface_slipping_at_zero_speed_has_the_friction_of_its_slip_side(mode, sign):
    """Just broken away, the slip speed is exactly 0: the slip mode takes μ(0⁺) = μ_k, not
    the stuck side's μ(0) = μ_s (eqs. 5–6); stuck, no sliding friction."""
    scene = belt(friction=StaticKinetic(mu_static=0.4, mu_kinetic=0.3))
    zero = np.zeros(1)
    _, friction = law_forces(scene.arrays, zero, zero, zero, np.array([mode]))
    assert friction[0] == sign * 0.3 * LOAD
    _, friction = law_forces(scene.arrays, zero, zero, zero, np.array([Mode.STICK]))
    assert friction[0] == 0.0


def assert_monodromy_agrees_with_differences(scene, event_tolerance=1e-10):
    """The monodromy of one period from the state 20 periods in agrees with differences to
    1e-6, over a period that sticks and breaks away."""
    transient = simulate(scene, 20, samples_per_period=1, event_capacity=0)
    y = np.concatenate([transient.x[-1], transient.v[-1]])
    counts = simulate(scene, 1, method=EXACT, samples_per_period=1,
                      initial=np.split(y, 2)).events.counts
    assert counts["sticking"] > 0 and counts["breakaway"] > 0, counts
    scale = state_scale(y)
    scale[scale == 0.0] = 1.0
    matrix = monodromy(scene, 1, initial=np.split(y, 2), method=EXACT)
    assert matrix.shape == (2, 2)
    reference = differenced_monodromy(scene, 1, y, scale, event_tolerance)
    assert scaled_error(matrix, reference, scale) <= 1e-6


def test_the_periodic_orbit_on_a_shaker_is_where_a_long_transient_settles():
    """Its stick phase gives a zero Floquet multiplier; the transient ends on the orbit's
    start to 2e-15 m and 8e-13 m/s (measured)."""
    scene = belt(HarmonicMotion(amplitude=1e-4, frequency=100.0),
                 block=Blade(mass=0.1, damping=2.0, stiffness=1e5), speed_rpm=6000.0,
                 load=12.0)
    orbit = periodic_orbit(scene, transient=20)
    assert orbit.stable and abs(orbit.multipliers[-1]) < 1e-12
    run = simulate(scene, 600, method=Adaptive(rtol=1e-11), samples_per_period=1,
                   event_capacity=0)
    assert abs(run.x[-1, 0] - orbit.initial[0][0]) < 1e-9 * orbit.peak[0]
    assert abs(run.v[-1, 0] - orbit.initial[1][0]) < 1e-9 * orbit.peak[0] * 2 * math.pi * 100


# ---- a stick that would tie two motions together ---------------------------------------------

def test_a_blade_held_by_a_wall_slips_on_a_shaker_instead_of_tying_them():
    """The blade is stuck to a fixed wall; each time the shaker's velocity passes zero its
    slip velocity does too, but sticking to it would tie the shaker to the wall: it slips
    the other way (a reversal) and the wall keeps holding."""
    group = BladeGroup().add_blade("blade", Blade(mass=0.1, damping=2.0, stiffness=1e5))
    group.add_fixed("wall").add_prescribed("shaker", HarmonicMotion(amplitude=1e-4,
                                                                    frequency=100.0))
    group.connect("blade", "wall", Interface(gap=0.0, angle=0.0,
                                             normal=ConstantLoad(force=100.0),
                                             friction=Coulomb(mu=0.5)))
    group.connect("blade", "shaker", Interface(gap=0.0, angle=0.0,
                                               normal=ConstantLoad(force=1.0),
                                               friction=Coulomb(mu=0.2)))
    scene = Scene(group=group, excitation=NO_EXCITATION, speed_rpm=6000.0)
    run = simulate(scene, 4, samples_per_period=50)
    assert np.all(run.modes[:, 0] == Mode.STICK)
    assert np.all(run.x[:, 0] == 0.0) and np.all(run.v[:, 0] == 0.0)
    assert np.all(run.modes[:, 1] != Mode.STICK)
    assert run.events.counts["reversal"] >= 7
