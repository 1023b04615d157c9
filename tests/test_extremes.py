"""The extremes of a periodic orbit where its velocity crosses zero, not at samples: the
amplitude (half the peak-to-peak), the peak |x| and the mean against closed forms."""

import math

import numpy as np
import pytest

import shroudnet as sn
from contact_laws import ConstantLoad, Coulomb

MASS, STIFFNESS = 0.1, 1e5
NATURAL = math.sqrt(STIFFNESS / MASS)  # [rad/s]


def single_blade(*, speed_rpm, amplitudes, damping=0.0, rubbing=None):
    """One blade on its spring, forced at engine order 1; ``rubbing`` (N, μ): pressed onto
    a fixed pad by a constant normal load N and rubbing along x with Coulomb friction."""
    group = sn.BladeGroup().add_blade("b", sn.Blade(mass=MASS, damping=damping,
                                                    stiffness=STIFFNESS))
    if rubbing is not None:
        load, mu = rubbing
        group.add_fixed("pad").connect("b", "pad", sn.Interface(
            gap=0.0, angle=0.0, normal=ConstantLoad(force=load), friction=Coulomb(mu=mu)))
    return sn.Scene(group=group, speed_rpm=speed_rpm, excitation=sn.Excitation(
        engine_order=1, amplitudes=amplitudes, phases=sn.AntiPhase()))


def rpm(omega):
    return 60.0 * omega / (2.0 * math.pi)


@pytest.mark.parametrize("beta", [0.8, 1.3])
def test_den_hartogs_oscillator_has_his_exact_amplitude_at_default_settings(beta):
    """Den Hartog (1931): m ẍ + k x + F sgn ẋ = P sin ωt moves without stops with
    X = (P/k) √(V² − (F/P)² U²), V = 1/(1 − β²), U = sin(π/β) / (β (1 + cos(π/β))),
    β = ω/ω_n. Its extremes lie where the friction force reverses, a switch: the sampled
    parabola missed them by 10⁻⁵ of X."""
    force, load, mu = 10.0, 10.0, 0.3
    scene = single_blade(speed_rpm=rpm(beta * NATURAL), amplitudes=(0.0, force),
                         rubbing=(load, mu))
    orbit = sn.periodic_orbit(scene)
    assert orbit.events.counts["reversal"] == 2 and orbit.events.counts["sticking"] == 0
    ratio = mu * load / force
    v = 1.0 / (1.0 - beta ** 2)
    u = math.sin(math.pi / beta) / (beta * (1.0 + math.cos(math.pi / beta)))
    exact = force / STIFFNESS * math.sqrt(v ** 2 - (ratio * u) ** 2)
    assert orbit.amplitude("b") == pytest.approx(exact, rel=1e-8)
    assert orbit.peak[0] == pytest.approx(exact, rel=1e-8)
    assert orbit.maximum[0] == pytest.approx(-orbit.minimum[0], rel=1e-8)


def test_amplitude_is_half_the_peak_to_peak_and_peak_keeps_the_static_deflection():
    """A damped linear blade under q0 + q1 sin ωt: amplitude q1/|k − mω² + icω|, mean
    q0/k, peak q0/k + amplitude (the smooth extremes, refined by one run each)."""
    q0, q1, damping, omega = 30.0, 5.0, 4.0, 0.93 * NATURAL
    scene = single_blade(speed_rpm=rpm(omega), amplitudes=(q0, q1), damping=damping)
    orbit = sn.periodic_orbit(scene, tolerance=1e-12)
    amplitude = q1 / abs(STIFFNESS - MASS * omega ** 2 + 1j * damping * omega)
    static = q0 / STIFFNESS
    assert orbit.amplitude("b") == pytest.approx(amplitude, rel=1e-9)
    assert orbit.mean[0] == pytest.approx(static, rel=1e-9)
    assert orbit.peak[0] == pytest.approx(static + amplitude, rel=1e-9)
    assert orbit.maximum[0] == pytest.approx(static + amplitude, rel=1e-9)
    assert orbit.minimum[0] == pytest.approx(static - amplitude, rel=1e-9)
    assert orbit.amplitude(0) == orbit.amplitude("b")
    coarse = sn.periodic_orbit(scene, tolerance=1e-12, samples_per_period=20)
    assert coarse.amplitude("b") == pytest.approx(amplitude, rel=1e-9)  # not the samples'


def test_a_branch_reads_its_orbits_amplitudes_and_they_save_and_load(tmp_path):
    from shroudnet.io import results
    branch = sn.continuation(lambda q0: single_blade(
        speed_rpm=rpm(0.9 * NATURAL), amplitudes=(q0, 5.0), damping=4.0), 0.0, 40.0,
        max_points=3)
    amplitude = 5.0 / abs(STIFFNESS - MASS * (0.9 * NATURAL) ** 2 + 4j * 0.9 * NATURAL)
    np.testing.assert_allclose(branch.amplitude("b"), amplitude, rtol=1e-8)
    np.testing.assert_allclose(branch.peak[:, 0], branch.parameter / STIFFNESS + amplitude,
                               rtol=1e-8)
    loaded = results.load(results.save_branch(tmp_path / "branch.npz", branch))
    for saved, orbit in zip(loaded.orbits, branch.orbits):
        for name in ("maximum", "minimum", "mean", "peak"):
            np.testing.assert_array_equal(getattr(saved, name), getattr(orbit, name))


def test_a_run_sampled_at_listed_times_meets_the_runs_to_each_time():
    """``integrate(times=)``: the paper's group (impacts, slip) sampled at seven instants
    of a period from the dense output of the steps that hold them, against seven runs each
    cut at its instant (both at rtol 1e-12, switches located to 1e-12 periods): the same
    positions and velocities to 1e-11 of their scales (measured 1.0e-13 and 2.0e-13).
    Times out of order, past the run or on a fixed grid are refused by name."""
    from shroudnet.run.simulate import integrate
    from shroudnet.steady.extremes import state_at
    scene = sn.scenes.three_blade_paper(gamma1=3.5)
    orbit = sn.periodic_orbit(scene, stability=False)
    initial = tuple(orbit.initial)
    period = scene.excitation_period
    times = period * np.array([0.05, 0.2, 0.31, 0.5, 0.77, 0.9, 1.0])
    method = sn.Adaptive(rtol=1e-12)
    listed = integrate(scene, 1, method=method, initial=initial, times=times,
                       event_tolerance=1e-12, event_capacity=0).run.output
    np.testing.assert_array_equal(listed.t, np.concatenate([[0.0], times]))
    gaps = np.array([np.concatenate([listed.x[k] - x, listed.v[k] - v]) for k, (x, v) in
                     enumerate((state_at(scene, initial, moment, method, 1e-12)
                                for moment in times), start=1)])
    n = len(listed.x[0])
    assert np.abs(gaps[:, :n]).max() <= 1e-11 * np.abs(listed.x).max()
    assert np.abs(gaps[:, n:]).max() <= 1e-11 * np.abs(listed.v).max()
    for bad, method in ((times[::-1], sn.Adaptive()), (2.5 * times, sn.Adaptive()),
                        (times, sn.FixedStep(steps_per_period=1000))):
        with pytest.raises(ValueError, match="integrate.times"):
            integrate(scene, 1, method=method, initial=initial, times=bad)
