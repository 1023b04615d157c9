"""Periodic orbits, their Floquet multipliers, and continuation of their families.

References computed here without Newton or the continuation: the forced damped linear
oscillator in closed form, long transients of ``simulate`` (which find every stable
orbit, and leave every unstable one), and up- and down-sweeps of transients, whose jumps
are where a branch folds.
"""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from contact_laws import LinearSpring
from shroudnet import (Adaptive, ConvergenceError, Interface, SimulationError, continuation,
                       periodic_orbit, simulate, sweep)
from shroudnet.scenes import three_blade_paper
from tests.test_physics_references import BLADE, facing_pads
from tests.test_tangent import free_oscillators

#: Transients as exact as the integrator goes, for the orbits they are compared with.
EXACT = Adaptive(rtol=1e-11)


def transient_states(scene, periods, last):
    """The stroboscopic states y = (x, ẋ) of the ``last`` periods of a long run from rest."""
    run = simulate(scene, periods, method=EXACT, samples_per_period=1, event_capacity=0)
    return np.hstack([run.x, run.v])[-last:]


def relative_distance(orbit, states):
    """min over ``states`` of max |y − y_orbit| / the orbit's max |y| (x and ẋ / lΩ)."""
    n = len(orbit.initial[0])
    frequency = orbit.scene.arrays.excitation_frequency
    weights = np.concatenate([np.ones(n), np.full(n, 1.0 / frequency)])
    y = orbit.state * weights
    return min(np.abs(s * weights - y).max() for s in states) / np.abs(y).max()


# ---- periodic orbits ------------------------------------------------------------------------

@pytest.mark.parametrize(("gamma1", "periods"), [(1.0, 1), (3.5, 3)])
def test_the_papers_orbits_agree_with_long_transients(gamma1, periods):
    """Fig. 6's period-1 (γ1 = 1) and period-3 (γ1 = 3.5) motions are stable orbits;
    a 600-period transient lands on them, in one of their ``periods`` phases."""
    scene = three_blade_paper(gamma1=gamma1)
    orbit = periodic_orbit(scene, periods)
    assert orbit.residual <= 1e-10 and orbit.stable
    assert relative_distance(orbit, transient_states(scene, 600, periods)) <= 1e-9
    assert len(orbit.multipliers) == 6
    assert np.all(np.diff(np.abs(orbit.multipliers)) <= 0.0)


def test_a_stick_phase_gives_zero_multipliers():
    """At γ1 = 3.5 a blade sticks once per orbit: the stuck interface's relative velocity
    is forgotten, one zero multiplier."""
    orbit = periodic_orbit(three_blade_paper(gamma1=3.5), 3)
    assert any(kind == "sticking" for _, kind in orbit.event_sequence)
    assert np.sum(np.abs(orbit.multipliers) <= 1e-12) == 1
    assert np.abs(orbit.multipliers[-1]) <= 1e-12


def test_newton_finds_an_unstable_orbit_that_transients_leave():
    """At the paper's γ1 = 2.2 the period-1 orbit is unstable (a complex pair outside the
    unit circle: the motion is quasi-periodic); Newton converges to it all the same."""
    scene = three_blade_paper()
    orbit = periodic_orbit(scene, 1)
    assert not orbit.stable
    assert abs(orbit.multipliers[0].imag) > 0.0
    assert orbit.multipliers[0] == pytest.approx(np.conj(orbit.multipliers[1]))
    assert relative_distance(orbit, transient_states(scene, 400, 10)) > 1e-3


def test_newton_solves_a_linear_scene_in_one_step():
    """Without contact the stroboscopic map is affine, φ(y) = M y + b, so Newton's step
    (M − I) Δy = −(φ(y) − y) lands on its fixed point from any start, here rest: the
    forced response in closed form, x_i(0) = Im(q1 e^{iφ_i} / (k − mω² + icω)). Plain
    iteration of the map would take some 150 periods to get there (|μ| = 0.885); a step
    with the wrong matrix, several."""
    scene = three_blade_paper(gap=1.0)
    orbit = periodic_orbit(scene, 1, transient=0, tolerance=1e-8)
    assert orbit.iterations == 1
    a = scene.arrays
    omega = a.excitation_frequency
    response = 50.0 * np.exp(1j * scene.excitation.blade_phases(3)) / (
        a.stiffness - a.mass * omega**2 + 1j * a.damping * omega)
    np.testing.assert_allclose(orbit.initial[0], response.imag,
                               atol=1e-8 * np.abs(response).max())
    np.testing.assert_allclose(orbit.initial[1], (1j * omega * response).imag,
                               atol=1e-8 * omega * np.abs(response).max())


def test_a_newton_that_cannot_converge_says_why():
    with pytest.raises(ConvergenceError, match=r"residual .* last"):
        periodic_orbit(three_blade_paper(gamma1=8.8), 1, transient=0, tolerance=1e-14)


@pytest.mark.parametrize(("guess", "message"), [
    (np.zeros(6), r"guess must be \(x0, v0\)"),
    ((np.zeros(3), np.zeros(2)), r"guess must be \(x0, v0\)"),
    ((np.zeros(3), np.full(3, np.nan)), "finite"),
])
def test_a_bad_guess_is_refused(guess, message):
    with pytest.raises(ValueError, match=message):
        periodic_orbit(three_blade_paper(), 1, guess=guess)


# ---- the stability an orbit reports is the one a transient finds ---------------------------

@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(gamma1=st.floats(0.5, 9.0), speed=st.floats(5500.0, 7000.0), q1=st.floats(5.0, 60.0),
       gap=st.floats(0.0, 4e-5), seed=st.integers(0, 2**16))
def test_an_orbit_reported_stable_keeps_a_transient_and_an_unstable_one_does_not(
        gamma1, speed, q1, gap, seed):
    scene = three_blade_paper(gamma1=gamma1, speed_rpm=speed, q1=q1, gap=gap)
    try:
        orbit = periodic_orbit(scene, 1, transient=50)
    except SimulationError:
        assume(False)
    largest = abs(orbit.multipliers[0])
    assume(orbit.singular == 0 and abs(largest - 1.0) > 0.02)
    n = len(orbit.initial[0])
    frequency = scene.arrays.excitation_frequency
    scale = np.concatenate([np.full(n, orbit.scale), np.full(n, orbit.scale * frequency)])
    kick = 1e-5 * scale * np.random.default_rng(seed).choice([-1.0, 1.0], 2 * n)
    run = simulate(scene, 400, method=EXACT, samples_per_period=1, event_capacity=0,
                   initial=np.split(orbit.state + kick, 2))
    distance = np.abs((np.hstack([run.x, run.v]) - orbit.state) / scale).max(axis=1)
    if orbit.stable:
        assert distance[-1] < 1e-6, (largest, distance[-1])
    else:
        assert distance.max() > 1e-3, (largest, distance.max())


# ---- continuation ---------------------------------------------------------------------------

def test_without_contact_the_branch_is_the_linear_forced_response_in_closed_form():
    """Across 5000–7000 rpm, gaps no blade closes: each orbit is x_i = Im(q1 e^{i(ωt+φ_i)}
    / (k − mω² + icω)), its peak q1/|k − mω² + icω|, E_ρ half its square, and its
    multipliers the eigenvalues of exp(A T_e)."""
    branch = continuation(lambda rpm: three_blade_paper(speed_rpm=rpm, gap=1.0),
                          5000.0, 7000.0, max_step=0.3)
    assert branch.parameter[0] == 5000.0 and branch.parameter[-1] == 7000.0
    assert len(branch) > 10 and not branch.bifurcations and branch.stable.all()
    for p, orbit in zip(branch.parameter, branch.orbits):
        scene = orbit.scene
        a = scene.arrays
        omega = a.excitation_frequency
        response = 50.0 * np.exp(1j * scene.excitation.blade_phases(3)) / (
            a.stiffness - a.mass * omega**2 + 1j * a.damping * omega)
        np.testing.assert_allclose(orbit.initial[0], response.imag,
                                   rtol=1e-8, atol=1e-9 * np.abs(response).max())
        np.testing.assert_allclose(orbit.initial[1], (1j * omega * response).imag,
                                   rtol=1e-8, atol=1e-9 * omega * np.abs(response).max())
        np.testing.assert_allclose(orbit.peak, np.abs(response), rtol=1e-6)
        np.testing.assert_allclose(orbit.mean_square, np.abs(response) ** 2 / 2, rtol=1e-6)
        expected = np.linalg.eigvals(free_oscillators(scene))
        for part in (np.abs, lambda z: np.abs(np.angle(z))):  # repeated: compare sorted
            np.testing.assert_allclose(np.sort(part(orbit.multipliers)),
                                       np.sort(part(expected)), rtol=1e-7, atol=1e-10)
    assert branch.amplitude("blade2") == pytest.approx(branch.peak[:, 1])


PAD = Interface(gap=1e-4, angle=math.pi / 2, normal=LinearSpring(stiffness=1e6))
STIFF_PAD = Interface(gap=0.0, angle=math.pi / 2, normal=LinearSpring(stiffness=1e6))


def pad_at(interface, q1):
    """A blade against a fixed node across a linear contact spring, at a speed [rpm]."""
    def at(rpm):
        return dataclasses.replace(facing_pads([(BLADE, interface)], (0.0, q1)),
                                   speed_rpm=rpm)
    return at


def jump(values, points):
    """The index i where E_ρ changes fastest from sweep point i to i + 1, checked to
    stand out: at least twice the logarithmic rate of change of any other step."""
    rate = np.abs(np.diff(np.log([point.energy_density for point in points]))
                  / np.diff(values))
    order = np.argsort(rate)
    assert rate[order[-1]] > 2.0 * rate[order[-2]], rate
    return order[-1]


@pytest.fixture(scope="module")
def hardening_branch():
    """The branch of a blade against the spring pad ``PAD`` over 7000–14000 rpm, through
    both folds (read by two tests; computed once)."""
    return continuation(pad_at(PAD, 1.0), 7000.0, 14000.0)


@pytest.mark.slow  # two sweeps of 450-period transients, some 20 s
def test_a_hardening_contact_folds_the_response_and_the_folds_are_the_jumps_of_sweeps(
        hardening_branch):
    """A gap that closes bends the resonance to higher speeds: between two folds three
    orbits coexist, the middle one unstable. A sweep of transients up the speed stays on
    the upper branch to the upper fold and drops there; down the speed it stays on the
    lower branch to the lower fold and jumps up there."""
    at = pad_at(PAD, 1.0)
    branch = hardening_branch
    folds = sorted(b.parameter for b in branch.bifurcations if b.kind == "fold")
    assert len(folds) == 2 and branch.ended == "reached p = 14000"
    lower, upper = folds
    between = (branch.parameter > lower + 10) & (branch.parameter < upper - 10)
    outside = (branch.parameter < lower - 10) | (branch.parameter > upper + 10)
    assert not branch.stable[between].all() and branch.stable[between].any()
    assert branch.stable[outside].all()
    step = 20.0  # rpm, near the folds; each sweep starts from rest where one orbit is
    up = np.concatenate([np.arange(lower - 200.0, upper - 300.0, 100.0),
                         np.arange(upper - 300.0, upper + 200.0, step)])
    down = np.concatenate([np.arange(upper + 200.0, lower + 300.0, -100.0),
                           np.arange(lower + 300.0, lower - 200.0, -step)])
    for values, fold in ((up, upper), (down, lower)):
        points = sweep(at, values, transient=400, record=50, continuation=True, workers=1,
                       progress=False, blade=0).points
        i = jump(values, points)
        assert min(values[i], values[i + 1]) - step <= fold \
            <= max(values[i], values[i + 1]) + step, (values[i], fold)
    kinds = [b.kind for b in branch.bifurcations]
    assert "grazing" in kinds


def test_a_folded_branch_turns_back_at_its_folds(hardening_branch):
    """The hardening pad's branch, without the sweeps: the parameter of its points turns
    back twice, and a fold is reported at each turn and nowhere else, located beyond the
    points around it (the branch's extreme parameter), with a real multiplier at +1; the
    orbits between the folds are unstable, those outside stable."""
    branch = hardening_branch
    p = branch.parameter
    step = np.sign(np.diff(p))
    turns = np.flatnonzero(step[1:] != step[:-1]) + 1  # p[i] is the discrete extreme
    folds = sorted((b for b in branch.bifurcations if b.kind == "fold"),
                   key=lambda b: b.index)
    assert len(turns) == len(folds) == 2, (turns, [b.index for b in folds])
    for turn, fold in zip(turns, folds):
        assert turn in (fold.index, fold.index + 1)
        around = p[fold.index:fold.index + 2]
        upper = step[fold.index - 1] > 0  # the parameter rose to this fold
        assert (fold.parameter >= around.max()) if upper else (fold.parameter <= around.min())
        assert fold.multiplier == pytest.approx(1.0, abs=1e-5)
    between = (np.arange(len(p)) > folds[0].index) & (np.arange(len(p)) <= folds[1].index)
    assert not branch.stable[between].any() and branch.stable[~between].all()


def test_a_period_doubling_starts_a_doubled_branch_that_a_transient_lands_on():
    """A blade touching a stiff pad (a bilinear oscillator), forced above its resonance:
    the period-1 orbit loses stability as a real multiplier passes −1, and a stable
    period-2 orbit is born there."""
    at = pad_at(STIFF_PAD, 20.0)
    branch = continuation(at, 20000.0, 22800.0)
    (doubling,) = [b for b in branch.bifurcations if b.kind == "period-doubling"]
    assert doubling.multiplier == pytest.approx(-1.0, abs=1e-6)
    before = branch.parameter < doubling.parameter
    assert branch.stable[before].all() and not branch.stable[~before].any()
    doubled = continuation(at, 20000.0, 22800.0, from_bifurcation=doubling)
    assert doubled.periods == 2
    assert doubled.parameter[0] == pytest.approx(doubling.parameter, rel=1e-2)
    assert np.all(doubled.parameter > doubling.parameter)
    orbit, single = doubled.orbits[-1], branch.orbits[-1]
    assert orbit.stable and orbit.switches[(0, "closing")] == 2
    assert doubled.parameter[-1] == branch.parameter[-1] == 22800.0
    # leaving the unstable period-1 orbit, a transient settles on the period-2 orbit
    run = simulate(orbit.scene, 600, method=EXACT, samples_per_period=1, event_capacity=0,
                   initial=np.split(single.state * (1.0 + 1e-6), 2))
    assert relative_distance(orbit, np.hstack([run.x, run.v])[-2:]) <= 1e-6


def test_the_papers_resonance_loses_period_one_at_a_torus_bifurcation():
    """Below about 6120 rpm the period-1 orbit of the paper's group has a complex pair of
    multipliers outside the unit circle: the quasi-periodic motion of the
    paper's 5990 rpm case (docs/guide/analysis.md)."""
    branch = continuation(lambda rpm: three_blade_paper(speed_rpm=rpm), 5900.0, 6400.0)
    (torus,) = [b for b in branch.bifurcations if b.kind == "torus"]
    assert abs(abs(torus.multiplier) - 1.0) <= 1e-6 and abs(torus.multiplier.imag) > 0.1
    assert not branch.stable[branch.parameter < torus.parameter].any()
    assert branch.stable[branch.parameter > torus.parameter].all()


@pytest.mark.parametrize(("arguments", "message"), [
    ((lambda p: three_blade_paper(), 1.0, 2.0), "same scene for different values"),
    ((lambda p: three_blade_paper(q1=p), 5.0, 5.0), "start and stop are both"),
    ((lambda p: "scene", 1.0, 2.0), "must return a shroudnet.Scene"),
])
def test_bad_continuation_input_is_refused_before_any_work(arguments, message):
    with pytest.raises((ValueError, TypeError), match=message):
        continuation(*arguments)


def test_continuation_refuses_a_bifurcation_it_cannot_start_from():
    branch = continuation(lambda q: three_blade_paper(q1=q, gap=1.0), 10.0, 20.0,
                          max_points=3)
    with pytest.raises(ValueError, match="period-doubling"):
        continuation(lambda q: three_blade_paper(q1=q), 10.0, 20.0,
                     from_bifurcation=branch)


def test_sweeps_and_branches_give_every_blades_peak_and_the_worst_blade():
    """Without contact, the linear forced response: each blade's peak q1/|k − mω² + icω|,
    from the orbits exactly and from a transient's samples to their spacing."""
    def at(rpm):
        return three_blade_paper(speed_rpm=rpm, gap=1.0)
    branch = continuation(at, 6000.0, 6100.0, max_points=3)
    values = branch.parameter
    points = sweep(at, values, transient=300, record=20, workers=1, progress=False).points
    for value, orbit, point in zip(values, branch.orbits, points):
        a = orbit.scene.arrays
        omega = a.excitation_frequency
        exact = 50.0 / np.abs(a.stiffness - a.mass * omega**2 + 1j * a.damping * omega)
        np.testing.assert_allclose(orbit.peak, exact, rtol=1e-9)
        # 50 samples a period: the largest misses by up to 1 − cos(π/50) = 2e-3, the
        # cubic through the samples and their rates by (2π/50)⁴/384 = 6e-7
        np.testing.assert_allclose(point.peak, exact, rtol=1e-6)
        assert point.worst_blade in (0, 1, 2)
    np.testing.assert_array_equal(branch.worst_blade(), np.argmax(branch.peak, axis=1))
    assert branch.amplification(branch).max() == pytest.approx(1.0)
    result = sweep(at, values, transient=300, record=20, workers=1, progress=False)
    np.testing.assert_allclose(result.amplification(branch.peak.max()),
                               result.peaks().max(axis=1) / branch.peak.max())
