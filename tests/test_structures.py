"""Substructures in the engine: nodes of many degrees of freedom, interfaces between their
points, stick as constraints (DESIGN §7).

A scene of one-mass blades, each rebuilt as a ``Substructure`` of one degree of freedom,
runs through the other half of the engine (``records.StructureScene``: modal coordinates,
rows for the interfaces, constraints for stick), which shares none of the clusters' code
with the first: the two must give the same events, trajectories and Floquet multipliers.
"""


import math

import numpy as np
import pytest

import shroudnet as sn
from contact_laws import Coulomb, LinearSpring
from shroudnet import scenes
from shroudnet.model.substructure import Substructure
from shroudnet.references import structures as bs
from tests.laws import StaticKinetic
from tests.test_tangent import (
    EXACT,
    differenced_monodromy,
    scaled_error,
    settled_state,
    settled_through_every_switch,
    state_scale,
)


def as_substructures(scene: sn.Scene) -> sn.Scene:
    """``scene`` with every Blade a one-degree-of-freedom Substructure whose point "x" is
    its displacement: the same physics, in the coordinates η = √m x."""
    old = scene.group
    group = sn.BladeGroup()
    for name, data in old.graph.nodes(data=True):
        body, motion = data["blade"], data.get("motion")
        if body is not None:
            group.add_blade(name, Substructure(
                [[body.mass]], [[body.stiffness_at(scene.speed_rpm)]], [[body.damping]],
                points={"x": [[1.0]]}, load="x", excitation_scale=body.excitation_scale))
        elif motion is not None:
            group.add_prescribed(name, motion)
        else:
            group.add_fixed(name)

    def end(node):
        return (node, "x") if old.graph.nodes[node]["blade"] is not None else node

    for left, right, interface in old.interfaces:
        group.connect(end(left), end(right), interface)
    for left, right, coupling in old.couplings:
        group.connect(end(left), end(right), coupling)
    group.graph.graph.update(old.graph.graph)
    return sn.Scene(group=group, excitation=scene.excitation, speed_rpm=scene.speed_rpm)


def stuck_ring():
    """Four blades in a preloaded ring that stick, break away, reverse and separate."""
    interface = sn.Interface(gap=-1e-5, angle=0.4, normal=LinearSpring(stiffness=3e5),
                             friction=Coulomb(mu=0.6))
    return sn.Scene(group=sn.BladeGroup.ring(
        4, sn.Blade(mass=0.08, damping=4.0, stiffness=1.5e5), interface),
        excitation=sn.Excitation(engine_order=1, amplitudes=(0.0, 30.0),
                                 phases=sn.EngineOrderWave()), speed_rpm=3000.0)


def switches(log, period):
    """(time in periods, interface, kind) of every logged switch, ordered by time to
    1e-6 periods, then interface and kind."""
    order = np.lexsort((log.kind, log.interface, np.round(log.time / period, 6)))
    return log.time[order] / period, log.interface[order], log.kind[order]


#: The two halves round differently (η = √m x; the couplings as a matrix), so their
#: trajectories part by the integrator's error: run both close to exact.
TIGHT = sn.Adaptive(rtol=1e-10)

CASES = {
    "paper group": (scenes.three_blade_paper, 40),
    "stuck ring (redundant constraints)": (stuck_ring, 30),
    "bladed disc (couplings)": (scenes.bladed_disc_24, 4),
    "block on a belt (prescribed motion)": (scenes.block_on_belt, 20),
}


def test_one_dof_substructures_give_the_paper_groups_poincare_points_to_1e12():
    """Both run close to exact (rtol 1e-13, switches to 1e-13 periods), the paper's group
    of blades and of one-coordinate substructures meet at every t = k T_e."""
    scene = scenes.three_blade_paper()
    exact = sn.Adaptive(rtol=1e-13)
    blades, structures = (sn.simulate(one, 40, method=exact, samples_per_period=1,
                                      event_tolerance=1e-13)
                          for one in (scene, as_substructures(scene)))
    assert structures.events.counts == blades.events.counts
    # a one-coordinate substructure's q is the blade's x (the engine's η = √m x)
    # measured 9.2e-13 (x) and 4.7e-13 (ẋ) of their amplitudes over 40 periods
    for ours, theirs in ((structures.x, blades.x), (structures.v, blades.v)):
        assert np.abs(ours - theirs).max() <= 1e-12 * np.abs(theirs).max()


@pytest.mark.parametrize("name", CASES)
def test_one_dof_substructures_reproduce_the_blades(name):
    make, periods = CASES[name]
    scene = make()
    blades, structures = (sn.simulate(one, periods, method=TIGHT)
                          for one in (scene, as_substructures(scene)))
    assert structures.scene.arrays.is_structure and not scene.arrays.is_structure
    assert structures.events.counts == blades.events.counts
    # the same switches, at the same times (where several fall together, as round a
    # symmetric disc, rounding may log them in another order)
    period = scene.excitation_period
    for expected, got in zip(switches(blades.events, period),
                             switches(structures.events, period)):
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-8)
    amplitude = np.abs(blades.x).max()  # a one-coordinate substructure's q is its x
    assert np.abs(structures.x - blades.x).max() <= 1e-8 * amplitude
    assert np.allclose(structures.energy.excitation_work, blades.energy.excitation_work,
                       rtol=1e-8)
    assert abs(structures.energy.residual) <= 1e-6 * abs(structures.energy.excitation_work)


# ---- many degrees of freedom -------------------------------------------------------------

def modal_blade():
    """A blade of three modes (first flap, edgewise, second flap), given as an FE modal
    analysis prints it: frequencies, modal masses, and the shapes at the shroud (two
    components, flapwise and edgewise) and at the load point."""
    shapes = {"shroud": np.array([[1.0, 0.3, -0.6], [0.2, 1.0, 0.4]]),
              "load": np.array([[0.8, 0.5, 0.3]])}
    return Substructure.modal([180.0, 420.0, 900.0], 0.005, [0.05, 0.04, 0.03], shapes,
                              load="load")


def modal_pair(gap=-2e-6, friction=Coulomb(mu=0.5), amplitude=20.0, face=0.6):
    """Two modal blades whose shrouds meet on a face inclined at ``face`` [rad]: a
    preloaded contact that separates, closes, sticks, breaks away and slips every period,
    its normal and slip directions each a different mix of the three modes."""
    normal, tangent = (math.cos(face), math.sin(face)), (-math.sin(face), math.cos(face))
    group = sn.BladeGroup().add_blade("blade1", modal_blade()).add_blade("blade2",
                                                                          modal_blade())
    group.connect(("blade1", "shroud"), ("blade2", "shroud"), sn.Interface(
        gap=gap, normal=LinearSpring(stiffness=2e5), friction=friction,
        normal_direction=normal, tangent_direction=tangent))
    return sn.Scene(group=group, excitation=sn.Excitation(
        engine_order=2, amplitudes=(0.0, amplitude), phases=sn.AntiPhase()), speed_rpm=5000.0)


def test_monodromy_of_a_multi_dof_orbit_with_impacts_stick_and_breakaway_agrees_with_differences():
    scene = modal_pair()
    y = settled_through_every_switch(scene, 30)
    scale = state_scale(y)
    matrix = sn.monodromy(scene, 1, initial=np.split(y, 2), method=EXACT)
    # the differenced runs locate their switches closer than the default 1e-10 periods:
    # the acceleration jumps where the contact closes, so they feel where it is located
    # (2.4e-6 at 1e-10, 2e-9 at 1e-12, 4.5e-10 at 1e-13)
    reference = differenced_monodromy(scene, 1, y, scale, 1e-13)
    assert scaled_error(matrix, reference, scale) <= 1e-6


def test_energy_ledger_of_a_multi_dof_run_closes_and_converges_with_the_tolerance():
    residuals = []
    for rtol in (1e-10, 1e-11):
        ledger = sn.simulate(modal_pair(), 20, method=sn.Adaptive(rtol=rtol)).energy
        assert ledger.friction_loss > 0.1 * ledger.excitation_work  # friction matters here
        residuals.append(abs(ledger.residual) / ledger.excitation_work)
    # measured: 1.3e-9 at rtol 1e-10, 1.3e-10 at 1e-11 (first order in rtol). This pair is
    # lightly damped (ζ 0.003) and open 80 % of the time, its impacts setting the third
    # modes ringing: Dormand–Prince's energy error on them is the residual's whole source
    # (without the contact, 3.6e-11 of a 16 times larger work)
    assert residuals[0] <= 2e-9 and residuals[1] <= 0.2 * residuals[0]


@pytest.mark.parametrize("scene, periods", [(scenes.modal_packet(), 20),
                                            (scenes.beam_pair(), 6)],
                         ids=["modal packet", "unreduced beams"])
def test_energy_ledger_of_the_packet_and_the_beams_closes_to_1e9_at_rtol_1e10(scene, periods):
    sim = sn.simulate(scene, periods, method=sn.Adaptive(rtol=1e-10))
    ledger = sim.energy
    assert all(sim.events.counts[kind] > 0 for kind in ("closing", "separation", "sticking",
                                                        "breakaway"))
    assert ledger.friction_loss > 0.3 * ledger.excitation_work
    # measured: 1.5e-11 (packet), 2.5e-14 (beams)
    assert abs(ledger.residual) <= 1e-9 * ledger.excitation_work


def test_two_unreduced_beams_with_a_shroud_contact_match_an_independent_reference():
    scene = scenes.beam_pair()
    orbit = sn.periodic_orbit(scene, history=True)
    counts = orbit.history.events.counts
    assert all(counts[kind] > 0 for kind in ("closing", "separation", "sticking",
                                             "breakaway")), counts
    dofs = scene.dof_matrix()
    q0, v0 = dofs @ orbit.initial[0], dofs @ orbit.initial[1]
    history = orbit.history
    reference = bs.run_structure(bs.structure_from_substructures(scene), q0, v0, history.t[-1],
                                 rtol=1e-12, atol=1e-16, t_eval=history.t)
    engine_q = history.x @ dofs.T
    amplitude = np.abs(engine_q).max()
    assert np.abs(reference.q - engine_q).max() <= 1e-8 * amplitude
    assert np.abs(reference.q[-1] - q0).max() <= 1e-8 * amplitude  # it is periodic there too


@pytest.mark.slow  # a law of the tests' own: a kernel of its own (a minute to compile)
def test_monodromy_where_friction_drops_at_breakaway_agrees_with_differences():
    """With μ(0⁺) < μ_s the acceleration jumps at breakaway, so the saltation there has a
    jump term and the breakaway guard's gradient (of the multiplier λ and of N) counts;
    with Coulomb friction it does not."""
    scene = modal_pair(friction=StaticKinetic(mu_static=0.5, mu_kinetic=0.35))
    y = settled_state(scene, 30)
    counts = sn.simulate(scene, 1, method=EXACT, samples_per_period=1,
                         initial=np.split(y, 2)).events.counts
    assert counts["breakaway"] > 0 and counts["sticking"] > 0, counts
    scale = state_scale(y)
    matrix = sn.monodromy(scene, 1, initial=np.split(y, 2), method=EXACT)
    reference = differenced_monodromy(scene, 1, y, scale, 1e-13)
    assert scaled_error(matrix, reference, scale) <= 1e-6


def test_fixed_steps_converge_at_fourth_order_on_a_multi_dof_pair():
    """Classical Runge–Kutta 4 on the three-mode pair, through its impacts, stick and
    breakaway: the same switches as the adaptive run, and an error that falls by 2⁴ as
    the step halves."""
    scene = modal_pair()
    exact = sn.simulate(scene, 3, method=EXACT, samples_per_period=10)
    errors = []
    for steps in (2000, 4000):
        fixed = sn.simulate(scene, 3, method=sn.FixedStep(steps_per_period=steps),
                            samples_per_period=10)
        assert fixed.events.counts == exact.events.counts
        errors.append(np.abs(fixed.x - exact.x).max() / np.abs(exact.x).max())
    assert errors[1] <= errors[0] / 8.0, errors


def test_lyapunov_exponents_of_a_free_modal_blade_sum_to_its_damping():
    """Without contact the flow is linear with trace −Σ_k 2 ζ_k ω_k, so the sum of all
    its Lyapunov exponents is that, whatever the time the single exponents take to part
    (Liouville)."""
    blade = modal_blade()
    scene = sn.Scene(group=sn.BladeGroup().add_blade("blade", blade), speed_rpm=5000.0,
                     excitation=sn.Excitation(engine_order=2, amplitudes=(0.0, 1.0),
                                              phases=sn.AntiPhase()))
    result = sn.lyapunov(scene, 40, transient=0, exponents=6)
    rates = 2 * math.pi * blade.frequencies_at(scene.speed_rpm) * 0.005
    assert result.per_second.sum() == pytest.approx(-2.0 * rates.sum(), rel=1e-6)
    assert np.all(result.per_second < 0.0)
