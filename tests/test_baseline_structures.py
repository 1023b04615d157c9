"""The event-driven reference for structures of many degrees of freedom
(``shroudnet.references.structures``) against what it does not compute itself: the closed-form
harmonic response of a linear system, the one-mass-blade reference ``shroudnet.references.blades``,
the closed-form decay of a Coulomb-damped oscillator, and the energy balance, the contact
spring's energy and the projection's properties for a point in the plane whose normal and
tangent rows are neither parallel nor orthogonal."""

import dataclasses
import math

import numpy as np
import pytest

from contact_laws import ConstantLoad, Coulomb, ExponentialFriction, LinearSpring, Regularised
from shroudnet import (
    AntiPhase,
    Blade,
    BladeGroup,
    Excitation,
    ExplicitPhases,
    Interface,
    Mode,
    Scene,
)
from shroudnet.references.blades import solve_ivp_baseline
from shroudnet.references.structures import (
    WORK_COLUMNS,
    Contact,
    StructureProblem,
    contact_forces,
    project_velocity,
    run_structure,
    shroud_contact,
    strobe_structure,
    structure_from_scene,
)
from shroudnet.scenes import three_blade_paper


def steady_state(problem, t):
    """(q, q̇) of the harmonic steady state at times ``t``: K X_0 = F_0 and
    (K − (hω)² M + i hω C) X_h = F_h^c − i F_h^s."""
    t = np.asarray(t, dtype=float)[:, None]
    q = np.linalg.solve(problem.stiffness, problem.force_static)[None, :] + 0.0 * t
    v = np.zeros_like(q)
    for h, (cos, sin) in enumerate(zip(problem.force_cos, problem.force_sin), start=1):
        w = h * problem.frequency
        amplitude = np.linalg.solve(problem.stiffness - w**2 * problem.mass
                                    + 1j * w * problem.damping, cos - 1j * sin)
        phasor = np.exp(1j * w * t)
        q = q + (amplitude[None, :] * phasor).real
        v = v + (1j * w * amplitude[None, :] * phasor).real
    return q, v


def test_a_linear_two_mass_system_settles_on_its_closed_form_harmonic_response():
    mass = np.array([[2.0, 0.3], [0.3, 1.0]])
    stiffness = np.array([[300.0, -100.0], [-100.0, 200.0]])
    # Rayleigh damping 4 M + 0.01 K: every mode decays at least as e^(−2t).
    problem = StructureProblem(
        mass=mass, damping=4.0 * mass + 0.01 * stiffness, stiffness=stiffness,
        force_static=np.array([1.0, -2.0]), force_cos=np.array([[3.0, 0.5], [0.0, 1.5]]),
        force_sin=np.array([[-1.0, 2.0], [0.7, 0.0]]), frequency=10.0,
        # a contact far beyond the motion: its guards are watched and never cross
        contacts=(Contact(normal_row=np.array([1.0, -1.0]), tangent_row=np.array([0.5, 1.0]),
                          gap=1.0, normal_law=LinearSpring(stiffness=1e4),
                          friction_law=Coulomb(mu=0.5)),))
    periods = 25  # 15.7 s: transients below e^(−31)
    last = problem.period * np.linspace(periods - 1, periods, 41)
    run = run_structure(problem, np.zeros(2), np.zeros(2), periods * problem.period,
                        t_eval=last)
    q, v = steady_state(problem, last)
    assert len(run.switch_times) == 0 and list(run.modes_end) == [Mode.OPEN]
    # Measured: 3.8e-11 and 3.9e-11.
    assert np.abs(run.q - q).max() < 1e-8 * np.abs(q).max()
    assert np.abs(run.v - v).max() < 1e-8 * np.abs(v).max()


def stick_chain() -> Scene:
    """Three mistuned blades in a chain and a contact from the last to a fixed node, with
    a mean force, a second harmonic and phases of no pattern: impacts, slip, stick and
    breakaway on all three contacts."""
    blades = [Blade(mass=0.08, damping=4.0, stiffness=1.5e5),
              Blade(mass=0.09, damping=3.0, stiffness=1.4e5, excitation_scale=0.7),
              Blade(mass=0.075, damping=5.0, stiffness=1.6e5)]
    shroud = Interface(gap=1e-5, angle=math.pi / 6, normal=LinearSpring(stiffness=4e5),
                       friction=ExponentialFriction(mu_static=0.9, mu_kinetic=0.6, beta=5.0))
    group = BladeGroup.chain(3, blades, shroud)
    group.add_fixed("disc")
    group.connect("blade3", "disc", Interface(gap=2e-5, angle=math.pi / 5,
                                              normal=LinearSpring(stiffness=3e5),
                                              friction=Coulomb(mu=1.0)))
    excitation = Excitation(engine_order=2, amplitudes=(5.0, 60.0, 15.0),
                            phases=ExplicitPhases((0.0, 2.0, 4.5)))
    return Scene(group=group, excitation=excitation, speed_rpm=6000.0)


@pytest.mark.parametrize("scene", [
    three_blade_paper(gamma1=3.5),                 # impacts, slip, stick and breakaway
    three_blade_paper(gamma1=1.0, friction=None),  # frictionless impacts
    stick_chain(),
], ids=["paper gamma1=3.5", "frictionless", "mistuned chain to ground"])
def test_one_coordinate_rows_reproduce_the_one_mass_blade_baseline(scene):
    periods = 10
    plain = solve_ivp_baseline(scene, periods, rtol=1e-10, atol=1e-14)
    run = strobe_structure(structure_from_scene(scene), np.zeros(3), np.zeros(3), periods,
                           rtol=1e-10, atol=1e-14)
    assert len(run.switch_times) == plain.switches > 10
    # Measured: 1.2e-9, 4.3e-10 and 5.3e-10 (velocities 2.1e-9, 6.4e-10, 3.5e-10).
    assert np.abs(run.q - plain.x).max() < 1e-8 * np.abs(plain.x).max()
    assert np.abs(run.v - plain.v).max() < 1e-8 * np.abs(plain.v).max()


def test_the_scene_conversion_reads_the_excitation_and_the_geometry_as_the_model_says():
    scene = stick_chain()
    problem = structure_from_scene(scene)
    a = scene.arrays
    for t in (0.0, 1.3e-4, 7.7e-3):
        # Q_i = s_i [q0 + Σ_n q_n sin(n (lΩ t + φ_i))], written out term by term
        expected = [s * (5.0 + 60.0 * math.sin(a.excitation_frequency * t + phi)
                         + 15.0 * math.sin(2.0 * (a.excitation_frequency * t + phi)))
                    for s, phi in zip((1.0, 0.7, 1.0), (0.0, 2.0, 4.5))]
        assert np.allclose(problem.force(t), expected, rtol=1e-13, atol=1e-12)
    expected = shroud_contact(3, 2, None, gap=2e-5, angle=math.pi / 5,
                              normal_law=LinearSpring(stiffness=3e5), friction_law=None)
    assert np.allclose(problem.contacts[2].normal_row, expected.normal_row, rtol=1e-15)
    assert np.allclose(problem.contacts[2].tangent_row, expected.tangent_row, rtol=1e-15)
    assert problem.contacts[2].gap == pytest.approx(expected.gap, rel=1e-15)


def test_a_coulomb_damped_oscillator_loses_four_mu_n_over_k_a_cycle_and_sticks():
    """m ẍ + k x = ∓μN while ẋ ≷ 0: each half cycle lasts π/ω₀ about the centre ±μN/k
    (the side friction pushes to), so the amplitude falls by 2μN/k a half cycle, 4μN/k a
    cycle, until a turning point lies within μN/k, where the mass sticks for good."""
    mass, stiffness, mu, load, x0 = 1.0, 100.0, 0.3, 10.0, 0.5
    omega = math.sqrt(stiffness / mass)
    drop = mu * load / stiffness  # 0.03 m
    problem = StructureProblem(
        mass=[[mass]], damping=[[0.0]], stiffness=[[stiffness]], force_static=[0.0],
        force_cos=np.zeros((0, 1)), force_sin=np.zeros((0, 1)), frequency=0.0,
        contacts=(Contact(normal_row=[0.0], tangent_row=[1.0], gap=0.0,
                          normal_law=ConstantLoad(force=load), friction_law=Coulomb(mu=mu)),))
    turning = [x0]  # 0.5, −0.44, 0.38, … 0.02: eight half cycles
    while abs(turning[-1]) > drop:
        turning.append(-math.copysign(abs(turning[-1]) - 2.0 * drop, turning[-1]))
    half = math.pi / omega
    ends = half * np.arange(len(turning) + 1)  # the turning points, then one more half cycle
    times = np.union1d(np.linspace(0.0, ends[-1], 801), ends)
    expected = np.empty_like(times)
    for k, t in enumerate(times):
        j = min(int(t // half), len(turning) - 1)
        if t >= (len(turning) - 1) * half:
            expected[k] = turning[-1]
            continue
        centre = math.copysign(drop, turning[j])
        expected[k] = centre + (turning[j] - centre) * math.cos(omega * (t - j * half))
    run = run_structure(problem, [x0], [0.0], times[-1], t_eval=times)
    assert len(turning) == 9
    # Measured: 2.8e-10 of x0, switch times to 7e-12.
    assert np.abs(run.q[:, 0] - expected).max() < 1e-8 * x0
    assert run.switch_kinds == ("reversal",) * 7 + ("sticking",)
    assert np.allclose(run.switch_times, ends[1:-1], rtol=1e-9, atol=0.0)
    amplitudes = np.abs(run.q[np.searchsorted(times, ends[:-1]), 0])
    assert np.allclose(amplitudes[:-2] - amplitudes[2:], 4.0 * drop, rtol=0.0, atol=1e-8 * x0)
    assert run.q_end[0] == pytest.approx(turning[-1], abs=1e-8 * x0)
    assert list(run.modes_end) == [Mode.STICK]
    # The friction's work is all the energy lost: ½ k (x0² − x_end²).
    assert run.work_end[WORK_COLUMNS.index("friction")] == pytest.approx(
        0.5 * stiffness * (x0**2 - turning[-1] ** 2), rel=1e-9)


#: A point in the plane (d = 2) on coupled springs, with a coupled mass, against a wall:
#: its normal and tangent rows are neither parallel nor orthogonal.
NORMAL_ROW, TANGENT_ROW, GAP, CONTACT_STIFFNESS = (np.array([0.3, 1.0]), np.array([1.0, 0.4]),
                                                   0.005, 2e3)


def point_on_wall(friction):
    mass = np.array([[1.0, 0.2], [0.2, 1.5]])
    stiffness = np.array([[400.0, -100.0], [-100.0, 300.0]])
    return StructureProblem(
        mass=mass, damping=0.01 * stiffness + 0.2 * mass, stiffness=stiffness,
        force_static=np.array([0.0, 5.0]), force_cos=np.array([[10.0, 2.0]]),
        force_sin=np.array([[0.0, 3.0]]), frequency=14.0,
        contacts=(Contact(normal_row=NORMAL_ROW, tangent_row=TANGENT_ROW, gap=GAP,
                          normal_law=LinearSpring(stiffness=CONTACT_STIFFNESS),
                          friction_law=friction),))


def modes_at(run, t):
    """The modes in force just before ``t`` (a sample on a switch is its left limit)."""
    k = np.searchsorted(run.switch_times, t, side="left")
    return run.initial_modes if k == 0 else run.switch_modes[k - 1]


@pytest.mark.parametrize("friction", [
    Coulomb(mu=0.8),
    ExponentialFriction(mu_static=0.9, mu_kinetic=0.5, beta=3.0),
    Regularised(law=Coulomb(mu=0.8), velocity=1e-2),
    None,
], ids=["coulomb", "velocity weakening", "regularised", "frictionless"])
def test_a_point_against_a_slanted_wall_keeps_its_energy_balance(friction):
    problem = point_on_wall(friction)
    end = 10 * problem.period
    run = run_structure(problem, np.zeros(2), np.zeros(2), end,
                        t_eval=np.linspace(0.0, end, 2001))
    work = run.work
    excitation = np.abs(work[:, 0]).max()
    residual = work[:, 0] - work[:, 1:].sum(axis=1) - (run.stored - run.stored[0])
    # Measured: 3e-11 to 5e-11 of the excitation's work; the contact's, 4e-12 to 3e-11.
    assert np.abs(residual).max() < 1e-8 * excitation
    # The contact spring returns what it takes: its work is ½ k_c δ² while closed, 0 open.
    penetration = run.q @ NORMAL_ROW - GAP
    contact = work[:, WORK_COLUMNS.index("contact")]
    assert np.abs(contact - 0.5 * CONTACT_STIFFNESS * np.maximum(penetration, 0.0) ** 2).max() \
        < 1e-8 * excitation
    kinds = set(run.switch_kinds)
    assert {"closing", "separation"} <= kinds
    sticks = friction is not None and friction.regularisation_velocity == 0.0
    assert ({"sticking", "breakaway"} <= kinds) == sticks
    assert "sticking" in kinds or not sticks
    if friction is None:
        assert work[-1, WORK_COLUMNS.index("friction")] == 0.0
    # While stuck the slip velocity stays 0 and the static friction within μ_s N.
    stuck = 0
    for t, q, v in zip(run.times, run.q, run.v):
        modes = modes_at(run, t)
        if modes[0] != Mode.STICK:
            continue
        stuck += 1
        forces = contact_forces(problem, modes, t, q, v)
        assert abs(forces.slip[0]) < 1e-9 * np.abs(run.v).max()
        assert abs(forces.friction[0]) <= friction.static_coefficient * forces.normal[0] \
            * (1.0 + 1e-9)
    assert (stuck > 50) == sticks


@pytest.mark.parametrize("friction", [None, Coulomb(mu=0.8)], ids=["frictionless", "coulomb"])
def test_a_contact_split_into_two_parallel_halves_moves_as_one_at_any_tolerance(friction):
    """Rows n/2 and t/2 with gap Δ/2 beside the wall's own contact add k_c δ/2 along n/2
    and μ k_c δ/2 along t/2: together one contact of stiffness 1.25 k_c. Both halves
    close, open, stick and break away at one instant in exact arithmetic, in rounding a
    hair apart; run at two tolerances they follow the single contact's trajectory (a
    switch taken twice, one half left behind, or a re-closing missed within the first
    step after a switch would show as a jump)."""
    wall = point_on_wall(friction)
    half = Contact(normal_row=NORMAL_ROW / 2, tangent_row=TANGENT_ROW / 2, gap=GAP / 2,
                   normal_law=LinearSpring(stiffness=CONTACT_STIFFNESS), friction_law=friction)
    single = Contact(normal_row=NORMAL_ROW, tangent_row=TANGENT_ROW, gap=GAP,
                     normal_law=LinearSpring(stiffness=1.25 * CONTACT_STIFFNESS),
                     friction_law=friction)
    split = dataclasses.replace(wall, contacts=(wall.contacts[0], half))
    one = dataclasses.replace(wall, contacts=(single,))
    end = 10 * wall.period
    samples = np.linspace(0.0, end, 41)
    reference = run_structure(one, np.zeros(2), np.zeros(2), end, t_eval=samples, rtol=1e-12)
    for problem, rtol in ((one, 1e-10), (split, 1e-10), (split, 1e-12)):
        run = run_structure(problem, np.zeros(2), np.zeros(2), end, t_eval=samples, rtol=rtol)
        # Measured: 1.4e-10 and 2.6e-10 at rtol 1e-10, 1.5e-14 at 1e-12.
        assert np.abs(run.q - reference.q).max() < 1e-8 * np.abs(reference.q).max()
        assert run.switch_kinds == reference.switch_kinds
        if problem is split:
            assert np.all(run.switch_modes[:, 0] == run.switch_modes[:, 1])


def test_stick_onset_keeps_the_momentum_the_constraint_allows_and_loses_the_rest():
    problem = point_on_wall(Coulomb(mu=5.0))
    q0 = np.array([0.0, 0.02])  # δ = 0.015: closed
    v0 = np.array([0.3, -0.1])  # s = 0.26
    run = run_structure(problem, q0, v0, 0.05, t_eval=[0.0, 0.05],
                        modes0=[Mode.STICK])
    after = run.v[0]
    along = np.array([-TANGENT_ROW[1], TANGENT_ROW[0]])  # t·w = 0: a motion stick allows
    mass = problem.mass
    assert abs(TANGENT_ROW @ after) < 1e-15
    assert along @ mass @ after == pytest.approx(along @ mass @ v0, rel=1e-14)
    jump = v0 - after
    # The kinetic energy lost is that of the jump (Pythagoras in the M-norm).
    assert run.work[0, WORK_COLUMNS.index("projection")] == pytest.approx(
        0.5 * jump @ mass @ jump, rel=1e-12)
    assert 0.5 * (v0 @ mass @ v0 - after @ mass @ after) == pytest.approx(
        0.5 * jump @ mass @ jump, rel=1e-12)
    assert run.initial_modes[0] == Mode.STICK


def test_redundant_stuck_rows_project_m_orthogonally_and_take_the_least_norm_friction():
    rng = np.random.default_rng(7)
    root = rng.normal(size=(3, 3))
    mass = root @ root.T + 3.0 * np.eye(3)
    first, second = np.array([1.0, -1.0, 0.0]), np.array([0.0, 1.0, -2.0])
    rows = (first, second, first + second)  # the third row is the sum of the others
    contacts = tuple(Contact(normal_row=np.zeros(3), tangent_row=row, gap=0.0,
                             normal_law=ConstantLoad(force=100.0), friction_law=Coulomb(mu=1.0))
                     for row in rows)
    problem = StructureProblem(mass=mass, damping=np.zeros((3, 3)),
                               stiffness=np.diag([100.0, 200.0, 300.0]),
                               force_static=np.array([1.0, 2.0, -3.0]),
                               force_cos=np.zeros((0, 3)), force_sin=np.zeros((0, 3)),
                               frequency=0.0, contacts=contacts)
    modes = [Mode.STICK] * 3
    velocity = rng.normal(size=3)
    projected = project_velocity(problem, modes, velocity)
    constraint = np.array(rows)
    null = np.cross(first, second)  # the one motion all three rows allow
    assert np.abs(constraint @ projected).max() < 1e-14
    assert null @ mass @ projected == pytest.approx(null @ mass @ velocity, rel=1e-13)
    assert np.allclose(project_velocity(problem, modes, projected), projected, atol=1e-15)
    q = np.array([0.01, -0.02, 0.005])
    forces = contact_forces(problem, modes, 0.0, q, projected)
    # The cluster moves along the null motion only, and λ has no part along (1, 1, −1),
    # the combination of rows that exerts no force.
    acceleration = forces.acceleration
    assert np.abs(constraint @ acceleration).max() < 1e-12 * np.abs(acceleration).max()
    assert abs(forces.friction @ np.array([1.0, 1.0, -1.0])) < 1e-12 * np.abs(forces.friction).max()
    resultant = problem.force(0.0) - problem.stiffness @ q
    assert np.allclose(mass @ acceleration + constraint.T @ forces.friction, resultant,
                       rtol=0.0, atol=1e-12 * np.abs(resultant).max())


def test_strobe_points_of_an_anti_phase_paper_group_fall_on_whole_periods():
    scene = three_blade_paper(gamma1=2.2, phases=AntiPhase())
    problem = structure_from_scene(scene)
    run = strobe_structure(problem, np.zeros(3), np.zeros(3), 3)
    assert np.allclose(run.times, scene.excitation_period * np.arange(4), rtol=1e-15)
    assert run.q.shape == (4, 3) and np.allclose(run.q[0], 0.0)
    assert np.array_equal(run.q_end, run.q[-1])


def test_bad_input_is_refused_with_the_field_named():
    good = point_on_wall(None)
    with pytest.raises(ValueError, match="mass must be positive definite"):
        StructureProblem(mass=[[1.0, 0.0], [0.0, -1.0]], damping=good.damping,
                         stiffness=good.stiffness, force_static=good.force_static,
                         force_cos=good.force_cos, force_sin=good.force_sin, frequency=1.0)
    with pytest.raises(ValueError, match="contacts\\[0\\] has rows of length 3"):
        StructureProblem(mass=good.mass, damping=good.damping, stiffness=good.stiffness,
                         force_static=good.force_static, force_cos=good.force_cos,
                         force_sin=good.force_sin, frequency=1.0,
                         contacts=(Contact(normal_row=np.ones(3), tangent_row=np.ones(3),
                                           gap=0.0, normal_law=LinearSpring(stiffness=1.0)),))
    with pytest.raises(TypeError, match="normal_law"):
        Contact(normal_row=[1.0], tangent_row=[0.0], gap=0.0, normal_law=lambda d, r: d)
    with pytest.raises(ValueError, match="modes0\\[0\\] is OPEN where the contact is closed"):
        run_structure(good, np.array([0.0, 0.02]), np.zeros(2), 0.1, modes0=[Mode.OPEN])
    with pytest.raises(ValueError, match="modes0\\[0\\] is STICK"):
        run_structure(good, np.array([0.0, 0.02]), np.zeros(2), 0.1, modes0=[Mode.STICK])
