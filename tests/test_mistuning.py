"""Mistuning studies: Whitehead's bound on a linearly coupled ring, and one mistuned blade
against the direct linear solve (K − ω²M + iωC) X = F at every speed."""

import math

import numpy as np
import pytest

from shroudnet import (
    Blade,
    BladeGroup,
    Coupling,
    EngineOrderWave,
    Excitation,
    HarmonicMotion,
    Scene,
    linear_modes,
    mistuning_study,
)
from shroudnet.studies.mistuning import mistuned_group

N = 6


def tuned_ring():
    ring = BladeGroup.ring(N, Blade(mass=0.1, damping=2.0, stiffness=1e5),
                           Coupling(stiffness=5e3))
    excitation = Excitation(engine_order=2, amplitudes=(0.0, 1.0), phases=EngineOrderWave())
    return Scene(group=ring, excitation=excitation, speed_rpm=6000.0)


def resonance_speeds(scene, count=31):
    """Speeds [rpm] round the ND 2 resonance that engine order 2 excites."""
    f = linear_modes(scene).of_diameter(2)[0]
    return np.linspace(0.96, 1.04, count) * f * 60.0 / 2


def direct_peaks(scene, speeds):
    """max over ``speeds`` of each blade's |X| from the complex linear solve."""
    peaks = np.zeros(scene.arrays.n_blades)
    for speed in speeds:
        a = Scene(group=scene.group, excitation=scene.excitation, speed_rpm=speed).arrays
        w = a.excitation_frequency
        force = a.harmonic_amplitudes[1] * np.exp(1j * a.harmonic_phases[1])
        dynamic = a.stiffness_matrix() - w * w * np.diag(a.mass) + 1j * w * a.damping_matrix()
        peaks = np.maximum(peaks, np.abs(np.linalg.solve(dynamic, force)))
    return peaks


@pytest.mark.slow  # 217 runs: the tuned ring and six samples at 31 speeds
def test_no_sample_of_a_linearly_coupled_ring_exceeds_whiteheads_bound():
    scene = tuned_ring()
    study = mistuning_study(scene, spread=0.03, samples=6, speeds_rpm=resonance_speeds(scene),
                            seed=3, progress=False)
    bound = 0.5 * (1.0 + math.sqrt(N))
    assert study.whitehead_bound == bound
    assert np.all(study.amplification <= bound)
    assert study.amplification.max() > 1.05  # mistuning does amplify
    assert study.worst_pattern == pytest.approx(study.patterns[study.worst])
    again = np.random.default_rng(3).normal(0.0, 0.03, size=(6, N))
    assert np.array_equal(study.patterns, again)


def test_one_mistuned_blade_amplifies_as_the_direct_linear_solve_says():
    scene = tuned_ring()
    speeds = resonance_speeds(scene, 21)
    pattern = np.zeros((1, N))
    pattern[0, 2] = 0.04
    study = mistuning_study(scene, spread=0.04, samples=1, speeds_rpm=speeds,
                            patterns=pattern, progress=False)
    mistuned = Scene(group=mistuned_group(scene, 1.0 + pattern[0], scene.blades),
                     excitation=scene.excitation, speed_rpm=scene.speed_rpm)
    expected = direct_peaks(mistuned, speeds).max() / direct_peaks(scene, speeds).max()
    # The loop's peak is the largest of 100 samples a period: within 1 − cos(π/100).
    assert study.amplification[0] == pytest.approx(expected, rel=1e-3)
    assert study.tuned_peak == pytest.approx(direct_peaks(scene, speeds).max(), rel=1e-3)


def test_a_mistuned_blade_has_its_frequency_scaled():
    scene = tuned_ring()
    factors = np.ones(N)
    factors[0] = 1.1
    group = mistuned_group(scene, factors)
    assert group.blade("blade1").stiffness == pytest.approx(1.21e5)
    couplings = {(a, b): c.stiffness for a, b, c in group.couplings}
    assert couplings[("blade1", "blade2")] == pytest.approx(5e3 * 1.21)
    assert couplings[("blade2", "blade3")] == 5e3
    # blade 2 mistuned too, by ε = 0: the coupling takes (1 + ε1)(1 + ε2)
    both = {(a, b): c.stiffness
            for a, b, c in mistuned_group(scene, factors, ["blade1", "blade2"]).couplings}
    assert both[("blade1", "blade2")] == pytest.approx(5e3 * 1.1)


def test_mistuning_keeps_fixed_and_prescribed_nodes_as_they_are():
    group = BladeGroup().add_blade("blade", Blade(mass=0.1, damping=2.0, stiffness=1e5))
    group.add_fixed("lug").add_prescribed("shaker", HarmonicMotion(amplitude=1e-5,
                                                                   frequency=100.0))
    group.connect("blade", "lug", Coupling(stiffness=1e3))
    group.connect("blade", "shaker", Coupling(stiffness=2e3))
    scene = Scene(group=group, speed_rpm=6000.0, excitation=Excitation(
        engine_order=1, amplitudes=(0.0, 1.0), phases=[0.0]))
    mistuned = mistuned_group(scene, [1.1])
    assert mistuned.fixed == ["lug"] and mistuned.prescribed == scene.group.prescribed
    assert [c.stiffness for *_, c in mistuned.couplings] == pytest.approx([1.21e3, 2.42e3])


@pytest.mark.parametrize("arguments, match", [
    ({"spread": -0.1, "samples": 2}, r"mistuning_study\.spread must be in \[0, 0\.3\]"),
    ({"spread": 0.1, "samples": 0}, r"mistuning_study\.samples"),
    ({"spread": 0.1, "samples": 2, "patterns": np.zeros((3, N))}, r"patterns must be 2 × 6"),
    ({"spread": 0.1, "samples": 2, "blades": ["ghost"]}, r"unknown: \['ghost'\]"),
])
def test_bad_study_arguments_are_refused_before_any_run(arguments, match):
    with pytest.raises(ValueError, match=match):
        mistuning_study(tuned_ring(), speeds_rpm=[6000.0], **arguments)
