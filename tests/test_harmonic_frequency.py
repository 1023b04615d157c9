"""Harmonic balance forced at a frequency of its own (``Excitation(frequency=f)``) at a
fixed speed: the speed sets the blades' stiffening, f the series' fundamental. A branch
in f of a linear packet against its closed form at every point (its response and its
Floquet multipliers e^{λ/f}), and of the Jenkins chain against exact orbits by shooting.

Kernels: the blades' and the elastic contacts' tangent flows, which
``test_harmonic_balance`` compiles anyway.
"""

import dataclasses

import numpy as np
import pytest

import shroudnet as sn
from tests.test_harmonic_balance import steady_response_in_dofs
from tests.test_hill_floquet import farthest, free_multipliers

#: The speed the modal blades are stiffened at [rpm]: their first flap mode at
#: √(180² + 3 · 50²) = 199.75 Hz (Southwell), against 180 Hz at rest.
SPEED = 3000.0


def at_frequency(scene, frequency):
    """``scene`` forced at ``frequency`` [Hz], its speed unchanged."""
    return dataclasses.replace(scene, excitation=dataclasses.replace(
        scene.excitation, frequency=frequency))


def open_packet(frequency):
    """Three modal blades at ``SPEED`` whose contacts never close (a linear structure),
    forced at ``frequency``."""
    return at_frequency(sn.scenes.modal_packet(blades=3, gap=1.0, friction=None,
                                               speed_rpm=SPEED), frequency)


def test_a_linear_branch_in_frequency_is_its_closed_form_at_every_point():
    """Every orbit of the branch is its steady response from the blades' own matrices at
    ``SPEED`` (``steady_response_in_dofs``, measured: 4e-15 of the motion), Hill's
    multipliers the structure's e^{λT} with T = 1/f (measured: 2e-14), and the branch
    peaks at the stiffened flap frequency (measured: 199.48 Hz, the grid's point nearest
    the damped peak)."""
    branch = sn.harmonic_continuation(open_packet, 190.0, 210.0, 1, max_step=0.5,
                                      parameter="f [Hz]")
    assert branch.ended == "reached p = 210" and branch.parameter[0] == 190.0
    for f, orbit in zip(branch.parameter, branch.orbits):
        assert orbit.scene.speed_rpm == SPEED
        assert orbit.period == pytest.approx(1.0 / f, rel=1e-15)
        expected = steady_response_in_dofs(orbit.scene)
        scale = np.abs(expected).max()
        assert np.abs(orbit.coefficients[1] - expected.imag).max() <= 1e-12 * scale
        assert np.abs(orbit.coefficients[2] - expected.real).max() <= 1e-12 * scale
        assert farthest(orbit.multipliers, free_multipliers(orbit.scene)) <= 1e-12
    peak = branch.parameter[int(np.argmax(branch.amplitude(("blade1", "shroud", 0))))]
    assert abs(peak - 199.75) <= 1.0


def chain_at(frequency):
    """The Jenkins chain at its own speed (720 rpm: 12 Hz), forced at ``frequency``."""
    return at_frequency(sn.scenes.jenkins_chain(), frequency)


def test_at_the_speeds_own_frequency_the_forced_scene_is_the_speed_locked_one():
    locked = sn.harmonic_balance(sn.scenes.jenkins_chain(), 5, stability=False)
    forced = sn.harmonic_balance(chain_at(12.0), 5, stability=False)
    assert forced.scene.excitation.frequency == 12.0
    assert np.abs(forced.coefficients - locked.coefficients).max() <= 1e-12 * np.abs(
        locked.coefficients).max()


@pytest.mark.parametrize("harmonics, accuracy", [(5, 3e-3), (15, 5e-5)])
def test_a_friction_branch_in_frequency_meets_the_exact_orbits(harmonics, accuracy):
    """The chain across its resonance at a fixed speed, its slider sticking and slipping:
    at the branch's ends and middle the exact orbit (shooting from the series) is within
    what H allows of the series' amplitude and energy per cycle (measured at H = 5: at
    most 1.0e-3 and 1.7e-3; at H = 15: 1.9e-5 and 2.4e-5)."""
    branch = sn.harmonic_continuation(chain_at, 9.5, 10.5, harmonics, max_step=0.3,
                                      stability=False, parameter="f [Hz]")
    assert branch.ended == "reached p = 10.5" and np.all(np.diff(branch.parameter) > 0.0)
    for k in (0, len(branch) // 2, len(branch) - 1):
        orbit = branch.orbits[k]
        assert orbit.converged and orbit.scene.speed_rpm == 720.0
        assert orbit.scene.excitation.frequency == branch.parameter[k]
        certificate = sn.certify(orbit)
        assert certificate.amplitude_error <= accuracy
        assert certificate.energy_error <= accuracy
