"""Coupling edges and blades without a spring to ground.

A coupling is a linear spring and damper between two nodes. Checked against references
computed here: the complex linear solve of the harmonic steady state (K − ω²M + iωC) X = F,
the dissipation π ω Re(Xᴴ C X) per period it implies, the plain solve_ivp implementation
(``shroudnet.references.blades``, which builds K and C as matrices where the loop sums edges), and
central differences of the trajectory for the monodromy matrix.
"""

import math

import numpy as np
import pytest

from contact_laws import ConstantLoad, Stribeck
from shroudnet import (
    Adaptive,
    Blade,
    BladeGroup,
    Coupling,
    Excitation,
    ExplicitPhases,
    Interface,
    Mode,
    Scene,
    assemble,
    monodromy,
    simulate,
)
from shroudnet.engine.generate import flags
from shroudnet.references.blades import solve_ivp_baseline
from shroudnet.scenes import three_blade_paper
from tests.test_tangent import (
    EXACT,
    differenced_monodromy,
    scaled_error,
    settled_state,
    state_scale,
)

ROOT = Blade(mass=0.1, damping=2.0, stiffness=1e5)
TIP = Blade(mass=0.05, damping=0.0, stiffness=0.0)  # held by its coupling alone


def two_mass_blade(speed_rpm=6000.0):
    """A root on a ground spring and a tip held by a coupling to it, forced at the root."""
    group = BladeGroup().add_blade("root", ROOT).add_blade("tip", TIP)
    group.connect("root", "tip", Coupling(stiffness=4e4, damping=1.0))
    excitation = Excitation(engine_order=1, amplitudes=(0.0, 1.0),
                            phases=ExplicitPhases((0.0, 0.0)))
    return Scene(group=group, excitation=excitation, speed_rpm=speed_rpm)


def harmonic_response(scene):
    """X with x(t) = Im(X e^{iωt}): the complex linear solve, ω = l Ω."""
    a = scene.arrays
    w = a.excitation_frequency
    force = a.harmonic_amplitudes[1] * np.exp(1j * a.harmonic_phases[1])
    dynamic = a.stiffness_matrix() - w * w * np.diag(a.mass) + 1j * w * a.damping_matrix()
    return np.linalg.solve(dynamic, force)


def test_coupled_blade_settles_on_the_linear_harmonic_response():
    scene = two_mass_blade()
    run = simulate(scene, 300, method=Adaptive(rtol=1e-10), samples_per_period=40)
    X = harmonic_response(scene)
    t = run.t[-40:]
    expected = (X[None, :] * np.exp(1j * scene.arrays.excitation_frequency * t[:, None])).imag
    # 2.3e-7: what is left of the transient
    assert np.abs(run.x[-40:] - expected).max() < 1e-6 * np.abs(X).max()
    assert np.abs(X[1]) > np.abs(X[0])  # the tip moves, and more than the root


def test_coupling_dampers_dissipate_what_the_linear_solve_says():
    scene = two_mass_blade()
    X = harmonic_response(scene)
    w = scene.arrays.excitation_frequency
    periods = 10
    run = simulate(scene, periods, method=Adaptive(rtol=1e-11),
                   initial=(X.imag, (1j * w * X).imag))
    damping = scene.arrays.damping_matrix()
    expected = periods * math.pi * w * np.real(X.conj() @ damping @ X)
    ledger = run.energy
    assert ledger.damping_loss == pytest.approx(expected, rel=1e-8)
    assert ledger.excitation_work == pytest.approx(expected, rel=1e-8)
    assert abs(ledger.stored_change) < 1e-8 * expected


def gripped_chain():
    """Three blades on two preloaded interfaces that stick and break away; the middle one
    has no spring to ground. A coupling joins the outer two (inside the cluster when both
    interfaces stick) and one joins the last blade to the disc."""
    group = BladeGroup().add_fixed("disc")
    group.add_blade("a", Blade(mass=0.08, damping=1.0, stiffness=1.2e5))
    group.add_blade("b", Blade(mass=0.04, damping=0.5, stiffness=0.0))
    group.add_blade("c", Blade(mass=0.08, damping=1.0, stiffness=1.0e5))
    pad = Interface(gap=0.0, angle=0.5, normal=ConstantLoad(force=25.0),
                    friction=Stribeck(mu_static=0.6, mu_kinetic=0.4, stribeck_velocity=0.05))
    group.connect("a", "b", pad).connect("b", "c", pad)
    group.connect("a", "c", Coupling(stiffness=3e4, damping=0.5))
    group.connect("c", "disc", Coupling(stiffness=2e4))
    excitation = Excitation(engine_order=1, amplitudes=(0.0, 30.0),
                            phases=ExplicitPhases((0.0, 0.0, 2.0)))
    return Scene(group=group, excitation=excitation, speed_rpm=6000.0)


def test_stick_clusters_with_couplings_follow_the_plain_solve_ivp_implementation():
    scene = gripped_chain()
    periods = 6
    start = (np.zeros(3), np.array([0.3, 0.0, -0.2]))  # slipping: both start in one mode
    compiled = simulate(scene, periods, method=Adaptive(rtol=1e-10, atol=1e-14),
                        samples_per_period=1, event_tolerance=1e-12, initial=start)
    counts = compiled.events.counts
    assert counts["sticking"] > 0 and counts["breakaway"] > 0, counts
    plain = solve_ivp_baseline(scene, periods, rtol=1e-10, atol=1e-14, initial=start)
    # The loop logs each interface's switch; the plain run counts restarts: one per instant.
    instants = 1 + np.count_nonzero(np.diff(compiled.events.time) > 1e-9 * compiled.t[1])
    assert plain.switches == instants < sum(counts.values())
    assert np.abs(plain.x - compiled.x).max() < 1e-7 * np.abs(compiled.x).max()
    assert np.abs(plain.v - compiled.v).max() < 1e-7 * np.abs(compiled.v).max()


def test_energy_ledger_balances_with_couplings_and_stick():
    run = simulate(gripped_chain(), 40, method=Adaptive(rtol=1e-10))
    ledger = run.energy
    assert ledger.friction_loss > 0.0 and ledger.damping_loss > 0.0
    assert abs(ledger.residual) < 1e-7 * ledger.excitation_work


def test_monodromy_with_couplings_agrees_with_differences_of_the_trajectory():
    scene = gripped_chain()
    y = settled_state(scene, 20)
    scale = state_scale(y)
    n = len(y) // 2
    matrix = monodromy(scene, 1, initial=(y[:n], y[n:]), method=EXACT)
    reference = differenced_monodromy(scene, 1, y, scale)
    assert scaled_error(matrix, reference, scale) <= 1e-6


def test_a_coupling_inside_a_stick_cluster_loads_its_static_friction():
    """All stuck, a–b–c move as one body; the a–c coupling pulls a and c apart from b's
    point of view, so the static friction of a–b carries it: its value is a's equilibrium,
    m_a ẍ = R_a − F_ab, with R_a counting the coupling."""
    scene = gripped_chain()
    x = np.array([2e-5, -1e-5, -3e-5])
    v = np.full(3, 0.1)
    stuck = assemble(scene, 0.0, x, v, [Mode.STICK, Mode.STICK])
    a = scene.arrays
    resultant_a = -a.damping[0] * v[0] - a.stiffness[0] * x[0] \
        - 3e4 * (x[0] - x[2]) - 0.5 * (v[0] - v[2])  # no excitation at t = 0
    force_ab = resultant_a - a.mass[0] * stuck.acceleration[0]
    assert np.allclose(stuck.acceleration, stuck.acceleration[0])
    assert stuck.interface_force[0] == pytest.approx(force_ab, rel=1e-12)


def test_kernels_carry_coupling_code_only_for_scenes_with_couplings():
    assert flags(gripped_chain().arrays)["HAS_COUPLINGS"]
    assert not flags(three_blade_paper().arrays)["HAS_COUPLINGS"]


def test_stiffness_matrix_sums_the_blades_and_the_couplings():
    a = gripped_chain().arrays
    expected = np.array([[1.2e5 + 3e4, 0.0, -3e4],
                         [0.0, 0.0, 0.0],
                         [-3e4, 0.0, 1.0e5 + 3e4 + 2e4]])
    assert np.array_equal(a.stiffness_matrix(), expected)
    assert np.array_equal(a.damping_matrix(), np.diag([1.5, 0.5, 1.5])
                          - np.array([[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]]))


@pytest.mark.parametrize("build, error, match", [
    (lambda: Coupling(stiffness=-1.0), ValueError, r"Coupling\.stiffness must be in \[0"),
    (lambda: Coupling(stiffness=1.0, damping=float("nan")), ValueError, r"Coupling\.damping"),
    (lambda: Coupling(stiffness=0.0), ValueError, r"stiffness > 0 .* or damping > 0"),
    (lambda: BladeGroup().add_blade("a", ROOT).add_blade("b", ROOT).connect("a", "b", 3.0),
     TypeError, r"Interface or a shroudnet\.Coupling"),
    (lambda: Blade(mass=1.0, damping=0.0, stiffness=-1.0), ValueError, r"Blade\.stiffness"),
])
def test_bad_couplings_are_refused_with_the_field_named(build, error, match):
    with pytest.raises(error, match=match):
        build()


def test_a_group_that_could_drift_away_is_refused():
    group = BladeGroup().add_blade("a", TIP).add_blade("b", TIP)
    group.connect("a", "b", Coupling(stiffness=1e4))
    excitation = Excitation(engine_order=1, amplitudes=(0.0, 1.0),
                            phases=ExplicitPhases((0.0, 0.0)))
    with pytest.raises(ValueError, match=r"blades \['a', 'b'\] float free.*add_fixed"):
        Scene(group=group, excitation=excitation, speed_rpm=6000.0)
    group.add_fixed("disc").connect("disc", "a", Coupling(stiffness=1e4))
    held = Scene(group=group, excitation=excitation, speed_rpm=6000.0)
    # both loads through disc–a, then bs own through a–b: x_b = 2/1e4 + 1/1e4
    assert held.arrays.static_deflection == pytest.approx(3e-4)
    assert "2 couplings" in repr(held.group)


def test_a_bladed_disc_goes_through_a_scene_file_and_back():
    from shroudnet.io import scenefile
    from shroudnet.scenes import bladed_disc_24
    scene = bladed_disc_24(sectors=4)
    text = scenefile.document(scene)
    assert text["sectors"] == 4 and len(text["couplings"]) == 4 * 3
    again = scenefile.read(json_round_trip(text)).scene
    assert scenefile.document(again) == text
    assert np.array_equal(again.arrays.stiffness_matrix(), scene.arrays.stiffness_matrix())
    assert again.group.graph.graph["sectors"] == 4


def json_round_trip(value):
    import json
    return json.loads(json.dumps(value))


@pytest.mark.parametrize("change, match", [
    (lambda d: d["couplings"][0].update(stiffness=-5.0),
     r"couplings\[0\]: Coupling\.stiffness must be in \[0, inf\) N/m, got -5"),
    (lambda d: d["couplings"][0].update(right="ghost"), r"couplings\[0\]: .*unknown node"),
    (lambda d: d["couplings"][0].update(spring=1.0), r"couplings\[0\]\.spring: unknown key"),
    (lambda d: d.update(sectors=5), r"sectors: must be a whole number >= 1 that divides"),
    (lambda d: [b.update(stiffness=0.0) for b in d["blades"] if b["name"].startswith("disc")],
     r"the scene: blades \[.*\] float free"),
])
def test_a_bad_coupling_in_a_scene_file_is_named(change, match):
    from shroudnet.io import scenefile
    from shroudnet.scenes import bladed_disc_24
    document = scenefile.document(bladed_disc_24(sectors=4))
    change(document)
    with pytest.raises(scenefile.SceneFileError, match=match):
        scenefile.read(document)
