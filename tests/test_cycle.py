"""One cycle of a periodic orbit in an engineer's terms: harmonics and phases, energy per
cycle, equivalent damping, against closed forms; carried along a branch and drawn."""

import math

import numpy as np
import pytest

import shroudnet as sn
from tests.test_extremes import MASS, NATURAL, STIFFNESS, rpm, single_blade

Q0, Q1, DAMPING = 2.0, 5.0, 4.0


def linear_orbit(beta):
    omega = beta * NATURAL
    scene = single_blade(speed_rpm=rpm(omega), amplitudes=(Q0, Q1), damping=DAMPING)
    return sn.periodic_orbit(scene, tolerance=1e-12), omega


@pytest.mark.parametrize("beta", [0.7, 1.4])
def test_a_linear_oscillators_harmonics_and_phase_are_its_closed_form(beta):
    """x = q0/k + X sin(ωt − ψ), X = q1/|k − mω² + icω|, ψ = atan2(cω, k − mω²); no
    higher harmonic."""
    orbit, omega = linear_orbit(beta)
    found = orbit.harmonics("b", order=3)
    amplitude = Q1 / abs(STIFFNESS - MASS * omega ** 2 + 1j * DAMPING * omega)
    lag = math.atan2(DAMPING * omega, STIFFNESS - MASS * omega ** 2)
    assert found.amplitudes[0] == pytest.approx(Q0 / STIFFNESS, rel=1e-10)
    assert found.amplitudes[1] == pytest.approx(amplitude, rel=1e-10)
    assert found.phases[1] == pytest.approx(-lag, abs=2e-10)
    assert np.all(found.amplitudes[2:] < 1e-10 * amplitude)
    assert found.frequencies[1] == pytest.approx(omega / (2 * math.pi), rel=1e-12)
    with pytest.raises(ValueError, match="order must be at most 49 with 100 samples"):
        orbit.harmonics("b", order=50)


@pytest.mark.parametrize("beta", [0.7, 1.0, 1.4])
def test_the_equivalent_damping_of_a_linear_viscous_oscillator_is_c_over_2m_omega(beta):
    """W_d = π c ω X², T_max = ½ m ω² X²: ζ_eq = c/(2mω) at every forcing frequency; the
    excitation's work per cycle is the viscous loss."""
    orbit, omega = linear_orbit(beta)
    assert orbit.equivalent_damping == pytest.approx(DAMPING / (2 * MASS * omega), rel=1e-9)
    energy = orbit.energy_per_cycle
    amplitude = Q1 / abs(STIFFNESS - MASS * omega ** 2 + 1j * DAMPING * omega)
    assert energy.damping == pytest.approx(math.pi * DAMPING * omega * amplitude ** 2,
                                           rel=1e-8)
    assert energy.excitation == pytest.approx(energy.dissipated, rel=1e-8)
    assert energy.friction == energy.contact == 0.0


def test_friction_loss_per_cycle_is_den_hartogs_4fx_and_the_hysteresis_loops_area():
    """Sliding without stops, the friction force F = μN reverses at the extremes ±X: it
    takes 4 F X a cycle, the ledger's loss exactly and the loop's area to its samples."""
    force, load, mu, beta = 10.0, 10.0, 0.3, 0.8
    scene = single_blade(speed_rpm=rpm(beta * NATURAL), amplitudes=(0.0, force),
                         rubbing=(load, mu))
    orbit = sn.periodic_orbit(scene)
    exact = 4.0 * mu * load * orbit.amplitude("b")
    assert orbit.energy_per_cycle.friction == pytest.approx(exact, rel=1e-8)
    assert orbit.energy_per_cycle.excitation == pytest.approx(exact, rel=1e-8)
    assert orbit.friction_losses()[0] == pytest.approx(exact, rel=1e-3)
    # undamped, friction alone dissipates: ζ_eq = 4FX / (4π · ½ m ω_max² …) > 0
    assert orbit.equivalent_damping > 0.0
    # the blade slides on a fixed pad along x: the interface's slip is the blade's motion
    slip, motion = orbit.slip_harmonics(0, order=3), orbit.harmonics("b", order=3)
    np.testing.assert_allclose(slip.amplitudes, motion.amplitudes, rtol=1e-12, atol=1e-20)
    np.testing.assert_allclose(slip.phases[1], motion.phases[1], atol=1e-12)
    with pytest.raises(ValueError, match="slip_harmonics"):
        orbit.slip_harmonics(3)


def test_a_branch_carries_the_content_and_the_figure_draws_any_of_it(tmp_path):
    from shroudnet.front.figures import forced_response
    from shroudnet.io import results
    branch = sn.continuation(lambda speed: single_blade(
        speed_rpm=speed, amplitudes=(Q0, Q1), damping=DAMPING), rpm(0.7 * NATURAL),
        rpm(0.8 * NATURAL), max_points=3)
    omega = 2 * math.pi * branch.parameter / 60.0
    np.testing.assert_allclose(branch.equivalent_damping, DAMPING / (2 * MASS * omega),
                               rtol=1e-8)
    amplitudes, phases = branch.harmonics("b", order=2)
    np.testing.assert_allclose(amplitudes[:, 1], branch.amplitude("b"), rtol=1e-8)
    assert amplitudes.shape == phases.shape == (len(branch), 3)
    np.testing.assert_allclose(branch.energy_per_cycle[:, 0], branch.energy_per_cycle[:, 1],
                               rtol=1e-8)
    loaded = results.load(results.save_branch(tmp_path / "branch.npz", branch))
    np.testing.assert_array_equal(loaded.equivalent_damping, branch.equivalent_damping)
    np.testing.assert_array_equal(loaded.energy_per_cycle, branch.energy_per_cycle)
    for quantity in ("amplitude", "peak", "equivalent damping", "friction loss", "phase"):
        axes = forced_response({"up": branch}, "b", quantity=quantity).axes[0]
        assert len(axes.lines[0].get_ydata()) == len(branch)
    assert "ζ_eq" in forced_response({"up": branch}, "b",
                                     quantity="equivalent damping").axes[0].get_ylabel()
    with pytest.raises(ValueError, match="quantity must be one of"):
        forced_response({"up": branch}, "b", quantity="colour")


def test_the_frequency_shift_says_when_the_branch_peaks_at_its_end():
    """Below resonance a linear blade's amplitude rises all the way, so the branch's
    largest is its last point: flagged and said. The linear limits (no interface: all
    three one) peak at the damped resonance ω_n √(1 − 2ζ²), ζ = c/(2 m ω_n). Across the
    resonance the branch's largest amplitude is inside it, there within its spacing."""
    def blade(speed):
        return single_blade(speed_rpm=speed, amplitudes=(Q0, Q1), damping=DAMPING)

    zeta = DAMPING / (2 * MASS * NATURAL)
    resonance = NATURAL * math.sqrt(1 - 2 * zeta ** 2) / (2 * math.pi)
    rising = sn.continuation(blade, rpm(0.7 * NATURAL), rpm(0.8 * NATURAL), max_points=3)
    shift = rising.frequency_shift("b")
    assert shift.at_end and "at its end" in str(shift)
    assert shift.peak == pytest.approx(rising.parameter[-1] / 60.0, rel=1e-12)
    assert shift.open == shift.stuck == shift.closed == pytest.approx(resonance, rel=1e-5)
    assert math.isnan(shift.stiffening)
    across = sn.continuation(blade, rpm(0.9 * NATURAL), rpm(1.1 * NATURAL))
    shift = across.frequency_shift("b")
    assert not shift.at_end and "at its end" not in str(shift)
    assert shift.peak == pytest.approx(resonance, rel=0.01)


@pytest.mark.slow
def test_the_frequency_shift_places_a_stuck_pairs_peak_at_its_stuck_resonance():
    """Two blades forced in phase through a preloaded contact that never slips: the pair
    moves as one body, so the branch peaks at √((k_a + k_b)/(m_a + m_b)), the stuck
    limit's resonance, far from the open blades' √(k_a/m_a)."""
    from contact_laws import Coulomb, LinearSpring

    def pair(speed):
        group = sn.BladeGroup().add_blade("a", sn.Blade(mass=0.1, damping=2.0,
                                                        stiffness=1e5))
        group.add_blade("b", sn.Blade(mass=0.3, damping=6.0, stiffness=2e5))
        group.connect("a", "b", sn.Interface(gap=-1e-3, angle=0.3,
                                             normal=LinearSpring(stiffness=1e6),
                                             friction=Coulomb(mu=50.0)))
        return sn.Scene(group=group, speed_rpm=speed, excitation=sn.Excitation(
            engine_order=1, amplitudes=(0.0, 1.0), phases=sn.ExplicitPhases((0.0, 0.0))))

    stuck = math.sqrt(3e5 / 0.4) / (2 * math.pi)
    branch = sn.continuation(pair, 60 * 0.9 * stuck, 60 * 1.1 * stuck, max_step=0.05)
    shift = branch.frequency_shift("a")
    assert shift.stuck == shift.closed == pytest.approx(stuck, rel=1e-3)  # preloaded
    assert shift.open == pytest.approx(math.sqrt(1e5 / 0.1) / (2 * math.pi), rel=1e-3)
    assert shift.peak == pytest.approx(stuck, rel=5e-3)
    assert shift.stiffening == pytest.approx(1.0, abs=0.02)
