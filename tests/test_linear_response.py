"""The linear forced response in the open and stuck limits (``frequency_response``), held to
closed forms written here from the scenes' inputs, and to the time integration of the same
linear motion."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import shroudnet as sn
from contact_laws import Coulomb, KelvinVoigt, LinearSpring
from shroudnet import scenes
from shroudnet.linear.response import ellipse_semi_major_axis

FREQUENCIES = np.linspace(120.0, 320.0, 41)


def paper_blade_terms(scene, f):
    """(F_i, m_i, c_i, k_i) of the paper group's blades: F_i = q_1 e^{iπ i} (anti-phase)."""
    omega = 2.0 * math.pi * f
    q1 = scene.excitation.amplitudes[1]
    terms = []
    for i, name in enumerate(scene.blades):
        blade = scene.group.blade(name)
        stiffness = blade.mass * (2.0 * math.pi * blade.frequency.at(scene.speed_rpm)) ** 2
        terms.append((q1 * (-1.0) ** i, blade.mass, blade.damping, stiffness, omega))
    return terms


def test_open_paper_blades_respond_as_single_oscillators():
    scene = scenes.three_blade_paper(gamma1=2.2)
    response = sn.frequency_response(scene, FREQUENCIES, "open")
    for k, f in enumerate(FREQUENCIES):
        for i, (force, m, c, stiffness, omega) in enumerate(paper_blade_terms(scene, f)):
            expected = force / (stiffness - m * omega ** 2 + 1j * c * omega)
            assert response.response[k, i] == pytest.approx(expected, rel=1e-12)


def test_stuck_paper_blades_respond_as_one_body():
    scene = scenes.three_blade_paper(gamma1=2.2)
    response = sn.frequency_response(scene, FREQUENCIES, "stuck")
    for k, f in enumerate(FREQUENCIES):
        terms = paper_blade_terms(scene, f)
        force, mass, damping, stiffness = (sum(t[j] for t in terms) for j in range(4))
        omega = terms[0][4]
        expected = force / (stiffness - mass * omega ** 2 + 1j * damping * omega)
        assert response.dofs("blade2")[k, 0] == pytest.approx(expected, rel=1e-12)
        assert np.allclose(response.response[k], expected, rtol=1e-12, atol=0.0)


def one_modal_blade(damping_ratio=0.02, q1=2.0, speed_rpm=3000.0):
    group = sn.BladeGroup().add_blade("b", scenes.modal_blade(damping_ratio=damping_ratio))
    return sn.Scene(group=group, speed_rpm=speed_rpm, excitation=sn.Excitation(
        engine_order=3, amplitudes=(0.0, q1), phases=sn.AntiPhase()))


def test_a_modal_blade_responds_by_modal_superposition():
    """R_p = Σ_k ψ_p,k ψ_load,k q_1 / (m_k (ω_k² − ω² + 2iζ ω_k ω)) from the modal data
    that ``scenes.modal_blade`` gives (frequencies by Southwell's law)."""
    scene = one_modal_blade()
    f0, coefficient = (180.0, 450.0, 1050.0), (3.0, 1.5, 2.0)
    masses, zeta = (0.06, 0.05, 0.04), 0.02
    shroud = np.array([[1.0, 0.25, -0.5], [0.15, 1.0, 0.35]])
    load = np.array([0.7, 0.4, 0.2])
    modal = [2.0 * math.pi * math.sqrt(f ** 2 + b * (3000.0 / 60.0) ** 2)
             for f, b in zip(f0, coefficient)]
    frequencies = np.linspace(100.0, 1500.0, 57)
    response = sn.frequency_response(scene, frequencies)
    for k, f in enumerate(frequencies):
        omega = 2.0 * math.pi * f
        participation = np.array([load[j] * 2.0 / (masses[j] * (w ** 2 - omega ** 2
                                                                 + 2j * zeta * w * omega))
                                  for j, w in enumerate(modal)])
        expected = shroud @ participation
        assert np.allclose(response.displacement("b", "shroud")[k], expected, rtol=1e-10,
                           atol=1e-12 * np.abs(expected).max())
        assert response.dofs("b")[k] == pytest.approx(participation, rel=1e-10)


def steady_amplitude(scene, point, periods=300, keep=20):
    """(max over the last ``keep`` periods of |r(t) − r̄| of ``point`` = (node, name), r̄
    its mean there (a preload's static deflection), the run's event counts), from a run
    of ``simulate``: the time integration of the same motion."""
    sim = sn.simulate(scene, periods, samples_per_period=400,
                      method=sn.Adaptive(rtol=1e-10))
    displacement = sim.displacement(*point)[-keep * 400:]
    displacement = displacement.reshape(len(displacement), -1)
    swing = displacement - displacement.mean(axis=0)
    return np.sqrt((swing ** 2).sum(axis=1)).max(), sim.events.counts


def test_the_open_limit_is_what_a_run_with_the_interfaces_apart_settles_to():
    scene = scenes.modal_packet(gap=1e-2, speed_rpm=2900.0)
    f = scene.excitation.engine_order * scene.speed_rpm / 60.0
    linear = sn.frequency_response(scene, [f], "open").amplitude("blade3", "shroud")[0]
    amplitude, counts = steady_amplitude(scene, ("blade3", "shroud"))
    assert counts["closing"] == 0
    assert amplitude == pytest.approx(linear, rel=1e-4)


@pytest.mark.parametrize("normal_law", [LinearSpring(stiffness=1e5),
                                        KelvinVoigt(stiffness=1e5, damping=20.0)],
                         ids=["spring", "spring and dashpot"])
def test_the_stuck_limit_is_what_a_run_whose_interfaces_never_slip_settles_to(normal_law):
    """A deep preload and μ = 100: the packet's interfaces stick from rest and stay stuck,
    each contact at its preload, its dashpot acting along the normal, which stick leaves
    free; the run is the constrained linear motion."""
    scene = scenes.modal_packet(gap=-2e-4, friction=Coulomb(mu=100.0), speed_rpm=3300.0,
                                normal_law=normal_law)
    f = scene.excitation.engine_order * scene.speed_rpm / 60.0
    amplitude, counts = steady_amplitude(scene, ("blade3", "shroud"))
    assert counts["breakaway"] == 0 and counts["separation"] == 0
    linear = sn.frequency_response(scene, [f], "stuck").amplitude("blade3", "shroud")[0]
    assert amplitude == pytest.approx(linear, rel=1e-4)


def test_a_preloaded_interface_that_cannot_stick_is_its_spring_and_dashpot():
    """Two blades and a frictionless interface preloaded at α: stuck, it slides freely and
    pushes by k_n sin²α and c_n sin²α between the blades; the 2 × 2 system solved by hand."""
    alpha, k_n, c_n = 0.7, 4e4, 3.0
    blade = sn.Blade(mass=0.08, damping=2.0, stiffness=1.2e5)
    group = sn.BladeGroup().add_blade("a", blade).add_blade("b", blade)
    group.connect("a", "b", sn.Interface(gap=-1e-5, angle=alpha, friction=None,
                                          normal=KelvinVoigt(stiffness=k_n, damping=c_n)))
    scene = sn.Scene(group=group, speed_rpm=3000.0, excitation=sn.Excitation(
        engine_order=2, amplitudes=(0.0, 5.0), phases=sn.AntiPhase()))
    frequencies = np.linspace(150.0, 350.0, 21)
    response = sn.frequency_response(scene, frequencies, "stuck").response
    s2 = math.sin(alpha) ** 2
    for k, f in enumerate(frequencies):
        omega = 2.0 * math.pi * f
        own = 1.2e5 - 0.08 * omega ** 2 + 2.0j * omega
        edge = (k_n + 1j * omega * c_n) * s2
        a, b = own + edge, -edge                    # [[a, b], [b, a]] X = (5, −5)
        determinant = a * a - b * b
        expected = ((a * 5.0 + b * 5.0) / determinant, (-a * 5.0 - b * 5.0) / determinant)
        assert response[k] == pytest.approx(expected, rel=1e-12)


def test_every_resonance_peak_lies_at_a_natural_frequency_of_its_limit():
    """Lightly damped (ζ = 1e-4), each local maximum of the response over a fine grid is
    within a grid step of one of ``linear_modes``' frequencies for the same limit."""
    scene = scenes.modal_packet(damping_ratio=1e-4)
    grid = np.linspace(150.0, 1400.0, 12501)
    for contacts in ("open", "stuck"):
        modes = sn.linear_modes(scene, contacts).frequencies
        size = np.linalg.norm(sn.frequency_response(scene, grid, contacts).response, axis=1)
        peaks = grid[1:-1][(size[1:-1] > size[:-2]) & (size[1:-1] > size[2:])]
        assert len(peaks) >= 3, contacts
        for peak in peaks:
            assert np.abs(modes - peak).min() <= grid[1] - grid[0], (contacts, peak)


@settings(max_examples=50, deadline=None)
@given(st.lists(st.complex_numbers(max_magnitude=10.0, allow_nan=False, allow_infinity=False),
                min_size=1, max_size=3))
def test_the_amplitude_is_the_largest_distance_over_a_cycle(phasor):
    r = np.array(phasor)[None, :]
    theta = np.linspace(0.0, 2.0 * math.pi, 20001)
    path = (r * np.exp(1j * theta)[:, None]).real
    sampled = np.sqrt((path ** 2).sum(axis=1)).max()
    exact = ellipse_semi_major_axis(r)[0]
    assert sampled <= exact * (1 + 1e-12) + 1e-300
    assert exact <= sampled * (1 + 1e-7) + 1e-12


@pytest.mark.parametrize("arguments, message", [
    (("scene", [100.0]), "needs a shroudnet.Scene"),
    ((None, [100.0], "rigid"), "contacts must be one of"),
    ((None, [], "open"), "non-empty"),
    ((None, [[1.0, 2.0]], "open"), "non-empty"),
    ((None, [0.0, 100.0], "open"), "finite and > 0"),
    ((None, [math.nan], "open"), "finite and > 0"),
    ((None, ["fast"], "open"), "must be numbers"),
])
def test_bad_input_is_refused_with_the_field_named(arguments, message):
    scene = scenes.three_blade_paper(gamma1=2.2)
    arguments = tuple(scene if a is None else a for a in arguments)
    with pytest.raises((TypeError, ValueError), match=message):
        sn.frequency_response(*arguments)


def test_an_undamped_group_at_its_natural_frequency_is_refused():
    blade = sn.Blade(mass=0.37, damping=0.0, stiffness=1.234e6)
    group = sn.BladeGroup().add_blade("a", blade).add_blade("b", blade)
    group.connect("a", "b", sn.Interface(gap=1e-3, angle=math.pi / 3,
                                          normal=LinearSpring(stiffness=1e5),
                                          friction=Coulomb(mu=0.3)))
    scene = sn.Scene(group=group, speed_rpm=3000.0, excitation=sn.Excitation(
        engine_order=2, amplitudes=(0.0, 1.0), phases=sn.AntiPhase()))
    for contacts in ("open", "stuck"):
        natural = sn.linear_modes(scene, contacts).frequencies[0]
        with pytest.raises(ValueError, match="resonance"):
            sn.frequency_response(scene, [natural], contacts)


@pytest.mark.parametrize("amplitudes", [(3.0,), (3.0, 0.0, 2.0)])
def test_an_excitation_without_a_first_harmonic_is_refused(amplitudes):
    scene = scenes.three_blade_paper(gamma1=2.2)
    scene = sn.Scene(group=scene.group, speed_rpm=scene.speed_rpm, excitation=sn.Excitation(
        engine_order=2, amplitudes=amplitudes, phases=sn.AntiPhase()))
    with pytest.raises(ValueError, match=r"amplitudes\[1\]"):
        sn.frequency_response(scene, [100.0])
