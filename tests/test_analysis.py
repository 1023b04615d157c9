"""Analysis: spectra, the period and chaos classifier, energy measures, Campbell."""

import functools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from shroudnet import (FixedStep, amplitude_spectrum, campbell, classify, classify_section,
                       friction_loss_per_cycle, simulate, spectrum, zero_one_test)
from shroudnet.scenes import paper_frequency_model, three_blade_paper
from tests.test_simulate import linear_response


@functools.cache  # 700 periods by solve_ivp take seconds; the period-2 section serves twice
def duffing_section(gamma, *, delta=0.3, omega=1.2, transient=200, record=500):
    """Poincaré points of x'' + δx' − x + x³ = γ cos ωt (the double-well Duffing oscillator
    of Guckenheimer & Holmes, §2.2): period 2 at γ = 0.28, chaotic at γ = 0.5."""
    period = 2 * math.pi / omega

    def field(t, y):
        return [y[1], -delta * y[1] + y[0] - y[0] ** 3 + gamma * math.cos(omega * t)]

    times = period * np.arange(transient, transient + record)
    run = solve_ivp(field, (0.0, times[-1]), [1.0, 0.0], method="DOP853", rtol=1e-10,
                    atol=1e-12, t_eval=times)
    return run.y.T


@pytest.fixture(scope="module")
def linear():
    scene = three_blade_paper(gap=1.0, q1=50.0, speed_rpm=6000.0)
    x0, v0 = linear_response(scene, [0.0])
    return simulate(scene, 24, method=FixedStep(steps_per_period=500), samples_per_period=50,
                    initial=(x0[0], v0[0]))


def test_a_linear_oscillator_is_p1_with_its_spectrum_at_the_excitation(linear):
    kind = classify(linear, "blade2", skip=4)
    assert kind.label == "p1" and kind.period == 1 and kind.mismatch < 1e-6
    spec = spectrum(linear, "blade2", skip=4, window="rectangular")
    assert spec.peak() == pytest.approx(1.0, abs=spec.resolution / 2)
    assert spec.resolution == pytest.approx(1 / 20)
    omega = linear.scene.arrays.excitation_frequency
    amplitude = np.hypot(linear.x[0, 1], linear.v[0, 1] / omega)
    assert spec.amplitude_at(1.0) == pytest.approx(amplitude, rel=1e-6)
    hann = spectrum(linear, "blade2", skip=4)
    assert hann.amplitude_at(1.0) == pytest.approx(amplitude, rel=1e-6)
    # RK4 at 500 steps per period errs by about (ω h)⁴ = (2π/500)⁴ ≈ 2.5e-8 of the
    # amplitude; the exact steady state puts every Poincaré point on the same spot.
    spread = np.ptp(linear.poincare("blade2", skip=4), axis=0)
    accuracy = (2 * math.pi / 500) ** 4
    assert spread[0] < accuracy * amplitude and spread[1] < accuracy * amplitude * omega


def test_a_p3_orbit_has_three_points_and_energy_at_odd_thirds_of_the_excitation():
    sim = simulate(three_blade_paper(gamma1=3.5), 300, samples_per_period=50)
    kind = classify(sim, 1, skip=240)
    assert kind.label == "p3"
    points = sim.poincare(1, skip=240)
    assert len(np.unique(np.round(points[:, 0] / np.abs(points[:, 0]).max(), 4))) == 3
    spec = spectrum(sim, 1, skip=240, window="rectangular")  # 60 periods: thirds on bins
    main = spec.amplitude_at(1.0)
    # The symmetric group keeps the odd multiples only, as the paper's Fig. 14 shows.
    for ratio in (1 / 3, 5 / 3, 7 / 3):
        assert spec.amplitude_at(ratio) > 1e-3 * main
    for ratio in (1 / 2, 1 / 4, 3 / 4, 5 / 4):
        assert spec.amplitude_at(ratio) < 1e-5 * main


def test_the_classifier_on_duffing_and_quasi_periodic_motions():
    doubled = classify_section(duffing_section(0.28))
    chaotic = classify_section(duffing_section(0.5))
    t = 2 * math.pi * np.arange(500)
    torus = np.column_stack([np.sin(t) + 0.5 * np.sin(math.sqrt(2) * t),
                             np.cos(t) + 0.5 * math.sqrt(2) * np.cos(math.sqrt(2) * t)])
    quasi = classify_section(torus)
    assert (doubled.label, chaotic.label, quasi.label) == ("p2", "chaotic", "quasi-periodic")
    assert chaotic.zero_one > 0.9
    assert abs(quasi.zero_one) < 0.1
    assert abs(zero_one_test(duffing_section(0.28)[:, 0])) < 0.1
    assert "0-1 test K" in str(chaotic)


def test_classifier_inputs_are_checked():
    with pytest.raises(ValueError, match="at least two Poincaré points"):
        classify_section(np.zeros((1, 2)))
    with pytest.raises(ValueError, match="not finite"):
        classify_section(np.array([[0.0, 1.0], [np.nan, 1.0]]))
    with pytest.raises(ValueError, match=r"zero_one_test\.series needs at least 50 entries"):
        zero_one_test(np.arange(10.0))
    with pytest.raises(ValueError, match="window must be"):
        amplitude_spectrum(np.arange(8.0), 4, window="flat")


def test_friction_loss_per_cycle_is_the_integral_of_friction_power():
    """∫ Σ f_e v_e dt over periods 2–12, by the trapezoid rule on the sampled friction
    force and on slip velocities v_e = (ẋ_i − ẋ_(i+1)) cos(π/3) computed here, against the
    integrator's own work column. The trapezoid rule errs by about a third of the
    change when every other sample is dropped (Richardson), and somewhat more where an
    event falls between samples: the change itself is the tolerance."""
    sim = simulate(three_blade_paper(gamma1=2.2), 12, samples_per_period=2000)
    rows = slice(2 * 2000, None)
    slip = (sim.v[rows, :-1] - sim.v[rows, 1:]) * math.cos(math.pi / 3)
    power = (sim.friction_force[rows] * slip).sum(axis=1)
    fine = np.trapezoid(power, sim.t[rows])
    coarse = np.trapezoid(power[::2], sim.t[rows][::2])
    per_cycle = friction_loss_per_cycle(sim, skip=2)
    assert per_cycle > 0.0
    assert per_cycle * 10 == pytest.approx(fine, abs=abs(fine - coarse))
    assert abs(fine - coarse) < 1e-5 * fine
    with pytest.raises(ValueError, match="skip must be a whole number of periods"):
        friction_loss_per_cycle(sim, skip=12)


def test_campbell_crossings_solve_the_southwell_law():
    model = paper_frequency_model()
    diagram = campbell(model, np.linspace(0.0, 12000.0, 121), engine_orders=(2, 3))
    assert [order for order, _, _ in diagram.crossings] == [2, 3]
    for order, speed, frequency in diagram.crossings:
        exact = 60.0 * model.f0 / math.sqrt(order**2 - model.coefficient)
        assert speed == pytest.approx(exact, rel=1e-9)
        assert frequency == pytest.approx(model.at(speed), rel=1e-9)
    np.testing.assert_allclose(diagram.line(2), 2 * diagram.speeds_rpm / 60)
