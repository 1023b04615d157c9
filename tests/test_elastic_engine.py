"""Elastic contacts in the time-domain loop: the Jenkins element's sliders in the state,
against ``shroudnet.references.jenkins`` (plain solve_ivp on the element's equations, no
code shared with the engine), its energy ledger, and its limits: rigid stick as k_t grows,
and what the loop refuses."""

import math
from collections import Counter

import numpy as np
import pytest

import shroudnet as sn
from contact_laws import ConstantLoad, Coulomb, ExponentialFriction, LinearSpring
from shroudnet.model.substructure import Substructure
from shroudnet.references.jenkins import JenkinsOscillator, run_oscillator

STIFFNESS = np.array([[100.0, 20.0, 5.0], [20.0, 150.0, 10.0], [5.0, 10.0, 80.0]])
#: The oscillator's excitation [rad/s], and the speed that gives it at engine order 1.
OMEGA = 7.0
SPEED = OMEGA * 60.0 / (2.0 * math.pi)
PERIODS = 3
K_N, K_T, MU, GAP = 1000.0, 500.0, 0.4, -0.01


def oscillator(dimension, load, static=0.0):
    """A 1 kg mass on springs K, pressed 1 cm into a rigid ground (k_n = 1 kN/m), with a
    Jenkins element (k_t = 500 N/m, μ = 0.4) in the ground's plane, forced by
    22 N sin(7 t) along ``load``: it closes, sticks, slips and separates every cycle."""
    keep = [0, 2] if dimension == 1 else [0, 1, 2]
    stiffness = STIFFNESS[np.ix_(keep, keep)]
    damping = 0.5 * np.eye(dimension + 1) + 1e-3 * stiffness
    direction = np.asarray(load, dtype=float)[keep]
    reference = JenkinsOscillator(
        mass=1.0, stiffness=stiffness, normal_stiffness=K_N, tangential_stiffness=K_T, mu=MU,
        force_static=static * direction, force_cos=0.0 * direction, force_sin=22.0 * direction,
        frequency=OMEGA, gap=GAP, damping=damping)
    n = dimension + 1
    body = Substructure(np.eye(n), stiffness, damping, points={"tip": np.eye(n)},
                        load=direction)
    group = sn.BladeGroup().add_blade("mass", body).add_fixed("ground")
    frame = np.eye(n)
    group.connect(("mass", "tip"), "ground", sn.Interface(
        gap=GAP, normal=LinearSpring(stiffness=K_N), friction=Coulomb(mu=MU),
        normal_direction=tuple(frame[-1]), tangent_directions=tuple(map(tuple, frame[:-1])),
        tangential_stiffness=K_T))
    scene = sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=1, amplitudes=(static, 22.0), phases=sn.AntiPhase()), speed_rpm=SPEED)
    return scene, reference


CASES = {"1-D": (1, (0.3, 0.2, 1.0)), "2-D": (2, (0.3, 0.2, 1.0)),
         "2-D, closing into slip": (2, (1.5, -1.0, 1.0))}


@pytest.fixture(scope="module", params=list(CASES), ids=list(CASES))
def runs(request):
    dimension, load = CASES[request.param]
    scene, reference = oscillator(dimension, load)
    sim = sn.simulate(scene, PERIODS, samples_per_period=100, method=sn.Adaptive(rtol=1e-10))
    period = 2.0 * math.pi / OMEGA
    ref = run_oscillator(reference, np.zeros(dimension + 1), np.zeros(dimension + 1),
                         PERIODS * period, t_eval=np.minimum(sim.t, PERIODS * period),
                         rtol=1e-12, atol=1e-14)
    return scene, sim, ref


def test_the_loop_moves_as_the_independent_jenkins_reference(runs):
    scene, sim, ref = runs
    x = sim.x @ scene.point_rows("mass", "tip").T
    # Measured: 5e-10 (1-D, 2-D) and 1.8e-9 (closing into slip) of the largest motion.
    assert np.abs(x - ref.x).max() <= 1e-8 * np.abs(ref.x).max()
    # The sampled friction force, along the first tangent: 1e-8 of its largest.
    assert np.abs(sim.friction_force[:, 0] - ref.forces[:, 0]).max() \
        <= 1e-7 * np.abs(ref.forces).max()
    # Every switch the reference makes, at the same instants (the loop, closing onto a
    # limit that its friction outruns at once, sticks and breaks away in one instant).
    kinds = Counter(ref.switch_kinds)
    assert {k: sim.events.counts[k] for k in ("closing", "separation", "sticking")} == {
        k: kinds[k] for k in ("closing", "separation", "sticking")}
    modes = [segment[2] for segment in ref.segments]
    into_slip = Counter(zip(modes[:-1], modes[1:]))[("open", "slip")]
    assert sim.events.counts["breakaway"] == kinds["breakaway"] + into_slip
    assert kinds["breakaway"] >= 4 and kinds["closing"] >= 4
    times = np.asarray(sim.events.time)
    period = 2.0 * math.pi / OMEGA
    for t in ref.switch_times:
        assert np.abs(times - t).min() <= 1e-7 * period


def test_a_driven_1d_element_dissipates_the_closed_form_of_jenkins_loop():
    """A Jenkins element (k_t = 10 kN/m, μ = 0.3) under a constant 10 N load, driven by
    u₀ sin ωt (u₀ = 1 mm, 50 Hz) against an anvil that does not give (1e12 N/m): it
    slips once u moves 2a = 2μN/k_t past a reversal, so a steady cycle dissipates
    4μN(u₀ − a), and the five periods from rest, slip lengths u₀ − a, nine of 2(u₀ − a)
    and u₀ − 2a, μN(20u₀ − 21a)."""
    load, mu, k_t, u0, frequency = 10.0, 0.3, 1e4, 1e-3, 50.0
    group = sn.BladeGroup().add_blade("anvil", sn.Blade(mass=1e6, damping=1e6,
                                                       stiffness=1e12))
    group.add_prescribed("driver", sn.HarmonicMotion(amplitude=u0, frequency=frequency))
    group.connect("driver", "anvil", sn.Interface(
        gap=0.0, angle=0.0, normal=ConstantLoad(force=load), friction=Coulomb(mu=mu),
        tangential_stiffness=k_t))
    scene = sn.Scene(group=group, excitation=sn.scenes.NO_EXCITATION,
                     speed_rpm=60.0 * frequency)
    sim = sn.simulate(scene, 5, samples_per_period=400, method=sn.Adaptive(rtol=1e-10))
    limit = mu * load
    a = limit / k_t
    assert sim.events.counts["breakaway"] == 11 and sim.events.counts["sticking"] == 10
    # Measured: 1.2e-8 (the anvil gives 3e-12 m); the loop's area 3.9e-5 (its samples).
    assert sim.energy.friction_loss == pytest.approx(limit * (20 * u0 - 21 * a), rel=1e-7)
    assert sn.hysteresis_loop(sim, 0, 1).area_per_cycle() == pytest.approx(
        4 * limit * (u0 - a), rel=1e-4)


def test_the_ledger_books_the_sliders_loss_and_the_springs_energy(runs):
    scene, sim, ref = runs
    excitation, damping, friction = ref.ledger[-1]
    ledger = sim.energy
    # Measured: each to 1e-9 of the excitation's work; the residual 1e-9 of it.
    assert ledger.excitation_work == pytest.approx(excitation, rel=1e-7)
    assert ledger.damping_loss == pytest.approx(damping, rel=1e-7)
    assert ledger.friction_loss == pytest.approx(friction, rel=1e-7)
    assert friction > 0.01 * excitation
    assert abs(ledger.residual) <= 1e-8 * excitation
    assert ledger.stored_change == pytest.approx(
        float(ref.stored[-1] - ref.stored_start), rel=1e-6)


def test_the_ledger_stores_the_stuck_springs_energy_where_a_run_ends_closed():
    """Pressed onto the ground by a static 60 N, the mass stays down after its first
    bounce: the run ends with its spring stretched, so the stored energy holds
    ½ k_t |r_t − w|² ≠ 0."""
    scene, reference = oscillator(1, (0.3, 0.2, 1.0), static=60.0)
    sim = sn.simulate(scene, 2, samples_per_period=10, method=sn.Adaptive(rtol=1e-10))
    period = 2.0 * math.pi / OMEGA
    ref = run_oscillator(reference, np.zeros(2), np.zeros(2), 2 * period, rtol=1e-12,
                         atol=1e-14, t_eval=np.minimum(sim.t, 2 * period))
    assert sim.modes[-1, 0] != sn.Mode.OPEN and ref.modes[-1] != "open"
    spring = 0.5 * K_T * float(np.sum((ref.x[-1, :1] - ref.slider[-1]) ** 2))
    assert spring > 1e-3 * abs(ref.stored[-1] - ref.stored_start)
    assert sim.energy.stored_change == pytest.approx(
        float(ref.stored[-1] - ref.stored_start), rel=1e-7)
    assert abs(sim.energy.residual) <= 1e-8 * abs(sim.energy.excitation_work)


def shroud_contact(speed_rpm):
    """A shroud-like contact: a 1 kg point on springs of 400, 250 and 400 kN/m, pressed
    30 µm into the ground (k_n = 300 kN/m) with a stiff Jenkins element (k_t = 1.2 MN/m,
    μ = 0.3), forced by 20 N sin(Ω t) along (0.1, 0.8, 0.6): its contact closes straight
    into slip in the tangent plane, whose direction turns as it slips."""
    stiffness = np.diag([4e5, 2.5e5, 4e5])
    load = np.array([0.1, 0.8, 0.6])
    omega = speed_rpm * math.pi / 30.0
    reference = JenkinsOscillator(
        mass=1.0, stiffness=stiffness, normal_stiffness=3e5, tangential_stiffness=1.2e6,
        mu=0.3, force_static=0.0 * load, force_cos=0.0 * load, force_sin=20.0 * load,
        frequency=omega, gap=-3e-5, damping=1e-4 * stiffness)
    body = Substructure(np.eye(3), stiffness, 1e-4 * stiffness, points={"tip": np.eye(3)},
                        load=load)
    group = sn.BladeGroup().add_blade("mass", body).add_fixed("ground")
    group.connect(("mass", "tip"), "ground", sn.Interface(
        gap=-3e-5, normal=LinearSpring(stiffness=3e5), friction=Coulomb(mu=0.3),
        normal_direction=(0.0, 0.0, 1.0), tangent_directions=((1.0, 0.0, 0.0),
                                                               (0.0, 1.0, 0.0)),
        tangential_stiffness=1.2e6))
    scene = sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=1, amplitudes=(0.0, 20.0), phases=sn.AntiPhase()), speed_rpm=speed_rpm)
    return scene, reference, 2.0 * math.pi / omega


def test_a_stiff_contact_closing_straight_into_slip_converges_to_the_reference():
    """The stretch u = r_t − w is the state, not w: a contact that closes into slip starts
    slipping with |f| = μN, not at the size of the integrator's error, so the motion
    converges as rtol shrinks and the steps do not collapse (with w in the state, the
    slider stayed glued to r_t at rtol 1e-8 and the steps collapsed at 1e-10)."""
    scene, reference, period = shroud_contact(12000.0)
    periods = 5
    errors = []
    for rtol in (1e-8, 1e-10):
        sim = sn.simulate(scene, periods, samples_per_period=100,
                          method=sn.Adaptive(rtol=rtol))
        ref = run_oscillator(reference, np.zeros(3), np.zeros(3), periods * period,
                             t_eval=np.minimum(sim.t, periods * period), rtol=1e-12,
                             atol=1e-16)
        x = sim.x @ scene.point_rows("mass", "tip").T
        errors.append(np.abs(x - ref.x).max() / np.abs(ref.x).max())
    modes = [segment[2] for segment in ref.segments]
    assert Counter(zip(modes[:-1], modes[1:]))[("open", "slip")] >= 2
    # Measured: 6.0e-6 at rtol 1e-8, 3.4e-9 at 1e-10; the ledger's residual 2.2e-9.
    assert errors[0] < 1e-4 and errors[1] < 2e-8
    assert abs(sim.energy.residual) <= 1e-8 * sim.energy.excitation_work


def pair(k_t, amplitude=60.0):
    """Two blades pressed together at 0.6 rad, forced apart in phase opposition so that
    the contact slips for part of each cycle; rigid stick where ``k_t`` is None."""
    return sn.scenes.blade_pair(tangential_stiffness=k_t, q1=amplitude)


def test_elastic_stick_between_blades_tends_to_rigid_stick_as_k_t_grows():
    """The same pair with k_t = 1e7, 1e8, 1e9 N/m against rigid stick: the motions
    differ by the vibration of the stuck spring, started as each stick begins with the
    relative velocity the slider leaves, so by v/ω_t ∝ 1/√k_t."""
    def motion(k_t):
        sim = sn.simulate(pair(k_t), 3, samples_per_period=50, method=sn.Adaptive(rtol=1e-10))
        assert sim.events.counts["breakaway"] >= 2 and sim.events.counts["sticking"] >= 2
        return sim.x

    rigid = motion(None)
    scale = np.abs(rigid).max()
    gaps = np.array([np.abs(motion(k) - rigid).max() / scale for k in (1e7, 1e8, 1e9)])
    # Measured: 8.2e-2, 2.4e-2, 7.8e-3: ratios 3.40 and 3.08 against √10 = 3.16.
    assert gaps[-1] < 1e-2
    assert gaps[:-1] / gaps[1:] == pytest.approx(math.sqrt(10.0), rel=0.15)


def fixed_step_errors(dimension, steps):
    """The motion's largest error, relative to its largest value, of the oscillator by
    classical RK4 at each of ``steps`` steps a period, against the reference."""
    scene, reference = oscillator(dimension, (0.3, 0.2, 1.0))
    period = 2.0 * math.pi / OMEGA
    start = np.zeros(dimension + 1)
    errors = []
    for count in steps:
        sim = sn.simulate(scene, PERIODS, samples_per_period=50,
                          method=sn.FixedStep(steps_per_period=count))
        ref = run_oscillator(reference, start, start, PERIODS * period,
                             t_eval=np.minimum(sim.t, PERIODS * period), rtol=1e-12,
                             atol=1e-14)
        x = sim.x @ scene.point_rows("mass", "tip").T
        errors.append(np.abs(x - ref.x).max() / np.abs(ref.x).max())
        assert abs(sim.energy.residual) <= 1e-3 * sim.energy.excitation_work
    return np.array(errors)


def test_fixed_steps_carry_the_sliders():
    """Classical RK4, the stretches staged as first-order coordinates beside the
    structure's. In one direction the error falls as h⁴. In two, a slip that starts or
    ends at |f| = 0 (closing straight into slip, opening from slip) turns its direction
    at the rate k_t|ṙ_⊥|/|f|, singular there, which fixed steps cannot follow: the error
    falls at about second order, and the adaptive method is the one to use."""
    errors = fixed_step_errors(1, (400, 800, 1600))
    # Measured: 5.6e-7, 3.6e-8, 2.2e-9: orders 3.98 and 3.99.
    assert errors[-1] < 1e-8
    assert np.log2(errors[:-1] / errors[1:]).min() > 3.7
    errors = fixed_step_errors(2, (400, 800, 1600))
    # Measured: 1.2e-5, 2.9e-6, 5.3e-7: orders 2.0 and 2.5.
    assert errors[-1] < 2e-6
    assert np.log2(errors[:-1] / errors[1:]).min() > 1.7


def test_what_the_loop_does_not_take_with_elastic_contacts_is_refused_by_name():
    group = sn.BladeGroup().add_blade("a", sn.Blade(mass=0.1, damping=2.0, stiffness=1e5))
    group.add_fixed("g").connect("a", "g", sn.Interface(
        gap=-1e-4, angle=0.6, normal=LinearSpring(stiffness=3e5),
        friction=ExponentialFriction(mu_static=0.3, mu_kinetic=0.2, beta=1.0),
        tangential_stiffness=1e6))
    speeds = sn.Scene(group=group, excitation=pair(None).excitation, speed_rpm=6000.0)
    with pytest.raises(ValueError, match=r"interface 0 \('a', 'g'\).*Coulomb"):
        sn.simulate(speeds, 1)


def test_the_packet_with_3d_elastic_contacts_sticks_slips_and_separates_its_ledger_closed():
    """``scenes.modal_packet(tangential_stiffness=)``: six three-mode blades whose shroud
    points move in three directions, each face's stick a Jenkins element in its plane."""
    scene = sn.scenes.modal_packet(tangential_stiffness=3e5, speed_rpm=2900.0)
    interface = scene.group.interfaces[0][2]
    assert interface.elastic and len(interface.tangent_directions) == 2
    assert scene.group.blade("blade1").points["shroud"].shape == (3, 3)
    sim = sn.simulate(scene, 10, method=sn.Adaptive(rtol=1e-10), samples_per_period=20)
    counts = sim.events.counts
    assert min(counts["closing"], counts["separation"], counts["sticking"],
               counts["breakaway"]) > 0
    ledger = sim.energy
    # Measured: the residual 1.4e-11 of the excitation's work, friction 49 % of it.
    assert ledger.friction_loss > 0.1 * ledger.excitation_work
    assert abs(ledger.residual) <= 1e-9 * ledger.excitation_work


def test_the_loops_in_both_directions_of_a_face_add_up_to_the_sliders_loss():
    """Over steady cycles ∮ f·dr_t = ∮ f·dw: the spring's ½k_t|u|² comes back to itself, so
    the areas of the hysteresis loops along t₁ and t₂ of every face add up to the friction
    loss the ledger books, to the samples' trapezoidal error."""
    scene = sn.scenes.modal_packet(tangential_stiffness=3e5, speed_rpm=2900.0)
    gaps = []
    for samples in (100, 400):
        sim = sn.simulate(scene, 30, method=sn.Adaptive(rtol=1e-10),
                          samples_per_period=samples)
        loops = [sn.hysteresis_loop(sim, e, 20, direction) for e in range(5)
                 for direction in (1, 2)]
        loss = (sim.work[-1, 2] - sim.work[20 * samples, 2]) / 10
        gaps.append(abs(sum(loop.area_per_cycle() for loop in loops) - loss) / loss)
        assert loops[1].area_per_cycle() > 0.01 * loops[0].area_per_cycle()
    # Measured: 2.2e-3 and 1.3e-4 of the loss: second order in the samples' spacing.
    assert gaps[1] <= 5e-4 and gaps[0] / gaps[1] > 8.0
    assert np.array_equal(sim.friction_along(0, 2), sim.friction_force_second[:, 0])


def test_a_loop_along_a_second_direction_needs_a_face_that_has_one():
    sim = sn.simulate(sn.scenes.modal_packet(), 3)
    with pytest.raises(ValueError, match=r"hysteresis_loop.direction = 2: interface 0 "
                                         r"\('blade1', 'blade2'\) slides along one "
                                         r"direction"):
        sn.hysteresis_loop(sim, 0, 1, 2)
    assert sim.friction_force_second is None
    assert not sim.friction_along(0, 2).any()
