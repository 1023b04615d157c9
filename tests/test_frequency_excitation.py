"""Excitation at a frequency apart from the speed (``Excitation(frequency=f)``): the speed
sets the blades' stiffening, f the forcing. A linear oscillator's orbit against its closed
form q/|k(Ω) − m ω² + i c ω|, a continuation in frequency at a fixed speed and a sweep
against the same, and the frequency through scene files and the command line.

Kernels: the paper's group with its gaps never closing (``scenes.three_blade_paper(gap=1)``),
which the suite compiles anyway.
"""

import dataclasses
import math

import numpy as np
import pytest

import shroudnet as sn
from shroudnet import scenes
from shroudnet.front.cli import main
from shroudnet.io import scenefile

#: The speed the stiffening is taken at [rpm]; the forcing's frequencies [Hz] around the
#: blades' first flap frequency there (213.2 Hz), none the l Ω/60 = 200 Hz of the speed.
SPEED = 6000.0
EXACT = sn.Adaptive(rtol=1e-12)


def open_group(frequency, q1=50.0):
    """The paper's three blades, their shrouds never closing (gaps of 1 m): three linear
    oscillators k(Ω) = m (2π f_d1(Ω))², forced in anti-phase at ``frequency`` [Hz]."""
    scene = scenes.three_blade_paper(gap=1.0, speed_rpm=SPEED, q1=q1)
    return dataclasses.replace(scene, excitation=dataclasses.replace(
        scene.excitation, frequency=frequency))


def closed_form(scene):
    """q/|k − m ω² + i c ω| [m] of the paper's blade at the scene's speed and frequency."""
    blade = scene.group.blade("blade1")
    omega = 2.0 * math.pi * scene.excitation.frequency
    stiffness = blade.stiffness_at(scene.speed_rpm)
    return scene.excitation.amplitudes[1] / abs(stiffness - blade.mass * omega**2
                                                + 1j * blade.damping * omega)


def test_the_frequency_is_its_own_and_the_speed_still_stiffens():
    scene = open_group(230.0)
    assert scene.excitation_period == 1.0 / 230.0
    assert scene.arrays.excitation_frequency == 2.0 * math.pi * 230.0
    assert scene.excitation.frequency_at(SPEED) == 230.0
    locked = scenes.three_blade_paper(gap=1.0, speed_rpm=SPEED)
    assert locked.excitation.frequency_at(SPEED) == 2 * SPEED / 60.0
    assert np.array_equal(scene.arrays.stiffness, locked.arrays.stiffness)
    with pytest.raises(ValueError, match=r"Excitation.frequency must be in \(0, inf\) Hz"):
        dataclasses.replace(scene.excitation, frequency=-1.0)
    with pytest.raises(TypeError, match=r"Excitation.frequency must be a real number"):
        dataclasses.replace(scene.excitation, frequency="fast")


@pytest.mark.parametrize("frequency", [190.0, 213.2, 236.7])
def test_a_linear_oscillator_forced_apart_from_the_speed_meets_its_closed_form(frequency):
    """Below, at and above the blades' resonance at 6000 rpm."""
    scene = open_group(frequency)
    orbit = sn.periodic_orbit(scene, method=EXACT, tolerance=1e-13, transient=0)
    expected = closed_form(scene)
    # Measured: 2.9e-13, 6.8e-12 and 3.5e-13 relative.
    for blade in scene.blades:
        assert abs(orbit.amplitude(blade) - expected) <= 1e-10 * expected


def test_a_continuation_in_frequency_at_a_fixed_speed_follows_the_closed_form():
    branch = sn.continuation(open_group, 203.0, 223.0, parameter="f [Hz]", max_step=0.05,
                             transient=0)
    assert branch.parameter[0] == 203.0 and abs(branch.parameter[-1] - 223.0) <= 1e-9
    expected = np.array([closed_form(orbit.scene) for orbit in branch.orbits])
    amplitude = branch.amplitude("blade2")
    # Measured: 7.1e-10 of the peak (the default tangent method, rtol 1e-10).
    assert np.abs(amplitude - expected).max() <= 1e-8 * expected.max()
    top = int(np.argmax(amplitude))
    assert 0 < top < len(branch) - 1  # the resonance lies inside the range


def test_a_sweep_in_frequency_reads_the_same_response():
    frequencies = [205.0, 213.0, 221.0]
    result = sn.sweep(open_group, frequencies, transient=60, record=10, workers=1,
                      method=EXACT, progress=None)
    for point in result.points:
        expected = closed_form(open_group(point.value))
        # The peaks between samples (100 a period), to the sampling's second order:
        # measured 6.0e-4, 3.2e-4 and 4.9e-4.
        assert abs(point.peak.max() - expected) <= 2e-3 * expected


def test_scene_files_and_the_command_line_take_the_frequency(tmp_path, capsys):
    scene = open_group(231.5)
    path = scenefile.save(tmp_path / "shaker.toml", scene)
    assert "frequency = 231.5" in path.read_text()
    again = scenefile.load(path).scene
    assert again.excitation.frequency == 231.5
    assert again.excitation_period == scene.excitation_period
    assert main(["sweep", str(path), "--param", "excitation.frequency", "--values",
                 "210", "215", "--transient", "2", "--record", "3", "--workers", "1",
                 "-o", str(tmp_path / "sweep")]) == 0
    assert "excitation.frequency" in capsys.readouterr().out
